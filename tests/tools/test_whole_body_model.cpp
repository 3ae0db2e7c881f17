// The shipped whole-body model (models/whole_body/whole_body.yaml) against what the paper's model has, against
// the source it was derived from (MS-Human-700 imported from MJCF, where ../shared is present), and in forward
// dynamics: ligaments slack at neutral and taut at their limits through the model's own joints, virtual links
// in equilibrium in the hang by the head (both engines' udot on it: tests/plugin/test_virtual_links.cpp); every
// wire's strength and cross-section, against the source's forces.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <vector>
#include <string>

#include "sinew/core/census.hpp"
#include "sinew/core/data.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/forward_simulation.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/io/model_loading.hpp"
#include "sinew/plugin/simbody_simulation.hpp"
#include "sinew/tools/whole_body_model.hpp"

namespace sinew {
namespace {

const std::filesystem::path kModelDir = std::filesystem::path(SINEW_SOURCE_DIR) / "models" / "whole_body";
const std::filesystem::path kShared = std::filesystem::path(SINEW_SHARED_DIR) / "data";
const std::filesystem::path kSource = kShared / "ms_human_700" / "MS-Human-700.xml";
const std::filesystem::path kDumas = kShared / "anthropometrics" / "dumas_2007.csv";

const Model& getShippedModel() {
    static const Model model = readModelFile((kModelDir / "whole_body.yaml").string());
    return model;
}

// Of the peak kinetic energy, as the issue asks of tight accuracy.
constexpr double kEnergyBound = 1e-6;

WholeBodyBuild deriveFromSource(const WholeBodyRules& rules) {
    const Model source = loadModel(kSource.string(), [](const std::string&) {});
    return buildWholeBodyModel(source, rules, readSegmentRatios(kDumas.string(), rules.missingMass->segment,
                                                                rules.missingMass->gender));
}

TEST(WholeBodyModel, CensusHasThePapersStructure) {
    const Census census = calcCensus(getShippedModel());
    EXPECT_GE(census.links, 50);
    EXPECT_GE(census.virtualLinks, 10);
    EXPECT_GE(census.loops, 4);
    EXPECT_GE(census.ligaments, 30);
    EXPECT_GE(census.cartilage, 1);
    EXPECT_GE(census.wires, 600);
    const Model& model = getShippedModel();
    for (int i = 0; i < model.getNumLinks(); ++i) {
        if (model.getLink(i).isVirtual) continue;
        const JointType type = model.getJoint(i).type;
        EXPECT_TRUE(type == JointType::Ball || type == JointType::Free) << model.getJoint(i).name;
    }
}

TEST(WholeBodyModel, ShippedFileIsWhatTheToolWritesFromTheSource) {
    if (!std::filesystem::exists(kSource)) GTEST_SKIP() << kSource << " is absent (it ships only with sinew's developer data)";
    const WholeBodyBuild built = deriveFromSource(readWholeBodyRules((kModelDir / "rules.yaml").string()));
    std::ifstream in(kModelDir / "whole_body.yaml");
    std::stringstream shipped;
    shipped << in.rdbuf();
    const std::string written = writeModelText(built.model);
    if (written == shipped.str()) return;
    std::stringstream a(shipped.str()), b(written);
    int line = 1;
    for (std::string x, y; std::getline(a, x) && std::getline(b, y) && x == y;) ++line;
    ADD_FAILURE() << "whole_body.yaml:" << line << " differs from what the tool writes; regenerate it with the "
                  << "command in models/whole_body/rules.yaml";
}

// Each source wire kept whole has, at the neutral pose, the length the imported source gives it.
TEST(WholeBodyModel, KeptWiresHaveTheSourceLengthsAtNeutral) {
    if (!std::filesystem::exists(kSource)) GTEST_SKIP() << kSource << " is absent (it ships only with sinew's developer data)";
    const Model source = loadModel(kSource.string(), [](const std::string&) {});
    const Model& model = getShippedModel();
    Data sourceData(source), data(model);
    calcPositionKinematics(source, sourceData, source.getDefaultQ());
    calcWirePaths(source, sourceData);
    calcPositionKinematics(model, data, model.getDefaultQ());
    calcWirePaths(model, data);
    int compared = 0;
    double worst = 0;
    for (int w = 0; w < source.getNumWires(); ++w) {
        const int v = model.findWireIndex(source.getWire(w).name);
        ASSERT_NE(v, Model::kNotFound) << source.getWire(w).name;
        const Wire& wire = model.getWire(v);
        bool forked = false;  // a forked head ends on a virtual link; docs/whole-body-model.md gives their lengths
        for (int i = 0; i < wire.numPoints; ++i)
            forked = forked || model.getLink(model.getWirePoints()[wire.firstPoint + i].link).isVirtual;
        if (forked) continue;
        EXPECT_NEAR(data.wireLength[v], sourceData.wireLength[w], 1e-3) << source.getWire(w).name;
        worst = std::max(worst, std::abs(data.wireLength[v] - sourceData.wireLength[w]));
        ++compared;
    }
    EXPECT_GE(compared, 600);
    std::printf("%d source wires kept whole: neutral lengths within %.3g m of the source's\n", compared, worst);
}

// Every wire can enter a tension distribution and report a stress: a finite, positive strength and cross-section.
// The muscles' strengths are the max isometric forces of the source as sinew's MJCF importer reads it, a fork's
// tendon carries its heads' sum, and each cross-section is its strength at the stress the rules give its kind.
TEST(WholeBodyModel, EveryWireHasAStrengthAndCrossSection) {
    const Model& model = getShippedModel();
    const WholeBodyRules rules = readWholeBodyRules((kModelDir / "rules.yaml").string());
    const WholeBodyStrength& s = rules.strength;
    for (const Wire& wire : model.getWires()) {
        SCOPED_TRACE(wire.name);
        ASSERT_TRUE(wire.strength && wire.crossSection);
        EXPECT_TRUE(std::isfinite(*wire.strength) && *wire.strength > 0);
        EXPECT_TRUE(std::isfinite(*wire.crossSection) && *wire.crossSection > 0);
        EXPECT_EQ(getWireStrength(wire), wire.strength);  // spring-dampers all: the strength is the wire's own
        const double stress = *wire.strength / *wire.crossSection;
        switch (wire.kind) {
            case WireKind::Muscle: EXPECT_NEAR(stress, s.specificTension, 1e-9 * s.specificTension); break;
            case WireKind::Tendon: EXPECT_NEAR(stress, s.tendonStress, 1e-9 * s.tendonStress); break;
            case WireKind::Ligament:
                EXPECT_EQ(*wire.crossSection, s.ligamentCrossSection);
                EXPECT_NEAR(stress, s.ligamentStress, 1e-9 * s.ligamentStress);
                break;
            case WireKind::Cartilage:
                EXPECT_EQ(*wire.crossSection, s.cartilageCrossSection);
                EXPECT_NEAR(stress, s.cartilageStress, 1e-9 * s.cartilageStress);
                break;
        }
    }
    if (!std::filesystem::exists(kSource)) GTEST_SKIP() << kSource << " is absent (it ships only with sinew's developer data)";
    const Model source = loadModel(kSource.string(), [](const std::string&) {});
    auto sourceForce = [&](const std::string& name) {
        const int w = source.findWireIndex(name);
        if (w == Model::kNotFound) {
            ADD_FAILURE() << "no wire '" << name << "' in the source";
            return 0.0;
        }
        const std::optional<double> force = source.getWire(w).law->getMaxIsometricForce();
        EXPECT_TRUE(force) << name;
        return force.value_or(0.0);
    };
    int muscles = 0;
    for (const Wire& wire : model.getWires()) {
        if (wire.kind != WireKind::Muscle) continue;
        EXPECT_EQ(*wire.strength, sourceForce(wire.name)) << wire.name;
        ++muscles;
    }
    EXPECT_EQ(muscles, source.getNumWires());
    for (const WholeBodyForkRule& fork : rules.forks) {
        double heads = 0;
        for (const std::string& head : fork.heads) heads += sourceForce(head);
        const int tendon = model.findWireIndex(fork.tendon);
        ASSERT_NE(tendon, Model::kNotFound) << fork.tendon;
        EXPECT_NEAR(*model.getWire(tendon).strength, heads, 1e-12 * heads) << fork.tendon;
    }
}

// The rules' strength numbers must be > 0, each rejected at its file's line, naming the field.
TEST(WholeBodyModel, RulesRejectAStrengthNumberThatIsNotPositive) {
    const std::filesystem::path path = std::filesystem::temp_directory_path() / "sinew_strength_rules.yaml";
    for (const std::string field :
         {"specific_tension", "tendon_stress", "ligament_cross_section", "cartilage_stress"}) {
        SCOPED_TRACE(field);
        std::ofstream(path) << "whole_body_rules: 1\nroot: pelvis\nstrength:\n  " << field << ": 0\n";
        try {
            readWholeBodyRules(path.string());
            ADD_FAILURE() << "a zero " << field << " was accepted";
        } catch (const ModelError& e) {
            const std::string message = e.what();
            EXPECT_EQ(message.rfind(path.string() + ":4: ", 0), 0u) << message;
            EXPECT_NE(message.find("'" + field + "' must be > 0"), std::string::npos) << message;
        }
    }
    std::filesystem::remove(path);
}

// The ball joint's quaternion for `link` turned by angle about axis (ground axes; the model's link frames are
// parallel to ground at neutral, so the parent frame's axes are ground's there).
Eigen::VectorXd turnJoint(const Model& model, int link, const Eigen::Vector3d& axis, double angle) {
    Eigen::VectorXd q = model.getDefaultQ();
    const Joint& joint = model.getJoint(link);
    const Eigen::Quaterniond turn(Eigen::AngleAxisd(angle, axis.normalized()));
    q.segment<4>(joint.qStart) << turn.w(), turn.x(), turn.y(), turn.z();
    return q;
}

double getRestLength(const Wire& wire) { return wire.lawSpec.parameters.getScalar("rest_length"); }

// Through the model's own joints (not the tool's point rotation): each joint ligament is slack at neutral and
// taut at the limit that stretches it, one of the turns about its flexion or abduction axis.
TEST(WholeBodyModel, LigamentsAreSlackAtNeutralAndTautAtTheirLimits) {
    const Model& model = getShippedModel();
    const WholeBodyRules rules = readWholeBodyRules((kModelDir / "rules.yaml").string());
    Data data(model);
    calcPositionKinematics(model, data, model.getDefaultQ());
    calcWirePaths(model, data);
    int checked = 0;
    for (const WholeBodyJointWiresRule& rule : rules.jointWires) {
        if (rule.kind != WireKind::Ligament) continue;
        const int link = model.findLinkIndex(rule.joint);
        const Eigen::Vector3d f = rule.flexionAxis.normalized(), d = rule.boneAxis.normalized().cross(f).normalized();
        for (int k = 0; k < 4; ++k) {
            const int w = model.findWireIndex(rule.name + "_" + rule.names[static_cast<std::size_t>(k)]);
            ASSERT_NE(w, Model::kNotFound);
            EXPECT_LT(data.wireLength[w], getRestLength(model.getWire(w))) << model.getWire(w).name << " taut at neutral";
            double longest = 0;
            for (double sign : {1.0, -1.0}) {
                Data turned(model);
                calcPositionKinematics(model, turned, turnJoint(model, link, k < 2 ? f : d, sign * (k < 2 ? rule.flexion : rule.abduction)));
                calcWirePaths(model, turned);
                longest = std::max(longest, turned.wireLength[w]);
            }
            EXPECT_GT(longest, getRestLength(model.getWire(w))) << model.getWire(w).name << " slack at its limit";
            ++checked;
        }
    }
    EXPECT_GE(checked, 30);
}

// The paper's section 4.1: hung by the head, the body falls into its wires; each virtual link stays balanced.
TEST(WholeBodyModel, VirtualLinksStayInEquilibriumInTheHang) {
    ForwardSimulationOptions options;
    options.hangBy = "head_neck";
    options.duration = 0.02;
    options.integrator = ForwardSimulationOptions::Integrator::RungeKutta4Fixed;
    options.fixedStep = 1e-4;
    const SimulationSummary summary = simulateForwardSinew(getShippedModel(), options, [](const SimulationFrame&) {});
    EXPECT_LE(summary.maxVirtualLinkResidual, 1e-6);
    EXPECT_GT(summary.peakKineticEnergy, 0);
}

// The hang undamped at tight accuracy, with both engines: they agree on the bones' coordinates, and each keeps the
// energy to its integrator's error (the wraps whose MuJoCo rules make a length jump are unwrapped by the rules,
// docs/whole-body-model.md; every other force is the gradient of the wires' potential).
TEST(WholeBodyModel, BothEnginesAgreeOnTheUndampedHangAndConserveEnergy) {
    if (!std::filesystem::exists(kSource)) GTEST_SKIP() << kSource << " is absent (it ships only with sinew's developer data)";
    WholeBodyRules rules = readWholeBodyRules((kModelDir / "rules.yaml").string());
    rules.stiffness.dampingRatio = 0;
    const Model model = deriveFromSource(rules).model;
    ForwardSimulationOptions options;
    options.hangBy = "head_neck";
    options.duration = 0.1;  // the first 0.1 s, before the motion turns chaotic
    options.reportInterval = 0.01;
    options.accuracy = 1e-8;
    std::vector<Eigen::VectorXd> sinewQ, simbodyQ;
    const SimulationSummary sinewRun =
        simulateForwardSinew(model, options, [&](const SimulationFrame& frame) { sinewQ.push_back(frame.q); });
    const SimulationSummary simbodyRun =
        simulateForward(model, options, [&](const SimulationFrame& frame) { simbodyQ.push_back(frame.q); });
    ASSERT_EQ(sinewQ.size(), simbodyQ.size());
    int boneQ = model.getNumQ();  // virtual links come last; their poses are each engine's own equilibrium solve
    for (int i = model.getNumLinks() - 1; i >= 0 && model.getLink(i).isVirtual; --i) boneQ = model.getJoint(i).qStart;
    double worst = 0;
    for (std::size_t k = 0; k < sinewQ.size(); ++k)
        worst = std::max(worst, (sinewQ[k] - simbodyQ[k]).head(boneQ).cwiseAbs().maxCoeff());
    std::printf("undamped whole-body hang, 0.1 s at accuracy 1e-8: max |dq| %.3g; energy drift sinew %.3g J, "
                "Simbody %.3g J, of peak kinetic energy %.3g J\n",
                worst, sinewRun.maxEnergyDrift, simbodyRun.maxEnergyDrift, sinewRun.peakKineticEnergy);
    EXPECT_LE(worst, 1e-6);
    EXPECT_LE(sinewRun.maxEnergyDrift, kEnergyBound * sinewRun.peakKineticEnergy);
    EXPECT_LE(simbodyRun.maxEnergyDrift, kEnergyBound * simbodyRun.peakKineticEnergy);
}

}  // namespace
}  // namespace sinew
