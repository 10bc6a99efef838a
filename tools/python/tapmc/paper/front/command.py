# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""``tapmc-paper front``: the run-time-versus-error front of the redeposition.

``tapmc-paper front [page] [--root DIR]`` writes doc/front.rst, its figures and
front_summary.csv from the committed runs (doc/validation/front); ``tapmc-paper front run
[--N 1024] [--seeds 4] [--jobs 2] ...`` runs the runs still missing from runs.csv, through
tapmc.campaign (resumable: a killed front resumes every run from its latest restart file).

Exit status: 0 on success; 1 when a run failed (the message names the run and its log);
2 on a usage error or a damaged or missing file (one line naming the file, and the line,
and what is wrong; no file of the front is written then); 3 when stopped by Ctrl-C (the
unfinished runs resume from their restart files at the next call).
"""

import argparse
import os
import sys

from ...campaign import STOPPED_STATUS, CampaignDirectoryError, CampaignError, CampaignStopped
from ...readers import TapmcFormatError
from .._runs import SOURCE_DIR
from . import data, page, runs
from .settings import EPS, SETTINGS, TAPS

#: the smallest N the front runs (the box side 32R sqrt(N / 4096) is 4R at N = 64)
MIN_N = 64
STOPPED = STOPPED_STATUS


def add_parser(sub):
    """Add the ``front`` command (and its ``run`` and ``page`` actions) to `sub`."""
    fr = sub.add_parser("front", help="the run-time-versus-error front of the redeposition: "
                        "'front run' runs it (resumable), 'front' or 'front page' writes "
                        "doc/front.rst from its runs",
                        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    root_help = ("repository whose doc/validation/front is read and whose doc/front.rst, figure "
                 "and tools/python/tapmc/paper/front_summary.csv are written (default: this "
                 "package's source tree; for an installed tapmc-paper, the current directory)")
    fr.add_argument("--root", type=os.path.abspath, default=None, metavar="DIR", help=root_help)
    actions = fr.add_subparsers(dest="front_action", metavar="{run,page}")
    pg = actions.add_parser("page", help="write doc/front.rst, its figures and "
                            "front_summary.csv from the runs (the default action)")
    pg.add_argument("--root", dest="page_root", type=os.path.abspath, default=None,
                    metavar="DIR", help=root_help)
    run = actions.add_parser("run", help="run the front's missing runs (resumable)")
    run.add_argument("--lmp", default=None, help="LAMMPS executable (default: $TAPMC_LMP, "
                     "build/lmp_tapmc or lmp_tapmc on the PATH)")
    run.add_argument("--N", type=int, default=1024, help="spheres (box side 32R sqrt(N/4096); "
                     "default %(default)s)")
    run.add_argument("--taps", type=int, default=TAPS, help="taps per run (default %(default)s)")
    run.add_argument("--seeds", type=int, default=4, help="seeds per setting (default 4)")
    run.add_argument("--eps", default=",".join("%g" % e for e in EPS),
                     help="comma list of tap strengths (default %(default)s)")
    run.add_argument("--settings", default="all",
                     help="comma list among %s, or all" % ", ".join(SETTINGS))
    run.add_argument("--jobs", type=int, default=1, help="runs at once (default 1)")
    run.add_argument("--nice", type=int, default=0, help="nice level of this command and its "
                     "lmp processes (default 0)")
    run.add_argument("--out", default=os.path.join(SOURCE_DIR, data.DATA_DIR),
                     help="the front's folder (default doc/validation/front)")
    run.add_argument("--list", action="store_true", help="print the runs still to do and stop")
    fr.set_defaults(front_parser=fr, run_parser=run)
    return fr


def _run_arguments(args):
    """(setting names, eps values) of ``front run``; argparse's error (exit 2) when wrong."""
    ap = args.run_parser
    names = list(SETTINGS) if args.settings == "all" else args.settings.split(",")
    bad = [n for n in names if n not in SETTINGS]
    if bad:
        ap.error("--settings: unknown %s (allowed: %s, all)" % (",".join(bad), ", ".join(SETTINGS)))
    try:
        eps_list = [float(e) for e in args.eps.split(",")]
    except ValueError:
        ap.error("--eps %r: expected a comma list of numbers" % args.eps)
    if args.N < MIN_N or args.taps < 1 or args.seeds < 1 or args.jobs < 1:
        ap.error("--N >= %d, --taps >= 1, --seeds >= 1 and --jobs >= 1 (got %d, %d, %d, %d)"
                 % (MIN_N, args.N, args.taps, args.seeds, args.jobs))
    if any(not 0 < e < 1 for e in eps_list):
        ap.error("--eps values must be in (0, 1), got %s" % args.eps)
    if args.nice < 0:
        ap.error("--nice must be >= 0, got %d" % args.nice)
    return names, eps_list


def _run(args):
    names, eps_list = _run_arguments(args)
    out = os.path.abspath(args.out)
    todo, done = runs.runs_to_do(out, args.N, args.taps, args.seeds, eps_list, names)
    print("front run: %d runs to do (N %d, %d taps, eps %s), %d done; out %s"
          % (len(todo), args.N, args.taps, args.eps, done, out), flush=True)
    if args.list:
        for run in todo:
            print("  %s N %d eps %g seed %d" % (run.setting, run.N, run.eps, run.seed))
        return 0
    if not todo:
        return 0
    if args.nice:
        os.nice(args.nice)  # the lmp processes inherit it
    try:
        rows = runs.run_front(out, todo, lmp=args.lmp, jobs=args.jobs, nice=args.nice)
    except CampaignStopped as err:
        print(f"tapmc-paper front run: {err}", file=sys.stderr)
        return STOPPED
    except KeyboardInterrupt:
        print("front run: stopped; the unfinished runs resume from their restart files at the "
              "next call", file=sys.stderr)
        return STOPPED
    except CampaignError as err:
        print(f"tapmc-paper front run: {err}", file=sys.stderr)
        return 1
    print("front run: %d runs added to %s" % (len(rows), os.path.join(out, data.RUNS_CSV)))
    return 0


def _page(args):
    root = getattr(args, "page_root", None) or args.root or str(SOURCE_DIR)
    print(f"front: {page.write_page(root)}")
    return 0


def main(args):
    """Run the ``front`` command of parsed `args`; returns the exit status."""
    try:
        return _run(args) if args.front_action == "run" else _page(args)
    except (data.FrontDataError, TapmcFormatError, CampaignDirectoryError,
            FileNotFoundError) as err:
        print(f"tapmc-paper front: {err}", file=sys.stderr)
        return 2
    except OSError as err:
        where = f"{err.filename}: " if err.filename else ""
        print(f"tapmc-paper front: {where}{err.strerror or err}", file=sys.stderr)
        return 2
