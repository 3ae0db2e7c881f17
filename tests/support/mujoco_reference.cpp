#include "support/mujoco_reference.hpp"

#include <mujoco/mujoco.h>
#include <tinyxml2.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>
#include <stdexcept>

namespace sinew::test {
namespace {

namespace fs = std::filesystem;
using tinyxml2::XMLDocument;
using tinyxml2::XMLElement;

// Tallies of what the preparation changed, per kind, written out as PreparedMjcf::changes.
using ChangeCounts = std::map<std::string, int>;

constexpr double kMassFloor = 1e-4;     // kg, MS-Human-700's own boundmass
constexpr double kInertiaFloor = 1e-8;  // kg m^2

void loadDocument(XMLDocument& doc, const fs::path& file) {
    if (doc.LoadFile(file.string().c_str()) != tinyxml2::XML_SUCCESS)
        throw std::runtime_error(file.string() + ": cannot read it as XML: " + doc.ErrorStr());
}

// MuJoCo 3 (src/xml/xml.cc, mjIncludeXML) looks for an include first relative to the main file's folder,
// then relative to the folder of the file holding the <include>; 2.2.2 knows only the first, which
// MS-Human-700's nested includes do not follow (MyoSuite's follow the first).
fs::path resolveInclude(const std::string& file, const fs::path& mainFolder, const fs::path& includingFolder,
                        const fs::path& includingFile) {
    if (fs::path(file).is_absolute()) return file;
    for (const fs::path& folder : {mainFolder, includingFolder})
        if (fs::is_regular_file(folder / file)) return (folder / file).lexically_normal();
    throw std::runtime_error(includingFile.string() + ": <include file=\"" + file + "\"> is neither in " +
                             mainFolder.string() + " nor in " + includingFolder.string());
}

// Appends to `target` a copy of each child element of `source` (from `sourceFile`), an <include> replaced by
// the children of its file's root (<mujoco>, or the older <mujocoinclude>), recursively, as MuJoCo inlines
// them before it parses anything. Comments and text go: MJCF reads neither.
void appendFlattened(const XMLElement& source, const fs::path& sourceFile, XMLElement& target,
                     const fs::path& mainFolder, ChangeCounts& counts) {
    for (const XMLElement* child = source.FirstChildElement(); child; child = child->NextSiblingElement()) {
        if (std::strcmp(child->Name(), "include") == 0) {
            const char* file = child->Attribute("file");
            if (!file)
                throw std::runtime_error(sourceFile.string() + ":" + std::to_string(child->GetLineNum()) +
                                         ": <include> without a file attribute");
            const fs::path included = resolveInclude(file, mainFolder, sourceFile.parent_path(), sourceFile);
            XMLDocument includedDoc;
            loadDocument(includedDoc, included);
            appendFlattened(*includedDoc.RootElement(), included, target, mainFolder, counts);
            ++counts["inlined <include> files"];
            continue;
        }
        XMLElement* copy = target.GetDocument()->NewElement(child->Name());
        for (const tinyxml2::XMLAttribute* a = child->FirstAttribute(); a; a = a->Next())
            copy->SetAttribute(a->Name(), a->Value());
        target.InsertEndChild(copy);
        appendFlattened(*child, sourceFile, *copy, mainFolder, counts);
    }
}

template <class Visit>
void forEachElement(XMLElement& element, const Visit& visit) {
    visit(element);
    for (XMLElement* child = element.FirstChildElement(); child; child = child->NextSiblingElement())
        forEachElement(*child, visit);
}

void removeElements(const std::vector<XMLElement*>& elements, ChangeCounts& counts) {
    for (XMLElement* e : elements) {
        ++counts[std::string("removed <") + e->Name() + ">"];
        e->Parent()->DeleteChild(e);
    }
}

// A body whose mass came from its mesh (MyoSuite's talus) is massless once the mesh goes, which MuJoCo's
// compiler refuses for a moving body: floors on masses and inertias, where the file sets none, change no
// position, length or Jacobian.
void addMassFloors(XMLElement& root, ChangeCounts& counts) {
    bool hasMassFloor = false, hasInertiaFloor = false;
    forEachElement(root, [&](XMLElement& e) {
        if (std::strcmp(e.Name(), "compiler") != 0) return;
        hasMassFloor = hasMassFloor || e.Attribute("boundmass");
        hasInertiaFloor = hasInertiaFloor || e.Attribute("boundinertia");
    });
    if (hasMassFloor && hasInertiaFloor) return;
    XMLElement* compiler = root.GetDocument()->NewElement("compiler");
    if (!hasMassFloor) compiler->SetAttribute("boundmass", kMassFloor);
    if (!hasInertiaFloor) compiler->SetAttribute("boundinertia", kInertiaFloor);
    root.InsertEndChild(compiler);
    ++counts["added mass or inertia floors to <compiler>"];
}

bool isAssetNeedingFile(const XMLElement& e) {
    const XMLElement* parent = e.Parent()->ToElement();
    if (!parent || std::strcmp(parent->Name(), "asset") != 0) return false;
    for (const char* kind : {"mesh", "texture", "material", "hfield", "skin"})
        if (std::strcmp(e.Name(), kind) == 0) return true;
    return false;
}

// The meshes, height fields and skins name files that are absent, textures name image files, and materials
// only refer to textures: all of them, and the geoms shaped by a mesh or height field, go. They are drawing,
// collision and (without <inertial>) mass shapes: no joint, site or wrap geom depends on them, so body frames,
// tendon lengths and Jacobians stay as they were. Contact pairs naming a removed geom go with it.
void removeFileAssets(XMLElement& root, ChangeCounts& counts) {
    std::vector<XMLElement*> assets, geoms;
    std::set<std::string> removedGeoms;
    forEachElement(root, [&](XMLElement& e) {
        if (isAssetNeedingFile(e)) assets.push_back(&e);
        const bool inDefault = e.Parent()->ToElement() && std::strcmp(e.Parent()->ToElement()->Name(), "default") == 0;
        if (std::strcmp(e.Name(), "geom") == 0 && !inDefault && (e.Attribute("mesh") || e.Attribute("hfield"))) {
            geoms.push_back(&e);
            if (const char* name = e.Attribute("name")) removedGeoms.insert(name);
        }
    });
    removeElements(assets, counts);
    removeElements(geoms, counts);
    std::vector<XMLElement*> pairs;
    forEachElement(root, [&](XMLElement& e) {
        if (e.Attribute("material")) {
            e.DeleteAttribute("material");
            ++counts["dropped material attributes"];
        }
        if (std::strcmp(e.Name(), "pair") != 0) return;
        for (const char* side : {"geom1", "geom2"})
            if (e.Attribute(side) && removedGeoms.count(e.Attribute(side))) {
                pairs.push_back(&e);
                return;
            }
    });
    removeElements(pairs, counts);
    if (!geoms.empty()) addMassFloors(root, counts);
}

std::filesystem::path makeTemporaryFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "sinew_mujoco_XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary folder from " + pattern);
    return pattern;
}

