#include "sinew/plugin/wire_decorations.hpp"

#include <algorithm>
#include <cstdlib>

#include "sinew/core/error.hpp"

#include "eigen_simtk.hpp"

namespace sinew {
namespace {

constexpr double kGrey = 0.55;

}  // namespace

WireDecorationGenerator::WireDecorationGenerator(const SimbodyWirePaths& paths, ShadingScale scale)
    : paths_(paths), scale_(scale), capsules_(calcBoneCapsules(paths.getModel())) {}

void WireDecorationGenerator::generateDecorations(const SimTK::State& state,
                                                  SimTK::Array_<SimTK::DecorativeGeometry>& geometry) {
    const Model& model = paths_.getModel();
    const bool withTensions = state.getSystemStage() >= SimTK::Stage::Velocity;
    const Data& data = withTensions ? paths_.realizeTensions(state) : paths_.realizePaths(state);
    const Eigen::VectorXd tensions = withTensions ? paths_.getTensions() : Eigen::VectorXd::Zero(model.getNumWires());
    const BodyFrame frame = calcBodyFrame(model, data, capsules_, state.getTime(), tensions);
    const SimTK::Vec3 bone(0.89, 0.87, 0.81);
    for (const SceneCapsule& capsule : frame.bones) {
        const Eigen::Vector3d axis = capsule.b_G - capsule.a_G;
        if (axis.norm() > 0) {
            // DecorativeCylinder runs along its y axis, centred on its origin.
            const SimTK::Rotation R_GC(SimTK::UnitVec3(toVec3(axis)), SimTK::YAxis);
            geometry.push_back(SimTK::DecorativeCylinder(capsule.radius, axis.norm() / 2)
                                   .setTransform(SimTK::Transform(R_GC, toVec3(0.5 * (capsule.a_G + capsule.b_G))))
                                   .setColor(bone));
        }
        for (const Eigen::Vector3d* end : {&capsule.a_G, &capsule.b_G})
            geometry.push_back(SimTK::DecorativeSphere(capsule.radius).setTransform(toVec3(*end)).setColor(bone));
    }
    for (int w = 0; w < model.getNumWires(); ++w) {
        const SceneWire& wire = frame.wires[static_cast<std::size_t>(w)];
        const Rgb c = withTensions ? calcWireColour(model, scale_, w, wire) : Rgb{kGrey, kGrey, kGrey};
        const double thickness = model.getWire(w).kind == WireKind::Muscle ? 2 : 1;
        for (std::size_t i = 0; i + 1 < wire.path_G.size(); ++i)
            geometry.push_back(SimTK::DecorativeLine(toVec3(wire.path_G[i]), toVec3(wire.path_G[i + 1]))
                                   .setColor(SimTK::Vec3(c.r, c.g, c.b))
                                   .setLineThickness(thickness));
    }
}

SimulationVisualizer::SimulationVisualizer(const Model& model, const std::string& hangBy) {
    const std::string problem = findVisualizerProblem();
    if (!problem.empty()) throw Error("--visualize: " + problem);
    SimbodyModelOptions options;
    options.hangBy = hangBy;
    system_ = std::make_unique<SimbodyModel>(model, options);
    visualizer_ = std::make_unique<SimTK::Visualizer>(system_->getSystem());
    visualizer_->setWindowTitle("sinew: " + model.getName() + ", wires coloured by tension");
    generator_ = new WireDecorationGenerator(*system_->getWirePaths(), scale_);
    visualizer_->addDecorationGenerator(generator_);
}

SimulationVisualizer::~SimulationVisualizer() = default;

void SimulationVisualizer::show(const SimulationFrame& frame) {
    const SimTK::State state = system_->makeState(frame.q, frame.u, SimTK::Stage::Velocity);
    const Model& model = system_->getModel();
    // Widen the scales to what this frame shows, so that colours never saturate mid-run.
    const BodyFrame shown = calcBodyFrame(model, system_->getWirePaths()->realizeTensions(state), {}, frame.time,
                                          system_->getWirePaths()->getTensions());
    const ShadingScale seen = calcShadingScale(model, {shown}, PictureOptions{});
    scale_ = ShadingScale{std::max(scale_.maxTension, seen.maxTension), std::max(scale_.maxStrain, seen.maxStrain)};
    generator_->setScale(scale_);
    visualizer_->report(state);
}

std::string findVisualizerProblem() {
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((!display || !*display) && (!wayland || !*wayland))
        return "no display: neither DISPLAY nor WAYLAND_DISPLAY is set, so simbody-visualizer cannot open a window";
    return "";
}

}  // namespace sinew
