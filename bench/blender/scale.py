#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# How inkline's time per frame and memory grow with the mesh: Suzanne subdivided 1 to 5 times
# (3.9k to 1.0M triangles, built by build_scene.py in Blender), 24 frames at 1024x1024 with SVG
# output, each size rendered several times by the real CLI.
#
#   bench/blender/scale.py [--inkline build/cli/inkline] [--pipeline-bench PATH] [--work DIR] [--levels 1,2,3,4,5]
#       [--runs 3] [--frames 24] [--reuse] [--mesh FILE ...] [-- EXTRA INKLINE RENDER ARGS]
#
# Installs nothing. Without `blender` on PATH the Suzanne meshes cannot be built: the script
# says so and times only the inputs given with --mesh, or those an earlier run left in --work with
# --reuse. --mesh takes any input `inkline render` does: a mesh file is rendered as inkline's
# default turntable, a glTF shot (bench/gltf/build_shot.py's, say) through its own camera and
# animation. Extra render arguments apply to every input: `-- --contour smooth` times smooth
# contours.
#
# Per size: the median over frames 2.. of the per-frame stage times `render -v` prints (every
# stage including the SVG file) and of the wall time from one frame's line to the next (where a
# frame's work overlaps the frame before, as the next frame's lines found while a frame is
# drawn do, this is what a frame costs the run, and the stage times add up to more), the first frame (which builds the cone tree and the BVH), the
# whole run from process start to exit (reading the mesh included) and its frames per second,
# CPU time, and the peak resident memory from wait4(), also net of the binary's own baseline
# (shared libraries: the same command on a one-triangle mesh), against the mesh's own size
# in memory (12 bytes per vertex and per triangle, core::Mesh). With inkline_pipeline_bench
# (bench/pipeline/; found next to the inkline binary's build folder), also the process CPU time
# per frame (frames 2..) of the same stages, which the machine's load disturbs far less.

import argparse
import functools
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
run = functools.partial(measured_run.run, who="scale.py")
STAGE = re.compile(r", ([a-z_]+) ([0-9.]+) ms")


