# SPDX-License-Identifier: Apache-2.0
"""Writes docs/benchmark/report.md and its plots from docs/benchmark/results.json.

Run by scripts/benchmark after the renders (or alone, to re-make the report from stored results):

    /usr/bin/python3 scripts/benchmark_report.py [DIR]      (default docs/benchmark)

Error: relMSE = mean over pixels and channels of (I - R)^2 / (R^2 + 0.01) against the stored
reference R, minus the reference's own noise (noise_rel_mse in its JSON: E[relMSE] = true error +
the reference's variance term; errors below that noise term are not used), and SSIM of tone-mapped
images. Equal-error time ratio: both engines' curves of log(time) against log(corrected relMSE) are
made monotone (the best error reached so far) and interpolated linearly; the ratio time_Torrance /
time_Cycles is taken on a grid of errors where both curves exist (geometric mean over the overlap,
and at the errors Cycles reaches with 16, 128 and 1024 samples). In Blender 4.x runs (results with
several Cycles variants: light tree, path guiding) the ratio is also given against each variant.
"""

import itertools
import json
import math
import os
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TARGET = 0.5          # the issue's goal: equal error in at most half of Cycles' time


def curve(rows, key="rel_mse_corrected", floor=0.0):
    """(log time, log error) points of an engine, monotone: error only falls as time grows.
    Points whose error is below `floor` (where the reference's own noise dominates) are left out."""
    pts = sorted((r["seconds"], r[key]) for r in rows
                 if r.get(key, 0) > max(floor, 0.0) and r["seconds"] > 0)
    out = []
    best = math.inf
    for t, e in pts:
        if e < best:
            best = e
            out.append((math.log(t), math.log(e)))
    return out


def time_at_error(c, log_e):
    """log time at which the monotone curve c reaches log error log_e (None outside it)."""
    if not c:
        return None
    es = [p[1] for p in c]
    if log_e > es[0] or log_e < es[-1]:
        return None
    for (t0, e0), (t1, e1) in itertools.pairwise(c):
        if e1 <= log_e <= e0:
            if e0 == e1:
                return t0
            w = (e0 - log_e) / (e0 - e1)
            return t0 + w * (t1 - t0)
    return c[0][0] if abs(log_e - es[0]) < 1e-12 else None


def equal_error(t_rows, c_rows, key="rel_mse_corrected", floor=0.0):
    """dict(geomean, lo, hi, at={spp: ratio}, overlap=(e_lo, e_hi)) of time_T/time_C at equal error,
    using only errors above `floor`."""
    ct, cc = curve(t_rows, key, floor), curve(c_rows, key, floor)
    res = dict(geomean=None, lo=None, hi=None, at={}, overlap=None)
    if len(ct) < 1 or len(cc) < 1:
        return res
    e_hi = min(ct[0][1], cc[0][1])
    e_lo = max(ct[-1][1], cc[-1][1])
    if e_hi >= e_lo:
        grid = np.linspace(e_lo, e_hi, 41) if e_hi > e_lo else np.array([e_lo])
        ratios = []
        for e in grid:
            a, b = time_at_error(ct, e), time_at_error(cc, e)
            if a is not None and b is not None:
                ratios.append(a - b)
        if ratios:
            res.update(geomean=math.exp(float(np.mean(ratios))), lo=math.exp(min(ratios)),
                       hi=math.exp(max(ratios)), overlap=(math.exp(e_lo), math.exp(e_hi)))
    for spp in (16, 128, 1024):
        row = next((r for r in c_rows if r["spp"] == spp), None)
        if row is None or row.get(key, 0) <= max(floor, 0.0):
            continue
        e = math.log(row[key])
        a, b = time_at_error(ct, e), time_at_error(cc, e)
        if a is not None and b is not None:
            res["at"][spp] = math.exp(a - b)
        elif a is None and ct and e < ct[-1][1]:
            res["at"][spp] = math.inf        # Torrance never got that low
    return res


