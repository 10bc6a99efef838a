#!/usr/bin/python3
# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Run time against accuracy of the redeposition knobs of fix mc/settle (eta, check interval,
# d_max, pick order) on the paper's periodic set-up, driving the LAMMPS executable.
"""Run time / accuracy front of fix mc/settle on examples/tapping/in.tapping_pbc.

For every setting and seed, runs T taps (eps = 0.01) of the paper's PBC set-up (4096 spheres,
create_packing, fix tapdilate, fix mc/settle, compute stereo/profile) and records the CPU time
per tap (user + system time of the lmp process / T) and the packing after T taps from the last
row of the thermo table: Phi_b = c_phi[1], <Phi^c> = c_phi[2], <Z> = c_phi[3]. Reports the mean
and standard error over seeds, and the deviation of each setting from the reference (eta 1e-7)
in units of the combined standard error, sqrt(se_s^2 + se_ref^2); since every setting uses the
same seeds (same initial packing, same seed of the moves), the paired deviation (mean of the
per-seed differences over its standard error) is printed as well.

Runs go seed by seed (every setting once per seed), each finished run is appended to
<csv>.runs.csv at once, so an interrupted run still gives a table: --summarize re-reads it.

A benchmark of the kernel's knobs (it reads lmp's CPU time and thermo output, no tapmc module):
the trade-off on the paper's protocol, over 1000 taps at two eps and two N against a converged
reference, with the setting to use for each purpose, is ``tapmc-paper front`` (doc/front.rst);
this one stays for what the front does not vary (the pick order) and for the short-run table of
doc/measurements.rst.

Usage:
  /usr/bin/python3 bench/tapping_front.py [--lmp build/lmp_tapmc] [--taps 100] [--seeds 3]
        [--quick] [--knobs eta,check,dmax,order] [--csv tapping_front.csv] [--summarize]
"""

import argparse
import csv
import math
import os
import re
import subprocess
import sys
import tempfile
import time

from bench_util import child_cpu, loop_time, mean_se, read_runs, thermo_rows

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_INPUT = os.path.join(ROOT, "examples", "tapping", "in.tapping_pbc")
FIRST_SEED = 4928
SEED_STEP = 1117

# name -> (knob group, fix mc/settle keywords). The default of fix mc/settle is eta 1e-6, check
# 0 (= one sweep = 4096 trials), dmax R/5 = 0.1 (R = 0.5), order random.
DEFAULT_KEYWORDS = {"eta": "1e-6", "check": "0", "dmax": "0.1", "order": "random"}
SETTINGS = [
    ("eta 1e-5", "eta", {"eta": "1e-5"}),
    ("default (eta 1e-6)", "default", {}),
    ("reference (eta 1e-7)", "reference", {"eta": "1e-7"}),
    ("check 40960", "check", {"check": "40960"}),
    ("dmax 0.05", "dmax", {"dmax": "0.05"}),
    ("dmax 0.2", "dmax", {"dmax": "0.2"}),
    ("order sweep", "order", {"order": "sweep"}),
]
REFERENCE = "reference (eta 1e-7)"
DEFAULT = "default (eta 1e-6)"
# The settings equal to the default by construction (shown in the table, not run twice).
ALIASES = [("eta 1e-6", "eta"), ("check 4096", "check"), ("dmax 0.1", "dmax"),
           ("order random", "order")]
OBSERVABLES = [("phi_b", "c_phi[1]"), ("phi_c", "c_phi[2]"), ("z_mean", "c_phi[3]")]
# rough CPU seconds per tap, for the announced budget only
COST_GUESS = {"1e-5": 0.18, "1e-6": 0.65, "1e-7": 1.7}


def keywords_of(overrides):
    kw = dict(DEFAULT_KEYWORDS)
    kw.update(overrides)
    return kw


