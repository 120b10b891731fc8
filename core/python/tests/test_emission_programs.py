"""Worlds and lights as shader programs (Scene.set_world_program, set_light_program; core
emission_shader.h): bad arguments are rejected, a world's program sees the direction as Cycles'
background does, next-event estimation of its map and BSDF sampling together converge to the
analytic irradiance, and a light's program sees the distance to its receiver."""
import numpy as np
import pytest
import torrance_core as tc

COLUMNS = 17     # opcode, mode, flags, resource, out, 12 inputs
GEOMETRY, CHANNEL, VECTOR_MATH, LIGHT_PATH = 96, 2, 5, 106
SCALE, MAXIMUM = 13, 12    # VectorMath's and Math's modes (shader_math.h)



def code_row(op, out, inputs=(), mode=0, flags=0, resource=-1):
    row = [op, mode, flags, resource, out] + [-1] * (COLUMNS - 5)
    row[5:5 + len(inputs)] = inputs
    return row


def add(scene, constants, rows, registers):
    return scene.add_shader_program(np.asarray(constants, np.float32).reshape(-1, 4),
                                    np.asarray(rows, np.int32).reshape(-1, COLUMNS), registers)


def sky_program(scene, color, power=1):
    """radiance = color * max(dir.z, 0) ** power: Geometry Position (the direction), its z."""
    rows = [code_row(GEOMETRY, 2, mode=0), code_row(CHANNEL, 3, (2,), mode=2)]
    reg = 3
    for _ in range(power - 1):
        rows.append(code_row(4, reg + 1, (reg, 3, 3), mode=2))       # Math Multiply
        reg += 1
    rows.append(code_row(4, reg + 1, (reg, 1, 1), mode=MAXIMUM))     # Math Maximum(z, 0)
    rows.append(code_row(VECTOR_MATH, reg + 2, (0, 0, 0, reg + 1), mode=SCALE))
    return add(scene, [(*color, 0.0), (0.0, 0.0, 0.0, 0.0)], rows, reg + 3), reg + 2


def test_bad_world_programs_are_rejected():
    scene = tc.Scene()
    pid, out = sky_program(scene, (1.0, 1.0, 1.0))
    with pytest.raises(ValueError, match="shader program 3"):
        scene.set_world_program(3, out)
    with pytest.raises(ValueError, match="not written"):
        scene.set_world_program(pid, out + 5)
    with pytest.raises(ValueError, match="resolution"):
        scene.set_world_program(pid, out, resolution=2)


def floor_scene(world):
    """A white Lambert floor z = 0 seen from above (orthographic), lit by `world` alone."""
    scene = tc.Scene()
    m = scene.add_material(base_color=(1, 1, 1), specular=0.0, roughness=1.0)
    scene.add_mesh(np.array([[-50, -50, 0], [50, -50, 0], [50, 50, 0], [-50, 50, 0]], np.float32),
                   np.array([[0, 1, 2], [0, 2, 3]]), material_indices=np.array([m, m]))
    world(scene)
    down = np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 5], [0, 0, 0, 1]], np.float32)
    scene.set_camera(down, type="ORTHO", ortho_scale=1.0)
    return scene


@pytest.mark.parametrize("power", [1, 8])
def test_a_sky_program_lights_a_floor_as_integrated(power):
    # L = c z^n over the upper hemisphere: E = c * 2 pi / (n + 2); the floor shows E / pi.
    c = np.array([0.3, 0.6, 0.9])
    settings = tc.RenderSettings(width=8, height=8, samples=256, max_bounces=1)
    img = tc.render(floor_scene(lambda s: s.set_world_program(*sky_program(s, c, power))),
                    settings).image
    expected = c * 2.0 / (power + 2)
    assert img[..., :3].reshape(-1, 3).mean(axis=0) == pytest.approx(expected, rel=0.02)


def test_the_program_sees_the_escaping_rays_path_state():
    # radiance = (Is Camera Ray, 1 - Is Camera Ray, 0): the camera sees red, the floor is lit
    # by green (E = pi from a uniform world: the floor shows 1).
    def world(scene):
        rows = [code_row(LIGHT_PATH, 3, mode=0),
                code_row(4, 4, (1, 3, 3), mode=1),                      # Math Subtract 1 - cam
                code_row(3, 5, (3, 4, 2))]                              # Combine (cam, 1-cam, 0)
        pid = add(scene, [(0.0, 0.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 0.0)],
                  rows, 6)
        scene.set_world_program(pid, 5)
    settings = tc.RenderSettings(width=8, height=8, samples=128, max_bounces=1)
    floor = tc.render(floor_scene(world), settings).image[..., :3].reshape(-1, 3).mean(axis=0)
    assert floor == pytest.approx((0.0, 1.0, 0.0), abs=0.02)
    sky = tc.Scene()
    world(sky)
    sky.set_camera(np.eye(4, dtype=np.float32), lens=30.0)
    seen = tc.render(sky, tc.RenderSettings(width=4, height=4, samples=1)).image[..., :3]
    assert np.allclose(seen.reshape(-1, 3), (1.0, 0.0, 0.0))


