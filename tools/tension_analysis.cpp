#include "sinew/tools/tension_analysis.hpp"

#include <cmath>

#include "sinew/core/body_actuator.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/inverse_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/thelen_muscle.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"

namespace sinew {
namespace {

const ThelenMuscle* findThelenMuscle(const Wire& wire) { return dynamic_cast<const ThelenMuscle*>(wire.law.get()); }

// options.maxTension, or each wire's max isometric force.
Eigen::VectorXd getWireStrengths(const Model& model, const TensionAnalysisOptions& options) {
    const int numWires = model.getNumWires();
    if (options.maxTension.size() > 0) {
        if (options.maxTension.size() != numWires)
            throw Error("tensions: " + std::to_string(options.maxTension.size()) + " maximum tensions given for " +
                        std::to_string(numWires) + " wires");
        return options.maxTension;
    }
    Eigen::VectorXd strength(numWires);
    for (int w = 0; w < numWires; ++w) {
        const Wire& wire = model.getWire(w);
        const ThelenMuscle* muscle = findThelenMuscle(wire);
        if (!muscle)
            throw Error("tensions: wire '" + wire.name + "' has force law '" + wire.lawSpec.type +
                        "', which has no max isometric force: give every wire's maximum tension");
        strength[w] = muscle->getParameters().maxIsometricForce;
    }
    return strength;
}

// A reserve's DOF or links must be the model's; a body actuator's axis must have a direction.
void checkReserve(const Model& model, const ReserveActuator& reserve) {
    const auto fail = [&](const std::string& what) { throw Error("tensions: reserve '" + reserve.name + "' " + what); };
    if (!reserve.body) {
        if (reserve.dof < 0 || reserve.dof >= model.getNumU())
            fail("acts on DOF " + std::to_string(reserve.dof) + ", expected 0 to " + std::to_string(model.getNumU() - 1));
        return;
    }
    const BodyActuator& body = *reserve.body;
    const bool pointForce = body.kind == BodyActuator::Kind::PointForce;
    for (const int link : {body.link, body.reactionLink})
        if (link < kGround || link >= model.getNumLinks())
            fail("acts on link " + std::to_string(link) + ", expected ground (-1) or 0 to " +
                 std::to_string(model.getNumLinks() - 1));
    if (pointForce && body.link == kGround) fail("pushes ground, which cannot move");
    if (!(body.axis.norm() > 0) || !body.axis.allFinite() || !body.point.allFinite())
        fail(std::string("has ") + (pointForce ? "direction" : "axis") + " (" + std::to_string(body.axis.x()) + ", " +
             std::to_string(body.axis.y()) + ", " + std::to_string(body.axis.z()) +
             ") or a point that is not finite; expected a finite, non-zero vector");
}

StaticOptimizationSettings makeStaticOptimizationSettings(const Eigen::VectorXd& maxIsometricForce,
                                                          const TensionAnalysisOptions& options) {
    StaticOptimizationSettings settings;
    settings.maxIsometricForce = maxIsometricForce;
    settings.minActivation = options.minActivation;
    settings.maxActivation = options.maxActivation;
    settings.reserves = options.reserves;
    settings.activationExponent = options.activationExponent;
    return settings;
}

}  // namespace

const char* toString(TensionMethod method) {
    switch (method) {
        case TensionMethod::Lp: return "lp";
        case TensionMethod::Qp: return "qp";
        case TensionMethod::StaticOptimization: return "so";
    }
    return "?";
}

TensionMethod parseTensionMethod(const std::string& name) {
    if (name == "lp") return TensionMethod::Lp;
    if (name == "qp") return TensionMethod::Qp;
    if (name == "so") return TensionMethod::StaticOptimization;
    throw Error("unknown tension method '" + name + "' (expected lp, qp or so)");
}

TensionAnalysis::TensionAnalysis(const Model& model, TensionAnalysisOptions options)
    : model_(model),
      options_(std::move(options)),
      data_(model),
      maxIsometricForce_(getWireStrengths(model, options_)),
      builder_(model, maxIsometricForce_, options_.problem),
      problem_(builder_.makeProblem()),
      J_(model.getNumWires(), model.getNumU()),
      forceMultiplier_(Eigen::VectorXd::Ones(model.getNumWires())),
      forcePerActivation_(maxIsometricForce_),
      reserveColumns_(Eigen::MatrixXd::Zero(model.getNumU(), static_cast<Eigen::Index>(options_.reserves.size()))) {
    const int nu = model.getNumU(), numWires = model.getNumWires();
    for (std::size_t r = 0; r < options_.reserves.size(); ++r) {
        checkReserve(model, options_.reserves[r]);
        if (!options_.reserves[r].body) reserveColumns_(options_.reserves[r].dof, static_cast<Eigen::Index>(r)) = 1;
    }
    if (numWires == 0) throw Error("tensions: model '" + model.getName() + "' has no wires");
    switch (options_.method) {
        case TensionMethod::Lp: lp_ = std::make_unique<LpSolver>(); break;
        case TensionMethod::Qp: qp_ = std::make_unique<ActiveSetSolver>(); break;
        case TensionMethod::StaticOptimization:
            if (options_.useMusclePhysiology)
                for (const Wire& wire : model.getWires())
                    if (!findThelenMuscle(wire))
                        throw Error("tensions: wire '" + wire.name + "' has force law '" + wire.lawSpec.type +
                                    "'; muscle physiology in static optimization needs thelen2003_muscle");
            so_ = std::make_unique<StaticOptimization>(makeStaticOptimizationSettings(maxIsometricForce_, options_));
            break;
    }
    frame_.tau.setZero(nu);
    frame_.tension.setZero(numWires);
    frame_.activation.setZero(numWires);
    frame_.reserveForce.setZero(static_cast<Eigen::Index>(options_.reserves.size()));
    frame_.residual.setZero(nu);
    frame_.reserve.setZero(nu);
    frame_.unactuated.assign(static_cast<std::size_t>(nu), 0);
    for (int link = 0; link < model.getNumLinks(); ++link)
        if (model.getLink(link).isVirtual && model.getJoint(link).parent == kGround) virtualLinksOnGround_.push_back(link);
    rigidMotion_.setZero(nu, 6);
    unbalanced_.setZero(nu);
    virtualLinkMotion_.resize(virtualLinksOnGround_.size());
}

void TensionAnalysis::reset() {
    if (lp_) lp_->reset();
    if (qp_) qp_->reset();
    if (so_) so_->reset();
}

// A body reserve's generalized force per unit force follows the configuration (J^T F); a DOF reserve's is
// its unit vector, set once.
void TensionAnalysis::calcReserveColumns() {
    for (std::size_t r = 0; r < options_.reserves.size(); ++r)
        if (options_.reserves[r].body)
            calcBodyActuatorGeneralizedForce(model_, data_, *options_.reserves[r].body,
                                             reserveColumns_.col(static_cast<Eigen::Index>(r)));
}

// A DOF's row of A (and, for static optimization, of the reserves' columns) is the generalized force per
// unit of each variable; a row that is zero to rounding (a floating root under internal wire forces and no
// residual actuators) cannot be distributed, so its target is set to zero and its tau reported as residual.
// A DOF of a joint on ground moves the whole body, and the virtual links hanging from ground must move
// with it for no wire to change length: wires through a virtual link reach that DOF's row (they pull the
// body but not the virtual link) although, once the virtual links' equilibrium rows hold, they cannot move
// the body as a whole. What the wires and loops do along that rigid motion of everything is what actuates
// the DOF: the largest |column . r| with r the motion's u, into rowSize. What no wire can balance there is
// r . tau: the equilibrium rows' targets (loads on virtual links, if any) move with the body.
void TensionAnalysis::judgeByRigidMotion(int rootLink, Eigen::VectorXd& rowSize) {
    const Joint& joint = model_.getJoint(rootLink);
    const Eigen::Vector3d& p_ref = data_.p_GM[static_cast<std::size_t>(rootLink)];
    const JointMotion H_root = calcJointMotion_G(joint, data_, rootLink, p_ref);
    for (std::size_t v = 0; v < virtualLinksOnGround_.size(); ++v) {
        const int link = virtualLinksOnGround_[v];
        virtualLinkMotion_[v].compute(calcJointMotion_G(model_.getJoint(link), data_, link, p_ref));
    }
    // Column c of rigidMotion_: the u of the rigid motion along mobility c; one pass over A for all of them.
    const Eigen::Index n = joint.nu;
    rigidMotion_.leftCols(n).setZero();
    for (int c = 0; c < joint.nu; ++c) {
        rigidMotion_(joint.uStart + c, c) = 1;
        for (std::size_t v = 0; v < virtualLinksOnGround_.size(); ++v) {
            const Joint& free = model_.getJoint(virtualLinksOnGround_[v]);
            rigidMotion_.block(free.uStart, c, free.nu, 1) = virtualLinkMotion_[v].solve(SpatialVector(H_root.col(c)));
        }
    }
    SpatialVector actuation = SpatialVector::Zero(), along;
    for (Eigen::Index k = 0; k < problem_.A.outerSize(); ++k) {
        along.head(n).setZero();
        for (Eigen::SparseMatrix<double>::InnerIterator it(problem_.A, k); it; ++it)
            along.head(n) += it.value() * rigidMotion_.row(it.row()).head(n).transpose();
        actuation.head(n) = actuation.head(n).cwiseMax(along.head(n).cwiseAbs());
    }
    for (int c = 0; c < joint.nu; ++c) {
        rowSize[joint.uStart + c] = actuation[c];
        unbalanced_[joint.uStart + c] = rigidMotion_.col(c).dot(frame_.tau);
    }
}

void TensionAnalysis::markUnactuated() {
    const Eigen::Index nu = problem_.getNumRows();
    Eigen::VectorXd& rowSize = frame_.reserve;  // workspace, overwritten after the solve
    rowSize.setZero();
    unbalanced_ = frame_.tau;
    for (Eigen::Index k = 0; k < problem_.A.outerSize(); ++k)
        for (Eigen::SparseMatrix<double>::InnerIterator it(problem_.A, k); it; ++it)
            rowSize[it.row()] = std::fmax(rowSize[it.row()], std::fabs(it.value()));
    if (!virtualLinksOnGround_.empty())
        for (int link = 0; link < model_.getNumLinks(); ++link) {
            const Joint& joint = model_.getJoint(link);
            if (joint.parent != kGround || model_.getLink(link).isVirtual) continue;
            judgeByRigidMotion(link, rowSize);
        }
    if (so_)
        for (Eigen::Index r = 0; r < reserveColumns_.cols(); ++r)
            for (Eigen::Index i = 0; i < nu; ++i) rowSize[i] = std::fmax(rowSize[i], std::fabs(reserveColumns_(i, r)));
    const double threshold = options_.unactuatedThreshold * rowSize.maxCoeff();
    frame_.unactuatedResidual = 0;
    for (Eigen::Index i = 0; i < nu; ++i) {
        const bool unactuated = !(rowSize[i] > threshold);
        frame_.unactuated[static_cast<std::size_t>(i)] = unactuated;
        if (unactuated) {
            frame_.unactuatedResidual += unbalanced_[i] * unbalanced_[i];
            problem_.target[i] = frame_.tau[i] - unbalanced_[i];
        }
    }
    frame_.unactuatedResidual = std::sqrt(frame_.unactuatedResidual);
}

// OpenSim's StaticOptimizationTarget::prepareToOptimize with use_muscle_physiology: the force per unit
// activation is Thelen2003Muscle::calcInextensibleTendonActiveFiberForce(s, 1): max isometric force times
// fl, fv (taken at activation 1) and cos(pennation) on a rigid tendon at the path's length and speed.
void TensionAnalysis::calcForceMultipliers() {
    if (!options_.useMusclePhysiology) return;
    calcWireSpeeds(model_, data_);
    for (int w = 0; w < model_.getNumWires(); ++w) {
        const ThelenFiberState fiber =
            findThelenMuscle(model_.getWire(w))->calcFiberState(data_.wireLength[w], data_.wireSpeed[w], 1.0);
        forceMultiplier_[w] = fiber.activeForceLength * fiber.forceVelocity * fiber.cosPennation;
    }
    forcePerActivation_ = maxIsometricForce_.cwiseProduct(forceMultiplier_);
}

const TensionFrame& TensionAnalysis::calcFrame(const Eigen::VectorXd& q, const Eigen::VectorXd& u,
                                               const Eigen::VectorXd& udot,
                                               const std::vector<SpatialVector>& appliedLinkForces) {
    TensionFrame& frame = frame_;
    calcInverseDynamics(model_, data_, q, u, udot, appliedLinkForces, frame.tau);  // kinematics at (q, u) too
    calcWirePaths(model_, data_);
    calcWireJacobian(model_, data_, J_);
    builder_.update(data_, J_, frame.tau, problem_);
    if (so_) calcReserveColumns();
    markUnactuated();

    const int numWires = model_.getNumWires();
    const DistributionResult* result = &distribution_;
    if (options_.method == TensionMethod::StaticOptimization) {
        calcForceMultipliers();
        so_->solve(problem_, forceMultiplier_, soResult_, reserveColumns_.cols() > 0 ? &reserveColumns_ : nullptr);
        result = &soResult_.distribution;
        frame.activation = soResult_.activation;
        frame.tension = soResult_.tension;
        frame.reserveForce = soResult_.reserveForce;
        frame.activeWires = 0;
        for (int w = 0; w < numWires; ++w) {
            const double lower = options_.minActivation.size() > 0 ? options_.minActivation[w] : 0.0;
            frame.activeWires += soResult_.activation[w] > lower + 1e-9;
        }
    } else {
        if (lp_) lp_->solve(problem_, distribution_);
        else qp_->solve(problem_, distribution_);
        frame.tension = distribution_.x.head(numWires);
        frame.activeWires = distribution_.activeVariables;
    }
    frame.status = result->status;
    frame.iterations = result->iterations;
    frame.usedIpopt = result->usedIpopt;
    frame.reserve = result->reserve;
    frame.residual = result->residual;
    for (Eigen::Index i = 0; i < frame.residual.size(); ++i)
        if (frame.unactuated[static_cast<std::size_t>(i)]) frame.residual[i] = frame.tau[i];
    frame.torqueError = 0.5 * frame.residual.squaredNorm();
    return frame;
}

}  // namespace sinew