def fmt_ratio(x):
    if x is None:
        return "—"
    if math.isinf(x):
        return "not reached"
    return f"{x:.2f}"


ENGINE_STYLES = (("tab:red", "o"), ("tab:blue", "s"), ("tab:green", "^"), ("tab:purple", "v"),
                 ("tab:orange", "D"))


def cycles_names(res):
    """The Cycles variants of a run ("cycles" alone before Blender 4.x runs)."""
    return list(res["settings"].get("cycles_variants", {"cycles": {}}))


def variant_ratios(scene_data, names):
    """{variant: equal_error(Torrance, variant)} on the corrected relMSE."""
    floor = scene_data["reference"]["noise_rel_mse"]
    return {v: equal_error(scene_data["torrance"], scene_data[v], floor=floor) for v in names}


def plot_scene(name, data, path, engines=("torrance", "cycles")):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    for engine, (color, marker) in zip(engines, ENGINE_STYLES, strict=False):
        rows = data[engine]
        t = [r["seconds"] for r in rows]
        ax1.loglog(t, [max(r["rel_mse"], 1e-12) for r in rows], marker=marker, color=color,
                   alpha=0.35, lw=1, ms=3)
        corr = [(r["seconds"], r["rel_mse_corrected"]) for r in rows if r["rel_mse_corrected"] > 0]
        if corr:
            ax1.loglog(*zip(*corr, strict=True), marker=marker, color=color, lw=1.8, ms=5,
                       label=f"{engine.capitalize()}")
        for r in rows:
            if r["spp"] in (1, 16, 256, 1024) and r["rel_mse_corrected"] > 0:
                ax1.annotate(str(r["spp"]), (r["seconds"], r["rel_mse_corrected"]), fontsize=7,
                             xytext=(3, 3), textcoords="offset points", color=color)
        ax2.semilogx(t, [1.0 - r["ssim"] for r in rows], marker=marker, color=color, lw=1.5,
                     ms=4, label=engine.capitalize())
    floor = data["reference"]["noise_rel_mse"]
    ax1.axhline(floor, color="gray", ls=":", lw=1, label="reference noise")
    ax1.set_xlabel("wall time of bpy.ops.render.render (s)")
    ax1.set_ylabel("relMSE vs reference (corrected; faint: raw)")
    ax1.set_title(f"{name}: error vs time")
    ax1.grid(True, which="both", alpha=0.3)
    ax1.legend(fontsize=8)
    ax2.set_yscale("log")
    ax2.set_xlabel("wall time (s)")
    ax2.set_ylabel("1 - SSIM")
    ax2.set_title(f"{name}: 1 - SSIM vs time")
    ax2.grid(True, which="both", alpha=0.3)
    ax2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)


