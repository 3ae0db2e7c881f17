#include "sinew/tools/inverse_kinematics.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "sinew/core/coordinate_coupler.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/virtual_link_equilibrium.hpp"
#include "sinew/core/wire_path.hpp"

namespace sinew {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Weight of the loops' gap (m) in the merit, against the tasks' cost (weight x m^2), beyond the largest
// multiplier: an exact penalty, so that a step that opens a loop is never bought by a better fit. Small
// otherwise, since every trial is closed again to roundoff before it is judged.
constexpr double kLoopMerit = 1;
constexpr int kActiveSetPasses = 8;
constexpr int kLoopClosingIterations = 6;
constexpr int kCurvatureRefreshIterations = 5;
constexpr double kClosedGap = 1e-15;  // m: roundoff on a body's size

bool hasScalarSpeed(const Joint& joint) { return joint.nq == joint.nu; }

// The links whose joints move any of `links` (each of them and its ancestors, ground excepted), in the
// model's order: the joint motions a Jacobian of points on `links` reads.
std::vector<int> findJointsMoving(const Model& model, const std::vector<int>& links) {
    std::vector<char> moves(static_cast<std::size_t>(model.getNumLinks()), 0);
    for (int link : links)
        for (int i = link; i != kGround && !moves[static_cast<std::size_t>(i)]; i = model.getJoint(i).parent)
            moves[static_cast<std::size_t>(i)] = 1;
    std::vector<int> found;
    for (int i = 0; i < model.getNumLinks(); ++i)
        if (moves[static_cast<std::size_t>(i)]) found.push_back(i);
    return found;
}

// d(theta)/d(delta) for exp(theta') = exp(delta) exp(theta): the inverse of SO(3)'s left Jacobian (Barfoot,
// State Estimation for Robotics, eq. 7.82). Exact, so that a fit that cannot reach its targets still stops
// at the true optimum of its cost.
Eigen::Matrix3d calcInverseLeftJacobian(const Eigen::Vector3d& theta) {
    const double angle = theta.norm();
    Eigen::Matrix3d skew;
    skew << 0, -theta.z(), theta.y(), theta.z(), 0, -theta.x(), -theta.y(), theta.x(), 0;
    const double c = angle < 1e-6 ? 1.0 / 12 : (1 / (angle * angle) - (1 + std::cos(angle)) / (2 * angle * std::sin(angle)));
    return Eigen::Matrix3d::Identity() - 0.5 * skew + c * skew * skew;
}

// M += sign A^T A for a symmetric M, by the lower half, mirrored: half the products of the full one.
void addGaussNewtonHessian(Eigen::MatrixXd& M, const Eigen::MatrixXd& A, double sign) {
    M.selfadjointView<Eigen::Lower>().rankUpdate(A.transpose(), sign);
    M.triangularView<Eigen::StrictlyUpper>() = M.transpose();
}

Eigen::Vector3d calcRotationVector(const Eigen::Matrix3d& R) {
    const Eigen::AngleAxisd rotation(R);
    return rotation.angle() * rotation.axis();
}

}  // namespace

InverseKinematicsSolver::InverseKinematicsSolver(const Model& model, std::vector<Marker> markers,
                                                 std::vector<MarkerTask> markerTasks,
                                                 std::vector<CoordinateTask> coordinateTasks,
                                                 InverseKinematicsOptions options,
                                                 std::vector<OrientationTask> orientationTasks)
    : model_(model),
      markers_(std::move(markers)),
      markerTasks_(std::move(markerTasks)),
      coordinateTasks_(std::move(coordinateTasks)),
      options_(options),
      orientationTasks_(std::move(orientationTasks)),
      data_(model),
      equilibrium_(model) {
    auto checkWeight = [](double weight, const std::string& what) {
        if (!std::isfinite(weight) || weight < 0)
            throw Error(what + ": weight must be finite and >= 0, got " + std::to_string(weight));
    };
    for (const MarkerTask& task : markerTasks_) {
        checkWeight(task.weight, "marker task '" + task.marker + "'");
        int found = -1;
        for (std::size_t m = 0; m < markers_.size(); ++m)
            if (markers_[m].name == task.marker) found = static_cast<int>(m);
        if (found < 0) throw Error("marker task '" + task.marker + "': the model has no such marker");
        taskMarker_.push_back(found);
    }
    for (const CoordinateTask& task : coordinateTasks_) {
        checkWeight(task.weight, "coordinate task '" + task.coordinate + "'");
        const int q = model.findCoordinateIndex(task.coordinate);
        if (q == Model::kNotFound) throw Error("coordinate task '" + task.coordinate + "': the model has no such coordinate");
        const Joint& joint = model.getJoint(model.getCoordinates()[static_cast<std::size_t>(q)].joint);
        if (!hasScalarSpeed(joint))
            throw Error("coordinate task '" + task.coordinate + "' is part of " + toString(joint.type) + " joint '" +
                        joint.name + "'s quaternion; coordinate tasks take pin and custom coordinates");
        taskCoordinate_.push_back(q);
    }
    for (const OrientationTask& task : orientationTasks_) {
        checkWeight(task.weight, "orientation task on '" + task.link + "'");
        const int link = model.findLinkIndex(task.link);
        if (link < 0) throw Error("orientation task: the model has no link '" + task.link + "'");
        taskLink_.push_back(link);
    }
    const int nu = model.getNumU();
    freeColumn_.assign(static_cast<std::size_t>(nu), -1);
    couplerOfU_.assign(static_cast<std::size_t>(nu), -1);
    for (std::size_t k = 0; k < model.getCouplers().size(); ++k)
        couplerOfU_[static_cast<std::size_t>(model.getCouplers()[k].dependentU)] = static_cast<int>(k);
    jointOfU_.resize(static_cast<std::size_t>(nu));
    for (int i = 0; i < model.getNumLinks(); ++i)
        for (int k = 0; k < model.getJoint(i).nu; ++k) jointOfU_[static_cast<std::size_t>(model.getJoint(i).uStart + k)] = i;
    for (int i = 0; i < model.getNumLinks(); ++i) {
        if (model.getLink(i).isVirtual) continue;  // massless wire nodes: no marker sees them
        const Joint& joint = model.getJoint(i);
        for (int k = 0; k < joint.nu; ++k) {
            const int u = joint.uStart + k;
            if (couplerOfU_[static_cast<std::size_t>(u)] >= 0) continue;
            if (hasScalarSpeed(joint)) {
                const Coordinate& c = model.getCoordinates()[static_cast<std::size_t>(joint.qStart + k)];
                if (c.locked) continue;
                if (c.clamped && (std::isfinite(c.rangeMin) || std::isfinite(c.rangeMax)))
                    boundedColumns_.push_back({numFree_, joint.qStart + k});
            }
            freeColumn_[static_cast<std::size_t>(u)] = numFree_++;
            columnLink_.push_back(i);
        }
    }
    childLinks_.resize(static_cast<std::size_t>(model.getNumLinks()));
    for (int i = 0; i < model.getNumLinks(); ++i)
        if (model.getJoint(i).parent != kGround) childLinks_[static_cast<std::size_t>(model.getJoint(i).parent)].push_back(i);
    const Eigen::Index rows = 3 * static_cast<Eigen::Index>(markerTasks_.size()) +
                              static_cast<Eigen::Index>(coordinateTasks_.size()) +
                              3 * static_cast<Eigen::Index>(orientationTasks_.size());
    r_.resize(rows);
    A_.resize(rows, numFree_);
    c_.resize(3 * static_cast<Eigen::Index>(model.getLoops().size()));
    G_.resize(c_.size(), numFree_);
    markerErrors_.resize(static_cast<Eigen::Index>(markerTasks_.size()));
    jointMotion_G_.resize(static_cast<std::size_t>(model.getNumLinks()));
    curvature_.setZero(numFree_, numFree_);
    observedIndex_.assign(static_cast<std::size_t>(numFree_), -1);
    orientationErrors_.resize(static_cast<Eigen::Index>(orientationTasks_.size()));
    std::vector<int> loopLinks;
    for (const Loop& loop : model.getLoops()) loopLinks.insert(loopLinks.end(), {loop.linkA, loop.linkB});
    std::vector<int> targetLinks = loopLinks;
    for (const int m : taskMarker_) targetLinks.push_back(markers_[static_cast<std::size_t>(m)].link);
    targetLinks.insert(targetLinks.end(), taskLink_.begin(), taskLink_.end());
    jacobianLinks_ = findJointsMoving(model, targetLinks);
    loopChainLinks_ = findJointsMoving(model, loopLinks);
    // data_.q is the pose of the last evaluation; a new Data holds the default q without its kinematics.
    calcPositionKinematics(model, data_, model.getDefaultQ());
}