def make_input(template_text, keywords, directory):
    """Copy of the input with the fix mc/settle line given explicit keywords."""
    pattern = re.compile(r"^(fix\s+\S+\s+\S+\s+mc/settle\s+.*?)\s*$", re.MULTILINE)
    matches = pattern.findall(template_text)
    if len(matches) != 1:
        raise RuntimeError("expected exactly one 'fix ... mc/settle' line in the input, found %d"
                           % len(matches))
    for key in keywords:
        if re.search(r"\b%s\b" % key, matches[0].split("mc/settle", 1)[1]):
            raise RuntimeError("the input's fix mc/settle line already sets '%s'" % key)
    extra = " ".join("%s %s" % (k, keywords[k]) for k in ("eta", "check", "dmax", "order"))
    text = pattern.sub(lambda m: m.group(1) + " " + extra, template_text)
    path = os.path.join(directory, "in.front")
    with open(path, "w") as f:
        f.write(text)
    return path


def parse_log(path):
    """Last thermo row (dict column -> float), the loop wall time and the sweeps of every tap of
    a LAMMPS log."""
    with open(path) as f:
        lines = f.read().splitlines()
    rows = thermo_rows(lines)
    if not rows:
        raise RuntimeError("no thermo table in %s" % path)
    sweeps = [r["f_settle[1]"] for r in rows if r.get("Step", 0) > 0 and "f_settle[1]" in r]
    return rows[-1], loop_time(lines)[0], sweeps


def run_one(lmp, template_text, keywords, taps, seed, eps):
    with tempfile.TemporaryDirectory(prefix="tapmc_front_") as tmp:
        infile = make_input(template_text, keywords, tmp)
        log = os.path.join(tmp, "log.lammps")
        cmd = [lmp, "-in", infile, "-var", "taps", str(taps), "-var", "eps", str(eps),
               "-var", "seed", str(seed), "-log", log, "-screen", "none", "-echo", "none"]
        proc = subprocess.Popen(cmd, cwd=tmp, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                env=dict(os.environ, OMP_NUM_THREADS="1"))
        out, err = proc.communicate()
        if proc.returncode != 0:
            tail = (out + err).decode(errors="replace")[-2000:]
            try:
                with open(log) as f:
                    tail = f.read()[-2000:]
            except OSError:
                pass
            raise RuntimeError("lmp failed (rc %d): %s\n%s" % (proc.returncode, " ".join(cmd), tail))
        last, loop, sweeps = parse_log(log)
    if int(last["Step"]) != taps:
        raise RuntimeError("last thermo row is step %d, expected %d" % (last["Step"], taps))
    return last, loop, sweeps


RUN_FIELDS = ["setting", "seed", "taps", "eta", "check", "dmax", "order", "cpu_s", "cpu_per_tap",
              "loop_wall_s", "sweeps_per_tap_sampled", "phi_b", "phi_c", "z_mean"]


