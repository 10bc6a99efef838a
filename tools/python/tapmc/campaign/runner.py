# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Campaign: runs a list of RunSpec in one folder, resumable, with a progress report. It
decides what runs and when; starting processes is :mod:`.launch`'s job, repairing a run folder
:mod:`.run_folder`'s and recording what happened :mod:`.provenance`'s."""

import json
import os
import platform
import signal
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from . import atomic, launch, provenance, repair, run_folder
from .progress import cost_sums, estimate_seconds_left, format_seconds, weighted_seconds_left
from ..readers import TapmcFormatError
from .errors import CampaignDirectoryError, CampaignError, CampaignStopped
from .spec import RunSpec

__all__ = ["Campaign", "PROGRESS_INTERVAL"]

#: seconds between two progress reports
PROGRESS_INTERVAL = 10.0

#: The signals that stop a running campaign cleanly (:class:`CampaignStopped`): a batch system's
#: or ``kill``'s SIGTERM, and Ctrl-C.
STOP_SIGNALS = (signal.SIGTERM, signal.SIGINT)
#: The signals of a LAMMPS that crashed (a fault of its own, never a stop from outside)
CRASH_SIGNALS = frozenset({signal.SIGSEGV, signal.SIGBUS, signal.SIGFPE, signal.SIGILL,
                           signal.SIGABRT, signal.SIGSYS, signal.SIGTRAP})


#: What a manifest records of the versions, each attempt too: the TAPMC tree the campaign runs
#: from (git describe), LAMMPS's version and the commit the executable was built from (both
#: from ``lmp -h``; lmp_build is None for a LAMMPS that does not print it).
VERSION_KEYS = ("tapmc_version", "lammps_version", "lmp_build")
#: variables of the paper's inputs that say how long a run goes and what it writes when, not
#: its trajectory: a run continued to more taps sets them anew (a level continued with
#: pevery = taps, a restart every gcd(50, taps), a replay to a later stop)
OUTPUT_VARIABLES = frozenset({"taps", "pevery", "rsteps", "thermo_every", "stop", "dump_times",
                              "dump_ends"})


def _versions_done(rec):
    """DONE.json's record of the versions that made a run: ``tapmc_versions`` (those its
    attempts recorded) and, when some attempts came before attempts recorded theirs,
    ``attempts_without_version``."""
    versions, unrecorded = provenance.attempt_versions(rec)
    return {"tapmc_versions": versions,
            **({"attempts_without_version": unrecorded} if unrecorded else {})}


class Campaign:
    """An ensemble of runs in one folder, resumable; see :mod:`tapmc.campaign`.

    Parameters
    ----------
    directory : path
        the campaign folder (created if needed).
    runs : list of RunSpec
        names must be unique.
    lmp : path or None
        the LAMMPS executable (default: :func:`find_lmp`).
    jobs : int or None
        runs at a time (pool) or partitions per mpirun (partition); default: the cores this
        process may use (its CPU affinity: ``taskset``, a batch system's cpuset) divided by
        the ranks of a run.
    mode : 'pool' or 'partition'
    progress_interval : float
        seconds between progress reports.
    stream : file
        where progress goes (default sys.stdout).
    pin_inputs : bool
        what to do when an input changed since the campaign started: False (default) stops
        with an error asking for a new campaign folder; True keeps running the campaign's own
        copy (a campaign that spans months of development stays one set of runs) and says so.
    tap_costs : dict or None
        run name -> the relative cost of each of its taps (``taps`` positive numbers, e.g. the
        seconds a cost model gives a tap at its eps), for the ETA of a run whose taps differ in
        cost (a ramp: its weak first levels would promise too early an end): its time so far
        is scaled by the cost left over the cost done (:func:`weighted_seconds_left`). Runs
        without one take their rate so far.
    """

    def __init__(self, directory, runs, lmp=None, jobs=None, mode="pool",
                 progress_interval=PROGRESS_INTERVAL, stream=None, pin_inputs=False,
                 tap_costs=None):
        runs = list(runs)
        if not runs:
            raise ValueError("runs = []: a campaign needs at least one RunSpec")
        names = set()
        for r in runs:
            if not isinstance(r, RunSpec):
                raise ValueError(f"runs: {r!r} is not a RunSpec")
            if r.name in names:
                raise ValueError(f"runs: name {r.name!r} appears twice; names must be unique")
            names.add(r.name)
        if mode not in ("pool", "partition"):
            raise ValueError(f"mode = {mode!r}: allowed values are 'pool' and 'partition'")
        nmax = max(r.nprocs for r in runs)
        if jobs is None:
            jobs = max(1, launch.available_cores() // nmax)
        if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
            raise ValueError(f"jobs = {jobs!r}: must be an integer >= 1")
        if progress_interval <= 0:
            raise ValueError(f"progress_interval = {progress_interval!r}: must be > 0")
        self.directory = Path(directory).resolve()
        self.check_directory()
        self.runs = runs
        self.lmp = launch.find_lmp(lmp)
        self.jobs = jobs
        self.mode = mode
        self.progress_interval = float(progress_interval)
        self.stream = stream if stream is not None else sys.stdout
        self.pin_inputs = bool(pin_inputs)
        self._by_name = {r.name: r for r in runs}
        self._cost_sums = cost_sums(tap_costs or {}, self._by_name)
        self._lock = threading.Lock()
        self._records = {}
        # the manifest records of runs of the campaign that this session does not run: kept
        self._other_records = []
        self._started = {}
        self._redo = {}  # name -> damaged files the running re-run must write again
        self._repairs = repair.RunRepairs(self.run_dir, self._records, self._lock, self.stream)
        self._again = set()  # runs whose restart LAMMPS could not read: pool mode retries
        self._lock_fds = ()  # the descriptor of campaign.lock while run() holds it
        self._manifest_error = None  # the OSError of the last manifest write, if it failed
        self._previous_version = None
        self._children = {}  # name (or batch) -> Popen of its running LAMMPS process
        self._stop_signal = None  # the name of the signal that stopped the campaign
        self._stopped = {}  # name -> the last tap of a run stopped with the campaign
        self._signalled = {}  # name -> the last tap of a run killed by a signal

    # -- folders -------------------------------------------------------------------------
    def check_directory(self):
        """Raise CampaignDirectoryError unless the campaign folder is usable: an existing
        directory that can be listed, with a readable manifest of MANIFEST_FORMAT if it has
        one, or a path whose nearest existing ancestor is a writable directory. Writes
        nothing (a dry run checks too); run() finds what only a write can show."""
        d = self.directory
        if d.exists():
            if not d.is_dir():
                raise CampaignDirectoryError(f"campaign directory {d}: exists and is not a "
                                             "directory")
            try:
                os.listdir(d)
            except OSError as err:
                raise CampaignDirectoryError(f"campaign directory {d}: cannot be read "
                                             f"({err.strerror})") from None
            provenance.read_manifest(d)
            return
        parent = d.parent
        while not parent.exists() and parent != parent.parent:
            parent = parent.parent
        if not parent.is_dir():
            raise CampaignDirectoryError(f"campaign directory {d}: cannot be created: {parent} "
                                         "is not a directory")
        if not os.access(parent, os.W_OK | os.X_OK):
            raise CampaignDirectoryError(f"campaign directory {d}: cannot be created: {parent} "
                                         "is not writable")

    def run_dir(self, name):
        """Folder of run ``name`` (whether or not it has run)."""
        return self.directory / "runs" / name

    def is_done(self, name):
        """True when run ``name`` finished successfully (its DONE.json exists)."""
        return (self.run_dir(name) / "DONE.json").exists()

    def result(self, name):
        """Folder of the finished run ``name``; raises if it is unknown or unfinished."""
        if name not in self._by_name:
            raise KeyError(f"run {name!r} is not in this campaign "
                           f"({len(self._by_name)} runs, e.g. {next(iter(self._by_name))!r})")
        if not self.is_done(name):
            raise RuntimeError(f"run {name!r} has not finished: call Campaign.run() first "
                               f"(folder {self.run_dir(name)})")
        return self.run_dir(name)

    def _input_copy(self, spec):
        return self.directory / self._manifest["inputs"][spec.input.name]["copy"]

    def _write_manifest(self, session=False):
        """Write manifest.json from the records. ``session``: a write while the runs run or
        after them: an OSError (a full disk) does not end the session nor hide its own errors;
        it is said once on the stream and kept in ``_manifest_error`` until a later write
        succeeds (every write holds every record)."""
        with self._lock:
            data = dict(self._manifest)
            data["updated"] = provenance.now()
            data["runs"] = [self._records[r.name] for r in self.runs] + self._other_records
            try:
                provenance.write_manifest(self.directory, data)
            except OSError as err:
                if not session:
                    raise
                if self._manifest_error is None:
                    try:
                        print(f"[campaign] warning: {_os_text(err)}: the manifest is not "
                              "written; the runs go on and a later write tries again",
                              file=self.stream, flush=True)
                    except (OSError, ValueError):
                        pass
                self._manifest_error = err
                return
            self._manifest_error = None

    # -- finished runs ---------------------------------------------------------------------
    @staticmethod
    def _check_parameters(spec, done_file):
        """Refuse (CampaignDirectoryError) a finished run whose DONE.json records other
        parameters than ``spec``: its name now means another run."""
        done = provenance.read_done(done_file)
        if done["run"] != json.loads(json.dumps(spec.describe())):
            raise CampaignDirectoryError(
                f"run {spec.name!r}: finished in {done_file.parent} with other "
                f"parameters ({done['run']}); use a new name or campaign")

    def _check_started_parameters(self, spec, record):
        """Refuse (CampaignDirectoryError) an unfinished run that has begun (a restart or a
        per-tap file in its folder) under other parameters than ``spec``, as its manifest
        ``record`` holds them: resumed, its trajectory would be the old run's up to the restart
        and the new one's after it (it resumed silently, and DONE.json recorded the new ones
        only). More taps than before continue the same run (with the variables that follow the
        taps, :data:`OUTPUT_VARIABLES`); fewer are refused too (it resumed beyond them and
        failed at every session)."""
        run_dir = self.run_dir(spec.name)
        begun = run_dir.is_dir() and (any(run_dir.glob("restart.*"))
                                      or (run_dir / spec.taps_file).exists())
        if not begun:
            return
        # as the record was written (paths as <campaign>/..., <repo>/...)
        now = json.loads(json.dumps(provenance.portable_paths(spec.describe(), self.directory)))
        changed = []
        for key in now:
            if key in ("name", "taps") or key not in record or record[key] == now[key]:
                continue
            if key == "variables" and isinstance(record[key], dict):
                old_vars, new_vars = record[key], now[key]
                changed += [f"{v} {old_vars.get(v, 'unset')!r} -> {new_vars.get(v, 'unset')!r}"
                            for v in sorted(set(old_vars) | set(new_vars))
                            if v not in OUTPUT_VARIABLES and old_vars.get(v) != new_vars.get(v)]
            else:
                changed.append(f"{key} {record[key]!r} -> {now[key]!r}")
        old_taps = record.get("taps")
        if old_taps is not None and now["taps"] is not None and now["taps"] < old_taps:
            changed.append(f"taps {old_taps} -> {now['taps']} (fewer)")
        if changed:
            raise CampaignDirectoryError(
                f"run {spec.name!r}: begun in {run_dir} with other parameters "
                f"({'; '.join(changed)}); resumed, it would continue the old run under the new "
                "ones: finish it with its own parameters, or use a new name or campaign")

    # -- one run ---------------------------------------------------------------------------
    def _prepare(self, spec):
        """Set up the folder of an unfinished run; returns the resume variables and the
        restart step resumed from (or None)."""
        run_dir = self.run_dir(spec.name)
        run_dir.mkdir(parents=True, exist_ok=True)
        kept = run_folder.keep_log_as_attempt(run_dir)  # an earlier attempt that did not finish
        rec = self._records[spec.name]
        with self._lock:
            # the start of an attempt killed with its campaign (no entry of its own)
            running = rec.pop("running_attempt", None)
            last = rec["attempts"][-1] if rec["attempts"] else {}
            if kept and running is None and "finished" in last and "log" not in last:
                last["log"] = kept  # the attempt its campaign saw end (stopped or failed)
            elif kept:
                entry = dict(running) if running else self._versions_of_last_attempt(rec)
                if running:  # its wall time: from its start to its last write (LAMMPS
                    # buffers its log, the per-tap file is written every tap: an attempt of
                    # 4 s read 1.2 s from its log alone)
                    written = [run_dir / kept, run_dir / spec.taps_file]
                    entry["wall_s"] = provenance.seconds_between(
                        running["started"], max(p.stat().st_mtime for p in written if p.exists()))
                    entry["wall_s_to"] = "the last write of its log or per-tap file"
                rec["attempts"].append(
                    {"interrupted": True, **entry, "log": kept,
                     "taps_done": run_folder.taps_done(run_dir / spec.taps_file)})
            elif running:  # killed, its log removed since: still the attempt where it began
                rec["attempts"].append({"interrupted": True, **running, "log": None})
        run_folder.remove_temporary_files(run_dir)  # of a rewrite killed before its rename
        fresh = {"resume": "no", "resume_file": "restart.*"}, None
        step, path = self._repairs.set_cut_restarts_aside(spec)
        if step is None:
            return fresh
        run_folder.trim_rows(run_dir / spec.taps_file, step)
        problem = run_folder.step_rows_problem(run_dir / spec.taps_file, step - 1,
                                               repair.first_steps(rec, step))
        if problem:  # rows lost before the restart: resumed, the run would lack them for good
            self._repairs.start_over(spec, f"{problem}, before its restart at step {step}")
            return fresh
        self._note_version_change(spec, rec, path)
        return {"resume": "yes", "resume_file": path.name}, step

    def _versions(self):
        """The versions of this session's LAMMPS executable and TAPMC (manifest keys)."""
        return {k: self._manifest[k] for k in VERSION_KEYS}

    @staticmethod
    def _versions_of_last_attempt(rec):
        """The versions of a run's last attempt entry (the attempt a kept log belongs to when
        its campaign recorded its end), or {} when it has none."""
        last = rec["attempts"][-1] if rec["attempts"] else {}
        return {k: last[k] for k in VERSION_KEYS if k in last}

    def _note_version_change(self, spec, rec, restart):
        """Say so when a run resumes under another TAPMC, or another build of the executable,
        than its last attempt (one trajectory then comes from two builds); an attempt recorded
        before attempts carried their version is taken as the campaign's last session's."""
        last = rec["attempts"][-1] if rec["attempts"] else {}
        version, whose = last.get("tapmc_version"), "its last attempt ran"
        if version is None:
            version, whose = self._previous_version, ("the campaign's last session ran (its "
                                                      "attempts did not record their version)")
        current = self._manifest["tapmc_version"]
        changes = [f"{whose} TAPMC {version}"] if version is not None and version != current \
            else []
        build, built = self._manifest["lmp_build"], last.get("lmp_build")
        if build is not None and built is not None and build != built:
            changes.append(f"its executable is built from {build}, its last attempt's from "
                           f"{built}")
        if changes:
            print(f"[campaign] run {spec.name!r}: resumes from {restart.name} under TAPMC "
                  f"{current}; {'; '.join(changes)} (manifest.json records each attempt's "
                  "versions; a campaign pinned to one build runs from a work tree of that "
                  "commit)", file=self.stream, flush=True)

    def _started_run(self, spec, cmd, step, **extra):
        """Record the command and start of a run (under the lock); the manifest keeps the
        start (``running_attempt``) until the attempt ends, so that an attempt killed with its
        campaign is still known by when it started, where from and which versions ran it."""
        rec = self._records[spec.name]
        rec["command"] = cmd
        rec.update(extra)
        rec["cwd"] = str(self.run_dir(spec.name))
        self._started[spec.name] = provenance.now()
        rec["running_attempt"] = {"started": self._started[spec.name],
                                  "resumed_from_step": step, **self._versions()}
        self._t0[spec.name] = time.time()
        self._done0[spec.name] = (run_folder.taps_done(self.run_dir(spec.name) / spec.taps_file)
                                  if step else 0)

    def _ending_error(self, spec, returncode, log):
        """(error, cut_short) of an attempt that ended: '' for one that finished its run
        (exit 0, the Total wall time line, the per-tap file at the last tap), else what went
        wrong; ``cut_short``: ended early with no error of its own, not crashed (stopped from
        outside)."""
        run_dir = log.parent
        text = log.read_text(errors="replace") if log.exists() else ""
        if returncode == 0 and "Total wall time" in text:
            done = run_folder.taps_done(run_dir / spec.taps_file)
            if spec.taps is not None and done != spec.taps:
                return (f"the per-tap file {spec.taps_file} ends at step {done}, expected "
                        f"{spec.taps}"), False
            return "", False
        own = run_folder.log_error(log) or run_folder.log_error(run_dir / "screen.txt")
        crashed = returncode is not None and -returncode in CRASH_SIGNALS
        cut_short = not own.startswith("ERROR") and not crashed
        if crashed:
            return (f"LAMMPS crashed (signal {_signal_name(-returncode)}) after tap "
                    f"{run_folder.taps_done(run_dir / spec.taps_file)}: a fault of the "
                    "executable, not a stop from outside (its log and screen.txt say where; "
                    "the run resumes from its latest restart file when the campaign runs "
                    "again)"), False
        if returncode is not None and returncode < 0 and cut_short:
            # stopped from outside: a line of the echoed input that mentions ERROR is no
            # error of the run
            return (f"LAMMPS was stopped by signal {_signal_name(-returncode)} (the run "
                    "resumes from its latest restart file when the campaign runs again)"), True
        if not own and returncode == 0:
            return (f"LAMMPS exited with code 0 without finishing the run (its log "
                    f"{'has no Total wall time line' if log.exists() else 'was not written'}): "
                    f"is {self.lmp} a LAMMPS that runs {spec.input.name}?"), cut_short
        return own or f"LAMMPS exited with code {returncode}", cut_short

    def _unreadable_restart(self, spec, log, resumed_from):
        """After an attempt that failed or was stopped: set aside the restart files it left cut
        short (a stopped run's folder then holds whole ones only) and the one it resumed from
        when LAMMPS could not read it; in that case the error to give (pool mode runs it again
        at once from the restart before), else ''."""
        unread = run_folder.restart_read_error(log) if resumed_from is not None else ""
        name = f"restart.{resumed_from}"
        _, path = self._repairs.set_cut_restarts_aside(
            spec, {name: f"LAMMPS could not read it ({unread})"} if unread else None)
        if not unread:
            return ""
        error = (f"LAMMPS could not read {name} ({unread}); it is set aside, and the run "
                 "resumes from " + (path.name if path is not None else "tap 0"))
        if self.mode == "pool":  # at once: _pool_one runs it again
            self._again.add(spec.name)
            return error
        return error + " when the campaign runs again"

    def _put_together(self, spec, rec, log):
        """The outputs of a run that finished put together (profile segments merged, repeated
        titles and old restarts gone) and checked (the files of a re-run after damage, every
        step of the per-tap file once): ('', log) or (the error, its log). A per-tap file that
        breaks the check sets the run's files aside, its log too: the run starts over."""
        run_dir = self.run_dir(spec.name)
        try:  # a malformed output names itself; the run then fails instead of the pool
            run_folder.merge_ave_time_parts(run_dir)
            run_folder.drop_repeated_titles(run_dir / spec.taps_file)
            run_folder.keep_latest_restart(run_dir, keep_every=spec.level_taps)
        except (TapmcFormatError, OSError) as err:
            return f"its outputs could not be put together: {err}", log
        missing = [n for n in self._redo.get(spec.name, []) if not (run_dir / n).exists()]
        if missing:
            return (f"re-run after damage did not write {', '.join(missing)} again; the damaged "
                    "files are in its damagedK/ folder"), log
        if spec.taps is None and not (run_dir / spec.taps_file).exists():
            return "", log
        last = spec.taps if spec.taps is not None else \
            run_folder.taps_done(run_dir / spec.taps_file)
        problem = run_folder.step_rows_problem(run_dir / spec.taps_file, last,
                                               repair.first_steps(rec))
        if not problem:
            return "", log
        # e.g. rows lost to a kill, or written by two processes at once
        aside = self._repairs.start_over(spec, problem)
        return (f"its per-tap file is damaged ({problem}): no DONE.json; its files are in "
                f"{aside.name}/ and it runs again from the start when the campaign runs "
                "again"), aside / log.name

    def _finish(self, spec, returncode, wall, resumed_from, cpu=None):
        """Check a run that ended; write DONE.json on success, return an error or ''. The
        attempt's record holds its wall time, the step it resumed from and the last step it
        wrote (``end_step``), and in pool mode its CPU seconds (``cpu_s``)."""
        run_dir = self.run_dir(spec.name)
        log = run_dir / "log.lammps"
        error, cut_short = self._ending_error(spec, returncode, log)
        stopped = cut_short and self._stop_signal is not None
        if stopped:  # its own words: a partition's log may hold only an echoed "ERROR" line
            error = (f"stopped with its campaign by {self._stop_signal} (the run resumes from "
                     "its latest restart file when the campaign runs again)")
        # Records change under the lock only: another thread may be writing the manifest.
        rec = self._records[spec.name]
        attempt = {"started": self._started.get(spec.name), "finished": provenance.now(),
                   "wall_s": round(wall, 3), "returncode": returncode,
                   "resumed_from_step": resumed_from, "error": error or None,
                   "end_step": run_folder.taps_done(run_dir / spec.taps_file),
                   **self._versions()}
        if cpu is not None:
            attempt["cpu_s"] = round(cpu, 3)
        with self._lock:
            rec.pop("running_attempt", None)
            rec["attempts"].append(attempt)
        if error:  # restarts cut short go aside, and one LAMMPS could not read is the error
            error = self._unreadable_restart(spec, log, None if stopped else resumed_from) \
                or error
        if stopped:  # no failure
            with self._lock:
                rec["status"] = "stopped"
                self._stopped[spec.name] = attempt["end_step"]
            return ""
        if cut_short and returncode is not None and returncode < 0:
            # killed by a signal that may be the campaign's own stop, reaching the child (the
            # terminal's Ctrl-C, a batch system's SIGTERM to every process) before the handler
            # ran: _run_locked counts it as stopped if the campaign stops
            self._signalled[spec.name] = attempt["end_step"]
        if not error:
            error, log = self._put_together(spec, rec, log)
        if error:
            with self._lock:
                rec["status"] = "failed"
            if not log.exists() and (run_dir / "screen.txt").exists():
                log = run_dir / "screen.txt"  # what the process said, where it wrote no log
            return f"run {spec.name!r} failed: {error}\n    log: {log}"
        self._redo.pop(spec.name, None)
        with self._lock:
            rec["status"] = "done"
            cost = provenance.attempt_costs(rec)
            rec["wall_s"] = cost["wall_s"]
        done = {"run": spec.describe(), "finished": provenance.now(), **cost,
                "attempts": len(rec["attempts"]),
                **_versions_done(rec),
                "outputs": provenance.output_digests(run_dir, run_folder.output_files(run_dir))}
        provenance.write_done(run_dir, done)
        return ""

    def _pool_one(self, spec):
        """Run one run (again from an earlier restart when LAMMPS could not read the one it
        resumed from); returns its error or ''."""
        error = ""
        while self._stop_signal is None:  # once stopped, runs not started are left alone
            run_dir = self.run_dir(spec.name)
            resume, step = self._prepare(spec)
            cmd = launch.lammps_command(self.lmp, spec, self._input_copy(spec), resume)
            with self._lock:
                self._started_run(spec, cmd, step)
            self._write_manifest(session=True)
            t0 = time.time()
            returncode, cpu = launch.run_child_timed(
                cmd, run_dir, run_dir / "screen.txt",
                lambda proc: self._child_started(spec.name, proc), self._lock_fds)
            self._children.pop(spec.name, None)
            error = self._finish(spec, returncode, time.time() - t0, step, cpu)
            with self._lock:
                self._t0.pop(spec.name, None)
            self._write_manifest(session=True)
            if spec.name not in self._again:
                break
            self._again.discard(spec.name)  # its restart set aside: it goes on from another
        return error

    def _partition_batch(self, index, batch):
        pdir = self.directory / "partition"
        pdir.mkdir(exist_ok=True)
        resumes = {spec.name: self._prepare(spec) for spec in batch}
        driver = pdir / f"batch{index}.in"
        atomic.write_text(driver, launch.partition_driver(
            batch, {s.name: self.run_dir(s.name) for s in batch},
            {name: r[0] for name, r in resumes.items()}, self._input_copy(batch[0]), cwd=pdir))
        cmd = launch.partition_command(self.lmp, batch, driver, pdir / f"batch{index}.log")
        with self._lock:
            for spec in batch:
                self._started_run(spec, cmd, resumes[spec.name][1],
                                  driver=str(driver.relative_to(self.directory)))
        self._write_manifest(session=True)
        t0 = time.time()
        key = f"batch{index}"
        returncode = launch.run_child(cmd, pdir, pdir / f"{key}.screen",
                                      lambda proc: self._child_started(key, proc),
                                      self._lock_fds)
        self._children.pop(key, None)
        errors = []
        for spec in batch:
            log = self.run_dir(spec.name) / "log.lammps"
            ok = log.exists() and "Total wall time" in log.read_text(errors="replace")
            err = self._finish(spec, 0 if ok else (returncode or 1), time.time() - t0,
                               resumes[spec.name][1])
            if err:
                errors.append(err)
            with self._lock:
                self._t0.pop(spec.name, None)
        self._write_manifest(session=True)
        return errors

    # -- stopping --------------------------------------------------------------------------
    # The handler runs in the main thread between two of its bytecodes, perhaps while that
    # thread holds self._lock: it takes no lock, and the workers check the flag it sets.
    def _child_started(self, key, proc):
        """Note a running LAMMPS process; one started after the stop is stopped at once."""
        self._children[key] = proc
        if self._stop_signal is not None:
            _terminate(proc)

    def _stop(self, signum, frame):
        """Signal handler: stop the LAMMPS children (their threads then record their attempts)
        and start no other run."""
        first = self._stop_signal is None
        if first:
            self._stop_signal = _signal_name(signum)
        for proc in list(self._children.values()):
            _terminate(proc)
        if first:
            try:  # the main thread may be inside a write to the same stream (partition mode),
                # or the stream is a pipe whose reader the same Ctrl-C ended
                print(f"[campaign] {self._stop_signal}: stopping the running runs and "
                      "recording their attempts; no other run starts", file=self.stream,
                      flush=True)
            except (RuntimeError, OSError, ValueError):
                pass

    def _install_stop_handlers(self):
        """Catch :data:`STOP_SIGNALS` while the runs run (in the main thread only: Python
        allows no handler elsewhere; a signal this process ignores, as a shell's background
        job ignores SIGINT, stays ignored); returns the handlers they replace, to restore
        (those set outside Python, which signal.signal reports as None, are left as ours)."""
        self._stop_signal, self._stopped, self._signalled, self._children = None, {}, {}, {}
        if threading.current_thread() is not threading.main_thread():
            return {}
        replaced = {}
        for signum in STOP_SIGNALS:
            if signal.getsignal(signum) is not signal.SIG_IGN:
                replaced[signum] = signal.signal(signum, self._stop)
        return {s: h for s, h in replaced.items() if h is not None}

    def _count_signalled_as_stopped(self, errors):
        """After a stop, the runs killed by a signal before the handler ran are stopped too,
        not failed; returns the errors without theirs."""
        for name, tap in self._signalled.items():
            self._records[name]["status"] = "stopped"
            self._stopped[name] = tap
        return [e for e in errors if not any(e.startswith(f"run {name!r} failed: ")
                                            for name in self._signalled)]

    def _stop_error(self, errors, note=""):
        """The CampaignStopped of a campaign stopped by a signal, naming where each running run
        stopped, how many runs did not start, and the failures of the session (then ``note``)."""
        stopped = ", ".join(f"{name!r} at tap {tap}" for name, tap in self._stopped.items())
        waiting = sum(1 for r in self.runs
                      if self._records[r.name].get("status") == "pending")
        failed = (f"; {len(errors)} run{'s' if len(errors) > 1 else ''} failed:\n  "
                  + "\n  ".join(errors)) if errors else ""
        return CampaignStopped(
            f"stopped by {self._stop_signal}: {len(self._stopped)} running run"
            f"{'s' if len(self._stopped) != 1 else ''} stopped and recorded"
            + (f" ({stopped})" if stopped else "") + f", {waiting} not started; running the "
            "campaign again resumes each from its latest restart file" + failed + note,
            self._stop_signal)

    # -- progress --------------------------------------------------------------------------
    def progress(self):
        """Per-run (name, taps done, total taps or None, finished) for every run."""
        out = []
        for spec in self.runs:
            done = self.is_done(spec.name)
            n = spec.taps if (done and spec.taps is not None) else \
                run_folder.taps_done(self.run_dir(spec.name) / spec.taps_file)
            out.append((spec.name, n, spec.taps, done))
        return out

    def _report(self, session_start, final=False):
        now = time.time()
        lines = []
        left, spt_running, done_session = {}, {}, 0
        with self._lock:
            running = dict(self._t0)
            done0 = dict(self._done0)
            records = {name: dict(rec) for name, rec in self._records.items()}
        for name, n, total, finished in self.progress():
            if total is not None and not finished:
                left[name] = max(0, total - n)
            if name in done0:
                done_session += max(0, n - done0[name])
            if name in running and not final:
                rate = (n - done0.get(name, 0)) / max(now - running[name], 1e-9)
                eta = (total - n) / rate if (total is not None and rate > 0) else None
                if name in self._cost_sums and total is not None:
                    eta = weighted_seconds_left(self._cost_sums[name], done0.get(name, 0), n,
                                                now - running[name])
                if eta is not None and total is not None and total > n:
                    spt_running[name] = eta / (total - n)
                elif rate > 0:
                    spt_running[name] = 1.0 / rate
                pct = f" ({100.0 * n / total:.0f}%)" if total else ""
                lines.append(f"[campaign]   {name}: {n}/{total if total is not None else '?'} "
                             f"taps{pct}, ETA {format_seconds(eta)}")
        finished = sum(1 for r in self.runs if self.is_done(r.name))
        elapsed = now - session_start
        rate = done_session / elapsed if elapsed > 0 else 0
        eta = estimate_seconds_left(left, records, spt_running, self.jobs, rate,
                                    started=running) if any(left.values()) else 0
        lines.append(f"[campaign] {finished}/{len(self.runs)} runs done, elapsed "
                     f"{format_seconds(elapsed)}, ETA {format_seconds(eta)}")
        print("\n".join(lines), file=self.stream, flush=True)

    # -- main ------------------------------------------------------------------------------
    def run(self, progress=True):
        """Run every unfinished run (resuming from restart files) and every finished run whose
        outputs were damaged since, write manifest.json; raise CampaignError naming each
        failed run and its log. Returns self."""
        self.check_directory()
        with launch.campaign_lock(self.directory) as lock:
            self._lock_fds = (lock.fileno(),)  # LAMMPS children hold the lock too
            try:
                return self._run_locked(progress)
            finally:
                self._lock_fds = ()

    def _session_manifest(self, previous):
        """This session's manifest.json (its runs added later): the campaign, this machine,
        the versions of the executable and of TAPMC, the inputs' copies; a warning line on
        the stream when no commit of this TAPMC describes the executable."""
        manifest = {
            "format": provenance.MANIFEST_FORMAT, "campaign": str(self.directory),
            "created": previous.get("created") or provenance.now(), "mode": self.mode,
            "jobs": self.jobs, "host": platform.node(), "python": sys.version.split()[0],
            "lmp": str(self.lmp), **provenance.lmp_versions(self.lmp),
            "tapmc_version": provenance.tapmc_version(),
            "inputs": provenance.copy_inputs(self.directory, self.runs, self.pin_inputs,
                                             self.stream, previous.get("inputs"))}
        mismatch = provenance.build_mismatch(self.lmp, manifest["lmp_build"],
                                             manifest["tapmc_version"])
        if mismatch:
            print(f"[campaign] warning: {mismatch}", file=self.stream, flush=True)
        return manifest

    def _run_locked(self, progress):
        self._manifest_error = None
        previous = provenance.read_manifest(self.directory)
        # the version of the campaign's last session: the best record of attempts that were
        # made before each attempt carried its own
        self._previous_version = previous.get("tapmc_version")
        old = {r["name"]: r for r in previous.get("runs", [])
               if isinstance(r, dict) and "name" in r}
        self._other_records = [r for name, r in old.items() if name not in self._by_name]
        self._manifest = self._session_manifest(previous)
        self._t0, self._done0 = {}, {}
        for spec in self.runs:  # every run's parameters first: a refusal moves nothing
            if self.is_done(spec.name):
                self._check_parameters(spec, self.run_dir(spec.name) / "DONE.json")
            elif spec.name in old:
                self._check_started_parameters(spec, old[spec.name])
        pending = []
        for spec in self.runs:
            done_file = self.run_dir(spec.name) / "DONE.json"
            rec = dict(old.get(spec.name, {}))
            rec.update(spec.describe())
            rec.setdefault("attempts", [])
            self._records[spec.name] = rec
            finished = done_file.exists()
            redo = self._repairs.unfinish_if_damaged(spec, done_file) if finished else None
            if redo is not None:  # damaged since it finished: it runs again
                self._redo[spec.name], finished = redo, False
            rec["status"] = "done" if finished else "pending"
            if not finished:
                pending.append(spec)
        self._write_manifest()
        if progress:
            print(f"[campaign] {self.directory}: {len(self.runs) - len(pending)} of "
                  f"{len(self.runs)} runs already done, {len(pending)} to run "
                  f"({self.mode}, {self.jobs} at a time)", file=self.stream, flush=True)
        if not pending:
            return self
        start = time.time()
        stop = threading.Event()

        def monitor():
            while not stop.wait(self.progress_interval):
                self._report(start)

        watcher = threading.Thread(target=monitor, daemon=True)
        if progress:
            watcher.start()
        errors = []
        handlers = self._install_stop_handlers()
        try:
            if self.mode == "pool":
                with ThreadPoolExecutor(max_workers=self.jobs) as pool:
                    for err in pool.map(self._pool_one, pending):
                        if err:
                            errors.append(err)
            else:
                for i, batch in enumerate(launch.partition_batches(pending, self.jobs)):
                    if self._stop_signal is None:
                        errors += self._partition_batch(i, batch)
        finally:
            for signum, handler in handlers.items():
                signal.signal(signum, handler)
            stop.set()
            if progress:
                watcher.join()
                try:
                    self._report(start, final=True)
                except (OSError, ValueError):  # a closed pipe: the stop or error matters more
                    pass
            if self._stop_signal is not None:
                errors = self._count_signalled_as_stopped(errors)
            # best effort: an error of the session that propagates comes first
            self._write_manifest(session=True)
        self._raise_session_error(errors, pending)
        return self

    def _raise_session_error(self, errors, pending):
        """Raise what the session that ran ``pending`` ends with: CampaignStopped (stopped by
        a signal), CampaignError (runs failed), either followed by the manifest's write error
        if the last write failed, or that OSError alone; nothing when all went well."""
        left = any(self._records[r.name].get("status") == "pending" for r in pending)
        unwritten = "" if self._manifest_error is None else (
            f"; and the manifest could not be written ({_os_text(self._manifest_error)})")
        if self._stop_signal is not None and (self._stopped or left):
            raise self._stop_error(errors, unwritten)
        if errors:
            raise CampaignError(f"{len(errors)} of {len(pending)} runs failed:\n  "
                                + "\n  ".join(errors) + unwritten)
        if self._manifest_error is not None:
            raise self._manifest_error


def _terminate(proc):
    """SIGTERM to a child that may have ended already. Not Popen.send_signal: it polls first,
    and that waitpid may reap the child before its thread's wait4, which then fails; the
    thread sets ``returncode`` right after its wait4, so a reaped child is never signalled."""
    if proc.returncode is None:
        try:
            os.kill(proc.pid, signal.SIGTERM)
        except OSError:  # ended in between
            pass


def _os_text(err):
    """An OSError as '<path>: <what>' (the path first, as tapmc-paper's lines give it)."""
    return f"{err.filename}: {err.strerror}" if err.filename else str(err.strerror or err)


def _signal_name(number):
    try:
        return signal.Signals(number).name
    except ValueError:
        return str(number)
