#include "sinew/tools/simulation_recorder.hpp"

#include <filesystem>

namespace sinew {
namespace {

void append(StorageTable& table, double time, const Eigen::VectorXd& row) {
    table.times.push_back(time);
    table.rows.emplace_back(row.data(), row.data() + row.size());
}

}  // namespace

SimulationRecorder::SimulationRecorder(const Model& model, std::string outputDirectory)
    : directory_(std::move(outputDirectory)),
      stem_(model.getName()),
      coordinates_{model.getName() + " coordinates", false, getCoordinateNames(model), {}, {}},
      speeds_{model.getName() + " speeds", false, getSpeedNames(model), {}, {}},
      tensions_{model.getName() + " wire tensions (N)", false, {}, {}, {}},
      energy_{model.getName() + " energy (J)", false, {"kinetic", "potential", "total"}, {}, {}} {
    for (const Wire& wire : model.getWires()) tensions_.columns.push_back(wire.name);
}

void SimulationRecorder::record(const SimulationFrame& frame) {
    append(coordinates_, frame.time, frame.q);
    append(speeds_, frame.time, frame.u);
    append(tensions_, frame.time, frame.tensions);
    append(energy_, frame.time,
           Eigen::Vector3d(frame.kineticEnergy, frame.potentialEnergy, frame.kineticEnergy + frame.potentialEnergy));
}

std::string SimulationRecorder::getPath(int k, bool incomplete) const {
    static const char* const kinds[kNumTables] = {"coordinates", "speeds", "tensions", "energy"};
    const std::filesystem::path path =
        std::filesystem::path(directory_) / (stem_ + "_" + kinds[k] + (incomplete ? "_incomplete" : "") + ".sto");
    return std::filesystem::absolute(path).string();
}

void SimulationRecorder::write(bool incomplete, const std::string& why) {
    StorageTable* tables[kNumTables] = {&coordinates_, &speeds_, &tensions_, &energy_};
    OutputFileSet outputs;
    for (int k = 0; k < kNumTables; ++k) {
        if (incomplete) {
            tables[k]->header = {"incomplete: " + why};
            tables[k]->name += " (INCOMPLETE)";
        }
        writeStorageFile(*tables[k], outputs, getPath(k, incomplete));
        outputs.retire(getPath(k, !incomplete));
    }
    outputs.commit();
}

}  // namespace sinew
