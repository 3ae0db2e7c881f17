#pragma once
// MJCF (MuJoCo XML) files read into a tree of elements in which every <include> has been replaced by the
// elements of the file it names, as MuJoCo's mjIncludeXML does before it parses anything, each element
// traced to the file and line it was written at; and the attribute readers the MJCF reader builds on,
// every problem a ModelError "file:line: <element> 'name': what was expected". Private to sinew_io.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "conversion_notes.hpp"

namespace sinew::mjcf {

struct XmlElement {
    std::string tag;
    std::vector<std::pair<std::string, std::string>> attributes;  // as written, in order
    std::vector<XmlElement> children;
    std::string file;  // the file it was written in (an included file for included elements)
    int line = 0;

    std::string where() const { return file + ":" + std::to_string(line); }
    const char* findAttribute(const char* name) const;  // nullptr when absent
    std::string getName() const;                       // the name attribute, "" when absent
    std::string describe() const;                      // "joint 'hip_r'", or "joint" without a name
    // Throws ModelError at where(): "<describe()>: message".
    [[noreturn]] void fail(const std::string& message) const;
};

// Reads `path`, whose root must be <mujoco>, with its includes expanded recursively. An include's file is
// looked for relative to the main file's folder (MuJoCo 2.2's rule, which MyoSuite's models follow), then
// relative to the folder of the file holding the <include> (the rule of MuJoCo since 3.1, which
// MS-Human-700's nested includes follow). The included file's root element (<mujoco> or <mujocoinclude>)
// is dropped and its child elements take the include's place. A missing or repeated file, an include with
// children and an included file without elements are errors at the include's file:line.
XmlElement readMjcfTree(const std::string& path);

// Attribute readers. Absent attributes leave the value alone and return false (nullopt); present ones must
// hold what is asked for. Numbers must be finite.
//
// MuJoCo's reads of a fixed count (`exact`) want that many numbers; the others (size, gainprm, ...) take up
// to `count` and keep the remaining entries as they were, which is how a default class's values survive
// a shorter attribute.
int readNumbers(const XmlElement& element, const char* name, double* values, int count, bool exact = true);
bool readNumber(const XmlElement& element, const char* name, double& value);
bool readVector3(const XmlElement& element, const char* name, Eigen::Vector3d& value);
bool readInt(const XmlElement& element, const char* name, int& value);
bool readBool(const XmlElement& element, const char* name, bool& value);
std::optional<std::string> readText(const XmlElement& element, const char* name);
// The index of the attribute's keyword in `keywords`, or -1 when the attribute is absent; another word is
// an error listing the keywords.
int readKeyword(const XmlElement& element, const char* name, const std::vector<const char*>& keywords);
// MuJoCo's true/false/auto: 0, 1 or 2 into `value`.
bool readTrueFalseAuto(const XmlElement& element, const char* name, int& value);

}  // namespace sinew::mjcf
