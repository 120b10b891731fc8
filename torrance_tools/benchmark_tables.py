# SPDX-License-Identifier: Apache-2.0
"""The speed/error benchmark's Markdown tables (scripts/benchmark_report.py): the summary of
equal-error ratios with and without adaptive sampling, the ratios after denoising (--denoised),
the ablation tables, rays/s against raw Embree and each scene's points. Each function returns a
list of lines. Needs no bpy."""

from torrance_tools.benchmark_points import geometric_mean
from torrance_tools.equal_error import equal_error, fmt_equal, fmt_ratio, meets

TARGET = 0.5          # the issue's goal: equal error in at most half of Cycles' time
RAYS_GOAL = 0.6       # the goal: the integrator traces >= 60 % of raw Embree's rays/s

# What a lever of the core is, for the ablation tables (any other field: its name in words).
LEVER_LABELS = {"specialize": "specialised kernels", "sampler=RANDOM": "Sobol sampler",
                "light_selection=IRRADIANCE": "light choice aware of the BSDF",
                "light_selection=UNIFORM": "light selection by contribution",
                "guiding": "path guiding", "camera_packets": "camera rays in 8-wide packets",
                "efficiency_roulette": "efficiency-aware Russian roulette",
                "mirror_images": "NEE of lights in mirrors, glossy surfaces; lamp spots",
                "nee_every_light": "NEE of both lights in two-light scenes",
                "caustics": "caustics by light tracing",
                "first_bounce_splits=0": "splitting at the first hit chosen by a pilot (opt-in)",
                "filter_splatting": "samples splatted over the pixels their filter covers"}


def ratios(d, torrance, cycles):
    """(relMSE, trimmed relMSE, 1 - SSIM) equal-error ratios of curve `torrance` against curve
    `cycles` of scene data d; None where a curve is missing."""
    if not d.get(torrance) or not d.get(cycles):
        return None
    floor = d["reference"]["noise_rel_mse"]
    return (equal_error(d[torrance], d[cycles], floor=floor),
            equal_error(d[torrance], d[cycles], key="rel_mse_trim_corrected", floor=floor),
            equal_error(d[torrance], d[cycles], key="dssim"))


