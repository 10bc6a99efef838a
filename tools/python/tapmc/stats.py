# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The bottom of the statistics: Student's t quantiles, the Welch-Satterthwaite degrees of
freedom, the weighted straight line and the one test every decision of the package makes,
:func:`beyond` ("a value further from a reference than t times its error").

A campaign has few realizations (2 to 10 seeds a point), so every confidence statement uses
Student's t with the error's own degrees of freedom, never the normal quantile. This module
imports nothing of the package: every other module may use it.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import stats as _scipy_stats

#: Two-sided confidence level of every t-based decision of the package (a statistical
#: standard; listed with the report's other conventions in tapmc.paper.claims.conventions).
#: The functions below read it when called (``confidence=None``), so that the report's table
#: of tolerances can vary it.
CONFIDENCE = 0.95
#: Significance below which a spread rejects the errors it is tested against: one run's own
#: error against the realizations' spread (tapmc.paper.claims), a paper ramp's level error
#: against its windows (tapmc.paper.paper_ramp), seeds' means against their own errors
#: (tapmc.hysteresis.seeds_together); convention: a 1 % test, as the fits'.
CALIBRATION_ALPHA = 0.01


def realization_factor(value, what):
    """``value`` as a float when it can be the factor by which another realization lands
    further than one run's own batch-means error (>= 1: the realizations' spread is never
    below it); ValueError naming ``what`` otherwise (also for NaN)."""
    factor = float(value)
    if not factor >= 1.0:
        raise ValueError(f"{what}: {factor!r}, must be >= 1 (the realizations' spread is never "
                         "below a run's own batch-means error)")
    return factor


def _level(confidence):
    return CONFIDENCE if confidence is None else confidence


def t_quantile(dof, confidence=None):
    """Two-sided ``confidence`` quantile (default :data:`CONFIDENCE`) of Student's t with
    ``dof`` degrees of freedom."""
    return float(_scipy_stats.t.ppf(0.5 + _level(confidence) / 2, dof))


def t_quantile_of_mean(n, confidence=None):
    """The t quantile of a mean over ``n`` realizations (dof n - 1); NaN below two."""
    return t_quantile(n - 1, confidence) if n > 1 else math.nan


def bonferroni_t_quantile(dof, tests, confidence=None):
    """The t quantile that keeps the family-wise ``confidence`` over ``tests`` tests."""
    return float(_scipy_stats.t.ppf(1 - (1 - _level(confidence)) / (2 * tests), dof))


def beyond(value, err, dof, reference=0.0, confidence=None):
    """True when ``value`` lies further than t * ``err`` from ``reference`` (t: the two-sided
    ``confidence`` quantile with ``dof`` degrees of freedom). False when it does not, or when
    the error cannot decide (no dof, a non-finite or absent error)."""
    if dof is None or dof < 1 or err is None or not np.isfinite(err) or not np.isfinite(value):
        return False
    return abs(value - reference) > t_quantile(dof, confidence) * err


def welch_dof(variances, dofs):
    """Welch-Satterthwaite dof of a sum of independent variance estimates ``variances`` with
    ``dofs`` each: (sum v)^2 / sum(v^2 / dof), rounded down, at least 1."""
    v = np.asarray(variances, dtype=float)
    d = np.asarray(dofs, dtype=float)
    denominator = float(np.sum(v ** 2 / d))
    if denominator <= 0:
        return int(np.min(d))
    return max(1, int(float(np.sum(v)) ** 2 / denominator))


def weighted_polyfit(x, y, err, degree):
    """Weighted least squares of a polynomial (coefficients of x^0 .. x^degree): (coef, cov,
    chi2)."""
    w = 1.0 / np.asarray(err) ** 2
    design = np.vander(np.asarray(x, dtype=float), degree + 1, increasing=True)
    cov = np.linalg.inv(design.T @ (design * w[:, None]))
    coef = cov @ (design.T @ (w * y))
    return coef, cov, float(np.sum(w * (y - design @ coef) ** 2))


def weighted_line_fit(x, y, err):
    """Weighted straight line y = a + b x: (a, its standard error, b, its standard error,
    dof); errors scaled by the reduced chi2 when it exceeds 1 (the scatter is then larger than
    the error bars say). Points with a non-finite value or a non-positive error are left out;
    fewer than three points, or fewer than two distinct x (no slope to fit), give NaNs and dof
    None."""
    x, y, err = map(np.asarray, (x, y, err))
    ok = np.isfinite(x) & np.isfinite(y) & np.isfinite(err) & (err > 0)
    x, y, err = x[ok], y[ok], err[ok]
    if len(x) < 3 or np.unique(x).size < 2:
        return math.nan, math.nan, math.nan, math.nan, None
    coef, cov, chi2 = weighted_polyfit(x, y, err, 1)
    dof = len(x) - 2
    scale = max(1.0, chi2 / dof)
    return (float(coef[0]), float(math.sqrt(cov[0, 0] * scale)), float(coef[1]),
            float(math.sqrt(cov[1, 1] * scale)), dof)


def weighted_line(x, y, err):
    """The slope of :func:`weighted_line_fit`: (b, its standard error, dof)."""
    return weighted_line_fit(x, y, err)[2:]


def mean_dof(n):
    """Degrees of freedom of a mean over n realizations (the smallest n of an array); None
    when fewer than two."""
    n = int(np.nanmin(np.atleast_1d(n))) if np.size(n) else 0
    return n - 1 if n >= 2 else None
