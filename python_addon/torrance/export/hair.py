# SPDX-License-Identifier: Apache-2.0
"""Hair strands -> tc.Scene.add_curves, as Cycles 3.4 exports them (blender/curves.cpp):

* particle hair: each particle system of type Hair drawn as Path whose modifier renders, its
  strands at 2^render_step + 1 keys (plus the spiral kink's extra steps), the children only when
  it has some (else the parents), through ParticleSystem.co_hair (world space). The radius along a
  strand follows Hair Shape: root and tip radius x radius scale / 2, blended by the arc length
  fraction t as (1 - t)^(1 + shape) (shape < 0) or (1 - t)^(1 / (1 - shape)) (shape > 0), 0 at the
  tip with Close Tip; the material is the settings' Material slot;
* Curves objects (Blender 3.3+): their points' positions and `radius` attribute (0.005 without
  one), curve offsets and `material_index` (curve domain) read with foreach_get.

Radii scale with the object (by the cube root of its matrix's determinant, as Cycles applies a
transform to hair). The shape is the scene's Render > Curves > Shape (Cycles' setting:
Rounded Ribbons or 3D Curves). co_hair is the Python API's only way to child strands: one call
per key (about a microsecond each), its results gathered into one numpy array.
"""

import numpy as np

from ..matrices import radius_scale, times_transpose
from ..shader_graph.hash_ops import hash_uint2, uint_to_float_incl

SHAPES = {'RIBBONS': 'RIBBON', 'THICK': 'ROUND'}
CURVES_DEFAULT_RADIUS = 0.005


def curve_shape(scene):
    """'RIBBON' or 'ROUND': the scene's curve shape (Cycles' setting; its default RIBBONS)."""
    settings = getattr(scene, "cycles_curves", None)
    return SHAPES.get(getattr(settings, "shape", 'RIBBONS'), 'RIBBON')


def hair_systems(obj):
    """The particle systems of obj that Cycles renders as hair strands."""
    for mod in getattr(obj, "modifiers", ()):
        if mod.type == 'PARTICLE_SYSTEM' and mod.show_render:
            psys = mod.particle_system
            part = psys.settings
            if part.type == 'HAIR' and part.render_type == 'PATH':
                yield psys


def has_particle_hair(obj):
    return obj.type == 'MESH' and next(hair_systems(obj), None) is not None


def strand_radii(keys, part):
    """Radii (curves, steps) of strands keys (curves, steps, 3) by the settings' Hair Shape."""
    seg = np.linalg.norm(np.diff(keys, axis=1), axis=2)
    arc = np.concatenate([np.zeros((len(keys), 1)), np.cumsum(seg, axis=1)], axis=1)
    length = arc[:, -1:]
    t = np.where(length > 0.0, arc / np.where(length > 0.0, length, 1.0), 0.0)
    r = 1.0 - t
    if part.shape < 0.0:
        r = r ** (1.0 + part.shape)
    elif part.shape > 0.0:
        r = r ** (1.0 / (1.0 - part.shape))
    half = part.radius_scale * 0.5
    root, tip = half * part.root_radius, half * part.tip_radius
    radii = r * (root - tip) + tip
    if part.use_close_tip:
        radii[:, -1] = 0.0
    return radii


def particle_strands(obj, psys):
    """(keys (n, 3) world space, radii (n,) before the object's scale, offsets) of one system."""
    part = psys.settings
    parents, children = len(psys.particles), len(psys.child_particles)
    first = parents if (part.child_type != 'NONE' and children) else 0
    count = parents + children - first
    steps = (1 << part.render_step) + 1
    if part.kink == 'SPIRAL':
        steps += part.kink_extra_steps
    if count <= 0:
        return None
    co = psys.co_hair
    flat = [c for p in range(first, first + count) for s in range(steps)
            for c in co(obj, particle_no=p, step=s)]
    keys = np.array(flat, dtype=np.float32).reshape(count, steps, 3)
    radii = strand_radii(keys.astype(np.float64), part).astype(np.float32)
    offsets = np.arange(count + 1, dtype=np.int64) * steps
    return keys.reshape(-1, 3), radii.reshape(-1), offsets


