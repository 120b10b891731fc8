# SPDX-License-Identifier: Apache-2.0
"""Compiles the node graph feeding a socket into a shader program (program.ProgramBuilder).

One registry (READERS, registry.py) maps a node's bl_idname to the function that turns one of its
outputs into a Value; this module walks links (through reroutes, muted nodes as Blender passes
them through, and node groups, nested) and applies Blender's implicit conversions between
floats, colours and vectors. A node no reader knows raises Unsupported, naming it, and the
caller keeps the socket's own value.
"""

from ..nodes import node_label
from .program import Value, constant

KIND_OF_SOCKET = {'VALUE': 'float', 'INT': 'float', 'BOOLEAN': 'float', 'RGBA': 'color',
                  'VECTOR': 'vector'}


class Unsupported(Exception):
    """A node or setting the shader graph can not compile (the message names it)."""


class GraphCompiler:
    """Compiles sockets of one material's node tree into one ProgramBuilder."""

    def __init__(self, builder, textures, readers, attributes=None, background=False,
                 volume_shader=False):
        self.builder = builder
        self.textures = textures          # texture_table.TextureTable
        self.readers = readers
        self.attributes = attributes if attributes is not None else AttributeIds()
        # A world's tree (emission_tree.py): no mesh, the hit's position is the ray's direction.
        self.background = background
        # A volume's tree (Cycles' volume shader, read as constants or as a program): nodes
        # Cycles reads only there (the Point Density in 4.x) give 0 elsewhere.
        self.volume_shader = volume_shader
        # A light's program: its light's matrix_world (4 x 4, rows), the object Texture
        # Coordinate > Normal and an IES Texture's Vector read (geometry.object_transform).
        self.object_matrix = None
        # A heterogeneous volume's program (volume_space.VolumeSpace): the Object and Generated
        # coordinates of points inside the volume instead of a mesh's attributes.
        self.volume = None
        self._cache = {}
        self._groups = []                 # the group nodes we are inside, outermost first

    # -- sockets ---------------------------------------------------------------------------------
    def input(self, socket, kind):
        """The Value of an input socket, converted to `kind`."""
        link = _active_link(socket)
        if link is None:
            return convert(self.builder, _default(socket), kind)
        return convert(self.builder, self.output(link.from_socket), kind)

    def input_inside(self, groups, socket, kind):
        """The Value of an input socket of a node inside the group nodes `groups` (outermost
        first), as `input` gives it there."""
        outer, self._groups = self._groups, list(groups)
        try:
            return self.input(socket, kind)
        finally:
            self._groups = outer

    def default(self, socket, kind):
        """An input socket's own value, converted to `kind`."""
        return convert(self.builder, _default(socket), kind)

    def attribute(self, key, kind='vector'):
        """A per-corner mesh attribute (export/mesh_attributes.py's keys), interpolated at the
        hit; the meshes of the material export it. In a world, as in Cycles' background: the
        Generated and Object coordinates are the direction, any other attribute 0."""
        if self.volume is not None:
            return self.volume.attribute(self, key, kind)
        if self.background:
            if key in (('generated',), ('object',)):
                return self.builder.emit("Geometry", 'vector', mode=0)
            return constant(kind, 0.0 if kind == 'float' else (0.0, 0.0, 0.0))
        return self.builder.emit("Attribute", kind, texture=self.attributes.request(key))

    def generated(self):
        """Texture Coordinate > Generated, what an unlinked texture Vector reads."""
        return self.attribute(('generated',))

    def output(self, socket):
        """The Value of an output socket (of its own kind)."""
        node = socket.node
        key = (tuple(g.as_pointer() for g in self._groups), node.as_pointer(), socket.identifier,
               self.builder.offset)
        if key not in self._cache:
            self._cache[key] = self._output(node, socket)
        return self._cache[key]

    def shared(self, node, part, make):
        """A Value that several outputs of `node` read (`part` names it; Raycast's hit record):
        make() gives it once per node, as `output` caches a socket's."""
        key = (tuple(g.as_pointer() for g in self._groups), node.as_pointer(), part,
               self.builder.offset)
        if key not in self._cache:
            self._cache[key] = make()
        return self._cache[key]

    def _output(self, node, socket):
        kind = KIND_OF_SOCKET.get(socket.type)
        if kind is None:
            raise Unsupported(f"{node_label(node)}'s output '{socket.name}' is a "
                              f"{socket.type.lower()}, not a value")
        if node.bl_idname == 'NodeReroute':
            return self.input(node.inputs[0], kind)
        if node.mute:
            for link in node.internal_links:
                if link.to_socket.identifier == socket.identifier:
                    return self.input(link.from_socket, kind)
            return convert(self.builder, _default(socket), kind)
        if node.bl_idname == 'ShaderNodeGroup':
            return self._group_output(node, socket, kind)
        if node.bl_idname == 'NodeGroupInput':
            return self._group_input(socket, kind)
        reader = self.readers.get(node.bl_idname)
        if reader is None:
            raise Unsupported(f"{node_label(node)} is not supported")
        return convert(self.builder, reader(self, node, socket), kind)

    def _group_output(self, group, socket, kind):
        tree = group.node_tree
        if tree is None:
            raise Unsupported(f"the group node {node_label(group)} has no node group")
        if len(self._groups) > 64:
            raise Unsupported(f"node groups nested more than 64 deep at {node_label(group)}")
        outputs = [n for n in tree.nodes if n.bl_idname == 'NodeGroupOutput']
        out = next((n for n in outputs if n.is_active_output), outputs[0] if outputs else None)
        target = by_identifier(out.inputs, socket.identifier) if out is not None else None
        if target is None:
            return convert(self.builder, _default(socket), kind)
        self._groups.append(group)
        try:
            return self.input(target, kind)
        finally:
            self._groups.pop()

    def _group_input(self, socket, kind):
        if not self._groups:
            raise Unsupported("a Group Input node outside a group")
        group = self._groups.pop()
        try:
            outer = by_identifier(group.inputs, socket.identifier)
            return (self.input(outer, kind) if outer is not None
                    else convert(self.builder, _default(socket), kind))
        finally:
            self._groups.append(group)


