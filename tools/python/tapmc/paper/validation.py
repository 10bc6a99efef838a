# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The validation report (``tapmc-paper report``): the numbers of Philippe & Bideau next to
TAPMC's, computed from a campaign, written as ``validation.rst`` with the figures embedded,
and its appendix pages beside it (:mod:`tapmc.paper.validation_appendix`).

The rows are the claims register (``tapmc/paper/claims.toml``, :mod:`tapmc.paper.claims`):
every claim of the paper with the statistic that tests it, its rule, where its tolerance comes
from and the runs that decide it. Every verdict is computed from the figure CSVs by the rule
of its appendix (:data:`RULES`); nothing is written by hand. Verdicts use Student's t
quantile for the measure's degrees of freedom (seeds - 1), so two seeds decide only large
effects, and a claim the data cannot decide is reported "undecided", with the reason. The main
page shows the answer on one screen (:mod:`tapmc.paper.summary`), then one row per claim, its
verdict following from its rows (:mod:`tapmc.paper.claims.aggregate`), then the figures; a
campaign below the paper's size gives a smoke test of the same claims.
"""

from __future__ import annotations

import json
import math
import re
import shutil
from collections import Counter
from importlib import import_module
from pathlib import Path

import numpy as np

from tapmc.readers import TapmcFormatError

from . import FIGURES
from . import _plotting as P
from . import _runs
from ._rst import list_table
from . import claims, paper_ramp, questions, redraw, sigma_eta
from . import summary as summary_screen
from .claims import fmt, scale_aspects
from .claims.aggregate import AGGREGATION_SENTENCE, claim_verdicts
from .claims.common import campaign_eta
from .front import bias_sentence  # what the redeposition setting costs in accuracy
from .front import read_summary as read_front_summary
from .scales import SCALES
from .validation_appendix import (APPENDICES, claim_label, escape_bars, render_appendices,
                                  scale_text, where)

#: the text of each rule of tapmc.paper.claims, as the report prints it (each rule's own
#: text: tapmc.paper.claims.rules).
RULES = {name: rule.text for name, rule in claims.RULES.items()}

FIG_DIR = _runs.FIG_DIR


#: the campaign's facts the report needs beyond the figure CSVs, kept next to them so that the
#: report can be rewritten from committed data alone (:func:`regenerate`).
SUMMARY_FILE = "report.json"
#: Scale fields listed for a scale that is no preset.
_SCALE_KEYS = ("taps", "steady_last", "fig2_eps", "steady sqrt(eps)", "ramp_sqrt0",
               "ramp_dsqrt", "ramp_levels", "ramp_taps_per_level", "ageing_eps",
               "ageing_taps", "ageing_waiting_times", "profile_eps", "pore_eps", "dump_times")


def campaign_summary(campaign):
    """What the report says of the campaign itself (a JSON-ready dict): its scale, sizes,
    runs, taps, seeds, eta and stop rules, the settings of each figure's own runs
    (``figures``, which its settings line states) and the initial <Phi^c> of its P.B.C.
    packings."""
    specs = campaign.runs
    scale = _runs.campaign_scale(campaign)
    preset = scale is not None and scale.name in SCALES and SCALES[scale.name] == scale
    fields = None
    if scale is not None and not preset:
        fields = scale.as_dict()
        fields["steady sqrt(eps)"] = tuple(round(math.sqrt(e), 4) for e in scale.steady_eps)
        fields = {k: fields[k] for k in _SCALE_KEYS}
    return {
        "scale": None if scale is None else scale.name,
        "preset": preset,
        "fields": fields,
        "sizes": sorted({(int(s.variables["N"]), float(s.variables["L"])) for s in specs
                         if "N" in s.variables}),
        "runs": len(specs),
        "taps": sorted({int(s.taps) for s in specs if s.taps is not None}),
        "seeds": len({s.seed for s in specs}),
        "seeds_per_point": _seeds_per_point(specs),
        "eta": sorted({float(s.variables["eta"]) for s in specs if "eta" in s.variables}),
        "ramp_taps_per_level": _ramp_taps_per_level(specs),
        "stop": sorted({P.stop_rule(P.settle_keys(s)) for s in specs}),
        "figures": redraw.campaign_figure_settings(campaign),
        "initial_phi_c": list(_initial_phi(campaign)),
    }


def _ramp_taps_per_level(specs):
    """The taps per level of the campaign's ramps (in.ramp's P), sorted: what the ramp ran
    with, which the paper-scale plan reduces below its preset's (``plan.py``)."""
    return sorted({int(s.variables["P"]) for s in specs
                   if s.input.name == "in.ramp" and "P" in s.variables})


