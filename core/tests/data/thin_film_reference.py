# SPDX-License-Identifier: Apache-2.0
"""Prints the reference figures of core/tests/test_thin_film.cpp: a thin film's RGB reflectance
from the exact (infinite) Airy sum of complex amplitudes, integrated over wavelength (0.5 nm
steps) against the CIE 1931 functions (the core's 5 nm table, interpolated) in double precision:
independent of the core's truncated Belcour-Barla series and its Fourier table.

    python3 core/tests/data/thin_film_reference.py
"""
import re
from pathlib import Path

import numpy as np

src = (Path(__file__).resolve().parents[2] / "src" / "shader" / "shader_convert.cpp").read_text()
block = src[src.index('kCie1931[kCieSteps + 1][3] = {'):]
block = block[:block.index('};')]
rows = re.findall(r'\{([-\d.]+)f, ([-\d.]+)f, ([-\d.]+)f\}', block)
cie = np.array([[float(x) for x in t] for t in rows])
mblock = src[src.index('kXyzToRec709[3][3] = {'):]
mblock = mblock[:mblock.index('};')]
M = np.array([float(x) for x in re.findall(r'(-?\d+\.\d+)f', mblock)]).reshape(3, 3)
lam = np.arange(380.0, 780.0 + 1e-9, 0.5)
xyz = np.stack([np.interp(lam, np.arange(380, 781, 5), cie[:, c]) for c in range(3)], 1)
rgb_cmf = xyz @ M.T


def amplitudes(n1, n2, c1):
    """s and p amplitude reflection from index n1 into n2 (n + ik, k >= 0: fields exp(i(kz - wt)))
    at cos c1 (in n1); and the cosine in n2 (n2 cos2 with Im >= 0: decaying)."""
    s1 = np.sqrt(1 - c1 * c1 + 0j)
    n2c2 = np.sqrt(n2 * n2 - (n1 * s1) ** 2 + 0j)
    if np.imag(n2c2) < 0:
        n2c2 = -n2c2
    rs = (n1 * c1 - n2c2) / (n1 * c1 + n2c2)
    rp = (n2 * n2 * c1 - n1 * n2c2) / (n2 * n2 * c1 + n1 * n2c2)
    return rs, rp, n2c2 / n2


def film_reflectance(c1, film, d, sub):
    """Exact reflectance of ambient(1) | film(d nm) | substrate (complex index ok), per lambda."""
    r12s, r12p, c2 = amplitudes(1.0, film, c1)
    r23s, r23p, _ = amplitudes(film, sub, c2)
    delta = 4 * np.pi * film * d * c2 / lam  # round-trip phase
    e = np.exp(1j * delta)
    rs = (r12s + r23s * e) / (1 + r12s * r23s * e)
    rp = (r12p + r23p * e) / (1 + r12p * r23p * e)
    return 0.5 * (abs(rs) ** 2 + abs(rp) ** 2)


def rgb5(c1, film, d, sub):
    R = film_reflectance(c1, film, d, sub)
    return (R[:, None] * rgb_cmf).sum(0) / rgb_cmf.sum(0)


def rgb4(c1, film, d, sub):
    R = film_reflectance(c1, film, d, sub)
    XYZ = (R[:, None] * xyz).sum(0) / xyz[:, 1].sum()
    return np.clip(M @ (XYZ * np.array([0.95047, 1.0, 1.08883])), 0, 1)


cases = [
    ("5x dielectric 250 nm 1.33 / 1.5, cos 1", rgb5(1.0, 1.33, 250, 1.5)),
    ("5x dielectric 250 nm 1.33 / 1.5, cos 0.5", rgb5(0.5, 1.33, 250, 1.5)),
    ("5x dielectric 500 nm 1.33 / 1.5, cos 0.8", rgb5(0.8, 1.33, 500, 1.5)),
    ("5x dielectric 300 nm 2.0 / 1.5, cos 0.7", rgb5(0.7, 2.0, 300, 1.5)),
    ("5x dielectric 400 nm 0.8 / 1.5, cos 0.9", rgb5(0.9, 0.8, 400, 1.5)),
]
for name, v in cases:
    print(name, np.array2string(v, precision=5))
for c, (n, k) in enumerate([(0.18, 3.42), (0.42, 2.35), (1.37, 1.77)]):
    print("5x gold-like conductor channel", c, "300 nm film 1.5, cos 0.9:",
          round(float(rgb5(0.9, 1.5, 300, n + 1j * k)[c]), 5))
print("4x dielectric 250 nm 1.33 / 1.5, cos 1",
      np.array2string(rgb4(1.0, 1.33, 250, 1.5), precision=5))
print("4x dielectric 500 nm 1.33 / 1.5, cos 0.8",
      np.array2string(rgb4(0.8, 1.33, 500, 1.5), precision=5))
