#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "arguments.hpp"
#include "commands.hpp"
#include "progress.hpp"
#include "sinew/io/model_loading.hpp"
#include "sinew/io/tool_setup.hpp"
#include "sinew/tools/bvh_targets.hpp"
#include "sinew/tools/inverse_kinematics_tool.hpp"

namespace sinew::cli {
namespace {

const char* kUsage =
    "usage: sinew ik MODEL CAPTURE.trc|CAPTURE.bvh [--setup IK_SETUP.xml] [--map MAP.yaml] [--start T] [--end T]\n"
    "                -o OUT.mot\n"
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
    "  --start T, --end T   time range, s (default: the setup's, or the whole capture)\n"
    "  -o OUT.mot      output file\n";

}  // namespace

int runInverseKinematicsCommand(const std::vector<std::string>& args) {
    std::string modelPath, capturePath, setupPath, mapPath, output;
    std::optional<double> start, end;
    ArgumentReader reader(args, kUsage);
    while (reader.next()) {
        if (reader.is("--setup")) setupPath = reader.value();
        else if (reader.is("--map")) mapPath = reader.value();
        else if (reader.is("--start")) start = reader.number();
        else if (reader.is("--end")) end = reader.number();
        else if (reader.is("-o", "--output")) output = reader.value();
        else reader.takePositional({&modelPath, &capturePath});
    }
    if (reader.helpShown()) return 0;
    if (modelPath.empty() || capturePath.empty() || output.empty()) return reader.failWithUsage();
    const auto printNote = [](const std::string& note) { std::printf("%s\n", note.c_str()); };
    const Model model = loadModel(modelPath, printNote);
    std::vector<Marker> markers;
    MarkerTable capture;
    if (std::filesystem::path(capturePath).extension() == ".bvh") {
        if (mapPath.empty()) mapPath = (std::filesystem::path(modelPath).parent_path() / "bvh_map.yaml").string();
        BvhTargets targets = makeBvhTargets(readBvhFile(capturePath), readBvhMap(mapPath), model);
        std::printf("BVH: %zu joints mapped by %s, %.4g m per BVH unit\n", targets.markers.size(), mapPath.c_str(),
                    targets.unit);
        markers = std::move(targets.markers);
        capture = std::move(targets.capture);
    } else {
        markers = loadMarkers(modelPath, model);
        capture = readTrcFile(capturePath);
    }
    InverseKinematicsRequest request;
    if (!setupPath.empty()) request = makeInverseKinematicsRequest(readInverseKinematicsSetup(setupPath));
    if (start) request.startTime = *start;
    if (end) request.endTime = *end;
    std::optional<Progress> progress;
    const auto onFrame = [&](int frame, int frames) {
        if (!progress) progress.emplace("inverse kinematics", frames);
        progress->update(frame);
    };
    const InverseKinematicsResult result = runInverseKinematics(model, markers, capture, request, printNote, onFrame);
    if (progress) progress->finish();
    const std::filesystem::path motion(output);
    if (!motion.parent_path().empty()) std::filesystem::create_directories(motion.parent_path());
    const std::string errors = (motion.parent_path() / (motion.stem().string() + "_marker_errors.sto")).string();
    writeInverseKinematicsFiles(model, result, output, errors);
    std::vector<double> rms;
    int unconverged = 0;
    for (const InverseKinematicsReport& report : result.motion.reports) {
        rms.push_back(report.rmsMarkerError);
        unconverged += report.converged ? 0 : 1;
    }
    std::sort(rms.begin(), rms.end());
    std::printf("%zu frames, %zu markers: marker RMS median %.4g m, largest %.4g m; %d frames not converged\n",
                rms.size(), result.markers.size(), rms[rms.size() / 2], rms.back(), unconverged);
    std::printf("-> %s, %s\n", output.c_str(), errors.c_str());
    return unconverged == 0 ? 0 : 3;
}

}  // namespace sinew::cli
