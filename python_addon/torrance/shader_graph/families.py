# SPDX-License-Identifier: Apache-2.0
"""The node families beyond the core ops: each a module with OPCODES (name -> the core's
ShaderOpcode number, in the family's range), FOLDS (the reference twins), READERS (bl_idname ->
reader) and, optionally, VARYING (ops that read the hit). Importing this module adds them all to
program (opcodes, folds) and gives their readers to the registry; adding a family is a line here.
"""

from . import program

# [family imports]
from . import vector  # noqa: I001
from . import voronoi  # noqa: I001
from . import voronoi4  # noqa: I001
from . import convert  # noqa: I001
from . import textures  # noqa: I001
from . import noise  # noqa: I001
from . import noise4  # noqa: I001
from . import gabor  # noqa: I001
from . import radial_tiling  # noqa: I001
from . import geometry  # noqa: I001
from . import local_rays  # noqa: I001
from . import image  # noqa: I001
from . import sky  # noqa: I001
from . import ies  # noqa: I001
from . import point_density  # noqa: I001
from . import particle_info  # noqa: I001

FAMILIES = (
    # [families]
    vector,
    voronoi,
    voronoi4,
    convert,
    textures,
    noise,
    noise4,
    gabor,
    radial_tiling,
    geometry,
    local_rays,
    image,
    sky,
    ies,
    point_density,
    particle_info,
)

READERS = {}
for _family in FAMILIES:
    program.add_family(_family.OPCODES, _family.FOLDS, getattr(_family, "VARYING", ()))
    READERS.update(_family.READERS)
