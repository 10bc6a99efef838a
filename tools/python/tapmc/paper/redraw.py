# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The figures of a report drawn again from its committed data: each figure's typed result
loaded from its CSV (``FigNResult.load``), drawn by its module's ``plot`` with the settings of
its runs that the campaign's report.json records (``figures``: :func:`campaign_figure_settings`;
``_plotting.settings_text``), written over its PNG. Nothing is run or analysed and no CSV is
written: ``tapmc-paper report --from-data --redraw``, after a change of drawing alone.

A report.json written before it recorded each figure's runs gives a preset campaign's figures
the settings of the runs its preset plans for them (the figure module's ``runs``, its ramps'
taps per level as report.json records them): the stop rule, eta and taps of the preset's
runs, which no preset changes."""

import json
from pathlib import Path

from . import _plotting as P
from . import _runs, fig2, fig3, fig4, fig5, fig6, fig7, fig8, fig9, fig10
from .scales import SCALES

#: the figure modules and their typed results, in the page's order
FIGURE_RESULTS = {module.NAME: (module, getattr(module, module.NAME.capitalize() + "Result"))
                  for module in (fig2, fig3, fig4, fig5, fig6, fig7, fig8, fig9, fig10)}
#: the campaign's settings beside the figures (tapmc.paper.validation writes it)
SUMMARY_FILE = "report.json"
#: the figures whose result does not record its eps: (the Scale field of their eps, their
#: boundary conditions; None: the Scale's pore_bc), as their modules' runs take them
FIGURE_EPS = {"fig5": ("ageing_eps", fig5.BC), "fig9": ("p0_eps", fig9.BC),
              "fig10": ("pore_eps", None)}


def committed_settings(folder):
    """The campaign's settings that the figures in ``folder`` state: its report.json."""
    return json.loads((Path(folder) / SUMMARY_FILE).read_text())


def campaign_figure_settings(campaign):
    """figure name -> the settings of the runs it draws (``_plotting.run_settings`` of its
    module's ``figure_runs``; with their eps for :data:`FIGURE_EPS`), for the figures the
    campaign has runs of: what report.json records as ``figures``."""
    out = {}
    for name, (module, _) in FIGURE_RESULTS.items():
        try:
            runs = module.figure_runs(campaign)
        except ValueError:      # the campaign has no run of that figure
            continue
        if runs:
            out[name] = P.run_settings(campaign.runs, runs, eps=name in FIGURE_EPS)
    return out


def planned_settings(name, summary):
    """The settings of the runs a preset plans for the figure ``name`` (its module's ``runs``
    at the preset's seeds; the ramps' taps per level as ``summary`` records them), without
    their seeds; {} for a campaign of no preset."""
    scale = SCALES.get(summary.get("scale")) if summary.get("preset") else None
    if scale is None:
        return {}
    module = FIGURE_RESULTS[name][0]
    runs = module.runs(scale, scale.seeds)
    if name == "fig6":      # its bottom panel: alpha at the end of each level of the ramp
        runs += [_runs.ramp_run(scale, fig4.BC, s) for s in _runs.seed_list(scale.seeds)]
    out = P.run_settings(runs, eps=name in FIGURE_EPS)
    del out["seeds_per_point"]
    if out["ramp_taps_per_level"] and summary.get("ramp_taps_per_level"):
        out["ramp_taps_per_level"] = list(summary["ramp_taps_per_level"])
    return out


def figure_settings(name, summary):
    """``summary`` (report.json) with the settings of the runs of the figure ``name``: those
    report.json records (``figures``), else those its preset plans
    (:func:`planned_settings`); and the eps and boundary conditions of a figure whose result
    does not record them (:data:`FIGURE_EPS`) from the campaign's preset, or from the fields
    report.json records of a scale of no preset (else left out)."""
    recorded = (summary.get("figures") or {}).get(name)
    summary = dict(summary, **(recorded if recorded is not None
                               else planned_settings(name, summary)))
    if name not in FIGURE_EPS or summary.get("eps"):
        return summary
    field, bc = FIGURE_EPS[name]
    scale = SCALES.get(summary.get("scale")) if summary.get("preset") else None
    fields = summary.get("fields") or {}
    eps = getattr(scale, field) if scale is not None else fields.get(field)
    if bc is None:
        bc = scale.pore_bc if scale is not None else None
    if eps is None:
        return summary
    return dict(summary, eps=[float(eps)], bc=[bc] if bc else [])


def draw_committed(name, folder, summary=None):
    """The figure ``name`` (fig2 ... fig10) drawn from ``folder``/``name``.csv: a matplotlib
    figure, not saved (``summary``: the campaign's report.json, read when None)."""
    module, result_class = FIGURE_RESULTS[name]
    if summary is None:
        summary = committed_settings(folder)
    result = result_class.load(Path(folder) / f"{name}.csv")
    settings = figure_settings(name, summary)
    if name == "fig6" and not result.ramp:      # no ramp drawn: its taps are not the figure's
        settings = dict(settings, ramp_taps_per_level=[], ramp_dsqrt=[])
    return module.plot(result, settings)


def redraw(out_dir):
    """Draw again every figure whose CSV is in ``out_dir``/validation over its PNG; returns
    the PNGs written."""
    folder = Path(out_dir) / _runs.FIG_DIR
    summary = committed_settings(folder)
    written = []
    for name in FIGURE_RESULTS:
        if (folder / f"{name}.csv").is_file():
            written.append(P.save_figure(draw_committed(name, folder, summary),
                                         folder / f"{name}.png"))
    return written
