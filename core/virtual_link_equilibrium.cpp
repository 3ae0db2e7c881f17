#include "sinew/core/virtual_link_equilibrium.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_path.hpp"

namespace sinew {
namespace {

constexpr int kMaxIterations = 50;
constexpr int kMaxHalvings = 60;  // line search: the step is halved at most this often (see the jump, below)
constexpr double kResidualTolerance = 1e-11;  // of the load on the link
constexpr double kTwistTolerance = 1e-9;      // relative change of the twist between iterations
constexpr double kRegularisation = 1e-12;     // of the largest stiffness entry, added to its diagonal
constexpr double kMinSegment = 1e-12;         // m, a shorter segment has no direction (as in calcWirePaths)

double calcTensionOf(const Wire& wire, double length, double speed, double time) {
    try {
        return wire.law->calcTension(WireState{length, speed, time});
    } catch (const Error& e) {
        throw Error("wire '" + wire.name + "': " + e.what());
    }
}

// The change of eq.residual (scaled) when the points of `wires` move by eq.dp_GP at fixed wire speeds, into
// `out` (the rows of slots firstSlot on), for N displacements at once (column j of dp_GP and of out). The
// wires must touch no slot before firstSlot. The virtual link in slot movedSlot
// (or none, -1) moves rigidly with its origin displaced by dOrigin[j], so its moment arms change by
// dp_GP - dOrigin; the other virtual links' points must not move. With f = -T g at each point
// (g = dL/dp = e_in - e_out): df = -T' dL g - T (de_in - de_out), where dL = sum over the wire's points of
// g . dp and de = (1 - e e^T) d(segment) / l. Each column's arithmetic is that of its displacement alone;
// taking a link's six together shares the lookups and moment arms that six passes repeated.
template <int N>
void calcResidualDerivatives(const Model& model, const Data& data, VirtualLinkEquilibriumData& eq,
                             const std::vector<int>& wires, int movedSlot, int firstSlot,
                             const std::array<Eigen::Vector3d, N>& dOrigin, Eigen::Ref<Eigen::MatrixXd> out) {
    const std::vector<WirePoint>& points = model.getWirePoints();
    out.setZero();
    for (int w : wires) {
        const Wire& wire = model.getWire(w);
        const std::size_t first = static_cast<std::size_t>(wire.firstPoint);
        const std::size_t last = first + static_cast<std::size_t>(wire.numPoints) - 1;
        std::array<double, N> dL{};
        for (std::size_t k = first; k <= last; ++k)
            for (int j = 0; j < N; ++j) dL[j] += data.dLdp_GP[k].dot(Eigen::Vector3d(eq.dp_GP[k].col(j)));
        for (std::size_t k = first; k < last; ++k) {
            const Eigen::Vector3d& e = eq.segmentDirection[k];
            for (int j = 0; j < N; ++j) {
                const Eigen::Vector3d relative = Eigen::Vector3d(eq.dp_GP[k + 1].col(j)) - Eigen::Vector3d(eq.dp_GP[k].col(j));
                eq.dSegmentDirection[k].col(j) = eq.segmentLength[k] > kMinSegment
                                                     ? Eigen::Vector3d((relative - e * e.dot(relative)) / eq.segmentLength[k])
                                                     : Eigen::Vector3d::Zero();
            }
        }
        const double T = eq.tension[w];
        std::array<double, N> dT;
        for (int j = 0; j < N; ++j) dT[j] = eq.tensionSlope[w] * dL[j];
        for (std::size_t k = first; k <= last; ++k) {
            const int slot = eq.slotOfLink[static_cast<std::size_t>(points[k].link)];
            if (slot < 0) continue;
            const std::size_t v = static_cast<std::size_t>(points[k].link), s = static_cast<std::size_t>(slot);
            const Eigen::Vector3d f = -T * data.dLdp_GP[k];
            const Eigen::Vector3d r = data.R_GB[v] * points[k].p_B;
            for (int j = 0; j < N; ++j) {
                Eigen::Vector3d dg = Eigen::Vector3d::Zero();
                if (k > first) dg += Eigen::Vector3d(eq.dSegmentDirection[k - 1].col(j));
                if (k < last) dg -= Eigen::Vector3d(eq.dSegmentDirection[k].col(j));
                const Eigen::Vector3d df = -dT[j] * data.dLdp_GP[k] - T * dg;
                const Eigen::Vector3d dr =
                    slot == movedSlot ? Eigen::Vector3d(Eigen::Vector3d(eq.dp_GP[k].col(j)) - dOrigin[j]) : Eigen::Vector3d::Zero();
                out.col(j).segment<3>(6 * (slot - firstSlot)) += (dr.cross(f) + r.cross(df)) / eq.lengthScale[s];
                out.col(j).segment<3>(6 * (slot - firstSlot) + 3) += df;
            }
        }
    }
}

// Per virtual link, the largest residual entry and the sum of the magnitudes of its wire forces.
void measureResidual(const Model& model, const Data& data, const VirtualLinkEquilibriumData& eq, int slot,
                     double& residual, double& load) {
    residual = eq.residual.segment<6>(6 * slot).lpNorm<Eigen::Infinity>();
    load = 0;
    for (int w : eq.wiresOfSlot[static_cast<std::size_t>(slot)]) {
        const Wire& wire = model.getWire(w);
        for (int k = wire.firstPoint; k < wire.firstPoint + wire.numPoints; ++k)
            if (model.getWirePoints()[static_cast<std::size_t>(k)].link == eq.links[static_cast<std::size_t>(slot)])
                load += eq.tension[w] * data.dLdp_GP[static_cast<std::size_t>(k)].norm();
    }
}

// True when the residual of every virtual link in slots [begin, end) is within tolerance of its load.
bool isWithinTolerance(const Model& model, const Data& data, const VirtualLinkEquilibriumData& eq, int begin, int end) {
    for (int s = begin; s < end; ++s) {
        double residual = 0, load = 0;
        measureResidual(model, data, eq, s, residual, load);
        if (!(residual <= kResidualTolerance * load)) return false;
    }
    return true;
}

// True when every virtual link's residual is within tolerance of its load; fills the status's measures.
bool measureStatus(const Model& model, const Data& data, VirtualLinkEquilibriumData& eq) {
    VirtualLinkEquilibriumStatus& status = eq.status;
    status.residual = status.forceScale = 0;
    status.slackLinks = 0;
    bool within = true;
    for (int s = 0; s < static_cast<int>(eq.links.size()); ++s) {
        double residual = 0, load = 0;
        measureResidual(model, data, eq, s, residual, load);
        if (!(residual <= status.residual)) status.residual = residual;  // a NaN residual stays visible
        status.forceScale = std::max(status.forceScale, load);
        if (load == 0) ++status.slackLinks;
        within = within && residual <= kResidualTolerance * load;
    }
    return within;
}

// Moves virtual link s from (R0, p0) by the scaled step [l dtheta; dp] times alpha: R = exp(dtheta) R0,
// kept orthonormal through a normalised quaternion (the Simbody plugin keeps poses across many solves).
void displacePose(Data& data, const VirtualLinkEquilibriumData& eq, std::size_t s, double alpha) {
    const std::size_t v = static_cast<std::size_t>(eq.links[s]);
    const Eigen::Vector3d dtheta = alpha * eq.step.segment<3>(6 * static_cast<Eigen::Index>(s)) / eq.lengthScale[s];
    const double angle = dtheta.norm();
    const Eigen::Quaterniond rotation =
        angle > 0 ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, dtheta / angle)) : Eigen::Quaterniond::Identity();
    data.R_GB[v] = (rotation * Eigen::Quaterniond(eq.R_GV0[s])).normalized().toRotationMatrix();
    data.p_GB[v] = eq.p_GV0[s] + alpha * eq.step.segment<3>(6 * static_cast<Eigen::Index>(s) + 3);
}

