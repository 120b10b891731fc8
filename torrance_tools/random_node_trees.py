# SPDX-License-Identifier: Apache-2.0
"""Random shader node trees for the shader graph's fuzz test (blender_tests/
test_shader_graph_fuzz.py): hypothesis strategies of tree *plans* (plain tuples, which hypothesis
prints and shrinks) and build_material, which makes a plan a Blender material.

A plan's nodes are drawn from a catalogue read off Blender's RNA (catalogue(kinds)): every enum
setting from its enum items, booleans, numbers within their hard range, names of attributes,
random socket values with extremes (0, +-1e30, +-1e-38, ...), colour ramp stops and curve points.
Links go from an earlier node to a later one, between any value sockets (float, colour and vector
in every combination: Blender's implicit conversions), some through reroutes, some from a BSDF's
Shader output (a link Blender draws red); nodes may be muted; node groups are nested plans whose
Group Input feeds their nodes. The material: a Mix Shader of a Principled BSDF and an Emission,
with TARGETS (Base Color, Roughness, Metallic, Emission, the Mix's Fac) fed by the plan's outputs.
"""

from dataclasses import dataclass

import bpy
from hypothesis import strategies as st

from torrance_tools.shader_graphs import Graph

VALUE_SOCKETS = ('VALUE', 'INT', 'BOOLEAN', 'RGBA', 'VECTOR')
INTERFACE_SOCKET = {'VALUE': 'NodeSocketFloat', 'RGBA': 'NodeSocketColor',
                    'VECTOR': 'NodeSocketVector'}
# (node, input) pairs the plan's outputs feed, in order.
TARGETS = (("Principled", "Base Color"), ("Principled", "Roughness"),
           ("Principled", "Metallic"), ("Principled", "Emission"), ("Mix", "Fac"))
NAMES = ('', 'Col', 'UVMap', 'absent')        # attribute, colour layer and UV map names
EXTREMES = (0.0, -0.0, 1.0, -1.0, 0.5, 2.0, 1e30, -1e30, 1e-38, -1e-38, 1e6, -1e6, 1e20)
_SKIPPED = {"mute", "hide", "select", "show_options", "show_preview", "show_texture",
            "use_custom_color", "name", "label", "location", "width", "width_hidden", "height",
            "color", "parent", "projection_blend"}
SHADER_SOURCE = -2          # a link's source: a Diffuse BSDF's Shader output
GROUP_INPUT = -1            # a link's source inside a group: its Group Input node


@dataclass(frozen=True)
class NodeType:
    """What a node type offers to vary: settings (name, strategy) and its inputs' count."""
    kind: str
    settings: tuple
    inputs: int


def _setting_strategy(prop):
    if prop.type == 'ENUM':
        return st.sampled_from([item.identifier for item in prop.enum_items])
    if prop.type == 'BOOLEAN':
        return st.booleans()
    if prop.type == 'INT':
        lo, hi = max(prop.hard_min, -1000), min(prop.hard_max, 1000)
        return st.one_of(st.sampled_from((lo, hi)), st.integers(lo, hi))
    if prop.type == 'FLOAT':
        lo, hi = max(prop.hard_min, -1e6), min(prop.hard_max, 1e6)
        number = st.one_of(st.sampled_from((lo, hi)), st.floats(lo, hi, width=32))
        n = prop.array_length          # a vector setting (the Sky Texture's Sun Direction)
        return st.tuples(*[number] * n) if n > 0 else number
    if prop.type == 'STRING':
        return st.sampled_from(NAMES)
    return None


def catalogue(kinds):
    """{kind: NodeType} of the shader node types `kinds` this Blender has (the registry reads
    newer ones too, e.g. 4.3's Gabor Texture), read from a scratch node of each."""
    tree = bpy.data.node_groups.new("catalogue scratch", 'ShaderNodeTree')
    try:
        types = {}
        for kind in sorted(k for k in kinds if hasattr(bpy.types, k)):
            node = tree.nodes.new(kind)
            settings = []
            for prop in node.bl_rna.properties:
                if prop.is_readonly or prop.identifier in _SKIPPED or \
                        prop.identifier.startswith("bl_") or getattr(prop, "is_enum_flag", False):
                    continue
                strategy = _setting_strategy(prop)
                if strategy is not None:
                    settings.append((prop.identifier, strategy))
            types[kind] = NodeType(kind, tuple(settings), len(node.inputs))
        return types
    finally:
        bpy.data.node_groups.remove(tree)


