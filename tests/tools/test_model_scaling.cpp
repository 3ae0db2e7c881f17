// Scaling the whole-body model to a subject (tools/model_scaling.cpp, tools/bvh_segment_scales.cpp) against
// what scaling must do: one factor everywhere is a homothety of every pose (link origins, wire lengths over
// their wraps, inertias as mass x length^2), and a BVH skeleton drawn from a model scaled by known factors
// gives those factors back, with a scaled model whose joint centres it reproduces.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/bvh_map.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/tools/bvh_segment_scales.hpp"
#include "sinew/tools/bvh_targets.hpp"
#include "sinew/tools/model_bvh.hpp"
#include "sinew/tools/model_scaling.hpp"
#include "support/bvh_subject.hpp"
#include "support/error_assertions.hpp"

namespace sinew {
namespace {

const std::filesystem::path kModels = std::filesystem::path(SINEW_SOURCE_DIR) / "models" / "whole_body";

const Model& wholeBody() {
    static const Model model = readModelFile((kModels / "whole_body.yaml").string());
    return model;
}

const BvhMap& wholeBodyMap() {
    static const BvhMap map = readBvhMap((kModels / "bvh_map.yaml").string());
    return map;
}

// q with every free joint's position (the root's, the virtual links') times s.
Eigen::VectorXd scalePositions(const Model& model, Eigen::VectorXd q, double s) {
    for (int i = 0; i < model.getNumLinks(); ++i)
        if (model.getJoint(i).type == JointType::Free) q.segment<3>(model.getJoint(i).qStart + 4) *= s;
    return q;
}

TEST(ModelScaling, OneFactorIsAHomothetyOfEveryPose) {
    const Model& model = wholeBody();
    const double s = 1.2;
    const Model scaled = scaleModel(model, std::vector<double>(static_cast<std::size_t>(model.getNumLinks()), s));
    ASSERT_EQ(scaled.getNumLinks(), model.getNumLinks());
    for (int i = 0; i < model.getNumLinks(); ++i) {
        const Link &a = model.getLink(i), &b = scaled.getLink(i);
        EXPECT_EQ(b.mass, a.mass) << a.name;
        EXPECT_LE((b.com_B - s * a.com_B).norm(), 1e-15) << a.name;
        EXPECT_LE((b.inertia_Bcom - s * s * a.inertia_Bcom).norm(), 1e-15) << a.name;
    }
    // The virtual links carried over with their neighbours: the default pose scaled about the ground origin.
    EXPECT_LE((scaled.getDefaultQ() - scalePositions(model, model.getDefaultQ(), s)).norm(), 1e-12);
    std::mt19937 rng(7);
    for (int trial = 0; trial < 3; ++trial) {
        const Eigen::VectorXd q = trial == 0 ? model.getDefaultQ() : test::randomBallPose(model, 0.4, rng);
        Data data(model), scaledData(scaled);
        calcPositionKinematics(model, data, q);
        calcWirePaths(model, data);
        calcPositionKinematics(scaled, scaledData, scalePositions(model, q, s));
        calcWirePaths(scaled, scaledData);
        for (int i = 0; i < model.getNumLinks(); ++i) {
            const std::size_t k = static_cast<std::size_t>(i);
            EXPECT_LE((scaledData.p_GB[k] - s * data.p_GB[k]).norm(), 1e-12) << model.getLink(i).name;
            EXPECT_LE((scaledData.R_GB[k] - data.R_GB[k]).norm(), 1e-12) << model.getLink(i).name;
        }
        // Every wire over its spheres and cylinders, which grow with the links that carry them.
        EXPECT_LE((scaledData.wireLength - s * data.wireLength).lpNorm<Eigen::Infinity>(), 1e-9) << "trial " << trial;
    }
    for (std::size_t w = 0; w < model.getWires().size(); ++w) {
        const double rest = model.getWires()[w].lawSpec.parameters.getScalar("rest_length");
        EXPECT_NEAR(scaled.getWires()[w].lawSpec.parameters.getScalar("rest_length"), s * rest, 1e-12 * rest)
            << model.getWires()[w].name;
    }
}

TEST(ModelScaling, RefusesBadFactors) {
    const Model& model = wholeBody();
    EXPECT_TRUE(test::throwsErrorAt([&] { scaleModel(model, {1.0, 2.0}); }, "scaling model 'whole_body'",
                                    {"2 factors", "links"}, ""));
    std::vector<double> factors(static_cast<std::size_t>(model.getNumLinks()), 1.0);
    factors[3] = -1;
    EXPECT_TRUE(test::throwsErrorAt([&] { scaleModel(model, factors); }, "scaling model 'whole_body'",
                                    {"lumbar4", "finite and > 0"}, ""));
}

TEST(BvhSegmentScales, ASkeletonOfKnownProportionsGivesItsFactorsBack) {
    const Model& model = wholeBody();
    const BvhMap& map = wholeBodyMap();
    const std::vector<double> known = test::linkFactorsOf(model, map, test::knownBvhFactors());
    const Model subject = scaleModel(model, known);
    const BvhMotion skeleton = makeModelBvh(subject, scaleBvhMapPoints(map, model, known), {subject.getDefaultQ()}, 1.0 / 120);
    const BvhSegmentScales scales = estimateBvhSegmentScales(skeleton, map, model, 0.01);
    EXPECT_EQ(scales.segments.size(), map.joints.size() - 1);  // one root
    for (std::size_t k = 0; k < map.joints.size(); ++k)
        EXPECT_NEAR(scales.jointFactors[k], test::knownBvhFactors().at(map.joints[k].first), 1e-12) << map.joints[k].first;
    // The model scaled by the estimate puts its target points where the subject's are: the BVH's joint
    // centres, at the rest pose.
    const Model fitted = scaleModel(model, scales.linkFactors);
    const BvhTargets targets = makeBvhTargets(skeleton, scaleBvhMapPoints(map, model, scales.linkFactors), fitted);
    Data data(fitted);
    calcPositionKinematics(fitted, data, fitted.getDefaultQ());
    for (std::size_t k = 0; k < targets.markers.size(); ++k)
        EXPECT_LE((calcMarkerLocation_G(data, targets.markers[k]) - targets.capture.positions[0].col(static_cast<Eigen::Index>(k)))
                      .norm(),
                  1e-12)
            << targets.markers[k].name;
}

TEST(BvhSegmentScales, RefusesAChildMappedAboveItsParent) {
    BvhMap map = wholeBodyMap();
    for (auto& [bvh, link] : map.joints)
        if (bvh == "rShin") link = "pelvis";
    const BvhMotion skeleton = makeModelBvh(wholeBody(), wholeBodyMap(), {wholeBody().getDefaultQ()}, 1.0 / 120);
    EXPECT_TRUE(test::throwsErrorAt<ModelError>([&] { estimateBvhSegmentScales(skeleton, map, wholeBody(), 0.01); },
                                                map.where[14], {"rShin", "not below", "femur_r"}, ""));
}

}  // namespace
}  // namespace sinew
