# SPDX-License-Identifier: MIT OR Apache-2.0
"""Import a `swell bake` directory into Blender as an animated ocean.

Written for swell; uses only Blender's public Python API (tested with Blender 3.4.1, Debian
bookworm's `blender` package). Three ways to run it:

* headless or from a terminal::

      blender --background --python tools/blender/swell_import_bake.py -- --bake DIR [--frame N]
          [--save out.blend] [--dump-vertices out.json]

* from Blender's Text Editor (Run Script imports nothing; it registers the operator), or
* as an add-on (Edit > Preferences > Add-ons > Install... this file): File > Import > swell bake.

What it builds (see tools/blender/README.md and docs/baking.md):

* a grid mesh with one vertex per map pixel of `bake.json`'s `grid` (cells + 1 per side; with a
  `--tile` bake the last column and row wrap to the first), in swell's local axes (+Y up), with
  UVs at the pixel centres;
* a Displace modifier (direction RGB to XYZ in local space, mid level 0, strength 1) driven by an
  image-sequence texture of `disp_NNNN.exr` with interpolation and clamping off, so each vertex
  moves by exactly its pixel's float displacement;
* the object rotated +90 degrees about X, so swell's +Y-up local axes land on Blender's Z-up world:
  Blender (X, Y, Z) = swell (x, -z, y), as `bake.json`'s `axes.to_blender` says;
* a material whose base colour mixes the water colour towards white by the foam map (when the
  bake has one), and the scene's frame range and frame rate set from the bake;
* scene frame f shows bake frame f (time f / fps); when the bake is one whole loop
  (`loop_frames` frames), frames beyond it wrap modulo `loop_frames` (the image sequences are
  cyclic), otherwise they hold the first or last frame.
"""

import argparse
import json
import math
import os
import sys

import bpy

bl_info = {
    "name": "swell bake importer",
    "author": "swell",
    "version": (1, 0, 0),
    "blender": (3, 4, 0),
    "location": "File > Import > swell bake (bake.json)",
    "description": "Sets up an animated ocean from a swell bake directory (displacement, normal, foam EXR)",
    "category": "Import-Export",
}

# bake.json's manifest_version values this script reads. Version 1 (before normal spaces and
# axes were recorded) has the same maps in world space, so it imports the same way.
SUPPORTED_MANIFEST_VERSIONS = (1, 2)

# Blender takes scene frame rates as an integer `fps` and a divisor `fps_base`.
MAX_BLENDER_FPS = 32767


class BakeError(Exception):
    """A bake directory this script cannot import; the message says why."""


def read_manifest(bake_dir):
    """Loads and checks `bake_dir/bake.json`; returns the manifest as a dict."""
    path = os.path.join(bake_dir, "bake.json")
    try:
        with open(path, encoding="utf-8") as f:
            manifest = json.load(f)
    except FileNotFoundError:
        raise BakeError(f"{path} does not exist: not a bake directory written by `swell bake`")
    except json.JSONDecodeError as e:
        raise BakeError(f"{path} is not valid JSON: {e}")
    version = manifest.get("manifest_version", 1)
    if version not in SUPPORTED_MANIFEST_VERSIONS:
        raise BakeError(
            f"{path}: manifest_version = {version} is not one of {SUPPORTED_MANIFEST_VERSIONS}; "
            "update tools/blender/swell_import_bake.py to the swell that baked it"
        )
    for key in ("grid", "fps", "frames", "maps"):
        if key not in manifest:
            raise BakeError(f"{path} has no `{key}`")
    return manifest


def map_entry(manifest, name):
    """The `maps` entry called `name` (disp, normal, foam), or None."""
    for m in manifest["maps"]:
        if m["name"] == name:
            return m
    return None


def frame_file(bake_dir, pattern, frame):
    """The file of `frame` for a pattern such as `disp_{frame:04}.exr`."""
    return os.path.join(bake_dir, pattern.format(frame=frame))


def sequence_timing(manifest):
    """How scene frames map to bake frames.

    Returns (first, count, cyclic): the image sequences start at scene frame `first` (the bake's
    first frame A, so scene frame f shows bake frame f), hold `count` frames, and are cyclic when
    the bake is exactly one loop of the model (count == loop_frames), so that scene frame f shows
    bake frame A + (f - A) mod count.
    """
    first, last = manifest["frames"]
    count = last - first + 1
    loop_frames = manifest.get("loop_frames")
    return first, count, loop_frames is not None and loop_frames == count


def load_sequence(bake_dir, manifest, name, label):
    """Loads map `name`'s EXR sequence as one Blender image (source SEQUENCE, non-colour data)."""
    entry = map_entry(manifest, name)
    if entry is None:
        return None
    first = manifest["frames"][0]
    path = frame_file(bake_dir, entry["exr"], first)
    if not os.path.isfile(path):
        raise BakeError(f"{path} does not exist: the bake's first frame is incomplete")
    image = bpy.data.images.load(path, check_existing=False)
    image.name = label
    image.source = "SEQUENCE"
    # Raw float data: no colour transform between the file and the texture lookup.
    image.colorspace_settings.name = "Non-Color"
    return image


