# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Statistics of the bell and the ramps (section III.B, Fig. 4; alpha's bell of Fig. 6): the
steady states' maximum and sides, the ramp's branches against each other and against the
steady states, the frozen low ramp and the critical (sqrt eps)* where the ramp's behaviour
turns."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from scipy.stats import chi2 as chi2_distribution

from tapmc.hysteresis import (CRITICAL_SQRT_EPS, LEVEL_TOLERANCE, BranchStatistic,
                              seeds_together)
from tapmc.stats import CALIBRATION_ALPHA, t_quantile, weighted_line, welch_dof

from .. import fig4, fig6
from ..paper_ramp import (LAST_TAPS as PAPER_RAMP_LAST, NOT_DOWN_YET,
                          TAPS_PER_LEVEL as PAPER_RAMP_TAPS, below_critical, beyond_critical,
                          by_eta, level_errors, runs_from_rows)

from .common import (above, below, campaign_eta, common_x, curve_of, mean_difference,
                     not_in_campaign,
                     paired_levels, protocol_label, seed_mean_of, seeds_error, steady_dof,
                     value_triple, WITHIN_RUN_DOF)
from .conventions import CRITICAL_BRACKET_HALF_WIDTH, SCATTER_CHECK_LEVELS
from .measure import Measure, fmt
from .registry import statistic


def _steady(data):
    """(x, mean, sem, n, index of the largest) of Fig. 4's steady states, None when fewer
    than three."""
    fig4 = data.result("fig4")
    if fig4 is None or len(fig4.steady) < 3:
        return None
    return (*curve_of(fig4.steady), int(np.nanargmax(fig4.steady.mean)))


@statistic("bell_maximum")
def bell_maximum(data, claim):
    """The bell's maximum as Fig. 4 fits it (tapmc.paper.fig4.bell_maximum: the vertex of a
    weighted parabola through the largest steady square and its neighbours), from Fig. 4's
    result with the realizations' calibration applied."""
    steady = _steady(data)
    if steady is None:
        return not_in_campaign("fewer than three steady states")
    x, _, _, _, i = steady
    top = data.result("fig4").sqrt_eps_max
    if not np.isfinite(top.err):
        why = fig4.bell_maximum(data.result("fig4").steady)[1]
        return [Measure(x[i], undecided=why, shown=f"largest at sqrt(eps) = {x[i]:g}")]
    return [Measure(top.value, top.err, top.n - 3,
                    shown=f"{fmt(top.value, top.err)} (parabola through {top.n} points)")]


def steady_maximum(data):
    """sqrt(eps) of the steady states' maximum (:func:`bell_maximum`: the parabola's vertex,
    or the largest point when that is undecided); None without three steady states."""
    if _steady(data) is None:
        return None
    return float(bell_maximum(data, None)[0].value)


def _side_slope(x, y, s, i, side, what):
    """Weighted straight line through the points of a bell below (``side`` "below") or above
    its largest point i, largest included."""
    pick = slice(0, i + 1) if side == "below" else slice(i, len(x))
    if len(x[pick]) < 3:
        return Measure(undecided=f"fewer than three {what} {side} the largest (at sqrt(eps) = "
                                 f"{x[i]:g})", label=f"{side} the largest")
    slope, err, dof = weighted_line(x[pick], y[pick], s[pick])
    if not np.isfinite(slope):
        return Measure(undecided=f"no error bars on the {what}", label=f"{side} the largest")
    return Measure(slope, err, dof, shown=f"slope {fmt(slope, err)}", label=f"{side} the largest",
                   sign=1 if side == "below" else -1)


@statistic("bell_side_slope")
def bell_side_slope(data, claim):
    steady = _steady(data)
    if steady is None:
        return not_in_campaign("fewer than three steady states")
    x, y, s, n, i = steady
    m = _side_slope(x, y, s, i, claim.params.get("side"), "steady states")
    m.label = ""
    return [m]


@statistic("alpha_bell")
def alpha_bell(data, claim):
    """Both sides of alpha against sqrt(eps) (Fig. 6 bottom): rising below its largest value,
    falling above it, as the steady states' bell; the weaker side is the measure (a bell needs
    both)."""
    fig6_result = data.result("fig6")
    bell = None if fig6_result is None else fig6_result.bell
    if bell is None or len(bell) < 3:
        rows = not_in_campaign("alpha of fewer than three runs of the bell")
    else:
        rows = _bell_rows(data, bell.x, bell.mean, bell.err)
    return rows + _window_reading(data)


def _bell_rows(data, x, y, s):
    """The rows of alpha's bell through the points (x, y +- s): about its own largest
    value, and above the steady states' maximum when the report has Fig. 4."""
    i = int(np.nanargmax(y))
    sides = [_side_slope(x, y, s, i, side, "alphas") for side in ("below", "above")]
    own = next((m for m in sides if m.undecided), None)
    if own is None:
        # the side that supports the bell less (its slope in units of its error, signed so
        # that the bell's direction is positive) decides
        weaker = min(sides, key=lambda m: m.sign * m.value / m.err)
        own = Measure(weaker.sign * weaker.value, weaker.err, weaker.dof,
                      shown="; ".join(f"{m.label}: {m.text()}" for m in sides))
    own.label = ""
    steady = _alpha_above_steady_maximum(data, x, y, s)
    if steady is None:
        return [own]
    own.label = "about its own largest value"
    return [own, steady]


