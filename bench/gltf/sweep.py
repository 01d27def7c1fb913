#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# Runs glTF files from anywhere (exporters' output, the Khronos sample models) through inkline:
# `info`, then a few frames in each of four modes (ray-cast, exact visibility, smooth contours,
# stippled tone). Per file and mode it prints the exit code, the strokes a frame, the wall time
# and the first warning or error, and it fails (exit 1) on what must not happen whatever the file
# holds: an exit code other than 0 (drawn) or 2 (refused), an error of more than one line, a
# non-finite number in the polylines JSON, or a file drawn in one mode and refused in another.
#
#   bench/gltf/sweep.py FILE_OR_FOLDER... [--inkline build/cli/inkline] [--size 512]
#                       [--frames 6] [--work /tmp/inkline-sweep] [--timeout 300]
import argparse
import glob
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time

MODES = {
    "raycast": ["--visibility", "raycast"],
    "exact": ["--visibility", "exact"],
    "smooth": ["--contour", "smooth"],
    "stipple": ["--tone", "stipple"],
}


def gltf_files(paths):
    out = []
    for p in paths:
        if os.path.isdir(p):
            for ext in ("gltf", "glb"):
                out += glob.glob(os.path.join(p, "**", "*." + ext), recursive=True)
        else:
            out.append(p)
    return sorted(set(out))


def non_finite(value):
    """Whether a parsed JSON value holds a NaN or an infinity anywhere."""
    if isinstance(value, float):
        return not math.isfinite(value)
    if isinstance(value, dict):
        return any(non_finite(v) for v in value.values())
    if isinstance(value, list):
        return any(non_finite(v) for v in value)
    return False


def frames_of(info_text, count):
    """`count` frames from the middle of the file's range (info's `frames: A..B`), else 1..count."""
    m = re.search(r"^frames: (-?\d+)\.\.(-?\d+)", info_text, re.M)
    if not m:
        return 1, count
    first, last = int(m.group(1)), int(m.group(2))
    if last - first + 1 <= count:
        return first, last
    start = (first + last - count + 1) // 2
    return start, start + count - 1


def run(cmd, timeout):
    t = time.perf_counter()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        return p.returncode, p.stdout, p.stderr, time.perf_counter() - t
    except subprocess.TimeoutExpired:
        return "timeout", "", "timed out after %d s" % timeout, time.perf_counter() - t


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("paths", nargs="+")
    ap.add_argument("--inkline", default="build/cli/inkline")
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--frames", type=int, default=6)
    ap.add_argument("--work", default="/tmp/inkline-sweep")
    ap.add_argument("--timeout", type=int, default=300)
    args = ap.parse_args()

    problems = []
    files = gltf_files(args.paths)
    if not files:
        sys.exit("no .gltf or .glb file in " + " ".join(args.paths))
    print("%-32s %-8s %4s %8s %-22s %s" % ("file", "mode", "exit", "s", "strokes a frame", "stderr (first line)"))
    for n, f in enumerate(files):
        name = os.path.basename(f)
        rc, out, err, _ = run([args.inkline, "info", f], args.timeout)
        if rc not in (0, 2):
            problems.append("%s: info exited %s: %s" % (f, rc, err.strip()[:200]))
        first, last = frames_of(out, args.frames)
        drawn = set()
        for mode, extra in MODES.items():
            work = os.path.join(args.work, "%03d" % n, mode)
            shutil.rmtree(work, ignore_errors=True)
            os.makedirs(work)
            cmd = [args.inkline, "render", f, "--size", "%dx%d" % (args.size, args.size), "--frames",
                   "%d:%d" % (first, last), "--json", os.path.join(work, "%04d.json")] + extra
            rc, _, err, dt = run(cmd, args.timeout)
            counts = []
            for j in sorted(glob.glob(os.path.join(work, "*.json"))):
                with open(j) as fh:
                    frame = json.load(fh)
                counts.append(len(frame["strokes"]))
                if non_finite(frame):
                    problems.append("%s (%s): a non-finite number in %s" % (f, mode, j))
            # Warnings and errors; the closing summary line is left out.
            lines = [l for l in err.splitlines() if l.strip() and " frame(s), " not in l]
            errors = [l for l in lines if l.startswith("inkline: error")]
            if rc not in (0, 2):
                problems.append("%s (%s): exit %s: %s" % (f, mode, rc, " | ".join(lines)[:300]))
            if rc == 2 and (len(errors) != 1 or len(lines) != len([l for l in lines if l.startswith("inkline: ")])):
                problems.append("%s (%s): refused without one error line" % (f, mode))
            drawn.add(rc == 0)
            print("%-32s %-8s %4s %8.2f %-22s %s" % (name[:32], mode, rc, dt, ",".join(map(str, counts))[:22],
                                                    lines[0][:110] if lines else ""))
        if len(drawn) > 1:
            problems.append("%s: drawn in some modes and refused in others" % f)
    print()
    print("%d file(s), %d problem(s)" % (len(files), len(problems)))
    for p in problems:
        print("  " + p)
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
