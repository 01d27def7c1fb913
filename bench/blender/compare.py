#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# inkline against Blender's Line Art (+ grease-pencil SVG export) and Freestyle (+ its SVG
# exporter) on the same scene: per-frame times and peak memory, side by side.
#
#   bench/blender/compare.py [--inkline build/cli/inkline] [--pipeline-bench PATH] [--work DIR] [--runs 5]
#       [--levels 4] [--frames 24] [--size 1024] [--freestyle-frames 4] [--no-freestyle]
#       [--reuse] [--per-frame] [-- EXTRA INKLINE RENDER ARGS]
#
# Installs nothing. Needs `blender` (Debian's 3.4) on PATH for the scene and the peers; without
# it the peers are skipped with a message, and inkline is timed alone if --work already holds a
# scene from an earlier run.
#
# Method (docs/performance.md):
# - build_scene.py builds the scene once (Suzanne, subdivided, triangulated; orbiting camera)
#   and writes the OBJ, the inkline scene with every camera, and a .blend.
# - Runs alternate (inkline first on even runs, Blender first on odd ones) so that the load of
#   this shared machine falls on both alike.
# - Start-up is excluded on both sides. inkline: the stage times `render -v` prints per frame
#   (extract .. svg, every stage of the frame including the SVG file; mesh loading happens
#   before the first frame and is reported apart), and the wall time from one frame's `-v` line
#   to the next (the next frame's lines are found while a frame is drawn, so the stage times of
#   a frame overlap the frame before's and add up to more than a frame costs the run). Blender: time_blender.py times frame_set
#   (Line Art's evaluation) + gpencil_export_svg per frame after the .blend is loaded.
# - Per frame: the median over runs; the table gives the median over frames of those, the
#   first frame (inkline builds its hierarchies there, once per mesh) and the whole run.
# - Freestyle: a Cycles render with Freestyle and its SVG add-on, minus the same render without
#   Freestyle, frame by frame (one run each, fewer frames: it is slow).
# - Peak memory: the maximum resident set size of each process, from wait4() (what
#   /usr/bin/time -v reports), largest over runs.
# - CPU time per frame (all threads), which the load of a shared machine disturbs far less than
#   wall time: Blender's from time.process_time() around each frame; inkline's from
#   inkline_pipeline_bench (bench/pipeline/, built with -DINKLINE_BUILD_BENCH=ON), which runs the
#   same stages as `render --svg` and times each frame in process CPU time. Found next to the
#   inkline binary's build folder, or given with --pipeline-bench; skipped when missing.

import argparse
import functools
import json
import os
import re
import shutil
import statistics
import sys
import tempfile
from pathlib import Path

import measured_run
from measured_run import FRAME_LINE, ms_between_frames

HERE = Path(__file__).resolve().parent
REPO = HERE.parent.parent
run = functools.partial(measured_run.run, who="compare.py")


STAGE = re.compile(r", ([a-z_]+) ([0-9.]+) ms")


def inkline_frames(text):
    """{frame: ms} from `render -v`: the sum of the frame's stage times."""
    out = {}
    for m in FRAME_LINE.finditer(text):
        out[int(m.group(1))] = sum(float(ms) for _, ms in STAGE.findall(m.group(0)))
    return out


def median_per_frame(runs):
    """runs: list of {frame: ms} -> {frame: median over runs}."""
    frames = sorted(set().union(*runs))
    return {f: statistics.median(r[f] for r in runs if f in r) for f in frames}


