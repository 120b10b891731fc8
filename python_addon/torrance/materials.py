# SPDX-License-Identifier: Apache-2.0
"""Blender materials -> Torrance's metallic/roughness materials.

Torrance has one material model (base colour, metallic, roughness, specular,
emission). It is read from the node that feeds the Surface of the material's
output node (the output Cycles would use):

* Principled BSDF: the sockets Base Color, Metallic, Roughness, Specular,
  Emission and Emission Strength;
* Diffuse BSDF: a pure diffuse material (specular 0);
* Emission: a black emitter.

A socket linked to something Torrance can not evaluate keeps its own default
value and the render reports it once per material and socket. Anything else
(another shader node, no output, nothing linked) becomes the neutral default
material and is reported.
"""

import math

# Cycles' surface for objects without material or with an empty slot is a 0.8 grey diffuse;
# ours is the neutral Principled default.
DEFAULT_MATERIAL = dict(
    base_color=(0.8, 0.8, 0.8),
    metallic=0.0,
    roughness=0.5,
    specular=0.5,
    emission=(0.0, 0.0, 0.0),
    emission_strength=0.0,
    specular_tint=0.0,
)

# Principled inputs that Torrance ignores, with the value at which ignoring them is exact.
_IGNORED_PRINCIPLED_INPUTS = (
    ("Subsurface", 0.0),
    ("Anisotropic", 0.0),
    ("Sheen", 0.0),
    ("Clearcoat", 0.0),
    ("Transmission", 0.0),
    ("Alpha", 1.0),
)

# Nodes whose output is a constant we can read.
_CONSTANT_NODES = {'RGB', 'VALUE'}


class Reporter:
    """Collects messages for engine.report(); each distinct message is reported once."""

    def __init__(self, engine=None):
        self.engine = engine
        self.seen = set()
        self.messages = []          # (level, text), in order

    def report(self, level, text):
        if (level, text) in self.seen:
            return
        self.seen.add((level, text))
        self.messages.append((level, text))
        if self.engine is not None:
            try:
                self.engine.report({level}, text)
            except Exception:        # never let reporting break a render
                print(f"Torrance {level}: {text}")
        else:
            print(f"Torrance {level}: {text}")

    def info(self, text):
        self.report('INFO', text)

    def warning(self, text):
        self.report('WARNING', text)

    def error(self, text):
        self.report('ERROR', text)


def _finite_or(value, fallback):
    try:
        v = float(value)
    except (TypeError, ValueError):
        return fallback
    return v if math.isfinite(v) else fallback


def _clamp(v, lo, hi):
    return lo if v < lo else hi if v > hi else v


def _color3(value, fallback):
    try:
        c = tuple(value)[:3]
    except TypeError:                       # a float socket linked into a colour
        c = (value, value, value)
    if len(c) < 3:
        return fallback
    return tuple(_finite_or(x, f) for x, f in zip(c, fallback))


def _active_links(socket):
    return [link for link in socket.links
            if link.is_valid and not link.is_muted]


def _follow(socket):
    """The output socket feeding an input socket, through reroutes; None when unlinked."""
    seen = 0
    while True:
        links = _active_links(socket) if socket.is_linked else []
        if not links:
            return None
        from_socket = links[0].from_socket
        node = from_socket.node
        if node.bl_idname == 'NodeReroute' and seen < 1000:
            seen += 1
            socket = node.inputs[0]
            continue
        return from_socket


def _node_label(node):
    """'Name' or 'Name' (Type) when the name does not say the type."""
    name = node.label or node.name
    if name == node.bl_label or name.startswith(node.bl_label + "."):
        return f"'{name}'"
    return f"'{name}' ({node.bl_label})"


