#include "sinew/core/model_builder.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>

#include "sinew/core/error.hpp"
#include "sinew/core/force_law_registry.hpp"
#include "sinew/core/spatial.hpp"

namespace sinew {
namespace {

bool isFinite(const Eigen::MatrixXd& m) { return m.allFinite(); }

void requireFinite(const std::string& where, const std::string& what, const Eigen::MatrixXd& m) {
    if (!isFinite(m)) throw ModelError(where, what + " must be finite (got NaN or inf)");
}

// Records `name` of a `kind` as defined at `where`; throws for an empty or already-used name.
void claimName(std::map<std::string, std::string>& defined, const std::string& kind, const std::string& name,
               const std::string& where) {
    if (name.empty()) throw ModelError(where, kind + " needs a non-empty name");
    auto [it, fresh] = defined.emplace(name, where);
    if (!fresh) throw ModelError(where, "duplicate " + kind + " name '" + name + "' (first defined at " + it->second + ")");
}

// An axis that is already unit is not renormalised: the model writer stores the axis, and any drift in its
// last bits would change the model on every write and read.
Eigen::Vector3d normalizeOnce(const Eigen::Vector3d& axis) {
    const bool isUnit = std::abs(axis.squaredNorm() - 1) <= 8 * std::numeric_limits<double>::epsilon();
    return isUnit ? axis : axis.normalized();
}

// Rotation taking F's z axis onto `axis` (pin joints rotate about F's z, as Simbody's Pin does); its z column
// is the unit axis bit for bit.
Eigen::Matrix3d rotationWithZAlong(const Eigen::Vector3d& axis) {
    const Eigen::Vector3d z = normalizeOnce(axis);
    Eigen::Matrix3d R = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), z).toRotationMatrix();
    R.col(2) = z;
    return R;
}

Eigen::Vector4d quaternionFromRotationVector(const Eigen::Vector3d& rotation) {
    const double angle = rotation.norm();
    const Eigen::Quaterniond q = angle > 0 ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, rotation / angle))
                                           : Eigen::Quaterniond::Identity();
    // q and -q are the same rotation; w >= 0 is the one a written model (rotation angle <= pi) reads back as.
    return (q.w() < 0 ? -1.0 : 1.0) * Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
}

void requireRotation(const std::string& where, const std::string& what, const Eigen::Matrix3d& R) {
    requireFinite(where, what, R);
    if (!(R * R.transpose()).isApprox(Eigen::Matrix3d::Identity(), 1e-9) || R.determinant() < 0)
        throw ModelError(where, what + " must be a rotation matrix (orthonormal, determinant +1)");
}

// OpenSim's CustomJoint threshold for axes that are not independent: |a x b| < 1e-5 for the unit axes.
bool areCollinear(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return a.normalized().cross(b.normalized()).norm() < 1e-5;
}

// A custom joint's axes and coordinates: six non-zero axes, rotation axes pairwise non-collinear as
// OpenSim's CustomJoint requires, every coordinate
// named by an axis declared, and every declared coordinate used by some axis.
void checkCustomJoint(const JointSpec& js, const std::string& label) {
    if (js.transformAxes.size() != 6)
        throw ModelError(js.where, label + ": a custom joint needs 6 transform axes (rotation1-3, translation1-3), got " +
                                       std::to_string(js.transformAxes.size()));
    static const char* const axisNames[] = {"rotation1", "rotation2", "rotation3", "translation1", "translation2",
                                            "translation3"};
    std::map<std::string, bool> used;  // declared coordinate -> named by an axis
    for (const CoordinateSpec& c : js.coordinates) {
        const std::string where = c.where.empty() ? js.where : c.where;
        if (c.name.empty()) throw ModelError(where, label + ": a coordinate needs a non-empty name");
        if (!used.emplace(c.name, false).second)
            throw ModelError(where, label + ": coordinate '" + c.name + "' is declared twice");
        if (!std::isfinite(c.defaultValue))
            throw ModelError(where, label + ": coordinate '" + c.name + "': default value must be finite");
        if (std::isnan(c.rangeMin) || std::isnan(c.rangeMax) || c.rangeMin > c.rangeMax)
            throw ModelError(where, label + ": coordinate '" + c.name + "': range must be [min, max] with min <= max");
    }
    for (int k = 0; k < 6; ++k) {
        const TransformAxisSpec& axis = js.transformAxes[static_cast<std::size_t>(k)];
        const std::string name = label + ": " + axisNames[k];
        if (!axis.axis.allFinite() || axis.axis.norm() < 1e-12)
            throw ModelError(js.where, name + " needs a finite, non-zero axis");
        if (!axis.coordinate.empty()) {
            auto it = used.find(axis.coordinate);
            if (it == used.end())
                throw ModelError(js.where, name + " names coordinate '" + axis.coordinate + "', which the joint does not "
                                                  "declare");
            it->second = true;
        }
    }
    for (const CoordinateSpec& c : js.coordinates)
        if (!used.at(c.name))
            throw ModelError(c.where.empty() ? js.where : c.where,
                             label + ": coordinate '" + c.name + "' drives none of the joint's transform axes");
    if (js.coordinates.empty())
        throw ModelError(js.where, label + ": a custom joint needs at least one coordinate (use a weld joint for none)");
    for (int a = 0; a < 3; ++a)
        for (int b = a + 1; b < 3; ++b)
            if (areCollinear(js.transformAxes[static_cast<std::size_t>(a)].axis,
                             js.transformAxes[static_cast<std::size_t>(b)].axis))
                throw ModelError(js.where, label + ": " + axisNames[a] + " and " + axisNames[b] +
                                               " are collinear; a custom joint's rotation axes must be independent");
}

// Translations along collinear axes add up (MuJoCo's slides along one axis, each coupled to the knee angle),
// so kinematics take them; but two free coordinates moving the body the same way make the joint's inertia
// singular, so a coupler must drive one of each such pair. Checked once the couplers are known.
void checkCollinearTranslations(const Model& model, const JointSpec& js, const Joint& joint, const std::string& label) {
    static const char* const axisNames[] = {"translation1", "translation2", "translation3"};
    auto isCoupled = [&](int coordinate) {
        for (const CoordinateCoupler& c : model.getCouplers())
            if (c.dependentQ == joint.qStart + coordinate) return true;
        return false;
    };
    for (int a = 3; a < 6; ++a)
        for (int b = a + 1; b < 6; ++b) {
            const TransformAxis& u = joint.transformAxes[static_cast<std::size_t>(a)];
            const TransformAxis& v = joint.transformAxes[static_cast<std::size_t>(b)];
            if (u.coordinate == kNoCoordinate || v.coordinate == kNoCoordinate || !areCollinear(u.axis, v.axis)) continue;
            if (u.coordinate != v.coordinate && !isCoupled(u.coordinate) && !isCoupled(v.coordinate))
                throw ModelError(js.where, label + ": " + axisNames[a - 3] + " and " + axisNames[b - 3] +
                                               " are collinear and neither coordinate is driven by a coupler; a custom "
                                               "joint's free translation axes must be independent");
        }
}