def _seeds_per_point(specs):
    """[fewest, most] realizations of one point: runs whose names differ only in their
    ``_s<seed>`` ending are one point (a campaign under way has more seeds at some points)."""
    counts = Counter(re.sub(r"_s\d+$", "", s.name) for s in specs)
    return [min(counts.values()), max(counts.values())] if counts else [0, 0]


def _seeds_text(summary):
    low, high = summary.get("seeds_per_point") or (summary["seeds"], summary["seeds"])
    seeds = f"{low}" if low == high else f"{low} to {high}"
    return f"{seeds} {'seed' if high == 1 else 'seeds'} per point"


def describe_scale(summary, paper_ramps=False):
    """The scale that was run, from :func:`campaign_summary`; ``paper_ramps``: the page also
    answers section III.B's question from ramps at the paper's 4000 taps per level (run
    apart from the figures' ramps: :mod:`tapmc.paper.paper_ramp`)."""
    size = ", ".join(f"N = {n} spheres in a {l:g}R x {l:g}R box" for n, l in summary["sizes"])
    if summary["scale"] is None:
        name = "a scale of no preset"
    elif summary["preset"]:
        name = f"the ``{summary['scale']}`` preset"
    else:
        name = f"the scale ``{summary['scale']}``"
    text = (f"Scale: {name} ({size}; {summary['runs']} runs of "
            f"{', '.join(map(str, summary['taps']))} taps; {_seeds_text(summary)}; "
            f"redeposition threshold eta = {', '.join(f'{e:g}' for e in summary['eta'])}"
            + "".join(f", {stop}" for stop in summary.get("stop") or ()) + "). "
            "The paper used N = 4096, L = 32R and 4000 taps, one run per point from the same "
            "initial packing (section III.B), and 10 realizations for the ageing of Fig. 5 "
            "(section III.C).")
    per_level = summary.get("ramp_taps_per_level")
    if per_level:
        text += (f" The ramps of Fig. 4 have {', '.join(map(str, per_level))} taps per level "
                 "(the paper: 4000)" + ("; ramps of their own at the paper's 4000 taps per "
                                        "level answer section III.B's question below."
                                        if paper_ramps else "."))
    if summary.get("planned_runs"):
        text += (f" The campaign is under way: {summary['runs']} of its "
                 f"{summary['planned_runs']} runs have finished, and this page is drawn from "
                 "them alone; the claims whose runs are missing are undecided.")
    if summary["fields"]:
        fields = {k: tuple(v) if isinstance(v, list) else v
                  for k, v in summary["fields"].items()}
        text += (" Its fields (a ``Scale.replace`` of the quick preset, recorded in the "
                 "campaign's ``scale.json``): "
                 + "; ".join(f"{k} = {fields[k]}" for k in _SCALE_KEYS) + ".")

    for eta in summary["eta"]:
        text += " " + bias_sentence(eta)
    return text


def _initial_phi(campaign):
    """<Phi^c> of the initial P.B.C. packings, one per packing seed: (mean, sem, n)."""
    per_seed = {}
    for spec in _runs.select(campaign, "const_", bc="pbc"):
        if spec.seed not in per_seed:
            per_seed[spec.seed] = [float(_runs.taps_table(campaign, spec)["phi_c"][0])]
    if not per_seed:
        return np.nan, np.nan, 0
    m, s, n = P.seed_stats(list(per_seed.values()))
    return float(m[0]), float(s[0]), int(n[0])


def _collect(drawn, out_dir):
    """Move (or draw) the figure files into out_dir/validation; returns name -> (png, csv)
    relative to out_dir."""
    target = Path(out_dir) / FIG_DIR
    target.mkdir(parents=True, exist_ok=True)
    out = {}
    for name, paths in drawn.items():
        moved = []
        for path in paths:
            path = Path(path)
            dest = target / path.name
            if path.resolve() != dest.resolve():
                shutil.move(str(path), dest)
            moved.append(dest)
        out[name] = tuple(moved)
    return out