Eigen::Vector3d generateUnitVector(std::mt19937& rng) {
    std::normal_distribution<double> normal;
    Eigen::Vector3d v(normal(rng), normal(rng), normal(rng));
    return v.normalized();
}

// y - y0 = a0 + a1 (x - x0) + ... + a4 (x - x0)^4, y0 and x0 the joints' qpos0 (MuJoCo's joint equality).
void applyJointCouplings(const mjModel& m, Eigen::VectorXd& qpos) {
    for (int pass = 0; pass < std::max(m.neq, 1); ++pass) {
        bool changed = false;
        for (int e = 0; e < m.neq; ++e) {
            if (m.eq_type[e] != mjEQ_JOINT || !m.eq_active[e]) continue;
            const int y = m.jnt_qposadr[m.eq_obj1id[e]];
            const int x = m.eq_obj2id[e] >= 0 ? m.jnt_qposadr[m.eq_obj2id[e]] : -1;
            const double dx = x >= 0 ? qpos[x] - m.qpos0[x] : 0;
            const mjtNum* a = m.eq_data + mjNEQDATA * e;
            const double value = m.qpos0[y] + a[0] + dx * (a[1] + dx * (a[2] + dx * (a[3] + dx * a[4])));
            changed = changed || value != qpos[y];
            qpos[y] = value;
        }
        if (!changed) return;  // a dependent joint that drives another needs one more pass
    }
}

}  // namespace

PreparedMjcf prepareMjcfForMujoco(const std::filesystem::path& mjcfPath, const std::filesystem::path& folder) {
    XMLDocument source;
    loadDocument(source, mjcfPath);
    XMLDocument flat;
    XMLElement* root = flat.NewElement(source.RootElement()->Name());
    for (const tinyxml2::XMLAttribute* a = source.RootElement()->FirstAttribute(); a; a = a->Next())
        root->SetAttribute(a->Name(), a->Value());
    flat.InsertEndChild(root);
    ChangeCounts counts;
    appendFlattened(*source.RootElement(), mjcfPath, *root, mjcfPath.parent_path(), counts);
    removeFileAssets(*root, counts);

    PreparedMjcf prepared;
    std::filesystem::create_directories(folder);
    prepared.file = folder / mjcfPath.filename();
    if (flat.SaveFile(prepared.file.string().c_str()) != tinyxml2::XML_SUCCESS)
        throw std::runtime_error(prepared.file.string() + ": cannot write it");
    for (const auto& [change, count] : counts) prepared.changes.push_back(change + ": " + std::to_string(count));
    return prepared;
}

