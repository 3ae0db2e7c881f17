#include "sinew/core/forward_dynamics.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <cmath>

#include "sinew/core/custom_joint.hpp"
#include "sinew/core/error.hpp"

namespace sinew {
namespace {

// Every quantity of an assembly joint, and of the handles on it, is taken about the joint's own point (its
// centre; the loop point; the hung link's origin): spatial vectors in ground axes with that point as
// reference. Moments then stay small wherever the model is, which keeps digits on large models far from
// the ground origin (docs/closed-chain.md, "Reference points").

using Motion = AssemblyJoint::Motion;
// A custom joint's n x n and n-vector quantities (n <= 6): fixed storage, no allocation.
using JointSquare = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
using JointVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;

// A spatial force w about the joint centre with S^T w = tau: the joint's generalized forces as a force on
// the child. A custom joint's w = S (S^T S)^-1 tau; any force along its constraint basis T may be added, as
// the joint carries those.
SpatialVector calcJointForce(Motion motion, const Eigen::Matrix3d& R, const JointMotion& S, const double* tau) {
    SpatialVector w = SpatialVector::Zero();
    switch (motion) {
        case Motion::Custom: {
            const JointSquare StS = S.transpose() * S;
            w = S * StS.llt().solve(Eigen::Map<const JointVector>(tau, S.cols()));
            break;
        }
        case Motion::Free:
            w.head<3>() = R * Eigen::Map<const Eigen::Vector3d>(tau);
            w.tail<3>() = R * Eigen::Map<const Eigen::Vector3d>(tau + 3);
            break;
        case Motion::Ball: w.head<3>() = R * Eigen::Map<const Eigen::Vector3d>(tau); break;
        case Motion::Pin: w.head<3>() = R.col(2) * tau[0]; break;
        case Motion::Weld: break;
    }
    return w;
}

// udot from the relative acceleration about the joint centre, a_beta - a_alpha - c = S udot, where S is
// [R; 0] (ball), [z; 0] (pin), [[R, 0], [0, R]] (free) or a custom joint's (least squares: exact for an
// acceleration in S's span).
void extractJointAcceleration(Motion motion, const Eigen::Matrix3d& R, const JointMotion& S, const SpatialVector& relative,
                              double* udot) {
    switch (motion) {
        case Motion::Custom: {
            const JointSquare StS = S.transpose() * S;
            Eigen::Map<JointVector>(udot, S.cols()) = StS.llt().solve(S.transpose() * relative);
            break;
        }
        case Motion::Free:
            Eigen::Map<Eigen::Vector3d>{udot} = R.transpose() * relative.head<3>();
            Eigen::Map<Eigen::Vector3d>{udot + 3} = R.transpose() * relative.tail<3>();
            break;
        case Motion::Ball: Eigen::Map<Eigen::Vector3d>{udot} = R.transpose() * relative.head<3>(); break;
        case Motion::Pin: udot[0] = R.col(2).dot(relative.head<3>()); break;
        case Motion::Weld: break;
    }
}

// target += M(d)^T I M(d): an articulated inertia I about point r, taken about point o = r - d and added
// (RBDA eq. 2.66 with X = M(d), the motion transform from o to r; M(d) = [[1, 0], [-d x, 1]]). With I =
// [[A, B], [B^T, C]]: B' = B + [d]x C and A' = A + [d]x B^T - B [d]x - [d]x C [d]x.
void addShiftedInertia(Matrix6d& target, const Matrix6d& I, const Eigen::Vector3d& d) {
    const Eigen::Matrix3d D = skew(d);
    const Eigen::Matrix3d B = I.topRightCorner<3, 3>();
    const Eigen::Matrix3d DC = D * I.bottomRightCorner<3, 3>();
    const Eigen::Matrix3d Bshifted = B + DC;
    // [d]x B^T - B [d]x - [d]x C [d]x as N + N^T, exactly symmetric.
    const Eigen::Matrix3d N = D * B.transpose() - 0.5 * DC * D;
    target.topLeftCorner<3, 3>() += I.topLeftCorner<3, 3>() + N + N.transpose();
    target.topRightCorner<3, 3>() += Bshifted;
    target.bottomLeftCorner<3, 3>() += Bshifted.transpose();
    target.bottomRightCorner<3, 3>() += I.bottomRightCorner<3, 3>();
}

// The same for I = [[0, 0], [0, K]], what a ball joint passes on: [[-[d]x K [d]x, [d]x K], [-K [d]x, K]].
void addShiftedTranslationalInertia(Matrix6d& target, const Eigen::Matrix3d& K, const Eigen::Vector3d& d) {
    const Eigen::Matrix3d D = skew(d);
    const Eigen::Matrix3d DK = D * K;
    const Eigen::Matrix3d N = 0.5 * DK * D;
    target.topLeftCorner<3, 3>() -= N + N.transpose();
    target.topRightCorner<3, 3>() += DK;
    target.bottomLeftCorner<3, 3>() += DK.transpose();
    target.bottomRightCorner<3, 3>() += K;
}

// The inverse of a symmetric positive definite spatial inertia [[A, B], [B^T, C]] by 3 x 3 blocks: with
// the Schur complement S = A - B C^-1 B^T, I^-1 = [[S^-1, -S^-1 B C^-1], [., C^-1 + C^-1 B^T S^-1 B C^-1]].
Matrix6d invertInertia(const Matrix6d& I) {
    const Eigen::Matrix3d Cinv = I.bottomRightCorner<3, 3>().inverse();
    const Eigen::Matrix3d BCinv = I.topRightCorner<3, 3>() * Cinv;
    const Eigen::Matrix3d Sinv = (I.topLeftCorner<3, 3>() - BCinv * I.topRightCorner<3, 3>().transpose()).inverse();
    Matrix6d G;
    G.topLeftCorner<3, 3>() = Sinv;
    G.topRightCorner<3, 3>() = -Sinv * BCinv;
    G.bottomLeftCorner<3, 3>() = G.topRightCorner<3, 3>().transpose();
    G.bottomRightCorner<3, 3>() = Cinv - BCinv.transpose() * G.topRightCorner<3, 3>();
    return G;
}

// Constraint-force bases T (6 x K, T^T S = 0) about a joint's centre. A ball (or ball loop) transmits forces
// through its centre, T = [0; 1], which only picks rows and columns: its own type, so that the products
// below take that shortcut. The others are matrices: a pin's, a custom joint's, the hang's identity.
struct BallBasis {};

template <typename Basis>
constexpr int kColumnsOf = Basis::ColsAtCompileTime;
template <>
constexpr int kColumnsOf<BallBasis> = 3;

template <typename Basis>
using Square = Eigen::Matrix<double, kColumnsOf<Basis>, kColumnsOf<Basis>>;

// Products with T: T^T W T, P T and T E T^T.
Eigen::Matrix3d projectOnBasis(const BallBasis&, const Matrix6d& W) { return W.bottomRightCorner<3, 3>(); }
template <int K>
Eigen::Matrix<double, K, K> projectOnBasis(const Eigen::Matrix<double, 6, K>& T, const Matrix6d& W) {
    return T.transpose() * W * T;
}

Eigen::Matrix<double, 6, 3> timesBasis(const Matrix6d& P, const BallBasis&) { return P.rightCols<3>(); }
template <int K>
Eigen::Matrix<double, 6, K> timesBasis(const Matrix6d& P, const Eigen::Matrix<double, 6, K>& T) {
    return P * T;
}

Matrix6d expandFromBasis(const BallBasis&, const Eigen::Matrix3d& E) {
    Matrix6d Y = Matrix6d::Zero();
    Y.bottomRightCorner<3, 3>() = E;
    return Y;
}
template <int K>
Matrix6d expandFromBasis(const Eigen::Matrix<double, 6, K>& T, const Eigen::Matrix<double, K, K>& E) {
    return T * E * T.transpose();
}

// E = (T^T W T)^-1 for a tree joint. Never singular: of the two subassemblies it joins, at least one
// moves freely.
template <typename Basis>
Square<Basis> calcJointCompliance(const Basis& T, const Matrix6d& W) {
    constexpr int K = kColumnsOf<Basis>;
    const Square<Basis> D = projectOnBasis(T, W);
    if constexpr (K <= 4) return D.inverse();  // Eigen's closed form, well conditioned for an SPD D this small
    else return D.llt().solve(Square<Basis>::Identity());
}

// E = (T^T W T)^+ for a closure with K constraint directions (a ball loop, 3; the hang weld, 6). D is
// singular when the closure repeats constraints the subassembly already has (a ball loop off the axis of a
// hinge...); its pseudo-inverse then gives the least-squares (minimum-norm) force and exact accelerations.
// Counts the redundant directions; `conditioning` gets the smallest kept eigenvalue over the largest.
template <typename Basis>
Square<Basis> calcClosureCompliance(const Basis& T, const Matrix6d& W, int& redundant, double& conditioning) {
    constexpr int K = kColumnsOf<Basis>;
    const Square<Basis> D = projectOnBasis(T, W);
    const Eigen::SelfAdjointEigenSolver<Square<Basis>> eigen(D);
    const auto& values = eigen.eigenvalues();
    // Roundoff in the subassembly's Phi (differences of inverse inertias) leaves a redundant direction at
    // about 1e-15 of the largest eigenvalue; genuine directions of real models sit far above 1e-9.
    const double largest = values.cwiseAbs().maxCoeff();
    Square<Basis> pseudoInverse = Square<Basis>::Zero();
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

// A pin transmits forces through its centre and moments about the two axes normal to it (R's x and y).
Eigen::Matrix<double, 6, 5> pinBasis(const Eigen::Matrix3d& R) {
    Eigen::Matrix<double, 6, 5> T = Eigen::Matrix<double, 6, 5>::Zero();
    T.bottomLeftCorner<3, 3>().setIdentity();
    T.block<3, 1>(0, 3) = R.col(0);
    T.block<3, 1>(0, 4) = R.col(1);
    return T;
}

// The constraint-force basis of a custom joint: the orthogonal complement of its S (n columns), the last
// 6 - n columns of Q in S = QR, so T^T S = 0. Calls f with it as a 6 x (6 - n) fixed-size matrix.
template <typename F>
void withCustomBasis(const JointMotion& S, F&& f) {
    const Eigen::HouseholderQR<JointMotion> qr(S);
    const Matrix6d Q = qr.householderQ();
    switch (S.cols()) {
        case 1: f(Eigen::Matrix<double, 6, 5>(Q.rightCols<5>())); break;
        case 2: f(Eigen::Matrix<double, 6, 4>(Q.rightCols<4>())); break;
        case 3: f(Eigen::Matrix<double, 6, 3>(Q.rightCols<3>())); break;
        case 4: f(Eigen::Matrix<double, 6, 2>(Q.rightCols<2>())); break;
        case 5: f(Eigen::Matrix<double, 6, 1>(Q.rightCols<1>())); break;
        default: f(Eigen::Matrix<double, 6, 0>()); break;
    }
}

// Bodies, assembly joints, operations, subassemblies, handles and links are numbered by int, as the
// schedule numbers them (ground is kGroundBody = -1); at() is the one place such a number indexes a vector.
template <typename T>
const T& at(const std::vector<T>& v, int i) { return v[static_cast<std::size_t>(i)]; }
template <typename T>
T& at(std::vector<T>& v, int i) { return v[static_cast<std::size_t>(i)]; }

// A subassembly's handle equations a_h = sum_k Phi_hk f_k + b_h over its numHandles pending handles.
struct HandleEquations {
    std::vector<Matrix6d>& blocks;         // Phi, numHandles x numHandles blocks, row-major
    std::vector<SpatialVector>& offsets;   // b
    int numHandles;

    Matrix6d& Phi(int h, int k) const { return at(blocks, h * numHandles + k); }
    SpatialVector& b(int h) const { return at(offsets, h); }
};

// The handle of a list that is the c-th once `removed` is taken out of it.
int skipHandle(int c, int removed) { return c < removed ? c : c + 1; }

// Everything calcForwardDynamics' stages share.
struct Evaluation {
    const Model& model;
    const AssemblySchedule& schedule;
    const Data& data;
    const Eigen::VectorXd& tau;
    const std::vector<SpatialVector>& linkForces;
    ForwardDynamicsData& fd;
    // The mass matrix's part alone: no velocity terms, gravity or link forces, so udot = A tau with A the
    // loop-constrained inverse inertia (the coordinate constraints' responses).
    bool inertialOnly = false;

    const AssemblyJoint& joint(int j) const { return at(schedule.getJoints(), j); }
    const AssemblyOperation& operation(int o) const { return at(schedule.getOperations(), o); }
    HandleEquations handleEquations(int subassembly) const {
        std::vector<SpatialVector>& b = at(fd.b, subassembly);
        return {at(fd.Phi, subassembly), b, static_cast<int>(b.size())};
    }
    // The orientation of a tree joint's F frame in ground.
    const Eigen::Matrix3d& R_GF(const AssemblyJoint& aj) const { return at(data.R_GF, aj.index); }
    const double* jointTau(const AssemblyJoint& aj) const { return tau.data() + model.getJoint(aj.index).uStart; }
    const JointMotion& S(int j) const { return at(fd.jointMotion, j); }
    SpatialVector jointForce(int j) const {
        const AssemblyJoint& aj = joint(j);
        return calcJointForce(aj.motion, R_GF(aj), S(j), jointTau(aj));
    }
    double* jointUdot(const AssemblyJoint& aj) const { return fd.udot.data() + model.getJoint(aj.index).uStart; }
    // The spatial forces on handles 2j (alpha) and 2j + 1 (beta) of joint j.
    SpatialVector& alphaForce(int j) const { return at(fd.handleForce, 2 * j); }
    SpatialVector& betaForce(int j) const { return at(fd.handleForce, 2 * j + 1); }

    // A body's velocity or acceleration (about its reference point) taken about point p; zero for ground.
    SpatialVector motionAt(const std::vector<SpatialVector>& ofBody, int body, const Eigen::Vector3d& p) const {
        if (body == kGroundBody) return SpatialVector::Zero();
        return shiftMotion(at(ofBody, body), p - at(fd.jointPoint, body));
    }
    const Eigen::Vector3d& pointOfHandle(int handle) const { return at(fd.jointPoint, handle / 2); }

    // The point each assembly joint's quantities are taken about.
    void placeJoint(int j) const {
        const AssemblyJoint& aj = joint(j);
        switch (aj.kind) {
            case AssemblyJoint::Kind::Tree: at(fd.jointPoint, j) = at(data.p_GM, aj.index); break;
            case AssemblyJoint::Kind::Loop: {
                const Loop& loop = model.getLoop(aj.index);
                at(fd.jointPoint, j) = at(data.p_GB, loop.linkA) + at(data.R_GB, loop.linkA) * loop.p_A;
                break;
            }
            case AssemblyJoint::Kind::Hang: at(fd.jointPoint, j) = at(data.p_GB, aj.index); break;
        }
    }

    // Rigid inertia, velocity and bias force p = v x* I v - f_ext of body b about its reference point o
    // (its inboard joint's centre), where the central inertia is diag(Ic, m 1) about the centre of mass c;
    // they start the body's articulated inertia and bias (docs/closed-chain.md, "Bodies").
    void prepareBody(int b) const {
        const AssemblyBody& body = schedule.getBody(b);
        const int first = body.links.front();
        const Eigen::Matrix3d& R = at(data.R_GB, first);
        const Eigen::Vector3d c = at(data.p_GB, first) + R * body.com;
        const Eigen::Matrix3d Ic = R * body.inertia * R.transpose();
        const Eigen::Vector3d& o = at(fd.jointPoint, b);
        const Eigen::Vector3d& w = at(data.w_GB, first);
        const Eigen::Vector3d vc = at(data.v_GB, first) + w.cross(c - at(data.p_GB, first));
        SpatialVector bias = SpatialVector::Zero();
        if (!inertialOnly) {
            SpatialVector biasAtCom;
            biasAtCom.head<3>() = w.cross(Ic * w);
            biasAtCom.tail<3>() = body.mass * (w.cross(vc) - model.getGravity());
            bias = shiftForce(biasAtCom, o - c);
            for (int link : body.links) bias -= shiftForce(at(linkForces, link), o - at(data.p_GB, link));
        }
        at(fd.articulatedBias, b) = bias;
        SpatialVector& v = at(fd.velocity, b);
        v.head<3>() = w;
        v.tail<3>() = vc + w.cross(o - c);
        // RBDA eq. 2.63 with the centre of mass at e = c - o.
        const Eigen::Matrix3d E = skew(c - o);
        Matrix6d& I = at(fd.articulatedInertia, b);
        const Eigen::Matrix3d rotational = Ic - body.mass * E * E;
        I.topLeftCorner<3, 3>() = 0.5 * (rotational + rotational.transpose());  // exactly symmetric, see absorb()
        I.topRightCorner<3, 3>() = body.mass * E;
        I.bottomLeftCorner<3, 3>() = -body.mass * E;
        I.bottomRightCorner<3, 3>() = body.mass * Eigen::Matrix3d::Identity();
    }

    // Relative motion S u = v_beta - v_alpha about the joint point and its bias c = dS/dt u = v_alpha x (S u),
    // plus, for a free or custom joint, (R v_FM) x (R w_FM): its centre moves in the parent; plus, for a
    // custom joint, R Hdot u, its subspace's own rate in F (docs/closed-chain.md, "Joints"). A custom
    // joint's S = [R 0; 0 R] H_FM.
    void prepareJoint(int j) const {
        const AssemblyJoint& aj = joint(j);
        const Eigen::Matrix3d* R = aj.kind == AssemblyJoint::Kind::Tree ? &R_GF(aj) : nullptr;
        if (aj.motion == Motion::Custom) {
            const JointMotion& H = at(data.H_FM, aj.index);
            JointMotion& Sj = at(fd.jointMotion, j);
            Sj.resize(6, H.cols());
            Sj.topRows<3>() = *R * H.topRows<3>();
            Sj.bottomRows<3>() = *R * H.bottomRows<3>();
        }
        SpatialVector& c = at(fd.jointBias, j);
        if (inertialOnly) {
            c.setZero();
            return;
        }
        const Eigen::Vector3d& p = at(fd.jointPoint, j);
        const SpatialVector vAlpha = motionAt(fd.velocity, aj.alphaBody, p);
        const SpatialVector relative = motionAt(fd.velocity, aj.betaBody, p) - vAlpha;
        c = crossMotion(vAlpha, relative);
        if (aj.motion == Motion::Free || aj.motion == Motion::Custom)
            c.tail<3>() += relative.tail<3>().cross(relative.head<3>());
        if (aj.motion == Motion::Custom) {
            const Joint& tree = model.getJoint(aj.index);
            const SpatialVector bias_F =
                calcCustomJointBias(tree, data.q.data() + tree.qStart, data.u.data() + tree.uStart);
            c.head<3>() += *R * bias_F.head<3>();
            c.tail<3>() += *R * bias_F.tail<3>();
        }
    }

    // Absorb (docs/closed-chain.md, "Absorb"): the child body's articulated inertia I and bias p about the
    // joint centre pass through the joint to the parent as Ia = I - U D^-1 U^T and pa = p + Ia c +
    // U D^-1 (tau - S^T p), with U = I S and D = S^T U (RBDA eqs. 7.37-7.40, Table 7.1), taken about the
    // parent's point. Ground takes nothing.
    void absorb(int j) const {
        const AssemblyJoint& aj = joint(j);
        const Matrix6d& I = at(fd.articulatedInertia, aj.betaBody);
        const SpatialVector& p = at(fd.articulatedBias, aj.betaBody);
        const Eigen::Matrix3d& R = R_GF(aj);
        const double* tauJ = jointTau(aj);
        const SpatialVector& c = at(fd.jointBias, j);
        SpatialVector pa = jointForce(j);
        // The parent's inertia, or none for ground; d: from the parent's point to the joint centre.
        const int parent = aj.alphaBody == kGroundBody ? 0 : aj.alphaBody;
        Matrix6d* parentInertia = aj.alphaBody == kGroundBody ? nullptr : &at(fd.articulatedInertia, parent);
        const Eigen::Vector3d d = parentInertia ? Eigen::Vector3d(at(fd.jointPoint, j) - at(fd.jointPoint, parent))
                                                : Eigen::Vector3d::Zero();
        switch (aj.motion) {
            case Motion::Ball: {
                // S = [R; 0]: U D^-1 U^T = I[:, 0:3] A^-1 I[0:3, :], so Ia = [[0, 0], [0, K]] with K the Schur
                // complement C - B^T A^-1 B, and pa = [R tau; ...]: 3 x 3 blocks only.
                const Eigen::Matrix3d B = I.topRightCorner<3, 3>();
                const Eigen::Matrix3d& Ainv = at(fd.rotationalInverse, j) = I.topLeftCorner<3, 3>().inverse();
                at(fd.singular, j) = !std::isfinite(Ainv.trace());  // a singular A's inverse is inf or NaN throughout
                const Eigen::Matrix3d BtAinv = B.transpose() * Ainv;
                // Kept exactly symmetric: the roundoff asymmetry of B^T A^-1 B grows geometrically along
                // chains of ball joints (1e-8 relative after 40 links, NaN after 127).
                const Eigen::Matrix3d BtAinvB = BtAinv * B;
                const Eigen::Matrix3d K = I.bottomRightCorner<3, 3>() - 0.5 * (BtAinvB + BtAinvB.transpose());
                pa.tail<3>() = p.tail<3>() + K * c.tail<3>() + BtAinv * (pa.head<3>() - p.head<3>());
                if (parentInertia) addShiftedTranslationalInertia(*parentInertia, K, d);
                break;
            }
            case Motion::Pin: {
                const Eigen::Vector3d z = R.col(2);
                const SpatialVector U = I.leftCols<3>() * z;
                const double D = z.dot(U.head<3>());
                at(fd.singular, j) = !(D > 0);
                const Matrix6d Ia = I - U * U.transpose() / D;
                pa = p + Ia * c + U * ((tauJ[0] - z.dot(p.head<3>())) / D);
                if (parentInertia) addShiftedInertia(*parentInertia, Ia, d);
                break;
            }
            case Motion::Custom: {
                const JointMotion& Sj = S(j);
                const JointMotion U = I * Sj;
                const Eigen::LLT<JointSquare> D(Sj.transpose() * U);
                at(fd.singular, j) = D.info() != Eigen::Success;
                const JointVector rest = Eigen::Map<const JointVector>(tauJ, Sj.cols()) - Sj.transpose() * p;
                const Matrix6d Ia = I - U * D.solve(U.transpose());
                pa = p + Ia * c + U * D.solve(rest);
                if (parentInertia) addShiftedInertia(*parentInertia, 0.5 * (Ia + Ia.transpose()), d);
                break;
            }
            case Motion::Free: break;  // S invertible: Ia = 0 and pa = the joint force
            case Motion::Weld: break;  // (never: welded links share a body)
        }
        if (parentInertia) at(fd.articulatedBias, parent) += shiftForce(pa, -d);
    }

    // The child's acceleration from its parent's, a = a_parent + c + S udot with udot = D^-1 (tau - S^T p -
    // U^T (a_parent + c)) (RBDA Table 7.1, third pass), and the joint's udot.
    void absorbAcceleration(int j) const {
        const AssemblyJoint& aj = joint(j);
        const Matrix6d& I = at(fd.articulatedInertia, aj.betaBody);
        const SpatialVector& p = at(fd.articulatedBias, aj.betaBody);
        const Eigen::Matrix3d& R = R_GF(aj);
        const double* tauJ = jointTau(aj);
        const SpatialVector base = motionAt(fd.bodyAcceleration, aj.alphaBody, at(fd.jointPoint, j)) + at(fd.jointBias, j);
        SpatialVector a = base;
        switch (aj.motion) {
            case Motion::Ball:
                // The moment row of I a + p = [R tau; f] gives the angular part; the linear part is the parent's.
                a.head<3>() = at(fd.rotationalInverse, j) * (R * Eigen::Map<const Eigen::Vector3d>(tauJ) - p.head<3>() -
                                                             I.topRightCorner<3, 3>() * a.tail<3>());
                break;
            case Motion::Pin: {
                const Eigen::Vector3d z = R.col(2);
                const SpatialVector U = I.leftCols<3>() * z;
                a.head<3>() += z * ((tauJ[0] - z.dot(p.head<3>()) - U.dot(a)) / z.dot(U.head<3>()));
                break;
            }
            case Motion::Free: {
                const Eigen::LLT<Matrix6d> inertia(I);
                at(fd.singular, j) = inertia.info() != Eigen::Success;
                a = inertia.solve(jointForce(j) - p);
                break;
            }
            case Motion::Custom: {
                const JointMotion& Sj = S(j);
                const JointMotion U = I * Sj;
                const Eigen::LLT<JointSquare> D(Sj.transpose() * U);
                Eigen::Map<JointVector> udot(jointUdot(aj), Sj.cols());
                udot = D.solve(Eigen::Map<const JointVector>(tauJ, Sj.cols()) - Sj.transpose() * p - U.transpose() * base);
                at(fd.bodyAcceleration, aj.betaBody) = base + Sj * udot;
                return;
            }
            case Motion::Weld: break;
        }
        at(fd.bodyAcceleration, aj.betaBody) = a;
        extractJointAcceleration(aj.motion, R, S(j), a - base, jointUdot(aj));
    }

    // AbsorbSubassembly: the child's subassembly has one handle, the joint's beta, with a_beta = W f + b.
    // Through the joint the force on it is f = w + T lambda with T^T (a_beta - a_parent - c) = 0, so
    // f = Y a_parent + g with Y and g as in a join (docs/closed-chain.md): in ABA's terms Ia = Y and pa = g.
    void absorbSubassembly(int o) const {
        const AssemblyOperation& op = operation(o);
        const AssemblyJoint& aj = joint(op.joint);
        const HandleEquations child = handleEquations(op.first);
        const Matrix6d& W = child.Phi(0, 0);
        const SpatialVector force = jointForce(op.joint);
        withJointBasis(op.joint, [&](const auto& T) {
            using Basis = std::decay_t<decltype(T)>;
            Square<Basis> E;
            if constexpr (kColumnsOf<Basis> > 0) E = calcJointCompliance(T, W);
            setJointTerms(o, T, E, W, force, child.b(0));
        });
        if (aj.alphaBody == kGroundBody) return;
        const int parent = aj.alphaBody;
        const Eigen::Vector3d d = at(fd.jointPoint, op.joint) - at(fd.jointPoint, parent);
        const Matrix6d& Y = at(fd.Y, o);
        // Exactly symmetric, as every articulated inertia is kept (roundoff asymmetry grows along chains).
        addShiftedInertia(at(fd.articulatedInertia, parent), 0.5 * (Y + Y.transpose()), d);
        at(fd.articulatedBias, parent) += shiftForce(at(fd.g, o), -d);
    }

    // The force through the joint once the parent's acceleration is known: f = Y a_parent + g.
    void absorbSubassemblyForce(int o) const {
        const int j = operation(o).joint;
        const SpatialVector f =
            at(fd.Y, o) * motionAt(fd.bodyAcceleration, joint(j).alphaBody, at(fd.jointPoint, j)) + at(fd.g, o);
        betaForce(j) = f;
        alphaForce(j) = -f;
    }

    // A skeleton body's leaf (docs/closed-chain.md, "Leaves"): with G = I^-1 about the body's point o,
    // Phi_hk = M(r_h - o) G M(r_k - o)^T and b_h = -M(r_h - o) G p. With M(r_h - o) G = [[G11, G12], [P_h,
    // Q_h]], P_h = G21 - [d_h]x G11 and Q_h = G22 - [d_h]x G12: Phi_hk = [[G11, P_k^T], [P_h, P_h [d_k]x + Q_h]].
    void leaf(int o) const {
        const int body = operation(o).first;
        const Matrix6d& G = at(fd.inverseInertia, body) = invertInertia(at(fd.articulatedInertia, body));
        at(fd.singular, body) = !std::isfinite(G.trace());  // body b's inboard joint is assembly joint b
        const SpatialVector a0 = -G * at(fd.articulatedBias, body);
        const std::vector<int>& handles = schedule.getHandles(body);
        const HandleEquations leafEquations = handleEquations(body);  // the body's leaf subassembly
        const int h = leafEquations.numHandles;
        std::vector<Matrix6d>& PQ = at(fd.scratchU, o);
        for (int k = 0; k < h; ++k) {
            const Eigen::Vector3d d = pointOfHandle(at(handles, k)) - at(fd.jointPoint, body);
            const Eigen::Matrix3d D = skew(d);
            Matrix6d& PQk = at(PQ, k);
            PQk.bottomLeftCorner<3, 3>() = G.bottomLeftCorner<3, 3>() - D * G.topLeftCorner<3, 3>();
            PQk.bottomRightCorner<3, 3>() = G.bottomRightCorner<3, 3>() - D * G.topRightCorner<3, 3>();
            PQk.topLeftCorner<3, 3>() = D;  // [d_k]x, kept for the blocks below
            leafEquations.b(k) = shiftMotion(a0, d);
        }
        for (int k = 0; k < h; ++k) {
            for (int i = 0; i <= k; ++i) {
                Matrix6d& block = leafEquations.Phi(i, k);
                block.topLeftCorner<3, 3>() = G.topLeftCorner<3, 3>();
                block.topRightCorner<3, 3>() = at(PQ, k).bottomLeftCorner<3, 3>().transpose();
                block.bottomLeftCorner<3, 3>() = at(PQ, i).bottomLeftCorner<3, 3>();
                block.bottomRightCorner<3, 3>() = at(PQ, i).bottomLeftCorner<3, 3>() * at(PQ, k).topLeftCorner<3, 3>() +
                                                  at(PQ, i).bottomRightCorner<3, 3>();
                if (i != k) leafEquations.Phi(k, i) = block.transpose();
            }
        }
    }

    // Join (docs/closed-chain.md, "Join"): subassemblies A and B through joint J into C. Y = T E T^T has
    // rank K (the joint's constraint directions), so each block update Phi_ha Y Phi_ak is done as
    // (Phi_ha T) E (Phi_ka T)^T: for a ball joint T selects the force rows and the update costs half.
    void join(int o) const {
        const SpatialVector force = jointForce(operation(o).joint);
        withJointBasis(operation(o).joint, [&](const auto& T) { joinThrough(o, T, force); });
    }

    // Calls f with tree joint j's constraint-force basis T (of its own type: see BallBasis).
    template <typename F>
    void withJointBasis(int j, F&& f) const {
        const AssemblyJoint& aj = joint(j);
        switch (aj.motion) {
            case Motion::Ball: f(BallBasis{}); break;
            case Motion::Pin: f(pinBasis(R_GF(aj))); break;
            case Motion::Free: f(Eigen::Matrix<double, 6, 0>()); break;
            case Motion::Custom: withCustomBasis(S(j), f); break;
            case Motion::Weld: break;  // welded links share a body: never a tree joint
        }
    }

    template <typename Basis>
    void joinThrough(int o, const Basis& T, const SpatialVector& force) const {
        constexpr int K = kColumnsOf<Basis>;
        const AssemblyOperation& op = operation(o);
        const HandleEquations A = handleEquations(op.first), B = handleEquations(op.second);
        const HandleEquations C = handleEquations(op.result);
        const int ia = op.alphaPosition, ib = op.betaPosition;
        const Matrix6d W = A.Phi(ia, ia) + B.Phi(ib, ib);
        Square<Basis> E;
        if constexpr (K > 0) E = calcJointCompliance(T, W);
        setJointTerms(o, T, E, W, force, B.b(ib) - A.b(ia));
        const SpatialVector& g = at(fd.g, o);
        // C's handles: A's but alpha, then B's but beta. fromA(c), and the handle in A or B it is.
        auto fromA = [&](int c) { return c < A.numHandles - 1; };
        auto source = [&](int c) { return fromA(c) ? skipHandle(c, ia) : skipHandle(c - (A.numHandles - 1), ib); };

        // U_c = Phi_h,joint T (6 x K) and U_c E, for every handle c of C (handle h of A or B).
        std::vector<Matrix6d>& U = at(fd.scratchU, o);
        std::vector<Matrix6d>& UE = at(fd.scratchUE, o);
        for (int c = 0; c < C.numHandles; ++c) {
            const int h = source(c);
            const Matrix6d& P = fromA(c) ? A.Phi(h, ia) : B.Phi(h, ib);
            at(U, c).leftCols<K>() = timesBasis(P, T);
            at(UE, c).leftCols<K>() = at(U, c).leftCols<K>() * E;
            C.b(c) = fromA(c) ? SpatialVector(A.b(h) - P * g) : SpatialVector(B.b(h) + P * g);
        }
        for (int c = 0; c < C.numHandles; ++c) {
            const int h = source(c);
            for (int d = c; d < C.numHandles; ++d) {
                const int k = source(d);
                const Matrix6d update = at(UE, c).leftCols<K>() * at(U, d).leftCols<K>().transpose();
                Matrix6d block;
                if (fromA(c) && fromA(d)) block = A.Phi(h, k) - update;
                else if (!fromA(c) && !fromA(d)) block = B.Phi(h, k) - update;
                else block = update;  // c in A, d in B (c < d keeps that order)
                C.Phi(c, d) = block;
                if (c != d) C.Phi(d, c) = block.transpose();
            }
        }
    }

    // Close (docs/closed-chain.md, "Close"): a loop (or the hang) whose two handles are both in A. With
    // Delta_h = Phi_h,beta - Phi_h,alpha, the update Delta_h Y Delta_k^T is done as (Delta_h T) E (Delta_k T)^T.
    void close(int o) const {
        if (joint(operation(o).joint).kind == AssemblyJoint::Kind::Loop) closeThrough(o, BallBasis{});
        else closeThrough(o, Matrix6d::Identity().eval());
    }

    template <typename Basis>
    void closeThrough(int o, const Basis& T) const {
        constexpr int K = kColumnsOf<Basis>;
        const AssemblyOperation& op = operation(o);
        const HandleEquations A = handleEquations(op.first), C = handleEquations(op.result);
        const int ia = op.alphaPosition, ib = op.betaPosition;
        // The c-th remaining handle of A.
        auto handleAt = [&](int c) { return c + (c >= std::min(ia, ib) ? 1 : 0) + (c + 1 >= std::max(ia, ib) ? 1 : 0); };
        const Matrix6d W = A.Phi(ia, ia) + A.Phi(ib, ib) - A.Phi(ia, ib) - A.Phi(ib, ia);
        const Square<Basis> E =
            calcClosureCompliance(T, W, at(fd.operationRedundancy, o), at(fd.operationConditioning, o));
        setJointTerms(o, T, E, W, SpatialVector::Zero(), A.b(ib) - A.b(ia));
        const SpatialVector& g = at(fd.g, o);
        std::vector<Matrix6d>& U = at(fd.scratchU, o);
        std::vector<Matrix6d>& UE = at(fd.scratchUE, o);
        for (int c = 0; c < C.numHandles; ++c) {
            const int h = handleAt(c);
            const Matrix6d delta = A.Phi(h, ib) - A.Phi(h, ia);
            at(U, c).leftCols<K>() = timesBasis(delta, T);
            at(UE, c).leftCols<K>() = at(U, c).leftCols<K>() * E;
            C.b(c) = A.b(h) + delta * g;
        }
        for (int c = 0; c < C.numHandles; ++c) {
            for (int d = c; d < C.numHandles; ++d) {
                const Matrix6d block =
                    A.Phi(handleAt(c), handleAt(d)) - at(UE, c).leftCols<K>() * at(U, d).leftCols<K>().transpose();
                C.Phi(c, d) = block;
                if (c != d) C.Phi(d, c) = block.transpose();
            }
        }
    }

    // Y = T E T^T and g = (1 - Y W) w - Y (b_beta - b_alpha - c) of operation o.
    template <typename Basis>
    void setJointTerms(int o, const Basis& T, const Square<Basis>& E, const Matrix6d& W, const SpatialVector& force,
                       const SpatialVector& bDifference) const {
        const SpatialVector& c = at(fd.jointBias, operation(o).joint);
        Matrix6d& Y = at(fd.Y, o);
        if constexpr (kColumnsOf<Basis> == 0) Y.setZero();
        else Y = expandFromBasis(T, E);
        at(fd.g, o) = force - Y * (W * force + bDifference - c);
    }

    // The force through the operation's joint, from the forces on its result's handles.
    void disassemble(int o) const {
        const AssemblyOperation& op = operation(o);
        const std::vector<int>& handlesA = schedule.getHandles(op.first);
        const HandleEquations A = handleEquations(op.first);
        const int ia = op.alphaPosition, ib = op.betaPosition;
        auto forceOn = [&](const std::vector<int>& handles, int k) -> const SpatialVector& {
            return at(fd.handleForce, at(handles, k));
        };
        SpatialVector sum = SpatialVector::Zero();
        if (op.kind == AssemblyOperation::Kind::Join) {
            const std::vector<int>& handlesB = schedule.getHandles(op.second);
            const HandleEquations B = handleEquations(op.second);
            for (int k = 0; k < B.numHandles; ++k)
                if (k != ib) sum += B.Phi(ib, k) * forceOn(handlesB, k);
            for (int k = 0; k < A.numHandles; ++k)
                if (k != ia) sum -= A.Phi(ia, k) * forceOn(handlesA, k);
        } else {
            for (int k = 0; k < A.numHandles; ++k)
                if (k != ia && k != ib) sum += (A.Phi(ib, k) - A.Phi(ia, k)) * forceOn(handlesA, k);
        }
        const SpatialVector f = at(fd.g, o) - at(fd.Y, o) * sum;
        betaForce(op.joint) = f;
        alphaForce(op.joint) = -f;
    }

    // A skeleton body's acceleration, a = I^-1 (sum of handle forces - p), about its point.
    void finishLeaf(int o) const {
        const int body = operation(o).first;
        SpatialVector total = -at(fd.articulatedBias, body);
        for (int h : schedule.getHandles(body))
            total += shiftForce(at(fd.handleForce, h), at(fd.jointPoint, body) - pointOfHandle(h));
        at(fd.bodyAcceleration, body) = at(fd.inverseInertia, body) * total;
    }

    // udot from a_beta - a_alpha - c = S udot about the joint point (absorbed joints have theirs already);
    // closures report their force on beta.
    void finishJoint(int j) const {
        const AssemblyJoint& aj = joint(j);
        switch (aj.kind) {
            case AssemblyJoint::Kind::Tree: {
                if (schedule.getTreeJointOperation(j) == AssemblyOperation::Kind::Absorb) break;
                const Eigen::Vector3d& p = at(fd.jointPoint, j);
                extractJointAcceleration(aj.motion, R_GF(aj), S(j),
                                         motionAt(fd.bodyAcceleration, aj.betaBody, p) -
                                             motionAt(fd.bodyAcceleration, aj.alphaBody, p) - at(fd.jointBias, j),
                                         jointUdot(aj));
                break;
            }
            case AssemblyJoint::Kind::Loop: at(fd.loopForce, aj.index) = betaForce(j).tail<3>(); break;
            case AssemblyJoint::Kind::Hang: fd.hangForce = betaForce(j); break;
        }
    }
};

}  // namespace

ForwardDynamicsData::ForwardDynamicsData(const Model& model, const AssemblySchedule& schedule) {
    const std::size_t bodies = static_cast<std::size_t>(schedule.getNumBodies());
    const std::size_t joints = schedule.getJoints().size();
    const std::size_t operations = schedule.getOperations().size();
    jointPoint.assign(joints, Eigen::Vector3d::Zero());
    jointBias.assign(joints, SpatialVector::Zero());
    jointMotion.assign(joints, JointMotion(6, 0));
    singular.assign(joints, 0);
    velocity.assign(bodies, SpatialVector::Zero());
    articulatedInertia.assign(bodies, Matrix6d::Zero());
    articulatedBias.assign(bodies, SpatialVector::Zero());
    inverseInertia.assign(bodies, Matrix6d::Zero());
    rotationalInverse.assign(joints, Eigen::Matrix3d::Zero());
    Phi.resize(static_cast<std::size_t>(schedule.getNumSubassemblies()));
    b.resize(Phi.size());
    for (int s = 0; s < schedule.getNumSubassemblies(); ++s) {
        const std::size_t h = schedule.getHandles(s).size();
        at(Phi, s).assign(h * h, Matrix6d::Zero());
        at(b, s).assign(h, SpatialVector::Zero());
    }
    Y.assign(operations, Matrix6d::Zero());
    g.assign(operations, SpatialVector::Zero());
    scratchU.resize(operations);
    scratchUE.resize(operations);
    for (std::size_t o = 0; o < operations; ++o) {
        const AssemblyOperation& op = schedule.getOperations()[o];
        const std::size_t h = op.result < 0 ? 0 : schedule.getHandles(op.result).size();
        scratchU[o].assign(h, Matrix6d::Zero());
        if (op.kind == AssemblyOperation::Kind::Join || op.kind == AssemblyOperation::Kind::Close)
            scratchUE[o].assign(h, Matrix6d::Zero());
    }
    operationRedundancy.assign(operations, 0);
    operationConditioning.assign(operations, 1.0);
    handleForce.assign(2 * joints, SpatialVector::Zero());
    udot = Eigen::VectorXd::Zero(model.getNumU());
    bodyAcceleration.assign(bodies, SpatialVector::Zero());
    loopForce.assign(static_cast<std::size_t>(model.getNumLoops()), Eigen::Vector3d::Zero());
    constraints = getCoordinateConstraints(model);
    const Eigen::Index m = static_cast<Eigen::Index>(constraints.size());
    constraintSlope = Eigen::VectorXd::Zero(m);
    constraintResponse = Eigen::MatrixXd::Zero(model.getNumU(), m);
    constraintMatrix = Eigen::MatrixXd::Zero(m, m);
    constraintSolver.compute(constraintMatrix);  // sizes its storage and sets its status (copies read it)
    freeUdot = Eigen::VectorXd::Zero(model.getNumU());
    constraintRhs = Eigen::VectorXd::Zero(m);
    constraintTau = Eigen::VectorXd::Zero(model.getNumU());
    coordinateConstraintForce = Eigen::VectorXd::Zero(m);
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
    using Kind = AssemblyOperation::Kind;
    forEach(0, numJoints, [&](int j) { e.placeJoint(j); });
    forEach(0, numBodies, [&](int body) { e.prepareBody(body); });
    forEach(0, numJoints, [&](int j) { e.prepareJoint(j); });
    for (int level = 0; level < numLevels; ++level)
        forEach(at(levels, level), at(levels, level + 1), [&](int o) {
            const AssemblyOperation& operation = e.operation(o);
            switch (operation.kind) {
                case Kind::Absorb: e.absorb(operation.joint); break;
                case Kind::AbsorbSubassembly: e.absorbSubassembly(o); break;
                case Kind::Leaf: e.leaf(o); break;
                case Kind::Join: e.join(o); break;
                case Kind::Close: e.close(o); break;
            }
        });
    for (int level = numLevels - 1; level >= 0; --level)
        forEach(at(levels, level), at(levels, level + 1), [&](int o) {
            const AssemblyOperation& operation = e.operation(o);
            switch (operation.kind) {
                case Kind::Absorb: e.absorbAcceleration(operation.joint); break;
                case Kind::AbsorbSubassembly: e.absorbSubassemblyForce(o); break;
                case Kind::Leaf: e.finishLeaf(o); break;
                case Kind::Join:
                case Kind::Close: e.disassemble(o); break;
            }
        });
    forEach(0, numJoints, [&](int j) { e.finishJoint(j); });
}

// One evaluation of every stage, alone or on `threads` threads.
void runEvaluation(const Evaluation& e, int threads) {
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
#pragma omp for schedule(static)
            for (int i = begin; i < end; ++i) f(i);
        });
    }
}