def summarize(rows, settings_run, csv_path, out=sys.stdout):
    by_setting = {}
    for row in rows:
        by_setting.setdefault(row["setting"], {})[int(row["seed"])] = row
    ref = by_setting.get(REFERENCE, {})
    lines, records = [], []
    head = "%-22s %6s %13s %9s %19s %19s %17s %13s %13s %13s" % (
        "setting", "seeds", "CPU s/tap", "sweeps", "Phi_b", "<Phi^c>", "<Z>",
        "dPhi_b/se", "dPhi^c/se", "dZ/se")
    lines.append(head)
    lines.append("%-22s %6s %13s %9s %19s %19s %17s %13s %13s %13s" % (
        "", "", "", "", "mean +- se", "mean +- se", "mean +- se",
        "comb (pair)", "comb (pair)", "comb (pair)"))
    order = [name for name, _, _ in SETTINGS if name in settings_run]
    for name in order:
        runs = by_setting.get(name, {})
        if not runs:
            continue
        seeds = sorted(runs)
        cpu = mean_se([float(runs[s]["cpu_per_tap"]) for s in seeds])
        sweeps = mean_se([float(runs[s]["sweeps_per_tap_sampled"]) for s in seeds])
        rec = {"setting": name, "seeds": len(seeds), "cpu_per_tap": cpu[0], "cpu_per_tap_se": cpu[1],
               "sweeps_per_tap_sampled": sweeps[0]}
        cols = []
        devs = []
        for key, _ in OBSERVABLES:
            vals = [float(runs[s][key]) for s in seeds]
            m, se = mean_se(vals)
            rec[key], rec[key + "_se"] = m, se
            digits = 4 if key == "z_mean" else 5
            cols.append("%.*f +- %.*f" % (digits, m, digits, se) if se == se else "%.*f" % (digits, m))
            common = [s for s in seeds if s in ref]
            if name == REFERENCE or not common:
                rec[key + "_dev_combined"] = rec[key + "_dev_paired"] = float("nan")
                devs.append("-" if name == REFERENCE else "n/a")
                continue
            rm, rse = mean_se([float(ref[s][key]) for s in common])
            mm, mse = mean_se([float(runs[s][key]) for s in common])
            comb = (mm - rm) / math.sqrt(mse ** 2 + rse ** 2) if mse == mse and rse == rse and (
                mse > 0 or rse > 0) else float("nan")
            dm, dse = mean_se([float(runs[s][key]) - float(ref[s][key]) for s in common])
            paired = dm / dse if dse == dse and dse > 0 else float("nan")
            rec[key + "_dev_combined"], rec[key + "_dev_paired"] = comb, paired
            devs.append("%s (%s)" % tuple("n/a" if v != v else "%+.1f" % v for v in (comb, paired)))
        records.append(rec)
        cpu_text = "%.3f +- %.3f" % cpu if cpu[1] == cpu[1] else "%.3f" % cpu[0]
        lines.append("%-22s %6d %13s %9.0f %19s %19s %17s %13s %13s %13s" % (
            name, len(seeds), cpu_text, sweeps[0], cols[0], cols[1], cols[2], devs[0], devs[1], devs[2]))
    lines.append("(same as the default: %s)" % ", ".join(a for a, _ in ALIASES))
    # Each knob against the default it changes (same seeds: paired differences), e.g. whether
    # sweep order differs from random order at the default eta.
    default = by_setting.get(DEFAULT, {})
    lines.append("")
    lines.append("%-22s %6s %24s %24s %24s" % ("vs the default", "seeds", "dPhi_b (d/se)",
                                               "d<Phi^c> (d/se)", "d<Z> (d/se)"))
    for name in order:
        runs = by_setting.get(name, {})
        common = sorted(s for s in runs if s in default)
        if name == DEFAULT or not common:
            continue
        cols = []
        for rec in records:
            if rec["setting"] == name:
                break
        for key, _ in OBSERVABLES:
            dm, dse = mean_se([float(runs[s][key]) - float(default[s][key]) for s in common])
            rec[key + "_vs_default"], rec[key + "_vs_default_se"] = dm, dse
            cols.append("%+.5f +- %.5f (%s)" % (dm, dse, "n/a" if not dse > 0 else "%+.1f" % (dm / dse)))
        lines.append("%-22s %6d %24s %24s %24s" % (name, len(common), cols[0], cols[1], cols[2]))
    for line in lines:
        print(line, file=out)
    if records:
        fields = list(records[0].keys())
        for r in records:
            for k in r:
                if k not in fields:
                    fields.append(k)
        with open(csv_path, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=fields)
            w.writeheader()
            for r in records:
                w.writerow({k: (("%.6g" % v) if isinstance(v, float) else v) for k, v in r.items()})
    return records


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--lmp", default=os.path.join(ROOT, "build", "lmp_tapmc"))
    ap.add_argument("--input", default=DEFAULT_INPUT)
    ap.add_argument("--taps", type=int, default=None, help="taps per run (default 100)")
    ap.add_argument("--seeds", type=int, default=None, help="seeds per setting (default 3)")
    ap.add_argument("--eps", type=float, default=0.01, help="tap strength (default 0.01)")
    ap.add_argument("--quick", action="store_true", help="taps 20, seeds 2, only the eta knob")
    ap.add_argument("--knobs", default=None,
                    help="comma list among eta,check,dmax,order (default all; --quick: eta)")
    ap.add_argument("--csv", default="tapping_front.csv", help="summary CSV (runs go to <csv>.runs.csv)")
    ap.add_argument("--summarize", action="store_true", help="only print the table from <csv>.runs.csv")
    args = ap.parse_args()

    taps = args.taps if args.taps is not None else (20 if args.quick else 100)
    n_seeds = args.seeds if args.seeds is not None else (2 if args.quick else 3)
    knobs = args.knobs.split(",") if args.knobs else (["eta"] if args.quick else
                                                     ["eta", "check", "dmax", "order"])
    bad = [k for k in knobs if k not in ("eta", "check", "dmax", "order")]
    if bad:
        ap.error("--knobs: unknown knob(s) %s (allowed: eta, check, dmax, order)" % ",".join(bad))
    if taps < 1 or n_seeds < 1:
        ap.error("--taps and --seeds must be >= 1 (got %d, %d)" % (taps, n_seeds))
    settings = [s for s in SETTINGS if s[1] in ("default", "reference") or s[1] in knobs]
    names = [s[0] for s in settings]
    runs_path = args.csv + ".runs.csv"

    if args.summarize:
        summarize(read_runs(runs_path, taps), names, args.csv)
        return 0

    lmp = os.path.abspath(args.lmp)
    if not os.access(lmp, os.X_OK):
        ap.error("--lmp %s is not an executable" % lmp)
    with open(args.input) as f:
        template_text = f.read()
    seeds = [FIRST_SEED + SEED_STEP * k for k in range(n_seeds)]
    guess = sum(COST_GUESS.get(keywords_of(o)["eta"], 1.0) * (2.5 if o.get("check") else 1.0)
                for _, _, o in settings) * taps * n_seeds
    print("tapping_front: %d settings x %d seeds x %d taps (eps %g), about %.0f CPU s by rough guess"
          % (len(settings), n_seeds, taps, args.eps, guess))
    print("lmp: %s\ninput: %s\nruns: %s" % (lmp, args.input, runs_path))
    sys.stdout.flush()

    done = {(r["setting"], int(r["seed"])) for r in read_runs(runs_path, taps)}
    new_file = not os.path.exists(runs_path)
    with open(runs_path, "a", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=RUN_FIELDS)
        if new_file:
            writer.writeheader()
        for seed in seeds:  # seed by seed: a partial run still covers every setting
            for name, _, overrides in settings:
                if (name, seed) in done:
                    continue
                kw = keywords_of(overrides)
                cpu0, t0 = child_cpu(), time.time()
                last, loop, sweeps = run_one(lmp, template_text, kw, taps, seed, args.eps)
                cpu = child_cpu() - cpu0
                row = {"setting": name, "seed": seed, "taps": taps, "cpu_s": "%.3f" % cpu,
                       "cpu_per_tap": "%.5f" % (cpu / taps), "loop_wall_s": "%.3f" % loop,
                       "sweeps_per_tap_sampled": "%.1f" % (sum(sweeps) / len(sweeps) if sweeps else 0)}
                row.update(kw)
                for key, column in OBSERVABLES:
                    row[key] = "%.6f" % last[column]
                writer.writerow(row)
                f.flush()
                print("  %-22s seed %5d: %7.1f s CPU (%.3f s/tap, wall %.1f s), Phi_b %.5f <Phi^c> %.5f <Z> %.4f"
                      % (name, seed, cpu, cpu / taps, time.time() - t0, last["c_phi[1]"],
                         last["c_phi[2]"], last["c_phi[3]"]))
                sys.stdout.flush()
    print()
    summarize(read_runs(runs_path, taps), names, args.csv)
    print("summary CSV: %s" % args.csv)
    return 0


if __name__ == "__main__":
    sys.exit(main())
