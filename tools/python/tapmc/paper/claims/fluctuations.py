# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Statistics of the fluctuations (section III.A, Fig. 3): the spectral slopes of <Z>, their
spread over eps, and sigma_<Z>'s intercept at sqrt(eps) = 0."""

from __future__ import annotations

import math

import numpy as np

from tapmc.stats import mean_dof, weighted_polyfit

from .common import (eps_of, eps_series, figure_param, not_in_campaign, one_seed_error_text,
                     steady_dof)
from .measure import Measure, fmt
from .registry import statistic


@statistic("spectral_slopes")
def spectral_slopes(data, claim):
    fig = data.figure("fig3")
    if fig is None:
        return not_in_campaign("no Fig. 3 runs")
    out = []
    for series in fig.series("params"):
        if series.endswith(":slope"):
            m, s, n = fig.param(series)
            out.append((eps_of(series),
                        Measure(-m, s, steady_dof(n, s), label=f"eps = {eps_of(series):g}",
                                shown=fmt(m, s))))
    return [m for _, m in sorted(out, key=lambda p: p[0])] or not_in_campaign("no spectrum")


#: Fraction of the frequencies (lowest, highest) compared by ``spectrum_eps_spread``.
SPECTRUM_BAND = 0.25


#: Resamplings of the spectra that propagate their sem to ``spectrum_eps_spread``.
SPECTRUM_RESAMPLINGS = 400


@statistic("spectrum_eps_spread")
def spectrum_eps_spread(data, claim):
    """Spread over eps of log10 P(f) in the highest-frequency band minus that in the lowest
    band (section III.A: eps is noticeable only at high frequencies)."""
    fig = data.figure("fig3")
    if fig is None:
        return not_in_campaign("no Fig. 3 runs")
    curves = [fig.get("a", s) for _, s in eps_series(fig, "a")]
    if len(curves) < 3:
        return not_in_campaign("fewer than three spectra")
    rng = np.random.default_rng(12345)

    def spread(samples):
        low, high = [], []
        for f, logp in samples:
            k = max(int(len(f) * SPECTRUM_BAND), 1)
            order = np.argsort(f)
            low.append(np.mean(logp[order[:k]]))
            high.append(np.mean(logp[order[-k:]]))
        return float(np.std(high, ddof=1) - np.std(low, ddof=1))

    def logs(f, p):
        ok = (f > 0) & (p > 0)
        return f[ok], np.log10(p[ok])

    base = spread([logs(f, p) for f, p, _, _ in curves])
    if not all(np.all(np.isfinite(s[(f > 0) & (p > 0)])) for f, p, s, _ in curves):
        return [Measure(base, undecided="one realization: the spectra have no error bars")]
    seeds = int(min(c[3].min() for c in curves))
    draws = []
    for _ in range(SPECTRUM_RESAMPLINGS):
        sample = []
        for f, p, s, _ in curves:
            if seeds == 1:
                # one run per eps: its bins are Gamma means of m = (P / err)^2 effective
                # periodogram ordinates (tapmc.fluctuations.PowerSpectrum.power_error)
                with np.errstate(divide="ignore"):
                    m = np.where(s > 0, (p / s) ** 2, np.inf)
                finite = np.isfinite(m) & (m > 0)
                factor = np.ones_like(p)
                factor[finite] = rng.gamma(m[finite], 1.0 / m[finite])
                noisy = p * factor
            else:
                noisy = p + s * rng.standard_normal(p.shape)
            sample.append(logs(f, np.where(noisy > 0, noisy, p)))
        draws.append(spread(sample))
    # one run: the errors follow from the estimator's known distribution, not from a sample
    # of realizations, so the verdict's quantile is the normal one (t with infinite dof)
    dof = math.inf if seeds == 1 else mean_dof(seeds)
    shown = f"{fmt(base, float(np.std(draws, ddof=1)))}" + (
        " (one run per eps: the periodogram's own errors)" if seeds == 1 else "")
    return [Measure(base, float(np.std(draws, ddof=1)), dof, shown=shown)]


@statistic("sigma_intercept")
def sigma_intercept(data, claim):
    """Intercept of a free straight line through sigma_<Z> against sqrt(eps) (Fig. 3 bottom);
    ``params.about = "line"``: sigma_<Z> about each run's straight line over its last taps
    (fig3's detrended series) instead of the paper's X_SS."""
    suffix = "_detrended" if claim.params.get("about") == "line" else ""
    fig = data.figure("fig3")
    absent = "fewer than three eps: no free straight line"
    if suffix and fig is not None and fig.get("b", "sigma_Z_detrended") is None:
        return [Measure(undecided="Fig. 3's CSV was drawn without the detrended sigma_<Z>: "
                                  "draw Fig. 3 again from its runs")]
    found, missing = figure_param(data, "fig3", "intercept" + suffix, absent)
    if missing:
        return missing
    fig, m, s, n = found
    b = fig.get("b", "sigma_Z" + suffix)
    dof = len(b[0]) - 2 if b is not None else None
    # a zero intercept means small against the smallest sigma measured
    effect = float(np.nanmin(b[1])) if b is not None else None
    shown = None
    factor = data.run_error("Z:sigma" + suffix)[0]
    if factor != 1.0 and b is not None and np.all(np.isfinite(b[2])) and np.all(b[2] > 0):
        # the same weighted line, one-run sigmas with a realization's error
        sem = np.where(b[3] == 1, b[2] * factor, b[2])
        coef, cov, _ = weighted_polyfit(b[0], b[1], sem, 1)
        m, s = float(coef[0]), float(math.sqrt(cov[0, 0]))
        shown = f"{fmt(m, s)} ({one_seed_error_text(factor)})"
    return [Measure(m, s, dof if dof and dof >= 1 else None, effect=effect, shown=shown)]
