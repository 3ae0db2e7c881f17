#include <cmath>
#include <cstdio>
#include <filesystem>

#include "arguments.hpp"
#include "commands.hpp"
#include "progress.hpp"
#include "sinew/core/coordinate_coupler.hpp"
#include "sinew/core/data.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/moment_arms.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/tools/coordinate_table.hpp"
#include "sinew/io/model_loading.hpp"

namespace sinew::cli {
namespace {

const char* kUsage =
    "usage: sinew moment-arms MODEL [--motion MOTION.mot] [-o DIR]\n"
    "  Wire (muscle-tendon) lengths and moment arms r = -dL/dq about every coordinate, at the model's\n"
    "  default pose or at each row of a coordinates table, written as OpenSim's MuscleAnalysis names its\n"
    "  files: <model>_Length.sto and <model>_MomentArm_<coordinate>.sto (one column per wire).\n"
    "  Coordinates no wire crosses get no file. MODEL: .osim or sinew .yaml.\n";

}  // namespace

int runMomentArms(const std::vector<std::string>& args) {
    std::string modelPath, motionPath, outputDir = "sinew_output";
    ArgumentReader reader(args, kUsage);
    while (reader.next()) {
        if (reader.is("--motion")) motionPath = reader.value();
        else if (reader.is("-o", "--output")) outputDir = reader.value();
        else reader.takePositional({&modelPath});
    }
    if (reader.helpShown()) return 0;
    if (modelPath.empty()) return reader.failWithUsage();
    const Model model = loadModel(modelPath, [](const std::string& note) { std::printf("%s\n", note.c_str()); });
    CoordinateSamples samples;
    if (motionPath.empty()) {
        samples.times = Eigen::VectorXd::Zero(1);
        samples.q = model.getDefaultQ().transpose();
    } else {
        samples = readCoordinateSamples(model, readStorageFile(motionPath));
    }
    std::vector<std::string> wireNames;
    for (const Wire& wire : model.getWires()) wireNames.push_back(wire.name);
    const std::vector<std::string> speedNames = getSpeedNames(model);
    StorageTable lengths{model.getName() + " wire lengths (m)", false, wireNames, {}, {}};
    std::vector<StorageTable> momentArms(speedNames.size(),
                                         StorageTable{"", false, wireNames, {}, {}});
    std::vector<bool> crossed(speedNames.size(), false);

    Data data(model);
    Eigen::MatrixXd R(model.getNumWires(), model.getNumU());
    Progress progress("moment arms", static_cast<double>(samples.times.size()));
    for (Eigen::Index row = 0; row < samples.times.size(); ++row) {
        // As OpenSim's AnalyzeTool, which assembles each frame: dependent coordinates follow their couplers.
        Eigen::VectorXd q = samples.q.row(row).transpose();
        applyCoordinateCouplers(model, q);
        calcPositionKinematics(model, data, q);
        calcWirePaths(model, data);
        calcMomentArms(model, data, R);
        // Named here, at the input row, rather than later as a cell of the output file.
        if (!data.wireLength.allFinite() || !R.allFinite())
            for (int w = 0; w < model.getNumWires(); ++w)
                if (!std::isfinite(data.wireLength[w]) || !R.row(w).allFinite())
                    throw Error((motionPath.empty() ? modelPath + ": at the default pose"
                                                    : motionPath + ": row " + std::to_string(row + 1) + " (t = " +
                                                          std::to_string(samples.times[row]) + " s)") +
                                ": wire '" + model.getWire(w).name +
                                "' has a non-finite length or moment arm (check its points and wrap objects)");
        lengths.times.push_back(samples.times[row]);
        lengths.rows.emplace_back(data.wireLength.data(), data.wireLength.data() + data.wireLength.size());
        for (std::size_t c = 0; c < speedNames.size(); ++c) {
            const Eigen::VectorXd column = R.col(static_cast<Eigen::Index>(c));
            crossed[c] = crossed[c] || column.cwiseAbs().maxCoeff() > 0;
            momentArms[c].times.push_back(samples.times[row]);
            momentArms[c].rows.emplace_back(column.data(), column.data() + column.size());
        }
        progress.update(static_cast<double>(row + 1));
    }
    progress.finish();
    std::filesystem::create_directories(outputDir);
    const std::filesystem::path dir(outputDir);
    OutputFileSet outputs;
    writeStorageFile(lengths, outputs, (dir / (model.getName() + "_Length.sto")).string());
    int files = 1;
    for (std::size_t c = 0; c < speedNames.size(); ++c) {
        const std::string path = (dir / (model.getName() + "_MomentArm_" + speedNames[c] + ".sto")).string();
        if (!crossed[c]) {
            outputs.retire(path);  // an earlier run's file for a coordinate this motion's wires no longer cross
            continue;
        }
        momentArms[c].name = model.getName() + " moment arms about " + speedNames[c] + " (m or m/m)";
        writeStorageFile(momentArms[c], outputs, path);
        ++files;
    }
    outputs.commit();
    std::printf("%d wires, %zu rows: %d files in %s\n", model.getNumWires(), lengths.times.size(), files,
                std::filesystem::absolute(dir).string().c_str());
    return 0;
}

}  // namespace sinew::cli
