# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Fig. 4 of Philippe & Bideau: steady-state <Phi^c> against sqrt(eps) and the hysteresis loop
(section III.B).

Solid black squares: the steady state of independent constant-eps runs from fresh packings
(mean of <Phi^c> over the last quarter of the taps of each seed, paper: the last 1000 of
4000), mean and standard error over seeds; the paper finds a bell with its maximum for
sqrt(eps) between 0.1 and 0.2. Open symbols: the ramp pair of section III.B, each one tapping
sequence with sqrt(eps) going up by ``dsqrt`` every P taps, down again and up again, each
level's steady state from ``tapmc.hysteresis.Hysteresis``, averaged over seeds:

* the ramp that goes beyond (sqrt eps)* ~ 0.15 (runs ``ramp_<bc>_s<seed>``, up to
  ``Scale.ramp_top``): circles (increase), up-triangles (decrease), down-triangles (increase
  again), the reversible branch;
* the ramp that stays below it (runs ``ramplow_<bc>_s<seed>``, up to
  ``Scale.ramp_below_top``): diamonds, left- and right-triangles, the irreversible branch;
* where the campaign has it, the ramp that turns at the first level beyond it (runs
  ``rampnear_<bc>_s<seed>``, ``Scale.ramp_near_levels``; the full plan's tier 4, not among
  this module's own runs): pentagons, hexagons, stars. With the ramp below it, it locates
  (sqrt eps)* within one step.

The dotted vertical line is (sqrt eps)* = 0.15.

CSV panels: ``a`` (series ``steady`` with x = sqrt(eps), sem over seeds or, for an eps with
one seed, that run's batch-means error; ``up1``, ``down``, ``up2`` of the
ramp beyond (sqrt eps)*; ``low:up1``, ``low:down``, ``low:up2`` of the ramp below it, ``near:...``
of the ramp just beyond it; sem over seeds), ``params``:

* ``sqrt_eps_max``: the bell's maximum, the vertex of a weighted parabola through the highest
  steady-state square and up to two neighbours on each side (:func:`bell_maximum`, what the
  claim ``bell-maximum`` is judged on), sem its error, n the parabola's points; the highest
  square's sqrt(eps) with no sem when the parabola is not tested (three points, no error
  bars, not concave); ``phi_c_max`` the highest square's value (x = its sqrt(eps));
* ``critical_sqrt_eps``: (sqrt eps)* = 0.15 (x = 0);
* per ramp, ``ramp:`` (beyond), ``low:`` (below) and ``near:`` (just beyond), the statistics of
  ``tapmc.hysteresis.RampBranches`` on the branches averaged over seeds (per level: the mean
  over seeds; its error the larger of the sem over seeds and the one the levels' batch-means
  standard errors give the mean, which alone serves with one seed),
  with x = the ramp's highest sqrt(eps), sem their standard error and n the seeds:
  ``<ramp>:top_sqrt_eps`` (mean = the highest sqrt(eps)); ``<ramp>:down_minus_up1`` (decrease
  minus first increase over their common sqrt(eps): > 0 on the reversible branch);
  ``<ramp>:down_slope`` (d<Phi^c>/d sqrt(eps) on the decrease: < 0 on the reversible branch;
  absent with a single decreasing level); ``<ramp>:up2_minus_down`` (second increase minus
  decrease: within noise when it retraces it); ``<ramp>:down_change`` (decrease minus the top
  level: within noise when the branch is frozen, the irreversible case);
* with two seeds or more, ``<ramp>:<name>:seeds`` for the three differences of levels (one row
  per seed, n = 1: that seed's value and the error its levels' batch-means errors give it),
  so that the error of their mean can be judged against the campaign's groups of
  realizations rather than by the spread of two or three seeds alone;
* with two seeds or more of the ramp beyond (sqrt eps)*, ``ramp:up1_at_steady:seeds``: each
  seed's mean of its first increase at the sqrt(eps) it shares with the steady squares, with
  the error its levels' batch-means errors give it (one row per seed, n = 1), for the claim
  that the first increase is nearly the steady curve: the squares are common to every seed.
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass, replace

import numpy as np

from tapmc.hysteresis import CRITICAL_SQRT_EPS, BranchData, Hysteresis, RampBranches
from tapmc.stats import weighted_polyfit

from . import _plotting as P
from . import _runs, _steady_state
from ._results import CsvRows, FigureResult, Series, Value
from ._steady_state import BC, steady_last