// Where a speed u's effect goes among the free unknowns, and by what factor: itself for a free speed, the
// independent coordinate through the coupler's slope for a dependent one (q_dep = s f(q_ind)), nowhere
// (-1) for a locked one or a virtual link's.
std::pair<int, double> InverseKinematicsSolver::findFreeColumn(int u) const {
    const int free = freeColumn_[static_cast<std::size_t>(u)];
    if (free >= 0) return {free, 1};
    const int k = couplerOfU_[static_cast<std::size_t>(u)];
    if (k < 0) return {-1, 0};
    const CoordinateCoupler& coupler = model_.getCouplers()[static_cast<std::size_t>(k)];
    const int independent = freeColumn_[static_cast<std::size_t>(coupler.independentU)];
    if (independent < 0) return {-1, 0};
    return {independent, coupler.scaleFactor * coupler.function.calcDerivative(data_.q[coupler.independentQ], 1)};
}

void InverseKinematicsSolver::calcJointMotions(const std::vector<int>& links) {
    for (const int i : links)
        jointMotion_G_[static_cast<std::size_t>(i)] = calcJointMotion_G(model_.getJoint(i), data_, i, data_.p_GM[static_cast<std::size_t>(i)]);
}

// visit(col, d(p_G)/d(unknown col)) for a point p_G fixed on `link`, or visit(col, d(w_GB)/d(unknown col))
// for its angular velocity: each joint from the link to the root moves it, by its twist (about the joint
// centre, shifted to the point).
template <bool angular, class Visit>
void InverseKinematicsSolver::visitJacobianColumns(int link, const Eigen::Vector3d& p_G, Visit&& visit) const {
    for (int i = link; i != kGround; i = model_.getJoint(i).parent) {
        const Joint& joint = model_.getJoint(i);
        const JointMotion& H_G = jointMotion_G_[static_cast<std::size_t>(i)];
        const Eigen::Vector3d arm = p_G - data_.p_GM[static_cast<std::size_t>(i)];
        for (int k = 0; k < joint.nu; ++k) {
            const auto [col, factor] = findFreeColumn(joint.uStart + k);
            if (col < 0) continue;
            if constexpr (angular)
                visit(col, factor * H_G.col(k).head<3>());
            else
                visit(col, factor * (H_G.col(k).tail<3>() + H_G.col(k).head<3>().cross(arm)));
        }
    }
}

void InverseKinematicsSolver::addPointJacobian(int link, const Eigen::Vector3d& p_G, double scale,
                                               Eigen::Ref<Eigen::MatrixXd> rows) const {
    visitJacobianColumns<false>(link, p_G, [&](int col, const Eigen::Vector3d& dp) { rows.col(col) += scale * dp; });
}

void InverseKinematicsSolver::addAngularJacobian(int link, const Eigen::Matrix3d& scale_G, Eigen::Ref<Eigen::MatrixXd> rows) const {
    visitJacobianColumns<true>(link, Eigen::Vector3d::Zero(), [&](int col, const Eigen::Vector3d& dw) { rows.col(col) += scale_G * dw; });
}

// gradient += (d(p_G)/du)^T force: A^T r for a point's rows without forming them.
void InverseKinematicsSolver::addPointGradient(int link, const Eigen::Vector3d& p_G, const Eigen::Vector3d& force,
                                               Eigen::VectorXd& gradient) const {
    if (link == kGround) return;
    visitJacobianColumns<false>(link, p_G, [&](int col, const Eigen::Vector3d& dp) { gradient[col] += dp.dot(force); });
}

// Per task kind: its residual rows at the pose in data_, their Jacobian rows, and their share A^T r of the
// gradient without forming those rows (the curvature's differences).

