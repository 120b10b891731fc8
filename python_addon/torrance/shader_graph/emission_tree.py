# SPDX-License-Identifier: Apache-2.0
"""A world's or a light's node tree compiled into one shader program: the radiance of its
Background and Emission closures (Color x Strength), through Mix and Add Shader nodes, as Cycles
sums an emitting shader's closures. A world's program the core runs per direction
(core/include/torrance/lights/emission_shader.h; background=True): the hit's position is the
direction, so Generated and Object coordinates and an Environment Texture's unlinked Vector
read it. A light's (background=False) the core runs at each point of the light a receiver
sees, or export/lights.py folds it to a factor.

Other closures add nothing to a world or a light in Cycles either (a BSDF has no light to
reflect there): they are reported and left out.
"""

from ..nodes import node_label, source_socket
from .color_ops import MIX_BLENDS
from .graph import GraphCompiler, Unsupported
from .math_ops import VECTOR_MATH_OPS
from .program import ProgramBuilder, constant

_EMITTERS = {'ShaderNodeBackground', 'ShaderNodeEmission'}
_MAX_DEPTH = 64
_BLACK = constant('color', (0.0, 0.0, 0.0))
_ZERO = constant('float', 0.0)


class EmissionTree:
    """Compiles the Surface of a World or Light Output into (ProgramBuilder, radiance Value).
    where: how messages name the owner ("World 'Sky'"); object_matrix: a light's matrix_world
    (4 x 4), what its object-space coordinates are relative to."""

    def __init__(self, where, textures, readers, reporter, background=True, object_matrix=None):
        self.builder = ProgramBuilder()
        self.values = GraphCompiler(self.builder, textures, readers, background=background)
        self.values.object_matrix = object_matrix
        self.where = where
        self.reporter = reporter

    def radiance(self, surface):
        """The radiance Value (a colour) of the closure tree feeding input socket `surface`."""
        return self._shader(source_socket(surface), 0)

    def _shader(self, output, depth):
        if output is None:
            return _BLACK
        node = output.node
        if depth > _MAX_DEPTH:
            self.reporter.warning(f"{self.where}: shader nodes nested deeper than {_MAX_DEPTH} "
                                  f"at {node_label(node)}; left out")
            return _BLACK
        if node.mute:
            passed = [link.from_socket for link in node.internal_links
                      if link.to_socket.identifier == output.identifier]
            return self._shader(source_socket(passed[0]) if passed else None, depth + 1)
        kind = node.bl_idname
        if kind in _EMITTERS:
            return self._emitter(node)
        if kind == 'ShaderNodeAddShader':
            a, b = (self._shader(source_socket(s), depth + 1) for s in node.inputs[:2])
            return self._vector_math("ADD", a, b)
        if kind == 'ShaderNodeMixShader':
            return self._mix(node, depth)
        self.reporter.warning(f"{self.where}: {node_label(node)} is not a light (Torrance, as "
                              f"Cycles, renders the Background and Emission closures here); "
                              f"left out")
        return _BLACK

    def _value(self, node, name, kind):
        """A closure input's Value; an input the graph can not compile keeps its own value."""
        socket = node.inputs[name]
        mark = self.builder.mark()
        try:
            return self.values.input(socket, kind)
        except Unsupported as exc:
            self.builder.rollback(mark)
            self.reporter.warning(f"{self.where}: input '{socket.name}' of {node_label(node)}: "
                                  f"{exc}; using the socket's own value")
            return self.values.default(socket, kind)

    def _emitter(self, node):
        color = self._value(node, "Color", 'color')
        strength = self._value(node, "Strength", 'float')
        return self.builder.emit("VectorMath", 'color', [color, _BLACK, _BLACK, strength],
                                 mode=VECTOR_MATH_OPS.index("SCALE"))

    def _mix(self, node, depth):
        fac = self._value(node, "Fac", 'float')
        a, b = (self._shader(source_socket(s), depth + 1) for s in node.inputs[1:3])
        # Cycles clamps a Mix Shader's factor to [0, 1] (svm_node_mix_closure).
        return self.builder.emit("MixColor", 'color', [fac, a, b], mode=MIX_BLENDS.index("MIX"),
                                 flags=2)

    def _vector_math(self, op, a, b):
        return self.builder.emit("VectorMath", 'color', [a, b, _BLACK, _ZERO],
                                 mode=VECTOR_MATH_OPS.index(op))
