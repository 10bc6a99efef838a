# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""alpha-window: is alpha's rise with eps (Fig. 6 bottom, claim gradient-bell) the model or
a reading, the gradient window reaching the loose top of the packing? Every finished P.B.C.
constant-eps run of the campaign re-analysed as Fig. 6 does (no simulation: its final
profile_z.dat and the lateral jackknife of dump.<taps>, tapmc.paper.fig6.run_alpha), alpha
in a window 5-18R that stays below the loose top at every eps beside alpha in Fig. 6's own
window, with the height where each final profile falls off (alpha_window.csv). The register
decides from it: gradient-bell's rows "window 5-18R (reading)"."""

from __future__ import annotations

from collections import defaultdict

import numpy as np

from tapmc.laws import profile_gradient
from tapmc.readers import read_ave_time

from .. import fig6
from .._rst import list_table
from ..claims import fmt
from ..claims.conventions import EQ7_SMOOTHING_WIDTH
from .common import (QuestionError, csv_schema, eps_of, finished_runs, run_radius,
                     taps_table)

NAME = "alpha-window"
CSV = "alpha_window.csv"
HEADER = ["run", "bc", "eps", "sqrt_eps", "seed", "window_lo", "window_hi", "alpha",
          "alpha_err", "default_window_hi", "alpha_default", "alpha_default_err",
          "loose_top", "upper_departure"]
#: the boundary condition of the bell's runs (Figs. 3-4 and Fig. 6's bottom panel)
BC = "pbc"
#: the narrower gradient window, in R: the paper's bottom (5R, above the floor's layers) and a
#: top 18R, well below the loose top of every final profile of the committed campaign (its
#: fall, :func:`loose_top`, starts at 27R at every eps, 0.0025 to 0.15; the packings are
#: 28-29R high), and 4-5R below Fig. 6's own top (22.8R, WINDOW_TOP_FRACTION of the initial
#: height): whatever the top few R do, this window does not see it. 13R holds 65 bins of R/5.
READING_WINDOW = (5.0, 18.0)
#: a block of the final profile is in the loose top when its mean falls this far below the
#: straight line of the reading window extrapolated: twice the largest departure of a block
#: inside the window in the committed campaign (0.010, the profile's layering and noise after
#: the smoothing), a twentieth of the profile's value; the fall at the top is 0.05-0.3
LOOSE_TOP_DROP = 0.02
#: the blocks' height, in R: the paper's smoothing of the profile (claims.conventions)
LOOSE_TOP_BLOCK = EQ7_SMOOTHING_WIDTH


def add_arguments(parser):
    """No options beyond --campaign and --out."""


def loose_top(zb, phi, window=READING_WINDOW, drop=LOOSE_TOP_DROP, block=LOOSE_TOP_BLOCK):
    """z/R where a profile leaves the bulk: the bottom of the first block of ``block`` R,
    counted from the window's bottom, whose mean falls more than ``drop`` below the
    straight line (tapmc.laws.profile_gradient) of the profile in ``window`` extrapolated;
    None when no block does (the profile does not reach the packing's top)."""
    zb, phi = np.asarray(zb, dtype=float), np.asarray(phi, dtype=float)
    fit = profile_gradient(zb, phi, window=window, boundary=BC)
    line = fit.params["Phi0"] - fit.params["alpha"] * zb
    for bottom in np.arange(window[0], zb.max(), block):
        inside = (zb >= bottom) & (zb < bottom + block)
        if inside.any() and np.mean(phi[inside] - line[inside]) < -drop:
            return float(bottom)
    return None


def upper_departure(zb, phi, default, window=READING_WINDOW):
    """Mean departure of a profile from the straight line of ``window`` over the bins Fig.
    6's ``default`` window has above it (window top < z/R <= default top): positive when the
    upper part of Fig. 6's window is denser than the narrow window's line (it flattens Fig.
    6's alpha), negative when looser (it steepens it). NaN when there are no such bins."""
    zb, phi = np.asarray(zb, dtype=float), np.asarray(phi, dtype=float)
    fit = profile_gradient(zb, phi, window=window, boundary=BC)
    upper = (zb > window[1]) & (zb <= default[1])
    if not upper.any():
        return float("nan")
    return float(np.mean(phi[upper] - (fit.params["Phi0"] - fit.params["alpha"] * zb[upper])))


def _profile_of(run_dir):
    """The run's profile_z.dat, QuestionError naming it when it is missing."""
    path = run_dir / "profile_z.dat"
    if not path.is_file():
        raise QuestionError(f"{path}: no such file (every finished constant-eps run writes "
                            "its vertical profile there; the run is incomplete)")
    return path


