"""Renders a pelage reference scene (scene/reference_scene.h) in Blender Cycles: the path-traced
reference that pelage's frames are measured against (scripts/reference-render.sh).

Run inside Blender (3.4; its Python has no numpy):
  blender -b --factory-startup -noaudio --python scripts/reference/cycles_render.py -- \
      SCENE.pelscene OUT.png [OUT2.png ...] [--samples N] [--as-drawn] [--passes DIR]

Each OUT is an independent render of the scene (N samples per pixel, Cycles' seed 0, 1, ...):
two of them let the caller estimate the reference's own Monte Carlo noise from their difference
(scripts/reference/compare.py).

--passes DIR also writes the first render's light passes (Cycles' view layer passes: Diffuse,
Glossy and Transmission, each Direct, Indirect and Color; the Principled Hair BSDF is glossy, the
skin diffuse) into DIR as NAME.f32 (linear float32 RGBA, rows bottom-up, as Blender keeps them)
with DIR/passes.json giving the image size and the names (scripts/reference/views.py passes reads
them): light a hair the eye sees got straight from a light and scattered once is GlossCol x
GlossDir, light scattered more than once GlossCol x GlossInd, the skin seen DiffCol x (DiffDir +
DiffInd).

What it builds, so that Lambert in Cycles equals pelage's Kd N.L:
- the camera: pelage's eye, target and up, `sensor_fit` VERTICAL with `angle_y` = pelage's
  vertical field of view, the same image size;
- a sun where pelage's key light is, of irradiance pi times its colour; a uniform world of
  pelage's ambient;
- the skin as a mesh, smooth shaded, a diffuse BSDF coloured by each corner's colour;
- each coat's hairs as a Curves object (POLY splines converted to curves) drawn as thick curves
  (`cycles_curves.shape` THICK), radius half the width at each point (--as-drawn: times the
  frame's culling factor, as pelage widens culled strands), the Principled Hair BSDF (Chiang et
  al. 2016) with direct colouring from each point's colour (the hair's root and tip colours
  mixed by k / (K - 1), as pelage grades them);
- film transparent (the caller composites over pelage's background), 'Standard' view transform,
  no denoising (Debian's Blender is built without it), a 1-pixel box pixel filter.
"""
import array
import json
import math
import os
import struct
import sys

import bpy
from mathutils import Matrix, Vector


def fail(message):
    print("cycles_render: error: " + message, file=sys.stderr)
    sys.exit(2)


def read_scene(path):
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        fail("%s: cannot read (%s)" % (path, e.strerror))
    if data[:8] != b"PLGSCN01" or len(data) < 16:
        fail("%s: not a pelage reference scene (pelage render --scene-files writes them)" % path)
    (length,) = struct.unpack_from("<Q", data, 8)
    if 16 + length > len(data):
        fail("%s: truncated header" % path)
    header = json.loads(data[16:16 + length].decode("utf-8"))
    if header.get("format") != "pelage reference scene" or header.get("version") != 1:
        fail("%s: format %r version %r; expected 'pelage reference scene' 1"
             % (path, header.get("format"), header.get("version")))
    base = 16 + length

    def values(spec, code):
        out = array.array(code)
        start = base + spec["offset"]
        end = start + 4 * spec["count"]
        if end > len(data):
            fail("%s: an array runs past the end of the file" % path)
        out.frombytes(data[start:end])
        if sys.byteorder != "little":
            out.byteswap()
        return out

    return header, values


