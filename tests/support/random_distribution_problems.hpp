#pragma once
// Random tension-distribution problems for the solver tests, with the degeneracies real models have:
// duplicate wires, wires with zero moment arms, DOFs no wire reaches, free (loop-force) columns and equality
// rows. Reproducible from a seed.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <random>
#include <string>
#include <vector>

#include "sinew/tensions/distribution_problem.hpp"

namespace sinew::test {

struct RandomProblemOptions {
    int rows = 12;
    int wires = 40;
    int maxRowsPerWire = 4;      // each wire reaches 1 to this many DOFs (moment arms in [-0.05, 0.05] m)
    int numFree = 0;             // dense free columns (loop forces)
    int numEquality = 0;         // the last rows are equalities
    int duplicateWires = 0;      // the last wires copy earlier ones
    int zeroWires = 0;           // wires whose moment arms are all (explicit) zeros
    int unreachableRows = 0;     // the first rows no wire reaches (target 0 there)
    // Target = A f + G lambda with f uniform in [low, high] x maxTension (outside [0, 1]: bounds become
    // active in the QP); the tolerance rows then get noise of this relative size.
    double tensionLow = 0.1, tensionHigh = 0.9, noise = 0;
    double tolerance = 1e-3;
    unsigned seed = 1;
};

inline std::string describe(const RandomProblemOptions& o) {
    return "problem(rows=" + std::to_string(o.rows) + ", wires=" + std::to_string(o.wires) + ", free=" +
           std::to_string(o.numFree) + ", equality=" + std::to_string(o.numEquality) + ", duplicate=" +
           std::to_string(o.duplicateWires) + ", zero=" + std::to_string(o.zeroWires) + ", unreachable=" +
           std::to_string(o.unreachableRows) + ", seed=" + std::to_string(o.seed) + ")";
}

inline DistributionProblem makeRandomProblem(const RandomProblemOptions& o) {
    std::mt19937 rng(o.seed);
    std::uniform_real_distribution<double> unit(0, 1), arm(-0.05, 0.05);
    std::uniform_int_distribution<int> reachable(o.unreachableRows, o.rows - 1), count(1, o.maxRowsPerWire);
    Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(o.rows, o.wires + o.numFree);
    std::vector<Eigen::Triplet<double>> entries;
    for (int w = 0; w < o.wires; ++w) {
        const int source = w - (o.wires - o.duplicateWires);
        if (source >= 0) {
            dense.col(w) = dense.col(source);
        } else {
            for (int k = count(rng); k > 0; --k) dense(reachable(rng), w) = arm(rng);
        }
    }
    for (int k = 0; k < o.numFree; ++k)
        for (int i = o.unreachableRows; i < o.rows; ++i) dense(i, o.wires + k) = arm(rng);
    for (int j = 0; j < dense.cols(); ++j)
        for (int i = 0; i < o.rows; ++i) {
            const bool zeroWire = j >= o.wires - o.zeroWires - o.duplicateWires && j < o.wires - o.duplicateWires;
            if (zeroWire && i == reachable(rng)) entries.emplace_back(i, j, 0.0);  // explicit zero, in the pattern
            else if (dense(i, j) != 0 && !zeroWire) entries.emplace_back(i, j, dense(i, j));
        }
    DistributionProblem p;
    p.A.resize(o.rows, o.wires + o.numFree);
    p.A.setFromTriplets(entries.begin(), entries.end());
    p.A.makeCompressed();
    p.numFree = o.numFree;
    p.lower.setZero(o.wires);
    p.upper.resize(o.wires);
    p.cost.resize(o.wires);
    for (int w = 0; w < o.wires; ++w) p.upper[w] = 100 + 900 * unit(rng), p.cost[w] = 0.5 + unit(rng);
    double meanSquaredArm = 0;
    for (int w = 0; w < o.wires; ++w) meanSquaredArm += p.A.col(w).squaredNorm() / o.wires;
    p.weight.setConstant(o.wires, 1e-6 * meanSquaredArm);
    Eigen::VectorXd x(o.wires + o.numFree);
    for (int w = 0; w < o.wires; ++w) x[w] = (o.tensionLow + (o.tensionHigh - o.tensionLow) * unit(rng)) * p.upper[w];
    for (int k = 0; k < o.numFree; ++k) x[o.wires + k] = 200 * (unit(rng) - 0.5);
    p.target = p.A * x;
    p.isEquality.assign(static_cast<std::size_t>(o.rows), false);
    for (int i = o.rows - o.numEquality; i < o.rows; ++i) p.isEquality[static_cast<std::size_t>(i)] = true;
    const double scale = p.target.cwiseAbs().maxCoeff();
    std::normal_distribution<double> gauss(0, o.noise * scale);
    for (int i = 0; i < o.rows - o.numEquality; ++i)
        if (i >= o.unreachableRows && o.noise > 0) p.target[i] += gauss(rng);
    p.tolerance.setConstant(o.rows, o.tolerance);
    return p;
}

// The degenerate family the solver tests sweep: plain, duplicates + zero wires + unreachable DOFs, free
// columns + equality rows, and all of them together, at a few sizes.
inline std::vector<RandomProblemOptions> makeProblemSweep(double tensionLow, double tensionHigh, double noise) {
    std::vector<RandomProblemOptions> sweep;
    unsigned seed = 1;
    for (const int rows : {6, 12, 20}) {
        for (int variant = 0; variant < 4; ++variant) {
            RandomProblemOptions o;
            o.rows = rows;
            o.wires = 3 * rows + 4;
            o.seed = seed++;
            o.tensionLow = tensionLow, o.tensionHigh = tensionHigh, o.noise = noise;
            if (variant == 1 || variant == 3) o.duplicateWires = 3, o.zeroWires = 2, o.unreachableRows = 2;
            if (variant == 2 || variant == 3) o.numFree = 3, o.numEquality = 2;
            sweep.push_back(o);
        }
    }
    return sweep;
}

}  // namespace sinew::test
