# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Fig. 5 of Philippe & Bideau: ageing of the time-correlation function A(t, t_W) of <Z>
(section III.C, eqs. 5-6), and the scaling variable that collapses it.

P.B.C., ``scale.ageing_eps``; realizations share the initial packing and differ by the Monte
Carlo seed (the paper averaged 10). Top: A(t, t_W) (``tapmc.ageing.Ageing``, averaged over the
realizations, with its standard error) for the waiting times ``scale.ageing_waiting_times``.
Bottom: the collapse, as the paper draws it: the curves rescaled, A / r^kappa against
t / r^mu with r = t_W / t_ref (t_ref the geometric mean of the waiting times), and the one
eq. 6, A_inf (1 - 1/(1 + B_A ln(1 + s/tau_A))), of the collapse (dotted). The paper sees
"obviously a scaling law" without naming its variable: mu and kappa are fitted with eq. 6 on
all curves at once (``tapmc.ageing.scaling_collapse``), with 68 % profile-likelihood intervals
and a leave-one-curve-out jackknife, and the collapse is also searched in time alone (kappa =
0). The reduced chi2 of the collapse is compared with that of one eq. 6 in t for every curve
(no rescaling, ``Ageing.collapse``). The bottom panel draws the time-and-amplitude collapse,
or the time-only one when the data do not determine mu with the amplitude free (the two
exponents then trade off along one direction). :func:`scaling_statistics` recomputes every
collapse statistic from the CSV's panel ``a``.

CSV panels: ``a`` (series ``tw=<t_W>``: x = t, mean A, sem, n realizations; drawn on the top
panel), ``b`` (the drawn collapse: ``tw=<t_W>`` with x = t / r^mu, mean = A / r^kappa, sem
likewise, and ``eq6``, its eq. 6 on the rescaled variable), ``params``:

* ``tw=<t_W>:<name>`` (x = t_W): eq. 6 fitted to one curve, mean = value, sem = 1-sigma error
  (bootstrap over realizations, ``Ageing.fit``) when the parameter is determined (empty when
  not), n = 1 determined / 0 not; ``:lo`` and ``:hi``: its 68 % profile interval, each closed
  side widened to that error (the delays of a curve are correlated: the profile alone is too
  narrow; a side widened beyond the allowed range opens), empty on an open side (n = 1 when
  that side closes); determined means both sides closed after widening;
* ``collapse:<name>``, ``collapse:reduced_chi2`` (and the same number as
  ``unscaled:reduced_chi2``): one eq. 6 in t for all waiting times, the curves unscaled;
* ``scaling:<name>`` for A_inf, B_A, tau_A (at t_ref), mu and kappa (sem = the larger
  half-width of the interval, n = 1 when the profile closes), with ``:lo``, ``:hi`` (the 68 %
  interval of ``ScalingCollapse.interval``: the profile widened to the jackknife and
  bootstrap errors, since the delays of a curve are correlated), ``:jackknife`` (the
  leave-one-curve-out standard error) and ``:bootstrap`` (the standard deviation over
  ``BOOTSTRAP_RESAMPLES`` resamples of the realizations; empty with fewer than
  ``tapmc.ageing.MIN_BOOTSTRAP_REALIZATIONS``), ``scaling:t_ref``, ``scaling:reduced_chi2``:
  the time-and-amplitude collapse; ``scaling:dispersion`` (the law-free collapse quality,
  ``tapmc.ageing.collapse_dispersion``, at the fitted exponents: about 1 for curves that are
  one within their errors), ``scaling:dispersion_mu``, ``scaling:dispersion_kappa`` and
  ``scaling:dispersion_min`` (the exponents that minimise it, and its value there);
  ``scaling_time:...`` the same for the collapse in time alone (no kappa);
  ``unscaled:dispersion`` the dispersion of the curves as they are;
* ``drawn:mu``, ``drawn:kappa``: the exponents of panel b (n = 1 for the time-and-amplitude
  collapse, 0 for the time-only one);
