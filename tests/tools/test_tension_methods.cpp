// Tension methods by name and extra column blocks, through TensionAnalysis on the shipped arm26:
// - "ipopt" (Ipopt's interior point on the QP's problem) gives the active-set QP's residuals and Z: Ipopt is
//   the independent reference of the active set.
// - A method registered from outside sinew is what TensionAnalysis runs.
// - Reserves are a column block in every method: with wires too weak for the motion, the LP and the QP make
//   up the rest with the reserves (the LP within its band, the QP to its optimum), and the wires' torques (calcWireGeneralizedForces, which never forms J)
//   plus the reserves' forces on their DOFs reproduce inverse dynamics less the residual.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sinew/core/error.hpp"
#include "sinew/core/inverse_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/tensions/active_set_solver.hpp"
#include "sinew/tensions/tension_method_registry.hpp"
#include "sinew/tools/tension_analysis.hpp"
#include "support/test_models.hpp"

namespace sinew {
namespace {

struct Frame {
    Eigen::VectorXd q, u, udot;
};

std::vector<Frame> makeFrames(const Model& model, unsigned seed, int count) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> angle(0.2, 1.2), rate(-1, 1);
    std::vector<Frame> frames(static_cast<std::size_t>(count));
    for (Frame& f : frames) {
        f.q.resize(model.getNumQ()), f.u.resize(model.getNumU()), f.udot.resize(model.getNumU());
        for (Eigen::Index i = 0; i < f.q.size(); ++i) f.q[i] = angle(rng);
        for (Eigen::Index i = 0; i < f.u.size(); ++i) f.u[i] = rate(rng), f.udot[i] = rate(rng);
    }
    return frames;
}

TensionAnalysisOptions makeOptions(const Model& model, const std::string& method, double maxTension) {
    TensionAnalysisOptions options;
    options.method = method;
    options.maxTension = Eigen::VectorXd::Constant(model.getNumWires(), maxTension);
    options.useMusclePhysiology = false;
    return options;
}

TEST(TensionMethods, IpoptGivesTheActiveSetResiduals) {
    // Ipopt solves the regularised QP; "qp" goes on from its optimum by proximal steps (active_set_solver.hpp),
    // which can only lower Z.
    if (!TensionMethodRegistry::global().contains("regularised-qp"))
        TensionMethodRegistry::global().add("regularised-qp", {WireVariables::Tension, [](const TensionMethodSettings&) {
                                                ActiveSetOptions options;
                                                options.proximalSteps = 0;
                                                return std::make_unique<ActiveSetSolver>(options);
                                            }});
    const test::NamedModel arm = test::loadArm26();
    const Model& model = arm.model;
    TensionAnalysis qp(model, makeOptions(model, "regularised-qp", 2000)), ipopt(model, makeOptions(model, "ipopt", 2000));
    TensionAnalysis refined(model, makeOptions(model, "qp", 2000));
    const std::vector<SpatialVector> noLoads(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
    for (const Frame& f : makeFrames(model, 3, 10)) {
        const TensionFrame& reference = qp.calcFrame(f.q, f.u, f.udot, noLoads);
        const Eigen::VectorXd expected = reference.residual;
        const double expectedZ = reference.torqueError;
        const TensionFrame& frame = ipopt.calcFrame(f.q, f.u, f.udot, noLoads);
        ASSERT_EQ(frame.status, DistributionStatus::Optimal);
        EXPECT_TRUE(frame.usedIpopt);
        // The generalized forces the wires leave undone, and Z: the tensions themselves are pinned down only
        // by the tiny regulariser, so an interior point's tolerance shows in them first.
        EXPECT_LT((frame.residual - expected).norm(), 1e-6 * (1 + frame.tau.norm()));
        EXPECT_NEAR(frame.torqueError, expectedZ, 1e-6 * (1 + frame.tau.squaredNorm()));
        EXPECT_LE(refined.calcFrame(f.q, f.u, f.udot, noLoads).torqueError, expectedZ);
    }
}

// Counts its solves and hands them to the active set.
class CountingSolver final : public TensionSolver {
public:
    explicit CountingSolver(int& solves) : solves_(solves) {}
    void solve(const DistributionProblem& problem, DistributionResult& result) override {
        ++solves_;
        qp_.solve(problem, result);
    }
    void reset() override { qp_.reset(); }

private:
    int& solves_;
    ActiveSetSolver qp_;
};

TEST(TensionMethods, ARegisteredMethodIsTheOneRun) {
    static int solves = 0;
    if (!TensionMethodRegistry::global().contains("counting-qp"))
        TensionMethodRegistry::global().add(
            "counting-qp", {WireVariables::Tension, [](const TensionMethodSettings&) {
                                return std::make_unique<CountingSolver>(solves);
                            }});
    const test::NamedModel arm = test::loadArm26();
    const Model& model = arm.model;
    TensionAnalysis counting(model, makeOptions(model, "counting-qp", 2000));
    const std::vector<SpatialVector> noLoads(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
    const Frame f = makeFrames(model, 5, 1).front();
    counting.calcFrame(f.q, f.u, f.udot, noLoads);
    EXPECT_EQ(solves, 1);
    try {
        TensionAnalysis unknown(model, makeOptions(model, "simplex", 2000));
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("counting-qp"), std::string::npos) << e.what();  // the known ones
    }
}

TEST(TensionMethods, ReservesMakeUpWhatWeakWiresCannot) {
    const test::NamedModel arm = test::loadArm26();
    const Model& model = arm.model;
    const std::vector<SpatialVector> noLoads(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
    for (const char* method : {"lp", "qp"}) {
        TensionAnalysisOptions options = makeOptions(model, method, 1.0);  // 1 N: far too weak
        for (int dof = 0; dof < model.getNumU(); ++dof) {
            ReserveActuator reserve;
            reserve.name = "reserve" + std::to_string(dof);
            reserve.dof = dof;
            reserve.optimalForce = 10.0 * (dof + 1);
            options.reserves.push_back(reserve);
        }
        TensionAnalysis analysis(model, options);
        for (const Frame& f : makeFrames(model, 9, 10)) {
            const TensionFrame& frame = analysis.calcFrame(f.q, f.u, f.udot, noLoads);
            ASSERT_EQ(frame.status, DistributionStatus::Optimal) << method;
            Data data(model);
            calcPositionKinematics(model, data, f.q);
            calcWirePaths(model, data);
            Eigen::VectorXd produced(model.getNumU());
            calcWireGeneralizedForces(model, data, frame.tension, produced);
            for (int dof = 0; dof < model.getNumU(); ++dof) produced[dof] += frame.reserveForce[dof];
            EXPECT_LT((frame.tau - produced - frame.residual).norm(), 1e-8 * (1 + frame.tau.norm())) << method;
            // The LP keeps every row within its band. The QP's objective is at most its value at no tension and
            // the reserves alone, Σ ½ tau_i² / (1 + F_i²) (F_i >= 10 the reserves' optimal forces), and ½ |r|²
            // is part of it.
            if (std::string(method) == "lp")
                EXPECT_LE(frame.residual.cwiseAbs().maxCoeff(), options.problem.torqueTolerance * (1 + 1e-6)) << method;
            else
                EXPECT_LE(frame.residual.norm(), frame.tau.norm() / std::sqrt(101.0) * (1 + 1e-6)) << method;
            EXPECT_GT(frame.reserveForce.cwiseAbs().maxCoeff(), 1.0) << method;  // the wires alone fall short
        }
    }
}

}  // namespace
}  // namespace sinew