#: the row of the gradient's bell read as "the same kind of bell as the steady states"
ALPHA_ABOVE_STEADY = "above the steady states' maximum"


def _alpha_above_steady_maximum(data, x, y, s):
    """The paper's "approximately the same kind of bell shape dependence as the other
    steady-state values" read literally: above the steady states' maximum (Fig. 4's parabola
    vertex, or its largest point when that is undecided) alpha falls as they do. A weighted
    straight line through the alphas there, its slope negated (falling is positive). None
    without Fig. 4."""
    top = steady_maximum(data)
    if top is None:
        return None
    pick = x >= top
    if pick.sum() < 3:
        return Measure(undecided=f"fewer than three alphas above the steady states' maximum "
                                 f"(sqrt(eps) = {top:.3g})", label=ALPHA_ABOVE_STEADY)
    slope, err, dof = weighted_line(x[pick], y[pick], s[pick])
    if not np.isfinite(slope):
        return Measure(undecided="no error bars on the alphas", label=ALPHA_ABOVE_STEADY)
    return Measure(-slope, err, dof, label=ALPHA_ABOVE_STEADY,
                   shown=f"slope {fmt(slope, err)} through the {int(pick.sum())} alphas at "
                         f"sqrt(eps) >= {top:.3g} (Fig. 4's maximum)")


def _window_reading(data):
    """gradient-bell's rows in the narrower window of ``tapmc-paper question alpha-window``
    (alpha_window.csv), labelled "window <lo>-<hi>R (reading)": the same sides and the same
    reading of the steady states' maximum as :func:`alpha_bell`'s rows, through alpha of
    the same runs averaged over seeds as Fig. 6 does (fig6.bell_series), with Fig. 6's
    calibration of its errors (:func:`_calibrated_alpha_errors`). [] when not measured."""
    rows = data.question("alpha_window")
    if not rows:
        return []
    lo, hi = (float(rows[0][k]) for k in ("window_lo", "window_hi"))
    label = f"window {lo:g}-{hi:g}R (reading)"
    seeds = alpha_window_seeds(rows)
    if len(seeds) < 3:
        return [Measure(undecided=f"alpha of {len(seeds)} eps in the window {lo:g}-{hi:g}R; "
                                  "the bell needs three", label=label)]
    x, y, _, _ = fig6.bell_series(seeds)
    measures = _bell_rows(data, x, y, _calibrated_alpha_errors(data, seeds))
    return [dataclasses.replace(m, label=f"{label}: {m.label}" if m.label else label)
            for m in measures]


def alpha_window_seeds(rows):
    """eps -> [(alpha, its error)] of the seeds of alpha_window.csv's ``rows`` (the
    reading window), sorted by eps and seed."""
    by_eps = {}
    for r in sorted(rows, key=lambda r: (float(r["eps"]), int(r["seed"]))):
        by_eps.setdefault(float(r["eps"]), []).append((float(r["alpha"]),
                                                       float(r["alpha_err"])))
    return by_eps


def _calibrated_alpha_errors(data, seeds):
    """The error of each eps's alpha as the report calibrates Fig. 6's bell:alpha
    (calibration.ONE_RUN_WINDOW_ROWS, quantity packing:alpha, P.B.C.): one seed's lateral
    jackknife times the realizations' factor (ReportData.run_error); several seeds' sem no
    smaller than the groups' realization error of such a mean (ReportData.realization_floor)."""
    factor = data.run_error("packing:alpha", "pbc")[0]
    errors = []
    for fits in seeds.values():
        _, err, n = fig6.bell_point(fits)
        if n == 1:
            errors.append(err * factor)
            continue
        floor = data.realization_floor("packing:alpha", [e for _, e in fits], "pbc")
        errors.append(err if floor is None or floor <= err else floor)
    return np.array(errors, dtype=float)


@statistic("alpha_ramp_hysteresis")
def alpha_ramp_hysteresis(data, claim):
    """alpha on the decreasing branch of the ramp minus on the first increase, at their
    common sqrt(eps) (Fig. 6 bottom panel, open symbols). One profile per level, whose
    straight line's own error is too small (its bins share spheres): the error is the scatter
    of the k level differences (t with k - 1 dof), which also holds any trend of the
    difference with sqrt(eps). The effect a hysteresis would have is alpha's variation along
    the first increase (<Phi^c>'s gap is as large as its own variation there); the same
    ratio of <Phi^c> (Fig. 4) is shown beside it. Then, per eta, the ramps at the paper's
    own protocol that turn beyond (sqrt eps)* (:func:`_paper_alpha_hysteresis`)."""
    fig6 = data.result("fig6")
    up, down = (None, None) if fig6 is None else (curve_of((fig6.ramp or {}).get(branch))
                                                  for branch in ("up1", "down"))
    paper = _paper_alpha_hysteresis(data)
    if up is None or down is None:
        return paper or not_in_campaign("no ramp profiles on branches 'up1' and 'down'")
    diffs = paired_levels(down, up)
    if len(diffs) < 3:
        return [Measure(undecided=f"{len(diffs)} sqrt(eps) common to the first increase and "
                                  "the decrease; the scatter needs three")] + paper
    phi_up, phi_down = ramp_branch(data, "up1"), ramp_branch(data, "down")
    phi_gap = None if phi_up is None or phi_down is None else paired_levels(phi_down, phi_up)
    return [_alpha_gap_measure(diffs, float(np.ptp(up[1])), phi_gap,
                               None if phi_up is None else phi_up[1])] + paper


