#pragma once
// Pictures of the body with its wires coloured by tension: front and side orthographic views of one or more
// frames, a colour bar per shaded quantity and a legend of the wire kinds, drawn with cairo and written as
// PNG (docs/rendering.md). Headless: no display, no GPU.
#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "sinew/core/model.hpp"
#include "sinew/render/body_scene.hpp"
#include "sinew/render/colour_map.hpp"

namespace sinew {

// Front: the viewer on the model's +x side (OpenSim's and MuJoCo's models face +x); side: on the body's
// right (x cross up). Up is against gravity (+y for a model without gravity).
enum class ViewDirection { Front, Side };
const char* toString(ViewDirection view);

// An orthographic projection onto the picture, pixels with y down.
struct OrthographicCamera {
    Eigen::Vector3d right_G = Eigen::Vector3d::UnitX();   // unit, the picture's +x in ground
    Eigen::Vector3d up_G = Eigen::Vector3d::UnitY();      // unit, the picture's up in ground
    Eigen::Vector3d toward_G = Eigen::Vector3d::UnitZ();  // unit, from the scene to the viewer
    Eigen::Vector3d centre_G = Eigen::Vector3d::Zero();   // m, the point drawn at centre_px
    Eigen::Vector2d centre_px = Eigen::Vector2d::Zero();  // px
    double pixelsPerMetre = 1;

    Eigen::Vector2d project(const Eigen::Vector3d& p_G) const;  // px
    double calcDepth(const Eigen::Vector3d& p_G) const { return toward_G.dot(p_G); }  // m, larger is nearer
};

// The camera's axes for a view of the model (centre and scale left to the layout).
OrthographicCamera makeCamera(const Model& model, ViewDirection view);

struct PictureOptions {
    int panelHeight = 640;  // px, one view of one frame
    std::vector<ViewDirection> views = {ViewDirection::Front, ViewDirection::Side};
    // The tension (N) and ligament strain at the top of their colour scales; NaN: the largest in the frames.
    double maxTension = std::numeric_limits<double>::quiet_NaN();
    double maxStrain = std::numeric_limits<double>::quiet_NaN();
    std::string title;  // drawn above the panels; empty: none
};

// The colour scales: tension 0 .. maxTension on viridis, ligament strain 0 .. maxStrain on plasma (a slack
// ligament's negative strain at the low end).
struct ShadingScale {
    double maxTension = 1;  // N, > 0
    double maxStrain = 0;   // > 0 where some wire is shaded by strain, else 0
};
ShadingScale calcShadingScale(const Model& model, const std::vector<BodyFrame>& frames, const PictureOptions& options);
Rgb calcWireColour(const Model& model, const ShadingScale& scale, int w, const SceneWire& wire);

struct PicturePanel {
    int frame = 0;  // index into the frames drawn
    ViewDirection view = ViewDirection::Front;
    OrthographicCamera camera;
    double x = 0, y = 0, width = 0, height = 0;  // px
};

// A vertical bar, the map's low end at the bottom (value 0) and its high end at the top (value `top`).
struct ColourBar {
    ColourMap map = ColourMap::Viridis;
    std::string label;
    double top = 1;
    double x = 0, y = 0, width = 0, height = 0;  // px
};

// Where everything goes: one frame's views side by side, or several frames side by side with a row per view;
// the bars and the legend to the right. Every frame of a view has the same camera, so motion shows.
struct PictureLayout {
    int width = 0, height = 0;  // px
    ShadingScale scale;
    std::vector<PicturePanel> panels;
    std::vector<ColourBar> colourBars;
    double legendX = 0, legendY = 0;  // px, the legend's top left
};
PictureLayout layoutPicture(const Model& model, const std::vector<BodyFrame>& frames, const PictureOptions& options);

// Writes the PNG at `path` as an OutputFileSet of one (io/atomic_file.hpp), so a failed write leaves no
// partial picture; throws sinew::Error naming the path and cairo's reason.
void writePicturePng(const Model& model, const std::vector<BodyFrame>& frames, const PictureLayout& layout,
                     const PictureOptions& options, const std::string& path);

}  // namespace sinew
