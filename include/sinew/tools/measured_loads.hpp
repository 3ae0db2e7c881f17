#pragma once
// Measured external loads (an OpenSim ExternalLoads file: ground reactions and the like) as functions of
// time, turned into spatial forces on sinew's links at a pose. Each data column is interpolated as OpenSim's
// ExternalForce interpolates it: a cubic GCVSPL spline through the samples (piecewise linear below four
// samples; at least two are needed), so the loads can be evaluated between the data file's rows.
#include <vector>

#include "sinew/core/data.hpp"
#include "sinew/core/model.hpp"
#include "sinew/signal/smoothing_spline.hpp"
#include "sinew/io/external_loads.hpp"

namespace sinew {

class MeasuredLoads {
public:
    // Resolves every applied force's bodies to links of `model` (ground included); throws ModelError at the
    // ExternalForce's line for a body the model lacks.
    MeasuredLoads(const Model& model, const ExternalLoads& loads);

    // Adds each applied force, torque and its moment to linkForces (one per link, Data::F_G convention: moment
    // about the link origin, force; ground axes) at time t, with the pose in `data` (position kinematics
    // done). Loads applied to ground are ignored, as they move nothing.
    void addLinkForces(const Data& data, double t, std::vector<SpatialVector>& linkForces) const;

private:
    struct Channel {  // one x, y, z triple of data columns, or absent
        std::vector<SmoothingSpline> splines;  // x, y, z; empty when absent
        Eigen::Vector3d calcValue(double t) const;
    };
    struct Load {
        int appliedTo = kGround, forceFrame = kGround, pointFrame = kGround;  // link indices
        Channel force, point, torque;  // N, m, N m
    };
    std::vector<Load> loads_;
};

// The applied link forces of a frame at time t and coordinates q: none, or `loads`' when given (then with
// position kinematics at q done into `data`, for the loads' frames). linkForces has one entry per link.
void calcAppliedLinkForces(const Model& model, const MeasuredLoads* loads, Data& data, double t, const Eigen::VectorXd& q,
                           std::vector<SpatialVector>& linkForces);

}  // namespace sinew
