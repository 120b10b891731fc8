# SPDX-License-Identifier: Apache-2.0
"""Node-graph test scenes for the shader graph's agreement tests (test_shader_graph_agreement.py
and one test per node family): a grid of patches seen from straight above, each an Emission
shader whose Color a node graph computes (or a lit material), rendered by Cycles and Torrance.

    def stripes(g):                       # a maker: returns the output socket to show
        tex = g.node("ShaderNodeTexChecker")
        g.link(g.uv(), tex.inputs["Vector"])
        return tex.outputs["Color"]

    agree_on_patches(MAKERS, faults=(...))
"""

import math

import bpy
import numpy as np

from torrance_tools import render_settings, testing
from torrance_tools.scene import node_material
from torrance_tools.seed_noise import agree_within_seed_noise
from torrance_tools.textures import new_image, set_uvs

W, H = 128, 96
ORTHO_SCALE = 4.4
COLUMNS = 4
PATCH, GAP = 1.0, 0.08


class Graph:
    """A node material being built (nodes, links, the shader feeding the output)."""

    def __init__(self, name, surface="ShaderNodeEmission"):
        self.mat, self.nodes, self.links, out = node_material(name)
        self.shader = self.nodes.new(surface)
        self.links.new(self.shader.outputs[0], out.inputs["Surface"])

    def node(self, kind, **settings):
        """A new node of type `kind`; where this Blender removed it (Combine RGB in 5.0), the node
        Blender would open it as."""
        import bpy
        from torrance.shader_graph.node_versions import COLOR_NODE_SUCCESSORS
        if not hasattr(bpy.types, kind) and kind in COLOR_NODE_SUCCESSORS:
            kind, mode = COLOR_NODE_SUCCESSORS[kind]
            settings = dict(mode=mode, **settings)
        n = self.nodes.new(kind)
        for key, value in settings.items():
            setattr(n, key, value)
        return n

    def link(self, a, b):
        self.links.new(a, b)

    @staticmethod
    def socket(node, name):
        """node's input `name`, available or not (Blender 4.x's node.inputs[name] finds only
        available sockets, e.g. not a 1D texture's Vector)."""
        from torrance.shader_graph.node_versions import input_socket
        return input_socket(node, name)

    def uv(self):
        return self.node("ShaderNodeTexCoord").outputs["UV"]

    def image(self, img, interpolation='Linear'):
        return self.node("ShaderNodeTexImage", image=img, interpolation=interpolation)

    def uv_parts(self):
        """The UVs' u and v (a Separate XYZ of the UV)."""
        sep = self.node("ShaderNodeSeparateXYZ")
        self.link(self.uv(), sep.inputs[0])
        return sep.outputs[0], sep.outputs[1]

    def uvw(self):
        """(u - 0.5, v - 0.5, 0.6 u + 0.8 v - 0.5): the UVs as a 3D point that varies in z too."""
        u, v = self.uv_parts()
        comb = self.node("ShaderNodeCombineXYZ")
        self.link(self.math('SUBTRACT', u, value_b=0.5), comb.inputs[0])
        self.link(self.math('SUBTRACT', v, value_b=0.5), comb.inputs[1])
        self.link(self.multiply_add(u, 0.6, self.multiply_add(v, 0.8, -0.5)), comb.inputs[2])
        return comb.outputs[0]

    def uv_affine(self, scale, offset):
        """UV * (scale, scale, 0) + offset, a 3-vector (Vector Math Multiply Add)."""
        m = self.node("ShaderNodeVectorMath", operation='MULTIPLY_ADD')
        self.link(self.uv(), m.inputs[0])
        m.inputs[1].default_value = (scale, scale, 0.0)
        m.inputs[2].default_value = offset
        return m.outputs[0]

    def _set(self, socket, value):
        """Links a socket to `socket`, or sets its default value to a number."""
        if isinstance(value, (int, float)):
            socket.default_value = value
        else:
            self.link(value, socket)

    def multiply_add(self, a, b, c):
        """a * b + c (Math Multiply Add) of sockets or numbers."""
        m = self.node("ShaderNodeMath", operation='MULTIPLY_ADD')
        for k, v in enumerate((a, b, c)):
            self._set(m.inputs[k], v)
        return m.outputs[0]

    def combine(self, r, g, b):
        """A colour of three sockets or numbers (Combine RGB)."""
        comb = self.node("ShaderNodeCombineRGB")
        for k, v in enumerate((r, g, b)):
            self._set(comb.inputs[k], v)
        return comb.outputs[0]

    def math(self, op, a, b=None, value_b=0.5, value_c=0.5, clamp=False):
        m = self.node("ShaderNodeMath", operation=op, use_clamp=clamp)
        self.link(a, m.inputs[0])
        if b is not None:
            self.link(b, m.inputs[1])
        else:
            m.inputs[1].default_value = value_b
        m.inputs[2].default_value = value_c
        return m.outputs[0]


