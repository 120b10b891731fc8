# SPDX-License-Identifier: Apache-2.0
"""Particle Info renders as Cycles renders it (3.4, and 4.2 / 5.3 through bpy): every output on
objects a particle system instances, Cycles' dummy particle everywhere else.

Seen from above (orthographic) through Emission shaders, no lighting noise: four emitters, each
a Newtonian particle system (no gravity, a fixed seed, particles born over frames 1-10 with a
random lifetime, rendered at frame 9: some not yet born, some dead) instancing an ico sphere of
its own material:
* Index / 24, Random, 0.5 Age / Lifetime + 0.5 (its dead particles shown: Age past Lifetime;
  2 child particles each, which Cycles gives the dummy particle);
* |Location x| / 3, |Location y| / 2, 3 Size (its unborn particles shown: negative Age);
* |Velocity| per axis (Render As Collection);
* |Angular Velocity| per axis (random axes).
The emitters themselves are rendered with the first material: no particle, Cycles' dummy (Index
0, Random that of particle 0, 0.86); so is the world's Particle Info (its Random the sky's
colour at the frame's edges).

Cycles' reference (seed 0) and a second Cycles image (seed 1) set the bounds; Torrance renders
seeds 2 and 3. Deliberate faults (one per output group) must fail them; by default only those
near the bounds are rendered again (TORRANCE_ALL_FAULTS=1: all). Blender 3.4, when written:
bounds ratio 0.996..1.004, block mean 0.0024; Torrance 0.9991, 0.0016. Faults: Age in seconds
block mean 0.0096 (B ratio 0.974); Index off by one R ratio 1.014; Random of another hash
0.0077; Size 1/9 0.0065; children given a parent's particle 0.0303; Location in the emitter's
space 0.0233; Velocity per frame 0.0410; Angular Velocity's axes turned R ratio 0.953; no dummy
particle's Random 0.569. bpy 4.2 and 5.3 alike: bounds 0.9928..1.0072, 0.0022; Torrance
0.9990, 0.0016; Index off by one R ratio 1.016, the others as in 3.4.

The figures are those of Render As Object for the Velocity emitter too (its particles' data
do not depend on it).

The viewport's scene (its SceneCache) then renders the final render's image, at frame 9 and
again one frame on (the instances updated in place, their particles' constants with them; the
dead particles do not move, their Age changes): mean difference 1.7e-6 and 2.0e-6 (bound 1e-5);
with the dead particles' constants left as they were (an update for moved instances only)
4.9e-5, failed.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_particle_info_agreement.py
"""

import bpy
import numpy as np

from torrance_tools import testing
from torrance_tools.seed_noise import agree_within_seed_noise
from torrance_tools.shader_graphs import Graph
from torrance_tools.viewport_render import viewport_scene_matches_final

W, H = 96, 64
FRAME = 9
COUNT = 24


def _abs_scaled(g, vector, scale):
    a = g.node("ShaderNodeVectorMath", operation='ABSOLUTE')
    g.link(vector, a.inputs[0])
    s = g.node("ShaderNodeVectorMath", operation='SCALE')
    s.inputs["Scale"].default_value = scale
    g.link(a.outputs[0], s.inputs[0])
    return s.outputs[0]


def _separate(g, vector):
    sep = g.node("ShaderNodeSeparateXYZ")
    g.link(vector, sep.inputs[0])
    return sep.outputs


def index_random_age():
    g = Graph("IndexRandomAge")
    info = g.node("ShaderNodeParticleInfo")
    ratio = g.math('DIVIDE', info.outputs["Age"], info.outputs["Lifetime"])
    g.link(g.combine(g.math('DIVIDE', info.outputs["Index"], value_b=COUNT),
                     info.outputs["Random"], g.multiply_add(ratio, 0.5, 0.5)),
           g.shader.inputs["Color"])
    return g.mat


