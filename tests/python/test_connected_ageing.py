# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# tapmc.connected_ageing on synthetic realizations with a known answer: a process whose
# increments have variance ln(s / (s - 1)) ages simply (C = ln(1 + t / t_w) exactly: mu = 1,
# kappa = 0); stationary increments do not age (C = t: mu = 0), the control that must fail the
# simple-ageing collapse; a drift shared by all realizations leaves C unchanged bit for bit
# while it dominates the paper's A of eq. 5.
import numpy as np
import pytest

from tapmc import Ageing
from tapmc.ageing import collapse_dispersion
from tapmc.connected_ageing import ConnectedAgeing, LawFreeCollapse, connected_curves

WAITING = [10, 30, 100, 300]
TAPS = 1000
REALIZATIONS = 120


def walks(step_variance, seed=1, drift=None):
    rng = np.random.default_rng(seed)
    s = np.arange(1, TAPS + 1)
    steps = rng.normal(size=(REALIZATIONS, TAPS)) * np.sqrt(step_variance(s))
    z = np.concatenate([np.zeros((REALIZATIONS, 1)), np.cumsum(steps, axis=1)], axis=1)
    if drift is not None:
        z = z + drift(np.arange(TAPS + 1))
    return z


def simple_ageing(seed=1, drift=None):
    """Step s has variance ln(s / (s - 1)) (the first step 1), so that from t_w >= 1 the
    displacement over t taps has variance ln((t_w + t) / t_w) exactly."""
    def variance(s):
        v = np.ones(len(s))
        v[1:] = np.log(s[1:] / (s[1:] - 1.0))
        return v
    return walks(variance, seed, drift)


def stationary(seed=1):
    return walks(lambda s: np.ones_like(s, dtype=float), seed)


def test_connected_function_is_the_variance_and_its_jackknife_error():
    z = stationary()
    ca = ConnectedAgeing(z, WAITING).compute()
    d = z[:, 300 + 5] - z[:, 300]
    assert ca.C[300][4] == pytest.approx(d.var(ddof=1), rel=1e-12)
    loo = [np.delete(d, i).var(ddof=1) for i in range(len(d))]
    jack = np.sqrt((len(d) - 1) / len(d) * np.sum((loo - np.mean(loo)) ** 2))
    assert ca.C_error[300][4] == pytest.approx(jack, rel=1e-9)
    # the expectation of C for unit steps is t: within a few errors at every delay checked
    for k in (0, 9, 99, 599):
        assert abs(ca.C[300][k] - (k + 1)) < 4 * ca.C_error[300][k]


def test_a_drift_shared_by_all_realizations_leaves_C_unchanged_and_dominates_A():
    drift = lambda t: -2.0 * np.log1p(t)  # noqa: E731 (the mean compaction)
    plain, drifting = simple_ageing(), simple_ageing(drift=drift)
    a = ConnectedAgeing(plain, WAITING).compute()
    b = ConnectedAgeing(drifting, WAITING).compute()
    for tw in WAITING:
        np.testing.assert_allclose(b.C[tw], a.C[tw], rtol=1e-9, atol=1e-12)
        np.testing.assert_allclose(b.drift[tw], a.drift[tw] + (drift(tw + b.t) - drift(tw)),
                                   atol=1e-12)
    # the paper's A is dominated by the drift at t_w = 10 (share of the squared mean)
    assert Ageing(drifting, WAITING).compute().drift_share(10) > 0.5


def test_simple_ageing_collapses_at_mu_one_and_not_at_zero():
    collapse = ConnectedAgeing(simple_ageing(), WAITING).compute().collapse()
    assert collapse.consistent_with(1.0), collapse
    assert not collapse.consistent_with(0.0), collapse
    assert abs(collapse.kappa) < max(0.1, 3 * collapse.kappa_error), collapse
    assert collapse.dispersion < collapse.dispersion_unscaled
    assert collapse.dispersion_simple < collapse.dispersion_unscaled


def test_control_without_ageing_collapses_at_mu_zero_and_fails_simple_ageing():
    collapse = ConnectedAgeing(stationary(), WAITING).compute().collapse(fit_amplitude=False)
    assert collapse.kappa == 0.0
    assert collapse.consistent_with(0.0), collapse
    assert not collapse.consistent_with(1.0), collapse
    assert collapse.dispersion_simple > 10 * collapse.dispersion_unscaled


def test_bad_input_is_refused_by_name():
    with pytest.raises(ValueError, match="z_series"):
        ConnectedAgeing(np.zeros((2, 50)), [1])
    with pytest.raises(ValueError, match="waiting_times"):
        ConnectedAgeing(np.zeros((5, 50)), [-1])
    with pytest.raises(ValueError, match="fewer than 3 delays"):
        ConnectedAgeing(np.zeros((5, 50)), [48])
    with pytest.raises(ValueError, match="groups"):
        LawFreeCollapse(groups=1)
    with pytest.raises(ValueError, match="at least 2 waiting times"):
        ConnectedAgeing(stationary(), [10]).compute().collapse()
    with pytest.raises(ValueError, match=r"at least 2 waiting times > 0, got \[0, 10\]"):
        ConnectedAgeing(stationary(), [0, 10]).compute().collapse()


def test_the_curve_of_t_w_0_is_measured_but_left_out_of_the_collapse():
    """t_w = 0 has no scale: C(t, 0) is computed, the collapse of [0, 10, 30] is the one of
    [10, 30] exactly (was a ZeroDivisionError)."""
    z = simple_ageing(seed=2)
    with_zero = ConnectedAgeing(z, [0, 10, 30]).compute()
    assert 0 in with_zero.C
    a = with_zero.collapse(fit_amplitude=False, groups=2)
    b = ConnectedAgeing(z, [10, 30]).compute().collapse(fit_amplitude=False, groups=2)
    assert (a.mu, a.mu_error, a.dispersion) == (b.mu, b.mu_error, b.dispersion)


def test_collapse_dispersion_refuses_what_it_cannot_compare():
    t = np.arange(1.0, 6.0)
    good = (t, t, np.ones(5))
    assert collapse_dispersion({1: good, 2: good}, 0.0) == 0.0
    for curves, message in (({1: good}, "at least 2"),
                            ({0: good, 2: good}, "must be > 0"),
                            ({1: good, 2: (t, t[:4], np.ones(5))}, "one length"),
                            ({1: good, 2: (t, t, np.zeros(5))}, "sigma must be > 0")):
        with pytest.raises(ValueError, match=message):
            collapse_dispersion(curves, 0.5)


def test_connected_curves_matches_the_class():
    z = stationary(seed=3)
    ca = ConnectedAgeing(z, [5, 50]).compute()
    curves = connected_curves(z, [5, 50], np.arange(1, TAPS - 50 + 1))
    np.testing.assert_array_equal(curves[50][1], ca.C[50])