// Rows sqrt(w) theta, theta the rotation vector of R_GF R_target^T (the error, in G); d(theta)/dt =
// J_l(theta)^-1 w_GB.
bool InverseKinematicsSolver::evaluateOrientation(std::size_t t, const InverseKinematicsTargets& targets,
                                                  Eigen::Ref<Eigen::VectorXd> r) {
    const Eigen::Matrix3d& R_target = targets.orientations[t];
    if (!R_target.allFinite()) {
        r.setZero();
        orientationErrors_[static_cast<Eigen::Index>(t)] = kNaN;
        return false;
    }
    const std::size_t b = static_cast<std::size_t>(taskLink_[t]);
    const Eigen::Vector3d theta = calcRotationVector(data_.R_GB[b] * orientationTasks_[t].R_BF * R_target.transpose());
    r = std::sqrt(orientationTasks_[t].weight) * theta;
    orientationErrors_[static_cast<Eigen::Index>(t)] = theta.norm();
    return true;
}

// w J_l(theta)^-1, the rows' factor on the link's angular velocity; theta from the residual r (0 for w = 0).
Eigen::Matrix3d InverseKinematicsSolver::calcOrientationScale(std::size_t t, const Eigen::Vector3d& r) const {
    const double w = std::sqrt(orientationTasks_[t].weight);
    return w > 0 ? Eigen::Matrix3d(w * calcInverseLeftJacobian(r / w)) : Eigen::Matrix3d::Zero();
}

void InverseKinematicsSolver::addOrientationJacobian(std::size_t t, const Eigen::Vector3d& r, Eigen::Ref<Eigen::MatrixXd> A) const {
    addAngularJacobian(taskLink_[t], calcOrientationScale(t, r), A);
}

void InverseKinematicsSolver::addOrientationGradient(std::size_t t, const Eigen::Vector3d& r, Eigen::VectorXd& gradient) const {
    const Eigen::Vector3d moment = calcOrientationScale(t, r).transpose() * r;
    visitJacobianColumns<true>(taskLink_[t], Eigen::Vector3d::Zero(),
                               [&](int col, const Eigen::Vector3d& dw) { gradient[col] += dw.dot(moment); });
}

bool InverseKinematicsSolver::evaluateMarker(std::size_t t, const InverseKinematicsTargets& targets, Eigen::Ref<Eigen::VectorXd> r) {
    const Eigen::Vector3d observed = targets.markers.col(static_cast<Eigen::Index>(t));
    if (!observed.allFinite()) {
        r.setZero();
        markerErrors_[static_cast<Eigen::Index>(t)] = kNaN;
        return false;
    }
    const Eigen::Vector3d p_G = calcMarkerLocation_G(data_, markers_[static_cast<std::size_t>(taskMarker_[t])]);
    r = std::sqrt(markerTasks_[t].weight) * (p_G - observed);
    markerErrors_[static_cast<Eigen::Index>(t)] = (p_G - observed).norm();
    return true;
}

void InverseKinematicsSolver::addMarkerJacobian(std::size_t t, Eigen::Ref<Eigen::MatrixXd> A) const {
    const Marker& marker = markers_[static_cast<std::size_t>(taskMarker_[t])];
    if (marker.link != kGround) addPointJacobian(marker.link, calcMarkerLocation_G(data_, marker), std::sqrt(markerTasks_[t].weight), A);
}

void InverseKinematicsSolver::addMarkerGradient(std::size_t t, const Eigen::Vector3d& r, Eigen::VectorXd& gradient) const {
    const Marker& marker = markers_[static_cast<std::size_t>(taskMarker_[t])];
    addPointGradient(marker.link, calcMarkerLocation_G(data_, marker), std::sqrt(markerTasks_[t].weight) * r, gradient);
}

void InverseKinematicsSolver::evaluateCoordinates(const InverseKinematicsTargets& targets, const Eigen::VectorXd& q,
                                                  Eigen::Ref<Eigen::VectorXd> r, Eigen::Ref<Eigen::MatrixXd> A,
                                                  bool withJacobian) {
    if (withJacobian) A.setZero();
    for (std::size_t t = 0; t < coordinateTasks_.size(); ++t) {
        const Eigen::Index row = static_cast<Eigen::Index>(t);
        const int qi = taskCoordinate_[t];
        const double w = std::sqrt(coordinateTasks_[t].weight);
        r[row] = w * (q[qi] - targets.coordinates[row]);
        if (!withJacobian) continue;
        const Coordinate& c = model_.getCoordinates()[static_cast<std::size_t>(qi)];
        const Joint& joint = model_.getJoint(c.joint);
        const auto [col, factor] = findFreeColumn(joint.uStart + (qi - joint.qStart));
        if (col >= 0) A(row, col) += w * factor;
    }
}

// A loop's two points in G, on linkA and linkB.
std::pair<Eigen::Vector3d, Eigen::Vector3d> InverseKinematicsSolver::calcLoopPoints(std::size_t l) const {
    const Loop& loop = model_.getLoops()[l];
    return {calcMarkerLocation_G(data_, Marker{"", loop.linkA, loop.p_A, ""}),
            calcMarkerLocation_G(data_, Marker{"", loop.linkB, loop.p_B, ""})};
}

void InverseKinematicsSolver::addLoopJacobian(std::size_t l, Eigen::Ref<Eigen::MatrixXd> G) const {
    const Loop& loop = model_.getLoops()[l];
    const auto [p_A, p_B] = calcLoopPoints(l);
    if (loop.linkA != kGround) addPointJacobian(loop.linkA, p_A, 1, G);
    if (loop.linkB != kGround) addPointJacobian(loop.linkB, p_B, -1, G);
}

void InverseKinematicsSolver::addLoopGradient(std::size_t l, const Eigen::Vector3d& multiplier, Eigen::VectorXd& gradient) const {
    const Loop& loop = model_.getLoops()[l];
    const auto [p_A, p_B] = calcLoopPoints(l);
    addPointGradient(loop.linkA, p_A, multiplier, gradient);
    addPointGradient(loop.linkB, p_B, -multiplier, gradient);
}

void InverseKinematicsSolver::fillLoopGaps(bool withJacobian) {
    if (withJacobian) G_.setZero();
    for (std::size_t l = 0; l < model_.getLoops().size(); ++l) {
        const Eigen::Index row = 3 * static_cast<Eigen::Index>(l);
        const auto [p_A, p_B] = calcLoopPoints(l);
        c_.segment<3>(row) = p_A - p_B;
        if (withJacobian) addLoopJacobian(l, G_.middleRows<3>(row));
    }
}