// The model's virtual links group by group (VirtualLinkEquilibriumData::groupStart): two are in one group when
// a wire passes through both, or through links of one group.
std::vector<int> orderByGroup(const Model& model, std::vector<int>& groupStart) {
    const int numLinks = model.getNumLinks();
    std::vector<int> parent(static_cast<std::size_t>(numLinks));
    std::iota(parent.begin(), parent.end(), 0);
    const auto root = [&parent](int i) {
        while (parent[static_cast<std::size_t>(i)] != i)
            i = parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
        return i;
    };
    const std::vector<WirePoint>& points = model.getWirePoints();
    for (int w = 0; w < model.getNumWires(); ++w) {
        const Wire& wire = model.getWire(w);
        int first = -1;
        for (int k = wire.firstPoint; k < wire.firstPoint + wire.numPoints; ++k) {
            const int link = points[static_cast<std::size_t>(k)].link;
            if (!model.getLink(link).isVirtual) continue;
            if (first < 0) first = link;
            else parent[static_cast<std::size_t>(root(link))] = root(first);
        }
    }
    std::vector<int> ordered;
    std::vector<char> placed(static_cast<std::size_t>(numLinks), 0);
    groupStart.assign(1, 0);
    for (int i = 0; i < numLinks; ++i) {
        if (!model.getLink(i).isVirtual || placed[static_cast<std::size_t>(root(i))]) continue;
        placed[static_cast<std::size_t>(root(i))] = 1;
        for (int j = i; j < numLinks; ++j)
            if (model.getLink(j).isVirtual && root(j) == root(i)) ordered.push_back(j);
        groupStart.push_back(static_cast<int>(ordered.size()));
    }
    return ordered;
}

}  // namespace

