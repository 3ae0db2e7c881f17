// The colour maps against matplotlib's full 256-entry tables (matplotlib/_cm_listed.py), at entries between
// the anchors that sinew keeps, and at the ends.
#include <gtest/gtest.h>

#include "sinew/render/colour_map.hpp"

namespace sinew {
namespace {

void expectColour(const Rgb& actual, const Rgb& expected, double tolerance) {
    EXPECT_NEAR(actual.r, expected.r, tolerance);
    EXPECT_NEAR(actual.g, expected.g, tolerance);
    EXPECT_NEAR(actual.b, expected.b, tolerance);
}

TEST(ColourMap, ViridisMatchesMatplotlibBetweenAnchors) {
    expectColour(calcColour(ColourMap::Viridis, 0.0), {0.267004, 0.004874, 0.329415}, 1e-12);
    expectColour(calcColour(ColourMap::Viridis, 100 / 255.0), {0.166617, 0.463708, 0.558119}, 0.004);
    expectColour(calcColour(ColourMap::Viridis, 200 / 255.0), {0.440137, 0.811138, 0.340967}, 0.004);
    expectColour(calcColour(ColourMap::Viridis, 1.0), {0.993248, 0.906157, 0.143936}, 1e-12);
}

TEST(ColourMap, PlasmaMatchesMatplotlibBetweenAnchors) {
    expectColour(calcColour(ColourMap::Plasma, 0.0), {0.050383, 0.029803, 0.527975}, 1e-12);
    expectColour(calcColour(ColourMap::Plasma, 77 / 255.0), {0.568201, 0.055778, 0.639477}, 0.004);
    expectColour(calcColour(ColourMap::Plasma, 1.0), {0.940015, 0.975158, 0.131326}, 1e-12);
}

TEST(ColourMap, ClampsOutsideTheUnitInterval) {
    expectColour(calcColour(ColourMap::Viridis, -3.0), calcColour(ColourMap::Viridis, 0.0), 0);
    expectColour(calcColour(ColourMap::Plasma, 7.0), calcColour(ColourMap::Plasma, 1.0), 0);
}

}  // namespace
}  // namespace sinew
