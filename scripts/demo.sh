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
/usr/bin/python3 scripts/plot_storage.py "$out/whole_body_energy.png" "$out/whole_body_energy.sto"
echo "demo: results (.sto tables of coordinates, speeds, 990 wire tensions and energy; the picture"
echo "      whole_body_energy.png) in $(pwd)/$out"
