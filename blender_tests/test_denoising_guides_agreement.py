# SPDX-License-Identifier: Apache-2.0
"""The Denoising Data passes (View Layer > Passes > Data > Denoising Data) as Cycles writes them.

Cycles' Denoising Albedo and Normal follow the path through smooth mirrors and glass (closures
with alpha_x alpha_y <= 0.075^2), multiplying the albedo by theirs, to the first surface whose
closures are at least a quarter rough, and write there its rough closures' albedo and their
normal in camera space; a path that escapes writes the world's colour as albedo and no normal.
The scene has each case: a red Diffuse sphere and a Diffuse floor and wall seen directly, a
smooth mirror (Glossy, roughness 0) and a smooth Glass sphere (roughness 0, IOR 1.45) showing
them, a rough gold metal sphere (Glossy, roughness 0.5: rough, it stops the path), the
world above the wall, and two partly transparent sheets: a leaf (Mix of 60 % Transparent and 40 %
Diffuse) and a veil (Principled Alpha 0.3). Cycles counts the Transparent closure among the
surface's closures (3.x/4.x: a singular one; 5.3: always carried through) and takes it by its
sample weight; Torrance passes a sheet before shading it, with probability 1 - opacity.
Checks, Cycles seed 0 the reference and seed 1 the bounds
(torrance_tools.render_passes), Torrance seeds 2 and 3: Denoising Albedo, Normal and Depth
agree within Cycles' own noise (the Normal on the signed block metric, bounded by Cycles' own
noise alone: its negative blocks count). Faults that must fail: the albedo and normal guides
swapped (here, on Torrance's images), in Blender 5.3 the features as Cycles 3.x/4.x write them
(here: the normal seen in the mirror not weighed by the mirror's albedo), and the features written
at the first surface whatever its roughness (albedo through glass and mirrors dropped; in the
core, by hand: commit message).

Cycles 5.3 blends the features (film/denoising_features.h): a closure diffuse-like by its alpha's
smoothstep, a surface writing its share of them and passing the rest on, the normal weighed by
the feature throughput, a glass's albedo 1 at every angle.

A second scene does the same with Principled BSDFs (v1's closures in Blender 3.x, v2's, as
Cycles 4.x makes them, in 4.x and 5.x): a rough plastic, a rough F82 metal, a coated and a
sheen-covered base, a smooth glass sphere and a smooth metal mirror showing them, on a rough
Principled floor (Multiscatter GGX, the node's default, from Blender 4.x on). A fault that must
fail there, in the core by hand: Principled v2's albedo taken from v1's closures (commit message).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_denoising_guides_agreement.py
"""

import bpy

from torrance_tools import testing
from torrance_tools.render_passes import (cycles_passes_of, pass_bounds, pass_failures,
                                          rgb, torrance_passes, torrance_passes_with_fault)
from torrance_tools.scene import node_material
from torrance_tools.scene import principled as make_principled
from torrance_tools.testing import check

W, H, SAMPLES, BOUNCES = 96, 72, 64, 8
# Blender 5.x's Cycles writes Denoising Depth otherwise (the background at the far clip, the
# near clip added; issue 39's Blender 5 guide options, not done): Albedo and Normal only there.
COMPARED = ("Denoising Albedo", "Denoising Normal") + (
    ("Denoising Depth",) if bpy.app.version < (5, 0, 0) else ())


def bsdf(name, kind, color, roughness=0.0, ior=None):
    """A material of one BSDF node (Diffuse, Glossy or Glass; GGX) at the Surface."""
    mat, nodes, links, out = node_material(name)
    kinds = {"diffuse": ("ShaderNodeBsdfDiffuse",),
             "glossy": ("ShaderNodeBsdfGlossy", "ShaderNodeBsdfAnisotropic"),
             "glass": ("ShaderNodeBsdfGlass",)}[kind]
    for idname in kinds:
        try:
            node = nodes.new(idname)
            break
        except RuntimeError:            # 4.x: the Glossy BSDF is the Anisotropic one
            continue
    if kind != "diffuse":
        node.distribution = 'GGX'
    node.inputs["Color"].default_value = (*color, 1.0)
    node.inputs["Roughness"].default_value = roughness
    if ior is not None:
        node.inputs["IOR"].default_value = ior
    links.new(node.outputs[0], out.inputs["Surface"])
    return mat


