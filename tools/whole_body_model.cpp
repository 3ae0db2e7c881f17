#include "sinew/tools/whole_body_model.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>

#include "sinew/core/data.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/model_builder.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/core/wire_path_samples.hpp"

namespace sinew {
namespace {

// A point fixed on a link of the new model, as it sits at the neutral pose.
struct NeutralPoint {
    std::string link;
    Eigen::Vector3d p_G = Eigen::Vector3d::Zero();
};

double calcPolylineLength(const std::vector<NeutralPoint>& points) {
    double length = 0;
    for (std::size_t k = 1; k < points.size(); ++k) length += (points[k].p_G - points[k - 1].p_G).norm();
    return length;
}

std::string formatLength(double metres) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f mm", 1e3 * metres);
    return text;
}

// The source model at its neutral pose, and where each of its links goes in the new one. New link frames
// are parallel to ground at the neutral pose, with their origin at the link's joint centre, so that every
// ball joint is at identity there and a point's new coordinates are its neutral ground position minus the
// link's origin.
class Reshaper {
public:
    Reshaper(const Model& source, const WholeBodyRules& rules, const std::optional<SegmentRatios>& ratios)
        : source_(source), rules_(rules), data_(source) {
        calcPositionKinematics(source_, data_, source_.getDefaultQ());
        calcWirePaths(source_, data_);
        assignGroups();
        completeMissingMasses(ratios);
    }

    WholeBodyBuild build() {
        ModelBuilder builder(rules_.name);
        builder.setGravity(source_.getGravity());
        addLinksAndJoints(builder);
        addWrapObjects(builder);
        addLoops(builder);
        std::set<std::string> forked;
        for (const WholeBodyForkRule& fork : rules_.forks) addFork(builder, fork, forked);
        addSourceWires(builder, forked);
        for (const WholeBodyPassiveRule& rule : rules_.passive) addPassiveWire(builder, rule);
        for (const WholeBodyJointWiresRule& rule : rules_.jointWires) addJointWires(builder, rule);
        addContacts(builder);
        return {builder.build(), notes_};
    }

private:
    [[noreturn]] void fail(const std::string& where, const std::string& what) const {
        throw ModelError(where.empty() ? rules_.file : where, what);
    }

    int findSourceLink(const std::string& body, const std::string& where) const {
        const int link = source_.findLinkIndex(body);
        if (link < 0) fail(where, "no body '" + body + "' in the source model '" + source_.getName() + "'");
        return link;
    }

    const std::string& groupOf(int sourceLink) const { return rules_.links[groupOfLink_[sourceLink]].name; }

    void assignGroups() {
        groupOfLink_.assign(static_cast<std::size_t>(source_.getNumLinks()), -1);
        for (std::size_t g = 0; g < rules_.links.size(); ++g) {
            const WholeBodyLinkRule& rule = rules_.links[g];
            if (rule.bodies.empty()) fail(rule.where, "link '" + rule.name + "' groups no body");
            for (const std::string& body : rule.bodies) {
                const int link = findSourceLink(body, rule.where);
                if (groupOfLink_[link] >= 0)
                    fail(rule.where, "body '" + body + "' is already in link '" + groupOf(link) + "'");
                groupOfLink_[link] = static_cast<int>(g);
            }
        }
        for (int i = 0; i < source_.getNumLinks(); ++i)
            if (groupOfLink_[i] < 0 && !source_.getLink(i).isVirtual)
                fail("", "source body '" + source_.getLink(i).name + "' is in no link of the rules");
        for (const WholeBodyLinkRule& rule : rules_.links) checkGroupIsConnected(rule);
        for (const WholeBodyLinkRule& rule : rules_.links) {
            const int first = source_.findLinkIndex(rule.bodies.front());
            const Joint& joint = source_.getJoint(first);
            origin_[rule.name] = data_.p_GB[first] + data_.R_GB[first] * joint.p_BM;
            const int parent = joint.parent;
            parentOf_[rule.name] = parent == kGround ? std::string() : groupOf(parent);
        }
    }

