# SPDX-License-Identifier: Apache-2.0
"""Random node graphs (issue 33): random node trees built in Blender (torrance_tools.
random_node_trees: every node type the shader graph reads, random settings from their RNA enum
items, extreme socket values, links between any value sockets, reroutes, muted nodes, nested
node groups, several outputs) feeding a Principled BSDF's Base Color, Roughness, Metallic and
Emission and a Mix Shader's Fac, compiled by the add-on (GraphCompiler, as materials.py does for
each input) and run by the core (Scene.run_shader_program) at a grid of UVs. For each tree:

  - compiling raises nothing but Unsupported (the add-on's report path), and the add-on's
    MaterialReader reads the material without falling back to "could not be read";
  - every register the core computes, at every point (UVs, positions, normals, incoming
    directions, back faces and attribute values varied), is finite;
  - instruction by instruction the core agrees with program.py's reference twins (program.fold)
    of the same inputs, and the Texture Coordinate, Geometry and Attribute ops give the point's
    globals exactly (the other ops reading the hit are checked for finiteness only).
    Where float and the reference part ways, agreement is not asked:
      * ops whose reference computes in double: inputs beyond 1e4 (as test_shader_program.py)
        or nonzero below 1e-30 (a quotient leaves float's range: Mapping's Normal type of a
        Scale of 1e-38 gives (0, 0, -0) in float, as Cycles' float does, (0, 0, -1) in
        double); and where the reference of the inputs moved by one or two floats agrees (a
        floor or a hue's sextant on the other side: Combine HSV of hue -1/6, h * 6 is -1 in
        float and -1.00000003 in double: (1, 0, 1) against (1, 0, 3e-8));
      * the float32 twins (noise, Voronoi, texture families; within 1e-5, relative and
        absolute: Magic's sin chains reach ~5e-6): inputs beyond 1e18 (Scale x Vector leaves
        float's range and the NaNs of inf - inf meet max(): Voronoi's Chebychev distance keeps
        a number with the core's std::max, NaN with numpy's), and for Magic and Wave beyond
        1e4 (the C library and the reference round sin by an ulp apart; a Distortion of 3e5
        magnifies that to any difference);
  - constant folding: the graph compiled without folding, evaluated by program.evaluate, gives
    each folded constant exactly (but for a White Noise of a -0, which the reader makes +0 only
    when it is a constant, as Cycles gets it), and a graph of constant-only nodes folds to
    constants.

Deterministic: the "ci" profile is derandomized (770 fixed trees; ~25 s of CPU). The "long" profile
(TORRANCE_FUZZ_PROFILE=long, scripts/fuzz) is randomized with TORRANCE_FUZZ_SCALE (20) times the
examples.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_shader_graph_fuzz.py
"""

import collections
import contextlib
import functools
import math
import os

import numpy as np
from hypothesis import HealthCheck, given, note, settings

from torrance_tools import testing
from torrance_tools.addon_access import core_holder, core_proxy
from torrance_tools.random_node_trees import (build_material, catalogue, remove_material,
                                              tree_plans)
from torrance_tools.textures import new_image

PROFILE = os.environ.get("TORRANCE_FUZZ_PROFILE", "ci")
SCALE = 1 if PROFILE == "ci" else int(os.environ.get("TORRANCE_FUZZ_SCALE", "20"))
_QUIET = [HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much]
settings.register_profile("ci", derandomize=True, deadline=None, database=None,
                          suppress_health_check=_QUIET, print_blob=True)
settings.register_profile("long", deadline=None, database=None, suppress_health_check=_QUIET,
                          print_blob=True)
settings.load_profile(PROFILE)
STATS = collections.Counter()     # what the examples covered (printed at the end)

# The shading points: UVs (inside, outside and far outside [0, 1]) and footprints.
UVS = np.array([[0.0, 0.0], [0.5, 0.5], [1.0, 1.0], [0.25, -0.75], [-3.3, 7.1], [1e3, -2e3],
                [1e7, 3e7]], np.float32)
