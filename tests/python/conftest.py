# SPDX-License-Identifier: MIT
"""Shared fixtures of the Python module's tests: the program to compare with, the samples, and
shapes made in code."""
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

SOURCE = Path(os.environ.get("INKLINE_SOURCE_DIR", Path(__file__).resolve().parents[2]))
SAMPLES = SOURCE / "samples"


@pytest.fixture
def inkline_exe():
    exe = os.environ.get("INKLINE_EXE")
    if not exe:
        pytest.fail("INKLINE_EXE is not set (run the tests through ctest)")
    return exe


def run_cli(exe, *args, check=True):
    r = subprocess.run([exe, "render", *map(str, args), "-q"], capture_output=True, text=True,
                       env={**os.environ, "SOURCE_DATE_EPOCH": "0"})
    if check and r.returncode != 0:
        raise AssertionError(f"inkline render {' '.join(map(str, args))}: exit {r.returncode}\n{r.stderr}")
    return r


def without_timings(text):
    doc = json.loads(text)
    doc["stats"].pop("ms", None)
    return doc


def icosphere(subdivisions=3, radius=1.0):
    """A sphere of triangles: vertices (V, 3) on the sphere, faces (T, 3) counter-clockwise."""
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6),
         (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
         (8, 6, 7), (9, 8, 1)]
    vertices = [np.array(p, float) / np.linalg.norm(p) for p in v]
    for _ in range(subdivisions):
        cache, faces = {}, []

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                m = vertices[a] + vertices[b]
                vertices.append(m / np.linalg.norm(m))
                cache[key] = len(vertices) - 1
            return cache[key]

        for a, b, c in f:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            faces += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = faces
    return np.array(vertices) * radius, np.array(f, np.int64)


def write_obj(path, vertices, faces):
    with open(path, "w") as out:
        for p in vertices:
            out.write("v %.17g %.17g %.17g\n" % tuple(p))
        for a, b, c in faces:
            out.write(f"f {a + 1} {b + 1} {c + 1}\n")
