# SPDX-License-Identifier: Apache-2.0
"""Displacement and Vector Displacement render as Cycles 3.4 renders them, and a Material
Output's Displacement as Cycles' default method, Bump Only.

Patches of the grid (torrance_tools.shader_graphs), each its own object with a turned, unevenly
scaled matrix (shader_graphs.object_matrix) and turned UVs:
- the nodes' offsets through an Emission shader (0.5 v + 0.5): Displacement in Object and World
  space, Vector Displacement in Tangent, Object and World space;
- an Emission shader showing Geometry > Normal of a material whose output has a Displacement
  (the surface's normal is the displacement's bump: no lighting noise);
- lit materials whose output has a Displacement: a metallic Principled BSDF (Displacement in
  World and Object space, Vector Displacement in Tangent space), a Mix Shader of two Glossy
  BSDFs, a dielectric Principled and a Diffuse BSDF (diffuse light: Cycles smooths it on bumped
  surfaces by its bump shadowing term against sd->N, which the displacement's bump replaces, so
  a closure whose Normal is unlinked gets no term; Torrance compares with the displaced normal
  too, ShaderOutputs::surface_normal; against the undisplaced one it rendered the dielectric
  1.4 % dark: 0.6191 against 0.6278 in red).
Cycles renders the output's Displacement as bump: the offset's component along the normal at
the hit and at the hit moved by the ray differentials, as heights of a Bump node (Strength 1,
Distance 1) whose normal becomes the shading normal.

Cycles 4.3+ takes the bump's heights at the hit moved by 0.1 of the ray differentials (the Bump
node's default Filter Width), earlier Cycles by the whole differentials.

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. Deliberate faults must fail: the nodes read in World space, Displacement's Scale
halved, the output's Displacement ignored, the Filter Width the other Cycles takes. A material
whose method is Displacement Only is reported (true displacement is not done) and rendered as
bump.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_shader_displacement_agreement.py
"""

from torrance_tools import testing
from torrance_tools.shader_graphs import (DictAttr, Graph, agree_on_patches, object_matrix,
                                          read_with, shown, turned_uvs)


def _setup(obj):
    turned_uvs(obj)
    object_matrix(obj)


def _noise(g, scale=4.0, output="Fac"):
    n = g.node("ShaderNodeTexNoise")
    n.inputs["Scale"].default_value = scale
    n.inputs["Detail"].default_value = 2.0
    return n.outputs[output]


def _displacement(g, space, scale=1.0, midlevel=0.3):
    d = g.node("ShaderNodeDisplacement", space=space)
    d.inputs["Midlevel"].default_value = midlevel
    d.inputs["Scale"].default_value = scale
    g.link(_noise(g), d.inputs["Height"])
    return d.outputs["Displacement"]


def _vector_displacement(g, space, scale=1.0):
    d = g.node("ShaderNodeVectorDisplacement", space=space)
    d.inputs["Midlevel"].default_value = 0.45
    d.inputs["Scale"].default_value = scale
    g.link(_noise(g, 3.0, "Color"), d.inputs["Vector"])
    return d.outputs["Displacement"]


def displacement_object(g):
    return shown(g, _displacement(g, 'OBJECT'))


def displacement_world(g):
    return shown(g, _displacement(g, 'WORLD', 1.5))


def vector_tangent(g):
    return shown(g, _vector_displacement(g, 'TANGENT', 1.5))


def vector_object(g):
    return shown(g, _vector_displacement(g, 'OBJECT'))


def vector_world(g):
    return shown(g, _vector_displacement(g, 'WORLD', 1.5))


def _to_output(g, displacement):
    g.link(displacement, g.nodes["Material Output"].inputs["Displacement"])


def displaced_normal(g):
    """Geometry > Normal of a surface whose output has a Displacement."""
    _to_output(g, _displacement(g, 'WORLD', 0.15))
    return shown(g, g.node("ShaderNodeNewGeometry").outputs["Normal"])


def _lit(name, surface="ShaderNodeBsdfPrincipled", metallic=1.0):
    g = Graph(name, surface)
    if "Base Color" in g.shader.inputs:
        g.shader.inputs["Base Color"].default_value = (0.7, 0.6, 0.5, 1.0)
        g.shader.inputs["Roughness"].default_value = 0.4
        g.shader.inputs["Metallic"].default_value = metallic
    return g


def lit_world():
    g = _lit("lit_world")
    _to_output(g, _displacement(g, 'WORLD', 0.12))
    return g.mat


def lit_object():
    g = _lit("lit_object")
    _to_output(g, _displacement(g, 'OBJECT', 0.1))
    return g.mat


def lit_vector_tangent():
    g = _lit("lit_vector_tangent")
    _to_output(g, _vector_displacement(g, 'TANGENT', 0.15))
    return g.mat


def lit_dielectric():
    g = _lit("lit_dielectric", metallic=0.0)
    _to_output(g, _displacement(g, 'WORLD', 0.12))
    return g.mat


