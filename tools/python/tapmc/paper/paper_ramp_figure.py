# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The figure of the ramps at the paper's own protocol (:mod:`tapmc.paper.paper_ramp`, section
III.B): ``paper_ramp.png``, <Phi^c> of every whole level against sqrt(eps), one panel per eta,
with the errors the finding decides with, and beside it ``paper_ramp_figure.csv``, every number
it draws (the error bars as drawn). The analysis lives in :mod:`tapmc.paper.paper_ramp`; this
module only draws it."""

from __future__ import annotations

from pathlib import Path

from ..hysteresis import CRITICAL_SQRT_EPS
from . import _plotting, _runs
from .paper_ramp import (BRANCH_STYLE, LAST_TAPS, TAPS_PER_LEVEL, calibrated, eta_label,
                         groups_by_eta, level_errors)
from .scales import FULL


def plot(rows, default_eta, axes=None, table=None):
    """The whole levels of every ramp (:class:`PaperRampRun`), one panel per eta (the default
    first; ``axes``: one axis per eta, new ones when None): <Phi^c> against sqrt(eps), a colour
    per run, a marker per branch (:data:`BRANCH_STYLE`), error bars the levels' batch-means
    errors, a thin line through the levels in the ramp's order (the loop), (sqrt eps)* dotted;
    the panels share their <Phi^c> range. ``table``: a FigureTable that gets every plotted
    number (panel: the eta, series: run and branch). Returns the axes."""
    panels = groups_by_eta(rows, default_eta)
    if axes is None:
        _, axes = _plotting.new_figure(nrows=len(panels), height=2.8, width=6.0)
    if len(axes) < len(panels):
        raise ValueError(f"axes: {len(axes)} given, the rows have {len(panels)} etas")
    for ax, (eta, runs) in zip(axes, panels):
        for colour, run in enumerate(runs):
            ax.plot(run.level_sqrt_eps, run.level_mean, color=f"C{colour}", lw=0.8)
            for name, (marker, words) in BRANCH_STYLE.items():
                sqrt_eps, mean, sem = run.branch(name)
                if len(sqrt_eps):
                    label = f"seed {run.seed}, to {run.top:g}: {words}"
                    ax.errorbar(sqrt_eps, mean, yerr=sem, marker=marker, mfc="none", ms=5,
                                color=f"C{colour}", ls="none", capsize=2, label=label)
                    if table is not None:
                        table.add(eta_label(eta, default_eta), label, sqrt_eps, mean, sem)
        ax.axvline(CRITICAL_SQRT_EPS, color="0.5", ls=":", lw=1,
                   label=f"$(\\varepsilon^{{1/2}})^* = {CRITICAL_SQRT_EPS:g}$")
        ax.set_title(eta_label(eta, default_eta), fontsize=8)
        ax.set_xlabel(r"$\varepsilon^{1/2}$")
        ax.set_ylabel(r"$\langle\Phi^c\rangle$ (last %d taps of a level)" % LAST_TAPS,
                      fontsize=8)
        _plotting.legend(ax, fontsize=6, outside=True)
    means = [m for r in rows for m in r.level_mean]
    if means:
        pad = 0.05 * (max(means) - min(means) or 0.01)
        for ax in axes[:len(panels)]:
            ax.set_ylim(min(means) - pad, max(means) + pad)
    return axes


def settings_line(rows, error_factor=None, scale=FULL):
    """The settings the figure states on top (every number of it is a setting of the runs, of
    the campaign's ``scale``: its size, eta, and the ramp's grid), with what its error bars
    are (:func:`calibrated`'s ``error_factor``)."""
    seeds = sorted({r.seed for r in rows})
    errors = level_errors(rows, error_factor)
    bars = "their batch-means errors" + (
        "" if errors.value == 1.0 else
        f" x {errors.value:.1f} (one {LAST_TAPS}-tap mean to the next)" if errors.from_window
        else f" x {errors.value:.1f} (the realizations' spread)")
    stop = _plotting.planned_stop(_runs.paper_ramp_run(scale, "pbc", 1, scale.ramp_below_top))
    return (f"N = {scale.N}, box {scale.L:g}R x {scale.L:g}R, P.B.C.; eta: each panel's, {stop}; "
            f"{TAPS_PER_LEVEL} taps per "
            f"level, steps of {scale.ramp_dsqrt:g} in sqrt(eps), means of the last {LAST_TAPS} "
            f"taps of each level, error bars {bars}; levels done whole only; "
            f"seeds {', '.join(map(str, seeds))}; "
            + _plotting.scale_text(scale))


def write_figure(rows, default_eta, path, error_factor=None, scale=FULL):
    """``paper_ramp.png``: :func:`plot` of the rows with the errors the finding decides with
    (:func:`calibrated`), its settings on top, and beside it ``paper_ramp_figure.csv``
    (:func:`~tapmc.paper._plotting.figure_csv_path`); returns the PNG's path."""
    table = _plotting.FigureTable()
    scaled = calibrated(rows, level_errors(rows, error_factor).value)
    fig = plot(scaled, default_eta, table=table)[0].figure
    _plotting.finish_figure(fig, settings_line(rows, error_factor, scale))
    return _plotting.write_figure(fig, Path(path), table)[0]
