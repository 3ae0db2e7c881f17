#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>

#include "arguments.hpp"
#include "commands.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/model_loading.hpp"
#include "sinew/render/body_motion.hpp"
#include "sinew/render/html_viewer.hpp"
#include "sinew/render/picture.hpp"

namespace sinew::cli {
namespace {

const char* kUsage =
    "usage: sinew render MODEL [options] -o OUT.png|OUT.html\n"
    "  Draws the body with its wires coloured by tension (viridis; ligaments with a rest length by strain,\n"
    "  plasma), with colour bars and a legend of wire kinds (docs/rendering.md). MODEL: sinew .yaml, .osim or\n"
    "  MJCF. Without --motion, the model's default pose; without --tensions, tensions from the wires' force\n"
    "  laws at each frame.\n"
    "  --motion Q.sto    coordinates over time (a .mot/.sto by coordinate name, or sinew simulate's\n"
    "                    *_coordinates.sto)\n"
    "  --tensions T.sto  wire tensions over time, one column per wire (sinew simulate's *_tensions.sto,\n"
    "                    sinew tensions' output)\n"
    "  --frame K         the row K (from 0) of the motion, or of the tensions without a motion (default 0)\n"
    "  --time T          the row nearest time T, s\n"
    "  --strip N         N frames evenly from the first row to the last, side by side (a row per view)\n"
    "  --start T, --end T   the strip's and the page's time range, s (default: every row)\n"
    "  --view V          front, side or both (default both)\n"
    "  --height PX       height of one view, px (default 640)\n"
    "  --max-tension F   tension at the top of the colour scale, N (default: the largest drawn)\n"
    "  --max-strain S    ligament strain at the top of its scale (default: the largest drawn)\n"
    "  -o OUT.png        the picture\n"
    "  -o OUT.html       a page that plays every row in the browser (three.js inlined; orbit, pause, scrub,\n"
    "                    speed; click a wire for its name, kind and tension curve)\n";

int toWholeNumber(const char* option, double value) {
    if (value != std::floor(value) || std::abs(value) > 1e9)
        throw Error(std::string(option) + " expects a whole number, got " + std::to_string(value));
    return static_cast<int>(value);
}

}  // namespace

int runRender(const std::vector<std::string>& args) {
    std::string modelPath, motionPath, tensionsPath, outputPath, view = "both";
    std::optional<int> frame, strip;
    std::optional<double> time;
    double startTime = -std::numeric_limits<double>::infinity(), finalTime = std::numeric_limits<double>::infinity();
    PictureOptions options;
    ArgumentReader reader(args, kUsage);
    while (reader.next()) {
        if (reader.is("--motion")) motionPath = reader.value();
        else if (reader.is("--tensions")) tensionsPath = reader.value();
        else if (reader.is("--frame")) frame = toWholeNumber("--frame", reader.number());
        else if (reader.is("--time")) time = reader.number();
        else if (reader.is("--strip")) strip = toWholeNumber("--strip", reader.number());
        else if (reader.is("--start")) startTime = reader.number();
        else if (reader.is("--end")) finalTime = reader.number();
        else if (reader.is("--view")) view = reader.value();
        else if (reader.is("--height")) options.panelHeight = toWholeNumber("--height", reader.number());
        else if (reader.is("--max-tension")) options.maxTension = reader.number();
        else if (reader.is("--max-strain")) options.maxStrain = reader.number();
        else if (reader.is("-o", "--output")) outputPath = reader.value();
        else reader.takePositional({&modelPath});
    }
    if (reader.helpShown()) return 0;
    if (modelPath.empty() || outputPath.empty()) return reader.failWithUsage();
    if (int(frame.has_value()) + int(time.has_value()) + int(strip.has_value()) > 1)
        throw Error("give at most one of --frame, --time and --strip");
    if (view == "front") options.views = {ViewDirection::Front};
    else if (view == "side") options.views = {ViewDirection::Side};
    else if (view != "both") throw Error("unknown view '" + view + "' (expected front, side or both)");
    const std::string extension = std::filesystem::path(outputPath).extension().string();
    if (extension != ".png" && extension != ".html")
        throw Error("-o " + outputPath + ": the output must be a .png or .html file");
    const bool html = extension == ".html";
    if (html && (frame || time || strip)) throw Error("--frame, --time and --strip are for pictures; the page plays every row");

    const Model model = loadModel(modelPath, [](const std::string& line) { std::printf("%s\n", line.c_str()); });
    std::optional<PoseTable> motion;
    std::optional<TensionTable> tensions;
    if (!motionPath.empty()) motion = readPoseTable(model, motionPath);
    if (!tensionsPath.empty()) tensions = readTensionTable(model, tensionsPath);
    // Rows index the motion, else the tensions table; the default pose alone has one frame.
    const Eigen::VectorXd times = motion ? motion->times : tensions ? tensions->times : Eigen::VectorXd::Zero(1);
    const std::string rowsFile = motion ? motionPath : tensions ? tensionsPath : "the default pose";
    // The strip and the page draw the rows in [--start, --end] (a tensions table of part of a motion).
    std::vector<int> inRange;
    for (Eigen::Index i = 0; i < times.size(); ++i)
        if (times[i] >= startTime && times[i] <= finalTime) inRange.push_back(static_cast<int>(i));
    if (inRange.empty())
        throw Error(rowsFile + ": no row in the time range [" + std::to_string(startTime) + ", " +
                    std::to_string(finalTime) + "] s");
    const Eigen::VectorXd rangeTimes = times(inRange);
    std::vector<int> rows = {0};
    if (frame) rows = {findFrame(times, *frame, rowsFile)};
    if (time) rows = {findFrameAtTime(times, *time, rowsFile)};
    if (strip || html) {
        rows.clear();
        for (int k : selectStripFrames(rangeTimes, strip ? *strip : static_cast<int>(rangeTimes.size()), rowsFile))
            rows.push_back(inRange[static_cast<std::size_t>(k)]);
    }

    const std::vector<BodyFrame> frames =
        calcBodyFrames(model, motion ? &*motion : nullptr, tensions ? &*tensions : nullptr, rows);
    options.title = model.getName() + (tensions ? ": wire tensions from " + std::filesystem::path(tensionsPath).filename().string()
                                                : ": wire tensions from the force laws");
    const std::filesystem::path parent = std::filesystem::path(outputPath).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    if (html) {
        writeHtmlViewer(model, frames, HtmlViewerOptions{options.title}, outputPath);
        std::printf("%s: %zu frames, %d wires, %.1f MB\n", outputPath.c_str(), frames.size(), model.getNumWires(),
                    static_cast<double>(std::filesystem::file_size(outputPath)) / 1e6);
        return 0;
    }
    const PictureLayout layout = layoutPicture(model, frames, options);
    writePicturePng(model, frames, layout, options, outputPath);
    std::printf("%s: %zu frame%s, %d wires, %d x %d px; tension scale 0 to %.4g N", outputPath.c_str(), frames.size(),
                frames.size() == 1 ? "" : "s", model.getNumWires(), layout.width, layout.height, layout.scale.maxTension);
    if (layout.scale.maxStrain > 0) std::printf(", ligament strain 0 to %.4g", layout.scale.maxStrain);
    std::printf("\n");
    return 0;
}

}  // namespace sinew::cli
