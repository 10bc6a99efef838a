#!/usr/bin/env python3
# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Measurements that settle open questions of the paper-scale validation (N = 4096, L = 32R,
P.B.C.); each writes one CSV that the paper-scale report renders (tapmc.paper.questions).

  first-tap   Is the drop of <Phi^c> at the first tap (P.B.C. runs: 58.3 % -> 57.1 % at
              eps = 0.15) a model effect or an unconverged redeposition? One tap from the
              same fresh packings at eta = 1e-7, 1e-8, 1e-9: <Phi^c> and <Z> at t = 0 and
              t = 1, and the sweeps the redeposition took.
  noise-floor What is sigma_<Z> without any tap (eps = 0): the redeposition's own noise, the
              floor under Fig. 3's sigma_<Z> = k sqrt(eps)? 1000 taps at eps = 0 from the
              packing after 4000 taps at eps = 0.0225 (the paper-scale campaign's
              restart.4000 of that run, committed as the input of this measurement),
              sigma_<Z> over them as Fig. 3 computes it, the drift of <Z>, and the slope of
              their power spectrum (Fig. 3's estimator): what a spectrum near the floor
              tends to at small eps.

  spectral-window
              Does the slope of Fig. 3's spectrum depend on the length of the steady window
              (the medium preset used 250 taps, the paper 1000)? The slope over the last 250,
              500, 1000 and 2000 taps of every finished P.B.C. constant-eps run of the
              paper-scale campaign (no simulation: its taps.dat files).

Usage (from the repository; minutes on one core, run under nice):

    bench/paper_questions.py first-tap   [--out DIR] [--lmp EXE] [--seeds 1 2 3]
    bench/paper_questions.py noise-floor [--out DIR] [--lmp EXE] [--restart FILE]
    bench/paper_questions.py spectral-window [--out DIR] [--campaign DIR]

DIR defaults to doc/paper_scale/validation/questions (what the committed page reads).
"""

from __future__ import annotations

import argparse
import csv
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

SOURCE = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(SOURCE / "tools" / "python"))
from tapmc.fluctuations import PowerSpectrum  # noqa: E402

INPUT = SOURCE / "examples" / "paper" / "in.constant_eps"
DEFAULT_OUT = SOURCE / "doc" / "paper_scale" / "validation" / "questions"
CAMPAIGN_RUN = SOURCE / "doc" / "validation" / "data" / "full" / "runs" / "const_pbc_eps0.0225_s1"
#: the paper's scale (section II)
PAPER = {"N": 4096, "L": 32}
FIRST_TAP_EPS = (0.0225, 0.15)
FIRST_TAP_ETA = (1e-7, 1e-8, 1e-9)
NOISE_TAPS = 1000
NOISE_FROM_STEP = 4000


def lmp_command(exe):
    exe = exe or os.environ.get("TAPMC_LMP") or SOURCE / "build" / "lmp_tapmc"
    if not Path(exe).is_file():
        sys.exit(f"paper_questions: LAMMPS executable {exe} not found (--lmp EXE or "
                 "$TAPMC_LMP; tools/run-tests.sh builds build/lmp_tapmc)")
    return ["nice", "-n", "10", str(exe)]


def run(lmp, folder, variables):
    args = [*lmp, "-in", str(INPUT), "-log", "log.lammps", "-screen", "none"]
    for key, value in variables.items():
        args += ["-var", key, str(value)]
    done = subprocess.run(args, cwd=folder, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"paper_questions: {' '.join(args)} failed in {folder}:\n{done.stderr[-2000:]}")
    return np.loadtxt(Path(folder) / "taps.dat", ndmin=2)


def write_csv(path, header, rows):
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as handle:
        out = csv.writer(handle)
        out.writerow(header)
        out.writerows(rows)
    print(f"wrote {path}")


def first_tap(args):
    lmp = lmp_command(args.lmp)
    rows = []
    for eps in FIRST_TAP_EPS:
        for eta in FIRST_TAP_ETA:
            for seed in args.seeds:
                with tempfile.TemporaryDirectory() as folder:
                    taps = run(lmp, folder, dict(PAPER, bc="pbc", eps=eps, eta=eta, seed=seed,
                                                 taps=1, rsteps=1000000))
                # columns of taps.dat: step phi_b phi_c Z z_top lateral central h_s sweeps ...
                t0, t1 = taps[0], taps[1]
                rows.append([eps, f"{eta:g}", seed, f"{t0[2]:.8f}", f"{t1[2]:.8f}",
                             f"{t0[3]:.8f}", f"{t1[3]:.8f}", int(t1[8])])
                print(f"eps {eps:g} eta {eta:g} seed {seed}: <Phi^c> {t0[2]:.4f} -> {t1[2]:.4f}"
                      f" ({int(t1[8])} sweeps)", flush=True)
    write_csv(Path(args.out) / "first_tap.csv",
              ["eps", "eta", "seed", "phi_c_0", "phi_c_1", "Z_0", "Z_1", "sweeps_1"], rows)


def noise_floor(args):
    lmp = lmp_command(args.lmp)
    restart = Path(args.restart).resolve()
    if not restart.is_file():
        sys.exit(f"paper_questions: restart file {restart} not found (--restart FILE: a packing "
                 "after 4000 taps of the paper-scale campaign)")
    with tempfile.TemporaryDirectory() as folder:
        taps = run(lmp, folder, dict(PAPER, bc="pbc", eps=0, eta=1e-7, seed=1, resume="yes",
                                     resume_file=restart,
                                     taps=NOISE_FROM_STEP + NOISE_TAPS, rsteps=1000000))
    z = taps[taps[:, 0] > NOISE_FROM_STEP, 3]
    t = np.arange(1, len(z) + 1, dtype=float)
    slope = float(np.polyfit(t, z, 1)[0])
    detrended = z - np.polyval(np.polyfit(t, z, 1), t)
    rows = [["sigma_Z", f"{np.std(z, ddof=1):.8g}"],
            ["sigma_Z_detrended", f"{np.std(detrended, ddof=1):.8g}"],
            ["drift_per_tap", f"{slope:.8g}"],
            ["Z_first", f"{z[0]:.8f}"], ["Z_last", f"{z[-1]:.8f}"],
            ["spectral_slope", f"{PowerSpectrum(z).compute().slope:.6g}"],
            ["spectral_slope_detrended", f"{PowerSpectrum(detrended).compute().slope:.6g}"],
            ["taps", len(z)], ["mean_sweeps", f"{np.mean(taps[taps[:, 0] > NOISE_FROM_STEP, 8]):.4g}"]]
    for name, value in rows:
        print(f"{name} = {value}")
    write_csv(Path(args.out) / "noise_floor.csv", ["quantity", "value"], rows)


SPECTRAL_WINDOWS = (250, 500, 1000, 2000)


def spectral_window(args):
    rows = []
    for run_dir in sorted(Path(args.campaign, "runs").glob("const_pbc_eps*_s*")):
        taps = run_dir / "taps.dat"
        if not (run_dir / "DONE.json").is_file():
            continue  # an unfinished run has no steady window yet
        table = np.loadtxt(taps, ndmin=2)
        z = table[table[:, 0] > 0, 3]
        eps = float(run_dir.name.split("_eps")[1].split("_s")[0])
        for window in SPECTRAL_WINDOWS:
            if window <= len(z):
                spectrum = PowerSpectrum(z[-window:]).compute()
                rows.append([run_dir.name, eps, len(z), window, f"{spectrum.slope:.6g}",
                             f"{spectrum.slope_error:.6g}"])
                print(f"{run_dir.name} ({len(z)} taps): last {window}: slope "
                      f"{spectrum.slope:.3f} +- {spectrum.slope_error:.3f}")
    write_csv(Path(args.out) / "spectral_window.csv",
              ["run", "eps", "taps", "window", "slope", "slope_error"], rows)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    for name in ("first-tap", "noise-floor", "spectral-window"):
        p = sub.add_parser(name)
        p.add_argument("--out", default=DEFAULT_OUT, type=Path)
        p.add_argument("--lmp", default=None)
    sub.choices["first-tap"].add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    sub.choices["noise-floor"].add_argument("--restart", default=CAMPAIGN_RUN / "restart.4000")
    sub.choices["spectral-window"].add_argument("--campaign", default=CAMPAIGN_RUN.parents[1])
    args = parser.parse_args(argv)
    {"first-tap": first_tap, "noise-floor": noise_floor,
     "spectral-window": spectral_window}[args.command](args)


if __name__ == "__main__":
    main()
