# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# tapmc.fluctuations: the spectral slope is recovered from synthetic 1/f^beta noise (spectral
# synthesis, beta in [0.5, 2]) within its reported error over seeds; steady-state mean, sigma_X
# and the batch-means standard error on series with known statistics; ErrorCalibration's
# factor against known realization spreads (calibrated, offsets, slow 1/f noise).
import os
import sys
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", HERE.parent.parent))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc._validate import NotComputedError  # noqa: E402
from tapmc.fluctuations import (ErrorCalibration, PowerSpectrum, SteadyState,  # noqa: E402
                                sigma_scaling, sigma_x)


def powerlaw_noise(n, beta, rng, pad=4):
    """Gaussian noise with power spectrum ~ f^-beta: random Fourier amplitudes ~ f^(-beta/2)
    over a series ``pad`` times longer, then a random window of n samples (so the sample is not
    periodic, as a real series is not)."""
    m = n * pad
    f = np.fft.rfftfreq(m)
    amp = np.zeros_like(f)
    amp[1:] = f[1:] ** (-beta / 2.0)
    coef = amp * (rng.normal(size=f.size) + 1j * rng.normal(size=f.size))
    x = np.fft.irfft(coef, m)
    start = rng.integers(0, m - n)
    return x[start:start + n]


@pytest.mark.parametrize("beta", [0.5, 1.0, 1.5, 2.0])
def test_slope_recovered_from_power_law_noise(beta):
    seeds = 30
    z = []
    for seed in range(seeds):
        x = 0.6 + 1e-3 * powerlaw_noise(4000, beta, np.random.default_rng(seed))
        ps = PowerSpectrum(x).compute()
        z.append((ps.slope + beta) / ps.slope_error)
    z = np.abs(np.array(z))
    # calibrated errors: ~95 % within 2 sigma, ~68 % within 1 sigma (binomial bounds, 30 seeds)
    assert np.mean(z <= 2) >= 0.8, z
    assert 0.4 <= np.mean(z <= 1) <= 0.95, z
    assert np.mean(z) < 1.3  # no bias beyond a fraction of the error


def test_slope_from_several_realizations():
    # periodograms of independent series average: the error shrinks about as 1/sqrt(series)
    beta, z, errs = 1.3, [], []
    for seed in range(20):
        rng = np.random.default_rng(500 + seed)
        x = np.array([7.0 + powerlaw_noise(1000, beta, rng) for _ in range(5)])
        ps = PowerSpectrum(x).compute()
        z.append((ps.slope + beta) / ps.slope_error)
        errs.append(ps.slope_error)
    z = np.abs(np.array(z))
    assert np.mean(z <= 2) >= 0.8 and 0.4 <= np.mean(z <= 1) <= 0.95, z
    single = PowerSpectrum(x[0]).compute().slope_error
    assert np.mean(errs) < 0.7 * single


def test_spectrum_of_white_noise_and_frequency_units():
    rng = np.random.default_rng(5)
    x = rng.normal(size=4096)
    ps = PowerSpectrum(x, taps_per_sample=1).compute()
    assert abs(ps.slope) < 3 * ps.slope_error
    assert ps.frequency.max() <= 0.5 and ps.frequency.min() >= 1.0 / 4096
    # one-sided density: its integral is the variance of X - X_SS
    assert np.trapz(ps.raw_power, ps.raw_frequency) == pytest.approx(np.var(x), rel=0.05)
    sparse = PowerSpectrum(x[::10], taps_per_sample=10).compute()
    assert sparse.frequency.max() <= 0.05
    ranged = PowerSpectrum(x, fit_range=(0.01, 0.2)).compute()
    assert ranged.fit.x.min() >= -2 and ranged.fit.x.max() <= np.log10(0.2)


def test_steady_state_mean_sigma_and_correlated_sem():
    rng = np.random.default_rng(11)
    # AR(1) fluctuations (correlation time ~ 10 taps) around 0.62 after a compaction transient
    n, a = 4000, 0.9
    noise = np.empty(n)
    noise[0] = 0.0
    eps = rng.normal(0, 1e-3, n)
    for i in range(1, n):
        noise[i] = a * noise[i - 1] + eps[i]
    x = 0.62 - 0.03 * np.exp(-np.arange(n) / 300.0) + noise
    ss = SteadyState(x, last=1000).compute()
    sd = 1e-3 / np.sqrt(1 - a * a)
    assert ss.mean == pytest.approx(0.62, abs=5 * ss.sem)
    assert ss.std == pytest.approx(sd, rel=0.15)
    assert sigma_x(x) == ss.std
    # correlated taps: the batch-means error is larger than the naive one by about
    # sqrt((1 + a) / (1 - a)) = 4.4
    assert 2.5 < ss.sem / ss.sem_naive < 7
    assert ss.last_value == x[-1]


