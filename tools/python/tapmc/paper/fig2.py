# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Fig. 2 of Philippe & Bideau: bottom packing fraction Phi_b against the number of taps t,
with what the fits of eqs. 3 and 4 can and cannot say.

F.B.C., three excitations (paper: eps = 5e-3, 5e-2, 0.15). Panel a: Phi_b in logarithmic
time; panel b: the same in linear time (the paper's two panels); the solid lines are the
simulation (mean over seeds, with the standard error as a band) and the dotted lines the
inverse-logarithmic fits of eq. 3 (``tapmc.laws.InverseLogLaw``) of the seed-averaged curves.
Panel c (not in the paper): <Z>(t) of the same runs with the fits of eq. 4
(``tapmc.laws.ZLaw``), which the paper proposes for <Z> (section III.A).

What the fits can say. Every parameter gets a 68 % profile-likelihood interval
(``FitResult.intervals``) and is *determined* only when that interval closes inside its
allowed range: section III.B says that at small eps "the triplet (X_inf, B, tau) is no longer
unique and depends strongly on the range of taps over which the data fitting is performed".
Each curve is also refitted over the tap ranges [1, T/4], [1, T/2], [1, T], [T/10, T]
(``tapmc.laws.range_refits``): the range deviation of a parameter is how many standard
deviations of a range's own profile separate its data from the value fitted on all taps.
Finally ln B is fitted against sqrt(eps) for eq. 3 and for eq. 4 (``tapmc.laws.
exponential_dependence``): section III.A's "B is consistent with an exponential dependence on
eps^(1/2)". The fit weights are the standard errors pooled over ``POOLED_SEM_WINDOW``
neighbouring taps (:func:`pooled_sem`).

Every statistic is a function of the arrays of a curve (:func:`analyse_curve`,
:func:`b_dependence`) and :func:`statistics` recomputes all of them from a figure CSV read with
``tapmc.paper._plotting.read_table``.

CSV panels:

* ``a``: ``eps=<e>`` (x = taps, Phi_b mean over seeds, sem, n seeds) and ``fit:eps=<e>``
  (eq. 3); ``c``: the same for <Z> and eq. 4.
* ``params``, per eps (x = eps): ``eps=<e>:<name>`` for the eq. 3 parameters X_inf, dX_inf, B,
  tau (mean = best value, sem = 1-sigma curvature error when determined, empty when not, n = 1
  determined / 0 not); ``eps=<e>:<name>:lo`` and ``:hi`` (the 68 % profile interval; empty on
  an open side, n = 1 when that side closes); ``eps=<e>:<name>:range_deviation`` (n = 1 when
  at most ``tapmc.laws.RANGE_Z_LIMIT``: consistent over the tap ranges) and
  ``eps=<e>:<name>:range_spread`` (max - min of the value over the ranges);
  ``eps=<e>:reduced_chi2`` (n = 1 when every parameter is determined). The eq. 4 parameters
  Z_inf, Z_0, B, tau likewise with the prefix ``eps=<e>:Z:`` (e.g. ``eps=0.05:Z:B:lo``,
  ``eps=0.05:Z:reduced_chi2``).
* ``B``: for ``<law>`` = ``eq3`` and ``eq4``: ``<law>:B`` (x = sqrt(eps), mean = B, n = 1
  determined), ``<law>:B:lo``, ``<law>:B:hi``; ``<law>:slope`` (d ln B / d sqrt(eps): mean,
  sem = curvature error, n = 1 determined), ``<law>:slope:lo``, ``<law>:slope:hi``,
  ``<law>:reduced_chi2`` (n = its degrees of freedom) and ``<law>:p_value`` (chi2 probability
  of the straight line; n = 1 when it passes, ``tapmc.laws.LINEARITY_P_MIN``, 0 when it fails
  or cannot be tested: fewer than three determined B, then empty).
"""

from __future__ import annotations

import numpy as np

from tapmc.laws import (InverseLogLaw, ZLaw, exponential_dependence, range_refits)

from . import _plotting as P
from . import _runs

NAME = "fig2"
#: Boundary conditions of the paper's Fig. 2.
BC = "fbc"
#: the paper's eps of Fig. 2.
PAPER_EPS = (5e-3, 5e-2, 0.15)
#: neighbouring taps whose squared standard errors are pooled into a fit weight: with few
#: seeds the standard error of one tap is itself uncertain by ~1/sqrt(2(n-1)) (100 % for two
#: seeds, where two crossing curves give a sem near 0 and a weight without bound); the
#: variance between seeds changes slowly with t, so 51 taps make it a stable weight.
POOLED_SEM_WINDOW = 51
#: the laws of the figure: eq. 3 for Phi_b (panel a), eq. 4 for <Z> (panel c); the CSV prefix
#: of their parameters.
LAWS = {"eq3": (InverseLogLaw, "phi_b", "a", ""), "eq4": (ZLaw, "Z", "c", "Z:")}


def runs(scale, seeds):
    """Constant-eps F.B.C. runs, one per eps of ``scale.fig2_eps`` and seed."""
    return [_runs.constant_eps_run(scale, BC, eps, s)
            for eps in scale.fig2_eps for s in _runs.seed_list(seeds)]


def curves(campaign, column="phi_b", bc=BC, eps_values=None):
    """dict eps -> (t, mean, sem, n) of a taps.dat column over the seeds of the campaign's
    constant-eps runs with boundary ``bc`` (all eps, or those in ``eps_values``)."""
    out = {}
    for eps, specs in _runs.constant_eps_groups(campaign, bc, eps_values).items():
        tables = [_runs.taps_table(campaign, s) for s in specs]
        length = min(len(t["step"]) for t in tables)
        t = tables[0]["step"][:length]
        mean, sem, n = P.seed_stats([tab[column][:length] for tab in tables])
        out[eps] = (t, mean, sem, n)
    return out


def pooled_sem(sem, window=POOLED_SEM_WINDOW):
    """sqrt of the running mean of sem^2 over ``window`` neighbouring points (fewer at the
    ends): a fit weight that a chance agreement of the seeds at one tap does not blow up.
    None when a sem is missing (one seed: the fit then uses the scatter of its residuals)."""
    sem = np.asarray(sem, dtype=float)
    window = int(window)
    if window < 1:
        raise ValueError(f"window = {window} must be an integer >= 1")
    if sem.size == 0 or not np.all(np.isfinite(sem)) or not np.any(sem > 0):
        return None
    half = window // 2
    c = np.concatenate([[0.0], np.cumsum(sem ** 2)])
    i = np.arange(sem.size)
    lo, hi = np.maximum(i - half, 0), np.minimum(i + half + 1, sem.size)
    return np.sqrt((c[hi] - c[lo]) / (hi - lo))


def fit_curve(t, mean, sem, law=None):
    """Eq. 3 (or ``law``) fitted to a seed-averaged curve, weighted by :func:`pooled_sem`."""
    law = InverseLogLaw() if law is None else law
    return law.fit(t, mean, sigma=pooled_sem(sem))


def analyse_curve(t, mean, sem, law=None, ranges=None):
    """Eq. 3 (or ``law``, e.g. ``ZLaw()`` for <Z>) fitted to a seed-averaged curve and refitted
    over the tap ranges (``tapmc.laws.range_refits``): a ``RangeRefits`` whose ``reference``
    is the fit of all taps with its profile intervals."""
    law = InverseLogLaw() if law is None else law
    return range_refits(law, t, mean, pooled_sem(sem), ranges)


def b_dependence(refits, name="B"):
    """ln B against sqrt(eps) (``tapmc.laws.exponential_dependence``) from a dict eps ->
    ``RangeRefits`` (or ``FitResult``) of one law."""
    eps = sorted(refits)
    fits = [getattr(refits[e], "reference", refits[e]) for e in eps]
    return exponential_dependence(np.sqrt(eps), [f.params[name] for f in fits],
                                  [f.intervals[name].lo for f in fits],
                                  [f.intervals[name].hi for f in fits])


def statistics(table):
    """Every statistic of the figure from its CSV (``tapmc.paper._plotting.read_table``):
    dict law tag ('eq3', 'eq4') -> {"curves": dict eps -> RangeRefits, "B":
    ExponentialDependence}; a law whose curves are not in the table is left out."""
    out = {}
    for tag, (law, _, panel, _) in LAWS.items():
        refits = {}
        for (pan, series), d in table.items():
            if pan == panel and series.startswith("eps=") and ":" not in series:
                refits[float(series[4:])] = analyse_curve(d["x"], d["mean"], d["sem"], law())
        if refits:
            out[tag] = {"curves": refits, "B": b_dependence(refits)}
    return out


def refit_table(table):
    """A ``FigureTable`` with the curves of ``table`` (a figure CSV read with
    ``tapmc.paper._plotting.read_table``), their fit curves and every ``params`` and ``B`` row
    recomputed from them by :func:`statistics`: a report drawn before these statistics existed gets them from
    its own committed curves (``tapmc-paper report --from-data --refit``)."""
    out = P.FigureTable()
    stats = statistics(table)
    fits = {(LAWS[tag][2], f"fit:eps={P.fmt_eps(eps)}"): refits.reference
            for tag, st in stats.items() for eps, refits in st["curves"].items()}
    for (panel, series), d in table.items():
        if panel in ("params", "B"):
            continue
        fit = fits.get((panel, series))
        mean = d["mean"] if fit is None else fit(d["x"])  # the fit curve of the new fit
        out.add(panel, series, d["x"], mean, d["sem"], d["n"])
    for tag, st in stats.items():
        prefix = LAWS[tag][3]
        for eps, refits in sorted(st["curves"].items()):
            add_curve_rows(out, eps, refits, prefix)
        add_b_rows(out, tag, st["curves"], st["B"])
    return out


def _bound(value):
    return (value, 1) if np.isfinite(value) else (np.nan, 0)


def add_curve_rows(table, eps, refits, prefix=""):
    """The params rows of one fitted curve (module text) into a ``FigureTable``."""
    fit = refits.reference
    tag = f"eps={P.fmt_eps(eps)}:{prefix}"
    errors = fit.errors
    deviation, consistent, spread = refits.deviation, refits.consistent, refits.spread
    for name, value in fit.params.items():
        iv = fit.intervals[name]
        table.add("params", f"{tag}{name}", eps, value, errors[name], int(iv.determined))
        for side, bound in (("lo", iv.lo), ("hi", iv.hi)):
            b, closed = _bound(bound)
            table.add("params", f"{tag}{name}:{side}", eps, b, None, closed)
        table.add("params", f"{tag}{name}:range_deviation", eps, deviation[name], None,
                  int(consistent[name]))
        table.add("params", f"{tag}{name}:range_spread", eps, spread[name], None,
                  sum(f is not None for f in refits.fits))
    table.add("params", f"{tag}reduced_chi2", eps, fit.reduced_chi2, None,
              int(not fit.undetermined_params))


def add_b_rows(table, tag, refits, dependence):
    """The ``B`` panel rows of one law (module text) into a ``FigureTable``."""
    for eps in sorted(refits):
        fit = refits[eps].reference
        iv = fit.intervals["B"]
        x = float(np.sqrt(eps))
        table.add("B", f"{tag}:B", x, iv.value, None, int(iv.determined))
        for side, bound in (("lo", iv.lo), ("hi", iv.hi)):
            b, closed = _bound(bound)
            table.add("B", f"{tag}:B:{side}", x, b, None, closed)
    iv = dependence.slope_interval
    if iv is not None:
        err = float(np.sqrt(dependence.fit.covariance[1, 1]))
        table.add("B", f"{tag}:slope", 0.0, iv.value, err if iv.determined else np.nan,
                  int(iv.determined))
        for side, bound in (("lo", iv.lo), ("hi", iv.hi)):
            b, closed = _bound(bound)
            table.add("B", f"{tag}:slope:{side}", 0.0, b, None, closed)
    table.add("B", f"{tag}:reduced_chi2", 0.0, dependence.reduced_chi2, None,
              dependence.dof)
    table.add("B", f"{tag}:p_value", 0.0, dependence.p_value, None,
              int(bool(dependence.linear)))


def paper_eps(available, targets=PAPER_EPS):
    """For each of the paper's eps, the nearest available eps (in log): the campaign may hold
    more F.B.C. runs (Figs. 6-8) than Fig. 2 shows."""
    available = sorted(available)
    return sorted({min(available, key=lambda e: abs(np.log(e / t))) for t in targets})


def _fit_label(fit):
    missing = fit.undetermined_params
    return "" if not missing else f" ({', '.join(missing)} undetermined)"


def draw(campaign, out_dir, eps_values=None):
    """Draw Fig. 2 from the campaign's F.B.C. constant-eps runs: those of ``eps_values``, by
    default the campaign's ``fig2_eps`` when its scale is known
    (``tapmc.paper._runs.campaign_scale``), else the eps nearest to the paper's 5e-3, 5e-2
    and 0.15."""
    png, csv = P.figure_paths(out_dir, NAME)
    specs = _runs.select(campaign, "const_", bc=BC)
    available = {s.variables["eps"] for s in specs}
    if eps_values is None and available:
        scale = _runs.campaign_scale(campaign)
        eps_values = scale.fig2_eps if scale is not None else paper_eps(available)
    table = P.FigureTable()
    fig, (ax_log, ax_lin, ax_z) = P.new_figure(3, 1)
    colors = {}
    for tag, (law, column, panel, prefix) in LAWS.items():
        data = curves(campaign, column, BC, eps_values)
        refits = {}
        for eps, (t, mean, sem, n) in data.items():
            label = f"eps = {P.fmt_eps(eps)}"
            refits[eps] = analyse_curve(t, mean, sem, law())
            fit = refits[eps].reference
            table.add(panel, f"eps={P.fmt_eps(eps)}", t, mean, sem, n)
            tfit = np.unique(np.concatenate([np.geomspace(1, max(t[-1], 1), 200),
                                             t[t > 0][:1]]))
            yfit = fit(tfit)
            table.add(panel, f"fit:eps={P.fmt_eps(eps)}", tfit, yfit, None, 0)
            add_curve_rows(table, eps, refits[eps], prefix)
            pos = t > 0
            axes = (ax_log, ax_lin) if tag == "eq3" else (ax_z,)
            for ax in axes:
                x = t[pos] if ax is not ax_lin else t
                line = P.errorbars(ax, x, mean[pos] if ax is not ax_lin else mean,
                                   sem[pos] if ax is not ax_lin else sem,
                                   label=label + _fit_label(fit), color=colors.get(eps))
                colors.setdefault(eps, line.get_color())
                ax.plot(tfit, yfit, ":", color=colors[eps])
        if refits:
            add_b_rows(table, tag, refits, b_dependence(refits))
    for ax in (ax_log, ax_z):
        ax.set_xscale("log")
    for ax in (ax_log, ax_lin, ax_z):
        ax.set_xlabel("t (taps)")
    ax_log.set_ylabel(r"$\Phi_b$")
    ax_lin.set_ylabel(r"$\Phi_b$")
    ax_z.set_ylabel(r"$\langle Z\rangle$")
    ax_log.legend(fontsize=7, title="F.B.C.; dotted: eq. 3 fits", title_fontsize=7)
    ax_z.legend(fontsize=7, title="dotted: eq. 4 fits", title_fontsize=7)
    return P.write_figure(fig, png, table, csv)
