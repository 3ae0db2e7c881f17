#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "arguments.hpp"
#include "commands.hpp"
#include "progress.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/model_loading.hpp"
#include "sinew/tensions/tension_method_registry.hpp"
#include "sinew/tools/tension_motion.hpp"

namespace sinew::cli {
namespace {

const char* kUsage =
    "usage: sinew tensions MODEL MOTION --method lp|qp|so|ipopt [options] -o TENSIONS.sto\n"
    "  Wire tensions per frame of a coordinates table (.mot/.sto): inverse dynamics (processed as OpenSim's\n"
    "  ID tool), the wire Jacobian, then the LP (least total tension), the QP (least squares), OpenSim's\n"
    "  static optimization (least squared activations) or ipopt (the QP's problem by Ipopt). DOFs no wire\n"
    "  reaches (a floating root) keep their generalized force as residual. Writes TENSIONS.sto, TENSIONS_report.sto (per frame: status 0 optimal,\n"
    "  1 infeasible, 2 failed; Z; active wires; ipopt 1 where the Ipopt fallback solved the frame;\n"
    "  residuals and phase-1 reserves per DOF: the least extra generalized force an infeasible frame\n"
    "  needs), TENSIONS_joint_loads.sto (per joint the load on its child link at the joint centre, child axes:\n"
    "  _mx _my _mz N m, _fx _fy _fz N; per loop _fx _fy _fz N on its link B), TENSIONS_ligament_stress.sto (Pa,\n"
    "  ligaments with a cross_section) and, for so, TENSIONS_activations.sto. Infeasible and failed frames are\n"
    "  kept and counted. Motion rows with NaN or empty cells are left out of the splines and written with\n"
    "  status 3 and zero tensions, their times listed. MODEL: .osim or .yaml.\n"
    "  --external-loads X.xml   OpenSim ExternalLoads (e.g. ground reactions)\n"
    "  --no-contact             without external loads, do not give the model's feet (its contacts: section)\n"
    "                           contact forces on the frames they touch the ground (TENSIONS_contact.sto)\n"
    "  --lowpass HZ             low-pass cut-off for the coordinates (default: no filtering)\n"
    "  --start T, --end T       time range, s (default: the whole motion)\n"
    "  --tolerance TAU          LP torque band, N m (default 1e-3)\n"
    "  --max-tension N          every wire's strength, N (default: each wire's own: its strength or\n"
    "                           its force law's max isometric force)\n"
    "  -o TENSIONS.sto          output file\n";

std::string withSuffix(const std::string& path, const std::string& suffix) {
    const std::filesystem::path p(path);
    return (p.parent_path() / (p.stem().string() + suffix + p.extension().string())).string();
}

void printSummary(const std::string& method, const TensionMotionSummary& summary) {
    std::printf("summary (%s): %d frames solved; per frame %.4g s median, %.4g s mean (inverse dynamics, J and "
                "the distribution), joint loads %.3g s median more; Z median %.4g, mean %.4g, max %.4g N^2 m^2\n",
                method.c_str(), summary.solvedFrames, summary.medianSeconds, summary.meanSeconds,
                summary.medianJointLoadSeconds, summary.medianZ, summary.meanZ, summary.maxZ);
    if (summary.contactFrames > 0)
        std::printf("contact (%s): %d frames with a foot down; root residual force median %.3g N, max %.3g N "
                    "(%.2f %% of the body weight, %.1f N)\n",
                    method.c_str(), summary.contactFrames, summary.medianRootResidual, summary.maxRootResidual,
                    100 * summary.maxRootResidual / summary.bodyWeight, summary.bodyWeight);
}

}  // namespace

int runTensions(const std::vector<std::string>& args) {
    std::string modelPath, motionPath, loadsPath, output, method;
    double maxTension = 0;
    TensionMotionOptions options;
    ArgumentReader reader(args, kUsage);
    while (reader.next()) {
        if (reader.is("--method")) method = reader.value();
        else if (reader.is("--external-loads")) loadsPath = reader.value();
        else if (reader.is("--no-contact")) options.contact = false;
        else if (reader.is("--lowpass")) options.lowpassCutoffHz = reader.number();
        else if (reader.is("--start")) options.startTime = reader.number();
        else if (reader.is("--end")) options.finalTime = reader.number();
        else if (reader.is("--tolerance")) options.analysis.problem.torqueTolerance = reader.number();
        else if (reader.is("--max-tension")) {
            maxTension = reader.number();
            if (!(maxTension > 0)) throw Error("--max-tension expects a strength > 0 N, got " + reader.value());
        }
        else if (reader.is("-o", "--output")) output = reader.value();
        else reader.takePositional({&modelPath, &motionPath});
    }
    if (reader.helpShown()) return 0;
    if (modelPath.empty() || motionPath.empty() || output.empty() || method.empty()) return reader.failWithUsage();
    TensionMethodRegistry::global().get(method);  // an unknown method fails before the model loads
    options.analysis.method = method;
    const Model model = loadModel(modelPath, [](const std::string& note) { std::printf("%s\n", note.c_str()); });
    if (maxTension > 0) options.analysis.maxTension = Eigen::VectorXd::Constant(model.getNumWires(), maxTension);
    std::optional<ExternalLoads> loads;
    if (!loadsPath.empty()) loads = readExternalLoads(loadsPath);
    std::optional<Progress> progress;
    options.onFrame = [&](int frame, int frames) {
        if (!progress) progress.emplace("tensions (" + method + ")", frames);
        progress->update(frame);
    };
    const StorageTable motion = readStorageFile(motionPath, NonFinite::Allow);
    checkLowpassOption(options.lowpassCutoffHz, motion, motionPath);
    const TensionMotionResult result = runTensionAnalysis(model, motion, loads ? &*loads : nullptr, options);
    if (progress) progress->finish();
    const std::filesystem::path parent = std::filesystem::path(output).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    // One set: an earlier run's activations must not stay beside tensions of another method.
    OutputFileSet outputs;
    writeStorageFile(result.tensions, outputs, output);
    writeStorageFile(result.report, outputs, withSuffix(output, "_report"));
    const auto writeUnlessEmpty = [&](const StorageTable& table, const std::string& suffix) {
        if (!table.columns.empty())
            writeStorageFile(table, outputs, withSuffix(output, suffix));
        else
            outputs.retire(withSuffix(output, suffix));
    };
    writeUnlessEmpty(result.activations, "_activations");
    writeUnlessEmpty(result.contact, "_contact");
    writeUnlessEmpty(result.jointLoads, "_joint_loads");
    writeUnlessEmpty(result.ligamentStress, "_ligament_stress");
    outputs.commit();
    std::printf("%zu frames, %zu wires (%s) -> %s\n", result.tensions.times.size(), result.tensions.columns.size(),
                method.c_str(), output.c_str());
    if (!result.missingRows.empty()) {
        std::printf("%zu motion rows have NaN or empty coordinates and were skipped (status 3, zero tensions):",
                    result.missingRows.size());
        const std::size_t listed = std::min<std::size_t>(result.missingRows.size(), 10);
        for (std::size_t k = 0; k < listed; ++k) {
            const int row = result.missingRows[k];
            std::printf("%s row %d (t = %g s)", k ? "," : "", row + 1, motion.times[static_cast<std::size_t>(row)]);
        }
        if (listed < result.missingRows.size()) std::printf(", and %zu more", result.missingRows.size() - listed);
        std::printf("\n");
    }
    if (result.flaggedFrames > 0)
        std::printf("%d of %zu frames flagged: %d infeasible (status 1), %d failed (status 2), %zu missing input "
                    "(status 3); see status and residuals in %s\n",
                    result.flaggedFrames, result.tensions.times.size(), result.infeasibleFrames, result.failedFrames,
                    result.missingRows.size(), withSuffix(output, "_report").c_str());
    if (result.ipoptFrames > 0)
        std::printf("%d frames solved by Ipopt (report column ipopt = 1)\n", result.ipoptFrames);
    printSummary(method, summarizeTensionMotion(model, result));
    return 0;
}

}  // namespace sinew::cli
