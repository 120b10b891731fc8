# SPDX-License-Identifier: Apache-2.0
"""Random scenes for the stress benchmark (scripts/benchmark --stress N), as plans: plain
dicts of numbers and names drawn from one seed (numpy's default_rng), the same on every machine
and Blender. torrance_tools.stress_scenes builds a plan in Blender. Needs no bpy.

A plan draws, independently of what Torrance does well:
  setting     indoor (a closed box room: the world does not reach it) or outdoor (a floor under
              the world);
  world       a Sky Texture or a two-colour gradient (no file);
  objects     2-5 of sphere, cube, torus, Suzanne, a randomly displaced grid, each with a material
              of: Principled (random base colour, metallic, roughness including exactly 0 and 1),
              Principled with a procedural texture (checker or noise) on its base colour, glass,
              smooth metal, rough metal, emissive;
  lights      1-3 of sun (outdoors), point, spot, area, sizes from tiny (1 mm) to large;
  camera      an ordinary view, or a grazing one over a near-mirror floor;
  caustic     sometimes: a small light seen through a glass sphere, or reflected by a smooth metal
              object, onto a diffuse floor.

Scene seeds of a run come from the run's stress seed (scene_seeds).
"""

import math

import numpy as np

SETTINGS = ("indoor", "outdoor")
WORLDS = ("sky", "gradient")
SHAPES = ("sphere", "cube", "torus", "suzanne", "displaced_grid")
MATERIALS = ("principled", "principled_textured", "glass", "metal_smooth", "metal_rough",
             "emissive")
LIGHTS = ("sun", "point", "spot", "area")
CAMERAS = ("ordinary", "grazing")
CAUSTICS = ("none", "glass", "metal")
TEXTURES = ("checker", "noise")
# every kind a plan can draw, as "category:value" (plan_kinds)
ALL_KINDS = frozenset(f"{cat}:{v}" for cat, values in (
    ("setting", SETTINGS), ("world", WORLDS), ("shape", SHAPES), ("material", MATERIALS),
    ("light", LIGHTS), ("camera", CAMERAS), ("caustic", CAUSTICS)) for v in values)

TARGET = (0.0, 0.0, 0.4)          # where the objects stand and the camera looks


def scene_seeds(stress_seed, count):
    """The seeds of the `count` scenes of a run with stress seed `stress_seed`."""
    rng = np.random.default_rng(stress_seed)
    return [int(s) for s in rng.integers(1, 2 ** 31 - 1, size=count)]


def _pick(rng, values, p=None):
    return str(values[int(rng.choice(len(values), p=p))])


def _colour(rng, lo=0.05, hi=0.9):
    return [round(float(x), 4) for x in rng.uniform(lo, hi, 3)]


def _tint(rng):
    """A light's colour: near white."""
    return [round(float(x), 4) for x in rng.uniform(0.75, 1.0, 3)]


def _roughness(rng):
    """Principled roughness: exactly 0 or 1 each 15 % of the time, else uniform."""
    u = rng.random()
    return 0.0 if u < 0.15 else 1.0 if u < 0.3 else round(float(rng.uniform(0.02, 0.98)), 4)


def material(rng, kind=None):
    """A material dict of `kind` (drawn when None)."""
    kind = kind or _pick(rng, MATERIALS, p=[0.3, 0.15, 0.15, 0.12, 0.13, 0.15])
    m = dict(kind=kind)
    if kind in ("principled", "principled_textured"):
        u = rng.random()
        metallic = 0.0 if u < 0.5 else 1.0 if u < 0.7 else round(float(rng.random()), 4)
        m.update(base_color=_colour(rng), metallic=metallic, roughness=_roughness(rng))
        if kind == "principled_textured":
            m.update(texture=_pick(rng, TEXTURES), second_color=_colour(rng),
                     scale=round(float(rng.uniform(2.0, 12.0)), 3))
    elif kind == "glass":
        m.update(color=_colour(rng, 0.75, 1.0), ior=round(float(rng.uniform(1.3, 1.8)), 4),
                 roughness=0.0 if rng.random() < 0.5 else round(float(rng.uniform(0.02, 0.5)), 4))
    elif kind in ("metal_smooth", "metal_rough"):
        rough = (0.0 if rng.random() < 0.5 else round(float(rng.uniform(0.005, 0.05)), 4)) \
            if kind == "metal_smooth" else round(float(rng.uniform(0.1, 0.7)), 4)
        m.update(base_color=_colour(rng, 0.5, 1.0), metallic=1.0, roughness=rough)
    elif kind == "emissive":
        m.update(color=_colour(rng, 0.3, 1.0), strength=round(float(rng.uniform(1.0, 8.0)), 3))
    return m