* ``scaling_test:needed``: the realizations the test of the drawn collapse across
  realizations needs (``tapmc.ageing.ScalingRealizationTest``); with that many or more,
  ``scaling_test:T2`` (Hotelling's T^2), ``:dof``, ``:p_value``, ``:bins`` (of delays, over
  all curves) and ``:realizations``; ``scaling_test_long:T2``, ``:dof``, ``:p_value``: the
  same over the delays t >= ``LONG_DELAYS`` alone. The test needs the realizations
  themselves, so a report refitted from a CSV keeps these rows as drawn;
* ``eq6_test:needed`` (x = 0): the realizations eq. 6's test on one curve needs; with that
  many, per waiting time (x = t_W) ``eq6_test:tw=<t_W>:T2``, ``:dof``, ``:p_value``,
  ``:bins``: eq. 6 on that curve alone tested across the realizations
  (``Ageing.eq6_test``, every delay), ``eq6_test_long:tw=<t_W>:...`` the same over the delays
  t >= ``LONG_DELAYS`` only, and ``drift_share:tw=<t_W>``: the share of the curve that
  is the square of the mean displacement (``Ageing.drift_share``); a refit keeps them as
  drawn.

:func:`analyse` returns a :class:`Fig5Result` (its ``save``/``load`` are the CSV), :func:`plot`
draws one, :func:`draw` does both into a folder; the ``add_*_rows`` functions write parts of
it into a ``FigureTable`` for :func:`refit_table`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tapmc.ageing import Ageing, scaling_collapse, scaling_test_min_realizations
from tapmc.laws import AgeingLaw

from . import _plotting as P
from . import _runs
from ._results import (Estimate, FigureResult, Series, Value, add_rows, estimates,
                       values)

NAME = "fig5"
BC = "pbc"


def runs(scale, seeds):
    """One ageing realization (in.ageing) per seed."""
    return [_runs.ageing_run(scale, BC, scale.ageing_eps, s) for s in _runs.seed_list(seeds)]


def ageing(campaign, waiting_times=None, bc=BC):
    """The Ageing result of the campaign's ageing runs of ``bc``."""
    specs = sorted(_runs.select(campaign, "ageing_", bc=bc), key=lambda s: s.seed)
    if not specs:
        raise ValueError(f"campaign {campaign.directory} has no ageing {bc} run")
    series = [_runs.taps_table(campaign, s)["Z"] for s in specs]
    length = min(len(z) for z in series)
    z = np.array([s[:length] for s in series])
    if waiting_times is None:
        scale = _runs.campaign_scale(campaign)
        if scale is not None and scale.ageing_taps == length - 1:
            waiting_times = scale.ageing_waiting_times
        else:
            waiting_times = default_waiting_times(length - 1)
    return Ageing(z, waiting_times).compute(), len(specs)


#: the paper's waiting times as fractions of a 4000-tap realization, for runs of no preset
#: scale (runs of a preset use its ``ageing_waiting_times``).
PAPER_WAITING_FRACTIONS = (10 / 4000, 30 / 4000, 100 / 4000, 300 / 4000, 1000 / 4000)


def default_waiting_times(taps):
    return sorted({max(1, int(round(f * taps))) for f in PAPER_WAITING_FRACTIONS})


def _curves(result):
    """(t_W, t, A, sem) per waiting time from an Ageing result."""
    out = []
    for tw in sorted(result.A):
        t = np.asarray(result.t[tw] if isinstance(result.t, dict) else result.t, dtype=float)
        a = np.asarray(result.A[tw], dtype=float)
        sem = result.A_sem[tw] if getattr(result, "A_sem", None) is not None else None
        sem = np.full(a.shape, np.nan) if sem is None else np.asarray(sem, dtype=float)
        n = min(len(t), len(a))
        out.append((tw, t[:n], a[:n], sem[:n]))
    return out


