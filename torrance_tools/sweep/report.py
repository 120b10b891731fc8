# SPDX-License-Identifier: Apache-2.0
"""Measures the paper's experiments (rendered by torrance_tools/sweep/experiments.py) and writes report.md.

Everything is measured on the linear EXR frames, inside the pixels that see the material in
question (runner.py's masks.npz: what each pixel centre sees, eroded by one pixel so that pixels
mixed by the 1.5 px filter are left out). Luminance is Rec. 709 Y.

Statistics of a region (all in torrance_tools.sweep.report.region_stats):
* highlight area: the share of its pixels brighter than T = 1.5 x (Y_base x E_sun / pi + Y_sky),
  where Y_base is the base colour's luminance, E_sun the suns' irradiance and Y_sky the sky's
  radiance. A surface of that colour can send no more than Y_base x E_sun / pi (Lambertian response
  to the sun, facing it) plus Y_sky (a perfect mirror of the uniform sky): a pixel above T shows the
  sun reflected specularly. The 1.5 margin covers noise and Burley's brighter grazing response
  (Cycles).
* peak: the mean Y of the region's 5 brightest pixels (the glints' brightness, however few);
* glint concentration: the share of the region's light in its brightest 1 % of pixels (1 % for an
  evenly lit region; near 100 % for a few mirror glints), the "mirror-like" measure;
* median Y (the body of the material), mean Y;
* glitter spread (water): the horizontal standard deviation of the light above each row's median,
  as a fraction of the image width: the width of the sun's reflection path.
Trends are Spearman rank correlations with the swept value; a verdict needs |rho| >= 0.8 with the
expected sign and a change end to end of at least 10 %.
"""

import json
import math
import os
import shutil
import subprocess
import time

import numpy as np

from torrance_tools import REPO
from torrance_tools.compare import read_exr
from torrance_tools.sweep import sheet

LUMA = np.array([0.2126, 0.7152, 0.0722])
MARGIN = 1.5
PEAK_PIXELS = 5


# --------------------------------------------------------------------------------------------
# Measuring

def luminance(img):
    return np.asarray(img, dtype=np.float64)[..., :3] @ LUMA


def erode(mask):
    """3x3 erosion (pixels whose 8 neighbours are in the mask too)."""
    m = np.pad(mask, 1, constant_values=False)
    out = np.ones_like(mask)
    h, w = mask.shape
    for dy in (0, 1, 2):
        for dx in (0, 1, 2):
            out &= m[dy:dy + h, dx:dx + w]
    return out


def spearman(x, y):
    x, y = np.asarray(x, float), np.asarray(y, float)
    if len(x) < 3 or np.ptp(x) == 0 or np.ptp(y) == 0 or not np.all(np.isfinite(y)):
        return float("nan")
    rx = np.argsort(np.argsort(x)).astype(float)
    ry = np.argsort(np.argsort(y)).astype(float)
    return float(np.corrcoef(rx, ry)[0, 1])


def verdict(x, y, sign, min_change=0.10):
    """Whether y follows the expected direction (sign +1: rises with x, -1: falls) over x."""
    rho = spearman(x, y)
    x, y = np.asarray(x, float), np.asarray(y, float)
    lo, hi = y[np.argmin(x)], y[np.argmax(x)]
    change = (hi - lo) / max(abs(lo), abs(hi), 1e-12)
    if not math.isfinite(rho):
        word = "no trend"
    elif np.sign(rho) == sign and abs(rho) >= 0.8 and abs(change) >= min_change:
        word = "agrees"
    elif np.sign(rho) == sign and abs(rho) >= 0.5:
        word = "agrees weakly"
    elif np.sign(rho) == -sign and abs(rho) >= 0.5:
        word = "disagrees"
    else:
        word = "no clear trend"
    return dict(rho=rho, change=float(change), verdict=word)


def highlight_threshold(plan, material):
    """T of the module docstring for a material of the sweep's scene."""
    info = plan.get("scene_info") or {}
    base = (info.get("materials", {}).get(material) or {}).get("Base Color", [0.8, 0.8, 0.8])
    y_base = float(np.dot(base[:3], LUMA))
    e_sun = sum(l["energy"] * float(np.dot(l["color"][:3], LUMA))
                for l in info.get("lights", []) if l["type"] == "SUN")
    world = info.get("world") or {}
    y_sky = float(np.dot(world.get("color", [0, 0, 0])[:3], LUMA)) * world.get("strength", 1.0)
    return MARGIN * (y_base * e_sun / math.pi + y_sky)


