#pragma once
// The viewer page (html_viewer.hpp) with its markers, in page order: @@TITLE@@, @@THREE@@ (three.min.js),
// @@ORBIT@@ (OrbitControls.js), @@DATA@@ (the motion as JSON). Internal to render/.
namespace sinew::render_detail {

extern const char* const kViewerPage;

}  // namespace sinew::render_detail
