# SPDX-License-Identifier: Apache-2.0
"""Mix Shader / Add Shader trees -> a Torrance mixture (Scene.add_mixture).

The tree under the material's Surface is walked as Cycles' SVM compiles it: a Mix Shader gives
its first Shader input the weight (1 - Fac) and its second Fac (Fac clamped to [0, 1]), an Add
Shader gives both the weight it received. The closures Torrance renders:

* Transparent BSDF (Color): rays pass through by its weight, Cycles' transparency (the other
  closures shade the rest; the core's ClosureType::Transparent);
* Holdout: for camera rays (through transparency) its weight leaves the pixel transparent
  (alpha and colour), as Cycles' holdout closure; it adds no light (the core's
  ClosureType::Holdout);
* Principled BSDF and Glass BSDF (as a lone one is read), Diffuse BSDF (Color, Roughness:
  Lambert or Cycles' Oren-Nayar), Glossy BSDF (Color, Roughness; GGX, Sharp as roughness 0;
  Multiscatter GGX as the Blender's Cycles: 3.x's random walk, 4.x's albedo scaling; Beckmann
  and Ashikhmin-Shirley as Cycles' lobes of theirs; Blender 4.x's Glossy,
  ShaderNodeBsdfAnisotropic, too), Emission;
* Velvet (3.x) / Sheen (4.x: Ashikhmin, Microfiber), Translucent, Refraction, Toon and Ray
  Portal BSDF (closure_nodes.py; rays pass a Ray Portal by its weight, as a Transparent's).

A Mix Shader's Fac may be any graph the shader graph compiles (a constant, an Image Texture's
Color luminance and a Checker Texture of constant inputs at the UVs keep factor kinds of their
own). Up to MAX_CLOSURES closures, MAX_FACTORS factors, MAX_DEPTH nested shader nodes;
what is beyond, and every other shader node, is reported once per node and material and left
out of the sum (it contributes nothing). One Normal input serves all closures: the first
closure's; a closure with a different normal source is reported. Likewise one Coat Normal serves
all coated Principled BSDFs: the first linked one's (compiled into the mixture's program).
"""

import bpy

from .material_values import DEFAULT_MATERIAL, color3, sanitize
from .shader_graph.graph import GraphCompiler, Unsupported
from .shader_graph.program import ProgramBuilder
from .shader_graph.registry import READERS
from .closure_nodes import CLOSURE_NODES, read_closure_node
from .nodes import finite_or, is_default_uv, node_label, plain_image, source_socket
from .normal_inputs import begin_displacement, compile_normal, normal_source, read_normal_input
from .anisotropy import GLOSSY, read_anisotropy
from .shader_graph.node_versions import cycles4_3_diffuse

MAX_CLOSURES = 8          # the core's kMaxMixtureComponents
MAX_FACTORS = 8           # the core's kMaxMixFactors
MAX_DEPTH = 8             # Mix/Add Shader nodes on one path

SHADER_TREE_NODES = {'ShaderNodeMixShader', 'ShaderNodeAddShader'}
# Surfaces read as a mixture (a one-closure one for a lone Diffuse or Glossy BSDF, 3.x's and
# 4.x's node, and closure_nodes.py's): a closure means the same alone and in a Mix.
MIXTURE_SURFACES = SHADER_TREE_NODES | {'ShaderNodeBsdfDiffuse', 'ShaderNodeBsdfGlossy',
                                        'ShaderNodeBsdfAnisotropic', 'ShaderNodeHoldout'} \
    | CLOSURE_NODES
# The Glossy distributions the core renders as lobes of their own (glossy_bsdf.h; else GGX).
_GLOSSY_DISTRIBUTIONS = {'BECKMANN', 'ASHIKHMIN_SHIRLEY'}


def _luminance(c):
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]


