# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""ramp-alpha: does alpha, the vertical gradient of Fig. 6, show hysteresis on the ramps at
the paper's own protocol (section III.B: 4000 taps per level; section IV.A: "alpha presents no
hysteresis effect")? No simulation: alpha of the vertical profile every ``paperramp*`` run of
the campaign prints at the end of each level (in.ramp's profile_z.dat, joined with the
segments of its resumed attempts while it runs), read as Fig. 6 reads the campaign's own
ramps (:func:`tapmc.paper.fig6.level_alphas`), one row per whole level (ramp_alpha.csv). The
register decides from it: gradient-no-hysteresis's rows "4000 taps per level, eta = ..." for
the ramps that turn beyond (sqrt eps)*; the page shows every ramp's branches against each
other."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from tapmc.campaign import joined_ave_time
from tapmc.hysteresis import CRITICAL_SQRT_EPS

from .. import _plotting, _runs, fig6, paper_ramp
from .._rst import list_table
from ..claims import fmt
from ..claims.bell import ramp_alpha_levels
from ..scales import FULL
from .alpha_window import READING_WINDOW
from .common import QuestionError, csv_schema, runs_folder, taps_table
from .ramp_replay import manifest_run

NAME = "ramp-alpha"
CSV = "ramp_alpha.csv"
PNG = "ramp_alpha.png"
#: height bands (R above the floor) where the mean Phi of every level-end profile is kept, to
#: tell where in the bed a branch gains: the floor's layers (0-4R, the height of Phi_b), the
#: next 4R, where the floor's layering decays (the raw profile oscillates up to about 11R,
#: eq7-fit on the page), and the bulk up to Fig. 6's window top (about 23R)
PHI_BANDS = ((0.0, 4.0), (4.0, 8.0), (8.0, 16.0), (16.0, 23.0))
BAND_COLUMNS = [f"phi_{lo:g}_{hi:g}R" for lo, hi in PHI_BANDS]
HEADER = ["run", "top", "eta", "seed", "step", "branch", "sqrt_eps", "alpha", "alpha_err",
          "window_lo", "window_hi", "alpha_reading", "reading_lo", "reading_hi", *BAND_COLUMNS]
#: the boundary condition of the paper's ramps (section III.B: P.B.C.)
BC = "pbc"
#: the profile file in.ramp writes at t = 0 and at the end of every level
PROFILE = "profile_z.dat"
#: the sphere radius of a run that sets none (the inputs' default)
DEFAULT_RADIUS = 0.5


def add_arguments(parser):
    """No options beyond --campaign and --out."""


def _radius(campaign, name):
    """R of run ``name``: its variable in the campaign's manifest.json (ramp_replay's
    manifest_run: a run still running has no DONE.json), DEFAULT_RADIUS when it sets none or
    the folder has no manifest (runs alone)."""
    if not (Path(campaign) / "manifest.json").is_file():
        return DEFAULT_RADIUS
    variables, _ = manifest_run(campaign, name)
    return float(variables.get("R", DEFAULT_RADIUS))


def _profiles(run_dir):
    """(blocks, steps) of a ramp's profiles so far, its resumed attempts' segments joined;
    QuestionError when it has none or they do not start at t = 0 (a damaged one: the
    readers' TapmcFormatError, which the command prints on one line)."""
    _, blocks = joined_ave_time(run_dir, PROFILE)
    if not blocks:
        raise QuestionError(f"{run_dir / PROFILE}: no profile yet (in.ramp writes the initial "
                            "packing's when it starts)")
    if blocks[0][0] != 0:
        raise QuestionError(f"{run_dir / PROFILE}: its first profile is at step {blocks[0][0]},"
                            " not the initial packing's (0): the gradient window is cut at "
                            "its height")
    arrays = [np.loadtxt(lines[1:], ndmin=2)[:, 1:] for _, lines in blocks]
    return arrays, [step for step, _ in blocks]


def analyse_run(campaign, run_dir, default_eta):
    """The rows of one paper ramp: one per level whose end it has printed."""
    m = paper_ramp.NAME.match(run_dir.name)
    if not m:
        raise QuestionError(f"{run_dir}: not a paper ramp's name "
                            "(paperramp<top>_<bc>[_eta<eta>]_s<seed>)")
    eta = float(m.group("eta")) if m.group("eta") else float(default_eta)
    blocks, steps = _profiles(run_dir)
    table = taps_table(run_dir / "taps.dat")
    r = _radius(campaign, run_dir.name)
    levels = fig6.level_alphas(blocks, steps, table, r, m.group("bc"))
    reading = fig6.level_alphas(blocks, steps, table, r, m.group("bc"), READING_WINDOW)
    by_step = dict(zip(steps, blocks))
    return [[run_dir.name, m.group("top"), f"{eta:g}", int(m.group("seed")), lv.step,
             lv.branch, f"{lv.sqrt_eps:.8g}", f"{lv.alpha:.8g}", f"{lv.err:.4g}",
             f"{lv.window[0]:g}", f"{lv.window[1]:.6g}", f"{low.alpha:.8g}",
             f"{READING_WINDOW[0]:g}", f"{READING_WINDOW[1]:g}",
             *(f"{phi:.8g}" for phi in band_means(by_step[lv.step], r))]
            for lv, low in zip(levels, reading)]


