// The model loader: every kind of bad model file is rejected with a message that starts at the offending
// "file:line" and names the element and field; and writing a model then reading it back changes nothing.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "sinew/core/error.hpp"
#include "support/random_model.hpp"
#include "sinew/io/model_file.hpp"
#include "support/error_assertions.hpp"

namespace sinew {
namespace {

// ---------------------------------------------------------------------------------------------------------
// Error reporting. Every test starts from one small valid model and replaces some of its lines, so the line
// an error should be reported at follows from the names below rather than from counting lines by hand.

enum Line : int {
    kVersion = 1,
    kName,
    kLinks,
    kUpper,
    kLower,
    kJoints,
    kShoulder,
    kElbow,
    kLoops,
    kWires,
    kWireName,
    kWireKind,
    kWirePoints,
    kPoint0,
    kPoint1,
    kForceLaw,
    kEnd
};

const char* const kBaseLines[] = {
    "sinew_model: 1",
    "name: two_links",
    "links:",
    "  - {name: upper, mass: 2.0, com: [0, -0.15, 0], inertia: [0.02, 0.02, 0.004, 0, 0, 0]}",
    "  - {name: lower, mass: 1.0, com: [0, -0.12, 0], inertia: [0.01, 0.01, 0.002, 0, 0, 0]}",
    "joints:",
    "  - {name: shoulder, type: ball, parent: ground, child: upper, parent_point: [0, 0, 0], child_point: [0, 0, 0]}",
    "  - {name: elbow, type: pin, parent: upper, child: lower, parent_point: [0, -0.3, 0], child_point: [0, 0, 0], "
    "axis: [0, 0, 1]}",
    "loops: []",
    "wires:",
    "  - name: biceps",
    "    kind: muscle",
    "    points:",
    "      - {link: upper, at: [0.02, -0.05, 0]}",
    "      - {link: lower, at: [0.02, -0.05, 0]}",
    "    force_law: {type: spring_damper, stiffness: 100, damping: 1, rest_length: 0.3}",
};
static_assert(sizeof(kBaseLines) / sizeof(kBaseLines[0]) == kEnd - 1, "one base line per Line name");

// The base model with some lines replaced; a replacement may span several lines (an insertion) or be empty
// (a blank line, which keeps the numbering of the lines after it).
std::string modelWith(const std::map<int, std::string>& replacements = {}) {
    std::string text;
    for (int line = kVersion; line < kEnd; ++line) {
        const auto it = replacements.find(line);
        text += (it != replacements.end() ? it->second : std::string(kBaseLines[line - 1])) + "\n";
    }
    return text;
}

// The base line `line` followed by extra lines, which then sit at line + 1, line + 2, ...
std::string followedBy(int line, const std::string& extra) { return std::string(kBaseLines[line - 1]) + "\n" + extra; }

// One line of the base model's text, from its fields.
std::string entry(const std::string& fields) { return "  - {" + fields + "}"; }  // a link, joint or loop
std::string point(const std::string& fields) { return "      - {" + fields + "}"; }
std::string forceLaw(const std::string& fields) { return "    force_law: {" + fields + "}"; }

const std::string kUpperInertia = "inertia: [0.02, 0.02, 0.004, 0, 0, 0]";
const std::string kLowerInertia = "inertia: [0.01, 0.01, 0.002, 0, 0, 0]";

// A 'loops:' section holding the given loops, the first at line kLoops + 1.
std::string loopsSection(const std::vector<std::string>& loops) {
    std::string text = "loops:";
    for (const std::string& loop : loops) text += "\n" + entry(loop);
    return text;
}

std::string loop(const std::string& name, const std::string& linkA, const std::string& pointA,
                 const std::string& linkB, const std::string& pointB) {
    return "name: " + name + ", link_a: " + linkA + ", point_a: " + pointA + ", link_b: " + linkB +
           ", point_b: " + pointB;
}

// Passes when loading `text` throws a ModelError whose message starts with "bad.yaml:<line>: " and contains
// every one of `words`.
::testing::AssertionResult rejectsAt(const std::string& text, int line, const std::vector<std::string>& words) {
    return test::throwsErrorAt<ModelError>([&] { readModelText(text, "bad.yaml"); },
                                           "bad.yaml:" + std::to_string(line) + ": ", words, text);
}

// The same for the base model with line `line` replaced, when the error belongs on that line.
::testing::AssertionResult rejectsLine(int line, const std::string& replacement,
                                       const std::vector<std::string>& words) {
    return rejectsAt(modelWith({{line, replacement}}), line, words);
}

std::string where(int line) { return "bad.yaml:" + std::to_string(line); }

TEST(ModelFileErrors, BaseModelLoads) {
    // Otherwise the tests below could pass on errors other than the one they introduce.
    const Model model = readModelText(modelWith(), "bad.yaml");
    EXPECT_EQ(model.getNumLinks(), 2);
    EXPECT_EQ(model.getNumWires(), 1);
}

TEST(ModelFileErrors, UnknownLinkInJoint) {
    EXPECT_TRUE(rejectsLine(kElbow, entry("name: elbow, type: pin, parent: forearm, child: lower, axis: [0, 0, 1]"),
                            {"joint 'elbow'", "unknown parent link 'forearm'"}));
    EXPECT_TRUE(rejectsLine(kElbow, entry("name: elbow, type: pin, parent: upper, child: hand, axis: [0, 0, 1]"),
                            {"joint 'elbow'", "unknown child link 'hand'"}));
}

TEST(ModelFileErrors, UnknownLinkInWirePoint) {
    EXPECT_TRUE(rejectsLine(kPoint1, point("link: hand, at: [0.02, -0.05, 0]"),
                            {"wire 'biceps'", "unknown link 'hand'"}));
}

TEST(ModelFileErrors, UnknownLinkInLoop) {
    const std::string clasp = loop("clasp", "upper", "[0, -0.1, 0]", "hand", "[0, 0, 0]");
    EXPECT_TRUE(rejectsAt(modelWith({{kLoops, loopsSection({clasp})}}), kLoops + 1,
                          {"loop 'clasp'", "unknown link 'hand'"}));
}

TEST(ModelFileErrors, DuplicateLinkName) {
    EXPECT_TRUE(rejectsLine(kLower, entry("name: upper, mass: 1.0, " + kLowerInertia),
                            {"duplicate link name 'upper'", where(kUpper)}));
}

TEST(ModelFileErrors, DuplicateWireName) {
    const std::string second = "  - name: biceps\n"
                               "    kind: tendon\n"
                               "    points: [{link: upper, at: [0, 0, 0]}, {link: lower, at: [0, 0, 0]}]\n" +
                               forceLaw("type: prescribed_tension, tension: 1");
    EXPECT_TRUE(rejectsAt(modelWith({{kForceLaw, followedBy(kForceLaw, second)}}), kForceLaw + 1,
                          {"duplicate wire name 'biceps'", where(kWireName)}));
}

TEST(ModelFileErrors, DuplicateJointName) {
    EXPECT_TRUE(rejectsLine(kElbow, entry("name: shoulder, type: weld, parent: upper, child: lower"),
                            {"duplicate joint name 'shoulder'", where(kShoulder)}));
}

TEST(ModelFileErrors, VirtualLinkNamedLikeAJoint) {
    EXPECT_TRUE(rejectsLine(kLoops, "virtual_links: [{name: elbow, initial_position: [0, 0, 0]}]",
                            {"virtual link 'elbow'", "joint 'elbow'", where(kElbow)}));
}

TEST(ModelFileErrors, WireWithFewerThanTwoPoints) {
    EXPECT_TRUE(rejectsAt(modelWith({{kWirePoints, "    points: []"}, {kPoint0, ""}, {kPoint1, ""}}), kWireName,
                          {"wire 'biceps'", "0 point(s)", "at least 2"}));
    EXPECT_TRUE(rejectsAt(modelWith({{kPoint1, ""}}), kWireName, {"wire 'biceps'", "1 point(s)", "at least 2"}));
}

TEST(ModelFileErrors, InertiaNotPositiveDefinite) {
    EXPECT_TRUE(rejectsLine(kUpper, entry("name: upper, mass: 2.0, inertia: [0.02, 0.02, -0.004, 0, 0, 0]"),
                            {"link 'upper'", "inertia", "positive definite"}));
    // Positive diagonal, but the products of inertia make it indefinite.
    EXPECT_TRUE(rejectsLine(kUpper, entry("name: upper, mass: 2.0, inertia: [0.02, 0.02, 0.02, 0.05, 0, 0]"),
                            {"link 'upper'", "inertia", "positive definite"}));
}

TEST(ModelFileErrors, InertiaViolatesTriangleInequality) {
    EXPECT_TRUE(rejectsLine(kUpper, entry("name: upper, mass: 2.0, inertia: [0.01, 0.01, 0.03, 0, 0, 0]"),
                            {"link 'upper'", "inertia", "triangle inequality"}));
}

TEST(ModelFileErrors, NanInNumberField) {
    EXPECT_TRUE(rejectsLine(kUpper, entry("name: upper, mass: .nan, " + kUpperInertia), {"'mass'", "finite", ".nan"}));
}

TEST(ModelFileErrors, InfInNumberField) {
    EXPECT_TRUE(rejectsLine(kPoint0, point("link: upper, at: [0.02, .inf, 0]"), {"'at'", "finite", ".inf"}));
    EXPECT_TRUE(rejectsLine(kForceLaw, forceLaw("type: spring_damper, stiffness: -.inf, rest_length: 0.3"),
                            {"'stiffness'", "finite", "-.inf"}));
}

TEST(ModelFileErrors, NonNumberWhereNumberExpected) {
    EXPECT_TRUE(rejectsLine(kLower, entry("name: lower, mass: heavy, " + kLowerInertia),
                            {"'mass'", "must be a number", "heavy"}));
    EXPECT_TRUE(rejectsLine(kLower, entry("name: lower, mass: 1.0, com: {x: 0}, " + kLowerInertia),
                            {"'com'", "number"}));
}

TEST(ModelFileErrors, WrongVectorLength) {
    EXPECT_TRUE(rejectsLine(kLower, entry("name: lower, mass: 1.0, com: [0, -0.12], " + kLowerInertia),
                            {"'com'", "3 numbers"}));
    EXPECT_TRUE(rejectsLine(kLower, entry("name: lower, mass: 1.0, inertia: [0.01, 0.01, 0.002]"),
                            {"link 'lower'", "'inertia'", "6 numbers"}));
}

TEST(ModelFileErrors, MissingRequiredField) {
    EXPECT_TRUE(rejectsLine(kUpper, entry("name: upper, com: [0, -0.15, 0], " + kUpperInertia),
                            {"link 'upper'", "missing field 'mass'"}));
}

TEST(ModelFileErrors, UnknownField) {
    EXPECT_TRUE(rejectsLine(kUpper, entry("name: upper, mas: 2.0, " + kUpperInertia), {"unknown field 'mas'", "link"}));
    EXPECT_TRUE(rejectsLine(kWireKind, "    knd: muscle", {"unknown field 'knd'", "wire"}));
}

TEST(ModelFileErrors, UnknownJointType) {
    EXPECT_TRUE(rejectsLine(kShoulder, entry("name: shoulder, type: hinge, parent: ground, child: upper"),
                            {"joint 'shoulder'", "unknown joint type 'hinge'"}));
}

TEST(ModelFileErrors, UnknownWireKind) {
    EXPECT_TRUE(rejectsLine(kWireKind, "    kind: rope", {"wire 'biceps'", "unknown kind 'rope'"}));
}

TEST(ModelFileErrors, UnknownForceLawType) {
    EXPECT_TRUE(rejectsLine(kForceLaw, forceLaw("type: bungee, stiffness: 100, rest_length: 0.3"),
                            {"wire 'biceps'", "unknown force law type 'bungee'"}));
}

TEST(ModelFileErrors, MisspelledForceLawParameter) {
    // A misspelled optional parameter would otherwise silently take its default.
    EXPECT_TRUE(rejectsLine(kForceLaw, forceLaw("type: spring_damper, stiffness: 100, dampng: 1, rest_length: 0.3"),
                            {"wire 'biceps'", "'dampng'"}));
    EXPECT_TRUE(rejectsLine(kForceLaw, forceLaw("type: spring_damper, stifness: 100, damping: 1, rest_length: 0.3"),
                            {"wire 'biceps'", "'stiffness'"}));
}

TEST(ModelFileErrors, NegativeStiffness) {
    EXPECT_TRUE(rejectsLine(kForceLaw, forceLaw("type: spring_damper, stiffness: -100, rest_length: 0.3"),
                            {"wire 'biceps'", "'stiffness'", ">= 0"}));
}

TEST(ModelFileErrors, LoopWithBothEndsOnOneLink) {
    const std::string self = loop("self", "lower", "[0, 0, 0]", "lower", "[0, -0.2, 0]");
    EXPECT_TRUE(rejectsAt(modelWith({{kLoops, loopsSection({self})}}), kLoops + 1, {"loop 'self'", "link 'lower'"}));
}

TEST(ModelFileErrors, LoopDuplicatingAnotherLoop) {
    const std::string strap = loop("strap", "upper", "[0, -0.3, 0.05]", "lower", "[0, 0, 0.05]");
    // The same closure written from the other end.
    const std::string again = loop("strap2", "lower", "[0, 0, 0.05]", "upper", "[0, -0.3, 0.05]");
    EXPECT_TRUE(rejectsAt(modelWith({{kLoops, loopsSection({strap, again})}}), kLoops + 2,
                          {"loop 'strap2'", "loop 'strap'", where(kLoops + 1)}));
}

TEST(ModelFileErrors, LoopClosingOverTreeJoint) {
    // The elbow already joins upper's [0, -0.3, 0] to lower's origin; either way round the loop is redundant.
    const std::string childFirst = loop("elbow2", "lower", "[0, 0, 0]", "upper", "[0, -0.3, 0]");
    const std::string parentFirst = loop("elbow2", "upper", "[0, -0.3, 0]", "lower", "[0, 0, 0]");
    for (const std::string& closure : {childFirst, parentFirst})
        EXPECT_TRUE(rejectsAt(modelWith({{kLoops, loopsSection({closure})}}), kLoops + 1,
                              {"loop 'elbow2'", "tree joint 'elbow'"}));
}

TEST(ModelFileErrors, LinkWithTwoParentJoints) {
    const std::string wrist = entry("name: wrist, type: ball, parent: ground, child: lower");
    EXPECT_TRUE(rejectsAt(modelWith({{kElbow, followedBy(kElbow, wrist)}}), kElbow + 1,
                          {"joint 'wrist'", "link 'lower'", "'elbow'"}));
}

TEST(ModelFileErrors, CycleOfJointsNeverReachingGround) {
    EXPECT_TRUE(rejectsLine(kShoulder, entry("name: shoulder, type: ball, parent: lower, child: upper"),
                            {"joint 'shoulder'", "cycle", "ground"}));
}

TEST(ModelFileErrors, LinkWithoutJoint) {
    const std::string hand = entry("name: hand, mass: 0.5, inertia: [0.001, 0.001, 0.001, 0, 0, 0]");
    EXPECT_TRUE(rejectsAt(modelWith({{kLower, followedBy(kLower, hand)}}), kLower + 1, {"link 'hand'", "no joint"}));
}

TEST(ModelFileErrors, WirePointOnGround) {
    EXPECT_TRUE(rejectsLine(kPoint0, point("link: ground, at: [0, 0, 0]"), {"wire 'biceps'", "ground"}));
}

TEST(ModelFileErrors, ConsecutiveCoincidentWirePoints) {
    // Point 0 repeated on the next line.
    EXPECT_TRUE(rejectsAt(modelWith({{kPoint1, followedBy(kPoint0, kBaseLines[kPoint1 - 1])}}), kPoint1,
                          {"wire 'biceps'", "coincide", "link 'upper'"}));
}

TEST(ModelFileErrors, YamlSyntaxError) {
    EXPECT_TRUE(rejectsLine(kLower, entry("name: lower, mass: 1.0, com: [0, -0.12, 0]], " + kLowerInertia),
                            {"YAML syntax error"}));
}

TEST(ModelFileErrors, MissingFormatVersion) {
    // A missing key has no line of its own; the error points at the start of the document.
    EXPECT_TRUE(rejectsAt(modelWith({{kVersion, "# no version"}}), kName, {"missing", "sinew_model"}));
}

TEST(ModelFileErrors, WrongFormatVersion) {
    EXPECT_TRUE(rejectsLine(kVersion, "sinew_model: 2", {"unsupported format version 2"}));
    EXPECT_TRUE(rejectsLine(kVersion, "sinew_model: one", {"'sinew_model'", "number"}));
}

TEST(ModelFileErrors, PinJointWithoutAxis) {
    EXPECT_TRUE(rejectsLine(kElbow, entry("name: elbow, type: pin, parent: upper, child: lower"),
                            {"joint 'elbow'", "pin", "axis"}));
}

TEST(ModelFileErrors, InitialAngleOnBallJoint) {
    const std::string shoulder = "name: shoulder, type: ball, parent: ground, child: upper";
    EXPECT_TRUE(rejectsLine(kShoulder, entry(shoulder + ", initial_angle: 0.5"),
                            {"joint 'shoulder'", "initial_angle", "pin"}));
}

// A wire's strength and cross-section must be finite and > 0: a number is checked where it is written, its sign
// where the wire is built, at the wire's line.
TEST(ModelFileErrors, BadWireStrengthOrCrossSection) {
    for (const std::string field : {"strength", "cross_section"}) {
        SCOPED_TRACE(field);
        const std::string named = field == "strength" ? "strength" : "cross-section";
        for (const std::string value : {"0", "-2"})
            EXPECT_TRUE(rejectsAt(modelWith({{kForceLaw, followedBy(kForceLaw, "    " + field + ": " + value)}}),
                                  kWireName, {"wire 'biceps'", named, "> 0"}));
        EXPECT_TRUE(rejectsAt(modelWith({{kForceLaw, followedBy(kForceLaw, "    " + field + ": .nan")}}), kForceLaw + 1,
                              {"'" + field + "'", "finite"}));
        EXPECT_TRUE(rejectsAt(modelWith({{kForceLaw, followedBy(kForceLaw, "    " + field + ": strong")}}),
                              kForceLaw + 1, {"'" + field + "'", "number"}));
    }
}

// ---------------------------------------------------------------------------------------------------------
// Round trip: write, read back, compare field by field; writing the reloaded model gives the same text.

void expectSameMatrix(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double tolerance, const std::string& what) {
    ASSERT_EQ(a.rows(), b.rows()) << what;
    ASSERT_EQ(a.cols(), b.cols()) << what;
    EXPECT_LE((a - b).cwiseAbs().maxCoeff(), tolerance) << what << "\n" << a << "\nvs\n" << b;
}

void expectSameModel(const Model& a, const Model& b) {
    EXPECT_EQ(a.getName(), b.getName());
    expectSameMatrix(a.getGravity(), b.getGravity(), 0, "gravity");
    ASSERT_EQ(a.getNumLinks(), b.getNumLinks());
    EXPECT_EQ(a.getNumQ(), b.getNumQ());
    EXPECT_EQ(a.getNumU(), b.getNumU());
    for (int i = 0; i < a.getNumLinks(); ++i) {
        const Link& la = a.getLink(i);
        const Link& lb = b.getLink(i);
        SCOPED_TRACE("link " + la.name);
        EXPECT_EQ(la.name, lb.name);
        EXPECT_EQ(la.isVirtual, lb.isVirtual);
        EXPECT_EQ(la.mass, lb.mass);
        expectSameMatrix(la.com_B, lb.com_B, 0, "com_B");
        expectSameMatrix(la.inertia_Bcom, lb.inertia_Bcom, 0, "inertia_Bcom");

        const Joint& ja = a.getJoint(i);
        const Joint& jb = b.getJoint(i);
        EXPECT_EQ(ja.name, jb.name);
        EXPECT_EQ(ja.type, jb.type);
        EXPECT_EQ(ja.parent, jb.parent);
        expectSameMatrix(ja.p_PF, jb.p_PF, 0, "p_PF");
        expectSameMatrix(ja.p_BM, jb.p_BM, 0, "p_BM");
        expectSameMatrix(ja.R_PF, jb.R_PF, 0, "R_PF");
        expectSameMatrix(ja.R_BM, jb.R_BM, 0, "R_BM");
        EXPECT_EQ(ja.qStart, jb.qStart);
        EXPECT_EQ(ja.nq, jb.nq);
        EXPECT_EQ(ja.uStart, jb.uStart);
        EXPECT_EQ(ja.nu, jb.nu);
    }
    // Ball and free poses are written as rotation vectors, so their quaternions come back to rounding.
    expectSameMatrix(a.getDefaultQ(), b.getDefaultQ(), 1e-15, "default q");

    ASSERT_EQ(a.getNumLoops(), b.getNumLoops());
    for (int k = 0; k < a.getNumLoops(); ++k) {
        const Loop& la = a.getLoop(k);
        const Loop& lb = b.getLoop(k);
        SCOPED_TRACE("loop " + la.name);
        EXPECT_EQ(la.name, lb.name);
        EXPECT_EQ(la.linkA, lb.linkA);
        EXPECT_EQ(la.linkB, lb.linkB);
        expectSameMatrix(la.p_A, lb.p_A, 0, "p_A");
        expectSameMatrix(la.p_B, lb.p_B, 0, "p_B");
    }

    ASSERT_EQ(a.getWirePoints().size(), b.getWirePoints().size());
    for (std::size_t k = 0; k < a.getWirePoints().size(); ++k) {
        EXPECT_EQ(a.getWirePoints()[k].link, b.getWirePoints()[k].link) << "wire point " << k;
        expectSameMatrix(a.getWirePoints()[k].p_B, b.getWirePoints()[k].p_B, 0, "wire point " + std::to_string(k));
    }
    ASSERT_EQ(a.getNumWires(), b.getNumWires());
    for (int w = 0; w < a.getNumWires(); ++w) {
        const Wire& wa = a.getWire(w);
        const Wire& wb = b.getWire(w);
        SCOPED_TRACE("wire " + wa.name);
        EXPECT_EQ(wa.name, wb.name);
        EXPECT_EQ(wa.kind, wb.kind);
        EXPECT_EQ(wa.firstPoint, wb.firstPoint);
        EXPECT_EQ(wa.numPoints, wb.numPoints);
        EXPECT_EQ(wa.lawSpec.type, wb.lawSpec.type);
        EXPECT_EQ(wa.lawSpec.parameters.getAll(), wb.lawSpec.parameters.getAll());
        EXPECT_EQ(a.getSupportLinks(wa), b.getSupportLinks(wb));
        EXPECT_EQ(wa.strength, wb.strength);
        EXPECT_EQ(wa.crossSection, wb.crossSection);
        ASSERT_NE(wb.law, nullptr);
    }
}

void expectRoundTrip(const Model& model) {
    const std::string text = writeModelText(model);
    const Model reloaded = readModelText(text, "written.yaml");
    expectSameModel(model, reloaded);
    EXPECT_EQ(writeModelText(reloaded), text);
}

TEST(ModelFileRoundTrip, Arm26) {
    const Model arm = readModelFile(SINEW_SOURCE_DIR "/models/arm26.yaml");
    ASSERT_EQ(arm.getNumWires(), 6);
    expectRoundTrip(arm);
}

TEST(ModelFileRoundTrip, WireStrengthAndCrossSection) {
    // Numbers no short decimal writes exactly, so a writer that rounded them would show.
    const Model model = readModelText(
        modelWith({{kForceLaw, followedBy(kForceLaw, "    strength: 1234.5678901234567\n    cross_section: 3.1e-05")}}),
        "strength.yaml");
    const Wire& wire = model.getWire(0);
    ASSERT_TRUE(wire.strength && wire.crossSection);
    EXPECT_EQ(*wire.strength, 1234.5678901234567);
    EXPECT_EQ(*wire.crossSection, 3.1e-05);
    // A spring-damper has no max isometric force: the wire's strength is the one it is given.
    EXPECT_FALSE(wire.law->getMaxIsometricForce());
    EXPECT_EQ(getWireStrength(wire), wire.strength);
    expectRoundTrip(model);
    // Without them, the wire has neither and its file neither.
    const Model plain = readModelText(modelWith(), "plain.yaml");
    EXPECT_FALSE(plain.getWire(0).strength || plain.getWire(0).crossSection || getWireStrength(plain.getWire(0)));
    EXPECT_EQ(writeModelText(plain).find("strength"), std::string::npos);
}

TEST(ModelFileRoundTrip, InitialPoses) {
    // Rotations of more than half a turn are written as the equivalent shorter rotation vector.
    for (const std::string rotation : {"[0.3, -0.2, 0.1]", "[0, 0, 4]", "[-2, 2, 2]"}) {
        SCOPED_TRACE("initial_rotation " + rotation);
        const std::string shoulder = "name: shoulder, type: free, parent: ground, child: upper, initial_position: "
                                     "[0.1, 1, -0.2], initial_rotation: " + rotation;
        const std::string elbow = "name: elbow, type: pin, parent: upper, child: lower, parent_point: [0, -0.3, 0], "
                                  "axis: [1, 2, 3], initial_angle: 5";
        expectRoundTrip(readModelText(modelWith({{kShoulder, entry(shoulder)}, {kElbow, entry(elbow)}}), "poses.yaml"));
    }
}

TEST(ModelFileRoundTrip, RandomModelsWithLoopsAndVirtualLinks) {
    for (unsigned seed = 1; seed <= 20; ++seed) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        RandomModelOptions options;
        options.numLinks = 12;
        options.numLoops = 3;
        options.numVirtualLinks = 2;
        options.pinFraction = 0.5;
        options.seed = seed;
        const Model model = generateRandomModel(options);
        ASSERT_EQ(model.getNumLoops(), 3);
        ASSERT_EQ(model.getNumLinks(), 14);
        expectRoundTrip(model);
    }
}

}  // namespace
}  // namespace sinew
