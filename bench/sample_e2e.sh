#!/usr/bin/env bash
# End to end: the 48-frame torus sample to SVG + PDF (multi-page) + PNG + JSON, several runs.
# Prints the wall time per frame of each run and the median per-stage times from the JSON stats.
#   bash bench/sample_e2e.sh [BUILD_DIR] [RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
runs=${2:-3}
inkline="$build/cli/inkline"
[ -x "$inkline" ] || { echo "build $inkline first (cmake --build $build)" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

echo "| run | frames | wall s | ms/frame |"
echo "| --- | ---: | ---: | ---: |"
for run in $(seq "$runs"); do
  rm -rf "$out/r"
  start=$(date +%s.%N)
  "$inkline" render samples/torus/scene.json -q -o "$out/r" --png "$out/r/png/f_%04d.png" --pdf "$out/r/sequence.pdf"
  end=$(date +%s.%N)
  python3 -c "print('| $run | 48 | %.2f | %.1f |' % (($end - $start), ($end - $start) * 1000 / 48))"
done

python3 - "$out/r/json" <<'PY'
import json, pathlib, statistics, sys
stages = {}
for f in sorted(pathlib.Path(sys.argv[1]).glob("*.json")):
    for stage, ms in json.load(open(f))["stats"]["ms"].items():
        stages.setdefault(stage, []).append(ms)
print("\n| stage (last run) | median ms/frame | max ms/frame |")
print("| --- | ---: | ---: |")
for stage, values in stages.items():
    print(f"| {stage} | {statistics.median(values):.2f} | {max(values):.2f} |")
print("\n(json writing itself is not in the stats; it is part of the wall time above)")
PY
