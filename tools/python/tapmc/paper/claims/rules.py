# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The rules that turn a measure into a verdict: one object per rule of the register, holding
its decision and the text the report prints for it, so a verdict is decided and described in
one place.

``t`` is the two-sided 95 % quantile of Student's t distribution with the measure's degrees
of freedom (seeds - 1 for a mean over seeds): sound for the few realizations a campaign has.
A measure without an uncertainty (one realization) is undecided, never agreed by default.
The rules (their text as the report prints it):
"""

from __future__ import annotations

import dataclasses
import enum
from dataclasses import dataclass

import numpy as np
from scipy import stats

from tapmc.stats import t_quantile

from .conventions import FIT_P_VALUE, NEAR_FRACTION, XI_CHECK_ROUNDING
from .measure import fmt


class Outcome(enum.StrEnum):
    """What a verdict says of a claim (a check of the tools holds or fails)."""

    AGREES = "agrees"
    #: a law the paper calls "reasonably well" or "nearly similar": within the paper's own
    #: stated precision, though our error bars reject it
    AGREES_AT_PAPER_PRECISION = "agrees at the paper's precision, not at ours"
    DISAGREES = "disagrees"
    UNDECIDED = "undecided"
    HOLDS = "holds"
    FAILS = "fails"


@dataclass(frozen=True)
class Verdict:
    """An outcome and why (``reason``: "" when the outcome says it all). Its text, as the
    report prints it: the outcome, then the reason in parentheses."""

    outcome: Outcome
    reason: str = ""

    def __str__(self):
        return f"{self.outcome} ({self.reason})" if self.reason else str(self.outcome)


AGREES, DISAGREES = Verdict(Outcome.AGREES), Verdict(Outcome.DISAGREES)


def undecided(reason):
    """The undecided verdict, saying why."""
    return Verdict(Outcome.UNDECIDED, reason)


def _band(m):
    """t err of a measure: its own quantile (e.g. a Bonferroni-corrected one) or Student's."""
    return (m.quantile if m.quantile is not None else t_quantile(m.dof)) * m.err


class Rule:
    """One rule of the register: ``name`` (claims.toml's ``rule``), ``text`` (the report's
    line), ``fields`` (the claim fields it needs), ``needs_error`` (undecided without an
    uncertainty) and :meth:`decide`."""

    name = ""
    text = ""
    fields = ()
    needs_error = True

    def decide(self, claim, m):
        raise NotImplementedError


class ValueRule(Rule):
    name = "value"
    text = ("agrees when |TAPMC - paper| <= t sem + half a unit of the paper's last printed "
            "digit, disagrees otherwise")
    fields = ("target",)

    def decide(self, claim, m):
        return AGREES if abs(m.value - claim.target) <= _band(m) + claim.rounding else DISAGREES


class RangeRule(Rule):
    name = "range"
    text = "agrees when TAPMC ± t sem meets the paper's range, disagrees otherwise"
    fields = ("lo", "hi")

    def decide(self, claim, m):
        band = _band(m)
        return AGREES if m.value + band >= claim.lo and m.value - band <= claim.hi else DISAGREES


class SignRule(Rule):
    name = "sign"
    text = ("agrees when the value has the paper's sign beyond t sem, disagrees when it has "
            "the other sign beyond t sem, undecided in between")
    fields = ("sign",)

    def decide(self, claim, m):
        signed, band = (m.sign if m.sign is not None else claim.sign) * m.value, _band(m)
        if signed > band:
            return AGREES
        if signed < -band:
            return DISAGREES
        return undecided("within the uncertainty of zero")


class ZeroRule(Rule):
    name = "zero"
    text = ("disagrees when |value| > t sem; agrees when |value| <= t sem and t sem is below "
            "the effect the claim denies (given in the verdict when it is not); undecided "
            "otherwise")

    def decide(self, claim, m):
        band = _band(m)
        if abs(m.value) > band:
            return DISAGREES
        if m.effect is None or not band < abs(m.effect):
            scale = "" if m.effect is None else f" {fmt(abs(m.effect))}"
            return undecided(f"uncertainty {fmt(band)} not below the effect{scale}")
        return AGREES


class NearRule(Rule):
    name = "near"
    text = ("for the paper's 'nearly' or 'approximately the same': agrees when |value| + t "
            f"sem is within {NEAR_FRACTION:g} times the effect the claim is measured "
            "against (given in the tolerance), disagrees when |value| - t sem exceeds "
            "it, undecided in between")

    def decide(self, claim, m):
        if m.effect is None or not np.isfinite(m.effect) or m.effect == 0:
            return undecided("no effect to compare the difference with")
        band, tolerance = _band(m), NEAR_FRACTION * abs(m.effect)
        if abs(m.value) + band <= tolerance:
            return AGREES
        if abs(m.value) - band > tolerance:
            return DISAGREES
        return undecided(f"|value| +- t sem {fmt(band)} straddles a tenth of the effect, "
                         f"{fmt(tolerance)}")


