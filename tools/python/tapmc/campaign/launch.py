# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Starting LAMMPS processes for a campaign: the executable, the cores this process may use,
the lock that keeps one runner per folder, one run as a child that dies with its parent, and
the batches, driver input and command line of LAMMPS's ``-partition`` mode."""

import contextlib
import ctypes
import fcntl
import os
import shutil
import signal
import subprocess
import tempfile
from pathlib import Path

from .._source import source_tree
from .errors import CampaignDirectoryError, CampaignError

__all__ = ["find_lmp", "available_cores", "campaign_lock", "child_setup", "run_child",
           "run_child_timed", "private_mpi_session", "mpirun_prefix",
           "lammps_command", "partition_batches", "partition_driver", "partition_command"]



def find_lmp(lmp=None):
    """Path of the LAMMPS executable: ``lmp``, else $TAPMC_LMP, else the repository's
    build/lmp_tapmc, else ``lmp_tapmc`` on the PATH. An ``lmp`` or a $TAPMC_LMP that is no
    executable file is FileNotFoundError naming it, never replaced by another build."""
    if lmp is not None:
        if Path(lmp).is_file() and os.access(lmp, os.X_OK):
            return Path(lmp).resolve()
        raise FileNotFoundError(f"lmp = {str(lmp)!r}: not an executable file")
    env = os.environ.get("TAPMC_LMP")
    if env:
        if Path(env).is_file() and os.access(env, os.X_OK):
            return Path(env).resolve()
        raise FileNotFoundError(f"TAPMC_LMP = {env!r}: not an executable file (unset it for "
                                "build/lmp_tapmc or lmp_tapmc on the PATH, or pass --lmp)")
    tree = source_tree()  # the source tree's build first; an installed package has none
    candidates = [tree / "build" / "lmp_tapmc" if tree else None, shutil.which("lmp_tapmc")]
    for c in candidates:
        if c and Path(c).is_file() and os.access(c, os.X_OK):
            return Path(c).resolve()
    raise FileNotFoundError("no LAMMPS executable: build TAPMC (build/lmp_tapmc), set TAPMC_LMP "
                            "or pass lmp=PATH")