def curves_from_table(table):
    """dict t_W -> (t, A, sem) of the ``tw=<t_W>`` curves of a Fig. 5 CSV's panel ``a``
    (``tapmc.paper._plotting.read_table``)."""
    return {float(series[3:]): (d["x"], d["mean"], d["sem"])
            for (panel, series), d in table.items()
            if panel == "a" and series.startswith("tw=") and ":" not in series}


def scaling_statistics(curves):
    """The two collapses of the module text from a dict t_W -> (t, A, sem) (waiting times 0
    are left out: they have no scale): dict "scaling" (time and amplitude) and
    "scaling_time" (time only) -> ``tapmc.ageing.ScalingCollapse`` (intervals from the profile
    and the jackknife over curves; no realizations, no bootstrap)."""
    curves = {tw: c for tw, c in curves.items() if tw > 0}
    return {"scaling": scaling_collapse(curves, fit_amplitude=True),
            "scaling_time": scaling_collapse(curves, fit_amplitude=False)}


#: resamples of the realizations for the bootstrap errors of the collapse exponents: a
#: standard deviation from 40 resamples is known to 11 %, enough to widen an interval, and
#: each resample refits the collapse on every delay of every curve.
BOOTSTRAP_RESAMPLES = 40


def _scaling_of(result):
    """The collapses of an ``Ageing`` result, with bootstrap errors over its realizations."""
    return {"scaling": result.scaling(True, bootstrap=BOOTSTRAP_RESAMPLES),
            "scaling_time": result.scaling(False, bootstrap=BOOTSTRAP_RESAMPLES)}


def drawn_collapse(stats):
    """The collapse of the bottom panel: time and amplitude when mu is determined there,
    else time only."""
    full = stats["scaling"]
    return full if full.interval("mu").determined else stats["scaling_time"]


def _bound(value):
    return (value, 1) if np.isfinite(value) else (np.nan, 0)


#: names of eq. 6's parameters, and of a collapse's (eq. 6 at t_ref and the exponents)
AGEING_NAMES = tuple(AgeingLaw.names)
SCALING_NAMES = AGEING_NAMES + ("mu", "kappa")
#: the rows that qualify a fitted parameter: its interval, and for a collapse its spreads
FIT_PARTS = ("lo", "hi")
COLLAPSE_PARTS = ("lo", "hi", "jackknife", "bootstrap")
#: the two collapses (time and amplitude; time alone) and their law-free dispersions
COLLAPSE_TAGS = ("scaling", "scaling_time")
DISPERSIONS = ("dispersion", "dispersion_mu", "dispersion_kappa", "dispersion_min")
#: the statistics of the tests across realizations, in the CSV's order
SCALING_TEST_NAMES = ("needed", "T2", "dof", "p_value", "bins", "realizations")
LONG_TEST_NAMES = ("T2", "dof", "p_value")
EQ6_TEST_NAMES = ("T2", "dof", "p_value", "bins")


def _estimate_rows(tag, fit):
    """Rows ``<tag>:<name>`` (and its parts) of a dict name -> Estimate."""
    return [row for name, est in fit.items() for row in est.rows("params", f"{tag}:{name}")]


def fit_estimates(x, fit, collapse=None):
    """name -> :class:`Estimate` of a FitResult at abscissa ``x`` (module text): the value,
    its error (n = 1 determined) and its interval ``lo``, ``hi``; for a ``ScalingCollapse``
    the intervals are its widened ones and ``jackknife``, ``bootstrap`` follow."""
    out = {}
    errors = fit.errors
    for name, value in fit.params.items():
        if collapse is None:
            # the delays of a curve are correlated: the profile alone is too narrow; each
            # closed side widened to the error of the fit (bootstrap over realizations)
            iv = fit.intervals[name].widened(errors[name])
        else:
            iv = collapse.interval(name)
        err = max(iv.half_widths) if iv.determined else np.nan
        if collapse is None and iv.determined:
            err = errors[name] if np.isfinite(errors[name]) else err
        parts = {}
        for side, bound in (("lo", iv.lo), ("hi", iv.hi)):
            b, closed = _bound(bound)
            parts[side] = Value(x, b, np.nan, closed)
        if collapse is not None:
            jk = collapse.jackknife[name]
            bs = np.nan if collapse.bootstrap is None else collapse.bootstrap[name]
            parts["jackknife"] = Value(x, jk, np.nan, int(np.isfinite(jk)))
            parts["bootstrap"] = Value(x, bs, np.nan, int(np.isfinite(bs)))
        out[name] = Estimate(Value(x, value, err, int(iv.determined)), parts)
    return out