def _objects(rng, radius):
    out = []
    for k in range(int(rng.integers(2, 6))):
        size = float(rng.uniform(0.2, 0.6))
        angle, dist = rng.uniform(0, 2 * math.pi), radius * math.sqrt(rng.random())
        lift = 0.0 if rng.random() < 0.7 else float(rng.uniform(0.1, 0.8))
        out.append(dict(name=f"Object{k}", shape=_pick(rng, SHAPES), size=round(size, 4),
                        location=[round(dist * math.cos(angle), 4),
                                  round(dist * math.sin(angle), 4), round(size + lift, 4)],
                        rotation=[round(float(x), 4) for x in rng.uniform(0, 2 * math.pi, 3)],
                        relief=[round(float(x), 4) for x in rng.uniform(-1, 1, 6)],
                        material=material(rng)))
    return out


def _aim(rng, at, dist, elevation_deg):
    az, el = rng.uniform(0, 2 * math.pi), math.radians(elevation_deg)
    return [round(at[0] + dist * math.cos(el) * math.cos(az), 4),
            round(at[1] + dist * math.cos(el) * math.sin(az), 4),
            round(at[2] + dist * math.sin(el), 4)]


def light(rng, kind, at, dist, elevation_deg, irradiance):
    """A light of `kind` about `dist` from `at` (aimed at it), giving about `irradiance` there."""
    loc = _aim(rng, at, dist, elevation_deg)
    d2 = sum((a - b) ** 2 for a, b in zip(loc, at, strict=True))
    li = dict(kind=kind, location=loc, target=list(at), color=_tint(rng))
    if kind == "sun":
        li.update(energy=irradiance, angle_deg=round(float(10 ** rng.uniform(-1, 1)), 4))
    elif kind in ("point", "spot"):
        li.update(energy=4 * math.pi * d2 * irradiance,
                  radius=round(float(10 ** rng.uniform(-3, -0.5)), 5))
        if kind == "spot":
            li.update(spot_size_deg=round(float(rng.uniform(20, 100)), 3),
                      blend=round(float(rng.random()), 4))
    else:
        li.update(energy=4 * d2 * irradiance, size=round(float(10 ** rng.uniform(-2, 0)), 5),
                  shape=_pick(rng, ("SQUARE", "DISK")))
    li["energy"] = round(float(li["energy"]), 4)
    return li


def _lights(rng, setting, room):
    count = int(rng.integers(1, 4))
    kinds = LIGHTS if setting == "outdoor" else LIGHTS[1:]      # no sun reaches a closed room
    out = []
    for _ in range(count):
        kind = _pick(rng, kinds)
        dist = float(rng.uniform(2.0, 5.0)) if room is None else float(
            rng.uniform(0.8, min(room[2] - 0.6, 0.45 * min(room[:2]))))
        out.append(light(rng, kind, TARGET, dist, float(rng.uniform(25, 75)),
                         float(rng.uniform(1.0, 4.0)) / count))
    return out


def _caustic(rng, kind):
    """A caustic set-up: a glass sphere under a small light, or a smooth metal object lit by a
    small light from low down, over a diffuse patch of floor."""
    at = [round(float(x), 4) for x in rng.uniform(-1.2, 1.2, 2)]
    r = float(rng.uniform(0.2, 0.4))
    centre = [*at, round(r + float(rng.uniform(0.0, 0.4)), 4)]
    if kind == "glass":
        obj_mat = material(rng, "glass")
        obj_mat["roughness"] = 0.0
        small = light(rng, _pick(rng, ("point", "spot")), centre, float(rng.uniform(1.2, 2.5)),
                      float(rng.uniform(70, 90)), float(rng.uniform(3.0, 10.0)))
        shape = "sphere"
    else:
        obj_mat = material(rng, "metal_smooth")
        small = light(rng, _pick(rng, ("point", "spot")), centre, float(rng.uniform(1.0, 2.0)),
                      float(rng.uniform(10, 30)), float(rng.uniform(3.0, 10.0)))
        shape = _pick(rng, ("sphere", "torus", "cube"))
    small["radius"] = round(float(10 ** rng.uniform(-2.5, -1.3)), 5)
    if small["kind"] == "spot":
        small["spot_size_deg"] = round(float(rng.uniform(30, 60)), 3)
    return dict(kind=kind, light=small, floor=dict(kind="principled", base_color=_colour(
        rng, 0.6, 0.9), metallic=0.0, roughness=1.0), object=dict(
        name="CausticObject", shape=shape, size=round(r, 4), location=centre,
        rotation=[round(float(x), 4) for x in rng.uniform(0, 2 * math.pi, 3)],
        relief=[0.0] * 6, material=obj_mat))


