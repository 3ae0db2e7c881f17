#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "mjcf_document.hpp"
#include "sinew/core/error.hpp"

namespace sinew::mjcf {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kEpsilon = 1e-14;  // mjEPS

// Names must be unique per kind of object, as MuJoCo's compiler requires.
class NameTable {
public:
    explicit NameTable(const char* kind) : kind_(kind) {}
    void add(const std::string& name, int index, const XmlElement& element) {
        if (name.empty()) return;
        if (!indices_.emplace(name, index).second) element.fail(std::string("repeated ") + kind_ + " name");
    }
    int find(const std::string& name) const {
        const auto it = indices_.find(name);
        return it == indices_.end() ? -1 : it->second;
    }
    int require(const std::string& name, const XmlElement& referrer, const char* attribute) const {
        const int index = find(name);
        if (index < 0) referrer.fail(std::string(attribute) + " '" + name + "': no " + kind_ + " has that name");
        return index;
    }

private:
    const char* kind_;
    std::map<std::string, int> indices_;
};

// MuJoCo's rule for limited="auto" (checklimited, user_objects.cc): with autolimits a range implies
// limits; without it a range needs an explicit limited.
bool resolveLimited(const XmlElement& element, int limited, const Eigen::Vector2d& range, bool autoLimits) {
    const bool hasRange = !(range[0] == 0 && range[1] == 0);
    if (limited != 2) return limited == 1;
    if (!autoLimits && hasRange)
        element.fail("has a range but no limited attribute; with the compiler's autolimits=\"false\" (MuJoCo "
                     "2.2.2's default) say limited=\"true\" or \"false\", or set autolimits=\"true\"");
    return hasRange;
}

std::string requireText(const XmlElement& element, const char* name) {
    const std::optional<std::string> text = readText(element, name);
    if (!text || text->empty()) element.fail(std::string("needs the attribute '") + name + "'");
    return *text;
}

class MjcfReader {
public:
    explicit MjcfReader(const std::string& path) : tree_(readMjcfTree(path)) { model_.file = path; }

    MjcfModel read() {
        model_.name = readText(tree_, "model").value_or("");
        for (const XmlElement& section : tree_.children)
            if (section.tag == "compiler") readCompiler(section);
        for (const XmlElement& section : tree_.children) {
            if (section.tag == "option") readOption(section);
            else if (section.tag == "default") defaults_.readSection(section);
        }
        MjcfBody world;
        world.name = "world";
        world.where = tree_.where();
        model_.bodies.push_back(world);
        bodyNames_.add("world", 0, tree_);
        readSections();
        return std::move(model_);
    }

private:
    // In MuJoCo's order (mjXReader::Parse): bodies before the tendons that name their sites, tendons before
    // the actuators that pull them.
    void readSections() {
        static const std::set<std::string> settings = {"compiler", "option", "default"};
        static const std::vector<std::string> elements = {"worldbody", "tendon", "actuator", "equality"};
        static const std::set<std::string> outside = {"size", "visual", "statistic", "custom", "asset", "contact",
                                                      "sensor", "keyframe", "extension"};
        for (const std::string& kind : elements)
            for (const XmlElement& section : tree_.children)
                if (section.tag == kind) readSection(section);
        for (const XmlElement& section : tree_.children) {
            const bool read = settings.count(section.tag) ||
                              std::find(elements.begin(), elements.end(), section.tag) != elements.end();
            if (outside.count(section.tag)) noteSection(section);
            else if (!read) section.fail("unrecognized element under <mujoco> (MuJoCo 2.2.2's MJCF)");
        }
    }

    void readSection(const XmlElement& section) {
        if (section.tag == "worldbody") {
            if (!section.attributes.empty()) section.fail("the world body cannot have attributes");
            readBodyContents(section, 0, defaults_.getMain());
        } else if (section.tag == "equality") {
            for (const XmlElement& e : section.children) readEquality(e);
        } else if (section.tag == "tendon") {
            for (const XmlElement& e : section.children) readTendon(e);
        } else {
            for (const XmlElement& e : section.children) readActuator(e);
        }
    }

