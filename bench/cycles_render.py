"""Renders stacks of per-seed Cycles images of a small scene built in code,
for bench/bench_cycles_pixels.py (runs under Blender's Python module, the
`bpy` wheel from PyPI, not under the project's venv; report only).

The scene (no assets): a Cornell-like room (2 x 2 x 2, open towards the
camera, black world) split by a partition into
  left   lit by a small ceiling area light: a tall diffuse box (the
         albedo change's surface), a glossy metal sphere, red left wall;
  right  lit by a dim point light high up, and by a lamp inside a glass
         sphere (an emissive sphere in a clear glass shell): its light
         reaches the diffuse surfaces only through caustic paths (shadow
         rays do not pass glass, so next event estimation never sees it),
         found by BSDF sampling alone, and by indirect light from the left
         part that comes round the front of the partition.  Without the
         light tree, next event estimation picks the dim light rarely
         (the lamp's ~2300 emissive triangles and the ceiling light
         compete for the picks): its pixels are zero in most renders at a
         few samples per pixel, lit by rare paths only.
Everything is rendered linear (Combined pass, float32 EXR read back), no
denoising, no adaptive sampling, no clamping (Cycles' default indirect
clamp of 10 is a bias that differs between samplers), no glossy filter,
the default pixel filter, 1 thread, CPU; seed i renders with
scene.cycles.seed = offset + i, each setting its own offset (disjoint
seeds between settings, so that two settings' renders are independent);
with --paired-with SETTING each setting renders with SETTING's seeds
instead (same-seed pairs, for paired tests), saved as NAME@SETTING_....

Settings (name: what differs from "base", Cycles' defaults: light tree on,
path guiding off):
  base          light tree on, path guiding off
  lt_off        light tree off
  guide_on      path guiding on (surface guiding, deterministic guiding)
  light_x1.02   the ceiling light's and the dim light's power x1.02
                (the lamp in glass unchanged)
  albedo_x1.05  the tall box's base colour x1.05
  lamp_off      the glass-shelled lamp off (the ceiling light's share of
                each pixel: where the light change is a 2% change)
  mask_albedo   (not a stack) the pixels where the tall box is seen: its
                material white emission, everything else black, 0 bounces
Each setting's stack is saved as <cache>/<name>_<spp>spp_<W>x<H>.npy,
float32 (K, H, W, 3), rows top to bottom; an existing stack is extended
(seeds K.. appended) when more seeds are asked for.

    /work/bpy-venv/bin/python bench/cycles_render.py --seeds 128 --spp 4 \
        [--size 64] [--cache /work/cycles-cache] [--settings base,lt_off,...]
        [--paired-with base]
"""
import argparse
import json
import math
import os
import sys
import tempfile
import time

import numpy as np

import bpy

SETTINGS = ("base", "lt_off", "guide_on", "light_x1.02", "albedo_x1.05", "lamp_off")
# disjoint seed ranges: setting j renders seeds OFFSET[j] + i
OFFSET = {"base": 0, "lt_off": 100000, "guide_on": 200000, "light_x1.02": 300000, "albedo_x1.05": 400000,
          "lamp_off": 500000}
LIGHT_POWER = 60.0      # W, the ceiling area light
LAMP_STRENGTH = 400.0   # emission strength of the lamp inside the glass sphere
BOX_ALBEDO = 0.6
DIM_LIGHT_POWER = 3.0   # W, the point light in the right part
N_AWAY_LIGHTS = 64      # spot lights behind the back wall, pointing away


def _material(name, color=None, *, emission=None, metallic=0.0, roughness=0.5, glass=False):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nt = m.node_tree
    for n in list(nt.nodes):
        nt.nodes.remove(n)
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    if emission is not None:
        sh = nt.nodes.new("ShaderNodeEmission")
        sh.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
        sh.inputs["Strength"].default_value = emission
    elif glass:
        sh = nt.nodes.new("ShaderNodeBsdfGlass")
        sh.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
        sh.inputs["Roughness"].default_value = 0.0
        sh.inputs["IOR"].default_value = 1.5
    elif metallic > 0:
        sh = nt.nodes.new("ShaderNodeBsdfPrincipled")
        sh.inputs["Base Color"].default_value = (*color, 1.0)
        sh.inputs["Metallic"].default_value = metallic
        sh.inputs["Roughness"].default_value = roughness
    else:
        sh = nt.nodes.new("ShaderNodeBsdfDiffuse")
        sh.inputs["Color"].default_value = (*color, 1.0)
    nt.links.new(sh.outputs[0], out.inputs["Surface"])
    return m


def _box(name, lo, hi, mat):
    """An axis-aligned box from corner lo to corner hi."""
    c = [(a + b) / 2 for a, b in zip(lo, hi)]
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=c)
    o = bpy.context.active_object
    o.name = name
    o.scale = [b - a for a, b in zip(lo, hi)]
    o.data.materials.append(mat)
    return o


def _sphere(name, loc, r, mat):
    bpy.ops.mesh.primitive_uv_sphere_add(segments=48, ring_count=24, radius=r, location=loc)
    o = bpy.context.active_object
    o.name = name
    bpy.ops.object.shade_smooth()
    o.data.materials.append(mat)
    return o