def _eq3_note(fig):
    """Fig. 2: the eq. 3 parameters per eps; an undetermined parameter is named, not given a
    number with an error the fit did not measure."""
    lines = []
    eps_list = sorted({float(s.split("=")[1].split(":")[0]) for s in fig.series("params")})
    for eps in eps_list:
        tag = f"eps={P.fmt_eps(eps)}"
        parts = []
        for name in ("X_inf", "dX_inf", "B", "tau"):
            value, err, determined = fig.param(f"{tag}:{name}")
            parts.append(f"{name} = {fmt(value, err, digits=4)}" if determined
                         else f"{name} undetermined")
        chi = fig.param(f"{tag}:reduced_chi2")[0]
        curve = fig.get("a", tag)
        one_run = curve is not None and np.nanmax(curve[3]) < 2
        # an unweighted fit's "reduced chi2" is its mean squared residual
        quality = f"rms residual {fmt(np.sqrt(chi))}" if one_run else f"reduced chi2 {fmt(chi)}"
        lines.append(f"* eps = {eps:g}: {', '.join(parts)}; {quality}")
    if not lines:
        return None
    return ("Eq. 3 fits of Fig. 2's curves (one run per eps, or the mean over seeds). Their "
            "errors treat the taps as independent, which they are not (Fig. 3), so they are too "
            "narrow; the claims' table tests the laws across independent realizations where "
            "there are some:\n\n" + "\n".join(lines))


def _sigma_note(fig):
    k, ks, _ = fig.param("k")
    chi = fig.param("k_reduced_chi2")[0]
    if not np.isfinite(k):
        return None
    return f"Proportional fit of sigma_<Z>: k = {fmt(k, ks)}; reduced chi2 {fmt(chi)}."


def _gradient_note(fig):
    lo, hi = fig.param("window_lo")[0], fig.param("window_hi")[0]
    mi, si, _ = fig.param("initial:alpha")
    if not np.isfinite(lo):
        return None
    return f"Gradient window {lo:.3g} <= z/R <= {hi:.3g}; initial packing: alpha = {fmt(mi, si)}."


def _ageing_note(fig):
    chi, _, det = fig.param("collapse:reduced_chi2")
    if not np.isfinite(chi):
        return None
    return (f"One eq. 6 for the unscaled curves of all waiting times: reduced chi2 {fmt(chi)}"
            f"{'' if det else ' (parameters not determined)'}.")


#: figure -> the note printed under it (facts of the figure that are no claim of their own).
_NOTES = {"fig2": _eq3_note, "fig3": _sigma_note, "fig6": _gradient_note, "fig5": _ageing_note}


def report_errors(out_dir, reader):
    """``reader.errors_from_report`` (``paper_ramp`` or ``sigma_eta``: the errors its finding
    is decided with) of the report already written to ``out_dir``, the errors of its page;
    None when out_dir holds no report."""
    try:
        summary, files = committed_inputs(out_dir)
    except FileNotFoundError:
        return None
    return reader.errors_from_report(claims.ReportData.from_files(summary, files))


def paper_ramp_headline(summary, files):
    """The central question's answer (a sentence, then a bullet per eta: README.md's too),
    with the errors the page decides it with; "" without questions/paper_ramp.csv."""
    path = _finding_csv(files, paper_ramp.CSV_NAME)
    if path is None:
        return ""
    factor = paper_ramp.errors_from_report(claims.ReportData.from_files(summary, files))
    return paper_ramp.headline_text(paper_ramp.read_csv(path), campaign_eta(summary), factor)


def _rows_and_notes(summary, files):
    """The register's rows evaluated on the figure CSVs (tapmc.paper.claims.evaluate), the
    note of each figure, the figures written, the note on one-run errors and the report data
    (whose realizations' factors the findings' errors take)."""
    data = claims.ReportData.from_files(summary, files)
    rows = claims.evaluate(claims.load_register(), data)
    notes = {}
    for name, note in _NOTES.items():
        fig = data.figure(name)
        text = note(fig) if fig is not None else None
        if text:
            notes[name] = text
    return rows, notes, data.written, data.run_error_note(), data


CAPTIONS = {
    "fig2": "Phi_b against taps (F.B.C.), logarithmic (top) and linear (middle) time, and <Z> "
            "against taps (bottom); dotted: eq. 3 fits (eq. 4 for <Z>).",
    "fig3": "Power spectrum of <Z> - <Z>_SS (top) and sigma_<Z> against sqrt(eps) (bottom; "
            "filled: about the steady mean, open: about each run's straight line).",
    "fig4": "Steady-state <Phi^c> against sqrt(eps) (squares) and the ramps up, down and up "
            "again (open symbols; the legend says where each ramp turns).",
    "fig5": "A(t, t_W) for several waiting times (top) and their collapse on eq. 6 (bottom).",
    "fig6": "Vertical profiles of the initial packing and after the taps, with eq. 7 fits "
            "(top), and the gradient alpha against sqrt(eps) after the taps and at the end of "
            "every level of the ramp (bottom).",
    "fig7": "Transversal profiles of the initial packing and after the taps; dotted: the 7R "
            "frontiers.",
    "fig8": "delta Phi_lateral (top) and delta Phi_central (bottom) against taps.",
    "fig9": "P0(sigma) of the tapped packing (circles), the initial packing (thin line) and "
            "Percus-Yevick (thick line).",
    "fig10": "rho_v(xi) (top) and rho_v(v) (bottom) at several tap counts; T and O: tetrahedral "
             "and octahedral sites.",
}