def summary(scenes):
    """The headline table: per scene the plain (unbiased) and the adaptive equal-error ratio;
    returns (lines, {scene: plain equal_error})."""
    lines = ["| scene | T/C plain: relMSE (geo. mean) | range | at Cycles' 16 / 128 / 1024 spp "
             f"error | goal ≤ {TARGET} | trimmed relMSE | 1−SSIM "
             "| T/C adaptive: relMSE | range | trimmed relMSE | seeds "
             "| bias (mean ratio T/ref, last plain point) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    plain_by_scene = {}
    for name, d in scenes.items():
        plain = ratios(d, "torrance", "cycles")
        adaptive = ratios(d, "torrance_adaptive", "cycles_adaptive")
        cells = []
        for r, with_spp in ((plain, True), (adaptive, False)):
            if r is None:
                cells += ["—"] * (6 if with_spp else 3)
                continue
            eq, trim, dssim = r
            rng = f"{fmt_ratio(eq['lo'])}–{fmt_ratio(eq['hi'])}" if eq["lo"] is not None else "—"
            cells += [fmt_equal(eq), rng]
            if with_spp:
                met = {None: "—", True: "yes", False: "no"}[meets(eq, TARGET)]
                cells += [" / ".join(fmt_equal(eq, k) for k in (16, 128, 1024)), met,
                          fmt_equal(trim), fmt_equal(dssim)]
            else:
                cells.append(fmt_equal(trim))
        plain_by_scene[name] = plain[0] if plain else equal_error([], [])
        last = d["torrance"][-1] if d.get("torrance") else None
        bias = f"{last['ratio']:.4f} ({last['spp']} spp)" if last else "—"
        seeds = d.get("seeds")
        lines.append(f"| [{name}](#{name.replace('_', '-')}) | " + " | ".join(cells)
                     + f" | {len(seeds) if seeds else '—'} | {bias} |")
    return lines, plain_by_scene


def denoised(scenes):
    """Per scene the equal-error ratios after denoising (scripts/benchmark --denoised: each
    engine's own denoiser) beside the undenoised ones of the same run."""
    lines = [f"| scene | T/C denoised: relMSE (geo. mean) | range | goal ≤ {TARGET} | 1−SSIM "
             "| T/C undenoised: relMSE | 1−SSIM | seeds |",
             "|---|---|---|---|---|---|---|---|"]
    for name, d in scenes.items():
        after = ratios(d, "torrance_denoised", "cycles_denoised")
        if after is None:
            continue
        before = ratios(d, "torrance", "cycles")
        eq, _trim, dssim = after
        rng = f"{fmt_ratio(eq['lo'])}–{fmt_ratio(eq['hi'])}" if eq["lo"] is not None else "—"
        met = {None: "—", True: "yes", False: "no"}[meets(eq, TARGET)]
        undenoised = ([fmt_equal(before[0]), fmt_equal(before[2])] if before
                      else ["—", "—"])
        lines.append(f"| [{name}](#{name.replace('_', '-')}) | {fmt_equal(eq)} | {rng} | {met} "
                     f"| {fmt_equal(dssim)} | " + " | ".join(undenoised)
                     + f" | {len(d.get('seeds') or [])} |")
    return lines


def lever_label(field, default, other):
    """`field` is a RenderSettings field, or FIELD=ALTERNATIVE for a string option's lever."""
    words = LEVER_LABELS.get(field, field.partition("=")[0].replace("_", " "))
    return f"{words} (`{field.partition('=')[0]}` {default!r} → {other!r})"


def lever_cells(tg):
    """(core time default, switched, speed-up, relMSE default, switched, error ratio,
    trimmed error ratio, efficiency gain) of one lever in one scene; times are the core's
    (the export is the same for all), errors the means over the seeds."""
    on, off = tg["on"], tg["off"]
    t_on = on.get("core_seconds") or on["seconds"]
    t_off = off.get("core_seconds") or off["seconds"]
    speed = t_off / max(t_on, 1e-9)
    err = off["rel_mse"] / max(on["rel_mse"], 1e-30)
    err_trim = off["rel_mse_trim"] / max(on["rel_mse_trim"], 1e-30)
    return t_on, t_off, speed, on["rel_mse"], off["rel_mse"], err, err_trim, speed * err


def ablation(res, scenes):
    """An overview (efficiency gain of every lever in every scene) and a table per scene."""
    s = res["settings"]
    levers = res.get("levers", [])
    if s.get("toggle_seeds") == 0:
        return ["Not measured in this run (`--toggle-seeds 0`)."]
    if not levers:
        return ["The core exposes no levers (no boolean fields of `torrance_core.RenderSettings` "
                "beyond the known ones, no string or integer option of ALTERNATIVES in "
                "`scripts/benchmark.py`)."]
    lines = [f"Torrance at {s['toggle_spp']} spp with its defaults, then with one lever of the "
             f"core switched at a time (everything else default), each variant rendered with the "
             f"same {s.get('toggle_seeds')} seeds, interleaved; errors are means over the seeds, "
             f"times medians of the core's render time. Speed-up = time(switched) / "
             f"time(default); error ratio = relMSE(switched) / relMSE(default); **efficiency "
             f"gain = (time × relMSE)(switched) / (time × relMSE)(default)**: how much longer the "
             f"core needs for the same error without the default choice (relMSE ∝ 1/samples). "
             f"Above 1: the default pays.", ""]
    names = [n for n, d in scenes.items() if d.get("ablation")]
    lines += ["| lever | " + " | ".join(names) + " | geometric mean |",
              "|---|" + "---|" * (len(names) + 1)]
    for lever in levers:
        gains = [lever_cells(scenes[n]["ablation"][lever["field"]])[-1]
                 if lever["field"] in scenes[n]["ablation"] else None for n in names]
        mean = geometric_mean(g for g in gains if g is not None)
        lines.append(f"| {lever_label(lever['field'], lever['default'], lever['other'])} | "
                     + " | ".join("—" if g is None else f"{g:.2f}×" for g in gains)
                     + f" | {'—' if mean is None else f'{mean:.2f}×'} |")
    for name in names:
        lines += ["", f"**{name}**", "",
                  "| lever | core time default (s) | switched (s) | speed-up | relMSE default "
                  "| relMSE switched | error ratio | trimmed error ratio | efficiency gain |",
                  "|---|---|---|---|---|---|---|---|---|"]
        for lever in levers:
            tg = scenes[name]["ablation"].get(lever["field"])
            if tg is None:
                continue
            t_on, t_off, speed, e_on, e_off, err, err_trim, gain = lever_cells(tg)
            lines.append(f"| {lever_label(lever['field'], tg['default'], tg['other'])} "
                         f"| {t_on:.3f} | {t_off:.3f} | {speed:.2f}× | {e_on:.3e} | {e_off:.3e} "
                         f"| {err:.2f} | {err_trim:.2f} | {gain:.2f}× |")
    return lines


def format_rays_value(key, value):
    if "fraction" in key:
        return f"{100 * value:.1f} %"
    if "per_second" in key:
        return f"{value / 1e6:.2f} M"
    return f"{value:.4g}"


def rays(scenes):
    """'Per-sample cost: rays/s against raw Embree': every numeric key of the scenes' `rays`
    (torrance_tools.ray_throughput.measure), and whether `fraction` reaches RAYS_GOAL."""
    measured = {n: d["rays"] for n, d in scenes.items() if isinstance(d.get("rays"), dict)}
    if not measured:
        return ["Not measured: torrance_tools.ray_throughput was not available in this run."]
    keys = []
    for r in measured.values():
        keys += [k for k, v in r.items() if isinstance(v, (int, float)) and
                 not isinstance(v, bool) and k not in keys]
    lines = ["| scene | " + " | ".join(f"`{k}`" for k in keys)
             + f" | goal ≥ {RAYS_GOAL * 100:.0f} % |",
             "|---|" + "---|" * (len(keys) + 1)]
    for name, r in measured.items():
        cells = [format_rays_value(k, r[k]) if k in r else "—" for k in keys]
        fraction = r.get("fraction")
        goal = "—" if fraction is None else ("yes" if fraction >= RAYS_GOAL else "no")
        lines.append(f"| {name} | " + " | ".join(cells) + f" | {goal} |")
    return lines


def points(d, curves):
    """A scene's points, one table per curve: setting, time, mean relMSE and trimmed relMSE
    side by side, SSIM, bias ratio, seeds."""
    lines = []
    for c in curves:
        rows = d.get(c)
        if not rows:
            continue
        adaptive = rows[0].get("threshold") is not None
        lines += ["", f"`{c}`:", "",
                  ("| threshold | spp (mean) " if adaptive else "| spp ")
                  + "| s (median) | mean relMSE | mean trimmed relMSE | SSIM | mean ratio "
                  "| seeds |",
                  "|---|" + ("---|" if adaptive else "") + "---|---|---|---|---|---|"]
        for r in rows:
            spp = r.get("samples_per_pixel")
            setting = (f"{r['threshold']:.3g} | {'—' if spp is None else f'{spp:.1f}'}"
                       if adaptive else str(r["spp"]))
            lines.append(f"| {setting} | {r['seconds']:.3f} | {r['rel_mse']:.3e} "
                         f"| {r['rel_mse_trim']:.3e} | {r['ssim']:.4f} | {r['ratio']:.4f} "
                         f"| {r.get('seeds', 1)} |")
    return lines


def goal_line(plain_by_scene):
    ok = [n for n, e in plain_by_scene.items() if meets(e, TARGET)]
    return (f"Goal (equal error in ≤ {TARGET}× Cycles' time, plain curves) met on {len(ok)} of "
            f"{len(plain_by_scene)} scenes{': ' + ', '.join(ok) if ok else ''}.")
