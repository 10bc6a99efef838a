# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Fig. 4 of Philippe & Bideau: steady-state <Phi^c> against sqrt(eps) and the hysteresis loop
(section III.B).

Solid black squares: the steady state of independent constant-eps runs from fresh packings
(mean of <Phi^c> over the last quarter of the taps of each seed, paper: the last 1000 of
4000), mean and standard error over seeds; the paper finds a bell with its maximum for
sqrt(eps) between 0.1 and 0.2. Open symbols: one tapping sequence with sqrt(eps) going up by
``dsqrt`` every P taps (circles), down again (up-triangles) and up again (down-triangles),
each level's steady state from ``tapmc.hysteresis.Hysteresis``, averaged over seeds.

CSV panels: ``a`` (series ``steady`` with x = sqrt(eps), and ``up1``, ``down``, ``up2``),
``params`` (``sqrt_eps_max``: the sqrt(eps) of the highest steady-state square, sem = half
the grid spacing there; ``phi_c_max`` the value there).
"""

from __future__ import annotations

from collections import defaultdict

import numpy as np

from tapmc.fluctuations import SteadyState

from . import _plotting as P
from . import _runs, _steady_state
from ._steady_state import BC, steady_last

NAME = "fig4"
BRANCH_STYLE = {"up1": ("o", "increase"), "down": ("^", "decrease"), "up2": ("v", "increase again")}


def runs(scale, seeds):
    """The constant-eps P.B.C. runs of ``scale.steady_eps`` (shared with Fig. 3:
    ``_steady_state.runs``) and one ramp run per seed."""
    return (_steady_state.runs(scale, seeds)
            + [_runs.ramp_run(scale, BC, s) for s in _runs.seed_list(seeds)])


def steady_states(campaign, column="phi_c", bc=BC):
    """(sqrt_eps, mean, sem, n) of the steady state of ``column`` over seeds, per eps."""
    groups = _runs.constant_eps_groups(campaign, bc)
    eps_list, means, sems, ns = [], [], [], []
    for eps, specs in groups.items():
        values = []
        for spec in specs:
            x = _runs.taps_table(campaign, spec)[column][1:]
            values.append([SteadyState(x, last=steady_last(len(x))).compute().mean])
        m, s, n = P.seed_stats(values)
        eps_list.append(eps)
        means.append(m[0])
        sems.append(s[0])
        ns.append(n[0])
    return np.sqrt(eps_list), np.array(means), np.array(sems), np.array(ns)


def _level_records(levels):
    """Hysteresis levels as a list of dicts (branch, sqrt_eps, mean)."""
    if isinstance(levels, np.ndarray) and levels.dtype.names:
        return [{k: levels[k][i] for k in levels.dtype.names} for i in range(len(levels))]
    return [dict(level) for level in levels]


def hysteresis_branches(campaign, column="phi_c", bc=BC):
    """dict branch -> (sqrt_eps, mean, sem, n) over the seeds of the ramp runs."""
    from tapmc.hysteresis import Hysteresis

    specs = _runs.select(campaign, "ramp_", bc=bc)
    collected = defaultdict(lambda: defaultdict(list))
    for spec in specs:
        tab = _runs.taps_table(campaign, spec)
        per_level = int(spec.variables["P"])
        last = steady_last(per_level)
        hyst = Hysteresis(tab["sqrt_eps"][1:], tab[column][1:], taps_per_level=per_level,
                          last=last).compute()
        for rec in _level_records(hyst.levels):
            key = round(float(rec["sqrt_eps"]), 9)
            collected[str(rec["branch"])][key].append(float(rec["mean"]))
    out = {}
    for branch, by_sq in collected.items():
        sq = np.array(sorted(by_sq))
        stats = [P.seed_stats([[v] for v in by_sq[k]]) for k in sq]
        out[branch] = (sq, np.array([s[0][0] for s in stats]), np.array([s[1][0] for s in stats]),
                       np.array([s[2][0] for s in stats]))
    return out


def bell_maximum(sq, mean):
    """sqrt(eps) of the highest steady state and half the grid spacing around it."""
    i = int(np.nanargmax(mean))
    spacing = np.diff(sq)
    half = 0.5 * (spacing[max(i - 1, 0)] if i > 0 else spacing[0]) if len(sq) > 1 else np.nan
    return sq[i], half, mean[i]


def draw(campaign, out_dir):
    png, csv = P.figure_paths(out_dir, NAME)
    table = P.FigureTable()
    fig, (ax,) = P.new_figure(1, 1, height=4.0)
    sq, mean, sem, n = steady_states(campaign)
    ax.errorbar(sq, mean, yerr=np.nan_to_num(sem), marker="s", color="k", ls="none", capsize=2,
                label="after the run at constant eps")
    table.add("a", "steady", sq, mean, sem, n)
    sq_max, half, phi_max = bell_maximum(sq, mean)
    table.add("params", "sqrt_eps_max", 0.0, sq_max, half, len(sq))
    table.add("params", "phi_c_max", sq_max, phi_max, sem[int(np.nanargmax(mean))], len(sq))
    if _runs.select(campaign, "ramp_", bc=BC):
        for branch, (bsq, bmean, bsem, bn) in hysteresis_branches(campaign).items():
            marker, label = BRANCH_STYLE.get(branch, ("x", branch))
            ax.errorbar(bsq, bmean, yerr=np.nan_to_num(bsem), marker=marker, mfc="none", ls="-",
                        lw=0.6, capsize=2, label=f"ramp: {label}")
            table.add("a", branch, bsq, bmean, bsem, bn)
    ax.set_xlabel(r"$\varepsilon^{1/2}$")
    ax.set_ylabel(r"steady state $\langle\Phi^c\rangle$")
    ax.legend(fontsize=7, title="P.B.C.", title_fontsize=7)
    return P.write_figure(fig, png, table, csv)
