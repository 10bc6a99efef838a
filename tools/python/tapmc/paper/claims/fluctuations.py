# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Statistics of the fluctuations (section III.A, Fig. 3): the spectral slopes of <Z>, their
spread over eps, and sigma_<Z>'s intercept at sqrt(eps) = 0."""

from __future__ import annotations

import math

import numpy as np

from tapmc.stats import mean_dof, weighted_polyfit

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


#: Resamplings of the spectra that propagate their sem to ``spectrum_eps_spread``.
SPECTRUM_RESAMPLINGS = 400


@statistic("spectrum_eps_spread")
def spectrum_eps_spread(data, claim):
    """Spread over eps of log10 P(f) in the highest-frequency band minus that in the lowest
    band (section III.A: eps is noticeable only at high frequencies)."""
    fig3 = data.result("fig3")
    if fig3 is None:
        return not_in_campaign("no Fig. 3 runs")
    curves = [(sp.power.x, sp.power.mean, sp.power.err, sp.power.n) for _, sp in _spectra(fig3)]
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
        # the same weighted line, one-run sigmas with a realization's error
        sem = np.where(b.n == 1, b.err * factor, b.err)
        coef, cov, _ = weighted_polyfit(b.x, b.mean, sem, 1)
        m, s = float(coef[0]), float(math.sqrt(cov[0, 0]))
        shown = f"{fmt(m, s)} ({one_seed_error_text(factor)})"
    return [Measure(m, s, dof if dof and dof >= 1 else None, effect=effect, shown=shown)]
