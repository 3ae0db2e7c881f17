// Natural smoothing splines against an independent dense solution: the truncated-power representation
// s(t) = sum_{k<m} a_k t^k + sum_i d_i (t - x_i)_+^(2m-1) with the natural moment conditions and the
// smoothing conditions s(x_i) + p (-1)^m (2m-1)! d_i / w_i = y_i (the Euler-Lagrange equations of the
// penalized sum of squares), solved densely. Also: polynomials of degree < m are reproduced for every p,
// derivatives match finite differences, GCV picks the p of least GCV and removes noise.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <random>

#include "sinew/core/error.hpp"
#include "sinew/signal/smoothing_spline.hpp"
#include "support/allocation_counter.hpp"
#include "support/error_assertions.hpp"

namespace sinew {
namespace {

double factorial(int k) { return k <= 1 ? 1.0 : k * factorial(k - 1); }

// d^order/dt^order of t^power
double powerDerivative(double t, int power, int order) {
    if (order > power) return 0;
    return factorial(power) / factorial(power - order) * std::pow(t, power - order);
}

// The dense reference: solves for (a, d) and evaluates s and its derivatives; also the influence matrix.
struct DenseNaturalSpline {
    int m;
    Eigen::VectorXd x, a, d;

    DenseNaturalSpline(int degree, const Eigen::VectorXd& sites, const Eigen::VectorXd& y, const Eigen::VectorXd& w,
                       double p)
        : m((degree + 1) / 2), x(sites) {
        const Eigen::MatrixXd M = matrix(w, p);
        Eigen::VectorXd rhs = Eigen::VectorXd::Zero(M.rows());
        rhs.head(x.size()) = y;
        const Eigen::VectorXd solution = M.fullPivLu().solve(rhs);
        a = solution.tail(m);
        d = solution.head(x.size());
    }

    Eigen::MatrixXd matrix(const Eigen::VectorXd& w, double p) const {
        const Eigen::Index n = x.size();
        Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n + m, n + m);
        const double sign = m % 2 == 0 ? 1 : -1;
        for (Eigen::Index i = 0; i < n; ++i) {
            for (Eigen::Index l = 0; l < n; ++l) M(i, l) = x(i) > x(l) ? std::pow(x(i) - x(l), 2 * m - 1) : 0.0;
            M(i, i) += p * sign * factorial(2 * m - 1) / w(i);
            for (int k = 0; k < m; ++k) M(i, n + k) = std::pow(x(i), k);
        }
        for (int k = 0; k < m; ++k)
            for (Eigen::Index l = 0; l < n; ++l) M(n + k, l) = std::pow(x(l), k);
        return M;
    }

    double derivative(double t, int order) const {
        double s = 0;
        for (int k = 0; k < m; ++k) s += a(k) * powerDerivative(t, k, order);
        for (Eigen::Index l = 0; l < x.size(); ++l)
            if (t > x(l)) s += d(l) * powerDerivative(t - x(l), 2 * m - 1, order);
        return s;
    }

    // n - trace(A), A = d s(x) / d y
    double residualDegreesOfFreedom(const Eigen::VectorXd& w, double p) const {
        const Eigen::Index n = x.size();
        const Eigen::MatrixXd M = matrix(w, p);
        Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n + m, n);
        rhs.topRows(n).setIdentity();
        const Eigen::MatrixXd coefficients = M.fullPivLu().solve(rhs);  // columns: (d; a) per unit datum
        // s(x_i) = y_i - p (-1)^m (2m-1)! d_i / w_i, so A_ii = 1 - p (-1)^m (2m-1)! dd_i/dy_i / w_i.
        const double sign = m % 2 == 0 ? 1 : -1;
        double dof = 0;
        for (Eigen::Index i = 0; i < n; ++i) dof += p * sign * factorial(2 * m - 1) * coefficients(i, i) / w(i);
        return dof;
    }
};

struct Samples {
    Eigen::VectorXd x, y, w;
};

