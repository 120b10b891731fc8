# SPDX-License-Identifier: Apache-2.0
"""Volume shaders -> the core's media (Scene.set_material_volume, set_material_volume_program,
set_world_volume).

What feeds the Volume of a Material Output (the medium inside the material's closed meshes) or of
a World Output (the medium around everything) is read as Cycles 3.4 sums volume closures
(svm/closure.h):

* Volume Absorption: absorption (1 - Color) x Density;
* Volume Scatter: scattering Color x Density, Henyey-Greenstein with its Anisotropy;
* Principled Volume: scattering Color x Density, absorption max(1 - Color, 0) x
  max(1 - sqrt(Absorption Color), 0) x Density, emission Emission Strength x Emission Color
  (only a Strength above Cycles' cutoff: a negative one emits nothing) plus the blackbody's
  (Blackbody Intensity, Temperature, Blackbody Tint);
* Volume Coefficients (Blender 5.x): scattering, absorption and emission per metre as given,
  the scattering with the node's phase function;
* Emission (in a Volume socket): emitted radiance per metre Color x Strength, signed (a negative
  one takes light away, as in Cycles);
* Mix Shader (its Fac clamped to [0, 1]) and Add Shader of those.

Coefficients are per metre. With constant inputs they are summed here (a homogeneous medium).
When an input of a material's volume varies through it (Density, Color, Absorption Color,
Emission Strength and Color, Strength, a Mix Shader's Fac fed by textures, maths, ramps ...) the
same sums are compiled into a shader program the core runs at points inside the volume (a
heterogeneous medium; Object and Generated coordinates as volume_space.py says). The phase
functions' inputs (volume_phase.py) and the blackbody's stay constant (one that varies keeps its
own value, reported), as does a World's volume. Surface closures in a Volume socket (Cycles
renders nothing for them either) are reported.
"""

import math
from functools import partial

from .blender_versions import used_node_tree
from .nodes import node_label, source_socket
from .shader_graph.convert_ops import blackbody
from .shader_graph.graph import GraphCompiler, Unsupported
from .shader_graph.program import ProgramBuilder, Value, constant
from .shader_graph.registry import READERS
from .volume_phase import HENYEY_GREENSTEIN, PHASE_INPUTS, node_phase, one_phase
from .volume_space import volume_space
from .volume_sums import CUTOFF, Constants, Program, Varies

_MAX_DEPTH = 64
_STEFAN_BOLTZMANN = 5.670373e-8 * 1e-6 / math.pi   # as Cycles' Principled Volume scales it
# Inputs read as constants in heterogeneous volumes too (one that varies: its own value, reported).
_CONSTANT_INPUTS = PHASE_INPUTS | {"Blackbody Intensity", "Temperature", "Blackbody Tint"}


