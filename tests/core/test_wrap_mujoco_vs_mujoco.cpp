// MuJoCo's wrapping in sinew against libmujoco 2.2.2 itself: a random leg (tests/support/mujoco_wrap_model.hpp:
// hinges, a sphere at the knee and a cylinder at the ankle, tendons over them without a side site, with one
// outside and one inside the geom, one with its side site on the next body, and one over both) written as MJCF and loaded with mj_loadXML, and built
// as sinew's model with ModelBuilder; at random poses MuJoCo's ten_length and ten_J rows against sinew's wire
// lengths and Jacobian.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <random>
#include <unistd.h>

#include "sinew/core/kinematics.hpp"
#include "sinew/core/wire_jacobian.hpp"
#include "sinew/core/wire_path.hpp"
#include "support/mujoco_reference.hpp"
#include "support/mujoco_wrap_model.hpp"

namespace sinew {
namespace {

namespace fs = std::filesystem;

// The leg's MJCF in a file of its own, removed again at the end.
class TemporaryMjcf {
public:
    TemporaryMjcf(const std::string& text, unsigned seed)
        : path_(fs::temp_directory_path() / ("sinew_mujoco_leg_" + std::to_string(::getpid()) + "_" + std::to_string(seed) + ".xml")) {
        std::ofstream(path_) << text;
    }
    ~TemporaryMjcf() { fs::remove(path_); }
    const fs::path& getPath() const { return path_; }

private:
    fs::path path_;
};

TEST(WrapMuJoCoVsMuJoCo, LengthsAndJacobianMatchLibmujoco) {
    double worstLength = 0, worstJacobian = 0;
    std::map<std::string, int> wrappedPoses, straightPoses;
    for (unsigned seed = 1; seed <= 3; ++seed) {
        std::mt19937 rng(seed);
        const test::MujocoLeg leg = test::generateMujocoLeg(rng);
        const Model model = test::buildMujocoLegModel(leg);
        const TemporaryMjcf file(test::writeMujocoLegMjcf(leg), seed);
        test::MujocoReference mujoco(file.getPath());
        ASSERT_EQ(mujoco.getNumTendons(), model.getNumWires());
        ASSERT_EQ(mujoco.getNumDofs(), model.getNumU());
        Data data(model);
        Eigen::MatrixXd J(model.getNumWires(), model.getNumU());
        std::uniform_real_distribution<double> angle(-1.5, 1.5);
        for (int pose = 0; pose < 25; ++pose) {
            // A hinge's qpos is sinew's coordinate of the same name; its dof the same u.
            Eigen::VectorXd q(model.getNumQ()), qpos = mujoco.getQpos0();
            std::vector<int> dofOfU(static_cast<std::size_t>(model.getNumU()));
            for (const test::MujocoJoint& joint : mujoco.getJoints()) {
                const int i = model.findCoordinateIndex(joint.name);
                ASSERT_GE(i, 0) << joint.name;
                q[i] = qpos[joint.qposAddress] = angle(rng);
                dofOfU[static_cast<std::size_t>(i)] = joint.dofAddress;
            }
            mujoco.calcKinematics(qpos);
            calcPositionKinematics(model, data, q);
            calcWirePaths(model, data);
            calcWireJacobian(model, data, J);
            for (int w = 0; w < model.getNumWires(); ++w) {
                const Wire& wire = model.getWire(w);
                const bool wrapped = data.wirePathSize[static_cast<std::size_t>(w)] > wire.numPoints;
                ++(wrapped ? wrappedPoses : straightPoses)[wire.name];
                worstLength = std::max(worstLength, std::abs(data.wireLength[w] - mujoco.getTendonLength(wire.name)));
                const Eigen::VectorXd row = mujoco.getTendonJacobian(wire.name);
                for (int i = 0; i < model.getNumU(); ++i)
                    worstJacobian = std::max(worstJacobian, std::abs(J(w, i) - row[dofOfU[static_cast<std::size_t>(i)]]));
            }
        }
    }
    std::cout << "sinew vs libmujoco 2.2.2: worst |length| " << worstLength << " m, worst |J| " << worstJacobian << " m/rad\n";
    EXPECT_LT(worstLength, 1e-9);
    EXPECT_LT(worstJacobian, 1e-9);
    // Every tendon wrapped at some of the 75 poses and went straight at others, so each rule was compared.
    for (const auto& [name, count] : wrappedPoses) {
        std::cout << "  " << name << ": wrapped at " << count << " poses, straight at " << straightPoses[name] << "\n";
        EXPECT_GE(count, 5) << name;
        EXPECT_GE(straightPoses[name], 5) << name;
    }
    EXPECT_EQ(wrappedPoses.size(), 8u);
}

}  // namespace
}  // namespace sinew
