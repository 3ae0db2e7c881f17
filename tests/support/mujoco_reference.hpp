#pragma once
// libmujoco (Debian's 2.2.2) as the independent reference for sinew's MJCF importer: it loads an MJCF model
// and gives MuJoCo's own body positions, spatial-tendon lengths and tendon Jacobians at a chosen qpos.
//
// MuJoCo 2.2.2 cannot read the big published models as they stand, so the file is first prepared in a
// temporary folder (prepareMjcfForMujoco): every <include> inlined by newer MuJoCo's path rule, the assets
// that need absent files (meshes, textures) and the geoms using them removed, and floors on masses a removed
// mesh leaves at zero. No attribute newer than 2.2.2 needs dropping: 2.2.2 refuses unknown attributes, and
// MS-Human-700, myoarm and myobody load. docs/validation.md ("MJCF import against libmujoco") says why each
// change leaves the kinematics alone.
#include <Eigen/Core>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <vector>

struct mjModel_;
struct mjData_;

namespace sinew::test {

// The MJCF file as MuJoCo 2.2.2 reads it, and what was changed to get there.
struct PreparedMjcf {
    std::filesystem::path file;        // the flattened, stripped copy
    std::vector<std::string> changes;  // one line per kind of change, with its count ("removed <mesh>: 189")
};

// Writes the prepared copy of `mjcfPath` into `folder` (created if needed). Throws std::runtime_error naming
// the file when an include cannot be found or read.
PreparedMjcf prepareMjcfForMujoco(const std::filesystem::path& mjcfPath, const std::filesystem::path& folder);

enum class MujocoJointType { Free, Ball, Slide, Hinge };  // mjtJoint's order

// One MuJoCo joint as the comparison needs it.
struct MujocoJoint {
    std::string name;
    MujocoJointType type = MujocoJointType::Hinge;
    int qposAddress = 0;       // first entry in qpos (7 free, 4 ball, 1 hinge/slide)
    int dofAddress = 0;        // first entry in qvel and the Jacobian's columns (6, 3, 1)
    std::string body;          // name of the body it moves
    bool limited = false;
    double rangeMin = 0, rangeMax = 0;  // rad or m (hinge, slide); ball: rangeMax is the largest angle
};

class MujocoReference {
public:
    // Prepares `mjcfPath` (into a fresh temporary folder, removed again by the destructor) and loads it with
    // mj_loadXML. Throws std::runtime_error with MuJoCo's error text when it refuses the file.
    explicit MujocoReference(const std::filesystem::path& mjcfPath);
    ~MujocoReference();
    MujocoReference(const MujocoReference&) = delete;
    MujocoReference& operator=(const MujocoReference&) = delete;

    const PreparedMjcf& getPreparation() const { return prepared_; }
    int getNumBodies() const;  // world included, as MuJoCo counts
    int getNumDofs() const;
    int getNumTendons() const;
    int getNumActuators() const;
    Eigen::VectorXd getQpos0() const;  // the model's reference pose (nq): hinge and slide refs, free bodies' poses

    std::vector<std::string> getBodyNames() const;    // the named bodies (not the world), in MuJoCo's order
    std::vector<std::string> getTendonNames() const;  // every tendon, in MuJoCo's order
    const std::vector<MujocoJoint>& getJoints() const { return joints_; }
    const MujocoJoint& getJoint(const std::string& name) const;  // throws when there is none
    bool isWrapping(const std::string& tendon) const;  // whether it passes over a sphere or cylinder geom
    // How many joint equality constraints (q1 = polynomial of q2, or q1 constant) the model has.
    int getNumJointCouplings() const;

    // A qpos within the joint ranges: hinges and slides uniform in their range (limited or not, [-1, 1] when
    // the range is empty), balls a random rotation within their cone, free joints a random rotation and a
    // position within 0.5 m of qpos0 on each axis; then the joint equality constraints' dependent joints set
    // from their polynomials, so that the pose is one the model can take.
    Eigen::VectorXd generateRandomQpos(std::mt19937& rng) const;

    // mj_kinematics, mj_comPos and mj_tendon at qpos (nq); the getters below read their results.
    void calcKinematics(const Eigen::VectorXd& qpos);
    // The largest |residual| of MuJoCo's joint equality constraints at qpos (mj_fwdPosition's efc_pos).
    double calcJointCouplingViolation(const Eigen::VectorXd& qpos) { return calcEqualityViolation(qpos, false); }
    // The same for its connect equalities (ball-joint loops), m.
    double calcConnectViolation(const Eigen::VectorXd& qpos) { return calcEqualityViolation(qpos, true); }
    // MuJoCo's forward dynamics (mj_forward): qacc (nv) at qpos, qvel, with qfrc_applied as the only input.
    Eigen::VectorXd calcAccelerations(const Eigen::VectorXd& qpos, const Eigen::VectorXd& qvel,
                                      const Eigen::VectorXd& appliedForces);
    // qpos moved along qvel (nv) for a time dt, quaternions on their manifold (mj_integratePos).
    Eigen::VectorXd integrateQpos(const Eigen::VectorXd& qpos, const Eigen::VectorXd& qvel, double dt) const;
    Eigen::Vector3d getBodyPosition(const std::string& body) const;  // xpos, m, world frame
    Eigen::Matrix3d getBodyRotation(const std::string& body) const;  // xmat
    double getTendonLength(const std::string& tendon) const;         // ten_length, m
    int countActiveWraps(const std::string& tendon) const;  // geoms the path touches now (tangent point pairs)
    Eigen::VectorXd getTendonJacobian(const std::string& tendon) const;  // ten_J row (nv): d length / d qvel

private:
    double calcEqualityViolation(const Eigen::VectorXd& qpos, bool connects);
    int findId(int type, const std::string& name) const;  // mjtObj type; throws when there is none
    std::string getName(int type, int id) const;          // "" for an unnamed object

    std::filesystem::path folder_;
    PreparedMjcf prepared_;
    std::unique_ptr<mjModel_, void (*)(mjModel_*)> model_;
    std::unique_ptr<mjData_, void (*)(mjData_*)> data_;
    std::vector<MujocoJoint> joints_;
};

}  // namespace sinew::test
