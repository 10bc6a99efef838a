# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Fits of the laws of Philippe & Bideau with parameters, 1-sigma uncertainties, a goodness of
fit and an explicit verdict on whether the parameters are determined by the data.

* :class:`InverseLogLaw`, eq. 3: X(t) = X_inf - dX_inf / (1 + B ln(1 + t/tau)), X = Phi_b or
  <Phi^c> (section III.A).
* :class:`ZLaw`, eq. 4: <Z>(t) = Z_inf (1 + B L) / (Z_inf/Z_0 + B L), L = ln(1 + t/tau).
* :class:`TwoExponentials`: y_inf + a1 exp(-t/tau1) + a2 exp(-t/tau2), tau1 <= tau2
  (section III.A: "a sum of two exponentials can also fit reasonably well <Z>(t)").
* :class:`AgeingLaw`, eq. 6: A(t) = A_inf (1 - 1/(1 + B_A ln(1 + t/tau_A))) (section III.C).
* :class:`ProfileLaw`, eq. 7: Phi(zb) = (Phi0 - alpha zb) / (1 + exp(beta (zb - zb_star))),
  zb = z/R, fitted above the wall layers (section IV.A), with :func:`profile_gradient`, the
  straight-line gradient alpha in the paper's window (5 <= z/R <= 22 FBC, 26 PBC).

