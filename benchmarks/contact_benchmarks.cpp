// Tensions with foot contact on the whole-body model: Contact/<lp|qp>/whole_body/<still|swing>. One frame is
// TensionAnalysis::calcFrame (inverse dynamics, wire paths and Jacobian, contact columns, the distribution)
// with all four feet down (tools/contact_detection.hpp finds them so): "still" repeats the neutral stance
// (warm, nothing changes), "swing" cycles through the first 7 frames of the right-hip swing the tests use
// (tests/tools/test_tension_contact.cpp), reset when it wraps. Wires are given their strength as there.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "sinew/io/model_file.hpp"
#include "sinew/tensions/contact_columns.hpp"
#include "sinew/tools/tension_analysis.hpp"

namespace sinew {
namespace {

const Model& getWholeBody() {
    static const Model model = readModelFile(std::string(SINEW_SOURCE_DIR) + "/models/whole_body/whole_body.yaml");
    return model;
}

// q, u, udot of frame i of the swing: still for 5 frames, then the right hip flexing about -y.
void makeSwingFrame(const Model& model, int i, Eigen::VectorXd& q, Eigen::VectorXd& u, Eigen::VectorXd& udot) {
    const Joint& hip = model.getJoint(model.findLinkIndex("femur_r"));
    const Eigen::Vector3d axis(0, -1, 0);
    const double s = i < 5 ? 0 : (i - 4) * 0.02 / 0.6, a = 0.25;
    q = model.getDefaultQ();
    u.setZero(model.getNumU());
    udot.setZero(model.getNumU());
    const Eigen::Quaterniond rotation(Eigen::AngleAxisd(a * (1 - std::cos(M_PI * s)), axis));
    q.segment<4>(hip.qStart) << rotation.w(), rotation.x(), rotation.y(), rotation.z();
    u.segment<3>(hip.uStart) = a * M_PI / 0.6 * std::sin(M_PI * s) * axis;
    udot.segment<3>(hip.uStart) = (i >= 5) * a * std::pow(M_PI / 0.6, 2) * std::cos(M_PI * s) * axis;
}

void benchmarkContactFrame(benchmark::State& state, const std::string& method, bool swing) {
    const Model& model = getWholeBody();
    Eigen::VectorXd strength(model.getNumWires());
    for (int w = 0; w < model.getNumWires(); ++w) {
        const Wire& wire = model.getWire(w);
        const ForceLawParameters& p = wire.lawSpec.parameters;
        strength[w] = wire.kind == WireKind::Muscle ? p.getScalar("stiffness") * p.getScalar("rest_length") / 0.98 : 2000.0;
    }
    auto contacts = std::make_shared<ContactColumns>(model);
    contacts->setInContact(std::vector<char>(model.getContacts().size(), 1));
    TensionAnalysisOptions options;
    options.method = method;
    options.maxTension = strength;
    options.columns = {contacts};
    TensionAnalysis analysis(model, options);
    const std::vector<SpatialVector> noLoads(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
    std::vector<Eigen::VectorXd> q(7), u(7), udot(7);
    for (int i = 0; i < 7; ++i) makeSwingFrame(model, i, q[i], u[i], udot[i]);
    int frame = 0, optimal = 0, frames = 0;
    analysis.calcFrame(q[0], u[0], udot[0], noLoads);  // the first, cold solve is not the per-frame cost
    for (auto _ : state) {
        if (swing && frame == 0) analysis.reset();
        const TensionFrame& result = analysis.calcFrame(q[frame], u[frame], udot[frame], noLoads);
        optimal += result.status == DistributionStatus::Optimal;
        ++frames;
        frame = swing ? (frame + 1) % 7 : 0;
    }
    state.counters["wires"] = model.getNumWires();
    state.counters["contact_columns"] = contacts->count();
    state.counters["optimal_share"] = frames ? static_cast<double>(optimal) / frames : 0;
}

void registerContactBenchmarks() {
    for (const char* method : {"lp", "qp"})
        for (const bool swing : {false, true})
            benchmark::RegisterBenchmark(
                ("Contact/" + std::string(method) + "/whole_body/" + (swing ? "swing" : "still")).c_str(),
                [method, swing](benchmark::State& state) { benchmarkContactFrame(state, method, swing); })
                ->Unit(benchmark::kMillisecond);
}

const bool kRegistered = (registerContactBenchmarks(), true);

}  // namespace
}  // namespace sinew
