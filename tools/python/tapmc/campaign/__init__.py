# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Ensembles of TAPMC runs: the paper's protocols over seeds and eps values.

A :class:`Campaign` runs a list of :class:`RunSpec` (one LAMMPS run each, e.g. one seed of
one eps of the constant-eps protocol of the paper, sections III-IV) in one folder::

    <campaign>/manifest.json          exact inputs (copies + sha256), versions, seeds,
                                      variables, command lines, timing
    <campaign>/inputs/<input>         the copies of the inputs that the runs execute
    <campaign>/runs/<name>/           log.lammps, per-tap file, profiles, dumps, restart.<step>
    <campaign>/runs/<name>/DONE.json  written after a run succeeded, with the sha256 and size
                                      of its outputs

Two ways to use the cores: ``mode='pool'`` (``jobs`` LAMMPS processes at a time on this
machine) or ``mode='partition'`` (LAMMPS's own multi-replica mode: one ``mpirun -np P
lmp_tapmc -partition Px1`` per batch of P runs, each partition running its run in its own
folder through world-style variables; this is how a campaign spans several nodes).

The runs are resumable: the inputs of ``examples/paper`` write ``restart.<step>`` files and
continue from one with ``-var resume yes -var resume_file restart.<step>``. A campaign that was
killed continues every unfinished run from its latest restart file (trimming the per-tap rows
written after it and merging the profile files of the two segments) and skips finished runs,
after checking their outputs: a finished run whose outputs were damaged since runs again.
What reads a campaign without running it checks each finished run it reads with
:func:`verify_finished_run` (DONE.json readable and complete, every output it lists intact).

Modules, one job each: :mod:`.spec` (RunSpec), :mod:`.launch` (processes, the lock,
``-partition``), :mod:`.run_folder` (a run's files and their repair for a resume),
:mod:`.repair` (damaged runs and restart files set aside, recorded), :mod:`.atomic` (files
written whole or not at all), :mod:`.provenance` (manifest, DONE.json, checksums),
:mod:`.progress` (the ETA), :mod:`.runner` (Campaign).
"""

from .errors import STOPPED_STATUS, CampaignDirectoryError, CampaignError, CampaignStopped
from .launch import available_cores, find_lmp
from .provenance import MANIFEST_FORMAT, verify_finished_run
from .run_folder import joined_ave_time, merge_ave_time_parts
from .runner import PROGRESS_INTERVAL, Campaign
from .spec import RunSpec, Words

__all__ = ["RunSpec", "Words", "Campaign", "CampaignError", "CampaignDirectoryError",
           "CampaignStopped", "STOPPED_STATUS", "find_lmp", "merge_ave_time_parts",
           "joined_ave_time",
           "MANIFEST_FORMAT", "PROGRESS_INTERVAL", "available_cores", "verify_finished_run"]
