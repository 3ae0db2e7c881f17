// The MJCF importer on small models written here, each compared with libmujoco 2.2.2 loading the same file
// (mj_loadXML): body masses, centres of mass and inertias as MuJoCo's compiler sets them, body frames
// after mj_kinematics at random qpos copied into sinew's q by joint name, the values MuJoCo computes at
// qpos0 (acc0, tendon spring lengths, connect anchors) and its joint-equality residuals. Then one refusal
// per kind of bad input, and the published models (../shared/data) imported with their census against
// MuJoCo's counts on a mesh-stripped copy. The big models' poses and tendon lengths are compared in
// test_mjcf_vs_mujoco.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "sinew/core/census.hpp"
#include "sinew/core/coordinate_coupler.hpp"
#include "sinew/core/data.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_path.hpp"
#include "sinew/io/mjcf_model.hpp"
#include "sinew/io/model_file.hpp"
#include "sinew/io/model_loading.hpp"
#include "support/error_assertions.hpp"

#ifdef SINEW_HAVE_MUJOCO
#include <mujoco/mujoco.h>

#include "support/mujoco_reference.hpp"
#endif

namespace sinew {
namespace {

namespace fs = std::filesystem;

// A folder private to the running test (ctest runs the tests of this file in parallel).
fs::path getTestFolder() {
    const fs::path folder = fs::path(::testing::TempDir()) / "sinew_mjcf_model" /
                            ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::create_directories(folder);
    return folder;
}

fs::path writeFile(const fs::path& path, const std::string& text) {
    fs::create_directories(path.parent_path());
    std::ofstream(path) << text;
    return path;
}

fs::path writeModel(const std::string& text) { return writeFile(getTestFolder() / "model.xml", text); }

bool contains(const std::vector<std::string>& lines, const std::string& part) {
    for (const std::string& line : lines)
        if (line.find(part) != std::string::npos) return true;
    return false;
}

#ifdef SINEW_HAVE_MUJOCO

// libmujoco's compiled model and its data.
class Mujoco {
public:
    explicit Mujoco(const fs::path& file) {
        char error[1000] = "";
        model_ = mj_loadXML(file.string().c_str(), nullptr, error, sizeof error);
        if (!model_) throw std::runtime_error("MuJoCo refuses " + file.string() + ": " + error);
        data_ = mj_makeData(model_);
    }
    ~Mujoco() {
        mj_deleteData(data_);
        mj_deleteModel(model_);
    }
    Mujoco(const Mujoco&) = delete;
    Mujoco& operator=(const Mujoco&) = delete;

