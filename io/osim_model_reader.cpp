#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <string_view>

#include "osim_xml.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/osim_model.hpp"

namespace sinew {

const char* toString(OsimJointType type) {
    switch (type) {
        case OsimJointType::Custom: return "CustomJoint";
        case OsimJointType::Pin: return "PinJoint";
        case OsimJointType::Slider: return "SliderJoint";
        case OsimJointType::Weld: return "WeldJoint";
        case OsimJointType::Ball: return "BallJoint";
        case OsimJointType::Gimbal: return "GimbalJoint";
        case OsimJointType::Universal: return "UniversalJoint";
        case OsimJointType::Planar: return "PlanarJoint";
        case OsimJointType::Free: return "FreeJoint";
    }
    return "?";
}

namespace {

using osim::Element;
using osim::XmlDocument;
using Motion = OsimMotionType;

struct JointTypeInfo {
    OsimJointType type;
    std::vector<OsimMotionType> motions;  // of its coordinates in order; a CustomJoint's come from its axes
};

const std::map<std::string, JointTypeInfo>& jointTypes() {
    static const std::map<std::string, JointTypeInfo> types = {
        {"CustomJoint", {OsimJointType::Custom, {}}},
        {"PinJoint", {OsimJointType::Pin, {Motion::Rotational}}},
        {"SliderJoint", {OsimJointType::Slider, {Motion::Translational}}},
        {"WeldJoint", {OsimJointType::Weld, {}}},
        {"BallJoint", {OsimJointType::Ball, {Motion::Rotational, Motion::Rotational, Motion::Rotational}}},
        {"GimbalJoint", {OsimJointType::Gimbal, {Motion::Rotational, Motion::Rotational, Motion::Rotational}}},
        {"UniversalJoint", {OsimJointType::Universal, {Motion::Rotational, Motion::Rotational}}},
        {"PlanarJoint", {OsimJointType::Planar, {Motion::Rotational, Motion::Translational, Motion::Translational}}},
        {"FreeJoint",
         {OsimJointType::Free,
          {Motion::Rotational, Motion::Rotational, Motion::Rotational, Motion::Translational, Motion::Translational,
           Motion::Translational}}}};
    return types;
}

struct PathForceTypeInfo {
    OsimPathForce::Kind kind;
    OsimActuatorLimits limits;  // the type's defaults
};

const std::map<std::string, PathForceTypeInfo>& pathForceTypes() {
    using Kind = OsimPathForce::Kind;
    const OsimActuatorLimits muscle{1, 0, 1, true};  // Muscle's constructor
    // Thelen2003Muscle and Millard2012EquilibriumMuscle start min_control at their minimum_activation
    // default, 0.01, before the XML is read.
    const OsimActuatorLimits activationFloor{1, 0.01, 1, true};
    static const std::map<std::string, PathForceTypeInfo> types = {
        {"Thelen2003Muscle", {Kind::Muscle, activationFloor}},
        {"Millard2012EquilibriumMuscle", {Kind::Muscle, activationFloor}},
        {"Millard2012AccelerationMuscle", {Kind::Muscle, muscle}},
        {"Schutte1993Muscle_Deprecated", {Kind::Muscle, muscle}},
        {"Delp1990Muscle_Deprecated", {Kind::Muscle, muscle}},
        {"RigidTendonMuscle", {Kind::Muscle, muscle}},
        {"DeGrooteFregly2016Muscle", {Kind::Muscle, muscle}},
        {"PathActuator", {Kind::PathActuator, {}}},
        {"Ligament", {Kind::Ligament, {}}},
        {"PathSpring", {Kind::PathSpring, {}}}};
    return types;
}

// A socket path joined to the path of the component that owns the socket, as OpenSim resolves it:
// absolute paths stand, relative ones start at the owner, ".." climbs one component.
std::string makeAbsolutePath(const std::string& owner, const std::string& path) {
    // Built in place: each segment appended as "/segment", ".." cutting the last one off again.
    std::string absolute;
    absolute.reserve(owner.size() + path.size() + 2);
    auto append = [&](std::string_view segments) {
        for (std::size_t start = 0; start <= segments.size();) {
            std::size_t end = segments.find('/', start);
            if (end == std::string_view::npos) end = segments.size();
            const std::string_view segment = segments.substr(start, end - start);
            if (segment == "..") {
                absolute.resize(absolute.empty() ? 0 : absolute.rfind('/'));
            } else if (!segment.empty() && segment != ".") {
                absolute += '/';
                absolute += segment;
            }
            start = end + 1;
        }
    };
    if (path.front() != '/') append(owner);
    append(path);
    return absolute.empty() ? "/" : absolute;
}

std::string lastSegment(const std::string& path) { return path.substr(path.find_last_of('/') + 1); }

class OsimModelReader {
public:
    explicit OsimModelReader(const std::string& path) : doc_(path) {}

