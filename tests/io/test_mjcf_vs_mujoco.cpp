// sinew's MJCF importer against libmujoco 2.2.2 on the published models in ../shared/data (MS-Human-700,
// MyoSuite's arm and full body): at random poses within the joint ranges, MuJoCo's qpos copied into sinew's q
// by joint name, sinew's link frames against MuJoCo's body frames, and its wire lengths and Jacobian rows
// against MuJoCo's spatial-tendon lengths and ten_J (docs/validation.md, "MJCF import against libmujoco").
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>
#include <random>

#include "support/mujoco_reference.hpp"

#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/mjcf_model.hpp"

namespace sinew {
namespace {

namespace fs = std::filesystem;

const fs::path kData = fs::path(SINEW_SHARED_DIR) / "data";

struct PublishedModel {
    const char* label;
    fs::path file;
    int muscles;  // as published: MS-Human-700's name; MyoSuite's README (MyoArm; MyoLeg + MyoBack for the body)
};

const PublishedModel kMsHuman{"MS-Human-700", kData / "ms_human_700" / "MS-Human-700.xml", 700};
const PublishedModel kMyoArm{"myoarm", kData / "myo_sim" / "arm" / "myoarm.xml", 63};
const PublishedModel kMyoBody{"myobody", kData / "myo_sim" / "body" / "myobody.xml", 80 + 210};

constexpr int kPoses = 20;

// MuJoCo's ten_J is d(ten_length)/d(qvel): central differences of its own lengths along each dof, moved on
// the configuration manifold, confirm how the reference reads it (dense rows, qvel's frames) before sinew is
// held to it.
void expectTendonJacobianIsTheDerivativeOfLengths(const PublishedModel& published) {
    if (!fs::exists(published.file)) GTEST_SKIP() << published.file << " is absent (sinew's developer data)";
    test::MujocoReference reference(published.file);
    const std::vector<std::string> tendons = reference.getTendonNames();
    std::mt19937 rng(5);
    constexpr double h = 1e-6;
    double worst = 0;
    std::string worstWhere;
    for (int pose = 0; pose < 2; ++pose) {
        const Eigen::VectorXd qpos = reference.generateRandomQpos(rng);
        std::vector<Eigen::VectorXd> rows;
        reference.calcKinematics(qpos);
        for (const std::string& t : tendons) rows.push_back(reference.getTendonJacobian(t));
        for (int dof = 0; dof < reference.getNumDofs(); ++dof) {
            const Eigen::VectorXd e = Eigen::VectorXd::Unit(reference.getNumDofs(), dof);
            std::vector<double> plus;
            reference.calcKinematics(reference.integrateQpos(qpos, e, h));
            for (const std::string& t : tendons) plus.push_back(reference.getTendonLength(t));
            reference.calcKinematics(reference.integrateQpos(qpos, e, -h));
            for (std::size_t t = 0; t < tendons.size(); ++t) {
                const double difference =
                    std::abs((plus[t] - reference.getTendonLength(tendons[t])) / (2 * h) - rows[t][dof]);
                if (difference <= worst) continue;
                worst = difference;
                worstWhere = tendons[t] + ", dof " + std::to_string(dof) + ", pose " + std::to_string(pose);
            }
        }
    }
    std::cout << published.label << ": MuJoCo's ten_J against differences of ten_length, worst " << worst << " ("
              << worstWhere << ")\n";
    EXPECT_LE(worst, 1e-6) << worstWhere;
}

TEST(MujocoReference, TendonJacobianIsTheDerivativeOfLengthsOnMsHuman700) {
    expectTendonJacobianIsTheDerivativeOfLengths(kMsHuman);
}
TEST(MujocoReference, TendonJacobianIsTheDerivativeOfLengthsOnMyoArm) {
    expectTendonJacobianIsTheDerivativeOfLengths(kMyoArm);
}
TEST(MujocoReference, TendonJacobianIsTheDerivativeOfLengthsOnMyoBody) {
    expectTendonJacobianIsTheDerivativeOfLengths(kMyoBody);
}

// The prepared copy (includes inlined, mesh geoms removed) still holds every muscle the models are published
// with: one actuator each.
TEST(MujocoReference, PreparedModelsKeepTheirPublishedMuscles) {
    for (const PublishedModel* published : {&kMsHuman, &kMyoArm, &kMyoBody}) {
        if (!fs::exists(published->file)) GTEST_SKIP() << published->file << " is absent (sinew's developer data)";
        const test::MujocoReference reference(published->file);
        std::cout << published->label << " in MuJoCo 2.2.2: nbody " << reference.getNumBodies() << ", njnt "
                  << reference.getJoints().size() << ", ntendon " << reference.getNumTendons() << ", nu "
                  << reference.getNumActuators() << ", joint couplings " << reference.getNumJointCouplings() << ";";
        for (const std::string& change : reference.getPreparation().changes) std::cout << " " << change << ";";
        std::cout << "\n";
        EXPECT_EQ(reference.getNumActuators(), published->muscles) << published->label;
    }
}

// The random poses are ones the models can take: MuJoCo finds its joint equalities satisfied there.
TEST(MujocoReference, RandomPosesSatisfyTheJointCouplings) {
    for (const PublishedModel* published : {&kMsHuman, &kMyoArm, &kMyoBody}) {
        if (!fs::exists(published->file)) GTEST_SKIP() << published->file << " is absent (sinew's developer data)";
        test::MujocoReference reference(published->file);
        ASSERT_GT(reference.getNumJointCouplings(), 0) << published->label;
        std::mt19937 rng(3);
        for (int pose = 0; pose < 3; ++pose)
            EXPECT_LE(reference.calcJointCouplingViolation(reference.generateRandomQpos(rng)), 1e-12)
                << published->label << " pose " << pose;
    }
}

// Whether the importer lists the MJCF element `kind` named `name` as left out or changed (mjcf_model.hpp:
// each line starts "<element> '<name>'").
bool isListedAsNotImported(const MjcfConversion& conversion, const std::string& kind, const std::string& name) {
    const std::string start = kind + " '" + name + "'";
    return std::any_of(conversion.notImported.begin(), conversion.notImported.end(),
                       [&](const std::string& line) { return line.compare(0, start.size(), start) == 0; });
}

// Where a MuJoCo joint's qpos and qvel sit in sinew's q and u, under the importer's conventions
// (mjcf_model.hpp): hinges and slides are coordinates named after them (q = qpos, u = qvel), a free joint is
// its body's link's joint. The three models have no ball joint, so none is mapped.
struct JointSlot {
    const test::MujocoJoint* joint = nullptr;
    int link = 0;
    int q = 0, u = 0;
};

struct JointMapping {
    std::vector<JointSlot> slots;
    // Joints the importer lists as left out: the bounded comparison holds them at qpos0 and leaves their
    // Jacobian columns out, so the rest of the model is still held to MuJoCo.
    std::vector<const test::MujocoJoint*> held;
};

JointMapping mapJoints(const MjcfConversion& conversion, const test::MujocoReference& reference,
                       std::vector<std::string>& problems) {
    const Model& model = conversion.model;
    JointMapping mapping;
    for (const test::MujocoJoint& joint : reference.getJoints()) {
        JointSlot slot;
        slot.joint = &joint;
        if (joint.type == test::MujocoJointType::Slide || joint.type == test::MujocoJointType::Hinge) {
            const int c = model.findCoordinateIndex(joint.name);
            if (c == Model::kNotFound) {
                if (isListedAsNotImported(conversion, "joint", joint.name)) mapping.held.push_back(&joint);
                else problems.push_back("no coordinate named after MuJoCo's joint '" + joint.name + "'");
                continue;
            }
            slot.link = model.getCoordinates()[static_cast<std::size_t>(c)].joint;
            const Joint& j = model.getJoint(slot.link);
            slot.q = c;
            slot.u = j.uStart + (c - j.qStart);
        } else if (joint.type == test::MujocoJointType::Ball) {
            problems.push_back("MuJoCo's ball joint '" + joint.name + "': this comparison maps no ball joints");
            continue;
        } else {
            slot.link = model.findLinkIndex(joint.body);
            if (slot.link < 0 || model.getJoint(slot.link).type != JointType::Free) {
                problems.push_back("MuJoCo's free joint '" + joint.name + "' is no free joint of a link '" +
                                   joint.body + "'");
                continue;
            }
            slot.q = model.getJoint(slot.link).qStart;
            slot.u = model.getJoint(slot.link).uStart;
        }
        mapping.slots.push_back(slot);
    }
    if (model.getNumU() + static_cast<int>(mapping.held.size()) != reference.getNumDofs())
        problems.push_back("sinew has " + std::to_string(model.getNumU()) + " speeds (and " +
                           std::to_string(mapping.held.size()) + " joints left out), MuJoCo " +
                           std::to_string(reference.getNumDofs()) + " dofs");
    return mapping;
}

// sinew's q for MuJoCo's qpos: the same numbers, a free joint's position and quaternion swapped into
// sinew's [quaternion, position] order.
Eigen::VectorXd toSinewQ(const Model& model, const std::vector<JointSlot>& slots, const Eigen::VectorXd& qpos) {
    Eigen::VectorXd q = model.getDefaultQ();
    for (const JointSlot& slot : slots) {
        const int a = slot.joint->qposAddress;
        if (slot.joint->type != test::MujocoJointType::Free) {
            q[slot.q] = qpos[a];
            continue;
        }
        q.segment<4>(slot.q) = qpos.segment<4>(a + 3);
        q.segment<3>(slot.q + 4) = qpos.segment<3>(a);
    }
    return q;
}

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
    Eigen::Matrix3d s;
    s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return s;
}

// T (nu x nv) with u = T qvel, at the pose in `data`. MuJoCo's free joint turns at a rate in the body frame
// B and moves the body origin at a velocity in the world, sinew's at w_FM and v_FM (of M's origin) in F, F
// fixed in ground: w_FM = R_FB w_B, v_FM = R_GF^T (v_B + (R_GB w_B) x (p_GM - p_GB)).
Eigen::MatrixXd calcSpeedMap(const Model& model, const Data& data, const std::vector<JointSlot>& slots, int nv) {
    Eigen::MatrixXd T = Eigen::MatrixXd::Zero(model.getNumU(), nv);
    for (const JointSlot& slot : slots) {
        const int d = slot.joint->dofAddress;
        if (slot.joint->type != test::MujocoJointType::Free) {
            T(slot.u, d) = 1;
            continue;
        }
        const std::size_t l = static_cast<std::size_t>(slot.link);
        const Eigen::Matrix3d R_FG = data.R_GF[l].transpose();
        T.block<3, 3>(slot.u, d + 3) = R_FG * data.R_GB[l];
        T.block<3, 3>(slot.u + 3, d) = R_FG;
        T.block<3, 3>(slot.u + 3, d + 3) = -R_FG * skew(data.p_GM[l] - data.p_GB[l]) * data.R_GB[l];
    }
    return T;
}

// The largest difference seen and where.
struct Worst {
    double value = 0;
    std::string where;
    void update(double difference, const std::string& what, int pose) {
        if (!(difference <= value)) value = difference, where = what + " (pose " + std::to_string(pose) + ")";
    }
};

struct PairedTendon {
    int wire = 0;
    std::string name;
    bool wraps = false;          // has a sphere or cylinder geom
    bool declared = false;       // the importer lists it as imported with a change
    bool sideSiteMoves = false;  // has a side site on another link than its wrap object's
};

bool hasSideSiteOnAnotherLink(const Model& model, int w) {
    const std::vector<WireWrap>& wraps = model.getWire(w).wraps;
    return std::any_of(wraps.begin(), wraps.end(), [&](const WireWrap& wrap) {
        return wrap.hasSideSite && wrap.sideSiteLink != model.getWrapObjects()[static_cast<std::size_t>(wrap.object)].link;
    });
}

// MuJoCo's named bodies and its tendons with their sinew links and wires.
struct Pairing {
    std::vector<std::string> bodies;
    std::vector<int> links;
    std::vector<PairedTendon> tendons;
};

// What has no partner is a problem unless the importer lists it as not imported.
Pairing pairObjects(const MjcfConversion& conversion, const test::MujocoReference& reference,
                    std::vector<std::string>& problems) {
    Pairing pairing;
    for (const std::string& body : reference.getBodyNames()) {
        const int link = conversion.model.findLinkIndex(body);
        if (link < 0) problems.push_back("no link named after MuJoCo's body '" + body + "'");
        pairing.bodies.push_back(body);
        pairing.links.push_back(link);
    }
    for (const std::string& tendon : reference.getTendonNames()) {
        const int wire = conversion.model.findWireIndex(tendon);
        const bool listed = isListedAsNotImported(conversion, "tendon", tendon);
        if (wire == Model::kNotFound && !listed)
            problems.push_back("no wire named after MuJoCo's tendon '" + tendon + "'");
        if (wire != Model::kNotFound)
            pairing.tendons.push_back({wire, tendon, reference.isWrapping(tendon), listed,
                                       hasSideSiteOnAnotherLink(conversion.model, wire)});
    }
    return pairing;
}

struct Comparison {
    Worst position, rotation;                 // bodies: m, and the largest entry of R_sinew - R_mujoco
    Worst length, jacobian;                   // tendons without wraps: m, and m per rad or m/m
    Worst wrapLength, wrapJacobian;           // tendons over spheres and cylinders
    // Tendons the importer lists as imported with a change, each on its own: reported, not bounded.
    std::map<std::string, std::pair<Worst, Worst>> declared;  // |dL|, |dJ|
    int wrappedCases = 0;  // (tendon, pose) pairs where MuJoCo's path touches a geom
    // Of the wrapping tendons, those whose side site moves relative to its geom, reported on their own too.
    Worst movingSideLength, movingSideJacobian;
    int movingSideWrappedCases = 0;
};

void comparePose(const Model& model, Data& data, test::MujocoReference& reference, const JointMapping& mapping,
                 const Pairing& pairing, const Eigen::VectorXd& qpos, int pose, Comparison& c) {
    reference.calcKinematics(qpos);
    calcPositionKinematics(model, data, toSinewQ(model, mapping.slots, qpos));
    calcWirePaths(model, data);
    Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
    calcWireJacobian(model, data, J);
    const Eigen::MatrixXd J_qvel = J * calcSpeedMap(model, data, mapping.slots, reference.getNumDofs());
    Eigen::VectorXd comparedDofs = Eigen::VectorXd::Ones(reference.getNumDofs());
    for (const test::MujocoJoint* joint : mapping.held) comparedDofs[joint->dofAddress] = 0;
    for (std::size_t b = 0; b < pairing.bodies.size(); ++b) {
        const std::size_t link = static_cast<std::size_t>(pairing.links[b]);
        const std::string& body = pairing.bodies[b];
        c.position.update((data.p_GB[link] - reference.getBodyPosition(body)).norm(), body, pose);
        c.rotation.update((data.R_GB[link] - reference.getBodyRotation(body)).cwiseAbs().maxCoeff(), body, pose);
    }
    for (const PairedTendon& t : pairing.tendons) {
        const double dL = std::abs(data.wireLength[t.wire] - reference.getTendonLength(t.name));
        const double dJ = ((J_qvel.row(t.wire).transpose() - reference.getTendonJacobian(t.name)).array() *
                           comparedDofs.array()).abs().maxCoeff();
        c.wrappedCases += reference.countActiveWraps(t.name) > 0;
        if (t.sideSiteMoves) {
            c.movingSideLength.update(dL, t.name, pose);
            c.movingSideJacobian.update(dJ, t.name, pose);
            c.movingSideWrappedCases += reference.countActiveWraps(t.name) > 0;
        }
        std::pair<Worst, Worst>* declared = t.declared ? &c.declared[t.name] : nullptr;
        Worst& length = declared ? declared->first : t.wraps ? c.wrapLength : c.length;
        Worst& jacobian = declared ? declared->second : t.wraps ? c.wrapJacobian : c.jacobian;
        length.update(dL, t.name, pose);
        jacobian.update(dJ, t.name, pose);
    }
}

// Bounds. Bodies and straight tendons are the same chain of rigid transforms in both programs, and wrapped
// tendons the same algorithm (WrapMethod::MuJoCo, core/wrap_mujoco.cpp), so only rounding separates them:
// measured up to 2e-14 (docs/validation.md). 1e-9 leaves room for rounding amplified near a tangency, and a
// convention or geometry slip is far larger.
constexpr double kPositionBound = 1e-9;  // m
constexpr double kRotationBound = 1e-9;
constexpr double kLengthBound = 1e-9;    // m
constexpr double kJacobianBound = 1e-9;  // m/rad, m/m

void printSummary(const PublishedModel& published, const Pairing& pairing, const JointMapping& mapping,
                  const Comparison& c, const Comparison* moving) {
    const auto wrapping = std::count_if(pairing.tendons.begin(), pairing.tendons.end(),
                                        [](const PairedTendon& t) { return t.wraps; });
    std::cout << published.label << ": " << pairing.bodies.size() << " bodies, " << mapping.slots.size()
              << " joints, " << pairing.tendons.size() << " tendons (" << wrapping << " wrapping, touching in "
              << c.wrappedCases << " tendon-poses), " << kPoses << " poses; worst |dx| " << c.position.value
              << " m, |dR| " << c.rotation.value << "; straight |dL| " << c.length.value << " m, |dJ| "
              << c.jacobian.value << "; wrapping |dL| " << c.wrapLength.value << " m, |dJ| " << c.wrapJacobian.value
              << "\n";
    const auto movingSide = std::count_if(pairing.tendons.begin(), pairing.tendons.end(),
                                          [](const PairedTendon& t) { return t.sideSiteMoves; });
    if (movingSide > 0)
        std::cout << "  of those, " << movingSide << " with a side site on another body than the geom's (touching in "
                  << c.movingSideWrappedCases << " tendon-poses): |dL| " << c.movingSideLength.value << " m, |dJ| "
                  << c.movingSideJacobian.value << "\n";
    for (const auto& [tendon, worst] : c.declared)
        std::cout << "  tendon '" << tendon << "', which the importer lists as changed: |dL| " << worst.first.value
                  << " m, |dJ| " << worst.second.value << "\n";
    for (const test::MujocoJoint* joint : mapping.held)
        std::cout << "  joint '" << joint->name << "' not imported: held at qpos0 above, Jacobian column not compared\n";
    if (!moving) return;
    const Worst& length = moving->length.value > moving->wrapLength.value ? moving->length : moving->wrapLength;
    std::cout << "  with those joints moving as their couplings drive them: |dx| " << moving->position.value << " m ("
              << moving->position.where << "), |dL| " << length.value << " m (" << length.where << ")\n";
}

void compareWithMujoco(const PublishedModel& published) {
    if (!fs::exists(published.file)) GTEST_SKIP() << published.file << " is absent (sinew's developer data)";
    const MjcfConversion conversion = readMjcfModel(published.file.string());
    const Model& model = conversion.model;
    test::MujocoReference reference(published.file);
    std::vector<std::string> problems;
    const JointMapping mapping = mapJoints(conversion, reference, problems);
    const Pairing pairing = pairObjects(conversion, reference, problems);
    for (const std::string& problem : problems) ADD_FAILURE() << published.label << ": " << problem;
    if (!problems.empty()) return;

    // The joints the importer leaves out are held at qpos0 for the bounded comparison; the same poses with
    // them moving show what leaving them out costs.
    Data data(model);
    std::mt19937 rng(2024);
    const Eigen::VectorXd qpos0 = reference.getQpos0();
    Comparison c, moving;
    for (int pose = 0; pose < kPoses; ++pose) {
        const Eigen::VectorXd coupled = reference.generateRandomQpos(rng);
        Eigen::VectorXd held = coupled;
        for (const test::MujocoJoint* joint : mapping.held) held[joint->qposAddress] = qpos0[joint->qposAddress];
        comparePose(model, data, reference, mapping, pairing, held, pose, c);
        if (!mapping.held.empty()) comparePose(model, data, reference, mapping, pairing, coupled, pose, moving);
    }
    printSummary(published, pairing, mapping, c, mapping.held.empty() ? nullptr : &moving);
    EXPECT_LE(c.position.value, kPositionBound) << c.position.where;
    EXPECT_LE(c.rotation.value, kRotationBound) << c.rotation.where;
    EXPECT_LE(c.length.value, kLengthBound) << c.length.where;
    EXPECT_LE(c.jacobian.value, kJacobianBound) << c.jacobian.where;
    EXPECT_LE(c.wrapLength.value, kLengthBound) << c.wrapLength.where;
    EXPECT_LE(c.wrapJacobian.value, kJacobianBound) << c.wrapJacobian.where;
}

TEST(MjcfVsMujoco, MsHuman700) { compareWithMujoco(kMsHuman); }
TEST(MjcfVsMujoco, MyoArm) { compareWithMujoco(kMyoArm); }
TEST(MjcfVsMujoco, MyoBody) { compareWithMujoco(kMyoBody); }

}  // namespace
}  // namespace sinew
