# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""ramp-pores: does nu, the mean normalised pore volume, have the reversible-irreversible
behaviour of <Phi^c> (section IV.B)? The packing at the end of every level of the ramp whose
restart file is kept (the run's folder, and the level ends of a replay in
DIR/replays/; --replay runs the ramp again up to the ends of --levels that have neither) is
dumped (a run of the campaign folder DIR/<run>_pores), and every level dumped there is
analysed as Fig. 10 analyses its run's dumps (tapmc-pores, one statistics box for all): nu
per level with the spatial jackknife over 4 x 4 lateral blocks (ramp_pores.csv, one row per
run and level: --run ramplow_pbc_s1 adds the ramp below (sqrt eps)*; a level whose packing is
gone keeps its row). DIR: --work, default OUT/partial/ramp_levels."""

from __future__ import annotations

import csv
from pathlib import Path

from tapmc.pores import jackknife_error, read_pores

from .. import _pores, _runs
from .._rst import list_table
from ..claims import fmt
from . import launch
from .common import QuestionError, QuestionRunError, read_csv, work_folder, write_csv
from .ramp_levels import BRANCH_NAMES
from .ramp_replay import (level_restarts, manifest_run, ramp_run_dir, ramp_table,
                          replay_folder, replay_ramp)

NAME = "ramp-pores"
CSV = "ramp_pores.csv"
RAMP_PORES_HEADER = ["run", "level", "branch", "sqrt_eps", "step", "nu", "nu_sem",
                     "window_top", "source"]
#: writes the packing of a restart file as the pore-dump runs write theirs (id x y z radius)
DUMP_OF_RESTART = ("read_restart ${restart}\n"
                   "write_dump all custom dump.$(step).lammpstrj id x y z radius "
                   "modify format float %.10g\n")


def add_arguments(parser):
    parser.add_argument("--run", default="ramp_pbc_s1",
                        help="the campaign's ramp run (a folder of CAMPAIGN/runs, named in its "
                             "manifest.json) whose level ends are dumped and analysed (default "
                             "%(default)s; ramplow_pbc_s1: the ramp below (sqrt eps)*)")
    parser.add_argument("--levels", type=int, nargs="+", default=None,
                        help="level indices that must be measured (in.ramp's 0 .. 3 nlev - 3): "
                             "one without a kept restart file or dump is replayed with "
                             "--replay, else an error (default: none; every level whose "
                             "packing is kept is measured anyway)")
    parser.add_argument("--work", default=None, type=Path,
                        help="folder of the ramp's replays (WORK/replays/) and of the level "
                             "dumps and their tapmc-pores outputs (WORK/<run>_pores) (default "
                             "OUT/partial/ramp_levels, shared with ramp-levels)")
    parser.add_argument("--replay", action="store_true",
                        help="run the ramp again up to the end of each of --levels without a "
                             "restart file or dump (in.ramp -var stop, in WORK/replays/)")


def dump_path(folder, k, P):
    """The dump of level k's end in the dump campaign ``folder``."""
    return Path(folder) / "runs" / f"level{k}" / f"dump.{(k + 1) * P}.lammpstrj"


