#!/usr/bin/env bash
# Writes the fuzzers' seed corpora into DIR/<reader>/ from the shipped models and, where present, the
# OpenSim and MyoSuite examples in ../shared/data (not shipped, so never copied into the repository).
# usage: fuzz/make_corpus.sh DIR
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:?usage: fuzz/make_corpus.sh DIR}
shared=../shared/data
mkdir -p "$out"/{yaml_model,osim_model,storage_file,external_loads,tool_setup,mjcf_model,bvh_file,trc_file}

cp models/arm26.yaml "$out/yaml_model/arm26.yaml"
# The whole-body model is 1 MB: its first links and wires keep the seed small and still a model.
cat > "$out/yaml_model/pendulum.yaml" <<'YAML'
sinew_model: 1
name: pendulum
gravity: [0, -9.81, 0]
links:
  - {name: bob, mass: 1.0, com: [0, -0.5, 0], inertia: [0.01, 0.01, 0.01, 0, 0, 0]}
joints:
  - {name: hinge, type: pin, parent: ground, child: bob, axis: [0, 0, 1], initial_angle: 0.3}
wires:
  - name: w
    points:
      - {link: ground, at: [0.1, 0, 0]}
      - {link: bob, at: [0, -0.5, 0]}
    force_law: {type: spring_damper, stiffness: 100, damping: 1, rest_length: 0.4}
YAML

# Force elements and contact geometry (docs/force-elements.md).
cat > "$out/yaml_model/force_elements.yaml" <<'YAML'
sinew_model: 1
name: elements
links:
  - {name: block, mass: 20, com: [0, 0, 0], inertia: [0.2, 0.3, 0.25, 0.01, 0, 0.02]}
  - {name: foot, mass: 5, com: [0, -0.25, 0], inertia: [0.1, 0.02, 0.1, 0, 0, 0]}
joints:
  - {name: ground_block, type: free, parent: ground, child: block, initial_position: [0, 1.1, 0]}
  - {name: knee, type: pin, parent: block, child: foot, parent_point: [0, -0.5, 0], axis: [0, 0, 1]}
contact_geometry:
  - {name: floor, shape: half_space, link: ground, rotation: [0, 0, -1.5707963267948966]}
  - {name: heel, shape: sphere, link: foot, translation: [0, -0.5, 0], radius: 0.05}
force_elements:
  - {type: coordinate_limit, name: limit, coordinate: knee, upper_stiffness: 20, upper_limit: 0, lower_stiffness: 20, lower_limit: -2.4, damping: 1, transition: 0.09}
  - {type: point_to_point_spring, name: spring, link_a: block, point_a: [0.1, 0, 0], link_b: foot, point_b: [0, -0.2, 0], stiffness: 2000, rest_length: 0.8}
  - {type: bushing, name: hip, link_a: block, rotation_a: [0.1, 0.2, 0.3], link_b: foot, translation_b: [0, 0.5, 0], rotational_stiffness: [10, 12, 14], translational_damping: [1, 2, 3]}
  - {type: hunt_crossley, name: contact, transition_velocity: 0.1, surfaces: [{geometry: floor, stiffness: 1e7, dissipation: 0.5}, {geometry: heel, stiffness: 2e7, static_friction: 0.7}]}
YAML

cat > "$out/osim_model/tiny.osim" <<'XML'
<?xml version="1.0" encoding="UTF-8" ?>
<OpenSimDocument Version="40000">
  <Model name="tiny">
    <Ground name="ground"/>
    <gravity>0 -9.81 0</gravity>
    <BodySet name="bodyset"><objects>
      <Body name="a"><mass>1</mass><mass_center>0 -0.1 0</mass_center><inertia>0.1 0.1 0.1 0 0 0</inertia></Body>
    </objects></BodySet>
    <JointSet name="jointset"><objects>
      <PinJoint name="pin"><socket_parent_frame>/ground</socket_parent_frame><socket_child_frame>/bodyset/a</socket_child_frame>
        <coordinates><Coordinate name="q"><default_value>0.2</default_value><range>-1 1</range></Coordinate></coordinates>
      </PinJoint>
    </objects></JointSet>
    <ForceSet name="forceset"><objects>
      <Thelen2003Muscle name="m"><max_isometric_force>100</max_isometric_force><optimal_fiber_length>0.1</optimal_fiber_length>
        <tendon_slack_length>0.1</tendon_slack_length><min_control>-Inf</min_control>
        <GeometryPath name="path"><PathPointSet><objects>
          <PathPoint name="p1"><socket_parent_frame>/ground</socket_parent_frame><location>0.05 0 0</location></PathPoint>
          <PathPoint name="p2"><socket_parent_frame>/bodyset/a</socket_parent_frame><location>0 -0.1 0</location></PathPoint>
        </objects></PathPointSet></GeometryPath>
      </Thelen2003Muscle>
    </objects></ForceSet>
  </Model>
</OpenSimDocument>
XML

printf 'tiny\nversion=1\nnRows=3\nnColumns=3\ninDegrees=yes\nendheader\ntime\tq\tu\n0\t1\t2\n0.01\t1.5\t\n0.02\tnan\t3e-310\n' \
  > "$out/storage_file/tiny.mot"
printf 'DataType=double\nversion=3\nOpenSimVersion=4.4\nendheader\ntime q u\n0 1 2\n1 2 3\n' > "$out/storage_file/v3.sto"

