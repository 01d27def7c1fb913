#!/usr/bin/env bash
# Runs the fuzz corpora through the replay test (tests/fuzz/replay_test.cpp) under valgrind
# memcheck, in the Release build (`build`), and fails on any memcheck error.
#   bash tests/fuzz/valgrind.sh [gtest filter, default: the mesh and glTF corpora]
# Needs valgrind (Debian package `valgrind`); it installs nothing itself.
set -euo pipefail
cd "$(dirname "$0")/../.."
filter=${1:-'FuzzCorpus.Mesh*:FuzzCorpus.Gltf*:FuzzCorpus.Obj*:FuzzCorpus.Off*:FuzzCorpus.Ply*:FuzzCorpus.Stl*'}

if ! command -v valgrind >/dev/null; then
  echo "valgrind: not found; install valgrind" >&2
  exit 1
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)" --target inkline_fuzz_replay_tests
valgrind --tool=memcheck --error-exitcode=99 --track-origins=yes --leak-check=full \
  --errors-for-leak-kinds=definite,indirect --show-leak-kinds=definite,indirect \
  ./build/tests/fuzz/inkline_fuzz_replay_tests --gtest_filter="$filter"
