# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Statistics of the model's knobs (section II): theta0 = pi/4 and d_max = R/5, from the knob
scans and the run-time-versus-error front."""

from __future__ import annotations

import math

import numpy as np

from tapmc.stats import mean_dof

from ..front import DEFAULT as FRONT_DEFAULT_SETTING
from .common import above, below
from .measure import Measure, fmt
from .register import PAPER_SCALE
from .registry import statistic
from .scan_tables import SCANS, THETA_LAW_SCAN_STEMS, scan_settings, scan_table


@statistic("dmax_intermediate")
def dmax_intermediate(data, claim):
    """d_max = R/5 against R/10 and R/2 on the front (same eta and stop rule, so about the same
    sweeps per tap): steady <Phi^c> of R/5 minus that of the other d_max, from their paired
    biases against the front's reference (error: both standard errors in quadrature, which
    over-states it, the two sharing the reference). Positive: the other d_max leaves the packing
    looser at the same cost, i.e. redeposits more slowly."""
    measures = []
    # per N and eps of the front (the settings of one N and eps share their seeds)
    for N, eps in sorted({(r["N"], r["eps"]) for r in data.front}):
        at = {r["setting"]: r for r in data.front if r["N"] == N and r["eps"] == eps}
        base = at.get(FRONT_DEFAULT_SETTING)
        for name in ("dmax R/10", "dmax R/2"):
            other = at.get(name)
            if base is None or other is None:
                continue
            d = base["phi_c_steady_bias"] - other["phi_c_steady_bias"]
            se = math.hypot(base["phi_c_steady_bias_se"], other["phi_c_steady_bias_se"])
            n = int(min(base["paired_seeds"], other["paired_seeds"]))
            measures.append(Measure(d, se, mean_dof(n), label=(
                f"eps = {eps:g}, N = {other['N']:.0f}: <Phi^c>(R/5) - <Phi^c>({name[5:]}), steady, "
                f"at {base['sweeps_per_tap']:.0f} and {other['sweeps_per_tap']:.0f} sweeps per tap"),
                lacks=_size_lacking(N)))
    for rows in data.scans["dmax"]:
        if rows:
            measures += _dmax_scan_measures(rows)
    return measures or [Measure(undecided="neither the front (doc/front.rst) nor a d_max scan "
                                          "(tapmc-paper question dmax) has measured d_max")]


def _scan_label(rows, n=None):
    first = rows[0]
    return (f"N = {first['N']}, eps = {float(first['eps']):g}, {scan_settings(rows)}: <Phi^c> "
            f"over taps {int(first['taps']) - 9}-{first['taps']} minus t = 0"
            + (f", {n} seeds" if n else ""))


@statistic("theta0_optimum")
def theta0_optimum(data, claim):
    """Section II: the paper's theta0 = pi/4 compacts most, a much smaller theta0 decompacts,
    a large one compacts less. From the theta0 scan (same packings, taps at fixed eps): 1 when
    no theta0 compacts more than pi/4 beyond t sem (paired), the smallest theta0 decompacts
    (gain below zero beyond t sem) and the largest compacts less than pi/4 (beyond t sem); 0
    when any of these is contradicted beyond t sem; undecided otherwise."""
    measures = [_theta0_measure(rows) for rows in data.scans["theta0"] if rows]
    return measures or [Measure(undecided="no theta0 scan (tapmc-paper question theta0)")]


def _size_lacking(N):
    """("size",) for runs of another N than the paper's, () for the paper's."""
    return () if int(float(N)) == PAPER_SCALE["N"] else ("size",)


def _theta0_measure(rows):
    m = _theta0_verdict(rows)
    m.lacks = _size_lacking(rows[0]["N"])
    return m


def _theta0_verdict(rows):
    table = scan_table(rows, "theta0")
    label = _scan_label(rows)
    if len(table) < 3 or not any(r["is_paper"] for r in table):
        return Measure(label=label, undecided="fewer than three theta0, or no pi/4, in the scan")
    n = min(r["n"] for r in table)
    if n < 2:
        return Measure(label=label, undecided="one seed per theta0")
    dof = n - 1
    label = _scan_label(rows, n)
    shown = "; ".join(f"{r['name']}: {fmt(r['gain'], r['gain_sem'], True)}" for r in table)
    better = [r for r in table
              if not r["is_paper"] and above(r["vs_paper"], r["vs_paper_sem"], dof)]
    small, large = table[0], table[-1]
    checks = {
        "no theta0 compacts more than pi/4": (not better, bool(better)),
        f"{small['name']} decompacts":
            (below(small["gain"], small["gain_sem"], dof),
             above(small["gain"], small["gain_sem"], dof)),
        f"{large['name']} compacts less than pi/4":
            (below(large["vs_paper"], large["vs_paper_sem"], dof),
             above(large["vs_paper"], large["vs_paper_sem"], dof)),
    }
    shown += f"; most: {max(table, key=lambda r: r['gain'])['name']}"
    contradicted = [k for k, (_, no) in checks.items() if no]
    open_ = [k for k, (yes, no) in checks.items() if not yes and not no]
    if contradicted:
        return Measure(0.0, label=label, shown=shown + "; contradicted: " + ", ".join(contradicted))
    if open_:
        return Measure(label=label, shown=shown, undecided="within t sem: " + ", ".join(open_))
    return Measure(1.0, label=label, shown=shown)


def _dmax_scan_measures(rows):
    """From a d_max scan, the paper's two sides of "intermediate" (section II), each with its
    own quantity, paired over the seeds (sign +: the paper's): a much smaller d_max leaves the
    packing "nearly frozen", its redeposition having a "very slight" effect: the compaction
    over the taps at R/5 minus at the smallest d_max; with a much larger one "the packing
    evolves very slowly": the compaction per sweep of the redeposition (per tap over the
    sweeps per tap) at R/5 minus at the largest."""
    table = scan_table(rows, "dmax")
    if len(table) < 3 or not any(r["is_paper"] for r in table):
        return [Measure(label=_scan_label(rows), undecided="fewer than three d_max, or no R/5")]
    n = min(r["n"] for r in table)
    most = max(table, key=lambda r: r["gain"])["name"]
    out = []
    small, large = table[0], table[-1]
    if not small["is_paper"]:
        out.append(Measure(-small["vs_paper"], small["vs_paper_sem"], mean_dof(n), label=(
            f"d_max scan, {_scan_label(rows, n)}: compaction with R/5 minus with "
            f"{small['name']} (nearly frozen); most with {most}"),
            lacks=_size_lacking(rows[0]["N"])))
    if not large["is_paper"]:
        value, err, seeds = _per_sweep_vs_paper(rows, large["value"])
        out.append(Measure(value, err, mean_dof(seeds), label=(
            f"d_max scan, {_scan_label(rows, n)}: compaction per sweep with R/5 minus with "
            f"{large['name']} (evolves very slowly)"),
            shown=f"{fmt(value, err)} per sweep of the redeposition",
            lacks=_size_lacking(rows[0]["N"])))
    return out


def _per_sweep_vs_paper(rows, value):
    """(mean, sem, seeds) over the seeds of the compaction per sweep of the redeposition,
    (<Phi^c>(end) - <Phi^c>(0)) / (taps x sweeps per tap), at R/5 minus at d_max ``value``
    (over R), paired on the seeds both have."""
    column, paper = SCANS["dmax"]["column"], SCANS["dmax"]["paper"]
    values = sorted({float(r[column]) for r in rows})
    at_paper = min(values, key=lambda f: abs(f - paper))

    def per_sweep(at):
        return {int(r["seed"]): (float(r["phi_c_end"]) - float(r["phi_c_0"]))
                / (float(r["taps"]) * float(r["sweeps_per_tap"]))
                for r in rows if float(r[column]) == at}

    mine, other = per_sweep(at_paper), per_sweep(value)
    d = np.array([mine[k] - other[k] for k in sorted(set(mine) & set(other))])
    if len(d) < 2:
        return (float(d.mean()) if len(d) else math.nan), math.nan, len(d)
    return float(d.mean()), float(d.std(ddof=1) / math.sqrt(len(d))), len(d)


@statistic("theta_law_shape")
def theta_law_shape(data, claim):
    """Section II: "a Poissonian and a linear distribution give qualitatively the same
    phenomenology; the pertinent parameter is the width theta0". Per alternative law and scan,
    against eq. 1's scan of the same N, stop rule and eta (the same packings): the phenomenology
    of theta0 that section II states for eq. 1 (a very small width decompacts, a large one
    compacts), read at the scan's smallest and largest width (beyond the seeds' t sem). 1 when
    the law does what eq. 1 does at both ends; 0 when it goes the other way at an end where
    both are decided; undecided otherwise. Shown: where each law turns from decompaction to
    compaction, in theta0 and in the mean angle <theta> of its moves (whether the width, read
    as <theta>, is the pertinent parameter)."""
    measures = []
    for stem in THETA_LAW_SCAN_STEMS:
        rows = data.question(stem)
        if not rows:
            continue
        gaussian = [g for g in data.scans["theta0"] if g and _same_scan(g[0], rows[0])]
        if not gaussian:
            measures.append(Measure(label=f"{stem}: {_scan_label(rows)}", undecided=(
                "no scan of eq. 1's law at the same N, stop rule and eta")))
            continue
        measures.append(_law_shape_measure(stem.split("_")[1], rows, gaussian[0]))
    return measures or [Measure(undecided=(
        "no scan of the alternative laws (tapmc-paper question theta0 --theta-law "
        "exponential | linear)"))]


def _same_scan(a, b):
    return all(str(a.get(k)) == str(b.get(k)) for k in ("N", "eps", "taps", "stop")) and \
        float(a.get("eta", 1e-7)) == float(b.get("eta", 1e-7))


def _way(row, dof):
    """+1 compacts, -1 decompacts (beyond t sem), 0 within it."""
    if above(row["gain"], row["gain_sem"], dof):
        return 1
    return -1 if below(row["gain"], row["gain_sem"], dof) else 0


def theta_law_density(law, theta0, theta):
    """The unnormalised density of theta under fix mc/settle's theta_law ``law`` ('angle':
    eq. 1; 'exponential', 'linear': section II's alternatives as TAPMC reads them)."""
    x = np.asarray(theta, dtype=float) / theta0
    if law == "exponential":
        return np.exp(-x)
    if law == "linear":
        return np.clip(1.0 - x, 0.0, None)
    return np.exp(-x * x)