VirtualLinkEquilibriumData::VirtualLinkEquilibriumData(const Model& model)
    : slotOfLink(static_cast<std::size_t>(model.getNumLinks()), -1) {
    links = orderByGroup(model, groupStart);
    for (std::size_t s = 0; s < links.size(); ++s) slotOfLink[static_cast<std::size_t>(links[s])] = static_cast<int>(s);
    const std::vector<WirePoint>& points = model.getWirePoints();
    std::vector<double> sumSquares(links.size(), 0.0);
    std::vector<int> count(links.size(), 0);
    wiresOfSlot.resize(links.size());
    for (int w = 0; w < model.getNumWires(); ++w) {
        const Wire& wire = model.getWire(w);
        bool touches = false;
        for (int k = wire.firstPoint; k < wire.firstPoint + wire.numPoints; ++k) {
            const WirePoint& point = points[static_cast<std::size_t>(k)];
            const int slot = slotOfLink[static_cast<std::size_t>(point.link)];
            if (slot < 0) continue;
            touches = true;
            std::vector<int>& slotWires = wiresOfSlot[static_cast<std::size_t>(slot)];
            if (slotWires.empty() || slotWires.back() != w) slotWires.push_back(w);
            sumSquares[static_cast<std::size_t>(slot)] += point.p_B.squaredNorm();
            ++count[static_cast<std::size_t>(slot)];
        }
        if (!touches) continue;
        // The solver differentiates the straight segments between fixed points.
        if (!wire.isPolyline())
            throw Error("wire '" + wire.name + "' passes through a virtual link and has conditional, moving or "
                        "wrapping path points; wires through virtual links must be plain polylines");
        wires.push_back(w);
    }
    for (std::size_t s = 0; s < links.size(); ++s) {
        const double rms = count[s] > 0 ? std::sqrt(sumSquares[s] / count[s]) : 0.0;
        lengthScale.push_back(rms > 0 ? rms : 1.0);
    }
    const Eigen::Index n = 6 * static_cast<Eigen::Index>(links.size());
    residual = Eigen::VectorXd::Zero(n);
    stiffness = Eigen::MatrixXd::Zero(n, n);
    boneRate = Eigen::VectorXd::Zero(n);
    step = Eigen::VectorXd::Zero(n);
    twist = Eigen::VectorXd::Zero(n);
    wiresOfGroup.resize(groupStart.size() - 1);
    for (int w : wires) {
        const Wire& wire = model.getWire(w);
        int slot = -1;
        for (int k = wire.firstPoint; slot < 0; ++k) slot = slotOfLink[static_cast<std::size_t>(points[static_cast<std::size_t>(k)].link)];
        const auto group = std::upper_bound(groupStart.begin(), groupStart.end(), slot) - groupStart.begin() - 1;
        wiresOfGroup[static_cast<std::size_t>(group)].push_back(w);
    }
    factor = Eigen::PartialPivLU<Eigen::MatrixXd>(n);
    for (std::size_t g = 0; g + 1 < groupStart.size(); ++g)
        groupFactor.emplace_back(6 * (groupStart[g + 1] - groupStart[g]));
    tension = Eigen::VectorXd::Zero(model.getNumWires());
    tensionSlope = Eigen::VectorXd::Zero(model.getNumWires());
    segmentDirection.assign(points.size(), Eigen::Vector3d::Zero());
    segmentLength.assign(points.size(), 0.0);
    dp_GP.assign(points.size(), Eigen::Matrix<double, 3, 6>::Zero());
    dSegmentDirection.assign(points.size(), Eigen::Matrix<double, 3, 6>::Zero());
    R_GV0.assign(links.size(), Eigen::Matrix3d::Identity());
    p_GV0.assign(links.size(), Eigen::Vector3d::Zero());
}