    OsimModel read() {
        const Element& root = doc_.getObject("Model");
        if (doc_.getVersion() < 40000)
            throw ModelError(doc_.where(root),
                             "OpenSim document Version " + std::to_string(doc_.getVersion()) +
                                 " is the OpenSim 3.x layout (joints inside bodies, location_in_parent); sinew reads "
                                 "Version 40000 and later. Open and save the model in OpenSim 4 to convert it.");
        model_.name = osim::getName(root);
        model_.file = doc_.getPath();
        model_.version = doc_.getVersion();
        readModelProperties(root);
        for (const std::string& path : frameOrder_) resolveFrame(path);
        if (jointSet_)
            for (const Element* joint : osim::getSetObjects(*jointSet_)) readJoint(*joint);
        if (constraintSet_)
            for (const Element* constraint : osim::getSetObjects(*constraintSet_)) readConstraint(*constraint);
        if (contactGeometrySet_)
            for (const Element* geometry : osim::getSetObjects(*contactGeometrySet_)) readContactGeometry(*geometry);
        if (forceSet_)
            for (const Element* force : osim::getSetObjects(*forceSet_)) readForce(*force);
        if (markerSet_)
            for (const Element* marker : osim::getSetObjects(*markerSet_)) readMarker(*marker);
        return std::move(model_);
    }

private:
    XmlDocument doc_;
    OsimModel model_;
    const Element* jointSet_ = nullptr;
    const Element* constraintSet_ = nullptr;
    const Element* forceSet_ = nullptr;
    const Element* contactGeometrySet_ = nullptr;
    std::string contactGeometrySetPath_ = "/contactgeometryset";
    const Element* markerSet_ = nullptr;
    std::string jointSetPath_ = "/jointset", forceSetPath_ = "/forceset", markerSetPath_ = "/markerset";
    // PhysicalOffsetFrame elements by absolute path, with the frames they resolved to (bodies and ground
    // enter resolved).
    std::map<std::string, const Element*> frameDefinitions_;
    std::vector<std::string> frameOrder_;  // their paths in file order
    std::map<std::string, OsimFrameRef> resolvedFrames_;
    std::set<std::string> resolving_;  // to catch frames offset from each other in a loop
    std::map<std::string, int> coordinatesByPath_;
    std::set<std::string> bodyNames_, jointNames_, coordinateNames_, forceNames_;

    void addUnsupported(const Element& element) {
        model_.unsupported.push_back({osim::typeOf(element), osim::getName(element), doc_.where(element)});
    }

    std::string requireName(const Element& element, std::set<std::string>& taken, const char* what) {
        const std::string name = osim::getName(element);
        if (name.empty()) doc_.fail(element, std::string("a ") + what + " needs a name attribute");
        if (!taken.insert(name).second) doc_.fail(element, std::string("a second ") + what + " named '" + name + "'");
        return name;
    }

    const Element& requireChild(const Element& owner, const char* property) const {
        const Element* child = osim::findChild(owner, property);
        if (!child) doc_.fail(owner, std::string("missing <") + property + ">");
        return *child;
    }

    void addFrameDefinition(const std::string& path, const Element& frame) {
        if (!frameDefinitions_.emplace(path, &frame).second) doc_.fail(frame, "a second frame at " + path);
        frameOrder_.push_back(path);
    }

    // The path a Set's objects live under: "/" + the set's name ("bodyset", "forceset", ...).
    std::string setPath(const Element& set, const char* defaultName) const {
        const std::string name = osim::getName(set);
        return "/" + (name.empty() ? std::string(defaultName) : name);
    }

    void readModelProperties(const Element& root) {
        for (const Element* child = osim::firstChild(root); child; child = osim::nextSibling(*child)) {
            const std::string type = osim::typeOf(*child);
            if (type == "Ground") {
                readGround(*child);
            } else if (type == "gravity") {
                model_.gravity = osim::readVector3(doc_, root, "gravity", model_.gravity);
            } else if (type == "length_units") {
                model_.lengthUnits = osim::readText(doc_, root, "length_units");
            } else if (type == "force_units") {
                model_.forceUnits = osim::readText(doc_, root, "force_units");
            } else if (type == "credits" || type == "publications" || type == "assembly_accuracy" ||
                       type == "ModelVisualPreferences") {
                // Documentation, assembly tolerance and display settings: nothing a dynamics model needs.
            } else if (type == "BodySet") {
                for (const Element* body : osim::getSetObjects(*child)) readBody(*body, setPath(*child, "bodyset"));
            } else if (type == "JointSet") {
                jointSet_ = child;
                jointSetPath_ = setPath(*child, "jointset");
                for (const Element* joint : osim::getSetObjects(*child))
                    collectFrames(*joint, "frames", jointSetPath_ + "/" + osim::getName(*joint));
            } else if (type == "ConstraintSet") {
                constraintSet_ = child;
            } else if (type == "ForceSet") {
                forceSet_ = child;
                forceSetPath_ = setPath(*child, "forceset");
            } else if (type == "MarkerSet") {
                markerSet_ = child;
                markerSetPath_ = setPath(*child, "markerset");
            } else if (type == "ComponentSet") {
                for (const Element* component : osim::getSetObjects(*child)) {
                    if (std::string(osim::typeOf(*component)) == "PhysicalOffsetFrame")
                        addFrameDefinition(setPath(*child, "componentset") + "/" + osim::getName(*component), *component);
                    else
                        addUnsupported(*component);
                }
            } else if (type == "ContactGeometrySet") {
                contactGeometrySet_ = child;
                contactGeometrySetPath_ = setPath(*child, "contactgeometryset");
            } else if (type == "ControllerSet" || type == "ProbeSet") {
                for (const Element* object : osim::getSetObjects(*child)) addUnsupported(*object);
            } else {
                addUnsupported(*child);
            }
        }
    }

