# SPDX-License-Identifier: Apache-2.0
"""Writes report.md of the paper's experiments: the verdicts measured by measure.py, tables, trend
plots, contact sheets and the Method (measure.py's description of the statistics)."""

import json
import math
import os
import shutil
import subprocess
import time

import numpy as np

from torrance_tools import REPO
from torrance_tools.sweep import measure, sheet


# --------------------------------------------------------------------------------------------
# Plots

def _plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


DEFAULT_LABELS = {"torrance": "Torrance", "torrance_principled": "Torrance PRINCIPLED",
                  "cycles": "Cycles"}
STYLE = {"torrance": dict(color="tab:green", marker="o", ls="-"),
         "torrance_principled": dict(color="tab:orange", marker="^", ls=":"),
         "cycles": dict(color="tab:blue", marker="s", ls="--")}


def plot_sweep(exp, stats_by_engine, path, labels):
    plt = _plt()
    keys = [("highlight", "highlight area (share of pixels)"), ("peak", "peak Y (5 brightest px)"),
            ("concentration", "glint concentration"), ("median", "median Y")]
    if exp["material"] == "Water":
        keys[0] = ("spread", "glitter spread (width fraction)")
    if any("stone_mean" in st["rows"][0] for st in stats_by_engine.values()):
        keys.append(("stone_mean", "stone mean Y (control)"))
    fig, axes = plt.subplots(1, len(keys), figsize=(3.0 * len(keys), 2.7))
    for ax, (key, label) in zip(axes, keys, strict=True):
        for engine, st in stats_by_engine.items():
            x = [row["value"] for row in st["rows"]]
            y = [row[key] for row in st["rows"]]
            ax.plot(x, y, label=labels.get(engine, engine), **STYLE.get(engine, {}))
        ax.set_xlabel(exp["input"])
        ax.set_title(label, fontsize=9)
        ax.tick_params(labelsize=8)
        if key in ("peak",):
            ax.set_yscale("log")
        if key == "stone_mean":
            lo, hi = ax.get_ylim()
            mid = 0.5 * (lo + hi)
            ax.set_ylim(min(lo, 0.8 * mid), max(hi, 1.2 * mid))
    axes[0].legend(fontsize=8)
    fig.suptitle(f"Fig. {exp['figure']}: {exp['title']}", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def plot_chart(data_by_engine, spheres_by_engine, path, labels):
    plt = _plt()
    n = len(data_by_engine)
    fig, axes = plt.subplots(1, n, figsize=(5.2 * n, 4.4), squeeze=False)
    axes = axes[0]
    for ax, (engine, data) in zip(axes, data_by_engine.items(), strict=True):
        img = sheet.to_display(data.image(data.frames[0]))
        h, w = img.shape[:2]
        ax.imshow(img)
        spheres = spheres_by_engine[engine]
        for (m, r), s in spheres.items():
            cx, cy = s["center"][0] * w, s["center"][1] * h
            ax.text(cx, cy + 0.055 * h, f"M{m:g}\nR{r:g}", color="white", fontsize=5,
                    ha="center", va="top")
        ax.set_title(f"{labels.get(engine, engine)}: rows metallic 1 (back) .. 0 "
                     f"(front); columns roughness 0.1 .. 1", fontsize=8)
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# --------------------------------------------------------------------------------------------
# Report

def _fmt(v, digits=3):
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "–"
    if not isinstance(v, float):
        return str(v)
    if v == 0:
        return "0"
    if abs(v) >= 1000 or abs(v) < 0.001:
        return f"{v:.2e}"
    return f"{v:.{digits}g}"


def _pct(v):
    return "–" if v is None or not math.isfinite(v) else f"{100 * v:.1f} %"


def _git_commit(root):
    try:
        sha = subprocess.run(["git", "-C", root, "rev-parse", "--short", "HEAD"],
                             capture_output=True, text=True, timeout=10).stdout.strip()
        dirty = subprocess.run(["git", "-C", root, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, timeout=10).stdout.strip()
        return sha + (" (with uncommitted changes)" if dirty else "")
    except Exception:
        return "unknown"


def _verdict_cell(res):
    if res is None:
        return "–"
    v = res["verdict"]
    mark = {"agrees": "yes", "agrees weakly": "weakly", "agrees in part": "in part",
            "disagrees": "**no**", "no clear trend": "no trend", "no trend": "no trend"}.get(v, v)
    if "agreeing" in res:
        return f"{mark} ({res['agreeing']}/{res['groups']}, mean ρ {res['rho']:+.2f})"
    if "deviation" in res:
        return f"{mark} (±{100 * res['deviation']:.1f} %)"
    first, last = res["ends"]
    against = res.get("against")
    return (f"{mark} (ρ {res['rho']:+.2f}; {_fmt(first)} → {_fmt(last)}"
            + (f"; against between {', '.join(against)}" if against else "") + ")")


def write_report(out, experiments, engines, timings, publish_dir=None, labels=None):
    """Measures the sweeps in `out`, writes out/report.md (+ plots); returns its path."""
    plots = os.path.join(out, "plots")
    os.makedirs(plots, exist_ok=True)
    images = []            # (path relative to out, published name)
    claims, sections, summary = [], [], dict(experiments={})
    engine_label = dict(DEFAULT_LABELS, **(labels or {}))
    first = None
    brdf_models = {}
    for exp in experiments:
        data_by_engine = {}
        for engine in engines:
            d = os.path.join(out, engine, exp["id"])
            if os.path.exists(os.path.join(d, "results.json")):
                data_by_engine[engine] = measure.SweepData(d)
        if not data_by_engine:
            continue
        first = first or next(iter(data_by_engine.values()))
        for e, d in data_by_engine.items():
            if d.plan.get("brdf_model"):
                brdf_models.setdefault(e, d.plan["brdf_model"])
        lines = [f"## Fig. {exp['figure']} — {exp['title']}", ""]
        for engine, data in data_by_engine.items():
            rel = os.path.relpath(os.path.join(data.dir, "sheet.png"), out)
            images.append((rel, f"{exp['id']}_{engine}.png"))
            lines += [f"![{exp['id']} {engine_label.get(engine, engine)}]({rel})", ""]
        if exp["input"] is None:      # the sphere chart
            spheres = {e: measure.analyse_chart(d) for e, d in data_by_engine.items()}
            plot = os.path.join(plots, f"{exp['id']}.png")
            plot_chart(data_by_engine, spheres, plot, engine_label)
            images.append((os.path.relpath(plot, out), f"{exp['id']}_labeled.png"))
            lines += [f"![{exp['id']} labeled]({os.path.relpath(plot, out)})", ""]
            cl = measure.chart_claims(spheres)
            claims += cl
            for key, label in (("peak", "brightest pixel Y"),
                               ("highlight_saturation", "highlight saturation (1 − min/max of "
                                                        "the brightest 3 %)"),
                               ("median", "median Y")):
                for engine, sp in spheres.items():
                    ms = sorted({k[0] for k in sp}, reverse=True)
                    rs = sorted({k[1] for k in sp})
                    lines += [f"**{label}, {engine_label.get(engine, engine)}** "
                              f"(rows metallic, columns roughness)", "",
                              "| metallic \\ roughness | "
                              + " | ".join(f"{r:g}" for r in rs) + " |",
                              "|---|" + "---|" * len(rs)]
                    for m in ms:
                        lines.append(f"| {m:g} | " + " | ".join(
                            _fmt(sp[(m, r)][key]) if (m, r) in sp else "–" for r in rs) + " |")
                    lines.append("")
            summary["experiments"][exp["id"]] = {
                e: {f"M{k[0]:g} R{k[1]:g}": v for k, v in sp.items()} for e, sp in spheres.items()}
        else:
            stats = {e: measure.analyse_sweep(d, exp) for e, d in data_by_engine.items()}
            plot = os.path.join(plots, f"{exp['id']}.png")
            plot_sweep(exp, stats, plot, engine_label)
            images.append((os.path.relpath(plot, out), f"{exp['id']}_trends.png"))
            lines += [f"![{exp['id']} trends]({os.path.relpath(plot, out)})", ""]
            cl = measure.claims_for(exp, stats, None)
            claims += cl
            stone = measure.stone_control(exp, stats)
            if stone:
                claims.append(dict(figure=exp["figure"], claim="the stone (control) is unchanged",
                                   source="paper", statistic="stone mean Y, max deviation",
                                   key="stone_mean", sign=0, results=stone))
            for engine, st in stats.items():
                has_stone = "stone_mean" in st["rows"][0]
                is_water = exp["material"] == "Water"
                head = (f"| {exp['input']} | highlight area | peak Y | max Y "
                        f"| glint concentration | median Y | mean RGB |"
                        + (" glitter spread |" if is_water else "")
                        + (" stone mean Y |" if has_stone else "") + " render s |")
                lines += [f"**{engine_label.get(engine, engine)}** — {exp['material']} region "
                          f"{st['pixels']} px, highlight threshold T = {st['threshold']:.3f}", "",
                          head, "|" + "---|" * (head.count("|") - 1)]
                for row in st["rows"]:
                    lines.append(
                        f"| {row['value']:g} | {_pct(row['highlight'])} | {_fmt(row['peak'])} | "
                        f"{_fmt(row['max'])} | "
                        f"{_pct(row['concentration'])} | {_fmt(row['median'])} | "
                        + ", ".join(f"{c:.3f}" for c in row["rgb"]) + " |"
                        + (f" {_pct(row['spread'])} |" if is_water else "")
                        + (f" {_fmt(row['stone_mean'])} |" if has_stone else "")
                        + f" {_fmt(row['seconds'])} |")
                lines.append("")
            summary["experiments"][exp["id"]] = stats
        lines += _claim_lines([c for c in claims if c["figure"] == exp["figure"]], engines,
                              engine_label)
        sections.append(lines)

    if first is None:
        raise SystemExit("experiments: nothing rendered yet in " + out)
    # Cross-sweep: is the highlight at roughness 0.4 dimmer than at 0.2?
    cross = _compare_r02_r04(summary["experiments"], engines)
    if cross:
        claims.append(cross)
        for lines in sections:
            if lines[0].startswith("## Fig. 4-2"):
                lines += _claim_lines([cross], engines, engine_label)

    res = first.plan["resolution"]
    models = ", ".join(f"{model}" for e, model in brdf_models.items()) or "–"
    head = ["# The paper's experiments: grass, stone and water under the sun", "",
            f"Generated by `scripts/experiments` on {time.strftime('%Y-%m-%d %H:%M')} from commit "
            f"{_git_commit(REPO)}. Sweeps {res[0]}x{res[1]} (sphere chart 1.5x), "
            f"{first.plan['samples']} samples per pixel, seed 0, max bounces 8; Torrance's BRDF "
            f"model(s): {models}; "
            + ("Cycles renders the same .blend side by side (GGX, no denoising, no clamping, "
               "no glossy blur)." if "cycles" in engines else "Torrance only.")
            + " Scenes: `scenes/make_grass_stone.py`, `make_water.py`, `make_sphere_chart.py` "
              "(seeded, no assets).", ""]
    head += _runtime_lines(out, experiments, engines, timings, engine_label)
    head += ["## Summary: the paper's observations, measured", "",
             "Each row is a claim — from the paper (as issue 5 states it) or what the paper's "
             "figures show by physics (\"expected\") — the statistic that tests it, and per "
             "renderer whether the measurement agrees: Spearman ρ of the statistic against the "
             "swept value, the statistic at the first → last value of the paper's order, and the "
             "steps between neighbouring values that go against the claimed direction, if any.", "",
             "| Fig. | claim | source | statistic | "
             + " | ".join(engine_label.get(e, e) for e in engines) + " |",
             "|---|---|---|---|" + "---|" * len(engines)]
    for c in claims:
        head.append(f"| {c['figure']} | {c['claim']} | {c['source']} | {c['statistic']} | "
                    + " | ".join(_verdict_cell(c["results"].get(e)) for e in engines) + " |")
    head += ["", _disagreement_text(claims, engines, engine_label), ""]
    head += _side_by_side(summary, engines, engine_label)
    method = ["## Method", "", measure.__doc__.split("\n\n", 1)[1].strip(), "",
              "Reproduce: `scripts/experiments` (add `--final` for 640x480 at 128 spp, "
              "`--no-cycles` for Torrance alone, `--publish` to copy this report to "
              "docs/experiments/). One sweep by hand: `scripts/blender -b out/experiments/scenes/"
              "grass_stone.blend --python torrance_tools/sweep/runner.py -- --material Grass "
              "--input Metallic --values 1,0.8,0.6,0.4,0.2,0 --set Roughness=0.2 --out DIR`.", ""]
    text = "\n".join(head + [line for s in sections for line in s] + method) + "\n"
    path = os.path.join(out, "report.md")
    with open(path, "w") as f:
        f.write(text)
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(dict(claims=claims, timings=timings), f, indent=1, default=_json_default)
    if publish_dir:
        os.makedirs(publish_dir, exist_ok=True)
        pub = text
        for rel, name in images:
            shutil.copyfile(os.path.join(out, rel), os.path.join(publish_dir, name))
            pub = pub.replace(f"]({rel})", f"]({name})")
        with open(os.path.join(publish_dir, "report.md"), "w") as f:
            f.write(pub)
    return path


def _side_by_side(summary, engines, engine_label):
    """Each Torrance run / Cycles: ratios of the regions' mean (sweeps) or median (chart) Y."""
    lines = []
    for run in [e for e in engines if e.startswith("torrance")]:
        for exp_id, stats in summary["experiments"].items():
            t, c = stats.get(run), stats.get("cycles")
            if not t or not c:
                continue
            who = engine_label.get(run, run)
            if exp_id == "sphere_chart":
                rows = {}
                for key, tv in t.items():
                    if key in c:
                        rows.setdefault(key.split()[0], []).append(tv["median"] / c[key]["median"])
                cells = ", ".join(f"{m[1:]}: {np.mean(v):.2f}" for m, v in
                                  sorted(rows.items(), key=lambda kv: -float(kv[0][1:])))
                lines.append(f"| {who} | {exp_id} | per metallic row — {cells} | |")
                continue
            # Frames pair up by position; a run with frames missing (no EXR) gives the ratios
            # of the frames both have, not an error.
            pairs = list(zip(t["rows"], c["rows"], strict=False))
            r = [a["mean"] / b["mean"] for a, b in pairs]
            stone = ""
            if "stone_mean" in t["rows"][0]:
                rs = [a["stone_mean"] / b["stone_mean"] for a, b in pairs]
                stone = f"{min(rs):.2f} – {max(rs):.2f}"
            lines.append(f"| {who} | {exp_id} | {min(r):.2f} – {max(r):.2f} | {stone} |")
    if not lines:
        return []
    return ["## Torrance and Cycles side by side", "",
            "Torrance / Cycles ratio of the mean luminance of each region over a sweep's frames "
            "(sphere chart: of each sphere's median Y, averaged over a metallic row). Cycles "
            "renders its Principled BSDF v1 (Burley diffuse, the specular lobe's Fresnel from the "
            "IOR, the lobes simply added); Torrance's PRINCIPLED model is that BSDF, its PAPER "
            "model the paper's Cook-Torrance (Lambert diffuse, Schlick Fresnel). The claims above "
            "compare trends within each renderer; these ratios show how far the absolute levels "
            "differ.", "",
            "| Torrance run | sweep | swept material | stone |", "|---|---|---|---|"] + lines + [""]


def _json_default(o):
    if isinstance(o, (np.floating, np.integer)):
        return o.item()
    if isinstance(o, tuple):
        return list(o)
    return str(o)


def _claim_lines(claims, engines, engine_label):
    if not claims:
        return []
    lines = ["Measured:", ""]
    for c in claims:
        cells = "; ".join(f"{engine_label.get(e, e)} {_verdict_cell(c['results'].get(e))}"
                          for e in engines)
        lines.append(f"- *{c['claim']}* ({c['source']}; {c['statistic']}): {cells}")
    return lines + [""]


def _compare_r02_r04(experiments, engines):
    a, b = experiments.get("grass_metallic_r02"), experiments.get("grass_metallic_r04")
    if not a or not b:
        return None
    res = {}
    for e in engines:
        if e not in a or e not in b:
            continue
        pa = {row["value"]: row["peak"] for row in a[e]["rows"]}
        pb = {row["value"]: row["peak"] for row in b[e]["rows"]}
        common = sorted(set(pa) & set(pb))
        dimmer = sum(pb[m] < pa[m] for m in common)
        ratio = float(np.exp(np.mean([np.log(pb[m] / pa[m]) for m in common])))
        res[e] = dict(verdict="agrees" if dimmer == len(common) else
                      ("agrees in part" if dimmer else "disagrees"),
                      agreeing=dimmer, groups=len(common), rho=ratio - 1.0)
    return dict(figure="4-2", claim="at roughness 0.4 the highlight is dimmer than at 0.2 "
                "(for every metallic)", source="expected",
                statistic="peak Y at r 0.4 vs 0.2 (mean ρ column: mean ratio − 1)",
                key="peak", sign=-1, results=res)


def _disagreement_text(claims, engines, engine_label):
    bad, steps = [], []
    for c in claims:
        for e in engines:
            r = c["results"].get(e)
            if r and r["verdict"] != "agrees":
                bad.append(f"{engine_label.get(e, e)} on Fig. {c['figure']} ({c['claim']}: "
                           f"{r['verdict']})")
            elif r and r.get("against"):
                steps.append(f"{engine_label.get(e, e)}, Fig. {c['figure']} {c['statistic']} "
                             f"between {', '.join(r['against'])}")
    text = ("Not (fully) borne out: " + "; ".join(bad) + "." if bad else
            "Every claim is borne out by the measurements (the trend over the whole sweep), for "
            "every renderer listed.")
    if steps:
        text += (" Single steps between neighbouring values that go the other way: "
                 + "; ".join(steps) + ".")
    return text


def _runtime_lines(out, experiments, engines, timings, engine_label):
    lines = ["## Runtime", "",
             "| sweep | frames | " + " | ".join(f"{engine_label.get(e, e)} render s (wall s)"
                                               for e in engines) + " |",
             "|---|---|" + "---|" * len(engines)]
    totals = {e: 0.0 for e in engines}
    for exp in experiments:
        cells, n = [], 0
        for e in engines:
            d = os.path.join(out, e, exp["id"])
            if not os.path.exists(os.path.join(d, "results.json")):
                cells.append("–")
                continue
            data = measure.SweepData(d)
            n = len(data.frames)
            wall = timings.get("sweeps", {}).get(f"{e}/{exp['id']}")
            totals[e] += data.seconds()
            cells.append(f"{data.seconds():.1f}" + (f" ({wall:.1f})" if wall else ""))
        lines.append(f"| {exp['id']} | {n} | " + " | ".join(cells) + " |")
    lines.append("| total | | " + " | ".join(f"{totals[e]:.1f}" for e in engines) + " |")
    wall = timings.get("render_wall_seconds")
    scenes = sum(timings.get("scenes", {}).values())
    lines += ["", f"Render seconds are Blender's wall time per frame (export + render + save); "
              f"wall seconds include Blender's start and the pixel masks. Scene building "
              f"{scenes:.1f} s; everything (scenes, sweeps) {wall:.0f} s on {os.cpu_count()} "
              f"cores." if wall else "", ""]
    return lines
