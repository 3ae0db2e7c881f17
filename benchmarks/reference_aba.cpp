#include "reference_aba.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <string>

#include "sinew/core/error.hpp"

namespace sinew_benchmarks {
namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
    Eigen::Matrix3d m;
    m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return m;
}

// Featherstone's cross products of a motion vector V = [w; v] with a motion vector and with a force vector.
Vector6 crossMotion(const Vector6& V, const Vector6& m) {
    Vector6 r;
    r << V.head<3>().cross(m.head<3>()), V.tail<3>().cross(m.head<3>()) + V.head<3>().cross(m.tail<3>());
    return r;
}

Vector6 crossForce(const Vector6& V, const Vector6& f) {
    Vector6 r;
    r << V.head<3>().cross(f.head<3>()) + V.tail<3>().cross(f.tail<3>()), V.head<3>().cross(f.tail<3>());
    return r;
}

}  // namespace

ReferenceAba::ReferenceAba(const sinew::Model& model) : gravity_(model.getGravity()) {
    for (int i = 0; i < model.getNumLinks(); ++i) {
        const sinew::Joint& joint = model.getJoint(i);
        const sinew::Link& link = model.getLink(i);
        const bool free = joint.type == sinew::JointType::Free;
        if (!(joint.type == sinew::JointType::Ball || (free && joint.parent == sinew::kGround)) || joint.parent >= i)
            throw sinew::Error("reference ABA: joint '" + joint.name + "' is not a ball joint (or a free root) after its parent");
        Body& b = bodies_.emplace_back();
        b.parent = joint.parent, b.free = free, b.qStart = joint.qStart, b.uStart = joint.uStart;
        b.mass = link.mass, b.com_B = link.com_B, b.inertia_B = link.inertia_Bcom;
        b.p_PF = joint.p_PF, b.R_PF = joint.R_PF, b.p_BM = joint.p_BM, b.R_BM = joint.R_BM;
    }
}