def plot_references(names, path, reference_dir="references"):
    """The stored references side by side (tone-mapped like the SSIM input)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import OpenImageIO as oiio
    fig, axes = plt.subplots(1, len(names), figsize=(2.2 * len(names), 2.0))
    for ax, name in zip(np.atleast_1d(axes), names, strict=True):
        inp = oiio.ImageInput.open(os.path.join(ROOT, reference_dir, f"cmp_{name}.exr"))
        spec = inp.spec()
        img = np.asarray(inp.read_image(0, 0, 0, 3, oiio.FLOAT)).reshape(spec.height, spec.width, 3)
        inp.close()
        x = np.maximum(img, 0.0)
        ax.imshow(np.clip((x / (1.0 + x)) ** (1.0 / 2.2), 0, 1))
        ax.set_title(name, fontsize=9)
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def write_report(directory):
    with open(os.path.join(directory, "results.json")) as f:
        res = json.load(f)
    scenes = res["scenes"]
    variants = cycles_names(res)
    s = res["settings"]
    for d in scenes.values():
        for engine in ("torrance", *variants):
            for r in d[engine]:
                r["dssim"] = 1.0 - r["ssim"]
    lines = []
    add = lines.append
    add(f"# Speed against error: Torrance vs Cycles {res['blender'].split()[0]}")
    add("")
    add(f"Generated by `scripts/benchmark` (never edited by hand) on {res['made']}. "
        f"Raw data: [results.json](results.json).")
    add("")
    m = res["machine"]
    dirty = (" (with uncommitted changes in core/ or python_addon/)"
             if res.get("torrance_dirty") else "")
    add(f"- Machine: {m['cpu']}, {m['cores']} cores, {m['system']}; load average at the start "
        f"{', '.join(f'{x:.2f}' for x in m['load_average'])} (a shared machine: timings carry "
        f"its load).")
    add(f"- Blender {res['blender']} (Cycles CPU); "
        f"Torrance at commit `{res['torrance_commit']}`{dirty}, "
        f"model {s.get('torrance_model', 'PRINCIPLED')} (Cycles' Principled "
        f"{'v2' if s.get('torrance_model') == 'PRINCIPLED_V2' else 'v1'}).")
    add(f"- {s['width']}x{s['height']} pixels, seed {s['seed']}, samples 1, 2, 4, … up to "
        f"{s['max_spp']} (an engine stops doubling after a render over {s['cap_seconds']:.0f} s); "
        f"both engines in one Blender process, alternating at each sample count.")
    add(f"- Time = wall time of `bpy.ops.render.render` (scene export/sync + render), measured the "
        f"same way for both after an untimed warm-up render. Blender start-up (with the add-on), "
        f"not included: {res['blender_startup_seconds']:.2f} s.")
    add(f"- One image's relMSE is dominated by a few fireflies: a point whose first render takes "
        f"under 1 s (5 s) is rendered with up to {s.get('max_seeds', 4)} (2) seeds, errors "
        f"averaged, time = median.")
    distribution = ("GGX" if len(variants) == 1 else
                    "the Principled nodes' own distribution")
    add("- Cycles: no denoising, no adaptive sampling, no clamping, no glossy blur, "
        f"light threshold 0, Blackman-Harris 1.5 px, {distribution}; bounces as each scene's "
        "BOUNCES (Torrance the same).")
    if len(variants) > 1:
        add("- Cycles variants, each a separate curve (\"cycles\" = the configuration above, "
            "light tree and path guiding off): "
            + "; ".join(f"`{v}`: " + ", ".join(f"{k}={val}" for k, val in
                                                s["cycles_variants"][v].items())
                        for v in variants)
            + ". Path guiding learns during the first `guiding_training_samples` (Cycles' "
            "default 128) samples of a render.")
    add(f"- Error against the stored converged Cycles reference "
        f"(`{s.get('references', 'references')}/`, made by `scripts/references`): "
        "relMSE = mean((I−R)²/(R²+0.01)) minus the reference's own noise "
        "term (measured from its two seeds; corrected errors below that term are not used), "
        "and SSIM of tone-mapped images. Equal-error time "
        "ratio = time_Torrance / time_Cycles at the same corrected relMSE, interpolating "
        "log-error against log-time; **below 1 Torrance is faster; the goal is ≤ "
        f"{TARGET}**.")
    add(f"- Total benchmark time: {res['total_seconds'] / 60:.1f} min.")
    add("")
    add("## Summary")
    add("")
    add("| scene | equal-error time ratio T/C (relMSE; geo. mean over overlap) | range "
        "| at Cycles' 16 / 128 / 1024 spp error | goal ≤ 0.5 "
        "| same, relMSE without the worst 0.1 % pixels | same by 1−SSIM "
        "| bias (mean ratio T/ref at max spp) |")
    add("|---|---|---|---|---|---|---|---|")
    summary = {}
    for name, d in scenes.items():
        eq = equal_error(d["torrance"], d["cycles"], floor=d["reference"]["noise_rel_mse"])
        eq_ssim = equal_error(d["torrance"], d["cycles"], key="dssim")
        eq_trim = equal_error(d["torrance"], d["cycles"], key="rel_mse_trim_corrected",
                              floor=d["reference"]["noise_rel_mse"])
        summary[name] = eq
        rng = f"{fmt_ratio(eq['lo'])}–{fmt_ratio(eq['hi'])}" if eq["lo"] is not None else "—"
        at = " / ".join(fmt_ratio(eq["at"].get(k)) for k in (16, 128, 1024))
        met = "—" if eq["geomean"] is None else ("yes" if eq["geomean"] <= TARGET else "no")
        last = d["torrance"][-1] if d["torrance"] else None
        bias = f"{last['ratio']:.4f} ({last['spp']} spp)" if last else "—"
        add(f"| [{name}](#{name.replace('_', '-')}) | {fmt_ratio(eq['geomean'])} | {rng} | {at} "
            f"| {met} | {fmt_ratio(eq_trim['geomean'])} | {fmt_ratio(eq_ssim['geomean'])} "
            f"| {bias} |")
    add("")
    ok = [n for n, e in summary.items() if e["geomean"] is not None and e["geomean"] <= TARGET]
    add(f"Goal (equal error in ≤ {TARGET}× Cycles' time) met on {len(ok)} of {len(summary)} "
        f"scenes{': ' + ', '.join(ok) if ok else ''}.")
    add("")
    if len(variants) > 1:
        add("## Torrance against each Cycles variant")
        add("")
        add("Equal-error time ratio Torrance / Cycles variant (relMSE, geometric mean over the "
            "overlap of the two curves, its range in brackets); below 1 Torrance is faster.")
        add("")
        add("| scene | " + " | ".join(f"T / `{v}`" for v in variants) + " |")
        add("|---|" + "---|" * len(variants))
        for name, d in scenes.items():
            cells = []
            for eq in variant_ratios(d, variants).values():
                rng = (f" ({fmt_ratio(eq['lo'])}–{fmt_ratio(eq['hi'])})"
                       if eq["lo"] is not None else "")
                cells.append(fmt_ratio(eq["geomean"]) + rng)
            add(f"| {name} | " + " | ".join(cells) + " |")
        add("")
    add("## What each specialisation buys")
    add("")
    if s.get("toggle_repeats") == 0:
        add("Not measured in this run (`--toggle-repeats 0`).")
    elif not res.get("toggles"):
        add("The core exposes no specialisation toggles yet (no boolean fields on "
            "`torrance_core.RenderSettings` beyond the known ones). The hook is in place: "
            "`scripts/benchmark.py` discovers any such field (e.g. `specialize`) and renders every "
            f"scene at {s['toggle_spp']} spp with it on and off; this section then lists time and "
            "error for each.")
    else:
        add(f"Torrance at {s['toggle_spp']} spp with its defaults, then with one option of the "
            f"core switched at a time (everything else default), {s.get('toggle_repeats', 1)} "
            f"interleaved rounds, median times. Time = the core's render time (the export is the "
            f"same for all); speed-up = time(switched) / time(default); "
            f"error ratio = relMSE(switched) / relMSE(default); efficiency gain = "
            f"(time × relMSE)(switched) / (time × relMSE)(default), i.e. how much longer the "
            f"switched core needs for the same error (relMSE ∝ 1/samples). Above 1: the "
            f"default choice pays. Single renders at a fixed seed: ratios of relMSE near 1 are "
            f"within noise.")
        add("")
        for t in res["toggles"]:
            field = t["field"]
            add(f"**`{field}` = {t['default']!r} (default) vs {t['other']!r}**")
            add("")
            add("| scene | core time default (s) | switched (s) | speed-up | relMSE default "
                "| relMSE switched | error ratio | efficiency gain |")
            add("|---|---|---|---|---|---|---|---|")
            gains = []
            for name, d in scenes.items():
                tg = d.get("toggles", {}).get(field)
                if tg is None:
                    continue
                on, off = tg["on"], tg["off"]
                t_on = on.get("core_seconds") or on["seconds"]
                t_off = off.get("core_seconds") or off["seconds"]
                speed = t_off / max(t_on, 1e-9)
                err = off["rel_mse"] / max(on["rel_mse"], 1e-30)
                gain = speed * err
                gains.append(gain)
                add(f"| {name} | {t_on:.3f} | {t_off:.3f} | {speed:.2f}× | "
                    f"{on['rel_mse']:.3e} | {off['rel_mse']:.3e} | {err:.2f} | {gain:.2f}× |")
            if gains:
                add("")
                add(f"Geometric mean efficiency gain of `{field}` = {t['default']!r}: "
                    f"{math.exp(sum(math.log(g) for g in gains) / len(gains)):.2f}×.")
            add("")
    add("")
    add("## Scenes")
    add("")
    try:
        plot_references(list(scenes), os.path.join(directory, "references.png"),
                        s.get("references", "references"))
        add("The references (Cycles, tone-mapped x/(1+x), gamma 2.2):")
        add("")
        add("![references](references.png)")
    except Exception as exc:          # the report does not depend on this picture
        add(f"(No picture of the references: {exc}.)")
    for name, d in scenes.items():
        png = f"{name}.png"
        plot_scene(name, d, os.path.join(directory, png), ("torrance", *variants))
        eq = summary[name]
        add("")
        add(f"### {name}")
        add("")
        add(f"{d['title']}. Reference: {d['reference']['samples']} Cycles samples, noise relMSE "
            f"{d['reference']['noise_rel_mse']:.2e}. Max bounces {d['bounces']}. "
            f"Equal-error time ratio T/C: **{fmt_ratio(eq['geomean'])}**"
            + (f" over relMSE {eq['overlap'][0]:.2e}–{eq['overlap'][1]:.2e}"
               if eq["overlap"] else "")
            + ".")
        add("")
        add(f"![{name}]({png})")
        add("")
        add("| spp | Torrance s | relMSE | trimmed | SSIM | mean ratio "
            "| Cycles s | relMSE | trimmed | SSIM | mean ratio |")
        add("|---|---|---|---|---|---|---|---|---|---|---|")
        by_spp = {}
        for engine in ("torrance", "cycles"):
            for r in d[engine]:
                by_spp.setdefault(r["spp"], {})[engine] = r
        for spp in sorted(by_spp):
            cells = []
            for engine in ("torrance", "cycles"):
                r = by_spp[spp].get(engine)
                cells += ([f"{r['seconds']:.3f}", f"{r['rel_mse']:.3e}", f"{r['rel_mse_trim']:.3e}",
                           f"{r['ssim']:.4f}", f"{r['ratio']:.4f}"] if r else ["—"] * 5)
            add(f"| {spp} | " + " | ".join(cells) + " |")
        if len(variants) > 1:
            add("")
            add("Cycles variants, seconds / relMSE:")
            add("")
            add("| spp | " + " | ".join(f"`{v}`" for v in variants) + " |")
            add("|---|" + "---|" * len(variants))
            for spp in sorted(by_spp):
                cells = [f"{r['seconds']:.3f} / {r['rel_mse']:.3e}" if r else "—"
                         for r in (next((x for x in d[v] if x["spp"] == spp), None)
                                   for v in variants)]
                add(f"| {spp} | " + " | ".join(cells) + " |")
    add("")
    path = os.path.join(directory, "report.md")
    with open(path, "w") as f:
        f.write("\n".join(lines))
    return path, summary


def main():
    directory = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "docs", "benchmark")
    path, summary = write_report(directory)
    for name, eq in summary.items():
        print(f"benchmark: {name:13s} equal-error time ratio Torrance/Cycles "
              f"{fmt_ratio(eq['geomean'])} (range {fmt_ratio(eq['lo'])}–{fmt_ratio(eq['hi'])})")
    print(f"benchmark: wrote {path}")


if __name__ == "__main__":
    main()
