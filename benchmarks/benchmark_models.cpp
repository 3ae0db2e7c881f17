#include "benchmark_models.hpp"

#include <algorithm>
#include <limits>
#include <random>
#include <stdexcept>
#include <tuple>

#include "fused_wire_force.hpp"
#include "sinew/core/assembly_schedule.hpp"
#include "sinew/core/data.hpp"
#include "sinew/core/forward_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "support/random_model.hpp"
#include "sinew/core/virtual_link_equilibrium.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/model_file.hpp"

namespace sinew_benchmarks {
namespace {

using Topology = sinew::RandomModelOptions::Topology;

// Free root, ball joints only (pinFraction 0), no virtual links: Simbody cannot compute accelerations for
// massless free bodies, and the peer must run on the same model. At most one via point, so a wire has 2.5
// points on average (the human body's wires have about 2.75).
sinew::Model makeRandomModel(Topology topology, int numLinks, int numLoops, int numWires) {
    sinew::RandomModelOptions options;
    options.numLinks = numLinks;
    options.topology = topology;
    options.rootJoint = sinew::JointType::Free;
    options.pinFraction = 0;
    options.numLoops = numLoops;
    options.numWires = numWires;
    options.maxViaPoints = 1;
    options.numVirtualLinks = 0;
    options.seed = 1;
    return sinew::generateRandomModel(options);
}

// max |a - b| / scale; infinite when either is not finite.
double calcUdotDifference(const Eigen::VectorXd& a, const Eigen::VectorXd& b, double scale) {
    if (!a.allFinite() || !b.allFinite()) return std::numeric_limits<double>::infinity();
    return (a - b).lpNorm<Eigen::Infinity>() / scale;
}

}  // namespace

std::vector<ModelSpec> getModelTable() {
    std::vector<ModelSpec> table;
    table.push_back({"arm26", "arm26", "wires", true,
                     [] { return sinew::readModelFile(SINEW_SOURCE_DIR "/models/arm26.yaml"); }});
    // sinew's shipped whole-body wire model (models/whole_body; docs/whole-body-model.md), virtual links and all.
    table.push_back({"whole_body_model", "whole_body_model", "shipped", true,
                     [] { return sinew::readModelFile(SINEW_SOURCE_DIR "/models/whole_body/whole_body.yaml"); }});
    // The whole human body's size (53 links, 162 dof, 4 loops, 547 wires), and the same tree with fewer
    // features, to show what each costs. The tree does not depend on the loops and wires drawn after it.
    for (const auto& [suffix, variant, numLoops, numWires] :
         {std::tuple<const char*, const char*, int, int>{"", "loops_wires", 4, 547}, {"_bare", "bare", 0, 0},
          {"_loops", "loops", 4, 0}, {"_wires", "wires", 0, 547}}) {
        table.push_back({std::string("wholebody") + suffix, "wholebody", variant, numLoops && numWires,
                         [numLoops = numLoops, numWires = numWires] {
                             return makeRandomModel(Topology::RandomTree, 53, numLoops, numWires);
                         }});
    }
    const std::pair<const char*, Topology> families[] = {{"chain", Topology::Chain}, {"tree", Topology::BinaryTree}};
    for (const auto& [family, topology] : families) {
        for (int n : {10, 30, 100, 300, 1000}) {
            for (const bool loops : {false, true}) {
                for (const bool wires : {false, true}) {
                    // A few loops, growing with the model: one per 50 links.
                    const int numLoops = loops ? std::max(1, n / 50) : 0;
                    const int numWires = wires ? 10 * n : 0;
                    const std::string variant = loops && wires ? "loops_wires" : loops ? "loops" : wires ? "wires" : "bare";
                    const std::string name = family + std::to_string(n) + (variant == "bare" ? "" : "_" + variant);
                    // The wire benchmarks do not depend on the loops: run them once per size.
                    table.push_back({name, family, variant, wires && !loops,
                                     [topology = topology, n, numLoops, numWires] {
                                         return makeRandomModel(topology, n, numLoops, numWires);
                                     }});
                }
            }
        }
    }
    return table;
}

ModelFixture::ModelFixture(sinew::Model model) : model_(std::move(model)), census_(sinew::calcCensus(model_)) {}

ModelFixture::~ModelFixture() = default;

void ModelFixture::prepare() {
    if (prepared_) return;
    prepared_ = true;
    simbody_ = std::make_unique<sinew::SimbodyModel>(model_);
    SimTK::Force::DiscreteForces generalizedForces(simbody_->updForces(), simbody_->getMatter());
    simbody_->updSystem().realizeTopology();
    const SimTK::MultibodySystem& system = simbody_->getSystem();

    // An assembled state near the default pose (or at it, where random loops lock the mechanism so that
    // the perturbed pose cannot be assembled), with loop-consistent speeds: the recipe of
    // tests/plugin/test_forward_dynamics.cpp.
    std::mt19937 rng(2024);
    const Eigen::VectorXd u0 = sinew::generateRandomSpeeds(model_, rng, 2.0);
    const Eigen::VectorXd q0 = sinew::integrateCoordinates(model_, model_.getDefaultQ(),
                                                           sinew::generateRandomSpeeds(model_, rng), 0.2);
    SimTK::State state = simbody_->makeState(q0, u0, SimTK::Stage::Position);
    try {
        system.project(state, 1e-13);
    } catch (const std::exception&) {
        projectionFellBack_ = true;
        state = simbody_->makeState(model_.getDefaultQ(), u0, SimTK::Stage::Position);
    }
    system.realize(state, SimTK::Stage::Velocity);
    // Long chains with many loops miss 1e-13 by roundoff (chain1000_loops: ~7e-13 on exit); accept the
    // tightest accuracy Simbody reaches. Both engines then take the same u as given.
    for (const double accuracy : {1e-13, 1e-10, 1e-8}) {
        SimTK::State projected = state;
        try {
            system.projectU(projected, accuracy);
        } catch (const std::exception&) {
            continue;
        }
        state = projected;
        break;
    }
    // Virtual links have no body in Simbody (they come last in sinew's u) and take no generalized force.
    const int nuSimbody = state.getNU();
    tau_ = sinew::generateRandomSpeeds(model_, rng, 5.0);
    tau_.tail(model_.getNumU() - nuSimbody).setZero();
    generalizedForces.setAllMobilityForces(state, sinew::toSimTK(Eigen::VectorXd(tau_.head(nuSimbody))));
    system.realize(state, SimTK::Stage::Acceleration);
    simbody_->calcCoordinates(state, q_, u_);  // the virtual links at Simbody's equilibrium
    Eigen::VectorXd udotSimbody = Eigen::VectorXd::Zero(model_.getNumU());
    udotSimbody.head(nuSimbody) = sinew::toEigen(state.getUDot());

    sinew::Data data(model_);
    sinew::calcPositionKinematics(model_, data, q_);
    sinew::calcVelocityKinematics(model_, data, u_);
    sinew::calcWirePaths(model_, data);
    sinew::calcWireSpeeds(model_, data);
    sinew::VirtualLinkEquilibriumData equilibrium(model_);
    sinew::calcVirtualLinkEquilibrium(model_, data, state.getTime(), equilibrium);
    Eigen::VectorXd tensions(model_.getNumWires());
    sinew::calcWireTensions(model_, data, state.getTime(), tensions);
    sinew::calcWireLinkForces(model_, data, tensions);
    const sinew::AssemblySchedule schedule(model_);
    sinew::ForwardDynamicsData fd(model_, schedule);
    sinew::calcForwardDynamics(model_, schedule, data, tau_, data.F_G, fd);

    SimTK::Vector udotFree;
    SimTK::Vector_<SimTK::SpatialVec> bodyAccelerations;
    simbody_->getMatter().calcAccelerationIgnoringConstraints(
        state, system.getMobilityForces(state, SimTK::Stage::Dynamics),
        system.getRigidBodyForces(state, SimTK::Stage::Dynamics), udotFree, bodyAccelerations);
    const double scale = std::max({udotSimbody.lpNorm<Eigen::Infinity>(),
                                   sinew::toEigen(udotFree).lpNorm<Eigen::Infinity>(), 1e-300});
    udotSinew_ = fd.udot;
    udotSimbody_ = udotSimbody;
    udotScale_ = scale;
    udotDifference_ = calcUdotDifference(udotSinew_, udotSimbody, udotScale_);
    simbodyState_ = std::make_unique<SimTK::State>(state);
}

double ModelFixture::calcUdotDifferenceFromSimbody(const Eigen::VectorXd& udot) const {
    return calcUdotDifference(udot, udotSimbody_, udotScale_);
}

void ModelFixture::prepareFused() {
    if (fused_) return;
    prepare();
    sinew::SimbodyModelOptions options;
    options.wires = false;
    fused_ = std::make_unique<sinew::SimbodyModel>(model_, options);
    std::vector<SimTK::MobilizedBodyIndex> bodies;
    for (int link = 0; link < model_.getNumLinks(); ++link)
        bodies.push_back(fused_->getMobilizedBody(link).getMobilizedBodyIndex());
    SimTK::Force::Custom(fused_->updForces(), new FusedWireForce(fused_->getMatter(), model_, bodies));  // owns it
    SimTK::Force::DiscreteForces generalizedForces(fused_->updForces(), fused_->getMatter());
    fused_->updSystem().realizeTopology();
    SimTK::State state = fused_->makeState(q_, u_, SimTK::Stage::Velocity);
    generalizedForces.setAllMobilityForces(state, sinew::toSimTK(tau_));
    fused_->getSystem().realize(state, SimTK::Stage::Acceleration);
    fusedUdotDifference_ = calcUdotDifference(udotSinew_, sinew::toEigen(state.getUDot()), udotScale_);
    fusedState_ = std::make_unique<SimTK::State>(state);
}

void ModelFixture::setCounters(benchmark::State& state) const {
    state.counters["links"] = census_.links;
    state.counters["dof"] = census_.dof;
    state.counters["wires"] = census_.wires;
    state.counters["wire_points"] = census_.wirePoints;
    state.counters["loops"] = census_.loops;
}

std::string ModelFixture::describe() const {
    return "links=" + std::to_string(census_.links) + " dof=" + std::to_string(census_.dof) +
           " nq=" + std::to_string(model_.getNumQ()) + " wires=" + std::to_string(census_.wires) +
           " wire_points=" + std::to_string(census_.wirePoints) + " loops=" + std::to_string(census_.loops) +
           " virtual_links=" + std::to_string(census_.virtualLinks);
}

}  // namespace sinew_benchmarks