def principled_input(node, value, *names):
    """Sets the first of `names` the node has (Blender 3.x's and 4.x's names for an input)."""
    for name in names:
        if node.inputs.get(name) is not None:
            node.inputs[name].default_value = value
            return
    raise KeyError(f"none of {names} on {node.name}")


def principled(name, color, roughness, metallic=0.0, coat=0.0, sheen=0.0, transmission=0.0):
    """A Principled BSDF material (Multiscatter GGX from Blender 4.x on, GGX before)."""
    mat = make_principled(name, color, metallic, roughness,
                          distribution='MULTI_GGX' if bpy.app.version >= (4, 0, 0) else 'GGX')
    node = mat.node_tree.nodes["Principled BSDF"]
    principled_input(node, coat, "Coat Weight", "Clearcoat")
    principled_input(node, 0.03, "Coat Roughness", "Clearcoat Roughness")
    principled_input(node, sheen, "Sheen Weight", "Sheen")
    principled_input(node, transmission, "Transmission Weight", "Transmission")
    return mat


def build_principled(scene):
    testing.setup_render(scene, width=W, height=H)
    testing.add_camera(scene, location=(0.0, -6.0, 2.0), target=(0.0, 0.0, 0.6), lens=35.0)
    testing.plane(scene, "Floor", 8.0, material=principled("Floor", (0.6, 0.55, 0.5), 0.8))
    testing.mesh_object(scene, "Mirror", [(1.6, -0.6, 0.0), (2.6, 1.2, 0.0), (2.6, 1.2, 1.5),
                                          (1.6, -0.6, 1.5)], [(0, 1, 2, 3)],
                        principled("Mirror", (0.9, 0.9, 0.9), 0.02, metallic=1.0))
    for name, center, radius, mat in (
            ("Plastic", (-1.8, 0.4, 0.5), 0.5, principled("Plastic", (0.1, 0.3, 0.8), 0.5)),
            ("Metal", (-0.6, 0.9, 0.5), 0.5,
             principled("Metal", (0.95, 0.65, 0.35), 0.4, metallic=1.0)),
            ("Coated", (0.6, 0.9, 0.45), 0.45,
             principled("Coated", (0.7, 0.1, 0.05), 0.5, coat=1.0)),
            ("Sheen", (1.2, -0.3, 0.35), 0.35,
             principled("Sheen", (0.05, 0.2, 0.05), 0.6, sheen=1.0)),
            ("Glass", (-0.4, -0.7, 0.55), 0.55,
             principled("Glass", (1.0, 1.0, 1.0), 0.0, transmission=1.0))):
        testing.sphere_object(scene, name, center, radius, mat)
    testing.add_sun(scene, strength=3.0)
    testing.set_world(scene, (0.3, 0.35, 0.45))
    scene.view_layers[0].cycles.denoising_store_passes = True


def build(scene):
    testing.setup_render(scene, width=W, height=H)
    testing.add_camera(scene, location=(0.0, -6.0, 2.0), target=(0.0, 0.0, 0.6), lens=35.0)
    testing.plane(scene, "Floor", 8.0, material=bsdf("Floor", "diffuse", (0.5, 0.45, 0.4)))
    testing.mesh_object(scene, "Wall", [(-4, 2.5, 0), (4, 2.5, 0), (4, 2.5, 1.6), (-4, 2.5, 1.6)],
                        [(0, 1, 2, 3)], bsdf("Wall", "diffuse", (0.2, 0.4, 0.7)))
    testing.mesh_object(scene, "Mirror", [(1.3, -0.8, 0.0), (2.5, 1.0, 0.0), (2.5, 1.0, 1.5),
                                          (1.3, -0.8, 1.5)], [(0, 1, 2, 3)],
                        bsdf("Mirror", "glossy", (0.9, 0.9, 0.9)))
    testing.sphere_object(scene, "Red", (-1.7, 0.2, 0.5), 0.5,
                          bsdf("Red", "diffuse", (0.7, 0.1, 0.05)))
    testing.sphere_object(scene, "Glass", (-0.3, -0.6, 0.6), 0.6,
                          bsdf("Glass", "glass", (1.0, 1.0, 1.0), ior=1.45))
    testing.sphere_object(scene, "Gold", (0.7, 0.9, 0.45), 0.45,
                          bsdf("Gold", "glossy", (0.9, 0.7, 0.3), roughness=0.5))
    testing.mesh_object(scene, "Leaf", [(-2.8, -0.9, 0.1), (-1.3, -0.9, 0.1), (-1.3, -0.9, 1.2),
                                        (-2.8, -0.9, 1.2)], [(0, 1, 2, 3)], leaf())
    testing.mesh_object(scene, "Veil", [(0.1, -0.3, 0.05), (1.2, -0.3, 0.05), (1.2, -0.3, 1.1),
                                        (0.1, -0.3, 1.1)], [(0, 1, 2, 3)], veil())
    testing.add_sun(scene, strength=3.0)
    testing.set_world(scene, (0.3, 0.35, 0.45))
    scene.view_layers[0].cycles.denoising_store_passes = True