// OpenSim's rule (CustomJoint::constructCoordinates): a coordinate that drives some axis through a linear
// function of slope +-1 is rotational or translational (the last such axis decides); otherwise coupled.
MotionType calcMotionType(const std::vector<TransformAxis>& axes, int coordinate) {
    bool pure = false;
    MotionType type = MotionType::Coupled;
    for (std::size_t k = 0; k < axes.size(); ++k) {
        if (axes[k].coordinate != coordinate) continue;
        const Function& f = axes[k].function;
        if (f.getType() == Function::Type::Linear && f.getScale() == 1 && std::abs(f.getCoefficients()[0]) == 1) {
            type = k < 3 ? MotionType::Rotational : MotionType::Translational;
            pure = true;
        } else if (!pure) {
            type = MotionType::Coupled;
        }
    }
    return type;
}

WrapObject buildWrapObject(const WrapObjectSpec& os, int link) {
    const std::string label = "wrap object '" + os.name + "'";
    WrapObject object;
    object.name = os.name;
    object.shape = os.shape;
    object.link = link;
    requireFinite(os.where, label + ": rotation", os.xyzBodyRotation);
    requireFinite(os.where, label + ": translation", os.translation);
    object.xyzBodyRotation = os.xyzBodyRotation;
    object.R_BW = calcRotationFromBodyFixedXYZ(os.xyzBodyRotation);
    object.p_BW = os.translation;
    switch (os.shape) {
        case WrapShape::Sphere:
        case WrapShape::Cylinder:
            if (!(std::isfinite(os.radius) && os.radius > 0)) throw ModelError(os.where, label + ": radius must be > 0");
            object.radius = os.radius;
            if (os.shape == WrapShape::Cylinder) {
                if (!(std::isfinite(os.length) && os.length > 0)) throw ModelError(os.where, label + ": length must be > 0");
                object.length = os.length;
            }
            break;
        case WrapShape::Ellipsoid:
            if (!(os.radii.allFinite() && os.radii.minCoeff() > 0))
                throw ModelError(os.where, label + ": the three radii must be > 0");
            object.radii = os.radii;
            break;
    }
    // OpenSim's spellings: "all", or an axis with an optional sign ("x" means "+x"), either case.
    std::string q = os.quadrant;
    for (char& c : q) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (q != "all") {
        const bool negative = !q.empty() && q[0] == '-';
        const std::string axis = !q.empty() && (q[0] == '-' || q[0] == '+') ? q.substr(1) : q;
        if (axis != "x" && axis != "y" && axis != "z")
            throw ModelError(os.where, label + ": unknown quadrant '" + os.quadrant + "' (expected all, x, +x, -x, y, +y, "
                                               "-y, z, +z or -z)");
        object.quadrantAxis = axis[0] - 'x';
        object.quadrantSign = negative ? -1 : 1;
        if (os.shape == WrapShape::Cylinder && object.quadrantAxis == 2)
            throw ModelError(os.where, label + ": a cylinder's quadrant must be across its axis (x or y), not along z");
    }
    return object;
}

// A wire's optional strength or cross-section: finite and > 0 when given.
void checkWireMagnitude(const std::optional<double>& value, const std::string& where, const std::string& label,
                        const char* field, const char* unit) {
    if (value && !(std::isfinite(*value) && *value > 0))
        throw ModelError(where, label + ": " + field + " must be a finite number > 0 (" + unit + "), got " +
                                    std::to_string(*value));
}

// One wrap of wire `label` (numPoints points) over `object` (index objectIndex): the range, and MuJoCo's
// restrictions: a sphere or cylinder, the one segment between two adjacent points, a side site only for it,
// on link sideSiteLink (resolved from wr.sideSiteLink).
WireWrap buildWireWrap(const WireWrapSpec& wr, const std::string& where, const std::string& label, int numPoints,
                       const WrapObject& object, int objectIndex, int sideSiteLink) {
    const int first = wr.firstPoint.value_or(0), last = wr.lastPoint.value_or(numPoints - 1);
    if (first < 0 || last >= numPoints || first >= last)
        throw ModelError(where, label + ": wrap range [" + std::to_string(first) + ", " + std::to_string(last) +
                                    "] must name two of its points 0.." + std::to_string(numPoints - 1) +
                                    ", first before last");
    WireWrap wrap{objectIndex, first, last, wr.method};
    const std::string wrapLabel = label + ": wrap over '" + wr.object + "'";
    if (!wr.sideSite && !wr.sideSiteLink.empty())
        throw ModelError(where, wrapLabel + ": side site link '" + wr.sideSiteLink + "' given without a side site");
    if (wr.method != WrapMethod::MuJoCo) {
        if (wr.sideSite) throw ModelError(where, wrapLabel + ": a side site needs the mujoco method");
        return wrap;
    }
    if (object.shape == WrapShape::Ellipsoid)
        throw ModelError(where, wrapLabel + ": the mujoco method wraps over spheres and cylinders only, not an ellipsoid");
    if (last != first + 1)
        throw ModelError(where, wrapLabel + ": the mujoco method wraps the one segment between two adjacent points "
                                            "(range [k, k + 1]), got [" + std::to_string(first) + ", " +
                                            std::to_string(last) + "]");
    if (wr.sideSite) {
        requireFinite(where, wrapLabel + ": side site", *wr.sideSite);
        wrap.hasSideSite = true;
        wrap.sideSiteLink = sideSiteLink;
        wrap.sideSite_B = *wr.sideSite;
    }
    return wrap;
}

