// The model file's wire features (wrap objects, wraps, MuJoCo's wraps with their side sites, on the object's
// link or another, conditional and moving points) written and read back give the same model, bit for bit,
// and bad ones are refused at their line.
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
        EXPECT_EQ(a.getSupportLinks(x), b.getSupportLinks(y));
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

// Whether the model `base` with `from` replaced by `to` is refused at `prefix` with all of `words`.
::testing::AssertionResult isEditRefused(const std::string& base, const std::string& from, const std::string& to,
                                         const std::string& prefix, const std::vector<std::string>& words) {
    std::string text = base;
    const std::size_t at = text.find(from);
    if (at == std::string::npos) return ::testing::AssertionFailure() << "no '" << from << "' in the model";
    text.replace(at, from.size(), to);
    return test::throwsErrorAt<ModelError>([&] { readModelText(text, "bad.yaml"); }, prefix, words, text);
}

TEST(WirePathYaml, BadFeaturesAreRefusedAtTheirLine) {
    auto refused = [](const std::string& from, const std::string& to, const std::string& prefix,
                      const std::vector<std::string>& words) {
        return isEditRefused(test::kWrapArmYaml, from, to, prefix, words);
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

// A MuJoCo tendon: two MuJoCo wraps on adjacent segments, one with a side site, over objects turned and
// moved in their links.
const char* const kMuJoCoTendonYaml = R"(sinew_model: 1
name: mujoco_tendon
links:
  - {name: base, mass: 0, inertia: [0, 0, 0, 0, 0, 0]}
  - {name: upper, mass: 2, com: [0, -0.15, 0], inertia: [0.02, 0.002, 0.02, 0, 0, 0]}
  - {name: lower, mass: 1, com: [0, -0.15, 0], inertia: [0.01, 0.001, 0.01, 0, 0, 0]}
joints:
  - {name: mount, type: weld, parent: ground, child: base}
  - {name: shoulder, type: pin, parent: base, child: upper, axis: [0, 0, 1]}
  - {name: elbow, type: pin, parent: upper, child: lower, parent_point: [0, -0.3, 0], axis: [0, 0, 1]}
wrap_objects:
  - {name: ball, type: sphere, link: upper, rotation: [0.1, -0.2, 0.3], translation: [0.001, -0.3, 0.002], radius: 0.04}
  - {name: drum, type: cylinder, link: lower, rotation: [0.3, 0.1, 0], translation: [0, -0.2, 0.01], radius: 0.03, length: 0.1}
  - {name: egg, type: ellipsoid, link: upper, radii: [0.03, 0.02, 0.025]}
wires:
  - name: tendon
    kind: tendon
    points:
      - {link: base, at: [0.03, -0.1, 0]}
      - {link: upper, at: [0.05, -0.2, 0.01]}
      - {link: lower, at: [0.04, -0.1, -0.01]}
      - {link: lower, at: [-0.04, -0.3, 0.01]}
    wraps: [{object: ball, range: [1, 2], method: mujoco, side_site: [0.1, -0.3, 0.02]}, {object: drum, range: [2, 3], method: mujoco}]
    force_law: {type: prescribed_tension, tension: 10}
)";

TEST(WirePathYaml, MuJoCoWrapsRoundTrip) {
    const Model a = readModelText(kMuJoCoTendonYaml, "mujoco_tendon.yaml");
    const Model b = readModelText(writeModelText(a), "written.yaml");
    const std::vector<WireWrap>&x = a.getWire(0).wraps, &y = b.getWire(0).wraps;
    ASSERT_EQ(x.size(), 2u);
    ASSERT_EQ(y.size(), 2u);
    EXPECT_EQ(x[0].method, WrapMethod::MuJoCo);
    EXPECT_TRUE(x[0].hasSideSite);
    EXPECT_FALSE(x[1].hasSideSite);
    // Without side_site_link the side site is on the object's link, in that link's frame as given.
    EXPECT_EQ(x[0].sideSiteLink, a.getWrapObjects()[0].link);
    EXPECT_EQ(x[0].sideSite_B, Eigen::Vector3d(0.1, -0.3, 0.02));
    for (std::size_t i = 0; i < x.size(); ++i) {
        EXPECT_EQ(x[i].method, y[i].method);
        EXPECT_EQ(x[i].firstPoint, y[i].firstPoint);
        EXPECT_EQ(x[i].lastPoint, y[i].lastPoint);
        EXPECT_EQ(x[i].hasSideSite, y[i].hasSideSite);
        EXPECT_EQ(x[i].sideSiteLink, y[i].sideSiteLink);
        EXPECT_EQ(x[i].sideSite_B, y[i].sideSite_B);
    }
    EXPECT_EQ(writeModelText(b), writeModelText(a));
    EXPECT_EQ(writeModelText(a).find("side_site_link"), std::string::npos);
}

// MuJoCo's side site on another body than its geom: on the drum (on 'lower'), one fixed on 'upper'.
std::string withSideSiteOnUpper() {
    std::string text = kMuJoCoTendonYaml;
    const std::string from = "{object: drum, range: [2, 3], method: mujoco}";
    text.replace(text.find(from), from.size(),
                 "{object: drum, range: [2, 3], method: mujoco, side_site: [0.03, -0.45, 0.01], side_site_link: upper}");
    return text;
}

TEST(WirePathYaml, SideSiteOnAnotherLinkRoundTrips) {
    const Model a = readModelText(withSideSiteOnUpper(), "side_site_link.yaml");
    const WireWrap& drum = a.getWire(0).wraps[1];
    ASSERT_TRUE(drum.hasSideSite);
    EXPECT_EQ(a.getWrapObjects()[static_cast<std::size_t>(drum.object)].link, a.findLinkIndex("lower"));
    EXPECT_EQ(drum.sideSiteLink, a.findLinkIndex("upper"));
    EXPECT_EQ(drum.sideSite_B, Eigen::Vector3d(0.03, -0.45, 0.01));
    const std::string text = writeModelText(a);
    EXPECT_NE(text.find(", side_site_link: upper}"), std::string::npos) << text;
    const Model b = readModelText(text, "written.yaml");
    EXPECT_EQ(b.getWire(0).wraps[1].sideSiteLink, drum.sideSiteLink);
    EXPECT_EQ(b.getWire(0).wraps[1].sideSite_B, drum.sideSite_B);
    EXPECT_EQ(writeModelText(b), text);
}

TEST(WirePathYaml, BadMuJoCoWrapsAreRefusedAtTheirLine) {
    auto refused = [](const std::string& from, const std::string& to, const std::vector<std::string>& words) {
        return isEditRefused(kMuJoCoTendonYaml, from, to, "bad.yaml:23", words);
    };
    EXPECT_TRUE(refused("{object: drum, range: [2, 3], method: mujoco}", "{object: egg, range: [2, 3], method: mujoco}",
                        {"tendon", "'egg'", "spheres and cylinders only"}));
    EXPECT_TRUE(refused("{object: drum, range: [2, 3], method: mujoco}", "{object: drum, range: [1, 3], method: mujoco}",
                        {"'drum'", "adjacent points", "[1, 3]"}));
    EXPECT_TRUE(refused("{object: drum, range: [2, 3], method: mujoco}", "{object: drum, range: [1, 2], method: mujoco}",
                        {"[1, 2]", "one object only"}));
    EXPECT_TRUE(refused("range: [1, 2], method: mujoco,", "range: [1, 2], method: hybrid,", {"'ball'", "needs the mujoco method"}));
    EXPECT_TRUE(refused("side_site: [0.1, -0.3, 0.02]", "side_site: [0.1, .nan, 0.02]", {"side_site", "finite"}));
    EXPECT_TRUE(refused("range: [2, 3], method: mujoco", "range: [2, 3], method: mujuco", {"'mujuco'", "mujoco"}));
    EXPECT_TRUE(refused("{object: drum, range: [2, 3], method: mujoco}",
                        "{object: drum, range: [2, 3], method: mujoco, side_site_link: upper}",
                        {"'drum'", "side site link 'upper'", "without a side site"}));
    EXPECT_TRUE(isEditRefused(withSideSiteOnUpper(), "side_site_link: upper", "side_site_link: forearm", "bad.yaml:23",
                              {"'drum'", "side site", "unknown link 'forearm'"}));
}

}  // namespace
}  // namespace sinew
