# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The answer on one screen: does TAPMC reproduce Philippe & Bideau, figure by figure.

One :class:`FigureEntry` per figure of the paper (claims of the register without a figure are
grouped by their section), in the register's order. Its outcome follows from the verdicts of
the figure's model claims (one per claim, from its rows: :mod:`tapmc.paper.claims.aggregate`)
by :func:`figure_outcome` (the rule :data:`OUTCOME_RULE` states); claims of kind "check" (the
tools' consistency) are never counted, and a claim that could not fail for any compaction
model (``could_fail = false``) never counts as agreeing. Its key number is the measure of
the claim marked ``headline`` in the register (``claims.toml``), beside the paper's value.
:func:`screen_rst` writes the screen at the top of the validation pages and
:func:`readme_lines` the paragraphs of README.md's "What the validation found", from the same
entries, so the README cannot drift from the page (tests/python/test_paper_summary.py).
"""

from __future__ import annotations

import enum
import math
import re
from dataclasses import dataclass
from pathlib import Path

from ._rst import list_table
from .claims.aggregate import claim_verdicts
from .claims.aggregate import count_sentence as claim_count_sentence
from .claims.rules import Outcome

#: the committed paper-scale page, which README.md's lines summarise and link
PAPER_SCALE_PAGE = "doc/paper_scale/validation.rst"
#: width of a figure's thumbnail in the screen's table: small enough for twelve rows on a
#: screen, large enough to recognise the paper's figure
THUMBNAIL_WIDTH = "160px"
#: the screen's section title (tests find the table by it)
SCREEN_TITLE = "Does TAPMC reproduce the paper?"

#: what each figure (or section, for the claims the text alone makes) of the paper is about
TOPICS = {
    "II": "the model's parameters theta0 and d_max",
    "2": "compaction laws (eq. 3, eq. 4)",
    "3": "fluctuations (spectrum, sigma)",
    "4": "bell curve and hysteresis",
    "5": "ageing",
    "6": "vertical profiles",
    "7": "transversal profiles",
    "8": "lateral and central zones",
    "9": "P0 and the packing fractions",
    "10": "pore distributions",
    "IV.A": "hysteresis of the gradient",
    "IV.B": "hysteresis of the pore density",
}


class FigureOutcome(enum.StrEnum):
    """What the screen says of one figure of the paper."""

    REPRODUCED = "reproduced"
    CAVEAT = "reproduced with a caveat"
    NOT_REPRODUCED = "not reproduced"
    NOT_TESTED = "not tested"


#: the rule of :func:`figure_outcome`, as the page prints it under the table
OUTCOME_RULE = (
    "A figure's outcome follows from the verdicts of its claims about the model (one verdict "
    "per claim, from its rows; checks of the tools are not counted, and a claim that could "
    "not fail for any compaction model counts when it disagrees, never when it agrees): not "
    "tested when no claim is decided; not reproduced when the disagreeing claims are at least "
    "as many as the agreeing ones; reproduced when every decided claim agrees at our "
    "precision and no claim is undecided for want of the paper's scale; reproduced with a "
    "caveat otherwise (some claims disagree, agree only at the paper's precision, or are "
    "undecided for scale).")

#: the outcomes of a claim that count as agreeing with the paper
AGREEING = (Outcome.AGREES, Outcome.AGREES_AT_PAPER_PRECISION)


@dataclass(frozen=True)
class FigureEntry:
    """One figure (or section) of the paper on the screen: ``key`` its figure number or
    section, ``title`` ("Fig. 2" or "Section II"), ``outcome`` and ``reason`` (the counts it
    follows from), ``headline`` (the key number, TAPMC's), ``paper`` (the paper's value beside
    it), ``png`` (the thumbnail, relative to the page; "" without a figure) and
    ``disagreeing`` (the ids of the claims that disagree) and ``claims`` (the verdicts of its
    claims, :class:`~tapmc.paper.claims.aggregate.ClaimVerdict`)."""

    key: str
    title: str
    topic: str
    outcome: FigureOutcome
    reason: str
    headline: str
    paper: str
    png: str
    disagreeing: tuple = ()
    claims: tuple = ()


def _key(claim):
    """The screen entry a claim belongs to: its figure, or its section when the text alone
    makes it."""
    return claim.figure or claim.section


def group_rows(rows):
    """The model rows grouped by figure (or section), in the paper's order: by the section
    of a group's first claim (in the register's order of sections), then by figure number,
    a section's text-only claims after its figures. key -> list of rows; rows of kind
    "check" are left out."""
    groups, sections = {}, {}
    for row in rows:
        sections.setdefault(row.claim.section, len(sections))
        if row.claim.kind == "model":
            groups.setdefault(_key(row.claim), []).append(row)

    def order(item):
        key, group = item
        return sections[group[0].claim.section], int(key) if key.isdigit() else math.inf

    return dict(sorted(groups.items(), key=order))


def figure_outcome(verdicts):
    """(FigureOutcome, reason) of one figure's model claims (their
    :class:`~tapmc.paper.claims.aggregate.ClaimVerdict`) by :data:`OUTCOME_RULE`."""
    agreeing = [v for v in verdicts if v.outcome in AGREEING and v.claim.could_fail]
    loose = sum(1 for v in agreeing if v.outcome != Outcome.AGREES)
    disagree = sum(1 for v in verdicts if v.outcome == Outcome.DISAGREES)
    scale = sum(1 for v in verdicts if v.undecided_for_scale)
    constructed = sum(1 for v in verdicts if v.outcome in AGREEING and not v.claim.could_fail)
    undecided = len(verdicts) - len(agreeing) - disagree - constructed
    agree = len(agreeing)
    reason = (f"{agree} of {len(verdicts)} claims agree"
              + (f" ({loose} at the paper's precision only)" if loose else "")
              + f", {disagree} {'disagrees' if disagree == 1 else 'disagree'}, "
              f"{undecided} undecided" + (f" ({scale} for scale)" if scale else ""))
    if constructed:
        reason += f", {constructed} could not fail"
    if agree + disagree == 0:
        return FigureOutcome.NOT_TESTED, reason
    if disagree >= agree:
        return FigureOutcome.NOT_REPRODUCED, reason
    if disagree == 0 and not scale and not loose:
        return FigureOutcome.REPRODUCED, reason
    return FigureOutcome.CAVEAT, reason


def _short(text):
    """A measure's text up to its first explanation ("; ", " over ", or a parenthesis other
    than the degrees of freedom): the full text is in the table of the page."""
    for mark in ("; ", " over "):
        text = text.split(mark)[0]
    return re.sub(r" \((?!\d+ dof\)).*", "", text)


def headline_row(rows):
    """The row whose measure is a figure's key number: of the claim marked ``headline`` in
    the register (else the first claim), the first row whose label starts with the headline's
    text (when it is one), preferring a row at the paper's scale; None without rows."""
    marked = [r for r in rows if r.claim.headline]
    if not marked:
        marked = [r for r in rows if r.claim.id == rows[0].claim.id] if rows else []
    if not marked:
        return None
    prefix = marked[0].claim.headline
    if isinstance(prefix, str):
        marked = [r for r in marked if r.label.startswith(prefix)] or marked
    return next((r for r in marked if not r.missing_scale), marked[0])


