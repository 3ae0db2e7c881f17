// Static optimization on OpenSim's gait2392 in both of its muscle models (92 Thelen2003 muscles; 92
// Millard2012Equilibrium muscles, each with its own law and curves) over every frame of gait2354's walk
// with its ground reactions and a reserve on every coordinate. The reference is the test's own problem
// written from its definition and solved by Ipopt: per frame min Σ a² + Σ c² over activations a in
// [0.01, 1] and reserve controls c, with -Jᵀ (F0 m a) + F_r c = τ on every DOF, where J is the wire Jacobian,
// F0 m each muscle's force per activation from its law at the path's length and lengthening speed J u, and
// τ inverse dynamics with the measured loads.
#include <gtest/gtest.h>

#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>

#include <filesystem>
#include <iostream>

#include "sinew/core/data.hpp"
#include "sinew/core/inverse_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/external_loads.hpp"
#include "sinew/io/model_loading.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/tools/coordinate_table.hpp"
#include "sinew/tools/motion_frames.hpp"
#include "sinew/tools/tension_motion.hpp"

namespace sinew {
namespace {

const std::filesystem::path kShared = std::filesystem::path(SINEW_SHARED_DIR) / "data";
constexpr double kMinActivation = 0.01, kReserveForce = 20;

// min Σ x² over x = [a; c], columns A (rows = DOFs), A x = tau, bounds as given.
class ActivationNlp : public Ipopt::TNLP {
public:
    ActivationNlp(Eigen::MatrixXd A, Eigen::VectorXd tau, Eigen::VectorXd lower, Eigen::VectorXd upper)
        : A_(std::move(A)), tau_(std::move(tau)), lower_(std::move(lower)), upper_(std::move(upper)) {}
    Eigen::VectorXd x;
    bool solved = false;

