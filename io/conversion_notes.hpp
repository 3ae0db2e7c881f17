#pragma once
// How the importers' notes (the notImported lines of OpenSim and MJCF conversions) name an element and show a
// number, so that every converter reads the same.
#include <string>

namespace sinew {

// "kind 'name' (where)", or "kind (where)" without a name.
std::string describeAt(const std::string& kind, const std::string& name, const std::string& where);

// A number as messages show it: six significant digits, no trailing zeros (0.1, 1e-08).
std::string formatNumber(double value);

}  // namespace sinew
