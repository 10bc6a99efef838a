# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Fig. 5 of Philippe & Bideau: ageing of the time-correlation function A(t, t_W) of <Z>
(section III.C, eqs. 5-6).

P.B.C., ``scale.ageing_eps``; realizations share the initial packing and differ by the Monte
Carlo seed (the paper averaged 10). Top: A(t, t_W) (``tapmc.ageing.Ageing``, averaged over the
realizations, with its standard error) for the waiting times ``scale.ageing_waiting_times``.
Bottom: the collapse: the same curves in logarithmic time with one eq. 6,
A_inf (1 - 1/(1 + B_A ln(1 + t/tau_A))), fitted to all of them together (``Ageing.collapse``,
dotted); its reduced chi2 measures the collapse. Each curve is also fitted alone
(``Ageing.fit``).

CSV panels: ``a`` (series ``tw=<t_W>``, x = t; drawn on both panels), ``b`` (``eq6``, the
common fit), ``params`` (``tw=<t_W>:<parameter>`` with x = t_W,
sem = 1-sigma error, n = 1 when the fit is determined, 0 when not; ``collapse:<parameter>``
and ``collapse:reduced_chi2`` of the common fit).
"""

from __future__ import annotations

import numpy as np

from tapmc.laws import AgeingLaw

from . import _plotting as P
from . import _runs

NAME = "fig5"
BC = "pbc"


def runs(scale, seeds):
    """One ageing realization (in.ageing) per seed."""
    return [_runs.ageing_run(scale, BC, scale.ageing_eps, s) for s in _runs.seed_list(seeds)]


def ageing(campaign, waiting_times=None, bc=BC):
    """The Ageing result of the campaign's ageing runs of ``bc``."""
    from tapmc.ageing import Ageing

    specs = sorted(_runs.select(campaign, "ageing_", bc=bc), key=lambda s: s.seed)
    if not specs:
        raise ValueError(f"campaign {campaign.directory} has no ageing {bc} run")
    series = [_runs.taps_table(campaign, s)["Z"] for s in specs]
    length = min(len(z) for z in series)
    z = np.array([s[:length] for s in series])
    if waiting_times is None:
        scale = _runs.campaign_scale(campaign)
        if scale is not None and scale.ageing_taps == length - 1:
            waiting_times = scale.ageing_waiting_times
        else:
            waiting_times = default_waiting_times(length - 1)
    return Ageing(z, waiting_times).compute(), len(specs)


#: the paper's waiting times as fractions of a 4000-tap realization, for runs of no preset
#: scale (runs of a preset use its ``ageing_waiting_times``).
PAPER_WAITING_FRACTIONS = (10 / 4000, 30 / 4000, 100 / 4000, 300 / 4000, 1000 / 4000)


def default_waiting_times(taps):
    return sorted({max(1, int(round(f * taps))) for f in PAPER_WAITING_FRACTIONS})


def _curves(result):
    """(t_W, t, A, sem) per waiting time from an Ageing result."""
    out = []
    for tw in sorted(result.A):
        t = np.asarray(result.t[tw] if isinstance(result.t, dict) else result.t, dtype=float)
        a = np.asarray(result.A[tw], dtype=float)
        sem = result.A_sem[tw] if getattr(result, "A_sem", None) is not None else None
        sem = np.full(a.shape, np.nan) if sem is None else np.asarray(sem, dtype=float)
        n = min(len(t), len(a))
        out.append((tw, t[:n], a[:n], sem[:n]))
    return out


def draw(campaign, out_dir, waiting_times=None):
    png, csv = P.figure_paths(out_dir, NAME)
    result, nreal = ageing(campaign, waiting_times)
    table = P.FigureTable()
    fig, (ax_a, ax_c) = P.new_figure(2, 1)
    for tw, t, a, sem in _curves(result):
        pos = t > 0
        line = P.errorbars(ax_a, t, a, sem, label=f"$t_W$ = {tw:g}")
        ax_c.plot(t[pos], a[pos], "o", ms=2, color=line.get_color(), label=f"$t_W$ = {tw:g}")
        table.add("a", f"tw={tw:g}", t, a, sem, nreal)
        try:
            fit = result.fit(tw)
        except (ValueError, RuntimeError):
            # too few realizations for the library's own error estimate: a direct eq. 6 fit
            # weighted by the standard errors where they exist
            keep = pos & (np.nan_to_num(sem) > 0)
            try:
                fit = AgeingLaw().fit(t[keep], a[keep], sigma=sem[keep])
            except (ValueError, RuntimeError):
                continue
        for name, value in fit.params.items():
            table.add("params", f"tw={tw:g}:{name}", tw, value, fit.errors.get(name, np.nan),
                      int(bool(fit.determined)))
    try:
        common = result.collapse()
    except (ValueError, RuntimeError):
        common = None
    if common is not None:
        t = np.asarray(result.t, dtype=float)
        ts = np.geomspace(max(t[t > 0].min(), 1.0), t.max(), 200)
        ax_c.plot(ts, common(ts), "k:", lw=1.5,
                  label="eq. 6" + ("" if common.determined else " (not determined)"))
        table.add("b", "eq6", ts, common(ts), None, 0)
        table.add("params", "collapse:reduced_chi2", 0.0, common.reduced_chi2, None,
                  int(bool(common.determined)))
        for name, value in common.params.items():
            table.add("params", f"collapse:{name}", 0.0, value, common.errors.get(name, np.nan),
                      int(bool(common.determined)))
    ax_a.set_xlabel("t (taps)")
    ax_a.set_ylabel(r"$A(t, t_W)$")
    ax_a.legend(fontsize=7, title=f"P.B.C., {nreal} realizations", title_fontsize=7)
    ax_c.set_xscale("log")
    ax_c.set_xlabel("t (taps)")
    ax_c.set_ylabel(r"$A(t, t_W)$")
    ax_c.legend(fontsize=7)
    return P.write_figure(fig, png, table, csv)