def region_stats(img, mask, threshold):
    Y = luminance(img)
    y = Y[mask]
    if y.size == 0:
        return None
    total = y.sum()
    ranked = np.sort(y)[::-1]
    top = ranked[:max(1, int(round(0.01 * y.size)))]
    rgb = np.asarray(img, float)[..., :3][mask].mean(axis=0)
    return dict(pixels=int(y.size), mean=float(y.mean()), median=float(np.median(y)),
                peak=float(ranked[:PEAK_PIXELS].mean()), max=float(y.max()),
                highlight=float(np.mean(y > threshold)),
                concentration=float(top.sum() / total) if total > 0 else float("nan"),
                green_share=float(rgb[1] / max(rgb.sum(), 1e-12)), rgb=[float(c) for c in rgb])


def glitter_spread(img, mask):
    """Horizontal std of the light above each row's median (fraction of the width)."""
    Y = luminance(img)
    h, w = Y.shape
    xs = np.arange(w, dtype=float)
    weights = np.zeros(w)
    for j in range(h):
        row = mask[j]
        if row.sum() < 8:
            continue
        excess = np.where(row, np.maximum(Y[j] - np.median(Y[j][row]), 0.0), 0.0)
        weights += excess
    if weights.sum() <= 0:
        return float("nan")
    mean = (weights * xs).sum() / weights.sum()
    return float(np.sqrt((weights * (xs - mean) ** 2).sum() / weights.sum()) / w)


class SweepData:
    """A rendered sweep: plan, per-frame records and images, masks."""

    def __init__(self, directory):
        self.dir = directory
        with open(os.path.join(directory, "results.json")) as f:
            self.results = json.load(f)
        self.plan = self.results["plan"]
        self.frames = [r for r in self.results["frames"] if r["exr"]]
        masks = np.load(os.path.join(directory, "masks.npz"))
        self.material_names = [str(n) for n in masks["material_names"]]
        self.labels = masks["material"]
        self._images = {}

    def image(self, row):
        key = row["frame"]
        if key not in self._images:
            self._images[key] = read_exr(os.path.join(self.dir, row["exr"]))
        return self._images[key]

    def region(self, material):
        if material not in self.material_names:
            return None
        return erode(self.labels == self.material_names.index(material))

    def values(self, name):
        return [float(r["inputs"][name]) for r in self.frames]

    def seconds(self):
        return sum(float(r["seconds"] or 0.0) for r in self.frames)


# --------------------------------------------------------------------------------------------
# Per experiment

def analyse_sweep(data, exp):
    """Per-frame statistics of the swept material (and the stone, the control)."""
    mat = exp["material"]
    mask = data.region(mat)
    T = highlight_threshold(data.plan, mat)
    rows = []
    stone = data.region("Stone")
    T_stone = highlight_threshold(data.plan, "Stone")
    for r in data.frames:
        img = data.image(r)
        s = region_stats(img, mask, T)
        if stone is not None:
            s["stone_mean"] = region_stats(img, stone, T_stone)["mean"]
        if mat == "Water":
            s["spread"] = glitter_spread(img, mask)
        s["value"] = float(r["inputs"][exp["input"]])
        s["seconds"] = r["seconds"]
        rows.append(s)
    return dict(threshold=T, rows=rows, pixels=int(mask.sum()))


def analyse_chart(data):
    """Per sphere: peak, highlight saturation, median; keyed by (metallic, roughness)."""
    img = data.image(data.frames[0])
    Y = luminance(img)
    spheres = {}
    h, w = Y.shape
    for name in data.material_names:
        if not name.startswith("Sphere M"):
            continue
        m, r = (float(t[1:]) for t in name.split()[1:3])
        mask = data.region(name)
        if mask is None or mask.sum() < 10:
            continue
        y = Y[mask]
        rgb = np.asarray(img, float)[..., :3][mask]
        n_top = max(3, int(round(0.03 * y.size)))
        top = np.argsort(y)[::-1][:n_top]
        hl = rgb[top].mean(axis=0)
        sat = 1.0 - hl.min() / max(hl.max(), 1e-12)
        yy, xx = np.nonzero(mask)
        spheres[(m, r)] = dict(peak=float(y.max()), median=float(np.median(y)),
                               highlight_saturation=float(sat), pixels=int(mask.sum()),
                               center=[float(xx.mean()) / w, float(yy.mean()) / h])
    return spheres


# --------------------------------------------------------------------------------------------
# Claims

