#include <filesystem>

#include "mjcf_document.hpp"
#include "mjcf_inertia.hpp"
#include "mjcf_joints.hpp"
#include "mjcf_tendons.hpp"
#include "sinew/core/data.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/inverse_dynamics.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/model_builder.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/mjcf_model.hpp"

namespace sinew {
namespace mjcf {
namespace {

// What sinew needs and MuJoCo may leave out: every moving link has mass, every link with mass positive
// principal moments. A body short of them (its mass came from mesh files sinew does not read, or
// boundmass without boundinertia) gets these floors, the ones the libmujoco reference adds to its
// mesh-stripped copies (tests/support/mujoco_reference.cpp), and a line in notImported.
constexpr double kMassFloor = 1e-4;     // kg
constexpr double kInertiaFloor = 1e-8;  // kg m^2

// Every element of the model, in the form ModelBuilder takes; kept so that the values MuJoCo computes at
// qpos0 can be filled in and the model built again.
struct ModelSpecs {
    std::string name;
    Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
    std::string gravityWhere;
    std::vector<LinkSpec> links;
    std::vector<JointSpec> joints;
    std::vector<WrapObjectSpec> wrapObjects;
    std::vector<TendonWire> wires;
    std::vector<CoordinateCouplerSpec> couplers;
    std::vector<LoopSpec> loops;
};

Model buildModel(const ModelSpecs& specs) {
    ModelBuilder builder(specs.name);
    builder.setGravity(specs.gravity, specs.gravityWhere);
    for (const LinkSpec& link : specs.links) builder.addLink(link);
    for (const JointSpec& joint : specs.joints) builder.addJoint(joint);
    for (const WrapObjectSpec& object : specs.wrapObjects) builder.addWrapObject(object);
    for (const TendonWire& wire : specs.wires) builder.addWire(wire.spec);
    for (const CoordinateCouplerSpec& coupler : specs.couplers) builder.addCoupler(coupler);
    for (const LoopSpec& loop : specs.loops) builder.addLoop(loop);
    return builder.build();
}

void applySinewFloors(const MjcfBody& body, MassProperties& p, std::vector<std::string>& notImported) {
    const std::string label = describeAt("body", body.name, body.where);
    const Eigen::Vector3d& I = p.principalMoments;
    const std::string moments = formatNumber(I[0]) + ", " + formatNumber(I[1]) + ", " + formatNumber(I[2]) + " kg m^2";
    if (body.joints.empty() && p.mass < kMinValue) {
        if (!I.isZero(0))
            notImported.push_back(label + ": massless, so its principal moments (" + moments + ") are dropped "
                                  "(sinew's massless links have no inertia)");
        p.mass = 0;
        p.principalMoments.setZero();
        return;
    }
    if (p.mass < kMinValue) {
        notImported.push_back(label + ": a moving body without mass (" + formatNumber(p.mass) + " kg); sinew gives it " +
                              formatNumber(kMassFloor) + " kg");
        p.mass = kMassFloor;
    }
    if (I.minCoeff() < kMinValue) {
        notImported.push_back(label + ": principal moments " + moments + " raised to at least " +
                              formatNumber(kInertiaFloor) + " kg m^2 (sinew needs a positive-definite inertia with mass)");
        p.principalMoments = I.cwiseMax(kInertiaFloor);
    }
}

// Links from the bodies' mass properties, scaled to the compiler's settotalmass as mj_setTotalmass does.
void addLinks(const MjcfModel& model, ModelSpecs& specs, std::vector<std::string>& notImported) {
    std::vector<MassProperties> properties;
    double total = 0;
    for (std::size_t b = 1; b < model.bodies.size(); ++b) {
        properties.push_back(calcBodyMassProperties(model, static_cast<int>(b)));
        total += properties.back().mass;
    }
    const double scale = model.compiler.setTotalMass > 0
                             ? std::max(kMinValue, model.compiler.setTotalMass / std::max(kMinValue, total))
                             : 1.0;
    for (std::size_t b = 1; b < model.bodies.size(); ++b) {
        MassProperties& p = properties[b - 1];
        p.mass *= scale;
        p.principalMoments *= scale;
        applySinewFloors(model.bodies[b], p, notImported);
        specs.links.push_back(LinkSpec{model.bodies[b].name, p.mass, p.com, p.calcInertia(), model.bodies[b].where});
        specs.joints.push_back(convertBodyJoints(model, static_cast<int>(b), notImported));
    }
}

// q1 = ref1 + sum_k c_k (q2 - ref2)^k (MuJoCo's joint equality) written as a polynomial in q2, highest
// power first.
Function makeCouplerFunction(const std::array<double, 5>& c, double ref1, double ref2) {
    std::vector<double> power(5, 0.0);  // coefficient of q2^j
    for (int k = 0; k < 5; ++k) {
        double binomial = 1;  // C(k, j) (-ref2)^(k - j), for j = k down to 0
        for (int j = k; j >= 0; --j) {
            power[static_cast<std::size_t>(j)] += c[static_cast<std::size_t>(k)] * binomial;
            binomial *= -ref2 * j / (k - j + 1);
        }
    }
    power[0] += ref1;
    while (power.size() > 1 && power.back() == 0) power.pop_back();
    return Function::polynomial(std::vector<double>(power.rbegin(), power.rend()));
}

// Why equality `e` has no sinew counterpart, or "" when it has one.
std::string findWhyNoCounterpart(const MjcfModel& model, const MjcfEquality& e) {
    if (!e.active) return "inactive (active=\"false\"), so it does not act in MuJoCo either";
    if (e.tag == "weld") return "weld constraints are not modelled";
    if (e.tag == "tendon") return "tendon equalities are not modelled";
    if (e.tag == "connect")
        return e.name1 == (e.name2.empty() ? std::string("world") : e.name2) ? "it connects a body to itself" : "";
    if (e.name2.empty()) return "it holds joint '" + e.name1 + "' at a constant; sinew has no such constraint";
    for (const std::string& name : {e.name1, e.name2}) {
        int body = -1;
        const int joint = findJoint(model, name, body);
        const JointKind type = model.bodies[static_cast<std::size_t>(body)].joints[static_cast<std::size_t>(joint)].type;
        if (type != JointKind::Hinge && type != JointKind::Slide)
            return "joint '" + name + "' is a ball or free joint; couplers join hinge and slide coordinates";
        if (!isImportedJoint(model, body, joint)) return "joint '" + name + "' is not a coordinate in sinew";
    }
    return "";
}

const MjcfJoint& getJoint(const MjcfModel& model, const std::string& name) {
    int body = -1;
    const int joint = findJoint(model, name, body);
    return model.bodies[static_cast<std::size_t>(body)].joints[static_cast<std::size_t>(joint)];
}

void addEqualities(const MjcfModel& model, ModelSpecs& specs, std::vector<std::string>& notImported) {
    const std::vector<Eigen::Isometry3d> poses = calcRestPoses(model);
    for (std::size_t i = 0; i < model.equalities.size(); ++i) {
        const MjcfEquality& e = model.equalities[i];
        const std::string name = e.name.empty() ? e.tag + std::to_string(i) : e.name;
        const std::string why = findWhyNoCounterpart(model, e);
        if (!why.empty()) {
            notImported.push_back(describeAt(e.tag, name, e.where) + ": " + why);
        } else if (e.tag == "joint") {
            const MjcfJoint& dependent = getJoint(model, e.name1);
            const MjcfJoint& independent = getJoint(model, e.name2);
            specs.couplers.push_back(CoordinateCouplerSpec{
                name, e.name1, e.name2, makeCouplerFunction(e.polycoef, dependent.ref, independent.ref), 1, e.where});
        } else {
            // A connect without body2 holds body1's anchor at its place in the world.
            const int a = findBody(model, e.name1), b = e.name2.empty() ? 0 : findBody(model, e.name2);
            const Eigen::Vector3d p_B = poses[static_cast<std::size_t>(b)].inverse() *
                                        (poses[static_cast<std::size_t>(a)] * e.anchor);
            specs.loops.push_back(LoopSpec{name, getLinkName(model, a), e.anchor, getLinkName(model, b), p_B, e.where});
        }
    }
}

// MuJoCo's M (mj_crb) at the model's default q: the tree's mass matrix plus each joint's armature on its
// speeds. Columns from inverse dynamics: tau(udot = e_i) - tau(0) at u = 0.
Eigen::MatrixXd calcMassMatrix(const MjcfModel& mjcf, const Model& model, Data& data) {
    const int nu = model.getNumU();
    const Eigen::VectorXd q = model.getDefaultQ(), u = Eigen::VectorXd::Zero(nu);
    const std::vector<SpatialVector> noLoads(static_cast<std::size_t>(model.getNumLinks()), SpatialVector::Zero());
    Eigen::VectorXd bias(nu), column(nu), udot = Eigen::VectorXd::Zero(nu);
    calcInverseDynamics(model, data, q, u, udot, noLoads, bias);
    Eigen::MatrixXd M(nu, nu);
    for (int i = 0; i < nu; ++i) {
        udot.setZero();
        udot[i] = 1;
        calcInverseDynamics(model, data, q, u, udot, noLoads, column);
        M.col(i) = column - bias;
    }
    for (const MjcfBody& body : mjcf.bodies) {
        if (body.joints.empty()) continue;
        const Joint& joint = model.getJoint(model.findLinkIndex(body.name));
        for (const MjcfJoint& j : body.joints) {
            const int qIndex = model.findCoordinateIndex(j.name);
            if (joint.type == JointType::Custom && qIndex >= 0)
                M.diagonal()[joint.uStart + qIndex - joint.qStart] += j.armature;
            else if (joint.type != JointType::Custom)
                M.diagonal().segment(joint.uStart, joint.nu).array() += j.armature;
        }
    }
    return M;
}

// The values MuJoCo computes at qpos0 (mj_setConst): a spring's rest length where springlength < 0, and a
// muscle's force scale / acc0 where force < 0, acc0 = |M^-1 J^T| for the tendon's Jacobian row J.
void fillQpos0Values(const MjcfModel& mjcf, ModelSpecs& specs) {
    bool needed = false;
    for (const TendonWire& wire : specs.wires) needed = needed || wire.restLengthAtQpos0 || wire.forceScale;
    if (!needed) return;
    const Model model = buildModel(specs);
    Data data(model);
    const Eigen::MatrixXd M = calcMassMatrix(mjcf, model, data);
    calcPositionKinematics(model, data, model.getDefaultQ());
    calcWirePaths(model, data);
    Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
    calcWireJacobian(model, data, J);
    const Eigen::LDLT<Eigen::MatrixXd> solver(M);
    for (std::size_t w = 0; w < specs.wires.size(); ++w) {
        TendonWire& wire = specs.wires[w];
        if (wire.restLengthAtQpos0) wire.spec.law.parameters.set("rest_length", {data.wireLength[Eigen::Index(w)]});
        if (!wire.forceScale) continue;
        const double acc0 = solver.solve(J.row(Eigen::Index(w)).transpose()).norm();
        wire.spec.law.parameters.set("max_isometric_force", {*wire.forceScale / std::max(kMinValue, acc0)});
    }
}

// Mesh geoms one by one (their files are not read); the other geoms and the sites that no tendon uses in
// one line each, since they are contact shapes, drawings and markers.
void noteGeomsAndSites(const MjcfModel& model, std::vector<std::string>& notImported) {
    std::vector<bool> wrapping(model.geoms.size(), false), onTendon(model.sites.size(), false);
    for (const MjcfTendon& tendon : model.tendons)
        for (const MjcfPathEntry& entry : tendon.path) {
            if (entry.kind == MjcfPathEntry::Kind::Geom) wrapping[static_cast<std::size_t>(entry.object)] = true;
            if (entry.kind == MjcfPathEntry::Kind::Site) onTendon[static_cast<std::size_t>(entry.object)] = true;
            if (entry.sideSite >= 0) onTendon[static_cast<std::size_t>(entry.sideSite)] = true;
        }
    const InertiaFromGeom rule = model.compiler.inertiaFromGeom;
    std::vector<const MjcfGeom*> shapes;
    for (std::size_t g = 0; g < model.geoms.size(); ++g) {
        const MjcfGeom& geom = model.geoms[g];
        const MjcfBody& body = model.bodies[static_cast<std::size_t>(geom.body)];
        const bool givesMass = geom.body > 0 && (rule == InertiaFromGeom::True || (rule == InertiaFromGeom::Auto && !body.inertial));
        if (geom.type == GeomKind::Mesh)
            notImported.push_back(describeAt("geom", geom.name, geom.where) + ": mesh '" + geom.mesh + "' is not read" +
                                  (givesMass ? ", so it gives body '" + body.name + "' no mass (as on a copy without meshes)"
                                             : " (a drawing and contact shape)"));
        else if (!wrapping[g])
            shapes.push_back(&geom);
    }
    if (!shapes.empty())
        notImported.push_back(describeAt("geom", shapes[0]->name, shapes[0]->where) + " and " +
                              std::to_string(shapes.size() - 1) + " more: contact and drawing shapes (their mass is "
                              "in their bodies' links)");
    std::vector<const MjcfSite*> markers;
    for (std::size_t s = 0; s < model.sites.size(); ++s)
        if (!onTendon[s]) markers.push_back(&model.sites[s]);
    if (!markers.empty())
        notImported.push_back(describeAt("site", markers[0]->name, markers[0]->where) + " and " +
                              std::to_string(markers.size() - 1) + " more: on no spatial tendon (sinew keeps wire "
                              "points only)");
}

// The massless link standing for the world body, welded to ground, when a wire point, side site, wrap
// object or loop is fixed on the world.
void addWorldLinkIfUsed(const MjcfModel& model, ModelSpecs& specs) {
    bool used = false;
    for (const TendonWire& wire : specs.wires) {
        for (const WirePointSpec& point : wire.spec.points) used = used || point.link == kWorldLink;
        for (const WireWrapSpec& wrap : wire.spec.wraps) used = used || wrap.sideSiteLink == kWorldLink;
    }
    for (const WrapObjectSpec& object : specs.wrapObjects) used = used || object.link == kWorldLink;
    for (const LoopSpec& loop : specs.loops) used = used || loop.linkA == kWorldLink || loop.linkB == kWorldLink;
    if (!used) return;
    specs.links.push_back(LinkSpec{kWorldLink, 0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero(), model.bodies[0].where});
    JointSpec weld;
    weld.name = kWorldLink;
    weld.type = JointType::Weld;
    weld.parent = "ground";
    weld.child = kWorldLink;
    weld.where = model.bodies[0].where;
    specs.joints.push_back(weld);
}

void noteUnsupported(const MjcfModel& model, std::vector<std::string>& notImported) {
    for (const MjcfUnsupported& u : model.unsupported)
        notImported.push_back(describeAt(u.tag, u.name, u.where) +
                              ": " + u.why);
}

}  // namespace
}  // namespace mjcf

MjcfConversion readMjcfModel(const std::string& path) {
    using namespace mjcf;
    const MjcfModel mjcf = readMjcfDocument(path);
    std::vector<std::string> notImported;
    ModelSpecs specs;
    specs.name = mjcf.name.empty() ? std::filesystem::path(path).stem().string() : mjcf.name;
    specs.gravity = mjcf.gravity;
    specs.gravityWhere = mjcf.file;
    addLinks(mjcf, specs, notImported);
    TendonConversion tendons = convertTendons(mjcf, notImported);
    specs.wires = std::move(tendons.wires);
    specs.wrapObjects = std::move(tendons.wrapObjects);
    addEqualities(mjcf, specs, notImported);
    addWorldLinkIfUsed(mjcf, specs);
    noteGeomsAndSites(mjcf, notImported);
    noteUnsupported(mjcf, notImported);
    fillQpos0Values(mjcf, specs);
    return {buildModel(specs), std::move(notImported)};
}

}  // namespace sinew
