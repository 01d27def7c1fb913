# SPDX-License-Identifier: MIT
# Builds an animated multi-object shot in Blender and writes, into OUT:
#   shot.glb       Blender's own glTF 2.0 export (cameras, animation, skin, shape keys)
#   frames/fNNNN.obj  every frame's geometry as Blender evaluates it, all objects in world space,
#                  in glTF's axes (x, z, -y), one vertex per Blender vertex
#   reference.json an inkline scene over that OBJ sequence with Blender's camera of every frame
#   shot.blend     the scene, for Line Art timing
# The shot: a ground plane; a box parented under a turning empty with a smooth ball parented
# to the box; a bending tube skinned to a two-bone armature; a sphere sunk a little into the
# ground (an intersection line) whose shape key swells it; a camera that moves and turns to keep
# the box in view. The OBJ frames name each object ("o NAME"), as the glTF file does. With
# --ortho SCALE the camera is orthographic, its Orthographic Scale SCALE.
#
#   blender -b --factory-startup --python bench/gltf/build_shot.py -- OUT [--frames N] [--detail K] [--ortho SCALE]
import math
import os
import sys

import bpy
import bmesh


def args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    out, frames, detail, ortho = argv[0] if argv else "shot", 24, 1, None
    i = 1
    while i < len(argv):
        if argv[i] == "--frames":
            frames = int(argv[i + 1])
        elif argv[i] == "--detail":
            detail = float(argv[i + 1])
        elif argv[i] == "--ortho":
            ortho = float(argv[i + 1])
        i += 2
    return out, frames, detail, ortho


def key(obj, path, frame, value):
    setattr(obj, path, value)
    obj.keyframe_insert(path, frame=frame)


def count(base, detail):
    """Segments or cuts at a detail: base times detail, rounded (a detail need not be whole)."""
    return max(3, round(base * detail))


def build(frames, detail, ortho):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, frames
    scene.render.fps = 24
    scene.render.resolution_x, scene.render.resolution_y = 1280, 720

    bpy.ops.mesh.primitive_plane_add(size=10)
    bpy.context.object.name = "Ground"

    bpy.ops.object.empty_add(location=(0, 0, 0))
    pivot = bpy.context.object
    pivot.name = "Pivot"
    key(pivot, "rotation_euler", 1, (0, 0, 0))
    key(pivot, "rotation_euler", frames, (0, 0, math.radians(60)))
    bpy.ops.mesh.primitive_cube_add(size=1, location=(-1.5, 0, 0.5))
    box = bpy.context.object
    box.name = "Box"
    box.parent = pivot
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.35, segments=count(16, detail), ring_count=count(8, detail),
                                         location=(-1.5, 0, 1.4))
    ball = bpy.context.object
    ball.name = "Ball"
    bpy.ops.object.shade_smooth()
    ball.parent = box
    ball.matrix_parent_inverse = box.matrix_world.inverted()

    # A tube along z, skinned to two bones; the upper bone bends.
    mesh = bpy.data.meshes.new("Tube")
    bm = bmesh.new()
    bmesh.ops.create_cone(bm, cap_ends=True, segments=count(16, detail), radius1=0.3, radius2=0.3, depth=2.0)
    bmesh.ops.subdivide_edges(bm, edges=[e for e in bm.edges if abs(e.verts[0].co.z - e.verts[1].co.z) > 1.0],
                              cuts=count(8, detail), use_grid_fill=False)
    bmesh.ops.translate(bm, verts=bm.verts, vec=(0, 0, 1.0))
    bm.to_mesh(mesh)
    bm.free()
    tube = bpy.data.objects.new("Tube", mesh)
    scene.collection.objects.link(tube)
    tube.location = (1.5, 0.5, 0)
    bpy.ops.object.armature_add(location=(1.5, 0.5, 0))
    rig = bpy.context.object
    rig.name = "Rig"
    bpy.ops.object.mode_set(mode="EDIT")
    root = rig.data.edit_bones[0]
    root.name = "Lower"
    root.head, root.tail = (0, 0, 0), (0, 0, 1)
    upper = rig.data.edit_bones.new("Upper")
    upper.head, upper.tail, upper.parent = (0, 0, 1), (0, 0, 2), root
    bpy.ops.object.mode_set(mode="OBJECT")
    for name in ("Lower", "Upper"):
        tube.vertex_groups.new(name=name)
    for v in mesh.vertices:
        w = min(max((v.co.z - 0.6) / 0.8, 0.0), 1.0)
        tube.vertex_groups["Lower"].add([v.index], 1.0 - w, "REPLACE")
        tube.vertex_groups["Upper"].add([v.index], w, "REPLACE")
    tube.parent = rig
    tube.matrix_parent_inverse = rig.matrix_world.inverted()
    mod = tube.modifiers.new("Armature", "ARMATURE")
    mod.object = rig
    bone = rig.pose.bones["Upper"]
    bone.rotation_mode = "XYZ"
    bone.rotation_euler = (0, 0, 0)
    bone.keyframe_insert("rotation_euler", frame=1)
    bone.rotation_euler = (math.radians(50), 0, 0)
    bone.keyframe_insert("rotation_euler", frame=frames)

    # A sphere sunk into the ground, whose shape key swells its top.
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.5, segments=count(24, detail), ring_count=count(12, detail),
                                         location=(0, -2, 0.4))
    blob = bpy.context.object
    blob.name = "Blob"
    bpy.ops.object.shade_smooth()
    blob.shape_key_add(name="Basis")
    swell = blob.shape_key_add(name="Swell")
    for i, v in enumerate(blob.data.vertices):
        if v.co.z > 0:
            swell.data[i].co = v.co * (1.0 + 0.6 * v.co.z)
    swell.value = 0.0
    swell.keyframe_insert("value", frame=1)
    swell.value = 1.0
    swell.keyframe_insert("value", frame=frames)

    bpy.ops.object.camera_add(location=(6, -7, 4))
    cam = bpy.context.object
    cam.name = "Camera"
    if ortho:
        cam.data.type = "ORTHO"
        cam.data.ortho_scale = ortho
    scene.camera = cam
    key(cam, "location", 1, (6, -7, 4))
    key(cam, "location", frames, (7, -4, 3))
    # The camera keeps the box in view: its rotation keyed at every frame (a Track To constraint
    # would not reach the glTF file: Blender's exporter keeps only keyed channels).
    cam.rotation_mode = "QUATERNION"
    for frame in range(1, frames + 1):
        scene.frame_set(frame)
        look = box.matrix_world.translation - cam.matrix_world.translation
        cam.rotation_quaternion = look.to_track_quat("-Z", "Y")
        cam.keyframe_insert("rotation_quaternion", frame=frame)
    return scene, cam


