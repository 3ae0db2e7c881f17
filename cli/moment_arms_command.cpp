#include <cstdio>
#include <filesystem>

#include "arguments.hpp"
#include "commands.hpp"
#include "progress.hpp"
#include "sinew/io/model_loading.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/tools/coordinate_table.hpp"
#include "sinew/tools/moment_arm_motion.hpp"

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
    const bool defaultPose = motionPath.empty();
    CoordinateSamples samples;
    if (defaultPose) {
        samples.times = Eigen::VectorXd::Zero(1);
        samples.q = model.getDefaultQ().transpose();
    } else {
        samples = readCoordinateSamples(model, readStorageFile(motionPath));
    }
    Progress progress("moment arms", static_cast<double>(samples.times.size()));
    MomentArmMotion motion = calcMomentArmMotion(model, samples, defaultPose ? modelPath : motionPath, !defaultPose,
                                                 [&](int frame, int) { progress.update(frame); });
    progress.finish();
    const int files = writeMomentArmFiles(model, motion, outputDir);
    const StorageTable& lengths = motion.lengths;
    const std::filesystem::path dir(outputDir);
    std::printf("%d wires, %zu rows: %d files in %s\n", model.getNumWires(), lengths.times.size(), files,
                std::filesystem::absolute(dir).string().c_str());
    return 0;
}

}  // namespace sinew::cli