InverseKinematicsSolver::Score InverseKinematicsSolver::evaluate(const InverseKinematicsTargets& targets,
                                                                const Eigen::VectorXd& q, bool withJacobian) {
    // A trial is judged at the pose its loop closing has just computed.
    if (data_.q != q) calcPositionKinematics(model_, data_, q);
    if (withJacobian) {
        calcJointMotions(jacobianLinks_);
        A_.setZero();
    }
    markersSeen_ = 0;
    for (std::size_t t = 0; t < markerTasks_.size(); ++t) {
        const Eigen::Index row = markerRow(t);
        const bool seen = evaluateMarker(t, targets, r_.segment<3>(row));
        markersSeen_ += seen;
        if (seen && withJacobian) addMarkerJacobian(t, A_.middleRows<3>(row));
    }
    const Eigen::Index coordinates = static_cast<Eigen::Index>(coordinateTasks_.size());
    evaluateCoordinates(targets, q, r_.segment(coordinateRow(0), coordinates), A_.middleRows(coordinateRow(0), coordinates),
                        withJacobian);
    for (std::size_t t = 0; t < orientationTasks_.size(); ++t) {
        const Eigen::Index row = orientationRow(t);
        if (evaluateOrientation(t, targets, r_.segment<3>(row)) && withJacobian)
            addOrientationJacobian(t, r_.segment<3>(row), A_.middleRows<3>(row));
    }
    fillLoopGaps(withJacobian);
    const double cost = 0.5 * r_.squaredNorm();
    return {cost, cost + (kLoopMerit + 2 * multipliers_.lpNorm<Eigen::Infinity>()) * c_.norm(),
            c_.size() == 0 || c_.lpNorm<Eigen::Infinity>() <= kClosedGap};
}

// Whether a target or loop moves with the free unknown `col` at the last evaluation (a finger no marker
// sees does not).
bool InverseKinematicsSolver::isObserved(Eigen::Index col) const { return !(A_.col(col).isZero(0) && G_.col(col).isZero(0)); }

// The linearised step leaves the loops open by its square; closing them again before the step is judged
// keeps the merit from refusing good steps for that gap (the Maratos effect) and every accepted pose
// closed. Minimum-norm Gauss-Newton on the gaps alone.
void InverseKinematicsSolver::closeLoops(Eigen::VectorXd& q) {
    if (c_.size() == 0) return;
    for (int iteration = 0; iteration < kLoopClosingIterations; ++iteration) {
        // The gaps alone: the tasks are evaluated once the pose is closed.
        calcPositionKinematics(model_, data_, q);
        fillLoopGaps(false);
        if (c_.lpNorm<Eigen::Infinity>() <= kClosedGap) return;
        calcJointMotions(loopChainLinks_);
        fillLoopGaps(true);
        // The minimum-norm step leaves the unknowns no loop moves where they are: it is decomposed over the
        // loops' chains alone (a few dozen columns of the whole body's 156).
        loopColumns_.clear();
        for (Eigen::Index j = 0; j < numFree_; ++j)
            if (!G_.col(j).isZero(0)) loopColumns_.push_back(j);
        Eigen::VectorXd delta = Eigen::VectorXd::Zero(numFree_);
        // G+ = G^T (G G^T)+: the minimum-norm step through the loops' few rows (12 x 12 on the whole body)
        // rather than a decomposition of all the chains' columns (90); a direction the loops repeat, or
        // nearly, is left alone rather than stepped along by its tiny singular value.
        const Eigen::MatrixXd chainG = G_(Eigen::all, loopColumns_);
        Eigen::MatrixXd GGt = Eigen::MatrixXd::Zero(chainG.rows(), chainG.rows());
        addGaussNewtonHessian(GGt, chainG.transpose(), 1);
        const Eigen::VectorXd chainStep = chainG.transpose() * GGt.completeOrthogonalDecomposition().solve(-c_);
        delta(loopColumns_) = chainStep;
        q = integrateCoordinates(model_, q, toSpeeds(delta), 1.0);
        applyCoordinateCouplers(model_, q);
    }
}

// min g^T d + 1/2 d^T (H + damping) d subject to c + G d = 0, with the entries `fixed` given by fixedStep: the
// KKT system [H G^T; G 0] [d; lambda] = [-g; -c] by its Schur complement on the loops. H by Cholesky, damped
// further until positive definite (with the residuals' curvature it need not be), and the loops' small G H^-1 G^T by a
// complete orthogonal decomposition, since loops may repeat one another's constraints (rank-deficient G).
Eigen::VectorXd InverseKinematicsSolver::solveKkt(double& damping, const std::vector<bool>& fixed,
                                                  const Eigen::VectorXd& fixedStep) {
    const Eigen::Index n = stepHessian_.rows();
    H_ = stepHessian_;
    Eigen::VectorXd b = -(observedA_.transpose() * r_), e = -c_;
    Eigen::MatrixXd G = observedG_;
    for (Eigen::Index j = 0; j < n; ++j) {
        if (!fixed[static_cast<std::size_t>(j)]) continue;
        b -= H_.col(j) * fixedStep[j];
        e -= G.col(j) * fixedStep[j];
        H_.row(j).setZero();
        H_.col(j).setZero();
        b[j] = fixedStep[j];
        G.col(j).setZero();
    }
    // The damping keeps the shift that made H positive definite: the curvature's negative directions change
    // little from step to step, and each factorisation refused on the way up costs a whole one (a mean of
    // 1.9 a step on the kick when each step's search started from the damping again, 1.35 now).
    for (;; damping *= 10) {
        for (Eigen::Index j = 0; j < n; ++j) H_(j, j) = fixed[static_cast<std::size_t>(j)] ? 1 : stepHessian_(j, j) + damping;
        if (cholesky_.compute(H_, blockSizes_)) break;
    }
    Eigen::VectorXd free = b;
    cholesky_.solveInPlace(free);
    if (G.rows() == 0) return free;
    // With H = L L^T and W = L^-1 G^T: S = W^T W, and H^-1 G^T lambda = L^-T (W lambda). One triangular
    // solve with the loops' columns instead of two (H^-1 G^T), which took 11 % of the whole body's steps.
    Eigen::MatrixXd W = G.transpose();
    cholesky_.solveLowerInPlace(W);
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(G.rows(), G.rows());
    addGaussNewtonHessian(S, W, 1);
    multipliers_ = S.completeOrthogonalDecomposition().solve(G * free - e);
    Eigen::VectorXd correction = W * multipliers_;
    cholesky_.solveLowerTransposeInPlace(correction);
    return free - correction;
}