#: the pages of the two reports, as documents of the documentation (the two link each other)
PAPER_SCALE_DOC = "/paper_scale/validation"
SMOKE_TEST_DOC = "/validation"


#: longest TAPMC cell of the main table, in characters: about five lines of its column on a
#: screen (issue 42 found cells of 600 characters); a longer measure is cut at a "; " and the
#: cell links the whole text on the claims' appendix
MAIN_CELL_CHARS = 240


def _brief(text):
    """``text`` cut after its last "; " within :data:`MAIN_CELL_CHARS` (at that length when it
    has none), "..." marking the cut; (text, whether it was cut)."""
    if len(text) <= MAIN_CELL_CHARS:
        return text, False
    head = text[:MAIN_CELL_CHARS]
    cut = head.rfind("; ")
    return (head[:cut] if cut > 0 else head).rstrip() + " ...", True


def _claims_table(verdicts, prefix):
    """The answer to "how close is TAPMC to the paper": one row per claim, with the verdict
    its rows give it (:mod:`tapmc.paper.claims.aggregate`); a claim of several rows shows
    the row its verdict rests on and links the table of all of them."""
    rows = []
    for verdict in verdicts:
        c, shown = verdict.claim, verdict.shown_row()
        claim = f"``{c.id}``: {escape_bars(c.claim)}"
        measure = shown.measure.text()
        if len(verdict.rows) > 1 and shown.label:
            measure = f"{shown.label}: {measure}"
        elif shown.label:
            claim += f" ({escape_bars(shown.label)})"
        measure, cut = _brief(measure)
        measure = escape_bars(measure)
        link = claim_label(prefix, c.id)
        if len(verdict.rows) > 1:
            measure += f" (:ref:`all {len(verdict.rows)} rows <{link}>`)"
        elif cut:
            measure += f" (:ref:`in full <{link}>`)"
        if not c.could_fail:
            claim += " [could not fail for any compaction model]"
        rows.append([where(c), claim, escape_bars(c.paper), measure, scale_text(verdict.rows),
                     f"{escape_bars(verdict.text())} [{c.rule}]"])
    return list_table(["Where", "Claim", "Paper", "TAPMC", "Paper scale?", "Verdict [rule]"],
                      rows, widths=(8, 30, 14, 20, 8, 20))


def _label_prefix(summary):
    """The prefix of the claims' labels: the campaign's scale (the two reports of one
    documentation have two)."""
    return summary.get("scale") or "campaign"


def _is_paper_scale(summary):
    """Whether the campaign has the paper's size (else its page is a smoke test)."""
    return "size" in scale_aspects(summary)


def _title_and_intro(summary):
    """The page's title and its first paragraph: the validation at the paper's size, else a
    smoke test of the same claims."""
    common = ("This page is written by ``tapmc-paper report`` from one campaign: every number "
              "below is computed from the campaign's runs and every verdict from the numbers, "
              "by the rules of its appendix. The rows are the claims register "
              "(``tools/python/tapmc/paper/claims.toml``): every claim of the paper, with the "
              "statistic that tests it. TAPMC values are means over seeds with their standard "
              "errors (sem); the paper gives single runs without error bars.")
    if _is_paper_scale(summary):
        return ("Validation against Philippe & Bideau", common + " The smoke test "
                f"(:doc:`{SMOKE_TEST_DOC}`) runs the same claims on a campaign below the "
                "paper's size.")
    return ("Smoke test against Philippe & Bideau",
            "This page is a smoke test: a campaign below the paper's size, run through the "
            "same claims to show that the pipeline works; its verdicts are not the validation, "
            f"which is on the paper-scale page (:doc:`{PAPER_SCALE_DOC}`). " + common)


def _finding_csv(files, name):
    """A finding's CSV, questions/<name> next to the figures; None without figures or file."""
    if not files:
        return None
    path = Path(next(iter(files.values()))[1]).parent / questions.FOLDER / name
    return path if path.exists() else None


def _finding_source(unit, name, command):
    """Where a finding's numbers are, as the page cites them."""
    return (f" Per {unit}: ``{Path(FIG_DIR) / questions.FOLDER / name}`` "
            f"(``tapmc-paper {command}``).")


