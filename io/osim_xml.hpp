#pragma once
// Reading OpenSim XML documents (models, tool setups, external loads, force sets) with pugixml, every value
// traced to the file and line it came from. Private to sinew_io.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "sinew/io/osim_actuator.hpp"
#include "sinew/io/osim_function.hpp"
#include "xml_file.hpp"

namespace sinew::osim {

// An element of a loaded document, reached only through the functions below (pugixml's node, opaque).
using Element = pugi::xml_node_struct;

class XmlDocument {
public:
    // Loads `path`. Throws ModelError at "file:line" for an unreadable or malformed file, or a root other
    // than <OpenSimDocument>.
    explicit XmlDocument(std::string path);
    XmlDocument(const XmlDocument&) = delete;
    XmlDocument& operator=(const XmlDocument&) = delete;

    const std::string& getPath() const { return file_.getPath(); }
    int getVersion() const { return version_; }  // the OpenSimDocument Version attribute, 0 when absent
    // The one child of <OpenSimDocument> of the given type (e.g. "Model"); throws when there is none.
    const Element& getObject(const char* type) const;
    // The first child of <OpenSimDocument>, whatever its type; throws when there is none.
    const Element& getFirstObject() const;

    std::string where(const Element& element) const;  // "file:line"
    // Throws ModelError at the element's line: "<Type name='x'>: message".
    [[noreturn]] void fail(const Element& element, const std::string& message) const;
    // A file named in this document, made absolute against this document's folder (OpenSim runs its tools
    // from the setup file's folder); an empty name stays empty.
    std::string resolveFile(const std::string& name) const;

private:
    const Element& getRoot() const;

    XmlFile file_;
    int version_ = 0;
};

// The element's tag: the type of an OpenSim object (<PinJoint>) or the name of a property (<mass>).
const char* typeOf(const Element& element);
// The first child element, and the element's next sibling element (of the given tag when one is given);
// nullptr when there is none.
const Element* firstChild(const Element& owner);
const Element* nextSibling(const Element& element, const char* type = nullptr);
// The element's own text, trimmed ("" when it has none).
std::string textOf(const Element& element);

// "<Type name='x'>" or "<Type>", for messages.
std::string describe(const Element& element);
std::string getName(const Element& element);  // the name attribute, "" when absent

// Properties: the child element `property` of `owner`, its text trimmed. Absent properties give the
// fallback; present ones that do not parse throw at their line.
const Element* findChild(const Element& owner, const char* property);
std::string readText(const XmlDocument& doc, const Element& owner, const char* property,
                     const std::string& fallback = "");
std::vector<double> readNumbers(const XmlDocument& doc, const Element& element);  // |x| <= 1e9; +-inf only as a control limit
double readDouble(const XmlDocument& doc, const Element& owner, const char* property, double fallback);
double readRequiredDouble(const XmlDocument& doc, const Element& owner, const char* property);
Eigen::Vector3d readVector3(const XmlDocument& doc, const Element& owner, const char* property,
                            const Eigen::Vector3d& fallback);
// Exactly `count` numbers, or the fallback when absent.
std::vector<double> readFixedNumbers(const XmlDocument& doc, const Element& owner, const char* property,
                                     std::size_t count, std::vector<double> fallback);
bool readBool(const XmlDocument& doc, const Element& owner, const char* property, bool fallback);
std::vector<std::string> readNames(const XmlDocument& doc, const Element& owner, const char* property);

// The children of <owner><objects>, or of `owner` itself when it has no <objects> (OpenSim's Set layout).
std::vector<const Element*> getSetObjects(const Element& owner);
// OpenSim's own renames of old type names (GeneralizedForce -> CoordinateActuator, ...).
std::string getCurrentTypeName(const std::string& type);

bool isFunctionType(std::string_view type);
// The function `element` is (e.g. a <SimmSpline>); an unknown type throws, naming the known ones.
OsimFunction readFunction(const XmlDocument& doc, const Element& element);
// A function-valued property: <property><Type>...</Type></property>, or <Type name="property"> (the form
// OpenSim 4 writes for TransformAxis); nullptr when absent.
const Element* findFunction(const XmlDocument& doc, const Element& owner, const char* property);

// <appliesForce>, or, in files older than OpenSim 4, the opposite of <isDisabled>.
bool readAppliesForce(const XmlDocument& doc, const Element& force, bool fallback);
// optimal_force, min_control, max_control and appliesForce over the defaults.
OsimActuatorLimits readActuatorLimits(const XmlDocument& doc, const Element& actuator, OsimActuatorLimits defaults);
OsimCoordinateActuator readCoordinateActuator(const XmlDocument& doc, const Element& element);
OsimPointActuator readPointActuator(const XmlDocument& doc, const Element& element);
OsimTorqueActuator readTorqueActuator(const XmlDocument& doc, const Element& element);

}  // namespace sinew::osim