class VolumeReader:
    """Reads the closure tree feeding a Volume socket; `where` names its owner in messages.
    space: a function giving the VolumeSpace (volume_space.py) of the meshes holding the volume
    (or None), called when an input varies through it (None: a world, whose varying inputs are
    not yet rendered)."""

    def __init__(self, where, textures, reporter, space=None):
        self.where = where
        self.reporter = reporter
        self.textures = textures
        self.space = _once(space) if space is not None else None
        self.values = GraphCompiler(ProgramBuilder(), textures, READERS, volume_shader=True)
        self._warned = set()

    def _warn(self, text):
        """A warning once (a tree read twice, as constants and then as a program)."""
        if text not in self._warned:
            self._warned.add(text)
            self.reporter.warning(text)

    def read(self, socket, weight=1.0):
        """set_material_volume/set_world_volume keywords (sigma_a, sigma_s, emission,
        anisotropy), or with a program set_material_volume_program's (program, registers,
        anisotropy, bounds), or None when nothing renders. weight scales every closure (a
        Volume object's density in object space)."""
        medium = Constants()
        try:
            self._shader(source_socket(socket), weight, medium, 0)
        except Varies:
            space = self.space() if self.space is not None else None
            if space is not None:
                return self._read_program(socket, space, weight)
            medium = Constants()
            self.values = GraphCompiler(ProgramBuilder(), self.textures, READERS,
                                        volume_shader=True)
            self._report_varying = True
            self._shader(source_socket(socket), weight, medium, 0)
        if medium.empty():
            return None
        return dict(sigma_a=tuple(medium.sigma_a), sigma_s=tuple(medium.sigma_s),
                    emission=tuple(medium.emission), **self._phase(medium.lobes))

    _report_varying = False
    _medium = None

    def _read_program(self, socket, space, weight):
        builder = ProgramBuilder()
        self.values = GraphCompiler(builder, self.textures, READERS, volume_shader=True)
        space.apply(self.values)
        medium = Program(builder)
        self._shader(source_socket(socket), weight, medium, 0)
        try:
            return _program_keywords(builder, medium, self._phase(medium.lobes), space)
        except ValueError as exc:
            self._warn(f"{self.where}: {exc}; the volume is left out")
            return None

    def _phase(self, lobes):
        """The phase function keywords of the closures' lobes (volume_phase.one_phase)."""
        return one_phase(lobes, self._warn, self.where)

    def _shader(self, output, weight, medium, depth):
        if output is None or (not isinstance(weight, Value) and weight <= 0.0):
            return
        node = output.node
        if depth > _MAX_DEPTH:
            self._warn(f"{self.where}: shader nodes nested deeper than {_MAX_DEPTH} "
                                  f"at {node_label(node)}; left out")
            return
        if node.mute:
            passed = [link.from_socket for link in node.internal_links
                      if link.to_socket.identifier == output.identifier]
            if passed:
                self._shader(source_socket(passed[0]), weight, medium, depth + 1)
            return
        kind = node.bl_idname
        self._medium = medium
        value = partial(self._value, node)
        if kind == 'ShaderNodeAddShader':
            for s in node.inputs[:2]:
                self._shader(source_socket(s), weight, medium, depth + 1)
        elif kind == 'ShaderNodeMixShader':
            fac = medium.clamp01(value("Fac", 'float'))
            a, b = node.inputs[1:3]
            weight_a, weight_b = medium.mix_weights(weight, fac)
            self._shader(source_socket(a), weight_a, medium, depth + 1)
            self._shader(source_socket(b), weight_b, medium, depth + 1)
        elif kind == 'ShaderNodeVolumeAbsorption':
            density = medium.positive(value("Density", 'float'))
            color = value("Color", 'color')
            medium.add('sigma_a', medium.one_minus(color), medium.times(weight, density))
        elif kind == 'ShaderNodeVolumeScatter':
            density = medium.positive(value("Density", 'float'))
            color = value("Color", 'color')
            medium.scatter(color, self._node_phase(node), medium.times(weight, density))
        elif kind == 'ShaderNodeVolumePrincipled':
            self._principled(node, weight, medium)
        elif kind == 'ShaderNodeVolumeCoefficients':
            self._coefficients(node, weight, medium)
        elif kind == 'ShaderNodeEmission':
            strength = value("Strength", 'float')
            medium.add('emission', value("Color", 'color'), medium.times(weight, strength))
        else:
            self._warn(f"{self.where}: {node_label(node)} is not a volume shader "
                                  f"(Torrance reads Volume Absorption, Volume Scatter, Principled "
                                  f"Volume, Volume Coefficients, Emission, Mix and Add Shader); "
                                  f"left out")

    def _grid(self, node, name, kind):
        """The grid a Principled Volume's `name` (Density/Color/Temperature Attribute) names, at
        the point (VolumeSpace.grid_value), or None where the volume has no such grid (Cycles
        then leaves the input as it is). A grid makes a constant medium vary (Varies)."""
        socket = node.inputs.get(name)
        grid = getattr(socket, "default_value", "") if socket is not None else ""
        space = self.space() if self.space is not None and grid else None
        if space is None or not space.has_grid(grid):
            return None
        if isinstance(self._medium, Constants):
            raise Varies
        return space.grid_value(self.values, grid, kind)

    def _principled(self, node, weight, medium):
        value = partial(self._value, node)
        density = value("Density", 'float')
        grid = self._grid(node, "Density Attribute", 'float')
        if grid is not None:
            density = medium.times(density, grid)
        density = medium.times(medium.positive(density), weight)
        if medium.above_cutoff(density):
            color = value("Color", 'color')
            grid = self._grid(node, "Color Attribute", 'color')
            if grid is not None:
                color = medium.product(color, grid)
            medium.scatter(color, self._node_phase(node), density)
            absorption_color = medium.sqrt_positive(value("Absorption Color", 'color'))
            medium.add('sigma_a', medium.product(medium.one_minus_positive(color),
                                                 medium.one_minus_positive(absorption_color)),
                       density)
        strength = value("Emission Strength", 'float')
        if medium.above_cutoff(strength):       # Cycles: emission only above the cutoff
            medium.add('emission', value("Emission Color", 'color'),
                       medium.times(weight, medium.positive(strength)))
        intensity = value("Blackbody Intensity", 'float')
        grid = self._grid(node, "Temperature Attribute", 'float') if intensity > CUTOFF else None
        if grid is not None:
            self._varying_blackbody(node, weight, medium, intensity, grid)
        elif intensity > CUTOFF:
            kelvin = max(value("Temperature", 'float'), 0.0)
            power = _STEFAN_BOLTZMANN * (1.0 + (kelvin ** 4 - 1.0) * intensity)
            if power > CUTOFF:
                tint = value("Blackbody Tint", 'color')
                rgb = [t * c for t, c in zip(tint, blackbody(kelvin), strict=True)]
                medium.add('emission', rgb, medium.times(weight, power))

    def _coefficients(self, node, weight, medium):
        """Blender 5.x's Volume Coefficients: the coefficients per metre as they are (scattering
        with the node's phase function, absorption, emission), as Cycles 5.x's
        svm_node_volume_coefficients."""
        value = partial(self._value, node)
        medium.scatter(value("Scatter Coefficients", 'color'), self._node_phase(node), weight)
        medium.add('sigma_a', value("Absorption Coefficients", 'color'), weight)
        medium.add('emission', value("Emission Coefficients", 'color'), weight)

    def _varying_blackbody(self, node, weight, medium, intensity, grid):
        """The blackbody's emission with Temperature x max(grid, 0) per point (Cycles' flame
        temperature from an attribute): power sigma (1 + (T^4 - 1) Intensity) x Tint x
        blackbody(T)."""
        kelvin = medium.positive(medium.times(self._value(node, "Temperature", 'float'),
                                              medium.positive(grid)))
        squared = medium.times(kelvin, kelvin)
        fourth = medium.times(squared, squared)
        power = medium.times(medium.times(medium.plus(fourth, -1.0), intensity), _STEFAN_BOLTZMANN)
        power = medium.plus(power, _STEFAN_BOLTZMANN)
        tint = self._value(node, "Blackbody Tint", 'color')
        rgb = medium.product(self.values.builder.emit("Blackbody", 'color', [kelvin]),
                             constant('color', tuple(tint)))
        medium.add('emission', rgb, medium.times(weight, power))

    def _node_phase(self, node):
        return node_phase(node, lambda name: self._value(node, name, 'float'))

    def _read(self, node, name, kind):
        """A closure input's Value; one the graph can not compile keeps its own value,
        reported."""
        socket = node.inputs.get(name)
        if socket is None:
            return constant(kind, 0.0 if kind == 'float' else (0.0, 0.0, 0.0))
        mark = self.values.builder.mark()
        try:
            return self.values.input(socket, kind)
        except Unsupported as exc:
            self._warn(f"{self.where}: input '{name}' of {node_label(node)}: {exc}; "
                                  f"using the socket's own value")
        self.values.builder.rollback(mark)
        return self.values.default(socket, kind)

    def _value(self, node, name, kind):
        """An input as the medium being read takes it (Constants: a number or RGB list, raising
        Varies for one that varies over space unless such inputs are being reported; Program:
        a Value); those Torrance takes as constant (_CONSTANT_INPUTS) a number or RGB list."""
        if name in _CONSTANT_INPUTS:
            return self._constant(node, name, kind)
        medium = self._medium
        read = self._read(node, name, kind)
        if isinstance(medium, Constants) and not read.constant and self._report_varying:
            self._warn(f"{self.where}: input '{name}' of {node_label(node)} varies "
                                  f"through the volume (heterogeneous volumes are rendered only "
                                  f"inside meshes); using the socket's own value")
            read = self.values.default(node.inputs.get(name), kind)
        return medium.value(read, kind)

    def _constant(self, node, name, kind):
        """An input Torrance takes as constant (Anisotropy, the blackbody's): its value; one
        that varies keeps the socket's own value, reported."""
        read = self._read(node, name, kind)
        if not read.constant:
            self._warn(f"{self.where}: input '{name}' of {node_label(node)} varies "
                                  f"through the volume, which Torrance does not yet render for "
                                  f"it; using the socket's own value")
            read = self.values.default(node.inputs.get(name), kind)
        return Constants().value(read, kind)


