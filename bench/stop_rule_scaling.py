#!/usr/bin/python3
# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Does the stopping rule of fix mc/settle mean the same thing at every N? Sweeps per tap and the
# packing after T taps against N (same bed height), for 'stop change' (the paper's rule) and
# 'stop drift', driving the LAMMPS executable.
"""Stopping rule of the redeposition against the number of spheres N.

Set-up: the paper's PBC set-up (section II: N = 4096 spheres of radius R = 0.5 in a square box of
side L = 32R, floor at z = 0, open top) with the side scaled as L = 32R sqrt(N/4096), so the bed
height stays the paper's (about 29R); fresh Jullien-Meakin packing (create_packing), then taps
of eps = 0.01 (fix tapdilate) each followed by a redeposition (fix mc/settle).

Two modes:

  taps (default): for every N, setting and seed, T taps; records sweeps per tap (f_settle[1],
      every tap), CPU seconds per tap (user + system time of the lmp process over T taps, so
      including the deposition) and the packing after T taps (Phi_b = c_phi[1], <Phi^c> =
      c_phi[2], <Z> = c_phi[3] of compute stereo/profile). Prints mean +- standard error over
      seeds, and for every setting the paired deviation (same seeds: same initial packings) from
      the reference setting at that N (--reference).

  --trajectories: the reason, measured. Records <Z> after every sweep (mc/settle with maxsweeps
      1, one timestep per sweep) for --sweeps sweeps after each of --traj-taps taps, and reports
      per N: the sweep at which the drift of <Z> per sweep, smoothed over 200 sweeps, crosses
      eta <Z> (an intensive quantity of the packing: the same at every N), the noise of the
      single-sweep change (standard deviation / mean) there, and where each rule, applied to the
      recorded series exactly as tapmc_stop_rule.h does, would stop. (One sweep per call draws
      other random numbers than one call per tap: the same process, not the same trajectory.)

Each finished run is appended to <csv>.runs.csv at once; --summarize re-reads it.

A benchmark of the redeposition's cost against N (no tapmc module): it is the measurement
behind the engine's ``stop drift`` rule, not a claim of the paper; the run-time-versus-error
trade-off of the settings on the paper's protocol is ``tapmc-paper front`` (doc/front.rst).

Usage:
  /usr/bin/python3 bench/stop_rule_scaling.py [--lmp build/lmp_tapmc] [--sizes 1024,4096,16384]
        [--taps 5] [--seeds 2] [--settings "change 1e-5,change 1e-6,change 1e-7,drift 3e-7"]
        [--reference "drift 3e-8"] [--csv stop_rule_scaling.csv] [--summarize]
  /usr/bin/python3 bench/stop_rule_scaling.py --trajectories [--sizes ...] [--sweeps 8000]
        [--traj-taps 3] [--seeds 1] [--etas 1e-6,3e-7,1e-7] [--keep-logs DIR]
  /usr/bin/python3 bench/stop_rule_scaling.py --trajectories --logs DIR/traj.*.log [--sweeps 8000]
"""

import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile
import time

from bench_util import (child_cpu, log_thermo_rows, loop_time, mean_se, read_runs,
                        thermo_rows)

FIRST_SEED = 4928
SEED_STEP = 1117
RADIUS = 0.5
PAPER_N, PAPER_SIDE = 4096, 16.0  # L = 32R
BOX_HEIGHT = 40.0                  # the example's box: room above the ~14.4 high bed
EPS = 0.01
# tapmc_defaults.h: kSettleDriftWindow, kSettleDriftConfidence, kSettleFreeFallAcceptance
DRIFT_WINDOW, DRIFT_CONFIDENCE, FREE_FALL_ACCEPTANCE = 32, 2.0, 0.5
SMOOTHING_SWEEPS = 200
DEFAULT_SETTINGS = "change 1e-5,change 1e-6,change 1e-7,drift 1e-6,drift 3e-7,drift 1e-7"
OBSERVABLES = [("phi_b", "c_phi[1]"), ("phi_c", "c_phi[2]"), ("z_mean", "c_phi[3]")]


def side_for(n):
    return PAPER_SIDE * math.sqrt(n / PAPER_N)


def preamble(n, seed):
    side = side_for(n)
    return ("units lj\natom_style sphere\nboundary p p fm\n"
            "region box block 0 %.15g 0 %.15g 0 %g\ncreate_box 1 box\n"
            "create_packing %d 1 %g %d floor 0.0\n" % (side, side, BOX_HEIGHT, n, RADIUS, seed))


