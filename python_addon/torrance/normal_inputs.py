# SPDX-License-Identifier: Apache-2.0
"""The Normal input of a BSDF node -> add_material()/add_mixture() normal arguments.

Whatever node graph feeds Normal is compiled into the closure's shader program (the
shader_graph's Bump and Normal Map readers, bump.py: a Bump node's Height of any graph,
evaluated at the hit and at the hit moved by the ray differentials as Cycles 3.4 does; Normal
Map in tangent or world space of any Color; chains of them): the result is
{'normal_value': the program's Value}, which the caller turns into a normal register.

Two plain cases keep the image paths of the core (no program needed; the same formulas):

* a tangent-space Normal Map of constant Strength whose Color is an Image Texture at the UVs ->
  normal_texture, normal_strength;
* a Bump node of constant Strength and Distance, its Normal unlinked, whose Height is an Image
  Texture's Color at the UVs (the height is the colour's luminance) -> bump_texture,
  bump_strength, bump_distance (negated when Invert is set).

What can not be compiled is reported and ignored (the surface's own normal).

A Material Output's Displacement is rendered as bump (shader_graph/displacement.py, as Cycles'
"Bump Only"): begin_displacement compiles it first into each closure program, whose reads of the
shading normal (an unlinked Normal, Geometry > Normal) then see the bumped one.
"""

from .nodes import finite_or, node_label, plain_image, source_socket
from .shader_graph.displacement import METHODS, bump_from_displacement, displacement_method
from .shader_graph.graph import GraphCompiler, Unsupported
from .shader_graph.node_versions import cycles4_normals, normal_map_directx
from .shader_graph.registry import READERS


def begin_displacement(reader, mat, builder):
    """Compiles the Displacement of mat's active output as bump into a new closure program
    (builder.shading_normal); reports what it can not render (true displacement, a graph it
    can not compile: then the surface keeps its own normal)."""
    tree = mat.node_tree if mat is not None else None
    output = tree.get_output_node('CYCLES') if tree is not None else None
    socket = output.inputs.get("Displacement") if output is not None else None
    if socket is None or source_socket(socket) is None:
        return
    where = f"Material '{mat.name}': the Displacement of {node_label(output)}"
    method = displacement_method(mat)
    if method != 'BUMP':
        reader.reporter.warning(f"{where}: method '{METHODS.get(method, method)}' - Torrance "
                                f"does no true displacement; rendered as bump (Bump Only)")
    mark = builder.mark()
    try:
        g = GraphCompiler(builder, reader.textures, READERS, reader.attributes)
        builder.shading_normal = bump_from_displacement(g, socket)
    except Unsupported as exc:
        builder.rollback(mark)
        reader.reporter.warning(f"{where}: {exc}; the displacement is ignored")

def normal_source(node):
    """The output socket feeding the Normal input of `node`, or None."""
    socket = node.inputs.get("Normal")
    return source_socket(socket) if socket is not None else None


def read_normal_input(reader, mat, node, builder=None):
    """{} or the normal arguments for the Normal input of `node` (reader: a MaterialReader;
    builder: the ProgramBuilder to compile a graph into, by default the reader's closure
    program)."""
    if builder is None and getattr(reader, "skip_normals", False):
        return {}                     # a mixture's closure: the mixture reads the normal
    builder = builder if builder is not None else reader._program
    socket = node.inputs.get("Normal")
    source = source_socket(socket) if socket is not None else None
    if source is None:
        displaced = builder.shading_normal
        return {} if displaced is None else dict(normal_value=displaced)
    src = source.node
    where = f"Material '{mat.name}': input 'Normal' of {node_label(node)}"
    plain_reader = {'ShaderNodeBump': _plain_bump, 'ShaderNodeNormalMap': _plain_normal_map}.get(
        src.bl_idname)
    # The image-only paths know no displaced shading normal.
    if plain_reader is not None and not src.mute and builder.shading_normal is None:
        plain = plain_reader(reader, mat, src, where)
        if plain is not None:
            return plain
    value = compile_normal(reader, socket, builder, where)
    return {} if value is None else dict(normal_value=value)


def compile_normal(reader, socket, builder, where):
    """The program Value of the node graph feeding the normal input `socket` (compiled into
    `builder`), or None, reported (`where`: the input's description), when it can not be
    compiled or is a constant vector (not a surface Torrance can shade)."""
    mark = builder.mark()
    try:
        value = GraphCompiler(builder, reader.textures, READERS, reader.attributes).input(
            socket, 'vector')
    except Unsupported as exc:
        builder.rollback(mark)
        reader.reporter.warning(f"{where}: {exc}; the normal is ignored")
        return None
    if value.constant:
        builder.rollback(mark)
        reader.reporter.warning(f"{where} is a constant vector; the normal is ignored")
        return None
    return value


def _constant_input(node, name):
    """The value of a float input that is unlinked or fed by a Value node, else None."""
    socket = node.inputs.get(name)
    if socket is None:
        return None
    source = source_socket(socket)
    if source is None:
        return float(socket.default_value)
    if source.node.type == 'VALUE' and not source.node.mute:
        return float(source.default_value)
    return None


def _plain_image(node, name):
    """The Image Texture node feeding input `name` by its Color at the UVs, or None."""
    socket = node.inputs.get(name)
    source = source_socket(socket) if socket is not None else None
    if (source is None or source.node.mute or source.node.bl_idname != 'ShaderNodeTexImage'
            or source.identifier != "Color" or not plain_image(source.node)
            or source.node.projection != 'FLAT'):
        return None
    return source


def _plain_normal_map(reader, mat, src, where):
    strength = _constant_input(src, "Strength")
    image = _plain_image(src, "Color")
    if src.space != 'TANGENT' or normal_map_directx(src) or strength is None or image is None:
        return None                   # read (or reported) by the shader graph
    if cycles4_normals() and finite_or(strength, 1.0) != 1.0:
        return None                   # Cycles 4.x's Strength: the shader graph's NormalMap op
    if src.uv_map:
        reader.reporter.info(f"{where}: {node_label(src)} names UV map '{src.uv_map}'; Torrance "
                             f"uses each mesh's active render UV map")
    strength = finite_or(strength, 1.0)
    tid = reader._image_node(mat, image.node, image, f"input 'Color' of {node_label(src)}")
    if tid is None or strength == 0.0:
        return {}
    return dict(normal_texture=tid, normal_strength=strength)


def _plain_bump(reader, mat, bump, where):
    strength = _constant_input(bump, "Strength")
    distance = _constant_input(bump, "Distance")
    image = _plain_image(bump, "Height")
    if (strength is None or distance is None or image is None
            or source_socket(bump.inputs["Normal"]) is not None):
        return None
    strength = max(0.0, finite_or(strength, 1.0))
    distance = finite_or(distance, 1.0)
    if bump.invert:
        distance = -distance
    tid = reader._image_node(mat, image.node, image, f"input 'Height' of {node_label(bump)}")
    if tid is None or strength == 0.0 or distance == 0.0:
        return {}
    return dict(bump_texture=tid, bump_strength=strength, bump_distance=distance)
