#include "sinew/core/wire_path_samples.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

// One way round a wrap's arc in its object's frame W, from the first tangent point (t = 0) to the second
// (t = 1): x(t) = centre + t rise + U cos(theta0 + t sweep) + V sin(theta0 + t sweep). A helix round a
// cylinder (rise along its axis), a plane section of a sphere or an ellipsoid (rise 0).
struct ArcWay {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero(), rise = Eigen::Vector3d::Zero();
    Eigen::Vector3d U = Eigen::Vector3d::Zero(), V = Eigen::Vector3d::Zero();
    double theta0 = 0, sweep = 0;  // rad

    Eigen::Vector3d at(double t) const {
        const double a = theta0 + t * sweep;
        return centre + t * rise + U * std::cos(a) + V * std::sin(a);
    }
    Eigen::Vector3d tangent(double t) const {  // dx/dt
        const double a = theta0 + t * sweep;
        return rise + sweep * (V * std::cos(a) - U * std::sin(a));
    }
    ArcWay otherWay() const {
        ArcWay other = *this;
        other.sweep = sweep > 0 ? sweep - 2 * M_PI : sweep + 2 * M_PI;
        return other;
    }
    int countSteps(double maxStepAngle) const {
        return std::max(1, static_cast<int>(std::ceil(std::abs(sweep) / maxStepAngle)));
    }
    // The integral of |dx/dt| by 4-point Gauss-Legendre on 16 panels: exact for a helix (constant speed),
    // to roundoff for the sections an ellipsoid's radii give.
    double calcLength() const {
        static const double nodes[2] = {0.3399810435848563, 0.8611363115940526};
        static const double weights[2] = {0.6521451548625461, 0.3478548451374538};
        constexpr int kPanels = 16;
        double length = 0;
        for (int k = 0; k < kPanels; ++k)
            for (int i = 0; i < 2; ++i)
                for (const double side : {-1.0, 1.0})
                    length += weights[i] * 0.5 / kPanels * tangent((k + 0.5 + 0.5 * side * nodes[i]) / kPanels).norm();
        return length;
    }
};

// The helix round a cylinder of radius R (axis W's z) from r1 to r2, the shorter way round: unrolled, the
// cylinder's shortest path is straight, so the rise is linear in the angle (docs/wire-paths.md, "Cylinder").
ArcWay makeHelix(double R, const Eigen::Vector3d& r1, const Eigen::Vector3d& r2) {
    ArcWay arc;
    arc.centre = Eigen::Vector3d(0, 0, r1.z());
    arc.rise = Eigen::Vector3d(0, 0, r2.z() - r1.z());
    arc.U = R * Eigen::Vector3d::UnitX();
    arc.V = R * Eigen::Vector3d::UnitY();
    arc.theta0 = std::atan2(r1.y(), r1.x());
    arc.sweep = std::remainder(std::atan2(r2.y(), r2.x()) - arc.theta0, 2 * M_PI);
    return arc;
}

// The plane of an arc over a sphere or an ellipsoid holds the segment ends p1, p2 and the tangent points
// r1, r2 (and a sphere's centre): of the normals those points give, the best conditioned.
Eigen::Vector3d calcArcPlaneNormal(const Eigen::Vector3d& p1, const Eigen::Vector3d& r1, const Eigen::Vector3d& r2,
                                   const Eigen::Vector3d& p2, bool throughCentre) {
    const Eigen::Vector3d pairs[][2] = {{r1 - p1, r2 - p1}, {r1 - p2, r2 - p2}, {r1 - p1, p2 - p1},
                                        {r2 - r1, p2 - p1}, {r1, r2}};
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    double best = 0;
    for (int k = 0; k < (throughCentre ? 5 : 4); ++k) {
        const Eigen::Vector3d n = pairs[k][0].cross(pairs[k][1]);
        const double size = pairs[k][0].norm() * pairs[k][1].norm();
        if (size > 0 && n.norm() / size > best) {
            best = n.norm() / size;
            normal = n.normalized();
        }
    }
    return normal;
}

// The section of the ellipsoid x^T D x = 1 (D = diag(1/radii^2)) by the plane through r1 with unit normal
// n, from r1 to r2 the shorter way in the section's own angle: with x = r1 + E s (E an orthonormal basis of
// the plane), (s - s0)^T M (s - s0) = k, M = Q diag(lambda) Q^T, an ellipse of semi-axes sqrt(k / lambda).
ArcWay makeSection(const Eigen::Vector3d& radii, const Eigen::Vector3d& n, const Eigen::Vector3d& r1,
                   const Eigen::Vector3d& r2) {
    Eigen::Matrix<double, 3, 2> E;
    const Eigen::Vector3d chord = r2 - r1 - n.dot(r2 - r1) * n;
    E.col(0) = chord.norm() > 0 ? chord.normalized() : n.unitOrthogonal();
    E.col(1) = n.cross(E.col(0));
    const Eigen::Vector3d D = radii.cwiseAbs2().cwiseInverse();
    const Eigen::Matrix2d M = E.transpose() * D.asDiagonal() * E;
    const Eigen::Vector2d g = E.transpose() * D.cwiseProduct(r1);
    const Eigen::Vector2d s0 = -M.ldlt().solve(g);
    const double k = std::max(0.0, -g.dot(s0) - (r1.dot(D.cwiseProduct(r1)) - 1));
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(M);
    const Eigen::Matrix2d& Q = eig.eigenvectors();
    const Eigen::Vector2d axes = (k / eig.eigenvalues().array()).sqrt();
    ArcWay arc;
    arc.centre = r1 + E * s0;
    arc.U = E * Q.col(0) * axes[0];
    arc.V = E * Q.col(1) * axes[1];
    auto angleOf = [&](const Eigen::Vector3d& x) {
        const Eigen::Vector2d z = (Q.transpose() * (E.transpose() * (x - r1) - s0)).cwiseQuotient(axes);
        return std::atan2(z[1], z[0]);
    };
    arc.theta0 = angleOf(r1);
    arc.sweep = std::remainder(angleOf(r2) - arc.theta0, 2 * M_PI);
    return arc;
}

