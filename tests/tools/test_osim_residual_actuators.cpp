// OpenSim's PointActuator and TorqueActuator (residuals on a floating root) and states files in sinew's
// static optimization: the actuators' generalized forces against finite differences of the kinematics,
// gait2354 with pelvis residuals against inverse dynamics (the residuals balance the root), and a states
// file against the coordinates it was made from (../shared/data/opensim, skipped when absent).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "sinew/core/body_actuator.hpp"
#include "sinew/core/inverse_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "support/random_model.hpp"
#include "sinew/io/external_loads.hpp"
#include "sinew/io/osim_model.hpp"
#include "sinew/io/osim_model_converter.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/io/tool_setup.hpp"
#include "sinew/tools/coordinate_table.hpp"
#include "sinew/tools/measured_loads.hpp"
#include "sinew/tools/osim_states.hpp"
#include "sinew/tools/static_optimization_tool.hpp"
#include "sinew/tools/tension_analysis.hpp"
#include "support/error_assertions.hpp"

namespace sinew {
namespace {

namespace fs = std::filesystem;
const fs::path kOpenSim = fs::path(SINEW_SHARED_DIR) / "data" / "opensim";
const fs::path kGait = kOpenSim / "gait2354";
const fs::path kArm26 = kOpenSim / "arm26";

Model convertModel(const fs::path& osim) { return convertOsimModel(readOsimModel(osim.string())).model; }

fs::path makeTempDir(const std::string& name) {
    const fs::path dir = fs::path(::testing::TempDir()) / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

void writeText(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

// ---------------------------------------------------------------------------------------------------
// Generalized forces by virtual work: tau_i = F . (velocity of the point, or angular velocity, per unit
// u_i), the velocities by central differences of the position kinematics along q advanced by u = e_i.

struct Pose {
    Eigen::Matrix3d R;
    Eigen::Vector3d p;
};

Pose calcLinkPose(const Model& model, const Eigen::VectorXd& q, int link) {
    if (link == kGround) return {Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()};
    Data data(model);
    calcPositionKinematics(model, data, q);
    return {data.R_GB[static_cast<std::size_t>(link)], data.p_GB[static_cast<std::size_t>(link)]};
}

Eigen::VectorXd calcVirtualWorkColumn(const Model& model, const Eigen::VectorXd& q, const BodyActuator& a) {
    const double h = 1e-6;
    const Pose at = calcLinkPose(model, q, a.link);
    const Eigen::Vector3d axis_G = (a.axisInGround ? a.axis : Eigen::Vector3d(at.R * a.axis)).normalized();
    // The material point the force acts on, in the link frame (a ground point: the one there now).
    const Eigen::Vector3d s_B = a.pointInGround ? Eigen::Vector3d(at.R.transpose() * (a.point - at.p)) : a.point;
    Eigen::VectorXd tau(model.getNumU());
    for (int i = 0; i < model.getNumU(); ++i) {
        const Eigen::VectorXd e = Eigen::VectorXd::Unit(model.getNumU(), i);
        const Eigen::VectorXd qPlus = integrateCoordinates(model, q, e, h), qMinus = integrateCoordinates(model, q, e, -h);
        if (a.kind == BodyActuator::Kind::PointForce) {
            const Pose plus = calcLinkPose(model, qPlus, a.link), minus = calcLinkPose(model, qMinus, a.link);
            tau[i] = axis_G.dot((plus.p + plus.R * s_B) - (minus.p + minus.R * s_B)) / (2 * h);
            continue;
        }
        const auto angularVelocity = [&](int link) -> Eigen::Vector3d {
            const Eigen::AngleAxisd turn(calcLinkPose(model, qPlus, link).R * calcLinkPose(model, qMinus, link).R.transpose());
            return turn.angle() * turn.axis() / (2 * h);
        };
        tau[i] = axis_G.dot(angularVelocity(a.link) - angularVelocity(a.reactionLink));
    }
    return tau;
}

BodyActuator makeRandomActuator(const Model& model, std::mt19937& rng, int variant) {
    std::uniform_int_distribution<int> link(0, model.getNumLinks() - 1);
    std::uniform_real_distribution<double> unit(-1, 1);
    BodyActuator a;
    a.kind = variant % 2 == 0 ? BodyActuator::Kind::PointForce : BodyActuator::Kind::Torque;
    a.link = link(rng);
    a.axis = Eigen::Vector3d(unit(rng), unit(rng), unit(rng)) * 3;  // not unit length: it is normalised
    a.axisInGround = (variant / 2) % 2 == 1;
    a.point = Eigen::Vector3d(unit(rng), unit(rng), unit(rng)) * 0.3;
    a.pointInGround = (variant / 4) % 2 == 1;
    if (a.kind == BodyActuator::Kind::Torque) {
        a.reactionLink = (variant / 4) % 2 == 1 ? kGround : link(rng);
        if (variant % 8 == 7) std::swap(a.link, a.reactionLink);  // bodyA = ground: only the reaction acts
    }
    return a;
}

void expectColumnsMatchVirtualWork(const std::string& name, const Model& model, std::mt19937& rng, double& worst) {
    Data data(model);
    Eigen::VectorXd column(model.getNumU());
    for (int trial = 0; trial < 16; ++trial) {
        const Eigen::VectorXd q = generateRandomCoordinates(model, rng);
        calcPositionKinematics(model, data, q);
        const BodyActuator a = makeRandomActuator(model, rng, trial);
        calcBodyActuatorGeneralizedForce(model, data, a, column);
        const Eigen::VectorXd reference = calcVirtualWorkColumn(model, q, a);
        const double error = (column - reference).lpNorm<Eigen::Infinity>() / std::max(1.0, reference.lpNorm<Eigen::Infinity>());
        worst = std::max(worst, error);
        EXPECT_LT(error, 1e-7) << name << ", trial " << trial << "\nsinew     " << column.transpose()
                               << "\nreference " << reference.transpose();
    }
}

TEST(BodyActuator, GeneralizedForcesMatchVirtualWork) {
    std::mt19937 rng(13);
    double worst = 0;
    const JointType roots[] = {JointType::Free, JointType::Custom, JointType::Ball, JointType::Pin};
    for (int m = 0; m < 8; ++m) {
        RandomModelOptions options;
        options.seed = 500 + static_cast<unsigned>(m);
        options.numLinks = 3 + 2 * m;
        options.rootJoint = roots[m % 4];
        options.customJointFraction = 0.4;
        options.numWires = 0;
        expectColumnsMatchVirtualWork("random model " + std::to_string(m), generateRandomModel(options), rng, worst);
    }
    if (fs::exists(kGait)) expectColumnsMatchVirtualWork("gait2354", convertModel(kGait / "subject01_simbody.osim"), rng, worst);
    std::cout << "body actuator generalized forces vs virtual work: worst relative difference " << worst << "\n";
}

// ---------------------------------------------------------------------------------------------------
// gait2354 walking with the usual residuals on the pelvis (FX FY FZ at a pelvis point, MX MY MZ against
// ground) and reserves on the joints its muscles cannot balance (subtalar, mtp).

std::vector<ReserveActuator> makeGaitReserves(const Model& model) {
    std::vector<ReserveActuator> reserves;
    const int pelvis = model.findLinkIndex("pelvis");
    for (int axis = 0; axis < 3; ++axis) {
        ReserveActuator force{std::string("F") + "XYZ"[axis], 0, 4.0};
        force.body = BodyActuator{};
        force.body->link = pelvis;
        force.body->point = Eigen::Vector3d(-0.0707, 0, 0);  // the pelvis centre of mass
        force.body->axis = Eigen::Vector3d::Unit(axis);
        force.body->axisInGround = true;
        reserves.push_back(force);
        ReserveActuator torque{std::string("M") + "XYZ"[axis], 0, 2.0};
        torque.body = BodyActuator{};
        torque.body->kind = BodyActuator::Kind::Torque;
        torque.body->link = pelvis;
        torque.body->axis = Eigen::Vector3d::Unit(axis);
        torque.body->axisInGround = true;
        reserves.push_back(torque);
    }
    for (const char* coordinate : {"subtalar_angle_r", "subtalar_angle_l", "mtp_angle_r", "mtp_angle_l"})
        reserves.push_back({std::string(coordinate) + "_reserve", model.findCoordinateIndex(coordinate), 1.0});
    return reserves;
}

TEST(OsimResidualActuators, Gait2354ResidualsBalanceThePelvis) {
    if (!fs::exists(kGait)) GTEST_SKIP() << "../shared/data/opensim/gait2354 is absent (sinew's developer data)";
    const Model model = convertModel(kGait / "subject01_simbody.osim");
    const MeasuredLoads measured(model, readExternalLoads((kGait / "subject01_walk1_grf.xml").string()));
    const CoordinateTrajectory motion = preprocessCoordinateSamples(
        model, readCoordinateSamples(model, readStorageFile((kGait / "subject01_walk1_ik.mot").string())), 6, 0.4, 1.6);
    const int pelvis = model.findLinkIndex("pelvis");
    const Joint& root = model.getJoint(pelvis);
    ASSERT_EQ(root.parent, kGround);

    TensionAnalysisOptions options;
    options.method = "so";
    TensionAnalysis bare(model, options);
    options.reserves = makeGaitReserves(model);
    TensionAnalysis withResiduals(model, options);

    Data data(model);
    std::vector<SpatialVector> loads(static_cast<std::size_t>(model.getNumLinks()));
    Eigen::VectorXd tau(model.getNumU());
    int bareOptimal = 0, optimal = 0;
    double worstRoot = 0, largestRoot = 0;
    for (Eigen::Index f = 0; f < motion.times.size(); ++f) {
        const Eigen::VectorXd q = motion.q.row(f).transpose(), u = motion.qdot.row(f).transpose(),
                              udot = motion.qddot.row(f).transpose();
        calcAppliedLinkForces(model, &measured, data, motion.times[f], q, loads);
        bareOptimal += bare.calcFrame(q, u, udot, loads).status == DistributionStatus::Optimal;
        const TensionFrame& frame = withResiduals.calcFrame(q, u, udot, loads);
        optimal += frame.status == DistributionStatus::Optimal;
        EXPECT_EQ(frame.unactuatedResidual, 0) << "t = " << motion.times[f];
        for (Eigen::Index i = 0; i < root.nu; ++i) largestRoot = std::max(largestRoot, std::fabs(frame.tau[root.uStart + i]));

        // Independently: the residuals as the forces and torques they are, added to the measured loads;
        // inverse dynamics then needs nothing more on the root's six DOFs (muscles are internal forces).
        SpatialVector& F = loads[static_cast<std::size_t>(pelvis)];
        const Eigen::Vector3d p_G = data.p_GB[static_cast<std::size_t>(pelvis)] +
                                    data.R_GB[static_cast<std::size_t>(pelvis)] * Eigen::Vector3d(-0.0707, 0, 0);
        for (int axis = 0; axis < 3; ++axis) {
            const Eigen::Vector3d force = frame.reserveForce[2 * axis] * Eigen::Vector3d::Unit(axis);
            F.head<3>() += (p_G - data.p_GB[static_cast<std::size_t>(pelvis)]).cross(force) +
                           frame.reserveForce[2 * axis + 1] * Eigen::Vector3d::Unit(axis);
            F.tail<3>() += force;
        }
        calcInverseDynamics(model, data, q, u, udot, loads, tau);
        worstRoot = std::max(worstRoot, tau.segment(root.uStart, root.nu).lpNorm<Eigen::Infinity>());
    }
    const int frames = static_cast<int>(motion.times.size());
    std::cout << "gait2354 static optimization, " << frames << " frames: optimal " << bareOptimal
              << " without reserves, " << optimal << " with pelvis residuals and reserves; root generalized "
              << "forces up to " << largestRoot << ", left unbalanced by the residuals " << worstRoot << "\n";
    EXPECT_LT(bareOptimal, frames);  // the reason for the reserves: subtalar cannot be balanced
    EXPECT_EQ(optimal, frames);
    EXPECT_GT(largestRoot, 10.0);  // the root really needed the residuals
    EXPECT_LT(worstRoot, 1e-6 * largestRoot);
}

// The same through an unchanged OpenSim AnalyzeTool setup and force-set file, written here.
std::string makeAnalyzeSetup(const std::string& motionElement, const std::string& forceSetFiles, double start,
                             double end, double cutoff, const fs::path& model, const std::string& externalLoads) {
    return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<OpenSimDocument Version=\"40000\">\n<AnalyzeTool name=\"so\">\n"
           "<model_file>" + model.string() + "</model_file>\n<replace_force_set>false</replace_force_set>\n"
           "<force_set_files>" + forceSetFiles + "</force_set_files>\n<results_directory>results</results_directory>\n"
           "<initial_time>" + std::to_string(start) + "</initial_time>\n<final_time>" + std::to_string(end) +
           "</final_time>\n<AnalysisSet name=\"Analyses\"><objects>\n<StaticOptimization name=\"StaticOptimization\">"
           "<start_time>" + std::to_string(start) + "</start_time><end_time>" + std::to_string(end) + "</end_time>"
           "</StaticOptimization>\n</objects></AnalysisSet>\n<external_loads_file>" + externalLoads +
           "</external_loads_file>\n" + motionElement + "\n<lowpass_cutoff_frequency_for_coordinates>" +
           std::to_string(cutoff) + "</lowpass_cutoff_frequency_for_coordinates>\n</AnalyzeTool>\n</OpenSimDocument>\n";
}

const char* const kGaitActuators = R"(<?xml version="1.0" encoding="UTF-8"?>
<OpenSimDocument Version="40000">
<ForceSet name="gait2354_residuals">
<objects>
<PointActuator name="FX"><body>pelvis</body><point>-0.0707 0 0</point><direction>1 0 0</direction>
  <force_is_global>true</force_is_global><optimal_force>4</optimal_force></PointActuator>
<PointActuator name="FY"><body>/bodyset/pelvis</body><point>-0.0707 0 0</point><direction>0 1 0</direction>
  <force_is_global>true</force_is_global><optimal_force>4</optimal_force></PointActuator>
<PointActuator name="FZ"><body>pelvis</body><point>-0.0707 0 0</point><direction>0 0 1</direction>
  <force_is_global>true</force_is_global><optimal_force>4</optimal_force></PointActuator>
<TorqueActuator name="MX"><bodyA>pelvis</bodyA><bodyB>ground</bodyB><axis>1 0 0</axis><optimal_force>2</optimal_force></TorqueActuator>
<TorqueActuator name="MY"><bodyA>pelvis</bodyA><bodyB>/ground</bodyB><axis>0 1 0</axis><optimal_force>2</optimal_force></TorqueActuator>
<TorqueActuator name="MZ"><bodyA>pelvis</bodyA><bodyB>ground</bodyB><axis>0 0 1</axis><optimal_force>2</optimal_force></TorqueActuator>
<CoordinateActuator name="subtalar_r_reserve"><coordinate>subtalar_angle_r</coordinate><optimal_force>1</optimal_force></CoordinateActuator>
<CoordinateActuator name="subtalar_l_reserve"><coordinate>subtalar_angle_l</coordinate><optimal_force>1</optimal_force></CoordinateActuator>
<CoordinateActuator name="mtp_r_reserve"><coordinate>mtp_angle_r</coordinate><optimal_force>1</optimal_force></CoordinateActuator>
<CoordinateActuator name="mtp_l_reserve"><coordinate>mtp_angle_l</coordinate><optimal_force>1</optimal_force></CoordinateActuator>
</objects>
</ForceSet>
</OpenSimDocument>
)";

TEST(OsimResidualActuators, Gait2354SetupWithResidualsSolvesEveryFrame) {
    if (!fs::exists(kGait)) GTEST_SKIP() << "../shared/data/opensim/gait2354 is absent (sinew's developer data)";
    const fs::path dir = makeTempDir("sinew_so_gait_residuals");
    writeText(dir / "actuators.xml", kGaitActuators);
    const std::string motion = "<coordinates_file>" + (kGait / "subject01_walk1_ik.mot").string() + "</coordinates_file>";
    const std::string loads = (kGait / "subject01_walk1_grf.xml").string();
    writeText(dir / "setup.xml", makeAnalyzeSetup(motion, "actuators.xml", 0.4, 1.6, 6, kGait / "subject01_simbody.osim", loads));
    const std::vector<std::string> written = runStaticOptimizationTool(readAnalyzeSetup((dir / "setup.xml").string()), "", {});
    const StorageTable force = readStorageFile(written[0]), report = readStorageFile(written[2]);
    for (const char* name : {"FX", "FY", "FZ", "MX", "MY", "MZ", "subtalar_r_reserve", "mtp_l_reserve"})
        EXPECT_NE(std::find(force.columns.begin(), force.columns.end(), name), force.columns.end()) << name;
    ASSERT_EQ(report.times.size(), 73u);
    double worstResidual = 0;
    for (const std::vector<double>& row : report.rows) {
        EXPECT_EQ(row[0], 0) << "status";
        for (std::size_t c = 0; c < report.columns.size(); ++c)
            if (report.columns[c].find("_residual") != std::string::npos) worstResidual = std::max(worstResidual, std::fabs(row[c]));
    }
    EXPECT_LT(worstResidual, 1e-6);  // every DOF balanced, the pelvis's six by the residuals

    // A residual on a body the model lacks is refused at its line.
    std::string wrong = kGaitActuators;
    wrong.replace(wrong.find("<body>pelvis</body>"), 19, "<body>hips</body>");
    writeText(dir / "actuators.xml", wrong);
    EXPECT_TRUE(test::throwsErrorAt(
        [&] { runStaticOptimizationTool(readAnalyzeSetup((dir / "setup.xml").string()), "", {}); },
        (dir / "actuators.xml").string() + ":5", {"PointActuator 'FX'", "'hips'"}, wrong));
}

// ---------------------------------------------------------------------------------------------------
// States files: arm26's AnalyzeTool run from a states file holding exactly the q and u its coordinates
// give (the splines' values and derivatives at every processed row) must give the same forces.

StorageTable makeStates(const Model& model, const CoordinateTrajectory& trajectory, bool openSim3Labels) {
    StorageTable states;
    states.name = "states";
    for (const Coordinate& c : model.getCoordinates()) {
        const std::string path = "/jointset/" + model.getJoint(c.joint).name + "/" + c.name;
        states.columns.push_back(openSim3Labels ? c.name : path + "/value");
        states.columns.push_back(openSim3Labels ? c.name + "_u" : path + "/speed");
    }
    states.columns.push_back(openSim3Labels ? "BIClong.activation" : "/forceset/BIClong/activation");  // ignored
    for (Eigen::Index r = 0; r < trajectory.processedTimes.size(); ++r) {
        const double t = trajectory.processedTimes[r];
        std::vector<double> row;
        for (const SmoothingSpline& spline : trajectory.splines) {
            row.push_back(spline.calcValue(t));
            row.push_back(spline.calcDerivative(t, 1));
        }
        row.push_back(0.5);
        states.times.push_back(t);
        states.rows.push_back(row);
    }
    return states;
}

TEST(OsimStates, Arm26StatesFileGivesTheForcesOfItsCoordinates) {
    if (!fs::exists(kArm26)) GTEST_SKIP() << "../shared/data/opensim/arm26 is absent (sinew's developer data)";
    const fs::path dir = makeTempDir("sinew_so_arm26_states");
    AnalyzeSetup setup = readAnalyzeSetup((kArm26 / "arm26_Setup_StaticOptimization.xml").string());
    const StorageTable fromCoordinates = readStorageFile(runStaticOptimizationTool(setup, (dir / "coordinates").string(), {})[0]);

    const Model model = convertModel(setup.modelFile);
    const CoordinateTrajectory trajectory = preprocessCoordinateSamples(
        model, readCoordinateSamples(model, readStorageFile(setup.coordinatesFile)),
        setup.lowpassCutoffFrequencyForCoordinates, setup.initialTime, setup.finalTime);
    for (const bool openSim3 : {false, true}) {
        const fs::path statesFile = dir / (openSim3 ? "states3.sto" : "states4.sto");
        writeStorageFile(makeStates(model, trajectory, openSim3), statesFile.string());
        AnalyzeSetup fromStatesSetup = setup;
        fromStatesSetup.statesFile = statesFile.string();
        std::vector<std::string> notes;
        const StorageTable fromStates = readStorageFile(runStaticOptimizationTool(
            fromStatesSetup, (dir / "states").string(), [&](const std::string& note) { notes.push_back(note); })[0]);
        EXPECT_NE(std::find(notes.begin(), notes.end(), "coordinates_file is ignored: states_file gives the motion"),
                  notes.end());
        ASSERT_EQ(fromStates.columns, fromCoordinates.columns);
        ASSERT_EQ(fromStates.times.size(), fromCoordinates.times.size());
        double worst = 0;
        for (std::size_t r = 0; r < fromStates.rows.size(); ++r) {
            EXPECT_EQ(fromStates.times[r], fromCoordinates.times[r]);
            for (std::size_t c = 0; c < fromStates.columns.size(); ++c)
                worst = std::max(worst, std::fabs(fromStates.rows[r][c] - fromCoordinates.rows[r][c]));
        }
        std::cout << "arm26 from a states file (" << (openSim3 ? "OpenSim 3" : "OpenSim 4") << " labels), "
                  << fromStates.times.size() << " frames: largest force difference " << worst << " N\n";
        // Same q, u and spline data: only the text round trip and rounding differ.
        EXPECT_LT(worst, 1e-6);
    }

    // The file's speeds are what the forces follow (not derivatives of its values): 5 % faster, other forces.
    StorageTable states = makeStates(model, trajectory, false);
    for (std::vector<double>& row : states.rows)
        for (std::size_t c = 1; c + 1 < row.size(); c += 2) row[c] *= 1.05;
    writeStorageFile(states, (dir / "faster.sto").string());
    AnalyzeSetup fasterSetup = setup;
    fasterSetup.statesFile = (dir / "faster.sto").string();
    const StorageTable faster = readStorageFile(runStaticOptimizationTool(fasterSetup, (dir / "faster").string(), {})[0]);
    double change = 0;
    for (std::size_t r = 0; r < faster.rows.size(); ++r)
        for (std::size_t c = 0; c < faster.columns.size(); ++c)
            change = std::max(change, std::fabs(faster.rows[r][c] - fromCoordinates.rows[r][c]));
    EXPECT_GT(change, 1.0);

    // A missing speed column and a table in degrees are refused at the table's header.
    states = makeStates(model, trajectory, false);
    const std::size_t speed = static_cast<std::size_t>(
        std::find(states.columns.begin(), states.columns.end(), "/jointset/r_elbow/r_elbow_flex/speed") - states.columns.begin());
    ASSERT_LT(speed, states.columns.size());
    states.columns[speed] = "/jointset/r_elbow/r_elbow_flex/accel";
    writeStorageFile(states, (dir / "bad.sto").string());
    EXPECT_TRUE(test::throwsErrorAt([&] { readOsimStates(model, readStorageFile((dir / "bad.sto").string())); },
                                    (dir / "bad.sto").string(), {"no speed column", "'r_elbow_flex'"}, "bad.sto"));
    states = makeStates(model, trajectory, false);
    states.inDegrees = true;
    writeStorageFile(states, (dir / "degrees.sto").string());
    EXPECT_TRUE(test::throwsErrorAt([&] { readOsimStates(model, readStorageFile((dir / "degrees.sto").string())); },
                                    (dir / "degrees.sto").string(), {"degrees"}, "degrees.sto"));
}

}  // namespace
}  // namespace sinew
