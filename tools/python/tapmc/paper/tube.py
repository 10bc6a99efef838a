# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Figures of a tapping run in a tube (examples/cylinder), the geometry of the experiments the
paper compares with: each writes one PNG and one CSV in the figures' tidy format
(:mod:`tapmc.paper._plotting`: panel,series,x,mean,sem,n; one row per plotted number, n = 1:
one run).

* :func:`compaction_figure`: panel ``a``, the packing fractions against taps (series
  ``Phi_b``, ``<Phi^c>``, ``phi_wall``, ``phi_core`` and ``fit:<Phi^c>``, eq. 3, when fitted;
  taps >= 1, the log axis), panel ``b``, <Z> (series ``<Z>``);
* :func:`radial_profile_figure`: panel ``a``, the annulus volume fraction against the distance
  from the axis, one series ``t=<step>`` per written profile.

Both state the run's settings (N, tube diameter, eps, eta, taps) in the title.
"""

from __future__ import annotations

from pathlib import Path

from . import _plotting as P

__all__ = ["compaction_figure", "radial_profile_figure"]


def _paths(prefix):
    prefix = Path(prefix)
    return prefix.with_name(prefix.name + ".png"), prefix.with_name(prefix.name + ".csv")


def compaction_figure(compaction, prefix):
    """Draw a :class:`tapmc.tube_runs.TubeCompaction` (computed here when it is not yet) into
    ``prefix``.png and ``prefix``.csv; returns their paths."""
    if not compaction.computed:
        compaction.compute()
    png, csv = _paths(prefix)
    table = P.FigureTable()
    fig, (ax_a, ax_b) = P.new_figure(2, 1, height=3.2, width=6.0)
    compaction.plot(ax_a)
    for name, (t, y) in compaction.plotted().items():
        table.add("a", name, t, y)
    compaction.plot_height(ax_b)
    keep = compaction.taps >= 1
    table.add("b", "<Z>", compaction.taps[keep], compaction.curves["<Z>"][keep])
    return P.write_figure(fig, png, table, csv)


def radial_profile_figure(profiles, prefix):
    """Draw a :class:`tapmc.tube_runs.RadialProfiles` into ``prefix``.png and ``prefix``.csv;
    returns their paths."""
    png, csv = _paths(prefix)
    table = P.FigureTable()
    fig, (ax,) = P.new_figure(1, 1, height=3.6, width=6.0)
    profiles.plot(ax)
    for k, step in enumerate(profiles.steps):
        table.add("a", f"t={int(step)}", profiles.r, profiles.phi[k])
    return P.write_figure(fig, png, table, csv)
