# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""What the report measures from (:class:`ReportData`): the figure CSVs (:class:`FigureData`),
with the realizations' calibration (:mod:`.calibration`) applied once where they load, the
campaign summary, the front's rows and the CSVs of the paper's questions."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from tapmc.fluctuations import ErrorCalibration

from .. import _plotting as P
from .. import fig2, fig3, fig4, fig5, fig6, fig7, fig8, fig9, fig10
from .._results import CsvRows, FigureResult
from .._runs import eps_tag
from ..front import read_summary
from .calibration import (CALIBRATION_ALPHA, ONE_RUN_WINDOW_ROWS, RUN_ERROR_LABELS,
                          RUN_ERROR_QUANTITIES, SEEDS_GROUP, ZONE_QUANTITIES, group_bc,
                          ROW_EPS, factor_heterogeneity, measured_factor,
                          realization_calibrations, realization_factors, realization_sharing,
                          realization_trends)
from . import conventions
from .common import steady_dof
from .scan_tables import SCANS, THETA_LAW_SCAN_STEMS, read_scan, scan_files


#: figure name -> its typed result (tapmc.paper.figN), what the report loads its CSV with
FIGURE_RESULTS = {"fig2": fig2.Fig2Result, "fig3": fig3.Fig3Result, "fig4": fig4.Fig4Result,
                  "fig5": fig5.Fig5Result, "fig6": fig6.Fig6Result, "fig7": fig7.Fig7Result,
                  "fig8": fig8.Fig8Result, "fig9": fig9.Fig9Result, "fig10": fig10.Fig10Result}


def load_figure(name, path):
    """Figure ``name``'s CSV ``path``: its typed result (:data:`FIGURE_RESULTS`), or the
    table of a figure without one."""
    result = FIGURE_RESULTS.get(name)
    return FigureData.read(path) if result is None else result.load(path)


class FigureData:
    """One figure's rows by panel and series: ``get(panel, series)`` -> (x, mean, sem, n)
    arrays or None; the view of the statistics not yet reading the typed results."""

    def __init__(self, table):
        self.table = table

    @classmethod
    def read(cls, path):
        return cls(P.read_table(path))

    @classmethod
    def of_result(cls, result):
        """The rows of a typed figure result (those its CSV has)."""
        return cls(result.table_dict())

    def scaled_one_run_errors(self, factor, chosen):
        """A copy whose rows with n = 1 in the series for which ``chosen(panel, series)``
        holds have their sem times ``factor`` (a number, or a function of the row's x)."""
        table = {}
        for (panel, series), d in self.table.items():
            d = dict(d)
            if chosen(panel, series):
                one = np.asarray(d["n"]) == 1
                scale = (np.array([factor(float(x)) for x in d["x"]]) if callable(factor)
                         else factor)
                d["sem"] = np.where(one, np.asarray(d["sem"], float) * scale, d["sem"])
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


def _group_of(calibration, mean, n):
    """The group of a computed ErrorCalibration with ``n`` realizations whose mean is
    ``mean`` (a figure's row over the same runs), or None."""
    for group, (means, _) in calibration.groups.items():
        # realization_scatter.csv prints 6 digits, the figure's CSV 10
        if len(means) == n and math.isclose(float(np.mean(means)), mean, rel_tol=1e-5,
                                            abs_tol=1e-10):
            return group
    return None


def _point_key(name, x, value):
    """The key of a figure's value in ReportData's recorded dof (rounded: the calibrated
    result's numbers are the CSV's)."""
    return name, round(float(x), 12), round(float(value), 9)


#: stems of the CSVs of tapmc-paper question (in the report's ``questions`` folder) that
#: decide claims of one-run campaigns: depositions at t = 0 (initial-packing), P0 over several
#: configurations (p0-configs), the first taps from the paper's F.B.C. start (lateral-first-tap),
#: realizations of the first taps (early-taps), one run's surrogate fits (fit-surrogates), the
#: fits of whole runs over realizations (seed-fits), the ramp's levels continued (ramp-levels)
#: and nu at its level ends (ramp-pores)
QUESTION_CSVS = ("initial_packing", "p0_configs", "lateral_first_tap", "early_taps",
                 "fit_surrogates", "ramp_levels", "ramp_pores", "realization_scatter",
                 "packing_scatter", "seed_fits", "paper_ramp", "alpha_window", "ramp_alpha"
                 ) + THETA_LAW_SCAN_STEMS