    void readGround(const Element& element) {
        model_.ground.name = osim::getName(element).empty() ? "ground" : osim::getName(element);
        model_.ground.where = doc_.where(element);
        readWrapObjects(element, model_.ground);
        const std::string path = "/" + model_.ground.name;
        resolvedFrames_[path] = {path, model_.ground.name, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()};
    }

    void readBody(const Element& element, const std::string& setPath) {
        OsimBody body;
        body.name = requireName(element, bodyNames_, "body");
        body.where = doc_.where(element);
        body.mass = osim::readRequiredDouble(doc_, element, "mass");
        if (body.mass < 0) doc_.fail(element, "negative mass " + std::to_string(body.mass));
        body.massCenter = osim::readVector3(doc_, element, "mass_center", body.massCenter);
        const std::vector<double> inertia = osim::readFixedNumbers(doc_, element, "inertia", 6, {0, 0, 0, 0, 0, 0});
        body.inertia = Eigen::Map<const Eigen::Matrix<double, 6, 1>>(inertia.data());
        readWrapObjects(element, body);
        const std::string path = setPath + "/" + body.name;
        resolvedFrames_[path] = {path, body.name, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()};
        collectFrames(element, "components", path);
        model_.bodies.push_back(std::move(body));
    }

    // PhysicalOffsetFrames held in owner's <list>; other components there are listed as unsupported.
    void collectFrames(const Element& owner, const char* list, const std::string& ownerPath) {
        const Element* frames = osim::findChild(owner, list);
        if (!frames) return;
        for (const Element* frame = osim::firstChild(*frames); frame; frame = osim::nextSibling(*frame)) {
            if (std::string(osim::typeOf(*frame)) != "PhysicalOffsetFrame") {
                addUnsupported(*frame);
                continue;
            }
            const std::string name = osim::getName(*frame);
            if (name.empty()) doc_.fail(*frame, "a frame needs a name attribute");
            addFrameDefinition(ownerPath + "/" + name, *frame);
        }
    }

    void readWrapObjects(const Element& owner, OsimBody& body) {
        const Element* set = osim::findChild(owner, "WrapObjectSet");
        if (!set) return;
        for (const Element* element : osim::getSetObjects(*set)) {
            const std::string type = osim::typeOf(*element);
            OsimWrapObject wrap;
            if (type == "WrapSphere") {
                wrap.shape = OsimWrapObject::Shape::Sphere;
                wrap.radius = osim::readDouble(doc_, *element, "radius", 0.05);
            } else if (type == "WrapCylinder") {
                wrap.shape = OsimWrapObject::Shape::Cylinder;
                wrap.radius = osim::readDouble(doc_, *element, "radius", 1);
                wrap.length = osim::readDouble(doc_, *element, "length", 1);
            } else if (type == "WrapEllipsoid") {
                wrap.shape = OsimWrapObject::Shape::Ellipsoid;
                wrap.dimensions = osim::readVector3(doc_, *element, "dimensions", Eigen::Vector3d::Constant(0.05));
            } else if (type == "WrapTorus") {
                wrap.shape = OsimWrapObject::Shape::Torus;
                wrap.innerRadius = osim::readDouble(doc_, *element, "inner_radius", 0.01);
                wrap.outerRadius = osim::readDouble(doc_, *element, "outer_radius", 0.05);
            } else {
                addUnsupported(*element);
                continue;
            }
            wrap.name = osim::getName(*element);
            if (wrap.name.empty()) doc_.fail(*element, "a wrap object needs a name attribute");
            wrap.body = body.name;
            wrap.xyzBodyRotation = osim::readVector3(doc_, *element, "xyz_body_rotation", wrap.xyzBodyRotation);
            wrap.translation = osim::readVector3(doc_, *element, "translation", wrap.translation);
            wrap.quadrant = osim::readText(doc_, *element, "quadrant", wrap.quadrant);
            wrap.active = osim::readBool(doc_, *element, "active", wrap.active);
            wrap.where = doc_.where(*element);
            body.wrapObjects.push_back(std::move(wrap));
        }
    }

    // The frame at an absolute path, resolving PhysicalOffsetFrames on first use; nullptr when none.
    const OsimFrameRef* resolveFrame(const std::string& path) {
        const auto resolved = resolvedFrames_.find(path);
        if (resolved != resolvedFrames_.end()) return &resolved->second;
        const auto definition = frameDefinitions_.find(path);
        if (definition == frameDefinitions_.end()) return nullptr;
        const Element& element = *definition->second;
        if (!resolving_.insert(path).second) doc_.fail(element, "frames are offset from each other in a loop");
        const OsimFrameRef parent = followFrameSocket(requireChild(element, "socket_parent"), path);
        OsimFrame frame;
        frame.name = osim::getName(element);
        frame.parentPath = parent.path;
        frame.translation = osim::readVector3(doc_, element, "translation", frame.translation);
        frame.orientation = osim::readVector3(doc_, element, "orientation", frame.orientation);
        frame.resolved = {path, parent.body, parent.p_BF + parent.R_BF * frame.translation,
                          parent.R_BF * calcRotationFromBodyFixedXYZ(frame.orientation)};
        frame.where = doc_.where(element);
        resolving_.erase(path);
        model_.frames.push_back(frame);
        return &(resolvedFrames_[path] = frame.resolved);
    }

