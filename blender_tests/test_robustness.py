# SPDX-License-Identifier: Apache-2.0
"""Awkward scenes render without crashing, without NaN/Inf, and say what they skipped.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_robustness.py
"""

import math

import bpy
import numpy as np

from torrance_tools import testing
from torrance_tools.testing import check

W, H, SAMPLES = 64, 48, 4


def base_scene(world=(0.2, 0.3, 0.4)):
    scene = testing.clear_scene()
    testing.setup_render(scene, width=W, height=H, samples=SAMPLES)
    testing.add_camera(scene)
    if world is not None:
        testing.set_world(scene, world)
    return scene


def render_case(name, scene, directory, expect=(), levels=('WARNING', 'INFO'), expect_error=None):
    """Renders; checks the result is finite and that each `expect` substring was reported."""
    error = None
    try:
        img, seconds = testing.render(scene, directory, name)
    except RuntimeError as exc:       # an ERROR report makes the operator raise
        error = str(exc)
        img, seconds = None, 0.0
    messages = testing.last_messages()
    print(f"[{name}] {seconds:.2f} s, reports: {messages}" + (f", error: {error}" if error else ""))
    if expect_error is not None:
        check(error is not None and expect_error in error,
              f"{name}: expected an error containing {expect_error!r}, got {error!r}")
        return None
    check(error is None, f"{name}: the render failed: {error}")
    check(img.shape == (H, W, 4), f"{name}: image shape {img.shape}")
    check(np.isfinite(img).all(), f"{name}: NaN/Inf in the image")
    for text in expect:
        check(any(text in m for level, m in messages if level in levels),
              f"{name}: no report containing {text!r} in {messages}")
    stats = testing.addon().render.last_stats
    check(stats.get("samples_done") == SAMPLES, f"{name}: samples_done {stats}")
    check(stats.get("nonfinite_pixels") == 0, f"{name}: NaN/Inf in the core's image {stats}")
    return img


def set_auto_smooth(mesh, on):
    """Auto smooth at 30 degrees on or off: Mesh.use_auto_smooth before Blender 4.1, which
    removed it; since then the edges sharper than 30 degrees marked sharp (on) or none (off)."""
    if hasattr(mesh, "use_auto_smooth"):
        mesh.use_auto_smooth = on
    else:
        mesh.set_sharp_from_angle(angle=math.radians(30.0) if on else math.pi)
        mesh.update()                 # the method does not tag the mesh for the depsgraph


