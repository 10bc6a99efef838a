# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Pieces shared by the Python benchmarks of bench/: LAMMPS log tables, child CPU time, the
mean and standard error over seeds, and the resumable per-run CSV files."""
import csv
import math
import os
import resource


def thermo_rows(lines):
    """Every thermo row (dict column -> float) of the LAMMPS output `lines`, in order; lines
    that are not rows (warnings between rows) are skipped."""
    rows, header = [], None
    for line in lines:
        words = line.split()
        if words[:1] == ["Step"]:
            header = words
            continue
        if line.startswith("Loop time of"):
            header = None
            continue
        if header and len(words) == len(header):
            try:
                rows.append(dict(zip(header, [float(w) for w in words])))
            except ValueError:
                continue
    return rows


def log_thermo_rows(path):
    """thermo_rows of a LAMMPS log file."""
    with open(path) as f:
        return thermo_rows(f.read().splitlines())


def loop_time(lines):
    """(seconds, number of atoms) of the last 'Loop time of ...' line, or (None, None)."""
    seconds = atoms = None
    for line in lines:
        if line.startswith("Loop time of"):
            words = line.split()
            seconds, atoms = float(words[3]), int(words[-2])
    return seconds, atoms


def child_cpu():
    """User + system CPU seconds of the finished child processes so far."""
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def mean_se(values):
    """Mean and standard error of the mean (nan where undefined)."""
    n = len(values)
    if n == 0:
        return float("nan"), float("nan")
    m = sum(values) / n
    if n < 2:
        return m, float("nan")
    return m, math.sqrt(sum((v - m) ** 2 for v in values) / (n - 1) / n)


def read_runs(path, taps):
    """The rows of a per-run CSV file (absent: none) made with `taps` taps."""
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return [r for r in csv.DictReader(f) if int(r["taps"]) == taps]
