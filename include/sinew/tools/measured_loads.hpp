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

// The data columns that an ExternalLoads file's forces read, as functions of time: each interpolated as
// OpenSim's ExternalForce interpolates it. They need no model, so a tool fits them while it reads the model:
// on a long force-plate record they are most of what MeasuredLoads costs.
class ExternalLoadCurves {
public:
    explicit ExternalLoadCurves(const ExternalLoads& loads);

private:
    friend class MeasuredLoads;
    // A force's columns among splines_: `count` from `first`, its force, point and torque x, y, z triples
    // at these offsets from `first` (-1 when absent).
    struct ForceColumns {
        std::size_t first = 0;
        int count = 0, force = -1, point = -1, torque = -1;
    };
    std::vector<ForceColumns> forces_;      // one per ExternalForce that applies a force, in file order
    std::vector<SmoothingSpline> splines_;  // one per column read, all on the data file's times
};

class MeasuredLoads {
public:
    // Resolves every applied force's bodies to links of `model` (ground included); throws ModelError at the
    // ExternalForce's line for a body the model lacks.
    MeasuredLoads(const Model& model, const ExternalLoads& loads);
    // The same with the curves fitted beforehand from the same `loads`; its errors come in the same order.
    MeasuredLoads(const Model& model, const ExternalLoads& loads, ExternalLoadCurves curves);

    // Adds each applied force, torque and its moment to linkForces (one per link, Data::F_G convention: moment
    // about the link origin, force; ground axes) at time t, with the pose in `data` (position kinematics
    // done). Loads applied to ground are ignored, as they move nothing.
    void addLinkForces(const Data& data, double t, std::vector<SpatialVector>& linkForces) const;

private:
    struct Load {
        int appliedTo = kGround, forceFrame = kGround, pointFrame = kGround;  // link indices
        ExternalLoadCurves::ForceColumns columns;  // N, m, N m
    };
    std::vector<Load> loads_;
    ExternalLoadCurves curves_;
};

// The applied link forces of a frame at time t and coordinates q: none, or `loads`' when given (then with
// position kinematics at q done into `data`, for the loads' frames). linkForces has one entry per link.
void calcAppliedLinkForces(const Model& model, const MeasuredLoads* loads, Data& data, double t, const Eigen::VectorXd& q,
                           std::vector<SpatialVector>& linkForces);

}  // namespace sinew
