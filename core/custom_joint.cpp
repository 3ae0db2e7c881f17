#include "sinew/core/custom_joint.hpp"

#include <Eigen/Geometry>

namespace sinew {
namespace {

// theta_k and its first (and, when `order` is 2, second) derivative with respect to the axis's
// coordinate; zero derivatives for an axis without one.
struct AxisDisplacements {
    double theta[6];
    double slope[6];
    double curvature[6];
};

AxisDisplacements calcAxisDisplacements(const Joint& joint, const double* q, int order) {
    AxisDisplacements d{};
    for (int k = 0; k < 6; ++k) {
        const TransformAxis& axis = joint.transformAxes[static_cast<std::size_t>(k)];
        const double x = axis.coordinate == kNoCoordinate ? 0.0 : q[axis.coordinate];
        d.theta[k] = axis.function.calcValue(x);
        if (axis.coordinate == kNoCoordinate) continue;
        d.slope[k] = axis.function.calcDerivative(x, 1);
        if (order == 2) d.curvature[k] = axis.function.calcDerivative(x, 2);
    }
    return d;
}

Eigen::Matrix3d rotationAbout(const Eigen::Vector3d& axis, double angle) {
    return Eigen::AngleAxisd(angle, axis).toRotationMatrix();
}

// The rotation axes in F after the rotations before them: W = [a_0, R_1 a_1, R_1 R_2 a_2], so that
// w_FM = W thetadot (the body-fixed sequence's angular velocity, in F). Also R_FM.
Eigen::Matrix3d calcRotationAxes(const Joint& joint, const double* theta, Eigen::Matrix3d* R_FM) {
    const Eigen::Vector3d& a0 = joint.transformAxes[0].axis;
    const Eigen::Vector3d& a1 = joint.transformAxes[1].axis;
    const Eigen::Vector3d& a2 = joint.transformAxes[2].axis;
    const Eigen::Matrix3d R1 = rotationAbout(a0, theta[0]);
    const Eigen::Matrix3d R12 = R1 * rotationAbout(a1, theta[1]);
    if (R_FM) *R_FM = R12 * rotationAbout(a2, theta[2]);
    Eigen::Matrix3d W;
    W << a0, R1 * a1, R12 * a2;
    return W;
}

}  // namespace

void calcCustomJointTransform(const Joint& joint, const double* q, Eigen::Matrix3d& R_FM, Eigen::Vector3d& p_FM,
                              JointMotion& H_FM) {
    const AxisDisplacements d = calcAxisDisplacements(joint, q, 1);
    const Eigen::Matrix3d W = calcRotationAxes(joint, d.theta, &R_FM);
    p_FM.setZero();
    H_FM.setZero();
    for (int k = 0; k < 6; ++k) {
        const TransformAxis& axis = joint.transformAxes[static_cast<std::size_t>(k)];
        if (k >= 3) p_FM += d.theta[k] * axis.axis;
        if (axis.coordinate == kNoCoordinate) continue;
        if (k < 3) H_FM.col(axis.coordinate).head<3>() += d.slope[k] * W.col(k);
        else H_FM.col(axis.coordinate).tail<3>() += d.slope[k] * axis.axis;
    }
}

// d/dt (W thetadot) = W thetaddot + Wdot thetadot with the column rates Wdot_1 = (a_0 thetadot_0) x W_1 and
// Wdot_2 = (a_0 thetadot_0 + W_1 thetadot_1) x W_2; thetaddot's part without udot is f'' u_c^2.
SpatialVector calcCustomJointBias(const Joint& joint, const double* q, const double* u) {
    const AxisDisplacements d = calcAxisDisplacements(joint, q, 2);
    const Eigen::Matrix3d W = calcRotationAxes(joint, d.theta, nullptr);
    double thetaDot[6] = {};
    SpatialVector bias = SpatialVector::Zero();
    for (int k = 0; k < 6; ++k) {
        const TransformAxis& axis = joint.transformAxes[static_cast<std::size_t>(k)];
        if (axis.coordinate == kNoCoordinate) continue;
        const double rate = u[axis.coordinate];
        thetaDot[k] = d.slope[k] * rate;
        const double thetaDDot = d.curvature[k] * rate * rate;
        if (k < 3) bias.head<3>() += thetaDDot * W.col(k);
        else bias.tail<3>() += thetaDDot * axis.axis;
    }
    const Eigen::Vector3d w1 = thetaDot[0] * W.col(0);  // angular velocity of the frame after rotation 1
    const Eigen::Vector3d w2 = w1 + thetaDot[1] * W.col(1);
    bias.head<3>() += w1.cross(W.col(1)) * thetaDot[1] + w2.cross(W.col(2)) * thetaDot[2];
    return bias;
}

}  // namespace sinew
