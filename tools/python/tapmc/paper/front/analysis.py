# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""What the front measures: for every setting, its cost (CPU s and sweeps per tap) and its bias
against the reference setting on what the paper reports: Phi_b, <Phi^c> and <Z> after 1, 10,
100 and 1000 taps and their means over the steady window. Settings are compared seed by seed:
a seed fixes the initial packing and the moves' seed, so the difference of two settings on one
seed removes most of the packing-to-packing scatter (paired differences, Student's t over the
seeds, :mod:`tapmc.stats`).

The reference is the tightest setting that runs in the budget (``REFERENCE``); it is shown to be
converged when the still tighter settings (``TIGHTER``) agree with it within their error.
:class:`Front` reads the runs (:mod:`.data`) and returns the table, the recommendations
(:class:`Recommendation`) and the reference checks (:class:`ReferenceCheck`).
"""

import math
import os
from dataclasses import dataclass, field

from ...stats import beyond, t_quantile_of_mean
from . import data
from .settings import (BOUNDED, EPS_MATCH, OBSERVABLES, PURPOSES, QUANTITY_NAMES, REFERENCE,
                       SETTINGS, STEADY_LAST, TAPS, TIGHTER, TIMES, time_window)


def _mean(values):
    return sum(values) / len(values)


def quantities(rows, taps=TAPS):
    """name -> value of one run's TapsTable: each observable around each of TIMES taps (mean
    over time_window) and its mean over the last STEADY_LAST taps."""
    out = {}
    n = len(rows)
    for key, _ in OBSERVABLES:
        column = rows.column(key)
        for t in TIMES:
            lo, hi = time_window(t, taps)
            if hi <= n:
                out[f"{key}_t{t}"] = _mean(column[lo - 1:hi])
        if n >= taps:
            out[f"{key}_steady"] = _mean(column[-STEADY_LAST:])
    # the window before the steady one: whether the packing still moves (not a QUANTITY_NAME)
    if n >= max(taps, 2 * STEADY_LAST):
        before = rows.phi_c[-2 * STEADY_LAST:-STEADY_LAST]
        out["phi_c_rise"] = out["phi_c_steady"] - _mean(before)
    return out


def mean_se(values):
    """Mean and its standard error (nan where undefined)."""
    n = len(values)
    if n == 0:
        return math.nan, math.nan
    m = sum(values) / n
    if n < 2:
        return m, math.nan
    return m, math.sqrt(sum((v - m) ** 2 for v in values) / (n - 1) / n)


@dataclass(frozen=True)
class Estimate:
    """A mean over seeds and its standard error (nan where undefined)."""
    mean: float
    se: float


@dataclass(frozen=True)
class PairedBias:
    """The mean over the paired seeds of (setting - reference) on the same seed, its standard
    error and its 95 % bound |mean| + t x se (nan below two paired seeds)."""
    mean: float
    se: float
    bound: float


@dataclass
class SettingResult:
    """One setting at one N and eps: its cost, its values and its paired biases against the
    reference (quantity names: settings.QUANTITY_NAMES), and the trend bounds of BOUNDED (how
    much its bias changes between eps and windows). ``summary_row()`` is its row of
    front_summary.csv."""
    N: int
    eps: float
    setting: str
    eta: str
    settle_keys: str
    seeds: int
    cpu_per_tap: Estimate
    sweeps_per_tap: float
    capped_taps: int
    paired_seeds: int
    rise: Estimate            # <Phi^c>: steady window minus the window before it
    values: dict              # quantity -> Estimate
    biases: dict              # quantity -> PairedBias
    trend_bounds: dict = field(default_factory=dict)   # BOUNDED quantity -> 95 % bound

    def summary_row(self):
        """The row of front_summary.csv (its columns in their order)."""
        row = {"N": self.N, "eps": self.eps, "setting": self.setting, "eta": self.eta,
               "settle_keys": self.settle_keys, "seeds": self.seeds,
               "cpu_per_tap": self.cpu_per_tap.mean, "cpu_per_tap_se": self.cpu_per_tap.se,
               "sweeps_per_tap": self.sweeps_per_tap, "capped_taps": self.capped_taps,
               "paired_seeds": self.paired_seeds, "phi_c_rise": self.rise.mean,
               "phi_c_rise_se": self.rise.se}
        for q in QUANTITY_NAMES:
            value, bias = self.values[q], self.biases[q]
            row.update({q: value.mean, q + "_se": value.se, q + "_bias": bias.mean,
                        q + "_bias_se": bias.se, q + "_bias_bound": bias.bound})
        for q in BOUNDED:
            row[q + "_trend_bound"] = self.trend_bounds[q]
        return row


@dataclass(frozen=True)
class Recommendation:
    """The cheapest setting, run at every eps of the front, that meets a purpose at one N."""
    purpose: str
    setting: str
    tolerance: float       # None: no bound (smoke test)
    criterion: str         # "bias", "trend" or None (see settings.PURPOSES)
    worst_bound: float     # the largest 95 % bound of its bias (BOUNDED, every eps)
    worst_trend: float     # the largest 95 % bound of the change of its bias
    worst_bias: float      # the largest |bias| of <Phi^c>, signed
    cpu_per_tap: float     # mean over eps


@dataclass(frozen=True)
class ReferenceCheck:
    """A tighter setting against the reference at one N and eps: the quantities whose 95 %
    interval of the paired bias excludes zero, out of those compared."""
    setting: str
    eps: float
    paired_seeds: int
    differing: list
    compared: int


class Front:
    """The front measured in ``data_dir`` (runs.csv and taps/): ``compute()`` returns self;
    ``table`` (one SettingResult per N, eps and setting), ``summary_rows()`` (the rows of
    front_summary.csv), ``recommendations(N)``, ``reference_check(N)``. FrontDataError names a damaged file."""

    def __init__(self, data_dir):
        self.data_dir = os.fspath(data_dir)
        runs_csv = os.path.join(self.data_dir, data.RUNS_CSV)
        if not os.path.isfile(runs_csv):
            raise data.FrontDataError(runs_csv, None, "no such file (run 'tapmc-paper front "
                                      "run' first)")
        self.runs = [r for r in data.read_runs(runs_csv) if r.taps == TAPS]
        if not self.runs:
            raise data.FrontDataError(runs_csv, None, f"no run of {TAPS} taps")
        self._table = None

    def _per_run(self):
        """(N, eps text, setting, seed) -> (RunRow, quantities) of every run."""
        per_run = {}
        for r in self.runs:
            path = data.taps_path(self.data_dir, r.setting, r.N, float(r.eps), r.seed)
            per_run[(r.N, r.eps, r.setting, r.seed)] = (r, quantities(data.read_taps(path, r.taps)))
        return per_run

    def compute(self):
        per_run = self._per_run()
        table = []
        paired = {}  # (N, setting) -> (quantity, eps) -> seed -> bias on that seed
        for N, eps in sorted({(k[0], float(k[1])) for k in per_run}):
            e = "%g" % eps
            ref = {k[3]: v[1] for k, v in per_run.items() if k[:3] == (N, e, REFERENCE)}
            for name in SETTINGS:
                mine = {k[3]: v for k, v in per_run.items() if k[:3] == (N, e, name)}
                if mine:
                    table.append(_setting_row(N, eps, name, mine, ref, paired))
        for row in table:
            for q in BOUNDED:
                row.trend_bounds[q] = _trend_bound(paired.get((row.N, row.setting), {}),
                                                   (q, row.eps))
        self._table = table
        return self

    def _need(self):
        if self._table is None:
            raise RuntimeError("Front: call compute() first")
        return self._table

    @property
    def table(self):
        return self._need()

    def rows(self, N=None, eps=None, setting=None):
        """The SettingResults at N, eps and setting (each None: all)."""
        return [r for r in self._need() if (N is None or r.N == N)
                and (eps is None or abs(r.eps - eps) < EPS_MATCH)
                and (setting is None or r.setting == setting)]

    def summary_rows(self):
        """The rows of front_summary.csv."""
        return [r.summary_row() for r in self._need()]

    @property
    def sizes(self):
        return sorted({r.N for r in self._need()})

    @property
    def eps_values(self):
        return sorted({r.eps for r in self._need()})

    @property
    def compared_sizes(self):
        """The N at which the reference has run: where biases (and a figure) exist."""
        return sorted({r.N for r in self._need() if r.setting == REFERENCE})

    def reference_check(self, N):
        """A ReferenceCheck for each tighter setting and eps at N with two paired seeds."""
        out = []
        for name in TIGHTER:
            for row in self.rows(N=N, setting=name):
                n = row.paired_seeds
                if n < 2:
                    continue
                compared = [q for q in QUANTITY_NAMES if row.biases[q].bound == row.biases[q].bound]
                off = [q for q in compared if beyond(row.biases[q].mean, row.biases[q].se, n - 1)]
                out.append(ReferenceCheck(name, row.eps, n, off, len(compared)))
        return out

    def recommendations(self, N):
        """purpose -> Recommendation at N (see :func:`recommend`)."""
        return recommend(self.summary_rows(), N)


def _setting_row(N, eps, name, mine, ref, paired):
    """The SettingResult of setting `name` at N and eps from its runs `mine` (seed -> (RunRow,
    quantities)) and the reference's quantities `ref` (seed -> quantities); records the
    per-seed biases of BOUNDED in `paired`."""
    seeds_ = sorted(mine)
    common = [s for s in seeds_ if s in ref]
    t95 = t_quantile_of_mean(len(common))
    values, biases = {}, {}
    for q in QUANTITY_NAMES:
        values[q] = Estimate(*mean_se([mine[s][1][q] for s in seeds_ if q in mine[s][1]]))
        by_seed = {s: mine[s][1][q] - ref[s][q] for s in common
                   if q in mine[s][1] and q in ref[s]}
        if q in BOUNDED:
            paired.setdefault((N, name), {})[(q, eps)] = by_seed
        d, se = mean_se(list(by_seed.values()))
        biases[q] = PairedBias(d, se, abs(d) + t95 * se if len(by_seed) > 1 else math.nan)
    return SettingResult(
        N=N, eps=eps, setting=name, eta=SETTINGS[name]["eta"],
        settle_keys=mine[seeds_[0]][0].settle_keys, seeds=len(seeds_),
        cpu_per_tap=Estimate(*mean_se([float(mine[s][0].cpu_per_tap) for s in seeds_])),
        sweeps_per_tap=mean_se([float(mine[s][0].sweeps_per_tap) for s in seeds_])[0],
        capped_taps=sum(mine[s][0].capped_taps for s in seeds_), paired_seeds=len(common),
        rise=Estimate(*mean_se([mine[s][1]["phi_c_rise"] for s in seeds_
                                if "phi_c_rise" in mine[s][1]])),
        values=values, biases=biases)


def _trend_bound(biases, here):
    """The 95 % bound of how a setting's bias changes between the compared quantities (<Phi^c>
    around tap 100 and steady: BOUNDED) and tap strengths: for ``here`` = (quantity, eps),
    |mean of (bias here - bias there)| + t x its standard error for every other (quantity,
    eps) there, the difference taken seed by seed (the same seed gives the same packing at every
    eps); the largest, nan without another entry of 2 common seeds. ``biases``: (quantity, eps)
    -> seed -> bias on that seed."""
    mine = biases.get(here, {})
    bounds = []
    for there, theirs in biases.items():
        if there == here:
            continue
        seeds_ = sorted(set(mine) & set(theirs))
        if len(seeds_) < 2:
            continue
        d, se = mean_se([mine[s] - theirs[s] for s in seeds_])
        bounds.append(abs(d) + t_quantile_of_mean(len(seeds_)) * se)
    return max(bounds) if bounds else math.nan


def _summary(rows):
    """Rows of front_summary.csv from SettingResults or summary rows (the rows cost.py reads)."""
    return [r.summary_row() if isinstance(r, SettingResult) else r for r in rows]


def worst_trend(name, rows):
    """The largest trend bound (BOUNDED, see _trend_bound) of setting `name` over its `rows`
    (SettingResults or summary rows; 0 for the reference; nan when one is missing)."""
    if name == REFERENCE:
        return 0.0
    bounds = [float(r.get(q + "_trend_bound", math.nan)) for r in _summary(rows) for q in BOUNDED]
    return max(bounds) if bounds and all(b == b for b in bounds) else math.nan


def worst_bias(name, rows):
    """The largest |bias| of <Phi^c> (BOUNDED) of setting `name` over its `rows`, signed."""
    biases = [float(r[q + "_bias"]) for r in _summary(rows) for q in BOUNDED]
    return max(biases, key=abs) if biases else math.nan


def worst_bound(name, rows):
    """The largest 95 % bound (BOUNDED) of setting `name` over its `rows` (0 for the reference;
    nan when a bound is missing or there are no rows)."""
    if name == REFERENCE:
        return 0.0
    bounds = [r[q + "_bias_bound"] for r in _summary(rows) for q in BOUNDED]
    return max(bounds) if bounds and all(b == b for b in bounds) else math.nan


def recommend(table, N):
    """purpose -> Recommendation at N, from the SettingResults of a Front (or the rows of
    front_summary.csv): for each purpose the cheapest setting, run at every eps of the front,
    whose 95 % bounds (BOUNDED) meet the purpose's tolerance at every eps."""
    rows_at = [r for r in _summary(table) if r["N"] == N]
    eps_all = sorted({r["eps"] for r in rows_at})
    candidates = []
    for name in SETTINGS:
        rows = [r for r in rows_at if r["setting"] == name]
        if len(rows) != len(eps_all):
            continue
        cost = sum(r["cpu_per_tap"] for r in rows) / len(rows)
        candidates.append((cost, name, worst_bound(name, rows), worst_trend(name, rows),
                           0.0 if name == REFERENCE else worst_bias(name, rows)))
    out = {}
    for purpose, tol, kind in PURPOSES:
        measure = {"bias": lambda c: c[2], "trend": lambda c: c[3]}.get(kind)
        ok = [c for c in candidates if measure is None or (measure(c) == measure(c) and measure(c) <= tol)]
        if ok:
            cost, name, worst, trend, bias = min(ok)
            out[purpose] = Recommendation(purpose, name, tol, kind, worst, trend, bias, cost)
    return out
