#pragma once
// One XML file parsed with pugixml, in place, with the line of each of its elements: pugixml keeps only
// byte offsets, and every reader of sinew's reports errors at file:line. The OpenSim and MJCF readers both
// load their files through it. Private to sinew_io.
#include <pugixml.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace sinew {

class XmlFile {
public:
    // tinyxml2's limit, kept: sinew's readers recurse through the elements (an MJCF body tree), and pugixml,
    // which does not, would hand them a document deep enough to overflow the stack.
    static constexpr int kMaxElementDepth = 500;

    // Reads and parses `path`. Throws ModelError: "cannot open" at `openedAt` (the element that named the
    // file, "file:line") or at the path when openedAt is empty; malformed XML at the line where the parser
    // stopped, quoting that line; a file without an element; elements nested deeper than kMaxElementDepth,
    // at the first too deep.
    explicit XmlFile(std::string path, const std::string& openedAt = "");
    XmlFile(const XmlFile&) = delete;
    XmlFile& operator=(const XmlFile&) = delete;

    const std::string& getPath() const { return path_; }
    pugi::xml_node getRoot() const { return document_.document_element(); }
    int getLine(pugi::xml_node node) const;  // 1-based; the element's opening tag

private:
    int lineAt(std::size_t offset) const;
    void checkDepth() const;

    std::string path_;
    std::string text_;                   // the file; the document's strings point into it
    std::vector<std::size_t> newlines_;  // offsets of the file's line ends
    pugi::xml_document document_;
};

// `text` without the white space XML allows around it (space, tab, CR, LF).
std::string trimXmlSpace(std::string_view text);

// The first child element of `node`, and its next sibling element: pugixml keeps the text between
// elements as nodes of their own. Null when there is none.
pugi::xml_node firstChildElement(pugi::xml_node node);
pugi::xml_node nextSiblingElement(pugi::xml_node node);

}  // namespace sinew
