#pragma once
// OpenSim tool setup files: InverseDynamicsTool, InverseKinematicsTool, AnalyzeTool with a StaticOptimization
// analysis, and the
// force-set files such a setup adds to the model (reserve and residual actuators). Files they name are made
// absolute against the setup file's folder, where OpenSim 4 runs its tools from. Values absent from the XML
// take OpenSim's defaults, written here.
#include <limits>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "sinew/io/osim_model.hpp"

namespace sinew {

struct InverseDynamicsSetup {
    std::string name;
    std::string file;       // the setup read
    std::string modelFile;  // absolute
    double startTime = -std::numeric_limits<double>::infinity();  // s, <time_range>
    double endTime = std::numeric_limits<double>::infinity();
    // Force names or groups ("Muscles", "Actuators", "All") left out of the dynamics.
    std::vector<std::string> forcesToExclude;
    std::string externalLoadsFile;  // absolute; empty: none
    std::string coordinatesFile;    // absolute
    double lowpassCutoffFrequencyForCoordinates = -1;  // Hz; negative: no filtering
    std::string resultsDirectory;                      // absolute
    std::string outputGenForceFile = "inverse_dynamics.sto";  // a file name inside resultsDirectory
    std::string inputDirectory;  // as written; OpenSim 4 resolves inputs against the setup's folder instead
    std::optional<bool> coordinatesInDegrees;  // an OpenSim 3 property, kept when present
};

struct StaticOptimizationAnalysis {
    std::string name = "StaticOptimization";
    bool on = true;
    double startTime = -std::numeric_limits<double>::infinity();  // s
    double endTime = std::numeric_limits<double>::infinity();
    int stepInterval = 1;    // results every this many time steps
    bool inDegrees = true;   // results' angles in degrees
    bool useModelForceSet = true;
    double activationExponent = 2;  // the cost is sum of activation^exponent
    bool useMusclePhysiology = true;  // muscle force-length-velocity limits the force per activation
    double optimizerConvergenceCriterion = 1e-4;
    int optimizerMaxIterations = 100;
    std::string where;  // "file:line" of its XML element
};

struct AnalyzeSetup {
    std::string name;
    std::string file;
    std::string modelFile;                  // absolute
    bool replaceForceSet = true;            // the force-set files replace the model's forces (else add to them)
    std::vector<std::string> forceSetFiles;  // absolute
    std::string resultsDirectory;           // absolute
    int outputPrecision = 8;
    double initialTime = 0, finalTime = 1;  // s
    bool solveForEquilibriumForAuxiliaryStates = false;
    std::string externalLoadsFile;  // absolute; empty: none
    // The motion: a states file, or coordinates (with optional speeds). Absolute; empty when absent.
    std::string statesFile, coordinatesFile, speedsFile;
    double lowpassCutoffFrequencyForCoordinates = -1;  // Hz; negative: no filtering
    std::optional<StaticOptimizationAnalysis> staticOptimization;
    std::vector<OsimUnsupported> unsupported;  // other analyses and controllers
};

// An InverseKinematicsTool's task: a marker (IKMarkerTask) or a coordinate (IKCoordinateTask) to track.
struct InverseKinematicsTaskSetup {
    std::string name;  // the marker's or the coordinate's
    bool apply = true;
    double weight = 0;  // OpenSim's default
    // Coordinate tasks: where the target comes from: "default_value" (the model's), "manual_value"
    // (`value`) or "from_file" (the setup's coordinate_file).
    std::string valueType = "default_value";
    double value = 0;
    std::string where;
};

struct InverseKinematicsSetup {
    std::string name;
    std::string file;
    std::string modelFile;       // absolute
    std::string markerFile;      // absolute (.trc)
    std::string coordinateFile;  // absolute; empty when Unassigned
    double startTime = -std::numeric_limits<double>::infinity();  // s, <time_range>
    double endTime = std::numeric_limits<double>::infinity();
    double accuracy = 1e-5;
    double constraintWeight = std::numeric_limits<double>::infinity();  // Inf: loops and couplers held exactly
    std::vector<InverseKinematicsTaskSetup> markerTasks, coordinateTasks;
    std::string resultsDirectory;  // absolute
    std::string outputMotionFile;  // a file name inside resultsDirectory
    bool reportErrors = true;
};

// A force-set file (<ForceSet>): the scalar actuators it holds.
struct OsimForceSet {
    std::string name;
    std::string file;
    std::vector<OsimCoordinateActuator> coordinateActuators;
    std::vector<OsimPointActuator> pointActuators;
    std::vector<OsimTorqueActuator> torqueActuators;
    std::vector<OsimUnsupported> unsupported;  // other force types
};

// Each throws ModelError at "file:line" naming the element and what was expected.
InverseDynamicsSetup readInverseDynamicsSetup(const std::string& path);
AnalyzeSetup readAnalyzeSetup(const std::string& path);
InverseKinematicsSetup readInverseKinematicsSetup(const std::string& path);
OsimForceSet readForceSetFile(const std::string& path);
// Whichever tool the file holds, as the type of its <OpenSimDocument>'s object says; any other tool is
// refused at the object's line.
using ToolSetup = std::variant<InverseDynamicsSetup, AnalyzeSetup, InverseKinematicsSetup>;
ToolSetup readToolSetup(const std::string& path);

}  // namespace sinew
