# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""tapmc.stats, the bottom of the package's statistics: t quantiles against tabulated
values, beyond() on both sides of its band, Welch's dof, the weighted line on exact data."""

import math
import os
import sys
from pathlib import Path

import numpy as np
import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc import stats  # noqa: E402


def test_t_quantiles_are_the_tabulated_ones():
    # two-sided 95 %: 12.706 (1 dof), 4.303 (2), 2.262 (9), 1.960 (normal limit)
    assert stats.t_quantile(1) == pytest.approx(12.7062, abs=1e-4)
    assert stats.t_quantile(2) == pytest.approx(4.3027, abs=1e-4)
    assert stats.t_quantile(9) == pytest.approx(2.2622, abs=1e-4)
    assert stats.t_quantile(10 ** 6) == pytest.approx(1.95996, abs=1e-4)
    assert stats.t_quantile_of_mean(10) == stats.t_quantile(9)
    assert math.isnan(stats.t_quantile_of_mean(1))
    # Bonferroni over one test is the plain quantile; over more it widens
    assert stats.bonferroni_t_quantile(5, 1) == pytest.approx(stats.t_quantile(5))
    assert stats.bonferroni_t_quantile(5, 4) > stats.t_quantile(5)


def test_beyond_decides_on_both_sides_of_the_band():
    t = stats.t_quantile(4)
    assert stats.beyond(1.0, 1.0 / t * 0.99, 4)          # just outside the band
    assert not stats.beyond(1.0, 1.0 / t * 1.01, 4)      # just inside
    assert stats.beyond(-1.0, 0.1, 4)                    # both signs
    assert stats.beyond(3.0, 0.1, 4, reference=2.0)
    assert not stats.beyond(2.05, 0.1, 4, reference=2.0)
    # an error that cannot decide never says "beyond"
    for err, dof in ((0.1, None), (0.1, 0), (math.nan, 4), (None, 4)):
        assert not stats.beyond(10.0, err, dof)


def test_welch_dof_of_equal_parts_adds_them():
    assert stats.welch_dof([1.0, 1.0], [4, 4]) == 8
    assert stats.welch_dof([1.0, 0.0], [4, 9]) == 4      # one part carries all the variance
    assert stats.welch_dof([0.0, 0.0], [3, 7]) == 3


def test_weighted_line_recovers_an_exact_line_and_needs_three_points():
    x = np.arange(6.0)
    slope, err, dof = stats.weighted_line(x, 2.0 + 0.5 * x, np.full(6, 0.1))
    assert slope == pytest.approx(0.5, abs=1e-12) and dof == 4
    # exact data: the error is the error bars' (chi2 = 0, no scaling)
    assert err == pytest.approx(0.1 / math.sqrt(np.sum((x - x.mean()) ** 2)), rel=1e-9)
    assert math.isnan(stats.weighted_line([0, 1], [0, 1], [1, 1])[0])
    # one x only (seeds of one eps): no slope, NaNs (a singular-matrix error before)
    assert math.isnan(stats.weighted_line_fit([0.1, 0.1, 0.1], [1, 2, 3], [1, 1, 1])[2])
    # scatter beyond the bars widens the error by sqrt(chi2 / dof)
    y = 2.0 + 0.5 * x + np.array([1, -1, 1, -1, 1, -1]) * 0.3
    assert stats.weighted_line(x, y, np.full(6, 0.1))[1] > err


def test_weighted_line_fit_gives_the_offset_with_its_error():
    """The offset of an exact line and its error from the bars: sigma^2 sum(x^2) / (n Sxx)."""
    x = np.arange(6.0)
    offset, offset_err, slope, _, dof = stats.weighted_line_fit(x, 2.0 + 0.5 * x,
                                                                np.full(6, 0.1))
    sxx = np.sum((x - x.mean()) ** 2)
    assert (offset, slope, dof) == (pytest.approx(2.0), pytest.approx(0.5), 4)
    assert offset_err == pytest.approx(0.1 * math.sqrt(np.sum(x ** 2) / (6 * sxx)), rel=1e-9)
    assert stats.weighted_line_fit(x, 2.0 + 0.5 * x, np.full(6, 0.1))[2:] == \
        stats.weighted_line(x, 2.0 + 0.5 * x, np.full(6, 0.1))
    assert math.isnan(stats.weighted_line_fit([0, 1], [0, 1], [1, 1])[0])


def test_mean_dof():
    assert stats.mean_dof(5) == 4
    assert stats.mean_dof([5, 3, 7]) == 2
    assert stats.mean_dof(1) is None and stats.mean_dof([]) is None