class FitRule(Rule):
    name = "fit"
    text = (f"agrees when the fit's test has a p-value of at least {FIT_P_VALUE:g} "
            "(its chi-square; across realizations, Hotelling's T^2 of the law over log-spaced "
            "bins of taps with their covariance between realizations), disagrees otherwise; "
            "a law the test rejects agrees at the paper's precision, not at ours, when its "
            "largest departure from the data is within the precision the paper can read "
            "(given in the tolerance)")
    needs_error = False

    def decide(self, claim, m):
        """``m.value``: the reduced chi-square with ``m.dof`` dof, unless the measure brings
        its own test's p-value."""
        if m.dof is None or m.dof < 1:
            return undecided("no degrees of freedom")
        p = m.p_value if m.p_value is not None else float(stats.chi2.sf(m.value * m.dof, m.dof))
        if p < FIT_P_VALUE and m.paper_precision is not None and m.paper_precision <= 1:
            return Verdict(Outcome.AGREES_AT_PAPER_PRECISION,
                           f"p = {p:.2g}; within the paper's precision")
        return Verdict(Outcome.AGREES if p >= FIT_P_VALUE else Outcome.DISAGREES, f"p = {p:.2g}")


class PatternRule(Rule):
    name = "pattern"
    text = ("agrees when the pattern over several measures (stated in the TAPMC column, "
            "each decided by its own uncertainty: the fits' intervals or t sem) is the "
            "paper's, disagrees when a measure contradicts it beyond its uncertainty, "
            "undecided otherwise")
    needs_error = False

    def decide(self, claim, m):
        """The statistic gives 1 for the paper's pattern, 0 for a contradicted one (and says
        why it cannot decide through ``m.undecided``)."""
        return AGREES if m.value == 1 else DISAGREES


class CheckRule(Rule):
    name = "check"
    text = "a check of the analysis tools (holds / fails), not counted as a reproduction"
    fields = ("target",)
    needs_error = False

    def decide(self, claim, m):
        ok = m.value >= claim.target - XI_CHECK_ROUNDING
        return Verdict(Outcome.HOLDS if ok else Outcome.FAILS)


class NoRule(Rule):
    name = "none"
    text = "no statistic yet: undecided, with the runs that would decide the claim"
    needs_error = False

    def decide(self, claim, m):
        return undecided(f"no statistic: decided by {claim.decided_by}")


#: name in claims.toml -> the rule, in the order the register's comments list them
RULES = {rule.name: rule for rule in (ValueRule(), RangeRule(), SignRule(), ZeroRule(),
                                      NearRule(), FitRule(), PatternRule(), CheckRule(),
                                      NoRule())}
RULE_NAMES = tuple(RULES)

__doc__ += "\n".join(f"* ``{rule.name}``: {rule.text};" for rule in RULES.values())


def _decidable(m):
    return m.dof is not None and m.dof >= 1 and np.isfinite(m.err)


def verdict(claim, m):
    """The :class:`Verdict` of measure ``m`` under the claim's rule (:data:`RULES`); with a
    systematic band on the measure, undecided unless the rule's outcome is the same anywhere
    within it (:func:`_same_within_systematic`)."""
    rule = RULES[claim.rule]
    if isinstance(rule, NoRule):
        return rule.decide(claim, m)
    if m.undecided:
        return undecided(m.undecided)
    if not np.isfinite(m.value):
        return undecided("not measured")
    if rule.needs_error and not _decidable(m):
        return undecided("no uncertainty: one realization")
    found = rule.decide(claim, m)
    if m.systematic is None or _same_within_systematic(rule, claim, m, found.outcome):
        return found
    return undecided(f"a systematic shift of {fmt(m.systematic[0])} to {fmt(m.systematic[1])} "
                     "could change it")


def _same_within_systematic(rule, claim, m, outcome):
    """Whether ``rule`` gives ``outcome`` with the value of ``m`` moved anywhere within its
    systematic band (low, high): tried at both ends and at the points of the band nearest
    zero and the claim's target (a zero, sign or value rule turns there, not at the ends)."""
    lo, hi = m.value + m.systematic[0], m.value + m.systematic[1]
    target = getattr(claim, "target", None)
    turns = [0.0] + ([float(target)] if target is not None and np.isfinite(target) else [])
    values = [lo, hi] + [min(max(t, lo), hi) for t in turns]
    return all(rule.decide(claim, dataclasses.replace(m, value=v, systematic=None)).outcome
               == outcome for v in values)