def location_size():
    g = Graph("LocationSize")
    info = g.node("ShaderNodeParticleInfo")
    x, y, _z = _separate(g, info.outputs["Location"])
    g.link(g.combine(g.math('MULTIPLY', g.math('ABSOLUTE', x), value_b=1.0 / 3.0),
                     g.math('MULTIPLY', g.math('ABSOLUTE', y), value_b=0.5),
                     g.math('MULTIPLY', info.outputs["Size"], value_b=3.0)),
           g.shader.inputs["Color"])
    return g.mat


def velocity():
    g = Graph("Velocity")
    info = g.node("ShaderNodeParticleInfo")
    g.link(_abs_scaled(g, info.outputs["Velocity"], 1.0), g.shader.inputs["Color"])
    return g.mat


def angular_velocity():
    g = Graph("AngularVelocity")
    info = g.node("ShaderNodeParticleInfo")
    g.link(_abs_scaled(g, info.outputs["Angular Velocity"], 0.4), g.shader.inputs["Color"])
    return g.mat


def sphere(name, material, x):
    """An ico sphere of radius 1 at (x, 0, 0), out of the camera's view (the viewport's
    depsgraph shows it: hide_render hides it from final renders only)."""
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=2, radius=1.0, location=(x, 0.0, 0.0))
    obj = bpy.context.active_object
    obj.name = name
    obj.data.materials.append(material)
    obj.hide_render = True          # only its instances are seen (Cycles' likewise)
    return obj


def emitter(scene, name, centre, material, instance, seed, **settings):
    """A 2.6 x 1.7 plane at centre emitting COUNT particles over frames 1-10 that instance
    `instance`, rendered with `material` itself; settings: the ParticleSettings' others."""
    obj = testing.plane(scene, name, 1.0, material=material)
    obj.scale = (2.6, 1.7, 1.0)
    obj.location = centre
    obj.modifiers.new("Particles", 'PARTICLE_SYSTEM')
    psys = obj.particle_systems[0]
    psys.seed = seed
    ps = psys.settings
    ps.count = COUNT
    ps.frame_start, ps.frame_end = 1, 10
    ps.lifetime, ps.lifetime_random = 7.0, 0.5
    ps.emit_from = 'FACE'
    ps.physics_type = 'NEWTON'
    ps.effector_weights.gravity = 0.0
    ps.normal_factor = 0.6
    ps.factor_random = 0.8
    ps.use_rotations = True
    ps.angular_velocity_mode = 'RAND'
    ps.angular_velocity_factor = 2.0
    ps.render_type = 'OBJECT'
    if instance is not None:
        ps.instance_object = instance
    ps.particle_size = 0.2
    ps.size_random = 0.5
    for key, value in settings.items():
        setattr(ps, key, value)
    return obj


def build(scene):
    testing.setup_render(scene, width=W, height=H)
    scene.render.fps = 24
    cam = testing.add_camera(scene, location=(0.0, 0.0, 10.0), target=(0.0, 0.0, 0.0))
    cam.data.type = 'ORTHO'
    cam.data.ortho_scale = 6.0
    world = testing.set_world(scene, (0.0, 0.0, 0.0), strength=0.25)
    tree = world.node_tree           # the world's Particle Info: the dummy's Random, 0.86
    tree.links.new(tree.nodes.new("ShaderNodeParticleInfo").outputs["Random"],
                   tree.nodes["Background"].inputs["Color"])
    first = index_random_age()
    emitter(scene, "EmitIndex", (-1.5, 1.0, 0.0), first, sphere("Ball", first, 10.0), 5,
            use_dead=True, child_type='SIMPLE', rendered_child_count=2,
            child_radius=0.3, use_parent_particles=True)
    emitter(scene, "EmitLocation", (1.5, 1.0, 0.0), first,
            sphere("Pebble", location_size(), 13.0), 7, show_unborn=True)
    drops = bpy.data.collections.new("Drops")      # Render As Collection, not in the scene
    drop = sphere("Drop", velocity(), 0.0)         # at the collection's origin
    drop.hide_render = False                      # (a collection's instances would hide too)
    for holder in drop.users_collection:
        holder.objects.unlink(drop)
    drops.objects.link(drop)
    emitter(scene, "EmitVelocity", (-1.5, -1.0, 0.0), first, None, 11,
            render_type='COLLECTION', instance_collection=drops)
    emitter(scene, "EmitSpin", (1.5, -1.0, 0.0), first, sphere("Top", angular_velocity(), 16.0), 13)
    for frame in range(1, FRAME + 1):     # the simulation, frame after frame
        scene.frame_set(frame)


