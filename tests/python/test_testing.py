# SPDX-License-Identifier: MIT
"""inkline.testing on cases where it must pass and where it must fail: polylines with known
offsets, lengths and ids, and frames of the same shot."""
import math
import re

import numpy as np
import pytest

import inkline
from inkline import testing
from conftest import icosphere


def circle(radius, n=400, center=(200.0, 200.0), start=0.0, end=2 * math.pi):
    t = np.linspace(start, end, n)
    return np.stack([center[0] + radius * np.cos(t), center[1] + radius * np.sin(t)], axis=1)


def stroke(points, ident, kind="silhouette", visible=True):
    points = np.asarray(points, float)
    n = len(points)
    return inkline.Stroke(id=ident, kind=kind, visible=visible, drawn=True, closed=False, ends=("S", "S"),
                          points=points, world=np.zeros((n, 3)), edges=np.zeros(max(n - 1, 0), np.uint32),
                          u=np.zeros(n), intensity=np.zeros(n), width=np.zeros(n))


def test_visible_length_by_kind_leaves_hidden_lines_out():
    lines = [stroke([[0, 0], [30, 40]], 1), stroke([[0, 0], [0, 10]], 2, "crease"),
             stroke([[0, 0], [100, 0]], 3, visible=False)]
    assert testing.visible_length(lines) == pytest.approx({"silhouette": 50.0, "crease": 10.0})
    assert testing.visible_length(lines, "crease") == pytest.approx(10.0)
    assert testing.visible_length(lines, "boundary") == 0.0


def test_precision_and_recall_of_offset_and_partial_lines():
    full = [circle(100)]
    # Offset by 0.6 px: within 1 px everywhere, not within 0.5 px anywhere.
    offset = [circle(100.6)]
    m = testing.match_lines(offset, full, tol_px=1.0)
    assert m.precision == pytest.approx(1.0) and m.recall == pytest.approx(1.0)
    m = testing.match_lines(offset, full, tol_px=0.5)
    assert m.precision == pytest.approx(0.0, abs=1e-9) and m.recall == pytest.approx(0.0, abs=1e-9)
    # Half the circle: every point of it lies on the full one; it covers half the full one.
    half = [circle(100, start=0.0, end=math.pi)]
    m = testing.match_lines(half, full, tol_px=0.5)
    assert m.precision == pytest.approx(1.0)
    assert m.recall == pytest.approx(0.5, abs=0.01)
    assert m.b_not_in_a and all(y < 200.0 + 1e-6 for _, y, _, _, _ in m.b_not_in_a)


def test_hausdorff_distance():
    assert testing.hausdorff_px([circle(100)], [circle(103)]) == pytest.approx(3.0, abs=0.2)
    # A stray stroke out of the circle sets the distance: its far end is 51 px from the circle.
    stray = [circle(100), np.array([[350.0, 200.0], [351.0, 200.0]])]
    assert testing.hausdorff_px(stray, [circle(100)]) == pytest.approx(51.0, abs=0.2)
    assert testing.hausdorff_px([], []) == 0.0
    assert math.isinf(testing.hausdorff_px([circle(10)], []))


def test_id_persistence_weights_by_length():
    before = [stroke([[0, 0], [10, 0]], 1), stroke([[0, 5], [10, 5]], 2)]
    after = [stroke([[0, 0], [30, 0]], 1), stroke([[0, 5], [10, 5]], 7)]
    assert testing.id_persistence(before, after) == pytest.approx(0.75)
    assert testing.id_persistence(before, before) == 1.0
    assert testing.id_persistence(before, []) == 1.0


def test_assert_lines_close_passes_within_tolerance_and_explains_a_failure():
    testing.assert_lines_close([circle(100.4)], [circle(100)], tol_px=0.5)
    missing = [circle(100, start=0.0, end=1.5 * math.pi)]
    with pytest.raises(AssertionError) as failure:
        testing.assert_lines_close(missing, [circle(100)], tol_px=0.5)
    message = str(failure.value)
    assert "recall 0.75" in message and "precision 1.0000" in message
    # Where: points of the missing quarter (x > 200, y < 200), named by stroke.
    where = re.findall(r"\((\d+\.\d+), (\d+\.\d+)\) px, (\d+\.\d+) px away", message)
    assert where and all(float(x) >= 199.0 and float(y) <= 201.0 for x, y, _ in where)
    assert "stroke 0" in message


def test_frames_of_a_turning_sphere():
    vertices, faces = icosphere(3)
    shot = inkline.scene(vertices, faces, image=(512, 512), frames=(1, 3), visibility="exact",
                         camera={"eye": [0, 0, 4], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": 40,
                                 "orbit": {"axis": [0, 1, 0], "degrees": 6}})
    a, b, c = (shot.render(n) for n in shot.frames)
    # A sphere's outline barely moves as it turns: the lines stay within a pixel, the ids stay.
    testing.assert_lines_close(a, b, tol_px=1.0)
    assert testing.id_persistence(a, b) > 0.95
    assert testing.hausdorff_px(a, c) < 2.0
    # Against a sphere 10% larger the same assertion fails, saying so.
    big = inkline.scene(vertices * 1.1, faces, image=(512, 512), visibility="exact",
                        camera={"eye": [0, 0, 4], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": 40}).render(1)
    with pytest.raises(AssertionError, match="lines differ beyond 1 px"):
        testing.assert_lines_close(a, big, tol_px=1.0)



