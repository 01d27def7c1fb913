#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# An independent exact check of the visibility inkline gives smooth contours (docs/contours.md),
# from its polylines JSON (docs/polylines-json.md) and the mesh it rendered:
#
#   bench/contours/exact_check.py MESH.off JSON_FOLDER_OR_FILES... [--every N] [--samples K]
#       [--seed S] [--json OUT]
#
# Render with `--contour smooth --hidden --json DIR/f_%04d.json` (a moving camera, a still mesh:
# the mesh's object space is world space). Every silhouette segment is checked at its midpoint p,
# on the triangle F it crosses (its entry in "edges"): p is visible iff the open segment
# p + t * (eye - p), 1e-6 < t < 1, meets no triangle except those sharing a vertex with F;
# degenerate triangles never occlude, and hits on triangle edges count. Ray/triangle tests are
# double-precision Moller-Trumbore, on the triangles whose projection from the eye may hold p's.
# inkline's verdict: visible iff the stroke is visible and the segment not in hidden_segments.
# Segments that leave their face's plane (drawn straight across a join by the stroke stage, not
# contour points) are left out.
# Prints per frame the checked length and the fraction of it that agrees, then the overall
# fraction, the worst frame and the disagreements, and last a line
# `agreement: 0.9987 of 123456 px over 120 frames`. --samples K checks K segments per frame
# drawn with probability proportional to their pixel length (each then stands for an equal share
# of the frame's length); otherwise every segment counts with its pixel length. numpy needed.
import argparse
import glob
import json
import os
import sys
import time

import numpy as np

T_MIN = 1e-6  # the segment toward the eye starts this fraction of |eye - p| away from p
BARY_EPS = 1e-12  # hits on edges count: barycentric slack
GRID = 256  # cells per side of the projected grid
PAIR_CHUNK = 2_000_000  # (point, triangle) pairs tested at once


def read_off(path):
    """Vertices (as inkline holds them: single precision, then double) and fan-triangulated
    triangles numbered as inkline numbers them."""
    with open(path, encoding="utf-8-sig", errors="replace") as f:
        lines = [l.split("#", 1)[0].split() for l in f]
    lines = [l for l in lines if l]
    if not lines or not lines[0][0].endswith("OFF"):
        raise SystemExit(f"{path}: not an OFF file")
    counts = lines[0][1:] or lines[1]
    body = lines[1:] if lines[0][1:] else lines[2:]
    nv, nf = int(counts[0]), int(counts[1])
    verts = np.array([[float(w) for w in l[:3]] for l in body[:nv]], dtype=np.float32).astype(np.float64)
    tris = []
    for l in body[nv:nv + nf]:
        c = [int(w) for w in l[1:1 + int(l[0])]]
        tris += [(c[0], c[k], c[k + 1]) for k in range(1, len(c) - 1)]
    return verts, np.array(tris, dtype=np.int64).reshape(-1, 3)


def occluders(verts, tris):
    """Mask of the triangles that may occlude: distinct indices and a non-zero area."""
    a, b, c = (verts[tris[:, k]] for k in range(3))
    distinct = (tris[:, 0] != tris[:, 1]) & (tris[:, 1] != tris[:, 2]) & (tris[:, 0] != tris[:, 2])
    area2 = np.linalg.norm(np.cross(b - a, c - a), axis=1)
    longest = np.max([np.sum((b - a) ** 2, 1), np.sum((c - b) ** 2, 1), np.sum((a - c) ** 2, 1)], axis=0)
    return distinct & (area2 > 1e-12 * longest)