class AttributeIds:
    """The scene's attribute keys -> the ids shader programs and meshes name them by."""

    def __init__(self):
        self.ids = {}

    def request(self, key):
        return self.ids.setdefault(key, len(self.ids))

    def keys_of(self, builder):
        """The keys a program's Attribute instructions read (sorted by repr: keys mix strings
        and tuples)."""
        from .program import OPCODE
        op = OPCODE.get("Attribute")
        used = {row[3] for row in builder.code if row[0] == op}
        return tuple(sorted((k for k, i in self.ids.items() if i in used), key=repr))


def by_identifier(sockets, identifier):
    """The socket of an identifier, or None (`sockets.get` looks up names, which a group's or
    the Mix node's sockets may share)."""
    for s in sockets:
        if s.identifier == identifier:
            return s
    return None


def _active_link(socket):
    if not socket.is_linked:
        return None
    for link in socket.links:
        if link.is_valid and not link.is_muted:
            return link
    return None


def _default(socket):
    kind = KIND_OF_SOCKET.get(socket.type)
    if kind is None or not hasattr(socket, "default_value"):
        return constant('float', 0.0)
    v = socket.default_value
    if kind == 'float':
        return constant('float', float(v))
    return constant(kind, tuple(v))


def convert(builder, v, kind):
    """Blender's implicit conversion of a Value to `kind`: colour -> float is the luminance,
    vector -> float the average, float -> colour/vector the value in every component."""
    if v.kind == kind:
        return v
    if kind == 'float':
        return builder.emit("Luminance" if v.kind == 'color' else "Average", 'float', [v])
    if v.kind == 'float':
        return builder.emit("Combine", kind, [v, v, v]) if not v.constant else \
            constant(kind, (v.value[0],) * 3)
    if v.constant:                   # colour <-> vector: the same xyz
        return constant(kind, v.value[:3])
    return Value(kind, register=v.register)
