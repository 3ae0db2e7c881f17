#include "sinew/core/forward_dynamics.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>

namespace sinew {
namespace {

// Every quantity of an assembly joint, and of the handles on it, is taken about the joint's own point (its
// centre; the loop point; the hung link's origin): spatial vectors in ground axes with that point as
// reference. Moments then stay small wherever the model is, which keeps digits on large models far from
// the ground origin (docs/closed-chain.md, "Reference points").

// A spatial force w about the joint centre with S^T w = tau: the joint's generalized forces as a force on
// the child.
SpatialVector calcJointForce(const Joint& joint, const Eigen::Matrix3d& R, const double* tau) {
    SpatialVector w = SpatialVector::Zero();
    switch (joint.type) {
        case JointType::Free:
            w.head<3>() = R * Eigen::Map<const Eigen::Vector3d>(tau);
            w.tail<3>() = R * Eigen::Map<const Eigen::Vector3d>(tau + 3);
            break;
        case JointType::Ball: w.head<3>() = R * Eigen::Map<const Eigen::Vector3d>(tau); break;
        case JointType::Pin: w.head<3>() = R.col(2) * tau[0]; break;
        case JointType::Weld: break;
    }
    return w;
}

// udot from the relative acceleration about the joint centre, a_beta - a_alpha - c = S udot, where S is
// [R; 0] (ball), [z; 0] (pin) or [[R, 0], [0, R]] (free).
void extractJointAcceleration(const Joint& joint, const Eigen::Matrix3d& R, const SpatialVector& relative,
                              double* udot) {
    switch (joint.type) {
        case JointType::Free:
            Eigen::Map<Eigen::Vector3d>{udot} = R.transpose() * relative.head<3>();
            Eigen::Map<Eigen::Vector3d>{udot + 3} = R.transpose() * relative.tail<3>();
            break;
        case JointType::Ball: Eigen::Map<Eigen::Vector3d>{udot} = R.transpose() * relative.head<3>(); break;
        case JointType::Pin: udot[0] = R.col(2).dot(relative.head<3>()); break;
        case JointType::Weld: break;
    }
}

// E = (T^T W T)^-1 for a tree joint. Never singular: of the two subassemblies it joins, at least one
// moves freely.
template <int K>
Eigen::Matrix<double, K, K> calcJointCompliance(const Eigen::Matrix<double, 6, K>& T, const Matrix6d& W) {
    const Eigen::Matrix<double, K, K> D = T.transpose() * W * T;
    if constexpr (K <= 4) return D.inverse();  // Eigen's closed form, well conditioned for an SPD D this small
    else return D.llt().solve(Eigen::Matrix<double, K, K>::Identity());
}

// E = (T^T W T)^+ for a closure with K constraint directions (a ball loop, 3; the hang weld, 6). D is
// singular when the closure repeats constraints the subassembly already has (a ball loop off the axis of a
// hinge...); its pseudo-inverse then gives the least-squares (minimum-norm) force and exact accelerations.
// Counts the redundant directions; `conditioning` gets the smallest kept eigenvalue over the largest.
template <int K>
Eigen::Matrix<double, K, K> calcClosureCompliance(const Eigen::Matrix<double, 6, K>& T, const Matrix6d& W,
                                                  int& redundant, double& conditioning) {
    using Square = Eigen::Matrix<double, K, K>;
    const Square D = T.transpose() * W * T;
    const Eigen::SelfAdjointEigenSolver<Square> eigen(D);
    const auto& values = eigen.eigenvalues();
    // Roundoff in the subassembly's Phi (differences of inverse inertias) leaves a redundant direction at
    // about 1e-15 of the largest eigenvalue; genuine directions of real models sit far above 1e-9.
    const double largest = values.cwiseAbs().maxCoeff();
    Square pseudoInverse = Square::Zero();
    redundant = 0;
    conditioning = 1;
    for (int i = 0; i < K; ++i) {
        if (values[i] > 1e-9 * largest) {
            pseudoInverse += eigen.eigenvectors().col(i) * eigen.eigenvectors().col(i).transpose() / values[i];
            conditioning = std::min(conditioning, values[i] / largest);
        } else {
            ++redundant;
        }
    }
    return pseudoInverse;
}

// Constraint-force bases T (T^T S = 0) about a joint's centre: a ball (or ball loop) transmits forces
// through its centre; a pin also moments about the two axes normal to it (R's x and y).
Eigen::Matrix<double, 6, 3> ballBasis() {
    Eigen::Matrix<double, 6, 3> T = Eigen::Matrix<double, 6, 3>::Zero();
    T.bottomRows<3>().setIdentity();
    return T;
}

Eigen::Matrix<double, 6, 5> pinBasis(const Eigen::Matrix3d& R) {
    Eigen::Matrix<double, 6, 5> T = Eigen::Matrix<double, 6, 5>::Zero();
    T.bottomLeftCorner<3, 3>().setIdentity();
    T.block<3, 1>(0, 3) = R.col(0);
    T.block<3, 1>(0, 4) = R.col(1);
    return T;
}

// Everything calcForwardDynamics' stages share.
struct Evaluation {
    const Model& model;
    const AssemblySchedule& schedule;
    const Data& data;
    const Eigen::VectorXd& tau;
    const std::vector<SpatialVector>& linkForces;
    ForwardDynamicsData& fd;