#: the question CSVs whose rows are groups of realizations (:meth:`ReportData.scatter_rows`)
SCATTER_CSVS = ("realization_scatter", "packing_scatter")


class ReportData:
    """The inputs of the report: each figure CSV loaded once as its typed result
    (:data:`FIGURE_RESULTS`), read by the statistics with the realizations' calibration
    applied (:meth:`result`; :attr:`figures`, the same rows by panel and series, for the
    statistics that still read those), the
    campaign ``summary`` (tapmc.paper.validation.campaign_summary) and ``front``, the rows of
    the run-time-versus-error front (tapmc.paper.front.read_summary; empty: not measured).
    ``written`` keeps the figure CSVs as the figures wrote them, for the page's measurements
    that print the CSVs' own numbers and for a copy of the data with some of them changed."""

    def __init__(self, summary, figures, front=(), scans=None, questions=None):
        """``scans``: knob (``theta0``, ``dmax``) -> its scans, each the rows of one CSV of
        tapmc-paper question (:data:`SCANS`); ``questions``: the rows of its other CSVs
        that decide claims a campaign of one run per point cannot (:data:`QUESTION_CSVS`), by
        file stem."""
        self.summary = summary
        self.front = list(front)
        self.scans = {knob: list((scans or {}).get(knob, ())) for knob in SCANS}
        self.questions = {stem: list(rows) for stem, rows in (questions or {}).items()}
        self._written_results = {name: fig for name, fig in figures.items()
                                 if isinstance(fig, FigureResult)}
        self.written = {name: FigureData.of_result(fig) if isinstance(fig, FigureResult)
                        else fig for name, fig in figures.items()}
        self._figures = None
        self._results = {}
        self._point_dofs = {}

    @property
    def figures(self):
        """name -> the figure's calibrated data (:meth:`_calibrated`), computed once, when
        the statistics first read them (after the questions' groups of realizations)."""
        if self._figures is None:
            self._calibrate_figures()
        return self._figures

    def _calibrate_figures(self):
        self._figures = {name: self._calibrated(name, fig) for name, fig in self.written.items()}

    def result(self, name):
        """Figure ``name``'s typed result (tapmc.paper.figN's FigNResult) with the
        realizations' calibration applied (:meth:`_calibrated`), built once from the calibrated
        rows; None when the figure is not in the report. A figure given as bare rows
        (:class:`FigureData`: a test's or a question's table) may hold some of its result's
        fields only: the others are empty."""
        if name not in self._results:
            calibrated = self.figures.get(name)
            written = self._written_results.get(name)
            if calibrated is None or name not in FIGURE_RESULTS:
                result = written
            elif written is not None and calibrated is self.written[name]:
                result = written        # nothing calibrated: the result as loaded
            else:
                # rows given in memory (no typed result) may hold some fields only
                result = FIGURE_RESULTS[name].of_rows(CsvRows.of_table(
                    f"{name}.csv", calibrated.table, partial=written is None))
                if name == "fig4":      # the bell's maximum weighs the calibrated squares
                    result = fig4.with_bell_maximum(result)
            self._results[name] = result
        return self._results[name]

    def question(self, stem):
        """The rows of tapmc-paper question's ``<stem>.csv`` ([] when not measured)."""
        return self.questions.get(stem, [])

    @classmethod
    def from_files(cls, summary, files):
        """``files``: name -> (png, csv) as the report collects them; the front from the
        package's front_summary.csv; the knob scans from ``questions/<knob>*.csv`` beside the
        figure CSVs (tapmc-paper question theta0 / dmax), when there."""
        scans, questions = {}, {}
        if files:
            folder = Path(next(iter(files.values()))[1]).parent / "questions"
            scans = {knob: [read_scan(path) for path in scan_files(folder, knob)]
                     for knob in SCANS}
            questions = {stem: read_scan(folder / f"{stem}.csv") for stem in QUESTION_CSVS
                         if (folder / f"{stem}.csv").is_file()}
        return cls(summary, {name: load_figure(name, paths[1]) for name, paths in files.items()},
                   read_summary(), scans, questions)

    def figure(self, name):
        """Figure ``name``'s calibrated data (:attr:`figures`), None when not in the report."""
        return self.figures.get(name)

    def _calibrated(self, name, fig):
        """Figure ``name``'s data ``fig``, the error of each of its one-run rows that is a
        window's own error (:data:`ONE_RUN_WINDOW_ROWS`) times the realizations' factor
        (:meth:`run_error`); Fig. 4's steady squares of several seeds with the groups' error
        (:meth:`_calibrated_steady_squares`)."""
        for quantity, bc, chosen in ONE_RUN_WINDOW_ROWS.get(name, ()):
            factor = self.run_error(quantity, bc)[0]
            trend = self._realization_trends(bc).get(quantity) if name in ROW_EPS else None
            if trend is not None:       # a factor that depends on eps: the row's own
                fig = fig.scaled_one_run_errors(
                    lambda x, eps=ROW_EPS[name], bc=bc, q=quantity:
                    self.run_error(q, bc, eps(x))[0], chosen)
            elif factor != 1.0:
                fig = fig.scaled_one_run_errors(factor, chosen)
        if name == "fig4":
            fig = self._calibrated_steady_squares(fig)
        for quantity, bc, chosen in ONE_RUN_WINDOW_ROWS.get(name, ()):
            fig = self._floored_seed_rows(name, fig, quantity, bc, chosen)
        return fig

    def _floored_seed_rows(self, name, fig, quantity, bc, chosen):
        """Figure ``name``'s rows of several seeds (in the series ``chosen(panel, series)``
        holds for) that are a group of realization_scatter.csv of ``quantity`` (the same
        runs: as many, the same mean) with their sem no smaller than the groups' realization
        error of such a mean (:meth:`realization_floor`), and that error's degrees of
        freedom, the pooled ones, recorded for :meth:`point_dof`: a sem of three seeds has
        2 dof (t = 4.3) and can be small by chance, while the groups measure the spread of
        realizations on many more."""
        pooled = self.pooled_calibration(quantity, bc)
        if pooled is None:
            return fig
        table, changed = dict(fig.table), False
        for (panel, series), d in fig.table.items():
            if not chosen(panel, series):
                continue
            sem = np.array(d["sem"], dtype=float)
            for i, (x, mean, n) in enumerate(zip(d["x"], d["mean"], d["n"])):
                group = _group_of(pooled, float(mean), int(n)) if n >= 2 else None
                if group is None:
                    continue
                floor = self.realization_floor(quantity, pooled.groups[group][1], bc)
                self._point_dofs[_point_key(name, x, mean)] = pooled.dof
                if floor is not None and not floor <= sem[i]:
                    sem[i], changed = floor, True
            table[(panel, series)] = {**d, "sem": sem}
        return FigureData(table) if changed else fig

    def realization_floor(self, quantity, errors, bc="pbc"):
        """The realization error of a mean of a few realizations of ``quantity`` with their
        own errors ``errors``: the groups' measured factor (calibration.measured_factor)
        times sqrt(sum e_i^2) / n; None without groups of ``quantity``. No mean of a few
        seeds has a smaller error than this: their own spread, with n - 1 dof, can be
        small by chance."""
        pooled = self.pooled_calibration(quantity, bc)
        errors = np.asarray(errors, dtype=float)
        if pooled is None or len(errors) == 0 or not np.all(np.isfinite(errors)):
            return None
        return measured_factor(pooled) * float(np.sqrt(np.sum(errors ** 2))) / len(errors)

    def point_dof(self, name, value):
        """Degrees of freedom of figure ``name``'s :class:`Value` ``value`` (of its calibrated
        result): the pooled ones of the groups of realizations when its seeds are one of them
        (:meth:`_floored_seed_rows`), else :func:`.common.steady_dof` (seeds - 1, or one
        run's batch-means dof)."""
        if self._figures is None:
            self._calibrate_figures()      # which records the pooled dof
        found = self._point_dofs.get(_point_key(name, value.x, value.value))
        return found if found is not None else steady_dof(value.n, value.err)

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

    def _realization_trends(self, bc="pbc"):
        """realization_trends of the campaign's groups for runs of ``bc``, computed once."""
        cache = self.__dict__.setdefault("_trends", {})
        if bc not in cache:
            cache[bc] = realization_trends(self.scatter_rows(), bc)
        return cache[bc]

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
        return [r for stem in SCATTER_CSVS for r in self.question(stem)]

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
                f"below {CALIBRATION_ALPHA:g}) are judged by their own spread, never below "
                "the groups' realization error of such a mean, and a ramp's difference of "
                f"{conventions.PAIRED_MIN_LEVELS} common levels or more by the paired "
                "test over its "
                "levels (their scatter, levels - 1 degrees of freedom), not by t with the "
                "seeds' one. A figure's value whose seeds are one of the groups (Fig. 4's "
                "steady squares, Fig. 3's spectral slopes, Fig. 9's steady state, Fig. 6's "
                "alphas) has the larger of their sem and the groups' error of such a mean "
                "(Fig. 3's spectral slopes with the pooled degrees of freedom rather than the "
                "seeds' two). "
                + self._factor_dependence_note())

    def _factor_dependence_note(self):
        """Whether the groups' factors depend on the group (eps) beyond chance."""
        every, _, _ = self._calibrations()
        differ = {q: factor_heterogeneity(c) for q, c in every.items()}
        differ = {q: p for q, p in differ.items() if p < CALIBRATION_ALPHA}
        trends = {**self._realization_trends("fbc"), **self._realization_trends("pbc")}
        text = ("Whether the factor depends on eps is tested over the groups (Bartlett's "
                f"test of their k_g^2, two-sided, at {CALIBRATION_ALPHA:g}): ")
        if not differ:
            return text + "no quantity's groups differ beyond chance, so one factor serves."
        listed = ", ".join(f"{RUN_ERROR_LABELS.get(q, q)} (p = {p:.2g}"
                           + (", a trend in sqrt(eps): each figure row of a known eps takes "
                              "the factor there)" if q in trends else
                              ", without a trend in sqrt(eps) beyond its error: the pooled "
                              "factor serves)") for q, p in differ.items())
        return text + f"the groups differ for {listed}."

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
        pooled = self.pooled_calibration(quantity, bc)
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

    def pooled_calibration(self, quantity, bc):
        """The ErrorCalibration of ``quantity`` that :func:`realization_factors` reads for
        ``bc`` (both boundary conditions' groups unless they differ), or None."""
        every, by_bc, sharing = self._calibrations()
        if quantity not in every:
            return None
        if sharing.get(quantity, 1.0) < CALIBRATION_ALPHA:
            return by_bc[bc].get(quantity)
        return every[quantity]

    def _calibrations(self):
        """(every group's, bc -> its groups', P.B.C.-F.B.C. sharing p-values) of
        :func:`realization_calibrations` of :meth:`scatter_rows`, computed once (they
        depend on the rows alone, not on any convention)."""
        # keyed by the question tables read (a test may give the data new ones)
        key = tuple(id(self.questions.get(stem)) for stem in SCATTER_CSVS)
        cached = self.__dict__.get("_calibration_sets")
        if cached is None or cached[0] != key:
            rows = self.scatter_rows()
            cached = self._calibration_sets = (key, (
                realization_calibrations(rows),
                {bc: realization_calibrations(rows, bc) for bc in ("pbc", "fbc")},
                realization_sharing(rows)))
        return cached[1]

    def recalibrated(self):
        """A copy sharing the loaded inputs, with nothing derived from them yet (the
        calibrated figures and results, the realization factors): what a report evaluated
        with another convention of the calibration reads (:mod:`.sensitivity`)."""
        copy = object.__new__(ReportData)
        kept = ("summary", "front", "scans", "questions", "_written_results", "written",
                "_calibration_sets")
        copy.__dict__.update({k: v for k, v in self.__dict__.items() if k in kept})
        copy._figures, copy._results, copy._point_dofs = None, {}, {}
        return copy

    def run_error(self, quantity, bc="pbc", eps=None):
        """(factor, dof) that turn one run's batch-means error of ``quantity`` ('phi_b',
        'phi_c', 'Z'; '<name>:halves' for a difference of two parts of one run; None: the
        largest factor of the three window means, for a quantity no group measures) into the
        error of a realization of a run of boundary condition ``bc`` ('pbc', 'fbc'): the
        campaign's :func:`realization_factors` where they reject calibrated errors, else
        (1, None) (the one-run error and its own dof). A profile's zone
        (:data:`ZONE_QUANTITIES`) that realization_scatter.csv does not measure takes the
        largest factor, as None does. ``eps``: the run's eps, at which a factor that depends
        on eps (:func:`realization_trends`) is taken (at least 1, as a pooled factor)."""
        trend = None if eps is None else self._realization_trends(bc).get(quantity)
        if trend is not None:
            return max(1.0, trend.factor(eps)), trend.dof
        factors = self._realization_factors(bc)
        if quantity in ZONE_QUANTITIES and quantity not in self._measured():
            quantity = None
        if quantity is None:
            means = [factors[k] for k in RUN_ERROR_QUANTITIES if k in factors]
            return max(means, default=(1.0, None))
        return factors.get(quantity, (1.0, None))