def _alpha_gap_measure(diffs, variation, phi_gap=None, phi_up=None, check=None, **row):
    """gradient-no-hysteresis's row of the level differences ``diffs`` of alpha (decrease
    minus first increase): their mean, its error from their scatter (t with k - 1 dof), against
    alpha's ``variation`` along the first increase; with <Phi^c>'s differences ``phi_gap`` and
    its first increase ``phi_up``, the same ratio of <Phi^c> beside it; ``check``: the
    :class:`ScatterCheck` of that error on pairs of seeds, whose factor it takes. ``row``:
    Measure's label and meets."""
    value = float(np.mean(diffs))
    err = float(np.std(diffs, ddof=1) / math.sqrt(len(diffs)))
    err *= 1.0 if check is None else check.factor
    how = "error from their scatter" + ("" if check is None else f"; {check.text()}")
    shown = (f"{fmt(value, err)} (decrease minus first increase, mean of {len(diffs)} common "
             f"sqrt(eps); {how}): {abs(value) / variation:.0%} of alpha's "
             f"variation along the first increase ({fmt(variation)})")
    if phi_gap is not None and len(phi_gap) and np.ptp(phi_up) > 0:
        shown += (f"; <Phi^c>: {abs(float(np.mean(phi_gap))) / float(np.ptp(phi_up)):.0%} "
                  "of its own")
    return Measure(value, err, len(diffs) - 1, effect=variation, shown=shown, **row)


def _paper_alpha_hysteresis(data):
    """Per eta, gradient-no-hysteresis's row of the ramps at the paper's own protocol that
    turn beyond (sqrt eps)* (ramp_alpha.csv of tapmc-paper question ramp-alpha: alpha at the
    end of every level of 4000 taps): the level differences of every seed pooled (one profile
    per level, as the campaign's ramps), against the variation of the seeds' mean alpha along
    their first increase; <Phi^c>'s ratio from the same ramps' levels (paper_ramp.csv).
    [] without such ramps."""
    levels = ramp_alpha_levels(data.question("ramp_alpha"))
    beyond = {run: v for run, v in levels.items() if v.top > CRITICAL_SQRT_EPS}
    if not beyond:
        return []
    phi_runs = {r.run: r for r in runs_from_rows(data.question("paper_ramp"))}
    first, check = campaign_eta(data.summary), scatter_check(levels)
    out = []
    for eta in sorted({v.eta for v in beyond.values()}, key=lambda e: (e != first, -e)):
        runs = sorted(run for run, v in beyond.items() if v.eta == eta)
        label = protocol_label(PAPER_RAMP_TAPS, eta)
        diffs = np.concatenate([beyond[r].difference("down", "up1") for r in runs])
        if len(diffs) < 3:
            out.append(Measure(label=label, meets=("ramp_taps",),
                               undecided=f"{len(diffs)} level(s) of the decrease at a sqrt(eps)"
                                         " of the first increase; the scatter needs three"))
            continue
        ups = [beyond[r].branches["up1"][1] for r in runs]
        up_mean = np.mean([u[:min(map(len, ups))] for u in ups], axis=0)
        phi = [phi_runs[r] for r in runs if r in phi_runs]
        phi_gap = np.concatenate([paired_levels(p.branch("down"), p.branch("up1"))
                                  for p in phi]) if phi else None
        phi_up = np.mean([p.branch("up1")[1][:len(up_mean)] for p in phi], axis=0) \
            if phi else None
        out.append(_alpha_gap_measure(diffs, float(np.ptp(up_mean)), phi_gap, phi_up, check,
                                      label=label, meets=("ramp_taps",)))
    return out


@dataclasses.dataclass(frozen=True)
class ScatterCheck:
    """How far the paper ramps' seeds of one turning level and eta lie apart in alpha's
    decrease minus first increase against the errors from their levels' scatter: ``chi2`` of
    each group's seeds about their weighted mean (tapmc.hysteresis.seeds_together), summed
    over ``groups`` groups (``dof``: seeds - 1 each), ``p`` its chance. The levels of one run
    share the packing's slow structure; if that made the scatter's error too small, seeds
    would lie further apart than it allows. ``factor``: sqrt(chi2 / dof) when the pairs reject
    the errors at CALIBRATION_ALPHA, else 1 (a factor from a few seeds is itself noisy)."""

    chi2: float
    dof: int
    groups: int

    @property
    def p(self):
        return float(chi2_distribution.sf(self.chi2, self.dof))

    @property
    def factor(self):
        ratio = math.sqrt(self.chi2 / self.dof)
        return ratio if ratio > 1.0 and self.p < CALIBRATION_ALPHA else 1.0

    def text(self):
        kept = "kept" if self.factor == 1.0 else f"x {self.factor:.1f}"
        return (f"that error checked on {self.groups} pair(s) of seeds of the paper ramps: "
                f"chi2 = {self.chi2:.1f} over {self.dof} dof (p = {self.p:.2f}), {kept}")