    const mjModel& m() const { return *model_; }
    mjData& d() { return *data_; }
    std::string getName(mjtObj type, int id) const {
        const char* name = mj_id2name(model_, type, id);
        return name ? name : "";
    }

private:
    mjModel* model_ = nullptr;
    mjData* data_ = nullptr;
};

Eigen::Quaterniond toQuaternion(const double* q) { return Eigen::Quaterniond(q[0], q[1], q[2], q[3]); }

// sinew's q for MuJoCo's qpos, joint by joint (docs/mjcf-import.md, "Joints"): hinges and slides by name,
// free joints with the quaternion first, balls as the body's quat times their qpos.
Eigen::VectorXd toSinewQ(const Model& model, const Mujoco& mujoco, const double* qpos) {
    const mjModel& m = mujoco.m();
    Eigen::VectorXd q = model.getDefaultQ();
    for (int j = 0; j < m.njnt; ++j) {
        const double* value = qpos + m.jnt_qposadr[j];
        const std::string name = mujoco.getName(mjOBJ_JOINT, j);
        if (m.jnt_type[j] == mjJNT_HINGE || m.jnt_type[j] == mjJNT_SLIDE) {
            const int index = model.findCoordinateIndex(name);
            EXPECT_GE(index, 0) << name;
            if (index >= 0) q[index] = *value;
            continue;
        }
        const Joint& joint = model.getJoint(model.findLinkIndex(mujoco.getName(mjOBJ_BODY, m.jnt_bodyid[j])));
        if (m.jnt_type[j] == mjJNT_FREE) {
            q.segment<4>(joint.qStart) << value[3], value[4], value[5], value[6];
            q.segment<3>(joint.qStart + 4) << value[0], value[1], value[2];
        } else {
            const Eigen::Quaterniond ball = toQuaternion(m.body_quat + 4 * m.jnt_bodyid[j]) * toQuaternion(value);
            q.segment<4>(joint.qStart) << ball.w(), ball.x(), ball.y(), ball.z();
        }
    }
    return q;
}

// A qpos: hinges and slides anywhere in [-1, 1], balls and free joints at random rotations.
std::vector<double> makeRandomQpos(const mjModel& m, std::mt19937& rng) {
    std::uniform_real_distribution<double> uniform(-1, 1);
    std::vector<double> qpos(m.qpos0, m.qpos0 + m.nq);
    for (int j = 0; j < m.njnt; ++j) {
        double* value = qpos.data() + m.jnt_qposadr[j];
        const int type = m.jnt_type[j];
        if (type == mjJNT_HINGE || type == mjJNT_SLIDE) {
            *value = uniform(rng);
            continue;
        }
        if (type == mjJNT_FREE) {
            for (int i = 0; i < 3; ++i) value[i] += uniform(rng);
            value += 3;
        }
        std::normal_distribution<double> normal;
        const Eigen::Vector4d turn = Eigen::Vector4d(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
        std::copy(turn.data(), turn.data() + 4, value);
    }
    return qpos;
}

void expectSameMassProperties(const Model& model, const Mujoco& mujoco) {
    const mjModel& m = mujoco.m();
    // sinew adds a massless "world" link, welded to ground, when wires or loops are fixed on the world.
    const bool worldLink = model.findLinkIndex("world") != Model::kNotFound;
    ASSERT_EQ(model.getNumLinks(), m.nbody - 1 + (worldLink ? 1 : 0));
    for (int b = 1; b < m.nbody; ++b) {
        const std::string name = mujoco.getName(mjOBJ_BODY, b);
        const Link& link = model.getLink(model.findLinkIndex(name));
        const Eigen::Matrix3d R = toQuaternion(m.body_iquat + 4 * b).toRotationMatrix();
        const Eigen::Matrix3d inertia = R * Eigen::Vector3d(m.body_inertia + 3 * b).asDiagonal() * R.transpose();
        EXPECT_NEAR(link.mass, m.body_mass[b], 1e-9 * std::max(1.0, m.body_mass[b])) << name;
        EXPECT_LT((link.com_B - Eigen::Vector3d(m.body_ipos + 3 * b)).norm(), 1e-9) << name;
        EXPECT_LT((link.inertia_Bcom - inertia).norm(), 1e-9 * std::max(1.0, inertia.norm())) << name << "\n"
            << link.inertia_Bcom << "\nMuJoCo\n" << inertia;
    }
}

// Body frames after mj_kinematics against sinew's link frames at the same pose; returns the worst error.
double compareKinematics(const Model& model, Mujoco& mujoco, int poses, unsigned seed) {
    const mjModel& m = mujoco.m();
    std::mt19937 rng(seed);
    Data data(model);
    double worst = 0;
    for (int pose = 0; pose < poses; ++pose) {
        // Pose 0 holds sinew's own default q to MuJoCo's qpos0.
        const std::vector<double> qpos = pose == 0 ? std::vector<double>(m.qpos0, m.qpos0 + m.nq) : makeRandomQpos(m, rng);
        std::copy(qpos.begin(), qpos.end(), mujoco.d().qpos);
        mj_kinematics(&m, &mujoco.d());
        calcPositionKinematics(model, data, pose == 0 ? model.getDefaultQ() : toSinewQ(model, mujoco, qpos.data()));
        for (int b = 1; b < m.nbody; ++b) {
            const int link = model.findLinkIndex(mujoco.getName(mjOBJ_BODY, b));
            const Eigen::Vector3d xpos(mujoco.d().xpos + 3 * b);
            const Eigen::Matrix3d xmat = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(mujoco.d().xmat + 9 * b);
            worst = std::max({worst, (data.p_GB[link] - xpos).norm(), (data.R_GB[link] - xmat).norm()});
        }
    }
    return worst;
}

// Imports `file` and holds it to libmujoco: mass properties and body frames at qpos0 and random poses.
MjcfConversion expectSameAsMujoco(const fs::path& file) {
    MjcfConversion conversion = readMjcfModel(file.string());
    Mujoco mujoco(file);
    expectSameMassProperties(conversion.model, mujoco);
    const double worst = compareKinematics(conversion.model, mujoco, 20, 7);
    EXPECT_LT(worst, 1e-9);
    std::printf("%s: %d bodies, body frames at 20 poses within %.2g of MuJoCo's\n", file.filename().string().c_str(),
                mujoco.m().nbody - 1, worst);
    return conversion;
}

const char* kDefaultsModel = R"(<mujoco model="defaults">
  <compiler angle="radian"/>
  <default>
    <joint axis="0 1 0" range="-1 1" limited="true"/>
    <geom type="capsule" size="0.05 0.2 0.3" density="500"/>
    <default class="heavy">
      <geom density="2000"/>
      <default class="boxy">
        <geom type="box" size="0.1"/>
      </default>
    </default>
    <default class="sideways">
      <joint axis="1 0 0" range="-0.5 2"/>
    </default>
  </default>
  <worldbody>
    <body name="a" pos="0 0 1" childclass="heavy">
      <joint name="ja"/>
      <geom/>
      <geom class="boxy" pos="0.1 0 0.05"/>
      <body name="b" pos="0 0.1 -0.5">
        <joint name="jb" class="sideways"/>
        <geom size="0.03" pos="0 0 -0.2"/>
        <body name="c" pos="0.2 0 0" childclass="boxy">
          <joint name="jc" type="slide" axis="0 0 1"/>
          <geom size="0.05 0.02"/>
          <geom class="main" size="0.04 0.1" pos="0 0.1 0"/>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>)";

TEST(MjcfModelVsMujoco, DefaultClassesChildclassAndPartialSizes) {
    const MjcfConversion conversion = expectSameAsMujoco(writeModel(kDefaultsModel));
    Mujoco mujoco(getTestFolder() / "model.xml");
    for (int j = 0; j < mujoco.m().njnt; ++j) {
        const Coordinate& c = conversion.model.getCoordinates()[conversion.model.findCoordinateIndex(mujoco.getName(mjOBJ_JOINT, j))];
        EXPECT_EQ(c.rangeMin, mujoco.m().jnt_range[2 * j]) << c.name;
        EXPECT_EQ(c.rangeMax, mujoco.m().jnt_range[2 * j + 1]) << c.name;
    }
}

// One body per way of writing an orientation, each turned again by a geom written another way.
std::string makeOrientationModel(const std::string& compiler) {
    return R"(<mujoco>
  <compiler )" + compiler + R"(/>
  <worldbody>
    <body name="quat" pos="0.1 0.2 0.3" quat="0.9 0.1 -0.3 0.2">
      <joint name="q1" axis="1 1 0"/>
      <geom type="box" size="0.1 0.2 0.05" euler="10 20 30" mass="2"/>
      <body name="euler" pos="0 0.3 0" euler="30 -45 60">
        <joint name="e1" axis="0 0 1" pos="0.05 0 0"/>
        <geom type="ellipsoid" size="0.1 0.05 0.02" axisangle="1 2 3 40"/>
        <body name="axisangle" pos="0 0 0.2" axisangle="0 1 1 -70">
          <joint name="a1" type="slide" axis="1 0 1"/>
          <geom type="cylinder" size="0.03 0.1" xyaxes="0 1 0 -1 0.2 0.3"/>
          <body name="xyaxes" pos="0.2 0 0" xyaxes="0 0 1 1 0.5 0">
            <joint name="x1" axis="0 1 0"/>
            <geom type="box" size="0.02 0.04 0.06" zaxis="1 -1 2"/>
            <body name="zaxis" pos="0 0 -0.1" zaxis="-1 0.3 -0.2">
              <joint name="z1" axis="1 0 0"/>
              <geom type="box" size="0.03 0.02 0.01" quat="0.2 0.3 0.4 0.5"/>
              <geom type="sphere" size="0.02" pos="0.05 0 0"/>
            </body>
          </body>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>)";
}

TEST(MjcfModelVsMujoco, OrientationsInDegreesWithEachEulerSequence) {
    for (const char* sequence : {"xyz", "XYZ", "zyx", "ZXY", "yXz"}) {
        SCOPED_TRACE(sequence);
        expectSameAsMujoco(writeModel(makeOrientationModel(std::string("eulerseq=\"") + sequence + "\"")));
    }
}

TEST(MjcfModelVsMujoco, OrientationsInRadians) {
    expectSameAsMujoco(writeModel(makeOrientationModel("angle=\"radian\" eulerseq=\"zxz\"")));
}

// Every primitive shape, sizes from fromto, mass against density, geoms of a group outside
// inertiagrouprange, explicit inertials (diagonal and full), and the compiler's floors.
const char* kInertiaModel = R"(<mujoco>
  <compiler boundmass="0.05" boundinertia="0.002" inertiagrouprange="0 2"/>
  <worldbody>
    <body name="sphere" pos="0 0 1">
      <freejoint name="free"/>
      <geom type="sphere" size="0.1" pos="0.1 0 0"/>
      <body name="capsule" pos="0 0 -0.3">
        <joint name="h1" axis="0 1 0"/>
        <geom type="capsule" fromto="0 0 0 0.1 0.2 -0.3" size="0.04"/>
        <geom type="capsule" size="0.02 0.1" pos="0 0.1 0" euler="90 0 0" mass="0.7"/>
        <body name="cylinder_box" pos="0 0.2 -0.3">
          <joint name="h2" axis="1 0 0"/>
          <geom type="cylinder" fromto="0 0 0 0 0 -0.25" size="0.03"/>
          <geom type="box" fromto="0 0 0 0.2 0 0" size="0.02"/>
          <geom type="ellipsoid" fromto="0 0 0 0 0.1 0.1" size="0.03" density="300"/>
          <geom type="box" size="1 1 1" group="3"/>
          <body name="ellipsoid" pos="0.1 0 0">
            <joint name="h3" axis="0 0 1"/>
            <geom type="ellipsoid" size="0.05 0.02 0.08" quat="1 1 0 0"/>
          </body>
          <body name="tiny" pos="0 0.05 0">
            <joint name="h4" axis="0 0 1"/>
            <geom type="sphere" size="0.01"/>
          </body>
        </body>
        <body name="diagonal" pos="0 0 -0.2">
          <joint name="s1" type="slide" axis="0 0 1"/>
          <inertial pos="0.01 0.02 0.03" quat="0.5 0.5 0.5 0.5" mass="1.5" diaginertia="0.01 0.02 0.025"/>
          <geom type="sphere" size="0.5"/>
        </body>
        <body name="full" pos="0.1 0 0">
          <joint name="s2" type="slide" axis="0 1 0"/>
          <inertial pos="0 0 0.1" mass="2" fullinertia="0.03 0.04 0.05 0.001 -0.002 0.003"/>
        </body>
      </body>
    </body>
    <body name="welded" pos="0.5 0 0" euler="0 0 45">
      <body name="welded_without_geoms" pos="0.1 0.2 0.3"/>
    </body>
  </worldbody>
</mujoco>)";

