# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Ensembles of TAPMC runs: the paper's protocols over seeds and eps values.

A :class:`Campaign` runs a list of :class:`RunSpec` (one LAMMPS run each, e.g. one seed of
one eps of the constant-eps protocol of the paper, sections III-IV) in one folder::

    <campaign>/manifest.json          exact inputs (copies + sha256), versions, seeds,
                                      variables, command lines, timing
    <campaign>/inputs/<input>         the copies of the inputs that the runs execute
    <campaign>/runs/<name>/           log.lammps, per-tap file, profiles, dumps, restart.<step>
    <campaign>/runs/<name>/DONE.json  written after a run succeeded: the run is never redone

Two ways to use the cores: ``mode='pool'`` (``jobs`` LAMMPS processes at a time on this
machine) or ``mode='partition'`` (LAMMPS's own multi-replica mode: one ``mpirun -np P
lmp_tapmc -partition Px1`` per batch of P runs, each partition running its run in its own
folder through world-style variables; this is how a campaign spans several nodes).

The runs are resumable: the inputs of ``examples/paper`` write ``restart.<step>`` files and
continue from one with ``-var resume yes -var resume_file restart.<step>``. A campaign that was
killed continues every unfinished run from its latest restart file (trimming the per-tap rows
written after it and merging the profile files of the two segments) and skips finished runs.
"""

from __future__ import annotations

import ctypes
import fcntl
import hashlib
import json
import os
import platform
import re
import shutil
import signal
import subprocess
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

__all__ = ["RunSpec", "Campaign", "CampaignError", "CampaignDirectoryError", "find_lmp",
           "merge_ave_time_parts", "MANIFEST_FORMAT"]

_NAME_RE = re.compile(r"^[A-Za-z0-9_.+-]+$")
_VAR_RE = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
#: variables the campaign sets itself (seed from RunSpec.seed, resume from the restart files)
_RESERVED = ("seed", "resume", "resume_file")
#: seconds between two progress reports
PROGRESS_INTERVAL = 10.0
_REPO = Path(__file__).resolve().parents[3]
#: Layout of a campaign folder (manifest keys, inputs/, runs/NAME/DONE.json) that this module
#: reads and writes, recorded as "format" in manifest.json. A manifest without the key was
#: written before it was recorded and has this layout. Raise it when a change of the layout
#: would make an older TAPMC misread a folder: a folder of another format is refused.
MANIFEST_FORMAT = 1


class CampaignError(RuntimeError):
    """A run of a campaign failed; the message names each failed run and its log."""


class CampaignDirectoryError(ValueError):
    """The campaign folder cannot be used: it is not a directory, cannot be created, read or
    written, its manifest is damaged or of another format, or it holds finished runs or input
    copies that differ from the ones asked for. The message names the path and what is wrong."""


def find_lmp(lmp=None):
    """Path of the LAMMPS executable: ``lmp``, else $TAPMC_LMP, else the repository's
    build/lmp_tapmc, else ``lmp_tapmc`` on the PATH."""
    if lmp is not None:
        if Path(lmp).is_file() and os.access(lmp, os.X_OK):
            return Path(lmp).resolve()
        raise FileNotFoundError(f"lmp = {str(lmp)!r}: not an executable file")
    candidates = [os.environ.get("TAPMC_LMP"), _REPO / "build" / "lmp_tapmc",
                  shutil.which("lmp_tapmc")]
    for c in candidates:
        if c and Path(c).is_file() and os.access(c, os.X_OK):
            return Path(c).resolve()
    raise FileNotFoundError("no LAMMPS executable: build TAPMC (build/lmp_tapmc), set TAPMC_LMP "
                            "or pass lmp=PATH")


def _sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _portable_paths(value, campaign_dir):
    """``value`` (nested dicts, lists, strings) with paths inside the campaign folder written
    as ``<campaign>/...`` and paths inside the repository as ``<repo>/...``: a manifest
    committed with its campaign (doc/validation/data) names no folder of the machine it ran
    on. Only what is written changes; the runner never reads these paths back."""
    prefixes = sorted(((str(Path(campaign_dir).resolve()), "<campaign>"),
                       (str(_REPO), "<repo>")), key=lambda p: -len(p[0]))

    def fix(text):
        for prefix, tag in prefixes:
            if text == prefix or text.startswith(prefix + os.sep):
                return tag + text[len(prefix):]
        return text

    if isinstance(value, dict):
        return {k: _portable_paths(v, campaign_dir) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_portable_paths(v, campaign_dir) for v in value]
    return fix(value) if isinstance(value, str) else value


def _now():
    return time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())


def _fmt_seconds(s):
    if s is None:
        return "?"
    s = int(round(s))
    h, rem = divmod(s, 3600)
    m, sec = divmod(rem, 60)
    return f"{h}h{m:02d}m{sec:02d}s" if h else (f"{m}m{sec:02d}s" if m else f"{sec}s")


class RunSpec:
    """One LAMMPS run of a campaign.

    Parameters
    ----------
    name : str
        unique in the campaign, letters, digits and ``_.+-`` (it names the run folder),
        e.g. ``"pbc_eps0.005_s3"``.
    input : path
        the LAMMPS input (e.g. ``examples/paper/in.constant_eps``).
    variables : dict
        ``-var`` values (numbers or strings; a list or tuple gives a multi-valued index
        variable, e.g. ``dump_times``). ``seed``, ``resume`` and ``resume_file`` are set by
        the campaign.
    seed : int
        the Monte Carlo seed (``-var seed``), positive.
    nprocs : int
        MPI ranks of this run (default 1).
    taps : int or None
        total taps of the run (its last step), for the progress report and the completion
        check; default ``variables['taps']``, or P (3 nlev - 2) for the ramp protocol
        (variables ``P`` and ``nlev`` of ``examples/paper/in.ramp``).
    """

    def __init__(self, name, input, variables=None, seed=1, nprocs=1, taps=None):
        if not isinstance(name, str) or not _NAME_RE.match(name):
            raise ValueError(f"name = {name!r}: must be a non-empty string of letters, digits "
                             "and _.+-")
        path = Path(input)
        if not path.is_file():
            raise ValueError(f"input = {str(input)!r}: no such file")
        variables = dict(variables or {})
        for key, value in variables.items():
            if not isinstance(key, str) or not _VAR_RE.match(key):
                raise ValueError(f"variables: name {key!r} is not a LAMMPS variable name")
            if key in _RESERVED:
                raise ValueError(f"variables[{key!r}]: set by the campaign (use RunSpec.seed "
                                 "for the seed)")
            values = value if isinstance(value, (list, tuple)) else [value]
            if not values:
                raise ValueError(f"variables[{key!r}] = {value!r}: empty list")
            for v in values:
                if not isinstance(v, (int, float, str)) or isinstance(v, bool) or \
                        (isinstance(v, str) and (not v or any(c.isspace() for c in v))):
                    raise ValueError(f"variables[{key!r}] = {value!r}: allowed values are "
                                     "numbers and strings without spaces (or a list of them)")
        if isinstance(seed, bool) or not isinstance(seed, int) or seed < 1:
            raise ValueError(f"seed = {seed!r}: must be an integer >= 1")
        if isinstance(nprocs, bool) or not isinstance(nprocs, int) or nprocs < 1:
            raise ValueError(f"nprocs = {nprocs!r}: must be an integer >= 1")
        if taps is None and "taps" in variables:
            taps = variables["taps"]
        if taps is None and "P" in variables and "nlev" in variables:  # examples/paper/in.ramp
            taps = int(variables["P"]) * (3 * int(variables["nlev"]) - 2)
        if taps is not None:
            try:
                taps = int(taps)
            except (TypeError, ValueError):
                raise ValueError(f"taps = {taps!r}: must be an integer >= 0") from None
            if taps < 0:
                raise ValueError(f"taps = {taps!r}: must be an integer >= 0")
        self.name = name
        self.input = path.resolve()
        self.variables = variables
        self.seed = seed
        self.nprocs = nprocs
        self.taps = taps

    @property
    def taps_file(self):
        """Name of the per-tap file (first column: the step) in the run folder."""
        return str(self.variables.get("taps_file", "taps.dat"))

    def var_args(self):
        """The ``-var`` arguments of this run (without resume)."""
        args = []
        for key, value in list(self.variables.items()) + [("seed", self.seed)]:
            values = value if isinstance(value, (list, tuple)) else [value]
            args += ["-var", key] + [str(v) for v in values]
        return args

    def describe(self):
        """A JSON-able description (what the manifest and DONE.json record)."""
        return {"name": self.name, "input": self.input.name, "variables": self.variables,
                "seed": self.seed, "nprocs": self.nprocs, "taps": self.taps}

    def __repr__(self):
        return (f"RunSpec(name={self.name!r}, input={str(self.input)!r}, "
                f"variables={self.variables!r}, seed={self.seed}, nprocs={self.nprocs})")


# ------------------------------------------------------------------------------------------
# Files of a run folder


def _latest_restart(run_dir):
    """(step, path) of the restart file of the largest step, or (None, None)."""
    best = (None, None)
    for p in run_dir.glob("restart.*"):
        m = re.fullmatch(r"restart\.(\d+)", p.name)
        if m and p.stat().st_size > 0 and (best[0] is None or int(m.group(1)) > best[0]):
            best = (int(m.group(1)), p)
    return best


def _first_int(line):
    try:
        return int(line.split()[0])
    except (IndexError, ValueError):
        return None


def _trim_rows(path, before_step):
    """Keep the comment lines and the rows of a per-step file whose step < before_step."""
    if not path.exists():
        return
    kept = []
    for line in path.read_text().splitlines(keepends=True):
        if not line.endswith("\n"):
            break  # a row cut short by the kill
        step = _first_int(line)
        if line.startswith("#") or (step is not None and step < before_step):
            kept.append(line)
    path.write_text("".join(kept))


def _drop_repeated_titles(path):
    """Remove the title line that each resumed segment appends again (fix print append)."""
    if not path.exists():
        return
    seen, out = set(), []
    for line in path.read_text().splitlines(keepends=True):
        if line.startswith("#"):
            if line in seen:
                continue
            seen.add(line)
        out.append(line)
    path.write_text("".join(out))


def _ave_time_blocks(path):
    """Header lines and blocks [(step, lines)] of a fix ave/time file (scalar or vector)."""
    lines = path.read_text().splitlines(keepends=True)
    header = [ln for ln in lines if ln.startswith("#")]
    body = [ln for ln in lines if not ln.startswith("#") and ln.strip()]
    vector = any("Number-of-rows" in h for h in header)
    blocks, i = [], 0
    while i < len(body):
        fields = body[i].split()
        step = int(fields[0])
        n = int(fields[1]) if vector else 0
        blocks.append((step, body[i:i + 1 + n]))
        i += 1 + n
    return header, blocks


def merge_ave_time_parts(run_dir):
    """Merge ``X.from<step>`` segments of fix ave/time files written by resumed runs into X.

    Each segment replaces the blocks of the earlier ones from its first step on; the merged
    file has the header of the first segment. Returns the list of merged file names."""
    run_dir = Path(run_dir)
    parts = {}
    for p in run_dir.glob("*.from*"):
        m = re.fullmatch(r"(.+)\.from(\d+)", p.name)
        if m:
            parts.setdefault(m.group(1), []).append((int(m.group(2)), p))
    merged = []
    for base, segs in parts.items():
        segs.sort()
        main = run_dir / base
        files = ([(0, main)] if main.exists() else []) + segs
        header, blocks = None, []
        for k, (start, p) in enumerate(files):
            h, b = _ave_time_blocks(p)
            header = header if header is not None else h
            end = files[k + 1][0] if k + 1 < len(files) else None
            blocks += [blk for blk in b if blk[0] >= start and (end is None or blk[0] < end)]
        main.write_text("".join(header) + "".join("".join(lines) for _, lines in blocks))
        for _, p in segs:
            p.unlink()
        merged.append(base)
    return merged


def _log_error(log):
    """The first ERROR line of a LAMMPS log (or screen file), or ''."""
    if not log.exists():
        return ""
    lines = log.read_text(errors="replace").splitlines()
    for line in lines:  # LAMMPS's own error lines start with ERROR (echoed input does not)
        if line.startswith("ERROR"):
            return line.strip()
    return next((line.strip() for line in lines if "ERROR" in line), "")


def _taps_done(path):
    """Step of the last row of a per-tap file (cheap: reads its tail), or 0."""
    try:
        with open(path, "rb") as f:
            f.seek(0, os.SEEK_END)
            size = f.tell()
            f.seek(max(0, size - 4096))
            tail = f.read().decode(errors="replace").splitlines()
    except OSError:
        return 0
    for line in reversed(tail):
        step = _first_int(line)
        if step is not None and not line.startswith("#"):
            return step
    return 0


def _die_with_parent():
    """Child setup: get SIGTERM when the campaign process dies (no orphaned runs that would
    race a resumed campaign)."""
    try:
        ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG
    except OSError:
        pass


def _mpirun_prefix(nprocs):
    env = os.environ.get("TAPMC_MPIRUN")
    if env:
        cmd = env.split()
    else:
        cmd = ["mpirun"]
        if hasattr(os, "geteuid") and os.geteuid() == 0:
            cmd.append("--allow-run-as-root")
        if nprocs > (os.cpu_count() or 1):
            cmd.append("--oversubscribe")
    return cmd + ["-np", str(nprocs)]


# ------------------------------------------------------------------------------------------


class Campaign:
    """An ensemble of runs in one folder, resumable; see the module docstring.

    Parameters
    ----------
    directory : path
        the campaign folder (created if needed).
    runs : list of RunSpec
        names must be unique.
    lmp : path or None
        the LAMMPS executable (default: :func:`find_lmp`).
    jobs : int or None
        runs at a time (pool) or partitions per mpirun (partition); default: the cores of
        this machine divided by the ranks of a run.
    mode : 'pool' or 'partition'
    progress_interval : float
        seconds between progress reports.
    stream : file
        where progress goes (default sys.stdout).
    pin_inputs : bool
        what to do when an input changed since the campaign started: False (default) stops
        with an error asking for a new campaign folder; True keeps running the campaign's own
        copy (a campaign that spans months of development stays one set of runs) and says so.
    """

    def __init__(self, directory, runs, lmp=None, jobs=None, mode="pool",
                 progress_interval=PROGRESS_INTERVAL, stream=None, pin_inputs=False):
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
            jobs = max(1, (os.cpu_count() or 1) // nmax)
        if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
            raise ValueError(f"jobs = {jobs!r}: must be an integer >= 1")
        if progress_interval <= 0:
            raise ValueError(f"progress_interval = {progress_interval!r}: must be > 0")
        self.directory = Path(directory).resolve()
        self.check_directory()
        self.runs = runs
        self.lmp = find_lmp(lmp)
        self.jobs = jobs
        self.mode = mode
        self.progress_interval = float(progress_interval)
        self.stream = stream if stream is not None else sys.stdout
        self.pin_inputs = bool(pin_inputs)
        self._by_name = {r.name: r for r in runs}
        self._lock = threading.Lock()
        self._records = {}
        self._started = {}

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
            self._read_manifest()
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

    def _read_manifest(self):
        """manifest.json of the folder as a dict ({} when there is none yet); a manifest that
        cannot be read, is not one, or has another format raises CampaignDirectoryError
        instead of being overwritten, so that a folder is never silently taken over."""
        path = self.directory / "manifest.json"
        if not path.exists():
            return {}
        try:
            data = json.loads(path.read_text())
        except OSError as err:
            raise CampaignDirectoryError(f"campaign manifest {path}: cannot be read "
                                         f"({err.strerror})") from None
        except ValueError as err:  # also UnicodeDecodeError
            raise CampaignDirectoryError(f"campaign manifest {path}: not valid JSON ({err}); "
                                         "a damaged manifest or not a campaign folder") from None
        if not isinstance(data, dict) or not isinstance(data.get("runs", []), list):
            raise CampaignDirectoryError(f"campaign manifest {path}: not a campaign manifest "
                                         "(expected a JSON object with a list of runs)")
        fmt = data.get("format", MANIFEST_FORMAT)
        if fmt != MANIFEST_FORMAT:
            raise CampaignDirectoryError(
                f"campaign manifest {path}: format {fmt!r}, this TAPMC reads format "
                f"{MANIFEST_FORMAT}; the campaign was made by another TAPMC version (use that "
                "version, or a new campaign directory)")
        return data

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

    # -- versions and inputs ---------------------------------------------------------------
    def _lammps_version(self):
        try:
            out = subprocess.run([str(self.lmp), "-h"], stdin=subprocess.DEVNULL,
                                 capture_output=True, text=True, timeout=60).stdout
        except (OSError, subprocess.TimeoutExpired):
            return None
        m = re.search(r"Simulator - (.+)", out)
        return m.group(1).strip() if m else None

    @staticmethod
    def _tapmc_version():
        try:
            out = subprocess.run(["git", "-C", str(_REPO), "describe", "--always", "--dirty",
                                  "--tags"], capture_output=True, text=True, timeout=30)
            return out.stdout.strip() or None
        except (OSError, subprocess.TimeoutExpired):
            return None

    def _copy_inputs(self):
        """Copy each input into <campaign>/inputs once; the runs execute the copies, so a
        resumed campaign runs exactly what it started with."""
        inputs = {}
        folder = self.directory / "inputs"
        folder.mkdir(parents=True, exist_ok=True)
        for r in self.runs:
            src = r.input
            if src.name in inputs:
                if inputs[src.name]["source"] != str(src):
                    raise ValueError(f"runs: two different inputs named {src.name!r} "
                                     f"({inputs[src.name]['source']} and {src})")
                continue
            digest = _sha256(src)
            copy = folder / src.name
            entry = {"source": str(src), "sha256": digest,
                     "copy": str(copy.relative_to(self.directory))}
            if copy.exists() and _sha256(copy) != digest:
                if not self.pin_inputs:
                    raise CampaignDirectoryError(
                        f"input {src}: differs from the copy this campaign started with "
                        f"({copy}); use a new campaign directory")
                entry.update(sha256=_sha256(copy), source_sha256=digest)
                print(f"[campaign] input {src} changed since this campaign started; its runs "
                      f"keep executing the campaign's copy {copy}", file=self.stream, flush=True)
            if not copy.exists():
                shutil.copyfile(src, copy)
            inputs[src.name] = entry
        return inputs

    def _write_manifest(self):
        with self._lock:
            data = dict(self._manifest)
            data["updated"] = _now()
            data["runs"] = [self._records[r.name] for r in self.runs]
            data = _portable_paths(data, self.directory)
            tmp = self.directory / "manifest.json.tmp"
            tmp.write_text(json.dumps(data, indent=1, sort_keys=False) + "\n")
            tmp.replace(self.directory / "manifest.json")

    # -- one run ---------------------------------------------------------------------------
    def _prepare(self, spec):
        """Set up the folder of an unfinished run; returns the extra -var arguments
        (resume) and the restart step resumed from (or None)."""
        run_dir = self.run_dir(spec.name)
        run_dir.mkdir(parents=True, exist_ok=True)
        attempts = sorted(run_dir.glob("log.attempt*.lammps"))
        if (run_dir / "log.lammps").exists():  # an earlier attempt that did not finish
            kept = run_dir / f"log.attempt{len(attempts) + 1}.lammps"
            (run_dir / "log.lammps").replace(kept)
            with self._lock:
                self._records[spec.name]["attempts"].append(
                    {"interrupted": True, "log": kept.name,
                     "taps_done": _taps_done(run_dir / spec.taps_file)})
        step, path = _latest_restart(run_dir)
        if step is None:
            return {"resume": "no", "resume_file": "restart.*"}, None
        _trim_rows(run_dir / spec.taps_file, step)
        return {"resume": "yes", "resume_file": path.name}, step

    def _finish(self, spec, returncode, wall, resumed_from):
        """Check a run that ended; write DONE.json on success, return an error or ''."""
        run_dir = self.run_dir(spec.name)
        log = run_dir / "log.lammps"
        text = log.read_text(errors="replace") if log.exists() else ""
        error = ""
        if returncode != 0 or "Total wall time" not in text:
            error = (_log_error(log) or _log_error(run_dir / "screen.txt")
                     or f"LAMMPS exited with code {returncode}")
        elif spec.taps is not None and _taps_done(run_dir / spec.taps_file) != spec.taps:
            error = (f"the per-tap file {spec.taps_file} ends at step "
                     f"{_taps_done(run_dir / spec.taps_file)}, expected {spec.taps}")
        rec = self._records[spec.name]
        rec["attempts"].append({"started": self._started.get(spec.name), "finished": _now(),
                                "wall_s": round(wall, 3), "returncode": returncode,
                                "resumed_from_step": resumed_from, "error": error or None})
        if error:
            rec["status"] = "failed"
            return (f"run {spec.name!r} failed: {error}\n    log: {log}")
        merge_ave_time_parts(run_dir)
        _drop_repeated_titles(run_dir / spec.taps_file)
        last, _ = _latest_restart(run_dir)
        for p in run_dir.glob("restart.*"):  # keep the last one: it continues the sequence
            m = re.fullmatch(r"restart\.(\d+)", p.name)
            if m and int(m.group(1)) != last:
                p.unlink()
        rec["status"] = "done"
        rec["wall_s"] = round(sum(a.get("wall_s", 0) for a in rec["attempts"]), 3)
        done = {"run": spec.describe(), "finished": _now(), "wall_s": rec["wall_s"],
                "attempts": len(rec["attempts"])}
        (run_dir / "DONE.json").write_text(json.dumps(done, indent=1) + "\n")
        return ""

    def _pool_one(self, spec):
        run_dir = self.run_dir(spec.name)
        resume, step = self._prepare(spec)
        cmd = [str(self.lmp), "-nocite", "-in", str(self._input_copy(spec)),
               "-log", "log.lammps", "-screen", "none"] + spec.var_args()
        for key, value in resume.items():
            cmd += ["-var", key, value]
        if spec.nprocs > 1:
            cmd = _mpirun_prefix(spec.nprocs) + cmd
        with self._lock:
            self._records[spec.name]["command"] = cmd
            self._records[spec.name]["cwd"] = str(run_dir)
            self._started[spec.name] = _now()
            self._t0[spec.name] = time.time()
            self._done0[spec.name] = _taps_done(run_dir / spec.taps_file) if step else 0
        self._write_manifest()
        t0 = time.time()
        with open(run_dir / "screen.txt", "w") as screen:
            proc = subprocess.run(cmd, cwd=run_dir, stdin=subprocess.DEVNULL, stdout=screen,
                                  stderr=subprocess.STDOUT, preexec_fn=_die_with_parent)
        error = self._finish(spec, proc.returncode, time.time() - t0, step)
        with self._lock:
            self._t0.pop(spec.name, None)
        self._write_manifest()
        return error

    def _input_copy(self, spec):
        return self.directory / self._manifest["inputs"][spec.input.name]["copy"]

    # -- partition mode ----------------------------------------------------------------------
    def _batches(self, pending):
        """Groups of at most `jobs` runs that one -partition mpirun can run together: same
        input, same ranks, same variable names, equal multi-valued variables."""
        groups = {}
        for spec in pending:
            multi = tuple(sorted((k, tuple(map(str, v))) for k, v in spec.variables.items()
                                 if isinstance(v, (list, tuple))))
            key = (str(spec.input), spec.nprocs, tuple(sorted(spec.variables)), multi)
            groups.setdefault(key, []).append(spec)
        batches = []
        for specs in groups.values():
            for i in range(0, len(specs), self.jobs):
                batches.append(specs[i:i + self.jobs])
        return batches

    def _partition_batch(self, index, batch):
        pdir = self.directory / "partition"
        pdir.mkdir(exist_ok=True)
        resumes = {}
        for spec in batch:
            resumes[spec.name] = self._prepare(spec)
        first = batch[0]
        lines = ["# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.",
                 "# Written by tapmc.campaign: one run per partition, each in its own folder.",
                 "variable run_dir world " + " ".join(str(self.run_dir(s.name)) for s in batch),
                 "shell cd ${run_dir}", "log log.lammps"]
        single = [k for k, v in first.variables.items() if not isinstance(v, (list, tuple))]
        for key in single + ["seed", "resume", "resume_file"]:
            values = []
            for s in batch:
                if key == "seed":
                    values.append(str(s.seed))
                elif key in ("resume", "resume_file"):
                    values.append(str(resumes[s.name][0][key]))
                else:
                    values.append(str(s.variables[key]))
            lines.append(f"variable {key} world " + " ".join(values))
        lines.append(f"include {self._input_copy(first)}")
        driver = pdir / f"batch{index}.in"
        driver.write_text("\n".join(lines) + "\n")
        cmd = _mpirun_prefix(len(batch) * first.nprocs) + [
            str(self.lmp), "-nocite", "-partition", f"{len(batch)}x{first.nprocs}",
            "-in", str(driver), "-log", str(pdir / f"batch{index}.log"),
            "-plog", "none", "-pscreen", "none"]
        for key, value in first.variables.items():
            if isinstance(value, (list, tuple)):
                cmd += ["-var", key] + [str(v) for v in value]
        with self._lock:
            for spec in batch:
                rec = self._records[spec.name]
                rec["command"] = cmd
                rec["driver"] = str(driver.relative_to(self.directory))
                rec["cwd"] = str(self.run_dir(spec.name))
                self._started[spec.name] = _now()
                self._t0[spec.name] = time.time()
                step = resumes[spec.name][1]
                self._done0[spec.name] = (_taps_done(self.run_dir(spec.name) / spec.taps_file)
                                          if step else 0)
        self._write_manifest()
        t0 = time.time()
        with open(pdir / f"batch{index}.screen", "w") as screen:
            proc = subprocess.run(cmd, cwd=pdir, stdin=subprocess.DEVNULL, stdout=screen,
                                  stderr=subprocess.STDOUT, preexec_fn=_die_with_parent)
        errors = []
        for spec in batch:
            log = self.run_dir(spec.name) / "log.lammps"
            ok = log.exists() and "Total wall time" in log.read_text(errors="replace")
            err = self._finish(spec, 0 if ok else (proc.returncode or 1), time.time() - t0,
                               resumes[spec.name][1])
            if err:
                errors.append(err)
            with self._lock:
                self._t0.pop(spec.name, None)
        self._write_manifest()
        return errors

    # -- progress --------------------------------------------------------------------------
    def progress(self):
        """Per-run (name, taps done, total taps or None, finished) for every run."""
        out = []
        for spec in self.runs:
            done = self.is_done(spec.name)
            n = spec.taps if (done and spec.taps is not None) else \
                _taps_done(self.run_dir(spec.name) / spec.taps_file)
            out.append((spec.name, n, spec.taps, done))
        return out

    def _report(self, session_start, final=False):
        now = time.time()
        lines = []
        total_left, done_session = 0, 0
        with self._lock:
            running = dict(self._t0)
            done0 = dict(self._done0)
        for name, n, total, finished in self.progress():
            if total is not None and not finished:
                total_left += max(0, total - n)
            if name in done0:
                done_session += max(0, n - done0[name])
            if name in running and not final:
                rate = (n - done0.get(name, 0)) / max(now - running[name], 1e-9)
                eta = (total - n) / rate if (total is not None and rate > 0) else None
                pct = f" ({100.0 * n / total:.0f}%)" if total else ""
                lines.append(f"[campaign]   {name}: {n}/{total if total is not None else '?'} "
                             f"taps{pct}, ETA {_fmt_seconds(eta)}")
        finished = sum(1 for r in self.runs if self.is_done(r.name))
        elapsed = now - session_start
        rate = done_session / elapsed if elapsed > 0 else 0
        eta = total_left / rate if rate > 0 else (0 if total_left == 0 else None)
        lines.append(f"[campaign] {finished}/{len(self.runs)} runs done, elapsed "
                     f"{_fmt_seconds(elapsed)}, ETA {_fmt_seconds(eta)}")
        print("\n".join(lines), file=self.stream, flush=True)

    # -- main ------------------------------------------------------------------------------
    def run(self, progress=True):
        """Run every unfinished run (resuming from restart files), write manifest.json;
        raise CampaignError naming each failed run and its log. Returns self."""
        self.check_directory()
        try:
            self.directory.mkdir(parents=True, exist_ok=True)
            lockfile = open(self.directory / "campaign.lock", "w")
        except OSError as err:
            raise CampaignDirectoryError(
                f"campaign directory {self.directory}: cannot be created or written "
                f"({err.strerror}: {err.filename})") from None
        with lockfile:
            try:
                fcntl.flock(lockfile, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError:
                raise CampaignError(f"campaign {self.directory} is being run by another "
                                    "process (campaign.lock is held)") from None
            return self._run_locked(progress)

    def _run_locked(self, progress):
        previous = self._read_manifest()
        old = {r["name"]: r for r in previous.get("runs", [])
               if isinstance(r, dict) and "name" in r}
        self._manifest = {
            "format": MANIFEST_FORMAT, "campaign": str(self.directory),
            "created": previous.get("created"), "mode": self.mode, "jobs": self.jobs,
            "host": platform.node(), "python": sys.version.split()[0], "lmp": str(self.lmp),
            "lammps_version": self._lammps_version(),
            "tapmc_version": self._tapmc_version(), "inputs": self._copy_inputs()}
        self._manifest["created"] = self._manifest["created"] or _now()
        self._t0, self._done0 = {}, {}
        pending = []
        for spec in self.runs:
            desc = spec.describe()
            done_file = self.run_dir(spec.name) / "DONE.json"
            if done_file.exists():
                try:
                    recorded = json.loads(done_file.read_text())["run"]
                except (OSError, ValueError, KeyError, TypeError) as err:
                    raise CampaignDirectoryError(f"{done_file}: cannot be read as the record of "
                                                 f"a finished run ({err!r})") from None
                if recorded != json.loads(json.dumps(desc)):
                    raise CampaignDirectoryError(
                        f"run {spec.name!r}: finished in {done_file.parent} with other "
                        f"parameters ({recorded}); use a new name or campaign")
            rec = dict(old.get(spec.name, {}))
            rec.update(desc)
            rec.setdefault("attempts", [])
            rec["status"] = "done" if done_file.exists() else "pending"
            self._records[spec.name] = rec
            if not done_file.exists():
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
        try:
            if self.mode == "pool":
                with ThreadPoolExecutor(max_workers=self.jobs) as pool:
                    for err in pool.map(self._pool_one, pending):
                        if err:
                            errors.append(err)
            else:
                for i, batch in enumerate(self._batches(pending)):
                    errors += self._partition_batch(i, batch)
        finally:
            stop.set()
            if progress:
                watcher.join()
                self._report(start, final=True)
        if errors:
            raise CampaignError(f"{len(errors)} of {len(pending)} runs failed:\n  "
                                + "\n  ".join(errors))
        return self