def scatter_check(levels):
    """The :class:`ScatterCheck` of ``levels`` (run -> :class:`RampAlphaLevels`): every
    turning level and eta with two seeds or more that have SCATTER_CHECK_LEVELS common levels
    each; None without such a group."""
    groups = {}
    for lv in levels.values():
        d = lv.difference("down", "up1")
        if len(d) >= SCATTER_CHECK_LEVELS:
            groups.setdefault((lv.top, lv.eta), []).append(
                BranchStatistic(float(np.mean(d)), float(np.std(d, ddof=1) / math.sqrt(len(d))),
                                len(d)))
    together = [seeds_together(g) for g in groups.values() if len(g) >= 2]
    if not together:
        return None
    return ScatterCheck(float(sum(t.chi2 for t in together)), sum(t.dof for t in together),
                        len(together))


@dataclasses.dataclass(frozen=True)
class RampAlphaLevels:
    """alpha at the level ends of one ramp at the paper's protocol (ramp_alpha.csv)."""

    top: float
    eta: float
    seed: int
    #: branch ('up1', 'down', 'up2') -> (sqrt_eps, alpha) arrays, levels in order
    branches: dict

    def difference(self, a, b):
        """Branch ``a`` minus branch ``b`` at their common sqrt(eps) (empty when either is
        missing)."""
        if a not in self.branches or b not in self.branches:
            return np.array([])
        return paired_levels(self.branches[a], self.branches[b])


def ramp_alpha_levels(rows, column="alpha"):
    """run -> :class:`RampAlphaLevels` of ramp_alpha.csv's ``rows`` (dicts of text): alpha
    in Fig. 6's window, or with ``column`` 'alpha_reading' in the reading window."""
    found = {}
    for r in rows:
        found.setdefault(r["run"], (r, {}))[1].setdefault(r["branch"], []).append(
            (float(r["sqrt_eps"]), float(r[column])))
    return {run: RampAlphaLevels(float(first["top"]), float(first["eta"]), int(first["seed"]),
                                 {b: tuple(np.array(c, dtype=float) for c in zip(*v))
                                  for b, v in by.items()})
            for run, (first, by) in found.items()}


def ramp_branch(data, name):
    """Fig. 4's curve ``name`` ((x, mean, sem, n) or None): ``steady``, a branch of the ramp
    beyond (sqrt eps)* (``up1``, ``down``, ``up2``) or ``<tag>:<branch>`` of another ramp."""
    fig4 = data.result("fig4")
    if fig4 is None:
        return None
    if name == "steady":
        return curve_of(fig4.steady)
    tag, _, branch = name.rpartition(":")
    ramp = fig4.ramps.get(tag or "ramp")
    return None if ramp is None else curve_of(ramp.branches.get(branch))


def _ramp(data, tag="ramp"):
    """Fig. 4's RampResult ``tag`` (None without it)."""
    fig4 = data.result("fig4")
    return None if fig4 is None else fig4.ramps.get(tag)


def _ramp_seed_mean(data, ramp, statistic, levels=None):
    """:func:`seed_mean_of` of a ramp's statistic and its seeds' values (phi_c's groups)."""
    return seed_mean_of(data, (ramp.statistics or {}).get(statistic),
                        (ramp.seeds or {}).get(statistic), "phi_c", levels=levels)


def hysteresis_gap(data):
    """Mean of the decreasing branch minus the first increase: the effect the "nearly the
    same" claims of the ramp are measured against."""
    down, up = ramp_branch(data, "down"), ramp_branch(data, "up1")
    if down is None or up is None:
        return None
    d = mean_difference(down, up)
    return None if d is None else d[0]


def _branch_difference(data, a, b, effect=None, statistic=None):
    """Branch ``a`` minus branch ``b`` of Fig. 4's ramp beyond (sqrt eps)*, mean over their
    common sqrt(eps). With several seeds of the ramp and their own values of that difference
    (Fig. 4 params ``ramp:<statistic>:seeds``) the error of the mean is judged with the
    campaign's groups of realizations (:func:`seed_mean`)."""
    ca, cb = ramp_branch(data, a), ramp_branch(data, b)
    if ca is None or cb is None:
        return not_in_campaign(f"no ramp branches {a!r} and {b!r}")
    d = mean_difference(ca, cb)
    if d is None:
        return [Measure(undecided=f"the branches {a!r} and {b!r} share no sqrt(eps)")]
    mean, err, dof, k = d
    how = ""
    if statistic is not None and dof is not None and dof >= 1:
        ramp = _ramp(data)
        if ramp is not None and statistic in (ramp.seeds or {}):
            _, err, dof, how = _ramp_seed_mean(data, ramp, statistic, paired_levels(ca, cb))
    if not np.isfinite(err):
        return [Measure(mean, undecided="one realization: the branches have no error bars")]
    return [Measure(mean, err, dof, effect=effect,
                    shown=f"{fmt(mean, err)} (mean of {k} common sqrt(eps)"
                          + (f"; {how})" if how else ")"))]


@statistic("ramp_up_minus_steady")
def ramp_up_minus_steady(data, claim):
    """The ramp's first increase minus the steady squares, mean over their common sqrt(eps).
    With several seeds of the ramp and each seed's mean of the first increase there (Fig. 4
    params ``ramp:up1_at_steady:seeds``), the error has two independent parts: the seeds'
    mean, judged with the campaign's groups of realizations (:func:`seed_mean`'s pooling),
    and the squares' own errors (other runs, one per sqrt(eps), shared by every seed),
    combined with the Welch-Satterthwaite dof. Otherwise the curves' errors
    (:func:`_branch_difference`). Then the row of the ramps at the paper's own protocol
    (:func:`_paper_protocol_up`)."""
    effect = hysteresis_gap(data)
    return _campaign_up_minus_steady(data, effect) + _paper_protocol_up(data, effect)


