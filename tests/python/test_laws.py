# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# The fits of tapmc.laws recover known parameters from synthetic data with Gaussian noise,
# within their reported 1-sigma errors, over many seeds (coverage of the 1- and 2-sigma
# intervals compatible with 68 % and 95 %), and report undetermined fits as undetermined.
import os
import sys
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", HERE.parent.parent))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc.laws import (AgeingLaw, InverseLogLaw, ProfileLaw, TwoExponentials,  # noqa: E402
                        ZLaw, profile_gradient)

SEEDS = 30
# Taps sampled as in a run written every tap at early times and sparsely later (log spacing).
TAPS = np.unique(np.round(np.concatenate([[0], np.geomspace(1, 4000, 200)])))


def coverage(law, x, true, noise, seeds=SEEDS, **fit_kw):
    """Fraction of seeds whose k-sigma interval holds the true value, per parameter."""
    inside1 = np.zeros(len(true))
    inside2 = np.zeros(len(true))
    for seed in range(seeds):
        rng = np.random.default_rng(1000 + seed)
        y = law.function(x, *true) + rng.normal(0.0, noise, x.size)
        res = law.fit(x, y, sigma=noise, **fit_kw)
        assert res.determined, (seed, res)
        p = np.array(list(res.params.values()))
        e = np.array(list(res.errors.values()))
        inside1 += np.abs(p - true) <= e
        inside2 += np.abs(p - true) <= 2 * e
    return inside1 / seeds, inside2 / seeds


def assert_calibrated(frac1, frac2):
    # 30 seeds: the 2-sigma count is Binomial(30, 0.954) (mean 28.6, sd 1.1), the 1-sigma count
    # Binomial(30, 0.683) (mean 20.5, sd 2.5); the bounds are > 3 sd away for calibrated errors.
    assert np.all(frac2 >= 0.8), frac2
    assert np.all(frac1 >= 0.4) and np.all(frac1 <= 0.95), frac1
    assert 0.55 <= frac1.mean() <= 0.82, frac1


@pytest.mark.parametrize("law,true,noise", [
    (InverseLogLaw(), np.array([0.64, 0.05, 0.4, 8.0]), 1e-3),
    (ZLaw(), np.array([7.0, 7.4, 0.4, 3.0]), 5e-3),
    (AgeingLaw(), np.array([0.02, 0.5, 10.0]), 3e-4),
])
def test_inverse_log_family_coverage(law, true, noise):
    frac1, frac2 = coverage(law, TAPS, true, noise)
    assert_calibrated(frac1, frac2)


def test_two_exponentials_coverage_and_ordering():
    t = np.arange(0.0, 2000.0, 5.0)
    true = np.array([7.0, 0.2, 20.0, 0.2, 500.0])
    frac1, frac2 = coverage(TwoExponentials(), t, true, 3e-3)
    assert_calibrated(frac1, frac2)
    # labels ordered tau1 <= tau2 whatever the start
    y = TwoExponentials.function(t, *true)
    res = TwoExponentials().fit(t, y, p0=[7.0, 0.2, 500.0, 0.2, 20.0])
    assert res.params["tau1"] == pytest.approx(20.0, rel=1e-6)
    assert res.params["tau2"] == pytest.approx(500.0, rel=1e-6)


def test_profile_law_coverage_and_gradient_window():
    zb = np.arange(0.25, 40.0, 0.5)
    true = np.array([0.62, 0.002, 1.5, 28.0])
    frac1, frac2 = coverage(ProfileLaw(boundary="fbc"), zb, true, 5e-3)
    assert_calibrated(frac1, frac2)
    # the straight-line gradient in the paper's windows is exact on a linear profile
    phi = 0.63 - 0.003 * zb
    for boundary, hi in (("fbc", 22.0), ("pbc", 26.0)):
        g = profile_gradient(zb, phi, boundary=boundary)
        assert g.params["alpha"] == pytest.approx(0.003, rel=1e-9)
        assert g.x.min() >= 5.0 and g.x.max() <= hi and g.x.max() > hi - 0.5
    assert ProfileLaw(boundary="pbc").window == (5.0, 26.0)


def test_a_default_window_reaching_the_surface_warns():
    """A bed 24 R high (eq. 7 with zb_star = 24): the 'pbc' window (5..26 R) reaches the surface
    decay and its line fitted the decay as a gradient (alpha 3x too large), without a word. It
    warns; a bed above the window, or a window given, does not."""
    import warnings as _warnings
    zb = np.arange(0.25, 40.0, 0.5)
    low = ProfileLaw.function(zb, 0.62, 0.0017, 1.5, 24.0)
    with pytest.warns(UserWarning, match=r"default window \(5, 26\) of boundary 'pbc' reaches"):
        steep = profile_gradient(zb, low, boundary="pbc")
    assert steep.params["alpha"] > 2 * 0.0017
    with _warnings.catch_warnings():
        _warnings.simplefilter("error")
        tall = ProfileLaw.function(zb, 0.62, 0.0017, 1.5, 40.0)
        assert profile_gradient(zb, tall, boundary="pbc").params["alpha"] == \
            pytest.approx(0.0017, rel=1e-3)
        assert profile_gradient(zb, low, window=(5.0, 18.0)).params["alpha"] == \
            pytest.approx(0.0017, rel=1e-3)