def lit_diffuse():
    g = _lit("lit_diffuse", "ShaderNodeBsdfDiffuse")
    g.shader.inputs["Color"].default_value = (0.7, 0.6, 0.5, 1.0)
    _to_output(g, _displacement(g, 'OBJECT', 0.1))
    return g.mat


def lit_mixed():
    """A Mix Shader of two Glossy BSDFs (GGX, roughness 0.2 and 0.5)."""
    g = _lit("lit_mixed", "ShaderNodeMixShader")
    g.shader.inputs["Fac"].default_value = 0.4
    for k, roughness in ((1, 0.2), (2, 0.5)):
        c = g.node("ShaderNodeBsdfGlossy", distribution='GGX')
        c.inputs["Color"].default_value = (0.7, 0.6, 0.5, 1.0)
        c.inputs["Roughness"].default_value = roughness
        g.link(c.outputs[0], g.shader.inputs[k])
    _to_output(g, _displacement(g, 'WORLD', 0.12))
    return g.mat


MAKERS = (displacement_object, displacement_world, vector_tangent, vector_object, vector_world,
          displaced_normal)
LIT = (lit_world, lit_object, lit_vector_tangent, lit_mixed)
DIFFUSE = (lit_dielectric, lit_diffuse)     # checked on their own: the term is a few per cent
for _make in (*MAKERS, *LIT, *DIFFUSE):
    _make.setup = _setup


def check_method_report():
    """A material whose method is Displacement Only: read with a warning, rendered as bump."""
    from torrance.materials import MaterialReader
    from torrance.reporting import Reporter
    from torrance.shader_graph.node_versions import displacement_owner
    testing.check(displacement_owner(lit_world()).displacement_method == 'BUMP',
                  "Cycles' default displacement method is not Bump Only")
    mat = lit_world()
    displacement_owner(mat).displacement_method = 'DISPLACEMENT'
    messages = []
    reporter = Reporter(None)
    reporter.report = lambda level, text: messages.append((level, text))
    args = MaterialReader(reporter, DryTextures()).read(mat)
    testing.check(args.get('normal_register', -1) >= 0, "the displacement is not read as bump")
    testing.check(any("true displacement" in text for _level, text in messages),
                  f"Displacement Only is not reported: {messages}")
    print(f"  Displacement Only reported: {messages}")


class DryTextures:
    def texture(self, image, interpolation="Linear"):
        return None


def displacement_ignored(original):
    return lambda g, displacement: g.builder.emit("Geometry", 'vector', mode=1)


def without_surface_normal(original):
    """A fault: the closure's program no longer says the displaced surface normal (the shadow
    terminator's smoothing then compares with the undisplaced one)."""
    def read(self, *args):
        out = original(self, *args)
        if isinstance(out, dict):
            out.pop('surface_normal_register', None)
            out.get('normal', {}).pop('surface_normal_register', None)
        return out
    return read


def other_filter_width(original):
    """The Filter Width of the other Cycles: 0.1 (4.3+'s default) where it is 1, else 1."""
    return lambda node=None: 0.1 if original(node) == 1.0 else 1.0


def main():
    testing.addon()
    import torrance.normal_inputs as normal_inputs
    from torrance.shader_graph import bump
    from torrance.shader_graph.registry import READERS
    check_method_report()
    readers = DictAttr(READERS)
    faults = (
        ("Displacement read in World space", readers, 'ShaderNodeDisplacement',
         read_with(space='WORLD')),
        ("Vector Displacement read in World space", readers, 'ShaderNodeVectorDisplacement',
         read_with(space='WORLD')),
        ("Displacement's Scale halved", readers, 'ShaderNodeDisplacement',
         read_with(lambda node: {"socket:Scale": node.inputs["Scale"].default_value / 2})),
        ("the output's Displacement ignored", normal_inputs, 'bump_from_displacement',
         displacement_ignored),
        ("the bump's Filter Width as the other Cycles takes it (before 4.3: 1, 4.3+: 0.1)",
         bump, 'bump_filter_width', other_filter_width))
    # Re-rendered every run: the faults within a few times the bounds. The Scale halved and the
    # Displacement ignored (3.4: ratios 0.9415 and 0.9150 against 0.9958..1.0042) render with
    # TORRANCE_ALL_FAULTS=1 only (testing.fault_renders).
    far = ("Displacement's Scale halved", "the output's Displacement ignored")
    agree_on_patches(MAKERS, lit=LIT, what="Displacement, Vector Displacement and bump from "
                     "the output's Displacement", samples=128,
                     faults=testing.faults_to_render(
                         faults, [f[0] for f in faults if f[0] not in far]))
    from torrance.materials import MaterialReader
    from torrance.mixtures import ShaderTreeReader
    agree_on_patches((), lit=DIFFUSE, what="diffuse light on displaced surfaces", samples=128,
                     faults=(("a Principled's displaced normal not said", MaterialReader,
                              '_with_program', without_surface_normal),
                             ("a Diffuse BSDF's displaced normal not said", ShaderTreeReader,
                              'read', without_surface_normal)))


testing.run(main)