FOOTPRINTS = (0.0, 0.05)
# The points' other globals (run_shader_program's keywords): unit normals and directions, grazing
# and opposed ones among them, back faces and front faces.
_R = 0.5 ** 0.5
HITS = dict(
    positions=np.array([[0, 0, 0], [1, 2, 3], [-5, 0.5, 1e3], [1e6, -1e6, 0], [0.3, 0.3, 0.3],
                        [-1, -1, -1], [1e7, 2e7, -3e7]], np.float32),
    normals=np.array([[0, 0, 1], [0, 0, -1], [1, 0, 0], [0.6, 0.8, 0], [0, 0.6, -0.8],
                      [_R, 0, _R], [0, 1, 0]], np.float32),
    true_normals=np.array([[0, 0, 1], [0, 0, -1], [1, 0, 0], [0, 1, 0], [0, 0.6, -0.8],
                           [0, 0, 1], [0, -1, 0]], np.float32),
    incoming=np.array([[0, 0, 1], [0, 0, 1], [0, 1, 0], [0.6, 0.8, 0], [-1, 0, 0],
                       [0, 0, -1], [_R, _R, 0]], np.float32),
    backfacing=np.array([0, 1, 0, 0, 1, 1, 0], np.float32))
# Attribute layer a at point k (any number of layers): moderate values and extremes.
_ATTRIBUTE_VALUES = np.array([0.0, 0.25, -1.0, 3.5, 1e30, -1e-38, 0.75, 2.0], np.float32)
# Nodes of constants only (none reads the hit when its inputs are unlinked).
CONSTANT_NODES = (
    'ShaderNodeValue', 'ShaderNodeRGB', 'ShaderNodeMath', 'ShaderNodeVectorMath', 'ShaderNodeMix',
    'ShaderNodeMixRGB', 'ShaderNodeInvert', 'ShaderNodeGamma', 'ShaderNodeBrightContrast',
    'ShaderNodeHueSaturation', 'ShaderNodeRGBToBW', 'ShaderNodeSeparateColor',
    'ShaderNodeSeparateRGB', 'ShaderNodeSeparateXYZ', 'ShaderNodeSeparateHSV',
    'ShaderNodeCombineColor', 'ShaderNodeCombineRGB', 'ShaderNodeCombineXYZ',
    'ShaderNodeCombineHSV', 'ShaderNodeValToRGB', 'ShaderNodeRGBCurve', 'ShaderNodeVectorCurve',
    'ShaderNodeFloatCurve', 'ShaderNodeMapRange', 'ShaderNodeClamp', 'ShaderNodeBlackbody',
    'ShaderNodeWavelength', 'ShaderNodeMapping', 'ShaderNodeVectorRotate')


# Nodes reading the hit that the "sources" run puts first in the tree.
HIT_SOURCES = ('ShaderNodeTexCoord', 'ShaderNodeNewGeometry', 'ShaderNodeAttribute',
               'ShaderNodeUVMap', 'ShaderNodeObjectInfo', 'ShaderNodeCameraData',
               'ShaderNodeVertexColor', 'ShaderNodeFresnel', 'ShaderNodeLayerWeight')


def addon_modules():
    from torrance.shader_graph import noise, program, registry, textures, voronoi
    from torrance.shader_graph.graph import KIND_OF_SOCKET, AttributeIds, GraphCompiler, Unsupported
    single = set(noise.OPCODES) | set(voronoi.OPCODES) | set(textures.OPCODES)
    return program, registry, KIND_OF_SOCKET, AttributeIds, GraphCompiler, Unsupported, single


(program, registry, KIND_OF_SOCKET, AttributeIds, GraphCompiler, Unsupported,
 SINGLE_PRECISION) = addon_modules()
# float32 twins whose agreement large inputs undo (chains of sin; see the docstring).
SINE_CHAINS = {"TexMagic", "Wave"}
# Ops that read the hit other than the UV: program.evaluate has no reference for them.
HIT_READERS = set(program.VARYING) - {"TexCoordUV"}


