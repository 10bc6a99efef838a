# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Statistics of the ageing claims (section III.C, Fig. 5, eq. 6): the collapse of the
response curves and eq. 6's law over the waiting times."""

from __future__ import annotations

import numpy as np

from tapmc.ageing import scaling_test_min_realizations

from ..fig5 import EQ6_TEST_MIN_REALIZATIONS, LONG_DELAYS
from .common import not_in_campaign
from .measure import Measure, fmt
from .registry import statistic


@statistic("ageing_collapse")
def ageing_collapse(data, claim):
    """Hotelling's T^2 of the drawn collapse of Fig. 5 across the realizations
    (``scaling_test:`` rows, tapmc.ageing.ScalingRealizationTest), with mu and the reduced
    chi2 over the correlated delays beside it (which decides nothing: its delays share their
    realizations and their errors come from the same few of them)."""
    fig = data.figure("fig5")
    if fig is None:
        return not_in_campaign("no ageing runs")
    drawn_mu = fig.param("drawn:mu")
    if not np.isfinite(drawn_mu[0]):
        return not_in_campaign("no rescaled collapse in the Fig. 5 data")
    tag = "scaling" if drawn_mu[2] == 1 else "scaling_time"
    chi = fig.param(f"{tag}:reduced_chi2")[0]
    mu, mu_err, mu_closed = fig.param(f"{tag}:mu")
    mu_text = fmt(mu, mu_err) if mu_closed == 1 else f"{fmt(mu)} (undetermined)"
    shown = (f"mu = {mu_text}; reduced chi2 over the correlated delays {fmt(chi)} (decides "
             "nothing)")
    curves = [s for s in fig.series("a") if s.startswith("tw=") and float(s[3:]) > 0]
    realizations = int(min(np.min(fig.get("a", s)[3]) for s in curves)) if curves else 0
    needed = fig.param("scaling_test:needed")[0]
    if not np.isfinite(needed):
        needed = scaling_test_min_realizations(len(curves), drawn_mu[2] == 1)
    if realizations < needed:
        return [Measure(shown=shown, undecided=(
            f"{realizations} realizations: the test of the collapse across realizations needs "
            f"at least {int(needed)} (the paper averaged 10)"))]
    T2 = fig.param("scaling_test:T2")[0]
    if not np.isfinite(T2):
        return [Measure(shown=shown, undecided=(
            "the Fig. 5 data have no test across realizations (drawn before it existed: "
            "draw Fig. 5 again from its runs)"))]
    dof = int(fig.param("scaling_test:dof")[0])
    bins = int(fig.param("scaling_test:bins")[0])
    shown += _long_delays_text("; the test", fig.param("scaling_test_long:p_value")[0])
    return [Measure(T2, dof=dof, p_value=fig.param("scaling_test:p_value")[0],
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
    fig = data.figure("fig5")
    if fig is None:
        return not_in_campaign("no ageing runs")
    curves = sorted((float(s[3:]), s) for s in fig.series("a")
                    if s.startswith("tw=") and float(s[3:]) > 0)
    if not curves:
        return not_in_campaign("no curve A(t, t_W) with t_W > 0 in the Fig. 5 data")
    needed = fig.param("eq6_test:needed")[0]
    if not np.isfinite(needed):                     # drawn before the rows existed
        needed = EQ6_TEST_MIN_REALIZATIONS
    out = []
    for tw, series in curves:
        label = f"t_W = {tw:g}"
        realizations = int(np.min(fig.get("a", series)[3]))
        if realizations < needed:
            out.append(Measure(label=label, undecided=(
                f"{realizations} realizations: eq. 6's test across realizations needs at "
                f"least {int(needed)} (the paper averaged 10)")))
            continue
        T2, _, _ = fig.param(f"eq6_test:tw={tw:g}:T2")
        if not np.isfinite(T2):
            out.append(Measure(label=label, undecided=(
                "the Fig. 5 data have no test of eq. 6 across realizations (drawn before it "
                "existed: draw Fig. 5 again from its runs)")))
            continue
        dof = int(fig.param(f"eq6_test:tw={tw:g}:dof")[0])
        bins = int(fig.param(f"eq6_test:tw={tw:g}:bins")[0])
        share = fig.param(f"drift_share:tw={tw:g}")[0]
        long_text = _long_delays_text(";", fig.param(f"eq6_test_long:tw={tw:g}:p_value")[0])
        out.append(Measure(T2, dof=dof, p_value=fig.param(f"eq6_test:tw={tw:g}:p_value")[0],
                           label=label,
                           shown=(f"T^2 {fmt(T2)} ({dof} dof) over {bins} log bins of delays, "
                                  f"{realizations} realizations; the mean displacement's "
                                  f"square is {fmt(share, pct=True)} of A{long_text}")))
    return out
