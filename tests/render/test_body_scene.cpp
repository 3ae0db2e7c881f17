// What pictures draw against core's own numbers: the drawn wire paths against core's wire lengths and end
// points, the bone capsules against the sizes worked by hand from the link's inertia.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/io/model_loading.hpp"
#include "sinew/render/body_scene.hpp"
#include "support/wrap_test_model.hpp"
#include "two_wire_model.hpp"

namespace sinew {
namespace {

double calcPolylineLength(const std::vector<Eigen::Vector3d>& path) {
    double length = 0;
    for (std::size_t i = 0; i + 1 < path.size(); ++i) length += (path[i + 1] - path[i]).norm();
    return length;
}

Eigen::Vector3d calcPoint_G(const Model& model, const Data& data, const Wire& wire, int point) {
    const int link = model.getWirePoints()[static_cast<std::size_t>(wire.firstPoint + point)].link;
    const Eigen::Vector3d p_B = calcWirePointLocation(model, wire, point, data.q);
    if (link == kGround) return p_B;
    return data.p_GB[static_cast<std::size_t>(link)] + data.R_GB[static_cast<std::size_t>(link)] * p_B;
}

TEST(BodyScene, PolylinePathsHaveCoresLengths) {
    const Model model = readModelFile(SINEW_SOURCE_DIR "/models/arm26.yaml");
    Data data(model);
    calcPositionKinematics(model, data, model.getDefaultQ());
    calcWirePaths(model, data);
    std::vector<Eigen::Vector3d> path;
    for (int w = 0; w < model.getNumWires(); ++w) {
        getWirePath_G(model, data, w, path);
        ASSERT_EQ(static_cast<int>(path.size()), model.getWire(w).numPoints);
        EXPECT_NEAR(calcPolylineLength(path), data.wireLength[w], 1e-12) << model.getWire(w).name;
    }
}

// Wrapped paths: from the origin to the insertion, with core's length over the wraps less at most the
// 5-degree chords' error (under 1e-3 of an arc's length).
TEST(BodyScene, WrappedPathsRunFromOriginToInsertion) {
    const std::string path = SINEW_SHARED_DIR "/data/opensim/arm26/arm26.osim";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent (developer data)";
    const Model model = loadModel(path, {});
    Data data(model);
    calcPositionKinematics(model, data, model.getDefaultQ());
    calcWirePaths(model, data);
    int wrapped = 0;
    std::vector<Eigen::Vector3d> drawn;
    for (int w = 0; w < model.getNumWires(); ++w) {
        const Wire& wire = model.getWire(w);
        getWirePath_G(model, data, w, drawn);
        wrapped += !wire.wraps.empty();
        EXPECT_LT((drawn.front() - calcPoint_G(model, data, wire, 0)).norm(), 1e-12) << wire.name;
        EXPECT_LT((drawn.back() - calcPoint_G(model, data, wire, wire.numPoints - 1)).norm(), 1e-12) << wire.name;
        EXPECT_LE(calcPolylineLength(drawn), data.wireLength[w] + 1e-12) << wire.name;
        EXPECT_GT(calcPolylineLength(drawn), (1 - 1e-3) * data.wireLength[w]) << wire.name;
    }
    EXPECT_GT(wrapped, 0);
}

// The wrap arm's cylinder, sphere and ellipsoid: each wrapped path is drawn along its arcs, with points
// beyond the evaluated path's and core's length less at most the chords' error.
TEST(BodyScene, WrapsAreDrawnAlongTheirArcs) {
    const Model model = test::loadWrapArm();
    Data data(model);
    std::mt19937 rng(5);
    int arcs = 0;
    std::vector<Eigen::Vector3d> drawn;
    for (int pose = 0; pose < 20; ++pose) {
        calcPositionKinematics(model, data, test::randomWrapArmPose(model, rng));
        calcWirePaths(model, data);
        for (int w = 0; w < model.getNumWires(); ++w) {
            getWirePath_G(model, data, w, drawn);
            const int evaluated = model.getWire(w).isPolyline() ? model.getWire(w).numPoints : data.wirePathSize[w];
            arcs += static_cast<int>(drawn.size()) > evaluated;
            EXPECT_LE(calcPolylineLength(drawn), data.wireLength[w] * (1 + 1e-12)) << model.getWire(w).name;
            EXPECT_GT(calcPolylineLength(drawn), data.wireLength[w] * (1 - 1e-3)) << model.getWire(w).name;
        }
    }
    EXPECT_GT(arcs, 20);
}

TEST(BodyScene, CapsulesAreSizedFromTheLinks) {
    const Model model = test::makeTwoWireModel();
    const std::vector<BoneCapsule> capsules = calcBoneCapsules(model);
    ASSERT_EQ(capsules.size(), 2u);
    // The post: from its joint centre to the bar's joint; r = 0.4 sqrt(2 * 0.002 / 2) = 0.01789 m, within
    // 3% to 12% of its 0.5 m.
    EXPECT_EQ(capsules[0].link, 0);
    EXPECT_LT((capsules[0].a_B - Eigen::Vector3d::Zero()).norm(), 1e-15);
    EXPECT_LT((capsules[0].b_B - Eigen::Vector3d(0, -0.5, 0)).norm(), 1e-15);
    EXPECT_NEAR(capsules[0].radius, 0.4 * std::sqrt(0.002), 1e-12);
    // The bar, a leaf: to twice its centre of mass; r = 0.4 sqrt(2 * 0.001 / 1) = 0.01789 m, of 0.5 m.
    EXPECT_LT((capsules[1].b_B - Eigen::Vector3d(0, -0.5, 0)).norm(), 1e-15);
    EXPECT_NEAR(capsules[1].radius, 0.4 * std::sqrt(0.002), 1e-12);
}

// OpenSim's knee is a custom joint that translates the tibia as it turns (p_PF is zero): the femur still
// reaches the knee, 0.396 m down in gait2354 (its femur_r-to-tibia_r translation at the default knee angle).
TEST(BodyScene, CapsulesReachJointsThatCustomJointsTranslate) {
    const std::string path = SINEW_SHARED_DIR "/data/opensim-models/Models/Gait2354_Simbody/gait2354_simbody.osim";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent (developer data)";
    const Model model = loadModel(path, {});
    const int femur = model.findLinkIndex("femur_r");
    ASSERT_GE(femur, 0);
    int found = 0;
    for (const BoneCapsule& capsule : calcBoneCapsules(model))
        if (capsule.link == femur) {
            ++found;
            EXPECT_NEAR((capsule.b_B - capsule.a_B).norm(), 0.396, 0.01);
        }
    EXPECT_EQ(found, 1);
}

TEST(BodyScene, StrainOnlyForLigamentsWithARestLength) {
    Model model = test::makeTwoWireModel();
    EXPECT_EQ(findRestLength(model.getWire(0)), 1.0);
    EXPECT_FALSE(isShadedByStrain(model.getWire(0)));  // a muscle
    const Model whole = readModelFile(SINEW_SOURCE_DIR "/models/whole_body/whole_body.yaml");
    int ligaments = 0;
    for (const Wire& wire : whole.getWires())
        if (wire.kind == WireKind::Ligament) {
            ++ligaments;
            EXPECT_TRUE(isShadedByStrain(wire)) << wire.name;
        }
    EXPECT_EQ(ligaments, 200);
}

TEST(BodyScene, RefusesANegativeTensionNamingTheWire) {
    const Model model = test::makeTwoWireModel();
    Data data(model);
    calcPositionKinematics(model, data, model.getDefaultQ());
    calcWirePaths(model, data);
    try {
        calcBodyFrame(model, data, calcBoneCapsules(model), 0.0, Eigen::Vector2d(1.0, -2.0));
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("wire 'loaded'"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace sinew