    // A frame socket (its text a component path relative to `ownerPath`, the socket's owner) resolved to
    // a body. A bare name that is not a path from the owner may name a frame anywhere, if only one.
    OsimFrameRef followFrameSocket(const Element& socket, const std::string& ownerPath) {
        const std::string text = osim::textOf(socket);
        if (text.empty()) doc_.fail(socket, "names no frame");
        const std::string path = makeAbsolutePath(ownerPath, text);
        if (const OsimFrameRef* frame = resolveFrame(path)) return *frame;
        if (text.find('/') == std::string::npos) {
            std::vector<std::string> matches;
            for (const auto& entry : resolvedFrames_)
                if (lastSegment(entry.first) == text) matches.push_back(entry.first);
            for (const auto& entry : frameDefinitions_)
                if (lastSegment(entry.first) == text && !resolvedFrames_.count(entry.first)) matches.push_back(entry.first);
            if (matches.size() == 1) return *resolveFrame(matches.front());
        }
        doc_.fail(socket, "'" + text + "' (" + path + ") is no body or frame of the model");
    }

    // A coordinate socket resolved to the coordinate's name, the same way as frames.
    std::string followCoordinateSocket(const Element& socket, const std::string& ownerPath) {
        const std::string text = osim::textOf(socket);
        if (text.empty()) doc_.fail(socket, "names no coordinate");
        const auto found = coordinatesByPath_.find(makeAbsolutePath(ownerPath, text));
        if (found != coordinatesByPath_.end()) return model_.coordinates[found->second].name;
        if (text.find('/') == std::string::npos && coordinateNames_.count(text)) return text;
        doc_.fail(socket, "'" + text + "' is no coordinate of the model");
    }

    void requireCoordinate(const Element& owner, const char* property, const std::string& name) {
        if (!coordinateNames_.count(name)) failOnProperty(owner, property, "'" + name + "' is no coordinate of the model");
    }

    void requireBody(const Element& owner, const char* property, const std::string& name) {
        if (name != model_.ground.name && !bodyNames_.count(name))
            failOnProperty(owner, property, "'" + name + "' is no body of the model");
    }

    // The property is absent when the name came out empty, so the error then points at its owner.
    [[noreturn]] void failOnProperty(const Element& owner, const char* property, const std::string& message) {
        const Element* child = osim::findChild(owner, property);
        if (!child) doc_.fail(owner, std::string("missing <") + property + ">");
        doc_.fail(*child, message);
    }

    void readJoint(const Element& element) {
        const auto info = jointTypes().find(osim::typeOf(element));
        if (info == jointTypes().end()) {
            addUnsupported(element);
            return;
        }
        OsimJoint joint;
        joint.name = requireName(element, jointNames_, "joint");
        joint.type = info->second.type;
        joint.where = doc_.where(element);
        const std::string path = jointSetPath_ + "/" + joint.name;
        joint.parent = followFrameSocket(requireChild(element, "socket_parent_frame"), path);
        joint.child = followFrameSocket(requireChild(element, "socket_child_frame"), path);
        std::vector<const Element*> declared;
        if (const Element* list = osim::findChild(element, "coordinates"))
            for (const Element* coordinate = osim::firstChild(*list); coordinate;
                 coordinate = osim::nextSibling(*coordinate)) {
                if (std::string(osim::typeOf(*coordinate)) != "Coordinate") doc_.fail(*coordinate, "expected a <Coordinate>");
                declared.push_back(coordinate);
            }
        std::vector<const Element*> ordered = declared;
        std::vector<OsimMotionType> motions = info->second.motions;
        if (joint.type == OsimJointType::Custom) {
            readSpatialTransform(element, joint);
            orderCustomCoordinates(element, joint, declared, ordered, motions);
        } else if (declared.size() != motions.size()) {
            doc_.fail(element, std::to_string(declared.size()) + " coordinates; a " + osim::typeOf(element) + " has " +
                                   std::to_string(motions.size()));
        }
        joint.firstCoordinate = static_cast<int>(model_.coordinates.size());
        joint.numCoordinates = static_cast<int>(ordered.size());
        for (std::size_t i = 0; i < ordered.size(); ++i) readCoordinate(*ordered[i], path, motions[i]);
        model_.joints.push_back(std::move(joint));
    }

    void readSpatialTransform(const Element& element, OsimJoint& joint) {
        const Element* transform = osim::findChild(element, "SpatialTransform");
        if (!transform) doc_.fail(element, "a CustomJoint needs a <SpatialTransform>");
        static const char* const names[6] = {"rotation1", "rotation2", "rotation3",
                                             "translation1", "translation2", "translation3"};
        for (int i = 0; i < 6; ++i) {
            OsimTransformAxis& axis = joint.spatialTransform[i];
            axis.axis = Eigen::Vector3d::Unit(i % 3);  // OpenSim's defaults: x, y, z, x, y, z
            axis.function.where = doc_.where(*transform);
            const Element* found = osim::findChild(*transform, "TransformAxis");
            while (found && osim::getName(*found) != names[i]) found = osim::nextSibling(*found, "TransformAxis");
            if (!found) continue;
            axis.coordinates = osim::readNames(doc_, *found, "coordinates");
            if (axis.coordinates.size() > 1)
                doc_.fail(*found, "driven by " + std::to_string(axis.coordinates.size()) +
                                      " coordinates; sinew reads functions of one coordinate");
            axis.axis = osim::readVector3(doc_, *found, "axis", axis.axis);
            if (axis.axis.norm() == 0) doc_.fail(*found, "the axis is zero");
            if (const Element* function = osim::findFunction(doc_, *found, "function"))
                axis.function = osim::readFunction(doc_, *function);
            else
                axis.function.where = doc_.where(*found);
        }
    }

