// Contact detection over a motion (tools/contact_detection.hpp) on a synthetic one: the standing model keeps
// its left foot planted and swings its right leg out; the detected frames are checked against the sole
// vertices' heights and speeds worked out by hand from the hip angle.
#include <gtest/gtest.h>

#include <cmath>

#include "sinew/core/error.hpp"
#include "sinew/tools/contact_detection.hpp"
#include "support/standing_model.hpp"

namespace sinew {
namespace {

struct Swing {
    Eigen::MatrixXd q, u;
    Eigen::VectorXd theta, rate;  // the right hip's abduction angle (rad, about x) and its rate
};

// Still for 0.3 s, then the right hip abducts smoothly to 0.3 rad over 0.7 s; 101 frames.
Swing makeSwing(const Model& model) {
    const int frames = 101;
    Swing swing{Eigen::MatrixXd(frames, model.getNumQ()), Eigen::MatrixXd::Zero(frames, model.getNumU()),
                Eigen::VectorXd(frames), Eigen::VectorXd(frames)};
    const Joint& hip = model.getJoint(model.findLinkIndex("leg_r"));
    for (int i = 0; i < frames; ++i) {
        const double t = 0.01 * i, s = std::fmax(0.0, (t - 0.3) / 0.7);
        swing.theta[i] = t < 0.3 ? 0 : 0.15 * (1 - std::cos(M_PI * s));
        swing.rate[i] = t < 0.3 ? 0 : 0.15 * M_PI / 0.7 * std::sin(M_PI * s);
        swing.q.row(i) = model.getDefaultQ().transpose();
        swing.q(i, hip.qStart) = std::cos(swing.theta[i] / 2);
        swing.q(i, hip.qStart + 1) = std::sin(swing.theta[i] / 2);
        swing.u(i, hip.uStart) = swing.rate[i];
    }
    return swing;
}

TEST(ContactDetection, PlantedFootAlwaysAndSwingingFootUntilItRisesOrMoves) {
    const Model model = test::makeStandingModel();
    const Swing swing = makeSwing(model);
    ContactDetectionOptions options;
    options.heightThreshold = 0.01;
    options.speedThreshold = 0.2;
    const ContactDetection detection = detectContacts(model, swing.q, swing.u, options);

    // The right sole's vertex (x, y, -0.9) under the hip at height 0.9, turned by theta about x: height
    // 0.9 + y sin(theta) - 0.9 cos(theta), speed |rate| sqrt(y^2 + 0.81). The left sole stays at 0.
    const double ys[] = {-0.04, -0.04, 0.04, 0.04};
    // The floor: the lowest height of a vertex slower than the speed threshold (the left sole's 0 included).
    double floor = 0;
    for (Eigen::Index i = 0; i < swing.theta.size(); ++i)
        for (const double y : ys)
            if (std::fabs(swing.rate[i]) * std::sqrt(y * y + 0.81) <= options.speedThreshold)
                floor = std::fmin(floor, 0.9 + y * std::sin(swing.theta[i]) - 0.9 * std::cos(swing.theta[i]));
    EXPECT_NEAR(detection.floorHeight, floor, 1e-12);
    int rightFrames = 0;
    for (Eigen::Index i = 0; i < swing.theta.size(); ++i) {
        bool touching = false;
        double lowest = 1e9;
        for (const double y : ys) {
            const double height = 0.9 + y * std::sin(swing.theta[i]) - 0.9 * std::cos(swing.theta[i]) - floor;
            const double speed = std::fabs(swing.rate[i]) * std::sqrt(y * y + 0.81);
            lowest = std::fmin(lowest, height);
            touching |= height <= options.heightThreshold && speed <= options.speedThreshold;
        }
        const std::vector<char>& inContact = detection.inContact[static_cast<std::size_t>(i)];
        EXPECT_EQ(inContact[0] != 0, touching) << "frame " << i;
        EXPECT_TRUE(inContact[1]) << "frame " << i;
        EXPECT_NEAR(detection.lowestHeight(i, 0), lowest, 1e-12);
        EXPECT_NEAR(detection.lowestHeight(i, 1), -floor, 1e-12);
        rightFrames += touching;
    }
    // The motion exercises both sides of the rule: the still part and the swing's start touch, its end does not.
    EXPECT_GT(rightFrames, 30);
    EXPECT_LT(rightFrames, 90);
}

TEST(ContactDetection, AGivenFloorIsUsed) {
    const Model model = test::makeStandingModel();
    const Swing swing = makeSwing(model);
    ContactDetectionOptions options;
    options.floorHeight = -0.5;  // far below: nothing is low enough
    const ContactDetection detection = detectContacts(model, swing.q, swing.u, options);
    EXPECT_EQ(detection.floorHeight, -0.5);
    for (const std::vector<char>& frame : detection.inContact) EXPECT_FALSE(frame[0] || frame[1]);
}

TEST(ContactDetection, BadInputsAreRefused) {
    const Model model = test::makeStandingModel();
    const Swing swing = makeSwing(model);
    EXPECT_THROW(detectContacts(model, swing.q.leftCols(3), swing.u), Error);
    ContactDetectionOptions options;
    options.speedThreshold = -1;
    EXPECT_THROW(detectContacts(model, swing.q, swing.u, options), Error);
}

}  // namespace
}  // namespace sinew
