# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Fig. 10 of Philippe & Bideau: volume distributions of the pores at different stages of the
compaction (section IV.B).

F.B.C., eps = 2e-2 (``scale.pore_eps``, ``scale.pore_bc``); the packing dumped at t = 0, 1, 4,
10, 30, 100, 300, 1000 and 4000 taps (``scale.dump_times``). tapmc-pores gives, in a
statistics box 2R above the floor and 2R from the walls, 18R high at most (lower when the
packing is: 80 % of its highest centre), (a) rho_v(xi) = xi^3 P(xi) against xi = r/R and
(b) rho_v(v) against v = xi^3, mean and standard error over seeds; with one seed (the paper's
protocol) the error within its dump from a spatial jackknife (4 x 4 lateral blocks of the
statistics box, ``tapmc.pores.PoreOutput.jackknife``). rho_v(v) is the paper's
(section IV.B): rho_v(v) = (xi/3) P(xi) = v n_v(v), with n_v the number density of v, so that
rho_v(v) dv = xi^3 P(xi) dxi and its integral is nu, not 1 (``tapmc.pores``, module text).
T and O mark the tetrahedral (xi_T = sqrt(3/2) - 1) and octahedral (xi_O = sqrt(2) - 1) sites.

CSV panels: ``a`` (series ``t=<taps>``, x = xi), ``b`` (series ``t=<taps>``, x = v; rho_v(v),
integral nu),
``params``: per t (x = t) ``nu`` (mean normalised pore volume), ``xi_min`` (smallest pore
size), ``xi_T`` (the start of the (xi - xi_T)^2 law fitted between 0.15 and xi_O,
``tapmc.pores.TetrahedralLaw``), ``nu_tail`` (the decay volume of the exponential tail of the
paper's rho_v(v), ``tapmc.pores.VolumeTail``; the paper: close to nu), ``small`` (integral of
xi^3 P(xi) over [xi_T, xi_O]), ``large`` (over [xi_O, inf)); ``small_change`` and
``large_change`` (integral of |rho_v(t_last) - rho_v(0)| over each range, relative to the
initial integral: the paper finds the small-pore part invariant).

:func:`analyse` returns a :class:`Fig10Result` (its ``save``/``load`` are the CSV),
:func:`plot` draws one, :func:`draw` does both into a folder.
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass

import numpy as np
from matplotlib import colormaps

from tapmc.pores import jackknife_error, read_pores

from . import _plotting as P
from . import _pores, _runs
from ._results import FigureCsvError, FigureResult, Series, Value

NAME = "fig10"
#: run-name prefix of the Fig. 10 runs.
KIND = "pores"


def runs(scale, seeds):
    """One pore-dump run per seed at ``scale.pore_eps`` and ``scale.pore_bc`` with dumps at
    ``scale.dump_times`` (and t = 0)."""
    return [_runs.pore_run(scale, scale.pore_bc, scale.pore_eps, s, scale.dump_times, kind=KIND)
            for s in _runs.seed_list(seeds)]


def _fitted(fit, key):
    try:
        return fit().params[key]
    except (ValueError, RuntimeError):
        return None


def _statistics(dist):
    """The per-dump statistics of Fig. 10 of one distribution (a dump, or a jackknife
    replicate of it): curves, nu, the fits' xi_T and nu_tail, the small and large shares."""
    return {"xi3_P_xi": dist.xi3_P_xi, "rho_v": dist.rho_v, "nu": dist.nu,
            "xi_T": _fitted(dist.tetrahedral_law, "xi_T"),
            "nu_tail": _fitted(dist.volume_tail, "nu_tail"),
            "small": _integral(dist.xi, dist.xi3_P_xi, P.XI_T, P.XI_O),
            "large": _integral(dist.xi, dist.xi3_P_xi, P.XI_O, np.inf)}


def _jackknife_errors(pores, step):
    """Errors of :func:`_statistics` within one dump: the spatial jackknife of
    ``tapmc.pores.PoreOutput.jackknife`` (a statistic a replicate's fit cannot give has none)."""
    replicates = [_statistics(r) for r in pores.jackknife(step)]
    errors = {}
    for name in replicates[0]:
        values = [r[name] for r in replicates]
        if all(v is not None for v in values):
            errors[name] = jackknife_error(values)
    return errors