    // A body's velocity or acceleration (about its centre of mass) taken about point p; zero for ground.
    SpatialVector motionAt(const std::vector<SpatialVector>& ofBody, int body, const Eigen::Vector3d& p) const {
        if (body == kGroundBody) return SpatialVector::Zero();
        const std::size_t bb = static_cast<std::size_t>(body);
        return shiftMotion(ofBody[bb], p - fd.massCenter[bb]);
    }
    const Eigen::Vector3d& pointOfHandle(int handle) const { return fd.jointPoint[static_cast<std::size_t>(handle / 2)]; }

    // The point each assembly joint's quantities are taken about.
    void placeJoint(std::size_t j) const {
        const AssemblyJoint& aj = schedule.getJoints()[j];
        const std::size_t l = static_cast<std::size_t>(aj.index);
        switch (aj.kind) {
            case AssemblyJoint::Kind::Tree: fd.jointPoint[j] = data.p_GM[l]; break;
            case AssemblyJoint::Kind::Loop: {
                const Loop& loop = model.getLoop(aj.index);
                const std::size_t a = static_cast<std::size_t>(loop.linkA);
                fd.jointPoint[j] = data.p_GB[a] + data.R_GB[a] * loop.p_A;
                break;
            }
            case AssemblyJoint::Kind::Hang: fd.jointPoint[j] = data.p_GB[l]; break;
        }
    }