def test_steady_state_of_a_window_too_short_to_batch_and_bad_counts():
    """Two or three taps cannot make two batches: the error is the naive one, never NaN; a
    count that is not a whole number (infinity, NaN, None, text) is refused by name."""
    x = np.array([1.0, 2.0, 3.0, 5.0, 4.0, 6.0])
    for last in (2, 3):
        s = SteadyState(x, last=last).compute()
        assert np.isfinite(s.sem) and s.sem == pytest.approx(s.sem_naive)
        assert s.batches_used == 0
    # fewer batches than asked when the window has under 2 taps per batch, and it says so
    s = SteadyState(x, last=5, batches=20).compute()
    assert (s.batches, s.batches_used) == (20, 2)
    assert s.sem == pytest.approx(np.std([x[1:3].mean(), x[3:5].mean()], ddof=1) / np.sqrt(2))
    assert SteadyState(np.arange(100.0), last=100).compute().batches_used == 20
    for bad in (float("inf"), float("nan"), None, "3", 2.5):
        with pytest.raises(ValueError, match=f"last = {bad!r} must be an integer >= 2"):
            SteadyState(x, last=bad)


def test_linear_detrend_separates_drift_from_fluctuations():
    # white noise of sigma 1e-3 on a drift of 1e-5 per tap: over 1000 taps the drift alone
    # spreads 1e-2 / sqrt(12) = 2.9e-3 about the mean, which the paper's sigma counts
    rng = np.random.default_rng(11)
    over_seeds = []
    for _ in range(200):
        x = 0.6 + 1e-5 * np.arange(3000) + rng.normal(0, 1e-3, 3000)
        raw = SteadyState(x, last=1000).compute()
        line = SteadyState(x, last=1000, detrend="linear").compute()
        assert raw.std == pytest.approx(np.hypot(1e-3, 1e-2 / np.sqrt(12)), rel=0.08)
        assert line.trend == pytest.approx(1e-5, abs=6 * np.sqrt(12) * 1e-3 / 1000 ** 1.5)
        assert line.mean == raw.mean
        over_seeds.append(line.std)
        assert sigma_x(x, detrend="linear") == line.std
    # ddof 2: the variance about the fitted line is unbiased
    assert np.mean(np.square(over_seeds)) == pytest.approx(1e-6, rel=0.01)
    # no drift: both agree to within the line's two fitted parameters
    y = rng.normal(0, 1e-3, 1000)
    assert SteadyState(y, detrend="linear").compute().std == pytest.approx(
        SteadyState(y).compute().std, rel=0.01)
    with pytest.raises(ValueError, match="detrend = 'quadratic'"):
        SteadyState(y, detrend="quadratic")
    with pytest.raises(ValueError, match="last >= 3"):
        SteadyState(y, last=2, detrend="linear")


def test_sigma_scaling_fit_and_validation():
    s = np.array([0.05, 0.1, 0.15, 0.2])
    res = sigma_scaling(s, 0.02 * s, 1e-4 * np.ones(4))
    assert res.params["k"] == pytest.approx(0.02)
    with pytest.raises(ValueError, match="last = 5000"):
        SteadyState(np.ones(4000), last=5000)
    with pytest.raises(ValueError, match="steady_from"):
        PowerSpectrum(np.ones(100), steady_from=95)
    with pytest.raises(ValueError, match="fit_range"):
        PowerSpectrum(np.ones(100), fit_range=(0.3, 0.1))
    with pytest.raises(NotComputedError):
        PowerSpectrum(np.ones(100)).slope
    with pytest.raises(NotComputedError):
        SteadyState(np.ones(100), last=50).mean
    # every documented result is a read-only property (these were plain attributes: an
    # AttributeError before compute(), and writable after)
    spectrum = PowerSpectrum(np.random.default_rng(0).normal(size=200))
    for name in ("x_ss", "sigma", "raw_frequency", "raw_power"):
        with pytest.raises(NotComputedError):
            getattr(spectrum, name)
    with pytest.raises(NotComputedError):
        SteadyState(np.ones(100), last=50).window
    spectrum.compute()
    with pytest.raises(AttributeError):
        spectrum.x_ss = 123.0


def test_a_window_too_short_for_batches_gives_the_naive_error_about_its_detrend():
    # last = 3 holds no two batches of 2 taps: sem is sem_naive, about the straight line
    for detrend in ("constant", "linear"):
        s = SteadyState([1.0, 2.0, 4.0], last=3, detrend=detrend).compute()
        assert s.batches_used == 0 and s.sem == s.sem_naive
    assert SteadyState([1.0, 2.0, 4.0], last=3, detrend="linear").compute().sem == \
        pytest.approx(np.sqrt(1.0 / 6.0) / np.sqrt(3.0))   # residuals 1/6, -1/3, 1/6; ddof 2
    with pytest.raises(ValueError, match="x must hold numbers"):
        SteadyState(["a", "b"])