def frame_segments(data):
    """Silhouette segments of one frame: world midpoints, pixel lengths, faces, inkline's verdicts."""
    mids, lengths, faces, visible = [], [], [], []
    for s in data["strokes"]:
        if s.get("kind") != "silhouette" or len(s["points"]) < 2:
            continue
        w, px = np.array(s["world"], float), np.array(s["points"], float)
        vis = np.full(len(px) - 1, bool(s.get("visible", True)))
        vis[np.array(s.get("hidden_segments", []), dtype=np.int64)] = False
        mids.append(0.5 * (w[:-1] + w[1:]))
        lengths.append(np.linalg.norm(px[1:] - px[:-1], axis=1))
        faces.append(np.array(s["edges"], dtype=np.int64))
        visible.append(vis)
    if not mids:
        return np.zeros((0, 3)), np.zeros(0), np.zeros(0, np.int64), np.zeros(0, bool)
    return np.concatenate(mids), np.concatenate(lengths), np.concatenate(faces), np.concatenate(visible)


def segment_hits(verts, tris, eye, p, face, q, t):
    """For pairs (point q[i], triangle t[i]): does the segment from p[q] toward the eye meet the
    triangle, which shares no vertex with face[q]?"""
    tq, fq = tris[t], tris[face[q]]
    far = ~(tq[:, :, None] == fq[:, None, :]).any(axis=(1, 2))
    q, t, tq = q[far], t[far], tq[far]
    o = p[q]
    d = eye - o
    v0 = verts[tq[:, 0]]
    e1, e2 = verts[tq[:, 1]] - v0, verts[tq[:, 2]] - v0
    h = np.cross(d, e2)
    det = np.einsum("ij,ij->i", e1, h)
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = 1.0 / det
        s = o - v0
        u = inv * np.einsum("ij,ij->i", s, h)
        r = np.cross(s, e1)
        v = inv * np.einsum("ij,ij->i", d, r)
        tt = inv * np.einsum("ij,ij->i", e2, r)
    hit = (det != 0) & (u >= -BARY_EPS) & (v >= -BARY_EPS) & (u + v <= 1 + BARY_EPS) & (tt > T_MIN) & (tt < 1)
    return q[hit]


def chunked_pairs(q, counts, cand):
    """Yields (point, triangle) index pairs, each point q[i] with its counts[i] candidates given
    by cand(i_rep, local): chunks of at most about PAIR_CHUNK pairs."""
    ends = np.cumsum(counts)
    i = 0
    while i < len(q):
        j = max(i + 1, int(np.searchsorted(ends, (ends[i - 1] if i else 0) + PAIR_CHUNK, "right")))
        c = counts[i:j]
        rep = np.repeat(np.arange(i, j), c)
        local = np.arange(len(rep)) - np.repeat(np.cumsum(c) - c, c)
        yield q[rep], cand(rep, local)
        i = j


