"""Scene.set_material_volume / set_world_volume (homogeneous volumes, issue 38) through the
module: argument checks."""
import numpy as np
import pytest

import torrance_core as tc


def box(lo, hi):
    """Vertices and outward (counter-clockwise) triangles of an axis-aligned box."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    v = np.array([[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0],
                  [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]], np.float32)
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    tris = [t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))]
    return v, np.array(tris, np.int32)


@pytest.mark.parametrize("kwargs, message", [
    (dict(sigma_a=(-1.0, 0.0, 0.0)), "sigma_a must be finite and not negative"),
    (dict(sigma_s=(0.0, float("nan"), 0.0)), "sigma_s must be finite"),
    (dict(emission=(0.0, 0.0, float("inf"))), "emission must be finite"),
    (dict(anisotropy=1.5), r"anisotropy must be in \[-1, 1\]"),
])
def test_bad_volume_arguments_are_rejected(kwargs, message):
    scene = tc.Scene()
    m = scene.add_material()
    with pytest.raises(ValueError, match=message):
        scene.set_material_volume(m, **kwargs)
    with pytest.raises(ValueError, match=message):
        scene.set_world_volume(**kwargs)
    with pytest.raises(ValueError, match="volume of material 3 but the scene has 1 materials"):
        scene.set_material_volume(3, sigma_a=(1.0, 1.0, 1.0))
    scene.set_material_volume(m, sigma_a=(1.0, 1.0, 1.0), pass_through=True)
