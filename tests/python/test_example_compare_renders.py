# Two renders of one shot compared: the ray-cast visibility test against the exact reference,
# frame by frame, and the strokes' ids from one frame to the next.
import inkline
from inkline.testing import assert_lines_close, hausdorff_px, id_persistence
from conftest import SAMPLES  # the repository's samples/ folder


def test_raycast_frames_match_the_exact_reference():
    scene = SAMPLES / "torus" / "scene.json"
    exact = inkline.open(scene, frames=(1, 3), visibility="exact")
    raycast = inkline.open(scene, frames=(1, 3), visibility="raycast")
    previous = None
    for n in exact.frames:
        a, b = raycast.render(n), exact.render(n)
        assert_lines_close(a, b, tol_px=1.0, min_precision=0.995, min_recall=0.995)
        assert hausdorff_px(a, b) < 2.0
        if previous is not None:
            assert id_persistence(previous, a) > 0.9  # the lines keep their ids as the torus turns
        previous = a
