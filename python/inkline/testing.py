# SPDX-License-Identifier: MIT
"""What a geometry test needs from two frames' lines: visible length by kind, precision and
recall of visible length within a pixel tolerance, the Hausdorff distance, id persistence, and
assert_lines_close() with a failure message that says where the lines differ and by how much.

Lines are compared in the image (px). Each argument that takes lines accepts a Frame, a list of
Strokes, or a list of (n, 2) point arrays (polylines). Strokes that are not visible are left out.
Distances are measured to the other side's polylines sampled every `step` px (a quarter pixel
by default), so they are exact to within half that step.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Iterable, Optional

import numpy as np

__all__ = ["visible_length", "LineMatch", "match_lines", "hausdorff_px", "id_persistence", "assert_lines_close"]


def _strokes(lines, kinds=None):
    """(points, stroke id or index, kind) of each visible polyline of `lines`."""
    strokes = getattr(lines, "strokes", lines)
    out = []
    for i, s in enumerate(strokes):
        if isinstance(s, np.ndarray) or isinstance(s, (list, tuple)):
            points = np.asarray(s, np.float64).reshape(-1, 2)
            out.append((points, i, None))
            continue
        if not s.visible or (kinds is not None and s.kind not in kinds):
            continue
        out.append((np.asarray(s.points, np.float64).reshape(-1, 2), s.id, s.kind))
    return out


def _kinds(kinds) -> Optional[set]:
    if kinds is None:
        return None
    return {kinds} if isinstance(kinds, str) else set(kinds)


def visible_length(lines, kind: Optional[str] = None):
    """Visible length in px: a dict by kind, or one kind's length (0 when it has none)."""
    totals: dict = {}
    for points, _, k in _strokes(lines):
        if len(points) > 1:
            totals[k] = totals.get(k, 0.0) + float(np.linalg.norm(np.diff(points, axis=0), axis=1).sum())
    if kind is not None:
        return totals.get(kind, 0.0)
    return totals


def _subdivide(points: np.ndarray, step: float, centred: bool):
    """Each segment of a polyline cut into pieces of at most `step` px: the pieces' middles
    (centred) or starts, the length each piece stands for, and the segment of each."""
    seg = points[1:] - points[:-1]
    length = np.hypot(seg[:, 0], seg[:, 1])
    n = np.maximum(1, np.ceil(length / step)).astype(np.int64)
    which = np.repeat(np.arange(len(seg)), n)
    k = np.arange(len(which)) - np.repeat(np.cumsum(n) - n, n)
    t = (k + (0.5 if centred else 0.0)) / n[which]
    return points[which] + seg[which] * t[:, None], (length / n)[which]


def _samples(strokes, step):
    """Points every `step` px or less along each polyline, the length each stands for, and the
    stroke it came from."""
    pts, weights, owners = [], [], []
    for points, ident, kind in strokes:
        if len(points) == 1:
            p, w = points, np.zeros(1)
        else:
            p, w = _subdivide(points, step, centred=True)
        pts.append(p)
        weights.append(w)
        owners.extend([(ident, kind)] * len(p))
    if not pts:
        return np.zeros((0, 2)), np.zeros(0), []
    return np.concatenate(pts), np.concatenate(weights), owners


def _vertices(strokes, step):
    """Points along each polyline, its vertices included, no farther than `step` apart."""
    pts = []
    for points, _, _ in strokes:
        if len(points) > 1:
            pts.append(_subdivide(points, step, centred=False)[0])
        pts.append(points[-1:])
    return np.concatenate(pts) if pts else np.zeros((0, 2))


