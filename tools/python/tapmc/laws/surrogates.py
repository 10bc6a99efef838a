# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""How well one run fixes a law's parameters, and whether they depend on the range of taps
fitted: :class:`SurrogateFits`, fits of Fourier surrogates of the run's residuals (one run's
taps are correlated, Fig. 3)."""

import numpy as np
from scipy.optimize import least_squares

from .._validate import as_1d, same_length
from ._computed import RangeTested, result_property
from .compaction import TapsLaw, default_tap_ranges, solve_nodes
from .fitting import POSITIVE_DECADES, RELATIVE_ERROR_LIMIT, TIME_SCALE_DECADES

__all__ = ["SurrogateFits", "DETERMINED_FACTOR", "SURROGATES", "SURROGATE_P_MIN"]

#: factor within which a positive scale (B, tau of eqs. 3 and 4, compared in ln) is
#: determined by :class:`SurrogateFits` and :class:`RealizationFits`: half the band's width
#: at most ln 2 (convention: a scale known to a factor 2 is known to its order)
DETERMINED_FACTOR = 2.0
#: Fourier surrogates of one run's residuals in a :class:`SurrogateFits`: 200 put the 16 and
#: 84 % points within about 3 % (in probability) and resolve a p-value of 1 %.
SURROGATES = 200
#: p-value below which a :class:`SurrogateFits` calls a parameter range dependent (a 1 %
#: test, as :data:`REALIZATION_P_MIN`).
SURROGATE_P_MIN = 0.01
#: distance (in ln) from the edge of (B, tau)'s allowed range within which a
#: :class:`SurrogateFits` fit counts as sitting on it
_EDGE_TOLERANCE = 1e-6


class SurrogateFits(RangeTested):
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
        if not isinstance(law, TapsLaw) or not law.linear:
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
        A = np.stack(self.law.basis(t, B, tau), axis=1) * sw[:, None]
        coef, *_ = np.linalg.lstsq(A, target * sw, rcond=None)
        return coef, target * sw - A @ coef

    def _fit(self, t, y, starts):
        """Comparison-scale parameters (nan where they do not exist) of the fit of (t, y)."""
        law = self.law
        target, w = law.target(y, np.ones_like(y))
        sw = np.sqrt(w)
        taus = np.geomspace(t.min() * 1e-2, t.max() * 1e2, self._GRID_NODES)
        Bs = np.geomspace(law.GRID_B[0], law.GRID_B[-1], self._GRID_NODES)
        BB, TT = (a.ravel() for a in np.meshgrid(Bs, taus, indexing="ij"))
        with np.errstate(all="ignore"):
            A = np.stack([np.broadcast_to(c, (BB.size, t.size)) * sw
                          for c in law.basis(t[None, :], BB[:, None], TT[:, None])], axis=1)
            normal = A @ A.transpose(0, 2, 1)                            # (nodes, amps, amps)
            rhs = A @ (target * sw)
            # |r|^2 = |y|^2 - rhs . coef for the least-squares amplitudes (collinear: inf)
            cost = np.sum((target * sw) ** 2) - np.sum(rhs * solve_nodes(normal, rhs), axis=1)
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
        values = dict(zip(law.nonlinear, (B, tau)))
        with np.errstate(all="ignore"):
            values.update(zip(law.linear, law.amplitudes_to_params(coef)))
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
        iB, itau = (self.law.names.index(k) for k in self.law.nonlinear)
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
        self._log = {k: k in law.nonlinear for k in law.names}
        B0, tau0 = (first[k] for k in law.nonlinear)
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

    params = result_property("params")
    samples = result_property("samples")
    low = result_property("low")
    high = result_property("high")
    half_width = result_property("half_width")
    determined = result_property("determined")
    range_p = result_property("range_p")
    used = result_property("used")
    log_scale = result_property("log_scale")
    fitted_ranges = result_property("ranges")

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
