# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Fig. 3 of Philippe & Bideau: fluctuations of <Z> in the steady state (section III.A).

Top: the power spectrum of <Z> - <Z>_SS against the frequency (1/taps), one curve per eps
(``tapmc.fluctuations.PowerSpectrum`` of each seed's steady segment, averaged over seeds, with
the log-log slope of each seed averaged over seeds; paper: slope 1 to 1.5 in magnitude).
Bottom: sigma_<Z> (standard deviation of <Z> over the steady segment) against sqrt(eps), mean
and standard error over seeds, with the proportional law sigma = k sqrt(eps) of the paper
(``tapmc.fluctuations.sigma_scaling``) dotted; open squares: sigma_<Z> about each run's
straight line over the same segment (``SteadyState(detrend="linear")``), for runs still
compacting at their end, whose drift the paper's definition counts as fluctuation.

The runs are the constant-eps P.B.C. runs of Fig. 4 (``scale.steady_eps``): the steady
segment is the last quarter of the taps (paper: the last 1000 of 4000).

CSV panels: ``a`` (series ``eps=<eps>``: x = frequency, mean/sem of the power), ``b``
(series ``sigma_Z``, ``sigma_Z_detrended``: x = sqrt(eps); ``fit:k sqrt(eps)``), ``params``
(``eps=<eps>:slope`` with x = eps; ``k`` and ``k_reduced_chi2`` of the proportional fit;
``intercept`` of a free straight line, which is zero for a proportional law, with its error in
the sem column; ``intercept_detrended``, the same for the detrended sigma).

The sem columns are over seeds. For an eps with one seed (n = 1; the paper's protocol, one
run per point) they are that run's own errors instead: the power's from the periodogram's
statistics (``PowerSpectrum.power_error``), the slope's error from the log-log fit of its
spectrum, and sigma_<Z>'s from batch means of the squared deviations over the steady
segment (successive taps are correlated), so that one run per eps still carries error bars.

:func:`analyse` returns a :class:`Fig3Result` (its ``save``/``load`` are the CSV), :func:`plot`
draws one, :func:`draw` does both into a folder.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tapmc.fluctuations import PowerSpectrum, SteadyState, sigma_scaling
from tapmc.laws import StraightLine

from . import _plotting as P
from . import _runs, _steady_state
from ._results import FigureResult, Series, Value
from ._steady_state import BC, sigma_error_one_run, steady_last

NAME = "fig3"


def runs(scale, seeds):
    """Constant-eps P.B.C. runs, one per eps of ``scale.steady_eps`` and seed (shared with
    Fig. 4: ``_steady_state.runs``)."""
    return _steady_state.runs(scale, seeds)


def series_by_eps(campaign, column, bc=BC):
    """dict eps -> list over seeds of the per-tap column (tap 0 excluded)."""
    groups = _runs.constant_eps_groups(campaign, bc)
    return {eps: [_runs.taps_table(campaign, s)[column][1:] for s in specs]
            for eps, specs in groups.items()}


def per_eps(campaign, column="Z", bc=BC):
    """Spectra, slopes and sigma per eps: dict eps -> dict with 'frequency', 'power' (mean,
    sem), 'slope' (mean, sem, n), 'sigma' and 'sigma_detrended' (mean, sem, n)."""
    out = {}
    for eps, series in series_by_eps(campaign, column, bc).items():
        length = min(len(s) for s in series)
        last = steady_last(length)
        spectra = [PowerSpectrum(s[:length], steady_from=length - last).compute()
                   for s in series]
        nbins = min(len(sp.frequency) for sp in spectra)
        freq = spectra[0].frequency[:nbins]
        pmean, psem, pn = P.seed_stats([sp.power[:nbins] for sp in spectra])
        slope = tuple(v[0] for v in P.seed_stats([[sp.slope] for sp in spectra]))
        sig = {}
        for detrend in SteadyState.DETRENDS:
            sig[detrend] = tuple(v[0] for v in P.seed_stats(
                [[SteadyState(s[:length], last=last, detrend=detrend).compute().std]
                 for s in series]))
        if len(series) == 1:  # one run: its own errors (module docstring)
            psem = spectra[0].power_error[:nbins]
            slope = (slope[0], spectra[0].slope_error, 1)
            sig = {d: (v[0], sigma_error_one_run(series[0][:length], last, detrend=d), 1)
                   for d, v in sig.items()}
        out[eps] = {"frequency": freq, "power": (pmean, psem, pn), "last": last,
                    "slope": slope, "slope_error_single": spectra[0].slope_error,
                    "sigma": sig["constant"], "sigma_detrended": sig["linear"]}
    return out


