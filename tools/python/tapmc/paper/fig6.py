# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Fig. 6 of Philippe & Bideau: vertical packing-fraction profiles Phi(z/R) with the eq. 7 fit
(section IV.A).

F.B.C.; the initial packing (dotted) and the packing after the run (solid) at the campaign's
eps nearest to the paper's 0.1. The profile is the exact slab average of compute
stereo/profile over bins of R/5 (the "smoothing" of the paper), averaged over seeds. Thin
lines: eq. 7 (``tapmc.laws.ProfileLaw``) fitted to the seed-averaged profiles.

The gradient alpha (``tapmc.laws.profile_gradient``, straight line Phi0 - alpha z/R) is fitted
per seed in the paper's window 5 <= z/R <= 22 (F.B.C.), cut at 78 % of the packing height
(22R of the paper's 28R) when the packing is lower; alpha > 0 is the paper's "negative
vertical gradient" (density decreasing with height).

Bottom panel, when the campaign has the P.B.C. constant-eps runs of the bell (Figs. 3-4):
alpha after the taps against sqrt(eps), the paper's "approximately the same kind of bell shape
dependence as the other steady-state values" (section IV.A), fitted in the P.B.C. window
5 <= z/R <= 26 cut as above; the sem is over seeds, or for one seed (the paper's protocol)
the error within its packing: the lateral jackknife of the profile of the packing dumped after
the last tap (4 x 4 blocks, ``tapmc.profiles.vertical_profile_jackknife``), as for
``final:alpha``. ``runs`` does not add those runs: ``tapmc-paper fig6`` alone draws the top panel, the
report (every figure) both.

Open symbols in the bottom panel, when the campaign has the ramp of Fig. 4: alpha in the profile
the ramp prints at the end of every level (``in.ramp``'s profile_z.dat), per branch (first
increase, decrease, second increase), for the paper's "alpha presents no hysteresis effect"
(section IV.A). The ramp prints no h_s, so its window is cut at WINDOW_TOP_FRACTION of the
height of its initial profile (:func:`profile_height`); the error is over seeds, or for one
seed the straight line's own (too small: the claim's statistic uses the scatter of the levels).

CSV panels: ``a`` (series ``initial``, ``final``, ``fit:initial``, ``fit:final``; x = z/R),
``b`` (series ``bell:alpha`` and ``ramp:up1``, ``ramp:down``, ``ramp:up2``: x = sqrt(eps)),
``params`` (``initial:alpha``, ``final:alpha``
over seeds; with two seeds or more ``final:alpha:seeds``, one row per seed: its alpha and the
lateral jackknife of its packing; ``final:<eq. 7 parameter>``, ``window_lo``, ``window_hi``,
``eps``).
"""

from __future__ import annotations

from collections import defaultdict

from pathlib import Path

import numpy as np

from tapmc.laws import PROFILE_WINDOWS, ProfileLaw, profile_gradient

from . import _plotting as P
from . import _profile_runs, _runs, _steady_state
from ._profile_runs import BC, nearest_eps_runs, profiles, radius

NAME = "fig6"
#: upper end of the gradient window as a fraction of the packing height (22R of 28R).
WINDOW_TOP_FRACTION = 22.0 / 28.0


def runs(scale, seeds):
    """Constant-eps F.B.C. runs of ``scale.profile_eps`` (shared with Figs. 7 and 8:
    ``_profile_runs.runs``)."""
    return _profile_runs.runs(scale, seeds)


def gradient_window(campaign, specs, bc=BC):
    """The paper's gradient window, cut at WINDOW_TOP_FRACTION of the initial packing height."""
    return window_below([_runs.taps_table(campaign, s)["h_s"][0] / radius(s) for s in specs],
                        bc)


def window_below(heights, bc=BC):
    """The paper's gradient window for ``bc``, cut at WINDOW_TOP_FRACTION of the lowest of
    the initial packing heights ``heights`` (in R)."""
    lo, hi = PROFILE_WINDOWS[bc]
    return lo, min(hi, WINDOW_TOP_FRACTION * float(np.min(heights)))


def final_dump(folder, taps):
    """The packing a constant-eps run dumps after its last tap (``dump_ends``)."""
    return Path(folder) / f"dump.{int(taps)}.lammpstrj"


def _alpha_jackknife(dump, r, centres, window, bc):
    """Error of alpha within the packing after the last tap: the lateral jackknife of its
    profile (``tapmc.profiles.vertical_profile_jackknife``) from the run's dump of that step;
    None when the run has no such dump."""
    from tapmc.fluctuations import jackknife_error
    from tapmc.profiles import vertical_profile_jackknife
    from tapmc.readers import read_dump

    if not dump.is_file():
        return None
    frame = next(iter(read_dump(dump).frames))
    width = (centres[-1] - centres[0]) / (len(centres) - 1)   # the compute's uniform bins
    edges = np.append(centres - width / 2, centres[-1] + width / 2)
    _, replicates = vertical_profile_jackknife(frame.positions, r, edges, frame.box_lo,
                                               frame.box_hi)
    alphas = [profile_gradient(centres / r, rep, window=window, boundary=bc).params["alpha"]
              for rep in replicates]
    return float(jackknife_error(alphas))


def final_alpha(campaign, spec, window, bc):
    """(alpha, its error) of the last profile of a run in ``window`` (:func:`run_alpha`)."""
    return run_alpha(_runs.run_dir(campaign, spec), int(spec.variables["taps"]), radius(spec),
                     window, bc)


def run_alpha(folder, taps, r, window, bc):
    """(alpha, its error) of the last profile (``profile_z.dat``) of the run in ``folder``
    (``taps`` taps, sphere radius ``r``) in ``window``. The error is the lateral jackknife of
    the packing dumped after the last tap (``dump.<taps>.lammpstrj``: the profile's bins share
    spheres, so the straight line's own error is too small); the line's own error when there
    is no dump."""
    from tapmc.readers import read_ave_time

    folder = Path(folder)
    blocks = read_ave_time(folder / "profile_z.dat").blocks
    fit = profile_gradient(blocks[-1, :, 0] / r, blocks[-1, :, 2], window=window, boundary=bc)
    within = _alpha_jackknife(final_dump(folder, taps), r, blocks[-1, :, 0], window, bc)
    return float(fit.params["alpha"]), (float(fit.errors["alpha"]) if within is None
                                        else within)


def alpha_bell(campaign, bc=_steady_state.BC):
    """(sqrt_eps, mean, sem, n) of alpha after the taps of the constant-eps runs of the bell;
    None when the campaign has none. One seed: the fit's own error (module docstring)."""
    try:
        groups = _runs.constant_eps_groups(campaign, bc)
    except ValueError:
        return None
    rows = []
    for eps, specs in groups.items():
        window = gradient_window(campaign, specs, bc)
        fits = [final_alpha(campaign, spec, window, bc) for spec in specs]
        if len(fits) == 1:
            rows.append((np.sqrt(eps), fits[0][0], fits[0][1], 1))
        else:
            m, s, n = P.seed_stats([[a] for a, _ in fits])
            rows.append((np.sqrt(eps), m[0], s[0], n[0]))
    return tuple(np.array(col, dtype=float) for col in zip(*rows))


def profile_height(zb, phi, window):
    """Height (z/R) of a packing from its vertical profile: the first zb above the window's
    bottom where Phi falls below half of its median inside the window. For a deposited
    packing it matches the mean top of the columns, h_s of compute stereo/profile, to about
    a bin (29.25R against 28.98R for the full preset's initial packing)."""
    lo, hi = window
    inside = (zb >= lo) & (zb <= hi)
    if inside.sum() < 3:
        raise ValueError(f"window = ({lo:g}, {hi:g}) holds {inside.sum()} profile points; "
                         "at least 3 are needed")
    level = 0.5 * float(np.median(phi[inside]))
    below = np.flatnonzero((zb > lo) & (phi < level))
    if not len(below):
        raise ValueError("the profile does not fall below half of its median: the packing "
                         "reaches the top of the profile, so its height is unknown")
    return float(zb[below[0]])


def ramp_alpha(campaign, bc=_steady_state.BC, prefix="ramp_"):
    """dict branch ('up1', 'down', 'up2') -> (sqrt_eps, alpha, err, n): alpha of the profile
    every ramp run named ``prefix...`` prints at the end of each level (in.ramp's
    profile_z.dat; its branch column names the branch), averaged over seeds; the error is the
    sem over seeds, or with one seed the straight line's own error. Empty when the campaign
    has no such ramp."""
    collected = defaultdict(lambda: defaultdict(list))
    for spec in _runs.select(campaign, prefix, bc=bc):
        prof = _runs.profile(campaign, spec, "profile_z.dat")
        tab = _runs.taps_table(campaign, spec)
        r = radius(spec)
        lo, hi = PROFILE_WINDOWS[bc]
        z0 = prof.blocks[0, :, 0] / r
        height = profile_height(z0, prof.blocks[0, :, 2], (lo, hi))
        window = (lo, min(hi, WINDOW_TOP_FRACTION * height))
        steps = np.asarray(tab["step"], dtype=int)
        sqrt_eps = _runs.ramp_sqrt_eps(tab)
        for block, step in zip(prof.blocks, np.asarray(prof.steps, dtype=int)):
            row = np.flatnonzero(steps == step)
            if step == 0 or not len(row):
                continue
            fit = profile_gradient(block[:, 0] / r, block[:, 2], window=window, boundary=bc)
            branch = _runs.RAMP_BRANCHES[int(tab["branch"][row[0]])]
            key = round(float(sqrt_eps[row[0]]), 9)
            collected[branch][key].append((float(fit.params["alpha"]),
                                           float(fit.errors["alpha"])))
    out = {}
    for branch in _runs.RAMP_BRANCHES:
        by_sq = collected.get(branch)
        if not by_sq:
            continue
        sq = np.array(sorted(by_sq))
        rows = []
        for key in sq:
            m, s, n = P.seed_stats([[a] for a, _ in by_sq[key]])
            rows.append((m[0], s[0] if n[0] >= 2 else by_sq[key][0][1], n[0]))
        out[branch] = (sq,) + tuple(np.array(col, dtype=float) for col in zip(*rows))
    return out


def draw(campaign, out_dir):
    png, csv = P.figure_paths(out_dir, NAME)
    bell = alpha_bell(campaign)
    ramp = ramp_alpha(campaign)
    try:
        eps, specs = nearest_eps_runs(campaign)
    except ValueError:
        if bell is None and not ramp:
            raise
        return _draw_bell_only(bell, ramp, png, csv)
    window = gradient_window(campaign, specs)
    zb, im, isem, i_n, fm, fsem, f_n = profiles(campaign, specs, "profile_z.dat")
    table = P.FigureTable()
    fig, axes = P.new_figure(2 if bell is not None or ramp else 1, 1, height=4.0)
    ax = axes[0]
    ax.plot(zb, im, ":", color="k", label="initial packing")
    ax.plot(zb, fm, "-", color="C3", label=f"after {int(specs[0].variables['taps'])} taps")
    ax.fill_between(zb, fm - np.nan_to_num(fsem), fm + np.nan_to_num(fsem), color="C3",
                    alpha=0.25, lw=0)
    table.add("a", "initial", zb, im, isem, i_n)
    table.add("a", "final", zb, fm, fsem, f_n)
    law = ProfileLaw(window=window)
    for tag, mean, color in (("initial", im, "k"), ("final", fm, "C3")):
        try:
            fit = law.fit(zb, mean)
        except (ValueError, RuntimeError):
            continue
        keep = zb >= window[0]
        ax.plot(zb[keep], fit(zb[keep]), "-", lw=0.6, color=color, alpha=0.7)
        table.add("a", f"fit:{tag}", zb[keep], fit(zb[keep]), None, 0)
        for name, value in fit.params.items():
            table.add("params", f"{tag}:eq7_{name}", eps, value, fit.errors.get(name, np.nan),
                      int(bool(fit.determined)))
    for tag, index in (("initial", 0), ("final", -1)):
        alphas, withins = [], []
        for spec in specs:
            blocks = _runs.profile(campaign, spec, "profile_z.dat").blocks
            z = blocks[index, :, 0] / radius(spec)
            alphas.append([profile_gradient(z, blocks[index, :, 2], window=window)
                           .params["alpha"]])
            if tag == "final":                   # the error within each seed's packing
                dump = final_dump(_runs.run_dir(campaign, spec), spec.variables["taps"])
                withins.append(_alpha_jackknife(dump, radius(spec), blocks[-1, :, 0], window,
                                                BC))
        m, s, n = P.seed_stats(alphas)
        if tag == "final" and len(specs) == 1:   # one seed: the error within its packing
            s = [np.nan if withins[0] is None else withins[0]]
        table.add("params", f"{tag}:alpha", eps, m[0], s[0], n[0])
        if tag == "final" and len(specs) >= 2 and all(w is not None for w in withins):
            table.add("params", "final:alpha:seeds", [eps] * len(specs),
                      [a[0] for a in alphas], withins, 1)
    table.add("params", "window_lo", eps, window[0], None, len(specs))
    table.add("params", "window_hi", eps, window[1], None, len(specs))
    table.add("params", "eps", eps, eps, None, len(specs))
    for edge in window:
        ax.axvline(edge, color="0.6", lw=0.6, ls="--")
    ax.set_xlabel("z/R")
    ax.set_ylabel(r"$\Phi$")
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=8, title=f"F.B.C., eps = {P.fmt_eps(eps)}; dashed: gradient window",
              title_fontsize=7)
    if bell is not None or ramp:
        _bell_panel(axes[1], bell, ramp, table)
    return P.write_figure(fig, png, table, csv)


def _bell_panel(ax, bell, ramp, table):
    if bell is not None:
        sq, mean, sem, n = bell
        table.add("b", "bell:alpha", sq, mean, sem, n)
        ax.errorbar(sq, mean, yerr=np.nan_to_num(sem), marker="s", ls="-", color="k",
                    capsize=2, label="after the taps")
    for branch, (sq, mean, sem, n) in ramp.items():
        marker, label = _runs.RAMP_BRANCH_STYLE[branch]
        table.add("b", f"ramp:{branch}", sq, mean, sem, n)
        ax.errorbar(sq, mean, yerr=np.nan_to_num(sem), marker=marker, mfc="none", ls="-",
                    lw=0.8, capsize=2, label=f"ramp: {label}")
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel(r"$\varepsilon^{1/2}$")
    ax.set_ylabel(r"$\alpha$ (P.B.C.)")
    if ramp:
        ax.legend(fontsize=7, title="open: end of every level of the ramp", title_fontsize=7)


def _draw_bell_only(bell, ramp, png, csv):
    table = P.FigureTable()
    fig, (ax,) = P.new_figure(1, 1, height=4.0)
    _bell_panel(ax, bell, ramp, table)
    return P.write_figure(fig, png, table, csv)