def exact_hidden(verts, tris, occ, eye, view, p, face):
    """Exact verdicts (True: hidden) of points p on triangles face, seen from eye."""
    fwd = view / np.linalg.norm(view)
    right = np.cross(fwd, [0.0, 1.0, 0.0] if abs(fwd[1]) < 0.9 else [1.0, 0.0, 0.0])
    right /= np.linalg.norm(right)
    basis = np.stack([right, np.cross(right, fwd), fwd])
    rel = (verts - eye) @ basis.T
    zeps = 1e-12 * np.abs(rel).max()
    tz = rel[tris, 2]
    front = occ & (tz > zeps).all(1)
    straddle = np.flatnonzero(occ & ~front & (tz > 0).any(1))  # always tested
    pq = (p - eye) @ basis.T
    ahead = pq[:, 2] > zeps
    hidden = np.zeros(len(p), bool)
    # Points at or behind the eye plane: every triangle. Others: the straddling ones.
    everything = np.flatnonzero(occ)
    for qs, pool in ((np.flatnonzero(~ahead), everything), (np.flatnonzero(ahead), straddle)):
        if len(qs) and len(pool):
            for q, t in chunked_pairs(qs, np.full(len(qs), len(pool)), lambda rep, local: pool[local]):
                hidden[segment_hits(verts, tris, eye, p, face, q, t)] = True
    qs = np.flatnonzero(ahead)
    if not len(qs):
        return hidden
    # Triangles wholly in front: binned by their projected bounding box (a triangle that meets
    # the segment holds, in projection from the eye, the projection of p).
    with np.errstate(divide="ignore", invalid="ignore"):
        proj = rel[:, :2] / rel[:, 2:3]
    qxy = pq[qs, :2] / pq[qs, 2:3]
    ids = np.flatnonzero(front)
    txy = proj[tris[ids]]
    lo, hi = txy.min(1), txy.max(1)
    pad = 1e-9 * (1.0 + np.abs(lo).max(1, keepdims=True) + np.abs(hi).max(1, keepdims=True))
    lo, hi = lo - pad, hi + pad
    g_lo, g_hi = qxy.min(0) - 1e-9, qxy.max(0) + 1e-9
    cell = (g_hi - g_lo) / GRID
    keep = (hi >= g_lo).all(1) & (lo <= g_hi).all(1)
    ids, lo, hi = ids[keep], lo[keep], hi[keep]
    c0 = np.clip(np.floor((lo - g_lo) / cell), 0, GRID - 1).astype(np.int64)
    c1 = np.clip(np.floor((hi - g_lo) / cell), 0, GRID - 1).astype(np.int64)
    span = c1 - c0 + 1
    n = span[:, 0] * span[:, 1]
    rep = np.repeat(np.arange(len(ids)), n)
    local = np.arange(len(rep)) - np.repeat(np.cumsum(n) - n, n)
    cells = (c0[rep, 1] + local // span[rep, 0]) * GRID + c0[rep, 0] + local % span[rep, 0]
    order = np.argsort(cells, kind="stable")
    binned = rep[order]
    start = np.concatenate([[0], np.cumsum(np.bincount(cells, minlength=GRID * GRID))])
    qc = np.clip(np.floor((qxy - g_lo) / cell), 0, GRID - 1).astype(np.int64)
    qcell = qc[:, 1] * GRID + qc[:, 0]
    counts = start[qcell + 1] - start[qcell]
    for q, k in chunked_pairs(qs, counts, lambda r, local: binned[start[qcell[r]] + local]):
        xy = qxy[np.searchsorted(qs, q)]
        inside = (lo[k] <= xy).all(1) & (xy <= hi[k]).all(1)
        hidden[segment_hits(verts, tris, eye, p, face, q[inside], ids[k[inside]])] = True
    return hidden


def on_face(verts, tris, points, faces):
    """Whether each point lies in the plane of its face (within 1e-6 of the face's size)."""
    a, b, c = (verts[tris[faces, k]] for k in range(3))
    n = np.cross(b - a, c - a)
    size = np.max([np.linalg.norm(b - a, axis=1), np.linalg.norm(c - a, axis=1)], axis=0)
    distance = np.abs(np.einsum("ij,ij->i", n, points - a)) / np.maximum(np.linalg.norm(n, axis=1), 1e-300)
    return distance <= 1e-6 * size


def check_frame(path, verts, tris, occ, samples, rng):
    """One frame's figures: tested length, agreeing length, the two disagreements (px, count)."""
    with open(path) as f:
        data = json.load(f)
    if data.get("format") != "inkline.polylines":
        raise SystemExit(f"{path}: not an inkline.polylines file")
    mids, lengths, faces, visible = frame_segments(data)
    if len(faces) and (faces.min() < 0 or faces.max() >= len(tris)):
        raise SystemExit(f"{path}: face {faces.max()} out of the mesh's {len(tris)} triangles "
                         "(rendered with --contour smooth, from this mesh?)")
    # Segments that the stroke stage drew straight across a join (a fold, a T-junction) leave
    # their face: not contour points, so not checked.
    keep = on_face(verts, tris, mids, faces)
    mids, lengths, faces, visible = mids[keep], lengths[keep], faces[keep], visible[keep]
    total = float(lengths.sum())
    if samples and total > 0:
        picks = rng.choice(len(lengths), size=samples, p=lengths / total)
        weights = np.bincount(picks, minlength=len(lengths)) * (total / samples)
    else:
        weights = lengths
    tested = np.flatnonzero(weights > 0) if samples else np.arange(len(lengths))
    cam = data["camera"]
    eye = np.array(cam["eye"], float)
    hidden = exact_hidden(verts, tris, occ, eye, np.array(cam["target"], float) - eye, mids[tested], faces[tested])
    w, vis = weights[tested], visible[tested]
    vis_hid, hid_vis = vis & hidden, ~vis & ~hidden
    return {"file": os.path.basename(path), "frame": data.get("frame"), "segments": int(len(tested)),
            "length_px": float(w.sum()), "agree_px": float(w[vis != hidden].sum()),
            "visible_but_hidden_px": float(w[vis_hid].sum()), "visible_but_hidden": int(vis_hid.sum()),
            "hidden_but_visible_px": float(w[hid_vis].sum()), "hidden_but_visible": int(hid_vis.sum())}


def expand(args):
    """JSON files: folders' *.json and globs, sorted."""
    paths = []
    for a in args:
        paths += sorted(glob.glob(os.path.join(a, "*.json"))) if os.path.isdir(a) else sorted(glob.glob(a))
    if not paths:
        raise SystemExit("no JSON files given or found")
    return paths


def main():
    parser = argparse.ArgumentParser(description="Exact visibility check of inkline's smooth contours.")
    parser.add_argument("mesh", help="the OFF mesh the frames were rendered from")
    parser.add_argument("inputs", nargs="+", help="folders of per-frame JSON, or files / globs")
    parser.add_argument("--every", type=int, default=1, help="check every N-th file (default 1)")
    parser.add_argument("--samples", type=int, default=0, help="segments per frame, length-weighted (default 0: all)")
    parser.add_argument("--seed", type=int, default=1, help="seed of the sampling (default 1)")
    parser.add_argument("--json", help="write the overall figures and the per-frame list to this file")
    args = parser.parse_args()

    start = time.perf_counter()
    verts, tris = read_off(args.mesh)
    occ = occluders(verts, tris)
    rng = np.random.default_rng(args.seed)
    rows = []
    for path in expand(args.inputs)[::max(1, args.every)]:
        r = check_frame(path, verts, tris, occ, args.samples, rng)
        r["agreement"] = r["agree_px"] / r["length_px"] if r["length_px"] > 0 else 1.0
        rows.append(r)
        print(f"{r['file']}: {r['segments']} segments, {r['length_px']:.1f} px, agreement {r['agreement']:.4f}"
              f" (visible/hidden {r['visible_but_hidden']}, hidden/visible {r['hidden_but_visible']})")
    total = sum(r["length_px"] for r in rows)
    out = {"agreement": sum(r["agree_px"] for r in rows) / total if total > 0 else 1.0, "length_px": total,
           "frames": len(rows), "samples": args.samples, "seconds": round(time.perf_counter() - start, 2)}
    for key in ("visible_but_hidden", "hidden_but_visible"):
        out[key + "_px"] = sum(r[key + "_px"] for r in rows)
        out[key] = sum(r[key] for r in rows)
    worst = min(rows, key=lambda r: r["agreement"])
    print(f"{len(tris)} triangles ({int(occ.sum())} may occlude), {len(rows)} frames in {out['seconds']:.1f} s")
    print(f"worst frame: {worst['file']} ({worst['agreement']:.4f} of {worst['length_px']:.1f} px)")
    print(f"inkline visible, exact hidden: {out['visible_but_hidden']} segments, {out['visible_but_hidden_px']:.1f} px")
    print(f"inkline hidden, exact visible: {out['hidden_but_visible']} segments, {out['hidden_but_visible_px']:.1f} px")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(dict(out, per_frame=rows), f, indent=1)
    print(f"agreement: {out['agreement']:.4f} of {total:.0f} px over {len(rows)} frames")


if __name__ == "__main__":
    sys.exit(main())
