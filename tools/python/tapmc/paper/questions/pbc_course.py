# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""pbc-course: how long does the dip of <Phi^c> after the first taps last, and does the
packing loosen at strong taps (eps >= 0.09)? From every finished P.B.C. constant-eps run of
the paper-scale campaign (no simulation: its taps.dat): <Phi^c> at t = 0, the lowest of the
first taps and when, the first tap from which a 10-tap running mean stays at or above the
t = 0 value for 10 taps, and the steady state (last 1000 taps, batch-means error) and the
difference of its two halves (is the packing still compacting at the end?) (pbc_course.csv)."""

from __future__ import annotations

import math
from collections import defaultdict

import numpy as np

from tapmc.fluctuations import DEFAULT_BATCHES, DEFAULT_LAST, SteadyState
from tapmc.stats import beyond

from .._rst import list_table
from ..claims import fmt
from .common import csv_schema, eps_of, finished_runs, require_steady_window, taps_table

NAME = "pbc-course"
CSV = "pbc_course.csv"
HEADER = ["run", "eps", "seed", "taps", "phi_c_0", "phi_c_min", "tap_min", "tap_back",
          "phi_c_steady", "phi_c_steady_sem", "phi_c_steady_sd", "steady_halves_diff",
          "steady_halves_diff_sem"]
#: taps of the running mean that decides when <Phi^c> has regained its t = 0 value (the
#: tap-to-tap spread at strong taps, 0.1 %, is a third of the dip's depth; ten taps average it
#: down below a tenth of the dip) and that it must then stay there for.
COURSE_SMOOTHING = 10
#: first taps searched for the lowest <Phi^c> (the dip is over by tap 100 at every eps).
COURSE_EARLY = 100

#: the strong taps of the question on loosening (issue of the paper-scale validation: the
#: packing was seen to loosen at eps >= 0.09, where Fig. 4's bell falls)
STRONG_EPS = 0.09
#: degrees of freedom of the difference of the steady window's halves (each half has half the
#: batches of tapmc.fluctuations.SteadyState)
HALVES_DOF = DEFAULT_BATCHES // 2 - 1


def add_arguments(parser):
    """No options beyond --campaign and --out."""


def recovery_tap(t, phi, level, width=COURSE_SMOOTHING):
    """First tap t_k (k >= 1) from which the running mean of ``width`` taps, phi[k..k+width),
    is at least ``level`` for ``width`` consecutive starts: the end of the dip below the
    initial packing; None when the series never regains it."""
    if len(phi) < 2 * width:
        return None
    running = np.convolve(phi, np.ones(width) / width, mode="valid")
    above = running >= level
    for k in range(1, len(above) - width + 1):
        if above[k:k + width].all():
            return int(t[k])
    return None


def steady_halves(x, steady):
    """(second half minus first half of the steady window, its error, its dof): each half
    with its batch-means error over half the batches (is the run still compacting?)."""
    half = steady.last // 2
    batches = steady.batches // 2
    first, second = (SteadyState(part, last=half, batches=batches).compute()
                     for part in (x[-steady.last:-half], x[-half:]))
    return (second.mean - first.mean, float(np.hypot(first.sem, second.sem)),
            2 * (min(batches, half // 2) - 1))


def analyse(campaign):
    """The rows of pbc_course.csv, one per finished P.B.C. constant-eps run."""
    rows = []
    for run_dir in finished_runs(campaign, "const_pbc_eps*_s*"):
        table = taps_table(run_dir / "taps.dat")
        t, phi = table["step"], table["phi_c"]
        eps = eps_of(run_dir.name)
        seed = int(run_dir.name.rsplit("_s", 1)[1])
        early = (t >= 1) & (t <= COURSE_EARLY)
        k = int(np.flatnonzero(early)[np.argmin(phi[early])])
        back = recovery_tap(t, phi, phi[0])
        require_steady_window(run_dir, len(phi) - 1, DEFAULT_LAST)
        steady = SteadyState(phi[1:]).compute()
        # still compacting? the second half of the steady window minus its first half
        drift, drift_se, _ = steady_halves(phi, steady)
        rows.append([run_dir.name, eps, seed, len(t) - 1, f"{phi[0]:.8f}", f"{phi[k]:.8f}",
                     int(t[k]), "" if back is None else back, f"{steady.mean:.8f}",
                     f"{steady.sem:.3g}", f"{steady.std:.3g}", f"{drift:.3g}", f"{drift_se:.3g}"])
        print(f"{run_dir.name}: phi_c {phi[0]:.4f} -> min {phi[k]:.4f} at tap {int(t[k])}, "
              f"back at tap {back}, steady {steady.mean:.4f} +- {steady.sem:.4f}, "
              f"halves differ by {drift:+.4f} +- {drift_se:.4f}")
    return rows


def measure(args):
    save(args.out / CSV, analyse(args.campaign))


save, load = csv_schema(HEADER)


def render(path, factors=None):
    """``factors``: realization factors (tapmc.paper.claims.realization_factors) that turn
    the runs' batch-means errors of <Phi^c>'s steady state and halves into a realization's."""
    rows = load(path)
    steady_k = (factors or {}).get("phi_c", (1.0, None))[0]
    halves_k = (factors or {}).get("phi_c:halves", (1.0, None))[0]
    if not rows:
        return []
    by_eps = defaultdict(list)
    for r in rows:
        by_eps[float(r["eps"])].append(r)
    lines = ["How long does the dip of <Phi^c> after the first taps last, and does the packing "
             f"loosen at strong taps (eps >= {STRONG_EPS:g})? The course of <Phi^c> in every "
             "P.B.C. run of the campaign (``pbc_course.csv``; back from: the first tap from "
             "which a 10-tap running mean stays at or above the t = 0 value for 10 taps; "
             "steady: the last 1000 taps, batch-means error; halves: the steady window's "
             "second half minus its first" + (
                 f"; both errors times the realizations' factor, {steady_k:.1f} and "
                 f"{halves_k:.1f} (realization-scatter)" if (steady_k, halves_k) != (1.0, 1.0)
                 else "") + "):", ""]
    table, summary = [], {}
    for eps in sorted(by_eps):
        group = by_eps[eps]
        for r in sorted(group, key=lambda r: int(r["seed"])):
            back = r["tap_back"] or "never"
            table.append([
                f"{eps:g}", r['seed'], fmt(float(r['phi_c_0']), None, True),
                f"{fmt(float(r['phi_c_min']), None, True)} ({r['tap_min']})", back,
                fmt(float(r['phi_c_steady']), steady_k * float(r['phi_c_steady_sem']), True),
                fmt(float(r['steady_halves_diff']),
                    halves_k * float(r['steady_halves_diff_sem']), True)])
        col = {k: np.array([float(r[k]) if r[k] != "" else math.nan for r in group])
               for k in ("phi_c_0", "phi_c_min", "tap_back", "phi_c_steady", "phi_c_steady_sem",
                         "steady_halves_diff", "steady_halves_diff_sem")}
        col["phi_c_steady_sem"] = col["phi_c_steady_sem"] * steady_k
        col["steady_halves_diff_sem"] = col["steady_halves_diff_sem"] * halves_k
        n = len(group)
        summary[eps] = {"depth": float(np.mean(col["phi_c_0"] - col["phi_c_min"])),
                        "back": col["tap_back"],
                        "gain": float(np.mean(col["phi_c_steady"] - col["phi_c_0"])),
                        "steady": float(np.mean(col["phi_c_steady"])),
                        "steady_se": float(np.sqrt(np.sum(col["phi_c_steady_sem"] ** 2)) / n),
                        "halves": float(np.mean(col["steady_halves_diff"])),
                        "halves_se": float(np.sqrt(np.sum(col["steady_halves_diff_sem"] ** 2))
                                           / n)}
    header = ["eps", "seed", "<Phi^c> at t = 0", "lowest (tap)", "back from tap", "steady",
              "halves"]
    return lines + list_table(header, table) + _readings(summary)


