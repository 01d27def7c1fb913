# SPDX-License-Identifier: MIT
"""inkline in Python: draw a scene's lines in process and get them back as numpy arrays.

    import inkline
    shot = inkline.open("scene.json", visibility="exact")
    frame = shot.render(shot.frames[0])
    for stroke in frame.strokes:
        stroke.points      # (n, 2) image px, origin top-left, y down
        stroke.world       # (n, 3) the same points in world space

Frames are drawn in order: stroke ids and u carry from one render() to the next, as in
`inkline render`. Bad input raises InputError with the program's message; an output that cannot
be written raises OutputError. docs/python.md has the whole interface.
"""
from __future__ import annotations

import builtins as _builtins
import json as _json
import os as _os
from dataclasses import dataclass, field
from typing import Optional, Sequence

import numpy as np

from . import _inkline
from ._inkline import InputError, InternalError, OutputError

__version__ = _inkline.__version__

__all__ = [
    "InputError", "OutputError", "InternalError", "Shot", "Frame", "Stroke", "Tone",
    "open", "scene", "read_json", "__version__",
]

_LIMITS = {"max_faces": 50_000_000, "max_image_side": 16384}


@dataclass(eq=False)
class Stroke:
    """One stroke of a frame, as the polylines JSON holds it (docs/polylines-json.md)."""

    id: int
    kind: str                 # silhouette, boundary, crease or intersection
    visible: bool
    drawn: bool               # False: shorter than brush.min_length_px, no outline
    closed: bool
    ends: tuple               # end types at the first and last point: "S", "A", "C" or "L"
    points: np.ndarray        # (n, 2) float64, image px
    world: np.ndarray         # (n, 3) float64, world space
    edges: np.ndarray         # (n - 1,) mesh edge of each segment (smooth contours: the face)
    u: np.ndarray             # (n,) arc-length parameter, px, carried between frames
    intensity: np.ndarray     # (n,) light intensity in [0, 1]
    width: np.ndarray         # (n,) brush width, px
    outline: list = field(default_factory=list)  # rings, each (k, 2) float64 px
    hidden_segments: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    object: Optional[str] = None
    style: Optional[str] = None
    # Drawing order (docs/strokes.md): the group (its main stroke's id), the level in the group's
    # hierarchy (0: the main stroke), the stroke it hangs from (None at level 0), its place.
    group: int = 0
    level: int = 0
    parent: Optional[int] = None
    order: int = 0

    @property
    def length_px(self) -> float:
        """Length of the stroke's polyline in the image, px."""
        if len(self.points) < 2:
            return 0.0
        return float(np.linalg.norm(np.diff(self.points, axis=0), axis=1).sum())


def _stroke_of(d: dict) -> Stroke:
    return Stroke(**d)


@dataclass(eq=False)
class Tone:
    """A frame's tone (scene "tone", docs/tone.md): its dots, one row each, ascending by sample, or
    its hatches."""

    mode: str                 # "stipple", "hatch" or "crosshatch"
    points: np.ndarray        # (n, 2) float64, the dots' centres, image px
    world: np.ndarray         # (n, 3) float64, the same points in world space
    faces: np.ndarray         # (n,) uint32, the mesh face each dot lies on
    barycentric: np.ndarray   # (n, 3) float64, its barycentric coordinates on that face
    radius: np.ndarray        # (n,) float64, px
    tone: np.ndarray          # (n,) float64, the tone asked for there
    samples: np.ndarray       # (n,) uint64, the surface sample: the same point of the surface in every frame
    stats: dict = field(default_factory=dict)  # samples, considered, wanted, inked, occluded (hatching: faces, segments, points, occluded, inked)
    # Hatching: one dict per hatch: family, plane, level (ints); points (k, 2), world (k, 3), width (k,)
    # float64; edges (k,) uint32.
    hatches: list = field(default_factory=list)
    # The modes drawn: [mode], or where objects have modes of their own each mode some object is
    # shaded with; then the other kind's stats too (hatch_stats with a stippled scene, else
    # stipple_stats).
    modes: list = field(default_factory=list)
    hatch_stats: Optional[dict] = None
    stipple_stats: Optional[dict] = None
    # Where objects have inks of their own (scene "objects" and "styles"): one dict per ink, color
    # ("#rrggbb"), opacity and style (the style rule's name, or ""); empty: the scene's ink alone.
    # `ink` gives each dot's index in it, as each hatch's "ink" does (0 with one ink or none).
    inks: list = field(default_factory=list)
    ink: Optional[np.ndarray] = None  # (n,) uint32

    def __len__(self) -> int:
        """Dots, or hatches with hatching."""
        return len(self.hatches) if self.mode in ("hatch", "crosshatch") else len(self.points)


