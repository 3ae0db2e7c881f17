// sinew::Function against hand-computed values, finite differences, and the properties that pin down the
// Forsythe-Malcolm-Moler spline OpenSim's SimmSpline uses (it reproduces any cubic; with three knots, the
// parabola through them; with two, the line).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "sinew/core/error.hpp"
#include "sinew/core/function.hpp"
#include "support/allocation_counter.hpp"

namespace sinew {
namespace {

double centralDifference(const Function& f, double x, int order) {
    const double h = 1e-5;
    if (order == 1) return (f.calcValue(x + h) - f.calcValue(x - h)) / (2 * h);
    return (f.calcDerivative(x + h, 1) - f.calcDerivative(x - h, 1)) / (2 * h);
}

std::vector<double> randomKnots(std::mt19937& rng, int n) {
    std::uniform_real_distribution<double> gap(0.1, 0.8);
    std::vector<double> x{-1.0};
    for (int i = 1; i < n; ++i) x.push_back(x.back() + gap(rng));
    return x;
}

TEST(Function, ConstantLinearPolynomialByHand) {
    const Function c = Function::constant(2.5);
    EXPECT_EQ(c.calcValue(-7), 2.5);
    EXPECT_EQ(c.calcDerivative(3, 1), 0.0);
    EXPECT_EQ(c.calcDerivative(3, 2), 0.0);
    const Function l = Function::linear(-2, 0.5);  // OpenSim's "slope intercept"
    EXPECT_DOUBLE_EQ(l.calcValue(1.5), -2.5);
    EXPECT_EQ(l.calcDerivative(1.5, 1), -2.0);
    EXPECT_EQ(l.calcDerivative(1.5, 2), 0.0);
    const Function p = Function::polynomial({2, -3, 0, 5});  // 2x^3 - 3x^2 + 5, highest first
    EXPECT_DOUBLE_EQ(p.calcValue(2), 9);
    EXPECT_DOUBLE_EQ(p.calcDerivative(2, 1), 12);  // 6x^2 - 6x
    EXPECT_DOUBLE_EQ(p.calcDerivative(2, 2), 18);  // 12x - 6
    EXPECT_EQ(p.getType(), Function::Type::Polynomial);
    EXPECT_EQ(p.getCoefficients(), (std::vector<double>{2, -3, 0, 5}));
}

TEST(Function, MultiplierScalesValueAndDerivatives) {
    const Function p = Function::polynomial({1, 0, 1});
    const Function m = p.multipliedBy(1.5).multipliedBy(-2);
    EXPECT_EQ(m.getScale(), -3.0);
    EXPECT_EQ(p.getScale(), 1.0);
    for (double x : {-1.0, 0.3, 2.0}) {
        EXPECT_DOUBLE_EQ(m.calcValue(x), -3 * (x * x + 1));
        EXPECT_DOUBLE_EQ(m.calcDerivative(x, 1), -6 * x);
        EXPECT_DOUBLE_EQ(m.calcDerivative(x, 2), -6);
    }
}

TEST(Function, SimmSplineReproducesAnyCubicOnRandomKnots) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> coefficient(-2, 2);
    for (int trial = 0; trial < 20; ++trial) {
        const std::vector<double> cubic{coefficient(rng), coefficient(rng), coefficient(rng), coefficient(rng)};
        const Function reference = Function::polynomial(cubic);
        const std::vector<double> x = randomKnots(rng, 4 + trial % 9);
        std::vector<double> y;
        for (double xi : x) y.push_back(reference.calcValue(xi));
        const Function spline = Function::simmSpline(x, y);
        std::uniform_real_distribution<double> inside(x.front(), x.back());
        for (int k = 0; k < 50; ++k) {
            const double s = inside(rng);
            ASSERT_NEAR(spline.calcValue(s), reference.calcValue(s), 1e-11) << "trial " << trial << " x " << s;
            ASSERT_NEAR(spline.calcDerivative(s, 1), reference.calcDerivative(s, 1), 1e-10);
            ASSERT_NEAR(spline.calcDerivative(s, 2), reference.calcDerivative(s, 2), 1e-9);
        }
    }
}

TEST(Function, SimmSplineThroughThreeKnotsIsTheParabolaAndThroughTwoTheLine) {
    const Function parabola = Function::polynomial({0.7, -1, 0.25});
    const std::vector<double> x{-0.5, 0.2, 1.4};
    std::vector<double> y;
    for (double xi : x) y.push_back(parabola.calcValue(xi));
    const Function three = Function::simmSpline(x, y);
    for (double s = -0.5; s <= 1.4; s += 0.05) {
        EXPECT_NEAR(three.calcValue(s), parabola.calcValue(s), 1e-13);
        EXPECT_NEAR(three.calcDerivative(s, 2), 1.4, 1e-12);
    }
    const Function two = Function::simmSpline({1, 3}, {2, -2});
    EXPECT_DOUBLE_EQ(two.calcValue(2.5), -1);
    EXPECT_DOUBLE_EQ(two.calcDerivative(2.5, 1), -2);
    EXPECT_EQ(two.calcDerivative(2.5, 2), 0.0);
}

TEST(Function, SplineIsTwiceContinuouslyDifferentiableAndExtrapolatesLinearly) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> value(-1, 1);
    const std::vector<double> x = randomKnots(rng, 9);
    std::vector<double> y;
    for (std::size_t i = 0; i < x.size(); ++i) y.push_back(value(rng));
    for (const Function& f : {Function::simmSpline(x, y), Function::naturalCubicSpline(x, y)}) {
        for (std::size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(f.calcValue(x[i]), y[i], 1e-14) << "knot " << i;
        const double e = 1e-11;  // either side of each interior knot: the two cubics meet to second order
        for (std::size_t i = 1; i + 1 < x.size(); ++i) {
            EXPECT_NEAR(f.calcValue(x[i] - e), f.calcValue(x[i] + e), 1e-9);
            for (int order : {1, 2}) {
                const double left = f.calcDerivative(x[i] - e, order);
                EXPECT_NEAR(left, f.calcDerivative(x[i] + e, order), 1e-9 * (1 + std::abs(left))) << "order " << order;
            }
        }
        for (double s : {x.front() - 0.7, x.back() + 1.3}) {
            const std::size_t end = s < x.front() ? 0 : x.size() - 1;
            const double slope = f.calcDerivative(x[end], 1);
            EXPECT_NEAR(f.calcValue(s), y[end] + (s - x[end]) * slope, 1e-13);
            EXPECT_EQ(f.calcDerivative(s, 1), slope);
            EXPECT_EQ(f.calcDerivative(s, 2), 0.0);
        }
        // OpenSim reads a NaturalCubicSpline as a SimmSpline: the same curve.
        EXPECT_EQ(f.calcValue(0.123), Function::simmSpline(x, y).calcValue(0.123));
    }
}

TEST(Function, DerivativesMatchFiniteDifferences) {
    std::mt19937 rng(7);
    const std::vector<double> x = randomKnots(rng, 7);
    const std::vector<double> y{0.1, -0.3, 0.2, 0.9, 0.4, -0.2, 0.0};
    const std::vector<Function> functions{Function::linear(1.3, -0.2), Function::polynomial({0.3, -1, 2, 0.5, -1}),
                                          Function::simmSpline(x, y).multipliedBy(1.14724),
                                          Function::naturalCubicSpline(x, y)};
    std::uniform_real_distribution<double> at(x.front() + 1e-3, x.back() - 1e-3);
    for (const Function& f : functions)
        for (int k = 0; k < 40; ++k) {
            const double s = at(rng);
            EXPECT_NEAR(f.calcDerivative(s, 1), centralDifference(f, s, 1), 1e-7);
            EXPECT_NEAR(f.calcDerivative(s, 2), centralDifference(f, s, 2), 1e-6);
        }
}

TEST(Function, RejectsBadInput) {
    auto message = [](auto&& make) {
        try {
            make();
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("(accepted)");
    };
    EXPECT_NE(message([] { Function::simmSpline({0, 1, 1}, {0, 1, 2}); }).find("strictly increasing"), std::string::npos);
    EXPECT_NE(message([] { Function::simmSpline({0, 1}, {0}); }).find("x has 2 values but y has 1"), std::string::npos);
    EXPECT_NE(message([] { Function::naturalCubicSpline({0}, {0}); }).find("at least 2 knots"), std::string::npos);
    EXPECT_NE(message([] { Function::simmSpline({0, NAN}, {0, 1}); }).find("finite"), std::string::npos);
    EXPECT_NE(message([] { Function::polynomial({}); }).find("at least one coefficient"), std::string::npos);
    EXPECT_NE(message([] { Function::linear(INFINITY, 0); }).find("finite"), std::string::npos);
    EXPECT_NE(message([] { Function::constant(1).multipliedBy(NAN); }).find("scale"), std::string::npos);
    EXPECT_NE(message([] { Function::constant(1).calcDerivative(0, 3); }).find("order must be 1 or 2"), std::string::npos);
}

TEST(Function, EvaluationAllocatesNothing) {
    if (!test::isCountingAllocations()) GTEST_SKIP() << "allocations are not counted under AddressSanitizer";
    const Function spline = Function::simmSpline({0, 0.5, 1.2, 2, 3.1}, {0, 1, -1, 0.5, 2}).multipliedBy(2);
    const Function polynomial = Function::polynomial({1, 2, 3, 4});
    const long long before = test::getAllocationCount();
    double sum = 0;
    for (double s = -1; s < 4; s += 0.01)
        sum += spline.calcValue(s) + spline.calcDerivative(s, 2) + polynomial.calcDerivative(s, 1);
    EXPECT_EQ(test::getAllocationCount(), before);
    EXPECT_TRUE(std::isfinite(sum));
}

}  // namespace
}  // namespace sinew
