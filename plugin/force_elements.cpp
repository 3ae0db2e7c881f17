#include "sinew/plugin/force_elements.hpp"

#include "eigen_simtk.hpp"
#include "sinew/core/force_elements.hpp"

namespace sinew {
namespace {

// OpenSim's CoordinateLimitForce on one mobility (sinew's u order is Simbody's).
class CoordinateLimitMobilityForce final : public SimTK::Force::Custom::Implementation {
public:
    explicit CoordinateLimitMobilityForce(CoordinateLimitForce limit) : limit_(std::move(limit)) {}
    void calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>&, SimTK::Vector_<SimTK::Vec3>&,
                   SimTK::Vector& mobilityForces) const override {
        mobilityForces[limit_.u] += calcCoordinateLimitForce(limit_, state.getQ()[limit_.q], state.getU()[limit_.u]);
    }
    SimTK::Real calcPotentialEnergy(const SimTK::State& state) const override {
        return calcCoordinateLimitEnergy(limit_, state.getQ()[limit_.q]);
    }

private:
    CoordinateLimitForce limit_;
};

}  // namespace

std::unique_ptr<SimTK::GeneralContactSubsystem> addForceElements(SimTK::MultibodySystem& system, SimTK::SimbodyMatterSubsystem& matter,
                      SimTK::GeneralForceSubsystem& forces, const Model& model,
                      const std::vector<SimTK::MobilizedBodyIndex>& mobilizedBodies) {
    const ForceElements& elements = model.getForceElements();
    const auto body = [&](int link) -> SimTK::MobilizedBody& {
        return link == kGround ? matter.updGround()
                               : matter.updMobilizedBody(mobilizedBodies[static_cast<std::size_t>(link)]);
    };
    const auto transform = [](const LinkFrame& frame) {
        return SimTK::Transform(toRotation(frame.R_BF), toVec3(frame.p_BF));
    };
    for (const CoordinateLimitForce& limit : elements.coordinateLimits)
        SimTK::Force::Custom(forces, new CoordinateLimitMobilityForce(limit));  // takes ownership
    for (const PointToPointSpring& spring : elements.springs)
        SimTK::Force::TwoPointLinearSpring(forces, body(spring.linkA), toVec3(spring.pointA), body(spring.linkB),
                                           toVec3(spring.pointB), spring.stiffness, spring.restLength);
    for (const BushingForce& bushing : elements.bushings) {
        SimTK::Vec6 stiffness, damping;
        for (int i = 0; i < 3; ++i) {
            stiffness[i] = bushing.rotationalStiffness[i], stiffness[i + 3] = bushing.translationalStiffness[i];
            damping[i] = bushing.rotationalDamping[i], damping[i + 3] = bushing.translationalDamping[i];
        }
        SimTK::Force::LinearBushing(forces, body(bushing.frameA.link), transform(bushing.frameA),
                                    body(bushing.frameB.link), transform(bushing.frameB), stiffness, damping);
    }
    if (elements.huntCrossley.empty()) return nullptr;
    auto subsystem = std::make_unique<SimTK::GeneralContactSubsystem>(system);  // the system adopts its guts
    SimTK::GeneralContactSubsystem& contacts = *subsystem;
    // One Simbody force per sphere/half-space pair: Simbody 3.7's HuntCrossleyForce stops at its first
    // separating contact and skips the rest of its set (docs/force-elements.md), which a set of two cannot do.
    for (const HuntCrossleyForce& force : elements.huntCrossley)
        for (const HuntCrossleyForce::Pair& pair : force.pairs) {
            const SimTK::ContactSetIndex set = contacts.createContactSet();
            SimTK::HuntCrossleyForce huntCrossley(forces, contacts, set);
            for (const int index : {pair.halfSpace, pair.sphere}) {
                const HuntCrossleySurface& surface = force.surfaces[static_cast<std::size_t>(index)];
                const ContactGeometry& geometry = elements.contactGeometry[static_cast<std::size_t>(surface.geometry)];
                const SimTK::ContactGeometry shape =
                    geometry.shape == ContactGeometry::Shape::Sphere
                        ? SimTK::ContactGeometry(SimTK::ContactGeometry::Sphere(geometry.radius))
                        : SimTK::ContactGeometry(SimTK::ContactGeometry::HalfSpace());
                contacts.addBody(set, body(geometry.frame.link), shape, transform(geometry.frame));
                huntCrossley.setBodyParameters(SimTK::ContactSurfaceIndex(contacts.getNumBodies(set) - 1),
                                               surface.stiffness, surface.dissipation, surface.staticFriction,
                                               surface.dynamicFriction, surface.viscousFriction);
            }
            huntCrossley.setTransitionVelocity(force.transitionVelocity);
        }
    return subsystem;
}

}  // namespace sinew