def available_cores():
    """Cores this process may run on: its CPU affinity (``taskset``, a batch system's cgroup
    cpuset) where the system reports it, else all cores of the machine."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return os.cpu_count() or 1


@contextlib.contextmanager
def campaign_lock(directory):
    """Hold ``<directory>/campaign.lock`` (created with the folder if needed) while the block
    runs: a second runner of the same folder gets CampaignError instead of racing this one.
    Yields the open lock file: the lock (flock) belongs to its open file description, so a
    LAMMPS child given its descriptor (``run_child``'s ``keep_fds``) holds the lock as long as
    it runs, also when its runner was killed; the lock is free when every holder is gone."""
    directory = Path(directory)
    try:
        directory.mkdir(parents=True, exist_ok=True)
        lockfile = open(directory / "campaign.lock", "w")
    except OSError as err:
        raise CampaignDirectoryError(
            f"campaign directory {directory}: cannot be created or written "
            f"({err.strerror}: {err.filename})") from None
    with lockfile:
        try:
            fcntl.flock(lockfile, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            raise CampaignError(
                f"campaign {directory} is being run by another process (campaign.lock is held: "
                "by another runner, or by a LAMMPS run a killed runner left, until it ends; "
                f"fuser -v {directory / 'campaign.lock'} names them)") from None
        yield lockfile


try:
    _LIBC = ctypes.CDLL("libc.so.6", use_errno=True)
except OSError:  # not glibc: no parent-death signal
    _LIBC = None
_PR_SET_PDEATHSIG = 1


def child_setup(parent):
    """The function a LAMMPS child runs between fork and exec (Popen's preexec_fn) so that it
    dies with its runner, the process ``parent`` (its pid): SIGTERM and SIGINT back to their
    default action unless ignored (inherited from the fork, the runner's Python handler would
    catch the parent-death signal and the child would go on), the parent-death signal SIGTERM
    (Linux's prctl), then a check that the runner still is its parent: one killed before the
    prctl is not seen by it, and the child then ends itself as the signal would have."""
    def setup():
        for signum in (signal.SIGTERM, signal.SIGINT):
            if signal.getsignal(signum) is not signal.SIG_IGN:
                signal.signal(signum, signal.SIG_DFL)
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGTERM})
        if _LIBC is not None:
            _LIBC.prctl(_PR_SET_PDEATHSIG, signal.SIGTERM)
        if os.getppid() != parent:
            os.kill(os.getpid(), signal.SIGTERM)  # unblocked, default: it ends the child here
            raise ChildProcessError(f"the runner {parent} is gone")  # not reached
    return setup


# Open MPI 4 keeps a session directory per job under <base>/ompi.<host>.<uid>, created in
# MPI_Init and removed, up to <base>/ompi.<host>.<uid>, in MPI_Finalize. Processes started
# without mpirun under OMPI_MCA_ess_singleton_isolated=1 (the fast start the user guide and the
# test suite use) all take the same one, jf.0/1/0: a run that starts while another one ends can
# find its parent removed between two mkdirs and die in MPI_Init ("ORTE_ERROR_LOG ...
# session_dir.c"). Beside a loop that ends such processes, 4 of 30 starts died; 0 of 30 with a
# base of their own (tests/python/test_campaign.py). The variable is Open MPI 4's; other MPIs
# ignore it.
_MPI_SESSION_BASE = "OMPI_MCA_orte_tmpdir_base"


@contextlib.contextmanager
def private_mpi_session():
    """Environment for one child whose MPI session directories nobody else shares: a fresh
    folder under the user's ``OMPI_MCA_orte_tmpdir_base`` (made if missing, as Open MPI would)
    or else the system's temporary folder, removed when the block ends. Where no folder can be
    made, the environment is unchanged."""
    base = os.environ.get(_MPI_SESSION_BASE) or None
    try:
        if base:
            os.makedirs(base, exist_ok=True)
        private = tempfile.mkdtemp(prefix="tapmc-mpi-", dir=base)
    except OSError:
        yield dict(os.environ)
        return
    try:
        yield dict(os.environ, **{_MPI_SESSION_BASE: private})
    finally:
        shutil.rmtree(private, ignore_errors=True)


def run_child(cmd, cwd, screen, started=None, keep_fds=()):
    """Run ``cmd`` in ``cwd`` with its output in the file ``screen``, as a child that dies with
    this process (:func:`child_setup`) and has MPI session directories of its own; returns its
    exit status. ``keep_fds``: descriptors the child inherits (the campaign's lock)."""
    return run_child_timed(cmd, cwd, screen, started, keep_fds)[0]


def run_child_timed(cmd, cwd, screen, started=None, keep_fds=()):
    """:func:`run_child`, returning (exit status, CPU seconds of the child: user + system).
    The CPU time is the child's own (wait4), whatever else runs at the same time: what a run
    costs on one core (tapmc.paper.front prices its settings by it). ``started``: called with
    the child's Popen once it runs (a campaign that is stopped signals its children)."""
    with open(screen, "w") as out, private_mpi_session() as env:
        proc = subprocess.Popen(cmd, cwd=cwd, stdin=subprocess.DEVNULL, stdout=out, env=env,
                                stderr=subprocess.STDOUT, preexec_fn=child_setup(os.getpid()),
                                pass_fds=tuple(keep_fds))
        try:
            if started is not None:
                started(proc)
            _, status, usage = os.wait4(proc.pid, 0)
        except BaseException:
            proc.kill()
            proc.wait()
            raise
        proc.returncode = os.waitstatus_to_exitcode(status)
    return proc.returncode, usage.ru_utime + usage.ru_stime


def mpirun_prefix(nprocs):
    """``mpirun -np nprocs`` from $TAPMC_MPIRUN, else ``mpirun`` (plus --allow-run-as-root
    as root, --oversubscribe beyond the cores this process may use)."""
    env = os.environ.get("TAPMC_MPIRUN")
    if env:
        cmd = env.split()
    else:
        cmd = ["mpirun"]
        if hasattr(os, "geteuid") and os.geteuid() == 0:
            cmd.append("--allow-run-as-root")
        if nprocs > available_cores():
            cmd.append("--oversubscribe")
    return cmd + ["-np", str(nprocs)]


def lammps_command(lmp, spec, input_copy, resume):
    """Command line of one run in pool mode: the input copy, the run's variables and seed,
    the ``resume`` variables, under mpirun when the run has several ranks."""
    cmd = [str(lmp), "-nocite", "-in", str(input_copy), "-log", "log.lammps",
           "-screen", "none"] + spec.var_args()
    for key, value in resume.items():
        cmd += ["-var", key, value]
    return mpirun_prefix(spec.nprocs) + cmd if spec.nprocs > 1 else cmd


def partition_batches(pending, jobs):
    """Groups of at most ``jobs`` runs that one -partition mpirun can run together: same
    input, same ranks, same variable names, equal multi-valued variables."""
    groups = {}
    for spec in pending:
        multi = tuple(sorted((k, tuple(map(str, v))) for k, v in spec.variables.items()
                             if isinstance(v, (list, tuple))))
        key = (str(spec.input), spec.nprocs, tuple(sorted(spec.variables)), multi)
        groups.setdefault(key, []).append(spec)
    batches = []
    for specs in groups.values():
        for i in range(0, len(specs), jobs):
            batches.append(specs[i:i + jobs])
    return batches


def _lammps_word(text):
    """``text`` as one word of a LAMMPS input line: as it is, or in double quotes when it holds
    a space, a single quote, ``#`` or ``$`` (LAMMPS splits on spaces, and reads # and $
    outside quotes); CampaignError for a double quote, which no quoting keeps."""
    if '"' in text:
        raise CampaignError(f"partition mode: {text} holds a double quote, which a LAMMPS "
                            "input line cannot quote; rename it, or use mode='pool'")
    return f'"{text}"' if any(c.isspace() or c in "'#$" for c in text) else text


def partition_driver(batch, run_dirs, resumes, input_copy, cwd=None):
    """Text of the driver input of a batch: each partition goes to its run's folder and sets
    its run's variables, seed and resume through world-style variables, then includes the
    input copy. ``run_dirs`` and ``resumes`` map run names to folders and resume variables.
    ``cwd``: the folder LAMMPS runs the driver in; the run folders are then written relative
    to it and the input copy relative to the run folders, so that a campaign path with spaces
    in it works (a world variable takes one value per word, and ``shell cd ${run_dir}`` sees
    the words of its value: no quoting keeps a value of several words together)."""
    first = batch[0]
    dirs = [Path(run_dirs[s.name]) for s in batch]
    include = Path(input_copy)
    if cwd is not None:
        dirs = [Path(os.path.relpath(d, cwd)) for d in dirs]
        include = Path(os.path.relpath(input_copy, run_dirs[first.name]))
    for d in dirs:
        if any(c.isspace() or c in "\"'#$" for c in str(d)):
            raise CampaignError(f"partition mode: run folder {d} holds a space, a quote, # or "
                                "$, which a LAMMPS world variable cannot hold; use a campaign "
                                "folder without them, or mode='pool'")
    lines = ["# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.",
             "# Written by tapmc.campaign: one run per partition, each in its own folder.",
             "variable run_dir world " + " ".join(str(d) for d in dirs),
             "shell cd ${run_dir}", "log log.lammps"]
    single = [k for k, v in first.variables.items() if not isinstance(v, (list, tuple))]
    for key in single + ["seed", "resume", "resume_file"]:
        values = []
        for s in batch:
            if key == "seed":
                values.append(str(s.seed))
            elif key in ("resume", "resume_file"):
                values.append(str(resumes[s.name][key]))
            else:
                value = str(s.variables[key])
                values.append(f'"{value}"' if " " in value else value)  # Words: one value
        lines.append(f"variable {key} world " + " ".join(values))
    lines.append(f"include {_lammps_word(str(include))}")
    return "\n".join(lines) + "\n"


def partition_command(lmp, batch, driver, log):
    """``mpirun ... lmp_tapmc -partition PxN -in driver``, with the batch's multi-valued
    variables (equal for every run of a batch) on the command line."""
    first = batch[0]
    cmd = mpirun_prefix(len(batch) * first.nprocs) + [
        str(lmp), "-nocite", "-partition", f"{len(batch)}x{first.nprocs}",
        "-in", str(driver), "-log", str(log), "-plog", "none", "-pscreen", "none"]
    for key, value in first.variables.items():
        if isinstance(value, (list, tuple)):
            cmd += ["-var", key] + [str(v) for v in value]
    return cmd