// The free unknowns that a target or loop observes at the last evaluation (the kick's 120 of 156), with A's
// and G's columns for them. The others are decoupled from the step (no row moves them, so neither does
// the curvature): the step's algebra runs on the observed ones alone.
void InverseKinematicsSolver::gatherObservedColumns() {
    observedByIndex_.clear();
    for (Eigen::Index j = 0; j < numFree_; ++j) {
        observedIndex_[static_cast<std::size_t>(j)] = -1;
        if (isObserved(j)) observedByIndex_.push_back(j);
    }
    // The blocks depend on the observed set alone, which changes only where a target comes or goes.
    if (observedByIndex_ != partitionedFor_) {
        partitionedFor_ = observedByIndex_;
        orderObservedColumns();
    }
    for (std::size_t k = 0; k < observed_.size(); ++k)
        observedIndex_[static_cast<std::size_t>(observed_[k])] = static_cast<Eigen::Index>(k);
    observedA_ = A_(Eigen::all, observed_);
    observedG_ = G_(Eigen::all, observed_);
}

// Two unknowns are coupled only where a task or loop observes both, that is where one's joint moves the
// other's link (or a loop joins their subtrees, which the factor checks). So the subtrees hanging off a
// trunk that holds the tree's root are independent blocks. Which links make the trunk is chosen greedily
// by the factor's arithmetic: from the root down, a subtree's chain of single children is moved into the
// trunk, down to the next link that branches, while that lowers it. On the whole body the trunk becomes
// the pelvis, spine and sternum (63 unknowns), and the legs, arms and head are the blocks (57).
void InverseKinematicsSolver::orderObservedColumns() {
    const std::size_t numLinks = childLinks_.size();
    std::vector<Eigen::Index> count(numLinks, 0);  // observed unknowns in each link's subtree
    for (const Eigen::Index j : observedByIndex_) ++count[static_cast<std::size_t>(columnLink_[static_cast<std::size_t>(j)])];
    for (std::size_t i = numLinks; i-- > 0;) {
        const int parent = model_.getJoint(static_cast<int>(i)).parent;
        if (parent != kGround) count[static_cast<std::size_t>(parent)] += count[i];
    }
    auto own = [&](int link) {
        Eigen::Index n = count[static_cast<std::size_t>(link)];
        for (int child : childLinks_[static_cast<std::size_t>(link)]) n -= count[static_cast<std::size_t>(child)];
        return n;
    };
    auto observedChildren = [&](int link) {
        std::vector<int> children;
        for (int child : childLinks_[static_cast<std::size_t>(link)])
            if (count[static_cast<std::size_t>(child)] > 0) children.push_back(child);
        return children;
    };
    // Flops of the factor: each block's own, its coupling's triangular solve and trunk update, the trunk's.
    auto cost = [](Eigen::Index trunk, const std::vector<Eigen::Index>& sizes) {
        const double t = static_cast<double>(trunk);
        double flops = t * t * t / 3;
        for (const Eigen::Index size : sizes) {
            const double s = static_cast<double>(size);
            flops += s * s * s / 3 + t * s * s + t * t * s / 2;
        }
        return flops;
    };
    std::vector<char> inTrunk(numLinks, 0);
    std::vector<int> roots;  // the blocks' top links
    for (std::size_t i = 0; i < numLinks; ++i)
        if (model_.getJoint(static_cast<int>(i)).parent == kGround && count[i] > 0) roots.push_back(static_cast<int>(i));
    Eigen::Index trunk = 0;
    auto sizesWithout = [&](std::size_t skipped, const std::vector<int>& added) {
        std::vector<Eigen::Index> sizes;
        for (std::size_t b = 0; b < roots.size(); ++b)
            if (b != skipped) sizes.push_back(count[static_cast<std::size_t>(roots[b])]);
        for (int link : added) sizes.push_back(count[static_cast<std::size_t>(link)]);
        return sizes;
    };
    // The chain from a block's top down to its first link that branches (or its end), which joins the trunk
    // as a whole: its links, and the blocks that then hang below it.
    std::vector<int> chain;
    auto followChain = [&](int top) {
        chain.clear();
        for (int link = top;;) {
            chain.push_back(link);
            std::vector<int> children = observedChildren(link);
            if (children.size() != 1) return children;
            link = children.front();
        }
    };
    auto countOwn = [&] {
        Eigen::Index moved = 0;
        for (const int link : chain) moved += own(link);
        return moved;
    };
    for (;;) {
        double best = cost(trunk, sizesWithout(roots.size(), {}));
        std::size_t bestRoot = roots.size();
        for (std::size_t b = 0; b < roots.size(); ++b) {
            const std::vector<int> below = followChain(roots[b]);
            const double split = cost(trunk + countOwn(), sizesWithout(b, below));
            if (split < best) best = split, bestRoot = b;
        }
        if (bestRoot == roots.size()) break;
        const std::vector<int> below = followChain(roots[bestRoot]);
        roots.erase(roots.begin() + static_cast<std::ptrdiff_t>(bestRoot));
        roots.insert(roots.end(), below.begin(), below.end());
        trunk += countOwn();
        for (const int link : chain) inTrunk[static_cast<std::size_t>(link)] = 1;
    }
    // Each link's block (its top link), or -1 for the trunk's; parents come before their children.
    std::vector<int> block(numLinks, -1);
    for (std::size_t i = 0; i < numLinks; ++i) {
        if (inTrunk[i]) continue;
        const int parent = model_.getJoint(static_cast<int>(i)).parent;
        block[i] = parent == kGround || inTrunk[static_cast<std::size_t>(parent)] ? static_cast<int>(i)
                                                                                 : block[static_cast<std::size_t>(parent)];
    }
    observed_.clear();
    blockSizes_.clear();
    std::sort(roots.begin(), roots.end());
    for (const int root : roots) {
        const std::size_t before = observed_.size();
        for (const Eigen::Index j : observedByIndex_)
            if (block[static_cast<std::size_t>(columnLink_[static_cast<std::size_t>(j)])] == root) observed_.push_back(j);
        blockSizes_.push_back(static_cast<Eigen::Index>(observed_.size() - before));
    }
    // The trunk deepest first, its root last: a block then couples to a last stretch of its rows (a leg to
    // the pelvis's alone), which is all the factor updates.
    for (auto it = observedByIndex_.rbegin(); it != observedByIndex_.rend(); ++it)
        if (block[static_cast<std::size_t>(columnLink_[static_cast<std::size_t>(*it)])] < 0) observed_.push_back(*it);
}

