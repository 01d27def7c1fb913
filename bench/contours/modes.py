#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Smooth contours against mesh-edge silhouettes on real meshes: each mesh turns 3 degrees a frame
# for 120 frames at 1024x1024 (the default turntable's camera, orbiting), drawn by the real CLI
# once per `--contour` mode, and measured from the polylines JSON:
#
#   bench/contours/modes.py MESH [MESH ...] [--inkline build/cli/inkline] [--work DIR] [--frames 120]
#       [--check-every N]
#
# Per mesh and mode: drawn strokes per frame (mean, and the total over the sequence), visible
# length per frame, stroke coherence (share of visible length whose id was in the frame before,
# over the whole sequence and the worst frame, bench/coherence/coherence.py), and the per-frame
# stage time (median of extract + chain + visibility + strokes over frames 2..). For smooth mode,
# the sequence is drawn once more with hidden lines kept and every N-th frame's contour
# visibility is checked by bench/contours/exact_check.py, an independent exact ray test of the
# same points (numpy: Debian's python3-numpy). Prints a markdown table.
#
# The meshes of docs/contours.md are Debian's libcgal-demo data:
#   tar xzf /usr/share/doc/libcgal-demo/data.tar.gz data/meshes
#   bench/contours/modes.py data/meshes/{bunny00,ChineseDragon-10kv,armadillo,fandisk}.off

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent.parent
sys.path.insert(0, str(HERE.parent / "coherence"))
import coherence  # noqa: E402
from turntable import turntable_scene  # noqa: E402


def render(inkline, scene, out, contour, hidden=False):
    """Draws the scene's frames to polylines JSON under `out`."""
    cmd = [inkline, "render", str(scene), "-q", "--contour", contour, "--json", str(out / "f_%04d.json")]
    if hidden:
        cmd.append("--hidden")
    subprocess.run(cmd, check=True)


def measure(folder):
    """Strokes, length, coherence and stage time of one rendered sequence."""
    paths = coherence.expand([str(folder)])
    frames = coherence.load(paths)
    drawn, lengths, stage_ms = [], [], []
    for path in paths:
        data = json.loads(Path(path).read_text())
        stats = data["stats"]
        drawn.append(stats["strokes"]["drawn"])
        lengths.append(sum(stats["visible_length_px"].values()))
        if data["frame"] > 1:
            stage_ms.append(sum(stats["ms"][k] for k in ("extract", "chain", "visibility", "strokes")))
    fractions, inherited_total, visible_total = [], 0.0, 0.0
    for f in sorted(frames):
        if f - 1 not in frames:
            continue
        before = {s["id"] for s in frames[f - 1]}
        visible = sum(s["length"] for s in frames[f] if s["visible"])
        inherited = sum(s["length"] for s in frames[f] if s["visible"] and s["id"] in before)
        fractions.append(inherited / visible if visible > 0 else 1.0)
        inherited_total += inherited
        visible_total += visible
    return {"drawn_mean": statistics.mean(drawn), "drawn_total": sum(drawn),
            "length_mean": statistics.mean(lengths),
            "coherence": inherited_total / max(visible_total, 1e-12), "coherence_min": min(fractions),
            "ms": statistics.median(stage_ms) if stage_ms else float("nan")}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("meshes", nargs="+")
    parser.add_argument("--inkline", default=str(REPO / "build" / "cli" / "inkline"))
    parser.add_argument("--work", help="where the JSON goes (default: a new temporary folder)")
    parser.add_argument("--frames", type=int, default=120)
    parser.add_argument("--check-every", type=int, default=4, help="exact check of every N-th frame (0: none)")
    args = parser.parse_args()
    work = Path(args.work or tempfile.mkdtemp(prefix="inkline-contours-"))

    rows = []
    for mesh in args.meshes:
        name = Path(mesh).stem
        base = work / name
        base.mkdir(parents=True, exist_ok=True)
        scene = base / "scene.json"
        scene.write_text(json.dumps(turntable_scene(args.inkline, mesh, args.frames), indent=2))
        result = {}
        for contour in ("mesh", "smooth"):
            out = base / contour
            render(args.inkline, scene, out, contour)
            result[contour] = measure(out)
        agreement = None
        if args.check_every > 0:
            out = base / "smooth-hidden"
            render(args.inkline, scene, out, "smooth", hidden=True)
            report = base / "exact_check.json"
            subprocess.run([sys.executable, str(HERE / "exact_check.py"), str(mesh), str(out),
                            "--every", str(args.check_every), "--json", str(report)], check=True,
                           stdout=subprocess.DEVNULL)
            agreement = json.loads(report.read_text())["agreement"]
        rows.append((name, result, agreement))
        print(f"{name}: done", file=sys.stderr)

    print("| mesh | drawn strokes / frame, mesh -> smooth | fewer | coherence mesh | coherence smooth "
          "| worst frame mesh / smooth | ms / frame mesh / smooth | exact agreement (smooth) |")
    print("|---|---|---:|---:|---:|---|---|---:|")
    for name, r, agreement in rows:
        m, s = r["mesh"], r["smooth"]
        fewer = 1.0 - s["drawn_total"] / max(m["drawn_total"], 1)
        check = "-" if agreement is None else f"{100.0 * agreement:.2f}%"
        print(f"| {name} | {m['drawn_mean']:.1f} -> {s['drawn_mean']:.1f} | {100.0 * fewer:.0f}% "
              f"| {100.0 * m['coherence']:.2f}% | {100.0 * s['coherence']:.2f}% "
              f"| {100.0 * m['coherence_min']:.1f}% / {100.0 * s['coherence_min']:.1f}% "
              f"| {m['ms']:.1f} / {s['ms']:.1f} | {check} |")
    print(f"JSON under {work}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
