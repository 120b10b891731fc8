# SPDX-License-Identifier: Apache-2.0
"""The Sky Texture node as Cycles renders it (opcode 61, the core's shader_sky.h): Preetham's
analytic sky, the Nishita sky of Blender 3.x-4.x (single scattering in an atmosphere of air,
dust and ozone, precomputed as Cycles' host does into a 512 x 128 texture, plus the
limb-darkened sun disc) and Blender 5.x's Single and Multiple Scattering (one kernel: a 512 x 256
texture over the whole sphere, the disc hidden below the Earth's rim and the sky added under it;
Single is Nishita's atmosphere, Multiple Fernando Garcia Linan's spectral model with multiple
scattering and the ground's bounce), and Hosek / Wilkie (the published XYZ dataset, cooked for
the sun, turbidity and ground albedo as Cycles' host does).

The reader asks the core for the op's table (torrance_core.preetham_sky_table /
nishita_sky_table / scattering_sky_table / hosek_sky_table, the functions Cycles'
SkyTextureNode::compile runs on the host); the twin here evaluates a table at a direction as the
core's op does (float32 results, the angles and transcendental functions in float64 rounded to
float32), the fold of a constant Vector and the reference evaluator's op.
"""

import math

import numpy as np

from .node_versions import SKY_TYPES_5, cycles_wraps_sun_elevation, input_socket, sky_dust_density
from .texture_mapping import is_identity, mapped
from .textures import _vector

OPCODES = {"TexSky": 61}
# The op's modes (the core's SkyModel) by Blender's sky_type (node_versions.SKY_TYPES_5: 5.x's).
SKY_MODELS = {'PREETHAM': 0, 'NISHITA': 1, 'SINGLE_SCATTERING': 2, 'MULTIPLE_SCATTERING': 2,
              'HOSEK_WILKIE': 3}
PREETHAM_TABLE = 20
HOSEK_TABLE = 32
NISHITA_HEADER = 12
SCATTERING_HEADER = 13

_F = np.float32
_HALF_PI = _F(math.pi / 2)
_PI = _F(math.pi)
_TWO_PI = _F(2 * math.pi)
# CIE XYZ -> Rec. 709 (the inverse of Blender's srgb_to_xyz.spimtx, as the core's).
_XYZ_TO_REC709 = np.array(((3.2404548360, -1.5371388501, -0.4985315469),
                           (-0.9692663899, 1.8760109288, 0.0415560823),
                           (0.0556434196, -0.2040258543, 1.0572251625)), np.float32)


def _acos(c):
    return _F(math.acos(min(max(float(c), -1.0), 1.0)))


def _spherical(d):
    return _acos(d[2]), _F(math.atan2(float(d[0]), float(d[1])))


def _rec709(xyz):
    return tuple(float(max(c, 0.0)) for c in _XYZ_TO_REC709 @ np.asarray(xyz, np.float32))


def _perez(lam, theta, gamma):
    cg = _F(math.cos(float(gamma)))
    return ((_F(1) + lam[0] * _F(math.exp(float(lam[1] / _F(math.cos(float(theta)))))))
            * (_F(1) + lam[2] * _F(math.exp(float(lam[3] * gamma))) + lam[4] * cg * cg))


def preetham(d, table):
    """Preetham's sky (Rec. 709) along d from the table (sun phi, theta, zenith Y, x, y, the
    Perez coefficients of Y, x, y)."""
    t = [_F(v) for v in table]
    theta, phi = _spherical([_F(v) for v in d[:3]])
    st, sp = t[1], t[0]
    gamma = _acos(_F(math.sin(theta)) * _F(math.sin(st)) * _F(math.cos(sp - phi))
                  + _F(math.cos(theta)) * _F(math.cos(st)))
    theta = min(theta, _HALF_PI - _F(0.001))
    with np.errstate(all='ignore'):
        cx = t[3] * _perez(t[10:15], theta, gamma)
        cy = t[4] * _perez(t[15:20], theta, gamma)
        lum = t[2] * _perez(t[5:10], theta, gamma)
        x = (cx / cy) * lum if cy != 0 else _F(0)
        z = (_F(1) - cx - cy) / cy * lum if cy != 0 and lum != 0 else _F(0)
    return _rec709((x, lum, z))


def _hosek_internal(c, theta, gamma):
    ct, cg = _F(math.cos(float(theta))), _F(math.cos(float(gamma)))
    exp_m = _F(math.exp(float(c[4] * gamma)))
    ray_m = cg * cg
    mie_m = (_F(1) + ray_m) / _F(math.pow(float(_F(1) + c[8] * c[8] - _F(2) * c[8] * cg), 1.5))
    zenith = _F(math.sqrt(float(ct)))
    return ((_F(1) + c[0] * _F(math.exp(float(c[1] / (ct + _F(0.01))))))
            * (c[2] + c[3] * exp_m + c[5] * ray_m + c[6] * mie_m + c[7] * zenith))