namespace {

// The slots of groups [first, last) and their residual's rows: slots [begin, end), rows [6 begin, 6 end).
struct GroupSlots {
    GroupSlots(const VirtualLinkEquilibriumData& eq, std::size_t first, std::size_t last)
        : begin(eq.groupStart[first]), end(eq.groupStart[last]), row(6 * begin), size(6 * (end - begin)) {}
    GroupSlots(const VirtualLinkEquilibriumData& eq, std::size_t g) : GroupSlots(eq, g, g + 1) {}
    int begin, end;
    Eigen::Index row, size;
};

// eq.residual's rows of group g, from the group's wires (their paths, speeds and tensions too).
void calcGroupResidual(const Model& model, Data& data, double time, VirtualLinkEquilibriumData& eq, std::size_t g) {
    const std::vector<WirePoint>& points = model.getWirePoints();
    const GroupSlots group(eq, g);
    for (int s = group.begin; s < group.end; ++s) {
        const std::size_t v = static_cast<std::size_t>(eq.links[static_cast<std::size_t>(s)]);
        data.p_GM[v] = data.p_GB[v];
    }
    eq.residual.segment(group.row, group.size).setZero();
    for (int w : eq.wiresOfGroup[g]) {
        const Wire& wire = model.getWire(w);
        const std::size_t first = static_cast<std::size_t>(wire.firstPoint);
        const std::size_t last = first + static_cast<std::size_t>(wire.numPoints) - 1;
        // Points on virtual links follow their links; those on bones are the caller's.
        for (std::size_t k = first; k <= last; ++k) {
            const std::size_t v = static_cast<std::size_t>(points[k].link);
            if (eq.slotOfLink[v] < 0) continue;
            const Eigen::Vector3d r = data.R_GB[v] * points[k].p_B;
            data.p_GP[k] = data.p_GB[v] + r;
            data.v_GP[k] = data.v_GB[v] + data.w_GB[v].cross(r);
        }
        // The path as calcWirePaths and calcWireSpeeds make it, keeping each segment's direction and length.
        double length = 0, speed = 0;
        Eigen::Vector3d e_in = Eigen::Vector3d::Zero();
        for (std::size_t k = first; k < last; ++k) {
            const Eigen::Vector3d segment = data.p_GP[k + 1] - data.p_GP[k];
            const double l = segment.norm();
            const Eigen::Vector3d e_out = l > kMinSegment ? Eigen::Vector3d(segment / l) : Eigen::Vector3d::Zero();
            eq.segmentLength[k] = l;
            eq.segmentDirection[k] = e_out;
            data.dLdp_GP[k] = e_in - e_out;
            length += l;
            e_in = e_out;
        }
        data.dLdp_GP[last] = e_in;
        for (std::size_t k = first; k <= last; ++k) speed += data.dLdp_GP[k].dot(data.v_GP[k]);
        data.wireLength[w] = length;
        data.wireSpeed[w] = speed;
        // The law's slope by central differences (laws give tensions only); a step of 1e-6 of the length keeps
        // truncation and roundoff near 1e-10 of the slope for smooth laws.
        const double T = calcTensionOf(wire, length, speed, time);
        const double h = 1e-6 * std::max(length, 1e-3);
        eq.tension[w] = T;
        eq.tensionSlope[w] =
            (calcTensionOf(wire, length + h, speed, time) - calcTensionOf(wire, length - h, speed, time)) / (2 * h);
        for (std::size_t k = first; k <= last; ++k) {
            const std::size_t v = static_cast<std::size_t>(points[k].link);
            const int slot = eq.slotOfLink[v];
            if (slot < 0) continue;
            const Eigen::Vector3d f = -T * data.dLdp_GP[k];
            eq.residual.segment<3>(6 * slot) += (data.R_GB[v] * points[k].p_B).cross(f) /
                                                eq.lengthScale[static_cast<std::size_t>(slot)];
            eq.residual.segment<3>(6 * slot + 3) += f;
        }
    }
}

// Group g's diagonal block of eq.stiffness and its rows of eq.boneRate (the other blocks are zero).
void calcGroupStiffness(const Model& model, const Data& data, VirtualLinkEquilibriumData& eq, std::size_t g) {
    const std::vector<WirePoint>& points = model.getWirePoints();
    const GroupSlots group(eq, g);
    auto stiffness = eq.stiffness.block(group.row, group.row, group.size, group.size);
    // A link's six columns together: the scaled residual's change for a unit scaled displacement of it.
    for (int s = group.begin; s < group.end; ++s) {
        const std::size_t ss = static_cast<std::size_t>(s);
        const std::size_t v = static_cast<std::size_t>(eq.links[ss]);
        std::array<Eigen::Vector3d, 6> dtheta, dOrigin;
        for (int j = 0; j < 6; ++j) {
            dtheta[j] = j < 3 ? Eigen::Vector3d(Eigen::Vector3d::Unit(j) / eq.lengthScale[ss]) : Eigen::Vector3d::Zero();
            dOrigin[j] = j < 3 ? Eigen::Vector3d(Eigen::Vector3d::Zero()) : Eigen::Vector3d(Eigen::Vector3d::Unit(j - 3));
        }
        for (int w : eq.wiresOfSlot[ss]) {
            const Wire& wire = model.getWire(w);
            for (int k = wire.firstPoint; k < wire.firstPoint + wire.numPoints; ++k) {
                const std::size_t kk = static_cast<std::size_t>(k);
                if (static_cast<std::size_t>(points[kk].link) != v) {
                    eq.dp_GP[kk].setZero();
                    continue;
                }
                const Eigen::Vector3d r = data.R_GB[v] * points[kk].p_B;
                for (int j = 0; j < 6; ++j) eq.dp_GP[kk].col(j) = Eigen::Vector3d(dOrigin[j] + dtheta[j].cross(r));
            }
        }
        // Moving one virtual link leaves the wires that do not touch it as they are.
        calcResidualDerivatives<6>(model, data, eq, eq.wiresOfSlot[ss], s, group.begin, dOrigin,
                                   stiffness.middleCols<6>(6 * static_cast<Eigen::Index>(s - group.begin)));
    }
    stiffness = -stiffness;
    // The bones' motion with the virtual links held still.
    for (int w : eq.wiresOfGroup[g]) {
        const Wire& wire = model.getWire(w);
        for (int k = wire.firstPoint; k < wire.firstPoint + wire.numPoints; ++k) {
            const std::size_t kk = static_cast<std::size_t>(k);
            eq.dp_GP[kk].col(0) = eq.slotOfLink[static_cast<std::size_t>(points[kk].link)] < 0 ? data.v_GP[kk]
                                                                                                : Eigen::Vector3d::Zero();
        }
    }
    calcResidualDerivatives<1>(model, data, eq, eq.wiresOfGroup[g], -1, group.begin, {Eigen::Vector3d::Zero()},
                               eq.boneRate.segment(group.row, group.size));
}

// The damped Newton iteration on the virtual links of groups [first, last) together, their stiffness
// factorised by `factor`; returns the iterations that lowered the residual.
int balanceGroups(const Model& model, Data& data, double time, VirtualLinkEquilibriumData& eq, std::size_t first,
                  std::size_t last, Eigen::PartialPivLU<Eigen::MatrixXd>& factor) {
    const GroupSlots slots(eq, first, last);
    auto residual = eq.residual.segment(slots.row, slots.size);
    auto stiffness = eq.stiffness.block(slots.row, slots.row, slots.size, slots.size);
    auto step = eq.step.segment(slots.row, slots.size);
    auto twist = eq.twist.segment(slots.row, slots.size);
    auto setTwist = [&]() {
        for (int s = slots.begin; s < slots.end; ++s) {
            const std::size_t v = static_cast<std::size_t>(eq.links[static_cast<std::size_t>(s)]);
            data.w_GB[v] = eq.twist.segment<3>(6 * s) / eq.lengthScale[static_cast<std::size_t>(s)];
            data.v_GB[v] = eq.twist.segment<3>(6 * s + 3);
        }
    };
    const auto calcResidual = [&]() {
        for (std::size_t g = first; g < last; ++g) calcGroupResidual(model, data, time, eq, g);
    };
    int iterations = 0;
    std::size_t lastRejected = first;  // the group whose trial residual refused the last rejected step
    calcResidual();
    double norm = residual.lpNorm<Eigen::Infinity>();
    for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
        for (std::size_t g = first; g < last; ++g) calcGroupStiffness(model, data, eq, g);
        // A small multiple of the identity keeps the solve defined where K is singular: a slack link (K and
        // residual zero: it stays put) or one whose wires all meet at one point (no rotational stiffness).
        const double regularisation = kRegularisation * stiffness.lpNorm<Eigen::Infinity>();
        if (regularisation == 0) {  // every wire through these virtual links is slack
            twist.setZero();
            setTwist();
            break;
        }
        stiffness.diagonal().array() += regularisation;
        factor.compute(stiffness);
        // The quasi-static twist: d(residual)/dt = -K twist + boneRate = 0.
        step.noalias() = factor.solve(eq.boneRate.segment(slots.row, slots.size));
        if (!step.allFinite()) break;
        const double twistChange = (step - twist).lpNorm<Eigen::Infinity>();
        const bool twistSettled = twistChange <= kTwistTolerance * step.lpNorm<Eigen::Infinity>();
        if (twistChange > 0) {
            twist = step;
            setTwist();
            calcResidual();
            norm = residual.lpNorm<Eigen::Infinity>();
        }
        if (twistSettled && isWithinTolerance(model, data, eq, slots.begin, slots.end)) break;
        // Newton: residual(x + step) ~ residual - K step = 0, then halved until the residual decreases.
        step.noalias() = factor.solve(residual);
        if (!step.allFinite()) break;
        for (int s = slots.begin; s < slots.end; ++s) {
            const std::size_t ss = static_cast<std::size_t>(s);
            eq.R_GV0[ss] = data.R_GB[static_cast<std::size_t>(eq.links[ss])];
            eq.p_GV0[ss] = data.p_GB[static_cast<std::size_t>(eq.links[ss])];
        }
        double alpha = 1;
        bool decreased = false;
        for (int halving = 0; halving <= kMaxHalvings && !decreased; ++halving, alpha /= 2) {
            for (int s = slots.begin; s < slots.end; ++s) displacePose(data, eq, static_cast<std::size_t>(s), alpha);
            // The step is refused as soon as one group's residual is no smaller, so the group that refused
            // the last one goes first: where one link crawls at a slack wire's kink the others' wires are not
            // made again for each trial.
            double trial = 0;
            for (std::size_t k = 0; k < last - first && trial < norm; ++k) {
                const std::size_t g = first + (lastRejected - first + k) % (last - first);
                calcGroupResidual(model, data, time, eq, g);
                const GroupSlots group(eq, g);
                const double groupTrial = eq.residual.segment(group.row, group.size).lpNorm<Eigen::Infinity>();
                if (!(groupTrial < norm)) {
                    trial = groupTrial;
                    lastRejected = g;
                }
            }
            decreased = trial < norm;
            if (decreased) norm = residual.lpNorm<Eigen::Infinity>();
        }
        if (decreased) ++iterations;
        if (!decreased) {  // stalled (at roundoff, or a kink of a law): back to the best pose
            for (int s = slots.begin; s < slots.end; ++s) displacePose(data, eq, static_cast<std::size_t>(s), 0.0);
            calcResidual();
            break;
        }
    }
    return iterations;
}

