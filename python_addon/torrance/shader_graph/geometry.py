# SPDX-License-Identifier: Apache-2.0
"""The geometry family: nodes that read the hit (the core's shader_geometry.h, opcodes 96-127):
Geometry, Texture Coordinate, UV Map, Color Attribute, Attribute, Fresnel, Layer Weight, Curves
Info and Point Info (shader_curves_info.h). None
folds: each reads the hit. Mesh attributes (Generated, Object, named UV maps, colour and geometry
attributes) are read through GraphCompiler.attribute (export/mesh_attributes.py's keys)."""

from ..nodes import node_label
from .graph import Unsupported
from .math_ops import VECTOR_MATH_OPS as _VECTOR_MATH
from .program import constant

OPCODES = {"Geometry": 96, "Reflection": 97, "Fresnel": 98, "LayerWeight": 99, "Attribute": 100,
           "Tangent": 101, "LightPath": 106, "CameraTransform": 107,
           "LightFalloff": 109, "Wireframe": 110, "VolumeGrid": 111, "CurvesInfo": 112,
           "PointInfo": 114}
VARYING = set(OPCODES)
FOLDS = {}

# Curves Info outputs -> the CurvesInfo op's mode (all 0 off a hair strand, as Cycles).
_CURVES_INFO = {"Is Strand": 0, "Intercept": 1, "Length": 2, "Thickness": 3, "Tangent Normal": 4,
                "Random": 5}


def _curves_info(g, node, socket):
    mode = _CURVES_INFO.get(socket.identifier)
    if mode is None:
        raise Unsupported(f"{node_label(node)}'s output '{socket.name}' is not supported")
    return g.builder.emit("CurvesInfo", 'vector' if socket.identifier == "Tangent Normal"
                          else 'float', mode=mode)


# Point Info outputs -> the PointInfo op's mode (0 off a point, as Cycles); its Random is the
# point set's ('point_random',) attribute, as Cycles' ATTR_STD_POINT_RANDOM (export/points.py).
_POINT_INFO = {"Position": 0, "Radius": 1}


def _point_info(g, node, socket):
    if socket.identifier == "Random":
        return g.builder.emit("Channel", 'float', [g.attribute(('point_random',))], mode=0)
    mode = _POINT_INFO.get(socket.identifier)
    if mode is None:
        raise Unsupported(f"{node_label(node)}'s output '{socket.name}' is not supported")
    return g.builder.emit("PointInfo", 'vector' if mode == 0 else 'float', mode=mode)


# Geometry outputs -> the Geometry op's mode.
_GEOMETRY = {"Position": 0, "Normal": 1, "True Normal": 2, "Incoming": 3, "Backfacing": 4,
             "Tangent": -1}


def shading_normal(g):
    """Geometry > Normal: the shading normal facing the viewer (an unlinked Normal input); the
    Material Output's Displacement rendered as bump when the program has one (ProgramBuilder.
    shading_normal)."""
    if g.builder.shading_normal is not None:
        return g.builder.shading_normal
    return g.builder.emit("Geometry", 'vector', mode=_GEOMETRY["Normal"])


def object_transform(g):
    """The hit's object transform, four Values for the core's ObjectTransform (shader_vector.h):
    its matrix's columns and location, per-object attribute layers (export/mesh_attributes.py's
    object_info; all 0 where unknown, which the core reads as no object); a light's program
    has its light's matrix (GraphCompiler.object_matrix) as constants."""
    if g.object_matrix is not None:
        m = g.object_matrix
        return [constant('vector', tuple(float(m[r][c]) for r in range(3))) for c in range(4)]
    return [g.attribute(('object_info', k)) for k in ('axis_x', 'axis_y', 'axis_z', 'location')]


# The Vector Transform op's mode for a Point from World to Object (vector.py numbers them).
_POINT_WORLD_TO_OBJECT = (0 * 3 + 0) * 3 + 1


