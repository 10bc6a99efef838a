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
"""

from __future__ import annotations

import numpy as np

from . import _plotting as P
from . import _profile_runs, _runs
from ._profile_runs import BC

NAME = "fig8"


def runs(scale, seeds):
    """The constant-eps F.B.C. runs of Fig. 6 (``scale.profile_eps``)."""
    return _profile_runs.runs(scale, seeds)


def increases(campaign, bc=BC, eps_values=None):
    """dict eps -> (t, (lateral mean, sem, n), (central mean, sem, n), finals) over seeds, for
    ``eps_values`` (default: the campaign's ``profile_eps`` when its scale is known
    (``tapmc.paper._runs.campaign_scale``), else every eps of the campaign's ``bc``
    constant-eps runs)."""
    from tapmc.profiles import ProfileIncrease

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


def draw(campaign, out_dir):
    png, csv = P.figure_paths(out_dir, NAME)
    data = increases(campaign)
    start = _profile_runs.fbc_start(_runs.select(campaign, "const_", bc=BC))
    prefix = "paper:" if start == "paper" else ""
    table = P.FigureTable()
    fig, (ax_l, ax_c) = P.new_figure(2, 1)
    for eps, (t, lat, cen, finals) in data.items():
        label = f"eps = {P.fmt_eps(eps)}"
        pos = t > 0
        line = P.errorbars(ax_l, t[pos], lat[0][pos], lat[1][pos], label=label)
        P.errorbars(ax_c, t[pos], cen[0][pos], cen[1][pos], label=label, color=line.get_color())
        table.add("a", f"{prefix}eps={P.fmt_eps(eps)}", t, *lat)
        table.add("b", f"{prefix}eps={P.fmt_eps(eps)}", t, *cen)
        for name, stats in finals.items():
            name = name if name.startswith("first_tap") else f"final_{name}"
            if name.endswith(":seeds"):       # each seed's window mean and its own error
                values, errors = stats
                table.add("params", f"eps={P.fmt_eps(eps)}:{name}", [eps] * len(values),
                          values, errors, 1)
                continue
            m, s, n = stats
            table.add("params", f"eps={P.fmt_eps(eps)}:{name}", eps, m[0], s[0], n[0])
    for ax, name in ((ax_l, "lateral"), (ax_c, "central")):
        ax.set_xscale("log")
        ax.axhline(0, color="0.7", lw=0.6)
        ax.set_xlabel("t (taps)")
        ax.set_ylabel(rf"$\delta\Phi_{{\rm {name}}}$")
    ax_l.legend(fontsize=7, title=_profile_runs.START_LABEL[start], title_fontsize=7)
    return P.write_figure(fig, png, table, csv)
