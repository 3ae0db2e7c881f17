// Coordinate couplers in the core: filling dependent coordinates (against the functions written out by
// hand), moment arms along the constraint (against central differences of the wire length, allocation-
// free, and finite where the dependent coordinate stands still), the builder's refusals, and sinew's
// forward simulation holding the couplers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "sinew/core/coordinate_coupler.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/forward_simulation.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/model_builder.hpp"
#include "sinew/core/moment_arms.hpp"
#include "sinew/core/wire_path.hpp"
#include "support/allocation_counter.hpp"
#include "support/error_assertions.hpp"

namespace sinew {
namespace {

LinkSpec makeLink(const std::string& name) {
    LinkSpec link;
    link.name = name;
    link.mass = 1.5;
    link.com_B = Eigen::Vector3d(0.02, -0.15, 0.01);
    link.inertia_Bcom = Eigen::Vector3d(0.02, 0.004, 0.02).asDiagonal();
    link.where = name + ".link";
    return link;
}

JointSpec makeJoint(const std::string& name, JointType type, const std::string& parent, const std::string& child) {
    JointSpec joint;
    joint.name = name;
    joint.type = type;
    joint.parent = parent;
    joint.child = child;
    joint.p_PF = Eigen::Vector3d(0, -0.3, 0);
    joint.where = name + ".joint";
    return joint;
}

JointSpec makePin(const std::string& name, const std::string& parent, const std::string& child, const Eigen::Vector3d& axis) {
    JointSpec joint = makeJoint(name, JointType::Pin, parent, child);
    joint.axis = axis;
    return joint;
}

// A custom joint sliding along x by its one coordinate.
JointSpec makeSlider(const std::string& name, const std::string& parent, const std::string& child) {
    JointSpec joint = makeJoint(name, JointType::Custom, parent, child);
    for (int k = 0; k < 6; ++k) {
        TransformAxisSpec axis;
        axis.axis = Eigen::Vector3d::Unit(k % 3);
        if (k == 3) axis.coordinate = name + "_x";
        joint.transformAxes.push_back(axis);
    }
    CoordinateSpec coordinate;
    coordinate.name = name + "_x";
    joint.coordinates.push_back(coordinate);
    return joint;
}

CoordinateCouplerSpec makeCoupler(const std::string& name, const std::string& dependent, const std::string& independent,
                                  const Function& function, double scale) {
    return {name, dependent, independent, function, scale, name + ".coupler"};
}

// ground -hip(pin z)- a -slide(custom, x)- b -ankle(pin, tilted)- c, and a ball-jointed d on c, with
// slide_x = 0.5 (0.2 hip^2 - 0.1 hip + 0.05).
ModelBuilder makeChain() {
    ModelBuilder builder("coupled_chain");
    for (const char* name : {"a", "b", "c", "d"}) builder.addLink(makeLink(name));
    builder.addJoint(makePin("hip", "ground", "a", Eigen::Vector3d::UnitZ()));
    builder.addJoint(makeSlider("slide", "a", "b"));
    builder.addJoint(makePin("ankle", "b", "c", Eigen::Vector3d(0.3, 0.2, 1)));
    builder.addJoint(makeJoint("wrist", JointType::Ball, "c", "d"));
    builder.addCoupler(makeCoupler("slide_coupler", "slide_x", "hip", Function::polynomial({0.2, -0.1, 0.05}), 0.5));
    return builder;
}

// The chain with ankle = -0.7 hip + 0.1 too, and two wires spanning it.
ModelBuilder makeBuilder() {
    ModelBuilder builder = makeChain();
    builder.addCoupler(makeCoupler("ankle_coupler", "ankle", "hip", Function::linear(-0.7, 0.1), 1));
    WireSpec wire;
    wire.name = "front";
    wire.points = {{"a", Eigen::Vector3d(0.05, -0.05, 0.01), "p"}, {"b", Eigen::Vector3d(0.04, -0.2, 0), "p"},
                   {"c", Eigen::Vector3d(0.03, -0.1, 0.02), "p"}};
    wire.law.type = "prescribed_tension";
    wire.law.parameters.set("tension", {10});
    wire.where = "front.wire";
    builder.addWire(wire);
    wire.name = "back";
    wire.points = {{"a", Eigen::Vector3d(-0.05, -0.02, 0), "p"}, {"c", Eigen::Vector3d(-0.03, -0.2, -0.02), "p"}};
    builder.addWire(wire);
    return builder;
}

TEST(CoordinateCoupler, FillsDependentCoordinatesFromTheIndependentOnes) {
    const Model model = makeBuilder().build();
    ASSERT_EQ(model.getNumCouplers(), 2);
    const int hip = model.findCoordinateIndex("hip"), slide = model.findCoordinateIndex("slide_x"),
              ankle = model.findCoordinateIndex("ankle");
    for (double h : {-1.2, 0.0, 0.25, 0.9}) {
        Eigen::VectorXd q = Eigen::VectorXd::Constant(model.getNumQ(), 7.0);  // nonsense the call overwrites
        q[hip] = h;
        applyCoordinateCouplers(model, q);
        EXPECT_EQ(q[hip], h);
        EXPECT_NEAR(q[slide], 0.5 * (0.2 * h * h - 0.1 * h + 0.05), 1e-16);
        EXPECT_NEAR(q[ankle], -0.7 * h + 0.1, 1e-16);
        for (int i = 0; i < model.getNumQ(); ++i)
            if (i != hip && i != slide && i != ankle) {
                EXPECT_EQ(q[i], 7.0) << i;  // the ball's quaternion untouched
            }
    }
}

TEST(CoordinateCoupler, MomentArmsFollowTheChainRuleWithoutAllocating) {
    const Model model = makeBuilder().build();
    const int hip = model.findCoordinateIndex("hip"), slide = model.findCoordinateIndex("slide_x"),
              ankle = model.findCoordinateIndex("ankle");
    Data data(model);
    Eigen::MatrixXd R(model.getNumWires(), model.getNumU());
    auto lengths = [&](double h) {
        Eigen::VectorXd q = model.getDefaultQ();
        q[hip] = h;
        applyCoordinateCouplers(model, q);
        calcPositionKinematics(model, data, q);
        calcWirePaths(model, data);
        return Eigen::VectorXd(data.wireLength);
    };
    const double step = 1e-5;
    for (double h : {-1.2, -0.4, 0.25, 0.9}) {
        const Eigen::VectorXd dL = lengths(h + step) - lengths(h - step);
        lengths(h);
        const long long before = test::getAllocationCount();
        calcMomentArms(model, data, R);
        EXPECT_EQ(test::getAllocationCount(), before);
        ASSERT_TRUE(R.allFinite());
        EXPECT_LT((R.col(hip) + dL / (2 * step)).lpNorm<Eigen::Infinity>(), 1e-8) << "hip " << h;
        // The ankle moves by -0.7 dhip; the slide by 0.5 (0.4 h - 0.1) dhip, which is 0 at h = 0.25.
        EXPECT_LT((R.col(ankle) + dL / (-0.7 * 2 * step)).lpNorm<Eigen::Infinity>(), 1e-8) << "ankle " << h;
        const double slideRate = 0.5 * (0.4 * h - 0.1);
        if (slideRate == 0) {
            EXPECT_TRUE(R.col(slide).isZero(0)) << "where the dependent coordinate stands still its column is 0";
        } else {
            EXPECT_LT((R.col(slide) + dL / (slideRate * 2 * step)).lpNorm<Eigen::Infinity>(), 1e-8) << "slide " << h;
        }
    }
}

TEST(CoordinateCoupler, BuilderRefusesBadCouplers) {
    struct Case {
        CoordinateCouplerSpec coupler;
        std::vector<std::string> words;
    };
    const Function f = Function::linear(1, 0);
    const std::vector<Case> cases = {
        {makeCoupler("c1", "knee", "hip", f, 1), {"coupler 'c1' dependent", "unknown coordinate 'knee'"}},
        {makeCoupler("c1", "wrist_qx", "hip", f, 1), {"coupler 'c1' dependent", "wrist_qx", "quaternion"}},
        {makeCoupler("c1", "hip", "hip", f, 1), {"coupler 'c1'", "'hip' cannot depend on itself"}},
        {makeCoupler("c1", "slide_x", "ankle", f, 1), {"coupler 'c1'", "'slide_x'", "already", "slide_coupler"}},
        {makeCoupler("c1", "hip", "slide_x", f, 1), {"coupler 'c1'", "chain"}},
        {makeCoupler("c1", "ankle", "slide_x", f, 1), {"chain"}},
        {makeCoupler("c1", "ankle", "hip", f, std::nan("")), {"coupler 'c1'", "scale factor must be finite"}},
        {makeCoupler("slide_coupler", "ankle", "hip", f, 1), {"duplicate coupler name 'slide_coupler'"}},
    };
    for (const Case& c : cases) {
        ModelBuilder builder = makeChain();
        builder.addCoupler(c.coupler);
        EXPECT_TRUE(test::throwsErrorAt<ModelError>([&] { builder.build(); }, c.coupler.where, c.words, c.coupler.name));
    }
}

// sinew's engine enforces the couplers (multipliers on top of the tree's solve): along a 1 s simulation from
// random speeds (projected onto the couplers) the dependent coordinates stay on q_dep = s f(q_ind), and with
// no wires the energy is conserved.
TEST(CoordinateCoupler, SinewSimulationHoldsCouplersAndConservesEnergy) {
    ModelBuilder builder = makeChain();
    builder.addCoupler(makeCoupler("ankle_coupler", "ankle", "hip", Function::linear(-0.7, 0.1), 1));
    const Model model = builder.build();
    ForwardSimulationOptions options;
    options.accuracy = 1e-10;
    options.initialSpeeds = Eigen::VectorXd::LinSpaced(model.getNumU(), -1.5, 2.0);
    double worstGap = 0;
    const SimulationSummary summary = simulateForwardSinew(model, options, [&](const SimulationFrame& frame) {
        for (const CoordinateCoupler& c : model.getCouplers())
            worstGap = std::max(worstGap, std::abs(frame.q[c.dependentQ] - c.scaleFactor * c.function.calcValue(frame.q[c.independentQ])));
    });
    ASSERT_GT(summary.peakKineticEnergy, 0.1);
    EXPECT_LE(worstGap, 1e-8);
    EXPECT_LE(summary.maxConstraintViolation, 1e-8);  // the couplers' gaps are part of it
    EXPECT_LE(summary.maxEnergyDrift / summary.peakKineticEnergy, 1e-7);
    std::printf("coupled chain, sinew's engine: coupler gap %.1e, relative energy drift %.1e over 1 s\n", worstGap,
                summary.maxEnergyDrift / summary.peakKineticEnergy);
}

}  // namespace
}  // namespace sinew