def _camera(rng, kind, room):
    if kind == "grazing":
        h = float(rng.uniform(0.06, 0.3))
        dist = float(rng.uniform(3.0, 6.0)) if room is None else 0.45 * min(room[:2])
        az = rng.uniform(0, 2 * math.pi)
        loc = [round(dist * math.cos(az), 4), round(dist * math.sin(az), 4), round(h, 4)]
        target = [0.0, 0.0, round(h * float(rng.uniform(0.3, 1.5)), 4)]
    else:
        dist = float(rng.uniform(3.5, 7.0)) if room is None else float(
            rng.uniform(1.5, 0.45 * min(room[:2])))
        loc, target = _aim(rng, TARGET, dist, float(rng.uniform(8, 45))), list(TARGET)
        if room is not None:
            loc[2] = min(loc[2], room[2] - 0.2)
    lens = float(rng.uniform(20, 35) if room is not None else rng.uniform(28, 55))
    return dict(kind=kind, location=loc, target=target, lens=round(lens, 3))


def _world(rng, setting):
    kind = _pick(rng, WORLDS)
    w = dict(kind=kind)
    if kind == "sky":
        w.update(sun_elevation_deg=round(float(rng.uniform(3, 70)), 3),
                 sun_rotation_deg=round(float(rng.uniform(0, 360)), 3),
                 strength=round(float(rng.uniform(0.05, 0.3)), 4))
    else:
        w.update(ground=_colour(rng, 0.02, 0.3), horizon=_colour(rng, 0.3, 1.0),
                 zenith=_colour(rng, 0.05, 0.8), strength=round(float(rng.uniform(0.3, 1.5)), 4))
    if setting == "indoor":
        w["strength"] = round(w["strength"] * 0.1, 5)
    return w


def plan(seed):
    """The scene of `seed` as a dict (JSON-able)."""
    rng = np.random.default_rng(int(seed))
    setting = _pick(rng, SETTINGS, p=[0.35, 0.65])
    room = ([round(float(x), 3) for x in (*rng.uniform(5.0, 8.0, 2), rng.uniform(2.6, 3.5))]
            if setting == "indoor" else None)
    camera_kind = _pick(rng, CAMERAS, p=[0.7, 0.3])
    if camera_kind == "grazing":
        floor = material(rng, "metal_smooth")
        floor["base_color"] = [round(float(x), 4) for x in rng.uniform(0.8, 0.95, 3)]
    else:
        floor = material(rng, _pick(rng, ("principled", "principled_textured"), p=[0.7, 0.3]))
    caustic_kind = _pick(rng, CAUSTICS, p=[0.6, 0.25, 0.15])
    return dict(
        seed=int(seed), setting=setting, room=room, world=_world(rng, setting), floor=floor,
        walls=material(rng, "principled") if room else None,
        objects=_objects(rng, 1.4 if room else 2.0), lights=_lights(rng, setting, room),
        camera=_camera(rng, camera_kind, room),
        caustic=None if caustic_kind == "none" else _caustic(rng, caustic_kind))


def plan_kinds(p):
    """The kinds ("category:value", see ALL_KINDS) a plan uses."""
    objects = p["objects"] + ([p["caustic"]["object"]] if p["caustic"] else [])
    lights = p["lights"] + ([p["caustic"]["light"]] if p["caustic"] else [])
    return ({f"setting:{p['setting']}", f"world:{p['world']['kind']}",
             f"camera:{p['camera']['kind']}",
             f"caustic:{p['caustic']['kind'] if p['caustic'] else 'none'}"}
            | {f"shape:{o['shape']}" for o in objects}
            | {f"material:{o['material']['kind']}" for o in objects}
            | {f"light:{li['kind']}" for li in lights})


def describe(p):
    """One line: what the scene of plan `p` is made of."""
    objects = p["objects"] + ([p["caustic"]["object"]] if p["caustic"] else [])
    lights = p["lights"] + ([p["caustic"]["light"]] if p["caustic"] else [])
    things = ", ".join(f"{o['shape'].replace('_', ' ')} ({o['material']['kind'].replace('_', ' ')}"
                       + (f", roughness {o['material']['roughness']:.2g}"
                          if "roughness" in o["material"] else "") + ")" for o in objects)
    sizes = ", ".join(li["kind"] + (f" r {li['radius']:.2g} m" if "radius" in li else
                                    f" {li['size']:.2g} m" if "size" in li else
                                    f" {li['angle_deg']:.2g}°") for li in lights)
    caustic = f"; caustic: small light via {p['caustic']['kind']}" if p["caustic"] else ""
    floor = p["floor"]["kind"].replace("_", " ")
    return (f"{p['setting']}, {p['world']['kind']} world, {p['camera']['kind']} camera over a "
            f"{floor} floor; {things}; lights: {sizes}{caustic}")