@dataclass(frozen=True)
class Collapse:
    """One collapse of the curves (``scaling``: time and amplitude; ``scaling_time``)."""

    tag: str
    t_ref: Value
    reduced_chi2: Value
    #: name (SCALING_NAMES) -> Estimate with COLLAPSE_PARTS
    params: dict
    #: name (DISPERSIONS) -> Value
    dispersion: dict

    def rows(self):
        return ([("params", f"{self.tag}:t_ref", self.t_ref),
                 ("params", f"{self.tag}:reduced_chi2", self.reduced_chi2)]
                + _estimate_rows(self.tag, self.params)
                + [("params", f"{self.tag}:{name}", v) for name, v in self.dispersion.items()])

    @classmethod
    def from_rows(cls, rows, tag):
        return cls(tag, rows.take_value("params", f"{tag}:t_ref"),
                   rows.take_value("params", f"{tag}:reduced_chi2"),
                   estimates(rows, "params", f"{tag}:", SCALING_NAMES, COLLAPSE_PARTS),
                   values(rows, "params", f"{tag}:", DISPERSIONS))

    @classmethod
    def of(cls, tag, col):
        """From a ``tapmc.ageing.ScalingCollapse``."""
        mu_free, kappa_free = col.dispersion_exponents
        return cls(tag, Value(0.0, col.t_ref), Value(0.0, col.reduced_chi2, np.nan,
                                                    int(not col.fit.undetermined_params)),
                   fit_estimates(0.0, col.fit, col),
                   {"dispersion": Value(0.0, col.dispersion()),
                    "dispersion_mu": Value(0.0, mu_free),
                    "dispersion_kappa": Value(0.0, kappa_free),
                    "dispersion_min": Value(0.0, col.dispersion(mu_free, kappa_free))})


@dataclass(frozen=True)
class Scaling:
    """The collapses of the curves and the one panel b draws (module text)."""

    unscaled_reduced_chi2: Value
    #: tag (COLLAPSE_TAGS) -> :class:`Collapse`
    collapses: dict
    unscaled_dispersion: Value
    #: the exponents of panel b (n = 1: the time-and-amplitude collapse, 0: time alone)
    drawn_mu: Value
    drawn_kappa: Value
    #: t_W -> the rescaled curve of panel b
    rescaled: dict

    @property
    def drawn(self):
        """The :class:`Collapse` panel b draws."""
        return self.collapses["scaling" if self.drawn_mu.n else "scaling_time"]

    def rows(self):
        return ([("params", "unscaled:reduced_chi2", self.unscaled_reduced_chi2)]
                + [row for col in self.collapses.values() for row in col.rows()]
                + [("params", "unscaled:dispersion", self.unscaled_dispersion),
                   ("params", "drawn:mu", self.drawn_mu),
                   ("params", "drawn:kappa", self.drawn_kappa)]
                + [("b", f"tw={tw:g}", s) for tw, s in self.rescaled.items()])

    @classmethod
    def from_rows(cls, rows):
        if not rows.has("params", "unscaled:reduced_chi2"):
            return None
        unscaled = rows.take_value("params", "unscaled:reduced_chi2")
        collapses = {tag: Collapse.from_rows(rows, tag) for tag in COLLAPSE_TAGS}
        dispersion = rows.take_value("params", "unscaled:dispersion")
        mu, kappa = rows.take_value("params", "drawn:mu"), rows.take_value("params",
                                                                           "drawn:kappa")
        rescaled = {float(s[len("tw="):]): rows.take("b", s) for _, s in rows.keys("b")
                    if s.startswith("tw=")}
        return cls(unscaled, collapses, dispersion, mu, kappa, rescaled)