def main():
    testing.addon()
    d = testing.tempdir()
    world = np.array([0.2, 0.3, 0.4])

    # 1. Empty scene: only the world.
    scene = base_scene()
    img = render_case("empty", scene, d)
    check(np.allclose(img[:, :, :3], world, atol=2e-3),
          f"empty: not the world colour {img.mean((0, 1))}")
    check(np.allclose(img[:, :, 3], 1.0), "empty: alpha is not 1")

    # 1b. Empty scene, world without nodes (where Blender has them: 5.0 always uses the
    # world's nodes); film transparent.
    scene = base_scene(world=None)
    testing.set_world(scene, (0.5, 0.25, 0.125), use_nodes=False)
    from torrance.blender_versions import used_node_tree
    if used_node_tree(scene.world) is None:
        img = render_case("world_no_nodes", scene, d)
        check(np.allclose(img[:, :, :3], (0.5, 0.25, 0.125), atol=2e-3),
              f"world colour {img.mean((0, 1))}")
    scene.render.film_transparent = True
    img = render_case("transparent", scene, d)
    check(np.abs(img).max() < 1e-6, "transparent: the background is not RGBA 0")

    # 1c. No world at all: black.
    scene = base_scene(world=None)
    img = render_case("no_world", scene, d)
    check(np.abs(img[:, :, :3]).max() < 1e-6, "no world: not black")

    # 1d. World with a Shader to RGB (Eevee's): unsupported, reported.
    scene = base_scene()
    nt = scene.world.node_tree
    to_rgb = nt.nodes.new("ShaderNodeShaderToRGB")
    nt.links.new(to_rgb.outputs["Color"], nt.nodes["Background"].inputs["Color"])
    render_case("world_shader_to_rgb", scene, d, expect=["Shader to RGB"])

    # 2. A mesh without faces (vertices and edges only): skipped.
    scene = base_scene()
    me = bpy.data.meshes.new("Edges")
    me.from_pydata([(0, 0, 0), (1, 0, 0), (1, 1, 0)], [(0, 1), (1, 2)], [])
    ob = bpy.data.objects.new("Edges", me)
    scene.collection.objects.link(ob)
    empty_mesh = bpy.data.objects.new("NoGeometry", bpy.data.meshes.new("NoGeometry"))
    scene.collection.objects.link(empty_mesh)
    img = render_case("no_faces", scene, d)
    check(np.allclose(img[:, :, :3], world, atol=2e-3), "no_faces: something was rendered")

    # 3. An object without material, one with an empty slot, a material index past the slots.
    scene = base_scene()
    testing.add_sun(scene, strength=3.0)
    testing.sphere_object(scene, "NoMaterial", (-1.2, 0, 0.6), 0.6)
    ob = testing.sphere_object(scene, "EmptySlot", (1.2, 0, 0.6), 0.6)
    ob.data.materials.append(None)
    ob2 = testing.plane(scene, "Floor", 8.0, material=testing.principled("Floor"))
    ob2.data.polygons[0].material_index = 5          # Cycles clamps it to the last slot
    img = render_case("no_material", scene, d)
    check(img[:, :, :3].mean() > world.mean() * 0.5, "no_material: implausibly dark")

    # 4. A mesh with a NaN vertex (and one with an Inf vertex): its triangles are dropped.
    scene = base_scene()
    testing.add_sun(scene)
    ob = testing.sphere_object(scene, "NaNSphere", (0, 0, 0.6), 0.6,
                               testing.principled("Red", (0.8, 0.1, 0.1)))
    me = ob.data
    co = np.empty(len(me.vertices) * 3, dtype=np.float32)
    me.vertices.foreach_get("co", co)
    co[3 * 10] = math.nan
    co[3 * 40 + 1] = math.inf       # foreach_set keeps Inf (typing it in a field clamps it)
    co[3 * 70 + 2] = -3.0e38        # a finite but absurd coordinate counts as Inf
    me.vertices.foreach_set("co", co)
    me.update()
    me.calc_loop_triangles()
    tris = np.empty(len(me.loop_triangles) * 3, dtype=np.int32)
    me.loop_triangles.foreach_get("vertices", tris)
    expected = int(np.isin(tris.reshape(-1, 3), [10, 40, 70]).any(axis=1).sum())
    img = render_case("nan_vertex", scene, d, expect=["NaN/Inf vertex"])
    msg = [m for _, m in testing.last_messages() if "NaN/Inf vertex" in m][0]
    check(f"'NaNSphere': {expected} triangle(s)" in msg,
          f"nan_vertex: expected {expected} dropped triangles: {msg}")
    centre = img[H // 2 - 2:H // 2 + 2, W // 2 - 2:W // 2 + 2, :3].mean(axis=(0, 1))
    check(centre[0] > 2 * centre[2], f"nan_vertex: the red sphere is missing: {centre}")

    # 5. Unsupported nodes: a Principled Base Color from a Shader to RGB (Eevee's, not read by
    #    the shader graph); a Specular BSDF surface (Eevee's only);
    #    an Emission surface (supported); a material without output; a Mix Shader.
    scene = base_scene()
    testing.add_sun(scene)
    noise_mat = testing.principled("NoiseMat", (0.2, 0.6, 0.2))
    nt = noise_mat.node_tree
    to_rgb = nt.nodes.new("ShaderNodeShaderToRGB")
    nt.links.new(to_rgb.outputs["Color"], nt.nodes["Principled BSDF"].inputs["Base Color"])
    nt.links.new(to_rgb.outputs["Alpha"], nt.nodes["Principled BSDF"].inputs["Roughness"])
    specular_mat = bpy.data.materials.new("SpecularMat")
    specular_mat.use_nodes = True
    nt = specular_mat.node_tree
    nt.nodes.remove(nt.nodes["Principled BSDF"])
    specular = nt.nodes.new("ShaderNodeEeveeSpecular")
    nt.links.new(specular.outputs[0], nt.nodes["Material Output"].inputs["Surface"])
    emit_mat = bpy.data.materials.new("EmitMat")
    emit_mat.use_nodes = True
    nt = emit_mat.node_tree
    nt.nodes.remove(nt.nodes["Principled BSDF"])
    emit = nt.nodes.new("ShaderNodeEmission")
    emit.inputs["Color"].default_value = (1.0, 0.5, 0.25, 1.0)
    emit.inputs["Strength"].default_value = 2.0
    nt.links.new(emit.outputs[0], nt.nodes["Material Output"].inputs["Surface"])
    no_output = bpy.data.materials.new("NoOutputMat")
    no_output.use_nodes = True
    no_output.node_tree.nodes.remove(no_output.node_tree.nodes["Material Output"])
    mix_mat = bpy.data.materials.new("MixMat")
    mix_mat.use_nodes = True
    nt = mix_mat.node_tree
    mix = nt.nodes.new("ShaderNodeMixShader")
    nt.links.new(nt.nodes["Principled BSDF"].outputs[0], mix.inputs[1])
    nt.links.new(mix.outputs[0], nt.nodes["Material Output"].inputs["Surface"])
    for i, mat in enumerate((noise_mat, specular_mat, emit_mat, no_output, mix_mat)):
        testing.sphere_object(scene, mat.name + "Sphere", (-2.4 + 1.2 * i, 0, 0.5), 0.5, mat,
                              segments=16, rings=8)
    img = render_case("unsupported_nodes", scene, d, expect=[
        "'NoiseMat': input 'Base Color'", "Shader to RGB", "'NoiseMat': input 'Roughness'",
        "'SpecularMat': the surface shader", "Specular BSDF",
        "'NoOutputMat': no active Material Output", "'MixMat'", "Mix Shader"])
    messages = testing.last_messages()
    check(not any("EmitMat" in m for _, m in messages), "EmitMat must not be reported")
    check(sum("'NoiseMat': input 'Base Color'" in m for _, m in messages) == 1,
          "each material/socket must be reported once")
    # The emitter is visible: its pixels are at least its radiance (1, .5, .25) x 2.
    check(img[:, :, 0].max() >= 1.9, f"emission not visible: max R {img[:, :, 0].max()}")

    # 6. Spot and area lights (supported), object types, a negative-scale object, a text and
    #    a curve.
    scene = base_scene()
    testing.add_sun(scene)
    spot = bpy.data.lights.new("Spot", 'SPOT')
    scene.collection.objects.link(bpy.data.objects.new("Spot", spot))
    area = bpy.data.lights.new("Area", 'AREA')
    area_ob = bpy.data.objects.new("Area", area)
    scene.collection.objects.link(area_ob)
    # Sheared: turned 45 degrees under a parent scaled along Y, its X and Y axes are not
    # perpendicular (the export keeps the Y edge's part across X; the core takes rectangles only).
    squash = bpy.data.objects.new("Squash", None)
    squash.scale = (1.0, 3.0, 1.0)
    scene.collection.objects.link(squash)
    area_ob.parent = squash
    area_ob.rotation_euler = (0.3, 0.0, math.radians(45))
    area_ob.location = (0.5, -0.4, 2.5)
    ob = testing.sphere_object(scene, "Mirrored", (0, 0, 0.6), 0.6, testing.principled("M"))
    ob.scale = (-1, 1, 1)
    font = bpy.data.curves.new("Text", 'FONT')
    font.body = "T"
    tob = bpy.data.objects.new("Text", font)
    tob.location = (1.5, 0, 0.2)
    tob.rotation_euler = (math.radians(90), 0, 0)
    scene.collection.objects.link(tob)
    curve = bpy.data.curves.new("Curve", 'CURVE')
    curve.dimensions = '3D'
    curve.bevel_depth = 0.1
    spline = curve.splines.new('POLY')
    spline.points.add(1)
    spline.points[0].co = (-2, 0, 0.5, 1)
    spline.points[1].co = (-1.2, 0, 1.2, 1)
    scene.collection.objects.link(bpy.data.objects.new("Curve", curve))
    render_case("lights_and_types", scene, d)
    stats = testing.addon().render.last_stats
    check(sorted(stats["object_names"]) == ["Curve", "Mirrored", "Text"],
          f"expected 3 mesh objects (sphere, text, curve): {stats}")
    check(stats["lights"] == 3, f"expected 3 lights (sun, spot, area): {stats}")
    check(not any("light" in m.lower() for _, m in testing.last_messages()),
          f"spot and area lights must not be reported: {testing.last_messages()}")

    # 7. Hidden objects are not exported; collection instances are.
    scene = base_scene()
    hidden = testing.sphere_object(scene, "Hidden", (0, 0, 0.6), 0.6)
    hidden.hide_render = True
    coll = bpy.data.collections.new("Instanced")
    src = testing.sphere_object(scene, "Source", (0, 0, 0), 0.3, segments=8, rings=4)
    scene.collection.objects.unlink(src)
    coll.objects.link(src)
    for i in range(3):
        inst = bpy.data.objects.new(f"Instance{i}", None)
        inst.instance_type = 'COLLECTION'
        inst.instance_collection = coll
        inst.location = (i - 1.0, 0, 0.3)
        scene.collection.objects.link(inst)
    render_case("instances", scene, d)
    stats = testing.addon().render.last_stats
    check(stats["objects"] == 3, f"expected the 3 instances only: {stats}")

    # 7b. Particles instancing a cube from a plane whose own render is off (show_self).
    scene = base_scene()
    testing.add_sun(scene)
    cube = testing.mesh_object(scene, "ParticleCube",
                               [(x, y, z) for x in (-.1, .1) for y in (-.1, .1) for z in (-.1, .1)],
                               [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6),
                                (0, 2, 6, 4), (1, 5, 7, 3)])
    cube.location = (0, 0, -50)
    emitter = testing.plane(scene, "Emitter", 2.0, z=0.2)
    emitter.modifiers.new("Particles", 'PARTICLE_SYSTEM')
    pset = emitter.particle_systems[0].settings
    pset.count = 4
    pset.frame_start = pset.frame_end = 1
    pset.physics_type = 'NO'
    pset.render_type = 'OBJECT'
    pset.instance_object = cube
    pset.particle_size = 1.0
    emitter.show_instancer_for_render = False
    render_case("particles", scene, d)
    names = testing.addon().render.last_stats["object_names"]
    check(sorted(names) == ["ParticleCube"] * 5,
          f"expected the cube and its 4 particle instances, not the emitter: {names}")

    # 7c. Normals: an auto-smooth cube (30 deg) renders like a flat one; a mesh with smooth
    #     and flat faces, and one with custom split normals, render without trouble.
    scene = base_scene()
    testing.add_sun(scene, rotation=(math.radians(30), 0, math.radians(40)))
    verts = [(x, y, z) for x in (-.6, .6) for y in (-.6, .6) for z in (0, 1.2)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    cube = testing.mesh_object(scene, "Cube", verts, faces,
                               testing.principled("C", (0.6, 0.6, 0.6)))
    flat = render_case("flat_cube", scene, d)
    cube.data.polygons.foreach_set("use_smooth", [True] * 6)
    set_auto_smooth(cube.data, True)
    cube.data.update()
    auto = render_case("auto_smooth_cube", scene, d)
    diff = np.abs(auto - flat).max()
    print(f"[auto_smooth_cube] max |auto smooth - flat| = {diff:.2e}")
    check(diff < 1e-3 * max(1.0, flat.max()), "an auto-smooth cube must render like a flat one")
    set_auto_smooth(cube.data, False)
    smooth = render_case("smooth_cube", scene, d)
    check(np.abs(smooth - flat).max() > 1e-2, "a smooth-shaded cube must differ from a flat one")
    cube.data.polygons[0].use_smooth = False
    render_case("mixed_cube", scene, d)
    set_auto_smooth(cube.data, True)
    cube.data.normals_split_custom_set_from_vertices([(0.0, 0.0, 1.0)] * 8)
    render_case("custom_normals_cube", scene, d)

    # 8. Border render: a window of the frame, same pixels as the full render there.
    scene = base_scene()
    testing.add_sun(scene)
    testing.sphere_object(scene, "Ball", (0, 0, 0.6), 0.8, testing.principled("B", (0.7, 0.3, 0.2)))
    testing.plane(scene, "Floor", 8.0, material=testing.principled("F"))
    scene.torrance.samples = SAMPLES
    full = render_case("full_frame", scene, d)
    rd = scene.render
    rd.use_border = True
    rd.use_crop_to_border = False
    rd.border_min_x, rd.border_max_x = 0.25, 0.75
    rd.border_min_y, rd.border_max_y = 0.1, 0.6
    part = render_case("border", scene, d)
    x0, x1 = int(0.25 * W), int(0.75 * W)
    y0, y1 = int(0.1 * H), int(0.6 * H)            # from the bottom
    top0, top1 = H - y1, H - y0                    # rows counted from the top
    inside = part[top0:top1, x0:x1, :3]
    ref = full[top0:top1, x0:x1, :3]
    outside = part.copy()
    outside[top0:top1, x0:x1] = 0
    diff = abs(inside.mean() - ref.mean()) / max(ref.mean(), 1e-6)
    print(f"[border] window mean {inside.mean():.4f} vs full frame {ref.mean():.4f} "
          f"(rel. diff {diff:.3f}); outside max {np.abs(outside).max():.4f}")
    check(diff < 0.1, "border: the window differs from the full frame")
    check(np.abs(outside).max() < 1e-6, "border: pixels outside the border were written")
    rd.use_border = False

    # 9. No camera: a clear error, no crash.
    scene = base_scene()
    bpy.data.objects.remove(scene.camera)
    render_case("no_camera", scene, d, expect_error="camera")


testing.run(main)