def mesh_counts(path, inkline, log):
    """Vertices and triangles of a mesh file: an OBJ's (polygons fan-triangulated) read here, any
    other input's (a glTF shot's welded and in total, .off, .ply, .stl) from `inkline info`."""
    if Path(path).suffix.lower() != ".obj":
        text = run([str(inkline), "info", str(path)], log)[3]
        return (int(re.search(r"^vertices: (\d+)", text, re.M).group(1)),
                int(re.search(r"^faces: (\d+)", text, re.M).group(1)))
    vertices = triangles = 0
    with open(path) as f:
        for line in f:
            vertices += line.startswith("v ")
            if line.startswith("f "):
                triangles += max(0, len(line.split()) - 3)
    return vertices, triangles


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--inkline", default=str(REPO / "build" / "cli" / "inkline"))
    ap.add_argument("--pipeline-bench", default=None, help="inkline_pipeline_bench (default: next to --inkline)")
    ap.add_argument("--work", default=os.path.join(tempfile.gettempdir(), "inkline-bench-scale"))
    ap.add_argument("--levels", default="1,2,3,4,5")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--frames", type=int, default=24)
    ap.add_argument("--reuse", action="store_true")
    ap.add_argument("--mesh", action="append", default=[], help="also time this input (a mesh: default turntable; a glTF shot)")
    ap.add_argument("extra", nargs="*", help="extra arguments for inkline render (after --)")
    args = ap.parse_args()

    inkline = Path(args.inkline)
    if not inkline.is_file():
        sys.exit("scale.py: no inkline at %s: build it or pass --inkline" % inkline)
    work = Path(args.work)
    (work / "logs").mkdir(parents=True, exist_ok=True)
    blender = shutil.which("blender")

    # The inputs: (label, render target, mesh file, frame arguments).
    inputs = []
    levels = [int(x) for x in args.levels.split(",") if x]
    if not blender and levels:
        print("scale.py: blender not found on PATH: cannot build the Suzanne meshes%s." %
              (" (using those left in %s)" % work if args.reuse else "; pass --mesh FILE to time other meshes"))
    for level in levels:
        scene_dir = work / ("suzanne_%d" % level)
        if blender and not (args.reuse and (scene_dir / "scene.json").is_file()):
            run([blender, "-b", "--factory-startup", "--python", str(HERE / "build_scene.py"), "--", str(scene_dir),
                 "--levels", str(level), "--frames", str(args.frames)], work / "logs" / ("build_%d.log" % level))
        if (scene_dir / "scene.json").is_file():
            inputs.append(("Suzanne, %d subdivisions" % level, scene_dir / "scene.json", scene_dir / "suzanne.obj", []))
    for mesh in args.mesh:
        inputs.append((Path(mesh).name, Path(mesh), Path(mesh), ["--frames", "1:%d" % args.frames]))
    if not inputs:
        print("scale.py: nothing to time.")
        return 0

    # The binary's own footprint: the same command on one triangle.
    tiny = work / "triangle.obj"
    tiny.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    _, _, base_rss, _ = run([str(inkline), "render", str(tiny), "--frames", "1:2", "--svg",
                             str(work / "out" / "tiny_%04d.svg"), "-q"] + args.extra, work / "logs" / "tiny.log")

    pipeline_bench = Path(args.pipeline_bench) if args.pipeline_bench else \
        inkline.parent.parent / "bench" / "pipeline" / "inkline_pipeline_bench"

    rows = []
    for label, target, mesh, frame_args in inputs:
        vertices, faces = mesh_counts(mesh, inkline, work / "logs" / "info.log")
        mesh_mb = 12.0 * (vertices + faces) / 2**20
        per_run = []
        for r in range(args.runs):
            cmd = [str(inkline), "render", str(target), "--svg", str(work / "out" / "frame_%04d.svg"), "-v"] + frame_args + args.extra
            stamps = []
            wall, cpu, rss, text = run(cmd, work / "logs" / ("%s_%d.log" % (mesh.stem + str(faces), r)), stamps)
            frames = {}
            for m in FRAME_LINE.finditer(text):
                frames[int(m.group(1))] = sum(float(ms) for _, ms in STAGE.findall(m.group(0)))
            first = min(frames)
            per_run.append({"wall": wall, "cpu": cpu, "rss": rss, "first": frames[first],
                            "later": statistics.median(v for f, v in frames.items() if f != first),
                            "interval": ms_between_frames(stamps),
                            "frames": len(frames)})
        cpu_per_frame = None
        if pipeline_bench.is_file() and str(target).endswith(".json"):
            _, _, _, text = run([str(pipeline_bench), str(target), "--svg", str(work / "out_bench"), "--repeat", "1"],
                                work / "logs" / ("bench_%d.log" % faces))
            m = re.search(r"\*\*per frame\*\* \| \*\*([0-9.]+)\*\* \| \*\*([0-9.]+)\*\*", text)
            cpu_per_frame = float(m.group(2)) if m else None
        med = lambda key: statistics.median(x[key] for x in per_run)
        rss = max(x["rss"] for x in per_run)
        n = per_run[0]["frames"]
        rows.append((label, faces, mesh_mb, med("later"), med("interval"), cpu_per_frame, med("first"), med("wall"),
                     n / med("wall"),
                     med("cpu"), rss, rss - base_rss, (rss - base_rss) / mesh_mb, min(x["wall"] for x in per_run),
                     max(x["wall"] for x in per_run)))
        print("scale.py: %s done" % label, file=sys.stderr)

    print("\n%d frames at 1024x1024 with SVG, %d runs per size (medians); load average %.1f; binary baseline %.0f MB\n"
          % (args.frames, args.runs, os.getloadavg()[0], base_rss))
    print("| mesh | triangles | mesh MB | ms/frame (frames 2..) | wall ms between frames | CPU ms/frame | frame 1 ms | "
          "whole run s (min-max) | frames/s, whole run | CPU s, whole run | peak RSS MB | RSS - baseline MB | / mesh |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for (label, faces, mesh_mb, later, interval, cpu_frame, first, wall, fps, cpu, rss, net, ratio, wall_min,
         wall_max) in rows:
        print("| %s | %d | %.1f | %.1f | %.1f | %s | %.0f | %.2f (%.2f-%.2f) | %.1f | %.2f | %.0f | %.0f | %.1fx |" % (
            label, faces, mesh_mb, later, interval, "-" if cpu_frame is None else "%.1f" % cpu_frame, first, wall,
            wall_min, wall_max, fps, cpu, rss, net, ratio))
    return 0


if __name__ == "__main__":
    sys.exit(main())