    // Every body after the first hangs from a body of the same link: the link is one rigid piece.
    void checkGroupIsConnected(const WholeBodyLinkRule& rule) const {
        for (std::size_t k = 1; k < rule.bodies.size(); ++k) {
            const int link = source_.findLinkIndex(rule.bodies[k]);
            const int parent = source_.getJoint(link).parent;
            if (parent == kGround || groupOf(parent) != rule.name)
                fail(rule.where, "body '" + rule.bodies[k] + "' of link '" + rule.name + "' hangs from '" +
                                     (parent == kGround ? std::string("ground") : source_.getLink(parent).name) +
                                     "', outside the link (list a link's bodies so each hangs from one before it)");
        }
    }

    // Mass and central inertia (ground axes at neutral) of a source link, completed where the rules say.
    struct MassProperties {
        double mass = 0;
        Eigen::Vector3d com_G = Eigen::Vector3d::Zero();
        Eigen::Matrix3d inertia_G = Eigen::Matrix3d::Zero();
    };

    MassProperties getSourceMass(int link) const {
        const auto completed = completedMass_.find(link);
        if (completed != completedMass_.end()) return completed->second;
        const Link& body = source_.getLink(link);
        const Eigen::Matrix3d& R = data_.R_GB[link];
        return {body.mass, data_.p_GB[link] + R * body.com_B, R * body.inertia_Bcom * R.transpose()};
    }

    // The bodies whose mass the source lacks share what their segment lacks, each as a solid box over the
    // extent of the wire points on it (the bone's muscle attachments), or a 2 cm sphere without points.
    void completeMissingMasses(const std::optional<SegmentRatios>& ratios) {
        if (!rules_.missingMass) return;
        const WholeBodyMassRule& rule = *rules_.missingMass;
        if (!ratios) fail(rule.where, "missing masses need the anthropometric table (--anthropometrics)");
        std::set<int> missing;
        for (const std::string& body : rule.missingBodies) missing.insert(findSourceLink(body, rule.where));
        double known = 0, knownInSegment = 0;
        for (int i = 0; i < source_.getNumLinks(); ++i)
            if (!missing.count(i)) known += source_.getLink(i).mass;
        for (const std::string& body : rule.segmentBodies) {
            const int link = findSourceLink(body, rule.where);
            if (missing.count(link)) fail(rule.where, "body '" + body + "' is listed both as known and as missing");
            knownInSegment += source_.getLink(link).mass;
        }
        const double ratio = ratios->relativeMass;
        const double wholeBody = (known - knownInSegment) / (1 - ratio);
        const double lacking = ratio * wholeBody - knownInSegment;
        if (!(ratio > 0 && ratio < 1) || !(lacking > 0))
            fail(rule.where, "segment '" + rule.segment + "' (mass ratio " + std::to_string(ratio) +
                                 ") leaves nothing for the missing bodies: its known bodies weigh " +
                                 std::to_string(knownInSegment) + " kg");
        const double each = lacking / static_cast<double>(missing.size());
        for (int link : missing) completedMass_[link] = calcBoxMass(link, each);
        notes_.push_back("masses: " + std::to_string(missing.size()) + " bodies without mass get " +
                         std::to_string(each) + " kg each, from Dumas 2007 " + rule.segment + " (" + rule.gender +
                         ", ratio " + std::to_string(ratio) + ") of a " + std::to_string(wholeBody) + " kg body");
    }

    MassProperties calcBoxMass(int link, double mass) const {
        Eigen::Vector3d lo = Eigen::Vector3d::Constant(-0.02), hi = Eigen::Vector3d::Constant(0.02);
        bool any = false;
        for (const WirePoint& point : source_.getWirePoints()) {
            if (point.link != link) continue;
            lo = any ? lo.cwiseMin(point.p_B) : point.p_B;
            hi = any ? hi.cwiseMax(point.p_B) : point.p_B;
            any = true;
        }
        const Eigen::Vector3d size = (hi - lo).cwiseMax(0.01);
        const Eigen::Vector3d centre = 0.5 * (lo + hi);
        Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
        inertia(0, 0) = mass * (size.y() * size.y() + size.z() * size.z()) / 12;
        inertia(1, 1) = mass * (size.x() * size.x() + size.z() * size.z()) / 12;
        inertia(2, 2) = mass * (size.x() * size.x() + size.y() * size.y()) / 12;
        const Eigen::Matrix3d& R = data_.R_GB[link];
        return {mass, data_.p_GB[link] + R * centre, R * inertia * R.transpose()};
    }

