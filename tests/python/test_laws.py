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

from tapmc.laws import (AgeingLaw, InverseLogLaw, ProfileLaw, RealizationLawTest,  # noqa: E402
                        TwoExponentials, ZLaw, profile_gradient)

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


# --- RealizationLawTest: the test of a law across independent realizations -----------------

REALIZATION_TAPS = np.arange(0.0, 401.0)


def correlated_noise(rng, n, sd, phi=0.95):
    """n realizations of an AR(1) noise (correlation time ~20 taps): the taps of one run are
    correlated, as the spectra of Fig. 3 say, and realizations are independent."""
    out = np.empty((n, REALIZATION_TAPS.size))
    x = rng.normal(0.0, sd, n)
    for i in range(REALIZATION_TAPS.size):
        x = phi * x + np.sqrt(1.0 - phi ** 2) * rng.normal(0.0, sd, n)
        out[:, i] = x
    return out


@pytest.mark.parametrize("law,true,sd", [
    (InverseLogLaw(), (0.60, 0.08, 0.3, 5.0), 1e-3),
    (ZLaw(), (7.1, 7.6, 0.4, 3.0), 1e-2),
])
def test_realization_test_is_calibrated_when_the_law_holds(law, true, sd):
    # 120 sets of 9 realizations (F(4, 5) test): under the law the p-values are uniform, so
    # the rejections at 5 % are Binomial(120, 0.05) (mean 6, sd 2.4); 16 is 4 sd above (the
    # linearisation of B and tau makes the test slightly liberal: 6.3 % in 1000 sets).
    rng = np.random.default_rng(7)
    curve = law.function(REALIZATION_TAPS, *true)
    p = np.array([RealizationLawTest(law).compute(
        REALIZATION_TAPS, curve + correlated_noise(rng, 9, sd)).p_value for _ in range(120)])
    assert 1 <= np.sum(p < 0.05) <= 16, np.sum(p < 0.05)
    assert 0.3 <= np.median(p) <= 0.7, np.median(p)


def test_realization_test_rejects_a_wrong_law_and_fits_a_right_one():
    rng = np.random.default_rng(3)
    power_law = 0.52 + 0.01 * REALIZATION_TAPS ** 0.3
    wrong = RealizationLawTest(InverseLogLaw()).compute(
        REALIZATION_TAPS, power_law + correlated_noise(rng, 9, 1e-3))
    assert wrong.p_value < 0.01 and not wrong.compatible, wrong
    true = (0.60, 0.08, 0.3, 5.0)
    right = RealizationLawTest(InverseLogLaw()).compute(
        REALIZATION_TAPS, InverseLogLaw.function(REALIZATION_TAPS, *true)
        + correlated_noise(rng, 9, 1e-5))
    assert right.compatible and right.dof == 4 and right.realizations == 9
    assert right.bin_edges[0] == 1 and right.bin_edges[-1] == 401 and len(right.bin_edges) == 9
    for name, value in zip(InverseLogLaw.names, true):
        assert abs(right.params[name] - value) <= 5 * right.errors[name] + 1e-9, (name, right)
    np.testing.assert_allclose(right.bin_model, right.bin_means, atol=5 * right.bin_sem.max())


def test_realization_test_messages():
    law = InverseLogLaw()
    curves = np.ones((5, REALIZATION_TAPS.size))
    with pytest.raises(ValueError, match="5 realizations: a test of 4 parameters needs at "
                                         "least 6"):
        RealizationLawTest(law).compute(REALIZATION_TAPS, curves)
    with pytest.raises(ValueError, match="bins = 3: must be an integer >= 5"):
        RealizationLawTest(law, bins=3)
    with pytest.raises(ValueError, match=r"curves must have shape \(realizations, 401\)"):
        RealizationLawTest(law).compute(REALIZATION_TAPS, curves[:, :10])
    with pytest.raises(ValueError, match="singular covariance"):
        RealizationLawTest(law).compute(REALIZATION_TAPS, np.ones((9, REALIZATION_TAPS.size)))
    with pytest.raises(RuntimeError, match="compute"):
        RealizationLawTest(law).p_value
    with pytest.raises(TypeError, match="tapmc.laws.Law"):
        RealizationLawTest("eq. 3")
