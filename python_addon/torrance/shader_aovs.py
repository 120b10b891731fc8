# SPDX-License-Identifier: Apache-2.0
"""Shader AOVs as Cycles renders them: the view layer's AOVs (View Layer > Shader AOV, each a
Value or a Color) are render passes under their own names, filled by the AOV Output nodes of the
materials (in node groups too, nested).

Each material's AOV Output nodes are compiled (shader_graph/) into one shader program of their
own, which the core runs at the surfaces a camera ray shades until one reaches the Alpha
Threshold (core extra_passes.h): a node adds its Color (a Color AOV) or its Value (a Value AOV)
unweighted to the sample, and the pass is the mean over the pixel's samples; 0 where no AOV
Output writes (the world, other materials). An AOV Output whose name is no valid AOV of the
view layer is ignored, as Cycles ignores it (reported as a note); AOV Outputs in the world's
node tree are not rendered (reported).
"""

from .blender_versions import used_node_tree
from .nodes import node_label
from .shader_graph.graph import GraphCompiler, Unsupported
from .shader_graph.program import ProgramBuilder, constant_key
from .shader_graph.registry import READERS

AOV_OUTPUT = 'ShaderNodeOutputAOV'
_MAX_GROUP_DEPTH = 64


def view_layer_aovs(view_layer):
    """[(name, 'VALUE' | 'COLOR')] of the view layer's valid AOVs, in order (Cycles' passes)."""
    return [(a.name, a.type) for a in getattr(view_layer, "aovs", ()) if a.is_valid]


def aov_name(node):
    """The AOV an AOV Output node writes (Blender 4.x: aov_name; 3.x: its own 'name')."""
    name = getattr(node, "aov_name", None)
    return node.name if name is None else name


def aov_nodes(tree, groups=(), depth=0):
    """(group nodes path, node) of each unmuted AOV Output node of tree and of the node groups
    used in it, nested (Cycles syncs every group node's nodes)."""
    for node in tree.nodes:
        if node.mute:
            continue
        if node.bl_idname == AOV_OUTPUT and getattr(node, "target", 'ALL') in ('ALL', 'CYCLES'):
            yield groups, node
        elif (node.bl_idname == 'ShaderNodeGroup' and node.node_tree is not None
              and depth < _MAX_GROUP_DEPTH):
            yield from aov_nodes(node.node_tree, groups + (node,), depth + 1)


def _register(builder, value):
    """A compiled input's register: a constant takes a slot of the program's constants."""
    if value.constant:
        return ('c', builder.constants.setdefault(constant_key(value.value),
                                                  len(builder.constants)))
    return ('r', value.register)


class AovPrograms:
    """Compiles the AOV Output nodes of each material for a view layer's AOVs and gives them to
    the core (Scene.set_aovs once, set_material_aovs per material)."""

    def __init__(self, tc_scene, aovs, reporter, textures, attributes):
        self.scene = tc_scene
        self.reporter = reporter
        self.textures = textures
        self.attributes = attributes
        self.index = {name: (i, kind) for i, (name, kind) in enumerate(aovs)}
        if aovs:
            tc_scene.set_aovs(aovs)

    def add(self, mat, material_index):
        """Compiles mat's AOV Output nodes for material `material_index`; returns what its
        meshes must export for them: (reads UVs, attribute keys), or None without AOVs."""
        tree = used_node_tree(mat) if mat is not None else None
        if tree is None or not self.index:
            self._note_ignored(mat, tree)
            return None
        builder = ProgramBuilder()
        compiler = GraphCompiler(builder, self.textures, READERS, self.attributes)
        writes = []
        for groups, node in aov_nodes(tree):
            name = aov_name(node)
            found = self.index.get(name)
            if found is None:
                self._ignored(mat, node, name)
                continue
            aov, kind = found
            socket = node.inputs["Color" if kind == 'COLOR' else "Value"]
            mark = builder.mark()
            try:
                value = compiler.input_inside(groups, socket,
                                              'color' if kind == 'COLOR' else 'float')
            except Unsupported as exc:
                builder.rollback(mark)
                self.reporter.warning(f"Material '{mat.name}': {node_label(node)} (AOV "
                                      f"'{name}'): {exc}; it writes its socket's own value")
                value = compiler.default(socket, 'color' if kind == 'COLOR' else 'float')
            writes.append((aov, _register(builder, value)))
        if not writes:
            return None
        program = builder.build()
        constants = len(builder.constants)      # computed values follow the constants
        self.scene.set_material_aovs(
            material_index, self.scene.add_shader_program(*program),
            [(aov, i if where == 'c' else constants + i) for aov, (where, i) in writes])
        return builder.uses_uvs(), self.attributes.keys_of(builder)

    def _note_ignored(self, mat, tree):
        if tree is None:
            return
        for _groups, node in aov_nodes(tree):
            self._ignored(mat, node, aov_name(node))

    def _ignored(self, mat, node, name):
        self.reporter.info(f"Material '{mat.name}': {node_label(node)} writes AOV '{name}', "
                           f"which the view layer does not have: ignored, as Cycles does")


def report_world_aovs(world, reporter):
    """AOV Output nodes in the world's node tree are not rendered: says so."""
    tree = used_node_tree(world) if world is not None else None
    if tree is not None and any(True for _ in aov_nodes(tree)):
        reporter.warning(f"World '{world.name}': AOV Output nodes of the world are not rendered "
                         f"by Torrance (their AOVs hold 0 on the background)")