def claims_for(exp, stats_by_engine, extra):
    """[(figure, claim, source, statistic, {engine: verdict dict}), ...] for one experiment."""
    out = []
    fig = exp["figure"]

    def add(claim, source, stat_label, key, sign, stats=stats_by_engine, xkey="value"):
        res = {}
        for engine, st in stats.items():
            x = [row[xkey] for row in st["rows"]]
            y = [row[key] for row in st["rows"]]
            res[engine] = verdict(x, y, sign)
            res[engine]["ends"] = (y[0], y[-1])          # first and last frame (paper's order)
            # Steps between neighbouring values that go against the expected direction.
            order = np.argsort(x)
            res[engine]["against"] = [f"{x[i]:g}→{x[j]:g}" for i, j in zip(order[:-1], order[1:])
                                      if (y[j] - y[i]) * sign < 0]
        out.append(dict(figure=fig, claim=claim, source=source, statistic=stat_label,
                        key=key, sign=sign, results=res))

    if exp["id"].startswith("grass_metallic"):
        add("the sun's specular highlight area shrinks as metallic falls", "paper",
            "highlight area of the grass", "highlight", +1)
        add("the grass body turns from a dark tinted mirror to green diffuse as metallic falls",
            "expected", "median Y of the grass", "median", -1)
        add("the highlight dims as metallic falls (F0 falls from the base colour to 0.04)",
            "expected", "peak Y of the grass", "peak", +1)
    elif exp["id"] == "grass_roughness_m05":
        add("reflection goes from mirror-like glints to a diffuse sheen as roughness rises",
            "paper", "glint concentration of the grass", "concentration", -1)
        add("the highlight's peak dims as roughness rises", "expected", "peak Y of the grass",
            "peak", -1)
    elif exp["id"] == "water_roughness_m1":
        add("reflection goes from mirror-like to diffuse as roughness rises", "paper",
            "glint concentration of the water", "concentration", -1)
        add("the sun's glitter dims as roughness rises", "expected", "peak Y of the water",
            "peak", -1)
        add("the sun's reflection path widens as roughness rises", "expected",
            "glitter spread (fraction of width)", "spread", +1)
    return out


def stone_control(exp, stats_by_engine):
    """The stone's mean Y across the sweep: max relative deviation from its average."""
    res = {}
    for engine, st in stats_by_engine.items():
        v = np.array([row.get("stone_mean", np.nan) for row in st["rows"]])
        if not np.all(np.isfinite(v)):
            continue
        dev = float(np.max(np.abs(v - v.mean())) / v.mean())
        res[engine] = dict(deviation=dev, verdict="agrees" if dev < 0.05 else "disagrees",
                           mean=float(v.mean()))
    return res


