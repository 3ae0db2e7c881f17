#include "sinew/plugin/simbody_model.hpp"

#include <algorithm>

#include "eigen_simtk.hpp"
#include "sinew/core/data.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/plugin/coordinate_constraints.hpp"
#include "sinew/plugin/custom_mobilizer.hpp"
#include "sinew/plugin/force_elements.hpp"

namespace sinew {
namespace {

SimTK::Body::Rigid makeBody(const Link& link) {
    const Eigen::Matrix3d& I = link.inertia_Bcom;
    const SimTK::Inertia inertiaAboutCom(SimTK::Vec3(I(0, 0), I(1, 1), I(2, 2)), SimTK::Vec3(I(0, 1), I(0, 2), I(1, 2)));
    const SimTK::Vec3 com = toVec3(link.com_B);
    // Simbody wants the inertia about the body origin.
    return SimTK::Body::Rigid(
        SimTK::MassProperties(link.mass, com, inertiaAboutCom.shiftFromMassCenter(com, link.mass)));
}

bool isWeldedToGround(const Model& model, int link) {
    for (; link != kGround; link = model.getJoint(link).parent)
        if (model.getJoint(link).type != JointType::Weld) return false;
    return true;
}

}  // namespace

SimTK::Vector toSimTK(const Eigen::VectorXd& v) {
    SimTK::Vector out(static_cast<int>(v.size()));
    for (int i = 0; i < out.size(); ++i) out[i] = v[i];
    return out;
}

Eigen::VectorXd toEigen(const SimTK::Vector& v) {
    Eigen::VectorXd out(v.size());
    for (int i = 0; i < v.size(); ++i) out[i] = v[i];
    return out;
}

SimbodyModel::SimbodyModel(Model model, SimbodyModelOptions options)
    : model_(std::move(model)), system_(std::make_unique<SimTK::MultibodySystem>()) {
    matter_ = std::make_unique<SimTK::SimbodyMatterSubsystem>(*system_);
    forces_ = std::make_unique<SimTK::GeneralForceSubsystem>(*system_);
    if (options.gravity) SimTK::Force::UniformGravity(*forces_, *matter_, toVec3(model_.getGravity()));

    for (int i = 0; i < model_.getNumLinks(); ++i) {
        // A virtual link is massless, which a Simbody body cannot be: no mobilized body (and no q or u in
        // Simbody's state; virtual links come last, so Simbody's q and u are the head of sinew's). Its wires
        // act through the VirtualLinkWireForce below.
        if (model_.getLink(i).isVirtual) {
            mobilizedBodies_.emplace_back();
            continue;
        }
        const Joint& joint = model_.getJoint(i);
        SimTK::MobilizedBody& parent = joint.parent == kGround ? matter_->updGround()
                                                               : matter_->updMobilizedBody(mobilizedBodies_[static_cast<std::size_t>(joint.parent)]);
        const SimTK::Transform X_PF(toRotation(joint.R_PF), toVec3(joint.p_PF));
        const SimTK::Transform X_BM(toRotation(joint.R_BM), toVec3(joint.p_BM));
        const SimTK::Body::Rigid body = makeBody(model_.getLink(i));
        SimTK::MobilizedBodyIndex index;
        switch (joint.type) {
            case JointType::Free: index = SimTK::MobilizedBody::Free(parent, X_PF, body, X_BM).getMobilizedBodyIndex(); break;
            case JointType::Ball: index = SimTK::MobilizedBody::Ball(parent, X_PF, body, X_BM).getMobilizedBodyIndex(); break;
            case JointType::Pin: index = SimTK::MobilizedBody::Pin(parent, X_PF, body, X_BM).getMobilizedBodyIndex(); break;
            case JointType::Weld: index = SimTK::MobilizedBody::Weld(parent, X_PF, body, X_BM).getMobilizedBodyIndex(); break;
            case JointType::Custom:
                index = addCustomMobilizer(parent, X_PF, body, X_BM, joint, options.customJoints);
                break;
        }
        mobilizedBodies_.push_back(index);
    }

    for (const Loop& loop : model_.getLoops())
        loopConstraints_.push_back(
            SimTK::Constraint::Ball(matter_->updMobilizedBody(mobilizedBodies_[static_cast<std::size_t>(loop.linkA)]),
                                    toVec3(loop.p_A),
                                    matter_->updMobilizedBody(mobilizedBodies_[static_cast<std::size_t>(loop.linkB)]),
                                    toVec3(loop.p_B))
                .getConstraintIndex());
    for (const CoordinateCoupler& coupler : model_.getCouplers())
        addCouplerConstraint(*matter_, model_, coupler, mobilizedBodies_);
    for (int q = 0; q < model_.getNumQ(); ++q)
        if (model_.getCoordinates()[static_cast<std::size_t>(q)].locked) addLockConstraint(*matter_, model_, q, mobilizedBodies_);

    if (options.forceElements) contacts_ = addForceElements(*system_, *matter_, *forces_, model_, mobilizedBodies_);

    if (!options.hangBy.empty()) {
        const int link = model_.findLinkIndex(options.hangBy);
        if (link < 0) throw Error("--hang-by: model '" + model_.getName() + "' has no link '" + options.hangBy + "'");
        if (model_.getLink(link).isVirtual) throw Error("--hang-by: '" + options.hangBy + "' is a virtual link");
        if (!isWeldedToGround(model_, link)) {
            Data data(model_);
            calcPositionKinematics(model_, data, model_.getDefaultQ());
            const std::size_t b = static_cast<std::size_t>(link);
            const SimTK::Transform X_GB(toRotation(data.R_GB[b]), toVec3(data.p_GB[b]));
            SimTK::Constraint::Weld(matter_->updGround(), X_GB, matter_->updMobilizedBody(mobilizedBodies_[b]),
                                    SimTK::Transform());
        }
    }

    if (options.wires && model_.getNumWires() > 0) {
        wirePaths_ = &SimbodyWirePaths::adopt(*system_, *matter_, model_, mobilizedBodies_);
        std::vector<char> throughVirtualLink(static_cast<std::size_t>(model_.getNumWires()), 0);
        const auto& links = model_.getLinks();
        if (std::any_of(links.begin(), links.end(), [](const Link& link) { return link.isVirtual; })) {
            auto* implementation = new VirtualLinkWireForce(*wirePaths_);
            SimTK::Force::Custom(*forces_, implementation);  // takes ownership
            virtualLinkWireForce_ = implementation;
            for (int w : wirePaths_->getEquilibrium().wires) throughVirtualLink[static_cast<std::size_t>(w)] = 1;
        }
        for (int w = 0; w < model_.getNumWires(); ++w) {
            if (throughVirtualLink[static_cast<std::size_t>(w)]) {
                wireImplementations_.push_back(nullptr);
                wireForces_.emplace_back();
                continue;
            }
            auto* implementation = new WireForce(*wirePaths_, w);
            wireImplementations_.push_back(implementation);
            wireForces_.push_back(SimTK::Force::Custom(*forces_, implementation).getForceIndex());  // takes ownership
        }
    }
    system_->realizeTopology();
}

const SimTK::MobilizedBody& SimbodyModel::getMobilizedBody(int link) const {
    if (model_.getLink(link).isVirtual)
        throw Error("link '" + model_.getLink(link).name + "' is a virtual link, which has no mobilized body");
    return matter_->getMobilizedBody(mobilizedBodies_.at(static_cast<std::size_t>(link)));
}

const SimTK::Constraint::Ball& SimbodyModel::getLoopConstraint(int loop) const {
    return SimTK::Constraint::Ball::downcast(matter_->getConstraint(loopConstraints_.at(static_cast<std::size_t>(loop))));
}

const SimTK::Force& SimbodyModel::getWireForceElement(int wire) const {
    getWireForce(wire);  // refuses a wire through a virtual link
    return forces_->getForce(wireForces_.at(static_cast<std::size_t>(wire)));
}

const WireForce& SimbodyModel::getWireForce(int wire) const {
    const WireForce* implementation = wireImplementations_.at(static_cast<std::size_t>(wire));
    if (!implementation)
        throw Error("wire '" + model_.getWire(wire).name + "' passes through a virtual link; its force is in "
                    "getVirtualLinkWireForce()");
    return *implementation;
}

Eigen::VectorXd SimbodyModel::calcWireTensions(const SimTK::State& state) const {
    if (!wirePaths_) return Eigen::VectorXd::Zero(model_.getNumWires());
    wirePaths_->realizeTensions(state);
    return wirePaths_->getTensions();
}

void SimbodyModel::calcCoordinates(const SimTK::State& state, Eigen::VectorXd& q, Eigen::VectorXd& u) const {
    q = model_.getDefaultQ();
    u = Eigen::VectorXd::Zero(model_.getNumU());
    q.head(state.getNQ()) = toEigen(state.getQ());
    u.head(state.getNU()) = toEigen(state.getU());
    if (virtualLinkWireForce_) {
        virtualLinkWireForce_->solve(state);
        getVirtualLinkCoordinates(model_, virtualLinkWireForce_->getData(), virtualLinkWireForce_->getEquilibrium(), q,
                                  u);
    }
}

SimTK::State SimbodyModel::makeState(const Eigen::VectorXd& q, const Eigen::VectorXd& u, SimTK::Stage stage) const {
    if (q.size() != model_.getNumQ() || u.size() != model_.getNumU())
        throw Error("state of model '" + model_.getName() + "' needs " + std::to_string(model_.getNumQ()) + " q and " +
                    std::to_string(model_.getNumU()) + " u, got " + std::to_string(q.size()) + " and " +
                    std::to_string(u.size()));
    SimTK::State state = system_->getDefaultState();
    state.updQ() = toSimTK(q.head(state.getNQ()));
    state.updU() = toSimTK(u.head(state.getNU()));
    system_->realize(state, stage);
    return state;
}

SimTK::State SimbodyModel::makeDefaultState(double accuracy) const {
    SimTK::State state = makeState(model_.getDefaultQ(), Eigen::VectorXd::Zero(model_.getNumU()), SimTK::Stage::Position);
    system_->project(state, accuracy);
    system_->realize(state, SimTK::Stage::Velocity);
    return state;
}

}  // namespace sinew
