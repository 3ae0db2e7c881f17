#pragma once
// The model's force elements (limits, springs, bushings, contact: core/force_elements.hpp) acting on a
// motion: inverse dynamics gives what the motion needs; the elements give part of it, as OpenSim applies
// every force a tool does not exclude, and the rest is what the joints or the wires must give.
#include <Eigen/Core>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"

namespace sinew {

class ForceElementLoads {
public:
    explicit ForceElementLoads(const Model& model);
    // tau (nu) -= the elements' generalized forces at the state in `data` (position and velocity kinematics
    // at (q, u) done, as calcInverseDynamics leaves them); nothing when the model has no force elements.
    // Overwrites data.scratchF_G; allocates nothing.
    void subtractFrom(Data& data, Eigen::Ref<Eigen::VectorXd> tau);

private:
    const Model& model_;
    Eigen::VectorXd direct_, fromLinks_;
};

}  // namespace sinew
