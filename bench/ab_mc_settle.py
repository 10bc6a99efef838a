# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Same-run A/B of the redeposition kernel: a reference commit against the working tree.

Builds the reference commit (default df91a11, the kernel of three days before the per-core
work) from `git archive` in a work directory, with the candidate build's own flags
(TAPMC_NATIVE, build type), then alternates the two programs pair by pair (A B, B A, A B, ...)
so that both see the same machine state, and prints per row the medians, the ratio of the
medians and the spread of the pairs' ratios.

Two kinds of rows:
  kernel  `bench_mc_settle --kernel` (trial moves per second of tapmc::Settler on the paper's
          scene and its variants, N = 4096; --large adds the bed N = 262144); by default the
          reference is built with the working tree's bench_mc_settle.cpp (the same benchmark
          code on both kernels: --ref-bench own uses the reference's program, its own rows);
  tap     (--lmp) `lmp_tapmc` on examples/paper/in.constant_eps from a fresh packing at the
          paper's scene (N = 4096, L = 32R, P.B.C., eps = 0.0225, default eta): CPU seconds per
          tap from the run's loop time, and whether both made the same taps (final <Z>, Phi_b).

Run on quiet cores: pause background runs (kill -STOP) and do not build meanwhile; the load
average of the start and the end is printed.

  instructions  (--instructions) each kernel program once under valgrind's callgrind: the
          instructions it executes (Ir), total and per function, ref against new. A count, not
          a time (it misses cache and memory effects), but exact and deaf to the other
          processes of the machine: on a busy or noisy machine, where the pairs' ratios spread
          by tens of per cent, it says whether a change altered the work at all (`--pairs 0
          --instructions`: the counts alone, nothing paused; about 2-3 min per program).

  /usr/bin/python3 bench/ab_mc_settle.py [--ref df91a11] [--build build] [--pairs 9] [--large] [--lmp]
      [--taps 5] [--work DIR] [--ref-bench current|own] [--instructions [--functions 8]] [--csv FILE]
