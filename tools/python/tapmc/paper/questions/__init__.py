# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Questions of the validation settled by a measurement: one module per question, each the
one owner of its CSV (its header, ``save`` and ``load``), its measurement (``measure(args)``:
LAMMPS runs through tapmc.campaign, see :mod:`.launch`, or a re-analysis of the campaign's
finished runs, ``analyse``) and its page text (``render``). :data:`QUESTIONS` lists them;
``tapmc-paper question NAME`` runs one (:mod:`.command`), and :func:`render_parts` writes
the sections of the validation's appendix pages from the CSVs in
``<report>/validation/questions/``: every number and every conclusion there is computed from
those files, so the report can be rewritten from committed data.

* first-tap (``first_tap.csv``): <Phi^c> before and after one tap from fresh packings, at
  several eta: whether the drop of <Phi^c> at the first tap of P.B.C. runs survives a tighter
  redeposition.
* noise-floor (``noise_floor.csv``): sigma_<Z> of 1000 taps at eps = 0 from a tapped packing:
  the floor under Fig. 3's sigma_<Z> = k sqrt(eps).
* spectral-window (``spectral_window.csv``): the slope of Fig. 3's spectrum over steady
  windows of several lengths, per run.
* pbc-course (``pbc_course.csv``): the course of <Phi^c> in every P.B.C. run of the campaign:
  how deep and how long the dip after the first taps is, and whether strong taps (eps >= 0.09)
  leave the packing looser than it started or still compacting at the end.
* realization-scatter (``realization_scatter.csv``): whether one run's batch-means error tells
  how far another realization lands, and the factor it falls short by.
* packing-scatter (``packing_scatter.csv``): the same question for the spatial jackknife of
  one packing (nu of the pores, alpha of the profile).
* integrity (``integrity.csv``): every dump of the campaign checked offline.
* early-taps (``early_taps.csv``): the first 400 taps from the campaign's F.B.C. packing over
  several realizations.
* fit-surrogates (``fit_surrogates.csv``) and seed-fits (``seed_fits.csv``): eqs. 3 and 4
  fitted to each F.B.C. run with Fourier surrogates, and over realizations of whole runs.
* initial-packing (``initial_packing.csv``), p0-configs (``p0_configs.csv``),
  lateral-first-tap (``lateral_first_tap.csv``), ramp-levels (``ramp_levels.csv``),
  ramp-pores (``ramp_pores.csv``), theta0 and dmax (``theta0*.csv``, ``dmax*.csv``), p0-fluid
  (``p0_fluid.csv``): see each module.
* crystallinity (``crystallinity.csv``): whether the campaign's tapped packings (bulk, floor
  layer, side-wall layer) crystallize, against their initial packings and exact FCC and HCP
  lattices: is a packing denser than the paper's ordered or random?
* alpha-window (``alpha_window.csv``): alpha of every P.B.C. constant-eps run in a window
  5-18R below the packing's loose top beside Fig. 6's own window: whether alpha's rise with
  eps is the model or the window's reading (the register's gradient-bell reads it).