def _readings(summary):
    """The dip's course with eps and the strong taps' steady states, from the per-eps
    ``summary`` of :func:`render`."""
    lines = []
    eps_sorted = sorted(summary)
    def grows(values):
        return all(b >= a for a, b in zip(values, values[1:]))

    deeper = grows([summary[e]["depth"] for e in eps_sorted])
    lengths = [float(np.max(summary[e]["back"])) for e in eps_sorted]
    longer = all(np.isfinite(lengths)) and grows(lengths)

    def back_text(e):
        back = summary[e]["back"]
        if np.any(~np.isfinite(back)):
            return "never regains it"
        return f"regains it from tap {int(np.max(back))}"

    lines += ["", "* The dip: " + "; ".join(
        f"eps = {e:g}: {fmt(summary[e]['depth'], None, True)} below t = 0, {back_text(e)}"
        for e in eps_sorted) + ". The dip " + (
        "deepens" if deeper else "does not deepen steadily") + " and " + (
        "lengthens" if longer else "does not lengthen steadily") + " with eps."]
    top = max(eps_sorted, key=lambda e: summary[e]["steady"])
    strong = [e for e in eps_sorted if e >= STRONG_EPS]
    if not strong:
        return lines + [f"* No run at eps >= {STRONG_EPS:g} yet: the loosening at strong taps "
                        "is not measured.", ""]
    for e in strong:
        d = summary[e]
        below = summary[top]["steady"] - d["steady"]
        below_se = math.hypot(summary[top]["steady_se"], d["steady_se"])
        moving = beyond(d["halves"], d["halves_se"], HALVES_DOF)
        ends = ("ends above its initial packing" if d["gain"] > 0 else
                "ends below its initial packing: a loosening that the taps do not undo")
        lines.append(
            f"* eps = {e:g}: the steady <Phi^c> is {fmt(below, below_se, True)} below the "
            f"largest (eps = {top:g}) and {fmt(abs(d['gain']), None, True)} "
            f"{'above' if d['gain'] > 0 else 'below'} t = 0: the packing {ends}. "
            + (f"Its halves differ by {fmt(d['halves'], d['halves_se'], True)}: still "
               + ("compacting" if d["halves"] > 0 else "loosening")
               + " at the end, so the value after these taps bounds the steady state from "
               + ("below." if d["halves"] > 0 else "above.")
               if moving else "Its halves agree within their error: steady."))
    transient = all(summary[e]["gain"] > 0 and np.all(np.isfinite(summary[e]["back"]))
                    for e in strong)
    still = [e for e in strong if summary[e]["halves"] > 0
             and beyond(summary[e]["halves"], summary[e]["halves_se"], HALVES_DOF)]
    lines.append(
        "* Verdict: the loosening at strong taps is "
        + ("transient: the first taps leave the packing looser than the sequential deposition "
           "it starts from (the first-tap measurement above tells whether that is the model "
           "or the redeposition's threshold), the taps then compact it beyond its start, and "
           "what remains is the falling side of Fig. 4's bell, which the paper shows itself"
           + (f"; at eps = {', '.join(f'{e:g}' for e in still)} part of the fall is a slower "
              "approach to the steady state, still under way after the run's taps, as it may "
              "be in the paper's values after 4000 taps." if still else ".")
           if transient else
           "not undone by the taps at every strong eps (see above): a difference from the "
           "paper's Fig. 4, whose squares all lie above the initial packing."))
    return lines + [""]

