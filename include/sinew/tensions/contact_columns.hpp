#pragma once
// The ground's push on the feet a model names (Model::getContacts) as bounded variables of the tension problem
// (docs/tensions-from-motion.md, "Contact"). At sole vertex v of a contact the force is
//
//     f_v = Σ_k β_vk d_k,   d_k = n + μ (cos θ_k t1 + sin θ_k t2),   θ_k = 2π k / K,   β_vk >= 0,
//
// n the ground normal (against gravity), t1, t2 the ground plane's axes, K the friction pyramid's edges. Every
// such force pushes (n . f_v >= 0), stays inside the pyramid inscribed in the Coulomb cone, and the centre of
// pressure of the contact's forces is a convex combination of its vertices: inside the sole polygon's hull.
// Column (v, k) of A is J_v^T d_k, the generalized force of a unit force d_k at the vertex: the sign of the
// wire columns (A x is what the variables produce), so no new kind of row or bound is needed.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"
#include "sinew/tensions/problem_columns.hpp"

namespace sinew {

// What one contact's variables add up to at a frame.
struct ContactWrench {
    Eigen::Vector3d force = Eigen::Vector3d::Zero();   // N, ground axes: the sum of the vertex forces
    // m, ground: the vertices' mean weighted by their normal forces (the centre of pressure); the link's first
    // vertex when the normal force is zero.
    Eigen::Vector3d centreOfPressure = Eigen::Vector3d::Zero();
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();  // N m, ground axes: the forces' moment about that point
};

// As a block of the tension problem (problem_columns.hpp): the variables are the β's, bounded [0, ∞) on the
// contacts setInContact marks and [0, 0] (with zero columns) on the others, at LP cost `cost` per unit (a
// newton of normal force) and the wires' QP weight.
class ContactColumns : public ProblemColumns {
public:
    // Throws sinew::Error when the model's gravity is zero (no "up" for the ground) or pyramidEdges < 3.
    explicit ContactColumns(const Model& model, int pyramidEdges = 8, double cost = 1e-3);

    // Which contacts touch the ground at the next frame (contacts; e.g. from detectContacts). None at first.
    // Throws sinew::Error when the size is not the model's number of contacts.
    void setInContact(const std::vector<char>& inContact);
    const std::vector<char>& getInContact() const { return inContact_; }

    int count() const override { return numColumns_; }
    void addPattern(int columnOffset, std::vector<Eigen::Triplet<double>>& entries) const override;
    void update(const Data& data, int columnOffset, Eigen::SparseMatrix<double>& A) override {
        update(data, inContact_, columnOffset, A);
    }
    void setVariables(double wireWeight, Eigen::Ref<Eigen::VectorXd> lower, Eigen::Ref<Eigen::VectorXd> upper,
                      Eigen::Ref<Eigen::VectorXd> cost, Eigen::Ref<Eigen::VectorXd> weight) const override;
    // On a frame with a contact down, the force rows (the linear half of u) of the free root joints the
    // touching contacts hang from: the ground is all that pushes the body as a whole, so the body's linear
    // momentum is balanced by the contact forces exactly, never by a residual force on the root. Its moment
    // rows stay least-squares rows: a captured motion's moment about the centre of pressure is what a sole
    // polygon cannot always hold. Without a contact down, nothing (the root's rows are then unactuated).
    void markEqualityRows(std::vector<bool>& isEquality) const override;

    int getNumColumns() const { return numColumns_; }  // Σ over contacts of (sole vertices x K)
    int getNumEdges() const { return numEdges_; }
    int getFirstColumn(int contact) const { return firstColumn_[static_cast<std::size_t>(contact)]; }  // from 0
    const Eigen::Vector3d& getNormal() const { return normal_; }  // n, unit, ground axes
    const Eigen::Vector3d& getEdge(int contact, int k) const;     // d_k of that contact's pyramid, ground axes

    // addPattern: the rows column j can reach are the DOFs of the joints from the contact's link to the root,
    // whether or not it touches the ground.

    // Writes the columns' values into A (whose columns columnOffset... hold addPattern's entries): contact c's
    // are J_v^T d_k when inContact[c] (contacts), explicit zeros otherwise. Needs calcPositionKinematics at
    // the frame's q; allocates nothing.
    void update(const Data& data, const std::vector<char>& inContact, int columnOffset, Eigen::SparseMatrix<double>& A);

    // Contact c's force, centre of pressure and moment from its variables (beta: all getNumColumns()).
    ContactWrench calcWrench(const Data& data, int contact, const Eigen::Ref<const Eigen::VectorXd>& beta) const;

private:
    const Model& model_;
    int numEdges_ = 4;
    double cost_ = 1e-3;
    std::vector<char> inContact_;         // (contacts)
    int numColumns_ = 0;
    Eigen::Vector3d normal_;
    std::vector<int> firstColumn_;        // (contacts)
    std::vector<Eigen::Vector3d> edges_;  // (contacts x K) d_k, contact-major
    Eigen::MatrixXd unitForces_;          // (nu x 3) workspace: J_v^T e_x, e_y, e_z of one vertex
};

// The generalized force (nu) of the force F_G (N, ground axes) at point p_B of `link`: J_p^T F_G, with zeros
// on the rows it cannot reach. Needs calcPositionKinematics.
void calcPointForceGeneralizedForce(const Model& model, const Data& data, int link, const Eigen::Vector3d& p_B,
                                    const Eigen::Vector3d& F_G, Eigen::Ref<Eigen::VectorXd> tau);

}  // namespace sinew