Samples randomSamples(int n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> step(0.5, 1.5), value(-1, 1), weight(0.5, 2);
    Samples s{Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n)};
    double t = 0;
    for (int i = 0; i < n; ++i) {
        s.x(i) = t;
        t += step(rng);
        s.y(i) = value(rng);
        s.w(i) = weight(rng);
    }
    s.x /= s.x(n - 1);  // sites on [0, 1], uneven
    return s;
}

std::vector<double> evaluationPoints(unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-0.2, 1.2);  // beyond both ends too (natural continuation)
    std::vector<double> points{0.0, 1.0};
    for (int i = 0; i < 25; ++i) points.push_back(u(rng));
    return points;
}

// p from interpolation to heavy smoothing, relative to the natural scale h^(2m-1) of sites h apart.
std::vector<double> smoothingParameters(int degree, int n) {
    const double scale = std::pow(1.0 / (n - 1), degree);
    return {0.0, 1e-2 * scale, scale, 1e2 * scale};
}

TEST(SmoothingSpline, MatchesTheDenseNaturalSplineForEveryDegreeAndP) {
    for (int degree : {1, 3, 5, 7}) {
        const Samples s = randomSamples(12, 10 + degree);
        for (double p : smoothingParameters(degree, 12)) {
            const SmoothingSpline spline = SmoothingSpline::fitForSmoothingParameter(degree, s.x, s.y, p, s.w);
            const DenseNaturalSpline reference(degree, s.x, s.y, s.w, p);
            for (int order = 0; order <= degree + 1; ++order) {
                double scale = 0;
                for (double t : evaluationPoints(degree)) scale = std::max(scale, std::abs(reference.derivative(t, order)));
                for (double t : evaluationPoints(degree)) {
                    if (t == 0 && order == degree) continue;  // s^(2m-1) jumps at the sites; the two sides differ
                    EXPECT_NEAR(spline.calcDerivative(t, order), reference.derivative(t, order), 1e-8 * (scale + 1))
                        << "degree " << degree << " p " << p << " t " << t << " order " << order;
                }
            }
            EXPECT_NEAR(spline.getResidualDegreesOfFreedom(), reference.residualDegreesOfFreedom(s.w, p), 1e-7)
                << "degree " << degree << " p " << p;
        }
    }
}

// Many series on the same sites share one basis: each column must still be its own interpolant.
TEST(SmoothingSpline, InterpolatesEveryColumnAsTheDenseNaturalSplineDoes) {
    for (int degree : {1, 3, 5, 7}) {
        const Samples s = randomSamples(14, 30 + degree);
        Eigen::MatrixXd values(s.x.size(), 3);
        for (int c = 0; c < 3; ++c) values.col(c) = randomSamples(14, 40 + 3 * degree + c).y;
        const std::vector<SmoothingSpline> splines = SmoothingSpline::interpolateColumns(degree, s.x, values);
        ASSERT_EQ(splines.size(), 3u);
        for (int c = 0; c < 3; ++c) {
            const DenseNaturalSpline reference(degree, s.x, values.col(c), Eigen::VectorXd::Ones(s.x.size()), 0.0);
            for (int order = 0; order < degree; ++order) {
                double scale = 0;
                for (double t : evaluationPoints(degree)) scale = std::max(scale, std::abs(reference.derivative(t, order)));
                for (double t : evaluationPoints(degree))
                    EXPECT_NEAR(splines[static_cast<std::size_t>(c)].calcDerivative(t, order), reference.derivative(t, order),
                                1e-8 * (scale + 1))
                        << "degree " << degree << " column " << c << " t " << t << " order " << order;
            }
        }
    }
}

