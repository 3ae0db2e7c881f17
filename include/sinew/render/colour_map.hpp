#pragma once
// The perceptual colour maps that pictures shade wires with (docs/rendering.md): matplotlib's viridis for
// tension and plasma for ligament strain, both perceptually uniform and readable in grey and by most
// colour-blind readers; two maps so a reader never mistakes a strain for a tension.
namespace sinew {

struct Rgb {
    double r = 0, g = 0, b = 0;  // each in [0, 1]
};

enum class ColourMap { Viridis, Plasma };
const char* toString(ColourMap map);

// The map's colour at t (not NaN), t clamped to [0, 1] (0: the low end). Matplotlib's 256-entry table sampled at every
// 16th entry and its last, linear in between (within 0.004 of the full table in every channel).
Rgb calcColour(ColourMap map, double t);

}  // namespace sinew