"""
import argparse
import csv
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
#: Files of the benchmark program copied onto the reference tree (--ref-bench current); the
#: scenes it includes (tests/unit/settle_test_scenes.h) stay the reference's own, which follow
#: that commit's types.
BENCH_FILES = ("bench/bench_mc_settle.cpp", "bench/bench_common.h")
#: A row of bench_mc_settle: label, value, unit.
ROW = re.compile(r"^(\S.*?)\s{2,}([0-9.]+) (M moves/s|s per tap)")


def cache_value(build, name, default=None):
    """A variable of build/CMakeCache.txt, or default."""
    path = os.path.join(build, "CMakeCache.txt")
    if not os.path.exists(path):
        return default
    with open(path) as f:
        for line in f:
            if line.startswith(name + ":"):
                return line.split("=", 1)[1].strip()
    return default


def run(cmd, **kw):
    """Runs cmd; on failure prints its output and stops with the command named."""
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, **kw)
    if p.returncode != 0:
        sys.stdout.write(p.stdout[-4000:])
        sys.exit(f"ab_mc_settle: '{' '.join(cmd)}' failed (exit {p.returncode})")
    return p.stdout


def build_reference(ref, work, candidate_build, ref_bench, targets):
    """Source of `ref` in work/<sha> (git archive, kept between calls) and its build; returns
    the build directory."""
    sha = run(["git", "-C", REPO, "rev-parse", "--short=10", ref + "^{commit}"]).strip()
    tree = os.path.join(work, f"{sha}-{ref_bench}")
    if not os.path.isdir(tree):
        os.makedirs(work, exist_ok=True)
        tmp = tempfile.mkdtemp(dir=work)
        archive = subprocess.Popen(["git", "-C", REPO, "archive", sha], stdout=subprocess.PIPE)
        run(["tar", "-x", "-C", tmp], stdin=archive.stdout)
        archive.wait()
        os.rename(tmp, tree)
    if ref_bench == "current":  # refreshed on every call: the benchmark code may have changed
        for rel in BENCH_FILES:
            src, dst = os.path.join(REPO, rel), os.path.join(tree, rel)
            if not os.path.exists(dst) or open(src).read() != open(dst).read():
                shutil.copyfile(src, dst)
    build = os.path.join(tree, "build")
    flags = [f"-DCMAKE_BUILD_TYPE={cache_value(candidate_build, 'CMAKE_BUILD_TYPE', 'Release')}",
             f"-DTAPMC_NATIVE={cache_value(candidate_build, 'TAPMC_NATIVE', 'OFF')}",
             "-DTAPMC_BUILD_PORES=OFF", "-DTAPMC_BUILD_TESTS=OFF", "-DTAPMC_BUILD_BENCH=ON",
             "-DTAPMC_PYTHON_USER_SITE=OFF"]
    headers = cache_value(candidate_build, "TAPMC_LAMMPS_HEADERS_DIR")
    if headers:
        flags.append(f"-DTAPMC_LAMMPS_HEADERS_DIR={headers}")
    print(f"reference {ref} = {sha}: building {', '.join(targets)} in {build}", flush=True)
    run(["cmake", "-S", tree, "-B", build] + flags)
    out = subprocess.run(["cmake", "--build", build, "-j2", "--target"] + targets,
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if out.returncode != 0:
        sys.stdout.write(out.stdout[-3000:])
        hint = " (try --ref-bench own: the reference's own program)" if ref_bench == "current" else ""
        sys.exit(f"ab_mc_settle: the reference {sha} does not build{hint}")
    return build


def kernel_rows(binary, own, large):
    """{label: M moves/s} of one bench_mc_settle run (--kernel, or --quick for --ref-bench own)."""
    out = run([binary, "--quick"] if own else [binary, "--kernel"] + (["--large"] if large else []))
    rows = {}
    for line in out.splitlines():
        m = ROW.match(line.strip())
        if m and m.group(3) == "M moves/s":
            rows[m.group(1).strip()] = float(m.group(2))
    if not rows:
        sys.exit(f"ab_mc_settle: no rows in the output of {binary}")
    return rows


def tap_rows(lmp, taps, work, label):
    """CPU seconds per tap of lmp_tapmc on the paper's scene, and the last tap's <Z>, Phi_b."""
    run_dir = os.path.join(work, f"tap-{label}")
    shutil.rmtree(run_dir, ignore_errors=True)
    os.makedirs(run_dir)
    cmd = [lmp, "-nocite", "-log", "log.lammps", "-screen", "none", "-in",
           os.path.join(REPO, "examples/paper/in.constant_eps"), "-var", "taps", str(taps),
           "-var", "eps", "0.0225", "-var", "seed", "7", "-var", "rsteps", str(10 * taps)]
    before = os.times()
    run(cmd, cwd=run_dir)
    after = os.times()
    cpu = (after.children_user - before.children_user) + (after.children_system -
                                                         before.children_system)
    loop = None
    with open(os.path.join(run_dir, "log.lammps")) as f:
        for line in f:
            if line.startswith("Loop time of"):
                loop = float(line.split()[3])
    with open(os.path.join(run_dir, "taps.dat")) as f:
        last = [line.split() for line in f if line.strip() and not line.startswith("#")][-1]
    return {"s per tap (loop)": loop / taps, "CPU s per process": cpu}, (last[1], last[3])


#: A function's line of callgrind_annotate: its Ir, the share, then "file:function [binary]".
ANNOTATE_LINE = re.compile(r"^\s*([0-9,]+) \(\s*[0-9.]+%\)\s+(.*?)\s*$")
#: The row of the whole program's instructions (CSV and table).
INSTRUCTIONS_ROW = "instructions, whole program (callgrind Ir)"


def parse_annotate(text):
    """(total Ir, {function: Ir}) from callgrind_annotate's output (--inclusive=no). A
    function is named without its source file (``???:`` when unknown) and without the binary in
    brackets, so that the same function of two builds has one name."""
    total, functions = None, {}
    for line in text.splitlines():
        m = ANNOTATE_LINE.match(line)
        if not m:
            continue
        ir, name = int(m.group(1).replace(",", "")), m.group(2)
        if name == "PROGRAM TOTALS":
            total = ir
            continue
        name = re.sub(r"\s+\[[^\]]*\]$", "", name).split(":", 1)[-1]  # "file:function"
        functions[name] = functions.get(name, 0) + ir
    if total is None:
        sys.exit("ab_mc_settle: callgrind_annotate printed no PROGRAM TOTALS line")
    return total, functions


def instruction_counts(binary, large, out_file):
    """(total Ir, {function: Ir}) of one `bench_mc_settle --kernel` run under callgrind."""
    for tool in ("valgrind", "callgrind_annotate"):
        if shutil.which(tool) is None:
            sys.exit(f"ab_mc_settle: --instructions needs '{tool}' on PATH "
                     f"(Debian: apt-get install valgrind)")
    run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out_file}", binary, "--kernel"]
        + (["--large"] if large else []))
    return parse_annotate(run(["callgrind_annotate", "--inclusive=no", "--threshold=100",
                               out_file]))


def instruction_table(ref, new, most):
    """Lines comparing two instruction counts: the totals and their ratio, then the `most`
    functions whose counts changed most (new - ref, largest |change| first)."""
    (ref_total, ref_fn), (new_total, new_fn) = ref, new
    lines = [f"{'total':46s} {ref_total:>16,d} {new_total:>16,d}   new / ref "
             f"{new_total / ref_total:.5f}"]
    changes = sorted(((new_fn.get(k, 0) - ref_fn.get(k, 0), k) for k in set(ref_fn) | set(new_fn)),
                     key=lambda c: -abs(c[0]))
    changes = [c for c in changes if c[0] != 0][:most]
    if changes:
        lines.append("largest changes by function (new - ref, share of the ref total):")
        lines += [f"  {d:+16,d} ({d / ref_total:+.4%})  {name[:110]}" for d, name in changes]
    else:
        lines.append("no function's count changed")
    return lines


#: Rows that are times or counts (lower is better); every other row is a rate.
TIME_ROWS = ("s per tap (loop)", "CPU s per process", INSTRUCTIONS_ROW)


def summarize(label, ref_values, new_values):
    """Medians and the speed-up of the working tree (> 1: faster), overall and pair by pair."""
    speedups = [(a / b if label in TIME_ROWS else b / a) for a, b in zip(ref_values, new_values)]
    ref_median, new_median = statistics.median(ref_values), statistics.median(new_values)
    return {"row": label, "ref_median": ref_median, "new_median": new_median,
            "speedup_of_medians": (ref_median / new_median if label in TIME_ROWS
                                   else new_median / ref_median),
            "pair_speedup_median": statistics.median(speedups),
            "pair_speedup_min": min(speedups), "pair_speedup_max": max(speedups),
            "pairs": len(speedups)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--ref", default="df91a11", help="reference commit (default df91a11)")
    ap.add_argument("--build", default=os.path.join(REPO, "build"),
                    help="the working tree's build directory (default build)")
    ap.add_argument("--pairs", type=int, default=9, help="alternating pairs (default 9)")
    ap.add_argument("--work", default=os.path.join(tempfile.gettempdir(), "tapmc-ab"),
                    help="where the reference is unpacked and built (kept between calls)")
    ap.add_argument("--ref-bench", choices=("current", "own"), default="current",
                    help="benchmark program of the reference: the working tree's (default) or its own")
    ap.add_argument("--lmp", action="store_true", help="also time a tap in lmp_tapmc")
    ap.add_argument("--no-kernel", action="store_true", help="skip the kernel rows")
    ap.add_argument("--large", action="store_true", help="kernel rows: also N = 262144")
    ap.add_argument("--taps", type=int, default=5, help="taps per lmp_tapmc run (default 5)")
    ap.add_argument("--instructions", action="store_true",
                    help="also count each kernel program's instructions under callgrind")
    ap.add_argument("--functions", type=int, default=8,
                    help="--instructions: how many functions' changes to list (default 8)")
    ap.add_argument("--csv", help="write the summary rows to this CSV file")
    args = ap.parse_args()
    if args.pairs < (0 if args.instructions else 1):
        sys.exit(f"ab_mc_settle: --pairs = {args.pairs}; allowed: an integer >= 1 "
                 f"(>= 0 with --instructions)")
    if args.instructions and args.no_kernel:
        sys.exit("ab_mc_settle: --instructions counts the kernel program; drop --no-kernel")
    if args.functions < 0:
        sys.exit(f"ab_mc_settle: --functions = {args.functions}; allowed: an integer >= 0")
    if args.taps < 1:
        sys.exit(f"ab_mc_settle: --taps = {args.taps}; allowed: an integer >= 1")
    build = os.path.abspath(args.build)
    if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
        sys.exit(f"ab_mc_settle: --build {build} is not a configured build directory")

    targets = ([] if args.no_kernel else ["bench_mc_settle"]) + (["lmp_tapmc"] if args.lmp else [])
    if not targets:
        sys.exit("ab_mc_settle: nothing to time (--no-kernel without --lmp)")
    print(f"candidate: working tree, building {', '.join(targets)} in {build}", flush=True)
    run(["cmake", "--build", build, "-j2", "--target"] + targets)
    ref_build = build_reference(args.ref, args.work, build, args.ref_bench, targets)
    programs = {"ref": ref_build, "new": build}
    own = args.ref_bench == "own"

    print(f"machine: {platform.processor() or platform.machine()}"
          f", TAPMC_NATIVE={cache_value(build, 'TAPMC_NATIVE', 'OFF')}, "
          f"load average at start {os.getloadavg()[0]:.2f}", flush=True)
    values = {"ref": {}, "new": {}}
    finals = {"ref": set(), "new": set()}
    t0 = time.time()
    for pair in range(args.pairs):
        order = ("ref", "new") if pair % 2 == 0 else ("new", "ref")
        for who in order:
            got = {}
            if not args.no_kernel:
                got.update(kernel_rows(os.path.join(programs[who], "bench", "bench_mc_settle"),
                                       own and who == "ref", args.large))
            if args.lmp:
                tap, final = tap_rows(os.path.join(programs[who], "lmp_tapmc"), args.taps,
                                      args.work, who)
                got.update(tap)
                finals[who].add(final)
            for label, v in got.items():
                values[who].setdefault(label, []).append(v)
        print(f"  pair {pair + 1}/{args.pairs} done ({time.time() - t0:.0f} s)", flush=True)

    rows = [summarize(label, values["ref"][label], values["new"][label])
            for label in values["new"] if label in values["ref"]]
    if args.pairs:
        print(f"\nload average at end {os.getloadavg()[0]:.2f}; {args.pairs} pairs, reference "
              f"{args.ref}; speed-up of the working tree (> 1: faster; rates new / ref, times "
              f"ref / new)")
        print(f"{'row':46s} {'ref':>9s} {'new':>9s} {'speed-up':>8s} "
              f"{'pairs: median [min, max]':>26s}")
        for r in rows:
            print(f"{r['row']:46s} {r['ref_median']:9.3f} {r['new_median']:9.3f} "
                  f"{r['speedup_of_medians']:8.3f}   {r['pair_speedup_median']:.3f} "
                  f"[{r['pair_speedup_min']:.3f}, {r['pair_speedup_max']:.3f}]")
    if args.lmp:
        same = finals["ref"] == finals["new"] and len(finals["new"]) == 1
        print(f"last tap (Phi_b, <Z>): ref {sorted(finals['ref'])}, new {sorted(finals['new'])}: "
              f"{'identical' if same else 'DIFFERENT'}")
    if args.instructions:
        counts = {}
        for who in ("ref", "new"):
            print(f"  counting the instructions of {who} under callgrind", flush=True)
            counts[who] = instruction_counts(
                os.path.join(programs[who], "bench", "bench_mc_settle"), args.large,
                os.path.join(args.work, f"callgrind.{who}"))
        print(f"\ninstructions (callgrind, bench_mc_settle --kernel, one run each: exact, "
              f"whatever else runs)\n{'':46s} {'ref':>16s} {'new':>16s}")
        print("\n".join(instruction_table(counts["ref"], counts["new"], args.functions)))
        rows.append(summarize(INSTRUCTIONS_ROW, [counts["ref"][0]], [counts["new"][0]]))
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)


if __name__ == "__main__":
    main()