@pytest.mark.parametrize("mode", [6, 7])
def test_environment_projections_agree_with_their_twins(load_module, mode):
    # The Environment Texture's Equirectangular (6) and Mirror Ball (7) projections of the
    # ImageProjection op (opcode 60) against the add-on's float32 twins, axes and zero included.
    image = load_module("shader_graph.projections")
    twin = image.direction_to_equirectangular if mode == 6 else image.direction_to_mirror_ball
    rng = np.random.default_rng(mode)
    dirs = np.concatenate([np.eye(3), -np.eye(3), np.zeros((1, 3)),
                           rng.normal(size=(53, 3)) * rng.uniform(0.01, 100, (53, 1))])
    n = len(dirs)
    constants = np.zeros((n, 4), np.float32)
    constants[:, :3] = dirs
    rows = [code_row(60, n + k, (k,) * 7, mode=mode) for k in range(n)]
    scene = tc.Scene()
    pid = add(scene, constants, rows, 2 * n)
    regs = scene.run_shader_program(pid, np.zeros((1, 2), np.float32))[0]
    got = np.array([regs[n + k][:2] for k in range(n)])
    want = np.array([[float(x) for x in twin(d)] for d in constants[:, :3]])
    assert np.abs(got - want).max() < 2e-6
    assert ((0 <= got) & (got <= 1)).all()


LIGHT_FALLOFF = 109


def test_a_light_program_sees_the_distance_to_its_receiver():
    # A point light of power P over a white Lambert floor at height h: irradiance P / (4 pi h^2)
    # under it; a program of Light Falloff > Linear (strength 1) multiplies it by the distance.
    def scene_with(program):
        scene = tc.Scene()
        m = scene.add_material(base_color=(1, 1, 1), specular=0.0, roughness=1.0)
        scene.add_mesh(np.array([[-50, -50, 0], [50, -50, 0], [50, 50, 0], [-50, 50, 0]],
                                np.float32), np.array([[0, 1, 2], [0, 2, 3]]),
                       material_indices=np.array([m, m]))
        scene.add_point_light(position=(0.0, 0.0, 2.0), power=100.0, radius=0.0)
        if program:
            pid = add(scene, [(1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 0.0)],
                      [code_row(LIGHT_FALLOFF, 2, (0, 1), mode=1)], 3)
            scene.set_light_program(pid, 2)
        cam = np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 1], [0, 0, 0, 1]], np.float32)
        scene.set_camera(cam, type="ORTHO", ortho_scale=0.01)
        return scene
    settings = tc.RenderSettings(width=2, height=2, samples=16, max_bounces=1)
    plain = tc.render(scene_with(False), settings).image[..., 0].mean()
    linear = tc.render(scene_with(True), settings).image[..., 0].mean()
    assert plain == pytest.approx(100.0 / (4 * np.pi * 4.0) / np.pi, rel=0.02)
    assert linear == pytest.approx(plain * 2.0, rel=0.01)


def test_bad_light_programs_are_rejected():
    scene = tc.Scene()
    pid, out = sky_program(scene, (1.0, 1.0, 1.0))
    with pytest.raises(ValueError, match="needs a light"):
        scene.set_light_program(pid, out)
    scene.add_point_light(position=(0.0, 0.0, 2.0))
    with pytest.raises(ValueError, match="shader program 9"):
        scene.set_light_program(9, out)
    with pytest.raises(ValueError, match="not written"):
        scene.set_light_program(pid, out + 5)


def sky_disc_world(guided):
    """A world of Blender 5.x's Multiple Scattering sky (TexSky mode 2) with a 2 degree sun 40
    degrees up; guided: its disc's cone given to set_world_program (Cycles' sun guiding)."""
    elevation, size = np.radians(40.0), np.radians(2.0)
    table = tc.scattering_sky_table(True, elevation, 0.0, size, 1.0, True, 100.0, 1.0, 1.0, 1.0)

    def world(scene):
        rows = [code_row(GEOMETRY, 1, mode=0), code_row(61, 2, (1,), mode=2, resource=0)]
        data = np.concatenate([[len(table)], table]).astype(np.float32)
        pid = scene.add_shader_program(np.zeros((1, 4), np.float32),
                                       np.asarray(rows, np.int32), 3, data)
        # Cycles' sun: elevation e, longitude (2 pi - rotation) + pi / 2.
        sun = (0.0, np.cos(elevation), np.sin(elevation), size / 2) if guided else None
        scene.set_world_program(pid, 2, sun=sun)
    return world


def test_sun_guiding_is_unbiased_and_less_noisy():
    # The map alone meets the disc in a cell or two: fireflies (pixel std 11.6 at 1024 spp, its
    # mean still 2.7 % off), where the guided cone gives 2.8 at any count.
    settings = tc.RenderSettings(width=8, height=8, samples=1024, max_bounces=1)
    images = {guided: tc.render(floor_scene(sky_disc_world(guided)), settings).image[..., :3]
              for guided in (False, True)}
    means = {k: img.reshape(-1, 3).mean(axis=0) for k, img in images.items()}
    assert means[True] == pytest.approx(means[False], rel=0.05)
    assert images[True].std() < 0.5 * images[False].std()
    scene = tc.Scene()
    pid, out = sky_program(scene, (1.0, 1.0, 1.0))
    with pytest.raises(ValueError, match="half angle"):
        scene.set_world_program(pid, out, sun=(0.0, 0.0, 1.0, 0.0 + 4.0))