class _Grid:
    """Nearest of a set of points, by a uniform grid searched in growing square rings."""

    def __init__(self, points: np.ndarray, cell: float):
        self.points = points
        self.cell = cell
        self.cells: dict = {}
        if len(points):
            keys = np.floor(points / cell).astype(np.int64)
            order = np.lexsort((keys[:, 1], keys[:, 0]))
            keys = keys[order]
            breaks = np.flatnonzero(np.any(np.diff(keys, axis=0) != 0, axis=1)) + 1
            for idx, key in zip(np.split(order, breaks), keys[np.concatenate(([0], breaks))]):
                self.cells[(int(key[0]), int(key[1]))] = idx
            self.extent = int(np.max(np.abs(keys))) + 2

    def nearest(self, q: np.ndarray, limit: float = np.inf) -> float:
        """Distance from q to the nearest point; `limit` when none is nearer."""
        if not self.cells:
            return limit
        cx, cy = int(np.floor(q[0] / self.cell)), int(np.floor(q[1] / self.cell))
        best = limit
        r = 0
        while True:
            # Every point in ring r is at least (r - 1) cells away.
            if (r - 1) * self.cell >= best or r > self.extent + abs(cx) + abs(cy):
                return best
            for x in range(cx - r, cx + r + 1):
                for y in (cy - r, cy + r) if 0 < r and x not in (cx - r, cx + r) else range(cy - r, cy + r + 1):
                    idx = self.cells.get((x, y))
                    if idx is not None:
                        d = float(np.min(np.hypot(*(self.points[idx] - q).T)))
                        best = min(best, d)
            r += 1


def _near(query: np.ndarray, ref: np.ndarray, radius: float) -> np.ndarray:
    """Distance from each query point to the nearest ref point, exact where it is at most
    `radius`, inf elsewhere: ref points bucketed in cells of `radius`, each query looking in
    the 3 x 3 cells around it, all at once."""
    out = np.full(len(query), np.inf)
    if len(query) == 0 or len(ref) == 0:
        return out
    offset = np.int64(1 << 30)

    def code(cells):
        return (cells[:, 0] + offset) * np.int64(1 << 31) + (cells[:, 1] + offset)

    ref_cells = np.floor(ref / radius).astype(np.int64)
    codes = code(ref_cells)
    order = np.argsort(codes, kind="stable")
    codes, ref = codes[order], ref[order]
    query_cells = np.floor(query / radius).astype(np.int64)
    for dx in (-1, 0, 1):
        for dy in (-1, 0, 1):
            c = code(query_cells + np.array([dx, dy]))
            lo = np.searchsorted(codes, c, "left")
            count = np.searchsorted(codes, c, "right") - lo
            k = int(count.max())
            if k == 0:
                continue
            idx = np.minimum(lo[:, None] + np.arange(k)[None, :], len(ref) - 1)
            d = np.hypot(*(ref[idx] - query[:, None, :]).transpose(2, 0, 1))
            d[np.arange(k)[None, :] >= count[:, None]] = np.inf
            out = np.minimum(out, d.min(axis=1))
    out[out > radius] = np.inf
    return out


def _distances(query: np.ndarray, ref: np.ndarray, radius: float, limit: float = np.inf) -> np.ndarray:
    """Distance from each query point to the nearest ref point (at most `limit`): the points
    within `radius` all at once, the others one by one."""
    d = _near(query, ref, radius)
    far = np.flatnonzero(np.isinf(d))
    if len(far):
        both = np.concatenate((query, ref))
        # Cells of about 1/200 of the extent: a search crosses at most about 200 rings.
        grid = _Grid(ref, max(radius, float(np.hypot(*(both.max(axis=0) - both.min(axis=0)))) / 200.0))
        d[far] = [grid.nearest(q, limit) for q in query[far]]
    return d


@dataclass
class LineMatch:
    """How two frames' visible lines agree within a tolerance."""

    precision: float   # share of a's visible length within tol_px of b's lines
    recall: float      # share of b's visible length within tol_px of a's lines
    length_a: float
    length_b: float
    tol_px: float
    # Where they differ: (x, y, distance, stroke id, kind) of a's and b's points farther than
    # tol_px from the other side's lines, worst first.
    a_not_in_b: list
    b_not_in_a: list


