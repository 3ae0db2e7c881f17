#include "sinew/core/forward_simulation.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "sinew/core/assembly_schedule.hpp"
#include "sinew/core/coordinate_coupler.hpp"
#include "sinew/core/force_elements.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/forward_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/virtual_link_equilibrium.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"

namespace sinew {
namespace {

using Integrator = ForwardSimulationOptions::Integrator;

// Time differences below this (relative to the time, or absolute below 1 s) are roundoff.
constexpr double kTimeResolution = 1e-14;
// A wire switch is located to within this fraction of the step it was found in.
constexpr double kSwitchWidth = 1e-9;

std::string formatTime(double t) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", t);
    return text;
}

// The state y = [q; u] (nq + nu), its derivative, and every buffer the integration needs, sized once.
// A virtual link's entries of y are not integrated (their derivatives are zero): they hold its equilibrium
// pose and quasi-static twist at the last accepted state, the warm start of every evaluation from there.
class SinewSimulator {
public:
    SinewSimulator(const Model& model, int hangLink)
        : model_(model),
          nq_(model.getNumQ()),
          nu_(model.getNumU()),
          schedule_(model, AssemblySchedule::Kind::Automatic, hangLink),
          data_(model),
          fd_(model, schedule_),
          equilibrium_(model),
          q_(nq_),
          u_(nu_),
          tau_(Eigen::VectorXd::Zero(nu_)),
          tensions_(model.getNumWires()) {
        const int n = nq_ + nu_;
        for (Eigen::VectorXd& k : k_) k.resize(n);
        yStage_.resize(n);
        yNew_.resize(n);
        error_.resize(n);
        for (Eigen::VectorXd& d : dense_) d.resize(n);
    }

    Data& updData() { return data_; }
    const VirtualLinkEquilibriumStatus& getVirtualLinkStatus() const { return equilibrium_.status; }
    const Eigen::VectorXd& getTensions() const { return tensions_; }

    // ydot = [qdot; udot] at (t, y): the forward dynamics with gravity, the force elements and the wire
    // tensions; leaves the kinematics, wire paths and tensions of (t, y) in data_ and tensions_.
    void calcStateDerivative(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) {
        calcKinematicsAndTensions(t, y);
        calcWireLinkForces(model_, data_, tensions_);
        tau_.setZero();
        addWireCoordinateForces(model_, data_, tensions_, tau_);  // moving points and ellipsoid-wrapped wires
        addForceElementForces(model_, data_, data_.F_G, tau_);
        calcForwardDynamics(model_, schedule_, data_, tau_, data_.F_G, fd_);
        for (int i = 0; i < model_.getNumLinks(); ++i) {
            const Joint& joint = model_.getJoint(i);
            const int qs = joint.qStart, us = joint.uStart;
            if (model_.getLink(i).isVirtual) {  // solved, not integrated
                ydot.segment<7>(qs).setZero();
                continue;
            }
            switch (joint.type) {
                case JointType::Free:
                    ydot.segment<3>(qs + 4) = u_.segment<3>(us + 3);  // dp_FM/dt = v_FM, both in F
                    [[fallthrough]];
                case JointType::Ball: {
                    // R_FM' = [w]x R_FM with w = w_FM in F, so q' = 1/2 [0; w] * q (quaternion product, w on the
                    // left); linear in q, so an unnormalised q gets a proportionally scaled derivative.
                    const Eigen::Vector3d w = u_.segment<3>(us);
                    const double s = y[qs];
                    const Eigen::Vector3d v = y.segment<3>(qs + 1);
                    ydot[qs] = -0.5 * w.dot(v);
                    ydot.segment<3>(qs + 1) = 0.5 * (s * w + w.cross(v));
                    break;
                }
                case JointType::Pin: ydot[qs] = u_[us]; break;
                case JointType::Weld: break;
                case JointType::Custom: ydot.segment(qs, joint.nq) = u_.segment(us, joint.nu); break;
            }
        }
        ydot.tail(nu_) = fd_.udot;  // 0 for the virtual links' joints
    }

