# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Ramps at fewer taps per level than the paper's 4000 (section III.B): the shift of each
branch's levels to 4000 taps that tapmc-paper question ramp-levels measured, and whether
a ramp claim's verdict survives that shift."""

from __future__ import annotations

import dataclasses
import itertools
import math

import numpy as np

from tapmc.hysteresis import LEVEL_TOLERANCE
from tapmc.stats import t_quantile

from .._runs import RAMP_BRANCHES
from ..fig4 import RAMPS
from .bell import campaign_separation, ramp_branch, turning_ramps, turning_top
from .common import WITHIN_RUN_DOF, value_triple
from .conventions import RAMP_REDUCTION_MIN_LEVELS
from .measure import fmt
from .register import PAPER_SCALE
from .rules import Verdict, verdict


#: the ramp statistics made of <Phi^c> of the branches, and the branches each reads: what a
#: shift of the levels (the campaign's taps per level against the paper's) can move
RAMP_REDUCTION_BRANCHES = {"ramp_down_minus_up": ("down", "up1"),
                           "ramp_up2_minus_down": ("up2", "down"),
                           "ramp_up_minus_steady": ("up1",),
                           "ramp_branch_slope": ("down",),
                           "low_ramp_frozen": ("down", "top")}


#: the ramp (Fig. 4's tag) whose levels bound a statistic's shift; "ramp" when not listed
RAMP_REDUCTION_TAGS = {"low_ramp_frozen": "low"}


#: the ramp of ramp_levels.csv's rows written before its column 'ramp' existed
RAMP_LEVELS_DEFAULT_RUN = "ramp_pbc_s1"


def ramp_tag(run):
    """Fig. 4's tag of a ramp run, from its name's prefix (tapmc.paper.fig4.RAMPS); None
    for a run of no ramp."""
    return next((tag for tag, prefix, *_ in RAMPS if run.startswith(prefix)), None)


def ramp_reduction_bounds(data, tag="ramp"):
    """branch -> (bound, levels, low, high): per branch of the ramp ``tag`` (Fig. 4's), the
    largest shift of a level's <Phi^c> from the campaign's taps per level to the paper's 4000,
    |shift| + t err, over the levels tapmc-paper question ramp-levels measured
    (ramp_levels.csv), and the signed range the shifts span, min(shift - t err) to
    max(shift + t err); only branches with RAMP_REDUCTION_MIN_LEVELS measured levels or more.
    The pseudo-branch "top" is the ramp's turning level alone (the first increase's highest
    sqrt(eps)), which a change on the way down is measured from. The shift compares two
    windows of one run, so its batch-means error takes the realizations' factor of such a
    difference (:meth:`ReportData.run_error` of 'phi_c:halves')."""
    factor = data.run_error("phi_c:halves")[0]
    found, top = {}, []
    for r in data.question("ramp_levels"):
        if int(float(r["taps_long"])) < PAPER_SCALE["ramp_taps"]:
            continue
        if ramp_tag(r.get("ramp") or RAMP_LEVELS_DEFAULT_RUN) != tag:
            continue
        shift = float(r["phi_c_long"]) - float(r["phi_c"])
        err = factor * math.hypot(float(r["phi_c_sem"]), float(r["phi_c_long_sem"]))
        branch = RAMP_BRANCHES[int(float(r["branch"]))]   # in.ramp's branch column
        reach = t_quantile(WITHIN_RUN_DOF) * err
        level = (shift - reach, shift + reach, int(float(r["level"])))
        found.setdefault(branch, []).append(level)
        if branch == "up1":
            top.append((float(r["sqrt_eps"]), level))

    def summary(levels):
        return (max(max(abs(lo), abs(hi)) for lo, hi, _ in levels),
                sorted(k for _, _, k in levels), min(lo for lo, _, _ in levels),
                max(hi for _, hi, _ in levels))

    out = {b: summary(v) for b, v in found.items() if len(v) >= RAMP_REDUCTION_MIN_LEVELS}
    fig4 = data.result("fig4")
    turn = math.nan if fig4 is None else turning_top(fig4, tag)
    at_top = [level for sq, level in top if abs(sq - turn) < LEVEL_TOLERANCE]
    if at_top:
        out["top"] = summary(at_top[:1])
    return out