def shader_material(name, surface, settings=None, inputs=None):
    """A material of one shader node of type `surface`: its node properties `settings` and its
    inputs' default values `inputs` (socket name -> value), set in the order given."""
    g = Graph(name, surface=surface)
    for key, value in (settings or {}).items():
        setattr(g.shader, key, value)
    for socket, value in (inputs or {}).items():
        g.shader.inputs[socket].default_value = value
    return g.mat


def make_sharp(node):
    """A Glossy or Glass BSDF made sharp: distribution Sharp (Blender 3.x), or GGX at roughness 0
    (4.x, which has no Sharp: its versioning turns Sharp into that)."""
    if 'SHARP' in node.bl_rna.properties['distribution'].enum_items.keys():
        node.distribution = 'SHARP'
    else:
        node.distribution = 'GGX'
        node.inputs["Roughness"].default_value = 0.0


def test_image():
    """16 x 16 sRGB colours: hue along x, brightness along y."""
    y, x = np.mgrid[0:16, 0:16] / 15.0
    px = np.dstack([0.5 + 0.5 * np.cos(6.28 * x), 0.5 + 0.5 * np.cos(6.28 * (x - 0.33)),
                    0.5 + 0.5 * np.cos(6.28 * (x - 0.67))]) * (0.25 + 0.75 * y[..., None])
    return new_image("Colours", np.dstack([px, np.ones_like(x)]).astype(np.float32))


def image_height(count):
    """The render's height that shows every one of `count` patches at W / ORTHO_SCALE pixels per
    unit: H up to three rows (12 patches); taller for more rows (which fell outside the view
    before), in whole 8-pixel blocks."""
    rows = math.ceil(count / COLUMNS)
    return max(H, 8 * math.ceil(rows * (PATCH + GAP) * W / ORTHO_SCALE / 8))


def _patch_corner(k, rows):
    i, j = k % COLUMNS, k // COLUMNS
    return (i - COLUMNS / 2) * (PATCH + GAP), (rows / 2 - j - 1) * (PATCH + GAP)


def build(scene, makers, lit=()):
    """The grid: one Emission patch per maker (maker(graph) -> the socket shown; the maker's
    name names the material), then one patch per lit material (made by lit's makers, of
    materials), under a sun and a sky; a maker's `setup(obj)`, if it has one, then edits its
    quad (e.g. adds attributes, object_matrix)."""
    height = image_height(len(makers) + len(lit))
    testing.setup_render(scene, width=W, height=height)
    cam = testing.add_camera(scene, location=(0.0, -0.001, 10.0), target=(0.0, 0.0, 0.0))
    cam.data.type = 'ORTHO'
    materials = []
    for make in makers:
        g = Graph(make.__name__)
        g.link(make(g), g.shader.inputs["Color"])
        materials.append(g.mat)
    materials += [make() for make in lit]
    setups = [getattr(make, "setup", None) for make in (*makers, *lit)]
    cam.data.ortho_scale = ORTHO_SCALE * max(W, height) / W    # it spans the longer side
    rows = math.ceil(len(materials) / COLUMNS)
    for k, (mat, setup) in enumerate(zip(materials, setups, strict=True)):
        x0, y0 = _patch_corner(k, rows)
        quad = testing.mesh_object(scene, mat.name, [(x0, y0, 0), (x0 + PATCH, y0, 0),
                                                     (x0 + PATCH, y0 + PATCH, 0),
                                                     (x0, y0 + PATCH, 0)], [(0, 1, 2, 3)], mat)
        set_uvs(quad, [(0, 0), (1, 0), (1, 1), (0, 1)])
        if setup is not None:
            setup(quad)
    testing.add_sun(scene, strength=2.0, rotation=(math.radians(30), 0, math.radians(20)),
                    angle=math.radians(5.0))
    testing.set_world(scene, (0.3, 0.32, 0.35))
    return [m.name for m in materials]