    LinkSpec calcLinkSpec(const WholeBodyLinkRule& rule) const {
        double mass = 0;
        Eigen::Vector3d moment = Eigen::Vector3d::Zero();
        std::vector<MassProperties> parts;
        for (const std::string& body : rule.bodies) parts.push_back(getSourceMass(source_.findLinkIndex(body)));
        for (const MassProperties& part : parts) {
            mass += part.mass;
            moment += part.mass * part.com_G;
        }
        if (!(mass > 0)) fail(rule.where, "link '" + rule.name + "' has no mass");
        const Eigen::Vector3d com_G = moment / mass;
        Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
        for (const MassProperties& part : parts) {
            const Eigen::Vector3d d = part.com_G - com_G;  // parallel axis theorem
            inertia += part.inertia_G + part.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
        }
        LinkSpec link;
        link.name = rule.name;
        link.mass = mass;
        link.com_B = com_G - origin_.at(rule.name);
        link.inertia_Bcom = 0.5 * (inertia + inertia.transpose());
        link.where = rule.where;
        return link;
    }

    // The feet (docs/whole-body-model.md, "Feet"): a sole polygon on each calcaneus and toes link. The vertices
    // are set in MS-Human-700's body frames (x forward, y up, z to the right) under its skin capsules: the
    // heel, the metatarsal heads and the toe tips, mirrored in z for the left foot. They are then levelled to
    // the lowest of them at the neutral pose, so that the soles lie flat on one floor there. A source without
    // these bodies gets no feet.
    void addContacts(ModelBuilder& builder) const {
        struct Sole {
            const char* body;
            double mirror;
            std::vector<Eigen::Vector3d> p;
        };
        const std::vector<Eigen::Vector3d> calcn = {{0.005, -0.01, -0.025}, {0.005, -0.01, 0.015},
                                                    {0.17, -0.01, 0.04}, {0.17, -0.01, -0.04}};
        const std::vector<Eigen::Vector3d> toes = {{0.0, -0.01, -0.035}, {0.0, -0.01, 0.03},
                                                   {0.05, -0.01, 0.02}, {0.055, -0.01, -0.03}};
        const std::vector<Sole> soles = {{"calcn_r", 1, calcn}, {"toes_r", 1, toes}, {"calcn_l", -1, calcn}, {"toes_l", -1, toes}};
        const Eigen::Vector3d up = -source_.getGravity().normalized();
        std::vector<std::vector<NeutralPoint>> placed;
        double floor = std::numeric_limits<double>::infinity();
        for (const Sole& sole : soles) {
            if (source_.findLinkIndex(sole.body) < 0) return;
            placed.emplace_back();
            for (const Eigen::Vector3d& p : sole.p) {
                placed.back().push_back(locate({sole.body, Eigen::Vector3d(p.x(), p.y(), sole.mirror * p.z()), false, ""}));
                floor = std::min(floor, up.dot(placed.back().back().p_G));
            }
        }
        for (const std::vector<NeutralPoint>& vertices : placed) {
            ContactSpec contact;
            contact.name = vertices.front().link;
            contact.link = vertices.front().link;
            contact.where = rules_.file;
            for (const NeutralPoint& vertex : vertices)
                contact.sole_B.push_back(toLink(vertex.link, vertex.p_G - (up.dot(vertex.p_G) - floor) * up));
            builder.addContact(contact);
        }
    }

