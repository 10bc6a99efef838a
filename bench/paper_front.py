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
a killed run starts again from its beginning. --jobs runs several at once (one core each).

Usage:
  /usr/bin/python3 bench/paper_front.py [--lmp build/lmp_tapmc] [--N 1024] [--taps 1000]
        [--seeds 4] [--eps 0.0225,0.1] [--settings all|name,name] [--jobs 2]
        [--out doc/validation/front] [--list]
"""

import argparse
import concurrent.futures
import csv
import gzip
import os
import shutil
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tools", "python"))
from tapmc.paper import front  # noqa: E402  (settings, file layout and the analysis)

INPUT = os.path.join(ROOT, "examples", "paper", "in.constant_eps")


def write_meta(out_dir, lmp, jobs, nice):
    """meta.json of the front (once, at its first run): what built the binary and where it ran."""
    import json
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


def run_one(lmp, setting, N, eps, taps, seed, out_dir, nice):
    """Runs one setting for one seed; returns its runs.csv row (taps.dat gzipped into out_dir)."""
    keys = front.settle_keys(setting, N)
    eta = front.SETTINGS[setting]["eta"]
    with tempfile.TemporaryDirectory(prefix="tapmc_front_") as tmp:
        cmd = [lmp, "-in", INPUT, "-var", "N", str(N), "-var", "L", "%g" % front.box_side_R(N),
               "-var", "eps", "%g" % eps, "-var", "taps", str(taps), "-var", "seed", str(seed),
               "-var", "eta", eta, "-var", "settle_keys", keys, "-var", "rsteps", str(10 * taps),
               "-var", "thermo_every", str(max(1, taps // 10)), "-log", "log.lammps",
               "-screen", "none", "-echo", "none"]
        if nice:
            cmd = ["nice", "-n", str(nice)] + cmd
        t0 = time.time()
        proc = subprocess.Popen(cmd, cwd=tmp, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                env=dict(os.environ, OMP_NUM_THREADS="1"))
        # wait4: this child's own CPU time, whatever else runs at the same time
        _, status, usage = os.wait4(proc.pid, 0)
        err = proc.stderr.read().decode(errors="replace")
        proc.stderr.close()
        wall = time.time() - t0
        rc = os.waitstatus_to_exitcode(status)
        if rc != 0:
            tail = err[-1500:]
            logpath = os.path.join(tmp, "log.lammps")
            if os.path.exists(logpath):
                with open(logpath) as f:
                    tail = f.read()[-1500:]
            raise RuntimeError("lmp failed (rc %d): %s\n%s" % (rc, " ".join(cmd), tail))
        table = front.read_taps(os.path.join(tmp, "taps.dat"))
        if len(table) != taps or table[-1]["step"] != taps:
            raise RuntimeError("%s: taps.dat has %d rows, expected %d" % (setting, len(table), taps))
        dest = front.taps_path(out_dir, setting, N, eps, seed)
        os.makedirs(os.path.dirname(dest), exist_ok=True)
        with open(os.path.join(tmp, "taps.dat"), "rb") as src, gzip.open(dest + ".part", "wb") as gz:
            shutil.copyfileobj(src, gz)
        os.replace(dest + ".part", dest)
    cpu = usage.ru_utime + usage.ru_stime
    return {"setting": setting, "N": N, "eps": "%g" % eps, "seed": seed, "taps": taps,
            "eta": eta, "settle_keys": keys, "cpu_s": "%.2f" % cpu, "wall_s": "%.1f" % wall,
            "cpu_per_tap": "%.5f" % (cpu / taps),
            "sweeps_per_tap": "%.1f" % (sum(r["sweeps"] for r in table) / taps),
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

    def job(key):
        name, N, eps, seed, taps = key
        row = run_one(lmp, name, N, float(eps), taps, seed, args.out, args.nice)
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
        for fut in [pool.submit(job, key) for key in todo]:
            fut.result()
    return 0


if __name__ == "__main__":
    sys.exit(main())
