#pragma once
// The QP tension distribution by a warm-started active-set method in the DOF-dimensional torque space
// (docs/tensions.md, "The active-set QP"; the paper's Eq. 14 with the regulariser below):
//
//     min ½ Σ_j weight_j x_j² + ½ Σ_{tolerance rows} (tau - A x)_i²
//     s.t. (A x)_i = tau_i on equality rows, lower <= x <= upper on the bounded variables,
//
// free variables unbounded and unweighted. It maximises the dual, a concave piecewise quadratic in the row
// multipliers y (one per DOF), by Newton steps with exact line search; x_j = clamp(a_j^T y / weight_j) and
// the Newton matrix is Σ + Σ_{free j} a_j a_j^T / weight_j, a rows x rows Cholesky factor that gets
// rank-one up/down-dates as variables enter and leave their bounds. Least squares (QP) and OpenSim's static
// optimization (static_optimization.hpp) are both this problem.
#include <Eigen/Core>
#include <Eigen/QR>
#include <memory>
#include <vector>

#include "sinew/tensions/distribution_problem.hpp"
#include "sinew/tensions/ipopt_solver.hpp"
#include "sinew/tensions/lp_solver.hpp"
#include "sinew/tensions/tension_solver.hpp"

namespace sinew {

struct ActiveSetOptions {
    // Converged when the dual gradient (the rows' residual of the optimality conditions) is below this
    // times the size of the generalized forces; or below roundoffTolerance times it after a full Newton
    // step that left the active set as it was, which solves the piecewise-quadratic dual exactly: what
    // is left is the Newton matrix's rounding (about 1e-10 on the whole-body kick, whose K spans 1 to 1e8).
    double tolerance = 1e-11;
    double roundoffTolerance = 1e-8;
    // Equality rows enter the Newton matrix with this times the mean a_j^T a_j / weight_j on the diagonal,
    // so that the matrix stays positive definite when a DOF is unreachable; they are then met to about
    // this relative accuracy (far below infeasibilityTolerance).
    double equalityRegularization = 1e-12;
    // An equality row left with a residual above this (relative to the generalized forces) makes the frame
    // Infeasible.
    double infeasibilityTolerance = 1e-6;
    int maxIterations = 500;
    // After the regularised optimum, up to this many proximal steps: the same QP with the regulariser
    // centred at the previous answer, ½ Σ weight (x - x_k)². Each step's Z = ½|tau - A x|² is no higher
    // than at x_k, where the regulariser vanishes, so the steps walk towards a least-squares optimum and
    // leave the regulariser the tie-break it is meant to be: the paper's QP (Eq. 14) minimises Z alone.
    // They stop when Z falls by less than proximalTolerance of itself. 0: the regularised optimum (static
    // optimization's, whose rows are all exact: there the regulariser is the objective). A step's
    // objective and KKT residuals are its own QP's.
    int proximalSteps = 12;
    double proximalTolerance = 1e-6;
    // They also stop once the residual's RMS over the tolerance rows is below this times the largest
    // generalized force: the accuracy the equality rows are held to (infeasibilityTolerance). Where the
    // wires can meet every row, Z falls geometrically to roundoff and the relative test alone would take
    // every step (on the whole-body benchmark 8 steps from 8e-5 to 1e-16 N²).
    double proximalResidualFloor = 1e-6;
    // The first step is centred at the LP's answer (lp_solver.hpp, the problem's band rows and costs) where
    // that has the lower Z and meets the equality rows, so that Z(QP) <= Z(LP) on every frame: the
    // regulariser holds back co-contractions whose gain in Z is small per newton, which the LP may use
    // (an LP solve per frame, warm from the last). Where the LP's answer meets the rows to the floor above,
    // the steps start from it without the regularised optimum.
    bool proximalFromLp = true;
    // A frame the active set does not solve (iteration limit, numerical breakdown) that the phase-1 LP
    // finds feasible is solved again by Ipopt (ipopt_solver.hpp; DistributionResult::usedIpopt).
    bool ipoptFallback = true;
};

// One solver per sequence of frames; it keeps the previous frame's multipliers as the warm start and its
// buffers. Not thread-safe: one per thread.
class ActiveSetSolver final : public TensionSolver {
public:
    explicit ActiveSetSolver(ActiveSetOptions options = {});

