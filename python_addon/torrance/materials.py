# SPDX-License-Identifier: Apache-2.0
"""Blender materials -> Torrance's metallic/roughness materials.

Torrance has one material model (base colour, metallic, roughness, specular,
emission). It is read from the node that feeds the Surface of the material's
output node (the output Cycles would use):

* Principled BSDF: the sockets Base Color, Metallic, Roughness, Specular,
  Emission and Emission Strength, and Normal (from a tangent-space Normal Map);
  v1's Transmission, IOR, Transmission Roughness and Specular Tint (glass, as Cycles 3.4; each
  from any graph); v2's Transmission Weight (Cycles 4.x's glass closure, from any graph:
  principled_transmission.py);
  Alpha (a value, or an Image Texture's Alpha output: the image's alpha channel);
  Blender 4.x's Principled v2 by its names (Specular IOR Level with IOR, Emission
  Color; _PRINCIPLED_SOCKETS) and, for the PRINCIPLED_V2 model, its IOR, Specular Tint
  colour and distribution (Multiscatter GGX or GGX); the coat (v1 Clearcoat, v2 Coat:
  principled_coat.py); the sheen (v1 Sheen, v2 Sheen Weight: principled_sheen.py); Anisotropic,
  Anisotropic Rotation and Tangent (anisotropy.py); v1's and v2's subsurface (Cycles' Random Walk:
  principled_subsurface.py); v2's Thin Wall (Blender 5.x: principled_thin_wall.py);
* Glass BSDF: Color, Roughness, IOR (GGX or Beckmann; Sharp is roughness 0);
* Transparent BSDF: Color (rays pass straight through, tinted);
* Emission: a black emitter;
* Mix Shader / Add Shader trees of Principled, Diffuse, Glossy BSDF and Emission (and a lone
  Diffuse or Glossy BSDF: a closure means the same alone and in a Mix): a mixture of closures
  (mixtures.py), its Fac any shader graph; a Mix Shader of a Transparent BSDF and another
  shader: that shader with an alpha (transparent_mix.py).

Base Color, Metallic, Roughness, Emission and its strength (and the Color and Roughness of
Diffuse and Glossy BSDF, the Color and Strength of Emission, a lone Principled's Alpha) may come
from any node graph the shader graph compiles (shader_graph/), the Normal from a Bump or Normal
Map node of any graph (normal_inputs.py). Textures are looked up with the mesh's active render UV
map; each image is loaded once per render (texture_table.TextureTable). A socket linked to
something Torrance can not evaluate keeps its own default value and the render reports it once
per material and socket. Anything else (another shader node, no output, nothing linked) becomes
the neutral default material and is reported.
"""


from typing import NamedTuple

import bpy
import numpy as np

from .blender_versions import used_node_tree
from .material_values import DEFAULT_MATERIAL, clamp as _clamp, color3 as _color3, \
    sanitize as _sanitize
from .nodes import finite_or, is_default_uv, node_label, plain_image, source_socket
from .shader_graph.graph import KIND_OF_SOCKET, AttributeIds, GraphCompiler, Unsupported
from .shader_graph.math_ops import VECTOR_MATH_OPS
from .shader_graph.program import ProgramBuilder, constant
from .shader_graph.registry import READERS
from .shader_graph.node_versions import cycles4_microfacets, cycles5_1_anisotropic_glass
from .mixtures import MIXTURE_SURFACES, read_mixture
from .anisotropy import GLOSSY, PRINCIPLED_V1, PRINCIPLED_V2, read_anisotropy
from .normal_inputs import begin_displacement, read_normal_input
from .principled_coat import read_coat
from .shader_aovs import AovPrograms
from .principled_sheen import read_sheen
from .principled_subsurface import read_subsurface
from .principled_specular import read_specular
from .principled_thin_wall import read_thin_wall
from .principled_transmission import read_dispersion, read_transmission
from .thin_film import read_thin_film
from .transparent_mix import read_transparent_mix
from .volume_grids import GridTable
from .volumes import has_only_volume, material_volume