    void addLinksAndJoints(ModelBuilder& builder) const {
        bool rootSeen = false;
        for (const WholeBodyLinkRule& rule : rules_.links) {
            builder.addLink(calcLinkSpec(rule));
            JointSpec joint;
            joint.name = rule.name + "_joint";
            joint.child = rule.name;
            joint.where = rule.where;
            const std::string& parent = parentOf_.at(rule.name);
            if (rule.name == rules_.root) {
                if (!parent.empty()) fail(rule.where, "the root link '" + rule.name + "' hangs from '" + parent + "'");
                rootSeen = true;
                joint.type = JointType::Free;
                joint.parent = "ground";
                joint.initialPosition = origin_.at(rule.name);
            } else {
                if (parent.empty()) fail(rule.where, "link '" + rule.name + "' hangs from ground but is not the root");
                joint.type = JointType::Ball;
                joint.parent = parent;
                joint.p_PF = origin_.at(rule.name) - origin_.at(parent);
            }
            builder.addJoint(joint);
        }
        if (!rootSeen) fail("", "the root link '" + rules_.root + "' is not among the links");
    }

    Eigen::Vector3d toLink(const std::string& link, const Eigen::Vector3d& p_G) const {
        const auto virtualLink = virtualOrigin_.find(link);
        if (virtualLink != virtualOrigin_.end()) return p_G - virtualLink->second;
        return p_G - origin_.at(link);
    }

    NeutralPoint locate(const SourcePoint& point) const {
        const int link = findSourceLink(point.body, point.where);
        return {groupOf(link), point.inGround ? point.p : Eigen::Vector3d(data_.p_GB[link] + data_.R_GB[link] * point.p)};
    }

    static std::string quadrantName(const WrapObject& object) {
        if (object.quadrantSign == 0) return "all";
        return std::string(object.quadrantSign > 0 ? "+" : "-") + "xyz"[object.quadrantAxis];
    }

    void addWrapObjects(ModelBuilder& builder) const {
        for (const WrapObject& object : source_.getWrapObjects()) {
            WrapObjectSpec spec;
            spec.name = object.name;
            spec.shape = object.shape;
            spec.link = groupOf(object.link);
            const Eigen::Matrix3d R_GW = data_.R_GB[object.link] * object.R_BW;
            spec.xyzBodyRotation = R_GW.eulerAngles(0, 1, 2);  // R = Rx Ry Rz, as the MJCF importer writes them
            spec.translation = toLink(spec.link, data_.p_GB[object.link] + data_.R_GB[object.link] * object.p_BW);
            spec.radius = object.radius;
            spec.length = object.length;
            spec.radii = object.radii;
            spec.quadrant = quadrantName(object);
            builder.addWrapObject(spec);
        }
    }

    void addLoops(ModelBuilder& builder) const {
        for (const WholeBodyLoopRule& rule : rules_.loops) {
            const NeutralPoint at = locate(rule.at);
            for (const std::string& link : {rule.linkA, rule.linkB})
                if (!origin_.count(link)) fail(rule.where, "loop '" + rule.name + "': no link '" + link + "'");
            LoopSpec loop;
            loop.name = rule.name;
            loop.linkA = rule.linkA;
            loop.p_A = toLink(rule.linkA, at.p_G);
            loop.linkB = rule.linkB;
            loop.p_B = toLink(rule.linkB, at.p_G);
            loop.where = rule.where;
            builder.addLoop(loop);
        }
    }

    // A source wire's own points at neutral, on their new links.
    std::vector<NeutralPoint> getNeutralPoints(const Wire& wire) const {
        std::vector<NeutralPoint> points;
        for (int i = 0; i < wire.numPoints; ++i) {
            const int p = wire.firstPoint + i;
            points.push_back({groupOf(source_.getWirePoints()[p].link), data_.p_GP[p]});
        }
        return points;
    }

    // The path of a source wire at neutral, as the points it passes: a wrap's tangent points and the points
    // along its arc between them (calcWirePathSamples, chords of at most 5.6 degrees), on the wrap object's link.
    std::vector<NeutralPoint> getNeutralPath(int w) const {
        const Wire& wire = source_.getWire(w);
        if (wire.isPolyline()) return getNeutralPoints(wire);
        std::vector<WirePathSample> samples;
        calcWirePathSamples(source_, data_, w, M_PI / 32, samples);
        std::vector<NeutralPoint> path;
        // A wrap that touches its object at a path point (an end on the surface) repeats that point.
        for (const WirePathSample& sample : samples)
            if (path.empty() || (sample.p_G - path.back().p_G).norm() >= 1e-9)
                path.push_back({groupOf(sample.link), sample.p_G});
        return path;
    }

