// The house rule: the calc* algorithms allocate nothing once Data and ForwardDynamicsData are sized.
#include <gtest/gtest.h>

#include <random>

#include "sinew/core/forward_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "support/allocation_counter.hpp"
#include "support/test_models.hpp"

namespace sinew {
namespace {

TEST(AllocationFree, CalcFunctionsAllocateNothing) {
    if (!test::isCountingAllocations()) GTEST_SKIP() << "allocations are not counted under AddressSanitizer";
    {  // the counter itself counts
        const long long start = test::getAllocationCount();
        Eigen::VectorXd probe = Eigen::VectorXd::LinSpaced(64, 0, 1);
        volatile double sink = probe.sum();
        (void)sink;
        ASSERT_GT(test::getAllocationCount(), start);
    }
    RandomModelOptions o;
    o.numLinks = 30;
    o.numLoops = 3;
    o.numWires = 120;
    o.seed = 9;
    const Model model = generateRandomModel(o);
    std::mt19937 rng(1);
    const Eigen::VectorXd q = generateRandomCoordinates(model, rng), u = generateRandomSpeeds(model, rng);
    const Eigen::VectorXd tau = generateRandomSpeeds(model, rng);
    Data data(model);
    Eigen::VectorXd tensions(model.getNumWires()), generalized(model.getNumU());
    Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
    for (const auto kind : {AssemblySchedule::Kind::Serial, AssemblySchedule::Kind::Balanced}) {
        const AssemblySchedule schedule(model, kind);
        ForwardDynamicsData fd(model, schedule);
        const long long before = test::getAllocationCount();
        calcPositionKinematics(model, data, q);
        calcVelocityKinematics(model, data, u);
        calcWirePaths(model, data);
        calcWireSpeeds(model, data);
        calcWireTensions(model, data, 0.0, tensions);
        calcWireJacobian(model, data, J);
        calcWireGeneralizedForces(model, data, tensions, generalized);
        calcWireLinkForces(model, data, tensions);
        calcForwardDynamics(model, schedule, data, tau, data.F_G, fd);
        EXPECT_EQ(test::getAllocationCount() - before, 0);
        EXPECT_TRUE(fd.udot.allFinite());
    }
}

}  // namespace
}  // namespace sinew
