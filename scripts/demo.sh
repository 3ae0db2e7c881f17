#!/usr/bin/env bash
# Sets up (packages, build), then runs the main job on the shipped default model: the arm hung by its
# shoulder girdle, swinging under gravity against its passive muscles for 1 s.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
out=build/demo
build/bin/sinew info models/arm26.yaml
build/bin/sinew simulate models/arm26.yaml --hang-by base --duration 1 -o "$out"
/usr/bin/python3 scripts/plot_storage.py "$out/arm26.png" "$out/arm26_tensions.sto" "$out/arm26_coordinates.sto" \
  "$out/arm26_energy.sto"
echo "demo: results (.sto tables and the picture arm26.png) in $(pwd)/$out"