# The Principled BSDF's socket names per node version: v1 is Blender 3.x's, v2 Blender 4.0's
# (renamed sockets; the version is told by the node's sockets, not by bpy.app.version).
#   field             v1 (3.x)         v2 (4.x)
_PRINCIPLED_SOCKETS = {
    'v1': dict(specular="Specular", emission="Emission", specular_tint="Specular Tint"),
    'v2': dict(specular="Specular IOR Level", emission="Emission Color",
               specular_tint="Specular Tint"),
}

# Blender's names of the microfacet distributions, for the reports of a Principled or Glass BSDF
# lobe Torrance renders as GGX.
_DISTRIBUTIONS = {'MULTI_GGX': "Multiscatter GGX", 'BECKMANN': "Beckmann"}


def principled_version(node):
    """'v2' for a Principled BSDF with Blender 4.0's sockets, else 'v1'."""
    return 'v2' if node.inputs.get("Specular IOR Level") is not None else 'v1'


# Nodes whose output is a constant we can read.
_CONSTANT_NODES = {'RGB', 'VALUE'}


# --------------------------------------------------------------------------------------------
# Materials

class MaterialReader:
    """Reads one Blender material into a dict of add_material() arguments."""

    def __init__(self, reporter, textures, attributes=None):
        self.reporter = reporter
        self.textures = textures         # TextureTable (the ui panels: a dry-run stand-in)
        self.attributes = attributes if attributes is not None else AttributeIds()
        self._begin_program(None)

    def _socket_value(self, mat, node, name, fallback):
        """The value of input `name` of `node`: its default, or a constant node it is linked to."""
        value, _texture = self._socket_input(mat, node, name, fallback, textures=False)
        return value

    def _socket_input(self, mat, node, name, fallback, textures=True, image_output="Color",
                      program_input=None):
        """(value, texture id or -1) of input `name` of `node`.

        The value is the socket's default, or what the node graph feeding it gives when that is a
        constant (graphs of constants are folded); the texture, when `textures`, comes from an
        Image Texture node linked to the socket by its `image_output` (Color, or Alpha for Alpha
        sockets; the value then stays the socket's default, used when the image can not be
        loaded). Any other graph is compiled into the closure's shader program when
        `program_input` names the add_material() input it feeds ('base_color', 'metallic',
        'roughness', 'emission'; read by _with_program); elsewhere it is reported.
        """
        socket = node.inputs.get(name)
        if socket is None:
            return fallback, -1
        source = source_socket(socket)
        if source is None:
            return socket.default_value, -1
        src_node = source.node
        if src_node.type in _CONSTANT_NODES and not src_node.mute:
            return source.default_value, -1
        if (textures and src_node.bl_idname == 'ShaderNodeTexImage' and not src_node.mute
                and source.identifier == image_output and plain_image(src_node)):
            tid = self._image_node(mat, src_node, source, f"input '{name}' of {node_label(node)}",
                                   image_output)
            return socket.default_value, (-1 if tid is None else tid)
        return self._graph_input(mat, node, socket, textures and program_input), -1

    def _graph_input(self, mat, node, socket, program_input, constant_in_program=False):
        """The value of a linked input from its node graph: a constant when the graph folds to
        one; else, with program_input, the socket's default (the program computes it).
        constant_in_program: a constant too becomes the program's input (the core reading that
        input from the program only, as the Hair BSDF's Tangent)."""
        where = f"Material '{mat.name}': input '{socket.name}' of {node_label(node)}"
        kind = KIND_OF_SOCKET.get(socket.type, 'float')
        builder = self._program
        mark = builder.mark()
        try:
            value = GraphCompiler(builder, self.textures, READERS, self.attributes).input(socket,
                                                                                         kind)
        except Unsupported as exc:
            builder.rollback(mark)
            self.reporter.warning(f"{where}: {exc}; using the socket's own value")
            return socket.default_value
        if value.constant and not (program_input and constant_in_program):
            return value.value[0] if kind == 'float' else value.value[:len(socket.default_value)]
        if program_input:
            self._program_inputs[program_input] = value
            return socket.default_value
        builder.rollback(mark)
        self.reporter.warning(f"{where} varies over the surface (its node graph reads textures or "
                              f"UVs), which Torrance does not support for this input; using the "
                              f"socket's own value")
        return socket.default_value

    def _program_value(self, mat, node, name, program_input, constant_in_program=False):
        """Input `name`'s value: its default when unlinked (None: no such input), else its
        graph's constant, or the socket's default with the graph compiled into the closure's
        program as `program_input` (_graph_input)."""
        socket = node.inputs.get(name)
        if socket is None or source_socket(socket) is None:
            return None if socket is None else socket.default_value
        return self._graph_input(mat, node, socket, program_input, constant_in_program)

    def _begin_program(self, mat):
        """A new shader program for the closure about to be read (mat's Displacement, as bump,
        first)."""
        self._program = ProgramBuilder()
        self._program_inputs = {}
        begin_displacement(self, mat, self._program)

    def _with_program(self, out):
        """add_material() arguments with the closure's shader program (if it has one); a Normal
        the program computes (read_normal_input's normal_value) becomes normal_register."""
        normal = out.pop('normal_value', None)
        if normal is not None:
            self._program_inputs['normal'] = normal
            if self._program.shading_normal is not None:     # the Displacement's, as bump
                self._program_inputs['surface_normal'] = self._program.shading_normal
        if self._program_inputs:
            for value in self._program_inputs.values():
                if value.constant:          # placed among the program's constants before build
                    self._program.constant_register(value)
            out['shader_program'] = self._program.build()
            out['program_reads_uvs'] = self._program.uses_uvs()
            out['program_attributes'] = self.attributes.keys_of(self._program)
            for key, value in self._program_inputs.items():
                out[f'{key}_register'] = (self._program.constant_register(value) if value.constant
                                          else self._program.register_of(value))
                out.pop(f'{key}_texture', None)
        return out

    def _image_node(self, mat, node, output, where, expected="Color"):
        """The texture id of an Image Texture node feeding `where` by its `expected` output
        (None when unusable)."""
        what = f"Material '{mat.name}': {node_label(node)} (feeding {where})"
        if output.identifier != expected:
            self.reporter.warning(f"{what}: only the {expected} output of an Image Texture is "
                                  f"supported here, not '{output.name}'; using the socket's own "
                                  f"value")
            return None
        if node.image is None:
            self.reporter.warning(f"{what} has no image; using the socket's own value")
            return None
        if expected == "Alpha" and node.image.alpha_mode == 'NONE':
            return None           # Blender's Alpha output is then 1: the socket's own value
        if node.projection != 'FLAT':
            self.reporter.warning(f"{what}: {node.projection.lower()} projection is not supported; "
                                  f"using flat UV mapping")
        if node.extension != 'REPEAT':
            self.reporter.warning(f"{what}: extension '{node.extension.title()}' is not supported; "
                                  f"the image repeats")
        vector = node.inputs.get("Vector")
        if vector is not None:
            src = source_socket(vector)
            if src is not None and src.node.bl_idname == 'ShaderNodeUVMap' and src.node.uv_map \
                    and not src.node.mute:
                self.reporter.info(
                    f"{what}: {node_label(src.node)} names UV map '{src.node.uv_map}'; Torrance "
                    f"uses each mesh's active render UV map here")
            elif src is not None and not is_default_uv(src):
                self.reporter.warning(
                    f"{what}: the Vector input is linked to {node_label(src.node)}, which Torrance "
                    f"does not support here; using the mesh's active render UV map")
        return self.textures.texture(node.image, node.interpolation)

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
        tree = used_node_tree(mat)
        if tree is None:
            # Like Cycles: a material without nodes is a diffuse surface of the viewport colour.
            return dict(DEFAULT_MATERIAL,
                        base_color=_color3(mat.diffuse_color, DEFAULT_MATERIAL['base_color']),
                        specular=0.0, metallic=0.0)

        output = tree.get_output_node('CYCLES')
        if output is None:
            return self._neutral(mat, "no active Material Output node")
        surface = output.inputs.get("Surface")
        source = source_socket(surface) if surface is not None else None
        if source is None:
            if has_only_volume(mat):    # a boundary of its volume (volumes.py), as in Cycles
                return dict(DEFAULT_MATERIAL)
            return self._neutral(mat, "nothing is connected to the Surface of the Material Output")

        node = source.node
        if node.mute:
            return self._neutral(mat, f"the surface node {node_label(node)} is muted")
        kind = node.bl_idname
        if kind == 'ShaderNodeBsdfPrincipled':
            return self._principled(mat, node)
        if kind == 'ShaderNodeBsdfGlass':
            return self._glass(mat, node)
        if kind == 'ShaderNodeBsdfTransparent':
            return self._transparent(mat, node)
        if kind == 'ShaderNodeEmission':
            return self._emission(mat, node)
        if kind in MIXTURE_SURFACES:
            with_alpha = read_transparent_mix(self, mat, node)
            if with_alpha is not None:
                return with_alpha
            mixture = read_mixture(self, mat, node)
            if mixture is None:
                return self._neutral(mat, f"no shader under {node_label(node)} can be rendered")
            return dict(mixture=mixture)
        return self._neutral(
            mat, f"the surface shader {node_label(node)} is not supported (Torrance reads "
                 f"Principled BSDF, Diffuse BSDF, Glossy BSDF, Glass BSDF, Transparent BSDF, "
                 f"Emission, Mix and Add Shader)")

    def _principled(self, mat, node):
        d = DEFAULT_MATERIAL
        v = self._socket_value
        t = self._socket_input
        version = principled_version(node)
        names = _PRINCIPLED_SOCKETS[version]
        self._begin_program(mat)
        base, base_tex = t(mat, node, "Base Color", d['base_color'], program_input='base_color')
        metallic, metallic_tex = t(mat, node, "Metallic", d['metallic'], program_input='metallic')
        roughness, roughness_tex = t(mat, node, "Roughness", d['roughness'],
                                     program_input='roughness')
        emission = {}
        if not self._varying_emission(mat, node, names['emission'], "Emission Strength", emission):
            color, emission_tex = t(mat, node, names['emission'], d['emission'],
                                    program_input='emission')
            emission = dict(emission=_color3(color, d['emission']), emission_texture=emission_tex,
                            emission_strength=finite_or(v(mat, node, "Emission Strength", 1.0),
                                                        0.0))
        # A lone Principled's Alpha from any graph (a mixture's closures' alphas are not read).
        in_mixture = getattr(self, "skip_normals", False)
        alpha, alpha_tex = t(mat, node, "Alpha", 1.0, image_output="Alpha",
                             program_input=None if in_mixture else 'alpha')
        specular = read_specular(self, mat, node, version, names['specular'])
        version_inputs = {}
        glass = {}
        if version == 'v2':
            specular_tint = 0.0            # v1's float; v2's colour is read for PRINCIPLED_V2
            tint = _color3(self._program_value(mat, node, names['specular_tint'],
                                               'specular_tint_color'), (1.0, 1.0, 1.0))
            # Diffuse Roughness (4.3+; any graph): the energy-preserving Oren-Nayar diffuse layer.
            diffuse_roughness = _clamp(finite_or(self._program_value(
                mat, node, "Diffuse Roughness", 'diffuse_roughness'), 0.0), 0.0, 1.0)
            version_inputs = dict(ior=specular['ior'],
                                  specular_tint_color=tuple(max(0.0, c) for c in tint),
                                  multiscatter_ggx=getattr(node, "distribution", "") == 'MULTI_GGX',
                                  **({'diffuse_roughness': diffuse_roughness}
                                     if diffuse_roughness > 0.0 else {}))
            transmission = read_transmission(self, mat, node)
            glass = dict(transmission, **read_thin_wall(self, mat, node),
                         **read_dispersion(self, mat, node, transmission))
        else:
            specular_tint = _clamp(finite_or(self._program_value(
                mat, node, names['specular_tint'], 'specular_tint'), 0.0), 0.0, 1.0)
            metallic_varies = metallic_tex >= 0 or 'metallic' in self._program_inputs
            glass = self._principled_glass(mat, node, metallic, metallic_varies)
            if bpy.app.version < (4, 0, 0) and getattr(node, "distribution", "") == 'MULTI_GGX':
                # Cycles 3.4's Multiscatter GGX: a random walk on the microsurface (principled.h;
                # its glass: multiscatter_glass_bsdf.h; the reflection lobe of a material with
                # glass keeps GGX, reported by _principled_glass).
                version_inputs = dict(multiscatter_walk=True)
        anisotropy = read_anisotropy(self, mat, node,
                                     PRINCIPLED_V2 if version == 'v2' else PRINCIPLED_V1)
        if anisotropy and glass and cycles5_1_anisotropic_glass():
            anisotropy['transmission_anisotropic'] = True
        out = dict(
            base_color=_color3(base, d['base_color']),
            metallic=_clamp(finite_or(metallic, d['metallic']), 0.0, 1.0),
            roughness=_clamp(finite_or(roughness, d['roughness']), 0.0, 1.0),
            specular=specular['specular'],
            specular_tint=specular_tint,
            base_color_texture=base_tex, metallic_texture=metallic_tex,
            roughness_texture=roughness_tex, **emission,
            **version_inputs,
            **glass,
            **read_coat(self, mat, node, version),
            **read_sheen(self, mat, node, version),
            **anisotropy,
            **read_subsurface(self, mat, node, version),
            **(read_thin_film(self, mat, node) if version == 'v2' else {}),
        )
        alpha = _clamp(finite_or(alpha, 1.0), 0.0, 1.0)
        if alpha < 1.0 or alpha_tex >= 0:
            out.update(alpha=alpha, alpha_texture=alpha_tex)
        if version == 'v2' and ('coat_weight' in out or 'sheen_weight' in out):
            # Cycles 4.x: the coat and sheen darken the emission (in a mix of shaders too)
            out['emission_under_layers'] = True
        out.update(read_normal_input(self, mat, node))
        return _sanitize(self._with_program(out))

    def _principled_glass(self, mat, node, metallic, metallic_varies):
        """add_material() glass arguments of a v1 Principled BSDF ({} without transmission), its
        Metallic as _principled read it (`metallic_varies`: from a texture or a program)."""
        transmission = read_transmission(self, mat, node, "Transmission").get('transmission', 0.0)
        if transmission == 0.0:
            return {}
        opaque_part = (transmission < 1.0 or 'transmission' in self._program_inputs
                       or metallic_varies or finite_or(metallic, 0.0) > 0.0)
        if getattr(node, "distribution", 'GGX') != 'GGX' and opaque_part:
            # Cycles 3.4 renders rough (> 0.05) transmission of Multiscatter GGX as its
            # multiple-scattering glass (so does Torrance: multiscatter_glass_bsdf.h) and the
            # specular lobe beside it as its walk too; Torrance renders that lobe as GGX.
            self.reporter.warning(f"Material '{mat.name}': {node_label(node)} with transmission "
                                  f"uses {_DISTRIBUTIONS.get(node.distribution, node.distribution)}"
                                  f"; Torrance renders its specular reflection lobe as GGX")
        refraction_roughness = self._program_value(mat, node, "Transmission Roughness",
                                                   'transmission_roughness')
        return dict(transmission=transmission, ior=self._ior(mat, node, 1.45),
                    transmission_roughness=_clamp(finite_or(refraction_roughness, 0.0), 0.0, 1.0))

    def _ior(self, mat, node, fallback):
        """The IOR socket of `node`, as Cycles uses it (max(IOR, 1e-5)); at most 1000 (any
        graph: the program's ior register where it varies)."""
        ior = finite_or(self._program_value(mat, node, "IOR", 'ior'), fallback)
        return _clamp(ior, 1e-5, 1000.0)

    def _glass(self, mat, node):
        """Glass BSDF: Color (or an Image Texture), Roughness, IOR, 5.x's Thin Film; GGX or
        Beckmann (Sharp = roughness 0) as the running Blender's Cycles renders them: in 3.x two
        closures split by the macro normal's Fresnel, Multiscatter GGX as Cycles 3.4's random walk
        (multiscatter_glass_bsdf.h); in 4.x/5.x one closure with the Fresnel per microfacet, GGX,
        Beckmann and Multiscatter GGX (energy compensation) (principled_glass_v2.h,
        glass_cycles4)."""
        d = DEFAULT_MATERIAL
        self._begin_program(mat)
        color, tex = self._socket_input(mat, node, "Color", (1.0, 1.0, 1.0))
        roughness = _clamp(finite_or(self._socket_value(mat, node, "Roughness", 0.0), 0.0),
                           0.0, 1.0)
        distribution = getattr(node, "distribution", 'GGX')
        cycles4 = cycles4_microfacets()
        walk = distribution == 'MULTI_GGX' and not cycles4
        if distribution == 'SHARP':
            roughness = 0.0
        elif distribution not in ('GGX', 'BECKMANN', 'MULTI_GGX'):
            self.reporter.warning(f"Material '{mat.name}': {node_label(node)} uses "
                                  f"{_DISTRIBUTIONS.get(distribution, distribution)}; Torrance "
                                  f"renders GGX")
        out = dict(d, base_color=_color3(color, (1.0, 1.0, 1.0)), metallic=0.0, specular=0.0,
                   roughness=roughness, glass=True, transmission=1.0,
                   distribution='BECKMANN' if distribution == 'BECKMANN' else 'GGX',
                   ior=self._ior(mat, node, 1.45), base_color_texture=tex,
                   **({'multiscatter_walk': True} if walk else {}),
                   **({'glass_cycles4': True, 'multiscatter_ggx': distribution == 'MULTI_GGX'}
                      if cycles4 else {}),
                   **read_thin_film(self, mat, node))
        if lobe := read_anisotropy(self, mat, node, GLOSSY):   # Blender 5.1+'s Anisotropy
            out.update(lobe, transmission_anisotropic=True)
        out.update(read_normal_input(self, mat, node))
        return _sanitize(self._with_program(out))

    def _transparent(self, mat, node):
        """Transparent BSDF: every ray passes straight through, tinted by Color."""
        color = _color3(self._socket_value(mat, node, "Color", (1.0, 1.0, 1.0)), (1.0, 1.0, 1.0))
        return _sanitize(dict(DEFAULT_MATERIAL, base_color=(0.0, 0.0, 0.0), specular=0.0,
                              alpha=0.0, transparent_color=tuple(_clamp(c, 0.0, 1.0)
                                                                 for c in color)))

    def _emission(self, mat, node):
        d = DEFAULT_MATERIAL
        self._begin_program(mat)
        out = dict(d, base_color=(0.0, 0.0, 0.0), metallic=0.0, specular=0.0)
        if not self._varying_emission(mat, node, "Color", "Strength", out):
            color, tex = self._socket_input(mat, node, "Color", (1.0, 1.0, 1.0),
                                            program_input='emission')
            out.update(emission=_color3(color, (1.0, 1.0, 1.0)), emission_texture=tex,
                       emission_strength=finite_or(self._socket_value(mat, node, "Strength", 1.0),
                                                   1.0))
        return _sanitize(self._with_program(out))

    def _varying_emission(self, mat, node, color_name, strength_name, out):
        """When the node graph varies the emission's strength over the surface: the closure's
        program computes Color x Strength (emission strength 1 in `out`); True then."""
        strength_socket = node.inputs.get(strength_name)
        if strength_socket is None or not strength_socket.is_linked:
            return False
        builder = self._program
        mark = builder.mark()
        compiler = GraphCompiler(builder, self.textures, READERS, self.attributes)
        try:
            strength = compiler.input(strength_socket, 'float')
            if strength.constant:
                builder.rollback(mark)
                return False
            color = compiler.input(node.inputs[color_name], 'color')
        except Unsupported as exc:
            builder.rollback(mark)
            self.reporter.warning(f"Material '{mat.name}': input '{strength_name}' of "
                                  f"{node_label(node)}: {exc}; using the socket's own value")
            return False
        zero = constant('vector', (0.0, 0.0, 0.0))
        self._program_inputs['emission'] = builder.emit(
            "VectorMath", 'color', [color, zero, zero, strength],
            mode=VECTOR_MATH_OPS.index("SCALE"))
        out.update(emission=(1.0, 1.0, 1.0), emission_strength=1.0, emission_texture=-1)
        return True


