# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The questions' LAMMPS runs, through tapmc.campaign: one launcher, one lock
(``campaign.lock``), one resume (from a run folder's latest restart file) and one manifest
per work folder. A question killed midway continues where it stopped when started again: its
finished runs are kept (DONE.json), its unfinished ones resume from their restart files."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

from tapmc.campaign import (Campaign, CampaignDirectoryError, CampaignError, CampaignStopped,
                            RunSpec, find_lmp)

from .. import _runs
from .common import QuestionError, QuestionRunError, taps_table

#: The inputs of the paper's protocols (examples/paper).
CONSTANT_EPS = _runs.DATA_DIR / _runs.CONSTANT_EPS
RAMP = _runs.DATA_DIR / _runs.RAMP
#: Restart interval of runs that print no restart file of their own (one tap: a killed run
#: of a few taps starts again).
NO_RESTART = 1000000


def lammps(exe):
    """The LAMMPS executable (--lmp EXE, $TAPMC_LMP or build/lmp_tapmc), or QuestionError."""
    try:
        return find_lmp(exe)
    except FileNotFoundError as err:
        raise QuestionError(f"{err} (--lmp EXE or $TAPMC_LMP; tools/run-tests.sh builds "
                            "build/lmp_tapmc)") from None


def spec(name, variables, input=CONSTANT_EPS, taps=None):
    """A RunSpec of the questions: ``variables`` of the input, ``seed`` among them; ``taps``:
    the run's last step when the variables do not say it (a replay's ``stop``)."""
    variables = dict(variables)
    seed = int(variables.pop("seed", 1))
    try:
        return RunSpec(name, input, variables, seed=seed, taps=taps)
    except ValueError as err:
        raise QuestionError(f"run {name}: {err}") from None


def run_all(work, specs, lmp, jobs=1, progress=True):
    """Run ``specs`` as a campaign in ``work`` (finished ones kept, unfinished ones resumed;
    ``progress``: the campaign's progress lines); returns dict name -> run folder.
    QuestionRunError on a failed run or a folder in use, QuestionError on an unusable folder;
    CampaignStopped passes through."""
    try:
        campaign = Campaign(work, specs, lmp=lmp, jobs=jobs, pin_inputs=True)
        campaign.run(progress=progress)
    except CampaignStopped:
        raise
    except (CampaignDirectoryError, ValueError) as err:  # an unusable folder or spec: exit 2
        raise QuestionError(str(err)) from None
    except CampaignError as err:  # a run failed, or the folder is in use: exit 1
        raise QuestionRunError(str(err)) from None
    return {s.name: campaign.run_dir(s.name) for s in specs}


def run_one(work, run_spec, lmp):
    """The taps table (tapmc.readers.Table) of one run of ``work``, run or resumed first."""
    folder = run_all(work, [run_spec], lmp, progress=False)[run_spec.name]
    return taps_table(folder / run_spec.taps_file)


def start_from(work, name, restart):
    """Put ``restart`` (a restart file of another run) into run ``name``'s folder of
    ``work`` unless it has a later one: the campaign then resumes the run from it."""
    folder = Path(work) / "runs" / name
    folder.mkdir(parents=True, exist_ok=True)
    target = folder / Path(restart).name
    if not target.is_file() and not (folder / "DONE.json").is_file():
        if not Path(restart).is_file():
            raise QuestionError(f"{restart}: no such restart file")
        shutil.copyfile(restart, target)


def reopen_if_shorter(work, name, taps):
    """A finished run of ``work`` that stopped before ``taps`` is made unfinished (its
    DONE.json kept as DONE.<its taps>.json): the campaign then continues it from its latest
    restart to the longer run asked (e.g. a larger --extend)."""
    done = Path(work) / "runs" / name / "DONE.json"
    if not done.is_file():
        return
    try:
        ran = int(json.loads(done.read_text())["run"]["taps"])
    except (ValueError, KeyError, TypeError):
        raise QuestionError(f"{done}: not a DONE.json of tapmc.campaign") from None
    if ran != taps:
        done.rename(done.with_name(f"DONE.{ran}.json"))
