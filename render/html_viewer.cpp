#include "sinew/render/html_viewer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "html_viewer_page.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/atomic_file.hpp"
#include "sinew/render/colour_map.hpp"
#include "sinew/render/picture.hpp"

namespace sinew {
namespace {

// Samples of each colour map handed to the page, which interpolates between them as calcColour does.
constexpr int kMapSamples = 64;

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot read three.js (Debian's libjs-three installs it; scripts/setup.sh)");
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// Inlined text must not end the <script> element it sits in.
std::string escapeScript(std::string text) {
    for (std::size_t at = text.find("</"); at != std::string::npos; at = text.find("</", at + 3)) text.insert(at + 1, "\\");
    return text;
}

std::string escapeHtml(const std::string& text) {
    std::string out;
    for (const char c : text) {
        if (c == '<') out += "&lt;";
        else if (c == '>') out += "&gt;";
        else if (c == '&') out += "&amp;";
        else out += c;
    }
    return out;
}

template <class T>
std::string encodeBase64(const std::vector<T>& values) {
    static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
    const std::size_t n = values.size() * sizeof(T);
    std::string out;
    out.reserve((n + 2) / 3 * 4);
    for (std::size_t i = 0; i < n; i += 3) {
        const std::uint32_t chunk = (std::uint32_t(bytes[i]) << 16) | (i + 1 < n ? std::uint32_t(bytes[i + 1]) << 8 : 0u) |
                                    (i + 2 < n ? std::uint32_t(bytes[i + 2]) : 0u);
        out += kDigits[(chunk >> 18) & 63];
        out += kDigits[(chunk >> 12) & 63];
        out += i + 1 < n ? kDigits[(chunk >> 6) & 63] : '=';
        out += i + 2 < n ? kDigits[chunk & 63] : '=';
    }
    return out;
}

nlohmann::json sampleMap(ColourMap map) {
    nlohmann::json samples = nlohmann::json::array();
    for (int i = 0; i < kMapSamples; ++i) {
        const Rgb c = calcColour(map, static_cast<double>(i) / (kMapSamples - 1));
        samples.push_back({c.r, c.g, c.b});
    }
    return samples;
}

void replaceOnce(std::string& page, const std::string& marker, const std::string& text) {
    const std::size_t at = page.find(marker);
    if (at == std::string::npos) throw Error("internal: the viewer page has no " + marker);
    page.replace(at, marker.size(), text);
}

}  // namespace

void writeHtmlViewer(const Model& model, const std::vector<BodyFrame>& frames, const HtmlViewerOptions& options,
                     const std::string& path) {
    if (frames.empty()) throw Error(path + ": the viewer needs at least one frame");
    const std::size_t numWires = static_cast<std::size_t>(model.getNumWires()), numBones = frames[0].bones.size();
    // Per frame: bone ends (6 per bone), each wire's number of path points and the points, tensions, strains.
    // The points, most of the page, as 16-bit steps across the motion's bounding box (under 0.05 mm for a
    // 2 m body): half the size of floats.
    Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), high = -low;
    for (const BodyFrame& frame : frames)
        for (const SceneWire& wire : frame.wires)
            for (const Eigen::Vector3d& p : wire.path_G) {
                low = low.cwiseMin(p);
                high = high.cwiseMax(p);
            }
    const double step = std::max((high - low).maxCoeff(), 1e-9) / 65535;
    std::vector<float> bones, tensions, strains;
    std::vector<std::uint16_t> counts, points;
    nlohmann::json times = nlohmann::json::array();
    for (const BodyFrame& frame : frames) {
        if (frame.wires.size() != numWires || frame.bones.size() != numBones)
            throw Error(path + ": the frame at t = " + std::to_string(frame.time) + " s is not of model '" + model.getName() + "'");
        times.push_back(frame.time);
        for (const SceneCapsule& bone : frame.bones)
            for (const Eigen::Vector3d* p : {&bone.a_G, &bone.b_G})
                for (int k = 0; k < 3; ++k) bones.push_back(static_cast<float>((*p)[k]));
        for (const SceneWire& wire : frame.wires) {
            counts.push_back(static_cast<std::uint16_t>(wire.path_G.size()));
            for (const Eigen::Vector3d& p : wire.path_G)
                for (int k = 0; k < 3; ++k) points.push_back(static_cast<std::uint16_t>(std::lround((p[k] - low[k]) / step)));
            tensions.push_back(static_cast<float>(wire.tension));
            strains.push_back(static_cast<float>(wire.strain));
        }
    }
    const ShadingScale scale = calcShadingScale(model, frames, PictureOptions{});
    const OrthographicCamera front = makeCamera(model, ViewDirection::Front);
    nlohmann::json data;
    data["title"] = options.title.empty() ? model.getName() : options.title;
    data["up"] = {front.up_G.x(), front.up_G.y(), front.up_G.z()};
    data["toward"] = {front.toward_G.x(), front.toward_G.y(), front.toward_G.z()};
    data["times"] = times;
    data["wires"] = nlohmann::json::array();
    for (int w = 0; w < model.getNumWires(); ++w) {
        const Wire& wire = model.getWire(w);
        data["wires"].push_back({{"name", wire.name}, {"kind", toString(wire.kind)}, {"byStrain", isShadedByStrain(wire)}});
    }
    data["boneRadius"] = nlohmann::json::array();
    for (const SceneCapsule& bone : frames[0].bones) data["boneRadius"].push_back(bone.radius);
    data["bones"] = encodeBase64(bones);
    data["counts"] = encodeBase64(counts);
    data["points"] = encodeBase64(points);
    data["pointsOrigin"] = {low.x(), low.y(), low.z()};
    data["pointsStep"] = step;
    data["tensions"] = encodeBase64(tensions);
    data["strains"] = encodeBase64(strains);
    data["maxTension"] = scale.maxTension;
    data["maxStrain"] = scale.maxStrain;
    data["viridis"] = sampleMap(ColourMap::Viridis);
    data["plasma"] = sampleMap(ColourMap::Plasma);

    std::string page = render_detail::kViewerPage;
    // The markers from the page's last to its first, so that no inserted text (which may hold anything that
    // looks like a marker) comes before a marker still to be found.
    replaceOnce(page, "@@DATA@@", escapeScript(data.dump()));
    replaceOnce(page, "@@ORBIT@@", escapeScript(readText(options.threeJsDir + "/examples/js/controls/OrbitControls.js")));
    replaceOnce(page, "@@THREE@@", escapeScript(readText(options.threeJsDir + "/three.min.js")));
    replaceOnce(page, "@@TITLE@@", escapeHtml(data["title"].get<std::string>()));
    writeFileAtomically(path, page);
}

}  // namespace sinew