    // Kinematics, wire paths, speeds and tensions at (t, y), into data_ and tensions_.
    void calcKinematicsAndTensions(double t, const Eigen::VectorXd& y) {
        q_ = y.head(nq_);
        u_ = y.tail(nu_);
        calcPositionKinematics(model_, data_, q_);
        calcVelocityKinematics(model_, data_, u_);
        calcWirePaths(model_, data_);
        calcWireSpeeds(model_, data_);
        calcVirtualLinkEquilibrium(model_, data_, t, equilibrium_);
        calcWireTensions(model_, data_, t, tensions_);
    }

    // Stores the virtual links' equilibrium at the state last evaluated, which must be y, in y: the warm
    // start of the evaluations that follow, and what the frames report.
    void storeVirtualLinks(Eigen::VectorXd& y) const {
        if (equilibrium_.links.empty()) return;
        getVirtualLinkCoordinates(model_, data_, equilibrium_, y.head(nq_), y.tail(nu_));
    }

    // Rescales every quaternion in y to unit length and its entries of ydot by the same factor (ydot is
    // linear in the quaternion, and udot does not depend on its norm, so ydot stays the derivative at y).
    void normalizeQuaternions(Eigen::VectorXd& y, Eigen::VectorXd& ydot) const {
        for (const Joint& joint : model_.getJoints()) {
            if (joint.type != JointType::Free && joint.type != JointType::Ball) continue;
            const double norm = y.segment<4>(joint.qStart).norm();
            y.segment<4>(joint.qStart) /= norm;
            ydot.segment<4>(joint.qStart) /= norm;
        }
    }

    // One classic RK4 step of size h from (t, y) with ydot = f(t, y) given; y and ydot advance to t + h.
    void stepRungeKutta4(double t, double h, Eigen::VectorXd& y, Eigen::VectorXd& ydot) {
        Eigen::VectorXd &k2 = k_[1], &k3 = k_[2], &k4 = k_[3];
        yStage_ = y + (0.5 * h) * ydot;
        calcStateDerivative(t + 0.5 * h, yStage_, k2);
        yStage_ = y + (0.5 * h) * k2;
        calcStateDerivative(t + 0.5 * h, yStage_, k3);
        yStage_ = y + h * k3;
        calcStateDerivative(t + h, yStage_, k4);
        y += (h / 6) * (ydot + 2 * k2 + 2 * k3 + k4);
        calcStateDerivative(t + h, y, ydot);
        normalizeQuaternions(y, ydot);
        storeVirtualLinks(y);
    }

    // One Dormand-Prince 5(4) trial step of size h from (t, y) with ydot = f(t, y) (Hairer, Norsett and
    // Wanner, Table 5.2): the fifth-order solution into yNew_ and its derivative (the FSAL stage) into
    // k_[6], and the RMS of the error estimate scaled by accuracy (1 + |y_i|) as the return value.
    double tryDormandPrince(double t, double h, const Eigen::VectorXd& y, const Eigen::VectorXd& ydot,
                            double accuracy) {
        const Eigen::VectorXd& k1 = ydot;
        Eigen::VectorXd &k2 = k_[1], &k3 = k_[2], &k4 = k_[3], &k5 = k_[4], &k6 = k_[5], &k7 = k_[6];
        yStage_ = y + h * (1.0 / 5) * k1;
        calcStateDerivative(t + h / 5, yStage_, k2);
        yStage_ = y + h * ((3.0 / 40) * k1 + (9.0 / 40) * k2);
        calcStateDerivative(t + 3 * h / 10, yStage_, k3);
        yStage_ = y + h * ((44.0 / 45) * k1 - (56.0 / 15) * k2 + (32.0 / 9) * k3);
        calcStateDerivative(t + 4 * h / 5, yStage_, k4);
        yStage_ = y + h * ((19372.0 / 6561) * k1 - (25360.0 / 2187) * k2 + (64448.0 / 6561) * k3 - (212.0 / 729) * k4);
        calcStateDerivative(t + 8 * h / 9, yStage_, k5);
        yStage_ = y + h * ((9017.0 / 3168) * k1 - (355.0 / 33) * k2 + (46732.0 / 5247) * k3 + (49.0 / 176) * k4 -
                           (5103.0 / 18656) * k5);
        calcStateDerivative(t + h, yStage_, k6);
        yNew_ = y + h * ((35.0 / 384) * k1 + (500.0 / 1113) * k3 + (125.0 / 192) * k4 - (2187.0 / 6784) * k5 +
                         (11.0 / 84) * k6);
        calcStateDerivative(t + h, yNew_, k7);
        // Fifth- minus fourth-order solution.
        error_ = h * ((71.0 / 57600) * k1 - (71.0 / 16695) * k3 + (71.0 / 1920) * k4 - (17253.0 / 339200) * k5 +
                      (22.0 / 525) * k6 - (1.0 / 40) * k7);
        return calcErrorNorm(error_, y, yNew_, accuracy);
    }

