# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Shared helpers of the figure modules ``tapmc.paper.fig2`` ... ``fig10``.

Every figure writes one PNG and one CSV. The CSV is a tidy table with one row per plotted
number::

    panel,series,x,mean,sem,n

``panel`` names the axis ("a" top, "b" bottom, as in the paper's captions), ``series`` the
curve (e.g. ``eps=0.05``, ``fit:eps=0.05``), ``x`` the abscissa, ``mean`` the mean over seeds
(or realizations), ``sem`` its standard error (sample standard deviation / sqrt(n), empty when
n < 2 or for a fitted curve) and ``n`` the number of seeds behind the mean.

Every PNG states its settings on top (:func:`finish_figure`, :func:`settings_text`: N, the box,
eta and the stop rule, the taps of its own runs, seeds, the campaign) and has its legends
placed off the data (:func:`legend`, through :mod:`tapmc._legends`).
"""

from __future__ import annotations

import csv
import math
import re
import textwrap
from collections import Counter, defaultdict
from pathlib import Path

import numpy as np

import matplotlib

from tapmc._legends import laid_out, place_legend, replace_legends
from tapmc.fluctuations import SteadyState

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from tapmc.readers import TapmcFormatError  # noqa: E402

from . import _runs  # noqa: E402
from .scales import SCALES  # noqa: E402

#: Column names of every figure CSV.
CSV_COLUMNS = ("panel", "series", "x", "mean", "sem", "n")

#: Resolution of the PNGs: the paper's two-panel layout at 110 dpi stays well under 200 kB.
PNG_DPI = 110

#: Tetrahedral and octahedral site sizes xi = r/R in a dense packing (paper, section IV.B).
XI_T = math.sqrt(1.5) - 1.0
XI_O = math.sqrt(2.0) - 1.0


def seed_stats(samples):
    """Mean and standard error over the first axis of ``samples`` (seeds x points).

    Rows may have different lengths (a run that stopped early): each point uses the seeds that
    reach it. Returns ``(mean, sem, n)``; ``sem`` is NaN where fewer than two seeds contribute.
    """
    rows = [np.asarray(s, dtype=float).ravel() for s in samples]
    if not rows:
        raise ValueError("seed_stats needs at least one sample, got none")
    length = max(len(r) for r in rows)
    table = np.full((len(rows), length), np.nan)
    for i, r in enumerate(rows):
        table[i, : len(r)] = r
    n = np.sum(np.isfinite(table), axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = np.nanmean(table, axis=0) if length else np.array([])
        std = np.nanstd(table, axis=0, ddof=1) if len(rows) > 1 else np.full(length, np.nan)
        sem = np.where(n > 1, std / np.sqrt(np.maximum(n, 1)), np.nan)
    return mean, sem, n


def window_seeds(per_seed, last):
    """(values, errors): each seed's mean over its last ``last`` taps and that mean's
    batch-means error (tapmc.fluctuations.SteadyState), the realizations behind
    :func:`window_stats` that a figure writes as ``<series>:seeds`` rows (errors NaN for a
    window too short for two batches)."""
    if last < 4:      # fewer than two batches of two taps: a mean, but no batch-means error
        return (np.array([np.asarray(x, float)[-last:].mean() for x in per_seed]),
                np.full(len(per_seed), np.nan))
    states = [SteadyState(np.asarray(x, float), last=last).compute() for x in per_seed]
    return np.array([s.mean for s in states]), np.array([s.sem for s in states])


def window_stats(per_seed, last):
    """(mean, sem, n) of the mean over the last ``last`` taps of each seed's series: sem over
    seeds; with one seed (the paper's protocol) that run's batch-means error over the window
    (tapmc.fluctuations.SteadyState: successive taps are correlated), n = 1."""
    m, s, n = seed_stats([[np.asarray(x)[-last:].mean()] for x in per_seed])
    if len(per_seed) == 1:
        s = window_seeds(per_seed, last)[1]
    return m, s, n


class FigureTable:
    """Rows of a figure CSV (see the module docstring), written with :meth:`write`."""

    def __init__(self):
        self._rows = []

    def add(self, panel, series, x, mean, sem=None, n=1):
        """Add one curve: arrays (or scalars) of equal length."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        mean = np.atleast_1d(np.asarray(mean, dtype=float))
        if sem is None:
            sem = np.full(x.shape, np.nan)
        sem = np.broadcast_to(np.asarray(sem, dtype=float), x.shape)
        n = np.broadcast_to(np.asarray(n), x.shape)
        if mean.shape != x.shape:
            raise ValueError(f"series {series!r}: x has {x.size} points but mean has {mean.size}")
        for xi, mi, si, ni in zip(x, mean, sem, n):
            self._rows.append((panel, series, xi, mi, si, int(ni)))

    def __len__(self):
        return len(self._rows)

    @property
    def rows(self):
        """The rows added so far: (panel, series, x, mean, sem, n) tuples, in order."""
        return list(self._rows)

    def write(self, path):
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        with open(path, "w", newline="") as handle:
            writer = csv.writer(handle)
            writer.writerow(CSV_COLUMNS)
            for panel, series, x, mean, sem, n in self._rows:
                writer.writerow([panel, series, _fmt(x), _fmt(mean), _fmt(sem), n])
        return path


def _fmt(value):
    return "" if not np.isfinite(value) else f"{value:.10g}"


class FigureCsvError(TapmcFormatError):
    """A figure CSV that cannot be read whole (the message names the file and line)."""


def read_table(path):
    """Read a figure CSV back: dict (panel, series) -> dict of arrays x, mean, sem, n, from
    :func:`figure_csv_rows` (the whole file checked first)."""
    out = defaultdict(lambda: {"x": [], "mean": [], "sem": [], "n": []})
    for _, panel, series, x, mean, sem, n in figure_csv_rows(path):
        cur = out[(panel, series)]
        for key, value in (("x", x), ("mean", mean), ("sem", sem), ("n", n)):
            cur[key].append(value)
    return {k: {c: np.asarray(v) for c, v in d.items()} for k, d in out.items()}


def figure_csv_rows(path):
    """(line, panel, series, x, mean, sem, n) of every row of a figure CSV, numbers parsed.

    The one reader of the figure CSVs (the report's tables and the figures' typed results):
    the whole file is checked first, so that nothing is drawn or judged from part of it. A file
    that is empty, cut short (its last line without the end-of-line that every row of
    :meth:`FigureTable.write` has), without the header of :data:`CSV_COLUMNS`, without a row,
    or with a row of another number of fields, a non-numeric x, mean or sem (empty is NaN) or
    a non-integer n raises :class:`FigureCsvError` (a :class:`tapmc.readers.TapmcFormatError`)
    naming the file, the line and what is wrong."""
    return [(lineno, panel, series, _csv_float(path, lineno, "x", x),
             _csv_float(path, lineno, "mean", mean), _csv_float(path, lineno, "sem", sem),
             _csv_int(path, lineno, n))
            for lineno, panel, series, x, mean, sem, n in _csv_rows(path)]


def _csv_rows(path):
    """(line, panel, series, x, mean, sem, n) of each row of a whole figure CSV, as text."""
    try:
        text = Path(path).read_bytes().decode()
    except UnicodeDecodeError as err:
        raise FigureCsvError(path, None, f"not a text file ({err.reason})") from None
    if not text:
        raise FigureCsvError(path, None, "empty file (a figure CSV has the header "
                             f"{','.join(CSV_COLUMNS)} and one row per plotted number)")
    if not text.endswith("\n"):
        raise FigureCsvError(path, text.count("\n") + 1, "cut short: the last line has no "
                             "end-of-line")
    reader = csv.reader(text.splitlines(keepends=True))
    header = next(reader)
    if tuple(header) != CSV_COLUMNS:
        raise FigureCsvError(path, 1, f"header {','.join(header)!r}, expected "
                             f"{','.join(CSV_COLUMNS)!r}")
    rows = []
    for fields in reader:
        if len(fields) != len(CSV_COLUMNS):
            raise FigureCsvError(path, reader.line_num, f"{len(fields)} fields, expected "
                                 f"{len(CSV_COLUMNS)} ({','.join(CSV_COLUMNS)})")
        rows.append((reader.line_num, *fields))
    if not rows:
        raise FigureCsvError(path, None, "no row after the header (a figure CSV has one "
                             "row per plotted number)")
    return rows


def _csv_float(path, lineno, column, text):
    if text == "":
        return np.nan
    try:
        value = float(text)
    except ValueError:
        raise FigureCsvError(path, lineno, f"{column} = {text!r} is not a number") from None
    if not np.isfinite(value):  # the writer leaves a value it has not empty (_fmt): damage
        raise FigureCsvError(path, lineno, f"{column} = {text!r} is not a finite number (a "
                             "figure CSV leaves a missing value empty)")
    return value


def _csv_int(path, lineno, text):
    try:
        return int(text)
    except ValueError:
        raise FigureCsvError(path, lineno, f"n = {text!r} is not an integer") from None


def new_figure(nrows=2, ncols=1, height=3.0, width=5.0):
    """A figure with the paper's stacked panels (``nrows`` x ``ncols`` axes, as an array)."""
    fig, axes = plt.subplots(nrows, ncols, figsize=(width * ncols, height * nrows), squeeze=False)
    return fig, axes.ravel()


def save_figure(fig, path):
    """Save ``fig`` as a PNG (small: :data:`PNG_DPI`) and close it; returns the path. A
    figure not yet laid out (:func:`finish_figure`) is laid out and its legends placed off
    the data first."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    if not laid_out(fig):
        replace_legends(fig, fig.tight_layout)
    fig.savefig(path, dpi=PNG_DPI)
    plt.close(fig)
    return path


#: width of the documentation's page body in pixels (alabaster, page_width 1100px): a figure
#: wider than this is shown at this width, a narrower one at its own
PAGE_WIDTH_PX = 820
#: the smallest height in pixels, as the page shows a figure, that its text may have
MIN_TEXT_PX = 8


def shown_text_px(points, png_width_px, shown_px=None):
    """The height in pixels of text of ``points`` in a PNG of :data:`PNG_DPI` that is
    ``png_width_px`` wide, as a page shows it: at ``shown_px`` (an rst ``:width:``), at most
    :data:`PAGE_WIDTH_PX`."""
    shown = min(png_width_px if shown_px is None else shown_px, PAGE_WIDTH_PX)
    return points * PNG_DPI / 72.0 * shown / png_width_px


#: font size of the settings line on top of a figure (smaller than the legends' 7 points)
SETTINGS_FONTSIZE = 7
#: characters of that font per inch of the figure's width: where its line wraps (measured
#: on the figures: 90 characters fill the 5-inch panels)
SETTINGS_CHARS_PER_INCH = 18


def finish_figure(fig, settings=None, seeds=None):
    """``fig`` with its settings stated on top and laid out, its legends placed off the data
    for the final size of its axes (:func:`tapmc._legends.replace_legends`); returns it.
    ``settings``: the campaign's settings (:func:`run_settings`, or the report's report.json),
    or the line itself (a string), None when not known; ``seeds``: the (fewest, most) seeds
    behind the figure's points (:func:`plotted_seeds`), which the line states instead of the
    campaign's."""
    if settings:
        text = settings if isinstance(settings, str) else settings_text(settings, seeds)
        fig.suptitle(wrap_settings(text, int(SETTINGS_CHARS_PER_INCH * fig.get_figwidth())),
                     fontsize=SETTINGS_FONTSIZE)
    replace_legends(fig, fig.tight_layout)
    return fig


def wrap_settings(text, width):
    """The settings line in lines of at most ``width`` characters, broken between its parts
    ("; "), a part longer than a line broken between words."""
    lines = []
    for part in text.split("; "):
        if lines and len(lines[-1]) + 2 + len(part) <= width:
            lines[-1] += "; " + part
        else:
            if lines:
                lines[-1] += ";"
            lines.extend(textwrap.wrap(part, width) or [""])
    return "\n".join(lines)


#: panels of a figure CSV that hold statistics, drawn on no axis (``B``: Fig. 2's ln B
#: against sqrt(eps))
UNDRAWN_PANELS = ("params", "B")


def plotted_seeds(result):
    """(fewest, most) seeds behind the plotted points of a figure result (the ``n`` of its
    drawn curves: the statistics of :data:`UNDRAWN_PANELS` are not drawn, a fitted curve has
    n = 0), None when it has none."""
    counts = {int(n) for panel, _, data in result.rows() if panel not in UNDRAWN_PANELS
              for n in np.atleast_1d(data.n) if n > 0}
    return (min(counts), max(counts)) if counts else None


#: fix mc/settle keywords of one value that the settings line states when a run sets them
#: (``stop``: the stop rule; ``check 0`` is the default, one sweep)
STATED_SETTLE_KEYS = ("stop", "window", "dmax", "check", "maxsweeps", "theta0", "theta_law")


def settle_keys(spec):
    """The fix mc/settle keywords (besides eta) of a run (``tapmc.campaign.RunSpec``): its
    ``settle_keys`` variable when its input passes that variable to the fix
    (in.constant_eps), else none (the fix's defaults: in.ramp, in.ageing, in.pore_dumps)."""
    keys = spec.variables.get("settle_keys")
    if keys is None:
        return ""
    try:
        uses = "${settle_keys}" in Path(spec.input).read_text()
    except OSError:     # the input is gone: the variable is what the run was given
        uses = True
    return str(keys) if uses else ""


def stop_rule(keys=""):
    """The redeposition's stop rule of fix mc/settle keywords ``keys`` (besides eta) as the
    settings line states it: ``stop change`` (the fix's default, the paper's) or ``stop
    drift``, followed by the other keywords of :data:`STATED_SETTLE_KEYS` the run sets."""
    words = str(keys).split()
    found = {}
    for i, word in enumerate(words[:-1]):
        if word in STATED_SETTLE_KEYS and word not in found:
            found[word] = words[i + 1]
    if found.get("check") == "0":
        del found["check"]
    parts = [f"stop {found.pop('stop', 'change')}"]
    return " ".join(parts + [f"{k} {found[k]}" for k in STATED_SETTLE_KEYS if k in found])


def _is_ramp(spec):
    return Path(str(spec.input)).name == "in.ramp"


def run_settings(specs, figure_runs=None, eps=False):
    """The settings of runs (``tapmc.campaign.RunSpec``s) in the fields of the report's
    report.json that :func:`settings_text` states: sizes [(N, L)], eta, stop (the stop rule
    of each, :func:`stop_rule`), taps (of the runs at constant eps), seeds_per_point
    [fewest, most] (runs whose names differ only in ``_s<seed>`` are one point),
    ramp_taps_per_level and ramp_dsqrt (of the ramps, in.ramp). ``figure_runs``: the runs
    of one figure, whose settings are given instead of those of all ``specs``; ``eps``: also
    their ``eps`` and ``bc`` (a figure whose result does not record its eps: Figs. 5, 9,
    10)."""
    runs = list(specs if figure_runs is None else figure_runs)
    points = Counter(re.sub(r"_s\d+$", "", s.name) for s in runs)
    ramps = [s for s in runs if _is_ramp(s)]
    out = {
        "sizes": sorted({(int(s.variables["N"]), float(s.variables["L"])) for s in runs
                         if "N" in s.variables}),
        "eta": sorted({float(s.variables["eta"]) for s in runs if "eta" in s.variables}),
        "stop": sorted({stop_rule(settle_keys(s)) for s in runs}),
        "taps": sorted({int(s.taps) for s in runs if s.taps is not None and not _is_ramp(s)}),
        "seeds_per_point": ([min(points.values()), max(points.values())] if points
                            else [0, 0]),
        "ramp_taps_per_level": sorted({int(s.variables["P"]) for s in ramps
                                       if "P" in s.variables}),
        "ramp_dsqrt": sorted({float(s.variables["dsqrt"]) for s in ramps
                              if "dsqrt" in s.variables}),
    }
    if eps:
        out["eps"] = sorted({float(s.variables["eps"]) for s in runs if "eps" in s.variables})
        out["bc"] = sorted({str(s.variables["bc"]) for s in runs if "bc" in s.variables})
    return out


def figure_settings(campaign, figure_runs, eps=False):
    """:func:`run_settings` of the runs of one figure of ``campaign`` with the campaign's
    scale (``scale``, ``preset``: what :func:`settings_text` names it by, as report.json
    does) and the name of its folder (``campaign``: no path)."""
    scale = _runs.campaign_scale(campaign)
    return dict(run_settings(campaign.runs, figure_runs, eps),
                scale=None if scale is None else scale.name,
                preset=scale is not None and SCALES.get(scale.name) == scale,
                campaign=Path(campaign.directory).name)


def scale_text(scale):
    """:func:`campaign_text` of a campaign of ``scale``: "full preset" when it is a preset
    unchanged, else "scale <name>"."""
    return campaign_text({"scale": scale.name, "preset": SCALES.get(scale.name) == scale})


def campaign_text(summary):
    """The campaign a figure comes from, named by its scale (report.json's ``scale`` and
    ``preset``): "campaign: full preset", "campaign: scale <name>", else by its folder's name
    (``campaign``); None when not known."""
    name = summary.get("scale")
    if not name:
        return f"campaign: {summary['campaign']}" if summary.get("campaign") else None
    return f"campaign: {name} preset" if summary.get("preset") else f"campaign: scale {name}"


def after_taps(taps=None, settings=None):
    """"after N taps" for a figure's final state: N the taps its result records, else the one
    taps count of its runs' settings (a dict of :func:`run_settings` or report.json);
    "after the taps" when neither gives one count."""
    if taps is None and isinstance(settings, dict) and len(settings.get("taps") or ()) == 1:
        taps = settings["taps"][0]
    return "after the taps" if taps is None else f"after {int(taps)} taps"


#: the campaign of the question figures drawn from the paper-scale campaign (their modules
#: take its settings from the FULL preset)
FULL_CAMPAIGN = {"scale": "full", "preset": True}


def planned_stop(spec):
    """The stop rule of a run as a campaign plans it (``spec``: the RunSpec a
    ``tapmc.paper._runs`` constructor makes): :func:`stop_rule` of :func:`settle_keys`."""
    return stop_rule(settle_keys(spec))


#: how the settings line names the boundary conditions
BC_LABEL = {"pbc": "P.B.C.", "fbc": "F.B.C."}


def taps_text(summary):
    """The taps of the runs (``taps``) and of the ramps' levels (``ramp_taps_per_level``,
    ``ramp_dsqrt``) as the settings line states them; "" when neither is known."""
    taps = summary.get("taps") or []
    per_level = summary.get("ramp_taps_per_level") or []
    steps = summary.get("ramp_dsqrt") or []
    ramps = ""
    if per_level:
        ramps = f"{', '.join(map(str, per_level))} taps per level"
        if steps:
            ramps += f", steps of {', '.join(f'{d:g}' for d in steps)} in sqrt(eps)"
    if not taps:
        return f"ramps of {ramps}" if ramps else ""
    span = f"{taps[0]}" if len(taps) == 1 else f"{taps[0]} to {taps[-1]}"
    return f"{span} taps per run" + (f" (ramps: {ramps})" if ramps else "")


def settings_text(summary, seeds=None):
    """One line stating the settings of a figure's runs from :func:`run_settings` or
    report.json: sphere count and box (side L in sphere radii R), the figure's boundary
    conditions and eps where given (``bc``, ``eps``: a figure that does not state them in its
    legends or on its axis), redeposition threshold eta and stop rule (``stop``; report.json
    written before it has none), taps per run (and per level of a ramp), seeds per point
    (``seeds``: the figure's own (fewest, most)) and the campaign (:func:`campaign_text`)."""
    parts = [f"N = {n}, box {l:g}R x {l:g}R" for n, l in summary["sizes"]]
    if summary.get("eps"):
        bc = ", ".join(BC_LABEL.get(b, b) for b in summary.get("bc", ()))
        parts.append((f"{bc}, " if bc else "") + "eps = "
                     + ", ".join(fmt_eps(e) for e in summary["eps"]))
    redeposition = []
    if summary.get("eta"):
        redeposition.append("eta = " + ", ".join(f"{e:g}" for e in summary["eta"]))
    redeposition += list(summary.get("stop") or [])
    if redeposition:
        parts.append(", ".join(redeposition))
    taps = taps_text(summary)
    if taps:
        parts.append(taps)
    low, high = seeds or summary.get("seeds_per_point") or (summary.get("seeds"),) * 2
    if high:
        seeds = f"{low}" if low == high else f"{low} to {high}"
        parts.append(f"{seeds} {'seed' if high == 1 else 'seeds'} per point")
    source = campaign_text(summary)
    if source:
        parts.append(source)
    return "; ".join(parts)


def write_figure(fig, png, table, csv=None):
    """A figure's two outputs: the PNG of ``fig`` and the CSV of ``table`` (default
    :func:`figure_csv_path` of the PNG); returns their paths."""
    csv = figure_csv_path(png) if csv is None else csv
    save_figure(fig, png)
    table.write(csv)
    return png, csv


def figure_csv_path(png):
    """The CSV of every number a figure draws beside its PNG, when the PNG's name is taken by a
    data CSV of its own (``paper_ramp.csv``): ``<stem>_figure.csv``."""
    return Path(png).with_name(Path(png).stem + "_figure.csv")


def errorbars(ax, x, mean, sem, label=None, **kw):
    """Mean over seeds with its standard error as a band (lines) or bars (markers)."""
    x = np.asarray(x, dtype=float)
    mean = np.asarray(mean, dtype=float)
    sem = np.nan_to_num(np.asarray(sem, dtype=float))
    if kw.get("marker") and kw.get("linestyle", "-") in ("", "none", "None"):
        return ax.errorbar(x, mean, yerr=sem, label=label, capsize=2, **kw)
    (line,) = ax.plot(x, mean, label=label, **kw)
    if np.any(sem > 0):
        ax.fill_between(x, mean - sem, mean + sem, color=line.get_color(), alpha=0.25, lw=0)
    return line


def legend(ax, **kw):
    """The legend of ``ax``, only when the axis has labelled artists, placed off the data
    (:func:`tapmc._legends.place_legend`; ``outside=True`` beside the axes) once the figure
    is laid out (:func:`finish_figure`, :func:`save_figure`)."""
    return place_legend(ax, later=True, **kw)


def fmt_eps(eps):
    """Compact label of an eps value (5e-3 -> '0.005')."""
    return f"{eps:.4g}"


def figure_paths(out_dir, name):
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    return out_dir / f"{name}.png", out_dir / f"{name}.csv"
