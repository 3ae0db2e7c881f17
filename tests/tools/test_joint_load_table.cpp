// The somatosensory tables of a tension analysis (docs/tensions-from-motion.md, "Somatosensory outputs"),
// on the stander (tests/support/standing_model.hpp) swinging its right leg about the hip while the left foot
// stands, worked by hand from the links' masses, the motion's accelerations and the solved forces:
// - each hip carries its leg's Newton-Euler balance: inertial force less gravity, the wires' pulls along
//   their straight segments and, on the standing leg, the contact's wrench (from the contact table);
// - the root joint carries the whole body's (the wires' pulls cancel in pairs): Newton and Euler for the
//   whole body against gravity and the contact, with the root's residual in it;
// - ligament stress is tension over the cross-section the model gives, for ligaments that have one only.
// On the whole-body model standing (loops, virtual links, four feet, a reserve on every DOF): with the
// solver's loop forces and the generalized forces the solution leaves to the joints, the equations close
// (inverse dynamics explains every DOF, the reactions' own loop solve adds nothing), the table's loop
// columns are the solver's loop forces, and the root carries Newton's balance of the whole body.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "sinew/core/kinematics.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/tensions/contact_columns.hpp"
#include "sinew/tools/joint_load_table.hpp"
#include "sinew/tools/tension_motion.hpp"
#include "support/standing_model.hpp"
#include "support/test_models.hpp"

