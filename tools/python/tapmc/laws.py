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
"""

import warnings

import numpy as np
from scipy.optimize import OptimizeWarning, curve_fit

from ._validate import as_1d, new_axis, same_length

__all__ = ["FitResult", "Law", "InverseLogLaw", "ZLaw", "TwoExponentials", "AgeingLaw",
           "ProfileLaw", "StraightLine", "profile_gradient", "PROFILE_WINDOWS",
           "CORRELATION_LIMIT", "RELATIVE_ERROR_LIMIT"]

#: |correlation| between two parameters above which they are reported as not separately
#: determined (the data fix only a combination of them).
CORRELATION_LIMIT = 0.999
#: relative 1-sigma error above which a parameter is reported as not determined (100 %).
RELATIVE_ERROR_LIMIT = 1.0
#: gradient windows of the paper (section IV.A), in units of R.
PROFILE_WINDOWS = {"fbc": (5.0, 22.0), "pbc": (5.0, 26.0)}


class FitResult:
    """Outcome of a fit: ``params`` and ``errors`` (1-sigma) as dicts, ``covariance``,
    ``correlation``, ``chi2``, ``dof``, ``reduced_chi2``, ``rms`` (residual root mean square),
    ``determined`` and ``note``. ``result(x)`` evaluates the fitted law; ``plot(ax)`` draws data
    and fit. With ``sigma`` given to the fit, errors are absolute (``chi2`` is the weighted sum
    and ``reduced_chi2`` tests the model); without it the errors are scaled by the scatter of
    the residuals and ``chi2`` is the plain sum of squared residuals."""

    def __init__(self, law, names, popt, pcov, x, y, sigma, determined, note, weighted):
        self.law = law
        self.names = list(names)
        self._popt = np.asarray(popt, dtype=float)
        self.covariance = np.asarray(pcov, dtype=float)
        self.x, self.y, self.sigma = x, y, sigma
        self.determined = bool(determined)
        self.note = note
        self.weighted = weighted
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
    def errors(self):
        diag = np.diag(self.covariance) if self.covariance.ndim == 2 else np.full(len(self.names), np.inf)
        with np.errstate(invalid="ignore"):
            return dict(zip(self.names, np.sqrt(np.abs(diag))))

    @property
    def correlation(self):
        d = np.sqrt(np.abs(np.diag(self.covariance)))
        with np.errstate(invalid="ignore", divide="ignore"):
            return self.covariance / np.outer(d, d)

    def __call__(self, x):
        return self.law.function(np.asarray(x, dtype=float), *self._popt)

    def __repr__(self):
        parts = ", ".join(f"{k}={v:.6g}+-{self.errors[k]:.2g}" for k, v in self.params.items())
        flag = "determined" if self.determined else f"NOT determined ({self.note})"
        return f"<FitResult {type(self.law).__name__}: {parts}; {flag}>"

    def plot(self, ax=None, logx=False, data_kw=None, **kw):
        """Data (points with error bars when sigma was given) and the fitted curve."""
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
        popt, pcov = self._canonical(popt, pcov)
        determined, more = self.assess(popt, pcov, lo, hi)
        notes += more
        return FitResult(self, self.names, popt, pcov, x, y, sigma, determined and not notes,
                         "; ".join(notes), weighted)

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
    """A law of the number of taps t >= 0 (the logarithmic laws of eqs. 3, 4 and 6)."""

    def _prepare(self, x, y, sigma):
        x, y, sigma, weighted = super()._prepare(x, y, sigma)
        if np.any(x < 0):
            bad = int(np.flatnonzero(x < 0)[0])
            raise ValueError(f"x[{bad}] = {x[bad]:g}: taps must be >= 0")
        return x, y, sigma, weighted


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

    names = ("X_inf", "dX_inf", "B", "tau")

    @staticmethod
    def function(t, X_inf, dX_inf, B, tau):
        return X_inf - dX_inf / (1.0 + _log_term(t, B, tau))

    def bounds(self, x, y):
        return ([-np.inf, -np.inf, 0.0, 0.0], [np.inf, np.inf, np.inf, np.inf])

    def initial_guess(self, t, y, w):
        B, tau, (c_inf, c_0) = _grid_inverse_log(t, y, w, 2)
        return [c_inf, c_inf - c_0, B, tau]


class ZLaw(_TapsLaw):
    """Eq. 4 (section III.A): <Z>(t) = Z_inf (1 + B L) / (Z_inf/Z_0 + B L), L = ln(1 + t/tau).
    Parameters ``Z_inf, Z_0, B, tau`` (all > 0). Equivalently 1/<Z> = g/Z_0 + (1 - g)/Z_inf with
    g = 1/(1 + B L), which gives the starting values."""

    names = ("Z_inf", "Z_0", "B", "tau")

    @staticmethod
    def function(t, Z_inf, Z_0, B, tau):
        L = _log_term(t, B, tau)
        return Z_inf * (1.0 + L) / (Z_inf / Z_0 + L)

    def bounds(self, x, y):
        return ([0.0, 0.0, 0.0, 0.0], [np.inf] * 4)

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

    names = ("A_inf", "B_A", "tau_A")

    @staticmethod
    def function(t, A_inf, B_A, tau_A):
        return A_inf * (1.0 - 1.0 / (1.0 + _log_term(t, B_A, tau_A)))

    def bounds(self, x, y):
        return ([0.0, 0.0, 0.0], [np.inf] * 3)

    def initial_guess(self, t, y, w):
        B, tau, (a_inf,) = _grid_inverse_log(t, y, w, 1)
        return [max(a_inf, 1e-300), B, tau]


class TwoExponentials(Law):
    """y(t) = y_inf + a1 exp(-t/tau1) + a2 exp(-t/tau2) with 0 < tau1 <= tau2 (the labels are
    ordered after the fit). Parameters ``y_inf, a1, tau1, a2, tau2``."""

    names = ("y_inf", "a1", "tau1", "a2", "tau2")
    may_vanish = ()

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

