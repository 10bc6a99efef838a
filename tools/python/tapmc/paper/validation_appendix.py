# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The appendix pages of the validation report, written by ``tapmc-paper report`` beside
its main page (:mod:`tapmc.paper.validation`) and linked from it: every row of every claim
(the per-eps, per-run and per-level detail behind each claim's one verdict), the claims
register, the rules of the verdicts, the calibrations of the errors with the integrity check
and the campaign's runs, and the questions settled by measurement. :data:`APPENDICES` names them; each is rendered from
the same rows and CSVs as the main page, so the pages cannot disagree.
"""

from __future__ import annotations

from tapmc.fluctuations import DEFAULT_BATCHES
from tapmc.pores import JACKKNIFE_BLOCKS
from tapmc.profiles import PROFILE_JACKKNIFE_BLOCKS

from . import claims, questions
from ._rst import list_table
from .claims.aggregate import AGGREGATION_RULE

HEADER = ".. TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS."

#: appendix page (its file name without .rst, beside the main page) -> its title
APPENDICES = {
    "validation_claims": "Every row of every claim",
    "validation_register": "The claims register",
    "validation_rules": "The rules of the verdicts",
    "validation_checks": "Calibrations of the errors, the integrity check and the runs",
    "validation_questions": "Questions settled by measurement",
}

#: how a value of one run per point (the paper's protocol) gets its error, stated with the rules
ONE_RUN_ERRORS = (
    "Errors of one run per point (the paper's protocol), where seeds give none: a time average "
    f"(steady state, zone means, halves) has the batch-means error over its taps "
    f"({DEFAULT_BATCHES} batches; t with {DEFAULT_BATCHES - 1} degrees of freedom); a quantity "
    "of one packing has the spatial jackknife over lateral blocks of the packing (pores: "
    f"{JACKKNIFE_BLOCKS} x {JACKKNIFE_BLOCKS} blocks, {JACKKNIFE_BLOCKS ** 2 - 1} degrees of "
    f"freedom; the profile's gradient alpha: {PROFILE_JACKKNIFE_BLOCKS} x "
    f"{PROFILE_JACKKNIFE_BLOCKS}, {PROFILE_JACKKNIFE_BLOCKS ** 2 - 1}); a spectrum has the "
    "periodogram's own errors, known exactly "
    "(the normal quantile); where one packing cannot give an error (P0, the initial packing, the "
    "paper's F.B.C. start) the configurations of tapmc-paper question give it, as the row "
    "says. These errors are within one realization: the spread between realizations is not in "
    "them.")

#: what the "Paper scale?" column says, stated with the rules
PAPER_SCALE_NOTE = (
    "\"Paper scale?\" says whether the campaign (or, for a measurement of its own such as a "
    "knob scan, its runs) had what the claim needs of the paper's scale (size: N = 4096 in a "
    "32R box; taps: 4000 per run; ramp_taps: 4000 per level; eta: 1e-7); without it the "
    "statistic is shown and the verdict is undecided. One exception: a ramp of fewer taps per "
    "level decides a claim of <Phi^c> on its branches when ``tapmc-paper question "
    "ramp-levels`` measured how far 4000 taps per level move the levels (two levels or more "
    "of every branch the claim reads, of the ramp the claim reads; the shifts +- their t error "
    "span a branch's range; a difference of two branches moves by the difference of their "
    "ranges; a ramp's turning level counts alone; the critical (sqrt eps)*: every ramp's "
    "change on the way down within its own range) and the verdict is the same anywhere within "
    "that range; the verdict says so.")


def where(claim):
    """The claim's place in the paper: its section, and its figure when it has one."""
    return f"{claim.section}" + (f", Fig. {claim.figure}" if claim.figure else "")


def escape_bars(text):
    """Text with its | escaped for reStructuredText (|value| is no substitution)."""
    return text.replace("|", "\\|")


def claim_label(prefix, claim_id):
    """The rst label of a claim's rows on the claims' appendix page; ``prefix`` keeps the
    labels of the two reports (two folders of one documentation) apart."""
    return f"{prefix}-claim-{claim_id}"


def scale_text(rows):
    """"yes", or "no: <aspects>" (with how many rows lack them when not all do)."""
    lacking = [r for r in rows if r.missing_scale]
    if not lacking:
        return "yes"
    aspects = ", ".join(dict.fromkeys(a for r in lacking for a in r.missing_scale))
    share = "" if len(lacking) == len(rows) else f" ({len(lacking)} of {len(rows)} rows)"
    return f"no: {aspects}{share}"


def _page(name, lines):
    title = APPENDICES[name]
    return "\n".join([HEADER, "", title, "=" * len(title), ""] + lines).rstrip() + "\n"


def _back(main):
    return [f"An appendix of :doc:`{main}`, written with it by ``tapmc-paper report`` from the "
            "same committed data.", ""]


def claims_page(verdicts, prefix, main):
    """Every claim with the table of its rows (one per eps, run, level or reading) and the
    verdict they give it (:data:`~tapmc.paper.claims.aggregate.AGGREGATION_RULE`)."""
    lines = _back(main) + [AGGREGATION_RULE, ""]
    for verdict in verdicts:
        c = verdict.claim
        title = f"``{c.id}``"
        lines += [f".. _{claim_label(prefix, c.id)}:", "", title, "-" * len(title), "",
                  f"{where(c)}: {escape_bars(c.claim)}. Paper: {escape_bars(c.paper)}.", "",
                  f"Verdict: **{escape_bars(verdict.text())}** [{c.rule}]"
                  + ("; this claim could not fail for any compaction model and is not counted "
                     "as reproduction." if not c.could_fail else "."), ""]
        lines += list_table(["Row", "TAPMC", "Paper scale?", "Verdict"],
                            [[escape_bars(row.label) or '(the claim)',
                              escape_bars(row.measure.text()), scale_text([row]),
                              escape_bars(str(row.verdict))] for row in verdict.rows],
                            widths=(30, 34, 10, 26)) + [""]
    return _page("validation_claims", lines)


def register_page(verdicts, main):
    """Where each claim's tolerance comes from and which runs decide it (one line a claim)."""
    lines = _back(main) + [
        "The register is ``tools/python/tapmc/paper/claims.toml``: every claim of the paper, "
        "with the statistic that tests it, where its tolerance comes from and the runs that "
        "decide it.", ""]
    lines += list_table(["Claim", "Where", "Statistic", "Tolerance from", "Decided by"],
                        [[f"``{v.claim.id}``", where(v.claim),
                          f"``{v.claim.statistic}``" if v.claim.statistic else "(none yet)",
                          v.claim.tolerance, v.claim.decided_by] for v in verdicts],
                        widths=(14, 8, 22, 28, 28))
    return _page("validation_register", lines)


def rules_page(verdicts, run_note, main, tolerances=()):
    """How a claim's verdict follows from its rows, the rules of the rows' verdicts (those
    the claims use), the errors of one run, what "Paper scale?" means, and the table of the
    conventions with their sources and sensitivities (``tolerances``: rst lines of
    :func:`tapmc.paper.claims.tolerance_table`)."""
    used = list(dict.fromkeys(v.claim.rule for v in verdicts))
    lines = _back(main) + [
        AGGREGATION_RULE, "",
        "Rules of the rows' verdicts (t: the two-sided 95 % quantile of Student's t with the "
        "measure's degrees of freedom, seeds - 1 for a mean over seeds):", ""]
    lines += [f"* [{key}] {escape_bars(claims.RULES[key].text)}" for key in used]
    lines += ["", ONE_RUN_ERRORS + (" " + run_note if run_note else ""), "", PAPER_SCALE_NOTE,
              ""]
    lines += list(tolerances)
    return _page("validation_rules", lines)


def questions_page(name, folder, groups, main):
    """The page of one group of the questions (``checks`` or ``questions``:
    :func:`tapmc.paper.questions.render_parts`)."""
    group = "checks" if name == "validation_checks" else "questions"
    body = groups.get(group, [])
    if not body:
        return _page(name, _back(main) + ["This campaign has no measurement of these "
                                          "(``tapmc-paper question NAME``)."])
    return _page(name, _back(main) + [questions.introduction(folder), ""] + body)


def render_appendices(verdicts, run_note, prefix, folder, groups, main="validation",
                      tolerances=()):
    """name -> the text of every appendix page (:data:`APPENDICES`): ``verdicts`` the claims'
    verdicts, ``run_note`` how one-run errors were scaled, ``prefix`` the claims' label
    prefix, ``folder`` the questions' CSV folder (None without one) and ``groups`` its rendered
    groups (:func:`tapmc.paper.questions.render_parts`), ``tolerances`` the conventions'
    table for the rules page."""
    pages = {"validation_claims": claims_page(verdicts, prefix, main),
             "validation_register": register_page(verdicts, main),
             "validation_rules": rules_page(verdicts, run_note, main, tolerances)}
    for name in ("validation_checks", "validation_questions"):
        pages[name] = questions_page(name, folder, groups, main)
    return pages


__all__ = ["APPENDICES", "ONE_RUN_ERRORS", "PAPER_SCALE_NOTE", "claim_label", "render_appendices",
           "scale_text", "where"]