def world_point_to_object(g, point):
    """A world point in the hit's object space (Cycles' object_inverse_position_transform)."""
    return g.builder.emit("VectorTransform", 'vector', [point, *object_transform(g), *[point] * 6],
                          mode=_POINT_WORLD_TO_OBJECT)


def normal_input(g, node, name="Normal"):
    socket = node.inputs.get(name)
    if socket is None or not socket.is_linked:
        return shading_normal(g)
    return g.input(socket, 'vector')


def _geometry(g, node, socket):
    mode = _GEOMETRY.get(socket.identifier)
    if mode is None:
        raise Unsupported(f"{node_label(node)}'s output '{socket.name}' is not supported")
    if mode == _GEOMETRY["Normal"]:
        return shading_normal(g)
    if mode == _GEOMETRY["Tangent"]:
        return default_tangent(g)
    return g.builder.emit("Geometry", 'float' if socket.identifier == "Backfacing" else 'vector',
                          mode=mode)


# The Vector Transform op's mode for a Normal from World to Object (vector.py numbers them).
_NORMAL_WORLD_TO_OBJECT = (2 * 3 + 0) * 3 + 1


def to_object_space(g, n):
    """A world-space normal n in the object's space as Cycles' object_inverse_normal_transform:
    normalize(M^T n) (the Vector Transform op's Normal with Cycles 4.x's normal transform,
    flags 2, in every Blender); unchanged where there is no object (a world)."""
    return g.builder.emit("VectorTransform", 'vector', [n, *object_transform(g), *[n] * 6],
                          mode=_NORMAL_WORLD_TO_OBJECT, flags=2)


def object_space_normal(g):
    """Texture Coordinate > Normal: the shading normal in object space, as Cycles' texco."""
    return to_object_space(g, shading_normal(g))


def _instancer_uv(g):
    """The UV the instancer gives an instance (Cycles' dupli_uv; 0 for an object itself)."""
    return g.attribute(('object_info', 'dupli_uv'))


def _texture_coordinate(g, node, socket):
    out = socket.identifier
    if node.from_instancer and out in ("Generated", "UV"):
        # Cycles' dupli coordinates: the instancer's, per instance (0 for an object itself).
        return (g.attribute(('object_info', 'dupli_generated')) if out == "Generated"
                else _instancer_uv(g))
    if out == "Reflection":
        return g.builder.emit("Reflection", 'vector')
    if out == "Normal":
        return object_space_normal(g)
    if node.object is not None and out == "Object":
        return _other_object(g, node)
    if out == "UV":
        return g.builder.emit("TexCoordUV", 'vector')
    if out == "Generated":
        return g.generated()
    if out == "Object":
        return g.attribute(('object',))
    if out == "Camera":
        return _camera_transform(g, node, 3)
    if out == "Window":
        return _camera_transform(g, node, 4)
    raise Unsupported(f"{node_label(node)}'s output '{socket.name}' is not supported")


def _uv_map(g, node, socket):
    if node.from_instancer:
        return _instancer_uv(g)
    if node.uv_map:
        return g.attribute(('uv', node.uv_map))
    return g.builder.emit("TexCoordUV", 'vector')


def _color_attribute(g, node, socket):
    """Color Attribute (Vertex Color) node: a colour attribute by name ('': the render one),
    its Alpha (0 where the mesh has none, as Cycles)."""
    if socket.identifier == "Alpha":
        return g.builder.emit("Channel", 'float', [g.attribute(('color_alpha', node.layer_name))],
                              mode=0)
    return g.attribute(('color', node.layer_name), 'color')


def _view_layer_attribute(node, socket):
    """A View Layer attribute: a constant of the render (export/object_attributes.py)."""
    import bpy
    from ..export.object_attributes import view_layer_attribute
    r, g, b, a = view_layer_attribute(bpy.context.scene, bpy.context.view_layer,
                                      node.attribute_name)
    out = socket.identifier
    if out in ("Fac", "Alpha"):
        return constant('float', (r + g + b) / 3.0 if out == "Fac" else a)
    return constant('vector' if out == "Vector" else 'color', (r, g, b))