    void noteSection(const XmlElement& section) {
        static const std::map<std::string, std::string> why = {
            {"size", "memory sizes"},
            {"visual", "rendering settings"},
            {"statistic", "rendering statistics"},
            {"custom", "user data"},
            {"asset", "meshes, textures and materials are drawing and collision assets"},
            {"contact", "contacts are not modelled"},
            {"sensor", "sensors are not modelled"},
            {"keyframe", "keyframes are not imported (the default pose is qpos0)"},
            {"extension", "plugins are not supported"}};
        if (section.tag == "contact" || section.tag == "sensor" || section.tag == "keyframe") {
            for (const XmlElement& e : section.children)
                model_.unsupported.push_back({e.tag, e.getName(), e.where(), why.at(section.tag)});
            return;
        }
        const std::size_t count = section.children.size();
        model_.unsupported.push_back({section.tag, "", section.where(),
                                      why.at(section.tag) + (count ? " (" + std::to_string(count) + " elements)" : "")});
    }

    void readCompiler(const XmlElement& e) {
        CompilerSettings& c = model_.compiler;
        readBool(e, "autolimits", c.autoLimits);
        readNumber(e, "boundmass", c.boundMass);
        readNumber(e, "boundinertia", c.boundInertia);
        readNumber(e, "settotalmass", c.setTotalMass);
        readBool(e, "balanceinertia", c.balanceInertia);
        readBool(e, "discardvisual", c.discardVisual);
        if (readKeyword(e, "coordinate", {"local", "global"}) == 1)
            e.fail("coordinate=\"global\" is not supported (MuJoCo's deprecated global frames); use local");
        const int angle = readKeyword(e, "angle", {"radian", "degree"});
        if (angle >= 0) c.angles.degree = angle == 1;
        if (const auto sequence = readText(e, "eulerseq")) {
            if (sequence->size() != 3 || sequence->find_first_not_of("xyzXYZ") != std::string::npos)
                e.fail("eulerseq '" + *sequence + "': expected 3 letters from x, y, z, X, Y, Z");
            c.angles.eulerSequence = *sequence;
        }
        const int fromGeom = readKeyword(e, "inertiafromgeom", {"false", "true", "auto"});
        if (fromGeom >= 0) c.inertiaFromGeom = static_cast<InertiaFromGeom>(fromGeom);
        double range[2] = {double(c.inertiaGroupRange[0]), double(c.inertiaGroupRange[1])};
        if (readNumbers(e, "inertiagrouprange", range, 2)) c.inertiaGroupRange = {int(range[0]), int(range[1])};
        bool fuse = false;
        if (readBool(e, "fusestatic", fuse) && fuse)
            model_.unsupported.push_back({"compiler", "", e.where(),
                                          "fusestatic: sinew keeps static bodies as welded links (same motion)"});
    }

    void readOption(const XmlElement& e) {
        readVector3(e, "gravity", model_.gravity);
        for (const XmlElement& flag : e.children)
            if (flag.tag == "flag" && readKeyword(flag, "gravity", {"disable", "enable"}) == 0)
                model_.gravity.setZero();
    }

    void readBodyContents(const XmlElement& element, int body, const DefaultClass& bodyClass);
    void readBody(const XmlElement& element, int parent, const DefaultClass& parentClass);
    void readInertial(const XmlElement& element, MjcfBody& body);
    MjcfJoint readJoint(const XmlElement& element, const DefaultClass& c, const MjcfBody& body);
    void readGeom(const XmlElement& element, const DefaultClass& c, int body);
    void readSite(const XmlElement& element, const DefaultClass& c, int body);
    void readTendon(const XmlElement& element);
    MjcfPathEntry readPathEntry(const XmlElement& element);
    void checkTendonPath(const MjcfTendon& tendon, const XmlElement& element) const;
    void readActuator(const XmlElement& element);
    void readEquality(const XmlElement& element);