// Of the two ways round, the one whose length calcWirePaths counted; where both are as long (half a turn),
// the one the straight segments p1 -> r1 and r2 -> p2 run into and out of.
ArcWay chooseWay(const ArcWay& arc, const Eigen::Vector3d& p1, const Eigen::Vector3d& r1, const Eigen::Vector3d& r2,
                 const Eigen::Vector3d& p2, double arcLength) {
    const ArcWay other = arc.otherWay();
    const double gap = std::abs(arc.calcLength() - arcLength) - std::abs(other.calcLength() - arcLength);
    if (std::abs(gap) > 1e-9 * arcLength) return gap < 0 ? arc : other;
    auto alignment = [&](const ArcWay& a) {
        return a.tangent(0).normalized().dot(r1 - p1) + a.tangent(1).normalized().dot(p2 - r2);
    };
    return alignment(arc) >= alignment(other) ? arc : other;
}

// The arc points strictly between the tangent points path[i - 1] and path[i] of one wrap (W's pose from
// Data's kinematics; the segment ends are the path's neighbouring points).
void addArcSamples(const Model& model, const Data& data, const Wire& wire, int start, int size, int i,
                   double maxStepAngle, std::vector<WirePathSample>& samples) {
    auto pathPoint = [&](int k) -> const Data::WirePathPoint& {
        return data.wirePath[static_cast<std::size_t>(start + std::max(0, std::min(size - 1, k)))];
    };
    const Data::WirePathPoint& second = pathPoint(i);
    const WrapObject& object =
        model.getWrapObjects()[static_cast<std::size_t>(wire.wraps[static_cast<std::size_t>(second.wrap)].object)];
    const std::size_t b = static_cast<std::size_t>(object.link);
    const Eigen::Matrix3d R_GW = data.R_GB[b] * object.R_BW;
    const Eigen::Vector3d p_GW = data.p_GB[b] + data.R_GB[b] * object.p_BW;
    auto toW = [&](int k) -> Eigen::Vector3d { return R_GW.transpose() * (pathPoint(k).p_G - p_GW); };
    const Eigen::Vector3d p1 = toW(i - 2), r1 = toW(i - 1), r2 = toW(i), p2 = toW(i + 1);
    ArcWay arc;
    if (object.shape == WrapShape::Cylinder) {
        arc = makeHelix(object.radius, r1, r2);
    } else {
        const bool sphere = object.shape == WrapShape::Sphere;
        const Eigen::Vector3d radii = sphere ? Eigen::Vector3d::Constant(object.radius) : object.radii;
        arc = makeSection(radii, calcArcPlaneNormal(p1, r1, r2, p2, sphere), r1, r2);
    }
    arc = chooseWay(arc, p1, r1, r2, p2, second.arcLength);
    const int steps = arc.countSteps(maxStepAngle);
    for (int k = 1; k < steps; ++k)
        samples.push_back({object.link, second.wrap, p_GW + R_GW * arc.at(static_cast<double>(k) / steps)});
}

}  // namespace

void calcWirePathSamples(const Model& model, const Data& data, int w, double maxStepAngle,
                         std::vector<WirePathSample>& samples) {
    if (!(maxStepAngle > 0))
        throw Error("wire path samples: the step " + std::to_string(maxStepAngle) + " rad must be > 0");
    const Wire& wire = model.getWire(w);
    samples.clear();
    if (wire.isPolyline()) {
        for (int i = 0; i < wire.numPoints; ++i) {
            const std::size_t p = static_cast<std::size_t>(wire.firstPoint + i);
            samples.push_back({model.getWirePoints()[p].link, -1, data.p_GP[p]});
        }
        return;
    }
    const int start = data.wirePathStart[static_cast<std::size_t>(w)];
    const int size = data.wirePathSize[static_cast<std::size_t>(w)];
    for (int i = 0; i < size; ++i) {
        const Data::WirePathPoint& point = data.wirePath[static_cast<std::size_t>(start + i)];
        const bool closesWrap =
            i > 0 && point.wrap >= 0 && data.wirePath[static_cast<std::size_t>(start + i - 1)].wrap == point.wrap;
        if (closesWrap && point.arcLength > 0) addArcSamples(model, data, wire, start, size, i, maxStepAngle, samples);
        samples.push_back({point.link, point.wrap, point.p_G});
    }
}

}  // namespace sinew