def setup_scene(header, samples):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    # A pixel is the mean over its own square, as pelage's strands are drawn (their coverage of
    # the pixel): a 1-pixel box filter, not Cycles' default 1.5-pixel Blackman-Harris, which
    # would blur the reference's strands into their neighbours.
    scene.cycles.pixel_filter_type = "BOX"
    scene.cycles.filter_width = 1.0
    scene.cycles.max_bounces = 32
    scene.cycles.transparent_max_bounces = 64
    scene.cycles_curves.shape = "THICK"
    scene.cycles_curves.subdivisions = 2
    cam = header["camera"]
    scene.render.resolution_x = cam["width"]
    scene.render.resolution_y = cam["height"]
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = True
    scene.render.image_settings.file_format = "PNG"
    scene.render.image_settings.color_mode = "RGBA"
    scene.render.image_settings.color_depth = "8"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.display_settings.display_device = "sRGB"
    scene.sequencer_colorspace_settings.name = "sRGB"

    # The camera: Blender's looks down its -Z with +Y up.
    data = bpy.data.cameras.new("pelage camera")
    data.sensor_fit = "VERTICAL"
    data.angle_y = math.radians(cam["fovYDegrees"])
    eye, target, up = (Vector(cam[k]) for k in ("eye", "target", "up"))
    forward = (target - eye).normalized()
    right = forward.cross(up).normalized()
    true_up = right.cross(forward)
    data.clip_start = max(1e-4, 0.01 * (target - eye).length)
    data.clip_end = 1000.0 * (target - eye).length
    obj = bpy.data.objects.new("pelage camera", data)
    rotation = Matrix((right, true_up, -forward)).transposed().to_4x4()
    obj.matrix_world = Matrix.Translation(eye) @ rotation
    scene.collection.objects.link(obj)
    scene.camera = obj

    # The key light: a sun shining along -direction with irradiance pi x colour, so a Lambert
    # surface of albedo a gets radiance a N.L (pelage's Kd N.L).
    light = header["light"]
    sun = bpy.data.lights.new("pelage key light", "SUN")
    sun.energy = math.pi
    sun.color = light["color"]
    sun.angle = 0.0
    sun_obj = bpy.data.objects.new("pelage key light", sun)
    sun_obj.rotation_euler = Vector(light["direction"]).to_track_quat("Z", "Y").to_euler()
    scene.collection.objects.link(sun_obj)

    # The ambient: a uniform world of pelage's ambient intensity.
    world = bpy.data.worlds.new("pelage ambient")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = tuple(light["ambient"]) + (1.0,)
    background.inputs["Strength"].default_value = 1.0
    scene.world = world
    return scene


# The colour attributes' name. Not "color": Cycles' Attribute node then reads black without a word
# (Blender 3.4).
COLOR = "pelage_color"


def attribute_node(tree, name):
    node = tree.nodes.new("ShaderNodeAttribute")
    node.attribute_type = "GEOMETRY"
    node.attribute_name = name
    return node


def add_skin(scene, header, values):
    skin = header["skin"]
    n_vertices, n_triangles = skin["vertices"], skin["triangles"]
    if n_triangles == 0:
        return
    mesh = bpy.data.meshes.new("pelage skin")
    mesh.vertices.add(n_vertices)
    mesh.vertices.foreach_set("co", values(skin["positions"], "f"))
    mesh.loops.add(3 * n_triangles)
    mesh.loops.foreach_set("vertex_index", values(skin["indices"], "I"))
    mesh.polygons.add(n_triangles)
    mesh.polygons.foreach_set("loop_start", array.array("i", range(0, 3 * n_triangles, 3)))
    mesh.polygons.foreach_set("loop_total", array.array("i", [3]) * n_triangles)
    mesh.polygons.foreach_set("use_smooth", array.array("b", [1]) * n_triangles)
    mesh.update()
    if mesh.validate():
        fail("the skin's triangles index vertices out of range")
    rgb = values(skin["cornerColors"], "f")
    rgba = array.array("f", [1.0]) * (4 * 3 * n_triangles)
    for c in range(3):
        rgba[c::4] = rgb[c::3]
    colors = mesh.color_attributes.new(COLOR, "FLOAT_COLOR", "CORNER")
    colors.data.foreach_set("color", rgba)
    material = bpy.data.materials.new("pelage skin")
    material.use_nodes = True
    tree = material.node_tree
    tree.nodes.clear()
    diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
    tree.links.new(attribute_node(tree, COLOR).outputs["Color"], diffuse.inputs["Color"])
    output = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(diffuse.outputs["BSDF"], output.inputs["Surface"])
    mesh.materials.append(material)
    obj = bpy.data.objects.new("pelage skin", mesh)
    scene.collection.objects.link(obj)


