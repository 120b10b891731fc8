# SPDX-License-Identifier: Apache-2.0
"""What differs in Blender's Python API between the Blenders that load the add-on (3.4, 4.2, 4.5,
5.0, 5.3), beyond the shader nodes (shader_graph/node_versions.py), in one place; each
difference is named once and told by the API itself where it can be:

  use_nodes   5.0 deprecates Material.use_nodes and World.use_nodes (always on; reading them
              warns), 5.1 Light.use_nodes: used_node_tree gives the tree Blender renders with.
  compositor  5.0 replaces Scene.node_tree (with Scene.use_nodes) by the node group
              Scene.compositing_node_group, and the File Output node's base_path and
              file_slots by directory and file_output_items (its files lose the frame number):
              compositor_tree and exr_file_output give them (for tests and tools).
  depsgraph   5.x flags the geometry of an object whose material changed (its mesh comes
              shading only, as in 4.x): object_geometry_changed tells a real geometry change.
  image formats  5.0 offers the format OPEN_EXR_MULTILAYER only under the media type
              Multi-Layer Image (and OPEN_EXR only under Image): set_multilayer_exr.
  bump terminator  Cycles 5.0 smooths the shadow terminator of bump- and normal-mapped
              surfaces with a microfacet shadowing term (and drops light the smooth and the
              mapped normal put on different sides): cycles5_bump_shadowing, the running
              Blender tells (no setting or node changed).
  denoising features  Cycles 5.3 blends its Denoising Albedo and Normal by the closures'
              roughness (and gives the view layer options Follow Reflections and Albedo Roughness
              Weighting for it); 3.x-5.0 switch: cycles_smooth_denoising_features, told by the
              options' presence.
  volume grids  Debian's Cycles 3.4 (built without NanoVDB) samples a Volume object's grid as a
              dense texture of its active bounding box: voxel i's centre at index i + 0.5 and
              nothing outside the box's voxels (scene/image_vdb.cpp); later Cycles sample NanoVDB
              in index space: cycles_dense_volume_textures (export/volume_objects.py).
  pass names  5.0 names the render passes in words (Cycles' engine.py, the compositor's
              Render Layers sockets, multilayer EXR layers): "Object Index", "Diffuse Direct",
              "Emission" ... for 3.x-4.x's "IndexOB", "DiffDir", "Emit": pass_name.
  light linking  4.0 adds Object.light_linking (receiver and blocker collections) and
              CollectionObject/CollectionChild.light_linking (include/exclude): has_light_linking;
              3.x has none, and the export then sends nothing (export/light_linking.py).
"""


def always_uses_nodes(owner):
    """True where owner's use_nodes is deprecated, i.e. its node tree is always used (5.0+)."""
    prop = owner.bl_rna.properties.get("use_nodes")
    return prop is None or getattr(prop, "is_deprecated", False)


def cycles5_bump_shadowing():
    """True where Cycles smooths bump terminators as 5.x does (RenderSettings'
    microfacet_bump_shadowing; measured in 5.3, 5.0-5.2 taken as 5.3), False for 3.x-4.x's."""
    import bpy
    return bpy.app.version >= (5, 0, 0)


def cycles_smooth_denoising_features():
    """True where Cycles writes the denoising features with 5.3's blended weights
    (RenderSettings' smooth_denoising_features): where its view layer settings have the options
    that came with them (5.0 has not; 5.1-5.2 are not at hand), else from 5.3 on."""
    import bpy
    layer_settings = getattr(bpy.types, "CyclesRenderLayerSettings", None)
    if layer_settings is None:          # Cycles' add-on not loaded
        return bpy.app.version >= (5, 3, 0)
    return "denoising_pass_follow_reflections" in layer_settings.bl_rna.properties