TEST(MjcfModelVsMujoco, InertiaFromGeomsAndInertials) { expectSameAsMujoco(writeModel(kInertiaModel)); }

TEST(MjcfModelVsMujoco, InertiaFromGeomsOverridesInertialsWhenTrue) {
    std::string text = kInertiaModel;
    text.replace(text.find("<compiler "), 10, "<compiler inertiafromgeom=\"true\" settotalmass=\"30\" ");
    expectSameAsMujoco(writeModel(text));
}

const char* kJointsModel = R"(<mujoco>
  <worldbody>
    <body name="pelvis" pos="0 0 1" quat="0.707107 0.707107 0 0">
      <joint name="tx" type="slide" axis="1 0 0" ref="0.1"/>
      <joint name="ty" type="slide" axis="0 1 1" ref="-0.2" limited="true" range="-0.5 0.5"/>
      <joint name="rz" axis="0 0 1" pos="0.01 0.02 0.03" ref="30"/>
      <joint name="rx" axis="1 0 0" pos="0.01 0.02 0.03" ref="-10" limited="true" range="-90 90"/>
      <joint name="ry" axis="0 1 0" pos="0.01 0.02 0.03"/>
      <geom type="sphere" size="0.1"/>
      <body name="thigh" pos="0 -0.1 0" euler="10 20 30">
        <joint name="hip" type="ball" pos="0 0.05 0"/>
        <geom type="capsule" fromto="0 0 0 0 -0.4 0" size="0.05"/>
        <body name="shank" pos="0 -0.4 0">
          <joint name="knee_slide" type="slide" axis="0 1 0" ref="0.01"/>
          <joint name="knee" axis="0 0 1" pos="0 0.01 0" ref="5"/>
          <joint name="knee_twist" axis="1 0.2 0" pos="0 0.01 0"/>
          <geom type="capsule" fromto="0 0 0 0 -0.4 0" size="0.04"/>
        </body>
      </body>
    </body>
    <body name="floating" pos="1 0 1" quat="0.9 0 0.3 0.1">
      <freejoint name="float"/>
      <geom type="box" size="0.1 0.2 0.3"/>
    </body>
  </worldbody>
</mujoco>)";

