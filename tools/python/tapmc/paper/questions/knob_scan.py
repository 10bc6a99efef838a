# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The knob scans of the paper's own parameters (theta0 and d_max, section II), which the
questions theta0 and dmax run: taps from the same fresh packings (P.B.C., eps = 0.0225,
N = --N at the paper's bed height) at every value of one fix mc/settle keyword, <Phi^c> at
t = 0 and over the last 10 taps per seed (<knob>[_tags].csv), and the page's table of a scan
with the claim's verdict."""

from __future__ import annotations

import csv
from collections import defaultdict
from pathlib import Path

import numpy as np

from .._rst import list_table
from ..claims import (SCANS, STATISTICS, ReportData, fmt, load_register, scan_settings,
                      scan_table, verdict)
from . import launch
from .common import PARTIAL, read_csv, work_folder, write_csv

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
#: the value that compacts most "redeposits longer" when it takes more than this factor times
#: the paper's value's sweeps per tap
SWEEPS_SHARE = 1.1


def add_arguments(parser):
    parser.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3, 4],
                        help="seeds of the scan's runs: each seed's fresh packing (the seed "
                             "deposits it and seeds the Monte Carlo redeposition) is tapped at "
                             "every value; the (seed, value) pairs the scan's CSV has are skipped "
                             "(default: %(default)s)")
    parser.add_argument("--N", type=int, default=THETA0_SCALE["N"],
                        help="spheres per run, in a P.B.C. box of side 32R sqrt(N/4096) (the "
                             "paper's bed height); another N than %(default)s adds _N<N> to "
                             "the CSV's name (default %(default)s)")
    parser.add_argument("--stop", choices=("change", "drift"), default="change",
                        help="fix mc/settle's stopping rule: change (the paper's: <Z> changes "
                             "by less than eta between two checks) or drift (<Z>'s drift per "
                             "sweep below eta <Z>; adds _drift to the CSV's name) "
                             "(default %(default)s)")
    parser.add_argument("--eta", type=float, default=1e-7,
                        help="fix mc/settle's convergence threshold eta of every run; recorded "
                             "in the CSV's eta column, not in its name (default %(default)s: "
                             "the front's reference)")


def scan_file_name(stem, stop, N, extra=()):
    """<stem>.csv for the default scan (stop change, N = 1024), else
    <stem>[_<extra>...][_<stop>][_N<N>].csv (extra: e.g. the theta law "solid", "wide")."""
    tags = (list(extra) + ([] if stop == "change" else [stop]) +
            ([] if N == THETA0_SCALE["N"] else [f"N{N}"]))
    return "_".join([stem] + tags) + ".csv"


def _scan_header(column, stem):
    return [column, stem, "seed", "N", "eps", "taps", "eta", "stop", "phi_c_0", "phi_c_end",
            "sweeps_per_tap"]


def settle_input(work, label, keys):
    """An input that sets in.constant_eps's ``settle_keys`` to ``keys`` (several words, which
    a campaign variable cannot hold) and runs it: in.constant_eps defines it as an index
    variable, which LAMMPS leaves as it is when it exists."""
    script = Path(work) / "inputs_of_values" / f"in.value_{label:.6f}"
    script.parent.mkdir(parents=True, exist_ok=True)
    script.write_text(f'variable settle_keys string "{keys}"\n'
                      f"include {launch.CONSTANT_EPS.resolve()}\n")
    return script


def box_side(N):
    """The side of the scan's P.B.C. box in R for N spheres: the paper's bed height, 32R at
    N = 4096."""
    return 32 * np.sqrt(N / 4096)


def _run_row(args, lmp, work, label, value, seed, keys):
    """The CSV row of one run of the scan (run in ``work``, or kept from before)."""
    scale = {"N": args.N, "L": box_side(args.N)}
    run = launch.spec(f"s{seed}_{label:.6f}",
                      dict(scale, bc="pbc", eps=THETA0_EPS, seed=seed, taps=THETA0_TAPS,
                           rsteps=launch.NO_RESTART, eta=args.eta),
                      input=settle_input(work, label, keys))
    taps = launch.run_one(work, run, lmp)
    phi, sweeps = taps["phi_c"], taps["sweeps"]
    last = phi[-THETA0_WINDOW:]
    return [f"{label:.6f}", repr(value), seed, args.N, THETA0_EPS, THETA0_TAPS, f"{args.eta:g}",
            args.stop, f"{phi[0]:.8f}", f"{last.mean():.8f}", f"{sweeps[1:].mean():.1f}"]


