#include "sinew/render/colour_map.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace sinew {
namespace {

// Entries 0, 16, ..., 240 and 255 of matplotlib's _viridis_data and _plasma_data (matplotlib/_cm_listed.py).
constexpr int kAnchors = 17;
constexpr Rgb kViridis[kAnchors] = {
    {0.267004, 0.004874, 0.329415}, {0.282327, 0.094955, 0.417331}, {0.278826, 0.175490, 0.483397},
    {0.258965, 0.251537, 0.524736}, {0.229739, 0.322361, 0.545706}, {0.199430, 0.387607, 0.554642},
    {0.172719, 0.448791, 0.557885}, {0.149039, 0.508051, 0.557250}, {0.127568, 0.566949, 0.550556},
    {0.120638, 0.625828, 0.533488}, {0.157851, 0.683765, 0.501686}, {0.246070, 0.738910, 0.452024},
    {0.369214, 0.788888, 0.382914}, {0.515992, 0.831158, 0.294279}, {0.678489, 0.863742, 0.189503},
    {0.845561, 0.887322, 0.099702}, {0.993248, 0.906157, 0.143936}};
constexpr Rgb kPlasma[kAnchors] = {
    {0.050383, 0.029803, 0.527975}, {0.193374, 0.018354, 0.590330}, {0.299855, 0.009561, 0.631624},
    {0.399411, 0.000859, 0.656133}, {0.494877, 0.011990, 0.657865}, {0.584391, 0.068579, 0.632812},
    {0.665129, 0.138566, 0.585582}, {0.736019, 0.209439, 0.527908}, {0.798216, 0.280197, 0.469538},
    {0.853319, 0.351553, 0.413734}, {0.901807, 0.425087, 0.359688}, {0.942598, 0.502639, 0.305816},
    {0.973416, 0.585761, 0.251540}, {0.991365, 0.675355, 0.198453}, {0.993033, 0.771720, 0.154808},
    {0.974443, 0.874622, 0.144061}, {0.940015, 0.975158, 0.131326}};

// The table index of anchor k: every 16th entry, the last anchor at 255.
double anchorIndex(int k) { return k == kAnchors - 1 ? 255.0 : 16.0 * k; }

}  // namespace

const char* toString(ColourMap map) { return map == ColourMap::Viridis ? "viridis" : "plasma"; }

Rgb calcColour(ColourMap map, double t) {
    const Rgb* table = map == ColourMap::Viridis ? kViridis : kPlasma;
    assert(!std::isnan(t));
    const double index = 255.0 * std::clamp(t, 0.0, 1.0);
    int k = std::min(static_cast<int>(index / 16.0), kAnchors - 2);
    const double s = (index - anchorIndex(k)) / (anchorIndex(k + 1) - anchorIndex(k));
    const Rgb& a = table[k];
    const Rgb& b = table[k + 1];
    return {a.r + s * (b.r - a.r), a.g + s * (b.g - a.g), a.b + s * (b.b - a.b)};
}

}  // namespace sinew
