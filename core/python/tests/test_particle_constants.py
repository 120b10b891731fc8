"""Particle Info's constants (python_addon/torrance/export/particles.py) from stand-ins of
Blender's depsgraph instances and particle systems: which particle an instance shows (none for
a child particle or another kind of instance, as Cycles' sync_dupli_particle), each system read
once, Age in frames, Random as Cycles' hash_uint2_to_float(index, 0) less the dummy particle's,
and an object without a particle reading 0 and getting no layer (mesh_attributes.ObjectInfo)."""
import importlib
import sys
import types
from types import SimpleNamespace as NS

import numpy as np
import pytest

from conftest import ADDON


@pytest.fixture(scope="module")
def export():
    """The add-on's export package's modules, without its __init__ (which imports bpy)."""
    name = "torrance_export_alone"
    package = types.ModuleType(name)
    package.__path__ = [str(ADDON / "export")]
    sys.modules[name] = package
    try:
        yield NS(particles=importlib.import_module(f"{name}.particles"),
                 attributes=importlib.import_module(f"{name}.mesh_attributes"))
    finally:
        for key in [k for k in sys.modules if k == name or k.startswith(name + ".")]:
            del sys.modules[key]


class Particles:
    """A ParticleSystem.particles stand-in: foreach_get of its fields, the calls counted."""

    def __init__(self, **fields):
        self.fields = {k: np.asarray(v, np.float32) for k, v in fields.items()}
        self.reads = 0

    def __len__(self):
        return len(self.fields["size"])

    def foreach_get(self, name, out):
        self.reads += 1
        out[:] = self.fields[name].ravel()


class System:
    def __init__(self, pointer, particles):
        self.pointer, self.particles = pointer, particles

    def as_pointer(self):
        return self.pointer


def instance(system, number):
    return NS(particle_system=system, persistent_id=[number, 0, 0, 0, 0, 0, 0, 0])


def three():
    return Particles(birth_time=[1.0, 2.5, 4.0], lifetime=[7.0, 5.5, 6.0], size=[0.1, 0.2, 0.3],
                     location=[[1, 2, 3], [4, 5, 6], [7, 8, 9]],
                     velocity=[[0.1, 0, 0], [0, 0.2, 0], [0, 0, 0.3]],
                     angular_velocity=[[1, 0, 0], [0, 2, 0], [0, 0, 3]])


def key(name):
    return ('object_info', 'particle_' + name)


def test_hash_of_arrays_is_the_hash_of_numbers(export):
    """hash_uint2 of a numpy array (the particles' Random) agrees with that of Python ints (the
    objects' random ids, which test_shader_object_info_agreement checks against Cycles)."""
    words = [0, 1, 2, 23, 1000, 2**31 - 1, 2**31, 2**32 - 1]
    hashes = export.attributes.hash_uint2(np.asarray(words, np.uint64))
    assert hashes.tolist() == [export.attributes.hash_uint2(w) for w in words]
    assert export.attributes.hash_uint2(0) == 3695015161
    assert export.particles.DUMMY_RANDOM == pytest.approx(3695015161 / 0xFFFFFFFF, rel=1e-7)


def test_records_and_constants(export):
    p = export.particles
    first, second = three(), three()
    a, b = System(111, first), System(222, second)
    table = p.ParticleTable(frame=9.0)
    insts = [instance(a, 2), instance(a, 0), instance(a, 3), instance(None, 0), instance(b, 1),
             instance(a, 1)]
    records = [table.record(i) for i in insts]
    assert records[2] == records[3] == p.NO_PARTICLE   # a child particle (3 >= 3), no system
    assert first.reads == second.reads == 6            # each system read once, every field
    out = table.constants(records)
    assert sorted(out) == sorted(export.attributes.PARTICLE_KEYS)
    shown = [0, 1, 4, 5]
    number = [2, 0, 1, 1]
    for k, n in zip(shown, number, strict=True):
        assert out[key('index')][k].tolist() == [n] * 3
        assert out[key('age')][k, 0] == pytest.approx(9.0 - first.fields["birth_time"][n])
        assert out[key('lifetime')][k, 0] == first.fields["lifetime"][n]
        assert out[key('size')][k, 0] == first.fields["size"][n]
        for name in ('location', 'velocity', 'angular_velocity'):
            assert out[key(name)][k].tolist() == first.fields[name][n].tolist()
        random = out[key('random')][k, 0] + np.float32(p.DUMMY_RANDOM)
        expected = export.attributes.hash_uint2(n) / 0xFFFFFFFF
        assert random == pytest.approx(expected, abs=2e-7)
    for k in (2, 3):                                    # Cycles' dummy particle: 0
        assert all(not out[name][k].any() for name in out)
    assert out[key('random')][1, 0] == 0.0              # particle 0's Random is the dummy's


def test_non_finite_particles_read_0(export):
    """A simulation gone wrong (NaN or Inf in a particle's data) gives 0, never NaN."""
    p = export.particles
    broken = three()
    broken.fields["velocity"][1] = (np.nan, np.inf, -np.inf)
    broken.fields["birth_time"][1] = np.nan
    table = p.ParticleTable(frame=9.0)
    out = table.constants([table.record(instance(System(1, broken), 1))])
    assert all(np.isfinite(values).all() for values in out.values())
    assert not out[key('velocity')].any() and out[key('age')][0, 0] == 0.0
    assert out[key('size')][0, 0] == np.float32(0.2)


def test_objects_without_particles(export):
    """An object's Object Info (and an instance's without a ParticleTable) reads the particle
    keys as 0 without holding them, so with_object_info adds no layer for them."""
    attributes = export.attributes
    obj = NS(name="Cube", color=(1.0, 0.5, 0.25, 1.0), pass_index=3)
    info = attributes.instances_info(obj, np.eye(4)[None, :3, :], [7])
    assert key('age') not in info
    assert info[key('age')].tolist() == [[0.0, 0.0, 0.0]]
    single = attributes.ObjectInfo({}, obj, 1, single=True)
    assert single[key('random')] == (0.0, 0.0, 0.0)
    layers = attributes.with_object_info(None, attributes.ObjectInfo({}, obj, 1, single=True),
                                         {key('size'): 0}, 2)
    assert layers is None
