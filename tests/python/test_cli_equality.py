# SPDX-License-Identifier: MIT
"""The module draws what the program draws: for the same scene and frames, the polylines JSON is
the program's byte for byte (stage timings aside), each stroke's arrays written as the JSON writes
them are the program's values, and SVG, PNG and PDF files are identical."""
import json
import re

import numpy as np
import pytest

import inkline
from conftest import SAMPLES, icosphere, run_cli, without_timings, write_obj

# Per-point arrays and the scale the JSON rounds them to (export/json.cpp); None: full precision.
ROUNDING = {"points": 1e4, "world": None, "u": 1e3, "intensity": 1e4, "width": 1e3}


def json_round(values, scale):
    """std::round(v * scale) / scale, as the JSON writer rounds (halves away from zero)."""
    x = np.asarray(values, np.float64) * scale
    return np.where(x >= 0, np.floor(x + 0.5), np.ceil(x - 0.5)) / scale


def formatted(values, scale):
    return json.dumps((values if scale is None else json_round(values, scale)).tolist())


def strip_ms(text):
    return re.sub(r'"ms":\{[^}]*\}', '"ms":{}', text)


def assert_frame_is_cli(frame, cli_json_path):
    cli_text = cli_json_path.read_text()
    assert strip_ms(frame.to_json()) == strip_ms(cli_text)
    cli = json.loads(cli_text)
    assert len(frame.strokes) == len(cli["strokes"]) > 0
    for mine, theirs in zip(frame.strokes, cli["strokes"]):
        assert (mine.id, mine.kind, mine.visible, mine.drawn, mine.closed, list(mine.ends)) == \
            (theirs["id"], theirs["kind"], theirs["visible"], theirs["drawn"], theirs["closed"], theirs["ends"])
        for key, scale in ROUNDING.items():
            assert formatted(getattr(mine, key), scale) == json.dumps(theirs[key]), (mine.id, key)
        assert json.dumps(mine.edges.tolist()) == json.dumps(theirs["edges"])
        assert [formatted(r, 1e4) for r in mine.outline] == [json.dumps(r) for r in theirs["outline"]]
        assert mine.hidden_segments.tolist() == theirs.get("hidden_segments", [])
        assert mine.style == theirs.get("style") and mine.object == theirs.get("object")
        assert (mine.group, mine.level, mine.parent, mine.order) == \
            (theirs["group"], theirs["level"], theirs["parent"], theirs["order"])
    # Read back, the program's file gives the same strokes to the JSON's precision.
    back = inkline.read_json(cli_json_path)
    for mine, theirs in zip(frame.strokes, back.strokes):
        np.testing.assert_array_equal(json_round(mine.points, 1e4), theirs.points)
        np.testing.assert_array_equal(mine.world, theirs.world)
        np.testing.assert_array_equal(mine.edges, theirs.edges)


def test_torus_sample_frames_files_and_arrays(inkline_exe, tmp_path, monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "0")
    scene = SAMPLES / "torus" / "scene.json"
    out = tmp_path / "cli"
    run_cli(inkline_exe, scene, "--frames", "1:4", "--visibility", "raycast", "--hidden", "-o", out,
            "--json", out / "%04d.json", "--svg", out / "%04d.svg", "--png", out / "%04d.png", "--pdf", out / "%04d.pdf")
    shot = inkline.open(scene, frames=(1, 4), visibility="raycast", hidden=True)
    assert list(shot.frames) == [1, 2, 3, 4]
    for n in shot.frames:
        frame = shot.render(n)
        assert frame.number == n and frame.image == (1024, 1024)
        assert any(not s.visible for s in frame.strokes), "hidden lines are drawn"
        assert_frame_is_cli(frame, out / f"{n:04d}.json")
        assert frame.to_svg() == (out / f"{n:04d}.svg").read_text()
        assert frame.to_png() == (out / f"{n:04d}.png").read_bytes()
        assert frame.to_pdf() == (out / f"{n:04d}.pdf").read_bytes()


