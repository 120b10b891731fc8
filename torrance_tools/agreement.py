# SPDX-License-Identifier: Apache-2.0
"""The Torrance-vs-Cycles agreement scene, its metrics and pass/fail criteria (used by the
headless tests: test_cycles_agreement.py, test_camera_agreement.py, test_lights.py, test_hdri.py,
test_textures.py, test_reference_scenes.py, test_cancel_memory.py, test_glass_agreement.py,
test_alpha_agreement.py, test_mix_shader_agreement.py, test_bump_agreement.py)."""

import math

import numpy as np

from torrance_tools import testing
from torrance_tools.compare import bias_metrics, image_offset
from torrance_tools.render_settings import setup_cycles, setup_torrance

# name, centre, radius, base colour, metallic, roughness
SPHERES = (
    ("RedPlastic", (-1.65, 0.0, 0.5), 0.5, (0.80, 0.10, 0.08), 0.0, 0.25),
    ("Gold", (-0.55, 0.3, 0.5), 0.5, (1.00, 0.76, 0.33), 1.0, 0.30),
    ("RoughSilver", (0.55, 0.0, 0.5), 0.5, (0.90, 0.90, 0.90), 1.0, 0.60),
    ("BluePaint", (1.65, 0.3, 0.5), 0.5, (0.10, 0.22, 0.80), 0.0, 0.70),
)


def build(scene, world=(0.10, 0.12, 0.15), sun=3.0, point=250.0):
    """Spheres on a floor in front of a wall, lit by a sun, a point light and the world."""
    testing.add_camera(scene, location=(0.0, -5.2, 1.9), target=(0.0, 0.3, 0.55), lens=40.0)
    # Matte floor and wall (Specular 0): there Lambert and Cycles' Burley diffuse agree to ~1%,
    # so the big surfaces measure units, camera and bounces rather than the BRDF difference.
    floor = testing.principled("Floor", (0.50, 0.50, 0.50), 0.0, 0.50, specular=0.0)
    wall = testing.principled("Wall", (0.60, 0.45, 0.30), 0.0, 0.50, specular=0.0)
    testing.plane(scene, "Floor", 12.0, material=floor)
    w = testing.mesh_object(scene, "Wall", [(-6, 2.2, 0), (6, 2.2, 0), (6, 2.2, 4), (-6, 2.2, 4)],
                            [(0, 1, 2, 3)], wall)
    for name, centre, radius, color, metallic, roughness in SPHERES:
        testing.sphere_object(scene, name, centre, radius,
                              testing.principled(name, color, metallic, roughness))
    testing.add_sun(scene, strength=sun, rotation=(math.radians(50), 0, math.radians(35)),
                    angle=math.radians(10.0))
    testing.add_point(scene, (2.2, -1.8, 2.6), power=point, radius=0.25, color=(1.0, 0.9, 0.8))
    testing.set_world(scene, world)
    return w


# Agreement criteria (see test_cycles_agreement.py for the measurements behind them).
THRESHOLDS = dict(
    ratio=(0.93, 1.06),          # overall and per channel
    block_mean=0.045,
    block_p90=0.12,
    offset=0.5,                  # pixels, each axis
)


def metrics(img, ref):
    """bias_metrics (RGB; signed: a Combined image may be negative) and the image offset in
    pixels of img against ref."""
    return dict(bias_metrics(img, ref, signed=True), offset=image_offset(img, ref))


def format_metrics(m):
    ch = "/".join(f"{c:.3f}" for c in m["channels"])
    return (f"ratio {m['ratio']:.4f} ({ch}), block mean {m['block_mean']:.4f}, "
            f"p90 {m['block_p90']:.4f}, offset ({m['offset'][0]:+.2f}, {m['offset'][1]:+.2f}) px")


def failures(m, thresholds=THRESHOLDS):
    """The thresholds a result violates (empty = agreement). `thresholds`: the ratio band (overall
    and per channel), block_mean, block_p90 and, if given, the offset in pixels."""
    lo, hi = thresholds["ratio"]
    out = []
    if not lo <= m["ratio"] <= hi:
        out.append(f"ratio {m['ratio']:.3f} outside [{lo}, {hi}]")
    for name, c in zip("RGB", m["channels"], strict=True):
        if not lo <= c <= hi:
            out.append(f"{name} ratio {c:.3f} outside [{lo}, {hi}]")
    if m["block_mean"] > thresholds["block_mean"]:
        out.append(f"block mean {m['block_mean']:.3f} > {thresholds['block_mean']}")
    if m["block_p90"] > thresholds["block_p90"]:
        out.append(f"block p90 {m['block_p90']:.3f} > {thresholds['block_p90']}")
    if ("offset" in thresholds
            and max(abs(m["offset"][0]), abs(m["offset"][1])) > thresholds["offset"]):
        out.append(f"offset ({m['offset'][0]:+.2f}, {m['offset'][1]:+.2f}) px > "
                   f"{thresholds['offset']}")
    return out