// A table's columns evaluated together (one interval look-up and one set of de Boor's factors for the
// splines that share sites) give each spline's calcDerivative bit for bit, inside the sites and in the
// natural continuation beyond them, also where splines of two fits (other sites) alternate in the list.
TEST(SmoothingSpline, ColumnsEvaluatedTogetherGiveEachSplinesOwnDerivatives) {
    for (int degree : {1, 3, 5, 7}) {
        const Samples a = randomSamples(20, 60 + degree), b = randomSamples(17, 70 + degree);
        Eigen::MatrixXd valuesA(a.x.size(), 3), valuesB(b.x.size(), 2);
        for (int c = 0; c < 3; ++c) valuesA.col(c) = randomSamples(20, 80 + 3 * degree + c).y;
        for (int c = 0; c < 2; ++c) valuesB.col(c) = randomSamples(17, 90 + 3 * degree + c).y;
        const std::vector<SmoothingSpline> fitA = SmoothingSpline::interpolateColumns(degree, a.x, valuesA);
        const std::vector<SmoothingSpline> fitB = SmoothingSpline::interpolateColumns(degree, b.x, valuesB);
        const std::vector<SmoothingSpline> mixed = {fitA[0], fitA[1], fitB[0], fitA[2], fitB[1], fitB[0]};
        const int highest = degree;  // one beyond the last non-zero derivative
        std::vector<double> together(mixed.size() * static_cast<std::size_t>(highest + 1));
        for (double t : {a.x(0) - 0.3, a.x(0), a.x(3), (a.x(4) + a.x(5)) / 2, b.x(5), b.x(16) + 0.1, a.x(19), a.x(19) + 2}) {
            SmoothingSpline::calcDerivatives(mixed.data(), mixed.size(), t, highest, together.data());
            for (std::size_t j = 0; j < mixed.size(); ++j)
                for (int order = 0; order <= highest; ++order)
                    EXPECT_EQ(together[j * static_cast<std::size_t>(highest + 1) + static_cast<std::size_t>(order)],
                              mixed[j].calcDerivative(t, order))
                        << "degree " << degree << " spline " << j << " t " << t << " order " << order;
        }
    }
}

TEST(SmoothingSpline, ReproducesPolynomialsOfDegreeBelowM) {
    for (int degree : {1, 3, 5, 7}) {
        const int m = (degree + 1) / 2;
        const Samples s = randomSamples(3 * m + 5, 20 + degree);
        Eigen::VectorXd c(m);
        for (int k = 0; k < m; ++k) c(k) = 0.7 - 0.4 * k;
        auto polynomial = [&](double t, int order) {
            double value = 0;
            for (int k = 0; k < m; ++k) value += c(k) * powerDerivative(t, k, order);
            return value;
        };
        Eigen::VectorXd y(s.x.size());
        for (Eigen::Index i = 0; i < y.size(); ++i) y(i) = polynomial(s.x(i), 0);
        const double heavy = smoothingParameters(degree, static_cast<int>(y.size()))[2];
        for (const SmoothingSpline& spline :
             {SmoothingSpline::fitForSmoothingParameter(degree, s.x, y, 0.0),
              SmoothingSpline::fitForSmoothingParameter(degree, s.x, y, heavy, s.w),
              SmoothingSpline::fitFromGCV(degree, s.x, y)})
            for (double t : evaluationPoints(degree))
                for (int order = 0; order <= degree; ++order)  // rounding grows like 1/h^order
                    EXPECT_NEAR(spline.calcDerivative(t, order), polynomial(t, order),
                                1e-10 * std::pow(static_cast<double>(y.size()), order))
                        << "degree " << degree << " t " << t << " order " << order;
    }
}

TEST(SmoothingSpline, InterpolatesWithNaturalEndsAndDerivativesMatchFiniteDifferences) {
    for (int degree : {3, 5, 7}) {
        const int m = (degree + 1) / 2;
        const Samples s = randomSamples(30, 30 + degree);
        const SmoothingSpline spline = SmoothingSpline::fitFromErrorVariance(degree, s.x, s.y, 0.0);
        EXPECT_EQ(spline.getSmoothingParameter(), 0);
        EXPECT_EQ(spline.getResidualDegreesOfFreedom(), 0);
        for (Eigen::Index i = 0; i < s.x.size(); ++i) EXPECT_NEAR(spline.calcValue(s.x(i)), s.y(i), 1e-11);
        // Natural: derivatives m .. 2m-2 vanish at both ends.
        for (int order = m; order <= 2 * m - 2; ++order) {
            EXPECT_NEAR(spline.calcDerivative(0.0, order), 0, 1e-6 * std::pow(30.0, order)) << order;
            EXPECT_NEAR(spline.calcDerivative(1.0, order), 0, 1e-6 * std::pow(30.0, order)) << order;
        }
        // Each derivative is the central difference of the one below (step h, error O(h^2)).
        const double h = 1e-5;
        for (double t : {0.13, 0.5, 0.77, 0.96})
            for (int order = 1; order <= 2; ++order) {
                const double difference =
                    (spline.calcDerivative(t + h, order - 1) - spline.calcDerivative(t - h, order - 1)) / (2 * h);
                EXPECT_NEAR(spline.calcDerivative(t, order), difference, 1e-5 * (1 + std::abs(difference)))
                    << "degree " << degree << " t " << t << " order " << order;
            }
    }
}

