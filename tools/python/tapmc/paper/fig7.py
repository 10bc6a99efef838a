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
``frontier_hi`` in units of R; ``eps``; ``taps``: the taps of the runs, the legend's "after N
taps"; ``paper_start``: 1 for the paper's start, 0 for the
start deposited between walls; the zone means of each seed's profile, mean and sem over seeds,
x = eps: ``initial:within_2R`` and ``final:within_2R``, Phi within 2R of either wall, the first
layer, where the paper's start is under-populated; ``initial:2R_to_7R`` and
``final:2R_to_7R``, the rest of the lateral zone; ``initial:central`` and ``final:central``,
beyond 7R).

:func:`analyse` returns a :class:`Fig7Result` (its ``save``/``load`` are the CSV), :func:`plot`
draws one, :func:`draw` does both into a folder.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _plotting as P
from . import _profile_runs, _runs
from ._profile_runs import nearest_eps_runs, profiles
from ._results import FigureResult, Series, Value

NAME = "fig7"
#: width of the lateral zone, in R (paper: the wall effects' range of about three layers).
LATERAL_WIDTH = 7.0
#: width of the first layer along a wall, in R (one diameter).
FIRST_LAYER_WIDTH = 2.0
#: the packings of the figure and the zones of :func:`zone_means`, in the CSV's order
STATES = ("initial", "final")
ZONES = ("within_2R", "2R_to_7R", "central")


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
        for state, block in zip(STATES, (blocks[0], blocks[-1])):
            for zone, value in zone_means(x, block[:, 2], side).items():
                per_seed.setdefault((state, zone), []).append([value])
    return {key: tuple(v[0] for v in P.seed_stats(values)) for key, values in per_seed.items()}


def runs(scale, seeds):
    """The constant-eps F.B.C. runs of Fig. 6 (``scale.profile_eps``)."""
    return _profile_runs.runs(scale, seeds)


@dataclass(frozen=True)
class Fig7Result(FigureResult):
    """The numbers of Fig. 7 (CSV schema: module text)."""

    eps: float
    seeds: int
    #: True from the paper's start, False from the start deposited between walls, None when
    #: not recorded (CSVs drawn before the starts were two)
    paper_start: object
    #: the zone frontiers LATERAL_WIDTH from either wall, in R
    frontiers: tuple
    initial: Series
    final: Series
    #: (state, zone) -> the zone mean over seeds (:func:`seed_zone_means`)
    zones: dict
    #: taps of the runs (the legend's "after N taps"; None in CSVs written before it)
    taps: int = None

    @property
    def side(self):
        """The box side in R: the frontiers stand LATERAL_WIDTH from either wall."""
        return self.frontiers[0] + self.frontiers[1]

    def rows(self):
        x, n = self.eps, self.seeds
        out = [("a", "initial", self.initial), ("a", "final", self.final),
               ("params", "frontier_lo", Value(x, self.frontiers[0], np.nan, n)),
               ("params", "frontier_hi", Value(x, self.frontiers[1], np.nan, n)),
               ("params", "eps", Value(x, self.eps, np.nan, n))]
        if self.paper_start is not None:
            out.append(("params", "paper_start", Value(x, float(self.paper_start), np.nan, n)))
        if self.taps is not None:
            out.append(("params", "taps", Value(x, float(self.taps), np.nan, n)))
        return out + [("params", f"{state}:{zone}", value)
                      for (state, zone), value in self.zones.items()]

    @classmethod
    def from_rows(cls, rows):
        initial, final = rows.take("a", "initial"), rows.take("a", "final")
        lo, hi = rows.take_value("params", "frontier_lo"), rows.take_value("params", "frontier_hi")
        eps = rows.take_value("params", "eps")
        start = (rows.take_value("params", "paper_start")
                 if rows.has("params", "paper_start") else None)
        taps = rows.take_value("params", "taps") if rows.has("params", "taps") else None
        zones = {(state, zone): rows.take_value("params", f"{state}:{zone}")
                 for state in STATES for zone in ZONES if rows.has("params", f"{state}:{zone}")}
        return cls(eps.value, eps.n, None if start is None else bool(start.value),
                   (lo.value, hi.value), initial, final, zones,
                   None if taps is None else int(taps.value))


def analyse(campaign):
    """Fig. 7 from the campaign's F.B.C. runs at the eps nearest to the paper's 0.1."""
    eps, specs = nearest_eps_runs(campaign)
    xb, im, isem, i_n, fm, fsem, f_n = profiles(campaign, specs, "profile_x.dat")
    side = float(specs[0].variables["L"])
    zones = {key: Value(eps, m, s, n)
             for key, (m, s, n) in seed_zone_means(campaign, specs, side).items()}
    return Fig7Result(eps, len(specs), _profile_runs.fbc_start(specs) == "paper",
                      (LATERAL_WIDTH, side - LATERAL_WIDTH), Series.of(xb, im, isem, i_n),
                      Series.of(xb, fm, fsem, f_n), zones, int(specs[0].variables["taps"]))


def plot(result, settings=None):
    """The figure of a :class:`Fig7Result` (drawing only)."""
    fig, (ax,) = P.new_figure(1, 1, height=4.0)
    final = P.after_taps(result.taps, settings)
    P.errorbars(ax, result.initial.x, result.initial.mean, result.initial.err,
                label="initial packing", color="k", ls=":")
    P.errorbars(ax, result.final.x, result.final.mean, result.final.err, label=final,
                color="C3")
    for x in result.frontiers:
        ax.axvline(x, color="0.4", ls=":", lw=1)
    ax.set_xlabel("x/R")
    ax.set_ylabel(r"$\Phi$")
    ax.set_xlim(0, result.side)
    start = "paper" if result.paper_start else "walls"
    P.legend(ax, fontsize=8,
              title=f"{_profile_runs.START_LABEL[start]}, eps = {P.fmt_eps(result.eps)}",
              title_fontsize=7)
    return P.finish_figure(fig, settings, P.plotted_seeds(result))


def draw(campaign, out_dir):
    """Fig. 7's PNG and CSV in ``out_dir``; returns their paths."""
    return analyse(campaign).save_with_png(
        plot, out_dir, NAME, P.figure_settings(campaign, figure_runs(campaign)))


def figure_runs(campaign):
    """The runs Fig. 7 draws: the F.B.C. runs at the eps nearest to the paper's 0.1."""
    return nearest_eps_runs(campaign)[1]