    // OpenSim orders a CustomJoint's coordinates by first use in rotation1 ... translation3 and infers
    // their motion types from the axes they drive (CustomJoint::constructCoordinates): an axis driven
    // through a slope +-1 LinearFunction makes it Rotational (rotation axes) or Translational, and the
    // last such axis wins; driving axes only through other functions makes it Coupled.
    void orderCustomCoordinates(const Element& element, const OsimJoint& joint,
                                const std::vector<const Element*>& declared, std::vector<const Element*>& ordered,
                                std::vector<OsimMotionType>& motions) {
        std::vector<std::string> names;
        for (const OsimTransformAxis& axis : joint.spatialTransform)
            for (const std::string& name : axis.coordinates)
                if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
        ordered.clear();
        motions.clear();
        for (const std::string& name : names) {
            const auto found = std::find_if(declared.begin(), declared.end(),
                                             [&](const Element* c) { return osim::getName(*c) == name; });
            if (found == declared.end())
                doc_.fail(element, "the SpatialTransform uses coordinate '" + name + "', not declared in <coordinates>");
            ordered.push_back(*found);
            bool pure = false;
            OsimMotionType motion = OsimMotionType::Coupled;
            for (int i = 0; i < 6; ++i) {
                const OsimTransformAxis& axis = joint.spatialTransform[i];
                if (std::find(axis.coordinates.begin(), axis.coordinates.end(), name) == axis.coordinates.end()) continue;
                const OsimFunction& f = axis.function;
                if (f.type == OsimFunctionType::Linear && std::abs(f.coefficients[0]) == 1.0) {
                    motion = i < 3 ? OsimMotionType::Rotational : OsimMotionType::Translational;
                    pure = true;
                } else if (!pure) {
                    motion = OsimMotionType::Coupled;
                }
            }
            motions.push_back(motion);
        }
        for (const Element* coordinate : declared)
            if (std::find(ordered.begin(), ordered.end(), coordinate) == ordered.end())
                doc_.fail(*coordinate, "not used by any TransformAxis of the joint");
    }

    void readCoordinate(const Element& element, const std::string& jointPath, OsimMotionType inferred) {
        OsimCoordinate coordinate;
        coordinate.name = requireName(element, coordinateNames_, "coordinate");
        coordinate.joint = static_cast<int>(model_.joints.size());
        coordinate.where = doc_.where(element);
        const std::string motion = osim::readText(doc_, element, "motion_type");
        if (motion.empty())
            coordinate.motionType = inferred;
        else if (motion == "rotational")
            coordinate.motionType = OsimMotionType::Rotational;
        else if (motion == "translational")
            coordinate.motionType = OsimMotionType::Translational;
        else if (motion == "coupled")
            coordinate.motionType = OsimMotionType::Coupled;
        else
            doc_.fail(*osim::findChild(element, "motion_type"),
                      "'" + motion + "', expected rotational, translational or coupled");
        coordinate.defaultValue = osim::readDouble(doc_, element, "default_value", 0);
        coordinate.defaultSpeedValue = osim::readDouble(doc_, element, "default_speed_value", 0);
        const std::vector<double> range = osim::readFixedNumbers(doc_, element, "range", 2, {-10, 10});
        if (range[0] > range[1]) doc_.fail(*osim::findChild(element, "range"), "the range's minimum exceeds its maximum");
        coordinate.rangeMin = range[0];
        coordinate.rangeMax = range[1];
        coordinate.clamped = osim::readBool(doc_, element, "clamped", false);
        coordinate.locked = osim::readBool(doc_, element, "locked", false);
        coordinate.prescribed = osim::readBool(doc_, element, "prescribed", false);
        if (const Element* function = osim::findFunction(doc_, element, "prescribed_function"))
            coordinate.prescribedFunction = osim::readFunction(doc_, *function);
        coordinatesByPath_[jointPath + "/" + coordinate.name] = static_cast<int>(model_.coordinates.size());
        model_.coordinates.push_back(std::move(coordinate));
    }