// Samples of a smooth signal with Gaussian noise of standard deviation sigma.
struct NoisySignal {
    Eigen::VectorXd t, truth, truthRate, noisy;
};

NoisySignal noisySignal(int n, double sigma, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0, sigma);
    NoisySignal s{Eigen::VectorXd::LinSpaced(n, 0, 2), Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n)};
    for (int i = 0; i < n; ++i) {
        const double t = s.t(i);
        s.truth(i) = std::sin(2 * M_PI * t) + 0.5 * std::cos(3 * M_PI * t);
        s.truthRate(i) = 2 * M_PI * std::cos(2 * M_PI * t) - 1.5 * M_PI * std::sin(3 * M_PI * t);
        s.noisy(i) = s.truth(i) + noise(rng);
    }
    return s;
}

double rms(const Eigen::VectorXd& v) { return std::sqrt(v.squaredNorm() / static_cast<double>(v.size())); }

TEST(SmoothingSpline, GCVAndKnownVarianceRemoveNoise) {
    const double sigma = 0.05;
    const NoisySignal s = noisySignal(200, sigma, 7);
    const double rawError = rms(s.noisy - s.truth);
    for (int degree : {3, 5}) {
        for (const bool gcv : {true, false}) {
            const SmoothingSpline spline = gcv ? SmoothingSpline::fitFromGCV(degree, s.t, s.noisy)
                                               : SmoothingSpline::fitFromErrorVariance(degree, s.t, s.noisy, sigma * sigma);
            Eigen::VectorXd fitted(s.t.size()), rate(s.t.size());
            for (Eigen::Index i = 0; i < s.t.size(); ++i) {
                fitted(i) = spline.calcValue(s.t(i));
                rate(i) = spline.calcDerivative(s.t(i), 1);
            }
            const double error = rms(fitted - s.truth);
            std::printf("degree %d %s: p %.3g, rms error %.4f (raw %.4f), rate error %.3f of %.3f, dof %.1f\n",
                        degree, gcv ? "GCV" : "variance", spline.getSmoothingParameter(), error, rawError,
                        rms(rate - s.truthRate), rms(s.truthRate), spline.getResidualDegreesOfFreedom());
            EXPECT_LT(error, 0.4 * rawError) << degree << (gcv ? " GCV" : " variance");
            EXPECT_LT(rms(rate - s.truthRate), 0.1 * rms(s.truthRate)) << degree;
            if (gcv) {
                EXPECT_NEAR(spline.getErrorVarianceEstimate(), sigma * sigma, 0.3 * sigma * sigma);
            }
        }
    }
}

TEST(SmoothingSpline, GCVChoosesTheSmoothingParameterOfLeastGCV) {
    const NoisySignal s = noisySignal(40, 0.1, 11);
    const Eigen::VectorXd w = Eigen::VectorXd::Ones(40);
    const SmoothingSpline spline = SmoothingSpline::fitFromGCV(5, s.t, s.noisy);
    // The dense reference's GCV on a fine logarithmic grid of p.
    double bestGcv = INFINITY, bestP = 0;
    for (double e = -14; e <= 0; e += 0.01) {
        const double p = std::pow(10.0, e);
        const DenseNaturalSpline reference(5, s.t, s.noisy, w, p);
        double rss = 0;
        for (Eigen::Index i = 0; i < s.t.size(); ++i) rss += std::pow(s.noisy(i) - reference.derivative(s.t(i), 0), 2);
        const double dofFraction = reference.residualDegreesOfFreedom(w, p) / 40;
        const double gcv = rss / 40 / (dofFraction * dofFraction);
        if (gcv < bestGcv) bestGcv = gcv, bestP = p;
    }
    EXPECT_LE(spline.getGeneralizedCrossValidation(), bestGcv * (1 + 1e-9));
    EXPECT_NEAR(std::log10(spline.getSmoothingParameter()), std::log10(bestP), 0.02);
}