void ReferenceAba::calcAccelerations(const Eigen::VectorXd& q, const Eigen::VectorXd& u, const Eigen::VectorXd& tau,
                                     Eigen::VectorXd& udot) {
    // Free root: its translation's columns, inertia products and bias (one body, so kept here).
    Eigen::Matrix3d freeS = Eigen::Matrix3d::Zero();  // translation columns' lower block (the upper is zero)
    Eigen::Matrix<double, 6, 3> freeU = Eigen::Matrix<double, 6, 3>::Zero();
    Eigen::Vector3d velocityOfCentre = Eigen::Vector3d::Zero();

    // Base to tip: poses, the joints' motion subspaces about ground's origin, velocities, biases, inertias.
    for (Body& b : bodies_) {
        const Body* parent = b.parent >= 0 ? &bodies_[static_cast<std::size_t>(b.parent)] : nullptr;
        const Eigen::Matrix3d R_GP = parent ? parent->R_GB : Eigen::Matrix3d::Identity();
        const Eigen::Vector3d p_GP = parent ? parent->p_GB : Eigen::Vector3d::Zero();
        const Vector6 V_P = parent ? parent->V : Vector6::Zero();
        const Eigen::Quaterniond rotation =
            Eigen::Quaterniond(q[b.qStart], q[b.qStart + 1], q[b.qStart + 2], q[b.qStart + 3]).normalized();
        b.R_GF = R_GP * b.R_PF;
        const Eigen::Vector3d p_FM = b.free ? Eigen::Vector3d(q.segment<3>(b.qStart + 4)) : Eigen::Vector3d::Zero();
        const Eigen::Vector3d centre = p_GP + R_GP * b.p_PF + b.R_GF * p_FM;
        b.R_GB = b.R_GF * rotation.toRotationMatrix() * b.R_BM.transpose();
        b.p_GB = centre - b.R_GB * b.p_BM;
        b.S.topRows<3>() = b.R_GF;
        b.S.bottomRows<3>() = skew(centre) * b.R_GF;
        const Vector6 Su = b.S * u.segment<3>(b.uStart);
        if (b.free) {
            // S's rotation columns move with the centre: their rate times u is v_centre x w.
            freeS = b.R_GF;
            velocityOfCentre = b.R_GF * u.segment<3>(b.uStart + 3);
            b.V = Su;
            b.V.tail<3>() += velocityOfCentre;
            b.c << Eigen::Vector3d::Zero(), velocityOfCentre.cross(Su.head<3>());
        } else {
            b.V = V_P + Su;
            b.c = crossMotion(V_P, Su);
        }
        const Eigen::Vector3d h = b.p_GB + b.R_GB * b.com_B;
        const Eigen::Matrix3d hx = skew(h);
        b.IA.topLeftCorner<3, 3>() = b.R_GB * b.inertia_B * b.R_GB.transpose() - b.mass * hx * hx;
        b.IA.topRightCorner<3, 3>() = b.mass * hx;
        b.IA.bottomLeftCorner<3, 3>() = -b.mass * hx;
        b.IA.bottomRightCorner<3, 3>() = b.mass * Eigen::Matrix3d::Identity();
        b.pA = crossForce(b.V, b.IA * b.V);
    }

    // Tip to base: each body's articulated inertia and bias force, handed to its parent.
    Eigen::Matrix<double, 6, 6> freeDinv = Eigen::Matrix<double, 6, 6>::Zero();
    Vector6 freeResidual = Vector6::Zero();
    for (auto it = bodies_.rbegin(); it != bodies_.rend(); ++it) {
        Body& b = *it;
        if (b.free) {
            Eigen::Matrix<double, 6, 6> S6;
            S6 << b.S, (Eigen::Matrix<double, 6, 3>() << Eigen::Matrix3d::Zero(), freeS).finished();
            const Eigen::Matrix<double, 6, 6> U6 = b.IA * S6;
            freeDinv = (S6.transpose() * U6).ldlt().solve(Eigen::Matrix<double, 6, 6>::Identity());
            freeResidual = tau.segment<6>(b.uStart) - S6.transpose() * b.pA;
            b.U = U6.leftCols<3>();
            freeU = U6.rightCols<3>();
            continue;  // the root: no parent
        }
        b.U = b.IA * b.S;
        b.Dinv = (b.S.transpose() * b.U).inverse();
        b.residual = tau.segment<3>(b.uStart) - b.S.transpose() * b.pA;
        if (b.parent < 0) continue;
        Body& parent = bodies_[static_cast<std::size_t>(b.parent)];
        const Eigen::Matrix<double, 6, 3> UDinv = b.U * b.Dinv;
        const Matrix6 Ia = b.IA - UDinv * b.U.transpose();
        parent.IA += Ia;
        parent.pA += b.pA + Ia * b.c + UDinv * b.residual;
    }

    // Base to tip: accelerations, gravity as ground accelerating upwards.
    Vector6 a0;
    a0 << Eigen::Vector3d::Zero(), -gravity_;
    for (Body& b : bodies_) {
        const Vector6 aP = (b.parent >= 0 ? bodies_[static_cast<std::size_t>(b.parent)].a : a0) + b.c;
        if (b.free) {
            Eigen::Matrix<double, 6, 6> U6;
            U6 << b.U, freeU;
            const Vector6 ud = freeDinv * (freeResidual - U6.transpose() * aP);
            udot.segment<6>(b.uStart) = ud;
            b.a = aP + b.S * ud.head<3>();
            b.a.tail<3>() += freeS * ud.tail<3>();
            continue;
        }
        const Eigen::Vector3d ud = b.Dinv * (b.residual - b.U.transpose() * aP);
        udot.segment<3>(b.uStart) = ud;
        b.a = aP + b.S * ud;
    }
}

}  // namespace sinew_benchmarks