def curves_strands(obj, matrix):
    """(keys world space, radii, offsets, material slot per curve, normals world space or None)
    of a Curves object."""
    data = obj.data
    n = len(data.points)
    num_curves = len(data.curves)
    if n == 0 or num_curves == 0:
        return None
    local = np.empty(3 * n, dtype=np.float32)
    data.points.foreach_get("position", local)
    radii = np.full(n, CURVES_DEFAULT_RADIUS, dtype=np.float32)
    attrs = data.attributes
    radius = attrs.get("radius")
    if radius is not None and radius.domain == 'POINT' and radius.data_type == 'FLOAT':
        radius.data.foreach_get("value", radii)
    offsets = np.empty(num_curves + 1, dtype=np.int32)
    data.curve_offset_data.foreach_get("value", offsets)
    slots = np.zeros(num_curves, dtype=np.int32)
    if "material_index" in attrs and attrs["material_index"].domain == 'CURVE':
        attrs["material_index"].data.foreach_get("value", slots)
    m = np.array(matrix, dtype=np.float64)
    keys = times_transpose(local.reshape(-1, 3).astype(np.float64), m[:3, :3]) + m[:3, 3]
    return keys.astype(np.float32), radii, offsets.astype(np.int64), slots, curve_normals(data, m)


def curve_normals(data, m):
    """The Curves' normal attribute per point (Blender 4.0+: Curves.normals, by its normal
    mode), turned by the world matrix m; Cycles aligns a Huang hair ellipse's major axis with it.
    None where Blender has none (3.x) or it is not finite."""
    normals = getattr(data, "normals", None)
    if normals is None or len(normals) != len(data.points):
        return None
    local = np.empty(3 * len(normals), dtype=np.float32)
    normals.foreach_get("vector", local)
    world = times_transpose(local.reshape(-1, 3).astype(np.float64), m[:3, :3]).astype(np.float32)
    return world if np.isfinite(world).all() else None


def strand_random(first, count):
    """The Curves Info node's Random of an object's strands first .. first + count - 1 (counted
    over its particle systems in order, or its Curves' curves), as Cycles' curve export:
    hash_uint2_to_float(index, 0)."""
    index = np.arange(first, first + count, dtype=np.uint32)
    return np.asarray(uint_to_float_incl(hash_uint2(index, np.zeros_like(index))), np.float32)


def read_strands(obj, psys, matrix):
    """(keys, radii, offsets[, slots, normals]) of obj's particle system psys, or of Curves
    object obj (psys None) at its world matrix; None without strands."""
    return curves_strands(obj, matrix) if psys is None else particle_strands(obj, psys)


def export_hair(tc_scene, hair, materials, reporter, shape, on_added=None, settings_of=None):
    """Adds the strands of `hair`: (evaluated object, its world matrix) pairs, particle-hair
    emitters and Curves objects. Returns the number of strands added. on_added(set id, object
    name, particle system name or None, offsets), if given, hears of each curve set added;
    settings_of(obj), if given, gives the keyword arguments of Scene.set_curves_settings for
    obj's strands (its pass index, holdout, light group, ...)."""
    strands = 0

    def added(set_id, obj, psys_name, offsets):
        if settings_of is not None:
            tc_scene.set_curves_settings(set_id, **settings_of(obj))
        if on_added is not None:
            on_added(set_id, obj.name, psys_name, offsets)

    for obj, matrix in hair:
        first_strand = 0         # the object's strands so far (Curves Info's Random)
        slot_to_material = materials.slot_indices([s.material for s in obj.material_slots])
        scale = radius_scale(matrix)
        if obj.type == 'CURVES':
            got = read_strands(obj, None, matrix)
            if got is None:
                continue
            keys, radii, offsets, slots, normals = got
            per_curve = slot_to_material[np.clip(slots, 0, len(slot_to_material) - 1)]
            set_id = tc_scene.add_curves(keys, radii * scale, offsets,
                                         materials=per_curve.astype(np.int64), shape=shape,
                                         random=strand_random(0, len(offsets) - 1),
                                         normals=normals)
            added(set_id, obj, None, offsets)
            strands += len(offsets) - 1
            continue
        for psys in hair_systems(obj):
            got = read_strands(obj, psys, matrix)
            if got is None:
                continue
            keys, radii, offsets = got
            slot = min(max(psys.settings.material - 1, 0), len(slot_to_material) - 1)
            per_curve = np.full(len(offsets) - 1, slot_to_material[slot], dtype=np.int64)
            if not np.isfinite(keys).all():
                reporter.warning(f"Object '{obj.name}': hair '{psys.name}' has non-finite keys; "
                                 f"not rendered")
                continue
            count = len(offsets) - 1
            set_id = tc_scene.add_curves(keys, radii * scale, offsets, materials=per_curve,
                                         shape=shape, random=strand_random(first_strand, count))
            added(set_id, obj, psys.name, offsets)
            first_strand += count
            strands += count
    return strands
