#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# The glTF shot of build_shot.py at growing detail: inkline against Blender's own evaluation
# (visible lines, exact visibility, compare_lines.py) and against Line Art on the same .blend
# (contour, crease and intersection on), per frame, side by side in one run.
#
#   bench/gltf/scale.py [--inkline build/cli/inkline] [--details 1,4,12,34] [--frames 12] [--work DIR]
#
# Per detail: triangles; inkline's median ms per frame over frames 2..N (every stage and the
# SVG, from `render -v`) and its peak resident memory; Line Art's median (evaluation + SVG export,
# bench/blender/time_blender.py); the ratio; the worst precision and recall of visible length
# against Blender's evaluation within 1 px. Needs `blender` on PATH; installs nothing.
import argparse
import json
import os
import re
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def run_measured(cmd):
    """Runs cmd; returns its stderr."""
    proc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        raise SystemExit("failed: %s\n%s" % (" ".join(cmd), proc.stderr))
    return proc.stderr


def inkline_frames(inkline, glb, frames, out):
    cmd = ["/usr/bin/time", "-f", "peak_kb %M", inkline, "render", glb, "--frames", "1:%d" % frames, "-v",
           "--svg", os.path.join(out, "svg", "%04d.svg"), "--json", os.path.join(out, "json", "%04d.json")]
    err = run_measured(cmd)
    per_frame = {}
    for line in err.splitlines():
        m = re.match(r"frame (\d+): .*?, (load .*)$", line)
        if m:
            per_frame[int(m.group(1))] = sum(float(x) for x in re.findall(r"([\d.]+) ms", m.group(2)))
    peak = int(re.search(r"peak_kb (\d+)", err).group(1)) / 1024.0
    faces = json.load(open(os.path.join(out, "json", "0001.json")))["stats"]["faces"]
    return statistics.median(per_frame[f] for f in range(2, frames + 1)), peak, faces


def lineart_frames(blend, frames, out):
    result = os.path.join(out, "lineart.json")
    subprocess.run(["blender", "-b", blend, "--python", os.path.join(ROOT, "bench", "blender", "time_blender.py"), "--",
                    "lineart", result, "--frames", "1:%d" % frames, "--svg-dir", os.path.join(out, "lineart_svg")],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    records = json.load(open(result))["frames"]
    return statistics.median(r["eval_ms"] + r["export_ms"] for r in records if r["frame"] >= 2)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--inkline", default=os.path.join(ROOT, "build", "cli", "inkline"))
    ap.add_argument("--details", default="1,4,12,34")
    ap.add_argument("--frames", type=int, default=12)
    ap.add_argument("--work", default="/tmp/inkline_gltf_bench")
    args = ap.parse_args()
    print("| triangles | inkline ms/frame | Line Art ms/frame | Line Art / inkline | inkline peak MB | precision | recall |")
    print("|---:|---:|---:|---:|---:|---:|---:|")
    for detail in (int(d) for d in args.details.split(",")):
        shot = os.path.join(args.work, "detail%d" % detail)
        subprocess.run(["blender", "-b", "--factory-startup", "--python", os.path.join(HERE, "build_shot.py"), "--", shot,
                        "--frames", str(args.frames), "--detail", str(detail)],
                       check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        check = subprocess.run([sys.executable, os.path.join(HERE, "compare_lines.py"), shot, "--inkline", args.inkline],
                               capture_output=True, text=True)
        worst = re.search(r"worst precision ([\d.]+), worst recall ([\d.]+)", check.stdout)
        if check.returncode != 0 or not worst:
            raise SystemExit("compare_lines.py failed (it needs numpy for %s):\n%s" % (sys.executable, check.stderr[-2000:]))
        ink_ms, peak, faces = inkline_frames(args.inkline, os.path.join(shot, "shot.glb"), args.frames, os.path.join(shot, "ink"))
        la_ms = lineart_frames(os.path.join(shot, "shot.blend"), args.frames, shot)
        print("| %s | %.1f | %.1f | %.1fx | %.0f | %s | %s |" % (
            format(faces, ","), ink_ms, la_ms, la_ms / ink_ms, peak, worst.group(1), worst.group(2)), flush=True)


if __name__ == "__main__":
    main()