// A massless link is accepted wherever it is, as OpenSim and Simbody accept one (a wrist's intermediate
// body between two pins); forward dynamics names the joint where it leaves the mass matrix singular.
void checkMassProperties(const LinkSpec& link) {
    if (!std::isfinite(link.mass)) throw ModelError(link.where, "link '" + link.name + "': mass must be finite");
    requireFinite(link.where, "link '" + link.name + "': com", link.com_B);
    requireFinite(link.where, "link '" + link.name + "': inertia", link.inertia_Bcom);
    if (link.mass < 0) throw ModelError(link.where, "link '" + link.name + "': mass must be >= 0");
    const Eigen::Matrix3d& I = link.inertia_Bcom;
    if (link.mass == 0) {
        if (!I.isZero(0))
            throw ModelError(link.where, "link '" + link.name + "': a massless link must have zero inertia");
        return;
    }
    // The eigensolver reads one triangle only, so a non-symmetric inertia would otherwise pass unchecked.
    if (!I.isApprox(I.transpose(), 1e-12))
        throw ModelError(link.where, "link '" + link.name + "': inertia is not symmetric");
    // A point mass (mass without inertia) is a body to OpenSim and Simbody; forward dynamics refuses it only
    // where no inertia then resists a joint's motion (calcForwardDynamics names that joint).
    if (I.isZero(0)) return;
    const Eigen::Vector3d eig = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I, Eigen::EigenvaluesOnly).eigenvalues();
    if (!(eig.minCoeff() > 0))
        throw ModelError(link.where, "link '" + link.name + "': inertia is not positive definite (smallest principal "
                                     "moment " + std::to_string(eig.minCoeff()) + " kg m^2)");
    // A rigid body's principal moments obey the triangle inequality; Simbody rejects inertias that do not.
    const double slack = 1e-12 * eig.sum();
    if (eig[0] + eig[1] < eig[2] - slack)
        throw ModelError(link.where, "link '" + link.name + "': inertia violates the triangle inequality of principal "
                                     "moments (" + std::to_string(eig[0]) + " + " + std::to_string(eig[1]) + " < " +
                                     std::to_string(eig[2]) + "), so no rigid body has it");
}

// A custom joint's transform axes (unit axes, coordinate indices, functions with OpenSim's defaults) and
// its coordinates, in order of first appearance in the axes as OpenSim orders them (CustomJoint::
// constructCoordinates), so q matches OpenSim's and Simbody's FunctionBased mobilizer's.
template <typename AddCoordinate>
void addCustomCoordinates(const JointSpec& js, Joint& joint, AddCoordinate&& addCoordinate) {
    std::vector<std::string> order;
    for (const TransformAxisSpec& spec : js.transformAxes) {
        TransformAxis axis;
        axis.axis = normalizeOnce(spec.axis);  // idempotent, so written models read back bit for bit
        if (!spec.coordinate.empty()) {
            auto it = std::find(order.begin(), order.end(), spec.coordinate);
            axis.coordinate = static_cast<int>(it - order.begin());
            if (it == order.end()) order.push_back(spec.coordinate);
        }
        axis.function = spec.function ? *spec.function
                                      : spec.coordinate.empty() ? Function::constant(0) : Function::linear(1, 0);
        joint.transformAxes.push_back(axis);
    }
    for (std::size_t k = 0; k < order.size(); ++k) {
        const CoordinateSpec& spec = *std::find_if(js.coordinates.begin(), js.coordinates.end(),
                                                   [&](const CoordinateSpec& c) { return c.name == order[k]; });
        Coordinate c;
        c.name = spec.name;
        c.motionType = calcMotionType(joint.transformAxes, static_cast<int>(k));
        c.defaultValue = spec.defaultValue;
        c.rangeMin = spec.rangeMin;
        c.rangeMax = spec.rangeMax;
        c.clamped = spec.clamped;
        c.locked = spec.locked;
        addCoordinate(c, spec.where.empty() ? js.where : spec.where);
    }
}

}  // namespace

void ModelBuilder::setGravity(const Eigen::Vector3d& gravity, std::string where) {
    gravity_ = gravity;
    gravityWhere_ = std::move(where);
}

// build()'s state between its stages: the model so far and the name tables later stages resolve against.
// Each stage checks or compiles one kind of element, in the order they refer to each other (as MuJoCo's
// mjCModel compiles its bodies, joints, tendons, ... in turn).
struct ModelBuilder::Compilation {
    explicit Compilation(const ModelBuilder& builder) : specs(builder) {}

    void claimLinkNames();
    void checkJoints();
    void checkLinks();
    void orderJoints();
    void buildLinkTree();
    void buildVirtualLinks();
    void buildLoops();
    void buildWrapObjects();
    void buildCouplers();
    void buildWires();

    void checkJoint(std::size_t j);
    void addCoordinate(Coordinate coordinate, const std::string& where);
    void addQuaternionCoordinates(const std::string& where, const std::string& name, const Eigen::Vector4d& quat,
                                  const Eigen::Vector3d* p);
    void appendJoint(Joint joint, Link link);
    void buildJoint(const JointSpec& js);
    void checkLoop(const LoopSpec& ls, const Loop& loop, const std::string& label) const;
    int resolveLink(const std::string& where, const std::string& owner, const std::string& name) const;
    std::pair<int, int> resolveCoordinate(const std::string& where, const std::string& owner,
                                          const std::string& name) const;
    void buildWire(const WireSpec& ws);
    void addWirePoint(const WireSpec& ws, std::size_t k, const std::string& label, Wire& wire);
    void addWireWrap(const WireWrapSpec& wr, const std::string& where, const std::string& label, Wire& wire) const;
    void findSupportLinks(Wire& wire);

    const ModelBuilder& specs;
    Model model;
    std::map<std::string, std::string> linkWhere;       // links' and virtual links' names (one namespace) -> where
    std::map<std::string, std::size_t> linkSpecIndex;   // link name -> index in specs.links_
    std::map<std::string, std::size_t> jointOfChild;    // child link name -> index in specs.joints_
    std::map<std::string, std::string> jointWhere;      // joint name -> where
    std::vector<std::size_t> order;                     // specs.joints_ indices, parents first
    std::map<std::string, int> linkIndex;               // link name -> the model's link index
    std::map<std::string, std::string> coordinateWhere;
    int nq = 0, nu = 0;                                 // so far
    std::map<std::string, std::string> loopWhere, wrapWhere, couplerWhere, wireWhere;
    std::map<std::string, int> wrapIndex;               // wrap object name -> index in the model's
};

Model ModelBuilder::build() const {
    Compilation c(*this);
    c.model.name_ = name_;
    requireFinite(gravityWhere_, "gravity", gravity_);
    c.model.gravity_ = gravity_;
    c.claimLinkNames();
    c.checkJoints();
    c.checkLinks();
    c.orderJoints();
    c.buildLinkTree();
    c.buildVirtualLinks();
    c.buildLoops();
    c.buildWrapObjects();
    c.buildCouplers();
    c.buildWires();
    buildContacts(c.model);
    buildForceElements(c.model);
    return std::move(c.model);
}

// Names: links and virtual links share one namespace; "ground" is reserved.
void ModelBuilder::Compilation::claimLinkNames() {
    auto claimLinkName = [&](const std::string& name, const std::string& where, const char* kind) {
        if (name == "ground") throw ModelError(where, std::string(kind) + " cannot be called 'ground' (reserved)");
        claimName(linkWhere, "link", name, where);
    };
    for (std::size_t i = 0; i < specs.links_.size(); ++i) {
        claimLinkName(specs.links_[i].name, specs.links_[i].where, "link");
        linkSpecIndex[specs.links_[i].name] = i;
    }
    for (const VirtualLinkSpec& v : specs.virtualLinks_) {
        claimLinkName(v.name, v.where, "virtual link");
        requireFinite(v.where, "virtual link '" + v.name + "': initial position", v.initialPosition);
    }
}