TEST(MjcfModelVsMujoco, SlidesThenHingesBallAndFreeJoints) {
    const MjcfConversion conversion = expectSameAsMujoco(writeModel(kJointsModel));
    const Model& model = conversion.model;
    EXPECT_EQ(model.getJoint(model.findLinkIndex("pelvis")).type, JointType::Custom);
    EXPECT_EQ(model.getJoint(model.findLinkIndex("thigh")).type, JointType::Ball);
    EXPECT_EQ(model.getJoint(model.findLinkIndex("floating")).type, JointType::Free);
    // The default pose is MuJoCo's qpos0 and the coordinate ranges its limits, in radians.
    Mujoco mujoco(getTestFolder() / "model.xml");
    const mjModel& m = mujoco.m();
    const Eigen::VectorXd q0 = toSinewQ(model, mujoco, m.qpos0);
    for (const char* name : {"tx", "ty", "rz", "rx", "ry", "knee_slide", "knee", "knee_twist"}) {
        const int j = mj_name2id(&m, mjOBJ_JOINT, name), index = model.findCoordinateIndex(name);
        EXPECT_NEAR(model.getDefaultQ()[index], q0[index], 1e-15) << name;
        const Coordinate& c = model.getCoordinates()[static_cast<std::size_t>(index)];
        EXPECT_EQ(std::isfinite(c.rangeMin), m.jnt_limited[j] == 1) << name;
        if (m.jnt_limited[j]) {
            EXPECT_NEAR(c.rangeMax, m.jnt_range[2 * j + 1], 1e-15) << name;
        }
    }
}

const char* kTendonModel = R"(<mujoco>
  <compiler angle="radian"/>
  <default>
    <default class="muscle"><muscle ctrllimited="true" ctrlrange="0 1"/></default>
  </default>
  <worldbody>
    <site name="origin" pos="0.02 0 1.2"/>
    <body name="upper" pos="0 0 1">
      <joint name="shoulder" axis="0 1 0" armature="0.01"/>
      <geom type="capsule" fromto="0 0 0 0 0 -0.3" size="0.04"/>
      <site name="s1" pos="0.05 0 -0.05"/>
      <site name="s1_again" pos="0.05 0 -0.05"/>
      <geom name="elbow_wrap" type="cylinder" fromto="0 -0.05 -0.3 0 0.05 -0.3" size="0.03"/>
      <body name="lower" pos="0 0 -0.3">
        <joint name="elbow" axis="0 1 0" limited="true" range="0 2.5" armature="0.02"/>
        <geom type="capsule" fromto="0 0 0 0 0 -0.3" size="0.03"/>
        <site name="side" pos="0.1 0 0.01"/>
        <site name="s2" pos="0.03 0 -0.1"/>
        <site name="s3" pos="-0.03 0 -0.2"/>
      </body>
    </body>
  </worldbody>
  <tendon>
    <spatial name="flexor"><site site="origin"/><site site="s1"/><site site="s2"/></spatial>
    <spatial name="spring" stiffness="200" damping="3"><site site="origin"/><site site="s3"/></spatial>
    <spatial name="wrapped" limited="true" range="0.1 0.9">
      <site site="s1"/><geom geom="elbow_wrap" sidesite="side"/><site site="s2"/><site site="s3"/>
    </spatial>
    <spatial name="merged"><site site="origin"/><site site="s1"/><site site="s1_again"/><site site="s3"/></spatial>
    <spatial name="branched"><site site="origin"/><site site="s1"/><pulley divisor="2"/><site site="s2"/><site site="s3"/></spatial>
    <fixed name="coupled"><joint joint="shoulder" coef="1"/></fixed>
  </tendon>
  <actuator>
    <motor name="motor" joint="elbow"/>
    <muscle name="flexor" class="muscle" tendon="flexor" lengthrange="0.3 0.6" scale="250"/>
    <general name="wrapped" class="muscle" tendon="wrapped" lengthrange="0.45 0.5" gainprm="0.7 1.1 300"/>
  </actuator>
</mujoco>)";

double getLawParameter(const Model& model, const std::string& wire, const std::string& parameter) {
    return model.getWire(model.findWireIndex(wire)).lawSpec.parameters.getScalar(parameter);
}