class CoreTextures:
    """The reader's texture table: each image added once to a core Scene."""

    def __init__(self, scene):
        from torrance.reporting import Reporter
        self.scene, self.ids = scene, {}
        # What readers find on the add-on's TextureTable besides texture(): its reporter (here
        # silent: check_material_reader looks at the reports), the depsgraph (None: bpy.context's)
        # and the Point Density nodes' voxels.
        self.reporter = Reporter(None)
        self.reporter.report = lambda level, text: None
        self.depsgraph = None
        self.point_density_grids = {}

    def texture(self, image, interpolation="Linear"):
        from torrance.texture_table import INTERPOLATIONS
        interpolation = INTERPOLATIONS.get(interpolation, "Linear")
        key = (image.name, interpolation)
        if key not in self.ids:
            w, h = image.size
            pixels = np.array(image.pixels[:], np.float32).reshape(h, w, 4)
            self.ids[key] = self.scene.add_texture(pixels, "sRGB", interpolation)
        return self.ids[key]


SKY_TABLES = ("nishita_sky_table", "scattering_sky_table", "hosek_sky_table", "preetham_sky_table")


@contextlib.contextmanager
def sky_tables_once():
    """The add-on's readers get each sky table (a pure function of the node's settings) computed
    once for each set of arguments: every tree is compiled three times (compile_targets,
    check_folding's unfolded compile, the MaterialReader), and a Nishita table costs the core
    ~0.3 s of CPU. The arguments are told apart by their repr (-0.0 from 0.0)."""
    mod = testing.addon()
    holder, core = core_holder(mod), mod.render.load_core()
    proxy = core_proxy(core)

    def once(name):
        compute, tables = getattr(core, name), {}

        def table(*args, **kwargs):
            key = repr((args, sorted(kwargs.items())))
            if key not in tables:
                tables[key] = compute(*args, **kwargs)
            else:
                STATS["sky tables reused"] += 1
            return tables[key]
        return table

    for name in SKY_TABLES:
        if hasattr(core, name):
            setattr(proxy, name, once(name))
    holder._core = proxy
    try:
        yield
    finally:
        holder._core = core


@contextlib.contextmanager
def folding_off():
    """ProgramBuilder.emit folds no op (every op taken as reading the hit) inside."""
    saved = set(program.VARYING)
    program.VARYING.update(program.OPCODE)
    try:
        yield
    finally:
        program.VARYING.clear()
        program.VARYING.update(saved)


def attribute_layers(count):
    """(len(UVS), count, 3) attribute values: layer a at point k, component c."""
    k, a, c = np.meshgrid(np.arange(len(UVS)), np.arange(count), np.arange(3), indexing='ij')
    return _ATTRIBUTE_VALUES[(k + 3 * a + c) % len(_ATTRIBUTE_VALUES)]


def compile_targets(sockets, textures):
    """(builder, attribute ids, the Value of each socket or None where Unsupported) compiled as
    materials.py compiles a closure's inputs: one GraphCompiler per socket, a rollback where
    Unsupported."""
    builder = program.ProgramBuilder()
    attributes = AttributeIds()
    values = []
    for socket in sockets:
        mark = builder.mark()
        try:
            compiler = GraphCompiler(builder, textures, registry.READERS, attributes)
            values.append(compiler.input(socket, KIND_OF_SOCKET[socket.type]))
        except Unsupported as exc:
            note(f"Unsupported ({socket.name}): {exc}")
            STATS["Unsupported inputs"] += 1
            builder.rollback(mark)
            values.append(None)
    return builder, attributes, values


def build_or_limit(builder):
    """builder.build(), or None past the core's register count (the add-on's ValueError)."""
    try:
        return builder.build()
    except ValueError as exc:
        if "Torrance evaluates at most" not in str(exc):
            raise
        note(str(exc))
        return None


def run_in_core(scene, built, footprint, layers):
    constants, code, registers, data = built
    pid = scene.add_shader_program(constants, code, registers, data)
    return scene.run_shader_program(pid, UVS, footprint, attributes=layers, **HITS)


