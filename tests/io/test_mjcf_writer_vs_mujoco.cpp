// sinew's MJCF writer against libmujoco 2.2.2: random models written, loaded by MuJoCo, and held to sinew's
// own kinematics, wire geometry, loops and forward dynamics at random states, through the writer's qpos and
// qvel maps (docs/mjcf-export.md).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <random>
#include <unistd.h>

#include "support/mujoco_reference.hpp"
#include "support/random_model.hpp"

#include "sinew/core/assembly_schedule.hpp"
#include "sinew/core/data.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/forward_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/mjcf_model_writer.hpp"

namespace sinew {
namespace {

namespace fs = std::filesystem;

// A tree of the options' shape, written as MJCF into a fresh folder and loaded by MuJoCo.
struct WrittenModel {
    Model model;
    fs::path folder;
    std::unique_ptr<test::MujocoReference> mujoco;

    explicit WrittenModel(const RandomModelOptions& options) : model(generateRandomModel(options)) {
        folder = fs::temp_directory_path() / ("sinew_mjcf_writer_" + std::to_string(::getpid()) + "_" +
                                              std::to_string(options.seed));
        fs::create_directories(folder);
        writeMjcfModel(model, (folder / "model.xml").string());
        mujoco = std::make_unique<test::MujocoReference>(folder / "model.xml");
    }
    ~WrittenModel() { fs::remove_all(folder); }
};

RandomModelOptions makeOptions(int seed, int numLoops, int numWires) {
    RandomModelOptions options;
    options.numLinks = 12;
    options.topology = RandomModelOptions::Topology::RandomTree;
    options.pinFraction = 0.3;
    options.numLoops = numLoops;
    options.numWires = numWires;
    options.maxViaPoints = 2;
    options.damping = 0;
    options.seed = static_cast<unsigned>(seed);
    return options;
}

// A pose near the default one (wires there are taut: rest lengths are 0.9 to 1 of the default lengths).
Eigen::VectorXd makePose(const Model& model, std::mt19937& rng, double spread) {
    return integrateCoordinates(model, model.getDefaultQ(), generateRandomSpeeds(model, rng), spread);
}

TEST(MjcfWriter, MujocosBodiesTendonsAndTendonJacobianAreSinews) {
    for (int seed = 1; seed <= 3; ++seed) {
        const WrittenModel written(makeOptions(seed, 2, 40));
        const Model& model = written.model;
        test::MujocoReference& mujoco = *written.mujoco;
        ASSERT_EQ(mujoco.getNumBodies(), model.getNumLinks() + 1);
        ASSERT_EQ(mujoco.getNumDofs(), model.getNumU());
        ASSERT_EQ(mujoco.getNumTendons(), model.getNumWires());
        std::mt19937 rng(static_cast<unsigned>(seed));
        Data data(model);
        Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
        for (int pose = 0; pose < 4; ++pose) {
            const Eigen::VectorXd q = makePose(model, rng, 1.0);
            calcPositionKinematics(model, data, q);
            calcWirePaths(model, data);
            calcWireJacobian(model, data, J);
            mujoco.calcKinematics(toMujocoQpos(model, q));
            for (int i = 0; i < model.getNumLinks(); ++i) {
                const Joint& joint = model.getJoint(i);
                const std::string& name = model.getLink(i).name;
                // MuJoCo's body frame is the link's joint frame M.
                const Eigen::Vector3d p_GM = data.p_GB[i] + data.R_GB[i] * joint.p_BM;
                EXPECT_LE((mujoco.getBodyPosition(name) - p_GM).norm(), 1e-12) << name << " at pose " << pose;
                EXPECT_LE((mujoco.getBodyRotation(name) - data.R_GB[i] * joint.R_BM).norm(), 1e-12) << name;
            }
            for (int w = 0; w < model.getNumWires(); ++w) {
                const std::string& name = model.getWire(w).name;
                EXPECT_NEAR(mujoco.getTendonLength(name), data.wireLength[w], 1e-12) << name;
                // A length's gradient is a covector: it maps as generalized forces do.
                const Eigen::VectorXd row = toMujocoVelocity(model, q, J.row(w).transpose());
                EXPECT_LE((mujoco.getTendonJacobian(name) - row).lpNorm<Eigen::Infinity>(), 1e-10) << name;
            }
        }
    }
}

TEST(MjcfWriter, ConnectsAreTheLoopsClosedAtTheDefaultPose) {
    const WrittenModel written(makeOptions(4, 3, 0));
    const Model& model = written.model;
    EXPECT_LE(written.mujoco->calcConnectViolation(toMujocoQpos(model, model.getDefaultQ())), 1e-12);
    // Away from it, MuJoCo's gap is sinew's: the anchors on both links are the model's.
    std::mt19937 rng(4);
    Data data(model);
    for (int pose = 0; pose < 3; ++pose) {
        const Eigen::VectorXd q = makePose(model, rng, 0.5);
        calcPositionKinematics(model, data, q);
        double gap = 0;
        for (const Loop& loop : model.getLoops())
            for (int axis = 0; axis < 3; ++axis)
                gap = std::max(gap, std::abs((data.p_GB[loop.linkA] + data.R_GB[loop.linkA] * loop.p_A -
                                              data.p_GB[loop.linkB] - data.R_GB[loop.linkB] * loop.p_B)[axis]));
        ASSERT_GT(gap, 1e-3);
        EXPECT_NEAR(written.mujoco->calcConnectViolation(toMujocoQpos(model, q)), gap, 1e-12 + 1e-9 * gap);
    }
}

TEST(MjcfWriter, MujocosForwardDynamicsIsSinewsOnTreesWithTautWires) {
    for (int seed = 5; seed <= 7; ++seed) {
        const WrittenModel written(makeOptions(seed, 0, 40));
        const Model& model = written.model;
        std::mt19937 rng(static_cast<unsigned>(seed));
        const Eigen::VectorXd q = makePose(model, rng, 0.02);
        const Eigen::VectorXd u = generateRandomSpeeds(model, rng, 0.05);
        const Eigen::VectorXd tau = Eigen::VectorXd::Random(model.getNumU());
        Data data(model);
        calcPositionKinematics(model, data, q);
        calcVelocityKinematics(model, data, u);
        calcWirePaths(model, data);
        calcWireSpeeds(model, data);
        Eigen::VectorXd tensions(model.getNumWires());
        calcWireTensions(model, data, 0.0, tensions);
        // MuJoCo's tendon spring pushes below its rest length where sinew's wire goes slack: taut wires only.
        for (int w = 0; w < model.getNumWires(); ++w) ASSERT_GT(tensions[w], 0) << model.getWire(w).name;
        calcWireLinkForces(model, data, tensions);
        const AssemblySchedule schedule(model);
        ForwardDynamicsData fd(model, schedule);
        calcForwardDynamics(model, schedule, data, tau, data.F_G, fd);
        const Eigen::VectorXd qacc = written.mujoco->calcAccelerations(
            toMujocoQpos(model, q), toMujocoVelocity(model, q, u), toMujocoVelocity(model, q, tau));
        const Eigen::VectorXd udot = fromMujocoVelocity(model, q, qacc);
        EXPECT_LE((udot - fd.udot).lpNorm<Eigen::Infinity>(), 1e-10 * fd.udot.lpNorm<Eigen::Infinity>())
            << "seed " << seed << "\nsinew  " << fd.udot.transpose() << "\nMuJoCo " << udot.transpose();
    }
}

TEST(MjcfWriter, RefusesWhatMjcfCannotSayNamingIt) {
    RandomModelOptions options = makeOptions(8, 0, 10);
    options.numVirtualLinks = 1;
    try {
        writeMjcfText(generateRandomModel(options));
        FAIL() << "a virtual link was written";
    } catch (const Error& error) {
        EXPECT_NE(std::string(error.what()).find("virtual link"), std::string::npos) << error.what();
    }
    options = makeOptions(9, 0, 10);
    options.customJointFraction = 1;
    try {
        writeMjcfText(generateRandomModel(options));
        FAIL() << "a custom joint was written";
    } catch (const Error& error) {
        EXPECT_NE(std::string(error.what()).find("custom joint"), std::string::npos) << error.what();
    }
    const Model model = generateRandomModel(makeOptions(10, 1, 5));
    const MjcfExport document = writeMjcfText(model);
    ASSERT_EQ(document.notes.size(), 2u);  // the wires' slack and the soft loops
    EXPECT_NE(document.notes[0].find("5 spring_damper wires"), std::string::npos) << document.notes[0];
    EXPECT_NE(document.notes[1].find("1 loops"), std::string::npos) << document.notes[1];
    EXPECT_THROW(toMujocoQpos(model, Eigen::VectorXd::Zero(3)), Error);
}

}  // namespace
}  // namespace sinew