def band_means(block, r):
    """The mean Phi of a profile block (columns z, ..., Phi; bins of equal width) in each of
    PHI_BANDS (z/R from the floor at 0): the slab average of the band."""
    z = block[:, 0] / r
    return [float(np.mean(block[(z >= lo) & (z < hi), 2])) for lo, hi in PHI_BANDS]


def analyse(campaign, default_eta=FULL.eta):
    """The rows of ramp_alpha.csv: every ``paperramp*`` run with a taps.dat, by name, its
    levels in order; QuestionError when the campaign has none."""
    runs = [d for d in sorted(runs_folder(campaign).glob("paperramp*"))
            if (d / "taps.dat").is_file()]
    if not runs:
        raise QuestionError(f"--campaign {campaign}: no paper ramp (runs/paperramp* with a "
                            "taps.dat)")
    rows = []
    for run_dir in runs:
        run_rows = analyse_run(campaign, run_dir, default_eta)
        rows += run_rows
        print(f"{run_dir.name}: alpha at the end of {len(run_rows)} levels", flush=True)
    return rows


def measure(args):
    scale = _runs.folder_scale(args.campaign)
    path = save(args.out / CSV, analyse(args.campaign, scale.eta))
    print(f"wrote {write_figure(load(path), args.out / PNG, scale)}")


save, load = csv_schema(HEADER)


def _difference_cell(levels, a, b):
    """'mean +- scatter error (k)' of branch a minus b over its k common levels (one level:
    its difference; none: '')."""
    d = levels.difference(a, b)
    if len(d) < 2:
        return "" if not len(d) else f"{d[0]:+.5f} (1 level)"
    return f"{fmt(float(np.mean(d)), float(np.std(d, ddof=1) / np.sqrt(len(d))))} ({len(d)})"


def render(path):
    """A table of every paper ramp: alpha's range along its first increase, and its
    decreasing branch minus its first increase and its second increase minus its decrease
    (mean over the common levels, error from their scatter); no verdict (the register's
    gradient-no-hysteresis rows give it for the ramps beyond (sqrt eps)*)."""
    rows = load(path)
    if not rows:
        return []
    table = []
    reading = ramp_alpha_levels(rows, "alpha_reading")
    ordered = sorted(ramp_alpha_levels(rows).items(),
                     key=lambda kv: (kv[1].top, -kv[1].eta, kv[1].seed))
    for run, lv in ordered:
        up = lv.branches.get("up1", (np.array([]), np.array([])))[1]
        table.append([f"{lv.top:g}", paper_ramp.eta_text(lv.eta), lv.seed,
                      sum(len(v[0]) for v in lv.branches.values()),
                      f"{up.min():.5f} to {up.max():.5f}" if len(up) else "",
                      _difference_cell(lv, "down", "up1"), _difference_cell(lv, "up2", "down"),
                      _difference_cell(reading[run], "down", "up1")])
    lo, hi = float(rows[0]["window_lo"]), max(float(r["window_hi"]) for r in rows)
    low = f"{float(rows[0]['reading_lo']):g}-{float(rows[0]['reading_hi']):g}R"
    lines = ["Does alpha show hysteresis at the paper's protocol (``gradient-no-hysteresis``)? "
             "alpha of the vertical profile every ramp at 4000 taps per level prints at the end "
             f"of each level, in the window {lo:g}R to at most {hi:.3g}R as Fig. 6 reads the "
             "campaign's ramps (``ramp_alpha.csv``). Differences: mean over the sqrt(eps) "
             "common to the two branches, the error from their scatter (one profile per "
             f"level); ramps turning beyond (sqrt eps)* = {CRITICAL_SQRT_EPS:g} decide the "
             "register's rows. The last column reads alpha in the window "
             f"{low} of ``alpha-window``, below the packing's loose top: a difference "
             "there is not the window's reading of the top.", ""]
    lines += list_table(["turning at", "eta", "seed", "levels", "alpha, first increase",
                         "decrease minus first increase (levels)",
                         "second increase minus decrease (levels)",
                         f"decrease minus first increase, {low}"], table)
    lines += ["", "Where in the bed a branch gains: the mean Phi of each level-end profile in bands "
              "of height above the floor, the decrease minus the first increase (mean over "
              "their common sqrt(eps), the error from their scatter; ``phi_<lo>_<hi>R`` of the "
              "CSV):", ""]
    bands = {c: ramp_alpha_levels(rows, c) for c in BAND_COLUMNS}
    lines += list_table(["turning at", "eta", "seed",
                         *(f"{lo:g}-{hi:g}R" for lo, hi in PHI_BANDS)],
                        [[f"{lv.top:g}", paper_ramp.eta_text(lv.eta), lv.seed,
                          *(_difference_cell(bands[c][run], "down", "up1")
                            for c in BAND_COLUMNS)] for run, lv in ordered])
    if (path.parent / PNG).is_file():
        lines += ["", f".. image:: {_runs.FIG_DIR}/{path.parent.name}/{PNG}",
                  "   :alt: alpha at the end of every level of the ramps at the paper's "
                  "protocol", ""]
    return lines + [""]


