# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Fig. 7 of Philippe & Bideau: transversal packing-fraction profiles Phi(x/R) (section IV.A).

F.B.C.; the initial packing (dotted) and the packing after the run (solid) at the campaign's
eps nearest to the paper's 0.1. Vertical cuts x = const (compute stereo/profile *axis x*)
restricted to one fixed z-window for both profiles (from 2R above the floor to 80 % of the
estimated initial packing height), exact bin means over bins of R/5, averaged over seeds. The
two vertical dotted lines are the frontiers 7R from the walls that separate
delta Phi_lateral from delta Phi_central (Fig. 8).

CSV panels: ``a`` (series ``initial``, ``final``; x = x/R), ``params`` (``frontier_lo``,
``frontier_hi`` in units of R; ``eps``).
"""

from __future__ import annotations

from . import _plotting as P
from . import _profile_runs
from ._profile_runs import nearest_eps_runs, profiles

NAME = "fig7"
#: width of the lateral zone, in R (paper: the wall effects' range of about three layers).
LATERAL_WIDTH = 7.0


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
    ax.set_xlabel("x/R")
    ax.set_ylabel(r"$\Phi$")
    ax.set_xlim(0, side)
    ax.legend(fontsize=8, title=f"F.B.C., eps = {P.fmt_eps(eps)}", title_fontsize=7)
    return P.write_figure(fig, png, table, csv)
