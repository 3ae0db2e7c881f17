#pragma once
// A sinew custom joint (OpenSim's CustomJoint) in Simbody, two ways:
// - SimbodyMobilizer::Sinew (the default): a MobilizedBody::Custom whose X_FM, H and Hdot are core's
//   (sinew/core/custom_joint.hpp), exact for every layout of coordinates on axes.
// - SimbodyMobilizer::FunctionBased: Simbody's MobilizedBody::FunctionBased, as OpenSim's CustomJoint builds
//   it (CustomJoint::extendAddToSystem). Its Hdot takes the angular velocity of generalized speed 0 (and of
//   speeds 0 and 1) for the rates of the second (and third) rotation axis, which is exact only when speed k
//   drives rotation k; where one coordinate drives several rotations (Rajagopal 2015's knees), its dynamics
//   are off and do not conserve energy (docs/opensim-joints.md, "Simbody's FunctionBased mobilizer").
#include "sinew/plugin/ndebug_guard.hpp"

#include <Simbody.h>

#include "sinew/core/function.hpp"
#include "sinew/core/model.hpp"

namespace sinew {

enum class SimbodyMobilizer { Sinew, FunctionBased };

// A sinew::Function as a SimTK::Function of `argumentSize` (0 or 1) arguments, for Simbody's
// FunctionBased mobilizer (which asks for derivatives up to second order).
class SimbodyFunction : public SimTK::Function {
public:
    SimbodyFunction(sinew::Function function, int argumentSize);
    SimTK::Real calcValue(const SimTK::Vector& x) const override;
    SimTK::Real calcDerivative(const SimTK::Array_<int>& derivComponents, const SimTK::Vector& x) const override;
    int getArgumentSize() const override { return argumentSize_; }
    int getMaxDerivativeOrder() const override { return 2; }
    SimTK::Function* clone() const override { return new SimbodyFunction(*this); }

private:
    sinew::Function function_;
    int argumentSize_;
};

// Adds `joint` (JointType::Custom) between `parent` and a new body; returns the new body's index.
SimTK::MobilizedBodyIndex addCustomMobilizer(SimTK::MobilizedBody& parent, const SimTK::Transform& X_PF,
                                             const SimTK::Body& body, const SimTK::Transform& X_BM, const Joint& joint,
                                             SimbodyMobilizer kind = SimbodyMobilizer::Sinew);

}  // namespace sinew
