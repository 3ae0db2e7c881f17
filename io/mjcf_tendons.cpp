#include "mjcf_tendons.hpp"

#include <algorithm>

#include "mjcf_inertia.hpp"
#include "mjcf_joints.hpp"
#include "sinew/core/error.hpp"

namespace sinew::mjcf {
namespace {

std::string getTendonName(const MjcfModel& model, int t) {
    const std::string& name = model.tendons[static_cast<std::size_t>(t)].name;
    return name.empty() ? "tendon" + std::to_string(t) : name;
}

bool hasPulley(const MjcfTendon& tendon) {
    for (const MjcfPathEntry& entry : tendon.path)
        if (entry.kind == MjcfPathEntry::Kind::Pulley) return true;
    return false;
}

[[noreturn]] void failActuator(const MjcfActuator& a, const std::string& message) {
    throw ModelError(a.where, a.tag + (a.name.empty() ? "" : " '" + a.name + "'") + ": " + message);
}

// The muscle fitted to a MuJoCo muscle actuator (mju_muscleGain): MuJoCo's normalised fibre length is
// range0 + (length - lengthrange0) / L0 with L0 = (lengthrange1 - lengthrange0) / (range1 - range0), i.e.
// a rigid tendon of slack length lengthrange0 - range0 L0 in series with a fibre of optimal length L0
// whose shortening speed is counted in vmax optimal lengths per second. Thelen's law takes no negative
// slack length, which that map gives most of MS-Human-700's muscles; those keep MuJoCo's optimum
// instead: no slack, and the optimal fibre length is the length at which MuJoCo's muscle is optimal,
// lengthrange0 + (1 - range0) L0 (docs/mjcf-import.md, "Muscles").
ForceLawSpec makeMuscleLaw(const MjcfActuator& a, std::optional<double>& forceScale,
                           std::vector<std::string>& notImported) {
    const ActuatorParams& p = a.params;
    const double range0 = p.gainprm[0], range1 = p.gainprm[1];
    if (!(range1 > range0)) failActuator(a, "the operating range gainprm[0..1] must increase");
    double optimalLength = (p.lengthrange[1] - p.lengthrange[0]) / (range1 - range0);
    double slackLength = p.lengthrange[0] - range0 * optimalLength;
    if (slackLength < 0) {
        notImported.push_back(describeAt(a.tag, a.name, a.where) + ": MuJoCo's length map has a negative tendon slack (" +
                              formatNumber(slackLength) + " m), which Thelen's law refuses; sinew keeps its "
                              "optimum (no slack, optimal fibre length " + formatNumber(optimalLength + slackLength) +
                              " m instead of " + formatNumber(optimalLength) + " m)");
        optimalLength += slackLength;
        slackLength = 0;
    }
    ForceLawSpec law;
    law.type = "thelen2003_muscle";
    const double force = p.gainprm[2];
    if (force < 0) forceScale = p.gainprm[3];
    law.parameters.set("max_isometric_force", {force < 0 ? 1.0 : force});  // replaced once acc0 is known
    law.parameters.set("optimal_fiber_length", {optimalLength});
    law.parameters.set("tendon_slack_length", {slackLength});
    law.parameters.set("max_contraction_velocity", {p.gainprm[6]});
    return law;
}

// Why actuator `a` gives its tendon no muscle law, or "" when it does.
std::string findWhyNotMuscle(const MjcfModel& model, const MjcfActuator& a) {
    if (a.transmission != "tendon")
        return "actuators on " + (a.transmission.empty() ? std::string("nothing") : a.transmission + "s") +
               " are not wires";
    if (a.params.gaintype != GainKind::Muscle) return "only muscle actuators (muscle gain) give wires a force law";
    const MjcfTendon& tendon = model.tendons[static_cast<std::size_t>(a.tendon)];
    if (!tendon.spatial) return "its tendon is a fixed tendon, not a wire";
    if (hasPulley(tendon)) return "its tendon branches at pulleys and MuJoCo's muscle pulls on their weighted sum";
    for (std::size_t i = 0; i < a.params.gear.size(); ++i)
        if (a.params.gear[i] != (i == 0 ? 1 : 0)) return "its gear is not 1: sinew's muscle pulls its wire directly";
    if (!(a.params.lengthrange[1] > a.params.lengthrange[0]))
        return "no lengthrange: MuJoCo computes it by simulation when it compiles, sinew does not";
    return "";
}

// The muscle actuator of each tendon (index into MjcfModel::actuators, -1 for none); the other actuators
// are listed.
std::vector<int> findMuscles(const MjcfModel& model, std::vector<std::string>& notImported) {
    std::vector<int> muscles(model.tendons.size(), -1);
    for (std::size_t i = 0; i < model.actuators.size(); ++i) {
        const MjcfActuator& a = model.actuators[i];
        std::string why = findWhyNotMuscle(model, a);
        if (why.empty() && muscles[static_cast<std::size_t>(a.tendon)] >= 0)
            why = "its tendon already has muscle '" +
                  model.actuators[static_cast<std::size_t>(muscles[static_cast<std::size_t>(a.tendon)])].name + "'";
        if (!why.empty()) {
            notImported.push_back(describeAt(a.tag, a.name, a.where) + ": " + why);
            continue;
        }
        muscles[static_cast<std::size_t>(a.tendon)] = static_cast<int>(i);
        if (a.params.biastype != BiasKind::Muscle)
            notImported.push_back(describeAt(a.tag, a.name, a.where) + ": its bias is not MuJoCo's passive muscle "
                                  "force, but sinew's Thelen law keeps its passive curve");
    }
    return muscles;
}

// MuJoCo's tendon spring and damper (tendon stiffness, damping, springlength) as sinew's spring_damper,
// which never pushes; a tendon with neither carries no tension of its own.
ForceLawSpec makeTendonLaw(const MjcfTendon& tendon, bool& restLengthAtQpos0) {
    ForceLawSpec law;
    if (tendon.stiffness == 0 && tendon.damping == 0) {
        law.type = "prescribed_tension";
        law.parameters.set("tension", {0.0});
        return law;
    }
    law.type = "spring_damper";
    law.parameters.set("stiffness", {tendon.stiffness});
    law.parameters.set("damping", {tendon.damping});
    // Without stiffness the rest length only gates the damper: keep it open at every length.
    restLengthAtQpos0 = tendon.stiffness > 0 && tendon.springlength < 0;
    const double rest = tendon.stiffness == 0 ? 1e-9 : restLengthAtQpos0 ? 1.0 : tendon.springlength;
    law.parameters.set("rest_length", {rest});
    return law;
}

// The path split at its pulleys.
std::vector<std::vector<const MjcfPathEntry*>> splitBranches(const MjcfTendon& tendon) {
    std::vector<std::vector<const MjcfPathEntry*>> branches(1);
    for (const MjcfPathEntry& entry : tendon.path) {
        if (entry.kind == MjcfPathEntry::Kind::Pulley) branches.emplace_back();
        else branches.back().push_back(&entry);
    }
    return branches;
}

// The model and what the conversion collects, shared by the tendon functions below.
struct TendonContext {
    const MjcfModel& model;
    std::vector<int> wrapGeoms;  // geoms some tendon wraps, in order of first use
    std::vector<std::string>& notImported;
};

WireWrapSpec makeWrap(const MjcfModel& model, const MjcfPathEntry& entry, int pointBefore) {
    WireWrapSpec wrap;
    wrap.object = model.geoms[static_cast<std::size_t>(entry.object)].name;
    wrap.firstPoint = pointBefore;
    wrap.lastPoint = pointBefore + 1;
    wrap.method = WrapMethod::MuJoCo;
    wrap.where = entry.where;
    // MuJoCo moves a side site with its own body, which may be another than its geom's (four of
    // MS-Human-700's are).
    if (entry.sideSite >= 0) {
        const MjcfSite& side = model.sites[static_cast<std::size_t>(entry.sideSite)];
        wrap.sideSite = side.pos;
        wrap.sideSiteLink = getLinkName(model, side.body);
    }
    return wrap;
}

WireSpec makeBranchWire(TendonContext& context, const std::vector<const MjcfPathEntry*>& branch,
                        const std::string& name, const std::string& where) {
    WireSpec wire;
    wire.name = name;
    wire.where = where;
    const MjcfSite* previous = nullptr;  // the site just before, when no geom lies between
    for (const MjcfPathEntry* entry : branch) {
        if (entry->kind == MjcfPathEntry::Kind::Site) {
            const MjcfSite& site = context.model.sites[static_cast<std::size_t>(entry->object)];
            // Two sites at one place on one body make a segment of zero length at every pose, which sinew
            // refuses and MuJoCo adds nothing for: one point stands for both.
            if (previous && previous->body == site.body && (previous->pos - site.pos).norm() < 1e-12) {
                context.notImported.push_back(describeAt("tendon", name, entry->where) + ": sites '" + previous->name +
                                              "' and '" + site.name + "' coincide on body '" +
                                              getLinkName(context.model, site.body) + "'; one wire point stands for both");
                continue;
            }
            wire.points.push_back(WirePointSpec{getLinkName(context.model, site.body), site.pos, entry->where});
            previous = &site;
            continue;
        }
        previous = nullptr;
        wire.wraps.push_back(makeWrap(context.model, *entry, static_cast<int>(wire.points.size()) - 1));
        std::vector<int>& geoms = context.wrapGeoms;
        if (std::find(geoms.begin(), geoms.end(), entry->object) == geoms.end()) geoms.push_back(entry->object);
    }
    return wire;
}

WrapObjectSpec makeWrapObject(const MjcfModel& model, int g) {
    const MjcfGeom& geom = model.geoms[static_cast<std::size_t>(g)];
    const CompiledGeom compiled = compileGeom(geom);
    WrapObjectSpec object;
    object.name = geom.name;
    object.shape = geom.type == GeomKind::Sphere ? WrapShape::Sphere : WrapShape::Cylinder;
    object.link = getLinkName(model, geom.body);
    object.xyzBodyRotation = compiled.quat.toRotationMatrix().eulerAngles(0, 1, 2);  // R = Rx Ry Rz
    object.translation = compiled.pos;
    object.radius = compiled.size[0];
    // MuJoCo wraps an infinite cylinder; the length is the drawn geom's.
    if (geom.type == GeomKind::Cylinder) object.length = 2 * compiled.size[1];
    object.where = geom.where;
    return object;
}

void noteTendonProperties(const MjcfTendon& tendon, const std::string& name, std::vector<std::string>& notImported) {
    const std::string label = describeAt("tendon", name, tendon.where);
    if (tendon.limited)
        notImported.push_back(label + ": its length limits [" + formatNumber(tendon.rangeMin) + ", " +
                              formatNumber(tendon.rangeMax) + "] m: sinew's wires have none");
    if (tendon.frictionloss != 0) notImported.push_back(label + ": frictionloss: sinew's wires have no friction");
}

void addTendonWires(TendonContext& context, int t, int muscle, TendonConversion& out) {
    const MjcfModel& model = context.model;
    std::vector<std::string>& notImported = context.notImported;
    const MjcfTendon& tendon = model.tendons[static_cast<std::size_t>(t)];
    const std::string name = getTendonName(model, t);
    const auto branches = splitBranches(tendon);
    noteTendonProperties(tendon, name, notImported);
    if (branches.size() > 1)
        notImported.push_back(describeAt("tendon", name, tendon.where) + ": split at its pulleys into " +
                              std::to_string(branches.size()) + " wires '" + name + "/0'...: MuJoCo's length is the "
                              "sum of each branch's length divided by the divisor of the pulley before it; its "
                              "spring and damper act on that sum and are not imported");
    for (std::size_t k = 0; k < branches.size(); ++k) {
        TendonWire wire;
        wire.tendon = t;
        const std::string wireName = branches.size() == 1 ? name : name + "/" + std::to_string(k);
        wire.spec = makeBranchWire(context, branches[k], wireName, tendon.where);
        if (muscle >= 0) {
            const MjcfActuator& a = model.actuators[static_cast<std::size_t>(muscle)];
            wire.spec.kind = WireKind::Muscle;
            wire.spec.law = makeMuscleLaw(a, wire.forceScale, notImported);
            wire.spec.lawWhere = a.where;
        } else {
            wire.spec.kind = WireKind::Tendon;
            MjcfTendon passive = tendon;
            if (branches.size() > 1) passive.stiffness = passive.damping = 0;
            wire.spec.law = makeTendonLaw(passive, wire.restLengthAtQpos0);
        }
        out.wires.push_back(std::move(wire));
    }
}

}  // namespace

TendonConversion convertTendons(const MjcfModel& model, std::vector<std::string>& notImported) {
    TendonConversion out;
    const std::vector<int> muscles = findMuscles(model, notImported);
    TendonContext context{model, {}, notImported};
    for (std::size_t t = 0; t < model.tendons.size(); ++t) {
        const MjcfTendon& tendon = model.tendons[t];
        if (!tendon.spatial) {
            notImported.push_back(describeAt("fixed", getTendonName(model, int(t)), tendon.where) +
                                  ": fixed tendons are weighted sums of joint positions, not wires");
            continue;
        }
        addTendonWires(context, static_cast<int>(t), muscles[t], out);
    }
    for (int g : context.wrapGeoms) out.wrapObjects.push_back(makeWrapObject(model, g));
    return out;
}

}  // namespace sinew::mjcf
