# SPDX-License-Identifier: Apache-2.0
"""Particle Info (Cycles' svm_node_particle_info): the particle that instanced the hit's object,
read from its instance constants (export/particles.py), Cycles' dummy particle (all 0, Random
that of particle 0) on anything else: objects, other instances, child particles, the world and
lights. No op of its own: the constants are attributes, as Object Info's."""

from ..nodes import node_label
from .graph import Unsupported
from .math_ops import MATH_OPS
from .program import constant

OPCODES = {}
FOLDS = {}

# Particle Info outputs -> the constant's name (mesh_attributes.PARTICLE_KEYS: 'particle_' + it).
_OUTPUTS = {"Index": 'index', "Random": 'random', "Age": 'age', "Lifetime": 'lifetime',
            "Location": 'location', "Size": 'size', "Velocity": 'velocity',
            "Angular Velocity": 'angular_velocity'}
_VECTORS = ('location', 'velocity', 'angular_velocity')


def _particle_info(g, node, socket):
    name = _OUTPUTS.get(socket.identifier)
    if name is None:
        raise Unsupported(f"{node_label(node)}'s output '{socket.name}' is not supported")
    value = g.attribute(('object_info', 'particle_' + name))
    if name in _VECTORS:
        return value
    value = g.builder.emit("Channel", 'float', [value], mode=0)
    if name == 'random':        # carried as the difference from the dummy particle's
        from ..export import particles      # (not at import: export imports the registry)
        value = g.builder.emit("Math", 'float', [value, constant('float', particles.DUMMY_RANDOM),
                                                 constant('float', 0.0)],
                               mode=MATH_OPS.index('ADD'))
    return value


READERS = {'ShaderNodeParticleInfo': _particle_info}
