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
  at most ``tapmc.laws.RANGE_Z_LIMIT``: consistent over the tap ranges; 0 when beyond it, or
  nan when no range had a fit to compare) and
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

:func:`analyse` returns a :class:`Fig2Result` (its ``save``/``load`` are the CSV), :func:`plot`
draws one, :func:`draw` does both into a folder; :func:`refit_table` gives the result
recomputed from a CSV's curves, every curve first.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tapmc.laws import (InverseLogLaw, ZLaw, exponential_dependence, range_refits)

from . import _plotting as P
from . import _runs
from ._results import Estimate, FigureResult, Series, Value, estimates

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


def _bound(value):
    return (value, 1) if np.isfinite(value) else (np.nan, 0)


def _sides(x, iv):
    """{'lo': Value, 'hi': Value} of an Interval at ``x`` (empty on an open side, n = 1 when
    that side closes)."""
    out = {}
    for side, bound in (("lo", iv.lo), ("hi", iv.hi)):
        b, closed = _bound(bound)
        out[side] = Value(x, b, np.nan, closed)
    return out


#: the rows that qualify each parameter of a curve's fit, in the CSV's order
CURVE_PARTS = ("lo", "hi", "range_deviation", "range_spread")


@dataclass(frozen=True)
class CurveFit:
    """One seed-averaged curve at one eps, its fitted law and what the fit can say."""

    eps: float
    data: Series
    #: the law fitted to all taps, evaluated for the figure
    curve: Series
    #: name -> Estimate (value, curvature error, n = 1 determined) with CURVE_PARTS
    params: dict
    #: n = 1 when every parameter is determined
    reduced_chi2: Value

    @property
    def label(self):
        return f"eps={P.fmt_eps(self.eps)}"

    def curve_rows(self, panel):
        return [(panel, self.label, self.data), (panel, f"fit:{self.label}", self.curve)]

    def param_rows(self, prefix):
        tag = f"{self.label}:{prefix}"
        return ([row for name, est in self.params.items()
                 for row in est.rows("params", tag + name)]
                + [("params", f"{tag}reduced_chi2", self.reduced_chi2)])

    @classmethod
    def from_rows(cls, rows, panel, label, law, prefix):
        data, curve = rows.take(panel, label), rows.take(panel, f"fit:{label}")
        params = estimates(rows, "params", f"{label}:{prefix}", law.names, CURVE_PARTS)
        chi2 = rows.take_value("params", f"{label}:{prefix}reduced_chi2")
        return cls(chi2.x, data, curve, params, chi2)

    @classmethod
    def of(cls, eps, data, curve, refits):
        """From a ``RangeRefits`` (:func:`analyse_curve`)."""
        fit = refits.reference
        deviation, consistent, spread = refits.deviation, refits.consistent, refits.spread
        params = {}
        for name, value in fit.params.items():
            iv = fit.intervals[name]
            parts = _sides(eps, iv)
            parts["range_deviation"] = Value(eps, deviation[name], np.nan,
                                             int(bool(consistent[name])))
            parts["range_spread"] = Value(eps, spread[name], np.nan,
                                          sum(f is not None for f in refits.fits))
            params[name] = Estimate(Value(eps, value, fit.errors[name], int(iv.determined)),
                                    parts)
        return cls(eps, data, curve, params, Value(eps, fit.reduced_chi2, np.nan,
                                                   int(not fit.undetermined_params)))