def hair_material():
    material = bpy.data.materials.new("pelage hair")
    material.use_nodes = True
    tree = material.node_tree
    tree.nodes.clear()
    hair = tree.nodes.new("ShaderNodeBsdfHairPrincipled")
    hair.parametrization = "COLOR"
    tree.links.new(attribute_node(tree, COLOR).outputs["Color"], hair.inputs["Color"])
    output = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(hair.outputs["BSDF"], output.inputs["Surface"])
    return material


def add_coat(scene, coat, values, as_drawn, material):
    n, K = coat["hairs"], coat["points"]
    if n == 0:
        return 0
    positions = values(coat["positions"], "f")
    widths = values(coat["widths"], "f")
    colors = values(coat["colors"], "f")
    widen = coat["cullFactor"] if as_drawn else 1.0
    curve = bpy.data.curves.new("pelage coat %d" % coat["coat"], "CURVE")
    curve.dimensions = "3D"
    co = array.array("f", [1.0]) * (4 * K)
    for i in range(n):
        spline = curve.splines.new("POLY")
        spline.points.add(K - 1)
        p = positions[3 * K * i:3 * K * (i + 1)]
        for a in range(3):
            co[a::4] = p[a::3]
        spline.points.foreach_set("co", co)
    obj = bpy.data.objects.new("pelage coat %d" % coat["coat"], curve)
    scene.collection.objects.link(obj)
    bpy.context.view_layer.objects.active = obj
    for other in scene.objects:
        other.select_set(other == obj)
    bpy.ops.object.convert(target="CURVES")
    obj = bpy.context.view_layer.objects.active
    curves = obj.data
    if len(curves.points) != n * K:
        fail("coat %d: %d curve points after conversion, expected %d"
             % (coat["coat"], len(curves.points), n * K))
    # Radius per point (metres): half the width. Set on the attribute itself (a Named Attribute
    # node's default output would leave every radius at Blender's default without a word).
    radius = array.array("f", (0.5 * widen * widths[k] for k in range(K))) * n
    if "widthScales" in coat:  # a groom's width per hair
        scales = values(coat["widthScales"], "f")
        for i in range(n):
            for k in range(K):
                radius[i * K + k] *= scales[i]
    if "radius" not in curves.attributes:
        curves.attributes.new("radius", "FLOAT", "POINT")
    curves.attributes["radius"].data.foreach_set("value", radius)
    rgba = array.array("f", [1.0]) * (4 * n * K)
    for i in range(n):
        root = colors[6 * i:6 * i + 3]
        tip = colors[6 * i + 3:6 * i + 6]
        for k in range(K):
            t = k / (K - 1) if K > 1 else 0.0
            o = 4 * (i * K + k)
            for a in range(3):
                rgba[o + a] = root[a] + t * (tip[a] - root[a])
    curves.attributes.new(COLOR, "FLOAT_COLOR", "POINT").data.foreach_set("color", rgba)
    curves.materials.append(material)
    # Check what Cycles will draw: the radii read back.
    back = array.array("f", [0.0]) * (n * K)
    curves.attributes["radius"].data.foreach_get("value", back)
    if back != radius:
        fail("coat %d: the curve radii did not take" % coat["coat"])
    return n


PASSES = ("diffuse_direct", "diffuse_indirect", "diffuse_color", "glossy_direct",
          "glossy_indirect", "glossy_color", "transmission_direct", "transmission_indirect",
          "transmission_color")


