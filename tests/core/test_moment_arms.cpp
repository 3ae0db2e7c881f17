// Moment arms r = -dL/dq against central differences of the wire lengths over the elbow's angle (q = u
// there) and along the shoulder's mobilities, on paths with wraps, conditional and moving points.
#include <gtest/gtest.h>

#include <random>

#include "sinew/core/kinematics.hpp"
#include "sinew/core/moment_arms.hpp"
#include "sinew/core/wire_path.hpp"
#include "support/wrap_test_model.hpp"

namespace sinew {
namespace {

TEST(MomentArms, AreMinusTheLengthsDerivatives) {
    const Model model = test::loadWrapArm();
    const int elbowQ = model.getJoint(model.findLinkIndex("lower")).qStart;
    const int elbowU = model.getJoint(model.findLinkIndex("lower")).uStart;
    std::mt19937 rng(31);
    Data data(model);
    Eigen::MatrixXd R(model.getNumWires(), model.getNumU());
    int compared = 0;
    for (int trial = 0; trial < 40; ++trial) {
        const Eigen::VectorXd q = test::randomWrapArmPose(model, rng);
        calcPositionKinematics(model, data, q);
        calcWirePaths(model, data);
        calcMomentArms(model, data, R);
        auto lengthsAt = [&](const Eigen::VectorXd& qq) {
            calcPositionKinematics(model, data, qq);
            calcWirePaths(model, data);
            return Eigen::VectorXd(data.wireLength);
        };
        const double h = 1e-6;
        for (int i = 0; i < model.getNumU(); ++i) {
            const Eigen::VectorXd e = Eigen::VectorXd::Unit(model.getNumU(), i);
            Eigen::VectorXd plusQ = integrateCoordinates(model, q, e, h), minusQ = integrateCoordinates(model, q, e, -h);
            if (i == elbowU) {  // a pin: q itself moves, r = -dL/dq
                plusQ = q;
                minusQ = q;
                plusQ[elbowQ] += h;
                minusQ[elbowQ] -= h;
            }
            const Eigen::VectorXd dLdq = (lengthsAt(plusQ) - lengthsAt(minusQ)) / (2 * h);
            for (int w = 0; w < model.getNumWires(); ++w) {
                if (model.getWire(w).name == "over_ellipsoid") continue;  // OpenSim's plane: see test_wire_path_features
                // A step that switches a wrap or a point on or off is no derivative: it jumps by far more.
                if (std::abs(dLdq[w] + R(w, i)) > 1e-3) continue;
                EXPECT_NEAR(R(w, i), -dLdq[w], 1e-6) << model.getWire(w).name << " mobility " << i << " trial " << trial;
                ++compared;
            }
        }
    }
    EXPECT_GT(compared, 600);
}

}  // namespace
}  // namespace sinew
