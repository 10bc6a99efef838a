# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""ramp-levels: what do the ramp's taps per level (the campaign's 1000, the paper's 4000)
change? A finished ramp keeps its restart files at the level ends; this continues chosen
levels from them at the level's sqrt(eps) (in.constant_eps, the run's seed and eta) by
--extend taps (default 3000: 4000 in all) and compares <Phi^c> over the level's last quarter
with that over the last quarter of the longer level (batch-means errors). Default levels: two
of every branch (a quarter of the way up the first increase and its top, the middle and the
bottom of the decrease, the middle and the top of the second increase). The continuations
are runs of one campaign folder, --work DIR (default OUT/partial/ramp_levels), with restart
files every 50 taps: a killed ramp-levels resumes there, and a larger --extend continues a
level. The rows of ramp_levels.csv for levels not listed are kept (a level measured in an
earlier session whose restart file is gone stays in the table). --replay: a level whose
restart file is gone starts from a replay of the ramp up to its end (in.ramp -var stop,
DIR/replays/, a restart file at every level end); its rows are compared with the campaign's
(column start: run, replay (identical) or replay (differs from step S)). Column ramp: the run
(--run); --run ramplow_pbc_s1 measures the ramp below (sqrt eps)*, whose turning level and
decrease bound its "nearly frozen" claim (ramp_levels.csv)."""

from __future__ import annotations

import csv
import math
from collections import defaultdict
from pathlib import Path

import numpy as np

from tapmc.fluctuations import SteadyState
from tapmc.stats import beyond

from .._rst import list_table
from .._steady_state import steady_last
from ..claims import RAMP_LEVELS_DEFAULT_RUN, ReportData, fmt, hysteresis_gap
from . import launch
from .common import QuestionError, last_rows, read_csv, work_folder, write_csv
from .pbc_course import HALVES_DOF
from .ramp_replay import manifest_run, ramp_run_dir, ramp_table, replay_ramp

NAME = "ramp-levels"
CSV = "ramp_levels.csv"
#: taps added to a continued ramp level: the campaign's 1000 + 3000 = the paper's 4000
RAMP_EXTEND = 3000
#: taps between the restart files of a continuation (a killed ramp-levels resumes from them)
RESTART_EVERY = 50
RAMP_LEVELS_HEADER = ["level", "branch", "sqrt_eps", "taps", "taps_long", "phi_c", "phi_c_sem",
                      "phi_c_long", "phi_c_long_sem", "start", "ramp"]
#: what the columns added to ramp_levels.csv hold in rows written before them: the levels
#: came from the run itself, of the ramp beyond (sqrt eps)* (tapmc.paper.claims)
RAMP_LEVELS_LATER_COLUMNS = {"start": "run", "ramp": RAMP_LEVELS_DEFAULT_RUN}
BRANCH_NAMES = ("first increase", "decrease", "second increase")
#: taps per level of the paper's ramp (section III.B, Fig. 4)
PAPER_RAMP_TAPS = 4000
#: a level's shift is "small" below this share of the hysteresis gap
GAP_SHARE = 0.1


def add_arguments(parser):
    parser.add_argument("--run", default="ramp_pbc_s1",
                        help="the campaign's ramp run (a folder of CAMPAIGN/runs, named in its "
                             "manifest.json) whose levels are continued (default %(default)s; "
                             "ramplow_pbc_s1: the ramp below (sqrt eps)*)")
    parser.add_argument("--levels", type=int, nargs="+", default=None,
                        help="level indices of the ramp continued (in.ramp's 0 .. 3 nlev - 3; "
                             "default: two of every branch, as above)")
    parser.add_argument("--extend", type=int, default=RAMP_EXTEND,
                        help="taps added to each level from its end, at its sqrt(eps); a "
                             "larger value continues a level measured before (default "
                             "%(default)s: the campaign's 1000 taps per level become the "
                             "paper's 4000)")
    parser.add_argument("--work", default=None, type=Path,
                        help="campaign folder of the level continuations and of the ramp's "
                             "replays, WORK/replays/ (default OUT/partial/ramp_levels)")
    parser.add_argument("--replay", action="store_true",
                        help="a level whose restart file the run no longer has starts from a "
                             "replay of the ramp up to the level's end (in.ramp -var stop, "
                             "in WORK/replays/); without it such a level is an error")


def default_ramp_levels(nlev):
    """Two levels of every branch, as the report needs to bound the branch's shift
    (tapmc.paper.claims.RAMP_REDUCTION_MIN_LEVELS): a quarter of the way up the first
    increase and its top, the middle and the bottom of the decrease, the middle and the top
    of the second increase (level indices of in.ramp: 0 .. 3 nlev - 3)."""
    top = nlev - 1
    half = (nlev - 1) // 2
    return sorted({top // 4, top, top + half, 2 * top, 2 * top + half, 3 * top})


def _level_start(args, lmp, variables, seed, k, data, work):
    """(restart file at level k's end, its rows, start) from the run, or from a replay."""
    P = int(variables["P"])
    end = (k + 1) * P
    restart = ramp_run_dir(args.campaign, args.run) / f"restart.{end}"
    if restart.is_file():
        return restart, data[(data[:, 0] > end - P) & (data[:, 0] <= end)], "run"
    if not args.replay:
        raise QuestionError(f"{restart} not found (a finished ramp keeps the restart files of "
                            "its level ends; an unfinished one has them up to its last step; "
                            "--replay runs the ramp again up to the level's end)")
    restart, replayed, start = replay_ramp(lmp, args.run, variables, seed, end, work, data)
    return restart, replayed[replayed[:, 0] > end - P], start


def _continue_level(args, lmp, variables, seed, k, restart, sq, work):
    """<Phi^c> of level k continued from its end by --extend taps (a run of ``work``)."""
    end = (int(variables["P"])) * (k + 1)
    size = {key: variables[key] for key in ("N", "L", "eta", "bc") if key in variables}
    taps = end + args.extend
    run = launch.spec(f"{args.run}_level{k}",
                      dict(size, sqrteps=sq, seed=seed, pevery=taps, taps=taps,
                           rsteps=math.gcd(RESTART_EVERY, taps)))
    launch.reopen_if_shorter(work, run.name, taps)
    launch.start_from(work, run.name, restart)
    table = launch.run_one(work, run, lmp)
    rows = last_rows(table)     # a resumed continuation prints its restart step again
    return np.array([table["phi_c"][rows[t]] for t in sorted(rows) if t > end])


def measure(args):
    variables, seed = manifest_run(args.campaign, args.run)
    P, nlev = int(variables["P"]), int(variables["nlev"])
    data, _ = ramp_table(ramp_run_dir(args.campaign, args.run))
    lmp = launch.lammps(args.lmp)     # after the inputs: a missing run is named first
    work = work_folder(args, "ramp_levels")
    rows = []
    for k in args.levels or default_ramp_levels(nlev):
        restart, level, start = _level_start(args, lmp, variables, seed, k, data, work)
        # the level's sqrt(eps); a row of a resume step may print 0 (_runs.ramp_sqrt_eps)
        sq = float(np.median(level[level[:, 3] > 0, 3]))
        more = _continue_level(args, lmp, variables, seed, k, restart, sq, work)
        longer = np.concatenate([level[:, 5], more])
        short = SteadyState(level[:, 5], last=steady_last(P)).compute()
        full = SteadyState(longer, last=steady_last(len(longer))).compute()
        rows.append([k, int(level[-1, 2]), f"{sq:.6g}", P, len(longer), f"{short.mean:.8f}",
                     f"{short.sem:.3g}", f"{full.mean:.8f}", f"{full.sem:.3g}", start,
                     args.run])
        print(f"level {k} (branch {int(level[-1, 2])}, sqrt(eps) {sq:g}, from the {start}): "
              f"<Phi^c> {short.mean:.4f} after {P} taps, {full.mean:.4f} after {len(longer)}",
              flush=True)
        # after every level: a session that ends before the last level keeps the others
        save(args.out / CSV, rows)


def save(path, rows):
    """ramp_levels.csv with ``rows`` and the rows of the (ramp, level) pairs measured before
    and not in ``rows``."""
    header = RAMP_LEVELS_HEADER
    path = Path(path)
    rows = list(rows)
    if path.is_file():
        with open(path, newline="") as handle:
            table = list(csv.reader(handle))
        if table and table[0] == header[:len(table[0])]:
            missing = [RAMP_LEVELS_LATER_COLUMNS[c] for c in header[len(table[0]):]]
            listed = {(r[-1], int(r[0])) for r in rows}
            old = [r + missing for r in table[1:] if r]
            rows += [r for r in old if (r[-1], int(r[0])) not in listed]
    return write_csv(path, header, sorted(rows, key=lambda r: (r[-1], int(r[0]))))


def load(path):
    return read_csv(path)


def render(path, fig4=None, factors=None):
    """``factors``: as in :func:`_pbc_course`; a level's shift compares two windows of one
    run, so its error takes the factor of <Phi^c>'s halves."""
    rows = load(path)
    k = (factors or {}).get("phi_c:halves", (1.0, None))[0]
    if not rows:
        return []
    taps, longer = int(rows[0]["taps"]), int(rows[0]["taps_long"])
    paper = " (the paper's)" if longer == PAPER_RAMP_TAPS else ""
    lines = [f"What do the ramp's {taps} taps per level change against {longer}{paper}? "
             f"Levels of the campaign's ramp continued from their end at the same sqrt(eps) to "
             f"{longer} taps (``ramp_levels.csv``; <Phi^c> over the last quarter of the level, "
             "batch-means errors" + (f"; the shift's error times {k:.1f}, the realizations' "
                                     "factor of a difference of two windows of one run "
                                     "(realization-scatter)" if k != 1.0 else "") + "):", ""]
    header = ["ramp", "level (branch)", "sqrt(eps)", f"after {taps} taps",
              f"after {longer} taps", "shift"]
    cells = []
    shifts = defaultdict(list)
    for r in rows:
        ramp = r.get("ramp") or RAMP_LEVELS_DEFAULT_RUN
        a, ea = float(r["phi_c"]), float(r["phi_c_sem"])
        b, eb = float(r["phi_c_long"]), float(r["phi_c_long_sem"])
        shifts[ramp].append((b - a, k * math.hypot(ea, eb)))
        start = r.get("start") or "run"
        mark = "; replayed" if start.startswith("replay") else ""
        cells.append([ramp, f"{r['level']} ({BRANCH_NAMES[int(r['branch'])]}{mark})",
                      f"{float(r['sqrt_eps']):g}", fmt(a, ea, True), fmt(b, eb, True),
                      fmt(*shifts[ramp][-1], True)])
    lines += list_table(header, cells)
    gap = None if fig4 is None else hysteresis_gap(ReportData({}, {"fig4": fig4}))
    texts = []
    for ramp, moves in shifts.items():
        largest = max(moves, key=lambda d: abs(d[0]))
        moved = [d for d in moves if beyond(d[0], d[1], HALVES_DOF)]
        texts.append(f"{ramp}: the longer levels move <Phi^c> by at most "
                     f"{fmt(largest[0], largest[1], True)}; {len(moved)} of {len(moves)} beyond "
                     "their error")
    largest = max(shifts.get(RAMP_LEVELS_DEFAULT_RUN) or [(0.0, 0.0)], key=lambda d: abs(d[0]))
    text = "; ".join(texts) + "."
    replays = sorted({(r.get("start") or "run")[len("replay ("):-1] for r in rows
                      if (r.get("start") or "").startswith("replay")})
    if replays:
        text += (" The levels marked replayed start from the ramp run again up to their end "
                 "(``--replay``: the campaign's restart file of that level end was gone); the "
                 "replay's taps against the campaign's: " + ", ".join(replays) + ".")
    if gap is not None:
        text += (f" The hysteresis gap of {RAMP_LEVELS_DEFAULT_RUN} (decrease minus first "
                 f"increase) is {fmt(gap, None, True)}: its shorter levels "
                 + ("change the branches by less than a tenth of it." if abs(largest[0])
                    < GAP_SHARE * abs(gap) else f"shift a level by {abs(largest[0] / gap):.0%} of it."))
    return lines + ["", text, ""]