def _program_keywords(builder, medium, phase, space):
    """set_material_volume_program's keywords of a Program's sums (None: nothing renders);
    ValueError when the program needs more registers than the core has."""
    registers = medium.registers()
    if all(isinstance(r, int) and r == -1 for r in registers.values()):
        return None
    out = {k: r if isinstance(r, int) else builder.register_of(r) for k, r in registers.items()}
    return dict(program=builder.build(), **out, **phase, bounds_min=space.bounds_min,
                bounds_max=space.bounds_max)


def _once(make):
    """make(), called at most once."""
    made = []

    def get():
        if not made:
            made.append(make())
        return made[0]
    return get


def _with_sampling(keywords, owner):
    """A homogeneous volume's keywords with the material's or world's Volume Sampling (Cycles'
    volume_sampling: DISTANCE, EQUIANGULAR or MULTIPLE_IMPORTANCE; defaults Multiple Importance on a
    material, Equiangular on a world); a heterogeneous one's (a 'program') take distance
    sampling only and are left as they are."""
    if keywords is None or 'program' in keywords:
        return keywords
    cycles = getattr(owner, "cycles", None)
    default = 'EQUIANGULAR' if owner.__class__.__name__ == "World" else 'MULTIPLE_IMPORTANCE'
    return dict(keywords, sampling=getattr(cycles, "volume_sampling", default))


