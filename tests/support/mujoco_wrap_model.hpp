#pragma once
// A small random MuJoCo-style leg for the MuJoCo wrapping tests: three bodies on hinges (each about an axis
// of its body frame through its origin), a sphere at the knee and a cylinder at the ankle, sites around
// them, and spatial tendons over each geom without a side site, with one outside and with one inside it,
// one over the knee with its side site on the shank (the next body), plus one tendon over both. The same description gives sinew's model (ModelBuilder: welded base for
// MuJoCo's world, custom joints with one rotation axis for the hinges, MuJoCo-method wraps) and an MJCF file.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <iomanip>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "sinew/core/model_builder.hpp"

namespace sinew::test {

struct MujocoLegBody {
    std::string name, parent;  // parent "world" for the first
    Eigen::Vector3d pos = Eigen::Vector3d::Zero();    // m, in the parent body's frame
    Eigen::Vector3d euler = Eigen::Vector3d::Zero();  // rad, intrinsic x-y-z (MuJoCo's default eulerseq)
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // unit, the hinge's axis in this body's frame
};

struct MujocoLegFrameItem {  // a site or a wrap geom
    std::string name, body;  // body "world" for MuJoCo's world body
    Eigen::Vector3d pos = Eigen::Vector3d::Zero();    // m, in the body's frame
    Eigen::Vector3d euler = Eigen::Vector3d::Zero();  // rad, geoms only
    WrapShape shape = WrapShape::Sphere;              // geoms only
    double radius = 0;                                // m, geoms only
};

// One element of a spatial tendon's path: a site, or a geom with an optional side site.
struct MujocoLegPathElement {
    std::string site, geom, sideSite;
};

struct MujocoLegTendon {
    std::string name;
    std::vector<MujocoLegPathElement> path;
};

struct MujocoLeg {
    std::vector<MujocoLegBody> bodies;  // parents first
    std::vector<MujocoLegFrameItem> sites, geoms;
    std::vector<MujocoLegTendon> tendons;