def _attribute(g, node, socket):
    """Attribute node: Geometry (a mesh attribute), Object (the object's, then its data's custom
    property or RNA path: per-object constants), Instancer (first the instance's particle
    settings and instancer object: per-instance constants) and View Layer (a constant);
    Color/Vector the attribute, Fac and Alpha as Cycles' svm_node_attr gives them for the
    attribute's type (export/mesh_attributes.py)."""
    kind, name, out = node.attribute_type, node.attribute_name, socket.identifier
    if kind == 'VIEW_LAYER':
        return _view_layer_attribute(node, socket)
    if kind not in ('GEOMETRY', 'OBJECT', 'INSTANCER'):
        raise Unsupported(f"{node_label(node)}: {kind.lower()} attributes are not supported")

    def key(what):
        if kind == 'GEOMETRY':
            return (what, name)
        return ('object_info', ('instancer_' + what if kind == 'INSTANCER' else what, name))

    if out in ("Fac", "Alpha"):
        scalars = g.attribute(key('attribute_fac_alpha'))
        return g.builder.emit("Channel", 'float', [scalars], mode=0 if out == "Fac" else 1)
    return g.attribute(key('attribute'), 'vector' if out == "Vector" else 'color')


# Volume Info outputs -> the grid each reads, as Cycles expands the node into Attribute nodes:
# Color the "color" grid's colour, the others their grid's Fac (a float grid's value, a colour
# grid's average); 0 where there is no such grid (a surface, a volume without it).
_VOLUME_INFO = {"Color": "color", "Density": "density", "Flame": "flame",
                "Temperature": "temperature"}


def _volume_info(g, node, socket):
    name = _VOLUME_INFO.get(socket.identifier)
    if name is None:
        raise Unsupported(f"{node_label(node)}'s output '{socket.name}' is not supported")
    if socket.identifier == "Color":
        return g.attribute(('attribute', name), 'color')
    return g.builder.emit("Channel", 'float', [g.attribute(('attribute_fac_alpha', name))], mode=0)


def _fresnel(g, node, socket):
    return g.builder.emit("Fresnel", 'float', [g.input(node.inputs["IOR"], 'float'),
                                               normal_input(g, node)])


def _layer_weight(g, node, socket):
    return g.builder.emit("LayerWeight", 'float',
                          [g.input(node.inputs["Blend"], 'float'), normal_input(g, node)],
                          mode=0 if socket.identifier == "Fresnel" else 1)


# Light Path outputs -> the LightPath op's mode (shader_geometry.h).
_LIGHT_PATH = {"Is Camera Ray": 0, "Is Shadow Ray": 1, "Is Diffuse Ray": 2, "Is Glossy Ray": 3,
               "Is Singular Ray": 4, "Is Reflection Ray": 5, "Is Transmission Ray": 6,
               "Ray Length": 7, "Ray Depth": 8, "Diffuse Depth": 9, "Glossy Depth": 10,
               "Transparent Depth": 11, "Transmission Depth": 12, "Portal Depth": 13}


def _light_path(g, node, socket):
    """Light Path: the path's state where the shader runs
    (core/include/torrance/integrator/path_state.h; Is Volume Scatter Ray 0: no volumes)."""
    if socket.identifier == "Is Volume Scatter Ray":
        return constant('float', 0.0)
    mode = _LIGHT_PATH.get(socket.identifier)
    if mode is None:
        raise Unsupported(f"{node_label(node)}'s output '{socket.name}' is not supported")
    return g.builder.emit("LightPath", 'float', mode=mode)


_FALLOFF = {"Quadratic": 0, "Linear": 1, "Constant": 2}


def _light_falloff(g, node, socket):
    """Light Falloff: Strength times the ray length to the power the output says, smoothed
    (core/include/torrance/shader/shader_geometry.h)."""
    mode = _FALLOFF.get(socket.identifier)
    if mode is None:
        raise Unsupported(f"{node_label(node)}'s output '{socket.name}' is not supported")
    args = [g.input(node.inputs[n], 'float') for n in ("Strength", "Smooth")]
    return g.builder.emit("LightFalloff", 'float', args, mode=mode)