def _group_rows(eps, runs):
    """The rows of the runs of one eps (``runs``: [(seed, run folder)]), Fig. 6's window
    cut at the lowest initial height of the group as Fig. 6 does."""
    tables = {seed: taps_table(run_dir / "taps.dat") for seed, run_dir in runs}
    radii = {seed: run_radius(run_dir) for seed, run_dir in runs}
    default = fig6.window_below([t["h_s"][0] / radii[seed] for seed, t in tables.items()],
                                BC)
    rows = []
    for seed, run_dir in runs:
        profile = read_ave_time(_profile_of(run_dir)).blocks[-1]
        r, taps = radii[seed], int(tables[seed]["step"][-1])
        alpha, err = fig6.run_alpha(run_dir, taps, r, READING_WINDOW, BC)
        alpha_d, err_d = fig6.run_alpha(run_dir, taps, r, default, BC)
        top = loose_top(profile[:, 0] / r, profile[:, 2])
        departure = upper_departure(profile[:, 0] / r, profile[:, 2], default)
        rows.append([run_dir.name, BC, f"{eps:g}", f"{np.sqrt(eps):.8g}", seed,
                     f"{READING_WINDOW[0]:g}", f"{READING_WINDOW[1]:g}", f"{alpha:.8g}",
                     f"{err:.4g}", f"{default[1]:.6g}", f"{alpha_d:.8g}", f"{err_d:.4g}",
                     "" if top is None else f"{top:g}", f"{departure:.4g}"])
        print(f"{run_dir.name}: alpha {alpha:.5f} +- {err:.5f} in {READING_WINDOW[0]:g}-"
              f"{READING_WINDOW[1]:g}R, {alpha_d:.5f} +- {err_d:.5f} in {default[0]:g}-"
              f"{default[1]:.4g}R; loose top from {top}R; above {READING_WINDOW[1]:g}R "
              f"{departure:+.4f} off the line", flush=True)
    return rows


def analyse(campaign):
    """The rows of alpha_window.csv, one per finished P.B.C. constant-eps run, by eps and
    seed."""
    groups = defaultdict(list)
    for run_dir in finished_runs(campaign, f"const_{BC}_eps*_s*"):
        groups[eps_of(run_dir.name)].append((int(run_dir.name.rsplit("_s", 1)[1]), run_dir))
    return [row for eps in sorted(groups) for row in _group_rows(eps, sorted(groups[eps]))]


def measure(args):
    save(args.out / CSV, analyse(args.campaign))


save, load = csv_schema(HEADER)


def seeds_by_eps(rows, column="alpha"):
    """eps -> [(alpha, its error)] of the seeds, sorted by eps and seed: ``column`` 'alpha'
    (the reading window) or 'alpha_default' (Fig. 6's)."""
    by_eps = defaultdict(list)
    for r in sorted(rows, key=lambda r: (float(r["eps"]), int(r["seed"]))):
        by_eps[float(r["eps"])].append((float(r[column]), float(r[f"{column}_err"])))
    return dict(by_eps)


def _mean_departures(rows):
    """Per eps (sorted), the seeds' mean of upper_departure."""
    by_eps = defaultdict(list)
    for r in rows:
        by_eps[float(r["eps"])].append(float(r["upper_departure"]))
    return [float(np.mean(by_eps[eps])) for eps in sorted(by_eps)]


def render(path):
    """A table of alpha in both windows against sqrt(eps) (seeds averaged as Fig. 6 does,
    the errors without the realizations' calibration the register applies), and where the
    final profiles leave the bulk; no verdict (gradient-bell's reading rows give it)."""
    rows = load(path)
    if not rows:
        return []
    x, narrow, narrow_err, n = fig6.bell_series(seeds_by_eps(rows))
    _, wide, wide_err, _ = fig6.bell_series(seeds_by_eps(rows, "alpha_default"))
    lo, hi = (float(rows[0][k]) for k in ("window_lo", "window_hi"))
    top_default = max(float(r["default_window_hi"]) for r in rows)
    tops = [float(r["loose_top"]) for r in rows if r["loose_top"] != ""]
    lines = ["Is alpha's rise with eps (``gradient-bell``) a reading, Fig. 6's window reaching "
             "the loose top of the packing? alpha of every P.B.C. constant-eps run in a "
             f"window {lo:g}-{hi:g}R and in Fig. 6's ({lo:g} to at most {top_default:.3g}R), "
             "seeds averaged as Fig. 6 does (``alpha_window.csv``; errors before the "
             "realizations' calibration, which the register's rows "
             f"\"window {lo:g}-{hi:g}R (reading)\" of ``gradient-bell`` apply):", ""]
    departures = _mean_departures(rows)
    lines += list_table(
        ["sqrt(eps)", "seeds", f"alpha, {lo:g}-{hi:g}R", "alpha, Fig. 6's window",
         f"Phi above {hi:g}R minus the {lo:g}-{hi:g}R line"],
        [[f"{x[k]:.4g}", int(n[k]), fmt(narrow[k], narrow_err[k]), fmt(wide[k], wide_err[k]),
          f"{departures[k]:+.3f}"] for k in range(len(x))])
    where = (f"The final profiles leave the bulk (a block of {LOOSE_TOP_BLOCK:g}R more than "
             f"{LOOSE_TOP_DROP:g} below the {lo:g}-{hi:g}R line) from "
             + (f"{min(tops):g}R at the lowest, {max(tops):g}R at the highest"
                if tops else "nowhere in the profile")
             + f" ({len(tops)} of {len(rows)} runs); above {hi:g}R Fig. 6's window holds "
             "the last column's departure, positive where denser than the line.")
    return lines + ["", where, ""]
