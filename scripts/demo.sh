#!/usr/bin/env bash
# Sets up (packages, build), then runs the main job on the shipped default model: the arm hung by its
# shoulder girdle, swinging under gravity against its passive muscles for 1 s.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
out=build/demo
build/bin/sinew info models/arm26.yaml
build/bin/sinew simulate models/arm26.yaml --hang-by base --duration 1 -o "$out"
echo "demo: results in $(pwd)/$out"