def scaling_rows(stats, curves, nreal):
    """(:class:`Scaling`, the drawn ``ScalingCollapse``) from :func:`scaling_statistics` (or
    ``Ageing.scaling``) results and the curves t_W -> (t, A, sem)."""
    shown = drawn_collapse(stats)
    full = shown is stats["scaling"]
    rescaled = {}
    for tw, (t, a, sem) in curves.items():
        if tw <= 0:
            continue
        s, y = shown.rescale(tw, t, a)
        rescaled[tw] = Series.of(s, y, shown.rescale(tw, t, sem)[1], nreal)
    scaling = Scaling(Value(0.0, stats["scaling"].unscaled_reduced_chi2),
                      {tag: Collapse.of(tag, col) for tag, col in stats.items()},
                      Value(0.0, stats["scaling"].dispersion(0.0, 0.0)),
                      Value(0.0, shown.mu, np.nan, int(full)),
                      Value(0.0, shown.kappa, np.nan, int(full)), rescaled)
    return scaling, shown


def add_scaling_rows(table, stats, curves, nreal):
    """The collapse rows of the module text (:func:`scaling_rows`) into a ``FigureTable``;
    returns the drawn collapse and dict t_W -> (rescaled t, rescaled A)."""
    scaling, shown = scaling_rows(stats, curves, nreal)
    add_rows(table, scaling.rows())
    return shown, {tw: (s.x, s.mean) for tw, s in scaling.rescaled.items()}


#: the first delay of the tests over long delays alone (the collapse's, eq. 6's): the paper's
#: Fig. 5 draws t on a linear axis to 3000 taps, where the delays below 100 fill 3 % of its
#: width
LONG_DELAYS = 100


def scaling_tests(result, shown, full):
    """(name -> Value of ``scaling_test:``, of ``scaling_test_long:``, the test or None): the
    drawn collapse ``shown`` (time and amplitude when ``full``) tested across the
    realizations of the ``Ageing`` ``result``, started from its fit."""
    curves = [tw for tw in result.waiting_times if tw > 0]
    needed = scaling_test_min_realizations(len(curves), full)
    test_values = {"needed": Value(0.0, needed)}
    if result.n_realizations < needed:
        return test_values, {}, None
    test = result.scaling_test(full, start=shown.fit.params)
    test_values.update({name: Value(0.0, value) for name, value in (
        ("T2", test.chi2), ("dof", test.dof), ("p_value", test.p_value),
        ("bins", sum(test.bins.values())), ("realizations", test.realizations))})
    try:
        long = result.scaling_test(full, start=shown.fit.params, t_min=LONG_DELAYS)
    except ValueError:                  # runs too short for bins of delays >= LONG_DELAYS
        return test_values, {}, test
    return test_values, {name: Value(0.0, value) for name, value in (
        ("T2", long.chi2), ("dof", long.dof), ("p_value", long.p_value))}, test


def add_test_rows(table, result, shown, full):
    """The ``scaling_test:`` rows of the module text (:func:`scaling_tests`) into a
    ``FigureTable``; returns the test (None with too few realizations)."""
    test_values, long_values, test = scaling_tests(result, shown, full)
    add_rows(table, _test_rows(test_values, long_values))
    return test


def _test_rows(test_values, long_values):
    return ([("params", f"scaling_test:{k}", v) for k, v in test_values.items()]
            + [("params", f"scaling_test_long:{k}", v) for k, v in long_values.items()])


#: realizations eq. 6's test on one curve needs (tapmc.laws.RealizationLawTest: bins > its
#: parameters, realizations > bins)
EQ6_TEST_MIN_REALIZATIONS = len(AgeingLaw.names) + 2


