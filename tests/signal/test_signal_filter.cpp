// Padding and the forward-backward Butterworth low-pass: padding continues lines and mirrors about the end
// points; the filter's gain on long sinusoids matches the analytic squared Butterworth magnitude with zero
// phase; its coefficients have the Butterworth poles' properties; bad input is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <random>

#include <Eigen/Eigenvalues>

#include "sinew/core/error.hpp"
#include "sinew/signal/signal_filter.hpp"
#include "support/error_assertions.hpp"

namespace sinew {
namespace {

// |H(f)|^2 of the digital 3rd-order Butterworth with pre-warped cutoff fc: the magnitude of one pass
// squared, i.e. the response of the forward-backward filter.
double analyticForwardBackwardGain(double f, double fc, double T) {
    return 1 / (1 + std::pow(std::tan(M_PI * f * T) / std::tan(M_PI * fc * T), 6));
}

// One pass's transfer function from its difference-equation coefficients, at frequency f.
std::complex<double> onePassResponse(const LowpassIIRCoefficients& c, double f, double T) {
    const std::complex<double> zInverse = std::polar(1.0, -2 * M_PI * f * T);
    std::complex<double> numerator = 0, denominator = 0, power = 1;
    for (int k = 0; k < 4; ++k, power *= zInverse) {
        numerator += c.numerator[k] * power;
        denominator += c.denominator[k] * power;
    }
    return numerator / denominator;
}

TEST(SignalFilter, PaddingContinuesLinesAndMirrorsAboutTheEnds) {
    // A line (like a uniform time column) continues as the same line.
    const Eigen::VectorXd line = Eigen::VectorXd::LinSpaced(9, 0.4, 1.2);
    const Eigen::VectorXd paddedLine = padSignal(line, 4);
    ASSERT_EQ(paddedLine.size(), 17);
    EXPECT_LT((paddedLine - Eigen::VectorXd::LinSpaced(17, 0.0, 1.6)).cwiseAbs().maxCoeff(), 1e-14);

    // Any signal: the pad is the point reflection of the signal about each end sample.
    std::mt19937 rng(3);
    std::normal_distribution<double> normal;
    Eigen::VectorXd s(11);
    for (double& v : s) v = normal(rng);
    const int pad = 5;
    const Eigen::VectorXd p = padSignal(s, pad);
    ASSERT_EQ(p.size(), 21);
    EXPECT_EQ(p.segment(pad, 11), s);
    for (int k = 1; k <= pad; ++k) {
        EXPECT_NEAR(p(pad - k) - s(0), -(s(k) - s(0)), 1e-14) << k;
        EXPECT_NEAR(p(pad + 10 + k) - s(10), -(s(10 - k) - s(10)), 1e-14) << k;
    }
    EXPECT_EQ(padSignal(s, 0), s);
    EXPECT_THROW(padSignal(s, 11), Error);  // would need sample 11 of 0..10
    EXPECT_THROW(padSignal(s, -1), Error);
    EXPECT_NO_THROW(padSignal(s, 10));
}

TEST(SignalFilter, OnePassIsTheThirdOrderButterworth) {
    const double T = 0.01, fc = 6;
    const LowpassIIRCoefficients c = calcLowpassIIRCoefficients(T, fc);
    EXPECT_DOUBLE_EQ(c.cutoffHz, fc);
    EXPECT_NEAR(std::abs(onePassResponse(c, 0, T)), 1, 1e-14);          // DC gain 1
    EXPECT_NEAR(std::abs(onePassResponse(c, 0.5 / T, T)), 0, 1e-12);    // zero at Nyquist
    EXPECT_NEAR(std::abs(onePassResponse(c, fc, T)), M_SQRT1_2, 1e-12); // -3 dB at the cutoff
    for (double f : {0.5, 2.0, 6.0, 10.0, 20.0, 40.0})
        EXPECT_NEAR(std::norm(onePassResponse(c, f, T)), analyticForwardBackwardGain(f, fc, T), 1e-12) << f;
    // Stable, with the Butterworth pole pattern: the poles (roots of z^3 + a1 z^2 + a2 z + a3, eigenvalues of
    // its companion matrix) lie inside the unit circle, and the real one is the bilinear image of s = -W.
    Eigen::Matrix3d companion;
    companion << -c.denominator[1], -c.denominator[2], -c.denominator[3], 1, 0, 0, 0, 1, 0;
    const Eigen::Vector3cd poles = companion.eigenvalues();
    const double W = std::tan(M_PI * fc * T);
    int realPoles = 0;
    for (const std::complex<double>& z : poles) {
        EXPECT_LT(std::abs(z), 1);
        if (std::abs(z.imag()) < 1e-12) {
            ++realPoles;
            EXPECT_NEAR(z.real(), (1 - W) / (1 + W), 1e-12);
        }
    }
    EXPECT_EQ(realPoles, 1);
}

TEST(SignalFilter, ForwardBackwardGainIsTheSquaredMagnitudeWithZeroPhase) {
    const double T = 0.01, fc = 6;
    const int n = 4000;
    for (double f : {0.25, 1.0, 3.0, 6.0, 9.0, 15.0}) {
        const double phase0 = 0.3;
        Eigen::VectorXd x(n);
        for (int i = 0; i < n; ++i) x(i) = std::sin(2 * M_PI * f * i * T + phase0);
        const Eigen::VectorXd y = lowpassIIR(x, T, fc);
        // Least-squares sine and cosine amplitudes over the middle half, away from the start-up transients.
        Eigen::MatrixXd basis(n / 2, 2);
        Eigen::VectorXd middle(n / 2);
        for (int i = 0; i < n / 2; ++i) {
            const double angle = 2 * M_PI * f * (i + n / 4) * T + phase0;
            basis(i, 0) = std::sin(angle);
            basis(i, 1) = std::cos(angle);
            middle(i) = y(i + n / 4);
        }
        const Eigen::Vector2d amplitude = basis.colPivHouseholderQr().solve(middle);
        const double expected = analyticForwardBackwardGain(f, fc, T);
        EXPECT_NEAR(amplitude(0), expected, 1e-6) << "in-phase gain at " << f << " Hz";
        EXPECT_NEAR(amplitude(1), 0, 1e-6) << "quadrature (phase) at " << f << " Hz";
    }
    // At the cutoff the forward-backward gain is 1/2 (each pass 1/sqrt 2).
    EXPECT_NEAR(analyticForwardBackwardGain(fc, fc, T), 0.5, 1e-15);
}

TEST(SignalFilter, ConstantsPassUnchanged) {
    const Eigen::VectorXd constant = Eigen::VectorXd::Constant(50, -2.75);
    EXPECT_LT((lowpassIIR(constant, 1.0 / 120, 8) - constant).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(SignalFilter, CutoffAboveNyquistIsLoweredLikeOpenSim) {
    EXPECT_DOUBLE_EQ(calcLowpassIIRCoefficients(0.01, 60).cutoffHz, 49);
    EXPECT_DOUBLE_EQ(calcLowpassIIRCoefficients(0.01, 50).cutoffHz, 49);
    EXPECT_DOUBLE_EQ(calcLowpassIIRCoefficients(0.01, 49.9).cutoffHz, 49.9);
}

TEST(SignalFilter, RefusesBadInput) {
    using test::throwsErrorAt;
    const Eigen::VectorXd ok = Eigen::VectorXd::LinSpaced(10, 0, 1);
    EXPECT_TRUE(throwsErrorAt([&] { lowpassIIR(ok.head(3), 0.01, 6); }, "lowpassIIR: ", {"3 samples"}, "3 samples"));
    Eigen::VectorXd withNaN = ok;
    withNaN(7) = std::nan("");
    EXPECT_TRUE(throwsErrorAt([&] { lowpassIIR(withNaN, 0.01, 6); }, "lowpassIIR: ", {"sample 7"}, "NaN at 7"));
    EXPECT_TRUE(throwsErrorAt([&] { lowpassIIR(ok, 0, 6); }, "lowpassIIR: ", {"sample period"}, "T = 0"));
    EXPECT_TRUE(throwsErrorAt([&] { lowpassIIR(ok, 0.01, 0); }, "lowpassIIR: ", {"cutoff"}, "fc = 0"));
    EXPECT_TRUE(throwsErrorAt([&] { lowpassIIR(ok, 0.01, std::nan("")); }, "lowpassIIR: ", {"cutoff"}, "fc = NaN"));
    EXPECT_TRUE(throwsErrorAt([&] { padSignal(ok, 10); }, "padSignal: ", {"pad size 10 for 10 samples"}, "pad 10"));
}

}  // namespace
}  // namespace sinew
