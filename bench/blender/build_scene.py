# SPDX-License-Identifier: MIT
# Builds the issue-10 comparison scene in Blender and writes it out for both sides.
#
#   blender -b --factory-startup --python bench/blender/build_scene.py -- OUT_DIR [--levels 4]
#       [--frames 24] [--size 1024]
#
# Scene: Suzanne, Catmull-Clark subdivided LEVELS times (4: 125,952 quads), triangulated
# (251,904 triangles); a camera orbiting it at distance 4 and 20 degrees elevation over FRAMES
# frames (360 degrees, starting in front of the face), vertical field of view 40 degrees,
# SIZE x SIZE pixels.
#
# Writes into OUT_DIR:
#   suzanne.obj   the triangulated mesh in Blender's world coordinates (Z up), no axis change
#   scene.json    an inkline scene with every frame's camera explicitly, in the same
#                 coordinates: eye, target = origin, up = +Z (docs/scene.md)
#   scene.blend   the same scene for time_blender.py (mesh, keyed camera, render size)
#
# Blender's camera looks down its local -Z with local +Y up; a camera whose world matrix has
# columns (s, u, -f) with f = normalize(target - eye), s = normalize(f x up), u = s x f is
# exactly glm::lookAt(eye, target, up), so both programs see the same view.

import json
import math
import os
import sys

import bmesh
import bpy
from mathutils import Matrix, Vector

DISTANCE = 4.0
ELEVATION_DEG = 20.0
FOV_Y_DEG = 40.0
# Normals differing by more than 46 degrees: Blender Line Art's crease angle 134 = 180 - 46.
CREASE_ANGLE_DEG = 46.0


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if not argv:
        raise SystemExit("usage: blender -b --python build_scene.py -- OUT_DIR [--levels N] "
                         "[--frames N] [--size PX]")
    opts = {"out": argv[0], "levels": 4, "frames": 24, "size": 1024}
    i = 1
    while i < len(argv):
        key = argv[i].lstrip("-")
        if key not in opts or i + 1 >= len(argv):
            raise SystemExit("build_scene.py: unknown or incomplete option " + argv[i])
        opts[key] = int(argv[i + 1])
        i += 2
    return opts


def eye_at(frame_index, frames):
    """Camera position of frame_index (0-based): a 360-degree orbit starting at -Y (Suzanne's
    face looks down -Y)."""
    azimuth = math.radians(-90.0 + 360.0 * frame_index / frames)
    elevation = math.radians(ELEVATION_DEG)
    return Vector((DISTANCE * math.cos(elevation) * math.cos(azimuth),
                   DISTANCE * math.cos(elevation) * math.sin(azimuth),
                   DISTANCE * math.sin(elevation)))


def look_at_matrix(eye, target, up):
    """World matrix of a Blender camera equal to glm::lookAt(eye, target, up)."""
    f = (target - eye).normalized()
    s = f.cross(up).normalized()
    u = s.cross(f)
    m = Matrix.Identity(4)
    for row in range(3):
        m[row][0], m[row][1], m[row][2], m[row][3] = s[row], u[row], -f[row], eye[row]
    return m


def build_mesh(levels):
    for ob in list(bpy.data.objects):
        bpy.data.objects.remove(ob, do_unlink=True)
    bpy.ops.mesh.primitive_monkey_add(size=2.0, location=(0.0, 0.0, 0.0))
    ob = bpy.context.active_object
    ob.name = "Suzanne"
    mod = ob.modifiers.new("subdivision", 'SUBSURF')
    mod.subdivision_type = 'CATMULL_CLARK'
    mod.levels = levels
    mod.render_levels = levels
    bpy.ops.object.modifier_apply(modifier=mod.name)
    bm = bmesh.new()
    bm.from_mesh(ob.data)
    bmesh.ops.triangulate(bm, faces=bm.faces[:], quad_method='BEAUTY', ngon_method='BEAUTY')
    bm.to_mesh(ob.data)
    bm.free()
    # Flat shading: Line Art then finds creases without its "crease on smooth surfaces" option.
    for poly in ob.data.polygons:
        poly.use_smooth = False
    return ob


def write_obj(ob, path):
    mesh = ob.data
    world = ob.matrix_world
    with open(path, "w") as out:
        out.write("# Suzanne for inkline bench/blender, %d triangles, Blender world coordinates\n"
                  % len(mesh.polygons))
        out.write("".join("v %.9g %.9g %.9g\n" % tuple(world @ v.co) for v in mesh.vertices))
        out.write("".join("f %d %d %d\n" % tuple(i + 1 for i in p.vertices) for p in mesh.polygons))


def main():
    opts = parse_args()
    out_dir = os.path.abspath(opts["out"])
    os.makedirs(out_dir, exist_ok=True)
    frames = opts["frames"]
    scene = bpy.context.scene

    ob = build_mesh(opts["levels"])
    write_obj(ob, os.path.join(out_dir, "suzanne.obj"))

    # Camera keyed on every frame with constant interpolation: frame k shows exactly eye_at(k).
    cam_data = bpy.data.cameras.new("Camera")
    cam_data.sensor_fit = 'VERTICAL'
    cam_data.angle_y = math.radians(FOV_Y_DEG)
    cam_data.clip_start = 0.1
    cam_data.clip_end = 100.0
    cam = bpy.data.objects.new("Camera", cam_data)
    scene.collection.objects.link(cam)
    scene.camera = cam
    target, up = Vector((0.0, 0.0, 0.0)), Vector((0.0, 0.0, 1.0))
    cameras = []
    for k in range(frames):
        eye = eye_at(k, frames)
        cam.matrix_world = look_at_matrix(eye, target, up)
        cam.keyframe_insert("location", frame=k + 1)
        cam.keyframe_insert("rotation_euler", frame=k + 1)
        cameras.append({"frame": k + 1, "eye": [round(c, 9) for c in eye], "target": [0, 0, 0],
                        "up": [0, 0, 1], "fov_y_deg": FOV_Y_DEG})
    for curve in cam.animation_data.action.fcurves:
        for key in curve.keyframe_points:
            key.interpolation = 'CONSTANT'

    scene.frame_start, scene.frame_end = 1, frames
    scene.render.resolution_x = scene.render.resolution_y = opts["size"]
    scene.render.resolution_percentage = 100
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out_dir, "scene.blend"))

    inkline_scene = {
        "version": 1,
        "mesh": "suzanne.obj",
        "frames": [1, frames],
        "image": {"width": opts["size"], "height": opts["size"]},
        "camera": {"frames": cameras},
        "lines": {"silhouette": True, "boundary": True, "crease": True,
                  "crease_angle_deg": CREASE_ANGLE_DEG},
    }
    # One camera per line: readable, and diffable between runs.
    text = json.dumps(inkline_scene, indent=1)
    frames_json = ",\n".join("   " + json.dumps(c) for c in cameras)
    text = text.replace(json.dumps({"frames": cameras}, indent=1).replace("\n", "\n "),
                        '{"frames": [\n' + frames_json + "\n  ]}")
    with open(os.path.join(out_dir, "scene.json"), "w") as out:
        out.write(text + "\n")
    print("build_scene: %d triangles, %d frames -> %s" % (len(ob.data.polygons), frames, out_dir))


main()
