# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Statistics of the ageing claims (section III.C, Fig. 5, eq. 6): the collapse of the
response curves and eq. 6's law over the waiting times."""

from __future__ import annotations

import math

import numpy as np

from tapmc.ageing import scaling_test_min_realizations

from ..fig5 import EQ6_TEST_MIN_REALIZATIONS, LONG_DELAYS
from .common import not_in_campaign, value_triple
from .measure import Measure, fmt
from .registry import statistic


def _value(values, name):
    """The number of row ``name`` of a Fig. 5 dict of Values (NaN when absent)."""
    value = (values or {}).get(name)
    return math.nan if value is None else value.value


def _waiting_curves(fig5):
    """(t_W, AgeingCurve) of Fig. 5's curves with t_W > 0, by t_W."""
    return sorted((tw, c) for tw, c in fig5.curves.items() if tw > 0)


@statistic("ageing_collapse")
def ageing_collapse(data, claim):
    """Hotelling's T^2 of the drawn collapse of Fig. 5 across the realizations
    (``scaling_test:`` rows, tapmc.ageing.ScalingRealizationTest), with mu and the reduced
    chi2 over the correlated delays beside it (which decides nothing: its delays share their
    realizations and their errors come from the same few of them)."""
    fig5 = data.result("fig5")
    if fig5 is None:
        return not_in_campaign("no ageing runs")
    scaling = fig5.scaling
    if scaling is None or not np.isfinite(scaling.drawn_mu.value):
        return not_in_campaign("no rescaled collapse in the Fig. 5 data")
    full = scaling.drawn_mu.n == 1
    drawn = scaling.drawn
    chi = drawn.reduced_chi2.value
    mu = drawn.params.get("mu")
    mu, mu_err, mu_closed = value_triple(None if mu is None else mu.value)
    mu_text = fmt(mu, mu_err) if mu_closed == 1 else f"{fmt(mu)} (undetermined)"
    shown = (f"mu = {mu_text}; reduced chi2 over the correlated delays {fmt(chi)} (decides "
             "nothing)")
    curves = _waiting_curves(fig5)
    realizations = int(min(np.min(c.A.n) for _, c in curves)) if curves else 0
    needed = _value(fig5.scaling_test, "needed")
    if not np.isfinite(needed):
        needed = scaling_test_min_realizations(len(curves), full)
    if realizations < needed:
        return [Measure(shown=shown, undecided=(
            f"{realizations} realizations: the test of the collapse across realizations needs "
            f"at least {int(needed)} (the paper averaged 10)"))]
    T2 = _value(fig5.scaling_test, "T2")
    if not np.isfinite(T2):
        return [Measure(shown=shown, undecided=(
            "the Fig. 5 data have no test across realizations (drawn before it existed: "
            "draw Fig. 5 again from its runs)"))]
    dof = int(_value(fig5.scaling_test, "dof"))
    bins = int(_value(fig5.scaling_test, "bins"))
    shown += _long_delays_text("; the test", _value(fig5.scaling_test_long, "p_value"))
    return [Measure(T2, dof=dof, p_value=_value(fig5.scaling_test, "p_value"),
                    shown=f"T^2 {fmt(T2)} ({dof} dof) over {bins} log bins of delays, "
                          f"{realizations} realizations; {shown}")]


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
