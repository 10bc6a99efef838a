# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""lateral-first-tap: does the first tap compact the lateral zone of the paper's F.B.C. start
(section IV.A, Fig. 8: delta Phi_lateral jumps at t = 1)? The campaign's F.B.C. runs start
from packings deposited between the walls; this builds the paper's start (periodic
deposition, walls, slight agitation: in.constant_eps fbc_start = paper) at N = 4096, L = 32R
for seeds 1-4 and taps it 5 times at each eps of Fig. 8 (0.005, 0.02, 0.05, 0.1): the lateral
and central zone means at t = 0..5 (lateral_first_tap.csv)."""

from __future__ import annotations

import math
from collections import defaultdict

import numpy as np

from .._rst import list_table
from ..claims import fmt
from . import launch
from .common import PAPER, csv_schema, work_folder

NAME = "lateral-first-tap"
CSV = "lateral_first_tap.csv"
HEADER = ["eps", "seed", "t", "lateral", "central", "phi_c"]
#: Fig. 8's eps (the full scale's profile_eps) and the taps run from the paper's F.B.C. start
LATERAL_EPS = (0.005, 0.02, 0.05, 0.1)
LATERAL_TAPS = 5


def add_arguments(parser):
    parser.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3, 4],
                        help="seeds of the paper's F.B.C. starts (the seed deposits the packing"
                             " and seeds the Monte Carlo redeposition), each tapped "
                             f"{LATERAL_TAPS} times at each eps of Fig. 8 "
                             "(default: %(default)s)")


def measure(args):
    lmp = launch.lammps(args.lmp)
    specs = {(eps, seed): launch.spec(f"eps{eps:g}_s{seed}",
                                      dict(PAPER, bc="fbc", fbc_start="paper", eps=eps,
                                           seed=seed, taps=LATERAL_TAPS,
                                           rsteps=launch.NO_RESTART))
             for eps in LATERAL_EPS for seed in args.seeds}
    folders = launch.run_all(work_folder(args, "lateral_first_tap"), list(specs.values()), lmp,
                             args.jobs)
    rows = []
    for (eps, seed), run in specs.items():
        taps = launch.taps_table(folders[run.name] / run.taps_file)
        lateral, central = taps["lateral"], taps["central"]
        rows += [[eps, seed, int(step), f"{lat:.8f}", f"{cen:.8f}", f"{phi:.8f}"]
                 for step, lat, cen, phi in zip(taps["step"], lateral, central, taps["phi_c"])]
        print(f"eps {eps:g} seed {seed}: delta Phi_lateral at t = 1: "
              f"{lateral[1] - lateral[0]:+.4f}, central {central[1] - central[0]:+.4f}",
              flush=True)
    save(args.out / CSV, rows)


save, load = csv_schema(HEADER)


def render(path, fig8=None):
    rows = load(path)
    per = defaultdict(lambda: defaultdict(dict))
    for r in rows:
        per[float(r["eps"])][int(r["seed"])][int(r["t"])] = (float(r["lateral"]),
                                                             float(r["central"]))
    if not per:
        return []
    last = min(max(t) for seeds in per.values() for t in seeds.values())
    lines = ["Does the first tap compact the lateral zone of the paper's F.B.C. start (Fig. 8)? "
             "The campaign's F.B.C. runs start from packings deposited between the walls; the "
             "paper's start (periodic deposition, then the walls and a slight agitation) tapped "
             f"{last} times at each eps (``lateral_first_tap.csv``; delta Phi against t = 0, "
             "mean ± sem over seeds):", ""]
    table = []

    def stat(values):
        v = np.asarray(values)
        return fmt(float(v.mean()), float(v.std(ddof=1) / math.sqrt(len(v)))
                   if len(v) > 1 else None)

    looser = float(np.mean([t[0][1] - t[0][0] for seeds in per.values()
                            for t in seeds.values()]))
    jumps, more = {}, True
    for eps, seeds in sorted(per.items()):
        lat1 = [t[1][0] - t[0][0] for t in seeds.values()]
        jumps[eps] = float(np.mean(lat1))
        more &= jumps[eps] > float(np.mean([t[1][1] - t[0][1] for t in seeds.values()]))
        table.append([f"{eps:g}", len(seeds), stat(lat1),
                      stat([t[1][1] - t[0][1] for t in seeds.values()]),
                      stat([t[last][0] - t[0][0] for t in seeds.values()])])
    lines += list_table(["eps", "seeds", "delta Phi_lateral, t = 1", "delta Phi_central, t = 1",
                         f"delta Phi_lateral, t = {last}"], table)
    walls = []
    if fig8 is not None:
        for s in fig8.series("a"):
            if s.startswith("eps="):
                t, mean, _, _ = fig8.get("a", s)
                if np.any(t == 1):
                    walls.append(f"{mean[t == 1][0]:+.4f} at eps = {s.split('=')[1]}")
    lines += ["", "From the paper's start the lateral zone "
              + ("gains at the first tap at every eps" if all(j > 0 for j in jumps.values())
                 else "does not gain at the first tap at every eps")
              + (", more than the central zone" if more else ", not more than the central zone")
              + (f" (at t = 0 it is looser than the central zone by {fmt(looser, None, True)}: "
                 "the start's walls are under-populated)" if looser > 0 else "")
              + (f"; from the start deposited between the walls it changes by "
                 f"{', '.join(walls)} instead" if walls else "") + ".", ""]
    return lines

