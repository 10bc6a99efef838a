# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The compaction and ageing laws of the taps (eqs. 3, 4 and 6, and two exponentials), and
how their parameters depend on the range of taps fitted and on eps.

* :class:`InverseLogLaw` (eq. 3), :class:`ZLaw` (eq. 4) and :class:`AgeingLaw` (eq. 6) are
  :class:`TapsLaw`: linear in their amplitudes once (B, tau) are fixed (eq. 4 in 1/<Z>), so a
  log-spaced grid over (B, tau) with exact linear least squares at every node gives a global
  starting point that does not depend on the user; scipy.optimize.curve_fit (trust region,
  with physical bounds) refines it (:meth:`tapmc.laws.Law.fit`).
* :class:`TwoExponentials`: section III.A's "a sum of two exponentials can also fit
  reasonably well <Z>(t)".
* :func:`range_refits` refits a law over several tap ranges and compares the spread of each
  parameter with the profile intervals: the statistic of the paper's "depends strongly on the
  range of taps" (section III.B).
* :func:`exponential_dependence` tests "B is consistent with an exponential dependence on
  eps^(1/2)" (section III.A).
"""

import numpy as np
from scipy.stats import chi2 as chi2_distribution

from .._validate import as_1d, same_length
from .fitting import FitResult, Interval, Law

__all__ = ["TapsLaw", "solve_nodes", "InverseLogLaw", "ZLaw", "AgeingLaw", "TwoExponentials",
           "default_tap_ranges", "RangeRefits", "range_refits", "LogLinear",
           "ExponentialDependence", "exponential_dependence", "RANGE_Z_LIMIT",
           "LINEARITY_P_MIN"]

#: deviation of a sub-range fit from the full-range value, in standard deviations of the
#: sub-range's profile (sqrt of its delta chi2 there), above which a parameter depends on the
#: fitted range. For nested tap ranges and a correct law the full-range value is a draw
#: within the sub-range's own scatter; 3 leaves room for the 4 ranges tested together.
RANGE_Z_LIMIT = 3.0
#: p-value of the chi2 of a straight line below which the line is rejected (5 % test).
LINEARITY_P_MIN = 0.05
#: det / product of the diagonal of the normal equations of a grid node below which its
#: amplitude columns count as collinear (the amplitudes are then not unique there).
_COLLINEAR_TOLERANCE = 1e-10


class TapsLaw(Law):
    """A law of the number of taps t >= 0 (the logarithmic laws of eqs. 3, 4 and 6).

    These laws are linear in their amplitudes once (B, tau) are fixed (eq. 4 in 1/<Z>): a
    subclass names its (B, tau) parameters in ``nonlinear`` and gives ``basis(t, B, tau)``,
    the columns multiplying its amplitudes ``linear`` (in the space of ``target``), which
    gives the profile a global start at every point (:meth:`_conditional_start`). That
    structure is public: :class:`tapmc.laws.SurrogateFits` and
    :class:`tapmc.laws.RealizationLawTest` solve the amplitudes exactly with it too."""

    x_label = "tap t"
    y_label = "X"

    nonlinear = ("B", "tau")
    linear = ()
    #: a coarse (B, tau) grid for the profile's global starts (refined by the refit)
    GRID_B = np.geomspace(1e-3, 1e3, 25)
    GRID_TAU_DECADES = (-2.0, 2.0, 25)

    def target(self, y, w):
        """(data, weights) in the space where the amplitudes are linear."""
        return y, w

    def amplitudes_to_params(self, a):
        return a

    def params_to_amplitude(self, name, value):
        return value

    def basis(self, t, B, tau):
        raise NotImplementedError

    def _conditional_start(self, x, y, sigma, i, value):
        if not self.linear or np.any(x < 0):
            return None
        tpos = x[x > 0]
        if tpos.size == 0:
            return None
        lo_d, hi_d, num = self.GRID_TAU_DECADES
        taus = np.geomspace(tpos.min() * 10 ** lo_d, tpos.max() * 10 ** hi_d, num)
        Bs = self.GRID_B
        name = self.names[i]
        iB, itau = (self.names.index(k) for k in self.nonlinear)
        if name == self.nonlinear[0]:
            Bs = np.array([value])
        elif name == self.nonlinear[1]:
            taus = np.array([value])
        BB, TT = (a.ravel() for a in np.meshgrid(Bs, taus, indexing="ij"))
        target, w = self.target(y, 1.0 / sigma ** 2)
        with np.errstate(all="ignore"):
            cols = self._grid_basis(x, BB, TT)                  # list of (nodes, n)
            free = list(range(len(self.linear)))
            if name in self.linear:
                # target - v c_k per node: only its products with w and the columns are needed
                k = self.linear.index(name)
                v = self.params_to_amplitude(name, value)
                free.remove(k)
                tt = (np.sum(w * target ** 2) - 2.0 * v * (cols[k] @ (w * target))
                      + v ** 2 * ((cols[k] ** 2) @ w))
                rhs = np.stack([cols[j] @ (w * target) - v * ((cols[j] * cols[k]) @ w)
                                for j in free], axis=1) if free else None
            else:
                tt = np.full(len(BB), np.sum(w * target ** 2))
                rhs = np.stack([cols[j] @ (w * target) for j in free], axis=1)
            m = len(free)
            coef = np.zeros((len(BB), len(self.linear)))
            sse = tt
            if m:
                normal = np.empty((len(BB), m, m))
                for a, ja in enumerate(free):
                    for b, jb in enumerate(free[a:], start=a):
                        normal[:, a, b] = normal[:, b, a] = (cols[ja] * cols[jb]) @ w
                sol = solve_nodes(normal, rhs)   # collinear nodes: nan, so sse = inf
                for j, k in enumerate(free):
                    coef[:, k] = sol[:, j]
                # |r|^2 = |t|^2 - rhs . sol at the least-squares amplitudes
                sse = tt - np.sum(rhs * sol, axis=1)
        sse = np.where(np.isfinite(sse), sse, np.inf)
        best = int(np.argmin(sse))
        if not np.isfinite(sse[best]):
            return None
        amps = coef[best]
        if name in self.linear:
            amps[self.linear.index(name)] = self.params_to_amplitude(name, value)
        p = np.empty(len(self.names))
        for k, v in zip(self.linear, self.amplitudes_to_params(amps)):
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
                           for c in self.basis(x[None, :], BB[:, None], TT[:, None])])
            _GRID_BASIS_CACHE[:] = [entry]   # one entry, replaced whole (threads see either)
        return entry[1]

    def _prepare(self, x, y, sigma):
        x, y, sigma, weighted = super()._prepare(x, y, sigma)
        if np.any(x < 0):
            bad = int(np.flatnonzero(x < 0)[0])
            raise ValueError(f"x[{bad}] = {x[bad]:g}: taps must be >= 0")
        return x, y, sigma, weighted


def solve_nodes(normal, rhs):
    """Amplitudes at every grid node from its normal equations, (nodes, m, m) and (nodes, m):
    nan at the nodes whose columns are (nearly) collinear, e.g. g = 1 for a tau far beyond
    the data, which have no unique amplitudes."""
    ok = np.abs(np.linalg.det(normal)) > _COLLINEAR_TOLERANCE * np.abs(
        np.prod(np.diagonal(normal, axis1=1, axis2=2), axis=1))
    sol = np.full(rhs.shape, np.nan)
    if ok.any():
        sol[ok] = np.linalg.solve(normal[ok], rhs[ok][..., None])[..., 0]
    return sol


#: the last grid of basis columns of :meth:`TapsLaw._grid_basis`, as [(key, columns)] (one
#: entry: a profile walks one data set at a time)
_GRID_BASIS_CACHE = []


def _log_term(t, B, tau):
    return B * np.log1p(np.maximum(t, 0.0) / tau)


def _log_term_derivatives(t, B, tau):
    """L = B ln(1 + t/tau) with dL/dB and dL/dtau (t clamped at 0 as in :func:`_log_term`)."""
    t = np.maximum(t, 0.0)
    ell = np.log1p(t / tau)
    return B * ell, ell, -B * t / (tau * (tau + t))


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


class InverseLogLaw(TapsLaw):
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

    @staticmethod
    def jacobian(t, X_inf, dX_inf, B, tau):
        L, dL_dB, dL_dtau = _log_term_derivatives(t, B, tau)
        g = 1.0 / (1.0 + L)
        df_dL = dX_inf * g * g
        return np.stack([np.ones_like(g), -g, df_dL * dL_dB, df_dL * dL_dtau], axis=-1)

    def bounds(self, x, y):
        return ([-np.inf, -np.inf, 0.0, 0.0], [np.inf, np.inf, np.inf, np.inf])

    linear = ("X_inf", "dX_inf")

    def basis(self, t, B, tau):
        g = 1.0 / (1.0 + _log_term(t, B, tau))
        return [np.ones_like(g), -g]

    def initial_guess(self, t, y, w):
        B, tau, (c_inf, c_0) = _grid_inverse_log(t, y, w, 2)
        return [c_inf, c_inf - c_0, B, tau]


class ZLaw(TapsLaw):
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

    @staticmethod
    def jacobian(t, Z_inf, Z_0, B, tau):
        L, dL_dB, dL_dtau = _log_term_derivatives(t, B, tau)
        ratio = Z_inf / Z_0
        inv_d = 1.0 / (ratio + L)
        f = Z_inf * (1.0 + L) * inv_d
        df_dL = Z_inf * (ratio - 1.0) * inv_d * inv_d
        return np.stack([f / Z_inf * (1.0 - ratio * inv_d), f * ratio / Z_0 * inv_d,
                         df_dL * dL_dB, df_dL * dL_dtau], axis=-1)

    def bounds(self, x, y):
        return ([0.0, 0.0, 0.0, 0.0], [np.inf] * 4)

    linear = ("Z_inf", "Z_0")

    def target(self, y, w):
        return 1.0 / y, w * y ** 4  # d(1/Z) = dZ / Z^2

    def params_to_amplitude(self, name, value):
        return 1.0 / value

    def amplitudes_to_params(self, a):
        with np.errstate(divide="ignore"):
            return np.where(a > 0, 1.0 / a, np.nan)

    def basis(self, t, B, tau):
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


class AgeingLaw(TapsLaw):
    """Eq. 6 (section III.C): A(t) = A_inf (1 - 1/(1 + B_A ln(1 + t/tau_A))). Parameters
    ``A_inf, B_A, tau_A`` (all > 0)."""

    x_label = "t (taps after the waiting time)"
    y_label = "A(t)"

    names = ("A_inf", "B_A", "tau_A")
    time_scales = ("tau_A",)

    @staticmethod
    def function(t, A_inf, B_A, tau_A):
        return A_inf * (1.0 - 1.0 / (1.0 + _log_term(t, B_A, tau_A)))

    @staticmethod
    def jacobian(t, A_inf, B_A, tau_A):
        L, dL_dB, dL_dtau = _log_term_derivatives(t, B_A, tau_A)
        g = 1.0 / (1.0 + L)
        df_dL = A_inf * g * g
        return np.stack([1.0 - g, df_dL * dL_dB, df_dL * dL_dtau], axis=-1)

    def bounds(self, x, y):
        return ([0.0, 0.0, 0.0], [np.inf] * 3)

    nonlinear = ("B_A", "tau_A")
    linear = ("A_inf",)

    def basis(self, t, B, tau):
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
    the skewed profiles of a degenerate law, and 0 for a range whose profile is flat there;
    nan when no range has a converged fit to compare), ``consistent`` (dict name -> deviation
    <= ``RANGE_Z_LIMIT``; None when nan: no evidence either way) and ``range_dependent`` (the
    names that are not consistent)."""

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
                worst = np.nan
                for f in self.fits:
                    if f is None or not f.converged:
                        continue
                    d = f.profile_delta_chi2(k, ref)
                    if np.isfinite(d) or d == np.inf:
                        worst = max(0.0 if np.isnan(worst) else worst, float(np.sqrt(d)))
                out[k] = worst
            self._deviation = out
        return self._deviation

    @property
    def consistent(self):
        return {k: None if np.isnan(d) else bool(d <= RANGE_Z_LIMIT)
                for k, d in self.deviation.items()}

    @property
    def range_dependent(self):
        return [k for k, ok in self.consistent.items() if ok is False]

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
    if ranges is None:
        if not np.max(t) > 4.0:
            raise ValueError(f"t ends at tap {np.max(t):g}: the default ranges start with "
                             f"[1, T/4], which needs T > 4; give ranges")
        ranges = default_tap_ranges(t)
    else:
        ranges = [tuple(map(float, r)) for r in ranges]
    for r in ranges:
        if len(r) != 2 or not r[0] < r[1]:
            raise ValueError(f"ranges entry {r!r} must be (first, last) with first < last")
    needed = len(law.names) + 2
    reference = law.fit(t, y, s).improved()
    fits = []
    for first, last in ranges:
        keep = (t >= first) & (t <= last)
        if keep.sum() < needed:
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
    ln B against sqrt(eps), None with determined B at fewer than 2 sqrt(eps)), ``slope`` and
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
    if len(np.unique(x[ok])) < 2:  # a slope needs two sqrt(eps) (seeds of one eps give none)
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
        intervals = {"ln_y0": Interval(popt[0], None, None, (-np.inf, np.inf), "exact"),
                     "slope": Interval(slope, slope - err, slope + err, (-np.inf, np.inf),
                                       "curvature")}
        res = FitResult(law, law.names, popt, cov, x2, y2, sig, True, "", True,
                        intervals=intervals)
        return ExponentialDependence(res, x[ok], x[~ok])
    return ExponentialDependence(law.fit(x[ok], np.log(b[ok]), sig), x[ok], x[~ok])
