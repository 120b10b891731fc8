# SPDX-License-Identifier: Apache-2.0
"""What the viewport's depsgraph shows, read without meshes (scene_cache.py's plan): the lights,
the unsupported objects and every mesh object or instance with its world matrix, material slots
and mesh key, and a fingerprint of it all that tells whether anything shown changed."""

import numpy as np

from .. import export
from ..export.mesh_attributes import dupli_record, instancer_record
from ..export.particles import NO_PARTICLE, ParticleTable
from ..export.points import PointCloudData, points_checksum
from ..nodes import holds_node


def matrix_tuple(m):
    return tuple(float(x) for row in m for x in row)


def slot_names(slots):
    return tuple(s.name if s is not None else "" for s in slots)


def instance_transform(matrix):
    """A mathutils 4x4 matrix as add_instances takes it: float64 (3, 4)."""
    return np.array(matrix, dtype=np.float64)[:3]


def plan_instances(depsgraph, options):
    """(plan, fingerprint, random ids, particles). plan: (kind, object, matrix, slots, mesh key) per
    instance, kind 'LIGHT', 'UNSUPPORTED', 'POINTS' (a point cloud: export.points'
    PointCloudData, its key with a checksum of its points) or 'MESH', for an instance its
    evaluated mesh as
    export.MeshData (inst.object is a temporary the iteration reuses for the next instance: read
    after it, every instance showed the last one's mesh; evaluated_get of the original, tried
    instead, changes the temporaries of later iterations: a collection instance's Object Color);
    random ids: a depsgraph instance's mesh key -> its instances' (random id, dupli_record,
    object colour, original object, instancer_record, particle record) (Object Info, Particle
    Info: recorded only where a material holds a Particle Info node), in plan order; particles:
    the ParticleTable of the particle records."""
    use_lights = options.get("use_scene_lights", True)
    plan = []
    random_ids = {}
    particles = ParticleTable(depsgraph.scene.frame_current_final)
    reads_particles = {}    # instance key -> whether its materials hold a Particle Info node
    fp = []
    for inst in depsgraph.object_instances:
        role = export.instance_role(inst)
        obj = inst.object
        if role == 'LIGHT':
            if use_lights:
                m = inst.matrix_world.copy()
                plan.append(('LIGHT', obj, m, None, None))
                fp.append(('L', obj.name, matrix_tuple(m)))
        elif role == 'POINTS':
            # Read at the build, from the point cloud (which outlives the instance's object);
            # its points' checksum in the key, so that a change rebuilds the scene.
            m = inst.matrix_world.copy()
            cloud = PointCloudData(obj, inst.random_id if inst.is_instance else None)
            key = ('P', obj.name, inst.is_instance, points_checksum(obj.data),
                   slot_names([s.material for s in cloud.material_slots]))
            plan.append(('POINTS', cloud, m, None, key))
            fp.append((key, matrix_tuple(m)))
        elif role in ('UNSUPPORTED', 'HAIR', 'VOLUME'):  # hair, volumes: final renders only
            plan.append(('UNSUPPORTED', obj, None, None, None))
            fp.append(('U', obj.name))
        elif role == 'MESH':
            m = inst.matrix_world.copy()
            slots = tuple(slot.material for slot in obj.material_slots)
            data_name = obj.data.name if obj.data is not None else ""
            if inst.is_instance:
                parent = inst.parent.name if inst.parent is not None else ""
                key = ('I', parent, obj.name, data_name, obj.as_pointer(),
                       obj.data.as_pointer() if obj.data is not None else 0)
                reads = reads_particles.get(key)
                if reads is None:
                    reads = reads_particles[key] = holds_node(slots, 'ShaderNodeParticleInfo')
                random_ids.setdefault(key, []).append((inst.random_id, dupli_record(inst),
                                                       tuple(obj.color), obj.original,
                                                       instancer_record(inst),
                                                       particles.record(inst) if reads
                                                       else NO_PARTICLE))
                obj = export.MeshData(obj)
            else:
                key = ('O', obj.name, data_name)
            plan.append(('MESH', obj, m, slots, key))
            fp.append(('M', key[:4], matrix_tuple(m), slot_names(slots)))
    if particles.shown:     # Particle Info's Age changes with the frame, moved or not
        fp.append(('P', float(particles.frame)))
    return plan, tuple(fp), random_ids, particles


def particle_state(random_ids, particles, eid, needs):
    """What the Particle Info constants of a plan's entry eid (mesh_entries) depend on: its
    particle record and the frame (a dead particle's Age changes, its matrix does not); None
    when it shows no particle or its materials (needs: materials.MeshNeeds) do not read them
    (random_ids, particles: plan_instances' answers)."""
    if not particles.shown or not needs.particles():
        return None
    key, n = eid
    randoms = random_ids.get(key)
    record = randoms[n][5] if randoms is not None and n < len(randoms) else NO_PARTICLE
    return None if record == NO_PARTICLE else (record, float(particles.frame))


def mesh_entries(plan):
    """entry id -> (obj, matrix, slots, key) for the plan's meshes; the id is the key and the
    how-many-th entry with that key it is (instances of one object share a key)."""
    out = {}
    seen = {}
    for kind, obj, matrix, slots, key in plan:
        if kind != 'MESH':
            continue
        n = seen.get(key, 0)
        seen[key] = n + 1
        out[(key, n)] = (obj, matrix, slots, key)
    return out


def lights_fingerprint(plan):
    """The lights, point clouds and unsupported objects of a plan, comparable: a change among
    them makes a new scene."""
    return tuple((kind, obj.name, None if m is None else matrix_tuple(m),
                  key if kind == 'POINTS' else None)
                 for kind, obj, m, _slots, key in plan if kind != 'MESH')
