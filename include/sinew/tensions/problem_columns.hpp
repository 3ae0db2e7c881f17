#pragma once
// A block of extra bounded unknowns of the tension problem (docs/tensions.md, "Extra column blocks"):
// variables besides the wires' tensions that help produce the generalized forces tau, such as reserve
// actuators (reserve_columns.hpp) or contact forces at the soles. WireProblemBuilder (wire_problem.hpp)
// places the blocks it is given after the wires' columns and before the loops' free ones, in their order:
//
//     A = [ -J^T (wires) | block 0 | block 1 | ... | loop columns ],   x = [f; x_0; x_1; ...; λ].
//
// Column j of a block is the generalized force (nu) per unit of its variable j, the wires' sign (A x is
// what the variables produce). The builder asks a block for its sparsity pattern once and for its values,
// bounds, LP cost, QP weight and equality rows every frame; it never drops a block's small entries as roundoff.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "sinew/core/data.hpp"

namespace sinew {

class ProblemColumns {
public:
    virtual ~ProblemColumns() = default;

    // Number of variables (columns), fixed.
    virtual int count() const = 0;
    // Appends (row, columnOffset + j, 1) for every row column j may reach at any frame: the pattern is
    // fixed for the analysis (a solver keeps its warm start while it stays), so a column that sometimes
    // vanishes keeps its entries and gets explicit zeros.
    virtual void addPattern(int columnOffset, std::vector<Eigen::Triplet<double>>& entries) const = 0;
    // Writes the frame's values into A's columns columnOffset ... columnOffset + count() - 1, which hold
    // addPattern's entries (rows sorted within each column). `data` holds the frame's position and
    // velocity kinematics (calcInverseDynamics leaves them) and the wire paths.
    virtual void update(const Data& data, int columnOffset, Eigen::SparseMatrix<double>& A) = 0;
    // The frame's bounds (may be infinite), LP cost per unit (>= 0 for a bounded LP) and QP weight (> 0,
    // the objective's ½ weight x²), each count() long. wireWeight is the frame's QP weight of every wire
    // (WireProblemOptions::regularization times the mean squared wire column), for weights relative to it.
    // Methods in activations (WireVariables::Activation) use the bounds only: their cost is Σ |x|^p.
    virtual void setVariables(double wireWeight, Eigen::Ref<Eigen::VectorXd> lower, Eigen::Ref<Eigen::VectorXd> upper,
                              Eigen::Ref<Eigen::VectorXd> cost, Eigen::Ref<Eigen::VectorXd> weight) const = 0;
    // Sets isEquality (nu) on the rows the frame's variables must meet exactly rather than in the least-squares
    // or band sense (after update, each frame; the virtual links' rows are set already). None by default.
    virtual void markEqualityRows(std::vector<bool>& isEquality) const { (void)isEquality; }
};

}  // namespace sinew