def set_image_user(iuser, manifest):
    """Makes an image user play the bake's frames at the scene frames that match them."""
    first, count, cyclic = sequence_timing(manifest)
    iuser.frame_duration = count
    iuser.frame_start = first
    # Blender shows file number (f - frame_start + 1) + frame_offset at scene frame f (wrapped
    # into [1, frame_duration] when cyclic, clamped otherwise): offset first - 1 gives file f.
    iuser.frame_offset = first - 1
    iuser.use_cyclic = cyclic
    iuser.use_auto_refresh = True


def build_grid_mesh(name, manifest):
    """The rest grid in swell's local axes (x, 0, z) with UVs at pixel centres.

    Vertex (i, j) is at origin_m + (i, j) * spacing_m, index j * (cells_x + 1) + i, the order of
    swell's own meshes and OBJ export. Its UV is ((i + 0.5) / width, 1 - (j + 0.5) / height):
    the centre of pixel (i, j) of a map whose row 0 is the top (Blender's images start at the
    bottom row, hence 1 - ...). With a `--tile` bake (width = cells) vertex i = cells gets
    u > 1, which the texture's REPEAT extension wraps to pixel 0, as the periodic patch does.
    """
    grid = manifest["grid"]
    cx, cz = grid["cells"]
    width, height = grid["pixels"]
    ox, oz = grid["origin_m"]
    sx, sz = grid["spacing_m"]
    nx, nz = cx + 1, cz + 1
    verts = [(ox + i * sx, 0.0, oz + j * sz) for j in range(nz) for i in range(nx)]
    faces = []
    for j in range(cz):
        for i in range(cx):
            v00 = j * nx + i
            # Counter-clockwise seen from +Y (swell's up), so faces point up after the rotation.
            faces.append((v00, v00 + nx, v00 + nx + 1, v00 + 1))
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    uv_layer = mesh.uv_layers.new(name="UVMap")
    # Per vertex once, then per face corner through the corners' vertex indices.
    vertex_uv = [((i + 0.5) / width, 1.0 - (j + 0.5) / height) for j in range(nz) for i in range(nx)]
    corner_vertex = [0] * len(mesh.loops)
    mesh.loops.foreach_get("vertex_index", corner_vertex)
    uv_layer.data.foreach_set("uv", [c for v in corner_vertex for c in vertex_uv[v]])
    mesh.update()
    return mesh


def build_material(name, manifest, foam_image):
    """Principled BSDF; with a foam map, base colour = mix(water, white, foam) by a colour ramp."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = nodes.get("Principled BSDF")
    water_rgba = (0.02, 0.10, 0.14, 1.0)
    if bsdf is not None:
        bsdf.inputs["Base Color"].default_value = water_rgba
        bsdf.inputs["Roughness"].default_value = 0.05
    if foam_image is None or bsdf is None:
        return mat
    uv = nodes.new("ShaderNodeUVMap")
    uv.uv_map = "UVMap"
    tex = nodes.new("ShaderNodeTexImage")
    tex.name = tex.label = "swell foam"
    tex.image = foam_image
    # Linear between pixel centres (the UVs sit on them), wrapping for tiled bakes.
    tex.interpolation = "Linear"
    tex.extension = "REPEAT" if manifest["grid"].get("tile") else "EXTEND"
    set_image_user(tex.image_user, manifest)
    ramp = nodes.new("ShaderNodeValToRGB")
    ramp.color_ramp.elements[0].color = water_rgba
    ramp.color_ramp.elements[1].color = (0.9, 0.92, 0.94, 1.0)
    links.new(uv.outputs["UV"], tex.inputs["Vector"])
    links.new(tex.outputs["Color"], ramp.inputs["Fac"])
    links.new(ramp.outputs["Color"], bsdf.inputs["Base Color"])
    return mat


def set_scene_timing(scene, manifest):
    """Scene frame range = the bake's range; frame rate = the bake's (as fps / fps_base)."""
    first, last = manifest["frames"]
    scene.frame_start = first
    scene.frame_end = last
    fps = float(manifest["fps"])
    fps_int = min(MAX_BLENDER_FPS, max(1, math.ceil(fps)))
    scene.render.fps = fps_int
    scene.render.fps_base = fps_int / fps


def import_bake(bake_dir, context=None, name="swell ocean"):
    """Builds the ocean object for `bake_dir` in the current scene and returns it."""
    context = context or bpy.context
    # Absolute paths: a saved .blend finds the maps from any working directory.
    bake_dir = os.path.abspath(bake_dir)
    manifest = read_manifest(bake_dir)
    if map_entry(manifest, "disp") is None:
        raise BakeError(f"{bake_dir}/bake.json lists no `disp` map")
    tile = bool(manifest["grid"].get("tile"))

    disp_image = load_sequence(bake_dir, manifest, "disp", f"{name} disp")
    foam_image = load_sequence(bake_dir, manifest, "foam", f"{name} foam")

    mesh = build_grid_mesh(name, manifest)
    obj = bpy.data.objects.new(name, mesh)
    context.scene.collection.objects.link(obj)
    # swell's local +Y up onto Blender's +Z up: (x, y, z) -> (x, -z, y).
    obj.rotation_euler = (math.pi / 2.0, 0.0, 0.0)

    tex = bpy.data.textures.new(f"{name} displacement", type="IMAGE")
    tex.image = disp_image
    set_image_user(tex.image_user, manifest)
    tex.use_interpolation = False  # nearest pixel: the vertex's own value
    tex.use_mipmap = False
    tex.use_clamp = False  # keep negative displacements
    tex.extension = "REPEAT" if tile else "EXTEND"

    mod = obj.modifiers.new("swell displacement", "DISPLACE")
    mod.texture = tex
    mod.texture_coords = "UV"
    mod.uv_layer = "UVMap"
    mod.direction = "RGB_TO_XYZ"
    mod.space = "LOCAL"
    mod.mid_level = 0.0
    mod.strength = 1.0

    obj.data.materials.append(build_material(f"{name} material", manifest, foam_image))
    set_scene_timing(context.scene, manifest)
    obj["swell_bake_dir"] = bake_dir
    obj["swell_normal_space"] = manifest.get("normal_space", "world")
    return obj


def dump_vertices(obj, path, frame):
    """Writes the evaluated mesh's world-space vertex positions (metres, Blender axes) as JSON."""
    depsgraph = bpy.context.evaluated_depsgraph_get()
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    world = evaluated.matrix_world
    verts = [list(world @ v.co) for v in mesh.vertices]
    foam = None
    for slot in obj.material_slots:
        node = slot.material.node_tree.nodes.get("swell foam") if slot.material and slot.material.node_tree else None
        if node is not None and node.image is not None:
            foam = {"image": bpy.path.abspath(node.image.filepath), "cyclic": node.image_user.use_cyclic}
    out = {"frame": frame, "vertices": verts, "foam": foam}
    evaluated.to_mesh_clear()
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        json.dump(out, f)
    os.replace(tmp, path)


