#pragma once
// A sinew custom joint as Simbody's MobilizedBody::FunctionBased, built the way OpenSim's CustomJoint builds
// it (CustomJoint::extendAddToSystem): the six transform axes' functions, each taking the one coordinate it
// names (or none), with the joint's axes. docs/opensim-joints.md.
#include "sinew/plugin/ndebug_guard.hpp"

#include <Simbody.h>

#include "sinew/core/function.hpp"
#include "sinew/core/model.hpp"

namespace sinew {

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
                                             const SimTK::Body& body, const SimTK::Transform& X_BM, const Joint& joint);

}  // namespace sinew