def hosek(d, table):
    """Hosek / Wilkie's sky (Rec. 709) along d from the table (sun phi, theta, the XYZ radiance
    scales, nine parameters per channel)."""
    t = np.asarray(table, np.float32)
    theta, phi = _spherical([_F(v) for v in d[:3]])
    gamma = _acos(_F(math.sin(theta)) * _F(math.sin(t[1])) * _F(math.cos(t[0] - phi))
                  + _F(math.cos(theta)) * _F(math.cos(t[1])))
    theta = min(theta, _HALF_PI - _F(0.001))
    with np.errstate(all='ignore'):
        xyz = [_hosek_internal(t[5 + 9 * k:14 + 9 * k], theta, gamma) * t[2 + k] for k in range(3)]
    return tuple(c * float(_F(2 * math.pi) / _F(683)) for c in _rec709(xyz))


def _lookup(texels, x, y):
    """Cycles' linear lookup, Extension Extend, of texels (h, w, 3)."""
    h, w = texels.shape[:2]
    fx, fy = _F(x) * _F(w) - _F(0.5), _F(y) * _F(h) - _F(0.5)
    ix, iy = math.floor(fx), math.floor(fy)
    tx, ty = fx - _F(ix), fy - _F(iy)
    x0, x1 = min(max(ix, 0), w - 1), min(max(ix + 1, 0), w - 1)
    y0, y1 = min(max(iy, 0), h - 1), min(max(iy + 1, 0), h - 1)
    return ((_F(1) - ty) * (_F(1) - tx) * texels[y0, x0] + (_F(1) - ty) * tx * texels[y0, x1]
            + ty * (_F(1) - tx) * texels[y1, x0] + ty * tx * texels[y1, x1])


def nishita(d, table):
    """The Nishita sky (Rec. 709) along d from the table (sun disc colours and settings, the
    texture's size, its texels)."""
    t = np.asarray(table, np.float32)
    w, h = int(t[10]), int(t[11])
    if len(t) != NISHITA_HEADER + 3 * w * h:
        return (0.0, 0.0, 0.0)
    texels = t[NISHITA_HEADER:].reshape(h, w, 3)
    bottom, top = t[0:3], t[3:6]
    elevation, rotation, diameter, intensity = t[6], t[7], t[8], t[9]
    d = np.asarray(d[:3], np.float32)
    theta, phi = _spherical(d)
    x = (phi + _PI + rotation) / _TWO_PI
    if x > 1:
        x -= _F(1)
    xyz = np.zeros(3, np.float32)
    if d[2] >= 0:
        angle = _angle(d, _sun(elevation, rotation))
        half = diameter / _F(2)
        view_elevation = _HALF_PI - theta
        if diameter >= 0 and angle < half:
            if elevation + half > 0:
                s = ((view_elevation - elevation) / diameter + _F(0.5) if elevation - half > 0
                     else view_elevation / (elevation + half))
                xyz = (bottom + s * (top - bottom)) * intensity
            r = angle / half
            xyz = xyz * _limb(r)
        else:
            xyz = _lookup(texels, x, _F(math.sqrt(max(float(view_elevation / _HALF_PI), 0.0))))
    elif d[2] >= -0.4:
        fade = _F(1) + d[2] * _F(2.5)
        xyz = _lookup(texels, x, -0.5) * (fade * fade * fade)
    return _rec709(xyz)


def _sun(elevation, rotation):
    """Cycles' sun direction at (elevation, Cycles' rotation)."""
    ce, lon = math.cos(float(elevation)), float(rotation + _HALF_PI)
    return np.array((ce * math.cos(lon), ce * math.sin(lon), math.sin(float(elevation))),
                    np.float32)


def _limb(r):
    """The disc's limb darkening at r, the distance from its centre over its radius."""
    return _F(1) - _F(0.6) * (_F(1) - _F(math.sqrt(max(float(1 - r * r), 0.0))))


def _angle(d, sun):
    return _F(2 * math.atan2(float(np.linalg.norm(d - sun)), float(np.linalg.norm(d + sun))))


def scattering(d, table):
    """Blender 5.x's Single / Multiple Scattering sky (Rec. 709) along d from the table (sun disc
    colours and settings, the Earth's rim, the texture's size, its texels)."""
    t = np.asarray(table, np.float32)
    w, h = int(t[11]), int(t[12])
    if len(t) != SCATTERING_HEADER + 3 * w * h:
        return (0.0, 0.0, 0.0)
    texels = t[SCATTERING_HEADER:].reshape(h, w, 3)
    bottom, top = t[0:3], t[3:6]
    elevation, rotation, diameter, intensity, earth = t[6], t[7], t[8], t[9], t[10]
    d = np.asarray(d[:3], np.float32)
    theta = _spherical(d)[0]
    angle = _angle(d, _sun(elevation, rotation))
    half = diameter * _F(0.5)
    view_elevation = _HALF_PI - theta
    xyz = np.zeros(3, np.float32)
    if diameter >= 0 and angle < half and view_elevation > earth:
        s = (view_elevation - elevation) / diameter + _F(0.5)
        r = angle / half
        xyz = (bottom + s * (top - bottom)) * intensity * _limb(r)
    x = (-_F(math.atan2(float(d[1]), float(d[0]))) - _HALF_PI + rotation) / _TWO_PI   # 5.x's
    x -= _F(math.floor(x))
    y = _F(math.copysign(math.sqrt(abs(float(view_elevation)) * 2 / math.pi),
                         float(view_elevation))) * _F(0.5) + _F(0.5)
    return _rec709(xyz + _lookup(texels, x, y))