def _wireframe(g, node, socket):
    """Wireframe: 1 within Size / 2 of the hit triangle's edges, in metres or (Pixel Size) in
    pixels (core/include/torrance/shader/shader_geometry.h)."""
    size = g.input(node.inputs["Size"], 'float')
    return g.builder.emit("Wireframe", 'float', [size], mode=1 if node.use_pixel_size else 0)


def _scene_camera():
    import bpy
    scene = bpy.context.scene
    return scene, (scene.camera if scene is not None else None)


def camera_rows(which):
    """The rows (four four-float tuples) of the scene camera's world -> camera transform
    (Cycles' camera space: +z ahead, the matrix without scale) or world -> NDC ([0, 1] over the
    frame, its w in the last row); None without a camera."""
    import bpy
    from mathutils import Matrix
    scene, cam = _scene_camera()
    if cam is None:
        return None
    m = cam.matrix_world.normalized()
    to_camera = Matrix.Diagonal((1.0, 1.0, -1.0, 1.0)) @ m.inverted_safe()
    if which == 'camera':
        rows = to_camera
    else:
        r = scene.render
        proj = cam.calc_matrix_camera(bpy.context.evaluated_depsgraph_get(),
                                      x=r.resolution_x, y=r.resolution_y,
                                      scale_x=r.pixel_aspect_x, scale_y=r.pixel_aspect_y)
        clip = proj @ m.inverted_safe()
        rows = [0.5 * (clip[0] + clip[3]), 0.5 * (clip[1] + clip[3]), clip[2], clip[3]]
    return [tuple(float(x) for x in row) for row in rows]


def camera_to_world_rows():
    """The rows (three four-float tuples) of the scene camera's camera -> world transform (the
    inverse of camera_rows('camera')); None without a camera."""
    from mathutils import Matrix
    rows = camera_rows('camera')
    if rows is None:
        return None
    inverse = Matrix(rows).inverted_safe()
    return [tuple(float(x) for x in inverse[i]) for i in range(3)]


def _other_object(g, node):
    """Texture Coordinate > Object of another object (its Object field): the hit's position in
    that object's space, its world matrix at export (CameraTransform's M p with the inverse)."""
    m = node.object.matrix_world.inverted_safe()
    return g.builder.emit("CameraTransform", 'vector',
                          [constant('vector', tuple(m[i])) for i in range(4)], mode=3)


def _camera_transform(g, node, mode):
    rows = camera_rows('ndc' if mode == 4 else 'camera')
    if rows is None:
        raise Unsupported(f"{node_label(node)}: the scene has no camera")
    if g.background:
        # Cycles' background: the camera space of the direction (as if from the camera).
        if mode != 3:
            raise Unsupported(f"{node_label(node)}: only Camera coordinates in a world")
        rows = [(*r[:3], 0.0) for r in rows]
    return g.builder.emit("CameraTransform", 'float' if mode in (1, 2) else 'vector',
                          [constant('vector', r) for r in rows], mode=mode)


_CAMERA_DATA = {"View Vector": 0, "View Z Depth": 1, "View Distance": 2}


def _camera_data(g, node, socket):
    """Camera Data, from the scene camera's transform at export (the viewport's view when it
    is not the camera view is not followed)."""
    return _camera_transform(g, node, _CAMERA_DATA[socket.identifier])


def _normal(g, node, socket):
    """Normal node: Normal its direction (normalised), Dot its dot product with the
    normalised input."""
    d = tuple(node.outputs["Normal"].default_value)
    length = sum(x * x for x in d) ** 0.5
    direction = constant('vector', tuple(x / length for x in d) if length > 0.0 else (0.0,) * 3)
    if socket.identifier == "Normal":
        return direction
    n = g.input(node.inputs["Normal"], 'vector')
    unit = g.builder.emit("VectorMath", 'vector', [n, n, n, constant('float', 0.0)],
                          mode=_VECTOR_MATH.index('NORMALIZE'))
    return g.builder.emit("VectorMath", 'float', [direction, unit, unit, constant('float', 0.0)],
                          mode=_VECTOR_MATH.index('DOT_PRODUCT'), flags=1)


