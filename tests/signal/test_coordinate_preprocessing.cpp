// OpenSim's inverse-dynamics preprocessing of coordinates: without filtering the splines interpolate and
// differentiate analytic signals; with filtering the pass band survives, the stop band goes, the padding
// and time range select the rows OpenSim would; uneven times are resampled; on gait2354 the frame times
// are exactly those of OpenSim 4.4.1's inverse_dynamics.sto and the result is finite and smooth.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "sinew/signal/coordinate_preprocessing.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/storage_file.hpp"
#include "support/error_assertions.hpp"

namespace sinew {
namespace {

constexpr double kDegree = M_PI / 180;

// Two columns sampled at 100 Hz on [0, 1]: a 1 Hz sine in degrees and a 0.5 Hz cosine in metres, plus
// `hum` times a 30 Hz sine in both.
struct Table {
    Eigen::VectorXd times;
    Eigen::MatrixXd values;
};

Table analyticTable(double hum) {
    Table t{Eigen::VectorXd::LinSpaced(101, 0, 1), Eigen::MatrixXd(101, 2)};
    for (Eigen::Index i = 0; i < 101; ++i) {
        const double s = t.times(i), noise = hum * std::sin(2 * M_PI * 30 * s);
        t.values(i, 0) = 40 * std::sin(2 * M_PI * s) + noise;
        t.values(i, 1) = 0.3 * std::cos(M_PI * s) + noise;
    }
    return t;
}

// The analytic (noise-free) coordinates in radians and metres and their derivatives.
Eigen::Vector2d truth(double s, int order) {
    const double w1 = 2 * M_PI, w2 = M_PI;
    const double a = 40 * kDegree * std::pow(w1, order) * std::sin(w1 * s + order * M_PI / 2);
    const double b = 0.3 * std::pow(w2, order) * std::cos(w2 * s + order * M_PI / 2);
    return {a, b};
}

TEST(CoordinatePreprocessing, WithoutFilteringTheSplinesInterpolateAndDifferentiate) {
    const Table table = analyticTable(0);
    CoordinatePreprocessingOptions options;
    options.columnScales = Eigen::Vector2d(kDegree, 1);
    const CoordinateTrajectory out = preprocessCoordinates(table.times, table.values, options);
    ASSERT_EQ(out.times, table.times);
    EXPECT_FALSE(out.resampled);
    for (Eigen::Index i = 0; i < out.times.size(); ++i) {
        const double s = out.times(i);
        EXPECT_LT((out.q.row(i).transpose() - truth(s, 0)).cwiseAbs().maxCoeff(), 1e-12) << s;
        // Quintic natural splines at 100 Hz: the derivatives are accurate except near the natural ends.
        if (s < 0.1 || s > 0.9) continue;
        EXPECT_LT((out.qdot.row(i).transpose() - truth(s, 1)).cwiseAbs().maxCoeff(), 1e-6) << s;
        EXPECT_LT((out.qddot.row(i).transpose() - truth(s, 2)).cwiseAbs().maxCoeff(), 1e-4) << s;
    }
}

TEST(CoordinatePreprocessing, FilteringKeepsThePassBandAndSelectsOpenSimsRows) {
    const Table table = analyticTable(1);  // 1 degree / 1 m of 30 Hz hum
    CoordinatePreprocessingOptions options;
    options.lowpassCutoffHz = 6;
    options.columnScales = Eigen::Vector2d(kDegree, 1);
    // The whole padded table (OpenSim's default time range): 101 + 2 * 50 rows from -0.5 s to 1.5 s.
    const CoordinateTrajectory padded = preprocessCoordinates(table.times, table.values, options);
    EXPECT_EQ(padded.times.size(), 201);
    EXPECT_NEAR(padded.times(0), -0.5, 1e-12);
    EXPECT_NEAR(padded.times(200), 1.5, 1e-12);
    EXPECT_FALSE(padded.resampled);
    EXPECT_NEAR(padded.samplePeriod, 0.01, 1e-15);
    EXPECT_DOUBLE_EQ(padded.usedCutoffHz, 6);

    options.startTime = 0;
    options.finalTime = 1;
    const CoordinateTrajectory out = preprocessCoordinates(table.times, table.values, options);
    ASSERT_EQ(out.times.size(), 101);
    EXPECT_LT((out.times - table.times).cwiseAbs().maxCoeff(), 1e-12);
    // The hum is gone (30 Hz gain ~ 1e-5), the 1 Hz and 0.5 Hz signals pass (gain 1 - 2e-5); the ends are
    // close too, thanks to the padding.
    for (Eigen::Index i = 0; i < out.times.size(); ++i) {
        const double s = out.times(i);
        EXPECT_LT(std::abs(out.q(i, 0) - truth(s, 0)(0)), 2e-3) << s;
        EXPECT_LT(std::abs(out.q(i, 1) - truth(s, 0)(1)), 2e-3) << s;
        if (s < 0.1 || s > 0.9) continue;
        EXPECT_LT((out.qdot.row(i).transpose() - truth(s, 1)).cwiseAbs().maxCoeff(), 0.02) << s;
    }
    // The same frames are the padded run's rows 50..150.
    EXPECT_EQ(out.q, padded.q.middleRows(50, 101));
}

TEST(CoordinatePreprocessing, UnevenTimesAreResampledAtTheSmallestStep) {
    Table table = analyticTable(0);
    for (Eigen::Index i = 0; i < table.times.size(); ++i)
        table.times(i) = std::round((i / 60.0) * 1e8) / 1e8;  // 60 Hz times printed with 8 decimals
    CoordinatePreprocessingOptions options;
    options.lowpassCutoffHz = 6;
    const CoordinateTrajectory out = preprocessCoordinates(table.times, table.values, options);
    EXPECT_TRUE(out.resampled);
    const Eigen::VectorXd padded = out.processedTimes;
    const double smallest = (padded.tail(padded.size() - 1) - padded.head(padded.size() - 1)).minCoeff();
    EXPECT_NEAR(out.samplePeriod, 1 / 60.0, 2e-8);
    EXPECT_NEAR(smallest, out.samplePeriod, 1e-12);
    EXPECT_NEAR(padded(0), -50 / 60.0, 1e-7);  // 2 t_0 - t_50
    EXPECT_LE(padded(padded.size() - 1), 150 / 60.0 + 1e-7);
}

// The rows of a storage file's first column, for OpenSim's own output.
std::vector<double> storageTimes(const std::string& path) {
    return readStorageFile(path).times;
}

TEST(CoordinatePreprocessing, Gait2354MatchesOpenSimsFramesAndIsSmooth) {
    const std::filesystem::path dir = std::filesystem::path(SINEW_SHARED_DIR) / "data/opensim/gait2354";
    if (!std::filesystem::exists(dir / "subject01_walk1_ik.mot"))
        GTEST_SKIP() << "shared data absent: " << dir << " (gait2354 coordinates and OpenSim's results)";
    const StorageTable ik = readStorageFile((dir / "subject01_walk1_ik.mot").string());
    ASSERT_TRUE(ik.inDegrees);
    const Eigen::Index rows = static_cast<Eigen::Index>(ik.times.size()), cols = static_cast<Eigen::Index>(ik.columns.size());
    Eigen::VectorXd times = Eigen::Map<const Eigen::VectorXd>(ik.times.data(), rows);
    Eigen::MatrixXd values(rows, cols);
    CoordinatePreprocessingOptions options;
    options.columnScales = Eigen::VectorXd::Constant(cols, kDegree);
    options.columnNames = ik.columns;
    for (Eigen::Index j = 0; j < cols; ++j) {
        for (Eigen::Index i = 0; i < rows; ++i) values(i, j) = ik.rows[i][j];
        if (ik.columns[j] == "pelvis_tx" || ik.columns[j] == "pelvis_ty" || ik.columns[j] == "pelvis_tz")
            options.columnScales(j) = 1;  // translations: metres either way
    }
    // subject01_Setup_InverseDynamics.xml: time_range 0.4 1.6, lowpass_cutoff_frequency_for_coordinates 6.
    options.lowpassCutoffHz = 6;
    options.startTime = 0.4;
    options.finalTime = 1.6;
    const CoordinateTrajectory out = preprocessCoordinates(times, values, options);

    // The frames OpenSim 4.4.1 reported (its times carry the resampling grid's rounding: 0.39999976 ...).
    const std::vector<double> reference = storageTimes((dir / "opensim-4.4.1/inverse_dynamics.sto").string());
    ASSERT_EQ(out.times.size(), static_cast<Eigen::Index>(reference.size()));
    EXPECT_TRUE(out.resampled);
    for (std::size_t i = 0; i < reference.size(); ++i)
        EXPECT_NEAR(out.times(static_cast<Eigen::Index>(i)), reference[i], 5e-9) << "frame " << i;

    ASSERT_TRUE(out.q.allFinite() && out.qdot.allFinite() && out.qddot.allFinite());
    const double dt = out.samplePeriod;
    for (Eigen::Index j = 0; j < cols; ++j) {
        // Filtered at 6 Hz the coordinates stay near the raw data (the raw rows are 0.24 us from the frames).
        double deviation = 0;
        for (Eigen::Index i = 0; i < rows; ++i) deviation = std::max(deviation, std::abs(out.q(i, j) - values(i, j) * options.columnScales(j)));
        EXPECT_LT(deviation, 0.03) << ik.columns[j];
        // Smooth: speeds and accelerations are the central differences of the level below to within the
        // differences' truncation error (6 Hz content at 60 Hz: a few percent of the range).
        for (const auto& [lower, upper] : {std::pair{&out.q, &out.qdot}, std::pair{&out.qdot, &out.qddot}}) {
            const double range = upper->col(j).cwiseAbs().maxCoeff() + 1e-9;
            for (Eigen::Index i = 1; i + 1 < out.times.size(); ++i) {
                const double difference = ((*lower)(i + 1, j) - (*lower)(i - 1, j)) / (2 * dt);
                EXPECT_LT(std::abs((*upper)(i, j) - difference), 0.05 * range) << ik.columns[j] << " frame " << i;
            }
        }
    }
}

TEST(CoordinatePreprocessing, RefusesBadInput) {
    auto expectError = [](const Eigen::VectorXd& t, const Eigen::MatrixXd& v, const CoordinatePreprocessingOptions& o,
                          const std::string& text) {
        EXPECT_TRUE(test::throwsErrorAt([&] { preprocessCoordinates(t, v, o); }, "coordinate preprocessing: ", {text},
                                        std::to_string(t.size()) + " rows"));
    };
    const Table table = analyticTable(0);
    CoordinatePreprocessingOptions named;
    named.columnNames = {"knee_angle_r", "pelvis_tx"};
    Eigen::VectorXd times = table.times;
    times(40) = times(39);
    expectError(times, table.values, named, "row 40");
    Eigen::MatrixXd values = table.values;
    values(17, 1) = std::nan("");
    expectError(table.times, values, named, "row 17 (t = 0.170000 s), column 'pelvis_tx'");
    CoordinatePreprocessingOptions o;
    o.lowpassCutoffHz = 0;
    expectError(table.times, table.values, o, "cutoff");
    o = {};
    o.columnScales = Eigen::Vector3d::Ones();
    expectError(table.times, table.values, o, "3 column scales for 2 columns");
    o = {};
    o.startTime = 2;
    o.finalTime = 3;
    expectError(table.times, table.values, o, "lies outside");
    o = {};
    o.splineDegree = 4;
    expectError(table.times, table.values, o, "spline degree 4");
    expectError(table.times.head(5), table.values.topRows(5), {}, "5 rows");
    expectError(table.times, table.values.topRows(5), {}, "5 rows of values for 101 times");
}

}  // namespace
}  // namespace sinew
