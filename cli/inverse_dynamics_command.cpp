#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "arguments.hpp"
#include "commands.hpp"
#include "progress.hpp"
#include "sinew/core/error.hpp"
#include "sinew/tools/inverse_dynamics_tool.hpp"
#include "sinew/io/model_loading.hpp"

namespace sinew::cli {
namespace {

const char* kUsage =
    "usage: sinew inverse-dynamics MODEL MOTION [options] -o OUT.sto\n"
    "  Generalized forces per frame of a coordinates table (.mot/.sto), processed as OpenSim's inverse\n"
    "  dynamics tool processes it; columns named as OpenSim names them. MODEL: .osim or sinew .yaml.\n"
    "  --external-loads X.xml   OpenSim ExternalLoads (e.g. ground reactions)\n"
    "  --lowpass HZ             low-pass cut-off for the coordinates (default: no filtering)\n"
    "  --start T, --end T       time range, s (default: the whole motion)\n"
    "  -o OUT.sto               output file\n";

}  // namespace

int runInverseDynamicsCommand(const std::vector<std::string>& args) {
    std::string modelPath, motionPath, loadsPath, output;
    InverseDynamicsOptions options;
    ArgumentReader reader(args, kUsage);
    while (reader.next()) {
        if (reader.is("--external-loads")) loadsPath = reader.value();
        else if (reader.is("--lowpass")) options.lowpassCutoffHz = reader.number();
        else if (reader.is("--start")) options.startTime = reader.number();
        else if (reader.is("--end")) options.finalTime = reader.number();
        else if (reader.is("-o", "--output")) output = reader.value();
        else reader.takePositional({&modelPath, &motionPath});
    }
    if (reader.helpShown()) return 0;
    if (modelPath.empty() || motionPath.empty() || output.empty()) return reader.failWithUsage();
    const Model model = loadModel(modelPath, [](const std::string& note) { std::printf("%s\n", note.c_str()); });
    std::optional<ExternalLoads> loads;
    if (!loadsPath.empty()) loads = readExternalLoads(loadsPath);
    std::optional<Progress> progress;
    // The motion's preprocessing (filter, splines) runs before the first frame; the frames after it are the
    // dynamics alone.
    using Clock = std::chrono::steady_clock;
    Clock::time_point firstFrameDone, lastFrameDone;
    options.onFrame = [&](int frame, int frames) {
        lastFrameDone = Clock::now();
        if (frame == 1) firstFrameDone = lastFrameDone;
        if (!progress) progress.emplace("inverse dynamics", frames);
        progress->update(frame);
    };
    const StorageTable motion = readStorageFile(motionPath);
    checkLowpassOption(options.lowpassCutoffHz, motion, motionPath);
    const Clock::time_point start = Clock::now();
    const StorageTable result = runInverseDynamics(model, motion, loads ? &*loads : nullptr, options);
    if (progress) progress->finish();
    const std::filesystem::path parent = std::filesystem::path(output).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    writeStorageFile(result, output);
    std::printf("%zu frames, %zu generalized forces -> %s\n", result.times.size(), result.columns.size(), output.c_str());
    if (result.times.size() > 1) {
        const auto ms = [](Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); };
        std::printf("time: %.3g ms preprocessing the motion and the first frame, then %.3g ms per frame\n",
                    ms(firstFrameDone - start), ms(lastFrameDone - firstFrameDone) / static_cast<double>(result.times.size() - 1));
    }
    return 0;
}

}  // namespace sinew::cli
