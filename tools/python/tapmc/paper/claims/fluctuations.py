# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Statistics of the fluctuations (section III.A, Fig. 3): the spectral slopes of <Z>, the
spectra of every eps at the lowest frequencies, and sigma_<Z>'s intercept at sqrt(eps) = 0."""

from __future__ import annotations

import math

import numpy as np
from scipy.stats import chi2 as chi2_distribution

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


def _band_level(f, power, err, lowest):
    """(log10 of the mean power over the lowest (or highest) SPECTRUM_BAND of the frequencies,
    its error from the bins' own errors, bins independent): the logarithm of the band's mean,
    not the mean of the bins' logarithms, which their few periodogram ordinates at low f
    would bias; on a logarithm the levels' differences grow with their ratio."""
    ok = (f > 0) & (power > 0)
    f, power, err = f[ok], power[ok], err[ok]
    k = max(int(len(f) * SPECTRUM_BAND), 1)
    order = np.argsort(f)
    pick = order[:k] if lowest else order[-k:]
    mean = float(np.mean(power[pick]))
    return math.log10(mean), float(np.sqrt(np.sum(err[pick] ** 2)) / k) / (mean * math.log(10))


def _one_level(levels):
    """(chi2, dof, p) of one level through the band means ``levels`` [(mean, err)]."""
    y, e = (np.array(v) for v in zip(*levels))
    w = 1.0 / e ** 2
    chi = float(np.sum(w * (y - np.sum(w * y) / np.sum(w)) ** 2))
    return chi, len(y) - 1, float(chi2_distribution.sf(chi, len(y) - 1))


@statistic("spectrum_low_band")
def spectrum_low_band(data, claim):
    """Section III.A, "the effect of eps is noticeable only for the high frequencies": at the
    lowest frequencies the spectra of every eps coincide. The chi-square of one level through
    the log10 of the mean power of each spectrum's lowest SPECTRUM_BAND of frequencies (one
    run per eps: the periodogram's own errors; several seeds: their sem); the same over the
    highest band is shown beside it."""
    fig3 = data.result("fig3")
    if fig3 is None:
        return not_in_campaign("no Fig. 3 runs")
    spectra = [sp.power for _, sp in _spectra(fig3)]
    if len(spectra) < 3:
        return not_in_campaign("fewer than three spectra")
    low = [_band_level(s.x, s.mean, s.err, True) for s in spectra]
    high = [_band_level(s.x, s.mean, s.err, False) for s in spectra]
    if not all(np.isfinite(e) and e > 0 for _, e in low + high):
        return [Measure(undecided="one realization: the spectra have no error bars")]
    chi, dof, p = _one_level(low)
    chi_high, _, p_high = _one_level(high)
    span = 10 ** (max(m for m, _ in low) - min(m for m, _ in low))
    return [Measure(chi / dof, dof=dof, p_value=p,
                    shown=f"lowest quarter of the frequencies: chi2 {fmt(chi)} ({dof} dof) of "
                          f"one level for the {len(low)} eps, whose levels span a factor "
                          f"{span:.3g}; highest quarter: chi2 {fmt(chi_high)}, p = "
                          f"{p_high:.2g}")]


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