NAME = "fig4"
#: (marker, label) of each branch of the ramp beyond (sqrt eps)* and of the ramp below it.
BRANCH_STYLE = _runs.RAMP_BRANCH_STYLE
LOW_BRANCH_STYLE = {"up1": ("D", "increase"), "down": ("<", "decrease"),
                    "up2": (">", "increase again")}
NEAR_BRANCH_STYLE = {"up1": ("p", "increase"), "down": ("h", "decrease"),
                     "up2": ("*", "increase again")}
#: the ramps of the pair: (CSV tag, run name prefix, branch style, legend words).
RAMPS = (("ramp", "ramp_", BRANCH_STYLE, "ramp beyond 0.15"),
         ("low", _runs.RAMP_BELOW_PREFIX, LOW_BRANCH_STYLE, "ramp below 0.15"),
         ("near", _runs.RAMP_NEAR_PREFIX, NEAR_BRANCH_STYLE, "ramp just beyond 0.15"))
BRANCHES = _runs.RAMP_BRANCHES
#: the ramp statistics that are means of level differences, so that the mean over seeds of
#: each seed's value is the statistic of the levels averaged over seeds: each seed's value
#: and its batch-means error are written too (``<ramp>:<name>:seeds``)
SEED_STATISTICS = ("down_minus_up1", "up2_minus_down", "down_change")


def runs(scale, seeds):
    """The constant-eps P.B.C. runs of ``scale.steady_eps`` (shared with Fig. 3:
    ``_steady_state.runs``) and, per seed, the ramp beyond (sqrt eps)* and the one below it."""
    seeds = _runs.seed_list(seeds)
    return (_steady_state.runs(scale, seeds)
            + [_runs.ramp_run(scale, BC, s) for s in seeds]
            + [_runs.ramp_below_run(scale, BC, s) for s in seeds])


def steady_states(campaign, column="phi_c", bc=BC):
    """(sqrt_eps, mean, sem, n) of the steady state of ``column`` over seeds, per eps; an eps
    with one seed (the paper's protocol: one run per point) gets that run's batch-means
    standard error (``SteadyState.sem``), n = 1."""
    groups = _runs.constant_eps_groups(campaign, bc)
    eps_list, means, sems, ns = [], [], [], []
    for eps, specs in groups.items():
        series = [_runs.taps_table(campaign, spec)[column][1:] for spec in specs]
        m, s, n = P.window_stats(series, steady_last(min(len(x) for x in series)))
        eps_list.append(eps)
        means.append(m[0])
        sems.append(s[0])
        ns.append(n[0])
    return np.sqrt(eps_list), np.array(means), np.array(sems), np.array(ns)


def _level_records(levels):
    """Hysteresis levels as a list of dicts (branch, sqrt_eps, mean, sem)."""
    if isinstance(levels, np.ndarray) and levels.dtype.names:
        return [{k: levels[k][i] for k in levels.dtype.names} for i in range(len(levels))]
    return [dict(level) for level in levels]


def _ramp_levels_per_run(campaign, column, bc, prefix):
    """[dict branch -> sqrt_eps -> (mean, sem)], one per ramp run named ``prefix...``."""
    out = []
    for spec in _runs.select(campaign, prefix, bc=bc):
        tab = _runs.taps_table(campaign, spec)
        per_level = int(spec.variables["P"])
        hyst = Hysteresis(_runs.ramp_sqrt_eps(tab)[1:], tab[column][1:],
                          taps_per_level=per_level, last=steady_last(per_level)).compute()
        run = defaultdict(dict)
        for rec in _level_records(hyst.levels):
            run[str(rec["branch"])][round(float(rec["sqrt_eps"]), 9)] = (float(rec["mean"]),
                                                                         float(rec["sem"]))
        out.append(run)
    return out


def _ramp_levels(campaign, column, bc, prefix):
    """dict branch -> sqrt_eps -> [(mean, sem) per seed] of the ramps named ``prefix...``."""
    collected = defaultdict(lambda: defaultdict(list))
    for run in _ramp_levels_per_run(campaign, column, bc, prefix):
        for branch, by_sq in run.items():
            for key, level in by_sq.items():
                collected[branch][key].append(level)
    return collected


