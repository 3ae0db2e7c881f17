#include "mjcf_inertia.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <vector>

#include "sinew/core/error.hpp"

namespace sinew::mjcf {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kEpsilon = 1e-14;  // mjEPS

// How many size parameters each geom type reads (mjGEOMINFO: plane, hfield, sphere, capsule, ellipsoid,
// cylinder, box, mesh).
int getNumSizes(GeomKind type) {
    static const int sizes[] = {3, 0, 1, 2, 3, 2, 3, 0};
    return sizes[static_cast<int>(type)];
}

double calcVolume(GeomKind type, const Eigen::Vector3d& s) {
    switch (type) {
        case GeomKind::Sphere: return 4 * kPi * s[0] * s[0] * s[0] / 3;
        case GeomKind::Capsule: return kPi * (s[0] * s[0] * 2 * s[1] + 4 * s[0] * s[0] * s[0] / 3);
        case GeomKind::Cylinder: return kPi * s[0] * s[0] * 2 * s[1];
        case GeomKind::Ellipsoid: return 4 * kPi * s[0] * s[1] * s[2] / 3;
        case GeomKind::Box: return 8 * s[0] * s[1] * s[2];
        default: return 0;
    }
}

// Principal moments about the geom's centre (mjCGeom::SetInertia). A capsule is a cylinder plus two
// hemispheres displaced along its axis.
Eigen::Vector3d calcPrincipalMoments(GeomKind type, const Eigen::Vector3d& s, double mass) {
    switch (type) {
        case GeomKind::Sphere: return Eigen::Vector3d::Constant(2 * mass * s[0] * s[0] / 5);
        case GeomKind::Capsule: {
            const double r = s[0], h = 2 * s[1];
            const double sphereMass = mass * 4 * r / (4 * r + 3 * h), cylinderMass = mass - sphereMass;
            const double sphereMoment = 2 * sphereMass * r * r / 5;
            const double transverse = cylinderMass * (3 * r * r + h * h) / 12 + sphereMoment +
                                      sphereMass * h * (3 * r + 2 * h) / 8;
            return {transverse, transverse, cylinderMass * r * r / 2 + sphereMoment};
        }
        case GeomKind::Cylinder: {
            const double h = 2 * s[1], transverse = mass * (3 * s[0] * s[0] + h * h) / 12;
            return {transverse, transverse, mass * s[0] * s[0] / 2};
        }
        case GeomKind::Ellipsoid:
            return {mass * (s[1] * s[1] + s[2] * s[2]) / 5, mass * (s[0] * s[0] + s[2] * s[2]) / 5,
                    mass * (s[0] * s[0] + s[1] * s[1]) / 5};
        case GeomKind::Box:
            return {mass * (s[1] * s[1] + s[2] * s[2]) / 3, mass * (s[0] * s[0] + s[2] * s[2]) / 3,
                    mass * (s[0] * s[0] + s[1] * s[1]) / 3};
        default: return Eigen::Vector3d::Zero();
    }
}

[[noreturn]] void failGeom(const MjcfGeom& geom, const std::string& message) {
    throw ModelError(geom.where, (geom.name.empty() ? std::string("geom") : "geom '" + geom.name + "'") + ": " + message);
}

// fromto: the geom's centre, its z axis along the segment (from - to, as MuJoCo takes it) and its half
// length in size[1]; an ellipsoid or box keeps size[0] across and takes the half length as size[2].
void applyFromTo(const MjcfGeom& geom, CompiledGeom& c) {
    const GeomKind t = geom.type;
    if (t != GeomKind::Capsule && t != GeomKind::Cylinder && t != GeomKind::Ellipsoid && t != GeomKind::Box)
        failGeom(geom, std::string("fromto needs a capsule, cylinder, ellipsoid or box, not a ") + toString(t));
    if (!geom.pos.isZero(0)) failGeom(geom, "both pos and fromto given; give one");
    const Eigen::Vector3d from = geom.fromto->head<3>(), to = geom.fromto->tail<3>();
    const Eigen::Vector3d direction = from - to;
    if (direction.squaredNorm() < kEpsilon || direction.norm() / 2 < kEpsilon)
        failGeom(geom, "the fromto points are too close to give a direction");
    c.size[1] = direction.norm() / 2;
    if (t == GeomKind::Ellipsoid || t == GeomKind::Box) {
        c.size[2] = c.size[1];
        c.size[1] = c.size[0];
    }
    c.pos = 0.5 * (from + to);
    c.quat = calcQuaternionFromZAxis(direction.normalized());
}

// The principal axes and moments of a symmetric inertia (columns of R, a rotation).
void diagonalize(const Eigen::Matrix3d& inertia, Eigen::Quaterniond& axes, Eigen::Vector3d& moments) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(inertia);
    Eigen::Matrix3d R = solver.eigenvectors();
    if (R.determinant() < 0) R.col(2) = -R.col(2);
    axes = Eigen::Quaterniond(R).normalized();
    moments = solver.eigenvalues();
}

