# SPDX-License-Identifier: MIT
"""What the module promises beyond the program's output: rendering lets other Python threads
run (the GIL is released), frames come in order from iteration, and the version is the
program's."""
import subprocess
import threading
import time

import numpy as np

import inkline
from conftest import SOURCE, icosphere

CAMERA = {"eye": [0.2, 0.3, 3.0], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": 40}


def test_other_threads_run_while_a_frame_renders():
    vertices, faces = icosphere(5)
    # A bumpy sphere: many short lines, a render long enough to watch.
    bumps = 1.0 + 0.02 * np.random.default_rng(7).standard_normal(len(vertices))
    shot = inkline.scene(vertices * bumps[:, None], faces, image=(2048, 2048), visibility="exact", camera=CAMERA)
    span = []

    def render():
        start = time.perf_counter()
        frame = shot.render(1)
        span.extend([start, time.perf_counter(), frame])

    worker = threading.Thread(target=render)
    ticks = []
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
    worker.join()
    start, end, frame = span
    assert frame.strokes
    # The main thread ran while the frame was being drawn: with the GIL held through the render
    # it could not have run between the render's first and last 10 ms.
    inside = [t for t in ticks if start + 0.01 < t < end - 0.01]
    assert end - start > 0.03 and len(inside) > 100


def test_iterating_a_shot_renders_its_frames_in_order():
    vertices, faces = icosphere(2)
    shot = inkline.scene(vertices, faces, camera={**CAMERA, "orbit": {"axis": [0, 1, 0], "degrees": 10}},
                         frames=(3, 5))
    assert [f.number for f in shot] == [3, 4, 5]


def test_version_is_the_programs(inkline_exe):
    out = subprocess.run([inkline_exe, "--version"], capture_output=True, text=True).stdout
    assert inkline.__version__ in out


def test_docs_show_the_worked_examples_as_they_are():
    docs = (SOURCE / "docs" / "python.md").read_text()
    for name in ("test_example_sphere_silhouette.py", "test_example_compare_renders.py"):
        text = (SOURCE / "tests" / "python" / name).read_text()
        assert "```python\n" + text + "```\n" in docs, f"docs/python.md does not show tests/python/{name} as it is"


def test_an_orthographic_camera_draws_a_sphere_its_own_size_from_any_distance():
    vertices, faces = icosphere(5)
    for eye in ([0.0, 0.0, 3.0], [1.0, 2.0, 30.0]):
        camera = {"eye": eye, "target": [0, 0, 0], "up": [0, 1, 0], "ortho_height": 3.0}
        frame = inkline.scene(vertices, faces, image=(600, 600), visibility="exact", camera=camera).render(1)
        assert frame.camera["ortho_height"] == 3.0 and "fov_y_deg" not in frame.camera
        points = np.concatenate([s.points for s in frame.strokes if s.visible])
        # A unit sphere is a circle of 200 px about the image centre (the target).
        radii = np.linalg.norm(points - [300.0, 300.0], axis=1)
        assert np.all(np.abs(radii - 200.0) < 0.25)