def _one_run_branches(run):
    """RampBranches computed from one ramp run's levels (their batch-means errors); None
    when it has no decreasing level yet or a level without a positive error."""
    if not run.get("up1") or not run.get("down"):
        return None
    try:
        data = {b: BranchData(sorted(by_sq), [by_sq[k][0] for k in sorted(by_sq)],
                              [by_sq[k][1] for k in sorted(by_sq)])
                for b, by_sq in run.items()}
    except ValueError:
        return None
    return RampBranches(data["up1"], data["down"], data.get("up2")).compute()


def _complete_runs(runs):
    """The runs (levels of :func:`_ramp_levels_per_run`) whose branches hold the same levels
    as the fullest run: a ramp still running is left out of the per-seed statistics."""
    shapes = [{b: sorted(v) for b, v in run.items()} for run in runs]
    full = max(shapes, key=lambda s: sum(len(v) for v in s.values()), default=None)
    return [run for run, shape in zip(runs, shapes) if shape == full]


def per_seed_ramp_branches(campaign, column="phi_c", bc=BC, prefix="ramp_"):
    """RampBranches of each ramp run named ``prefix...`` from its own levels and their
    batch-means errors, for the runs whose branches are complete (the same levels as every
    other such run): the realizations that the claims pool with the campaign's groups of
    realizations (tapmc.paper.claims.ReportData.seed_mean_error)."""
    runs = _complete_runs(_ramp_levels_per_run(campaign, column, bc, prefix))
    return [stats for run in runs for stats in [_one_run_branches(run)] if stats is not None]


def per_seed_branch_mean(campaign, sqrt_eps, branch="up1", column="phi_c", bc=BC,
                         prefix="ramp_"):
    """(values, errors): per complete ramp run named ``prefix...``, the mean of its
    ``branch`` levels at the given ``sqrt_eps`` (Fig. 4's steady squares that the branch
    shares) and the error the levels' batch-means errors give it, sqrt(sum sem^2) / k.
    The squares are other runs, common to every seed: what differs between seeds is this
    mean, so the claim "the first increase is nearly the steady curve" judges its spread
    with the campaign's groups of realizations and adds the squares' own error once. Runs
    whose branch misses one of ``sqrt_eps`` are left out."""
    values, errors = [], []
    for run in _complete_runs(_ramp_levels_per_run(campaign, column, bc, prefix)):
        levels = run.get(branch, {})
        keys = np.array(sorted(levels))
        picked = [levels[keys[np.isclose(keys, x)][0]] for x in sqrt_eps
                  if np.any(np.isclose(keys, x))]
        if len(sqrt_eps) == 0 or len(picked) != len(sqrt_eps):
            continue
        values.append(float(np.mean([m for m, _ in picked])))
        errors.append(float(np.sqrt(sum(e * e for _, e in picked)) / len(picked)))
    return np.array(values), np.array(errors)


def hysteresis_branches(campaign, column="phi_c", bc=BC, prefix="ramp_"):
    """dict branch -> (sqrt_eps, mean, sem, n) over the seeds of the ramp runs named
    ``prefix...`` (``ramp_``: beyond (sqrt eps)*; ``ramplow_``: below it); sem over seeds, or
    with one seed (the campaign's tier 3) the level's batch-means sem, n = 1."""
    out = {}
    for branch, by_sq in _ramp_levels(campaign, column, bc, prefix).items():
        sq = np.array(sorted(by_sq))
        stats = [P.seed_stats([[m] for m, _ in by_sq[k]]) for k in sq]
        sem = [s[1][0] if len(by_sq[k]) > 1 else by_sq[k][0][1] for k, s in zip(sq, stats)]
        out[branch] = (sq, np.array([s[0][0] for s in stats]), np.array(sem, dtype=float),
                       np.array([s[2][0] for s in stats]))
    return out