MujocoReference::MujocoReference(const std::filesystem::path& mjcfPath)
    : folder_(makeTemporaryFolder()), model_(nullptr, mj_deleteModel), data_(nullptr, mj_deleteData) {
    try {
        prepared_ = prepareMjcfForMujoco(mjcfPath, folder_);
        char error[1000] = "";
        model_.reset(mj_loadXML(prepared_.file.string().c_str(), nullptr, error, sizeof error));
        if (!model_)
            throw std::runtime_error(mjcfPath.string() + ": MuJoCo " + mj_versionString() + " refuses its prepared copy " +
                                     prepared_.file.string() + ": " + error);
    } catch (...) {
        std::filesystem::remove_all(folder_);
        throw;
    }
    // Dense, so that ten_J is the ntendon x nv matrix whatever nv is (2.2.2 compresses its rows when sparse).
    model_->opt.jacobian = mjJAC_DENSE;
    data_.reset(mj_makeData(model_.get()));
    for (int j = 0; j < model_->njnt; ++j) {
        MujocoJoint joint;
        joint.name = getName(mjOBJ_JOINT, j);
        joint.type = static_cast<MujocoJointType>(model_->jnt_type[j]);
        joint.qposAddress = model_->jnt_qposadr[j];
        joint.dofAddress = model_->jnt_dofadr[j];
        joint.body = getName(mjOBJ_BODY, model_->jnt_bodyid[j]);
        joint.limited = model_->jnt_limited[j] != 0;
        joint.rangeMin = model_->jnt_range[2 * j];
        joint.rangeMax = model_->jnt_range[2 * j + 1];
        joints_.push_back(joint);
    }
}

MujocoReference::~MujocoReference() {
    std::error_code ignored;
    std::filesystem::remove_all(folder_, ignored);
}

int MujocoReference::getNumBodies() const { return model_->nbody; }
int MujocoReference::getNumDofs() const { return model_->nv; }
int MujocoReference::getNumTendons() const { return model_->ntendon; }
int MujocoReference::getNumActuators() const { return model_->nu; }
Eigen::VectorXd MujocoReference::getQpos0() const { return Eigen::Map<const Eigen::VectorXd>(model_->qpos0, model_->nq); }

int MujocoReference::findId(int type, const std::string& name) const {
    const int id = mj_name2id(model_.get(), type, name.c_str());
    if (id < 0) throw std::runtime_error("MuJoCo's model " + prepared_.file.string() + " has no " +
                                         (type == mjOBJ_BODY ? "body" : type == mjOBJ_JOINT ? "joint" : "tendon") +
                                         " named '" + name + "'");
    return id;
}

std::string MujocoReference::getName(int type, int id) const {
    const char* name = mj_id2name(model_.get(), type, id);
    return name ? name : "";
}

std::vector<std::string> MujocoReference::getBodyNames() const {
    std::vector<std::string> names;
    for (int b = 1; b < model_->nbody; ++b)
        if (!getName(mjOBJ_BODY, b).empty()) names.push_back(getName(mjOBJ_BODY, b));
    return names;
}

std::vector<std::string> MujocoReference::getTendonNames() const {
    std::vector<std::string> names;
    for (int t = 0; t < model_->ntendon; ++t) names.push_back(getName(mjOBJ_TENDON, t));
    return names;
}

const MujocoJoint& MujocoReference::getJoint(const std::string& name) const {
    return joints_[static_cast<std::size_t>(findId(mjOBJ_JOINT, name))];
}

bool MujocoReference::isWrapping(const std::string& tendon) const {
    const int t = findId(mjOBJ_TENDON, tendon);
    for (int i = model_->tendon_adr[t]; i < model_->tendon_adr[t] + model_->tendon_num[t]; ++i)
        if (model_->wrap_type[i] == mjWRAP_SPHERE || model_->wrap_type[i] == mjWRAP_CYLINDER) return true;
    return false;
}

int MujocoReference::countActiveWraps(const std::string& tendon) const {
    const int t = findId(mjOBJ_TENDON, tendon);
    const int* path = data_->wrap_obj + data_->ten_wrapadr[t];
    // A geom the tendon touches adds its two tangent points to the path, each marked with its id.
    return static_cast<int>(std::count_if(path, path + data_->ten_wrapnum[t], [](int obj) { return obj >= 0; })) / 2;
}

int MujocoReference::getNumJointCouplings() const {
    return static_cast<int>(std::count(model_->eq_type, model_->eq_type + model_->neq, mjEQ_JOINT));
}

