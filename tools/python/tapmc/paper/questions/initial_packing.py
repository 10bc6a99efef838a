# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""initial-packing: is the initial P.B.C. packing's <Phi^c> the paper's 58.4 % (section
IV.B)? The campaign starts every run from one packing (the paper's protocol); this deposits
the same packing (create_packing, N = 4096, L = 32R, P.B.C.) with seeds 1..20 and measures it
as the runs do at t = 0 (no tap): Phi_b, <Phi^c> and <Z> per seed, the spread between
depositions that one packing hides (initial_packing.csv)."""

from __future__ import annotations

import math

import numpy as np

from ..claims import fmt, load_register
from . import launch
from .common import PAPER, csv_schema, work_folder

NAME = "initial-packing"
CSV = "initial_packing.csv"
HEADER = ["seed", "N", "L", "bc", "phi_b", "phi_c", "Z"]
#: depositions measured by initial-packing: the sem of <Phi^c> over them is then about a
#: tenth of a unit of the paper's last digit (0.1 %)
INITIAL_SEEDS = tuple(range(1, 21))
#: <Phi^c> of the paper's initial P.B.C. packing (section IV.B): the register's target
PAPER_INITIAL_PHI_C = next(c.target for c in load_register() if c.id == "phi-initial")


def add_arguments(parser):
    parser.add_argument("--seeds", type=int, nargs="+", default=list(INITIAL_SEEDS),
                        help="deposition seeds: one P.B.C. packing (N = 4096, L = 32R) "
                             "deposited per seed and measured at t = 0, without a tap "
                             f"(default: {INITIAL_SEEDS[0]} to {INITIAL_SEEDS[-1]})")


def measure(args):
    lmp = launch.lammps(args.lmp)
    # taps = 0: the packing as deposited, measured by the runs' own computes
    specs = {seed: launch.spec(f"s{seed}", dict(PAPER, bc="pbc", seed=seed, taps=0, pevery=1,
                                                rsteps=launch.NO_RESTART))
             for seed in args.seeds}
    folders = launch.run_all(work_folder(args, "initial_packing"), list(specs.values()), lmp,
                             args.jobs)
    rows = []
    for seed, run in specs.items():
        t0 = launch.taps_table(folders[run.name] / run.taps_file)
        phi_b, phi_c, z = t0["phi_b"][0], t0["phi_c"][0], t0["Z"][0]
        rows.append([seed, PAPER["N"], PAPER["L"], "pbc", f"{phi_b:.8f}", f"{phi_c:.8f}",
                     f"{z:.8f}"])
        print(f"seed {seed}: Phi_b {phi_b:.4f} <Phi^c> {phi_c:.4f} <Z> {z:.3f}", flush=True)
    save(args.out / CSV, rows)


save, load = csv_schema(HEADER)


def render(path):
    rows = load(path)
    if len(rows) < 2:
        return []
    col = {k: np.array([float(r[k]) for r in rows]) for k in ("phi_b", "phi_c", "Z")}
    n = len(rows)
    sizes = sorted({(int(r["N"]), float(r["L"])) for r in rows})
    where = ", ".join(f"N = {N}, L = {L:g}R" for N, L in sizes)

    def stat(x, pct):
        sd = float(np.std(x, ddof=1))
        spread = f"{100 * sd:.2f} %" if pct else f"{sd:.3g}"
        return f"{fmt(float(np.mean(x)), sd / math.sqrt(n), pct)} (one packing spreads {spread})"

    phi = col["phi_c"]
    away = (PAPER_INITIAL_PHI_C - phi.mean()) / phi.std(ddof=1)
    return [f"The initial P.B.C. packing over {n} depositions (``initial_packing.csv``; {where}, "
            "measured as the runs measure it at t = 0): <Phi^c> = " + stat(phi, True)
            + f", range {fmt(phi.min(), None, True)} to {fmt(phi.max(), None, True)}; "
            f"Phi_b = {stat(col['phi_b'], True)}; <Z> = {stat(col['Z'], False)}. The paper's "
            f"{100 * PAPER_INITIAL_PHI_C:.1f} % is one packing's, {away:+.1f} spreads of one "
            "packing from the mean: the claim's row compares it with that prediction interval.",
            ""]