def _headline_text(row):
    if row is None:
        return "n/a"
    label = row.claim.headline if isinstance(row.claim.headline, str) else ""
    if label and not row.label.startswith(label):
        label = ""
    value = _short(row.measure.text())
    return f"{row.claim.id}{' (' + label + ')' if label else ''}: {value}"


def summarise(rows, files):
    """The screen's entries (:class:`FigureEntry`) from the evaluated rows
    (:func:`tapmc.paper.claims.evaluate`) and the figure files of the page (name -> (png,
    csv))."""
    entries = []
    for key, group in group_rows(rows).items():
        verdicts = claim_verdicts(group)
        outcome, reason = figure_outcome(verdicts)
        head = headline_row(group)
        png = files.get(f"fig{key}", ("",))[0]
        disagreeing = tuple(v.claim.id for v in verdicts if v.outcome == Outcome.DISAGREES)
        entries.append(FigureEntry(
            key=key, title=f"Fig. {key}" if key.isdigit() else f"Section {key}",
            topic=TOPICS.get(key, group[0].claim.claim), outcome=outcome, reason=reason,
            headline=_headline_text(head), paper=head.claim.paper if head else "",
            png=f"validation/{Path(png).name}" if png else "", disagreeing=disagreeing,
            claims=tuple(verdicts)))
    return entries


def counts(entries):
    """FigureOutcome -> the number of entries with it, in the enum's order."""
    return {o: sum(1 for e in entries if e.outcome == o) for o in FigureOutcome}


def count_sentence(entries):
    """"Of N figures and sections of the paper: a reproduced, b with a caveat, ..."."""
    n = counts(entries)
    return (f"Of the paper's {len(entries)} figures and sections tested by the register: "
            f"{n[FigureOutcome.REPRODUCED]} reproduced, {n[FigureOutcome.CAVEAT]} reproduced "
            f"with a caveat, {n[FigureOutcome.NOT_REPRODUCED]} not reproduced, "
            f"{n[FigureOutcome.NOT_TESTED]} not tested.")


def claims_sentence(entries):
    """The claim counts of the entries' model claims
    (:func:`tapmc.paper.claims.aggregate.count_sentence`): reproduced physics apart from
    claims that could not fail, every outcome counted."""
    return claim_count_sentence([v for e in entries for v in e.claims])


def open_questions(entries):
    """One sentence per figure with disagreeing rows: the claims that disagree."""
    return [f"{e.title} ({e.topic}; {e.outcome}): {', '.join(e.disagreeing)} "
            f"{'disagrees' if len(e.disagreeing) == 1 else 'disagree'} with the paper."
            for e in entries if e.disagreeing]