    WireSpec makeWire(const std::string& name, WireKind kind, const std::vector<NeutralPoint>& points,
                      const std::string& where) const {
        WireSpec wire;
        wire.name = name;
        wire.kind = kind;
        wire.where = where;
        for (const NeutralPoint& point : points) {
            WirePointSpec spec;
            spec.link = point.link;
            spec.p_B = toLink(point.link, point.p_G);
            spec.where = where;
            wire.points.push_back(spec);
        }
        return wire;
    }

    void setSpringDamper(WireSpec& wire, double stiffness, double restLength) const {
        wire.law.type = "spring_damper";
        wire.law.parameters.set("stiffness", {stiffness});
        wire.law.parameters.set("damping", {rules_.stiffness.dampingRatio * stiffness});
        wire.law.parameters.set("rest_length", {restLength});
    }

    // Strength and cross-section (docs/whole-body-model.md, "Strength and cross-section"): a muscle's or a
    // tendon's strength is given, its cross-section follows from the stress its kind bears at that strength.
    void setStrength(WireSpec& wire, double strength) const {
        const WholeBodyStrength& s = rules_.strength;
        wire.strength = strength;
        wire.crossSection = strength / (wire.kind == WireKind::Muscle ? s.specificTension : s.tendonStress);
    }

    // A ligament's or cartilage's cross-section is its kind's, its strength that area at the ultimate stress.
    void setPassiveStrength(WireSpec& wire) const {
        const WholeBodyStrength& s = rules_.strength;
        const bool cartilage = wire.kind == WireKind::Cartilage;
        wire.crossSection = cartilage ? s.cartilageCrossSection : s.ligamentCrossSection;
        wire.strength = *wire.crossSection * (cartilage ? s.cartilageStress : s.ligamentStress);
    }

    // The source's strength of a muscle (its own, else its force law's max isometric force), for its strength
    // and a stiffness in proportion; 1000 N where it has neither.
    double getMaxForce(const Wire& wire) const { return getWireStrength(wire).value_or(1000.0); }

    double calcMuscleStiffness(const Wire& wire, double neutralLength) const {
        return rules_.stiffness.muscleStrainStiffness * getMaxForce(wire) / neutralLength;
    }

    int findSourceWire(const std::string& name, const std::string& where) const {
        const int w = source_.findWireIndex(name);
        if (w < 0) fail(where, "no wire '" + name + "' in the source model");
        return w;
    }

    void addFork(ModelBuilder& builder, const WholeBodyForkRule& rule, std::set<std::string>& forked) {
        if (rule.heads.size() < 2) fail(rule.where, "fork '" + rule.name + "' needs two heads or more");
        std::vector<std::vector<NeutralPoint>> paths;
        double tendonStrength = 0;  // the heads all pull on the node, and the tendon carries them on
        for (const std::string& head : rule.heads) {
            if (!forked.insert(head).second) fail(rule.where, "wire '" + head + "' is already forked");
            const int w = findSourceWire(head, rule.where);
            paths.push_back(getNeutralPath(w));
            tendonStrength += getMaxForce(source_.getWire(w));
        }
        const std::vector<NeutralPoint>& first = paths.front();
        const Eigen::Vector3d& a = first[first.size() - 2].p_G;
        const Eigen::Vector3d node = a + rule.fraction * (first.back().p_G - a);
        const double prestretch = rules_.stiffness.prestretch;
        virtualOrigin_[rule.name] = node;
        builder.addVirtualLink({rule.name, node, rule.where});
        for (std::size_t h = 0; h < rule.heads.size(); ++h) {
            const int w = source_.findWireIndex(rule.heads[h]);
            std::vector<NeutralPoint> headPath = paths[h];
            headPath.back() = {rule.name, node};
            WireSpec head = makeWire(rule.heads[h], source_.getWire(w).kind, headPath, rule.where);
            const double headLength = calcPolylineLength(headPath);
            setSpringDamper(head, calcMuscleStiffness(source_.getWire(w), headLength), (1 - prestretch) * headLength);
            setStrength(head, getMaxForce(source_.getWire(w)));
            builder.addWire(head);
            const double unitLength = headLength + (paths.front().back().p_G - node).norm();
            notes_.push_back("fork '" + rule.name + "': '" + rule.heads[h] + "' and the tendon are " +
                             formatLength(unitLength - data_.wireLength[w]) + " longer than the source's " +
                             formatLength(data_.wireLength[w]) +
                             (source_.getWire(w).isPolyline() ? "" : " (its wraps became via points along their neutral arcs)"));
            if (h > 0) continue;
            const std::vector<NeutralPoint> tail = {{rule.name, node}, paths.front().back()};
            WireSpec tendon = makeWire(rule.tendon, WireKind::Tendon, tail, rule.where);
            setSpringDamper(tendon, rules_.stiffness.tendonStiffness, (1 - prestretch) * calcPolylineLength(tail));
            setStrength(tendon, tendonStrength);
            builder.addWire(tendon);
        }
    }

