# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The fitting machinery of :mod:`tapmc.laws`: :class:`Law` (the base class of every fitter of
the package), :class:`FitResult` (parameters, goodness of fit, a verdict on whether the data
determine them) and :class:`Interval` (a profile-likelihood interval of one parameter).

**Determination.** The paper notes (section III.B) that at small eps the triplet
(X_inf, B, tau) "is no longer unique and depends strongly on the range of taps": the data
then constrain only a combination of the parameters. A :class:`FitResult` has
``determined = False`` and says why in ``note`` when the fit did not converge, the covariance
is singular or not finite, a parameter's 1-sigma error exceeds 100 % of its value, a parameter
sits on a bound, or two parameters are correlated beyond ``CORRELATION_LIMIT``. The numbers are
still returned: they describe the data, they are just not unique.

**Honest uncertainties.** A curvature error (the covariance of the fit) is a statement about
a parabola at the best fit; where the data fix only a combination of parameters it is
meaningless (the first medium-scale Fig. 2 printed ``tau = 2.67e+05 +- 0.026``). Every
:class:`FitResult` of :meth:`Law.fit` therefore has a profile likelihood per parameter
(:attr:`FitResult.intervals`): the parameter is fixed on a walk across its allowed range
(:meth:`Law.profile_limits`), the others are refitted, and the 68 % interval is where
chi2 - chi2_min <= ``PROFILE_DELTA_CHI2`` (= 1, Wilks, one parameter), the chi2 rescaled by
the reduced chi2 when that exceeds 1 (the scatter says the errors are too small or the law is
not exact; an unweighted fit always uses the residual scatter). A parameter is *determined*
(:attr:`FitResult.determined_params`) only when its interval closes on both sides inside its
allowed range; otherwise the open side is ``nan`` and :attr:`FitResult.errors` shows ``nan``
for it, never a curvature error.
"""

import warnings

import numpy as np
from scipy.optimize import OptimizeWarning, curve_fit, least_squares

from .._legends import place_legend
from .._validate import as_1d, new_axis, same_length

__all__ = ["Interval", "FitResult", "Law", "CORRELATION_LIMIT", "RELATIVE_ERROR_LIMIT",
           "PROFILE_DELTA_CHI2", "POSITIVE_DECADES", "TIME_SCALE_DECADES", "UNBOUNDED_SPAN"]

#: |correlation| between two parameters above which they are reported as not separately
#: determined (the data fix only a combination of them).
CORRELATION_LIMIT = 0.999
#: relative 1-sigma error above which a parameter is reported as not determined (100 %).
RELATIVE_ERROR_LIMIT = 1.0
#: chi2 - chi2_min of the 68.3 % profile-likelihood interval of one parameter (Wilks' theorem,
#: one degree of freedom).
PROFILE_DELTA_CHI2 = 1.0
#: allowed range of a positive parameter without a natural scale: this many decades either
#: side of its best value (a profile still flat there constrains nothing measurable).
POSITIVE_DECADES = 6.0
#: allowed range of a time scale (tau of eqs. 3, 4, 6): from the first positive tap / 10^3 to
#: the last tap x 10^3; beyond them the law is degenerate (a pure logarithm, resp. its linear
#: start) and a flat profile there means the data do not see tau.
TIME_SCALE_DECADES = 3.0
#: allowed range of an unbounded parameter: best value +- this many times (|value| + the
#: range of the data for an amplitude, or |value| + its curvature error otherwise).
UNBOUNDED_SPAN = 100.0
#: steps of the profile walk grow by this factor (few refits to reach a far limit) ...
_PROFILE_GROWTH = 2.0
#: ... and the crossing of the threshold is refined by this many secant refits.
_PROFILE_REFINE = 3
#: a chi2 found by the profile below the fit's by more than this fraction of the threshold is
#: reported as a local minimum of the fit (a smaller drop moves no interval end noticeably).
_LOCAL_MINIMUM_TOLERANCE = 0.05


class Interval:
    """A 68 % profile-likelihood interval of one parameter: ``value`` (best fit), ``lo``,
    ``hi`` (``nan`` on an open side: the chi2 stays within the threshold up to the limit of the
    allowed range), ``limits`` (that allowed range), ``determined`` (closed on both sides),
    ``method`` ('profile', or 'curvature' for a result built from a covariance found
    otherwise, e.g. a generalised least-squares line) and, for a profile, ``grid`` and
    ``delta_chi2`` (the walk: parameter values and chi2 - chi2_min, rescaled)."""

    def __init__(self, value, lo, hi, limits, method, grid=None, delta_chi2=None):
        self.value = float(value)
        self.lo = float(lo) if lo is not None else np.nan
        self.hi = float(hi) if hi is not None else np.nan
        self.limits = (float(limits[0]), float(limits[1]))
        self.method = method
        self.grid = grid
        self.delta_chi2 = delta_chi2

    @property
    def determined(self):
        return bool(np.isfinite(self.lo) and np.isfinite(self.hi))

    def widened(self, width, method=None):
        """This interval with each closed side moved out to at least ``width`` from the value
        (an error found otherwise, e.g. a bootstrap over realizations when the points of the
        fit are correlated); a side pushed beyond the allowed ``limits`` becomes open."""
        width = float(width) if np.isfinite(width) else 0.0
        lo, hi = self.lo, self.hi
        if np.isfinite(lo):
            lo = min(lo, self.value - width)
            lo = lo if lo > self.limits[0] else np.nan
        if np.isfinite(hi):
            hi = max(hi, self.value + width)
            hi = hi if hi < self.limits[1] else np.nan
        return Interval(self.value, lo, hi, self.limits, method or self.method)

    @property
    def half_widths(self):
        """(value - lo, hi - value); ``nan`` on an open side."""
        return self.value - self.lo, self.hi - self.value

    def __repr__(self):
        lo = f"{self.lo:.4g}" if np.isfinite(self.lo) else f"open (limit {self.limits[0]:.3g})"
        hi = f"{self.hi:.4g}" if np.isfinite(self.hi) else f"open (limit {self.limits[1]:.3g})"
        return f"<Interval {self.value:.6g} in [{lo}, {hi}]>"


def correlation_matrix(covariance):
    """The correlation matrix of a covariance: C_ij / sqrt(C_ii C_jj) (``nan`` where a variance
    is 0 or not finite)."""
    cov = np.asarray(covariance, dtype=float)
    err = np.sqrt(np.abs(np.diag(cov)))
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = cov / np.outer(err, err)
    corr[~np.isfinite(corr)] = np.nan
    return corr


def _scatter_scale(model, y, sigma, nparams):
    """The factor of a weighted fit's covariance: its reduced chi2 when that exceeds 1 (the
    points scatter more than their stated errors, which then understate them by
    sqrt(chi2/dof)), else 1 (a scatter below the errors is taken for chance, never a reason to
    narrow them). The convention of :func:`tapmc.stats.weighted_line_fit` and of the profile
    intervals (:attr:`FitResult.chi2_scale`), so that ``errors`` and ``intervals`` of one fit
    tell one error size."""
    dof = len(y) - nparams
    if dof < 1:
        return 1.0
    reduced = float(np.sum(((y - model) / sigma) ** 2)) / dof
    return max(1.0, reduced) if np.isfinite(reduced) else 1.0


class FitResult:
    """Outcome of a fit: ``params`` (dict), ``intervals`` (dict of :class:`Interval`, the 68 %
    profile-likelihood intervals), ``determined_params`` / ``undetermined_params`` (names whose
    interval closes / does not close inside the allowed range), ``errors`` (1-sigma curvature
    errors of the determined parameters, ``nan`` for the others), ``covariance``,
    ``correlation``, ``chi2``, ``dof``, ``reduced_chi2``, ``rms`` (residual root mean square),
    ``converged``, ``determined`` (the covariance verdict of :meth:`Law.assess` and every
    parameter determined) and ``note`` (why not). ``result(x)`` evaluates the fitted law;
    ``plot(ax)`` draws data and fit. With ``sigma`` given to the fit, ``chi2`` is the weighted
    sum and ``reduced_chi2`` tests the model; the covariance (so ``errors``) is the one the
    errors ``sigma`` give, multiplied by ``reduced_chi2`` when that exceeds 1 (the points
    scatter more than their errors say; errors times sqrt(chi2/dof), never narrowed), as the
    profile ``intervals`` are (``chi2_scale``) and :func:`tapmc.stats.weighted_line_fit`;
    without it the errors are scaled by the scatter of the residuals and ``chi2`` is the plain
    sum of squared residuals. The profiles are computed on first use of ``intervals``, ``errors``,
    ``determined`` or ``note`` (a few tens of refits); a result built otherwise may be given
    its ``intervals`` (dict of :class:`Interval`) instead."""

    def __init__(self, law, names, popt, pcov, x, y, sigma, determined, note, weighted,
                 bounds=None, converged=True, intervals=None):
        self.law = law
        self.names = list(names)
        self._popt = np.asarray(popt, dtype=float)
        self.covariance = np.asarray(pcov, dtype=float)
        self.x, self.y, self.sigma = x, y, sigma
        self._verdict = bool(determined)
        self._note = note
        self.weighted = weighted
        #: (lo, hi) bounds of the fit: a result of Law.fit is profiled; one built from a
        #: covariance found otherwise (bounds None) keeps curvature intervals.
        self.bounds = bounds
        self.converged = bool(converged)
        self._intervals = intervals
        self._profile_note = ""
        self._profile_best = None
        resid = y - self(x)
        self.residuals = resid
        self.chi2 = float(np.sum((resid / sigma) ** 2)) if weighted else float(np.sum(resid ** 2))
        self.dof = int(len(x) - len(names))
        self.reduced_chi2 = self.chi2 / self.dof if self.dof > 0 else np.nan
        self.rms = float(np.sqrt(np.mean(resid ** 2)))

    @property
    def params(self):
        return dict(zip(self.names, self._popt))

    @property
    def curvature_errors(self):
        """1-sigma errors from the covariance alone, for every parameter (also the
        undetermined ones, where they mean nothing): for diagnostics, not for reporting."""
        diag = np.diag(self.covariance) if self.covariance.ndim == 2 else np.full(len(self.names), np.inf)
        with np.errstate(invalid="ignore"):
            return dict(zip(self.names, np.sqrt(np.abs(diag))))

    @property
    def correlation(self):
        """Correlation matrix of the parameters (rows and columns in ``names`` order) from
        ``covariance``; an entry near +-1 means the data fix only a combination of the two
        (:meth:`Law.assess` flags beyond ``CORRELATION_LIMIT``)."""
        if self.covariance.ndim != 2:
            return np.full((len(self.names), len(self.names)), np.nan)
        return correlation_matrix(self.covariance)

    @property
    def errors(self):
        """1-sigma errors of the determined parameters (curvature, or the covariance set by
        the caller, e.g. a bootstrap); ``nan`` for an undetermined parameter."""
        determined = set(self.determined_params)
        return {k: (v if k in determined else np.nan) for k, v in self.curvature_errors.items()}

    @property
    def intervals(self):
        if self._intervals is None:
            self._intervals = self._compute_intervals()
        return self._intervals

    @property
    def determined_params(self):
        return [k for k in self.names if self.intervals[k].determined]

    @property
    def undetermined_params(self):
        return [k for k in self.names if not self.intervals[k].determined]

    @property
    def determined(self):
        return self._verdict and not self.undetermined_params

    @determined.setter
    def determined(self, value):
        self._verdict = bool(value)

    @property
    def note(self):
        self.intervals
        return "; ".join(filter(None, [self._note, self._profile_note]))

    @note.setter
    def note(self, value):
        self._note = value

    def improved(self, rounds=3):
        """This fit, or a refit from the lowest chi2 that its profiles met when that is lower
        by more than a small fraction of the profile threshold (the fit had stopped in a
        local minimum or on a slope of a flat valley); repeated up to ``rounds`` times. The
        profiles are computed (as for ``intervals``)."""
        res = self
        for _ in range(int(rounds)):
            res.intervals
            if res._profile_best is None or res._profile_best[1] is None:
                return res
            best, start = res._profile_best
            if not best < res.chi2 - _LOCAL_MINIMUM_TOLERANCE * PROFILE_DELTA_CHI2 * \
                    res.chi2_scale:
                return res
            new = res.law.fit(res.x, res.y, res.sigma if res.weighted else None,
                              p0=list(start))
            if not (new.converged and new.chi2 < res.chi2):
                return res
            res = new
        return res

    @property
    def chi2_scale(self):
        """The factor dividing chi2 differences in the profiles: the reduced chi2 when it
        exceeds 1 (always, for an unweighted fit), else 1."""
        scale = self.reduced_chi2
        if not np.isfinite(scale) or scale <= 0:
            return 1.0
        return scale if not self.weighted else max(1.0, scale)

    def profile_delta_chi2(self, name, value):
        """(chi2 - chi2_min) / ``chi2_scale`` of the profile of parameter ``name`` at
        ``value`` (the others refitted): 1 at the ends of the 68 % interval, its square root
        the distance of ``value`` in standard deviations for a parabolic profile. nan for a
        result that cannot be profiled."""
        if name not in self.names:
            raise ValueError(f"name = {name!r} must be one of the parameters {self.names}")
        if self.bounds is None or not self.converged:
            return np.nan
        i = self.names.index(name)
        lo, hi = (np.asarray(b, dtype=float) for b in self.bounds)
        if not lo[i] <= value <= hi[i]:
            return np.inf
        c, _ = self.law._profile_point(self.x, self.y, self.sigma, i, float(value), self._popt,
                                       lo, hi)
        return max(0.0, c - self.chi2) / self.chi2_scale if np.isfinite(c) else np.nan

    def _compute_intervals(self):
        if self.bounds is not None and self.converged:
            try:
                out, note = self.law.profile(self)
                self._profile_note = note
                return out
            except (ValueError, RuntimeError, np.linalg.LinAlgError) as exc:
                self._profile_note = f"profile failed ({exc})"
                return {k: Interval(v, None, None, (np.nan, np.nan), "profile")
                        for k, v in self.params.items()}
        if not self.converged:
            self._profile_note = "no intervals: the fit did not converge"
            return {k: Interval(v, None, None, (np.nan, np.nan), "profile")
                    for k, v in self.params.items()}
        err = self.curvature_errors
        ok = self._verdict
        return {k: Interval(v, v - err[k] if ok else None, v + err[k] if ok else None,
                            (-np.inf, np.inf), "curvature") for k, v in self.params.items()}

    def __call__(self, x):
        return self.law.function(np.asarray(x, dtype=float), *self._popt)

    def __repr__(self):
        parts = []
        for k, v in self.params.items():
            iv = self.intervals[k]
            if iv.determined:
                parts.append(f"{k}={v:.6g} [{iv.lo:.4g}, {iv.hi:.4g}]")
            else:
                lo = f"{iv.lo:.4g}" if np.isfinite(iv.lo) else "open"
                hi = f"{iv.hi:.4g}" if np.isfinite(iv.hi) else "open"
                parts.append(f"{k}={v:.6g} (undetermined: [{lo}, {hi}])")
        flag = "determined" if self.determined else f"NOT determined ({self.note})"
        return f"<FitResult {type(self.law).__name__}: {', '.join(parts)}; {flag}>"

    def plot(self, ax=None, logx=False, data_kw=None, xlabel=None, ylabel=None, **kw):
        """Data (points with error bars when sigma was given) and the fitted curve, with a
        legend; the axes are labelled ``xlabel`` / ``ylabel``, by default with the law's
        ``x_label`` / ``y_label`` where the axis has no label yet."""
        ax = new_axis(ax)
        data_kw = dict({"fmt": ".", "ms": 3, "alpha": 0.6, "label": "data"}, **(data_kw or {}))
        ax.errorbar(self.x, self.y, yerr=self.sigma if self.weighted else None, **data_kw)
        lo, hi = np.min(self.x), np.max(self.x)
        if logx:
            xs = np.geomspace(max(lo, hi * 1e-6, 1e-12), hi, 400)
            ax.set_xscale("log")
        else:
            xs = np.linspace(lo, hi, 400)
        kw.setdefault("label", type(self.law).__name__ + ("" if self.determined
                                                          else " (not determined)"))
        ax.plot(xs, self(xs), **kw)
        if xlabel is not None or not ax.get_xlabel():
            ax.set_xlabel(xlabel if xlabel is not None else self.law.x_label)
        if ylabel is not None or not ax.get_ylabel():
            ax.set_ylabel(ylabel if ylabel is not None else self.law.y_label)
        place_legend(ax, fontsize=8)
        return ax


class Law:
    """A law y = function(x, *params) with automatic starting values and physical bounds: the
    base class of every fitter of the package (here and in :mod:`tapmc.fluctuations` and
    :mod:`tapmc.pores`). A law sets ``names`` (its parameters, in the order of ``function``),
    ``function(x, *params)`` and ``initial_guess(x, y, w)`` (``w`` the weights 1/sigma^2), and
    may set ``bounds(x, y)``, ``may_vanish`` and ``jacobian``; :meth:`fit` and :meth:`assess`
    do the rest."""

    names = ()
    #: parameters that may legitimately be zero (their relative error is not tested)
    may_vanish = ()
    #: parameters with the units of x (time scales): allowed range ``TIME_SCALE_DECADES``
    #: beyond the data in the profile (:meth:`profile_limits`)
    time_scales = ()
    #: parameters with the units of y (asymptotes, amplitudes): an unbounded one spans
    #: ``UNBOUNDED_SPAN`` times the range of the data in the profile
    amplitudes = ()
    #: axis labels of :meth:`FitResult.plot` (what x and y are for this law)
    x_label = "x"
    y_label = "y"

    @staticmethod
    def function(x, *p):
        raise NotImplementedError

    #: ``jacobian(x, *params)``, the (len(x), len(names)) derivatives of ``function``, or None:
    #: then the fits difference ``function`` (2-point). An exact one costs about one call of
    #: ``function`` where the differences cost one per parameter, and the fits of a profile
    #: walk or a range refit evaluate it thousands of times.
    jacobian = None

    def initial_guess(self, x, y, w):
        raise NotImplementedError

    def bounds(self, x, y):
        return (-np.inf, np.inf)

    def _prepare(self, x, y, sigma):
        x = as_1d("x", x, min_len=len(self.names) + 1)
        y = as_1d("y", y)
        same_length("x", x, "y", y)
        weighted = sigma is not None
        if weighted:
            sigma = np.asarray(sigma, dtype=float)
            if sigma.ndim > 1 or sigma.size not in (1, y.size):
                raise ValueError(f"sigma has shape {sigma.shape}; give one value or one per "
                                 f"point ({y.size})")
            sigma = np.broadcast_to(sigma.reshape(-1) if sigma.ndim else sigma, y.shape).copy()
            if not np.all(np.isfinite(sigma) & (sigma > 0)):
                raise ValueError("sigma must be finite and > 0 everywhere")
        else:
            sigma = np.ones_like(y)
        return x, y, sigma, weighted

    def fit(self, x, y, sigma=None, p0=None):
        """Fit the law to (x, y) with optional 1-sigma errors ``sigma`` (scalar or per point);
        ``p0`` overrides the automatic starting values. Returns a :class:`FitResult`."""
        x, y, sigma, weighted = self._prepare(x, y, sigma)
        lo, hi = self.bounds(x, y)
        lo = np.broadcast_to(lo, (len(self.names),)).astype(float)
        hi = np.broadcast_to(hi, (len(self.names),)).astype(float)
        if p0 is not None and np.shape(p0) != (len(self.names),):
            raise ValueError(f"p0 has shape {np.shape(p0)}; give one start per parameter "
                             f"({', '.join(self.names)})")
        start = np.asarray(p0 if p0 is not None else self.initial_guess(x, y, 1.0 / sigma ** 2),
                           dtype=float)
        # keep the start strictly inside finite bounds (trust-region requirement)
        for i in range(len(start)):
            if np.isfinite(lo[i]) and start[i] <= lo[i]:
                start[i] = lo[i] + 1e-9 * (1.0 + abs(lo[i]))
            if np.isfinite(hi[i]) and start[i] >= hi[i]:
                start[i] = hi[i] - 1e-9 * (1.0 + abs(hi[i]))
        notes = []
        converged = True
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", OptimizeWarning)
            try:
                popt, pcov = curve_fit(self.function, x, y, p0=start, sigma=sigma,
                                       absolute_sigma=weighted, bounds=(lo, hi),
                                       method="trf", x_scale="jac", max_nfev=20000,
                                       jac=self.jacobian or "2-point")
            except (RuntimeError, ValueError) as exc:
                popt = start
                pcov = np.full((len(start), len(start)), np.inf)
                notes.append(f"fit did not converge ({exc})")
                converged = False
        if weighted and converged:
            pcov = pcov * _scatter_scale(self.function(x, *popt), y, sigma, len(self.names))
        popt, pcov = self._canonical(popt, pcov)
        determined, more = self.assess(popt, pcov, lo, hi)
        notes += more
        return FitResult(self, self.names, popt, pcov, x, y, sigma, determined and not notes,
                         "; ".join(notes), weighted, bounds=(lo, hi), converged=converged)

    def profile_limits(self, x, y, popt, lo, hi, errors):
        """The allowed range of every parameter for its profile: a list of ``(low, high,
        logarithmic)``. A finite bound is a limit; a time scale (``time_scales``) spans
        ``TIME_SCALE_DECADES`` beyond the taps; another positive parameter
        ``POSITIVE_DECADES`` either side of its value (walked in log); an unbounded one its
        value +- ``UNBOUNDED_SPAN`` (|value| + data range) for an amplitude (``amplitudes``),
        (|value| + curvature error) otherwise. The best value is always inside."""
        out = []
        xpos = x[x > 0]
        for i, name in enumerate(self.names):
            p = popt[i]
            positive = lo[i] >= 0 and p > 0
            if name in self.time_scales and positive and xpos.size:
                a = max(xpos.min() * 10 ** -TIME_SCALE_DECADES, lo[i])
                b = min(xpos.max() * 10 ** TIME_SCALE_DECADES, hi[i])
                log = a > 0
            elif positive and not np.isfinite(hi[i]):
                a, b, log = p * 10 ** -POSITIVE_DECADES, p * 10 ** POSITIVE_DECADES, True
            else:
                extra = np.ptp(y) if name in self.amplitudes else errors[i]
                scale = abs(p) + (extra if np.isfinite(extra) else 0.0)
                scale = scale if scale > 0 else 1.0
                a = lo[i] if np.isfinite(lo[i]) else p - UNBOUNDED_SPAN * scale
                b = hi[i] if np.isfinite(hi[i]) else p + UNBOUNDED_SPAN * scale
                log = False
            out.append((min(a, p), max(b, p), log))
        return out

    def _profile_point(self, x, y, sigma, i, value, start, lo, hi):
        """One point of a profile: the fit with parameter ``i`` fixed at ``value`` from the
        previous point's parameters ``start``, and, when the law offers a global start for the
        fixed problem (:meth:`_conditional_start`) whose chi2 is lower, from that start too
        (a continuation alone can follow a local valley: a profile must be a global minimum
        over the other parameters, or its interval closes too early). ``(chi2, params)``."""
        c, q = self._fixed_fit(x, y, sigma, i, value, start, lo, hi)
        alt = self._conditional_start(x, y, sigma, i, value)
        if alt is not None:
            with np.errstate(all="ignore"):
                c_alt = float(np.sum(((self.function(x, *alt) - y) / sigma) ** 2))
            if np.isfinite(c_alt) and not (c_alt >= c):
                c2, q2 = self._fixed_fit(x, y, sigma, i, value, alt, lo, hi)
                if np.isfinite(c2) and not (c2 >= c):
                    return c2, q2
        return c, q

    def _conditional_start(self, x, y, sigma, i, value):
        """A global starting point for the fit with parameter ``i`` fixed at ``value``, or
        None (no such search for this law: the profile follows the previous point)."""
        return None

    def _fixed_fit(self, x, y, sigma, i, value, start, lo, hi):
        """chi2 and parameters of the fit with parameter ``i`` fixed at ``value``."""
        p = np.array(start, dtype=float)
        p[i] = value
        free = np.arange(len(p)) != i
        if not free.any():
            with np.errstate(all="ignore"):
                r = (self.function(x, *p) - y) / sigma
            return float(np.sum(r ** 2)), p
        flo, fhi = lo[free], hi[free]
        q0 = p[free].copy()
        for j in range(len(q0)):  # strictly inside finite bounds (trust-region requirement)
            if np.isfinite(flo[j]) and q0[j] <= flo[j]:
                q0[j] = flo[j] + 1e-9 * (1.0 + abs(flo[j]))
            if np.isfinite(fhi[j]) and q0[j] >= fhi[j]:
                q0[j] = fhi[j] - 1e-9 * (1.0 + abs(fhi[j]))

        def residuals(q):
            full = p.copy()
            full[free] = q
            return (self.function(x, *full) - y) / sigma

        jac = "2-point"
        if self.jacobian is not None:
            def jac(q):
                full = p.copy()
                full[free] = q
                return self.jacobian(x, *full)[:, free] / sigma[:, None]

        with np.errstate(all="ignore"):
            try:
                fit = least_squares(residuals, q0, jac=jac, bounds=(flo, fhi), method="trf",
                                    x_scale="jac", max_nfev=100 * len(p))
            except ValueError:  # not finite at the start: this value is not allowed
                return np.nan, p
        p[free] = fit.x
        return 2.0 * float(fit.cost), p

    def profile(self, result):
        """Profile likelihood of every parameter of ``result`` (a :class:`FitResult` of this
        law): returns ``(intervals, note)``, ``intervals`` a dict of :class:`Interval`.

        For each parameter, a walk from the best value towards each limit of
        :meth:`profile_limits` (steps growing by a factor 2 from the curvature error, in log
        for positive parameters) refits the others at every step, starting from the previous
        step, until chi2 - chi2_min exceeds the threshold (then a few secant refits place the
        crossing) or the limit is reached (that side is open). The threshold is
        ``PROFILE_DELTA_CHI2`` times the reduced chi2 when that exceeds 1 (always, for an
        unweighted fit): a law that does not describe the data within their errors widens
        its intervals instead of narrowing them. A lower chi2 found on the way (the fit
        stopped in a local minimum) becomes chi2_min and is reported in ``note``."""
        x, y, sigma = result.x, result.y, result.sigma
        lo, hi = (np.asarray(b, dtype=float) for b in result.bounds)
        popt = result._popt
        scale = result.chi2_scale
        thr = PROFILE_DELTA_CHI2 * scale
        chi2_min = result.chi2
        err = np.array(list(result.curvature_errors.values()))
        limits = self.profile_limits(x, y, popt, lo, hi, err)
        samples = [(self._profile_walk(x, y, sigma, i, limits[i], popt, err, chi2_min, thr,
                                       lo, hi), limits[i]) for i in range(len(popt))]
        best, best_params = chi2_min, None
        for pts, _ in samples:
            for _, c, q in pts:
                if c < best:
                    best, best_params = c, q
        result._profile_best = (best, best_params)
        note = ""
        if best < chi2_min - _LOCAL_MINIMUM_TOLERANCE * thr:
            note = (f"the profile found a chi2 lower by {chi2_min - best:.3g} than the fit's: "
                    "the fit stopped in a local minimum (FitResult.improved() refits from there); "
                    "intervals are about the lower one")
        out = {}
        for name, (pts, limit) in zip(self.names, samples):
            out[name] = _profile_interval(popt[self.names.index(name)], pts, limit, best, scale)
        return out, note

    def _profile_walk(self, x, y, sigma, i, limits, popt, err, chi2_min, thr, lo, hi):
        """The walk of :meth:`profile` for parameter ``i``: ``(value, chi2, params)`` at its best
        value and at every step from there towards each end of its allowed range ``limits``
        (``(low, high, logarithmic)``), until chi2 - chi2_min exceeds ``thr`` (the crossing then
        placed by :meth:`_refine`) or the end is reached (that side is open)."""
        a, b, log = limits
        fwd = np.log if log else (lambda v: v)
        back = np.exp if log else (lambda v: v)
        u0, ua, ub = fwd(popt[i]), fwd(a), fwd(b)
        pts = [(popt[i], chi2_min, popt)]
        span = ub - ua
        if not span > 0:
            return pts
        e = err[i] / popt[i] if log else err[i]
        step0 = e if np.isfinite(e) and e > 0 else span / 100
        step0 = float(np.clip(step0, span * 1e-4, span / 10))
        for direction, limit in ((-1.0, ua), (1.0, ub)):
            if direction * (limit - u0) <= 0:
                continue
            u_prev, c_prev, q_prev, step = u0, chi2_min, popt, step0
            while True:
                u = u_prev + direction * step
                at_limit = direction * (u - limit) >= 0
                u = limit if at_limit else u
                c, q = self._profile_point(x, y, sigma, i, back(u), q_prev, lo, hi)
                if np.isfinite(c):
                    pts.append((back(u), c, q))
                if np.isfinite(c) and c - chi2_min > thr:
                    self._refine(x, y, sigma, i, back, lo, hi, chi2_min, thr, pts,
                                 (u_prev, c_prev, q_prev), (u, c))
                    break
                if at_limit:
                    break
                if np.isfinite(c):
                    u_prev, c_prev, q_prev = u, c, q
                step *= _PROFILE_GROWTH
        return pts

    def _refine(self, x, y, sigma, i, back, lo, hi, chi2_min, thr, pts, inner, outer):
        """Secant refits on sqrt(chi2 - chi2_min), linear in the parameter for a parabolic
        profile, to place the threshold crossing between ``inner`` and ``outer``."""
        u_in, c_in, q_in = inner
        u_out, c_out = outer
        target = np.sqrt(thr)
        for _ in range(_PROFILE_REFINE):
            r_in, r_out = np.sqrt(max(c_in - chi2_min, 0.0)), np.sqrt(c_out - chi2_min)
            if r_out <= r_in:
                return
            u = u_in + (u_out - u_in) * (target - r_in) / (r_out - r_in)
            c, q = self._profile_point(x, y, sigma, i, back(u), q_in, lo, hi)
            if not np.isfinite(c):
                return
            pts.append((back(u), c, q))
            if abs(c - chi2_min - thr) < 0.05 * thr:
                return
            if c - chi2_min > thr:
                u_out, c_out = u, c
            else:
                u_in, c_in, q_in = u, c, q

    def _canonical(self, popt, pcov):
        return popt, pcov

    def assess(self, popt, pcov, lo, hi):
        """Whether the parameters ``popt`` with covariance ``pcov`` are determined, given the
        bounds ``lo`` and ``hi`` (one per parameter): ``(determined, notes)``, the notes saying
        why not (covariance not finite, a parameter on a bound, a relative error above
        ``RELATIVE_ERROR_LIMIT``, correlations beyond ``CORRELATION_LIMIT``). :meth:`fit` applies
        it to the fit's covariance; it also judges a covariance found otherwise (a bootstrap)."""
        notes = []
        if not np.all(np.isfinite(pcov)):
            return False, ["covariance not finite: the data do not constrain every parameter"]
        err = np.sqrt(np.abs(np.diag(pcov)))
        for i, name in enumerate(self.names):
            span = (hi[i] - lo[i]) if np.isfinite(hi[i] - lo[i]) else 1.0 + abs(popt[i])
            for bound in (lo[i], hi[i]):
                if np.isfinite(bound) and abs(popt[i] - bound) <= 1e-6 * span + 1e-12 * abs(bound):
                    notes.append(f"{name} at its bound {bound:g}")
            if name not in self.may_vanish and err[i] > RELATIVE_ERROR_LIMIT * abs(popt[i]):
                notes.append(f"{name} error {err[i]:.3g} exceeds 100% of its value "
                             f"{popt[i]:.3g}")
        corr = correlation_matrix(pcov)
        n = len(self.names)
        pairs = [f"{self.names[i]}/{self.names[j]} {corr[i, j]:+.5f}" for i in range(n)
                 for j in range(i + 1, n) if abs(corr[i, j]) > CORRELATION_LIMIT]
        if pairs:
            notes.append("correlations beyond " + f"{CORRELATION_LIMIT:g} (the data fix only a "
                         "combination of these): " + ", ".join(pairs))
        return not notes, notes


