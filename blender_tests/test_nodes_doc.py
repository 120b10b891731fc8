# SPDX-License-Identifier: Apache-2.0
"""docs/nodes.md (Blender 3.x; docs/nodes_blender4.2.md in bpy 4.2, docs/nodes_blender5.3.md in
bpy 5.3: nodes_doc.doc_path) is what scripts/nodes_doc writes from the shader graph's registry
now (regenerate them after adding a node: scripts/nodes_doc, scripts/nodes_doc 4.2,
scripts/nodes_doc 5.3), and every registry entry names a shader node of this Blender (or one it
removed or has not yet: node_versions.REMOVED_NODES, ADDED_NODES).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_nodes_doc.py
"""

import os

from torrance_tools import nodes_doc, testing


def main():
    testing.addon()
    unknown = nodes_doc.unknown_entries()
    testing.check(not unknown, f"registry entries that are no shader node of this Blender: "
                               f"{unknown}")
    doc = nodes_doc.doc_path()
    name = os.path.relpath(doc, os.path.dirname(os.path.dirname(doc)))
    with open(doc, encoding="utf-8") as f:
        current = f.read()
    import bpy
    command = "scripts/nodes_doc" + ("" if bpy.app.version < (4, 0, 0) else
                                     " {}.{}".format(*bpy.app.version[:2]))
    testing.check(current == nodes_doc.markdown(),
                  f"{name} is out of date with the registry: run {command}")
    print(f"{name} current; {current.count('rendered (shader graph)')} nodes rendered by "
          f"the shader graph")


testing.run(main)