class Frame:
    """One drawn frame: its strokes, camera and image size, and its files."""

    def __init__(self, number: int, image: tuple, camera: dict, strokes=None, native=None, stats=None, tone=None):
        self.number = number
        self.image = image
        self.camera = camera
        self._strokes = strokes
        self._native = native
        self._stats = stats
        self._tone = tone
        self._tone_read = native is None

    @property
    def strokes(self) -> list[Stroke]:
        if self._strokes is None:
            self._strokes = [_stroke_of(d) for d in self._native.strokes()]
        return self._strokes

    @property
    def tone(self) -> Optional[Tone]:
        """The tone's dots as arrays; None without tone (the scene's or the shot's tone is none)."""
        if not self._tone_read:
            d = self._native.tone()
            self._tone = None if d is None else Tone(**d)
            self._tone_read = True
        return self._tone

    @property
    def warnings(self) -> list[str]:
        """Drawable oddities found drawing this frame (e.g. the camera inside the mesh)."""
        return list(self._native.warnings) if self._native is not None else []

    @property
    def stats(self) -> dict:
        """The polylines JSON's stats: faces, edges tested, visible length by kind, stage ms."""
        if self._stats is None:
            self._stats = _json.loads(self.to_json())["stats"]
        return self._stats

    def __repr__(self) -> str:
        return f"<inkline.Frame {self.number}: {len(self.strokes)} strokes, {self.image[0]}x{self.image[1]} px>"

    # Files ---------------------------------------------------------------------------------

    def _drawn(self, what: str):
        if self._native is None:
            raise InputError(f"{what}: a frame read from polylines JSON has no drawing; render it to write {what}")
        return self._native

    def to_json(self) -> str:
        """The polylines JSON, exactly as `inkline render --json` writes it."""
        return self._drawn("polylines JSON").json()

    def to_svg(self, layers: str = "kind", path_format: str = "polygon", centerline: bool = False,
               background: Optional[str] = None) -> str:
        return self._drawn("SVG").svg(layers, path_format, centerline, background)

    def to_png(self, path_format: str = "polygon", centerline: bool = False, background: Optional[str] = None) -> bytes:
        return self._drawn("PNG").png(path_format, centerline, background)

    def to_pdf(self, page: Optional[str] = None, margin_mm: float = 10.0, dpi: float = 96.0, path_format: str = "polygon",
               centerline: bool = False, background: Optional[str] = None, layers: str = "kind") -> bytes:
        return self._drawn("PDF").pdf(page, margin_mm, dpi, path_format, centerline, background, layers)

    def write_json(self, path) -> None:
        _write(path, self.to_json().encode())

    def write_svg(self, path, **options) -> None:
        _write(path, self.to_svg(**options).encode())

    def write_png(self, path, **options) -> None:
        _write(path, self.to_png(**options))

    def write_pdf(self, path, **options) -> None:
        _write(path, self.to_pdf(**options))


def _write(path, contents: bytes) -> None:
    """Whole or nothing: a temporary beside the file, renamed into place (as the program does)."""
    _inkline.write_file(_os.fspath(path), contents)


class Shot:
    """What a render draws, frame after frame. Make one with open() or scene()."""

    def __init__(self, native):
        self._native = native

    @property
    def frames(self) -> range:
        return range(self._native.first_frame, self._native.last_frame + 1)

    @property
    def warnings(self) -> list[str]:
        """Drawable oddities of the mesh (degenerate faces, non-manifold edges)."""
        return list(self._native.warnings)

    def render(self, frame: int) -> Frame:
        """Draws a frame (the GIL is released meanwhile). Draw frames in order: ids carry over."""
        if isinstance(frame, bool) or not isinstance(frame, (int, np.integer)):
            raise InputError(f"frame: expected an integer, not {type(frame).__name__}")
        native = self._native.render(int(frame))
        return Frame(native.number, native.image, native.camera, native=native)

    def __iter__(self):
        for f in self.frames:
            yield self.render(f)


def _args(frames, size, hidden, contour, visibility, tracker, tone=None):
    a = _inkline.ShotArgs()
    if frames is not None:
        a.frames = _pair("frames", frames)
    if size is not None:
        a.size = _pair("size", size)
    a.hidden = _flag("hidden", hidden)
    if contour is not None:
        a.contour = _text("contour", contour)
    a.visibility = _text("visibility", visibility)
    a.tracker = _text("tracker", tracker)
    if tone is not None:
        a.tone = _text("tone", tone)
    return a


