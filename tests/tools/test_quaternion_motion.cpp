// Motions of ball and free joints read from coordinate tables (coordinate_table.hpp): the quaternion
// columns splined and turned into angular speeds must give the generalized forces of the motion itself,
// whatever sign each row's quaternions carry.
#include <gtest/gtest.h>

#include <random>

#include "sinew/core/coordinate_rates.hpp"
#include "sinew/core/data.hpp"
#include "sinew/core/inverse_dynamics.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/tools/coordinate_table.hpp"
#include "sinew/tools/inverse_dynamics_tool.hpp"
#include "support/error_assertions.hpp"
#include "support/random_model.hpp"

namespace sinew {
namespace {

Model makeModel() {
    RandomModelOptions options;
    options.numLinks = 7;
    options.rootJoint = JointType::Free;
    options.pinFraction = 0.3;
    options.numWires = 0;
    options.seed = 5;
    return generateRandomModel(options);
}

// q(t) = a + b sin(t) + c t² per coordinate; the table holds the quaternions normalised (as IK writes them)
// and, where `flipSigns`, every other row's quaternions negated.
struct SmoothMotion {
    Eigen::VectorXd a, b, c;
    Eigen::VectorXd q(double t) const { return a + std::sin(t) * b + t * t * c; }
    Eigen::VectorXd qdot(double t) const { return std::cos(t) * b + 2 * t * c; }
    Eigen::VectorXd qddot(double t) const { return -std::sin(t) * b + 2 * c; }
};

SmoothMotion makeMotion(const Model& model) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> uniform(-0.5, 0.5);
    SmoothMotion motion;
    motion.a = generateRandomCoordinates(model, rng);
    motion.b = Eigen::VectorXd::NullaryExpr(model.getNumQ(), [&] { return uniform(rng); });
    motion.c = Eigen::VectorXd::NullaryExpr(model.getNumQ(), [&] { return uniform(rng); });
    return motion;
}

StorageTable writeTable(const Model& model, const SmoothMotion& motion, int rows, double rate, bool flipSigns) {
    StorageTable table;
    table.name = "quaternion motion";
    table.columns = getCoordinateNames(model);
    for (int r = 0; r < rows; ++r) {
        const double t = r / rate;
        Eigen::VectorXd q = motion.q(t);
        for (const Joint& joint : model.getJoints()) {
            if (joint.type != JointType::Ball && joint.type != JointType::Free) continue;
            q.segment<4>(joint.qStart).normalize();
            if (flipSigns && r % 2) q.segment<4>(joint.qStart) *= -1;
        }
        table.times.push_back(t);
        table.rows.emplace_back(q.data(), q.data() + q.size());
    }
    return table;
}

class QuaternionMotion : public ::testing::TestWithParam<bool> {};

TEST_P(QuaternionMotion, GivesTheGeneralizedForcesOfTheMotion) {
    const Model model = makeModel();
    ASSERT_TRUE(hasQuaternionJoints(model));
    const SmoothMotion motion = makeMotion(model);
    const int rows = 241;
    const StorageTable table = writeTable(model, motion, rows, 240.0, GetParam());
    const StorageTable forces = runInverseDynamics(model, table, nullptr, {});
    ASSERT_EQ(forces.rows.size(), static_cast<std::size_t>(rows));
    ASSERT_EQ(forces.columns.size(), static_cast<std::size_t>(model.getNumU()));
    EXPECT_EQ(forces.columns[0], model.getJoint(0).name + "_wx_moment");
    EXPECT_EQ(forces.columns[3], model.getJoint(0).name + "_vx_force");

    Data data(model);
    Eigen::VectorXd u, udot, tau(model.getNumU());
    const std::vector<SpatialVector> noLoads(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
    double worst = 0, largest = 0;
    // The splines' end conditions bend the first and last rows: OpenSim's tools share them; the interior is
    // what the rates must reproduce.
    for (int r = 10; r < rows - 10; ++r) {
        const double t = forces.times[static_cast<std::size_t>(r)];
        calcSpeedsFromCoordinateRates(model, motion.q(t), motion.qdot(t), motion.qddot(t), u, udot);
        calcInverseDynamics(model, data, motion.q(t), u, udot, noLoads, tau);
        const Eigen::VectorXd ours =
            Eigen::Map<const Eigen::VectorXd>(forces.rows[static_cast<std::size_t>(r)].data(), model.getNumU());
        worst = std::max(worst, (ours - tau).lpNorm<Eigen::Infinity>());
        largest = std::max(largest, tau.lpNorm<Eigen::Infinity>());
    }
    EXPECT_GT(largest, 1.0);
    EXPECT_LT(worst, 1e-7 * largest) << "largest generalized force " << largest;
}

INSTANTIATE_TEST_SUITE_P(Signs, QuaternionMotion, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& flip) { return flip.param ? "flipped" : "kept"; });

TEST(QuaternionMotionErrors, NameTheRowOfAQuaternionOffUnitLength) {
    const Model model = makeModel();
    StorageTable table = writeTable(model, makeMotion(model), 20, 100.0, false);
    table.where = "kick.mot:7";
    for (int k = 0; k < 4; ++k) table.rows[4][static_cast<std::size_t>(k)] *= 1.5;
    EXPECT_TRUE(test::throwsErrorAt([&] { readCoordinateSamples(model, table); }, "kick.mot:7",
                                    {"row 4", model.getJoint(0).name + "_qw", "norm"}, "row 4 scaled by 1.5"));
}

}  // namespace
}  // namespace sinew