// Joints: each real link is the child of exactly one joint. A virtual link's 6-DOF joint takes the
// virtual link's name.
void ModelBuilder::Compilation::checkJoints() {
    for (std::size_t j = 0; j < specs.joints_.size(); ++j) checkJoint(j);
    for (const VirtualLinkSpec& v : specs.virtualLinks_)
        if (jointWhere.count(v.name))
            throw ModelError(v.where, "virtual link '" + v.name + "' has the name of joint '" + v.name + "' (" +
                                          jointWhere.at(v.name) + "); its own joint takes that name");
}

void ModelBuilder::Compilation::checkJoint(std::size_t j) {
    const JointSpec& js = specs.joints_[j];
    claimName(jointWhere, "joint", js.name, js.where);
    const std::string label = "joint '" + js.name + "'";
    if (!linkSpecIndex.count(js.child))
        throw ModelError(js.where, label + ": unknown child link '" + js.child + "'" +
                                       (linkWhere.count(js.child) ? " (virtual links have no joint)" : ""));
    if (js.parent != "ground" && !linkSpecIndex.count(js.parent))
        throw ModelError(js.where, label + ": unknown parent link '" + js.parent + "'" +
                                       (linkWhere.count(js.parent) ? " (a virtual link cannot be a parent)" : ""));
    if (js.parent == js.child) throw ModelError(js.where, label + ": a link cannot be its own parent");
    auto [prev, first] = jointOfChild.emplace(js.child, j);
    if (!first)
        throw ModelError(js.where, label + ": link '" + js.child + "' already has joint '" +
                                       specs.joints_[prev->second].name + "' to its parent; close loops with a "
                                       "'loops' entry instead");
    requireFinite(js.where, label + ": parent_point", js.p_PF);
    requireFinite(js.where, label + ": child_point", js.p_BM);
    if (js.type == JointType::Pin) {
        if (!js.axis || !js.axis->allFinite() || js.axis->norm() < 1e-12)
            throw ModelError(js.where, label + ": a pin joint needs a finite, non-zero axis");
    } else if (js.axis) {
        throw ModelError(js.where, label + ": only pin joints take an axis");
    }
    if (js.type == JointType::Custom) {
        checkCustomJoint(js, label);
    } else if (!js.transformAxes.empty() || !js.coordinates.empty()) {
        throw ModelError(js.where, label + ": only custom joints take transform axes and coordinates");
    }
    if ((js.R_PF || js.R_BM) && js.type != JointType::Custom && js.type != JointType::Weld)
        throw ModelError(js.where, label + ": only custom and weld joints take frame orientations");
    if (js.R_PF) requireRotation(js.where, label + ": parent frame orientation", *js.R_PF);
    if (js.R_BM) requireRotation(js.where, label + ": child frame orientation", *js.R_BM);
    if (js.initialRotation && js.type != JointType::Ball && js.type != JointType::Free)
        throw ModelError(js.where, label + ": initial_rotation applies to ball and free joints only");
    if (js.initialAngle && js.type != JointType::Pin)
        throw ModelError(js.where, label + ": initial_angle applies to pin joints only");
    if (js.initialPosition && js.type != JointType::Free)
        throw ModelError(js.where, label + ": initial_position applies to free joints only");
    if (js.initialRotation) requireFinite(js.where, label + ": initial_rotation", *js.initialRotation);
    if (js.initialPosition) requireFinite(js.where, label + ": initial_position", *js.initialPosition);
    if (js.initialAngle && !std::isfinite(*js.initialAngle))
        throw ModelError(js.where, label + ": initial_angle must be finite");
}

// Links: each has a joint, and mass properties some rigid body has.
void ModelBuilder::Compilation::checkLinks() {
    for (const LinkSpec& ls : specs.links_) {
        auto it = jointOfChild.find(ls.name);
        if (it == jointOfChild.end())
            throw ModelError(ls.where, "link '" + ls.name + "' has no joint (every link needs one joint to its "
                                       "parent or to ground)");
        checkMassProperties(ls);
    }
}

// Parents-first order: depth-first from ground, siblings in file order, so subtrees stay contiguous.
void ModelBuilder::Compilation::orderJoints() {
    const std::vector<JointSpec>& joints = specs.joints_;
    std::map<std::string, std::vector<std::size_t>> childJoints;  // parent name -> joints
    for (std::size_t j = 0; j < joints.size(); ++j) childJoints[joints[j].parent].push_back(j);
    std::vector<std::size_t> stack;
    auto pushChildren = [&](const std::string& parent) {
        const auto& kids = childJoints[parent];
        stack.insert(stack.end(), kids.rbegin(), kids.rend());
    };
    pushChildren("ground");
    while (!stack.empty()) {
        const std::size_t j = stack.back();
        stack.pop_back();
        order.push_back(j);
        pushChildren(joints[j].child);
    }
    if (order.size() != joints.size()) {
        for (const JointSpec& js : joints)
            if (std::find_if(order.begin(), order.end(), [&](std::size_t o) { return joints[o].name == js.name; }) ==
                order.end())
                throw ModelError(js.where, "joint '" + js.name + "' is part of a cycle of joints that never reaches "
                                           "ground; close loops with a 'loops' entry instead");
    }
}

// Appends the next coordinate (q entry) of the joint about to be appended.
void ModelBuilder::Compilation::addCoordinate(Coordinate coordinate, const std::string& where) {
    claimName(coordinateWhere, "coordinate", coordinate.name, where);
    coordinate.joint = static_cast<int>(model.joints_.size());
    model.coordinates_.push_back(std::move(coordinate));
}

// A free or ball joint's quaternion and (free) position entries, named after the joint.
void ModelBuilder::Compilation::addQuaternionCoordinates(const std::string& where, const std::string& name,
                                                         const Eigen::Vector4d& quat, const Eigen::Vector3d* p) {
    static const char* const quaternionSuffixes[] = {"_qw", "_qx", "_qy", "_qz"};
    static const char* const positionSuffixes[] = {"_x", "_y", "_z"};
    for (int k = 0; k < 4; ++k) {
        Coordinate c;
        c.name = name + quaternionSuffixes[k];
        c.defaultValue = quat[k];
        addCoordinate(c, where);
    }
    for (int k = 0; p && k < 3; ++k) {
        Coordinate c;
        c.name = name + positionSuffixes[k];
        c.motionType = MotionType::Translational;
        c.defaultValue = (*p)[k];
        addCoordinate(c, where);
    }
}

