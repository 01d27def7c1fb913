#!/usr/bin/env bash
# Fuzzes the scene parser and mesh loading with libFuzzer (clang) under ASan + UBSan, for a
# bounded time per target. New inputs join tests/fuzz/corpus/<target>/; a crash is saved there
# too (as crash-*), so tests/fuzz/replay_test.cpp keeps it as a regression test.
#   bash tests/fuzz/run.sh [seconds per target, default 600] [targets, default: scene mesh]
# Needs clang-14 and libclang-rt-14-dev (Debian); it installs nothing itself.
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=${1:-600}
targets=${2:-scene mesh}

if ! command -v clang++-14 >/dev/null; then
  echo "fuzz: clang++-14 not found; install clang-14 libclang-rt-14-dev" >&2
  exit 1
fi
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DINKLINE_BUILD_FUZZ=ON -DINKLINE_SANITIZE=ON \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link" >/dev/null
cmake --build build-fuzz -j "$(nproc)" --target inkline_scene_fuzz inkline_mesh_fuzz

status=0
for target in $targets; do
  echo "== fuzzing $target for ${seconds}s =="
  work=$(mktemp -d)
  # New interesting inputs go to a scratch folder; the minimised set is merged into the corpus.
  # -timeout: an input that takes 10 s is a hang, saved like a crash.
  if ! ./build-fuzz/tests/fuzz/inkline_${target}_fuzz -max_total_time="$seconds" -max_len=4096 -timeout=10 \
      -artifact_prefix="tests/fuzz/corpus/$target/" -print_final_stats=1 "$work" "tests/fuzz/corpus/$target"; then
    status=1
  fi
  # Edge coverage only, so the corpus keeps one input per new edge rather than per hit count.
  ./build-fuzz/tests/fuzz/inkline_${target}_fuzz -merge=1 -use_counters=0 -use_value_profile=0 \
    -artifact_prefix="tests/fuzz/corpus/$target/" \
    "tests/fuzz/corpus/$target" "$work" >/dev/null 2>&1 || true
  rm -rf "$work"
done
exit $status
