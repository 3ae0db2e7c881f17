// What the assembly schedule leaves out or refuses: virtual links take no part in the forward dynamics (the
// same udot as the model built without them), loops and hangs on them and joint types the dynamics does not
// handle are errors naming the link or joint.
#include <gtest/gtest.h>

#include <random>

#include "sinew/core/forward_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/model_builder.hpp"
#include "support/random_model.hpp"
#include "support/error_assertions.hpp"

namespace sinew {
namespace {

// Copies joint `from`'s slice of a vector of model `a` (q when `positions`, else u) into the joint of the
// same name in model `b`.
void copyJointSlice(const Model& a, const Eigen::VectorXd& va, const Model& b, Eigen::VectorXd& vb, bool positions) {
    for (int i = 0; i < a.getNumLinks(); ++i) {
        const Joint& ja = a.getJoint(i);
        const Joint& jb = b.getJoint(b.findLinkIndex(a.getLink(i).name));
        if (positions) vb.segment(jb.qStart, jb.nq) = va.segment(ja.qStart, ja.nq);
        else vb.segment(jb.uStart, jb.nu) = va.segment(ja.uStart, ja.nu);
    }
}

// The same random model with and without virtual links (they are generated after the links and loops, so
// the rest is identical), at the same state with no link forces: the real joints' udot agree, the virtual
// links' udot are 0.
TEST(AssemblySchedule, VirtualLinksAreLeftOutOfTheDynamics) {
    std::mt19937 rng(5);
    double worst = 0;
    for (unsigned seed = 1; seed <= 6; ++seed) {
        RandomModelOptions o;
        o.numLinks = 12;
        o.numLoops = static_cast<int>(seed % 3);
        o.numWires = 0;
        o.seed = seed;
        o.numVirtualLinks = 2;
        const Model withVirtual = generateRandomModel(o);
        o.numVirtualLinks = 0;
        const Model plain = generateRandomModel(o);
        ASSERT_EQ(withVirtual.getNumLinks(), plain.getNumLinks() + 2);

        const Eigen::VectorXd q = generateRandomCoordinates(plain, rng), u = generateRandomSpeeds(plain, rng);
        const Eigen::VectorXd tau = generateRandomSpeeds(plain, rng, 5.0);
        Eigen::VectorXd qv = generateRandomCoordinates(withVirtual, rng), uv = generateRandomSpeeds(withVirtual, rng);
        Eigen::VectorXd tauv = generateRandomSpeeds(withVirtual, rng, 5.0);
        copyJointSlice(plain, q, withVirtual, qv, true);
        copyJointSlice(plain, u, withVirtual, uv, false);
        copyJointSlice(plain, tau, withVirtual, tauv, false);

        for (const auto kind : {AssemblySchedule::Kind::Serial, AssemblySchedule::Kind::Balanced}) {
            auto evaluate = [&](const Model& model, const Eigen::VectorXd& qm, const Eigen::VectorXd& um,
                                const Eigen::VectorXd& taum) {
                Data data(model);
                calcPositionKinematics(model, data, qm);
                calcVelocityKinematics(model, data, um);
                // Forces on the virtual links would be ignored; none on any link keeps the comparison exact.
                const std::vector<SpatialVector> noForces(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
                const AssemblySchedule schedule(model, kind);
                ForwardDynamicsData fd(model, schedule);
                fd.udot.setConstant(1.0);  // so that the zeros below are written, not left over
                calcForwardDynamics(model, schedule, data, taum, noForces, fd);
                return fd.udot;
            };
            const Eigen::VectorXd udot = evaluate(plain, q, u, tau);
            const Eigen::VectorXd udotVirtual = evaluate(withVirtual, qv, uv, tauv);
            Eigen::VectorXd udotMapped = Eigen::VectorXd::Zero(withVirtual.getNumU());
            copyJointSlice(plain, udot, withVirtual, udotMapped, false);
            const double difference = (udotVirtual - udotMapped).lpNorm<Eigen::Infinity>() /
                                      std::max(udot.lpNorm<Eigen::Infinity>(), 1.0);
            EXPECT_LE(difference, 1e-12) << "seed " << seed;
            worst = std::max(worst, difference);
            for (int i = 0; i < withVirtual.getNumLinks(); ++i) {
                if (!withVirtual.getLink(i).isVirtual) continue;
                const Joint& joint = withVirtual.getJoint(i);
                EXPECT_EQ(udotVirtual.segment(joint.uStart, joint.nu).lpNorm<Eigen::Infinity>(), 0.0) << "seed " << seed;
            }
        }
    }
    std::printf("with and without virtual links: worst relative udot difference %.2e\n", worst);
}

TEST(AssemblySchedule, RefusesToHangByAVirtualLink) {
    RandomModelOptions o;
    o.numLinks = 4;
    o.numVirtualLinks = 1;
    const Model model = generateRandomModel(o);
    int virtualLink = -1;
    for (int i = 0; i < model.getNumLinks(); ++i)
        if (model.getLink(i).isVirtual) virtualLink = i;
    ASSERT_GE(virtualLink, 0);
    EXPECT_TRUE(test::throwsErrorAt([&] { AssemblySchedule(model, AssemblySchedule::Kind::Automatic, virtualLink); },
                                    "model '", {"virtual link '" + model.getLink(virtualLink).name + "'", "hang"},
                                    "hang by a virtual link"));
}

TEST(AssemblySchedule, RefusesALoopOnAVirtualLink) {
    ModelBuilder builder("loop_on_virtual");
    LinkSpec link;
    link.name = "bone";
    link.mass = 1;
    link.inertia_Bcom = 0.01 * Eigen::Matrix3d::Identity();
    builder.addLink(link);
    JointSpec joint;
    joint.name = "hip";
    joint.type = JointType::Ball;
    joint.parent = "ground";
    joint.child = "bone";
    builder.addJoint(joint);
    builder.addVirtualLink({"knot", Eigen::Vector3d(0, -0.2, 0), ""});
    builder.addLoop({"tie", "bone", Eigen::Vector3d(0, -0.2, 0), "knot", Eigen::Vector3d::Zero(), ""});
    const Model model = builder.build();
    EXPECT_TRUE(test::throwsErrorAt([&] { AssemblySchedule schedule(model); }, "model 'loop_on_virtual'",
                                    {"loop 'tie'", "virtual link 'knot'"}, "a loop on a virtual link"));
}

}  // namespace
}  // namespace sinew