# Blender 5.0's names of the render passes whose 3.x-4.x names are short (Cycles' engine.py).
_PASS_NAMES_SINCE_5 = {
    "IndexOB": "Object Index", "IndexMA": "Material Index", "DiffDir": "Diffuse Direct",
    "DiffInd": "Diffuse Indirect", "DiffCol": "Diffuse Color", "GlossDir": "Glossy Direct",
    "GlossInd": "Glossy Indirect", "GlossCol": "Glossy Color", "TransDir": "Transmission Direct",
    "TransInd": "Transmission Indirect", "TransCol": "Transmission Color", "Emit": "Emission",
    "Env": "Environment", "AO": "Ambient Occlusion",
}


def pass_name(name):
    """The running Blender's name of a render pass Blender 3.x-4.x call `name` (Cycles')."""
    import bpy
    return _PASS_NAMES_SINCE_5.get(name, name) if bpy.app.version >= (5, 0, 0) else name


def cycles_dense_volume_textures():
    """True where Cycles samples OpenVDB grids as dense textures (Blender 3.4, measured against
    Debian's build; later versions taken as NanoVDB's, not yet measured: their bpy wheels have
    no openvdb module)."""
    import bpy
    return bpy.app.version < (3, 5, 0)


def has_light_linking():
    """Whether this Blender has light and shadow linking (Object.light_linking, 4.0+)."""
    import bpy
    return "light_linking" in bpy.types.Object.bl_rna.properties


def used_node_tree(owner):
    """The node tree Blender renders a material, world or light with, or None where it has none
    or does not use it (use_nodes off, before it was deprecated)."""
    tree = owner.node_tree
    if tree is None:
        return None
    return tree if always_uses_nodes(owner) or owner.use_nodes else None


def object_geometry_changed(update, shading_only_data):
    """Whether a depsgraph update of an object changes its geometry. shading_only_data: the
    names of the geometry data reported in the same update with shading only (a material edit);
    an object showing such data without modifiers (which could read the material) keeps its
    geometry though Blender 5 flags it."""
    if not update.is_updated_geometry:
        return False
    obj = update.id
    data = getattr(obj, "data", None)
    return data is None or data.name not in shading_only_data or len(obj.modifiers) > 0


def compositor_tree(scene):
    """The scene's compositor node tree, made (with Blender's default Render Layers and output
    nodes) where the scene has none yet."""
    import bpy
    if not hasattr(scene, "compositing_node_group"):
        scene.use_nodes = True        # Blender 3.4 to 4.5: makes scene.node_tree
        return scene.node_tree
    tree = scene.compositing_node_group
    if tree is None:
        tree = bpy.data.node_groups.new(f"{scene.name} Compositor", 'CompositorNodeTree')
        tree.nodes.new('CompositorNodeRLayers')
        scene.compositing_node_group = tree
    return tree


def exr_file_output(tree, directory, sockets):
    """A File Output node in the compositor `tree` writing each output socket of `sockets` as a
    32-bit OpenEXR named after the socket (with the frame number before Blender 5.0)."""
    out = tree.nodes.new("CompositorNodeOutputFile")
    if hasattr(out, "file_output_items"):
        out.directory = directory
        out.file_name = ""            # else the .blend's name prefixes the files
        out.format.media_type = 'IMAGE'
    else:
        out.base_path = directory
        out.file_slots.clear()
    out.format.file_format = 'OPEN_EXR'
    out.format.color_depth = '32'
    out.format.color_mode = 'RGBA'
    for socket in sockets:
        if hasattr(out, "file_output_items"):
            kind = {'VALUE': 'FLOAT', 'VECTOR': 'VECTOR'}.get(socket.type, 'RGBA')
            out.file_output_items.new(kind, socket.name)
        else:
            out.file_slots.new(socket.name)
        tree.links.new(socket, out.inputs[socket.name])
    return out


def set_multilayer_exr(settings):
    """Image format settings (e.g. scene.render.image_settings) to a multilayer OpenEXR."""
    if hasattr(settings, "media_type"):
        settings.media_type = 'MULTI_LAYER_IMAGE'
    settings.file_format = 'OPEN_EXR_MULTILAYER'