    // The dense output of the last Dormand-Prince trial step of size h from (y, ydot), fourth order (Hairer,
    // Norsett and Wanner sec. II.6; the coefficients of their code dopri5): y(t + theta h) for theta in [0, 1].
    void prepareDenseOutput(double h, const Eigen::VectorXd& y, const Eigen::VectorXd& ydot) {
        const Eigen::VectorXd &k3 = k_[2], &k4 = k_[3], &k5 = k_[4], &k6 = k_[5], &k7 = k_[6];
        dense_[0] = yNew_ - y;
        dense_[1] = h * ydot - dense_[0];
        dense_[2] = dense_[0] - h * k7 - dense_[1];
        dense_[3] = h * ((-12715105075.0 / 11282082432) * ydot + (87487479700.0 / 32700410799) * k3 +
                         (-10690763975.0 / 1880347072) * k4 + (701980252875.0 / 199316789632) * k5 +
                         (-1453857185.0 / 822651844) * k6 + (69997945.0 / 29380423) * k7);
    }
    void interpolate(double theta, const Eigen::VectorXd& y, Eigen::VectorXd& out) const {
        const double theta1 = 1 - theta;
        out = y + theta * (dense_[0] + theta1 * (dense_[1] + theta * (dense_[2] + theta1 * dense_[3])));
    }

    // The earliest theta in (0, 1] of the last trial step at which the set of pulling wires differs from
    // `taut`, bracketed by bisection on the dense output to [lo, hi] with (hi - lo) h <= width.
    void locateWireSwitch(double t, double h, const Eigen::VectorXd& y, const std::vector<char>& taut, double width,
                          double& lo, double& hi) {
        lo = 0;
        hi = 1;
        while ((hi - lo) * h > width) {
            const double mid = 0.5 * (lo + hi);
            interpolate(mid, y, yStage_);
            calcKinematicsAndTensions(t + mid * h, yStage_);
            (isTautSet(taut) ? lo : hi) = mid;
        }
    }

    // Which wires pull (tension > 0) at the state last evaluated: the force laws' kinks (slack to taut, and
    // the clamp at zero tension) lie on the boundaries between these sets.
    void captureTautSet(std::vector<char>& taut) const {
        for (std::size_t w = 0; w < taut.size(); ++w) taut[w] = tensions_[static_cast<Eigen::Index>(w)] > 0;
    }
    bool isTautSet(const std::vector<char>& taut) const {
        for (std::size_t w = 0; w < taut.size(); ++w)
            if ((tensions_[static_cast<Eigen::Index>(w)] > 0) != static_cast<bool>(taut[w])) return false;
        return true;
    }

    // An explicit Euler step of size dt (a wire switch's bracket, a time sliver) to time tEnd.
    void nudge(double tEnd, double dt, Eigen::VectorXd& y, Eigen::VectorXd& ydot) {
        y += dt * ydot;
        calcStateDerivative(tEnd, y, ydot);
        normalizeQuaternions(y, ydot);
        storeVirtualLinks(y);
    }

    // Accepts the last Dormand-Prince trial step: y, ydot advance to its end (its last stage, evaluated there).
    void acceptDormandPrince(Eigen::VectorXd& y, Eigen::VectorXd& ydot) {
        y = yNew_;
        ydot = k_[6];
        normalizeQuaternions(y, ydot);
        storeVirtualLinks(y);
    }

