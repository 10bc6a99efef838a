#!/usr/bin/python3
# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Run time against error of every redeposition setting of fix mc/settle on the paper's tapping
# protocol (examples/paper/in.constant_eps), over taps 1 to 1000 and the steady state.
"""Run-time-versus-error front of fix mc/settle on the paper's protocol.

Every run is examples/paper/in.constant_eps (fresh Jullien-Meakin packing, PBC, T taps at
constant eps) with one redeposition setting (eta, stop rule, d_max, check interval) and one seed;
the seed also fixes the initial packing, so the settings are compared seed by seed (paired).
A run keeps its per-tap table (taps.dat: Phi_b, <Phi^c>, <Z>, sweeps, ...) gzipped, and one row of
runs.csv with its CPU time (user + system of the lmp process). The analysis (bias of each
setting against the reference after 1, 10, 100 and 1000 taps and in the steady window, cost,
recommended settings, the doc page and its figure) is tapmc.paper.front; this script only runs.

Runs are independent and resumable: a finished run is never run again (its row is in runs.csv);
a run works in <out>/work/... with a restart file every 1/20 of its taps, and a stopped run
(SIGTERM or Ctrl-C to this script) resumes from its latest restart, bit for bit the same taps,
its CPU time counted for the taps it kept. --jobs runs several at once (one core each).

Usage:
  /usr/bin/python3 bench/paper_front.py [--lmp build/lmp_tapmc] [--N 1024] [--taps 1000]
        [--seeds 4] [--eps 0.0225,0.1] [--settings all|name,name] [--jobs 2]
        [--out doc/validation/front] [--list]
"""

import argparse
import concurrent.futures
import csv
import gzip
import json
import os
import shutil
import signal
import subprocess
import sys
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tools", "python"))
# the campaign runner's restart finder: it skips an empty file that a kill left behind
from tapmc.campaign.run_folder import latest_restart  # noqa: E402
from tapmc.paper import front  # noqa: E402  (settings, file layout and the analysis)

INPUT = os.path.join(ROOT, "examples", "paper", "in.constant_eps")
WORK = "work"                # <out>/work/<N_eps>/<setting>_s<seed>/: a run until it ends
ATTEMPTS = "attempts.json"   # per attempt: first and last tap, CPU and wall seconds, sweeps
RESTARTS_PER_RUN = 20        # restart files per run (N = 4096, 1000 taps: one every 50 taps)


def write_meta(out_dir, lmp, jobs, nice):
    """meta.json of the front (once, at its first run): what built the binary and where it ran."""
    import platform
    path = os.path.join(out_dir, front.META)
    if os.path.exists(path):
        return
    commit = subprocess.run(["git", "-C", ROOT, "describe", "--always", "--dirty"],
                            capture_output=True, text=True).stdout.strip() or "unknown"
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(l.split(":", 1)[1].strip() for l in f if l.startswith("model name"))
    except (OSError, StopIteration):
        pass
    # the executable's name only: the data must not carry one machine's paths
    meta = {"commit": commit, "lmp": os.path.basename(lmp), "machine": cpu, "cores": os.cpu_count(), "jobs": jobs,
            "nice": nice, "started": time.strftime("%Y-%m-%d", time.gmtime())}
    os.makedirs(out_dir, exist_ok=True)
    with open(path, "w") as f:
        json.dump(meta, f, indent=1, sort_keys=True)
        f.write("\n")


def work_dir(out_dir, setting, N, eps, seed):
    """The folder a run works in until it ends: restart files, taps.dat and its attempts."""
    taps_gz = front.taps_path(out_dir, setting, N, eps, seed)
    rel = os.path.relpath(taps_gz, os.path.join(out_dir, "taps"))
    return os.path.join(out_dir, WORK, rel[:-len(".dat.gz")])