Every fitter has ``fit(x, y, sigma=None) -> FitResult``. Starting values are found
automatically: eqs. 3, 4 and 6 are linear in their amplitudes once (B, tau) are fixed (eq. 4 in
1/<Z>), so a log-spaced grid over (B, tau) with exact linear least squares at every node gives
a global starting point that does not depend on the user; scipy.optimize.curve_fit (trust
region, with physical bounds) refines it.

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
for it, never a curvature error. :func:`range_refits` refits a law over several tap ranges and
compares the spread of each parameter with the profile intervals: the statistic of the paper's
"depends strongly on the range of taps" (section III.B); :class:`SurrogateFits` asks the same
of one run with correlated taps, from Fourier surrogates of its residuals, and
:class:`RealizationLawTest` tests a law across independent realizations.
:func:`exponential_dependence` tests "B is consistent with an exponential dependence on
eps^(1/2)" (section III.A).
"""

import warnings

import numpy as np
from scipy.optimize import OptimizeWarning, curve_fit, least_squares
from scipy.stats import chi2 as chi2_distribution
from scipy.stats import f as f_distribution

from ._legends import place_legend
from ._validate import as_1d, new_axis, same_length

__all__ = ["FitResult", "Law", "InverseLogLaw", "ZLaw", "TwoExponentials", "AgeingLaw",
           "ProfileLaw", "StraightLine", "profile_gradient", "PROFILE_WINDOWS",
           "CORRELATION_LIMIT", "RELATIVE_ERROR_LIMIT", "DETERMINED_FACTOR",
           "PROFILE_DELTA_CHI2",
           "POSITIVE_DECADES", "TIME_SCALE_DECADES", "UNBOUNDED_SPAN", "RANGE_Z_LIMIT",
           "LINEARITY_P_MIN", "Interval", "RangeRefits", "range_refits", "default_tap_ranges",
           "LogLinear", "ExponentialDependence", "exponential_dependence",
           "RealizationLawTest", "realization_bin_covariance", "hotelling_gls",
           "REALIZATION_MAX_BINS", "REALIZATION_P_MIN",
           "SurrogateFits", "SURROGATES", "SURROGATE_P_MIN", "RealizationFits",
           "spread_interval", "spread_verdict"]

#: |correlation| between two parameters above which they are reported as not separately
#: determined (the data fix only a combination of them).
CORRELATION_LIMIT = 0.999
#: relative 1-sigma error above which a parameter is reported as not determined (100 %).
RELATIVE_ERROR_LIMIT = 1.0
#: factor within which a positive scale (B, tau of eqs. 3 and 4, compared in ln) is
#: determined by :class:`SurrogateFits` and :class:`RealizationFits`: half the band's width
#: at most ln 2 (convention: a scale known to a factor 2 is known to its order)
DETERMINED_FACTOR = 2.0
#: gradient windows of the paper (section IV.A), in units of R.
PROFILE_WINDOWS = {"fbc": (5.0, 22.0), "pbc": (5.0, 26.0)}
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
#: deviation of a sub-range fit from the full-range value, in standard deviations of the
#: sub-range's profile (sqrt of its delta chi2 there), above which a parameter depends on the
#: fitted range. For nested tap ranges and a correct law the full-range value is a draw
#: within the sub-range's own scatter; 3 leaves room for the 4 ranges tested together.
RANGE_Z_LIMIT = 3.0
#: p-value of the chi2 of a straight line below which the line is rejected (5 % test).
LINEARITY_P_MIN = 0.05
#: at most this many log-spaced bins of taps in a :class:`RealizationLawTest`: each bin adds a
#: dimension to the covariance that the realizations must estimate (it needs realizations >
#: bins), and 8 bins over 2-4 decades resolve the curvature the laws describe.
REALIZATION_MAX_BINS = 8
#: p-value below which a :class:`RealizationLawTest` rejects the law (a 1 % test).
REALIZATION_P_MIN = 0.01
#: Fourier surrogates of one run's residuals in a :class:`SurrogateFits`: 200 put the 16 and
#: 84 % points within about 3 % (in probability) and resolve a p-value of 1 %.
SURROGATES = 200
#: p-value below which a :class:`SurrogateFits` calls a parameter range dependent (a 1 %
#: test, as :data:`REALIZATION_P_MIN`).
SURROGATE_P_MIN = 0.01
#: distance (in ln) from the edge of (B, tau)'s allowed range within which a
#: :class:`SurrogateFits` fit counts as sitting on it
_EDGE_TOLERANCE = 1e-6
#: best (B, tau) grid nodes from which a :class:`RealizationLawTest` refines its GLS fit,
#: beside the law's own fit of the mean curve (the minimum chi-square decides the test: a
#: local minimum would reject a law that holds).
_GRID_STARTS = 4
#: ... of which this many (the best after the fit of (B, tau) alone) are polished by the fit
#: of all parameters; two, because eq. 4's amplitudes are linear only to first order.
_POLISHED_STARTS = 2
#: steps of the profile walk grow by this factor (few refits to reach a far limit) ...
_PROFILE_GROWTH = 2.0
#: ... and the crossing of the threshold is refined by this many secant refits.
_PROFILE_REFINE = 3
#: a chi2 found by the profile below the fit's by more than this fraction of the threshold is
#: reported as a local minimum of the fit (a smaller drop moves no interval end noticeably).
_LOCAL_MINIMUM_TOLERANCE = 0.05
#: det / product of the diagonal of the normal equations of a grid node below which its
#: amplitude columns count as collinear (the amplitudes are then not unique there).
_COLLINEAR_TOLERANCE = 1e-10


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


class FitResult:
    """Outcome of a fit: ``params`` (dict), ``intervals`` (dict of :class:`Interval`, the 68 %
    profile-likelihood intervals), ``determined_params`` / ``undetermined_params`` (names whose
    interval closes / does not close inside the allowed range), ``errors`` (1-sigma curvature
    errors of the determined parameters, ``nan`` for the others), ``covariance``,
    ``correlation``, ``chi2``, ``dof``, ``reduced_chi2``, ``rms`` (residual root mean square),
    ``converged``, ``determined`` (the covariance verdict of :meth:`Law.assess` and every
    parameter determined) and ``note`` (why not). ``result(x)`` evaluates the fitted law;
    ``plot(ax)`` draws data and fit. With ``sigma`` given to the fit, errors are absolute
    (``chi2`` is the weighted sum and ``reduced_chi2`` tests the model); without it the errors
    are scaled by the scatter of the residuals and ``chi2`` is the plain sum of squared
    residuals. The profiles are computed on first use of ``intervals``, ``errors``,
    ``determined`` or ``note`` (a few tens of refits)."""

    def __init__(self, law, names, popt, pcov, x, y, sigma, determined, note, weighted,
                 bounds=None, converged=True):
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
        self._intervals = None
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
    may set ``bounds(x, y)`` and ``may_vanish``; :meth:`fit` and :meth:`assess` do the rest."""

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
            sigma = np.broadcast_to(np.asarray(sigma, dtype=float), y.shape).copy()
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
                                       method="trf", x_scale="jac", max_nfev=20000)
            except (RuntimeError, ValueError) as exc:
                popt = start
                pcov = np.full((len(start), len(start)), np.inf)
                notes.append(f"fit did not converge ({exc})")
                converged = False
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

        with np.errstate(all="ignore"):
            try:
                fit = least_squares(residuals, q0, bounds=(flo, fhi), method="trf",
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
        samples = []
        for i in range(len(popt)):
            a, b, log = limits[i]
            fwd = np.log if log else (lambda v: v)
            back = np.exp if log else (lambda v: v)
            u0, ua, ub = fwd(popt[i]), fwd(a), fwd(b)
            pts = [(popt[i], chi2_min, popt)]
            span = ub - ua
            if span > 0:
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
            samples.append((pts, limits[i]))
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
        for name, (pts, (a, b, log)) in zip(self.names, samples):
            pts = sorted(pts, key=lambda point: point[0])
            v = np.array([point[0] for point in pts])
            d = (np.array([point[1] for point in pts]) - best) / scale
            inside = np.flatnonzero(d <= PROFILE_DELTA_CHI2)
            if inside.size == 0:  # a fit without residuals: only rounding left in d
                inside = np.array([int(np.argmin(d))])
            value = popt[self.names.index(name)]
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
            out[name] = Interval(value, ends[0], ends[1], (a, b), "profile", v, d)
        return out, note

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
        with np.errstate(invalid="ignore", divide="ignore"):
            corr = pcov / np.outer(err, err)
        n = len(self.names)
        pairs = [f"{self.names[i]}/{self.names[j]} {corr[i, j]:+.5f}" for i in range(n)
                 for j in range(i + 1, n) if abs(corr[i, j]) > CORRELATION_LIMIT]
        if pairs:
            notes.append("correlations beyond " + f"{CORRELATION_LIMIT:g} (the data fix only a "
                         "combination of these): " + ", ".join(pairs))
        return not notes, notes


class _TapsLaw(Law):
    """A law of the number of taps t >= 0 (the logarithmic laws of eqs. 3, 4 and 6).

    These laws are linear in their amplitudes once (B, tau) are fixed (eq. 4 in 1/<Z>): a
    subclass names its (B, tau) parameters in ``_nonlinear`` and gives ``_basis(t, B, tau)``,
    the columns multiplying its amplitudes ``_linear`` (in the space of ``_target``), which
    gives the profile a global start at every point (:meth:`_conditional_start`)."""

    x_label = "tap t"
    y_label = "X"

    _nonlinear = ("B", "tau")
    _linear = ()
    #: a coarse (B, tau) grid for the profile's global starts (refined by the refit)
    _GRID_B = np.geomspace(1e-3, 1e3, 25)
    _GRID_TAU_DECADES = (-2.0, 2.0, 25)

    def _target(self, y, w):
        """(data, weights) in the space where the amplitudes are linear."""
        return y, w

    def _amplitudes_to_params(self, a):
        return a

    def _params_to_amplitude(self, name, value):
        return value

    def _basis(self, t, B, tau):
        raise NotImplementedError

    def _conditional_start(self, x, y, sigma, i, value):
        if not self._linear or np.any(x < 0):
            return None
        tpos = x[x > 0]
        if tpos.size == 0:
            return None
        lo_d, hi_d, num = self._GRID_TAU_DECADES
        taus = np.geomspace(tpos.min() * 10 ** lo_d, tpos.max() * 10 ** hi_d, num)
        Bs = self._GRID_B
        name = self.names[i]
        iB, itau = (self.names.index(k) for k in self._nonlinear)
        if name == self._nonlinear[0]:
            Bs = np.array([value])
        elif name == self._nonlinear[1]:
            taus = np.array([value])
        BB, TT = (a.ravel() for a in np.meshgrid(Bs, taus, indexing="ij"))
        target, w = self._target(y, 1.0 / sigma ** 2)
        with np.errstate(all="ignore"):
            cols = self._grid_basis(x, BB, TT)                  # list of (nodes, n)
            free = list(range(len(self._linear)))
            if name in self._linear:
                # target - v c_k per node: only its products with w and the columns are needed
                k = self._linear.index(name)
                v = self._params_to_amplitude(name, value)
                free.remove(k)
                tt = (np.sum(w * target ** 2) - 2.0 * v * (cols[k] @ (w * target))
                      + v ** 2 * ((cols[k] ** 2) @ w))
                rhs = np.stack([cols[j] @ (w * target) - v * ((cols[j] * cols[k]) @ w)
                                for j in free], axis=1) if free else None
            else:
                tt = np.full(len(BB), np.sum(w * target ** 2))
                rhs = np.stack([cols[j] @ (w * target) for j in free], axis=1)
            m = len(free)
            coef = np.zeros((len(BB), len(self._linear)))
            sse = tt
            if m:
                normal = np.empty((len(BB), m, m))
                for a, ja in enumerate(free):
                    for b, jb in enumerate(free[a:], start=a):
                        normal[:, a, b] = normal[:, b, a] = (cols[ja] * cols[jb]) @ w
                sol = _solve_nodes(normal, rhs)   # collinear nodes: nan, so sse = inf
                for j, k in enumerate(free):
                    coef[:, k] = sol[:, j]
                # |r|^2 = |t|^2 - rhs . sol at the least-squares amplitudes
                sse = tt - np.sum(rhs * sol, axis=1)
        sse = np.where(np.isfinite(sse), sse, np.inf)
        best = int(np.argmin(sse))
        if not np.isfinite(sse[best]):
            return None
        amps = coef[best]
        if name in self._linear:
            amps[self._linear.index(name)] = self._params_to_amplitude(name, value)
        p = np.empty(len(self.names))
        for k, v in zip(self._linear, self._amplitudes_to_params(amps)):
            p[self.names.index(k)] = v
        p[iB], p[itau] = BB[best], TT[best]
        p[i] = value
        return p if np.all(np.isfinite(p)) else None

    def _grid_basis(self, x, BB, TT):
        """The basis columns at every (B, tau) node, kept for the next call on the same taps
        and nodes: a profile fixes one parameter after another on the same data, and the
        columns (a logarithm per tap and node) cost more than the fits they start."""
        key = (type(self), x.tobytes(), BB.tobytes(), TT.tobytes())
        entry = _GRID_BASIS_CACHE[0] if _GRID_BASIS_CACHE else None
        if entry is None or entry[0] != key:
            entry = (key, [np.ascontiguousarray(np.broadcast_to(c, (BB.size, x.size)))
                           for c in self._basis(x[None, :], BB[:, None], TT[:, None])])
            _GRID_BASIS_CACHE[:] = [entry]   # one entry, replaced whole (threads see either)
        return entry[1]

    def _prepare(self, x, y, sigma):
        x, y, sigma, weighted = super()._prepare(x, y, sigma)
        if np.any(x < 0):
            bad = int(np.flatnonzero(x < 0)[0])
            raise ValueError(f"x[{bad}] = {x[bad]:g}: taps must be >= 0")
        return x, y, sigma, weighted


def _solve_nodes(normal, rhs):
    """Amplitudes at every grid node from its normal equations, (nodes, m, m) and (nodes, m):
    nan at the nodes whose columns are (nearly) collinear, e.g. g = 1 for a tau far beyond
    the data, which have no unique amplitudes."""
    ok = np.abs(np.linalg.det(normal)) > _COLLINEAR_TOLERANCE * np.abs(
        np.prod(np.diagonal(normal, axis1=1, axis2=2), axis=1))
    sol = np.full(rhs.shape, np.nan)
    if ok.any():
        sol[ok] = np.linalg.solve(normal[ok], rhs[ok][..., None])[..., 0]
    return sol


#: the last grid of basis columns of :meth:`_TapsLaw._grid_basis`, as [(key, columns)] (one
#: entry: a profile walks one data set at a time)
_GRID_BASIS_CACHE = []


def _log_term(t, B, tau):
    return B * np.log1p(np.maximum(t, 0.0) / tau)


def _grid_inverse_log(t, targets, w, ncols):
    """Grid over (B, tau) of g = 1/(1 + B ln(1 + t/tau)); for each node solve the weighted
    linear least squares targets ~ c0 * (1 - g) + c1 * g (ncols = 2) or c0 * (1 - g)
    (ncols = 1). Returns (B, tau, coefficients) of the best node."""
    tpos = t[t > 0]
    if tpos.size == 0:
        raise ValueError("x needs positive values (taps) to fit a logarithmic law")
    t_lo, t_hi = tpos.min(), tpos.max()
    taus = np.geomspace(t_lo * 1e-2, t_hi * 1e2, 41)
    Bs = np.geomspace(1e-3, 1e3, 43)
    best = (np.inf, None)
    for tau in taus:
        ell = np.log1p(t / tau)
        g = 1.0 / (1.0 + Bs[:, None] * ell[None, :])  # (nB, n)
        h = 1.0 - g
        if ncols == 1:
            s11 = (w * h * h).sum(1)
            b1 = (w * h * targets).sum(1)
            c1 = b1 / s11
            sse = (w * targets ** 2).sum() - c1 * b1
            coefs = c1[:, None]
        else:  # 2x2 normal equations for every B at once
            s11, s12, s22 = (w * h * h).sum(1), (w * h * g).sum(1), (w * g * g).sum(1)
            b1, b2 = (w * h * targets).sum(1), (w * g * targets).sum(1)
            det = s11 * s22 - s12 ** 2
            with np.errstate(divide="ignore", invalid="ignore"):
                c1 = (s22 * b1 - s12 * b2) / det
                c2 = (s11 * b2 - s12 * b1) / det
            sse = (w * targets ** 2).sum() - c1 * b1 - c2 * b2
            coefs = np.stack([c1, c2], axis=1)
        sse = np.where(np.isfinite(sse), sse, np.inf)
        k = int(np.argmin(sse))
        if sse[k] < best[0]:
            best = (sse[k], (Bs[k], tau, coefs[k]))
    return best[1]


class InverseLogLaw(_TapsLaw):
    """Eq. 3 (section III.A): X(t) = X_inf - dX_inf / (1 + B ln(1 + t/tau)); X(0) = X_inf -
    dX_inf. Parameters ``X_inf, dX_inf, B, tau`` (B, tau > 0; dX_inf of either sign, negative
    for a decompaction). At small eps the data often fix only a combination of (X_inf, B, tau):
    the result then says it is not determined (section III.B)."""

    x_label = "tap t"
    y_label = "X (Phi_b or <Phi^c>)"

    names = ("X_inf", "dX_inf", "B", "tau")
    time_scales = ("tau",)
    amplitudes = ("X_inf", "dX_inf")

    @staticmethod
    def function(t, X_inf, dX_inf, B, tau):
        return X_inf - dX_inf / (1.0 + _log_term(t, B, tau))

    def bounds(self, x, y):
        return ([-np.inf, -np.inf, 0.0, 0.0], [np.inf, np.inf, np.inf, np.inf])

    _linear = ("X_inf", "dX_inf")

    def _basis(self, t, B, tau):
        g = 1.0 / (1.0 + _log_term(t, B, tau))
        return [np.ones_like(g), -g]

    def initial_guess(self, t, y, w):
        B, tau, (c_inf, c_0) = _grid_inverse_log(t, y, w, 2)
        return [c_inf, c_inf - c_0, B, tau]


class ZLaw(_TapsLaw):
    """Eq. 4 (section III.A): <Z>(t) = Z_inf (1 + B L) / (Z_inf/Z_0 + B L), L = ln(1 + t/tau).
    Parameters ``Z_inf, Z_0, B, tau`` (all > 0). Equivalently 1/<Z> = g/Z_0 + (1 - g)/Z_inf with
    g = 1/(1 + B L), which gives the starting values."""

    x_label = "tap t"
    y_label = "<Z>"

    names = ("Z_inf", "Z_0", "B", "tau")
    time_scales = ("tau",)
    amplitudes = ("Z_inf", "Z_0")

    @staticmethod
    def function(t, Z_inf, Z_0, B, tau):
        L = _log_term(t, B, tau)
        return Z_inf * (1.0 + L) / (Z_inf / Z_0 + L)

    def bounds(self, x, y):
        return ([0.0, 0.0, 0.0, 0.0], [np.inf] * 4)

    _linear = ("Z_inf", "Z_0")

    def _target(self, y, w):
        return 1.0 / y, w * y ** 4  # d(1/Z) = dZ / Z^2

    def _params_to_amplitude(self, name, value):
        return 1.0 / value

    def _amplitudes_to_params(self, a):
        with np.errstate(divide="ignore"):
            return np.where(a > 0, 1.0 / a, np.nan)

    def _basis(self, t, B, tau):
        g = 1.0 / (1.0 + _log_term(t, B, tau))
        return [1.0 - g, g]

    def _conditional_start(self, x, y, sigma, i, value):
        return None if np.any(y <= 0) else super()._conditional_start(x, y, sigma, i, value)

    def initial_guess(self, t, y, w):
        if np.any(y <= 0):
            raise ValueError("eq. 4 needs <Z> > 0 everywhere")
        # d(1/Z) = dZ / Z^2: weights of the reciprocal data
        B, tau, (inv_inf, inv_0) = _grid_inverse_log(t, 1.0 / y, w * y ** 4, 2)
        return [1.0 / inv_inf if inv_inf > 0 else y[-1], 1.0 / inv_0 if inv_0 > 0 else y[0],
                B, tau]


class AgeingLaw(_TapsLaw):
    """Eq. 6 (section III.C): A(t) = A_inf (1 - 1/(1 + B_A ln(1 + t/tau_A))). Parameters
    ``A_inf, B_A, tau_A`` (all > 0)."""

    x_label = "t (taps after the waiting time)"
    y_label = "A(t)"

    names = ("A_inf", "B_A", "tau_A")
    time_scales = ("tau_A",)

    @staticmethod
    def function(t, A_inf, B_A, tau_A):
        return A_inf * (1.0 - 1.0 / (1.0 + _log_term(t, B_A, tau_A)))

    def bounds(self, x, y):
        return ([0.0, 0.0, 0.0], [np.inf] * 3)

    _nonlinear = ("B_A", "tau_A")
    _linear = ("A_inf",)

    def _basis(self, t, B, tau):
        return [1.0 - 1.0 / (1.0 + _log_term(t, B, tau))]

    def initial_guess(self, t, y, w):
        B, tau, (a_inf,) = _grid_inverse_log(t, y, w, 1)
        return [max(a_inf, 1e-300), B, tau]


class TwoExponentials(Law):
    """y(t) = y_inf + a1 exp(-t/tau1) + a2 exp(-t/tau2) with 0 < tau1 <= tau2 (the labels are
    ordered after the fit). Parameters ``y_inf, a1, tau1, a2, tau2``."""

    x_label = "tap t"
    y_label = "<Z>"

    names = ("y_inf", "a1", "tau1", "a2", "tau2")
    may_vanish = ()
    time_scales = ("tau1", "tau2")
    amplitudes = ("y_inf", "a1", "a2")

    @staticmethod
    def function(t, y_inf, a1, tau1, a2, tau2):
        return y_inf + a1 * np.exp(-t / tau1) + a2 * np.exp(-t / tau2)

    def bounds(self, x, y):
        return ([-np.inf, -np.inf, 0.0, -np.inf, 0.0], [np.inf] * 5)

    def initial_guess(self, t, y, w):
        span = np.ptp(t)
        dt = np.min(np.diff(np.unique(t))) if len(np.unique(t)) > 1 else 1.0
        taus = np.geomspace(max(dt * 0.3, span * 1e-4), span * 3.0, 30)
        sw = np.sqrt(w)
        best = (np.inf, None)
        for i, t1 in enumerate(taus):
            e1 = np.exp(-(t - t[0]) / t1)
            for t2 in taus[i + 2:]:
                e2 = np.exp(-(t - t[0]) / t2)
                M = np.stack([np.ones_like(t), e1, e2], axis=1) * sw[:, None]
                coef, *_ = np.linalg.lstsq(M, y * sw, rcond=None)
                sse = np.sum((M @ coef - y * sw) ** 2)
                if sse < best[0]:
                    best = (sse, [coef[0], coef[1] * np.exp(t[0] / t1), t1,
                                  coef[2] * np.exp(t[0] / t2), t2])
        return best[1]

    def _canonical(self, popt, pcov):
        if popt[2] > popt[4]:
            order = [0, 3, 4, 1, 2]
            popt = popt[order]
            pcov = pcov[np.ix_(order, order)]
        return popt, pcov


class StraightLine(Law):
    """y = Phi0 - alpha x (the numerator of eq. 7); parameters ``Phi0, alpha`` (alpha may be 0
    within errors: its sign is the result, so its relative error is not a determination test)."""

    names = ("Phi0", "alpha")
    may_vanish = ("alpha",)

    @staticmethod
    def function(x, Phi0, alpha):
        return Phi0 - alpha * x

    def initial_guess(self, x, y, w):
        slope, intercept = np.polyfit(x, y, 1, w=np.sqrt(w))
        return [intercept, -slope]


def _window(window, boundary):
    if window is None:
        key = str(boundary).lower()
        if key not in PROFILE_WINDOWS:
            raise ValueError(f"boundary = {boundary!r} must be 'fbc' or 'pbc' (or give window)")
        return PROFILE_WINDOWS[key]
    lo, hi = (float(v) for v in window)
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
        raise ValueError(f"window = {window!r} must be (lo, hi) with lo < hi, in units of R")
    return lo, hi


def profile_gradient(zb, phi, window=None, boundary="fbc", sigma=None):
    """The vertical gradient alpha of section IV.A: a straight line Phi0 - alpha zb fitted to
    the profile inside ``window`` (default 5 <= z/R <= 22 for ``boundary`` 'fbc', 26 for 'pbc').
    The bin means of compute stereo/profile are exact slab averages, the "smoothing" of the
    paper. Returns a :class:`FitResult` (params ``Phi0``, ``alpha``)."""
    lo, hi = _window(window, boundary)
    zb = as_1d("zb", zb)
    phi = as_1d("phi", phi)
    same_length("zb", zb, "phi", phi)
    inside = (zb >= lo) & (zb <= hi)
    if inside.sum() < 3:
        raise ValueError(f"window = ({lo:g}, {hi:g}) holds {inside.sum()} profile points; "
                         "at least 3 are needed")
    s = None if sigma is None else np.broadcast_to(np.asarray(sigma, float), zb.shape)[inside]
    return StraightLine().fit(zb[inside], phi[inside], s)


class ProfileLaw(Law):
    """Eq. 7 (section IV.A): Phi(zb) = (Phi0 - alpha zb) / (1 + exp(beta (zb - zb_star))),
    zb = z/R. Parameters ``Phi0, alpha, beta, zb_star`` (beta > 0). The fit uses the points
    with zb >= window[0] (above the wall layers whose peaks eq. 7 does not describe); the
    window (default 5..22 for ``boundary='fbc'``, 5..26 for 'pbc') also sets the starting
    values of (Phi0, alpha) by :func:`profile_gradient`. A negative gradient in the paper's
    wording means the density decreases with height, i.e. alpha > 0 here."""

    x_label = "z/R"
    y_label = "Phi(z)"

    names = ("Phi0", "alpha", "beta", "zb_star")
    may_vanish = ("alpha",)

    def __init__(self, window=None, boundary="fbc"):
        self.window = _window(window, boundary)

    @staticmethod
    def function(zb, Phi0, alpha, beta, zb_star):
        arg = np.clip(beta * (zb - zb_star), -700, 700)
        return (Phi0 - alpha * zb) / (1.0 + np.exp(arg))

    def bounds(self, x, y):
        return ([-np.inf, -np.inf, 0.0, -np.inf], [np.inf] * 4)

    def fit(self, zb, phi, sigma=None, p0=None):
        zb = as_1d("zb", zb)
        phi = as_1d("phi", phi)
        same_length("zb", zb, "phi", phi)
        keep = zb >= self.window[0]
        if keep.sum() < 6:
            raise ValueError(f"only {keep.sum()} profile points above zb = {self.window[0]:g}; "
                             "eq. 7 needs at least 6")
        s = None if sigma is None else np.broadcast_to(np.asarray(sigma, float), zb.shape)[keep]
        return super().fit(zb[keep], phi[keep], s, p0)

    def initial_guess(self, zb, phi, w):
        lo, hi = self.window
        inside = (zb >= lo) & (zb <= hi)
        if inside.sum() >= 3:
            slope, intercept = np.polyfit(zb[inside], phi[inside], 1)
        else:
            slope, intercept = 0.0, np.max(phi)
        plateau = intercept + slope * zb
        ratio = np.where(plateau > 0, phi / np.where(plateau > 0, plateau, 1), 0)
        # zb_star: where the profile falls to half its plateau; width from the 80%..20% points
        above = zb[ratio < 0.5]
        zb_star = above.min() if above.size else zb.max()
        hi80 = zb[(ratio < 0.8) & (zb <= zb_star)]
        lo20 = zb[(ratio < 0.2) & (zb >= zb_star)]
        width = (lo20.min() if lo20.size else zb_star + 1) - (hi80.min() if hi80.size else zb_star - 1)
        beta = 2.0 * np.log(4.0) / max(width, 1e-3)
        return [intercept, -slope, beta, zb_star]



def default_tap_ranges(t):
    """The tap ranges of :func:`range_refits`: [1, T/4], [1, T/2], [1, T] and [T/10, T], T the
    last tap: early and late parts of a run, as a user choosing "the range of taps over which
    the data fitting is performed" (section III.B) would."""
    T = float(np.max(t))
    return [(1.0, T / 4), (1.0, T / 2), (1.0, T), (T / 10, T)]


class RangeRefits:
    """A law refitted over several tap ranges (:func:`range_refits`), the statistic of the
    paper's "the triplet (X_inf, B, tau) ... depends strongly on the range of taps over which
    the data fitting is performed" (section III.B).

    Results: ``reference`` (the fit of all the data, with its profile intervals), ``ranges``
    (list of (first, last) taps), ``fits`` (one :class:`FitResult` per range, None where the
    range holds too few points), ``values`` (dict name -> array over ranges, nan where no fit),
    ``spread`` (dict name -> max - min over the ranges), ``spread_ratio`` (spread / width of
    the reference interval; nan when that interval is open), ``deviation`` (dict name -> the
    largest over the ranges of sqrt(profile delta chi2 of the range's fit at the reference
    value), :meth:`FitResult.profile_delta_chi2`: how many standard deviations each range puts
    between its data and the value fitted on all of them; a likelihood ratio, valid also for
    the skewed profiles of a degenerate law, and 0 for a range whose profile is flat there),
    ``consistent`` (dict name -> deviation <= ``RANGE_Z_LIMIT``) and ``range_dependent`` (the
    names that are not)."""

    def __init__(self, law, reference, ranges, fits):
        self.law = law
        self.reference = reference
        self.ranges = list(ranges)
        self.fits = list(fits)
        self._deviation = None

    @property
    def names(self):
        return list(self.law.names)

    @property
    def values(self):
        return {k: np.array([f.params[k] if f is not None else np.nan for f in self.fits])
                for k in self.names}

    @property
    def spread(self):
        out = {}
        for k, v in self.values.items():
            ok = v[np.isfinite(v)]
            out[k] = float(np.ptp(ok)) if ok.size else np.nan
        return out

    @property
    def spread_ratio(self):
        out = {}
        for k, s in self.spread.items():
            iv = self.reference.intervals[k]
            out[k] = s / (iv.hi - iv.lo) if iv.determined and iv.hi > iv.lo else np.nan
        return out

    @property
    def deviation(self):
        if self._deviation is None:
            out = {}
            for k in self.names:
                ref = self.reference.params[k]
                worst = 0.0
                for f in self.fits:
                    if f is None or not f.converged:
                        continue
                    d = f.profile_delta_chi2(k, ref)
                    if np.isfinite(d) or d == np.inf:
                        worst = max(worst, float(np.sqrt(d)))
                out[k] = worst
            self._deviation = out
        return self._deviation

    @property
    def consistent(self):
        return {k: bool(d <= RANGE_Z_LIMIT) for k, d in self.deviation.items()}

    @property
    def range_dependent(self):
        return [k for k, ok in self.consistent.items() if not ok]

    def __repr__(self):
        dev = ", ".join(f"{k} {v:.3g}" for k, v in self.deviation.items())
        return (f"<RangeRefits {type(self.law).__name__} over {len(self.ranges)} ranges: "
                f"deviation {dev}; range dependent: {self.range_dependent or 'none'}>")


def range_refits(law, t, y, sigma=None, ranges=None):
    """Refit ``law`` to (t, y, sigma) over several tap ranges (default
    :func:`default_tap_ranges`: [1, T/4], [1, T/2], [1, T], [T/10, T]) and compare each
    parameter across them with the profile intervals: returns a :class:`RangeRefits`. A range
    with fewer points than the law has parameters plus 2 gets no fit (None)."""
    if not isinstance(law, Law):
        raise ValueError(f"law = {law!r} must be a tapmc.laws.Law")
    t = as_1d("t", t)
    y = as_1d("y", y)
    same_length("t", t, "y", y)
    s = None if sigma is None else np.broadcast_to(np.asarray(sigma, dtype=float), t.shape)
    ranges = default_tap_ranges(t) if ranges is None else [tuple(map(float, r)) for r in ranges]
    for r in ranges:
        if len(r) != 2 or not r[0] < r[1]:
            raise ValueError(f"ranges entry {r!r} must be (first, last) with first < last")
    reference = law.fit(t, y, s).improved()
    fits = []
    for first, last in ranges:
        keep = (t >= first) & (t <= last)
        if keep.sum() < len(law.names) + 2:
            fits.append(None)
            continue
        sk = None if s is None else s[keep]
        # the law's own global start, and the reference values: the better of the two fits
        own = law.fit(t[keep], y[keep], sk)
        near = law.fit(t[keep], y[keep], sk, p0=list(reference.params.values()))
        fits.append(near if near.converged and not (near.chi2 >= own.chi2) else own)
    return RangeRefits(law, reference, ranges, fits)


class LogLinear(Law):
    """ln y = ln_y0 + slope x, fitted in ln y: the exponential dependence y = y0 exp(slope x)
    of section III.A ("B is consistent with an exponential dependence on eps^(1/2)")."""

    names = ("ln_y0", "slope")
    may_vanish = ("ln_y0", "slope")

    @staticmethod
    def function(x, ln_y0, slope):
        return ln_y0 + slope * x

    def initial_guess(self, x, y, w):
        slope, intercept = np.polyfit(x, y, 1, w=np.sqrt(w))
        return [intercept, slope]


class ExponentialDependence:
    """Result of :func:`exponential_dependence`: ``fit`` (the :class:`LogLinear` FitResult of
    ln B against sqrt(eps), None with fewer than 2 determined B), ``slope`` and
    ``slope_interval`` (the 68 % profile :class:`Interval`, rescaled by the reduced chi2 when
    that exceeds 1), ``reduced_chi2``, ``dof``, ``p_value`` (chi2 probability of the straight
    line; nan with no degree of freedom), ``linear`` (p_value >= ``LINEARITY_P_MIN``; None when
    not testable: fewer than 3 determined B), ``used`` and ``excluded`` (the sqrt(eps) whose B
    is determined and enters the fit, and those whose B interval is open)."""

    def __init__(self, fit, used, excluded):
        self.fit = fit
        self.used = np.asarray(used, dtype=float)
        self.excluded = np.asarray(excluded, dtype=float)

    @property
    def slope(self):
        return float(self.fit.params["slope"]) if self.fit is not None else np.nan

    @property
    def slope_interval(self):
        return self.fit.intervals["slope"] if self.fit is not None else None

    @property
    def dof(self):
        return self.fit.dof if self.fit is not None else 0

    @property
    def reduced_chi2(self):
        return float(self.fit.reduced_chi2) if self.fit is not None and self.dof > 0 else np.nan

    @property
    def p_value(self):
        if self.fit is None or self.dof <= 0:
            return np.nan
        return float(chi2_distribution.sf(self.fit.chi2, self.dof))

    @property
    def linear(self):
        return None if not np.isfinite(self.p_value) else bool(self.p_value >= LINEARITY_P_MIN)

    def __repr__(self):
        if self.fit is None:
            return (f"<ExponentialDependence: not testable, {self.used.size} determined B "
                    f"(excluded sqrt(eps) {list(self.excluded)})>")
        iv = self.slope_interval
        return (f"<ExponentialDependence: slope {self.slope:.4g} [{iv.lo:.4g}, {iv.hi:.4g}], "
                f"reduced chi2 {self.reduced_chi2:.3g} ({self.dof} dof), p {self.p_value:.3g}, "
                f"linear {self.linear}>")


def exponential_dependence(sqrt_eps, B, B_lo, B_hi):
    """Test "B is consistent with an exponential dependence on eps^(1/2)" (section III.A): a
    weighted straight line through ln B against sqrt(eps), the error of ln B being half the
    width of its 68 % interval in log, (ln B_hi - ln B_lo) / 2 (the profile intervals of the
    eq. 3 or eq. 4 fits, :attr:`FitResult.intervals`). Points whose interval is open (nan
    bound: B undetermined) are left out and listed in ``excluded``; a B that is undetermined
    carries no information on its eps dependence. Returns an :class:`ExponentialDependence`."""
    x = as_1d("sqrt_eps", sqrt_eps)
    b = as_1d("B", B, finite=False)
    lo = as_1d("B_lo", B_lo, finite=False)
    hi = as_1d("B_hi", B_hi, finite=False)
    for name, arr in (("B", b), ("B_lo", lo), ("B_hi", hi)):
        same_length("sqrt_eps", x, name, arr)
    ok = np.isfinite(b) & np.isfinite(lo) & np.isfinite(hi) & (lo > 0) & (hi > lo) & (b > 0)
    if ok.sum() < 2:
        return ExponentialDependence(None, x[ok], x[~ok])
    sig = 0.5 * (np.log(hi[ok]) - np.log(lo[ok]))
    law = LogLinear()
    if ok.sum() == 2:  # a line through two points: exact, no degree of freedom
        x2, y2 = x[ok], np.log(b[ok])
        slope = (y2[1] - y2[0]) / (x2[1] - x2[0])
        err = np.hypot(sig[0], sig[1]) / abs(x2[1] - x2[0])
        popt = [y2[0] - slope * x2[0], slope]
        cov = np.full((2, 2), np.nan)
        cov[1, 1] = err ** 2
        res = FitResult(law, law.names, popt, cov, x2, y2, sig, True, "", True)
        res._intervals = {"ln_y0": Interval(popt[0], None, None, (-np.inf, np.inf), "exact"),
                          "slope": Interval(slope, slope - err, slope + err,
                                            (-np.inf, np.inf), "curvature")}
        return ExponentialDependence(res, x[ok], x[~ok])
    return ExponentialDependence(law.fit(x[ok], np.log(b[ok]), sig), x[ok], x[~ok])


def realization_bin_covariance(per_run):
    """(means, covariance of the means, whitening matrix) of bin means over independent
    realizations: ``per_run`` has one row per realization, one column per bin; the covariance
    is the sample covariance over the n realizations divided by n, and the whitening matrix
    W has W^T W = its inverse."""
    per_run = np.asarray(per_run, dtype=float)
    n = per_run.shape[0]
    means = per_run.mean(axis=0)
    cov = np.atleast_2d(np.cov(per_run, rowvar=False, ddof=1)) / n
    try:
        whiten = np.linalg.inv(np.linalg.cholesky(cov))
    except np.linalg.LinAlgError:
        raise ValueError("the realizations' bin means have a singular covariance "
                         "(identical realizations?)") from None
    return means, cov, whiten


def hotelling_gls(means, whiten, model, starts, lo, hi, realizations):
    """GLS fit of ``model(q)`` (one value per bin) to the bin means of ``realizations``
    independent realizations (:func:`realization_bin_covariance`), from each of ``starts``
    within the bounds (lo, hi), the best kept. Its minimum chi-square is Hotelling's T^2 in
    the q = bins - parameters directions the model cannot absorb, so F = (n - q) T^2 / (q (n -
    1)) follows F(q, n - q) when the model holds (exact for a model linear in its parameters
    and Gaussian bin means, the usual linearisation otherwise). Returns dict ``x`` (best
    parameters), ``errors`` (curvature errors, diagnostics only), ``chi2`` (T^2), ``dof`` (q),
    ``F``, ``p_value``, ``realizations``, ``bin_model``."""
    n, bins = int(realizations), len(means)
    starts = [np.asarray(s, dtype=float) for s in starts]
    p = starts[0].size
    q = bins - p
    if q < 1 or n <= bins:
        raise ValueError(f"{bins} bins, {p} parameters and {n} realizations: the test needs "
                         "realizations > bins > parameters")

    def residual(x):
        return whiten @ (means - model(x))

    lo = np.broadcast_to(lo, (p,)).astype(float)
    hi = np.broadcast_to(hi, (p,)).astype(float)
    lo_in = lo + 1e-9 * (1.0 + np.abs(np.where(np.isfinite(lo), lo, 0.0)))
    hi_in = hi - 1e-9 * (1.0 + np.abs(np.where(np.isfinite(hi), hi, 0.0)))
    fit = None
    for start in starts:
        start = np.where(np.isfinite(lo) & (start <= lo), lo_in, start)
        start = np.where(np.isfinite(hi) & (start >= hi), hi_in, start)
        with np.errstate(all="ignore"):
            trial = least_squares(residual, start, bounds=(lo, hi), method="trf",
                                  x_scale="jac", max_nfev=20000)
        if fit is None or trial.cost < fit.cost:
            fit = trial
    chi2 = float(np.sum(fit.fun ** 2))
    F = (n - q) * chi2 / (q * (n - 1))
    with np.errstate(all="ignore"):
        errors = np.sqrt(np.diag(np.linalg.pinv(fit.jac.T @ fit.jac)))
    return dict(x=[float(v) for v in fit.x], errors=[float(v) for v in errors], chi2=chi2,
                dof=q, F=float(F), p_value=float(f_distribution.sf(F, q, n - q)),
                realizations=n, bin_model=model(fit.x))


class _Computed:
    """Results that exist once ``compute`` has run: ``_result`` (a dict) is None before, and
    every result property (:func:`_result_property`) says which call fills it."""

    #: the call that fills the results, as the error before it names it
    _compute_call = "compute(...)"
    _result = None

    def _get(self, key):
        if self._result is None:
            raise RuntimeError(f"call {self._compute_call} first")
        return self._result[key]


def _result_property(key):
    """A read-only property returning the computed result ``key`` of a :class:`_Computed`."""
    return property(lambda self: self._get(key))


class RealizationLawTest(_Computed):
    """Is a law compatible with the mean of independent realizations of the same process?

    The taps of one run are correlated (their spectrum is a power law, Fig. 3), so a
    chi-square over the taps of one run, or over the mean of a few runs with per-tap errors,
    does not have its textbook distribution. Independent realizations give the covariance
    between times instead. The taps ``t >= t_min`` are cut into ``bins`` log-spaced bins
    (default: as many as the realizations allow, at most :data:`REALIZATION_MAX_BINS`); every
    realization gives one mean per bin; their sample covariance S (n realizations) gives the
    covariance S/n of the bins' means over realizations. The law, averaged over each bin's
    taps, is fitted to those means by generalized least squares with that covariance (for
    eqs. 3, 4 and 6 by variable projection: see :meth:`_projected_starts`). Its minimum
    chi-square is Hotelling's T^2 in the q = bins - parameters directions the law cannot
    absorb (exact for a law linear in its parameters and Gaussian bin means, the usual
    linearisation otherwise), so
    F = (n - q) T^2 / (q (n - 1)) follows F(q, n - q) when the law holds; ``p_value`` is its
    upper tail. Needs n >= bins + 1 >= parameters + 2.

    ``compute(t, curves)``: ``curves`` has one row per realization, one column per tap of
    ``t``. Results: ``params`` (dict), ``errors`` (curvature errors of the GLS fit, for
    diagnostics only: with a covariance estimated from 9 realizations they cover the true
    value in about 40 % of cases, not 68 %),
    ``chi2`` (T^2), ``dof`` (q), ``F``, ``p_value``, ``compatible`` (p_value >=
    :data:`REALIZATION_P_MIN`), ``realizations``, ``bin_edges``, ``bin_means``,
    ``bin_sem``, ``bin_model``.
    """

    def __init__(self, law, bins=None, t_min=1.0):
        if not isinstance(law, Law):
            raise TypeError(f"law must be a tapmc.laws.Law, got {type(law).__name__}")
        self.law = law
        self.p = len(law.names)
        if bins is not None and (int(bins) != bins or bins < self.p + 1):
            raise ValueError(f"bins = {bins}: must be an integer >= {self.p + 1} (the law's "
                             f"{self.p} parameters + 1)")
        self.bins = None if bins is None else int(bins)
        self.t_min = float(t_min)
        self._result = None

    def compute(self, t, curves):
        t = as_1d("t", t)
        curves = np.asarray(curves, dtype=float)
        if curves.ndim != 2 or curves.shape[1] != t.size:
            raise ValueError(f"curves must have shape (realizations, {t.size}), got "
                             f"{curves.shape}")
        if not np.all(np.isfinite(curves)):
            raise ValueError("curves must be finite")
        n = curves.shape[0]
        bins = self.bins if self.bins is not None else min(REALIZATION_MAX_BINS, n - 1)
        if n < bins + 1 or bins < self.p + 1:
            raise ValueError(f"{n} realizations: a test of {self.p} parameters needs at least "
                             f"{self.p + 2} (realizations > bins > parameters)")
        keep = t >= self.t_min
        t, curves = t[keep], curves[:, keep]
        edges = np.unique(np.round(np.geomspace(t.min(), t.max() + 1, bins + 1)))
        if edges.size != bins + 1:
            raise ValueError(f"taps {t.min():g}-{t.max():g} are too few for {bins} "
                             "log-spaced bins")
        which = np.searchsorted(edges, t, side="right") - 1
        members = [which == b for b in range(bins)]
        if any(not m.any() for m in members):
            raise ValueError(f"a log-spaced bin of taps {t.min():g}-{t.max():g} is empty")
        per_run = np.stack([curves[:, m].mean(axis=1) for m in members], axis=1)
        means, cov, whiten = realization_bin_covariance(per_run)
        binning = np.stack([m / m.sum() for m in members])          # (bins, taps)

        def model(q):
            return binning @ self.law.function(t, *q)

        first = self.law.fit(t, curves.mean(axis=0)).params
        first = np.array([first[k] for k in self.law.names], dtype=float)
        starts = self._projected_starts(t, binning, means, cov, first) or [first]
        lo, hi = self.law.bounds(t, means)
        fit = hotelling_gls(means, whiten, model, starts, lo, hi, n)
        self._result = dict(fit, params=dict(zip(self.law.names, fit["x"])),
                            errors=dict(zip(self.law.names, fit["errors"])),
                            bin_edges=edges, bin_means=means, bin_sem=np.sqrt(np.diag(cov)))
        return self

    def _projected_starts(self, t, binning, means, cov, first):
        """Starts of the GLS fit, best first, for a law of the taps that is linear in its
        amplitudes once (B, tau) are fixed (:class:`_TapsLaw`); [] for another law.

        The amplitudes are solved by GLS in the law's linear space (the bin means' covariance
        carried there to first order) for every (B, tau), which leaves a fit of (ln B, ln tau)
        alone (variable projection). It starts from the law's fit of the mean curve and from
        the :data:`_GRID_STARTS` best nodes of a (B, tau) grid: the law's own fit weighs
        taps, not bins, and can sit in another minimum of the GLS. The GLS of all parameters
        then only polishes the best of them (exact for eqs. 3 and 6, whose amplitudes are
        linear in the data's own space), instead of wandering along the valley of (B, tau) from each
        start."""
        law = self.law
        if not isinstance(law, _TapsLaw) or not law._linear or np.any(means <= 0):
            return []
        target, weight = law._target(means, np.ones_like(means))
        scale = 1.0 / np.sqrt(weight)                  # |d target / d mean|
        try:
            whiten = np.linalg.inv(np.linalg.cholesky(cov * np.outer(scale, scale)))
        except np.linalg.LinAlgError:
            return []
        y = whiten @ target
        iB, itau = (law.names.index(k) for k in law._nonlinear)

        def design(B, tau):                            # (..., bins, amplitudes)
            columns = law._basis(t[None, :], np.atleast_1d(B)[:, None],
                                 np.atleast_1d(tau)[:, None])
            return np.stack([np.broadcast_to(c, (np.size(B), t.size)) @ binning.T @ whiten.T
                             for c in columns], axis=2)

        def amplitudes(A):
            return _solve_nodes(np.einsum("kba,kbc->kac", A, A), np.einsum("kba,b->ka", A, y))

        lo_d, hi_d, num = law._GRID_TAU_DECADES
        taus = np.geomspace(t.min() * 10 ** lo_d, t.max() * 10 ** hi_d, num)
        BB, TT = (a.ravel() for a in np.meshgrid(law._GRID_B, taus, indexing="ij"))
        with np.errstate(all="ignore"):
            A = design(BB, TT)
            cost = np.sum((np.einsum("kba,ka->kb", A, amplitudes(A)) - y) ** 2, axis=1)
        cost = np.where(np.isfinite(cost), cost, np.inf)
        nodes = [(first[iB], first[itau])] + [
            (BB[k], TT[k]) for k in np.argsort(cost)[:_GRID_STARTS] if np.isfinite(cost[k])]
        # ln B and ln tau stay within the grid widened by a decade each side; the polish
        # that follows has the law's own bounds
        lo = np.log([law._GRID_B[0] / 10.0, taus[0] / 10.0])
        hi = np.log([law._GRID_B[-1] * 10.0, taus[-1] * 10.0])

        def residual(u):
            A = design(np.exp(u[0]), np.exp(u[1]))
            r = (A @ amplitudes(A)[..., None])[0, :, 0] - y
            return np.where(np.isfinite(r), r, 1e150)

        found = []
        for B, tau in nodes:
            if not (np.isfinite(B) and np.isfinite(tau) and B > 0 and tau > 0):
                continue
            u0 = np.clip(np.log([B, tau]), lo + 1e-9, hi - 1e-9)
            with np.errstate(all="ignore"):
                fit = least_squares(residual, u0, bounds=(lo, hi), method="trf",
                                    x_scale=1.0, max_nfev=400)
                B, tau = np.exp(fit.x)
                amps = amplitudes(design(B, tau))[0]
            p = np.empty(self.p)
            for name, v in zip(law._linear, law._amplitudes_to_params(amps)):
                p[law.names.index(name)] = v
            p[iB], p[itau] = B, tau
            if np.all(np.isfinite(p)):
                found.append((fit.cost, p))
        found.sort(key=lambda node: node[0])
        return [p for _, p in found[:_POLISHED_STARTS]]

    _compute_call = "compute(t, curves)"

    params = _result_property("params")
    errors = _result_property("errors")
    chi2 = _result_property("chi2")
    dof = _result_property("dof")
    F = _result_property("F")
    p_value = _result_property("p_value")
    realizations = _result_property("realizations")
    bin_edges = _result_property("bin_edges")
    bin_means = _result_property("bin_means")
    bin_sem = _result_property("bin_sem")
    bin_model = _result_property("bin_model")

    @property
    def compatible(self):
        return bool(self.p_value >= REALIZATION_P_MIN)

    def __repr__(self):
        if self._result is None:
            return f"<RealizationLawTest of {type(self.law).__name__}: not computed>"
        return (f"<RealizationLawTest of {type(self.law).__name__}: T2 {self.chi2:.3g} "
                f"({self.dof} dof, {self.realizations} realizations), F {self.F:.3g}, "
                f"p {self.p_value:.3g}>")


class _RangeTested(_Computed):
    """Fits over tap ranges with a p-value per parameter (``range_p``) and a level ``p_min``."""

    @property
    def range_dependent(self):
        """The parameters whose range test rejects one value over the ranges."""
        return [k for k, p in self.range_p.items() if np.isfinite(p) and p < self.p_min]


class SurrogateFits(_RangeTested):
    """How well does one run fix a law's parameters, and do they depend on the fitted range?

    One run's taps are correlated (their spectrum is a power law, Fig. 3), so the profile
    intervals of :meth:`Law.fit` and the tests of :func:`range_refits`, which treat the
    scatter about the law as independent, are too narrow. Here the law is fitted to the run;
    its residuals give ``surrogates`` new series with the same periodogram (Fourier
    surrogates: the residuals' Fourier amplitudes with uniform random phases, which keep their
    autocovariance, long-range part included, up to the run's length) added to the fitted
    curve; every surrogate is fitted again, over all taps and over each range of
    :func:`default_tap_ranges` that is not all of them, exactly as the run is.

    The fits are least squares in the law's linear space (eq. 3 as it is, eq. 4 in 1/<Z> with
    first-order weights) with the amplitudes solved exactly for every (B, tau): a fit of
    (ln B, ln tau) alone, from the best node of a (B, tau) grid and from the run's values,
    inside B's and tau's allowed ranges (:data:`POSITIVE_DECADES` about the run's B,
    :data:`TIME_SCALE_DECADES` beyond the taps for tau): a tenth of a second where a free
    four-parameter fit wanders for seconds along a degenerate valley. B and tau are compared
    in ln, the amplitudes as they are.

    * A parameter is *determined* when half the 16-84 % width of its surrogate values is at
      most :data:`RELATIVE_ERROR_LIMIT` of its fitted value (in ln: at most
      ln :data:`DETERMINED_FACTOR`, a factor of 2); a fit whose (B, tau) sits on the edge of
      its allowed range counts as unbounded, and the run's own fit there leaves every
      parameter undetermined.
    * The residuals hold what the fit did not absorb: the part of the noise along the law's
      own directions is missing from them, and any misfit of the law is in them as if it were
      noise. Under noise with a power-law spectrum the 16-84 % band is therefore narrower
      than the spread of independent realizations where they fix a parameter
      (test_slow_surrogate_fits.py), and a misfit
      widens it instead of showing as a range dependence. "Undetermined" and "not unique"
      are the verdicts this test can give safely; "determined" is an upper bound on what
      one run shows.
    * A parameter *depends on the range* when, over the ranges, the largest
      |range value - all-taps value| / (its spread over the surrogates) is exceeded in at most
      a fraction ``p_min`` of the surrogates (the same statistic there, where the law holds by
      construction).

    ``law``: a law of the taps linear in its amplitudes (:class:`InverseLogLaw`,
    :class:`ZLaw`, :class:`AgeingLaw`). ``compute(t, y)``: one value per tap of consecutive
    taps ``t``; taps below ``t_min`` are left out. Results: ``params`` (the run's fit),
    ``samples`` (dict name -> values over the surrogates, B and tau in ln), ``log_scale``,
    ``low`` and ``high`` (16 and 84 % of the surrogates, in the parameter's units),
    ``half_width`` (in the comparison scale), ``determined`` (dict), ``range_p`` (dict name
    -> p-value), ``range_dependent`` (names), ``unique`` (every parameter determined and none
    range dependent), ``ranges``, ``used`` (surrogates fitted)."""

    #: nodes per axis of the (B, tau) grid that gives each fit a global start (B over the
    #: laws' grid span, tau two decades beyond the taps): 9 x 9 finds the valley, the
    #: refinement does the rest
    _GRID_NODES = 9

    def __init__(self, law, surrogates=None, ranges=None, t_min=1.0, seed=0, p_min=None):
        if not isinstance(law, _TapsLaw) or not law._linear:
            raise TypeError(f"law must be a law of the taps linear in its amplitudes "
                            f"(InverseLogLaw, ZLaw, AgeingLaw), got {type(law).__name__}")
        surrogates = SURROGATES if surrogates is None else surrogates
        p_min = SURROGATE_P_MIN if p_min is None else p_min
        if int(surrogates) != surrogates or surrogates < 20:
            raise ValueError(f"surrogates = {surrogates}: must be an integer >= 20 (the 16 "
                             "and 84 % points and a 5 % tail need that many)")
        if not 0.0 < p_min < 0.5:
            raise ValueError(f"p_min = {p_min}: must be in (0, 0.5)")
        if not t_min > 0:
            raise ValueError(f"t_min = {t_min}: must be > 0 (tau's allowed range starts "
                             "from the first tap fitted)")
        self.law = law
        self.surrogates = int(surrogates)
        self.ranges = None if ranges is None else [tuple(map(float, r)) for r in ranges]
        self.t_min = float(t_min)
        self.seed = seed
        self.p_min = float(p_min)
        self._result = None

    @staticmethod
    def fourier_surrogate(x, rng):
        """A series with the periodogram of ``x`` and random phases (mean of ``x`` kept)."""
        spectrum = np.fft.rfft(x - x.mean())
        phases = rng.uniform(0.0, 2.0 * np.pi, spectrum.size)
        phases[0] = 0.0
        if x.size % 2 == 0:
            phases[-1] = 0.0  # the Nyquist term stays real
        return np.fft.irfft(np.abs(spectrum) * np.exp(1j * phases), n=x.size) + x.mean()

    def _amplitudes(self, t, target, sw, B, tau):
        """(amplitudes, weighted residuals) of the linear least squares at fixed (B, tau)."""
        A = np.stack(self.law._basis(t, B, tau), axis=1) * sw[:, None]
        coef, *_ = np.linalg.lstsq(A, target * sw, rcond=None)
        return coef, target * sw - A @ coef

    def _fit(self, t, y, starts):
        """Comparison-scale parameters (nan where they do not exist) of the fit of (t, y)."""
        law = self.law
        target, w = law._target(y, np.ones_like(y))
        sw = np.sqrt(w)
        taus = np.geomspace(t.min() * 1e-2, t.max() * 1e2, self._GRID_NODES)
        Bs = np.geomspace(law._GRID_B[0], law._GRID_B[-1], self._GRID_NODES)
        BB, TT = (a.ravel() for a in np.meshgrid(Bs, taus, indexing="ij"))
        with np.errstate(all="ignore"):
            A = np.stack([np.broadcast_to(c, (BB.size, t.size)) * sw
                          for c in law._basis(t[None, :], BB[:, None], TT[:, None])], axis=1)
            normal = A @ A.transpose(0, 2, 1)                            # (nodes, amps, amps)
            rhs = A @ (target * sw)
            # |r|^2 = |y|^2 - rhs . coef for the least-squares amplitudes (collinear: inf)
            cost = np.sum((target * sw) ** 2) - np.sum(rhs * _solve_nodes(normal, rhs), axis=1)
            cost = np.where(np.isfinite(cost), cost, np.inf)
        best = int(np.argmin(cost))
        starts = list(starts) + ([(BB[best], TT[best])] if np.isfinite(cost[best]) else [])
        lo, hi = self._bounds

        def residual(u):
            return self._amplitudes(t, target, sw, np.exp(u[0]), np.exp(u[1]))[1]

        fit = None
        for B, tau in starts:
            u0 = np.clip(np.log([B, tau]), lo + 1e-9, hi - 1e-9)
            with np.errstate(all="ignore"):
                trial = least_squares(residual, u0, bounds=(lo, hi), method="trf",
                                      x_scale=1.0, max_nfev=400)
            if fit is None or trial.cost < fit.cost:
                fit = trial
        B, tau = np.exp(fit.x)
        coef, _ = self._amplitudes(t, target, sw, B, tau)
        values = dict(zip(law._nonlinear, (B, tau)))
        with np.errstate(all="ignore"):
            values.update(zip(law._linear, law._amplitudes_to_params(coef)))
        row = np.array([np.log(values[k]) if self._log[k] else values[k]
                        for k in law.names], dtype=float)
        # (B, tau) on the edge of its allowed range: the data fix none of the parameters
        # there (the amplitudes follow the edge), so the surrogate counts as unbounded
        at_edge = bool(np.any(np.minimum(fit.x - lo, hi - fit.x) < _EDGE_TOLERANCE))
        return row, at_edge

    def _fits(self, t, y, start):
        """Rows: all taps, then each range (starting from the all-taps fit)."""
        row, edge = self._fit(t, y, [start])
        rows, edges = [row], [edge]
        iB, itau = (self.law.names.index(k) for k in self.law._nonlinear)
        own = (np.exp(row[iB]), np.exp(row[itau]))
        for first, last in self._ranges:
            keep = (t >= first) & (t <= last)
            row, edge = self._fit(t[keep], y[keep], [own])
            rows.append(row)
            edges.append(edge)
        return np.array(rows), np.array(edges)

    def compute(self, t, y):
        law = self.law
        t = as_1d("t", t)
        y = as_1d("y", y)
        same_length("t", t, "y", y)
        keep = t >= self.t_min
        t, y = t[keep], y[keep]
        need = 3 * (len(law.names) + 2)
        if t.size < need:
            raise ValueError(f"{t.size} taps from t_min = {self.t_min:g}: a surrogate test of "
                             f"{len(law.names)} parameters needs at least {need}")
        if np.any(np.diff(t) != 1.0):
            raise ValueError("t must be consecutive taps (the surrogates keep the residuals' "
                             "correlation between successive taps)")
        ranges = default_tap_ranges(t) if self.ranges is None else self.ranges
        self._ranges = [r for r in ranges
                        if not (r[0] <= t.min() and r[1] >= t.max())
                        and ((t >= r[0]) & (t <= r[1])).sum() >= len(law.names) + 2]
        first = law.fit(t, y).params
        self._log = {k: k in law._nonlinear for k in law.names}
        B0, tau0 = (first[k] for k in law._nonlinear)
        if not (np.isfinite(B0) and B0 > 0 and np.isfinite(tau0) and tau0 > 0):
            raise ValueError(f"the law's fit of this run has B = {B0:g}, tau = {tau0:g}: "
                             "the logarithmic law does not describe it")
        self._bounds = (np.array([np.log(B0) - POSITIVE_DECADES * np.log(10.0),
                                  np.log(t.min()) - TIME_SCALE_DECADES * np.log(10.0)]),
                        np.array([np.log(B0) + POSITIVE_DECADES * np.log(10.0),
                                  np.log(t.max()) + TIME_SCALE_DECADES * np.log(10.0)]))
        start = (B0, tau0)
        observed, observed_edge = self._fits(t, y, start)
        ref = observed[0]
        params = {k: float(np.exp(v) if self._log[k] else v) for k, v in zip(law.names, ref)}
        curve = law.function(t, *[params[k] for k in law.names])
        if not np.all(np.isfinite(curve)):
            raise ValueError("the law's fit of this run is not finite at every tap")
        residuals = y - curve
        rng = np.random.default_rng(self.seed)
        runs, edges = [], []
        for _ in range(self.surrogates):
            r, e = self._fits(t, curve + self.fourier_surrogate(residuals, rng), start)
            runs.append(r)
            edges.append(e)
        runs, edges = np.array(runs), np.array(edges)    # (S, 1 + ranges, params), (S, ...)
        runs = np.where(np.isfinite(runs) & ~edges[:, :, None], runs, np.inf)
        observed = np.where(observed_edge[:, None], np.nan, observed)
        full = runs[:, 0, :]
        with np.errstate(invalid="ignore"):  # unbounded surrogates: inf, and inf - inf
            q16, q84 = np.percentile(full, [16.0, 84.0], axis=0)
            half = (q84 - q16) / 2.0
        determined = {}
        for i, k in enumerate(law.names):
            limit = (np.log(DETERMINED_FACTOR) if self._log[k]
                     else RELATIVE_ERROR_LIMIT * abs(ref[i]))
            determined[k] = bool(np.isfinite(half[i]) and half[i] <= limit
                                 and not observed_edge[0])
        range_p = {k: np.nan for k in law.names}
        if self._ranges:
            with np.errstate(invalid="ignore", divide="ignore"):
                dev = runs[:, 1:, :] - runs[:, :1, :]                # (S, ranges, params)
                obs = observed[1:] - observed[:1]
                for i, k in enumerate(law.names):
                    d = dev[:, :, i]
                    d = d[np.all(np.isfinite(d), axis=1)]
                    if d.shape[0] < 20 or not np.all(np.isfinite(obs[:, i])):
                        continue
                    spread = np.std(d, axis=0, ddof=1)
                    z_sur = np.max(np.abs(d / spread), axis=1)
                    z_obs = np.max(np.abs(obs[:, i] / spread))
                    range_p[k] = float((1 + np.sum(z_sur >= z_obs)) / (1 + d.shape[0]))
        back = {k: (np.exp if self._log[k] else float) for k in law.names}
        self._result = dict(
            params=params, samples={k: full[:, i] for i, k in enumerate(law.names)},
            low={k: float(back[k](q16[i])) for i, k in enumerate(law.names)},
            high={k: float(back[k](q84[i])) for i, k in enumerate(law.names)},
            half_width={k: float(half[i]) for i, k in enumerate(law.names)},
            determined=determined, range_p=range_p, used=int(runs.shape[0]),
            log_scale=dict(self._log), ranges=list(self._ranges))
        return self

    _compute_call = "compute(t, y)"

    params = _result_property("params")
    samples = _result_property("samples")
    low = _result_property("low")
    high = _result_property("high")
    half_width = _result_property("half_width")
    determined = _result_property("determined")
    range_p = _result_property("range_p")
    used = _result_property("used")
    log_scale = _result_property("log_scale")
    fitted_ranges = _result_property("ranges")

    @property
    def unique(self):
        return all(self.determined.values()) and not self.range_dependent

    def __repr__(self):
        if self._result is None:
            return f"<SurrogateFits of {type(self.law).__name__}: not computed>"
        undetermined = [k for k, d in self.determined.items() if not d]
        return (f"<SurrogateFits of {type(self.law).__name__} over {self.used} surrogates: "
                f"undetermined {undetermined or 'none'}; range dependent "
                f"{self.range_dependent or 'none'}>")


def spread_interval(values, level=0.95):
    """(sd, low, high): the sample standard deviation of ``values`` (n >= 2, normal) and its
    two-sided chi-square confidence interval at ``level`` (n - 1 dof)."""
    values = as_1d("values", values)
    if values.size < 2:
        raise ValueError(f"{values.size} value(s): a spread needs at least 2")
    if not 0.0 < level < 1.0:
        raise ValueError(f"level = {level}: must be in (0, 1)")
    dof = values.size - 1
    tail = (1.0 - level) / 2.0
    sd = float(np.std(values, ddof=1))
    return (sd, sd * float(np.sqrt(dof / chi2_distribution.ppf(1.0 - tail, dof))),
            sd * float(np.sqrt(dof / chi2_distribution.ppf(tail, dof))))


def spread_verdict(low, high, limit):
    """Is a spread with confidence interval (low, high) within ``limit``? True when all of
    the interval is, False when none of it is, None when the data cannot tell."""
    if low > limit:
        return False
    return True if high <= limit else None


class RealizationFits(_RangeTested):
    """Do independent realizations fix a law's parameters, and do they depend on the range of
    taps fitted? The question :class:`SurrogateFits` answers from one run (safely only for
    "undetermined"), answered from a few realizations of the same process.

    Every realization is fitted on its own (the law's :meth:`Law.fit`) over all taps and over
    each tap range; B and tau are compared in ln, the amplitudes as they are.

    * A parameter's *spread* is the sample standard deviation of its fitted values over the
      realizations (for normal values half the 16-84 % width, the quantity
      :class:`SurrogateFits` bounds). With few realizations it carries the chi-square interval
      of ``level`` (n - 1 dof, :func:`spread_interval`): the parameter is *determined* (True,
      :func:`spread_verdict`) when the upper end is at
      most ln :data:`DETERMINED_FACTOR` (B, tau) or :data:`RELATIVE_ERROR_LIMIT` times |mean|
      (amplitudes),
      *undetermined* (False) when the lower end exceeds that limit, and None (the
      realizations cannot tell) in between. A realization whose fit is not finite, or not
      positive for a parameter compared in ln, fixes nothing: spread infinite.
    * A range *shifts* a parameter by the mean over realizations of (range fit - all-taps
      fit), with its t interval (n - 1 dof). The parameter *depends on the range* when the
      smallest two-sided t-test p over the ranges, times their number (Bonferroni), is below
      ``p_min`` (:data:`SURROGATE_P_MIN`, the surrogates' level). ``range_bound``, the
      largest |shift| + t sem, is reported (seed-fits writes it), not used by the verdict: a
      range that starts after the law's curvature (T/10 to T) leaves tau free in every
      realization, so it bounds nothing even where the law holds.
    * ``unique`` (as :class:`SurrogateFits` defines it): True when every parameter is
      determined and none range dependent, False when one is undetermined or range
      dependent, None otherwise.

    ``compute(t, curves)``: one row per realization (n >= 2), one column per tap of ``t``;
    taps below ``t_min`` are left out. Results: ``values`` (name -> fitted values over the
    realizations, comparison scale), ``mean`` (back in the parameter's units), ``spread``,
    ``spread_low``, ``spread_high``, ``limit`` (comparison scale), ``determined``,
    ``range_shift`` (name -> largest |shift|), ``range_bound`` (name -> largest
    |shift| + t sem), ``range_p``, ``range_dependent`` (names), ``unique``, ``log_scale``,
    ``realizations``, ``fitted_ranges``."""

    def __init__(self, law, ranges=None, t_min=1.0, level=0.95, p_min=None):
        if not isinstance(law, _TapsLaw) or not law._linear:
            raise TypeError(f"law must be a law of the taps with (B, tau) (InverseLogLaw, ZLaw, "
                            f"AgeingLaw), got {type(law).__name__}")
        p_min = SURROGATE_P_MIN if p_min is None else p_min
        if not 0.0 < level < 1.0:
            raise ValueError(f"level = {level}: must be in (0, 1)")
        if not 0.0 < p_min < 0.5:
            raise ValueError(f"p_min = {p_min}: must be in (0, 0.5)")
        if not t_min > 0:
            raise ValueError(f"t_min = {t_min}: must be > 0")
        self.law = law
        self.ranges = None if ranges is None else [tuple(map(float, r)) for r in ranges]
        self.t_min = float(t_min)
        self.level = float(level)
        self.p_min = float(p_min)
        self._result = None

    def _comparison(self, params):
        """Fitted values in the comparison scale (ln for B and tau; nan where undefined)."""
        out = []
        for k in self.law.names:
            v = float(params[k])
            if k in self.law._nonlinear:
                v = np.log(v) if np.isfinite(v) and v > 0 else np.nan
            out.append(v if np.isfinite(v) else np.nan)
        return np.array(out)

    def compute(self, t, curves):
        from scipy.stats import t as t_distribution

        law = self.law
        t = as_1d("t", t)
        curves = np.asarray(curves, dtype=float)
        if curves.ndim != 2 or curves.shape[1] != t.size:
            raise ValueError(f"curves must have shape (realizations, {t.size}), got "
                             f"{curves.shape}")
        n = curves.shape[0]
        if n < 2:
            raise ValueError(f"{n} realization(s): a spread needs at least 2")
        if not np.all(np.isfinite(curves)):
            raise ValueError("curves must be finite at every tap")
        keep = t >= self.t_min
        t, curves = t[keep], curves[:, keep]
        need = len(law.names) + 2
        if t.size < need:
            raise ValueError(f"{t.size} taps from t_min = {self.t_min:g}: a fit of "
                             f"{len(law.names)} parameters needs at least {need}")
        ranges = default_tap_ranges(t) if self.ranges is None else self.ranges
        ranges = [r for r in ranges if not (r[0] <= t.min() and r[1] >= t.max())
                  and ((t >= r[0]) & (t <= r[1])).sum() >= need]
        fits = np.empty((n, 1 + len(ranges), len(law.names)))
        for i, y in enumerate(curves):
            fits[i, 0] = self._comparison(law.fit(t, y).params)
            for j, (first, last) in enumerate(ranges):
                inside = (t >= first) & (t <= last)
                fits[i, j + 1] = self._comparison(law.fit(t[inside], y[inside]).params)
        full = fits[:, 0, :]
        dof = n - 1
        tail = (1.0 - self.level) / 2.0
        t_quantile = float(t_distribution.ppf(1.0 - tail, dof))
        res = {key: {} for key in ("values", "mean", "spread", "spread_low", "spread_high",
                                   "limit", "determined", "range_shift", "range_bound",
                                   "range_p")}
        for i, k in enumerate(law.names):
            log = k in law._nonlinear
            v = full[:, i]
            finite = bool(np.all(np.isfinite(v)))
            mean = float(np.mean(v)) if finite else np.nan
            limit = np.log(DETERMINED_FACTOR) if log else (
                RELATIVE_ERROR_LIMIT * abs(mean) if finite else np.nan)
            if finite:
                spread, low, high = spread_interval(v, self.level)
                determined = spread_verdict(low, high, limit)
            else:
                spread, low, high, determined = np.inf, np.inf, np.inf, False
            shifts, bounds, ps = [], [], []
            for j in range(len(ranges)):
                d = fits[:, j + 1, i] - full[:, i]
                if not np.all(np.isfinite(d)):
                    shifts.append(np.inf)
                    bounds.append(np.inf)
                    continue
                m, sem = float(np.mean(d)), float(np.std(d, ddof=1) / np.sqrt(n))
                shifts.append(abs(m))
                bounds.append(abs(m) + t_quantile * sem)
                if sem > 0:
                    ps.append(2.0 * float(t_distribution.sf(abs(m) / sem, dof)))
                else:
                    ps.append(0.0 if m != 0 else 1.0)
            res["values"][k] = v
            res["mean"][k] = float(np.exp(mean)) if log else mean
            res["spread"][k] = spread
            res["spread_low"][k] = float(low)
            res["spread_high"][k] = float(high)
            res["limit"][k] = float(limit)
            res["determined"][k] = determined
            res["range_shift"][k] = float(max(shifts)) if shifts else np.nan
            res["range_bound"][k] = float(max(bounds)) if bounds else np.nan
            res["range_p"][k] = (float(min(1.0, len(ranges) * min(ps))) if ps else np.nan)
        self._result = dict(res, log_scale={k: k in law._nonlinear for k in law.names},
                            realizations=n, ranges=list(ranges))
        return self

    _compute_call = "compute(t, curves)"

    values = _result_property("values")
    mean = _result_property("mean")
    spread = _result_property("spread")
    spread_low = _result_property("spread_low")
    spread_high = _result_property("spread_high")
    limit = _result_property("limit")
    determined = _result_property("determined")
    range_shift = _result_property("range_shift")
    range_bound = _result_property("range_bound")
    range_p = _result_property("range_p")
    log_scale = _result_property("log_scale")
    realizations = _result_property("realizations")
    fitted_ranges = _result_property("ranges")

    @property
    def unique(self):
        if any(d is False for d in self.determined.values()) or self.range_dependent:
            return False
        return True if all(d is True for d in self.determined.values()) else None

    def __repr__(self):
        if self._result is None:
            return f"<RealizationFits of {type(self.law).__name__}: not computed>"
        states = {True: "determined", False: "undetermined", None: "cannot tell"}
        text = ", ".join(f"{k} {states[d]}" for k, d in self.determined.items())
        return (f"<RealizationFits of {type(self.law).__name__} over {self.realizations} "
                f"realizations: {text}; range dependent {self.range_dependent or 'none'}; "
                f"unique {self.unique}>")