// Appends a joint whose coordinates were just added, with its child link.
void ModelBuilder::Compilation::appendJoint(Joint joint, Link link) {
    const bool custom = joint.type == JointType::Custom;
    joint.nq = custom ? static_cast<int>(model.coordinates_.size()) - nq : getNumQ(joint.type);
    joint.nu = custom ? joint.nq : getNumU(joint.type);
    joint.qStart = nq;
    joint.uStart = nu;
    nq += joint.nq;
    nu += joint.nu;
    linkIndex[link.name] = static_cast<int>(model.links_.size());
    model.links_.push_back(std::move(link));
    model.joints_.push_back(std::move(joint));
}

// The tree's links and joints, parents first, each joint with its coordinates.
void ModelBuilder::Compilation::buildLinkTree() {
    for (std::size_t j : order) buildJoint(specs.joints_[j]);
}

void ModelBuilder::Compilation::buildJoint(const JointSpec& js) {
    const LinkSpec& ls = specs.links_[linkSpecIndex.at(js.child)];
    Joint joint;
    joint.name = js.name;
    joint.type = js.type;
    joint.parent = js.parent == "ground" ? kGround : linkIndex.at(js.parent);
    joint.p_PF = js.p_PF;
    joint.p_BM = js.p_BM;
    if (js.type == JointType::Pin) joint.R_PF = joint.R_BM = rotationWithZAlong(*js.axis);
    if (js.R_PF) joint.R_PF = *js.R_PF;
    if (js.R_BM) joint.R_BM = *js.R_BM;
    const Eigen::Vector4d quat = quaternionFromRotationVector(js.initialRotation.value_or(Eigen::Vector3d::Zero()));
    switch (js.type) {
        case JointType::Free: {
            const Eigen::Vector3d p = js.initialPosition.value_or(Eigen::Vector3d::Zero());
            addQuaternionCoordinates(js.where, js.name, quat, &p);
            break;
        }
        case JointType::Ball: addQuaternionCoordinates(js.where, js.name, quat, nullptr); break;
        case JointType::Pin: {
            Coordinate c;
            c.name = js.name;
            c.defaultValue = js.initialAngle.value_or(0.0);
            addCoordinate(c, js.where);
            break;
        }
        case JointType::Weld: break;
        case JointType::Custom:
            addCustomCoordinates(js, joint, [&](Coordinate c, const std::string& where) { addCoordinate(c, where); });
            break;
    }
    // Exactly symmetric (an inertia computed as R D R^T is not), as the model file stores one triangle.
    const Eigen::Matrix3d inertia_Bcom = 0.5 * (ls.inertia_Bcom + ls.inertia_Bcom.transpose());
    appendJoint(joint, Link{ls.name, ls.mass, ls.com_B, inertia_Bcom, false});
}

// Virtual links: massless, on free joints of their own name after the tree; then the model's sizes.
void ModelBuilder::Compilation::buildVirtualLinks() {
    for (const VirtualLinkSpec& v : specs.virtualLinks_) {
        Joint joint;
        joint.name = v.name;
        joint.type = JointType::Free;
        addQuaternionCoordinates(v.where, v.name, Eigen::Vector4d(1, 0, 0, 0), &v.initialPosition);
        Link link;
        link.name = v.name;
        link.isVirtual = true;
        appendJoint(joint, link);
    }
    model.nq_ = nq;
    model.nu_ = nu;
    model.defaultQ_.resize(nq);
    for (int i = 0; i < nq; ++i) model.defaultQ_[i] = model.coordinates_[static_cast<std::size_t>(i)].defaultValue;
}

int ModelBuilder::Compilation::resolveLink(const std::string& where, const std::string& owner,
                                           const std::string& name) const {
    if (name == "ground")
        throw ModelError(where, owner + ": 'ground' is not a link; attach to a link (fix a link to ground with a "
                                        "weld joint, or simulate with --hang-by)");
    auto it = linkIndex.find(name);
    if (it == linkIndex.end()) throw ModelError(where, owner + ": unknown link '" + name + "'");
    return it->second;
}

// A coordinate a wire point or coupler depends on: its index in q and in u, for one with qdot = u.
std::pair<int, int> ModelBuilder::Compilation::resolveCoordinate(const std::string& where, const std::string& owner,
                                                                 const std::string& name) const {
    const int q = model.findCoordinateIndex(name);
    if (q == Model::kNotFound) throw ModelError(where, owner + ": unknown coordinate '" + name + "'");
    const Joint& joint = model.joints_[static_cast<std::size_t>(model.coordinates_[static_cast<std::size_t>(q)].joint)];
    if (joint.nq != joint.nu)
        throw ModelError(where, owner + ": coordinate '" + name + "' is part of " + toString(joint.type) + " joint '" +
                                    joint.name + "'s quaternion; only pin and custom coordinates (qdot = u) can be named here");
    return std::pair<int, int>(q, joint.uStart + (q - joint.qStart));
}

// Loops: two distinct links, closing neither another loop's joint nor a tree joint.
void ModelBuilder::Compilation::buildLoops() {
    for (const LoopSpec& ls : specs.loops_) {
        claimName(loopWhere, "loop", ls.name, ls.where);
        const std::string label = "loop '" + ls.name + "'";
        const Loop loop{ls.name, resolveLink(ls.where, label, ls.linkA), ls.p_A, resolveLink(ls.where, label, ls.linkB),
                        ls.p_B};
        requireFinite(ls.where, label + ": point_a", ls.p_A);
        requireFinite(ls.where, label + ": point_b", ls.p_B);
        if (loop.linkA == loop.linkB) throw ModelError(ls.where, label + ": both ends are on link '" + ls.linkA + "'");
        checkLoop(ls, loop, label);
        model.loops_.push_back(loop);
    }
}

void ModelBuilder::Compilation::checkLoop(const LoopSpec& ls, const Loop& loop, const std::string& label) const {
    for (const Loop& other : model.loops_) {
        const bool same = (other.linkA == loop.linkA && other.linkB == loop.linkB && other.p_A.isApprox(loop.p_A) &&
                           other.p_B.isApprox(loop.p_B)) ||
                          (other.linkA == loop.linkB && other.linkB == loop.linkA && other.p_A.isApprox(loop.p_B) &&
                           other.p_B.isApprox(loop.p_A));
        if (same)
            throw ModelError(ls.where, label + " closes the same joint as loop '" + other.name + "' (" +
                                           loopWhere.at(other.name) + ")");
    }
    for (int end = 0; end < 2; ++end) {
        const int child = end == 0 ? loop.linkA : loop.linkB;
        const int parent = end == 0 ? loop.linkB : loop.linkA;
        const Joint& joint = model.joints_[static_cast<std::size_t>(child)];
        const Eigen::Vector3d& p_child = end == 0 ? loop.p_A : loop.p_B;
        const Eigen::Vector3d& p_parent = end == 0 ? loop.p_B : loop.p_A;
        if (joint.parent == parent && joint.type != JointType::Free && (p_child - joint.p_BM).norm() < 1e-12 &&
            (p_parent - joint.p_PF).norm() < 1e-12)
            throw ModelError(ls.where, label + " closes over tree joint '" + joint.name +
                                           "', which already joins these two points");
    }
}

