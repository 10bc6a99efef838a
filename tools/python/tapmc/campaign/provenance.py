# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""What a campaign records about itself: manifest.json (format, versions, input copies and
their sha256, per run its parameters, commands and attempts) and each finished run's DONE.json
(its parameters and the sha256 and size of its outputs), and the check of those outputs."""

import calendar
import hashlib
import json
import math
import os
import re
import subprocess
import time
from pathlib import Path

from .._source import git_checkout, source_tree
from . import atomic
from .errors import CampaignDirectoryError, CampaignError
from .launch import private_mpi_session

__all__ = ["MANIFEST_FORMAT", "sha256", "now", "portable_paths", "read_manifest",
           "write_manifest", "lmp_versions", "tapmc_version", "copy_inputs",
           "read_done", "write_done", "output_digests", "damaged_outputs",
           "verify_finished_run", "attempt_versions", "attempt_costs", "build_mismatch"]

#: Layout of a campaign folder (manifest keys, inputs/, runs/NAME/DONE.json) that this package
#: reads and writes, recorded as "format" in manifest.json. A manifest without the key was
#: written before it was recorded and has this layout. Raise it when a change of the layout
#: would make an older TAPMC misread a folder: a folder of another format is refused.
MANIFEST_FORMAT = 1


def sha256(path):
    """Hex SHA-256 of a file's bytes."""
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


#: How the manifest writes a UTC time.
TIME_FORMAT = "%Y-%m-%dT%H:%M:%SZ"


def now():
    """The current UTC time as the manifest writes it."""
    return time.strftime(TIME_FORMAT, time.gmtime())


def seconds_between(start, end_epoch):
    """Seconds from ``start`` (as :func:`now` writes it) to ``end_epoch`` (seconds since the
    epoch, e.g. a file's mtime), rounded to the manifest's precision; never negative."""
    begin = calendar.timegm(time.strptime(start, TIME_FORMAT))
    return max(0.0, round(end_epoch - begin, 3))


