# SPDX-License-Identifier: Apache-2.0
"""Particle Info's constants of the objects a particle system instances (Render As Object or
Collection), as Cycles syncs them (intern/cycles/blender/particles.cpp, sync_dupli_particle, and
svm/geometry.h, svm_node_particle_info), alike in Blender 3.4, 4.2 and 5.3:

* an instance whose depsgraph entry names a particle_system, and whose persistent_id[0] (the
  particle's number in that system) is one of the system's particles, shows that particle:
  Index its number, Age the scene's frame (frame_current_final) minus its birth time and
  Lifetime its lifetime, both in frames, Location, Size, Velocity and Angular Velocity the
  ParticleSystem.particles' own (world space, Blender's units); Random hash_uint2(index, 0)
  as a float in 0..1 (util/hash.h);
* everything else (an object, another kind of instance, a child particle: Cycles hands
  children no data) shows Cycles' dummy particle: all 0, Random hash_uint2(0, 0)'s float.

The shader programs read the constants as instance attributes (mesh_attributes.PARTICLE_KEYS),
0 where an object has none; so Random is carried as its difference from the dummy's, which
the shader graph adds back (shader_graph/particle_info.py)."""

import numpy as np

from .mesh_attributes import PARTICLE_KEYS, hash_uint2, uint_to_unit_float

NO_PARTICLE = -1       # a record of an instance that shows no particle (the dummy)

_FIELDS = (('birth_time', 1), ('lifetime', 1), ('size', 1), ('location', 3), ('velocity', 3),
           ('angular_velocity', 3))


def particle_random(indices):
    """float32 (N,): Particle Info's Random of particle numbers (hash_uint2_to_float(i, 0))."""
    return uint_to_unit_float(hash_uint2(np.asarray(indices, np.uint64)))


# Cycles' dummy particle's Random (particle number 0's too): 0.86031...
DUMMY_RANDOM = float(particle_random([0])[0])


def _key(name):
    key = ('object_info', 'particle_' + name)
    assert key in PARTICLE_KEYS
    return key


def _read_particles(psys):
    """{field: float32 (n,) or (n, 3)} of a particle system's particles (foreach_get)."""
    particles = psys.particles
    n = len(particles)
    out = {}
    for name, width in _FIELDS:
        values = np.empty(n * width, np.float32)
        particles.foreach_get(name, values)
        out[name] = values.reshape(n, width) if width > 1 else values
    return out


class ParticleTable:
    """The particles of the systems that instance objects in one depsgraph pass (each system
    read once, when its first instance is met: the depsgraph's instances live for one step of
    the iteration) and, per instance, a record of the particle it shows."""

    def __init__(self, frame):
        self.frame = np.float32(frame)    # the scene's frame_current_final
        self._numbers = {}                # evaluated particle system pointer -> its number
        self._systems = []                # per number: _read_particles' answer
        self.shown = False                # whether any instance shows a particle

    def record(self, inst):
        """Which particle the depsgraph instance inst shows: (system number << 32) | particle
        number, or NO_PARTICLE (not a particle system's instance, or a child particle)."""
        psys = inst.particle_system
        if psys is None:
            return NO_PARTICLE
        pointer = psys.as_pointer()
        number = self._numbers.get(pointer)
        if number is None:
            number = self._numbers[pointer] = len(self._systems)
            self._systems.append(_read_particles(psys))
        index = inst.persistent_id[0]
        if not 0 <= index < len(self._systems[number]['size']):
            return NO_PARTICLE
        self.shown = True
        return (number << 32) | index

    def constants(self, records):
        """{PARTICLE_KEYS key: float32 (N, 3)} of N records (record's answers): a number as
        (v, v, v); Random less DUMMY_RANDOM; all 0 for NO_PARTICLE; NaN and Inf (a simulation
        gone wrong) 0, as the mesh attributes' (no NaN reaches the shader programs)."""
        records = np.asarray(records, np.int64).reshape(-1)
        n = len(records)
        out = {key: np.zeros((n, 3), np.float32) for key in PARTICLE_KEYS}
        shown = records >= 0
        numbers = records >> 32
        indices = records & 0xFFFFFFFF
        for number in np.unique(numbers[shown]):
            rows = shown & (numbers == number)
            index = indices[rows]
            system = self._systems[int(number)]
            numbers_of = {
                'index': index.astype(np.float32),
                'random': particle_random(index) - np.float32(DUMMY_RANDOM),
                'age': self.frame - system['birth_time'][index],
                'lifetime': system['lifetime'][index],
                'size': system['size'][index]}
            for name, values in numbers_of.items():
                out[_key(name)][rows] = values[:, None]
            for name in ('location', 'velocity', 'angular_velocity'):
                out[_key(name)][rows] = system[name][index]
        for values in out.values():
            np.nan_to_num(values, copy=False, nan=0.0, posinf=0.0, neginf=0.0)
        return out