def parse_setting(text):
    words = text.split()
    if len(words) != 2 or words[0] not in ("change", "drift"):
        raise ValueError("setting '%s': expected 'change ETA' or 'drift ETA'" % text)
    float(words[1])
    return words[0], words[1]


def run_lmp(lmp, text, tmp):
    path = os.path.join(tmp, "in.run")
    with open(path, "w") as f:
        f.write(text)
    log = os.path.join(tmp, "log.lammps")
    cmd = [lmp, "-in", path, "-log", log, "-screen", "none", "-echo", "none"]
    proc = subprocess.run(cmd, cwd=tmp, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          env=dict(os.environ, OMP_NUM_THREADS="1"))
    if proc.returncode != 0:
        tail = (proc.stdout + proc.stderr).decode(errors="replace")[-2000:]
        raise RuntimeError("lmp failed (rc %d): %s\n%s" % (proc.returncode, " ".join(cmd), tail))
    return log


# ---- taps mode --------------------------------------------------------------------------------

RUN_FIELDS = ["n", "setting", "seed", "taps", "cpu_s", "cpu_per_tap", "sweeps_per_tap",
              "sweeps_first_tap", "capped_taps", "phi_b", "phi_c", "z_mean"]


def run_taps(lmp, n, setting, seed, taps):
    rule, eta = setting
    text = preamble(n, seed) + (
        "compute phi all stereo/profile floor 0.0\n"
        "fix tap all tapdilate %g floor 0.0\n"
        "fix settle all mc/settle %d floor 0.0 stop %s eta %s\n"
        "thermo_style custom step c_phi[1] c_phi[2] c_phi[3] f_settle[1] f_settle[4]\n"
        "thermo_modify format float %%.8f lost error\nthermo 1\nrun %d\n"
        % (EPS, seed, rule, eta, taps))
    with tempfile.TemporaryDirectory(prefix="tapmc_stoprule_") as tmp:
        cpu0 = child_cpu()
        log = run_lmp(lmp, text, tmp)
        cpu = child_cpu() - cpu0
        rows = [r for r in log_thermo_rows(log) if r["Step"] > 0]
    if not rows or int(rows[-1]["Step"]) != taps:
        raise RuntimeError("N %d %s seed %d: no thermo row for tap %d" % (n, setting, seed, taps))
    sweeps = [r["f_settle[1]"] for r in rows]
    last = rows[-1]
    row = {"n": n, "setting": " ".join(setting), "seed": seed, "taps": taps,
           "cpu_s": "%.3f" % cpu, "cpu_per_tap": "%.5f" % (cpu / taps),
           "sweeps_per_tap": "%.1f" % (sum(sweeps) / len(sweeps)),
           "sweeps_first_tap": "%.1f" % sweeps[0],
           "capped_taps": "%d" % sum(1 for r in rows if r["f_settle[4]"] != 0)}
    for key, column in OBSERVABLES:
        row[key] = "%.6f" % last[column]
    return row


