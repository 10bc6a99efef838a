#!/usr/bin/python3
# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Seconds per tap of fix mc/settle on 1 and 2 MPI ranks, side by side, for growing N.

For each N (paper aspect: R = 0.5, L = 32 R * sqrt(N / 4096), so the bed is as tall as the
paper's 4096 spheres in L = 32 R) a Jullien-Meakin packing is made once (create_packing, cached
in --workdir), then each configuration runs the same taps of eps = 0.01 with a fixed amount of
work per tap (eta 1e-12 and 'maxsweeps S': every tap makes exactly S sweeps), so that the
timings compare equal work:
  1 rank, scheme gather  (the serial kernel: the reference of the speed-up)
  1 rank, scheme domain  (the decomposed code path on one rank: its own overhead)
  2 ranks, scheme domain (processors * * 1)
Each configuration runs --repeats times and its fastest run is reported (the machine is shared:
the fastest run is the least disturbed one), with the spread (slowest / fastest - 1). The
machine's own ceiling for 2 ranks is measured too: two serial runs at once, one per core;
2 x (serial alone) / (slower of the pair) is the most any static two-way split of the work can
gain on this machine at that moment (column ceiling, in the 2-rank rows).
Printed: s per tap, trial moves per second per core, speed-up of 2 ranks over the serial
kernel, peak RSS of the largest process, and for scheme domain the time per phase (trial moves,
ghost refreshes, reductions, rebuilds) from the fix's output vector. A model of the time per
round then extrapolates the communication and synchronisation cost to 64 and 1024 ranks.

  /usr/bin/python3 bench/bench_domain.py --lmp build/lmp_tapmc [--sizes 4096,32768,262144]
      [--sweeps 1000] [--taps 2] [--repeats 3] [--quick] [--csv FILE]
"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys
import tempfile

from bench_util import thermo_rows

R = 0.5
# Round-time jitter (sd / mean of a round's trial time between ranks) assumed for a dedicated
# cluster node in the model: the trial counts of a round differ between ranks by about 1.2 %
# (sd 134 of 8192 for the difference of two ranks), with cache and system noise on top.
QUIET_NODE_JITTER = 0.05
MPIRUN = ["mpirun", "--allow-run-as-root", "--oversubscribe"]

PACK = """units lj
atom_style sphere
boundary p p fm
processors * * 1
region box block 0 {side} 0 {side} 0 {height}
create_box 1 box
create_packing {n} 1 {r} 4928 floor 0.0
write_data {data}
"""

TAPS = """units lj
atom_style sphere
boundary p p fm
processors * * 1
read_data {data}
fix tap all tapdilate 0.01 floor 0.0
fix settle all mc/settle 4928 floor 0.0 eta 1e-12 maxsweeps {sweeps} scheme {scheme}
thermo_style custom step f_settle[1] f_settle[5] f_settle[7] f_settle[8] f_settle[9] f_settle[10] f_settle[11] f_settle[12]
thermo_modify format float %.9g
thermo 1
run {taps}
"""


def side_of(n):
    return 32 * R * math.sqrt(n / 4096.0)


