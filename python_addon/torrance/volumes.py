# SPDX-License-Identifier: Apache-2.0
"""Volume shaders -> the core's homogeneous media (Scene.set_material_volume, set_world_volume).

What feeds the Volume of a Material Output (the medium inside the material's closed meshes) or of
a World Output (the medium around everything) is read as Cycles 3.4 sums volume closures
(svm/closure.h), with constant inputs:

* Volume Absorption: absorption (1 - Color) x Density;
* Volume Scatter: scattering Color x Density, Henyey-Greenstein with its Anisotropy;
* Principled Volume: scattering Color x Density, absorption max(1 - Color, 0) x
  max(1 - sqrt(Absorption Color), 0) x Density, emission Emission Strength x Emission Color plus
  the blackbody's (Blackbody Intensity, Temperature, Blackbody Tint);
* Emission (in a Volume socket): emitted radiance per metre Color x Strength;
* Mix Shader (its Fac clamped to [0, 1]) and Add Shader of those.

Coefficients are per metre. Scattering closures of different anisotropies become one lobe of
their scattering-weighted mean anisotropy (reported). An input whose graph varies over space
(textures, attributes: heterogeneous volumes) is not yet rendered: it keeps its own value and is
reported; so are phase functions other than Henyey-Greenstein (Blender 4.4+) and surface closures
in a Volume socket (Cycles renders nothing for them either).
"""

import math

from .blender_versions import used_node_tree
from .nodes import node_label, source_socket
from .shader_graph.convert_ops import blackbody
from .shader_graph.graph import GraphCompiler, Unsupported
from .shader_graph.program import ProgramBuilder
from .shader_graph.registry import READERS

_MAX_DEPTH = 64
_CUTOFF = 1e-5                      # Cycles' CLOSURE_WEIGHT_CUTOFF
_STEFAN_BOLTZMANN = 5.670373e-8 * 1e-6 / math.pi   # as Cycles' Principled Volume scales it


class _Medium:
    """Coefficients summed over closures (RGB lists), and the anisotropies by their scattering."""

    def __init__(self):
        self.sigma_a = [0.0, 0.0, 0.0]
        self.sigma_s = [0.0, 0.0, 0.0]
        self.emission = [0.0, 0.0, 0.0]
        self.lobes = []             # (g, mean scattering)

    def add(self, field, rgb, weight):
        target = getattr(self, field)
        for i in range(3):
            target[i] += max(float(rgb[i]), 0.0) * weight

    def scatter(self, rgb, g, weight):
        self.add('sigma_s', rgb, weight)
        mean = sum(max(float(c), 0.0) for c in rgb) * weight / 3.0
        if mean > 0.0:
            self.lobes.append((g, mean))

    def empty(self):
        return max(self.sigma_a + self.sigma_s + self.emission) <= 0.0


