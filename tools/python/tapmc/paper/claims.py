# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The claims register (``claims.toml``) and the statistics and rules that decide each claim.

The register lists every claim of Philippe & Bideau (section, figure, meaning, the statistic
that tests it, the rule, where its tolerance comes from, the scale it needs and the runs that
decide it). A statistic reads the figure CSVs of a campaign (:class:`ReportData`) and returns
one or more :class:`Measure` (a value, its standard error and the degrees of freedom of that
error); a rule turns a measure into a verdict:

* ``value``: agrees when |value - target| <= t * err + rounding, disagrees otherwise;
* ``range``: agrees when [value - t err, value + t err] meets [lo, hi], disagrees otherwise;
* ``sign``: agrees when sign * value > t * err, disagrees when sign * value < -t * err,
  undecided in between;
* ``zero``: disagrees when |value| > t * err; agrees (consistent with zero) when
  |value| <= t * err and t * err is smaller than the measure's ``effect``, the size of the
  effect the claim denies (e.g. the change Percus-Yevick predicts between the two packing
  fractions); undecided when the data are too uncertain to tell zero from that effect;
* ``near``: for the paper's "nearly" / "approximately the same": agrees when
  |value| + t * err is within NEAR_FRACTION (a tenth) of the measure's ``effect`` (e.g. the
  hysteresis gap the two branches are compared against), disagrees when |value| - t * err
  exceeds it, undecided in between (a difference can be real and still small);
