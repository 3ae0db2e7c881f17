#!/usr/bin/env bash
# Sets up (packages, build), then runs the main job on the shipped default model: the paper's section 4.1
# experiment, sinew's whole-body wire model (models/whole_body, docs/whole-body-model.md) hung by the head for
# 1 s under gravity against its passive spring-damper wires, with sinew's O(N) engine.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
out=build/demo
build/bin/sinew info models/whole_body/whole_body.yaml
build/bin/sinew simulate models/whole_body/whole_body.yaml --engine sinew --integrator rk4 --step 1e-4 \
  --hang-by head_neck --duration 1 --interval 0.01 -o "$out"
build/bin/sinew plot "$out/whole_body_energy.sto" --ylabel "energy (J)" -o "$out/whole_body_energy.png"
echo "demo: results (.sto tables of coordinates, speeds, 990 wire tensions and energy; the picture"
echo "      whole_body_energy.png) in $(pwd)/$out"
# The paper's Fig. 9 analogue: six frames of the hang, the wires coloured by the tensions the run wrote.
build/bin/sinew render models/whole_body/whole_body.yaml --motion "$out/whole_body_coordinates.sto" \
  --tensions "$out/whole_body_tensions.sto" --strip 6 --view front -o "$out/whole_body_hang_strip.png"
echo "demo: the hang strip (paper's Fig. 9) in $(pwd)/$out/whole_body_hang_strip.png"

# The paper's section 4.2: the motion-captured kick (CMU subject 11, trial 1, "soccer - kick ball"), fitted by
# sinew's BVH inverse kinematics on the whole-body model scaled to the subject (models/whole_body/
# kick_11_01.mot and whole_body_subject11.yaml, docs/motion-capture.md), then inverse dynamics and the wire
# tensions by the LP and by the QP, the feet's ground contact solved with them (docs/tensions-from-motion.md).
# The tensions are bounded below only, as in the paper's LP and QP (--max-tension 1e6 N); the run covers
# the kick itself, 3.30 to 3.50 s (the support foot landing, the ball struck at 3.35 s, the follow-through):
# the whole motion takes minutes (docs/results.md).
kick=build/demo/kick
subject=models/whole_body/whole_body_subject11.yaml
motion=models/whole_body/kick_11_01.mot
window=(--lowpass 6 --start 3.3 --end 3.5)
bvh=../shared/data/cmu_mocap/11_01.bvh
if [ -f "$bvh" ]; then
  echo "demo: the kick's fit, its first 0.1 s again (the shipped motion fitted all 598 frames)"
  build/bin/sinew ik models/whole_body/whole_body.yaml "$bvh" --end 0.1 -o "$kick/kick_ik_check.mot"
else
  echo "demo: $bvh is absent; the shipped kick's fit: joint-centre RMS median 1.03 cm, largest 1.75 cm (docs/motion-capture.md)"
fi
build/bin/sinew inverse-dynamics "$subject" "$motion" "${window[@]}" -o "$kick/kick_inverse_dynamics.sto"
build/bin/sinew tensions "$subject" "$motion" --method lp,qp --max-tension 1e6 "${window[@]}" -o "$kick/kick.sto"
echo "paper (Table 2, 2 GHz Pentium IV): lp 0.375 s/frame, Z 8,622 N^2; qp 27.25 s/frame, Z 2,339 N^2"
# The paper's Fig. 10 analogue: the moment of the strike, and the kick to play in a browser.
# The colour scale tops at 2 kN: at the strike the LP drives a few wires to its 1e6 N bound.
build/bin/sinew render "$subject" --motion "$motion" --tensions "$kick/kick_lp.sto" --time 3.35 --max-tension 2000 \
  -o "$kick/kick_lp.png"
build/bin/sinew render "$subject" --motion "$motion" --tensions "$kick/kick_lp.sto" --start 3.3 --end 3.5 --max-tension 2000 \
  -o "$kick/kick_lp.html"
echo "demo: the kick's tables (tensions, reports, contact, joint loads, ligament stress per method) and pictures"
echo "      (kick_lp.png, the paper's Fig. 10; kick_lp.html, the kick to play) in $(pwd)/$kick"