class VolumeReader:
    """Reads the closure tree feeding a Volume socket; `where` names its owner in messages."""

    def __init__(self, where, textures, reporter):
        self.where = where
        self.reporter = reporter
        self.values = GraphCompiler(ProgramBuilder(), textures, READERS)

    def read(self, socket):
        """set_material_volume/set_world_volume keywords (sigma_a, sigma_s, emission,
        anisotropy), or None when nothing renders."""
        medium = _Medium()
        self._shader(source_socket(socket), 1.0, medium, 0)
        if medium.empty():
            return None
        total = sum(w for _, w in medium.lobes)
        anisotropy = sum(g * w for g, w in medium.lobes) / total if total > 0.0 else 0.0
        if len({g for g, _ in medium.lobes}) > 1:
            self.reporter.warning(f"{self.where}: scattering closures of different anisotropies "
                                  f"are rendered as one of their mean anisotropy {anisotropy:.3g}")
        return dict(sigma_a=tuple(medium.sigma_a), sigma_s=tuple(medium.sigma_s),
                    emission=tuple(medium.emission),
                    anisotropy=max(-1.0, min(1.0, anisotropy)))

    def _shader(self, output, weight, medium, depth):
        if output is None or weight <= 0.0:
            return
        node = output.node
        if depth > _MAX_DEPTH:
            self.reporter.warning(f"{self.where}: shader nodes nested deeper than {_MAX_DEPTH} "
                                  f"at {node_label(node)}; left out")
            return
        if node.mute:
            passed = [link.from_socket for link in node.internal_links
                      if link.to_socket.identifier == output.identifier]
            if passed:
                self._shader(source_socket(passed[0]), weight, medium, depth + 1)
            return
        kind = node.bl_idname
        if kind == 'ShaderNodeAddShader':
            for s in node.inputs[:2]:
                self._shader(source_socket(s), weight, medium, depth + 1)
        elif kind == 'ShaderNodeMixShader':
            fac = min(max(self._value(node, "Fac", 'float'), 0.0), 1.0)
            a, b = node.inputs[1:3]
            self._shader(source_socket(a), weight * (1.0 - fac), medium, depth + 1)
            self._shader(source_socket(b), weight * fac, medium, depth + 1)
        elif kind == 'ShaderNodeVolumeAbsorption':
            density = max(self._value(node, "Density", 'float'), 0.0)
            color = self._value(node, "Color", 'color')
            medium.add('sigma_a', [1.0 - c for c in color], weight * density)
        elif kind == 'ShaderNodeVolumeScatter':
            self._check_phase(node)
            density = max(self._value(node, "Density", 'float'), 0.0)
            color = self._value(node, "Color", 'color')
            medium.scatter(color, self._value(node, "Anisotropy", 'float'), weight * density)
        elif kind == 'ShaderNodeVolumePrincipled':
            self._principled(node, weight, medium)
        elif kind == 'ShaderNodeEmission':
            strength = self._value(node, "Strength", 'float')
            medium.add('emission', self._value(node, "Color", 'color'), weight * strength)
        else:
            self.reporter.warning(f"{self.where}: {node_label(node)} is not a volume shader "
                                  f"(Torrance reads Volume Absorption, Volume Scatter, Principled "
                                  f"Volume, Emission, Mix and Add Shader); left out")

    def _principled(self, node, weight, medium):
        density = max(self._value(node, "Density", 'float'), 0.0) * weight
        if density > _CUTOFF:
            color = self._value(node, "Color", 'color')
            medium.scatter(color, self._value(node, "Anisotropy", 'float'), density)
            absorption_color = [math.sqrt(max(c, 0.0))
                                for c in self._value(node, "Absorption Color", 'color')]
            medium.add('sigma_a', [max(1.0 - c, 0.0) * max(1.0 - a, 0.0)
                                   for c, a in zip(color, absorption_color, strict=True)], density)
        strength = self._value(node, "Emission Strength", 'float')
        if strength > _CUTOFF:
            medium.add('emission', self._value(node, "Emission Color", 'color'), weight * strength)
        intensity = self._value(node, "Blackbody Intensity", 'float')
        if intensity > _CUTOFF:
            kelvin = max(self._value(node, "Temperature", 'float'), 0.0)
            power = _STEFAN_BOLTZMANN * (1.0 + (kelvin ** 4 - 1.0) * intensity)
            if power > _CUTOFF:
                tint = self._value(node, "Blackbody Tint", 'color')
                rgb = [t * c for t, c in zip(tint, blackbody(kelvin), strict=True)]
                medium.add('emission', rgb, weight * power)

    def _check_phase(self, node):
        phase = getattr(node, "phase", 'HENYEY_GREENSTEIN')
        if phase != 'HENYEY_GREENSTEIN':
            self.reporter.warning(f"{self.where}: the {phase.replace('_', '-').title()} phase "
                                  f"function of {node_label(node)} is not yet rendered; "
                                  f"Henyey-Greenstein with its Anisotropy instead")

    def _value(self, node, name, kind):
        """A closure input's constant value (a float, or an RGB list); an input that varies
        over space or that the graph can not compile keeps its own value, reported."""
        socket = node.inputs.get(name)
        if socket is None:
            return 0.0 if kind == 'float' else [0.0, 0.0, 0.0]
        mark = self.values.builder.mark()
        try:
            value = self.values.input(socket, kind)
        except Unsupported as exc:
            value = None
            self.reporter.warning(f"{self.where}: input '{name}' of {node_label(node)}: {exc}; "
                                  f"using the socket's own value")
        if value is not None and not value.constant:
            value = None
            self.reporter.warning(f"{self.where}: input '{name}' of {node_label(node)} varies "
                                  f"through the volume (heterogeneous volumes are not yet "
                                  f"rendered); using the socket's own value")
        if value is None:
            self.values.builder.rollback(mark)
            value = self.values.default(socket, kind)
        if kind == 'float':
            v = float(value.value[0])
            return v if math.isfinite(v) else 0.0
        return [float(c) if math.isfinite(c) else 0.0 for c in tuple(value.value)[:3]]


def _output_sockets(owner):
    """The (Surface, Volume) input sockets of the output Cycles uses, or None."""
    tree = used_node_tree(owner)
    output = tree.get_output_node('CYCLES') if tree is not None else None
    if output is None:
        return None
    return output.inputs.get("Surface"), output.inputs.get("Volume")


def material_volume(mat, textures, reporter):
    """(set_material_volume keywords without the material, pass_through) for a material whose
    output's Volume is linked to something that renders, else None. pass_through: its Surface
    is unlinked (Cycles renders such a surface as a boundary rays cross)."""
    sockets = _output_sockets(mat) if mat is not None else None
    if sockets is None or sockets[1] is None or source_socket(sockets[1]) is None:
        return None
    medium = VolumeReader(f"Material '{mat.name}'", textures, reporter).read(sockets[1])
    if medium is None:
        return None
    return medium, sockets[0] is None or source_socket(sockets[0]) is None


def has_only_volume(mat):
    """Whether a material's output has a linked Volume and nothing on its Surface."""
    sockets = _output_sockets(mat) if mat is not None else None
    return (sockets is not None and sockets[1] is not None and source_socket(sockets[1]) is not None
            and (sockets[0] is None or source_socket(sockets[0]) is None))


def world_volume(world, textures, reporter):
    """set_world_volume keywords for the world's Volume, or None."""
    sockets = _output_sockets(world) if world is not None else None
    if sockets is None or sockets[1] is None or source_socket(sockets[1]) is None:
        return None
    return VolumeReader(f"World '{world.name}'", textures, reporter).read(sockets[1])