class MaterialReader:
    """Reads one Blender material into a dict of add_material() arguments."""

    def __init__(self, reporter):
        self.reporter = reporter

    def _socket_value(self, mat, node, name, fallback):
        """The value of input `name` of `node`: its default, or a constant node it is linked to."""
        socket = node.inputs.get(name)
        if socket is None:
            return fallback
        source = _follow(socket)
        if source is not None:
            src_node = source.node
            if src_node.type in _CONSTANT_NODES and not src_node.mute:
                return source.default_value
            self.reporter.warning(
                f"Material '{mat.name}': input '{name}' of {_node_label(node)} is linked to "
                f"{_node_label(src_node)}, which Torrance does not support; using the "
                f"socket's own value")
        return socket.default_value

    def read(self, mat):
        """add_material() keyword arguments for a Blender material (None = default material)."""
        if mat is None:
            return dict(DEFAULT_MATERIAL)
        try:
            return self._read(mat)
        except Exception as exc:      # a broken node tree must not stop the render
            self.reporter.warning(
                f"Material '{mat.name}' could not be read ({exc}); using the default material")
            return dict(DEFAULT_MATERIAL)

    def _neutral(self, mat, why):
        self.reporter.warning(f"Material '{mat.name}': {why}; using the neutral default material")
        return dict(DEFAULT_MATERIAL)

    def _read(self, mat):
        if not mat.use_nodes or mat.node_tree is None:
            # Like Cycles: a material without nodes is a diffuse surface of the viewport colour.
            return dict(DEFAULT_MATERIAL,
                        base_color=_color3(mat.diffuse_color, DEFAULT_MATERIAL['base_color']),
                        specular=0.0, metallic=0.0)

        tree = mat.node_tree
        output = tree.get_output_node('CYCLES')
        if output is None:
            return self._neutral(mat, "no active Material Output node")
        surface = output.inputs.get("Surface")
        source = _follow(surface) if surface is not None else None
        if source is None:
            return self._neutral(mat, "nothing is connected to the Surface of the Material Output")

        node = source.node
        if node.mute:
            return self._neutral(mat, f"the surface node {_node_label(node)} is muted")
        kind = node.bl_idname
        if kind == 'ShaderNodeBsdfPrincipled':
            return self._principled(mat, node)
        if kind == 'ShaderNodeBsdfDiffuse':
            return self._diffuse(mat, node)
        if kind == 'ShaderNodeEmission':
            return self._emission(mat, node)
        return self._neutral(
            mat, f"the surface shader {_node_label(node)} is not supported "
                 f"(Torrance reads Principled BSDF, Diffuse BSDF and Emission)")

    def _principled(self, mat, node):
        d = DEFAULT_MATERIAL
        v = self._socket_value
        out = dict(
            base_color=_color3(v(mat, node, "Base Color", d['base_color']), d['base_color']),
            metallic=_clamp(_finite_or(v(mat, node, "Metallic", d['metallic']), d['metallic']), 0.0, 1.0),
            roughness=_clamp(_finite_or(v(mat, node, "Roughness", d['roughness']), d['roughness']), 0.0, 1.0),
            specular=max(0.0, _finite_or(v(mat, node, "Specular", d['specular']), d['specular'])),
            emission=_color3(v(mat, node, "Emission", d['emission']), d['emission']),
            emission_strength=_finite_or(v(mat, node, "Emission Strength", 1.0), 0.0),
            specular_tint=_clamp(_finite_or(v(mat, node, "Specular Tint", 0.0), 0.0), 0.0, 1.0),
        )
        ignored = []
        for name, neutral in _IGNORED_PRINCIPLED_INPUTS:
            socket = node.inputs.get(name)
            if socket is None:
                continue
            if socket.is_linked or abs(_finite_or(socket.default_value, neutral) - neutral) > 1e-6:
                ignored.append(name)
        normal = node.inputs.get("Normal")
        if normal is not None and _follow(normal) is not None:
            ignored.append("Normal")
        if ignored:
            self.reporter.warning(
                f"Material '{mat.name}': Torrance ignores the Principled BSDF input(s) "
                f"{', '.join(ignored)}")
        return _sanitize(out)

    def _diffuse(self, mat, node):
        d = DEFAULT_MATERIAL
        color = _color3(self._socket_value(mat, node, "Color", d['base_color']), d['base_color'])
        return _sanitize(dict(d, base_color=color, metallic=0.0, specular=0.0, roughness=1.0))

    def _emission(self, mat, node):
        d = DEFAULT_MATERIAL
        color = _color3(self._socket_value(mat, node, "Color", (1.0, 1.0, 1.0)), (1.0, 1.0, 1.0))
        strength = _finite_or(self._socket_value(mat, node, "Strength", 1.0), 1.0)
        return _sanitize(dict(d, base_color=(0.0, 0.0, 0.0), metallic=0.0, specular=0.0,
                              emission=color, emission_strength=strength))


def _sanitize(m):
    """Keep values in the ranges the core accepts."""
    m['base_color'] = tuple(_clamp(c, 0.0, 1.0) for c in m['base_color'])
    m['emission'] = tuple(max(0.0, c) for c in m['emission'])
    m['emission_strength'] = max(0.0, m['emission_strength'])
    if m['emission_strength'] == 0.0 or max(m['emission']) == 0.0:
        m['emission'] = (0.0, 0.0, 0.0)
        m['emission_strength'] = 0.0
    return m


class MaterialTable:
    """Adds each Blender material to a tc.Scene once; maps materials to indices."""

    def __init__(self, tc_scene, reporter):
        self.scene = tc_scene
        self.reader = MaterialReader(reporter)
        self.indices = {}
        self._default = None

    def default_index(self):
        if self._default is None:
            self._default = self.scene.add_material(**DEFAULT_MATERIAL)
        return self._default

    def index(self, mat):
        if mat is None:
            return self.default_index()
        key = mat.original.name_full if mat.original is not None else mat.name_full
        idx = self.indices.get(key)
        if idx is None:
            idx = self.scene.add_material(**self.reader.read(mat))
            self.indices[key] = idx
        return idx
