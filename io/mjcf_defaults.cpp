#include "mjcf_defaults.hpp"

namespace sinew::mjcf {

const char* toString(GeomKind kind) {
    switch (kind) {
        case GeomKind::Plane: return "plane";
        case GeomKind::HeightField: return "hfield";
        case GeomKind::Sphere: return "sphere";
        case GeomKind::Capsule: return "capsule";
        case GeomKind::Ellipsoid: return "ellipsoid";
        case GeomKind::Cylinder: return "cylinder";
        case GeomKind::Box: return "box";
        case GeomKind::Mesh: return "mesh";
    }
    return "?";
}

namespace {

const std::vector<const char*> kGeomKeywords = {"plane", "hfield", "sphere", "capsule", "ellipsoid", "cylinder",
                                                "box", "mesh"};

void readFromTo(const XmlElement& element, std::optional<Eigen::Matrix<double, 6, 1>>& fromto) {
    Eigen::Matrix<double, 6, 1> values;
    if (readNumbers(element, "fromto", values.data(), 6)) fromto = values;
}

template <typename Kind>
void readKind(const XmlElement& element, const char* name, const std::vector<const char*>& keywords, Kind& kind) {
    const int keyword = readKeyword(element, name, keywords);
    if (keyword >= 0) kind = static_cast<Kind>(keyword);
}

// The muscle shortcut's parameters (MuJoCo's OneActuator, "muscle"): its defaults replace the global ones
// still in place, then its named attributes land in gainprm, and biasprm copies gainprm.
void readMuscleShortcut(const XmlElement& element, ActuatorParams& p) {
    const std::array<double, 9> global{1, 0, 0, 0, 0, 0, 0, 0, 0}, muscle{0.75, 1.05, -1, 200, 0.5, 1.6, 1.5, 1.3, 1.2};
    if (p.dynprm[0] == 1) p.dynprm[0] = 0.01;
    if (p.dynprm[1] == 0) p.dynprm[1] = 0.04;
    for (std::size_t i = 0; i < muscle.size(); ++i)
        if (p.gainprm[i] == global[i]) p.gainprm[i] = muscle[i];
    readNumbers(element, "timeconst", p.dynprm.data(), 2);
    readNumbers(element, "range", p.gainprm.data(), 2);
    const char* const names[] = {"force", "scale", "lmin", "lmax", "vmax", "fpmax", "fvmax"};
    for (std::size_t i = 0; i < 7; ++i) readNumber(element, names[i], p.gainprm[i + 2]);
    for (std::size_t i = 0; i < 9; ++i) p.biasprm[i] = p.gainprm[i];
    p.dyntype = DynamicsKind::Muscle;
    p.gaintype = GainKind::Muscle;
    p.biastype = BiasKind::Muscle;
}

// The servo and motor shortcuts: only their implied types matter to the importer (they are not muscles).
void readOtherShortcut(const std::string& tag, ActuatorParams& p) {
    p.dyntype = tag == "cylinder" ? DynamicsKind::Filter : tag == "intvelocity" ? DynamicsKind::Integrator
                                                                                 : DynamicsKind::None;
    p.gaintype = tag == "damper" ? GainKind::Affine : GainKind::Fixed;
    p.biastype = (tag == "position" || tag == "velocity" || tag == "intvelocity" || tag == "cylinder")
                     ? BiasKind::Affine
                     : BiasKind::None;
}

}  // namespace

void readJointParams(const XmlElement& element, JointParams& p) {
    readKind(element, "type", {"free", "ball", "slide", "hinge"}, p.type);
    readTrueFalseAuto(element, "limited", p.limited);
    readVector3(element, "pos", p.pos);
    readVector3(element, "axis", p.axis);
    readNumbers(element, "range", p.range.data(), 2);
    readNumber(element, "ref", p.ref);
    readNumber(element, "springref", p.springref);
    readNumber(element, "stiffness", p.stiffness);
    readNumber(element, "damping", p.damping);
    readNumber(element, "armature", p.armature);
    readNumber(element, "frictionloss", p.frictionloss);
    readNumbers(element, "springdamper", p.springdamper.data(), 2);
}

void readGeomParams(const XmlElement& element, GeomParams& p) {
    readKind(element, "type", kGeomKeywords, p.type);
    readNumbers(element, "size", p.size.data(), 3, false);
    readVector3(element, "pos", p.pos);
    readOrientation(element, p.orientation);
    readFromTo(element, p.fromto);
    double mass = 0;
    if (readNumber(element, "mass", mass)) p.mass = mass;
    readNumber(element, "density", p.density);
    readInt(element, "group", p.group);
    readInt(element, "contype", p.contype);
    readInt(element, "conaffinity", p.conaffinity);
    if (const auto mesh = readText(element, "mesh")) p.mesh = *mesh;
    if (const auto hfield = readText(element, "hfield")) p.hfield = *hfield;
}

void readSiteParams(const XmlElement& element, SiteParams& p) {
    readKind(element, "type", kGeomKeywords, p.type);
    readVector3(element, "pos", p.pos);
    readFromTo(element, p.fromto);
}

void readTendonParams(const XmlElement& element, TendonParams& p) {
    readTrueFalseAuto(element, "limited", p.limited);
    readNumbers(element, "range", p.range.data(), 2);
    readNumber(element, "stiffness", p.stiffness);
    readNumber(element, "damping", p.damping);
    readNumber(element, "frictionloss", p.frictionloss);
    readNumber(element, "springlength", p.springlength);
}

bool isActuatorTag(const std::string& tag) {
    for (const char* known : {"general", "motor", "position", "velocity", "damper", "intvelocity", "cylinder", "muscle",
                              "adhesion"})
        if (tag == known) return true;
    return false;
}

void readActuatorParams(const XmlElement& element, ActuatorParams& p) {
    readNumbers(element, "lengthrange", p.lengthrange.data(), 2);
    readNumbers(element, "gear", p.gear.data(), 6, false);
    if (element.tag == "general") {
        readKind(element, "dyntype", {"none", "integrator", "filter", "muscle", "user"}, p.dyntype);
        readKind(element, "gaintype", {"fixed", "affine", "muscle", "user"}, p.gaintype);
        readKind(element, "biastype", {"none", "affine", "muscle", "user"}, p.biastype);
        readNumbers(element, "dynprm", p.dynprm.data(), 10, false);
        readNumbers(element, "gainprm", p.gainprm.data(), 10, false);
        readNumbers(element, "biasprm", p.biasprm.data(), 10, false);
    } else if (element.tag == "muscle") {
        readMuscleShortcut(element, p);
    } else {
        readOtherShortcut(element.tag, p);
    }
}

void readEqualityParams(const XmlElement& element, EqualityParams& p) { readBool(element, "active", p.active); }

DefaultClasses::DefaultClasses() {
    classes_.push_back(DefaultClass{});
    classes_.front().name = "main";
    byName_["main"] = 0;
}

void DefaultClasses::readSection(const XmlElement& section) {
    // A top-level <default> is class "main" whatever its class attribute says (mjXReader::Default renames
    // the top class to it).
    if (const auto name = readText(section, "class")) {
        byName_.erase(classes_.front().name);
        classes_.front().name = *name;
        byName_[*name] = 0;
    }
    readClass(section, 0);
}

void DefaultClasses::readClass(const XmlElement& section, std::size_t index) {
    for (const XmlElement& element : section.children) {
        DefaultClass& c = classes_[index];
        if (element.tag == "joint") readJointParams(element, c.joint);
        else if (element.tag == "geom") readGeomParams(element, c.geom);
        else if (element.tag == "site") readSiteParams(element, c.site);
        else if (element.tag == "tendon") readTendonParams(element, c.tendon);
        else if (isActuatorTag(element.tag)) readActuatorParams(element, c.actuator);
        else if (element.tag == "equality") readEqualityParams(element, c.equality);
    }
    // Nested classes copy their parent once its own elements are read, as MuJoCo's AddDef does.
    for (const XmlElement& element : section.children) {
        if (element.tag != "default") continue;
        const std::optional<std::string> name = readText(element, "class");
        if (!name || name->empty()) element.fail("a nested default needs a class name");
        if (byName_.count(*name)) element.fail("default class '" + *name + "' is defined twice");
        DefaultClass child = classes_[index];
        child.name = *name;
        byName_[*name] = classes_.size();
        classes_.push_back(std::move(child));
        readClass(element, classes_.size() - 1);
    }
}

const DefaultClass& DefaultClasses::find(const std::string& name, const XmlElement& referrer) const {
    const auto it = byName_.find(name);
    if (it == byName_.end()) referrer.fail("unknown default class '" + name + "'");
    return classes_[it->second];
}

const DefaultClass& DefaultClasses::findFor(const XmlElement& element, const DefaultClass& inherited) const {
    const std::optional<std::string> name = readText(element, "class");
    return name ? find(*name, element) : inherited;
}

}  // namespace sinew::mjcf
