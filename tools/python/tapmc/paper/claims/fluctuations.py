# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Statistics of the fluctuations (section III.A, Fig. 3): the spectral slopes of <Z>, the
spectra of every eps at the lowest frequencies, and sigma_<Z>'s intercept at sqrt(eps) = 0."""

from __future__ import annotations

import numpy as np
from scipy.stats import chi2 as chi2_distribution

from tapmc.fluctuations import (binned_periodogram_layout, binned_periodograms,
                                shaped_gaussian_series)
from tapmc.stats import weighted_line_fit

from .. import _plotting as P
from .common import not_in_campaign, one_seed_error_text, value_triple
from .conventions import SPECTRUM_BAND
from .measure import Measure, fmt
from .registry import statistic


@statistic("spectral_slopes")
def spectral_slopes(data, claim):
    fig3 = data.result("fig3")
    if fig3 is None:
        return not_in_campaign("no Fig. 3 runs")
    out = []
    for eps, spectrum in _spectra(fig3):
        m, s, n = value_triple(spectrum.slope)
        out.append(Measure(-m, s, data.point_dof("fig3", spectrum.slope), label=f"eps = {eps:g}",
                           shown=fmt(m, s)))
    return out or not_in_campaign("no spectrum")


def _spectra(fig3):
    """(eps, Spectrum) of Fig. 3's result by eps, eps as the figure labels it (the CSV's
    ``eps=<eps>``, four digits: the page's labels)."""
    return sorted((float(P.fmt_eps(eps)), spectrum) for eps, spectrum in fig3.spectra.items())


#: relative tolerance between a CSV's bin frequencies and those PowerSpectrum gives a window of
#: 1/f_lowest taps: the CSV keeps ten significant digits (tapmc.paper._plotting.FigureTable)
LAYOUT_RTOL = 1e-6


#: parametric-bootstrap replicas of the band test (:func:`band_levels_test`): p resolved to
#: 1/(replicas + 1); its Monte Carlo standard deviation at p = 0.01 is about 0.002
BOOTSTRAP_REPLICAS = 2000
#: seed of the bootstrap's random numbers: the page made again from the same data says the
#: same p
BOOTSTRAP_SEED = 1995
#: the bootstrap stops once this many null statistics reach the observed one, p = this /
#: the replicas made (Besag & Clifford's sequential Monte Carlo p, valid as the full one): a
#: p far above 1 % is known after a few tens of replicas, to about 1/sqrt(20) = 22 % of itself
BOOTSTRAP_EXCEEDANCES = 20
#: series of the bootstrap synthesised at once (memory: this many x 4 x the window, floats),
#: and at most this many campaigns between two looks at the exceedances
BOOTSTRAP_CHUNK_SERIES = 2000
BOOTSTRAP_CHUNK_CAMPAIGNS = 50
#: bootstrap p values kept per process (:func:`band_levels_test`), keyed by everything they
#: depend on; a report asks the same spectra's p about 18 times (1.3 s each)
BOOTSTRAP_MEMO_SIZE = 64
_BOOTSTRAP_P_MEMO = {}


def _band(x, lowest):
    """Indices of the lowest (or highest) SPECTRUM_BAND of the bins ``x`` (increasing), at
    least one."""
    k = max(int(len(x) * SPECTRUM_BAND), 1)
    return np.arange(k) if lowest else np.arange(len(x) - k, len(x))


def _layout(series):
    """(window in taps, ordinates a bin, the relative covariance of one series' bin means:
    tapmc.fluctuations.binned_periodogram_layout) of a spectrum drawn by Fig. 3, a periodogram
    of 1/f_lowest taps, one sample a tap (its lowest bin holds the lowest ordinate alone), or
    None when the frequencies are not that binning's."""
    samples = int(round(1.0 / series.x[0]))
    frequency, counts, relative = binned_periodogram_layout(samples)
    n = len(series.x)
    if len(frequency) < n or not np.allclose(frequency[:n], series.x, rtol=LAYOUT_RTOL):
        return None
    return samples, counts[:n], relative[:n, :n]