def ramp_reduction_shift(claim, data, bounds):
    """(low, high): how far the paper's taps per level could move the measure of a ramp
    claim, from the branches' shifts on its ramp (``bounds``: Fig. 4's tag ->
    :func:`ramp_reduction_bounds`; the ramp of :data:`RAMP_REDUCTION_TAGS`): a difference of
    two branches a - b (:data:`RAMP_REDUCTION_BRANCHES` in that order) by low_a - high_b to
    high_a - low_b (branches that shift alike move their difference less than either), a
    branch against the constant-eps runs by its own range, the decreasing branch's weighted
    slope by +- the largest slope shifts within the bound give, bound * sum w|x - xw| /
    sum w (x - xw)^2. None when a branch it reads has no bound."""
    branches = RAMP_REDUCTION_BRANCHES.get(claim.statistic)
    bounds = bounds.get(RAMP_REDUCTION_TAGS.get(claim.statistic, "ramp"), {})
    if not branches or any(b not in bounds for b in branches):
        return None
    if claim.statistic == "ramp_branch_slope":
        curve = ramp_branch(data, claim.params.get("branch", "down"))
        if curve is None:
            return None
        x, _, err = (np.asarray(v, float) for v in curve[:3])
        w = 1.0 / err ** 2
        dx = x - np.sum(w * x) / np.sum(w)
        reach = bounds[branches[0]][0] * float(np.sum(w * np.abs(dx)) / np.sum(w * dx ** 2))
        return -reach, reach
    if len(branches) == 1:
        return bounds[branches[0]][2], bounds[branches[0]][3]
    (_, _, lo_a, hi_a), (_, _, lo_b, hi_b) = (bounds[b] for b in branches)
    return lo_a - hi_b, hi_a - lo_b


def _turning_ramps_shifted(claim, data, bounds):
    """The outcome of ``claim`` (critical_separation) that holds with every ramp's
    decrease-minus-top change (Fig. 4 params ``<tag>:down_change``) moved anywhere within the
    range its own levels give (branches "down" and "top" of :func:`ramp_reduction_bounds`),
    with the ramps' (turning sqrt(eps), (low, high)); (None, ramps) when a ramp lacks a range
    or the outcome differs between the ends (every combination is tried of each ramp's ends
    and, inside its range, the shift that brings its change to zero, where its behaviour
    turns)."""
    fig4 = data.result("fig4")
    if fig4 is None:
        return None, []
    tags = turning_ramps(fig4)
    ranges = []
    for tag in tags:
        b = bounds.get(tag, {})
        if "down" not in b or "top" not in b:
            return None, []
        ranges.append((tag, (b["down"][2] - b["top"][3], b["down"][3] - b["top"][2])))
    tops = [turning_top(fig4, tag) for tag, _ in ranges]
    changes = [value_triple((fig4.ramps[tag].statistics or {}).get("down_change"))[0]
               for tag, _ in ranges]
    candidates = [[lo, hi] + ([-change] if lo < -change < hi else [])
                  for (_, (lo, hi)), change in zip(ranges, changes)]
    outcomes = set()
    for ends in itertools.product(*candidates):
        shifts = {tag: shift for (tag, _), shift in zip(ranges, ends)}
        outcomes |= {verdict(claim, m).outcome
                     for m in campaign_separation(data, shifts)}
    return (outcomes.pop() if len(outcomes) == 1 else None), [(top, r) for top, (_, r)
                                                         in zip(tops, ranges)]


def _shift_text(shift):
    """A shift range (low, high) as the verdicts write it."""
    lo, hi = shift
    if math.isclose(lo, -hi):
        return f"at most {fmt(hi)}"
    return f"{fmt(lo)} to {fmt(hi)}"


def reduced_ramp_verdict(claim, m, found, data, bounds, per_level):
    """(the verdict ``found`` of a ramp claim measured at fewer taps per level than the
    paper's, kept and saying why when the levels' measured shifts (``bounds``: Fig. 4's tag ->
    :func:`ramp_reduction_bounds`) cannot change it, else None; what the shifts could do, for
    the undecided verdict). The critical (sqrt eps)* pattern moves each ramp's change on the
    way down within its own range (:func:`_turning_ramps_shifted`); a measure, its value
    within :func:`ramp_reduction_shift`."""
    word = found.outcome
    taps = f"at {per_level or 'fewer'} taps per level"
    if claim.statistic == "critical_separation":
        shifted, ranges = _turning_ramps_shifted(claim, data, bounds)
        if shifted != word:
            return None, ""
        moves = "; ".join(f"top {top:g} by {_shift_text(r)}" for top, r in ranges)
        return Verdict(word, f"{taps}; the paper's 4000 would move the changes on the way "
                             f"down, {moves} (ramp-levels: each ramp's decrease and turning "
                             "level), which leaves the verdict"), ""
    shift = ramp_reduction_shift(claim, data, bounds)
    if shift is None:
        return None, ""
    # the same rule, with the shift as a systematic band on the measure
    if verdict(claim, dataclasses.replace(m, systematic=shift)).outcome != word:
        return None, f"; the paper's 4000 could move it by {_shift_text(shift)}"
    tag = RAMP_REDUCTION_TAGS.get(claim.statistic, "ramp")
    levels = "; ".join(f"{b}: level{'s' if len(bounds[tag][b][1]) > 1 else ''} "
                       f"{', '.join(map(str, bounds[tag][b][1]))}"
                       for b in RAMP_REDUCTION_BRANCHES[claim.statistic])
    if tag != "ramp":
        levels = f"{tag} ramp, {levels}"
    return Verdict(word, f"{taps}; the paper's 4000 would move it by {_shift_text(shift)} "
                         f"(ramp-levels, {levels}), which leaves the verdict"), ""