// Wrap objects, before the wires that name them.
void ModelBuilder::Compilation::buildWrapObjects() {
    for (const WrapObjectSpec& os : specs.wrapObjects_) {
        claimName(wrapWhere, "wrap object", os.name, os.where);
        wrapIndex[os.name] = static_cast<int>(model.wrapObjects_.size());
        model.wrapObjects_.push_back(buildWrapObject(os, resolveLink(os.where, "wrap object '" + os.name + "'", os.link)));
    }
}

// Couplers: distinct coordinates, each dependent on one coupler at most, no dependent one driving
// another coupler (moment arms and applyCoordinateCouplers take one step of the chain rule). Then the
// custom joints' collinear translations, which a coupler may make legal.
void ModelBuilder::Compilation::buildCouplers() {
    for (const CoordinateCouplerSpec& cs : specs.couplers_) {
        claimName(couplerWhere, "coupler", cs.name, cs.where);
        const std::string label = "coupler '" + cs.name + "'";
        if (!std::isfinite(cs.scaleFactor)) throw ModelError(cs.where, label + ": scale factor must be finite");
        const auto [dq, du] = resolveCoordinate(cs.where, label + " dependent", cs.dependentCoordinate);
        const auto [iq, iu] = resolveCoordinate(cs.where, label + " independent", cs.independentCoordinate);
        if (dq == iq)
            throw ModelError(cs.where, label + ": coordinate '" + cs.dependentCoordinate + "' cannot depend on itself");
        for (const CoordinateCoupler& other : model.couplers_) {
            const std::string clash = "coupler '" + other.name + "' (" + couplerWhere.at(other.name) + ")";
            if (other.dependentQ == dq)
                throw ModelError(cs.where, label + ": coordinate '" + cs.dependentCoordinate +
                                               "' is already the dependent coordinate of " + clash);
            if (other.dependentQ == iq || other.independentQ == dq)
                throw ModelError(cs.where, label + " and " + clash + " form a chain (a dependent coordinate driving "
                                               "another coupler); sinew's couplers take independent coordinates only");
        }
        model.couplers_.push_back({cs.name, dq, du, iq, iu, cs.function, cs.scaleFactor});
    }
    for (std::size_t k = 0; k < order.size(); ++k)
        if (model.joints_[k].type == JointType::Custom)
            checkCollinearTranslations(model, specs.joints_[order[k]], model.joints_[k],
                                       "joint '" + model.joints_[k].name + "'");
}

// Wires: points, wraps, force law and the links they act on.
void ModelBuilder::Compilation::buildWires() {
    for (const WireSpec& ws : specs.wires_) buildWire(ws);
}

void ModelBuilder::Compilation::buildWire(const WireSpec& ws) {
    claimName(wireWhere, "wire", ws.name, ws.where);
    const std::string label = "wire '" + ws.name + "'";
    if (ws.points.size() < 2)
        throw ModelError(ws.where, label + " has " + std::to_string(ws.points.size()) +
                                       " point(s); a wire needs at least 2 (origin and insertion)");
    Wire wire;
    wire.name = ws.name;
    wire.kind = ws.kind;
    wire.firstPoint = static_cast<int>(model.wirePoints_.size());
    wire.numPoints = static_cast<int>(ws.points.size());
    for (std::size_t k = 0; k < ws.points.size(); ++k) addWirePoint(ws, k, label, wire);
    for (const WireWrapSpec& wr : ws.wraps) addWireWrap(wr, wr.where.empty() ? ws.where : wr.where, label, wire);
    checkWireMagnitude(ws.strength, ws.where, label, "strength", "N");
    checkWireMagnitude(ws.crossSection, ws.where, label, "cross-section", "m^2");
    wire.strength = ws.strength;
    wire.crossSection = ws.crossSection;
    wire.lawSpec = ws.law;
    try {
        wire.law = ForceLawRegistry::global().create(ws.law.type, ws.law.parameters);
    } catch (const ModelError&) {
        throw;
    } catch (const Error& e) {
        throw ModelError(ws.lawWhere.empty() ? ws.where : ws.lawWhere, label + ": " + e.what());
    }
    findSupportLinks(wire);
    model.wires_.push_back(std::move(wire));
}

// Point k of wire ws, with its condition and motions, onto the model's wire points.
void ModelBuilder::Compilation::addWirePoint(const WireSpec& ws, std::size_t k, const std::string& label, Wire& wire) {
    const WirePointSpec& ps = ws.points[k];
    const std::string& where = ps.where.empty() ? ws.where : ps.where;
    const std::string pointLabel = label + ": point " + std::to_string(k);
    WirePoint point{resolveLink(where, label, ps.link), ps.p_B};
    const int pointIndex = static_cast<int>(k);
    if (ps.condition) {
        const WirePointConditionSpec& c = *ps.condition;
        if (!std::isfinite(c.min) || !std::isfinite(c.max) || c.min > c.max)
            throw ModelError(where, pointLabel + ": the active range of coordinate '" + c.coordinate +
                                        "' must be finite with min <= max");
        wire.conditions.push_back({pointIndex, resolveCoordinate(where, pointLabel, c.coordinate).first, c.min, c.max});
    }
    std::array<bool, 3> moving{false, false, false};
    for (const WirePointMotionSpec& m : ps.motions) {
        if (m.axis < 0 || m.axis > 2 || moving[static_cast<std::size_t>(m.axis)])
            throw ModelError(where, pointLabel + ": each of x, y, z can move with one coordinate at most");
        moving[static_cast<std::size_t>(m.axis)] = true;
        point.p_B[m.axis] = 0;  // not read: the function gives this component
        const auto [q, u] = resolveCoordinate(where, pointLabel, m.coordinate);
        wire.motions.push_back({pointIndex, m.axis, q, u, m.function});
    }
    requireFinite(where, pointLabel, point.p_B);
    // Only two fixed points can coincide for good; conditional and moving ones part again.
    const bool fixedPair = k > 0 && !ps.condition && ps.motions.empty() && !ws.points[k - 1].condition &&
                           ws.points[k - 1].motions.empty();
    if (fixedPair) {
        const WirePoint& prev = model.wirePoints_.back();
        if (prev.link == point.link && (prev.p_B - point.p_B).norm() < 1e-12)
            throw ModelError(where, label + ": points " + std::to_string(k - 1) + " and " + std::to_string(k) +
                                        " coincide on link '" + ps.link + "' (zero-length segment)");
    }
    model.wirePoints_.push_back(point);
}