Eigen::VectorXd InverseKinematicsSolver::solveStep(double& damping, const Eigen::VectorXd& q) {
    gatherObservedColumns();
    const Eigen::Index n = static_cast<Eigen::Index>(observed_.size());
    // The bounded unknowns fixed at a bound this pass, and how far that moves them.
    std::vector<bool> fixed(static_cast<std::size_t>(n), false);
    Eigen::VectorXd fixedStep = Eigen::VectorXd::Zero(n);
    Eigen::VectorXd step(n);
    // The curvature learnt at another pose, as its residuals and multipliers are to these: it vanishes
    // with them (quadratic convergence onto a capture the model can reach), and where a target or loop
    // no longer observes an unknown (a marker unseen this frame) it no longer curves.
    const double residuals = std::sqrt(r_.squaredNorm() + multipliers_.squaredNorm());
    if (useCurvature_ && curvatureResiduals_ > 0)
        stepHessian_ = std::min(1.0, residuals / curvatureResiduals_) * curvature_(observed_, observed_);
    else
        stepHessian_.setZero(n, n);
    addGaussNewtonHessian(stepHessian_, observedA_, 1);
    for (int pass = 0; pass < kActiveSetPasses; ++pass) {
        step = solveKkt(damping, fixed, fixedStep);
        bool changed = false;
        for (const auto& [col, qi] : boundedColumns_) {
            const Eigen::Index k = observedIndex_[static_cast<std::size_t>(col)];
            if (k < 0 || fixed[static_cast<std::size_t>(k)]) continue;
            const Coordinate& c = model_.getCoordinates()[static_cast<std::size_t>(qi)];
            const double value = q[qi];
            const double next = value + step[k];
            if (next > c.rangeMax || next < c.rangeMin) {
                fixed[static_cast<std::size_t>(k)] = true;
                fixedStep[k] = (next > c.rangeMax ? c.rangeMax : c.rangeMin) - value;
                changed = true;
            }
        }
        if (!changed) break;
    }
    Eigen::VectorXd delta = Eigen::VectorXd::Zero(numFree_);
    delta(observed_) = step;
    // An unobserved clamped coordinate outside its range (a default pose) goes to the range's end: nothing
    // couples it to the rest.
    for (const auto& [col, qi] : boundedColumns_) {
        if (observedIndex_[static_cast<std::size_t>(col)] >= 0) continue;
        const Coordinate& c = model_.getCoordinates()[static_cast<std::size_t>(qi)];
        if (q[qi] > c.rangeMax) delta[col] = c.rangeMax - q[qi];
        if (q[qi] < c.rangeMin) delta[col] = c.rangeMin - q[qi];
    }
    return delta;
}

Eigen::VectorXd InverseKinematicsSolver::toSpeeds(const Eigen::VectorXd& delta) const {
    Eigen::VectorXd du = Eigen::VectorXd::Zero(model_.getNumU());
    for (int u = 0; u < model_.getNumU(); ++u) {
        const int col = freeColumn_[static_cast<std::size_t>(u)];
        if (col >= 0) du[u] = delta[col];
    }
    return du;
}

double InverseKinematicsSolver::calcCostAtAccuracy(const InverseKinematicsTargets& targets) const {
    double weights = 0;
    for (std::size_t t = 0; t < markerTasks_.size(); ++t)
        if (targets.markers.col(static_cast<Eigen::Index>(t)).allFinite()) weights += markerTasks_[t].weight;
    for (const CoordinateTask& task : coordinateTasks_) weights += task.weight;
    for (std::size_t t = 0; t < orientationTasks_.size(); ++t)
        if (targets.orientations[t].allFinite()) weights += orientationTasks_[t].weight;
    return 0.5 * weights * options_.accuracy * options_.accuracy;
}

bool InverseKinematicsSolver::isSmallStep(const Eigen::VectorXd& delta) const {
    const Eigen::VectorXd moved = A_ * delta;
    for (std::size_t t = 0; t < markerTasks_.size(); ++t) {
        const double w = std::sqrt(markerTasks_[t].weight);
        if (w > 0 && moved.segment<3>(3 * static_cast<Eigen::Index>(t)).norm() > options_.accuracy * w) return false;
    }
    const Eigen::Index first = 3 * static_cast<Eigen::Index>(markerTasks_.size());
    for (std::size_t t = 0; t < coordinateTasks_.size(); ++t) {
        const double w = std::sqrt(coordinateTasks_[t].weight);
        if (w > 0 && std::abs(moved[first + static_cast<Eigen::Index>(t)]) > options_.accuracy * w) return false;
    }
    const Eigen::Index orientations = first + static_cast<Eigen::Index>(coordinateTasks_.size());
    for (std::size_t t = 0; t < orientationTasks_.size(); ++t) {
        const double w = std::sqrt(orientationTasks_[t].weight);
        if (w > 0 && moved.segment<3>(orientations + 3 * static_cast<Eigen::Index>(t)).norm() > options_.accuracy * w)
            return false;
    }
    return true;
}

void InverseKinematicsSolver::checkFrame(const InverseKinematicsTargets& targets, const Eigen::VectorXd& q) const {
    if (targets.markers.cols() != static_cast<Eigen::Index>(markerTasks_.size()) ||
        targets.coordinates.size() != static_cast<Eigen::Index>(coordinateTasks_.size()))
        throw Error("inverse kinematics: the frame has " + std::to_string(targets.markers.cols()) + " markers and " +
                    std::to_string(targets.coordinates.size()) + " coordinate targets; the solver's tasks are " +
                    std::to_string(markerTasks_.size()) + " and " + std::to_string(coordinateTasks_.size()));
    if (q.size() != model_.getNumQ() || !q.allFinite())
        throw Error("inverse kinematics: the starting coordinates must be " + std::to_string(model_.getNumQ()) +
                    " finite values");
    if (!targets.coordinates.allFinite()) throw Error("inverse kinematics: a coordinate task's target is not finite");
    if (targets.orientations.size() != orientationTasks_.size())
        throw Error("inverse kinematics: the frame has " + std::to_string(targets.orientations.size()) +
                    " orientations; the solver's orientation tasks are " + std::to_string(orientationTasks_.size()));
}

