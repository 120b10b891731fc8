# SPDX-License-Identifier: Apache-2.0
"""Measures the paper's experiments (rendered by torrance_tools/sweep/experiments.py): per-region
statistics, trends and the verdict on each of the paper's claims (written up by report.py).

Everything is measured on the linear EXR frames, inside the pixels that see the material in
question (runner.py's masks.npz: what each pixel centre sees, eroded by one pixel so that pixels
mixed by the 1.5 px filter are left out). Luminance is Rec. 709 Y.

Statistics of a region (all in torrance_tools.sweep.measure.region_stats):
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

import numpy as np

from torrance_tools.compare import REC709_LUMA, luminance, read_exr

MARGIN = 1.5
PEAK_PIXELS = 5


# --------------------------------------------------------------------------------------------
# Measuring

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
    y_base = float(np.dot(base[:3], REC709_LUMA))
    e_sun = sum(lt["energy"] * float(np.dot(lt["color"][:3], REC709_LUMA))
                for lt in info.get("lights", []) if lt["type"] == "SUN")
    world = info.get("world") or {}
    y_sky = (float(np.dot(world.get("color", [0, 0, 0])[:3], REC709_LUMA))
             * world.get("strength", 1.0))
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
            res[engine]["against"] = [f"{x[i]:g}→{x[j]:g}"
                                      for i, j in zip(order[:-1], order[1:], strict=True)
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
