# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Fig. 8 of Philippe & Bideau: lateral (top) and central (bottom) packing-fraction increases
delta Phi_lateral(t) and delta Phi_central(t) relative to the initial packing (section IV.A).

F.B.C., four excitations (``scale.profile_eps``); the means of the transversal profile within
7R of the side walls (lateral) and beyond (central), in one fixed z-window, from compute
stereo/profile's exact zone means (taps.dat columns ``lateral`` and ``central``); the
increase per seed minus its t = 0 value (``tapmc.profiles.ProfileIncrease``), mean and
standard error over seeds. The paper finds delta Phi_central systematically below
delta Phi_lateral and a nearly frozen dynamics at small eps.

The runs start from the scale's F.B.C. packing (``Scale.fbc_start``). From the paper's start
(periodic deposition, walls, slight agitation: section IV.A) the walls are under-populated and
delta Phi_lateral jumps at the first tap, as in the paper's Fig. 8; from the start deposited
between walls it dips.

CSV panels: ``a`` (lateral) and ``b`` (central), series ``eps=<eps>`` (start deposited between
walls) or ``paper:eps=<eps>`` (the paper's start), x = t; ``params`` (whatever the start:
``eps=<eps>:final_lateral``, ``eps=<eps>:final_central`` and, paired per seed,
``eps=<eps>:final_central_minus_lateral``: mean over the last quarter of the taps, over seeds
(one seed: that run's batch-means error; with two seeds or more also
``eps=<eps>:final_<zone>:seeds``, one row per seed: its window mean and batch-means error);
``eps=<eps>:first_tap_lateral``,
``eps=<eps>:first_tap_central``: delta Phi after the first tap, over seeds; x = eps).

:func:`analyse` returns a :class:`Fig8Result` (its ``save``/``load`` are the CSV), :func:`plot`
draws one, :func:`draw` does both into a folder.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tapmc.profiles import ProfileIncrease

from . import _plotting as P
from . import _profile_runs, _runs
from ._profile_runs import BC
from ._results import FigureResult, Series, Value

NAME = "fig8"


def runs(scale, seeds):
    """The constant-eps F.B.C. runs of Fig. 6 (``scale.profile_eps``)."""
    return _profile_runs.runs(scale, seeds)