_GEOMETRY_GLOBALS = ("positions", "normals", "true_normals", "incoming")


def hit_reference(name, mode, resource, k, layers):
    """The globals at point k an op reading the hit gives (None: not checked)."""
    if name == "TexCoordUV":
        return (float(UVS[k][0]), float(UVS[k][1]), 0.0, 0.0)
    if name == "Geometry":
        if mode == 4:
            return (float(HITS["backfacing"][k]), 0.0, 0.0, 0.0)
        return (*(float(x) for x in HITS[_GEOMETRY_GLOBALS[mode]][k]), 0.0)
    if name == "Attribute":
        return (*(float(x) for x in layers[k, resource]), 1.0) if resource < layers.shape[1] \
            else (0.0,) * 4
    return None


def _nudged(args):
    """args with every component moved by one and by two floats, down and up."""
    out = []
    for direction in (-np.inf, np.inf):
        moved = np.asarray(args, np.float32)
        for _ in range(2):
            moved = np.nextafter(moved, np.float32(direction))
            out.append([tuple(float(x) for x in a) for a in moved])
    return out


def reference_of(name, mode, flags, resource, args, data):
    """What program.py's reference gives for one instruction (not reading the hit) of the
    core's inputs."""
    table = None
    if resource >= 0:
        table = tuple(data[resource + 1:resource + 1 + int(data[resource])])
    return program.finite(program.fold(name, mode, flags, args, table))


def check_instructions(built, regs, layers):
    """Every instruction's output register, at every point, against the reference of its
    input registers as the core computed them (or the point's globals, for ops reading them)."""
    constants, code, _registers, data = built
    np.testing.assert_array_equal(regs[:, :len(constants)], np.broadcast_to(
        constants, (len(UVS), *constants.shape)), err_msg="the constants' registers")
    low_bits = (1 << program.OFFSET_SHIFT) - 1
    for k in range(len(UVS)):
        got = regs[k]
        for row in code:
            op, mode, flags, resource, out = (int(x) for x in row[:5])
            name = program.OPCODE_NAME[op]
            args = [tuple(float(x) for x in got[i]) for i in row[5:] if i >= 0]
            where = f"{name} mode {mode} flags {flags} args {args} at point {k}"
            if name in program.VARYING:
                want = hit_reference(name, mode, resource, k, layers) \
                    if flags >> program.OFFSET_SHIFT == 0 else None
                if want is not None:
                    np.testing.assert_array_equal(got[out], np.float32(want), err_msg=where)
                continue
            reference = functools.partial(reference_of, name, mode, flags & low_bits, resource,
                                          data=data)
            want = reference(args)
            single = name in SINGLE_PRECISION
            magnitudes = [abs(x) for a in args for x in a]
            extreme = (max(magnitudes, default=0.0) > 1e4 or max(map(abs, want)) > 1e6
                       or any(0.0 < m < 1e-30 for m in magnitudes))
            beyond_float = max(magnitudes, default=0.0) > 1e18
            if (extreme and (not single or name in SINE_CHAINS)) or beyond_float:
                continue    # float's range: the core's float and the reference's double part
            tolerance = dict(rtol=1e-5, atol=1e-5) if single else dict(rtol=2e-4, atol=2e-5)
            if not single and not np.allclose(got[out], want, **tolerance) and any(
                    np.allclose(got[out], reference(nudged), **tolerance)
                    for nudged in _nudged(args)):
                continue    # a discontinuity within float's rounding of the inputs
            np.testing.assert_allclose(got[out], want, err_msg=where, **tolerance)


def check_material_reader(mat, textures):
    """The add-on's own reading: only reports, never a material it "could not read"."""
    from torrance.materials import MaterialReader
    from torrance.reporting import Reporter
    reporter = Reporter(None)
    messages = []
    reporter.report = lambda level, text: messages.append(text)
    MaterialReader(reporter, textures).read(mat)
    for text in messages:
        note(f"reported: {text}")
    broken = [t for t in messages if "could not be read" in t and "evaluates at most" not in t]
    testing.check(not broken, f"the material fell back to the default: {broken}")