def _paper_ramp_finding(files, summary, error_factor):
    """(headline, finding, figure): the answer about the irreversible branch at the paper's
    ramp protocol in one sentence, and with its numbers, from questions/paper_ramp.csv next to
    the figures (``tapmc-paper paper-ramp``), its errors times ``error_factor``
    (:func:`tapmc.paper.paper_ramp.errors_from_report`), and the page's path of the ramps'
    figure written beside it (None without one); or ("", "", None)."""
    path = _finding_csv(files, paper_ramp.CSV_NAME)
    if path is None:
        return "", "", None
    rows = paper_ramp.read_csv(path)
    default_eta = campaign_eta(summary)
    figure = (Path(FIG_DIR) / questions.FOLDER / paper_ramp.PNG_NAME
              if (path.parent / paper_ramp.PNG_NAME).is_file() else None)
    return (paper_ramp.headline_text(rows, default_eta, error_factor)
            + "\n\nThe numbers with their errors: the first open question below.",
            paper_ramp.finding_text(rows, default_eta, error_factor,
                                    _finding_source("run", paper_ramp.CSV_NAME, "paper-ramp")),
            figure)


def _sigma_eta_finding(files, default_eta, factor_of=None):
    """The finding about sigma_<Z> against eta (section III.A, Fig. 3: is its offset the
    redeposition's noise?) from questions/sigma_eta.csv next to the figures (``tapmc-paper
    sigma-eta``), with its figure written beside it when there is one ((text, (page path, alt
    text)), as :func:`tapmc.paper.summary.screen_rst` takes it), or ""."""
    path = _finding_csv(files, sigma_eta.CSV_NAME)
    if path is None:
        return ""
    text = sigma_eta.finding_text(sigma_eta.read_csv(path), default_eta, factor_of)
    if not text:
        return ""
    text += _finding_source("point", sigma_eta.CSV_NAME, "sigma-eta")
    return _with_figure(text, path.parent / sigma_eta.PNG_NAME,
                        "sigma_<Z> and the steady packing against sqrt(eps), per eta")


def _with_figure(text, png, alt):
    """A finding's item: (text, (page path of ``png``, ``alt``)) when its figure was written
    beside its CSV, else the text alone (:func:`tapmc.paper.summary.screen_rst`)."""
    if not png.is_file():
        return text
    return text, (str(Path(FIG_DIR) / questions.FOLDER / png.name), alt)


def _connected_ageing_finding(files):
    """The finding about ageing with the drift removed (section III.C, Fig. 5: does the
    packing age, or does A(t, t_W) measure the drift?) from questions/connected_ageing.csv
    (``tapmc-paper question connected-ageing``), with its figure when there is one, or ""."""
    module = questions.connected_ageing
    path = _finding_csv(files, module.CSV)
    if path is None:
        return ""
    text = module.finding_text(module.load(path))
    if not text:
        return ""
    text += _finding_source("waiting time and delay", module.CSV,
                            f"question {module.NAME}")
    return _with_figure(text, path.parent / module.PNG,
                        "the paper's A(t, t_W) and the connected C(t, t_W) against the delay")


def _appendix_line():
    return ["Appendices: " + "; ".join(f":doc:`{title.lower()} <{name}>`"
                                       for name, title in APPENDICES.items()) + ".", ""]


def _rewrite_lines():
    return [f"The numbers come from the figure CSVs and ``{FIG_DIR}/{SUMMARY_FILE}`` (the "
            "campaign's scale and initial packings), committed with this page; rewrite it and "
            "its appendices from them (a test checks that this gives the committed pages):", "",
            ".. snippet: skip rewrites this page; tests/python/test_validation_report.py "
            "checks that it gives the committed text", "",
            ".. code-block:: sh", "",
            "   build/tapmc-paper report --from-data --out doc", "",
            "or run a campaign and draw everything anew (``--full`` for the paper's scale, "
            "hours to days):", "",
            ".. snippet: skip runs a whole campaign",
            "", ".. code-block:: sh", "",
            "   build/tapmc-paper report --quick --campaign tapmc-paper-quick --out doc", ""]


def _figure_lines(files, notes):
    lines = []
    for name in FIGURES:
        if name not in files:
            continue
        png, csv = files[name]
        number = name[3:]
        title = f"Fig. {number}"
        lines += [title, "-" * len(title), "", CAPTIONS.get(name, ""), "",
                  f".. image:: {FIG_DIR}/{Path(png).name}", f"   :alt: Fig. {number}", "",
                  f"Data: ``{FIG_DIR}/{Path(csv).name}`` (columns panel, series, x, mean, sem, "
                  "n).", ""]
        if name in notes:
            lines += [notes[name], ""]
    return lines