// The twist the solve starts from: the virtual links' in `data`, scaled.
void readTwist(const Data& data, VirtualLinkEquilibriumData& eq) {
    for (std::size_t s = 0; s < eq.links.size(); ++s) {
        const std::size_t v = static_cast<std::size_t>(eq.links[s]);
        eq.twist.segment<3>(6 * static_cast<Eigen::Index>(s)) = eq.lengthScale[s] * data.w_GB[v];
        eq.twist.segment<3>(6 * static_cast<Eigen::Index>(s) + 3) = data.v_GB[v];
    }
}

// Both entry points' solve, from the twist in `data`: every group together (in motion), or each group on its
// own (at rest); then the status.
const VirtualLinkEquilibriumStatus& solveEquilibrium(const Model& model, Data& data, double time,
                                                     VirtualLinkEquilibriumData& eq, bool groupsApart) {
    eq.status = VirtualLinkEquilibriumStatus{};
    if (eq.links.empty()) return eq.status;
    readTwist(data, eq);
    if (groupsApart) {
        for (std::size_t g = 0; g < eq.wiresOfGroup.size(); ++g)
            eq.status.iterations =
                std::max(eq.status.iterations, balanceGroups(model, data, time, eq, g, g + 1, eq.groupFactor[g]));
    } else {
        eq.status.iterations = balanceGroups(model, data, time, eq, 0, eq.wiresOfGroup.size(), eq.factor);
    }
    eq.status.converged = measureStatus(model, data, eq);
    return eq.status;
}

}  // namespace

