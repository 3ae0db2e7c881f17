#pragma once
// Simbody's visualizer drawing the body as sinew's pictures do (sinew/render/picture.hpp): the links as
// capsules and every wire's evaluated path coloured by tension (ligaments by strain), from the system's
// SimbodyWirePaths, so the visualizer shows the paths and tensions the wire forces apply.
#include "sinew/plugin/ndebug_guard.hpp"

#include <Simbody.h>
#include <memory>
#include <string>
#include <vector>

#include "sinew/render/body_scene.hpp"
#include "sinew/core/simulation.hpp"
#include "sinew/render/picture.hpp"
#include "sinew/plugin/simbody_model.hpp"
#include "sinew/plugin/wire_paths.hpp"

namespace sinew {

class WireDecorationGenerator : public SimTK::DecorationGenerator {
public:
    // `paths` (SimbodyModel::getWirePaths()) must outlive the generator; `scale` sets the colour scales' tops.
    WireDecorationGenerator(const SimbodyWirePaths& paths, ShadingScale scale);

    // Appends, in ground: per capsule a DecorativeCylinder and two DecorativeSpheres; per wire path segment
    // a DecorativeLine in the wire's colour (calcWireColour). Tensions need the state realized to Velocity;
    // below it the wires are drawn grey.
    void generateDecorations(const SimTK::State& state, SimTK::Array_<SimTK::DecorativeGeometry>& geometry) override;
    void setScale(const ShadingScale& scale) { scale_ = scale; }

private:
    const SimbodyWirePaths& paths_;
    ShadingScale scale_;
    std::vector<BoneCapsule> capsules_;
};

// A simulation's frames shown in simbody-visualizer as they are made (either engine's frames: a Simbody
// system of the model is kept for the drawing alone), the colour scale widened to the largest tension and
// strain shown so far. Throws sinew::Error with findVisualizerProblem()'s reason where no window can open.
class SimulationVisualizer {
public:
    SimulationVisualizer(const Model& model, const std::string& hangBy);
    ~SimulationVisualizer();
    void show(const SimulationFrame& frame);

private:
    std::unique_ptr<SimbodyModel> system_;
    std::unique_ptr<SimTK::Visualizer> visualizer_;
    WireDecorationGenerator* generator_ = nullptr;  // owned by visualizer_
    ShadingScale scale_;
};

// Why simbody-visualizer cannot open a window here (no DISPLAY or WAYLAND_DISPLAY), or empty when it can
// try (Simbody's Visualizer then reports its own failures, a missing simbody-visualizer among them).
std::string findVisualizerProblem();

}  // namespace sinew