def trim_taps(path, last_step):
    """Keeps the complete rows of taps.dat up to `last_step`, each step once, under one header:
    a killed attempt may have written taps past its last restart, and half a line; a resumed
    attempt writes the header and the row of its restart step again (the same numbers)."""
    kept, steps, header = [], set(), False
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                if not header:
                    kept.append(line)
                header = True
                continue
            words = line.split()
            if len(words) != len(front.TAPS_COLUMNS) or not line.endswith("\n"):
                continue  # half a row: the attempt was killed while writing it
            step = int(float(words[0]))
            if step <= last_step and step not in steps:
                steps.add(step)
                kept.append(line)
    with open(path + ".part", "w") as f:
        f.writelines(kept)
    os.replace(path + ".part", path)


def sweeps_between(path, first, last):
    """Sum of the sweeps of the taps first < step <= last in taps.dat."""
    if not os.path.exists(path):
        return 0.0
    return sum(r["sweeps"] for r in front.read_taps(path) if first < r["step"] <= last)


def last_complete_step(path):
    rows = front.read_taps(path) if os.path.exists(path) else []
    return rows[-1]["step"] if rows else 0


def load_attempts(work):
    path = os.path.join(work, ATTEMPTS)
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return json.load(f)


def save_attempts(work, attempts):
    path = os.path.join(work, ATTEMPTS)
    with open(path + ".part", "w") as f:
        json.dump(attempts, f, indent=1)
        f.write("\n")
    os.replace(path + ".part", path)