def summarize(rows, reference, csv_path, out=sys.stdout):
    table = {}
    for r in rows:
        table.setdefault((int(r["n"]), r["setting"]), {})[int(r["seed"])] = r
    sizes = sorted({k[0] for k in table})
    order = []
    for r in rows:
        if r["setting"] not in order:
            order.append(r["setting"])
    head = "%7s %-13s %5s %10s %15s %15s %19s %19s %17s %26s" % (
        "N", "setting", "seeds", "CPU s/tap", "sweeps/tap", "sweeps tap 1", "Phi_b", "<Phi^c>",
        "<Z>", "d<Phi^c> vs ref (d/se)")
    print(head, file=out)
    records = []
    for n in sizes:
        ref = table.get((n, reference), {})
        for setting in order:
            runs = table.get((n, setting))
            if not runs:
                continue
            seeds = sorted(runs)
            rec = {"n": n, "setting": setting, "seeds": len(seeds)}
            for key in ("cpu_per_tap", "sweeps_per_tap", "sweeps_first_tap", "phi_b", "phi_c",
                        "z_mean"):
                rec[key], rec[key + "_se"] = mean_se([float(runs[s][key]) for s in seeds])
            rec["capped_taps"] = sum(int(runs[s]["capped_taps"]) for s in seeds)
            common = [s for s in seeds if s in ref]
            for key in ("phi_b", "phi_c", "z_mean"):
                if setting == reference or not common:
                    rec[key + "_dev"] = rec[key + "_dev_se"] = float("nan")
                    continue
                rec[key + "_dev"], rec[key + "_dev_se"] = mean_se(
                    [float(runs[s][key]) - float(ref[s][key]) for s in common])
            records.append(rec)

            def pm(key, digits):
                m, se = rec[key], rec[key + "_se"]
                return ("%.*f +- %.*f" % (digits, m, digits, se)) if se == se else "%.*f" % (digits, m)
            if setting == reference:
                dev = "reference"
            elif rec["phi_c_dev"] != rec["phi_c_dev"]:
                dev = "n/a"
            else:
                d, se = rec["phi_c_dev"], rec["phi_c_dev_se"]
                dev = "%+.5f +- %.5f" % (d, se) if se == se else "%+.5f" % d
                if se == se and se > 0:
                    dev += " (%+.1f)" % (d / se)
            print("%7d %-13s %5d %10s %15s %15s %19s %19s %17s %26s" % (
                n, setting, len(seeds), "%.3f" % rec["cpu_per_tap"], pm("sweeps_per_tap", 0),
                pm("sweeps_first_tap", 0), pm("phi_b", 5), pm("phi_c", 5), pm("z_mean", 4), dev),
                file=out)
            if rec["capped_taps"]:
                print("        (%d taps stopped at the maxsweeps cap)" % rec["capped_taps"], file=out)
    if records:
        fields = []
        for r in records:
            fields += [k for k in r if k not in fields]
        with open(csv_path, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=fields)
            w.writeheader()
            for r in records:
                w.writerow({k: ("%.6g" % v) if isinstance(v, float) else v for k, v in r.items()})
    return records


# ---- trajectories mode ------------------------------------------------------------------------

def trajectory_input(n, seed, taps, sweeps):
    return preamble(n, seed) + (
        "fix settle all mc/settle %d floor 0.0 eta 1e-12 maxsweeps 1\n"
        "thermo_style custom step f_settle[3] f_settle[2] f_settle[5] f_settle[6]\n"
        "thermo_modify format float %%.15g warn 0\nthermo 1\n"
        "variable t loop %d\nlabel tap\n"
        "fix tap all tapdilate %g floor 0.0\nrun 1\nunfix tap\nrun %d\nnext t\njump SELF tap\n"
        % (seed, taps, EPS, sweeps))


def read_trajectories(log):
    """(N, {step: thermo row}, last step) of a log of trajectory_input."""
    by_step, n = {}, None
    with open(log) as f:
        lines = f.read().splitlines()
    for r in thermo_rows(lines):
        if r["Step"] > 0 and r["f_settle[5]"] > 0:
            by_step[int(r["Step"])] = r
    n = loop_time(lines)[1]
    if not by_step or n is None:
        raise RuntimeError("%s: no trajectory" % log)
    return n, by_step, max(by_step)