class ShaderTreeReader:
    """Reads one material's Mix/Add Shader tree (reader: the MaterialReader, for closures,
    sockets, images and reports)."""

    def __init__(self, reader, mat):
        self.reader = reader
        self.mat = mat
        self.closures = []        # (type, add_material kwargs, terms)
        self.factors = []         # add_mixture factor dicts
        self.normal = None        # the normal arguments of the first closure
        self.normal_from = None
        self.normal_key = None            # (node, output) feeding the first closure's Normal
        self.coat_normal = None           # the first linked Coat Normal's program Value
        self.coat_normal_from = None
        self.coat_normal_key = None
        self.program = ProgramBuilder()   # the factors the shader graph computes
        self.program_factors = {}         # factor index -> its Value in self.program
        begin_displacement(reader, mat, self.program)

    def warn(self, text):
        self.reader.reporter.warning(f"Material '{self.mat.name}': {text}")

    def read(self, node):
        """dict(closures=..., factors=..., normal=...) or None when no closure is left."""
        self._walk(node, [], 0)
        if not self.closures:
            return None
        normal = dict(self.normal or {})
        normal_value = normal.pop('normal_value', None)
        out = dict(closures=self.closures, factors=self.factors, normal=normal)
        if normal_value is not None:
            normal['normal_register'] = self.program.register_of(normal_value)
            if self.program.shading_normal is not None:       # the Displacement's, as bump
                normal['surface_normal_register'] = self.program.register_of(
                    self.program.shading_normal)
        if self.coat_normal is not None:
            normal['coat_normal_register'] = self.program.register_of(self.coat_normal)
        if self.program_factors or normal_value is not None or self.coat_normal is not None:
            out.update(shader_program=self.program.build(),
                       program_reads_uvs=self.program.uses_uvs(),
                       program_attributes=self.reader.attributes.keys_of(self.program))
            for index, value in self.program_factors.items():
                self.factors[index] = dict(kind="program",
                                           register=self.program.register_of(value))
        return out

    def _walk(self, node, terms, depth):
        kind = node.bl_idname
        if kind in SHADER_TREE_NODES:
            if depth >= MAX_DEPTH:
                self.warn(f"{node_label(node)} is nested deeper than {MAX_DEPTH} shader nodes; "
                          f"Torrance leaves it out")
                return
            shaders = [s for s in node.inputs if s.type == 'SHADER']
            if node.mute:             # a muted node passes its first shader through
                self._follow(shaders[0] if shaders else None, terms, depth + 1)
                return
            for s in shaders[:2]:
                if source_socket(s) is None:
                    self.reader.reporter.info(
                        f"Material '{self.mat.name}': a Shader input of {node_label(node)} is "
                        f"empty; it adds nothing (black), as in Cycles")
            if kind == 'ShaderNodeAddShader':
                for s in shaders[:2]:
                    self._follow(s, terms, depth + 1)
                return
            fac = self._factor(node)
            if fac is None:
                return
            first, second = shaders[0], shaders[1]
            if isinstance(fac, float):            # a constant: folded in when it decides alone
                if fac < 1.0:
                    self._follow(first, terms + [('const', 1.0 - fac)], depth + 1)
                if fac > 0.0:
                    self._follow(second, terms + [('const', fac)], depth + 1)
                return
            index = fac
            self._follow(first, terms + [-index - 1], depth + 1)
            self._follow(second, terms + [index], depth + 1)
            return
        if node.mute:
            self.warn(f"the shader {node_label(node)} is muted; Torrance leaves it out")
            return
        self.reader.skip_normals = True   # the mixture reads one normal for all closures
        try:
            closure = self._closure(node)
        finally:
            self.reader.skip_normals = False
        if closure is None:
            return
        if len(self.closures) >= MAX_CLOSURES:
            self.warn(f"{node_label(node)}: more than {MAX_CLOSURES} shaders are mixed; Torrance "
                      f"leaves it out")
            return
        kind_name, args = closure
        source = normal_source(node)
        key = None if source is None else (source.node.as_pointer(), source.identifier)
        if self.normal is None:
            self.normal = read_normal_input(self.reader, self.mat, node, self.program)
            self.normal_from, self.normal_key = node, key
        elif key != self.normal_key:
            self.warn(f"{node_label(node)} has another Normal than {node_label(self.normal_from)}; "
                      f"Torrance uses one normal for all mixed shaders (that of "
                      f"{node_label(self.normal_from)})")
        if node.bl_idname == 'ShaderNodeBsdfPrincipled' and 'coat_weight' in args:
            self._coat_normal(node)
        self.closures.append((kind_name, args, self._resolve(terms)))

    def _coat_normal(self, node):
        """Compiles a coated Principled's linked Clearcoat / Coat Normal into the mixture's
        program: the first one serves all coats; another one is reported."""
        socket = node.inputs.get("Coat Normal") or node.inputs.get("Clearcoat Normal")
        source = source_socket(socket) if socket is not None else None
        if source is None:
            return
        key = (source.node.as_pointer(), source.identifier)
        if self.coat_normal_key is None:
            where = f"Material '{self.mat.name}': input '{socket.name}' of {node_label(node)}"
            value = compile_normal(self.reader, socket, self.program, where)
            if value is not None:
                self.coat_normal, self.coat_normal_from, self.coat_normal_key = value, node, key
        elif key != self.coat_normal_key:
            self.warn(f"{node_label(node)} has another {socket.name} than "
                      f"{node_label(self.coat_normal_from)}; Torrance uses one for all mixed "
                      f"shaders (that of {node_label(self.coat_normal_from)})")

    def _follow(self, socket, terms, depth):
        source = source_socket(socket) if socket is not None else None
        if source is not None:        # an unlinked Shader input adds nothing, as in Cycles
            self._walk(source.node, terms, depth)

    def _resolve(self, terms):
        """Constant terms become constant factors (the core multiplies factors only)."""
        out = []
        for t in terms:
            if isinstance(t, tuple):
                if t[1] >= 1.0:
                    continue
                index = self._add_factor(dict(kind="constant", value=t[1]))
                if index is None:
                    continue
                out.append(index)
            else:
                out.append(t)
        return out

    def _add_factor(self, factor):
        if factor in self.factors:
            return self.factors.index(factor)
        if len(self.factors) >= MAX_FACTORS:
            self.warn(f"more than {MAX_FACTORS} different Mix Shader factors; Torrance treats "
                      f"the others as 1")
            return None
        self.factors.append(factor)
        return len(self.factors) - 1

    # ----------------------------------------------------------------------------------------
    # Mix factors

    def _factor(self, node):
        """A float (constant Fac, clamped to [0, 1]) or the index of a texture factor."""
        reader = self.reader
        socket = node.inputs.get("Fac") or node.inputs[0]
        source = source_socket(socket)
        clamp = lambda v: min(max(v, 0.0), 1.0)  # noqa: E731
        if source is None or source.node.type in {'VALUE', 'RGB'}:
            value = source.default_value if source is not None else socket.default_value
            try:
                value = float(value) if source is None or source.node.type == 'VALUE' \
                    else _luminance(tuple(value))
            except (TypeError, ValueError):
                value = 0.5
            return clamp(value) if value == value else 0.5
        src = source.node
        where = f"the Fac of {node_label(node)}"
        # An Image Texture at the UVs and a Checker Texture at the UVs of constant inputs have
        # factor kinds of their own; anything else is the shader graph's.
        if not src.mute and src.bl_idname == 'ShaderNodeTexImage' \
                and source.identifier == "Color" and plain_image(src):
            tid = reader._image_node(self.mat, src, source, where)
            index = self._add_factor(dict(kind="image", texture=tid)) if tid is not None else None
            return index if index is not None else clamp(float(socket.default_value))
        if not src.mute and src.bl_idname == 'ShaderNodeTexChecker' and _plain_checker(src):
            index = self._add_factor(self._checker(src, source))
            return index if index is not None else clamp(float(socket.default_value))
        value = self._graph_factor(socket, where)
        return value if value is not None else clamp(float(socket.default_value))

    def _graph_factor(self, socket, where):
        """A Fac from its node graph: a float when it folds to a constant, else the index of a
        program factor; None when the graph can not be compiled (reported)."""
        reader = self.reader
        mark = self.program.mark()
        try:
            value = GraphCompiler(self.program, reader.textures, READERS,
                                  reader.attributes).input(socket, 'float')
        except Unsupported as exc:
            self.program.rollback(mark)
            self.warn(f"{where}: {exc}; using the socket's own value")
            return None
        if value.constant:
            v = value.value[0]
            return min(max(v, 0.0), 1.0) if v == v else 0.5
        # A placeholder (unique: _add_factor merges equal factors), its register set by read().
        index = self._add_factor(dict(kind="program", register=-1 - len(self.program_factors)))
        if index is None:
            self.program.rollback(mark)
            return None
        self.program_factors[index] = value
        return index

    def _checker(self, node, output):
        """The factor of a Checker Texture at the UVs with constant inputs (_plain_checker)."""
        constants = {name: node.inputs[name].default_value
                     for name in ("Color1", "Color2", "Scale")}
        scale = float(constants["Scale"]) if constants["Scale"] is not None else 5.0
        if output.identifier == "Fac":
            c1, c2 = 1.0, 0.0
        else:
            c1 = _luminance(tuple(constants["Color1"])[:3])
            c2 = _luminance(tuple(constants["Color2"])[:3])
        return dict(kind="checker", scale=scale, color1=c1, color2=c2)

    # ----------------------------------------------------------------------------------------
    # Closures

    def _closure(self, node):
        reader, mat = self.reader, self.mat
        kind = node.bl_idname
        if kind == 'ShaderNodeBsdfPrincipled':
            args = reader._principled(mat, node)
            for key in ('normal_texture', 'normal_strength', 'bump_texture', 'bump_strength',
                        'bump_distance'):
                args.pop(key, None)         # the mixture's normal serves all closures
            return 'principled', args
        if kind == 'ShaderNodeEmission':
            return 'emission', reader._emission(mat, node)
        if kind == 'ShaderNodeBsdfTransparent':   # rays pass through by its weight
            return 'transparent', reader._transparent(mat, node)
        if kind == 'ShaderNodeHoldout':           # camera rays' alpha taken off by its weight
            return 'holdout', dict(DEFAULT_MATERIAL, base_color=(0.0, 0.0, 0.0), specular=0.0)
        if kind == 'ShaderNodeBsdfGlass':       # a material of its own, as a lone Glass BSDF
            args = reader._glass(mat, node)
            for key in ('normal_texture', 'normal_strength', 'bump_texture', 'bump_strength',
                        'bump_distance'):
                args.pop(key, None)         # the mixture's normal serves all closures
            return 'principled', args
        if kind in ('ShaderNodeBsdfDiffuse', 'ShaderNodeBsdfGlossy', 'ShaderNodeBsdfAnisotropic'):
            return self._colour_roughness(node)
        if kind in CLOSURE_NODES:
            return read_closure_node(reader, mat, node)
        self.warn(f"the shader {node_label(node)} is not supported in a mix (Torrance mixes "
                  f"Principled, Diffuse, Glossy, Glass, Transparent, Holdout, Emission, Velvet / "
                  f"Sheen, Translucent, Refraction, Toon, Principled Hair, Subsurface Scattering, "
                  f"Metallic and Ray Portal); it is left out")
        return None

    def _colour_roughness(self, node):
        reader, mat = self.reader, self.mat
        d = DEFAULT_MATERIAL
        kind = 'diffuse'
        sharp = getattr(node, "distribution", None) == 'SHARP'
        reader._begin_program(mat)
        color, color_tex = reader._socket_input(mat, node, "Color", d['base_color'],
                                                program_input='base_color')
        roughness, roughness_tex = ((0.0, -1) if sharp else reader._socket_input(
            mat, node, "Roughness", 0.0, program_input='roughness'))
        roughness = min(max(finite_or(roughness, 0.0), 0.0), 1.0)
        if cycles4_3_diffuse() and (roughness > 0.0 or node.inputs["Roughness"].is_linked):
            kind = 'diffuse_energy_preserving'  # a rough Diffuse of 4.3+ (at 0 both are Lambert)
        lobe = {}       # the glossy lobe's anisotropy and distribution
        if node.bl_idname in ('ShaderNodeBsdfGlossy', 'ShaderNodeBsdfAnisotropic'):
            kind = 'glossy'
            if not sharp:
                lobe = read_anisotropy(reader, mat, node, GLOSSY)
            # Cycles 4.x's Multiscatter GGX is GGX scaled by its albedo (glossy_bsdf.h);
            # 3.x's is a random walk among the microfacets (multiscatter_glossy_bsdf.h).
            multiscatter = node.distribution == 'MULTI_GGX' and bpy.app.version >= (4, 0, 0)
            lobe['multiscatter_ggx'] = multiscatter
            if node.distribution in _GLOSSY_DISTRIBUTIONS:
                lobe['distribution'] = node.distribution
            if node.distribution == 'MULTI_GGX' and not multiscatter:
                kind = 'glossy_multiscatter_v1'
        args = dict(d, base_color=color3(color, d['base_color']), metallic=0.0, specular=0.0,
                    roughness=roughness, base_color_texture=color_tex,
                    roughness_texture=roughness_tex, **lobe)
        return kind, sanitize(reader._with_program(args))


def _plain_checker(node):
    """A Checker Texture at the UVs whose Color1, Color2 and Scale are unlinked."""
    vector = node.inputs.get("Vector")
    src = source_socket(vector) if vector is not None else None
    return (src is not None and is_default_uv(src)
            and all(source_socket(node.inputs[n]) is None for n in ("Color1", "Color2", "Scale")))


def read_mixture(reader, mat, node):
    """The add_mixture() description of the shader tree at `node`, or None (nothing usable)."""
    return ShaderTreeReader(reader, mat).read(node)
