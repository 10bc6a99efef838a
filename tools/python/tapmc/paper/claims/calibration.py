# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The realizations' calibration of one-run errors: groups of runs that differ only in their
seed (realization_scatter.csv, packing_scatter.csv) give the factor by which realizations
spread beyond one run's batch-means error (tapmc.fluctuations.ErrorCalibration), and the
rows of each figure CSV that take it."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np
from scipy import stats

from tapmc.fluctuations import ErrorCalibration
from tapmc.stats import t_quantile

from .conventions import CALIBRATION_ALPHA


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


#: the name under which a statistic's few seeds join the campaign's groups of realizations
#: (ReportData.seed_mean_error); no run of a campaign is named so
SEEDS_GROUP = "<the statistic's seeds>"


def _final_zone(name):
    """chosen(panel, series) of Fig. 8's final value of zone ``name``."""
    return lambda panel, series: panel == "params" and series.endswith(f":final_{name}")


#: figure -> eps of a row's x, for the figures whose rows of :data:`ONE_RUN_WINDOW_ROWS`
#: are at one eps each (Fig. 3's params at x = eps, Fig. 4's curves at x = sqrt(eps)): where
#: the realization factor depends on eps (:func:`realization_trends`) they take it there
ROW_EPS = {"fig3": lambda x: x, "fig4": lambda x: x * x}


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
    """dict quantity -> (k, dof) from the rows of the questions'
    realization_scatter.csv for runs of boundary condition ``bc``: the factor by which the
    realizations of a group of runs that differ only in their seed spread beyond their
    batch-means errors (tapmc.fluctuations.ErrorCalibration, pooled over the groups), for
    the quantities where it rejects k = 1 at :data:`CALIBRATION_ALPHA`; dof: the pooled
    realizations' dof. The groups of both boundary conditions are pooled unless their
    factors differ (:func:`realization_sharing` below CALIBRATION_ALPHA): then ``bc``'s
    groups alone. A boundary condition without groups takes the other's."""
    return {q: (c.factor, c.dof) for q, c in _pooled_calibrations(rows, bc).items()
            if c.p_value < CALIBRATION_ALPHA and c.factor > 1}


def _pooled_calibrations(rows, bc):
    """dict quantity -> the calibration :func:`realization_factors` uses for ``bc``: the
    groups of both boundary conditions pooled, or ``bc``'s alone where they differ."""
    every = realization_calibrations(rows)
    own = realization_calibrations(rows, bc)
    sharing = realization_sharing(rows)
    return {q: own[q] if sharing.get(q, 1.0) < CALIBRATION_ALPHA else c
            for q, c in every.items()}


def measured_factor(calibration):
    """The factor a computed ErrorCalibration measures, k, where it rejects k = 1 on either
    side at :data:`CALIBRATION_ALPHA` (realizations spreading beyond their own errors, or
    measurably within them: a spectral slope's periodogram errors), else 1: what the error
    of a mean of a few realizations is floored at (:meth:`ReportData.realization_floor`)."""
    upper = calibration.p_value
    if upper < CALIBRATION_ALPHA or 1.0 - upper < CALIBRATION_ALPHA:
        return calibration.factor
    return 1.0


def group_eps(group):
    """eps of a group of realization_scatter.csv named ``<kind>_<bc>_eps<eps>`` (None for
    a group of no single eps, e.g. the initial packings)."""
    found = re.search(r"_eps([0-9.]+[0-9])", group)
    return float(found.group(1)) if found else None


def factor_heterogeneity(calibration):
    """Two-sided p-value that the groups of a computed ErrorCalibration share one factor:
    Bartlett's test of their k_g^2 = s_g^2 / e_g^2, each with n_g - 1 dof (the within-run
    errors' own scatter neglected, as in ErrorCalibration.same_factor_p). Groups of three
    runs give k_g^2 2 dof each: a range of k_g from 1 to 7 can be chance."""
    dofs = np.array([len(calibration.groups[g][0]) - 1 for g in calibration.ratios], float)
    k2 = np.array([calibration.ratios[g] ** 2 for g in calibration.ratios])
    if len(dofs) < 2 or np.any(k2 <= 0):
        return 1.0
    total = dofs.sum()
    pooled = float(np.sum(dofs * k2) / total)
    statistic = total * math.log(pooled) - float(np.sum(dofs * np.log(k2)))
    correction = 1 + (np.sum(1 / dofs) - 1 / total) / (3 * (len(dofs) - 1))
    return float(stats.chi2.sf(statistic / correction, len(dofs) - 1))


@dataclass(frozen=True)
class FactorTrend:
    """The realization factor's trend in eps: ln k^2 = a + b sqrt(eps), a weighted straight
    line through the groups' ln k_g^2 (weights (n_g - 1) / 2, the inverse variance of the
    logarithm of a variance with n_g - 1 dof); ``dof``: the pooled realizations' minus the
    line's second parameter."""

    a: float
    b: float
    b_err: float
    dof: int
    heterogeneity_p: float

    def factor(self, eps):
        """k at ``eps``."""
        return math.exp((self.a + self.b * math.sqrt(eps)) / 2)


def factor_trend(calibration):
    """The :class:`FactorTrend` of a computed ErrorCalibration where its factor measurably
    depends on eps: the groups differ beyond chance (:func:`factor_heterogeneity` below
    :data:`CALIBRATION_ALPHA`) and the line's slope is beyond t times its error, over three
    groups or more of one eps each; None otherwise (one pooled factor serves)."""
    p = factor_heterogeneity(calibration)
    picked = [(group_eps(g), g) for g in calibration.ratios if group_eps(g) is not None]
    if p >= CALIBRATION_ALPHA or len(picked) < 3:
        return None
    x = np.sqrt([e for e, _ in picked])
    y = np.log([calibration.ratios[g] ** 2 for _, g in picked])
    w = np.array([(len(calibration.groups[g][0]) - 1) / 2 for _, g in picked], dtype=float)
    design = np.vstack([np.ones_like(x), x]).T
    cov = np.linalg.inv(design.T @ (design * w[:, None]))
    a, b = cov @ (design.T @ (w * y))
    trend = FactorTrend(float(a), float(b), float(math.sqrt(cov[1, 1])),
                        calibration.dof - 1, p)
    if abs(trend.b) <= t_quantile(trend.dof) * trend.b_err:
        return None
    return trend


def realization_trends(rows, bc="pbc"):
    """dict quantity -> :class:`FactorTrend` of the groups :func:`realization_factors`
    pools for ``bc``, for the quantities whose factor measurably depends on eps
    (:func:`factor_trend`): their one-run rows of a known eps take the trend's factor
    there instead of the pooled one."""
    trends = {q: factor_trend(c) for q, c in _pooled_calibrations(rows, bc).items()}
    return {q: trend for q, trend in trends.items() if trend is not None}


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