def check_folding(sockets, values, textures):
    """The graph compiled without folding, evaluated by the reference, gives each folded
    constant (its kind's components) exactly."""
    with folding_off():
        builder, _ids, unfolded = compile_targets(sockets, textures)
    built = build_or_limit(builder)
    if built is None:
        return
    constants, code, registers, data = built
    regs = program.evaluate(constants, code, registers, (0.5, 0.5), data=data) \
        if not any(program.OPCODE_NAME[int(r[0])] in HIT_READERS for r in code) else None
    if regs is not None and _white_noise_of_minus_zero(code, regs):
        note("a White Noise of a computed -0: folded as +0 (noise._plus_zero), not compared")
        return
    for socket, folded, value in zip(sockets, values, unfolded, strict=True):
        if folded is None or not folded.constant or value is None:
            continue
        got = value.value if value.constant else (regs[builder.register_of(value)]
                                                  if regs is not None else None)
        if got is None:
            continue
        n = 1 if folded.kind == 'float' else 3
        testing.check(tuple(got[:n]) == tuple(folded.value[:n]),
                      f"{socket.name}: folded {folded.value[:n]}, unfolded {tuple(got[:n])}")


def _white_noise_of_minus_zero(code, regs):
    """Whether a White Noise instruction reads a -0. White Noise hashes the bits, and the
    reader makes a constant's -0s +0 (Cycles gets its constants so) but keeps a -0 computed at
    the hit, so folding its input changes its value there, by design."""
    return any(program.OPCODE_NAME[int(row[0])] == "WhiteNoise" and any(
        x == 0.0 and math.copysign(1.0, x) < 0.0 for i in row[5:] if i >= 0 for x in regs[i])
        for row in code)


def check_tree(plan, image, core, constant_only=False):
    mat, groups, sockets = build_material(plan, image)
    try:
        scene = core.Scene()
        textures = CoreTextures(scene)
        builder, attributes, values = compile_targets(sockets, textures)
        if constant_only:
            for socket, value in zip(sockets, values, strict=True):
                testing.check(value is None or value.constant,
                              f"{socket.name}: a graph of constants did not fold")
        check_folding(sockets, values, textures)
        check_material_reader(mat, CoreTextures(core.Scene()))
        built = build_or_limit(builder)
        STATS["trees"] += 1
        STATS["constant inputs"] += sum(1 for v in values if v is not None and v.constant)
        if built is None or len(built[1]) == 0:
            STATS["programs over the register limit"] += built is None
            return
        STATS["programs run"] += 1
        STATS["instructions"] += len(built[1])
        STATS.update(program.OPCODE_NAME[int(r[0])] for r in built[1])
        layers = attribute_layers(len(attributes.ids))
        for footprint in FOOTPRINTS:
            regs = run_in_core(scene, built, footprint, layers)
            bad = np.argwhere(~np.isfinite(regs))
            testing.check(len(bad) == 0, f"non-finite registers (point, register, channel): "
                                         f"{bad[:8].tolist()}")
            check_instructions(built, regs, layers)
    finally:
        remove_material(mat, groups)


def fuzz(types, image, core, examples, constant_only=False, sources=()):
    @settings(max_examples=examples * SCALE)
    @given(plan=tree_plans(types, max_nodes=6 if constant_only else 8, sources=sources))
    def random_trees(plan):
        check_tree(plan, image, core, constant_only)
    random_trees()


def main():
    core = testing.core()
    testing.clear_scene()
    image = new_image("fuzz image", np.random.default_rng(1).random((4, 5, 4)).astype(np.float32))
    types = catalogue(registry.READERS)
    with sky_tables_once():
        fuzz(types, image, core, examples=400)
        fuzz(types, image, core, examples=250, sources=HIT_SOURCES)
        fuzz({k: t for k, t in types.items() if k in CONSTANT_NODES}, image, core,
             examples=120, constant_only=True)
    print("covered:", dict(STATS.most_common()), flush=True)


testing.run(main)