def split_taps(by_step, last, sweeps):
    """Per tap (the step of the tap, then one step per sweep): (Z0, z list, acceptance list),
    entry 0 the first sweep after the tap, Z0 the <Z> right after the tap (logs without the
    f_settle[6] column: Z0 = the first sweep's <Z>, which is then dropped)."""
    out = []
    per_tap = sweeps + 1
    for t in range(last // per_tap):
        rows = [by_step[s] for s in range(1 + t * per_tap, 1 + (t + 1) * per_tap)]
        z = [r["f_settle[3]"] for r in rows]
        acc = [r["f_settle[2]"] for r in rows]
        if "f_settle[6]" in rows[0]:
            out.append((rows[0]["f_settle[6]"], z, acc))
        else:
            out.append((z[0], z[1:], acc[1:]))
    return out


def record_trajectories(lmp, n, seed, taps, sweeps, keep=None):
    """Runs trajectory_input; returns its log's taps (split_taps)."""
    with tempfile.TemporaryDirectory(prefix="tapmc_stoprule_") as tmp:
        log = run_lmp(lmp, trajectory_input(n, seed, taps, sweeps), tmp)
        if keep:
            os.makedirs(keep, exist_ok=True)
            with open(log) as src, open(os.path.join(keep, "traj.%d.%d.log" % (n, seed)), "w") as dst:
                dst.write(src.read())
        _, by_step, last = read_trajectories(log)
    return split_taps(by_step, last, sweeps)


def change_stop(z0, z, acc, eta):
    """First sweep (1-based) at which the paper's rule stops (tapmc_stop_rule.h, Change)."""
    prev = z0
    for k, (zk, ak) in enumerate(zip(z, acc)):
        if abs(zk - prev) / abs(prev) < eta and ak < FREE_FALL_ACCEPTANCE:
            return k + 1
        prev = zk
    return None


def drift_stop(z0, z, acc, eta, window=DRIFT_WINDOW, confidence=DRIFT_CONFIDENCE):
    """First sweep at which 'stop drift' stops (tapmc_stop_rule.h, Drift, one check a sweep)."""
    series = [z0] + list(z)
    for k in range(window, len(series)):
        dec = [series[j - 1] - series[j] for j in range(k - window + 1, k + 1)]
        m = sum(dec) / window
        se = math.sqrt(sum((d - m) ** 2 for d in dec) / (window - 1) / window)
        if (abs(m) + confidence * se) / abs(series[k]) < eta and acc[k - 1] < FREE_FALL_ACCEPTANCE:
            return k
    return None


def smoothed_crossing(z, eta, width=SMOOTHING_SWEEPS):
    """Sweep at which the drift per sweep averaged over `width` sweeps (centred) drops below
    eta <Z>: the deterministic point both rules approach when N is large."""
    for k in range(width, len(z)):
        if (z[k - width] - z[k]) / width / z[k] < eta:
            return k - width // 2 + 1
    return None


def noise_ratio(z, at, half=100):
    """Standard deviation / mean of the single-sweep decrement of <Z> around sweep `at`."""
    lo, hi = max(1, at - half), min(len(z) - 1, at + half)
    dec = [z[k - 1] - z[k] for k in range(lo, hi)]
    m, _ = mean_se(dec)
    sd = math.sqrt(sum((d - m) ** 2 for d in dec) / (len(dec) - 1))
    return sd / m if m > 0 else float("nan")


def trajectories(args, sizes, seeds):
    etas = [float(e) for e in args.etas.split(",")]
    lines = ["%7s %7s %5s %12s %11s %12s %12s" % ("N", "eta", "taps", "crossing", "noise sd/mu",
                                                   "change stop", "drift stop")]
    records = []
    recorded = {}
    for log in args.logs or []:
        n, by_step, last = read_trajectories(log)
        recorded.setdefault(n, []).extend(split_taps(by_step, last, args.sweeps))
    for n in sizes if not args.logs else sorted(recorded):
        series = recorded.get(n, [])
        for seed in seeds if not args.logs else []:
            t0 = time.time()
            series += record_trajectories(args.lmp, n, seed, args.traj_taps, args.sweeps,
                                          args.keep_logs)
            print("  N %d seed %d: %d taps x %d sweeps recorded in %.0f s"
                  % (n, seed, args.traj_taps, args.sweeps, time.time() - t0))
            sys.stdout.flush()
        for eta in etas:
            cross, noise, chg, drf = [], [], [], []
            for z0, z, acc in series:
                c = smoothed_crossing(z, eta)
                cross.append(c if c is not None else float("nan"))
                noise.append(noise_ratio(z, c) if c is not None else float("nan"))
                s = change_stop(z0, z, acc, eta)
                chg.append(s if s is not None else float("nan"))
                s = drift_stop(z0, z, acc, eta)
                drf.append(s if s is not None else float("nan"))
            rec = {"n": n, "eta": eta, "taps": len(series)}
            for key, vals in (("crossing", cross), ("noise", noise), ("change_stop", chg),
                              ("drift_stop", drf)):
                good = [v for v in vals if v == v]
                rec[key] = sum(good) / len(good) if good else float("nan")
                rec[key + "_missing"] = len(vals) - len(good)
            records.append(rec)

            def cell(key, fmt):
                text = fmt % rec[key] if rec[key] == rec[key] else "> %d" % args.sweeps
                return text + ("*" if rec[key + "_missing"] else "")
            lines.append("%7d %7g %5d %12s %11s %12s %12s" % (
                n, eta, len(series), cell("crossing", "%.0f"), cell("noise", "%.2f"),
                cell("change_stop", "%.0f"), cell("drift_stop", "%.0f")))
    lines.append("(mean over taps and seeds; * = some taps did not get there within %d sweeps)"
                 % args.sweeps)
    print("\n".join(lines))
    with open(args.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(records[0].keys()))
        w.writeheader()
        for r in records:
            w.writerow({k: ("%.6g" % v) if isinstance(v, float) else v for k, v in r.items()})
    print("CSV: %s" % args.csv)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap.add_argument("--lmp", default=os.path.join(root, "build", "lmp_tapmc"))
    ap.add_argument("--sizes", default="1024,4096,16384")
    ap.add_argument("--seeds", type=int, default=None, help="seeds (default 2; trajectories 1)")
    ap.add_argument("--taps", type=int, default=5)
    ap.add_argument("--settings", default=DEFAULT_SETTINGS,
                    help="comma list of 'change ETA' / 'drift ETA' (default: %s)" % DEFAULT_SETTINGS)
    ap.add_argument("--reference", default="change 1e-7",
                    help="setting the deviations are measured from (default: change 1e-7)")
    ap.add_argument("--csv", default=None, help="summary CSV (runs go to <csv>.runs.csv)")
    ap.add_argument("--summarize", action="store_true", help="only the table from <csv>.runs.csv")
    ap.add_argument("--trajectories", action="store_true", help="record <Z> after every sweep")
    ap.add_argument("--sweeps", type=int, default=8000, help="trajectories: sweeps per tap")
    ap.add_argument("--traj-taps", type=int, default=3, help="trajectories: taps per run")
    ap.add_argument("--etas", default="1e-6,3e-7,1e-7", help="trajectories: eta values")
    ap.add_argument("--keep-logs", default=None, metavar="DIR",
                    help="trajectories: keep the logs in DIR (traj.N.seed.log)")
    ap.add_argument("--logs", nargs="+", default=None, metavar="LOG",
                    help="trajectories: analyse these kept logs instead of running lmp_tapmc")
    args = ap.parse_args()

    try:
        sizes = [int(s) for s in args.sizes.split(",")]
        settings = [parse_setting(s) for s in args.settings.split(",")]
        reference = " ".join(parse_setting(args.reference))
    except ValueError as e:
        ap.error(str(e))
    if min(sizes) < 1 or args.taps < 1 or args.sweeps < 2 * SMOOTHING_SWEEPS or args.traj_taps < 1:
        ap.error("--sizes and --taps must be >= 1, --sweeps >= %d" % (2 * SMOOTHING_SWEEPS))
    n_seeds = args.seeds if args.seeds is not None else (1 if args.trajectories else 2)
    seeds = [FIRST_SEED + SEED_STEP * k for k in range(n_seeds)]
    if args.csv is None:
        args.csv = "stop_rule_trajectories.csv" if args.trajectories else "stop_rule_scaling.csv"
    if args.summarize:
        summarize(read_runs(args.csv + ".runs.csv", args.taps), reference, args.csv)
        return 0
    if args.trajectories and args.logs:
        trajectories(args, sizes, seeds)
        return 0
    args.lmp = os.path.abspath(args.lmp)
    if not os.access(args.lmp, os.X_OK):
        ap.error("--lmp %s is not an executable" % args.lmp)
    if args.trajectories:
        trajectories(args, sizes, seeds)
        return 0

    keys = [" ".join(s) for s in settings]
    if reference not in keys:
        settings.append(tuple(reference.split()))
    runs_path = args.csv + ".runs.csv"
    done = {(int(r["n"]), r["setting"], int(r["seed"])) for r in read_runs(runs_path, args.taps)}
    print("stop_rule_scaling: sizes %s, %d settings, %d seeds, %d taps (eps %g); runs: %s"
          % (sizes, len(settings), n_seeds, args.taps, EPS, runs_path))
    new_file = not os.path.exists(runs_path)
    with open(runs_path, "a", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=RUN_FIELDS)
        if new_file:
            writer.writeheader()
        for n in sizes:
            for seed in seeds:
                for setting in settings:
                    if (n, " ".join(setting), seed) in done:
                        continue
                    t0 = time.time()
                    row = run_taps(args.lmp, n, setting, seed, args.taps)
                    writer.writerow(row)
                    f.flush()
                    print("  N %6d %-13s seed %5d: %6.1f s CPU (wall %.1f s), %s sweeps/tap, "
                          "<Phi^c> %s" % (n, " ".join(setting), seed, float(row["cpu_s"]),
                                          time.time() - t0, row["sweeps_per_tap"], row["phi_c"]))
                    sys.stdout.flush()
    print()
    summarize(read_runs(runs_path, args.taps), reference, args.csv)
    print("summary CSV: %s" % args.csv)
    return 0


if __name__ == "__main__":
    sys.exit(main())
