# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Fig. 7 of Philippe & Bideau: transversal packing-fraction profiles Phi(x/R) (section IV.A).

F.B.C.; the initial packing (dotted) and the packing after the run (solid) at the campaign's
eps nearest to the paper's 0.1. Vertical cuts x = const (compute stereo/profile *axis x*)
restricted to one fixed z-window for both profiles (from 2R above the floor to 80 % of the
estimated initial packing height), exact bin means over bins of R/5, averaged over seeds. The
two vertical dotted lines are the frontiers 7R from the walls that separate
delta Phi_lateral from delta Phi_central (Fig. 8).

The runs start from the scale's F.B.C. packing (``Scale.fbc_start``, see
:mod:`tapmc.paper._profile_runs`); with the paper's start (``paper``, section IV.A) the initial
profile is under-populated along the walls (the paper's Fig. 7b).

CSV panels: ``a`` (series ``initial``, ``final``; x = x/R), ``params`` (``frontier_lo``,
``frontier_hi`` in units of R; ``eps``; ``paper_start``: 1 for the paper's start, 0 for the
start deposited between walls; the zone means of each seed's profile, mean and sem over seeds,
x = eps: ``initial:within_2R`` and ``final:within_2R``, Phi within 2R of either wall, the first
layer, where the paper's start is under-populated; ``initial:2R_to_7R`` and
``final:2R_to_7R``, the rest of the lateral zone; ``initial:central`` and ``final:central``,
beyond 7R).
"""

from __future__ import annotations

import numpy as np

from . import _plotting as P
from . import _profile_runs, _runs
from ._profile_runs import nearest_eps_runs, profiles

NAME = "fig7"
#: width of the lateral zone, in R (paper: the wall effects' range of about three layers).
LATERAL_WIDTH = 7.0
#: width of the first layer along a wall, in R (one diameter).
FIRST_LAYER_WIDTH = 2.0


def zone_means(x, phi, side, first_layer=FIRST_LAYER_WIDTH, lateral=LATERAL_WIDTH):
    """Means of a transversal profile ``phi`` (bin means at bin centres ``x``, in R; box side
    ``side``) over three zones: within ``first_layer`` of either wall, from there to
    ``lateral`` (the rest of the lateral zone), and beyond (central); a dict of floats."""
    x, phi = np.asarray(x, dtype=float), np.asarray(phi, dtype=float)
    dist = np.minimum(x, side - x)
    zones = {"within_2R": dist < first_layer,
             "2R_to_7R": (dist >= first_layer) & (dist < lateral),
             "central": dist >= lateral}
    return {name: float(phi[mask].mean()) if np.any(mask) else np.nan
            for name, mask in zones.items()}


def seed_zone_means(campaign, specs, side):
    """{(state, zone): (mean, sem, n)} over seeds, state 'initial' or 'final'."""
    per_seed = {}
    for spec in specs:
        blocks = _runs.profile(campaign, spec, "profile_x.dat").blocks
        x = blocks[0, :, 0] / _profile_runs.radius(spec)
        for state, block in (("initial", blocks[0]), ("final", blocks[-1])):
            for zone, value in zone_means(x, block[:, 2], side).items():
                per_seed.setdefault((state, zone), []).append([value])
    return {key: tuple(v[0] for v in P.seed_stats(values)) for key, values in per_seed.items()}


def runs(scale, seeds):
    """The constant-eps F.B.C. runs of Fig. 6 (``scale.profile_eps``)."""
    return _profile_runs.runs(scale, seeds)


def draw(campaign, out_dir):
    png, csv = P.figure_paths(out_dir, NAME)
    eps, specs = nearest_eps_runs(campaign)
    xb, im, isem, i_n, fm, fsem, f_n = profiles(campaign, specs, "profile_x.dat")
    side = float(specs[0].variables["L"])
    table = P.FigureTable()
    fig, (ax,) = P.new_figure(1, 1, height=4.0)
    P.errorbars(ax, xb, im, isem, label="initial packing", color="k", ls=":")
    P.errorbars(ax, xb, fm, fsem, label=f"after {int(specs[0].variables['taps'])} taps",
                color="C3")
    table.add("a", "initial", xb, im, isem, i_n)
    table.add("a", "final", xb, fm, fsem, f_n)
    frontiers = (LATERAL_WIDTH, side - LATERAL_WIDTH)
    for x in frontiers:
        ax.axvline(x, color="0.4", ls=":", lw=1)
    table.add("params", "frontier_lo", eps, frontiers[0], None, len(specs))
    table.add("params", "frontier_hi", eps, frontiers[1], None, len(specs))
    table.add("params", "eps", eps, eps, None, len(specs))
    start = _profile_runs.fbc_start(specs)
    table.add("params", "paper_start", eps, float(start == "paper"), None, len(specs))
    for (state, zone), (m, s, n) in seed_zone_means(campaign, specs, side).items():
        table.add("params", f"{state}:{zone}", eps, m, s, n)
    ax.set_xlabel("x/R")
    ax.set_ylabel(r"$\Phi$")
    ax.set_xlim(0, side)
    ax.legend(fontsize=8, title=f"{_profile_runs.START_LABEL[start]}, eps = {P.fmt_eps(eps)}",
              title_fontsize=7)
    return P.write_figure(fig, png, table, csv)
