#!/usr/bin/env bash
# Builds sinew (scripts/setup.sh), runs the benchmarks into build/benchmarks.json and the tension ones into
# build/tension_benchmarks.json, then pairs sinew with Simbody per model and fits the scaling slopes
# (scripts/plot_scaling.py), and plots them (sinew plot -> build/forward_dynamics_scaling_<variant>.png).
# docs/performance.md has the numbers of the last full run.
# usage: scripts/bench.sh [google-benchmark args...]   e.g. --benchmark_filter=wholebody
# Arguments come after the defaults below and override them. A full run takes about 10 minutes on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh
# The CPU's name goes into the JSON's context (Google Benchmark records only its count and clock).
cpu_model=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1 | tr -d ',=')
# Three repetitions of at least 0.2 s each; plot_scaling.py takes the fastest, the one least disturbed by
# other work on the machine, and names the benchmarks whose repetitions disagree by more than 10%.
build/bin/sinew_benchmarks --benchmark_out=build/benchmarks.json --benchmark_out_format=json \
  --benchmark_context="cpu_model=${cpu_model:-unknown}" \
  --benchmark_min_time=0.2 --benchmark_repetitions=3 --benchmark_display_aggregates_only=true "$@"
# Tension distribution and whole frames of tensions from motion (docs/tensions-from-motion.md), same settings.
build/bin/tension_benchmarks --benchmark_out=build/tension_benchmarks.json --benchmark_out_format=json \
  --benchmark_context="cpu_model=${cpu_model:-unknown}" \
  --benchmark_min_time=0.2 --benchmark_repetitions=3 --benchmark_display_aggregates_only=true "$@"

# The tables, slopes and targets (Debian's Python); the scaling curves, one plot per variant, by sinew plot.
/usr/bin/python3 scripts/plot_scaling.py build/benchmarks.json --png ''
for variant in 'bare:[0-9]$' 'loops:[0-9]_loops$' 'wires:[0-9]_wires$' 'loops_wires:_loops_wires$'; do
  build/bin/sinew plot --benchmark build/benchmarks.json --filter "^ForwardDynamics/.*${variant#*:}" \
    --title "one forward-dynamics evaluation, ${variant%%:*}" -o "build/forward_dynamics_scaling_${variant%%:*}.png"
done
