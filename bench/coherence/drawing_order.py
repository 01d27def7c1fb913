#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# How steady the drawing order is over a sequence, from its per-frame polylines JSON (standard
# library only), as docs/strokes.md measures it: of the strokes that keep their ids from one frame
# to the next,
#   same level: the share whose `level` is unchanged;
#   in order:   the share in the longest run of them that keeps last frame's `order` (the longest
#               subsequence, taken in this frame's order, whose orders last frame ascend);
#   both:       the share in the longest such run among the strokes that keep their level.
#
#   bench/coherence/drawing_order.py JSON_DIR [JSON_DIR ...]
#
# A turntable as in docs/strokes.md (40 frames at 3 degrees a frame, 1024 px, ray-cast):
#   bench/coherence/turntable.py build/cli/inkline data/meshes/armadillo.off 40 > /tmp/arm.json
#   build/cli/inkline render /tmp/arm.json --visibility raycast -q --json /tmp/arm/%04d.json
#   bench/coherence/drawing_order.py /tmp/arm

import bisect
import json
import sys
from pathlib import Path


def longest_ascending(values):
    """Length of the longest strictly ascending subsequence."""
    tails = []
    for v in values:
        k = bisect.bisect_left(tails, v)
        if k == len(tails):
            tails.append(v)
        else:
            tails[k] = v
    return len(tails)


def steadiness(folder):
    """(kept strokes per frame pair, share with the same level, share in order)."""
    files = sorted(Path(folder).glob("*.json"))
    if len(files) < 2:
        sys.exit("%s: fewer than two frames of polylines JSON" % folder)
    last = None
    kept = same_level = in_order = both_kept = 0
    for path in files:
        strokes = {s["id"]: s for s in json.loads(path.read_text())["strokes"]}
        if last is not None:
            both = [i for i in strokes if i in last]
            level_kept = [i for i in both if strokes[i]["level"] == last[i]["level"]]
            kept += len(both)
            same_level += len(level_kept)
            in_order += longest_ascending([last[i]["order"] for i in sorted(both, key=lambda i: strokes[i]["order"])])
            both_kept += longest_ascending([last[i]["order"] for i in sorted(level_kept, key=lambda i: strokes[i]["order"])])
        last = strokes
    pairs = len(files) - 1
    return kept / pairs, same_level / max(kept, 1), in_order / max(kept, 1), both_kept / max(kept, 1)


def main():
    if len(sys.argv) < 2:
        sys.exit("usage: drawing_order.py JSON_DIR [JSON_DIR ...]")
    print("| sequence | strokes kept / frame | same level | in order | both |")
    print("|---|---:|---:|---:|---:|")
    for folder in sys.argv[1:]:
        kept, level, order, both = steadiness(folder)
        print("| %s | %.0f | %.1f%% | %.1f%% | %.1f%% |" % (folder, kept, 100 * level, 100 * order, 100 * both))


if __name__ == "__main__":
    main()
