# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The answer on one screen (tapmc.paper.summary): each figure's outcome follows from its
claims' verdicts (one per claim, from its rows) by the stated rule (synthetic rows with a
known answer for every outcome, and controls that must not pass), the committed pages answer within their first 80 lines with a figure within
150, and README.md's "What the validation found" is what the paper-scale page's data give."""

import os
import shutil
import sys
from pathlib import Path

import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc.paper import paper_ramp, summary, validation  # noqa: E402
from tapmc.paper.claims import Claim, Measure, Row, Verdict  # noqa: E402
from tapmc.paper.claims.aggregate import claim_verdicts  # noqa: E402
from tapmc.paper.claims.rules import Outcome  # noqa: E402
from tapmc.paper.summary import FigureOutcome  # noqa: E402

DOC = SOURCE / "doc"
PAGES = [DOC, DOC / "paper_scale"]
#: "the first screen" of a page and where its first figure must be (issue 42)
FIRST_SCREEN_LINES = 80
FIRST_FIGURE_LINE = 150


def _claim(figure="2", section="III.A", kind="model", ident="c", headline=False,
           could_fail=True):
    return Claim(id=ident, section=section, figure=figure, claim="a claim", paper="paper",
                 kind=kind, statistic="", rule="none", tolerance="a source", decided_by="",
                 headline=headline, could_fail=could_fail)


def _rows(*outcomes, figure="2", kind="model", scale=(), ident="c", could_fail=True):
    """One row per outcome (an Outcome), all of one claim of one figure."""
    claim = _claim(figure=figure, kind=kind, ident=ident, could_fail=could_fail)
    return [Row(claim, f"row {i}", Measure(value=1.0, err=0.1), Verdict(o), scale)
            for i, o in enumerate(outcomes)]


def _verdicts(*outcomes, scale=(), could_fail=True):
    """One claim of one row per outcome: the figure's claims' verdicts."""
    rows = [row for i, o in enumerate(outcomes)
            for row in _rows(o, ident=f"claim{i}", scale=scale, could_fail=could_fail)]
    return claim_verdicts(rows)


A, D, U = Outcome.AGREES, Outcome.DISAGREES, Outcome.UNDECIDED
P = Outcome.AGREES_AT_PAPER_PRECISION


@pytest.mark.parametrize("outcomes, scale, expected", [
    ((A, A, A), (), FigureOutcome.REPRODUCED),
    ((A, U), (), FigureOutcome.REPRODUCED),            # undecided for want of seeds only
    ((A, A, D), (), FigureOutcome.CAVEAT),
    ((A, P), (), FigureOutcome.CAVEAT),                 # agrees only at the paper's precision
    ((A, U), ("size",), FigureOutcome.CAVEAT),          # undecided for scale
    ((A, D), (), FigureOutcome.NOT_REPRODUCED),         # a tie is no reproduction
    ((D, D, A), (), FigureOutcome.NOT_REPRODUCED),
    ((U, U), (), FigureOutcome.NOT_TESTED),
    ((U,), ("taps",), FigureOutcome.NOT_TESTED),
])
def test_figure_outcome_follows_the_rule(outcomes, scale, expected):
    assert summary.figure_outcome(_verdicts(*outcomes, scale=scale))[0] == expected


@pytest.mark.parametrize("n", [1, 2, 5])
def test_control_a_figure_whose_claims_all_disagree_is_never_reproduced(n):
    outcome, reason = summary.figure_outcome(_verdicts(*[D] * n))
    assert outcome == FigureOutcome.NOT_REPRODUCED
    assert f"{n} {'disagrees' if n == 1 else 'disagree'}" in reason


def test_a_figure_counts_claims_not_rows():
    """Ten agreeing rows of one claim weigh as much as the one row of another claim: one
    claim each, so one agreeing and one disagreeing claim are a tie, not reproduced."""
    rows = _rows(*[A] * 10, ident="many") + _rows(D, ident="one")
    entries = summary.summarise(rows, {})
    assert entries[0].outcome == FigureOutcome.NOT_REPRODUCED
    assert entries[0].reason.startswith("1 of 2 claims agree, 1 disagrees")


def test_claims_that_could_not_fail_are_never_counted_as_agreeing():
    """A claim any compaction model satisfies is no reproduction: a figure of such claims
    alone is not tested, and they do not outweigh a disagreeing claim."""
    assert summary.figure_outcome(_verdicts(A, A, could_fail=False))[0] == \
        FigureOutcome.NOT_TESTED
    rows = _rows(A, ident="built", could_fail=False) + _rows(A, ident="built2", could_fail=False)
    rows += _rows(D, ident="physics") + _rows(A, ident="physics2")
    outcome, reason = summary.figure_outcome(claim_verdicts(rows))
    assert outcome == FigureOutcome.NOT_REPRODUCED and "2 could not fail" in reason


def test_checks_are_never_counted():
    """A figure's check rows (the tools' consistency) neither make nor change its outcome."""
    checks = _rows(Outcome.FAILS, Outcome.HOLDS, figure="10", kind="check", ident="check")
    assert summary.summarise(checks, {}) == []
    entries = summary.summarise(_rows(A, figure="10") + checks, {})
    assert [e.outcome for e in entries] == [FigureOutcome.REPRODUCED]
    assert entries[0].reason.startswith("1 of 1 claims agree")


def test_entries_follow_the_paper_order_with_thumbnails_and_headlines():
    text = _claim(figure="", section="II", ident="text-claim")
    later = _claim(figure="10", section="IV.B", ident="pores")
    head = _claim(figure="2", section="III.A", ident="eq3", headline="eps = 0.05")
    rows = [Row(text, "", Measure(), Verdict(U), ()),     # the register's order of sections
            Row(_claim(figure="3", ident="third"), "", Measure(), Verdict(A), ()),
            Row(_claim(ident="first"), "", Measure(value=3.0, err=1.0), Verdict(A), ()),
            Row(head, "eps = 0.005", Measure(value=4.0, err=1.0), Verdict(A), ()),
            Row(head, "eps = 0.05, after", Measure(value=5.0, err=1.0), Verdict(A), ()),
            Row(later, "", Measure(value=2.0, err=0.5), Verdict(D), ())]
    files = {"fig2": (Path("x/fig2.png"), Path("x/fig2.csv"))}
    entries = summary.summarise(rows, files)
    assert [e.key for e in entries] == ["II", "2", "3", "10"]   # figures by number
    assert [e.png for e in entries] == ["", "validation/fig2.png", "", ""]
    assert entries[1].headline == "eq3 (eps = 0.05): 5 ± 1"
    assert entries[3].disagreeing == ("pores",)
    rst = "\n".join(summary.screen_rst(entries, "a finding."))
    assert ".. image:: validation/fig2.png" in rst and summary.OUTCOME_RULE in rst
    assert "* a finding." in rst
    assert "Fig. 10 (pore distributions; not reproduced): pores disagrees" in rst
    # the central answer's figure follows its sentence, before the table; none without one
    lines = summary.screen_rst(entries, "a finding.", "The answer.", ("q/ramps.png", "ramps"))
    at = lines.index("The answer.")
    # at its own width (at most the page's): its text is drawn for that size
    assert lines[at + 2:at + 5] == [".. image:: q/ramps.png", "   :alt: ramps", ""]
    assert lines[at + 5].startswith(".. list-table::")
    assert not any("q/ramps.png" in line for line in summary.screen_rst(entries, "", "The answer."))
    # a finding with its own figure: the image indented under that item, the next item after
    lines = summary.screen_rst(entries, ["a finding.", ("sigma.", ("q/sigma.png", "sigma")), ""])
    at = lines.index("* sigma.")
    assert lines[at - 1] == "* a finding."
    assert lines[at + 1:at + 5] == ["", "  .. image:: q/sigma.png", "     :alt: sigma", ""]
    assert lines[at + 5].startswith("* Fig. 10")
    assert "* none" in summary.screen_rst(summary.summarise(rows[:1], {}), "")


def _entries(page):
    return validation.page_entries(*validation.committed_inputs(page))


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_the_page_answers_on_its_first_screen(page):
    lines = (page / "validation.rst").read_text().splitlines()
    title = lines.index(summary.SCREEN_TITLE) + 1
    table = next(i for i, line in enumerate(lines, 1)
                 if i > title and line.startswith(".. list-table::"))
    counts = next(i for i, line in enumerate(lines, 1) if line.startswith("Of the paper's "))
    image = next(i for i, line in enumerate(lines, 1) if ".. image::" in line)
    assert max(title, counts, table) <= FIRST_SCREEN_LINES, (title, counts, table)
    assert image <= FIRST_FIGURE_LINE, image
    entries = _entries(page)
    assert lines[counts - 1] == summary.count_sentence(entries)
    assert lines.index(summary.claims_sentence(entries)) + 1 <= FIRST_SCREEN_LINES


def test_readme_says_what_the_paper_scale_page_found():
    page = DOC / "paper_scale"
    ramps = page / "validation" / "questions" / paper_ramp.CSV_NAME
    headline = validation.paper_ramp_headline(*validation.committed_inputs(page))
    figure = (ramps.parent / paper_ramp.PNG_NAME).is_file()
    expected = summary.readme_lines(_entries(page), headline, figure)
    assert validation.readme_lines(page) == expected
    assert (summary.README_FIGURE in expected) == figure
    readme = (SOURCE / "README.md").read_text().splitlines()
    start = readme.index("## What the validation found") + 3   # the heading, a line, a comment
    assert readme[start:start + len(expected)] == expected, (
        "README.md's 'What the validation found' differs from the paper-scale page: run "
        "'tapmc-paper report --from-data --out doc/paper_scale --readme README.md'")
    assert readme[start + len(expected)] == "" and readme[start + len(expected) + 1][:3] == "## "
    assert "[doc/paper_scale/validation.rst](doc/paper_scale/validation.rst)" in expected[-1]


def test_readme_section_is_replaced_up_to_the_next_heading():
    """The section's body, after the heading and its two preamble lines, is replaced up to the
    next '## ' heading; the rest of the file stays; a README without the section, or without
    a heading after it, is refused naming what is missing."""
    text = "# T\n\n## What the validation found\n\n<!-- c -->\nold 1\nold 2\n\n## Next\nx\n"
    assert summary.readme_with_lines(text, ["new"]) == (
        "# T\n\n## What the validation found\n\n<!-- c -->\nnew\n\n## Next\nx\n")
    with pytest.raises(ValueError, match="no line '## What the validation found'"):
        summary.readme_with_lines("# T\n", ["new"])
    with pytest.raises(ValueError, match="no '## ' heading after"):
        summary.readme_with_lines("## What the validation found\n\n<!-- c -->\nold\n", ["x"])


def test_report_from_data_writes_the_readme_section(tmp_path, capsys):
    """``report --from-data --readme``: the section of a README copy is the page's lines; a
    README without the section: exit 2 naming it, the file as it was."""
    from tapmc.paper import cli
    page = tmp_path / "page"
    shutil.copytree(DOC / "paper_scale", page)
    readme = tmp_path / "README.md"
    readme.write_text("# TAPMC\n\n## What the validation found\n\n<!-- c -->\nstale\n\n"
                      "## Reproducing\nkept\n")
    assert cli.main(["report", "--from-data", "--out", str(page), "--readme",
                     str(readme)]) == 0
    lines = readme.read_text().splitlines()
    assert lines[5:5 + len(validation.readme_lines(page))] == validation.readme_lines(page)
    assert "stale" not in lines and lines[-2:] == ["## Reproducing", "kept"]
    readme.write_text("# no section\n")
    assert cli.main(["report", "--from-data", "--out", str(page), "--readme",
                     str(readme)]) == 2
    assert "no line '## What the validation found'" in capsys.readouterr().err
    assert readme.read_text() == "# no section\n"