def _bartlett(levels, seeds, shape, band_covariance):
    """Bartlett's statistic of one level for the band levels ``levels`` (..., spectra) of
    spectra averaged over ``seeds`` each, the spectra's common shape over the band ``shape``
    (..., bins) and one series' relative covariance of the band's bin means: each level a
    scaled chi-square of nu = 2 / (relative variance) dof (Satterthwaite)."""
    relative_variance = (np.einsum("...i,ij,...j->...", shape, band_covariance, shape)
                         / shape.sum(axis=-1) ** 2)
    nu = 2.0 * seeds / relative_variance[..., None]
    total = nu.sum(axis=-1)
    pooled = np.sum(nu * levels, axis=-1) / total
    statistic = np.sum(nu * np.log(pooled[..., None] / levels), axis=-1)
    dof = levels.shape[-1] - 1
    return statistic / (1.0 + (np.sum(1.0 / nu, axis=-1) - 1.0 / total) / (3.0 * dof))


def _band_statistic(band_powers, seeds, band_covariance):
    """Bartlett's statistic from the band's bin means (..., spectra, bins) of spectra averaged
    over ``seeds``; the shape, under the null hypothesis common, their seed-weighted mean."""
    shape = np.einsum("...eb,e->...b", band_powers, seeds) / seeds.sum()
    return _bartlett(band_powers.mean(axis=-1), seeds, shape, band_covariance)


