#!/usr/bin/env bash
# Fuzzes the scene parser and the mesh readers with libFuzzer (clang) under ASan + UBSan, for a
# bounded time per target. New inputs join tests/fuzz/corpus/<target>/ (merged: only inputs that
# add coverage); a crash is saved there too (as crash-*), so tests/fuzz/replay_test.cpp keeps it
# as a regression test.
#   bash tests/fuzz/run.sh [seconds per target, default 600] [targets, default: scene mesh gltf mesh_arrays obj off ply stl]
# Targets: scene (the scene parser), mesh (any reader, picked by the first byte), and obj, off,
# ply, stl (one reader each). FUZZ_JOBS=N runs N targets at once (default 1).
# Needs clang-14 and libclang-rt-14-dev (Debian); it installs nothing itself.
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=${1:-600}
targets=${2:-scene mesh gltf mesh_arrays obj off ply stl}
jobs=${FUZZ_JOBS:-1}

if ! command -v clang++-14 >/dev/null; then
  echo "fuzz: clang++-14 not found; install clang-14 libclang-rt-14-dev" >&2
  exit 1
fi
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DINKLINE_BUILD_FUZZ=ON -DINKLINE_SANITIZE=ON "${launcher[@]}" \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link" >/dev/null
build_targets=()
for target in $targets; do build_targets+=("inkline_${target}_fuzz"); done
cmake --build build-fuzz -j "$(nproc)" --target "${build_targets[@]}"

fuzz_one() {
  local target=$1 work
  work=$(mktemp -d)
  mkdir -p "tests/fuzz/corpus/$target"
  echo "== fuzzing $target for ${seconds}s (log: build-fuzz/$target.log) =="
  # New interesting inputs go to a scratch folder; the minimised set is merged into the corpus.
  # -timeout: an input that takes 10 s is a hang, saved like a crash.
  local status=0
  ./build-fuzz/tests/fuzz/inkline_${target}_fuzz -max_total_time="$seconds" -max_len=4096 -timeout=10 \
      -artifact_prefix="tests/fuzz/corpus/$target/" -print_final_stats=1 "$work" "tests/fuzz/corpus/$target" \
      >"build-fuzz/$target.log" 2>&1 || status=1
  grep -E "^stat::number_of_executed_units|^stat::new_units_added|^Done|ERROR|SUMMARY" "build-fuzz/$target.log" \
    | sed "s/^/$target: /" || true
  # Edge coverage only, so the corpus keeps one input per new edge rather than per hit count.
  ./build-fuzz/tests/fuzz/inkline_${target}_fuzz -merge=1 -use_counters=0 -use_value_profile=0 \
    -artifact_prefix="tests/fuzz/corpus/$target/" \
    "tests/fuzz/corpus/$target" "$work" >/dev/null 2>&1 || true
  rm -rf "$work"
  return $status
}

status=0
running=0
pids=()
for target in $targets; do
  fuzz_one "$target" &
  pids+=($!)
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then
    wait "${pids[0]}" || status=1
    pids=("${pids[@]:1}")
    running=$((running - 1))
  fi
done
for pid in "${pids[@]}"; do wait "$pid" || status=1; done
exit $status