def lmp_command(lmp, setting, N, eps, taps, seed, nice, resume_file=None):
    keys = front.settle_keys(setting, N)
    cmd = [lmp, "-in", INPUT, "-var", "N", str(N), "-var", "L", "%g" % front.box_side_R(N),
           "-var", "eps", "%g" % eps, "-var", "taps", str(taps), "-var", "seed", str(seed),
           "-var", "eta", front.SETTINGS[setting]["eta"], "-var", "settle_keys", keys,
           "-var", "rsteps", str(restart_every(taps)),
           "-var", "thermo_every", str(max(1, taps // 10)), "-log", "log.lammps",
           "-screen", "none", "-echo", "none"]
    if resume_file:
        cmd += ["-var", "resume", "yes", "-var", "resume_file", resume_file]
    if nice:
        cmd = ["nice", "-n", str(nice)] + cmd
    return cmd


def restart_every(taps):
    """Taps between restart files: RESTARTS_PER_RUN of them, so a killed run loses little."""
    return max(1, taps // RESTARTS_PER_RUN)


def run_attempt(lmp, setting, N, eps, taps, seed, work, nice, children=None):
    """One attempt of a run in `work`: from its latest restart (rows past it trimmed and the
    killed attempt's CPU cut to what it kept), or fresh. Records the attempt in attempts.json.
    Returns True when the run reached `taps`."""
    taps_dat = os.path.join(work, "taps.dat")
    attempts = load_attempts(work)
    step, path = latest_restart(work)
    restart = None if path is None else path.name
    if restart is None:
        step = 0
        attempts = []
        if os.path.exists(taps_dat):
            os.remove(taps_dat)
    else:
        trim_taps(taps_dat, step)
        # the previous attempt keeps the CPU of the taps it kept, by their share of its sweeps
        if attempts and "kept_cpu" not in attempts[-1]:
            a = attempts[-1]
            kept = sweeps_between(taps_dat, a["start"], min(step, a["end"]))
            a["kept_sweeps"] = kept
            a["kept_cpu"] = a["cpu"] * kept / a["sweeps"] if a["sweeps"] > 0 else 0.0
    cmd = lmp_command(lmp, setting, N, eps, taps, seed, nice, restart)
    t0 = time.time()
    proc = subprocess.Popen(cmd, cwd=work, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            env=dict(os.environ, OMP_NUM_THREADS="1"))
    if children is not None:
        children.add(proc)
    # wait4: this child's own CPU time, whatever else runs at the same time
    _, status, usage = os.wait4(proc.pid, 0)
    if children is not None:
        children.discard(proc)
    err = proc.stderr.read().decode(errors="replace")
    proc.stderr.close()
    rc = os.waitstatus_to_exitcode(status)
    end = last_complete_step(taps_dat)
    attempts.append({"start": step, "end": end, "cpu": usage.ru_utime + usage.ru_stime,
                     "wall": time.time() - t0, "sweeps": sweeps_between(taps_dat, step, end),
                     "rc": rc})
    save_attempts(work, attempts)
    if rc == 0:
        return True
    if rc < 0 or rc == 128 + 15:  # killed by a signal: resumable
        return False
    tail = err[-1500:]
    logpath = os.path.join(work, "log.lammps")
    if os.path.exists(logpath):
        with open(logpath) as f:
            tail = f.read()[-1500:]
    raise RuntimeError("lmp failed (rc %d): %s\n%s" % (rc, " ".join(cmd), tail))


def run_cpu_seconds(attempts, total_sweeps):
    """CPU seconds of a run: every attempt's CPU for the taps it kept (the last one all of its
    own), scaled to all the run's sweeps when an attempt's record is missing (a hard kill)."""
    cpu = sweeps = 0.0
    for a in attempts:
        cpu += a.get("kept_cpu", a["cpu"])
        sweeps += a.get("kept_sweeps", a["sweeps"])
    return cpu * total_sweeps / sweeps if sweeps > 0 else cpu


def run_one(lmp, setting, N, eps, taps, seed, out_dir, nice, children=None):
    """Runs (or resumes) one setting for one seed; returns its runs.csv row (taps.dat gzipped
    into out_dir), or None when the run was stopped before its end (resumable)."""
    work = work_dir(out_dir, setting, N, eps, seed)
    os.makedirs(work, exist_ok=True)
    if not run_attempt(lmp, setting, N, eps, taps, seed, work, nice, children):
        return None
    taps_dat = os.path.join(work, "taps.dat")
    trim_taps(taps_dat, taps)
    table = front.read_taps(taps_dat)
    if len(table) != taps or [r["step"] for r in table] != list(range(1, taps + 1)):
        raise RuntimeError("%s: taps.dat has %d rows, expected steps 1..%d" % (setting, len(table), taps))
    attempts = load_attempts(work)
    dest = front.taps_path(out_dir, setting, N, eps, seed)
    os.makedirs(os.path.dirname(dest), exist_ok=True)
    with open(taps_dat, "rb") as src, gzip.open(dest + ".part", "wb") as gz:
        shutil.copyfileobj(src, gz)
    os.replace(dest + ".part", dest)
    total_sweeps = sum(r["sweeps"] for r in table)
    cpu = run_cpu_seconds(attempts, total_sweeps)
    wall = sum(a["wall"] for a in attempts)
    shutil.rmtree(work)
    try:  # and its empty parents, up to <out>/work
        os.removedirs(os.path.dirname(work))
    except OSError:
        pass
    return {"setting": setting, "N": N, "eps": "%g" % eps, "seed": seed, "taps": taps,
            "eta": front.SETTINGS[setting]["eta"], "settle_keys": front.settle_keys(setting, N),
            "cpu_s": "%.2f" % cpu, "wall_s": "%.1f" % wall, "cpu_per_tap": "%.5f" % (cpu / taps),
            "sweeps_per_tap": "%.1f" % (total_sweeps / taps),
            "capped_taps": sum(1 for r in table if r["capped"] > 0)}


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--lmp", default=os.path.join(ROOT, "build", "lmp_tapmc"))
    ap.add_argument("--N", type=int, default=1024, help="spheres (box side 32R sqrt(N/4096))")
    ap.add_argument("--taps", type=int, default=front.TAPS, help="taps per run (default %(default)s)")
    ap.add_argument("--seeds", type=int, default=4, help="seeds per setting (default 4)")
    ap.add_argument("--eps", default=",".join("%g" % e for e in front.EPS),
                    help="comma list of tap strengths (default %(default)s)")
    ap.add_argument("--settings", default="all",
                    help="comma list among %s, or all" % ", ".join(front.SETTINGS))
    ap.add_argument("--jobs", type=int, default=1, help="runs at once (default 1)")
    ap.add_argument("--nice", type=int, default=0, help="nice level of the lmp processes")
    ap.add_argument("--out", default=os.path.join(ROOT, front.DATA_DIR))
    ap.add_argument("--list", action="store_true", help="print the runs still to do and stop")
    args = ap.parse_args()

    names = list(front.SETTINGS) if args.settings == "all" else args.settings.split(",")
    bad = [n for n in names if n not in front.SETTINGS]
    if bad:
        ap.error("--settings: unknown %s (allowed: %s, all)" % (",".join(bad), ", ".join(front.SETTINGS)))
    try:
        eps_list = [float(e) for e in args.eps.split(",")]
    except ValueError:
        ap.error("--eps %r: expected a comma list of numbers" % args.eps)
    if args.N < 64 or args.taps < 1 or args.seeds < 1 or args.jobs < 1:
        ap.error("--N >= 64, --taps >= 1, --seeds >= 1 and --jobs >= 1 (got %d, %d, %d, %d)"
                 % (args.N, args.taps, args.seeds, args.jobs))
    if any(not 0 < e < 1 for e in eps_list):
        ap.error("--eps values must be in (0, 1), got %s" % args.eps)
    lmp = os.path.abspath(args.lmp)
    if not args.list and not os.access(lmp, os.X_OK):
        ap.error("--lmp %s is not an executable" % lmp)

    runs_csv = os.path.join(args.out, "runs.csv")
    done = {front.run_key(r) for r in front.read_runs(runs_csv)}
    todo = []
    # seed-major, cheap settings first: a partial front still covers every setting
    for seed in front.seeds(args.seeds):
        for eps in eps_list:
            for name in names:
                if not front.wanted(name, eps):
                    continue
                key = (name, args.N, "%g" % eps, seed, args.taps)
                if key not in done:
                    todo.append(key)
    print("paper_front: %d runs to do (N %d, %d taps, eps %s), %d done; out %s"
          % (len(todo), args.N, args.taps, args.eps, len(done), args.out))
    if args.list:
        for key in todo:
            print("  %s N %d eps %s seed %d" % key[:4])
        return 0
    sys.stdout.flush()
    os.makedirs(args.out, exist_ok=True)
    write_meta(args.out, lmp, args.jobs, args.nice)
    lock = threading.Lock()
    start = time.time()
    finished = [0]
    children = set()   # lmp processes running now
    stopping = threading.Event()

    def stop(signum, frame):
        # SIGTERM / Ctrl-C: stop the lmp processes; each run keeps its taps up to its latest
        # restart and the CPU they cost, and resumes from there next time
        stopping.set()
        for proc in list(children):
            try:
                proc.terminate()
            except OSError:
                pass

    signal.signal(signal.SIGTERM, stop)
    signal.signal(signal.SIGINT, stop)

    def job(key):
        if stopping.is_set():
            return
        name, N, eps, seed, taps = key
        row = run_one(lmp, name, N, float(eps), taps, seed, args.out, args.nice, children)
        if row is None:
            if not stopping.is_set():
                raise RuntimeError("%s N %d eps %s seed %d: lmp was killed from outside" % key[:4])
            return
        with lock:
            new = not os.path.exists(runs_csv)
            with open(runs_csv, "a", newline="") as f:
                w = csv.DictWriter(f, fieldnames=front.RUN_FIELDS)
                if new:
                    w.writeheader()
                w.writerow(row)
            finished[0] += 1
            elapsed = time.time() - start
            eta_s = elapsed / finished[0] * (len(todo) - finished[0])
            print("  [%d/%d] %-24s N %d eps %-6s seed %d: %.3f CPU s/tap, %s sweeps/tap "
                  "(elapsed %.0f s, ETA %.0f s)" % (finished[0], len(todo), name, N, eps, seed,
                                                    float(row["cpu_per_tap"]), row["sweeps_per_tap"],
                                                    elapsed, eta_s))
            sys.stdout.flush()

    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = [pool.submit(job, key) for key in todo]
        while not all(f.done() for f in futures):
            # short waits, so that a signal is handled at once (in this thread)
            concurrent.futures.wait(futures, timeout=1.0)
        for fut in futures:
            fut.result()
    if stopping.is_set():
        print("paper_front: stopped; %d runs finished, the rest resume from their restart files"
              % finished[0])
        return 3
    return 0


if __name__ == "__main__":
    sys.exit(main())