    // Inertia, velocity and bias force p = v x* I v - f_ext about the body's centre of mass c, where the
    // spatial inertia is diag(Ic, m 1); then the leaf's handle equations, Phi_hk = M(r_h - c) I^-1
    // M(r_k - c)^T and b_h = -M(r_h - c) I^-1 p (docs/closed-chain.md, "Leaves").
    void prepareBody(int body) const {
        const std::size_t bb = static_cast<std::size_t>(body);
        const std::vector<int>& links = schedule.getLinksOfBody(body);
        double mass = 0;
        Eigen::Vector3d c = Eigen::Vector3d::Zero();
        for (int link : links) {
            const std::size_t l = static_cast<std::size_t>(link);
            const Link& info = model.getLink(link);
            mass += info.mass;
            c += info.mass * (data.p_GB[l] + data.R_GB[l] * info.com_B);
        }
        c /= mass;
        Eigen::Matrix3d Ic = Eigen::Matrix3d::Zero();
        SpatialVector external = SpatialVector::Zero();
        external.tail<3>() = mass * model.getGravity();
        for (int link : links) {
            const std::size_t l = static_cast<std::size_t>(link);
            const Link& info = model.getLink(link);
            const Eigen::Vector3d d = data.p_GB[l] + data.R_GB[l] * info.com_B - c;
            Ic += data.R_GB[l] * info.inertia_Bcom * data.R_GB[l].transpose() +
                  info.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
            external += shiftForce(linkForces[l], c - data.p_GB[l]);
        }
        Matrix6d& Iinv = fd.inertiaInverse[bb];
        Iinv.setZero();
        Iinv.topLeftCorner<3, 3>() = Ic.inverse();
        Iinv.bottomRightCorner<3, 3>() = Eigen::Matrix3d::Identity() / mass;
        fd.massCenter[bb] = c;
        const std::size_t first = static_cast<std::size_t>(links.front());
        const Eigen::Vector3d& w = data.w_GB[first];
        SpatialVector v;
        v << w, data.v_GB[first] + w.cross(c - data.p_GB[first]);
        fd.velocity[bb] = v;
        SpatialVector momentum;
        momentum << Ic * w, mass * v.tail<3>();
        fd.bias[bb] = crossForce(v, momentum) - external;

        // With A = Ic^-1 and S_h = skew(r_h - c), M(d_h) I^-1 M(d_k)^T is
        // [[A, A S_k], [(A S_h)^T, S_h^T A S_k + 1/m]]: one 3x3 product per pair of handles.
        const std::vector<int>& handles = schedule.getHandles(body);
        const std::size_t h = handles.size();
        const Eigen::Matrix3d A = Iinv.topLeftCorner<3, 3>();
        const SpatialVector a0 = -Iinv * fd.bias[bb];
        for (std::size_t k = 0; k < h; ++k) {
            const Eigen::Vector3d dk = pointOfHandle(handles[k]) - c;
            const Eigen::Matrix3d Sk = skew(dk);
            const Eigen::Matrix3d ASk = A * Sk;
            for (std::size_t i = 0; i <= k; ++i) {
                const Eigen::Matrix3d Si = skew(pointOfHandle(handles[i]) - c);
                Matrix6d& block = fd.Phi[bb][i * h + k];
                block.topLeftCorner<3, 3>() = A;
                block.topRightCorner<3, 3>() = ASk;
                block.bottomLeftCorner<3, 3>() = (A * Si).transpose();
                block.bottomRightCorner<3, 3>() = Si.transpose() * ASk;
                block.bottomRightCorner<3, 3>().diagonal().array() += 1 / mass;
                if (i != k) fd.Phi[bb][k * h + i] = block.transpose();
            }
            fd.b[bb][k] = shiftMotion(a0, dk);
        }
    }

    // Relative motion S u = v_beta - v_alpha about the joint point and its bias c = dS/dt u = v_alpha x (S u),
    // plus, for a free joint, (R v_FM) x (R w_FM): its centre moves in the parent (docs/closed-chain.md,
    // "Joints").
    void prepareJoint(std::size_t j) const {
        const AssemblyJoint& aj = schedule.getJoints()[j];
        const Eigen::Vector3d& p = fd.jointPoint[j];
        const SpatialVector vAlpha = motionAt(fd.velocity, aj.alphaBody, p);
        const SpatialVector relative = motionAt(fd.velocity, aj.betaBody, p) - vAlpha;
        fd.jointBias[j] = crossMotion(vAlpha, relative);
        if (aj.kind == AssemblyJoint::Kind::Tree && model.getJoint(aj.index).type == JointType::Free)
            fd.jointBias[j].tail<3>() += relative.tail<3>().cross(relative.head<3>());
    }

    // Join (docs/closed-chain.md, "Join"): subassemblies A and B through joint J into C. Y = T E T^T has
    // rank K (the joint's constraint directions), so each block update Phi_ha Y Phi_ak is done as
    // (Phi_ha T) E (Phi_ka T)^T: for a ball joint T selects the force rows and the update costs half.
    void join(std::size_t o) const {
        const AssemblyJoint& aj = schedule.getJoints()[static_cast<std::size_t>(schedule.getOperations()[o].joint)];
        const Joint& joint = model.getJoint(aj.index);
        const Eigen::Matrix3d& R = data.R_GF[static_cast<std::size_t>(aj.index)];
        const SpatialVector force = calcJointForce(joint, R, tau.data() + joint.uStart);
        switch (joint.type) {
            case JointType::Ball: joinThrough<3>(o, ballBasis(), force); break;
            case JointType::Pin: joinThrough<5>(o, pinBasis(R), force); break;
            case JointType::Free: joinThrough<0>(o, Eigen::Matrix<double, 6, 0>(), force); break;
            case JointType::Weld: break;  // welded links share a body: never an assembly joint
        }
    }

