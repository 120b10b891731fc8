# SPDX-License-Identifier: Apache-2.0
"""docs/nodes.md is what scripts/nodes_doc writes from the shader graph's registry now (regenerate
it after adding a node), and every registry entry names a shader node of this Blender.

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_nodes_doc.py
"""

import os

from torrance_tools import nodes_doc, testing

DOC = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "docs",
                   "nodes.md")


def main():
    testing.addon()
    unknown = nodes_doc.unknown_entries()
    testing.check(not unknown, f"registry entries that are no shader node of this Blender: "
                               f"{unknown}")
    with open(DOC, encoding="utf-8") as f:
        current = f.read()
    testing.check(current == nodes_doc.markdown(),
                  "docs/nodes.md is out of date with the registry: run scripts/nodes_doc")
    print(f"docs/nodes.md current; {current.count('rendered (shader graph)')} nodes rendered by "
          f"the shader graph")


testing.run(main)
