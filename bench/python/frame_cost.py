#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# What drawing a frame costs from Python against the program: the same input and frames, the
# module's Shot.render() timed around the call (the GIL released, the strokes left in C++ until
# asked for) against the per-frame stage times `inkline render -v` prints (extraction,
# visibility, strokes; the files are written after them and not counted). Runs alternate
# program, module, program, module ... in one session so both see the same machine.
#
#   bench/python/frame_cost.py INPUT [--build build] [--frames 24] [--runs 3] [--visibility raycast]
#       [--python /usr/bin/python3]
#
# The module runs under --python, the interpreter it was built for (Debian's python3 by default,
# as the build picks it), whichever Python runs this script.
#
# INPUT is a scene (.json) or a mesh (drawn as the default turntable), e.g. Suzanne subdivided 4
# times (251,904 triangles) from bench/blender/build_scene.py. Per run: the median over frames
# 2.. of each side, and the first frame; then the medians over runs and their ratio.

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent.parent
FRAME_LINE = re.compile(r"^frame (\d+): .*$", re.M)
STAGE = re.compile(r", ([a-z_]+) ([0-9.]+) ms")


def program_frames(exe, source, frames, visibility, work):
    """Per frame, the sum of the stage times the program prints with -v."""
    r = subprocess.run([exe, "render", source, "--frames", f"1:{frames}", "--visibility", visibility, "-v", "-q",
                        "--json", os.path.join(work, "%d.json")], capture_output=True, text=True, check=True)
    out = {}
    for m in FRAME_LINE.finditer(r.stderr):
        out[int(m.group(1))] = sum(float(ms) for _, ms in STAGE.findall(m.group(0)))
    return [out[n] for n in sorted(out)]


def module_frames(python, source, frames, visibility):
    """Per frame, the wall time of Shot.render() and the frame's own stage times."""
    code = f"""
import json, sys, time
import inkline
shot = inkline.open({str(source)!r}, frames=(1, {frames}), visibility={visibility!r})
walls, stages = [], []
for n in shot.frames:
    t = time.perf_counter()
    frame = shot.render(n)
    walls.append(1000.0 * (time.perf_counter() - t))
    stages.append(sum(frame.stats["ms"].values()))
print(json.dumps([walls, stages]))
"""
    r = subprocess.run([python, "-c", code], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("frame_cost.py: the module failed under %s:\n%s" % (python, r.stderr[-3000:]))
    import json
    return json.loads(r.stdout)


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("input")
    p.add_argument("--build", default=str(REPO / "build"))
    p.add_argument("--frames", type=int, default=24)
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--visibility", default="raycast")
    p.add_argument("--python", default="/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable)
    a = p.parse_args()
    exe = os.path.join(a.build, "cli", "inkline")
    os.environ["PYTHONPATH"] = os.path.join(a.build, "python")
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for run in range(a.runs):
            program = program_frames(exe, a.input, a.frames, a.visibility, work)
            walls, stages = module_frames(a.python, a.input, a.frames, a.visibility)
            row = (statistics.median(program[1:]), statistics.median(walls[1:]), statistics.median(stages[1:]),
                   program[0], walls[0])
            rows.append(row)
            print(f"run {run + 1}: frames 2..{a.frames} median: program stages {row[0]:.2f} ms, module render() "
                  f"{row[1]:.2f} ms (its stages {row[2]:.2f} ms); first frame {row[3]:.1f} against {row[4]:.1f} ms",
                  flush=True)
    program, module, stages = (statistics.median(r[i] for r in rows) for i in range(3))
    print(f"median of {a.runs} runs: program {program:.2f} ms/frame, module {module:.2f} ms/frame "
          f"({module / program:.3f}x; the module's own stages {stages:.2f} ms)")


if __name__ == "__main__":
    main()
