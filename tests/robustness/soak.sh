#!/usr/bin/env bash
# Soak test (issue 15): 10,000 frames of tensions on gait2354 and a 60 s simulated hang of arm26, each with
# its resident memory sampled through the run; passes when the RSS at the end (the last sample) exceeds the
# RSS a quarter into the run (past the motion's preprocessing, into the frames) by at most 5 %: nothing
# grows per frame beyond the result tables themselves. Needs ../shared/data/opensim for gait2354 (skipped otherwise).
# usage: tests/robustness/soak.sh [BUILD_DIR]   (default build)
set -euo pipefail
cd "$(dirname "$0")/../.."
sinew=${1:-build}/bin/sinew
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
status=0

# Runs the command, sampling VmRSS every 0.05 s; prints the early and late samples and their ratio.
soak() {
  local name=$1
  shift
  "$@" >"$work/$name.log" 2>&1 &
  local pid=$! samples=()
  while kill -0 "$pid" 2>/dev/null; do
    rss=$(awk '/^VmRSS/ {print $2}' "/proc/$pid/status" 2>/dev/null || true)
    [ -n "$rss" ] && samples+=("$rss")
    sleep 0.05
  done
  wait "$pid" || { echo "soak $name: the command failed"; tail -3 "$work/$name.log"; status=1; return; }
  local n=${#samples[@]} early late
  ((n >= 10)) || { echo "soak $name: too short to sample ($n samples)"; return; }
  early=${samples[$((n / 4))]}
  late=${samples[$((n - 1))]}
  python3 -c "import sys; e,l=$early,$late; r=l/e; print(f'soak $name: {$n} samples, RSS early {e/1024:.1f} MiB, late {l/1024:.1f} MiB, ratio {r:.3f}'); sys.exit(0 if r <= 1.05 else 1)" \
    || status=1
}

gait=../shared/data/opensim/gait2354
if [ -d "$gait" ]; then
  # 10,000 rows: the walk's 73 rows cycled with continuing times (the step between cycles is the row step).
  python3 - "$gait/subject01_walk1_ik.mot" "$work/walk10000.mot" <<'PY'
import sys
lines = open(sys.argv[1]).read().split('\n')
end = next(i for i, l in enumerate(lines) if l.strip() == 'endheader')
labels = lines[end + 1]
rows = [l.split('\t') if '\t' in l else l.split() for l in lines[end + 2:] if l.strip()]
step = float(rows[1][0]) - float(rows[0][0])
out = ['walk x 10000', 'version=1', 'nRows=10000', 'nColumns=%d' % len(rows[0]), 'inDegrees=yes', 'endheader', labels]
for k in range(10000):
    r = rows[k % len(rows)]
    out.append('\t'.join(['%.6f' % (k * step)] + r[1:]))
open(sys.argv[2], 'w').write('\n'.join(out) + '\n')
PY
  soak gait2354_tensions_10000 "$sinew" tensions "$gait/subject01_simbody.osim" "$work/walk10000.mot" --method lp \
    -o "$work/tensions.sto"
  echo "  $(grep -m1 'frames' "$work/gait2354_tensions_10000.log")"
else
  echo "soak: $gait is absent; the gait2354 tensions soak is skipped"
fi
# Frames every 0.1 s: the result tables (336 bytes a frame) stay small beside what the integration holds.
soak arm26_hang_60s "$sinew" simulate models/arm26.yaml --hang-by base --duration 60 --interval 0.1 -o "$work/hang"
echo "  $(grep -m1 'frames' "$work/arm26_hang_60s.log")"
exit $status
