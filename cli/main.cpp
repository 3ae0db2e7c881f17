// sinew: wire-driven musculoskeletal dynamics on Simbody.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "commands.hpp"

namespace {

const char* kUsage =
    "usage: sinew COMMAND [options]\n"
    "\n"
    "commands:\n"
    "  info MODEL                      the model's census (paper's Table 1); MODEL: sinew .yaml, .osim or MJCF\n"
    "  simulate MODEL [--engine sinew|simbody] [--integrator adaptive|rk4] [--step H]\n"
    "                 [--hang-by LINK] [--duration T] [--interval DT] [--accuracy A] [-o DIR]\n"
    "                                  passive forward simulation with sinew's or Simbody's engine;\n"
    "                                  writes .sto files of coordinates, speeds, wire tensions and energy\n"
    "  import MODEL -o MODEL.yaml      converts an OpenSim 4 (.osim) or MuJoCo MJCF (.xml) model,\n"
    "                                  listing what it leaves out\n"
    "  export MODEL -o MODEL.xml       writes the model as MuJoCo MJCF, listing how MuJoCo's model differs\n"
    "  inverse-dynamics MODEL MOTION [--external-loads X.xml] [--lowpass HZ] -o OUT.sto\n"
    "                                  generalized forces per frame, processed as OpenSim's ID tool\n"
    "  ik MODEL CAPTURE.trc [--setup IK_SETUP.xml] -o OUT.mot\n"
    "                                  inverse kinematics of a marker capture (OpenSim's IK problem)\n"
    "  run-tool SETUP.xml [-o DIR]     runs an OpenSim InverseDynamicsTool, InverseKinematicsTool or\n"
    "                                  AnalyzeTool (StaticOptimization) setup as it stands\n"
    "  moment-arms MODEL [--motion M] [-o DIR]   wire lengths and moment arms (OpenSim MuscleAnalysis files)\n"
    "  tensions MODEL MOTION --method lp|qp|so [--external-loads X.xml] [--lowpass HZ] -o TENSIONS.sto\n"
    "                                  wire tensions per frame (LP, least squares or static optimization)\n"
    "  whole-body SOURCE --rules R.yaml [--anthropometrics T.csv] -o MODEL.yaml\n"
    "                                  derives the whole-body wire model from MS-Human-700 by the rules\n"
    "  render MODEL [--motion Q.sto] [--tensions T.sto] [--frame K | --time T | --strip N] -o OUT.png|.html\n"
    "                                  the body with its wires coloured by tension (front and side views),\n"
    "                                  or a browser page that plays the motion\n"
    "  plot FILE.sto ... [--columns A,B] -o OUT.png | plot --benchmark RESULTS.json [--filter RE] -o OUT.png\n"
    "                                  line plots of storage columns over time, benchmark scaling curves\n"
    "\n"
    "Run 'sinew COMMAND --help' for a command's options.\n";

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
        std::fputs(kUsage, argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    const std::string command = argv[1];
    const std::vector<std::string> args(argv + 2, argv + argc);
    try {
        if (command == "info") return sinew::cli::runInfo(args);
        if (command == "simulate") return sinew::cli::runSimulate(args);
        if (command == "import") return sinew::cli::runImport(args);
        if (command == "export") return sinew::cli::runExport(args);
        if (command == "inverse-dynamics") return sinew::cli::runInverseDynamicsCommand(args);
        if (command == "ik") return sinew::cli::runInverseKinematicsCommand(args);
        if (command == "run-tool") return sinew::cli::runRunTool(args);
        if (command == "moment-arms") return sinew::cli::runMomentArms(args);
        if (command == "tensions") return sinew::cli::runTensions(args);
        if (command == "whole-body") return sinew::cli::runWholeBody(args);
        if (command == "render") return sinew::cli::runRender(args);
        if (command == "plot") return sinew::cli::runPlot(args);
        std::fprintf(stderr, "sinew: unknown command '%s'\n\n%s", command.c_str(), kUsage);
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "sinew %s: error: %s\n", command.c_str(), e.what());
        return 1;
    }
}