def mean_angle(law, theta0, points=20001):
    """<theta> of the moves of ``law`` at width ``theta0`` on [0, pi/2] (trapezoid rule)."""
    theta = np.linspace(0.0, 0.5 * math.pi, points)
    weight = theta_law_density(law, theta0, theta)
    weight[[0, -1]] *= 0.5          # the trapezoid rule on a uniform grid
    return float(np.sum(theta * weight) / np.sum(weight))


def turning_width(table, law):
    """(theta0, <theta>) where the compaction of a scan first turns from negative to positive
    as the width grows (linear between the two widths around it); None when it does not."""
    for a, b in zip(table, table[1:]):
        if a["gain"] < 0.0 <= b["gain"]:
            f = a["gain"] / (a["gain"] - b["gain"])
            mean_a, mean_b = (mean_angle(law, math.pi * r["value"]) for r in (a, b))
            return math.pi * (a["value"] + f * (b["value"] - a["value"])), \
                mean_a + f * (mean_b - mean_a)
    return None


def _turning_text(table, law):
    turn = turning_width(table, law)
    if turn is None:
        return "no turn within the scan"
    return (f"turns at theta0 = {turn[0] / math.pi:.3f} pi, "
            f"<theta> = {math.degrees(turn[1]):.1f} deg")