    void addSourceWires(ModelBuilder& builder, const std::set<std::string>& forked) const {
        const std::set<std::string> unwrapped(rules_.unwrapped.begin(), rules_.unwrapped.end());
        for (const std::string& name : unwrapped) findSourceWire(name, rules_.file);
        for (int w = 0; w < source_.getNumWires(); ++w) {
            const Wire& wire = source_.getWire(w);
            if (forked.count(wire.name)) continue;
            if (!wire.conditions.empty() || !wire.motions.empty())
                fail("", "source wire '" + wire.name + "' has conditional or moving points, which links cannot keep");
            const bool unwrap = unwrapped.count(wire.name) > 0;
            WireSpec spec = makeWire(wire.name, wire.kind, unwrap ? getNeutralPath(w) : getNeutralPoints(wire), "");
            for (const WireWrap& wrap : wire.wraps)
                if (!unwrap) spec.wraps.push_back(convertWrap(wrap));
            const double length = data_.wireLength[w];
            const double stiffness = wire.kind == WireKind::Muscle ? calcMuscleStiffness(wire, length)
                                                                   : rules_.stiffness.tendonStiffness;
            setSpringDamper(spec, stiffness, (1 - rules_.stiffness.prestretch) * length);
            if (wire.kind == WireKind::Muscle || wire.kind == WireKind::Tendon) setStrength(spec, getMaxForce(wire));
            else setPassiveStrength(spec);
            builder.addWire(spec);
        }
    }

    WireWrapSpec convertWrap(const WireWrap& wrap) const {
        const WrapObject& object = source_.getWrapObjects()[static_cast<std::size_t>(wrap.object)];
        WireWrapSpec spec;
        spec.object = object.name;
        spec.firstPoint = wrap.firstPoint;
        spec.lastPoint = wrap.lastPoint;
        spec.method = wrap.method;
        if (wrap.hasSideSite) {
            const int link = wrap.sideSiteLink;
            spec.sideSiteLink = groupOf(link);
            spec.sideSite = toLink(spec.sideSiteLink, data_.p_GB[link] + data_.R_GB[link] * wrap.sideSite_B);
        }
        return spec;
    }

    bool isInSubtree(const std::string& link, const std::string& top) const {
        for (std::string at = link; !at.empty(); at = parentOf_.at(at))
            if (at == top) return true;
        return false;
    }

    // The passive wire's length with `joint`'s link (and everything below it) turned by `angle` about `axis`
    // (ground axes) through its joint centre.
    double calcLengthTurned(const std::string& joint, const Eigen::Vector3d& axis, double angle,
                            std::vector<NeutralPoint> points) const {
        const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
        const Eigen::Vector3d& centre = origin_.at(joint);
        for (NeutralPoint& point : points)
            if (isInSubtree(point.link, joint)) point.p_G = centre + R * (point.p_G - centre);
        return calcPolylineLength(points);
    }

