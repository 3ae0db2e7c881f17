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
    "usage: sinew tensions MODEL MOTION --method lp|qp|so|ipopt[,...] [options] -o TENSIONS.sto\n"
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
    "  --method M1,M2,...       several methods in turn, each writing TENSIONS_<method>.sto and its files,\n"
    "                           then a table of them side by side (s/frame, Z; the paper's Table 2) and on\n"
    "                           how many frames each later method's Z is at most the first's\n"
    "  --tolerance TAU          LP torque band, N m (default 1e-3)\n"
    "  --max-tension N          every wire's strength, N (default: each wire's own: its strength or\n"
    "                           its force law's max isometric force)\n"
    "  -o TENSIONS.sto          output file\n";

std::string withSuffix(const std::string& path, const std::string& suffix) {
    const std::filesystem::path p(path);
    return (p.parent_path() / (p.stem().string() + suffix + p.extension().string())).string();
}

// "lp,qp" -> {"lp", "qp"}; each named once.
std::vector<std::string> splitMethods(const std::string& list) {
    std::vector<std::string> methods;
    std::size_t begin = 0;
    for (;;) {
        const std::size_t end = list.find(',', begin);
        const std::string method = list.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
        if (method.empty() || std::find(methods.begin(), methods.end(), method) != methods.end())
            throw Error("--method expects method names separated by commas, each once (e.g. lp,qp), got '" + list + "'");
        methods.push_back(method);
        if (end == std::string::npos) return methods;
        begin = end + 1;
    }
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

// The run's files as one set: an earlier run's activations must not stay beside tensions of another method.
void writeTensionOutputs(const TensionMotionResult& result, const std::string& output) {
    const std::filesystem::path parent = std::filesystem::path(output).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
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
}

void printRunNotes(const TensionMotionResult& result, const StorageTable& motion, const std::string& method,
                   const std::string& output) {
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
}

// The methods side by side (the paper's Table 2: seconds per frame and Z), and how often each later method's
// Z is at most the first's on the same frame.
void printComparison(const std::vector<std::string>& methods, const std::vector<TensionMotionSummary>& summaries,
                     const std::vector<TensionMotionResult>& results) {
    std::printf("\n%-8s %7s %11s %13s %15s %13s %13s\n", "method", "frames", "infeasible", "s/frame mean",
                "s/frame median", "Z mean", "Z median");
    for (std::size_t m = 0; m < methods.size(); ++m)
        std::printf("%-8s %7d %11d %13.4g %15.4g %13.4g %13.4g\n", methods[m].c_str(), summaries[m].solvedFrames,
                    results[m].infeasibleFrames, summaries[m].meanSeconds, summaries[m].medianSeconds,
                    summaries[m].meanZ, summaries[m].medianZ);
    std::printf("(Z = 1/2 |tau - A x|^2 per frame, N^2 m^2, over every DOF, the root's included)\n");
    for (std::size_t m = 1; m < methods.size(); ++m)
        std::printf("Z(%s) <= Z(%s) on %d of %d frames\n", methods[m].c_str(), methods[0].c_str(),
                    countFramesWithZAtMost(results[m], results[0]), summaries[m].solvedFrames);
}

}  // namespace

int runTensions(const std::vector<std::string>& args) {
    std::string modelPath, motionPath, loadsPath, output, methodList;
    double maxTension = 0;
    TensionMotionOptions options;
    ArgumentReader reader(args, kUsage);
    while (reader.next()) {
        if (reader.is("--method")) methodList = reader.value();
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
    if (modelPath.empty() || motionPath.empty() || output.empty() || methodList.empty()) return reader.failWithUsage();
    const std::vector<std::string> methods = splitMethods(methodList);
    for (const std::string& method : methods) TensionMethodRegistry::global().get(method);  // before the model loads
    const Model model = loadModel(modelPath, [](const std::string& note) { std::printf("%s\n", note.c_str()); });
    if (maxTension > 0) options.analysis.maxTension = Eigen::VectorXd::Constant(model.getNumWires(), maxTension);
    std::optional<ExternalLoads> loads;
    if (!loadsPath.empty()) loads = readExternalLoads(loadsPath);
    const StorageTable motion = readStorageFile(motionPath, NonFinite::Allow);
    checkLowpassOption(options.lowpassCutoffHz, motion, motionPath);
    std::vector<TensionMotionResult> results;
    std::vector<TensionMotionSummary> summaries;
    for (const std::string& method : methods) {
        options.analysis.method = method;
        std::optional<Progress> progress;
        options.onFrame = [&](int frame, int frames) {
            if (!progress) progress.emplace("tensions (" + method + ")", frames);
            progress->update(frame);
        };
        results.push_back(runTensionAnalysis(model, motion, loads ? &*loads : nullptr, options));
        if (progress) progress->finish();
        const std::string methodOutput = methods.size() > 1 ? withSuffix(output, "_" + method) : output;
        writeTensionOutputs(results.back(), methodOutput);
        printRunNotes(results.back(), motion, method, methodOutput);
        summaries.push_back(summarizeTensionMotion(model, results.back()));
        printSummary(method, summaries.back());
    }
    if (methods.size() > 1) printComparison(methods, summaries, results);
    return 0;
}

}  // namespace sinew::cli