TEST(MjcfModelVsMujoco, TendonsMusclesAndTheirQpos0Values) {
    const fs::path file = writeModel(kTendonModel);
    const MjcfConversion conversion = expectSameAsMujoco(file);
    const Model& model = conversion.model;
    Mujoco mujoco(file);
    const mjModel& m = mujoco.m();
    // force = -1: MuJoCo's scale / acc0, acc0 from the mass matrix with armature and the tendon Jacobian.
    const int flexor = mj_name2id(&m, mjOBJ_ACTUATOR, "flexor");
    EXPECT_NEAR(getLawParameter(model, "flexor", "max_isometric_force"), 250 / m.actuator_acc0[flexor],
                1e-9 * 250 / m.actuator_acc0[flexor]);
    EXPECT_NEAR(getLawParameter(model, "spring", "rest_length"), m.tendon_lengthspring[mj_name2id(&m, mjOBJ_TENDON, "spring")], 1e-12);
    EXPECT_EQ(model.getWire(model.findWireIndex("spring")).kind, WireKind::Tendon);
    // MuJoCo's length map (closed form): L0 = (0.5 - 0.45) / (1.1 - 0.7), slack = 0.45 - 0.7 L0; the flexor's
    // map has a negative slack (0.3 - 0.75 * 1.0), so it keeps its optimum, 0.3 + 0.25 * 1.0.
    EXPECT_NEAR(getLawParameter(model, "wrapped", "optimal_fiber_length"), 0.125, 1e-15);
    EXPECT_NEAR(getLawParameter(model, "wrapped", "tendon_slack_length"), 0.3625, 1e-15);
    EXPECT_EQ(getLawParameter(model, "wrapped", "max_isometric_force"), 300);
    EXPECT_EQ(getLawParameter(model, "wrapped", "max_contraction_velocity"), 1.5);
    EXPECT_NEAR(getLawParameter(model, "flexor", "optimal_fiber_length"), 0.55, 1e-15);
    EXPECT_EQ(getLawParameter(model, "flexor", "tendon_slack_length"), 0);
    // The wrap: MuJoCo's method over the geom's compiled frame, between the sites around it, the side site
    // kept on its own body (not the geom's).
    const Wire& wrapped = model.getWire(model.findWireIndex("wrapped"));
    ASSERT_EQ(wrapped.wraps.size(), 1u);
    const WireWrap& wrap = wrapped.wraps[0];
    const WrapObject& cylinder = model.getWrapObjects()[static_cast<std::size_t>(wrap.object)];
    const int geom = mj_name2id(&m, mjOBJ_GEOM, "elbow_wrap");
    EXPECT_EQ(cylinder.name, "elbow_wrap");
    EXPECT_EQ(wrap.method, WrapMethod::MuJoCo);
    EXPECT_EQ(wrap.firstPoint, 0);
    EXPECT_EQ(wrap.lastPoint, 1);
    EXPECT_EQ(wrap.sideSiteLink, model.findLinkIndex("lower"));
    EXPECT_EQ(cylinder.link, model.findLinkIndex("upper"));
    EXPECT_LT((wrap.sideSite_B - Eigen::Vector3d(m.site_pos + 3 * mj_name2id(&m, mjOBJ_SITE, "side"))).norm(), 1e-15);
    EXPECT_FALSE(contains(conversion.notImported, "side site"));
    EXPECT_LT((cylinder.p_BW - Eigen::Vector3d(m.geom_pos + 3 * geom)).norm(), 1e-15);
    EXPECT_LT((cylinder.R_BW - toQuaternion(m.geom_quat + 4 * geom).toRotationMatrix()).norm(), 1e-12);
    EXPECT_EQ(cylinder.radius, m.geom_size[3 * geom]);
    // Coincident sites make one point; a pulley splits its tendon; the rest is listed.
    EXPECT_EQ(model.getWire(model.findWireIndex("merged")).numPoints, 3);
    EXPECT_NE(model.findWireIndex("branched/0"), Model::kNotFound);
    EXPECT_NE(model.findWireIndex("branched/1"), Model::kNotFound);
    for (const char* note : {"sites 's1' and 's1_again' coincide", "divided by the divisor", "fixed 'coupled'",
                             "motor 'motor'", "length limits [0.1, 0.9]", "negative tendon slack"})
        EXPECT_TRUE(contains(conversion.notImported, note)) << note;
}

// Side sites on the world body and on the next body than their geom's, and no wire point on the world.
const char* kSideSiteModel = R"(<mujoco>
  <worldbody>
    <site name="fixed_side" pos="0.2 0.01 0.9"/>
    <body name="upper" pos="0 0 1">
      <joint name="shoulder" axis="0 1 0"/>
      <geom type="capsule" fromto="0 0 0 0 0 -0.3" size="0.04"/>
      <geom name="elbow_ball" type="sphere" pos="0 0 -0.3" size="0.04"/>
      <site name="above" pos="0.05 0 -0.1"/>
      <body name="lower" pos="0 0 -0.3">
        <joint name="elbow" axis="0 1 0"/>
        <geom type="capsule" fromto="0 0 0 0 0 -0.3" size="0.03"/>
        <site name="below" pos="0.04 0 -0.15"/>
        <site name="turning_side" pos="-0.03 0.01 -0.12"/>
      </body>
    </body>
  </worldbody>
  <tendon>
    <spatial name="by_the_world"><site site="above"/><geom geom="elbow_ball" sidesite="fixed_side"/><site site="below"/></spatial>
    <spatial name="by_the_forearm"><site site="above"/><geom geom="elbow_ball" sidesite="turning_side"/><site site="below"/></spatial>
  </tendon>
</mujoco>)";

TEST(MjcfModelVsMujoco, SideSitesMoveWithTheirOwnBodies) {
    const fs::path file = writeModel(kSideSiteModel);
    const MjcfConversion conversion = expectSameAsMujoco(file);
    const Model& model = conversion.model;
    EXPECT_EQ(model.getWire(model.findWireIndex("by_the_world")).wraps[0].sideSiteLink, model.findLinkIndex("world"));
    EXPECT_EQ(model.getWire(model.findWireIndex("by_the_forearm")).wraps[0].sideSiteLink, model.findLinkIndex("lower"));
    // The tendons' lengths as MuJoCo computes them, the side sites moving with their bodies, at poses where
    // each tendon wraps and at others where it goes straight.
    Mujoco mujoco(file);
    const mjModel& m = mujoco.m();
    Data data(model);
    std::mt19937 rng(11);
    double worst = 0;
    std::vector<int> wrapped(static_cast<std::size_t>(m.ntendon), 0);
    for (int pose = 0; pose < 20; ++pose) {
        const std::vector<double> qpos = makeRandomQpos(m, rng);
        std::copy(qpos.begin(), qpos.end(), mujoco.d().qpos);
        mj_fwdPosition(&m, &mujoco.d());
        calcPositionKinematics(model, data, toSinewQ(model, mujoco, qpos.data()));
        calcWirePaths(model, data);
        for (int t = 0; t < m.ntendon; ++t) {
            const int w = model.findWireIndex(mujoco.getName(mjOBJ_TENDON, t));
            worst = std::max(worst, std::abs(data.wireLength[w] - mujoco.d().ten_length[t]));
            wrapped[static_cast<std::size_t>(t)] += data.wirePathSize[static_cast<std::size_t>(w)] > model.getWire(w).numPoints;
        }
    }
    std::printf("side sites on other bodies: worst |dL| %.2g m over 20 poses, wrapped at %d and %d of them\n", worst,
                wrapped[0], wrapped[1]);
    EXPECT_LT(worst, 1e-12);
    for (const int count : wrapped) {
        EXPECT_GE(count, 3);
        EXPECT_LE(count, 17);
    }
}