TEST(SmoothingSpline, EvaluatingAllocatesNothing) {
    if (!test::isCountingAllocations()) GTEST_SKIP() << "allocations are not counted under AddressSanitizer";
    const Samples s = randomSamples(50, 5);
    const SmoothingSpline spline = SmoothingSpline::fitForSmoothingParameter(5, s.x, s.y, 1e-6);
    double sum = 0;
    const long long before = test::getAllocationCount();
    for (double t = -0.1; t < 1.1; t += 0.01) sum += spline.calcValue(t) + spline.calcDerivative(t, 2);
    EXPECT_EQ(test::getAllocationCount(), before);
    EXPECT_TRUE(std::isfinite(sum));
}

TEST(SmoothingSpline, RefusesBadInput) {
    auto refused = [](auto action, const std::string& words, const std::string& input) {
        return test::throwsErrorAt(action, "smoothing spline: ", {words}, input);
    };
    const Samples s = randomSamples(10, 1);
    EXPECT_TRUE(refused([&] { SmoothingSpline::fitFromGCV(4, s.x, s.y); }, "degree 4", "degree 4"));
    EXPECT_TRUE(refused([&] { SmoothingSpline::fitFromGCV(9, s.x, s.y); }, "degree 9", "degree 9"));
    EXPECT_TRUE(refused([&] { SmoothingSpline::fitFromGCV(5, s.x.head(5), s.y.head(5)); }, "at least 6", "5 samples"));
    EXPECT_TRUE(refused([&] { SmoothingSpline::fitFromGCV(5, s.x, s.y.head(9)); }, "9 values for 10 sites", "9 values"));
    Eigen::VectorXd x = s.x;
    x(6) = x(5);
    EXPECT_TRUE(refused([&] { SmoothingSpline::fitFromGCV(5, x, s.y); }, "x[6]", "x[6] = x[5]"));
    Eigen::VectorXd y = s.y;
    y(3) = std::nan("");
    EXPECT_TRUE(refused([&] { SmoothingSpline::fitFromGCV(5, s.x, y); }, "y[3]", "y[3] NaN"));
    Eigen::VectorXd w = Eigen::VectorXd::Ones(10);
    w(2) = 0;
    EXPECT_TRUE(refused([&] { SmoothingSpline::fitFromGCV(5, s.x, s.y, w); }, "w[2]", "w[2] = 0"));
    EXPECT_TRUE(refused([&] { SmoothingSpline::fitForSmoothingParameter(5, s.x, s.y, -1); }, "smoothing parameter", "p < 0"));
    EXPECT_TRUE(refused([&] { SmoothingSpline::fitFromErrorVariance(5, s.x, s.y, -1); }, "error variance", "var < 0"));
    Eigen::MatrixXd columns(10, 2);
    columns << s.y, s.y;
    columns(4, 1) = std::nan("");
    EXPECT_TRUE(refused([&] { SmoothingSpline::interpolateColumns(5, s.x, columns); }, "y[4]", "column NaN"));
    EXPECT_TRUE(refused([&] { SmoothingSpline::interpolateColumns(5, s.x, columns.topRows(9)); }, "9 rows of values for 10 sites",
                        "9 rows"));
    const SmoothingSpline spline = SmoothingSpline::fitFromGCV(5, s.x, s.y);
    EXPECT_TRUE(refused([&] { spline.calcDerivative(0.5, -1); }, "derivative order -1", "order -1"));
    EXPECT_TRUE(refused([&] { spline.calcValue(std::nan("")); }, "non-finite", "t NaN"));
}

}  // namespace
}  // namespace sinew
