# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""``tapmc-paper question NAME [options]``: run one question of :data:`QUESTIONS` (its
measurement or re-analysis, writing its CSV into --out); ``--list`` lists them.

Exit status: 0 on success; 1 when the question cannot run or finish (bad input, named with
its file and what is wrong, or a failed run): nothing is written then, no committed CSV is
replaced by an empty or partial one; 2 on a usage error. A question killed midway resumes
where it stopped when started again (its runs are a tapmc.campaign folder under
OUT/partial/)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from tapmc.campaign import STOPPED_STATUS, CampaignStopped
from tapmc.readers import TapmcFormatError

from .. import _runs
from .._arguments import folder, positive_int
from . import CAMPAIGN_QUESTIONS, QUESTIONS
from .common import DEFAULT_CAMPAIGN, DEFAULT_OUT, QuestionError, QuestionRunError


def _summary(module):
    """The first sentence of a question's docstring, without its name."""
    text = " ".join((module.__doc__ or "").split())
    return text.split(": ", 1)[-1].split("? ")[0] + "?" if "?" in text else text[:100]


def add_parser(parser):
    """The options of ``question``: --list, and one sub-command per question."""
    parser.add_argument("--list", action="store_true", help="list the questions and exit")
    sub = parser.add_subparsers(dest="question", metavar="NAME")
    for name, module in QUESTIONS.items():
        p = sub.add_parser(name, help=_summary(module).replace("%", "%%"),  # argparse formats it
                           description=module.__doc__,
                           formatter_class=argparse.RawDescriptionHelpFormatter)
        p.add_argument("--out", type=folder, default=DEFAULT_OUT, metavar="DIR",
                       help="where the CSV goes (default: the committed page's "
                            "doc/paper_scale/validation/questions, in the source tree; for an "
                            "installed tapmc-paper, in the current directory)")
        p.add_argument("--lmp", type=Path, default=None, metavar="EXE",
                       help="LAMMPS executable (default: $TAPMC_LMP, build/lmp_tapmc)")
        p.add_argument("--jobs", type=positive_int, default=1, metavar="J",
                       help="LAMMPS runs at a time (default 1)")
        if name in CAMPAIGN_QUESTIONS:
            p.add_argument("--campaign", type=folder, default=DEFAULT_CAMPAIGN, metavar="DIR",
                           help="the campaign whose runs are read (default: the committed "
                                "paper-scale campaign, doc/validation/data/full, in the source "
                                "tree; for an installed tapmc-paper, in the current directory)")
        module.add_arguments(p)
    return parser


def run(args, parser):
    """Run ``args.question``; the exit status."""
    if args.list:
        for name, module in QUESTIONS.items():
            print(f"{name:20s} {_summary(module)}")
        return 0
    if not args.question:
        parser.error("question: give a NAME (--list lists them)")
    out = getattr(args, "out", None)
    if out is not None and out.exists() and not out.is_dir():  # before minutes of analysis
        print(f"tapmc-paper question {args.question}: --out {out} is a file, not a folder",
              file=sys.stderr)
        return 2
    try:
        QUESTIONS[args.question].measure(args)
    except CampaignStopped as err:
        print(f"tapmc-paper question {args.question}: {err}", file=sys.stderr)
        return STOPPED_STATUS
    except (QuestionRunError, _runs.PoresFailed) as err:  # a run failed: 1
        print(f"tapmc-paper question {args.question}: {err}", file=sys.stderr)
        return 1
    except (QuestionError, TapmcFormatError) as err:  # usage, path, damaged input: 2
        print(f"tapmc-paper question {args.question}: {err}", file=sys.stderr)
        return 2
    except OSError as err:  # a path that cannot be used (--out in a read-only folder): 2
        where = f"{err.filename}: " if err.filename else ""
        print(f"tapmc-paper question {args.question}: {where}{err.strerror or err}",
              file=sys.stderr)
        return 2
    return 0