const char* kEqualityModel = R"(<mujoco>
  <worldbody>
    <body name="a" pos="0 0 1">
      <joint name="ha" axis="0 1 0" ref="20"/>
      <geom type="sphere" size="0.05"/>
      <body name="b" pos="0 0 -0.3">
        <joint name="sb" type="slide" axis="0 0 1" ref="0.02"/>
        <geom type="sphere" size="0.05"/>
      </body>
      <body name="c" pos="0.2 0 -0.3" euler="0 30 0">
        <joint name="hc" axis="1 0 0" ref="-15"/>
        <geom type="sphere" size="0.05"/>
      </body>
    </body>
  </worldbody>
  <equality>
    <joint name="slide_follows" joint1="sb" joint2="ha" polycoef="0.01 0.05 -0.02 0.003 0.001"/>
    <joint name="hinge_follows" joint1="hc" joint2="ha" polycoef="0 -0.5 0 0 0"/>
    <connect name="loop" body1="b" body2="c" anchor="0.1 0.05 -0.02"/>
    <weld name="weld" body1="b" body2="c"/>
    <connect name="off" body1="b" body2="c" anchor="0 0 0" active="false"/>
  </equality>
</mujoco>)";

TEST(MjcfModelVsMujoco, JointEqualitiesBecomeCouplersAndConnectsLoops) {
    const fs::path file = writeModel(kEqualityModel);
    const MjcfConversion conversion = readMjcfModel(file.string());
    const Model& model = conversion.model;
    ASSERT_EQ(model.getNumCouplers(), 2);
    Mujoco mujoco(file);
    const mjModel& m = mujoco.m();
    mjData& d = mujoco.d();
    // Couplers applied to random independent coordinates give poses where MuJoCo's equality residuals vanish.
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> uniform(-1.5, 1.5);
    for (int pose = 0; pose < 10; ++pose) {
        Eigen::VectorXd q = model.getDefaultQ();
        q[model.findCoordinateIndex("ha")] = uniform(rng);
        applyCoordinateCouplers(model, q);
        for (const char* name : {"ha", "sb", "hc"})
            d.qpos[m.jnt_qposadr[mj_name2id(&m, mjOBJ_JOINT, name)]] = q[model.findCoordinateIndex(name)];
        mj_forward(&m, &d);
        int rows = 0;
        for (int i = 0; i < d.nefc; ++i)
            if (d.efc_type[i] == mjCNSTR_EQUALITY && m.eq_type[d.efc_id[i]] == mjEQ_JOINT) {
                EXPECT_NEAR(d.efc_pos[i], 0, 1e-14) << mujoco.getName(mjOBJ_EQUALITY, d.efc_id[i]);
                ++rows;
            }
        EXPECT_EQ(rows, 2);
    }
    // The loop's point on body2 is where MuJoCo places the anchor at qpos0 (eq_data[3..5]).
    ASSERT_EQ(model.getNumLoops(), 1);
    const int loop = mj_name2id(&m, mjOBJ_EQUALITY, "loop");
    EXPECT_LT((model.getLoop(0).p_A - Eigen::Vector3d(0.1, 0.05, -0.02)).norm(), 1e-15);
    EXPECT_LT((model.getLoop(0).p_B - Eigen::Vector3d(m.eq_data + mjNEQDATA * loop + 3)).norm(), 1e-14);
    EXPECT_TRUE(contains(conversion.notImported, "weld 'weld'"));
    EXPECT_TRUE(contains(conversion.notImported, "connect 'off'"));
}

#else

TEST(MjcfModelVsMujoco, NeedsLibmujoco) {
    GTEST_SKIP() << "libmujoco (libmujoco-dev) is not installed: the comparisons with MuJoCo are not built";
}

#endif  // SINEW_HAVE_MUJOCO

TEST(MjcfModel, IncludesFollowBothPathRules) {
    const fs::path folder = getTestFolder();
    writeFile(folder / "parts" / "defaults.xml", R"(<mujocoinclude>
  <default><geom type="capsule" size="0.03 0.1"/></default>
</mujocoinclude>)");
    // arm.xml names hand.xml relative to itself (MuJoCo 3's rule), finger.xml relative to the main file.
    writeFile(folder / "parts" / "arm.xml", R"(<mujoco>
  <body name="arm" pos="0 0 -0.3">
    <joint name="j1" axis="1 0 0"/>
    <geom fromto="0 0 0 0 0 -0.3" size="0.04"/>
    <include file="hand.xml"/>
    <include file="parts/finger.xml"/>
  </body>
</mujoco>)");
    writeFile(folder / "parts" / "hand.xml", R"(<mujoco><body name="hand" pos="0 0 -0.3"><joint name="j2"/><geom/></body></mujoco>)");
    writeFile(folder / "parts" / "finger.xml", R"(<mujoco>
  <body name="finger" pos="0.05 0 -0.3"><joint name="j3" axis="0 1 0"/><geom size="0.01 0.02"/></body>
</mujoco>)");
    const fs::path main = writeFile(folder / "main.xml", R"(<mujoco model="arm">
  <include file="parts/defaults.xml"/>
  <worldbody>
    <body name="base" pos="0 0 1"><joint name="j0"/><geom size="0.1 0.2"/><include file="parts/arm.xml"/></body>
  </worldbody>
</mujoco>)");
    const fs::path flat = writeFile(folder / "flat.xml", R"(<mujoco model="arm">
  <default><geom type="capsule" size="0.03 0.1"/></default>
  <worldbody>
    <body name="base" pos="0 0 1"><joint name="j0"/><geom size="0.1 0.2"/>
      <body name="arm" pos="0 0 -0.3"><joint name="j1" axis="1 0 0"/><geom fromto="0 0 0 0 0 -0.3" size="0.04"/>
        <body name="hand" pos="0 0 -0.3"><joint name="j2"/><geom/></body>
        <body name="finger" pos="0.05 0 -0.3"><joint name="j3" axis="0 1 0"/><geom size="0.01 0.02"/></body>
      </body>
    </body>
  </worldbody>
</mujoco>)");
    // The included model is the flat one, which libmujoco 2.2.2 reads (it knows only the main-file rule).
    EXPECT_EQ(writeModelText(readMjcfModel(main.string()).model), writeModelText(readMjcfModel(flat.string()).model));
#ifdef SINEW_HAVE_MUJOCO
    expectSameAsMujoco(flat);
#endif
}


