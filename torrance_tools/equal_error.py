# SPDX-License-Identifier: Apache-2.0
"""Equal-error time ratios of two error-vs-time curves (the speed/error benchmark's headline
figure, scripts/benchmark_report.py). Needs no bpy.

A curve is made monotone (the best error reached so far) and read as log(time) against
log(error), interpolated linearly; the ratio time_A / time_B is taken on a grid of errors where
both curves exist (geometric mean over the overlap, its range) and at the errors curve B reaches
with 16, 128 and 1024 samples.
"""

import itertools
import math

import numpy as np


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
    """dict(geomean, lo, hi, at={spp: ratio}, overlap=(e_lo, e_hi), bound, at_bound={spp: bound})
    of time_T/time_C at equal error, using only errors above `floor`.

    Where the curves share no range of errors because one engine's worst error is already below
    the other's best, geomean is a bound ("≤": T's first point beat C's last, so at C's best error
    T needed at most its first point's time; "≥" the other way round), and so are the `at` ratios
    at errors T only passed before its first point (at_bound)."""
    ct, cc = curve(t_rows, key, floor), curve(c_rows, key, floor)
    res = dict(geomean=None, lo=None, hi=None, at={}, overlap=None, bound="", at_bound={})
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
    if res["geomean"] is None and ct and cc:
        if ct[0][1] < cc[-1][1]:
            res.update(geomean=math.exp(ct[0][0] - cc[-1][0]), bound="≤")
        elif cc[0][1] < ct[-1][1]:
            res.update(geomean=math.exp(ct[-1][0] - cc[0][0]), bound="≥")
    for spp in (16, 128, 1024):           # plain curves only (adaptive points have thresholds)
        row = next((r for r in c_rows if r["spp"] == spp and not r.get("threshold")), None)
        if row is None or row.get(key, 0) <= max(floor, 0.0):
            continue
        e = math.log(row[key])
        a, b = time_at_error(ct, e), time_at_error(cc, e)
        if a is not None and b is not None:
            res["at"][spp] = math.exp(a - b)
        elif a is None and ct and e < ct[-1][1]:
            res["at"][spp] = math.inf        # Torrance never got that low
        elif a is None and b is not None and ct and e > ct[0][1]:
            res["at"][spp] = math.exp(ct[0][0] - b)  # Torrance was below it from its first point
            res["at_bound"][spp] = "≤"
    return res


def fmt_equal(eq, spp=None):
    """An equal_error result's geometric mean (or its `at` ratio at spp) as text, with its bound."""
    if spp is not None:
        return eq["at_bound"].get(spp, "") + fmt_ratio(eq["at"].get(spp))
    return (eq["bound"] if eq["geomean"] is not None else "") + fmt_ratio(eq["geomean"])


def meets(eq, target):
    """True/False whether the equal-error ratio is within target; None when unknown (no ratio, or
    only a lower bound within it)."""
    if eq["geomean"] is None or (eq["bound"] == "≥" and eq["geomean"] <= target):
        return None
    return eq["geomean"] <= target


def fmt_ratio(x):
    if x is None:
        return "—"
    if math.isinf(x):
        return "not reached"
    return f"{x:.2f}"