    // RMS over i of e_i / (accuracy (1 + max(|a_i|, |b_i|))).
    double calcErrorNorm(const Eigen::VectorXd& e, const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                         double accuracy) const {
        double sum = 0;
        for (Eigen::Index i = 0; i < e.size(); ++i) {
            const double scaled = e[i] / (accuracy * (1 + std::max(std::abs(a[i]), std::abs(b[i]))));
            sum += scaled * scaled;
        }
        return e.size() ? std::sqrt(sum / static_cast<double>(e.size())) : 0.0;
    }

    // Hairer, Norsett and Wanner's starting step (sec. II.4, "automatic step size control"), for order 5.
    double calcInitialStep(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& ydot, double accuracy,
                           double maxStep) {
        const Eigen::VectorXd zero = Eigen::VectorXd::Zero(y.size());
        const double d0 = calcErrorNorm(y, y, zero, accuracy), d1 = calcErrorNorm(ydot, y, zero, accuracy);
        const double h0 = std::min(maxStep, d0 < 1e-5 || d1 < 1e-5 ? 1e-6 : 0.01 * d0 / d1);
        yStage_ = y + h0 * ydot;
        calcStateDerivative(t + h0, yStage_, k_[1]);
        const double d2 = calcErrorNorm(k_[1] - ydot, y, zero, accuracy) / h0;
        const double h1 = std::max(d1, d2) <= 1e-15 ? std::max(1e-6, h0 * 1e-3)
                                                     : std::pow(0.01 / std::max(d1, d2), 1.0 / 5);
        return std::min({100 * h0, h1, maxStep});
    }

private:
    const Model& model_;
    const int nq_, nu_;
    const AssemblySchedule schedule_;
    Data data_;
    ForwardDynamicsData fd_;
    VirtualLinkEquilibriumData equilibrium_;
    Eigen::VectorXd q_, u_;       // the state being evaluated, split (nq, nu)
    Eigen::VectorXd tau_;         // generalized forces of moving wire points, else zero (nu)
    Eigen::VectorXd tensions_;    // N (numWires)
    Eigen::VectorXd k_[7];        // Runge-Kutta stages (nq + nu each)
    Eigen::VectorXd yStage_, yNew_, error_;  // (nq + nu)
    Eigen::VectorXd dense_[4];    // dense output coefficients of the last trial step (nq + nu each)
};

// The loop, coordinate and hang velocity constraints G u = 0: one row block per loop (relative velocity of
// the two loop points, 3 rows) and for the hang (the hung link's angular velocity and origin velocity, 6
// rows), built column by column from unit speeds, and a row per coupler or lock (getCoordinateConstraints).
// Needs calcPositionKinematics in `data`.
Eigen::MatrixXd calcVelocityConstraintMatrix(const Model& model, Data& data, int hangLink) {
    const int loopRows = 3 * model.getNumLoops();
    const std::vector<CoordinateConstraint> constraints = getCoordinateConstraints(model);
    const int rows = loopRows + static_cast<int>(constraints.size()) + (hangLink >= 0 ? 6 : 0);
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(rows, model.getNumU());
    Eigen::VectorXd unit = Eigen::VectorXd::Zero(model.getNumU());
    auto pointVelocity = [&](int link, const Eigen::Vector3d& p_B) {
        const std::size_t b = static_cast<std::size_t>(link);
        return Eigen::Vector3d(data.v_GB[b] + data.w_GB[b].cross(data.R_GB[b] * p_B));
    };
    for (int j = 0; j < model.getNumU(); ++j) {
        unit.setZero();
        unit[j] = 1;
        calcVelocityKinematics(model, data, unit);
        for (int k = 0; k < model.getNumLoops(); ++k) {
            const Loop& loop = model.getLoop(k);
            G.block<3, 1>(3 * k, j) = pointVelocity(loop.linkA, loop.p_A) - pointVelocity(loop.linkB, loop.p_B);
        }
        if (hangLink >= 0) {
            const std::size_t h = static_cast<std::size_t>(hangLink);
            G.block<3, 1>(rows - 6, j) = data.w_GB[h];
            G.block<3, 1>(rows - 3, j) = data.v_GB[h];
        }
    }
    for (std::size_t k = 0; k < constraints.size(); ++k) {
        const CoordinateConstraint& row = constraints[k];
        const int r = loopRows + static_cast<int>(k);
        G(r, row.speed) = 1;
        if (row.otherSpeed >= 0) G(r, row.otherSpeed) -= calcCoordinateConstraintSlope(model, row, data.q);
    }
    return G;
}

}  // namespace