def test_plots():
    import matplotlib
    matplotlib.use("Agg")
    rng = np.random.default_rng(2)
    ps = PowerSpectrum(powerlaw_noise(2000, 1.0, rng)).compute()
    assert len(ps.plot(raw=True).lines) == 3
    ss = SteadyState(rng.normal(size=2000)).compute()
    assert len(ss.plot().lines) >= 4


@pytest.mark.parametrize("backend", ["template", None])
def test_plot_keeps_the_users_backend_and_figures(backend):
    # plot(ax=None) makes its figure on the backend in use: it never switches backend (a
    # switch closes every open figure, e.g. a notebook's); headless, matplotlib picks Agg.
    import subprocess
    code = ("import numpy as np, matplotlib, matplotlib.pyplot as plt\n"
            "from tapmc.fluctuations import SteadyState\n"
            "before = matplotlib.get_backend()\n"
            "fig, _ = plt.subplots()\n"
            "ax = SteadyState(np.arange(10.0), last=5).compute().plot()\n"
            "assert matplotlib.get_backend() == before, (before, matplotlib.get_backend())\n"
            "assert plt.fignum_exists(fig.number) and ax.figure is not fig\n"
            "print(before)\n")
    env = {k: v for k, v in os.environ.items() if k not in ("MPLBACKEND", "DISPLAY",
                                                            "WAYLAND_DISPLAY")}
    env["PYTHONPATH"] = str(SOURCE / "tools" / "python")
    if backend:
        env["MPLBACKEND"] = backend
    run = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip().lower() == (backend or "agg")


def test_power_error_is_the_scatter_of_one_runs_spectrum():
    """One run's bin errors (from the periodogram's statistics) match the scatter of the binned
    power over independent runs: they stand in for a sem over seeds."""
    rng = np.random.default_rng(11)
    runs = [PowerSpectrum(rng.normal(size=1000)).compute() for _ in range(400)]
    power = np.array([r.power for r in runs])
    predicted = np.mean([r.power_error / r.power for r in runs], axis=0)
    observed = power.std(axis=0, ddof=1) / power.mean(axis=0)
    assert np.all(np.abs(observed / predicted - 1) < 0.2), (observed, predicted)
    # bins of one ordinate: an exponential variable, relative error 1
    one = runs[0].counts == 1
    assert one.any() and np.allclose(predicted[one], 1.0)


def _calibration(rng, groups, runs, taps, offset=0.0, make=None):
    """ErrorCalibration of ``groups`` x ``runs`` series of ``taps`` taps: white noise of unit
    variance plus, per realization, a constant offset of standard deviation ``offset``
    (``make(rng)`` replaces the white noise when given)."""
    series = {f"g{g}": [(make(rng) if make else rng.normal(size=taps))
                        + offset * rng.normal() for _ in range(runs)] for g in range(groups)}
    return ErrorCalibration.from_series(series, last=taps).compute()


def test_error_calibration_is_calibrated_for_white_noise():
    # batch means are exact for uncorrelated taps: k = 1 within its interval 95 % of the time
    # and the p-value of k = 1 uniform (about 5 % below 0.05)
    rng = np.random.default_rng(11)
    trials = [_calibration(rng, 3, 4, 400) for _ in range(200)]
    rejected = np.mean([c.p_value < 0.05 for c in trials])
    covered = np.mean([c.interval()[0] <= 1.0 <= c.interval()[1] for c in trials])
    assert 0.01 <= rejected <= 0.10
    assert covered >= 0.88
    assert 0.9 < np.median([c.factor for c in trials]) < 1.1


def test_error_calibration_recovers_a_known_realization_spread():
    # an offset per realization of sd 0.1 over 400 white taps (window mean's error 1/20):
    # another realization lands sqrt(1 + 0.1^2 * 400) = sqrt(5) within-run errors away
    rng = np.random.default_rng(12)
    truth = np.sqrt(1 + 0.1 ** 2 * 400)
    trials = [_calibration(rng, 6, 5, 400, offset=0.1) for _ in range(100)]
    assert abs(np.median([c.factor for c in trials]) / truth - 1) < 0.1
    covered = np.mean([c.interval()[0] <= truth <= c.interval()[1] for c in trials])
    assert covered >= 0.85
    assert np.mean([c.p_value < 1e-3 for c in trials]) > 0.95


