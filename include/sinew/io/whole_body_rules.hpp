#pragma once
// The rules that derive sinew's whole-body model from a detailed source model (models/whole_body/rules.yaml,
// read here; applied by tools/whole_body_model), and the anthropometric ratios that complete missing masses.
// The file's fields are documented in docs/whole-body-model.md.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "sinew/core/model.hpp"

namespace sinew {

// A point fixed on a source body's link: given in the body's frame, or in ground at the neutral pose (m).
struct SourcePoint {
    std::string body;
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    bool inGround = false;
    std::string where;  // "rules.yaml:line"
};

struct WholeBodyLinkRule {
    std::string name;
    std::vector<std::string> bodies;  // source bodies welded into this link; the first one's joint is the link's
    std::string where;
};

// A ball-joint loop closure: the two links keep the point together (placed on link A at neutral).
struct WholeBodyLoopRule {
    std::string name;
    std::string linkA, linkB;
    SourcePoint at;
    std::string where;
};

// Forked muscles: each head's path runs to the virtual link, placed `fraction` of the way along the first
// head's last segment at the neutral pose, instead of to its insertion; a tendon wire continues from there
// to the first head's insertion.
struct WholeBodyForkRule {
    std::string name;                // the virtual link
    std::vector<std::string> heads;  // source wire names (>= 2)
    double fraction = 0.5;           // in (0, 1)
    std::string tendon;              // name of the tendon wire beyond the node
    std::string where;
};

// Four passive wires around a ball joint that replaced the source's hinges, as a joint capsule's ligaments
// (or an intervertebral disc's cartilage): at the joint centre plus radius x each of +d, -d, +f, -f, where
// f is the flexion axis and d = bone x f, each from halfSpan up the bone (on the parent) to halfSpan down it
// (on the child). Ligaments: the +-d pair restrains flexion-extension (limit `flexion`), the +-f pair
// abduction-adduction (limit `abduction`), each towards the side that stretches it; cartilage is
// pre-tensioned instead.
struct WholeBodyJointWiresRule {
    std::string name;
    WireKind kind = WireKind::Ligament;
    std::string joint;  // the child link of the ball joint
    Eigen::Vector3d flexionAxis = Eigen::Vector3d::UnitY();  // ground axes at neutral
    Eigen::Vector3d boneAxis = Eigen::Vector3d::UnitZ();     // from the joint towards the parent link
    double radius = 0.03, halfSpan = 0.015;                   // m
    double flexion = 0.5, abduction = 0.3;                    // rad
    std::vector<std::string> names;  // the four wires' names after `name`, in the order +d, -d, +f, -f
    std::string where;
};

// A passive wire placed from landmarks. Ligaments restrain a joint's motion: slack at the neutral pose,
// rest length at `limitFraction` of the way from the neutral length to the length with the child link
// rotated by `limitAngle` about `limitAxis` (ground axes at neutral) relative to its parent; cartilage
// is pre-tensioned: rest length = (1 - precompression) x neutral length.
struct WholeBodyPassiveRule {
    std::string name;
    WireKind kind = WireKind::Ligament;
    std::vector<SourcePoint> points;  // origin, via points, insertion
    std::string joint;                // ligaments: the link whose joint they restrain
    Eigen::Vector3d limitAxis = Eigen::Vector3d::UnitZ();
    double limitAngle = 0;  // rad
    std::string where;
};

struct WholeBodyStiffness {
    // Muscles: stiffness = muscleStrainStiffness * (the source's max isometric force) / (neutral length).
    double muscleStrainStiffness = 1;   // dimensionless
    double tendonStiffness = 2e4;       // N/m (tendons beyond a fork)
    double ligamentStiffness = 2e4;     // N/m
    double cartilageStiffness = 5e4;    // N/m
    double cartilagePrecompression = 0.02;
    double limitFraction = 0.8;
    // Muscles and tendons (forked ones too): rest length = (1 - prestretch) x neutral length. Taut at neutral,
    // they start away from the kink of a spring at its rest length, where a virtual link's Newton solve does not
    // settle and an integrator would locate a slack/taut switch of every wire at every step.
    double prestretch = 0.02;
    double dampingRatio = 0.01;         // damping = dampingRatio * stiffness (s)
};

// Each wire's strength (N, the most tension a tension distribution may give it) and cross-section (m^2, for
// stress = tension / area); docs/whole-body-model.md, "Strength and cross-section", cites the numbers.
struct WholeBodyStrength {
    // Muscles: strength = the source's max isometric force, cross-section (PCSA) = strength / specificTension.
    double specificTension = 0.35e6;  // Pa
    // Tendons beyond a fork: strength = the heads' strengths summed, cross-section = strength / tendonStress.
    double tendonStress = 25e6;  // Pa
    // Ligaments and cartilage: a cross-section per kind, strength = cross-section x ultimate stress.
    double ligamentCrossSection = 30e-6;     // m^2
    double ligamentStress = 35e6;            // Pa
    double cartilageCrossSection = 200e-6;   // m^2
    double cartilageStress = 2e6;            // Pa
};

// Masses the source lacks (MS-Human-700's ribs took theirs from meshes), completed from a segment's mass
// ratio (Dumas 2007): the missing bodies share equally what the segment lacks once the known bodies in it
// are counted; whole-body mass M = (known mass - known segment mass) / (1 - ratio).
struct WholeBodyMassRule {
    std::string segment;                     // Dumas segment name, e.g. Thorax
    std::string gender = "M";
    std::vector<std::string> segmentBodies;  // source bodies of known mass inside the segment
    std::vector<std::string> missingBodies;  // source bodies whose mass is missing
    std::string where;
};

struct WholeBodyRules {
    std::string name = "whole_body";
    std::string file;  // the rules file, for messages
    std::string root;  // the link with the free joint
    std::vector<WholeBodyLinkRule> links;
    std::vector<WholeBodyLoopRule> loops;
    std::vector<WholeBodyForkRule> forks;
    // Source wires whose wraps become via points along their neutral path (as forked heads' do): wraps whose
    // MuJoCo rules make the length jump as the body moves (a side site's tie between the two ways round, an
    // end crossing the circle), which no integrator can carry energy across.
    std::vector<std::string> unwrapped;
    std::vector<WholeBodyPassiveRule> passive;
    std::vector<WholeBodyJointWiresRule> jointWires;
    std::optional<WholeBodyMassRule> missingMass;
    WholeBodyStiffness stiffness;
    WholeBodyStrength strength;
};

// Reads a rules file; ModelError at "file:line" naming the field.
WholeBodyRules readWholeBodyRules(const std::string& path);

// One Dumas 2007 segment row (anthropometrics CSV: UTF-8 BOM, a trailing "j" marking Dumas' negative products
// of inertia). Throws sinew::Error naming the file and line, or the segment and gender it lacks.
struct SegmentRatios {
    double relativeMass = 0;
};
SegmentRatios readSegmentRatios(const std::string& csvPath, const std::string& segment, const std::string& gender);

}  // namespace sinew
