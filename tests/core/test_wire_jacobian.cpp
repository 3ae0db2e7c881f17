// The wire Jacobian against central finite differences of wire lengths, on random models with loops and
// virtual links, and its consistency with the wire speeds it predicts.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "support/test_models.hpp"

namespace sinew {
namespace {

Eigen::VectorXd calcLengths(const Model& model, Data& data, const Eigen::VectorXd& q) {
    calcPositionKinematics(model, data, q);
    calcWirePaths(model, data);
    return data.wireLength;
}

// Central differences along each mobility, moving q on its manifold (quaternions rotate exactly).
Eigen::MatrixXd calcJacobianByFiniteDifferences(const Model& model, const Eigen::VectorXd& q, double h) {
    Data data(model);
    Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
    for (int i = 0; i < model.getNumU(); ++i) {
        const Eigen::VectorXd e = Eigen::VectorXd::Unit(model.getNumU(), i);
        const Eigen::VectorXd plus = calcLengths(model, data, integrateCoordinates(model, q, e, h));
        const Eigen::VectorXd minus = calcLengths(model, data, integrateCoordinates(model, q, e, -h));
        J.col(i) = (plus - minus) / (2 * h);
    }
    return J;
}

TEST(WireJacobian, MatchesCentralFiniteDifferencesOnRandomModels) {
    std::mt19937 rng(7);
    for (const test::NamedModel& m : test::makeRandomModels(30, true)) {
        const Model& model = m.model;
        for (int trial = 0; trial < 3; ++trial) {
            const Eigen::VectorXd q = generateRandomCoordinates(model, rng);
            Data data(model);
            calcLengths(model, data, q);
            Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
            calcWireJacobian(model, data, J);
            const Eigen::MatrixXd reference = calcJacobianByFiniteDifferences(model, q, 1e-6);
            // On one link every wire keeps its length: J is exactly zero (the free root moves all points alike).
            if (model.getNumLinks() > 1) {
                ASSERT_GT(J.norm(), 0) << m.name;
            }
            for (int w = 0; w < model.getNumWires(); ++w) {
                const double scale = std::max(reference.row(w).norm(), 1e-3);
                EXPECT_LE((J.row(w) - reference.row(w)).norm() / scale, 1e-6)
                    << m.name << " wire " << model.getWire(w).name << " trial " << trial;
            }
        }
    }
}

// The sparse J^T against the finite differences on every entry, those outside its pattern (the joints at and
// above a wire's anchors' lowest common link, the ones reaching none of its links) included; and the dense J
// read from it entry for entry.
TEST(WireJacobian, SparseTransposeMatchesFiniteDifferencesEverywhere) {
    std::mt19937 rng(17);
    for (const test::NamedModel& m : test::makeRandomModels(30, true)) {
        const Model& model = m.model;
        const Eigen::VectorXd q = generateRandomCoordinates(model, rng);
        Data data(model);
        calcLengths(model, data, q);
        Eigen::SparseMatrix<double> Jt = makeWireJacobianTransposePattern(model);
        ASSERT_LT(Jt.nonZeros(), model.getNumWires() * model.getNumU()) << m.name;
        calcWireJacobianTranspose(model, data, Jt);
        const Eigen::MatrixXd sparse = Eigen::MatrixXd(Jt).transpose();
        const Eigen::MatrixXd reference = calcJacobianByFiniteDifferences(model, q, 1e-6);
        Eigen::MatrixXd dense(model.getNumWires(), model.getNumU());
        calcWireJacobian(model, data, dense);
        EXPECT_EQ((sparse - dense).cwiseAbs().maxCoeff(), 0.0) << m.name;
        for (int w = 0; w < model.getNumWires(); ++w) {
            const double scale = std::max(reference.row(w).norm(), 1e-3);
            EXPECT_LE((sparse.row(w) - reference.row(w)).norm() / scale, 1e-6) << m.name << " wire " << model.getWire(w).name;
        }
    }
}

TEST(WireJacobian, SparseTransposeRejectsAnotherPattern) {
    const std::vector<test::NamedModel> models = test::makeRandomModels(10, true);
    const Model& model = models.back().model;
    Data data(model);
    calcLengths(model, data, model.getDefaultQ());
    Eigen::SparseMatrix<double> wrongShape(model.getNumU() + 1, model.getNumWires());
    wrongShape.makeCompressed();
    EXPECT_THROW(calcWireJacobianTranspose(model, data, wrongShape), Error);
    Eigen::SparseMatrix<double> empty(model.getNumU(), model.getNumWires());
    empty.makeCompressed();
    try {
        calcWireJacobianTranspose(model, data, empty);
        FAIL() << "an empty pattern was filled";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("outside the sparse J^T's pattern"), std::string::npos) << e.what();
    }
}

TEST(WireJacobian, PredictsWireSpeeds) {
    std::mt19937 rng(11);
    for (const test::NamedModel& m : test::makeRandomModels(15, true)) {
        const Model& model = m.model;
        const Eigen::VectorXd q = generateRandomCoordinates(model, rng);
        const Eigen::VectorXd u = generateRandomSpeeds(model, rng);
        Data data(model);
        calcPositionKinematics(model, data, q);
        calcVelocityKinematics(model, data, u);
        calcWirePaths(model, data);
        calcWireSpeeds(model, data);
        Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
        calcWireJacobian(model, data, J);
        const Eigen::VectorXd predicted = J * u;
        EXPECT_LE((predicted - data.wireSpeed).lpNorm<Eigen::Infinity>(),
                  1e-12 * std::max(1.0, data.wireSpeed.lpNorm<Eigen::Infinity>()))
            << m.name;
    }
}

TEST(WireJacobian, GeneralizedForcesAreMinusJacobianTransposeTimesTensions) {
    std::mt19937 rng(13);
    for (const test::NamedModel& m : test::makeRandomModels(15, true)) {
        const Model& model = m.model;
        Data data(model);
        calcLengths(model, data, generateRandomCoordinates(model, rng));
        Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
        calcWireJacobian(model, data, J);
        std::uniform_real_distribution<double> tension(0, 100);
        Eigen::VectorXd f(model.getNumWires());
        for (Eigen::Index w = 0; w < f.size(); ++w) f[w] = tension(rng);
        Eigen::VectorXd tau(model.getNumU());
        calcWireGeneralizedForces(model, data, f, tau);
        const Eigen::VectorXd expected = -J.transpose() * f;
        EXPECT_LE((tau - expected).lpNorm<Eigen::Infinity>(), 1e-12 * std::max(1.0, expected.lpNorm<Eigen::Infinity>()))
            << m.name;
    }
}

// A hand-worked case: a point mass pendulum-like chain of two pins about z, one wire from a fixed point on
// the root link to the tip. l = |p_tip - p_origin| with the tip at distance r from the second pin, so
// dl/dtheta2 = (1/l) (p_tip - p_origin) . (z x (p_tip - p_pin2)).
TEST(WireJacobian, TwoPinHandWorkedCase) {
    const Model model = readModelText(R"(
sinew_model: 1
links:
  - {name: upper, mass: 1, com: [0, -0.5, 0], inertia: [0.1, 0.1, 0.1, 0, 0, 0]}
  - {name: lower, mass: 1, com: [0, -0.5, 0], inertia: [0.1, 0.1, 0.1, 0, 0, 0]}
joints:
  - {name: hip, type: pin, parent: ground, child: upper, axis: [0, 0, 1]}
  - {name: knee, type: pin, parent: upper, child: lower, parent_point: [0, -1, 0], axis: [0, 0, 1]}
wires:
  - name: w
    kind: muscle
    points: [{link: upper, at: [0.2, 0, 0]}, {link: lower, at: [0, -0.5, 0]}]
    force_law: {type: prescribed_tension, tension: 1}
)", "two_pin.yaml");
    Eigen::VectorXd q(2);
    q << 0.3, 0.9;
    Data data(model);
    calcLengths(model, data, q);
    Eigen::MatrixXd J(1, 2);
    calcWireJacobian(model, data, J);
    // By hand: rotations about z in the plane.
    auto rot = [](double a, const Eigen::Vector2d& v) {
        return Eigen::Vector2d(std::cos(a) * v.x() - std::sin(a) * v.y(), std::sin(a) * v.x() + std::cos(a) * v.y());
    };
    const Eigen::Vector2d origin = rot(q[0], {0.2, 0});
    const Eigen::Vector2d knee = rot(q[0], {0, -1});
    const Eigen::Vector2d tip = knee + rot(q[0] + q[1], {0, -0.5});
    const Eigen::Vector2d d = tip - origin;
    const double l = d.norm();
    auto perp = [](const Eigen::Vector2d& r) { return Eigen::Vector2d(-r.y(), r.x()); };  // z x r
    const double dl_dknee = d.dot(perp(tip - knee)) / l;
    const double dl_dhip = (d.dot(perp(tip)) - d.dot(perp(origin))) / l;
    EXPECT_NEAR(data.wireLength[0], l, 1e-14);
    EXPECT_NEAR(J(0, 0), dl_dhip, 1e-14);
    EXPECT_NEAR(J(0, 1), dl_dknee, 1e-14);
}

}  // namespace
}  // namespace sinew
