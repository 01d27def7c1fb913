#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Stroke coherence of a rendered sequence, computed from its polylines JSON (docs/polylines-json.md):
#
#   bench/coherence/coherence.py FOLDER_OR_GLOB [...] [--drawn-only] [--worst N] [--csv FILE]
#
# For every frame whose previous frame is also given:
# - inherited fraction: the exact length of the visible strokes whose id was present in the
#   previous frame's file, over the length of all visible strokes (docs/strokes.md, "Measured");
# - loop start movement: how far (px) the first point of each closed stroke moved since the
#   previous frame, for ids that were closed strokes there too.
# Prints per-frame min, median, frames at 95% or more, the overall fraction and the median loop
# start movement; --worst N lists the N worst frames with their new strokes. Standard library only.
import argparse
import glob
import json
import math
import os
import statistics
import sys


def polyline_length(points):
    return sum(math.dist(points[i], points[i + 1]) for i in range(len(points) - 1))


def load(paths):
    frames = {}
    for path in paths:
        with open(path) as f:
            data = json.load(f)
        if data.get("format") != "inkline.polylines":
            raise SystemExit(f"{path}: not an inkline.polylines file")
        frames[data["frame"]] = [
            {
                "id": s["id"],
                "kind": s["kind"],
                "visible": s.get("visible", True),
                "drawn": s.get("drawn", True),
                "closed": s.get("closed", False),
                "ends": s.get("ends", []),
                "start": s["points"][0] if s["points"] else None,
                # Segments drawn across a short occluded gap (hidden_segments) are not visible length.
                "length": polyline_length(s["points"])
                - sum(math.dist(s["points"][k], s["points"][k + 1]) for k in s.get("hidden_segments", [])),
            }
            for s in data["strokes"]
        ]
    return frames


def expand(args):
    paths = []
    for a in args:
        if os.path.isdir(a):
            paths += sorted(glob.glob(os.path.join(a, "*.json")))
        else:
            paths += sorted(glob.glob(a))
    if not paths:
        raise SystemExit("no JSON files given or found")
    return paths


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("inputs", nargs="+", help="folders of per-frame JSON, or globs")
    parser.add_argument("--drawn-only", action="store_true", help="count only drawn strokes (min_length_px and up)")
    parser.add_argument("--worst", type=int, default=0, help="list the N worst frames and their new strokes")
    parser.add_argument("--csv", help="write frame,fraction,visible_px,new_px,loop_moves_median to this file")
    parser.add_argument("--threshold", type=float, default=0.95, help="per-frame target (default 0.95)")
    args = parser.parse_args()

    frames = load(expand(args.inputs))
    rows = []
    moves = []
    inherited_total = visible_total = 0.0
    for f in sorted(frames):
        if f - 1 not in frames:
            continue
        before = {s["id"]: s for s in frames[f - 1]}
        visible = inherited = 0.0
        new = []
        frame_moves = []
        for s in frames[f]:
            if s["visible"] and (s["drawn"] or not args.drawn_only):
                visible += s["length"]
                if s["id"] in before:
                    inherited += s["length"]
                else:
                    new.append(s)
            old = before.get(s["id"])
            if s["closed"] and old is not None and old["closed"] and s["start"] and old["start"]:
                frame_moves.append(math.dist(s["start"], old["start"]))
        moves += frame_moves
        fraction = inherited / visible if visible > 0.0 else 1.0
        inherited_total += inherited
        visible_total += visible
        rows.append((f, fraction, visible, visible - inherited, frame_moves, new))

    if not rows:
        raise SystemExit("need at least two consecutive frames")
    fractions = [r[1] for r in rows]
    at_target = sum(1 for x in fractions if x >= args.threshold)
    print(f"frames compared: {len(rows)} ({rows[0][0] - 1}..{rows[-1][0]})")
    print(
        f"inherited visible length: overall {100.0 * inherited_total / max(visible_total, 1e-12):.2f}%, "
        f"per frame min {100.0 * min(fractions):.1f}% (frame {rows[fractions.index(min(fractions))][0]}), "
        f"median {100.0 * statistics.median(fractions):.2f}%, "
        f">= {100.0 * args.threshold:.0f}% in {at_target} of {len(rows)} frames"
    )
    if moves:
        print(f"loop start movement: median {statistics.median(moves):.2f} px, "
              f"90th percentile {sorted(moves)[int(0.9 * (len(moves) - 1))]:.2f} px over {len(moves)} moves")
    else:
        print("loop start movement: no loop seen in two consecutive frames")

    if args.csv:
        with open(args.csv, "w") as out:
            out.write("frame,fraction,visible_px,new_px,loop_moves_median_px\n")
            for f, fraction, visible, new_px, frame_moves, _ in rows:
                m = statistics.median(frame_moves) if frame_moves else ""
                out.write(f"{f},{fraction:.5f},{visible:.2f},{new_px:.2f},{m}\n")
    for f, fraction, visible, new_px, _, new in sorted(rows, key=lambda r: r[1])[: args.worst]:
        print(f"frame {f}: {100.0 * fraction:.1f}% of {visible:.0f} px; new {new_px:.0f} px in {len(new)} strokes")
        for s in sorted(new, key=lambda s: -s["length"])[:8]:
            ends = "".join(s["ends"])
            print(f"    id {s['id']:5d} {s['kind']:10s} {ends:3s} {'loop ' if s['closed'] else ''}"
                  f"{'' if s['drawn'] else 'undrawn '}{s['length']:7.1f} px at "
                  f"({s['start'][0]:.0f}, {s['start'][1]:.0f})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