def knob_scan(args, column, values, keyword, extra_keys="", extra_tags=()):
    """Taps from the same fresh packings at every value of one fix mc/settle keyword
    (scan_file_name). Each run's row is written when it ends, and a scan started again skips
    the (seed, value) pairs its CSV already has. The rows go to <out>/partial/ while the scan
    runs and its CSV moves to <out> when every run is in, so that the report never reads half
    a scan. extra_keys are added to every run's fix mc/settle keywords (e.g. "theta_law
    solid"), extra_tags to the CSV name."""
    lmp = launch.lammps(args.lmp)
    stem = column.split("_over_")[0]
    final = Path(args.out) / scan_file_name(stem, args.stop, args.N, extra_tags)
    path = Path(args.out) / PARTIAL / final.name
    work = work_folder(args, final.stem)
    path.parent.mkdir(parents=True, exist_ok=True)
    if final.is_file() and not path.is_file():
        final.replace(path)     # more seeds for a finished scan: it is partial again meanwhile
    done = set()
    if path.is_file():
        done = {(int(r["seed"]), f"{float(r[column]):.6f}") for r in read_csv(path)}
    else:
        write_csv(path, _scan_header(column, stem), [], allow_empty=True)
    for seed in args.seeds:
        for label, value in values:
            if (seed, f"{label:.6f}") in done:
                continue
            keys = (f"{keyword} {value!r}" + (f" {extra_keys}" if extra_keys else "") +
                    (" stop drift" if args.stop == "drift" else ""))
            row = _run_row(args, lmp, work, label, value, seed, keys)
            with open(path, "a", newline="") as handle:
                csv.writer(handle).writerow(row)
            print(f"seed {seed} {column} = {label:.4f}: <Phi^c> {float(row[8]):.4f} -> "
                  f"{float(row[9]):.4f} ({float(row[10]):.0f} sweeps per tap)", flush=True)
    path.replace(final)
    print(f"wrote {final}")


#: knob -> (the question, the knob's name, the paper's value as written, the claim's statistic)
SCAN_QUESTIONS = {
    "theta0": ("Does theta0 = pi/4, the width of the trial moves' angular distribution (eq. 1), "
               "give the largest compaction rate, and does a much smaller theta0 decompact "
               "(section II)?", "theta0", "pi/4", "theta0_optimum"),
    "dmax": ("Is d_max = R/5 an intermediate value, much smaller or larger steps slowing the "
             "redeposition (section II)?", "d_max", "R/5", "dmax_intermediate"),
}


def render(path, knob):
    """One knob scan (theta0 or dmax): the table, the claim's
    verdict on it and whether the value that compacts most just redeposits longer."""
    rows = read_csv(path)
    table = scan_table(rows, knob)
    if not table:
        return []
    question, name, paper, statistic = SCAN_QUESTIONS[knob]
    first = rows[0]
    sweeps = defaultdict(list)
    for r in rows:
        sweeps[float(r[SCANS[knob]["column"]])].append(float(r["sweeps_per_tap"]))
    lines = [f"{question} {first['taps']} taps at eps = {float(first['eps']):g} from the same "
             f"fresh packings (N = {first['N']}, P.B.C., {scan_settings(rows)}) at each {name} "
             f"(``{Path(path).name}``; gain: <Phi^c> over the last 10 taps minus <Phi^c> at "
             f"t = 0, mean ± sem over seeds; against {paper}: the paired difference on the same "
             "seeds):", ""]
    lines += list_table(
        [name, "gain of <Phi^c>", f"against {paper}", "sweeps per tap"],
        [[r['name'], fmt(r['gain'], r['gain_sem'], True),
          "0" if r["is_paper"] else fmt(r['vs_paper'], r['vs_paper_sem'], True),
          f"{np.mean(sweeps[r['value']]):.0f}"] for r in table])
    claim = next(c for c in load_register() if c.statistic == statistic)
    measures = STATISTICS[statistic](ReportData({}, {}, (), {knob: [rows]}), claim)
    below = any(m.lacks for m in measures)
    text = (f"Verdict of the claim (rule {claim.rule}, t sem with {table[0]['n']} seeds): "
            + "; ".join(str(verdict(claim, m)) for m in measures)
            + (f" at N = {int(float(rows[0]['N']))}, below the paper's N (the claims' table "
               "counts it undecided there)" if below else "") + ".")
    # does the value that compacts most simply redeposit longer than the paper's?
    ref = next(r for r in table if r["is_paper"])
    best = max(table, key=lambda r: r["gain"])
    s_q, s_b = np.mean(sweeps[ref["value"]]), np.mean(sweeps[best["value"]])
    if best is not ref:
        if s_b > SWEEPS_SHARE * s_q:
            text += (f" {best['name']}, which compacts most, also takes more sweeps per tap than "
                     f"{paper} ({s_b:.0f} against {s_q:.0f}) before the stopping rule ends a "
                     f"tap: its gain mixes the effect of {name} with the redeposition's length.")
        else:
            text += (f" {best['name']}, which compacts most, takes about as many sweeps per tap "
                     f"as {paper} ({s_b:.0f} against {s_q:.0f}): its gain is the effect of "
                     f"{name} itself, not of a longer redeposition.")
    return lines + ["", text, ""]

