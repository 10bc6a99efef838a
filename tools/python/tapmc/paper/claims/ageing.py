# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Statistics of the ageing claims (section III.C, Fig. 5, eq. 6): the law-free collapse of
the response curves and eq. 6's law over the waiting times."""

from __future__ import annotations

import functools
import math

import numpy as np
from scipy import integrate, special

from ..fig5 import EQ6_TEST_MIN_REALIZATIONS, LONG_DELAYS
from .common import not_in_campaign
from .conventions import LAW_FREE_MIN_REALIZATIONS
from .measure import Measure, fmt
from .registry import statistic


def _value(values, name):
    """The number of row ``name`` of a Fig. 5 dict of Values (NaN when absent)."""
    value = (values or {}).get(name)
    return math.nan if value is None else value.value


def _waiting_curves(fig5):
    """(t_W, AgeingCurve) of Fig. 5's curves with t_W > 0, by t_W."""
    return sorted((tw, c) for tw, c in fig5.curves.items() if tw > 0)


@functools.lru_cache(maxsize=64)
def dispersion_p_bound(dispersion, realizations):
    """An upper bound of the p-value of the law-free dispersion of curves that collapse
    (tapmc.ageing.collapse_dispersion: the mean over the delays of squared differences
    between the rescaled curves, each standardized by the two curves' sems): each term is the
    square of a difference of means over ``realizations`` standardized by its sem, Y ~ F(1,
    n - 1); whatever the correlation between the delays, their mean is dominated by one Y in
    convex order (Jensen), so P(mean >= d) <= min over a < d of E[(Y - a)+] / (d - a).
    A pure function of its two numbers, kept (the report's table of conventions re-evaluates
    the claims many times on the same data: 200 integrals each)."""
    if not (np.isfinite(dispersion) and dispersion > 0) or realizations < 4:
        return math.nan  # F(1, n - 1) has no mean below 4 realizations: no bound
    dfd = realizations - 1

    def survival(x):
        # the survival function of F(1, n - 1), as scipy.stats.f(1, dfd).sf computes it on
        # x > 0 (the same special function), without its per-call checks (200 integrals)
        return special.fdtrc(1, dfd, x)

    def stop_loss(a):
        return integrate.quad(survival, a, np.inf, limit=200)[0]

    grid = np.linspace(0.0, dispersion, 201)[:-1]
    return float(min(1.0, min(stop_loss(a) / (dispersion - a) for a in grid)))


@statistic("ageing_collapse")
def ageing_collapse(data, claim):
    """Section III.C, "there is obviously a scaling law": one rescaling of t (and of A)
    collapses the curves of every t_W, whatever the master curve. The law-free dispersion of
    Fig. 5's curves at the exponents that minimise it (tapmc.ageing.collapse_dispersion, rows
    ``scaling:dispersion_min``, ``_mu``, ``_kappa``), about 1 for curves that are one within
    their errors, with the p-value bound of :func:`dispersion_p_bound`; the collapse on eq. 6
    tested across realizations (``scaling_test:``) is shown beside it and decides nothing
    (eq. 6 is the next claim)."""
    fig5 = data.result("fig5")
    if fig5 is None:
        return not_in_campaign("no ageing runs")
    scaling = fig5.scaling
    law_free = None if scaling is None else scaling.collapses["scaling"].dispersion
    d = _value(law_free, "dispersion_min")
    if not np.isfinite(d):
        return not_in_campaign("no law-free collapse in the Fig. 5 data")
    curves = _waiting_curves(fig5)
    realizations = int(min(np.min(c.A.n) for _, c in curves)) if curves else 0
    shown = (f"law-free dispersion {fmt(d)} at mu = {fmt(_value(law_free, 'dispersion_mu'))}, "
             f"kappa = {fmt(_value(law_free, 'dispersion_kappa'))} (1 for curves that are one "
             f"within their errors; unscaled {fmt(scaling.unscaled_dispersion.value)}), "
             f"{realizations} realizations") + _eq6_collapse_text(fig5)
    if realizations < LAW_FREE_MIN_REALIZATIONS:
        return [Measure(d, shown=shown, undecided=(
            f"{realizations} realizations: the curves' errors need at least "
            f"{LAW_FREE_MIN_REALIZATIONS}"))]
    p = dispersion_p_bound(d, realizations)
    return [Measure(d, dof=realizations - 1, p_value=p,
                    shown=f"{shown}; p <= {p:.2g} whatever the delays' correlation")]


def _eq6_collapse_text(fig5):
    """The collapse on eq. 6 tested across the realizations, as the page shows it beside the
    law-free one ("" when the Fig. 5 data have no such test)."""
    T2 = _value(fig5.scaling_test, "T2")
    if not np.isfinite(T2):
        return ""
    return (f"; on eq. 6 as master curve (decides nothing): T^2 {fmt(T2)} "
            f"({int(_value(fig5.scaling_test, 'dof'))} dof), p = "
            f"{_value(fig5.scaling_test, 'p_value'):.2g}")


def _long_delays_text(lead, p_value):
    """``lead`` and the p-value of a Fig. 5 test over the long delays alone (``""`` when the
    figure data have none)."""
    if not np.isfinite(p_value):
        return ""
    return (f"{lead} over the delays >= {LONG_DELAYS} alone (a linear axis of t, as the paper "
            f"draws it): p = {fmt(p_value, digits=2)}")


@statistic("ageing_eq6")
def ageing_eq6(data, claim):
    """Eq. 6 on each curve of Fig. 5 alone, tested across the realizations (``eq6_test:``
    rows, tapmc.ageing.Ageing.eq6_test), one row per waiting time, with the share of the curve
    that is the square of the mean displacement (``drift_share:``)."""
    fig5 = data.result("fig5")
    if fig5 is None:
        return not_in_campaign("no ageing runs")
    curves = _waiting_curves(fig5)
    if not curves:
        return not_in_campaign("no curve A(t, t_W) with t_W > 0 in the Fig. 5 data")
    needed = math.nan if fig5.eq6_test_needed is None else fig5.eq6_test_needed.value
    if not np.isfinite(needed):                     # drawn before the rows existed
        needed = EQ6_TEST_MIN_REALIZATIONS
    out = []
    for tw, curve in curves:
        label = f"t_W = {tw:g}"
        realizations = int(np.min(curve.A.n))
        if realizations < needed:
            out.append(Measure(label=label, undecided=(
                f"{realizations} realizations: eq. 6's test across realizations needs at "
                f"least {int(needed)} (the paper averaged 10)")))
            continue
        test = (fig5.eq6_tests or {}).get(tw)
        T2 = math.nan if test is None else _value(test.every_delay, "T2")
        if not np.isfinite(T2):
            out.append(Measure(label=label, undecided=(
                "the Fig. 5 data have no test of eq. 6 across realizations (drawn before it "
                "existed: draw Fig. 5 again from its runs)")))
            continue
        dof = int(_value(test.every_delay, "dof"))
        bins = int(_value(test.every_delay, "bins"))
        share = test.drift_share.value
        long_text = _long_delays_text(";", _value(test.long_delays, "p_value"))
        out.append(Measure(T2, dof=dof, p_value=_value(test.every_delay, "p_value"),
                           label=label,
                           shown=(f"T^2 {fmt(T2)} ({dof} dof) over {bins} log bins of delays, "
                                  f"{realizations} realizations; the mean displacement's "
                                  f"square is {fmt(share, pct=True)} of A{long_text}")))
    return out
