#include "mjcf_xml.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <strings.h>

#include "number_text.hpp"
#include "sinew/core/error.hpp"
#include "xml_file.hpp"

namespace sinew::mjcf {
namespace fs = std::filesystem;

const char* XmlElement::findAttribute(const char* name) const {
    for (const auto& [key, value] : attributes)
        if (key == name) return value.c_str();
    return nullptr;
}

std::string XmlElement::getName() const {
    const char* name = findAttribute("name");
    return name ? name : "";
}

std::string XmlElement::describe() const {
    const std::string name = getName();
    return name.empty() ? tag : tag + " '" + name + "'";
}

void XmlElement::fail(const std::string& message) const { throw ModelError(where(), describe() + ": " + message); }

namespace {

// Expands one document's elements into the tree, following includes into their files.
class TreeReader {
public:
    explicit TreeReader(const std::string& mainPath)
        : mainFolder_(fs::path(mainPath).parent_path()), included_{fs::absolute(mainPath).lexically_normal()} {}

    void appendChildren(pugi::xml_node source, const XmlFile& file, XmlElement& target) {
        for (pugi::xml_node child = firstChildElement(source); child; child = nextSiblingElement(child)) {
            XmlElement element = convert(child, file);
            if (strcasecmp(child.name(), "include") == 0) {
                appendIncluded(element, child, target);
                continue;
            }
            appendChildren(child, file, element);
            target.children.push_back(std::move(element));
        }
    }

    static XmlElement convert(pugi::xml_node source, const XmlFile& file) {
        XmlElement element;
        element.tag = source.name();
        for (const pugi::xml_attribute& a : source.attributes()) element.attributes.emplace_back(a.name(), a.value());
        element.file = file.getPath();
        element.line = file.getLine(source);
        return element;
    }

private:
    void appendIncluded(const XmlElement& include, pugi::xml_node source, XmlElement& target) {
        if (source.first_child()) include.fail("an include cannot have children");
        const std::optional<std::string> name = readText(include, "file");
        if (!name || name->empty()) include.fail("needs the file attribute naming the file to include");
        const fs::path path = resolve(include, *name);
        const fs::path absolute = fs::absolute(path).lexically_normal();
        for (const fs::path& earlier : included_)
            if (earlier == absolute) include.fail("'" + path.string() + "' is already included");
        included_.push_back(absolute);
        const XmlFile file(path.string(), include.where());
        if (!firstChildElement(file.getRoot()))
            include.fail("'" + path.string() + "' holds no element under its root <" + file.getRoot().name() + ">");
        appendChildren(file.getRoot(), file, target);
    }

    fs::path resolve(const XmlElement& include, const std::string& name) const {
        const fs::path file(name);
        if (file.is_absolute()) {
            if (fs::is_regular_file(file)) return file;
            include.fail("'" + name + "' does not exist");
        }
        const fs::path fromMain = (mainFolder_ / file).lexically_normal();
        if (fs::is_regular_file(fromMain)) return fromMain;
        const fs::path fromIncluding = (fs::path(include.file).parent_path() / file).lexically_normal();
        if (fs::is_regular_file(fromIncluding)) return fromIncluding;
        include.fail("'" + name + "' is neither at " + fromMain.string() + " (relative to the main file) nor at " +
                     fromIncluding.string() + " (relative to this file)");
    }

    fs::path mainFolder_;
    std::vector<fs::path> included_;  // absolute paths; MuJoCo refuses a file included twice
};

[[noreturn]] void failAttribute(const XmlElement& element, const char* name, const std::string& message) {
    element.fail(std::string("attribute '") + name + "': " + message);
}

}  // namespace

XmlElement readMjcfTree(const std::string& path) {
    const XmlFile file(path);
    XmlElement tree = TreeReader::convert(file.getRoot(), file);
    if (strcasecmp(file.getRoot().name(), "mujoco") != 0)
        throw ModelError(tree.where(), "the root element is <" + tree.tag + ">; an MJCF file has <mujoco>");
    TreeReader(path).appendChildren(file.getRoot(), file, tree);
    return tree;
}

int readNumbers(const XmlElement& element, const char* name, double* values, int count, bool exact) {
    const char* text = element.findAttribute(name);
    if (!text) return 0;
    std::istringstream tokens(text);
    std::string token;
    int read = 0;
    while (tokens >> token) {
        if (read == count)
            failAttribute(element, name, "'" + std::string(text) + "' has more than " + std::to_string(count) +
                                             (count == 1 ? " number" : " numbers"));
        const std::optional<double> value = parseNumber(token);
        if (!value) failAttribute(element, name, "'" + token + "' is not a number");
        if (!std::isfinite(*value)) failAttribute(element, name, "'" + token + "' is not a finite number");
        values[read++] = *value;
    }
    if (read == 0 || (exact && read < count))
        failAttribute(element, name, "'" + std::string(text) + "': expected " +
                                         (exact ? std::to_string(count) : "1 to " + std::to_string(count)) +
                                         (count == 1 ? " number" : " numbers"));
    return read;
}

bool readNumber(const XmlElement& element, const char* name, double& value) {
    return readNumbers(element, name, &value, 1) > 0;
}

bool readVector3(const XmlElement& element, const char* name, Eigen::Vector3d& value) {
    return readNumbers(element, name, value.data(), 3) > 0;
}

bool readInt(const XmlElement& element, const char* name, int& value) {
    double number = 0;
    if (!readNumber(element, name, number)) return false;
    if (number != std::floor(number) || std::abs(number) > 1e9)
        failAttribute(element, name, "'" + std::string(element.findAttribute(name)) + "' is not a whole number");
    value = static_cast<int>(number);
    return true;
}

bool readBool(const XmlElement& element, const char* name, bool& value) {
    const int keyword = readKeyword(element, name, {"false", "true"});
    if (keyword < 0) return false;
    value = keyword == 1;
    return true;
}

std::optional<std::string> readText(const XmlElement& element, const char* name) {
    const char* text = element.findAttribute(name);
    if (!text) return std::nullopt;
    return std::string(text);
}

int readKeyword(const XmlElement& element, const char* name, const std::vector<const char*>& keywords) {
    const char* text = element.findAttribute(name);
    if (!text) return -1;
    std::string known;
    for (std::size_t i = 0; i < keywords.size(); ++i) {
        if (std::string(text) == keywords[i]) return static_cast<int>(i);
        known += (i == 0 ? "" : i + 1 == keywords.size() ? " or " : ", ") + std::string(keywords[i]);
    }
    failAttribute(element, name, "'" + std::string(text) + "': expected " + known);
}

bool readTrueFalseAuto(const XmlElement& element, const char* name, int& value) {
    const int keyword = readKeyword(element, name, {"false", "true", "auto"});
    if (keyword < 0) return false;
    value = keyword;
    return true;
}

}  // namespace sinew::mjcf