def ramp_branches(campaign, column="phi_c", bc=BC, prefix="ramp_"):
    """(RampBranches computed, seeds) of the ramp runs named ``prefix...``: per level the mean
    over seeds, and as its error the larger of the sem over seeds and the error the levels'
    own batch-means sems give the mean (sqrt(sum sem_i^2) / n), so that a chance agreement of
    two seeds does not make the error vanish (one seed: the level's batch-means sem); None when
    the campaign has no such ramp, it has no decreasing level yet, or a level has no positive
    error (a level that did not move at all decides nothing)."""
    levels = _ramp_levels(campaign, column, bc, prefix)
    if not levels.get("up1") or not levels.get("down"):
        return None
    data, seeds = {}, []
    for branch, by_sq in levels.items():
        sq, mean, sem = [], [], []
        for key in sorted(by_sq):
            values = by_sq[key]
            m, s, n = P.seed_stats([[v] for v, _ in values])
            sq.append(key)
            mean.append(m[0])
            within = np.sqrt(sum(e * e for _, e in values)) / len(values)
            sem.append(max(s[0], within) if n[0] >= 2 else within)
            seeds.append(int(n[0]))
        try:
            data[branch] = BranchData(sq, mean, sem)
        except ValueError:
            return None
    return RampBranches(data["up1"], data["down"], data.get("up2")).compute(), min(seeds)


#: fewest squares that test a parabola about the largest one: three points always fit one
#: exactly, and its vertex then only restates which point is largest
BELL_FIT_MIN_POINTS = 4


def bell_maximum(steady):
    """The bell's maximum (section III.B: between sqrt(eps) = 0.1 and 0.2): the vertex of a
    weighted parabola through the largest steady square and up to two neighbours on each
    side, as ``(Value(0, vertex, its error, points of the parabola), "")``. When the parabola
    is not tested (fewer than :data:`BELL_FIT_MIN_POINTS` points), its points have no error
    bars or are not concave: ``(Value(0, sqrt(eps) of the largest square, NaN, points), why)``."""
    x, y, s = steady.x, steady.mean, steady.err
    if not np.any(np.isfinite(y)):
        return Value(0.0, np.nan, np.nan, 0), "no steady state"
    i = int(np.nanargmax(y))
    lo, hi = max(0, i - 2), min(len(x), i + 3)
    if hi - lo < 3:
        lo, hi = max(0, hi - 3), max(hi, 3)
    xs, ys, ss = x[lo:hi], y[lo:hi], s[lo:hi]
    largest = Value(0.0, float(x[i]), np.nan, len(xs))
    if len(xs) < BELL_FIT_MIN_POINTS:
        return largest, (f"{len(x)} steady states: a parabola through three points is not "
                         "tested by any")
    if not np.all(np.isfinite(ss)) or np.any(ss <= 0):
        return largest, "one realization: the steady states have no error bars"
    (_, b, c), cov, _ = weighted_polyfit(xs, ys, ss, 2)
    if not c < 0:
        return largest, "the points around the largest are not concave"
    vertex = -b / (2 * c)
    grad = np.array([0.0, -1 / (2 * c), b / (2 * c**2)])
    return Value(0.0, float(vertex), float(np.sqrt(grad @ cov @ grad)), len(xs)), ""


#: significant digits of a number in a figure CSV (tapmc.paper._plotting.FigureTable.write)
CSV_DIGITS = 10


def _as_written(series):
    """``series`` as its CSV rows hold it (:data:`CSV_DIGITS`): the bell's maximum is fitted
    to the squares the CSV keeps, so that a refit from the CSV (:func:`refit_table`, the
    report's calibrated result) gives the same number."""
    def rounded(values):
        return np.array([float(f"{v:.{CSV_DIGITS}g}") for v in values])

    return Series(rounded(series.x), rounded(series.mean), rounded(series.err), series.n)


def with_bell_maximum(result):
    """``result`` (a :class:`Fig4Result`) with its bell maximum fitted again from its steady
    squares (:func:`bell_maximum`): after their errors change (the report's realization
    calibration) or for a CSV written before the maximum was the parabola's vertex."""
    return replace(result, sqrt_eps_max=bell_maximum(result.steady)[0])


def refit_table(table):
    """A ``FigureTable`` of a Fig. 4 CSV (``tapmc.paper._plotting.read_table``'s ``table``) with
    its bell maximum fitted again from its own steady squares (:func:`with_bell_maximum`)."""
    return with_bell_maximum(Fig4Result.of_rows(CsvRows.of_table("fig4.csv", table))).table()


#: the statistics of ``tapmc.hysteresis.RampBranches`` a ramp's params rows hold, in order
RAMP_STATISTICS = ("down_minus_up1", "down_slope", "up2_minus_down", "down_change")


