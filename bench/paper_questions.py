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

  initial-packing
              Is the initial P.B.C. packing's <Phi^c> the paper's 58.4 % (section IV.B)? The
              campaign starts every run from one packing (the paper's protocol); this
              deposits the same packing (create_packing, N = 4096, L = 32R, P.B.C.) with
              seeds 1..20 and measures it as the runs do at t = 0 (no tap): Phi_b, <Phi^c>
              and <Z> per seed, the spread between depositions that one packing hides.

  p0-configs  Are Fig. 9's comparisons (P0 of the tapped packing against the initial packing's
              and against Percus-Yevick) decided once the curves carry error bars? The
              campaign has one packing of each (the paper's protocol). This measures P0 as
              Fig. 9 does (tapmc-pores --p0, same window and point count) on 8 depositions
              at t = 0 and on 8 configurations of the tapped packing: the campaign's run at
              eps = 0.0225 continued from its restart.4000 at the same eps, one dump every
              100 taps (taps 4100 to 4800). Mean, sem and n of P0(sigma) for both, and the
              volume fraction the points see.

  lateral-first-tap
              Does the first tap compact the lateral zone of the paper's F.B.C. start (section
              IV.A, Fig. 8: delta Phi_lateral jumps at t = 1)? The campaign's F.B.C. runs start
              from packings deposited between the walls; this builds the paper's start
              (periodic deposition, walls, slight agitation: in.constant_eps fbc_start =
              paper) at N = 4096, L = 32R for seeds 1-4 and taps it 5 times at each eps of
              Fig. 8 (0.005, 0.02, 0.05, 0.1): the lateral and central zone means at t = 0..5.

  ramp-levels What do the ramp's taps per level (the campaign's 1000, the paper's 4000)
              change? A finished ramp keeps its restart files at the level ends; this
              continues chosen levels from them at the level's sqrt(eps) (in.constant_eps,
              the run's seed and eta) by --extend taps (default 3000: 4000 in all) and
              compares <Phi^c> over the level's last quarter with that over the last quarter
              of the longer level (batch-means errors). Default levels: two of every branch
              (a quarter of the way up the first increase and its top, the middle and the
              bottom of the decrease, the middle and the top of the second increase). Each
              continuation runs in its own folder under --work DIR (default DIR/partial/
              ramp_levels, DIR the --out folder) with restart files every 50 taps: a killed
              ramp-levels resumes there, and a larger --extend continues it. The rows of
              ramp_levels.csv for levels not listed are kept (a level measured in an
              earlier session whose restart file is gone stays in the table). --replay: a
              level whose restart file is gone starts from a replay of the ramp up to its end
              (in.ramp -var stop, in DIR/partial/ramp_levels/<run>_replay, a restart file at
              every level end); its rows are compared with the campaign's (column start:
              run, replay (identical) or replay (differs from step S)). Column ramp: the
              run (--run); --run ramplow_pbc_s1 measures the ramp below (sqrt eps)*, whose
              turning level and decrease bound its "nearly frozen" claim.

  ramp-pores  Does nu, the mean normalised pore volume, have the reversible-irreversible
              behaviour of <Phi^c> (section IV.B)? The packing at the end of every level of
              the ramp whose restart file is kept (the run's folder, and the level ends of a
              replay in DIR/partial/ramp_levels/<run>_replay; --replay runs the ramp again up
              to the ends of --levels that have neither) is dumped into
              DIR/partial/ramp_levels/<run>_pores, and every level dumped there is analysed
              as Fig. 10 analyses its run's dumps (tapmc-pores, one statistics box for all):
              nu per level with the spatial jackknife over 4 x 4 lateral blocks
              (ramp_pores.csv, one row per run and level: --run ramplow_pbc_s1 adds the ramp
              below (sqrt eps)*; a level whose packing is gone keeps its row).

  fit-surrogates
              Does one 4000-tap run fix the triplet (X_inf, B, tau) of eq. 3 (and eq. 4's
              parameters), and do they depend on the range of taps fitted (section III.B)?
              Per finished F.B.C. constant-eps run of the campaign (every seed; the claims
              read the first of each eps): tapmc.laws.SurrogateFits
              (Fourier surrogates of the run's residuals, --surrogates, default 200; no
              simulation). And, from early_taps.csv, the spread of the same fits over the
              independent realizations of the first 400 taps.

  seed-fits   Do independent realizations fix the triplet (X_inf, B, tau) of eq. 3 (and
              eq. 4's parameters) over a whole run, and do they depend on the range of taps
              fitted (section III.B)? Every group of finished constant-eps and ageing runs
              that differ only in their seed (realization-scatter's groups): each run fitted
              from tap 1 over all its taps and over taps 1-T/4, 1-T/2 and T/10-T, the spread
              of each parameter over the runs with its 95 % chi-square interval, and the
              paired t-test of each range against all taps (tapmc.laws.RealizationFits; no
              simulation, seconds).

  pbc-course  How long does the dip of <Phi^c> after the first taps last, and does the
              packing loosen at strong taps (eps >= 0.09)? From every finished P.B.C.
              constant-eps run of the paper-scale campaign (no simulation: its taps.dat):
              <Phi^c> at t = 0, the lowest of the first taps and when, the first tap from which
              a 10-tap running mean stays at or above the t = 0 value for 10 taps, and the
              steady state (last 1000 taps, batch-means error) and the difference of its
              two halves (is the packing still compacting at the end?).

  realization-scatter
              Does the error one run gives its steady state (batch means over its last 1000
              taps, the error of every one-seed point of the report) tell how far another
              realization lands? Every group of finished runs that differ only in their
              seed (the constant-eps points with several seeds, P.B.C. and F.B.C.; the
              ageing runs: ten streams from one packing), no simulation: per run and per
              Phi_b, <Phi^c>, <Z>,
              the window mean and its batch-means error, the value at t = 0 (whether
              the realizations share their packing), the difference of the window's
              halves with its error (pbc-course's test of a run still compacting), and
              Fig. 3's sigma_<Z> and spectral slope with their one-run errors (sem_dof
              empty: the slope's error is known exactly), and Fig. 8's final zone means
              (lateral, central, their difference: the last quarter of the taps). The
              report compares the realizations' spread with their errors
              (tapmc.fluctuations.ErrorCalibration), per boundary condition, and tests
              whether the two share one factor.

  packing-scatter
              Does the spatial jackknife of one packing (4 x 4 lateral blocks), the error
              of nu (pores, Fig. 10) and of alpha (the profile's gradient, Fig. 6) wherever
              one run gives a point, tell how far another realization lands? The final
              packings (dump.<taps>) of every group of finished constant-eps runs that
              differ only in their seed, and the distinct initial packings (dump.0) of each
              boundary condition, no simulation (tapmc-pores in Fig. 10's statistics box,
              a few seconds per packing; alpha in Fig. 6's window): per packing nu and
              alpha with their jackknife errors, in realization_scatter.csv's columns.

  integrity   Do thousands of taps leave a legal hard-sphere packing, and do the numbers a
              run prints describe the packing it dumps? Every dump of the paper-scale
              campaign (no simulation: the t = 0 and final packings of every run, Fig. 10's
              nine) checked offline (tapmc.packing.PackingCheck): spheres, the closest pair
              (overlaps beyond the model's tolerance and the dump's rounding), the floor and
              the side walls; and Phi_b, <Phi^c>, <Z>, z_top, h_s recomputed from the
              positions against the run's taps.dat row of that tap.

  early-taps  Does Phi_b compact faster per tap in the first decade than later (section III.A:
              "as the packing progressively densifies, the compaction efficiency
              decreases"), is the slowing on a logarithmic time axis strongest at the
              smallest eps, and are Phi_b(t) and <Z>(t) compatible with eqs. 3 and 4? One
              run gives neither the first decade's rate nor a fit a trustworthy error: its
              taps' scatter is correlated (Fig. 3). This taps the campaign's F.B.C. packing
              (its pack_seed) 400 times at each eps of Fig. 2 with Monte Carlo seeds 2-9,
              resumable from restart files in <out>/partial/early_taps/, and adds the
              campaign's own run (seed 1) from its taps.dat: Phi_b, <Phi^c> and <Z> at
              t = 0..400 per seed, whose rates and laws are tested across realizations.

  p0-fluid    Is a tapped packing expected to follow the Percus-Yevick P0(sigma) of Fig. 9
              as closely as it does (max |P0 - PY| = 0.025 at Phi = 0.606)? PY is a theory of
              the equilibrium hard-sphere fluid: P0 measured with the same tool and settings
              (tapmc-pores --p0, Fig. 9's random point count) on equilibrium fluids at several
              Phi (NVT Metropolis MC, bench/bench_hs_fluid.cpp: 4000 spheres in a periodic
              cube, several configurations per Phi), with the contact value g(1+) against
              Carnahan-Starling as the check of equilibrium: the baseline of the packing's
              deviation, and a validation of the measurement where PY is accurate.

  theta0      Does theta0 = pi/4 give the largest compaction rate, and does a much smaller
              theta0 decompact (section II)? From the same fresh packings (N = 1024, the
              paper's bed height on a 16R base, P.B.C., eps = 0.0225, the default eta) 100
              taps at seven widths theta0 of the trial moves' angular distribution (eq. 1),
              pi/16 to pi/2: <Phi^c> at t = 0 and its mean over taps 91-100 per seed.
              --N sets the spheres (box 32R sqrt(N/4096), the paper's bed height; the CSV
              then ends in _N<N>); a scan started again skips the runs its CSV has.
              --stop drift (with --eta, default 1e-7: the front's reference) repeats it
              with a converged redeposition, into theta0_drift.csv: a wider theta0 takes more
              sweeps before the paper's stopping rule ends a tap, so the default scan mixes
              the width's effect with the redeposition's length.
              --theta-law solid reads P(theta) of eq. 1 per unit solid angle (fix mc/settle
              theta_law solid; CSV tag _solid); --wide scans instead the widths beyond the
              paper's truncation pi/2 (3/4 pi, pi, 30 pi: the flat limit; CSV tag _wide).

  dmax        Is d_max = R/5 an intermediate value, much smaller or larger steps slowing the
              redeposition (section II)? The same scan as theta0 over seven d_max, R/50 to
              R (dmax.csv; --stop drift: dmax_drift.csv).

Usage (from the repository; minutes on one core, run under nice):

    bench/paper_questions.py first-tap   [--out DIR] [--lmp EXE] [--seeds 1 2 3]
    bench/paper_questions.py noise-floor [--out DIR] [--lmp EXE] [--restart FILE]
    bench/paper_questions.py spectral-window [--out DIR] [--campaign DIR]
    bench/paper_questions.py pbc-course [--out DIR] [--campaign DIR]
    bench/paper_questions.py integrity [--out DIR] [--campaign DIR]
    bench/paper_questions.py early-taps [--out DIR] [--lmp EXE] [--campaign DIR] [--seeds 2 ...]
                                        [--taps 400] [--work DIR] [--eps E ...]
    bench/paper_questions.py initial-packing [--out DIR] [--lmp EXE] [--seeds 1 2 ...]
    bench/paper_questions.py p0-configs [--out DIR] [--lmp EXE] [--restart FILE] [--work DIR]
    bench/paper_questions.py lateral-first-tap [--out DIR] [--lmp EXE] [--seeds 1 2 3 4]
    bench/paper_questions.py ramp-levels [--out DIR] [--lmp EXE] [--campaign DIR]
                                         [--run ramp_pbc_s1] [--levels K ...] [--extend 3000]
                                         [--work DIR] [--replay]
    bench/paper_questions.py ramp-pores  [--out DIR] [--lmp EXE] [--campaign DIR]
                                         [--run ramp_pbc_s1] [--levels K ...] [--work DIR]
                                         [--replay]
    bench/paper_questions.py theta0 [--out DIR] [--lmp EXE] [--seeds 1 2 3 4]
                                    [--stop change|drift] [--eta 1e-7] [--N 1024]
                                    [--theta-law angle|solid] [--wide]
    bench/paper_questions.py dmax   (the same options as theta0)
    bench/paper_questions.py p0-fluid [--out DIR] [--phi 0.3 0.4 ...] [--configs C]
                                      [--work DIR] [--mc EXE]

p0-fluid keeps its configurations and tapmc-pores outputs in --work DIR when given (a re-run
reuses them); the MC program is --mc EXE, else build/bench/bench_hs_fluid, else
bench/bench_hs_fluid.cpp compiled with $CXX (default c++) into the work folder.

DIR defaults to doc/paper_scale/validation/questions (what the committed page reads).
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

SOURCE = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(SOURCE / "tools" / "python"))
from tapmc.campaign.run_folder import keep_latest_restart, latest_restart  # noqa: E402
from tapmc.paper.claims import RAMP_LEVELS_DEFAULT_RUN  # noqa: E402
from tapmc.readers import read_fix_print  # noqa: E402
from tapmc.fluctuations import DEFAULT_BATCHES, PowerSpectrum, SteadyState  # noqa: E402

INPUT = SOURCE / "examples" / "paper" / "in.constant_eps"
DEFAULT_OUT = SOURCE / "doc" / "paper_scale" / "validation" / "questions"
CAMPAIGN_RUN = SOURCE / "doc" / "validation" / "data" / "full" / "runs" / "const_pbc_eps0.0225_s1"
#: the paper's scale (section II)
PAPER = {"N": 4096, "L": 32}
FIRST_TAP_EPS = (0.0225, 0.15)
FIRST_TAP_ETA = (1e-7, 1e-8, 1e-9)
#: theta0 scan: widths (multiples of pi), its scale and taps; the window of taps averaged
THETA0_PI = (1 / 16, 1 / 8, 1 / 6, 1 / 4, 1 / 3, 5 / 12, 1 / 2)
#: theta0 --wide: widths beyond the truncation pi/2 (30 pi: within 3e-4 of the flat limit)
THETA0_WIDE_PI = (3 / 4, 1, 30)
THETA0_SCALE = {"N": 1024, "L": 16}
THETA0_EPS = 0.0225
THETA0_TAPS = 100
THETA0_WINDOW = 10
#: the sphere radius of in.constant_eps (distance units), and the dmax scan's values (over R)
THETA0_RADIUS = 0.5
DMAX_OVER_R = (1 / 50, 1 / 20, 1 / 10, 1 / 5, 1 / 3, 1 / 2, 1)
NOISE_TAPS = 1000
NOISE_FROM_STEP = 4000


def lmp_command(exe):
    exe = exe or os.environ.get("TAPMC_LMP") or SOURCE / "build" / "lmp_tapmc"
    if not Path(exe).is_file():
        sys.exit(f"paper_questions: LAMMPS executable {exe} not found (--lmp EXE or "
                 "$TAPMC_LMP; tools/run-tests.sh builds build/lmp_tapmc)")
    return ["nice", "-n", "10", str(Path(exe).resolve())]  # runs in other folders


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


#: depositions measured by initial-packing: the sem of <Phi^c> over them is then about a
#: tenth of a unit of the paper's last digit (0.1 %)
INITIAL_SEEDS = tuple(range(1, 21))


def initial_packing(args):
    lmp = lmp_command(args.lmp)
    rows = []
    for seed in args.seeds:
        with tempfile.TemporaryDirectory() as folder:
            # taps = 0: the packing as deposited, measured by the runs' own computes
            taps = run(lmp, folder, dict(PAPER, bc="pbc", seed=seed, taps=0, pevery=1,
                                         rsteps=1000000))
        t0 = taps[0]
        rows.append([seed, PAPER["N"], PAPER["L"], "pbc", f"{t0[1]:.8f}", f"{t0[2]:.8f}",
                     f"{t0[3]:.8f}"])
        print(f"seed {seed}: Phi_b {t0[1]:.4f} <Phi^c> {t0[2]:.4f} <Z> {t0[3]:.3f}", flush=True)
    write_csv(Path(args.out) / "initial_packing.csv",
              ["seed", "N", "L", "bc", "phi_b", "phi_c", "Z"], rows)


#: configurations of each packing for p0-configs: depositions, and dumps of the tapped run
P0_CONFIGS = 8
#: taps between the tapped configurations: twice the batch length of the steady state's
#: batch-means error (50 taps), beyond the correlation of successive taps
P0_CONFIG_SPACING = 100
#: eps of the continued run: that of the campaign's Fig. 9 run (CAMPAIGN_RUN)
P0_CONFIG_EPS = 0.0225


def _p0_of(dumps, seed, work):
    """P0(sigma) and the volume fraction seen by the points of each dump, measured as Fig. 9
    measures it (tapmc.paper._pores: the window from the floor + 2R to the lower of 20R and
    0.8 of the highest centre)."""
    from tapmc.paper import _pores, _runs
    from tapmc.pores import read_pores

    out = []
    for k, dump in enumerate(dumps):
        top = _pores.window_top(dump, 0.5)
        prefix = Path(work) / f"p0_{Path(dump).parent.name}_{Path(dump).stem}"
        _runs.run_pores([dump], prefix, ["--radii", "--z", f"{_pores.WINDOW_BOTTOM:g}:{top:.4f}",
                                         "--p0", str(_pores.P0_POINTS), "--seed", str(seed + k)])
        pores = read_pores(prefix)
        out.append((np.asarray(pores.p0["sigma"]), np.asarray(pores.p0["P0_measured"]),
                    float(pores.frames["phi_p0"][0])))
    return out


def campaign_restart(path):
    """The restart file of --restart, resolved; exits with a message when it is missing."""
    restart = Path(path).resolve()
    if not restart.is_file():
        sys.exit(f"paper_questions: restart file {restart} not found (--restart FILE: the "
                 "packing after 4000 taps of the paper-scale campaign's eps = 0.0225 run)")
    return restart


def p0_configs(args):
    lmp = lmp_command(args.lmp)
    restart = campaign_restart(args.restart)
    keep = args.work is not None
    work = Path(args.work) if keep else Path(tempfile.mkdtemp(prefix="p0_configs_"))
    work.mkdir(parents=True, exist_ok=True)
    initial = []
    for seed in range(1, args.configs + 1):
        folder = work / f"initial_s{seed}"
        folder.mkdir(exist_ok=True)
        if not (folder / "dump.0.lammpstrj").is_file():
            run(lmp, folder, dict(PAPER, bc="pbc", seed=seed, taps=0, pevery=1,
                                  rsteps=1000000, dump_ends="yes"))
        initial.append(folder / "dump.0.lammpstrj")
    tapped_dir = work / "tapped"
    tapped_dir.mkdir(exist_ok=True)
    start = NOISE_FROM_STEP
    tapped, previous = [], restart
    for k in range(1, args.configs + 1):
        step = start + k * P0_CONFIG_SPACING
        dump = tapped_dir / f"dump.{step}.lammpstrj"
        if not dump.is_file():
            run(lmp, tapped_dir, dict(PAPER, bc="pbc", eps=P0_CONFIG_EPS, eta=1e-7, seed=1,
                                      resume="yes", resume_file=previous, taps=step,
                                      rsteps=P0_CONFIG_SPACING, pevery=P0_CONFIG_SPACING,
                                      dump_ends="yes"))
            print(f"tapped configuration at tap {step}", flush=True)
        tapped.append(dump)
        previous = tapped_dir / f"restart.{step}"
    curves = {"initial": _p0_of(initial, 1, work), "tapped": _p0_of(tapped, 101, work)}
    sigma = curves["initial"][0][0]
    columns, stats = [], {}
    for key, items in curves.items():
        p0 = np.array([c[1] for c in items])
        phi = np.array([c[2] for c in items])
        stats[key] = (p0.mean(axis=0), p0.std(axis=0, ddof=1) / np.sqrt(len(p0)), len(p0),
                      phi.mean(), phi.std(ddof=1) / np.sqrt(len(phi)))
        print(f"{key}: {len(p0)} configurations, phi seen by the points "
              f"{phi.mean():.5f} +- {stats[key][4]:.5f}")
    rows = [[f"{x:.6g}"] + sum(([f"{stats[k][0][i]:.8g}", f"{stats[k][1][i]:.3g}", stats[k][2]]
                                for k in ("initial", "tapped")), [])
            for i, x in enumerate(sigma)]
    rows.append(["phi"] + sum(([f"{stats[k][3]:.8g}", f"{stats[k][4]:.3g}", stats[k][2]]
                               for k in ("initial", "tapped")), []))
    write_csv(Path(args.out) / "p0_configs.csv",
              ["sigma", "initial", "initial_sem", "initial_n", "tapped", "tapped_sem",
               "tapped_n"], rows)
    if not keep:
        import shutil

        shutil.rmtree(work, ignore_errors=True)


#: Fig. 8's eps (the full scale's profile_eps) and the taps run from the paper's F.B.C. start
LATERAL_EPS = (0.005, 0.02, 0.05, 0.1)
LATERAL_TAPS = 5


def lateral_first_tap(args):
    lmp = lmp_command(args.lmp)
    rows = []
    for eps in LATERAL_EPS:
        for seed in args.seeds:
            with tempfile.TemporaryDirectory() as folder:
                taps = run(lmp, folder, dict(PAPER, bc="fbc", fbc_start="paper", eps=eps,
                                             seed=seed, taps=LATERAL_TAPS, rsteps=1000000))
            # columns of taps.dat: step phi_b phi_c Z z_top lateral central h_s sweeps ...
            for row in taps:
                rows.append([eps, seed, int(row[0]), f"{row[5]:.8f}", f"{row[6]:.8f}",
                             f"{row[2]:.8f}"])
            print(f"eps {eps:g} seed {seed}: delta Phi_lateral at t = 1: "
                  f"{taps[1, 5] - taps[0, 5]:+.4f}, central {taps[1, 6] - taps[0, 6]:+.4f}",
                  flush=True)
    write_csv(Path(args.out) / "lateral_first_tap.csv",
              ["eps", "seed", "t", "lateral", "central", "phi_c"], rows)


#: sub-folder of --out where a knob scan writes its rows until every run is in
PARTIAL = "partial"
#: taps added to a continued ramp level: the campaign's 1000 + 3000 = the paper's 4000
RAMP_EXTEND = 3000


def _manifest_run(campaign, name):
    """(variables, seed) of run ``name`` in the campaign's manifest.json."""
    import json

    path = Path(campaign) / "manifest.json"
    if not path.is_file():
        sys.exit(f"paper_questions: {path} not found (--campaign DIR: a campaign folder)")
    for run in json.loads(path.read_text())["runs"]:
        if run["name"] == name:
            return run["variables"], int(run["seed"])
    sys.exit(f"paper_questions: no run {name!r} in {path}")


def default_ramp_levels(nlev):
    """Two levels of every branch, as the report needs to bound the branch's shift
    (tapmc.paper.claims.RAMP_REDUCTION_MIN_LEVELS): a quarter of the way up the first
    increase and its top, the middle and the bottom of the decrease, the middle and the top
    of the second increase (level indices of in.ramp: 0 .. 3 nlev - 3)."""
    top = nlev - 1
    half = (nlev - 1) // 2
    return sorted({top // 4, top, top + half, 2 * top, 2 * top + half, 3 * top})


def ramp_levels(args):
    from tapmc.paper._steady_state import steady_last

    lmp = lmp_command(args.lmp)
    variables, seed = _manifest_run(args.campaign, args.run)
    P, nlev = int(variables["P"]), int(variables["nlev"])
    run_dir = Path(args.campaign) / "runs" / args.run
    work = Path(args.work) if args.work else Path(args.out) / PARTIAL / "ramp_levels"
    # step level branch sqrt_eps Phi_b phi_c Z; a running ramp may have half a last row
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        table = np.atleast_2d(np.genfromtxt(run_dir / "taps.dat", invalid_raise=False))
    size = {k: variables[k] for k in ("N", "L", "eta", "bc") if k in variables}
    rows = []
    for k in args.levels or default_ramp_levels(nlev):
        end = (k + 1) * P
        restart = run_dir / f"restart.{end}"
        start = "run"
        level = table[(table[:, 0] > end - P) & (table[:, 0] <= end)]
        if not restart.is_file():
            if not args.replay:
                sys.exit(f"paper_questions: {restart} not found (a finished ramp keeps the "
                         "restart files of its level ends; an unfinished one has them up to its "
                         "last step; --replay runs the ramp again up to the level's end)")
            restart, replayed, start = replay_ramp(lmp, args.run, variables, seed, end, work,
                                                   table)
            level = replayed[replayed[:, 0] > end - P]
        # the level's sqrt(eps); a row of a resume step may print 0 (_runs.ramp_sqrt_eps)
        sq = float(np.median(level[level[:, 3] > 0, 3]))
        # a continuation of its own folder: a killed ramp-levels resumes it, and a longer
        # --extend continues it from its latest restart
        more = realization(lmp, work / f"{args.run}_level{k}",
                           dict(size, sqrteps=sq, seed=seed, pevery=end + args.extend),
                           end + args.extend, start=restart, first=end + 1)
        longer = np.concatenate([level[:, 5], [float(r[2]) for r in more]])
        short = SteadyState(level[:, 5], last=steady_last(P)).compute()
        full = SteadyState(longer, last=steady_last(len(longer))).compute()
        rows.append([k, int(level[-1, 2]), f"{sq:.6g}", P, len(longer), f"{short.mean:.8f}",
                     f"{short.sem:.3g}", f"{full.mean:.8f}", f"{full.sem:.3g}", start,
                     args.run])
        print(f"level {k} (branch {int(level[-1, 2])}, sqrt(eps) {sq:g}, from the {start}): "
              f"<Phi^c> {short.mean:.4f} after {P} taps, {full.mean:.4f} after {len(longer)}",
              flush=True)
        # after every level: a session that ends before the last level keeps the others
        write_ramp_levels(Path(args.out) / "ramp_levels.csv", rows)


RAMP_LEVELS_HEADER = ["level", "branch", "sqrt_eps", "taps", "taps_long", "phi_c", "phi_c_sem",
                      "phi_c_long", "phi_c_long_sem", "start", "ramp"]
#: what the columns added to ramp_levels.csv hold in rows written before them: the levels
#: came from the run itself, of the ramp beyond (sqrt eps)* (tapmc.paper.claims)
RAMP_LEVELS_LATER_COLUMNS = {"start": "run", "ramp": RAMP_LEVELS_DEFAULT_RUN}


def write_ramp_levels(path, rows):
    """ramp_levels.csv with ``rows`` and the rows of the (ramp, level) pairs measured before
    and not in ``rows``."""
    header = RAMP_LEVELS_HEADER
    rows = list(rows)
    if path.is_file():
        with open(path, newline="") as handle:
            table = list(csv.reader(handle))
        if table and table[0] == header[:len(table[0])]:
            missing = [RAMP_LEVELS_LATER_COLUMNS[c] for c in header[len(table[0]):]]
            listed = {(r[-1], int(r[0])) for r in rows}
            old = [r + missing for r in table[1:] if r]
            rows += [r for r in old if (r[-1], int(r[0])) not in listed]
    write_csv(path, header, sorted(rows, key=lambda r: (r[-1], int(r[0]))))


RAMP_INPUT = SOURCE / "examples" / "paper" / "in.ramp"


def replay_ramp(lmp, name, variables, seed, end, work, table):
    """The ramp ``name`` run again from its start up to step ``end`` (in.ramp's ``stop``), for
    a level whose restart file the campaign no longer has. The replay keeps a restart file at
    every level end in ``work``/<name>_replay: a killed replay resumes from its latest below
    ``end``, and a later call for a later level continues it. Returns (the restart file at
    ``end``, the replay's taps rows 1..end, how they compare with the campaign's rows
    ``table``: 'replay (identical)' when every common row holds the same numbers, bit for bit
    as printed (a restart-step row that printed sqrt(eps) = 0 aside), else 'replay (differs
    from step S)')."""
    from tapmc.campaign.run_folder import trim_rows

    folder = work / f"{name}_replay"
    folder.mkdir(parents=True, exist_ok=True)
    P = int(variables["P"])
    target = folder / f"restart.{end}"
    with _folder_lock(folder):
        if not target.is_file():
            below = sorted(int(p.name.split(".")[1]) for p in folder.glob("restart.*")
                           if p.name.split(".")[1].isdigit() and int(p.name.split(".")[1]) < end)
            extra = {}
            if below:
                trim_rows(folder / "taps.dat", below[-1])
                extra = {"resume": "yes", "resume_file": f"restart.{below[-1]}"}
            print(f"replaying {name} from step {below[-1] if below else 0} to {end}", flush=True)
            cmd = [*lmp, "-in", str(RAMP_INPUT), "-log", "log.lammps", "-screen", "none"]
            for key, value in dict(variables, seed=seed, rsteps=P, stop=end, **extra).items():
                cmd += ["-var", key, str(value)]
            done = subprocess.run(cmd, cwd=folder, capture_output=True, text=True)
            if done.returncode != 0 or not target.is_file():
                sys.exit(f"paper_questions: {' '.join(cmd)} failed in {folder}:\n"
                         f"{done.stderr[-2000:]}")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        replayed = np.atleast_2d(np.genfromtxt(folder / "taps.dat", invalid_raise=False))
    replayed = replayed[(replayed[:, 0] >= 1) & (replayed[:, 0] <= end)]
    return target, replayed, "replay (" + _replay_agreement(replayed, table) + ")"


def _replay_agreement(replayed, table):
    """'identical' when the rows of the same steps hold the same numbers (sqrt(eps) compared
    where neither is 0: a resumed run's restart-step row may print 0), else 'differs from
    step S'."""
    steps = np.intersect1d(replayed[:, 0], table[:, 0])
    a = replayed[np.isin(replayed[:, 0], steps)]
    b = table[np.isin(table[:, 0], steps)]
    a, b = a[np.argsort(a[:, 0])], b[np.argsort(b[:, 0])]
    if len(a) == 0 or a.shape[1] != b.shape[1]:
        return "no common rows"
    same = np.all(np.delete(a, 3, axis=1) == np.delete(b, 3, axis=1), axis=1)
    same &= (a[:, 3] == b[:, 3]) | (a[:, 3] == 0) | (b[:, 3] == 0)
    if same.all():
        return "identical"
    return f"differs from step {int(a[np.argmin(same), 0])}"


RAMP_PORES_HEADER = ["run", "level", "branch", "sqrt_eps", "step", "nu", "nu_sem",
                     "window_top", "source"]
#: writes the packing of a restart file as the pore-dump runs write theirs (id x y z radius)
DUMP_OF_RESTART = ("read_restart ${restart}\n"
                   "write_dump all custom dump.$(step).lammpstrj id x y z radius "
                   "modify format float %.10g\n")


def _level_restarts(folder, P):
    """dict level -> restart file at its end (restart.<(level + 1) P>) in ``folder``."""
    out = {}
    for path in Path(folder).glob("restart.*"):
        step = path.name.split(".", 1)[1]
        if step.isdigit() and int(step) > 0 and int(step) % P == 0:
            out[int(step) // P - 1] = path
    return out


def ramp_pores(args):
    from tapmc.paper import _pores, _runs
    from tapmc.pores import jackknife_error, read_pores

    lmp = lmp_command(args.lmp)
    variables, seed = _manifest_run(args.campaign, args.run)
    P, nlev = int(variables["P"]), int(variables["nlev"])
    sqrt0, dsqrt = float(variables["sqrt0"]), float(variables["dsqrt"])
    run_dir = Path(args.campaign) / "runs" / args.run
    work = Path(args.work) if args.work else Path(args.out) / PARTIAL / "ramp_levels"
    folder = work / f"{args.run}_pores"
    csv_path = Path(args.out) / "ramp_pores.csv"
    # where each level's packing comes from: a dump made before (its source as the CSV
    # recorded it), else a restart file at its end, the run's before a replay's
    recorded = {}
    if csv_path.is_file():
        with open(csv_path, newline="") as handle:
            recorded = {int(r["level"]): r["source"] for r in csv.DictReader(handle)
                        if r.get("run") == args.run}
    sources = {k: (path, "replay") for k, path in
               _level_restarts(work / f"{args.run}_replay", P).items()}
    sources.update({k: (path, "run") for k, path in _level_restarts(run_dir, P).items()})
    for path in folder.glob("dump.*.lammpstrj"):
        step = path.name.split(".")[1]
        if step.isdigit() and int(step) % P == 0 and int(step) // P - 1 not in sources:
            sources[int(step) // P - 1] = (None, recorded.get(int(step) // P - 1, "run"))
    last = 3 * nlev - 3
    for k in args.levels or ():
        if not 0 <= k <= last:
            sys.exit(f"paper_questions: --levels {k}: allowed levels of {args.run} are 0 .. "
                     f"{last}")
    missing = sorted(k for k in args.levels or () if k not in sources)
    if missing and not args.replay:
        sys.exit(f"paper_questions: no restart file at the end of levels {missing} of "
                 f"{args.run} (--replay runs the ramp again up to them)")
    if missing:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            table = np.atleast_2d(np.genfromtxt(run_dir / "taps.dat", invalid_raise=False))
        for k in missing:
            restart, _, start = replay_ramp(lmp, args.run, variables, seed, (k + 1) * P, work,
                                            table)
            sources[k] = (restart, start)
    if not sources:
        sys.exit(f"paper_questions: no level-end restart file of {args.run} in {run_dir} or "
                 f"{work / (args.run + '_replay')} (--levels K --replay runs the ramp again)")
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "in.dump").write_text(DUMP_OF_RESTART)
    dumps = {}
    for k, (restart, _) in sorted(sources.items()):
        dump = folder / f"dump.{(k + 1) * P}.lammpstrj"
        if not dump.is_file():
            done = subprocess.run([*lmp, "-log", "none", "-screen", "none", "-in", "in.dump",
                                   "-var", "restart", str(Path(restart).resolve())],
                                  cwd=folder, capture_output=True, text=True)
            if done.returncode != 0 or not dump.is_file():
                sys.exit(f"paper_questions: dumping {restart} failed:\n{done.stdout[-1500:]}"
                         f"{done.stderr[-1500:]}")
        dumps[k] = dump
    # every level dumped so far in one analysis with one statistics box, as Fig. 10 takes one
    # box for every dump of its run: a level measured later gets the same box as the others
    top = min(_pores.window_top(d, float(variables.get("R", 0.5))) for d in dumps.values())
    prefix = _runs.run_pores(list(dumps.values()), folder / "pores",
                             ["--radii", "--z", f"{_pores.WINDOW_BOTTOM:g}:{top:.4f}",
                              "--frame-hist", "--pores"])
    pores = read_pores(prefix)
    rows = []
    for k in sorted(dumps):
        step = (k + 1) * P
        branch, sq = _runs.ramp_level(k, nlev, sqrt0, dsqrt)
        nu = pores.distribution(step).nu
        sem = jackknife_error([r.nu for r in pores.jackknife(step)])
        rows.append([args.run, k, branch, f"{sq:.6g}", step, f"{nu:.8f}", f"{sem:.3g}",
                     f"{top:.4f}", sources[k][1]])
        print(f"level {k} (branch {branch}, sqrt(eps) {sq:g}): nu = {nu:.5f} +- {sem:.5f}",
              flush=True)
    write_ramp_pores(csv_path, rows)


def write_ramp_pores(path, rows):
    """ramp_pores.csv with ``rows`` and the rows (of any ramp) of the levels not in ``rows``:
    one table for every ramp measured (the one beyond (sqrt eps)* and the one below it)."""
    rows = list(rows)
    if path.is_file():
        with open(path, newline="") as handle:
            table = list(csv.reader(handle))
        if table and table[0] == RAMP_PORES_HEADER:
            listed = {(r[0], int(r[1])) for r in rows}
            rows += [r for r in table[1:] if r and (r[0], int(r[1])) not in listed]
    write_csv(path, RAMP_PORES_HEADER, sorted(rows, key=lambda r: (r[0], int(r[1]))))


def scan_file_name(stem, stop, N, extra=()):
    """<stem>.csv for the default scan (stop change, N = 1024), else
    <stem>[_<extra>...][_<stop>][_N<N>].csv (extra: e.g. the theta law "solid", "wide")."""
    tags = (list(extra) + ([] if stop == "change" else [stop]) +
            ([] if N == THETA0_SCALE["N"] else [f"N{N}"]))
    return "_".join([stem] + tags) + ".csv"


def knob_scan(args, column, values, keyword, extra_keys="", extra_tags=()):
    """Taps from the same fresh packings (P.B.C., THETA0_EPS, N = --N at the paper's bed height)
    at every value of one fix mc/settle keyword: <Phi^c> at t = 0 and over the last
    THETA0_WINDOW taps per seed (scan_file_name). Each run's row is written when it ends, and a
    scan started again skips the (seed, value) pairs its CSV already has. The rows go to
    <out>/partial/ while the scan runs and its CSV moves to <out> when every run is in, so that
    the report never reads half a scan. extra_keys are added to every run's fix mc/settle
    keywords (e.g. "theta_law solid"), extra_tags to the CSV name."""
    lmp = lmp_command(args.lmp)
    stem = column.split("_over_")[0]
    final = Path(args.out) / scan_file_name(stem, args.stop, args.N, extra_tags)
    path = Path(args.out) / PARTIAL / final.name
    path.parent.mkdir(parents=True, exist_ok=True)
    if final.is_file() and not path.is_file():
        final.replace(path)     # more seeds for a finished scan: it is partial again meanwhile
    header = [column, stem, "seed", "N", "eps", "taps", "eta", "stop", "phi_c_0", "phi_c_end",
              "sweeps_per_tap"]
    done = set()
    if path.is_file():
        with open(path, newline="") as handle:
            done = {(int(r["seed"]), f"{float(r[column]):.6f}") for r in csv.DictReader(handle)}
    else:
        write_csv(path, header, [])
    scale = {"N": args.N, "L": 32 * np.sqrt(args.N / 4096)}
    for seed in args.seeds:
        for label, value in values:
            if (seed, f"{label:.6f}") in done:
                continue
            with tempfile.TemporaryDirectory() as folder:
                keys = (f"{keyword} {value!r}" + (f" {extra_keys}" if extra_keys else "") +
                        (" stop drift" if args.stop == "drift" else ""))
                taps = run(lmp, folder, dict(scale, bc="pbc", eps=THETA0_EPS, seed=seed,
                                             taps=THETA0_TAPS, rsteps=1000000, eta=args.eta,
                                             settle_keys=keys))
            # columns of taps.dat: step phi_b phi_c Z z_top lateral central h_s sweeps ...
            last = taps[-THETA0_WINDOW:]
            with open(path, "a", newline="") as handle:
                csv.writer(handle).writerow(
                    [f"{label:.6f}", repr(value), seed, args.N, THETA0_EPS, THETA0_TAPS,
                     f"{args.eta:g}", args.stop, f"{taps[0, 2]:.8f}", f"{last[:, 2].mean():.8f}",
                     f"{taps[1:, 8].mean():.1f}"])
            print(f"seed {seed} {column} = {label:.4f}: <Phi^c> {taps[0, 2]:.4f} -> "
                  f"{last[:, 2].mean():.4f} ({taps[1:, 8].mean():.0f} sweeps per tap)", flush=True)
    path.replace(final)
    print(f"wrote {final}")


def theta0_scan(args):
    law = getattr(args, "theta_law", "angle")
    wide = getattr(args, "wide", False)
    tags = ([law] if law != "angle" else []) + (["wide"] if wide else [])
    knob_scan(args, "theta0_over_pi",
              [(f, np.pi * f) for f in (THETA0_WIDE_PI if wide else THETA0_PI)], "theta0",
              extra_keys=f"theta_law {law}" if law != "angle" else "", extra_tags=tags)


def dmax_scan(args):
    knob_scan(args, "dmax_over_R", [(f, f * THETA0_RADIUS) for f in DMAX_OVER_R], "dmax")


def noise_floor(args):
    lmp = lmp_command(args.lmp)
    restart = campaign_restart(args.restart)
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


#: taps of the running mean that decides when <Phi^c> has regained its t = 0 value (the
#: tap-to-tap spread at strong taps, 0.1 %, is a third of the dip's depth; ten taps average it
#: down below a tenth of the dip) and that it must then stay there for.
COURSE_SMOOTHING = 10
#: first taps searched for the lowest <Phi^c> (the dip is over by tap 100 at every eps).
COURSE_EARLY = 100


def recovery_tap(t, phi, level, width=COURSE_SMOOTHING):
    """First tap t_k (k >= 1) from which the running mean of ``width`` taps, phi[k..k+width),
    is at least ``level`` for ``width`` consecutive starts: the end of the dip below the
    initial packing; None when the series never regains it."""
    if len(phi) < 2 * width:
        return None
    running = np.convolve(phi, np.ones(width) / width, mode="valid")
    above = running >= level
    for k in range(1, len(above) - width + 1):
        if above[k:k + width].all():
            return int(t[k])
    return None


def steady_halves(x, steady):
    """(second half minus first half of the steady window, its error, its dof): each half
    with its batch-means error over half the batches (is the run still compacting?)."""
    half = steady.last // 2
    batches = steady.batches // 2
    first, second = (SteadyState(part, last=half, batches=batches).compute()
                     for part in (x[-steady.last:-half], x[-half:]))
    return (second.mean - first.mean, float(np.hypot(first.sem, second.sem)),
            2 * (min(batches, half // 2) - 1))


def pbc_course(args):
    rows = []
    for run_dir in sorted(Path(args.campaign, "runs").glob("const_pbc_eps*_s*")):
        if not (run_dir / "DONE.json").is_file():
            continue  # an unfinished run has no steady window yet
        table = np.loadtxt(run_dir / "taps.dat", ndmin=2)
        t, phi = table[:, 0], table[:, 2]
        eps = float(run_dir.name.split("_eps")[1].split("_s")[0])
        seed = int(run_dir.name.rsplit("_s", 1)[1])
        early = (t >= 1) & (t <= COURSE_EARLY)
        k = int(np.flatnonzero(early)[np.argmin(phi[early])])
        back = recovery_tap(t, phi, phi[0])
        steady = SteadyState(phi[1:]).compute()
        # still compacting? the second half of the steady window minus its first half
        drift, drift_se, _ = steady_halves(phi, steady)
        rows.append([run_dir.name, eps, seed, len(t) - 1, f"{phi[0]:.8f}", f"{phi[k]:.8f}",
                     int(t[k]), "" if back is None else back, f"{steady.mean:.8f}",
                     f"{steady.sem:.3g}", f"{steady.std:.3g}", f"{drift:.3g}", f"{drift_se:.3g}"])
        print(f"{run_dir.name}: phi_c {phi[0]:.4f} -> min {phi[k]:.4f} at tap {int(t[k])}, "
              f"back at tap {back}, steady {steady.mean:.4f} +- {steady.sem:.4f}, "
              f"halves differ by {drift:+.4f} +- {drift_se:.4f}")
    write_csv(Path(args.out) / "pbc_course.csv",
              ["run", "eps", "seed", "taps", "phi_c_0", "phi_c_min", "tap_min", "tap_back",
               "phi_c_steady", "phi_c_steady_sem", "phi_c_steady_sd", "steady_halves_diff",
               "steady_halves_diff_sem"], rows)


#: the scalars of taps.dat whose steady state the report quotes with one run's error
SCATTER_COLUMNS = ("phi_b", "phi_c", "Z")
#: the zone means of taps.dat (compute stereo/profile's lateral and central zones) whose final
#: window Fig. 8 quotes, and their difference per run
ZONE_COLUMNS = ("lateral", "central")


def _seed_groups(campaign):
    """dict group -> [(seed, run folder)] of the finished constant-eps and ageing runs
    (``<kind>_<bc>_eps<eps>_s<seed>``, P.B.C. and F.B.C.) with at least two seeds."""
    groups = {}
    for run_dir in sorted(Path(campaign, "runs").glob("*_eps*_s*")):
        if not run_dir.name.startswith(("const_", "ageing_")):
            continue
        if not (run_dir / "DONE.json").is_file():
            continue  # an unfinished run has no steady window yet
        group, seed = run_dir.name.rsplit("_s", 1)
        groups.setdefault(group, []).append((int(seed), run_dir))
    return {g: sorted(runs) for g, runs in groups.items() if len(runs) >= 2}


def realization_scatter(args):
    from tapmc.paper.fig3 import sigma_error_one_run

    rows = []
    for group, runs in _seed_groups(args.campaign).items():
        tables = {seed: read_fix_print(run_dir / "taps.dat") for seed, run_dir in runs}
        taps = {len(t["step"]) for t in tables.values()}
        if len(taps) != 1:
            print(f"{group}: seeds of different lengths {sorted(taps)}: skipped")
            continue
        for seed, run_dir in runs:
            table = tables[seed]
            keep = table["step"] > 0
            for column in SCATTER_COLUMNS:
                x = table[column][keep]
                steady = SteadyState(x).compute()
                rows.append([group, run_dir.name, seed, int(keep.sum()), column,
                             f"{table[column][0]:.8g}", f"{steady.mean:.8g}",
                             f"{steady.sem:.4g}", steady.last,
                             min(DEFAULT_BATCHES, steady.last // 2) - 1])
                # pbc-course's test of a run still compacting, as it computes it
                drift, drift_se, dof = steady_halves(x, steady)
                rows.append([group, run_dir.name, seed, int(keep.sum()), f"{column}:halves",
                             "", f"{drift:.6g}", f"{drift_se:.4g}", steady.last, dof])
            # Fig. 3's sigma_<Z> (about X_SS and about the window's straight line) with its
            # one-run error (batch means of the squared deviations)
            z = table["Z"][keep]
            for detrend, suffix in (("constant", ""), ("linear", "_detrended")):
                steady = SteadyState(z, detrend=detrend).compute()
                rows.append([group, run_dir.name, seed, int(keep.sum()), f"Z:sigma{suffix}",
                             "", f"{steady.std:.6g}",
                             f"{sigma_error_one_run(z, steady.last, detrend=detrend):.4g}",
                             steady.last, min(DEFAULT_BATCHES, steady.last // 2) - 1])
            # Fig. 3's spectral slope over the same window, with the periodogram's error
            spectrum = PowerSpectrum(z, steady_from=len(z) - steady.last).compute()
            rows.append([group, run_dir.name, seed, int(keep.sum()), "Z:slope", "",
                         f"{spectrum.slope:.6g}", f"{spectrum.slope_error:.4g}", steady.last,
                         ""])
            # Fig. 8's final zone means and their difference, as fig8 takes them (the last
            # quarter of the taps, batch means)
            if all(c in table for c in ZONE_COLUMNS):
                zones = {c: table[c][keep] for c in ZONE_COLUMNS}
                zones["central_minus_lateral"] = zones["central"] - zones["lateral"]
                last = max(int(keep.sum()) // 4, 1)
                for name, x in zones.items():
                    steady = SteadyState(x, last=last).compute()
                    rows.append([group, run_dir.name, seed, int(keep.sum()), f"zone:{name}",
                                 f"{table[name][0]:.8g}" if name in table else "",
                                 f"{steady.mean:.8g}", f"{steady.sem:.4g}", steady.last,
                                 min(DEFAULT_BATCHES, steady.last // 2) - 1])
            mine = [r for r in rows if r[1] == run_dir.name]
            print(f"{run_dir.name}: " + ", ".join(
                f"{r[4]} {float(r[6]):.5f} +- {float(r[7]):.5f}" for r in mine))
    write_csv(Path(args.out) / "realization_scatter.csv",
              ["group", "run", "seed", "taps", "column", "start", "mean", "sem", "last",
               "sem_dof"], rows)


#: packing-scatter's quantities of one packing, as realization_scatter.csv names columns
PACKING_NU, PACKING_ALPHA = "packing:nu", "packing:alpha"


def _run_radius(run_dir):
    """The sphere radius R a finished run ran with (its DONE.json's variables; 0.5, the
    inputs' default, when it sets none)."""
    done = json.loads((Path(run_dir) / "DONE.json").read_text() or "{}")
    return float(done.get("run", {}).get("variables", {}).get("R", 0.5))


def _packing_nu(dump, work, radius):
    """(nu, its spatial jackknife error) of one dump in Fig. 10's statistics box (2R above
    the floor to 20R or SURFACE_FRACTION of the highest centre), tapmc-pores' outputs kept in
    ``work`` under the dump's run folder name (one analysis per dump: dumps of different runs
    share their step)."""
    from tapmc.paper import _pores, _runs
    from tapmc.pores import jackknife_error, read_pores

    dump = Path(dump)
    step = int(dump.name.split(".")[1])
    top = _pores.window_top(dump, radius)
    prefix = _runs.run_pores([dump], Path(work) / f"{dump.parent.name}_t{step}",
                             ["--radii", "--z", f"{_pores.WINDOW_BOTTOM:g}:{top:.4f}",
                              "--frame-hist", "--pores"])
    pores = read_pores(prefix)
    return (pores.distribution(step).nu,
            jackknife_error([r.nu for r in pores.jackknife(step)]))


def packing_scatter(args):
    from tapmc.paper import fig6
    from tapmc.paper.claims import group_bc
    from tapmc.pores import JACKKNIFE_BLOCKS
    from tapmc.profiles import PROFILE_JACKKNIFE_BLOCKS

    work = Path(args.work) if args.work else Path(args.out) / PARTIAL / "packing_scatter"
    work.mkdir(parents=True, exist_ok=True)
    # the jackknifes' dof: their blocks (lateral, per side) squared, minus one
    nu_dof, alpha_dof = JACKKNIFE_BLOCKS ** 2 - 1, PROFILE_JACKKNIFE_BLOCKS ** 2 - 1
    rows, initial = [], {}
    for group, runs in _seed_groups(args.campaign).items():
        if not group.startswith("const_"):
            continue      # the ageing runs dump no packing
        bc = group_bc(group)
        tables = {seed: read_fix_print(run_dir / "taps.dat") for seed, run_dir in runs}
        taps = {int(t["step"][-1]) for t in tables.values()}
        if len(taps) != 1:
            print(f"{group}: seeds of different lengths {sorted(taps)}: skipped")
            continue
        last = taps.pop()
        radii = {seed: _run_radius(run_dir) for seed, run_dir in runs}
        window = fig6.window_below([t["h_s"][0] / radii[seed] for seed, t in tables.items()],
                                   bc)
        for seed, run_dir in runs:
            start = tables[seed]["phi_c"][0]
            nu, nu_err = _packing_nu(fig6.final_dump(run_dir, last), work, radii[seed])
            alpha, alpha_err = fig6.run_alpha(run_dir, last, radii[seed], window, bc)
            rows.append([group, run_dir.name, seed, last, PACKING_NU, f"{start:.8g}",
                         f"{nu:.8g}", f"{nu_err:.4g}", "", nu_dof])
            rows.append([group, run_dir.name, seed, last, PACKING_ALPHA, f"{start:.8g}",
                         f"{alpha:.8g}", f"{alpha_err:.4g}", "", alpha_dof])
            print(f"{run_dir.name}: nu {nu:.5f} +- {nu_err:.5f}, alpha {alpha:.5f} +- "
                  f"{alpha_err:.5f}", flush=True)
            # the initial packings: one per seed and boundary condition (every eps of a seed
            # starts from it), told apart by their <Phi^c>
            initial.setdefault(bc, {}).setdefault(f"{start:.8f}", (seed, run_dir))
    for bc, packings in sorted(initial.items()):
        if len(packings) < 2:
            continue
        for seed, run_dir in sorted(packings.values()):
            nu, nu_err = _packing_nu(run_dir / "dump.0.lammpstrj", work,
                                     _run_radius(run_dir))
            rows.append([f"initial_{bc}", run_dir.name, seed, 0, PACKING_NU,
                         f"{read_fix_print(run_dir / 'taps.dat')['phi_c'][0]:.8g}",
                         f"{nu:.8g}", f"{nu_err:.4g}", "", nu_dof])
            print(f"{run_dir.name} at t = 0: nu {nu:.5f} +- {nu_err:.5f}", flush=True)
    write_csv(Path(args.out) / "packing_scatter.csv",
              ["group", "run", "seed", "taps", "column", "start", "mean", "sem", "last",
               "sem_dof"], rows)


#: early-taps: the first REALIZATION_TAPS taps from the campaign's F.B.C. packing, with Monte
#: Carlo seeds other than the campaign's (1): 8 more realizations, 9 with the campaign's run,
#: give the first decade's rate an error over seeds (8 dof, t = 2.31) and Fig. 2's laws a
#: test whose covariance between times comes from independent runs
#: (tapmc.laws.RealizationLawTest). 400 taps span 2.6 of the run's 3.6 decades for about a
#: tenth of its cost (3.4, 5.7 and 7.7 CPU-min per realization at eps = 0.005, 0.05, 0.15).
REALIZATION_TAPS = 400
EARLY_SEEDS = tuple(range(2, 10))
#: the campaign's seed: its pack_seed is the packing every F.B.C. run starts from
CAMPAIGN_SEED = 1
#: taps between the restart files of a realization (a killed early-taps resumes from them)
REALIZATION_RESTART_EVERY = 50


def realization(lmp, folder, variables, taps, start=None, first=0):
    """Rows (step, phi_b, phi_c, Z as text) of taps first..taps of one run in ``folder``: kept
    when the folder already holds them, otherwise run, or resumed from the folder's latest
    restart file (the same taps bit for bit as one uninterrupted run). ``start``: a restart
    file the run continues (its step is ``first`` - 1) instead of a fresh packing."""
    folder.mkdir(parents=True, exist_ok=True)
    out = folder / "taps.dat"
    with _folder_lock(folder):
        if not (out.is_file() and _has_taps(out, taps, first)):
            step, restart = latest_restart(folder)
            if step is not None:
                extra = {"resume": "yes", "resume_file": restart.name}
            elif start is not None:
                extra = {"resume": "yes", "resume_file": Path(start).resolve()}
            else:
                extra = {}
            # restart files at steps that include the last: a later call for more taps
            # continues from it
            every = math.gcd(REALIZATION_RESTART_EVERY, taps)
            run(lmp, folder, dict(variables, taps=taps, rsteps=every, **extra))
            keep_latest_restart(folder)   # it alone continues the run
    names, printed = _printed_rows(out)
    return [[printed[t][names.index(c)] for c in ("step", "phi_b", "phi_c", "Z")]
            for t in range(first, taps + 1)]


@contextlib.contextmanager
def _folder_lock(folder, poll=30.0):
    """Hold ``folder`` for one process: several early-taps processes (one per eps, or
    overlapping seed lists) then never run the same realization at once; a process that
    finds the folder held waits for it, then finds the taps there. A lock whose process is
    gone (killed) is taken over."""
    lock = folder / "running.pid"
    while True:
        try:
            handle = os.open(lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY)
            os.write(handle, str(os.getpid()).encode())
            os.close(handle)
            break
        except FileExistsError:
            try:
                holder = int(lock.read_text().strip())
            except (FileNotFoundError, ValueError):   # released, or its pid not written yet
                time.sleep(min(poll, 1.0))
                continue
            try:
                os.kill(holder, 0)              # the holder is alive: wait for it
                time.sleep(poll)
            except ProcessLookupError:
                lock.unlink(missing_ok=True)
    try:
        yield
    finally:
        lock.unlink(missing_ok=True)


def _has_taps(path, taps, first=0):
    _, printed = _printed_rows(path)
    return all(t in printed for t in range(first, taps + 1))


def early_taps(args):
    from tapmc.paper.scales import FULL

    lmp = lmp_command(args.lmp)
    work = Path(args.work) if args.work else Path(args.out) / PARTIAL / "early_taps"
    rows = []
    for eps in args.eps or FULL.fig2_eps:
        own = Path(args.campaign, "runs", f"const_fbc_eps{eps:g}_s{CAMPAIGN_SEED}", "taps.dat")
        if own.is_file() and _has_taps(own, args.taps):
            # the campaign's own run is the realization of seed 1
            names, printed = _printed_rows(own)
            rows += [[eps, CAMPAIGN_SEED, t] + [printed[t][names.index(c)]
                                                for c in ("phi_b", "phi_c", "Z")]
                     for t in range(args.taps + 1)]
        for seed in args.seeds:
            start = time.monotonic()
            taps = realization(lmp, work / f"eps{eps:g}_s{seed}",
                               dict(PAPER, bc="fbc", eps=eps, seed=seed,
                                    pack_seed=CAMPAIGN_SEED), args.taps)
            rows += [[eps, seed, int(float(r[0]))] + r[1:] for r in taps]
            print(f"eps {eps:g} seed {seed}: Phi_b {float(taps[0][1]):.4f} -> "
                  f"{float(taps[-1][1]):.4f} at tap {args.taps} "
                  f"({time.monotonic() - start:.0f} s)", flush=True)
    write_csv(Path(args.out) / "early_taps.csv", ["eps", "seed", "t", "phi_b", "phi_c", "Z"],
              rows)


#: the laws of Fig. 2 and the column each describes
FIT_LAWS = (("eq3", "phi_b"), ("eq4", "Z"))


def _law(name):
    from tapmc.laws import InverseLogLaw, ZLaw

    return {"eq3": InverseLogLaw, "eq4": ZLaw}[name]()


def fit_surrogates(args):
    """Per finished F.B.C. constant-eps run of the campaign (every seed: the claims read the
    first, the others show how the surrogates' verdict varies between realizations) and law
    of Fig. 2: how well the run fixes each parameter and whether it depends on the tap range
    (tapmc.laws.SurrogateFits, from tap 1 as Fig. 2 is drawn); and, from early_taps.csv, the
    spread of the same fit over independent realizations of the first taps (sample 16-84 % of
    the fitted values)."""
    from tapmc.laws import RELATIVE_ERROR_LIMIT, SurrogateFits

    header = ["source", "eps", "law", "taps", "parameter", "value", "low", "high",
              "half_width", "log_scale", "determined", "range_p", "fits"]
    rows = []
    for run_dir in sorted(Path(args.campaign, "runs").glob("const_fbc_eps*_s*")):
        if not (run_dir / "DONE.json").is_file():
            continue
        eps = float(run_dir.name.split("_eps")[1].split("_s")[0])
        names, printed = _printed_rows(run_dir / "taps.dat")
        t = np.array(sorted(printed), dtype=float)
        for law_name, column in FIT_LAWS:
            start = time.monotonic()
            y = np.array([float(printed[int(k)][names.index(column)]) for k in t])
            fits = SurrogateFits(_law(law_name), surrogates=args.surrogates,
                                 seed=args.seed).compute(t, y)
            for k in fits.params:
                rows.append([run_dir.name, eps, law_name, int(t.max()), k,
                             f"{fits.params[k]:.8g}", f"{fits.low[k]:.8g}", f"{fits.high[k]:.8g}",
                             f"{fits.half_width[k]:.6g}", int(fits.log_scale[k]),
                             int(fits.determined[k]), f"{fits.range_p[k]:.4g}", fits.used])
            print(f"{run_dir.name} {law_name}: {fits} ({time.monotonic() - start:.0f} s)",
                  flush=True)
    early = Path(args.out) / "early_taps.csv"
    if early.is_file():
        curves = {}
        with open(early) as handle:
            for r in csv.DictReader(handle):
                curves.setdefault(float(r["eps"]), {}).setdefault(int(r["seed"]), []).append(r)
        for eps, by_seed in sorted(curves.items()):
            for law_name, column in FIT_LAWS:
                law = _law(law_name)
                values = []
                for seed_rows in by_seed.values():
                    t = np.array([float(r["t"]) for r in seed_rows])
                    y = np.array([float(r[column]) for r in seed_rows])
                    keep = t >= 1
                    values.append(law.fit(t[keep], y[keep]).params)
                for k in law.names:
                    v = np.array([p[k] for p in values])
                    log = k in ("B", "tau") and np.all(v > 0)
                    scaled = np.log(v) if log else v
                    lo, mid, hi = np.percentile(scaled, [16.0, 50.0, 84.0])
                    back = np.exp if log else float
                    half = (hi - lo) / 2.0
                    # the determination rule of SurrogateFits, over realizations
                    limit = np.log(2.0) if log else RELATIVE_ERROR_LIMIT * abs(mid)
                    rows.append(["realizations", eps, law_name, int(t.max()), k,
                                 f"{float(back(mid)):.8g}", f"{float(back(lo)):.8g}",
                                 f"{float(back(hi)):.8g}", f"{half:.6g}", int(log),
                                 int(half <= limit), "nan", len(values)])
                print(f"realizations eps {eps:g} {law_name}: {len(values)} fits", flush=True)
    write_csv(Path(args.out) / "fit_surrogates.csv", header, rows)


#: the header of seed_fits.csv (values: each run's fit in the comparison scale, ln for B and
#: tau; determined: 1, 0, or empty when the realizations cannot tell)
SEED_FITS_HEADER = ["group", "bc", "eps", "law", "taps", "realizations", "parameter", "values",
                    "mean", "spread", "spread_low", "spread_high", "limit", "log_scale",
                    "determined", "range_shift", "range_bound", "range_p"]


def seed_fits(args):
    """Per group of realizations (_seed_groups) and law of Fig. 2: tapmc.laws.RealizationFits
    over the taps every run has, from tap 1."""
    from tapmc.laws import RealizationFits

    rows = []
    for group, runs in _seed_groups(args.campaign).items():
        printed = [_printed_rows(run_dir / "taps.dat") for _, run_dir in runs]
        last = min(max(p) for _, p in printed)
        t = np.arange(1, last + 1, dtype=float)
        bc = group.split("_")[1]
        eps = float(group.split("_eps")[1])
        for law_name, column in FIT_LAWS:
            curves = [[float(p[int(k)][names.index(column)]) for k in t] for names, p in printed]
            fits = RealizationFits(_law(law_name)).compute(t, curves)
            for k in fits.law.names:
                d = fits.determined[k]
                rows.append([group, bc, eps, law_name, last, fits.realizations, k,
                             ";".join(f"{v:.6g}" for v in fits.values[k]),
                             f"{fits.mean[k]:.8g}", f"{fits.spread[k]:.6g}",
                             f"{fits.spread_low[k]:.6g}", f"{fits.spread_high[k]:.6g}",
                             f"{fits.limit[k]:.6g}", int(fits.log_scale[k]),
                             "" if d is None else int(d), f"{fits.range_shift[k]:.6g}",
                             f"{fits.range_bound[k]:.6g}", f"{fits.range_p[k]:.4g}"])
            print(f"{group} {law_name}: {fits}", flush=True)
    write_csv(Path(args.out) / "seed_fits.csv", SEED_FITS_HEADER, rows)


#: columns of a run's taps.dat that a dumped packing reproduces (tapmc.packing.PackingCheck)
INTEGRITY_COLUMNS = ("phi_b", "phi_c", "Z", "z_top", "h_s")
#: what the dump's rounding (%.10g: 5e-9 on a coordinate of the paper's box) can move a mean
#: height, a slab fraction or the surface height by, at most (with a factor 2 of room)
INTEGRITY_SLACK = 1e-8


def _printed_rows(path):
    """(column names, {step: the last row printed for it, as text fields}) of a taps.dat: a
    resumed run prints the steps after its restart again, and the last print is the one of
    the run that continued (and wrote the dumps from then on)."""
    names, rows = None, {}
    with open(path) as handle:
        for line in handle:
            if line.startswith("#"):
                names = line[1:].split()
            elif line.strip():
                fields = line.split()
                rows[int(float(fields[0]))] = fields
    if names is None:
        sys.exit(f"paper_questions: {path} has no '# step ...' header line")
    return names, rows


def integrity(args):
    from tapmc.packing import PackingCheck
    from tapmc.readers import read_dump

    rows = []
    runs = sorted(p for p in Path(args.campaign, "runs").iterdir() if p.is_dir())
    for run_dir in runs:
        dumps = sorted(run_dir.glob("dump.*.lammpstrj"),
                       key=lambda p: int(p.name.split(".")[1]))
        if not dumps or not (run_dir / "taps.dat").is_file():
            continue
        names, printed = _printed_rows(run_dir / "taps.dat")
        for dump in dumps:
            frame = read_dump(dump).frames[-1]
            check = PackingCheck(frame).compute()
            row = printed.get(frame.step)
            scalars = check.scalars()
            worst, worst_name = 0.0, ""
            for name in INTEGRITY_COLUMNS:
                if row is None or name not in names:
                    continue
                text = row[names.index(name)]
                decimals = len(text.split(".")[1]) if "." in text else 0
                # the difference in units of what the print and the dump's rounding allow
                allowed = 0.5 * 10.0 ** -decimals + INTEGRITY_SLACK
                ratio = abs(scalars[name] - float(text)) / allowed
                if ratio >= worst:
                    worst, worst_name = ratio, name
            rows.append([run_dir.name, frame.step, check.n, f"{check.min_gap:.4g}",
                         check.overlaps, f"{check.floor_gap:.4g}",
                         "" if check.wall_gap is None else f"{check.wall_gap:.4g}",
                         int(check.legal),
                         f"{check.resolution / (2 * float(check.radii.min())):.3g}",
                         f"{check.phi_c:.8f}", "" if row is None else f"{worst:.3g}",
                         worst_name])
            print(f"{run_dir.name} t = {frame.step}: {check!r}, printed scalars within "
                  f"{worst:.2f} of their allowance ({worst_name})", flush=True)
    if not rows:
        sys.exit(f"paper_questions: no run of {args.campaign} has dumps and a taps.dat")
    write_csv(Path(args.out) / "integrity.csv",
              ["run", "tap", "n", "min_gap", "overlaps", "floor_gap", "wall_gap", "legal",
               "resolution_rel", "phi_c", "scalars_worst", "scalars_worst_column"], rows)


#: Phi of the fluids: stable fluid up to freezing (0.494), then metastable ones (the 4000
#: spheres do not crystallise within the runs at 0.54: g(1+) stays on the fluid's branch).
P0_FLUID_PHI = (0.30, 0.40, 0.45, 0.49, 0.52, 0.54)
#: FCC cells per side of the start lattice: 4 * 10^3 = 4000 spheres, near the paper's 4096.
P0_FLUID_CELLS = 10
#: configurations per Phi: the sem of max |P0 - PY| is then about 3e-4, a tenth of the
#: smallest value measured (200000 random points give each configuration about 1e-3).
P0_FLUID_CONFIGS = 8
#: mean-square displacement (diameters^2) before the first configuration: every sphere has
#: moved by about 1.4 diameters, far beyond the cage (a tenth of a diameter) that sets the
#: local structure P0 measures.
P0_FLUID_EQ_MSD = 2.0
#: between configurations: beyond the structural relaxation (rms 0.7 diameter), so the
#: configurations are independent samples of the local structure.
P0_FLUID_SPACING_MSD = 0.5
#: sweep bound per stage; a stage stopped by it is seen in the CSV (eq_msd, min_spacing_msd).
P0_FLUID_MAX_SWEEPS = 400000
MC_SOURCE = SOURCE / "bench" / "bench_hs_fluid.cpp"
MC_FLAGS = ("-O2", "-std=c++17")


def mc_command(exe, work):
    """The hard-sphere MC program: --mc EXE, build/bench/bench_hs_fluid, else compiled."""
    candidates = [Path(exe)] if exe else [
        Path(os.environ.get("TAPMC_BUILD_DIR", SOURCE / "build")) / "bench" / "bench_hs_fluid"]
    for path in candidates:
        if path.is_file() and os.access(path, os.X_OK):
            if path.stat().st_mtime < MC_SOURCE.stat().st_mtime:
                print(f"paper_questions: warning: {path} is older than {MC_SOURCE}")
            return ["nice", "-n", "2", str(path)]
    if exe:
        sys.exit(f"paper_questions: --mc {exe}: no such executable")
    built = Path(work) / "bench_hs_fluid"
    if not built.is_file() or built.stat().st_mtime < MC_SOURCE.stat().st_mtime:
        cxx = os.environ.get("CXX", "c++")
        done = subprocess.run([cxx, *MC_FLAGS, "-o", str(built), str(MC_SOURCE)],
                              capture_output=True, text=True)
        if done.returncode != 0:
            sys.exit(f"paper_questions: compiling {MC_SOURCE} with {cxx} failed:\n"
                     f"{done.stderr[-2000:]}")
    return ["nice", "-n", "2", str(built)]


def parse_mc(text):
    """(dict of the 'key value' lines, list of per-configuration dicts) of bench_hs_fluid."""
    values, configs = {}, []
    for line in text.splitlines():
        fields = line.split()
        if fields and fields[0] == "config":
            configs.append({fields[k]: float(fields[k + 1]) for k in range(0, len(fields), 2)})
        elif len(fields) == 2:
            values[fields[0]] = float(fields[1])
    return values, configs


def fluid_configurations(mc, folder, phi, args):
    """Run the MC for ``phi`` into ``folder`` unless a finished run is there (mc.txt is written
    last); returns (values, configs, dumps)."""
    log = folder / "mc.txt"
    dumps = [folder / f"fluid.{k}.lammpstrj" for k in range(1, args.configs + 1)]
    if not (log.is_file() and all(d.is_file() for d in dumps)):
        folder.mkdir(parents=True, exist_ok=True)
        seed = args.seed * 1000 + round(1000 * phi)
        cmd = [*mc, "--phi", f"{phi:g}", "--cells", str(args.cells), "--seed", str(seed),
               "--configs", str(args.configs), "--eq-msd", f"{args.eq_msd:g}",
               "--spacing-msd", f"{args.spacing_msd:g}", "--max-sweeps", str(args.max_sweeps),
               "--prefix", str(folder / "fluid")]
        done = subprocess.run(cmd, capture_output=True, text=True)
        if done.returncode != 0:
            sys.exit(f"paper_questions: {' '.join(cmd)} failed:\n{done.stderr[-2000:]}")
        (folder / "mc.txt.partial").write_text(done.stdout)
        (folder / "mc.txt.partial").rename(log)
    values, configs = parse_mc(log.read_text())
    if len(configs) != args.configs or int(values["N"]) != 4 * args.cells ** 3:
        sys.exit(f"paper_questions: {log} is from other settings (remove {folder})")
    return values, configs, dumps


def p0_fluid(args):
    from tapmc.paper._pores import P0_POINTS
    from tapmc.paper._runs import pores_executable
    from tapmc.pores import percus_yevick_p0, read_pores

    with tempfile.TemporaryDirectory() as scratch:
        work = Path(args.work) if args.work else Path(scratch)
        work.mkdir(parents=True, exist_ok=True)
        mc = mc_command(args.mc, work)
        pores = ["nice", "-n", "2", pores_executable()]
        rows, curves = [], []
        for phi in args.phi:
            folder = work / f"phi_{phi:g}"
            values, configs, dumps = fluid_configurations(mc, folder, phi, args)
            p0s, phis = [], []
            for k, dump in enumerate(dumps, start=1):
                prefix = folder / f"pores_{k}"
                if not Path(str(prefix) + ".p0.csv").is_file():
                    # Fig. 9's settings: P0_POINTS random points, one seed per configuration;
                    # the box is triply periodic, so the selection is the whole box.
                    cmd = [*pores, "-q", "--p0", str(P0_POINTS), "--seed", str(k),
                           "-o", str(prefix), str(dump)]
                    done = subprocess.run(cmd, capture_output=True, text=True)
                    if done.returncode != 0:
                        sys.exit(f"paper_questions: {' '.join(cmd)} failed:\n{done.stderr}")
                result = read_pores(prefix)
                sigma = np.asarray(result.p0["sigma"], dtype=float)
                p0s.append(np.asarray(result.p0["P0_measured"], dtype=float))
                phis.append(float(result.frames["phi_p0"][0]))
            p0s, phis = np.array(p0s), np.array(phis)
            n = len(p0s)
            mean, sem = p0s.mean(axis=0), p0s.std(axis=0, ddof=1) / np.sqrt(n)
            # as Fig. 9: each configuration against PY at the volume fraction its random points
            # see (the same points, so their noise cancels in part); mean and sem of that
            # difference over the configurations
            theories = np.array([percus_yevick_p0(sigma, q) for q in phis], dtype=float)
            diffs = p0s - theories
            diff = diffs.mean(axis=0)
            diff_sem = diffs.std(axis=0, ddof=1) / np.sqrt(n)
            theory = theories.mean(axis=0)
            phi_points = float(phis.mean())
            at = int(np.argmax(np.abs(diff)))
            singles = np.abs(diffs).max(axis=1)
            exact = np.asarray(percus_yevick_p0(sigma, values["phi"]), dtype=float)
            spacing = min(c["msd_spacing"] for c in configs)
            rows.append([
                f"{values['phi']:.6g}", int(values["N"]), n, f"{phi_points:.6g}",
                f"{phis.std(ddof=1) / np.sqrt(n):.3g}", P0_POINTS,
                f"{abs(diff[at]):.6g}", f"{diff_sem[at]:.3g}", f"{sigma[at]:.6g}",
                f"{diff[at]:.6g}", f"{theory[at]:.6g}",
                f"{np.mean(singles):.6g}", f"{np.std(singles, ddof=1) / np.sqrt(n):.3g}",
                f"{np.max(np.abs(mean - exact)):.6g}", f"{values['acceptance']:.4g}",
                f"{values['delta']:.4g}", int(values["eq_sweeps"]),
                int(values["sample_sweeps"]), f"{values['eq_msd']:.4g}", f"{spacing:.4g}",
                f"{values['g_contact']:.6g}", f"{values['g_contact_sem']:.3g}",
                f"{values['g_contact_cs']:.6g}", f"{values['min_distance']:.9g}",
                f"{values['seconds']:.4g}"])
            curves += [[f"{values['phi']:.6g}", f"{s:.6g}", f"{m:.6g}", f"{e:.3g}", f"{t:.6g}",
                        f"{d:.6g}", f"{de:.3g}"]
                       for s, m, e, t, d, de in zip(sigma, mean, sem, theory, diff, diff_sem)]
            print(f"Phi {values['phi']:.3f}: max |P0 - PY| = {abs(diff[at]):.4f} +- "
                  f"{diff_sem[at]:.4f} at sigma = {sigma[at]:.3f}; g(1+) {values['g_contact']:.3f} "
                  f"(CS {values['g_contact_cs']:.3f}); msd {values['eq_msd']:.2f}; "
                  f"{values['seconds']:.0f} s", flush=True)
        write_csv(Path(args.out) / "p0_fluid.csv",
                  ["phi", "N", "configs", "phi_points", "phi_points_sem", "p0_points",
                   "max_abs_diff", "max_abs_diff_sem", "sigma_at_max", "diff_at_max", "py_at_max",
                   "max_abs_diff_per_config", "max_abs_diff_per_config_sem",
                   "max_abs_diff_exact_phi", "acceptance", "delta", "eq_sweeps",
                   "sample_sweeps", "eq_msd", "min_spacing_msd", "g_contact", "g_contact_sem",
                   "g_contact_cs", "min_distance", "mc_seconds"], rows)
        if args.work:
            write_csv(work / "p0_fluid_curves.csv",
                      ["phi", "sigma", "P0", "P0_sem", "PY", "P0_minus_PY", "P0_minus_PY_sem"],
                      curves)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    for name in ("first-tap", "noise-floor", "spectral-window", "pbc-course", "integrity",
                 "realization-scatter", "packing-scatter",
                 "early-taps", "initial-packing", "p0-configs", "lateral-first-tap",
                 "ramp-levels", "ramp-pores", "theta0", "dmax", "p0-fluid", "fit-surrogates",
                 "seed-fits"):
        p = sub.add_parser(name)
        p.add_argument("--out", default=DEFAULT_OUT, type=Path)
        p.add_argument("--lmp", default=None)
    sub.choices["first-tap"].add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    sub.choices["lateral-first-tap"].add_argument("--seeds", type=int, nargs="+",
                                                  default=[1, 2, 3, 4])
    sub.choices["early-taps"].add_argument("--seeds", type=int, nargs="+",
                                           default=list(EARLY_SEEDS))
    sub.choices["early-taps"].add_argument("--taps", type=int, default=REALIZATION_TAPS)
    # one eps per process runs the realizations on several cores (each process writes the CSV
    # of its own eps: a last run without --eps, every realization done, writes them all)
    sub.choices["early-taps"].add_argument("--eps", type=float, nargs="+", default=None)
    sub.choices["early-taps"].add_argument("--work", default=None, type=Path)
    sub.choices["initial-packing"].add_argument("--seeds", type=int, nargs="+",
                                                default=list(INITIAL_SEEDS))
    for name in ("theta0", "dmax"):
        sub.choices[name].add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3, 4])
        sub.choices[name].add_argument("--N", type=int, default=THETA0_SCALE["N"])
        sub.choices[name].add_argument("--stop", choices=("change", "drift"), default="change")
        sub.choices[name].add_argument("--eta", type=float, default=1e-7)
    sub.choices["theta0"].add_argument("--theta-law", choices=("angle", "solid"),
                                       default="angle")
    sub.choices["theta0"].add_argument("--wide", action="store_true")
    for name in ("noise-floor", "p0-configs"):
        sub.choices[name].add_argument("--restart", default=CAMPAIGN_RUN / "restart.4000")
    sub.choices["p0-configs"].add_argument("--configs", type=int, default=P0_CONFIGS)
    sub.choices["p0-configs"].add_argument("--work", default=None, type=Path)
    sub.choices["fit-surrogates"].add_argument("--surrogates", type=int, default=None)
    sub.choices["fit-surrogates"].add_argument("--seed", type=int, default=1)
    for name in ("spectral-window", "pbc-course", "integrity", "early-taps", "ramp-levels",
                 "realization-scatter", "packing-scatter",
                 "ramp-pores", "fit-surrogates", "seed-fits"):
        sub.choices[name].add_argument("--campaign", default=CAMPAIGN_RUN.parents[1])
    sub.choices["packing-scatter"].add_argument("--work", default=None, type=Path)
    sub.choices["ramp-levels"].add_argument("--run", default="ramp_pbc_s1")
    sub.choices["ramp-levels"].add_argument("--levels", type=int, nargs="+", default=None)
    sub.choices["ramp-levels"].add_argument("--extend", type=int, default=RAMP_EXTEND)
    sub.choices["ramp-levels"].add_argument("--work", default=None, type=Path)
    sub.choices["ramp-levels"].add_argument("--replay", action="store_true")
    sub.choices["ramp-pores"].add_argument("--run", default="ramp_pbc_s1")
    sub.choices["ramp-pores"].add_argument("--levels", type=int, nargs="+", default=None)
    sub.choices["ramp-pores"].add_argument("--work", default=None, type=Path)
    sub.choices["ramp-pores"].add_argument("--replay", action="store_true")
    fluid = sub.choices["p0-fluid"]
    fluid.add_argument("--phi", type=float, nargs="+", default=list(P0_FLUID_PHI))
    fluid.add_argument("--configs", type=int, default=P0_FLUID_CONFIGS)
    fluid.add_argument("--cells", type=int, default=P0_FLUID_CELLS)
    fluid.add_argument("--eq-msd", type=float, default=P0_FLUID_EQ_MSD)
    fluid.add_argument("--spacing-msd", type=float, default=P0_FLUID_SPACING_MSD)
    fluid.add_argument("--max-sweeps", type=int, default=P0_FLUID_MAX_SWEEPS)
    fluid.add_argument("--seed", type=int, default=1)
    fluid.add_argument("--work", default=None, type=Path)
    fluid.add_argument("--mc", default=None)
    args = parser.parse_args(argv)
    if args.command == "early-taps":
        from tapmc.paper.claims import EARLY_DECADE

        if args.taps < EARLY_DECADE[1]:
            parser.error(f"--taps must be at least {EARLY_DECADE[1]:g} (the first decade), "
                         f"got {args.taps}")
    if args.command == "p0-fluid":
        if args.configs < 2:
            parser.error(f"--configs must be at least 2 (error bars), got {args.configs}")
        if any(not 0.01 <= p <= 0.58 for p in args.phi):
            parser.error(f"--phi values must be in [0.01, 0.58], got {args.phi}")
    {"first-tap": first_tap, "noise-floor": noise_floor,
     "spectral-window": spectral_window, "pbc-course": pbc_course, "integrity": integrity,
     "realization-scatter": realization_scatter, "packing-scatter": packing_scatter,
     "early-taps": early_taps,
     "initial-packing": initial_packing, "p0-configs": p0_configs,
     "lateral-first-tap": lateral_first_tap, "ramp-levels": ramp_levels,
     "ramp-pores": ramp_pores, "theta0": theta0_scan, "dmax": dmax_scan,
     "p0-fluid": p0_fluid, "fit-surrogates": fit_surrogates,
     "seed-fits": seed_fits}[args.command](args)


if __name__ == "__main__":
    main()
