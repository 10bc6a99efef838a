# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Steady state and fluctuations of a global value X(t) (Phi_b, <Phi^c>, <Z>) over taps t,
section III.A-B and Fig. 3 of Philippe & Bideau.

* :class:`SteadyState`: X_SS, the mean over the last ``last`` taps (paper: the last 1000 of
  4000), with its standard deviation sigma_X = sqrt(<(X - X_SS)^2>) and a standard error that
  accounts for the correlation between successive taps (batch means).
* :class:`PowerSpectrum`: the power spectrum of X - X_SS against the frequency 1/taps and its
  log-log slope with an uncertainty.
* :func:`sigma_x` and :func:`sigma_scaling` (sigma_X proportional to sqrt(eps), Fig. 3).
* :class:`ErrorCalibration`: whether one run's own (batch-means) error tells how far another
  realization of the same settings lands, and by which factor it falls short.
"""

import numpy as np
from scipy import fft as scipy_fft
from scipy import signal, special, stats

from ._legends import place_legend
from ._validate import as_1d, as_2d, computed_repr, new_axis, positive_int, require, result
from .laws import FitResult, Law

__all__ = ["SteadyState", "ErrorCalibration", "PowerSpectrum", "sigma_x", "sigma_scaling", "Proportional",
           "DEFAULT_LAST", "DEFAULT_BATCHES", "DEFAULT_BINS_PER_DECADE", "jackknife_error",
           "binned_periodogram_layout", "binned_periodograms", "shaped_gaussian_series"]

#: taps averaged for the steady state (paper, section III.B: the last 1000 of 4000 taps)
DEFAULT_LAST = 1000
#: batches of the batch-means standard error: 20 batches of 50 taps for 1000 taps, longer than
#: the correlation time of the steady-state fluctuations in the paper's runs
DEFAULT_BATCHES = 20
#: logarithmic frequency bins per decade for the averaged spectrum (about 10 gives bins holding
#: several periodogram ordinates everywhere but at the lowest frequencies)
DEFAULT_BINS_PER_DECADE = 10
#: correlation of periodogram ordinates k apart (k = 0, 1, 2) for a tapered series:
#: |sum_t w_t^2 exp(-2 pi i k t / N)|^2 / (sum_t w_t^2)^2; Hann: w^2 has Fourier weights
#: 3/8, -1/4, 1/16, so (1, 4/9, 1/36); boxcar (no taper): independent ordinates
WINDOW_CORRELATIONS = {"hann": (1.0, 4.0 / 9.0, 1.0 / 36.0), "boxcar": (1.0,)}


def jackknife_error(replicates):
    """Standard error of a statistic from its leave-one-block-out replicates (B of them, first
    axis): sqrt((B - 1) / B * sum (theta_k - mean theta)^2). The blocks are spatial for one
    packing (tapmc.pores.PoreOutput.jackknife, tapmc.profiles.vertical_profile_jackknife),
    where seeds give no error."""
    r = np.asarray(replicates, dtype=float)
    b = r.shape[0]
    if b < 2:
        raise ValueError(f"a jackknife needs at least 2 replicates, got {b}")
    return np.sqrt((b - 1) / b * np.sum((r - r.mean(axis=0)) ** 2, axis=0))


def _batch_sem(x, batches):
    """Batch-means standard error of the mean of x; with fewer than 2 batches of at least one
    value (a window of 2 or 3 taps) the naive std / sqrt(n), the only one there is."""
    n = len(x) // batches if batches >= 2 else 0
    if n < 1:
        return float(np.std(x, ddof=1) / np.sqrt(len(x)))
    means = x[: n * batches].reshape(batches, n).mean(axis=1)
    return float(np.std(means, ddof=1) / np.sqrt(batches))


class SteadyState:
    """Steady-state value of a series X(t), one value per tap (section III.B).

    Parameters: ``x`` (the series), ``last`` (taps averaged at the end, default 1000),
    ``batches`` (batches for the standard error, default 20), ``detrend`` (what sigma_X is
    measured about: ``"constant"``, X_SS, the paper's definition; or ``"linear"``, a straight
    line fitted over the window, for a run still compacting at its end, whose drift would
    otherwise count as fluctuation. A straight line also takes out part of the slowest
    fluctuations, so the linear sigma_X is a lower estimate of the steady state's).
    Results after ``compute()``: ``mean`` (X_SS), ``std`` (sigma_X over the window, about
    ``detrend``), ``trend`` (slope per tap of the straight line over the window), ``sem``
    (batch-means standard error of X_SS: successive taps are correlated, so the naive
    std/sqrt(n) underestimates it), ``batches_used`` (the batches ``sem`` came from:
    ``batches``, or fewer when the window has under 2 taps per batch, ``last // 2``; 0 when it
    cannot hold two, and ``sem`` is then the naive one), ``sem_naive``, ``last_value`` (the paper's alternative
    estimate, "directly through the last value"), ``window`` (slice of the taps used)."""

    DETRENDS = ("constant", "linear")

    def __init__(self, x, last=DEFAULT_LAST, batches=DEFAULT_BATCHES, detrend="constant"):
        self.x = as_1d("x", x, min_len=2)
        self.last = positive_int("last", last, minimum=2)
        if self.last > len(self.x):
            raise ValueError(f"last = {last} exceeds the series length {len(self.x)}")
        self.batches = positive_int("batches", batches, minimum=2)
        if detrend not in self.DETRENDS:
            raise ValueError(f"detrend = {detrend!r}: expected one of {self.DETRENDS}")
        if detrend == "linear" and self.last < 3:
            raise ValueError(f"detrend = 'linear' needs last >= 3 (two fitted parameters), "
                             f"got last = {last}")
        self.detrend = detrend
        self._mean = None

    def compute(self):
        seg = self.x[-self.last:]
        self._window = slice(len(self.x) - self.last, len(self.x))
        self._mean = float(seg.mean())
        self._trend = float(np.polyfit(np.arange(len(seg)), seg, 1)[0])
        self._std = float(np.std(self.deviations(), ddof=1 if self.detrend == "constant" else 2))
        used = min(self.batches, self.last // 2)  # batches of at least 2 taps each
        self._batches_used = used if used >= 2 else 0
        self._sem_naive = self._std / np.sqrt(len(seg))
        # a window too short for two batches: the naive error, about ``detrend`` as sem_naive
        self._sem = _batch_sem(seg, used) if used >= 2 else self._sem_naive
        return self

    def deviations(self):
        """X - X_SS (``detrend`` constant) or X minus its straight line (linear) over the
        window."""
        seg = self.x[-self.last:]
        if self.detrend == "constant":
            return seg - seg.mean()
        t = np.arange(len(seg))
        return seg - np.polyval(np.polyfit(t, seg, 1), t)

    window = result("_window")
    mean = result("_mean")
    std = result("_std")
    trend = result("_trend")
    sem = result("_sem")
    sem_naive = result("_sem_naive")
    batches_used = result("_batches_used")
    last_value = property(lambda self: float(self.x[-1]))

    def __repr__(self):
        return computed_repr(self, "_mean", f"of {len(self.x)} values, last {self.last}",
                             lambda: f"X_SS {self._mean:.6g} +- {self._sem:.2g}, "
                                     f"sigma_X {self._std:.3g}")

    def plot(self, ax=None, ylabel="X (the series, per tap)", **kw):
        """The series, the averaging window (grey) and X_SS +- sigma_X (solid, dotted)."""
        ax = new_axis(ax)
        t = np.arange(len(self.x))
        ax.plot(t, self.x, lw=0.7, **kw)
        ax.set_ylabel(ylabel)
        ax.axvspan(self.window.start, len(self.x) - 1, color="0.9")
        ax.axhline(self.mean, color="k")
        ax.axhline(self.mean + self.std, color="k", ls=":")
        ax.axhline(self.mean - self.std, color="k", ls=":")
        ax.set_xlabel("taps")
        return ax


class ErrorCalibration:
    """Does the error one run gives itself tell how far another realization lands?

    ``SteadyState.sem`` is the batch-means error of one run's time average: its error given
    that run's own history. Fluctuations slower than a batch (Fig. 3: spectra falling as f^-1
    to f^-1.5) escape it, and independent realizations of the same settings then scatter more
    than their errors say. Over groups of realizations that share their settings this compares
    the realizations' spread of the window mean with their own errors:

        k^2 = sum_g (n_g - 1) s_g^2 / e_g^2 / sum_g (n_g - 1)

    s_g: standard deviation of group g's n_g window means; e_g^2: their mean squared
    within-run error. k = 1 when the within-run errors are calibrated; otherwise one run's
    error times k is the error of a realization. With calibrated errors k^2 follows about an
    F distribution with sum (n_g - 1) and sum n_g * within_dof degrees of freedom (each
    within-run variance has within_dof; exact for one group), or chi2(dof) / dof for errors
    known exactly (a spectral slope's, from the periodogram's statistics), which gives k's
    interval and the p-value of k = 1 (one-sided: a spread too large for the errors).

    Parameters: ``groups`` (dict name -> (means, sems): a group's window means and their
    within-run errors, at least two realizations each), ``within_dof`` (degrees of freedom of
    one within-run error: batches - 1; None: known exactly). Results after ``compute()``:
    ``factor`` (k), ``dof`` (sum n_g - 1), ``within_dof_total`` (None for exact errors),
    ``p_value``, ``spreads`` / ``errors`` / ``ratios``
    (dict name -> s_g, e_g, s_g / e_g); :meth:`interval` (k's confidence interval);
    :meth:`same_factor_p` (do two sets of groups, e.g. two boundary conditions, share one k?).
    :meth:`from_series` measures the groups from the series themselves."""

    def __init__(self, groups, within_dof=DEFAULT_BATCHES - 1):
        if not isinstance(groups, dict) or not groups:
            raise ValueError("groups: expected a non-empty dict name -> (means, sems)")
        self.groups = {}
        for name, pair in groups.items():
            if len(pair) != 2:
                raise ValueError(f"group {name!r}: expected (means, sems), got {len(pair)} "
                                 "arrays")
            means = as_1d(f"group {name!r} means", pair[0], min_len=2)
            sems = as_1d(f"group {name!r} sems", pair[1], min_len=2)
            if len(means) != len(sems):
                raise ValueError(f"group {name!r}: {len(means)} means but {len(sems)} sems")
            if np.any(sems <= 0):
                raise ValueError(f"group {name!r}: within-run errors must be > 0, got "
                                 f"min {sems.min():g}")
            self.groups[name] = (means, sems)
        self.within_dof = None if within_dof is None else positive_int("within_dof",
                                                                        within_dof)
        self._factor = None

    @classmethod
    def from_series(cls, groups, last=DEFAULT_LAST, batches=DEFAULT_BATCHES):
        """From ``groups``: dict name -> list of series (one per realization); each series'
        window mean and batch-means error over its last ``last`` taps (SteadyState)."""
        pairs = {}
        for name, series in groups.items():
            states = [SteadyState(x, last=last, batches=batches).compute() for x in series]
            pairs[name] = ([s.mean for s in states], [s.sem for s in states])
        return cls(pairs, within_dof=min(batches, last // 2) - 1)

    def compute(self):
        self._spreads, self._errors, self._ratios = {}, {}, {}
        pooled, dof, within = 0.0, 0, 0
        for name, (means, sems) in self.groups.items():
            spread = float(np.std(means, ddof=1))
            error = float(np.sqrt(np.mean(sems ** 2)))
            self._spreads[name], self._errors[name] = spread, error
            self._ratios[name] = spread / error
            pooled += (len(means) - 1) * (spread / error) ** 2
            dof += len(means) - 1
            within += len(means) * (self.within_dof or 0)
        self._dof = dof
        self._within_total = within if self.within_dof is not None else None
        self._factor = float(np.sqrt(pooled / dof))
        self._p_value = float(self._null().sf(self._factor ** 2))
        return self

    def _null(self):
        """Distribution of k^2 with calibrated errors."""
        if self._within_total is None:
            return stats.chi2(self.dof, scale=1.0 / self.dof)
        return stats.f(self.dof, self._within_total)

    factor = result("_factor")
    dof = result("_dof")
    @property
    def within_dof_total(self):
        """Degrees of freedom of the pooled within-run errors; None for exact errors."""
        require(self, "_factor")
        return self._within_total
    p_value = result("_p_value")
    spreads = result("_spreads")
    errors = result("_errors")
    ratios = result("_ratios")

    def __repr__(self):
        return computed_repr(self, "_factor", f"of {len(self.groups)} groups",
                             lambda: f"factor {self._factor:.3g} ({self._dof} dof, "
                                     f"p = {self._p_value:.2g})")

    def interval(self, level=0.95):
        """(low, high) of k at confidence ``level``: k^2 / F quantiles."""
        if not 0 < level < 1:
            raise ValueError(f"level = {level}: expected 0 < level < 1")
        k2 = self.factor ** 2
        tail = (1 - level) / 2
        hi_q, lo_q = (self._null().ppf(q) for q in (1 - tail, tail))
        return float(np.sqrt(k2 / hi_q)), float(np.sqrt(k2 / lo_q))

    def same_factor_p(self, other):
        """Two-sided p-value of the hypothesis that ``other`` (a computed ErrorCalibration
        of other groups) has the same factor k: the ratio of the two k^2 follows
        F(dof, other.dof). The within-run errors' own scatter is neglected next to the
        realizations' (their dof are the batches' times the runs': 19 per run by default)."""
        if not isinstance(other, ErrorCalibration):
            raise ValueError(f"other: expected an ErrorCalibration, got {type(other).__name__}")
        require(other, "_factor")
        if other.factor == 0.0:  # identical means in every group of other: the test is symmetric
            if self.factor == 0.0:
                raise ValueError("both calibrations have factor 0 (identical realization means "
                                 "in every group, e.g. one seed run twice): nothing to compare")
            return other.same_factor_p(self)
        ratio = stats.f(self.dof, other.dof)
        tail = ratio.sf((self.factor / other.factor) ** 2)
        return float(min(1.0, 2 * min(tail, 1 - tail)))

    def plot(self, ax=None, **kw):
        """Each group's spread over its within-run error, and the pooled k with its 95 %
        interval (1: calibrated)."""
        ax = new_axis(ax)
        names = list(self.ratios)
        ax.plot(range(len(names)), [self.ratios[n] for n in names], "o", **kw)
        low, high = self.interval()
        ax.axhspan(low, high, color="0.85")
        ax.axhline(self.factor, color="k")
        ax.axhline(1.0, color="k", ls=":")
        ax.set_xticks(range(len(names)))
        ax.set_xticklabels(names, rotation=30, ha="right")
        ax.set_xlabel("group of realizations")
        ax.set_ylabel("realizations' spread / within-run error")
        return ax


def sigma_x(x, last=DEFAULT_LAST, detrend="constant"):
    """sigma_X = sqrt(<(X - X_SS)^2>) over the last ``last`` taps (section III.A, Fig. 3);
    ``detrend="linear"``: about the window's straight line instead (see SteadyState)."""
    return SteadyState(x, last=last, detrend=detrend).compute().std


class _LogLogLine(Law):
    names = ("log10_amplitude", "slope")
    may_vanish = ("log10_amplitude", "slope")

    @staticmethod
    def function(x, a, b):
        return a + b * x

    def initial_guess(self, x, y, w):
        b, a = np.polyfit(x, y, 1)
        return [a, b]


def _log_bins(f, bins_per_decade):
    """The logarithmic bin (a label, increasing with f) of every frequency ``f`` (> 0,
    increasing): ``bins_per_decade`` bins a decade, edges at powers of 10^(1/bins_per_decade)."""
    edges = 10 ** (np.arange(np.floor(np.log10(f[0]) * bins_per_decade),
                             np.ceil(np.log10(f[-1]) * bins_per_decade) + 2) / bins_per_decade)
    return np.digitize(f, edges)


def _relative_covariance(which, ordinate_correlation):
    """Relative covariance (cov / (mean_i mean_j)) of the bin means of ONE periodogram whose
    ordinates fall in the bins ``which`` (labels, increasing): the ordinates are exponential
    variables, those of a tapered series correlated with their neighbours
    (``ordinate_correlation``, :data:`WINDOW_CORRELATIONS`), the spectrum taken as flat
    across a bin. n independent periodograms averaged divide it by n."""
    labels = np.unique(which)
    index = np.searchsorted(labels, which)  # bin of every ordinate, 0..nbins-1
    nbins = len(labels)
    cov = np.zeros((nbins, nbins))
    np.add.at(cov, (index, index), ordinate_correlation[0])
    for lag, r in enumerate(ordinate_correlation[1:], start=1):
        np.add.at(cov, (index[:-lag], index[lag:]), r)
        np.add.at(cov, (index[lag:], index[:-lag]), r)
    counts = np.bincount(index, minlength=nbins).astype(float)
    return cov / np.outer(counts, counts)


def binned_periodogram_layout(samples, taps_per_sample=1,
                              bins_per_decade=DEFAULT_BINS_PER_DECADE, window="hann"):
    """What :class:`PowerSpectrum` makes of a segment of ``samples`` samples, before any data:
    (``frequency`` of its bins, ``counts`` of periodogram ordinates a bin, the bin means'
    ``relative_covariance`` for one series, divide by the number of independent series
    averaged). The statistics of a binned spectrum are known from this layout alone, so that
    a test of spectra need not take each spectrum's errors from its own noisy power
    (tapmc.paper.claims.fluctuations.spectrum_low_band)."""
    f = np.arange(1, samples // 2 + 1) / (samples * taps_per_sample)
    which = _log_bins(f, bins_per_decade)
    labels = np.unique(which)
    frequency = np.array([np.exp(np.mean(np.log(f[which == b]))) for b in labels])
    counts = np.array([np.sum(which == b) for b in labels])
    return frequency, counts, _relative_covariance(which, WINDOW_CORRELATIONS[window])


#: a series of a given spectrum (:func:`shaped_gaussian_series`) is synthesised over this many
#: times its length and cut to its last part: not periodic, and carrying power below its own
#: lowest frequency, which leaks into its lowest ordinates as in a window of a longer run
SYNTHESIS_OVERSAMPLING = 4


def shaped_gaussian_series(frequency, power, low_slope, samples, count, rng):
    """``count`` independent stationary Gaussian series of ``samples`` samples (one a tap)
    whose power spectrum is proportional to ``power`` at ``frequency`` (1/taps, increasing;
    linear in log-log between them, flat above the highest, the power law of log-log slope
    ``low_slope`` below the lowest), as an array (count, samples). Spectral synthesis: random
    complex Gaussian Fourier amplitudes over :data:`SYNTHESIS_OVERSAMPLING` times the length,
    the last ``samples`` kept. The scale is not fixed: for tests of spectra's ratios."""
    length = SYNTHESIS_OVERSAMPLING * samples
    f = np.fft.rfftfreq(length)[1:]
    log_f, log_p = np.log(np.asarray(frequency, float)), np.log(np.asarray(power, float))
    shape = np.interp(np.log(f), log_f, log_p)
    below = f < frequency[0]
    shape[below] = log_p[0] + low_slope * (np.log(f[below]) - log_f[0])
    amplitude = np.concatenate([[0.0], np.exp(0.5 * (shape - shape.max()))])
    z = rng.standard_normal((count, len(amplitude))) * (1 + 0j)
    z += 1j * rng.standard_normal((count, len(amplitude)))
    z *= amplitude
    return scipy_fft.irfft(z, n=length, axis=1, overwrite_x=True)[:, -samples:]


def binned_periodograms(x, counts, window="hann"):
    """The bin means (n_series, bins) of the periodograms of the rows of ``x`` about their
    means, ordinates f > 0 binned ``counts`` a bin from the lowest (the first bins of
    :func:`binned_periodogram_layout`): :class:`PowerSpectrum`'s power of each row, for many
    rows at once."""
    _, p = signal.periodogram(x - x.mean(axis=1, keepdims=True), axis=1, window=window,
                              detrend="constant", scaling="density")
    edges = np.concatenate([[0], np.cumsum(counts)]) + 1  # ordinate 0 (f = 0) left out
    return np.stack([p[:, a:b].mean(axis=1) for a, b in zip(edges[:-1], edges[1:])], axis=1)


class PowerSpectrum:
    """Power spectrum of the fluctuations X - X_SS against the frequency f = 1/taps and its
    log-log slope (section III.A, Fig. 3: "more or less a simple power-law ... with a slope in
    the range 1 to 1.5", i.e. P(f) ~ f^slope with slope about -1 to -1.5).

    Estimator: the periodogram (one-sided power spectral density, scipy.signal.periodogram) of
    the segment ``x[steady_from:]`` minus its mean X_SS, with a Hann window (its side lobes fall
    as f^-3, so that steep spectra, up to f^-2 and beyond, are not flattened by leakage from the
    lowest frequencies), averaged in logarithmic frequency bins (``bins_per_decade``). The slope
    is a weighted straight-line fit of log10 P against log10 f over ``fit_range`` (default all
    bins), each bin weighted by the number of periodogram ordinates it averages; its
    uncertainty is scaled by the scatter of the binned points about the line.

    Parameters: ``x`` (one value per sample; or (n_series, n_samples) for independent
    realizations, e.g. seeds, whose periodograms are averaged, each about its own X_SS),
    ``steady_from`` (first sample of the segment, default 0), ``taps_per_sample`` (taps between samples, default 1: f in 1/taps),
    ``bins_per_decade``, ``fit_range`` ((f_min, f_max) in 1/taps or None).
    Results: ``frequency`` and ``power`` (binned), ``power_error`` (the bin means' standard
    error from the periodogram's own statistics, ordinate correlations included),
    ``counts`` (ordinates per bin),
    ``raw_frequency`` and ``raw_power`` (the periodogram), ``slope``, ``slope_error``,
    ``fit`` (a :class:`tapmc.laws.FitResult` in log10-log10), ``x_ss``, ``sigma``.
    """

    def __init__(self, x, steady_from=None, taps_per_sample=1, bins_per_decade=DEFAULT_BINS_PER_DECADE,
                 fit_range=None, window="hann"):
        arr = np.asarray(x, dtype=float)
        if arr.ndim == 2:
            self.x = as_2d("x", arr, min_rows=1, min_cols=16)
        else:
            self.x = as_1d("x", arr, min_len=16)[None, :]
        n = self.x.shape[1]
        start = 0 if steady_from is None else positive_int("steady_from", steady_from, minimum=0)
        if n - start < 16:
            raise ValueError(f"steady_from = {steady_from} leaves {n - start} samples;"
                             " at least 16 are needed for a spectrum")
        self.steady_from = start
        self.taps_per_sample = positive_int("taps_per_sample", taps_per_sample)
        self.bins_per_decade = positive_int("bins_per_decade", bins_per_decade)
        if fit_range is not None:
            lo, hi = (float(v) for v in fit_range)
            if not (0 < lo < hi):
                raise ValueError(f"fit_range = {fit_range!r} must be (f_min, f_max) with "
                                 "0 < f_min < f_max (in 1/taps)")
            fit_range = (lo, hi)
        self.fit_range = fit_range
        if window not in WINDOW_CORRELATIONS:
            raise ValueError(f"window = {window!r} must be one of {sorted(WINDOW_CORRELATIONS)}")
        self.window = window
        self.ordinate_correlation = WINDOW_CORRELATIONS[window]
        self._fit = None

    def compute(self):
        seg = self.x[:, self.steady_from:]
        x_ss = seg.mean(axis=1, keepdims=True)  # X_SS of every series
        self._x_ss = float(x_ss.mean())
        self._sigma = float(np.sqrt(np.mean((seg - x_ss) ** 2)))
        f, p = signal.periodogram(seg - x_ss, fs=1.0 / self.taps_per_sample, axis=1,
                                  window=self.window, detrend="constant", scaling="density")
        p = p.mean(axis=0)  # independent series: their periodograms average
        f, p = f[1:], p[1:]  # f = 0 carries the removed mean only
        self._raw_frequency, self._raw_power = f, p
        which = _log_bins(f, self.bins_per_decade)
        freq, power, counts = [], [], []
        for b in np.unique(which):
            sel = which == b
            freq.append(np.exp(np.mean(np.log(f[sel]))))
            power.append(p[sel].mean())
            counts.append(sel.sum())
        self._frequency = np.array(freq)
        self._power = np.array(power)
        self._counts = np.array(counts)
        use = self._power > 0
        if self.fit_range is not None:
            use &= (self._frequency >= self.fit_range[0]) & (self._frequency <= self.fit_range[1])
        if use.sum() < 3:
            raise ValueError(f"only {use.sum()} spectrum bins in fit_range = {self.fit_range}; "
                             "at least 3 are needed for a slope")
        relative = _relative_covariance(which, self.ordinate_correlation) / self.x.shape[0]
        # the bin means' own error: what one run's spectrum carries in place of a sem over
        # realizations (a Gamma mean of m effective ordinates has relative error 1/sqrt(m))
        self._power_error = self._power * np.sqrt(np.diag(relative))
        self._fit = self._fit_slope(relative, use)
        return self

    def _fit_slope(self, relative, use):
        """Generalised least squares of log10 P against log10 f over the bins in ``use``.
        The periodogram ordinates are exponential variables; those of a tapered series are
        correlated with their neighbours (``ordinate_correlation``). The covariance of the bin
        means follows from that (delta method), the exact variance of the log of a Gamma
        variable (trigamma) replaces the delta-method diagonal, and the bias of that log,
        ln(m) - digamma(m) for m effective ordinates, is removed (left in, it would flatten the
        slope through the sparse low-frequency bins)."""
        cov = relative[np.ix_(use, use)]
        m_eff = 1.0 / np.diag(cov)
        ratio = special.polygamma(1, m_eff) * m_eff  # exact / delta-method variance of the log
        cov = cov * np.sqrt(np.outer(ratio, ratio)) / np.log(10) ** 2
        x = np.log10(self._frequency[use])
        y = np.log10(self._power[use]) + (np.log(m_eff) - special.digamma(m_eff)) / np.log(10)
        design = np.stack([np.ones_like(x), x], axis=1)
        cinv = np.linalg.inv(cov)
        pcov = np.linalg.inv(design.T @ cinv @ design)
        popt = pcov @ design.T @ cinv @ y
        resid = y - design @ popt
        chi2 = float(resid @ cinv @ resid)
        dof = len(x) - 2
        # a spectrum that is not a power law over the range scatters more than the estimator
        # does: widen the errors by the reduced chi2 then (never narrow them)
        pcov = pcov * max(1.0, chi2 / dof if dof > 0 else 1.0)
        res = FitResult(_LogLogLine(), _LogLogLine.names, popt, pcov, x, y,
                        np.sqrt(np.diag(cov)), True, "", True)
        res.chi2, res.dof = chi2, dof
        res.reduced_chi2 = chi2 / dof if dof > 0 else np.nan
        return res

    x_ss = result("_x_ss")
    sigma = result("_sigma")
    raw_frequency = result("_raw_frequency")
    raw_power = result("_raw_power")
    frequency = result("_frequency")
    power = result("_power")
    power_error = result("_power_error")
    counts = result("_counts")
    fit = result("_fit")

    def __repr__(self):
        runs, taps = self.x.shape
        return computed_repr(self, "_power", f"of {runs} run(s) x {taps} taps",
                             lambda: f"{len(self._frequency)} frequency bins")
    slope = property(lambda self: float(self.fit.params["slope"]))
    slope_error = property(lambda self: float(self.fit.errors["slope"]))

    def plot(self, ax=None, raw=False, **kw):
        """Binned spectrum (points) and the fitted power law, log-log."""
        ax = new_axis(ax)
        if raw:
            ax.loglog(self.raw_frequency, self.raw_power, color="0.8", lw=0.5,
                      label="periodogram")
        kw.setdefault("marker", "o")
        kw.setdefault("ls", "none")
        kw.setdefault("label", "binned")
        ax.loglog(self.frequency, self.power, **kw)
        fx = 10 ** self.fit.x
        ax.loglog(fx, 10 ** self.fit(self.fit.x), "k-",
                  label=f"slope {self.slope:.2f} $\\pm$ {self.slope_error:.2f}")
        ax.set_xlabel("frequency (1/taps)")
        ax.set_ylabel("power")
        place_legend(ax, fontsize=8)
        return ax


class Proportional(Law):
    """y = k x (sigma_X proportional to sqrt(eps), section III.A)."""

    names = ("k",)

    @staticmethod
    def function(x, k):
        return k * x

    def initial_guess(self, x, y, w):
        return [np.sum(w * x * y) / np.sum(w * x * x)]


def sigma_scaling(sqrt_eps, sigma, sigma_error=None):
    """Fit sigma_X = k sqrt(eps) (Fig. 3b); returns a :class:`tapmc.laws.FitResult`; its
    ``reduced_chi2`` (with ``sigma_error``) tests the proportionality."""
    return Proportional().fit(sqrt_eps, sigma, sigma_error)

