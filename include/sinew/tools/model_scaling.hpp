#pragma once
// A model scaled to a subject, segment by segment, as OpenSim's ScaleTool scales one (docs/inverse-kinematics.md,
// "Scaling to the subject"): every length fixed in a link's frame is multiplied by that link's factor, its
// mass is kept and its inertia scaled by the factor squared (a body of the same mass, stretched uniformly);
// wire force laws' lengths follow their path's change of length at the default pose.
#include <vector>

#include "sinew/core/model.hpp"

namespace sinew {

// factors: one per link (model.getNumLinks(); virtual links' entries are not read), each > 0.
//
// Scaled per link B by s_B: its centre of mass, its joint's child point and its children's parent points,
// its wire points, wrap objects (centre, radius, length, radii), loop points, side sites and sole vertices;
// inertia by s_B^2, a free root's default position by its own factor. A virtual link's default position is
// kept where it was relative to the link of the nearest wire point next to it. Force-law parameters named
// `*_length` (a spring's rest length, a muscle's optimal fibre and tendon slack lengths) are multiplied by
// the ratio of the wire's length after and before, at the default pose, as OpenSim's Muscle::postScale does.
// Throws sinew::Error for a factor that is not finite and positive, a wrong count, a custom joint with a
// translation or a moving wire point (lengths given as functions, which a factor cannot scale).
Model scaleModel(const Model& model, const std::vector<double>& factors);

}  // namespace sinew