def _main_page(summary, files, rows, verdicts, notes, prefix, data):
    """The text of validation.rst: the answer on one screen, one row per claim, the figures."""
    title, intro = _title_and_intro(summary)
    headline, finding, figure = _paper_ramp_finding(files, summary,
                                                    paper_ramp.errors_from_report(data))
    lines = [".. TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.", "",
             title, "=" * len(title), "", intro, "", describe_scale(summary, bool(headline)),
             ""]
    lines += _appendix_line()
    sigma = _sigma_eta_finding(files, campaign_eta(summary), sigma_eta.errors_from_report(data))
    findings = [f for f in (finding, sigma, _connected_ageing_finding(files)) if f]
    lines += summary_screen.screen_rst(summary_screen.summarise(rows, files), findings, headline,
                                       figure and (figure, "the ramps at the paper's protocol"))
    lines += ["How close is TAPMC to the paper", "-" * 31, "",
              AGGREGATION_SENTENCE + " The rules of "
              "the rows' verdicts, the errors of one run and what \"Paper scale?\" means: "
              ":doc:`validation_rules`.", ""]
    lines += _claims_table(verdicts, prefix) + [""]
    lines += _rewrite_lines()
    lines += _figure_lines(files, notes)
    return "\n".join(lines).rstrip() + "\n"


def render_pages(summary, files):
    """file name -> text of every page of the report: validation.rst (:func:`render`) and
    its appendices (:data:`~tapmc.paper.validation_appendix.APPENDICES`), from one evaluation
    of the register on the campaign summary and the figure files (name -> (png, csv))."""
    rows, notes, figures, run_note, data = _rows_and_notes(summary, files)
    verdicts = claim_verdicts(rows)
    prefix = _label_prefix(summary)
    folder, groups = None, {}
    if files:
        folder = Path(next(iter(files.values()))[1]).parent / questions.FOLDER
        groups = questions.render_parts(folder, figures, summary["eta"], read_front_summary())
    pages = {"validation": _main_page(summary, files, rows, verdicts, notes, prefix, data)}
    pages.update(render_appendices(verdicts, run_note, prefix, folder, groups,
                                    tolerances=claims.tolerance_table(rows)))
    return {f"{name}.rst": text for name, text in pages.items()}


def render(summary, files):
    """The text of validation.rst from the campaign summary and the figure files (name ->
    (png, csv))."""
    return render_pages(summary, files)["validation.rst"]


def write_rst(summary, files, out_dir):
    """Write out_dir/validation.rst and its appendix pages (:func:`render_pages`) and the
    summary as out_dir/validation/report.json, each whole or not at all (every page is
    rendered before any file is written); returns the path of validation.rst."""
    out_dir = Path(out_dir)
    pages = render_pages(summary, files)
    (out_dir / FIG_DIR).mkdir(parents=True, exist_ok=True)
    _write_whole(out_dir / FIG_DIR / SUMMARY_FILE, json.dumps(summary, indent=1) + "\n")
    return _write_pages(out_dir, pages)


def _write_pages(out_dir, pages):
    """Write every page of ``pages`` (file name -> text) into out_dir, each whole; returns
    the path of validation.rst."""
    for name, text in pages.items():
        _write_whole(Path(out_dir) / name, text)
    return Path(out_dir) / "validation.rst"


def committed_inputs(out_dir):
    """(summary, files) of a report already written to out_dir: report.json and the figure
    PNG/CSV pairs in out_dir/validation. Raises FileNotFoundError naming what is missing, and
    TapmcFormatError naming the file (and line) when report.json (:func:`read_summary`) or a
    figure CSV (``_plotting.read_table``) is damaged: every input is checked before anything
    is rendered."""
    folder = Path(out_dir) / FIG_DIR
    path = folder / SUMMARY_FILE
    if not path.is_file():
        raise FileNotFoundError(f"{path}: no report summary (written by 'tapmc-paper report' "
                                "from a campaign)")
    for name in FIGURES:  # a figure drawn without its CSV: the CSV was lost since (its claims
        png, csv = folder / f"{name}.png", folder / f"{name}.csv"  # would turn undecided)
        if png.is_file() and not csv.is_file():
            raise FileNotFoundError(f"{csv}: missing beside {png} (a figure is written with "
                                    "its CSV, from which the page is rendered)")
    files = {name: (folder / f"{name}.png", folder / f"{name}.csv") for name in FIGURES
             if (folder / f"{name}.csv").is_file()}
    if not files:
        raise FileNotFoundError(f"{folder}: no figure CSV (fig2.csv ... fig10.csv)")
    summary = read_summary(path)
    for _, csv in files.values():
        P.read_table(csv)
    return summary, files


