// Simbody's visualizer decorations against core: at a Simbody state, every DecorativeLine is a segment of
// the wire's path as core's calcWirePaths evaluates it at the same q, in the colour of the tension that
// core's force laws give at the same q and u; the capsules are calcBoneCapsules' placed by core's kinematics.
#include "sinew/plugin/ndebug_guard.hpp"

#include <gtest/gtest.h>

#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/plugin/simbody_model.hpp"
#include "sinew/plugin/wire_decorations.hpp"

namespace sinew {
namespace {

// Sorts decorations by kind (SimTK's DecorativeGeometry is a handle; its implementation is reached by a visitor).
struct Collector : SimTK::DecorativeGeometryImplementation {
    std::vector<SimTK::DecorativeLine> lines;
    std::vector<SimTK::DecorativeCylinder> cylinders;
    std::vector<SimTK::DecorativeSphere> spheres;
    int others = 0;
    void implementPointGeometry(const SimTK::DecorativePoint&) override { ++others; }
    void implementLineGeometry(const SimTK::DecorativeLine& g) override { lines.push_back(g); }
    void implementBrickGeometry(const SimTK::DecorativeBrick&) override { ++others; }
    void implementCylinderGeometry(const SimTK::DecorativeCylinder& g) override { cylinders.push_back(g); }
    void implementCircleGeometry(const SimTK::DecorativeCircle&) override { ++others; }
    void implementSphereGeometry(const SimTK::DecorativeSphere& g) override { spheres.push_back(g); }
    void implementEllipsoidGeometry(const SimTK::DecorativeEllipsoid&) override { ++others; }
    void implementFrameGeometry(const SimTK::DecorativeFrame&) override { ++others; }
    void implementTextGeometry(const SimTK::DecorativeText&) override { ++others; }
    void implementMeshGeometry(const SimTK::DecorativeMesh&) override { ++others; }
    void implementMeshFileGeometry(const SimTK::DecorativeMeshFile&) override { ++others; }
    void implementTorusGeometry(const SimTK::DecorativeTorus&) override { ++others; }
    void implementArrowGeometry(const SimTK::DecorativeArrow&) override { ++others; }
    void implementConeGeometry(const SimTK::DecorativeCone&) override { ++others; }
};

Collector generate(const SimbodyModel& system, const SimTK::State& state, const ShadingScale& scale) {
    WireDecorationGenerator generator(*system.getWirePaths(), scale);
    SimTK::Array_<SimTK::DecorativeGeometry> geometry;
    generator.generateDecorations(state, geometry);
    Collector collector;
    for (SimTK::DecorativeGeometry& g : geometry) g.implementGeometry(collector);
    return collector;
}

double distance(const SimTK::Vec3& a, const Eigen::Vector3d& b) { return (Eigen::Vector3d(a[0], a[1], a[2]) - b).norm(); }

TEST(WireDecorations, LinesAreCoresPathsInTheirTensionsColours) {
    const Model model = readModelFile(SINEW_SOURCE_DIR "/models/arm26.yaml");
    const SimbodyModel system(model);
    Eigen::VectorXd q = model.getDefaultQ(), u(model.getNumU());
    q[model.getNumQ() - 1] += 0.4;  // the elbow
    u << 0.3, -0.2, 0.1, 1.5;
    const SimTK::State state = system.makeState(q, u, SimTK::Stage::Velocity);
    const ShadingScale scale{100.0, 0.0};
    const Collector decorations = generate(system, state, scale);

    Data data(model);
    calcPositionKinematics(model, data, q);
    calcVelocityKinematics(model, data, u);
    calcWirePaths(model, data);
    calcWireSpeeds(model, data);
    Eigen::VectorXd tensions(model.getNumWires());
    calcWireTensions(model, data, 0.0, tensions);
    std::size_t line = 0;
    std::vector<Eigen::Vector3d> path;
    for (int w = 0; w < model.getNumWires(); ++w) {
        getWirePath_G(model, data, w, path);
        const Rgb expected = calcColour(ColourMap::Viridis, tensions[w] / scale.maxTension);
        for (std::size_t i = 0; i + 1 < path.size(); ++i, ++line) {
            ASSERT_LT(line, decorations.lines.size());
            const SimTK::DecorativeLine& drawn = decorations.lines[line];
            EXPECT_LT(distance(drawn.getPoint1(), path[i]), 1e-9) << model.getWire(w).name;
            EXPECT_LT(distance(drawn.getPoint2(), path[i + 1]), 1e-9) << model.getWire(w).name;
            EXPECT_NEAR(drawn.getColor()[0], expected.r, 1e-9);
            EXPECT_NEAR(drawn.getColor()[1], expected.g, 1e-9);
            EXPECT_NEAR(drawn.getColor()[2], expected.b, 1e-9);
        }
    }
    EXPECT_EQ(line, decorations.lines.size());
    EXPECT_GT(tensions.maxCoeff(), 0.0);

    // Capsules: two spheres each, at the capsule's ends as core's kinematics places them.
    const std::vector<BoneCapsule> capsules = calcBoneCapsules(model);
    ASSERT_EQ(decorations.spheres.size(), 2 * capsules.size());
    for (std::size_t c = 0; c < capsules.size(); ++c) {
        const std::size_t link = static_cast<std::size_t>(capsules[c].link);
        const Eigen::Vector3d a_G = data.p_GB[link] + data.R_GB[link] * capsules[c].a_B;
        EXPECT_LT(distance(decorations.spheres[2 * c].getTransform().p(), a_G), 1e-9);
        EXPECT_NEAR(decorations.spheres[2 * c].getRadius(), capsules[c].radius, 1e-15);
    }
    EXPECT_EQ(decorations.others, 0);
}

TEST(WireDecorations, GreyWithoutVelocities) {
    const Model model = readModelFile(SINEW_SOURCE_DIR "/models/arm26.yaml");
    const SimbodyModel system(model);
    const SimTK::State state = system.makeState(model.getDefaultQ(), Eigen::VectorXd::Zero(model.getNumU()),
                                                SimTK::Stage::Position);
    const Collector decorations = generate(system, state, ShadingScale{});
    ASSERT_FALSE(decorations.lines.empty());
    for (const SimTK::DecorativeLine& line : decorations.lines) EXPECT_EQ(line.getColor(), SimTK::Vec3(0.55));
}

}  // namespace
}  // namespace sinew