@dataclass(frozen=True)
class BDependence:
    """ln B against sqrt(eps) for one law (panel ``B``, module text)."""

    tag: str
    #: B per eps against sqrt(eps) (n = 1 determined) and its interval's sides
    B: Series
    B_lo: Series
    B_hi: Series
    #: d ln B / d sqrt(eps) with its interval (None: fewer than two determined B)
    slope: Estimate
    reduced_chi2: Value
    p_value: Value

    def rows(self):
        out = []
        for i in range(len(self.B)):
            out += [("B", f"{self.tag}:B", Value.of_series(self.B, i)),
                    ("B", f"{self.tag}:B:lo", Value.of_series(self.B_lo, i)),
                    ("B", f"{self.tag}:B:hi", Value.of_series(self.B_hi, i))]
        if self.slope is not None:
            out += self.slope.rows("B", f"{self.tag}:slope")
        return out + [("B", f"{self.tag}:reduced_chi2", self.reduced_chi2),
                      ("B", f"{self.tag}:p_value", self.p_value)]

    @classmethod
    def from_rows(cls, rows, tag):
        slope = (Estimate.from_rows(rows, "B", f"{tag}:slope", ("lo", "hi"))
                 if rows.has("B", f"{tag}:slope") else None)
        return cls(tag, rows.take("B", f"{tag}:B"), rows.take("B", f"{tag}:B:lo"),
                   rows.take("B", f"{tag}:B:hi"), slope,
                   rows.take_value("B", f"{tag}:reduced_chi2"),
                   rows.take_value("B", f"{tag}:p_value"))

    @classmethod
    def of(cls, tag, refits, dependence):
        """From a dict eps -> RangeRefits and its ``ExponentialDependence``."""
        eps = sorted(refits)
        intervals = [refits[e].reference.intervals["B"] for e in eps]
        x = np.sqrt(eps)
        columns = [Series.of(x, [iv.value for iv in intervals], None,
                             [int(iv.determined) for iv in intervals])]
        for side in ("lo", "hi"):
            sides = [_sides(0.0, iv)[side] for iv in intervals]
            columns.append(Series.of(x, [v.value for v in sides], None, [v.n for v in sides]))
        iv = dependence.slope_interval
        slope = None
        if iv is not None:
            err = float(np.sqrt(dependence.fit.covariance[1, 1]))
            slope = Estimate(Value(0.0, iv.value, err if iv.determined else np.nan,
                                   int(iv.determined)), _sides(0.0, iv))
        return cls(tag, *columns, slope,
                   Value(0.0, dependence.reduced_chi2, np.nan, dependence.dof),
                   Value(0.0, dependence.p_value, np.nan, int(bool(dependence.linear))))


@dataclass(frozen=True)
class LawFits:
    """One law of the figure (``eq3`` for Phi_b, ``eq4`` for <Z>) on every eps."""

    tag: str
    #: eps -> :class:`CurveFit`
    curves: dict
    B: BDependence

    @property
    def panel(self):
        return LAWS[self.tag][2]

    @property
    def prefix(self):
        return LAWS[self.tag][3]


@dataclass(frozen=True)
class Fig2Result(FigureResult):
    """The numbers of Fig. 2 (CSV schema: module text)."""

    #: tag ('eq3', 'eq4') -> :class:`LawFits` of the laws whose curves the figure has
    laws: dict
    #: the layout of a refitted CSV (:func:`refit_table`): every curve first, then the
    #: statistics; a drawn CSV has each curve's statistics after it
    curves_first: bool = False

    def rows(self):
        laws = self.laws.values()
        if self.curves_first:
            return ([row for law in laws for c in law.curves.values()
                     for row in c.curve_rows(law.panel)]
                    + [row for law in laws for row in
                       [r for c in law.curves.values() for r in c.param_rows(law.prefix)]
                       + law.B.rows()])
        return [row for law in laws for row in
                [r for c in law.curves.values()
                 for r in c.curve_rows(law.panel) + c.param_rows(law.prefix)]
                + law.B.rows()]

    @classmethod
    def from_rows(cls, rows):
        order = [panel for panel, _ in rows.keys()]
        curves_first = "params" in order and order.index("params") > 2
        laws = {}
        for tag, (law, _, panel, prefix) in LAWS.items():
            labels = [s for _, s in rows.keys(panel) if not s.startswith("fit:")]
            if not labels:
                continue
            fits = [CurveFit.from_rows(rows, panel, label, law, prefix) for label in labels]
            laws[tag] = LawFits(tag, {c.eps: c for c in fits}, BDependence.from_rows(rows, tag))
        return cls(laws, curves_first)


def _fit_curve_points(t):
    """Taps at which a fitted law is drawn: 200 log-spaced from 1 to the last tap, and the
    first tap > 0."""
    return np.unique(np.concatenate([np.geomspace(1, max(t[-1], 1), 200), t[t > 0][:1]]))


def analyse(campaign, eps_values=None):
    """Fig. 2 from the campaign's F.B.C. constant-eps runs: those of ``eps_values``, by
    default the campaign's ``fig2_eps`` when its scale is known
    (``tapmc.paper._runs.campaign_scale``), else the eps nearest to the paper's 5e-3, 5e-2
    and 0.15."""
    specs = _runs.select(campaign, "const_", bc=BC)
    available = {s.variables["eps"] for s in specs}
    if eps_values is None and available:
        scale = _runs.campaign_scale(campaign)
        eps_values = scale.fig2_eps if scale is not None else paper_eps(available)
    laws = {}
    for tag, (law, column, _, _) in LAWS.items():
        refits, fits = {}, {}
        for eps, (t, mean, sem, n) in curves(campaign, column, BC, eps_values).items():
            refits[eps] = analyse_curve(t, mean, sem, law())
            tfit = _fit_curve_points(t)
            fits[eps] = CurveFit.of(eps, Series.of(t, mean, sem, n),
                                    Series.of(tfit, refits[eps].reference(tfit), None, 0),
                                    refits[eps])
        if refits:
            laws[tag] = LawFits(tag, fits, BDependence.of(tag, refits, b_dependence(refits)))
    return Fig2Result(laws)


