#include "xml_file.hpp"

#include <algorithm>
#include <fstream>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

std::string readWholeFile(const std::string& path, const std::string& openedAt) {
    std::ifstream file(path, std::ios::binary | std::ios::ate);
    const std::streamoff size = file.is_open() ? static_cast<std::streamoff>(file.tellg()) : -1;
    const std::string where = openedAt.empty() ? path : openedAt;
    if (size < 0) throw ModelError(where, "cannot open '" + path + "' for reading");
    std::string text(static_cast<std::size_t>(size), '\0');
    file.seekg(0);
    if (!file.read(text.data(), size)) throw ModelError(where, "cannot open '" + path + "' for reading");
    return text;
}

// The node itself when it is an element, else its next sibling element.
pugi::xml_node elementFrom(pugi::xml_node node) {
    while (node && node.type() != pugi::node_element) node = node.next_sibling();
    return node;
}

}  // namespace

std::string trimXmlSpace(std::string_view text) {
    const char* const blanks = " \t\r\n";
    const std::size_t begin = text.find_first_not_of(blanks);
    return begin == std::string_view::npos ? "" : std::string(text.substr(begin, text.find_last_not_of(blanks) - begin + 1));
}

pugi::xml_node firstChildElement(pugi::xml_node node) { return elementFrom(node.first_child()); }

pugi::xml_node nextSiblingElement(pugi::xml_node node) { return elementFrom(node.next_sibling()); }

XmlFile::XmlFile(std::string path, const std::string& openedAt)
    : path_(std::move(path)), text_(readWholeFile(path_, openedAt)) {
    for (std::size_t i = text_.find('\n'); i != std::string::npos; i = text_.find('\n', i + 1)) newlines_.push_back(i);
    // In place: no copy of the file, and the offsets pugixml reports are the file's own.
    const pugi::xml_parse_result parsed = document_.load_buffer_inplace(text_.data(), text_.size());
    if (parsed.status == pugi::status_no_document_element) throw ModelError(path_, "no XML element in the file");
    if (!parsed) {
        const int line = lineAt(static_cast<std::size_t>(std::max<std::ptrdiff_t>(parsed.offset, 0)));
        // The line as the file has it: parsing in place has cut text_ into strings.
        const std::string original = readWholeFile(path_, openedAt);
        const std::size_t begin = line == 1 ? 0 : newlines_[static_cast<std::size_t>(line - 2)] + 1;
        const std::size_t end = std::min({original.find('\n', begin), original.size(), begin + 80});
        throw ModelError(path_ + ":" + std::to_string(line), std::string("malformed XML (") + parsed.description() +
                                                                  ") at '" + trimXmlSpace(original.substr(begin, end - begin)) + "'");
    }
    checkDepth();
}

void XmlFile::checkDepth() const {
    // Depth first without recursion: down to the first child, else on to the next sibling of the node or
    // of its nearest ancestor that has one.
    pugi::xml_node node = document_.first_child();
    for (int depth = 1; node;) {
        if (depth > kMaxElementDepth && node.type() == pugi::node_element)
            throw ModelError(path_ + ":" + std::to_string(getLine(node)),
                             "<" + std::string(node.name()) + "> is nested " + std::to_string(depth) +
                                 " elements deep; sinew reads XML up to " + std::to_string(kMaxElementDepth) + " deep");
        if (const pugi::xml_node child = node.first_child()) {
            node = child, ++depth;
            continue;
        }
        while (!node.next_sibling()) {
            node = node.parent(), --depth;
            if (depth == 0) return;  // back at the document
        }
        node = node.next_sibling();
    }
}

int XmlFile::lineAt(std::size_t offset) const {
    return 1 + static_cast<int>(std::lower_bound(newlines_.begin(), newlines_.end(), offset) - newlines_.begin());
}

int XmlFile::getLine(pugi::xml_node node) const {
    return lineAt(static_cast<std::size_t>(std::max<std::ptrdiff_t>(node.offset_debug(), 0)));
}

}  // namespace sinew
