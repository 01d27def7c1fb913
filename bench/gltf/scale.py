#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# The glTF shot of build_shot.py at growing detail: inkline against Blender's own evaluation
# (visible lines, exact visibility, compare_lines.py) and against Line Art on the same .blend
# (contour, crease and intersection on), per frame, side by side in one run.
#
#   bench/gltf/scale.py [--inkline build/cli/inkline] [--details 1,2,4,12,34] [--frames 12] [--runs 3]
#                       [--work DIR]
#
# A detail multiplies the shot's segment counts and need not be whole: 1.4 gives about 2k triangles.
#
# Per detail: triangles; inkline's wall ms per frame: the median time from one frame's
# `render -v` line to the next, over frames 2..N of --runs runs writing SVG (as Line Art's
# figure exports SVG), which is what a frame costs the run now that the next frame's lines are
# found while a frame is drawn; beside it the median of the stages' sum (each stage's own time,
# so with overlapping work more than a frame's share); its peak resident memory; Line Art's
# median over as many runs (evaluation + SVG export, bench/blender/time_blender.py), each run
# right after one of inkline's; the ratio of the two wall times; the worst precision and recall
# of visible length against Blender's evaluation within 1 px. Needs `blender` on PATH; installs
# nothing.
import argparse
import json
import os
import re
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "bench", "blender"))
import measured_run  # noqa: E402


def inkline_run(inkline, glb, frames, out, run):
    """One run: (wall ms between frames, stage sums ms) of frames 2.., and its peak RSS MB."""
    os.makedirs(out, exist_ok=True)
    stamps = []
    cmd = [inkline, "render", glb, "--frames", "1:%d" % frames, "-v", "--svg", os.path.join(out, "svg", "%04d.svg")]
    _, _, peak, text = measured_run.run(cmd, os.path.join(out, "run%d.log" % run), stamps, who="inkline")
    times = [t for t, line in stamps if measured_run.FRAME_LINE.match(line)]
    between = [1000.0 * (b - a) for a, b in zip(times, times[1:])]
    sums = [sum(float(x) for x in re.findall(r"([\d.]+) ms", m.group(2)))
            for m in re.finditer(r"^frame (\d+): .*?, (load .*)$", text, re.M) if int(m.group(1)) >= 2]
    return between, sums, peak


def faces_of(inkline, glb, out):
    one = os.path.join(out, "json", "0001.json")
    subprocess.run([inkline, "render", glb, "--frames", "1:1", "--json", one], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return json.load(open(one))["stats"]["faces"]


def lineart_run(blend, frames, out):
    """One Line Art run: its ms per frame (evaluation + SVG export) of frames 2.."""
    result = os.path.join(out, "lineart.json")
    subprocess.run(["blender", "-b", blend, "--python", os.path.join(ROOT, "bench", "blender", "time_blender.py"), "--",
                    "lineart", result, "--frames", "1:%d" % frames, "--svg-dir", os.path.join(out, "lineart_svg")],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return [r["eval_ms"] + r["export_ms"] for r in json.load(open(result))["frames"] if r["frame"] >= 2]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--inkline", default=os.path.join(ROOT, "build", "cli", "inkline"))
    ap.add_argument("--details", default="1,2,4,12,34")
    ap.add_argument("--frames", type=int, default=12)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--work", default="/tmp/inkline_gltf_bench")
    args = ap.parse_args()
    print("| triangles | inkline ms/frame | stage sums | Line Art ms/frame | Line Art / inkline | inkline peak MB "
          "| precision | recall |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|")
    for detail in (float(d) for d in args.details.split(",")):
        shot = os.path.join(args.work, "detail%g" % detail)
        subprocess.run(["blender", "-b", "--factory-startup", "--python", os.path.join(HERE, "build_shot.py"), "--", shot,
                        "--frames", str(args.frames), "--detail", "%g" % detail],
                       check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        check = subprocess.run([sys.executable, os.path.join(HERE, "compare_lines.py"), shot, "--inkline", args.inkline],
                               capture_output=True, text=True)
        worst = re.search(r"worst precision ([\d.]+), worst recall ([\d.]+)", check.stdout)
        if check.returncode != 0 or not worst:
            raise SystemExit("compare_lines.py failed (it needs numpy for %s):\n%s" % (sys.executable, check.stderr[-2000:]))
        # inkline and Line Art take turns, so that both see the machine as it is.
        between, sums, peaks, lineart = [], [], [], []
        for run in range(args.runs):
            b, s, peak = inkline_run(args.inkline, os.path.join(shot, "shot.glb"), args.frames, os.path.join(shot, "ink"), run)
            between += b
            sums += s
            peaks.append(peak)
            lineart += lineart_run(os.path.join(shot, "shot.blend"), args.frames, shot)
        faces = faces_of(args.inkline, os.path.join(shot, "shot.glb"), os.path.join(shot, "ink"))
        ink_ms, sums_ms, peak, la_ms = (statistics.median(between), statistics.median(sums), statistics.median(peaks),
                                        statistics.median(lineart))
        print("| %s | %.1f | %.1f | %.1f | %.1fx | %.0f | %s | %s |" % (
            format(faces, ","), ink_ms, sums_ms, la_ms, la_ms / ink_ms, peak, worst.group(1), worst.group(2)), flush=True)


if __name__ == "__main__":
    main()
