# SPDX-License-Identifier: MIT
# Checks inkline's camera against Blender's: every point of a polylines JSON frame (its world
# coordinates, glTF axes) projected by Blender's own camera of that frame
# (bpy_extras.object_utils.world_to_camera_view) must land on the point's pixel. Run it on the
# .blend that build_shot.py saved, with a frame inkline drew from that shot's .glb:
#
#   inkline render SHOT/shot.glb --frames F --json f.json
#   blender -b SHOT/shot.blend --python bench/gltf/camera_check.py -- f.json
import json
import sys

import bpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector


def main():
    path = sys.argv[sys.argv.index("--") + 1]
    with open(path) as f:
        frame = json.load(f)
    scene = bpy.context.scene
    scene.frame_set(frame["frame"])
    width, height = frame["image"]["width"], frame["image"]["height"]
    worst, count = 0.0, 0
    for stroke in frame["strokes"]:
        for px, world in zip(stroke["points"], stroke["world"]):
            v = world_to_camera_view(scene, scene.camera, Vector((world[0], -world[2], world[1])))
            worst = max(worst, abs(v.x * width - px[0]), abs((1.0 - v.y) * height - px[1]))
            count += 1
    print("camera %s, frame %d: %d points, worst pixel difference %.6f" %
          (scene.camera.data.type, frame["frame"], count, worst))


main()