    const MujocoLegFrameItem& findSite(const std::string& name) const {
        for (const MujocoLegFrameItem& s : sites)
            if (s.name == name) return s;
        throw std::runtime_error("no site " + name);
    }
};

inline Eigen::Matrix3d rotationFromEuler(const Eigen::Vector3d& e) {
    return (Eigen::AngleAxisd(e.x(), Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(e.y(), Eigen::Vector3d::UnitY()) *
            Eigen::AngleAxisd(e.z(), Eigen::Vector3d::UnitZ()))
        .toRotationMatrix();
}

// Thigh, shank and foot hanging along -y, turned a little; wrap geoms at the knee and the ankle with their
// tendons' sites on either side of them, so that bending the joints wraps them one way or the other.
inline MujocoLeg generateMujocoLeg(std::mt19937& rng) {
    std::uniform_real_distribution<double> uniform(-1, 1);
    auto vector = [&](double scale) { return Eigen::Vector3d(scale * uniform(rng), scale * uniform(rng), scale * uniform(rng)); };
    auto direction = [&] { return Eigen::Vector3d(vector(1).normalized()); };
    MujocoLeg leg;
    leg.bodies = {{"thigh", "world", vector(0.02), vector(0.3), direction()},
                  {"shank", "thigh", Eigen::Vector3d(0, -0.3, 0) + vector(0.02), vector(0.3), direction()},
                  {"foot", "shank", Eigen::Vector3d(0, -0.25, 0) + vector(0.02), vector(0.3), Eigen::Vector3d::UnitZ()}};
    const double kneeRadius = 0.04 + 0.01 * uniform(rng), ankleRadius = 0.03 + 0.01 * uniform(rng);
    const Eigen::Vector3d knee = leg.bodies[1].pos + vector(0.005), ankle = leg.bodies[2].pos + vector(0.005);
    const Eigen::Vector3d ankleEuler = vector(0.4);
    // The foot's hinge near the drum's axis, so that it winds the tendons round the drum.
    leg.bodies[2].axis = (rotationFromEuler(leg.bodies[2].euler).transpose() * rotationFromEuler(ankleEuler) *
                              Eigen::Vector3d::UnitZ() + vector(0.2)).normalized();
    leg.geoms = {{"knee_ball", "thigh", knee, Eigen::Vector3d::Zero(), WrapShape::Sphere, kneeRadius},
                 {"ankle_drum", "shank", ankle, ankleEuler, WrapShape::Cylinder, ankleRadius}};
    // Sites above (+y) and below (-y) a joint centre, on a random side of it across y.
    auto aroundJoint = [&](const std::string& name, const std::string& body, const Eigen::Vector3d& centre, double up) {
        const double side = uniform(rng) < 0 ? -1 : 1;
        leg.sites.push_back({name, body,
                             centre + Eigen::Vector3d(side * (0.03 + 0.04 * std::abs(uniform(rng))), up * (0.06 + 0.08 * std::abs(uniform(rng))),
                                                      0.03 * uniform(rng))});
    };
    for (const char* tag : {"plain", "side", "inside", "both"}) {
        aroundJoint(std::string("knee_above_") + tag, "thigh", knee, 1);
        aroundJoint(std::string("knee_below_") + tag, "shank", Eigen::Vector3d::Zero(), -1);
        aroundJoint(std::string("ankle_above_") + tag, "shank", ankle, 1);
        aroundJoint(std::string("ankle_below_") + tag, "foot", Eigen::Vector3d::Zero(), -1);
    }
    leg.sites.push_back({"hip", "world", Eigen::Vector3d(0.05, 0.1, 0) + vector(0.02)});
    // Side sites: outside the geom, on a random side; inside it, off its centre.
    leg.sites.push_back({"knee_side_out", "thigh", knee + (3 * kneeRadius) * direction()});
    leg.sites.push_back({"knee_side_in", "thigh", knee + (0.5 * kneeRadius) * direction()});
    const Eigen::Matrix3d R_drum = rotationFromEuler(ankleEuler);
    const Eigen::Vector3d across = Eigen::Vector3d(uniform(rng), uniform(rng), 0).normalized();
    leg.sites.push_back({"ankle_side_out", "shank", ankle + R_drum * Eigen::Vector3d(3 * ankleRadius * across.x(),
                                                                                       3 * ankleRadius * across.y(), 0.05 * uniform(rng))});
    leg.sites.push_back({"ankle_side_in", "shank", ankle + R_drum * Eigen::Vector3d(0.5 * ankleRadius * across.x(),
                                                                                      0.5 * ankleRadius * across.y(), 0.05 * uniform(rng))});
    // A side site on the shank for the knee's ball (on the thigh), off the knee, which turns round it as
    // the knee bends (drawn last, so that the rest of the leg is the same for a seed).
    const MujocoLegBody& shank = leg.bodies[1];
    leg.sites.push_back({"knee_side_shank", "shank",
                         rotationFromEuler(shank.euler).transpose() * (knee - shank.pos) + (3 * kneeRadius) * direction()});
    aroundJoint("knee_above_turning", "thigh", knee, 1);
    aroundJoint("knee_below_turning", "shank", Eigen::Vector3d::Zero(), -1);
    auto over = [](const std::string& a, const std::string& geom, const std::string& side, const std::string& b) {
        return std::vector<MujocoLegPathElement>{{a, "", ""}, {"", geom, side}, {b, "", ""}};
    };
    leg.tendons = {{"knee_plain", over("knee_above_plain", "knee_ball", "", "knee_below_plain")},
                   {"knee_side", over("knee_above_side", "knee_ball", "knee_side_out", "knee_below_side")},
                   {"knee_inside", over("knee_above_inside", "knee_ball", "knee_side_in", "knee_below_inside")},
                   {"knee_turning", over("knee_above_turning", "knee_ball", "knee_side_shank", "knee_below_turning")},
                   {"ankle_plain", over("ankle_above_plain", "ankle_drum", "", "ankle_below_plain")},
                   {"ankle_side", over("ankle_above_side", "ankle_drum", "ankle_side_out", "ankle_below_side")},
                   {"ankle_inside", over("ankle_above_inside", "ankle_drum", "ankle_side_in", "ankle_below_inside")},
                   {"both", {{"hip", "", ""}, {"knee_above_both", "", ""}, {"", "knee_ball", "knee_side_out"},
                             {"knee_below_both", "", ""}, {"ankle_above_both", "", ""}, {"", "ankle_drum", ""},
                             {"ankle_below_both", "", ""}}}};
    return leg;
}

inline std::string linkOf(const std::string& body) { return body == "world" ? "base" : body; }

// sinew's model of the leg: MuJoCo's world is a link welded to ground, each hinge a custom joint.
inline Model buildMujocoLegModel(const MujocoLeg& leg) {
    ModelBuilder builder("mujoco_leg");
    builder.addLink({"base", 0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero(), ""});
    builder.addJoint([] {
        JointSpec weld;
        weld.name = "mount", weld.type = JointType::Weld, weld.parent = "ground", weld.child = "base";
        return weld;
    }());
    for (const MujocoLegBody& body : leg.bodies) {
        builder.addLink({body.name, 1, Eigen::Vector3d::Zero(), 0.01 * Eigen::Matrix3d::Identity(), ""});
        JointSpec hinge;
        hinge.name = body.name + "_hinge", hinge.type = JointType::Custom;
        hinge.parent = linkOf(body.parent), hinge.child = body.name;
        hinge.p_PF = body.pos, hinge.R_PF = rotationFromEuler(body.euler), hinge.R_BM = Eigen::Matrix3d::Identity();
        hinge.coordinates.emplace_back();
        hinge.coordinates.back().name = hinge.name;
        // The other two rotation axes (constant 0) only need to be independent of the hinge's.
        Eigen::Index least = 0;
        body.axis.cwiseAbs().minCoeff(&least);
        const Eigen::Vector3d other1 = body.axis.cross(Eigen::Vector3d::Unit(least)).normalized(), other2 = body.axis.cross(other1);
        hinge.transformAxes = {{body.axis, hinge.name, {}}, {other1, "", {}}, {other2, "", {}},
                               {Eigen::Vector3d::UnitX(), "", {}}, {Eigen::Vector3d::UnitY(), "", {}}, {Eigen::Vector3d::UnitZ(), "", {}}};
        builder.addJoint(hinge);
    }
    for (const MujocoLegFrameItem& geom : leg.geoms) {
        WrapObjectSpec object;
        object.name = geom.name, object.shape = geom.shape, object.link = linkOf(geom.body);
        object.xyzBodyRotation = geom.euler, object.translation = geom.pos, object.radius = geom.radius;
        object.length = 0.1;  // MuJoCo's wrapping cylinder is infinite; the length is not read
        builder.addWrapObject(object);
    }
    for (const MujocoLegTendon& tendon : leg.tendons) {
        WireSpec wire;
        wire.name = tendon.name, wire.kind = WireKind::Tendon;
        wire.law.type = "prescribed_tension";
        wire.law.parameters.set("tension", {10});
        for (const MujocoLegPathElement& e : tendon.path) {
            if (e.geom.empty()) {
                const MujocoLegFrameItem& site = leg.findSite(e.site);
                wire.points.push_back({linkOf(site.body), site.pos, ""});
                continue;
            }
            WireWrapSpec wrap;
            wrap.object = e.geom, wrap.method = WrapMethod::MuJoCo;
            wrap.firstPoint = static_cast<int>(wire.points.size()) - 1, wrap.lastPoint = *wrap.firstPoint + 1;
            if (!e.sideSite.empty()) {
                const MujocoLegFrameItem& side = leg.findSite(e.sideSite);
                wrap.sideSite = side.pos;
                wrap.sideSiteLink = linkOf(side.body);
            }
            wire.wraps.push_back(wrap);
        }
        builder.addWire(wire);
    }
    return builder.build();
}

// The leg as MJCF for MuJoCo 2.2.2 (angles in radians; each body's mass given, the geoms' left out of it).
inline std::string writeMujocoLegMjcf(const MujocoLeg& leg) {
    std::ostringstream out;
    out << std::setprecision(17);
    auto vec = [&](const Eigen::Vector3d& v) {
        std::ostringstream s;
        s << std::setprecision(17) << v.x() << ' ' << v.y() << ' ' << v.z();
        return s.str();
    };
    auto items = [&](const std::string& body, const std::string& indent) {
        for (const MujocoLegFrameItem& s : leg.sites)
            if (s.body == body) out << indent << "<site name=\"" << s.name << "\" pos=\"" << vec(s.pos) << "\"/>\n";
        for (const MujocoLegFrameItem& g : leg.geoms)
            if (g.body == body)
                out << indent << "<geom name=\"" << g.name << "\" type=\"" << (g.shape == WrapShape::Sphere ? "sphere" : "cylinder")
                    << "\" size=\"" << g.radius << (g.shape == WrapShape::Cylinder ? " 0.05" : "") << "\" pos=\"" << vec(g.pos)
                    << "\" euler=\"" << vec(g.euler) << "\" contype=\"0\" conaffinity=\"0\"/>\n";
    };
    out << "<mujoco model=\"mujoco_leg\">\n  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n  <worldbody>\n";
    items("world", "    ");
    std::string indent = "    ";
    for (const MujocoLegBody& b : leg.bodies) {  // a chain: each body inside the one before
        out << indent << "<body name=\"" << b.name << "\" pos=\"" << vec(b.pos) << "\" euler=\"" << vec(b.euler) << "\">\n";
        indent += "  ";
        out << indent << "<inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"0.01 0.01 0.01\"/>\n";
        out << indent << "<joint name=\"" << b.name << "_hinge\" type=\"hinge\" pos=\"0 0 0\" axis=\"" << vec(b.axis) << "\"/>\n";
        items(b.name, indent);
    }
    for (std::size_t i = 0; i < leg.bodies.size(); ++i) {
        indent.resize(indent.size() - 2);
        out << indent << "</body>\n";
    }
    out << "  </worldbody>\n  <tendon>\n";
    for (const MujocoLegTendon& t : leg.tendons) {
        out << "    <spatial name=\"" << t.name << "\">\n";
        for (const MujocoLegPathElement& e : t.path) {
            if (e.geom.empty()) out << "      <site site=\"" << e.site << "\"/>\n";
            else out << "      <geom geom=\"" << e.geom << "\"" << (e.sideSite.empty() ? "" : " sidesite=\"" + e.sideSite + "\"") << "/>\n";
        }
        out << "    </spatial>\n";
    }
    out << "  </tendon>\n</mujoco>\n";
    return out.str();
}

}  // namespace sinew::test