const char* toString(ForwardSimulationOptions::Integrator integrator) {
    switch (integrator) {
        case Integrator::Adaptive: return "adaptive";
        case Integrator::RungeKutta4Fixed: return "rk4";
    }
    return "?";
}

long checkSimulationOptions(const ForwardSimulationOptions& options) {
    auto require = [](bool ok, const char* option, double value, const char* expected) {
        if (!ok) throw Error(std::string(option) + " " + formatTime(value) + ": expected " + expected);
    };
    const double finite = std::numeric_limits<double>::max();
    require(options.duration > 0 && options.duration <= finite, "--duration", options.duration, "a finite time > 0 s");
    require(options.reportInterval > 0 && options.reportInterval <= finite, "--interval", options.reportInterval,
            "a finite time > 0 s");
    require(options.accuracy > 0 && options.accuracy < 1, "--accuracy", options.accuracy, "a value in (0, 1)");
    require(options.fixedStep > 0 && options.fixedStep <= finite, "--step", options.fixedStep, "a finite time > 0 s");
    require(options.minStep > 0 && options.minStep <= finite, "--min-step", options.minStep, "a finite time > 0 s");
    require(options.maxSteps > 0, "--max-steps", static_cast<double>(options.maxSteps), "a count > 0");
    const double intervals = std::ceil(options.duration / options.reportInterval - 1e-9);
    if (!(intervals + 1 <= static_cast<double>(kMaxSimulationFrames)))
        throw Error("--duration " + formatTime(options.duration) + " s at --interval " +
                    formatTime(options.reportInterval) + " s gives " + formatTime(intervals + 1) + " frames; at most " +
                    std::to_string(kMaxSimulationFrames) + " (lengthen --interval)");
    // Report times closer than this cannot be told apart once added to the time reached.
    if (options.reportInterval < 1e3 * kTimeResolution * std::max(1.0, options.duration))
        throw Error("--interval " + formatTime(options.reportInterval) + " s is below the time resolution at t = " +
                    formatTime(options.duration) + " s");
    return std::max(1L, static_cast<long>(intervals));
}

double getReportTime(const ForwardSimulationOptions& options, long i) {
    return std::min(options.duration, static_cast<double>(i) * options.reportInterval);
}

double calcConstraintViolation(const Model& model, Data& data, const Eigen::VectorXd& q, int hangLink,
                               const Eigen::Vector3d& p_GH) {
    calcPositionKinematics(model, data, q);
    double worst = 0;
    for (const Loop& loop : model.getLoops()) {
        const std::size_t a = static_cast<std::size_t>(loop.linkA), b = static_cast<std::size_t>(loop.linkB);
        const Eigen::Vector3d p_GA = data.p_GB[a] + data.R_GB[a] * loop.p_A;
        const Eigen::Vector3d p_GB = data.p_GB[b] + data.R_GB[b] * loop.p_B;
        worst = std::max(worst, (p_GA - p_GB).norm());
    }
    forEachCoordinateConstraint(model, [&](const CoordinateConstraint& constraint) {
        worst = std::max(worst, std::abs(calcCoordinateConstraintGap(model, constraint, q)));
    });
    if (hangLink >= 0) worst = std::max(worst, (data.p_GB[static_cast<std::size_t>(hangLink)] - p_GH).norm());
    return worst;
}