    void readConstraint(const Element& element) {
        if (std::string(osim::typeOf(element)) != "CoordinateCouplerConstraint") {
            addUnsupported(element);
            return;
        }
        OsimCoordinateCoupler coupler;
        coupler.name = osim::getName(element);
        coupler.where = doc_.where(element);
        coupler.enforced = osim::findChild(element, "isEnforced") ? osim::readBool(doc_, element, "isEnforced", true)
                                                                  : !osim::readBool(doc_, element, "isDisabled", false);
        const Element* function = osim::findFunction(doc_, element, "coupled_coordinates_function");
        if (!function) doc_.fail(element, "missing <coupled_coordinates_function>");
        coupler.function = osim::readFunction(doc_, *function);
        coupler.independentCoordinates = osim::readNames(doc_, element, "independent_coordinate_names");
        if (coupler.independentCoordinates.empty()) doc_.fail(element, "missing <independent_coordinate_names>");
        for (const std::string& name : coupler.independentCoordinates)
            requireCoordinate(element, "independent_coordinate_names", name);
        coupler.dependentCoordinate = osim::readText(doc_, element, "dependent_coordinate_name");
        if (coupler.dependentCoordinate.empty()) doc_.fail(element, "missing <dependent_coordinate_name>");
        requireCoordinate(element, "dependent_coordinate_name", coupler.dependentCoordinate);
        coupler.scaleFactor = osim::readDouble(doc_, element, "scale_factor", 1);
        model_.couplers.push_back(std::move(coupler));
    }

    void readForce(const Element& element) {
        const std::string type = osim::getCurrentTypeName(osim::typeOf(element));
        if (type == "CoordinateActuator") {
            model_.coordinateActuators.push_back(osim::readCoordinateActuator(doc_, element));
            requireCoordinate(element, "coordinate", model_.coordinateActuators.back().coordinate);
        } else if (type == "PointActuator") {
            model_.pointActuators.push_back(osim::readPointActuator(doc_, element));
            requireBody(element, "body", model_.pointActuators.back().body);
        } else if (type == "TorqueActuator") {
            model_.torqueActuators.push_back(osim::readTorqueActuator(doc_, element));
            requireBody(element, "bodyA", model_.torqueActuators.back().bodyA);
            requireBody(element, "bodyB", model_.torqueActuators.back().bodyB);
        } else if (pathForceTypes().count(type)) {
            readPathForce(element, type);
        } else if (type == "CoordinateLimitForce") {
            readCoordinateLimitForce(element);
        } else if (type == "PointToPointSpring") {
            readPointToPointSpring(element);
        } else if (type == "BushingForce") {
            readBushingForce(element);
        } else if (type == "HuntCrossleyForce") {
            readHuntCrossleyForce(element);
        } else {
            addUnsupported(element);
        }
    }

    // A frame with an offset applied in it: location (m) and orientation (body-fixed XYZ, rad).
    static OsimFrameRef offsetFrame(OsimFrameRef frame, const Eigen::Vector3d& location, const Eigen::Vector3d& orientation) {
        frame.p_BF += frame.R_BF * location;
        frame.R_BF = frame.R_BF * calcRotationFromBodyFixedXYZ(orientation);
        return frame;
    }

    void readContactGeometry(const Element& element) {
        OsimContactGeometry geometry;
        geometry.type = osim::typeOf(element);
        geometry.name = osim::getName(element);
        geometry.where = doc_.where(element);
        if (geometry.type != "ContactSphere" && geometry.type != "ContactHalfSpace") {
            addUnsupported(element);
            return;
        }
        const std::string path = contactGeometrySetPath_ + "/" + geometry.name;
        geometry.frame = offsetFrame(followFrameSocket(requireChild(element, "socket_frame"), path),
                                     osim::readVector3(doc_, element, "location", Eigen::Vector3d::Zero()),
                                     osim::readVector3(doc_, element, "orientation", Eigen::Vector3d::Zero()));
        if (geometry.type == "ContactSphere") geometry.radius = osim::readRequiredDouble(doc_, element, "radius");
        model_.contactGeometry.push_back(std::move(geometry));
    }

    // The name, file:line and appliesForce every force element of the ForceSet starts with.
    template <class Force>
    Force readForceHeader(const Element& element) {
        Force force;
        force.name = requireName(element, forceNames_, "force");
        force.where = doc_.where(element);
        force.appliesForce = osim::readAppliesForce(doc_, element, true);
        return force;
    }

    void readCoordinateLimitForce(const Element& element) {
        OsimCoordinateLimitForce force = readForceHeader<OsimCoordinateLimitForce>(element);
        force.coordinate = osim::readText(doc_, element, "coordinate");
        requireCoordinate(element, "coordinate", force.coordinate);
        force.upperStiffness = osim::readDouble(doc_, element, "upper_stiffness", force.upperStiffness);
        force.upperLimit = osim::readDouble(doc_, element, "upper_limit", force.upperLimit);
        force.lowerStiffness = osim::readDouble(doc_, element, "lower_stiffness", force.lowerStiffness);
        force.lowerLimit = osim::readDouble(doc_, element, "lower_limit", force.lowerLimit);
        force.damping = osim::readDouble(doc_, element, "damping", force.damping);
        force.transition = osim::readDouble(doc_, element, "transition", force.transition);
        model_.coordinateLimits.push_back(std::move(force));
    }

    void readPointToPointSpring(const Element& element) {
        OsimPointToPointSpring spring = readForceHeader<OsimPointToPointSpring>(element);
        const std::string path = forceSetPath_ + "/" + spring.name;
        const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
        spring.point1 = offsetFrame(followFrameSocket(requireChild(element, "socket_body1"), path),
                                    osim::readVector3(doc_, element, "point1", zero), zero);
        spring.point2 = offsetFrame(followFrameSocket(requireChild(element, "socket_body2"), path),
                                    osim::readVector3(doc_, element, "point2", zero), zero);
        spring.stiffness = osim::readDouble(doc_, element, "stiffness", spring.stiffness);
        spring.restLength = osim::readDouble(doc_, element, "rest_length", spring.restLength);
        model_.springs.push_back(std::move(spring));
    }