def _is_int(value):
    return isinstance(value, int) and not isinstance(value, bool)


def _is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _list_of(check, length=None):
    return lambda value: (isinstance(value, list) and length in (None, len(value))
                          and all(check(v) for v in value))


def _count(least):
    """An integer no smaller than ``least`` (a count of runs, taps or seeds)."""
    return lambda value: _is_int(value) and value >= least


def _positive(value):
    """A finite number above zero (a length, a threshold)."""
    return _is_number(value) and math.isfinite(value) and value > 0


def _initial_phi_c(value):
    """[mean, sem, n] of the initial <Phi^c>: a fraction in [0, 1], an error >= 0 and a count
    >= 0, each null when the campaign had no initial packing to read."""
    if not _list_of(lambda v: v is None or _is_number(v), 3)(value):
        return False
    mean, sem, n = value
    return ((mean is None or 0 <= mean <= 1) and (sem is None or sem >= 0)
            and (n is None or (float(n).is_integer() and n >= 0)))


#: report.json's fields (:func:`campaign_summary`): name -> (the type the page needs, its test)
SUMMARY_FIELDS = {
    "scale": ("a string or null", lambda v: v is None or isinstance(v, str)),
    "preset": ("true or false", lambda v: isinstance(v, bool)),
    "fields": ("null or an object with the fields " + ", ".join(_SCALE_KEYS),
               lambda v: v is None or (isinstance(v, dict) and all(k in v for k in _SCALE_KEYS))),
    "sizes": ("a list of [N, L] pairs (an integer N >= 1 and a length L > 0)",
              _list_of(lambda v: _list_of(_is_number, 2)(v) and _count(1)(v[0])
                       and _positive(v[1]))),
    "runs": ("an integer >= 0", _count(0)),
    "taps": ("a list of integers >= 1", _list_of(_count(1))),
    "seeds": ("an integer >= 0", _count(0)),
    "eta": ("a list of numbers > 0", _list_of(_positive)),
    "initial_phi_c": ("a list [mean, sem, n] of numbers or nulls, the mean in [0, 1], the sem "
                      "and n >= 0", _initial_phi_c),
}
#: fields of report.json that a summary written before them lacks
OPTIONAL_SUMMARY_FIELDS = {
    "seeds_per_point": ("a list [fewest, most] of integers, 0 <= fewest <= most",
                        lambda v: _list_of(_count(0), 2)(v) and v[0] <= v[1]),
    "ramp_taps_per_level": ("a list of integers >= 1", _list_of(_count(1))),
    "planned_runs": ("an integer >= 0", _count(0)),
    "stop": ("a list of strings (the stop rules, 'stop change ...')",
             _list_of(lambda v: isinstance(v, str) and v.startswith("stop "))),
    "figures": ("an object: figure name -> the settings of its runs",
                lambda v: isinstance(v, dict) and all(isinstance(f, dict) for f in v.values())),
}


def read_summary(path):
    """report.json as a dict, checked field by field (:data:`SUMMARY_FIELDS`): a file that is
    not JSON, not an object, lacks a field or has one of another type raises TapmcFormatError
    naming the file, the field and the type expected, before anything of it is printed."""
    try:
        summary = json.loads(Path(path).read_bytes())
    except ValueError as err:  # also UnicodeDecodeError
        raise TapmcFormatError(path, getattr(err, "lineno", None),
                               f"not valid JSON ({err})") from None
    if not isinstance(summary, dict):
        raise TapmcFormatError(path, None, f"a JSON {type(summary).__name__}, expected an "
                               "object (the report summary written by 'tapmc-paper report')")
    for name, (expected, valid) in {**SUMMARY_FIELDS, **OPTIONAL_SUMMARY_FIELDS}.items():
        if name not in summary and name in OPTIONAL_SUMMARY_FIELDS:
            continue
        if name not in summary:
            raise TapmcFormatError(path, None, f"no field {name!r} ({expected})")
        if not valid(summary[name]):
            raise TapmcFormatError(path, None, f"field {name!r} is {summary[name]!r}, "
                                   f"expected {expected}")
    return summary


def _write_whole(path, text):
    """Write ``text`` to ``path`` through a temporary file renamed when complete: a kill or
    a full disk never leaves part of a page or CSV in place of the committed one."""
    path = Path(path)
    tmp = path.with_name(path.name + ".tmp")
    try:
        tmp.write_text(text)
        tmp.replace(path)
    finally:
        tmp.unlink(missing_ok=True)
    return path


#: figure -> the function that recomputes its statistics from its own curves (module docs).
_REFITS = {"fig2": "refit_table", "fig4": "refit_table", "fig5": "refit_table"}


