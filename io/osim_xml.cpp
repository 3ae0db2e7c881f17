#include "osim_xml.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string_view>
#include <filesystem>
#include <map>
#include <sstream>

#include "number_text.hpp"
#include "sinew/core/error.hpp"

namespace sinew {

const char* toString(OsimFunctionType type) {
    switch (type) {
        case OsimFunctionType::Constant: return "Constant";
        case OsimFunctionType::Linear: return "LinearFunction";
        case OsimFunctionType::SimmSpline: return "SimmSpline";
        case OsimFunctionType::NaturalCubicSpline: return "NaturalCubicSpline";
        case OsimFunctionType::PiecewiseLinear: return "PiecewiseLinearFunction";
        case OsimFunctionType::Polynomial: return "PolynomialFunction";
        case OsimFunctionType::Multiplier: return "MultiplierFunction";
    }
    return "?";
}

namespace osim {
namespace {

const std::map<std::string, OsimFunctionType, std::less<>>& functionTypes() {
    static const std::map<std::string, OsimFunctionType, std::less<>> types = {
        {"Constant", OsimFunctionType::Constant},
        {"LinearFunction", OsimFunctionType::Linear},
        {"SimmSpline", OsimFunctionType::SimmSpline},
        {"NaturalCubicSpline", OsimFunctionType::NaturalCubicSpline},
        {"PiecewiseLinearFunction", OsimFunctionType::PiecewiseLinear},
        {"PolynomialFunction", OsimFunctionType::Polynomial},
        {"MultiplierFunction", OsimFunctionType::Multiplier}};
    return types;
}

pugi::xml_node nodeOf(const Element& element) { return pugi::xml_node(const_cast<Element*>(&element)); }

// Knots of a spline or piecewise-linear function: x and y of one size >= 2, x strictly increasing.
void readKnots(const XmlDocument& doc, const Element& element, OsimFunction& function) {
    const Element* x = findChild(element, "x");
    const Element* y = findChild(element, "y");
    if (!x || !y) doc.fail(element, "needs both <x> and <y> knots");
    function.x = readNumbers(doc, *x);
    function.y = readNumbers(doc, *y);
    if (function.x.size() != function.y.size() || function.x.size() < 2)
        doc.fail(element, std::to_string(function.x.size()) + " x and " + std::to_string(function.y.size()) +
                              " y knots; expected the same number, at least 2");
    for (std::size_t i = 1; i < function.x.size(); ++i)
        if (!(function.x[i] > function.x[i - 1]))
            doc.fail(*x, "knots must increase strictly; x[" + std::to_string(i) + "] = " + std::to_string(function.x[i]) +
                             " follows " + std::to_string(function.x[i - 1]));
}

}  // namespace

XmlDocument::XmlDocument(std::string path) : file_(std::move(path)) {
    const pugi::xml_node root = file_.getRoot();
    if (std::string(root.name()) != "OpenSimDocument")
        throw ModelError(where(*root.internal_object()), "the root element is <" + std::string(root.name()) +
                                                             ">; an OpenSim file has <OpenSimDocument>");
    version_ = root.attribute("Version").as_int(0);
}

const Element& XmlDocument::getRoot() const { return *file_.getRoot().internal_object(); }

const Element& XmlDocument::getObject(const char* type) const {
    const Element* object = findChild(getRoot(), type);
    if (!object) fail(getRoot(), std::string("holds no <") + type + ">");
    return *object;
}

const Element& XmlDocument::getFirstObject() const {
    const Element* object = firstChild(getRoot());
    if (!object) fail(getRoot(), "holds no object");
    return *object;
}

std::string XmlDocument::where(const Element& element) const {
    const std::string line = std::to_string(file_.getLine(nodeOf(element)));
    std::string where;
    where.reserve(getPath().size() + 1 + line.size());
    return where.append(getPath()).append(1, ':').append(line);
}

void XmlDocument::fail(const Element& element, const std::string& message) const {
    throw ModelError(where(element), describe(element) + ": " + message);
}

std::string XmlDocument::resolveFile(const std::string& name) const {
    if (name.empty()) return name;
    const std::filesystem::path file(name);
    if (file.is_absolute()) return file.lexically_normal().string();
    return (std::filesystem::path(getPath()).parent_path() / file).lexically_normal().string();
}

const char* typeOf(const Element& element) { return nodeOf(element).name(); }

const Element* firstChild(const Element& owner) { return firstChildElement(nodeOf(owner)).internal_object(); }

const Element* nextSibling(const Element& element, const char* type) {
    return (type ? nodeOf(element).next_sibling(type) : nextSiblingElement(nodeOf(element))).internal_object();
}

std::string textOf(const Element& element) { return trimXmlSpace(nodeOf(element).child_value()); }

std::string describe(const Element& element) {
    const std::string name = getName(element);
    return "<" + std::string(typeOf(element)) + (name.empty() ? "" : " name='" + name + "'") + ">";
}

std::string getName(const Element& element) { return nodeOf(element).attribute("name").value(); }

const Element* findChild(const Element& owner, const char* property) { return nodeOf(owner).child(property).internal_object(); }

std::string readText(const XmlDocument&, const Element& owner, const char* property, const std::string& fallback) {
    const Element* element = findChild(owner, property);
    return element ? textOf(*element) : fallback;
}

// The bound of the YAML model format (io/yaml_fields.hpp), for the same reasons.
constexpr double kMaxOsimMagnitude = 1e9;

std::vector<double> readNumbers(const XmlDocument& doc, const Element& element) {
    // SimTK writes vectors as "~[1,2,3]" and some files wrap them in parentheses; both read as plain lists.
    const std::string_view text = nodeOf(element).child_value();
    auto separates = [](char c) {
        switch (c) {
            case ' ': case '\t': case '\n': case '\r': case '\f': case '\v':
            case ',': case '(': case ')': case '[': case ']': case '~': return true;
            default: return false;
        }
    };
    std::vector<double> numbers;
    numbers.reserve(4);  // most lists are a vector's 3 numbers: one allocation, not three
    for (std::size_t i = 0; i < text.size();) {
        while (i < text.size() && separates(text[i])) ++i;
        const std::size_t start = i;
        while (i < text.size() && !separates(text[i])) ++i;
        if (i == start) break;
        const std::string_view token = text.substr(start, i - start);
        const std::optional<double> parsed = parseNumber(token);
        if (!parsed) doc.fail(element, "'" + std::string(token) + "' is not a number");
        const double value = *parsed;
        if (std::isnan(value)) doc.fail(element, "NaN is not a value");
        // OpenSim writes an actuator's absent control limit as Inf; nowhere else does sinew carry one.
        const std::string_view name = typeOf(element);
        if (std::isinf(value) && name != "min_control" && name != "max_control")
            doc.fail(element, "<" + std::string(name) + "> '" + std::string(token) + "' is not a finite number");
        if (std::isfinite(value) && std::abs(value) > kMaxOsimMagnitude)
            doc.fail(element, "<" + std::string(name) + "> " + std::string(token) + " is beyond the magnitude 1e9 sinew bounds a model's "
                              "numbers to (docs/model-format.md, \"Bounds\")");
        numbers.push_back(value);
    }
    return numbers;
}

double readDouble(const XmlDocument& doc, const Element& owner, const char* property, double fallback) {
    const Element* element = findChild(owner, property);
    return element ? readFixedNumbers(doc, owner, property, 1, {})[0] : fallback;
}

double readRequiredDouble(const XmlDocument& doc, const Element& owner, const char* property) {
    if (!findChild(owner, property)) doc.fail(owner, std::string("missing <") + property + ">");
    return readDouble(doc, owner, property, 0);
}

Eigen::Vector3d readVector3(const XmlDocument& doc, const Element& owner, const char* property,
                            const Eigen::Vector3d& fallback) {
    if (!findChild(owner, property)) return fallback;
    const std::vector<double> numbers = readFixedNumbers(doc, owner, property, 3, {});
    return Eigen::Vector3d(numbers[0], numbers[1], numbers[2]);
}

std::vector<double> readFixedNumbers(const XmlDocument& doc, const Element& owner, const char* property,
                                     std::size_t count, std::vector<double> fallback) {
    const Element* element = findChild(owner, property);
    if (!element) return fallback;
    std::vector<double> numbers = readNumbers(doc, *element);
    if (numbers.size() != count)
        doc.fail(*element, "expected " + std::to_string(count) + (count == 1 ? " number" : " numbers") + ", got '" +
                               textOf(*element) + "'");
    return numbers;
}

bool readBool(const XmlDocument& doc, const Element& owner, const char* property, bool fallback) {
    const Element* element = findChild(owner, property);
    if (!element) return fallback;
    std::string text = textOf(*element);
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
    if (text == "true") return true;
    if (text == "false") return false;
    doc.fail(*element, "expected true or false, got '" + textOf(*element) + "'");
}

std::vector<std::string> readNames(const XmlDocument& doc, const Element& owner, const char* property) {
    std::istringstream tokens(readText(doc, owner, property));
    std::vector<std::string> names;
    std::string name;
    while (tokens >> name) names.push_back(name);
    return names;
}

std::vector<const Element*> getSetObjects(const Element& owner) {
    std::vector<const Element*> objects;
    const Element* list = findChild(owner, "objects");
    if (!list) return objects;
    for (const Element* child = firstChild(*list); child; child = nextSibling(*child)) objects.push_back(child);
    return objects;
}

std::string getCurrentTypeName(const std::string& type) {
    static const std::map<std::string, std::string> renamed = {{"GeneralizedForce", "CoordinateActuator"},
                                                               {"Force", "PointActuator"},
                                                               {"Torque", "TorqueActuator"},
                                                               {"Schutte1993Muscle", "Schutte1993Muscle_Deprecated"},
                                                               {"Delp1990Muscle", "Delp1990Muscle_Deprecated"}};
    const auto found = renamed.find(type);
    return found == renamed.end() ? type : found->second;
}

bool isFunctionType(std::string_view type) { return functionTypes().count(type) > 0; }

OsimFunction readFunction(const XmlDocument& doc, const Element& element) {
    const auto type = functionTypes().find(typeOf(element));
    if (type == functionTypes().end()) {
        std::string known;
        for (const auto& entry : functionTypes()) known += (known.empty() ? "" : ", ") + entry.first;
        doc.fail(element, "unknown function type (sinew reads " + known + ")");
    }
    OsimFunction function;
    function.type = type->second;
    function.where = doc.where(element);
    switch (function.type) {
        case OsimFunctionType::Constant:
            function.value = readDouble(doc, element, "value", 0);
            break;
        case OsimFunctionType::Linear:
            function.coefficients = readFixedNumbers(doc, element, "coefficients", 2, {1, 0});
            break;
        case OsimFunctionType::Polynomial:
            function.coefficients = findChild(element, "coefficients")
                                        ? readNumbers(doc, *findChild(element, "coefficients"))
                                        : std::vector<double>{1};
            if (function.coefficients.empty()) doc.fail(element, "a polynomial needs at least one coefficient");
            break;
        case OsimFunctionType::SimmSpline:
        case OsimFunctionType::NaturalCubicSpline:
        case OsimFunctionType::PiecewiseLinear:
            readKnots(doc, element, function);
            break;
        case OsimFunctionType::Multiplier: {
            const Element* inner = findFunction(doc, element, "function");
            if (!inner) doc.fail(element, "needs the <function> it scales");
            function.inner.push_back(readFunction(doc, *inner));
            function.scale = readDouble(doc, element, "scale", 1);
            break;
        }
    }
    return function;
}

const Element* findFunction(const XmlDocument& doc, const Element& owner, const char* property) {
    if (const Element* wrapper = findChild(owner, property)) {
        const Element* function = firstChild(*wrapper);
        if (function && nextSibling(*function))
            doc.fail(*wrapper, "holds more than one element; expected one function");
        return function;
    }
    for (const Element* child = firstChild(owner); child; child = nextSibling(*child))
        if (getName(*child) == property) return child;
    return nullptr;
}

OsimActuatorLimits readActuatorLimits(const XmlDocument& doc, const Element& actuator, OsimActuatorLimits defaults) {
    OsimActuatorLimits limits;
    limits.optimalForce = readDouble(doc, actuator, "optimal_force", defaults.optimalForce);
    limits.minControl = readDouble(doc, actuator, "min_control", defaults.minControl);
    limits.maxControl = readDouble(doc, actuator, "max_control", defaults.maxControl);
    if (limits.minControl > limits.maxControl)
        doc.fail(actuator, "min_control " + std::to_string(limits.minControl) + " exceeds max_control " +
                               std::to_string(limits.maxControl));
    limits.appliesForce = readAppliesForce(doc, actuator, defaults.appliesForce);
    return limits;
}

bool readAppliesForce(const XmlDocument& doc, const Element& force, bool fallback) {
    return findChild(force, "appliesForce") ? readBool(doc, force, "appliesForce", fallback)
                                            : !readBool(doc, force, "isDisabled", !fallback);
}

namespace {

std::string readRequiredName(const XmlDocument& doc, const Element& owner, const char* property) {
    const std::string text = readText(doc, owner, property);
    if (text.empty()) doc.fail(owner, std::string("missing <") + property + ">");
    return text;
}

}  // namespace

OsimCoordinateActuator readCoordinateActuator(const XmlDocument& doc, const Element& element) {
    OsimCoordinateActuator actuator;
    actuator.name = getName(element);
    actuator.coordinate = readRequiredName(doc, element, "coordinate");
    actuator.limits = readActuatorLimits(doc, element, {});
    actuator.where = doc.where(element);
    return actuator;
}

OsimPointActuator readPointActuator(const XmlDocument& doc, const Element& element) {
    OsimPointActuator actuator;
    actuator.name = getName(element);
    actuator.body = readRequiredName(doc, element, "body");
    actuator.point = readVector3(doc, element, "point", actuator.point);
    actuator.pointIsGlobal = readBool(doc, element, "point_is_global", actuator.pointIsGlobal);
    actuator.direction = readVector3(doc, element, "direction", actuator.direction);
    actuator.forceIsGlobal = readBool(doc, element, "force_is_global", actuator.forceIsGlobal);
    actuator.limits = readActuatorLimits(doc, element, {});
    actuator.where = doc.where(element);
    return actuator;
}

OsimTorqueActuator readTorqueActuator(const XmlDocument& doc, const Element& element) {
    OsimTorqueActuator actuator;
    actuator.name = getName(element);
    actuator.bodyA = readRequiredName(doc, element, "bodyA");
    actuator.bodyB = readRequiredName(doc, element, "bodyB");
    actuator.axis = readVector3(doc, element, "axis", actuator.axis);
    actuator.torqueIsGlobal = readBool(doc, element, "torque_is_global", actuator.torqueIsGlobal);
    actuator.limits = readActuatorLimits(doc, element, {});
    actuator.where = doc.where(element);
    return actuator;
}

}  // namespace osim
}  // namespace sinew