    template <int K>
    void joinThrough(std::size_t o, const Eigen::Matrix<double, 6, K>& T, const SpatialVector& force) const {
        const AssemblyOperation& op = schedule.getOperations()[o];
        const std::vector<Matrix6d>& PA = fd.Phi[static_cast<std::size_t>(op.first)];
        const std::vector<Matrix6d>& PB = fd.Phi[static_cast<std::size_t>(op.second)];
        const std::vector<SpatialVector>& bA = fd.b[static_cast<std::size_t>(op.first)];
        const std::vector<SpatialVector>& bB = fd.b[static_cast<std::size_t>(op.second)];
        std::vector<Matrix6d>& C = fd.Phi[static_cast<std::size_t>(op.result)];
        std::vector<SpatialVector>& bC = fd.b[static_cast<std::size_t>(op.result)];
        const int hA = static_cast<int>(bA.size()), hB = static_cast<int>(bB.size()), hC = static_cast<int>(bC.size());
        const int ia = op.alphaPosition, ib = op.betaPosition;
        auto A = [&](int i, int k) -> const Matrix6d& { return PA[static_cast<std::size_t>(i * hA + k)]; };
        auto B = [&](int i, int k) -> const Matrix6d& { return PB[static_cast<std::size_t>(i * hB + k)]; };
        const Matrix6d W = A(ia, ia) + B(ib, ib);
        Eigen::Matrix<double, K, K> E;
        if constexpr (K > 0) E = calcJointCompliance<K>(T, W);
        setJointTerms<K>(o, T, E, W, force, bB[static_cast<std::size_t>(ib)] - bA[static_cast<std::size_t>(ia)]);
        const SpatialVector& g = fd.g[o];

        // U_h = Phi_h,joint T (6 x K) and U_h E, for every remaining handle of A and of B.
        std::vector<Matrix6d>& U = fd.scratchU[o];
        std::vector<Matrix6d>& UE = fd.scratchUE[o];
        for (int c = 0; c < hC; ++c) {
            const bool fromA = c < hA - 1;
            const int h = fromA ? (c < ia ? c : c + 1) : (c - (hA - 1) < ib ? c - (hA - 1) : c - (hA - 1) + 1);
            const Matrix6d& P = fromA ? A(h, ia) : B(h, ib);
            U[static_cast<std::size_t>(c)].leftCols<K>() = P * T;
            UE[static_cast<std::size_t>(c)].leftCols<K>() = U[static_cast<std::size_t>(c)].leftCols<K>() * E;
            bC[static_cast<std::size_t>(c)] = fromA ? SpatialVector(bA[static_cast<std::size_t>(h)] - P * g)
                                                    : SpatialVector(bB[static_cast<std::size_t>(h)] + P * g);
        }
        for (int c = 0; c < hC; ++c) {
            const bool cFromA = c < hA - 1;
            const int h = cFromA ? (c < ia ? c : c + 1) : (c - (hA - 1) < ib ? c - (hA - 1) : c - (hA - 1) + 1);
            for (int d = c; d < hC; ++d) {
                const bool dFromA = d < hA - 1;
                const int k = dFromA ? (d < ia ? d : d + 1) : (d - (hA - 1) < ib ? d - (hA - 1) : d - (hA - 1) + 1);
                const Matrix6d update = UE[static_cast<std::size_t>(c)].leftCols<K>() *
                                        U[static_cast<std::size_t>(d)].leftCols<K>().transpose();
                Matrix6d block;
                if (cFromA && dFromA) block = A(h, k) - update;
                else if (!cFromA && !dFromA) block = B(h, k) - update;
                else block = update;  // c in A, d in B (c < d keeps that order)
                C[static_cast<std::size_t>(c * hC + d)] = block;
                if (c != d) C[static_cast<std::size_t>(d * hC + c)] = block.transpose();
            }
        }
    }