    // Solves `problem` (validated; throws sinew::Error when malformed) into `result`, starting from the
    // previous frame's multipliers when the number of rows is the same. A frame whose equality rows no x
    // within the bounds meets is Infeasible (infeasible_frame.hpp: the phase-1 reserve, the least-squares
    // answer); a feasible one the active set fails on goes to Ipopt (ActiveSetOptions::ipoptFallback).
    void solve(const DistributionProblem& problem, DistributionResult& result) override;
    // The next solve starts cold (y = 0).
    void reset() override {
        hasWarmStart_ = false;
        lpStepY_.resize(0);
        if (lp_) lp_->reset();
    }

private:
    enum Regime : signed char { AtLower = -1, Free = 0, AtUpper = 1 };
    static constexpr int kStallIterations = 50;   // Newton steps before a feasibility check (phase 1)
    static constexpr int kPolishIterations = 20;  // dual Newton steps after the Ipopt fallback
    static constexpr int kEqualityPasses = 3;       // shifts of the equality rows' targets (solveDual)
    static constexpr int kEqualityPassIterations = 10;  // Newton steps a shift may take
    static constexpr double kEqualityRoundoff = 1e-14;  // relative to the rows' size
    // sameProblem: `problem` is the one the last call solved, so its set-up (the free columns' QR, Sigma)
    // still holds, and the Newton matrix's factor where no up/down-date has touched it.
    void solveDual(const DistributionProblem& problem, DistributionResult& result, int maxIterations = -1,
                   bool sameProblem = false);
    bool runNewton(const DistributionProblem& problem, double tauScale, int limit, int& iterations, bool& fullStep,
                   double& relativeGradient);
    bool shiftEqualityTargets(const DistributionProblem& problem, double tauScale);
    void writeDualResult(const DistributionProblem& problem, bool converged, int iterations, DistributionResult& result);
    void refineProximally(const DistributionProblem& problem, DistributionResult& result);
    bool startFromLp(const DistributionProblem& problem, DistributionResult& result);
    bool solveLp(const DistributionProblem& problem);
    double calcProximalFloor(const DistributionProblem& problem) const;
    int takeProximalSteps(const DistributionProblem& problem, double centerError, bool fromLp, DistributionResult& result);
    void setUpFrame(const DistributionProblem& problem);
    void startFrom(const Eigen::VectorXd& start);
    void evaluate(const DistributionProblem& problem);
    bool factorize(const DistributionProblem& problem);
    bool updateFactor(const DistributionProblem& problem);
    double searchLine(const DistributionProblem& problem);
    void toReduced(const Eigen::VectorXd& rowVector, Eigen::VectorXd& reduced);
    void fromReduced(const Eigen::VectorXd& reduced, Eigen::VectorXd& rowVector);

    ActiveSetOptions options_;
    bool hasWarmStart_ = false;
    int rank_ = 0;  // rank of the free variables' columns G; the dual lives in null(G^T), rows - rank_ wide
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr_;  // of G_
    Eigen::MatrixXd G_;                 // (numSupportRows_ x numFree) the free columns' non-zero rows, dense
    Eigen::MatrixXd nullBasis_;         // (numSupportRows_ x numSupportRows_ - rank_) Q's columns spanning null(G^T)
    Eigen::MatrixXd supportBlock_;      // (numSupportRows_ x numSupportRows_ - rank_) factorize's workspace
    int numSupportRows_ = 0;            // rows some free column reaches
    std::vector<int> rowOrder_;         // (rows) the support rows, then the others
    std::vector<int> rowPosition_;      // (rows) each row's place in rowOrder_
    Eigen::VectorXd supportWork_;       // (numSupportRows_)
    Eigen::VectorXd y_;                 // (rows) multipliers; kept between frames
    Eigen::VectorXd sigma_;             // (rows) 1 on tolerance rows, the regulariser on equality rows
    Eigen::VectorXd center_;            // (numBounded) the regulariser's centre: 0, or x_k in a proximal step
    Eigen::VectorXd equalityShift_;     // (rows) added to the equality rows' targets (solveDual)
    Eigen::VectorXd convergedY_, convergedShift_;  // the last converged pass's
    Eigen::VectorXd regularisedY_;      // (rows) the frame's regularised optimum's y, the next frame's start
    Eigen::VectorXd v_;                 // (numBounded) center_j + a_j^T y / weight_j: the unclamped x
    Eigen::VectorXd x_;                 // (numBounded)
    std::vector<Regime> regime_;        // (numBounded) at y
    std::vector<Regime> factored_;      // (numBounded) the regimes the factor holds
    bool factorValid_ = false;          // L_ factors this problem's Newton matrix at factored_
    int factorUpdates_ = 0;             // up/down-dates since L_ was factorised
    std::vector<Regime> stepped_;       // (numBounded) the regimes at the last step's start
    Eigen::MatrixXd K_;                 // (rows x rows) Newton matrix before reduction
    Eigen::MatrixXd L_;                 // (reduced) its Cholesky factor, lower
    Eigen::VectorXd gradient_, direction_, rowWork_;  // (rows)
    Eigen::VectorXd reducedGradient_, reducedDirection_, reducedWork_;  // (rows - rank_)
    Eigen::VectorXd slopeOfX_;          // (numBounded) a_j^T direction
    struct Event {
        double t;
        double slopeChange;
    };
    std::vector<Event> events_;
    std::unique_ptr<IpoptSolver> ipopt_;  // the fallback, made on first use
    DistributionResult polished_;         // the fallback's answer after a few dual Newton steps
    DistributionResult proximal_;         // a proximal step's answer, kept when it lowers the residual
    std::unique_ptr<LpSolver> lp_;        // the proximal steps' start (ActiveSetOptions::proximalFromLp)
    DistributionResult lpAnswer_;
    bool lpSolved_ = false;               // lpAnswer_ is this frame's
    Eigen::VectorXd lpStepY_;             // (rows) where the last first step from the LP's answer ended
};

}  // namespace sinew
