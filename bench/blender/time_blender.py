# SPDX-License-Identifier: MIT
# Times Blender's line renderers per frame on the scene of build_scene.py.
#
#   blender -b OUT_DIR/scene.blend --python bench/blender/time_blender.py -- MODE RESULT.json
#       [--frames A:B] [--svg-dir DIR]
#
# MODE:
#   lineart    a grease-pencil object with a Line Art modifier on Suzanne (contour, which in
#              Line Art includes border edges, and crease at 134 degrees, i.e. normals more than
#              46 degrees apart), evaluated by frame_set, then bpy.ops.wm.gpencil_export_svg of
#              that frame. Times: "eval" (Line Art) and "export" (SVG), per frame.
#   baseline   the same frame_set loop without Line Art: what stepping the scene costs alone.
#   freestyle  Cycles render (1 sample) with Freestyle on (silhouette, border, crease at 134
#              degrees, visible lines) and the Freestyle SVG exporter add-on.
#   render     the same render without Freestyle: subtract it from "freestyle".
#
# Start-up (Blender itself, loading the .blend, building the modifier) happens before the first
# timed frame and is not counted. RESULT.json gets {"mode", "frames": [{"frame", "ms", "cpu_ms",
# ...}]}: wall-clock and process CPU time (all threads) per frame.

import json
import math
import os
import sys
import time

import bpy

CREASE_ANGLE_BLENDER_DEG = 134.0


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) < 2 or argv[0] not in ("lineart", "baseline", "freestyle", "render"):
        raise SystemExit("usage: blender -b scene.blend --python time_blender.py -- "
                         "lineart|baseline|freestyle|render RESULT.json [--frames A:B] [--svg-dir DIR]")
    opts = {"mode": argv[0], "result": argv[1], "frames": None, "svg_dir": None}
    i = 2
    while i + 1 < len(argv):
        if argv[i] == "--frames":
            a, _, b = argv[i + 1].partition(":")
            opts["frames"] = (int(a), int(b or a))
        elif argv[i] == "--svg-dir":
            opts["svg_dir"] = argv[i + 1]
        else:
            raise SystemExit("time_blender.py: unknown option " + argv[i])
        i += 2
    return opts


def add_lineart(scene, source):
    """A grease-pencil object whose Line Art modifier draws source's lines into one layer; with
    no source object, every object of the scene's, intersections included (a glTF shot,
    bench/gltf/build_shot.py)."""
    gp = bpy.data.grease_pencils.new("LineArt")
    ob = bpy.data.objects.new("LineArt", gp)
    scene.collection.objects.link(ob)
    layer = gp.layers.new("Lines")
    layer.frames.new(scene.frame_start)  # Line Art writes into the layer's active frame
    mat = bpy.data.materials.new("Ink")
    bpy.data.materials.create_gpencil_data(mat)
    gp.materials.append(mat)
    mod = ob.grease_pencil_modifiers.new("LineArt", 'GP_LINEART')
    if source is not None:
        mod.source_type = 'OBJECT'
        mod.source_object = source
    else:
        mod.source_type = 'SCENE'
    mod.target_layer = layer.info
    mod.target_material = mat
    mod.use_contour = True
    mod.use_crease = True
    mod.crease_threshold = math.radians(CREASE_ANGLE_BLENDER_DEG)
    mod.use_crease_on_smooth = True  # the mesh is flat-shaded anyway; creases everywhere
    mod.use_crease_on_sharp = True
    for flag in ("use_loose", "use_material", "use_edge_mark", "use_intersection",
                 "use_light_contour", "use_shadow"):
        setattr(mod, flag, False)
    mod.use_intersection = source is None
    for other in bpy.context.view_layer.objects:
        other.select_set(False)
    ob.select_set(True)
    bpy.context.view_layer.objects.active = ob
    return ob