namespace {

int findHangLink(const Model& model, const std::string& hangBy) {
    if (hangBy.empty()) return -1;
    const int hangLink = model.findLinkIndex(hangBy);
    if (hangLink < 0) throw Error("--hang-by: model '" + model.getName() + "' has no link '" + hangBy + "'");
    if (model.getLink(hangLink).isVirtual) throw Error("--hang-by: '" + hangBy + "' is a virtual link");
    return hangLink;
}

// T = sum over links of 1/2 (m |v_com|^2 + w^T I_com w); V = -m g . p_com + wire energy. Needs the
// kinematics and wire paths in `data`.
void calcMechanicalEnergy(const Model& model, const Data& data, double& kinetic, double& potential) {
    kinetic = 0;
    potential = calcWirePotentialEnergy(model, data) + calcForceElementPotentialEnergy(model, data);
    for (int i = 0; i < model.getNumLinks(); ++i) {
        const Link& link = model.getLink(i);
        const std::size_t b = static_cast<std::size_t>(i);
        const Eigen::Vector3d r_G = data.R_GB[b] * link.com_B;
        const Eigen::Vector3d v_com = data.v_GB[b] + data.w_GB[b].cross(r_G);
        const Eigen::Vector3d w_B = data.R_GB[b].transpose() * data.w_GB[b];
        kinetic += 0.5 * (link.mass * v_com.squaredNorm() + w_B.dot(link.inertia_Bcom * w_B));
        potential -= link.mass * model.getGravity().dot(data.p_GB[b] + r_G);
    }
}

// One simulateForwardSinew: the state y = [q; u] at time t, the integrator's step, the frames it reports
// and the summary they add up to.
class SinewRun {
public:
    SinewRun(const Model& model, const ForwardSimulationOptions& options, int hangLink,
             const std::function<void(const SimulationFrame&)>& onFrame)
        : model_(model),
          options_(options),
          hangLink_(hangLink),
          onFrame_(onFrame),
          nq_(model.getNumQ()),
          nu_(model.getNumU()),
          simulator_(model, hangLink),
          data_(simulator_.updData()),
          y_(nq_ + nu_),
          ydot_(nq_ + nu_),
          tautStart_(static_cast<std::size_t>(model.getNumWires())) {
        frame_.q.resize(nq_);
        frame_.u.resize(nu_);
        frame_.tensions.resize(model.getNumWires());
    }

    // The initial state: the default pose, where the loops must already be closed (this engine does not
    // assemble them) and where the hung link is welded; speeds projected onto the velocity constraints.
    void setInitialState() {
        y_.head(nq_) = model_.getDefaultQ();
        applyCoordinateCouplers(model_, y_.head(nq_));
        calcPositionKinematics(model_, data_, y_.head(nq_));
        p_GH_ = hangLink_ >= 0 ? data_.p_GB[static_cast<std::size_t>(hangLink_)] : Eigen::Vector3d::Zero();
        const double initialGap = calcConstraintViolation(model_, data_, y_.head(nq_), hangLink_, p_GH_);
        if (initialGap > options_.accuracy)
            throw Error("model '" + model_.getName() + "': the loops are open by up to " + std::to_string(initialGap) +
                        " m at the default pose; sinew's engine does not assemble loops (Simbody's does)");
        y_.tail(nu_).setZero();
        if (options_.initialSpeeds.size() > 0) {
            if (options_.initialSpeeds.size() != nu_) throw Error("initial speeds need " + std::to_string(nu_) + " values");
            const Eigen::MatrixXd G = calcVelocityConstraintMatrix(model_, data_, hangLink_);
            // The nearest u (least squares) with G u = 0: subtract the minimum-norm du with G du = G u0.
            y_.tail(nu_) = options_.initialSpeeds;
            if (G.rows() > 0) y_.tail(nu_) -= G.completeOrthogonalDecomposition().solve(G * options_.initialSpeeds);
        }
    }

    // ydot, the pulling wires and the first step at t = 0, and its frame.
    void start() {
        simulator_.calcStateDerivative(t_, y_, ydot_);
        simulator_.storeVirtualLinks(y_);
        simulator_.captureTautSet(tautStart_);
        h_ = options_.integrator == Integrator::Adaptive
                 ? simulator_.calcInitialStep(t_, y_, ydot_, options_.accuracy, options_.reportInterval)
                 : options_.fixedStep;
        report(t_);
    }

    // Integrates to tReport and reports the frame there.
    void advanceTo(double tReport) {
        if (options_.integrator == Integrator::RungeKutta4Fixed) advanceFixed(tReport);
        else advanceAdaptive(tReport);
        t_ = tReport;
        report(t_);
    }

