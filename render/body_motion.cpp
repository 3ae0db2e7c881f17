#include "sinew/render/body_motion.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/virtual_link_equilibrium.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/storage_file.hpp"
#include "sinew/tools/coordinate_table.hpp"

namespace sinew {
namespace {

// Rows of two tables written for the same instants may differ in the last digits a writer keeps.
constexpr double kSameTime = 1e-6;  // s

std::string formatTime(double t) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", t);
    return text;
}

int findRowAtTime(const TensionTable& tensions, double time, const std::string& motionFile, int motionRow) {
    for (Eigen::Index r = 0; r < tensions.times.size(); ++r)
        if (std::abs(tensions.times[r] - time) <= kSameTime) return static_cast<int>(r);
    throw Error(tensions.file + ": no row at t = " + formatTime(time) + " s, the time of frame " +
                std::to_string(motionRow) + " of " + motionFile);
}

// Wire lengths (m) at q.
void calcLengthsAt(const Model& model, Data& data, const Eigen::VectorXd& q, Eigen::VectorXd& lengths) {
    calcPositionKinematics(model, data, q);
    calcWirePaths(model, data);
    lengths = data.wireLength;
}

}  // namespace

PoseTable readPoseTable(const Model& model, const std::string& path) {
    const StorageTable table = readStorageFile(path);
    PoseTable poses;
    poses.file = path;
    const CoordinateSamples samples = readCoordinateSamples(model, table);
    poses.times = samples.times;
    poses.q = samples.q;
    return poses;
}

TensionTable readTensionTable(const Model& model, const std::string& path) {
    const StorageTable table = readStorageFile(path);
    std::vector<std::string> names;
    for (const Wire& wire : model.getWires()) names.push_back(wire.name);
    const std::vector<int> columnOf = matchStorageColumns(table, names, ExtraColumns::Refuse);
    TensionTable tensions;
    tensions.file = path;
    const Eigen::Index rows = static_cast<Eigen::Index>(table.times.size());
    tensions.times = Eigen::Map<const Eigen::VectorXd>(table.times.data(), rows);
    tensions.tensions.resize(rows, model.getNumWires());
    for (Eigen::Index r = 0; r < rows; ++r)
        for (int w = 0; w < model.getNumWires(); ++w) {
            const double f = table.rows[static_cast<std::size_t>(r)][static_cast<std::size_t>(columnOf[static_cast<std::size_t>(w)])];
            if (f < 0)
                throw Error(path + ": row " + std::to_string(r) + " (t = " + formatTime(tensions.times[r]) +
                            " s), column '" + names[static_cast<std::size_t>(w)] + "': tension " + formatTime(f) +
                            " N is negative (a wire cannot push)");
            tensions.tensions(r, w) = f;
        }
    return tensions;
}

int findFrame(const Eigen::VectorXd& times, int frame, const std::string& file) {
    if (frame < 0 || frame >= times.size())
        throw Error("frame " + std::to_string(frame) + " is out of range: " + file + " has " +
                    std::to_string(times.size()) + (times.size() == 1 ? " frame" : " frames") + " (0 to " +
                    std::to_string(times.size() - 1) + ")");
    return frame;
}

int findFrameAtTime(const Eigen::VectorXd& times, double time, const std::string& file) {
    if (times.size() == 0 || time < times[0] - kSameTime || time > times[times.size() - 1] + kSameTime)
        throw Error("time " + formatTime(time) + " s is out of range: " + file + " spans " +
                    (times.size() ? formatTime(times[0]) + " to " + formatTime(times[times.size() - 1]) + " s"
                                  : std::string("no rows")));
    Eigen::Index nearest = 0;
    (times.array() - time).abs().minCoeff(&nearest);
    return static_cast<int>(nearest);
}

std::vector<int> selectStripFrames(const Eigen::VectorXd& times, int count, const std::string& file) {
    if (count < 1 || count > times.size())
        throw Error("--strip " + std::to_string(count) + ": " + file + " has " + std::to_string(times.size()) +
                    " frames; a strip takes 1 to that many");
    std::vector<int> rows;
    for (int i = 0; i < count; ++i)
        rows.push_back(count == 1 ? 0 : static_cast<int>(std::lround(static_cast<double>(i) * (times.size() - 1) / (count - 1))));
    return rows;
}

std::vector<BodyFrame> calcBodyFrames(const Model& model, const PoseTable* motion, const TensionTable* tensions,
                                      const std::vector<int>& rows) {
    const std::vector<BoneCapsule> capsules = calcBoneCapsules(model);
    Data data(model);
    std::optional<VirtualLinkEquilibriumData> equilibrium;
    bool hasVirtualLinks = false;
    for (const Link& link : model.getLinks()) hasVirtualLinks = hasVirtualLinks || link.isVirtual;
    Eigen::VectorXd f(model.getNumWires()), before, after;
    std::vector<BodyFrame> frames;
    for (const int row : rows) {
        const double time = motion ? motion->times[row] : tensions ? tensions->times[row] : 0.0;
        Eigen::VectorXd speeds = Eigen::VectorXd::Zero(model.getNumWires());
        if (motion && !tensions && motion->times.size() > 1) {
            const Eigen::Index last = motion->times.size() - 1;
            const Eigen::Index r0 = std::max<Eigen::Index>(row - 1, 0), r1 = std::min<Eigen::Index>(row + 1, last);
            calcLengthsAt(model, data, motion->q.row(r0).transpose(), before);
            calcLengthsAt(model, data, motion->q.row(r1).transpose(), after);
            speeds = (after - before) / (motion->times[r1] - motion->times[r0]);
        }
        calcPositionKinematics(model, data, motion ? Eigen::VectorXd(motion->q.row(row).transpose()) : model.getDefaultQ());
        calcWirePaths(model, data);
        if (!motion && hasVirtualLinks) {
            // The default pose's virtual links are wherever the file put them: balance them at rest.
            if (!equilibrium) equilibrium.emplace(model);
            calcVirtualLinkEquilibriumAtRest(model, data, time, *equilibrium);
        }
        if (tensions) {
            f = tensions->tensions.row(motion ? findRowAtTime(*tensions, time, motion->file, row) : row).transpose();
        } else {
            data.wireSpeed = speeds;
            calcWireTensions(model, data, time, f);
        }
        frames.push_back(calcBodyFrame(model, data, capsules, time, f));
    }
    return frames;
}

}  // namespace sinew
