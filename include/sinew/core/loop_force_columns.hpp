#pragma once
// A ball loop's constraint force (docs/joint-loads.md, eq. 2): a force f (ground axes) on link B at its loop
// point p_B and -f on link A at p_A. Its generalized forces are G^T f, G = d(p_B - p_A)/du the loop's
// constraint Jacobian, so the three columns of G^T are what joint reactions solve for the loop forces with
// and what the tension problem's free variables multiply (the paper's Eq. 8).
#include <Eigen/Core>
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"
#include "sinew/core/spatial.hpp"

namespace sinew {

// Adds loop `loopIndex`'s force pair, f_G (N, ground axes) on link B at p_B and -f_G on link A at p_A, to F
// (numLinks, the Data::F_G convention: moment about each link's origin, force). Needs calcPositionKinematics.
void addLoopForce(const Model& model, const Data& data, int loopIndex, const Eigen::Vector3d& f_G,
                  std::vector<SpatialVector>& F);

// columns (nu x 3): column c is the generalized force of the unit pair f_G = e_c of loop `loopIndex`, i.e.
// G^T. Needs calcPositionKinematics; uses Data::scratchF_G. Throws sinew::Error on a bad loop index or size.
void calcLoopForceColumns(const Model& model, Data& data, int loopIndex, Eigen::Ref<Eigen::MatrixXd> columns);

}  // namespace sinew
