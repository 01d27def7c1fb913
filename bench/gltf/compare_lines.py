#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# Checks inkline's glTF evaluation against Blender's: renders SHOT/shot.glb and the reference
# (SHOT/reference.json: the same frames as Blender evaluates them, written by build_shot.py)
# with exact visibility, and compares the visible lines of every frame: precision and recall of
# visible length within TOL px (default 1).
#
#   bench/gltf/compare_lines.py SHOT [--inkline build/cli/inkline] [--tol 1.0]
import argparse
import json
import math
import os
import subprocess
import sys

import numpy as np


def segments(path):
    """Every visible segment of a polylines JSON, as an (n, 4) array x0 y0 x1 y1."""
    with open(path) as f:
        frame = json.load(f)
    segs = []
    for s in frame["strokes"]:
        if not s.get("visible", True):
            continue
        p = s["points"]
        segs.extend(p[i] + p[i + 1] for i in range(len(p) - 1))
    return np.array(segs, dtype=float).reshape(-1, 4)


def samples(segs, step=0.25):
    """Points every `step` px along the segments, each with the length it stands for."""
    pts, weights = [], []
    for x0, y0, x1, y1 in segs:
        length = math.hypot(x1 - x0, y1 - y0)
        n = max(1, int(math.ceil(length / step)))
        t = (np.arange(n) + 0.5) / n
        pts.append(np.stack([x0 + (x1 - x0) * t, y0 + (y1 - y0) * t], axis=1))
        weights.append(np.full(n, length / n))
    if not pts:
        return np.zeros((0, 2)), np.zeros(0)
    return np.concatenate(pts), np.concatenate(weights)


def covered(points, segs, tol):
    """For each point, whether a segment lies within tol of it."""
    if len(segs) == 0:
        return np.zeros(len(points), dtype=bool)
    out = np.zeros(len(points), dtype=bool)
    a, b = segs[:, :2], segs[:, 2:]
    d = b - a
    dd = np.maximum((d * d).sum(axis=1), 1e-30)
    for start in range(0, len(points), 2048):
        p = points[start:start + 2048, None, :]
        t = np.clip(((p - a) * d).sum(axis=2) / dd, 0.0, 1.0)
        closest = a + t[..., None] * d
        dist = np.sqrt(((p - closest) ** 2).sum(axis=2)).min(axis=1)
        out[start:start + 2048] = dist <= tol
    return out


def fraction(a, b, tol):
    pts, w = samples(a)
    if w.sum() == 0:
        return 1.0
    return float((w * covered(pts, b, tol)).sum() / w.sum())


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("shot")
    ap.add_argument("--inkline", default="build/cli/inkline")
    ap.add_argument("--tol", type=float, default=1.0)
    args = ap.parse_args()
    shot = args.shot
    with open(os.path.join(shot, "reference.json")) as f:
        ref = json.load(f)
    first, last = ref["frames"]
    size = "%dx%d" % (ref["image"]["width"], ref["image"]["height"])
    for name, source in (("gltf", os.path.join(shot, "shot.glb")), ("ref", os.path.join(shot, "reference.json"))):
        subprocess.run([args.inkline, "render", source, "--frames", "%d:%d" % (first, last), "--size", size,
                        "--visibility", "exact", "-q", "--json", os.path.join(shot, "out", name, "%04d.json")],
                       check=True)
    worst_p = worst_r = 1.0
    print("| frame | visible px (glTF) | visible px (Blender) | precision | recall |")
    print("|---:|---:|---:|---:|---:|")
    for frame in range(first, last + 1):
        a = segments(os.path.join(shot, "out", "gltf", "%04d.json" % frame))
        b = segments(os.path.join(shot, "out", "ref", "%04d.json" % frame))
        p, r = fraction(a, b, args.tol), fraction(b, a, args.tol)
        worst_p, worst_r = min(worst_p, p), min(worst_r, r)
        la = float(np.hypot(a[:, 2] - a[:, 0], a[:, 3] - a[:, 1]).sum()) if len(a) else 0.0
        lb = float(np.hypot(b[:, 2] - b[:, 0], b[:, 3] - b[:, 1]).sum()) if len(b) else 0.0
        print("| %d | %.0f | %.0f | %.4f | %.4f |" % (frame, la, lb, p, r))
    print("worst precision %.4f, worst recall %.4f (within %.2f px)" % (worst_p, worst_r, args.tol))
    return 0 if worst_p >= 0.995 and worst_r >= 0.995 else 1


if __name__ == "__main__":
    sys.exit(main())
