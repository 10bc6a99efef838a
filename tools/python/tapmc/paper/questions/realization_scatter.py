# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""realization-scatter: does the error one run gives its steady state (batch means over its
last 1000 taps, the error of every one-seed point of the report) tell how far another
realization lands? Every group of finished runs that differ only in their seed (the
constant-eps points with several seeds, P.B.C. and F.B.C.; the ageing runs: ten streams from
one packing), no simulation: per run and per Phi_b, <Phi^c>, <Z>, the window mean and its
batch-means error, the value at t = 0 (whether the realizations share their packing), the
difference of the window's halves with its error (pbc-course's test of a run still
compacting), and Fig. 3's sigma_<Z> and spectral slope with their one-run errors (sem_dof
empty: the slope's error is known exactly), and Fig. 8's final zone means (lateral, central,
their difference: the last quarter of the taps) (realization_scatter.csv). The page compares
the realizations' spread with their errors (tapmc.fluctuations.ErrorCalibration), per
boundary condition, and tests whether the two share one factor."""

from __future__ import annotations

from collections import defaultdict

from tapmc.fluctuations import DEFAULT_BATCHES, DEFAULT_LAST, PowerSpectrum, SteadyState

from ..claims import (CALIBRATION_ALPHA, RUN_ERROR_LABELS, RUN_ERROR_QUANTITIES,
                      ZONE_QUANTITIES, realization_calibrations)
from .._steady_state import sigma_error_one_run
from .calibration import calibration_table, load, save, scatter_by_bc, scatter_quantity
from .common import require_steady_window, seed_groups, taps_table
from .pbc_course import steady_halves

NAME = "realization-scatter"
CSV = "realization_scatter.csv"
#: the scalars of taps.dat whose steady state the report quotes with one run's error
SCATTER_COLUMNS = ("phi_b", "phi_c", "Z")
#: the zone means of taps.dat (compute stereo/profile's lateral and central zones) whose final
#: window Fig. 8 quotes, and their difference per run
ZONE_COLUMNS = ("lateral", "central")
#: the window means of realization_scatter.csv, as the page names them
SCALAR_NAMES = {q: RUN_ERROR_LABELS[q] for q in RUN_ERROR_QUANTITIES}
#: the rows of the realization-scatter table: the window means and Fig. 8's zones
TABLE_NAMES = {**SCALAR_NAMES, **{q: RUN_ERROR_LABELS[q] for q in ZONE_QUANTITIES}}


def add_arguments(parser):
    """No options beyond --campaign and --out."""


def _window_rows(head, table, keep):
    """The rows of one run's window means and halves (SCATTER_COLUMNS)."""
    rows = []
    for column in SCATTER_COLUMNS:
        x = table[column][keep]
        steady = SteadyState(x).compute()
        rows.append(head + [column, f"{table[column][0]:.8g}", f"{steady.mean:.8g}",
                            f"{steady.sem:.4g}", steady.last,
                            min(DEFAULT_BATCHES, steady.last // 2) - 1])
        # pbc-course's test of a run still compacting, as it computes it
        drift, drift_se, dof = steady_halves(x, steady)
        rows.append(head + [f"{column}:halves", "", f"{drift:.6g}", f"{drift_se:.4g}",
                            steady.last, dof])
    return rows


def _fig3_rows(head, table, keep):
    """Fig. 3's sigma_<Z> (about X_SS and about the window's straight line) with its one-run
    error (batch means of the squared deviations), and the spectral slope with the
    periodogram's error, over the same window."""
    rows = []
    z = table["Z"][keep]
    for detrend, suffix in (("constant", ""), ("linear", "_detrended")):
        steady = SteadyState(z, detrend=detrend).compute()
        rows.append(head + [f"Z:sigma{suffix}", "", f"{steady.std:.6g}",
                            f"{sigma_error_one_run(z, steady.last, detrend=detrend):.4g}",
                            steady.last, min(DEFAULT_BATCHES, steady.last // 2) - 1])
    spectrum = PowerSpectrum(z, steady_from=len(z) - steady.last).compute()
    rows.append(head + ["Z:slope", "", f"{spectrum.slope:.6g}", f"{spectrum.slope_error:.4g}",
                        steady.last, ""])
    return rows


def _zone_rows(head, table, keep):
    """Fig. 8's final zone means and their difference, as fig8 takes them (the last quarter
    of the taps, batch means); none when the input writes no zones."""
    if not all(c in table for c in ZONE_COLUMNS):
        return []
    zones = {c: table[c][keep] for c in ZONE_COLUMNS}
    zones["central_minus_lateral"] = zones["central"] - zones["lateral"]
    last = max(int(keep.sum()) // 4, 1)
    rows = []
    for name, x in zones.items():
        steady = SteadyState(x, last=last).compute()
        rows.append(head + [f"zone:{name}", f"{table[name][0]:.8g}" if name in table else "",
                            f"{steady.mean:.8g}", f"{steady.sem:.4g}", steady.last,
                            min(DEFAULT_BATCHES, steady.last // 2) - 1])
    return rows


def analyse(campaign):
    """The rows of realization_scatter.csv (calibration.SCATTER_HEADER)."""
    rows = []
    for group, runs in seed_groups(campaign).items():
        tables = {seed: taps_table(run_dir / "taps.dat") for seed, run_dir in runs}
        taps = {len(t["step"]) for t in tables.values()}
        if len(taps) != 1:
            print(f"{group}: seeds of different lengths {sorted(taps)}: skipped")
            continue
        for seed, run_dir in runs:
            table = tables[seed]
            keep = table["step"] > 0
            require_steady_window(run_dir, int(keep.sum()), DEFAULT_LAST)
            head = [group, run_dir.name, seed, int(keep.sum())]
            mine = (_window_rows(head, table, keep) + _fig3_rows(head, table, keep)
                    + _zone_rows(head, table, keep))
            rows += mine
            print(f"{run_dir.name}: " + ", ".join(
                f"{r[4]} {float(r[6]):.5f} +- {float(r[7]):.5f}" for r in mine))
    return rows


def measure(args):
    save(args.out / CSV, analyse(args.campaign))


def render(path):
    """The table of each group's spread against its runs' own errors and the pooled factors
    (tapmc.paper.claims.realization_calibrations), with the verdict."""
    rows = load(path)
    calib = realization_calibrations(rows)
    if not rows or not calib:
        return []
    starts = defaultdict(set)
    for r in rows:
        if r["column"] == "phi_c":
            starts[r["group"]].add(r["start"])
    lines = ["Does the error one run gives its steady state tell how far another realization "
             "lands? Every one-seed point of this page (the paper's protocol: one run per "
             "point) carries its run's batch-means error (last 1000 taps, "
             f"{DEFAULT_BATCHES} batches). The campaign's groups of runs that differ only in "
             "their seed (``realization_scatter.csv``) measure it: the spread of their steady "
             "states against their own errors (tapmc.fluctuations.ErrorCalibration; 1 when the "
             "errors are calibrated):", ""]
    lines += calibration_table(
        calib, TABLE_NAMES, {k: scatter_quantity(k) for k in RUN_ERROR_LABELS},
        ("runs", "rms error within a run"),
        lambda group, n: f"{n} (" + ("one packing" if len(starts[group]) == 1 else
                                     f"{len(starts[group])} packings") + ")")
    lines += scatter_by_bc(rows)
    short = {k: c for k, c in calib.items() if c.p_value < CALIBRATION_ALPHA}
    if not short:
        lines += ["* Verdict: the one-run errors are compatible with the realizations' spread "
                  f"(no p below {CALIBRATION_ALPHA:g}): a one-seed error bar is the error of "
                  "the model's steady state.", ""]
        return lines
    means = [k for k in SCALAR_NAMES if k in short]
    text = ", ".join(f"{SCALAR_NAMES[k]} {short[k].factor:.1f}" for k in means)
    lines += [
        "* Verdict: the one-run errors are too small" + (f" (window means: {text})" if text
                                                         else "")
        + ": fluctuations slower than a batch (Fig. 3's spectra fall as f^-1 to f^-1.5) move "
        "a run's whole window, so a one-seed error bar is the error of that run's time "
        "average, not of the model's steady state, and another realization lands about k of "
        "them away. Where a row of the claims' table or a measurement below rests on one "
        "run's time average, its error is the batch-means error times the factor of its "
        "quantity (the note under the claims' rules lists them; a difference of two windows "
        "of one run takes the halves' factor)."
        + (" The realizations' spread does not reject the errors of "
           + ", ".join(f"{RUN_ERROR_LABELS[k]} (k = {calib[k].factor:.2f})"
                       for k in RUN_ERROR_LABELS if k in calib and k not in short)
           + ": those stand as they are." if set(calib) - set(short) else ""), ""]
    return lines