def build_scene(size, spp):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    sc = bpy.context.scene
    white = _material("white", (0.73, 0.73, 0.73))
    red = _material("red", (0.63, 0.065, 0.05))
    green = _material("green", (0.14, 0.45, 0.09))
    t = 0.05  # wall thickness
    _box("floor", (-1 - t, -1, -t), (1 + t, 1 + t, 0), white)
    _box("ceiling", (-1 - t, -1, 2), (1 + t, 1 + t, 2 + t), white)
    _box("back", (-1 - t, 1, 0), (1 + t, 1 + t, 2), white)
    _box("left", (-1 - t, -1, 0), (-1, 1, 2), red)
    _box("right", (1, -1, 0), (1 + t, 1, 2), green)
    _box("partition", (0.2, -0.3, 0), (0.2 + t, 1, 2), white)
    box_mat = _material("box", (BOX_ALBEDO, BOX_ALBEDO, BOX_ALBEDO))
    box = _box("tall_box", (-0.75, 0.15, 0), (-0.3, 0.6, 1.2), box_mat)
    box.rotation_euler = (0, 0, math.radians(15))
    _sphere("metal_sphere", (-0.35, -0.35, 0.3), 0.3, _material("metal", (0.9, 0.85, 0.7), metallic=1.0,
                                                                  roughness=0.15))
    # the lamp in a glass shell, right part
    _sphere("glass_shell", (0.62, 0.55, 0.3), 0.12, _material("glass", glass=True))
    _sphere("lamp", (0.62, 0.55, 0.3), 0.06, _material("lamp", emission=LAMP_STRENGTH))
    # a diffuse block in the right part, casting caustic shadows
    _box("block", (0.35, -0.1, 0), (0.6, 0.15, 0.35), white)
    bpy.ops.object.light_add(type="AREA", location=(-0.4, 0.2, 1.98))
    light = bpy.context.active_object
    light.name = "ceiling_light"
    light.data.shape = "SQUARE"
    light.data.size = 0.3
    light.data.energy = LIGHT_POWER
    # a dim point light high in the right part: the light tree picks it for
    # the right part's pixels; without the tree it competes with the
    # ceiling light and the lamp's ~2300 emissive triangles, and is rarely
    # picked (its pixels zero in most renders, bright when picked)
    bpy.ops.object.light_add(type="POINT", location=(0.7, 0.1, 1.75))
    nook = bpy.context.active_object
    nook.name = "dim_light"
    nook.data.shadow_soft_size = 0.02
    nook.data.energy = DIM_LIGHT_POWER
    # many lights that light nothing the camera can see: spot lights behind
    # the back wall pointing away from the room (a scene with many lights
    # elsewhere).  The light tree's cone bounds never pick them for the
    # room's points; without the tree they take most of next event
    # estimation's picks, and the room's lights are picked rarely.
    for i in range(N_AWAY_LIGHTS):
        x, z = -0.9 + 1.8 * (i % 8) / 7, 0.1 + 1.8 * (i // 8) / max(1, (N_AWAY_LIGHTS - 1) // 8)
        bpy.ops.object.light_add(type="SPOT", location=(x, 1.4, z), rotation=(math.radians(-90), 0, 0))
        sp = bpy.context.active_object
        sp.name = f"away_{i}"
        sp.data.energy = DIM_LIGHT_POWER
        sp.data.spot_size = math.radians(30)
        sp.data.shadow_soft_size = 0.02
    bpy.ops.object.camera_add(location=(0, -3.2, 1.0), rotation=(math.radians(90), 0, 0))
    cam = bpy.context.active_object
    cam.data.lens = 38
    sc.camera = cam
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    sc.world = world
    r = sc.render
    r.engine = "CYCLES"
    r.resolution_x = r.resolution_y = size
    r.resolution_percentage = 100
    r.threads_mode = "FIXED"
    r.threads = 1
    r.film_transparent = False
    r.image_settings.file_format = "OPEN_EXR"
    r.image_settings.color_depth = "32"
    r.image_settings.exr_codec = "NONE"
    r.image_settings.color_mode = "RGB"
    sc.view_settings.view_transform = "Standard"
    sc.view_settings.look = "None"
    sc.view_settings.exposure = 0.0
    sc.view_settings.gamma = 1.0
    c = sc.cycles
    c.device = "CPU"
    c.samples = spp
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.use_animated_seed = False
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.blur_glossy = 0.0
    c.caustics_reflective = True
    c.caustics_refractive = True
    c.use_light_tree = True
    c.use_guiding = False
    return sc


def apply_setting(sc, name):
    c = sc.cycles
    c.use_light_tree = name != "lt_off"
    c.use_guiding = name == "guide_on"
    if name == "guide_on":
        c.use_surface_guiding = True
        c.use_volume_guiding = False
        c.use_deterministic_guiding = True
    f = 1.02 if name == "light_x1.02" else 1.0
    bpy.data.objects["ceiling_light"].data.energy = LIGHT_POWER * f
    bpy.data.objects["dim_light"].data.energy = DIM_LIGHT_POWER * f
    lamp = bpy.data.materials["lamp"].node_tree.nodes["Emission"]
    lamp.inputs["Strength"].default_value = 0.0 if name == "lamp_off" else LAMP_STRENGTH
    a = BOX_ALBEDO * (1.05 if name == "albedo_x1.05" else 1.0)
    node = bpy.data.materials["box"].node_tree.nodes["Diffuse BSDF"]
    node.inputs["Color"].default_value = (a, a, a, 1.0)


def render_one(sc, seed, tmpdir):
    sc.cycles.seed = seed
    path = os.path.join(tmpdir, f"r{seed}.exr")
    sc.render.filepath = path
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(path)
    w, h = img.size
    buf = np.empty(w * h * img.channels, dtype=np.float32)
    img.pixels.foreach_get(buf)
    ch = img.channels
    bpy.data.images.remove(img)
    os.remove(path)
    a = buf.reshape(h, w, ch)[::-1, :, :3]  # Blender's rows run bottom to top
    return np.ascontiguousarray(a)


def render_mask(sc, size, cache, spp):
    """The tall box's pixels: its material white emission, the rest black,
    no bounces; 64 spp; saved as float coverage (H, W)."""
    path = os.path.join(cache, f"mask_albedo_{spp}spp_{size}x{size}.npy")
    if os.path.exists(path):
        return
    black = _material("black_em", emission=0.0)
    white_em = _material("white_em", emission=1.0)
    for o in bpy.data.objects:
        if o.type == "MESH":
            o.data.materials[0] = white_em if o.name == "tall_box" else black
    bpy.data.objects["ceiling_light"].hide_render = True
    for o in bpy.data.objects:
        if o.type == "LIGHT":
            o.hide_render = True
    c = sc.cycles
    c.max_bounces, c.samples = 0, 64
    with tempfile.TemporaryDirectory() as td:
        a = render_one(sc, 0, td)
    np.save(path, a[..., 0].astype(np.float32))
    print("mask", path, int((a[..., 0] > 0.5).sum()), "pixels", flush=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", type=int, default=128)
    ap.add_argument("--spp", type=int, default=4)
    ap.add_argument("--size", type=int, default=64)
    ap.add_argument("--cache", default="/work/cycles-cache")
    ap.add_argument("--settings", default=",".join(SETTINGS))
    ap.add_argument("--paired-with", default=None, metavar="SETTING",
                    help="render each setting with SETTING's seeds (same-seed pairs, for paired tests); "
                         "written to NAME@SETTING_...npy")
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    a = ap.parse_args(argv)
    os.makedirs(a.cache, exist_ok=True)
    names = [s for s in a.settings.split(",") if s]
    for n in names:
        if n not in SETTINGS and n != "mask_albedo":
            raise SystemExit(f"unknown setting {n!r}; known: {', '.join(SETTINGS)}, mask_albedo")
    sc = build_scene(a.size, a.spp)
    print("Blender", bpy.app.version_string, bpy.app.build_hash.decode(), flush=True)
    with tempfile.TemporaryDirectory() as td:
        for n in names:
            if n == "mask_albedo":
                continue
            tag = f"{n}@{a.paired_with}" if a.paired_with else n
            offset = OFFSET[a.paired_with] if a.paired_with else OFFSET[n]
            path = os.path.join(a.cache, f"{tag}_{a.spp}spp_{a.size}x{a.size}.npy")
            have = np.load(path) if os.path.exists(path) else np.zeros((0, a.size, a.size, 3), np.float32)
            if have.shape[0] >= a.seeds:
                print(tag, "has", have.shape[0], "seeds", flush=True)
                continue
            apply_setting(sc, n)
            t0 = time.time()
            new = []
            for i in range(have.shape[0], a.seeds):
                new.append(render_one(sc, offset + i, td))
                if (i + 1) % 16 == 0:  # save as we go: a stopped run keeps its renders
                    have = np.concatenate([have, np.stack(new)])
                    new = []
                    np.save(path, have)
                    print(f"{tag}: {have.shape[0]} seeds, {(time.time() - t0):.0f} s", flush=True)
            if new:
                have = np.concatenate([have, np.stack(new)])
                np.save(path, have)
            print(tag, have.shape, f"{time.time() - t0:.0f} s", flush=True)
    if a.paired_with:
        return
    meta = os.path.join(a.cache, f"meta_{a.spp}spp_{a.size}x{a.size}.json")
    with open(meta, "w") as f:
        json.dump({"blender": bpy.app.version_string, "build_hash": bpy.app.build_hash.decode(),
                   "spp": a.spp, "size": a.size, "offsets": OFFSET, "light_power": LIGHT_POWER,
                   "lamp_strength": LAMP_STRENGTH, "box_albedo": BOX_ALBEDO,
                   "dim_light_power": DIM_LIGHT_POWER,
                   "away_lights": N_AWAY_LIGHTS, "threads": 1,
                   "device": "CPU"}, f, indent=1)
    if "mask_albedo" in names:
        render_mask(sc, a.size, a.cache, a.spp)


if __name__ == "__main__":
    main()