    SimulationSummary& getSummary() { return summary_; }

private:
    void report(double t) {
        frame_.time = t;
        frame_.q = y_.head(nq_);
        frame_.u = y_.tail(nu_);
        summary_.maxConstraintViolation = std::max(summary_.maxConstraintViolation,
                                                   calcConstraintViolation(model_, data_, frame_.q, hangLink_, p_GH_));
        simulator_.calcKinematicsAndTensions(t, y_);
        frame_.tensions = simulator_.getTensions();
        summary_.maxVirtualLinkResidual =
            recordVirtualLinkResidual(summary_.maxVirtualLinkResidual, simulator_.getVirtualLinkStatus(), t);
        calcMechanicalEnergy(model_, data_, frame_.kineticEnergy, frame_.potentialEnergy);
        const double energy = frame_.kineticEnergy + frame_.potentialEnergy;
        if (summary_.frames == 0) summary_.initialEnergy = energy;
        if (!std::isfinite(energy) || !frame_.q.allFinite())
            throw Error("simulation diverged at t = " + formatTime(t) + " s (non-finite state)");
        summary_.maxEnergyDrift = std::max(summary_.maxEnergyDrift, std::abs(energy - summary_.initialEnergy));
        summary_.peakKineticEnergy = std::max(summary_.peakKineticEnergy, frame_.kineticEnergy);
        ++summary_.frames;
        onFrame_(frame_);
    }

    // Counts integrator steps tried against options.maxSteps.
    void spend(double tNow, long steps) {
        attempts_ += steps;
        if (attempts_ > options_.maxSteps)
            throw Error("simulation stopped at t = " + formatTime(tNow) + " s: the step budget (--max-steps " +
                        std::to_string(options_.maxSteps) + ") ran out; the model may be too stiff (check its "
                        "stiffnesses, damping and masses) or --max-steps too small");
    }

    // Equal RK4 steps no longer than fixedStep, ending on the report time.
    void advanceFixed(double tReport) {
        const double span = tReport - t_;
        const double steps = std::ceil(span / options_.fixedStep - 1e-9);
        spend(t_, static_cast<long>(std::min(steps, 1e18)));
        const int n = std::max(1, static_cast<int>(steps));
        for (int k = 0; k < n; ++k) {
            const double tk = t_ + span * k / n;
            simulator_.stepRungeKutta4(tk, span / n, y_, ydot_);
        }
        summary_.steps += n;
    }

    // Dormand-Prince steps under error control to the report time.
    void advanceAdaptive(double tReport) {
        lastRejected_ = false;
        while (t_ < tReport) {
            const double remaining = tReport - t_;
            if (remaining <= 10 * kTimeResolution * std::max(1.0, tReport)) {  // a sliver left by a wire switch
                simulator_.nudge(tReport, remaining, y_, ydot_);
                simulator_.captureTautSet(tautStart_);
                t_ = tReport;
                break;
            }
            // Land on the report time without leaving a sliver: the whole remainder, or half of it.
            const bool toReport = remaining <= h_;
            const double hStep = toReport ? remaining : std::min(h_, remaining <= 2 * h_ ? remaining / 2 : h_);
            if (hStep < std::max(options_.minStep, kTimeResolution * std::max(1.0, t_)))
                throw Error("simulation stopped at t = " + formatTime(t_) + " s: the step size collapsed to " +
                            formatTime(hStep) + " s (below --min-step " + formatTime(options_.minStep) +
                            " s); the model may be too stiff or diverging (check its stiffnesses, damping, "
                            "masses and wire points)");
            spend(t_, 1);
            tryAdaptiveStep(hStep, toReport, tReport);
        }
    }

