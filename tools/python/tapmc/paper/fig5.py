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
"""

from __future__ import annotations

import numpy as np

from tapmc.ageing import scaling_collapse
from tapmc.laws import AgeingLaw

from . import _plotting as P
from . import _runs

NAME = "fig5"
BC = "pbc"


def runs(scale, seeds):
    """One ageing realization (in.ageing) per seed."""
    return [_runs.ageing_run(scale, BC, scale.ageing_eps, s) for s in _runs.seed_list(seeds)]


def ageing(campaign, waiting_times=None, bc=BC):
    """The Ageing result of the campaign's ageing runs of ``bc``."""
    from tapmc.ageing import Ageing

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


def add_fit_rows(table, tag, x, fit, collapse=None):
    """Rows ``<tag>:<name>`` (+ ``:lo``, ``:hi``) of a FitResult; for a ``ScalingCollapse``
    the intervals are its widened ones and ``:jackknife``, ``:bootstrap`` follow."""
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
        table.add("params", f"{tag}:{name}", x, value, err, int(iv.determined))
        for side, bound in (("lo", iv.lo), ("hi", iv.hi)):
            b, closed = _bound(bound)
            table.add("params", f"{tag}:{name}:{side}", x, b, None, closed)
        if collapse is not None:
            jk = collapse.jackknife[name]
            bs = np.nan if collapse.bootstrap is None else collapse.bootstrap[name]
            table.add("params", f"{tag}:{name}:jackknife", x, jk, None, int(np.isfinite(jk)))
            table.add("params", f"{tag}:{name}:bootstrap", x, bs, None, int(np.isfinite(bs)))


def add_scaling_rows(table, stats, curves, nreal):
    """The collapse rows of the module text (``params`` ``unscaled:``, ``scaling:``,
    ``scaling_time:``, ``drawn:``; panel ``b``'s rescaled curves) from
    :func:`scaling_statistics` (or ``Ageing.scaling``) results; returns the drawn collapse and
    dict t_W -> (rescaled t, rescaled A)."""
    table.add("params", "unscaled:reduced_chi2", 0.0,
              stats["scaling"].unscaled_reduced_chi2, None, 1)
    for tag, col in stats.items():
        table.add("params", f"{tag}:t_ref", 0.0, col.t_ref, None, 1)
        table.add("params", f"{tag}:reduced_chi2", 0.0, col.reduced_chi2, None,
                  int(not col.fit.undetermined_params))
        add_fit_rows(table, tag, 0.0, col.fit, col)
        mu_free, kappa_free = col.dispersion_exponents
        table.add("params", f"{tag}:dispersion", 0.0, col.dispersion(), None, 1)
        table.add("params", f"{tag}:dispersion_mu", 0.0, mu_free, None, 1)
        table.add("params", f"{tag}:dispersion_kappa", 0.0, kappa_free, None, 1)
        table.add("params", f"{tag}:dispersion_min", 0.0,
                  col.dispersion(mu_free, kappa_free), None, 1)
    table.add("params", "unscaled:dispersion", 0.0, stats["scaling"].dispersion(0.0, 0.0),
              None, 1)
    shown = drawn_collapse(stats)
    full = shown is stats["scaling"]
    table.add("params", "drawn:mu", 0.0, shown.mu, None, int(full))
    table.add("params", "drawn:kappa", 0.0, shown.kappa, None, int(full))
    rescaled = {}
    for tw, (t, a, sem) in curves.items():
        if tw <= 0:
            continue
        s, y = shown.rescale(tw, t, a)
        _, ys = shown.rescale(tw, t, sem)
        table.add("b", f"tw={tw:g}", s, y, ys, nreal)
        rescaled[tw] = (s, y)
    return shown, rescaled


#: the first delay of the tests over long delays alone (the collapse's, eq. 6's): the paper's
#: Fig. 5 draws t on a linear axis to 3000 taps, where the delays below 100 fill 3 % of its
#: width
LONG_DELAYS = 100


def add_test_rows(table, result, shown, full):
    """The ``scaling_test:`` rows of the module text: the drawn collapse ``shown`` (time and
    amplitude when ``full``) tested across the realizations of the ``Ageing`` ``result``,
    started from its fit."""
    from tapmc.ageing import scaling_test_min_realizations

    curves = [tw for tw in result.waiting_times if tw > 0]
    needed = scaling_test_min_realizations(len(curves), full)
    table.add("params", "scaling_test:needed", 0.0, needed, None, 1)
    if result.n_realizations < needed:
        return None
    test = result.scaling_test(full, start=shown.fit.params)
    for name, value in (("T2", test.chi2), ("dof", test.dof), ("p_value", test.p_value),
                        ("bins", sum(test.bins.values())), ("realizations", test.realizations)):
        table.add("params", f"scaling_test:{name}", 0.0, value, None, 1)
    try:
        long = result.scaling_test(full, start=shown.fit.params, t_min=LONG_DELAYS)
    except ValueError:                  # runs too short for bins of delays >= LONG_DELAYS
        return test
    for name, value in (("T2", long.chi2), ("dof", long.dof), ("p_value", long.p_value)):
        table.add("params", f"scaling_test_long:{name}", 0.0, value, None, 1)
    return test


