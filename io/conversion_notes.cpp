#include "conversion_notes.hpp"

#include <sstream>

namespace sinew {

std::string describeAt(const std::string& kind, const std::string& name, const std::string& where) {
    return (name.empty() ? kind : kind + " '" + name + "'") + " (" + where + ")";
}

std::string formatNumber(double value) {
    std::ostringstream text;
    text << value;
    return text.str();
}

}  // namespace sinew
