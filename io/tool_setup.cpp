#include "sinew/io/tool_setup.hpp"

#include "osim_xml.hpp"
#include "sinew/core/error.hpp"

namespace sinew {
namespace {

using osim::Element;
using osim::XmlDocument;

// A file property made absolute against the setup's folder; `required` ones must be given.
std::string readFile(const XmlDocument& doc, const Element& tool, const char* property, bool required) {
    const std::string file = doc.resolveFile(osim::readText(doc, tool, property));
    if (required && file.empty()) doc.fail(tool, std::string("missing <") + property + ">");
    return file;
}

void checkTimeOrder(const XmlDocument& doc, const Element& element, double start, double end) {
    if (start > end)
        doc.fail(element, "starts at " + std::to_string(start) + " s, after its end at " + std::to_string(end) + " s");
}

int readCount(const XmlDocument& doc, const Element& owner, const char* property, int fallback) {
    const double value = osim::readDouble(doc, owner, property, fallback);
    if (value != static_cast<int>(value) || value < 1)
        doc.fail(*osim::findChild(owner, property), "expected a whole number >= 1");
    return static_cast<int>(value);
}

StaticOptimizationAnalysis readStaticOptimization(const XmlDocument& doc, const Element& element) {
    StaticOptimizationAnalysis settings;
    settings.name = osim::getName(element).empty() ? settings.name : osim::getName(element);
    settings.where = doc.where(element);
    settings.on = osim::readBool(doc, element, "on", settings.on);
    settings.startTime = osim::readDouble(doc, element, "start_time", settings.startTime);
    settings.endTime = osim::readDouble(doc, element, "end_time", settings.endTime);
    checkTimeOrder(doc, element, settings.startTime, settings.endTime);
    settings.stepInterval = readCount(doc, element, "step_interval", settings.stepInterval);
    settings.inDegrees = osim::readBool(doc, element, "in_degrees", settings.inDegrees);
    settings.useModelForceSet = osim::readBool(doc, element, "use_model_force_set", settings.useModelForceSet);
    settings.activationExponent = osim::readDouble(doc, element, "activation_exponent", settings.activationExponent);
    if (!(settings.activationExponent > 0))
        doc.fail(*osim::findChild(element, "activation_exponent"), "the exponent must be positive");
    settings.useMusclePhysiology = osim::readBool(doc, element, "use_muscle_physiology", settings.useMusclePhysiology);
    settings.optimizerConvergenceCriterion =
        osim::readDouble(doc, element, "optimizer_convergence_criterion", settings.optimizerConvergenceCriterion);
    if (!(settings.optimizerConvergenceCriterion > 0))
        doc.fail(*osim::findChild(element, "optimizer_convergence_criterion"), "the tolerance must be positive");
    settings.optimizerMaxIterations = readCount(doc, element, "optimizer_max_iterations", settings.optimizerMaxIterations);
    return settings;
}

InverseDynamicsSetup readInverseDynamicsTool(const XmlDocument& doc, const Element& tool) {
    const std::string& path = doc.getPath();
    InverseDynamicsSetup setup;
    setup.name = osim::getName(tool);
    setup.file = path;
    setup.modelFile = readFile(doc, tool, "model_file", true);
    const std::vector<double> range = osim::readFixedNumbers(doc, tool, "time_range", 2, {setup.startTime, setup.endTime});
    setup.startTime = range[0];
    setup.endTime = range[1];
    if (const Element* timeRange = osim::findChild(tool, "time_range"))
        checkTimeOrder(doc, *timeRange, setup.startTime, setup.endTime);
    setup.forcesToExclude = osim::readNames(doc, tool, "forces_to_exclude");
    setup.externalLoadsFile = readFile(doc, tool, "external_loads_file", false);
    setup.coordinatesFile = readFile(doc, tool, "coordinates_file", true);
    setup.lowpassCutoffFrequencyForCoordinates = osim::readDouble(doc, tool, "lowpass_cutoff_frequency_for_coordinates",
                                                                  setup.lowpassCutoffFrequencyForCoordinates);
    setup.resultsDirectory = doc.resolveFile(osim::readText(doc, tool, "results_directory", "."));
    setup.outputGenForceFile = osim::readText(doc, tool, "output_gen_force_file", setup.outputGenForceFile);
    setup.inputDirectory = osim::readText(doc, tool, "input_directory");
    if (osim::findChild(tool, "coordinates_in_degrees"))
        setup.coordinatesInDegrees = osim::readBool(doc, tool, "coordinates_in_degrees", true);
    return setup;
}

AnalyzeSetup readAnalyzeTool(const XmlDocument& doc, const Element& tool) {
    const std::string& path = doc.getPath();
    AnalyzeSetup setup;
    setup.name = osim::getName(tool);
    setup.file = path;
    setup.modelFile = readFile(doc, tool, "model_file", true);
    setup.replaceForceSet = osim::readBool(doc, tool, "replace_force_set", setup.replaceForceSet);
    for (const std::string& file : osim::readNames(doc, tool, "force_set_files"))
        setup.forceSetFiles.push_back(doc.resolveFile(file));
    setup.resultsDirectory = doc.resolveFile(osim::readText(doc, tool, "results_directory", "."));
    setup.outputPrecision = readCount(doc, tool, "output_precision", setup.outputPrecision);
    setup.initialTime = osim::readDouble(doc, tool, "initial_time", setup.initialTime);
    setup.finalTime = osim::readDouble(doc, tool, "final_time", setup.finalTime);
    checkTimeOrder(doc, tool, setup.initialTime, setup.finalTime);
    setup.solveForEquilibriumForAuxiliaryStates = osim::readBool(doc, tool, "solve_for_equilibrium_for_auxiliary_states",
                                                                 setup.solveForEquilibriumForAuxiliaryStates);
    setup.externalLoadsFile = readFile(doc, tool, "external_loads_file", false);
    setup.statesFile = readFile(doc, tool, "states_file", false);
    setup.coordinatesFile = readFile(doc, tool, "coordinates_file", false);
    setup.speedsFile = readFile(doc, tool, "speeds_file", false);
    if (setup.statesFile.empty() && setup.coordinatesFile.empty())
        doc.fail(tool, "names no motion: give a <states_file> or a <coordinates_file>");
    setup.lowpassCutoffFrequencyForCoordinates = osim::readDouble(doc, tool, "lowpass_cutoff_frequency_for_coordinates",
                                                                  setup.lowpassCutoffFrequencyForCoordinates);
    if (const Element* analyses = osim::findChild(tool, "AnalysisSet"))
        for (const Element* analysis : osim::getSetObjects(*analyses)) {
            if (std::string(osim::typeOf(*analysis)) == "StaticOptimization" && !setup.staticOptimization)
                setup.staticOptimization = readStaticOptimization(doc, *analysis);
            else
                setup.unsupported.push_back({osim::typeOf(*analysis), osim::getName(*analysis), doc.where(*analysis)});
        }
    if (const Element* controllers = osim::findChild(tool, "ControllerSet"))
        for (const Element* controller : osim::getSetObjects(*controllers))
            setup.unsupported.push_back({osim::typeOf(*controller), osim::getName(*controller), doc.where(*controller)});
    return setup;
}

InverseKinematicsTaskSetup readInverseKinematicsTask(const XmlDocument& doc, const Element& element) {
    InverseKinematicsTaskSetup task;
    task.name = osim::getName(element);
    task.where = doc.where(element);
    if (task.name.empty()) doc.fail(element, "a task needs the name of its marker or coordinate");
    task.apply = osim::readBool(doc, element, "apply", task.apply);
    task.weight = osim::readDouble(doc, element, "weight", task.weight);
    if (task.weight < 0) doc.fail(element, "weight must be >= 0");
    task.valueType = osim::readText(doc, element, "value_type", task.valueType);
    if (task.valueType != "default_value" && task.valueType != "manual_value" && task.valueType != "from_file")
        doc.fail(element, "value_type '" + task.valueType + "' is not default_value, manual_value or from_file");
    task.value = osim::readDouble(doc, element, "value", task.value);
    return task;
}

InverseKinematicsSetup readInverseKinematicsTool(const XmlDocument& doc, const Element& tool) {
    InverseKinematicsSetup setup;
    setup.name = osim::getName(tool);
    setup.file = doc.getPath();
    setup.modelFile = readFile(doc, tool, "model_file", true);
    setup.markerFile = readFile(doc, tool, "marker_file", true);
    if (osim::readText(doc, tool, "coordinate_file") != "Unassigned")  // OpenSim's word for none
        setup.coordinateFile = readFile(doc, tool, "coordinate_file", false);
    const std::vector<double> range = osim::readFixedNumbers(doc, tool, "time_range", 2, {setup.startTime, setup.endTime});
    setup.startTime = range[0];
    setup.endTime = range[1];
    checkTimeOrder(doc, tool, setup.startTime, setup.endTime);
    setup.accuracy = osim::readDouble(doc, tool, "accuracy", setup.accuracy);
    if (!(setup.accuracy > 0)) doc.fail(*osim::findChild(tool, "accuracy"), "accuracy must be > 0");
    const std::string weight = osim::readText(doc, tool, "constraint_weight", "Inf");
    if (weight != "Inf" && weight != "inf" && weight != "Infinity")
        setup.constraintWeight = osim::readDouble(doc, tool, "constraint_weight", setup.constraintWeight);
    if (const Element* tasks = osim::findChild(tool, "IKTaskSet"))
        for (const Element* task : osim::getSetObjects(*tasks)) {
            const std::string type = osim::typeOf(*task);
            if (type == "IKMarkerTask")
                setup.markerTasks.push_back(readInverseKinematicsTask(doc, *task));
            else if (type == "IKCoordinateTask")
                setup.coordinateTasks.push_back(readInverseKinematicsTask(doc, *task));
            else
                doc.fail(*task, "expected an IKMarkerTask or IKCoordinateTask");
        }
    setup.resultsDirectory = doc.resolveFile(osim::readText(doc, tool, "results_directory", "."));
    setup.outputMotionFile = osim::readText(doc, tool, "output_motion_file", setup.name + "_ik.mot");
    setup.reportErrors = osim::readBool(doc, tool, "report_errors", setup.reportErrors);
    return setup;
}

}  // namespace

InverseKinematicsSetup readInverseKinematicsSetup(const std::string& path) {
    const XmlDocument doc(path);
    return readInverseKinematicsTool(doc, doc.getObject("InverseKinematicsTool"));
}

InverseDynamicsSetup readInverseDynamicsSetup(const std::string& path) {
    const XmlDocument doc(path);
    return readInverseDynamicsTool(doc, doc.getObject("InverseDynamicsTool"));
}

AnalyzeSetup readAnalyzeSetup(const std::string& path) {
    const XmlDocument doc(path);
    return readAnalyzeTool(doc, doc.getObject("AnalyzeTool"));
}

ToolSetup readToolSetup(const std::string& path) {
    const XmlDocument doc(path);
    const Element& tool = doc.getFirstObject();
    const std::string type = osim::typeOf(tool);
    if (type == "InverseDynamicsTool") return readInverseDynamicsTool(doc, tool);
    if (type == "AnalyzeTool") return readAnalyzeTool(doc, tool);
    if (type == "InverseKinematicsTool") return readInverseKinematicsTool(doc, tool);
    doc.fail(tool, "not a tool sinew runs (expected an InverseDynamicsTool, InverseKinematicsTool or AnalyzeTool setup)");
}

OsimForceSet readForceSetFile(const std::string& path) {
    const XmlDocument doc(path);
    const Element& set = doc.getObject("ForceSet");
    OsimForceSet forces;
    forces.name = osim::getName(set);
    forces.file = path;
    for (const Element* element : osim::getSetObjects(set)) {
        const std::string type = osim::getCurrentTypeName(osim::typeOf(*element));
        if (type == "CoordinateActuator")
            forces.coordinateActuators.push_back(osim::readCoordinateActuator(doc, *element));
        else if (type == "PointActuator")
            forces.pointActuators.push_back(osim::readPointActuator(doc, *element));
        else if (type == "TorqueActuator")
            forces.torqueActuators.push_back(osim::readTorqueActuator(doc, *element));
        else
            forces.unsupported.push_back({osim::typeOf(*element), osim::getName(*element), doc.where(*element)});
    }
    return forces;
}

}  // namespace sinew
