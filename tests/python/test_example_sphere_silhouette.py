# A mesh's silhouette against the analytic one: a sphere of radius R seen from distance d
# through a perspective camera outlines a circle of radius f * tan(asin(R / d)) px around the
# image centre, where f = (height / 2) / tan(fov_y / 2).
import math

import numpy as np

import inkline
from inkline.testing import assert_lines_close, visible_length
from conftest import icosphere  # vertices on the unit sphere, faces counter-clockwise


def test_sphere_silhouette_is_the_analytic_circle():
    vertices, faces = icosphere(4)
    d, fov, size = 4.0, 40.0, 800
    shot = inkline.scene(vertices, faces, image=(size, size), visibility="exact",
                         camera={"eye": [0, 0, d], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": fov})
    frame = shot.render(1)

    f = (size / 2) / math.tan(math.radians(fov) / 2)
    radius = f * math.tan(math.asin(1.0 / d))
    t = np.linspace(0, 2 * math.pi, 1000)
    circle = np.stack([size / 2 + radius * np.cos(t), size / 2 + radius * np.sin(t)], axis=1)

    silhouettes = [s for s in frame.strokes if s.kind == "silhouette"]
    assert len(silhouettes) == 1 and silhouettes[0].closed
    assert_lines_close(silhouettes, [circle], tol_px=0.5, min_precision=1.0, min_recall=1.0)
    assert abs(visible_length(frame, "silhouette") - 2 * math.pi * radius) < 0.01 * radius
    # Every point of the line is on the sphere, in world space too.
    assert np.allclose(np.linalg.norm(silhouettes[0].world, axis=1), 1.0, atol=1e-3)