def test_error_calibration_sees_slow_noise_that_batch_means_miss():
    # short correlations (AR(1), 3 taps, against batches of 20) leave k near 1; a spectrum
    # falling as f^-1.4 (Fig. 3's slopes) puts power below a batch's frequency, so the runs
    # scatter several within-run errors apart
    rng = np.random.default_rng(13)

    def ar1(rng, n=400, phi=0.5):
        x = np.empty(n)
        x[0] = rng.normal()
        for i in range(1, n):
            x[i] = phi * x[i - 1] + rng.normal()
        return x

    short = [_calibration(rng, 4, 4, 400, make=ar1).factor for _ in range(40)]
    assert 0.85 < np.median(short) < 1.25
    slow = _calibration(rng, 6, 5, 1000, make=lambda r: powerlaw_noise(1000, 1.4, r))
    assert slow.factor > 2 and slow.p_value < 1e-6


def test_error_calibration_same_factor_p_is_uniform_under_one_factor_and_rejects_two():
    # two sets of groups with one realization offset (k = sqrt 5 both): the p-value is about
    # uniform (5 % below 0.05); sets whose offsets differ (k = sqrt 5 against sqrt 37 over 400
    # white taps) are told apart by the larger set of groups
    rng = np.random.default_rng(14)
    same = [_calibration(rng, 4, 5, 400, offset=0.1).same_factor_p(
        _calibration(rng, 1, 3, 400, offset=0.1)) for _ in range(300)]
    assert 0.02 <= np.mean(np.less(same, 0.05)) <= 0.09
    assert 0.4 < np.median(same) < 0.6
    apart = [_calibration(rng, 4, 5, 400, offset=0.1).same_factor_p(
        _calibration(rng, 2, 5, 400, offset=0.3)) for _ in range(100)]
    assert np.mean(np.less(apart, 0.05)) > 0.8   # F(8, 16) at a ratio of 7.4: power 0.89
    # symmetric in its two arguments
    a, b = _calibration(rng, 3, 4, 400), _calibration(rng, 2, 3, 400, offset=0.1)
    assert a.same_factor_p(b) == pytest.approx(b.same_factor_p(a))
    with pytest.raises(ValueError, match="other: expected an ErrorCalibration"):
        a.same_factor_p(2.0)
    # a set of groups whose realizations agree exactly (one seed run twice): factor 0, a factor
    # apart from any other, symmetric; two such sets: nothing to compare
    twins = ErrorCalibration({"x": ([1.0, 1.0], [0.1, 0.1])}).compute()
    assert twins.factor == 0.0
    assert a.same_factor_p(twins) == twins.same_factor_p(a) == pytest.approx(0.0, abs=1e-3)
    with pytest.raises(ValueError, match="both calibrations have factor 0"):
        twins.same_factor_p(twins)
    with pytest.raises(NotComputedError):
        a.same_factor_p(ErrorCalibration({"x": ([1.0, 2.0], [0.1, 0.1])}))


def test_error_calibration_results_plot_and_validation():
    import matplotlib
    matplotlib.use("Agg")
    means = {"a": ([1.0, 1.2, 0.8], [0.1, 0.1, 0.1]), "b": ([2.0, 2.1], [0.05, 0.05])}
    calib = ErrorCalibration(means, within_dof=19)
    with pytest.raises(NotComputedError):
        calib.factor
    calib.compute()
    # group a: s = 0.2, e = 0.1 (ratio 2, 2 dof); b: s = 0.0707, e = 0.05 (ratio sqrt 2, 1 dof)
    assert calib.ratios["a"] == pytest.approx(2.0)
    assert calib.ratios["b"] == pytest.approx(np.sqrt(2.0))
    assert calib.factor == pytest.approx(np.sqrt((2 * 4 + 1 * 2) / 3))
    assert calib.dof == 3 and calib.within_dof_total == 5 * 19
    low, high = calib.interval(0.68)
    assert low < calib.factor < high
    assert len(calib.plot().lines) == 3
    with pytest.raises(ValueError, match="group 'x' means"):
        ErrorCalibration({"x": ([1.0], [0.1])})
    with pytest.raises(ValueError, match="group 'x': within-run errors must be > 0"):
        ErrorCalibration({"x": ([1.0, 2.0], [0.1, 0.0])})
    with pytest.raises(ValueError, match="group 'x': 2 means but 3 sems"):
        ErrorCalibration({"x": ([1.0, 2.0], [0.1, 0.1, 0.1])})
    with pytest.raises(ValueError, match="level = 1.5"):
        calib.interval(1.5)
    with pytest.raises(ValueError, match="groups"):
        ErrorCalibration({})
    # errors known exactly: chi2(3) / 3 instead of F(3, 95)
    exact = ErrorCalibration(means, within_dof=None).compute()
    assert exact.factor == calib.factor and exact.within_dof_total is None
    from scipy import stats
    assert exact.p_value == pytest.approx(stats.chi2.sf(3 * calib.factor ** 2, 3))
