# SPDX-License-Identifier: Apache-2.0
"""What differs in Blender's Python API between the Blenders that load the add-on (3.4, 4.2, 4.5,
5.0, 5.3), beyond the shader nodes (shader_graph/node_versions.py), in one place; each
difference is named once and told by the API itself where it can be:

  use_nodes   5.0 deprecates Material.use_nodes and World.use_nodes (always on; reading them
              warns), 5.1 Light.use_nodes: used_node_tree gives the tree Blender renders with.
  compositor  5.0 replaces Scene.node_tree (with Scene.use_nodes) by the node group
              Scene.compositing_node_group: compositor_tree gives it (for tests and tools).
"""


def _always_uses_nodes(owner):
    """True where owner's use_nodes is deprecated, i.e. its node tree is always used (5.0+)."""
    prop = owner.bl_rna.properties.get("use_nodes")
    return prop is None or getattr(prop, "is_deprecated", False)


def used_node_tree(owner):
    """The node tree Blender renders a material, world or light with, or None where it has none
    or does not use it (use_nodes off, before it was deprecated)."""
    tree = owner.node_tree
    if tree is None:
        return None
    return tree if _always_uses_nodes(owner) or owner.use_nodes else None


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
