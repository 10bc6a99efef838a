# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""tapmc.laws.RealizationFits: do a few independent realizations fix the parameters of eq. 3
(section III.B's triplet), and do they depend on the range of taps fitted? And the
chi-square interval of a spread it decides with (spread_interval, spread_verdict)."""

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools" / "python"))

from tapmc.laws import (InverseLogLaw, RealizationFits, StraightLine, ZLaw,  # noqa: E402
                        spread_interval, spread_verdict)

T = np.arange(1, 801, dtype=float)
LAW = InverseLogLaw()
TRUTH = dict(X_inf=0.60, dX_inf=0.04, B=0.3, tau=5.0)


def realizations(n, rms, seed, curve=None):
    clean = LAW.function(T, *TRUTH.values()) if curve is None else curve
    rng = np.random.default_rng(seed)
    return clean + rms * rng.standard_normal((n, T.size))


@pytest.mark.parametrize("n", [2, 3, 6])
def test_the_spread_verdict_errs_at_most_at_its_level(n):
    """Brute force over 4000 sets of n normal values: a spread just inside the limit is
    called undetermined (False), and one just outside determined (True), in at most 2.5 % of
    the sets (the interval's one-sided tail), and the interval holds the true sd in 95 %."""
    rng = np.random.default_rng(n)
    limit, sets = 1.0, 4000
    for sigma, wrong in ((0.9, False), (1.1, True)):
        verdicts, covered = [], 0
        for _ in range(sets):
            sd, low, high = spread_interval(rng.normal(3.0, sigma, n))
            verdicts.append(spread_verdict(low, high, limit))
            covered += low <= sigma <= high
        assert verdicts.count(wrong) <= 0.025 * sets + 3 * np.sqrt(0.025 * sets), (sigma, n)
        assert abs(covered / sets - 0.95) < 0.015, covered / sets
    # the three answers, and the interval about the sample sd
    assert spread_verdict(0.5, 0.9, 1.0) is True
    assert spread_verdict(1.1, 5.0, 1.0) is False
    assert spread_verdict(0.5, 5.0, 1.0) is None
    sd, low, high = spread_interval([1.0, 2.0, 3.0])
    assert sd == pytest.approx(1.0) and low < sd < high


def test_many_realizations_of_a_well_fixed_law_make_it_unique_two_cannot_tell():
    eight = RealizationFits(LAW).compute(T, realizations(8, 2e-4, 1))
    assert eight.unique is True, eight
    assert eight.realizations == 8 and len(eight.fitted_ranges) == 3
    assert eight.log_scale == {"X_inf": False, "dX_inf": False, "B": True, "tau": True}
    for k, v in TRUTH.items():
        assert eight.mean[k] == pytest.approx(v, rel=0.05), k
        assert eight.spread_low[k] <= eight.spread[k] <= eight.spread_high[k]
        assert len(eight.values[k]) == 8
    assert eight.limit["B"] == pytest.approx(np.log(2.0))
    assert eight.limit["X_inf"] == pytest.approx(0.60, rel=0.01)   # within its value
    # the same law from two realizations: a spread of one dof bounds nothing
    two = RealizationFits(LAW).compute(T, realizations(2, 2e-4, 1))
    assert None in two.determined.values() and two.unique is None, two


def test_a_pure_logarithm_leaves_b_undetermined():
    # the B -> 0 limit of eq. 3: X_inf and B trade along a valley, so every realization
    # lands elsewhere on it
    y = 0.55 + 0.004 * np.log1p(T / 2.0)
    fits = RealizationFits(LAW).compute(T, realizations(6, 2e-4, 2, curve=y))
    assert fits.determined["B"] is False, fits
    assert fits.unique is False


def test_a_law_that_changes_with_the_taps_depends_on_the_range():
    # eq. 3 for the first half, then the compaction takes off again: every realization's
    # early ranges disagree with its all-taps fit the same way
    y = LAW.function(T, *TRUTH.values()) + np.where(T > 400, 0.01 * (T - 400) / 400, 0.0)
    fits = RealizationFits(LAW).compute(T, realizations(6, 2e-4, 3, curve=y))
    assert fits.range_dependent, fits
    assert fits.unique is False
    assert all(fits.range_bound[k] >= fits.range_shift[k] for k in LAW.names)


def test_eq4_tap_zero_left_out_and_results_before_compute():
    z = ZLaw().function(T, 6.9, 7.4, 0.5, 5.0)
    curves = z + 2e-3 * np.random.default_rng(4).standard_normal((5, T.size))
    fits = RealizationFits(ZLaw())
    with pytest.raises(RuntimeError, match="compute"):
        fits.mean
    assert "not computed" in repr(fits)
    fits.compute(np.concatenate([[0.0], T]), np.hstack([np.full((5, 1), 7.4), curves]))
    assert fits.mean["Z_0"] == pytest.approx(7.4, rel=0.01)
    assert fits.determined["Z_0"] is True
    assert "RealizationFits of ZLaw over 5 realizations" in repr(fits)


def test_bad_input_is_refused_with_the_argument_named():
    curves = realizations(3, 2e-4, 5)
    with pytest.raises(TypeError, match="StraightLine"):
        RealizationFits(StraightLine())
    with pytest.raises(ValueError, match="level = 1"):
        RealizationFits(LAW, level=1.0)
    with pytest.raises(ValueError, match="p_min = 0.7"):
        RealizationFits(LAW, p_min=0.7)
    with pytest.raises(ValueError, match="t_min = 0"):
        RealizationFits(LAW, t_min=0)
    with pytest.raises(ValueError, match=r"shape \(realizations, 800\)"):
        RealizationFits(LAW).compute(T, curves[:, :-1])
    with pytest.raises(ValueError, match="1 realization"):
        RealizationFits(LAW).compute(T, curves[:1])
    with pytest.raises(ValueError, match="finite"):
        RealizationFits(LAW).compute(T, np.where(T > 5, curves, np.nan))
    with pytest.raises(ValueError, match="needs at least 6"):
        RealizationFits(LAW).compute(T[:4], curves[:, :4])
    with pytest.raises(ValueError, match="1 value"):
        spread_interval([1.0])
    with pytest.raises(ValueError, match="level = 0"):
        spread_interval([1.0, 2.0], level=0.0)
