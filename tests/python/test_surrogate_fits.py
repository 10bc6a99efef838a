# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""tapmc.laws.SurrogateFits: how well one run fixes the parameters of eq. 3, and whether they
depend on the range of taps fitted (section III.B), with Fourier surrogates of the run's
residuals. Its calibration against independent realizations is test_slow_surrogate_fits.py."""

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools" / "python"))

from tapmc.laws import InverseLogLaw, StraightLine, SurrogateFits, ZLaw  # noqa: E402

T = np.arange(1, 1001, dtype=float)
LAW = InverseLogLaw()
TRUTH = dict(X_inf=0.60, dX_inf=0.04, B=0.3, tau=5.0)


def curve(**change):
    return LAW.function(T, *{**TRUTH, **change}.values())


def test_fourier_surrogate_keeps_the_periodogram_and_the_mean():
    rng = np.random.default_rng(1)
    for n in (999, 1000):
        x = np.cumsum(rng.standard_normal(n)) * 1e-3 + 0.6
        s = SurrogateFits.fourier_surrogate(x, rng)
        assert s.mean() == pytest.approx(x.mean(), abs=1e-12)
        assert np.allclose(np.abs(np.fft.rfft(s - s.mean())),
                           np.abs(np.fft.rfft(x - x.mean())), rtol=1e-9, atol=1e-12)
        assert not np.allclose(s, x)


def test_a_well_fixed_law_is_unique():
    y = curve() + 2e-4 * np.random.default_rng(2).standard_normal(T.size)
    fits = SurrogateFits(LAW, surrogates=40, seed=3).compute(T, y)
    assert fits.unique, fits
    assert fits.used == 40 and fits.log_scale == {"X_inf": False, "dX_inf": False,
                                                  "B": True, "tau": True}
    for k, v in TRUTH.items():
        assert fits.low[k] < fits.params[k] < fits.high[k]
        # white noise: the 16-84 % band, widened three times about the fit, holds the truth
        half = (fits.high[k] - fits.low[k]) / 2
        assert abs(fits.params[k] - v) < 3 * half + 1e-12, (k, fits.params[k], v)
    assert len(fits.fitted_ranges) == 3  # [1, T] itself is the reference, not a range
    assert all(0 < p <= 1 for p in fits.range_p.values())


def test_a_pure_logarithm_leaves_the_triplet_undetermined():
    # the B -> 0 limit of eq. 3: X_inf and B trade against each other along a valley
    y = 0.55 + 0.004 * np.log1p(T / 2.0)
    y = y + 2e-4 * np.random.default_rng(4).standard_normal(T.size)
    fits = SurrogateFits(LAW, surrogates=40, seed=5).compute(T, y)
    assert not fits.determined["B"], fits
    assert not fits.unique


def test_a_law_that_changes_with_the_taps_is_not_unique():
    # the first half follows eq. 3, then the compaction takes off again: the misfit enters
    # the residuals, so the surrogates carry it as slow noise and widen every band (the
    # class's docstring): the triplet is not unique, whether as undetermined or as range
    # dependent
    y = curve() + np.where(T > 500, 0.01 * (T - 500) / 500, 0.0)
    y = y + 2e-4 * np.random.default_rng(6).standard_normal(T.size)
    fits = SurrogateFits(LAW, surrogates=40, seed=7).compute(T, y)
    assert not fits.unique, fits


def test_eq4_and_results_before_compute():
    z = ZLaw().function(T, 6.9, 7.4, 0.5, 5.0)
    z = z + 2e-3 * np.random.default_rng(8).standard_normal(T.size)
    fits = SurrogateFits(ZLaw(), surrogates=20, seed=9)
    with pytest.raises(RuntimeError, match="compute"):
        fits.params
    assert "not computed" in repr(fits)
    fits.compute(np.concatenate([[0.0], T]), np.concatenate([[7.4], z]))  # tap 0 left out
    assert fits.params["Z_0"] == pytest.approx(7.4, rel=0.01)
    assert fits.determined["Z_0"] and fits.determined["Z_inf"]
    assert "SurrogateFits of ZLaw over 20 surrogates" in repr(fits)


def test_bad_input_is_refused_with_the_argument_named():
    y = curve()
    with pytest.raises(TypeError, match="StraightLine"):
        SurrogateFits(StraightLine())
    with pytest.raises(ValueError, match="surrogates = 10"):
        SurrogateFits(LAW, surrogates=10)
    with pytest.raises(ValueError, match="p_min = 0.7"):
        SurrogateFits(LAW, p_min=0.7)
    with pytest.raises(ValueError, match="t_min = 0"):
        SurrogateFits(LAW, t_min=0)
    with pytest.raises(ValueError, match="consecutive taps"):
        SurrogateFits(LAW, surrogates=20).compute(T[::2], y[::2])
    with pytest.raises(ValueError, match="needs at least 18"):
        SurrogateFits(LAW, surrogates=20).compute(T[:10], y[:10])
    with pytest.raises(ValueError, match="needs at least 18"):
        SurrogateFits(LAW, surrogates=20, t_min=995).compute(T, y)