    // One trial step of size hStep (to tReport if toReport): accepted, rejected, or split at a wire switch
    // inside it. Error control with safety factor 0.9 and growth limited to [0.2, 5] (after a rejection, <= 1).
    void tryAdaptiveStep(double hStep, bool toReport, double tReport) {
        const double err = simulator_.tryDormandPrince(t_, hStep, y_, ydot_, options_.accuracy);
        if (!std::isfinite(err)) throw Error("simulation diverged at t = " + formatTime(t_) + " s (non-finite state)");
        double factor = err > 0 ? kSafety * std::pow(err, -1.0 / 5) : kMaxFactor;
        factor = std::clamp(factor, kMinFactor, lastRejected_ ? 1.0 : kMaxFactor);
        if (err <= 1 && !simulator_.isTautSet(tautStart_) && hStep > 1e3 * kTimeResolution * std::max(1.0, t_)) {
            crossWireSwitch(hStep, toReport, tReport);
        } else if (err <= 1) {
            simulator_.acceptDormandPrince(y_, ydot_);
            simulator_.captureTautSet(tautStart_);
            t_ = toReport ? tReport : t_ + hStep;
            ++summary_.steps;
            // A step shortened to reach the report time says little about the next one.
            h_ = hStep < h_ && factor >= 1 ? std::max(h_, hStep * factor) : hStep * factor;
            lastRejected_ = false;
        } else {
            h_ = hStep * factor;
            lastRejected_ = true;
        }
    }

    // A wire went slack or taut inside the step: a kink (or, with damping, a jump) in the forces that costs
    // Runge-Kutta its order and fools its error estimate. Step to just before the switch with stages that
    // all see the old forces, then across its bracket by Euler. The bracket is kept wider than roundoff in
    // t, so that crossing it always makes progress.
    void crossWireSwitch(double hStep, bool toReport, double tReport) {
        const double resolution = 4 * kTimeResolution * std::max(1.0, t_);
        double lo = 0, hi = 1;
        simulator_.prepareDenseOutput(hStep, y_, ydot_);
        simulator_.locateWireSwitch(t_, hStep, y_, tautStart_, std::max(kSwitchWidth * hStep, resolution), lo, hi);
        if (lo * hStep < resolution) lo = 0;
        if (lo > 0) {
            const double errLo = simulator_.tryDormandPrince(t_, lo * hStep, y_, ydot_, options_.accuracy);
            if (!(errLo <= 1)) {  // rare: retry shorter, as for any rejected step
                h_ = lo * hStep * std::clamp(kSafety * std::pow(errLo, -1.0 / 5), kMinFactor, 1.0);
                lastRejected_ = true;
                return;
            }
            simulator_.acceptDormandPrince(y_, ydot_);
            ++summary_.steps;
        }
        const double tHi = hi == 1 && toReport ? tReport : t_ + hi * hStep;
        simulator_.nudge(tHi, (hi - lo) * hStep, y_, ydot_);
        simulator_.captureTautSet(tautStart_);
        t_ = tHi;
        ++summary_.wireSwitches;
        lastRejected_ = false;
    }

    static constexpr double kSafety = 0.9, kMinFactor = 0.2, kMaxFactor = 5;

    const Model& model_;
    const ForwardSimulationOptions& options_;
    const int hangLink_;
    const std::function<void(const SimulationFrame&)>& onFrame_;
    const int nq_, nu_;
    SinewSimulator simulator_;
    Data& data_;
    Eigen::Vector3d p_GH_ = Eigen::Vector3d::Zero();  // m, where the hung link's origin is held
    Eigen::VectorXd y_, ydot_;                        // (nq + nu) at t_
    double t_ = 0;
    double h_ = 0;                     // the next step to try
    std::vector<char> tautStart_;      // pulling wires at (t_, y_)
    long attempts_ = 0;                // integrator steps tried, against options.maxSteps
    bool lastRejected_ = false;        // the last trial step in this report interval was rejected
    SimulationFrame frame_;
    SimulationSummary summary_;
};

}  // namespace

SimulationSummary simulateForwardSinew(const Model& model, const ForwardSimulationOptions& options,
                                       const std::function<void(const SimulationFrame&)>& onFrame) {
    const long numReports = checkSimulationOptions(options);
    SinewRun run(model, options, findHangLink(model, options.hangBy), onFrame);
    run.setInitialState();
    const auto start = std::chrono::steady_clock::now();
    run.start();
    for (long i = 1; i <= numReports; ++i) run.advanceTo(getReportTime(options, i));
    SimulationSummary& summary = run.getSummary();
    summary.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return summary;
}

}  // namespace sinew