def _pair(name, value):
    if isinstance(value, int) and not isinstance(value, bool):
        return (value, value)
    try:
        a, b = value
    except (TypeError, ValueError):
        raise InputError(f"{name}: expected two integers, not {value!r}"[:200]) from None
    for v in (a, b):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)):
            raise InputError(f"{name}: expected two integers, not {value!r}"[:200])
        if not -(2**31) < int(v) < 2**31:
            raise InputError(f"{name}: {int(v)} is out of range")
    return (int(a), int(b))


def _flag(name, value):
    if not isinstance(value, (bool, np.bool_)):
        raise InputError(f"{name}: expected True or False, not {value!r}"[:200])
    return bool(value)


def _text(name, value):
    if not isinstance(value, str):
        raise InputError(f"{name}: expected a string, not {type(value).__name__}")
    return value


def _limit(name, value):
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or int(value) < 1:
        raise InputError(f"{name}: expected a positive integer, not {value!r}"[:200])
    return int(value)


def open(path, *, frames=None, size=None, hidden=False, contour=None, visibility="auto", tracker="incremental",
         tone=None, gltf_scene=None, animation=None, camera=None, fps=None, max_faces=_LIMITS["max_faces"],
         max_image_side=_LIMITS["max_image_side"]) -> Shot:
    """Opens a scene (.json), a mesh (.obj .off .ply .stl: a 48-frame turntable) or a glTF shot.

    The keywords are `inkline render`'s options: frames=(first, last) or one frame, size=(w, h),
    hidden, contour ("mesh" or "smooth"), visibility ("auto": raycast where Embree is built in,
    else exact; "raycast"; "exact"), tracker ("incremental" or "brute"), tone ("stipple", "hatch",
    "crosshatch" or "none": overrides the scene's tone mode), and for glTF input gltf_scene, animation, camera, fps.
    """
    path = _os.fspath(path)
    if not isinstance(path, str):
        raise InputError("path: expected a file name")
    args = _args(frames, size, hidden, contour, visibility, tracker, tone)
    scene_index = -1
    if gltf_scene is not None:
        if isinstance(gltf_scene, bool) or not isinstance(gltf_scene, (int, np.integer)) or not 0 <= gltf_scene < 2**30:
            raise InputError(f"gltf_scene: expected a scene index 0..2^30, not {gltf_scene!r}"[:200])
        scene_index = int(gltf_scene)
    if fps is not None and (isinstance(fps, bool) or not isinstance(fps, (int, float)) or not 0 < fps <= 1e6):
        raise InputError(f"fps: expected a number of frames per second in (0, 1e6], not {fps!r}"[:200])
    native = _inkline.Shot(path, args, scene_index, "" if animation is None else _text("animation", animation),
                           "" if camera is None else _text("camera", camera), 0.0 if fps is None else float(fps),
                           _limit("max_faces", max_faces), _limit("max_image_side", max_image_side))
    return Shot(native)


def scene(vertices, faces, *, camera, image=(1024, 1024), frames=(1, 1), name="arrays", size=None, hidden=False,
          contour=None, visibility="auto", tracker="incremental", max_faces=_LIMITS["max_faces"],
          max_image_side=_LIMITS["max_image_side"], **keys) -> Shot:
    """A shot of a mesh given as arrays: vertices (V, 3), or (F, V, 3) for a mesh that deforms
    over frames first.. (one set of positions per frame), and faces (T, 3) of vertex indices,
    counter-clockwise. `camera`, `image` (w, h), `frames` (first, last) and any other scene key
    (light, lines, brush, styles, object; docs/scene.md) as the scene file writes them.
    """
    if not isinstance(camera, dict):
        raise InputError("camera: expected a dict of scene keys (eye, target, up, fov_y_deg, ...)")
    if "mesh" in keys:
        raise InputError("mesh: give the mesh as vertices and faces")
    width, height = _pair("image", image)
    first, last = _pair("frames", frames)
    doc = {"mesh": _text("name", name) or "arrays", "image": {"width": width, "height": height},
           "frames": [first, last], "camera": camera, **keys}
    try:
        text = _json.dumps(doc, allow_nan=False)
    except (TypeError, ValueError) as e:
        raise InputError(f"scene: cannot be written as JSON: {e}"[:200]) from None
    v = _array("vertices", vertices, np.float64)
    f = _array("faces", faces, np.int64)
    args = _args(None, size, hidden, contour, visibility, tracker)
    native = _inkline.Shot(text, name, v, f, args, _limit("max_faces", max_faces),
                           _limit("max_image_side", max_image_side))
    return Shot(native)