namespace sinew {
namespace {

constexpr double kLigamentArea = 2e-4;  // m^2, hip_r_0's cross-section

// The stander with hip_r_0 a ligament of cross-section kLigamentArea and hip_l_0 a ligament without one.
Model makeStanderWithLigaments() {
    std::string text = test::standingModelText();
    const std::string muscle = "kind: muscle\n";
    const std::size_t first = text.find("name: hip_r_0\n");
    text.replace(text.find(muscle, first), muscle.size(),
                 "kind: ligament\n    cross_section: " + std::to_string(kLigamentArea) + "\n");
    const std::size_t left = text.find("name: hip_l_0\n");
    text.replace(text.find(muscle, left), muscle.size(), "kind: ligament\n");
    return readModelText(text, "stander_ligaments.yaml");
}

// The right hip turning about y by theta(t) = 0.3 sin(2 pi 2 t) (a fixed axis, so u = theta' y in F and in
// the leg alike), the trunk and the left leg still.
struct Swing {
    CoordinateTrajectory states;
    Eigen::VectorXd angle, rate, acceleration;  // (frames) rad, rad/s, rad/s^2
};

Swing makeSwing(const Model& model, int frames) {
    Swing swing;
    CoordinateTrajectory& states = swing.states;
    states.times = Eigen::VectorXd::LinSpaced(frames, 0, 0.02 * (frames - 1));
    states.q = model.getDefaultQ().transpose().replicate(frames, 1);
    states.qdot = Eigen::MatrixXd::Zero(frames, model.getNumU());
    states.qddot = states.qdot;
    const Joint& hip = model.getJoint(model.findLinkIndex("leg_r"));
    const double w = 4 * M_PI, amplitude = 0.3;
    swing.angle = amplitude * (w * states.times.array()).sin();
    swing.rate = amplitude * w * (w * states.times.array()).cos();
    swing.acceleration = -w * w * swing.angle;
    for (int i = 0; i < frames; ++i) {
        const Eigen::Quaterniond rotation(Eigen::AngleAxisd(swing.angle[i], Eigen::Vector3d::UnitY()));
        states.q.block<1, 4>(i, hip.qStart) << rotation.w(), rotation.x(), rotation.y(), rotation.z();
        states.qdot(i, hip.uStart + 1) = swing.rate[i];
        states.qddot(i, hip.uStart + 1) = swing.acceleration[i];
    }
    return swing;
}

double column(const StorageTable& table, std::size_t row, const std::string& name) {
    for (std::size_t k = 0; k < table.columns.size(); ++k)
        if (table.columns[k] == name) return table.rows[row][k];
    ADD_FAILURE() << "table '" << table.name << "' has no column " << name;
    return 0;
}

Eigen::Vector3d vector(const StorageTable& table, std::size_t row, const std::string& prefix) {
    return {column(table, row, prefix + "x"), column(table, row, prefix + "y"), column(table, row, prefix + "z")};
}

// A link's pose and motion in ground, by hand: the trunk stays at the model's default pose (identity
// orientation at its initial position); a leg hangs from its hip centre, turned by `angle` about y.
struct LinkMotion {
    Eigen::Matrix3d R_GB = Eigen::Matrix3d::Identity();
    Eigen::Vector3d p_GB = Eigen::Vector3d::Zero();
    Eigen::Vector3d w = Eigen::Vector3d::Zero(), alpha = Eigen::Vector3d::Zero();
};

// The spatial force [moment about p; force] (ground axes) that a link's motion needs beyond gravity:
// I alpha + w x I w + (c - p) x m (a_c - g), m (a_c - g).
Eigen::Matrix<double, 6, 1> inertialForce(const Model& model, int link, const LinkMotion& motion,
                                          const Eigen::Vector3d& p) {
    const Link& body = model.getLink(link);
    const Eigen::Vector3d r = motion.R_GB * body.com_B;  // from the origin, which is fixed (trunk) or the hip
    const Eigen::Vector3d a = motion.alpha.cross(r) + motion.w.cross(motion.w.cross(r));
    const Eigen::Matrix3d I = motion.R_GB * body.inertia_Bcom * motion.R_GB.transpose();
    const Eigen::Vector3d f = body.mass * (a - model.getGravity());
    Eigen::Matrix<double, 6, 1> F;
    F << I * motion.alpha + motion.w.cross(I * motion.w) + (motion.p_GB + r - p).cross(f), f;
    return F;
}

TEST(JointLoadTable, HipsAndRootCarryTheirSubtreesNewtonEulerBalance) {
    const Model model = makeStanderWithLigaments();
    const int frames = 6;
    const Swing swing = makeSwing(model, frames);
    TensionMotionOptions options;
    options.analysis.method = "lp";
    options.analysis.maxTension = Eigen::VectorXd::Constant(model.getNumWires(), 2000);
    const TensionMotionResult result = runTensionAnalysis(model, swing.states, nullptr, options);
    ASSERT_EQ(result.jointLoads.rows.size(), static_cast<std::size_t>(frames));
    ASSERT_EQ(result.jointLoads.columns.size(), 3u * 6u);  // root, hip_r, hip_l; no loops

    const int trunk = model.findLinkIndex("trunk");
    const Eigen::Vector3d p_trunk = model.getDefaultQ().segment<3>(model.getJoint(trunk).qStart + 4);
    int standing = 0;
    for (int i = 0; i < frames; ++i) {
        const std::size_t row = static_cast<std::size_t>(i);
        // The contact forces the solution gives, as the contact table reports them (ground axes).
        const StorageTable& contact = result.contact;
        EXPECT_EQ(column(contact, row, "foot_r_in_contact"), 0) << "the swinging foot, frame " << i;
        standing += column(contact, row, "foot_l_in_contact") == 1;
        std::vector<LinkMotion> motion(static_cast<std::size_t>(model.getNumLinks()));
        motion[static_cast<std::size_t>(trunk)].p_GB = p_trunk;
        Eigen::Matrix<double, 6, 1> wholeBody = Eigen::Matrix<double, 6, 1>::Zero();  // about the trunk's origin
        for (const char* side : {"r", "l"}) {
            const int leg = model.findLinkIndex(std::string("leg_") + side);
            const Joint& hip = model.getJoint(leg);
            LinkMotion& m = motion[static_cast<std::size_t>(leg)];
            m.p_GB = p_trunk + hip.p_PF;
            if (side[0] == 'r') {
                m.R_GB = Eigen::AngleAxisd(swing.angle[i], Eigen::Vector3d::UnitY()).toRotationMatrix();
                m.w = swing.rate[i] * Eigen::Vector3d::UnitY();
                m.alpha = swing.acceleration[i] * Eigen::Vector3d::UnitY();
            }
            // The hip's load on the leg, about the hip centre: what the leg's motion needs less what the wires
            // and the ground give it.
            Eigen::Matrix<double, 6, 1> load = inertialForce(model, leg, m, m.p_GB);
            for (int w = 0; w < model.getNumWires(); ++w) {
                const Wire& wire = model.getWire(w);
                const WirePoint& onTrunk = model.getWirePoints()[static_cast<std::size_t>(wire.firstPoint)];
                const WirePoint& onLeg = model.getWirePoints()[static_cast<std::size_t>(wire.firstPoint + 1)];
                if (onLeg.link != leg) continue;
                const Eigen::Vector3d a = p_trunk + onTrunk.p_B, b = m.p_GB + m.R_GB * onLeg.p_B;
                const double tension = result.tensions.rows[row][static_cast<std::size_t>(w)];
                const Eigen::Vector3d pull = tension * (a - b).normalized();
                load.head<3>() -= (b - m.p_GB).cross(pull);
                load.tail<3>() -= pull;
            }
            const std::string foot = std::string("foot_") + side;
            const Eigen::Vector3d force = vector(contact, row, foot + "_f"), cop = vector(contact, row, foot + "_cop");
            load.head<3>() -= vector(contact, row, foot + "_m") + (cop - m.p_GB).cross(force);
            load.tail<3>() -= force;

            const std::string name = hip.name;
            const Eigen::Vector3d moment_B = vector(result.jointLoads, row, name + "_m");
            const Eigen::Vector3d force_B = vector(result.jointLoads, row, name + "_f");
            const double scale = 1 + load.norm();
            EXPECT_NEAR((m.R_GB * moment_B - load.head<3>()).norm(), 0, 1e-9 * scale) << name << " frame " << i;
            EXPECT_NEAR((m.R_GB * force_B - load.tail<3>()).norm(), 0, 1e-9 * scale) << name << " frame " << i;

            wholeBody += inertialForce(model, leg, m, p_trunk);
            wholeBody.head<3>() -= vector(contact, row, foot + "_m") + (cop - p_trunk).cross(force);
            wholeBody.tail<3>() -= force;
        }
        // The root: the whole body's balance (the trunk's axes are ground's), which the contact leaves to the
        // root's residual.
        wholeBody += inertialForce(model, trunk, motion[static_cast<std::size_t>(trunk)], p_trunk);
        const std::string root = model.getJoint(trunk).name;
        const double scale = 1 + wholeBody.norm();
        EXPECT_NEAR((vector(result.jointLoads, row, root + "_m") - wholeBody.head<3>()).norm(), 0, 1e-9 * scale) << i;
        EXPECT_NEAR((vector(result.jointLoads, row, root + "_f") - wholeBody.tail<3>()).norm(), 0, 1e-9 * scale) << i;
        EXPECT_NEAR(vector(result.jointLoads, row, root + "_f").norm(), column(contact, row, "root_force_residual"),
                    1e-9 * scale) << i;
    }
    EXPECT_EQ(standing, frames);  // the left foot is down throughout, so its contact forces are checked

    // Ligament stress: hip_r_0 alone (hip_l_0 has no cross-section, the others are muscles).
    ASSERT_EQ(result.ligamentStress.columns, std::vector<std::string>{"hip_r_0"});
    ASSERT_EQ(result.ligamentStress.rows.size(), static_cast<std::size_t>(frames));
    const std::size_t hip_r_0 = static_cast<std::size_t>(model.findWireIndex("hip_r_0"));
    double largest = 0;
    for (std::size_t row = 0; row < result.ligamentStress.rows.size(); ++row) {
        const double tension = result.tensions.rows[row][hip_r_0];
        EXPECT_NEAR(result.ligamentStress.rows[row][0], tension / kLigamentArea, 1e-12 * (1 + tension / kLigamentArea));
        largest = std::max(largest, tension);
    }
    EXPECT_GT(largest, 1);  // the ligament pulls on some frame, so the check is not 0 = 0
}

// Without a ligament that has a cross-section there is no stress table; missing-input frames get zero rows.
TEST(JointLoadTable, NoStressTableWithoutCrossSectionsAndZeroRowsForMissingFrames) {
    const Model model = test::makeStandingModel();
    StorageTable motion;
    motion.columns = getCoordinateNames(model);
    for (int i = 0; i < 8; ++i) {
        motion.times.push_back(0.01 * i);
        const Eigen::VectorXd q = model.getDefaultQ();
        motion.rows.emplace_back(q.data(), q.data() + q.size());
    }
    motion.rows[4][0] = std::nan("");
    TensionMotionOptions options;
    options.analysis.method = "lp";
    options.analysis.maxTension = Eigen::VectorXd::Constant(model.getNumWires(), 2000);
    const TensionMotionResult result = runTensionAnalysis(model, motion, nullptr, options);
    EXPECT_TRUE(result.ligamentStress.columns.empty());
    ASSERT_EQ(result.missingRows, std::vector<int>{4});
    ASSERT_EQ(result.jointLoads.rows.size(), 8u);
    EXPECT_EQ(result.jointLoads.times[4], motion.times[4]);
    for (double value : result.jointLoads.rows[4]) EXPECT_EQ(value, 0);
    // The solved frames' rows are not zero (the hips hold the legs), so the zero row marks the missing one.
    for (const std::size_t row : {3u, 5u})
        EXPECT_GT(std::abs(column(result.jointLoads, row, "hip_r_fz")), 1) << "row " << row;
}

TEST(JointLoadTable, WholeBodyLoopsKeepTheSolversForcesAndTheRootNewtonsBalance) {
    const Model model = readModelFile(test::sourcePath("models/whole_body/whole_body.yaml"));
    ASSERT_GT(model.getNumLoops(), 0);
    const auto contacts = std::make_shared<ContactColumns>(model);
    contacts->setInContact(std::vector<char>(model.getContacts().size(), 1));
    TensionAnalysisOptions options;
    options.method = "lp";
    options.maxTension = Eigen::VectorXd::Constant(model.getNumWires(), 5000);
    options.columns = {contacts};
    // A reserve on every DOF (one-signed, so the LP is bounded), cheaper per N m than the wires: the
    // solution leaves generalized forces to the joints, which must not end up in the loops.
    const std::vector<std::string> dofs = getSpeedNames(model);
    for (int dof = 0; dof < model.getNumU(); ++dof)
        options.reserves.push_back({dofs[static_cast<std::size_t>(dof)] + "_reserve", dof, 1, 0});  // pushes only
    TensionAnalysis analysis(model, options);
    const Eigen::VectorXd q = model.getDefaultQ(), zero = Eigen::VectorXd::Zero(model.getNumU());
    const std::vector<SpatialVector> noLoads(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
    const TensionFrame& frame = analysis.calcFrame(q, zero, zero, noLoads);
    ASSERT_NE(frame.status, DistributionStatus::Failed);
    StorageTable table;
    JointLoadTable loads(model, contacts, table);
    Data frameData(model);
    loads.appendFrame(MotionFrame{0, 0.0, q, zero, zero, noLoads, frameData, false}, analysis, frame);
    const JointReactionsData& reactions = loads.getReactions();

    double mass = 0;
    for (const Link& link : model.getLinks()) mass += link.mass;
    const double weight = mass * model.getGravity().norm();
    // The solver's loop forces with the tensions, the contacts and the applied generalized forces explain
    // every DOF: nothing is left to the residual, and the reactions' own loop solve adds no force.
    EXPECT_LE(reactions.residual.lpNorm<Eigen::Infinity>(), 1e-9 * weight);
    const Eigen::VectorXd& x = analysis.getSolution().x;
    const Eigen::Index loopStart = x.size() - 3 * model.getNumLoops();
    Data data(model);
    calcPositionKinematics(model, data, q);
    const std::size_t loopColumns = 6 * static_cast<std::size_t>(model.getNumLinks());
    double loopForces = 0;
    for (int k = 0; k < model.getNumLoops(); ++k) {
        const std::size_t l = static_cast<std::size_t>(k);
        EXPECT_LE(reactions.loopForce_G[l].norm(), 1e-9 * weight) << model.getLoop(k).name;
        const Eigen::Vector3d f_G = x.segment<3>(loopStart + 3 * k);
        loopForces += f_G.norm();
        // The table's loop columns: the solver's force in link B's axes.
        ASSERT_EQ(table.columns[loopColumns + 3 * l], model.getLoop(k).name + "_fx");
        const Eigen::Vector3d f_B(table.rows[0][loopColumns + 3 * l], table.rows[0][loopColumns + 3 * l + 1],
                                  table.rows[0][loopColumns + 3 * l + 2]);
        EXPECT_LE((data.R_GB[static_cast<std::size_t>(model.getLoop(k).linkB)] * f_B - f_G).norm(), 1e-12 * weight);
    }
    EXPECT_GT(loopForces, 1);  // the loops pull, so the checks above are not 0 = 0
    EXPECT_GT(frame.reserveForce.lpNorm<1>(), 1);  // and the reserves act

    // At rest the root's force is the body's weight less the ground's push (wires and loops are internal).
    const Eigen::VectorXd beta = x.segment(analysis.getColumnStart(0), contacts->count());
    Eigen::Vector3d ground = Eigen::Vector3d::Zero();
    for (int c = 0; c < static_cast<int>(model.getContacts().size()); ++c)
        ground += contacts->calcWrench(data, c, beta).force;
    EXPECT_GT(ground.z(), 0.5 * weight);  // the feet carry the body
    const int pelvis = model.findLinkIndex("pelvis");
    const Eigen::Vector3d rootForce_G = reactions.F_GM[static_cast<std::size_t>(pelvis)].tail<3>();
    EXPECT_LE((rootForce_G - (-mass * model.getGravity() - ground)).norm(), 1e-9 * weight);
    const std::size_t fx = 6 * static_cast<std::size_t>(pelvis) + 3;
    EXPECT_EQ(table.columns[fx], model.getJoint(pelvis).name + "_fx");
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(table.rows[0][fx + static_cast<std::size_t>(c)],
                    reactions.F_BM[static_cast<std::size_t>(pelvis)][3 + c], 1e-12 * weight);
}

}  // namespace
}  // namespace sinew