@dataclass(frozen=True)
class RampResult:
    """One ramp of the pair (CSV tag ``ramp``, ``low`` or ``near``): its branches averaged
    over seeds and the statistics of their levels."""

    tag: str
    #: branch ('up1', 'down', 'up2') -> steady state per level against sqrt(eps)
    branches: dict
    #: the highest sqrt(eps) (None: no decreasing level yet, no statistics)
    top_sqrt_eps: Value = None
    #: name (RAMP_STATISTICS) -> Value at x = the top; a statistic the ramp cannot give is absent
    statistics: dict = None
    #: name (SEED_STATISTICS) -> each seed's value and error (two seeds or more)
    seeds: dict = None
    #: each seed's first increase at the steady squares' sqrt(eps) (ramp beyond only)
    up1_at_steady_seeds: Series = None

    @property
    def series_prefix(self):
        return "" if self.tag == "ramp" else f"{self.tag}:"

    def rows(self):
        out = [("a", self.series_prefix + branch, s) for branch, s in self.branches.items()]
        if self.top_sqrt_eps is None:
            return out
        out.append(("params", f"{self.tag}:top_sqrt_eps", self.top_sqrt_eps))
        for name, value in self.statistics.items():
            out.append(("params", f"{self.tag}:{name}", value))
            if name in self.seeds:
                out.append(("params", f"{self.tag}:{name}:seeds", self.seeds[name]))
        if self.up1_at_steady_seeds is not None:
            out.append(("params", f"{self.tag}:up1_at_steady:seeds", self.up1_at_steady_seeds))
        return out

    @classmethod
    def from_rows(cls, rows, tag):
        prefix = "" if tag == "ramp" else f"{tag}:"
        branches = {b: rows.take("a", prefix + b) for b in BRANCHES if rows.has("a", prefix + b)}
        if not branches and not rows.has("params", f"{tag}:top_sqrt_eps"):
            return None
        if not rows.has("params", f"{tag}:top_sqrt_eps"):
            return cls(tag, branches)
        top = rows.take_value("params", f"{tag}:top_sqrt_eps")
        stats = {name: rows.take_value("params", f"{tag}:{name}") for name in RAMP_STATISTICS
                 if rows.has("params", f"{tag}:{name}")}
        seeds = {name: rows.take("params", f"{tag}:{name}:seeds") for name in SEED_STATISTICS
                 if rows.has("params", f"{tag}:{name}:seeds")}
        return cls(tag, branches, top, stats, seeds,
                   rows.take_optional("params", f"{tag}:up1_at_steady:seeds"))


@dataclass(frozen=True)
class Fig4Result(FigureResult):
    """The numbers of Fig. 4 (CSV schema: module text)."""

    #: steady state of the constant-eps runs against sqrt(eps)
    steady: Series
    #: the bell's maximum (:func:`bell_maximum`: the parabola's vertex, its error and points)
    #: and the highest square's value
    sqrt_eps_max: Value
    phi_c_max: Value
    #: tag -> :class:`RampResult` of the ramps the campaign has
    ramps: dict
    #: (sqrt eps)* (None in CSVs drawn before it was written)
    critical_sqrt_eps: Value = None

    def rows(self):
        out = [("a", "steady", self.steady), ("params", "sqrt_eps_max", self.sqrt_eps_max),
               ("params", "phi_c_max", self.phi_c_max)]
        if self.critical_sqrt_eps is not None:
            out.append(("params", "critical_sqrt_eps", self.critical_sqrt_eps))
        return out + [row for ramp in self.ramps.values() for row in ramp.rows()]

    @classmethod
    def from_rows(cls, rows):
        steady = rows.take("a", "steady")
        top, phi = rows.take_value("params", "sqrt_eps_max"), rows.take_value("params",
                                                                              "phi_c_max")
        critical = (rows.take_value("params", "critical_sqrt_eps")
                    if rows.has("params", "critical_sqrt_eps") else None)
        ramps = {tag: RampResult.from_rows(rows, tag) for tag, _, _, _ in RAMPS}
        return cls(steady, top, phi, {t: r for t, r in ramps.items() if r is not None},
                   critical)