def object_matrix(obj):
    """Gives obj a matrix that turns about a tilted axis, scales unevenly and moves, its mesh
    taken back by the inverse so that the patch stays in place: object space differs from world
    space everywhere, normals and directions transform differently."""
    from mathutils import Matrix, Vector
    k = len(obj.name) % 3
    m = (Matrix.Translation(Vector((0.3, -0.2 + 0.1 * k, 0.5)))
         @ Matrix.Rotation(math.radians(40.0 + 25.0 * k), 4, Vector((0.3, 1.0, 0.6)).normalized())
         @ Matrix.Diagonal((1.6, 0.7, 1.2 + 0.2 * k, 1.0)))
    obj.data.transform(m.inverted())
    obj.matrix_world = m


def turned_uvs(obj, degrees=30.0):
    """obj's UVs (the grid's quad: (0, 0) .. (1, 1)) turned about (0, 0): the UV tangent is
    not an axis."""
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    obj.data.uv_layers.remove(obj.data.uv_layers[0])
    set_uvs(obj, [(c * u - s * v, s * u + c * v) for u, v in ((0, 0), (1, 0), (1, 1), (0, 1))])


def shown(g, vector):
    """0.5 v + 0.5 (Vector Math Multiply Add): a unit vector as a colour."""
    m = g.node("ShaderNodeVectorMath", operation='MULTIPLY_ADD')
    g.link(vector, m.inputs[0])
    m.inputs[1].default_value = (0.5, 0.5, 0.5)
    m.inputs[2].default_value = (0.5, 0.5, 0.5)
    return m.outputs[0]


def patch_means(img, count):
    """Mean RGB of each patch's inner pixels, in the grid's order."""
    rows = math.ceil(count / COLUMNS)
    px = W / ORTHO_SCALE
    height = img.shape[0]
    out = []
    for k in range(count):
        x0, y0 = _patch_corner(k, rows)
        c0, c1 = int(W / 2 + x0 * px) + 3, int(W / 2 + (x0 + PATCH) * px) - 3
        r0, r1 = int(height / 2 - (y0 + PATCH) * px) + 3, int(height / 2 - y0 * px) - 3
        out.append(img[r0:r1, c0:c1, :3].mean(axis=(0, 1)))
    return out


def print_patches(names, directory, samples=64):
    """Per patch, Torrance's and Cycles' means (for finding which patch disagrees)."""
    scene = bpy.context.scene
    render_settings.setup_cycles(scene, samples, 2, seed=1)
    cycles, _ = testing.render(scene, directory, "patches_cycles")
    render_settings.setup_torrance(scene, samples, 2, seed=2)
    torrance, _ = testing.render(scene, directory, "patches_torrance")
    for name, t, c in zip(names, patch_means(torrance, len(names)),
                          patch_means(cycles, len(names)), strict=True):
        print(f"  {name:16s} Torrance {np.round(t, 4)}  Cycles {np.round(c, 4)}")


class DictAttr:
    """One entry of a dict (e.g. the registry's READERS) as an attribute, so that
    agree_within_seed_noise's faults can patch it."""

    def __init__(self, table):
        self.__dict__['_table'] = table

    def __getattr__(self, key):
        return self._table[key]

    def __setattr__(self, key, value):
        self._table[key] = value


