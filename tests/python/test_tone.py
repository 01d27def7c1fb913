# SPDX-License-Identifier: MIT
"""A frame's tone in Python: the dots as arrays are the polylines JSON's, read back from it they
are the same, the files draw them, and the module's tone="stipple" draws what --tone stipple
draws."""
import json
import re

import numpy as np
import pytest

import inkline
from conftest import SAMPLES, icosphere, run_cli

CAMERA = {"eye": [0.4, 0.6, 3.2], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": 40}


def json_round(values, scale):
    x = np.asarray(values, np.float64) * scale
    return np.where(x >= 0, np.floor(x + 0.5), np.ceil(x - 0.5)) / scale


def strip_ms(text):
    return re.sub(r'"ms":\{[^}]*\}', '"ms":{}', text)


def stippled_sphere(**tone):
    vertices, faces = icosphere(3)
    return inkline.scene(vertices, faces, camera=CAMERA, image=(256, 256), visibility="exact",
                         light={"direction": [-0.5, -0.8, -0.4]}, tone={"max": 0.6, **tone})


def test_tone_arrays_are_the_jsons_dots():
    frame = stippled_sphere().render(1)
    tone = frame.tone
    assert isinstance(tone, inkline.Tone) and tone.mode == "stipple"
    n = len(tone)
    assert n > 100
    assert tone.points.shape == (n, 2) and tone.world.shape == (n, 3) and tone.barycentric.shape == (n, 3)
    for a in (tone.faces, tone.radius, tone.tone, tone.samples):
        assert a.shape == (n,)
    assert tone.faces.dtype == np.uint32 and tone.samples.dtype == np.uint64
    assert np.all(np.diff(tone.samples.astype(np.int64)) > 0)
    np.testing.assert_allclose(tone.barycentric.sum(axis=1), 1.0, atol=1e-6)
    assert set(tone.stats) == {"samples", "considered", "wanted", "inked", "occluded"}

    doc = json.loads(frame.to_json())["tone"]
    assert [d["sample"] for d in doc["dots"]] == tone.samples.tolist()
    assert [d["face"] for d in doc["dots"]] == tone.faces.tolist()
    np.testing.assert_array_equal(np.array([d["point"] for d in doc["dots"]]), json_round(tone.points, 1e4))
    np.testing.assert_array_equal(np.array([d["world"] for d in doc["dots"]]), tone.world)
    assert doc["stats"] == tone.stats

    back = inkline.read_json(frame.to_json()).tone
    np.testing.assert_array_equal(back.samples, tone.samples)
    np.testing.assert_array_equal(back.faces, tone.faces)
    np.testing.assert_array_equal(back.world, tone.world)
    np.testing.assert_array_equal(back.points, json_round(tone.points, 1e4))

    svg = frame.to_svg()
    assert svg.count("<circle") == n
    assert svg.index('<g id="tone"') < svg.index('<g id="silhouette"')


def test_no_tone_without_a_tone():
    vertices, faces = icosphere(2)
    frame = inkline.scene(vertices, faces, camera=CAMERA, image=(128, 128)).render(1)
    assert frame.tone is None
    assert "tone" not in json.loads(frame.to_json())
    assert 'id="tone"' not in frame.to_svg()
    assert inkline.read_json(frame.to_json()).tone is None
    assert stippled_sphere(mode="none").render(1).tone is None


def test_tone_keyword_draws_what_the_program_draws(inkline_exe, tmp_path, monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "0")
    scene = SAMPLES / "torus" / "scene.json"
    run_cli(inkline_exe, scene, "--frames", "1", "--size", "256x256", "--visibility", "raycast", "--tone", "stipple",
            "--json", tmp_path / "f.json", "--svg", tmp_path / "f.svg", "--png", tmp_path / "f.png")
    frame = inkline.open(scene, frames=1, size=(256, 256), visibility="raycast", tone="stipple").render(1)
    assert len(frame.tone) > 0
    assert strip_ms(frame.to_json()) == strip_ms((tmp_path / "f.json").read_text())
    assert frame.to_svg() == (tmp_path / "f.svg").read_text()
    assert frame.to_png() == (tmp_path / "f.png").read_bytes()


def test_bad_tone_keyword_is_an_input_error():
    with pytest.raises(inkline.InputError, match=r"^tone 'bogus': expected stipple, hatch, crosshatch or none$"):
        inkline.open(SAMPLES / "torus" / "scene.json", frames=1, tone="bogus")
    with pytest.raises(inkline.InputError, match=r"^tone: expected a string"):
        inkline.open(SAMPLES / "torus" / "scene.json", frames=1, tone=1)


def test_hatches_are_the_jsons_and_read_back():
    vertices, faces = icosphere(3)
    frame = inkline.scene(vertices, faces, camera=CAMERA, image=(256, 256), visibility="exact",
                          light={"direction": [-0.5, -0.8, -0.4]},
                          tone={"mode": "crosshatch", "max": 0.6}).render(1)
    tone = frame.tone
    assert tone.mode == "crosshatch" and len(tone) == len(tone.hatches) > 10
    assert len(tone.points) == 0
    assert {h["family"] for h in tone.hatches} == {0, 1}
    for h in tone.hatches:
        k = len(h["points"])
        assert k >= 2 and h["points"].shape == (k, 2) and h["world"].shape == (k, 3)
        assert h["edges"].dtype == np.uint32 and h["edges"].shape == (k,) and h["width"].shape == (k,)
        assert h["faces"].dtype == np.uint32 and h["faces"].shape == (k,) and np.all(h["faces"] < len(faces))
        assert np.all(h["width"] <= 0.8 + 1e-12)
    assert set(tone.stats) == {"faces", "segments", "points", "occluded", "inked"}

    doc = json.loads(frame.to_json())["tone"]
    assert [(h["family"], h["plane"]) for h in doc["hatches"]] == [(h["family"], h["plane"]) for h in tone.hatches]
    back = inkline.read_json(frame.to_json()).tone
    assert len(back.hatches) == len(tone.hatches)
    for a, b in zip(back.hatches, tone.hatches):
        assert (a["family"], a["plane"], a["level"]) == (b["family"], b["plane"], b["level"])
        np.testing.assert_array_equal(a["world"], b["world"])
        np.testing.assert_array_equal(a["edges"], b["edges"])
        np.testing.assert_array_equal(a["faces"], b["faces"])
        np.testing.assert_array_equal(a["points"], json_round(b["points"], 1e4))

    svg = frame.to_svg()
    assert svg.count("<path data-family=") == len(tone.hatches)
    assert 'data-mode="crosshatch"' in svg


def test_objects_with_modes_of_their_own_give_dots_and_hatches(tmp_path):
    vertices, faces = icosphere(3)
    lines = []
    for name, dx, base in (("Left", -1.2, 0), ("Right", 1.2, len(vertices))):
        lines.append(f"o {name}")
        lines += [f"v {x + dx!r} {y!r} {z!r}" for x, y, z in vertices]
        lines += [f"f {a + base + 1} {b + base + 1} {c + base + 1}" for a, b, c in faces]
    (tmp_path / "spheres.obj").write_text("\n".join(lines) + "\n")
    scene = tmp_path / "spheres.json"
    scene.write_text(json.dumps({
        "mesh": "spheres.obj", "image": {"width": 320, "height": 160},
        "camera": {"eye": [0, 0, 6], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": 30},
        "light": {"direction": [0.0, -0.3, -1.0]}, "tone": {"mode": "stipple", "max": 0.6},
        "objects": {"Right": {"tone": {"mode": "hatch"}}},
        "styles": [{"name": "warm", "select": {"object": "Right"}, "tone": {"color": "#a03010", "opacity": 0.7}}]}))
    frame = inkline.open(scene, frames=1, visibility="exact").render(1)
    tone = frame.tone
    assert tone.mode == "stipple" and tone.modes == ["stipple", "hatch"]
    assert len(tone.points) > 100 and np.all(tone.points[:, 0] < 160)
    assert tone.hatches and all(np.all(h["points"][:, 0] > 160) for h in tone.hatches)
    assert tone.hatch_stats["segments"] > 0 and tone.stipple_stats is None
    back = inkline.read_json(frame.to_json()).tone
    assert back.modes == tone.modes and back.hatch_stats == tone.hatch_stats
    assert len(back.hatches) == len(tone.hatches) and np.array_equal(back.samples, tone.samples)
    # The style gives the hatched sphere an ink of its own.
    assert tone.inks == [{"color": "#171412", "opacity": 1.0, "style": ""},
                         {"color": "#a03010", "opacity": 0.7, "style": "warm"}]
    assert tone.ink.dtype == np.uint32 and np.all(tone.ink == 0) and len(tone.ink) == len(tone.points)
    assert all(h["ink"] == 1 for h in tone.hatches)
    assert back.inks == tone.inks and np.array_equal(back.ink, tone.ink)
    assert [h["ink"] for h in back.hatches] == [h["ink"] for h in tone.hatches]
    assert 'id="tone-ink-2" data-style="warm" fill="#a03010" opacity="0.7"' in frame.to_svg()
