# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""p0-configs: are Fig. 9's comparisons (P0 of the tapped packing against the initial
packing's and against Percus-Yevick) decided once the curves carry error bars? The campaign
has one packing of each (the paper's protocol). This measures P0 as Fig. 9 does
(tapmc-pores --p0, same window and point count) on 8 depositions at t = 0 and on 8
configurations of the tapped packing: the campaign's run at eps = 0.0225 continued from its
restart.4000 at the same eps, one dump every 100 taps (taps 4100 to 4800). Mean, sem and n of
P0(sigma) for both, and the volume fraction the points see (p0_configs.csv)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from tapmc.pores import percus_yevick_p0, read_pores

from .. import _pores, _runs
from ..claims import fmt
from . import launch
from .common import PAPER, csv_schema, work_folder
from .noise_floor import NOISE_FROM_STEP, add_arguments as restart_argument, campaign_restart

NAME = "p0-configs"
CSV = "p0_configs.csv"
HEADER = ["sigma", "initial", "initial_sem", "initial_n", "tapped", "tapped_sem", "tapped_n"]
#: configurations of each packing for p0-configs: depositions, and dumps of the tapped run
P0_CONFIGS = 8
#: taps between the tapped configurations: twice the batch length of the steady state's
#: batch-means error (50 taps), beyond the correlation of successive taps
P0_CONFIG_SPACING = 100
#: eps of the continued run: that of the campaign's Fig. 9 run (CAMPAIGN_RUN)
P0_CONFIG_EPS = 0.0225

#: the tapped configurations count as independent when their P0 scatter is at least this
#: share of the independent depositions' (a smaller scatter means correlated configurations,
#: and error bars too small by about the square root of the ratio)
P0_INDEPENDENT_SHARE = 0.5


def add_arguments(parser):
    restart_argument(parser)
    parser.add_argument("--configs", type=int, default=P0_CONFIGS,
                        help="configurations of each packing: depositions at t = 0 (seeds 1 "
                             "to CONFIGS) and dumps of the tapped run, one every "
                             f"{P0_CONFIG_SPACING} taps from tap "
                             f"{NOISE_FROM_STEP + P0_CONFIG_SPACING} (default %(default)s)")
    parser.add_argument("--work", default=None, type=Path,
                        help="the runs' folder (default OUT/partial/p0_configs)")


def p0_of(dumps, seed, work):
    """P0(sigma) and the volume fraction seen by the points of each dump, measured as Fig. 9
    measures it (tapmc.paper._pores: the window from the floor + 2R to the lower of 20R and
    0.8 of the highest centre)."""
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


def deposited(lmp, work, configs, jobs):
    """The dumps of ``configs`` depositions at t = 0 (seeds 1..configs)."""
    specs = [launch.spec(f"initial_s{seed}", dict(PAPER, bc="pbc", seed=seed, taps=0, pevery=1,
                                                  rsteps=launch.NO_RESTART, dump_ends="yes"))
             for seed in range(1, configs + 1)]
    folders = launch.run_all(Path(work) / "initial", specs, lmp, jobs)
    return [folders[s.name] / "dump.0.lammpstrj" for s in specs]


def tapped(lmp, work, restart, configs):
    """The dumps of the tapped packing: the run continued from ``restart`` at its eps, one
    configuration every P0_CONFIG_SPACING taps, each link a run of its own campaign folder
    (a killed chain resumes at its last link)."""
    dumps, previous = [], restart
    for k in range(1, configs + 1):
        step = NOISE_FROM_STEP + k * P0_CONFIG_SPACING
        link = Path(work) / f"tapped_{step}"
        run = launch.spec("tapped", dict(PAPER, bc="pbc", eps=P0_CONFIG_EPS, eta=1e-7, seed=1,
                                         taps=step, rsteps=P0_CONFIG_SPACING,
                                         pevery=P0_CONFIG_SPACING, dump_ends="yes"))
        launch.start_from(link, run.name, previous)
        folder = launch.run_all(link, [run], lmp)[run.name]
        dumps.append(folder / f"dump.{step}.lammpstrj")
        previous = folder / f"restart.{step}"
        print(f"tapped configuration at tap {step}", flush=True)
    return dumps


def measure(args):
    lmp = launch.lammps(args.lmp)
    restart = campaign_restart(args.restart)
    work = work_folder(args, "p0_configs")
    curves = {"initial": p0_of(deposited(lmp, work, args.configs, args.jobs), 1, work),
              "tapped": p0_of(tapped(lmp, work, restart, args.configs), 101, work)}
    sigma = curves["initial"][0][0]
    stats = {}
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
    save(args.out / CSV, rows)


save, load = csv_schema(HEADER)


def render(path):
    rows = load(path)
    data = [r for r in rows if r["sigma"] != "phi"]
    phi = [r for r in rows if r["sigma"] == "phi"]
    if len(data) < 3 or not phi:
        return []
    col = {k: np.array([float(r[k]) for r in data]) for k in data[0]}
    n_i, n_t = int(col["initial_n"].min()), int(col["tapped_n"].min())
    # scatter of one configuration about the mean, summed over sigma, tapped over initial
    spread = {k: float(np.sqrt(np.sum((col[f"{k}_sem"] ** 2) * col[f"{k}_n"])))
              for k in ("initial", "tapped")}
    ratio = spread["tapped"] / spread["initial"] if spread["initial"] > 0 else math.nan
    p = phi[0]
    independent = ratio >= P0_INDEPENDENT_SHARE
    gap = np.abs(col["initial"] - col["tapped"])
    k = int(np.argmax(gap))
    diff = float(gap[k])
    predicted = float(np.max(np.abs(percus_yevick_p0(col["sigma"], float(p["tapped"]))
                                    - percus_yevick_p0(col["sigma"], float(p["initial"])))))
    return [f"Fig. 9's P0(sigma) with error bars (``p0_configs.csv``): {n_i} depositions at "
            f"t = 0 (Phi seen by the points {fmt(float(p['initial']), float(p['initial_sem']), True)}"
            f") and {n_t} configurations of the tapped packing, the Fig. 9 run continued at its "
            f"eps one dump every 100 taps ({fmt(float(p['tapped']), float(p['tapped_sem']), True)}"
            "). One tapped configuration scatters about the mean "
            f"{ratio:.2f} times as much as one deposition: "
            + ("the configurations are about as different as independent packings, and their "
               "sem is the error of the tapped curve." if independent else
               "the configurations are correlated; their sem underestimates the error of the "
               "tapped curve, and a disagreement found with it is not conclusive."),
            "The claims' rows of Fig. 9 compare the curves sigma by sigma with these errors "
            "(Bonferroni-corrected t over the sigma points).",
            f"The two packings' curves differ by at most {fmt(diff, None)} (sigma = "
            f"{col['sigma'][k]:.3g}); Percus-Yevick predicts a change of at most "
            f"{fmt(predicted, None)} between their Phi: the measured difference is "
            f"{100 * diff / predicted:.0f} % of it. "
            + ("The curves differ about as their packing fractions predict: at these errors "
               "the paper's 'no significant difference' does not hold; the change is small "
               "against P0 itself (a few % of it near sigma = 1), which a plot hardly shows."
               if diff >= 0.5 * predicted else
               "The curves differ much less than their packing fractions predict, as the paper "
               "says."), ""]