@dataclass(frozen=True)
class Eq6Test:
    """Eq. 6 on one curve tested across the realizations (module text)."""

    tw: float
    drift_share: Value
    #: name (EQ6_TEST_NAMES) -> Value, every delay and the long delays alone (may be empty)
    every_delay: dict
    long_delays: dict

    def rows(self):
        tw = f"tw={self.tw:g}"
        return ([("params", f"drift_share:{tw}", self.drift_share)]
                + [("params", f"eq6_test:{tw}:{k}", v) for k, v in self.every_delay.items()]
                + [("params", f"eq6_test_long:{tw}:{k}", v) for k, v in self.long_delays.items()])

    @classmethod
    def from_rows(cls, rows, tw):
        label = f"tw={tw:g}"
        return cls(tw, rows.take_value("params", f"drift_share:{label}"),
                   values(rows, "params", f"eq6_test:{label}:", EQ6_TEST_NAMES),
                   values(rows, "params", f"eq6_test_long:{label}:", EQ6_TEST_NAMES))


def eq6_tests(result):
    """(the ``eq6_test:needed`` Value, t_W -> :class:`Eq6Test`) of the ``Ageing`` ``result``:
    each curve of t_W > 0 alone, when the realizations suffice."""
    needed = Value(0.0, EQ6_TEST_MIN_REALIZATIONS)
    if result.n_realizations < EQ6_TEST_MIN_REALIZATIONS:
        return needed, {}
    tests = {}
    for tw in result.waiting_times:
        if tw <= 0:
            continue
        found = {}
        for tag, t_min in (("eq6_test", 1), ("eq6_test_long", LONG_DELAYS)):
            try:
                test = result.eq6_test(tw, t_min=t_min)
            except ValueError:
                if t_min == 1:
                    raise
                found[tag] = {}
                continue                # runs too short for bins of delays >= LONG_DELAYS
            found[tag] = {name: Value(float(tw), value, np.nan, test.realizations)
                          for name, value in (("T2", test.chi2), ("dof", test.dof),
                                              ("p_value", test.p_value),
                                              ("bins", len(test.bin_edges) - 1))}
        tests[float(tw)] = Eq6Test(float(tw), Value(float(tw), result.drift_share(tw), np.nan,
                                                    result.n_realizations),
                                   found["eq6_test"], found["eq6_test_long"])
    return needed, tests


def refit_table(table):
    """A ``FigureTable`` with the curves and per-curve rows of ``table`` (a Fig. 5 CSV read
    with ``tapmc.paper._plotting.read_table``) and the collapse recomputed from its curves
    (:func:`scaling_statistics`, no bootstrap: the realizations are not in a CSV): a report
    drawn before the collapse existed gets it from its own committed curves
    (``tapmc-paper report --from-data --refit``)."""
    out = P.FigureTable()
    collapse_tags = ("unscaled:", "scaling:", "scaling_time:", "drawn:")
    for (panel, series), d in table.items():
        if panel == "b" or (panel == "params" and series.startswith(collapse_tags)):
            continue
        out.add(panel, series, d["x"], d["mean"], d["sem"], d["n"])
    curves = curves_from_table(table)
    nreal = int(min(np.min(d["n"]) for (p, s), d in table.items()
                    if p == "a" and s.startswith("tw=")))
    shown, _ = add_scaling_rows(out, scaling_statistics(curves), curves, nreal)
    out.add("b", "eq6", *master_curve(shown, curves))
    return out


def master_curve(shown, curves):
    """(s, eq. 6 of the collapse, None, 0): the dotted curve of panel b over the rescaled
    delays of the curves t_W -> (t, A, sem)."""
    rescaled = [shown.rescale(tw, t, a)[0] for tw, (t, a, _) in curves.items() if tw > 0]
    ss = np.geomspace(min(s[s > 0].min() for s in rescaled),
                      max(s[s > 0].max() for s in rescaled), 200)
    return ss, shown.master(ss), None, 0


@dataclass(frozen=True)
class AgeingCurve:
    """A(t, t_W) of one waiting time over the realizations and eq. 6 fitted to it."""

    tw: float
    A: Series
    #: name (AGEING_NAMES) -> Estimate with FIT_PARTS; empty when no fit converged
    fit: dict

    def rows(self):
        return [("a", f"tw={self.tw:g}", self.A)] + _estimate_rows(f"tw={self.tw:g}", self.fit)