def _one_way(strokes_q, strokes_r, tol, step):
    pts, weights, owners = _samples(strokes_q, step)
    d = _distances(pts, _vertices(strokes_r, step), tol)
    total = float(weights.sum())
    inside = float(weights[d <= tol].sum()) if total > 0 else 0.0
    far = np.flatnonzero(d > tol)
    far = far[np.argsort(-d[far])]
    misses = [(float(pts[i, 0]), float(pts[i, 1]), float(d[i]), owners[i][0], owners[i][1]) for i in far]
    return (inside / total if total > 0 else 1.0), total, misses, d


def match_lines(a, b, tol_px: float = 1.0, *, kinds=None, step: float = 0.25) -> LineMatch:
    """Precision and recall of visible length of `a` against `b` within tol_px."""
    if not tol_px > 0:
        raise ValueError("tol_px: expected a positive tolerance")
    sa, sb = _strokes(a, _kinds(kinds)), _strokes(b, _kinds(kinds))
    step = min(step, tol_px / 2)
    precision, la, a_far, _ = _one_way(sa, sb, tol_px, step)
    recall, lb, b_far, _ = _one_way(sb, sa, tol_px, step)
    return LineMatch(precision, recall, la, lb, tol_px, a_far, b_far)


def hausdorff_px(a, b, *, kinds=None, step: float = 0.25) -> float:
    """The Hausdorff distance between two frames' visible lines, px (inf when one side has lines
    and the other none, 0 when neither has)."""
    sa, sb = _strokes(a, _kinds(kinds)), _strokes(b, _kinds(kinds))
    pa, pb = _vertices(sa, step), _vertices(sb, step)
    if len(pa) == 0 and len(pb) == 0:
        return 0.0
    if len(pa) == 0 or len(pb) == 0:
        return float("inf")
    radius = max(8.0 * step, 2.0)
    da = _distances(pa, pb, radius)
    db = _distances(pb, pa, radius)
    return float(max(da.max(), db.max()))


def id_persistence(before, after) -> float:
    """Share of `after`'s visible length on strokes whose id `before` also has (1 when `after`
    has no visible length): the stroke coherence measure."""
    ids = {ident for _, ident, _ in _strokes(before)}
    total = kept = 0.0
    for points, ident, _ in _strokes(after):
        length = float(np.linalg.norm(np.diff(points, axis=0), axis=1).sum()) if len(points) > 1 else 0.0
        total += length
        if ident in ids:
            kept += length
    return kept / total if total > 0 else 1.0


def _where(misses, limit=5) -> str:
    if not misses:
        return "    none"
    rows = []
    for x, y, d, ident, kind in misses[:limit]:
        what = f"stroke {ident}" + (f" ({kind})" if kind else "")
        rows.append(f"    ({x:.2f}, {y:.2f}) px, {d:.2f} px away: {what}")
    if len(misses) > limit:
        rows.append(f"    ... and {len(misses) - limit} more points")
    return "\n".join(rows)


def assert_lines_close(a, b, tol_px: float = 1.0, *, min_precision: float = 0.99, min_recall: float = 0.99,
                       kinds=None) -> LineMatch:
    """Asserts that at least min_precision of a's visible length lies within tol_px of b's lines
    and at least min_recall of b's within tol_px of a's. The AssertionError says by how much they
    miss and where the lines differ (the farthest points, their strokes and distances)."""
    m = match_lines(a, b, tol_px, kinds=kinds)
    if m.precision >= min_precision and m.recall >= min_recall:
        return m
    raise AssertionError(
        f"lines differ beyond {tol_px:g} px: precision {m.precision:.4f} (at least {min_precision:g}) of "
        f"{m.length_a:.1f} px, recall {m.recall:.4f} (at least {min_recall:g}) of {m.length_b:.1f} px\n"
        f"  a's lines not near b ({len(m.a_not_in_b)} sample points):\n{_where(m.a_not_in_b)}\n"
        f"  b's lines not near a ({len(m.b_not_in_a)} sample points):\n{_where(m.b_not_in_a)}")