    // A ligament is slack at neutral and reaches its rest length `limitFraction` of the way to its length
    // at the limit; cartilage is pre-tensioned.
    void addPassiveWire(ModelBuilder& builder, const std::string& name, WireKind kind,
                        const std::vector<NeutralPoint>& points, double atLimit, const std::string& where) const {
        WireSpec wire = makeWire(name, kind, points, where);
        const double neutral = calcPolylineLength(points);
        const WholeBodyStiffness& s = rules_.stiffness;
        if (kind == WireKind::Cartilage) {
            setSpringDamper(wire, s.cartilageStiffness, (1 - s.cartilagePrecompression) * neutral);
        } else {
            if (!(atLimit > neutral + 1e-4))
                fail(where, "ligament '" + name + "' does not lengthen towards its limit (" + formatLength(neutral) +
                                " at neutral, " + formatLength(atLimit) + " at the limit)");
            setSpringDamper(wire, s.ligamentStiffness, neutral + s.limitFraction * (atLimit - neutral));
        }
        setPassiveStrength(wire);
        builder.addWire(wire);
    }

    void addPassiveWire(ModelBuilder& builder, const WholeBodyPassiveRule& rule) const {
        if (rule.points.size() < 2) fail(rule.where, "passive wire '" + rule.name + "' needs two points or more");
        std::vector<NeutralPoint> points;
        for (const SourcePoint& point : rule.points) points.push_back(locate(point));
        double atLimit = 0;
        if (rule.kind == WireKind::Ligament) {
            if (!origin_.count(rule.joint)) fail(rule.where, "ligament '" + rule.name + "': no link '" + rule.joint + "'");
            atLimit = calcLengthTurned(rule.joint, rule.limitAxis, rule.limitAngle, points);
        }
        addPassiveWire(builder, rule.name, rule.kind, points, atLimit, rule.where);
    }

    void addJointWires(ModelBuilder& builder, const WholeBodyJointWiresRule& rule) const {
        const auto parent = parentOf_.find(rule.joint);
        if (parent == parentOf_.end() || parent->second.empty())
            fail(rule.where, "'" + rule.name + "': link '" + rule.joint + "' has no ball joint to a parent link");
        const Eigen::Vector3d f = rule.flexionAxis.normalized();
        const Eigen::Vector3d bone = rule.boneAxis.normalized();
        const Eigen::Vector3d d = bone.cross(f).normalized();
        const Eigen::Vector3d& centre = origin_.at(rule.joint);
        const Eigen::Vector3d directions[] = {d, -d, f, -f};
        for (int k = 0; k < 4; ++k) {
            const Eigen::Vector3d at = centre + rule.radius * directions[k];
            const std::vector<NeutralPoint> points = {{parent->second, at + rule.halfSpan * bone},
                                                      {rule.joint, at - rule.halfSpan * bone}};
            // The pair across d bends about f, the pair across f about d; the stretching side is the limit.
            // Cartilage is pre-tensioned instead, with no limit.
            const Eigen::Vector3d axis = k < 2 ? f : d;
            const double angle = k < 2 ? rule.flexion : rule.abduction;
            const double atLimit = rule.kind != WireKind::Ligament
                                       ? 0.0
                                       : std::max(calcLengthTurned(rule.joint, axis, angle, points),
                                                  calcLengthTurned(rule.joint, axis, -angle, points));
            addPassiveWire(builder, rule.name + "_" + rule.names[static_cast<std::size_t>(k)], rule.kind, points,
                           atLimit, rule.where);
        }
    }

    const Model& source_;
    const WholeBodyRules& rules_;
    Data data_;
    std::vector<int> groupOfLink_;                   // source link -> index into rules.links
    std::map<std::string, Eigen::Vector3d> origin_;  // new link -> its origin in ground at neutral (m)
    std::map<std::string, std::string> parentOf_;    // new link -> its parent link ("" for ground)
    std::map<std::string, Eigen::Vector3d> virtualOrigin_;
    std::map<int, MassProperties> completedMass_;
    std::vector<std::string> notes_;
};

}  // namespace

WholeBodyBuild buildWholeBodyModel(const Model& source, const WholeBodyRules& rules,
                                   const std::optional<SegmentRatios>& segmentRatios) {
    return Reshaper(source, rules, segmentRatios).build();
}

}  // namespace sinew
