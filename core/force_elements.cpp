#include "sinew/core/force_elements.hpp"

#include <algorithm>
#include <cmath>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"

namespace sinew {
namespace {

// SimTK::Function::Step from y0 at x0 to y1 at x1: 10 t^3 - 15 t^4 + 6 t^5 in between.
double step(double y0, double y1, double x0, double x1, double x) {
    if (x <= x0) return y0;
    if (x >= x1) return y1;
    const double t = (x - x0) / (x1 - x0);
    return y0 + (y1 - y0) * t * t * t * (10 - 15 * t + 6 * t * t);
}

struct FramePose {
    Eigen::Matrix3d R_GF;
    Eigen::Vector3d p_GF;
};

FramePose locate(const Data& data, const LinkFrame& frame) {
    if (frame.link == kGround) return {frame.R_BF, frame.p_BF};
    const std::size_t b = static_cast<std::size_t>(frame.link);
    return {data.R_GB[b] * frame.R_BF, data.p_GB[b] + data.R_GB[b] * frame.p_BF};
}

Eigen::Vector3d locatePoint(const Data& data, int link, const Eigen::Vector3d& p_B) {
    if (link == kGround) return p_B;
    const std::size_t b = static_cast<std::size_t>(link);
    return data.p_GB[b] + data.R_GB[b] * p_B;
}

// Velocity in ground of the point of `link` now at p_G.
Eigen::Vector3d calcPointVelocity(const Data& data, int link, const Eigen::Vector3d& p_G) {
    if (link == kGround) return Eigen::Vector3d::Zero();
    const std::size_t b = static_cast<std::size_t>(link);
    return data.v_GB[b] + data.w_GB[b].cross(p_G - data.p_GB[b]);
}

// A force f (ground axes) at p_G, and a moment m, on `link` as its spatial force about its origin.
void applyForce(const Data& data, int link, const Eigen::Vector3d& p_G, const Eigen::Vector3d& f,
                const Eigen::Vector3d& m, std::vector<SpatialVector>& linkForces) {
    if (link == kGround) return;
    const std::size_t b = static_cast<std::size_t>(link);
    linkForces[b].head<3>() += m + (p_G - data.p_GB[b]).cross(f);
    linkForces[b].tail<3>() += f;
}

void addSpringForces(const Data& data, const PointToPointSpring& spring, std::vector<SpatialVector>& linkForces) {
    const Eigen::Vector3d a = locatePoint(data, spring.linkA, spring.pointA);
    const Eigen::Vector3d b = locatePoint(data, spring.linkB, spring.pointB);
    const double distance = (b - a).norm();
    if (distance == 0) return;  // no direction: Simbody's spring applies nothing there either
    const Eigen::Vector3d f = spring.stiffness * (distance - spring.restLength) * (b - a) / distance;
    applyForce(data, spring.linkA, a, f, Eigen::Vector3d::Zero(), linkForces);
    applyForce(data, spring.linkB, b, -f, Eigen::Vector3d::Zero(), linkForces);
}

// Simbody's N for body-fixed X-Y-Z angles: qdot = N w_M, w_M the angular velocity in the moving frame.
Eigen::Matrix3d calcXYZRateMatrix(const Eigen::Vector3d& q) {
    const double s1 = std::sin(q[1]), c1 = std::cos(q[1]), s2 = std::sin(q[2]), c2 = std::cos(q[2]);
    Eigen::Matrix3d N;
    N << c2, -s2, 0, c1 * s2, c1 * c2, 0, -s1 * c2, s1 * s2, c1;
    return N / c1;
}

void addBushingForces(const Data& data, const BushingForce& bushing, std::vector<SpatialVector>& linkForces) {
    const FramePose A = locate(data, bushing.frameA), B = locate(data, bushing.frameB);
    const Eigen::Matrix3d R_AB = A.R_GF.transpose() * B.R_GF;
    const Eigen::Vector3d p_AB_G = B.p_GF - A.p_GF;
    const Eigen::Vector3d angles = calcBodyFixedXYZ(R_AB), p_AB = A.R_GF.transpose() * p_AB_G;
    // B's velocity in A, the derivative taken in A.
    const Eigen::Vector3d w_A = bushing.frameA.link == kGround ? Eigen::Vector3d::Zero()
                                                               : data.w_GB[static_cast<std::size_t>(bushing.frameA.link)];
    const Eigen::Vector3d w_B = bushing.frameB.link == kGround ? Eigen::Vector3d::Zero()
                                                               : data.w_GB[static_cast<std::size_t>(bushing.frameB.link)];
    const Eigen::Vector3d v_AB_G = calcPointVelocity(data, bushing.frameB.link, B.p_GF) -
                                   calcPointVelocity(data, bushing.frameA.link, A.p_GF) - w_A.cross(p_AB_G);
    const Eigen::Matrix3d N = calcXYZRateMatrix(angles);
    const Eigen::Vector3d angleRates = N * (B.R_GF.transpose() * (w_B - w_A));
    const Eigen::Vector3d translationRates = A.R_GF.transpose() * v_AB_G;
    const Eigen::Vector3d fAngles = -(bushing.rotationalStiffness.cwiseProduct(angles) +
                                      bushing.rotationalDamping.cwiseProduct(angleRates));
    const Eigen::Vector3d fTranslation = -(bushing.translationalStiffness.cwiseProduct(p_AB) +
                                           bushing.translationalDamping.cwiseProduct(translationRates));
    // The angles' generalized forces as a moment on B (moment = N^T f in B's axes), the translation's as a
    // force at B's origin; -both on A, at the same place.
    const Eigen::Vector3d m_G = B.R_GF * (N.transpose() * fAngles);
    const Eigen::Vector3d f_G = A.R_GF * fTranslation;
    applyForce(data, bushing.frameB.link, B.p_GF, f_G, m_G, linkForces);
    applyForce(data, bushing.frameA.link, B.p_GF, -f_G, -m_G, linkForces);
}

double calcBushingEnergy(const Data& data, const BushingForce& bushing) {
    const FramePose A = locate(data, bushing.frameA), B = locate(data, bushing.frameB);
    const Eigen::Vector3d angles = calcBodyFixedXYZ(A.R_GF.transpose() * B.R_GF);
    const Eigen::Vector3d p_AB = A.R_GF.transpose() * (B.p_GF - A.p_GF);
    return 0.5 * (bushing.rotationalStiffness.dot(angles.cwiseAbs2()) +
                  bushing.translationalStiffness.dot(p_AB.cwiseAbs2()));
}

// One sphere dipping into a half-space: depth, the contact point and the outward normal, in ground.
struct SphereContact {
    double depth = 0;
    Eigen::Vector3d point, normal;
};

bool findSphereContact(const Data& data, const ContactGeometry& halfSpace, const ContactGeometry& sphere,
                       SphereContact& contact) {
    const FramePose H = locate(data, halfSpace.frame);
    const Eigen::Vector3d centre_G = locate(data, sphere.frame).p_GF;
    const Eigen::Vector3d centre_H = H.R_GF.transpose() * (centre_G - H.p_GF);
    contact.depth = centre_H.x() + sphere.radius;
    if (contact.depth <= 0) return false;
    // Simbody's contact point: halfway between the surface and the sphere's deepest point.
    contact.point = H.p_GF + H.R_GF * Eigen::Vector3d(0.5 * contact.depth, centre_H.y(), centre_H.z());
    contact.normal = -H.R_GF.col(0);
    return true;
}

// Simbody's pairing of two surfaces' materials (HuntCrossleyForceImpl::calcForce), each stiffness taken to
// the power 2/3 as HuntCrossleyForce::setBodyParameters stores it; `shareOfA` is a's share of the overlap's
// shift (surface 1's s1).
struct PairMaterial {
    double stiffness, dissipation, staticFriction, dynamicFriction, viscousFriction, shareOfA;
};
PairMaterial combine(const HuntCrossleySurface& a, const HuntCrossleySurface& b) {
    const auto harmonic = [](double x, double y) { return x == 0 && y == 0 ? 0.0 : 2 * x * y / (x + y); };
    const double ka = std::cbrt(a.stiffness * a.stiffness), kb = std::cbrt(b.stiffness * b.stiffness);
    const double s1 = kb / (ka + kb);
    return {ka * s1,
            a.dissipation * s1 + b.dissipation * (1 - s1),
            harmonic(a.staticFriction, b.staticFriction),
            harmonic(a.dynamicFriction, b.dynamicFriction),
            harmonic(a.viscousFriction, b.viscousFriction),
            s1};
}

// Calls visit(halfSpaceSurface, sphereSurface, sphere, contact) for every touching pair of `force`.
template <class Visit>
void forEachContact(const Model& model, const Data& data, const HuntCrossleyForce& force, Visit visit) {
    const std::vector<ContactGeometry>& geometry = model.getForceElements().contactGeometry;
    for (const HuntCrossleyForce::Pair& pair : force.pairs) {
        const HuntCrossleySurface& h = force.surfaces[static_cast<std::size_t>(pair.halfSpace)];
        const HuntCrossleySurface& s = force.surfaces[static_cast<std::size_t>(pair.sphere)];
        const ContactGeometry& sphere = geometry[static_cast<std::size_t>(s.geometry)];
        SphereContact contact;
        if (findSphereContact(data, geometry[static_cast<std::size_t>(h.geometry)], sphere, contact))
            visit(h, s, sphere, contact);
    }
}

void addContactForces(const Model& model, const Data& data, const HuntCrossleyForce& force,
                      std::vector<SpatialVector>& linkForces) {
    const std::vector<ContactGeometry>& geometry = model.getForceElements().contactGeometry;
    forEachContact(model, data, force, [&](const HuntCrossleySurface& h, const HuntCrossleySurface& s,
                                           const ContactGeometry& sphere, const SphereContact& contact) {
        const PairMaterial m = combine(h, s);
        const int halfSpaceLink = geometry[static_cast<std::size_t>(h.geometry)].frame.link;
        const double x = contact.depth;
        // The stiffer surface yields less: the force acts nearer its side.
        const Eigen::Vector3d point = contact.point + x * (0.5 - m.shareOfA) * contact.normal;
        const double hertz = 4.0 / 3.0 * m.stiffness * x * std::sqrt(sphere.radius * m.stiffness * x);
        const Eigen::Vector3d v = calcPointVelocity(data, halfSpaceLink, point) -
                                  calcPointVelocity(data, sphere.frame.link, point);
        const double normalSpeed = v.dot(contact.normal);
        const double f = hertz * (1 + 1.5 * m.dissipation * normalSpeed);
        // A separating contact whose damping outweighs its spring pulls nothing. (Simbody 3.7 stops at the
        // first such contact and skips the rest of its force's contacts: docs/force-elements.md.)
        if (f <= 0) return;
        Eigen::Vector3d onSphere = f * contact.normal;
        const Eigen::Vector3d slip = v - normalSpeed * contact.normal;
        const double slipSpeed = slip.norm();
        if (slipSpeed != 0) {
            const double r = slipSpeed / force.transitionVelocity;
            const double friction =
                f * (std::min(r, 1.0) * (m.dynamicFriction + 2 * (m.staticFriction - m.dynamicFriction) / (1 + r * r)) +
                     m.viscousFriction * slipSpeed);
            onSphere += friction * slip / slipSpeed;
        }
        applyForce(data, sphere.frame.link, point, onSphere, Eigen::Vector3d::Zero(), linkForces);
        applyForce(data, halfSpaceLink, point, -onSphere, Eigen::Vector3d::Zero(), linkForces);
    });
}

double calcContactEnergy(const Model& model, const Data& data, const HuntCrossleyForce& force) {
    double energy = 0;
    forEachContact(model, data, force, [&](const HuntCrossleySurface& h, const HuntCrossleySurface& s,
                                           const ContactGeometry& sphere, const SphereContact& contact) {
        const double k = combine(h, s).stiffness, x = contact.depth;
        energy += 0.4 * (4.0 / 3.0 * k * x * std::sqrt(sphere.radius * k * x)) * x;
    });
    return energy;
}

}  // namespace

Eigen::Vector3d calcBodyFixedXYZ(const Eigen::Matrix3d& R) {
    return {std::atan2(-R(1, 2), R(2, 2)), std::atan2(R(0, 2), std::hypot(R(1, 2), R(2, 2))),
            std::atan2(-R(0, 1), R(0, 0))};
}

double calcCoordinateLimitForce(const CoordinateLimitForce& limit, double q, double qdot) {
    const double kUpper = step(0, limit.upperStiffness, limit.upperLimit, limit.upperLimit + limit.transition, q);
    const double kLower = step(limit.lowerStiffness, 0, limit.lowerLimit - limit.transition, limit.lowerLimit, q);
    // The damping grows with the stiffness's share of its full value (OpenSim divides by the stiffness,
    // which a zero stiffness turns into NaN; here that side adds no damping).
    const double share = (limit.upperStiffness > 0 ? kUpper / limit.upperStiffness : 0) +
                         (limit.lowerStiffness > 0 ? kLower / limit.lowerStiffness : 0);
    return -kUpper * (q - limit.upperLimit) + kLower * (limit.lowerLimit - q) - limit.damping * share * qdot;
}

double calcCoordinateLimitEnergy(const CoordinateLimitForce& limit, double q) {
    double k = 0, delta = 0;
    if (q > limit.upperLimit) k = limit.upperStiffness, delta = q - limit.upperLimit;
    else if (q < limit.lowerLimit) k = limit.lowerStiffness, delta = limit.lowerLimit - q;
    else return 0;
    const double t = limit.transition;
    if (delta >= t) return k * (-2.0 / 14.0 * t * t + 0.5 * delta * delta);
    const double x = delta / t;
    return k * x * x * x * (2 - 2.5 * x + 6.0 / 7.0 * x * x) * delta * delta;
}

void addForceElementForces(const Model& model, const Data& data, std::vector<SpatialVector>& linkForces,
                           Eigen::Ref<Eigen::VectorXd> tau) {
    const ForceElements& elements = model.getForceElements();
    for (const CoordinateLimitForce& limit : elements.coordinateLimits)
        tau[limit.u] += calcCoordinateLimitForce(limit, data.q[limit.q], data.u[limit.u]);
    for (const PointToPointSpring& spring : elements.springs) addSpringForces(data, spring, linkForces);
    for (const BushingForce& bushing : elements.bushings) addBushingForces(data, bushing, linkForces);
    for (const HuntCrossleyForce& force : elements.huntCrossley) addContactForces(model, data, force, linkForces);
}

double calcForceElementPotentialEnergy(const Model& model, const Data& data) {
    const ForceElements& elements = model.getForceElements();
    double energy = 0;
    for (const CoordinateLimitForce& limit : elements.coordinateLimits)
        energy += calcCoordinateLimitEnergy(limit, data.q[limit.q]);
    for (const PointToPointSpring& spring : elements.springs) {
        const double stretch = (locatePoint(data, spring.linkB, spring.pointB) -
                                locatePoint(data, spring.linkA, spring.pointA)).norm() - spring.restLength;
        energy += 0.5 * spring.stiffness * stretch * stretch;
    }
    for (const BushingForce& bushing : elements.bushings) energy += calcBushingEnergy(data, bushing);
    for (const HuntCrossleyForce& force : elements.huntCrossley) energy += calcContactEnergy(model, data, force);
    return energy;
}

}  // namespace sinew