Eigen::VectorXd MujocoReference::generateRandomQpos(std::mt19937& rng) const {
    std::uniform_real_distribution<double> unit(0, 1);
    Eigen::VectorXd qpos = getQpos0();
    for (const MujocoJoint& joint : joints_) {
        double* q = qpos.data() + joint.qposAddress;
        if (joint.type == MujocoJointType::Hinge || joint.type == MujocoJointType::Slide) {
            const bool hasRange = joint.rangeMin < joint.rangeMax;
            const double lo = hasRange ? joint.rangeMin : -1, hi = hasRange ? joint.rangeMax : 1;
            q[0] = lo + (hi - lo) * unit(rng);
            continue;
        }
        const bool cone = joint.type == MujocoJointType::Ball && joint.limited && joint.rangeMax > 0;
        const double angle = (cone ? joint.rangeMax : M_PI) * unit(rng);
        const Eigen::Quaterniond rotation(Eigen::AngleAxisd(angle, generateUnitVector(rng)));
        const bool free = joint.type == MujocoJointType::Free;
        double* quaternion = free ? q + 3 : q;
        quaternion[0] = rotation.w(), quaternion[1] = rotation.x(), quaternion[2] = rotation.y(),
        quaternion[3] = rotation.z();
        if (free)
            for (int k = 0; k < 3; ++k) q[k] += unit(rng) - 0.5;
    }
    applyJointCouplings(*model_, qpos);
    return qpos;
}

void MujocoReference::calcKinematics(const Eigen::VectorXd& qpos) {
    if (qpos.size() != model_->nq)
        throw std::runtime_error("qpos has " + std::to_string(qpos.size()) + " entries, MuJoCo's model " +
                                 std::to_string(model_->nq));
    std::copy(qpos.data(), qpos.data() + qpos.size(), data_->qpos);
    mj_kinematics(model_.get(), data_.get());
    mj_comPos(model_.get(), data_.get());
    mj_tendon(model_.get(), data_.get());
}

double MujocoReference::calcEqualityViolation(const Eigen::VectorXd& qpos, bool connects) {
    calcKinematics(qpos);
    mj_fwdPosition(model_.get(), data_.get());
    double worst = 0;
    for (int i = 0; i < data_->nefc; ++i)
        if (data_->efc_type[i] == mjCNSTR_EQUALITY && model_->eq_type[data_->efc_id[i]] == (connects ? mjEQ_CONNECT : mjEQ_JOINT))
            worst = std::max(worst, std::abs(data_->efc_pos[i]));
    return worst;
}

Eigen::VectorXd MujocoReference::calcAccelerations(const Eigen::VectorXd& qpos, const Eigen::VectorXd& qvel,
                                                   const Eigen::VectorXd& appliedForces) {
    if (qpos.size() != model_->nq || qvel.size() != model_->nv || appliedForces.size() != model_->nv)
        throw std::runtime_error("calcAccelerations: expected qpos of " + std::to_string(model_->nq) + " and qvel and forces of " +
                                 std::to_string(model_->nv));
    mj_resetData(model_.get(), data_.get());
    Eigen::Map<Eigen::VectorXd>(data_->qpos, model_->nq) = qpos;
    Eigen::Map<Eigen::VectorXd>(data_->qvel, model_->nv) = qvel;
    Eigen::Map<Eigen::VectorXd>(data_->qfrc_applied, model_->nv) = appliedForces;
    mj_forward(model_.get(), data_.get());
    return Eigen::Map<const Eigen::VectorXd>(data_->qacc, model_->nv);
}

Eigen::VectorXd MujocoReference::integrateQpos(const Eigen::VectorXd& qpos, const Eigen::VectorXd& qvel,
                                               double dt) const {
    Eigen::VectorXd moved = qpos;
    mj_integratePos(model_.get(), moved.data(), qvel.data(), dt);
    return moved;
}

Eigen::Vector3d MujocoReference::getBodyPosition(const std::string& body) const {
    return Eigen::Map<const Eigen::Vector3d>(data_->xpos + 3 * findId(mjOBJ_BODY, body));
}

Eigen::Matrix3d MujocoReference::getBodyRotation(const std::string& body) const {
    // xmat is row-major.
    return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(data_->xmat + 9 * findId(mjOBJ_BODY, body));
}

double MujocoReference::getTendonLength(const std::string& tendon) const {
    return data_->ten_length[findId(mjOBJ_TENDON, tendon)];
}

Eigen::VectorXd MujocoReference::getTendonJacobian(const std::string& tendon) const {
    return Eigen::Map<const Eigen::VectorXd>(data_->ten_J + model_->nv * findId(mjOBJ_TENDON, tendon), model_->nv);
}

}  // namespace sinew::test