# Object Info outputs -> the per-object attribute key (export/mesh_attributes.py).
_OBJECT_INFO = {"Location": 'location', "Color": 'color', "Alpha": 'alpha',
                "Object Index": 'index', "Random": 'random'}


def _material_pass_index(g, node):
    """The pass index of the material whose tree holds node (or the outermost group node)."""
    import bpy
    tree = g._groups[0].id_data if g._groups else node.id_data
    original = getattr(tree, "original", tree)
    for m in bpy.data.materials:
        if m.node_tree is not None and (m.node_tree == tree or m.node_tree == original):
            return m.pass_index
    return 0


def _object_info(g, node, socket):
    """Object Info: the object's constants as attribute layers (a world-space mesh's; an
    instance's constants, Scene.set_instance_constants, in the final render and the viewport);
    Material Index the material's pass index."""
    out = socket.identifier
    if out == "Material Index":
        return constant('float', float(_material_pass_index(g, node)))
    key = _OBJECT_INFO.get(out)
    if key is None:
        raise Unsupported(f"{node_label(node)}'s output '{socket.name}' is not supported")
    kind = {'location': 'vector', 'color': 'color'}.get(key, 'float')
    value = g.attribute(('object_info', key), 'vector' if kind == 'float' else kind)
    if kind == 'float':
        return g.builder.emit("Channel", 'float', [value], mode=0)
    return value


_TANGENT_AXES = {'X': 0, 'Y': 1, 'Z': 2}


def _tangent(g, node, socket):
    """Tangent: Radial about an axis of the Generated coordinates, or the UV map's tangent (each
    mesh's active render UV map: the hit's UV tangent, as the tangent-space Normal Map reads
    it), through the object's normal transform, perpendicular to the shading normal."""
    if node.direction_type == 'UV_MAP':
        mode, generated = 3, None
    elif node.direction_type == 'RADIAL' and node.axis in _TANGENT_AXES:
        mode, generated = _TANGENT_AXES[node.axis], g.generated()
    else:
        raise Unsupported(f"{node_label(node)}: direction {node.direction_type} {node.axis}")
    return _emit_tangent(g, mode, generated)


def _emit_tangent(g, mode, generated):
    normal = shading_normal(g)
    position = normal if generated is None else generated      # the UV Map mode reads none
    return g.builder.emit("Tangent", 'vector', [position, *object_transform(g), normal],
                          mode=mode)


def default_tangent(g):
    """Geometry > Tangent, which Cycles links to an unlinked Tangent input (the Anisotropic BSDF's,
    4.x's Glossy's): with Generated coordinates (every mesh has them) the Tangent node's Radial Z,
    Cycles' primitive_tangent."""
    return _emit_tangent(g, _TANGENT_AXES['Z'], g.generated())


READERS = {
    'ShaderNodeTangent': _tangent,
    'ShaderNodeLightPath': _light_path,
    'ShaderNodeLightFalloff': _light_falloff,
    'ShaderNodeWireframe': _wireframe,
    'ShaderNodeCameraData': _camera_data,
    'ShaderNodeNormal': _normal,
    'ShaderNodeObjectInfo': _object_info,
    'ShaderNodeNewGeometry': _geometry,
    'ShaderNodeHairInfo': _curves_info,
    'ShaderNodePointInfo': _point_info,
    'ShaderNodeVolumeInfo': _volume_info,
    'ShaderNodeTexCoord': _texture_coordinate,
    'ShaderNodeUVMap': _uv_map,
    'ShaderNodeVertexColor': _color_attribute,
    'ShaderNodeAttribute': _attribute,
    'ShaderNodeFresnel': _fresnel,
    'ShaderNodeLayerWeight': _layer_weight,
}
