# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""One verdict per claim (tapmc.paper.claims.aggregate): a claim's verdict follows from its
rows by the stated rule, on synthetic rows with a known answer (a control that must agree, one
that must fail), every outcome of the Outcome enum is counted, and every claim of the register
gets exactly one verdict on the committed pages."""

import os
import sys
from pathlib import Path

import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc.paper.claims import Claim, Measure, Row, Verdict  # noqa: E402
from tapmc.paper.claims import aggregate  # noqa: E402
from tapmc.paper.claims.aggregate import (  # noqa: E402
    AGGREGATION_RULE, ClaimVerdict, claim_verdicts, combined_outcome, count_sentence,
    model_outcomes)
from tapmc.paper.claims.rules import Outcome  # noqa: E402

A, D, U = Outcome.AGREES, Outcome.DISAGREES, Outcome.UNDECIDED
P = Outcome.AGREES_AT_PAPER_PRECISION


def _claim(ident="c", kind="model", could_fail=True, headline=False):
    return Claim(id=ident, section="III.A", figure="3", claim="a claim", paper="paper",
                 kind=kind, statistic="", rule="none", tolerance="a source", decided_by="",
                 headline=headline, could_fail=could_fail)


def _rows(outcomes, ident="c", labels=None, scale=(), **fields):
    claim = _claim(ident, **fields)
    labels = labels or [f"eps = {0.01 * (i + 1):g}" for i in range(len(outcomes))]
    return [Row(claim, label, Measure(value=-1.2, err=0.1), Verdict(o), scale)
            for label, o in zip(labels, outcomes)]


def _one(outcomes, **kw):
    (verdict,) = claim_verdicts(_rows(outcomes, **kw))
    return verdict


def test_control_every_eps_within_the_band_agrees():
    """The control that must agree: ten eps, each agreeing (as Fig. 3's spectral slopes
    within [-1.5, -1])."""
    verdict = _one([A] * 10)
    assert verdict.outcome == A
    assert verdict.text() == "agrees (10 of 10 eps agree)"


def test_control_one_eps_beyond_its_band_makes_the_claim_disagree():
    """The control that must fail: nine agreeing eps do not outvote one contradicted eps (a
    majority rule would pass it)."""
    verdict = _one([A] * 9 + [D])
    assert verdict.outcome == D
    assert verdict.text() == "disagrees (1 of 10 eps disagrees, 9 agree)"


@pytest.mark.parametrize("outcomes, expected", [
    ((A,), A),
    ((A, U, U), A),              # undecided rows do not change a decided verdict
    ((U, U), U),                 # nothing decided
    ((A, P), P),                 # agreement at the paper's precision only is the weaker
    ((P, D), D),
    ((D, U), D),
    ((Outcome.HOLDS, Outcome.FAILS), Outcome.FAILS),   # a check fails when any row fails
    ((Outcome.HOLDS, Outcome.HOLDS), Outcome.HOLDS),
])
def test_the_claims_outcome_follows_the_rule(outcomes, expected):
    assert combined_outcome(outcomes) == expected


def test_every_decided_outcome_has_a_precedence():
    """An outcome added to the enum must be placed in the rule, not silently ignored."""
    assert set(aggregate.PRECEDENCE) | {U} == set(Outcome)
    text = count_sentence(claim_verdicts(_rows([A])))
    assert all(aggregate.counted(o, 0) in text for o in model_outcomes())


def test_the_counts_are_claims_and_keep_claims_that_could_not_fail_apart():
    rows = (_rows([A] * 10, ident="slopes") + _rows([D, A], ident="laws")
            + _rows([P], ident="precision") + _rows([U], ident="open")
            + _rows([A], ident="built", could_fail=False)
            + _rows([Outcome.HOLDS], ident="check", kind="check"))
    text = count_sentence(claim_verdicts(rows))
    assert text.startswith("5 claims of the paper about the model, measured in 15 rows. "
                           "Of the 4 claims that could fail: 1 agrees; 1 agrees at the paper's "
                           "precision, not at ours; 1 disagrees; 1 undecided.")
    assert "1 claim could not fail for any compaction model and is not counted as " \
           "reproduction: 1 agrees;" in text
    assert "1 check of the tools: 1 holds; 0 fail." in text


def test_rows_group_by_claim_in_the_register_order():
    rows = _rows([A], ident="b") + _rows([D], ident="a") + _rows([U], ident="b", labels=["x"])
    verdicts = claim_verdicts(rows)
    assert [v.claim.id for v in verdicts] == ["b", "a"]
    assert [len(v.rows) for v in verdicts] == [2, 1]
    assert verdicts[0].outcome == A and verdicts[0].reason == "1 of 2 rows agrees, 1 undecided"


def test_the_shown_row_is_the_one_the_verdict_rests_on():
    verdict = _one([A, D, A])
    assert verdict.shown_row() is verdict.rows[1]
    marked = _one([A, A], headline="eps = 0.02")
    assert marked.shown_row() is marked.rows[1]
    assert isinstance(marked, ClaimVerdict) and marked.missing_scale == ()
    lacking = _one([U, U], scale=("size",))
    assert lacking.undecided_for_scale and lacking.missing_scale == ("size",)
    # of the rows with the claim's outcome, one at the paper's scale comes first (a ramp at
    # 4000 taps per level before the campaign's at 1000)
    short, full = _rows([D], labels=["1000 taps"], scale=("ramp_taps",)), _rows([D, D])
    (both,) = claim_verdicts(short + full)
    assert both.shown_row() is both.rows[1]
    # ... unless it has no value yet (a ramp at the paper's scale still going up): the row
    # with a number comes first
    pending = Row(short[0].claim, "4000 taps", Measure(), Verdict(U), ())
    (waiting,) = claim_verdicts(_rows([U], labels=["1000 taps"], scale=("ramp_taps",))
                                + [pending])
    assert waiting.shown_row() is waiting.rows[0]
    (alone,) = claim_verdicts([pending])
    assert alone.shown_row() is pending


def test_the_rule_is_stated_as_it_is_applied():
    assert "disagrees when any of its rows disagrees" in AGGREGATION_RULE
    assert "undecided when no row is decided" in AGGREGATION_RULE