def _sources(args, P, work, folder):
    """dict level -> (restart file or None, source): a dump made before (its source as the
    CSV recorded it), else a restart file at its end, the run's before a replay's."""
    recorded = {}
    if (args.out / CSV).is_file():
        recorded = {int(r["level"]): r["source"] for r in load(args.out / CSV)
                    if r.get("run") == args.run}
    run_dir = ramp_run_dir(args.campaign, args.run)
    sources = {k: (path, "replay") for k, path in
               level_restarts(replay_folder(work, args.run), P).items()}
    sources.update({k: (path, "run") for k, path in level_restarts(run_dir, P).items()})
    for path in Path(folder).glob("runs/level*/dump.*.lammpstrj"):
        step = path.name.split(".")[1]
        if step.isdigit() and int(step) % P == 0 and int(step) // P - 1 not in sources:
            sources[int(step) // P - 1] = (None, recorded.get(int(step) // P - 1, "run"))
    return sources


def _replay_missing(args, lmp, variables, seed, sources, work):
    """Levels of --levels without a packing: replayed with --replay, else QuestionError."""
    P, nlev = int(variables["P"]), int(variables["nlev"])
    last = 3 * nlev - 3
    for k in args.levels or ():
        if not 0 <= k <= last:
            raise QuestionError(f"--levels {k}: allowed levels of {args.run} are 0 .. {last}")
    missing = sorted(k for k in args.levels or () if k not in sources)
    if missing and not args.replay:
        raise QuestionError(f"no restart file at the end of levels {missing} of {args.run} "
                            "(--replay runs the ramp again up to them)")
    if missing:
        table, _ = ramp_table(ramp_run_dir(args.campaign, args.run))
        for k in missing:
            restart, _, start = replay_ramp(lmp, args.run, variables, seed, (k + 1) * P, work,
                                            table)
            sources[k] = (restart, start)
    if not sources:
        raise QuestionError(f"no level-end restart file of {args.run} in its run folder or "
                            f"{replay_folder(work, args.run)} (--levels K --replay runs the "
                            "ramp again)")


def _dumps(lmp, sources, folder, P):
    """dict level -> its dump, made from its restart file where not made before."""
    script = Path(folder) / "in.dump"
    Path(folder).mkdir(parents=True, exist_ok=True)
    script.write_text(DUMP_OF_RESTART)
    todo = [launch.spec(f"level{k}", {"restart": str(Path(restart).resolve())}, input=script)
            for k, (restart, _) in sorted(sources.items())
            if not dump_path(folder, k, P).is_file()]
    if todo:
        launch.run_all(folder, todo, lmp)
    dumps = {k: dump_path(folder, k, P) for k in sorted(sources)}
    for k, dump in dumps.items():
        if not dump.is_file():
            raise QuestionRunError(f"dumping level {k} left no {dump}")
    return dumps


def measure(args):
    variables, seed = manifest_run(args.campaign, args.run)
    ramp_run_dir(args.campaign, args.run)
    lmp = launch.lammps(args.lmp)     # after the inputs: a missing run is named first
    P, nlev = int(variables["P"]), int(variables["nlev"])
    sqrt0, dsqrt = float(variables["sqrt0"]), float(variables["dsqrt"])
    work = work_folder(args, "ramp_levels")
    folder = work / f"{args.run}_pores"
    sources = _sources(args, P, work, folder)
    _replay_missing(args, lmp, variables, seed, sources, work)
    dumps = _dumps(lmp, sources, folder, P)
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
    save(args.out / CSV, rows)


def save(path, rows):
    """ramp_pores.csv with ``rows`` and the rows (of any ramp) of the levels not in ``rows``:
    one table for every ramp measured (the one beyond (sqrt eps)* and the one below it)."""
    rows = list(rows)
    path = Path(path)
    if path.is_file():
        with open(path, newline="") as handle:
            table = list(csv.reader(handle))
        if table and table[0] == RAMP_PORES_HEADER:
            listed = {(r[0], int(r[1])) for r in rows}
            rows += [r for r in table[1:] if r and (r[0], int(r[1])) not in listed]
    return write_csv(path, RAMP_PORES_HEADER, sorted(rows, key=lambda r: (r[0], int(r[1]))))


def load(path):
    return read_csv(path)


def render(path):
    rows = load(path)
    if not rows:
        return []
    lines = ["Does nu, the mean normalised pore volume, follow <Phi^c> around the ramp (section "
             "IV.B: the same reversible-irreversible behaviour)? The packings at the level ends "
             "of the campaign's ramps (``ramp_...``: Fig. 4's, ``paperramp...``: at the paper's "
             "4000 taps per level) analysed as Fig. 10's dumps are (``ramp_pores.csv``: one "
             "packing per level, the statistics box from 2R to "
             f"{float(rows[0]['window_top']):g}R above the floor, the error the lateral "
             "jackknife over 4 x 4 blocks):", ""]
    table = []
    for r in rows:
        mark = "; replayed" if r["source"].startswith("replay") else ""
        table.append([r['run'], f"{r['level']} ({BRANCH_NAMES[int(r['branch'])]}{mark})",
                      f"{float(r['sqrt_eps']):g}", fmt(float(r['nu']), float(r['nu_sem']))])
    lines += list_table(["run", "level (branch)", "sqrt(eps)", "nu"], table)
    text = ("The levels marked replayed are the ends of a replay of the ramp (``--replay``, "
            "bit for bit the campaign's taps) where the campaign's restart file was gone; the "
            "claims table reads the signs (``nu-hysteresis``).")
    return lines + ["", text, ""]

