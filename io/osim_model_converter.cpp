#include "sinew/io/osim_model_converter.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "conversion_notes.hpp"
#include "number_text.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/model_builder.hpp"

namespace sinew {
namespace {

// OpenSim's fixed-axis joints written as CustomJoint SpatialTransforms (docs/opensim-import.md): for each
// of rotation1-3 and translation1-3, the axis in F and the index of the joint coordinate driving it
// (-1: none). Rotation axes are listed even when unused because a SpatialTransform needs three
// independent ones.
struct AxisTable {
    std::array<Eigen::Vector3d, 6> axes;
    std::array<int, 6> coordinate;
};

AxisTable getAxisTable(OsimJointType type) {
    const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY(), z = Eigen::Vector3d::UnitZ();
    switch (type) {
        case OsimJointType::Pin: return {{z, x, y, x, y, z}, {0, -1, -1, -1, -1, -1}};
        case OsimJointType::Slider: return {{x, y, z, x, y, z}, {-1, -1, -1, 0, -1, -1}};
        case OsimJointType::Universal: return {{x, y, z, x, y, z}, {0, 1, -1, -1, -1, -1}};
        case OsimJointType::Ball:
        case OsimJointType::Gimbal: return {{x, y, z, x, y, z}, {0, 1, 2, -1, -1, -1}};
        case OsimJointType::Planar: return {{z, x, y, x, y, z}, {0, -1, -1, 1, 2, -1}};
        case OsimJointType::Free: return {{x, y, z, x, y, z}, {0, 1, 2, 3, 4, 5}};
        case OsimJointType::Custom:
        case OsimJointType::Weld: break;
    }
    throw Error(std::string("no axis table for OpenSim joint type ") + toString(type));
}

std::string linkName(const OsimModel& osim, const std::string& body) {
    return body == osim.ground.name ? std::string("ground") : body;
}

// SimTK::Inertia's own validity test (MassProperties.h, Inertia_::errChk), which OpenSim's Body relies on:
// moments non-negative, the triangle inequality and the products bounded by the moments, each with
// Simbody's slop of sqrt(eps) times the moments' sum.
bool isValidSimbodyInertia(const Eigen::Matrix3d& I) {
    const Eigen::Vector3d d = I.diagonal();
    const double significant = std::pow(std::numeric_limits<double>::epsilon(), 7.0 / 8.0);  // SimTK::SignificantReal
    if (!(d.minCoeff() >= -significant)) return false;
    const double slop = std::max(d.sum(), 1.0) * std::sqrt(std::numeric_limits<double>::epsilon());
    return d[0] + d[1] + slop >= d[2] && d[0] + d[2] + slop >= d[1] && d[1] + d[2] + slop >= d[0] &&
           d[0] + slop >= std::abs(2 * I(1, 2)) && d[1] + slop >= std::abs(2 * I(0, 2)) &&
           d[2] + slop >= std::abs(2 * I(0, 1));
}

// OpenSim's Body::getInertia policy, applied where OpenSim applies it and reported in `notes`: a massless
// body (|mass| <= SimTK::SignificantReal) gets zero inertia; an inertia SimTK::Inertia refuses becomes a
// sphere whose moment is the norm of the given moments over sqrt(3).
LinkSpec convertBody(const OsimBody& body, std::vector<std::string>& notes) {
    LinkSpec link;
    link.name = body.name;
    link.mass = body.mass;
    link.com_B = body.massCenter;
    const auto& I = body.inertia;  // Ixx Iyy Izz Ixy Ixz Iyz
    link.inertia_Bcom << I[0], I[3], I[4], I[3], I[1], I[5], I[4], I[5], I[2];
    link.where = body.where;
    if (!link.inertia_Bcom.allFinite() || !std::isfinite(link.mass)) return link;  // the builder names the field
    const double significant = std::pow(std::numeric_limits<double>::epsilon(), 7.0 / 8.0);
    if (std::abs(link.mass) <= significant) {
        if (!link.inertia_Bcom.isZero(0))
            notes.push_back(describeAt("Body", body.name, body.where) +
                            ": massless but with non-zero inertia; inertia reset to zero, as OpenSim does");
        link.mass = 0;
        link.inertia_Bcom.setZero();
    } else if (!isValidSimbodyInertia(link.inertia_Bcom)) {
        const Eigen::Vector3d moments = link.inertia_Bcom.diagonal();
        const double sphere = moments.norm() / std::sqrt(3.0);
        notes.push_back(describeAt("Body", body.name, body.where) + ": invalid inertia (moments " +
                        formatNumber(moments[0]) + ", " + formatNumber(moments[1]) + ", " + formatNumber(moments[2]) +
                        "); reset to a sphere of moment " + formatNumber(sphere) + " kg m^2, as OpenSim's Body does");
        link.inertia_Bcom = sphere * Eigen::Matrix3d::Identity();
    }
    return link;
}

CoordinateSpec convertCoordinate(const OsimCoordinate& c) {
    CoordinateSpec spec;
    spec.name = c.name;
    spec.defaultValue = c.defaultValue;
    spec.rangeMin = c.rangeMin;
    spec.rangeMax = c.rangeMax;
    spec.clamped = c.clamped;
    spec.locked = c.locked;
    spec.where = c.where;
    return spec;
}

JointSpec convertJoint(const OsimModel& osim, const OsimJoint& oj) {
    JointSpec js;
    js.name = oj.name;
    js.parent = linkName(osim, oj.parent.body);
    js.child = oj.child.body;
    js.p_PF = oj.parent.p_BF;
    js.R_PF = oj.parent.R_BF;
    js.p_BM = oj.child.p_BF;
    js.R_BM = oj.child.R_BF;
    js.where = oj.where;
    if (oj.type == OsimJointType::Weld) {
        js.type = JointType::Weld;
        return js;
    }
    js.type = JointType::Custom;
    for (int c = 0; c < oj.numCoordinates; ++c)
        js.coordinates.push_back(convertCoordinate(osim.coordinates[static_cast<std::size_t>(oj.firstCoordinate + c)]));
    if (oj.type == OsimJointType::Custom) {
        for (const OsimTransformAxis& axis : oj.spatialTransform) {
            if (axis.coordinates.size() > 1)
                throw ModelError(axis.function.where, "joint '" + oj.name + "': a transform axis driven by " +
                                                          std::to_string(axis.coordinates.size()) +
                                                          " coordinates (sinew takes at most one)");
            TransformAxisSpec spec;
            spec.axis = axis.axis;
            if (!axis.coordinates.empty()) spec.coordinate = axis.coordinates.front();
            spec.function = convertOsimFunction(axis.function);
            js.transformAxes.push_back(spec);
        }
        return js;
    }
    const AxisTable table = getAxisTable(oj.type);
    for (std::size_t k = 0; k < 6; ++k) {
        TransformAxisSpec spec;
        spec.axis = table.axes[k];
        const int c = table.coordinate[k];
        if (c >= 0) {
            if (c >= oj.numCoordinates)
                throw ModelError(oj.where, std::string(toString(oj.type)) + " '" + oj.name + "' has " +
                                               std::to_string(oj.numCoordinates) + " coordinates, expected more");
            spec.coordinate = js.coordinates[static_cast<std::size_t>(c)].name;
            spec.function = Function::linear(1, 0);
        } else {
            spec.function = Function::constant(0);
        }
        js.transformAxes.push_back(spec);
    }
    return js;
}

WrapObjectSpec convertWrapObject(const OsimWrapObject& w, const std::string& link) {
    WrapObjectSpec spec;
    spec.name = w.name;
    spec.link = link;
    spec.xyzBodyRotation = w.xyzBodyRotation;
    spec.translation = w.translation;
    spec.where = w.where;
    spec.quadrant = (w.quadrant.empty() || w.quadrant == "Unassigned") ? std::string("all") : w.quadrant;
    switch (w.shape) {
        case OsimWrapObject::Shape::Sphere: spec.shape = WrapShape::Sphere; spec.radius = w.radius; break;
        case OsimWrapObject::Shape::Cylinder:
            spec.shape = WrapShape::Cylinder;
            spec.radius = w.radius;
            spec.length = w.length;
            break;
        case OsimWrapObject::Shape::Ellipsoid: spec.shape = WrapShape::Ellipsoid; spec.radii = w.dimensions; break;
        case OsimWrapObject::Shape::Torus: break;  // refused by the caller
    }
    return spec;
}

// sinew's wire points sit on links, so path points on ground (muscles anchored to the world, as in
// Tug_of_War) go to a massless link welded to ground at the world frame: the same geometry and dynamics.
std::string getGroundAnchorName(const OsimModel& osim) {
    std::string name = "ground_anchor";
    auto taken = [&](const std::string& candidate) {
        return std::any_of(osim.bodies.begin(), osim.bodies.end(),
                           [&](const OsimBody& body) { return body.name == candidate; });
    };
    while (taken(name)) name += "_";
    return name;
}

bool hasGroundPathPoints(const OsimModel& osim) {
    for (const OsimPathForce& force : osim.pathForces)
        for (const OsimPathPoint& point : force.path.points)
            if (point.frame.body == osim.ground.name) return true;
    return false;
}

void addGroundAnchor(const OsimModel& osim, ModelBuilder& builder, std::vector<std::string>& notes) {
    const std::string name = getGroundAnchorName(osim);
    builder.addLink(LinkSpec{name, 0.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero(), osim.ground.where});
    JointSpec weld;
    weld.name = name + "_weld";
    weld.type = JointType::Weld;
    weld.parent = "ground";
    weld.child = name;
    weld.where = osim.ground.where;
    builder.addJoint(weld);
    notes.push_back(describeAt("Ground", osim.ground.name, osim.ground.where) + ": its path points are on '" + name +
                    "', a massless link welded to ground (sinew's wire points sit on links)");
}

WirePointSpec convertPathPoint(const OsimModel& osim, const OsimPathPoint& point, const std::string& muscle) {
    WirePointSpec spec;
    spec.link = point.frame.body;
    spec.where = point.where;
    if (spec.link == osim.ground.name) spec.link = getGroundAnchorName(osim);
    if (point.type != OsimPathPoint::Type::Moving) {
        spec.p_B = point.frame.p_BF + point.frame.R_BF * point.location;
        if (point.type == OsimPathPoint::Type::Conditional)
            spec.condition = WirePointConditionSpec{point.coordinate, point.rangeMin, point.rangeMax};
        return spec;
    }
    // A moving component maps onto one axis of the link only on an unrotated frame at its origin.
    if (!point.frame.R_BF.isIdentity(0) || !point.frame.p_BF.isZero(0))
        throw ModelError(point.where, "muscle '" + muscle + "': moving path point '" + point.name +
                                          "' on an offset frame (sinew moves points along their link's axes only)");
    for (int axis = 0; axis < 3; ++axis) {
        const Function f = convertOsimFunction(point.locationFunctions[static_cast<std::size_t>(axis)]);
        const std::string& coordinate = point.locationCoordinates[static_cast<std::size_t>(axis)];
        if (coordinate.empty())
            spec.p_B[axis] = f.calcValue(0);
        else
            spec.motions.push_back(WirePointMotionSpec{axis, coordinate, f});
    }
    return spec;
}

WrapMethod convertWrapMethod(const OsimPathWrap& wrap) {
    if (wrap.method == "midpoint") return WrapMethod::Midpoint;
    if (wrap.method == "axial") return WrapMethod::Axial;
    if (wrap.method == "hybrid" || wrap.method.empty()) return WrapMethod::Hybrid;
    throw ModelError(wrap.where, "unknown wrap method '" + wrap.method + "' (expected hybrid, midpoint or axial)");
}

// The file's properties named in `names` (OpenSim's name, sinew's parameter) as law parameters.
void copyMuscleProperties(const OsimPathForce& muscle, const std::vector<std::pair<std::string, std::string>>& names,
                          ForceLawSpec& law) {
    for (const auto& [osimName, sinewName] : names) {
        const auto it = muscle.properties.find(osimName);
        // An empty element is an optional property left unset (OpenSim's empty list property).
        if (it == muscle.properties.end() || it->second.empty()) continue;
        const std::optional<double> value = parseNumber(it->second);
        if (!value)
            throw ModelError(muscle.where, "muscle '" + muscle.name + "': " + osimName + " '" + it->second +
                                               "' is not a number");
        law.parameters.set(sinewName, {*value});
    }
}

// Millard2012EquilibriumMuscle and DeGrooteFregly2016Muscle keep their own laws and curves; every other
// muscle type becomes Thelen's (with its curve parameters when the file gives them), which the
// conversion's warnings say.
ForceLawSpec makeMuscleLaw(const OsimPathForce& muscle, std::vector<std::string>& warnings) {
    ForceLawSpec law;
    const bool millard = muscle.type == "Millard2012EquilibriumMuscle";
    const bool deGroote = muscle.type == "DeGrooteFregly2016Muscle";
    law.type = millard ? "millard2012_muscle" : deGroote ? "degroote_fregly2016_muscle" : "thelen2003_muscle";
    law.parameters.set("max_isometric_force", {muscle.maxIsometricForce});
    law.parameters.set("optimal_fiber_length", {muscle.optimalFiberLength});
    law.parameters.set("tendon_slack_length", {muscle.tendonSlackLength});
    law.parameters.set("pennation_angle_at_optimal", {muscle.pennationAngleAtOptimal});
    law.parameters.set("max_contraction_velocity", {muscle.maxContractionVelocity});
    if (millard) {
        std::vector<std::pair<std::string, std::string>> names{{"fiber_damping", "fiber_damping"},
                                                               {"maximum_pennation_angle", "maximum_pennation_angle"}};
        const std::map<std::string, std::vector<std::string>> curves{
            {"ActiveForceLengthCurve",
             {"min_norm_active_fiber_length", "transition_norm_fiber_length", "max_norm_active_fiber_length",
              "shallow_ascending_slope", "minimum_value"}},
            {"ForceVelocityCurve",
             {"concentric_slope_at_vmax", "concentric_slope_near_vmax", "isometric_slope", "eccentric_slope_at_vmax",
              "eccentric_slope_near_vmax", "max_eccentric_velocity_force_multiplier", "concentric_curviness",
              "eccentric_curviness"}},
            {"FiberForceLengthCurve",
             {"strain_at_zero_force", "strain_at_one_norm_force", "stiffness_at_low_force",
              "stiffness_at_one_norm_force", "curviness"}}};
        for (const auto& [curve, properties] : curves)
            for (const std::string& property : properties) names.emplace_back(curve + "." + property, property);
        copyMuscleProperties(muscle, names, law);
        return law;
    }
    if (deGroote) {
        static const std::vector<std::pair<std::string, std::string>> names{
            {"active_force_width_scale", "active_force_width_scale"},
            {"fiber_damping", "fiber_damping"},
            {"passive_fiber_strain_at_one_norm_force", "passive_fiber_strain_at_one_norm_force"}};
        copyMuscleProperties(muscle, names, law);
        const auto ignore = muscle.properties.find("ignore_passive_fiber_force");
        if (ignore != muscle.properties.end() && (ignore->second == "true" || ignore->second == "1"))
            law.parameters.set("ignore_passive_fiber_force", {1});
        return law;
    }
    if (muscle.type != "Thelen2003Muscle")
        warnings.push_back(describeAt(muscle.type, muscle.name, muscle.where) +
                           ": sinew has no law of this type; it becomes thelen2003_muscle with the same max isometric "
                           "force, fibre and tendon lengths, pennation and max contraction velocity");
    static const std::vector<std::pair<std::string, std::string>> names{{"FmaxMuscleStrain", "fmax_muscle_strain"},
                                                                        {"KshapeActive", "kshape_active"},
                                                                        {"KshapePassive", "kshape_passive"},
                                                                        {"Af", "af"},
                                                                        {"Flen", "flen"}};
    copyMuscleProperties(muscle, names, law);
    return law;
}

void addMuscle(const OsimModel& osim, const OsimPathForce& muscle, ModelBuilder& builder,
               std::vector<std::string>& warnings) {
    WireSpec wire;
    wire.name = muscle.name;
    wire.kind = WireKind::Muscle;
    wire.where = muscle.where;
    for (const OsimPathPoint& point : muscle.path.points) wire.points.push_back(convertPathPoint(osim, point, muscle.name));
    for (const OsimPathWrap& wrap : muscle.path.wraps) {
        WireWrapSpec spec;
        spec.object = wrap.wrapObject;
        if (wrap.rangeBegin > 0) spec.firstPoint = wrap.rangeBegin - 1;
        if (wrap.rangeEnd > 0) spec.lastPoint = wrap.rangeEnd - 1;
        spec.method = convertWrapMethod(wrap);
        spec.where = wrap.where;
        wire.wraps.push_back(spec);
    }
    wire.law = makeMuscleLaw(muscle, warnings);
    builder.addWire(std::move(wire));
}

CoordinateCouplerSpec convertCoupler(const OsimCoordinateCoupler& coupler) {
    // sinew's functions take one argument; OpenSim's of several (MultivariatePolynomialFunction) have no
    // counterpart.
    if (coupler.independentCoordinates.size() != 1)
        throw ModelError(coupler.where, "CoordinateCouplerConstraint '" + coupler.name + "': " +
                                            std::to_string(coupler.independentCoordinates.size()) +
                                            " independent coordinates (sinew couples to exactly one)");
    CoordinateCouplerSpec spec;
    spec.name = coupler.name;
    spec.dependentCoordinate = coupler.dependentCoordinate;
    spec.independentCoordinate = coupler.independentCoordinates.front();
    spec.function = convertOsimFunction(coupler.function);
    spec.scaleFactor = coupler.scaleFactor;
    spec.where = coupler.where;
    return spec;
}

LinkFrameSpec convertFrame(const OsimModel& osim, const OsimFrameRef& frame) {
    return {linkName(osim, frame.body), frame.p_BF, calcBodyFixedXYZ(frame.R_BF)};
}

// OpenSim's CoordinateLimitForce takes degrees (and stiffness per degree) on a rotational coordinate.
CoordinateLimitForceSpec convertCoordinateLimit(const OsimModel& osim, const OsimCoordinateLimitForce& force) {
    const OsimCoordinate* coordinate = findCoordinate(osim, force.coordinate);
    const double w = coordinate && coordinate->motionType == OsimMotionType::Rotational ? M_PI / 180 : 1.0;
    return {force.name,      force.coordinate, force.upperStiffness / w, w * force.upperLimit, force.lowerStiffness / w,
            w * force.lowerLimit, force.damping / w, w * force.transition, force.where};
}

// Every pair OpenSim's contact set would test that sinew computes: a sphere and a half-space on different
// bodies. Other pairs (two spheres) are listed as not imported.
void addHuntCrossleyForce(const OsimModel& osim, const OsimHuntCrossleyForce& force, ModelBuilder& builder,
                          std::set<std::string>& usedGeometry, std::vector<std::string>& notImported) {
    HuntCrossleyForceSpec spec{force.name, {}, force.transitionVelocity, force.where};
    int spheres = 0;
    for (const OsimHuntCrossleyForce::Parameters& p : force.parameters)
        for (const std::string& name : p.geometry) {
            const auto geometry = std::find_if(osim.contactGeometry.begin(), osim.contactGeometry.end(),
                                               [&](const OsimContactGeometry& g) { return g.name == name; });
            if (geometry == osim.contactGeometry.end())
                throw ModelError(force.where, "HuntCrossleyForce '" + force.name + "': no contact geometry '" + name + "'");
            spheres += geometry->type == "ContactSphere";
            usedGeometry.insert(name);
            spec.surfaces.push_back({name, p.stiffness, p.dissipation, p.staticFriction, p.dynamicFriction, p.viscousFriction});
        }
    if (spheres > 1)
        notImported.push_back(describeAt("HuntCrossleyForce", force.name, force.where) +
                              ": its sphere-sphere pairs (sinew computes spheres against half-spaces only)");
    builder.addHuntCrossleyForce(std::move(spec));
}

void addForceElements(const OsimModel& osim, ModelBuilder& builder, std::vector<std::string>& notImported) {
    const auto disabled = [&](const char* type, const std::string& name, const std::string& where) {
        notImported.push_back(describeAt(type, name, where) + ": disabled in the model");
    };
    for (const OsimCoordinateLimitForce& force : osim.coordinateLimits) {
        if (force.appliesForce) builder.addCoordinateLimitForce(convertCoordinateLimit(osim, force));
        else disabled("CoordinateLimitForce", force.name, force.where);
    }
    for (const OsimPointToPointSpring& spring : osim.springs) {
        if (!spring.appliesForce) {
            disabled("PointToPointSpring", spring.name, spring.where);
            continue;
        }
        builder.addPointToPointSpring({spring.name, linkName(osim, spring.point1.body), linkName(osim, spring.point2.body),
                                       spring.point1.p_BF, spring.point2.p_BF, spring.stiffness, spring.restLength,
                                       spring.where});
    }
    for (const OsimBushingForce& bushing : osim.bushings) {
        if (!bushing.appliesForce) {
            disabled("BushingForce", bushing.name, bushing.where);
            continue;
        }
        builder.addBushingForce({bushing.name, convertFrame(osim, bushing.frame1), convertFrame(osim, bushing.frame2),
                                 bushing.rotationalStiffness, bushing.translationalStiffness, bushing.rotationalDamping,
                                 bushing.translationalDamping, bushing.where});
    }
    std::set<std::string> usedGeometry;
    for (const OsimHuntCrossleyForce& force : osim.huntCrossley) {
        if (force.appliesForce) addHuntCrossleyForce(osim, force, builder, usedGeometry, notImported);
        else disabled("HuntCrossleyForce", force.name, force.where);
    }
    // Geometry no force touches with does nothing; it is kept only where a force uses it.
    for (const OsimContactGeometry& geometry : osim.contactGeometry) {
        if (!usedGeometry.count(geometry.name)) {
            notImported.push_back(describeAt(geometry.type, geometry.name, geometry.where) + ": no contact force uses it");
            continue;
        }
        const bool sphere = geometry.type == "ContactSphere";
        builder.addContactGeometry({geometry.name,
                                    sphere ? ContactGeometry::Shape::Sphere : ContactGeometry::Shape::HalfSpace,
                                    convertFrame(osim, geometry.frame), geometry.radius, geometry.where});
    }
}

}  // namespace

void reportOsimConversion(const OsimConversion& conversion, const std::function<void(const std::string&)>& notes) {
    if (!notes) return;
    for (const std::string& line : conversion.warnings) notes("warning: " + line);
    for (const std::string& line : conversion.notImported) notes("not imported: " + line);
}

Function convertOsimFunction(const OsimFunction& f) {
    try {
        switch (f.type) {
            case OsimFunctionType::Constant: return Function::constant(f.value);
            case OsimFunctionType::Linear: return Function::linear(f.coefficients.at(0), f.coefficients.at(1));
            case OsimFunctionType::SimmSpline: return Function::simmSpline(f.x, f.y);
            case OsimFunctionType::NaturalCubicSpline: return Function::naturalCubicSpline(f.x, f.y);
            case OsimFunctionType::Polynomial: return Function::polynomial(f.coefficients);
            case OsimFunctionType::Multiplier: return convertOsimFunction(f.inner.at(0)).multipliedBy(f.scale);
            case OsimFunctionType::PiecewiseLinear: break;
        }
    } catch (const ModelError&) {
        throw;
    } catch (const std::exception& e) {
        throw ModelError(f.where, std::string(toString(f.type)) + ": " + e.what());
    }
    throw ModelError(f.where, std::string(toString(f.type)) + " is not supported by sinew's model (expected "
                                  "Constant, LinearFunction, SimmSpline, NaturalCubicSpline, PolynomialFunction or "
                                  "MultiplierFunction)");
}

OsimConversion convertOsimModel(const OsimModel& osim) {
    ModelBuilder builder(osim.name);
    std::vector<std::string> notImported;
    builder.setGravity(osim.gravity, osim.file);
    std::vector<std::string> warnings;
    for (const OsimBody& body : osim.bodies) builder.addLink(convertBody(body, warnings));
    for (const OsimJoint& joint : osim.joints) builder.addJoint(convertJoint(osim, joint));
    if (hasGroundPathPoints(osim)) addGroundAnchor(osim, builder, warnings);

    auto addWrapObjects = [&](const OsimBody& body) {
        for (const OsimWrapObject& w : body.wrapObjects) {
            if (w.shape == OsimWrapObject::Shape::Torus)
                notImported.push_back(describeAt("WrapTorus", w.name, w.where) + ": torus wrapping is not supported");
            else if (!w.active)
                notImported.push_back(describeAt("wrap object", w.name, w.where) + ": inactive");
            else
                builder.addWrapObject(convertWrapObject(w, linkName(osim, body.name)));
        }
    };
    addWrapObjects(osim.ground);
    for (const OsimBody& body : osim.bodies) addWrapObjects(body);

    for (const OsimPathForce& force : osim.pathForces) {
        if (force.kind != OsimPathForce::Kind::Muscle)
            notImported.push_back(describeAt(force.type, force.name, force.where) +
                                  ": only muscles become wires so far");
        else if (!force.limits.appliesForce)
            notImported.push_back(describeAt(force.type, force.name, force.where) + ": disabled in the model");
        else
            addMuscle(osim, force, builder, warnings);
    }
    for (const OsimCoordinateCoupler& coupler : osim.couplers) {
        if (coupler.enforced)
            builder.addCoupler(convertCoupler(coupler));
        else
            notImported.push_back(describeAt("CoordinateCouplerConstraint", coupler.name, coupler.where) +
                                  ": disabled in the model (the dependent coordinate is free, as in OpenSim)");
    }
    addForceElements(osim, builder, notImported);
    for (const OsimCoordinateActuator& a : osim.coordinateActuators)
        notImported.push_back(describeAt("CoordinateActuator", a.name, a.where) + ": actuators are not wires");
    for (const OsimPointActuator& a : osim.pointActuators)
        notImported.push_back(describeAt("PointActuator", a.name, a.where) + ": actuators are not wires");
    for (const OsimTorqueActuator& a : osim.torqueActuators)
        notImported.push_back(describeAt("TorqueActuator", a.name, a.where) + ": actuators are not wires");
    for (const OsimUnsupported& u : osim.unsupported)
        notImported.push_back(describeAt(u.type, u.name, u.where) + ": not read from the .osim file");
    return {builder.build(), std::move(notImported), std::move(warnings)};
}

}  // namespace sinew
