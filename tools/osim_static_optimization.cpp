#include <algorithm>

#include "sinew/core/error.hpp"
#include "sinew/tools/osim_states.hpp"
#include "sinew/tools/static_optimization_tool.hpp"
#include "sinew/tools/tension_motion.hpp"

namespace sinew {
namespace {

ReserveActuator makeReserve(const std::string& name, const OsimActuatorLimits& limits) {
    ReserveActuator reserve;
    reserve.name = name;
    reserve.optimalForce = limits.optimalForce;
    reserve.minControl = limits.minControl;
    reserve.maxControl = limits.maxControl;
    return reserve;
}

ReserveActuator makeReserve(const Model& model, const OsimCoordinateActuator& actuator) {
    const int dof = model.findCoordinateIndex(actuator.coordinate);  // scalar coordinates: q index = u index
    if (dof == Model::kNotFound)
        throw ModelError(actuator.where, "CoordinateActuator '" + actuator.name + "' acts on coordinate '" +
                                             actuator.coordinate + "', which model '" + model.getName() + "' lacks");
    ReserveActuator reserve = makeReserve(actuator.name, actuator.limits);
    reserve.dof = dof;
    return reserve;
}

// An actuator's body: a body name or an OpenSim 4 component path ("/bodyset/pelvis", "/ground").
int findBody(const Model& model, const std::string& body, const std::string& type, const std::string& name,
             const std::string& where) {
    const int link = model.findLinkIndex(body.substr(body.find_last_of('/') + 1));
    if (link == Model::kNotFound)
        throw ModelError(where, type + " '" + name + "' acts on body '" + body + "', which model '" +
                                    model.getName() + "' lacks");
    return link;
}

ReserveActuator makeReserve(const Model& model, const OsimPointActuator& actuator) {
    BodyActuator body;
    body.kind = BodyActuator::Kind::PointForce;
    body.link = findBody(model, actuator.body, "PointActuator", actuator.name, actuator.where);
    if (body.link == kGround)
        throw ModelError(actuator.where, "PointActuator '" + actuator.name + "' pushes ground, which cannot move");
    if (!(actuator.direction.norm() > 0))
        throw ModelError(actuator.where, "PointActuator '" + actuator.name + "' has a zero <direction>");
    body.point = actuator.point;
    body.pointInGround = actuator.pointIsGlobal;
    body.axis = actuator.direction;
    body.axisInGround = actuator.forceIsGlobal;
    ReserveActuator reserve = makeReserve(actuator.name, actuator.limits);
    reserve.body = body;
    return reserve;
}

ReserveActuator makeReserve(const Model& model, const OsimTorqueActuator& actuator) {
    BodyActuator body;
    body.kind = BodyActuator::Kind::Torque;
    body.link = findBody(model, actuator.bodyA, "TorqueActuator", actuator.name, actuator.where);
    body.reactionLink = findBody(model, actuator.bodyB, "TorqueActuator", actuator.name, actuator.where);
    if (!(actuator.axis.norm() > 0))
        throw ModelError(actuator.where, "TorqueActuator '" + actuator.name + "' has a zero <axis>");
    body.axis = actuator.axis;
    body.axisInGround = actuator.torqueIsGlobal;
    ReserveActuator reserve = makeReserve(actuator.name, actuator.limits);
    reserve.body = body;
    return reserve;
}

// Columns: the wires' then the reserves'; rows as in `wires` and `reserves`.
StorageTable joinColumns(const std::string& name, const StorageTable& wires, const StorageTable& reserves) {
    StorageTable table = wires;
    table.name = name;
    table.columns.insert(table.columns.end(), reserves.columns.begin(), reserves.columns.end());
    for (std::size_t r = 0; r < table.rows.size(); ++r)
        table.rows[r].insert(table.rows[r].end(), reserves.rows[r].begin(), reserves.rows[r].end());
    return table;
}

}  // namespace

OsimStaticOptimizationResult runOsimStaticOptimization(const Model& model, const StorageTable& motionTable,
                                                       const ExternalLoads* loads,
                                                       const OsimStaticOptimizationOptions& options) {
    TensionMotionOptions motion;
    motion.analysis.method = "so";
    motion.analysis.minActivation = options.minActivation;
    motion.analysis.maxActivation = options.maxActivation;
    motion.analysis.useMusclePhysiology = options.useMusclePhysiology;
    motion.analysis.activationExponent = options.activationExponent;
    for (const OsimCoordinateActuator& actuator : options.reserves)
        motion.analysis.reserves.push_back(makeReserve(model, actuator));
    for (const OsimPointActuator& actuator : options.pointActuators)
        motion.analysis.reserves.push_back(makeReserve(model, actuator));
    for (const OsimTorqueActuator& actuator : options.torqueActuators)
        motion.analysis.reserves.push_back(makeReserve(model, actuator));
    motion.lowpassCutoffHz = options.lowpassCutoffHz;
    motion.startTime = options.startTime;
    motion.finalTime = options.finalTime;
    motion.accelerationsFromSpeedSplines = true;
    motion.stepInterval = options.stepInterval;
    motion.onFrame = options.onFrame;
    const TensionMotionResult run =
        options.motionIsStates
            ? runTensionAnalysis(model, readOsimStates(model, motionTable, options.startTime, options.finalTime),
                                 loads, motion)
            : runTensionAnalysis(model, motionTable, loads, motion);

    OsimStaticOptimizationResult result;
    result.force = joinColumns("ModelForces", run.tensions, run.reserves);
    // The reserves' controls are their forces per optimal force.
    StorageTable controls = run.reserves;
    for (std::vector<double>& row : controls.rows)
        for (std::size_t r = 0; r < row.size(); ++r) row[r] /= motion.analysis.reserves[r].optimalForce;
    result.activation = joinColumns("Static Optimization", run.activations, controls);
    result.report = run.report;
    result.flaggedFrames = run.flaggedFrames;
    return result;
}

}  // namespace sinew
