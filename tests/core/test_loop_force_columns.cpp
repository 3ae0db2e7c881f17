// A loop's force columns against central finite differences of its gap p_B - p_A (the columns are
// (d gap/du)^T), and its force pair against the power it does on the links' motion, on random models with
// loops, virtual links and free, ball and weld roots.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "sinew/core/kinematics.hpp"
#include "sinew/core/loop_force_columns.hpp"
#include "support/error_assertions.hpp"
#include "support/test_models.hpp"

namespace sinew {
namespace {

// The loop's gap in ground: link B's point less link A's. Fills Data's position kinematics at q.
Eigen::Vector3d calcGap(const Model& model, Data& data, const Eigen::VectorXd& q, const Loop& loop) {
    calcPositionKinematics(model, data, q);
    const auto point = [&](int link, const Eigen::Vector3d& p_B) -> Eigen::Vector3d {
        const std::size_t k = static_cast<std::size_t>(link);
        return data.p_GB[k] + data.R_GB[k] * p_B;
    };
    return point(loop.linkB, loop.p_B) - point(loop.linkA, loop.p_A);
}

TEST(LoopForceColumns, AreTheGapsJacobianTransposedByFiniteDifferences) {
    std::mt19937 rng(17);
    int loopsChecked = 0;
    for (const test::NamedModel& m : test::makeRandomModels(30, true)) {
        const Model& model = m.model;
        Data data(model);
        for (int trial = 0; trial < 2; ++trial) {
            const Eigen::VectorXd q = generateRandomCoordinates(model, rng);
            for (int l = 0; l < model.getNumLoops(); ++l) {
                const Loop& loop = model.getLoop(l);
                // Central differences along each mobility, q moved on its manifold (quaternions rotate exactly).
                const double h = 1e-6;
                Eigen::MatrixXd G(3, model.getNumU());
                for (int i = 0; i < model.getNumU(); ++i) {
                    const Eigen::VectorXd e = Eigen::VectorXd::Unit(model.getNumU(), i);
                    G.col(i) = (calcGap(model, data, integrateCoordinates(model, q, e, h), loop) -
                                calcGap(model, data, integrateCoordinates(model, q, e, -h), loop)) /
                               (2 * h);
                }
                calcPositionKinematics(model, data, q);
                Eigen::MatrixXd columns(model.getNumU(), 3);
                calcLoopForceColumns(model, data, l, columns);
                ASSERT_GT(G.norm(), 0) << m.name;
                EXPECT_LE((columns - G.transpose()).norm() / std::max(G.norm(), 1e-3), 1e-6)
                    << m.name << " loop " << loop.name << " trial " << trial;
                ++loopsChecked;
            }
        }
    }
    EXPECT_GE(loopsChecked, 40);
}

// The pair's power on the links' motion (moment . w + force . v of each link's origin) is f . d gap/dt.
TEST(LoopForceColumns, ForcePairDoesThePowerOfTheGapRate) {
    std::mt19937 rng(19);
    std::uniform_real_distribution<double> component(-100, 100);
    int loopsChecked = 0;
    for (const test::NamedModel& m : test::makeRandomModels(15, true)) {
        const Model& model = m.model;
        Data data(model);
        calcPositionKinematics(model, data, generateRandomCoordinates(model, rng));
        calcVelocityKinematics(model, data, generateRandomSpeeds(model, rng));
        for (int l = 0; l < model.getNumLoops(); ++l) {
            const Loop& loop = model.getLoop(l);
            const Eigen::Vector3d f(component(rng), component(rng), component(rng));
            std::vector<SpatialVector> F(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
            addLoopForce(model, data, l, f, F);
            double power = 0, scale = 0;  // scale: the sum of the terms' sizes, for roundoff
            for (std::size_t k = 0; k < F.size(); ++k) {
                const double moment = F[k].head<3>().dot(data.w_GB[k]), force = F[k].tail<3>().dot(data.v_GB[k]);
                power += moment + force;
                scale += std::abs(moment) + std::abs(force);
            }
            ASSERT_GT(scale, 0) << m.name;
            const auto pointVelocity = [&](int link, const Eigen::Vector3d& p_B) -> Eigen::Vector3d {
                const std::size_t k = static_cast<std::size_t>(link);
                return data.v_GB[k] + data.w_GB[k].cross(data.R_GB[k] * p_B);
            };
            const double expected = f.dot(pointVelocity(loop.linkB, loop.p_B) - pointVelocity(loop.linkA, loop.p_A));
            EXPECT_NEAR(power, expected, 1e-13 * scale) << m.name;
            ++loopsChecked;
        }
    }
    EXPECT_GE(loopsChecked, 10);
}

TEST(LoopForceColumns, RefusesABadLoopOrSize) {
    const test::NamedModel m = test::makeRandomModels(30, true)[1];
    ASSERT_EQ(m.model.getNumLoops(), 1) << m.name;
    Data data(m.model);
    calcPositionKinematics(m.model, data, Eigen::VectorXd::Zero(m.model.getNumQ()));
    Eigen::MatrixXd columns(m.model.getNumU(), 3);
    EXPECT_TRUE(test::throwsErrorAt([&] { calcLoopForceColumns(m.model, data, 1, columns); },
                                    "loop force columns of model", {"loop 1", "expected 0 to 0"}, m.name));
    Eigen::MatrixXd wrong(m.model.getNumU(), 2);
    EXPECT_TRUE(test::throwsErrorAt([&] { calcLoopForceColumns(m.model, data, 0, wrong); },
                                    "loop force columns of model", {"x 2", "expected nu x 3"}, m.name));
}

}  // namespace
}  // namespace sinew
