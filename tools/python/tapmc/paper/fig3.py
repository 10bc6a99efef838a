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
"""

from __future__ import annotations

import numpy as np

from tapmc.fluctuations import DEFAULT_BATCHES, PowerSpectrum, SteadyState, sigma_scaling
from tapmc.laws import StraightLine

from . import _plotting as P
from . import _runs, _steady_state
from ._steady_state import BC, steady_last

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


def sigma_error_one_run(x, last, batches=DEFAULT_BATCHES, detrend="constant"):
    """Error of sigma_X over the last ``last`` taps of one run: batch means of the squared
    deviations (from the segment's mean, or its straight line: ``detrend``) give the error of
    sigma_X^2, propagated to sigma_X."""
    dev2 = SteadyState(x, last=last, detrend=detrend).deviations() ** 2
    size = len(dev2) // batches
    if size < 1 or batches < 2:
        return np.nan
    means = dev2[: size * batches].reshape(batches, size).mean(axis=1)
    var_err = float(np.std(means, ddof=1) / np.sqrt(batches))
    sigma = float(np.sqrt(dev2.mean()))
    return var_err / (2.0 * sigma) if sigma > 0 else np.nan


def analyse(campaign, column="Z", bc=BC):
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


def draw(campaign, out_dir):
    png, csv = P.figure_paths(out_dir, NAME)
    data = analyse(campaign)
    table = P.FigureTable()
    fig, (ax_s, ax_sig) = P.new_figure(2, 1)
    for eps, d in data.items():
        pmean, psem, pn = d["power"]
        s_mean, s_sem, s_n = d["slope"]
        label = f"eps = {P.fmt_eps(eps)}, slope {s_mean:.2f}"
        ax_s.errorbar(d["frequency"], pmean, yerr=np.nan_to_num(psem), marker="o", ms=3,
                      ls="-", lw=0.8, capsize=0, label=label)
        table.add("a", f"eps={P.fmt_eps(eps)}", d["frequency"], pmean, psem, pn)
        table.add("params", f"eps={P.fmt_eps(eps)}:slope", eps, s_mean, s_sem, s_n)
    ax_s.set_xscale("log")
    ax_s.set_yscale("log")
    ax_s.set_xlabel("frequency (1/taps)")
    ax_s.set_ylabel(r"power of $\langle Z\rangle - \langle Z\rangle_{SS}$")
    ax_s.legend(fontsize=7, title="P.B.C.", title_fontsize=7)

    eps = np.array(sorted(data))
    sq = np.sqrt(eps)
    for key, series, marker, label in (
            ("sigma", "sigma_Z", "s", r"$\sigma_{\langle Z\rangle}$"),
            ("sigma_detrended", "sigma_Z_detrended", "s",
             r"$\sigma_{\langle Z\rangle}$ about each run's straight line")):
        smean = np.array([data[e][key][0] for e in eps])
        ssem = np.array([data[e][key][1] for e in eps])
        sn = np.array([data[e][key][2] for e in eps])
        table.add("b", series, sq, smean, ssem, sn)
        weights = ssem if np.all(np.isfinite(ssem)) and np.all(ssem > 0) else None
        ax_sig.errorbar(sq, smean, yerr=np.nan_to_num(ssem), marker=marker, ls="none",
                        color="k", capsize=2, label=label,
                        mfc="k" if key == "sigma" else "none")
        suffix = "" if key == "sigma" else "_detrended"
        if key == "sigma" and len(eps) >= 2:
            prop = sigma_scaling(sq, smean, weights)
            xs = np.linspace(0, sq.max() * 1.05, 50)
            ax_sig.plot(xs, prop(xs), "k:", label=r"$k\,\varepsilon^{1/2}$")
            table.add("b", "fit:k sqrt(eps)", xs, prop(xs), None, 0)
            table.add("params", "k", 0.0, prop.params["k"], prop.errors["k"], len(eps))
            table.add("params", "k_reduced_chi2", 0.0, prop.reduced_chi2, None, len(eps))
        if len(eps) >= 3:
            line = StraightLine().fit(sq, smean, weights)
            intercept = list(line.params)[0]
            table.add("params", "intercept" + suffix, 0.0, line.params[intercept],
                      line.errors[intercept], len(eps))
    ax_sig.set_xlim(left=0)
    ax_sig.set_ylim(bottom=0)
    ax_sig.set_xlabel(r"$\varepsilon^{1/2}$")
    ax_sig.set_ylabel(r"$\sigma_{\langle Z\rangle}$")
    ax_sig.legend(fontsize=8)
    return P.write_figure(fig, png, table, csv)