def distributions(campaign, bc=None):
    """dict step -> lists over seeds of xi, xi3_P_xi, v, rho_v (the paper's rho_v(v) =
    v n_v(v)), nu, xi_min (smallest selected pore), xi_T (fitted by
    ``tapmc.pores.TetrahedralLaw``) and nu_tail (``VolumeTail`` on rho_v); with one seed (the
    paper's protocol) also ``errors``: name -> the error within the dump from the spatial
    jackknife (:func:`_jackknife_errors`)."""
    specs = _runs.select(campaign, KIND + "_", **({} if bc is None else {"bc": bc}))
    if not specs:
        raise ValueError(f"campaign {campaign.directory} has no pore-dump run")
    out = defaultdict(lambda: defaultdict(list))
    for spec in specs:
        prefix, _ = _pores.analyse(campaign, spec, "fig10", extra=["--frame-hist", "--pores"])
        pores = read_pores(prefix)
        for step in pores.timesteps:
            dist = pores.distribution(step)
            d = out[step]
            for name in ("xi", "xi3_P_xi", "v", "rho_v"):
                d[name].append(getattr(dist, name))
            d["nu"].append([dist.nu])
            sel = (pores.pores["timestep"] == step) & (pores.pores["selected"] == 1)
            d["xi_min"].append([float(pores.pores["xi"][sel].min())])
            fitted = _statistics(dist)
            for name in ("xi_T", "nu_tail"):
                if fitted[name] is not None:
                    d[name].append([fitted[name]])
            if len(specs) == 1:
                d["errors"] = _jackknife_errors(pores, step)
    return dict(sorted(out.items()))


def _integral(x, y, lo, hi):
    edges_w = np.gradient(x)
    keep = (x >= lo) & (x < hi)
    return float(np.sum(y[keep] * edges_w[keep]))


#: the statistics of each dump (params rows, x = t), in the CSV's order
DUMP_STATISTICS = ("nu", "xi_min", "xi_T", "nu_tail", "small", "large")
#: those every dump has (the others are fits, absent where one failed)
EVERY_DUMP_STATISTICS = ("nu", "small", "large")
#: the pore-size ranges of the small and large shares: tetrahedral to octahedral sites, beyond
SHARES = (("small", P.XI_T, P.XI_O), ("large", P.XI_O, np.inf))


@dataclass(frozen=True)
class PoreDump:
    """The distributions of one dump (t taps) and its statistics."""

    step: int
    #: xi^3 P(xi) against xi (panel a) and rho_v(v) against v (panel b)
    xi3_P_xi: Series
    rho_v: Series
    #: name (DUMP_STATISTICS) -> Value at x = t; a fit that failed is absent
    statistics: dict


@dataclass(frozen=True)
class Fig10Result(FigureResult):
    """The numbers of Fig. 10 (CSV schema: module text)."""

    #: t -> :class:`PoreDump`
    dumps: dict
    #: integral of |rho_v(t_last) - rho_v(0)| over each share, relative to the initial one
    small_change: Value
    large_change: Value

    def rows(self):
        out = []
        for dump in self.dumps.values():
            out += [("a", f"t={dump.step}", dump.xi3_P_xi), ("b", f"t={dump.step}", dump.rho_v)]
            out += [("params", name, value) for name, value in dump.statistics.items()]
        return out + [("params", "small_change", self.small_change),
                      ("params", "large_change", self.large_change)]

    @classmethod
    def from_rows(cls, rows):
        by_step = {name: rows.take("params", name) for name in DUMP_STATISTICS
                   if rows.has("params", name)}
        dumps = {}
        for _, label in rows.keys("a"):
            step = int(label[len("t="):])
            stats = {name: Value.of_series(series, i) for name, series in by_step.items()
                     for i in np.flatnonzero(series.x == step)}
            missing = [name for name in EVERY_DUMP_STATISTICS if name not in stats]
            if missing:
                raise FigureCsvError(rows.path, None, f"no params row {', '.join(missing)} at "
                                     f"x = {step} (every dump of panel a has one)")
            dumps[step] = PoreDump(step, rows.take("a", label), rows.take("b", label), stats)
        return cls(dumps, rows.take_value("params", "small_change"),
                   rows.take_value("params", "large_change"))


