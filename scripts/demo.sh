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
