#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "arguments.hpp"
#include "commands.hpp"
#include "progress.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/io/model_loading.hpp"
#include "sinew/io/tool_setup.hpp"
#include "sinew/tools/bvh_inverse_kinematics.hpp"
#include "sinew/tools/inverse_kinematics_tool.hpp"

namespace sinew::cli {
namespace {

const char* kUsage =
    "usage: sinew ik MODEL CAPTURE.trc|CAPTURE.bvh [--setup IK_SETUP.xml] [--map MAP.yaml] [--no-scaling]\n"
    "                [--scaled-model SCALED.yaml] [--start T] [--end T] [--decimals N] -o OUT.mot\n"
    "  Inverse kinematics of a capture: per frame, the coordinates that best fit the model's markers (its\n"
    "  OpenSim MarkerSet) to a TRC file's, or its links' joint centres to a BVH file's joints, loops and\n"
    "  couplers kept, clamped coordinates in range, warm-started from the previous frame (the first frame\n"
    "  from the default pose, a free root turned onto the capture). Writes OUT.mot (OpenSim's columns,\n"
    "  angles in degrees) and\n"
    "  OUT_marker_errors.sto (per frame: weighted squared error, RMS and largest marker error, markers seen,\n"
    "  iterations, converged).\n"
    "  --setup X.xml   an OpenSim IK setup: its marker and coordinate tasks (weights) and time range; without\n"
    "                  it, every model marker in the capture at weight 1\n"
    "  --map MAP.yaml  BVH joints to model links and the BVH axes (default: bvh_map.yaml beside MODEL, as\n"
    "                  models/whole_body/ ships it)\n"
    "  --no-scaling    fit a BVH capture with the model as it is; by default its segments are first scaled to\n"
    "                  the BVH skeleton's (per segment, mass kept; docs/inverse-kinematics.md)\n"
    "  --scaled-model SCALED.yaml   write the scaled model the BVH capture was fitted with\n"
    "  --start T, --end T   time range, s (default: the setup's, or the whole capture)\n"
    "  --decimals N    write OUT.mot's values with N digits after the point (default: 17 significant digits)\n"
    "  -o OUT.mot      output file\n";

void printScales(const BvhMap& map, const BvhSegmentScales& scales) {
    std::printf("scaled to the BVH skeleton, per segment:");
    for (std::size_t k = 0; k < map.joints.size(); ++k)
        std::printf("%s %s %.3f", k % 6 == 0 ? "\n " : ",", map.joints[k].first.c_str(), scales.jointFactors[k]);
    std::printf("\n");
}

}  // namespace

int runInverseKinematicsCommand(const std::vector<std::string>& args) {
    std::string modelPath, capturePath, setupPath, mapPath, scaledPath, output;
    std::optional<double> start, end;
    bool scaling = true;
    int decimals = -1;
    ArgumentReader reader(args, kUsage);
    while (reader.next()) {
        if (reader.is("--setup")) setupPath = reader.value();
        else if (reader.is("--map")) mapPath = reader.value();
        else if (reader.is("--no-scaling")) scaling = false;
        else if (reader.is("--scaled-model")) scaledPath = reader.value();
        else if (reader.is("--start")) start = reader.number();
        else if (reader.is("--end")) end = reader.number();
        else if (reader.is("--decimals")) {
            const double value = reader.number();
            if (value < 0 || value > 17 || value != std::floor(value))
                throw Error("--decimals takes a whole number from 0 to 17, got " + std::to_string(value));
            decimals = static_cast<int>(value);
        }
        else if (reader.is("-o", "--output")) output = reader.value();
        else reader.takePositional({&modelPath, &capturePath});
    }
    if (reader.helpShown()) return 0;
    if (modelPath.empty() || capturePath.empty() || output.empty()) return reader.failWithUsage();
    const auto printNote = [](const std::string& note) { std::printf("%s\n", note.c_str()); };
    const Model loaded = loadModel(modelPath, printNote);
    InverseKinematicsRequest request;
    if (!setupPath.empty()) request = makeInverseKinematicsRequest(readInverseKinematicsSetup(setupPath));
    if (start) request.startTime = *start;
    if (end) request.endTime = *end;
    std::optional<Progress> progress;
    const auto onFrame = [&](int frame, int frames) {
        if (!progress) progress.emplace("inverse kinematics", frames);
        progress->update(frame);
    };
    const auto started = std::chrono::steady_clock::now();
    std::optional<BvhInverseKinematics> bvhFit;
    InverseKinematicsResult result;
    if (std::filesystem::path(capturePath).extension() == ".bvh") {
        if (mapPath.empty()) mapPath = (std::filesystem::path(modelPath).parent_path() / "bvh_map.yaml").string();
        const BvhMap map = readBvhMap(mapPath);
        bvhFit = runBvhInverseKinematics(loaded, readBvhFile(capturePath), map, scaling, request, printNote, onFrame);
        if (progress) progress->finish();
        std::printf("BVH: %zu joints mapped by %s, %.4g m per BVH unit, orientation weight %g m^2/rad^2\n",
                    map.joints.size(), mapPath.c_str(), bvhFit->unit, map.orientationWeight);
        if (bvhFit->scales) printScales(map, *bvhFit->scales);
        if (!scaledPath.empty()) {
            writeModelFile(bvhFit->model, scaledPath);
            std::printf("model fitted -> %s\n", scaledPath.c_str());
        }
        result = std::move(bvhFit->result);
    } else {
        result = runInverseKinematics(loaded, loadMarkers(modelPath, loaded), readTrcFile(capturePath), request,
                                      printNote, onFrame);
        if (progress) progress->finish();
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const Model& model = bvhFit ? bvhFit->model : loaded;
    const std::filesystem::path motion(output);
    if (!motion.parent_path().empty()) std::filesystem::create_directories(motion.parent_path());
    const std::string errors = (motion.parent_path() / (motion.stem().string() + "_marker_errors.sto")).string();
    writeInverseKinematicsFiles(model, result, output, errors, true, decimals);
    const InverseKinematicsSummary summary = summarizeInverseKinematics(result);
    std::printf("%d frames, %zu markers: per frame RMS error median %.4g m, largest %.4g m; largest single error "
                "%.4g m; iterations median %g, largest %g; %.3g ms/frame; %d frames not converged\n",
                summary.frames, result.markers.size(), summary.medianRmsError, summary.largestRmsError,
                summary.largestError, summary.medianIterations, summary.largestIterations,
                1e3 * seconds / summary.frames, summary.unconverged);
    std::printf("-> %s, %s\n", output.c_str(), errors.c_str());
    return summary.unconverged == 0 ? 0 : 3;
}

}  // namespace sinew::cli