    XmlElement tree_;
    MjcfModel model_;
    DefaultClasses defaults_;
    NameTable bodyNames_{"body"}, jointNames_{"joint"}, siteNames_{"site"}, geomNames_{"geom"}, tendonNames_{"tendon"},
        actuatorNames_{"actuator"}, equalityNames_{"equality"};
    int numJoints_ = 0;
};

void MjcfReader::readBodyContents(const XmlElement& element, int body, const DefaultClass& bodyClass) {
    static const std::set<std::string> notModelled = {"camera", "light"};
    for (const XmlElement& child : element.children) {
        const DefaultClass& c = defaults_.findFor(child, bodyClass);
        if (child.tag == "body") readBody(child, body, bodyClass);
        else if (child.tag == "geom") readGeom(child, c, body);
        else if (child.tag == "site") readSite(child, c, body);
        else if (notModelled.count(child.tag))
            model_.unsupported.push_back({child.tag, child.getName(), child.where(), "cameras and lights are not modelled"});
        else if (body == 0 && (child.tag == "joint" || child.tag == "freejoint" || child.tag == "inertial"))
            child.fail("the world body cannot have joints or an inertial");
        else if (child.tag == "inertial") readInertial(child, model_.bodies[static_cast<std::size_t>(body)]);
        else if (child.tag == "joint" || child.tag == "freejoint") {
            MjcfJoint joint = readJoint(child, c, model_.bodies[static_cast<std::size_t>(body)]);
            MjcfBody& owner = model_.bodies[static_cast<std::size_t>(body)];
            jointNames_.add(joint.name, numJoints_++, child);
            owner.joints.push_back(std::move(joint));
        } else if (child.tag == "composite")
            child.fail("composite objects are not supported (sinew reads the bodies they would generate only "
                       "when written out)");
        else
            child.fail("unrecognized element in a body (MuJoCo 2.2.2's MJCF)");
    }
}

void MjcfReader::readBody(const XmlElement& element, int parent, const DefaultClass& parentClass) {
    const std::optional<std::string> childClass = readText(element, "childclass");
    const DefaultClass& bodyClass = childClass ? defaults_.find(*childClass, element) : parentClass;
    MjcfBody body;
    body.parent = parent;
    body.where = element.where();
    const int index = static_cast<int>(model_.bodies.size());
    body.name = element.getName().empty() ? "body" + std::to_string(index) : element.getName();
    readVector3(element, "pos", body.pos);
    OrientationSpec orientation;
    readOrientation(element, orientation);
    body.quat = resolveOrientation(orientation, model_.compiler.angles, element);
    readBool(element, "mocap", body.mocap);
    bodyNames_.add(body.name, index, element);
    model_.bodies.push_back(std::move(body));
    readBodyContents(element, index, bodyClass);
}

void MjcfReader::readInertial(const XmlElement& element, MjcfBody& body) {
    MjcfInertial inertial;
    inertial.where = element.where();
    if (!readVector3(element, "pos", inertial.pos)) element.fail("needs the attribute 'pos'");
    if (!readNumber(element, "mass", inertial.mass)) element.fail("needs the attribute 'mass'");
    if (inertial.mass < 0) element.fail("mass " + formatNumber(inertial.mass) + " kg is negative; expected >= 0");
    readVector3(element, "diaginertia", inertial.diagonal);
    Eigen::Matrix<double, 6, 1> full;
    if (readNumbers(element, "fullinertia", full.data(), 6)) inertial.full = full;
    OrientationSpec orientation;
    readOrientation(element, orientation);
    inertial.quat = resolveOrientation(orientation, model_.compiler.angles, element);
    body.inertial = inertial;
}

MjcfJoint MjcfReader::readJoint(const XmlElement& element, const DefaultClass& c, const MjcfBody& body) {
    JointParams p = element.tag == "freejoint" ? JointParams{} : c.joint;
    if (element.tag == "freejoint") p.type = JointKind::Free;
    else readJointParams(element, p);
    MjcfJoint joint;
    joint.name = element.getName().empty() ? body.name + "_joint" + std::to_string(body.joints.size()) : element.getName();
    joint.type = p.type;
    joint.where = element.where();
    const bool hinge = p.type == JointKind::Hinge, free = p.type == JointKind::Free;
    const double angle = model_.compiler.angles.degree ? kPi / 180 : 1;
    joint.limited = !free && resolveLimited(element, p.limited, p.range, model_.compiler.autoLimits);
    if (joint.limited) {
        if (p.type == JointKind::Ball ? p.range[0] != 0 : p.range[0] >= p.range[1])
            element.fail(p.type == JointKind::Ball ? "a ball joint's range must start at 0"
                                                   : "range[0] must be smaller than range[1]");
        const double scale = (hinge || p.type == JointKind::Ball) ? angle : 1;
        joint.rangeMin = p.range[0] * scale;
        joint.rangeMax = p.range[1] * scale;
    }
    if (!free) joint.pos = p.pos;
    if (p.type == JointKind::Hinge || p.type == JointKind::Slide) {
        if (p.axis.squaredNorm() < kEpsilon) element.fail("axis is too small to give a direction");
        joint.axis = p.axis.normalized();
    }
    if ((p.springdamper[0] != 0 || p.springdamper[1] != 0) && (p.springdamper[0] <= 0 || p.springdamper[1] <= 0))
        element.fail("springdamper values must both be positive when given");
    joint.ref = p.ref * (hinge ? angle : 1);
    joint.springref = p.springref * (hinge ? angle : 1);
    joint.stiffness = p.stiffness;
    joint.damping = p.damping;
    joint.armature = p.armature;
    joint.frictionloss = p.frictionloss;
    return joint;
}

void MjcfReader::readGeom(const XmlElement& element, const DefaultClass& c, int body) {
    GeomParams p = c.geom;
    readGeomParams(element, p);
    // discardvisual drops drawing-only geoms when they are read, before they can give any mass.
    if (model_.compiler.discardVisual && p.contype == 0 && p.conaffinity == 0) return;
    MjcfGeom geom;
    geom.name = element.getName();
    geom.body = body;
    geom.type = p.type;
    geom.size = p.size;
    geom.pos = p.pos;
    geom.quat = resolveOrientation(p.orientation, model_.compiler.angles, element);
    geom.fromto = p.fromto;
    geom.mass = p.mass;
    geom.density = p.density;
    geom.group = p.group;
    geom.mesh = p.type == GeomKind::Mesh ? p.mesh : "";
    geom.where = element.where();
    if (geom.mass && *geom.mass < 0) element.fail("mass " + formatNumber(*geom.mass) + " kg is negative; expected >= 0");
    if (geom.density < 0) element.fail("density is negative; expected >= 0");
    geomNames_.add(geom.name, static_cast<int>(model_.geoms.size()), element);
    model_.geoms.push_back(std::move(geom));
}

void MjcfReader::readSite(const XmlElement& element, const DefaultClass& c, int body) {
    SiteParams p = c.site;
    readSiteParams(element, p);
    MjcfSite site;
    site.name = element.getName();
    site.body = body;
    site.pos = p.pos;
    site.where = element.where();
    if (p.fromto) {
        if (p.type != GeomKind::Capsule && p.type != GeomKind::Cylinder && p.type != GeomKind::Ellipsoid &&
            p.type != GeomKind::Box)
            element.fail("fromto needs a capsule, cylinder, ellipsoid or box site");
        if (!p.pos.isZero(0)) element.fail("both pos and fromto given; give one");
        site.pos = 0.5 * (p.fromto->head<3>() + p.fromto->tail<3>());
    }
    siteNames_.add(site.name, static_cast<int>(model_.sites.size()), element);
    model_.sites.push_back(std::move(site));
}

void MjcfReader::readTendon(const XmlElement& element) {
    if (element.tag != "spatial" && element.tag != "fixed")
        element.fail("unrecognized element in <tendon>; expected spatial or fixed");
    TendonParams p = defaults_.findFor(element, defaults_.getMain()).tendon;
    readTendonParams(element, p);
    MjcfTendon tendon;
    tendon.name = element.getName();
    tendon.spatial = element.tag == "spatial";
    tendon.where = element.where();
    tendon.limited = resolveLimited(element, p.limited, p.range, model_.compiler.autoLimits);
    if (tendon.limited && p.range[0] >= p.range[1]) element.fail("range[0] must be smaller than range[1]");
    tendon.rangeMin = p.range[0];
    tendon.rangeMax = p.range[1];
    tendon.stiffness = p.stiffness;
    tendon.damping = p.damping;
    tendon.frictionloss = p.frictionloss;
    tendon.springlength = p.springlength;
    for (const XmlElement& entry : element.children) tendon.path.push_back(readPathEntry(entry));
    if (tendon.path.empty()) element.fail("a tendon's path cannot be empty");
    checkTendonPath(tendon, element);
    tendonNames_.add(tendon.name, static_cast<int>(model_.tendons.size()), element);
    model_.tendons.push_back(std::move(tendon));
}

MjcfPathEntry MjcfReader::readPathEntry(const XmlElement& element) {
    MjcfPathEntry entry;
    entry.where = element.where();
    if (element.tag == "site") {
        entry.name = requireText(element, "site");
        entry.object = siteNames_.require(entry.name, element, "site");
    } else if (element.tag == "geom") {
        entry.kind = MjcfPathEntry::Kind::Geom;
        entry.name = requireText(element, "geom");
        entry.object = geomNames_.require(entry.name, element, "geom");
        const GeomKind type = model_.geoms[static_cast<std::size_t>(entry.object)].type;
        if (type != GeomKind::Sphere && type != GeomKind::Cylinder)
            element.fail("geom '" + entry.name + "' is a " + toString(type) + "; tendons wrap spheres and cylinders");
        if (const auto side = readText(element, "sidesite")) entry.sideSite = siteNames_.require(*side, element, "sidesite");
    } else if (element.tag == "pulley") {
        entry.kind = MjcfPathEntry::Kind::Pulley;
        if (!readNumber(element, "divisor", entry.divisor)) element.fail("needs the attribute 'divisor'");
        if (entry.divisor <= 0) element.fail("divisor must be positive");
    } else if (element.tag == "joint") {
        entry.kind = MjcfPathEntry::Kind::Joint;
        entry.name = requireText(element, "joint");
        jointNames_.require(entry.name, element, "joint");
        if (!readNumber(element, "coef", entry.divisor)) element.fail("needs the attribute 'coef'");
    } else {
        element.fail("unrecognized element in a tendon; expected site, geom, pulley or joint");
    }
    return entry;
}

// MuJoCo's path rules (mjCTendon::Compile): spatial paths of sites, wrapping geoms between two sites and
// pulleys between branches; fixed paths of joints only.
void MjcfReader::checkTendonPath(const MjcfTendon& tendon, const XmlElement& element) const {
    using Kind = MjcfPathEntry::Kind;
    const std::vector<MjcfPathEntry>& path = tendon.path;
    const std::size_t n = path.size();
    if (tendon.spatial && n < 2) element.fail("a spatial tendon needs at least two path elements");
    for (std::size_t i = 0; i < n; ++i) {
        const Kind kind = path[i].kind, before = i > 0 ? path[i - 1].kind : Kind::Pulley,
                   after = i + 1 < n ? path[i + 1].kind : Kind::Pulley;
        const XmlElement& entry = element.children[i];
        if (!tendon.spatial && kind != Kind::Joint) entry.fail("a fixed tendon's path holds joints only");
        if (tendon.spatial && kind == Kind::Joint) entry.fail("a spatial tendon's path cannot hold joints");
        if (kind == Kind::Pulley && (before == Kind::Pulley && i > 0)) entry.fail("two pulleys in a row");
        if (kind == Kind::Pulley && i + 1 == n) entry.fail("a path cannot end with a pulley");
        if (kind == Kind::Site && before == Kind::Pulley && after == Kind::Pulley)
            entry.fail("a site needs a neighbour in the path that is not a pulley");
        if (kind == Kind::Site && after == Kind::Site && i + 1 < n && path[i].object == path[i + 1].object)
            entry.fail("the same site twice in a row");
        if (kind == Kind::Geom && (i == 0 || i + 1 == n || before != Kind::Site || after != Kind::Site))
            entry.fail("a wrapping geom must lie between two sites");
    }
}

void MjcfReader::readActuator(const XmlElement& element) {
    if (!isActuatorTag(element.tag)) element.fail("unrecognized element in <actuator>");
    MjcfActuator actuator;
    actuator.name = element.getName();
    actuator.tag = element.tag;
    actuator.where = element.where();
    actuator.params = defaults_.findFor(element, defaults_.getMain()).actuator;
    readActuatorParams(element, actuator.params);
    for (const char* kind : {"joint", "jointinparent", "tendon", "cranksite", "site", "body"}) {
        const std::optional<std::string> target = readText(element, kind);
        if (!target) continue;
        if (!actuator.transmission.empty()) element.fail("more than one transmission target; give one");
        actuator.transmission = kind;
        actuator.target = *target;
    }
    if (actuator.transmission == "tendon") actuator.tendon = tendonNames_.require(actuator.target, element, "tendon");
    if (actuator.transmission == "joint" || actuator.transmission == "jointinparent")
        jointNames_.require(actuator.target, element, actuator.transmission.c_str());
    if (actuator.transmission == "site" || actuator.transmission == "cranksite")
        siteNames_.require(actuator.target, element, actuator.transmission.c_str());
    if (actuator.transmission == "body") bodyNames_.require(actuator.target, element, "body");
    actuatorNames_.add(actuator.name, static_cast<int>(model_.actuators.size()), element);
    model_.actuators.push_back(std::move(actuator));
}

void MjcfReader::readEquality(const XmlElement& element) {
    static const std::map<std::string, std::pair<const char*, const char*>> objects = {
        {"connect", {"body1", "body2"}}, {"weld", {"body1", "body2"}}, {"joint", {"joint1", "joint2"}},
        {"tendon", {"tendon1", "tendon2"}}};
    const auto kind = objects.find(element.tag);
    if (kind == objects.end()) element.fail("unrecognized equality constraint; expected connect, weld, joint or tendon");
    MjcfEquality e;
    e.tag = element.tag;
    e.name = element.getName();
    e.where = element.where();
    EqualityParams p = defaults_.findFor(element, defaults_.getMain()).equality;
    readEqualityParams(element, p);
    e.active = p.active;
    e.name1 = requireText(element, kind->second.first);
    e.name2 = readText(element, kind->second.second).value_or("");
    for (const std::string* name : {&e.name1, &e.name2}) {
        if (name->empty()) continue;
        const char* attribute = name == &e.name1 ? kind->second.first : kind->second.second;
        if (e.tag == "joint") jointNames_.require(*name, element, attribute);
        if (e.tag == "connect" || e.tag == "weld") bodyNames_.require(*name, element, attribute);
        if (e.tag == "tendon") tendonNames_.require(*name, element, attribute);
    }
    if (e.tag == "connect" && !readVector3(element, "anchor", e.anchor)) element.fail("needs the attribute 'anchor'");
    readNumbers(element, "polycoef", e.polycoef.data(), 5);
    equalityNames_.add(e.name, static_cast<int>(model_.equalities.size()), element);
    model_.equalities.push_back(std::move(e));
}

}  // namespace

MjcfModel readMjcfDocument(const std::string& path) { return MjcfReader(path).read(); }

int findBody(const MjcfModel& model, const std::string& name) {
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
        if (model.bodies[i].name == name) return static_cast<int>(i);
    return -1;
}

int findJoint(const MjcfModel& model, const std::string& name, int& body) {
    for (std::size_t b = 0; b < model.bodies.size(); ++b)
        for (std::size_t j = 0; j < model.bodies[b].joints.size(); ++j)
            if (model.bodies[b].joints[j].name == name) {
                body = static_cast<int>(b);
                return static_cast<int>(j);
            }
    return -1;
}

}  // namespace sinew::mjcf
