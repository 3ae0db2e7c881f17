// The browser viewer: the page holds everything it needs (three.js inlined, no external script) and its data
// decode, independently of the writer, to the frames it was given; and in headless Chromium, driven through
// chromedriver by tests/render/drive_viewer.py, it plays, pauses, scrubs, picks a wire by a click, logs no
// error, and its screenshot is not blank and shows the picked wire in the pick colour.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "png_pixels.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/render/body_motion.hpp"
#include "sinew/render/html_viewer.hpp"
#include "two_wire_model.hpp"

namespace sinew {
namespace {

std::string testPath(const std::string& name) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "sinew_test_html_viewer";
    std::filesystem::create_directories(dir);
    return (dir / name).string();
}

std::string readText(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

std::vector<unsigned char> decodeBase64(const std::string& text) {
    std::vector<unsigned char> bytes;
    unsigned value = 0;
    int bits = 0;
    for (const char c : text) {
        const std::string digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        const std::size_t d = digits.find(c);
        if (d == std::string::npos) break;  // '=' padding
        value = (value << 6) | static_cast<unsigned>(d);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            bytes.push_back(static_cast<unsigned char>((value >> bits) & 0xff));
        }
    }
    return bytes;
}

// The two-wire model swinging its hinge from 0 to 1 rad over 1 s, 41 frames.
std::vector<BodyFrame> makeSwing(const Model& model) {
    StorageTable table{"swing", false, {"hinge"}, {}, {}};
    for (int i = 0; i <= 40; ++i) {
        table.times.push_back(i / 40.0);
        table.rows.push_back({i / 40.0});
    }
    const std::string path = testPath("swing.sto");
    writeStorageFile(table, path);
    const PoseTable motion = readPoseTable(model, path);
    return calcBodyFrames(model, &motion, nullptr, selectStripFrames(motion.times, 41, path));
}

TEST(HtmlViewer, PageIsSelfContainedAndHoldsTheFrames) {
    const Model model = test::makeTwoWireModel();
    const std::vector<BodyFrame> frames = makeSwing(model);
    const std::string path = testPath("swing.html");
    writeHtmlViewer(model, frames, {}, path);
    const std::string page = readText(path);
    EXPECT_EQ(page.find("<script src"), std::string::npos);
    EXPECT_NE(page.find("REVISION=\"111\""), std::string::npos);  // Debian's three.js, inlined
    EXPECT_NE(page.find("OrbitControls"), std::string::npos);
    for (const char* marker : {"@@TITLE@@", "@@THREE@@", "@@ORBIT@@", "@@DATA@@"})
        EXPECT_EQ(page.find(marker), std::string::npos) << marker;

    const std::string open = "<script type=\"application/json\" id=\"sinew-data\">";
    const std::size_t begin = page.find(open) + open.size();
    std::string json = page.substr(begin, page.find("</script>", begin) - begin);
    const nlohmann::json data = nlohmann::json::parse(json);
    ASSERT_EQ(data["times"].size(), frames.size());
    EXPECT_EQ(data["wires"][1]["name"], "loaded");
    const std::vector<unsigned char> counts = decodeBase64(data["counts"]), points = decodeBase64(data["points"]);
    const std::vector<unsigned char> tensions = decodeBase64(data["tensions"]);
    ASSERT_EQ(counts.size(), 2 * 2 * frames.size());  // uint16 per wire per frame
    std::size_t at = 0;
    for (std::size_t f = 0; f < frames.size(); ++f)
        for (std::size_t w = 0; w < 2; ++w) {
            const SceneWire& wire = frames[f].wires[w];
            std::uint16_t count = 0;
            std::memcpy(&count, &counts[2 * (2 * f + w)], 2);
            ASSERT_EQ(count, wire.path_G.size());
            float tension = 0;
            std::memcpy(&tension, &tensions[4 * (2 * f + w)], 4);
            EXPECT_NEAR(tension, wire.tension, 1e-4 * (1 + wire.tension));
            for (const Eigen::Vector3d& p : wire.path_G)
                for (int k = 0; k < 3; ++k, ++at) {
                    std::uint16_t steps = 0;
                    std::memcpy(&steps, &points[2 * at], 2);
                    const double value = data["pointsOrigin"][static_cast<std::size_t>(k)].get<double>() +
                                         data["pointsStep"].get<double>() * steps;
                    EXPECT_NEAR(value, p[k], 0.51 * data["pointsStep"].get<double>());
                }
        }
    EXPECT_EQ(2 * at, points.size());
    EXPECT_LT(data["pointsStep"].get<double>(), 1.1 / 65535);  // the swing spans under 1.1 m
}

TEST(HtmlViewer, PlaysScrubsAndPicksInHeadlessChromium) {
    for (const char* program : {"/usr/bin/chromium", "/usr/bin/chromedriver", "/usr/bin/python3"})
        if (!std::filesystem::exists(program))
            GTEST_SKIP() << program << " is absent (Debian's chromium and chromium-driver; scripts/setup.sh)";
    const Model model = test::makeTwoWireModel();
    const std::string page = testPath("swing_browser.html"), shot = testPath("swing_browser.png");
    const std::string log = testPath("drive_viewer.log");
    writeHtmlViewer(model, makeSwing(model), {}, page);
    std::filesystem::remove(shot);
    const std::string command = "/usr/bin/python3 " SINEW_SOURCE_DIR "/tests/render/drive_viewer.py '" + page + "' '" +
                                shot + "' loaded > '" + log + "' 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << readText(log);
    const test::PngPixels pixels(shot);
    EXPECT_GE(pixels.width, 800);
    int inked = 0, picked = 0;
    for (int y = 0; y < pixels.height; ++y)
        for (int x = 0; x < pixels.width; ++x) {
            inked += !pixels.isWhite(x, y);
            const Rgb c = pixels.at(x, y);
            picked += c.r > 0.75 && c.g < 0.3 && c.b < 0.3;  // the pick colour, (0.9, 0.1, 0.1)
        }
    EXPECT_GT(inked, pixels.width * pixels.height / 100);
    EXPECT_GT(picked, 20) << "the picked wire is not drawn in the pick colour";
}

}  // namespace
}  // namespace sinew
