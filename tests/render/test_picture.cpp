// Pictures read back from their PNG files: the size the layout gives, not blank, the colour bars running
// from their map's low end to its high end (against matplotlib's values), and wires coloured by tension
// rank: on a model with one slack and one highly loaded wire, the pixels at each wire's midpoint
// (projected with the panel's camera) show the two ends of viridis.
#include <gtest/gtest.h>

#include <filesystem>

#include "png_pixels.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/io/model_loading.hpp"
#include "sinew/render/body_motion.hpp"
#include "sinew/render/picture.hpp"
#include "two_wire_model.hpp"

namespace sinew {
namespace {

const Rgb kViridisLow{0.267004, 0.004874, 0.329415}, kViridisHigh{0.993248, 0.906157, 0.143936};
const Rgb kPlasmaLow{0.050383, 0.029803, 0.527975}, kPlasmaHigh{0.940015, 0.975158, 0.131326};
// 8-bit channels, and the bar's bottom and top rows half a row inside its ends.
constexpr double kColourTolerance = 0.012;

std::string outputPath(const std::string& name) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "sinew_test_picture";
    std::filesystem::create_directories(dir);
    return (dir / name).string();
}

struct Rendered {
    PictureLayout layout;
    std::vector<BodyFrame> frames;
    test::PngPixels pixels;
};

Rendered render(const Model& model, const std::vector<BodyFrame>& frames, const std::string& name,
                const PictureOptions& options = {}) {
    const PictureLayout layout = layoutPicture(model, frames, options);
    const std::string path = outputPath(name);
    writePicturePng(model, frames, layout, options, path);
    return {layout, frames, test::PngPixels(path)};
}

// The picture's own size, some drawing in every panel, and every colour bar's ends.
void expectWholePicture(const Rendered& r) {
    EXPECT_EQ(r.pixels.width, r.layout.width);
    EXPECT_EQ(r.pixels.height, r.layout.height);
    for (const PicturePanel& panel : r.layout.panels) {
        int inked = 0, total = 0;
        for (int y = static_cast<int>(panel.y) + 30; y < static_cast<int>(panel.y + panel.height); ++y)
            for (int x = static_cast<int>(panel.x); x < static_cast<int>(panel.x + panel.width); ++x, ++total)
                inked += !r.pixels.isWhite(x, y);
        EXPECT_GT(inked, total / 200) << toString(panel.view) << " panel of frame " << panel.frame << " is blank";
    }
    ASSERT_FALSE(r.layout.colourBars.empty());
    for (const ColourBar& bar : r.layout.colourBars) {
        const bool viridis = bar.map == ColourMap::Viridis;
        const double x = bar.x + bar.width / 2;
        EXPECT_LT(r.pixels.findNearestColour(x, bar.y + bar.height - 0.5, viridis ? kViridisLow : kPlasmaLow, 0),
                  kColourTolerance) << bar.label;
        EXPECT_LT(r.pixels.findNearestColour(x, bar.y + 0.5, viridis ? kViridisHigh : kPlasmaHigh, 0), kColourTolerance)
            << bar.label;
    }
}

Eigen::Vector3d calcMidpoint(const std::vector<Eigen::Vector3d>& path) {
    double length = 0;
    for (std::size_t i = 0; i + 1 < path.size(); ++i) length += (path[i + 1] - path[i]).norm();
    double left = length / 2;
    for (std::size_t i = 0; i + 1 < path.size(); ++i) {
        const double segment = (path[i + 1] - path[i]).norm();
        if (left <= segment) return path[i] + (left / segment) * (path[i + 1] - path[i]);
        left -= segment;
    }
    return path.back();
}

TEST(Picture, SlackAndLoadedWiresAtTheEndsOfTheScale) {
    const Model model = test::makeTwoWireModel();
    const std::vector<BodyFrame> frames = calcBodyFrames(model, nullptr, nullptr, {0});
    // The force law by hand: k (l - l0) at rest, 0 when shorter than the rest length.
    EXPECT_EQ(frames[0].wires[0].tension, 0.0);
    EXPECT_NEAR(frames[0].wires[1].tension, 1000 * (0.5 - 0.25), 1e-9);
    const Rendered r = render(model, frames, "two_wires.png");
    expectWholePicture(r);
    ASSERT_EQ(r.layout.panels.size(), 2u);
    for (const PicturePanel& panel : r.layout.panels) {
        const Eigen::Vector2d slack = panel.camera.project(calcMidpoint(frames[0].wires[0].path_G));
        const Eigen::Vector2d loaded = panel.camera.project(calcMidpoint(frames[0].wires[1].path_G));
        EXPECT_GT((slack - loaded).norm(), 20.0);
        EXPECT_LT(r.pixels.findNearestColour(slack.x(), slack.y(), kViridisLow, 1), kColourTolerance) << toString(panel.view);
        EXPECT_LT(r.pixels.findNearestColour(loaded.x(), loaded.y(), kViridisHigh, 1), kColourTolerance) << toString(panel.view);
        EXPECT_GT(r.pixels.findNearestColour(loaded.x(), loaded.y(), kViridisLow, 1), 0.5) << toString(panel.view);
    }
}

TEST(Picture, GivenScaleTopPutsTheLoadedWireMidway) {
    const Model model = test::makeTwoWireModel();
    PictureOptions options;
    options.maxTension = 500;
    options.views = {ViewDirection::Front};
    const Rendered r = render(model, calcBodyFrames(model, nullptr, nullptr, {0}), "two_wires_scale.png", options);
    const PicturePanel& panel = r.layout.panels.at(0);
    const Eigen::Vector2d loaded = panel.camera.project(calcMidpoint(r.frames[0].wires[1].path_G));
    // 250 N of 500 N: matplotlib's viridis at 0.5 lies between its entries 127 and 128.
    EXPECT_LT(r.pixels.findNearestColour(loaded.x(), loaded.y(), {0.128729, 0.563265, 0.551229}, 1), kColourTolerance);
}

TEST(Picture, Arm26) {
    const Model model = readModelFile(SINEW_SOURCE_DIR "/models/arm26.yaml");
    expectWholePicture(render(model, calcBodyFrames(model, nullptr, nullptr, {0}), "arm26.png"));
}

TEST(Picture, ImportedOpenSimModel) {
    const std::string path = SINEW_SHARED_DIR "/data/opensim-models/Models/Gait2354_Simbody/gait2354_simbody.osim";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent (developer data)";
    const Model model = loadModel(path, {});
    expectWholePicture(render(model, calcBodyFrames(model, nullptr, nullptr, {0}), "gait2354.png"));
}

TEST(Picture, WholeBodyWithLigamentStrain) {
    const Model model = readModelFile(SINEW_SOURCE_DIR "/models/whole_body/whole_body.yaml");
    const Rendered r = render(model, calcBodyFrames(model, nullptr, nullptr, {0}), "whole_body.png");
    expectWholePicture(r);
    ASSERT_EQ(r.layout.colourBars.size(), 2u);
    EXPECT_EQ(r.layout.colourBars[1].map, ColourMap::Plasma);
}

// A strip of OpenSim's arm26 IK motion: rows 0, 60 and 120 of its 121, a row of panels per view.
TEST(Picture, StripOfAMotion) {
    const std::string osim = SINEW_SHARED_DIR "/data/opensim/arm26/arm26.osim";
    const std::string mot = SINEW_SHARED_DIR "/data/opensim/arm26/arm26_InverseKinematics.mot";
    if (!std::filesystem::exists(osim)) GTEST_SKIP() << osim << " is absent (developer data)";
    const Model model = loadModel(osim, {});
    const PoseTable motion = readPoseTable(model, mot);
    const std::vector<int> rows = selectStripFrames(motion.times, 3, mot);
    EXPECT_EQ(rows, (std::vector<int>{0, 60, 120}));
    const Rendered r = render(model, calcBodyFrames(model, &motion, nullptr, rows), "arm26_strip.png");
    expectWholePicture(r);
    ASSERT_EQ(r.layout.panels.size(), 6u);
    for (const PicturePanel& panel : r.layout.panels)
        EXPECT_EQ(r.frames[static_cast<std::size_t>(panel.frame)].time, motion.times[rows[static_cast<std::size_t>(panel.frame)]]);
    // The same camera for every frame of a view, so that the motion shows.
    EXPECT_EQ(r.layout.panels[0].camera.pixelsPerMetre, r.layout.panels[4].camera.pixelsPerMetre);
    EXPECT_LT((r.layout.panels[0].camera.centre_G - r.layout.panels[4].camera.centre_G).norm(), 1e-15);
}

}  // namespace
}  // namespace sinew