def view3d_override():
    """The SVG exporter projects through a 3D view; background mode has a screen but no
    window, so pass the Layout screen's 3D view explicitly, looking through the camera."""
    screen = bpy.data.screens["Layout"]
    area = next(a for a in screen.areas if a.type == 'VIEW_3D')
    region = next(r for r in area.regions if r.type == 'WINDOW')
    area.spaces.active.region_3d.view_perspective = 'CAMERA'
    return {"screen": screen, "area": area, "region": region}


def setup_freestyle(scene, enabled, svg_dir):
    scene.render.engine = 'CYCLES'
    scene.cycles.device = 'CPU'
    scene.cycles.samples = 1
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    scene.render.use_freestyle = enabled
    scene.render.line_thickness_mode = 'ABSOLUTE'
    view_layer = scene.view_layers[0]
    view_layer.use_freestyle = enabled
    settings = view_layer.freestyle_settings
    settings.mode = 'EDITOR'
    settings.crease_angle = math.radians(CREASE_ANGLE_BLENDER_DEG)
    settings.use_culling = False
    settings.use_smoothness = False
    if not settings.linesets:
        settings.linesets.new("LineSet")
    for i, lineset in enumerate(settings.linesets):
        lineset.show_render = i == 0
    lineset = settings.linesets[0]
    lineset.select_by_visibility = True
    lineset.visibility = 'VISIBLE'
    lineset.select_by_edge_types = True
    lineset.select_by_face_marks = lineset.select_by_collection = lineset.select_by_image_border = False
    edge_types = ("silhouette", "border", "crease", "ridge_valley", "suggestive_contour",
                  "material_boundary", "contour", "external_contour", "edge_mark")
    for edge in edge_types:
        setattr(lineset, "select_" + edge, edge in ("silhouette", "border", "crease"))
    if enabled:
        import addon_utils
        addon_utils.enable("render_freestyle_svg", default_set=True)
        scene.svg_export.use_svg_export = True
        scene.svg_export.mode = 'FRAME'
        scene.render.filepath = os.path.join(svg_dir, "freestyle_")


def main():
    opts = parse_args()
    scene = bpy.context.scene
    first, last = opts["frames"] or (scene.frame_start, scene.frame_end)
    svg_dir = os.path.abspath(opts["svg_dir"] or os.path.join(os.path.dirname(opts["result"]), "svg"))
    os.makedirs(svg_dir, exist_ok=True)
    suzanne = bpy.data.objects.get("Suzanne")  # absent in a glTF shot: Line Art takes the scene
    mode = opts["mode"]

    override = None
    if mode == "lineart":
        add_lineart(scene, suzanne)
        override = view3d_override()
    elif mode in ("freestyle", "render"):
        setup_freestyle(scene, mode == "freestyle", svg_dir)
        scene.render.image_settings.file_format = 'PNG'

    # Leave the first frame so the first timed frame_set really evaluates.
    scene.frame_set(last + 1)
    frames = []
    for frame in range(first, last + 1):
        record = {"frame": frame}
        c0 = time.process_time()  # CPU time of the whole process, all threads
        t0 = time.perf_counter()
        scene.frame_set(frame)
        if mode in ("lineart", "baseline"):
            bpy.context.evaluated_depsgraph_get()  # frame_set has evaluated it already
            t1 = time.perf_counter()
            record["eval_ms"] = 1000.0 * (t1 - t0)
            if mode == "lineart":
                with bpy.context.temp_override(**override):
                    bpy.ops.wm.gpencil_export_svg(
                        filepath=os.path.join(svg_dir, "lineart_%04d.svg" % frame), use_fill=False,
                        selected_object_type='ACTIVE', use_clip_camera=True)
            record["export_ms"] = 1000.0 * (time.perf_counter() - t1)
        else:
            bpy.ops.render.render(write_still=False)
        record["ms"] = 1000.0 * (time.perf_counter() - t0)
        record["cpu_ms"] = 1000.0 * (time.process_time() - c0)
        frames.append(record)
        print("time_blender: %s frame %d: %.1f ms" % (mode, frame, record["ms"]), flush=True)

    with open(opts["result"], "w") as out:
        json.dump({"mode": mode, "blender": bpy.app.version_string, "frames": frames}, out, indent=1)


main()
