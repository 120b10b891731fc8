# SPDX-License-Identifier: Apache-2.0
"""The sums of a volume's closures (volumes.py) in two forms with the same operations: Constants
(Python numbers: a homogeneous medium, summed in float64 at export as before) and Program (shader
program Values: a heterogeneous medium, summed per point by the core). VolumeReader walks the
closure tree once and calls the same methods on either."""

import math

from .shader_graph.math_ops import VECTOR_MATH_OPS
from .shader_graph.program import Value, constant

CUTOFF = 1e-5                      # Cycles' CLOSURE_WEIGHT_CUTOFF


class Varies(Exception):
    """A volume input varies through the volume (read it again as a program: _Program)."""


class Constants:
    """Closure inputs as Python floats and RGB lists, summed as Cycles sums volume closures:
    a homogeneous medium (set_material_volume)."""

    def __init__(self):
        self.sigma_a = [0.0, 0.0, 0.0]
        self.sigma_s = [0.0, 0.0, 0.0]
        self.emission = [0.0, 0.0, 0.0]
        self.lobes = []             # ((phase, g, a, b), mean scattering): volume_phase.py

    def value(self, read, kind):
        if not read.constant:
            raise Varies
        if kind == 'float':
            v = float(read.value[0])
            return v if math.isfinite(v) else 0.0
        return [float(c) if math.isfinite(c) else 0.0 for c in tuple(read.value)[:3]]

    @staticmethod
    def times(a, b):
        return a * b

    @staticmethod
    def positive(x):
        return max(x, 0.0)

    @staticmethod
    def plus(a, b):
        return a + b

    @staticmethod
    def clamp01(x):
        return min(max(x, 0.0), 1.0)

    @staticmethod
    def above_cutoff(x):
        return x > CUTOFF

    @staticmethod
    def mix_weights(weight, fac):
        return weight * (1.0 - fac), weight * fac

    @staticmethod
    def one_minus(rgb):
        return [1.0 - c for c in rgb]

    @staticmethod
    def one_minus_positive(rgb):
        return [max(1.0 - c, 0.0) for c in rgb]

    @staticmethod
    def sqrt_positive(rgb):
        return [math.sqrt(max(c, 0.0)) for c in rgb]

    @staticmethod
    def product(a, b):
        return [x * y for x, y in zip(a, b, strict=True)]

    def add(self, field, rgb, weight):
        """target += rgb x weight; an extinction's colour clamped at 0, an emission's signed (a
        negative one takes light away, as Cycles' volume Emission closure renders it)."""
        target = getattr(self, field)
        for i in range(3):
            c = float(rgb[i])
            target[i] += (c if field == 'emission' else max(c, 0.0)) * weight

    def scatter(self, rgb, phase, weight):
        self.add('sigma_s', rgb, weight)
        mean = sum(max(float(c), 0.0) for c in rgb) * weight / 3.0
        if mean > 0.0:
            self.lobes.append((phase, mean))

    def empty(self):
        return max(self.sigma_a + self.sigma_s + [abs(e) for e in self.emission]) <= 0.0


class Program:
    """Closure inputs as shader program Values (program.py), the sums computed per point: a
    heterogeneous medium (set_material_volume_program). Constant Values fold as they meet."""

    def __init__(self, builder):
        self.builder = builder
        self.sigma_a = self.sigma_s = self.emission = None
        self.lobes = []             # ((phase, g, a, b), None): unweighted
        self._zero = constant('color', (0.0, 0.0, 0.0))
        self._one = constant('color', (1.0, 1.0, 1.0))

    @staticmethod
    def value(read, kind):
        return read

    def _math(self, op, a, b, flags=0):
        return self.builder.math(op, a, b, flags)

    def _vector(self, op, a, b, scale=None):
        return self.builder.emit("VectorMath", 'color', [a, b, b, scale or constant('float', 0.0)],
                                 mode=VECTOR_MATH_OPS.index(op))

    def times(self, a, b):
        return self._math("MULTIPLY", *(x if isinstance(x, Value) else constant('float', x)
                                        for x in (a, b)))

    def positive(self, x):
        return self._math("MAXIMUM", x, constant('float', 0.0))

    def plus(self, a, b):
        return self._math("ADD", *(x if isinstance(x, Value) else constant('float', x)
                                   for x in (a, b)))

    def clamp01(self, x):
        return self._math("ADD", x, constant('float', 0.0), flags=1)

    @staticmethod
    def above_cutoff(_x):
        return True                 # Cycles' per-point cutoff (1e-5) left out

    def one_minus(self, rgb):
        return self._vector("SUBTRACT", self._one, rgb)

    def one_minus_positive(self, rgb):
        return self._vector("MAXIMUM", self.one_minus(rgb), self._zero)

    def sqrt_positive(self, rgb):
        root = [self._math("SQRT", self.positive(
            self.builder.emit("Channel", 'float', [rgb], mode=i)), constant('float', 0.0))
            for i in range(3)]
        return self.builder.emit("Combine", 'color', root)

    def product(self, a, b):
        return self._vector("MULTIPLY", a, b)

    def add(self, field, rgb, weight):
        if not isinstance(rgb, Value):            # a constant colour (the blackbody's)
            rgb = constant('color', tuple(rgb))
        if not isinstance(weight, Value):
            weight = constant('float', weight)
        if field != 'emission':                   # as Constants.add: emission signed
            rgb = self._vector("MAXIMUM", rgb, self._zero)
        term = self._vector("SCALE", rgb, self._zero, scale=weight)
        before = getattr(self, field)
        setattr(self, field, term if before is None else self._vector("ADD", before, term))

    def scatter(self, rgb, phase, weight):
        self.add('sigma_s', rgb, weight)
        self.lobes.append((phase, None))

    def mix_weights(self, weight, fac):
        return self.times(weight, self._math("SUBTRACT", constant('float', 1.0), fac)), \
            self.times(weight, fac)

    def registers(self):
        """sigma_a, sigma_s and emission: their registers (-1: zero), before build()."""
        out = {}
        for field in ('sigma_a', 'sigma_s', 'emission'):
            v = getattr(self, field)
            out[field] = -1 if v is None else (self.builder.constant_register(v) if v.constant
                                               else v)
        return out