def _ramp_result(campaign, tag, prefix, steady_sqrt_eps):
    """The :class:`RampResult` of the ramp runs named ``prefix...`` (module text)."""
    branches = {branch: Series.of(*columns)
                for branch, columns in hysteresis_branches(campaign, prefix=prefix).items()}
    found = ramp_branches(campaign, prefix=prefix)
    if found is None:
        return RampResult(tag, branches)
    stats, seeds = found
    top = stats.top_sqrt_eps
    per_seed = per_seed_ramp_branches(campaign, prefix=prefix) if seeds >= 2 else []
    values, seed_rows = {}, {}
    for name in RAMP_STATISTICS:
        value = getattr(stats, name)
        if value is None:
            continue
        values[name] = Value(top, value.value, value.sem, seeds)
        if name in SEED_STATISTICS and len(per_seed) >= 2:
            seed_rows[name] = Series.of([top] * len(per_seed),
                                        [getattr(r, name).value for r in per_seed],
                                        [getattr(r, name).sem for r in per_seed], 1)
    at_steady = None
    if tag == "ramp" and seeds >= 2:
        up1 = branches.get("up1")
        common = [x for x in steady_sqrt_eps if up1 is not None and np.any(np.isclose(up1.x, x))]
        found_values, errors = (per_seed_branch_mean(campaign, common, prefix=prefix)
                                if common else ([], []))
        if len(found_values) >= 2:
            at_steady = Series.of([top] * len(found_values), found_values, errors, 1)
    return RampResult(tag, branches, Value(0.0, top, np.nan, seeds), values, seed_rows,
                      at_steady)


def analyse(campaign):
    """Fig. 4 from the campaign's constant-eps P.B.C. runs and its ramps."""
    sq, mean, sem, n = steady_states(campaign)
    steady = Series.of(sq, mean, sem, n)
    ramps = {tag: _ramp_result(campaign, tag, prefix, sq) for tag, prefix, _, _ in RAMPS
             if _runs.select(campaign, prefix, bc=BC)}
    top = int(np.nanargmax(mean))
    return Fig4Result(steady, bell_maximum(_as_written(steady))[0],
                      Value(sq[top], mean[top], sem[top], len(sq)), ramps,
                      Value(0.0, CRITICAL_SQRT_EPS, np.nan, 1))


def ramp_words(ramp, words):
    """The legend's name of one ramp (:class:`RampResult`): where it turns (its highest
    sqrt(eps)) and its seeds, e.g. "ramp to 0.3 (2 seeds)"; ``words`` (where it stands to
    0.15) while it has no decreasing level."""
    top = None if ramp is None else ramp.top_sqrt_eps
    if top is None or not np.isfinite(top.value):
        return words
    seeds = f" ({top.n} seed{'s' if top.n != 1 else ''})" if top.n else ""
    return f"ramp to {top.value:.3g}{seeds}"


def plot(result, settings=None):
    """The figure of a :class:`Fig4Result` (drawing only)."""
    fig, (ax,) = P.new_figure(1, 1, height=4.0)
    steady = result.steady
    ax.errorbar(steady.x, steady.mean, yerr=np.nan_to_num(steady.err), marker="s", color="k",
                ls="none", capsize=2, label="after the run at constant eps")
    ax.axvline(CRITICAL_SQRT_EPS, color="0.5", ls=":", lw=1,
               label=r"$(\varepsilon^{1/2})^* = 0.15$")
    for tag, _, style, words in RAMPS:
        ramp = result.ramps.get(tag)
        branches = ramp.branches if ramp is not None else {}
        words = ramp_words(ramp, words)
        for branch, s in branches.items():
            marker, label = style.get(branch, ("x", branch))
            ax.errorbar(s.x, s.mean, yerr=np.nan_to_num(s.err), marker=marker, mfc="none",
                        ls="-", lw=0.6, capsize=2, label=f"{words}: {label}")
    ax.set_xlabel(r"$\varepsilon^{1/2}$")
    ax.set_ylabel(r"steady state $\langle\Phi^c\rangle$")
    P.legend(ax, fontsize=7, title="P.B.C.", title_fontsize=7)
    return P.finish_figure(fig, settings, P.plotted_seeds(result))


def draw(campaign, out_dir):
    """Fig. 4's PNG and CSV in ``out_dir``; returns their paths."""
    return analyse(campaign).save_with_png(
        plot, out_dir, NAME, P.figure_settings(campaign, figure_runs(campaign)))


def figure_runs(campaign):
    """The runs Fig. 4 draws: the constant-eps P.B.C. runs and the ramps of :data:`RAMPS`."""
    return ([s for group in _runs.constant_eps_groups(campaign, BC).values() for s in group]
            + [s for _, prefix, _, _ in RAMPS for s in _runs.select(campaign, prefix, bc=BC)])