#: realizations eq. 6's test on one curve needs (tapmc.laws.RealizationLawTest: bins > its
#: parameters, realizations > bins)
EQ6_TEST_MIN_REALIZATIONS = len(AgeingLaw.names) + 2


def add_eq6_rows(table, result):
    """The ``eq6_test:`` and ``drift_share:`` rows of the module text for every waiting time
    > 0 of the ``Ageing`` ``result``."""
    table.add("params", "eq6_test:needed", 0.0, EQ6_TEST_MIN_REALIZATIONS, None, 1)
    if result.n_realizations < EQ6_TEST_MIN_REALIZATIONS:
        return
    for tw in result.waiting_times:
        if tw <= 0:
            continue
        table.add("params", f"drift_share:tw={tw:g}", float(tw), result.drift_share(tw),
                  None, result.n_realizations)
        for tag, t_min in (("eq6_test", 1), ("eq6_test_long", LONG_DELAYS)):
            try:
                test = result.eq6_test(tw, t_min=t_min)
            except ValueError:
                if t_min == 1:
                    raise
                continue                # runs too short for bins of delays >= LONG_DELAYS
            for name, value in (("T2", test.chi2), ("dof", test.dof),
                                ("p_value", test.p_value), ("bins", len(test.bin_edges) - 1)):
                table.add("params", f"{tag}:tw={tw:g}:{name}", float(tw), value, None,
                          test.realizations)


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
    rescaled = [s for tw, (t, a, sem) in curves.items() if tw > 0
                for s in [shown.rescale(tw, t, a)[0]]]
    ss = np.geomspace(min(s[s > 0].min() for s in rescaled),
                      max(s[s > 0].max() for s in rescaled), 200)
    out.add("b", "eq6", ss, shown.master(ss), None, 0)
    return out


def draw(campaign, out_dir, waiting_times=None):
    png, csv = P.figure_paths(out_dir, NAME)
    result, nreal = ageing(campaign, waiting_times)
    table = P.FigureTable()
    fig, (ax_a, ax_c) = P.new_figure(2, 1)
    colors = {}
    curves = {}
    for tw, t, a, sem in _curves(result):
        line = P.errorbars(ax_a, t, a, sem, label=f"$t_W$ = {tw:g}")
        colors[tw] = line.get_color()
        table.add("a", f"tw={tw:g}", t, a, sem, nreal)
        curves[float(tw)] = (t, a, sem)
        try:
            fit = result.fit(tw)
        except (ValueError, RuntimeError):
            # too few realizations for the library's own error estimate: a direct eq. 6 fit
            # weighted by the standard errors where they exist
            keep = (t > 0) & (np.nan_to_num(sem) > 0)
            try:
                fit = AgeingLaw().fit(t[keep], a[keep], sigma=sem[keep])
            except (ValueError, RuntimeError):
                continue
        add_fit_rows(table, f"tw={tw:g}", tw, fit)
    try:
        common = result.collapse()
    except (ValueError, RuntimeError):
        common = None
    if common is not None:
        table.add("params", "collapse:reduced_chi2", 0.0, common.reduced_chi2, None,
                  int(bool(common.determined)))
        add_fit_rows(table, "collapse", 0.0, common)
    try:
        stats = _scaling_of(result) if hasattr(result, "scaling") else \
            scaling_statistics(curves)
    except (ValueError, RuntimeError):
        stats = None
    if stats is not None:
        shown, rescaled = add_scaling_rows(table, stats, curves, nreal)
        if hasattr(result, "scaling_test"):
            add_test_rows(table, result, shown, shown is stats["scaling"])
    if hasattr(result, "eq6_test"):
        add_eq6_rows(table, result)               # each curve alone: with or without a collapse
    if stats is not None:
        smin, smax = np.inf, 0.0
        for tw, (s, y) in rescaled.items():
            pos = s > 0
            ax_c.plot(s[pos], y[pos], "o", ms=2, color=colors.get(tw), label=f"$t_W$ = {tw:g}")
            smin, smax = min(smin, s[pos].min()), max(smax, s[pos].max())
        ss = np.geomspace(smin, smax, 200)
        iv = shown.interval("mu")
        mu_text = (f"[{iv.lo:.2f}, {iv.hi:.2f}]" if iv.determined else "undetermined")
        ax_c.plot(ss, shown.master(ss), "k:", lw=1.5,
                  label=f"eq. 6; $\\mu$ = {shown.mu:.2f} {mu_text}, $\\kappa$ = "
                        f"{shown.kappa:.2f}; red. $\\chi^2$ {shown.reduced_chi2:.3g} "
                        f"(unscaled {shown.unscaled_reduced_chi2:.3g})")
        table.add("b", "eq6", ss, shown.master(ss), None, 0)
        ax_c.set_xlabel(rf"$t\,/\,(t_W/{shown.t_ref:.3g})^{{\mu}}$ (taps)")
        ax_c.set_ylabel(rf"$A\,/\,(t_W/{shown.t_ref:.3g})^{{\kappa}}$")
    ax_a.set_xlabel("t (taps)")
    ax_a.set_ylabel(r"$A(t, t_W)$")
    ax_a.legend(fontsize=7, title=f"P.B.C., {nreal} realizations", title_fontsize=7)
    ax_c.set_xscale("log")
    ax_c.legend(fontsize=6)
    return P.write_figure(fig, png, table, csv)