void ModelBuilder::Compilation::addWireWrap(const WireWrapSpec& wr, const std::string& where, const std::string& label,
                                            Wire& wire) const {
    auto it = wrapIndex.find(wr.object);
    if (it == wrapIndex.end()) throw ModelError(where, label + ": unknown wrap object '" + wr.object + "'");
    const WrapObject& object = model.wrapObjects_[static_cast<std::size_t>(it->second)];
    const int sideSiteLink = wr.sideSiteLink.empty()
                                 ? object.link
                                 : resolveLink(where, label + ": wrap over '" + wr.object + "': side site", wr.sideSiteLink);
    const WireWrap wrap = buildWireWrap(wr, where, label, wire.numPoints, object, it->second, sideSiteLink);
    // MuJoCo may wrap one geom in several segments of a tendon, but each segment over one geom only.
    for (const WireWrap& other : wire.wraps) {
        const bool mujoco = wrap.method == WrapMethod::MuJoCo || other.method == WrapMethod::MuJoCo;
        const bool overlapping = other.firstPoint < wrap.lastPoint && wrap.firstPoint < other.lastPoint;
        if (!mujoco && other.object == it->second)
            throw ModelError(where, label + ": wraps over '" + wr.object + "' twice");
        if (mujoco && overlapping)
            throw ModelError(where, label + ": a mujoco wrap's segment [" + std::to_string(wrap.firstPoint) + ", " +
                                        std::to_string(wrap.lastPoint) + "] is wrapped by one object only");
    }
    wire.wraps.push_back(wrap);
}

// The links between the wire's anchors (points, wrap objects, side sites) and the root, tip to base (a parent's
// index is below its children's), and how many lie below the anchors' lowest common link: going tip to base,
// that is the first link whose subtree holds every anchor.
void ModelBuilder::Compilation::findSupportLinks(Wire& wire) {
    std::vector<int> anchors;
    for (int k = 0; k < wire.numPoints; ++k) anchors.push_back(model.wirePoints_[static_cast<std::size_t>(wire.firstPoint + k)].link);
    for (const WireWrap& wrap : wire.wraps) {
        anchors.push_back(model.wrapObjects_[static_cast<std::size_t>(wrap.object)].link);
        if (wrap.hasSideSite) anchors.push_back(wrap.sideSiteLink);
    }
    std::vector<int> support;
    std::vector<int> anchorsBelow(model.joints_.size(), -1);  // per link: anchors in its subtree; -1 off the support
    for (const int anchor : anchors)
        for (int l = anchor; l != kGround && anchorsBelow[static_cast<std::size_t>(l)] < 0;
             l = model.joints_[static_cast<std::size_t>(l)].parent) {
            anchorsBelow[static_cast<std::size_t>(l)] = 0;
            support.push_back(l);
        }
    std::sort(support.begin(), support.end(), std::greater<int>());
    for (const int anchor : anchors)  // an anchor on ground is below no link: then every support link spans
        if (anchor != kGround) ++anchorsBelow[static_cast<std::size_t>(anchor)];
    wire.numSpanLinks = static_cast<int>(support.size());
    for (std::size_t i = 0; i < support.size(); ++i) {
        const std::size_t link = static_cast<std::size_t>(support[i]);
        if (anchorsBelow[link] == static_cast<int>(anchors.size())) {
            wire.numSpanLinks = static_cast<int>(i);
            break;
        }
        const int parent = model.joints_[link].parent;
        if (parent != kGround) anchorsBelow[static_cast<std::size_t>(parent)] += anchorsBelow[link];
    }
    wire.firstSupportLink = static_cast<int>(model.supportLinks_.size());
    wire.numSupportLinks = static_cast<int>(support.size());
    model.supportLinks_.insert(model.supportLinks_.end(), support.begin(), support.end());
}

void ModelBuilder::buildContacts(Model& model) const {
    std::map<std::string, std::string> contactWhere;
    for (const ContactSpec& cs : contacts_) {
        claimName(contactWhere, "contact", cs.name, cs.where);
        const std::string label = "contact '" + cs.name + "'";
        const int link = model.findLinkIndex(cs.link);
        if (link == Model::kNotFound || link == kGround)
            throw ModelError(cs.where, label + ": unknown link '" + cs.link + "' (a contact is on one of the model's links)");
        if (model.links_[static_cast<std::size_t>(link)].isVirtual)
            throw ModelError(cs.where, label + ": link '" + cs.link + "' is a virtual link, which cannot touch the ground");
        if (cs.sole_B.empty()) throw ModelError(cs.where, label + ": the sole needs at least one vertex");
        for (std::size_t k = 0; k < cs.sole_B.size(); ++k)
            requireFinite(cs.where, label + ": sole vertex " + std::to_string(k), cs.sole_B[k]);
        if (!(cs.friction >= 0) || !std::isfinite(cs.friction))
            throw ModelError(cs.where, label + ": friction " + std::to_string(cs.friction) + " must be finite and >= 0");
        model.contacts_.push_back({cs.name, link, cs.sole_B, cs.friction});
    }
}

namespace {

// A frame spec on the model's links, checked.
LinkFrame resolveFrame(const Model& model, const LinkFrameSpec& spec, const std::string& where, const std::string& label) {
    const int link = model.findLinkIndex(spec.link);
    if (link == Model::kNotFound) throw ModelError(where, label + ": unknown link '" + spec.link + "'");
    if (link != kGround && model.getLink(link).isVirtual)
        throw ModelError(where, label + ": link '" + spec.link + "' is a virtual link, which carries wires only");
    requireFinite(where, label + ": translation", spec.translation);
    requireFinite(where, label + ": rotation", spec.xyzBodyRotation);
    return {link, spec.translation, calcRotationFromBodyFixedXYZ(spec.xyzBodyRotation), spec.xyzBodyRotation};
}

void requireNonNegative(const std::string& where, const std::string& label, const char* what, double value) {
    if (!(value >= 0) || !std::isfinite(value))
        throw ModelError(where, label + ": " + what + " " + std::to_string(value) + " must be finite and >= 0");
}

void requireNonNegative(const std::string& where, const std::string& label, const char* what,
                        const Eigen::Vector3d& value) {
    for (int i = 0; i < 3; ++i) requireNonNegative(where, label, what, value[i]);
}

}  // namespace

