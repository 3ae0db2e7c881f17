#pragma once
// Random link trees with loops, wires and virtual links, for tests and benchmarks. Reproducible from a seed.
#include <Eigen/Core>
#include <random>

#include "sinew/core/model.hpp"

namespace sinew {

struct RandomModelOptions {
    enum class Topology { Chain, BinaryTree, RandomTree };
    int numLinks = 10;
    Topology topology = Topology::RandomTree;
    // free, ball (a pendulum), pin, weld, or custom (six coordinates, one per axis, as OpenSim's ground_pelvis)
    JointType rootJoint = JointType::Free;
    double pinFraction = 0.2;  // share of non-root joints that are pins instead of balls
    // Share of non-root joints that are custom joints: 1-3 coordinates on random axes, each driving a rotation
    // linearly, the other axes constant or coupled to a coordinate through splines, polynomials, multipliers.
    double customJointFraction = 0;
    int numLoops = 0;          // ball closures between random link pairs, assembled at the default pose
    int numWires = 20;         // wires spanning 1 to 3 joints (0 in a one-link model)
    int maxViaPoints = 2;
    int numVirtualLinks = 0;   // each carries a forked wire: two heads in, one tail out
    double damping = 1.0;      // N*s/m on every wire (0 for conservative models)
    unsigned seed = 1;
};

// The wires are spring-dampers, taut at the default pose (rest length 0.9 to 1 times the default length);
// muscles soft, tendons, ligaments and cartilage stiff.
Model generateRandomModel(const RandomModelOptions& options);

// Random coordinates: unit quaternions uniformly distributed, pin angles in [-pi, pi], translations in
// [-1, 1] m, custom joints' coordinates in [-2.5, 2.5] (their splines' knots span [-2, 2]).
Eigen::VectorXd generateRandomCoordinates(const Model& model, std::mt19937& rng);
// Random speeds, uniform in [-scale, scale].
Eigen::VectorXd generateRandomSpeeds(const Model& model, std::mt19937& rng, double scale = 1.0);

}  // namespace sinew
