#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include "arguments.hpp"
#include "commands.hpp"
#include "progress.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/forward_simulation.hpp"
#include "sinew/io/model_loading.hpp"
#include "sinew/plugin/simbody_simulation.hpp"
#include "sinew/plugin/wire_decorations.hpp"
#include "sinew/tools/simulation_recorder.hpp"

namespace sinew::cli {
namespace {

const char* kUsage =
    "usage: sinew simulate MODEL [options]\n"
    "  Passive forward simulation under gravity and the wires' force laws, with either engine. MODEL is a\n"
    "  sinew YAML model, an OpenSim .osim or an MJCF file (converted on the fly, what is left out listed).\n"
    "  --engine E        simbody (default): Simbody's dynamics, constraints projected each step;\n"
    "                    sinew: sinew's assembly-disassembly dynamics, constraints at acceleration level\n"
    "  --integrator I    adaptive (default): error-controlled (simbody: Runge-Kutta-Merson,\n"
    "                    sinew: Dormand-Prince 5(4)); rk4: fourth-order Runge-Kutta at a fixed step\n"
    "  --step H          the rk4 step, s (default 0.001); each interval is split into equal steps <= H\n"
    "  --hang-by LINK    weld LINK to ground at its initial pose (the paper's body hung by the head)\n"
    "  --duration T      simulated time, s (default 1)\n"
    "  --interval DT     time between output frames, s (default 0.01)\n"
    "  --accuracy A      adaptive integrator accuracy and constraint tolerance (default 1e-6)\n"
    "  --max-steps N     step budget: integrator steps tried in all (default 1e6)\n"
    "  --min-step H      the run stops when the adaptive step falls below H, s (default 1e-12)\n"
    "  --visualize       show the run in simbody-visualizer as it goes, wires coloured by tension\n"
    "                    (needs a display)\n"
    "  -o DIR            output folder (default sinew_output)\n"
    "  A run that stops early (budget, collapsed step, non-finite state) writes the frames it reached as\n"
    "  <model>_*_incomplete.sto, removes the complete files of an earlier run, and exits with status 1.\n";

enum class Engine { Simbody, Sinew };

void printRunHeader(const Model& model, const ForwardSimulationOptions& options, Engine engine) {
    std::printf("simulating %s (%d links, %d DOF, %d wires, %d loops) for %g s%s\n", model.getName().c_str(),
                model.getNumLinks(), model.getNumU(), model.getNumWires(), model.getNumLoops(), options.duration,
                options.hangBy.empty() ? "" : (", hung by " + options.hangBy).c_str());
    const bool adaptive = options.integrator == ForwardSimulationOptions::Integrator::Adaptive;
    char integratorText[96];
    if (adaptive)
        std::snprintf(integratorText, sizeof integratorText, "%s, accuracy %g",
                      engine == Engine::Sinew ? "Dormand-Prince 5(4)" : "Runge-Kutta-Merson", options.accuracy);
    else
        std::snprintf(integratorText, sizeof integratorText, "%s at a fixed step <= %g s",
                      engine == Engine::Sinew ? "classic Runge-Kutta 4" : "Runge-Kutta-Merson", options.fixedStep);
    std::printf("engine: %s (%s)\n", engine == Engine::Sinew ? "sinew" : "simbody", integratorText);
}

void printSummary(const SimulationSummary& summary, const SimulationRecorder& recorder) {
    std::printf("%d frames, %d integrator steps, %.3f s wall: %.3g s per output frame, %.3g s per integrator step\n",
                summary.frames, summary.steps, summary.wallSeconds, summary.wallSeconds / summary.frames,
                summary.wallSeconds / std::max(summary.steps, 1));
    // The paper's section 4.1 figure, for the whole-body hang (Nakamura et al.: passive wires, hung by the head).
    std::printf("paper: 0.5 s per frame (whole body, 2 GHz Pentium IV)\n");
    if (summary.wireSwitches > 0) std::printf("%d wire switches (slack/taut) located\n", summary.wireSwitches);
    std::printf("max position-constraint violation %.3g m\n", summary.maxConstraintViolation);
    std::printf("energy drift: max |E - E0| = %.3g J (%.3g of peak kinetic energy %.3g J; dissipated by any wire damping)\n",
                summary.maxEnergyDrift,
                summary.peakKineticEnergy > 0 ? summary.maxEnergyDrift / summary.peakKineticEnergy : 0.0,
                summary.peakKineticEnergy);
    std::printf("output files:\n");
    for (int k = 0; k < SimulationRecorder::kNumTables; ++k) std::printf("  %s\n", recorder.getPath(k, false).c_str());
}

}  // namespace

int runSimulate(const std::vector<std::string>& args) {
    std::string modelPath, outputDir = "sinew_output";
    bool visualize = false;
    ForwardSimulationOptions options;
    Engine engine = Engine::Simbody;
    ArgumentReader reader(args, kUsage);
    while (reader.next()) {
        if (reader.is("--engine")) {
            const std::string& name = reader.value();
            if (name == "simbody") engine = Engine::Simbody;
            else if (name == "sinew") engine = Engine::Sinew;
            else throw Error("unknown engine '" + name + "' (expected sinew or simbody)");
        } else if (reader.is("--integrator")) {
            const std::string& name = reader.value();
            if (name == "adaptive") options.integrator = ForwardSimulationOptions::Integrator::Adaptive;
            else if (name == "rk4") options.integrator = ForwardSimulationOptions::Integrator::RungeKutta4Fixed;
            else throw Error("unknown integrator '" + name + "' (expected adaptive or rk4)");
        } else if (reader.is("--step")) options.fixedStep = reader.number();
        else if (reader.is("--hang-by")) options.hangBy = reader.value();
        else if (reader.is("--duration")) options.duration = reader.number();
        else if (reader.is("--interval")) options.reportInterval = reader.number();
        else if (reader.is("--accuracy")) options.accuracy = reader.number();
        else if (reader.is("--max-steps")) {
            const double steps = reader.number();
            if (!(steps >= 1 && steps <= 1e15 && steps == std::floor(steps)))
                throw Error("--max-steps expects a whole number >= 1, got '" + std::to_string(steps) + "'");
            options.maxSteps = static_cast<long>(steps);
        } else if (reader.is("--min-step")) options.minStep = reader.number();
        else if (reader.is("--visualize")) visualize = true;
        else if (reader.is("-o", "--output")) outputDir = reader.value();
        else reader.takePositional({&modelPath});
    }
    if (reader.helpShown()) return 0;
    if (modelPath.empty()) return reader.failWithUsage();
    checkSimulationOptions(options);  // before the model loads: option errors first
    const Model model = loadModel(modelPath, [](const std::string& line) { std::printf("%s\n", line.c_str()); });
    std::optional<SimulationVisualizer> visualizer;
    if (visualize) visualizer.emplace(model, options.hangBy);
    std::filesystem::create_directories(outputDir);

    SimulationRecorder recorder(model, outputDir);

    printRunHeader(model, options, engine);
    Progress progress("simulate", options.duration);
    const auto simulate = engine == Engine::Sinew ? simulateForwardSinew : simulateForward;
    SimulationSummary summary;
    try {
        summary = simulate(model, options, [&](const SimulationFrame& frame) {
            recorder.record(frame);
            progress.update(frame.time);
            if (visualizer) visualizer->show(frame);
        });
    } catch (const Error& e) {
        progress.finish();
        if (recorder.getNumFrames() == 0) throw;
        std::string why = e.what();
        std::replace(why.begin(), why.end(), '\n', ' ');
        recorder.write(true, why);
        std::fprintf(stderr, "%d frames up to t = %g s written as %s and the other *_incomplete.sto files\n",
                     recorder.getNumFrames(), recorder.getLastTime(), recorder.getPath(0, true).c_str());
        throw;
    }
    progress.finish();
    recorder.write(false);

    printSummary(summary, recorder);
    return 0;
}

}  // namespace sinew::cli