def _entry_row(entry):
    image = (f".. image:: {entry.png}\n         :width: {THUMBNAIL_WIDTH}\n"
             f"         :alt: {entry.title}") if entry.png else "(text)"
    return [f"{entry.title}: {entry.topic}", f"**{entry.outcome}** ({entry.reason})",
            entry.headline, entry.paper, image]


#: The central answer's figure and a finding's own figure are shown at their own width (at
#: most the page's: _plotting.PAGE_WIDTH_PX), the size their text is drawn for: shown at 500
#: or 600 pixels, their legends were 5 to 6 pixels high.


def screen_rst(entries, finding="", headline="", figure=None):
    """The one screen, as rst lines: the counts, the central question's answer (``headline``,
    when given, with ``figure``: (page path of its PNG, alt text), when given), one table row
    per entry (outcome, key number, the paper's value, thumbnail), the rule, and the open
    questions (``finding``: a finding or a list of them, e.g. the irreversible branch of
    section III.B with its numbers, first of them when given; a finding may be a pair (text,
    figure), its figure (page path of its PNG, alt text) drawn inside its item)."""
    lines = [SCREEN_TITLE, "-" * len(SCREEN_TITLE), "", count_sentence(entries), "",
             claims_sentence(entries), ""] + ([headline, ""] if headline else [])
    if figure:
        path, alt = figure
        lines += [f".. image:: {path}", f"   :alt: {alt}", ""]
    lines += list_table(["Figure", "Outcome", "Key number (TAPMC)", "Paper", "Figure"],
                        [_entry_row(entry) for entry in entries], widths=(18, 22, 26, 16, 18))
    lines += ["", OUTCOME_RULE, "", "Open questions:", ""]
    findings = [finding] if isinstance(finding, (str, tuple)) else list(finding)
    items = [f if isinstance(f, tuple) else (f, None) for f in findings]
    items = [(text, own) for text, own in items if text]
    items += [(q, None) for q in open_questions(entries)]
    for text, own in items:
        lines.append(f"* {text}")
        if own:  # indented under the item's text: the image belongs to it
            path, alt = own
            lines += ["", f"  .. image:: {path}", f"     :alt: {alt}", ""]
    return lines + ([] if items else ["* none"]) + [""]


#: The central answer's figure as README.md shows it (Markdown; the path from the top).
README_FIGURE = ("![The ramps at the paper's protocol, one panel per eta]"
                 "(doc/paper_scale/validation/questions/paper_ramp.png)")


def readme_lines(entries, headline="", figure=False):
    """The lines of README.md's "What the validation found" (from the paper-scale page's
    entries), one paragraph each: the figures' counts, the claims' counts, the central
    question's answer (``headline``: tapmc.paper.paper_ramp.headline_text, when given; its
    lines, a sentence and a list, become lines of README.md) and its
    figure (``figure``: when its PNG is committed, :data:`README_FIGURE`), the open questions,
    the link."""
    open_titles = [f"{e.title}, {e.topic} ({', '.join(e.disagreeing)})" for e in entries
                   if e.disagreeing]
    central = ([headline] if headline else []) + ([README_FIGURE] if figure else [])
    paragraphs = [count_sentence(entries), claims_sentence(entries), *central,
                  "Open questions, where claims disagree: "
                  + ("; ".join(open_titles) or "none") + ".",
                  f"Every figure, row and rule: [{PAPER_SCALE_PAGE}]({PAPER_SCALE_PAGE})."]
    return [line for p in paragraphs for line in (*p.split("\n"), "")][:-1]


#: README.md's section that :func:`readme_lines` fills: its heading, then a blank line and the
#: comment that says who writes it, then the lines, up to the next "## " heading
README_SECTION = "## What the validation found"
README_PREAMBLE_LINES = 2


def readme_with_lines(text, lines):
    """README.md's ``text`` with the body of :data:`README_SECTION` (after its preamble, up to
    the next "## " heading) replaced by ``lines``; ValueError naming what is missing."""
    old = text.splitlines()
    if README_SECTION not in old:
        raise ValueError(f"no line '{README_SECTION}' (the section the summary is written into)")
    start = old.index(README_SECTION) + 1 + README_PREAMBLE_LINES
    end = next((i for i in range(start, len(old)) if old[i].startswith("## ")), None)
    if end is None:
        raise ValueError(f"no '## ' heading after '{README_SECTION}': the section's end is "
                         "unknown")
    return "\n".join(old[:start] + list(lines) + [""] + old[end:]) + "\n"


__all__ = ["FigureEntry", "FigureOutcome", "OUTCOME_RULE", "summarise", "figure_outcome",
           "screen_rst", "readme_lines", "readme_with_lines", "README_SECTION",
           "open_questions", "counts", "claims_sentence"]
