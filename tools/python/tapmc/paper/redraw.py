# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The figures of a report drawn again from its committed data: each figure's typed result
loaded from its CSV (``FigNResult.load``), drawn by its module's ``plot`` with the settings of
the campaign's report.json (``_plotting.settings_text``), written over its PNG. Nothing is
run or analysed and no CSV is written: ``tapmc-paper report --from-data --redraw``, after a
change of drawing alone."""

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


def figure_settings(name, summary):
    """``summary`` (report.json) with the eps and boundary conditions of the figure ``name``
    where its result does not record them (:data:`FIGURE_EPS`): from the campaign's preset,
    or from the fields report.json records of a scale of no preset (else left out)."""
    if name not in FIGURE_EPS:
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
    return module.plot(result_class.load(Path(folder) / f"{name}.csv"),
                       figure_settings(name, summary))


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
