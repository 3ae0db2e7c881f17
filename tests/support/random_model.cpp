#include "support/random_model.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "sinew/core/data.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/model_builder.hpp"

namespace sinew {
namespace {

double uniform(std::mt19937& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

int uniformInt(std::mt19937& rng, int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }

Eigen::Vector3d uniformVector(std::mt19937& rng, double halfWidth) {
    return Eigen::Vector3d(uniform(rng, -halfWidth, halfWidth), uniform(rng, -halfWidth, halfWidth),
                           uniform(rng, -halfWidth, halfWidth));
}

Eigen::Quaterniond uniformRotation(std::mt19937& rng) {
    std::normal_distribution<double> normal;
    return Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
}

std::string linkName(int i) { return "link" + std::to_string(i); }

int pickParent(const RandomModelOptions& options, std::mt19937& rng, int child) {
    switch (options.topology) {
        case RandomModelOptions::Topology::Chain: return child - 1;
        case RandomModelOptions::Topology::BinaryTree: return (child - 1) / 2;
        case RandomModelOptions::Topology::RandomTree: return uniformInt(rng, 0, child - 1);
    }
    return child - 1;
}

Eigen::Vector3d uniformDirection(std::mt19937& rng) {
    std::normal_distribution<double> normal;
    return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
}

// A random function of a coordinate for a custom joint's axis, displacements of about `size` (rad or m).
Function randomFunction(std::mt19937& rng, double size) {
    const int kind = uniformInt(rng, 0, 3);
    if (kind == 0) return Function::linear(uniform(rng, -1, 1), uniform(rng, -size, size));
    if (kind == 1) return Function::polynomial({uniform(rng, -0.1, 0.1) * size, uniform(rng, -0.3, 0.3) * size,
                                                uniform(rng, -size, size), uniform(rng, -size, size)});
    std::vector<double> x{-2.0}, y;
    while (x.back() < 2.0) x.push_back(std::min(2.0, x.back() + uniform(rng, 0.3, 1.2)));
    for (std::size_t k = 0; k < x.size(); ++k) y.push_back(uniform(rng, -size, size));
    const Function spline = kind == 2 ? Function::simmSpline(x, y) : Function::naturalCubicSpline(x, y);
    return uniform(rng, 0, 1) < 0.5 ? spline.multipliedBy(uniform(rng, 0.8, 1.2)) : spline;
}

// A custom joint on random, well separated axes. A root joint drives each axis linearly by a coordinate of
// its own; others have 1-3 coordinates, each the linear driver of a rotation, and the remaining axes
// constant or coupled. Two layouts where Simbody's FunctionBased mobilizer departs from the derivatives of
// its own X_FM are left out, since these models are compared against Simbody (docs/opensim-joints.md,
// "Simbody's FunctionBased"): constant rotations are zero (as in OpenSim's models), and rotation 3 is never
// coupled to the joint's first coordinate while rotation 2 moves.
void makeRandomCustomJoint(std::mt19937& rng, bool root, JointSpec& joint) {
    joint.type = JointType::Custom;
    joint.transformAxes.assign(6, TransformAxisSpec{});
    for (int group = 0; group < 6; group += 3) {
        Eigen::Matrix3d axes;
        do {
            for (int k = 0; k < 3; ++k) axes.col(k) = uniformDirection(rng);
        } while (std::abs(axes.determinant()) < 0.3);
        for (int k = 0; k < 3; ++k) joint.transformAxes[static_cast<std::size_t>(group + k)].axis = axes.col(k);
    }
    const int numCoordinates = root ? 6 : uniformInt(rng, 1, 3);
    for (int c = 0; c < numCoordinates; ++c) {
        CoordinateSpec coordinate;
        coordinate.name = joint.name + "_q" + std::to_string(c);
        joint.coordinates.push_back(coordinate);
    }
    const int numDriven = std::min(numCoordinates, 3);
    for (;;) {
        std::vector<int> driven{0, 1, 2};  // rotation axes given a linear driver (the first numDriven)
        std::shuffle(driven.begin(), driven.end(), rng);
        for (int k = 0; k < 6; ++k) {
            TransformAxisSpec& axis = joint.transformAxes[static_cast<std::size_t>(k)];
            const auto driver = std::find(driven.begin(), driven.begin() + numDriven, k);
            axis.function.reset();
            if (root) {
                axis.coordinate = joint.coordinates[static_cast<std::size_t>(k)].name;
            } else if (driver != driven.begin() + numDriven) {
                axis.coordinate = joint.coordinates[static_cast<std::size_t>(driver - driven.begin())].name;
            } else if (uniform(rng, 0, 1) < 0.6) {
                axis.coordinate = joint.coordinates[static_cast<std::size_t>(uniformInt(rng, 0, numCoordinates - 1))].name;
                axis.function = randomFunction(rng, k < 3 ? 0.3 : 0.02);
            } else {
                axis.coordinate.clear();
                axis.function = Function::constant(k < 3 ? 0.0 : uniform(rng, -0.02, 0.02));
            }
        }
        // The first coordinate in axis order becomes the joint's q0 (the builder orders them so).
        std::string first;
        for (const TransformAxisSpec& axis : joint.transformAxes)
            if (first.empty()) first = axis.coordinate;
        if (joint.transformAxes[1].coordinate.empty() || joint.transformAxes[2].coordinate != first) return;
    }
}

// A wire's points before its force law is known, with the default-pose positions needed to pick one.
struct DraftWire {
    WireSpec spec;
    double defaultLength = 0;
};

}  // namespace

Model generateRandomModel(const RandomModelOptions& options) {
    std::mt19937 rng(options.seed);
    ModelBuilder tree("random" + std::to_string(options.numLinks));
    std::vector<int> parent(static_cast<std::size_t>(options.numLinks), kGround);
    for (int i = 0; i < options.numLinks; ++i) {
        LinkSpec link;
        link.name = linkName(i);
        link.mass = uniform(rng, 0.5, 5.0);
        link.com_B = Eigen::Vector3d(0, -0.12, 0) + uniformVector(rng, 0.03);
        // Principal moments within a factor of two of each other always satisfy the triangle inequality.
        const Eigen::Vector3d moments = link.mass * 0.01 * Eigen::Vector3d(uniform(rng, 0.5, 1), uniform(rng, 0.5, 1),
                                                                           uniform(rng, 0.5, 1));
        const Eigen::Matrix3d R = uniformRotation(rng).toRotationMatrix();
        link.inertia_Bcom = R * moments.asDiagonal() * R.transpose();
        tree.addLink(link);

        JointSpec joint;
        joint.name = "joint" + std::to_string(i);
        joint.child = link.name;
        if (i == 0) {
            joint.type = options.rootJoint;
            joint.parent = "ground";
            if (joint.type == JointType::Pin) joint.axis = uniformVector(rng, 1).normalized();
            if (joint.type == JointType::Custom) makeRandomCustomJoint(rng, true, joint);
        } else {
            parent[static_cast<std::size_t>(i)] = pickParent(options, rng, i);
            joint.parent = linkName(parent[static_cast<std::size_t>(i)]);
            joint.p_PF = Eigen::Vector3d(0, -0.25, 0) + uniformVector(rng, 0.08);
            joint.p_BM = uniformVector(rng, 0.02);
            joint.type = uniform(rng, 0, 1) < options.pinFraction ? JointType::Pin : JointType::Ball;
            if (joint.type == JointType::Pin) joint.axis = uniformVector(rng, 1).normalized();
            // Drawn only when asked for, so models without custom joints keep their seeds' shapes.
            if (options.customJointFraction > 0 && uniform(rng, 0, 1) < options.customJointFraction) {
                joint.axis.reset();
                makeRandomCustomJoint(rng, false, joint);
            }
        }
        tree.addJoint(joint);
    }

    // Default pose of the bare tree, to place loop closures and virtual links and to size the wires.
    const Model bare = tree.build();
    Data data(bare);
    calcPositionKinematics(bare, data, bare.getDefaultQ());
    // The builder stores links parents-first, so generator index i ("link<i>") maps to another model index.
    std::vector<std::size_t> modelIndex;
    for (int i = 0; i < options.numLinks; ++i) modelIndex.push_back(static_cast<std::size_t>(bare.findLinkIndex(linkName(i))));
    auto inLink = [&](int link, const Eigen::Vector3d& p_G) -> Eigen::Vector3d {
        const std::size_t b = modelIndex[static_cast<std::size_t>(link)];
        return data.R_GB[b].transpose() * (p_G - data.p_GB[b]);
    };
    // Virtual links follow the real ones; each starts unrotated at its fork point.
    std::vector<Eigen::Vector3d> forks_G;
    auto toGround = [&](int link, const Eigen::Vector3d& p_B) -> Eigen::Vector3d {
        if (link >= options.numLinks) return forks_G[static_cast<std::size_t>(link - options.numLinks)] + p_B;
        const std::size_t b = modelIndex[static_cast<std::size_t>(link)];
        return data.p_GB[b] + data.R_GB[b] * p_B;
    };

    ModelBuilder builder = tree;
    for (int c = 0; c < options.numLoops && options.numLinks >= 2; ++c) {
        const int a = uniformInt(rng, 0, options.numLinks - 1);
        int b = uniformInt(rng, 0, options.numLinks - 2);
        if (b >= a) ++b;
        auto comInGround = [&](int link) {
            return toGround(link, bare.getLinks()[modelIndex[static_cast<std::size_t>(link)]].com_B);
        };
        const Eigen::Vector3d p_G = 0.5 * (comInGround(a) + comInGround(b)) +
                                    uniformVector(rng, 0.02);
        builder.addLoop({"loop" + std::to_string(c), linkName(a), inLink(a, p_G), linkName(b), inLink(b, p_G), ""});
    }

    std::vector<DraftWire> drafts;
    auto addPoint = [&](DraftWire& draft, int link, const Eigen::Vector3d& p_B, const Eigen::Vector3d*& previous_G,
                        Eigen::Vector3d& storage) {
        const std::string name = link < options.numLinks ? linkName(link) : "virtual" + std::to_string(link - options.numLinks);
        draft.spec.points.push_back({name, p_B, ""});
        const Eigen::Vector3d p_G = toGround(link, p_B);
        if (previous_G) draft.defaultLength += (p_G - *previous_G).norm();
        storage = p_G;
        previous_G = &storage;
    };
    const WireKind kinds[] = {WireKind::Muscle, WireKind::Tendon, WireKind::Ligament, WireKind::Cartilage};
    for (int w = 0; w < options.numWires; ++w) {
        // The joints a wire crosses: one to three steps from its insertion link (never the root, when
        // there is another) towards the root.
        std::vector<int> path{uniformInt(rng, options.numLinks > 1 ? 1 : 0, options.numLinks - 1)};
        const int hops = uniformInt(rng, 1, 3);
        for (int h = 0; h < hops && parent[static_cast<std::size_t>(path.back())] != kGround; ++h)
            path.push_back(parent[static_cast<std::size_t>(path.back())]);
        std::reverse(path.begin(), path.end());  // origin link first
        DraftWire draft;
        draft.spec.name = "wire" + std::to_string(w);
        draft.spec.kind = kinds[uniformInt(rng, 0, 3)];
        const int numPoints = 2 + uniformInt(rng, 0, options.maxViaPoints);
        std::vector<int> pointLinks{path.front()};
        for (int k = 1; k + 1 < numPoints; ++k) pointLinks.push_back(path[static_cast<std::size_t>(uniformInt(rng, 0, static_cast<int>(path.size()) - 1))]);
        std::sort(pointLinks.begin() + 1, pointLinks.end(), [&](int x, int y) {
            return std::find(path.begin(), path.end(), x) < std::find(path.begin(), path.end(), y);
        });
        pointLinks.push_back(path.back());
        const Eigen::Vector3d* previous = nullptr;
        Eigen::Vector3d storage;
        for (int link : pointLinks)
            addPoint(draft, link, Eigen::Vector3d(0, -0.12, 0) + uniformVector(rng, 0.06), previous, storage);
        drafts.push_back(draft);
    }
    for (int v = 0; v < options.numVirtualLinks; ++v) {
        const int virtualLink = options.numLinks + v;
        const int heads[2] = {uniformInt(rng, 0, options.numLinks - 1), uniformInt(rng, 0, options.numLinks - 1)};
        const int tail = uniformInt(rng, 0, options.numLinks - 1);
        forks_G.push_back((toGround(heads[0], Eigen::Vector3d::Zero()) + toGround(heads[1], Eigen::Vector3d::Zero()) +
                           toGround(tail, Eigen::Vector3d::Zero())) / 3.0 + uniformVector(rng, 0.05));
        builder.addVirtualLink({"virtual" + std::to_string(v), forks_G.back(), ""});
        for (int part = 0; part < 3; ++part) {
            DraftWire draft;
            draft.spec.name = "virtual" + std::to_string(v) + (part < 2 ? "_head" + std::to_string(part) : "_tail");
            draft.spec.kind = WireKind::Muscle;
            const Eigen::Vector3d* previous = nullptr;
            Eigen::Vector3d storage;
            const Eigen::Vector3d onVirtual = uniformVector(rng, 0.01);
            const int bone = part < 2 ? heads[part] : tail;
            const Eigen::Vector3d onBone = Eigen::Vector3d(0, -0.12, 0) + uniformVector(rng, 0.06);
            if (part < 2) {
                addPoint(draft, bone, onBone, previous, storage);
                addPoint(draft, virtualLink, onVirtual, previous, storage);
            } else {
                addPoint(draft, virtualLink, onVirtual, previous, storage);
                addPoint(draft, bone, onBone, previous, storage);
            }
            drafts.push_back(draft);
        }
    }
    for (DraftWire& draft : drafts) {
        const bool soft = draft.spec.kind == WireKind::Muscle;
        const double stiffness = soft ? uniform(rng, 200, 2000) : uniform(rng, 5e3, 2e4);
        const double restLength = std::max(1e-3, draft.defaultLength * uniform(rng, 0.9, 1.0));
        draft.spec.law.type = "spring_damper";
        draft.spec.law.parameters.set("stiffness", {stiffness});
        draft.spec.law.parameters.set("damping", {options.damping});
        draft.spec.law.parameters.set("rest_length", {restLength});
        builder.addWire(draft.spec);
    }
    return builder.build();
}

Eigen::VectorXd generateRandomCoordinates(const Model& model, std::mt19937& rng) {
    Eigen::VectorXd q = model.getDefaultQ();
    for (const Joint& joint : model.getJoints()) {
        if (joint.type == JointType::Free || joint.type == JointType::Ball) {
            const Eigen::Quaterniond r = uniformRotation(rng);
            q.segment<4>(joint.qStart) << r.w(), r.x(), r.y(), r.z();
        }
        if (joint.type == JointType::Free) q.segment<3>(joint.qStart + 4) = uniformVector(rng, 1.0);
        if (joint.type == JointType::Pin) q[joint.qStart] = uniform(rng, -M_PI, M_PI);
        if (joint.type == JointType::Custom)
            for (int k = 0; k < joint.nq; ++k) q[joint.qStart + k] = uniform(rng, -2.5, 2.5);
    }
    return q;
}

Eigen::VectorXd generateRandomSpeeds(const Model& model, std::mt19937& rng, double scale) {
    Eigen::VectorXd u(model.getNumU());
    for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = uniform(rng, -scale, scale);
    return u;
}

}  // namespace sinew