def test_exact_data_give_exact_parameters():
    true = [0.61, 0.03, 0.7, 12.0]
    res = InverseLogLaw().fit(TAPS, InverseLogLaw.function(TAPS, *true))
    np.testing.assert_allclose(list(res.params.values()), true, rtol=1e-6)
    assert res.rms < 1e-10


def test_early_linear_regime_is_not_determined():
    # tau far beyond the data: X grows linearly, only the initial slope is fixed
    t = np.arange(0.0, 100.0)
    rng = np.random.default_rng(7)
    y = InverseLogLaw.function(t, 0.64, 0.06, 0.3, 1e4) + rng.normal(0, 1e-3, t.size)
    res = InverseLogLaw().fit(t, y, sigma=1e-3)
    assert not res.determined
    assert "exceeds 100%" in res.note or "correlations" in res.note
    # the fitted curve still describes the data
    assert res.reduced_chi2 < 1.5


def test_small_eps_triplet_not_unique():
    # section III.B: at small eps (X_inf, B, tau) is no longer unique
    rng = np.random.default_rng(3)
    y = InverseLogLaw.function(TAPS, 0.62, 0.02, 0.05, 50.0) + rng.normal(0, 2e-3, TAPS.size)
    res = InverseLogLaw().fit(TAPS, y, sigma=2e-3)
    assert not res.determined and res.note
    assert "determined" in repr(res)


def test_validation_messages():
    with pytest.raises(ValueError, match="x needs at least"):
        InverseLogLaw().fit([0, 1], [1, 2])
    with pytest.raises(ValueError, match="same length"):
        InverseLogLaw().fit(np.arange(10), np.arange(9))
    with pytest.raises(ValueError, match="taps must be >= 0"):
        ZLaw().fit(np.arange(-1.0, 9.0), np.ones(10))
    with pytest.raises(ValueError, match="sigma"):
        AgeingLaw().fit(np.arange(10.0), np.arange(10.0), sigma=0.0)
    with pytest.raises(ValueError, match=r"sigma has shape \(9,\); give one value or one per "
                       r"point \(10\)"):
        AgeingLaw().fit(np.arange(10.0), np.arange(10.0), sigma=np.ones(9))
    with pytest.raises(ValueError, match=r"p0 has shape \(2,\); give one start per parameter "
                       r"\(X_inf, dX_inf, B, tau\)"):
        InverseLogLaw().fit(TAPS, np.linspace(0.58, 0.6, TAPS.size), p0=[0.6, 0.02])
    # one sigma for all points, as a scalar or a one-element list, gives the same fit
    y = InverseLogLaw.function(TAPS, 0.62, 0.02, 0.5, 50.0)
    assert InverseLogLaw().fit(TAPS, y, sigma=[2e-3]).params == \
        InverseLogLaw().fit(TAPS, y, sigma=2e-3).params
    with pytest.raises(ValueError, match="boundary"):
        ProfileLaw(boundary="xyz")
    with pytest.raises(ValueError, match="window"):
        ProfileLaw(window=(10, 5))


def test_plot_draws_data_and_fit():
    import matplotlib
    matplotlib.use("Agg")
    res = AgeingLaw().fit(TAPS, AgeingLaw.function(TAPS, 0.02, 0.5, 10.0))
    ax = res.plot(logx=True)
    assert len(ax.lines) >= 2


def test_fit_plot_labels_its_axes_and_has_a_legend():
    """FitResult.plot names x and y after the law (or as asked) and draws a legend."""
    import matplotlib
    matplotlib.use("Agg")
    t = np.arange(1.0, 300.0)
    y = 0.6 - 0.02 / (1 + 0.3 * np.log(1 + t / 5)) + np.random.default_rng(3).normal(0, 1e-4, t.size)
    ax = InverseLogLaw().fit(t, y).plot(logx=True)
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("tap t", "X (Phi_b or <Phi^c>)")
    assert {x.get_text() for x in ax.get_legend().get_texts()} >= {"data", "InverseLogLaw"}
    ax = InverseLogLaw().fit(t, y).plot(ylabel="<Phi^c>")
    assert ax.get_ylabel() == "<Phi^c>"


