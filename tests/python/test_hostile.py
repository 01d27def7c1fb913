# SPDX-License-Identifier: MIT
"""Arguments and files that cannot be drawn raise inkline.InputError (a ValueError) with one line
naming the argument, key or file, as the program's messages do; outputs that cannot be written
raise inkline.OutputError (an OSError) and leave no partial file; nothing crashes."""
import json
import os

import numpy as np
import pytest

import inkline
from conftest import SAMPLES, icosphere, run_cli

CAMERA = {"eye": [0, 0, 4], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": 40}
SPHERE = icosphere(1)


def raises(message, call, error=inkline.InputError):
    with pytest.raises(error) as e:
        call()
    assert message in str(e.value), str(e.value)
    assert "\n" not in str(e.value)
    return str(e.value)


def test_errors_are_the_programs(inkline_exe, tmp_path):
    bad = tmp_path / "scene.json"
    bad.write_text('{"mesh": "missing.obj", "camera": {"eye": [0, 0, 0], "target": [0, 0, 0]}}')
    cli = run_cli(inkline_exe, bad, "--json", tmp_path / "x.json", check=False)
    assert cli.returncode != 0
    message = raises("scene.json", lambda: inkline.open(bad))
    assert cli.stderr.strip() == "inkline: error: " + message
    assert issubclass(inkline.InputError, ValueError) and issubclass(inkline.OutputError, OSError)


@pytest.mark.parametrize("path, message", [
    ("no-such-file.obj", "no-such-file.obj"),
    ("empty.obj", "empty.obj"),
    ("folder", "folder"),
    ("broken.json", "broken.json"),
    ("mesh.xyz", "mesh.xyz"),
])
def test_files_that_cannot_be_read(tmp_path, path, message):
    (tmp_path / "empty.obj").write_text("")
    (tmp_path / "folder").mkdir()
    (tmp_path / "broken.json").write_text('{"mesh": ')
    (tmp_path / "mesh.xyz").write_text("1 2 3\n")
    raises(message, lambda: inkline.open(tmp_path / path))


@pytest.mark.parametrize("kwargs, message", [
    ({"frames": (5, 2)}, "frames"),
    ({"frames": "1:3"}, "frames"),
    ({"frames": (1.5, 2)}, "frames"),
    ({"frames": (1, 2**40)}, "frames"),
    ({"size": (0, 100)}, "size"),
    ({"size": (100, 10**9)}, "size"),
    ({"size": (True, 3)}, "size"),
    ({"hidden": "yes"}, "hidden"),
    ({"contour": "wiggly"}, "contour 'wiggly'"),
    ({"contour": 3}, "contour"),
    ({"visibility": "gl"}, "visibility 'gl'"),
    ({"visibility": "psychic"}, "visibility 'psychic'"),
    ({"tracker": "lazy"}, "tracker 'lazy'"),
    ({"max_faces": 10}, "more than 10 faces, the limit (raise it with max_faces=)"),
    ({"max_faces": -1}, "max_faces"),
    ({"animation": "walk"}, "animation: applies only to glTF"),
    ({"gltf_scene": 1}, "gltf_scene: applies only to glTF"),
    ({"gltf_scene": -3}, "gltf_scene"),
    ({"fps": float("nan")}, "fps"),
    ({"fps": 0}, "fps"),
])
def test_open_arguments(kwargs, message):
    raises(message, lambda: inkline.open(SAMPLES / "torus" / "scene.json", **kwargs))


@pytest.mark.parametrize("vertices, faces, message", [
    (np.array([[0, 0, np.nan], [1, 0, 0], [0, 1, 0]]), [[0, 1, 2]], "vertices[0]: coordinate nan is not finite"),
    (np.array([[0, 0, np.inf], [1, 0, 0], [0, 1, 0]]), [[0, 1, 2]], "vertices[0]: coordinate inf is not finite"),
    (np.array([[0, 0, 1e300], [1, 0, 0], [0, 1, 0]]), [[0, 1, 2]], "vertices[0]: coordinate"),
    (np.eye(3), [[0, 1, 3]], "faces[0]: vertex index 3 out of range (3 vertices)"),
    (np.eye(3), [[0, -1, 2]], "faces[0]: vertex index -1 out of range"),
    (np.eye(3), np.array([[0, 1, 2**63 - 1]], np.uint64), "out of range"),
    (np.eye(3), np.zeros((0, 3), int), "faces: no triangles"),
    (np.zeros((0, 3)), [[0, 1, 2]], "vertices: no vertices"),
    (np.eye(3)[:, :2], [[0, 1, 2]], "vertices: expected an array of shape (V, 3)"),
    (np.eye(3), [[0, 1, 2, 0]], "faces: expected an array of shape (T, 3)"),
    (np.eye(3), [[0.0, 1.0, 2.0]], "faces: expected integer vertex indices"),
    (np.eye(3), [["a", "b", "c"]], "faces: expected numbers"),
    ([[0, 0], [1, 0, 0]], [[0, 1, 2]], "vertices"),
    (np.zeros((2, 3, 2)), [[0, 1, 2]], "vertices: expected an array of shape"),
    (np.stack([np.eye(3), np.full((3, 3), np.nan)]), [[0, 1, 2]], "vertices[1][0]: coordinate nan"),
])
def test_arrays(vertices, faces, message):
    frames = (1, len(vertices)) if isinstance(vertices, np.ndarray) and vertices.ndim == 3 else (1, 1)
    raises(message, lambda: inkline.scene(vertices, faces, camera=CAMERA, frames=frames))


@pytest.mark.parametrize("kwargs, message", [
    ({"camera": {"eye": [0, 0, 0], "target": [0, 0, 0]}}, "camera"),
    ({"camera": "front"}, "camera: expected a dict"),
    ({"camera": CAMERA, "image": (0, 10)}, "image.width"),
    ({"camera": CAMERA, "light": {"direction": [float("nan"), 0, 0]}}, "scene: cannot be written as JSON"),
    ({"camera": CAMERA, "brush": {"width_max_px": -1}}, "brush.width_max_px"),
    ({"camera": CAMERA, "colour": 1}, "colour"),
    ({"camera": CAMERA, "mesh": "x.obj"}, "mesh: give the mesh as vertices and faces"),
    ({"camera": CAMERA, "frames": (1, 3), "max_faces": 5}, "faces: 80 triangles exceed the limit of 5"),
])
def test_scene_keys(kwargs, message):
    raises(message, lambda: inkline.scene(*SPHERE, **kwargs))


def test_deforming_arrays_have_their_frames_only():
    shot = inkline.scene(np.stack([SPHERE[0]] * 2), SPHERE[1], camera=CAMERA, frames=(1, 2))
    shot.render(1)
    shot.render(2)
    raises("frame 3: outside the shot's frames 1..2", lambda: shot.render(3))
    raises("frame 0: outside the shot's frames 1..2", lambda: shot.render(0))
    raises("frame: expected an integer", lambda: shot.render("3"))
    raises("vertices: 2 frames of positions for frames 1..3 (one set per frame)",
           lambda: inkline.scene(np.stack([SPHERE[0]] * 2), SPHERE[1], camera=CAMERA, frames=(1, 3)))


def test_unwritable_outputs_leave_old_files_and_no_temporaries(tmp_path):
    frame = inkline.scene(*SPHERE, camera=CAMERA).render(1)
    (tmp_path / "folder").mkdir()
    raises("folder", lambda: frame.write_svg(tmp_path / "folder"), inkline.OutputError)
    old = tmp_path / "old.svg"
    old.write_text("old")
    if os.geteuid() != 0:
        old.chmod(0o444)
        raises("old.svg", lambda: frame.write_svg(old), inkline.OutputError)
        assert old.read_text() == "old"
    blocker = tmp_path / "file"
    blocker.write_text("x")
    raises("file", lambda: frame.write_json(blocker / "frame.json"), inkline.OutputError)
    frame.write_svg(tmp_path / "new" / "frame.svg")
    assert (tmp_path / "new" / "frame.svg").read_text() == frame.to_svg()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file", "folder", "new", "old.svg"]
    assert sorted(p.name for p in (tmp_path / "new").iterdir()) == ["frame.svg"]


@pytest.mark.parametrize("call, message", [
    (lambda f: f.to_svg(layers="colour"), "layers 'colour'"),
    (lambda f: f.to_svg(path_format="spline"), "path_format 'spline'"),
    (lambda f: f.to_png(background="blue"), "background"),
    (lambda f: f.to_pdf(page="B9"), "B9"),
    (lambda f: f.to_pdf(dpi=0), "dpi"),
    (lambda f: f.to_pdf(margin_mm=-1), "margin_mm"),
    (lambda f: f.to_pdf(layers="colour"), "layers 'colour'"),
])
def test_writer_options(call, message):
    frame = inkline.scene(*SPHERE, camera=CAMERA).render(1)
    raises(message, lambda: call(frame))


def test_images_too_large_for_cairo_are_refused_before_drawing():
    frame = inkline.scene(*SPHERE, camera=CAMERA, image=(40000, 10), max_image_side=50000).render(1)
    raises("32767", lambda: frame.to_png())


@pytest.mark.parametrize("text, message", [
    ("{}", "not an inkline.polylines document"),
    ('{"format": "inkline.polylines"}', "missing key 'strokes'"),
    ('{"format": "inkline.polylines", "frame": 1, "image": {"width": 2, "height": 2}, "camera": {}, '
     '"strokes": [{"id": 1}]}', "missing key 'points'"),
    ('{"format": "inkline.polylines", "frame": 1, "image": {"width": 2, "height": 2}, "camera": {}, '
     '"strokes": [{"id": 1, "kind": "crease", "visible": true, "closed": false, "points": [[1, 2, 3]]}]}', "reshape"),
])
def test_polylines_json_that_cannot_be_read(text, message):
    raises(message, lambda: inkline.read_json(text))


def test_read_back_frames_have_no_drawing(tmp_path):
    frame = inkline.scene(*SPHERE, camera=CAMERA).render(1)
    frame.write_json(tmp_path / "f.json")
    back = inkline.read_json(tmp_path / "f.json")
    assert [s.id for s in back.strokes] == [s.id for s in frame.strokes]
    raises("a frame read from polylines JSON has no drawing", lambda: back.to_svg())
    raises("missing.json", lambda: inkline.read_json(tmp_path / "missing.json"))