_TEXTURE_KEYS = ('base_color_texture', 'metallic_texture', 'roughness_texture',
                 'emission_texture', 'normal_texture', 'bump_texture', 'alpha_texture')


def uses_textures(m):
    """Whether add_material() arguments (or a mixture: its closures, texture factors and
    normal) use any texture or UV pattern (the mesh then needs its UVs)."""
    if 'mixture' in m:
        mix = m['mixture']
        return (any(uses_textures(args) for _kind, args, _terms in mix['closures'])
                or any(f['kind'] not in ("constant", "program") for f in mix['factors'])
                or mix.get('program_reads_uvs', False)
                or uses_textures(mix['normal']) or uses_textures(mix.get('alpha', {})))
    return m.get('program_reads_uvs', False) or any(m.get(k, -1) >= 0 for k in _TEXTURE_KEYS)


def attribute_keys(m):
    """The mesh attribute keys add_material() arguments (or a mixture's closures) read."""
    if 'mixture' in m:
        mix = m['mixture']
        return tuple(sorted({k for _kind, args, _terms in mix['closures']
                             for k in attribute_keys(args)} | set(attribute_keys(mix)), key=repr))
    return m.get('program_attributes', ())


def emits(m):
    """Whether add_material() arguments (or any closure of a mixture) emit light."""
    if 'mixture' in m:
        return any(emits(args) for _kind, args, _terms in m['mixture']['closures'])
    strength = m.get("emission_strength", 0.0)
    color = m.get("emission", (0.0, 0.0, 0.0))
    return strength != 0.0 and (any(color) or m.get("emission_texture", -1) >= 0
                                 or m.get("emission_register", -1) >= 0)