@dataclass(frozen=True)
class Fig5Result(FigureResult):
    """The numbers of Fig. 5 (CSV schema: module text)."""

    #: t_W -> :class:`AgeingCurve`
    curves: dict
    #: one eq. 6 in t for every curve (``collapse:``; None when it did not converge)
    common_reduced_chi2: Value = None
    common_fit: dict = None
    #: the collapses (None when they did not converge)
    scaling: Scaling = None
    #: the tests across realizations (empty in CSVs drawn before them)
    scaling_test: dict = None
    scaling_test_long: dict = None
    eq6_test_needed: Value = None
    #: t_W -> :class:`Eq6Test`
    eq6_tests: dict = None
    #: eq. 6 of the drawn collapse on the rescaled variable (panel b)
    master: Series = None

    @property
    def realizations(self):
        return int(min(np.min(c.A.n) for c in self.curves.values()))

    def rows(self):
        out = [row for curve in self.curves.values() for row in curve.rows()]
        if self.common_reduced_chi2 is not None:
            out += [("params", "collapse:reduced_chi2", self.common_reduced_chi2)]
            out += _estimate_rows("collapse", self.common_fit)
        if self.scaling is not None:
            out += self.scaling.rows()
        out += _test_rows(self.scaling_test or {}, self.scaling_test_long or {})
        if self.eq6_test_needed is not None:
            out += [("params", "eq6_test:needed", self.eq6_test_needed)]
        out += [row for test in (self.eq6_tests or {}).values() for row in test.rows()]
        return out + ([] if self.master is None else [("b", "eq6", self.master)])

    @classmethod
    def from_rows(cls, rows):
        curves = {}
        for _, label in rows.keys("a"):
            tw = float(label[len("tw="):])
            curves[tw] = AgeingCurve(tw, rows.take("a", label),
                                     estimates(rows, "params", f"{label}:", AGEING_NAMES,
                                               FIT_PARTS))
        common = (rows.take_value("params", "collapse:reduced_chi2")
                  if rows.together(("params", "collapse:reduced_chi2"),
                                   *(("params", f"collapse:{name}") for name in AGEING_NAMES))
                  else None)
        common_fit = estimates(rows, "params", "collapse:", AGEING_NAMES, FIT_PARTS)
        scaling = Scaling.from_rows(rows)
        tests = values(rows, "params", "scaling_test:", SCALING_TEST_NAMES)
        long = values(rows, "params", "scaling_test_long:", LONG_TEST_NAMES)
        needed = (rows.take_value("params", "eq6_test:needed")
                  if rows.has("params", "eq6_test:needed") else None)
        eq6 = {tw: Eq6Test.from_rows(rows, tw) for tw in curves
               if rows.has("params", f"drift_share:tw={tw:g}")}
        return cls(curves, common, common_fit, scaling, tests, long, needed, eq6,
                   rows.take_optional("b", "eq6"))


def _curve_fit(result, tw, t, a, sem):
    """Eq. 6 fitted to one curve: the library's (bootstrap errors), or with too few
    realizations for it a direct fit weighted by the standard errors where they exist; None
    when neither converges."""
    try:
        return result.fit(tw)
    except (ValueError, RuntimeError):
        keep = (t > 0) & (np.nan_to_num(sem) > 0)
        try:
            return AgeingLaw().fit(t[keep], a[keep], sigma=sem[keep])
        except (ValueError, RuntimeError):
            return None