# Faults, one per output group: each replaces an attribute of torrance.export.particles.

def age_in_seconds(original):
    def constants(self, records):
        out = original(self, records)
        out[('object_info', 'particle_age')] /= 24.0
        return out
    return constants


def index_off_by_one(original):
    def constants(self, records):
        out = original(self, records)
        index = out[('object_info', 'particle_index')]
        index[np.asarray(records).reshape(-1) >= 0] += 1.0
        return out
    return constants


def random_of_another_hash(original):
    def random(indices):
        from torrance.export.mesh_attributes import hash_uint2, uint_to_unit_float
        return uint_to_unit_float(hash_uint2(np.asarray(indices, np.uint64), 1))
    return random


def children_as_parents(original):
    """Child particles given the particle of their number modulo the count (Cycles gives them
    none)."""
    def record(self, inst):
        r = original(self, inst)
        if r < 0 and inst.particle_system is not None:
            return (self._numbers[inst.particle_system.as_pointer()] << 32) | \
                (inst.persistent_id[0] % COUNT)
        return r
    return record


def size_one(original):
    def constants(self, records):
        out = original(self, records)
        out[('object_info', 'particle_size')][np.asarray(records).reshape(-1) >= 0] = 1.0 / 9
        return out
    return constants


def location_in_the_emitters_space(original):
    """Location less the EmitLocation emitter's own (its object space, not the world)."""
    def constants(self, records):
        out = original(self, records)
        shown = np.asarray(records).reshape(-1) >= 0
        out[('object_info', 'particle_location')][shown] -= np.float32((1.5, 1.0, 0.0))
        return out
    return constants


def velocity_per_frame(original):
    def constants(self, records):
        out = original(self, records)
        out[('object_info', 'particle_velocity')] /= 24.0
        return out
    return constants


def angular_velocity_swizzled(original):
    def constants(self, records):
        out = original(self, records)
        w = out[('object_info', 'particle_angular_velocity')]
        w[:] = w[:, [1, 2, 0]]
        return out
    return constants


def no_dummy_random(original):
    """The objects without a particle read Random 0 (no dummy particle)."""
    return 0.0


def next_frame(scene):
    """The particles one frame on: every instance moves (the viewport updates them in place)."""
    scene.frame_set(FRAME + 1)


def main():
    testing.addon()
    import torrance.export.particles as particles
    table = particles.ParticleTable
    scene = testing.clear_scene()
    build(scene)
    faults = (("Age in seconds", table, "constants", age_in_seconds),
              ("Index off by one", table, "constants", index_off_by_one),
              ("Random of another hash", particles, "particle_random", random_of_another_hash),
              ("children given a parent's particle", table, "record", children_as_parents),
              ("Size 1/9", table, "constants", size_one),
              ("Location in the emitter's space", table, "constants",
               location_in_the_emitters_space),
              ("Velocity per frame", table, "constants", velocity_per_frame),
              ("Angular Velocity's axes turned", table, "constants",
               angular_velocity_swizzled),
              ("no dummy particle's Random", particles, "DUMMY_RANDOM", no_dummy_random))
    narrow = ("Age in seconds", "Index off by one", "Random of another hash", "Size 1/9")
    agree_within_seed_noise(
        scene, testing.tempdir(), 16, 1, "Particle Info",
        faults=testing.faults_to_render(faults, narrow),
        tolerance=1.5, ratio_sigmas=3.0, ratio_floor=0.004)
    viewport_scene_matches_final(scene, W, H, next_frame, "Particle Info", tolerance=1e-5)


testing.run(main)
