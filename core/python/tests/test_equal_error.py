"""Equal-error time ratios (torrance_tools.equal_error): read where two error-vs-time curves
overlap, and a bound where one engine's worst error is already below the other's best."""
import math

from torrance_tools.equal_error import equal_error, fmt_equal, meets


def rows(points):
    """Benchmark rows from (spp, seconds, relMSE) triples."""
    return [dict(spp=spp, seconds=t, rel_mse_corrected=e) for spp, t, e in points]


def test_overlapping_curves_give_the_ratio_at_equal_error():
    cycles = rows([(16, 1.0, 1e-1), (128, 8.0, 1.25e-2)])
    torrance = rows([(16, 0.5, 1e-1), (128, 4.0, 1.25e-2)])
    eq = equal_error(torrance, cycles)
    assert abs(eq["geomean"] - 0.5) < 1e-9 and eq["bound"] == ""
    assert fmt_equal(eq) == "0.50" and meets(eq, 0.5)


def test_a_curve_below_the_others_best_gives_a_bound():
    cycles = rows([(16, 1.0, 1e-1), (128, 8.0, 1e-2), (1024, 64.0, 1e-3)])
    # Torrance's first point (0.2 s) already beats Cycles' last (64 s): at Cycles' best error
    # Torrance needs at most 0.2 s.
    torrance = rows([(4, 0.2, 5e-4), (8, 0.4, 2.5e-4)])
    eq = equal_error(torrance, cycles)
    assert eq["bound"] == "≤" and math.isclose(eq["geomean"], 0.2 / 64.0)
    assert fmt_equal(eq) == "≤0.00" and meets(eq, 0.5) is True
    # Cycles' 16 and 128 spp errors: Torrance was below them from 0.2 s on.
    assert math.isclose(eq["at"][16], 0.2 / 1.0) and eq["at_bound"][16] == "≤"
    assert fmt_equal(eq, 128) == "≤0.03"
    # The other way round: a lower bound, which says nothing about a goal it is below.
    flipped = equal_error(cycles, torrance)
    assert flipped["bound"] == "≥" and math.isclose(flipped["geomean"], 64.0 / 0.2)
    assert meets(flipped, 0.5) is False
    assert meets(equal_error(rows([(4, 0.01, 1e-1)]), rows([(4, 1.0, 1e-3)])), 0.5) is None