def run(cmd, cwd):
    """Runs cmd; returns (output, peak RSS in MiB of the largest process it started)."""
    wrapper = ("import resource, subprocess, sys\n"
               "p = subprocess.run(sys.argv[1:], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,"
               " text=True)\n"
               "sys.stdout.write(p.stdout)\n"
               "print('PEAK_RSS_KB', resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n"
               "sys.exit(p.returncode)\n")
    proc = subprocess.run([sys.executable, "-c", wrapper] + cmd, cwd=cwd, text=True,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    if proc.returncode != 0:
        sys.exit(f"command failed ({proc.returncode}): {' '.join(cmd)}\n{proc.stdout[-3000:]}")
    rss = int(re.search(r"PEAK_RSS_KB (\d+)", proc.stdout).group(1)) / 1024.0
    return proc.stdout, rss


def make_packing(lmp, n, workdir):
    data = os.path.join(workdir, f"packing_{n}.data")
    if not os.path.exists(data):
        side = side_of(n)
        height = 2.5 * n * 4.0 / 3.0 * math.pi * R ** 3 / (0.58 * side ** 2) + 4 * R
        with open(os.path.join(workdir, f"in.pack_{n}"), "w") as f:
            f.write(PACK.format(side=side, height=height, n=n, r=R, data=data))
        run([lmp, "-in", f"in.pack_{n}", "-log", "none", "-nocite"], workdir)
    return data


def tap_run(lmp, data, ranks, scheme, sweeps, taps, workdir):
    name = f"in.taps_{os.path.basename(data)}_{ranks}_{scheme}"
    with open(os.path.join(workdir, name), "w") as f:
        f.write(TAPS.format(data=data, sweeps=sweeps, scheme=scheme, taps=taps))
    cmd = [lmp, "-in", name, "-log", "none", "-nocite"]
    if ranks > 1:
        cmd = MPIRUN + ["-np", str(ranks)] + cmd
    out, rss = run(cmd, workdir)
    loop = float(re.search(r"Loop time of ([0-9.eE+-]+) on", out).group(1))
    rows = [r for r in thermo_rows(out.splitlines()) if r["Step"] > 0]  # step 0: the set-up

    def total(name):
        return sum(r[name] for r in rows)

    return {"loop": loop, "trials": total("f_settle[5]"), "rss": rss,
            "rounds": total("f_settle[8]"), "rebuilds": total("f_settle[7]"),
            "phases": [total(f"f_settle[{k}]") for k in (9, 10, 11, 12)], "taps": len(rows)}


def concurrent_serial_pair(lmp, data, sweeps, taps, workdir):
    """Two serial runs (scheme gather) started at once, one per core: s per tap of each. On a
    machine whose cores slow each other down (shared caches, memory bandwidth, a virtual
    machine's cores shared with other tenants) the slower one bounds what any static two-way
    split of the work can gain."""
    name = f"in.taps_{os.path.basename(data)}_1_gather"
    with open(os.path.join(workdir, name), "w") as f:
        f.write(TAPS.format(data=data, sweeps=sweeps, scheme="gather", taps=taps))
    cmd = [lmp, "-in", name, "-log", "none", "-nocite"]
    procs = [subprocess.Popen(cmd, cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              text=True) for _ in range(2)]
    times = []
    for proc in procs:
        out = proc.communicate()[0]
        if proc.returncode != 0:
            sys.exit(f"command failed ({proc.returncode}): {' '.join(cmd)}\n{out[-3000:]}")
        times.append(float(re.search(r"Loop time of ([0-9.eE+-]+) on", out).group(1)) / taps)
    return times


def ghosts_per_rank(n, side, ranks_per_axis, cutoff):
    """Ghost spheres of a square sub-domain column (x-y grid): the ring of width `cutoff`."""
    per_area = n / side ** 2
    w = side / ranks_per_axis
    return per_area * ((w + 2 * cutoff) ** 2 - w ** 2)


def expected_max_normal(p):
    """E[max of p independent standard normal variables] (numerical integral)."""
    step, total = 1e-3, 0.0
    for k in range(-8000, 8001):
        x = k * step
        pdf = math.exp(-0.5 * x * x) / math.sqrt(2 * math.pi)
        cdf = 0.5 * (1 + math.erf(x / math.sqrt(2)))
        total += x * p * pdf * cdf ** (p - 1) * step
    return total


def model(t_trial, n, side, ranks, cutoff, jitter, acceptance=0.012, latency=2e-6,
          bandwidth=10e9, reduce_latency=2e-6):
    """Seconds per check (one sweep) per rank of the decomposed scheme on an x-y grid of
    `ranks` ranks: trial moves + 4 rounds x (4 forward-communication swaps carrying the moved
    spheres of the ghost shell + one allreduce + waiting for the slowest rank).
    - moved spheres: each sphere is active in one round per cycle and moves with probability
      `acceptance` (1.2 %: a tap of examples/tapping at the default eta), 32 bytes each;
    - waiting: a round's trial time fluctuates between ranks with standard deviation
      jitter x (its mean), and every rank waits for the slowest of `ranks`;
    - network constants: an InfiniBand-class cluster (assumed, stated in bench/README.md);
      t_trial and jitter measured here."""
    per_axis = math.sqrt(ranks)
    rounds = 4
    compute = n / ranks * t_trial
    ghosts = ghosts_per_rank(n, side, per_axis, cutoff)
    moved_bytes = 32 * ghosts * acceptance / rounds
    wait = jitter * compute / rounds * expected_max_normal(ranks)
    per_round = 4 * latency + moved_bytes / bandwidth + \
        2 * math.log2(max(ranks, 2)) * reduce_latency + wait
    return compute, rounds * per_round, side / per_axis


def fastest(runs):
    """The fastest of repeated runs, with the spread of their loop times."""
    best = min(runs, key=lambda r: r["loop"])
    best["spread"] = max(r["loop"] for r in runs) / best["loop"] - 1
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lmp", default="build/lmp_tapmc")
    ap.add_argument("--sizes", default="4096,32768,262144")
    ap.add_argument("--sweeps", type=int, default=1000, help="sweeps per tap (fixed work)")
    ap.add_argument("--taps", type=int, default=2)
    ap.add_argument("--repeats", type=int, default=3, help="runs per configuration (fastest kept)")
    ap.add_argument("--quick", action="store_true", help="sizes 4096,32768, 50 sweeps")
    ap.add_argument("--workdir", default=None, help="packing cache (default: a temp dir)")
    ap.add_argument("--csv", default=None)
    a = ap.parse_args()
    lmp = os.path.abspath(a.lmp)
    if a.quick:
        a.sizes, a.sweeps, a.repeats = "4096,32768", 50, 1
    if a.repeats < 1:
        sys.exit(f"--repeats = {a.repeats} must be at least 1")
    workdir = a.workdir or tempfile.mkdtemp(prefix="tapmc_bench_domain_")
    os.makedirs(workdir, exist_ok=True)
    cpu = next((line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo")
                if line.startswith("model name")), "unknown")
    print(f"# bench_domain: {a.sweeps} sweeps per tap, {a.taps} taps of eps 0.01, fastest of "
          f"{a.repeats} run(s), CPU {cpu}, {os.cpu_count()} cores")
    header = ["N", "ranks", "scheme", "s_per_tap", "spread", "Mmoves_per_s_per_core",
              "speedup_vs_serial", "peak_rss_MiB", "rounds_per_tap", "ghost_rebuilds", "s_trials",
              "s_ghost_refresh", "s_reductions", "s_rebuilds", "ceiling"]
    print(" ".join(f"{h:>12}" for h in header))
    results = []
    t_trial = jitter = None
    for n in [int(s) for s in a.sizes.split(",")]:
        data = make_packing(lmp, n, workdir)
        serial = None
        for ranks, scheme in ((1, "gather"), (1, "domain"), (2, "domain")):
            r = fastest([tap_run(lmp, data, ranks, scheme, a.sweeps, a.taps, workdir)
                         for _ in range(a.repeats)])
            per_tap = r["loop"] / r["taps"]
            rate = r["trials"] / r["loop"] / ranks / 1e6
            if scheme == "gather":
                serial = per_tap
            if ranks == 1 and scheme == "domain" and r["trials"]:
                t_trial = r["phases"][0] / r["trials"]
            if ranks == 2 and r["rounds"]:
                # All of rank 0's refresh time counted as waiting for the other rank (an upper
                # bound: it includes the forward communication): E[wait] = sigma E[max of 2].
                round_trials = r["phases"][0] / r["rounds"]
                jitter = r["phases"][1] / r["rounds"] / expected_max_normal(2) / round_trials
            ceiling = 0.0
            if ranks == 2:
                pairs = [concurrent_serial_pair(lmp, data, a.sweeps, a.taps, workdir)
                         for _ in range(a.repeats)]
                ceiling = 2 * serial / min(max(pair) for pair in pairs)
            row = [n, ranks, scheme, per_tap, r["spread"], rate, serial / per_tap, r["rss"],
                   r["rounds"] / r["taps"], r["rebuilds"]] + r["phases"] + [ceiling]
            results.append(row)
            print(" ".join(f"{v:>12.4g}" if isinstance(v, float) else f"{v:>12}" for v in row),
                  flush=True)
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(header)
            w.writerows(results)

    # Communication model: where the decomposed scheme stops scaling, with the jitter measured
    # here (this shared machine) and with QUIET_NODE_JITTER (assumed: a dedicated cluster node).
    cutoff = 2 * R + 4 * 0.2 * R + R  # 2 R_max + margin (4 d_max, d_max = R/5) + skin R
    for label, sigma in (("measured here", jitter), ("a quiet node, assumed", QUIET_NODE_JITTER)):
        print(f"\n# model (x-y grid, 4 rounds per sweep; t_trial = {t_trial * 1e9:.1f} ns measured "
              f"at the largest N; round-time jitter {100 * sigma:.1f} % (sd / mean), {label}; "
              "network: 2 us latency, 10 GB/s, allreduce 2 log2(P) x 2 us)")
        print(f"{'N':>9} {'ranks':>6} {'width/R':>8} {'s/sweep compute':>16} "
              f"{'s/sweep comm+wait':>17} {'efficiency':>10} {'speed-up':>9}")
        for n, ranks in ((409600, 64), (409600, 1024), (4096 * 64, 64), (4096 * 1024, 1024),
                         (32768 * 1024, 1024)):
            side = side_of(n)
            compute, comm, width = model(t_trial, n, side, ranks, cutoff, sigma)
            eff = compute / (compute + comm)
            fits = width >= (2 * 2 * R + 4 * 4 * 0.2 * R)
            print(f"{n:>9} {ranks:>6} {width / R:>8.1f} {compute:>16.3g} {comm:>17.3g} "
                  f"{eff:>10.2f} {ranks * eff:>9.1f}{'' if fits else '  (sub-domain too narrow)'}")

if __name__ == "__main__":
    main()
