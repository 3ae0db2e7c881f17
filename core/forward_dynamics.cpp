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

// The constraint-force basis T of a joint about its centre (6 x k, k = 6 - nu; T^T S = 0), with joint-frame
// axes R.
using ConstraintBasis = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>;
using SmallSquare = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;

ConstraintBasis calcConstraintBasis(JointType type, const Eigen::Matrix3d& R) {
    ConstraintBasis T = ConstraintBasis::Zero(6, 6 - getNumU(type));
    switch (type) {
        case JointType::Free: break;
        case JointType::Ball: T.bottomRows<3>().setIdentity(); break;  // forces through the centre
        case JointType::Pin:  // forces through the centre, and moments about the two axes normal to the pin
            T.bottomLeftCorner<3, 3>().setIdentity();
            T.block<3, 1>(0, 3) = R.col(0);
            T.block<3, 1>(0, 4) = R.col(1);
            break;
        case JointType::Weld: T.setIdentity(); break;
    }
    return T;
}

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

// M(d): a motion about one point, taken about the point d away ([[1, 0], [-d x, 1]]); its transpose takes a
// force about the point d away back to the first point.
Matrix6d motionShift(const Eigen::Vector3d& d) {
    Matrix6d M = Matrix6d::Identity();
    M.bottomLeftCorner<3, 3>() = -skew(d);
    return M;
}

// Y = T (T^T W T)^-1 T^T for a tree joint. Never singular: of the two subassemblies it joins, at least
// one moves freely.
void calcJointCompliance(const ConstraintBasis& T, const Matrix6d& W, Matrix6d& Y) {
    if (T.cols() == 0) {
        Y.setZero();
        return;
    }
    const SmallSquare D = T.transpose() * W * T;
    Y = T * Eigen::LLT<SmallSquare>(D).solve(T.transpose());
}

