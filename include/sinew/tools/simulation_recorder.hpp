#pragma once
// The tables of a forward simulation, frame by frame, from either engine (sinew's
// core/forward_simulation.hpp or Simbody's plugin/simbody_simulation.hpp: both report SimulationFrame), and
// their files: <model>_coordinates, _speeds, _tensions and _energy.sto, or the _incomplete set of a run that
// stopped early.
#include <string>

#include "sinew/core/model.hpp"
#include "sinew/core/simulation.hpp"
#include "sinew/io/storage_file.hpp"

namespace sinew {

class SimulationRecorder {
public:
    SimulationRecorder(const Model& model, std::string outputDirectory);

    void record(const SimulationFrame& frame);
    int getNumFrames() const { return static_cast<int>(coordinates_.times.size()); }
    double getLastTime() const { return coordinates_.times.back(); }

    // Writes the frames recorded as the complete set, or as the incomplete one headed by `why`, in one set
    // that retires the other's files.
    void write(bool incomplete, const std::string& why = "");
    // The absolute path of table k (0 coordinates, 1 speeds, 2 tensions, 3 energy) of either set.
    std::string getPath(int k, bool incomplete) const;
    static constexpr int kNumTables = 4;

private:
    std::string directory_, stem_;
    StorageTable coordinates_, speeds_, tensions_, energy_;
};

}  // namespace sinew
