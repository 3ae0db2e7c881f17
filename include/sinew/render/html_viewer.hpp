#pragma once
// A self-contained HTML page that plays a motion in the browser with the wires coloured by tension (as the
// pictures colour them): three.js from Debian's libjs-three inlined, so the file opens with no network;
// orbit, pause, scrub and speed; a click on a wire shows its name, kind and tension curve; a legend of the
// kinds (each can be hidden) and the colour scales. docs/rendering.md describes the page and its test hooks.
#include <string>
#include <vector>

#include "sinew/core/model.hpp"
#include "sinew/render/body_scene.hpp"

namespace sinew {

struct HtmlViewerOptions {
    std::string title;
    // Where libjs-three installs three.min.js and examples/js/controls/OrbitControls.js.
    std::string threeJsDir = "/usr/share/javascript/three";
};

// Writes the page at `path` (complete or not at all: an OutputFileSet of one). Throws sinew::Error naming
// the file when three.js is not installed, or for frames that do not match the model.
void writeHtmlViewer(const Model& model, const std::vector<BodyFrame>& frames, const HtmlViewerOptions& options,
                     const std::string& path);

}  // namespace sinew