    // Close (docs/closed-chain.md, "Close"): a loop (or the hang) whose two handles are both in A. With
    // Delta_h = Phi_h,beta - Phi_h,alpha, the update Delta_h Y Delta_k^T is done as (Delta_h T) E (Delta_k T)^T.
    void close(std::size_t o) const {
        const AssemblyJoint& aj = schedule.getJoints()[static_cast<std::size_t>(schedule.getOperations()[o].joint)];
        if (aj.kind == AssemblyJoint::Kind::Loop) closeThrough<3>(o, ballBasis());
        else closeThrough<6>(o, Matrix6d::Identity());
    }

    template <int K>
    void closeThrough(std::size_t o, const Eigen::Matrix<double, 6, K>& T) const {
        const AssemblyOperation& op = schedule.getOperations()[o];
        const std::vector<Matrix6d>& PA = fd.Phi[static_cast<std::size_t>(op.first)];
        const std::vector<SpatialVector>& bA = fd.b[static_cast<std::size_t>(op.first)];
        std::vector<Matrix6d>& C = fd.Phi[static_cast<std::size_t>(op.result)];
        std::vector<SpatialVector>& bC = fd.b[static_cast<std::size_t>(op.result)];
        const int hA = static_cast<int>(bA.size()), hC = static_cast<int>(bC.size());
        const int ia = op.alphaPosition, ib = op.betaPosition;
        auto A = [&](int i, int k) -> const Matrix6d& { return PA[static_cast<std::size_t>(i * hA + k)]; };
        // The c-th remaining handle of A.
        auto handleAt = [&](int c) { return c + (c >= std::min(ia, ib) ? 1 : 0) + (c + 1 >= std::max(ia, ib) ? 1 : 0); };
        const Matrix6d W = A(ia, ia) + A(ib, ib) - A(ia, ib) - A(ib, ia);
        const Eigen::Matrix<double, K, K> E =
            calcClosureCompliance<K>(T, W, fd.operationRedundancy[o], fd.operationConditioning[o]);
        setJointTerms<K>(o, T, E, W, SpatialVector::Zero(),
                         bA[static_cast<std::size_t>(ib)] - bA[static_cast<std::size_t>(ia)]);
        const SpatialVector& g = fd.g[o];
        std::vector<Matrix6d>& U = fd.scratchU[o];
        std::vector<Matrix6d>& UE = fd.scratchUE[o];
        for (int c = 0; c < hC; ++c) {
            const int h = handleAt(c);
            const Matrix6d delta = A(h, ib) - A(h, ia);
            U[static_cast<std::size_t>(c)].leftCols<K>() = delta * T;
            UE[static_cast<std::size_t>(c)].leftCols<K>() = U[static_cast<std::size_t>(c)].leftCols<K>() * E;
            bC[static_cast<std::size_t>(c)] = bA[static_cast<std::size_t>(h)] + delta * g;
        }
        for (int c = 0; c < hC; ++c) {
            for (int d = c; d < hC; ++d) {
                const Matrix6d block = A(handleAt(c), handleAt(d)) - UE[static_cast<std::size_t>(c)].leftCols<K>() *
                                                                         U[static_cast<std::size_t>(d)].leftCols<K>().transpose();
                C[static_cast<std::size_t>(c * hC + d)] = block;
                if (c != d) C[static_cast<std::size_t>(d * hC + c)] = block.transpose();
            }
        }
    }

    // Y = T E T^T and g = (1 - Y W) w - Y (b_beta - b_alpha - c) of operation o.
    template <int K>
    void setJointTerms(std::size_t o, const Eigen::Matrix<double, 6, K>& T, const Eigen::Matrix<double, K, K>& E,
                       const Matrix6d& W, const SpatialVector& force, const SpatialVector& bDifference) const {
        const SpatialVector& c = fd.jointBias[static_cast<std::size_t>(schedule.getOperations()[o].joint)];
        Matrix6d& Y = fd.Y[o];
        if constexpr (K == 0) Y.setZero();
        else Y = T * E * T.transpose();
        fd.g[o] = force - Y * (W * force + bDifference - c);
    }

