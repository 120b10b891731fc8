# SPDX-License-Identifier: Apache-2.0
"""The native module works in the Python running this: a sunlit grey plane seen from above renders
finite and lit (ctest python_module_py313 runs it in Python 3.13, the Python of Blender 5.1+).

    PYTHONPATH=build/addon build/py313/bin/python core/python/tests/smoke_render.py
"""
import sys

import numpy as np

import torrance_core as tc


def main():
    scene = tc.Scene()
    grey = scene.add_material(base_color=(0.5, 0.5, 0.5), specular=0.0, roughness=1.0)
    quad = np.array([[-5, -5, 0], [5, -5, 0], [5, 5, 0], [-5, 5, 0]], np.float32)
    scene.add_mesh(quad, np.array([[0, 1, 2], [0, 2, 3]], np.int32), material_indices=[grey] * 2)
    scene.add_sun(direction=(0, 0, -1), strength=np.pi, angle=0.0)
    camera = np.eye(4)
    camera[2, 3] = 5.0
    scene.set_camera(camera, type="ORTHO", ortho_scale=1.0)
    settings = tc.RenderSettings(width=8, height=8, samples=16, max_bounces=0)
    image = np.asarray(tc.render(scene, settings).image)
    green = float(image[..., 1].mean())
    python = sys.version.split()[0]
    print(f"torrance_core {tc.__version__} in Python {python}: green mean {green:.4f}")
    if not np.isfinite(image).all() or abs(green - 0.5) > 0.05:
        sys.exit("the plane should be 0.5 grey (sun of strength pi straight down)")


if __name__ == "__main__":
    main()