InverseKinematicsReport InverseKinematicsSolver::solve(const InverseKinematicsTargets& targets, Eigen::VectorXd& q) {
    checkFrame(targets, q);
    InverseKinematicsReport report;
    applyCoordinateCouplers(model_, q);
    multipliers_.setZero(c_.size());
    useCurvature_ = true;
    Score score = evaluate(targets, q, true);
    double damping = 1e-6 * (1 + A_.colwise().squaredNorm().maxCoeff());
    const double dampingFloor = 1e-12 * (1 + damping);
    bool lastTaken = false;
    const double reachedCost = calcCostAtAccuracy(targets);
    for (report.iterations = 0; report.iterations < options_.maxIterations;) {
        const Eigen::VectorXd delta = solveStep(damping, q);
        const Eigen::VectorXd du = toSpeeds(delta);
        ++report.iterations;
        // Converged when the step moves no task's target by more than the accuracy (m, or rad for a
        // coordinate task): coordinates that no task observes (a spine between two tracked vertebrae) may
        // drift along their flat directions without ending the solve late or never. Or, for a fit that
        // cannot reach its targets (its cost above what every target off by the accuracy would cost), when
        // an undamped-enough step (the last one taken too) lowers the merit by no more than that fraction of
        // it: Simbody's Assembler's accuracy, which OpenSim's IK passes on, "the goal within that fraction
        // of its minimum".
        const bool small = isSmallStep(delta);
        Eigen::VectorXd trial = integrateCoordinates(model_, q, du, 1.0);
        applyCoordinateCouplers(model_, trial);
        closeLoops(trial);
        // With the Jacobian: most trials are taken, and the next step needs it there.
        const Score trialScore = evaluate(targets, trial, true);
        // Both poses closed to roundoff: the gaps' part of the merit is that roundoff alone, which would
        // hide the last digits of an exact fit's cost (a segment frame weighted 4e-4 m^2/rad^2 off by 1e-7
        // rad costs 2e-18).
        const bool closed = score.closed && trialScore.closed;
        const double before = closed ? score.cost : score.merit, after = closed ? trialScore.cost : trialScore.merit;
        if (after <= before) {
            const bool flat = lastTaken && after > reachedCost && before - after <= options_.accuracy * after;
            // Gauss-Newton converging only linearly (a step that took off less than half the merit): a fit
            // that cannot reach its targets or pulls against a loop.
            const bool linear = after > 0.5 * before;
            q = trial;
            score = trialScore;
            damping = std::max(dampingFloor, damping / 3);
            lastTaken = true;
            // The curvature from the frame that last needed it serves the next frames, whose residuals
            // are about the same: refreshed only where the one in hand no longer gives a fast solve.
            if (linear && report.iterations % kCurvatureRefreshIterations == 0) refreshCurvature(targets, q);
            if ((small || flat) && c_.lpNorm<Eigen::Infinity>() <= options_.constraintTolerance) {
                report.converged = true;
                break;
            }
        } else {
            evaluate(targets, q, true);
            damping *= 4;
            lastTaken = false;
            // A curvature that proposes a refused step is no longer the fit's (learnt at another frame's
            // pose, or lost in the roundoff of an exact fit): Gauss-Newton's steps until it is refreshed.
            useCurvature_ = false;
            // The loops' curvature, which the linearised gaps leave out, can refuse steps far below the accuracy.
            if (small) {
                report.converged = c_.lpNorm<Eigen::Infinity>() <= options_.constraintTolerance;
                break;
            }
        }
    }
    fillReport(report);
    return report;
}

