#pragma once
// Which of the model's contacts (its feet, Model::getContacts) touch the ground at each frame of a motion
// without force plates (docs/tensions-from-motion.md, "Contact"). Heights are along "up", against gravity.
// A contact touches the ground at a frame when one of its sole vertices is both low (at most heightThreshold
// above the floor) and slow (its speed, from the frame's u, at most speedThreshold): a foot resting on the
// ground, whether flat, on its heel or on its toes.
#include <Eigen/Core>
#include <limits>
#include <vector>

#include "sinew/core/model.hpp"

namespace sinew {

struct ContactDetectionOptions {
    // The kick's inverse-kinematics fit (models/whole_body/kick_11_01.mot) leaves a standing foot up to 5 cm above
    // the floor (the fitted root's height drifts over the trial) and rolls a pushing-off toe at up to
    // 0.45 m/s: tighter thresholds miss most of its stance (docs/tensions-from-motion.md, "Which frames").
    double heightThreshold = 0.06;  // m above the floor
    double speedThreshold = 0.5;    // m/s
    // m along up. NaN: the lowest height a sole vertex reaches over the motion while slower than
    // speedThreshold (the lowest of all when none is), so that a motion whose floor is not at the origin
    // (motion capture, inverse kinematics' root offset) needs no setting.
    double floorHeight = std::numeric_limits<double>::quiet_NaN();
};

struct ContactDetection {
    double floorHeight = 0;                   // m along up: the one used
    std::vector<std::vector<char>> inContact;  // (frames x contacts) 1 where the contact touches the ground
    Eigen::MatrixXd lowestHeight;              // (frames x contacts) m above the floor, of the lowest vertex
    Eigen::MatrixXd lowestSpeed;               // (frames x contacts) m/s, of the slowest low vertex (or lowest)
};

// q (frames x nq) and u (frames x nu), one row per frame. Throws sinew::Error when their sizes do not fit the
// model, the model has no gravity or a threshold is negative.
ContactDetection detectContacts(const Model& model, const Eigen::MatrixXd& q, const Eigen::MatrixXd& u,
                                const ContactDetectionOptions& options = {});

}  // namespace sinew