* ``fit``: agrees when the chi-square of the fit has a p-value of at least 1 %;
* ``pattern``: a claim about several measures at once (e.g. "not unique at small eps, unique
  at larger eps"), each decided by its own uncertainty (the fits' intervals, t sem); the
  statistic gives 1 when the pattern is the paper's, 0 when a measure contradicts it beyond
  its uncertainty, and says why when it cannot decide;
* ``check``: a consistency check of the tools (holds / fails), never counted;
* ``none``: no statistic yet: undecided, with the runs that would decide it.

``t`` is the two-sided 95 % quantile of Student's t distribution with the measure's degrees
of freedom (seeds - 1 for a mean over seeds): sound for the few realizations a campaign has.
A measure without an uncertainty (one realization) is undecided, never agreed by default.
"""

from __future__ import annotations

import csv
import dataclasses
import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy import stats

from tapmc.fluctuations import DEFAULT_BATCHES, ErrorCalibration
from tapmc.stats import (CONFIDENCE, bonferroni_t_quantile, mean_dof as _dof, t_quantile,
                         weighted_line as _weighted_line,
                         weighted_polyfit as _weighted_polyfit, welch_dof)
from tapmc.hysteresis import CRITICAL_SQRT_EPS, LEVEL_TOLERANCE

from . import _plotting as P
from ._runs import RAMP_BRANCHES

#: The register, next to this module.
REGISTER = Path(__file__).with_name("claims.toml")
#: p-value below which a fit's chi-square rejects the law (rule ``fit``).
FIT_P_VALUE = 0.01
#: Rounding of the pore dumps' coordinates, allowed below xi_T by the ``check`` rule.
XI_CHECK_ROUNDING = 1e-3
#: The paper's scale (section II): N, box side in R, taps per run and per ramp level, eta.
PAPER_SCALE = {"N": 4096, "L": 32.0, "taps": 4000, "ramp_taps": 4000, "eta": 1e-7}

KINDS = ("model", "check")
RULE_NAMES = ("value", "range", "sign", "zero", "near", "fit", "pattern", "check", "none")
#: "nearly the same" (rule ``near``): within a tenth of the effect the claim is measured
#: against, the share below which the ramp-levels text also calls a shift negligible
NEAR_FRACTION = 0.1
ASPECTS = ("size", "taps", "ramp_taps", "eta")


@dataclass(frozen=True)
class Claim:
    """One [[claim]] of the register (see the comments at the top of ``claims.toml``)."""

    id: str
    section: str
    figure: str
    claim: str
    paper: str
    kind: str
    statistic: str
    rule: str
    tolerance: str
    decided_by: str
    needs: tuple = ()
    target: float | None = None
    lo: float | None = None
    hi: float | None = None
    sign: int | None = None
    rounding: float = 0.0
    params: dict = field(default_factory=dict)

    def __post_init__(self):
        where = f"claim {self.id!r}"
        if self.kind not in KINDS:
            raise ValueError(f"{where}: kind = {self.kind!r}: allowed values {KINDS}")
        if self.rule not in RULE_NAMES:
            raise ValueError(f"{where}: rule = {self.rule!r}: allowed values {RULE_NAMES}")
        bad = [a for a in self.needs if a not in ASPECTS]
        if bad:
            raise ValueError(f"{where}: needs = {bad}: allowed values {ASPECTS}")
        if self.statistic and self.statistic not in STATISTICS:
            raise ValueError(f"{where}: statistic = {self.statistic!r} is not one of "
                             f"tapmc.paper.claims.STATISTICS")
        if (self.rule == "none") != (not self.statistic):
            raise ValueError(f"{where}: rule 'none' goes with an empty statistic and only then")
        required = {"value": ("target",), "range": ("lo", "hi"), "sign": ("sign",),
                    "check": ("target",)}.get(self.rule, ())
        for name in required:
            if getattr(self, name) is None:
                raise ValueError(f"{where}: rule {self.rule!r} needs the field {name!r}")
        if self.sign not in (None, -1, 1):
            raise ValueError(f"{where}: sign = {self.sign!r}: allowed values -1, 1")
        if not self.tolerance.strip():
            raise ValueError(f"{where}: a tolerance needs its source (field 'tolerance')")


def load_register(path=REGISTER):
    """The claims of the register at ``path``, in its order (validated; ids unique)."""
    with open(path, "rb") as handle:
        raw = tomllib.load(handle)
    claims = []
    for entry in raw.get("claim", []):
        entry = dict(entry)
        entry["needs"] = tuple(entry.get("needs", ()))
        try:
            claims.append(Claim(**entry))
        except TypeError as err:
            raise ValueError(f"{path}: claim {entry.get('id')!r}: {err}") from None
    ids = [c.id for c in claims]
    duplicates = sorted({i for i in ids if ids.count(i) > 1})
    if duplicates:
        raise ValueError(f"{path}: claim ids used twice: {duplicates}")
    return claims


# ---------------------------------------------------------------- measures and data


@dataclass
class Measure:
    """What a statistic measured for one row: ``value`` with standard error ``err`` whose
    degrees of freedom are ``dof``; ``shown`` replaces the default text of the value;
    ``quantile`` replaces the t quantile (e.g. Bonferroni-corrected maxima); ``sign`` the
    claim's expected sign (a claim measured twice, e.g. both sides of a bell); ``effect`` is the
    size of the effect a ``zero`` claim denies (agreement needs an uncertainty below it);
    ``undecided`` says why the data cannot decide (the value may still be shown); ``lacks``
    the aspects of the paper's scale (:data:`ASPECTS`) this measure's own runs lack, when they
    are not the campaign's (a scan at N = 1024); ``p_value`` is a fit test's own p-value (the
    F of tapmc.laws.RealizationLawTest), which the fit rule uses instead of the chi-square's."""

    value: float = math.nan
    err: float = math.nan
    dof: float | None = None
    label: str = ""
    shown: str | None = None
    quantile: float | None = None
    effect: float | None = None
    sign: int | None = None
    undecided: str | None = None
    lacks: tuple = ()
    p_value: float | None = None

    def text(self):
        if self.shown is not None:
            return self.shown
        return fmt(self.value, self.err)


def fmt(value, err=None, pct=False, digits=3):
    """A number with its error, as the report prints it ("n/a" when not finite)."""
    if value is None or not np.isfinite(value):
        return "n/a"
    if pct:
        if err is None or not np.isfinite(err):
            return f"{100 * value:.2f} %"
        return f"{100 * value:.2f} ± {100 * err:.2f} %"
    if err is None or not np.isfinite(err):
        return f"{value:.{digits}g}"
    return f"{value:.{digits}g} ± {err:.2g}"


class FigureData:
    """One figure CSV: ``get(panel, series)`` -> (x, mean, sem, n) arrays or None."""

    def __init__(self, table):
        self.table = table

    @classmethod
    def read(cls, path):
        return cls(P.read_table(path))

    def scaled_one_run_errors(self, factor, chosen):
        """A copy whose rows with n = 1 in the series for which ``chosen(panel, series)``
        holds have their sem times ``factor``."""
        table = {}
        for (panel, series), d in self.table.items():
            d = dict(d)
            if chosen(panel, series):
                one = np.asarray(d["n"]) == 1
                d["sem"] = np.where(one, np.asarray(d["sem"], float) * factor, d["sem"])
            table[(panel, series)] = d
        return FigureData(table)

    def get(self, panel, series):
        d = self.table.get((panel, series))
        if d is None:
            return None
        return (np.asarray(d["x"], float), np.asarray(d["mean"], float),
                np.asarray(d["sem"], float), np.asarray(d["n"], float))

    def param(self, series):
        """(value, sem, n) of a one-row ``params`` series, NaNs when absent."""
        d = self.get("params", series)
        if d is None:
            return math.nan, math.nan, 0
        return float(d[1][0]), float(d[2][0]), int(d[3][0])

    def series(self, panel):
        return [s for (p, s) in self.table if p == panel]


#: stems of the CSVs of bench/paper_questions.py (in the report's ``questions`` folder) that
#: decide claims of one-run campaigns: depositions at t = 0 (initial-packing), P0 over several
#: configurations (p0-configs), the first taps from the paper's F.B.C. start (lateral-first-tap),
#: realizations of the first taps (early-taps), one run's surrogate fits (fit-surrogates), the
#: fits of whole runs over realizations (seed-fits), the ramp's levels continued (ramp-levels)
#: and nu at its level ends (ramp-pores)
QUESTION_CSVS = ("initial_packing", "p0_configs", "lateral_first_tap", "early_taps",
                 "fit_surrogates", "ramp_levels", "ramp_pores", "realization_scatter",
                 "packing_scatter", "seed_fits")


class ReportData:
    """The inputs of the report: ``figures`` (name -> :class:`FigureData`), the campaign
    ``summary`` (tapmc.paper.validation.campaign_summary) and ``front``, the rows of the
    run-time-versus-error front (tapmc.paper.front.read_summary; empty: not measured)."""

    def __init__(self, summary, figures, front=(), scans=None, questions=None):
        """``scans``: knob (``theta0``, ``dmax``) -> its scans, each the rows of one CSV of
        bench/paper_questions.py (:data:`SCANS`); ``questions``: the rows of its other CSVs
        that decide claims a campaign of one run per point cannot (:data:`QUESTION_CSVS`), by
        file stem."""
        self.summary = summary
        self.figures = figures
        self.front = list(front)
        self.scans = {knob: list((scans or {}).get(knob, ())) for knob in SCANS}
        self.questions = {stem: list(rows) for stem, rows in (questions or {}).items()}

    def question(self, stem):
        """The rows of bench/paper_questions.py's ``<stem>.csv`` ([] when not measured)."""
        return self.questions.get(stem, [])

    @classmethod
    def from_files(cls, summary, files):
        """``files``: name -> (png, csv) as the report collects them; the front from the
        package's front_summary.csv; the knob scans from ``questions/<knob>*.csv`` beside the
        figure CSVs (bench/paper_questions.py theta0 / dmax), when there."""
        from .front import read_summary

        scans, questions = {}, {}
        if files:
            folder = Path(next(iter(files.values()))[1]).parent / "questions"
            scans = {knob: [read_scan(path) for path in scan_files(folder, knob)]
                     for knob in SCANS}
            questions = {stem: read_scan(folder / f"{stem}.csv") for stem in QUESTION_CSVS
                         if (folder / f"{stem}.csv").is_file()}
        return cls(summary, {name: FigureData.read(paths[1]) for name, paths in files.items()},
                   read_summary(), scans, questions)

    def figure(self, name):
        """Figure ``name``'s data, the error of each of its one-run rows that is a window's
        own error (:data:`ONE_RUN_WINDOW_ROWS`) times the realizations' factor
        (:meth:`run_error`)."""
        fig = self.figures.get(name)
        if fig is None:
            return fig
        for quantity, bc, chosen in ONE_RUN_WINDOW_ROWS.get(name, ()):
            factor = self.run_error(quantity, bc)[0]
            if factor != 1.0:
                fig = fig.scaled_one_run_errors(factor, chosen)
        if name == "fig4":
            fig = self._calibrated_steady_squares(fig)
        return fig

    def _calibrated_steady_squares(self, fig):
        """Fig. 4's steady squares of several seeds with the error of their mean no smaller
        than the groups of realizations give it: those seeds are a group of
        realization_scatter.csv (``const_pbc_eps<eps>``, the same window of the last 1000
        taps), whose own errors times the pooled factor (:meth:`seed_mean_error`) replace
        the sem over seeds when larger. A sem of three seeds has 2 dof and can be small by
        chance; one-seed squares already carry the factor, so every square is weighed alike
        in the bell's fits. The seeds' own spread stays when it is the larger."""
        steady = fig.table.get(("a", "steady"))
        if steady is None or not np.any(np.asarray(steady["n"]) >= 2):
            return fig
        from ._runs import eps_tag

        rows = [r for r in self.question("realization_scatter") if r["column"] == "phi_c"]
        sem = np.array(steady["sem"], dtype=float)
        for i, (x, mean, n) in enumerate(zip(steady["x"], steady["mean"], steady["n"])):
            group = f"const_pbc_eps{eps_tag(float(x) ** 2)}"
            runs = [r for r in rows if r["group"] == group]
            if n < 2 or len(runs) != n:
                continue
            values = np.array([float(r["mean"]) for r in runs])
            if not math.isclose(float(np.mean(values)), float(mean), abs_tol=1e-8):
                continue    # not the same window or seeds: leave the square's own error
            found = self.seed_mean_error("phi_c", values, [float(r["sem"]) for r in runs],
                                         "pbc", groups=(group,))
            if found is not None and not found[0] <= sem[i]:
                sem[i] = found[0]
        if np.array_equal(sem, np.asarray(steady["sem"], dtype=float), equal_nan=True):
            return fig
        table = dict(fig.table)
        table[("a", "steady")] = {**steady, "sem": sem}
        return FigureData(table)

    def _realization_factors(self, bc="pbc"):
        """realization_factors of the campaign's groups of realizations (:meth:`scatter_rows`)
        for runs of ``bc``, computed once."""
        cache = self.__dict__.setdefault("_factors", {})
        if bc not in cache:
            cache[bc] = realization_factors(self.scatter_rows(), bc)
        return cache[bc]

    def scatter_rows(self):
        """The rows of realization_scatter.csv (time averages) and packing_scatter.csv
        (quantities of one packing), one table of groups of realizations."""
        return self.question("realization_scatter") + self.question("packing_scatter")

    def run_error_note(self):
        """The sentence that says which one-run errors were scaled to realizations and by
        how much ("" when realization_scatter.csv rejects no one-run error)."""
        pbc, fbc = self._realization_factors("pbc"), self._realization_factors("fbc")
        if not pbc and not fbc:
            return ""
        parts = []
        for q, label in RUN_ERROR_LABELS.items():
            kp, kf = (f.get(q, (1.0, None))[0] for f in (pbc, fbc))
            if q in pbc or q in fbc:
                parts.append(f"{label} x {kp:.1f}" if kp == kf else
                             f"{label} x {kp:.1f} (P.B.C.), x {kf:.1f} (F.B.C.)")
        rows = self.scatter_rows()
        measured = {group_bc(r["group"]) for r in rows}
        if measured == {"pbc"}:
            where = ("measured on the P.B.C. groups (F.B.C. runs, which have no group, take "
                     "the same)")
        elif any(p < CALIBRATION_ALPHA for p in realization_sharing(rows).values()):
            where = ("pooled over the groups of both boundary conditions where they share "
                     "one factor, and each boundary condition's own where they do not")
        else:
            where = ("pooled over the groups of both boundary conditions, which share one "
                     "factor")
        return ("The campaign's groups of runs that differ only in their seed show that "
                "realizations spread beyond these errors (``realization-scatter`` below): the "
                "time averages of one run that decide a row (Fig. 2's windows and halves, "
                "Fig. 4's steady states and ramp levels, Fig. 8's zones, Fig. 9's steady "
                "state, Fig. 3's sigma_<Z>) carry the batch-means error times the factor "
                f"{where} (" + ", ".join(parts)
                + ("" if any(q in self._measured() for q in ZONE_QUANTITIES)
                   else "; a profile's zones the largest") + "). "
                "A mean of a few seeds (Fig. 4's differences of a ramp's levels, Fig. 8's final "
                "zones, Fig. 6's final alpha, Fig. 4's first increase against the steady "
                "squares) is judged the same way: its seeds join the "
                "groups as one more group (unless they are one of them already), and the "
                "error of the mean is their own errors times the factor so pooled, with the "
                "pooled degrees of freedom, rather than the spread of two seeds with one "
                "degree of freedom; seeds that spread unlike the groups (F test, two-sided, "
                f"below {CALIBRATION_ALPHA:g}) are judged by their own spread. A steady "
                "square of Fig. 4 with several seeds has the larger of their sem and the "
                "error so pooled.")

    def _measured(self):
        """The quantities the groups of realizations measure (:meth:`scatter_rows`),
        rejected or not."""
        return {r["column"] for r in self.scatter_rows()}

    def seed_mean_error(self, quantity, values, errors, bc="pbc", groups=()):
        """(error, dof, factor) of the mean of a few realizations ``values`` of ``quantity``
        (e.g. two seeds of a ramp), each with its own batch-means error ``errors``: their
        group joins the campaign's groups of realizations of ``quantity`` (the ones
        :func:`realization_factors` pools for ``bc``) in one tapmc.fluctuations.
        ErrorCalibration, whose factor k (at least 1) times the error the runs' own errors
        give the mean, sqrt(sum e_i^2) / n, is the error, with the pooled dof. Two seeds
        alone give their spread 1 dof (a t quantile of 12.7); the groups give the same
        spread some 17. None (judge the seeds alone) when the campaign has no such groups,
        fewer than two values are given, or their spread differs from the groups' (the F
        test of ErrorCalibration.same_factor_p below :data:`CALIBRATION_ALPHA`). When the
        seeds are already one of the groups (their name among ``groups``, e.g. Fig. 8's
        F.B.C. runs at eps = 0.02, ``const_fbc_eps0.02``) the groups' own factor and dof
        serve: the seeds do not count twice."""
        values = np.asarray(values, dtype=float)
        errors = np.asarray(errors, dtype=float)
        if (len(values) < 2 or len(errors) != len(values) or not np.all(np.isfinite(values))
                or not np.all(np.isfinite(errors)) or np.any(errors <= 0)):
            return None
        pooled = self._pooled_calibration(quantity, bc)
        if pooled is None:
            return None
        calibration = pooled
        if not any(g in pooled.groups for g in groups):
            own = ErrorCalibration({SEEDS_GROUP: (values, errors)},
                                   within_dof=pooled.within_dof).compute()
            if own.same_factor_p(pooled) < CALIBRATION_ALPHA:
                return None
            calibration = ErrorCalibration({**pooled.groups, SEEDS_GROUP: (values, errors)},
                                           within_dof=pooled.within_dof).compute()
        factor = max(1.0, calibration.factor)
        return (factor * float(np.sqrt(np.sum(errors ** 2))) / len(values), calibration.dof,
                factor)

    def _pooled_calibration(self, quantity, bc):
        """The ErrorCalibration of ``quantity`` that :func:`realization_factors` reads for
        ``bc`` (both boundary conditions' groups unless they differ), or None."""
        rows = self.scatter_rows()
        every = realization_calibrations(rows)
        if quantity not in every:
            return None
        if realization_sharing(rows).get(quantity, 1.0) < CALIBRATION_ALPHA:
            return realization_calibrations(rows, bc).get(quantity)
        return every[quantity]

    def run_error(self, quantity, bc="pbc"):
        """(factor, dof) that turn one run's batch-means error of ``quantity`` ('phi_b',
        'phi_c', 'Z'; '<name>:halves' for a difference of two parts of one run; None: the
        largest factor of the three window means, for a quantity no group measures) into the
        error of a realization of a run of boundary condition ``bc`` ('pbc', 'fbc'): the
        campaign's :func:`realization_factors` where they reject calibrated errors, else
        (1, None) (the one-run error and its own dof). A profile's zone
        (:data:`ZONE_QUANTITIES`) that realization_scatter.csv does not measure takes the
        largest factor, as None does."""
        factors = self._realization_factors(bc)
        if quantity in ZONE_QUANTITIES and quantity not in self._measured():
            quantity = None
        if quantity is None:
            means = [factors[k] for k in RUN_ERROR_QUANTITIES if k in factors]
            return max(means, default=(1.0, None))
        return factors.get(quantity, (1.0, None))


#: the quantities of realization_scatter.csv, as the page names them: a window mean, the
#: difference of its halves, Fig. 3's sigma_<Z> about X_SS and about the window's line, and
#: its spectral slope
RUN_ERROR_LABELS = {"phi_b": "Phi_b", "phi_b:halves": "Phi_b halves",
                    "phi_c": "<Phi^c>", "phi_c:halves": "<Phi^c> halves",
                    "Z": "<Z>", "Z:halves": "<Z> halves", "Z:sigma": "sigma_<Z>",
                    "Z:sigma_detrended": "sigma_<Z> about the window's line",
                    "Z:slope": "the spectral slope of <Z>",
                    "zone:lateral": "the lateral zone", "zone:central": "the central zone",
                    "zone:central_minus_lateral": "central minus lateral zone",
                    "packing:nu": "nu of a packing", "packing:alpha": "alpha of a packing"}
#: a profile's zone means (compute stereo/profile's, taps.dat ``lateral`` and ``central``) and
#: their difference per run, Fig. 8's final values
ZONE_QUANTITIES = ("zone:lateral", "zone:central", "zone:central_minus_lateral")
#: the window means whose one-run error realization_scatter.csv calibrates
RUN_ERROR_QUANTITIES = tuple(q for q in RUN_ERROR_LABELS if ":" not in q)
#: one-sided significance below which the realizations' spread rejects one run's own error
CALIBRATION_ALPHA = 0.01
#: the name under which a statistic's few seeds join the campaign's groups of realizations
#: (ReportData.seed_mean_error); no run of a campaign is named so
SEEDS_GROUP = "<the statistic's seeds>"


def _final_zone(name):
    """chosen(panel, series) of Fig. 8's final value of zone ``name``."""
    return lambda panel, series: panel == "params" and series.endswith(f":final_{name}")


#: figure -> [(quantity, bc, chosen(panel, series))]: the rows of a figure CSV whose one-run
#: error is within one realization (a window's batch means, a spectral slope's periodogram, a
#: packing's spatial jackknife), the quantity whose realization factor they take and the
#: boundary condition of the figure's runs
ONE_RUN_WINDOW_ROWS = {
    "fig3": [("Z:slope", "pbc",
              lambda panel, series: panel == "params" and series.endswith(":slope"))],
    "fig4": [("phi_c", "pbc", lambda panel, series: panel == "a" or series == "phi_c_max"
              or series.endswith((":down_change", ":down_minus_up1", ":up2_minus_down")))],
    "fig8": [(zone, "fbc", _final_zone(zone.partition(":")[2])) for zone in ZONE_QUANTITIES],
    "fig9": [("phi_c", "pbc", lambda panel, series: series == "phi_c_steady")],
    "fig6": [("packing:alpha", "fbc", lambda panel, series: series == "final:alpha"),
             ("packing:alpha", "pbc", lambda panel, series: series == "bell:alpha")],
    "fig10": [("packing:nu", "fbc",
               lambda panel, series: panel == "params" and series == "nu")],
}


def group_bc(group):
    """Boundary condition of a group of realization_scatter.csv: 'fbc' for F.B.C. runs
    (``<kind>_fbc..._eps<eps>``), 'pbc' for every other group."""
    parts = group.split("_")
    return "fbc" if len(parts) > 1 and parts[1].startswith("fbc") else "pbc"


def realization_factors(rows, bc="pbc"):
    """dict quantity -> (k, dof) from the rows of bench/paper_questions.py's
    realization_scatter.csv for runs of boundary condition ``bc``: the factor by which the
    realizations of a group of runs that differ only in their seed spread beyond their
    batch-means errors (tapmc.fluctuations.ErrorCalibration, pooled over the groups), for
    the quantities where it rejects k = 1 at :data:`CALIBRATION_ALPHA`; dof: the pooled
    realizations' dof. The groups of both boundary conditions are pooled unless their
    factors differ (:func:`realization_sharing` below CALIBRATION_ALPHA): then ``bc``'s
    groups alone. A boundary condition without groups takes the other's."""
    every = realization_calibrations(rows)
    own = realization_calibrations(rows, bc)
    sharing = realization_sharing(rows)
    out = {}
    for q, c in every.items():
        if sharing.get(q, 1.0) < CALIBRATION_ALPHA:
            c = own[q]
        if c.p_value < CALIBRATION_ALPHA and c.factor > 1:
            out[q] = (c.factor, c.dof)
    return out


def realization_sharing(rows):
    """dict quantity -> two-sided p-value that the P.B.C. and the F.B.C. groups of
    realization_scatter.csv share one factor (ErrorCalibration.same_factor_p), for the
    quantities both measure."""
    pbc, fbc = realization_calibrations(rows, "pbc"), realization_calibrations(rows, "fbc")
    return {q: pbc[q].same_factor_p(fbc[q]) for q in pbc if q in fbc}


def realization_calibrations(rows, bc=None):
    """dict quantity -> computed ErrorCalibration of realization_scatter.csv's rows (groups of
    at least two runs) of boundary condition ``bc`` ('pbc', 'fbc'; None: every group)."""
    if bc not in (None, "pbc", "fbc"):
        raise ValueError(f"bc = {bc!r}: allowed values are None, 'pbc', 'fbc'")
    by, dof = {}, {}
    for r in rows:
        if bc is not None and group_bc(r["group"]) != bc:
            continue
        by.setdefault(r["column"], {}).setdefault(r["group"], []).append(
            (float(r["mean"]), float(r["sem"])))
        dof[r["column"]] = int(r["sem_dof"]) if r["sem_dof"] else None   # None: exact
    out = {}
    for quantity, groups in by.items():
        pairs = {g: ([m for m, _ in v], [e for _, e in v]) for g, v in groups.items()
                 if len(v) >= 2}
        if pairs:
            out[quantity] = ErrorCalibration(pairs, within_dof=dof[quantity]).compute()
    return out


def _run_error_text(factor):
    """What a one-seed value's error is, as its TAPMC column says it."""
    if factor == 1.0:
        return "one seed: error within the run"
    return (f"one seed: error within the run x {factor:.1f}, the spread of realizations "
            "measured by realization-scatter")


def _missing(what):
    return [Measure(undecided=f"not in this campaign ({what})")]


def _eps_of(series):
    """eps of a series named 'eps=<eps>' or 'eps=<eps>:<name>'."""
    return float(series.split("=")[1].split(":")[0])


def _eps_series(fig, panel):
    """Sorted (eps, series) of the data series 'eps=<eps>' of a panel (fits excluded)."""
    out = [(_eps_of(s), s) for s in fig.series(panel) if s.startswith("eps=") and ":" not in s]
    return sorted(out)


def _common_x(a, b):
    """Index pairs (i, k) of the x common to the curves a and b ((x, mean, sem, n) each)."""
    pairs = []
    for i, x in enumerate(a[0]):
        match = np.isclose(b[0], x)
        if np.any(match):
            pairs.append((i, int(np.argmax(match))))
    return pairs


def _mean_difference(a, b):
    """Mean over the common x of the curves a - b ((x, mean, sem, n) each), its error and dof;
    None when they share no x."""
    pairs = _common_x(a, b)
    if not pairs:
        return None
    diffs = [a[1][i] - b[1][k] for i, k in pairs]
    errs = np.array([math.hypot(a[2][i], b[2][k]) for i, k in pairs])
    ns = [min(a[3][i], b[3][k]) for i, k in pairs]
    err = float(np.sqrt(np.sum(errs**2)) / len(errs)) if np.all(np.isfinite(errs)) else math.nan
    return float(np.mean(diffs)), err, _steady_dof(int(np.min(ns)), err), len(diffs)


# ---------------------------------------------------------------- statistics




def initial_phi(data, claim):
    """<Phi^c> of the initial P.B.C. packing. A campaign with one packing (the paper's
    protocol) is decided by the depositions of the same size measured at t = 0 (``initial-
    packing``), when there: the paper's value is one packing's, so the interval is the mean's
    error combined with the spread of single packings (a prediction interval)."""
    m, s, n = (math.nan if v is None else v for v in data.summary["initial_phi_c"])
    sizes = {(int(N), float(L)) for N, L in data.summary.get("sizes") or ()}
    phis = np.array([float(r["phi_c"]) for r in data.question("initial_packing")
                     if r["bc"] == "pbc" and (int(r["N"]), float(r["L"])) in sizes])
    if len(phis) >= 2 and not (np.isfinite(n) and n >= len(phis)):
        mean, sd = float(phis.mean()), float(phis.std(ddof=1))
        sem = sd / math.sqrt(len(phis))
        return [Measure(mean, math.hypot(sem, sd), len(phis) - 1,
                        shown=f"{fmt(mean, sem, pct=True)} over {len(phis)} depositions (one "
                              f"packing spreads {100 * sd:.2f} %; the campaign's: "
                              f"{fmt(m, None, pct=True)})")]
    return [Measure(m, s, _dof(n), shown=fmt(m, s, pct=True))]


#: Degrees of freedom of the batch-means error of one run's steady state (the batches of
#: tapmc.fluctuations.SteadyState, minus one): the uncertainty of a figure value of one seed.
WITHIN_RUN_DOF = DEFAULT_BATCHES - 1


def _steady_dof(n, err):
    """dof of a steady-state value: seeds - 1, or for one seed with a batch-means error
    :data:`WITHIN_RUN_DOF`."""
    if n >= 2:
        return n - 1
    return WITHIN_RUN_DOF if n == 1 and np.isfinite(err) else None


def tapped_phi(data, claim):
    """The steady <Phi^c> after the taps against the paper's value read at tap 4000: a single
    tap's value, so the interval is the steady state's error combined with the spread of
    single taps (a prediction interval). Without the steady state: the value at the end."""
    fig = data.figure("fig9")
    if fig is None:
        return _missing("no Fig. 9 runs")
    m, s, n = fig.param("phi_c_steady")
    if not np.isfinite(m):
        m, s, n = fig.param("phi_c_final")
        return [Measure(m, s, _dof(n), shown=fmt(m, s, pct=True))]
    sd = fig.param("phi_c_tap_sd")[0]
    err = math.hypot(s, sd) if np.isfinite(s) else math.nan
    return [Measure(m, err, _steady_dof(n, s),
                    shown=f"{fmt(m, s, pct=True)} (steady state; single taps spread "
                          f"{100 * sd:.2f} %" + (f"; {_tapped_one_seed(data)})" if n == 1
                                                 else ")"))]


def _tapped_one_seed(data):
    factor = data.run_error("phi_c")[0]
    if factor == 1.0:
        return "one seed: the spread between realizations is not included"
    return _run_error_text(factor)


def pbc_compaction(data, claim):
    fig = data.figure("fig9")
    if fig is None:
        return _missing("no Fig. 9 runs")
    mi, si, ni = fig.param("phi_c_initial")
    mf, sf, nf = fig.param("phi_c_steady")
    if not np.isfinite(mf):
        mf, sf, nf = fig.param("phi_c_final")
        dof = _dof(min(ni, nf))
    else:
        dof = _steady_dof(min(ni, nf), sf)
        if nf == 1:
            si = 0.0  # one packing: its initial value is exact, the steady mean is not
    return [Measure(mf - mi, math.hypot(si, sf), dof,
                    shown=f"{fmt(mi, si, pct=True)} -> {fmt(mf, sf, pct=True)}")]


def _figure_param(data, name, series, absent):
    """(fig, value, sem, n) of a one-row params series of figure ``name``, or (None,
    undecided measures) naming what is missing (``absent``: why the series is not there)."""
    fig = data.figure(name)
    if fig is None:
        return None, _missing(f"no Fig. {name[3:]} runs")
    m, s, n = fig.param(series)
    if not np.isfinite(m):
        return None, _missing(absent)
    return (fig, m, s, n), None


def _per_curve(data, name, panel, measure):
    """``measure(fig, eps, t, mean, sem, n)`` of every curve 'eps=<eps>' of a figure panel."""
    fig = data.figure(name)
    if fig is None:
        return _missing(f"no Fig. {name[3:]} runs")
    out = [measure(fig, eps, *fig.get(panel, series)) for eps, series in _eps_series(fig, panel)]
    return out or _missing(f"no curve in panel {panel} of Fig. {name[3:]}")


def _gain(fig, eps, t, mean, sem, n, run_error=(1.0, None)):
    """Mean of the last quarter minus the first point. One seed (the paper's protocol): the
    curve is the run itself, so the last quarter's mean has its batch-means error
    (tapmc.fluctuations.SteadyState) and the start, the run's own packing, none."""
    from tapmc.fluctuations import SteadyState

    q = max(len(t) // 4, 1)
    gain = float(np.mean(mean[-q:]) - mean[0])
    if np.nanmax(n) == 1 and q >= 2 * DEFAULT_BATCHES:
        err = SteadyState(mean, last=q).compute().sem * run_error[0]
        return Measure(gain, err, WITHIN_RUN_DOF, label=f"eps = {eps:g}",
                       shown=f"{fmt(gain, err)} ({_run_error_text(run_error[0])})")
    err = float(math.sqrt(np.nanmean(sem[-q:]) ** 2 + sem[0] ** 2)) \
        if np.isfinite(sem[0]) else math.nan
    return Measure(gain, err, _dof(n), label=f"eps = {eps:g}")


def phi_b_gain(data, claim):
    return _per_curve(data, "fig2", "a",
                      lambda *curve: _gain(*curve, run_error=data.run_error("phi_b", "fbc")))


def _fit_quality(fig, prefix, npoints, nparams, label):
    chi, _, determined = fig.param(f"{prefix}reduced_chi2")
    if not np.isfinite(chi):
        return Measure(label=label, undecided="no fit in the figure data")
    dof = npoints - nparams
    shown = f"reduced chi2 {fmt(chi)} ({dof} dof)"
    if dof < 1:
        return Measure(chi, label=label, shown=shown, undecided="fewer points than parameters")
    return Measure(chi, dof=dof, label=label, shown=shown)


def _law_quality(prefix):
    """The per-curve chi-square of a 4-parameter law of Fig. 2 whose params rows are named
    ``eps=<e>:<prefix>reduced_chi2`` (eq. 3: no prefix; eq. 4: ``Z:``), shown but undecided:
    the taps of a run are correlated (Fig. 3), so a chi-square over them with per-tap errors
    has no known distribution, whatever the number of seeds (with two seeds the medium
    preset's eq. 3 fits had reduced chi2 0.03: a test that cannot fail). The laws are decided
    across realizations (:func:`_law_across_realizations`)."""
    def measure(fig, eps, t, mean, sem, n):
        m = _fit_quality(fig, f"eps={P.fmt_eps(eps)}:{prefix}", len(t), 4, f"eps = {eps:g}")
        if m.undecided is None:
            seeds = _dof(n)
            if seeds is None:
                # without error bars the fit's "reduced chi2" is its mean squared residual
                m.shown = f"rms residual {fmt(math.sqrt(m.value))}"
                m.undecided = ("one realization: no error bars for a chi-square (the taps' "
                               "scatter is correlated)")
            else:
                m.undecided = (f"{seeds + 1} seeds: a chi-square over correlated taps has no "
                               f"known distribution; needs {REALIZATION_MIN_SEEDS} "
                               "realizations (bench/paper_questions.py early-taps)")
        return m
    return measure


#: realizations (early_taps.csv) that test a law of Fig. 2 across runs: a 4-parameter law
#: needs 6 (tapmc.laws.RealizationLawTest: realizations > bins > parameters) ...
REALIZATION_MIN_SEEDS = 6
#: ... spanning at least two decades of taps, over which the laws' curvature shows
REALIZATION_MIN_TAPS = 100


def realization_curves(data, eps, column):
    """(t, curves) of ``column`` over the realizations of early_taps.csv at ``eps`` (one row
    per seed, the taps 0..T every one of them has), or None when fewer than
    :data:`REALIZATION_MIN_SEEDS` span :data:`REALIZATION_MIN_TAPS` taps."""
    by_seed = {}
    for r in data.question("early_taps"):
        if math.isclose(float(r["eps"]), eps, rel_tol=1e-9):
            by_seed.setdefault(int(r["seed"]), {})[int(float(r["t"]))] = float(r[column])
    seeds = [s for s, v in by_seed.items() if max(v) >= REALIZATION_MIN_TAPS]
    if len(seeds) < REALIZATION_MIN_SEEDS:
        return None
    last = min(max(by_seed[s]) for s in seeds)
    t = np.arange(0, last + 1)
    if not all(all(k in by_seed[s] for k in t) for s in seeds):
        return None
    return t.astype(float), np.array([[by_seed[s][k] for k in t] for s in sorted(seeds)])


def loosening_end(data, eps):
    """The first tap at which the mean Phi_b over the realizations of early_taps.csv at
    ``eps`` is back at its t = 0 value (the first taps loosen the deposited packing, which no
    monotonic law follows), or None (too few realizations, or still loose at their last tap)."""
    curves = realization_curves(data, eps, "phi_b")
    return None if curves is None else back_at_start(curves[0], curves[1].mean(axis=0))


def back_at_start(t, mean):
    """The first tap t >= 1 at which ``mean`` (Phi_b over realizations, t[0] = 0) is back at
    its t = 0 value, or None."""
    back = np.flatnonzero((np.asarray(t) >= 1) & (np.asarray(mean) >= mean[0]))
    return float(t[back[0]]) if back.size else None


def _law_across_realizations(data, eps, law, column):
    """Measures of one law of Fig. 2 tested across the realizations of early_taps.csv at
    ``eps`` (tapmc.laws.RealizationLawTest): over every tap from the first, and from the end
    of the first taps' loosening (:func:`loosening_end`); None when the realizations are too
    few."""
    from tapmc.laws import RealizationLawTest

    curves = realization_curves(data, eps, column)
    if curves is None:
        return None
    out = []
    back = loosening_end(data, eps)
    for t_min, part in ((1.0, "every tap"), (back, "after the first taps' loosening")):
        label = f"eps = {eps:g}, {part}"
        if t_min is None or t_min * 10 > curves[0][-1]:
            out.append(Measure(label=label, undecided=(
                "the packing is still looser than at t = 0 a decade before the "
                "realizations' last tap")))
            continue
        test = RealizationLawTest(law, t_min=t_min).compute(*curves)
        edges = test.bin_edges
        out.append(Measure(test.chi2, dof=test.dof, p_value=test.p_value, label=label,
                           shown=f"T^2 {fmt(test.chi2)} ({test.dof} dof) over taps "
                                 f"{edges[0]:g}-{edges[-1] - 1:g} in {len(edges) - 1} log "
                                 f"bins, {test.realizations} realizations from the same "
                                 "packing"))
    return out


def _fig2_law_quality(data, law, column, panel, prefix):
    """Per eps of Fig. 2: the law across realizations where early_taps.csv has them (two
    measures: every tap, and after the first taps' loosening), else the chi-square of the
    figure's own fit (:func:`_law_quality`)."""
    fig = data.figure("fig2")
    if fig is None:
        return _missing("no Fig. 2 runs")
    out = []
    for eps, series in _eps_series(fig, panel):
        ms = _law_across_realizations(data, eps, law, column)
        out += ms if ms is not None else [_law_quality(prefix)(fig, eps, *fig.get(panel, series))]
    return out or _missing(f"no curve in panel {panel} of Fig. 2")


def eq3_fit_quality(data, claim):
    from tapmc.laws import InverseLogLaw

    return _fig2_law_quality(data, InverseLogLaw(), "phi_b", "a", "")


#: Parameters of eq. 3 whose uniqueness section III.B discusses: the triplet (X_inf, B, tau).
EQ3_TRIPLET = ("X_inf", "B", "tau")


def _eq3_uniqueness(fig, eps):
    """(unique, reason) of the eq. 3 triplet at one eps from Fig. 2's params: unique when
    every parameter is determined (its profile interval closes) and consistent over the tap
    ranges; None when the figure data have no intervals."""
    tag = f"eps={P.fmt_eps(eps)}"
    if fig.get("params", f"{tag}:tau:range_deviation") is None:
        return None, ""
    undetermined = [k for k in EQ3_TRIPLET if fig.param(f"{tag}:{k}")[2] != 1]
    dependent = [k for k in EQ3_TRIPLET if fig.param(f"{tag}:{k}:range_deviation")[2] != 1]
    reasons = ([f"{', '.join(undetermined)} undetermined"] if undetermined else []) + \
        ([f"{', '.join(dependent)} range dependent"] if dependent else [])
    return not reasons, "; ".join(reasons) or "unique"


#: why the fits of Fig. 2 decide nothing with one run per eps: their errors come from the
#: scatter of the taps about the law, whose correlation (Fig. 3's spectrum) they ignore, so
#: the intervals, the range tests and B's errors would be too narrow
ONE_RUN_FITS = "one realization: the fits' intervals ignore the taps' correlation"


def _one_run_fig2(fig):
    """True when every curve of Fig. 2 is one run (n = 1)."""
    series = _eps_series(fig, "a")
    return bool(series) and max(np.nanmax(fig.get("a", name)[3]) for _, name in series) < 2


def _run_seed(name):
    """The seed of a campaign run's folder name (``..._s<seed>``)."""
    return int(name.rsplit("_s", 1)[1])


def surrogate_fits(data, law):
    """eps -> {parameter: row} of fit_surrogates.csv for ``law`` ('eq3', 'eq4') and the
    campaign's run of the paper's protocol at each eps: the first seed (the other seeds'
    rows, and the realizations of the first taps, are shown beside it, not read here)."""
    first = {}
    for r in data.question("fit_surrogates"):
        if r["source"] != "realizations" and r["law"] == law:
            e = float(r["eps"])
            first[e] = min(first.get(e, r["source"]), r["source"], key=_run_seed)
    out = {}
    for r in data.question("fit_surrogates"):
        if r["law"] == law and first.get(float(r["eps"])) == r["source"]:
            out.setdefault(float(r["eps"]), {})[r["parameter"]] = r
    return dict(sorted(out.items()))


def _surrogate_uniqueness(params, names):
    """(unique, reason) of one run's parameters ``names`` from its fit_surrogates rows."""
    from tapmc.laws import SURROGATE_P_MIN

    undetermined = [k for k in names if params[k]["determined"] != "1"]
    dependent = [k for k in names if float(params[k]["range_p"]) < SURROGATE_P_MIN]
    reasons = ([f"{', '.join(undetermined)} undetermined"] if undetermined else []) + \
        ([f"{', '.join(dependent)} range dependent"] if dependent else [])
    return not reasons, "; ".join(reasons) or "unique within the surrogates"


#: why a "unique" triplet of one run decides nothing: the surrogates' bands are narrower than
#: the spread of independent realizations (tests/python/test_slow_surrogate_fits.py)
SURROGATES_UNIQUE = ("one run's surrogates show an upper bound of how well the triplet is "
                     "fixed: 'unique' needs realizations")


def realization_fits(data, law, bc):
    """eps -> {parameter: row} of seed_fits.csv (bench/paper_questions.py seed-fits: whole runs
    fitted over realizations, tapmc.laws.RealizationFits) for ``law`` ('eq3', 'eq4') and
    boundary condition ``bc``; at an eps with several groups, the one of most realizations."""
    out = {}
    for r in data.question("seed_fits"):
        if r["law"] != law or r["bc"] != bc:
            continue
        group = out.setdefault(float(r["eps"]), {})
        if group and int(next(iter(group.values()))["realizations"]) > int(r["realizations"]):
            continue
        if group and next(iter(group.values()))["group"] != r["group"]:
            group.clear()
        group[r["parameter"]] = r
    return dict(sorted(out.items()))


def _realization_uniqueness(params, names):
    """(unique: True, False or None, reason) of the triplet ``names`` from one group's
    seed_fits rows: the spread over realizations decides "determined" both ways (its
    chi-square interval), a paired t-test over the ranges "range dependent"."""
    from tapmc.laws import SURROGATE_P_MIN

    def spread(k):
        r = params[k]
        unit = "ln " if r["log_scale"] == "1" else ""
        return (f"sd of {unit}{k} {float(r['spread']):.2g} (95 %: {float(r['spread_low']):.2g} "
                f"to {float(r['spread_high']):.2g}; limit {float(r['limit']):.2g})")

    undetermined = [k for k in names if params[k]["determined"] == "0"]
    open_ = [k for k in names if params[k]["determined"] == ""]
    dependent = [k for k in names if float(params[k]["range_p"]) < SURROGATE_P_MIN]
    n = params[names[0]]["realizations"]
    reasons = ([f"{', '.join(undetermined)} undetermined ({'; '.join(map(spread, undetermined))})"]
               if undetermined else []) + \
        ([f"{', '.join(dependent)} range dependent"] if dependent else [])
    if reasons:
        return False, f"{n} realizations: " + "; ".join(reasons)
    if open_:
        return None, (f"{n} realizations cannot tell whether {', '.join(open_)} "
                      f"{'is' if len(open_) == 1 else 'are'} fixed "
                      f"({'; '.join(map(spread, open_))})")
    return True, f"{n} realizations: unique"


def _triplet_pattern(states, shown):
    """The pattern over ``states`` [(eps, unique: True/False/None, reason)], by eps: holds
    (1) when the smallest eps is not unique and a larger one is, contradicted (0) when the
    smallest is unique or none is, undecided otherwise."""
    first = states[0][1]
    if first is True or all(u is False for _, u, _ in states):
        return [Measure(0.0, shown=shown)]
    if first is False and any(u is True for _, u, _ in states[1:]):
        return [Measure(1.0, shown=shown)]
    return None


def _triplet_from_surrogates(rows, realized=None):
    """The pattern from one run per eps (fit_surrogates.csv): "not unique" is safe (the
    surrogates' bands are too narrow, never too wide), "unique" is not. Where realizations
    of whole runs (``realized``: seed_fits rows by eps) decide, they replace the run's
    verdict; where they cannot tell, a run's "not unique" still decides."""
    realized = realized or {}
    states = []
    for e in sorted(set(rows) | set(realized)):
        one = _surrogate_uniqueness(rows[e], EQ3_TRIPLET) if e in rows else None
        many = _realization_uniqueness(realized[e], EQ3_TRIPLET) if e in realized else None
        if many is not None and (many[0] is not None or one is None or one[0]):
            unique = many[0]
            why = many[1] + (f" (the run's surrogates: {one[1]})" if one else "")
        else:
            unique = False if not one[0] else None
            why = one[1] + (f" ({many[1]})" if many else "")
        states.append((e, unique, why))
    shown = "; ".join(f"eps = {e:g}: {why}" for e, _, why in states) + \
        " (one run per eps, Fourier surrogates of its residuals: fit_surrogates.csv" + \
        ("; realizations of whole runs: seed_fits.csv)" if realized else ")")
    decided = _triplet_pattern(states, shown)
    if decided is not None:
        return decided
    unsure = [e for e, u, _ in states if u is None]
    if all(e not in realized for e in unsure):
        return [Measure(undecided=SURROGATES_UNIQUE, shown=shown)]
    return [Measure(undecided=_REALIZATIONS_UNSURE.format(", ".join(f"{e:g}" for e in unsure)),
                    shown=shown)]


#: why realizations of whole runs leave the pattern open (they decide "fixed" both ways)
_REALIZATIONS_UNSURE = ("the realizations cannot tell whether the triplet is fixed at eps = {}: "
                        "their spread's 95 % interval straddles the limit")


def _triplet_from_realizations(realized, label):
    """The pattern from realizations of whole runs alone (seed_fits.csv rows by eps)."""
    states = [(e, *_realization_uniqueness(p, EQ3_TRIPLET)) for e, p in realized.items()]
    shown = "; ".join(f"eps = {e:g}: {why}" for e, _, why in states) + \
        " (realizations of whole runs: seed_fits.csv)"
    decided = _triplet_pattern(states, shown)
    if decided is not None:
        return [Measure(decided[0].value, label=label, shown=shown)]
    unsure = ", ".join(f"{e:g}" for e, u, _ in states if u is None)
    return [Measure(undecided=_REALIZATIONS_UNSURE.format(unsure), label=label, shown=shown)]


def eq3_triplet_pattern(data, claim):
    """Section III.B: the triplet is not unique at the smallest eps and unique at some larger
    eps (1), or not (0). Fig. 2's F.B.C. runs (their surrogates, and realizations of whole
    runs where the campaign has them); a second row from the P.B.C. groups of realizations
    when there are two eps or more."""
    rows = surrogate_fits(data, "eq3")
    if len(rows) >= 2:
        out = _triplet_from_surrogates(rows, realization_fits(data, "eq3", "fbc"))
        pbc = realization_fits(data, "eq3", "pbc")
        if len(pbc) >= 2:
            out = [dataclasses.replace(out[0], label="F.B.C., Fig. 2's runs")] + \
                _triplet_from_realizations(pbc, "P.B.C. realizations")
        return out
    fig = data.figure("fig2")
    if fig is None:
        return _missing("no Fig. 2 runs")
    series = _eps_series(fig, "a")
    if len(series) < 2:
        return _missing("fewer than two eps in Fig. 2")
    if _one_run_fig2(fig):
        return [Measure(undecided=ONE_RUN_FITS)]
    states = [(e, *_eq3_uniqueness(fig, e)) for e, _ in series]
    if any(u is None for _, u, _ in states):
        return _missing("no profile intervals and range refits in the Fig. 2 data")
    shown = "; ".join(f"eps = {e:g}: {why}" for e, _, why in states)
    holds = (not states[0][1]) and any(u for _, u, _ in states[1:])
    return [Measure(1.0 if holds else 0.0, shown=shown)]


def eq4_fit_quality(data, claim):
    from tapmc.laws import ZLaw

    return _fig2_law_quality(data, ZLaw(), "Z", "c", "Z:")


def _b_from_surrogates(rows, label):
    """ln B against sqrt(eps) from one run per eps (fit_surrogates.csv): only where B is
    determined (an undetermined B is safe, a determined one an upper bound), with the
    surrogates' half widths as errors. Too narrow errors make a rejection unsafe and an
    agreement safe, so only agreement decides."""
    from scipy.stats import chi2 as chi2_distribution

    determined = {e: p["B"] for e, p in rows.items() if p["B"]["determined"] == "1"}
    text = "; ".join(f"eps = {e:g}: B {float(p['B']['value']):.3g} "
                     f"({float(p['B']['low']):.3g}-{float(p['B']['high']):.3g})"
                     for e, p in rows.items())
    if len(determined) < 3:
        missing = [f"{e:g}" for e in rows if e not in determined]
        return Measure(label=label, shown=text,
                       undecided=f"B undetermined at eps = {', '.join(missing)} (one run per "
                                 "eps, Fourier surrogates): fewer than three eps with a "
                                 "determined B")
    x = np.sqrt(np.array(list(determined)))
    y = np.log([float(p["value"]) for p in determined.values()])
    err = np.array([float(p["half_width"]) for p in determined.values()])
    coef = np.polyfit(x, y, 1, w=1.0 / err)
    chi = float(np.sum(((y - np.polyval(coef, x)) / err) ** 2))
    dof = len(x) - 2
    p_value = float(chi2_distribution.sf(chi, dof))
    shown = f"{text}; d ln B / d sqrt(eps) = {coef[0]:.3g}, chi2 {chi:.3g} ({dof} dof)"
    if p_value >= 0.01:
        return Measure(chi / dof, dof=dof, label=label, shown=shown, p_value=p_value)
    return Measure(label=label, shown=shown,
                   undecided=f"p = {p_value:.2g}, but one run's surrogate errors are too "
                             "narrow to reject")


def b_exponential(data, claim):
    """ln B linear in sqrt(eps) (Fig. 2 panel B) for the B of eq. 3 and of eq. 4."""
    from_surrogates = [_b_from_surrogates(rows, f"B of {law.replace('eq', 'eq. ')}")
                       for law in ("eq3", "eq4") if len(rows := surrogate_fits(data, law)) >= 1]
    if from_surrogates:
        return from_surrogates
    fig = data.figure("fig2")
    if fig is None:
        return _missing("no Fig. 2 runs")
    one_run = _one_run_fig2(fig)
    out = []
    for law in ("eq3", "eq4"):
        d = fig.get("B", f"{law}:reduced_chi2")
        if d is None:
            continue
        chi, dof = float(d[1][0]), int(d[3][0])
        slope = fig.get("B", f"{law}:slope")
        text = "" if slope is None else f"d ln B / d sqrt(eps) = {fmt(slope[1][0], slope[2][0])}; "
        label = f"B of {law.replace('eq', 'eq. ')}"
        if one_run:
            out.append(Measure(label=label, undecided=ONE_RUN_FITS,
                               shown=text.rstrip("; ") or None))
        elif dof < 1 or not np.isfinite(chi):
            out.append(Measure(label=label, undecided="fewer than three eps with a determined B",
                               shown=text.rstrip("; ") or None))
        else:
            out.append(Measure(chi, dof=dof, label=label,
                               shown=f"{text}reduced chi2 {fmt(chi)} ({dof} dof)"))
    return out or _missing("no B(sqrt(eps)) fit in the Fig. 2 data")


def ageing_collapse(data, claim):
    """Hotelling's T^2 of the drawn collapse of Fig. 5 across the realizations
    (``scaling_test:`` rows, tapmc.ageing.ScalingRealizationTest), with mu and the reduced
    chi2 over the correlated delays beside it (which decides nothing: its delays share their
    realizations and their errors come from the same few of them)."""
    fig = data.figure("fig5")
    if fig is None:
        return _missing("no ageing runs")
    drawn_mu = fig.param("drawn:mu")
    if not np.isfinite(drawn_mu[0]):
        return _missing("no rescaled collapse in the Fig. 5 data")
    tag = "scaling" if drawn_mu[2] == 1 else "scaling_time"
    chi = fig.param(f"{tag}:reduced_chi2")[0]
    mu, mu_err, mu_closed = fig.param(f"{tag}:mu")
    mu_text = fmt(mu, mu_err) if mu_closed == 1 else f"{fmt(mu)} (undetermined)"
    shown = (f"mu = {mu_text}; reduced chi2 over the correlated delays {fmt(chi)} (decides "
             "nothing)")
    curves = [s for s in fig.series("a") if s.startswith("tw=") and float(s[3:]) > 0]
    realizations = int(min(np.min(fig.get("a", s)[3]) for s in curves)) if curves else 0
    needed = fig.param("scaling_test:needed")[0]
    if not np.isfinite(needed):
        from tapmc.ageing import scaling_test_min_realizations
        needed = scaling_test_min_realizations(len(curves), drawn_mu[2] == 1)
    if realizations < needed:
        return [Measure(shown=shown, undecided=(
            f"{realizations} realizations: the test of the collapse across realizations needs "
            f"at least {int(needed)} (the paper averaged 10)"))]
    T2 = fig.param("scaling_test:T2")[0]
    if not np.isfinite(T2):
        return [Measure(shown=shown, undecided=(
            "the Fig. 5 data have no test across realizations (drawn before it existed: "
            "draw Fig. 5 again from its runs)"))]
    dof = int(fig.param("scaling_test:dof")[0])
    bins = int(fig.param("scaling_test:bins")[0])
    shown += _long_delays_text("; the test", fig.param("scaling_test_long:p_value")[0])
    return [Measure(T2, dof=dof, p_value=fig.param("scaling_test:p_value")[0],
                    shown=f"T^2 {fmt(T2)} ({dof} dof) over {bins} log bins of delays, "
                          f"{realizations} realizations; {shown}")]


def _long_delays_text(lead, p_value):
    """``lead`` and the p-value of a Fig. 5 test over the long delays alone (``""`` when the
    figure data have none)."""
    from tapmc.paper.fig5 import LONG_DELAYS

    if not np.isfinite(p_value):
        return ""
    return (f"{lead} over the delays >= {LONG_DELAYS} alone (a linear axis of t, as the paper "
            f"draws it): p = {fmt(p_value, digits=2)}")


def ageing_eq6(data, claim):
    """Eq. 6 on each curve of Fig. 5 alone, tested across the realizations (``eq6_test:``
    rows, tapmc.ageing.Ageing.eq6_test), one row per waiting time, with the share of the curve
    that is the square of the mean displacement (``drift_share:``)."""
    fig = data.figure("fig5")
    if fig is None:
        return _missing("no ageing runs")
    curves = sorted((float(s[3:]), s) for s in fig.series("a")
                    if s.startswith("tw=") and float(s[3:]) > 0)
    if not curves:
        return _missing("no curve A(t, t_W) with t_W > 0 in the Fig. 5 data")
    from tapmc.paper.fig5 import EQ6_TEST_MIN_REALIZATIONS

    needed = fig.param("eq6_test:needed")[0]
    if not np.isfinite(needed):                     # drawn before the rows existed
        needed = EQ6_TEST_MIN_REALIZATIONS
    out = []
    for tw, series in curves:
        label = f"t_W = {tw:g}"
        realizations = int(np.min(fig.get("a", series)[3]))
        if realizations < needed:
            out.append(Measure(label=label, undecided=(
                f"{realizations} realizations: eq. 6's test across realizations needs at "
                f"least {int(needed)} (the paper averaged 10)")))
            continue
        T2, _, _ = fig.param(f"eq6_test:tw={tw:g}:T2")
        if not np.isfinite(T2):
            out.append(Measure(label=label, undecided=(
                "the Fig. 5 data have no test of eq. 6 across realizations (drawn before it "
                "existed: draw Fig. 5 again from its runs)")))
            continue
        dof = int(fig.param(f"eq6_test:tw={tw:g}:dof")[0])
        bins = int(fig.param(f"eq6_test:tw={tw:g}:bins")[0])
        share = fig.param(f"drift_share:tw={tw:g}")[0]
        long_text = _long_delays_text(";", fig.param(f"eq6_test_long:tw={tw:g}:p_value")[0])
        out.append(Measure(T2, dof=dof, p_value=fig.param(f"eq6_test:tw={tw:g}:p_value")[0],
                           label=label,
                           shown=(f"T^2 {fmt(T2)} ({dof} dof) over {bins} log bins of delays, "
                                  f"{realizations} realizations; the mean displacement's "
                                  f"square is {fmt(share, pct=True)} of A{long_text}")))
    return out


#: Decades of the log-time slopes of ``log_time_slowing``: the first decade of taps (the last
#: one is [T/10, T]).
EARLY_DECADE = (1.0, 10.0)


def first_decade_rates(t, x):
    """(rate per tap, rate per unit ln t) of one realization over the first decade
    (:data:`EARLY_DECADE`), each from the means of the decade's two halves (per tap: taps 1-5
    and 6-10; per ln t: split at sqrt(10)), and the two gaps between the halves (taps, ln t):
    ((rate, gap), (log_rate, log_gap))."""
    lo, hi = EARLY_DECADE
    first, second = (t >= lo) & (t <= hi / 2), (t > hi / 2) & (t <= hi)
    gap = float(np.mean(t[second]) - np.mean(t[first]))
    rate = (float(np.mean(x[second])) - float(np.mean(x[first]))) / gap
    mid = math.sqrt(lo * hi)
    low, high = (t >= lo) & (t < mid), (t >= mid) & (t <= hi)
    log_gap = float(np.mean(np.log(t[high])) - np.mean(np.log(t[low])))
    log_rate = (float(np.mean(x[high])) - float(np.mean(x[low]))) / log_gap
    return (rate, gap), (log_rate, log_gap)


#: realizations of the first decade (bench/paper_questions.py early-taps) below which its
#: rates keep one run's error (one tap's spread): the sem of fewer has too few degrees of
#: freedom to decide anything
EARLY_MIN_SEEDS = 4


def _early_seeds(data, eps):
    """The first decade's rates over the realizations of early_taps.csv at ``eps`` (the
    campaign's run and more Monte Carlo seeds from the same packing): (per tap (mean, sem),
    per ln t (mean, sem), seeds) or None when fewer than :data:`EARLY_MIN_SEEDS`."""
    rows = [r for r in data.question("early_taps")
            if math.isclose(float(r["eps"]), eps, rel_tol=1e-9)]
    by_seed = {}
    for r in rows:
        by_seed.setdefault(int(r["seed"]), []).append((float(r["t"]), float(r["phi_b"])))
    rates = []
    for points in by_seed.values():
        t, x = (np.array(v) for v in zip(*sorted(points)))
        if np.all(np.isin(np.arange(EARLY_DECADE[0], EARLY_DECADE[1] + 1), t)):
            (rate, _), (log_rate, _) = first_decade_rates(t, x)
            rates.append((rate, log_rate))
    if len(rates) < EARLY_MIN_SEEDS:
        return None
    values = np.array(rates)
    sem = values.std(axis=0, ddof=1) / math.sqrt(len(values))
    mean = values.mean(axis=0)
    return (mean[0], sem[0]), (mean[1], sem[1]), len(values)


def _log_rates_one_run(t, x, early_seeds=None, halves_factor=1.0):
    """Rates of Phi_b per unit ln t of one run (the curve is the run) over the first decade and
    the last decade [T/10, T], each from the means of the decade's two halves in ln t: the
    late halves with their batch-means errors (tapmc.fluctuations.SteadyState), the early ones
    with the error over realizations when ``early_seeds`` (:func:`_early_seeds`) has them,
    else with one tap's spread about the steady state (not divided by their number: taps that
    close are correlated); ``halves_factor`` scales the late error to a realization's
    (:meth:`ReportData.run_error` of 'phi_b:halves'). ((early, error), (late, error))."""
    from tapmc.fluctuations import SteadyState

    if early_seeds is not None:
        early = early_seeds[1]
    else:
        spread = SteadyState(x, last=max(len(t) // 4, 2)).compute().std
        (_, _), (log_rate, log_gap) = first_decade_rates(t, x)
        early = (log_rate, math.sqrt(2.0) * spread / log_gap)
    lo, hi = t[-1] / 10.0, t[-1]
    mid = math.sqrt(lo * hi)
    parts = [(t >= lo) & (t < mid), (t >= mid) & (t <= hi)]
    means = [float(np.mean(x[p])) for p in parts]
    errs = [SteadyState(x[p], last=int(p.sum())).compute().sem for p in parts]
    gap = float(np.mean(np.log(t[parts[1]])) - np.mean(np.log(t[parts[0]])))
    return early, ((means[1] - means[0]) / gap, halves_factor * math.hypot(*errs) / gap)


def _log_slope(t, mean, sem, lo, hi):
    pick = (t >= lo) & (t <= hi) & (t > 0)
    return _weighted_line(np.log(t[pick]), mean[pick], sem[pick])



def _rate_change_one_run(eps, t, x, early_seeds=None, halves_factor=1.0):
    """:func:`_rate_change` of one run (the curve is the run): the late rate from the means of
    its last two quarters (each with its batch-means error); the early rate from the means of
    the two halves of the first decade (taps 1-5 and 6-10, as the line over the decade for
    several seeds): over the realizations of ``early_seeds`` (:func:`_early_seeds`) when
    there, else the run's own, each half with one tap's spread about the steady state as its
    error (taps that close together are correlated, so the spread is not divided by their
    number). ``halves_factor``: as in :func:`_log_rates_one_run`."""
    from tapmc.fluctuations import SteadyState

    q = len(t) // 4
    third, fourth = (SteadyState(x[:len(t) - k * q], last=q).compute() for k in (1, 0))
    late = (fourth.mean - third.mean) / q
    e_late = halves_factor * math.hypot(third.sem, fourth.sem) / q
    if early_seeds is not None:
        (early, e_early), _, seeds = early_seeds
        dof = min(seeds - 1, WITHIN_RUN_DOF)
        source = f"the first decade over {seeds} realizations from the same packing"
    else:
        (early, gap), _ = first_decade_rates(t, x)
        e_early = math.sqrt(2.0) * fourth.std / gap
        dof = WITHIN_RUN_DOF
        source = "one seed: errors within the run"
    if halves_factor != 1.0:
        source += f"; the last half's error x {halves_factor:.1f} (realization-scatter)"
    return Measure(late - early, math.hypot(e_late, e_early), dof,
                   label=f"eps = {eps:g}",
                   shown=f"{fmt(late, e_late)} vs {fmt(early, e_early)} per tap (last half vs "
                         f"first decade; {source})")


def _rate_change(fig, eps, t, mean, sem, n, early_seeds=None, halves_factor=1.0):
    """Rate dPhi_b/dt over the last half of the taps minus that over the first decade."""
    if np.nanmax(n) == 1 and len(t) >= 8 * DEFAULT_BATCHES and t[-1] > 10 * EARLY_DECADE[1]:
        return _rate_change_one_run(eps, t, mean, early_seeds, halves_factor)
    early, e_early, _ = _weighted_line_in(t, mean, sem, *EARLY_DECADE)
    late, e_late, _ = _weighted_line_in(t, mean, sem, t[-1] / 2.0, t[-1])
    label = f"eps = {eps:g}"
    if not (np.isfinite(early) and np.isfinite(late)):
        return Measure(label=label, undecided="no error bars on the curve")
    return Measure(late - early, math.hypot(e_late, e_early), _dof(n), label=label,
                   shown=f"{fmt(late, e_late)} vs {fmt(early, e_early)} per tap "
                         f"(last half vs first decade)")


def _weighted_line_in(t, mean, sem, lo, hi):
    pick = (t >= lo) & (t <= hi)
    return _weighted_line(t[pick], mean[pick], sem[pick])


def efficiency_decrease(data, claim):
    return _per_curve(data, "fig2", "a", lambda fig, eps, *curve: _rate_change(
        fig, eps, *curve, early_seeds=_early_seeds(data, eps),
        halves_factor=data.run_error("phi_b:halves", "fbc")[0]))


def _fig2_end_curves(data):
    """(fig, [(eps, series) of the smallest and the largest eps]) of Fig. 2's panel a, or
    (None, the missing-data measures) when there are not two eps."""
    fig = data.figure("fig2")
    if fig is None:
        return None, _missing("no Fig. 2 runs")
    curves = _eps_series(fig, "a")
    if len(curves) < 2:
        return None, _missing("fewer than two eps in Fig. 2")
    return fig, [curves[0], curves[-1]]


def log_time_slowing(data, claim):
    """(late / early rate of Phi_b per unit ln t) at the smallest eps minus that at the
    largest: negative when the slowing is strongest at small eps (section III.A)."""
    fig, ends = _fig2_end_curves(data)
    if fig is None:
        return ends
    ratios = []
    for eps, series in ends:
        t, mean, sem, n = fig.get("a", series)
        if np.nanmax(n) == 1 and t[-1] >= 100 * EARLY_DECADE[1]:
            seeds = _early_seeds(data, eps)
            (early, e_early), (late, e_late) = _log_rates_one_run(
                t, mean, seeds, data.run_error("phi_b:halves", "fbc")[0])
            dof = WITHIN_RUN_DOF if seeds is None else min(seeds[2] - 1, WITHIN_RUN_DOF)
        else:
            early, e_early, _ = _log_slope(t, mean, sem, *EARLY_DECADE)
            late, e_late, _ = _log_slope(t, mean, sem, t[-1] / 10.0, t[-1])
            dof = _dof(n)
        if not (np.isfinite(early) and early > 2 * e_early):
            return [Measure(undecided=f"no significant compaction in the first decade at "
                                      f"eps = {eps:g} (rate {fmt(early, e_early)})")]
        r = late / early
        ratios.append((eps, r, abs(r) * math.hypot(e_late / late if late else math.inf,
                                                    e_early / early), dof))
    (e0, r0, s0, d0), (e1, r1, s1, d1) = ratios
    dofs = [d for d in (d0, d1) if d is not None]
    dof = min(dofs) if len(dofs) == 2 else None
    # both ratios beyond 1 by t sem: the log-time rate grows at both eps, no slowing on ln t
    speeding = dof is not None and all(r - t_quantile(dof) * s > 1
                                       for r, s in ((r0, s0), (r1, s1)))
    return [Measure(r0 - r1, math.hypot(s0, s1), dof,
                    shown=f"late/early rate {fmt(r0, s0)} (eps = {e0:g}) vs {fmt(r1, s1)} "
                          f"(eps = {e1:g})" + (
                              "; both above 1: per unit ln t neither run slows down within "
                              "its taps (the first decade begins with the first taps' "
                              "loosening), the weakest taps compacting latest" if speeding
                              else ""))]


#: late_gain_share: the windows, as fractions of the run's taps T, whose means give Phi_b at
#: the end ([0.9 T, T]) and a decade before it ([0.09 T, 0.11 T]); batches of the earlier,
#: shorter window (81 taps of 4000: batches of 8)
LATE_WINDOW = (0.9, 1.0)
DECADE_BEFORE_WINDOW = (0.09, 0.11)
SHORT_WINDOW_BATCHES = 10


def _late_share(t, mean, sem, n, factor=1.0):
    """(share of the gain X(T) - X(0) made over the last decade, its error, dof) of one
    curve: X over [0.9 T, T] and over [0.09 T, 0.11 T] (one run: batch-means errors times
    ``factor``, :meth:`ReportData.run_error`; several
    seeds: the curve's sem averaged over each window, not reduced for the taps' correlation)."""
    from tapmc.fluctuations import SteadyState

    T = t[-1]
    windows = [(t >= lo * T) & (t <= hi * T) for lo, hi in (LATE_WINDOW, DECADE_BEFORE_WINDOW)]
    end, before = (float(np.mean(mean[w])) for w in windows)
    if np.nanmax(n) == 1:
        errs = [factor * SteadyState(mean[w], last=int(w.sum()), batches=b).compute().sem
                for w, b in zip(windows, (DEFAULT_BATCHES, SHORT_WINDOW_BATCHES))]
        dof = min(DEFAULT_BATCHES, SHORT_WINDOW_BATCHES) - 1
    else:
        errs = [float(np.nanmean(sem[w])) for w in windows]
        dof = _dof(n)
    gain = end - mean[0]
    share = (end - before) / gain
    # d share / d end = (before - X0) / gain^2, d share / d before = -1 / gain
    err = math.hypot((before - mean[0]) / gain ** 2 * errs[0], errs[1] / gain)
    return share, err, dof


def late_gain_share(data, claim):
    """Share of Phi_b's gain made over the last decade at the smallest eps minus that at the
    largest: positive when the smallest eps is farthest from its steady state at the end of
    the run (section III.A: 'without never really reaching it', most of all at small eps)."""
    fig, ends = _fig2_end_curves(data)
    if fig is None:
        return ends
    shares = []
    for eps, series in ends:
        t, mean, sem, n = fig.get("a", series)
        if t[-1] < 10 * EARLY_DECADE[1] or (
                np.nanmax(n) == 1 and np.sum(t >= LATE_WINDOW[0] * t[-1]) < 2 * DEFAULT_BATCHES):
            return _missing("runs too short for a last decade of taps")
        shares.append((eps, *_late_share(t, mean, sem, n, data.run_error("phi_b", "fbc")[0])))
    (e0, s0, d0, f0), (e1, s1, d1, f1) = shares
    dofs = [d for d in (f0, f1) if d is not None]
    return [Measure(s0 - s1, math.hypot(d0, d1), min(dofs) if len(dofs) == 2 else None,
                    shown=f"share of the gain over the last decade {fmt(s0, d0)} "
                          f"(eps = {e0:g}) vs {fmt(s1, d1)} (eps = {e1:g})")]


def spectral_slopes(data, claim):
    fig = data.figure("fig3")
    if fig is None:
        return _missing("no Fig. 3 runs")
    out = []
    for series in fig.series("params"):
        if series.endswith(":slope"):
            m, s, n = fig.param(series)
            out.append((_eps_of(series),
                        Measure(-m, s, _steady_dof(n, s), label=f"eps = {_eps_of(series):g}",
                                shown=fmt(m, s))))
    return [m for _, m in sorted(out, key=lambda p: p[0])] or _missing("no spectrum")


#: Fraction of the frequencies (lowest, highest) compared by ``spectrum_eps_spread``.
SPECTRUM_BAND = 0.25
#: Resamplings of the spectra that propagate their sem to ``spectrum_eps_spread``.
SPECTRUM_RESAMPLINGS = 400


def spectrum_eps_spread(data, claim):
    """Spread over eps of log10 P(f) in the highest-frequency band minus that in the lowest
    band (section III.A: eps is noticeable only at high frequencies)."""
    fig = data.figure("fig3")
    if fig is None:
        return _missing("no Fig. 3 runs")
    curves = [fig.get("a", s) for _, s in _eps_series(fig, "a")]
    if len(curves) < 3:
        return _missing("fewer than three spectra")
    rng = np.random.default_rng(12345)

    def spread(samples):
        low, high = [], []
        for f, logp in samples:
            k = max(int(len(f) * SPECTRUM_BAND), 1)
            order = np.argsort(f)
            low.append(np.mean(logp[order[:k]]))
            high.append(np.mean(logp[order[-k:]]))
        return float(np.std(high, ddof=1) - np.std(low, ddof=1))

    def logs(f, p):
        ok = (f > 0) & (p > 0)
        return f[ok], np.log10(p[ok])

    base = spread([logs(f, p) for f, p, _, _ in curves])
    if not all(np.all(np.isfinite(s[(f > 0) & (p > 0)])) for f, p, s, _ in curves):
        return [Measure(base, undecided="one realization: the spectra have no error bars")]
    seeds = int(min(c[3].min() for c in curves))
    draws = []
    for _ in range(SPECTRUM_RESAMPLINGS):
        sample = []
        for f, p, s, _ in curves:
            if seeds == 1:
                # one run per eps: its bins are Gamma means of m = (P / err)^2 effective
                # periodogram ordinates (tapmc.fluctuations.PowerSpectrum.power_error)
                with np.errstate(divide="ignore"):
                    m = np.where(s > 0, (p / s) ** 2, np.inf)
                finite = np.isfinite(m) & (m > 0)
                factor = np.ones_like(p)
                factor[finite] = rng.gamma(m[finite], 1.0 / m[finite])
                noisy = p * factor
            else:
                noisy = p + s * rng.standard_normal(p.shape)
            sample.append(logs(f, np.where(noisy > 0, noisy, p)))
        draws.append(spread(sample))
    # one run: the errors follow from the estimator's known distribution, not from a sample
    # of realizations, so the verdict's quantile is the normal one (t with infinite dof)
    dof = math.inf if seeds == 1 else _dof(seeds)
    shown = f"{fmt(base, float(np.std(draws, ddof=1)))}" + (
        " (one run per eps: the periodogram's own errors)" if seeds == 1 else "")
    return [Measure(base, float(np.std(draws, ddof=1)), dof, shown=shown)]


def sigma_intercept(data, claim):
    """Intercept of a free straight line through sigma_<Z> against sqrt(eps) (Fig. 3 bottom);
    ``params.about = "line"``: sigma_<Z> about each run's straight line over its last taps
    (fig3's detrended series) instead of the paper's X_SS."""
    suffix = "_detrended" if claim.params.get("about") == "line" else ""
    fig = data.figure("fig3")
    absent = "fewer than three eps: no free straight line"
    if suffix and fig is not None and fig.get("b", "sigma_Z_detrended") is None:
        return [Measure(undecided="Fig. 3's CSV was drawn without the detrended sigma_<Z>: "
                                  "draw Fig. 3 again from its runs")]
    found, missing = _figure_param(data, "fig3", "intercept" + suffix, absent)
    if missing:
        return missing
    fig, m, s, n = found
    b = fig.get("b", "sigma_Z" + suffix)
    dof = len(b[0]) - 2 if b is not None else None
    # a zero intercept means small against the smallest sigma measured
    effect = float(np.nanmin(b[1])) if b is not None else None
    shown = None
    factor = data.run_error("Z:sigma" + suffix)[0]
    if factor != 1.0 and b is not None and np.all(np.isfinite(b[2])) and np.all(b[2] > 0):
        # the same weighted line, one-run sigmas with a realization's error
        sem = np.where(b[3] == 1, b[2] * factor, b[2])
        coef, cov, _ = _weighted_polyfit(b[0], b[1], sem, 1)
        m, s = float(coef[0]), float(math.sqrt(cov[0, 0]))
        shown = f"{fmt(m, s)} ({_run_error_text(factor)})"
    return [Measure(m, s, dof if dof and dof >= 1 else None, effect=effect, shown=shown)]


def _steady(data):
    """(x, mean, sem, n, index of the largest) of Fig. 4's steady states, None when fewer
    than three."""
    fig = data.figure("fig4")
    steady = None if fig is None else fig.get("a", "steady")
    if steady is None or len(steady[0]) < 3:
        return None
    return (*steady, int(np.nanargmax(steady[1])))


def bell_maximum(data, claim):
    """Vertex of a weighted parabola through the largest steady state and its neighbours."""
    steady = _steady(data)
    if steady is None:
        return _missing("fewer than three steady states")
    x, y, s, n, i = steady
    lo, hi = max(0, i - 2), min(len(x), i + 3)
    if hi - lo < 3:
        lo, hi = max(0, hi - 3), max(hi, 3)
    xs, ys, ss = x[lo:hi], y[lo:hi], s[lo:hi]
    if len(xs) < 4:
        # three points always fit a parabola exactly: its vertex then only restates which
        # point is largest, wherever the true maximum lies between the neighbours
        return [Measure(x[i], undecided=f"{len(x)} steady states: a parabola through three "
                                        "points is not tested by any",
                        shown=f"largest at sqrt(eps) = {x[i]:g}")]
    if not np.all(np.isfinite(ss)) or np.any(ss <= 0):
        return [Measure(x[i], undecided="one realization: the steady states have no error bars",
                        shown=f"largest at sqrt(eps) = {x[i]:g}")]
    (a0, b, c), cov, _ = _weighted_polyfit(xs, ys, ss, 2)
    if not c < 0:
        return [Measure(x[i], undecided="the points around the largest are not concave",
                        shown=f"largest at sqrt(eps) = {x[i]:g}")]
    vertex = -b / (2 * c)
    grad = np.array([0.0, -1 / (2 * c), b / (2 * c**2)])
    err = float(math.sqrt(grad @ cov @ grad))
    return [Measure(float(vertex), err, len(xs) - 3,
                    shown=f"{fmt(vertex, err)} (parabola through {len(xs)} points)")]


def _side_slope(x, y, s, i, side, what):
    """Weighted straight line through the points of a bell below (``side`` "below") or above
    its largest point i, largest included."""
    pick = slice(0, i + 1) if side == "below" else slice(i, len(x))
    if len(x[pick]) < 3:
        return Measure(undecided=f"fewer than three {what} {side} the largest (at sqrt(eps) = "
                                 f"{x[i]:g})", label=f"{side} the largest")
    slope, err, dof = _weighted_line(x[pick], y[pick], s[pick])
    if not np.isfinite(slope):
        return Measure(undecided=f"no error bars on the {what}", label=f"{side} the largest")
    return Measure(slope, err, dof, shown=f"slope {fmt(slope, err)}", label=f"{side} the largest",
                   sign=1 if side == "below" else -1)


def bell_side_slope(data, claim):
    steady = _steady(data)
    if steady is None:
        return _missing("fewer than three steady states")
    x, y, s, n, i = steady
    m = _side_slope(x, y, s, i, claim.params.get("side"), "steady states")
    m.label = ""
    return [m]


def alpha_bell(data, claim):
    """Both sides of alpha against sqrt(eps) (Fig. 6 bottom): rising below its largest value,
    falling above it, as the steady states' bell; the weaker side is the measure (a bell needs
    both)."""
    fig = data.figure("fig6")
    bell = None if fig is None else fig.get("b", "bell:alpha")
    if bell is None or len(bell[0]) < 3:
        return _missing("alpha of fewer than three runs of the bell")
    x, y, s, n = bell
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
    if _steady(data) is None:
        return None
    top = float(bell_maximum(data, None)[0].value)
    pick = x >= top
    if pick.sum() < 3:
        return Measure(undecided=f"fewer than three alphas above the steady states' maximum "
                                 f"(sqrt(eps) = {top:.3g})", label=ALPHA_ABOVE_STEADY)
    slope, err, dof = _weighted_line(x[pick], y[pick], s[pick])
    if not np.isfinite(slope):
        return Measure(undecided="no error bars on the alphas", label=ALPHA_ABOVE_STEADY)
    return Measure(-slope, err, dof, label=ALPHA_ABOVE_STEADY,
                   shown=f"slope {fmt(slope, err)} through the {int(pick.sum())} alphas at "
                         f"sqrt(eps) >= {top:.3g} (Fig. 4's maximum)")


def _paired_levels(a, b):
    """a - b at the sqrt(eps) common to the branch curves a and b ((x, mean, sem, n) each)."""
    return np.array([a[1][i] - b[1][k] for i, k in _common_x(a, b)])


def alpha_ramp_hysteresis(data, claim):
    """alpha on the decreasing branch of the ramp minus on the first increase, at their
    common sqrt(eps) (Fig. 6 bottom panel, open symbols). One profile per level, whose
    straight line's own error is too small (its bins share spheres): the error is the scatter
    of the k level differences (t with k - 1 dof), which also holds any trend of the
    difference with sqrt(eps). The effect a hysteresis would have is alpha's variation along
    the first increase (<Phi^c>'s gap is as large as its own variation there); the same
    ratio of <Phi^c> (Fig. 4) is shown beside it."""
    fig = data.figure("fig6")
    up = None if fig is None else fig.get("b", "ramp:up1")
    down = None if fig is None else fig.get("b", "ramp:down")
    if up is None or down is None:
        return _missing("no ramp profiles on branches 'up1' and 'down'")
    diffs = _paired_levels(down, up)
    if len(diffs) < 3:
        return [Measure(undecided=f"{len(diffs)} sqrt(eps) common to the first increase and "
                                  "the decrease; the scatter needs three")]
    value = float(np.mean(diffs))
    err = float(np.std(diffs, ddof=1) / math.sqrt(len(diffs)))
    variation = float(np.ptp(up[1]))
    shown = (f"{fmt(value, err)} (decrease minus first increase, mean of {len(diffs)} common "
             f"sqrt(eps); error from their scatter): {abs(value) / variation:.0%} of alpha's "
             f"variation along the first increase ({fmt(variation)})")
    phi_up, phi_down = _ramp(data, "up1"), _ramp(data, "down")
    if phi_up is not None and phi_down is not None:
        gap = _paired_levels(phi_down, phi_up)
        if len(gap) and np.ptp(phi_up[1]) > 0:
            shown += (f"; <Phi^c>: {abs(float(np.mean(gap))) / float(np.ptp(phi_up[1])):.0%} "
                      "of its own")
    return [Measure(value, err, len(diffs) - 1, effect=variation, shown=shown)]


def _ramp(data, name):
    fig = data.figure("fig4")
    return None if fig is None else fig.get("a", name)


def hysteresis_gap(data):
    """Mean of the decreasing branch minus the first increase: the effect the "nearly the
    same" claims of the ramp are measured against."""
    down, up = _ramp(data, "down"), _ramp(data, "up1")
    if down is None or up is None:
        return None
    d = _mean_difference(down, up)
    return None if d is None else d[0]


def _branch_difference(data, a, b, effect=None, statistic=None):
    """Branch ``a`` minus branch ``b`` of Fig. 4's ramp beyond (sqrt eps)*, mean over their
    common sqrt(eps). With several seeds of the ramp and their own values of that difference
    (Fig. 4 params ``ramp:<statistic>:seeds``) the error of the mean is judged with the
    campaign's groups of realizations (:func:`_seed_mean`)."""
    ca, cb = _ramp(data, a), _ramp(data, b)
    if ca is None or cb is None:
        return _missing(f"no ramp branches {a!r} and {b!r}")
    d = _mean_difference(ca, cb)
    if d is None:
        return [Measure(undecided=f"the branches {a!r} and {b!r} share no sqrt(eps)")]
    mean, err, dof, k = d
    how = ""
    if statistic is not None and dof is not None and dof >= 1:
        fig = data.figure("fig4")
        if fig.get("params", f"ramp:{statistic}:seeds") is not None:
            _, err, dof, how = _seed_mean(data, fig, f"ramp:{statistic}", "phi_c")
    if not np.isfinite(err):
        return [Measure(mean, undecided="one realization: the branches have no error bars")]
    return [Measure(mean, err, dof, effect=effect,
                    shown=f"{fmt(mean, err)} (mean of {k} common sqrt(eps)"
                          + (f"; {how})" if how else ")"))]


def ramp_up_minus_steady(data, claim):
    """The ramp's first increase minus the steady squares, mean over their common sqrt(eps).
    With several seeds of the ramp and each seed's mean of the first increase there (Fig. 4
    params ``ramp:up1_at_steady:seeds``), the error has two independent parts: the seeds'
    mean, judged with the campaign's groups of realizations (:func:`_seed_mean`'s pooling),
    and the squares' own errors (other runs, one per sqrt(eps), shared by every seed),
    combined with the Welch-Satterthwaite dof. Otherwise the curves' errors
    (:func:`_branch_difference`)."""
    effect = hysteresis_gap(data)
    fig = data.figure("fig4")
    up, steady = _ramp(data, "up1"), _ramp(data, "steady")
    seeds = None if fig is None else fig.get("params", "ramp:up1_at_steady:seeds")
    pairs = [] if up is None or steady is None else _common_x(up, steady)
    if seeds is None or len(seeds[1]) < 2 or not pairs:
        return _branch_difference(data, "up1", "steady", effect)
    values, errors = seeds[1], seeds[2]
    k = len(pairs)
    squares = np.array([steady[1][j] for _, j in pairs])
    square_sems = np.array([steady[2][j] for _, j in pairs])
    square_dofs = [_steady_dof(int(steady[3][j]), steady[2][j]) for _, j in pairs]
    if not np.all(np.isfinite(square_sems)) or None in square_dofs:
        return _branch_difference(data, "up1", "steady", effect)
    seed_err, seed_dof, how, _ = _seeds_error(data, values, errors, "phi_c")
    how = how or f"{len(values)} seeds: the spread of their own values"
    value = float(np.mean(values) - np.mean(squares))
    square_parts = square_sems ** 2 / k ** 2
    err = math.sqrt(seed_err ** 2 + float(np.sum(square_parts)))
    dof = welch_dof(np.r_[seed_err ** 2, square_parts], [seed_dof, *square_dofs])
    return [Measure(value, err, dof, effect=effect,
                    shown=f"{fmt(value, err)} (mean of {k} common sqrt(eps); {how}; the "
                          f"squares' own errors added, {dof} dof)")]


def ramp_down_minus_up(data, claim):
    return _branch_difference(data, "down", "up1", statistic="down_minus_up1")


def ramp_up2_minus_down(data, claim):
    return _branch_difference(data, "up2", "down", hysteresis_gap(data),
                              statistic="up2_minus_down")


def _seed_mean(data, fig, series, quantity, bc="pbc", groups=()):
    """(value, error, dof, text) of the params row ``series`` of ``fig``: with two seeds or
    more and their own values (``<series>:seeds``: Fig. 4's ramp statistics, Fig. 8's final
    zones, Fig. 6's final alpha) the error of their mean judged with the campaign's groups
    of realizations of ``quantity``
    (ReportData.seed_mean_error); otherwise the row's own error (the sem over seeds, or
    one seed's batch-means error) with :func:`_steady_dof`. ``text``: how the error was
    obtained ("" for the row's own). ``groups``: the names the seeds have as a group of
    realizations (ReportData.seed_mean_error). Seeds judged alone (no groups, or a spread
    unlike theirs) take at least the sem of their own values with n - 1 dof: a row that
    combines the levels' sems over seeds as independent understates the spread of seeds
    that differ at every level alike."""
    m, s, n = fig.param(series)
    seeds = fig.get("params", f"{series}:seeds")
    if n >= 2 and seeds is not None and len(seeds[1]) >= 2:
        err, dof, text, pooled = _seeds_error(data, seeds[1], seeds[2], quantity, bc, groups)
        return m, err if pooled else max(s, err), dof, text
    return m, s, _steady_dof(n, s), ""


def _seeds_error(data, values, errors, quantity, bc="pbc", groups=()):
    """(error, dof, text, pooled) of the mean of a few seeds ``values`` of ``quantity``, each
    with its own error ``errors``: pooled with the campaign's groups of realizations
    (ReportData.seed_mean_error: their own errors times the pooled factor, the pooled dof),
    or, judged alone (no groups, or a spread unlike theirs), the sem of their own values
    with n - 1 dof. ``text`` says how ("" for seeds alone in a campaign without groups)."""
    found = data.seed_mean_error(quantity, values, errors, bc, groups)
    if found is not None:
        err, dof, factor = found
        return err, dof, (f"{len(values)} seeds: their own errors x {factor:.1f}, pooled "
                          f"with the groups of realizations ({dof} dof)"), True
    values = np.asarray(values, dtype=float)
    sem = float(np.std(values, ddof=1) / math.sqrt(len(values)))
    text = ""
    if data._pooled_calibration(quantity, bc) is not None:
        listed = ", ".join(fmt(v) for v in values)
        text = (f"{len(values)} seeds ({listed}): the spread of their own values, which "
                "differs from the groups of realizations")
    return sem, len(values) - 1, text, False


def low_ramp_frozen(data, claim):
    """The ramp that stayed below (sqrt eps)*: its decreasing branch minus its top level
    (Fig. 4 params ``low:down_change``), against the same change on the ramp that went beyond
    it (``ramp:down_change``), the effect "nearly frozen" denies. With several seeds the error
    of their mean is judged with the campaign's groups of realizations (:func:`_seed_mean`)."""
    found, missing = _figure_param(data, "fig4", "low:down_change",
                                   "no ramp that stays below (sqrt eps)*")
    if missing:
        return missing
    fig = found[0]
    m, s, dof, how = _seed_mean(data, fig, "low:down_change", "phi_c")
    effect = fig.param("ramp:down_change")[0]
    return [Measure(m, s, dof, effect=effect if np.isfinite(effect) else None,
                    shown=f"{fmt(m, s)} (decrease minus top level; the ramp beyond (sqrt eps)* "
                          f"changes by {fmt(effect)}" + (f"; {how})" if how else ")"))]


#: The paper's "(sqrt eps)* ~ 0.15": a separation located within two of its ramp steps
#: (dsqrt = 0.025) of 0.15 agrees; a bracket of turning points wider than that cannot tell
#: 0.15 from its neighbours.
CRITICAL_BRACKET_HALF_WIDTH = 0.05


def _ramp_turning_behaviour(data, fig, tag, effect):
    """(top, behaviour, text) of the ramp ``tag`` of Fig. 4: behaviour ``compacts`` when its
    decreasing branch rose above its top level beyond t sem (the reversible case), ``frozen``
    when it stayed within t sem of it and t sem is below ``effect`` (the change of the ramps
    that compact), ``decompacts`` when it fell below beyond t sem, None otherwise. The error
    of a mean of several seeds: :func:`_seed_mean`."""
    top = fig.param(f"{tag}:top_sqrt_eps")[0]
    m, s, dof, _ = _seed_mean(data, fig, f"{tag}:down_change", "phi_c")
    if not np.isfinite(m) or dof is None:
        return top, None, f"top {top:g}: no error on its decrease"
    band = t_quantile(dof) * s
    text = f"top {top:g}: decrease minus top level {fmt(m, s)}"
    if m > band:
        return top, "compacts", text
    if m < -band:
        return top, "decompacts", text
    if effect is not None and band < effect:
        return top, "frozen", text
    return top, None, text


def critical_separation(data, claim):
    """Section III.B: (sqrt eps)* ~ 0.15 separates a ramp whose decreasing branch compacts on
    the way down (the reversible branch) from one whose decreasing branch stays frozen at its
    top level. From every ramp of Fig. 4 (params ``<tag>:top_sqrt_eps`` and
    ``<tag>:down_change``): 1 when each ramp turning above 0.15 compacts, each turning below
    is frozen (within t sem, below the change of the ramps that compact) and the highest frozen
    and lowest compacting turning points lie within :data:`CRITICAL_BRACKET_HALF_WIDTH` of
    0.15; 0 when a ramp turning above 0.15 does not compact on the way down or one turning
    below moves beyond t sem; undecided otherwise (a side without a ramp, a behaviour within
    the errors, or a bracket too wide to locate 0.15)."""
    fig = data.figure("fig4")
    tags = [] if fig is None else sorted(s[:-len(":top_sqrt_eps")] for s in fig.series("params")
                                         if s.endswith(":top_sqrt_eps"))
    if not tags:
        return _missing("no ramp with a decreasing branch")
    critical = fig.param("critical_sqrt_eps")[0]
    critical = critical if np.isfinite(critical) else CRITICAL_SQRT_EPS
    changes = [_seed_mean(data, fig, f"{t}:down_change", "phi_c")[:3] for t in tags]
    # the frozen side's bar: the smallest change the compacting ramps surely have
    compacting = [m - t_quantile(dof) * s for m, s, dof in changes
                  if np.isfinite(m) and dof is not None]
    effect = max(compacting) if compacting and max(compacting) > 0 else None
    ramps = sorted((_ramp_turning_behaviour(data, fig, t, effect) for t in tags),
                   key=lambda r: r[0])
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


def ramp_branch_slope(data, claim):
    branch = _ramp(data, claim.params.get("branch", "down"))
    if branch is None:
        return _missing("no ramp")
    slope, err, dof = _weighted_line(*branch[:3])
    if not np.isfinite(slope):
        return [Measure(undecided="fewer than three levels with error bars")]
    return [Measure(slope, err, dof, shown=f"slope {fmt(slope, err)}")]


def _fbc_group_names(eps):
    """The names realization-scatter gives the group of the F.B.C. constant-eps runs at
    ``eps`` (either start: tapmc.paper._runs.constant_eps_run); () without an eps."""
    if not np.isfinite(eps):
        return ()
    from ._runs import PAPER_START_TAG, eps_tag

    return tuple(f"const_{tag}_eps{eps_tag(eps)}" for tag in ("fbc", PAPER_START_TAG))


def final_alpha(data, claim):
    found, missing = _figure_param(data, "fig6", "final:alpha", "no F.B.C. profile runs")
    if missing:
        return missing
    fig, m, s, n = found
    from tapmc.profiles import PROFILE_JACKKNIFE_BLOCKS

    if n >= 2:
        m, s, dof, how = _seed_mean(data, fig, "final:alpha", "packing:alpha", "fbc",
                                    _fbc_group_names(fig.param("eps")[0]))
        return [Measure(m, s, dof, shown=fmt(m, s) + (f" ({how})" if how else ""))]
    within = " (one seed: lateral jackknife of its packing)" if n == 1 and np.isfinite(s) else ""
    return [Measure(m, s, _jackknife_dof(n, s, PROFILE_JACKKNIFE_BLOCKS),
                    shown=fmt(m, s) + within)]


def central_minus_lateral(data, claim):
    fig = data.figure("fig8")
    if fig is None:
        return _missing("no Fig. 8 runs")
    out = []
    for eps in sorted({_eps_of(s) for s in fig.series("params")}):
        tag = f"eps={P.fmt_eps(eps)}"
        cen = fig.param(f"{tag}:final_central")
        lat = fig.param(f"{tag}:final_lateral")
        # the zones of one run move together: their difference per seed (paired) has the
        # error; CSVs written before it was drawn fall back to the zones' errors combined
        diff = fig.param(f"{tag}:final_central_minus_lateral")
        if not np.isfinite(diff[0]):
            diff = (cen[0] - lat[0], math.hypot(cen[1], lat[1]), min(cen[2], lat[2]))
        value, err, n = diff
        factor = data.run_error("zone:central_minus_lateral", "fbc")[0]
        within = (f" ({_run_error_text(factor)})" if n == 1 and np.isfinite(err) else "")
        dof = _steady_dof(n, err)
        if n >= 2 and fig.get("params", f"{tag}:final_central_minus_lateral:seeds") is not None:
            _, err, dof, how = _seed_mean(data, fig, f"{tag}:final_central_minus_lateral",
                                          "zone:central_minus_lateral", "fbc",
                                          _fbc_group_names(eps))
            within = f" ({how})"
        out.append(Measure(value, err, dof, label=f"eps = {eps:g}",
                           shown=f"{fmt(cen[0], cen[1])} vs {fmt(lat[0], lat[1])}; "
                                 f"difference {fmt(value, err)}{within}"))
    return out or _missing("no F.B.C. profile")


def lateral_first_tap(data, claim):
    fig = data.figure("fig8")
    if fig is None:
        return _missing("no Fig. 8 runs")
    paper_start = [(e, s) for e, s in ((_eps_of(s), s) for s in fig.series("a")
                                       if s.startswith("paper:eps="))]
    if not paper_start and data.question("lateral_first_tap"):
        return _lateral_first_tap_measured(data.question("lateral_first_tap"))
    if not paper_start:
        values = []
        for eps, series in _eps_series(fig, "a"):
            t, mean, sem, n = fig.get("a", series)
            if np.any(t == 1):
                values.append(f"{fmt(mean[t == 1][0], sem[t == 1][0])} at eps = {eps:g}")
        seen = "; with the start deposited between walls: " + ", ".join(values) if values else ""
        return [Measure(undecided="no F.B.C. run from the paper's start" + seen)]
    out = []
    for eps, series in sorted(paper_start):
        t, mean, sem, n = fig.get("a", series)
        if not np.any(t == 1):
            continue
        k = int(np.argmax(t == 1))
        out.append(Measure(mean[k], sem[k], _dof(n[k]), label=f"eps = {eps:g}"))
    return out or _missing("no tap 1 in the paper-start curves")


def _lateral_first_tap_measured(rows):
    """delta Phi_lateral at t = 1 per eps over the seeds of bench/paper_questions.py
    lateral-first-tap (the paper's F.B.C. start, taps from t = 0)."""
    per = {}
    for r in rows:
        per.setdefault(float(r["eps"]), {}).setdefault(int(r["seed"]), {})[int(r["t"])] = \
            float(r["lateral"])
    out = []
    for eps, seeds in sorted(per.items()):
        jumps = np.array([t[1] - t[0] for t in seeds.values() if 0 in t and 1 in t])
        if len(jumps) == 0:
            continue
        sem = float(jumps.std(ddof=1) / math.sqrt(len(jumps))) if len(jumps) > 1 else math.nan
        out.append(Measure(float(jumps.mean()), sem, _dof(len(jumps)), label=f"eps = {eps:g}",
                           shown=f"{fmt(float(jumps.mean()), sem)} (the paper's start, "
                                 f"{len(jumps)} seeds: bench/paper_questions.py "
                                 "lateral-first-tap)"))
    return out or _missing("no tap 1 from the paper's start")


def _pointwise_zero(x, diff, err, n, what, effect):
    """The largest standardized difference over the points, tested against the Bonferroni
    corrected t quantile (so that many points do not make a disagreement by chance)."""
    ok = np.isfinite(diff) & np.isfinite(err) & (err > 0)
    if not np.any(ok):
        k = int(np.nanargmax(np.abs(diff))) if np.any(np.isfinite(diff)) else 0
        return [Measure(float(diff[k]) if len(diff) else math.nan,
                        undecided="one realization: the curves have no error bars",
                        shown=f"max |{what}| = {fmt(np.nanmax(np.abs(diff)))}")]
    idx = np.flatnonzero(ok)
    k = idx[int(np.argmax(np.abs(diff[idx]) / err[idx]))]
    dof = _dof(n[k])
    if dof is None:
        return [Measure(float(diff[k]), undecided="one realization")]
    quantile = bonferroni_t_quantile(dof, len(idx))
    return [Measure(float(diff[k]), float(err[k]), dof, quantile=quantile, effect=effect,
                    shown=f"{fmt(diff[k], err[k])} at sigma = {x[k]:.3g} (largest of "
                          f"{len(idx)} standardized differences)")]


def _py_change(fig, sigma):
    """Largest change over sigma of the Percus-Yevick P0 (eqs. 8-9) between the initial and
    the tapped packing fractions: the effect a P0 claim is measured against (None when the
    packing fractions are not in the data)."""
    from tapmc.pores import percus_yevick_p0

    phi_i, phi_f = fig.param("phi_initial")[0], fig.param("phi_final")[0]
    if not (np.isfinite(phi_i) and np.isfinite(phi_f)):
        return None
    return float(np.max(np.abs(percus_yevick_p0(sigma, phi_f) -
                               percus_yevick_p0(sigma, phi_i))))


def _p0_configurations(data, other, what, more_than=1):
    """The comparison of :func:`_p0_difference` over the configurations of
    bench/paper_questions.py p0-configs (depositions at t = 0, dumps of the continued Fig. 9
    run), None when they are not there or are not more than ``more_than`` of each kind."""
    from tapmc.pores import percus_yevick_p0

    rows = [r for r in data.question("p0_configs") if r["sigma"] != "phi"]
    phi = [r for r in data.question("p0_configs") if r["sigma"] == "phi"]
    if len(rows) < 3 or not phi:
        return None
    col = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    if min(col["initial_n"].min(), col["tapped_n"].min()) <= more_than:
        return None
    phi_i, phi_t = float(phi[0]["initial"]), float(phi[0]["tapped"])
    x = col["sigma"]
    effect = float(np.max(np.abs(percus_yevick_p0(x, phi_t) - percus_yevick_p0(x, phi_i))))
    if other == "initial":
        diff, err = col["initial"] - col["tapped"], np.hypot(col["initial_sem"], col["tapped_sem"])
        n = np.minimum(col["initial_n"], col["tapped_n"])
    else:
        diff = np.asarray(percus_yevick_p0(x, phi_t), float) - col["tapped"]
        err, n = col["tapped_sem"], col["tapped_n"]
    out = _pointwise_zero(x, diff, err, n, what, effect)
    for m in out:
        m.shown = (m.shown or m.text()) + (
            f" (P0 over {int(col['initial_n'].min())} depositions and "
            f"{int(col['tapped_n'].min())} configurations of the tapped packing: "
            "bench/paper_questions.py p0-configs)")
    return out


def _p0_difference(data, other, what):
    """P0 of the tapped packing against the curve ``other`` of Fig. 9 (the initial packing's,
    with its sem, or Percus-Yevick's, exact), sigma by sigma (:func:`_pointwise_zero`). Curves
    of fewer realizations than ``p0-configs`` has configurations (one run per point, the
    paper's protocol, or a campaign under way with two seeds, whose sem over two is itself
    hardly known) are compared over those configurations instead, when there."""
    fig = data.figure("fig9")
    if fig is None:
        return _missing("no Fig. 9 runs")
    final, ref = fig.get("a", "final"), fig.get("a", other)
    if final is None or ref is None:
        return _missing("no P0 curves")
    measured = _p0_configurations(data, other, what, more_than=int(np.nanmax(final[3])))
    if measured is not None:
        return measured
    x = final[0]
    ref_err = np.nan_to_num(np.interp(x, ref[0], ref[2]))  # Percus-Yevick: exact
    n = final[3] if other == "percus_yevick" else np.minimum(final[3], ref[3].min())
    return _pointwise_zero(x, np.interp(x, ref[0], ref[1]) - final[1],
                           np.hypot(ref_err, final[2]), n, what, _py_change(fig, x))


def p0_initial_minus_final(data, claim):
    return _p0_difference(data, "initial", "P0(initial) - P0(tapped)")


def p0_final_minus_py(data, claim):
    return _p0_difference(data, "percus_yevick", "Percus-Yevick - P0(tapped)")


def xi_min(data, claim):
    fig = data.figure("fig10")
    if fig is None:
        return _missing("no pore dumps")
    d = fig.get("params", "xi_min")
    if d is None:
        return _missing("no xi_min")
    i = int(np.argmin(d[1]))
    return [Measure(float(d[1][i]), float(d[2][i]), _dof(d[3][i]),
                    shown=fmt(d[1][i], d[2][i], digits=4))]


def _jackknife_dof(n, err, blocks_per_side):
    """dof of a value of one packing or several: seeds - 1, or for one seed with the error of
    a lateral jackknife over blocks_per_side^2 blocks, that number minus one."""
    n = int(np.nanmin(np.atleast_1d(n))) if np.size(n) else 0
    if n >= 2:
        return n - 1
    return blocks_per_side ** 2 - 1 if n == 1 and np.all(np.isfinite(err)) else None


def _pore_dof(n, err):
    """dof of a Fig. 10 value (tapmc.pores.PoreOutput.jackknife for one seed)."""
    from tapmc.pores import JACKKNIFE_BLOCKS

    return _jackknife_dof(n, err, JACKKNIFE_BLOCKS)


def nu_ramp_hysteresis(data, claim):
    """Section IV.B: nu has the reversible-irreversible behaviour of <Phi^c> (section III.B).
    From nu at the level ends of the ramp beyond (sqrt eps)* (bench/paper_questions.py
    ramp-pores: one packing per level, the spatial jackknife's error), the two signs that
    make <Phi^c>'s reversible branch, with nu's sign reversed (more pore volume, less
    packing): the decreasing branch lies below the first increase (mean of the differences at
    their common sqrt(eps), the levels' errors combined), and on it nu rises with sqrt(eps)
    (weighted straight line)."""
    # the ramp beyond (sqrt eps)* (runs ramp_<bc>_s<seed>; ramplow_ and rampnear_ are others)
    rows = [r for r in data.question("ramp_pores") if r["run"].startswith("ramp_")]
    if not rows:
        return _missing("no nu at the level ends of the ramp beyond (sqrt eps)* "
                        "(bench/paper_questions.py ramp-pores)")
    # one packing per level: its jackknife times the packings' factor where they reject it
    factor = data.run_error("packing:nu")[0]
    branches = {}
    for index, name in enumerate(RAMP_BRANCHES):   # in.ramp's branch column
        picked = sorted((float(r["sqrt_eps"]), float(r["nu"]), float(r["nu_sem"]) * factor)
                        for r in rows if int(r["branch"]) == index)
        if picked:
            x, y, e = map(np.array, zip(*picked))
            branches[name] = (x, y, e, np.ones(len(x), int))
    dof = _pore_dof(1, 0.0)
    out = []
    up, down = branches.get("up1"), branches.get("down")
    pairs = [] if up is None or down is None else _common_x(down, up)
    label = "decrease minus first increase"
    if pairs:
        diffs = _paired_levels(down, up)
        err = math.sqrt(sum(down[2][i] ** 2 + up[2][k] ** 2 for i, k in pairs)) / len(pairs)
        value = float(np.mean(diffs))
        out.append(Measure(value, err, dof, label=label, sign=-1, shown=(
            f"{fmt(value, err)} (mean of {len(pairs)} common sqrt(eps); one packing per level, "
            "lateral jackknife)")))
    else:
        out.append(Measure(label=label, undecided="no level of the first increase at a "
                                                  "sqrt(eps) of the decrease"))
    label = "slope on the decrease"
    if down is not None:
        slope, err, line_dof = _weighted_line(*down[:3])
        if np.isfinite(slope):
            out.append(Measure(slope, err, line_dof, label=label, sign=1,
                               shown=f"slope {fmt(slope, err)} over {len(down[0])} levels"))
            return out
    out.append(Measure(label=label, undecided="fewer than three levels of the decrease"))
    return out


def _pore_curves(data):
    fig = data.figure("fig10")
    if fig is None:
        return None
    curves = sorted((float(s.split("=")[1]), fig.get("a", s)) for s in fig.series("a")
                    if s.startswith("t="))
    return curves or None


def _band_integral(x, y, s, lo, hi):
    """Integral of a histogram curve over lo < x <= hi (bin width from the x spacing) and its
    error (bins independent)."""
    width = np.gradient(x) if len(x) > 1 else np.ones_like(x)
    pick = (x > lo) & (x <= hi)
    value = float(np.sum(y[pick] * width[pick]))
    err = float(math.sqrt(np.sum((s[pick] * width[pick]) ** 2)))
    return value, err


def pore_share_change(data, claim):
    """Change from t = 0 to the last dump of the integral of xi^3 P(xi) over the small pores
    (xi_T, xi_O] or the large ones (> xi_O)."""
    curves = _pore_curves(data)
    if curves is None:
        return _missing("no pore dumps")
    (t0, first), (t1, last) = curves[0], curves[-1]
    lo, hi = (P.XI_T, P.XI_O) if claim.params.get("range") == "small" else (P.XI_O, math.inf)
    a, ea = _band_integral(*first[:3], lo, hi)
    b, eb = _band_integral(*last[:3], lo, hi)
    n = min(first[3].min(), last[3].min())
    shown = f"{fmt(a, ea)} (t = {t0:g}) -> {fmt(b, eb)} (t = {t1:g})"
    dof = _pore_dof(n, [ea, eb])
    if dof is None:
        return [Measure(b - a, shown=shown, undecided="one realization: no error bars")]
    # invariance of the small pores means small against the change of the large ones
    la, _ = _band_integral(*first[:3], P.XI_O, math.inf)
    lb, _ = _band_integral(*last[:3], P.XI_O, math.inf)
    return [Measure(b - a, math.hypot(ea, eb), dof, shown=shown, effect=abs(lb - la))]


def _quadratic_law(x, y, s):
    """Weighted fit of c (xi - xi_T)^2 to the bins of (xi_T, xi_O] with error bars: (pick,
    basis, c), None when fewer than three such bins."""
    pick = (x > P.XI_T) & (x <= P.XI_O) & np.isfinite(s) & (s > 0)
    if pick.sum() < 3:
        return None
    basis = (x[pick] - P.XI_T) ** 2
    w = 1 / s[pick] ** 2
    return pick, basis, float(np.sum(w * basis * y[pick]) / np.sum(w * basis**2))


def pore_quadratic_fit(data, claim):
    """Chi-square of xi^3 P(xi) = c (xi - xi_T)^2 over (xi_T, xi_O] at the last dump."""
    curves = _pore_curves(data)
    if curves is None:
        return _missing("no pore dumps")
    t, (x, y, s, n) = curves[-1]
    law = _quadratic_law(x, y, s)
    if law is None:
        return [Measure(undecided="fewer than three histogram bins with error bars between "
                                  "xi_T and xi_O")]
    pick, basis, c = law
    dof = int(pick.sum()) - 1
    chi = float(np.sum((y[pick] - c * basis) ** 2 / s[pick] ** 2)) / dof
    return [Measure(chi, dof=dof, shown=f"reduced chi2 {fmt(chi)} ({dof} dof, t = {t:g})")]


def pore_law_deviation(fig10):
    """How far the fitted c (xi - xi_T)^2 departs from xi^3 P(xi) at the last dump, relative to
    the histogram's largest value in (xi_T, xi_O] (the scale of the figure; bins near xi_T,
    where the curve starts from zero, would make relative deviations meaningless): dict t,
    bins, rms, max, at (xi of the largest), error (median bin error on the same scale); None
    without bins with error bars."""
    curves = None if fig10 is None else _pore_curves(ReportData({}, {"fig10": fig10}))
    if not curves:
        return None
    t, (x, y, s, n) = curves[-1]
    law = _quadratic_law(x, y, s)
    if law is None:
        return None
    pick, basis, c = law
    scale = float(np.max(y[pick]))
    rel = (y[pick] - c * basis) / scale
    k = int(np.argmax(np.abs(rel)))
    return {"t": t, "bins": int(pick.sum()), "rms": float(np.sqrt(np.mean(rel**2))),
            "max": float(np.abs(rel[k])), "at": float(x[pick][k]),
            "error": float(np.median(s[pick]) / scale)}


def _pore_param(data, name):
    fig = data.figure("fig10")
    return None if fig is None else fig.get("params", name)


def nu_tail_over_nu(data, claim):
    nu, tail = _pore_param(data, "nu"), _pore_param(data, "nu_tail")
    if nu is None or tail is None:
        return _missing("no nu_tail")
    m, s = tail[1][-1] / nu[1][-1], 0.0
    ratio_err = abs(m) * math.hypot(tail[2][-1] / tail[1][-1], nu[2][-1] / nu[1][-1])
    s = ratio_err if np.isfinite(ratio_err) else math.nan
    return [Measure(float(m), float(s), _pore_dof(min(nu[3][-1], tail[3][-1]), s),
                    label=f"t = {nu[0][-1]:g}")]


def nu_change(data, claim):
    nu = _pore_param(data, "nu")
    if nu is None:
        return _missing("no nu")
    x, m, s, n = nu
    err = math.hypot(s[-1], s[0])
    return [Measure(m[-1] - m[0], err, _pore_dof(min(n[0], n[-1]), err),
                    shown=f"{fmt(m[0], s[0], digits=4)} -> {fmt(m[-1], s[-1], digits=4)}")]


def dmax_intermediate(data, claim):
    """d_max = R/5 against R/10 and R/2 on the front (same eta and stop rule, so about the same
    sweeps per tap): steady <Phi^c> of R/5 minus that of the other d_max, from their paired
    biases against the front's reference (error: both standard errors in quadrature, which
    over-states it, the two sharing the reference). Positive: the other d_max leaves the packing
    looser at the same cost, i.e. redeposits more slowly."""
    from .front import DEFAULT

    measures = []
    # per N and eps of the front (the settings of one N and eps share their seeds)
    for N, eps in sorted({(r["N"], r["eps"]) for r in data.front}):
        at = {r["setting"]: r for r in data.front if r["N"] == N and r["eps"] == eps}
        base = at.get(DEFAULT)
        for name in ("dmax R/10", "dmax R/2"):
            other = at.get(name)
            if base is None or other is None:
                continue
            d = base["phi_c_steady_bias"] - other["phi_c_steady_bias"]
            se = math.hypot(base["phi_c_steady_bias_se"], other["phi_c_steady_bias_se"])
            n = int(min(base["paired_seeds"], other["paired_seeds"]))
            measures.append(Measure(d, se, _dof(n), label=(
                f"eps = {eps:g}, N = {other['N']:.0f}: <Phi^c>(R/5) - <Phi^c>({name[5:]}), steady, "
                f"at {base['sweeps_per_tap']:.0f} and {other['sweeps_per_tap']:.0f} sweeps per tap"),
                lacks=_size_lacking(N)))
    for rows in data.scans["dmax"]:
        if rows:
            measures += _dmax_scan_measures(rows)
    return measures or [Measure(undecided="neither the front (doc/front.rst) nor a d_max scan "
                                          "(bench/paper_questions.py dmax) has measured d_max")]


def _fraction(frac, unit, limit):
    """frac x unit as the report writes it (pi/4, 5pi/12, R/50, R)."""
    from fractions import Fraction

    f = Fraction(frac).limit_denominator(limit)
    return (unit if f.numerator == 1 else f"{f.numerator}{unit}") + (
        f"/{f.denominator}" if f.denominator != 1 else "")


def _pi_fraction(frac):
    return _fraction(frac, "pi", 48)


def _r_fraction(frac):
    return _fraction(frac, "R", 100)


#: the knob scans of bench/paper_questions.py: CSV column of the value, the paper's value, how
#: a value is written
SCANS = {"theta0": {"column": "theta0_over_pi", "paper": 0.25, "name": _pi_fraction},
         "dmax": {"column": "dmax_over_R", "paper": 0.2, "name": _r_fraction}}


#: tags of scans that test another reading of the model, not the paper's claim (theta0
#: --theta-law solid: P(theta) per unit solid angle; --wide: theta0 beyond the paper's pi/2):
#: measured in doc/measurements.rst, left out of the claims
OTHER_READING_TAGS = ("solid", "wide")


def scan_files(folder, knob):
    """The CSVs of one knob's scans in ``folder``: <knob>.csv, <knob>_<stop>.csv (not those
    tagged with :data:`OTHER_READING_TAGS`)."""
    folder = Path(folder)
    return sorted([p for p in folder.glob(f"{knob}*.csv")
                   if (p.stem == knob or p.stem.startswith(knob + "_")) and
                   not set(p.stem.split("_")[1:]) & set(OTHER_READING_TAGS)])


def read_scan(path):
    """Rows of a CSV of bench/paper_questions.py (a knob scan: theta0 / dmax; the initial
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


def _scan_label(rows, n=None):
    first = rows[0]
    return (f"N = {first['N']}, eps = {float(first['eps']):g}, {scan_settings(rows)}: <Phi^c> "
            f"over taps {int(first['taps']) - 9}-{first['taps']} minus t = 0"
            + (f", {n} seeds" if n else ""))


def theta0_optimum(data, claim):
    """Section II: the paper's theta0 = pi/4 compacts most, a much smaller theta0 decompacts,
    a large one compacts less. From the theta0 scan (same packings, taps at fixed eps): 1 when
    no theta0 compacts more than pi/4 beyond t sem (paired), the smallest theta0 decompacts
    (gain below zero beyond t sem) and the largest compacts less than pi/4 (beyond t sem); 0
    when any of these is contradicted beyond t sem; undecided otherwise."""
    measures = [_theta0_measure(rows) for rows in data.scans["theta0"] if rows]
    return measures or [Measure(undecided="no theta0 scan (bench/paper_questions.py theta0)")]


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
    t = t_quantile(n - 1)
    label = _scan_label(rows, n)
    shown = "; ".join(f"{r['name']}: {fmt(r['gain'], r['gain_sem'], True)}" for r in table)
    better = [r for r in table if not r["is_paper"] and r["vs_paper"] > t * r["vs_paper_sem"]]
    small, large = table[0], table[-1]
    checks = {
        "no theta0 compacts more than pi/4": (not better, bool(better)),
        f"{small['name']} decompacts":
            (small["gain"] < -t * small["gain_sem"], small["gain"] > t * small["gain_sem"]),
        f"{large['name']} compacts less than pi/4":
            (large["vs_paper"] < -t * large["vs_paper_sem"],
             large["vs_paper"] > t * large["vs_paper_sem"]),
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
    """From a d_max scan: the compaction at R/5 minus that at the smallest and at the largest
    d_max, paired over the seeds (sign +: those slow the redeposition down)."""
    table = scan_table(rows, "dmax")
    if len(table) < 3 or not any(r["is_paper"] for r in table):
        return [Measure(label=_scan_label(rows), undecided="fewer than three d_max, or no R/5")]
    n = min(r["n"] for r in table)
    out = []
    for other in (table[0], table[-1]):
        if other["is_paper"]:
            continue
        out.append(Measure(-other["vs_paper"], other["vs_paper_sem"], _dof(n), label=(
            f"d_max scan, {_scan_label(rows, n)}: compaction with R/5 minus with {other['name']}; "
            f"most with {max(table, key=lambda r: r['gain'])['name']}"),
            lacks=_size_lacking(rows[0]["N"])))
    return out


STATISTICS = {f.__name__: f for f in (
    initial_phi, dmax_intermediate, theta0_optimum, tapped_phi, pbc_compaction, phi_b_gain, efficiency_decrease, eq3_fit_quality,
    eq3_triplet_pattern, eq4_fit_quality, b_exponential, ageing_collapse, ageing_eq6,
    log_time_slowing, late_gain_share, spectral_slopes, spectrum_eps_spread,
    sigma_intercept, bell_maximum, bell_side_slope, alpha_bell, alpha_ramp_hysteresis,
    ramp_up_minus_steady,
    ramp_down_minus_up, ramp_up2_minus_down, low_ramp_frozen, ramp_branch_slope,
    critical_separation,
    final_alpha, central_minus_lateral, lateral_first_tap, p0_initial_minus_final,
    p0_final_minus_py, xi_min, pore_share_change, pore_quadratic_fit, nu_tail_over_nu,
    nu_change, nu_ramp_hysteresis)}


# ---------------------------------------------------------------- rules


def _decidable(m):
    return m.dof is not None and m.dof >= 1 and np.isfinite(m.err)


def verdict(claim, m):
    """The verdict of one measure under the claim's rule: a text starting with "agrees",
    "disagrees", "undecided", "holds" or "fails"."""
    if m.undecided:
        return f"undecided ({m.undecided})"
    if not np.isfinite(m.value):
        return "undecided (not measured)"
    rule = claim.rule
    if rule == "check":
        ok = m.value >= claim.target - XI_CHECK_ROUNDING
        return "holds" if ok else "fails"
    if rule == "pattern":
        return "agrees" if m.value == 1 else "disagrees"
    if rule == "fit":
        if m.dof is None or m.dof < 1:
            return "undecided (no degrees of freedom)"
        p = m.p_value if m.p_value is not None else float(stats.chi2.sf(m.value * m.dof, m.dof))
        return ("agrees" if p >= FIT_P_VALUE else "disagrees") + f" (p = {p:.2g})"
    if not _decidable(m):
        return "undecided (no uncertainty: one realization)"
    t = m.quantile if m.quantile is not None else t_quantile(m.dof)
    band = t * m.err
    if rule == "value":
        return "agrees" if abs(m.value - claim.target) <= band + claim.rounding else "disagrees"
    if rule == "range":
        return "agrees" if (m.value + band >= claim.lo and m.value - band <= claim.hi) \
            else "disagrees"
    if rule == "sign":
        signed = (m.sign if m.sign is not None else claim.sign) * m.value
        if signed > band:
            return "agrees"
        if signed < -band:
            return "disagrees"
        return "undecided (within the uncertainty of zero)"
    if rule == "near":
        if m.effect is None or not np.isfinite(m.effect) or m.effect == 0:
            return "undecided (no effect to compare the difference with)"
        tolerance = NEAR_FRACTION * abs(m.effect)
        if abs(m.value) + band <= tolerance:
            return "agrees"
        if abs(m.value) - band > tolerance:
            return "disagrees"
        return (f"undecided (|value| +- t sem {fmt(band)} straddles a tenth of the effect, "
                f"{fmt(tolerance)})")
    if rule == "zero":
        if abs(m.value) > band:
            return "disagrees"
        if m.effect is None or not band < abs(m.effect):
            scale = "" if m.effect is None else f" {fmt(abs(m.effect))}"
            return f"undecided (uncertainty {fmt(band)} not below the effect{scale})"
        return "agrees"
    raise ValueError(f"rule {rule!r}")


def scale_aspects(summary):
    """The parts of the paper's scale (:data:`ASPECTS`) a campaign summary meets."""
    from .scales import SCALES

    met = set()
    sizes = [tuple(s) for s in summary.get("sizes", [])]
    if sizes and all(int(n) == PAPER_SCALE["N"] and float(l) == PAPER_SCALE["L"]
                     for n, l in sizes):
        met.add("size")
    etas = summary.get("eta", [])
    if etas and all(math.isclose(float(e), PAPER_SCALE["eta"]) for e in etas):
        met.add("eta")
    scale = None
    if summary.get("preset") and summary.get("scale") in SCALES:
        scale = SCALES[summary["scale"]]
    fields = summary.get("fields") or {}
    taps = scale.taps if scale is not None else fields.get("taps")
    per_level = scale.ramp_taps_per_level if scale is not None else \
        fields.get("ramp_taps_per_level")
    if taps is not None and int(taps) >= PAPER_SCALE["taps"]:
        met.add("taps")
    if summary.get("ramp_taps_per_level"):   # what the ramps ran with decides, not the preset
        per_level = min(summary["ramp_taps_per_level"])
    if per_level is not None and int(per_level) >= PAPER_SCALE["ramp_taps"]:
        met.add("ramp_taps")
    return met


@dataclass
class Row:
    """One row of the report: the claim, the label of its measure, the measure, the verdict
    and whether the campaign had the scale the claim needs."""

    claim: Claim
    label: str
    measure: Measure
    verdict: str
    missing_scale: tuple

    @property
    def outcome(self):
        """agrees / disagrees / undecided / holds / fails (the verdict's first word)."""
        return self.verdict.split(" ")[0]


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
#: levels of a branch measured at the paper's taps per level before their largest shift
#: stands for the whole branch (one level says nothing of how the shift varies along it)
RAMP_REDUCTION_MIN_LEVELS = 2


def ramp_tag(run):
    """Fig. 4's tag of a ramp run, from its name's prefix (tapmc.paper.fig4.RAMPS); None
    for a run of no ramp."""
    from .fig4 import RAMPS

    return next((tag for tag, prefix, *_ in RAMPS if run.startswith(prefix)), None)


def ramp_reduction_bounds(data, tag="ramp"):
    """branch -> (bound, levels, low, high): per branch of the ramp ``tag`` (Fig. 4's), the
    largest shift of a level's <Phi^c> from the campaign's taps per level to the paper's 4000,
    |shift| + t err, over the levels bench/paper_questions.py ramp-levels measured
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
    fig = data.figure("fig4")
    turn = math.nan if fig is None else fig.param(f"{tag}:top_sqrt_eps")[0]
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
        curve = _ramp(data, claim.params.get("branch", "down"))
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
    """The verdict word of ``claim`` (critical_separation) that holds with every ramp's
    decrease-minus-top change (Fig. 4 params ``<tag>:down_change``) moved anywhere within the
    range its own levels give (branches "down" and "top" of :func:`ramp_reduction_bounds`),
    with the ramps' (turning sqrt(eps), (low, high)); (None, ramps) when a ramp lacks a range or the word
    differs between the ends (every combination is tried of each ramp's ends and, inside its
    range, the shift that brings its change to zero, where its behaviour turns)."""
    import itertools

    fig = data.figures.get("fig4")
    if fig is None:
        return None, []
    tags = sorted(s[:-len(":top_sqrt_eps")] for s in fig.series("params")
                  if s.endswith(":top_sqrt_eps"))
    ranges = []
    for tag in tags:
        b = bounds.get(tag, {})
        if "down" not in b or "top" not in b:
            return None, []
        ranges.append((tag, (b["down"][2] - b["top"][3], b["down"][3] - b["top"][2])))
    tops = [fig.param(f"{tag}:top_sqrt_eps")[0] for tag, _ in ranges]
    changes = [fig.param(f"{tag}:down_change")[0] for tag, _ in ranges]
    candidates = [[lo, hi] + ([-change] if lo < -change < hi else [])
                  for (_, (lo, hi)), change in zip(ranges, changes)]
    words = set()
    for ends in itertools.product(*candidates):
        table = dict(fig.table)
        for (tag, _), shift in zip(ranges, ends):
            d = dict(table[("params", f"{tag}:down_change")])
            d["mean"] = np.asarray(d["mean"], float) + shift
            table[("params", f"{tag}:down_change")] = d
        moved = ReportData(data.summary, dict(data.figures, fig4=FigureData(table)),
                           data.front, data.scans, data.questions)
        words |= {verdict(claim, m).split(" ")[0]
                  for m in STATISTICS[claim.statistic](moved, claim)}
    return (words.pop() if len(words) == 1 else None), [(top, r) for top, (_, r)
                                                         in zip(tops, ranges)]


def _shift_text(shift):
    """A shift range (low, high) as the verdicts write it."""
    lo, hi = shift
    if math.isclose(lo, -hi):
        return f"at most {fmt(hi)}"
    return f"{fmt(lo)} to {fmt(hi)}"


def _robust_to(claim, m, shift, text):
    """Whether the verdict ``text`` of ``m`` stays the same with the value moved anywhere
    within ``shift`` = (low, high): tried at both ends and at the points of the interval
    nearest zero and the claim's target (a zero or value rule turns there, not at the ends)."""
    word = text.split(" ")[0]
    lo, hi = m.value + shift[0], m.value + shift[1]
    turns = [0.0] + ([float(claim.target)] if getattr(claim, "target", None) is not None
                     and np.isfinite(claim.target) else [])
    values = [lo, hi] + [min(max(t, lo), hi) for t in turns]
    return all(verdict(claim, dataclasses.replace(m, value=v)).split(" ")[0] == word
               for v in values)


def _reduced_ramp_verdict(claim, m, text, data, bounds, per_level):
    """(the verdict ``text`` of a ramp claim measured at fewer taps per level than the
    paper's, kept and saying why when the levels' measured shifts (``bounds``: Fig. 4's tag ->
    :func:`ramp_reduction_bounds`) cannot change it, else None; what the shifts could do, for
    the undecided verdict). The critical (sqrt eps)* pattern moves each ramp's change on the
    way down within its own range (:func:`_turning_ramps_shifted`); a measure, its value
    within :func:`ramp_reduction_shift`."""
    word = text.split(" ")[0]
    taps = f"at {per_level or 'fewer'} taps per level"
    if claim.statistic == "critical_separation":
        found, ranges = _turning_ramps_shifted(claim, data, bounds)
        if found != word:
            return None, ""
        moves = "; ".join(f"top {top:g} by {_shift_text(r)}" for top, r in ranges)
        return (f"{word} ({taps}; the paper's 4000 would move the changes on the way down, "
                f"{moves} (ramp-levels: each ramp's decrease and turning level), which leaves "
                "the verdict)"), ""
    shift = ramp_reduction_shift(claim, data, bounds)
    if shift is None:
        return None, ""
    if not _robust_to(claim, m, shift, text):
        return None, f"; the paper's 4000 could move it by {_shift_text(shift)}"
    tag = RAMP_REDUCTION_TAGS.get(claim.statistic, "ramp")
    levels = "; ".join(f"{b}: level{'s' if len(bounds[tag][b][1]) > 1 else ''} "
                       f"{', '.join(map(str, bounds[tag][b][1]))}"
                       for b in RAMP_REDUCTION_BRANCHES[claim.statistic])
    if tag != "ramp":
        levels = f"{tag} ramp, {levels}"
    return (f"{word} ({taps}; the paper's 4000 would move it by {_shift_text(shift)} "
            f"(ramp-levels, {levels}), which leaves the verdict)"), ""


def evaluate(claims, data):
    """The report rows of every claim (one per measure) for ``data`` (:class:`ReportData`).

    A model claim the campaign lacks part of the paper's scale for is undecided, with one
    exception: the ramp at fewer taps per level than the paper's, when ramp-levels measured
    the levels' shift to 4000 taps on every branch the measure reads and the verdict stays
    the same anywhere within the range the shifts give (:func:`_reduced_ramp_verdict`)."""
    met = scale_aspects(data.summary)
    from .fig4 import RAMPS

    bounds = {tag: ramp_reduction_bounds(data, tag) for tag, *_ in RAMPS}
    per_level = ", ".join(map(str, data.summary.get("ramp_taps_per_level") or []))
    rows = []
    for claim in claims:
        missing = tuple(a for a in claim.needs if a not in met)
        if not claim.statistic:
            rows.append(Row(claim, "", Measure(), f"undecided (no statistic: decided by "
                                                  f"{claim.decided_by})", missing))
            continue
        for m in STATISTICS[claim.statistic](data, claim):
            text = verdict(claim, m)
            lacking = missing + tuple(a for a in m.lacks if a not in missing)
            if lacking and not text.startswith("undecided") and claim.kind == "model":
                decided, reach = (_reduced_ramp_verdict(claim, m, text, data, bounds, per_level)
                                  if lacking == ("ramp_taps",) else (None, ""))
                text = decided or (f"undecided (scale: needs the paper's {', '.join(lacking)}; "
                                   f"at this scale it {text.split(' ')[0]}{reach})")
            rows.append(Row(claim, m.label, m, text, lacking))
    return rows


__all__ = ["Claim", "Measure", "ReportData", "FigureData", "Row", "load_register", "evaluate",
           "verdict", "scale_aspects", "STATISTICS", "RULE_NAMES", "REGISTER"]