def gl(v):
    """Blender (Z up) to glTF (Y up) axes, as Blender's glTF exporter converts them."""
    return (v[0], v[2], -v[1])


def write_frames(out, scene, cam, frames):
    os.makedirs(os.path.join(out, "frames"), exist_ok=True)
    cameras = []
    for frame in range(1, frames + 1):
        scene.frame_set(frame)
        depsgraph = bpy.context.evaluated_depsgraph_get()
        lines = []
        base = 1
        for obj in scene.objects:
            if obj.type != "MESH":
                continue
            ev = obj.evaluated_get(depsgraph)
            m = ev.to_mesh()
            world = ev.matrix_world
            lines.append("o " + obj.name)
            for v in m.vertices:
                p = gl(world @ v.co)
                lines.append("v %.9g %.9g %.9g" % p)
            for poly in m.polygons:
                lines.append("f " + " ".join(str(base + i) for i in poly.vertices))
            base += len(m.vertices)
            ev.to_mesh_clear()
        with open(os.path.join(out, "frames", "f%04d.obj" % frame), "w") as f:
            f.write("\n".join(lines) + "\n")
        mw = cam.evaluated_get(depsgraph).matrix_world
        eye = mw.translation
        forward = -mw.col[2].xyz
        up = mw.col[1].xyz
        aspect = scene.render.resolution_x / scene.render.resolution_y
        view = {"frame": frame, "eye": list(gl(eye)), "target": list(gl(eye + forward)), "up": list(gl(up))}
        if cam.data.type == "ORTHO":
            view["ortho_height"] = cam.data.ortho_scale / aspect  # sensor fit AUTO, landscape: the scale is the width
        else:
            view["fov_y_deg"] = math.degrees(2.0 * math.atan(math.tan(cam.data.angle / 2.0) / aspect))
        cameras.append(view)
    import json
    with open(os.path.join(out, "reference.json"), "w") as f:
        json.dump({"mesh": {"sequence": "frames/f%04d.obj"}, "frames": [1, frames],
                   "image": {"width": 1024, "height": 576}, "camera": {"frames": cameras}}, f, indent=1)


def main():
    out, frames, detail, ortho = args()
    os.makedirs(out, exist_ok=True)
    scene, cam = build(frames, detail, ortho)
    bpy.ops.export_scene.gltf(filepath=os.path.join(out, "shot.glb"), export_format="GLB", export_cameras=True,
                              export_animations=True, export_skins=True, export_morph=True, export_apply=False)
    write_frames(out, scene, cam, frames)
    bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(os.path.join(out, "shot.blend")))


main()