def registry_readers():
    """The registry's readers (bl_idname -> reader) as attributes, for faults that patch one."""
    from torrance.shader_graph.registry import READERS
    return DictAttr(READERS)


def _setting(node, key):
    """(owner, attribute) of a read_with key: "socket:Name" an input's default value, "a.b" the
    node's a's b, else the node's attribute."""
    if key.startswith("socket:"):
        return node.inputs[key[len("socket:"):]], "default_value"
    *path, attr = key.split(".")
    owner = node
    for name in path:
        owner = getattr(owner, name)
    return owner, attr


def read_with(settings=None, /, **values):
    """A make_fault for agree_within_seed_noise's (label, owner, attr, make_fault) faults on a
    node reader (e.g. DictAttr(READERS), 'ShaderNodeMath'): each node is read with some of its
    settings changed for that read only, restored after. The settings are `values` and, when
    given, settings(node)'s dict (from the node as it is; None: no change). A key names a
    setting of the node ("operation"), of one of its members ("color_ramp.color_mode"), or, as
    "socket:Name", an input socket's default value:

        read_with(operation='ADD')
        read_with(**{"socket:Scale": 1.0})
        read_with(lambda node: {"feature": 'F1'} if node.feature == 'F2' else None)
    """
    def make_fault(original):
        def read(g, node, socket):
            changes = dict(values)
            if settings is not None:
                changes.update(settings(node) or {})
            saved = []
            try:
                for key, value in changes.items():
                    owner, attr = _setting(node, key)
                    saved.append((owner, attr, getattr(owner, attr)))
                    setattr(owner, attr, value)
                return original(g, node, socket)
            finally:
                for owner, attr, value in reversed(saved):
                    setattr(owner, attr, value)
        return read
    return make_fault


def read_output_as(wrong):
    """A make_fault for a node reader: each output named in `wrong` (identifier -> another
    output's identifier) is read as that other output."""
    def make_fault(original):
        def read(g, node, socket):
            name = wrong.get(socket.identifier)
            return original(g, node, node.outputs[name] if name else socket)
        return read
    return make_fault


def closure_left_out(bl_idname):
    """A make_fault for mixtures.ShaderTreeReader._closure: every closure node of that type is
    left out of the mixture."""
    def make_fault(original):
        def closure(self, node):
            return None if node.bl_idname == bl_idname else original(self, node)
        return closure
    return make_fault


def closure_changed(closure_types, change):
    """A make_fault for mixtures.ShaderTreeReader._closure: every closure of closure_types (the
    core's names, e.g. 'principled_hair') read as change(closure, args) -> (closure, args)."""
    def make_fault(original):
        def closure(self, node):
            out = original(self, node)
            if out is None or out[0] not in closure_types:
                return out
            return change(*out)
        return closure
    return make_fault


def skip_without(bl_idname, what):
    """Exits 77 (ctest's skipped), saying why, where this Blender has no node bl_idname (what:
    its name and the Blender that added it); else returns the registry's readers, patchable
    (DictAttr) for agree_on_patches' faults, with the add-on enabled."""
    import sys
    if not hasattr(bpy.types, bl_idname):
        print(f"SKIPPED: Blender {bpy.app.version_string} has no {what}", flush=True)
        sys.exit(77)
    testing.addon()
    from torrance.shader_graph.registry import READERS
    return DictAttr(READERS)


def agree_on_patches(makers, faults=(), lit=(), what="the shader graph", samples=32):
    """Builds the grid and checks Torrance against Cycles within Cycles' seed-to-seed noise
    (agree_within_seed_noise), printing each patch's means when they disagree."""
    scene = testing.clear_scene()
    names = build(scene, makers, lit)
    directory = testing.tempdir()
    try:
        agree_within_seed_noise(scene, directory, samples, 2, what, faults=faults,
                                tolerance=1.5, ratio_sigmas=3.0, ratio_floor=0.004)
    except AssertionError:
        print_patches(names, directory)
        raise
