// TensionAnalysis per frame on the shipped arm26: whatever the method, the tensions it reports must
// produce, through sinew's one-pass generalized forces of tensions (calcWireGeneralizedForces, which never
// forms J), the inverse dynamics torques less the reported residual; and Z must be that residual's size.
// On frames made feasible by construction (accelerations that known tensions f0 produce) each method's own
// promise is checked against f0. runTensionAnalysis keeps a row for every motion row, NaN rows included. Wire
// strengths written in the model file bound the tensions as the same maximum tensions given as options do.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>

#include "sinew/core/error.hpp"
#include "sinew/core/inverse_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "support/random_model.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/io/model_loading.hpp"
#include "sinew/tensions/tension_method_registry.hpp"
#include "sinew/tools/tension_analysis.hpp"
#include "sinew/tools/tension_motion.hpp"
#include "support/test_models.hpp"

namespace sinew {
namespace {

// The generalized forces of `tensions` at q, computed without the Jacobian.
Eigen::VectorXd calcWireTorques(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& tensions) {
    Data data(model);
    calcPositionKinematics(model, data, q);
    calcWirePaths(model, data);
    Eigen::VectorXd tau(model.getNumU());
    calcWireGeneralizedForces(model, data, tensions, tau);
    return tau;
}

class TensionAnalysisTest : public ::testing::TestWithParam<std::string> {};

TEST_P(TensionAnalysisTest, TensionsReproduceTheInverseDynamicsTorques) {
    const test::NamedModel arm = test::loadArm26();
    const Model& model = arm.model;
    TensionAnalysisOptions options;
    options.method = GetParam();
    options.maxTension = Eigen::VectorXd::Constant(model.getNumWires(), 2000);
    options.useMusclePhysiology = false;  // spring-damper wires: force per activation is maxTension
    TensionAnalysis analysis(model, options);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> angle(0.2, 1.2), rate(-1, 1);
    const std::vector<SpatialVector> noLoads(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
    for (int frame = 0; frame < 20; ++frame) {
        Eigen::VectorXd q(model.getNumQ()), u(model.getNumU()), udot(model.getNumU());
        for (Eigen::Index i = 0; i < q.size(); ++i) q[i] = angle(rng);
        for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = rate(rng), udot[i] = rate(rng);
        const TensionFrame& result = analysis.calcFrame(q, u, udot, noLoads);

        Data data(model);
        Eigen::VectorXd tau(model.getNumU());
        calcInverseDynamics(model, data, q, u, udot, noLoads, tau);
        EXPECT_LT((result.tau - tau).norm(), 1e-12 * (1 + tau.norm()));
        const Eigen::VectorXd produced = calcWireTorques(model, q, result.tension);
        EXPECT_LT((tau - produced - result.residual).norm(), 1e-8 * (1 + tau.norm())) << "frame " << frame;
        EXPECT_NEAR(result.torqueError, 0.5 * (tau - produced).squaredNorm(), 1e-9 * (1 + tau.squaredNorm()));
        EXPECT_TRUE((result.tension.array() >= -1e-9).all() && (result.tension.array() <= 2000 + 1e-6).all());
        EXPECT_EQ(std::count(result.unactuated.begin(), result.unactuated.end(), 1), 0);
    }
}

INSTANTIATE_TEST_SUITE_P(Methods, TensionAnalysisTest,
                         ::testing::Values("lp", "qp", "so"),
                         [](const ::testing::TestParamInfo<std::string>& method) { return method.param; });

// udot at (q, u) whose inverse dynamics generalized forces are `target`: inverse dynamics is affine in
// udot, tau = M udot + tau(udot = 0), so M's columns come from unit accelerations.
Eigen::VectorXd calcAccelerationsFor(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& u,
                                     const Eigen::VectorXd& target) {
    const std::vector<SpatialVector> noLoads(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
    Data data(model);
    const Eigen::Index nu = model.getNumU();
    Eigen::VectorXd bias(nu), column(nu), udot = Eigen::VectorXd::Zero(nu);
    calcInverseDynamics(model, data, q, u, udot, noLoads, bias);
    Eigen::MatrixXd M(nu, nu);
    for (Eigen::Index i = 0; i < nu; ++i) {
        udot.setZero();
        udot[i] = 1;
        calcInverseDynamics(model, data, q, u, udot, noLoads, column);
        M.col(i) = column - bias;
    }
    return M.partialPivLu().solve(target - bias);
}

// Frames feasible by construction: tensions f0 strictly within [0, 2000] N and the accelerations whose
// inverse dynamics they produce exactly. Every method must then find an optimal frame, and its optimum
// can be no worse than f0: the LP's total tension at most f0's, static optimization's squared activations
// at most f0's (rows exact, tension = 2000 × activation), the QP's Z at most the regulariser's share of f0
// and of the LP's tensions.
TEST(TensionAnalysis, FeasibleFramesMeetEachMethodsPromise) {
    const test::NamedModel arm = test::loadArm26();
    const Model& model = arm.model;
    const Eigen::Index wires = model.getNumWires();
    TensionAnalysisOptions options;
    options.maxTension = Eigen::VectorXd::Constant(wires, 2000);
    options.useMusclePhysiology = false;
    std::unique_ptr<TensionAnalysis> analyses[3];
    const char* const methods[] = {"lp", "qp", "so"};
    for (int m = 0; m < 3; ++m) {
        options.method = methods[m];
        analyses[m] = std::make_unique<TensionAnalysis>(model, options);
    }
    const double tolerance = options.problem.torqueTolerance, eps = options.problem.regularization;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> angle(0.2, 1.2), rate(-1, 1), tension(50, 1500);
    const std::vector<SpatialVector> noLoads(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
    for (int frame = 0; frame < 20; ++frame) {
        Eigen::VectorXd q(model.getNumQ()), u(model.getNumU()), f0(wires);
        for (Eigen::Index i = 0; i < q.size(); ++i) q[i] = angle(rng);
        for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = rate(rng);
        for (Eigen::Index j = 0; j < wires; ++j) f0[j] = tension(rng);
        const Eigen::VectorXd tau = calcWireTorques(model, q, f0);
        const Eigen::VectorXd udot = calcAccelerationsFor(model, q, u, tau);
        // The QP regulariser's weight: eps times the mean squared generalized force per newton over the wires.
        double meanSquaredArm = 0;
        for (Eigen::Index j = 0; j < wires; ++j)
            meanSquaredArm += calcWireTorques(model, q, Eigen::VectorXd::Unit(wires, j)).squaredNorm() / static_cast<double>(wires);
        const double weight = eps * meanSquaredArm;

        const TensionFrame& lp = analyses[0]->calcFrame(q, u, udot, noLoads);
        ASSERT_EQ(lp.status, DistributionStatus::Optimal) << "frame " << frame;
        EXPECT_LT((lp.tau - tau).norm(), 1e-9 * tau.norm()) << "frame " << frame;
        EXPECT_LE(lp.residual.cwiseAbs().maxCoeff(), tolerance * (1 + 1e-6)) << "frame " << frame;
        EXPECT_LE(lp.tension.sum(), f0.sum() * (1 + 1e-9)) << "frame " << frame;
        const double lpZ = lp.torqueError;
        const Eigen::VectorXd lpTension = lp.tension;

        const TensionFrame& qp = analyses[1]->calcFrame(q, u, udot, noLoads);
        ASSERT_EQ(qp.status, DistributionStatus::Optimal) << "frame " << frame;
        EXPECT_LE(qp.torqueError, 0.5 * weight * f0.squaredNorm() * (1 + 1e-6)) << "frame " << frame;
        EXPECT_LE(qp.torqueError, lpZ + 0.5 * weight * lpTension.squaredNorm() * (1 + 1e-6)) << "frame " << frame;

        const TensionFrame& so = analyses[2]->calcFrame(q, u, udot, noLoads);
        ASSERT_EQ(so.status, DistributionStatus::Optimal) << "frame " << frame;
        EXPECT_LT(so.residual.norm(), 1e-6 * tau.norm()) << "frame " << frame;
        EXPECT_LT((so.tension - 2000 * so.activation).norm(), 1e-9 * f0.norm()) << "frame " << frame;
        EXPECT_LE(so.activation.squaredNorm(), (f0 / 2000).squaredNorm() * (1 + 1e-9)) << "frame " << frame;
        EXPECT_TRUE((so.activation.array() >= -1e-9).all() && (so.activation.array() <= 1 + 1e-9).all());
    }
}

// A floating body whose forked wires meet on virtual links: those wires reach the free root's rows (they
// pull on the bones, not on the virtual links hanging from ground), but with the virtual links in
// equilibrium no wire moves the body as a whole. The root's six DOFs are unactuated, their inverse-dynamics
// torques reported as the frame's residual, and every other DOF left to the wires; a load on a virtual link
// leaves the root what it would leave it if applied to the body.
TEST(TensionAnalysis, FreeRootStaysUnactuatedWithVirtualLinks) {
    RandomModelOptions modelOptions;
    modelOptions.numLinks = 8;
    modelOptions.rootJoint = JointType::Free;
    modelOptions.numWires = 30;
    modelOptions.numVirtualLinks = 2;
    modelOptions.seed = 5;
    const Model model = generateRandomModel(modelOptions);
    TensionAnalysisOptions options;
    options.maxTension = Eigen::VectorXd::Constant(model.getNumWires(), 2000);
    options.useMusclePhysiology = false;
    TensionAnalysis analysis(model, options);
    const Joint& root = model.getJoint(0);
    ASSERT_EQ(root.nu, 6);
    int virtualLink = -1;
    for (int link = 0; link < model.getNumLinks(); ++link)
        if (model.getLink(link).isVirtual) virtualLink = link;
    ASSERT_GE(virtualLink, 0);
    std::mt19937 rng(3);
    const std::vector<SpatialVector> noLoads(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
    for (int frame = 0; frame < 5; ++frame) {
        const Eigen::VectorXd q = generateRandomCoordinates(model, rng), u = generateRandomSpeeds(model, rng);
        const Eigen::VectorXd udot = generateRandomSpeeds(model, rng);
        const TensionFrame& result = analysis.calcFrame(q, u, udot, noLoads);
        Data data(model);
        Eigen::VectorXd tau(model.getNumU());
        calcInverseDynamics(model, data, q, u, udot, noLoads, tau);
        for (int i = 0; i < model.getNumU(); ++i) {
            const bool onRoot = i >= root.uStart && i < root.uStart + root.nu;
            EXPECT_EQ(result.unactuated[static_cast<std::size_t>(i)], onRoot ? 1 : 0) << "DOF " << i << ", frame " << frame;
        }
        EXPECT_NEAR(result.unactuatedResidual, tau.segment(root.uStart, 6).norm(), 1e-9 * tau.norm()) << "frame " << frame;

        // A load on a virtual link reaches the body only through the virtual link's wires, so the root is
        // left what the same load applied to the body would leave it.
        std::vector<SpatialVector> onVirtualLink = noLoads, onBody = noLoads;
        SpatialVector F;
        F << 3, -2, 1, 40, 25, -30;  // moment about the virtual link's origin; force
        const std::size_t v = static_cast<std::size_t>(virtualLink);
        onVirtualLink[v] = F;
        calcPositionKinematics(model, data, q);
        onBody[0] << F.head<3>() + (data.p_GB[v] - data.p_GB[0]).cross(F.tail<3>()), F.tail<3>();
        Eigen::VectorXd tauBody(model.getNumU());
        calcInverseDynamics(model, data, q, u, udot, onBody, tauBody);
        const TensionFrame& loaded = analysis.calcFrame(q, u, udot, onVirtualLink);
        // (The wires cannot always balance the load on the virtual link, tension only, so the frame may be
        // infeasible; what the root is left is decided before the distribution.)
        EXPECT_NEAR(loaded.unactuatedResidual, tauBody.segment(root.uStart, 6).norm(), 1e-9 * tauBody.norm()) << "frame " << frame;
        EXPECT_GT(std::abs(loaded.unactuatedResidual - tau.segment(root.uStart, 6).norm()), 1.0) << "frame " << frame;
    }
}

// OpenSim's arm26 and its IK motion with rows of NaN: every row keeps its place in every table, the NaN
// rows flagged with zeros, the others exactly what the same motion without those rows gives.
TEST(TensionMotion, NaNRowsAreFlaggedAndTheRestMatchesTheMotionWithoutThem) {
    const std::filesystem::path dir = std::filesystem::path(SINEW_SHARED_DIR) / "data" / "opensim" / "arm26";
    if (!std::filesystem::exists(dir / "arm26.osim"))
        GTEST_SKIP() << "../shared/data/opensim/arm26 is absent (it ships only with sinew's developer data)";
    const Model model = loadModel((dir / "arm26.osim").string(), [](const std::string&) {});
    const StorageTable finiteMotion = readStorageFile((dir / "arm26_InverseKinematics.mot").string());
    const std::vector<int> gaps = {10, 11, 50};
    StorageTable motion = finiteMotion, finite = finiteMotion;
    finite.times.clear();
    finite.rows.clear();
    for (std::size_t r = 0; r < motion.rows.size(); ++r) {
        if (std::find(gaps.begin(), gaps.end(), static_cast<int>(r)) != gaps.end()) {
            motion.rows[r][r % motion.columns.size()] = std::nan("");
            continue;
        }
        finite.times.push_back(motion.times[r]);
        finite.rows.push_back(motion.rows[r]);
    }
    TensionMotionOptions options;
    options.analysis.method = "so";
    const TensionMotionResult result = runTensionAnalysis(model, motion, nullptr, options);
    const TensionMotionResult reference = runTensionAnalysis(model, finite, nullptr, options);
    EXPECT_EQ(result.missingRows, gaps);
    EXPECT_EQ(result.flaggedFrames, result.infeasibleFrames + result.failedFrames + 3);
    EXPECT_EQ(result.infeasibleFrames, reference.infeasibleFrames);
    for (const StorageTable* table : {&result.tensions, &result.activations, &result.reserves, &result.report}) {
        EXPECT_EQ(table->times, motion.times);
        for (const std::vector<double>& row : table->rows)
            EXPECT_TRUE(std::all_of(row.begin(), row.end(), [](double value) { return std::isfinite(value); }));
    }
    std::size_t next = 0;  // row of the reference
    for (std::size_t r = 0; r < motion.times.size(); ++r) {
        const std::vector<double>& report = result.report.rows[r];
        if (std::find(gaps.begin(), gaps.end(), static_cast<int>(r)) != gaps.end()) {
            EXPECT_EQ(report[0], kMissingInputStatus);
            EXPECT_TRUE(std::all_of(report.begin() + 1, report.end(), [](double value) { return value == 0; }));
            EXPECT_TRUE(std::all_of(result.tensions.rows[r].begin(), result.tensions.rows[r].end(),
                                    [](double value) { return value == 0; }));
            continue;
        }
        EXPECT_EQ(result.tensions.rows[r], reference.tensions.rows[next]) << "row " << r;
        EXPECT_EQ(result.activations.rows[r], reference.activations.rows[next]) << "row " << r;
        EXPECT_EQ(report, reference.report.rows[next]) << "row " << r;
        ++next;
    }

    // A time range keeps the gaps inside it only.
    options.startTime = 0.3;
    options.finalTime = 0.8;
    EXPECT_EQ(runTensionAnalysis(model, motion, nullptr, options).missingRows, std::vector<int>{50});
}

// arm26's spring-damper wires, each given a strength in its file: with no maximum tensions given, the LP and
// the QP bound each wire by its strength, as they do when those strengths are given as maximum tensions.
TEST(TensionAnalysis, WireStrengthsFromTheModelFileBoundTheTensions) {
    const test::NamedModel arm = test::loadArm26();
    const int wires = arm.model.getNumWires();
    Eigen::VectorXd strength(wires);
    std::string withStrengths;
    std::istringstream lines(writeModelText(arm.model));
    int w = 0;
    for (std::string line; std::getline(lines, line);) {
        withStrengths += line + "\n";
        const std::size_t key = line.find("force_law:");
        if (key == std::string::npos) continue;
        strength[w] = 150 + 60 * w;  // weak enough that some bounds hold in the frames below
        withStrengths += line.substr(0, key) + "strength: " + std::to_string(150 + 60 * w) + "\n";
        ++w;
    }
    ASSERT_EQ(w, wires);
    const Model model = readModelText(withStrengths, "arm26_strength.yaml");
    const std::vector<SpatialVector> noLoads(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
    for (const std::string method : {"lp", "qp"}) {
        SCOPED_TRACE(method);
        TensionAnalysisOptions options;
        options.method = method;
        options.useMusclePhysiology = false;
        TensionAnalysis fromModel(model, options);
        options.maxTension = strength;
        TensionAnalysis fromOptions(arm.model, options);
        std::mt19937 rng(11);
        std::uniform_real_distribution<double> angle(0.2, 1.2), rate(-3, 3);
        int bounded = 0;
        for (int frame = 0; frame < 20; ++frame) {
            Eigen::VectorXd q(model.getNumQ()), u(model.getNumU()), udot(model.getNumU());
            for (Eigen::Index i = 0; i < q.size(); ++i) q[i] = angle(rng);
            for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = rate(rng), udot[i] = rate(rng);
            const Eigen::VectorXd tension = fromModel.calcFrame(q, u, udot, noLoads).tension;
            const Eigen::VectorXd reference = fromOptions.calcFrame(q, u, udot, noLoads).tension;
            EXPECT_LT((tension - reference).norm(), 1e-9 * (1 + reference.norm())) << "frame " << frame;
            EXPECT_TRUE((tension.array() >= -1e-9).all() && (tension.array() <= strength.array() + 1e-6).all())
                << tension.transpose();
            bounded += ((strength - tension).array() < 1e-6).any() ? 1 : 0;
        }
        EXPECT_GT(bounded, 0) << "no frame reached a strength, so the test could not tell the bounds apart";
    }
}

// The model's force elements act before the wires share the rest, as OpenSim's static optimization keeps
// every force it does not override: arm26 with an elbow limit spring (reached from 1 rad) asks the wires for
// inverse dynamics' torques less the limit's, which OpenSim's CoordinateLimitForce formula gives.
TEST(TensionAnalysis, ForceElementsActBeforeTheWiresShare) {
    std::ifstream file(test::sourcePath("models/arm26.yaml"));
    std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    text += "force_elements:\n  - {type: coordinate_limit, name: elbow_limit, coordinate: r_elbow, upper_stiffness: 50, "
            "upper_limit: 1.0, lower_stiffness: 50, lower_limit: 0, damping: 2, transition: 0.2}\n";
    const Model model = readModelText(text, "arm26_with_limit.yaml");
    const Model bare = test::loadArm26().model;
    TensionAnalysisOptions options;
    options.method = "qp";
    options.maxTension = Eigen::VectorXd::Constant(model.getNumWires(), 2000);
    options.useMusclePhysiology = false;
    TensionAnalysis withLimit(model, options), without(bare, options);
    const int elbowQ = model.findCoordinateIndex("r_elbow");
    const CoordinateLimitForce& limit = model.getForceElements().coordinateLimits.front();
    const std::vector<SpatialVector> noLoads(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
    Eigen::VectorXd q = model.getDefaultQ(), u = Eigen::VectorXd::Constant(model.getNumU(), 0.3);
    const Eigen::VectorXd udot = Eigen::VectorXd::Constant(model.getNumU(), -0.2);
    for (double elbow : {0.5, 1.1, 1.3}) {
        q[elbowQ] = elbow;
        Eigen::VectorXd expected = without.calcFrame(q, u, udot, noLoads).tau;
        expected[limit.u] -= calcCoordinateLimitForce(limit, elbow, u[limit.u]);
        EXPECT_LT((withLimit.calcFrame(q, u, udot, noLoads).tau - expected).norm(), 1e-12) << elbow;
    }
    EXPECT_NE(calcCoordinateLimitForce(limit, 1.3, 0.3), 0);
}

TEST(TensionAnalysis, RefusesWiresWithoutStrength) {
    const test::NamedModel arm = test::loadArm26();
    TensionAnalysisOptions options;  // no maxTension, spring-damper wires
    try {
        TensionAnalysis analysis(arm.model, options);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("wire '"), std::string::npos) << e.what();
    }
    EXPECT_THROW(TensionMethodRegistry::global().get("simplex"), Error);
}

}  // namespace
}  // namespace sinew
