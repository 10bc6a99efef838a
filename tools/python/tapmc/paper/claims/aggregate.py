# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""One verdict per claim: a claim of the register measured by several rows (several eps,
runs, waiting times, levels or readings of one sentence) gets one :class:`ClaimVerdict`,
which follows from its rows' verdicts by :data:`AGGREGATION_RULE`; the pages count claims,
not rows, and keep the rows in a table of each claim.

The rule gives a disagreement precedence over any number of agreements, not a majority: the
paper states each of these claims for every case it shows (every eps of Fig. 3's spectra,
every waiting time of Fig. 5), so one case contradicted beyond its band contradicts the
sentence, and a majority would let a claim pass with counter-examples in its own table.
Undecided rows are listed but do not change a decided verdict: they are the cases the data
cannot decide (too few seeds, a scale below the paper's), not counter-examples.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from .rules import Outcome

#: the outcomes of a check of the tools (never counted as a reproduction)
CHECK_OUTCOMES = (Outcome.HOLDS, Outcome.FAILS)
#: the decided outcomes, the one that prevails over the others first: a disagreement (or a
#: failed check) over any agreement, an agreement at the paper's precision only over full
#: agreement (the claim then holds only as loosely as the paper states it)
PRECEDENCE = (Outcome.FAILS, Outcome.DISAGREES, Outcome.AGREES_AT_PAPER_PRECISION,
              Outcome.AGREES, Outcome.HOLDS)

#: how a claim's verdict follows from its rows, as the pages print it
AGGREGATION_RULE = (
    "A claim measured by several rows (several eps, runs, waiting times or readings) has one "
    "verdict: it disagrees when any of its rows disagrees beyond its band (the paper states "
    "the claim for every case it shows, so one contradicted case contradicts it, where a "
    "majority would hide counter-examples); otherwise it agrees at the paper's precision when "
    "a decided row does, and agrees when every decided row agrees; it is undecided when no "
    "row is decided. Undecided rows are listed with the claim but do not change a decided "
    "verdict. A check of the tools fails when any of its rows fails.")

#: the rule in one sentence, for the main page (the rules' page gives it whole)
AGGREGATION_SENTENCE = (
    "A claim's verdict follows from its rows (one per eps, run, waiting time or reading, "
    "listed on the appendix of every row): it disagrees when any row disagrees, agrees when "
    "every decided row agrees (at the paper's precision only, when a row agrees only so), and "
    "is undecided when no row is decided.")


def model_outcomes():
    """The outcomes a claim about the model can have, in the enum's order (every outcome
    but a check's: an outcome added to :class:`Outcome` shows up in the counts)."""
    return tuple(o for o in Outcome if o not in CHECK_OUTCOMES)


#: a row label that is one value of a parameter and nothing else ("eps = 0.05", "t_W = 30")
_ONE_VALUE = re.compile(r"^(eps|t_W) = [-+.\deE]+$")
#: the parameter of such labels -> what the counts call its rows
_UNITS = {"eps": "eps", "t_W": "waiting times"}


def row_unit(rows):
    """What a claim's rows are, for the verdict's counts: "eps" when every row is one eps
    and nothing else (its label "eps = <value>"), "waiting times" when every row is one t_W,
    else "rows"."""
    matches = [_ONE_VALUE.match(r.label) for r in rows]
    names = {m.group(1) for m in matches if m}
    if rows and all(matches) and len(names) == 1:
        return _UNITS[names.pop()]
    return "rows"


def verb(outcome, n):
    """An outcome's text as the verb of n claims or rows: "agrees" for one, "agree" for
    several (its first word loses its s in the plural), "undecided" for any number."""
    text = str(outcome)
    first, _, rest = text.partition(" ")
    if n == 1 or not first.endswith("s"):
        return text
    return first[:-1] + (" " + rest if rest else "")


def counted(outcome, n):
    """"3 agree", "1 agrees", "0 undecided"."""
    return f"{n} {verb(outcome, n)}"


def combined_outcome(outcomes):
    """The claim's outcome from its rows' outcomes by :data:`AGGREGATION_RULE`: the first of
    :data:`PRECEDENCE` among the decided ones, undecided when none is decided."""
    present = set(outcomes)
    unknown = present - set(PRECEDENCE) - {Outcome.UNDECIDED}
    if unknown:
        raise ValueError(f"no precedence for the outcomes {sorted(unknown)}: add them to "
                         "tapmc.paper.claims.aggregate.PRECEDENCE")
    return next((o for o in PRECEDENCE if o in present), Outcome.UNDECIDED)


@dataclass(frozen=True)
class ClaimVerdict:
    """One claim of the register with its rows (:class:`~.evaluate.Row`, in the register's
    order) and the verdict they give it (:func:`combined_outcome`)."""

    claim: object
    rows: tuple
    outcome: Outcome

    @property
    def counts(self):
        """Outcome -> the number of rows with it (outcomes of no row left out)."""
        found = {}
        for row in self.rows:
            found[row.outcome] = found.get(row.outcome, 0) + 1
        return {o: found[o] for o in Outcome if o in found}

    @property
    def missing_scale(self):
        """The parts of the paper's scale that some row lacks, in the rows' order."""
        return tuple(dict.fromkeys(a for r in self.rows for a in r.missing_scale))

    @property
    def undecided_for_scale(self):
        """Undecided, and some row lacks part of the paper's scale."""
        return self.outcome == Outcome.UNDECIDED and bool(self.missing_scale)

    @property
    def reason(self):
        """The counts the verdict follows from: "10 of 10 eps agree", or "2 of 6 rows
        disagree, 3 agree, 1 undecided" (the outcome's own count first)."""
        n, unit = len(self.rows), row_unit(self.rows)
        counts = self.counts
        first = self.outcome if self.outcome in counts else next(iter(counts))
        parts = [f"{counts[first]} of {n} {unit} {verb(first, counts[first])}"]
        parts += [counted(o, k) for o, k in counts.items() if o != first]
        return ", ".join(parts)

    def text(self):
        """The verdict as the pages print it: the row's own verdict (with its reason) for a
        claim of one row, the outcome and its counts otherwise."""
        if len(self.rows) == 1:
            return str(self.rows[0].verdict)
        return f"{self.outcome} ({self.reason})"

    def shown_row(self):
        """The row the main table shows for the claim: the first that disagrees (or fails)
        when the claim does, else the row of the claim's headline label when it has one,
        else the first row with the claim's outcome; a row at the paper's scale (none of it
        missing, e.g. a ramp at the paper's 4000 taps per level) before one that lacks it, and
        a row with a value before one without (a ramp at the paper's scale not yet measured)."""
        rows = self.rows
        if isinstance(self.claim.headline, str) and self.outcome not in (
                Outcome.DISAGREES, Outcome.FAILS):
            rows = [r for r in rows if r.label.startswith(self.claim.headline)] or rows
        same = [r for r in rows if r.outcome == self.outcome] or [rows[0]]
        return min(same, key=lambda r: (not _has_value(r.measure), bool(r.missing_scale)))


def _has_value(measure):
    """Whether a row's measure shows a number or a text of its own (not "n/a")."""
    value = measure.value
    return measure.shown is not None or (isinstance(value, (int, float))
                                          and math.isfinite(value))


def claim_verdicts(rows):
    """The :class:`ClaimVerdict` of every claim of ``rows`` (the rows of
    :func:`~.evaluate.evaluate`), in the order of their first row."""
    grouped = {}
    for row in rows:
        grouped.setdefault(row.claim.id, []).append(row)
    return [ClaimVerdict(group[0].claim, tuple(group),
                         combined_outcome(r.outcome for r in group))
            for group in grouped.values()]


def count_outcomes(verdicts, outcomes):
    """Outcome -> the number of ``verdicts`` with it, for every outcome of ``outcomes`` (zero
    included), in their order."""
    return {o: sum(1 for v in verdicts if v.outcome == o) for o in outcomes}


def count_sentence(verdicts):
    """The claim counts of a page, over the outcomes of :class:`Outcome`: the model claims
    that could fail (reproduced physics or not), those that could not fail for any compaction
    model (counted apart), and the checks of the tools."""
    model = [v for v in verdicts if v.claim.kind == "model"]
    physics = [v for v in model if v.claim.could_fail]
    constructed = [v for v in model if not v.claim.could_fail]
    checks = [v for v in verdicts if v.claim.kind != "model"]

    def listed(group, outcomes):
        return "; ".join(counted(o, k) for o, k in count_outcomes(group, outcomes).items())

    rows = sum(len(v.rows) for v in model)
    text = (f"{len(model)} claims of the paper about the model, measured in {rows} rows. "
            f"Of the {len(physics)} claims that could fail: "
            f"{listed(physics, model_outcomes())}.")
    one = len(constructed) == 1
    text += (f" {len(constructed)} {'claim' if one else 'claims'} could not fail for any "
             f"compaction model and {'is' if one else 'are'} not counted as reproduction"
             + (f": {listed(constructed, model_outcomes())}." if constructed else "."))
    if checks:
        text += (f" {len(checks)} {'check' if len(checks) == 1 else 'checks'} of the tools: "
                 f"{listed(checks, CHECK_OUTCOMES)}.")
    return text


__all__ = ["AGGREGATION_RULE", "AGGREGATION_SENTENCE", "CHECK_OUTCOMES", "PRECEDENCE",
           "ClaimVerdict", "claim_verdicts",
           "combined_outcome", "count_outcomes", "count_sentence", "counted", "model_outcomes",
           "row_unit", "verb"]