#: the sigma series of panel b: (result field, CSV series, suffix of its intercept row)
SIGMA_SERIES = (("sigma", "sigma_Z", ""), ("sigma_detrended", "sigma_Z_detrended", "_detrended"))


@dataclass(frozen=True)
class Spectrum:
    """The power spectrum of one eps (panel a) and its log-log slope."""

    eps: float
    power: Series
    slope: Value


@dataclass(frozen=True)
class Fig3Result(FigureResult):
    """The numbers of Fig. 3 (CSV schema: module text)."""

    #: eps -> :class:`Spectrum`
    spectra: dict
    #: sigma_<Z> against sqrt(eps), and about each run's straight line (None in CSVs drawn
    #: before it)
    sigma: Series
    sigma_detrended: Series = None
    #: the proportional law k sqrt(eps) (two eps or more): its curve, k, its reduced chi2
    law_curve: Series = None
    k: Value = None
    k_reduced_chi2: Value = None
    #: intercepts of a free straight line through each sigma series (three eps or more)
    intercept: Value = None
    intercept_detrended: Value = None

    def rows(self):
        out = []
        for sp in self.spectra.values():
            label = f"eps={P.fmt_eps(sp.eps)}"
            out += [("a", label, sp.power), ("params", f"{label}:slope", sp.slope)]
        for field, series, suffix in SIGMA_SERIES:
            if getattr(self, field) is None:
                continue
            out.append(("b", series, getattr(self, field)))
            if field == "sigma" and self.k is not None:
                out += [("b", "fit:k sqrt(eps)", self.law_curve), ("params", "k", self.k),
                        ("params", "k_reduced_chi2", self.k_reduced_chi2)]
            if getattr(self, "intercept" + suffix) is not None:
                out.append(("params", "intercept" + suffix, getattr(self, "intercept" + suffix)))
        return out

    @classmethod
    def from_rows(cls, rows):
        spectra = {}
        for _, label in rows.keys("a"):
            slope = rows.take_value("params", f"{label}:slope")
            spectra[slope.x] = Spectrum(slope.x, rows.take("a", label), slope)
        sigma = rows.take("b", "sigma_Z")
        optional = {name: rows.take_value("params", name)
                    for name in ("intercept", "intercept_detrended")
                    if rows.has("params", name)}
        law = rows.together(("params", "k"), ("params", "k_reduced_chi2"),
                            ("b", "fit:k sqrt(eps)"))
        if law:
            optional.update(k=rows.take_value("params", "k"),
                            k_reduced_chi2=rows.take_value("params", "k_reduced_chi2"))
        return cls(spectra, sigma, rows.take_optional("b", "sigma_Z_detrended"),
                   rows.take("b", "fit:k sqrt(eps)") if law else None, **optional)


def _sigma_weights(sigma):
    """Fit weights of a sigma series: its errors when every point has one, else None."""
    return sigma.err if np.all(np.isfinite(sigma.err)) and np.all(sigma.err > 0) else None