* ramp-alpha (``ramp_alpha.csv``): alpha at the end of every level of the ramps at the
  paper's 4000 taps per level: whether alpha shows hysteresis at the paper's protocol (the
  register's gradient-no-hysteresis reads it).
* campaign-runs (``campaign_runs.csv``): every run of the campaign with its settings (eta,
  eps or a ramp's range and taps per level), how far it got, what its attempts recorded and
  cost by the cost rule, and the TAPMC versions that ran it.
* connected-ageing (``connected_ageing.csv``, ``connected_ageing.png``): Fig. 5's ageing
  realizations with the drift of the compaction removed (the connected function and a
  collapse without a law): does the packing age, or does A(t, t_W) measure the drift?
* Fig. 10's pores (:mod:`.pore_shares`) and the final <Phi^c> carried to the front's settings
  (:mod:`.final_phi`): sections computed from other CSVs, without a command.
"""

from __future__ import annotations

from pathlib import Path

from ..claims import SCANS, realization_factors, scan_files
from . import (alpha_window, campaign_runs, connected_ageing, crystallinity, dmax, early_taps,
               final_phi, first_tap, fit_surrogates, integrity, initial_packing, knob_scan,
               lateral_first_tap, noise_floor, p0_configs, p0_fluid, packing_scatter, pbc_course,
               pore_shares, ramp_alpha, ramp_levels, ramp_pores, realization_scatter,
               seed_fits, spectral_window, theta0)
from .calibration import load as load_scatter
from .common import QuestionError, QuestionRunError

FOLDER = "questions"
#: every question with a command: name -> its module (NAME, add_arguments, measure; the
#: modules with a CSV of their own also CSV, save, load and render)
QUESTIONS = {m.NAME: m for m in (
    first_tap, noise_floor, spectral_window, pbc_course, integrity, realization_scatter,
    packing_scatter, early_taps, initial_packing, p0_configs, lateral_first_tap, ramp_levels,
    ramp_pores, theta0, dmax, p0_fluid, fit_surrogates, seed_fits, crystallinity,
    alpha_window, connected_ageing, campaign_runs, ramp_alpha)}
#: the questions whose measurement reads the campaign's runs (--campaign)
CAMPAIGN_QUESTIONS = ("spectral-window", "pbc-course", "integrity", "early-taps",
                      "ramp-levels", "realization-scatter", "packing-scatter", "ramp-pores",
                      "fit-surrogates", "seed-fits", "crystallinity", "alpha-window",
                      "connected-ageing", "campaign-runs", "ramp-alpha")
#: the page's section title
TITLE = "Questions settled by measurement"
#: the commands named under the title, in the page's order, with the CSV that shows each was
#: run (first-tap, noise-floor and spectral-window are always named)
NAMED = (("realization-scatter", "realization_scatter.csv"),
         ("packing-scatter", "packing_scatter.csv"), ("pbc-course", "pbc_course.csv"),
         ("integrity", "integrity.csv"), ("campaign-runs", "campaign_runs.csv"),
         ("early-taps", "early_taps.csv"),
         ("fit-surrogates", "fit_surrogates.csv"), ("seed-fits", "seed_fits.csv"),
         ("initial-packing", "initial_packing.csv"), ("p0-configs", "p0_configs.csv"),
         ("lateral-first-tap", "lateral_first_tap.csv"), ("ramp-levels", "ramp_levels.csv"),
         ("ramp-pores", "ramp_pores.csv"), ("crystallinity", "crystallinity.csv"),
         ("alpha-window", "alpha_window.csv"),
         ("connected-ageing", "connected_ageing.csv"), ("ramp-alpha", "ramp_alpha.csv"))


def _commands(folder):
    """The commands that made the CSVs of ``folder``, as the page names them."""
    names = ["first-tap", "noise-floor", "spectral-window"]
    names += [name for name, csv in NAMED if (folder / csv).is_file()]
    names += [k for k in ("theta0", "dmax") if any(folder.glob(f"{k}*.csv"))]
    names += ["p0-fluid"] if (folder / p0_fluid.CSV).is_file() else []
    return ", ".join(f"``{n}``" for n in names)


#: the heading of each question's section on the appendix pages
HEADINGS = {
    first_tap: "The first tap (first-tap)", noise_floor: "The noise floor (noise-floor)",
    spectral_window: "The spectrum's window (spectral-window)",
    realization_scatter: "Errors of one run against realizations (realization-scatter)",
    packing_scatter: "Errors of one packing against realizations (packing-scatter)",
    pbc_course: "The course of P.B.C. runs (pbc-course)", integrity: "Integrity (integrity)",
    campaign_runs: "The campaign's runs (campaign-runs)",
    early_taps: "The early taps (early-taps)",
    fit_surrogates: "Eq. 3 and eq. 4 fitted run by run (fit-surrogates)",
    seed_fits: "Eq. 3 and eq. 4 fitted over realizations (seed-fits)",
    initial_packing: "The initial packing (initial-packing)",
    p0_configs: "P0 over configurations (p0-configs)",
    ramp_levels: "Taps per ramp level (ramp-levels)", ramp_pores: "Pores of the ramp (ramp-pores)",
    lateral_first_tap: "The lateral zone's first tap (lateral-first-tap)",
    p0_fluid: "P0 of an equilibrium fluid (p0-fluid)",
    crystallinity: "Crystallinity of the tapped packings (crystallinity)",
    alpha_window: "alpha in a window below the loose top (alpha-window)",
    connected_ageing: "Ageing with the drift removed (connected-ageing)",
    ramp_alpha: "alpha on the ramps at the paper's protocol (ramp-alpha)",
    pore_shares: "Fig. 10's pores",
    final_phi: "The final <Phi^c> at the front's settings"}
#: the calibrations of the errors and the integrity check: their own appendix page (the
#: other questions are on the questions' page)
CHECKS = (realization_scatter, packing_scatter, integrity, campaign_runs)
#: the groups of :func:`render_parts`
GROUPS = ("checks", "questions")


def _section(module, lines):
    """A question's lines under its heading ([] when it has none)."""
    if not lines:
        return []
    title = HEADINGS[module]
    return [title, "~" * len(title), ""] + lines


def _measured(folder, figures, factors):
    """(module, lines) of the questions with a CSV, in the page's order."""
    def there(module):
        return (folder / module.CSV).is_file()

    parts = []
    for module, extra in ((first_tap, ()), (noise_floor, (figures.get("fig3"),)),
                          (spectral_window, ()), (realization_scatter, ()),
                          (packing_scatter, ()), (pbc_course, (factors,)), (integrity, ()),
                          (campaign_runs, ()),
                          (early_taps, ())):
        if there(module):
            parts.append((module, module.render(folder / module.CSV, *extra)))
    if there(fit_surrogates):
        seeds = seed_fits.load(folder / seed_fits.CSV) if there(seed_fits) else []
        parts.append((fit_surrogates, fit_surrogates.render(folder / fit_surrogates.CSV, seeds)))
    for module, extra in ((seed_fits, ()), (initial_packing, ()), (p0_configs, ()),
                          (ramp_levels, (figures.get("fig4"), factors)), (ramp_pores, ()),
                          (lateral_first_tap, (figures.get("fig8"),)), (crystallinity, ()),
                          (alpha_window, ()), (ramp_alpha, ()), (connected_ageing, ())):
        if there(module):
            parts.append((module, module.render(folder / module.CSV, *extra)))
    for knob in SCANS:
        for scan in scan_files(folder, knob):
            title = f"The {knob} scan ({Path(scan).name})"
            parts.append((None, [title, "~" * len(title), ""] + knob_scan.render(scan, knob)))
    laws = theta0.render_laws(folder)
    if laws:
        title = "The laws of theta (theta-law-shape)"
        parts.append((None, [title, "~" * len(title), ""] + laws))
    if there(p0_fluid):
        parts.append((p0_fluid, p0_fluid.render(folder / p0_fluid.CSV, figures.get("fig9"))))
    return parts


def _sections(folder, figures, etas, front_rows):
    """(group, lines) of every question with a CSV in ``folder``, each under its heading, in
    the page's order: "checks" for :data:`CHECKS`, "questions" for the others."""
    folder = Path(folder)
    figures = figures or {}
    scatter = folder / realization_scatter.CSV
    factors = realization_factors(load_scatter(scatter)) if scatter.is_file() else {}
    measured = _measured(folder, figures, factors)
    if not measured:
        return []
    measured.append((pore_shares, pore_shares.render(figures.get("fig10"))))
    measured.append((final_phi, final_phi.render(figures.get("fig9"), list(etas),
                                                 front_rows or [])))
    return [("checks" if module in CHECKS else "questions",
             _section(module, lines) if module is not None else lines)
            for module, lines in measured]


def render_parts(folder, figures=None, etas=(), front_rows=None):
    """The rst lines of the questions by group (:data:`GROUPS`): "checks" (the calibrations
    of the errors and the integrity check, :data:`CHECKS`) and "questions" (the others), each
    question under its heading; every group [] when ``folder`` holds none of the CSVs.
    ``figures``: name -> tapmc.paper.claims.FigureData of the same report (Fig. 3's k, Fig. 9's
    packing)."""
    groups = {name: [] for name in GROUPS}
    for group, lines in _sections(folder, figures, etas, front_rows):
        groups[group] += lines
    return groups


def introduction(folder):
    """The sentence that names the commands behind the questions' CSVs in ``folder``."""
    return (f"Measured by ``tapmc-paper question NAME`` ({_commands(Path(folder))}), whose "
            "CSVs are in ``validation/questions/``; the text below is computed from them.")


def render_section(folder, figures=None, etas=(), front_rows=None):
    """The rst lines of every question (:func:`render_parts`), in the page's order, under one
    title, or [] when ``folder`` holds none of the CSVs."""
    parts = [line for _, lines in _sections(folder, figures, etas, front_rows)
             for line in lines]
    if not parts:
        return []
    return [TITLE, "-" * len(TITLE), "", introduction(folder), ""] + parts


__all__ = ["render_section", "render_parts", "introduction", "FOLDER", "QUESTIONS", "GROUPS",
           "QuestionError", "QuestionRunError"]