class MeshNeeds(NamedTuple):
    """What a mesh must export for its materials: the render UV map, and the attributes their
    shader programs read, as (key, id) pairs (export/mesh_attributes.py's keys, the ids the
    programs name them by). False when nothing. for_uv_pass: the UV map is for the UV pass only
    (no material reads it)."""
    uvs: bool = False
    attributes: tuple = ()
    for_uv_pass: bool = False

    def object_info(self):
        """Whether the materials read Object Info (per-object constants: exported for
        flattened meshes only; instances' shared prototypes read 0)."""
        return any(k[0] == 'object_info' for k, _ in self.attributes)

    def instancers(self):
        """Whether the materials read an Instancer attribute (instancer_record per instance)."""
        return any(k[0] == 'object_info' and isinstance(k[1], tuple)
                   and k[1][0].startswith('instancer_') for k, _ in self.attributes)

    def particles(self):
        """Whether the materials read Particle Info (export/particles.py, per instance)."""
        from .export.mesh_attributes import PARTICLE_KEYS
        return any(k in PARTICLE_KEYS for k, _ in self.attributes)

    def duplis(self):
        """Whether the materials read an instance's instancer coordinates (dupli_record)."""
        return any(k in (('object_info', 'dupli_generated'), ('object_info', 'dupli_uv'))
                   for k, _ in self.attributes)

    @staticmethod
    def of(needs):
        """A MeshNeeds from a MeshNeeds or a bool (UVs or not)."""
        return needs if isinstance(needs, MeshNeeds) else MeshNeeds(bool(needs))

    def __bool__(self):
        return self.uvs or bool(self.attributes)