def _output_sockets(owner):
    """The (Surface, Volume) input sockets of the output Cycles uses, or None."""
    tree = used_node_tree(owner)
    output = tree.get_output_node('CYCLES') if tree is not None else None
    if output is None:
        return None
    return output.inputs.get("Surface"), output.inputs.get("Volume")


def material_volume(mat, textures, reporter, depsgraph=None, grid_table=None):
    """(set_material_volume keywords without the material, pass_through) for a material whose
    output's Volume is linked to something that renders, else None; keywords with a 'program'
    (its add_shader_program arguments) are set_material_volume_program's (a heterogeneous
    volume). pass_through: its Surface is unlinked (Cycles renders such a surface as a boundary
    rays cross). depsgraph: the one being exported, where a heterogeneous volume's meshes are
    found (volume_space.py); without it the volume is read as homogeneous. grid_table
    (volume_grids.GridTable): where the grids of a smoke domain holding it are added."""
    sockets = _output_sockets(mat) if mat is not None else None
    if sockets is None or sockets[1] is None or source_socket(sockets[1]) is None:
        return None
    where = f"Material '{mat.name}'"
    medium = VolumeReader(where, textures, reporter,
                          space=lambda: volume_space(mat, where, reporter, depsgraph,
                                                     grid_table)).read(sockets[1])
    if medium is None:
        return None
    return _with_sampling(medium, mat), sockets[0] is None or source_socket(sockets[0]) is None


def has_volume(owner):
    """Whether a material's or world's output has a linked Volume."""
    sockets = _output_sockets(owner) if owner is not None else None
    return sockets is not None and sockets[1] is not None and source_socket(sockets[1]) is not None


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
    medium = VolumeReader(f"World '{world.name}'", textures, reporter).read(sockets[1])
    return _with_sampling(medium, world)


def object_volume(mat, where, textures, reporter, space, density=1.0):
    """The volume keywords (as material_volume's first item) of material mat's Volume inside a
    Volume object's VolumeSpace (its grids), its closures scaled by density, or None when nothing
    renders."""
    sockets = _output_sockets(mat)
    if sockets is None or sockets[1] is None or source_socket(sockets[1]) is None:
        return None
    return _with_sampling(VolumeReader(f"{where}, material '{mat.name}'", textures, reporter,
                                       space=lambda: space).read(sockets[1], density), mat)


def default_volume(space, textures, density=1.0):
    """Cycles' default volume (scene/shader.cpp: a Principled Volume of its defaults) inside a
    Volume object without a material: scattering and absorption 0.5 x max(density grid, 0),
    Henyey-Greenstein of anisotropy 0; constant 0.5 without a "density" grid; all scaled by
    density."""
    builder = ProgramBuilder()
    values = GraphCompiler(builder, textures, READERS, volume_shader=True)
    space.apply(values)
    grid = space.grid_value(values, "density", 'float')
    if grid is None:
        return dict(sigma_a=(0.5 * density,) * 3, sigma_s=(0.5 * density,) * 3,
                    emission=(0.0,) * 3, anisotropy=0.0)
    medium = Program(builder)
    density = medium.times(medium.positive(grid), density)
    medium.scatter(constant('color', (0.5, 0.5, 0.5)), (HENYEY_GREENSTEIN, 0.0, 0.0, 0.0),
                   density)
    medium.add('sigma_a', (0.5, 0.5, 0.5), density)
    return _program_keywords(builder, medium, one_phase(medium.lobes, None, ""), space)
