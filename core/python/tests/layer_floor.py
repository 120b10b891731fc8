"""A floor of one material under a uniform white world, seen from above (the Principled layer
tests: coat, sheen): its mean RGB; the inputs named in `from_program` come from a shader
program's constant registers (<name>_register, or the register argument a dict maps them to)
instead of add_material's values."""
import numpy as np
import torrance_core as tc

COLUMNS = 17


def floor(model, from_program=(), **material):
    scene = tc.Scene()
    if from_program:
        values = [material[name] for name in from_program]
        constants = np.array([[*np.atleast_1d(v), *[0] * (4 - np.size(v))] for v in values],
                             np.float32)
        pid = scene.add_shader_program(constants, np.zeros((0, COLUMNS), np.int32),
                                       len(values))
        material = dict(material, program=pid)
        for register, name in enumerate(from_program):
            # A value add_material accepts, which the register replaces (a transmission 1, as
            # the add-on passes it: the material is added as transmitting).
            neutral = {"ior": 1.5, "transmission": 1.0}.get(name, 0.0) \
                if np.size(material[name]) == 1 else (1.0, 1.0, 1.0)
            argument = from_program[name] if isinstance(from_program, dict) else f"{name}_register"
            material.update({name: neutral, argument: register})
    material.setdefault("base_color", (0.5, 0.5, 0.5))
    material.setdefault("roughness", 0.5)
    m = scene.add_material(**material)
    scene.add_mesh(np.array([[-50, -50, 0], [50, -50, 0], [50, 50, 0], [-50, 50, 0]], np.float32),
                   np.array([[0, 1, 2], [0, 2, 3]]), material_indices=np.array([m, m]))
    scene.set_world((1.0, 1.0, 1.0), 1.0)
    down = np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 5], [0, 0, 0, 1]], np.float32)
    scene.set_camera(down, type="ORTHO", ortho_scale=1.0)
    settings = tc.RenderSettings(width=8, height=8, samples=256, max_bounces=1, seed=3,
                                 brdf_model=model)
    return tc.render(scene, settings).image[..., :3].reshape(-1, 3).mean(axis=0)
