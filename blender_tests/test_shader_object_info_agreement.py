# SPDX-License-Identifier: Apache-2.0
"""Object Info renders as Cycles 3.4 renders it: Location, Color, Alpha, Object Index, Material
Index and Random; so do the Attribute node's Object attributes (a custom property of the object
or of its mesh, an RNA path) and View Layer attributes (a scene's custom property), each shown
through an Emission shader on patches of the grid (torrance_tools.shader_graphs), every patch
its own object (its own location, colour, pass index and name, hence random number), two of
them sharing one mesh.

These are world-space meshes (the final render's objects); instanced objects are
test_object_info_instances_agreement.py's.

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. Deliberate faults (the random number of another hash, the object colour's red
and blue swapped, attributes not searched on the object's data) must fail them.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_shader_object_info_agreement.py
"""

from torrance_tools import testing
from torrance_tools.shader_graphs import agree_on_patches

_SETTINGS = {}


def _info(g, output):
    return g.node("ShaderNodeObjectInfo").outputs[output]


def _object(color, index, location=None):
    def setup(obj):
        obj.color = color
        obj.pass_index = index
        if location is not None:
            obj.location = location
    return setup


def location(g):
    v = g.node("ShaderNodeVectorMath", operation='ABSOLUTE')
    s = g.node("ShaderNodeVectorMath", operation='SCALE')
    s.inputs["Scale"].default_value = 0.3
    g.link(_info(g, "Location"), v.inputs[0])
    g.link(v.outputs[0], s.inputs[0])
    return s.outputs[0]


location.setup = _object((0.2, 0.5, 0.9, 1.0), 1, (0.3, -0.2, 0.4))


def color(g):
    return _info(g, "Color")


color.setup = _object((0.9, 0.4, 0.1, 0.3), 2)


def alpha_and_index(g):
    comb = g.node("ShaderNodeCombineRGB")
    g.link(_info(g, "Alpha"), comb.inputs[0])
    g.link(g.math('MULTIPLY', _info(g, "Object Index"), value_b=0.1), comb.inputs[1])
    g.link(g.math('MULTIPLY', _info(g, "Material Index"), value_b=0.2), comb.inputs[2])
    g.mat.pass_index = 3
    return comb.outputs[0]


alpha_and_index.setup = _object((0.1, 0.2, 0.3, 0.6), 7)


def _random(g):
    comb = g.node("ShaderNodeCombineRGB")
    r = _info(g, "Random")
    g.link(r, comb.inputs[0])
    g.link(g.math('FRACT', g.math('MULTIPLY', r, value_b=7.0)), comb.inputs[1])
    g.link(g.math('FRACT', g.math('MULTIPLY', r, value_b=53.0)), comb.inputs[2])
    return comb.outputs[0]


def random_a(g):
    return _random(g)


def random_b(g):
    return _random(g)


def _share_mesh(obj):
    """The second Random patch's object takes the first's mesh (a flattened mesh shared by two
    objects), moved to its own place."""
    first = _SETTINGS.get("first")
    if first is None:
        _SETTINGS["first"] = obj
        return
    offset = [a - b for a, b in zip(obj.data.vertices[0].co, first.data.vertices[0].co,
                                     strict=True)]
    obj.data = first.data
    obj.location = offset


random_a.setup = _share_mesh
random_b.setup = _share_mesh

def _attribute(g, kind, name, output):
    return g.node("ShaderNodeAttribute", attribute_type=kind,
                  attribute_name=name).outputs[output]


def object_attribute(g):
    """An Object attribute: the object's custom property 'tint' (an array)."""
    return _attribute(g, 'OBJECT', "tint", "Color")


def _tinted(obj):
    obj["tint"] = (0.2, 0.7, 0.4)


object_attribute.setup = _tinted


def attribute_kinds(g):
    """R: an Object attribute found on the object's mesh ('gain', a number: its Fac), G: the
    RNA path 'color' (the object colour's alpha), B: a View Layer attribute found on the scene
    ('haze': its Fac)."""
    return g.combine(_attribute(g, 'OBJECT', "gain", "Fac"),
                     _attribute(g, 'OBJECT', "color", "Alpha"),
                     _attribute(g, 'VIEW_LAYER', "haze", "Fac"))


def _gain(obj):
    obj.data["gain"] = 0.6
    obj.color = (0.3, 0.9, 0.2, 0.45)
    obj.users_scene[0]["haze"] = 0.35


attribute_kinds.setup = _gain

MAKERS = (location, color, alpha_and_index, random_a, random_b, object_attribute,
          attribute_kinds)


def other_random(original):
    def info(obj, matrix, random_id=None):
        return original(obj, matrix, 12345)
    return info


def color_swapped(original):
    def info(obj, matrix, random_id=None):
        out = original(obj, matrix, random_id)
        c = out[('object_info', 'color')]
        out[('object_info', 'color')] = (c[2], c[1], c[0])
        return out
    return info


def data_not_searched(original):
    """A fault: an Object attribute looked up on the object alone, not on its data."""
    def lookup(obj, name, instancer=()):
        from torrance.export.object_attributes import rgba_attribute
        return rgba_attribute((*instancer, obj), name)
    return lookup


def main():
    testing.addon()
    import torrance.export.object_attributes as object_attributes
    import torrance.export.scene as export_scene
    agree_on_patches(
        MAKERS, what="Object Info and Object / View Layer attributes",
        faults=(("random of another hash", export_scene, "object_info", other_random),
                ("colour's red and blue swapped", export_scene, "object_info", color_swapped),
                ("attributes not searched on the object's data", object_attributes,
                 "object_attribute", data_not_searched)))


testing.run(main)
