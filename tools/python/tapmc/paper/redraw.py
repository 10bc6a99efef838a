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

#: the figure modules and their typed results, in the page's order
FIGURE_RESULTS = {module.NAME: (module, getattr(module, module.NAME.capitalize() + "Result"))
                  for module in (fig2, fig3, fig4, fig5, fig6, fig7, fig8, fig9, fig10)}
#: the campaign's settings beside the figures (tapmc.paper.validation writes it)
SUMMARY_FILE = "report.json"


def committed_settings(folder):
    """The campaign's settings that the figures in ``folder`` state: its report.json."""
    return json.loads((Path(folder) / SUMMARY_FILE).read_text())


def draw_committed(name, folder, settings=None):
    """The figure ``name`` (fig2 ... fig10) drawn from ``folder``/``name``.csv: a matplotlib
    figure, not saved (``settings``: None reads report.json)."""
    module, result_class = FIGURE_RESULTS[name]
    if settings is None:
        settings = committed_settings(folder)
    return module.plot(result_class.load(Path(folder) / f"{name}.csv"), settings)


def redraw(out_dir):
    """Draw again every figure whose CSV is in ``out_dir``/validation over its PNG; returns
    the PNGs written."""
    folder = Path(out_dir) / _runs.FIG_DIR
    settings = committed_settings(folder)
    written = []
    for name in FIGURE_RESULTS:
        if (folder / f"{name}.csv").is_file():
            written.append(P.save_figure(draw_committed(name, folder, settings),
                                         folder / f"{name}.png"))
    return written