def analyse(campaign, waiting_times=None):
    """Fig. 5 from the campaign's ageing runs (:func:`ageing`)."""
    result, nreal = ageing(campaign, waiting_times)
    curves, raw = {}, {}
    for tw, t, a, sem in _curves(result):
        fit = _curve_fit(result, tw, t, a, sem)
        curves[float(tw)] = AgeingCurve(float(tw), Series.of(t, a, sem, nreal),
                                        {} if fit is None else fit_estimates(tw, fit))
        raw[float(tw)] = (t, a, sem)
    parts = {}
    try:
        common = result.collapse()
        parts.update(common_reduced_chi2=Value(0.0, common.reduced_chi2, np.nan,
                                               int(bool(common.determined))),
                     common_fit=fit_estimates(0.0, common))
    except (ValueError, RuntimeError):
        pass
    try:
        stats = _scaling_of(result) if hasattr(result, "scaling") else scaling_statistics(raw)
    except (ValueError, RuntimeError):
        stats = None
    if stats is not None:
        parts["scaling"], shown = scaling_rows(stats, raw, nreal)
        if hasattr(result, "scaling_test"):
            parts["scaling_test"], parts["scaling_test_long"], _ = scaling_tests(
                result, shown, shown is stats["scaling"])
        parts["master"] = Series.of(*master_curve(shown, raw))
    if hasattr(result, "eq6_test"):               # each curve alone: with or without a collapse
        parts["eq6_test_needed"], parts["eq6_tests"] = eq6_tests(result)
    return Fig5Result(curves, **parts)


def plot(result, settings=None):
    """The figure of a :class:`Fig5Result` (drawing only)."""
    fig, (ax_a, ax_c) = P.new_figure(2, 1)
    colors = {}
    for tw, curve in result.curves.items():
        line = P.errorbars(ax_a, curve.A.x, curve.A.mean, curve.A.err, label=f"$t_W$ = {tw:g}")
        colors[tw] = line.get_color()
    ax_a.set_xlabel("t (taps)")
    ax_a.set_ylabel(r"$A(t, t_W)$")
    P.legend(ax_a, fontsize=7, title=f"P.B.C., {result.realizations} realizations",
                title_fontsize=7)
    ax_c.set_xlabel(r"$t\,/\,(t_W/t_{\rm ref})^{\mu}$ (taps)")
    ax_c.set_ylabel(r"$A\,/\,(t_W/t_{\rm ref})^{\kappa}$")
    if result.scaling is not None and result.master is not None:
        _collapse_panel(ax_c, result.scaling, result.master, colors)
    ax_c.set_xscale("log")
    return P.finish_figure(fig, settings, P.plotted_seeds(result))


def _collapse_panel(ax, scaling, master, colors):
    for tw, s in scaling.rescaled.items():
        pos = s.x > 0
        ax.plot(s.x[pos], s.mean[pos], "o", ms=2, color=colors.get(tw), label=f"$t_W$ = {tw:g}")
    drawn = scaling.drawn
    mu = drawn.params["mu"]
    mu_text = (f"[{mu.part('lo').value:.2f}, {mu.part('hi').value:.2f}]" if mu.value.n
               else "undetermined")
    ax.plot(master.x, master.mean, "k:", lw=1.5,
            label=f"eq. 6; $\\mu$ = {scaling.drawn_mu.value:.2f} {mu_text}, $\\kappa$ = "
                  f"{scaling.drawn_kappa.value:.2f}; red. $\\chi^2$ "
                  f"{drawn.reduced_chi2.value:.3g} "
                  f"(unscaled {scaling.unscaled_reduced_chi2.value:.3g})")
    t_ref = drawn.t_ref.value
    ax.set_xlabel(rf"$t\,/\,(t_W/{t_ref:.3g})^{{\mu}}$ (taps)")
    ax.set_ylabel(rf"$A\,/\,(t_W/{t_ref:.3g})^{{\kappa}}$")
    P.legend(ax, fontsize=6)


def figure_runs(campaign):
    """The runs Fig. 5 draws: the ageing realizations."""
    return _runs.select(campaign, "ageing_", bc=BC)


def draw(campaign, out_dir, waiting_times=None):
    """Fig. 5's PNG and CSV in ``out_dir``; returns their paths."""
    settings = P.figure_settings(campaign, figure_runs(campaign), eps=True)
    return analyse(campaign, waiting_times).save_with_png(plot, out_dir, NAME, settings)