    // The force through the operation's joint, from the forces on its result's handles.
    void disassemble(std::size_t o) const {
        const AssemblyOperation& op = schedule.getOperations()[o];
        const std::vector<int>& handlesA = schedule.getHandles(op.first);
        const std::vector<Matrix6d>& PA = fd.Phi[static_cast<std::size_t>(op.first)];
        const int hA = static_cast<int>(handlesA.size());
        const int ia = op.alphaPosition, ib = op.betaPosition;
        auto forceOn = [&](const std::vector<int>& handles, int k) -> const SpatialVector& {
            return fd.handleForce[static_cast<std::size_t>(handles[static_cast<std::size_t>(k)])];
        };
        SpatialVector sum = SpatialVector::Zero();
        if (!op.isClose) {
            const std::vector<int>& handlesB = schedule.getHandles(op.second);
            const std::vector<Matrix6d>& PB = fd.Phi[static_cast<std::size_t>(op.second)];
            const int hB = static_cast<int>(handlesB.size());
            for (int k = 0; k < hB; ++k)
                if (k != ib) sum += PB[static_cast<std::size_t>(ib * hB + k)] * forceOn(handlesB, k);
            for (int k = 0; k < hA; ++k)
                if (k != ia) sum -= PA[static_cast<std::size_t>(ia * hA + k)] * forceOn(handlesA, k);
        } else {
            for (int k = 0; k < hA; ++k)
                if (k != ia && k != ib)
                    sum += (PA[static_cast<std::size_t>(ib * hA + k)] - PA[static_cast<std::size_t>(ia * hA + k)]) *
                           forceOn(handlesA, k);
        }
        const SpatialVector f = fd.g[o] - fd.Y[o] * sum;
        fd.handleForce[static_cast<std::size_t>(2 * op.joint + 1)] = f;
        fd.handleForce[static_cast<std::size_t>(2 * op.joint)] = -f;
    }

    // a = I^-1 (sum of handle forces - p), about the centre of mass.
    void finishBody(int body) const {
        const std::size_t bb = static_cast<std::size_t>(body);
        SpatialVector total = -fd.bias[bb];
        for (int h : schedule.getHandles(body))
            total += shiftForce(fd.handleForce[static_cast<std::size_t>(h)], fd.massCenter[bb] - pointOfHandle(h));
        fd.bodyAcceleration[bb] = fd.inertiaInverse[bb] * total;
    }

