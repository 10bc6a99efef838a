# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The rules that turn a measure into a verdict."""

from __future__ import annotations

import numpy as np
from scipy import stats

from tapmc.stats import t_quantile

from .measure import fmt


#: p-value below which a fit's chi-square rejects the law (rule ``fit``).
FIT_P_VALUE = 0.01


#: Rounding of the pore dumps' coordinates, allowed below xi_T by the ``check`` rule.
XI_CHECK_ROUNDING = 1e-3


RULE_NAMES = ("value", "range", "sign", "zero", "near", "fit", "pattern", "check", "none")


#: "nearly the same" (rule ``near``): within a tenth of the effect the claim is measured
#: against, the share below which the ramp-levels text also calls a shift negligible
NEAR_FRACTION = 0.1


def _decidable(m):
    return m.dof is not None and m.dof >= 1 and np.isfinite(m.err)


def verdict(claim, m):
    """The verdict of one measure under the claim's rule: a text starting with "agrees",
    "disagrees", "undecided", "holds" or "fails"."""
    if m.undecided:
        return f"undecided ({m.undecided})"
    if not np.isfinite(m.value):
        return "undecided (not measured)"
    rule = claim.rule
    if rule == "check":
        ok = m.value >= claim.target - XI_CHECK_ROUNDING
        return "holds" if ok else "fails"
    if rule == "pattern":
        return "agrees" if m.value == 1 else "disagrees"
    if rule == "fit":
        if m.dof is None or m.dof < 1:
            return "undecided (no degrees of freedom)"
        p = m.p_value if m.p_value is not None else float(stats.chi2.sf(m.value * m.dof, m.dof))
        return ("agrees" if p >= FIT_P_VALUE else "disagrees") + f" (p = {p:.2g})"
    if not _decidable(m):
        return "undecided (no uncertainty: one realization)"
    t = m.quantile if m.quantile is not None else t_quantile(m.dof)
    band = t * m.err
    if rule == "value":
        return "agrees" if abs(m.value - claim.target) <= band + claim.rounding else "disagrees"
    if rule == "range":
        return "agrees" if (m.value + band >= claim.lo and m.value - band <= claim.hi) \
            else "disagrees"
    if rule == "sign":
        signed = (m.sign if m.sign is not None else claim.sign) * m.value
        if signed > band:
            return "agrees"
        if signed < -band:
            return "disagrees"
        return "undecided (within the uncertainty of zero)"
    if rule == "near":
        if m.effect is None or not np.isfinite(m.effect) or m.effect == 0:
            return "undecided (no effect to compare the difference with)"
        tolerance = NEAR_FRACTION * abs(m.effect)
        if abs(m.value) + band <= tolerance:
            return "agrees"
        if abs(m.value) - band > tolerance:
            return "disagrees"
        return (f"undecided (|value| +- t sem {fmt(band)} straddles a tenth of the effect, "
                f"{fmt(tolerance)})")
    if rule == "zero":
        if abs(m.value) > band:
            return "disagrees"
        if m.effect is None or not band < abs(m.effect):
            scale = "" if m.effect is None else f" {fmt(abs(m.effect))}"
            return f"undecided (uncertainty {fmt(band)} not below the effect{scale})"
        return "agrees"
    raise ValueError(f"rule {rule!r}")