def _dump(step, d):
    """The :class:`PoreDump` of one step of :func:`distributions`: means over seeds, or with
    one seed the jackknife errors within its dump."""
    errors = d.get("errors", {})

    def stats(name, samples):
        m, s, n = P.seed_stats(samples)
        return (m, np.atleast_1d(errors[name]), n) if name in errors else (m, s, n)

    xi3 = Series.of(d["xi"][0], *stats("xi3_P_xi", d["xi3_P_xi"]))
    values = {name: Value.of_stats(step, stats(name, d[name]))
              for name in DUMP_STATISTICS[:4] if d.get(name)}
    for name, lo, hi in SHARES:
        values[name] = Value(step, _integral(xi3.x, xi3.mean, lo, hi),
                             errors.get(name, np.nan), len(d["nu"]))
    return PoreDump(step, xi3, Series.of(d["v"][0], *stats("rho_v", d["rho_v"])), values)


def analyse(campaign, bc=None):
    """Fig. 10 from the campaign's pore-dump runs (:func:`distributions`)."""
    dumps = {step: _dump(step, d) for step, d in distributions(campaign, bc).items()}
    first, last = dumps[min(dumps)].xi3_P_xi, dumps[max(dumps)].xi3_P_xi
    changes = []
    for _, lo, hi in SHARES:
        base = _integral(first.x, first.mean, lo, hi)
        change = (_integral(first.x, np.abs(last.mean - first.mean), lo, hi) / base
                  if base > 0 else np.nan)
        changes.append(Value(max(dumps), change, np.nan, 1))
    return Fig10Result(dumps, *changes)


def plot(result, settings=None):
    """The figure of a :class:`Fig10Result` (drawing only)."""
    fig, (ax_xi, ax_v) = P.new_figure(2, 1)
    for dump, color in zip(result.dumps.values(), matplotlib_colors(len(result.dumps))):
        label = f"t = {dump.step}"
        for ax, series in ((ax_xi, dump.xi3_P_xi), (ax_v, dump.rho_v)):
            P.errorbars(ax, series.x, series.mean, series.err, label=label, color=color,
                        lw=0.9)
    for ax, marks, xlabel, ylabel in (
            (ax_xi, (P.XI_T, P.XI_O), r"$\xi = r/R$", r"$\rho_v(\xi) = \xi^3 P(\xi)$"),
            (ax_v, (P.XI_T ** 3, P.XI_O ** 3), r"$v = \xi^3$", r"$\rho_v(v)$")):
        for x, name in zip(marks, "TO"):
            ax.axvline(x, color="0.5", ls="--", lw=0.6)
            ax.annotate(name, (x, 1.0), xycoords=("data", "axes fraction"), ha="center",
                        va="bottom", fontsize=9)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.set_ylim(bottom=0)
        P.legend(ax, fontsize=6, ncol=2)
    ax_xi.set_xlim(0, 1.0)
    ax_v.set_xlim(0, 0.6)
    return P.finish_figure(fig, settings, P.plotted_seeds(result))


def figure_runs(campaign):
    """The runs Fig. 10 draws: the pore-dump runs."""
    return _runs.select(campaign, KIND + "_")


def draw(campaign, out_dir):
    """Fig. 10's PNG and CSV in ``out_dir``; returns their paths."""
    settings = P.figure_settings(campaign, figure_runs(campaign), eps=True)
    return analyse(campaign).save_with_png(plot, out_dir, NAME, settings)


def matplotlib_colors(n):
    """``n`` colours of the viridis map, early to late dumps."""
    cmap = colormaps["viridis"]
    return [cmap(x) for x in np.linspace(0.0, 0.9, max(n, 1))]