// Throws, naming a joint whose motion no inertia resisted (a point mass at a ball's centre...): u̇ would be
// infinite there. The outermost such joint: its NaNs spread to the joints inboard of it.
void requireRegular(const Model& model, const AssemblySchedule& schedule, const ForwardDynamicsData& fd) {
    for (std::size_t j = fd.singular.size(); j-- > 0;) {
        if (!fd.singular[j]) continue;
        const AssemblyJoint& aj = schedule.getJoints()[j];
        const std::string link = model.getLink(aj.index).name;
        throw Error("model '" + model.getName() + "': forward dynamics is singular at joint '" +
                    model.getJoint(aj.index).name + "' of link '" + link +
                    "': no inertia resists a motion it allows (a point mass at a ball or free joint's centre or on a "
                    "pin's axis, with nothing massive beyond it); give link '" + link + "' a rotational inertia");
    }
}

// Coordinate constraints (docs/closed-chain.md, "Coordinate constraints"), row k: a coupler's q_dep =
// s f(q_ind) has G_k = e_dep - s f'(q_ind) e_ind (qdot = u for both) and G_k udot = s f''(q_ind) u_ind^2; a
// locked coordinate has G_k = e_i and G_k udot = 0. udot is affine in tau: udot = udot_free + A G^T lambda,
// with A G_k^T from a pass with tau = G_k^T and no velocity terms, gravity or applied forces. Solving the
// m x m system G A G^T lambda = rhs - G udot_free gives the multipliers; a last pass with tau + G^T lambda
// then leaves every output (udot, accelerations, loop and handle forces) consistent with them.
void enforceCoordinateConstraints(const Evaluation& free, int threads) {
    const Model& model = free.model;
    const Data& data = free.data;
    ForwardDynamicsData& fd = free.fd;
    const int m = static_cast<int>(fd.constraints.size());
    for (int k = 0; k < m; ++k) {
        const CoordinateConstraint& row = at(fd.constraints, k);
        fd.constraintSlope[k] = calcCoordinateConstraintSlope(model, row, data.q);
        fd.constraintRhs[k] = 0;  // a lock's: udot = 0
        if (row.coupler < 0) continue;
        const CoordinateCoupler& c = at(model.getCouplers(), row.coupler);
        const double rate = data.u[c.independentU];
        fd.constraintRhs[k] = c.scaleFactor * c.function.calcDerivative(data.q[c.independentQ], 2) * rate * rate;
    }
    // G_k v for a vector v (nu) or a row of a matrix.
    auto applyRow = [&](int k, const auto& v) {
        const CoordinateConstraint& row = at(fd.constraints, k);
        return row.otherSpeed < 0 ? v(row.speed) : v(row.speed) - fd.constraintSlope[k] * v(row.otherSpeed);
    };
    // tau += G_k^T scale.
    auto addRowTranspose = [&](int k, double scale) {
        const CoordinateConstraint& row = at(fd.constraints, k);
        fd.constraintTau[row.speed] += scale;
        if (row.otherSpeed >= 0) fd.constraintTau[row.otherSpeed] -= fd.constraintSlope[k] * scale;
    };
    fd.freeUdot = fd.udot;
    for (int k = 0; k < m; ++k) {
        fd.constraintTau.setZero();
        addRowTranspose(k, 1);
        Evaluation response{model, free.schedule, data, fd.constraintTau, free.linkForces, fd};
        response.inertialOnly = true;
        runEvaluation(response, threads);
        fd.constraintResponse.col(k) = fd.udot;
    }
    for (int k = 0; k < m; ++k) {
        for (int l = 0; l < m; ++l)
            fd.constraintMatrix(k, l) = applyRow(k, [&](int u) { return fd.constraintResponse(u, l); });
        fd.constraintRhs[k] -= applyRow(k, [&](int u) { return fd.freeUdot[u]; });
    }
    // G A G^T is symmetric (A is); kept exactly so for the factorisation.
    fd.constraintMatrix = 0.5 * (fd.constraintMatrix + fd.constraintMatrix.transpose()).eval();
    fd.constraintSolver.compute(fd.constraintMatrix);
    fd.coordinateConstraintForce = fd.constraintSolver.solve(fd.constraintRhs);
    fd.constraintTau = free.tau;
    for (int k = 0; k < m; ++k) addRowTranspose(k, fd.coordinateConstraintForce[k]);
    runEvaluation({model, free.schedule, data, fd.constraintTau, free.linkForces, fd}, threads);
}

}  // namespace

void calcForwardDynamics(const Model& model, const AssemblySchedule& schedule, const Data& data,
                         const Eigen::VectorXd& tau, const std::vector<SpatialVector>& linkForces,
                         ForwardDynamicsData& fd, int threads) {
    const Evaluation e{model, schedule, data, tau, linkForces, fd};
    runEvaluation(e, threads);
    requireRegular(model, schedule, fd);
    if (!fd.constraints.empty()) enforceCoordinateConstraints(e, threads);
    // Virtual links take no part (their quasi-static treatment drives them).
    for (int link : schedule.getVirtualLinks()) {
        const Joint& joint = model.getJoint(link);
        fd.udot.segment(joint.uStart, joint.nu).setZero();
    }
    fd.redundantConstraints = 0;
    fd.loopConditioning = 1;
    for (std::size_t o = 0; o < fd.operationRedundancy.size(); ++o) {
        fd.redundantConstraints += fd.operationRedundancy[o];
        fd.loopConditioning = std::min(fd.loopConditioning, fd.operationConditioning[o]);
    }
}

}  // namespace sinew