def noise_limits(noise, factor=2.0, ratio_floor=0.004, block_floor=0.004):
    """Allowed errors of a render measured against its Cycles own seed-to-seed noise `noise`
    (metrics of a Cycles render at the same samples and another seed against the reference):
    factor x that noise plus a floor, for the ratios (overall and per channel) and block means."""
    worst_ratio = max(abs(c - 1.0) for c in [noise["ratio"], *noise["channels"]])
    return dict(ratio=factor * worst_ratio + ratio_floor,
                block_mean=factor * noise["block_mean"] + block_floor)


def noise_failures(m, limits):
    """The noise_limits a result violates (empty = agreement within Cycles' own noise)."""
    bad = [f"{name} ratio {r:.4f} off by more than {limits['ratio']:.4f}"
           for name, r in zip(("mean", "R", "G", "B"), [m["ratio"], *m["channels"]], strict=True)
           if abs(r - 1.0) > limits["ratio"]]
    if m["block_mean"] > limits["block_mean"]:
        bad.append(f"block mean {m['block_mean']:.4f} > {limits['block_mean']:.4f}")
    return bad


def noise_bounds(own, tolerance=1.5, ratio_sigmas=3.0, ratio_floor=0.015):
    """Thresholds (for failures()) from Cycles' own noise: `own` = metrics of a second Cycles
    render (another seed) against the reference. Block mean and p90 may be `tolerance` x Cycles'
    own; the ratio may be off by ratio_sigmas x Cycles' own largest |ratio - 1| (overall or per
    channel), at least ratio_floor. No offset bound (the scenes' camera is tested elsewhere)."""
    r = max(ratio_floor, ratio_sigmas * max(abs(own["ratio"] - 1.0),
                                            *(abs(c - 1.0) for c in own["channels"])))
    return dict(ratio=(1.0 - r, 1.0 + r), block_mean=tolerance * own["block_mean"],
                block_p90=tolerance * own["block_p90"])


def cycles_reference_and_noise(scene, directory, samples, bounces, ref_samples=None,
                               seeds=(0, 1)):
    """Cycles' reference of `scene` (ref_samples, default samples; seed seeds[0]) and Cycles' own
    noise: the metrics of a second Cycles render (samples, seed seeds[1]) against it, printed;
    with more seeds, one render's typical noise over them (typical_noise). Returns (reference
    image, noise metrics) for noise_bounds or noise_limits."""
    ref_samples = ref_samples or samples
    setup_cycles(scene, ref_samples, bounces, seed=seeds[0])
    ref, t_ref = testing.render(scene, directory, "cycles_reference")
    own = []
    for seed in seeds[1:]:
        setup_cycles(scene, samples, bounces, seed=seed)
        other, t_other = testing.render(scene, directory, "cycles_noise")
        own.append(metrics(other, ref))
        print(f"Cycles {samples} spp seed {seed} vs the reference ({ref_samples} spp, seed "
              f"{seeds[0]}): {format_metrics(own[-1])}  ({t_other:.1f} s; reference {t_ref:.1f} s)",
              flush=True)
    if len(own) == 1:
        return ref, own[0]
    noise = typical_noise(own)
    print(f"Cycles' typical noise over seeds {', '.join(map(str, seeds[1:]))}: "
          f"{format_metrics(noise)}", flush=True)
    return ref, noise


def typical_noise(all_metrics):
    """One render's typical metrics() against a reference, from several seeds' (a single seed's
    block p90 varies by half from seed to seed): block mean, p90 and max averaged, and each ratio
    1 + the root mean square of its deviations from 1 (the size of one seed's deviation, as
    noise_bounds and noise_limits read it)."""
    out = mean_metrics(all_metrics)
    out["ratio"] = 1.0 + float(np.sqrt(np.mean([(m["ratio"] - 1.0) ** 2 for m in all_metrics])))
    out["channels"] = list(1.0 + np.sqrt(np.mean(
        [[(c - 1.0) ** 2 for c in m["channels"]] for m in all_metrics], axis=0)))
    return out


def print_verdict(label, m, bad):
    """One line: the metrics of a render and what it violates ("ok" if nothing)."""
    print(f"{label}: {format_metrics(m)}" + (f"  FAIL: {'; '.join(bad)}" if bad else "  ok"),
          flush=True)


def mean_metrics(all_metrics):
    """The mean of several metrics() results (one per seed)."""
    keys = ("ratio", "block_mean", "block_p90", "block_max")
    out = {k: float(np.mean([m[k] for m in all_metrics])) for k in keys}
    out["channels"] = list(np.mean([m["channels"] for m in all_metrics], axis=0))
    out["offset"] = tuple(np.mean([m["offset"] for m in all_metrics], axis=0))
    return out


def render_torrance(scene, directory, name, samples, max_bounces, model='PRINCIPLED'):
    """Renders with Torrance's `model`; (image, seconds), the image checked for NaN/Inf."""
    setup_torrance(scene, samples, max_bounces, brdf_model=model)
    img, seconds = testing.render(scene, directory, name)
    testing.check(np.isfinite(img).all(), f"{name}: NaN/Inf in Torrance's image")
    return img, seconds
