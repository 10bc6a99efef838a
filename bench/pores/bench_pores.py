#!/usr/bin/python3
# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Benchmark of tapmc-pores against scipy/Qhull doing the same job in the same run: time, CPU time,
# peak RSS (each computation in its own process, measured with wait4), and the ratio.
"""Usage: /usr/bin/python3 bench/pores/bench_pores.py [--build BUILD_DIR] [--sizes 4096,100000,1000000]
       [--frames 20] [--qhull-max 1000000] [--workdir DIR]

BUILD_DIR defaults to $TAPMC_BUILD_DIR, else "build"; the packings and outputs go to --workdir,
default BUILD_DIR/bench/pores/work (kept between runs: the packings are generated once).

Packings: random sequential addition of hard spheres (phi = 0.33) from bench_pores_packing; the
4096-sphere frame has the paper's geometry (32R x 32R, periodic in x and y, walls in z). Larger
frames are periodic in x and y, with walls in z, in a box about as tall as wide.
The Qhull side: images of the centres within the same padding (4R) of the periodic faces, scipy's
Delaunay (Qhull), circumcentres and radii in numpy, cells kept when their circumcentre is in the
box: the same pores (random packings have no degenerate vertex to merge).
"""
import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np

R = 0.5
PADDING = 4 * R  # tapmc-pores default (pores_config.h)


def measured(cmd):
    """Runs cmd; wall and CPU seconds and peak RSS (MiB) of that process alone (wait4)."""
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    out, err = proc.stdout.read(), proc.stderr.read()
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"bench_pores: {' '.join(cmd)} failed:\n{err}")
    return {"wall": wall, "cpu": usage.ru_utime + usage.ru_stime, "rss_mib": usage.ru_maxrss / 1024,
            "stdout": out, "stderr": err}


def read_dump(path):
    with open(path) as f:
        lines = [next(f) for _ in range(9)]
        n = int(lines[3])
        bounds = np.array([[float(v) for v in lines[5 + k].split()] for k in range(3)])
        periodic = [flag == "pp" for flag in lines[4].split()[3:6]]
        data = np.loadtxt(f, max_rows=n)
    return data[:, 2:5], bounds, periodic


def qhull_job(path):
    """The scipy/Qhull computation (run in a child process): prints seconds and pore count."""
    from scipy.spatial import Delaunay
    centres, bounds, periodic = read_dump(path)
    start = time.perf_counter()
    lo, hi = bounds[:, 0], bounds[:, 1]
    length = hi - lo
    points = [centres]
    for shift in np.ndindex(3, 3, 3):
        s = np.array(shift) - 1
        if not s.any() or any(s[k] != 0 and not periodic[k] for k in range(3)):
            continue
        image = centres + s * length
        keep = np.all([(image[:, k] >= lo[k] - PADDING) & (image[:, k] < hi[k] + PADDING)
                       for k in range(3) if periodic[k]], axis=0)
        points.append(image[keep])
    points = np.vstack(points)
    tri = Delaunay(points)
    p = points[tri.simplices]
    a = p[:, 1:] - p[:, :1]
    det = np.linalg.det(a)
    ok = np.abs(det) > 1e-14
    centre = np.linalg.solve(a[ok], 0.5 * np.einsum("nij,nij->ni", a[ok], a[ok])[..., None])[..., 0] + p[ok, 0]
    radius = np.linalg.norm(centre - p[ok, 0], axis=1)
    inside = np.all([(centre[:, k] >= lo[k]) & (centre[:, k] < hi[k]) for k in range(3) if periodic[k]], axis=0)
    xi = radius[inside] / R - 1
    seconds = time.perf_counter() - start
    print(json.dumps({"seconds": seconds, "pores": int(len(xi)), "nu": float(np.mean(xi ** 3))}))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.environ.get("TAPMC_BUILD_DIR", "build"))
    parser.add_argument("--sizes", default="4096,100000,1000000")
    parser.add_argument("--frames", type=int, default=20, help="frames in the 4096-sphere dump")
    parser.add_argument("--qhull-max", type=int, default=1000000, help="largest size also run with Qhull")
    parser.add_argument("--workdir", help="default: BUILD_DIR/bench/pores/work")
    parser.add_argument("--qhull", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.qhull:
        return qhull_job(args.qhull)

    tool = os.path.join(args.build, "tools/pores/tapmc-pores")
    generator = os.path.join(args.build, "bench/pores/bench_pores_packing")
    for program in (tool, generator):
        if not os.access(program, os.X_OK):
            sys.exit(f"bench_pores: {program} not found: build it, or give the build directory with --build")
    if args.workdir is None:
        args.workdir = os.path.join(args.build, "bench/pores/work")
    os.makedirs(args.workdir, exist_ok=True)
    print(f"machine: {os.uname().nodename}, {os.cpu_count()} cores, load {os.getloadavg()[0]:.2f}; "
          "times are one core (tapmc-pores is serial; Qhull too)")
    print(f"{'N':>9} {'frames':>6} | {'tapmc-pores s/frame':>19} {'cpu s':>7} {'RSS MiB':>8} | "
          f"{'Qhull s/frame':>13} {'RSS MiB':>8} | {'speed-up':>8}  pores of frame 1 (tool / Qhull)")
    for n in [int(v) for v in args.sizes.split(",")]:
        frames = args.frames if n <= 4096 else 1
        side = 16.0 if n <= 4096 else round((n * 4 / 3 * np.pi * R ** 3 / 0.33) ** (1 / 3), 3)
        dump = os.path.join(args.workdir, f"packing_{n}.dump")
        if not os.path.exists(dump):
            subprocess.run([generator, "--n", str(n), "--lx", str(side), "--ly", str(side), "--phi", "0.33",
                            "--frames", str(frames), "--output", dump], check=True, capture_output=True)
        prefix = os.path.join(args.workdir, f"out_{n}")
        run = measured([tool, "-q", "-o", prefix, dump])
        table = np.genfromtxt(prefix + ".frames.csv", delimiter=",", names=True, dtype=None, encoding=None)
        per_frame = float(np.median(np.atleast_1d(table["seconds"])))
        pores = int(np.atleast_1d(table["pores"])[0])
        unresolved = int(np.atleast_1d(table["unresolved"])[0])
        row = (f"{n:>9} {frames:>6} | {per_frame:>19.4f} {run['cpu']:>7.2f} {run['rss_mib']:>8.0f} | ")
        if n <= args.qhull_max:
            q = measured([sys.executable, os.path.abspath(__file__), "--qhull", dump])
            result = json.loads(q["stdout"])
            row += (f"{result['seconds']:>13.4f} {q['rss_mib']:>8.0f} | {result['seconds'] / per_frame:>7.1f}x  "
                    f"{pores} (+{unresolved} unresolved) / {result['pores']}")
        else:
            row += f"{'-':>13} {'-':>8} | {'-':>8}  {pores}"
        print(row, flush=True)
    print("tapmc-pores s/frame: analysis of one frame (median), without reading the text dump; cpu s and RSS:"
          " the whole process (all frames, dump parsing included). Qhull: the same pore computation in"
          " scipy (Delaunay + numpy circumcentres + selection), dump parsing excluded. Pore counts differ by"
          " the flat hull cells above the free surfaces: tapmc-pores reports them as unresolved, Qhull keeps"
          " those whose circumcentre falls in the box in x and y.")


if __name__ == "__main__":
    main()
