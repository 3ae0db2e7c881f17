#!/usr/bin/env python3
"""Writes models/arm26.yaml, sinew's default model, from OpenSim's arm26.osim (opensim-models; the model's
credits: the OpenSim team after Holzbaur et al. 2005, CC BY 3.0).

The numbers (masses, inertias, joint centres, muscle path points, muscle parameters) are OpenSim's; the
modelling choices are sinew's and documented in docs/models.md:
- base is welded to ground as in arm26; the shoulder (a 1-coordinate CustomJoint in arm26) becomes a ball
  joint; the elbow becomes a pin about arm26's elbow axis;
- each Thelen2003Muscle becomes a passive spring-damper wire through its path points (wrap objects are
  not part of sinew's via-point wires): rest length = optimal fibre length + tendon slack length,
  stiffness = max isometric force / optimal fibre length, damping = 1% of that stiffness per second;
- initial pose: shoulder elevated 45 degrees about arm26's elevation axis, elbow flexed 60 degrees, so the
  hang simulation swings.

usage: scripts/convert_arm26.py ../shared/data/opensim/arm26/arm26.osim models/arm26.yaml
"""
import math
import sys
import xml.etree.ElementTree as ET


def numbers(text):
    return [float(x) for x in text.split()]


def vec(values):
    return "[" + ", ".join(repr(round(v, 12)) for v in values) + "]"


def offset_frame(joint, name):
    for frame in joint.iter("PhysicalOffsetFrame"):
        if frame.get("name") == name:
            if any(numbers(frame.find("orientation").text)):
                raise SystemExit(f"frame {name}: rotated offset frames are not handled by this converter")
            return frame.find("socket_parent").text.split("/")[-1], numbers(frame.find("translation").text)
    raise SystemExit(f"frame {name} not found in joint {joint.get('name')}")


def joint_frames(joint):
    parent_body, parent_point = offset_frame(joint, joint.find("socket_parent_frame").text)
    child_body, child_point = offset_frame(joint, joint.find("socket_child_frame").text)
    return parent_body, parent_point, child_body, child_point


def first_axis(joint):
    return numbers(joint.find(".//TransformAxis/axis").text)


def main(src, dst):
    root = ET.parse(src).getroot()
    model = root.find("Model")
    gravity = numbers(model.find("gravity").text)
    out = ["# sinew model converted by scripts/convert_arm26.py from OpenSim's arm26.osim (opensim-org/opensim-models;",
           "# model credits: OpenSim team after Holzbaur et al. 2005, CC BY 3.0). docs/models.md says what changed and why.",
           "sinew_model: 1", "name: arm26", f"gravity: {vec(gravity)}", "links:"]
    for body in model.find("BodySet/objects").findall("Body"):
        inertia = numbers(body.find("inertia").text)
        out.append(f"  - {{name: {body.get('name')}, mass: {float(body.find('mass').text)!r}, "
                   f"com: {vec(numbers(body.find('mass_center').text))}, inertia: {vec(inertia)}}}")
    joints = model.find("JointSet/objects")
    weld = joints.find("WeldJoint")
    parent, p_parent, child, p_child = joint_frames(weld)
    out += ["joints:",
            f"  - {{name: {weld.get('name')}, type: weld, parent: {parent}, child: {child}, "
            f"parent_point: {vec(p_parent)}, child_point: {vec(p_child)}}}"]
    for joint in joints.findall("CustomJoint"):
        parent, p_parent, child, p_child = joint_frames(joint)
        axis = first_axis(joint)
        norm = math.sqrt(sum(a * a for a in axis))
        axis = [a / norm for a in axis]
        if joint.get("name") == "r_shoulder":
            rotation = [math.radians(45) * a for a in axis]
            out.append(f"  - {{name: {joint.get('name')}, type: ball, parent: {parent}, child: {child}, "
                       f"parent_point: {vec(p_parent)}, child_point: {vec(p_child)}, "
                       f"initial_rotation: {vec(rotation)}}}")
        else:
            out.append(f"  - {{name: {joint.get('name')}, type: pin, parent: {parent}, child: {child}, "
                       f"parent_point: {vec(p_parent)}, child_point: {vec(p_child)}, axis: {vec(axis)}, "
                       f"initial_angle: {math.radians(60)!r}}}")
    out.append("wires:")
    for muscle in model.find("ForceSet/objects"):
        if not muscle.tag.endswith("Muscle"):
            continue
        fmax = float(muscle.find("max_isometric_force").text)
        lopt = float(muscle.find("optimal_fiber_length").text)
        lslack = float(muscle.find("tendon_slack_length").text)
        stiffness = fmax / lopt
        out += [f"  - name: {muscle.get('name')}", "    kind: muscle", "    points:"]
        for point in muscle.find("GeometryPath/PathPointSet/objects"):
            if point.tag != "PathPoint":
                raise SystemExit(f"{muscle.get('name')}: unsupported path point {point.tag}")
            body = point.find("socket_parent_frame").text.split("/")[-1]
            out.append(f"      - {{link: {body}, at: {vec(numbers(point.find('location').text))}}}")
        out.append(f"    force_law: {{type: spring_damper, stiffness: {round(stiffness, 6)!r}, "
                   f"damping: {round(0.01 * stiffness, 6)!r}, rest_length: {round(lopt + lslack, 6)!r}}}")
    with open(dst, "w") as f:
        f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    main(sys.argv[1], sys.argv[2])