floats = st.one_of(st.sampled_from(EXTREMES), st.floats(-10.0, 10.0, width=32))
socket_values = st.tuples(floats, floats, floats, floats)
unit = st.floats(0.0, 1.0, width=32)
ramps = st.tuples(st.sampled_from(('EASE', 'CARDINAL', 'LINEAR', 'B_SPLINE', 'CONSTANT')),
                  st.sampled_from(('RGB', 'HSV', 'HSL')),
                  st.lists(st.tuples(unit, socket_values), max_size=3).map(tuple))
curve_points = st.lists(st.tuples(st.integers(0, 3), st.floats(-2, 2, width=32),
                                  st.floats(-2, 2, width=32)), max_size=3).map(tuple)
# The functions given to .map() are named: Hypothesis 6.67 (Debian 12's) reads a lambda's source
# again at every draw (record_call), which took a fifth of the fuzz test's time.


def _ramp_extra(ramp):
    return ("ramp", ramp)


def _curves_extra(curves):
    return ("curves", curves)


extras = st.one_of(st.none(), ramps.map(_ramp_extra),
                   st.tuples(st.sampled_from(('EXTRAPOLATED', 'HORIZONTAL')),
                             curve_points).map(_curves_extra))


@st.composite
def node_plans(draw, types, depth):
    """(kind, settings, socket values, muted, extra) or, for a group node, ("GROUP", a tree plan,
    socket values, muted, None)."""
    if depth > 0 and draw(st.integers(0, 5)) == 0:
        sub = draw(tree_plans(types, depth - 1, interface=True))
        return ("GROUP", sub, draw(st.lists(socket_values, max_size=len(sub[0])).map(tuple)),
                draw(st.booleans()), None)
    t = types[draw(st.sampled_from(sorted(types)))]
    chosen = [(name, draw(s)) for name, s in t.settings if draw(st.integers(0, 2)) > 0]
    values = draw(st.lists(socket_values, max_size=t.inputs).map(tuple))
    return (t.kind, tuple(chosen), values, draw(st.integers(0, 9)) == 0, draw(extras))


@st.composite
def tree_plans(draw, types, depth=2, interface=False, max_nodes=8, sources=()):
    """(interface inputs' kinds, nodes, links, outputs): links (source, output choice, node,
    input choice, reroutes) from an earlier node (or GROUP_INPUT / SHADER_SOURCE) to a later one;
    outputs (node, output choice, kind) feed a group's outputs or, at the top, TARGETS (None:
    left unlinked). sources: node types (of `types`) the first node is drawn from, when given
    (nodes reading the hit, so that the ops after them run in the core, not folded)."""
    inputs = tuple(draw(st.lists(st.sampled_from(sorted(INTERFACE_SOCKET)), max_size=3)))
    nodes = tuple(draw(st.lists(node_plans(types, depth), min_size=1 if interface else 2,
                                max_size=max_nodes)))
    if sources:
        nodes = (draw(node_plans({k: types[k] for k in sources}, 0)), *nodes)
    first = GROUP_INPUT if interface and inputs else 0
    links = []
    for target in range(len(nodes)):      # each node's inputs: mostly from the nodes before it
        for _ in range(draw(st.sampled_from((0, 1, 1, 2, 3)))):
            if draw(st.integers(0, 19)) == 0:
                source = SHADER_SOURCE
            elif target > first:
                source = target - 1 - draw(st.integers(0, target - 1 - first))
            else:
                continue
            links.append((source, draw(st.integers(0, 8)), target, draw(st.integers(0, 11)),
                          draw(st.sampled_from((0, 0, 0, 1, 2)))))
    count = draw(st.integers(1, 3)) if interface else len(TARGETS)
    last = len(nodes) - 1
    def back_from_last(k):
        return last - k

    fed = st.tuples(st.integers(0, last).map(back_from_last), st.integers(0, 8),
                    st.sampled_from(sorted(INTERFACE_SOCKET)))
    outputs = tuple(draw(fed if interface else st.one_of(st.none(), fed)) for _ in range(count))
    return inputs, nodes, tuple(links), outputs


def _set_value(socket, value):
    if not hasattr(socket, "default_value"):
        return
    if socket.type == 'VALUE':
        socket.default_value = value[0]
    elif socket.type == 'INT':
        socket.default_value = int(max(min(value[0], 2 ** 31 - 1), -2 ** 31))
    elif socket.type == 'BOOLEAN':
        socket.default_value = value[0] > 0.5
    elif socket.type in ('RGBA', 'VECTOR'):
        socket.default_value = value[:len(socket.default_value)]


