#!/usr/bin/env bash
# Installs missing packages, builds inkline and renders the bundled torus turntable into out/.
set -euo pipefail
cd "$(dirname "$0")/.."

bash .ci/setup
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)" --target inkline
./build/cli/inkline render samples/torus/scene.json -o out "$@"
echo "wrote out/svg/frame_*.svg and out/json/frame_*.json"
