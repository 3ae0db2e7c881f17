#pragma once
// sinew's model as a MuJoCo MJCF file (readable by MuJoCo 2.2.2, Debian's, and later), so that MuJoCo can be
// timed and checked on the very model sinew runs (docs/mjcf-export.md):
// - each link a body whose frame is the link's joint frame M (so a ball joint's quaternion is MuJoCo's, up to
//   the default pose), with the link's mass, centre of mass and full inertia;
// - the bodies placed at the model's default pose, which is MuJoCo's qpos0: MuJoCo takes a `connect`
//   equality's second anchor from qpos0, and sinew's loops are closed there;
// - ball joints `ball`, pins `hinge` about M's z with `ref` = the default angle, welds no joint, the free root
//   `free`; loops `connect` equalities; polyline wires spatial tendons over one site per wire point, a
//   spring-damper's stiffness, damping and rest length as the tendon's stiffness, damping and springlength.
// What MuJoCo's model does differently is returned as notes (one line per kind, with counts); what MJCF
// cannot say (custom joints, free joints below the root, massless virtual links, couplers, wrapping,
// conditional and moving points) is refused with an Error naming the element.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "sinew/core/model.hpp"

namespace sinew {

struct MjcfExport {
    std::string text;                // the MJCF document
    std::vector<std::string> notes;  // how MuJoCo's model differs from sinew's, one line per kind
};

// Throws the Error writeMjcfText would for a model MJCF cannot say, without writing anything.
void requireMjcfWritable(const Model& model);
MjcfExport writeMjcfText(const Model& model);
// Writes the document to `path` (whole or not at all) and returns the notes.
std::vector<std::string> writeMjcfModel(const Model& model, const std::string& path);

// MuJoCo's qpos (nq: 7 free, 4 ball, 1 hinge) for sinew's q on the written model. MuJoCo orders joints as the
// document's bodies, depth first (children in link order), which need not be sinew's link order.
Eigen::VectorXd toMujocoQpos(const Model& model, const Eigen::VectorXd& q);
// A vector of sinew's speed space (speeds, accelerations or generalized forces, nu) at q, in MuJoCo's qvel
// coordinates (nv = nu): MuJoCo measures a ball's or free body's angular velocity in the moving body's frame
// (sinew in F) and a free body's linear velocity in the world (sinew in F). The change is a rotation per
// joint, so it maps forces as it maps speeds, and accelerations too (the rotation's rate meets w x w = 0).
Eigen::VectorXd toMujocoVelocity(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& u);
Eigen::VectorXd fromMujocoVelocity(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qvel);

}  // namespace sinew
