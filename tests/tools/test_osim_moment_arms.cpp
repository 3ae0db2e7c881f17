// Moment arms of OpenSim's example muscles (imported from ../shared/data/opensim) against finite
// differences of the path lengths, and their anatomical signs.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <random>

#include "sinew/core/data.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/moment_arms.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/osim_model_converter.hpp"

namespace sinew {
namespace {

const std::filesystem::path kOpenSimData = std::filesystem::path(SINEW_SHARED_DIR) / "data" / "opensim";

Model importShared(const std::string& relative) {
    return convertOsimModel(readOsimModel((kOpenSimData / relative).string())).model;
}

Eigen::VectorXd calcLengths(const Model& model, Data& data, const Eigen::VectorXd& q) {
    calcPositionKinematics(model, data, q);
    calcWirePaths(model, data);
    return data.wireLength;
}

// Random poses inside each coordinate's range (translations within 0.1 m of the default).
std::vector<Eigen::VectorXd> makePoses(const Model& model, int count) {
    std::mt19937 rng(7);
    std::vector<Eigen::VectorXd> poses{model.getDefaultQ()};
    for (int p = 0; p < count; ++p) {
        Eigen::VectorXd q = model.getDefaultQ();
        for (std::size_t i = 0; i < model.getCoordinates().size(); ++i) {
            const Coordinate& c = model.getCoordinates()[i];
            double lo = c.rangeMin, hi = c.rangeMax;
            if (c.motionType != MotionType::Rotational) {
                lo = std::max(lo, c.defaultValue - 0.1);
                hi = std::min(hi, c.defaultValue + 0.1);
            }
            q[static_cast<Eigen::Index>(i)] = std::uniform_real_distribution<double>(lo, hi)(rng);
        }
        poses.push_back(q);
    }
    return poses;
}

// Every moment arm equals -dL/dq by central differences to 1e-6 m, except where the path switches (a
// conditional point or a wrap engaging within the step), found as differences that disagree between two
// step sizes; those must be rare. arm26's TRIlong and BIClong wrap ellipsoids, TRIlong next to a cylinder.
void checkAgainstFiniteDifferences(const Model& model) {
    Data data(model);
    Eigen::MatrixXd R(model.getNumWires(), model.getNumU());
    int compared = 0, switching = 0;
    double worst = 0;
    for (const Eigen::VectorXd& q : makePoses(model, 30)) {
        calcLengths(model, data, q);
        calcMomentArms(model, data, R);
        for (int c = 0; c < model.getNumU(); ++c) {
            auto centralDifference = [&](double h) {
                Eigen::VectorXd plus = q, minus = q;
                plus[c] += h;
                minus[c] -= h;
                return Eigen::VectorXd((calcLengths(model, data, plus) - calcLengths(model, data, minus)) / (2 * h));
            };
            const Eigen::VectorXd coarse = centralDifference(1e-5), fine = centralDifference(1e-6);
            for (int w = 0; w < model.getNumWires(); ++w) {
                if (std::abs(coarse[w] - fine[w]) > 1e-6) {
                    ++switching;
                    continue;
                }
                ++compared;
                worst = std::max(worst, std::abs(R(w, c) + coarse[w]));
            }
        }
    }
    std::cout << model.getName() << ": " << compared << " moment arms against -dL/dq, worst difference " << worst
              << " m; " << switching << " skipped where the path switches within the step\n";
    EXPECT_LE(worst, 1e-6);
    EXPECT_LE(switching, compared / 100);
}

// The sign of the moment arm at the default pose: +1 or -1 in the coordinate's positive direction.
void expectSign(const Model& model, const std::string& wire, const std::string& coordinate, int sign,
                const char* meaning) {
    Data data(model);
    Eigen::MatrixXd R(model.getNumWires(), model.getNumU());
    calcLengths(model, data, model.getDefaultQ());
    calcMomentArms(model, data, R);
    const int w = model.findWireIndex(wire), c = model.findCoordinateIndex(coordinate);
    ASSERT_GE(w, 0) << wire;
    ASSERT_GE(c, 0) << coordinate;
    EXPECT_GT(sign * R(w, c), 1e-3) << wire << " about " << coordinate << ": expected to " << meaning << ", moment arm "
                                    << R(w, c) << " m";
}

TEST(OsimMomentArms, Arm26) {
    if (!std::filesystem::exists(kOpenSimData / "arm26")) GTEST_SKIP() << "../shared/data/opensim/arm26 is absent";
    const Model model = importShared("arm26/arm26.osim");
    checkAgainstFiniteDifferences(model);
    for (const char* flexor : {"BIClong", "BICshort", "BRA"}) expectSign(model, flexor, "r_elbow_flex", +1, "flex the elbow");
    for (const char* extensor : {"TRIlong", "TRIlat", "TRImed"})
        expectSign(model, extensor, "r_elbow_flex", -1, "extend the elbow");
    expectSign(model, "BIClong", "r_shoulder_elev", +1, "elevate (flex) the shoulder");
    expectSign(model, "TRIlong", "r_shoulder_elev", -1, "extend the shoulder");
}

TEST(OsimMomentArms, Gait2354) {
    if (!std::filesystem::exists(kOpenSimData / "gait2354")) GTEST_SKIP() << "../shared/data/opensim/gait2354 is absent";
    const Model model = importShared("gait2354/subject01_simbody.osim");
    checkAgainstFiniteDifferences(model);
    // gait2354's knee angle is negative in flexion, so knee extensors have positive moment arms.
    for (const char* side : {"_r", "_l"}) {
        const std::string s = side;
        expectSign(model, "vas_int" + s, "knee_angle" + s, +1, "extend the knee");
        expectSign(model, "rect_fem" + s, "knee_angle" + s, +1, "extend the knee");
        expectSign(model, "bifemsh" + s, "knee_angle" + s, -1, "flex the knee");
        expectSign(model, "med_gas" + s, "knee_angle" + s, -1, "flex the knee");
        expectSign(model, "iliacus" + s, "hip_flexion" + s, +1, "flex the hip");
        expectSign(model, "psoas" + s, "hip_flexion" + s, +1, "flex the hip");
        expectSign(model, "glut_max2" + s, "hip_flexion" + s, -1, "extend the hip");
        expectSign(model, "bifemlh" + s, "hip_flexion" + s, -1, "extend the hip");
        expectSign(model, "add_mag2" + s, "hip_adduction" + s, +1, "adduct the hip");
        expectSign(model, "glut_med2" + s, "hip_adduction" + s, -1, "abduct the hip");
        expectSign(model, "tib_ant" + s, "ankle_angle" + s, +1, "dorsiflex the ankle");
        expectSign(model, "soleus" + s, "ankle_angle" + s, -1, "plantarflex the ankle");
        expectSign(model, "med_gas" + s, "ankle_angle" + s, -1, "plantarflex the ankle");
    }
}

}  // namespace
}  // namespace sinew