_EVALUATORS = {0: preetham, 1: nishita, 2: scattering, 3: hosek}


def _fold_sky(mode, flags, a, table):
    rgb = _EVALUATORS[mode](a[0], table)
    return (*rgb, 1.0)


FOLDS = {"TexSky": _fold_sky}


# -- the reader -----------------------------------------------------------------------------------

def _unsupported(node, what):
    from ..nodes import node_label
    from .graph import Unsupported
    return Unsupported(f"{node_label(node)}: {what}")


def sky_table(node):
    """(mode, table) of a Sky Texture node, as Cycles' SkyTextureNode::compile computes them."""
    kind = node.sky_type
    if kind not in SKY_MODELS:
        raise _unsupported(node, f"sky type {kind.replace('_', ' ').title()}")
    from ..core_module import load_core
    core = load_core()
    if kind in ('PREETHAM', 'HOSEK_WILKIE'):
        d = np.asarray(node.sun_direction, np.float64)
        length = float(np.linalg.norm(d))
        d = tuple(float(c) for c in (d / length if length > 0 else d))
        if kind == 'HOSEK_WILKIE':
            return SKY_MODELS[kind], core.hosek_sky_table(d, float(node.turbidity),
                                                          float(node.ground_albedo))
        return SKY_MODELS[kind], core.preetham_sky_table(d, float(node.turbidity))
    if kind in SKY_TYPES_5:
        table = core.scattering_sky_table(
            kind == 'MULTIPLE_SCATTERING', node.sun_elevation, node.sun_rotation, node.sun_size,
            node.sun_intensity, bool(node.sun_disc), node.altitude, node.air_density,
            sky_dust_density(node), node.ozone_density)
        return SKY_MODELS[kind], table
    table = core.nishita_sky_table(
        node.sun_elevation, node.sun_rotation, node.sun_size, node.sun_intensity,
        bool(node.sun_disc), node.altitude, node.air_density, sky_dust_density(node),
        node.ozone_density, wrap_elevation=cycles_wraps_sun_elevation())
    return SKY_MODELS[kind], table


def _direction(g, node):
    """The Vector input as Blender gives it to Cycles: a Nishita (or 5.x scattering) sky with its
    sun disc makes the socket unavailable (node_shader_update_sky), its link ignored: Generated
    coordinates."""
    if input_socket(node, "Vector").enabled:
        return _vector(g, node)
    return mapped(g, node, g.generated())


def _cycles_sun(node):
    """(elevation, rotation) of a Nishita / scattering sun as Cycles' kernel takes them (wrapped
    first where Cycles wraps: shader_sky.h's wrapped_sun, cycles_sun_rotation)."""
    e, r = float(node.sun_elevation), float(node.sun_rotation)
    if node.sky_type in SKY_TYPES_5 or cycles_wraps_sun_elevation():
        e = math.fmod(e, 2 * math.pi)
        if abs(e) >= math.pi:
            e -= math.copysign(2.0, e) * math.pi
        if e >= math.pi / 2 or e <= -math.pi / 2:
            e, r = math.copysign(math.pi, e) - e, r + math.pi
    r = math.fmod(r, 2 * math.pi)
    return e, 2 * math.pi - (r + 2 * math.pi if r < 0 else r)


def _note_sun(g, node):
    """A world's sky with its sun disc, for Cycles' sun guiding (light/background.cpp): its
    Vector unlinked or Texture Coordinate > Generated, the disc's direction (x, y, z) and half
    angle in g.suns by node (None where Cycles would fall back to the map: a Vector from elsewhere
    or, Torrance's own limit, a Texture Mapping other than the identity)."""
    if not g.background or node.sky_type in ('PREETHAM', 'HOSEK_WILKIE') or not node.sun_disc:
        return
    socket = input_socket(node, "Vector")
    links = [link for link in socket.links if link.is_valid and not link.is_muted]
    suns = g.__dict__.setdefault("suns", {})
    if links and (links[0].from_node.bl_idname != 'ShaderNodeTexCoord'
                  or links[0].from_socket.identifier != "Generated"):
        return
    if not is_identity(node.texture_mapping):
        suns[node.name] = None
        return
    e, r = _cycles_sun(node)
    lon = r + math.pi / 2
    suns[node.name] = (math.cos(e) * math.cos(lon), math.cos(e) * math.sin(lon), math.sin(e),
                       max(float(node.sun_size), 0.0005) * 0.5)


def _read_sky(g, node, socket):
    mode, table = sky_table(node)
    _note_sun(g, node)
    return g.builder.emit("TexSky", 'color', [_direction(g, node)], mode=mode, table=table)


READERS = {'ShaderNodeTexSky': _read_sky}