def leaf():
    """A leaf of 60 % Transparent BSDF and 40 % Diffuse: mostly diffuse by its sample weights
    (Cycles 3.x/4.x write its features, 5.3 a part of its normal and carry the rest through)."""
    mat, nodes, links, out = node_material("Leaf")
    mix = nodes.new("ShaderNodeMixShader")
    mix.inputs["Fac"].default_value = 0.4
    links.new(nodes.new("ShaderNodeBsdfTransparent").outputs[0], mix.inputs[1])
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (0.8, 0.7, 0.3, 1.0)
    links.new(diffuse.outputs[0], mix.inputs[2])
    links.new(mix.outputs[0], out.inputs["Surface"])
    return mat


def veil():
    """A Principled BSDF of Alpha 0.3: mostly transparent (Cycles 3.x/4.x carry its features
    through it, and on along whichever closure the path takes)."""
    mat = principled("Veil", (0.2, 0.6, 0.15), 0.5)
    mat.node_tree.nodes["Principled BSDF"].inputs["Alpha"].default_value = 0.3
    return mat


def compared(img, name, _ref):
    return rgb(img[name])


def swapped(p):
    """Torrance's passes with the albedo and normal guides swapped (the first fault)."""
    out = dict(p)
    out["Denoising Albedo"], out["Denoising Normal"] = p["Denoising Normal"], p["Denoising Albedo"]
    return out


def agree(label, build, switched_features_fault=False):
    """Cycles' and Torrance's Denoising Data of the scene build() makes agree; swapped guides
    do not, nor (switched_features_fault, where Cycles blends them: 5.3) 3.x/4.x's switched
    features."""
    from torrance import blender_versions
    print(f"--- {label}")
    scene, d, ref, other = cycles_passes_of(build, SAMPLES, BOUNCES)
    check(all(name in ref for name in COMPARED), f"Cycles wrote no Denoising Data: {sorted(ref)}")
    bounds = pass_bounds(ref, other, COMPARED, compared, signed=("Denoising Normal",))
    ours = [torrance_passes(scene, d, SAMPLES, BOUNCES, seed) for seed in (2, 3)]
    check(not testing.last_messages(), f"unexpected reports: {testing.last_messages()}")
    check(all(name in p for p in ours for name in COMPARED),
          f"Torrance wrote no Denoising Data: {sorted(ours[0])}")
    bad = pass_failures(ours, ref, bounds, compared, "Torrance")
    check(not bad, "Torrance's Denoising Data disagree with Cycles': " + "; ".join(bad))
    caught = pass_failures([swapped(p) for p in ours], ref, bounds, compared, "Swapped")
    check(caught, "the guides swapped were not caught")
    if switched_features_fault and blender_versions.cycles_smooth_denoising_features():
        switched = torrance_passes_with_fault(scene, d, SAMPLES, BOUNCES, blender_versions,
                                              "cycles_smooth_denoising_features",
                                              lambda _blended: lambda: False)
        caught = pass_failures([switched], ref, bounds, compared, "Switched")
        check(caught, "3.x/4.x's switched features were not caught in a Blender that blends them")
    layer = scene.view_layers[0].cycles
    if hasattr(layer, "denoising_pass_follow_reflections"):     # Blender 5.x: not read, said so
        layer.denoising_pass_follow_reflections = False
        torrance_passes(scene, d, 1, BOUNCES, 2, name="options")
        layer.denoising_pass_follow_reflections = True
        said = [m for m in testing.last_messages() if "Follow Reflections" in m[1]]
        check(said, f"Follow Reflections off was not reported: {testing.last_messages()}")


def main():
    agree("BSDF nodes", build, switched_features_fault=True)
    agree("Principled BSDFs", build_principled)


testing.run(main)
