#include "sinew/render/picture.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "cairo_canvas.hpp"
#include "sinew/core/error.hpp"

namespace sinew {
namespace {

using render_detail::drawText;
using render_detail::setColour;
using render_detail::TextAlign;

constexpr double kMargin = 16;        // px around each panel's drawing
constexpr double kCaptionHeight = 22;  // px, a panel's caption above its drawing
constexpr double kTitleHeight = 30;   // px
constexpr double kSideWidth = 190;    // px, the colour bars and the legend
constexpr double kBarHeight = 220;    // px
constexpr Rgb kBone{0.89, 0.87, 0.81}, kBoneEdge{0.50, 0.48, 0.44}, kInk{0.15, 0.15, 0.15};

// How a wire kind is drawn: width (px) and dash pattern (px on, px off; empty: solid).
struct KindStyle {
    double width;
    std::vector<double> dashes;
};
KindStyle getKindStyle(WireKind kind) {
    switch (kind) {
        case WireKind::Muscle: return {2.0, {}};
        case WireKind::Tendon: return {1.3, {}};
        case WireKind::Ligament: return {1.6, {5, 2.5}};
        case WireKind::Cartilage: return {2.6, {1.5, 1.5}};
    }
    return {2.0, {}};
}
constexpr WireKind kKinds[] = {WireKind::Muscle, WireKind::Tendon, WireKind::Ligament, WireKind::Cartilage};

std::string formatValue(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", value);
    return text;
}

// A drawable at its depth: a capsule (index into bones) or a wire segment (wire, first point).
struct Item {
    double depth;
    int bone, wire, point;
};

void drawPanel(cairo_t* cr, const Model& model, const BodyFrame& frame, const PicturePanel& panel,
               const ShadingScale& scale) {
    const OrthographicCamera& camera = panel.camera;
    std::vector<Item> items;
    for (std::size_t b = 0; b < frame.bones.size(); ++b) {
        const SceneCapsule& bone = frame.bones[b];
        items.push_back({camera.calcDepth(0.5 * (bone.a_G + bone.b_G)), static_cast<int>(b), -1, 0});
    }
    for (std::size_t w = 0; w < frame.wires.size(); ++w) {
        const std::vector<Eigen::Vector3d>& path = frame.wires[w].path_G;
        for (std::size_t i = 0; i + 1 < path.size(); ++i)
            items.push_back({camera.calcDepth(0.5 * (path[i] + path[i + 1])), -1, static_cast<int>(w), static_cast<int>(i)});
    }
    // Painter's order: the farthest first.
    std::stable_sort(items.begin(), items.end(), [](const Item& a, const Item& b) { return a.depth < b.depth; });

    cairo_save(cr);
    cairo_rectangle(cr, panel.x, panel.y, panel.width, panel.height);
    cairo_clip(cr);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    for (const Item& item : items) {
        if (item.bone >= 0) {
            const SceneCapsule& bone = frame.bones[static_cast<std::size_t>(item.bone)];
            const Eigen::Vector2d a = camera.project(bone.a_G), b = camera.project(bone.b_G);
            const double width = std::max(2 * bone.radius * camera.pixelsPerMetre, 2.0);
            cairo_set_dash(cr, nullptr, 0, 0);
            for (int pass = 0; pass < 2; ++pass) {
                setColour(cr, pass == 0 ? kBoneEdge : kBone);
                cairo_set_line_width(cr, pass == 0 ? width + 1.5 : width);
                cairo_move_to(cr, a.x(), a.y());
                cairo_line_to(cr, b.x(), b.y());
                cairo_stroke(cr);
            }
            continue;
        }
        const SceneWire& wire = frame.wires[static_cast<std::size_t>(item.wire)];
        const KindStyle style = getKindStyle(model.getWire(item.wire).kind);
        const Eigen::Vector2d a = camera.project(wire.path_G[static_cast<std::size_t>(item.point)]);
        const Eigen::Vector2d b = camera.project(wire.path_G[static_cast<std::size_t>(item.point) + 1]);
        setColour(cr, calcWireColour(model, scale, item.wire, wire));
        cairo_set_line_width(cr, style.width);
        cairo_set_dash(cr, style.dashes.data(), static_cast<int>(style.dashes.size()), 0);
        cairo_move_to(cr, a.x(), a.y());
        cairo_line_to(cr, b.x(), b.y());
        cairo_stroke(cr);
    }
    cairo_restore(cr);
    setColour(cr, kInk);
    char caption[96];
    std::snprintf(caption, sizeof caption, "%s, t = %.3f s", toString(panel.view), frame.time);
    drawText(cr, panel.x + panel.width / 2, panel.y + 15, caption, 13, TextAlign::Centre);
}

void drawColourBar(cairo_t* cr, const ColourBar& bar) {
    // One pixel row per colour, t at the row's centre, the low end at the bottom.
    cairo_save(cr);
    cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
    const int rows = static_cast<int>(bar.height);
    for (int i = 0; i < rows; ++i) {
        setColour(cr, calcColour(bar.map, (i + 0.5) / rows));
        cairo_rectangle(cr, bar.x, bar.y + bar.height - i - 1, bar.width, 1);
        cairo_fill(cr);
    }
    cairo_restore(cr);
    setColour(cr, kInk);
    cairo_set_line_width(cr, 1);
    cairo_set_dash(cr, nullptr, 0, 0);
    cairo_rectangle(cr, bar.x - 0.5, bar.y - 0.5, bar.width + 1, bar.height + 1);
    cairo_stroke(cr);
    drawText(cr, bar.x, bar.y - 10, bar.label, 13);
    for (int k = 0; k <= 4; ++k) {
        const double y = bar.y + bar.height * (1 - k / 4.0);
        cairo_move_to(cr, bar.x + bar.width, y);
        cairo_line_to(cr, bar.x + bar.width + 5, y);
        cairo_stroke(cr);
        drawText(cr, bar.x + bar.width + 8, y + 4, formatValue(bar.top * k / 4.0), 11);
    }
}

void drawLegend(cairo_t* cr, const Model& model, double x, double y) {
    setColour(cr, kInk);
    drawText(cr, x, y, "wires", 13);
    y += 8;
    for (const WireKind kind : kKinds) {
        int count = 0;
        for (const Wire& wire : model.getWires()) count += wire.kind == kind;
        if (count == 0) continue;
        y += 20;
        const KindStyle style = getKindStyle(kind);
        cairo_set_line_width(cr, style.width);
        cairo_set_dash(cr, style.dashes.data(), static_cast<int>(style.dashes.size()), 0);
        cairo_move_to(cr, x, y - 4);
        cairo_line_to(cr, x + 36, y - 4);
        cairo_stroke(cr);
        drawText(cr, x + 44, y, std::string(toString(kind)) + " (" + std::to_string(count) + ")", 12);
    }
    cairo_set_dash(cr, nullptr, 0, 0);
}

// Projected extent of a frame in a camera's picture axes, about the camera's centre (m).
void extendBounds(const OrthographicCamera& camera, const BodyFrame& frame, Eigen::Vector2d& low, Eigen::Vector2d& high) {
    auto add = [&](const Eigen::Vector3d& p_G, double radius) {
        const Eigen::Vector2d p(camera.right_G.dot(p_G), camera.up_G.dot(p_G));
        low = low.cwiseMin(p - Eigen::Vector2d::Constant(radius));
        high = high.cwiseMax(p + Eigen::Vector2d::Constant(radius));
    };
    for (const SceneCapsule& bone : frame.bones) {
        add(bone.a_G, bone.radius);
        add(bone.b_G, bone.radius);
    }
    for (const SceneWire& wire : frame.wires)
        for (const Eigen::Vector3d& p : wire.path_G) add(p, 0);
}

}  // namespace

const char* toString(ViewDirection view) { return view == ViewDirection::Front ? "front" : "side"; }

Eigen::Vector2d OrthographicCamera::project(const Eigen::Vector3d& p_G) const {
    const Eigen::Vector3d d = p_G - centre_G;
    return {centre_px.x() + pixelsPerMetre * right_G.dot(d), centre_px.y() - pixelsPerMetre * up_G.dot(d)};
}

OrthographicCamera makeCamera(const Model& model, ViewDirection view) {
    const Eigen::Vector3d& g = model.getGravity();
    const Eigen::Vector3d up = g.norm() > 0 ? Eigen::Vector3d(-g.normalized()) : Eigen::Vector3d::UnitY();
    // The body's forward: +x made horizontal (+z for a model whose gravity is along x).
    Eigen::Vector3d forward = Eigen::Vector3d::UnitX() - up.x() * up;
    if (forward.norm() < 1e-6) forward = Eigen::Vector3d::UnitZ() - up.z() * up;
    forward.normalize();
    OrthographicCamera camera;
    camera.up_G = up;
    camera.toward_G = view == ViewDirection::Front ? forward : Eigen::Vector3d(forward.cross(up));
    camera.right_G = up.cross(camera.toward_G);
    return camera;
}

ShadingScale calcShadingScale(const Model& model, const std::vector<BodyFrame>& frames, const PictureOptions& options) {
    double maxTension = 0, maxStrain = 0;
    bool anyStrain = false;
    for (const BodyFrame& frame : frames)
        for (int w = 0; w < model.getNumWires(); ++w) {
            const SceneWire& wire = frame.wires[static_cast<std::size_t>(w)];
            if (isShadedByStrain(model.getWire(w))) {
                anyStrain = true;
                maxStrain = std::max(maxStrain, wire.strain);
            } else {
                maxTension = std::max(maxTension, wire.tension);
            }
        }
    ShadingScale scale;
    // A picture where every wire is slack still needs a scale; 1 N and 1% strain are as good as any.
    scale.maxTension = std::isnan(options.maxTension) ? (maxTension > 0 ? maxTension : 1.0) : options.maxTension;
    if (anyStrain) scale.maxStrain = std::isnan(options.maxStrain) ? (maxStrain > 0 ? maxStrain : 0.01) : options.maxStrain;
    if (!(scale.maxTension > 0) || (anyStrain && !(scale.maxStrain > 0)))
        throw Error("the colour scale's top must be > 0 (got tension " + formatValue(scale.maxTension) + " N, strain " +
                    formatValue(scale.maxStrain) + ")");
    return scale;
}

Rgb calcWireColour(const Model& model, const ShadingScale& scale, int w, const SceneWire& wire) {
    if (isShadedByStrain(model.getWire(w))) return calcColour(ColourMap::Plasma, wire.strain / scale.maxStrain);
    return calcColour(ColourMap::Viridis, wire.tension / scale.maxTension);
}

PictureLayout layoutPicture(const Model& model, const std::vector<BodyFrame>& frames, const PictureOptions& options) {
    if (frames.empty() || options.views.empty()) throw Error("a picture needs at least one frame and one view");
    if (options.panelHeight < 100) throw Error("the panel height must be at least 100 px");
    PictureLayout layout;
    layout.scale = calcShadingScale(model, frames, options);
    const std::size_t numViews = options.views.size();
    std::vector<OrthographicCamera> cameras;
    std::vector<Eigen::Vector2d> lows, highs;
    double scale = std::numeric_limits<double>::infinity();
    const double drawingHeight = options.panelHeight - kCaptionHeight - 2 * kMargin;
    for (const ViewDirection view : options.views) {
        cameras.push_back(makeCamera(model, view));
        Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), high = -low;
        for (const BodyFrame& frame : frames) extendBounds(cameras.back(), frame, low, high);
        lows.push_back(low);
        highs.push_back(high);
        scale = std::min(scale, drawingHeight / std::max(high.y() - low.y(), 1e-3));
    }
    // One scale for every panel, so that sizes compare; each view as wide as its extent needs.
    const bool strip = frames.size() > 1;
    const double top = options.title.empty() ? 0 : kTitleHeight;
    std::vector<double> widths;
    for (std::size_t v = 0; v < numViews; ++v)
        widths.push_back(std::max((highs[v].x() - lows[v].x()) * scale, 60.0) + 2 * kMargin);
    double x = 0, maxRowWidth = 0;
    for (std::size_t f = 0; f < frames.size(); ++f)
        for (std::size_t v = 0; v < numViews; ++v) {
            PicturePanel panel;
            panel.frame = static_cast<int>(f);
            panel.view = options.views[v];
            panel.width = strip ? *std::max_element(widths.begin(), widths.end()) : widths[v];
            panel.height = options.panelHeight;
            panel.x = strip ? static_cast<double>(f) * panel.width : x;
            panel.y = top + (strip ? static_cast<double>(v) * options.panelHeight : 0);
            x += panel.width;
            panel.camera = cameras[v];
            panel.camera.pixelsPerMetre = scale;
            const Eigen::Vector2d mid = 0.5 * (lows[v] + highs[v]);
            panel.camera.centre_G = mid.x() * cameras[v].right_G + mid.y() * cameras[v].up_G;
            panel.camera.centre_px = {panel.x + panel.width / 2, panel.y + kCaptionHeight + kMargin + drawingHeight / 2};
            maxRowWidth = std::max(maxRowWidth, panel.x + panel.width);
            layout.panels.push_back(panel);
        }
    const double sideX = std::round(maxRowWidth + 10);
    double barY = std::round(top + 40);
    layout.colourBars.push_back({ColourMap::Viridis, "tension (N)", layout.scale.maxTension, sideX, barY, 22, kBarHeight});
    if (layout.scale.maxStrain > 0) {
        barY += kBarHeight + 60;
        layout.colourBars.push_back({ColourMap::Plasma, "ligament strain", layout.scale.maxStrain, sideX, barY, 22, kBarHeight});
    }
    layout.legendX = sideX;
    layout.legendY = barY + kBarHeight + 40;
    layout.width = static_cast<int>(sideX + kSideWidth);
    const double panelsBottom = top + static_cast<double>(strip ? numViews : 1) * options.panelHeight;
    layout.height = static_cast<int>(std::ceil(std::max(panelsBottom, layout.legendY + 100)));
    return layout;
}

void writePicturePng(const Model& model, const std::vector<BodyFrame>& frames, const PictureLayout& layout,
                     const PictureOptions& options, const std::string& path) {
    render_detail::Canvas canvas(layout.width, layout.height, path);
    cairo_t* cr = canvas.get();
    if (!options.title.empty()) {
        setColour(cr, kInk);
        drawText(cr, 12, 21, options.title, 16);
    }
    for (const PicturePanel& panel : layout.panels)
        drawPanel(cr, model, frames[static_cast<std::size_t>(panel.frame)], panel, layout.scale);
    for (const ColourBar& bar : layout.colourBars) drawColourBar(cr, bar);
    drawLegend(cr, model, layout.legendX, layout.legendY);
    canvas.writePng(path);
}

}  // namespace sinew