def chart_claims(spheres_by_engine):
    """Claims on the sphere chart, each over all rows/columns."""
    out = []
    specs = [("highlights dim as roughness rises (every metallic row)", "peak", "roughness", -1,
              "brightest pixel per sphere", None),
             ("metal highlights take the base colour, dielectric ones stay white (every "
              "roughness column up to 0.4, where a highlight stands out)", "highlight_saturation",
              "metallic", +1, "saturation of the brightest 3 % of the sphere", 0.4),
             ("the body darkens as metallic rises (every roughness column)", "median", "metallic",
              -1, "median Y per sphere", None)]
    for claim, key, along, sign, label, max_roughness in specs:
        res = {}
        for engine, spheres in spheres_by_engine.items():
            ms = sorted({k[0] for k in spheres})
            rs = sorted({k[1] for k in spheres})
            if max_roughness is not None:
                rs = [r for r in rs if r <= max_roughness + 1e-9]
            groups = ms if along == "roughness" else rs
            verdicts = []
            for g in groups:
                keys = [(g, r) for r in rs] if along == "roughness" else [(m, g) for m in ms]
                keys = [k for k in keys if k in spheres]
                x = [k[1] if along == "roughness" else k[0] for k in keys]
                y = [spheres[k][key] for k in keys]
                verdicts.append(verdict(x, y, sign))
            n_ok = sum(v["verdict"] == "agrees" for v in verdicts)
            rhos = [v["rho"] for v in verdicts]
            res[engine] = dict(verdict="agrees" if n_ok == len(verdicts) else
                               ("agrees in part" if n_ok else "disagrees"),
                               agreeing=n_ok, groups=len(verdicts),
                               rho=float(np.nanmean(rhos)) if rhos else float("nan"))
        out.append(dict(figure="4-5", claim=claim, source="expected", statistic=label, key=key,
                        sign=sign, results=res))
    return out


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
    for ax, (key, label) in zip(axes, keys):
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
    for ax, (engine, data) in zip(axes, data_by_engine.items()):
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
                data_by_engine[engine] = SweepData(d)
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
            spheres = {e: analyse_chart(d) for e, d in data_by_engine.items()}
            plot = os.path.join(plots, f"{exp['id']}.png")
            plot_chart(data_by_engine, spheres, plot, engine_label)
            images.append((os.path.relpath(plot, out), f"{exp['id']}_labeled.png"))
            lines += [f"![{exp['id']} labeled]({os.path.relpath(plot, out)})", ""]
            cl = chart_claims(spheres)
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
                              "| metallic \\ roughness | " + " | ".join(f"{r:g}" for r in rs) + " |",
                              "|---|" + "---|" * len(rs)]
                    for m in ms:
                        lines.append(f"| {m:g} | " + " | ".join(
                            _fmt(sp[(m, r)][key]) if (m, r) in sp else "–" for r in rs) + " |")
                    lines.append("")
            summary["experiments"][exp["id"]] = {
                e: {f"M{k[0]:g} R{k[1]:g}": v for k, v in sp.items()} for e, sp in spheres.items()}
        else:
            stats = {e: analyse_sweep(d, exp) for e, d in data_by_engine.items()}
            plot = os.path.join(plots, f"{exp['id']}.png")
            plot_sweep(exp, stats, plot, engine_label)
            images.append((os.path.relpath(plot, out), f"{exp['id']}_trends.png"))
            lines += [f"![{exp['id']} trends]({os.path.relpath(plot, out)})", ""]
            cl = claims_for(exp, stats, None)
            claims += cl
            stone = stone_control(exp, stats)
            if stone:
                claims.append(dict(figure=exp["figure"], claim="the stone (control) is unchanged",
                                   source="paper", statistic="stone mean Y, max deviation",
                                   key="stone_mean", sign=0, results=stone))
            for engine, st in stats.items():
                has_stone = "stone_mean" in st["rows"][0]
                is_water = exp["material"] == "Water"
                head = (f"| {exp['input']} | highlight area | peak Y | max Y | glint concentration | "
                        f"median Y | mean RGB |" + (" glitter spread |" if is_water else "")
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
             "figures show by physics (\"expected\") — the statistic that tests it, and per renderer "
             "whether the measurement agrees: Spearman ρ of the statistic against the swept "
             "value, the statistic at the first → last value of the paper's order, and the steps "
             "between neighbouring values that go against the claimed direction, if any.", "",
             "| Fig. | claim | source | statistic | " + " | ".join(engine_label.get(e, e) for e in engines)
             + " |", "|---|---|---|---|" + "---|" * len(engines)]
    for c in claims:
        head.append(f"| {c['figure']} | {c['claim']} | {c['source']} | {c['statistic']} | "
                    + " | ".join(_verdict_cell(c["results"].get(e)) for e in engines) + " |")
    head += ["", _disagreement_text(claims, engines, engine_label), ""]
    head += _side_by_side(summary, engines, engine_label)
    method = ["## Method", "", __doc__.split("\n\n", 1)[1].strip(), "",
              "Reproduce: `scripts/experiments` (add `--final` for 640x480 at 128 spp, "
              "`--no-cycles` for Torrance alone, `--publish` to copy this report to "
              "docs/experiments/). One sweep by hand: `scripts/blender -b out/experiments/scenes/"
              "grass_stone.blend --python torrance_tools/sweep/runner.py -- --material Grass --input "
              "Metallic --values 1,0.8,0.6,0.4,0.2,0 --set Roughness=0.2 --out DIR`.", ""]
    text = "\n".join(head + [l for s in sections for l in s] + method) + "\n"
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
            r = [a["mean"] / b["mean"] for a, b in zip(t["rows"], c["rows"])]
            stone = ""
            if "stone_mean" in t["rows"][0]:
                rs = [a["stone_mean"] / b["stone_mean"] for a, b in zip(t["rows"], c["rows"])]
                stone = f"{min(rs):.2f} – {max(rs):.2f}"
            lines.append(f"| {who} | {exp_id} | {min(r):.2f} – {max(r):.2f} | {stone} |")
    if not lines:
        return []
    return ["## Torrance and Cycles side by side", "",
            "Torrance / Cycles ratio of the mean luminance of each region over a sweep's frames "
            "(sphere chart: of each sphere's median Y, averaged over a metallic row). Cycles renders "
            "its Principled BSDF v1 (Burley diffuse, the specular lobe's Fresnel from the IOR, the "
            "lobes simply added); Torrance's PRINCIPLED model is that BSDF, its PAPER model the "
            "paper's Cook-Torrance (Lambert diffuse, Schlick Fresnel). The claims above compare "
            "trends within each renderer; these ratios show how far the absolute levels differ.", "",
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
            data = SweepData(d)
            n = len(data.frames)
            wall = timings.get("sweeps", {}).get(f"{e}/{exp['id']}")
            totals[e] += data.seconds()
            cells.append(f"{data.seconds():.1f}" + (f" ({wall:.1f})" if wall else ""))
        lines.append(f"| {exp['id']} | {n} | " + " | ".join(cells) + " |")
    lines.append("| total | | " + " | ".join(f"{totals[e]:.1f}" for e in engines) + " |")
    wall = timings.get("render_wall_seconds")
    scenes = sum(timings.get("scenes", {}).values())
    lines += ["", f"Render seconds are Blender's wall time per frame (export + render + save); wall "
              f"seconds include Blender's start and the pixel masks. Scene building "
              f"{scenes:.1f} s; everything (scenes, sweeps) {wall:.0f} s on {os.cpu_count()} cores."
              if wall else "", ""]
    return lines