def increases(campaign, bc=BC, eps_values=None):
    """dict eps -> (t, (lateral mean, sem, n), (central mean, sem, n), finals) over seeds, for
    ``eps_values`` (default: the campaign's ``profile_eps`` when its scale is known
    (``tapmc.paper._runs.campaign_scale``), else every eps of the campaign's ``bc``
    constant-eps runs)."""
    if eps_values is None:
        scale = _runs.campaign_scale(campaign)
        eps_values = scale.profile_eps if scale is not None else None
    groups = _runs.constant_eps_groups(campaign, bc, eps_values)
    out = {}
    for eps, specs in groups.items():
        tables = [_runs.taps_table(campaign, s) for s in specs]
        length = min(len(tab["step"]) for tab in tables)
        t = tables[0]["step"][:length]
        inc = ProfileIncrease(t, np.array([tab["lateral"][:length] for tab in tables]),
                              np.array([tab["central"][:length] for tab in tables])).compute()
        n = np.full(length, len(tables))
        last = max(length // 4, 1)
        lateral_all, central_all = inc.delta_lateral_all, inc.delta_central_all
        zones = (("lateral", lateral_all), ("central", central_all),
                 ("central_minus_lateral", [c - lat for c, lat in zip(central_all, lateral_all)]))
        finals = {zone: P.window_stats(per_seed, last) for zone, per_seed in zones}
        if len(tables) >= 2:
            for zone, per_seed in zones:
                values, errors = P.window_seeds(per_seed, last)
                if np.all(np.isfinite(errors) & (errors > 0)):   # a window of batches
                    finals[f"{zone}:seeds"] = (values, errors)
        first = np.flatnonzero(t == 1)
        if len(first):
            finals.update({f"first_tap_{zone}": P.seed_stats([[x[first[0]]] for x in per_seed])
                           for zone, per_seed in (("lateral", inc.delta_lateral_all),
                                                  ("central", inc.delta_central_all))})
        out[eps] = (t, (np.asarray(inc.delta_lateral), np.asarray(inc.delta_lateral_sem), n),
                    (np.asarray(inc.delta_central), np.asarray(inc.delta_central_sem), n), finals)
    return out


#: the zones of the final window means, in the CSV's order
FINAL_ZONES = ("lateral", "central", "central_minus_lateral")
#: those every Fig. 8 CSV has (central_minus_lateral came later: the smoke page's CSV lacks it)
FINAL_ZONES_SINCE_FIRST = ("lateral", "central")
#: the zones of the first tap's increase, in the CSV's order
FIRST_TAP_ZONES = ("lateral", "central")


@dataclass(frozen=True)
class ZoneIncreases:
    """delta Phi_lateral(t) and delta Phi_central(t) at one eps with their statistics."""

    eps: float
    lateral: Series
    central: Series
    #: zone (FINAL_ZONES) -> mean over the last quarter of the taps
    final: dict
    #: zone -> each seed's window mean and its batch-means error (two seeds or more)
    final_seeds: dict
    #: zone (FIRST_TAP_ZONES) -> delta Phi after the first tap
    first_tap: dict

    def rows(self, prefix):
        label = f"eps={P.fmt_eps(self.eps)}"
        return ([("a", prefix + label, self.lateral), ("b", prefix + label, self.central)]
                + [("params", f"{label}:final_{zone}", v) for zone, v in self.final.items()]
                + [("params", f"{label}:final_{zone}:seeds", v)
                   for zone, v in self.final_seeds.items()]
                + [("params", f"{label}:first_tap_{zone}", v)
                   for zone, v in self.first_tap.items()])

    @classmethod
    def from_rows(cls, rows, prefix, label):
        def zones(names, form, take):
            """The zones' rows the CSV has (each zone's seeds are written when its seeds'
            errors are finite)."""
            return {zone: take("params", f"{label}:{form.format(zone)}") for zone in names
                    if rows.has("params", f"{label}:{form.format(zone)}")}

        first_tap = [("params", f"{label}:first_tap_{zone}") for zone in FIRST_TAP_ZONES]

        return cls(float(label[len("eps="):]), rows.take("a", prefix + label),
                   rows.take("b", prefix + label),
                   {zone: rows.take_value("params", f"{label}:final_{zone}")
                    for zone in FINAL_ZONES
                    if zone in FINAL_ZONES_SINCE_FIRST
                    or rows.has("params", f"{label}:final_{zone}")},
                   zones(FINAL_ZONES, "final_{}:seeds", rows.take),
                   # both zones of tap 1 or none (a run without tap 1); one alone is refused
                   zones(FIRST_TAP_ZONES, "first_tap_{}", rows.take_value)
                   if rows.together(*first_tap) else {})


@dataclass(frozen=True)
class Fig8Result(FigureResult):
    """The numbers of Fig. 8 (CSV schema: module text)."""

    #: True when the runs start from the paper's packing (series ``paper:eps=...``)
    paper_start: bool
    #: eps -> :class:`ZoneIncreases`
    increases: dict

    def rows(self):
        prefix = "paper:" if self.paper_start else ""
        return [row for inc in self.increases.values() for row in inc.rows(prefix)]

    @classmethod
    def from_rows(cls, rows):
        series = [s for _, s in rows.keys("a")]
        paper_start = bool(series) and series[0].startswith("paper:")
        prefix = "paper:" if paper_start else ""
        increases = [ZoneIncreases.from_rows(rows, prefix, s[len(prefix):]) for s in series]
        return cls(paper_start, {inc.eps: inc for inc in increases})


def analyse(campaign):
    """Fig. 8 from the campaign's F.B.C. constant-eps runs (:func:`increases`)."""
    start = _profile_runs.fbc_start(_runs.select(campaign, "const_", bc=BC))
    out = {}
    for eps, (t, lat, cen, finals) in increases(campaign).items():
        final = {z: Value.of_stats(eps, finals[z]) for z in FINAL_ZONES}
        seeds = {z: Series.of([eps] * len(finals[f"{z}:seeds"][0]), *finals[f"{z}:seeds"], 1)
                 for z in FINAL_ZONES if f"{z}:seeds" in finals}
        first = {z: Value.of_stats(eps, finals[f"first_tap_{z}"]) for z in FIRST_TAP_ZONES
                 if f"first_tap_{z}" in finals}
        out[eps] = ZoneIncreases(eps, Series.of(t, *lat), Series.of(t, *cen), final, seeds,
                                 first)
    return Fig8Result(start == "paper", out)


def plot(result, settings=None):
    """The figure of a :class:`Fig8Result` (drawing only)."""
    fig, (ax_l, ax_c) = P.new_figure(2, 1)
    for eps, inc in result.increases.items():
        label = f"eps = {P.fmt_eps(eps)}"
        pos = inc.lateral.x > 0
        line = P.errorbars(ax_l, inc.lateral.x[pos], inc.lateral.mean[pos],
                           inc.lateral.err[pos], label=label)
        P.errorbars(ax_c, inc.central.x[pos], inc.central.mean[pos], inc.central.err[pos],
                    label=label, color=line.get_color())
    start = "paper" if result.paper_start else "walls"
    for ax, name in ((ax_l, "lateral"), (ax_c, "central")):
        ax.set_xscale("log")
        ax.axhline(0, color="0.7", lw=0.6)
        ax.set_xlabel("t (taps)")
        ax.set_ylabel(rf"$\delta\Phi_{{\rm {name}}}$")
        P.legend(ax, fontsize=7, title=_profile_runs.START_LABEL[start],
                  title_fontsize=7)
    return P.finish_figure(fig, settings, P.plotted_seeds(result))


def draw(campaign, out_dir):
    """Fig. 8's PNG and CSV in ``out_dir``; returns their paths."""
    return analyse(campaign).save_with_png(
        plot, out_dir, NAME, P.figure_settings(campaign, figure_runs(campaign)))


def figure_runs(campaign):
    """The runs Fig. 8 draws: the F.B.C. constant-eps runs of :func:`increases`."""
    scale = _runs.campaign_scale(campaign)
    eps_values = scale.profile_eps if scale is not None else None
    return [s for group in _runs.constant_eps_groups(campaign, BC, eps_values).values()
            for s in group]
