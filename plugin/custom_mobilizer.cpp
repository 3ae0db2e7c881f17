#include "sinew/plugin/custom_mobilizer.hpp"

#include "eigen_simtk.hpp"
#include "sinew/core/custom_joint.hpp"
#include "sinew/core/data.hpp"

namespace sinew {
namespace {

SimTK::SpatialVec toSpatialVec(const SpatialVector& v) {
    return {SimTK::Vec3(v[0], v[1], v[2]), SimTK::Vec3(v[3], v[4], v[5])};
}

SpatialVector toSpatialVector(const SimTK::SpatialVec& v) {
    SpatialVector out;
    out << v[0][0], v[0][1], v[0][2], v[1][0], v[1][1], v[1][2];
    return out;
}

// qdot = u for a custom joint's coordinates: the default N = 1 of MobilizedBody::Custom holds.
class SinewCustomMobilizer : public SimTK::MobilizedBody::Custom::Implementation {
public:
    SinewCustomMobilizer(SimTK::SimbodyMatterSubsystem& matter, Joint joint)
        : Implementation(matter, joint.nu, joint.nq), joint_(std::move(joint)) {}
    Implementation* clone() const override { return new SinewCustomMobilizer(*this); }

    SimTK::Transform calcMobilizerTransformFromQ(const SimTK::State&, int, const SimTK::Real* q) const override {
        Eigen::Matrix3d R_FM;
        Eigen::Vector3d p_FM;
        JointMotion H_FM;
        calcCustomJointTransform(joint_, q, R_FM, p_FM, H_FM);
        return SimTK::Transform(toRotation(R_FM), toVec3(p_FM));
    }
    SimTK::SpatialVec multiplyByHMatrix(const SimTK::State& s, int nu, const SimTK::Real* u) const override {
        return toSpatialVec(calcH(s) * Eigen::Map<const Eigen::VectorXd>(u, nu));
    }
    void multiplyByHTranspose(const SimTK::State& s, const SimTK::SpatialVec& F, int nu, SimTK::Real* f) const override {
        Eigen::Map<Eigen::VectorXd>(f, nu) = calcH(s).transpose() * toSpatialVector(F);
    }
    SimTK::SpatialVec multiplyByHDotMatrix(const SimTK::State& s, int nu, const SimTK::Real* u) const override {
        return toSpatialVec(calcHDot(s) * Eigen::Map<const Eigen::VectorXd>(u, nu));
    }
    void multiplyByHDotTranspose(const SimTK::State& s, const SimTK::SpatialVec& F, int nu, SimTK::Real* f) const override {
        Eigen::Map<Eigen::VectorXd>(f, nu) = calcHDot(s).transpose() * toSpatialVector(F);
    }

private:
    JointMotion calcH(const SimTK::State& s) const {
        const SimTK::Vector q = getQ(s);
        Eigen::Matrix3d R_FM;
        Eigen::Vector3d p_FM;
        JointMotion H_FM;
        calcCustomJointTransform(joint_, &q[0], R_FM, p_FM, H_FM);
        return H_FM;
    }
    JointMotion calcHDot(const SimTK::State& s) const {
        const SimTK::Vector q = getQ(s), u = getU(s);
        JointMotion HDot_FM;
        calcCustomJointHDot(joint_, &q[0], &u[0], HDot_FM);
        return HDot_FM;
    }

    Joint joint_;
};

SimTK::MobilizedBodyIndex addFunctionBasedMobilizer(SimTK::MobilizedBody& parent, const SimTK::Transform& X_PF,
                                                    const SimTK::Body& body, const SimTK::Transform& X_BM,
                                                    const Joint& joint) {
    SimTK::Array_<const SimTK::Function*> functions;  // FunctionBased takes ownership
    SimTK::Array_<SimTK::Array_<int>> coordinateIndices;
    SimTK::Array_<SimTK::Vec3> axes;
    for (const TransformAxis& axis : joint.transformAxes) {
        const bool driven = axis.coordinate != kNoCoordinate;
        functions.push_back(new SimbodyFunction(axis.function, driven ? 1 : 0));
        coordinateIndices.push_back(driven ? SimTK::Array_<int>(1, axis.coordinate) : SimTK::Array_<int>());
        axes.push_back(SimTK::Vec3(axis.axis[0], axis.axis[1], axis.axis[2]));
    }
    return SimTK::MobilizedBody::FunctionBased(parent, X_PF, body, X_BM, joint.nu, functions, coordinateIndices, axes)
        .getMobilizedBodyIndex();
}

}  // namespace

SimbodyFunction::SimbodyFunction(sinew::Function function, int argumentSize)
    : function_(std::move(function)), argumentSize_(argumentSize) {}

SimTK::Real SimbodyFunction::calcValue(const SimTK::Vector& x) const {
    return function_.calcValue(argumentSize_ > 0 ? x[0] : 0.0);
}

// derivComponents lists the argument differentiated for each order; with one argument only its length counts.
SimTK::Real SimbodyFunction::calcDerivative(const SimTK::Array_<int>& derivComponents, const SimTK::Vector& x) const {
    if (argumentSize_ == 0) return 0.0;
    return function_.calcDerivative(x[0], static_cast<int>(derivComponents.size()));
}

SimTK::MobilizedBodyIndex addCustomMobilizer(SimTK::MobilizedBody& parent, const SimTK::Transform& X_PF,
                                             const SimTK::Body& body, const SimTK::Transform& X_BM, const Joint& joint,
                                             SimbodyMobilizer kind) {
    if (kind == SimbodyMobilizer::FunctionBased) return addFunctionBasedMobilizer(parent, X_PF, body, X_BM, joint);
    return SimTK::MobilizedBody::Custom(parent, new SinewCustomMobilizer(parent.updMatterSubsystem(), joint), X_PF, body,
                                        X_BM)
        .getMobilizedBodyIndex();
}

}  // namespace sinew