// Y = T (T^T W T)^+ T^T for a closure with K constraint directions (a ball loop, 3; the hang weld, 6). D is
// singular when the closure repeats constraints the subassembly already has (a ball loop off the axis of a
// hinge...); its pseudo-inverse then gives the least-squares (minimum-norm) force and exact accelerations.
// Returns the number of redundant directions; `conditioning` gets the smallest kept eigenvalue over the
// largest.
template <int K>
int calcClosureCompliance(const Eigen::Matrix<double, 6, K>& T, const Matrix6d& W, Matrix6d& Y, double& conditioning) {
    using Square = Eigen::Matrix<double, K, K>;
    const Square D = T.transpose() * W * T;
    const Eigen::SelfAdjointEigenSolver<Square> eigen(D);
    const auto& values = eigen.eigenvalues();
    // Roundoff in the subassembly's Phi (differences of inverse inertias) leaves a redundant direction at
    // about 1e-15 of the largest eigenvalue; genuine directions of real models sit far above 1e-9.
    const double largest = values.cwiseAbs().maxCoeff();
    Square pseudoInverse = Square::Zero();
    int redundant = 0;
    conditioning = 1;
    for (int i = 0; i < K; ++i) {
        if (values[i] > 1e-9 * largest) {
            pseudoInverse += eigen.eigenvectors().col(i) * eigen.eigenvectors().col(i).transpose() / values[i];
            conditioning = std::min(conditioning, values[i] / largest);
        } else {
            ++redundant;
        }
    }
    Y = T * pseudoInverse * T.transpose();
    return redundant;
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

        const std::vector<int>& handles = schedule.getHandles(body);
        const std::size_t h = handles.size();
        const SpatialVector a0 = -Iinv * fd.bias[bb];
        for (std::size_t k = 0; k < h; ++k) {
            const Matrix6d Mk = motionShift(pointOfHandle(handles[k]) - c);
            const Matrix6d IinvMkT = Iinv * Mk.transpose();
            for (std::size_t i = 0; i <= k; ++i) {
                const Matrix6d block = motionShift(pointOfHandle(handles[i]) - c) * IinvMkT;
                fd.Phi[bb][i * h + k] = block;
                fd.Phi[bb][k * h + i] = block.transpose();
            }
            fd.b[bb][k] = Mk * a0;
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

    // Y and g of the operation's joint, and its generalized forces as a spatial force on beta.
    void calcJointTerms(std::size_t o, const Matrix6d& W, const SpatialVector& bBeta, const SpatialVector& bAlpha) const {
        const AssemblyOperation& op = schedule.getOperations()[o];
        const AssemblyJoint& aj = schedule.getJoints()[static_cast<std::size_t>(op.joint)];
        const SpatialVector& c = fd.jointBias[static_cast<std::size_t>(op.joint)];
        Matrix6d& Y = fd.Y[o];
        SpatialVector force = SpatialVector::Zero();
        fd.operationRedundancy[o] = 0;
        fd.operationConditioning[o] = 1;
        switch (aj.kind) {
            case AssemblyJoint::Kind::Tree: {
                const Joint& joint = model.getJoint(aj.index);
                const Eigen::Matrix3d& R = data.R_GF[static_cast<std::size_t>(aj.index)];
                calcJointCompliance(calcConstraintBasis(joint.type, R), W, Y);
                force = calcJointForce(joint, R, tau.data() + joint.uStart);
                break;
            }
            case AssemblyJoint::Kind::Loop: {
                Eigen::Matrix<double, 6, 3> T = Eigen::Matrix<double, 6, 3>::Zero();
                T.bottomRows<3>().setIdentity();
                fd.operationRedundancy[o] = calcClosureCompliance<3>(T, W, Y, fd.operationConditioning[o]);
                break;
            }
            case AssemblyJoint::Kind::Hang:
                fd.operationRedundancy[o] =
                    calcClosureCompliance<6>(Matrix6d::Identity(), W, Y, fd.operationConditioning[o]);
                break;
        }
        fd.g[o] = force - Y * (W * force) - Y * (bBeta - bAlpha - c);
    }

    // Join (docs/closed-chain.md, "Join"): subassemblies A and B through joint J into C.
    void join(std::size_t o) const {
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
        auto setC = [&](int i, int k, const Matrix6d& block) {
            C[static_cast<std::size_t>(i * hC + k)] = block;
            if (i != k) C[static_cast<std::size_t>(k * hC + i)] = block.transpose();
        };
        // Positions in the result: A's handles but alpha, then B's but beta.
        auto inCfromA = [&](int k) { return k < ia ? k : k - 1; };
        auto inCfromB = [&](int k) { return hA - 1 + (k < ib ? k : k - 1); };
        calcJointTerms(o, A(ia, ia) + B(ib, ib), bB[static_cast<std::size_t>(ib)], bA[static_cast<std::size_t>(ia)]);
        const Matrix6d& Y = fd.Y[o];
        const SpatialVector& g = fd.g[o];
        for (int h = 0; h < hA; ++h) {
            if (h == ia) continue;
            const Matrix6d L = A(h, ia) * Y;
            for (int k = h; k < hA; ++k)
                if (k != ia) setC(inCfromA(h), inCfromA(k), A(h, k) - L * A(ia, k));
            for (int k = 0; k < hB; ++k)
                if (k != ib) setC(inCfromA(h), inCfromB(k), L * B(ib, k));
            bC[static_cast<std::size_t>(inCfromA(h))] = bA[static_cast<std::size_t>(h)] - A(h, ia) * g;
        }
        for (int h = 0; h < hB; ++h) {
            if (h == ib) continue;
            const Matrix6d R = B(h, ib) * Y;
            for (int k = h; k < hB; ++k)
                if (k != ib) setC(inCfromB(h), inCfromB(k), B(h, k) - R * B(ib, k));
            bC[static_cast<std::size_t>(inCfromB(h))] = bB[static_cast<std::size_t>(h)] + B(h, ib) * g;
        }
    }

    // Close (docs/closed-chain.md, "Close"): a loop whose two handles are both in subassembly A.
    void close(std::size_t o) const {
        const AssemblyOperation& op = schedule.getOperations()[o];
        const std::vector<Matrix6d>& PA = fd.Phi[static_cast<std::size_t>(op.first)];
        const std::vector<SpatialVector>& bA = fd.b[static_cast<std::size_t>(op.first)];
        std::vector<Matrix6d>& C = fd.Phi[static_cast<std::size_t>(op.result)];
        std::vector<SpatialVector>& bC = fd.b[static_cast<std::size_t>(op.result)];
        const int hA = static_cast<int>(bA.size()), hC = static_cast<int>(bC.size());
        const int ia = op.alphaPosition, ib = op.betaPosition;
        auto A = [&](int i, int k) -> const Matrix6d& { return PA[static_cast<std::size_t>(i * hA + k)]; };
        auto inC = [&](int k) { return k - (k > ia ? 1 : 0) - (k > ib ? 1 : 0); };
        calcJointTerms(o, A(ia, ia) + A(ib, ib) - A(ia, ib) - A(ib, ia), bA[static_cast<std::size_t>(ib)],
                       bA[static_cast<std::size_t>(ia)]);
        const Matrix6d& Y = fd.Y[o];
        const SpatialVector& g = fd.g[o];
        for (int h = 0; h < hA; ++h) {
            if (h == ia || h == ib) continue;
            const Matrix6d dY = (A(h, ib) - A(h, ia)) * Y;
            for (int k = h; k < hA; ++k) {
                if (k == ia || k == ib) continue;
                const Matrix6d block = A(h, k) - dY * (A(ib, k) - A(ia, k));
                C[static_cast<std::size_t>(inC(h) * hC + inC(k))] = block;
                if (h != k) C[static_cast<std::size_t>(inC(k) * hC + inC(h))] = block.transpose();
            }
            bC[static_cast<std::size_t>(inC(h))] = bA[static_cast<std::size_t>(h)] + (A(h, ib) - A(h, ia)) * g;
        }
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
    operationRedundancy.assign(operations, 0);
    operationConditioning.assign(operations, 1.0);
    handleForce.assign(2 * schedule.getJoints().size(), SpatialVector::Zero());
    udot = Eigen::VectorXd::Zero(model.getNumU());
    bodyAcceleration.assign(bodies, SpatialVector::Zero());
    loopForce.assign(static_cast<std::size_t>(model.getNumLoops()), Eigen::Vector3d::Zero());
}

void calcForwardDynamics(const Model& model, const AssemblySchedule& schedule, const Data& data,
                         const Eigen::VectorXd& tau, const std::vector<SpatialVector>& linkForces,
                         ForwardDynamicsData& fd, int threads) {
    const Evaluation e{model, schedule, data, tau, linkForces, fd};
    const int numBodies = schedule.getNumBodies();
    const int numJoints = static_cast<int>(schedule.getJoints().size());
    const std::vector<int>& levels = schedule.getLevelStarts();
    const int numLevels = schedule.getNumLevels();
    // One parallel region; each "omp for" ends in a barrier, so a level starts when the one before is done.
    // With one thread (or without OpenMP) this is the plain serial algorithm.
#pragma omp parallel num_threads(threads) if (threads > 1)
    {
#pragma omp for schedule(static)
        for (int j = 0; j < numJoints; ++j) e.placeJoint(static_cast<std::size_t>(j));
#pragma omp for schedule(static)
        for (int body = 0; body < numBodies; ++body) e.prepareBody(body);
#pragma omp for schedule(static)
        for (int j = 0; j < numJoints; ++j) e.prepareJoint(static_cast<std::size_t>(j));
        for (int level = 0; level < numLevels; ++level) {
#pragma omp for schedule(dynamic, 1)
            for (int o = levels[static_cast<std::size_t>(level)]; o < levels[static_cast<std::size_t>(level) + 1]; ++o) {
                const std::size_t op = static_cast<std::size_t>(o);
                if (schedule.getOperations()[op].isClose) e.close(op);
                else e.join(op);
            }
        }
        for (int level = numLevels - 1; level >= 0; --level) {
#pragma omp for schedule(dynamic, 1)
            for (int o = levels[static_cast<std::size_t>(level)]; o < levels[static_cast<std::size_t>(level) + 1]; ++o)
                e.disassemble(static_cast<std::size_t>(o));
        }
#pragma omp for schedule(static)
        for (int body = 0; body < numBodies; ++body) e.finishBody(body);
#pragma omp for schedule(static)
        for (int j = 0; j < numJoints; ++j) e.finishJoint(static_cast<std::size_t>(j));
    }
    fd.redundantConstraints = 0;
    fd.loopConditioning = 1;
    for (std::size_t o = 0; o < fd.operationRedundancy.size(); ++o) {
        fd.redundantConstraints += fd.operationRedundancy[o];
        fd.loopConditioning = std::min(fd.loopConditioning, fd.operationConditioning[o]);
    }
}

}  // namespace sinew