def portable_paths(value, campaign_dir):
    """``value`` (nested dicts, lists, strings) with paths inside the campaign folder written
    as ``<campaign>/...`` and paths inside the repository as ``<repo>/...``: a manifest
    committed with its campaign (doc/validation/data) names no folder of the machine it ran
    on. Only what is written changes; the runner never reads these paths back."""
    tree = source_tree()  # an installed package has no repository to name
    prefixes = sorted([(str(Path(campaign_dir).resolve()), "<campaign>")]
                      + ([(str(tree), "<repo>")] if tree else []), key=lambda p: -len(p[0]))

    def fix(text):
        for prefix, tag in prefixes:
            if text == prefix or text.startswith(prefix + os.sep):
                return tag + text[len(prefix):]
        return text

    if isinstance(value, dict):
        return {k: portable_paths(v, campaign_dir) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [portable_paths(v, campaign_dir) for v in value]
    return fix(value) if isinstance(value, str) else value


def read_manifest(directory):
    """manifest.json of a campaign folder as a dict ({} when there is none yet); a manifest
    that cannot be read, is not one, or has another format raises CampaignDirectoryError
    instead of being overwritten, so that a folder is never silently taken over."""
    path = Path(directory) / "manifest.json"
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
    if type(fmt) is not int or fmt != MANIFEST_FORMAT:  # true == 1 and "1" are no format
        raise CampaignDirectoryError(
            f"campaign manifest {path}: format {fmt!r}, this TAPMC reads format "
            f"{MANIFEST_FORMAT}; the campaign was made by another TAPMC version (use that "
            "version, or a new campaign directory)")
    for record in data.get("runs", []):
        _check_run_record(path, record)
    return data


def _check_run_record(path, record):
    """A run's record of the manifest: an object whose attempts are a list of objects, each
    time (wall_s, cpu_s) absent, null or a finite number >= 0; CampaignDirectoryError naming
    the run and the field otherwise (a damaged record broke the price of a dry run)."""
    if not isinstance(record, dict):
        raise CampaignDirectoryError(f"campaign manifest {path}: a run record is {record!r}, "
                                     "not a JSON object")
    name = record.get("name", "?")
    attempts = record.get("attempts", [])
    if not isinstance(attempts, list) or not all(isinstance(a, dict) for a in attempts):
        raise CampaignDirectoryError(f"campaign manifest {path}: run {name!r}: attempts is "
                                     f"{attempts!r}, not a list of attempt records")
    for k, attempt in enumerate(attempts):
        for key in ("wall_s", "cpu_s"):
            value = attempt.get(key)
            if value is not None and (isinstance(value, bool) or
                                      not isinstance(value, (int, float)) or
                                      not math.isfinite(value) or value < 0):
                raise CampaignDirectoryError(
                    f"campaign manifest {path}: run {name!r}, attempt {k + 1}: {key} = "
                    f"{value!r}, not a finite number of seconds >= 0")


def write_manifest(directory, data):
    """Write manifest.json (paths made portable) through a temporary file, so that a kill
    never leaves half a manifest."""
    directory = Path(directory)
    atomic.write_text(directory / "manifest.json",
                      json.dumps(portable_paths(data, directory), indent=1) + "\n")


def lmp_versions(lmp):
    """What ``lmp -h`` says of the executable (a LAMMPS process like the runs, with MPI
    session directories of its own): {"lammps_version": LAMMPS's version, "lmp_build": the
    commit lmp_tapmc was built from (its "TAPMC build:" line)}, each None when not printed
    (another LAMMPS, an older lmp_tapmc) or when the executable cannot run."""
    try:
        with private_mpi_session() as env:
            out = subprocess.run([str(lmp), "-h"], stdin=subprocess.DEVNULL, env=env,
                                 capture_output=True, text=True, timeout=60).stdout
    except (OSError, subprocess.TimeoutExpired):
        out = ""
    version = re.search(r"Simulator - (.+)", out)
    build = re.search(r"^TAPMC build: (\S+)", out, re.MULTILINE)
    return {"lammps_version": version.group(1).strip() if version else None,
            "lmp_build": build.group(1) if build else None}


def tapmc_version():
    """``git describe`` of the TAPMC checkout this package runs from, or None (an installed
    package: never the commit of a repository that merely holds the install or the venv)."""
    repo = git_checkout()
    if repo is None:
        return None
    try:
        out = subprocess.run(["git", "-C", str(repo), "describe", "--always", "--dirty",
                              "--tags"], capture_output=True, text=True, timeout=30)
        return out.stdout.strip() or None
    except (OSError, subprocess.TimeoutExpired):
        return None


def build_mismatch(lmp, lmp_build, tapmc):
    """One sentence when the executable cannot be pinned to the commit of this TAPMC: built
    from another commit (``lmp_build``, its 'TAPMC build:' line, against ``tapmc``, this
    package's ``git describe``; a ``-dirty`` suffix of either is not a commit of its own) or
    from a tree with uncommitted changes; None when they agree or either is unknown (another
    LAMMPS, a TAPMC outside git). A TAPMC_LMP left pointing at an older build otherwise runs a
    whole campaign's attempts under a binary that no commit of it describes."""
    if not lmp_build or not tapmc:
        return None
    clean = lmp_build.removesuffix("-dirty")
    if clean != tapmc.removesuffix("-dirty"):
        why = (f"was built from {lmp_build}, and this TAPMC is {tapmc}: its attempts record "
               f"{lmp_build} as their build")
    elif clean != lmp_build:
        why = (f"was built from {lmp_build}, a tree with uncommitted changes: no commit "
               "describes the binary its attempts run")
    else:
        return None
    return (f"the executable {lmp} {why}; to pin the campaign to one commit, build lmp_tapmc "
            "from a clean tree of this TAPMC (cmake --build) and point TAPMC_LMP or --lmp at "
            "it")


def attempt_versions(record):
    """(versions, unrecorded): the TAPMC versions that ran a run's manifest ``record``
    (``tapmc_version`` of its attempts, in order, each once) and how many of its attempts were
    recorded before attempts carried their version (their version is not known)."""
    versions, unrecorded = [], 0
    for attempt in record.get("attempts", []):
        version = attempt.get("tapmc_version")
        if version is None:
            unrecorded += 1
        elif version not in versions:
            versions.append(version)
    return versions, unrecorded


def attempt_costs(record):
    """What a run's manifest ``record`` says it cost: ``wall_s`` and ``cpu_s``, the sums over
    its attempts (None when no attempt has that time: partition mode measures no CPU time per
    run), and, when some attempts have none (killed with their campaign by SIGKILL, or from
    before attempts recorded it), ``attempts_without_wall_time`` /
    ``attempts_without_cpu_time``: the sums are then lower bounds. DONE.json keeps these."""
    attempts = record.get("attempts", [])
    out = {}
    for key, name in (("wall_s", "wall"), ("cpu_s", "cpu")):
        timed = [a[key] for a in attempts if a.get(key) is not None]
        out[key] = round(sum(timed), 3) if timed else None
        if len(timed) < len(attempts):
            out[f"attempts_without_{name}_time"] = len(attempts) - len(timed)
    return out


def _recorded_sha256(recorded, name):
    """The sha256 a previous manifest's "inputs" recorded for the copy of input ``name``, or
    None (no record, or not one this TAPMC wrote)."""
    entry = recorded.get(name) if isinstance(recorded, dict) else None
    digest = entry.get("sha256") if isinstance(entry, dict) else None
    return digest if isinstance(digest, str) and re.fullmatch(r"[0-9a-f]{64}", digest) \
        else None


def copy_inputs(directory, runs, pin_inputs, stream, recorded=None):
    """Copy each input into <campaign>/inputs once and return the manifest's "inputs" entry;
    the runs execute the copies, so a resumed campaign runs exactly what it started with.

    A copy is written whole or not at all (:func:`atomic.copy_file`: a kill or a full disk
    leaves none; the error names the copy). ``recorded``: the "inputs" of the manifest so far;
    a copy whose sha256 differs from the one recorded (damaged since) is copied again when its
    source still has that sha256, else CampaignDirectoryError names both files, as it does
    for a missing copy whose source changed. An input that changed since the campaign started:
    CampaignDirectoryError, or with ``pin_inputs`` a note on ``stream`` and both digests
    recorded. The entries of ``recorded`` for inputs no run of ``runs`` uses are kept."""
    directory = Path(directory)
    inputs = {}
    folder = directory / "inputs"
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise atomic.named(err, folder) from None
    manifest = directory / "manifest.json"
    for r in runs:
        src = r.input
        if src.name in inputs:
            if inputs[src.name]["source"] != str(src):
                raise ValueError(f"runs: two different inputs named {src.name!r} "
                                 f"({inputs[src.name]['source']} and {src})")
            continue
        digest = sha256(src)
        copy = folder / src.name
        entry = {"source": str(src), "sha256": digest,
                 "copy": str(copy.relative_to(directory))}
        known = _recorded_sha256(recorded, src.name)
        if copy.exists() and known is not None and sha256(copy) != known:
            if digest != known:
                raise CampaignDirectoryError(
                    f"input copy {copy}: its sha256 differs from the one {manifest} recorded, "
                    f"and so does its source {src}: the input this campaign started with is "
                    "gone; put it back in either place or use a new campaign directory")
            atomic.copy_file(src, copy)
            print(f"[campaign] input copy {copy}: its sha256 differed from the one "
                  f"{manifest.name} recorded (damaged since); copied again from {src}, which "
                  "has it", file=stream, flush=True)
        if copy.exists() and sha256(copy) != digest:
            if not pin_inputs:
                raise CampaignDirectoryError(
                    f"input {src}: differs from the copy this campaign started with "
                    f"({copy}); use a new campaign directory")
            entry.update(sha256=sha256(copy), source_sha256=digest)
            print(f"[campaign] input {src} changed since this campaign started; its runs "
                  f"keep executing the campaign's copy {copy}", file=stream, flush=True)
        if not copy.exists():
            if known is not None and digest != known:
                raise CampaignDirectoryError(
                    f"input copy {copy}: missing, and its source {src} differs from the "
                    f"sha256 {manifest} recorded for the copy: the input this campaign "
                    "started with is gone; put it back in either place or use a new campaign "
                    "directory")
            atomic.copy_file(src, copy)
        inputs[src.name] = entry
    # the inputs of runs this session does not run keep their records (a session of some runs
    # dropped them, and a changed input of the others then went unnoticed)
    for name, entry in (recorded.items() if isinstance(recorded, dict) else ()):
        inputs.setdefault(name, entry)
    return inputs


def read_done(done_file):
    """The record of a finished run (DONE.json) as a dict with at least "run"; one that
    cannot be read raises CampaignDirectoryError naming it."""
    try:
        done = json.loads(Path(done_file).read_text())
        if not isinstance(done["run"], dict):
            raise TypeError(f"'run' is {type(done['run']).__name__}, not an object")
        outputs = done.get("outputs", {})
        if not isinstance(outputs, dict) or not all(
                isinstance(v, dict) and "sha256" in v and "size" in v for v in outputs.values()):
            raise TypeError("'outputs' is not an object of {sha256, size} per file")
    except (OSError, ValueError, KeyError, TypeError) as err:
        raise CampaignDirectoryError(f"{done_file}: cannot be read as the record of "
                                     f"a finished run ({err!r})") from None
    return done


def write_done(run_dir, done):
    """Write DONE.json, the mark of a finished run, last and through a temporary file."""
    atomic.write_text(Path(run_dir) / "DONE.json", json.dumps(done, indent=1) + "\n")


def output_digests(run_dir, names):
    """{name: {"sha256", "size"}} of the files ``names`` of a run folder (DONE.json's
    "outputs")."""
    run_dir = Path(run_dir)
    return {name: {"sha256": sha256(run_dir / name), "size": (run_dir / name).stat().st_size}
            for name in names}


#: Outputs a finished run may lack without being damaged: its final restart file continues
#: the run (a longer run, a later protocol) but no figure reads it, and a campaign committed
#: with the project (doc/validation/data) leaves it out to stay small.
OPTIONAL_OUTPUTS = re.compile(r"restart\.\d+")


def damaged_outputs(run_dir, recorded):
    """{name: what is wrong} for the files of ``recorded`` (DONE.json's "outputs") that are
    missing (unless OPTIONAL_OUTPUTS) or whose size or sha256 differ from the record; {} when
    all are intact. A temporary file of the campaign's own writes (``NAME.tmp``) that an older
    TAPMC recorded as an output is no output."""
    run_dir = Path(run_dir)
    damaged = {}
    for name, digest in recorded.items():
        if atomic.is_temporary(name):
            continue
        path = run_dir / name
        if not path.is_file() and OPTIONAL_OUTPUTS.fullmatch(name):
            continue
        if not path.is_file():
            damaged[name] = "missing"
        elif path.stat().st_size != digest["size"]:
            damaged[name] = (f"{path.stat().st_size} bytes, {digest['size']} when the run "
                             "finished")
        elif sha256(path) != digest["sha256"]:
            damaged[name] = "sha256 differs from the one recorded when the run finished"
    return damaged


def _recorded_taps_file(run, done_file):
    """The per-tap file a DONE.json's "run" names (its ``taps_file`` variable, else
    taps.dat, as RunSpec.taps_file)."""
    variables = run.get("variables", {})
    if not isinstance(variables, dict):
        raise CampaignDirectoryError(f"{done_file}: 'run.variables' is "
                                     f"{type(variables).__name__}, not an object")
    return str(variables.get("taps_file", "taps.dat"))


def verify_finished_run(run_dir, spec=None):
    """Check that the finished run in ``run_dir`` can be read as it is, and return its
    record (DONE.json as a dict). What reads a campaign without running it (``tapmc-paper
    report --finished-only``) calls this first, for every finished run it reads.

    CampaignDirectoryError, naming DONE.json and what is wrong, when the record is missing,
    cannot be read (cut, not JSON, not an object with "run"), names another run than its
    folder's, or records other parameters than ``spec`` (a RunSpec, when given), or lists
    outputs without the run's per-tap file (an incomplete record). CampaignError, naming
    each damaged file and what differs, when an output it lists is missing or its size or
    sha256 differ from the record (:func:`damaged_outputs`): the run changed since it
    finished, and only a campaign run (``Campaign.run``) may run it again. A DONE.json
    written before TAPMC recorded the outputs has no checksums and is trusted as it is, as
    ``Campaign.run`` trusts it."""
    run_dir = Path(run_dir)
    done_file = run_dir / "DONE.json"
    if not done_file.is_file():
        raise CampaignDirectoryError(f"{done_file}: missing; the run {run_dir.name!r} has not "
                                     "finished")
    done = read_done(done_file)
    run = done["run"]
    if run.get("name") != run_dir.name:
        raise CampaignDirectoryError(f"{done_file}: records the run {run.get('name')!r}, not "
                                     f"{run_dir.name!r} of its folder")
    if spec is not None and run != json.loads(json.dumps(spec.describe())):
        raise CampaignDirectoryError(f"{done_file}: records other parameters ({run}) than the "
                                     f"run {spec.name!r} asked for ({spec.describe()})")
    recorded = done.get("outputs")
    if recorded is None:
        return done
    taps_file = _recorded_taps_file(run, done_file)
    if taps_file not in recorded:
        raise CampaignDirectoryError(f"{done_file}: its outputs do not list the per-tap file "
                                     f"{taps_file}; an incomplete record of a finished run")
    damaged = damaged_outputs(run_dir, recorded)
    if damaged:
        files = "; ".join(f"{run_dir / name}: {what}" for name, what in sorted(damaged.items()))
        raise CampaignError(f"run {run_dir.name!r} changed since it finished ({done_file} "
                            f"records its outputs): {files}; running the campaign again "
                            "redoes it")
    return done
