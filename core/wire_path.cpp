#include "sinew/core/wire_path.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wrap_object.hpp"

namespace sinew {
namespace {

using PathPoint = Data::WirePathPoint;

// OpenSim's ConditionalPathPoint::isActive, with its 1e-5 widening of the range.
bool isPointActive(const Wire& wire, int point, const Eigen::VectorXd& q) {
    for (const WirePointCondition& c : wire.conditions)
        if (c.point == point) return !(q[c.q] < c.min - 1e-5 || q[c.q] > c.max + 1e-5);  // NaN q stays on the path
    return true;
}

double clampToRange(const Model& model, int q, double value) {
    const Coordinate& c = model.getCoordinates()[static_cast<std::size_t>(q)];
    return std::clamp(value, c.rangeMin, c.rangeMax);
}

bool isSameWrap(const PathPoint& a, const PathPoint& b) { return a.wrap >= 0 && a.wrap == b.wrap; }

// The length of a path: straight segments, and the surface length between a wrap's two tangent points.
double calcPathLength(const PathPoint* path, int size) {
    double length = 0;
    for (int i = 0; i + 1 < size; ++i)
        length += isSameWrap(path[i], path[i + 1]) ? path[i + 1].arcLength : (path[i + 1].p_G - path[i].p_G).norm();
    return length;
}

// A wire's path slice in Data: a short array with room for every point and two tangent points per wrap.
class PathSlice {
public:
    PathSlice(PathPoint* begin, int& size) : begin_(begin), size_(size) {}
    PathPoint* data() const { return begin_; }
    int size() const { return size_; }
    PathPoint& operator[](int i) const { return begin_[i]; }
    void append(const PathPoint& p) { begin_[size_++] = p; }
    void insert(int at, const PathPoint& p) {
        std::copy_backward(begin_ + at, begin_ + size_, begin_ + size_ + 1);
        begin_[at] = p;
        ++size_;
    }
    // Removes a wrap's two tangent points, if the path has them.
    void removeWrap(int wrap) {
        for (int i = 0; i < size_; ++i)
            if (begin_[i].wrap == wrap) {
                std::copy(begin_ + i + 2, begin_ + size_, begin_ + i);
                size_ -= 2;
                return;
            }
    }
    int find(int point) const {
        for (int i = 0; i < size_; ++i)
            if (begin_[i].point == point) return i;
        return -1;
    }

private:
    PathPoint* begin_;
    int& size_;
};

// What a path is computed from: Data's link poses, wire points and coordinates, or displaced copies.
struct PathInputs {
    const std::vector<Eigen::Matrix3d>& R_GB;
    const std::vector<Eigen::Vector3d>& p_GB;
    const std::vector<Eigen::Vector3d>& p_GP;
    const Eigen::VectorXd& q;
};

// A MuJoCo wrap's side site in its object's frame W (pose R_GW, p_GW) at this pose: it moves with its own
// link, which need not be the object's.
Eigen::Vector3d calcSideSite_W(const PathInputs& data, const WireWrap& wrap, const Eigen::Matrix3d& R_GW,
                               const Eigen::Vector3d& p_GW) {
    const std::size_t b = static_cast<std::size_t>(wrap.sideSiteLink);
    return R_GW.transpose() * (data.p_GB[b] + data.R_GB[b] * wrap.sideSite_B - p_GW);
}

// OpenSim's GeometryPath::applyWrapObjects: each wrap in turn takes its tangent points out, tries every
// segment in its range, and puts back the wrap a segment must take (it passes through the object) or,
// failing that, the one that lengthens the path least. With several wraps, up to 8 rounds until the
// length settles within 0.5 mm; a first round where the first wrap missed and the second found an end
// inside its object is redone with those two swapped. MuJoCo's wraps each take a segment of their own, so
// they settle in one round whatever their order (docs/wire-paths.md, "MuJoCo wrapping").
void applyWraps(const Model& model, const PathInputs& data, const Wire& wire, PathSlice path) {
    const int numWraps = static_cast<int>(wire.wraps.size());
    const bool independent = std::all_of(wire.wraps.begin(), wire.wraps.end(),
                                         [](const WireWrap& wrap) { return wrap.method == WrapMethod::MuJoCo; });
    const int rounds = numWraps < 2 || independent ? 1 : 8;
    bool swapped = false;
    double lastLength = std::numeric_limits<double>::infinity();
    WrapStatus firstStatus = WrapStatus::NoWrap, secondStatus = WrapStatus::NoWrap;
    for (int round = 0; round < rounds; ++round) {
        for (int i = 0; i < numWraps; ++i) {
            const int w = swapped && i < 2 ? 1 - i : i;
            const WireWrap& wrap = wire.wraps[static_cast<std::size_t>(w)];
            const WrapObject& object = model.getWrapObjects()[static_cast<std::size_t>(wrap.object)];
            path.removeWrap(w);
            // The first and last active points of the wrap's range, and where they are in the path.
            int first = wrap.firstPoint, last = wrap.lastPoint;
            while (first <= wrap.lastPoint && !isPointActive(wire, first, data.q)) ++first;
            while (last >= wrap.firstPoint && !isPointActive(wire, last, data.q)) --last;
            if (first > last) continue;
            const int start = path.find(first), end = path.find(last);
            const std::size_t b = static_cast<std::size_t>(object.link);
            const Eigen::Matrix3d R_GW = data.R_GB[b] * object.R_BW;
            const Eigen::Vector3d p_GW = data.p_GB[b] + data.R_GB[b] * object.p_BW;
            const Eigen::Vector3d sideSite_W =
                wrap.hasSideSite ? calcSideSite_W(data, wrap, R_GW, p_GW) : Eigen::Vector3d(Eigen::Vector3d::Zero());
            WrapStatus status = WrapStatus::NoWrap;
            WrapSolution best;
            int bestSegment = -1;
            double leastIncrease = std::numeric_limits<double>::infinity();
            for (int k = start; k < end; ++k) {
                if (isSameWrap(path[k], path[k + 1])) continue;
                const Eigen::Vector3d p1_W = R_GW.transpose() * (path[k].p_G - p_GW);
                const Eigen::Vector3d p2_W = R_GW.transpose() * (path[k + 1].p_G - p_GW);
                const WrapSolution s = calcWrap(object, wrap.method, wrap.hasSideSite ? &sideSite_W : nullptr, p1_W, p2_W);
                status = s.status;
                if (status == WrapStatus::MandatoryWrap) {
                    best = s;
                    bestSegment = k;
                    break;
                }
                if (status == WrapStatus::Wrapped) {
                    const double increase = s.calcLength(p1_W, p2_W) - (p2_W - p1_W).norm();
                    if (increase < leastIncrease) {
                        leastIncrease = increase;
                        best = s;
                        bestSegment = k;
                    }
                }
            }
            if (i == 0) firstStatus = status;
            if (i == 1) secondStatus = status;
            if (bestSegment < 0) continue;
            path.insert(bestSegment + 1, PathPoint{object.link, -1, w, p_GW + R_GW * best.r1_W, Eigen::Vector3d::Zero(), 0});
            path.insert(bestSegment + 2,
                        PathPoint{object.link, -1, w, p_GW + R_GW * best.r2_W, Eigen::Vector3d::Zero(), best.arcLength});
        }
        const double length = calcPathLength(path.data(), path.size());
        if (std::abs(length - lastLength) < 0.0005) break;
        lastLength = length;
        if (round == 0 && numWraps > 1 && firstStatus == WrapStatus::NoWrap && secondStatus == WrapStatus::InsideRadius) {
            swapped = true;
            path.removeWrap(0);
        }
    }
}

// The active points of a wire in order, with the wraps' tangent points.
void buildGeneralWirePath(const Model& model, const PathInputs& inputs, const Wire& wire, PathSlice path) {
    for (int k = 0; k < wire.numPoints; ++k)
        if (isPointActive(wire, k, inputs.q)) {
            const std::size_t kk = static_cast<std::size_t>(wire.firstPoint + k);
            path.append(PathPoint{model.getWirePoints()[kk].link, k, -1, inputs.p_GP[kk], Eigen::Vector3d::Zero(), 0});
        }
    applyWraps(model, inputs, wire, path);
}

// The path of a wire with conditional or moving points or wraps (points already in Data::p_GP), its
// length, and d(length)/d(p) of each of its points with tangent points held on their objects: by the
// envelope theorem that is the whole derivative for shortest paths (docs/wire-paths.md).
void calcGeneralWirePath(const Model& model, Data& data, int w) {
    const Wire& wire = model.getWire(w);
    data.wirePathSize[static_cast<std::size_t>(w)] = 0;
    PathSlice path(data.wirePath.data() + data.wirePathStart[static_cast<std::size_t>(w)],
                   data.wirePathSize[static_cast<std::size_t>(w)]);
    buildGeneralWirePath(model, PathInputs{data.R_GB, data.p_GB, data.p_GP, data.q}, wire, path);
    for (int i = 0; i < path.size(); ++i) path[i].dLdp_G.setZero();
    for (int i = 0; i + 1 < path.size(); ++i) {
        if (isSameWrap(path[i], path[i + 1])) continue;  // rigid on the object's link: no derivative
        const Eigen::Vector3d segment = path[i + 1].p_G - path[i].p_G;
        const double l = segment.norm();
        if (l <= 1e-12) continue;  // a collapsed segment pulls on neither end
        path[i].dLdp_G -= segment / l;
        path[i + 1].dLdp_G += segment / l;
    }
    data.wireLength[w] = calcPathLength(path.data(), path.size());
}

// Whether `link` moves with the joint of `jointLink` (is it or one of its descendants).
bool movesWith(const Model& model, int link, int jointLink) {
    for (int l = link; l != kGround; l = model.getJoint(l).parent)
        if (l == jointLink) return true;
    return false;
}

// One central difference along a mobility: the links that move with its joint (jointLink, or none for
// kGround) displaced by the rigid motion of twist xi_G ([angular; linear at p_ref], per unit u) over a step
// h, the coordinate q_index (or none for -1) moved by h, and the wire's points placed again.
struct Displacement {
    int jointLink = kGround;
    SpatialVector xi_G = SpatialVector::Zero();
    Eigen::Vector3d p_ref = Eigen::Vector3d::Zero();
    int qIndex = -1;
};

// Sets the displaced copies of the poses of the wire's links and of its points back to Data's.
void resetDisplacedCopies(const Model& model, Data& data, const Wire& wire) {
    const std::vector<WirePoint>& points = model.getWirePoints();
    auto reset = [&](int link) {
        data.displacedR_GB[static_cast<std::size_t>(link)] = data.R_GB[static_cast<std::size_t>(link)];
        data.displacedP_GB[static_cast<std::size_t>(link)] = data.p_GB[static_cast<std::size_t>(link)];
    };
    for (int k = 0; k < wire.numPoints; ++k) {
        const std::size_t kk = static_cast<std::size_t>(wire.firstPoint + k);
        reset(points[kk].link);
        data.displacedP_GP[kk] = data.p_GP[kk];
    }
    for (const WireWrap& wrap : wire.wraps) {
        reset(model.getWrapObjects()[static_cast<std::size_t>(wrap.object)].link);
        if (wrap.hasSideSite) reset(wrap.sideSiteLink);
    }
}

// The wire's length after `displacement` over a step h; leaves the displaced copies as Data has them.
double calcDisplacedLength(const Model& model, Data& data, const Wire& wire, const Displacement& displacement,
                           double h) {
    const std::vector<WirePoint>& points = model.getWirePoints();
    const Eigen::Vector3d angle = h * displacement.xi_G.head<3>();
    const Eigen::Matrix3d rotation =
        angle.norm() > 0 ? Eigen::AngleAxisd(angle.norm(), angle.normalized()).toRotationMatrix() : Eigen::Matrix3d::Identity();
    auto displace = [&](int link) {
        const std::size_t b = static_cast<std::size_t>(link);
        if (displacement.jointLink == kGround || !movesWith(model, link, displacement.jointLink)) return;
        data.displacedR_GB[b] = rotation * data.R_GB[b];
        data.displacedP_GB[b] = displacement.p_ref + rotation * (data.p_GB[b] - displacement.p_ref) + h * displacement.xi_G.tail<3>();
    };
    for (int k = 0; k < wire.numPoints; ++k) displace(points[static_cast<std::size_t>(wire.firstPoint + k)].link);
    for (const WireWrap& wrap : wire.wraps) {
        displace(model.getWrapObjects()[static_cast<std::size_t>(wrap.object)].link);
        if (wrap.hasSideSite) displace(wrap.sideSiteLink);
    }
    if (displacement.qIndex >= 0) data.displacedQ[displacement.qIndex] += h;
    for (int k = 0; k < wire.numPoints; ++k) {
        const std::size_t kk = static_cast<std::size_t>(wire.firstPoint + k), b = static_cast<std::size_t>(points[kk].link);
        data.displacedP_GP[kk] = data.displacedP_GB[b] + data.displacedR_GB[b] * calcWirePointLocation(model, wire, k, data.displacedQ);
    }
    int size = 0;
    buildGeneralWirePath(model, PathInputs{data.displacedR_GB, data.displacedP_GB, data.displacedP_GP, data.displacedQ}, wire,
                         PathSlice(data.displacedPath.data(), size));
    const double length = calcPathLength(data.displacedPath.data(), size);
    resetDisplacedCopies(model, data, wire);
    if (displacement.qIndex >= 0) data.displacedQ[displacement.qIndex] = data.q[displacement.qIndex];
    return length;
}

// dL/du of wire w by central differences of its whole path, OpenSim's wrap rounds included: along each
// mobility of the joints that move some but not all of its points, objects and side sites (the span links), as
// the rigid motion of the joint's subtree (the joint's twist from its motion subspace), with the coordinate
// itself moved for the wire's moving and conditional points. A step of 1e-6 (rad or m) keeps truncation and
// roundoff near 1e-10 of the moment arm.
void calcLengthGradientNumerically(const Model& model, Data& data, int w) {
    constexpr double h = 1e-6;
    const Wire& wire = model.getWire(w);
    auto gradient = data.wireLengthGradient.row(data.wireGradientRow[static_cast<std::size_t>(w)]);
    gradient.setZero();
    resetDisplacedCopies(model, data, wire);
    data.displacedQ = data.q;
    // Where the path jumps within the step (OpenSim's ellipsoid heuristics can flip the wrap to the other
    // side), the central difference would be the jump over 2h: the one-sided difference away from it is
    // taken instead, the smaller one, as the two sides then differ by far more than h times the curvature.
    const double length = data.wireLength[w];
    auto difference = [&](const Displacement& d) {
        const double forward = (calcDisplacedLength(model, data, wire, d, h) - length) / h;
        const double backward = (length - calcDisplacedLength(model, data, wire, d, -h)) / h;
        if (std::abs(forward - backward) > 1e-2) return std::abs(forward) < std::abs(backward) ? forward : backward;
        return 0.5 * (forward + backward);
    };
    const auto spanBegin = model.getSupportLinks().begin() + wire.firstSupportLink, spanEnd = spanBegin + wire.numSpanLinks;
    for (auto it = spanBegin; it != spanEnd; ++it) {
        const int link = *it;
        const Joint& joint = model.getJoint(link);
        const std::size_t b = static_cast<std::size_t>(link);
        const JointMotion H_G = calcJointMotion_G(joint, data, link, data.p_GM[b]);
        for (int c = 0; c < joint.nu; ++c) {
            // Coordinates are rates of their own only where nq == nu (not quaternions).
            const int qIndex = joint.nq == joint.nu ? joint.qStart + c : -1;
            gradient[joint.uStart + c] = difference(Displacement{link, H_G.col(c), data.p_GM[b], qIndex});
        }
    }
    // Coordinates that move a point in its link without moving any of the wire's links.
    for (const WirePointMotion& m : wire.motions) {
        const bool done = std::any_of(spanBegin, spanEnd, [&](int link) {
            const Joint& joint = model.getJoint(link);
            return m.u >= joint.uStart && m.u < joint.uStart + joint.nu;
        });
        if (!done) gradient[m.u] = difference(Displacement{kGround, SpatialVector::Zero(), Eigen::Vector3d::Zero(), m.q});
    }
}

}  // namespace

Eigen::Vector3d calcWirePointLocation(const Model& model, const Wire& wire, int point, const Eigen::VectorXd& q) {
    Eigen::Vector3d p_B = model.getWirePoints()[static_cast<std::size_t>(wire.firstPoint + point)].p_B;
    for (const WirePointMotion& m : wire.motions)
        if (m.point == point) p_B[m.axis] = m.function.calcValue(clampToRange(model, m.q, q[m.q]));
    return p_B;
}

double calcWirePointMotionRate(const Model& model, const WirePointMotion& motion, const Eigen::VectorXd& q) {
    const double value = q[motion.q];
    if (clampToRange(model, motion.q, value) != value) return 0;
    return motion.function.calcDerivative(value, 1);
}

double calcWirePointMotionTerm(const Model& model, const Data& data, int w, const WirePointMotion& motion) {
    const PathPoint* path = data.wirePath.data() + data.wirePathStart[static_cast<std::size_t>(w)];
    for (int i = 0; i < data.wirePathSize[static_cast<std::size_t>(w)]; ++i)
        if (path[i].point == motion.point)
            return path[i].dLdp_G.dot(data.R_GB[static_cast<std::size_t>(path[i].link)].col(motion.axis)) *
                   calcWirePointMotionRate(model, motion, data.q);
    return 0;
}

bool isLengthDifferentiatedNumerically(const Model& model, int w) {
    const Wire& wire = model.getWire(w);
    return std::any_of(wire.wraps.begin(), wire.wraps.end(), [&](const WireWrap& wrap) {
        return model.getWrapObjects()[static_cast<std::size_t>(wrap.object)].shape == WrapShape::Ellipsoid;
    });
}

void calcWirePaths(const Model& model, Data& data) {
    const std::vector<WirePoint>& points = model.getWirePoints();
    for (std::size_t k = 0; k < points.size(); ++k) {
        const std::size_t b = static_cast<std::size_t>(points[k].link);
        data.p_GP[k] = data.p_GB[b] + data.R_GB[b] * points[k].p_B;
    }
    for (int w = 0; w < model.getNumWires(); ++w) {
        const Wire& wire = model.getWire(w);
        if (!wire.isPolyline()) {
            for (const WirePointMotion& m : wire.motions) {
                const std::size_t k = static_cast<std::size_t>(wire.firstPoint + m.point);
                const std::size_t b = static_cast<std::size_t>(points[k].link);
                data.p_GP[k] = data.p_GB[b] + data.R_GB[b] * calcWirePointLocation(model, wire, m.point, data.q);
            }
            calcGeneralWirePath(model, data, w);
            if (data.wireGradientRow[static_cast<std::size_t>(w)] >= 0) calcLengthGradientNumerically(model, data, w);
            continue;
        }
        const std::size_t first = static_cast<std::size_t>(wire.firstPoint);
        const std::size_t last = first + static_cast<std::size_t>(wire.numPoints) - 1;
        double length = 0;
        Eigen::Vector3d e_in = Eigen::Vector3d::Zero();
        for (std::size_t k = first; k < last; ++k) {
            const Eigen::Vector3d segment = data.p_GP[k + 1] - data.p_GP[k];
            const double l = segment.norm();
            length += l;
            // A segment that has collapsed to a point has no direction; it then pulls on neither end.
            const Eigen::Vector3d e_out = l > 1e-12 ? Eigen::Vector3d(segment / l) : Eigen::Vector3d::Zero();
            data.dLdp_GP[k] = e_in - e_out;
            e_in = e_out;
        }
        data.dLdp_GP[last] = e_in;
        data.wireLength[w] = length;
    }
}

void calcWireSpeeds(const Model& model, Data& data) {
    const std::vector<WirePoint>& points = model.getWirePoints();
    for (std::size_t k = 0; k < points.size(); ++k) {
        const std::size_t b = static_cast<std::size_t>(points[k].link);
        data.v_GP[k] = data.v_GB[b] + data.w_GB[b].cross(data.p_GP[k] - data.p_GB[b]);
    }
    for (int w = 0; w < model.getNumWires(); ++w) {
        const Wire& wire = model.getWire(w);
        double speed = 0;
        if (wire.isPolyline()) {
            for (int k = wire.firstPoint; k < wire.firstPoint + wire.numPoints; ++k)
                speed += data.dLdp_GP[static_cast<std::size_t>(k)].dot(data.v_GP[static_cast<std::size_t>(k)]);
            data.wireSpeed[w] = speed;
            continue;
        }
        const int row = data.wireGradientRow[static_cast<std::size_t>(w)];
        if (row >= 0) {
            data.wireSpeed[w] = data.wireLengthGradient.row(row).dot(data.u);
            continue;
        }
        // A moving point also moves in its link: R_GB dp_B/dq qdot, with qdot = u for its coordinate.
        for (const WirePointMotion& m : wire.motions) {
            const std::size_t k = static_cast<std::size_t>(wire.firstPoint + m.point);
            const std::size_t b = static_cast<std::size_t>(points[k].link);
            data.v_GP[k] += data.R_GB[b].col(m.axis) * (calcWirePointMotionRate(model, m, data.q) * data.u[m.u]);
        }
        const PathPoint* path = data.wirePath.data() + data.wirePathStart[static_cast<std::size_t>(w)];
        for (int i = 0; i < data.wirePathSize[static_cast<std::size_t>(w)]; ++i) {
            const PathPoint& p = path[i];
            const std::size_t b = static_cast<std::size_t>(p.link);
            const Eigen::Vector3d v_G = p.point >= 0 ? data.v_GP[static_cast<std::size_t>(wire.firstPoint + p.point)]
                                                     : Eigen::Vector3d(data.v_GB[b] + data.w_GB[b].cross(p.p_G - data.p_GB[b]));
            speed += p.dLdp_G.dot(v_G);
        }
        data.wireSpeed[w] = speed;
    }
}

void calcWireTensions(const Model& model, const Data& data, double time, Eigen::Ref<Eigen::VectorXd> tensions) {
    for (int w = 0; w < model.getNumWires(); ++w) {
        const Wire& wire = model.getWire(w);
        try {
            tensions[w] = wire.law->calcTension(WireState{data.wireLength[w], data.wireSpeed[w], time});
        } catch (const Error& e) {
            throw Error("wire '" + wire.name + "': " + e.what());
        }
    }
}

double calcWirePotentialEnergy(const Model& model, const Data& data) {
    double energy = 0;
    for (int w = 0; w < model.getNumWires(); ++w) energy += model.getWire(w).law->calcPotentialEnergy(data.wireLength[w]);
    return energy;
}

}  // namespace sinew
