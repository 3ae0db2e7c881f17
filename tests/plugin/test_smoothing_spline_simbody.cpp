// sinew's smoothing splines against Simbody's GCVSPL (SimTK::SplineFitter, the code OpenSim's GCVSpline runs):
// the same p gives the same curve and residual degrees of freedom; GCV and a known error variance pick the
// same smoothing; error variance 0 interpolates as OpenSim's coordinate splines do; and the spline stage of
// the coordinate preprocessing equals SimTK splines fitted to the same processed table.
#include <gtest/gtest.h>

#include <random>

#include "sinew/plugin/ndebug_guard.hpp"
// (the guard comes first)
#include <SimTKmath.h>

#include "sinew/signal/coordinate_preprocessing.hpp"
#include "sinew/signal/smoothing_spline.hpp"

namespace sinew {
namespace {

struct Samples {
    Eigen::VectorXd x, y;
};

// Uneven sites on [0, 2] and a smooth signal with noise.
Samples noisySamples(int n, double sigma, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> step(0.6, 1.4);
    std::normal_distribution<double> noise(0, sigma);
    Samples s{Eigen::VectorXd(n), Eigen::VectorXd(n)};
    double t = 0;
    for (int i = 0; i < n; ++i, t += step(rng)) s.x(i) = t;
    s.x *= 2 / s.x(n - 1);
    for (int i = 0; i < n; ++i) s.y(i) = std::sin(3 * s.x(i)) + 0.3 * s.x(i) * s.x(i) + noise(rng);
    return s;
}

SimTK::Vector toSimTK(const Eigen::VectorXd& v) {
    SimTK::Vector out(static_cast<int>(v.size()));
    for (int i = 0; i < out.size(); ++i) out[i] = v(i);
    return out;
}

// Largest difference of value, first and second derivatives at 200 points strictly inside the sites (at
// the end sites the two codes take derivatives that jump there, as for degree 1, from different sides),
// relative to the largest magnitude of each.
double curveDifference(const SmoothingSpline& ours, SimTK::SplineFitter<SimTK::Real>& theirs, const Eigen::VectorXd& x) {
    const SimTK::Spline& spline = theirs.getSpline();
    double worst = 0;
    for (int order = 0; order <= 2; ++order) {
        double difference = 0, magnitude = 0;
        for (int k = 0; k < 200; ++k) {
            const double t = x(0) + (x(x.size() - 1) - x(0)) * (k + 0.5) / 200.0;
            const double reference = order == 0 ? spline.calcValue(t) : spline.calcDerivative(order, t);
            difference = std::max(difference, std::abs(ours.calcDerivative(t, order) - reference));
            magnitude = std::max(magnitude, std::abs(reference));
        }
        worst = std::max(worst, difference / magnitude);
    }
    return worst;
}

TEST(SmoothingSplineVsSimbody, SameSmoothingParameterSameSpline) {
    const Samples s = noisySamples(40, 0.05, 1);
    for (int degree : {1, 3, 5, 7}) {
        const double natural = std::pow(2.0 / 39, degree);
        for (double p : {1e-2 * natural, natural, 1e2 * natural}) {
            const SmoothingSpline ours = SmoothingSpline::fitForSmoothingParameter(degree, s.x, s.y, p);
            auto theirs = SimTK::SplineFitter<SimTK::Real>::fitForSmoothingParameter(degree, toSimTK(s.x), toSimTK(s.y), p);
            EXPECT_LT(curveDifference(ours, theirs, s.x), 1e-7) << "degree " << degree << " p " << p;
            EXPECT_NEAR(ours.getResidualDegreesOfFreedom(), theirs.getDegreesOfFreedom(), 1e-7)
                << "degree " << degree << " p " << p;
        }
    }
}

TEST(SmoothingSplineVsSimbody, GCVAndKnownVarianceChooseTheSameSmoothing) {
    const Samples s = noisySamples(120, 0.05, 2);
    for (int degree : {3, 5}) {
        const SmoothingSpline ours = SmoothingSpline::fitFromGCV(degree, s.x, s.y);
        auto theirs = SimTK::SplineFitter<SimTK::Real>::fitFromGCV(degree, toSimTK(s.x), toSimTK(s.y));
        std::printf("degree %d GCV: p %.6g (Simbody %.6g), dof %.4f (%.4f)\n", degree, ours.getSmoothingParameter(),
                    theirs.getSmoothingParameter(), ours.getResidualDegreesOfFreedom(), theirs.getDegreesOfFreedom());
        // GCV is flat at its minimum: the two searches stop at slightly different p, ours no worse.
        const SmoothingSpline atTheirP =
            SmoothingSpline::fitForSmoothingParameter(degree, s.x, s.y, theirs.getSmoothingParameter());
        EXPECT_LE(ours.getGeneralizedCrossValidation(), atTheirP.getGeneralizedCrossValidation() * (1 + 1e-12));
        EXPECT_NEAR(ours.getSmoothingParameter() / theirs.getSmoothingParameter(), 1, 1e-3) << degree;
        EXPECT_LT(curveDifference(ours, theirs, s.x), 1e-4) << degree;

        const SmoothingSpline known = SmoothingSpline::fitFromErrorVariance(degree, s.x, s.y, 0.05 * 0.05);
        auto theirsKnown =
            SimTK::SplineFitter<SimTK::Real>::fitFromErrorVariance(degree, toSimTK(s.x), toSimTK(s.y), 0.05 * 0.05);
        EXPECT_NEAR(known.getSmoothingParameter() / theirsKnown.getSmoothingParameter(), 1, 1e-3) << degree;
        EXPECT_LT(curveDifference(known, theirsKnown, s.x), 1e-4) << degree;
    }
}

TEST(SmoothingSplineVsSimbody, ZeroErrorVarianceInterpolatesLikeOpenSimsGCVSpline) {
    const Samples s = noisySamples(60, 0.05, 3);
    for (int degree : {3, 5}) {
        const SmoothingSpline ours = SmoothingSpline::fitFromErrorVariance(degree, s.x, s.y, 0.0);
        auto theirs = SimTK::SplineFitter<SimTK::Real>::fitFromErrorVariance(degree, toSimTK(s.x), toSimTK(s.y), 0.0);
        EXPECT_LT(curveDifference(ours, theirs, s.x), 1e-9) << degree;
    }
}

TEST(SmoothingSplineVsSimbody, PreprocessingSplinesAreSimTKsOnTheProcessedTable) {
    // 60 Hz samples printed with 8 decimals (uneven, so resampled), filtered at 6 Hz.
    const int rows = 73;
    Eigen::VectorXd times(rows);
    Eigen::MatrixXd values(rows, 2);
    for (int i = 0; i < rows; ++i) {
        times(i) = std::round((0.4 + i / 60.0) * 1e8) / 1e8;
        values(i, 0) = 30 * std::sin(4 * times(i)) + 2 * std::sin(60 * times(i));
        values(i, 1) = 0.9 + 0.05 * std::cos(7 * times(i));
    }
    CoordinatePreprocessingOptions options;
    options.lowpassCutoffHz = 6;
    options.startTime = 0.4;
    options.finalTime = 1.6;
    options.columnScales = Eigen::Vector2d(M_PI / 180, 1);
    const CoordinateTrajectory out = preprocessCoordinates(times, values, options);
    ASSERT_TRUE(out.resampled);
    for (int j = 0; j < 2; ++j) {
        auto fitter = SimTK::SplineFitter<SimTK::Real>::fitFromErrorVariance(5, toSimTK(out.processedTimes),
                                                                             toSimTK(out.processedValues.col(j)), 0.0);
        const SimTK::Spline& spline = fitter.getSpline();
        for (Eigen::Index i = 0; i < out.times.size(); ++i) {
            const double t = out.times(i);
            EXPECT_NEAR(out.q(i, j), spline.calcValue(t), 1e-10 * (1 + std::abs(out.q(i, j))));
            EXPECT_NEAR(out.qdot(i, j), spline.calcDerivative(1, t), 1e-8 * (1 + out.qdot.col(j).cwiseAbs().maxCoeff()));
            EXPECT_NEAR(out.qddot(i, j), spline.calcDerivative(2, t), 1e-7 * (1 + out.qddot.col(j).cwiseAbs().maxCoeff()));
        }
    }
}

}  // namespace
}  // namespace sinew
