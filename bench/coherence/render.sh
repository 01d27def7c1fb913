#!/usr/bin/env bash
# Renders the two coherence sequences to polylines JSON and measures them: the torus sample
# and a mesh of your choice, each turning 3 degrees per frame (120 frames), 1024 x 1024,
# default brush; each once as it is and once with hidden lines kept (--hidden), where a line
# that comes into view shows the id it had while hidden.
#
#   bash bench/coherence/render.sh [BUILD_DIR] [MESH] [OUT_DIR]
#
# MESH is any mesh inkline reads, e.g. bunny00.off from Debian's libcgal-demo data
# (tar xzf /usr/share/doc/libcgal-demo/data.tar.gz: data/meshes/bunny00.off); without it only
# the torus is rendered. The mesh gets the camera of the default turntable (20 degrees above
# its centre, fitted in 35 degrees) orbiting 360 degrees over 120 frames.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build=${1:-build}
mesh=${2:-}
out=${3:-$(mktemp -d)}
inkline="$build/cli/inkline"
[ -x "$inkline" ] || { echo "build $inkline first (cmake --build $build)" >&2; exit 1; }
mkdir -p "$out"

# measure NAME SCENE: renders SCENE without and with hidden lines under $out/NAME and
# $out/NAME-hidden, and measures both.
measure() {
  local name=$1 scene=$2
  echo "== $name, 3 degrees per frame"
  rm -rf "${out:?}/$name/json" "${out:?}/$name-hidden"
  "$inkline" render "$scene" -q --json "$out/$name/json/f_%04d.json"
  python3 "$here/coherence.py" "$out/$name/json" --worst 3
  echo "== $name, 3 degrees per frame, --hidden"
  "$inkline" render "$scene" -q --hidden --json "$out/$name-hidden/json/f_%04d.json"
  python3 "$here/coherence.py" "$out/$name-hidden/json" --worst 3
}

rm -rf "$out/torus"
measure torus "$here/torus_3deg.json"

if [ -n "$mesh" ]; then
  rm -rf "$out/mesh"
  mkdir -p "$out/mesh"
  # The default turntable's camera (core::default_turntable_scene), over 120 frames.
  python3 "$here/turntable.py" "$inkline" "$(realpath "$mesh")" 120 > "$out/mesh/scene.json"
  measure mesh "$out/mesh/scene.json"
fi
echo "JSON under $out"
