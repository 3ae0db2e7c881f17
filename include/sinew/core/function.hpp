#pragma once
// A scalar function of one variable with its first and second derivatives: the functions OpenSim's
// CustomJoint transform axes and coordinate couplers use (Constant, LinearFunction, SimmSpline,
// NaturalCubicSpline, PolynomialFunction, each optionally scaled as a MultiplierFunction). A value type;
// evaluating it allocates nothing. Conventions and sources in docs/opensim-joints.md, "Functions".
#include <vector>

namespace sinew {

class Function {
public:
    enum class Type { Constant, Linear, SimmSpline, NaturalCubicSpline, Polynomial };

    // Every factory throws sinew::Error for non-finite numbers or knots it cannot fit.
    static Function constant(double value);
    static Function linear(double slope, double intercept);
    // OpenSim's SimmSpline (Forsythe, Malcolm and Moler's cubic spline; end conditions match the third
    // derivative of the cubic through the first and last four knots), extrapolated linearly with the end
    // slopes. Needs >= 2 knots with strictly increasing, finite x.
    static Function simmSpline(std::vector<double> x, std::vector<double> y);
    // OpenSim 4 reads a NaturalCubicSpline as a SimmSpline (RegisterTypes_osimCommon.cpp renames the
    // type), so this is the same curve; the type is kept only to be written back under its own name.
    static Function naturalCubicSpline(std::vector<double> x, std::vector<double> y);
    // sum_i c_i x^(n-1-i), highest order first as SimTK::Function::Polynomial; at least one coefficient.
    static Function polynomial(std::vector<double> coefficientsHighestFirst);
    // OpenSim's MultiplierFunction: scale times this function (scales of nested multipliers multiply).
    Function multipliedBy(double scale) const;

    double calcValue(double x) const;
    double calcDerivative(double x, int order) const;  // order 1 or 2; throws sinew::Error otherwise

    Type getType() const { return type_; }
    double getScale() const { return scale_; }  // 1 unless multipliedBy
    const std::vector<double>& getX() const { return x_; }  // knots (splines), empty otherwise
    const std::vector<double>& getY() const { return y_; }
    // {value} (constant), {slope, intercept} (linear), highest order first (polynomial); empty for splines.
    const std::vector<double>& getCoefficients() const { return coefficients_; }

private:
    Function() = default;
    static Function fitSpline(Type type, std::vector<double> x, std::vector<double> y);  // knots checked
    double evaluateUnscaled(double x, int order) const;
    double evaluateSpline(double x, int order) const;

    Type type_ = Type::Constant;
    double scale_ = 1;
    std::vector<double> coefficients_;
    std::vector<double> x_, y_;
    // Spline segment k: y_k + b_k dx + c_k dx^2 + d_k dx^3 with dx = x - x_k (FMM's coefficient names).
    std::vector<double> b_, c_, d_;
};

}  // namespace sinew
