# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Fig. 2 of Philippe & Bideau: bottom packing fraction Phi_b against the number of taps t.

F.B.C., three excitations (paper: eps = 5e-3, 5e-2, 0.15); top panel in logarithmic time,
bottom panel in linear time; the solid lines are the simulation (mean over seeds, with the
standard error as a band) and the dotted lines the inverse-logarithmic fits of eq. 3
(``tapmc.laws.InverseLogLaw``) of the seed-averaged curves.

CSV panels: ``a`` (the data and fits, drawn on both panels), ``params`` (one row per fitted
parameter: series ``eps=<eps>:<name>``, x = eps, mean = value, sem = 1-sigma error, n = 1 if
the fit is determined and 0 if not).
"""

from __future__ import annotations

import numpy as np

from tapmc.laws import InverseLogLaw

from . import _plotting as P
from . import _runs

NAME = "fig2"
#: Boundary conditions of the paper's Fig. 2.
BC = "fbc"
#: the paper's eps of Fig. 2.
PAPER_EPS = (5e-3, 5e-2, 0.15)


def runs(scale, seeds):
    """Constant-eps F.B.C. runs, one per eps of ``scale.fig2_eps`` and seed."""
    return [_runs.constant_eps_run(scale, BC, eps, s)
            for eps in scale.fig2_eps for s in _runs.seed_list(seeds)]


def curves(campaign, column="phi_b", bc=BC, eps_values=None):
    """dict eps -> (t, mean, sem, n) of a taps.dat column over the seeds of the campaign's
    constant-eps runs with boundary ``bc`` (all eps, or those in ``eps_values``)."""
    out = {}
    for eps, specs in _runs.constant_eps_groups(campaign, bc, eps_values).items():
        tables = [_runs.taps_table(campaign, s) for s in specs]
        length = min(len(t["step"]) for t in tables)
        t = tables[0]["step"][:length]
        mean, sem, n = P.seed_stats([tab[column][:length] for tab in tables])
        out[eps] = (t, mean, sem, n)
    return out


def fit_curve(t, mean, sem):
    """Eq. 3 fit of a seed-averaged curve (weights = standard errors when every point has one)."""
    sigma = sem if np.all(np.isfinite(sem)) and np.all(sem > 0) else None
    return InverseLogLaw().fit(t, mean, sigma=sigma)


def paper_eps(available, targets=PAPER_EPS):
    """For each of the paper's eps, the nearest available eps (in log): the campaign may hold
    more F.B.C. runs (Figs. 6-8) than Fig. 2 shows."""
    available = sorted(available)
    return sorted({min(available, key=lambda e: abs(np.log(e / t))) for t in targets})


def draw(campaign, out_dir, eps_values=None):
    """Draw Fig. 2 from the campaign's F.B.C. constant-eps runs: those of ``eps_values``, by
    default the campaign's ``fig2_eps`` when its scale is known
    (``tapmc.paper._runs.campaign_scale``), else the eps nearest to the paper's 5e-3, 5e-2
    and 0.15."""
    png, csv = P.figure_paths(out_dir, NAME)
    specs = _runs.select(campaign, "const_", bc=BC)
    available = {s.variables["eps"] for s in specs}
    if eps_values is None and available:
        scale = _runs.campaign_scale(campaign)
        eps_values = scale.fig2_eps if scale is not None else paper_eps(available)
    data = curves(campaign, "phi_b", BC, eps_values)
    table = P.FigureTable()
    fig, (ax_log, ax_lin) = P.new_figure(2, 1)
    for eps, (t, mean, sem, n) in data.items():
        label = f"eps = {P.fmt_eps(eps)}"
        fit = fit_curve(t, mean, sem)
        table.add("a", f"eps={P.fmt_eps(eps)}", t, mean, sem, n)
        tfit = np.unique(np.concatenate([np.geomspace(1, max(t[-1], 1), 200), t[t > 0][:1]]))
        yfit = fit(tfit)
        table.add("a", f"fit:eps={P.fmt_eps(eps)}", tfit, yfit, None, 0)
        for name, value in fit.params.items():
            table.add("params", f"eps={P.fmt_eps(eps)}:{name}", eps, value,
                      fit.errors.get(name, np.nan), int(bool(fit.determined)))
        table.add("params", f"eps={P.fmt_eps(eps)}:reduced_chi2", eps, fit.reduced_chi2, None,
                  int(bool(fit.determined)))
        pos = t > 0
        line = P.errorbars(ax_log, t[pos], mean[pos], sem[pos], label=label)
        ax_log.plot(tfit, yfit, ":", color=line.get_color())
        P.errorbars(ax_lin, t, mean, sem, label=label, color=line.get_color())
        ax_lin.plot(tfit, yfit, ":", color=line.get_color())
    ax_log.set_xscale("log")
    for ax in (ax_log, ax_lin):
        ax.set_xlabel("t (taps)")
        ax.set_ylabel(r"$\Phi_b$")
    ax_log.legend(fontsize=8, title="F.B.C.; dotted: eq. 3 fits", title_fontsize=8)
    return P.write_figure(fig, png, table, csv)
