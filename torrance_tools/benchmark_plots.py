# SPDX-License-Identifier: Apache-2.0
"""The speed/error benchmark's pictures (scripts/benchmark_report.py): per scene, error against
time, log-log, for every curve (plain and adaptive, each engine), and the references side by
side. Needs no bpy (matplotlib, OpenImageIO)."""

import os

import numpy as np

from torrance_tools import REPO

# engine -> (colour, marker); an adaptive curve has its engine's colour, dashed; a denoised one
# (scripts/benchmark --denoised) dotted
ENGINE_STYLES = {"torrance": ("tab:red", "o"), "cycles": ("tab:blue", "s"),
                 "cycles_light_tree": ("tab:green", "^"), "cycles_guiding": ("tab:purple", "v"),
                 "cycles_guiding_light_tree": ("tab:orange", "D")}
ADAPTIVE_SUFFIX = "_adaptive"
DENOISED_SUFFIX = "_denoised"


def curve_style(curve):
    """(colour, marker, line style, label) of a curve name such as "cycles_adaptive"."""
    adaptive, denoised = curve.endswith(ADAPTIVE_SUFFIX), curve.endswith(DENOISED_SUFFIX)
    engine = curve.removesuffix(ADAPTIVE_SUFFIX).removesuffix(DENOISED_SUFFIX)
    color, marker = ENGINE_STYLES.get(engine, ("tab:gray", "x"))
    label = (engine.replace("_", " ").capitalize() + (" adaptive" if adaptive else "")
             + (" denoised" if denoised else ""))
    return color, marker, ("--" if adaptive else ":" if denoised else "-"), label


def point_label(row):
    """What to write beside a point: its samples, or its threshold on an adaptive curve."""
    return f"{row['threshold']:.3g}" if row.get("threshold") else str(row["spp"])


def plot_scene(name, data, path, curves):
    """Left: relMSE (corrected, faint: raw) against time; right: 1 - SSIM against time."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    for c in curves:
        rows = data.get(c) or []
        if not rows:
            continue
        color, marker, ls, label = curve_style(c)
        face = "white" if ls == "--" else color          # adaptive: hollow markers
        t = [r["seconds"] for r in rows]
        ax1.loglog(t, [max(r["rel_mse"], 1e-12) for r in rows], marker=marker, color=color,
                   ls=ls, alpha=0.3, lw=1, ms=3)
        corr = [(r["seconds"], r["rel_mse_corrected"], r) for r in rows
                if r["rel_mse_corrected"] > 0]
        if corr:
            ax1.loglog([p[0] for p in corr], [p[1] for p in corr], marker=marker, color=color,
                       mfc=face, ls=ls, lw=1.8, ms=5, label=label)
        for seconds, err, r in corr[::2]:
            ax1.annotate(point_label(r), (seconds, err), fontsize=6, xytext=(3, 3),
                         textcoords="offset points", color=color)
        ax2.loglog(t, [max(1.0 - r["ssim"], 1e-9) for r in rows], marker=marker, color=color,
                   mfc=face, ls=ls, lw=1.5, ms=4, label=label)
    ax1.axhline(data["reference"]["noise_rel_mse"], color="gray", ls=":", lw=1,
                label="reference noise")
    ax1.set_xlabel("wall time of bpy.ops.render.render (s), median over seeds")
    ax1.set_ylabel("mean relMSE over seeds (corrected; faint: raw)")
    ax1.set_title(f"{name}: error vs time")
    ax2.set_xlabel("wall time (s)")
    ax2.set_ylabel("1 - SSIM")
    ax2.set_title(f"{name}: 1 - SSIM vs time")
    for ax in (ax1, ax2):
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)


def plot_references(names, path, reference_dir="references"):
    """The stored references side by side (tone-mapped like the SSIM input)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from torrance_tools.compare import read_exr, tonemap
    fig, axes = plt.subplots(1, len(names), figsize=(2.2 * len(names), 2.0))
    for ax, name in zip(np.atleast_1d(axes), names, strict=True):
        img = read_exr(os.path.join(REPO, reference_dir, f"cmp_{name}.exr"))
        ax.imshow(np.clip(tonemap(img), 0, 1))
        ax.set_title(name, fontsize=9)
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