def _array(name, value, dtype):
    try:
        a = np.asarray(value)
    except Exception as e:  # a sequence numpy cannot make an array of
        raise InputError(f"{name}: not an array: {e}"[:200]) from None
    if a.dtype == object or not (np.issubdtype(a.dtype, np.number) or a.dtype == np.bool_):
        raise InputError(f"{name}: expected numbers, not {a.dtype}")
    if dtype == np.int64:
        if not np.issubdtype(a.dtype, np.integer):
            raise InputError(f"{name}: expected integer vertex indices, not {a.dtype}")
        if a.dtype == np.uint64 and a.size and a.max() > np.iinfo(np.int64).max:
            raise InputError(f"{name}: vertex index {int(a.max())} out of range")
    return np.ascontiguousarray(a, dtype=dtype)


# Polylines JSON -------------------------------------------------------------------------------

def read_json(source) -> Frame:
    """A frame read back from polylines JSON (a path, or the text itself): the same Frame and
    Stroke objects render() gives, without a drawing (only geometry)."""
    if isinstance(source, (str, bytes)) and (source.lstrip()[:1] in ("{", b"{")):
        text, where = source, "polylines JSON"
    else:
        where = _os.fspath(source)
        try:
            with _builtins.open(where, "rb") as f:
                text = f.read()
        except OSError as e:
            raise InputError(f"{where}: {e.strerror}") from None
    try:
        doc = _json.loads(text)
        if doc.get("format") != "inkline.polylines":
            raise ValueError("not an inkline.polylines document")
        strokes = [_stroke_from_json(s) for s in doc["strokes"]]
        image = (int(doc["image"]["width"]), int(doc["image"]["height"]))
        tone = _tone_from_json(doc["tone"]) if "tone" in doc else None
        return Frame(int(doc["frame"]), image, doc["camera"], strokes=strokes, stats=doc.get("stats", {}), tone=tone)
    except KeyError as e:
        raise InputError(f"{where}: missing key {e}"[:200]) from None
    except (ValueError, TypeError, AttributeError) as e:
        raise InputError(f"{where}: {e}"[:200]) from None


def _stroke_from_json(s: dict) -> Stroke:
    n = len(s["points"])
    f64 = lambda key, cols: np.asarray(s.get(key, []), np.float64).reshape(-1, cols) if cols else \
        np.asarray(s.get(key, []), np.float64).reshape(-1)
    return Stroke(
        id=int(s["id"]), kind=str(s["kind"]), visible=bool(s["visible"]), drawn=bool(s.get("drawn", True)),
        closed=bool(s["closed"]), ends=tuple(s.get("ends", ("S", "S"))),
        points=f64("points", 2), world=f64("world", 3), edges=np.asarray(s.get("edges", []), np.uint32),
        u=f64("u", 0) if "u" in s else np.zeros(n), intensity=f64("intensity", 0) if "intensity" in s else np.zeros(n),
        width=f64("width", 0) if "width" in s else np.zeros(n),
        outline=[np.asarray(r, np.float64).reshape(-1, 2) for r in s.get("outline", [])],
        hidden_segments=np.asarray(s.get("hidden_segments", []), np.int64),
        object=s.get("object"), style=s.get("style"), group=int(s.get("group", 0)), level=int(s.get("level", 0)),
        parent=None if s.get("parent") is None else int(s["parent"]), order=int(s.get("order", 0)))


def _tone_from_json(t: dict) -> Tone:
    dots = t["dots"]

    def column(key, dtype, cols):
        return np.asarray([d[key] for d in dots], dtype).reshape((-1, cols) if cols else -1)

    hatches = [{"family": int(h["family"]), "plane": int(h["plane"]), "level": int(h["level"]),
                "points": np.asarray(h["points"], np.float64).reshape(-1, 2),
                "world": np.asarray(h["world"], np.float64).reshape(-1, 3),
                "edges": np.asarray(h["edges"], np.uint32), "faces": np.asarray(h["faces"], np.uint32),
                "width": np.asarray(h["width"], np.float64),
                "ink": int(h.get("ink", 0))}
               for h in t.get("hatches", [])]
    return Tone(mode=str(t["mode"]), points=column("point", np.float64, 2), world=column("world", np.float64, 3),
                faces=column("face", np.uint32, 0), barycentric=column("barycentric", np.float64, 3),
                radius=column("radius", np.float64, 0), tone=column("tone", np.float64, 0),
                samples=column("sample", np.uint64, 0), stats=dict(t.get("stats", {})), hatches=hatches,
                modes=list(t.get("modes", [t["mode"]])), hatch_stats=t.get("hatch_stats"),
                stipple_stats=t.get("stipple_stats"), inks=list(t.get("inks", [])),
                ink=np.asarray([d.get("ink", 0) for d in dots], np.uint32))