def enable_passes(scene, folder):
    """Cycles' light passes written by the compositor as float EXRs into folder (one per pass)."""
    layer = scene.view_layers[0]
    for name in PASSES:
        setattr(layer, "use_pass_" + name, True)
    scene.use_nodes = True
    tree = scene.node_tree
    tree.nodes.clear()
    layers = tree.nodes.new("CompositorNodeRLayers")
    out = tree.nodes.new("CompositorNodeOutputFile")
    out.base_path = folder
    out.format.file_format = "OPEN_EXR"
    out.format.color_depth = "32"
    out.file_slots.clear()
    names = [o.name for o in layers.outputs if o.enabled and o.name not in ("Image", "Alpha")]
    for name in names:
        out.file_slots.new(name)
        tree.links.new(layers.outputs[name], out.inputs[-1])
    composite = tree.nodes.new("CompositorNodeComposite")
    tree.links.new(layers.outputs["Image"], composite.inputs["Image"])
    return names


def write_passes(folder, names, width, height):
    """The compositor's EXRs (NAME0001.exr) as NAME.f32 and passes.json; the EXRs removed."""
    for name in names:
        exr = [f for f in os.listdir(folder) if f.startswith(name) and f.endswith(".exr")]
        if len(exr) != 1:
            fail("pass %s: expected one EXR in %s, got %d" % (name, folder, len(exr)))
        image = bpy.data.images.load(os.path.join(folder, exr[0]))
        pixels = array.array("f", [0.0]) * len(image.pixels)
        image.pixels.foreach_get(pixels)
        if len(pixels) != 4 * width * height:
            fail("pass %s: %d values, expected %d" % (name, len(pixels), 4 * width * height))
        with open(os.path.join(folder, name + ".f32"), "wb") as f:
            if sys.byteorder != "little":
                pixels.byteswap()
            pixels.tofile(f)
        bpy.data.images.remove(image)
        os.remove(os.path.join(folder, exr[0]))
    with open(os.path.join(folder, "passes.json"), "w") as f:
        json.dump({"width": width, "height": height, "passes": names}, f)


def main(argv):
    args = argv[argv.index("--") + 1:] if "--" in argv else []
    samples, as_drawn, paths, passes = 256, False, [], None
    i = 0
    while i < len(args):
        if args[i] == "--samples" and i + 1 < len(args):
            samples = int(args[i + 1])
            i += 2
        elif args[i] == "--passes":
            if i + 1 >= len(args):
                fail("--passes needs a folder")
            passes = args[i + 1]
            i += 2
        elif args[i] == "--as-drawn":
            as_drawn = True
            i += 1
        else:
            paths.append(args[i])
            i += 1
    if len(paths) < 2 or not 1 <= samples <= 65536:
        fail("usage: blender -b --python cycles_render.py -- SCENE.pelscene OUT.png "
             "[OUT2.png ...] [--samples N (1..65536)] [--as-drawn] [--passes DIR]")
    header, values = read_scene(paths[0])
    scene = setup_scene(header, samples)
    add_skin(scene, header, values)
    material = hair_material()
    hairs = sum(add_coat(scene, c, values, as_drawn, material) for c in header["coats"])
    names = enable_passes(scene, passes) if passes else None
    for seed, out in enumerate(paths[1:]):
        print("cycles_render: %d hairs, %d skin triangles, %dx%d, %d samples, seed %d -> %s"
              % (hairs, header["skin"]["triangles"], header["camera"]["width"],
                 header["camera"]["height"], samples, seed, out))
        scene.cycles.seed = seed
        scene.render.filepath = out
        bpy.ops.render.render(write_still=True)
        if names is not None:
            write_passes(passes, names, header["camera"]["width"], header["camera"]["height"])
            names, scene.use_nodes = None, False  # the later seeds: the image alone


if __name__ == "__main__":
    main(sys.argv)