// mjCBody::GeomFrame: one geom gives its own frame; several give their total mass, its centre and the
// principal axes of their summed inertias.
bool setFromGeoms(const MjcfModel& model, int body, MassProperties& p) {
    std::vector<CompiledGeom> geoms;
    const std::array<int, 2>& groups = model.compiler.inertiaGroupRange;
    for (const MjcfGeom& geom : model.geoms)
        if (geom.body == body && geom.type != GeomKind::Mesh && geom.group >= groups[0] && geom.group <= groups[1])
            geoms.push_back(compileGeom(geom));
    if (geoms.empty()) return false;
    if (geoms.size() == 1) {
        p = {geoms[0].mass, geoms[0].pos, geoms[0].quat, geoms[0].inertia};
        return true;
    }
    p.mass = 0;
    p.com.setZero();
    for (const CompiledGeom& g : geoms) {
        p.mass += g.mass;
        p.com += g.mass * g.pos;
    }
    const MjcfBody& b = model.bodies[static_cast<std::size_t>(body)];
    if (p.mass < kMinValue)
        throw ModelError(b.where, "body '" + b.name + "': its geoms have no mass, so MuJoCo cannot place its "
                                  "centre of mass; give the body an <inertial> or its geoms mass");
    p.com /= p.mass;
    Eigen::Matrix3d total = Eigen::Matrix3d::Zero();
    for (const CompiledGeom& g : geoms) {
        const Eigen::Matrix3d R = g.quat.toRotationMatrix();
        const Eigen::Vector3d d = g.pos - p.com;
        total += R * g.inertia.asDiagonal() * R.transpose() +
                 g.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
    }
    diagonalize(total, p.principalAxes, p.principalMoments);
    return true;
}

MassProperties fromInertial(const MjcfInertial& inertial) {
    MassProperties p{inertial.mass, inertial.pos, inertial.quat, inertial.diagonal};
    if (inertial.full) {
        const auto& f = *inertial.full;
        Eigen::Matrix3d full;
        full << f[0], f[3], f[4], f[3], f[1], f[5], f[4], f[5], f[2];
        diagonalize(full, p.principalAxes, p.principalMoments);
        if (p.principalMoments.minCoeff() < kEpsilon)
            throw ModelError(inertial.where, "inertial: fullinertia must be positive definite (smallest principal "
                                             "moment " + formatNumber(p.principalMoments.minCoeff()) + " kg m^2)");
    }
    return p;
}

// boundmass and boundinertia floors, then MuJoCo's checks (mjCBody::Compile).
void applyBounds(const MjcfModel& model, const MjcfBody& body, MassProperties& p) {
    const CompilerSettings& c = model.compiler;
    p.mass = std::max(p.mass, c.boundMass);
    for (int i = 0; i < 3; ++i) p.principalMoments[i] = std::max(p.principalMoments[i], c.boundInertia);
    if (p.mass < 0 || p.principalMoments.minCoeff() < 0)
        throw ModelError(body.where, "body '" + body.name + "': mass and inertia cannot be negative");
    const Eigen::Vector3d& I = p.principalMoments;
    if (I[0] + I[1] < I[2] || I[0] + I[2] < I[1] || I[1] + I[2] < I[0]) {
        if (!c.balanceInertia)
            throw ModelError(body.where, "body '" + body.name + "': principal moments " + formatNumber(I[0]) + ", " +
                                         formatNumber(I[1]) + ", " + formatNumber(I[2]) +
                                         " kg m^2 break A + B >= C (set the compiler's balanceinertia to even them)");
        p.principalMoments.setConstant(I.sum() / 3);
    }
}

}  // namespace

CompiledGeom compileGeom(const MjcfGeom& geom) {
    CompiledGeom c;
    c.pos = geom.pos;
    c.quat = geom.quat;
    c.size = geom.size;
    if (geom.fromto) applyFromTo(geom, c);
    if (geom.type == GeomKind::Plane && !(c.size[2] > 0)) failGeom(geom, "a plane's size[2] must be positive");
    for (int i = 0; i < getNumSizes(geom.type) && geom.type != GeomKind::Plane; ++i)
        if (!(c.size[i] > 0))
            failGeom(geom, std::string("a ") + toString(geom.type) + " needs " + std::to_string(getNumSizes(geom.type)) +
                               " positive sizes, size[" + std::to_string(i) + "] is " + std::to_string(c.size[i]));
    const double volume = calcVolume(geom.type, c.size);
    // An explicit mass on a shape without volume (a plane) leaves it massless, as MuJoCo does.
    if (geom.mass && *geom.mass == 0) return c;
    if (geom.mass && volume <= kMinValue) return c;
    c.mass = geom.mass ? *geom.mass : geom.density * volume;
    c.inertia = calcPrincipalMoments(geom.type, c.size, c.mass);
    return c;
}

Eigen::Matrix3d MassProperties::calcInertia() const {
    const Eigen::Matrix3d R = principalAxes.toRotationMatrix();
    return R * principalMoments.asDiagonal() * R.transpose();
}

MassProperties calcBodyMassProperties(const MjcfModel& model, int body) {
    const MjcfBody& b = model.bodies[static_cast<std::size_t>(body)];
    MassProperties p;
    bool defined = false;
    if (b.inertial) {
        p = fromInertial(*b.inertial);
        defined = true;
    }
    const InertiaFromGeom rule = model.compiler.inertiaFromGeom;
    if (rule == InertiaFromGeom::True || (rule == InertiaFromGeom::Auto && !b.inertial))
        defined = setFromGeoms(model, body, p) || defined;
    // Neither an inertial nor a geom: MuJoCo copies the body's own frame, relative to its parent, into the
    // inertial frame (mjCBody::Compile, "ipos undefined"), so body_ipos is the body's pos.
    if (!defined) {
        p.com = b.pos;
        p.principalAxes = b.quat;
    }
    applyBounds(model, b, p);
    return p;
}

}  // namespace sinew::mjcf