def analyse(campaign, column="Z", bc=BC):
    """Fig. 3 from the campaign's constant-eps runs of ``bc`` (:func:`per_eps`), with the
    proportional law and the free lines' intercepts of panel b."""
    data = per_eps(campaign, column, bc)
    spectra = {eps: Spectrum(eps, Series.of(d["frequency"], *d["power"]),
                             Value.of_stats(eps, d["slope"])) for eps, d in data.items()}
    eps = np.array(sorted(data))
    sq = np.sqrt(eps)
    sigma = {field: Series.of(sq, *(np.array([data[e][field][i] for e in eps]) for i in range(3)))
             for field, _, _ in SIGMA_SERIES}
    fitted = {}
    if len(eps) >= 2:
        law = sigma_scaling(sq, sigma["sigma"].mean, _sigma_weights(sigma["sigma"]))
        xs = np.linspace(0, sq.max() * 1.05, 50)
        fitted.update(law_curve=Series.of(xs, law(xs), None, 0),
                      k=Value(0.0, law.params["k"], law.errors["k"], len(eps)),
                      k_reduced_chi2=Value(0.0, law.reduced_chi2, np.nan, len(eps)))
    if len(eps) >= 3:
        for field, _, suffix in SIGMA_SERIES:
            line = StraightLine().fit(sq, sigma[field].mean, _sigma_weights(sigma[field]))
            name = list(line.params)[0]
            fitted["intercept" + suffix] = Value(0.0, line.params[name], line.errors[name],
                                                 len(eps))
    return Fig3Result(spectra, sigma["sigma"], sigma["sigma_detrended"], **fitted)


def plot(result, settings=None):
    """The figure of a :class:`Fig3Result` (drawing only)."""
    fig, (ax_s, ax_sig) = P.new_figure(2, 1)
    for eps, sp in result.spectra.items():
        ax_s.errorbar(sp.power.x, sp.power.mean, yerr=np.nan_to_num(sp.power.err), marker="o",
                      ms=3, ls="-", lw=0.8, capsize=0,
                      label=f"eps = {P.fmt_eps(eps)}, slope {sp.slope.value:.2f}")
    ax_s.set_xscale("log")
    ax_s.set_yscale("log")
    ax_s.set_xlabel("frequency (1/taps)")
    ax_s.set_ylabel(r"power of $\langle Z\rangle - \langle Z\rangle_{SS}$")
    P.legend(ax_s, fontsize=7, title="P.B.C.", title_fontsize=7)
    for field, label in (("sigma", r"$\sigma_{\langle Z\rangle}$"),
                         ("sigma_detrended",
                          r"$\sigma_{\langle Z\rangle}$ about each run's straight line")):
        sigma = getattr(result, field)
        if sigma is None:
            continue
        ax_sig.errorbar(sigma.x, sigma.mean, yerr=np.nan_to_num(sigma.err), marker="s",
                        ls="none", color="k", capsize=2, label=label,
                        mfc="k" if field == "sigma" else "none")
        if field == "sigma" and result.law_curve is not None:
            ax_sig.plot(result.law_curve.x, result.law_curve.mean, "k:",
                        label=r"$k\,\varepsilon^{1/2}$")
    ax_sig.set_xlim(left=0)
    ax_sig.set_ylim(bottom=0)
    ax_sig.set_xlabel(r"$\varepsilon^{1/2}$")
    ax_sig.set_ylabel(r"$\sigma_{\langle Z\rangle}$")
    P.legend(ax_sig, fontsize=8)
    return P.finish_figure(fig, settings, P.plotted_seeds(result))


def draw(campaign, out_dir):
    """Fig. 3's PNG and CSV in ``out_dir``; returns their paths."""
    return analyse(campaign).save_with_png(
        plot, out_dir, NAME, P.figure_settings(campaign, figure_runs(campaign)))


def figure_runs(campaign):
    """The runs Fig. 3 draws: the constant-eps P.B.C. runs."""
    return [s for group in _runs.constant_eps_groups(campaign, BC).values() for s in group]