class MaterialTable:
    """Adds each Blender material to a tc.Scene once; maps materials to indices."""

    def __init__(self, tc_scene, reporter, textures, aovs=(), depsgraph=None):
        self.scene = tc_scene
        # The depsgraph being exported (heterogeneous volumes find their meshes in it; the
        # viewport sets it anew at each update).
        self.depsgraph = depsgraph
        self.varying_volumes = set()   # names of the materials with a heterogeneous volume
        self.volume_grids = GridTable(tc_scene)   # smoke domains' grids (volume_grids.py)
        self.textures = textures
        self.attribute_ids = AttributeIds()
        self.reader = MaterialReader(reporter, self.textures, self.attribute_ids)
        # The view layer's shader AOVs [(name, type)]: the materials' AOV Output programs.
        self.aov_programs = AovPrograms(tc_scene, list(aovs), reporter, textures,
                                        self.attribute_ids)
        self.indices = {}
        self.textured = set()     # indices of materials that use textures
        self.attributes = {}      # index -> the mesh attribute keys its programs read
        self.emissive = set()     # indices of materials that emit light
        self.pass_indices = {}    # index -> Blender's pass index (Material Index pass), if not 0
        self.names = {}           # index -> the material's name (Cryptomatte's Material layer)
        self.uv_pass = False      # the UV pass is on: every mesh exports its render UV map
        self._default = None

    def default_index(self):
        if self._default is None:
            self._default = self.scene.add_material(**DEFAULT_MATERIAL)
        return self._default

    def index(self, mat):
        if mat is None:
            return self.default_index()
        # Never through mat.original: in a final render that is bpy.data's material, which
        # the main thread may delete meanwhile; the evaluated one lives as long as the depsgraph.
        key = mat.as_pointer()
        idx = self.indices.get(key)
        if idx is None:
            args = self.reader.read(mat)
            idx = self._add(args)
            if uses_textures(args):
                self.textured.add(idx)
            keys = attribute_keys(args)
            aov_needs = self.aov_programs.add(mat, idx)
            if aov_needs is not None:
                if aov_needs[0]:
                    self.textured.add(idx)        # its meshes export their UVs
                keys = tuple(sorted(set(keys) | set(aov_needs[1]), key=repr))
            if keys:
                self.attributes[idx] = keys
            if emits(args):
                self.emissive.add(idx)
            if mat.pass_index:
                self.pass_indices[idx] = float(mat.pass_index)
            self.names[idx] = mat.name
            self._add_volume(mat, idx)
            self.indices[key] = idx
        return idx

    def _add_volume(self, mat, idx):
        """The material's volume (volumes.py), if it has one; one that can not be read or that
        the core refuses is reported and left out (the render goes on without it)."""
        try:
            volume = material_volume(mat, self.textures, self.reader.reporter, self.depsgraph,
                                     self.volume_grids)
            if volume is not None and 'program' in volume[0]:
                self.varying_volumes.add(mat.name)
                keywords = dict(volume[0])
                keywords['program'] = self.scene.add_shader_program(*keywords['program'])
                self.scene.set_material_volume_program(idx, **keywords, pass_through=volume[1])
            elif volume is not None:
                self.scene.set_material_volume(idx, **volume[0], pass_through=volume[1])
        except Exception as exc:         # a broken volume must not stop the render
            self.reader.reporter.warning(f"Material '{mat.name}': its volume could not be read "
                                         f"({exc}); it is left out")

    def _add(self, args):
        """Adds add_material() arguments, or a mixture's closures and then the mixture."""
        if 'mixture' not in args:
            return self._add_material(args)
        mix = args['mixture']
        closures = [(kind, self._add_material(a), terms) for kind, a, terms in mix['closures']]
        program = mix.get('shader_program')
        pid = self.scene.add_shader_program(*program) if program is not None else -1
        return self.scene.add_mixture(closures, mix['factors'], **mix['normal'],
                                      **mix.get('alpha', {}), program=pid)

    def _add_material(self, args):
        """add_material() of one closure's arguments, its shader program added first."""
        args = dict(args)
        program = args.pop('shader_program', None)
        args.pop('program_reads_uvs', None)
        args.pop('program_attributes', None)
        if program is not None:
            args['program'] = self.scene.add_shader_program(*program)
        return self.scene.add_material(**args)

    def slot_indices(self, slots):
        """int32 material index per slot (materials or None); one default entry without slots."""
        if not slots:
            return np.array([self.default_index()], dtype=np.int32)
        return np.array([self.index(m) for m in slots], dtype=np.int32)

    def needs_uvs(self, indices):
        """What meshes with these material indices must export (MeshNeeds, false when
        nothing): the render UV map when one uses a texture, and the attributes their
        programs read."""
        keys = set()
        for i in indices:
            keys.update(self.attributes.get(i, ()))
        ids = self.attribute_ids.ids
        textured = any(i in self.textured for i in indices)
        return MeshNeeds(self.uv_pass or textured,
                         tuple((k, ids[k]) for k in sorted(keys, key=repr)),
                         self.uv_pass and not textured)

    def send_pass_indices(self):
        """Gives the core the materials' pass indices (Scene.set_material_pass_indices)."""
        if self.pass_indices:
            values = np.zeros(max(self.pass_indices) + 1, np.float32)
            for idx, value in self.pass_indices.items():
                values[idx] = value
            self.scene.set_material_pass_indices(values)