    void readBushingForce(const Element& element) {
        OsimBushingForce bushing = readForceHeader<OsimBushingForce>(element);
        const std::string path = forceSetPath_ + "/" + bushing.name;
        collectFrames(element, "frames", path);
        bushing.frame1 = followFrameSocket(requireChild(element, "socket_frame1"), path);
        bushing.frame2 = followFrameSocket(requireChild(element, "socket_frame2"), path);
        const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
        bushing.rotationalStiffness = osim::readVector3(doc_, element, "rotational_stiffness", zero);
        bushing.translationalStiffness = osim::readVector3(doc_, element, "translational_stiffness", zero);
        bushing.rotationalDamping = osim::readVector3(doc_, element, "rotational_damping", zero);
        bushing.translationalDamping = osim::readVector3(doc_, element, "translational_damping", zero);
        model_.bushings.push_back(std::move(bushing));
    }

    void readHuntCrossleyForce(const Element& element) {
        OsimHuntCrossleyForce force = readForceHeader<OsimHuntCrossleyForce>(element);
        force.transitionVelocity = osim::readDouble(doc_, element, "transition_velocity", force.transitionVelocity);
        if (const Element* set = osim::findChild(element, "HuntCrossleyForce::ContactParametersSet"))
            for (const Element* p : osim::getSetObjects(*set)) {
                OsimHuntCrossleyForce::Parameters parameters;
                std::istringstream names(osim::readText(doc_, *p, "geometry"));
                for (std::string name; names >> name;) parameters.geometry.push_back(name);
                parameters.stiffness = osim::readDouble(doc_, *p, "stiffness", 0);
                parameters.dissipation = osim::readDouble(doc_, *p, "dissipation", 0);
                parameters.staticFriction = osim::readDouble(doc_, *p, "static_friction", 0);
                parameters.dynamicFriction = osim::readDouble(doc_, *p, "dynamic_friction", 0);
                parameters.viscousFriction = osim::readDouble(doc_, *p, "viscous_friction", 0);
                force.parameters.push_back(std::move(parameters));
            }
        model_.huntCrossley.push_back(std::move(force));
    }

    void readPathForce(const Element& element, const std::string& type) {
        const PathForceTypeInfo& info = pathForceTypes().at(type);
        OsimPathForce force;
        force.type = type;
        force.kind = info.kind;
        force.name = requireName(element, forceNames_, "force");
        force.where = doc_.where(element);
        const Element& path = requireChild(element, "GeometryPath");
        const std::string pathName = osim::getName(path).empty() ? "geometrypath" : osim::getName(path);
        force.path = readGeometryPath(path, forceSetPath_ + "/" + force.name + "/" + pathName);
        force.limits = osim::readActuatorLimits(doc_, element, info.limits);
        if (force.kind == OsimPathForce::Kind::Muscle) {
            force.maxIsometricForce = osim::readDouble(doc_, element, "max_isometric_force", force.maxIsometricForce);
            force.optimalFiberLength = osim::readDouble(doc_, element, "optimal_fiber_length", force.optimalFiberLength);
            force.tendonSlackLength = osim::readDouble(doc_, element, "tendon_slack_length", force.tendonSlackLength);
            force.pennationAngleAtOptimal =
                osim::readDouble(doc_, element, "pennation_angle_at_optimal", force.pennationAngleAtOptimal);
            force.maxContractionVelocity =
                osim::readDouble(doc_, element, "max_contraction_velocity", force.maxContractionVelocity);
        }
        collectProperties(element, "", force);
        model_.pathForces.push_back(std::move(force));
    }

    // Every property of the force but its path: scalars as text, functions read, nested objects
    // flattened as "Object.property".
    void collectProperties(const Element& owner, const std::string& prefix, OsimPathForce& force) {
        auto prefixed = [&prefix](std::string_view name) {
            std::string key;
            key.reserve(prefix.size() + name.size() + 1);
            return key.append(prefix).append(name);
        };
        for (const Element* child = osim::firstChild(owner); child; child = osim::nextSibling(*child)) {
            const std::string_view type = osim::typeOf(*child);
            if (type == "GeometryPath" || type == "Appearance") continue;  // the path is read; display only
            const Element* only = osim::firstChild(*child);
            if (!only) {
                force.properties[prefixed(type)] = osim::textOf(*child);
            } else if (!osim::nextSibling(*only) && osim::isFunctionType(osim::typeOf(*only))) {
                force.curves[prefixed(type)] = osim::readFunction(doc_, *only);
            } else if (osim::isFunctionType(type)) {
                const std::string name = osim::getName(*child);
                force.curves[prefixed(name.empty() ? type : std::string_view(name))] = osim::readFunction(doc_, *child);
            } else {
                collectProperties(*child, prefixed(type).append(1, '.'), force);
            }
        }
    }