// The 1-based line of the first occurrence of `needle` in `text`.
int lineOf(const std::string& text, const std::string& needle) {
    const std::size_t at = text.find(needle);
    EXPECT_NE(at, std::string::npos) << needle;
    return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

// A small valid model with `insert` placed inside <mujoco>, and the refusal it must cause at the line of
// `needle`, naming `words`.
void expectRefusal(const std::string& insert, const std::string& needle, const std::vector<std::string>& words) {
    const std::string text = "<mujoco>\n  <worldbody>\n    <site name=\"anchor\"/>\n"
                             "    <body name=\"arm\" pos=\"0 0 1\">\n      <joint name=\"swing\"/>\n"
                             "      <geom name=\"bone\" type=\"sphere\" size=\"0.1\"/>\n      <site name=\"tip\"/>\n"
                             "    </body>\n  </worldbody>\n" + insert + "</mujoco>\n";
    const fs::path file = writeModel(text);
    EXPECT_TRUE(test::throwsErrorAt<ModelError>([&] { readMjcfModel(file.string()); },
                                                file.string() + ":" + std::to_string(lineOf(text, needle)), words, text));
}

TEST(MjcfModel, RefusesUnknownBodies) {
    expectRefusal("  <equality><connect body1=\"arm\" body2=\"hand\" anchor=\"0 0 0\"/></equality>\n", "<connect",
                  {"connect", "body2 'hand'", "no body"});
}

TEST(MjcfModel, RefusesUnknownSites) {
    expectRefusal("  <tendon><spatial name=\"t\">\n    <site site=\"anchor\"/>\n    <site site=\"toe\"/>\n  </spatial></tendon>\n",
                  "site=\"toe\"", {"site 'toe'", "no site"});
}

TEST(MjcfModel, RefusesUnknownGeoms) {
    expectRefusal("  <tendon><spatial name=\"t\">\n    <site site=\"anchor\"/>\n    <geom geom=\"knee\"/>\n"
                  "    <site site=\"tip\"/>\n  </spatial></tendon>\n",
                  "geom=\"knee\"", {"geom 'knee'", "no geom"});
}

TEST(MjcfModel, RefusesUnknownClasses) {
    expectRefusal("  <worldbody>\n    <geom name=\"floor\" class=\"ground\" type=\"plane\" size=\"1 1 1\"/>\n  </worldbody>\n",
                  "class=\"ground\"", {"geom 'floor'", "unknown default class 'ground'"});
}

TEST(MjcfModel, RefusesMissingIncludesAtTheIncludingFile) {
    expectRefusal("  <include file=\"parts/absent.xml\"/>\n", "<include", {"include", "parts/absent.xml", "main file"});
}

TEST(MjcfModel, RefusesNaN) {
    expectRefusal("  <worldbody>\n    <body name=\"b\" pos=\"0 nan 0\"/>\n  </worldbody>\n", "pos=\"0 nan",
                  {"body 'b'", "attribute 'pos'", "'nan' is not a finite number"});
}

TEST(MjcfModel, RefusesInfiniteAndMalformedNumbers) {
    expectRefusal("  <option gravity=\"0 0 -inf\"/>\n", "<option", {"option", "gravity", "finite"});
    expectRefusal("  <option gravity=\"0 0 -9.8.1\"/>\n", "<option", {"option", "'-9.8.1' is not a number"});
}

// pugixml parses any depth without recursion, but the readers recurse through the elements: a document
// deeper than XmlFile::kMaxElementDepth (500, tinyxml2's limit) is refused at its first element too deep.
TEST(MjcfModel, RefusesElementsNestedTooDeep) {
    std::string bodies;
    for (int i = 0; i < 20000; ++i) bodies += "<body>";
    for (int i = 0; i < 20000; ++i) bodies += "</body>";
    expectRefusal("  <worldbody>" + bodies + "</worldbody>\n", "<body><body>", {"<body>", "nested 501 elements deep", "500"});
}

TEST(MjcfModel, RefusesNegativeMass) {
    expectRefusal("  <worldbody>\n    <body name=\"b\">\n      <inertial pos=\"0 0 0\" mass=\"-1\" diaginertia=\"1 1 1\"/>\n"
                  "    </body>\n  </worldbody>\n", "<inertial", {"inertial", "mass", "negative"});
    expectRefusal("  <worldbody>\n    <geom name=\"g\" size=\"0.1\" mass=\"-2\"/>\n  </worldbody>\n", "name=\"g\"",
                  {"geom 'g'", "negative"});
}

TEST(MjcfModel, RefusesJointLayoutsSinewCannotExpress) {
    expectRefusal("  <worldbody>\n    <body name=\"b\">\n      <joint name=\"h\"/>\n      <joint name=\"s\" type=\"slide\"/>\n"
                  "      <geom size=\"0.1\"/>\n    </body>\n  </worldbody>\n",
                  "<body name=\"b\"", {"body 'b'", "slide 's'", "follows hinge 'h'"});
    expectRefusal("  <worldbody>\n    <body name=\"b\">\n      <joint name=\"h1\" pos=\"0 0 0\"/>\n"
                  "      <joint name=\"h2\" axis=\"1 0 0\" pos=\"0 0 0.1\"/>\n      <geom size=\"0.1\"/>\n    </body>\n"
                  "  </worldbody>\n", "<body name=\"b\"", {"body 'b'", "'h1' and 'h2'", "different anchors"});
}

TEST(MjcfModel, ListsWhatItDoesNotImport) {
    const std::string text = R"(<mujoco>
  <worldbody>
    <body name="arm"><joint name="swing" damping="2"/><geom type="sphere" size="0.1"/>
      <body name="hand" pos="0 0 -0.3"><joint name="wrist"/><geom type="sphere" size="0.05"/></body>
    </body>
  </worldbody>
  <equality><weld name="glue" body1="arm" body2="hand"/></equality>
  <sensor><jointpos name="angle" joint="swing"/></sensor>
  <keyframe><key name="start" qpos="0.1 0.2"/></keyframe>
</mujoco>)";
    const MjcfConversion conversion = readMjcfModel(writeModel(text).string());
    const std::string file = (getTestFolder() / "model.xml").string();
    for (const std::string& line : {"weld 'glue' (" + file + ":" + std::to_string(lineOf(text, "<weld")) + ")",
                                    "jointpos 'angle' (" + file + ":" + std::to_string(lineOf(text, "<jointpos")) + ")",
                                    "key 'start' (" + file + ":" + std::to_string(lineOf(text, "<key ")) + ")",
                                    "joint 'swing' (" + file + ":" + std::to_string(lineOf(text, "name=\"swing\"")) +
                                        "): damping 2"})
        EXPECT_TRUE(contains(conversion.notImported, line)) << line;
    EXPECT_EQ(conversion.model.getGravity(), Eigen::Vector3d(0, 0, -9.81));
}