def test_bare_mesh_turntable_and_smooth_contours(inkline_exe, tmp_path):
    mesh = SAMPLES / "looks" / "bushing.obj"
    for contour in ("mesh", "smooth"):
        out = tmp_path / contour
        run_cli(inkline_exe, mesh, "--frames", "1:3", "--visibility", "exact", "--contour", contour, "--json",
                out / "%d.json")
        shot = inkline.open(mesh, frames=(1, 3), visibility="exact", contour=contour)
        for n in shot.frames:
            assert_frame_is_cli(shot.render(n), out / f"{n}.json")


def test_styles_and_texture(inkline_exe, tmp_path, monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "0")
    scene = SAMPLES / "looks" / "brush.json"
    run_cli(inkline_exe, scene, "--frames", "1:2", "--visibility", "raycast", "--layers", "style", "--path-format",
            "bezier", "--json", tmp_path / "%d.json", "--svg", tmp_path / "%d.svg", "--pdf", tmp_path / "%d.pdf")
    shot = inkline.open(scene, frames=(1, 2), visibility="raycast")
    for n in shot.frames:
        frame = shot.render(n)
        assert any(s.style for s in frame.strokes)
        assert_frame_is_cli(frame, tmp_path / f"{n}.json")
        assert frame.to_svg(layers="style", path_format="bezier") == (tmp_path / f"{n}.svg").read_text()
        pdf = frame.to_pdf(layers="style", path_format="bezier")
        assert pdf == (tmp_path / f"{n}.pdf").read_bytes()
        assert pdf != frame.to_pdf(layers="kind", path_format="bezier"), "the PDF's layers follow `layers`"


SPHERE_SCENE = {
    "camera": {"eye": [0.3, 0.5, 3.5], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": 40,
               "orbit": {"axis": [0, 1, 0], "degrees": 30}},
    "light": {"direction": [-1, -1, -1]},
    "lines": {"silhouette": True, "crease": True, "crease_angle_deg": 30},
}


def test_arrays_in_code_equal_the_same_mesh_from_a_file(inkline_exe, tmp_path):
    vertices, faces = icosphere(3)
    vertices = vertices * [1.0, 0.8, 1.2]
    write_obj(tmp_path / "sphere.obj", vertices, faces)
    doc = {"mesh": "sphere.obj", "image": {"width": 640, "height": 480}, "frames": [1, 3], **SPHERE_SCENE}
    (tmp_path / "scene.json").write_text(json.dumps(doc))
    run_cli(inkline_exe, tmp_path / "scene.json", "--visibility", "exact", "--json", tmp_path / "%d.json")
    shot = inkline.scene(vertices, faces, image=(640, 480), frames=(1, 3), name="sphere.obj", visibility="exact",
                         **SPHERE_SCENE)
    for n in shot.frames:
        assert_frame_is_cli(shot.render(n), tmp_path / f"{n}.json")


def test_deforming_arrays_equal_an_obj_sequence(inkline_exe, tmp_path):
    vertices, faces = icosphere(2)
    frames = np.stack([vertices * [1.0 + 0.1 * k, 1.0, 1.0 - 0.05 * k] for k in range(3)])
    for k, v in enumerate(frames):
        write_obj(tmp_path / f"m_{k + 1}.obj", v, faces)
    doc = {"mesh": {"sequence": "m_%d.obj"}, "image": {"width": 400, "height": 400}, "frames": [1, 3], **SPHERE_SCENE}
    (tmp_path / "scene.json").write_text(json.dumps(doc))
    run_cli(inkline_exe, tmp_path / "scene.json", "--visibility", "exact", "--json", tmp_path / "%d.json")
    shot = inkline.scene(frames, faces, image=(400, 400), frames=(1, 3), visibility="exact", **SPHERE_SCENE)
    for n in shot.frames:
        assert_frame_is_cli(shot.render(n), tmp_path / f"{n}.json")