    OsimGeometryPath readGeometryPath(const Element& element, const std::string& ownerPath) {
        OsimGeometryPath path;
        path.where = doc_.where(element);
        for (const Element* point : osim::getSetObjects(requireChild(element, "PathPointSet"))) {
            const std::string type = osim::typeOf(*point);
            OsimPathPoint pathPoint;
            if (type == "PathPoint")
                pathPoint.type = OsimPathPoint::Type::Fixed;
            else if (type == "ConditionalPathPoint")
                pathPoint.type = OsimPathPoint::Type::Conditional;
            else if (type == "MovingPathPoint")
                pathPoint.type = OsimPathPoint::Type::Moving;
            else {
                addUnsupported(*point);
                continue;
            }
            pathPoint.name = osim::getName(*point);
            pathPoint.where = doc_.where(*point);
            const std::string pointPath = ownerPath + "/" + pathPoint.name;
            pathPoint.frame = followFrameSocket(requireChild(*point, "socket_parent_frame"), pointPath);
            pathPoint.location = osim::readVector3(doc_, *point, "location", pathPoint.location);
            if (pathPoint.type == OsimPathPoint::Type::Conditional) {
                pathPoint.coordinate = followCoordinateSocket(requireChild(*point, "socket_coordinate"), pointPath);
                const std::vector<double> range = osim::readFixedNumbers(doc_, *point, "range", 2, {0, 0});
                pathPoint.rangeMin = range[0];
                pathPoint.rangeMax = range[1];
            }
            if (pathPoint.type == OsimPathPoint::Type::Moving) {
                static const char* const functions[3] = {"x_location", "y_location", "z_location"};
                static const char* const sockets[3] = {"socket_x_coordinate", "socket_y_coordinate",
                                                       "socket_z_coordinate"};
                for (int i = 0; i < 3; ++i) {
                    pathPoint.locationFunctions[i].where = pathPoint.where;  // OpenSim's default: Constant 0
                    if (const Element* function = osim::findFunction(doc_, *point, functions[i]))
                        pathPoint.locationFunctions[i] = osim::readFunction(doc_, *function);
                    const Element* socket = osim::findChild(*point, sockets[i]);
                    if (socket && !osim::textOf(*socket).empty())
                        pathPoint.locationCoordinates[i] = followCoordinateSocket(*socket, pointPath);
                }
            }
            path.points.push_back(std::move(pathPoint));
        }
        if (path.points.size() < 2)
            doc_.fail(element, std::to_string(path.points.size()) + " path points; a path needs at least 2");
        if (const Element* wraps = osim::findChild(element, "PathWrapSet"))
            for (const Element* wrap : osim::getSetObjects(*wraps)) path.wraps.push_back(readPathWrap(*wrap));
        return path;
    }

    OsimPathWrap readPathWrap(const Element& element) {
        if (std::string(osim::typeOf(element)) != "PathWrap") doc_.fail(element, "expected a <PathWrap>");
        OsimPathWrap wrap;
        wrap.where = doc_.where(element);
        wrap.wrapObject = osim::readText(doc_, element, "wrap_object");
        if (wrap.wrapObject.empty()) doc_.fail(element, "missing <wrap_object>");
        // OpenSim looks for the object on ground, then on each body, and takes the first of that name.
        std::vector<const OsimBody*> owners{&model_.ground};
        for (const OsimBody& body : model_.bodies) owners.push_back(&body);
        for (const OsimBody* body : owners)
            for (const OsimWrapObject& object : body->wrapObjects)
                if (wrap.body.empty() && object.name == wrap.wrapObject) wrap.body = body->name;
        if (wrap.body.empty())
            doc_.fail(*osim::findChild(element, "wrap_object"), "'" + wrap.wrapObject + "' is no wrap object of the model");
        wrap.method = osim::readText(doc_, element, "method", wrap.method);
        if (wrap.method != "hybrid" && wrap.method != "midpoint" && wrap.method != "axial")
            doc_.fail(*osim::findChild(element, "method"), "'" + wrap.method + "', expected hybrid, midpoint or axial");
        const std::vector<double> range = osim::readFixedNumbers(doc_, element, "range", 2, {-1, -1});
        wrap.rangeBegin = static_cast<int>(range[0]);
        wrap.rangeEnd = static_cast<int>(range[1]);
        return wrap;
    }

    void readMarker(const Element& element) {
        OsimMarker marker;
        marker.name = osim::getName(element);
        marker.where = doc_.where(element);
        marker.frame = followFrameSocket(requireChild(element, "socket_parent_frame"), markerSetPath_ + "/" + marker.name);
        marker.location = osim::readVector3(doc_, element, "location", marker.location);
        marker.fixed = osim::readBool(doc_, element, "fixed", marker.fixed);
        model_.markers.push_back(std::move(marker));
    }
};

template <typename T>
const T* findByName(const std::vector<T>& items, const std::string& name) {
    const auto found = std::find_if(items.begin(), items.end(), [&](const T& item) { return item.name == name; });
    return found == items.end() ? nullptr : &*found;
}

}  // namespace

OsimModel readOsimModel(const std::string& path) { return OsimModelReader(path).read(); }

const OsimBody* findBody(const OsimModel& model, const std::string& name) { return findByName(model.bodies, name); }
const OsimCoordinate* findCoordinate(const OsimModel& model, const std::string& name) {
    return findByName(model.coordinates, name);
}
const OsimJoint* findJoint(const OsimModel& model, const std::string& name) { return findByName(model.joints, name); }
const OsimPathForce* findPathForce(const OsimModel& model, const std::string& name) {
    return findByName(model.pathForces, name);
}

}  // namespace sinew
