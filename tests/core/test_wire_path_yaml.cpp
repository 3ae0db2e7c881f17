// The model file's wire features (wrap objects, wraps, conditional and moving points) written and read
// back give the same model, bit for bit, and bad ones are refused at their line.
#include <gtest/gtest.h>

#include <random>

#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_path.hpp"
#include "support/error_assertions.hpp"
#include "support/wrap_test_model.hpp"

namespace sinew {
namespace {

TEST(WirePathYaml, RoundTripKeepsEveryFeature) {
    const Model a = test::loadWrapArm();
    const Model b = readModelText(writeModelText(a), "written.yaml");
    ASSERT_EQ(a.getWrapObjects().size(), b.getWrapObjects().size());
    for (std::size_t i = 0; i < a.getWrapObjects().size(); ++i) {
        const WrapObject &x = a.getWrapObjects()[i], &y = b.getWrapObjects()[i];
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.shape, y.shape);
        EXPECT_EQ(x.link, y.link);
        EXPECT_EQ(x.R_BW, y.R_BW);
        EXPECT_EQ(x.p_BW, y.p_BW);
        EXPECT_EQ(x.radius, y.radius);
        EXPECT_EQ(x.length, y.length);
        EXPECT_EQ(x.radii, y.radii);
        EXPECT_EQ(x.quadrantAxis, y.quadrantAxis);
        EXPECT_EQ(x.quadrantSign, y.quadrantSign);
    }
    ASSERT_EQ(a.getNumWires(), b.getNumWires());
    for (int w = 0; w < a.getNumWires(); ++w) {
        const Wire &x = a.getWire(w), &y = b.getWire(w);
        ASSERT_EQ(x.conditions.size(), y.conditions.size());
        for (std::size_t i = 0; i < x.conditions.size(); ++i) {
            EXPECT_EQ(x.conditions[i].point, y.conditions[i].point);
            EXPECT_EQ(x.conditions[i].q, y.conditions[i].q);
            EXPECT_EQ(x.conditions[i].min, y.conditions[i].min);
            EXPECT_EQ(x.conditions[i].max, y.conditions[i].max);
        }
        ASSERT_EQ(x.motions.size(), y.motions.size());
        for (std::size_t i = 0; i < x.motions.size(); ++i) {
            EXPECT_EQ(x.motions[i].point, y.motions[i].point);
            EXPECT_EQ(x.motions[i].axis, y.motions[i].axis);
            EXPECT_EQ(x.motions[i].q, y.motions[i].q);
            EXPECT_EQ(x.motions[i].u, y.motions[i].u);
            for (const double s : {-1.5, 0.3, 1.7, 3.5}) EXPECT_EQ(x.motions[i].function.calcValue(s), y.motions[i].function.calcValue(s));
        }
        ASSERT_EQ(x.wraps.size(), y.wraps.size());
        for (std::size_t i = 0; i < x.wraps.size(); ++i) {
            EXPECT_EQ(x.wraps[i].object, y.wraps[i].object);
            EXPECT_EQ(x.wraps[i].firstPoint, y.wraps[i].firstPoint);
            EXPECT_EQ(x.wraps[i].lastPoint, y.wraps[i].lastPoint);
            EXPECT_EQ(x.wraps[i].method, y.wraps[i].method);
        }
        EXPECT_EQ(x.supportLinks, y.supportLinks);
    }
    // And so the same lengths.
    std::mt19937 rng(41);
    Data da(a), db(b);
    for (int trial = 0; trial < 10; ++trial) {
        const Eigen::VectorXd q = test::randomWrapArmPose(a, rng);
        calcPositionKinematics(a, da, q);
        calcWirePaths(a, da);
        calcPositionKinematics(b, db, q);
        calcWirePaths(b, db);
        EXPECT_EQ(da.wireLength, db.wireLength);
    }
    EXPECT_EQ(writeModelText(b), writeModelText(a));
}

TEST(WirePathYaml, BadFeaturesAreRefusedAtTheirLine) {
    const std::string base = test::kWrapArmYaml;
    auto refused = [&](const std::string& from, const std::string& to, const std::string& prefix,
                       const std::vector<std::string>& words) {
        std::string text = base;
        const std::size_t at = text.find(from);
        if (at == std::string::npos) return ::testing::AssertionFailure() << "no '" << from << "' in the model";
        text.replace(at, from.size(), to);
        return test::throwsErrorAt<ModelError>([&] { readModelText(text, "bad.yaml"); }, prefix, words, text);
    };
    EXPECT_TRUE(refused("radius: 0.02, length", "radius: -0.02, length", "bad.yaml:12", {"elbow_cylinder", "radius"}));
    EXPECT_TRUE(refused("quadrant: +x", "quadrant: +w", "bad.yaml:13", {"head", "quadrant '+w'"}));
    EXPECT_TRUE(refused("radii: [0.035, 0.02, 0.025]", "radii: [0.035, 0, 0.025]", "bad.yaml:14", {"radii"}));
    EXPECT_TRUE(refused("type: sphere, link: upper, radius", "type: sphere, link: upper, length: 1, radius", "bad.yaml:13",
                        {"takes no 'length'"}));
    EXPECT_TRUE(refused("[{object: elbow_cylinder}]\n    force_law: {type: prescribed_tension, tension: 10}",
                        "[{object: elbow_cylindre}]\n    force_law: {type: prescribed_tension, tension: 10}", "bad.yaml:21",
                        {"over_cylinder", "unknown wrap object 'elbow_cylindre'"}));
    EXPECT_TRUE(refused("{object: head, range: [0, 1]}", "{object: head, range: [1, 3]}", "bad.yaml:43",
                        {"two_wraps", "wrap range [1, 3]"}));
    EXPECT_TRUE(refused("{object: head, range: [0, 1]}", "{object: head, method: spiral}", "bad.yaml:43",
                        {"unknown wrap method 'spiral'"}));
    EXPECT_TRUE(refused("active_when: {coordinate: elbow,", "active_when: {coordinate: wrist,", "bad.yaml:49",
                        {"conditional_and_moving", "point 1", "unknown coordinate 'wrist'"}));
    EXPECT_TRUE(refused("range: [0.5, 2.0]", "range: [2.5, 2.0]", "bad.yaml:49", {"min <= max"}));
    EXPECT_TRUE(refused("x: {coordinate: elbow,", "x: {coordinate: shoulder_qx,", "bad.yaml:50",
                        {"quaternion", "pin and custom"}));
    EXPECT_TRUE(refused("y: {coordinate: elbow, function: {type: linear", "w: {coordinate: elbow, function: {type: linear",
                        "bad.yaml:54", {"unknown field 'w' in moving"}));
}

}  // namespace
}  // namespace sinew