void ModelBuilder::buildForceElements(Model& model) const {
    ForceElements& elements = model.forceElements_;
    std::map<std::string, std::string> names;
    for (const CoordinateLimitForceSpec& spec : coordinateLimits_) {
        claimName(names, "force element", spec.name, spec.where);
        const std::string label = "CoordinateLimitForce '" + spec.name + "'";
        const int q = model.findCoordinateIndex(spec.coordinate);
        if (q == Model::kNotFound) throw ModelError(spec.where, label + ": unknown coordinate '" + spec.coordinate + "'");
        const Joint& joint = model.getJoint(model.getCoordinates()[static_cast<std::size_t>(q)].joint);
        if (joint.type != JointType::Pin && joint.type != JointType::Custom)
            throw ModelError(spec.where, label + ": coordinate '" + spec.coordinate +
                                             "' is part of a quaternion; a limit needs a pin or custom joint's coordinate");
        for (const auto& [what, value] : {std::pair<const char*, double>{"upper stiffness", spec.upperStiffness},
                                          {"lower stiffness", spec.lowerStiffness},
                                          {"damping", spec.damping}})
            requireNonNegative(spec.where, label, what, value);
        if (!(spec.transition > 0) || !std::isfinite(spec.transition))
            throw ModelError(spec.where, label + ": transition " + std::to_string(spec.transition) + " must be > 0");
        if (!std::isfinite(spec.upperLimit) || !std::isfinite(spec.lowerLimit) || !(spec.lowerLimit <= spec.upperLimit))
            throw ModelError(spec.where, label + ": limits [" + std::to_string(spec.lowerLimit) + ", " +
                                             std::to_string(spec.upperLimit) + "] must be finite with lower <= upper");
        const int u = joint.uStart + (q - joint.qStart);
        elements.coordinateLimits.push_back({spec.name, q, u, spec.upperStiffness, spec.upperLimit, spec.lowerStiffness,
                                             spec.lowerLimit, spec.damping, spec.transition});
    }
    for (const PointToPointSpringSpec& spec : springs_) {
        claimName(names, "force element", spec.name, spec.where);
        const std::string label = "PointToPointSpring '" + spec.name + "'";
        const LinkFrame a = resolveFrame(model, {spec.linkA, spec.pointA, Eigen::Vector3d::Zero()}, spec.where, label);
        const LinkFrame b = resolveFrame(model, {spec.linkB, spec.pointB, Eigen::Vector3d::Zero()}, spec.where, label);
        if (a.link == b.link) throw ModelError(spec.where, label + ": both points are on '" + spec.linkA + "'");
        requireNonNegative(spec.where, label, "stiffness", spec.stiffness);
        requireNonNegative(spec.where, label, "rest length", spec.restLength);
        elements.springs.push_back({spec.name, a.link, b.link, a.p_BF, b.p_BF, spec.stiffness, spec.restLength});
    }
    for (const BushingForceSpec& spec : bushings_) {
        claimName(names, "force element", spec.name, spec.where);
        const std::string label = "BushingForce '" + spec.name + "'";
        BushingForce bushing{spec.name,
                             resolveFrame(model, spec.frameA, spec.where, label),
                             resolveFrame(model, spec.frameB, spec.where, label),
                             spec.rotationalStiffness,
                             spec.translationalStiffness,
                             spec.rotationalDamping,
                             spec.translationalDamping};
        if (bushing.frameA.link == bushing.frameB.link)
            throw ModelError(spec.where, label + ": both frames are on '" + spec.frameA.link + "'");
        requireNonNegative(spec.where, label, "rotational stiffness", spec.rotationalStiffness);
        requireNonNegative(spec.where, label, "translational stiffness", spec.translationalStiffness);
        requireNonNegative(spec.where, label, "rotational damping", spec.rotationalDamping);
        requireNonNegative(spec.where, label, "translational damping", spec.translationalDamping);
        elements.bushings.push_back(std::move(bushing));
    }
    std::map<std::string, std::string> geometryNames;
    for (const ContactGeometrySpec& spec : contactGeometry_) {
        claimName(geometryNames, "contact geometry", spec.name, spec.where);
        const std::string label = "contact geometry '" + spec.name + "'";
        const bool sphere = spec.shape == ContactGeometry::Shape::Sphere;
        if (sphere && (!(spec.radius > 0) || !std::isfinite(spec.radius)))
            throw ModelError(spec.where, label + ": radius " + std::to_string(spec.radius) + " must be finite and > 0");
        elements.contactGeometry.push_back({spec.name, spec.shape, resolveFrame(model, spec.frame, spec.where, label),
                                            sphere ? spec.radius : 0.0});
    }
    for (const HuntCrossleyForceSpec& spec : huntCrossley_) {
        claimName(names, "force element", spec.name, spec.where);
        const std::string label = "HuntCrossleyForce '" + spec.name + "'";
        if (!(spec.transitionVelocity > 0) || !std::isfinite(spec.transitionVelocity))
            throw ModelError(spec.where, label + ": transition velocity " + std::to_string(spec.transitionVelocity) +
                                             " must be finite and > 0");
        HuntCrossleyForce force{spec.name, {}, spec.transitionVelocity, {}};
        for (const HuntCrossleySurfaceSpec& surface : spec.surfaces) {
            const auto it = std::find_if(elements.contactGeometry.begin(), elements.contactGeometry.end(),
                                         [&](const ContactGeometry& g) { return g.name == surface.geometry; });
            if (it == elements.contactGeometry.end())
                throw ModelError(spec.where, label + ": unknown contact geometry '" + surface.geometry + "'");
            if (!(surface.stiffness > 0) || !std::isfinite(surface.stiffness))
                throw ModelError(spec.where, label + ": '" + surface.geometry + "' has stiffness " +
                                                 std::to_string(surface.stiffness) + ", expected > 0");
            for (const auto& [what, value] : {std::pair<const char*, double>{"dissipation", surface.dissipation},
                                              {"static friction", surface.staticFriction},
                                              {"dynamic friction", surface.dynamicFriction},
                                              {"viscous friction", surface.viscousFriction}})
                requireNonNegative(spec.where, label + ", '" + surface.geometry + "'", what, value);
            force.surfaces.push_back({static_cast<int>(it - elements.contactGeometry.begin()), surface.stiffness,
                                      surface.dissipation, surface.staticFriction, surface.dynamicFriction,
                                      surface.viscousFriction});
        }
        const auto geometryOf = [&](const HuntCrossleySurface& s) -> const ContactGeometry& {
            return elements.contactGeometry[static_cast<std::size_t>(s.geometry)];
        };
        for (std::size_t h = 0; h < force.surfaces.size(); ++h)
            for (std::size_t s = 0; s < force.surfaces.size(); ++s) {
                const ContactGeometry& halfSpace = geometryOf(force.surfaces[h]);
                const ContactGeometry& sphere = geometryOf(force.surfaces[s]);
                if (halfSpace.shape == ContactGeometry::Shape::HalfSpace && sphere.shape == ContactGeometry::Shape::Sphere &&
                    halfSpace.frame.link != sphere.frame.link)
                    force.pairs.push_back({static_cast<int>(h), static_cast<int>(s)});
            }
        elements.huntCrossley.push_back(std::move(force));
    }
}

}  // namespace sinew