def refit(out_dir):
    """Recompute, from the curves of the figure CSVs in out_dir/validation, the statistics
    their figure modules can compute from a CSV alone (:data:`_REFITS`), rewriting those
    CSVs (curves kept, PNGs untouched). Every input is checked first
    (:func:`committed_inputs`); a CSV is replaced only by a complete, non-empty refit
    (:func:`_replace_csv`). Returns the rewritten paths."""
    _, files = committed_inputs(out_dir)
    done = []
    for name, function in _REFITS.items():
        if name in files:
            csv = Path(files[name][1])
            module = import_module(f"{__package__}.{name}")
            try:
                table = getattr(module, function)(P.read_table(csv))
            except TapmcFormatError:
                raise
            except (ValueError, IndexError, KeyError) as err:
                raise ValueError(f"{csv}: cannot be refitted ({err}); left as it is") from None
            done.append(_replace_csv(table, csv))
    return done


def _replace_csv(table, csv):
    """Replace ``csv`` by ``table`` (a FigureTable) through a temporary file, renamed only
    when it holds rows and reads back as a whole figure CSV; else ``csv`` stays as it is."""
    csv = Path(csv)
    if not len(table):
        raise ValueError(f"{csv}: the refit gives no row; left as it is")
    tmp = csv.with_name(csv.name + ".tmp")
    try:
        table.write(tmp)
        P.read_table(tmp)
        tmp.replace(csv)
    finally:
        tmp.unlink(missing_ok=True)
    return csv


def page_entries(summary, files):
    """The figures' entries of the page (tapmc.paper.summary.summarise) of a report's
    ``summary`` and figure ``files`` (:func:`committed_inputs`): the rows the page evaluates."""
    return summary_screen.summarise(_rows_and_notes(summary, files)[0], files)


def readme_lines(out_dir):
    """README.md's "What the validation found" lines of the report in ``out_dir`` (its
    committed data, :func:`committed_inputs`): the counts, the central question's answer with
    its figure when its PNG is there, the open questions."""
    summary, files = committed_inputs(out_dir)
    figure = (Path(out_dir) / FIG_DIR / "questions" / paper_ramp.PNG_NAME).is_file()
    return summary_screen.readme_lines(page_entries(summary, files),
                                       paper_ramp_headline(summary, files), figure)


def update_readme(readme, out_dir):
    """Write README.md's "What the validation found" from the report in ``out_dir``
    (:func:`readme_lines`); the file is replaced only when complete. Returns its path."""
    readme = Path(readme)
    text = summary_screen.readme_with_lines(readme.read_text(), readme_lines(out_dir))
    tmp = readme.with_name(readme.name + ".tmp")
    tmp.write_text(text)
    tmp.replace(readme)
    return readme


def regenerate(out_dir):
    """Rewrite out_dir/validation.rst and its appendix pages from the committed data alone
    (report.json and the figure CSVs in out_dir/validation, checked first by
    :func:`committed_inputs`); nothing is run or drawn. Returns the path of validation.rst."""
    summary, files = committed_inputs(out_dir)
    return _write_pages(out_dir, render_pages(summary, files))


def report(campaign, out_dir, drawn=None, planned_runs=None):
    """Write ``out_dir/validation.rst``, its appendix pages and the figures it embeds under
    ``out_dir/validation/``.

    ``drawn``: name -> (png, csv) of figures already drawn (moved into ``out_dir/validation``);
    the figures not given are drawn here. ``planned_runs``: the number of runs of the whole
    campaign when ``campaign`` holds only its finished ones (a campaign under way; the page
    says how many are done). Returns the path of the rst."""
    out_dir = Path(out_dir)
    drawn = dict(drawn or {})
    target = out_dir / FIG_DIR
    for name in FIGURES:
        if name in drawn:
            continue
        module = import_module(f"{__package__}.{name}")
        try:
            drawn[name] = module.draw(campaign, target)
        except TapmcFormatError:
            raise  # a damaged output of a run: never a figure left out
        except ValueError:
            continue  # this campaign has no run of that figure
    summary = campaign_summary(campaign)  # reads runs: before any committed file is replaced
    files = _collect(drawn, out_dir)
    if planned_runs is not None and planned_runs > summary["runs"]:
        summary["planned_runs"] = int(planned_runs)
    return write_rst(summary, files, out_dir)


__all__ = ["report", "regenerate", "refit", "readme_lines", "update_readme", "page_entries",
           "render", "render_pages", "write_rst",
           "campaign_summary",
           "committed_inputs", "read_summary", "RULES"]
