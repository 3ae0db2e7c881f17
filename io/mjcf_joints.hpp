#pragma once
// An MJCF body's joints as one sinew joint (docs/mjcf-import.md, "Joints"): none is a weld, a free joint
// a free joint, a ball a ball, and a sequence of slides then hinges one custom joint whose coordinates are
// MuJoCo's qpos of those joints. Private to sinew_io.
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "mjcf_document.hpp"
#include "sinew/core/model_builder.hpp"

namespace sinew::mjcf {

// The sinew link that carries what is fixed on body `body` (sites, wrap geoms, loop anchors): the body's
// link, or for the world body kWorldLink, a massless link welded to ground that the converter adds when
// something needs it (sinew attaches wires to links, not to ground).
constexpr const char* kWorldLink = "world";
std::string getLinkName(const MjcfModel& model, int body);

// The joint connecting body `body` (not the world) to its parent. A layout sinew cannot express (a hinge
// before a slide, hinges about different anchors, collinear hinges, a ball with other joints, a free joint
// below the top level) throws ModelError at the body naming its joints. Lines for `notImported`: a slide
// collinear with an earlier one and coupled by no equality (held at its ref), joint damping, stiffness,
// armature and friction.
JointSpec convertBodyJoints(const MjcfModel& model, int body, std::vector<std::string>& notImported);

// Each body's frame in the world at qpos0, where every joint sits at its ref: the bodies' own frames
// composed down the tree (index 0, the world, is the identity).
std::vector<Eigen::Isometry3d> calcRestPoses(const MjcfModel& model);

// Whether joint `joint` of body `body` became a coordinate (false for a collinear, uncoupled slide held at
// its ref).
bool isImportedJoint(const MjcfModel& model, int body, int joint);

}  // namespace sinew::mjcf