def summary(per_frame):
    values = [per_frame[f] for f in sorted(per_frame)]
    return {"median": statistics.median(values), "first": values[0], "mean": statistics.mean(values),
            "min": min(values), "max": max(values)}


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--inkline", default=str(REPO / "build" / "cli" / "inkline"))
    ap.add_argument("--pipeline-bench", default=None, help="inkline_pipeline_bench (default: next to --inkline)")
    ap.add_argument("--work", default=os.path.join(tempfile.gettempdir(), "inkline-bench-blender"))
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--levels", type=int, default=4)
    ap.add_argument("--frames", type=int, default=24)
    ap.add_argument("--size", type=int, default=1024)
    ap.add_argument("--freestyle-frames", type=int, default=4)
    ap.add_argument("--no-freestyle", action="store_true")
    ap.add_argument("--reuse", action="store_true", help="keep the scene of an earlier run in --work")
    ap.add_argument("--per-frame", action="store_true", help="also print every frame's medians")
    ap.add_argument("extra", nargs="*", help="extra arguments for inkline render (after --)")
    args = ap.parse_args()

    inkline = Path(args.inkline)
    if not inkline.is_file():
        sys.exit("compare.py: no inkline at %s: build it (cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "
                 "&& cmake --build build) or pass --inkline" % inkline)
    work = Path(args.work)
    scene_dir = work / "scene"
    blender = shutil.which("blender")
    if not blender:
        print("compare.py: blender not found on PATH: skipping Blender Line Art and Freestyle "
              "(Debian: apt-get install blender).")
        if not (scene_dir / "scene.json").is_file():
            print("compare.py: no scene in %s either (build_scene.py makes it with Blender): nothing to time." % scene_dir)
            return 0
    for sub in ("logs", "inkline", "blender"):
        (work / sub).mkdir(parents=True, exist_ok=True)

    if blender and not (args.reuse and (scene_dir / "scene.blend").is_file()):
        run([blender, "-b", "--factory-startup", "--python", str(HERE / "build_scene.py"), "--",
             str(scene_dir), "--levels", str(args.levels), "--frames", str(args.frames), "--size", str(args.size)],
            work / "logs" / "build_scene.log")
    scene = json.loads((scene_dir / "scene.json").read_text())
    faces = sum(1 for line in open(scene_dir / "suzanne.obj") if line.startswith("f "))
    load_before = os.getloadavg()

    def time_inkline(r):
        cmd = [str(inkline), "render", str(scene_dir / "scene.json"), "--svg",
               str(work / "inkline" / "frame_%04d.svg"), "-v"] + args.extra
        stamps = []
        wall, cpu, rss, text = run(cmd, work / "logs" / ("inkline_%d.log" % r), stamps)
        frames = inkline_frames(text)
        if len(frames) != scene["frames"][1] - scene["frames"][0] + 1:
            sys.exit("compare.py: could not read inkline's per-frame times from -v (see %s)" % (work / "logs"))
        return {"frames": frames, "wall": wall, "cpu": cpu, "rss": rss, "between": ms_between_frames(stamps)}

    def time_blender(mode, r, frames=None):
        result = work / "blender" / ("%s_%d.json" % (mode, r))
        cmd = [blender, "-b", str(scene_dir / "scene.blend"), "--python", str(HERE / "time_blender.py"), "--",
               mode, str(result), "--svg-dir", str(work / "blender" / "svg")]
        if frames:
            cmd += ["--frames", "%d:%d" % frames]
        wall, cpu, rss, _ = run(cmd, work / "logs" / ("%s_%d.log" % (mode, r)))
        data = json.loads(result.read_text())
        return {"frames": {f["frame"]: f["ms"] for f in data["frames"]},
                "cpu_frames": {f["frame"]: f.get("cpu_ms", 0.0) for f in data["frames"]}, "wall": wall, "cpu": cpu,
                "rss": rss}

    pipeline_bench = Path(args.pipeline_bench) if args.pipeline_bench else \
        inkline.parent.parent / "bench" / "pipeline" / "inkline_pipeline_bench"

    def inkline_cpu_per_frame(r):
        """Median process CPU ms per frame (frames 2..) from inkline_pipeline_bench, or None."""
        if not pipeline_bench.is_file():
            return None
        _, _, _, text = run([str(pipeline_bench), str(scene_dir / "scene.json"), "--svg", str(work / "inkline_bench")],
                            work / "logs" / ("pipeline_bench_%d.log" % r))
        m = re.search(r"\*\*per frame\*\* \| \*\*([0-9.]+)\*\* \| \*\*([0-9.]+)\*\*", text)
        return float(m.group(2)) if m else None

    ink_runs, la_runs, ink_cpu = [], [], []
    for r in range(args.runs):
        order = ("inkline", "lineart") if r % 2 == 0 else ("lineart", "inkline")
        for side in order:
            if side == "inkline":
                ink_runs.append(time_inkline(r))
                cpu_ms = inkline_cpu_per_frame(r)
                if cpu_ms is not None:
                    ink_cpu.append(cpu_ms)
            elif blender:
                la_runs.append(time_blender("lineart", r))
        print("compare.py: run %d/%d done" % (r + 1, args.runs), file=sys.stderr)

    fs_line = None
    if blender and not args.no_freestyle and args.freestyle_frames > 0:
        span = (1, min(args.freestyle_frames, args.frames))
        render_only = time_blender("render", 0, span)
        with_lines = time_blender("freestyle", 0, span)
        lines = {f: with_lines["frames"][f] - render_only["frames"][f] for f in with_lines["frames"]}
        cpu_lines = {f: with_lines["cpu_frames"][f] - render_only["cpu_frames"][f] for f in with_lines["frames"]}
        fs_line = {"frames": lines, "cpu": statistics.median(cpu_lines.values()), "rss": with_lines["rss"],
                   "render_rss": render_only["rss"], "render_median": statistics.median(render_only["frames"].values())}
    base_rss = time_blender("baseline", 0, (1, 1))["rss"] if blender else None
    load_after = os.getloadavg()

    ink = summary(median_per_frame([x["frames"] for x in ink_runs]))
    run_medians = [statistics.median(x["frames"].values()) for x in ink_runs]
    print("\n%d triangles, %d frames at %dx%d, %d alternating runs; load average %.1f before, %.1f after "
          "(%d CPUs)\n" % (faces, args.frames, args.size, args.size, args.runs, load_before[0], load_after[0],
                           os.cpu_count()))
    ink_cpu_ms = statistics.median(ink_cpu) if ink_cpu else None
    print("| renderer | ms/frame (median) | min - max | first frame ms | mean ms/frame | vs inkline | "
          "CPU ms/frame | vs inkline (CPU) | peak RSS MB | run medians ms |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|")

    def row(name, s, cpu_ms, rss, medians):
        is_inkline = name.startswith("inkline")
        ratio = s["median"] / ink["median"]
        cpu_ratio = "-" if cpu_ms is None or ink_cpu_ms is None else \
            "1x" if is_inkline else "%.1fx" % (cpu_ms / ink_cpu_ms)
        print("| %s | %.1f | %.1f - %.1f | %.1f | %.1f | %s | %s | %s | %s | %s |" % (
            name, s["median"], s["min"], s["max"], s["first"], s["mean"],
            "1x" if is_inkline else "%.1fx slower" % ratio, "-" if cpu_ms is None else "%.1f" % cpu_ms, cpu_ratio,
            "%.0f" % rss if rss is not None else "-", ", ".join("%.0f" % m for m in medians)))

    row("inkline (brush outlines + SVG)", ink, ink_cpu_ms, max(x["rss"] for x in ink_runs), run_medians)
    if la_runs:
        la = summary(median_per_frame([x["frames"] for x in la_runs]))
        la_cpu = statistics.median(median_per_frame([x["cpu_frames"] for x in la_runs]).values())
        row("Blender Line Art + gpencil SVG export", la, la_cpu, max(x["rss"] for x in la_runs),
            [statistics.median(x["frames"].values()) for x in la_runs])
    if fs_line:
        row("Blender Freestyle + SVG add-on, minus render", summary(fs_line["frames"]), fs_line["cpu"], fs_line["rss"], [])
    print()
    between = statistics.median(x["between"] for x in ink_runs)
    print("inkline: %.1f ms wall between one frame and the next (median over runs of the median over frames "
          "2..; a frame's stage times overlap the frame before's)%s" % (
              between, "; Line Art's median frame is %.1fx that" % (la["median"] / between) if la_runs else ""))
    print("inkline whole runs: %s s wall (mesh loading and first-frame builds included), %s s CPU" % (
        ", ".join("%.2f" % x["wall"] for x in ink_runs), ", ".join("%.2f" % x["cpu"] for x in ink_runs)))
    if la_runs:
        print("Line Art whole runs: %s s wall (Blender start-up included)" % ", ".join("%.2f" % x["wall"] for x in la_runs))
    if fs_line:
        print("Freestyle: %d frames, one run; the Cycles render it rides on took %.0f ms/frame (subtracted); "
              "render alone peaked at %.0f MB" % (len(fs_line["frames"]), fs_line["render_median"], fs_line["render_rss"]))
    if base_rss is not None:
        print("Blender with the scene loaded and no lines: %.0f MB peak" % base_rss)
    if args.per_frame:
        ink_pf = median_per_frame([x["frames"] for x in ink_runs])
        la_pf = median_per_frame([x["frames"] for x in la_runs]) if la_runs else {}
        print("\n| frame | inkline ms | Line Art ms |\n|---:|---:|---:|")
        for f in sorted(ink_pf):
            print("| %d | %.1f | %s |" % (f, ink_pf[f], "%.1f" % la_pf[f] if f in la_pf else "-"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
