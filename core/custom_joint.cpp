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
    H_FM.setZero(6, joint.nu);
    for (int k = 0; k < 6; ++k) {
        const TransformAxis& axis = joint.transformAxes[static_cast<std::size_t>(k)];
        if (k >= 3) p_FM += d.theta[k] * axis.axis;
        if (axis.coordinate == kNoCoordinate) continue;
        if (k < 3) H_FM.col(axis.coordinate).head<3>() += d.slope[k] * W.col(k);
        else H_FM.col(axis.coordinate).tail<3>() += d.slope[k] * axis.axis;
    }
}

// Hdot's column c: each axis k that coordinate c drives contributes f_k'' u_c W_k + f_k' Wdot_k (rotations)
// or f_k'' u_c a_k (translations), with the column rates of W = [a_0, R_1 a_1, R_1 R_2 a_2]:
// Wdot_0 = 0, Wdot_1 = (a_0 thetadot_0) x W_1, Wdot_2 = (a_0 thetadot_0 + W_1 thetadot_1) x W_2.
void calcCustomJointHDot(const Joint& joint, const double* q, const double* u, JointMotion& HDot_FM) {
    const AxisDisplacements d = calcAxisDisplacements(joint, q, 2);
    const Eigen::Matrix3d W = calcRotationAxes(joint, d.theta, nullptr);
    double thetaDot[3] = {};
    for (int k = 0; k < 3; ++k) {
        const int c = joint.transformAxes[static_cast<std::size_t>(k)].coordinate;
        if (c != kNoCoordinate) thetaDot[k] = d.slope[k] * u[c];
    }
    const Eigen::Vector3d w1 = thetaDot[0] * W.col(0);  // angular velocity of the frame after rotation 1
    const Eigen::Vector3d w2 = w1 + thetaDot[1] * W.col(1);
    const Eigen::Vector3d WDot[3] = {Eigen::Vector3d::Zero(), w1.cross(W.col(1)), w2.cross(W.col(2))};
    HDot_FM.setZero(6, joint.nu);
    for (int k = 0; k < 6; ++k) {
        const TransformAxis& axis = joint.transformAxes[static_cast<std::size_t>(k)];
        const int c = axis.coordinate;
        if (c == kNoCoordinate) continue;
        if (k < 3) HDot_FM.col(c).head<3>() += d.curvature[k] * u[c] * W.col(k) + d.slope[k] * WDot[k];
        else HDot_FM.col(c).tail<3>() += d.curvature[k] * u[c] * axis.axis;
    }
}

SpatialVector calcCustomJointBias(const Joint& joint, const double* q, const double* u) {
    JointMotion HDot_FM;
    calcCustomJointHDot(joint, q, u, HDot_FM);
    return HDot_FM * Eigen::Map<const Eigen::VectorXd>(u, joint.nu);
}

}  // namespace sinew
