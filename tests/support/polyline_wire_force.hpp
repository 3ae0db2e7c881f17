#pragma once
// An independent reference for the Simbody plugin's wires: a straight via-point polyline through stations
// fixed on mobilized bodies, length, speed and forces computed from Simbody's own kinematics alone (no
// sinew core), as the plugin's WireForce computed them before it ran core's path code. Plain polyline wires
// only: their length, speed and forces must agree with the plugin's to roundoff.
#include "sinew/plugin/ndebug_guard.hpp"

#include <Simbody.h>
#include <memory>
#include <string>
#include <vector>

#include "sinew/core/error.hpp"
#include "sinew/core/force_law.hpp"
#include "sinew/core/model.hpp"
#include "sinew/plugin/simbody_model.hpp"

namespace sinew::test {

class PolylineWireForce : public SimTK::Force::Custom::Implementation {
public:
    struct Station {
        SimTK::MobilizedBodyIndex body;
        SimTK::Vec3 p_B;  // m, in the body frame
    };

    PolylineWireForce(const SimTK::SimbodyMatterSubsystem& matter, std::vector<Station> path,
                      std::shared_ptr<const ForceLaw> law)
        : matter_(matter), path_(std::move(path)), law_(std::move(law)) {}

    // Need the state realized to Position (length) or Velocity (speed, tension).
    double calcLength(const SimTK::State& state) const {
        double length = 0;
        for (std::size_t k = 1; k < path_.size(); ++k)
            length += (findStationInGround(state, k) - findStationInGround(state, k - 1)).norm();
        return length;
    }
    double calcLengtheningSpeed(const SimTK::State& state) const {
        double length = 0, speed = 0;
        measure(state, length, speed);
        return speed;
    }
    double calcTension(const SimTK::State& state) const {
        double length = 0, speed = 0;
        measure(state, length, speed);
        return law_->calcTension(WireState{length, speed, state.getTime()});
    }

    // Equal and opposite forces along each segment; a segment with both ends on one body adds nothing.
    void calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& bodyForces,
                   SimTK::Vector_<SimTK::Vec3>&, SimTK::Vector&) const override {
        const double tension = calcTension(state);
        if (tension == 0) return;
        for (std::size_t k = 0; k + 1 < path_.size(); ++k) {
            const SimTK::Vec3 segment = findStationInGround(state, k + 1) - findStationInGround(state, k);
            const double l = segment.norm();
            if (path_[k].body == path_[k + 1].body || l <= 1e-12) continue;
            const SimTK::Vec3 f_G = tension * segment / l;
            matter_.getMobilizedBody(path_[k].body).applyForceToBodyPoint(state, path_[k].p_B, f_G, bodyForces);
            matter_.getMobilizedBody(path_[k + 1].body).applyForceToBodyPoint(state, path_[k + 1].p_B, -f_G, bodyForces);
        }
    }
    SimTK::Real calcPotentialEnergy(const SimTK::State& state) const override {
        return law_->calcPotentialEnergy(calcLength(state));
    }

private:
    SimTK::Vec3 findStationInGround(const SimTK::State& state, std::size_t k) const {
        return matter_.getMobilizedBody(path_[k].body).findStationLocationInGround(state, path_[k].p_B);
    }
    void measure(const SimTK::State& state, double& length, double& speed) const {
        length = speed = 0;
        SimTK::Vec3 p0, v0;
        matter_.getMobilizedBody(path_[0].body).findStationLocationAndVelocityInGround(state, path_[0].p_B, p0, v0);
        for (std::size_t k = 1; k < path_.size(); ++k) {
            SimTK::Vec3 p1, v1;
            matter_.getMobilizedBody(path_[k].body).findStationLocationAndVelocityInGround(state, path_[k].p_B, p1, v1);
            const SimTK::Vec3 segment = p1 - p0;
            const double l = segment.norm();
            length += l;
            if (l > 1e-12) speed += SimTK::dot(segment / l, v1 - v0);
            p0 = p1;
            v0 = v1;
        }
    }

    const SimTK::SimbodyMatterSubsystem& matter_;
    std::vector<Station> path_;
    std::shared_ptr<const ForceLaw> law_;
};

// A model's wires (plain polylines, no virtual links) as PolylineWireForce elements in a system built
// without the plugin's wires: the reference system of a comparison.
class PolylineReferenceSystem {
public:
    explicit PolylineReferenceSystem(const Model& model, SimbodyModelOptions options = {}) {
        options.wires = false;
        simbody_ = std::make_unique<SimbodyModel>(model, options);
        for (const Wire& wire : model.getWires()) {
            if (!wire.isPolyline()) throw Error("wire '" + wire.name + "' is not a plain polyline");
            std::vector<PolylineWireForce::Station> path;
            for (int k = wire.firstPoint; k < wire.firstPoint + wire.numPoints; ++k) {
                const WirePoint& point = model.getWirePoints()[static_cast<std::size_t>(k)];
                path.push_back({simbody_->getMobilizedBody(point.link).getMobilizedBodyIndex(),
                                SimTK::Vec3(point.p_B[0], point.p_B[1], point.p_B[2])});
            }
            auto* element = new PolylineWireForce(simbody_->getMatter(), std::move(path), wire.law);
            elements_.push_back(element);
            forces_.push_back(SimTK::Force::Custom(simbody_->updForces(), element).getForceIndex());  // owns it
        }
        simbody_->updSystem().realizeTopology();
    }

    SimbodyModel& updSimbodyModel() { return *simbody_; }
    const SimbodyModel& getSimbodyModel() const { return *simbody_; }
    const PolylineWireForce& getWire(int w) const { return *elements_.at(static_cast<std::size_t>(w)); }
    const SimTK::Force& getWireForceElement(int w) const {
        return simbody_->updForces().getForce(forces_.at(static_cast<std::size_t>(w)));
    }

private:
    std::unique_ptr<SimbodyModel> simbody_;
    std::vector<const PolylineWireForce*> elements_;  // owned by the system
    std::vector<SimTK::ForceIndex> forces_;
};

}  // namespace sinew::test