cat > "$out/tool_setup/id.xml" <<'XML'
<?xml version="1.0" encoding="UTF-8" ?>
<OpenSimDocument Version="30000">
  <InverseDynamicsTool name="id">
    <results_directory>out</results_directory><model_file>m.osim</model_file>
    <time_range>0 1</time_range><coordinates_file>q.mot</coordinates_file>
    <lowpass_cutoff_frequency_for_coordinates>6</lowpass_cutoff_frequency_for_coordinates>
    <output_gen_force_file>id.sto</output_gen_force_file>
  </InverseDynamicsTool>
</OpenSimDocument>
XML

cat > "$out/mjcf_model/tiny.xml" <<'XML'
<mujoco model="tiny">
  <default><joint damping="0.1"/><geom size="0.02"/></default>
  <worldbody>
    <body name="upper" pos="0 0 1">
      <inertial pos="0 0 -0.1" mass="1" diaginertia="0.01 0.01 0.001"/>
      <joint name="shoulder" type="hinge" axis="0 1 0" range="-90 90"/>
      <site name="s1" pos="0.02 0 0"/>
      <body name="lower" pos="0 0 -0.3">
        <inertial pos="0 0 -0.1" mass="0.5" diaginertia="0.005 0.005 0.0005"/>
        <joint name="elbow" type="hinge" axis="0 1 0" range="0 150"/>
        <site name="s2" pos="0.02 0 -0.05"/>
      </body>
    </body>
  </worldbody>
  <tendon><spatial name="t"><site site="s1"/><site site="s2"/></spatial></tendon>
  <actuator><muscle name="m" tendon="t"/></actuator>
</mujoco>
XML

if [ -d "$shared/opensim" ]; then
  cp "$shared/opensim/arm26/arm26.osim" "$out/osim_model/"
  cp "$shared/opensim/arm26/arm26_InverseKinematics.mot" "$shared/opensim/gait2354/subject01_walk1_grf.mot" \
     "$shared/opensim/arm26/arm26_StaticOptimization_force.sto" "$out/storage_file/"
  cp "$shared/opensim/arm26/"*Setup*.xml "$shared/opensim/gait2354/"*Setup*.xml "$out/tool_setup/"
  # The data file by its absolute path: the fuzzer's input lives in /tmp, away from the example.
  sed "s#<datafile>[^<]*</datafile>#<datafile>$(realpath "$shared/opensim/gait2354/subject01_walk1_grf.mot")</datafile>#" \
    "$shared/opensim/gait2354/subject01_walk1_grf.xml" > "$out/external_loads/grf.xml"
else
  echo "make_corpus: $shared/opensim is absent; the corpora hold the built-in seeds only" >&2
fi
if [ -d "$shared/myo_sim" ]; then cp "$shared/myo_sim/basic/myomuscle.xml" "$out/mjcf_model/"; fi
# Limits, springs, a bushing on an offset frame, Hunt-Crossley contact; and Millard muscles.
for model in BouncingBlock/bouncing_block.osim Tug_of_War/Tug_of_War_Millard.osim; do
  if [ -f "$shared/opensim-models/Models/$model" ]; then cp "$shared/opensim-models/Models/$model" "$out/osim_model/"; fi
done
# ExternalLoads without a data file still exercises the XML side.
cat > "$out/external_loads/nodata.xml" <<'XML'
<?xml version="1.0" encoding="UTF-8" ?>
<OpenSimDocument Version="30000">
  <ExternalLoads name="loads"><objects>
    <ExternalForce name="f"><applied_to_body>a</applied_to_body><force_expressed_in_body>ground</force_expressed_in_body>
      <point_expressed_in_body>ground</point_expressed_in_body><force_identifier>f_v</force_identifier>
      <point_identifier>f_p</point_identifier></ExternalForce>
  </objects><datafile>/nonexistent.mot</datafile></ExternalLoads>
</OpenSimDocument>
XML
printf 'PathFileType\t4\t(X/Y/Z)\tsmall.trc\nDataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\tOrigDataRate\tOrigDataStartFrame\tOrigNumFrames\n100.00\t100.00\t2\t2\tmm\t100.00\t1\t2\nFrame#\tTime\tA\t\t\tB\t\t\n\t\tX1\tY1\tZ1\tX2\tY2\tZ2\n\n1\t0.00\t1234.5\t-20.25\t7\t0.5\t1\t2\n2\t0.01\t1235\t-20\t7\t\t\t\n' \
  > "$out/trc_file/small.trc"
cat > "$out/bvh_file/small.bvh" <<'BVH'
HIERARCHY
ROOT hip
{
  OFFSET 0 0 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
  JOINT knee
  {
    OFFSET 0 -10 0
    CHANNELS 3 Zrotation Xrotation Yrotation
    End Site
    {
      OFFSET 0 -10 0
    }
  }
}
MOTION
Frames: 2
Frame Time: 0.0083333
0 30 0 0 0 0 10 0 0
1 30 0 5 0 0 12 0 0
BVH
# The CMU take's hierarchy and first frames (the whole take is 775 kB).
if [ -f "$shared/cmu_mocap/11_01.bvh" ]; then
  awk '/^Frames:/ {print "Frames: 20"; next} {print} /^Frame Time:/ {n = 1; next} n && ++k >= 20 {exit}' \
    "$shared/cmu_mocap/11_01.bvh" > "$out/bvh_file/cmu_11_01_head.bvh"
fi
echo "make_corpus: seeds in $out"
