# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""early-taps: does Phi_b compact faster per tap in the first decade than later (section
III.A: "as the packing progressively densifies, the compaction efficiency decreases"), and
are Phi_b(t) and <Z>(t) compatible with eqs. 3 and 4? One run gives neither the first decade's rate nor a fit
a trustworthy error: its taps' scatter is correlated (Fig. 3). This taps the campaign's
F.B.C. packing (its pack_seed) 400 times at each eps of Fig. 2 with Monte Carlo seeds 2-9,
as a resumable campaign in <out>/partial/early_taps/, and adds the campaign's own run (seed
1) from its taps.dat: Phi_b, <Phi^c> and <Z> at t = 0..400 per seed, whose rates and laws are
tested across realizations (early_taps.csv)."""

from __future__ import annotations

import math
from collections import defaultdict
from pathlib import Path

import numpy as np

from .._rst import list_table
from ..claims import EARLY_DECADE, back_at_start, first_decade_rates, fmt
from ..scales import FULL
from . import launch
from .common import PAPER, QuestionError, csv_schema, last_rows, taps_table, work_folder

NAME = "early-taps"
CSV = "early_taps.csv"
HEADER = ["eps", "seed", "t", "phi_b", "phi_c", "Z"]
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


def add_arguments(parser):
    parser.add_argument("--seeds", type=int, nargs="+", default=list(EARLY_SEEDS),
                        help="Monte Carlo seeds of the realizations, each tapping the "
                             "campaign's F.B.C. packing (its pack_seed 1); the campaign's own "
                             "run adds seed 1 from its taps.dat "
                             f"(default: {EARLY_SEEDS[0]} to {EARLY_SEEDS[-1]})")
    parser.add_argument("--taps", type=int, default=REALIZATION_TAPS,
                        help="taps of each realization, at least "
                             f"{EARLY_DECADE[1]:g} (the first decade) (default %(default)s)")
    parser.add_argument("--eps", type=float, nargs="+", default=None,
                        help="the eps measured (default: Fig. 2's); the CSV then holds those "
                             "only. The realizations of one --work folder run in one process "
                             "(its campaign.lock): use --jobs J for several cores")
    parser.add_argument("--work", default=None, type=Path,
                        help="the realizations' campaign folder (default OUT/partial/"
                             "early_taps)")


def check(args):
    """Refuse a --taps shorter than the first decade (the claims' rates need it)."""
    if args.taps < EARLY_DECADE[1]:
        raise QuestionError(f"--taps must be at least {EARLY_DECADE[1]:g} (the first decade), "
                            f"got {args.taps}")


def curve_rows(eps, seed, table, taps):
    """The rows of early_taps.csv of one realization, taps 0..``taps``; [] when the table
    does not reach them."""
    rows = last_rows(table)
    if not all(t in rows for t in range(taps + 1)):
        return []
    return [[eps, seed, t] + [f"{table[c][rows[t]]:.10g}" for c in ("phi_b", "phi_c", "Z")]
            for t in range(taps + 1)]


def measure(args):
    check(args)
    lmp = launch.lammps(args.lmp)
    every = math.gcd(REALIZATION_RESTART_EVERY, args.taps)
    specs = {(eps, seed): launch.spec(f"eps{eps:g}_s{seed}",
                                      dict(PAPER, bc="fbc", eps=eps, seed=seed,
                                           pack_seed=CAMPAIGN_SEED, taps=args.taps,
                                           rsteps=every))
             for eps in args.eps or FULL.fig2_eps for seed in args.seeds}
    folders = launch.run_all(work_folder(args, "early_taps"), list(specs.values()), lmp,
                             args.jobs)
    rows = []
    for eps in args.eps or FULL.fig2_eps:
        # the campaign's own run is the realization of seed 1
        own = Path(args.campaign, "runs", f"const_fbc_eps{eps:g}_s{CAMPAIGN_SEED}", "taps.dat")
        if own.is_file():
            rows += curve_rows(eps, CAMPAIGN_SEED, taps_table(own), args.taps)
        for seed in args.seeds:
            run = specs[(eps, seed)]
            table = taps_table(folders[run.name] / run.taps_file)
            rows += curve_rows(eps, seed, table, args.taps)
            print(f"eps {eps:g} seed {seed}: Phi_b {table['phi_b'][0]:.4f} -> "
                  f"{table['phi_b'][-1]:.4f} at tap {args.taps}", flush=True)
    save(args.out / CSV, rows)


save, load = csv_schema(HEADER)


def render(path):
    rows = load(path)
    if not rows:
        return []
    curves = defaultdict(dict)
    for r in rows:
        curves[float(r["eps"])].setdefault(int(r["seed"]), {})[int(r["t"])] = float(r["phi_b"])
    lines = ["Does Phi_b compact faster per tap in the first decade than later, and how far apart "
             "are realizations at its end? One run gives the first decade's rate with one "
             "tap's spread of the steady state as its error. Here the campaign's F.B.C. packing "
             "is tapped up to 400 times at each eps of Fig. 2 with more Monte Carlo seeds, the "
             "campaign's own run being one of them (``early_taps.csv``; mean ± sem over "
             "realizations; the rates from the means of the decade's halves, taps 1-5 and "
             "6-10 per tap, split at sqrt(10) per unit ln t, as the claims compute them):", ""]
    header = ["eps", "realizations", "Phi_b at t = 0", "t = 1", "t = 10", "spread at t = 10",
              "rate per tap", "rate per unit ln t", "back at the t = 0 value from tap"]
    table = []
    taps = np.arange(EARLY_DECADE[0], EARLY_DECADE[1] + 1)
    for eps in sorted(curves):
        series = [c for c in curves[eps].values() if all(k in c for k in [0, *taps])]
        if len(series) < 2:
            continue
        x = np.array([[c[k] for k in [0, *taps]] for c in series])
        t = np.array([0, *taps], dtype=float)
        rates = np.array([[v for v, _ in first_decade_rates(t, row)] for row in x])
        n = len(series)

        def mean_sem(values):
            sem = float(np.std(values, ddof=1) / math.sqrt(n))
            return float(np.mean(values)), sem if sem > 0 else None

        table.append([f"{eps:g}", n, fmt(*mean_sem(x[:, 0]), digits=5),
                      fmt(*mean_sem(x[:, 1]), digits=5), fmt(*mean_sem(x[:, -1]), digits=5),
                      fmt(float(np.std(x[:, -1], ddof=1))), fmt(*mean_sem(rates[:, 0])),
                      fmt(*mean_sem(rates[:, 1])), back_at_start_text(curves[eps])])
    return lines + list_table(header, table) + ["", "The claim on the compaction's efficiency "
                    "takes its first-decade rates from these realizations (their error over "
                    "realizations, n - 1 degrees of freedom) and its late rates from the "
                    "campaign's run (batch means). The first taps loosen the deposited "
                    "packing; the last column is the first tap at which the realizations' mean "
                    "Phi_b is back at its t = 0 value (over the taps every realization has). "
                    "Eqs. 3 and 4 are tested across the realizations that span 100 taps or "
                    "more (tapmc.laws.RealizationLawTest) from that tap on, in the claims' "
                    "table (the test from tap 1, the loosening included, shown beside it).",
                    ""]


def back_at_start_text(by_seed):
    """claims.back_at_start of the mean Phi_b over the realizations ``by_seed`` (seed ->
    {tap: Phi_b}), over the taps all of them have ("-" if never)."""
    last = min(max(c) for c in by_seed.values())
    t = np.arange(last + 1)
    if not all(all(k in c for k in t) for c in by_seed.values()):
        return "-"
    back = back_at_start(t, np.mean([[c[k] for k in t] for c in by_seed.values()], axis=0))
    return f"{back:g}" if back is not None else f"- (not by tap {last})"