def _campaign_up_minus_steady(data, effect):
    """:func:`ramp_up_minus_steady`'s row of the campaign's own ramp (Fig. 4)."""
    ramp = _ramp(data)
    up, steady = ramp_branch(data, "up1"), ramp_branch(data, "steady")
    seeds = None if ramp is None else ramp.up1_at_steady_seeds
    pairs = [] if up is None or steady is None else common_x(up, steady)
    if seeds is None or len(seeds) < 2 or not pairs or not all(
            np.isfinite(steady[2][j]) and steady_dof(int(steady[3][j]), steady[2][j]) is not None
            for _, j in pairs):
        return _branch_difference(data, "up1", "steady", effect)
    seed_err, seed_dof, how, _ = seeds_error(data, seeds.mean, seeds.err, "phi_c")
    how = how or f"{len(seeds.mean)} seeds: the spread of their own values"
    return [_up_minus_squares(seeds.mean, seed_err, seed_dof, how, steady, pairs, effect)]


def _up_minus_squares(values, seed_err, seed_dof, how, steady, pairs, effect, label="",
                      meets=(), note=""):
    """The Measure of the seeds' first increase (``values``: each seed's mean over the common
    sqrt(eps), their mean's error and dof) minus the squares at those sqrt(eps) (``pairs``:
    index pairs into ``steady``, (x, mean, sem, n)), the squares' own errors added with the
    Welch-Satterthwaite dof."""
    k = len(pairs)
    squares = np.array([steady[1][j] for _, j in pairs])
    square_parts = np.array([steady[2][j] for _, j in pairs]) ** 2 / k ** 2
    square_dofs = [steady_dof(int(steady[3][j]), steady[2][j]) for _, j in pairs]
    value = float(np.mean(values) - np.mean(squares))
    err = math.sqrt(seed_err ** 2 + float(np.sum(square_parts)))
    dof = welch_dof(np.r_[seed_err ** 2, square_parts], [seed_dof, *square_dofs])
    return Measure(value, err, dof, label=label, meets=meets, effect=effect,
                   shown=f"{fmt(value, err)} (mean of {k} common sqrt(eps); {how}; the "
                         f"squares' own errors added, {dof} dof{note})")


def _paper_protocol_up(data, effect):
    """The row of the ramps at the paper's own protocol (paper_ramp.csv: 4000 taps per level)
    at the campaign's eta, the threshold of its squares: the first increase of every seed
    that has all its levels up to the turning one, minus the squares, mean over the sqrt(eps)
    common to them. One seed's error: its levels' batch-means errors (in quadrature, over the
    number of levels) times the realizations' factor of a steady state; several seeds: their
    mean judged as the campaign's ramps are (:func:`seeds_error`). Seeds short of their
    turning level are named, not counted; ramps of one seed that turn at different levels
    are one realization here, counted once (:func:`_one_ramp_per_seed`); [] without such
    ramps or squares."""
    eta, steady = campaign_eta(data.summary), ramp_branch(data, "steady")
    runs = _one_ramp_per_seed(r for r in runs_from_rows(data.question("paper_ramp"))
                              if r.eta == eta)
    if eta is None or steady is None or not runs:
        return []
    label = protocol_label(PAPER_RAMP_TAPS, eta)
    ups = {r.run: r.branch("up1") for r in runs}
    whole = [r for r in runs
             if len(ups[r.run][0]) and abs(ups[r.run][0].max() - r.top) <= LEVEL_TOLERANCE]
    waiting = "; ".join(f"seed {r.seed} (turning at {r.top:g}) at tap {r.taps_done}, "
                        f"{len(ups[r.run][0])} of its first increase's levels done"
                        for r in runs if r not in whole)
    common = [x for x in steady[0]
              if all(np.any(np.isclose(ups[r.run][0], x)) for r in whole)] if whole else []
    if not common:
        return [Measure(label=label, meets=("ramp_taps",),
                        undecided="no ramp has finished its first increase at a sqrt(eps) of "
                                  f"the squares yet ({waiting or 'none'})")]
    pairs = common_x((np.array(common),), steady)
    values, errors = [], []
    for r in whole:
        x, mean, sem = ups[r.run]
        at = [int(np.argmax(np.isclose(x, c))) for c in common]
        values.append(float(np.mean(mean[at])))
        errors.append(float(np.sqrt(np.sum(sem[at] ** 2))) / len(at))
    seed_err, seed_dof, how = _paper_seeds_error(data, values, errors, "phi_c")
    return [_up_minus_squares(values, seed_err, seed_dof, how, steady, pairs, effect,
                              label=label, meets=("ramp_taps",),
                              note=f"; not counted yet: {waiting}" if waiting else "")]


def _one_ramp_per_seed(runs):
    """One ramp per seed, the one turning lowest: ramps of one seed start from the same
    packing with the same Monte Carlo stream, so their first increases are one realization up
    to the lower turning level (the committed ramps of seed 1 to 0.125 and to 0.2 are
    identical to tap 7457, then part by round-off), not independent seeds."""
    kept = {}
    for r in sorted(runs, key=lambda r: (r.seed, r.top, r.run)):
        kept.setdefault(r.seed, r)
    return list(kept.values())