def _profile_interval(value, pts, limits, best, scale):
    """The :class:`Interval` of one parameter of best fit ``value`` from the points
    ``(value, chi2, params)`` of its profile walk (:meth:`Law.profile`): its ends are where
    (chi2 - ``best``) / ``scale`` crosses ``PROFILE_DELTA_CHI2``, interpolated linearly in its
    square root (linear in the parameter, or in its log on a logarithmic walk, for a
    parabolic profile); a side still inside at the last value walked is open."""
    a, b, log = limits
    pts = sorted(pts, key=lambda point: point[0])
    v = np.array([point[0] for point in pts])
    d = (np.array([point[1] for point in pts]) - best) / scale
    inside = np.flatnonzero(d <= PROFILE_DELTA_CHI2)
    if inside.size == 0:  # a fit without residuals: only rounding left in d
        inside = np.array([int(np.argmin(d))])
    ends = []
    for k, outer in ((inside[0], inside[0] - 1), (inside[-1], inside[-1] + 1)):
        if outer < 0 or outer >= len(v):
            ends.append(None)  # inside up to the last value walked: open
            continue
        fwd = np.log if log else (lambda q: q)
        back = np.exp if log else (lambda q: q)
        r_in, r_out = np.sqrt(max(d[k], 0.0)), np.sqrt(d[outer])
        frac = float(np.clip((1.0 - r_in) / (r_out - r_in), 0.0, 1.0)) if r_out > r_in else 0.0
        ends.append(float(back(fwd(v[k]) + frac * (fwd(v[outer]) - fwd(v[k])))))
    return Interval(value, ends[0], ends[1], (a, b), "profile", v, d)
