# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The laws tested across independent realizations of the same process, whose taps, unlike
one run's, are independent between runs: :class:`RealizationLawTest` (Hotelling's T^2 of a
law's GLS fit to the realizations' bin means, :func:`realization_bin_covariance`,
:func:`hotelling_gls`) and :class:`RealizationFits` (the spread of the parameters over the
realizations and their dependence on the range of taps, :func:`spread_interval`,
:func:`spread_verdict`)."""

import numpy as np
from scipy.optimize import least_squares
from scipy.stats import chi2 as chi2_distribution
from scipy.stats import f as f_distribution

from .._validate import as_1d
from ._computed import Computed, RangeTested, result_property
from .compaction import TapsLaw, default_tap_ranges, solve_nodes
from .fitting import RELATIVE_ERROR_LIMIT, Law
from .surrogates import DETERMINED_FACTOR, SURROGATE_P_MIN

__all__ = ["realization_bin_covariance", "hotelling_gls", "RealizationLawTest", "spread_interval",
           "spread_verdict", "RealizationFits", "REALIZATION_MAX_BINS", "REALIZATION_P_MIN"]

#: at most this many log-spaced bins of taps in a :class:`RealizationLawTest`: each bin adds a
#: dimension to the covariance that the realizations must estimate (it needs realizations >
#: bins), and 8 bins over 2-4 decades resolve the curvature the laws describe.
REALIZATION_MAX_BINS = 8
#: p-value below which a :class:`RealizationLawTest` rejects the law (a 1 % test).
REALIZATION_P_MIN = 0.01
#: best (B, tau) grid nodes from which a :class:`RealizationLawTest` refines its GLS fit,
#: beside the law's own fit of the mean curve (the minimum chi-square decides the test: a
#: local minimum would reject a law that holds).
_GRID_STARTS = 4
#: ... of which this many (the best after the fit of (B, tau) alone) are polished by the fit
#: of all parameters; two, because eq. 4's amplitudes are linear only to first order.
_POLISHED_STARTS = 2


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


class RealizationLawTest(Computed):
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
        if not np.isfinite(t_min):
            raise ValueError(f"t_min = {t_min}: must be finite")
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
        if np.count_nonzero(keep) < bins:
            raise ValueError(f"t_min = {self.t_min:g} leaves {np.count_nonzero(keep)} taps (t "
                             f"ends at {t.max():g}): {bins} bins need at least {bins}")
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
        amplitudes once (B, tau) are fixed (:class:`TapsLaw`); [] for another law.

        The amplitudes are solved by GLS in the law's linear space (the bin means' covariance
        carried there to first order) for every (B, tau), which leaves a fit of (ln B, ln tau)
        alone (variable projection). It starts from the law's fit of the mean curve and from
        the :data:`_GRID_STARTS` best nodes of a (B, tau) grid: the law's own fit weighs
        taps, not bins, and can sit in another minimum of the GLS. The GLS of all parameters
        then only polishes the best of them (exact for eqs. 3 and 6, whose amplitudes are
        linear in the data's own space), instead of wandering along the valley of (B, tau) from each
        start."""
        law = self.law
        if not isinstance(law, TapsLaw) or not law.linear or np.any(means <= 0):
            return []
        target, weight = law.target(means, np.ones_like(means))
        scale = 1.0 / np.sqrt(weight)                  # |d target / d mean|
        try:
            whiten = np.linalg.inv(np.linalg.cholesky(cov * np.outer(scale, scale)))
        except np.linalg.LinAlgError:
            return []
        y = whiten @ target
        iB, itau = (law.names.index(k) for k in law.nonlinear)

        def design(B, tau):                            # (..., bins, amplitudes)
            columns = law.basis(t[None, :], np.atleast_1d(B)[:, None],
                                 np.atleast_1d(tau)[:, None])
            return np.stack([np.broadcast_to(c, (np.size(B), t.size)) @ binning.T @ whiten.T
                             for c in columns], axis=2)

        def amplitudes(A):
            return solve_nodes(np.einsum("kba,kbc->kac", A, A), np.einsum("kba,b->ka", A, y))

        lo_d, hi_d, num = law.GRID_TAU_DECADES
        taus = np.geomspace(t.min() * 10 ** lo_d, t.max() * 10 ** hi_d, num)
        BB, TT = (a.ravel() for a in np.meshgrid(law.GRID_B, taus, indexing="ij"))
        with np.errstate(all="ignore"):
            A = design(BB, TT)
            cost = np.sum((np.einsum("kba,ka->kb", A, amplitudes(A)) - y) ** 2, axis=1)
        cost = np.where(np.isfinite(cost), cost, np.inf)
        nodes = [(first[iB], first[itau])] + [
            (BB[k], TT[k]) for k in np.argsort(cost)[:_GRID_STARTS] if np.isfinite(cost[k])]
        # ln B and ln tau stay within the grid widened by a decade each side; the polish
        # that follows has the law's own bounds
        lo = np.log([law.GRID_B[0] / 10.0, taus[0] / 10.0])
        hi = np.log([law.GRID_B[-1] * 10.0, taus[-1] * 10.0])

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
            for name, v in zip(law.linear, law.amplitudes_to_params(amps)):
                p[law.names.index(name)] = v
            p[iB], p[itau] = B, tau
            if np.all(np.isfinite(p)):
                found.append((fit.cost, p))
        found.sort(key=lambda node: node[0])
        return [p for _, p in found[:_POLISHED_STARTS]]

    _compute_call = "compute(t, curves)"

    params = result_property("params")
    errors = result_property("errors")
    chi2 = result_property("chi2")
    dof = result_property("dof")
    F = result_property("F")
    p_value = result_property("p_value")
    realizations = result_property("realizations")
    bin_edges = result_property("bin_edges")
    bin_means = result_property("bin_means")
    bin_sem = result_property("bin_sem")
    bin_model = result_property("bin_model")

    @property
    def compatible(self):
        return bool(self.p_value >= REALIZATION_P_MIN)

    def __repr__(self):
        if self._result is None:
            return f"<RealizationLawTest of {type(self.law).__name__}: not computed>"
        return (f"<RealizationLawTest of {type(self.law).__name__}: T2 {self.chi2:.3g} "
                f"({self.dof} dof, {self.realizations} realizations), F {self.F:.3g}, "
                f"p {self.p_value:.3g}>")


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


class RealizationFits(RangeTested):
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
        if not isinstance(law, TapsLaw) or not law.linear:
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
            if k in self.law.nonlinear:
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
            log = k in law.nonlinear
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
        self._result = dict(res, log_scale={k: k in law.nonlinear for k in law.names},
                            realizations=n, ranges=list(ranges))
        return self

    _compute_call = "compute(t, curves)"

    values = result_property("values")
    mean = result_property("mean")
    spread = result_property("spread")
    spread_low = result_property("spread_low")
    spread_high = result_property("spread_high")
    limit = result_property("limit")
    determined = result_property("determined")
    range_shift = result_property("range_shift")
    range_bound = result_property("range_bound")
    range_p = result_property("range_p")
    log_scale = result_property("log_scale")
    realizations = result_property("realizations")
    fitted_ranges = result_property("ranges")

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