def refit_table(table):
    """A ``FigureTable`` with the curves of ``table`` (a figure CSV read with
    ``tapmc.paper._plotting.read_table``), their fit curves and every ``params`` and ``B`` row
    recomputed from them by :func:`statistics`: a report drawn before these statistics existed
    gets them from its own committed curves (``tapmc-paper report --from-data --refit``)."""
    laws = {}
    for tag, st in statistics(table).items():
        panel = LAWS[tag][2]
        fits = {}
        for eps, refits in sorted(st["curves"].items()):
            label = f"eps={P.fmt_eps(eps)}"
            data, old = table[(panel, label)], table[(panel, f"fit:{label}")]
            fits[eps] = CurveFit.of(
                eps, Series.of(data["x"], data["mean"], data["sem"], data["n"]),
                Series.of(old["x"], refits.reference(old["x"]), old["sem"], old["n"]), refits)
        laws[tag] = LawFits(tag, fits, BDependence.of(tag, st["curves"], st["B"]))
    return Fig2Result(laws, curves_first=True).table()


def paper_eps(available, targets=PAPER_EPS):
    """For each of the paper's eps, the nearest available eps (in log): the campaign may hold
    more F.B.C. runs (Figs. 6-8) than Fig. 2 shows."""
    available = sorted(available)
    return sorted({min(available, key=lambda e: abs(np.log(e / t))) for t in targets})


def _fit_label(fit):
    missing = [name for name, est in fit.params.items() if not est.value.n]
    return "" if not missing else f" ({', '.join(missing)} undetermined)"


def plot(result, settings=None):
    """The figure of a :class:`Fig2Result` (drawing only): Phi_b on logarithmic and linear
    time, and <Z> (eq. 4) where the result has its curves."""
    has_z = any(law.curves for tag, law in result.laws.items() if tag != "eq3")
    fig, axes = P.new_figure(2 + has_z, 1)
    ax_log, ax_lin = axes[:2]
    panels = {"eq3": (ax_log, ax_lin), "other": tuple(axes[2:])}
    colors = {}
    for tag, law in result.laws.items():
        for eps, fit in law.curves.items():
            label = f"eps = {P.fmt_eps(eps)}" + _fit_label(fit)
            t, pos = fit.data.x, fit.data.x > 0
            for ax in panels["eq3" if tag == "eq3" else "other"]:
                keep = slice(None) if ax is ax_lin else pos
                line = P.errorbars(ax, t[keep], fit.data.mean[keep], fit.data.err[keep],
                                   label=label, color=colors.get(eps))
                colors.setdefault(eps, line.get_color())
                ax.plot(fit.curve.x, fit.curve.mean, ":", color=colors[eps])
    for ax in axes:
        ax.set_xlabel("t (taps)")
        if ax is not ax_lin:
            ax.set_xscale("log")
    ax_log.set_ylabel(r"$\Phi_b$")
    ax_lin.set_ylabel(r"$\Phi_b$")
    for ax in (ax_log, ax_lin):
        P.legend(ax, fontsize=7, title="F.B.C.; dotted: eq. 3 fits", title_fontsize=7)
    for ax in panels["other"]:
        ax.set_ylabel(r"$\langle Z\rangle$")
        P.legend(ax, fontsize=7, title="F.B.C.; dotted: eq. 4 fits", title_fontsize=7)
    return P.finish_figure(fig, settings, P.plotted_seeds(result))


def figure_runs(campaign, eps_values=None):
    """The runs Fig. 2 draws: the F.B.C. constant-eps runs of :func:`analyse`'s eps."""
    specs = _runs.select(campaign, "const_", bc=BC)
    if eps_values is None and specs:
        scale = _runs.campaign_scale(campaign)
        eps_values = (scale.fig2_eps if scale is not None
                      else paper_eps({s.variables["eps"] for s in specs}))
    return [s for group in _runs.constant_eps_groups(campaign, BC, eps_values).values()
            for s in group]


def draw(campaign, out_dir, eps_values=None):
    """Fig. 2's PNG and CSV in ``out_dir`` (:func:`analyse`); returns their paths."""
    return analyse(campaign, eps_values).save_with_png(
        plot, out_dir, NAME, P.figure_settings(campaign, figure_runs(campaign, eps_values)))
