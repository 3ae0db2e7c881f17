#include "sinew/io/model_loading.hpp"

#include <cctype>
#include <fstream>
#include <iterator>

#include "sinew/core/error.hpp"
#include "sinew/io/mjcf_model.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/io/osim_markers.hpp"
#include "sinew/io/osim_model_converter.hpp"

namespace sinew {
namespace {

// The name of the first element of XML `text`, past the declaration, comments and DOCTYPE; "" when the
// text does not start like XML.
std::string findRootElementName(const std::string& text) {
    std::size_t i = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;  // a UTF-8 byte order mark
    while (true) {
        while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
        if (i >= text.size() || text[i] != '<') return "";
        const char* close = text.compare(i, 4, "<!--") == 0 ? "-->" : (text.compare(i, 2, "<?") == 0 || text.compare(i, 2, "<!") == 0) ? ">" : nullptr;
        if (!close) break;
        const std::size_t end = text.find(close, i);
        if (end == std::string::npos) return "";
        i = end + std::char_traits<char>::length(close);
    }
    std::size_t end = i + 1;
    while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end])) && text[end] != '>' &&
           text[end] != '/')
        ++end;
    return text.substr(i + 1, end - i - 1);
}

}  // namespace

const char* toString(ModelFormat format) {
    switch (format) {
        case ModelFormat::SinewYaml: return "sinew YAML";
        case ModelFormat::OpenSim: return "OpenSim";
        case ModelFormat::Mjcf: return "MJCF";
    }
    return "?";
}

ModelFormat detectModelFormat(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw ModelError(path, "cannot open for reading");
    // The root element comes after at most a declaration and a licence comment; 64 kB holds them.
    std::string head(64 * 1024, '\0');
    file.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(file.gcount()));
    const std::string root = findRootElementName(head);
    if (root.empty()) return ModelFormat::SinewYaml;
    if (root == "mujoco") return ModelFormat::Mjcf;
    if (root == "OpenSimDocument") return ModelFormat::OpenSim;
    throw ModelError(path, "an XML file with root element <" + root +
                               ">; sinew reads MJCF (<mujoco>), OpenSim models (<OpenSimDocument>) and its YAML models");
}

Model loadModel(const std::string& path, const std::function<void(const std::string&)>& notes) {
    const ModelFormat format = detectModelFormat(path);
    if (format == ModelFormat::SinewYaml) return readModelFile(path);
    if (format == ModelFormat::Mjcf) {
        MjcfConversion conversion = readMjcfModel(path);
        if (notes)
            for (const std::string& line : conversion.notImported) notes("not imported: " + line);
        return std::move(conversion.model);
    }
    OsimConversion conversion = convertOsimModel(readOsimModel(path));
    reportOsimConversion(conversion, notes);
    return std::move(conversion.model);
}

std::vector<Marker> loadMarkers(const std::string& path, const Model& model) {
    if (detectModelFormat(path) != ModelFormat::OpenSim) return {};
    return convertOsimMarkers(readOsimModel(path).markers, model);
}

}  // namespace sinew