def _set_extra(node, extra):
    what, data = extra
    if what == "ramp" and node.bl_idname == 'ShaderNodeValToRGB':
        interpolation, mode, stops = data
        ramp = node.color_ramp
        ramp.interpolation, ramp.color_mode = interpolation, mode
        for position, color in stops:
            ramp.elements.new(position).color = color
    elif what == "curves" and hasattr(node, "mapping"):
        extend, points = data
        node.mapping.extend = extend
        curves = node.mapping.curves
        for curve, x, y in points:
            curves[curve % len(curves)].points.new(x, y)
        node.mapping.update()


def _pick(sockets, choice, kinds=VALUE_SOCKETS):
    usable = [s for s in sockets if s.enabled and s.type in kinds]
    return usable[choice % len(usable)] if usable else None


class _Builder:
    """Makes plans into node trees (and node groups) with one image for Image and Environment
    Texture nodes."""

    def __init__(self, image, name):
        self.image, self.name, self.groups = image, name, []

    def node(self, tree, plan):
        kind, settings, values, muted, extra = plan
        if kind == "GROUP":
            node = tree.nodes.new('ShaderNodeGroup')
            node.node_tree = self.group(settings)
        else:
            node = tree.nodes.new(kind)
            for name, value in settings:
                setattr(node, name, value)
            if kind in ('ShaderNodeTexImage', 'ShaderNodeTexEnvironment'):
                node.image = self.image
            if extra is not None:
                _set_extra(node, extra)
        for socket, value in zip(node.inputs, values, strict=False):
            _set_value(socket, value)
        node.mute = muted
        return node

    def tree(self, tree, plan, group_input=None):
        """The plan's nodes and links in `tree`: the nodes made."""
        _inputs, node_plans_, links, _outputs = plan
        made = [self.node(tree, p) for p in node_plans_]
        for source, out_choice, target, in_choice, reroutes in links:
            if source == SHADER_SOURCE:
                out = tree.nodes.new('ShaderNodeBsdfDiffuse').outputs[0]
            else:
                out = _pick((group_input if source == GROUP_INPUT else made[source]).outputs,
                            out_choice)
            into = _pick(made[target].inputs, in_choice)
            if out is None or into is None:
                continue
            for _ in range(reroutes):
                reroute = tree.nodes.new('NodeReroute')
                tree.links.new(out, reroute.inputs[0])
                out = reroute.outputs[0]
            tree.links.new(out, into)
        return made

    def group(self, plan):
        inputs, _nodes, _links, outputs = plan
        group = bpy.data.node_groups.new(f"{self.name} group {len(self.groups)}",
                                         'ShaderNodeTree')
        self.groups.append(group)
        for k, kind in enumerate(inputs):
            group.inputs.new(INTERFACE_SOCKET[kind], f"In {k}")
        for k, (_node, _choice, kind) in enumerate(outputs):
            group.outputs.new(INTERFACE_SOCKET[kind], f"Out {k}")
        entry = group.nodes.new('NodeGroupInput')
        exit_ = group.nodes.new('NodeGroupOutput')
        made = self.tree(group, plan, entry)
        for k, (node, choice, _kind) in enumerate(outputs):
            out = _pick(made[node].outputs, choice)
            if out is not None:
                group.links.new(out, exit_.inputs[k])
        return group


def build_material(plan, image, name="Fuzz"):
    """(material, its node groups, the TARGETS' sockets) of a top-level tree plan."""
    g = Graph(name, surface="ShaderNodeMixShader")
    shaders = {"Principled": g.node("ShaderNodeBsdfPrincipled"), "Mix": g.shader}
    g.link(shaders["Principled"].outputs[0], g.shader.inputs[1])
    g.link(g.node("ShaderNodeEmission").outputs[0], g.shader.inputs[2])
    builder = _Builder(image, name)
    made = builder.tree(g.mat.node_tree, plan)
    targets = [shaders[node].inputs[socket] for node, socket in TARGETS]
    for target, fed in zip(targets, plan[3], strict=True):
        out = _pick(made[fed[0]].outputs, fed[1]) if fed is not None else None
        if out is not None:
            g.link(out, target)
    return g.mat, builder.groups, targets


def remove_material(mat, groups):
    bpy.data.materials.remove(mat)
    for group in groups:
        bpy.data.node_groups.remove(group)
