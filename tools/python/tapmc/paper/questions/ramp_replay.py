# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""What ramp-levels and ramp-pores share: a ramp run of the campaign (its manifest entry and
its taps), and its replay up to a level end whose restart file the campaign no longer has
(in.ramp's ``stop``), run as a resumable campaign run of its own."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from . import launch
from .common import QuestionError, QuestionRunError, taps_table

#: the runs of a ramp's replays, under the questions' ramp work folder
REPLAYS = "replays"


def manifest_run(campaign, name):
    """(variables, seed) of run ``name`` in the campaign's manifest.json."""
    path = Path(campaign) / "manifest.json"
    if not path.is_file():
        raise QuestionError(f"{path} not found (--campaign DIR: a campaign folder)")
    try:
        runs = json.loads(path.read_text())["runs"]
    except (ValueError, KeyError, TypeError) as err:
        raise QuestionError(f"{path}: not a campaign manifest ({err})") from None
    for run in runs:
        if run.get("name") == name:
            return run["variables"], int(run["seed"])
    raise QuestionError(f"no run {name!r} in {path}")


def ramp_run_dir(campaign, name):
    """The folder of the ramp ``name``; QuestionError when it is missing."""
    run_dir = Path(campaign) / "runs" / name
    if not run_dir.is_dir():
        raise QuestionError(f"{run_dir}: no such run folder (--run {name} of --campaign "
                            f"{campaign})")
    return run_dir


def ramp_table(run_dir):
    """The ramp's taps as a matrix (columns of in.ramp: step level branch sqrt_eps phi_b
    phi_c Z) read by tapmc.readers.read_fix_print (a running ramp's half last row left
    out)."""
    table = taps_table(Path(run_dir) / "taps.dat")
    return table.data, table.columns


def level_restarts(folder, P):
    """dict level -> restart file at its end (restart.<(level + 1) P>) in ``folder``."""
    out = {}
    for path in Path(folder).glob("restart.*"):
        step = path.name.split(".", 1)[1]
        if step.isdigit() and int(step) > 0 and int(step) % P == 0:
            out[int(step) // P - 1] = path
    return out


def replay_folder(work, name):
    """The run folder of the replay of ramp ``name``."""
    return Path(work) / REPLAYS / "runs" / f"{name}_replay"


def replay_ramp(lmp, name, variables, seed, end, work, table):
    """The ramp ``name`` run again from its start up to step ``end`` (in.ramp's ``stop``), for
    a level whose restart file the campaign no longer has. The replay keeps a restart file at
    every level end: a killed replay resumes from its latest, and a later call for a later
    level continues it. Returns (the restart file at ``end``, the replay's taps rows 1..end,
    how they compare with the campaign's rows ``table``: 'replay (identical)' when every
    common row holds the same numbers, bit for bit as printed (a restart-step row that
    printed sqrt(eps) = 0 aside), else 'replay (differs from step S)')."""
    P = int(variables["P"])
    replays = Path(work) / REPLAYS
    run = launch.spec(f"{name}_replay", dict(variables, seed=seed, rsteps=P, stop=end),
                      input=launch.RAMP, taps=end)
    target = replay_folder(work, name) / f"restart.{end}"
    if not target.is_file():
        launch.reopen_if_shorter(replays, run.name, end)
        print(f"replaying {name} to step {end}", flush=True)
        launch.run_all(replays, [run], lmp)
    if not target.is_file():
        raise QuestionRunError(f"the replay of {name} to step {end} left no {target}")
    replayed, _ = ramp_table(replay_folder(work, name))
    replayed = replayed[(replayed[:, 0] >= 1) & (replayed[:, 0] <= end)]
    return target, replayed, "replay (" + replay_agreement(replayed, table) + ")"


def replay_agreement(replayed, table):
    """'identical' when the rows of the same steps hold the same numbers (sqrt(eps) compared
    where neither is 0: a resumed run's restart-step row may print 0), else 'differs from
    step S'."""
    steps = np.intersect1d(replayed[:, 0], table[:, 0])
    a = replayed[np.isin(replayed[:, 0], steps)]
    b = table[np.isin(table[:, 0], steps)]
    a, b = a[np.argsort(a[:, 0])], b[np.argsort(b[:, 0])]
    if len(a) == 0 or a.shape[1] != b.shape[1]:
        return "no common rows"
    same = np.all(np.delete(a, 3, axis=1) == np.delete(b, 3, axis=1), axis=1)
    same &= (a[:, 3] == b[:, 3]) | (a[:, 3] == 0) | (b[:, 3] == 0)
    if same.all():
        return "identical"
    return f"differs from step {int(a[np.argmin(same), 0])}"
