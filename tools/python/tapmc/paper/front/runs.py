# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The runs of the front, through :mod:`tapmc.campaign` (its launcher, lock, resume and
manifest): every run is examples/paper/in.constant_eps with one setting and one seed; the
seed also fixes the initial packing, so the settings are compared seed by seed (paired).

The campaign folder is ``<out>/work`` (not committed). A run writes a restart file every
1/``RESTARTS_PER_RUN`` of its taps; a killed front (any signal, even SIGKILL) resumes every
unfinished run from its latest restart, bit for bit the same taps, when it is run again. A
finished run is recorded (:func:`record_finished`): its taps.dat gzipped into
``<out>/taps/``, one row of ``<out>/runs.csv`` with its CPU time, and its campaign folder
removed; a run of runs.csv is never run again.

The CPU time of a run is the lmp process's own (user + system, from the campaign's attempt
records): an attempt that was stopped counts for the taps it kept, by their share of its
sweeps (the taps after its last restart are run again by the next attempt, the same taps).
"""

import gzip
import os
import platform
import shutil
import subprocess
import time
from dataclasses import dataclass

from ...campaign import Campaign, CampaignError, RunSpec, Words
from ..._source import git_checkout
from ...campaign.provenance import read_manifest
from .._runs import CONSTANT_EPS, DATA_DIR as INPUTS_DIR
from . import data
from .settings import SETTINGS, box_side_R, seeds, settle_keys, wanted

#: the campaign folder under the front's folder (a run lives there until it ends)
WORK = "work"
#: restart files per run (N = 4096, 1000 taps: one every 50 taps)
RESTARTS_PER_RUN = 20
#: thermo lines per run
THERMO_LINES = 10


@dataclass(frozen=True)
class FrontRun:
    """One run of the front: a setting at N and eps, one seed, `taps` taps."""
    setting: str
    N: int
    eps: float
    seed: int
    taps: int

    @property
    def key(self):
        return (self.setting, self.N, "%g" % self.eps, self.seed, self.taps)

    @property
    def name(self):
        return data.run_name(self.setting, self.N, self.eps, self.seed)


def restart_every(taps):
    """Taps between restart files: RESTARTS_PER_RUN of them, so a killed run loses little."""
    return max(1, taps // RESTARTS_PER_RUN)


def run_spec(run):
    """The campaign's RunSpec of a front run."""
    return RunSpec(run.name, INPUTS_DIR / CONSTANT_EPS, seed=run.seed, taps=run.taps, variables={
        "N": run.N, "L": "%g" % box_side_R(run.N), "eps": "%g" % run.eps, "taps": run.taps,
        "eta": SETTINGS[run.setting]["eta"], "settle_keys": Words(settle_keys(run.setting, run.N)),
        "rsteps": restart_every(run.taps), "thermo_every": max(1, run.taps // THERMO_LINES)})


def runs_to_do(out_dir, N, taps, seed_count, eps_list, names):
    """(the FrontRuns not yet in runs.csv, the number already there), seed-major with cheap
    settings first: a partial front still covers every setting."""
    done = {r.key for r in data.read_runs(os.path.join(out_dir, data.RUNS_CSV))}
    todo = []
    for seed in seeds(seed_count):
        for eps in eps_list:
            for name in names:
                run = FrontRun(name, N, eps, seed, taps)
                if wanted(name, eps) and run.key not in done:
                    todo.append(run)
    return todo, len(done)


def _swept(table, first, last):
    """Sweeps of the taps first < step <= last."""
    return sum(s for step, s in zip(table.step, table.sweeps) if first < step <= last)


def run_cpu_seconds(attempts, table):
    """CPU seconds of a finished run from the campaign's attempt records (``resumed_from_step``,
    ``end_step``, ``cpu_s``) and its TapsTable: each attempt counts its CPU for the taps it kept
    (up to the restart the next attempt resumed from) by their share of the sweeps it ran; the
    sum is scaled to all the run's sweeps when some taps have no timed attempt (a front killed
    with its lmp: that attempt left no record)."""
    timed = [a for a in attempts if a.get("cpu_s") is not None]
    cpu = covered = 0.0
    for i, a in enumerate(timed):
        start = a.get("resumed_from_step") or 0
        end = a.get("end_step", start)
        kept_end = end if i + 1 == len(timed) else min(end, timed[i + 1].get("resumed_from_step") or 0)
        ran, kept = _swept(table, start, end), _swept(table, start, kept_end)
        cpu += a["cpu_s"] * kept / ran if ran > 0 else 0.0
        covered += kept
    total = _swept(table, 0, table.step[-1])
    return cpu * total / covered if covered > 0 else cpu


def _gzip_into(src, dest):
    os.makedirs(os.path.dirname(dest), exist_ok=True)
    with open(src, "rb") as f, gzip.open(dest + ".part", "wb") as gz:
        shutil.copyfileobj(f, gz)
    os.replace(dest + ".part", dest)


def _row(run, table, record):
    """The runs.csv row of a finished run."""
    attempts = record.get("attempts", [])
    cpu = run_cpu_seconds(attempts, table)
    wall = sum(a.get("wall_s") or 0.0 for a in attempts)
    return data.RunRow(setting=run.setting, N=run.N, eps="%g" % run.eps, seed=run.seed,
                       taps=run.taps, eta=SETTINGS[run.setting]["eta"],
                       settle_keys=settle_keys(run.setting, run.N), cpu_s="%.2f" % cpu,
                       wall_s="%.1f" % wall, cpu_per_tap="%.5f" % (cpu / run.taps),
                       sweeps_per_tap="%.1f" % (sum(table.sweeps) / run.taps),
                       capped_taps=sum(1 for c in table.capped if c > 0))


def record_finished(out_dir, runs):
    """Record every run of `runs` whose campaign run finished (DONE.json): its gzipped taps,
    its runs.csv row (the file written whole), then its campaign folder removed. Returns the
    rows added."""
    work = os.path.join(out_dir, WORK)
    records = {r.get("name"): r for r in read_manifest(work).get("runs", []) if isinstance(r, dict)}
    rows, finished = [], []
    for run in runs:
        run_dir = os.path.join(work, "runs", run.name)
        if not os.path.isfile(os.path.join(run_dir, "DONE.json")):
            continue
        taps_dat = os.path.join(run_dir, "taps.dat")
        table = data.read_taps(taps_dat, run.taps)
        _gzip_into(taps_dat, data.taps_path(out_dir, run.setting, run.N, run.eps, run.seed))
        rows.append(_row(run, table, records.get(run.name, {})))
        finished.append(run_dir)
    if rows:
        data.append_runs(os.path.join(out_dir, data.RUNS_CSV), rows)
    for run_dir in finished:
        shutil.rmtree(run_dir)
    return rows


def machine_meta(lmp, jobs, nice):
    """What meta.json records: the commit, the executable's name (no machine path), the CPU,
    cores, runs at a time, nice level and the day."""
    repo = git_checkout()  # an installed package describes no repository
    commit = "unknown" if repo is None else subprocess.run(
        ["git", "-C", str(repo), "describe", "--always", "--dirty"],
        capture_output=True, text=True).stdout.strip() or "unknown"
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    return {"commit": commit, "lmp": os.path.basename(str(lmp)), "machine": cpu,
            "cores": os.cpu_count(), "jobs": jobs, "nice": nice,
            "started": time.strftime("%Y-%m-%d", time.gmtime())}


def run_front(out_dir, todo, lmp=None, jobs=1, nice=0, stream=None):
    """Run the FrontRuns `todo` in ``<out_dir>/work`` (resuming the unfinished ones) and record
    every finished one; returns the rows added. CampaignError (a run failed: the others are
    recorded) and CampaignDirectoryError pass through."""
    os.makedirs(out_dir, exist_ok=True)
    campaign = Campaign(os.path.join(out_dir, WORK), [run_spec(r) for r in todo], lmp=lmp,
                        jobs=jobs, stream=stream)
    data.write_meta(out_dir, machine_meta(campaign.lmp, jobs, nice))
    try:
        campaign.run()
    except CampaignError:
        record_finished(out_dir, todo)
        raise
    return record_finished(out_dir, todo)