def _paper_beyond(data, measure_of_run, quantity, what, effect=None):
    """Per eta, a row of the ramps at the paper's own protocol (paper_ramp.csv) that turn
    beyond (sqrt eps)*: ``measure_of_run(run)`` gives a seed's (value, its levels' error,
    number of levels) or None while the run lacks the levels (``what`` names them); one seed's
    error times the realizations' factor of ``quantity``, several seeds' mean by
    :func:`seeds_error`; [] without such ramps."""
    beyond = beyond_critical(runs_from_rows(data.question("paper_ramp")))
    out = []
    first = campaign_eta(data.summary)
    for eta in sorted({r.eta for r in beyond}, key=lambda e: (e != first, -e)):
        label = protocol_label(PAPER_RAMP_TAPS, eta)
        found = [(r, measure_of_run(r)) for r in beyond if r.eta == eta]
        done = [(r, m) for r, m in found if m is not None]
        waiting = "; ".join(f"seed {r.seed} (turning at {r.top:g}) at tap {r.taps_done}"
                            for r, m in found if m is None)
        if not done:
            out.append(Measure(label=label, meets=("ramp_taps",),
                               undecided=f"{what} not done yet ({waiting})"))
            continue
        values, errors = [m[0] for _, m in done], [m[1] for _, m in done]
        err, dof, how = _paper_seeds_error(data, values, errors, quantity)
        value = float(np.mean(values))
        tops = ", ".join(sorted({f"{r.top:g}" for r, _ in done}))
        out.append(Measure(value, err, dof, label=label, meets=("ramp_taps",), effect=effect,
                           shown=f"{fmt(value, err)} (turning at {tops}; {done[0][1][2]} "
                                 f"level{'s' if done[0][1][2] != 1 else ''}; {how}"
                                 + (f"; not counted yet: {waiting})" if waiting else ")")))
    return out


def _run_branch_difference(a, b):
    """A paper ramp's branch ``a`` minus its branch ``b`` at their common sqrt(eps): (mean,
    error of the mean, levels), or None when they share none."""
    def measure(run):
        (xa, ma, sa), (xb, mb, sb) = run.branch(a), run.branch(b)
        pairs = [(i, int(np.argmax(np.isclose(xb, x)))) for i, x in enumerate(xa)
                 if np.any(np.isclose(xb, x))]
        if not pairs:
            return None
        diffs = [ma[i] - mb[k] for i, k in pairs]
        err = math.sqrt(sum(sa[i] ** 2 + sb[k] ** 2 for i, k in pairs)) / len(pairs)
        return float(np.mean(diffs)), err, len(pairs)
    return measure


def _run_branch_slope(run):
    """The slope of a paper ramp's decreasing branch (weighted straight line): (slope, error,
    levels), or None before three levels."""
    x, mean, sem = run.branch("down")
    if len(x) < 3:
        return None
    slope, err, _ = weighted_line(x, mean, sem)
    return slope, err, len(x)


@statistic("ramp_down_minus_up")
def ramp_down_minus_up(data, claim):
    """The decreasing branch minus the first increase of the ramp beyond (sqrt eps)*: the
    campaign's (:func:`_branch_difference`), then per eta the ramps at the paper's protocol."""
    return _branch_difference(data, "down", "up1", statistic="down_minus_up1") + _paper_beyond(
        data, _run_branch_difference("down", "up1"), "phi_c:halves",
        "a decreasing level at a sqrt(eps) of the first increase")


@statistic("ramp_up2_minus_down")
def ramp_up2_minus_down(data, claim):
    """The second increase minus the decreasing branch of the ramp beyond (sqrt eps)*, against
    the campaign's hysteresis gap: the campaign's, then per eta the paper-protocol ramps."""
    gap = hysteresis_gap(data)
    return _branch_difference(data, "up2", "down", gap, statistic="up2_minus_down") + \
        _paper_beyond(data, _run_branch_difference("up2", "down"), "phi_c:halves",
                      "a level of the second increase at a sqrt(eps) of the decrease", gap)


def _paper_protocol_frozen(data, effect):
    """One row per eta of the ramps at the paper's own protocol (tapmc-paper paper-ramp's
    paper_ramp.csv: 4000 taps per level, turning below (sqrt eps)*): the mean over the seeds
    whose ramp came down two levels of the decreasing branch minus the turning level; the
    error of one seed is its levels' batch-means error times the realizations' factor of a
    difference of two parts of one run, of several the :func:`seeds_error` of their mean.
    Seeds not yet two levels down leave the row undecided, saying how far they got. These runs
    have the paper's taps per level, which the campaign's Fig. 4 ramps may lack (``meets``).
    Only the ramps turning below (sqrt eps)* count (a ramp beyond it is the reversible case)."""
    out = []
    rows = below_critical(runs_from_rows(data.question("paper_ramp")))
    for eta, decided, running in by_eta(rows, campaign_eta(data.summary)):
        label = protocol_label(PAPER_RAMP_TAPS, eta)
        if not decided:
            out.append(Measure(label=label, meets=("ramp_taps",),
                               undecided=f"{NOT_DOWN_YET} ({running})"))
            continue
        m, err, dof, how = _paper_down_change(data, decided)
        tops = ", ".join(sorted({f"{r.top:g}" for r in decided}))
        out.append(Measure(m, err, dof, label=label, meets=("ramp_taps",), effect=effect,
                           shown=f"{fmt(m, err)} (decrease minus turning level {tops}"
                                 + (f"; {how})" if how else ")")))
    return out