def plot(rows, axes=None, default_eta=FULL.eta):
    """alpha at the end of every level against sqrt(eps), one panel per eta (the campaign's
    ``default_eta`` first; ``axes``: one per eta, new ones when None), a colour per ramp, a
    marker per branch (paper_ramp.BRANCH_STYLE), a thin line through the levels in the ramp's
    order, (sqrt eps)* dotted. Returns the axes."""
    levels = ramp_alpha_levels(rows)
    etas = sorted({lv.eta for lv in levels.values()}, key=lambda e: (e != default_eta, -e))
    if axes is None:
        _, axes = _plotting.new_figure(nrows=len(etas), height=2.6, width=6.0)
    order = {}
    for r in rows:
        order.setdefault(r["run"], []).append((float(r["sqrt_eps"]), float(r["alpha"])))
    for ax, eta in zip(axes, etas):
        runs = sorted((run for run, lv in levels.items() if lv.eta == eta),
                      key=lambda run: (levels[run].top, levels[run].seed))
        for colour, run in enumerate(runs):
            lv = levels[run]
            ax.plot(*zip(*order[run]), color=f"C{colour}", lw=0.8)
            for branch, (marker, words) in paper_ramp.BRANCH_STYLE.items():
                if branch in lv.branches:
                    ax.plot(*lv.branches[branch], marker=marker, mfc="none", ms=5, ls="none",
                            color=f"C{colour}", label=f"seed {lv.seed}, to {lv.top:g}: {words}")
        ax.axvline(CRITICAL_SQRT_EPS, color="0.5", ls=":", lw=1,
                   label=f"$(\\varepsilon^{{1/2}})^* = {CRITICAL_SQRT_EPS:g}$")
        ax.set_title(paper_ramp.eta_label(eta, default_eta), fontsize=8)
        ax.set_xlabel(r"$\varepsilon^{1/2}$")
        ax.set_ylabel(r"$\alpha$ (end of each level)", fontsize=8)
        _plotting.legend(ax, fontsize=6, outside=True)
    return axes


def write_figure(rows, path, scale=FULL):
    """ramp_alpha.png: :func:`plot`, its settings on top (``scale``: the campaign's,
    :func:`~tapmc.paper._runs.folder_scale`); returns the path."""
    fig = plot(rows, default_eta=scale.eta)[0].figure
    hi = max(float(r["window_hi"]) for r in rows)
    seeds = ", ".join(map(str, sorted({int(r["seed"]) for r in rows})))
    # the stop rule of the scale's paper ramps (any top on its grid has the same)
    top = scale.ramp_sqrt0 + scale.ramp_dsqrt
    stop = _plotting.planned_stop(_runs.paper_ramp_run(scale, "pbc", 1, top))
    _plotting.finish_figure(fig, f"N = {scale.N}, box {scale.L:g}R x {scale.L:g}R, P.B.C.; "
                            f"eta: each panel's, {stop}; "
                            f"{paper_ramp.TAPS_PER_LEVEL} taps per level, steps of "
                            f"{scale.ramp_dsqrt:g} in sqrt(eps); alpha of the vertical profile "
                            f"at the end of each level (one profile), fitted in "
                            f"{float(rows[0]['window_lo']):g}R to at most {hi:.3g}R; levels "
                            f"done whole only; seeds {seeds}; "
                            + _plotting.scale_text(scale))
    return _plotting.save_figure(fig, path)
