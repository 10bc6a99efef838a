# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Fig. 9 of Philippe & Bideau: Gotoh's pore size distribution P0(sigma) against the
Percus-Yevick expression (section IV.B, eqs. 8-9).

P.B.C.; P0 measured by tapmc-pores (the probability that a random point of the statistics
box lies farther than sigma R from every centre) for the packing after the run (open
circles) and for the initial packing (thin line), mean and standard error over seeds; the
thick line is the Percus-Yevick P0 (``tapmc.pores.percus_yevick_p0``) at the volume fraction
of the final packings (the fraction of random points inside a sphere). The paper finds the
measured P0 close to the theory and hardly different between the initial (58.4 %) and the
tapped (60.6 %) packings.

CSV panels: ``a`` (series ``final``, ``initial``, ``percus_yevick``; x = sigma), ``params``
(``phi_initial``, ``phi_final`` seen by the random points; ``max_abs_diff_initial_final``,
``max_abs_diff_final_py``; ``phi_c_initial``, ``phi_c_final`` of the stereology at the two
dumps; ``phi_c_steady``: the steady state of <Phi^c>, the mean over the last quarter of the
taps (the paper's last 1000 of 4000), whose sem is over seeds, or for one seed (n = 1) the
batch-means error of that mean (``tapmc.fluctuations.SteadyState``, successive taps being
correlated); ``phi_c_tap_sd``: the standard deviation of single taps about it (the spread of a
value read at one tap, as the paper's 60.6 % is)).
"""

from __future__ import annotations

import numpy as np

from tapmc.fluctuations import SteadyState

from . import _plotting as P
from . import _pores, _runs
from ._steady_state import steady_last

NAME = "fig9"
BC = "pbc"
#: eps of the Fig. 9 runs when the campaign's scale is not recorded (that of the presets).
DEFAULT_P0_EPS = 0.0225


def runs(scale, seeds):
    """One constant-eps P.B.C. run per seed at ``scale.p0_eps`` (the paper does not give the eps
    of Fig. 9; the presets take one of their bell's eps, so the run is shared with Figs. 3-4),
    which dumps its packing at t = 0 and after ``scale.taps`` taps."""
    return [_runs.constant_eps_run(scale, BC, scale.p0_eps, s) for s in _runs.seed_list(seeds)]


def p0_runs(campaign, bc=BC):
    """(eps, specs): the campaign's constant-eps runs of ``bc`` at its scale's ``p0_eps``
    (nearest eps when the scale is not recorded)."""
    scale = _runs.campaign_scale(campaign)
    groups = _runs.constant_eps_groups(campaign, bc)
    target = scale.p0_eps if scale is not None else DEFAULT_P0_EPS
    eps = min(groups, key=lambda e: abs(np.log(e / target)))
    return eps, groups[eps]


def p0_curves(campaign, bc=BC):
    """dict 'initial'/'final' -> (sigma, list of P0 per seed, list of phi per seed) and the
    stereological <Phi^c> at both ends, over the runs of :func:`p0_runs`."""
    from tapmc.pores import read_pores

    _, specs = p0_runs(campaign, bc)
    out = {"initial": [None, [], []], "final": [None, [], []]}
    phi_c = {"initial": [], "final": [], "steady": []}
    for spec in specs:
        files = _pores.dumps(_runs.run_dir(campaign, spec))
        first, last = min(files), max(files)
        tab = _runs.taps_table(campaign, spec)
        for key, step in (("initial", first), ("final", last)):
            prefix, _ = _pores.analyse(campaign, spec, f"p0_t{step}", steps=[step],
                                       extra=["--p0", str(_pores.P0_POINTS), "--seed",
                                              str(spec.seed)])
            pores = read_pores(prefix)
            out[key][0] = pores.p0["sigma"]
            out[key][1].append(pores.p0["P0_measured"])
            out[key][2].append([float(pores.frames["phi_p0"][0])])
            row = np.searchsorted(tab["step"], step)
            phi_c[key].append([tab["phi_c"][row]])
        series = np.asarray(tab["phi_c"], dtype=float)
        phi_c["steady"].append(SteadyState(series, last=steady_last(len(series) - 1)).compute())
    return out, phi_c


def steady_phi(states):
    """(mean, sem, n, tap_sd) of the steady <Phi^c> over the runs' SteadyState results: sem
    over seeds, or the batch-means error of one run's mean when there is one seed."""
    means = [s.mean for s in states]
    tap_sd = float(np.mean([s.std for s in states]))
    if len(states) == 1:
        return means[0], states[0].sem, 1, tap_sd
    m, s, n = P.seed_stats([[v] for v in means])
    return float(m[0]), float(s[0]), int(n[0]), tap_sd


def draw(campaign, out_dir):
    from tapmc.pores import percus_yevick_p0

    png, csv = P.figure_paths(out_dir, NAME)
    curves, phi_c = p0_curves(campaign)
    table = P.FigureTable()
    fig, (ax,) = P.new_figure(1, 1, height=4.0)
    stats = {}
    for key in ("final", "initial"):
        sigma, p0s, phis = curves[key]
        mean, sem, n = P.seed_stats(p0s)
        stats[key] = (sigma, mean)
        pm, ps, pn = P.seed_stats(phis)
        table.add("a", key, sigma, mean, sem, n)
        table.add("params", f"phi_{key}", 0.0, pm[0], ps[0], pn[0])
        cm, cs, cn = P.seed_stats(phi_c[key])
        table.add("params", f"phi_c_{key}", 0.0, cm[0], cs[0], cn[0])
        if key == "final":
            phi_final = pm[0]
            every = max(len(sigma) // 40, 1)
            ax.errorbar(sigma[::every], mean[::every], yerr=np.nan_to_num(sem[::every]),
                        marker="o", mfc="none", ls="none", color="C0", capsize=1,
                        label=f"after the taps ($\\Phi$ = {100 * pm[0]:.1f} %)")
        else:
            ax.plot(sigma, mean, "-", lw=0.8, color="k",
                    label=f"initial packing ($\\Phi$ = {100 * pm[0]:.1f} %)")
    m, s, n, tap_sd = steady_phi(phi_c["steady"])
    table.add("params", "phi_c_steady", 0.0, m, s, n)
    table.add("params", "phi_c_tap_sd", 0.0, tap_sd, None, n)
    sigma = stats["final"][0]
    theory = np.asarray(percus_yevick_p0(sigma, phi_final), dtype=float)
    ax.plot(sigma, theory, "-", lw=2.5, color="C1", alpha=0.7,
            label=f"Percus-Yevick, $\\Phi$ = {100 * phi_final:.1f} %")
    table.add("a", "percus_yevick", sigma, theory, None, 0)
    table.add("params", "max_abs_diff_initial_final", 0.0,
              float(np.max(np.abs(stats["final"][1] - stats["initial"][1]))), None, 1)
    table.add("params", "max_abs_diff_final_py", 0.0,
              float(np.max(np.abs(stats["final"][1] - theory))), None, 1)
    ax.set_yscale("log")
    ax.set_ylim(max(1e-5, float(np.nanmin(stats["final"][1][stats["final"][1] > 0])) / 2), 1.2)
    ax.set_xlabel(r"$\sigma = r'/R$")
    ax.set_ylabel(r"$P_0(\sigma)$")
    ax.legend(fontsize=7, title="P.B.C.", title_fontsize=7)
    return P.write_figure(fig, png, table, csv)
