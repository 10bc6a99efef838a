# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The knob scans of tapmc-paper question (theta0, d_max): where their CSVs are, how a
scan's values are written and the table of compaction per value."""

from __future__ import annotations

import csv
import math
from fractions import Fraction
from pathlib import Path

import numpy as np


def _fraction(frac, unit, limit):
    """frac x unit as the report writes it (pi/4, 5pi/12, R/50, R)."""
    f = Fraction(frac).limit_denominator(limit)
    return (unit if f.numerator == 1 else f"{f.numerator}{unit}") + (
        f"/{f.denominator}" if f.denominator != 1 else "")


def _pi_fraction(frac):
    return _fraction(frac, "pi", 48)


def _r_fraction(frac):
    return _fraction(frac, "R", 100)


#: the knob scans of tapmc-paper question: CSV column of the value, the paper's value, how
#: a value is written
SCANS = {"theta0": {"column": "theta0_over_pi", "paper": 0.25, "name": _pi_fraction},
         "dmax": {"column": "dmax_over_R", "paper": 0.2, "name": _r_fraction}}


#: section II's alternative laws of theta (fix mc/settle theta_law), scanned in theta0 like
#: eq. 1 (tapmc-paper question theta0 --theta-law LAW: theta0_<law>[_N4096].csv): the claim
#: theta-law-shape reads them
ALTERNATIVE_THETA_LAWS = ("exponential", "linear")
THETA_LAW_SCAN_STEMS = tuple(f"theta0_{law}{size}" for law in ALTERNATIVE_THETA_LAWS
                             for size in ("", "_N4096"))

#: tags of scans that test another reading of the model, not the paper's claim about eq. 1's
#: theta0 (theta0 --theta-law solid: P(theta) per unit solid angle; --wide: theta0 beyond the
#: paper's pi/2; the alternative laws): solid and wide measured in doc/measurements.rst, left
#: out of the claims; the alternative laws read by theta-law-shape only
OTHER_READING_TAGS = ("solid", "wide") + ALTERNATIVE_THETA_LAWS


def scan_files(folder, knob):
    """The CSVs of one knob's scans in ``folder``: <knob>.csv, <knob>_<stop>.csv (not those
    tagged with :data:`OTHER_READING_TAGS`)."""
    folder = Path(folder)
    return sorted([p for p in folder.glob(f"{knob}*.csv")
                   if (p.stem == knob or p.stem.startswith(knob + "_")) and
                   not set(p.stem.split("_")[1:]) & set(OTHER_READING_TAGS)])


def read_scan(path):
    """Rows of a CSV of tapmc-paper question (a knob scan: theta0 / dmax; the initial
    packings)."""
    with open(path, newline="") as handle:
        return list(csv.DictReader(handle))


def scan_settings(rows):
    """The redeposition setting of a scan, as the report writes it."""
    r = rows[0]
    return f"stop {r.get('stop', 'change')}, eta = {float(r.get('eta', 1e-7)):g}"


def scan_table(rows, knob):
    """Per value of a knob scan: the compaction over the scan's taps, <Phi^c>(end) -
    <Phi^c>(0), mean and standard error over seeds, and its paired difference from the
    paper's value on the same seeds (same initial packing). Sorted by value."""
    spec = SCANS[knob]
    by_value = {}
    for r in rows:
        by_value.setdefault(float(r[spec["column"]]), {})[int(r["seed"])] = (
            float(r["phi_c_end"]) - float(r["phi_c_0"]))
    paper = min(by_value, key=lambda f: abs(f - spec["paper"])) if by_value else None
    out = []
    for value in sorted(by_value):
        gains = by_value[value]
        seeds = sorted(set(gains) & set(by_value[paper]))
        g = np.array([gains[k] for k in seeds])
        d = np.array([gains[k] - by_value[paper][k] for k in seeds])
        n = len(seeds)
        sem = (lambda a: float(np.std(a, ddof=1) / math.sqrt(n)) if n > 1 else math.nan)
        out.append({"value": value, "name": spec["name"](value), "n": n,
                    "gain": float(g.mean()) if n else math.nan, "gain_sem": sem(g),
                    "vs_paper": float(d.mean()) if n else math.nan,
                    "vs_paper_sem": 0.0 if value == paper else sem(d), "is_paper": value == paper})
    return out
