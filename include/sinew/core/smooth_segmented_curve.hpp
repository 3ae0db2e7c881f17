#pragma once
// A C1-smooth curve y(x) made of quintic Bézier corners, as OpenSim's SmoothSegmentedFunction builds the
// Millard 2012 muscle curves (SegmentedQuinticBezierToolkit::calcQuinticBezierCornerControlPoints): between
// consecutive knots (x, y, dy/dx) one corner whose control points lie on the knots' tangent lines, pulled
// towards the lines' intersection by the segment's curviness. Outside the first and last knots the curve
// continues along their tangents. The integral from the first knot is exact (Gauss-Legendre on each
// segment's degree-9 integrand), so a passive curve's energy is its force's work to rounding.
#include <string>
#include <vector>

namespace sinew {

struct CurveKnot {
    double x = 0, y = 0, slope = 0;
};

class SmoothSegmentedCurve {
public:
    SmoothSegmentedCurve() = default;
    // knots: two or more, x strictly increasing; curviness: one per segment, in [0, 1] as OpenSim's curve
    // objects take it (scaled to 0.1 + 0.8 c as OpenSim's factory scales it). Throws sinew::Error naming
    // `name` and the segment when a corner is not C-shaped (its tangents do not meet between the knots).
    SmoothSegmentedCurve(std::string name, const std::vector<CurveKnot>& knots, const std::vector<double>& curviness);

    double calcValue(double x) const;
    double calcSlope(double x) const;
    // ∫ y dx from the first knot's x to x (negative below it).
    double calcIntegral(double x) const;

    double getFirstX() const { return segments_.front().x[0]; }
    double getLastX() const { return segments_.back().x[5]; }
    const std::string& getName() const { return name_; }

private:
    struct Segment {
        double x[6], y[6];
        double integralBefore = 0;  // ∫ y dx from the first knot to this segment's start
    };
    struct Point {
        const Segment* segment = nullptr;
        double u = 0;  // Bézier parameter in [0, 1]
    };
    Point locate(double x) const;
    double integrateSegment(const Segment& segment, double u) const;

    std::string name_;
    std::vector<Segment> segments_;
    CurveKnot first_, last_;
};

}  // namespace sinew
