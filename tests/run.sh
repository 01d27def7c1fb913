#!/usr/bin/env bash
# The whole test suite: installs missing packages, builds, runs every test with CTest.
# With CI=true it also runs the Slurm farm test (tests/slurm/slurm_test.sh; INKLINE_SLURM_TEST=1
# alone) and builds and runs the suite under AddressSanitizer + UndefinedBehaviorSanitizer
# (INKLINE_SANITIZE=1 alone).
set -euo pipefail
cd "$(dirname "$0")/.."

bash .ci/setup
jobs=$(nproc)

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DINKLINE_WERROR=ON -DINKLINE_BUILD_PYTHON=ON >/dev/null
cmake --build build -j "$jobs"
ctest --test-dir build -j "$jobs" --output-on-failure

# The farm on a real single-node Slurm cluster (root only; installs slurm-wlm and munge).
if [ "${CI:-}" = "true" ] || [ "${INKLINE_SLURM_TEST:-0}" = "1" ]; then
  bash tests/slurm/slurm_test.sh build
fi

if [ "${CI:-}" = "true" ] || [ "${INKLINE_SANITIZE:-0}" = "1" ]; then
  echo "== sanitizer build (ASan + UBSan) =="
  # Warnings are gated by the build above; GCC 12 adds false -Wmaybe-uninitialized reports inside
  # libstdc++'s <regex> under sanitizer instrumentation, so this build does not turn them into errors.
  cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DINKLINE_SANITIZE=ON -DINKLINE_WERROR=OFF >/dev/null
  cmake --build build-sanitize -j "$jobs"
  # intercept_tls_get_addr=0: Mesa, opened with dlopen, keeps dynamic thread-local storage that
  # GCC 12's LeakSanitizer crashes on at exit while walking it (tests/gl/CMakeLists.txt).
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 LSAN_OPTIONS="suppressions=$(pwd)/tests/lsan.supp:print_suppressions=0:intercept_tls_get_addr=0" \
    ctest --test-dir build-sanitize -j "$jobs" --output-on-failure
fi