class IMPORT_OT_swell_bake(bpy.types.Operator):
    """Set up an animated ocean from a swell bake directory (bake.json and EXR maps)"""

    bl_idname = "import_scene.swell_bake"
    bl_label = "Import swell bake"
    bl_options = {"REGISTER", "UNDO"}

    filepath: bpy.props.StringProperty(subtype="FILE_PATH")
    filter_glob: bpy.props.StringProperty(default="bake.json", options={"HIDDEN"})

    def execute(self, context):
        try:
            import_bake(os.path.dirname(self.filepath), context)
        except BakeError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        return {"FINISHED"}

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}


def menu_import(self, context):
    self.layout.operator(IMPORT_OT_swell_bake.bl_idname, text="swell bake (bake.json)")


def register():
    bpy.utils.register_class(IMPORT_OT_swell_bake)
    bpy.types.TOPBAR_MT_file_import.append(menu_import)


def unregister():
    bpy.types.TOPBAR_MT_file_import.remove(menu_import)
    bpy.utils.unregister_class(IMPORT_OT_swell_bake)


def parse_args(argv):
    p = argparse.ArgumentParser(
        prog="blender --background --python swell_import_bake.py --",
        description="Import a swell bake directory as an animated ocean.",
    )
    p.add_argument("--bake", required=True, help="the bake directory (holds bake.json)")
    p.add_argument("--frame", type=int, help="scene frame to show (default: the bake's first)")
    p.add_argument("--name", default="swell ocean", help="object name (default: %(default)s)")
    p.add_argument("--keep-scene", action="store_true", help="keep the default cube, camera and light")
    p.add_argument("--save", help="save the scene as this .blend file")
    p.add_argument("--dump-vertices", help="write the evaluated mesh's world vertex positions as JSON")
    return p.parse_args(argv)


def main(argv):
    args = parse_args(argv)
    if not args.keep_scene:
        for obj in list(bpy.context.scene.objects):
            bpy.data.objects.remove(obj, do_unlink=True)
    try:
        obj = import_bake(args.bake, name=args.name)
    except BakeError as e:
        print(f"error: {e}", file=sys.stderr)
        sys.exit(1)
    scene = bpy.context.scene
    frame = scene.frame_start if args.frame is None else args.frame
    scene.frame_set(frame)
    if args.dump_vertices:
        dump_vertices(obj, args.dump_vertices, frame)
    if args.save:
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(args.save))
    print(f"swell: imported {args.bake} as '{obj.name}', scene frame {frame}")


if __name__ == "__main__":
    if "--" in sys.argv:
        main(sys.argv[sys.argv.index("--") + 1 :])
    else:
        # Run from the Text Editor: make the operator available (File > Import).
        register()
