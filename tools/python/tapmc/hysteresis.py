# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Steady-state values along a ramp of the excitation, section III.B and Fig. 4 of Philippe &
Bideau: sqrt(eps) raised by 0.025 every 4000 taps, then lowered, then raised again; the steady
state of every level is the mean over its last 1000 taps, and the levels form the branches
'up1', 'down' and 'up2' (the paper's "irreversible" first increase and "reversible" branch).

The claims of section III.B are decided on the branch data (per level: sqrt(eps), the mean over
the last taps and its standard error) by :class:`RampBranches`:

* a ramp that went beyond (sqrt eps)* ~ 0.15 (:data:`CRITICAL_SQRT_EPS`) comes back on the
  *reversible* branch: the decreasing branch lies above the first increase
  (``down_minus_up1`` > 0), <Phi^c> falls with sqrt(eps) on it (``down_slope`` < 0), and the
  second increase retraces it (``up2_minus_down`` within noise);
* a ramp that stayed below it comes back *irreversibly*: the decreasing branch is nearly frozen
  at the value it had at the top of the ramp (``down_change`` within noise).

"Within noise" and the signs are decided at :data:`Z_DECIDE` standard errors
(:class:`BranchStatistic`)."""

import math
from dataclasses import dataclass, replace

import numpy as np
from scipy.stats import chi2 as chi2_distribution

from ._legends import place_legend
from ._validate import (as_1d, computed_repr, in_range, new_axis, positive, positive_int, require,
                        result, same_length)
from .fluctuations import SteadyState
from .stats import CALIBRATION_ALPHA

__all__ = ["Hysteresis", "LEVEL_TOLERANCE", "CRITICAL_SQRT_EPS", "Z_DECIDE", "BranchData",
           "BranchStatistic", "common_levels", "branch_difference", "branch_slope", "branch_change",
           "RampBranches", "SeedsTogether", "seeds_together"]

#: (sqrt eps)* ~ 0.15 of section III.B, between the irreversible and the reversible behaviour
CRITICAL_SQRT_EPS = 0.15
#: standard errors that decide a sign (|value| > Z_DECIDE sem) or count as noise (below)
Z_DECIDE = 2.0

#: sqrt(eps) values closer than this belong to one level (thermo prints 6 digits or more)
LEVEL_TOLERANCE = 1e-6

_DTYPE = [("branch", "U4"), ("level", int), ("sqrt_eps", float), ("mean", float),
          ("sem", float), ("std", float), ("first_tap", int), ("last_tap", int)]


class Hysteresis:
    """Per-level steady states of a ramp run (section III.B, Fig. 4).

    Parameters: ``sqrt_eps_per_tap`` and ``x_per_tap`` (one entry per tap, entry k = the tap
    k + 1 and the state after it; e.g. fix tapdilate's f_ID[2] and <Phi^c> from compute
    stereo/profile, without the initial row of step 0), ``taps_per_level`` (default 4000),
    ``last`` (taps averaged at the end of each level, default 1000).

    The run is cut into consecutive levels of ``taps_per_level`` taps (an unfinished last level
    shorter than ``last`` is left out; ``incomplete_taps`` counts those taps). Inside the
    averaging window of a level sqrt(eps) must be constant. Branches: the first level and every
    level up to the ramp's first turn (the last level before sqrt(eps) first decreases) are
    'up1', the levels after it that decrease are 'down', and the levels after the lowest point
    of the descent are 'up2' (which may go higher than 'up1' went). One loop: a ramp that turns
    down again during 'up2' raises ValueError naming the level (cut the run into loops).

    Results after ``compute()``: ``levels`` (numpy structured array with fields branch, level,
    sqrt_eps, mean, sem, std, first_tap, last_tap), ``branch(name)``, ``plot(ax)``."""

    def __init__(self, sqrt_eps_per_tap, x_per_tap, taps_per_level=4000, last=1000):
        self.sqrt_eps = as_1d("sqrt_eps_per_tap", sqrt_eps_per_tap)
        self.x = as_1d("x_per_tap", x_per_tap)
        same_length("sqrt_eps_per_tap", self.sqrt_eps, "x_per_tap", self.x)
        self.taps_per_level = positive_int("taps_per_level", taps_per_level, minimum=2)
        self.last = positive_int("last", last, minimum=2)
        if self.last > self.taps_per_level:
            raise ValueError(f"last = {last} exceeds taps_per_level = {taps_per_level}")
        if len(self.x) < self.last:
            raise ValueError(f"the run has {len(self.x)} taps, fewer than last = {last}")

    def compute(self):
        rows = []
        n = len(self.x)
        n_levels = int(np.ceil(n / self.taps_per_level))
        self._incomplete_taps = 0
        for k in range(n_levels):
            a = k * self.taps_per_level
            b = min(n, a + self.taps_per_level)
            if b - a < self.last:
                self._incomplete_taps = b - a
                break
            window = self.sqrt_eps[b - self.last:b]
            if np.ptp(window) > LEVEL_TOLERANCE:
                raise ValueError(f"level {k} (taps {a + 1}..{b}): sqrt(eps) varies from "
                                 f"{window.min():g} to {window.max():g} inside the averaging "
                                 f"window of the last {self.last} taps; check taps_per_level and that "
                                 "entry k is tap k + 1 (no step-0 row)")
            ss = SteadyState(self.x[a:b], last=self.last).compute()
            rows.append(["", k, float(np.median(window)), ss.mean, ss.sem, ss.std, a + 1, b])
        values = np.array([r[2] for r in rows])
        branch = "up1"
        for k, row in enumerate(rows):
            falls = k > 0 and values[k] < values[k - 1] - LEVEL_TOLERANCE
            rises = k > 0 and values[k] > values[k - 1] + LEVEL_TOLERANCE
            if branch == "up1" and falls:
                branch = "down"
            elif branch == "down" and rises:
                branch = "up2"
            elif branch == "up2" and falls:
                raise ValueError(
                    f"level {k} (taps {row[6]}..{row[7]}): sqrt(eps) turns down again, from "
                    f"{values[k - 1]:g} to {values[k]:g}, after the second increase; Hysteresis "
                    f"takes one loop (up, down, up): pass the taps up to {row[6] - 1}")
            row[0] = branch
        self._levels = np.array([tuple(r) for r in rows], dtype=_DTYPE)
        return self

    levels = result("_levels")
    incomplete_taps = result("_incomplete_taps")

    def __repr__(self):
        return computed_repr(self, "_levels", f"of {len(self.x)} taps, {self.taps_per_level} "
                             f"per level", lambda: f"{len(self._levels)} levels")

    def branch(self, name):
        """The levels of one branch ('up1', 'down' or 'up2')."""
        if name not in ("up1", "down", "up2"):
            raise ValueError(f"branch = {name!r} must be 'up1', 'down' or 'up2'")
        return self.levels[self.levels["branch"] == name]

    def plot(self, ax=None, ylabel=r"$\langle\Phi^c\rangle$"):
        """Steady state against sqrt(eps), one marker per branch (Fig. 4)."""
        ax = new_axis(ax)
        style = {"up1": ("o", "C0"), "down": ("v", "C1"), "up2": ("^", "C2")}
        for name, (marker, color) in style.items():
            lv = self.branch(name)
            if len(lv):
                ax.errorbar(lv["sqrt_eps"], lv["mean"], yerr=lv["sem"], marker=marker,
                            color=color, ls="-", label=name, capsize=2)
        ax.set_xlabel(r"$\varepsilon^{1/2}$")
        ax.set_ylabel(ylabel)
        place_legend(ax)
        return ax


@dataclass(frozen=True)
class BranchData:
    """One branch of a ramp: per level ``sqrt_eps``, the steady state ``mean`` (over the last
    taps of the level, and over seeds) and its standard error ``sem`` (all of one length,
    finite, sem > 0; any order)."""

    sqrt_eps: np.ndarray
    mean: np.ndarray
    sem: np.ndarray

    def __post_init__(self):
        sq = as_1d("sqrt_eps", self.sqrt_eps)
        mean = as_1d("mean", self.mean)
        sem = as_1d("sem", self.sem)
        same_length("sqrt_eps", sq, "mean", mean)
        same_length("sqrt_eps", sq, "sem", sem)
        if np.any(sem <= 0):
            bad = int(np.flatnonzero(sem <= 0)[0])
            raise ValueError(f"sem[{bad}] = {sem[bad]!r} must be > 0 (a level without an "
                             "uncertainty decides nothing)")
        for name, value in (("sqrt_eps", sq), ("mean", mean), ("sem", sem)):
            object.__setattr__(self, name, value)

    @classmethod
    def from_levels(cls, levels):
        """From levels of :meth:`Hysteresis.branch` (fields sqrt_eps, mean, sem)."""
        return cls(levels["sqrt_eps"], levels["mean"], levels["sem"])

    def __len__(self):
        return len(self.sqrt_eps)


@dataclass(frozen=True)
class BranchStatistic:
    """A statistic of branch data: ``value`` with its standard error ``sem`` over ``n`` levels.
    ``z`` = value / sem; ``positive`` / ``negative``: beyond ``Z_DECIDE`` standard errors;
    ``within_noise``: |z| < ``Z_DECIDE``."""

    value: float
    sem: float
    n: int

    @property
    def z(self):
        return self.value / self.sem if self.sem > 0 else math.copysign(math.inf, self.value)

    @property
    def positive(self):
        return self.z > Z_DECIDE

    @property
    def negative(self):
        return self.z < -Z_DECIDE

    @property
    def within_noise(self):
        return abs(self.z) < Z_DECIDE


@dataclass(frozen=True)
class SeedsTogether:
    """One statistic of several seeds taken together: ``pooled`` their mean, with the
    standard error of a mean of independent seeds (the root of the sum of their squared
    errors over the number of seeds), times sqrt(chi2 / dof) when the seeds scatter more than
    their errors say (chi2 > dof; as the package's weighted fits do); ``chi2`` (``dof`` = seeds - 1) the seeds' scatter about
    their weighted mean against their own errors, ``p`` its chance; ``consistent``: the seeds
    agree within their errors (p >= CALIBRATION_ALPHA, the project's one threshold for a
    scatter that rejects the errors)."""

    pooled: BranchStatistic
    chi2: float
    dof: int
    p: float

    @property
    def consistent(self):
        return self.p >= CALIBRATION_ALPHA

    @property
    def widened(self):
        """The factor the pooled error took from the seeds' scatter, sqrt(chi2 / dof) (1
        when they scatter within their errors)."""
        return math.sqrt(max(1.0, self.chi2 / self.dof))

    def scatter_text(self):
        chance = f"p = {self.p:.2g}" if self.p >= 1e-4 else "p < 1e-4"
        return f"chi2 = {self.chi2:.1f} for {self.dof} dof, {chance}"


def seeds_together(stats):
    """:class:`SeedsTogether` of two or more :class:`~tapmc.hysteresis.BranchStatistic` (one
    per seed, each with a positive error); ValueError otherwise."""
    stats = list(stats)
    if len(stats) < 2 or not all(s.sem > 0 for s in stats):
        raise ValueError(f"seeds_together: {len(stats)} statistics, needs 2 or more, each with "
                         "an error > 0")
    values = np.array([s.value for s in stats])
    sems = np.array([s.sem for s in stats])
    weights = 1.0 / sems ** 2
    weighted = float(np.sum(weights * values) / np.sum(weights))
    scatter = float(np.sum(weights * (values - weighted) ** 2))
    dof = len(stats) - 1
    # seeds scattered beyond their errors (chi2 > dof, not yet rejected) widen the error of
    # their mean by the square root of the reduced chi2, as tapmc.stats.weighted_line_fit
    raw = BranchStatistic(float(values.mean()), float(np.sqrt(np.sum(sems ** 2))) / len(stats),
                          sum(s.n for s in stats))
    together = SeedsTogether(raw, scatter, dof, float(chi2_distribution.sf(scatter, dof)))
    return replace(together, pooled=replace(raw, sem=raw.sem * together.widened))


def common_levels(a, b, tolerance=LEVEL_TOLERANCE):
    """Index pairs (i, j) of the levels of a and b at the same sqrt(eps)."""
    pairs = []
    for i, x in enumerate(a.sqrt_eps):
        match = np.flatnonzero(np.abs(b.sqrt_eps - x) <= tolerance)
        if len(match):
            pairs.append((i, int(match[0])))
    return pairs


def branch_difference(a, b):
    """Mean over the sqrt(eps) common to branches ``a`` and ``b`` of a - b; its standard error
    sqrt(sum(sem_a^2 + sem_b^2)) / k over the k common levels (independent levels).
    ValueError when they share no sqrt(eps)."""
    pairs = common_levels(a, b)
    if not pairs:
        raise ValueError(f"the branches share no sqrt(eps) (a: {list(a.sqrt_eps)}, b: "
                         f"{list(b.sqrt_eps)})")
    i, j = map(np.array, zip(*pairs))
    diff = a.mean[i] - b.mean[j]
    sem = math.sqrt(float(np.sum(a.sem[i] ** 2 + b.sem[j] ** 2))) / len(pairs)
    return BranchStatistic(float(diff.mean()), sem, len(pairs))


def branch_slope(branch):
    """Slope d<X>/d sqrt(eps) of a weighted straight line through the levels of ``branch``
    (weights 1/sem^2), with its standard error, scaled by sqrt(chi2/dof) when the scatter
    exceeds the error bars; two levels give the line through them. ValueError for fewer than
    two levels or a single sqrt(eps)."""
    if len(branch) < 2 or np.ptp(branch.sqrt_eps) <= LEVEL_TOLERANCE:
        raise ValueError(f"a slope needs two levels at different sqrt(eps), the branch has "
                         f"sqrt(eps) = {list(branch.sqrt_eps)}")
    w = 1.0 / branch.sem ** 2
    design = np.vstack([np.ones_like(branch.sqrt_eps), branch.sqrt_eps]).T
    cov = np.linalg.inv(design.T @ (design * w[:, None]))
    coef = cov @ (design.T @ (w * branch.mean))
    dof = len(branch) - 2
    scale = 1.0
    if dof > 0:
        chi2 = float(np.sum(w * (branch.mean - design @ coef) ** 2))
        scale = max(1.0, chi2 / dof)
    return BranchStatistic(float(coef[1]), math.sqrt(cov[1, 1] * scale), len(branch))


def branch_change(branch, start_mean, start_sem):
    """Mean over the levels of ``branch`` of (level - start): how far the branch moved from a
    starting value (e.g. the top level of the ramp); standard error
    sqrt(sum(sem^2) / k^2 + start_sem^2) (the start is common to the k differences)."""
    start_sem = positive("start_sem", start_sem)
    k = len(branch)
    sem = math.sqrt(float(np.sum(branch.sem ** 2)) / k ** 2 + start_sem ** 2)
    return BranchStatistic(float(np.mean(branch.mean) - start_mean), sem, k)


class RampBranches:
    """The statistics that decide the claims of section III.B on one ramp's branches.

    Parameters: ``up1``, ``down`` and ``up2`` (:class:`BranchData` or (sqrt_eps, mean, sem)
    triples; ``up2`` may be None when the ramp did not go up again), ``critical`` ((sqrt
    eps)*, default 0.15).

    Results after ``compute()``:

    * ``top_sqrt_eps`` (the highest sqrt(eps) of the first increase), ``went_above_critical``
      (top_sqrt_eps > critical);
    * ``down_minus_up1``: the decreasing branch minus the first increase, mean over their
      common sqrt(eps) (:func:`branch_difference`); > 0 is the hysteresis of Fig. 4;
    * ``down_slope``: the slope of the decreasing branch (:func:`branch_slope`; None with one
      level): < 0 when <Phi^c> falls with sqrt(eps) on the reversible branch;
    * ``up2_minus_down``: the second increase minus the decreasing branch (None without up2
      or without a sqrt(eps) common to both);
    * ``down_change``: the decreasing branch minus the top level of the first increase
      (:func:`branch_change`), how far the packing moved once the excitation went down;
    * verdicts at ``Z_DECIDE`` standard errors: ``reversible`` (went above and
      down_minus_up1 positive), ``falls_with_sqrt_eps`` (down_slope negative), ``retraced``
      (up2_minus_down within noise), ``frozen`` (stayed below and down_change within noise).
    """

    def __init__(self, up1, down, up2=None, critical=CRITICAL_SQRT_EPS):
        self.up1 = self._branch("up1", up1)
        self.down = self._branch("down", down)
        self.up2 = None if up2 is None else self._branch("up2", up2)
        self.critical = in_range("critical", critical, 0.0, 1.0, lo_open=True)
        self._top = None

    @staticmethod
    def _branch(name, data):
        if isinstance(data, BranchData):
            return data
        try:
            sq, mean, sem = data
        except (TypeError, ValueError):
            raise ValueError(f"{name} must be BranchData or a (sqrt_eps, mean, sem) triple, "
                             f"got {type(data).__name__}") from None
        try:
            return BranchData(sq, mean, sem)
        except ValueError as err:
            raise ValueError(f"{name}: {err}") from None

    @classmethod
    def from_hysteresis(cls, hysteresis, critical=CRITICAL_SQRT_EPS):
        """From a computed :class:`Hysteresis` (one run; the sems are its batch-means
        standard errors)."""
        up2 = hysteresis.branch("up2")
        return cls(BranchData.from_levels(hysteresis.branch("up1")),
                   BranchData.from_levels(hysteresis.branch("down")),
                   BranchData.from_levels(up2) if len(up2) else None, critical)

    def compute(self):
        top = int(np.argmax(self.up1.sqrt_eps))
        self._top = float(self.up1.sqrt_eps[top])
        self._down_minus_up1 = branch_difference(self.down, self.up1)
        varied = np.ptp(self.down.sqrt_eps) > LEVEL_TOLERANCE
        self._down_slope = branch_slope(self.down) if varied else None
        self._up2_minus_down = (branch_difference(self.up2, self.down)
                                if self.up2 is not None and common_levels(self.up2, self.down)
                                else None)
        self._down_change = branch_change(self.down, self.up1.mean[top], self.up1.sem[top])
        return self

    top_sqrt_eps = result("_top")
    down_minus_up1 = result("_down_minus_up1")
    down_change = result("_down_change")

    @property
    def went_above_critical(self):
        return self.top_sqrt_eps > self.critical

    @property
    def down_slope(self):
        require(self, "_top")
        return self._down_slope

    @property
    def up2_minus_down(self):
        require(self, "_top")
        return self._up2_minus_down

    @property
    def reversible(self):
        return self.went_above_critical and self.down_minus_up1.positive

    @property
    def falls_with_sqrt_eps(self):
        return self.down_slope is not None and self.down_slope.negative

    @property
    def retraced(self):
        return self.up2_minus_down is not None and self.up2_minus_down.within_noise

    @property
    def frozen(self):
        return not self.went_above_critical and self.down_change.within_noise

    def plot(self, ax=None, ylabel=r"$\langle\Phi^c\rangle$", label="", markers=("o", "^", "v")):
        """The branches against sqrt(eps) (open symbols) and (sqrt eps)* (dotted line)."""
        ax = new_axis(ax)
        for branch, name, marker in zip((self.up1, self.down, self.up2),
                                        ("up1", "down", "up2"), markers):
            if branch is not None:
                ax.errorbar(branch.sqrt_eps, branch.mean, yerr=branch.sem, marker=marker,
                            mfc="none", ls="-", capsize=2, label=f"{label}{name}")
        ax.axvline(self.critical, color="0.5", ls=":", lw=1)
        ax.set_xlabel(r"$\varepsilon^{1/2}$")
        ax.set_ylabel(ylabel)
        place_legend(ax)
        return ax