def _law_shape_measure(law, rows, gaussian_rows):
    mine, eq1 = scan_table(rows, "theta0"), scan_table(gaussian_rows, "theta0")
    n = min([r["n"] for r in mine + eq1] or [0])
    label = f"{law} P(theta) against eq. 1's, {_scan_label(rows, n)}"
    lacks = _size_lacking(rows[0]["N"])
    if n < 2 or len(mine) < 2 or len(eq1) < 2:
        return Measure(label=label, lacks=lacks,
                       undecided="fewer than two seeds or two widths per scan")
    dof = n - 1
    shown = "; ".join(f"{r['name']}: {fmt(r['gain'], r['gain_sem'], True)}" for r in mine)
    shown += (f"; {law} {_turning_text(mine, law)}; eq. 1 {_turning_text(eq1, 'angle')}")
    ends = {"smallest": (mine[0], eq1[0]), "largest": (mine[-1], eq1[-1])}
    other_way, open_ = [], []
    for end, (a, b) in ends.items():
        way, eq1_way = _way(a, dof), _way(b, dof)
        if way and eq1_way and way != eq1_way:
            other_way.append(f"{end} width {a['name']}")
        elif not (way and eq1_way):
            open_.append(f"{end} width {a['name']}")
    if other_way:
        return Measure(0.0, label=label, lacks=lacks,
                       shown=shown + "; the other way than eq. 1 at the " + ", ".join(other_way))
    if open_:
        return Measure(label=label, lacks=lacks, shown=shown,
                       undecided="within t sem at the " + ", ".join(open_))
    return Measure(1.0, label=label, lacks=lacks, shown=shown)