def _paper_down_change(data, decided):
    """(mean, error, dof, how) of the change on the way down of paper-protocol ramps
    (:class:`PaperRampRun` rows, each with its levels' batch-means error): one seed's error
    times the realizations' factor of a difference of two parts of one run; several seeds'
    mean by :func:`seeds_error`."""
    values = [r.down_change for r in decided]
    err, dof, how = _paper_seeds_error(data, values, [r.down_change_sem for r in decided],
                                       "phi_c:halves")
    return float(np.mean(values)), err, dof, how


def _paper_seeds_error(data, values, errors, one_run_quantity):
    """(error, dof, how) of the mean of paper-protocol seeds' ``values``, each with its levels'
    batch-means error ``errors``: several seeds judged with the campaign's groups of
    realizations (:func:`seeds_error`, phi_c), one seed its error times the realizations'
    factor of ``one_run_quantity`` (run_error: 'phi_c' for a window mean, 'phi_c:halves' for a
    difference of two parts of one run), or the ramps' own factor of a level's mean when
    larger (:func:`tapmc.paper.paper_ramp.level_errors`)."""
    if len(values) >= 2:
        err, dof, how, _ = seeds_error(data, values, errors, "phi_c")
        return err, dof, how or f"{len(values)} seeds: the spread of their own values"
    levels = level_errors(runs_from_rows(data.question("paper_ramp")),
                          data.run_error(one_run_quantity)[0])
    factor = levels.value
    return factor * errors[0], WITHIN_RUN_DOF, "one seed" + (
        f": its levels' errors x {factor:.1f}" if factor != 1.0 else "") + (
        f" (one {PAPER_RAMP_LAST}-tap mean to the next)" if levels.from_window else "")


@statistic("low_ramp_frozen")
def low_ramp_frozen(data, claim):
    """The ramp that stayed below (sqrt eps)*: its decreasing branch minus its top level
    (Fig. 4 params ``low:down_change``), against the same change on the ramp that went beyond
    it (``ramp:down_change``), the effect "nearly frozen" denies. With several seeds the error
    of their mean is judged with the campaign's groups of realizations (:func:`seed_mean`).
    Then one row per eta of the ramps at the paper's own protocol
    (:func:`_paper_protocol_frozen`), against the same effect."""
    if data.result("fig4") is None:
        return not_in_campaign("no Fig. 4 runs")
    low = _ramp(data, "low")
    if low is None or not np.isfinite(value_triple((low.statistics or {}).get("down_change"))[0]):
        return not_in_campaign("no ramp that stays below (sqrt eps)*")
    m, s, dof, how = _ramp_seed_mean(data, low, "down_change")
    beyond = _ramp(data)
    effect = value_triple(None if beyond is None
                          else (beyond.statistics or {}).get("down_change"))[0]
    effect = effect if np.isfinite(effect) else None
    return [Measure(m, s, dof, effect=effect,
                    shown=f"{fmt(m, s)} (decrease minus top level; the ramp beyond (sqrt eps)* "
                          f"changes by {fmt(effect)}" + (f"; {how})" if how else ")"))
            ] + _paper_protocol_frozen(data, effect)


def turning_ramps(fig4):
    """The tags of Fig. 4's result's ramps that turned and came down (a top sqrt(eps)),
    sorted."""
    return sorted(tag for tag, ramp in fig4.ramps.items() if ramp.top_sqrt_eps is not None)


def turning_top(fig4, tag):
    """The top sqrt(eps) of Fig. 4's ramp ``tag`` (NaN when it has none)."""
    ramp = fig4.ramps.get(tag)
    return value_triple(None if ramp is None else ramp.top_sqrt_eps)[0]


def _turning_behaviour(top, change, effect):
    """(top, behaviour, text) of a ramp turning at ``top`` whose decrease minus top level is
    ``change`` = (value, error, dof): behaviour ``compacts`` when its decreasing branch rose
    above its top level beyond t sem (the reversible case), ``frozen`` when it stayed within
    t sem of it and t sem is below ``effect`` (the change of the ramps that compact),
    ``decompacts`` when it fell below beyond t sem, None otherwise."""
    m, s, dof = change
    if not np.isfinite(m) or dof is None:
        return top, None, f"top {top:g}: no error on its decrease"
    text = f"top {top:g}: decrease minus top level {fmt(m, s)}"
    if above(m, s, dof):
        return top, "compacts", text
    if below(m, s, dof):
        return top, "decompacts", text
    if effect is not None and t_quantile(dof) * s < effect:
        return top, "frozen", text
    return top, None, text


@statistic("critical_separation")
def critical_separation(data, claim):
    """Section III.B: (sqrt eps)* ~ 0.15 separates a ramp whose decreasing branch compacts on
    the way down (the reversible branch) from one whose decreasing branch stays frozen at its
    top level (:func:`separation`): on the campaign's ramps of Fig. 4
    (:func:`campaign_separation`), then, per eta, on the ramps at the paper's own protocol
    (paper_ramp.csv; each turning level's seeds as :func:`low_ramp_frozen` takes them)."""
    rows = campaign_separation(data)
    for eta, decided, running in by_eta(runs_from_rows(data.question("paper_ramp")),
                                        campaign_eta(data.summary)):
        label = protocol_label(PAPER_RAMP_TAPS, eta)
        tops = sorted({r.top for r in decided})
        ramps = [(top, _paper_down_change(data, [r for r in decided if r.top == top])[:3])
                 for top in tops]
        found = separation(ramps, CRITICAL_SQRT_EPS) if ramps else [
            Measure(undecided=f"{NOT_DOWN_YET} ({running})")]
        note = f"; not counted yet: {running}" if ramps and running else ""
        rows += [dataclasses.replace(m, label=label, meets=("ramp_taps",),
                                     shown=(m.shown or "") + note) for m in found]
    return rows


