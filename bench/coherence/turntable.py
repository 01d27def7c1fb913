#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# A scene that turns the camera around a mesh as the default turntable does
# (core::default_turntable_scene: 20 degrees above the mesh's centre, its bounding sphere fitted
# in 35 degrees), 3 degrees a frame, at 1024x1024; printed as scene JSON:
#
#   bench/coherence/turntable.py INKLINE MESH [FRAMES]     (FRAMES: 120 unless given)

import json
import math
import re
import subprocess
import sys
from pathlib import Path


def turntable_scene(inkline, mesh, frames=120):
    """The scene, from the bounds `inkline info` gives."""
    text = subprocess.run([str(inkline), "info", str(mesh)], capture_output=True, text=True, check=True).stdout
    lo, hi = (list(map(float, v.split(","))) for v in re.search(r"bounds: \[(.*)\] \.\. \[(.*)\]", text).groups())
    center = [(a + b) / 2 for a, b in zip(lo, hi)]
    radius = max(math.dist(lo, hi) / 2, 1e-6)
    distance = 1.1 * radius / math.sin(math.radians(35 / 2))
    e = math.radians(20)
    eye = [center[0], center[1] + distance * math.sin(e), center[2] + distance * math.cos(e)]
    return {"version": 1, "mesh": str(Path(mesh).resolve()), "frames": [1, frames],
            "image": {"width": 1024, "height": 1024},
            "camera": {"eye": eye, "target": center, "fov_y_deg": 35,
                       "orbit": {"axis": [0, 1, 0], "degrees": 3.0 * frames}}}


if __name__ == "__main__":
    if len(sys.argv) not in (3, 4):
        sys.exit("usage: turntable.py INKLINE MESH [FRAMES]")
    json.dump(turntable_scene(sys.argv[1], sys.argv[2], int(sys.argv[3]) if len(sys.argv) == 4 else 120),
              sys.stdout, indent=2)
    print()