void calcVirtualLinkResidual(const Model& model, Data& data, double time, VirtualLinkEquilibriumData& eq) {
    for (std::size_t g = 0; g < eq.wiresOfGroup.size(); ++g) calcGroupResidual(model, data, time, eq, g);
}

void calcVirtualLinkStiffness(const Model& model, const Data& data, VirtualLinkEquilibriumData& eq) {
    eq.stiffness.setZero();
    for (std::size_t g = 0; g < eq.wiresOfGroup.size(); ++g) calcGroupStiffness(model, data, eq, g);
}

const VirtualLinkEquilibriumStatus& calcVirtualLinkEquilibrium(const Model& model, Data& data, double time,
                                                               VirtualLinkEquilibriumData& eq) {
    // In motion every group is solved together, with one line search: K leaves out how the wires' speeds
    // change with the pose, and where a damped wire goes taut solved apart stalled where solved together did
    // not (a random model's taut forks: 30 N left on one link).
    return solveEquilibrium(model, data, time, eq, false);
}

void getVirtualLinkCoordinates(const Model& model, const Data& data, const VirtualLinkEquilibriumData& eq,
                               Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> u) {
    // A virtual link's free joint joins ground's frame to the link's own (both offsets zero): R_FM = R_GB.
    for (int v : eq.links) {
        const Joint& joint = model.getJoint(v);
        const std::size_t b = static_cast<std::size_t>(v);
        Eigen::Quaterniond rotation(data.R_GB[b]);
        if (rotation.w() < 0) rotation.coeffs() = -rotation.coeffs();
        q.segment<4>(joint.qStart) << rotation.w(), rotation.x(), rotation.y(), rotation.z();
        q.segment<3>(joint.qStart + 4) = data.p_GB[b];
        u.segment<3>(joint.uStart) = data.w_GB[b];
        u.segment<3>(joint.uStart + 3) = data.v_GB[b];
    }
}

