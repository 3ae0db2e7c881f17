#pragma once
// OpenSim Function objects (joint transform axes, moving path points, couplers, muscle curves) as read from
// XML, kept as data: turning them into something that evaluates is the model converter's job.
#include <string>
#include <vector>

namespace sinew {

enum class OsimFunctionType {
    Constant,            // f(x) = value
    Linear,              // f(x) = coefficients[0] x + coefficients[1]
    SimmSpline,          // SIMM's natural cubic spline through (x, y)
    NaturalCubicSpline,  // OpenSim 1.x name of the same spline; OpenSim 4 reads it as a SimmSpline
    PiecewiseLinear,     // straight segments through (x, y)
    Polynomial,          // sum of coefficients[i] x^(n-1-i): highest power first, as OpenSim stores it
    Multiplier,          // f(x) = scale * inner[0](x)
};

const char* toString(OsimFunctionType type);

struct OsimFunction {
    OsimFunctionType type = OsimFunctionType::Constant;
    double value = 0;                  // Constant
    std::vector<double> coefficients;  // Linear: {slope, intercept} (size 2); Polynomial: size >= 1
    std::vector<double> x, y;          // splines and PiecewiseLinear: knots, x strictly increasing, size >= 2
    double scale = 1;                  // Multiplier
    std::vector<OsimFunction> inner;   // Multiplier: the one function it scales (size 1)
    std::string where;                 // "file:line" of the function's XML element
};

}  // namespace sinew
