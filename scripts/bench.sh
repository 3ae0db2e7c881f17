#!/usr/bin/env bash
# Builds sinew (scripts/setup.sh), runs the benchmarks into build/benchmarks.json, and prints, per model, the
# sinew wire Jacobian and wire forces next to one Simbody forward-dynamics evaluation with the same wires.
# usage: scripts/bench.sh [google-benchmark args...]   e.g. --benchmark_min_time=0.2 --benchmark_filter=random
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh
build/bin/sinew_benchmarks --benchmark_out=build/benchmarks.json --benchmark_out_format=json "$@"

python3 - build/benchmarks.json <<'EOF'
import json
import sys
from collections import defaultdict

TO_US = {"ns": 1e-3, "us": 1.0, "ms": 1e3, "s": 1e6}
PEERS = [("WireJacobian/", "jacobian"), ("WireForces/", "forces"), ("ForwardDynamics/simbody/", "simbody")]

with open(sys.argv[1]) as f:
    runs = json.load(f)["benchmarks"]

# With --benchmark_repetitions every run appears several times: take the median aggregate when there is one,
# else the mean of the repetitions.
samples = defaultdict(list)
medians = {}
for run in runs:
    if run.get("error_occurred"):
        continue
    name = run.get("run_name", run["name"])
    time_us = run["real_time"] * TO_US[run["time_unit"]]
    if run.get("run_type") == "aggregate":
        if run.get("aggregate_name") == "median":
            medians[name] = time_us
    else:
        samples[name].append(time_us)
times = {name: sum(values) / len(values) for name, values in samples.items()}
times.update(medians)

models = []
for run in runs:
    for prefix, _ in PEERS:
        name = run.get("run_name", run["name"])
        if name.startswith(prefix) and name[len(prefix):] not in models:
            models.append(name[len(prefix):])

def show(value):
    return f"{value:12.2f}" if value is not None else f"{'-':>12}"

print()
print(f"{'model':<12}{'jacobian us':>12}{'forces us':>12}{'simbody us':>12}{'simbody/jac':>12}")
for model in models:
    t = {key: times.get(prefix + model) for prefix, key in PEERS}
    ratio = t["simbody"] / t["jacobian"] if t["simbody"] and t["jacobian"] else None
    print(f"{model:<12}{show(t['jacobian'])}{show(t['forces'])}{show(t['simbody'])}{show(ratio)}")
EOF