    bool get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnzJacobian, Ipopt::Index& nnzHessian,
                      IndexStyleEnum& style) override {
        n = static_cast<Ipopt::Index>(A_.cols());
        m = static_cast<Ipopt::Index>(A_.rows());
        nnzJacobian = n * m;
        nnzHessian = n;
        style = C_STYLE;
        return true;
    }
    bool get_bounds_info(Ipopt::Index n, Ipopt::Number* xLower, Ipopt::Number* xUpper, Ipopt::Index m,
                         Ipopt::Number* gLower, Ipopt::Number* gUpper) override {
        for (Ipopt::Index j = 0; j < n; ++j) xLower[j] = lower_[j], xUpper[j] = upper_[j];
        for (Ipopt::Index i = 0; i < m; ++i) gLower[i] = gUpper[i] = tau_[i];
        return true;
    }
    bool get_starting_point(Ipopt::Index n, bool, Ipopt::Number* x0, bool, Ipopt::Number*, Ipopt::Number*,
                            Ipopt::Index, bool, Ipopt::Number*) override {
        for (Ipopt::Index j = 0; j < n; ++j) x0[j] = std::max(lower_[j], std::min(upper_[j], 0.1));
        return true;
    }
    bool eval_f(Ipopt::Index n, const Ipopt::Number* x0, bool, Ipopt::Number& f) override {
        f = Eigen::Map<const Eigen::VectorXd>(x0, n).squaredNorm();
        return true;
    }
    bool eval_grad_f(Ipopt::Index n, const Ipopt::Number* x0, bool, Ipopt::Number* g) override {
        for (Ipopt::Index j = 0; j < n; ++j) g[j] = 2 * x0[j];
        return true;
    }
    bool eval_g(Ipopt::Index n, const Ipopt::Number* x0, bool, Ipopt::Index m, Ipopt::Number* g) override {
        Eigen::Map<Eigen::VectorXd>(g, m) = A_ * Eigen::Map<const Eigen::VectorXd>(x0, n);
        return true;
    }
    bool eval_jac_g(Ipopt::Index n, const Ipopt::Number*, bool, Ipopt::Index m, Ipopt::Index, Ipopt::Index* row,
                    Ipopt::Index* column, Ipopt::Number* values) override {
        Ipopt::Index k = 0;
        for (Ipopt::Index i = 0; i < m; ++i)
            for (Ipopt::Index j = 0; j < n; ++j, ++k) {
                if (values) values[k] = A_(i, j);
                else row[k] = i, column[k] = j;
            }
        return true;
    }
    bool eval_h(Ipopt::Index n, const Ipopt::Number*, bool, Ipopt::Number objectiveFactor, Ipopt::Index,
                const Ipopt::Number*, bool, Ipopt::Index, Ipopt::Index* row, Ipopt::Index* column,
                Ipopt::Number* values) override {
        for (Ipopt::Index j = 0; j < n; ++j) {
            if (values) values[j] = 2 * objectiveFactor;
            else row[j] = column[j] = j;
        }
        return true;
    }
    void finalize_solution(Ipopt::SolverReturn status, Ipopt::Index n, const Ipopt::Number* x0, const Ipopt::Number*,
                           const Ipopt::Number*, Ipopt::Index, const Ipopt::Number*, const Ipopt::Number*, Ipopt::Number,
                           const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
        solved = status == Ipopt::SUCCESS;
        x = Eigen::Map<const Eigen::VectorXd>(x0, n);
    }

private:
    Eigen::MatrixXd A_;
    Eigen::VectorXd tau_, lower_, upper_;
};

Eigen::VectorXd solveWithIpopt(const Eigen::MatrixXd& A, const Eigen::VectorXd& tau, const Eigen::VectorXd& lower,
                               const Eigen::VectorXd& upper) {
    Ipopt::SmartPtr<ActivationNlp> nlp = new ActivationNlp(A, tau, lower, upper);
    Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
    app->Options()->SetIntegerValue("print_level", 0);
    app->Options()->SetStringValue("sb", "yes");
    app->Options()->SetNumericValue("tol", 1e-12);
    app->Options()->SetStringValue("hessian_constant", "yes");
    app->Options()->SetStringValue("jac_c_constant", "yes");
    app->Options()->SetStringValue("jac_d_constant", "yes");
    EXPECT_EQ(app->Initialize(), Ipopt::Solve_Succeeded);
    app->OptimizeTNLP(nlp);
    EXPECT_TRUE(nlp->solved);
    return nlp->x;
}

void checkAgainstIpopt(const char* file, const std::string& lawType) {
    const std::filesystem::path modelPath = kShared / "opensim-models" / "Models" / "Gait2392_Simbody" / file;
    const std::filesystem::path walk = kShared / "opensim" / "gait2354";
    if (!std::filesystem::exists(modelPath) || !std::filesystem::exists(walk))
        GTEST_SKIP() << "../shared/data (OpenSim's gait2392 and gait2354's walk) is absent: it ships only with "
                        "sinew's developer data";
    const Model model = loadModel(modelPath.string(), {});
    const int nu = model.getNumU(), numWires = model.getNumWires();
    ASSERT_EQ(numWires, 92);
    for (const Wire& wire : model.getWires()) ASSERT_EQ(wire.lawSpec.type, lawType) << wire.name;
    const ExternalLoads loads = readExternalLoads((walk / "subject01_walk1_grf.xml").string());
    const StorageTable motion = readStorageFile((walk / "subject01_walk1_ik.mot").string());
    const CoordinateTrajectory trajectory =
        preprocessCoordinateSamples(model, readCoordinateSamples(model, motion), 6.0, -INFINITY, INFINITY);

    TensionMotionOptions options;
    options.analysis.method = "so";
    options.analysis.minActivation = Eigen::VectorXd::Constant(numWires, kMinActivation);
    for (int dof = 0; dof < nu; ++dof) {
        ReserveActuator reserve;
        reserve.name = "reserve_" + std::to_string(dof);
        reserve.dof = dof;
        reserve.optimalForce = kReserveForce;
        options.analysis.reserves.push_back(reserve);
    }
    const TensionMotionResult run = runTensionAnalysis(model, trajectory, &loads, options);
    ASSERT_EQ(run.activations.rows.size(), static_cast<std::size_t>(trajectory.times.size()));
    EXPECT_EQ(run.flaggedFrames, 0);

    const MeasuredLoads measured(model, loads);
    Data data(model);
    Eigen::MatrixXd J(numWires, nu);
    Eigen::VectorXd tau(nu);
    Eigen::VectorXd lower(numWires + nu), upper(numWires + nu);
    lower << Eigen::VectorXd::Constant(numWires, kMinActivation), Eigen::VectorXd::Constant(nu, -1e19);
    upper << Eigen::VectorXd::Ones(numWires), Eigen::VectorXd::Constant(nu, 1e19);
    double worst = 0, largestReserve = 0;
    forEachMotionFrame(model, trajectory, &measured, [&](const MotionFrame& frame) {
        calcInverseDynamics(model, data, frame.q, frame.u, frame.udot, frame.appliedLinkForces, tau);
        calcPositionKinematics(model, data, frame.q);
        calcWirePaths(model, data);
        calcWireJacobian(model, data, J);
        const Eigen::VectorXd speed = J * frame.u;
        Eigen::MatrixXd A(nu, numWires + nu);
        for (int w = 0; w < numWires; ++w) {
            const ForceLaw& law = *model.getWire(w).law;
            const double perActivation =
                *law.getMaxIsometricForce() * law.calcActiveForceMultiplier({data.wireLength[w], speed[w], frame.time});
            A.col(w) = -J.row(w).transpose() * perActivation;
        }
        A.rightCols(nu) = kReserveForce * Eigen::MatrixXd::Identity(nu, nu);
        const Eigen::VectorXd x = solveWithIpopt(A, tau, lower, upper);
        const std::vector<double>& ours = run.activations.rows[static_cast<std::size_t>(frame.index)];
        for (int w = 0; w < numWires; ++w) {
            const double difference = std::fabs(ours[static_cast<std::size_t>(w)] - x[w]);
            worst = std::max(worst, difference);
            EXPECT_LE(difference, 1e-6) << file << " frame " << frame.index << " muscle " << model.getWire(w).name;
        }
        largestReserve = std::max(largestReserve, x.tail(nu).cwiseAbs().maxCoeff() * kReserveForce);
    });
    std::cout << file << ": " << trajectory.times.size() << " frames, largest activation difference from Ipopt "
              << worst << ", largest reserve " << largestReserve << " N m or N\n";
}

TEST(Gait2392StaticOptimization, ThelenModelMatchesIpoptOnEveryFrame) {
    checkAgainstIpopt("gait2392_thelen2003muscle.osim", "thelen2003_muscle");
}

TEST(Gait2392StaticOptimization, MillardModelMatchesIpoptOnEveryFrame) {
    checkAgainstIpopt("gait2392_millard2012muscle.osim", "millard2012_muscle");
}

}  // namespace
}  // namespace sinew