TEST(MjcfModel, LoadModelChoosesTheReaderByContent) {
    // An MJCF file whatever its name, beside the sinew model it imports to.
    const fs::path mjcf = writeFile(getTestFolder() / "arm.yaml", "<?xml version=\"1.0\"?>\n<!-- an arm -->\n"
                                    "<mujoco model=\"arm\"><worldbody><body name=\"a\"><joint name=\"j\"/>"
                                    "<geom size=\"0.1\"/></body></worldbody><contact><exclude body1=\"a\" body2=\"world\"/></contact></mujoco>\n");
    EXPECT_EQ(detectModelFormat(mjcf.string()), ModelFormat::Mjcf);
    std::vector<std::string> notes;
    const Model model = loadModel(mjcf.string(), [&](const std::string& line) { notes.push_back(line); });
    EXPECT_TRUE(contains(notes, "not imported: exclude"));
    const fs::path yaml = getTestFolder() / "arm_sinew.xml";
    writeModelFile(model, yaml.string());
    EXPECT_EQ(detectModelFormat(yaml.string()), ModelFormat::SinewYaml);
    EXPECT_EQ(writeModelText(loadModel(yaml.string(), {})), writeModelText(model));
    const fs::path other = writeFile(getTestFolder() / "other.xml", "<robot name=\"r\"/>");
    EXPECT_TRUE(test::throwsErrorAt<ModelError>([&] { detectModelFormat(other.string()); }, other.string(),
                                                {"<robot>", "MJCF", "OpenSim"}, "<robot/>"));
}

// The published models (../shared/data, developer data): imported whole, their census against MuJoCo's
// own counts on the mesh-stripped copy libmujoco 2.2.2 reads.
const fs::path kData = fs::path(SINEW_SHARED_DIR) / "data";

void expectCensusLikeMujoco(const fs::path& file) {
    if (!fs::exists(file)) GTEST_SKIP() << file << " is absent (developer data in ../shared/data)";
    const MjcfConversion conversion = readMjcfModel(file.string());
    const Census census = calcCensus(conversion.model);
    // Written and read back unchanged.
    EXPECT_EQ(writeModelText(readModelText(writeModelText(conversion.model), "copy")), writeModelText(conversion.model));
    std::printf("%s: %d links, %d DOF, %d wires (%d muscles), %d couplers\n", file.filename().string().c_str(),
                census.links, census.dof, census.wires, census.muscles, conversion.model.getNumCouplers());
#ifdef SINEW_HAVE_MUJOCO
    const test::MujocoReference reference(file);
    const Mujoco mujoco(reference.getPreparation().file);
    const mjModel& m = mujoco.m();
    int spatial = 0, muscles = 0, couplings = 0, heldSlides = 0, uncoupled = 0;
    for (int t = 0; t < m.ntendon; ++t) spatial += m.tendon_num[t] > 0 && m.wrap_type[m.tendon_adr[t]] != mjWRAP_JOINT;
    for (int a = 0; a < m.nu; ++a) muscles += m.actuator_gaintype[a] == mjGAIN_MUSCLE && m.actuator_trntype[a] == mjTRN_TENDON;
    for (int e = 0; e < m.neq; ++e) couplings += m.eq_type[e] == mjEQ_JOINT && m.eq_obj2id[e] >= 0 && m.eq_active[e];
    for (const std::string& line : conversion.notImported) {
        heldSlides += line.find("stays at its ref") != std::string::npos;
        uncoupled += line.find("is not a coordinate in sinew") != std::string::npos;
    }
    EXPECT_EQ(census.links, m.nbody - 1 + (conversion.model.findLinkIndex("world") != Model::kNotFound ? 1 : 0));
    EXPECT_EQ(census.dof, m.nv - heldSlides);
    EXPECT_EQ(census.wires, spatial);
    EXPECT_EQ(census.muscles, muscles);
    EXPECT_EQ(conversion.model.getNumCouplers(), couplings - uncoupled);
    std::printf("  MuJoCo: %d bodies, nv %d, %d spatial tendons, %d muscles, %d joint couplings\n", m.nbody - 1, m.nv,
                spatial, muscles, couplings);
#else
    std::printf("  libmujoco is not installed: the census is not compared with MuJoCo's\n");
#endif
}

TEST(MjcfModel, ImportsMsHuman700) { expectCensusLikeMujoco(kData / "ms_human_700" / "MS-Human-700.xml"); }
TEST(MjcfModel, ImportsMyoArm) { expectCensusLikeMujoco(kData / "myo_sim" / "arm" / "myoarm.xml"); }
TEST(MjcfModel, ImportsMyoBody) { expectCensusLikeMujoco(kData / "myo_sim" / "body" / "myobody.xml"); }

}  // namespace
}  // namespace sinew