@pytest.mark.parametrize("law, params", [
    (InverseLogLaw, (0.62, 0.05, 0.8, 20.0)), (InverseLogLaw, (0.58, -0.01, 30.0, 0.5)),
    (ZLaw, (7.0, 7.4, 0.9, 15.0)), (ZLaw, (6.1, 5.2, 0.02, 800.0)),
    (AgeingLaw, (0.01, 2.0, 30.0)), (AgeingLaw, (3e-4, 0.05, 2.0))])
def test_exact_jacobians_are_the_derivatives_of_the_laws(law, params):
    # the fits use them in place of differences: each column against a central difference
    t = np.concatenate([[0.0], np.geomspace(0.3, 5000.0, 80)])
    jac = law.jacobian(t, *params)
    assert jac.shape == (t.size, len(law.names))
    for k, p in enumerate(params):
        h = 1e-6 * abs(p)
        up, down = list(params), list(params)
        up[k], down[k] = p + h, p - h
        numeric = (law.function(t, *up) - law.function(t, *down)) / (2 * h)
        scale = np.max(np.abs(numeric)) + 1e-300
        assert np.max(np.abs(jac[:, k] - numeric)) < 1e-6 * scale, (law.__name__, law.names[k])
    # a wrong column would be caught: the derivative in B is not the one in tau
    assert not np.allclose(jac[:, -2], jac[:, -1])


@pytest.mark.parametrize("lo, hi", [(10.0, 20.0), (-5.0, 5.0)])
def test_correlation_of_a_straight_line_is_the_least_squares_one(lo, hi):
    # y = Phi0 - alpha x by least squares: corr(Phi0, alpha) = mean(x) / sqrt(mean(x^2)),
    # 0.985 on [10, 20] (intercept and slope nearly one combination), 0 on a centred window.
    x = np.linspace(lo, hi, 30)
    y = 0.6 - 0.002 * x + np.random.default_rng(3).normal(0.0, 1e-3, x.size)
    res = profile_gradient(x, y, window=(lo, hi))
    corr = res.correlation
    expected = x.mean() / np.sqrt(np.mean(x ** 2))
    assert corr.shape == (2, 2)
    np.testing.assert_allclose(np.diag(corr), 1.0, rtol=1e-12)
    assert corr[0, 1] == pytest.approx(corr[1, 0], rel=1e-12)
    assert corr[0, 1] == pytest.approx(expected, abs=1e-6)


def test_errors_of_a_weighted_fit_grow_with_a_scatter_beyond_the_error_bars():
    """True scatter twice the stated errors (10 points, dof 8): FitResult.errors are scaled by
    sqrt(chi2/dof) when it exceeds 1, as the profile intervals and stats.weighted_line_fit are,
    so that the intercept's 2-sigma interval holds the truth in about 95 % of the replicas (the
    unscaled curvature errors, half the true spread: about 69 %) and one fit tells one error
    size; a scatter within the errors leaves them as stated (never narrowed)."""
    from tapmc.fluctuations import sigma_scaling
    from tapmc.laws import StraightLine
    from tapmc.stats import weighted_line_fit

    rng = np.random.default_rng(7)
    x = np.sqrt(np.linspace(0.0025, 0.15, 10))
    err = 0.001 * (1 + rng.random(10))
    intercept, slope, underestimate = 0.005, 0.02, 2.0
    inside_line, inside_k, replicas = 0, 0, 200
    for _ in range(replicas):
        y = intercept + slope * x + underestimate * err * rng.standard_normal(10)
        fit = StraightLine().fit(x, y, err)
        a, a_err, _, _, _ = weighted_line_fit(x, y, err)
        assert fit.params["Phi0"] == pytest.approx(a, rel=1e-6)
        assert fit.errors["Phi0"] == pytest.approx(a_err, rel=1e-4)
        inside_line += abs(fit.params["Phi0"] - intercept) < 2 * fit.errors["Phi0"]
        proportional = sigma_scaling(x, slope * x + underestimate * err * rng.standard_normal(10),
                                     err)
        inside_k += abs(proportional.params["k"] - slope) < 2 * proportional.errors["k"]
    # Binomial(200, 0.95): sd 0.015; the unscaled errors cover about 0.69
    assert inside_line / replicas > 0.88 and inside_k / replicas > 0.88, (inside_line, inside_k)
    # the profile interval of a straight line is its (scaled) curvature error
    interval = fit.intervals["Phi0"]
    assert 0.5 * (interval.hi - interval.lo) == pytest.approx(fit.errors["Phi0"], rel=1e-2)
    # a scatter below the errors: the stated errors, not narrowed
    exact = StraightLine().fit(x, intercept + slope * x, err)
    _, stated, _, _, _ = weighted_line_fit(x, intercept + slope * x, err)
    assert exact.errors["Phi0"] == pytest.approx(stated, rel=1e-4)
