// Inverse kinematics (tools/inverse_kinematics.cpp) against what it must reproduce: a pose whose markers it is
// given exactly, the first-order optimality of a constrained fit (finite differences of the cost along the
// loops' tangent space), coordinate ranges, locks and couplers, and OpenSim's own IK of a walk.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <random>

#include "sinew/core/coordinate_coupler.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/model_builder.hpp"
#include "support/random_model.hpp"
#include "sinew/tools/inverse_kinematics.hpp"
#include "support/error_assertions.hpp"

namespace sinew {
namespace {

// Three markers per link at random places within 10 cm of its origin.
std::vector<Marker> makeMarkers(const Model& model, std::mt19937& rng) {
    std::uniform_real_distribution<double> offset(-0.1, 0.1);
    std::vector<Marker> markers;
    for (int i = 0; i < model.getNumLinks(); ++i)
        for (int k = 0; k < 3; ++k)
            markers.push_back({model.getLink(i).name + "_m" + std::to_string(k), i,
                               Eigen::Vector3d(offset(rng), offset(rng), offset(rng)), ""});
    return markers;
}

std::vector<MarkerTask> allMarkers(const std::vector<Marker>& markers) {
    std::vector<MarkerTask> tasks;
    for (const Marker& m : markers) tasks.push_back({m.name, 1});
    return tasks;
}

Eigen::Matrix3Xd locateMarkers(const Model& model, const std::vector<Marker>& markers, const Eigen::VectorXd& q) {
    Data data(model);
    calcPositionKinematics(model, data, q);
    Eigen::Matrix3Xd located(3, static_cast<Eigen::Index>(markers.size()));
    for (std::size_t m = 0; m < markers.size(); ++m)
        located.col(static_cast<Eigen::Index>(m)) = calcMarkerLocation_G(data, markers[m]);
    return located;
}

// Largest distance between the links' origins and between their axes at two poses.
double calcPoseDifference(const Model& model, const Eigen::VectorXd& qa, const Eigen::VectorXd& qb) {
    Data a(model), b(model);
    calcPositionKinematics(model, a, qa);
    calcPositionKinematics(model, b, qb);
    double worst = 0;
    for (int i = 0; i < model.getNumLinks(); ++i) {
        const std::size_t k = static_cast<std::size_t>(i);
        worst = std::max({worst, (a.p_GB[k] - b.p_GB[k]).norm(), (a.R_GB[k] - b.R_GB[k]).norm()});
    }
    return worst;
}

Eigen::VectorXd perturb(const Model& model, const Eigen::VectorXd& q, double size, std::mt19937& rng) {
    std::normal_distribution<double> normal(0, size);
    Eigen::VectorXd u(model.getNumU());
    for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = normal(rng);
    return integrateCoordinates(model, q, u, 1.0);
}

TEST(InverseKinematics, RecoversAPoseFromItsExactMarkers) {
    for (unsigned seed = 1; seed <= 4; ++seed) {
        RandomModelOptions options;
        options.numLinks = 12;
        options.seed = seed;
        options.customJointFraction = 0.3;
        options.numWires = 0;
        const Model model = generateRandomModel(options);
        std::mt19937 rng(seed);
        const std::vector<Marker> markers = makeMarkers(model, rng);
        const Eigen::VectorXd truth = perturb(model, model.getDefaultQ(), 0.25, rng);
        InverseKinematicsOptions ikOptions;
        ikOptions.accuracy = 1e-8;  // m of marker motion in the last step
        InverseKinematicsSolver solver(model, markers, allMarkers(markers), {}, ikOptions);
        InverseKinematicsTargets targets{locateMarkers(model, markers, truth), Eigen::VectorXd()};
        Eigen::VectorXd q = model.getDefaultQ();
        const InverseKinematicsReport report = solver.solve(targets, q);
        EXPECT_TRUE(report.converged) << "seed " << seed;
        EXPECT_EQ(report.markersSeen, static_cast<int>(markers.size()));
        EXPECT_LE(report.rmsMarkerError, 1e-10) << "seed " << seed;
        EXPECT_LE(calcPoseDifference(model, q, truth), 1e-9) << "seed " << seed << " (" << report.iterations << " iterations)";
    }
}

// Orientation tasks alone (a frame on every link, turned from the link's by a random rotation), from the
// orientations of a pose: the solver turns every link back onto them (quadratic convergence to a zero
// residual, which only a right orientation Jacobian gives within a few iterations).
TEST(InverseKinematics, RecoversAPoseFromItsLinksOrientations) {
    for (unsigned seed = 1; seed <= 3; ++seed) {
        RandomModelOptions options;
        options.numLinks = 10;
        options.seed = seed;
        options.customJointFraction = 0.3;
        options.numWires = 0;
        const Model model = generateRandomModel(options);
        std::mt19937 rng(seed);
        const Eigen::VectorXd truth = perturb(model, model.getDefaultQ(), 0.25, rng);
        std::vector<OrientationTask> tasks;
        InverseKinematicsTargets targets{Eigen::Matrix3Xd(3, 0), Eigen::VectorXd(), {}};
        Data data(model);
        calcPositionKinematics(model, data, truth);
        std::normal_distribution<double> normal(0, 1);
        for (int i = 0; i < model.getNumLinks(); ++i) {
            const Eigen::Matrix3d R_BF =
                Eigen::AngleAxisd(1.0, Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized()).toRotationMatrix();
            tasks.push_back({model.getLink(i).name, R_BF, 0.01});
            targets.orientations.push_back(data.R_GB[static_cast<std::size_t>(i)] * R_BF);
        }
        InverseKinematicsOptions ikOptions;
        ikOptions.accuracy = 1e-10;
        InverseKinematicsSolver solver(model, {}, {}, {}, ikOptions, tasks);
        Eigen::VectorXd q = model.getDefaultQ();
        const InverseKinematicsReport report = solver.solve(targets, q);
        EXPECT_TRUE(report.converged) << "seed " << seed << ", " << report.iterations << " iterations";
        EXPECT_LE(report.iterations, 15) << "seed " << seed;
        EXPECT_EQ(report.orientationsSeen, model.getNumLinks());
        EXPECT_LE(report.maxOrientationError, 1e-10) << "seed " << seed;
    }
}

// Loops' gaps at q, and their Jacobian along u by central differences.
Eigen::VectorXd calcLoopGaps(const Model& model, const Eigen::VectorXd& q) {
    Data data(model);
    calcPositionKinematics(model, data, q);
    Eigen::VectorXd c(3 * static_cast<Eigen::Index>(model.getLoops().size()));
    for (std::size_t l = 0; l < model.getLoops().size(); ++l) {
        const Loop& loop = model.getLoops()[l];
        c.segment<3>(3 * static_cast<Eigen::Index>(l)) = calcMarkerLocation_G(data, {"", loop.linkA, loop.p_A, ""}) -
                                                         calcMarkerLocation_G(data, {"", loop.linkB, loop.p_B, ""});
    }
    return c;
}

Eigen::MatrixXd calcLoopJacobian(const Model& model, const Eigen::VectorXd& q, double h) {
    const int nu = model.getNumU();
    Eigen::MatrixXd G(3 * static_cast<Eigen::Index>(model.getLoops().size()), nu);
    for (int i = 0; i < nu; ++i) {
        const Eigen::VectorXd e = Eigen::VectorXd::Unit(nu, i) * h;
        G.col(i) = (calcLoopGaps(model, integrateCoordinates(model, q, e, 1)) -
                    calcLoopGaps(model, integrateCoordinates(model, q, -e, 1))) / (2 * h);
    }
    return G;
}

// A random model without wires and with two loops.
Model makeModelWithTwoLoops(int numLinks, unsigned seed, double customJointFraction = 0) {
    RandomModelOptions options;
    options.numLinks = numLinks;
    options.numLoops = 2;
    options.numWires = 0;
    options.customJointFraction = customJointFraction;
    options.seed = seed;
    return generateRandomModel(options);
}

// The part of the weighted marker cost's gradient at q (central differences) that no combination of the
// loops' normals explains: zero at a constrained optimum (KKT: g + G^T lambda = 0).
double calcUnexplainedSlope(const Model& model, const std::vector<Marker>& markers, const std::vector<MarkerTask>& tasks,
                            const Eigen::Matrix3Xd& observed, const Eigen::VectorXd& q) {
    auto cost = [&](const Eigen::VectorXd& qq) {
        const Eigen::Matrix3Xd p = locateMarkers(model, markers, qq);
        double sum = 0;
        for (std::size_t t = 0; t < tasks.size(); ++t)
            sum += 0.5 * tasks[t].weight * (p.col(static_cast<Eigen::Index>(t)) - observed.col(static_cast<Eigen::Index>(t))).squaredNorm();
        return sum;
    };
    const double h = 1e-6;
    const int nu = model.getNumU();
    Eigen::VectorXd gradient(nu);
    for (int i = 0; i < nu; ++i) {
        const Eigen::VectorXd e = Eigen::VectorXd::Unit(nu, i) * h;
        gradient[i] = (cost(integrateCoordinates(model, q, e, 1)) - cost(integrateCoordinates(model, q, -e, 1))) / (2 * h);
    }
    const Eigen::MatrixXd Gt = calcLoopJacobian(model, q, h).transpose();
    const Eigen::VectorXd lambda = Gt.completeOrthogonalDecomposition().solve(-gradient);
    std::printf("gradient %.2g, of which the loops leave %.2g unexplained\n", gradient.lpNorm<Eigen::Infinity>(),
                (gradient + Gt * lambda).lpNorm<Eigen::Infinity>());
    return (gradient + Gt * lambda).lpNorm<Eigen::Infinity>();
}

// With loops, markers 2 mm off a pose moved along the loops' tangent space (so that they almost close):
// the fit keeps every loop closed, and no motion that keeps them closed lowers the cost (the cost's
// gradient, by central differences, is a combination of the loops' normals).
TEST(InverseKinematics, KeepsLoopsClosedAtAConstrainedOptimum) {
    const Model model = makeModelWithTwoLoops(10, 5);
    std::mt19937 rng(11);
    const std::vector<Marker> markers = makeMarkers(model, rng);
    std::vector<MarkerTask> tasks = allMarkers(markers);
    for (std::size_t t = 0; t < tasks.size(); ++t) tasks[t].weight = 0.5 + static_cast<double>(t % 3);
    const Eigen::VectorXd q0 = model.getDefaultQ();
    const Eigen::MatrixXd tangent0 = Eigen::FullPivLU<Eigen::MatrixXd>(calcLoopJacobian(model, q0, 1e-6)).kernel();
    std::normal_distribution<double> normal(0, 1);
    Eigen::VectorXd along(tangent0.cols());
    for (Eigen::Index i = 0; i < along.size(); ++i) along[i] = normal(rng);
    const Eigen::VectorXd moved = integrateCoordinates(model, q0, 0.2 * tangent0 * along.normalized(), 1.0);
    Eigen::Matrix3Xd observed = locateMarkers(model, markers, moved);
    for (Eigen::Index m = 0; m < observed.cols(); ++m)
        observed.col(m) += 0.002 * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
    InverseKinematicsOptions ikOptions;
    ikOptions.accuracy = 1e-12;
    InverseKinematicsSolver solver(model, markers, tasks, {}, ikOptions);
    Eigen::VectorXd q = q0;
    const InverseKinematicsReport report = solver.solve({observed, Eigen::VectorXd()}, q);
    ASSERT_TRUE(report.converged) << report.iterations << " iterations, loops open by " << report.constraintViolation;
    EXPECT_LE(report.constraintViolation, 1e-10);
    EXPECT_LE(calcLoopGaps(model, q).lpNorm<Eigen::Infinity>(), 1e-10);
    std::printf("loops closed to %.2g m in %d iterations; marker RMS %.3g m\n", report.constraintViolation,
                report.iterations, report.rmsMarkerError);
    EXPECT_LE(calcUnexplainedSlope(model, markers, tasks, observed, q), 1e-8);
}

// Markers 5 cm off at random, on a model with loops and custom joints: no pose reaches them, and
// Gauss-Newton alone converges only linearly there (without the curvature: 37 iterations, and stopped with
// 4.9e-8 of the gradient unexplained). The solver's curvature of the residuals and loops (forward
// differences over the subtree each unknown moves) takes it to the constrained optimum (checked by central
// differences of the cost, as above) in 24.
TEST(InverseKinematics, ReachesAFarOptimumFastThroughTheResidualsCurvature) {
    const Model model = makeModelWithTwoLoops(12, 7, 0.3);
    std::mt19937 rng(3);
    const std::vector<Marker> markers = makeMarkers(model, rng);
    const std::vector<MarkerTask> tasks = allMarkers(markers);
    Eigen::Matrix3Xd observed = locateMarkers(model, markers, model.getDefaultQ());
    std::normal_distribution<double> normal(0, 0.05);
    for (Eigen::Index m = 0; m < observed.cols(); ++m) observed.col(m) += Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
    InverseKinematicsOptions ikOptions;
    ikOptions.accuracy = 1e-12;
    InverseKinematicsSolver solver(model, markers, tasks, {}, ikOptions);
    Eigen::VectorXd q = model.getDefaultQ();
    const InverseKinematicsReport report = solver.solve({observed, Eigen::VectorXd()}, q);
    std::printf("marker RMS %.3g m in %d iterations\n", report.rmsMarkerError, report.iterations);
    ASSERT_TRUE(report.converged) << report.iterations << " iterations";
    EXPECT_LE(report.iterations, 30);
    EXPECT_LE(calcUnexplainedSlope(model, markers, tasks, observed, q), 2e-8);
}

// A one-link pendulum on a custom joint: a clamped coordinate stops at its range, a locked one stays at its
// default, a coupled one follows its coupler, and a coordinate task pulls towards its target.
TEST(InverseKinematics, KeepsRangesLocksAndCouplers) {
    ModelBuilder builder("pendulum");
    LinkSpec link;
    link.name = "arm";
    link.mass = 1;
    link.inertia_Bcom = Eigen::Matrix3d::Identity() * 0.01;
    builder.addLink(link);
    JointSpec joint;
    joint.name = "shoulder";
    joint.type = JointType::Custom;
    joint.parent = "ground";
    joint.child = "arm";
    CoordinateSpec swing, twist, lift, slide;
    swing.name = "swing";
    swing.rangeMin = -0.2;
    swing.rangeMax = 0.3;
    swing.clamped = true;
    twist.name = "twist";
    twist.locked = true;
    twist.defaultValue = 0.1;
    lift.name = "lift";
    slide.name = "slide";
    joint.coordinates = {swing, twist, lift, slide};
    joint.transformAxes = {{Eigen::Vector3d::UnitZ(), "swing", {}}, {Eigen::Vector3d::UnitX(), "twist", {}},
                           {Eigen::Vector3d::UnitY(), "lift", {}},  {Eigen::Vector3d::UnitX(), "slide", {}},
                           {Eigen::Vector3d::UnitY(), "", {}},      {Eigen::Vector3d::UnitZ(), "", {}}};
    builder.addJoint(joint);
    builder.addCoupler({"slide_of_lift", "slide", "lift", Function::linear(0.05, 0.01), 1, ""});
    const Model model = builder.build();
    const std::vector<Marker> markers = {{"tip", 0, Eigen::Vector3d(0, -0.5, 0), ""},
                                         {"side", 0, Eigen::Vector3d(0.2, -0.3, 0.1), ""}};
    // Targets from a pose beyond the swing's range, with the twist off its lock.
    Eigen::VectorXd wanted = model.getDefaultQ();
    wanted << 0.6, -0.3, 0.4, 0;
    applyCoordinateCouplers(model, wanted);
    InverseKinematicsSolver solver(model, markers, allMarkers(markers), {{"lift", 10}});
    Eigen::VectorXd q = model.getDefaultQ();
    const InverseKinematicsReport report = solver.solve({locateMarkers(model, markers, wanted), Eigen::VectorXd::Constant(1, 0.2)}, q);
    EXPECT_TRUE(report.converged);
    EXPECT_NEAR(q[0], 0.3, 1e-12);  // the range's end
    EXPECT_EQ(q[1], 0.1);           // locked
    EXPECT_NEAR(q[3], 0.05 * q[2] + 0.01, 1e-15);  // coupled
    EXPECT_GT(q[2], 0.2);  // between the markers' 0.4 and the task's 0.2
    EXPECT_LT(q[2], 0.4);
}

TEST(InverseKinematics, FramesWarmStartAndUnseenMarkersLeaveCoordinatesWhereTheyWere) {
    RandomModelOptions options;
    options.numLinks = 6;
    options.topology = RandomModelOptions::Topology::Chain;
    options.numWires = 0;
    options.seed = 3;
    const Model model = generateRandomModel(options);
    std::mt19937 rng(3);
    const std::vector<Marker> markers = makeMarkers(model, rng);
    const Eigen::VectorXd first = perturb(model, model.getDefaultQ(), 0.3, rng);
    const Eigen::VectorXd second = perturb(model, first, 0.05, rng);
    InverseKinematicsTargets a{locateMarkers(model, markers, first), Eigen::VectorXd()};
    InverseKinematicsTargets b{locateMarkers(model, markers, second), Eigen::VectorXd()};
    // The last link's markers go unseen in the second frame: its joint has nothing to fit.
    for (Eigen::Index m = b.markers.cols() - 3; m < b.markers.cols(); ++m) b.markers(0, m) = std::nan("");
    InverseKinematicsSolver solver(model, markers, allMarkers(markers), {});
    const InverseKinematicsMotion motion = solveInverseKinematics(solver, model.getDefaultQ(), {a, b});
    ASSERT_EQ(motion.q.size(), 2u);
    EXPECT_LE(calcPoseDifference(model, motion.q[0], first), 1e-9);
    EXPECT_EQ(motion.reports[1].markersSeen, static_cast<int>(markers.size()) - 3);
    EXPECT_TRUE(std::isnan(motion.reports[1].markerErrors[motion.reports[1].markerErrors.size() - 1]));
    const Joint& last = model.getJoint(model.getNumLinks() - 1);
    EXPECT_LE((motion.q[1] - motion.q[0]).segment(last.qStart, last.nq).norm(), 1e-12);
}

TEST(InverseKinematics, RefusesBadTasksAndTargets) {
    RandomModelOptions options;
    options.numLinks = 3;
    options.numWires = 0;
    const Model model = generateRandomModel(options);
    const std::vector<Marker> markers = {{"m", 1, Eigen::Vector3d::Zero(), ""}};
    EXPECT_TRUE(test::throwsErrorAt([&] { InverseKinematicsSolver(model, markers, {{"nope", 1}}, {}); }, "",
                                  {"marker task 'nope'", "no such marker"}, "unknown marker"));
    EXPECT_TRUE(test::throwsErrorAt([&] { InverseKinematicsSolver(model, markers, {{"m", -1}}, {}); }, "",
                                  {"'m'", "weight"}, "negative weight"));
    const std::string quaternion = getCoordinateNames(model)[0];
    EXPECT_TRUE(test::throwsErrorAt([&] { InverseKinematicsSolver(model, markers, {{"m", 1}}, {{quaternion, 1}}); }, "",
                                  {quaternion, "quaternion"}, "coordinate task on a quaternion"));
    InverseKinematicsSolver solver(model, markers, {{"m", 1}}, {});
    Eigen::VectorXd q = model.getDefaultQ();
    EXPECT_TRUE(test::throwsErrorAt([&] { solver.solve({Eigen::Matrix3Xd::Zero(3, 2), Eigen::VectorXd()}, q); }, "",
                                  {"2 markers", "1 and 0"}, "wrong marker count"));
}

}  // namespace
}  // namespace sinew