double recordVirtualLinkResidual(double worst, const VirtualLinkEquilibriumStatus& status, double time) {
    if (!std::isfinite(status.residual))
        throw Error("virtual-link equilibrium broke down at t = " + std::to_string(time) + " s (residual " +
                    std::to_string(status.residual) + " N after " + std::to_string(status.iterations) + " iterations)");
    return std::max(worst, status.residual);
}

const VirtualLinkEquilibriumStatus& calcVirtualLinkEquilibriumAtRest(const Model& model, Data& data, double time,
                                                                     VirtualLinkEquilibriumData& eq) {
    calcVelocityKinematics(model, data, Eigen::VectorXd::Zero(model.getNumU()));
    // Only the points of its own wires: the whole body's other 952 wires (some wrapped) cost 5 % of a kick
    // frame's fit when every path was made for it.
    const std::vector<WirePoint>& points = model.getWirePoints();
    for (int w : eq.wires) {
        const Wire& wire = model.getWire(w);
        for (int k = wire.firstPoint; k < wire.firstPoint + wire.numPoints; ++k) {
            const std::size_t kk = static_cast<std::size_t>(k), b = static_cast<std::size_t>(points[kk].link);
            data.p_GP[kk] = data.p_GB[b] + data.R_GB[b] * points[kk].p_B;
            data.v_GP[kk].setZero();
        }
    }
    // At rest K is the residual's exact derivative: each group is solved on its own, so that one crawling at
    // a slack wire's kink neither holds the others to its line search nor pays for their stiffness.
    return solveEquilibrium(model, data, time, eq, true);
}

}  // namespace sinew
