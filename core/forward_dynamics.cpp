#include "sinew/core/forward_dynamics.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>

namespace sinew {
namespace {

// The constraint-force basis T of a joint (6 x k, k = 6 - nu; T^T S = 0), in ground at the origin, for a
// joint whose centre is p with joint-frame axes R (docs/closed-chain.md, "Joints").
using ConstraintBasis = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>;
using SmallSquare = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;

ConstraintBasis calcConstraintBasis(JointType type, const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
    ConstraintBasis T(6, 6 - getNumU(type));
    switch (type) {
        case JointType::Free: break;
        case JointType::Ball:  // forces through the centre
            T.topRows<3>() = skew(p);
            T.bottomRows<3>().setIdentity();
            break;
        case JointType::Pin:  // forces through the centre, and moments about the two axes normal to the pin
            T.setZero();
            T.topLeftCorner<3, 3>() = skew(p);
            T.bottomLeftCorner<3, 3>().setIdentity();
            T.block<3, 1>(0, 3) = R.col(0);
            T.block<3, 1>(0, 4) = R.col(1);
            break;
        case JointType::Weld: T.setIdentity(); break;
    }
    return T;
}

// A spatial force w with S^T w = tau: the joint's generalized forces as a force on the child.
SpatialVector calcJointForce(const Joint& joint, const Eigen::Matrix3d& R, const Eigen::Vector3d& p,
                             const double* tau) {
    SpatialVector w = SpatialVector::Zero();
    switch (joint.type) {
        case JointType::Free:
            w.tail<3>() = R * Eigen::Map<const Eigen::Vector3d>(tau + 3);
            w.head<3>() = R * Eigen::Map<const Eigen::Vector3d>(tau) + p.cross(w.tail<3>());
            break;
        case JointType::Ball: w.head<3>() = R * Eigen::Map<const Eigen::Vector3d>(tau); break;
        case JointType::Pin: w.head<3>() = R.col(2) * tau[0]; break;
        case JointType::Weld: break;
    }
    return w;
}

// udot from the relative acceleration a_beta - a_alpha - c = S udot (S has orthonormal angular columns).
void extractJointAcceleration(const Joint& joint, const Eigen::Matrix3d& R, const Eigen::Vector3d& p,
                              const SpatialVector& relative, double* udot) {
    switch (joint.type) {
        case JointType::Free:
            Eigen::Map<Eigen::Vector3d>{udot} = R.transpose() * relative.head<3>();
            Eigen::Map<Eigen::Vector3d>{udot + 3} = R.transpose() * (relative.tail<3>() - p.cross(relative.head<3>()));
            break;
        case JointType::Ball: Eigen::Map<Eigen::Vector3d>{udot} = R.transpose() * relative.head<3>(); break;
        case JointType::Pin: udot[0] = R.col(2).dot(relative.head<3>()); break;
        case JointType::Weld: break;
    }
}

SpatialVector calcLinkVelocity(const Data& data, int link) {
    const std::size_t b = static_cast<std::size_t>(link);
    SpatialVector v;
    v.head<3>() = data.w_GB[b];
    v.tail<3>() = data.v_GB[b] - data.w_GB[b].cross(data.p_GB[b]);
    return v;
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

// Y = T (T^T W T)^+ T^T for a ball loop (T is 6 x 3). D is singular when the loop repeats constraints the
// subassembly already has (a ball loop off the axis of a hinge...); its pseudo-inverse then gives the
// least-squares (minimum-norm) force and exact accelerations. Returns the number of redundant directions;
// lowers `conditioning` to the smallest kept eigenvalue over the largest.
int calcLoopCompliance(const ConstraintBasis& T, const Matrix6d& W, Matrix6d& Y, double& conditioning) {
    const Eigen::Matrix<double, 6, 3> T3 = T;
    const Eigen::Matrix3d D = T3.transpose() * W * T3;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(D);
    const Eigen::Vector3d& values = eigen.eigenvalues();
    // Roundoff in the subassembly's Phi (differences of inverse inertias) leaves a redundant direction at
    // about 1e-15 of the largest eigenvalue; genuine directions of real models sit far above 1e-9.
    const double cutoff = 1e-9 * values.cwiseAbs().maxCoeff();
    Eigen::Matrix3d pseudoInverse = Eigen::Matrix3d::Zero();
    int redundant = 0;
    for (int i = 0; i < 3; ++i) {
        if (values[i] > cutoff) {
            pseudoInverse += eigen.eigenvectors().col(i) * eigen.eigenvectors().col(i).transpose() / values[i];
            conditioning = std::min(conditioning, values[i] / values.maxCoeff());
        } else {
            ++redundant;
        }
    }
    Y = T3 * pseudoInverse * T3.transpose();
    return redundant;
}

}  // namespace

ForwardDynamicsData::ForwardDynamicsData(const Model& model, const AssemblySchedule& schedule) {
    const std::size_t bodies = static_cast<std::size_t>(schedule.getNumBodies());
    inertia.assign(bodies, Matrix6d::Zero());
    inertiaInverse.assign(bodies, Matrix6d::Zero());
    velocity.assign(bodies, SpatialVector::Zero());
    bias.assign(bodies, SpatialVector::Zero());
    jointVelocity.assign(schedule.getJoints().size(), SpatialVector::Zero());
    jointBias.assign(schedule.getJoints().size(), SpatialVector::Zero());
    Phi.resize(static_cast<std::size_t>(schedule.getNumSubassemblies()));
    b.resize(Phi.size());
    for (std::size_t s = 0; s < Phi.size(); ++s) {
        const std::size_t h = schedule.getHandles(static_cast<int>(s)).size();
        Phi[s].assign(h * h, Matrix6d::Zero());
        b[s].assign(h, SpatialVector::Zero());
    }
    Y.assign(schedule.getOperations().size(), Matrix6d::Zero());
    g.assign(schedule.getOperations().size(), SpatialVector::Zero());
    handleForce.assign(2 * schedule.getJoints().size(), SpatialVector::Zero());
    udot = Eigen::VectorXd::Zero(model.getNumU());
    bodyAcceleration.assign(bodies, SpatialVector::Zero());
    loopForce.assign(static_cast<std::size_t>(model.getNumLoops()), Eigen::Vector3d::Zero());
}

void calcForwardDynamics(const Model& model, const AssemblySchedule& schedule, const Data& data,
                         const Eigen::VectorXd& tau, const std::vector<SpatialVector>& linkForces,
                         ForwardDynamicsData& fd) {
    const int numBodies = schedule.getNumBodies();
    const std::vector<AssemblyJoint>& joints = schedule.getJoints();

    // Bodies: inertia, velocity and bias force p = v x* I v - f_ext (docs/closed-chain.md, "Leaves").
    for (int body = 0; body < numBodies; ++body) {
        const std::size_t bb = static_cast<std::size_t>(body);
        Matrix6d& I = fd.inertia[bb];
        SpatialVector external = SpatialVector::Zero();
        I.setZero();
        for (int link : schedule.getLinksOfBody(body)) {
            const std::size_t l = static_cast<std::size_t>(link);
            const Link& info = model.getLink(link);
            const Eigen::Vector3d com_G = data.p_GB[l] + data.R_GB[l] * info.com_B;
            I += calcSpatialInertia(info.mass, com_G, data.R_GB[l] * info.inertia_Bcom * data.R_GB[l].transpose());
            const Eigen::Vector3d weight = info.mass * model.getGravity();
            external.head<3>() += com_G.cross(weight);
            external.tail<3>() += weight;
            external += linkForces[l];
        }
        fd.inertiaInverse[bb] = I.llt().solve(Matrix6d::Identity());
        fd.velocity[bb] = calcLinkVelocity(data, schedule.getLinksOfBody(body).front());
        fd.bias[bb] = crossForce(fd.velocity[bb], I * fd.velocity[bb]) - external;
        // Leaf: every handle of the body sees its inverse inertia; b = -I^-1 p.
        const SpatialVector leafB = -fd.inertiaInverse[bb] * fd.bias[bb];
        for (Matrix6d& block : fd.Phi[bb]) block = fd.inertiaInverse[bb];
        for (SpatialVector& v : fd.b[bb]) v = leafB;
    }
    // Ground: immovable, Phi = 0 and b = 0 (as initialised).
    auto velocityOf = [&](int body) {
        return body == kGroundBody ? SpatialVector::Zero().eval() : fd.velocity[static_cast<std::size_t>(body)];
    };

    // Joints: relative motion S u = v_beta - v_alpha and its bias c = dS/dt u = v_alpha x (S u), plus, for a
    // free joint, (R v_FM) x (R w_FM): its centre moves in the parent (docs/closed-chain.md, "Joints").
    for (std::size_t j = 0; j < joints.size(); ++j) {
        const AssemblyJoint& aj = joints[j];
        const SpatialVector vAlpha = velocityOf(aj.alphaBody);
        const SpatialVector relative = velocityOf(aj.betaBody) - vAlpha;
        fd.jointVelocity[j] = relative;
        fd.jointBias[j] = crossMotion(vAlpha, relative);
        if (!aj.isLoop && model.getJoint(aj.index).type == JointType::Free) {
            const Eigen::Vector3d& p = data.p_GM[static_cast<std::size_t>(aj.index)];
            const Eigen::Vector3d translation = relative.tail<3>() - p.cross(relative.head<3>());
            fd.jointBias[j].tail<3>() += translation.cross(relative.head<3>());
        }
    }

    // Geometry of an assembly joint: its type, joint-frame axes R and centre p in ground.
    struct JointGeometry {
        JointType type;
        Eigen::Matrix3d R;
        Eigen::Vector3d p;
        SpatialVector force;  // the joint's generalized forces as a spatial force on beta
    };
    auto geometryOf = [&](const AssemblyJoint& aj) {
        if (aj.isLoop) {
            const Loop& loop = model.getLoop(aj.index);
            const std::size_t a = static_cast<std::size_t>(loop.linkA);
            return JointGeometry{JointType::Ball, Eigen::Matrix3d::Identity(), data.p_GB[a] + data.R_GB[a] * loop.p_A,
                                 SpatialVector::Zero()};
        }
        const Joint& joint = model.getJoint(aj.index);
        const std::size_t l = static_cast<std::size_t>(aj.index);
        return JointGeometry{joint.type, data.R_GF[l], data.p_GM[l],
                             calcJointForce(joint, data.R_GF[l], data.p_GM[l], tau.data() + joint.uStart)};
    };

    // Assembly, tips to root (docs/closed-chain.md, "Join" and "Close").
    const std::vector<AssemblyOperation>& operations = schedule.getOperations();
    fd.redundantConstraints = 0;
    fd.loopConditioning = 1;
    for (std::size_t o = 0; o < operations.size(); ++o) {
        const AssemblyOperation& op = operations[o];
        const JointGeometry geometry = geometryOf(joints[static_cast<std::size_t>(op.joint)]);
        const ConstraintBasis T = calcConstraintBasis(geometry.type, geometry.R, geometry.p);
        const SpatialVector& c = fd.jointBias[static_cast<std::size_t>(op.joint)];
        Matrix6d& Y = fd.Y[o];
        SpatialVector& g = fd.g[o];
        std::vector<Matrix6d>& C = fd.Phi[static_cast<std::size_t>(op.result)];
        std::vector<SpatialVector>& bC = fd.b[static_cast<std::size_t>(op.result)];
        const std::vector<Matrix6d>& PA = fd.Phi[static_cast<std::size_t>(op.first)];
        const std::vector<SpatialVector>& bA = fd.b[static_cast<std::size_t>(op.first)];
        const int hA = static_cast<int>(bA.size());
        const int hC = static_cast<int>(bC.size());
        const int ia = op.alphaPosition;
        auto A = [&](int i, int k) -> const Matrix6d& { return PA[static_cast<std::size_t>(i * hA + k)]; };
        auto setC = [&](int i, int k, const Matrix6d& block) {
            C[static_cast<std::size_t>(i * hC + k)] = block;
            if (i != k) C[static_cast<std::size_t>(k * hC + i)] = block.transpose();
        };
        if (!op.isClose) {
            const std::vector<Matrix6d>& PB = fd.Phi[static_cast<std::size_t>(op.second)];
            const std::vector<SpatialVector>& bB = fd.b[static_cast<std::size_t>(op.second)];
            const int hB = static_cast<int>(bB.size());
            const int ib = op.betaPosition;
            auto B = [&](int i, int k) -> const Matrix6d& { return PB[static_cast<std::size_t>(i * hB + k)]; };
            // Positions in the result: A's handles but alpha, then B's but beta.
            auto inCfromA = [&](int k) { return k < ia ? k : k - 1; };
            auto inCfromB = [&](int k) { return hA - 1 + (k < ib ? k : k - 1); };
            const Matrix6d W = A(ia, ia) + B(ib, ib);
            calcJointCompliance(T, W, Y);
            g = geometry.force - Y * (W * geometry.force) - Y * (bB[static_cast<std::size_t>(ib)] - bA[static_cast<std::size_t>(ia)] - c);
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
        } else {
            const int ib = op.betaPosition;
            auto inC = [&](int k) { return k - (k > ia ? 1 : 0) - (k > ib ? 1 : 0); };
            const Matrix6d W = A(ia, ia) + A(ib, ib) - A(ia, ib) - A(ib, ia);
            fd.redundantConstraints += calcLoopCompliance(T, W, Y, fd.loopConditioning);
            g = -Y * (bA[static_cast<std::size_t>(ib)] - bA[static_cast<std::size_t>(ia)] - c);
            for (int h = 0; h < hA; ++h) {
                if (h == ia || h == ib) continue;
                const Matrix6d dY = (A(h, ib) - A(h, ia)) * Y;
                for (int k = h; k < hA; ++k)
                    if (k != ia && k != ib) setC(inC(h), inC(k), A(h, k) - dY * (A(ib, k) - A(ia, k)));
                bC[static_cast<std::size_t>(inC(h))] = bA[static_cast<std::size_t>(h)] + (A(h, ib) - A(h, ia)) * g;
            }
        }
    }

    // Disassembly, root to tips: the force through each joint, from the forces on the result's handles.
    for (std::size_t o = operations.size(); o-- > 0;) {
        const AssemblyOperation& op = operations[o];
        const std::vector<int>& handlesA = schedule.getHandles(op.first);
        const std::vector<Matrix6d>& PA = fd.Phi[static_cast<std::size_t>(op.first)];
        const int hA = static_cast<int>(handlesA.size());
        const int ia = op.alphaPosition;
        SpatialVector sum = SpatialVector::Zero();
        if (!op.isClose) {
            const std::vector<int>& handlesB = schedule.getHandles(op.second);
            const std::vector<Matrix6d>& PB = fd.Phi[static_cast<std::size_t>(op.second)];
            const int hB = static_cast<int>(handlesB.size());
            const int ib = op.betaPosition;
            for (int k = 0; k < hB; ++k)
                if (k != ib) sum += PB[static_cast<std::size_t>(ib * hB + k)] * fd.handleForce[static_cast<std::size_t>(handlesB[static_cast<std::size_t>(k)])];
            for (int k = 0; k < hA; ++k)
                if (k != ia) sum -= PA[static_cast<std::size_t>(ia * hA + k)] * fd.handleForce[static_cast<std::size_t>(handlesA[static_cast<std::size_t>(k)])];
        } else {
            const int ib = op.betaPosition;
            for (int k = 0; k < hA; ++k)
                if (k != ia && k != ib)
                    sum += (PA[static_cast<std::size_t>(ib * hA + k)] - PA[static_cast<std::size_t>(ia * hA + k)]) *
                           fd.handleForce[static_cast<std::size_t>(handlesA[static_cast<std::size_t>(k)])];
        }
        const SpatialVector f = fd.g[o] - fd.Y[o] * sum;
        fd.handleForce[static_cast<std::size_t>(2 * op.joint + 1)] = f;
        fd.handleForce[static_cast<std::size_t>(2 * op.joint)] = -f;
    }

    // Bodies: a = I^-1 (sum of handle forces - p); joints: udot from a_beta - a_alpha - c = S udot.
    for (int body = 0; body < numBodies; ++body) {
        SpatialVector total = -fd.bias[static_cast<std::size_t>(body)];
        for (int h : schedule.getHandles(body)) total += fd.handleForce[static_cast<std::size_t>(h)];
        fd.bodyAcceleration[static_cast<std::size_t>(body)] = fd.inertiaInverse[static_cast<std::size_t>(body)] * total;
    }
    auto accelerationOf = [&](int body) {
        return body == kGroundBody ? SpatialVector::Zero().eval() : fd.bodyAcceleration[static_cast<std::size_t>(body)];
    };
    for (std::size_t j = 0; j < joints.size(); ++j) {
        const AssemblyJoint& aj = joints[j];
        if (aj.isLoop) {
            fd.loopForce[static_cast<std::size_t>(aj.index)] = fd.handleForce[2 * j + 1].tail<3>();
            continue;
        }
        const Joint& joint = model.getJoint(aj.index);
        const std::size_t l = static_cast<std::size_t>(aj.index);
        extractJointAcceleration(joint, data.R_GF[l], data.p_GM[l],
                                 accelerationOf(aj.betaBody) - accelerationOf(aj.alphaBody) - fd.jointBias[j],
                                 fd.udot.data() + joint.uStart);
    }
}

}  // namespace sinew