// The Lagrangian's curvature beyond Gauss-Newton's A^T A, the residuals' and the loops' sum r_i Hess(r_i) +
// lambda^T Hess(c), by forward differences of its gradient over the free unknowns that a task or loop
// observes. Without it a fit that cannot reach its targets (residuals of centimetres, segment frames a few
// tenths of a radian off, as in any real capture) or pulls against a loop converges only linearly.
// A difference re-evaluates only the rows whose links the perturbed unknown moves (its joint's subtree, and
// its couplers'): the others' contributions to the gradient are the same numbers before and after, so the
// column is what a whole re-evaluation gives, at the cost of the subtree. Restores the evaluation at q.
void InverseKinematicsSolver::refreshCurvature(const InverseKinematicsTargets& targets, const Eigen::VectorXd& q) {
    const double h = 1e-7;
    const std::size_t numLoops = model_.getLoops().size();
    // Each task's and loop's share of the gradient at q, A_t^T r_t and G_l^T lambda_l.
    Eigen::MatrixXd markerGradient(numFree_, static_cast<Eigen::Index>(markerTasks_.size()));
    Eigen::MatrixXd orientationGradient(numFree_, static_cast<Eigen::Index>(orientationTasks_.size()));
    Eigen::MatrixXd loopGradient(numFree_, static_cast<Eigen::Index>(numLoops));
    for (std::size_t t = 0; t < markerTasks_.size(); ++t)
        markerGradient.col(static_cast<Eigen::Index>(t)) = A_.middleRows<3>(markerRow(t)).transpose() * r_.segment<3>(markerRow(t));
    for (std::size_t t = 0; t < orientationTasks_.size(); ++t)
        orientationGradient.col(static_cast<Eigen::Index>(t)) =
            A_.middleRows<3>(orientationRow(t)).transpose() * r_.segment<3>(orientationRow(t));
    for (std::size_t l = 0; l < numLoops; ++l) {
        const Eigen::Index row = 3 * static_cast<Eigen::Index>(l);
        loopGradient.col(static_cast<Eigen::Index>(l)) = G_.middleRows<3>(row).transpose() * multipliers_.segment<3>(row);
    }
    const Eigen::Index coordinateRows = static_cast<Eigen::Index>(coordinateTasks_.size());
    const Eigen::VectorXd coordinateGradient =
        A_.middleRows(coordinateRow(0), coordinateRows).transpose() * r_.segment(coordinateRow(0), coordinateRows);
    const std::vector<JointMotion> jointMotion = jointMotion_G_;
    std::vector<char> moved(static_cast<std::size_t>(model_.getNumLinks()));
    auto movedLink = [&](int link) { return link != kGround && moved[static_cast<std::size_t>(link)]; };
    Eigen::MatrixXd coordinateRowsA(coordinateRows, numFree_);
    Eigen::Vector3d residual;
    Eigen::VectorXd coordinateResiduals(coordinateRows), change(numFree_);
    Eigen::MatrixXd hessian = Eigen::MatrixXd::Zero(numFree_, numFree_);
    for (int u = 0; u < model_.getNumU(); ++u) {
        const int col = freeColumn_[static_cast<std::size_t>(u)];
        if (col < 0 || !isObserved(col)) continue;
        // Only u's joint stepped: integrateCoordinates renormalises every quaternion, which would move
        // every link by roundoff.
        const Joint& stepped = model_.getJoint(jointOfU_[static_cast<std::size_t>(u)]);
        Eigen::VectorXd& plus = curvaturePose_;
        plus = q;
        curvatureSpeed_.setZero(model_.getNumU());
        curvatureSpeed_[u] = h;
        integrateJointCoordinates(stepped, q, curvatureSpeed_, 1.0, plus);
        applyCoordinateCouplers(model_, plus);
        calcPositionKinematics(model_, data_, plus);
        for (int i = 0; i < model_.getNumLinks(); ++i) {
            const Joint& joint = model_.getJoint(i);
            moved[static_cast<std::size_t>(i)] = movedLink(joint.parent) ||
                                                 plus.segment(joint.qStart, joint.nq) != q.segment(joint.qStart, joint.nq);
        }
        for (const int i : jacobianLinks_)
            if (moved[static_cast<std::size_t>(i)])
                jointMotion_G_[static_cast<std::size_t>(i)] = calcJointMotion_G(model_.getJoint(i), data_, i, data_.p_GM[static_cast<std::size_t>(i)]);
        evaluateCoordinates(targets, plus, coordinateResiduals, coordinateRowsA, true);
        change = coordinateRowsA.transpose() * coordinateResiduals - coordinateGradient;
        for (std::size_t t = 0; t < markerTasks_.size(); ++t) {
            if (!movedLink(markers_[static_cast<std::size_t>(taskMarker_[t])].link) || !evaluateMarker(t, targets, residual)) continue;
            addMarkerGradient(t, residual, change);
            change -= markerGradient.col(static_cast<Eigen::Index>(t));
        }
        for (std::size_t t = 0; t < orientationTasks_.size(); ++t) {
            if (!movedLink(taskLink_[t]) || !evaluateOrientation(t, targets, residual)) continue;
            addOrientationGradient(t, residual, change);
            change -= orientationGradient.col(static_cast<Eigen::Index>(t));
        }
        for (std::size_t l = 0; l < numLoops; ++l) {
            const Loop& loop = model_.getLoops()[l];
            if (!movedLink(loop.linkA) && !movedLink(loop.linkB)) continue;
            addLoopGradient(l, multipliers_.segment<3>(3 * static_cast<Eigen::Index>(l)), change);
            change -= loopGradient.col(static_cast<Eigen::Index>(l));
        }
        hessian.col(col) = change / h;
        for (const int i : jacobianLinks_)
            if (moved[static_cast<std::size_t>(i)]) jointMotion_G_[static_cast<std::size_t>(i)] = jointMotion[static_cast<std::size_t>(i)];
    }
    // An unobserved unknown's column is zero in both, and so in the difference.
    curvature_ = 0.5 * (hessian + hessian.transpose());
    addGaussNewtonHessian(curvature_, A_, -1);
    evaluate(targets, q, true);
    curvatureResiduals_ = std::sqrt(r_.squaredNorm() + multipliers_.squaredNorm());
    useCurvature_ = true;
}

// The fit errors at the pose of the last evaluation.
void InverseKinematicsSolver::fillReport(InverseKinematicsReport& report) const {
    report.markersSeen = markersSeen_;
    report.markerErrors = markerErrors_;
    double sum = 0;
    for (Eigen::Index t = 0; t < markerErrors_.size(); ++t) {
        if (std::isnan(markerErrors_[t])) continue;
        sum += markerErrors_[t] * markerErrors_[t];
        if (markerErrors_[t] > report.maxMarkerError || report.worstMarker < 0) {
            report.maxMarkerError = markerErrors_[t];
            report.worstMarker = static_cast<int>(t);
        }
    }
    report.rmsMarkerError = markersSeen_ > 0 ? std::sqrt(sum / markersSeen_) : 0;
    double angles = 0;
    for (Eigen::Index t = 0; t < orientationErrors_.size(); ++t) {
        if (std::isnan(orientationErrors_[t])) continue;
        ++report.orientationsSeen;
        angles += orientationErrors_[t] * orientationErrors_[t];
        report.maxOrientationError = std::max(report.maxOrientationError, orientationErrors_[t]);
    }
    report.rmsOrientationError = report.orientationsSeen > 0 ? std::sqrt(angles / report.orientationsSeen) : 0;
    report.constraintViolation = c_.size() > 0 ? c_.lpNorm<Eigen::Infinity>() : 0;
}

const VirtualLinkEquilibriumStatus& InverseKinematicsSolver::balanceVirtualLinks(Eigen::VectorXd& q) {
    if (equilibrium_.links.empty()) return equilibrium_.status;
    calcPositionKinematics(model_, data_, q);
    calcVirtualLinkEquilibriumAtRest(model_, data_, 0, equilibrium_);
    // The speeds are those of the rest the balance assumes; q's alone are wanted.
    Eigen::VectorXd speeds = Eigen::VectorXd::Zero(model_.getNumU());
    getVirtualLinkCoordinates(model_, data_, equilibrium_, q, speeds);
    return equilibrium_.status;
}

InverseKinematicsMotion solveInverseKinematics(InverseKinematicsSolver& solver, const Eigen::VectorXd& q0,
                                               const std::vector<InverseKinematicsTargets>& targets,
                                               const std::function<void(int frame, int frames)>& onFrame) {
    InverseKinematicsMotion motion;
    Eigen::VectorXd q = q0;
    const int frames = static_cast<int>(targets.size());
    for (int k = 0; k < frames; ++k) {
        motion.reports.push_back(solver.solve(targets[static_cast<std::size_t>(k)], q));
        solver.balanceVirtualLinks(q);
        motion.q.push_back(q);
        if (onFrame) onFrame(k + 1, frames);
    }
    return motion;
}

}  // namespace sinew
