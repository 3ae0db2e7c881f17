// The contact columns (tensions/contact_columns.hpp) against finite differences: by virtual power, column
// (v, k) dotted with any u is d_k . (the sole vertex's velocity), the velocity taken from positions at
// q -/+ u h. Also the pyramid's edges and the centre of pressure's place inside the sole.
#include <gtest/gtest.h>

#include <random>

#include "sinew/core/data.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/tensions/contact_columns.hpp"
#include "support/random_model.hpp"
#include "support/standing_model.hpp"

namespace sinew {
namespace {

// A random tree with custom and pin joints, a foot with a triangular sole on its last link, y up.
Model makeRandomModelWithFoot() {
    RandomModelOptions options;
    options.numLinks = 12;
    options.customJointFraction = 0.3;
    options.seed = 41;
    const Model model = generateRandomModel(options);
    const std::string foot = model.getLink(model.getNumLinks() - 1).name;
    return readModelText(writeModelText(model) + "contacts:\n  - {name: foot, link: " + foot +
                             ", friction: 0.6, sole: [[0.1, -0.2, 0], [0, -0.2, 0.1], [-0.1, -0.25, -0.05]]}\n",
                         "random_with_foot.yaml");
}

Eigen::SparseMatrix<double> makeColumns(const Model& model, const ContactColumns& columns) {
    std::vector<Eigen::Triplet<double>> entries;
    columns.addPattern(0, entries);
    Eigen::SparseMatrix<double> A(model.getNumU(), columns.getNumColumns());
    A.setFromTriplets(entries.begin(), entries.end());
    A.makeCompressed();
    return A;
}

void expectColumnsAreVirtualPower(const Model& model, unsigned seed) {
    ContactColumns columns(model, 5);
    Eigen::SparseMatrix<double> A = makeColumns(model, columns);
    std::mt19937 rng(seed);
    Data data(model), displaced(model);
    const double h = 1e-6;
    for (int trial = 0; trial < 4; ++trial) {
        const Eigen::VectorXd q = generateRandomCoordinates(model, rng);
        const Eigen::VectorXd u = generateRandomSpeeds(model, rng);
        calcPositionKinematics(model, data, q);
        columns.update(data, std::vector<char>(model.getContacts().size(), 1), 0, A);
        const Eigen::VectorXd power = A.transpose() * u;
        std::vector<std::vector<Eigen::Vector3d>> p[2];
        for (int side = 0; side < 2; ++side) {
            calcPositionKinematics(model, displaced, integrateCoordinates(model, q, u, side == 0 ? -h : h));
            for (const Contact& contact : model.getContacts()) {
                p[side].emplace_back();
                for (const Eigen::Vector3d& p_B : contact.sole_B)
                    p[side].back().push_back(displaced.p_GB[contact.link] + displaced.R_GB[contact.link] * p_B);
            }
        }
        for (std::size_t c = 0; c < model.getContacts().size(); ++c)
            for (std::size_t v = 0; v < model.getContacts()[c].sole_B.size(); ++v) {
                const Eigen::Vector3d velocity = (p[1][c][v] - p[0][c][v]) / (2 * h);
                for (int k = 0; k < columns.getNumEdges(); ++k) {
                    const int j = columns.getFirstColumn(static_cast<int>(c)) + static_cast<int>(v) * columns.getNumEdges() + k;
                    const double expected = columns.getEdge(static_cast<int>(c), k).dot(velocity);
                    EXPECT_NEAR(power[j], expected, 1e-7 * (1 + velocity.norm())) << "contact " << c << " vertex " << v;
                }
            }
        // Out of contact the same pattern holds zeros.
        columns.update(data, std::vector<char>(model.getContacts().size(), 0), 0, A);
        EXPECT_EQ(A.norm(), 0);
    }
}

TEST(ContactColumns, ColumnsAreTheVirtualPowerOfTheEdgeForcesOnTheStandingModel) {
    expectColumnsAreVirtualPower(test::makeStandingModel(), 3);
}

TEST(ContactColumns, ColumnsAreTheVirtualPowerOfTheEdgeForcesOnARandomTree) {
    expectColumnsAreVirtualPower(makeRandomModelWithFoot(), 5);
}

TEST(ContactColumns, EdgesLieOnTheFrictionCone) {
    const Model model = makeRandomModelWithFoot();
    const ContactColumns columns(model, 6);
    EXPECT_NEAR((columns.getNormal() - Eigen::Vector3d(0, 1, 0)).norm(), 0, 1e-15);  // the random model's gravity is -y
    for (int k = 0; k < 6; ++k) {
        const Eigen::Vector3d d = columns.getEdge(0, k);
        EXPECT_NEAR(d.dot(columns.getNormal()), 1, 1e-15);
        EXPECT_NEAR((d - columns.getNormal()).norm(), 0.6, 1e-15);
    }
}

TEST(ContactColumns, CentreOfPressureIsInsideTheSole) {
    const Model model = test::makeStandingModel();
    const ContactColumns columns(model);
    Data data(model);
    std::mt19937 rng(9);
    calcPositionKinematics(model, data, generateRandomCoordinates(model, rng));
    std::uniform_real_distribution<double> unit(0, 1);
    for (int trial = 0; trial < 20; ++trial) {
        Eigen::VectorXd beta(columns.getNumColumns());
        for (Eigen::Index j = 0; j < beta.size(); ++j) beta[j] = unit(rng) < 0.5 ? 0.0 : 100 * unit(rng);
        const ContactWrench wrench = columns.calcWrench(data, 0, beta);
        const Contact& foot = model.getContacts()[0];
        // In the link frame the sole is the rectangle x in [-0.05, 0.15], y in [-0.04, 0.04] at z = -0.9.
        const Eigen::Vector3d cop_B = data.R_GB[foot.link].transpose() * (wrench.centreOfPressure - data.p_GB[foot.link]);
        EXPECT_GE(cop_B.x(), -0.05 - 1e-12);
        EXPECT_LE(cop_B.x(), 0.15 + 1e-12);
        EXPECT_LE(std::abs(cop_B.y()), 0.04 + 1e-12);
        EXPECT_NEAR(cop_B.z(), -0.9, 1e-12);
        EXPECT_GE(wrench.force.dot(columns.getNormal()), 0);
    }
}

}  // namespace
}  // namespace sinew
