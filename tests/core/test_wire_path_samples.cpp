// Sampled wire paths (core/wire_path_samples.cpp) against calcWirePaths: every point sampled on a wrap lies
// on its object's surface, the samples start and end at the wire's ends and pass its path points, and the
// polyline through them has the wire's length, over OpenSim's cylinders, spheres and ellipsoids (the wrap
// arm) and MuJoCo's spheres and cylinders (random legs), at random poses.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/core/wire_path_samples.hpp"
#include "support/mujoco_wrap_model.hpp"
#include "support/wrap_test_model.hpp"

namespace sinew {
namespace {

double calcPolylineLength(const std::vector<WirePathSample>& samples) {
    double length = 0;
    for (std::size_t i = 0; i + 1 < samples.size(); ++i) length += (samples[i + 1].p_G - samples[i].p_G).norm();
    return length;
}

// The implicit surface equation of the object at a point in ground, in units of its radius: 0 on it.
double calcSurfaceError(const Data& data, const WrapObject& object, const Eigen::Vector3d& p_G) {
    const std::size_t b = static_cast<std::size_t>(object.link);
    const Eigen::Vector3d x = (data.R_GB[b] * object.R_BW).transpose() * (p_G - data.p_GB[b] - data.R_GB[b] * object.p_BW);
    switch (object.shape) {
        case WrapShape::Sphere: return x.norm() / object.radius - 1;
        case WrapShape::Cylinder: return x.head<2>().norm() / object.radius - 1;
        case WrapShape::Ellipsoid: return x.cwiseQuotient(object.radii).norm() - 1;
    }
    return 1;
}

struct Worst {
    double surface = 0, length = 0;
    int arcs = 0;                      // wire poses with an arc sampled
    int arcPoints[3] = {0, 0, 0};      // points sampled strictly on arcs, by WrapShape
};

// At the pose in `data` (calcWirePaths done): samples of every wire, fine and coarse.
void checkSamples(const Model& model, const Data& data, Worst& worst) {
    std::vector<WirePathSample> fine, coarse;
    for (int w = 0; w < model.getNumWires(); ++w) {
        const Wire& wire = model.getWire(w);
        calcWirePathSamples(model, data, w, 1e-3, fine);
        calcWirePathSamples(model, data, w, 0.1, coarse);
        const std::size_t first = static_cast<std::size_t>(wire.firstPoint);
        const std::size_t last = first + static_cast<std::size_t>(wire.numPoints) - 1;
        ASSERT_GE(fine.size(), 2u);
        EXPECT_EQ((fine.front().p_G - data.p_GP[first]).norm(), 0.0) << wire.name;
        EXPECT_EQ((fine.back().p_G - data.p_GP[last]).norm(), 0.0) << wire.name;
        // Every path point is among the samples, in order.
        std::size_t at = 0;
        const int size = wire.isPolyline() ? wire.numPoints : data.wirePathSize[static_cast<std::size_t>(w)];
        for (int i = 0; i < size && !wire.isPolyline(); ++i) {
            const Data::WirePathPoint& point = data.wirePath[static_cast<std::size_t>(data.wirePathStart[w] + i)];
            while (at < coarse.size() && coarse[at].p_G != point.p_G) ++at;
            EXPECT_LT(at, coarse.size()) << wire.name << " misses path point " << i;
        }
        for (const WirePathSample& s : fine) {
            if (s.wrap < 0) continue;
            const WireWrap& wrap = wire.wraps[static_cast<std::size_t>(s.wrap)];
            const WrapObject& object = model.getWrapObjects()[static_cast<std::size_t>(wrap.object)];
            EXPECT_EQ(s.link, object.link);
            ++worst.arcPoints[static_cast<int>(object.shape)];
            worst.surface = std::max(worst.surface, std::abs(calcSurfaceError(data, object, s.p_G)));
        }
        const double length = data.wireLength[w];
        worst.length = std::max(worst.length, std::abs(calcPolylineLength(fine) - length) / length);
        EXPECT_NEAR(calcPolylineLength(fine), length, 1e-6 * length) << wire.name;
        // Chords cut corners: coarser samples are shorter, by the chord error of 0.1 rad steps at most.
        EXPECT_LE(calcPolylineLength(coarse), length * (1 + 1e-12)) << wire.name;
        EXPECT_GT(calcPolylineLength(coarse), length * (1 - 1e-3)) << wire.name;
        worst.arcs += static_cast<int>(fine.size() - coarse.size()) > 0;
    }
}

TEST(WirePathSamples, LieOnOpenSimWrapsAndKeepTheWiresLength) {
    const Model model = test::loadWrapArm();
    Data data(model);
    std::mt19937 rng(17);
    Worst worst;
    for (int pose = 0; pose < 40; ++pose) {
        calcPositionKinematics(model, data, test::randomWrapArmPose(model, rng));
        calcWirePaths(model, data);
        checkSamples(model, data, worst);
    }
    EXPECT_LT(worst.surface, 1e-12);
    EXPECT_GT(worst.arcs, 40);  // wires that did wrap
    for (const WrapShape shape : {WrapShape::Sphere, WrapShape::Cylinder, WrapShape::Ellipsoid})
        EXPECT_GT(worst.arcPoints[static_cast<int>(shape)], 1000) << toString(shape);
    std::printf("wrap arm: %d wrapped wire poses; worst off the surface %.1e radii, worst length %.1e relative\n",
                worst.arcs, worst.surface, worst.length);
}

TEST(WirePathSamples, LieOnMuJoCoWrapsAndKeepTheWiresLength) {
    std::mt19937 rng(18);
    Worst worst;
    for (int leg = 0; leg < 10; ++leg) {
        const Model model = test::buildMujocoLegModel(test::generateMujocoLeg(rng));
        Data data(model);
        std::uniform_real_distribution<double> angle(-1.5, 1.5);
        for (int pose = 0; pose < 10; ++pose) {
            Eigen::VectorXd q(model.getNumQ());
            for (int i = 0; i < q.size(); ++i) q[i] = angle(rng);
            calcPositionKinematics(model, data, q);
            calcWirePaths(model, data);
            checkSamples(model, data, worst);
        }
    }
    EXPECT_LT(worst.surface, 1e-12);
    EXPECT_GT(worst.arcs, 50);
    for (const WrapShape shape : {WrapShape::Sphere, WrapShape::Cylinder})
        EXPECT_GT(worst.arcPoints[static_cast<int>(shape)], 1000) << toString(shape);
    std::printf("MuJoCo legs: %d wrapped wire poses; worst off the surface %.1e radii, worst length %.1e relative\n",
                worst.arcs, worst.surface, worst.length);
}

TEST(WirePathSamples, RefusesAStepThatIsNotPositive) {
    const Model model = test::loadWrapArm();
    Data data(model);
    calcPositionKinematics(model, data, model.getDefaultQ());
    calcWirePaths(model, data);
    std::vector<WirePathSample> samples;
    EXPECT_THROW(calcWirePathSamples(model, data, 0, 0.0, samples), Error);
    EXPECT_THROW(calcWirePathSamples(model, data, 0, std::nan(""), samples), Error);
}

}  // namespace
}  // namespace sinew