def campaign_separation(data, shifts=None):
    """:func:`separation` on every ramp of Fig. 4 (params ``<tag>:top_sqrt_eps`` and
    ``<tag>:down_change``; the error of a mean of several seeds: :func:`seed_mean`).
    ``shifts``: Fig. 4's tag -> a shift of that ramp's change on the way down (a systematic
    band: :mod:`.reduced_ramps`)."""
    fig4 = data.result("fig4")
    tags = [] if fig4 is None else turning_ramps(fig4)
    if not tags:
        return not_in_campaign("no ramp with a decreasing branch")
    critical = value_triple(fig4.critical_sqrt_eps)[0]
    critical = critical if np.isfinite(critical) else CRITICAL_SQRT_EPS
    changes = [_ramp_seed_mean(data, fig4.ramps[t], "down_change")[:3] for t in tags]
    if shifts:
        changes = [(m + shifts[t], s, dof) for t, (m, s, dof) in zip(tags, changes)]
    return separation([(turning_top(fig4, t), c) for t, c in zip(tags, changes)], critical)


def separation(ramps, critical):
    """The measures of the separation at ``critical`` from ramps (top, (change on the way down,
    error, dof)): 1 when each ramp turning above ``critical`` compacts, each turning below is
    frozen (within t sem, below the change of the ramps that compact) and the highest frozen
    and lowest compacting turning points lie within :data:`CRITICAL_BRACKET_HALF_WIDTH` of
    it; 0 when a ramp turning above does not compact on the way down or one turning below
    moves beyond t sem; undecided otherwise (a side without a ramp, a behaviour within the
    errors, or a bracket too wide to locate ``critical``)."""
    # the frozen side's bar: the smallest change the compacting ramps surely have
    compacting = [m - t_quantile(dof) * s for _, (m, s, dof) in ramps
                  if np.isfinite(m) and dof is not None]
    effect = max(compacting) if compacting and max(compacting) > 0 else None
    ramps = sorted((_turning_behaviour(top, c, effect) for top, c in ramps), key=lambda r: r[0])
    words = {"compacts": "compacts on the way down", "frozen": "frozen",
             "decompacts": "decompacts on the way down", None: "within the errors"}
    shown = "; ".join(f"{text} ({words[behaviour]})" for _, behaviour, text in ramps)
    contradicted = [f"top {top:g} " + ("does not compact on the way down" if top > critical
                                       else "moves on the way down")
                    for top, behaviour, _ in ramps
                    if (top > critical and behaviour in ("frozen", "decompacts"))
                    or (top <= critical and behaviour in ("compacts", "decompacts"))]
    if contradicted:
        return [Measure(0.0, shown=shown + "; contradicted: " + ", ".join(contradicted))]
    if any(behaviour is None for _, behaviour, _ in ramps):
        return [Measure(shown=shown, undecided="a ramp's decrease is within the errors of "
                                                "both behaviours")]
    frozen = [top for top, behaviour, _ in ramps if behaviour == "frozen"]
    compacts = [top for top, behaviour, _ in ramps if behaviour == "compacts"]
    if not frozen or not compacts:
        side = "below" if not frozen else "above"
        return [Measure(shown=shown, undecided=f"no ramp turning {side} {critical:g}: the "
                                               "separation needs one on each side")]
    lo, hi = max(frozen), min(compacts)
    shown += f"; (sqrt eps)* in ({lo:g}, {hi:g}]"
    reach = CRITICAL_BRACKET_HALF_WIDTH + LEVEL_TOLERANCE    # levels on a grid of 0.025
    if critical - lo > reach or hi - critical > reach:
        return [Measure(shown=shown, undecided=(
            f"the turning points bracket (sqrt eps)* in ({lo:g}, {hi:g}], wider than "
            f"{critical:g} +- {CRITICAL_BRACKET_HALF_WIDTH:g}: a ramp turning in "
            f"({critical:g}, {critical + CRITICAL_BRACKET_HALF_WIDTH:g}] would locate it"))]
    return [Measure(1.0, shown=shown)]


@statistic("ramp_branch_slope")
def ramp_branch_slope(data, claim):
    """The slope of a branch of the ramp beyond (sqrt eps)*: the campaign's, then (for the
    decreasing branch) per eta the paper-protocol ramps."""
    name = claim.params.get("branch", "down")
    paper = (_paper_beyond(data, _run_branch_slope, "phi_c", "three decreasing levels")
             if name == "down" else [])
    branch = ramp_branch(data, name)
    if branch is None:
        return not_in_campaign("no ramp") + paper
    slope, err, dof = weighted_line(*branch[:3])
    if not np.isfinite(slope):
        return [Measure(undecided="fewer than three levels with error bars")] + paper
    return [Measure(slope, err, dof, shown=f"slope {fmt(slope, err)}")] + paper
