# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The ``tapmc-paper`` command: one subcommand per figure of the paper, and ``report``.

``tapmc-paper figN [--quick|--medium|--full] [--seeds K] [--jobs J] [--campaign DIR] [--out DIR]``
builds the runs of Fig. N at the chosen scale (:mod:`tapmc.paper.scales`), runs the missing
ones in the campaign folder (:class:`tapmc.campaign.Campaign`: resumable, shared by all
figures, so runs common to several figures run once) and draws the PNG and the CSV of every
plotted number into the output folder. ``tapmc-paper report`` does this for every figure and
writes the validation report (``tapmc.paper.validation``). ``tapmc-paper question NAME`` runs
one question of the validation settled by a measurement (``tapmc.paper.questions``).

Exit status: 0 on success, 1 when a run failed (the message names the run and its log) or,
with ``report --finished-only``, a finished run's outputs changed since it finished, 2 on a
usage error, a figure that this installation does not provide, or a path that cannot be
used (a campaign folder that is not a directory, cannot be created, read or written, has a
damaged manifest or one of another format, or was made with another Scale; an ``--out`` that
cannot be created or written), or a damaged input (a DONE.json, a per-tap file, report.json
or a figure CSV): one line naming the path (and line) and what is wrong, no traceback.
"""

from __future__ import annotations

import argparse
import importlib
import json
import sys
import tempfile
from pathlib import Path

from tapmc.campaign import (STOPPED_STATUS, Campaign, CampaignDirectoryError, CampaignError,
                            CampaignStopped, launch, provenance)
from tapmc.campaign.repair import first_steps
from tapmc.campaign.run_folder import resume_restart, step_rows_problem
from tapmc.readers import TapmcFormatError

from .. import __version__
from . import FIGURES, _runs, cost, paper_ramp, paper_ramp_figure, plan, sigma_eta
from ._arguments import folder, positive_int
from .front import command as front_command
from .plan import TIERS
from .scales import FBC_STARTS, get_scale

try:
    from .questions import command as question_command
    QUESTIONS_MISSING = None
except ImportError as err:  # a question reads a figure module this installation lacks
    question_command, QUESTIONS_MISSING = None, str(err)


class FigureUnavailable(RuntimeError):
    """A figure module (tapmc.paper.figN) is missing or lacks runs()/draw()."""


def load_validation():
    """The module ``tapmc.paper.validation`` (the report), loaded like a figure module: it
    reads the figure modules, which an installation may lack; FigureUnavailable if it is not
    installed."""
    modname = f"{__package__}.validation"
    try:
        return importlib.import_module(modname)
    except ModuleNotFoundError as err:
        if err.name != modname:
            raise
        raise FigureUnavailable("report: the module tapmc.paper.validation is not installed in "
                                "this TAPMC") from None


def load_figure(name):
    """The module ``tapmc.paper.<name>``; FigureUnavailable with a clear message if this
    installation does not have it (or it lacks ``runs`` and ``draw``)."""
    if name not in FIGURES:
        raise FigureUnavailable(f"figure {name!r}: allowed values are {', '.join(FIGURES)}")
    modname = f"{__package__}.{name}"
    try:
        module = importlib.import_module(modname)
    except ModuleNotFoundError as err:
        if err.name != modname:
            raise  # the figure module exists but one of its own imports is missing
        raise FigureUnavailable(
            f"{name}: the figure module {modname} is not installed in this TAPMC "
            f"(looked in {Path(__file__).parent}); available figures: "
            f"{', '.join(available_figures()) or 'none'}") from None
    for attr in ("runs", "draw"):
        if not callable(getattr(module, attr, None)):
            raise FigureUnavailable(f"{name}: module {modname} has no {attr}() function "
                                    "(a figure module needs runs(scale, seeds) and "
                                    "draw(campaign, out_dir))")
    return module


def available_figures():
    """Figure subcommands whose module file is present."""
    here = Path(__file__).parent
    return [f for f in FIGURES if (here / f"{f}.py").exists()]


def _add_scale_options(p):
    """The options every figure and report command shares: scale, seeds, jobs, folders,
    launcher."""
    size = p.add_mutually_exclusive_group()
    size.add_argument("--quick", dest="scale", action="store_const", const="quick",
                      help="small packings and few taps, about a minute per figure on "
                           "2 cores (the default)")
    size.add_argument("--medium", dest="scale", action="store_const", const="medium",
                      help="N = 1024, L = 16R, 1000 taps, 2 seeds: about 25 minutes for "
                           "every figure on 2 cores (the smoke test doc/validation.rst)")
    size.add_argument("--full", dest="scale", action="store_const", const="full",
                      help="the paper's scale: N = 4096, L = 32R, 4000 taps, 10 seeds "
                           "(hours to days)")
    p.set_defaults(scale="quick")
    p.add_argument("--fbc-start", choices=FBC_STARTS, default=None,
                   help="F.B.C. initial packing of the constant-eps runs (Figs. 2, 6-8): "
                        "walls (deposited between the walls, the default) or paper (the "
                        "paper's periodic deposition adapted to the walls by a slight "
                        "agitation, section IV.A); default campaign folder "
                        "./tapmc-paper-SCALE-fbc-paper")
    p.add_argument("--seeds", type=positive_int, default=None, metavar="K",
                   help="number of seeds (realizations) per point; default: the scale's")
    p.add_argument("--out", type=folder, default=None, metavar="DIR",
                   help="where PNG and CSV files go (default: CAMPAIGN/figures)")
    _add_run_options(p, "campaign folder, shared by the figures and resumable (default: "
                        "./tapmc-paper-SCALE)")


def _add_run_options(p, campaign_help):
    """The options of every command that runs a campaign: jobs, folder, launcher."""
    p.add_argument("--jobs", type=positive_int, default=None, metavar="J",
                   help="runs at a time (default: the cores this process may use)")
    p.add_argument("--campaign", type=folder, default=None, metavar="DIR", help=campaign_help)
    p.add_argument("--mode", choices=("pool", "partition"), default="pool",
                   help="pool: a process pool on this machine; partition: LAMMPS "
                        "-partition under mpirun (multi-node)")
    p.add_argument("--lmp", type=Path, default=None, metavar="EXE",
                   help="LAMMPS executable (default: $TAPMC_LMP, build/lmp_tapmc)")
    p.add_argument("--dry-run", action="store_true",
                   help="list the runs and exit without running anything")
    p.add_argument("--quiet", action="store_true", help="no progress report")


def build_parser():
    parser = argparse.ArgumentParser(
        prog="tapmc-paper",
        description="Reproduce the figures of Philippe & Bideau (tapping model): run the "
                    "paper's protocols as a resumable campaign of LAMMPS runs, then draw each "
                    "figure as a PNG with a CSV of every plotted number.",
        epilog="Example: tapmc-paper fig2 --quick --jobs 2   (writes tapmc-paper-quick/"
               "figures/fig2.png and fig2.csv)")
    parser.add_argument("--version", action="version", version=f"tapmc-paper {__version__}",
                        help="print the version of TAPMC (of the tapmc package that runs) and exit")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True

    for fig in FIGURES:
        _add_scale_options(sub.add_parser(fig, help=f"Fig. {fig[3:]} of the paper"))
    _add_report_parser(sub)
    _add_campaign_and_plan_parsers(sub)
    front_command.add_parser(sub)
    _add_paper_ramp_and_question_parsers(sub)
    return parser


def _add_report_parser(sub):
    """``report``: every figure, then the validation page."""
    report = sub.add_parser("report", help="every figure, then the validation report")
    _add_scale_options(report)
    report.add_argument("--from-data", action="store_true",
                        help="rewrite OUT/validation.rst and its appendix pages "
                             "(OUT/validation_*.rst) from the figure CSVs and report.json "
                             "already in OUT/validation (default OUT: the source tree's doc/, "
                             "the current directory's for an installed tapmc-paper); "
                             "nothing is run or drawn")
    report.add_argument("--refit", action="store_true",
                        help="with --from-data: first recompute the statistics that a figure "
                             "module can compute from its CSV's curves (Fig. 2's fit "
                             "intervals, range refits and ln B; Fig. 4's bell maximum; Fig. "
                             "5's collapse), rewriting those CSVs")
    report.add_argument("--readme", type=Path, metavar="README",
                        help="also write the section 'What the validation found' of README "
                             "(the repository's README.md) from the page written to OUT: the "
                             "counts, the central question's answer, the open questions")
    report.add_argument("--redraw", action="store_true",
                        help="with --from-data: first draw every figure's PNG again from its "
                             "committed CSV (its typed result) and report.json, after a change "
                             "of drawing alone; no CSV is written")
    report.add_argument("--finished-only", action="store_true",
                        help="draw the figures and the report from the campaign's finished "
                             "runs only, running nothing (a campaign under way); figures "
                             "without their runs are left out and their claims undecided")


def _add_campaign_and_plan_parsers(sub):
    """``campaign`` (the paper-scale plan's runs) and ``plan`` (their CPU time first)."""
    plan = sub.add_parser("campaign", help="run the paper-scale campaign (tapmc.paper.plan) "
                                           "up to a tier, without drawing")
    plan.add_argument("--full", dest="scale", action="store_const", const="full",
                      help="the paper's scale, the only one of the plan (may be left out)")
    plan.set_defaults(scale="full")
    _add_run_options(plan, "campaign folder, resumable (default: ./tapmc-paper-full)")
    plan.add_argument("--tier", type=int, choices=TIERS, default=1,
                      help="run tiers 1 .. TIER of the plan (default 1: the paper's one run "
                           "per point)")
    plan.add_argument("--first", nargs="+", default=(), metavar="PATTERN",
                      help="run the runs whose names match these shell-style patterns first "
                           "(e.g. 'ageing_*'), in the patterns' order, then the rest in the "
                           "plan's order")
    cp = sub.add_parser("plan", help="the CPU time of runs before they run (the cost rule of "
                                     "tapmc.paper.cost, from the front's measurements)")
    cp.add_argument("--N", type=positive_int, required=True, help="spheres per run")
    cp.add_argument("--taps", type=positive_int, required=True, help="taps per run")
    cp.add_argument("--eps", type=float, nargs="+", required=True, metavar="EPS",
                    help="tap strengths (eps, not sqrt(eps)); one row each")
    cp.add_argument("--setting", nargs="+", default=None, metavar="NAME",
                    help="purposes (publication, exploration, smoke: the setting doc/front.rst "
                         "recommends for each at the nearest N measured) or fix mc/settle "
                         "settings ('change 1e-6', 'drift 1e-7'); default: the three purposes")
    cp.add_argument("--seeds", type=positive_int, default=1, metavar="K",
                    help="runs (seeds) per eps and setting (default 1)")
    cp.add_argument("--jobs", type=positive_int, default=None, metavar="J",
                    help="runs at a time, for the wall time (default: the cores this process may use)")


def _add_campaign_reader(sub, name, what, runs, csv_name):
    """A command that reads a campaign's runs (finished or not) into one CSV of the report's
    questions folder."""
    parser = sub.add_parser(name, help=f"{what}, written to the report's questions/{csv_name}")
    parser.add_argument("--campaign", type=folder, required=True, metavar="DIR",
                        help=f"campaign directory holding {runs}")
    parser.add_argument("--out", type=folder, default=Path("doc/paper_scale"), metavar="DIR",
                        help="report directory (default doc/paper_scale): writes "
                             f"DIR/validation/questions/{csv_name}")


def _add_paper_ramp_and_question_parsers(sub):
    """``paper-ramp`` (section III.B at the paper's ramp protocol) and ``question NAME``."""
    _add_campaign_reader(sub, "paper-ramp", "section III.B's question at the paper's ramp "
                         "protocol: the campaign's paperramp* runs judged (frozen or not)",
                         "runs/paperramp*", paper_ramp.CSV_NAME)
    _add_campaign_reader(sub, "sigma-eta", "sigma_<Z> and the bell's top against the "
                         "redeposition threshold: the campaign's const_* and consteta_* "
                         "P.B.C. runs", "runs/const_* and runs/consteta_*", sigma_eta.CSV_NAME)
    question = sub.add_parser("question", help="one question of the validation settled by a "
                                               "measurement (tapmc.paper.questions; --list "
                                               "lists them)")
    if question_command is not None:
        question_command.add_parser(question)


def _read_campaign(args, name, module, unit, write_figure):
    """A campaign reader's command (``paper-ramp``, ``sigma-eta``): ``module.analyse`` on the
    campaign's runs, its CSV written to the report's questions folder, its finding printed
    with the errors of the report in --out, its figure drawn by ``write_figure``; exit 2
    naming the folder when the campaign has no runs/ or nothing to read, or naming the file
    when --out holds a damaged report (nothing written). The campaign's default eta and the
    settings its figure states are those of the Scale it records (scale.json; the full
    preset without one)."""
    if not (args.campaign / "runs").is_dir():
        print(f"tapmc-paper {name}: --campaign {args.campaign} has no runs/ folder",
              file=sys.stderr)
        return 2
    if args.out.exists() and not args.out.is_dir():
        print(f"tapmc-paper {name}: --out {args.out} is a file, not a folder", file=sys.stderr)
        return 2
    try:
        scale = _runs.folder_scale(args.campaign)
        rows = module.analyse(args.campaign, scale.eta)
    except (TapmcFormatError, CampaignDirectoryError) as err:  # a damaged taps.dat, manifest
        print(f"tapmc-paper {name}: {err}", file=sys.stderr)
        return 2
    if not rows:
        print(f"tapmc-paper {name}: --campaign {args.campaign} has no run to read "
              f"({module.RUNS_READ})", file=sys.stderr)
        return 2
    try:
        errors = _report_errors(args.out, module)  # the errors of the page in --out
    except TapmcFormatError as err:
        print(f"tapmc-paper {name}: --out {args.out} holds a damaged report, whose errors "
              f"the finding would take: {err}", file=sys.stderr)
        return 2
    path = module.write_csv(rows, args.out / _runs.FIG_DIR / "questions" / module.CSV_NAME)
    print(module.finding_text(rows, scale.eta, errors))
    if errors is None:
        print(f"{name}: {args.out} holds no report: the verdicts take the runs' own "
              "batch-means errors, not the realizations' (tapmc-paper report, then again)")
    print(f"{name}: {path} ({len(rows)} {unit})")
    png = path.parent / module.PNG_NAME  # its figure beside its CSV, with the same errors
    figure = write_figure(rows, scale.eta, png, errors, scale=scale)
    print(f"{name}: {figure}")
    return 0


def _report_errors(out, reader):
    """The errors of the report in ``out`` for a campaign reader's finding (validation's
    report_errors; None without a report, or when this installation has no report module)."""
    try:
        return load_validation().report_errors(out, reader)
    except FigureUnavailable:
        return None


def scale_of(args):
    """The Scale of a command: the preset, with ``--fbc-start`` when given."""
    scale = get_scale(args.scale)
    if args.fbc_start is not None:
        scale = scale.replace(fbc_start=args.fbc_start)
    return scale


def default_campaign_dir(scale):
    """./tapmc-paper-SCALE, or ./tapmc-paper-SCALE-fbc-paper for the paper's F.B.C. start."""
    suffix = "-fbc-paper" if scale.fbc_start == "paper" else ""
    return Path(f"tapmc-paper-{scale.name}{suffix}")


def _campaign_for(args, modules):
    scale = scale_of(args)
    seeds = args.seeds if args.seeds is not None else scale.seeds
    runs, seen = [], {}
    for name, module in modules:
        for spec in module.runs(scale, seeds):
            if spec.name in seen:
                if seen[spec.name].describe() != spec.describe():
                    raise ValueError(f"{name}: run {spec.name!r} is also defined, differently, "
                                     "by another figure")
                continue
            seen[spec.name] = spec
            runs.append(spec)
    directory = args.campaign or default_campaign_dir(scale)
    # pinned as 'campaign' pins them: a campaign folder made by an earlier TAPMC (the committed
    # one) redraws and resumes with its own copies of the inputs instead of being refused
    return Campaign(directory, runs, lmp=args.lmp, jobs=args.jobs, mode=args.mode,
                    pin_inputs=True)


def _check_dir(path, label, create):
    """Refuse a folder (``label``: the campaign directory, --out) that cannot hold what the
    command writes before the campaign runs: hours of runs must not end at a mkdir. With
    ``create``, make it and write a probe file in it, the one check that also holds for root
    and for read-only file systems."""
    path = Path(path)
    if path.exists() and not path.is_dir():
        raise ValueError(f"{label} {path}: exists and is not a directory")
    if not path.exists():
        parent = path.parent
        while not parent.exists() and parent != parent.parent:
            parent = parent.parent
        if not parent.is_dir():
            raise ValueError(f"{label} {path}: cannot be created: {parent} is not a directory")
    if create:
        try:
            path.mkdir(parents=True, exist_ok=True)
            with tempfile.TemporaryFile(dir=path):
                pass
        except OSError as err:
            raise ValueError(f"{label} {path}: cannot be created or written "
                             f"({err.strerror})") from None


def _os_message(err):
    """One line for an OSError: the path first, then what is wrong."""
    where = f"{err.filename}: " if err.filename else ""
    return f"tapmc-paper: {where}{err.strerror or err}"


def _scale_before_run(campaign, scale):
    """Record the Scale of a new campaign folder before its first run starts, so that a later
    command with another scale is refused (_runs.check_scale) before it could resume these
    runs with other sizes. A folder made before scale.json existed gets it after a run that
    succeeded (see _run_campaign): only then do its finished runs match the scale."""
    if not (campaign.directory / "manifest.json").exists():
        _runs.write_scale(campaign.directory, scale)


def _run_plan(args):
    """``tapmc-paper campaign``: the paper-scale plan's runs, resumable, nothing drawn."""
    scale = get_scale("full")
    directory = args.campaign or Path(f"tapmc-paper-{scale.name}")
    try:
        # The plan's campaign is pinned: it keeps the Scale it started with (as its inputs),
        # so that FULL can change while a campaign of many sessions runs.
        recorded = _runs.recorded_scale(directory)
        if recorded is not None and recorded.name != scale.name:
            _runs.check_scale(directory, scale)  # another preset's folder: refused, named
        if recorded is not None and recorded != scale:
            changed = [k for k, v in scale.as_dict().items() if recorded.as_dict()[k] != v]
            print(f"[campaign] {directory}: keeps the Scale it started with ("
                  f"{', '.join(changed)} differ from this TAPMC's FULL)", flush=True)
            scale = recorded
        # the jobs the Campaign would take by default (the paper-scale runs have one rank),
        # which decide the plan's order
        jobs = args.jobs if args.jobs is not None else max(1, launch.available_cores())
        specs = plan.first(plan.runs(args.tier, scale, jobs=jobs), args.first)
        campaign = Campaign(directory, specs, lmp=args.lmp, jobs=jobs, mode=args.mode,
                            pin_inputs=True, tap_costs=_tap_costs(specs))
        _check_dir(campaign.directory, "campaign directory", create=not args.dry_run)
    except (ValueError, FileNotFoundError) as err:
        print(f"tapmc-paper: {err}", file=sys.stderr)
        return 2
    if args.dry_run:
        return _list_runs(campaign, f"full plan, tiers 1-{args.tier}", args.jobs)
    return _run_campaign(campaign, scale, args.quiet)


def _tap_costs(specs):
    """Run name -> the seconds the cost rule gives each of its taps, for the ETA of the runs
    whose taps differ in cost (the ramps; Campaign's ``tap_costs``); {} when the front's
    summary behind the rule cannot be read, and a run the rule cannot price is left out."""
    try:
        rule = cost.CostRule.from_summary()
    except cost.CostError:
        return {}
    out = {}
    for spec in specs:
        try:
            seconds = cost.tap_seconds(spec, rule)
        except (cost.CostError, KeyError, ValueError):
            continue
        if seconds.min() < seconds.max():  # a constant-eps run: its rate so far says as much
            out[spec.name] = seconds
    return out


def _run_campaign(campaign, scale, quiet):
    """Run the campaign; the exit status: 0, 1 (a run failed), 2 (the folder is unusable) or
    STOPPED_STATUS (stopped by SIGTERM or Ctrl-C; its runs' attempts recorded)."""
    try:
        _scale_before_run(campaign, scale)
        campaign.run(progress=not quiet)
        _runs.write_scale(campaign.directory, scale)
    except CampaignStopped as err:
        print(f"tapmc-paper: {err}", file=sys.stderr)
        return STOPPED_STATUS
    except CampaignDirectoryError as err:
        print(f"tapmc-paper: {err}", file=sys.stderr)
        return 2
    except OSError as err:
        print(_os_message(err), file=sys.stderr)
        return 2
    except (CampaignError, ValueError) as err:
        print(f"tapmc-paper: {err}", file=sys.stderr)
        return 1
    return 0


def _report_from_data(args):
    """``tapmc-paper report --from-data``: the report rewritten from committed data."""
    out = args.out or _runs.SOURCE_DIR / "doc"
    try:
        validation = load_validation()
        if args.refit:
            for csv in validation.refit(out):
                print(f"refit: {csv}")
        if args.redraw:
            for png in importlib.import_module(f"{__package__}.redraw").redraw(out):
                print(f"redraw: {png}")
        path = validation.regenerate(out)
    except (FigureUnavailable, FileNotFoundError, ValueError) as err:  # also TapmcFormatError
        print(f"tapmc-paper: {err}", file=sys.stderr)
        return 2
    except OSError as err:
        print(_os_message(err), file=sys.stderr)
        return 2
    print(f"report: {path}")
    return _write_readme(args, validation, out)


def _write_readme(args, validation, out):
    """With ``--readme``: README's section "What the validation found" from the report just
    written to ``out`` (``validation.update_readme``); exit 2 naming the file and what it
    lacks when it cannot be written."""
    if getattr(args, "readme", None) is None:
        return 0
    try:
        readme = validation.update_readme(args.readme, out)
    except (FileNotFoundError, ValueError) as err:
        print(f"tapmc-paper: --readme {args.readme}: {err}", file=sys.stderr)
        return 2
    except OSError as err:
        print(_os_message(err), file=sys.stderr)
        return 2
    print(f"report: {readme}")
    return 0


def _recorded_variables(campaign, name):
    """The variables a finished run ran with (its DONE.json), None when unreadable."""
    try:
        done = json.loads((campaign.run_dir(name) / "DONE.json").read_text())
        return done["run"]["variables"]
    except (OSError, ValueError, KeyError, TypeError):
        return None


def _finished_view(campaign, extra=()):
    """(view, planned): the same campaign restricted to its finished runs (nothing is written
    or run), with the finished runs of ``extra`` (e.g. the paper-scale plan's, whose ramps run
    1000 taps per level where the figure modules' FULL asks 4000); ``planned`` counts the runs
    of both. Where both name one run, the spec whose variables are those the run ran with
    (its DONE.json) is taken, else the one of ``extra``: the figures then read a ramp with
    the taps per level it has."""
    extra_by_name = {spec.name: spec for spec in extra}
    specs = []
    for spec in campaign.runs:
        other = extra_by_name.pop(spec.name, None)
        if other is not None and other.variables != spec.variables:
            ran = _recorded_variables(campaign, spec.name)
            spec = spec if ran is not None and ran == spec.variables else other
        specs.append(spec)
    specs += list(extra_by_name.values())
    done = [spec for spec in specs if campaign.is_done(spec.name)]
    if not done:
        raise ValueError(f"campaign {campaign.directory}: none of its {len(campaign.runs)} runs "
                         "has finished (--finished-only draws from finished runs)")
    return Campaign(campaign.directory, done, lmp=campaign.lmp, jobs=campaign.jobs,
                    mode=campaign.mode), len(specs)


def _recorded_cost(record):
    """"; its N attempts recorded ... CPU h, ... h of wall time" from a run's manifest record,
    naming the attempts without a time (killed with their campaign, or from before attempts
    recorded it: the sums are then lower bounds); "" before its first attempt."""
    attempts = (record or {}).get("attempts") or []
    if not attempts:
        return ""
    cost = provenance.attempt_costs(record)
    sums, gaps = [], []
    for key, unit, kind in (("cpu_s", "CPU h", "CPU"), ("wall_s", "h of wall time", "wall")):
        if cost[key] is not None:
            sums.append(f"{cost[key] / 3600.0:.3g} {unit}")
        untimed = cost.get(f"attempts_without_{kind.lower()}_time")
        if untimed:
            gaps.append(f"{kind} time unknown for "
                        + ("all" if cost[key] is None else f"{untimed}"))
    return (f"; {len(attempts)} attempt{'s' if len(attempts) > 1 else ''}: "
            + (", ".join(sums) + " recorded" if sums else "no time recorded")
            + (f" ({', '.join(gaps)})" if gaps and sums else ""))


def _damage(run_dir):
    """What a campaign would find wrong with a finished run's folder, as the dry run's state:
    outputs missing or changed since the run finished ("damaged (taps.dat), to run again": it
    redoes the run), a DONE.json it cannot read (it stops there), or "" when intact."""
    try:
        recorded = provenance.read_done(Path(run_dir) / "DONE.json").get("outputs")
    except CampaignDirectoryError:
        return "damaged (DONE.json unreadable: the campaign stops at it)"
    names = sorted(provenance.damaged_outputs(run_dir, recorded) if recorded else {})
    if not names:
        return ""
    return ("damaged (" + ", ".join(names[:3])
            + (f" and {len(names) - 3} more" if len(names) > 3 else "") + "), to run again")


def _list_runs(campaign, what, jobs=None):
    """The runs of a dry run, each with its CPU hours by the cost rule (times its ranks), how
    far it got (a run under way: the tap of its latest restart file, where it resumes, and
    the CPU hours of the taps from there) and what its attempts recorded, and the CPU hours
    left in all; on stderr, the campaign's warning when no commit of this TAPMC describes its
    executable (:func:`tapmc.campaign.provenance.build_mismatch`). The wall time is that of
    ``jobs`` runs at a time (--jobs; default: the cores this process may use)."""
    print(f"campaign {campaign.directory} ({what}, {len(campaign.runs)} runs):")
    why = None  # the first reason a run has no estimate
    try:
        rule = cost.CostRule.from_summary()
    except cost.CostError as err:
        rule, why = None, str(err)
    records = {r["name"]: r for r in provenance.read_manifest(campaign.directory).get("runs", [])
               if isinstance(r, dict) and "name" in r}
    left, unknown, each = 0.0, 0, []
    for spec in campaign.runs:
        done = campaign.is_done(spec.name)
        seconds = None
        try:
            seconds = cost.tap_seconds(spec, rule) if rule else None
        except KeyError as err:
            why = why or f"{spec.name} has no {err.args[0]!r} variable"
        except (cost.CostError, ValueError, TypeError) as err:  # TypeError: taps unknown
            why = why or str(err)
        ranks = spec.nprocs / 3600.0
        hours = float(seconds.sum()) * ranks if seconds is not None else None
        damage = _damage(campaign.run_dir(spec.name)) if done else ""
        done = done and not damage  # a run would redo it (from its latest restart, or anew)
        tap = 0 if done else (resume_restart(campaign.run_dir(spec.name))[0] or 0)
        # an unfinished run's rows before its restart (a finished one's damage is its own)
        lost = tap and not damage and step_rows_problem(campaign.run_dir(spec.name) / spec.taps_file, tap - 1,
                                         first_steps(records.get(spec.name, {}), tap),
                                         past_last=True)
        if lost:  # rows lost before the restart: the run goes again from the start
            damage, tap = f"{lost}: to run again from the start", 0
        to_run = float(seconds[tap:].sum()) * ranks if seconds is not None else None
        price = f"{hours:.3g} CPU h" if hours is not None else "cost unknown"
        state = "done" if done else damage if damage else "to run" if not tap else (
            f"resumes from tap {tap}, " + (f"{to_run:.3g} CPU h to run" if to_run is not None
                                           else "to run"))
        print(f"  {spec.name}  [{spec.input.name}, taps {spec.taps}, {price}, {state}"
              f"{_recorded_cost(records.get(spec.name))}]")
        if not done:
            if to_run is None:
                unknown += 1
            else:
                left += to_run
                each.append(to_run / spec.nprocs)  # one run's wall hours
    mismatch = provenance.build_mismatch(campaign.lmp,
                                         provenance.lmp_versions(campaign.lmp)["lmp_build"],
                                         provenance.tapmc_version())
    if mismatch:  # what the campaign would say at its start, before it is started
        print(f"tapmc-paper: warning: {mismatch}", file=sys.stderr)
    jobs = jobs or max(1, launch.available_cores())
    print(f"left to run: about {_hours_text(left)} of CPU (the cost rule of tapmc-paper plan; "
          f"{_hours_text(cost.wall_hours(each, jobs))} of wall time on {jobs} "
          f"{'core' if jobs == 1 else 'cores'})"
          + (f"; {unknown} runs without an estimate: {why}" if unknown else ""))
    return 0


def _plan_cost(args):
    """``tapmc-paper plan``: CPU hours per run and in all, for every eps and setting asked."""
    try:
        rule = cost.CostRule.from_summary()
        settings = [(name, cost.tier_setting(name, rule, args.N))
                    for name in (args.setting or list(cost.TIERS))]
        rows = [(label, name, eps, rule.sweeps_per_tap(args.N, eps, name),
                 rule.seconds_per_tap(args.N, eps, name),
                 rule.cpu_hours(args.N, args.taps, eps, name))
                for label, name in settings for eps in args.eps]
    except cost.CostError as err:
        print(f"tapmc-paper plan: {err}", file=sys.stderr)
        return 2
    jobs = args.jobs or max(1, launch.available_cores())
    print(f"N = {args.N}, {args.taps} taps per run, {args.seeds} run(s) per eps and setting; "
          f"cost rule: {rule.describe()} (one core of the front's machine; scale by your "
          "core's speed)")
    header = ("setting", "eps", "sweeps/tap", "CPU s/tap", "CPU h/run", "CPU h")
    print("  %-36s %8s %10s %9s %9s %9s" % header)
    total, each = 0.0, []
    for label, name, eps, sweeps, per_tap, hours in rows:
        shown = name if label == name else f"{label}: {name}"
        print("  %-36s %8g %10.0f %9.3f %9.2f %9.2f" % (shown, eps, sweeps, per_tap, hours,
                                                       hours * args.seeds))
        total += hours * args.seeds
        each += [hours] * args.seeds
    print(f"total: {total:.1f} CPU hours, about {cost.wall_hours(each, jobs):.1f} h of wall "
          f"time on {jobs} cores (the longest run first; never below the longest run)")
    for label, name in settings:
        print(f"  {label}: {cost.lammps_line(name, args.N)}")
    return 0


def main(argv=None):
    """tapmc-paper; returns the exit status. Ctrl-C outside the runs (while reading, drawing
    or starting up; the runs have their own stop, exit 3) ends with one line and 130."""
    try:
        return _main(argv)
    except KeyboardInterrupt:
        print("tapmc-paper: interrupted (Ctrl-C)", file=sys.stderr)
        return 130


def _main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command == "question":
        if question_command is None:
            print(f"tapmc-paper question: not available in this installation "
                  f"({QUESTIONS_MISSING})", file=sys.stderr)
            return 2
        return question_command.run(args, parser)
    if args.command == "campaign":
        return _run_plan(args)
    if args.command == "front":
        return front_command.main(args)
    if args.command == "paper-ramp":
        return _read_campaign(args, "paper-ramp", paper_ramp, "runs",
                              paper_ramp_figure.write_figure)
    if args.command == "sigma-eta":
        return _read_campaign(args, "sigma-eta", sigma_eta, "points", sigma_eta.write_figure)
    if args.command == "plan":
        return _plan_cost(args)
    if args.command == "report" and args.refit and not args.from_data:
        parser.error("report: --refit rewrites the committed figure CSVs of --from-data and "
                     "works with --from-data only")
    if args.command == "report" and args.redraw and not args.from_data:
        parser.error("report: --redraw draws the committed figures of --from-data again and "
                     "works with --from-data only")
    if args.command == "report" and args.from_data:
        return _report_from_data(args)
    figures = list(FIGURES) if args.command == "report" else [args.command]
    try:
        modules = [(f, load_figure(f)) for f in figures]
        validation = load_validation() if args.command == "report" else None
        campaign = _campaign_for(args, modules)
        scale = scale_of(args)
        _runs.check_scale(campaign.directory, scale)
        out = args.out or campaign.directory / "figures"
        folders = ((campaign.directory, "campaign directory"),
                   (out, "--out" if args.out else "figure folder"))
        # every check that writes nothing first: a bad --out leaves no empty campaign folder
        finished_only = getattr(args, "finished_only", False)
        if finished_only and not campaign.directory.is_dir():  # it runs nothing: reads only
            raise ValueError(f"campaign directory {campaign.directory}: does not exist "
                             "(--finished-only draws the runs a campaign has finished)")
        for create in (False, not args.dry_run):
            for path, label in folders:
                _check_dir(path, label, create)
    except (FigureUnavailable, ValueError, FileNotFoundError) as err:
        print(f"tapmc-paper: {err}", file=sys.stderr)
        return 2
    if args.dry_run:
        return _list_runs(campaign, args.scale, args.jobs)
    planned = len(campaign.runs)
    if getattr(args, "finished_only", False):
        try:
            extra = plan.drawn_runs() if scale.name == "full" else ()
            campaign, planned = _finished_view(campaign, extra)
            _runs.check_finished_runs(campaign)  # nothing is drawn from a damaged run
        except ValueError as err:  # also CampaignDirectoryError: a DONE.json cut or incomplete
            print(f"tapmc-paper: {err}", file=sys.stderr)
            return 2
        except CampaignError as err:  # an output changed since its run finished
            print(f"tapmc-paper: {err}", file=sys.stderr)
            return 1
    else:
        status = _run_campaign(campaign, scale, args.quiet)
        if status:
            return status
    return _draw_and_report(args, campaign, modules, validation, out, planned)


def _hours_text(hours):
    """A duration given in hours, as a reader takes it in: hours from 0.1 h, else minutes, else
    seconds (a quick campaign's 0.009 CPU h read '0.0 CPU hours')."""
    if hours >= 0.1:
        return f"{hours:.1f} h"
    if hours * 60 >= 1:
        return f"{hours * 60:.0f} min"
    return f"{hours * 3600:.0f} s"


def _draw_and_report(args, campaign, modules, validation, out, planned):
    """Draw every figure of ``modules`` from the campaign and, with ``validation``, write the
    report; returns the exit status. With --finished-only a figure whose runs have not
    finished is left out (its ValueError), but a damaged file of a run stops the command."""
    try:
        drawn = {}
        for name, module in modules:
            try:
                png, csv = module.draw(campaign, out)
            except TapmcFormatError:
                raise
            except ValueError as err:
                if not getattr(args, "finished_only", False):
                    raise
                print(f"{name}: left out ({err})")
                continue
            drawn[name] = (Path(png), Path(csv))
            if validation is None:
                print(f"{name}: {png}  {csv}")
        if validation is not None:  # the report moves the figures into out/validation
            report = validation.report(campaign, out, drawn, planned_runs=planned)
            moved_to = Path(out) / validation.FIG_DIR
            for name, (png, csv) in drawn.items():
                print(f"{name}: {moved_to / png.name}  {moved_to / csv.name}")
            print(f"report: {report}")
    except TapmcFormatError as err:  # a run's output damaged: named, never left out
        print(f"tapmc-paper: {err}", file=sys.stderr)
        return 2
    except _runs.PoresFailed as err:  # the pore tool failed on a run's dumps
        print(f"tapmc-paper: {err}", file=sys.stderr)
        return 1
    except OSError as err:
        print(_os_message(err), file=sys.stderr)
        return 2
    return _write_readme(args, validation, out) if validation is not None else 0