def _null_statistics(pooled, counts, band, seeds, samples, band_covariance, replicas):
    """Bartlett's statistics, a chunk at a time, of ``replicas`` campaigns of the same layout
    (``seeds`` a spectrum, windows of ``samples`` taps) whose spectra are all the seed-weighted
    mean ``pooled`` of the measured ones (below the lowest frequency continued by the log-log
    slope of the band)."""
    frequency = binned_periodogram_layout(samples)[0][:len(pooled)]
    log_f, log_power = np.log(frequency[band]), np.log(pooled[band])
    # a band of one frequency (a quick campaign's short windows) has no slope: continued flat
    # (polyfit warned 'poorly conditioned' on every report and returned an arbitrary one)
    low_slope = float(np.polyfit(log_f, log_power, 1)[0]) if np.ptp(log_f) > 0 else 0.0
    rng = np.random.default_rng(BOOTSTRAP_SEED)
    per_campaign = int(seeds.sum())
    owner = np.repeat(np.arange(len(seeds)), seeds.astype(int))  # spectrum of every series
    chunk = max(1, min(BOOTSTRAP_CHUNK_SERIES // per_campaign, BOOTSTRAP_CHUNK_CAMPAIGNS))
    for start in range(0, replicas, chunk):
        n = min(chunk, replicas - start)
        x = shaped_gaussian_series(frequency, pooled, low_slope, samples, n * per_campaign, rng)
        bins = binned_periodograms(x, counts)[:, band].reshape(n, per_campaign, len(band))
        powers = np.stack([bins[:, owner == e].mean(axis=1) for e in range(len(seeds))], axis=1)
        yield _band_statistic(powers, seeds, band_covariance)


def _bootstrap_p(statistic, null_chunks, replicas):
    """Monte Carlo p of ``statistic`` from the null statistics ``null_chunks``: (1 + #{T* >=
    T}) / (1 + replicas), or, once BOOTSTRAP_EXCEEDANCES of them reach it, that number over
    the replicas made (sequential: Besag & Clifford, Biometrika 78, 301, 1991)."""
    made = reached = 0
    for null in null_chunks:
        made += len(null)
        reached += int(np.sum(null >= statistic))
        if reached >= BOOTSTRAP_EXCEEDANCES:
            return reached / made
    return (1.0 + reached) / (1.0 + replicas)


def band_levels_test(spectra, lowest=True, replicas=None):
    """Whether the spectra ``spectra`` (Series of bin frequency, mean power and seeds ``n``,
    all on Fig. 3's binning of one window) have one level over their lowest (or highest)
    SPECTRUM_BAND of frequencies: (Bartlett's statistic, its dof, p, the ratio of the largest
    band level to the smallest), or a reason (str) when it cannot be tested.

    Statistic. The band level of a spectrum, B = the mean of its band's bin means, is a
    weighted sum of periodogram ordinates, exponential variables correlated by the taper: its
    relative variance follows from the binning alone (ordinates a bin, their correlations,
    tapmc.fluctuations.binned_periodogram_layout) and the spectrum's shape over the band,
    divided by the seeds averaged. Under the null hypothesis every eps has the same spectrum,
    so that shape is the seed-weighted mean of all the spectra (not each noisy spectrum
    itself, whose low power would give itself a small error), and B is, to the Satterthwaite
    approximation, a scaled chi-square of nu = 2 / (relative variance) dof. Equal spectra are
    equal scales of such variables: Bartlett's statistic of homogeneity (the likelihood ratio
    with Bartlett's correction).

    p. The chi-square approximation of Bartlett's statistic (spectra - 1 dof) is conservative
    here (a band of a few correlated ordinates is no chi-square), so p is that of a parametric
    bootstrap: the statistic of ``replicas`` campaigns of the same layout (windows, seeds a
    spectrum) whose spectra are all the measured ones' seed-weighted mean, Gaussian series
    (tapmc.fluctuations.shaped_gaussian_series, the spectrum continued below the window's
    lowest frequency by the band's own log-log slope), p = (1 + #{T* >= T}) / (1 + replicas),
    the simulation stopped early once BOOTSTRAP_EXCEEDANCES replicas reach T
    (:func:`_bootstrap_p`). ``replicas`` None: BOOTSTRAP_REPLICAS (read when called); 0: the
    chi-square approximation.

    Why not the spectra's own errors: the seeds' sem (2 dof over 3 seeds) and one run's
    errors scaled by its own noisy power, taken as exact, made the earlier chi-square of the
    logarithms reject identical spectra at 1 % in 15-26 % of the campaign's layouts. Measured
    size and power (tests/python/studies/study_low_band_size.py, 10 eps, seeds
    3,1,1,1,3,1,1,1,1,3, 1000-tap windows, identical f^-alpha spectra, alpha 1 to 1.5):
    rejections at 1 % / 5 % of 300 null campaigns, this bootstrap 0.3 % / 4.3 % (alpha 1),
    0.7 % / 6.3 % (alpha 1.3), 0.3 % / 4.3 % (alpha 1.5) (+- 1.1 % on a 1 % rate); the
    chi-square approximation 0.3 % / 1.3 %, 0 % / 3.3 %, 0 % / 2.0 %; the earlier test
    15 % / 33 %, 20 % / 36 %, 26 % / 43 %. Power at 1 % (alpha 1.3, one spectrum 2, 4, 8
    times the others): bootstrap 7 %, 60 %, 92 %; chi-square approximation 4 %, 48 %, 87 %.
    On the committed campaign (Fig. 3's CSV) p is 0.004-0.006 over bootstrap seeds (4000
    replicas), 0.008 with the spectrum below the window taken flat: below 1 % either way."""
    layouts = [_layout(s) for s in spectra]
    if any(layout is None for layout in layouts):
        return ("the spectra's frequencies are not Fig. 3's binning of a periodogram: no model "
                "of their statistics")
    if len({len(s.x) for s in spectra}) > 1 or not all(
            np.allclose(s.x, spectra[0].x, rtol=LAYOUT_RTOL) for s in spectra):
        return "the spectra are on different frequencies (windows of different lengths)"
    samples, counts, relative = layouts[0]
    band = _band(spectra[0].x, lowest)
    powers = np.array([s.mean[band] for s in spectra])
    seeds = np.array([float(np.nanmin(s.n[band])) for s in spectra])
    if not (np.all(powers > 0) and np.all(seeds >= 1)):
        return "a spectrum without power or seeds in the band"
    band_covariance = relative[np.ix_(band, band)]
    statistic = float(_band_statistic(powers, seeds, band_covariance))
    dof = len(spectra) - 1
    replicas = BOOTSTRAP_REPLICAS if replicas is None else int(replicas)
    if replicas > 0:
        pooled = np.sum([n * s.mean for n, s in zip(seeds, spectra)], axis=0) / seeds.sum()
        # the bootstrap is a function of these alone (its seed fixed): a report evaluates the
        # register many times over (its tables of tolerances), each with the same spectra
        key = (statistic, pooled.tobytes(), seeds.tobytes(), samples, np.asarray(counts).tobytes(),
               np.asarray(band).tobytes(), band_covariance.tobytes(), replicas, BOOTSTRAP_SEED,
               BOOTSTRAP_EXCEEDANCES)
        if key not in _BOOTSTRAP_P_MEMO:
            if len(_BOOTSTRAP_P_MEMO) >= BOOTSTRAP_MEMO_SIZE:
                _BOOTSTRAP_P_MEMO.clear()
            _BOOTSTRAP_P_MEMO[key] = _bootstrap_p(statistic, _null_statistics(
                pooled, counts, band, seeds, samples, band_covariance, replicas), replicas)
        p = _BOOTSTRAP_P_MEMO[key]
    else:
        p = float(chi2_distribution.sf(statistic, dof))
    levels = powers.mean(axis=1)
    return statistic, dof, float(p), float(levels.max() / levels.min())


@statistic("spectrum_low_band")
def spectrum_low_band(data, claim):
    """Section III.A, "the effect of eps is noticeable only for the high frequencies": at the
    lowest frequencies the spectra of every eps coincide. Bartlett's test of one level for the
    mean power of each spectrum's lowest SPECTRUM_BAND of frequencies, their statistics from
    the periodogram's binning and the seeds averaged (:func:`band_levels_test`); the same over
    the highest band is shown beside it."""
    fig3 = data.result("fig3")
    if fig3 is None:
        return not_in_campaign("no Fig. 3 runs")
    spectra = [sp.power for _, sp in _spectra(fig3)]
    if len(spectra) < 3:
        return not_in_campaign("fewer than three spectra")
    low = band_levels_test(spectra, lowest=True)
    # shown beside: its p is tiny, the chi-square approximation tells it
    high = band_levels_test(spectra, lowest=False, replicas=0)
    if isinstance(low, str):
        return [Measure(undecided=low)]
    statistic, dof, p, span = low
    beside = ("" if isinstance(high, str) else
              f"; highest quarter: Bartlett {fmt(high[0])}, p = {high[2]:.2g}")
    return [Measure(statistic / dof, dof=dof, p_value=p,
                    shown=f"lowest quarter of the frequencies: Bartlett's statistic "
                          f"{fmt(statistic)} ({dof} dof) of one level for the {len(spectra)} "
                          f"eps, whose levels span a factor {span:.3g}{beside}")]


@statistic("sigma_intercept")
def sigma_intercept(data, claim):
    """Intercept of a free straight line through sigma_<Z> against sqrt(eps) (Fig. 3 bottom);
    ``params.about = "line"``: sigma_<Z> about each run's straight line over its last taps
    (fig3's detrended series) instead of the paper's X_SS."""
    suffix = "_detrended" if claim.params.get("about") == "line" else ""
    fig3 = data.result("fig3")
    if fig3 is None:
        return not_in_campaign("no Fig. 3 runs")
    b = fig3.sigma_detrended if suffix else fig3.sigma
    if b is None:
        return [Measure(undecided="Fig. 3's CSV was drawn without the detrended sigma_<Z>: "
                                  "draw Fig. 3 again from its runs")]
    m, s, n = value_triple(getattr(fig3, "intercept" + suffix))
    if not np.isfinite(m):
        return not_in_campaign("fewer than three eps: no free straight line")
    dof = len(b) - 2
    # a zero intercept means small against the smallest sigma measured
    effect = float(np.nanmin(b.mean))
    shown = None
    factor = data.run_error("Z:sigma" + suffix)[0]
    if factor != 1.0 and np.all(np.isfinite(b.err)) and np.all(b.err > 0):
        # the same weighted line, one-run sigmas with a realization's error (errors widened
        # by the reduced chi2 when it exceeds 1, as Fig. 3's own line: FitResult.errors)
        sem = np.where(b.n == 1, b.err * factor, b.err)
        m, s = weighted_line_fit(b.x, b.mean, sem)[:2]
        shown = f"{fmt(m, s)} ({one_seed_error_text(factor)})"
    return [Measure(m, s, dof if dof and dof >= 1 else None, effect=effect, shown=shown)]
