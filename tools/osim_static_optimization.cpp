#include <algorithm>

#include "sinew/core/error.hpp"
#include "sinew/tools/static_optimization_tool.hpp"
#include "sinew/tools/tension_motion.hpp"

namespace sinew {
namespace {

ReserveActuator makeReserve(const Model& model, const OsimCoordinateActuator& actuator) {
    const int dof = model.findCoordinateIndex(actuator.coordinate);  // scalar coordinates: q index = u index
    if (dof == Model::kNotFound)
        throw ModelError(actuator.where, "CoordinateActuator '" + actuator.name + "' acts on coordinate '" +
                                             actuator.coordinate + "', which model '" + model.getName() + "' lacks");
    ReserveActuator reserve;
    reserve.name = actuator.name;
    reserve.dof = dof;
    reserve.optimalForce = actuator.limits.optimalForce;
    reserve.minControl = actuator.limits.minControl;
    reserve.maxControl = actuator.limits.maxControl;
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

OsimStaticOptimizationResult runOsimStaticOptimization(const Model& model, const StorageTable& coordinates,
                                                       const ExternalLoads* loads,
                                                       const OsimStaticOptimizationOptions& options) {
    TensionMotionOptions motion;
    motion.analysis.method = TensionMethod::StaticOptimization;
    motion.analysis.minActivation = options.minActivation;
    motion.analysis.maxActivation = options.maxActivation;
    motion.analysis.useMusclePhysiology = options.useMusclePhysiology;
    for (const OsimCoordinateActuator& actuator : options.reserves)
        motion.analysis.reserves.push_back(makeReserve(model, actuator));
    motion.lowpassCutoffHz = options.lowpassCutoffHz;
    motion.startTime = options.startTime;
    motion.finalTime = options.finalTime;
    motion.accelerationsFromSpeedSplines = true;
    motion.onFrame = options.onFrame;
    const TensionMotionResult run = runTensionAnalysis(model, coordinates, loads, motion);

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
