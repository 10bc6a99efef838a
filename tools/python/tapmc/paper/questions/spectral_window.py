# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""spectral-window: does the slope of Fig. 3's spectrum depend on the length of the steady
window (the medium preset used 250 taps, the paper 1000)? The slope over the last 250, 500,
1000 and 2000 taps of every finished P.B.C. constant-eps run of the paper-scale campaign (no
simulation: its taps.dat files; spectral_window.csv)."""

from __future__ import annotations

from collections import defaultdict

import numpy as np

from tapmc.fluctuations import PowerSpectrum

from ..claims import fmt
from .common import csv_schema, eps_of, finished_runs, taps_table

NAME = "spectral-window"
CSV = "spectral_window.csv"
HEADER = ["run", "eps", "taps", "window", "slope", "slope_error"]
SPECTRAL_WINDOWS = (250, 500, 1000, 2000)
#: the window "moves" the slope when the slopes' range exceeds this many times their largest
#: error (the page's reading; a difference of two slopes has about sqrt 2 of one's error)
MOVE_FACTOR = 2


def add_arguments(parser):
    """No options beyond --campaign and --out."""


def analyse(campaign):
    """The rows of spectral_window.csv: per finished P.B.C. constant-eps run and window, the
    spectral slope of <Z> over the run's last taps and its error."""
    rows = []
    for run_dir in finished_runs(campaign, "const_pbc_eps*_s*"):
        table = taps_table(run_dir / "taps.dat")
        z = table["Z"][table["step"] > 0]
        for window in SPECTRAL_WINDOWS:
            if window <= len(z):
                spectrum = PowerSpectrum(z[-window:]).compute()
                rows.append([run_dir.name, eps_of(run_dir.name), len(z), window,
                             f"{spectrum.slope:.6g}", f"{spectrum.slope_error:.6g}"])
                print(f"{run_dir.name} ({len(z)} taps): last {window}: slope "
                      f"{spectrum.slope:.3f} +- {spectrum.slope_error:.3f}")
    return rows


def measure(args):
    save(args.out / CSV, analyse(args.campaign))


save, load = csv_schema(HEADER)


def render(path):
    rows = load(path)
    runs = defaultdict(list)
    for r in rows:
        runs[(float(r["eps"]), r["run"], int(r["taps"]))].append(
            (int(r["window"]), float(r["slope"]), float(r["slope_error"])))
    lines = ["Fig. 3's spectral slope against the length of the steady window "
             "(``spectral_window.csv``; the last W taps of each P.B.C. run of the campaign):", ""]
    for (eps, run, taps), items in sorted(runs.items()):
        slopes = np.array([v for _, v, _ in items])
        errors = np.array([e for _, _, e in items])
        spread = float(np.ptp(slopes))
        moved = spread > MOVE_FACTOR * float(np.max(errors))
        text = ", ".join(f"W = {w}: {fmt(v, e)}" for w, v, e in items)
        lines.append(f"* eps = {eps:g} ({taps} taps): {text}; the window "
                     + ("moves the slope beyond twice its error." if moved else
                        "moves it by less than twice its error."))
    return lines + [""]