    // udot from a_beta - a_alpha - c = S udot about the joint point; closures report their force on beta.
    void finishJoint(std::size_t j) const {
        const AssemblyJoint& aj = schedule.getJoints()[j];
        switch (aj.kind) {
            case AssemblyJoint::Kind::Tree: {
                const Joint& joint = model.getJoint(aj.index);
                const Eigen::Vector3d& p = fd.jointPoint[j];
                extractJointAcceleration(joint, data.R_GF[static_cast<std::size_t>(aj.index)],
                                         motionAt(fd.bodyAcceleration, aj.betaBody, p) -
                                             motionAt(fd.bodyAcceleration, aj.alphaBody, p) - fd.jointBias[j],
                                         fd.udot.data() + joint.uStart);
                break;
            }
            case AssemblyJoint::Kind::Loop:
                fd.loopForce[static_cast<std::size_t>(aj.index)] = fd.handleForce[2 * j + 1].tail<3>();
                break;
            case AssemblyJoint::Kind::Hang: fd.hangForce = fd.handleForce[2 * j + 1]; break;
        }
    }
};

}  // namespace

ForwardDynamicsData::ForwardDynamicsData(const Model& model, const AssemblySchedule& schedule) {
    const std::size_t bodies = static_cast<std::size_t>(schedule.getNumBodies());
    const std::size_t operations = schedule.getOperations().size();
    massCenter.assign(bodies, Eigen::Vector3d::Zero());
    inertiaInverse.assign(bodies, Matrix6d::Zero());
    velocity.assign(bodies, SpatialVector::Zero());
    bias.assign(bodies, SpatialVector::Zero());
    jointPoint.assign(schedule.getJoints().size(), Eigen::Vector3d::Zero());
    jointBias.assign(schedule.getJoints().size(), SpatialVector::Zero());
    Phi.resize(static_cast<std::size_t>(schedule.getNumSubassemblies()));
    b.resize(Phi.size());
    for (std::size_t s = 0; s < Phi.size(); ++s) {
        const std::size_t h = schedule.getHandles(static_cast<int>(s)).size();
        Phi[s].assign(h * h, Matrix6d::Zero());
        b[s].assign(h, SpatialVector::Zero());
    }
    Y.assign(operations, Matrix6d::Zero());
    g.assign(operations, SpatialVector::Zero());
    scratchU.resize(operations);
    scratchUE.resize(operations);
    for (std::size_t o = 0; o < operations; ++o) {
        const std::size_t h = schedule.getHandles(schedule.getOperations()[o].result).size();
        scratchU[o].assign(h, Matrix6d::Zero());
        scratchUE[o].assign(h, Matrix6d::Zero());
    }
    operationRedundancy.assign(operations, 0);
    operationConditioning.assign(operations, 1.0);
    handleForce.assign(2 * schedule.getJoints().size(), SpatialVector::Zero());
    udot = Eigen::VectorXd::Zero(model.getNumU());
    bodyAcceleration.assign(bodies, SpatialVector::Zero());
    loopForce.assign(static_cast<std::size_t>(model.getNumLoops()), Eigen::Vector3d::Zero());
}

namespace {

// The stages in order; forEach(begin, end, f) runs f over a range, alone or shared between threads.
template <typename ForEach>
void runStages(const Evaluation& e, ForEach&& forEach) {
    const AssemblySchedule& schedule = e.schedule;
    const int numBodies = schedule.getNumBodies();
    const int numJoints = static_cast<int>(schedule.getJoints().size());
    const std::vector<int>& levels = schedule.getLevelStarts();
    const int numLevels = schedule.getNumLevels();
    forEach(0, numJoints, [&](int j) { e.placeJoint(static_cast<std::size_t>(j)); });
    forEach(0, numBodies, [&](int body) { e.prepareBody(body); });
    forEach(0, numJoints, [&](int j) { e.prepareJoint(static_cast<std::size_t>(j)); });
    for (int level = 0; level < numLevels; ++level)
        forEach(levels[static_cast<std::size_t>(level)], levels[static_cast<std::size_t>(level) + 1], [&](int o) {
            const std::size_t op = static_cast<std::size_t>(o);
            if (schedule.getOperations()[op].isClose) e.close(op);
            else e.join(op);
        });
    for (int level = numLevels - 1; level >= 0; --level)
        forEach(levels[static_cast<std::size_t>(level)], levels[static_cast<std::size_t>(level) + 1],
                [&](int o) { e.disassemble(static_cast<std::size_t>(o)); });
    forEach(0, numBodies, [&](int body) { e.finishBody(body); });
    forEach(0, numJoints, [&](int j) { e.finishJoint(static_cast<std::size_t>(j)); });
}

}  // namespace

void calcForwardDynamics(const Model& model, const AssemblySchedule& schedule, const Data& data,
                         const Eigen::VectorXd& tau, const std::vector<SpatialVector>& linkForces,
                         ForwardDynamicsData& fd, int threads) {
    const Evaluation e{model, schedule, data, tau, linkForces, fd};
    if (threads <= 1) {
        // Plain loops: even a one-thread OpenMP team pays for every worksharing barrier.
        runStages(e, [](int begin, int end, const auto& f) {
            for (int i = begin; i < end; ++i) f(i);
        });
    } else {
        // One parallel region; each worksharing loop ends in a barrier, so a level starts when the one
        // before it is done.
#pragma omp parallel num_threads(threads)
        runStages(e, [](int begin, int end, const auto& f) {
#pragma omp for schedule(dynamic, 1)
            for (int i = begin; i < end; ++i) f(i);
        });
    }
    fd.redundantConstraints = 0;
    fd.loopConditioning = 1;
    for (std::size_t o = 0; o < fd.operationRedundancy.size(); ++o) {
        fd.redundantConstraints += fd.operationRedundancy[o];
        fd.loopConditioning = std::min(fd.loopConditioning, fd.operationConditioning[o]);
    }
}

}  // namespace sinew
