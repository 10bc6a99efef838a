# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Ageing, section III.C of Philippe & Bideau: the two-time function A(t, t_w) of <Z> averaged
over realizations (eq. 5) and its collapse onto eq. 6.

Reading of eq. 5. The paper prints A(t, t_W) = mean of (<Z>(t) - <Z>(t + t_W))^2 and fits
A(t, t_W) = A_inf (1 - 1/(1 + B_A ln(1 + t/tau_A))) (eq. 6), which vanishes at t = 0 and
depends on the time t elapsed since the waiting time. Both hold together only when t is the
delay and t_w the age of the packing:

    A(t, t_w) = mean over realizations of (<Z>(t_w + t) - <Z>(t_w))^2,

so A(0, t_w) = 0 for every t_w and the curves for different waiting times can collapse onto eq.
6 as functions of t. This is the reading used here (eq. 5 with its two time symbols exchanged);
t and t_w are counted in taps, index 0 of a series being the initial packing.

The scaling variable. The paper sees "obviously a scaling law" in Fig. 5 and draws the curves
collapsed on one eq. 6, without saying on which variable. :func:`scaling_collapse` searches it:
A(t, t_w) = (t_w/t_ref)^kappa F(t / (t_w/t_ref)^mu) with F of eq. 6, i.e. one eq. 6 whose
tau_A grows as t_w^mu and whose amplitude as t_w^kappa (t_ref the geometric mean of the
waiting times, so A_inf and tau_A are those of a typical t_w): the usual ageing forms t/t_w
(mu = 1, "simple ageing") and no ageing (mu = kappa = 0) are points of this family. mu and kappa
are fitted with every parameter of eq. 6 by weighted least squares on all curves at once; the
reduced chi2 of the collapse is compared with that of one eq. 6 in t itself (no rescaling).

Their uncertainty. The delays of one curve come from the same realizations: A(t, t_w) and
A(t + 1, t_w) share almost all their increments, so a chi2 that counts every delay as
independent, and the profile-likelihood interval built on it (``tapmc.laws.FitResult.
intervals``), are far too narrow (a random walk, which has no ageing, gives a "determined" mu
several profile widths away from 0). :meth:`ScalingCollapse.interval` therefore widens the
profile interval to the leave-one-curve-out jackknife standard error and, when the
realizations are at hand (:meth:`Ageing.scaling` with ``bootstrap``), to the standard
deviation over realizations resampled with replacement; a side that the profile leaves open
stays open.

Its test. Whether one rescaling collapses the curves within their errors is a question for the
realizations, not for the delays: :class:`ScalingRealizationTest` cuts every curve into
log-spaced bins of delays, takes each realization's mean of (<Z>(t_w + t) - <Z>(t_w))^2 per
bin, and fits the collapse to the bins' means by generalized least squares with their
covariance between realizations (``tapmc.laws.hotelling_gls``): Hotelling's T^2, whose
p-values are uniform for 10 realizations of curves that collapse (the slow test
tests/python/test_slow_ageing_scaling_test.py), where the reduced chi2 of the fit, a sum over
correlated delays each weighted by an error estimated from the same few realizations, has no
known distribution. The collapse is tested with eq. 6 as its master curve, so a curve that
eq. 6 itself does not follow fails it too: :meth:`Ageing.eq6_test` tests eq. 6 on one curve
alone, the same way. Where the packing still compacts, A is mostly the square of the mean
displacement (:meth:`Ageing.drift_share`), which starts as t^2 (a drift) where eq. 6 starts
linear in t.
"""

import numpy as np

from ._legends import place_legend
from ._validate import as_1d, as_2d, computed_repr, new_axis, require, result
from .laws import (REALIZATION_MAX_BINS, REALIZATION_P_MIN, AgeingLaw, Law,
                   RealizationLawTest, hotelling_gls, realization_bin_covariance)

__all__ = ["Ageing", "MIN_BOOTSTRAP_REALIZATIONS", "ScaledAgeingLaw", "ScalingCollapse",
           "ScalingRealizationTest", "scaling_collapse", "scaling_test_min_realizations",
           "collapse_dispersion", "SCALING_EXPONENT_RANGE"]

#: allowed range of the scaling exponents mu (time) and kappa (amplitude): beyond +-3 a
#: factor 10 in t_w would rescale t by more than 10^3, far outside any run of the paper
#: (waiting times 10 to 1000 taps in runs of 4000).
SCALING_EXPONENT_RANGE = (-3.0, 3.0)
#: half-width in ln t of the smoothing that gives a curve's level for the weights of the
#: collapse (a factor 1.2 in t: 1 delay near t = 5, 37 near t = 200)
_LEVEL_LOG_WINDOW = np.log(1.2)
#: log-spaced delays per curve for the grid search of the starting exponents (the final fit
#: uses every delay).
_START_POINTS_PER_CURVE = 40

#: fewer realizations than this have too few distinct resamples for bootstrap errors (the
#: paper averaged 10)
MIN_BOOTSTRAP_REALIZATIONS = 5


class Ageing:
    """A(t, t_w) over realizations (eq. 5, see the module text for the reading) and eq. 6.

    Parameters: ``z_series`` (n_realizations, n_taps + 1): <Z> after 0, 1, ... taps of every
    realization (at least 2 realizations); ``waiting_times``: the t_w in taps; ``t`` (optional)
    the delays in taps, default every delay 0 .. n_taps - max(t_w), common to all t_w.

    Results after ``compute()``: ``t`` (delays), ``A`` (dict t_w -> array over t), ``A_sem``
    (dict t_w -> standard error over realizations), ``n_realizations``. ``fit(t_w)`` fits eq. 6
    to one curve, ``collapse()`` fits eq. 6 to all curves at once (the scaling of Fig. 5) and
    returns a :class:`tapmc.laws.FitResult` whose reduced chi2 measures how well the curves for
    different t_w collapse; ``eq6_test(t_w)`` tests eq. 6 on one curve across the
    realizations; ``drift_share(t_w)`` is the share of A that the mean compaction makes (the
    square of the mean displacement), not the realizations' spread; ``plot(ax)`` draws the
    curves and the collapse fit."""

    def __init__(self, z_series, waiting_times, t=None):
        self.z = as_2d("z_series", z_series, min_rows=2, min_cols=2)
        tw = np.atleast_1d(np.asarray(waiting_times))
        if tw.size == 0 or np.any(tw < 0) or np.any(tw != np.round(tw)):
            raise ValueError(f"waiting_times = {waiting_times!r} must be integers >= 0 (taps)")
        self.waiting_times = [int(v) for v in tw]
        n = self.z.shape[1] - 1
        if max(self.waiting_times) >= n:
            raise ValueError(f"waiting time {max(self.waiting_times)} leaves no delay in a "
                             f"series of {n} taps")
        if t is None:
            t = np.arange(0, n - max(self.waiting_times) + 1)
        else:
            t = as_1d("t", t)
            if np.any(t < 0) or np.any(t != np.round(t)):
                raise ValueError("t must hold integer delays >= 0 (taps)")
            if t.max() + max(self.waiting_times) > n:
                raise ValueError(f"t_max + t_w = {int(t.max()) + max(self.waiting_times)} "
                                 f"exceeds the {n} taps of the series")
        self._t_in = t.astype(int)

    def compute(self):
        t = self._t_in
        self.n_realizations = self.z.shape[0]
        A, sem = {}, {}
        for tw in self.waiting_times:
            d2 = (self.z[:, tw + t] - self.z[:, [tw]]) ** 2  # (realizations, delays)
            A[tw] = d2.mean(axis=0)
            sem[tw] = d2.std(axis=0, ddof=1) / np.sqrt(self.n_realizations)
        self._t, self._A, self._A_sem = t.astype(float), A, sem
        return self

    t = result("_t")
    A = result("_A")
    A_sem = result("_A_sem")

    def __repr__(self):
        return computed_repr(self, "_A", f"of {self.z.shape[0]} realizations x "
                             f"{self.z.shape[1] - 1} taps, t_w {self.waiting_times}",
                             lambda: f"A(t, t_w) at {len(self._t)} delays")

    def _curves(self, tws, rows=None):
        """(t, A, sem) of every (t_w, t > 0) pair, realizations ``rows`` (default all)."""
        z = self.z if rows is None else self.z[rows]
        t = self._t_in[self._t_in > 0]
        ts, ys, ss = [], [], []
        for tw in tws:
            d2 = (z[:, tw + t] - z[:, [tw]]) ** 2
            ts.append(t.astype(float))
            ys.append(d2.mean(axis=0))
            ss.append(d2.std(axis=0, ddof=1) / np.sqrt(len(z)))
        return np.concatenate(ts), np.concatenate(ys), np.concatenate(ss)

    def _fit(self, tws, bootstrap, seed):
        require(self, "_A")
        bootstrap = int(bootstrap)
        if bootstrap < 0:
            raise ValueError(f"bootstrap = {bootstrap} must be >= 0 (0: no resampling)")
        law = AgeingLaw()
        t, a, sem = self._curves(tws)
        keep = sem > 0  # a delay where every realization moved alike carries no error estimate
        t, a, sem = t[keep], a[keep], sem[keep]
        # weights from the law, not from each point's own scatter: a point that fluctuates low
        # also has a low standard error and would pull a fit weighted by it (the standard error
        # of a mean of squares is proportional to its mean, so sigma = law * median(sem / A))
        first = law.fit(t, a, sem)
        ratio = float(np.median(sem / a))
        model_sigma = np.maximum(first(t), 1e-300) * ratio
        res = law.fit(t, a, model_sigma, p0=list(first.params.values()))
        if bootstrap:
            # the points of one curve (and of curves of different t_w) come from the same
            # realizations and are strongly correlated: the weighted-fit covariance ignores
            # that, so the errors are taken from refits on realizations resampled with
            # replacement
            rng = np.random.default_rng(seed)
            p0 = list(res.params.values())
            samples = []
            for _ in range(bootstrap):
                rows = rng.integers(0, self.n_realizations, self.n_realizations)
                _, ab, _ = self._curves(tws, rows)
                fit_b = law.fit(t, ab[keep], model_sigma, p0=p0)
                if fit_b.converged:
                    samples.append(list(fit_b.params.values()))
            lo, hi = (np.broadcast_to(v, (3,)).astype(float) for v in law.bounds(None, None))
            if len(samples) < max(10, bootstrap // 2):
                res.determined = False
                res.note = "; ".join(filter(None, [res.note, f"only {len(samples)} of "
                                                   f"{bootstrap} bootstrap refits converged: "
                                                   "errors from the weighted fit, too small"]))
                return res
            # determined only if both the fit's own covariance (it sees degenerate directions
            # of the law, e.g. the linear regime t << tau_A) and the bootstrap one pass
            analytic_ok, analytic_note = res.determined, res.note
            res.covariance = np.cov(np.array(samples).T)
            determined, notes = law.assess(list(res.params.values()), res.covariance, lo, hi)
            res.determined = determined and analytic_ok
            notes = ([f"weighted fit: {analytic_note}"] if analytic_note else []) + notes
            if self.n_realizations < MIN_BOOTSTRAP_REALIZATIONS:
                res.determined = False
                notes.append(f"only {self.n_realizations} realizations: too few for bootstrap "
                             f"errors (at least {MIN_BOOTSTRAP_REALIZATIONS})")
            res.note = "; ".join(notes + [f"errors from {len(samples)} bootstrap resamples "
                                          "of the realizations"])
        return res

    def fit(self, t_w, bootstrap=100, seed=0):
        """Eq. 6 fitted to the curve of one waiting time, weighted by the standard errors
        (t = 0, where A vanishes exactly, is left out); parameter errors from ``bootstrap``
        resamples of the realizations (0: the weighted-fit covariance, which ignores the
        correlation between delays and underestimates them)."""
        if t_w not in self.A:
            raise ValueError(f"t_w = {t_w!r} is not one of the waiting times {self.waiting_times}")
        return self._fit([t_w], bootstrap, seed)

    def scaling(self, fit_amplitude=True, bootstrap=0, seed=0):
        """:func:`scaling_collapse` of the curves of the waiting times > 0: the scaling
        variable t / t_w^mu (and amplitude t_w^kappa) that collapses them on one eq. 6. With
        ``bootstrap`` > 0 the collapse is refitted on that many resamples of the realizations
        (with replacement) and ``bootstrap`` of the result holds each parameter's standard
        deviation over them (at least ``MIN_BOOTSTRAP_REALIZATIONS`` realizations needed)."""
        require(self, "_A")
        bootstrap = int(bootstrap)
        if bootstrap < 0:
            raise ValueError(f"bootstrap = {bootstrap} must be >= 0 (0: no resampling)")
        tws = [tw for tw in self.waiting_times if tw > 0]
        curves = {tw: (self.t, self.A[tw], self.A_sem[tw]) for tw in tws}
        res = scaling_collapse(curves, fit_amplitude)
        if bootstrap and self.n_realizations >= MIN_BOOTSTRAP_REALIZATIONS:
            rng = np.random.default_rng(seed)
            t, _, sig, tw_pts = _stack(res._curves, res._sigma)
            law = ScaledAgeingLaw(tw_pts, res.t_ref, fit_amplitude)
            # the delays kept by the collapse (t > 0 with a standard error), per waiting time
            delays = {tw: c[0].astype(int) for tw, c in res._curves.items()}
            samples = []
            for _ in range(bootstrap):
                rows = self.z[rng.integers(0, self.n_realizations, self.n_realizations)]
                a = np.concatenate([((rows[:, int(tw) + delays[tw]] - rows[:, [int(tw)]]) ** 2)
                                    .mean(axis=0) for tw in res._curves])
                fit_b = law.fit(t, a, sig, p0=list(res.fit.params.values()))
                if fit_b.converged:
                    samples.append(list(fit_b.params.values()))
            if len(samples) >= 2:
                res.bootstrap = dict(zip(res.fit.names, np.std(samples, axis=0, ddof=1)))
        return res

    def scaling_test(self, fit_amplitude=True, start=None, t_min=1):
        """:class:`ScalingRealizationTest` of the collapse of the curves of the waiting times
        > 0 (time and amplitude, or time alone) over the delays t >= ``t_min``, started from
        ``start`` (dict of the :class:`ScaledAgeingLaw` parameters; default the collapse of
        the mean curves)."""
        require(self, "_A")
        tws = [tw for tw in self.waiting_times if tw > 0]
        t = self._t_in[self._t_in >= max(int(t_min), 1)]
        return ScalingRealizationTest(fit_amplitude).compute(self.z, tws, t, start)

    def _displacements(self, t_w):
        """(delays t > 0, (<Z>(t_w + t) - <Z>(t_w)) per realization and delay)."""
        require(self, "_A")
        if t_w not in self.A:
            raise ValueError(f"t_w = {t_w!r} is not one of the waiting times {self.waiting_times}")
        t = self._t_in[self._t_in > 0]
        return t, self.z[:, t_w + t] - self.z[:, [t_w]]

    def drift_share(self, t_w):
        """The share of A(t, t_w), summed over the delays t > 0, that is the square of the mean
        displacement (the drift of the mean compaction, the same in every realization) rather
        than their spread: A = mean(d)^2 + var(d) over realizations; the square of the mean is
        corrected for its own noise, var(d) / (n - 1), so that pure fluctuations give about 0
        and a drift without fluctuations gives 1."""
        _, d = self._displacements(t_w)
        spread = d.var(axis=0)                                  # over realizations, ddof = 0
        drift = d.mean(axis=0) ** 2 - spread / (self.n_realizations - 1)
        total = float(np.sum(self.A[t_w][self._t_in > 0]))     # A = mean(d)^2 + spread
        return float(np.sum(drift)) / total if total > 0 else np.nan

    def eq6_test(self, t_w, bins=None, t_min=1):
        """Is eq. 6 compatible with the curve of one waiting time across the realizations?
        :class:`tapmc.laws.RealizationLawTest` of :class:`tapmc.laws.AgeingLaw` on each
        realization's (<Z>(t_w + t) - <Z>(t_w))^2 over the delays t >= ``t_min``, in
        log-spaced bins (default as many as the realizations allow): Hotelling's T^2. Needs 5
        realizations (bins > the law's 3 parameters, realizations > bins)."""
        t, d = self._displacements(t_w)
        return RealizationLawTest(AgeingLaw(), bins=bins, t_min=t_min).compute(
            t.astype(float), d ** 2)

    def collapse(self, bootstrap=100, seed=0):
        """Eq. 6 fitted to all waiting times together: one (A_inf, B_A, tau_A) for every t_w
        (the scaling of Fig. 5); errors as in :meth:`fit`."""
        return self._fit(self.waiting_times, bootstrap, seed)

    def plot(self, ax=None, fit=True):
        ax = new_axis(ax)
        for tw in self.waiting_times:
            keep = self.t > 0
            ax.errorbar(self.t[keep], self.A[tw][keep], yerr=self.A_sem[tw][keep], fmt=".",
                        ms=3, label=f"$t_w$ = {tw}")
        if fit:
            res = self.collapse(bootstrap=0)
            ts = np.geomspace(max(self.t[self.t > 0].min(), 1e-3), self.t.max(), 200)
            ax.plot(ts, res(ts), "k-", label="eq. 6" + ("" if res.determined else
                                                       " (not determined)"))
        ax.set_xscale("log")
        ax.set_xlabel("t (taps)")
        ax.set_ylabel(r"$A(t, t_w)$")
        place_legend(ax)
        return ax


class ScaledAgeingLaw(Law):
    """Eq. 6 on the rescaled variables (module text): A(t, t_w) = r^kappa A_inf (1 - 1/(1 +
    B_A ln(1 + t/(tau_A r^mu)))), r = t_w/t_ref, for points (t, t_w) given as ``t`` and the
    per-point waiting times ``t_w`` of the constructor. Parameters ``A_inf, B_A, tau_A, mu,
    kappa`` (``kappa`` left out with ``fit_amplitude=False``: curves rescaled in time only)."""

    time_scales = ("tau_A",)

    def __init__(self, t_w, t_ref=None, fit_amplitude=True):
        self.t_w = as_1d("t_w", t_w)
        if np.any(self.t_w <= 0):
            raise ValueError("t_w must be > 0 everywhere (a waiting time of 0 has no scale)")
        self.t_ref = float(np.exp(np.mean(np.log(np.unique(self.t_w))))) if t_ref is None \
            else float(t_ref)
        if not (np.isfinite(self.t_ref) and self.t_ref > 0):
            raise ValueError(f"t_ref = {t_ref!r} must be finite and > 0")
        self.fit_amplitude = bool(fit_amplitude)
        self.names = ("A_inf", "B_A", "tau_A", "mu", "kappa") if self.fit_amplitude \
            else ("A_inf", "B_A", "tau_A", "mu")
        self._log_r = np.log(self.t_w / self.t_ref)

    def function(self, t, A_inf, B_A, tau_A, mu, kappa=0.0):
        log_r = self._log_r if np.shape(t) == self._log_r.shape else 0.0
        return np.exp(kappa * log_r) * AgeingLaw.function(t * np.exp(-mu * log_r), A_inf,
                                                          B_A, tau_A)

    def bounds(self, x, y):
        lo, hi = SCALING_EXPONENT_RANGE
        n = len(self.names) - 3
        return ([0.0, 0.0, 0.0] + [lo] * n, [np.inf] * 3 + [hi] * n)

    def initial_guess(self, t, y, w):
        # a grid of exponents; at each, eq. 6's own global start on the rescaled curves, on a
        # log-spaced subset of the delays of every curve
        keep = np.zeros(t.size, dtype=bool)
        for tw in np.unique(self.t_w):
            idx = np.flatnonzero(self.t_w == tw)
            order = idx[np.argsort(t[idx])]
            pick = np.unique(np.round(np.geomspace(1, order.size, _START_POINTS_PER_CURVE)))
            keep[order[pick.astype(int) - 1]] = True
        ts, ys, ws, lr = t[keep], y[keep], w[keep], self._log_r[keep]
        mus = np.linspace(-1.5, 1.5, 13)
        kappas = np.linspace(-1.5, 1.5, 13) if self.fit_amplitude else np.array([0.0])
        law = AgeingLaw()
        best = (np.inf, None)
        for mu in mus:
            for kappa in kappas:
                scale = np.exp(kappa * lr)
                s, a, wa = ts * np.exp(-mu * lr), ys / scale, ws * scale ** 2
                try:
                    p = law.initial_guess(s, a, wa)
                except ValueError:
                    continue
                sse = np.sum(wa * (law.function(s, *p) - a) ** 2)
                if sse < best[0]:
                    best = (sse, list(p) + [mu] + ([kappa] if self.fit_amplitude else []))
        if best[1] is None:
            raise ValueError("no starting point for the scaled eq. 6: check the curves")
        return best[1]


class ScalingCollapse:
    """Result of :func:`scaling_collapse`. ``fit`` (the FitResult of :class:`ScaledAgeingLaw`:
    profile ``intervals`` of ``mu``, ``kappa`` and of eq. 6's ``A_inf, B_A, tau_A`` at t_ref),
    ``unscaled`` (one eq. 6 in t for every curve, the same points and weights), ``mu``,
    ``kappa`` (0 without amplitude rescaling), ``t_ref``, ``reduced_chi2`` and
    ``unscaled_reduced_chi2`` (the collapse against no rescaling), ``jackknife`` (dict name ->
    leave-one-curve-out standard error; nan with fewer than 3 curves), ``waiting_times``,
    ``rescale(t_w, t, A)`` -> (t / r^mu, A / r^kappa) with r = t_w/t_ref, ``master(s)`` (the
    eq. 6 of the collapse on the rescaled variable), ``dispersion(mu=None, kappa=None)`` and
    ``dispersion_exponents`` (the law-free collapse, :func:`collapse_dispersion`) and
    ``plot(ax=None)``."""

    def __init__(self, fit, unscaled, curves, sigma):
        self.fit = fit
        self.unscaled = unscaled
        self._curves = curves
        self._sigma = sigma  # dict t_w -> the weights of the fit (sigma per delay)
        self._jackknife = None
        #: dict name -> standard deviation over bootstrap resamples of the realizations
        #: (:meth:`Ageing.scaling`), None when not computed
        self.bootstrap = None

    def interval(self, name):
        """The 68 % interval of parameter ``name``: its profile interval, each side widened to
        the jackknife standard error and the bootstrap standard deviation when larger (module
        text); an open side stays open, and a side widened beyond the allowed range opens
        (``tapmc.laws.Interval.widened``). A :class:`tapmc.laws.Interval`."""
        spread = [self.jackknife.get(name, np.nan)]
        if self.bootstrap is not None:
            spread.append(self.bootstrap.get(name, np.nan))
        spread = [v for v in spread if np.isfinite(v)]
        return self.fit.intervals[name].widened(max(spread) if spread else 0.0,
                                                "profile, jackknife, bootstrap")

    @property
    def waiting_times(self):
        return sorted(self._curves)

    @property
    def t_ref(self):
        return self.fit.law.t_ref

    @property
    def mu(self):
        return float(self.fit.params["mu"])

    @property
    def kappa(self):
        return float(self.fit.params.get("kappa", 0.0))

    @property
    def reduced_chi2(self):
        return float(self.fit.reduced_chi2)

    @property
    def unscaled_reduced_chi2(self):
        return float(self.unscaled.reduced_chi2)

    def rescale(self, t_w, t, A):
        r = float(t_w) / self.t_ref
        return np.asarray(t, float) / r ** self.mu, np.asarray(A, float) / r ** self.kappa

    def master(self, s):
        p = self.fit.params
        return AgeingLaw.function(np.asarray(s, float), p["A_inf"], p["B_A"], p["tau_A"])

    def dispersion(self, mu=None, kappa=None):
        """Law-free quality of the collapse at exponents ``mu``, ``kappa`` (default: the fitted
        ones): :func:`collapse_dispersion` of the curves with the weights of the fit. Compare
        ``dispersion()`` with ``dispersion(0, 0)`` (no rescaling): unlike the reduced chi2 it
        does not depend on eq. 6 being the master curve."""
        mu = self.mu if mu is None else mu
        kappa = self.kappa if kappa is None else kappa
        curves = {tw: (c[0], c[1], self._sigma[tw]) for tw, c in self._curves.items()}
        return collapse_dispersion(curves, mu, kappa, self.t_ref)

    @property
    def dispersion_exponents(self):
        """(mu, kappa) minimising :meth:`dispersion` (Nelder-Mead from the fitted exponents,
        kappa held at 0 for a collapse in time alone): the scaling variable without eq. 6."""
        from scipy.optimize import minimize

        lo, hi = SCALING_EXPONENT_RANGE
        amplitude = "kappa" in self.fit.names

        def cost(v):
            mu, kappa = (v[0], v[1]) if amplitude else (v[0], 0.0)
            if not (lo <= mu <= hi and lo <= kappa <= hi):
                return np.inf
            d = self.dispersion(mu, kappa)
            return d if np.isfinite(d) else np.inf

        start = [self.mu, self.kappa] if amplitude else [self.mu]
        res = minimize(cost, start, method="Nelder-Mead",
                       options={"xatol": 1e-3, "fatol": 1e-6, "maxiter": 400})
        return (float(res.x[0]), float(res.x[1]) if amplitude else 0.0)

    @property
    def jackknife(self):
        if self._jackknife is None:
            tws = self.waiting_times
            names = self.fit.names
            if len(tws) < 3:
                self._jackknife = {k: np.nan for k in names}
            else:
                values = []
                for drop in tws:
                    sub = {tw: c for tw, c in self._curves.items() if tw != drop}
                    t, a, sig, tw_pts = _stack(sub, self._sigma)
                    law = ScaledAgeingLaw(tw_pts, self.t_ref, "kappa" in names)
                    res = law.fit(t, a, sig, p0=list(self.fit.params.values()))
                    values.append(list(res.params.values()))
                values = np.array(values)
                k = len(tws)
                se = np.sqrt((k - 1) / k * np.sum((values - values.mean(0)) ** 2, axis=0))
                self._jackknife = dict(zip(names, se))
        return self._jackknife

    def __repr__(self):
        iv = self.interval("mu")
        lo = f"{iv.lo:.3g}" if np.isfinite(iv.lo) else "open"
        hi = f"{iv.hi:.3g}" if np.isfinite(iv.hi) else "open"
        return (f"<ScalingCollapse mu = {self.mu:.3g} [{lo}, {hi}], kappa = {self.kappa:.3g}; "
                f"reduced chi2 {self.reduced_chi2:.3g} (unscaled {self.unscaled_reduced_chi2:.3g})>")

    def plot(self, ax=None):
        """The rescaled curves and the eq. 6 of the collapse, in logarithmic time."""
        ax = new_axis(ax)
        smin, smax = np.inf, 0.0
        for tw in self.waiting_times:
            t, a, sem = self._curves[tw]
            s, y = self.rescale(tw, t, a)
            ax.plot(s, y, "o", ms=2, label=f"$t_W$ = {tw:g}")
            smin, smax = min(smin, s.min()), max(smax, s.max())
        ss = np.geomspace(smin, smax, 200)
        ax.plot(ss, self.master(ss), "k:", lw=1.5, label="eq. 6 of the collapse")
        ax.set_xscale("log")
        ax.set_xlabel(rf"$t\,/\,(t_W/{self.t_ref:.3g})^{{{self.mu:.2f}}}$")
        ax.set_ylabel(rf"$A\,/\,(t_W/{self.t_ref:.3g})^{{{self.kappa:.2f}}}$")
        place_legend(ax, fontsize=7)
        return ax


def scaling_test_min_realizations(curves, fit_amplitude=True):
    """The fewest realizations with which :class:`ScalingRealizationTest` can test the
    collapse of ``curves`` waiting times: bins >= curves and > parameters, realizations >
    bins."""
    parameters = 5 if fit_amplitude else 4
    return max(int(curves), parameters + 1) + 1


#: exponents (mu, and kappa with the amplitude) of the grid of starts of
#: :class:`ScalingRealizationTest` (within SCALING_EXPONENT_RANGE), and how many of its best
#: nodes are polished besides the collapse of the mean curves
_TEST_GRID_EXPONENTS = (-1.5, -1.0, -0.5, 0.0, 0.5, 1.0, 1.5, 2.0)
_TEST_GRID_STARTS = 4


class ScalingRealizationTest:
    """Is the collapse of Fig. 5 (:class:`ScaledAgeingLaw`: one eq. 6 on t / r^mu, amplitude
    r^kappa, r = t_w / t_ref) compatible with the curves of independent realizations?

    Every curve (delays t >= 1 of one waiting time) is cut into log-spaced bins of delays: n -
    1 bins in all for n realizations (at most :data:`tapmc.laws.REALIZATION_MAX_BINS` per
    curve), shared evenly, the remainder going to the shortest waiting times (their curves
    change most over the delays). Each realization gives one mean of (<Z>(t_w + t) -
    <Z>(t_w))^2 per bin; the collapse, averaged over each bin's delays, is fitted to the bins'
    means by GLS with their covariance over realizations, and its minimum chi-square is
    Hotelling's T^2 with q = bins - parameters (``tapmc.laws.hotelling_gls``): F = (n - q) T^2
    / (q (n - 1)) follows F(q, n - q) when the collapse holds. Needs
    :func:`scaling_test_min_realizations` realizations (7 for five waiting times with the
    amplitude, 6 in time alone).

    ``compute(z, waiting_times, t=None, start=None)``: ``z`` as :class:`Ageing`'s
    ``z_series``; ``t`` the delays (default every delay the series leaves after the longest
    waiting time); ``start`` a dict of the law's parameters (default: the
    :func:`scaling_collapse` of the mean curves). Results: ``params``, ``chi2`` (T^2),
    ``dof`` (q), ``F``, ``p_value``, ``compatible`` (p_value >=
    :data:`tapmc.laws.REALIZATION_P_MIN`), ``realizations``, ``bins`` (dict t_w -> bins of
    its curve), ``t_ref``."""

    def __init__(self, fit_amplitude=True):
        self.fit_amplitude = bool(fit_amplitude)
        self._result = None

    def compute(self, z, waiting_times, t=None, start=None):
        z = as_2d("z", z, min_rows=2, min_cols=2)
        tws = sorted({int(v) for v in np.atleast_1d(waiting_times)})
        if not tws or tws[0] <= 0:
            raise ValueError(f"waiting_times = {waiting_times!r} must be integers > 0 (a "
                             "waiting time of 0 has no scale)")
        n, taps = z.shape[0], z.shape[1] - 1
        t = np.arange(1, taps - tws[-1] + 1) if t is None else as_1d("t", t)
        t = t[t >= 1].astype(int)
        if t.size == 0 or t.max() + tws[-1] > taps:
            raise ValueError(f"delays up to {t.max() if t.size else 0} and t_w = {tws[-1]} "
                             f"need more than the {taps} taps of the series")
        needed = scaling_test_min_realizations(len(tws), self.fit_amplitude)
        if n < needed:
            raise ValueError(f"{n} realizations: the test of the collapse of {len(tws)} "
                             f"curves needs at least {needed}")
        total = min(n - 1, REALIZATION_MAX_BINS * len(tws))
        share = [total // len(tws) + (k < total % len(tws)) for k in range(len(tws))]
        per_run, rows, points_t, points_tw, bins, squares = [], [], [], [], {}, {}
        for tw, nbins in zip(tws, share):
            edges = np.unique(np.round(np.geomspace(t.min(), t.max() + 1, nbins + 1)))
            if edges.size != nbins + 1:
                raise ValueError(f"delays {t.min()}-{t.max()} are too few for {nbins} "
                                 "log-spaced bins")
            which = np.searchsorted(edges, t, side="right") - 1
            d2 = squares[tw] = (z[:, tw + t] - z[:, [tw]]) ** 2   # (realizations, delays)
            for b in range(nbins):
                member = which == b
                per_run.append(d2[:, member].mean(axis=1))
                row = np.zeros(t.size * len(tws))
                row[len(points_t) * t.size + np.flatnonzero(member)] = 1.0 / member.sum()
                rows.append(row)
            points_t.append(t.astype(float))
            points_tw.append(np.full(t.size, float(tw)))
            bins[tw] = nbins
        per_run = np.array(per_run).T                               # (realizations, bins)
        binning = np.array(rows)                                    # (bins, points)
        law = ScaledAgeingLaw(np.concatenate(points_tw), fit_amplitude=self.fit_amplitude)
        t_all = np.concatenate(points_t)
        means, cov, whiten = realization_bin_covariance(per_run)
        if start is None:
            mean_curves = {tw: (t.astype(float), d2.mean(axis=0),
                                d2.std(axis=0, ddof=1) / np.sqrt(n))
                           for tw, d2 in squares.items()}
            start = scaling_collapse(mean_curves, self.fit_amplitude).fit.params
        x0 = np.array([float(start[k]) for k in law.names])
        lo, hi = law.bounds(None, None)

        def model(x):
            return binning @ law.function(t_all, *x)

        starts = [x0] + self._grid_starts(binning, t_all, law, means, whiten, model)
        fit = hotelling_gls(means, whiten, model, starts, lo, hi, n)
        self._result = dict(fit, params=dict(zip(law.names, fit["x"])), bins=bins,
                            t_ref=law.t_ref)
        return self

    def _grid_starts(self, binning, t_all, law, means, whiten, model):
        """The :data:`_TEST_GRID_STARTS` best nodes of a grid of exponents (mu, and kappa with
        the amplitude), eq. 6's own start on the rescaled bin means at each, by their GLS
        chi-square: the minimum T^2 needs the GLS's global minimum, and the collapse of the
        mean curves, weighted per delay, can start it in another valley (a T^2 too large,
        a test too liberal)."""
        delay = binning @ t_all                    # mean delay of each bin
        log_r = binning @ law._log_r               # ln(t_w / t_ref) of each bin's curve
        kappas = _TEST_GRID_EXPONENTS if self.fit_amplitude else (0.0,)
        eq6 = AgeingLaw()
        nodes = []
        for mu in _TEST_GRID_EXPONENTS:
            for kappa in kappas:
                scale = np.exp(kappa * log_r)
                try:
                    p = eq6.initial_guess(delay * np.exp(-mu * log_r), means / scale,
                                          np.ones_like(means))
                except ValueError:
                    continue
                x = np.array(list(p) + [mu] + ([kappa] if self.fit_amplitude else []))
                with np.errstate(all="ignore"):
                    cost = float(np.sum((whiten @ (means - model(x))) ** 2))
                if np.isfinite(cost):
                    nodes.append((cost, x))
        nodes.sort(key=lambda node: node[0])
        return [x for _, x in nodes[:_TEST_GRID_STARTS]]

    def _get(self, key):
        if self._result is None:
            raise RuntimeError("call compute(z, waiting_times) first")
        return self._result[key]

    params = property(lambda self: self._get("params"))
    chi2 = property(lambda self: self._get("chi2"))
    dof = property(lambda self: self._get("dof"))
    F = property(lambda self: self._get("F"))
    p_value = property(lambda self: self._get("p_value"))
    realizations = property(lambda self: self._get("realizations"))
    bins = property(lambda self: self._get("bins"))
    t_ref = property(lambda self: self._get("t_ref"))

    @property
    def compatible(self):
        return bool(self.p_value >= REALIZATION_P_MIN)

    def __repr__(self):
        if self._result is None:
            return "<ScalingRealizationTest: not computed>"
        return (f"<ScalingRealizationTest: T2 {self.chi2:.3g} ({self.dof} dof, "
                f"{self.realizations} realizations, {sum(self.bins.values())} bins), "
                f"p {self.p_value:.3g}>")


def _clean_curves(curves):
    out = {}
    for tw, curve in curves.items():
        t, a, sem = (np.asarray(v, dtype=float) for v in curve)
        if not (t.shape == a.shape == sem.shape):
            raise ValueError(f"curve t_w = {tw}: t, A and sem must have the same length")
        keep = (t > 0) & np.isfinite(a) & np.isfinite(sem) & (sem > 0)
        if keep.sum() < 3:
            raise ValueError(f"curve t_w = {tw}: fewer than 3 delays t > 0 with a sem > 0")
        out[float(tw)] = (t[keep], a[keep], sem[keep])
    return out


def _log_window_mean(t, a):
    """Mean of ``a`` over the points whose t lies within a factor exp(_LEVEL_LOG_WINDOW) of
    each t (t > 0, sorted or not)."""
    order = np.argsort(t)
    lt = np.log(t[order])
    c = np.concatenate([[0.0], np.cumsum(a[order])])
    lo = np.searchsorted(lt, lt - _LEVEL_LOG_WINDOW, side="left")
    hi = np.searchsorted(lt, lt + _LEVEL_LOG_WINDOW, side="right")
    out = np.empty_like(a)
    out[order] = (c[hi] - c[lo]) / (hi - lo)
    return out


def collapse_dispersion(curves, mu, kappa=0.0, t_ref=None):
    """How far the curves are from one curve once rescaled, t / r^mu and A / r^kappa with r =
    t_w / t_ref (default the geometric mean of the waiting times), whatever that curve is:
    every point of each curve against every other curve interpolated (linearly in ln t) where
    they overlap, residual over the two errors combined; returns the mean squared residual
    (about 1 for curves that are one within their errors; nan when no two curves overlap).
    ``curves``: dict t_w -> (t, A, sigma), t > 0. The points of a curve are correlated, so
    compare values of it (at several exponents, or against no rescaling) rather than read it
    as a chi2 with a known distribution. Waiting times must be > 0 (t_w = 0 has no scale), at
    least 2, and every sigma > 0 (at t > 0)."""
    if len(curves) < 2:
        raise ValueError(f"curves has {len(curves)} waiting time(s); a dispersion needs at least 2")
    if any(float(tw) <= 0 for tw in curves):
        raise ValueError(f"waiting times {sorted(curves)} must be > 0 (t_w = 0 has no scale)")
    curves = {float(tw): tuple(np.asarray(v, dtype=float) for v in c) for tw, c in curves.items()}
    for tw, (t, a, sig) in curves.items():
        if not t.shape == a.shape == sig.shape or t.ndim != 1:
            raise ValueError(f"curve t_w = {tw:g}: t, A and sigma must be 1-D of one length, got "
                             f"shapes {t.shape}, {a.shape}, {sig.shape}")
        if not np.all(sig[t > 0] > 0):
            raise ValueError(f"curve t_w = {tw:g}: sigma must be > 0 at every t > 0")
    if t_ref is None:
        t_ref = float(np.exp(np.mean(np.log(list(curves)))))
    scaled = {}
    for tw, (t, a, sig) in curves.items():
        r = tw / t_ref
        keep = t > 0
        order = np.argsort(t[keep])
        scaled[tw] = (np.log(t[keep][order]) - mu * np.log(r), a[keep][order] / r ** kappa,
                      sig[keep][order] / r ** kappa)
    total, count = 0.0, 0
    for ti, (li, ai, ei) in scaled.items():
        for tj, (lj, aj, ej) in scaled.items():
            if ti == tj:
                continue
            # li is sorted: the points inside the other curve's span are one slice of it
            first = int(np.searchsorted(li, lj[0], side="left"))
            end = int(np.searchsorted(li, lj[-1], side="right"))
            if end <= first:
                continue
            at = li[first:end]
            a_other = np.interp(at, lj, aj)
            e_other = np.interp(at, lj, ej)
            r = (ai[first:end] - a_other) / np.sqrt(ei[first:end] ** 2 + e_other ** 2)
            total += float(np.sum(r ** 2))
            count += int(end - first)
    return total / count if count else np.nan


def _stack(curves, sigma=None):
    """Stacked (t, A, sigma, t_w) of the curves (dict t_w -> (t, A, sem)); sigma the curves'
    sem, or the dict t_w -> weights ``sigma``."""
    t = np.concatenate([c[0] for c in curves.values()])
    a = np.concatenate([c[1] for c in curves.values()])
    tw = np.concatenate([np.full(c[0].size, k) for k, c in curves.items()])
    sig = np.concatenate([c[2] if sigma is None else sigma[k] for k, c in curves.items()])
    return t, a, sig, tw


def scaling_collapse(curves, fit_amplitude=True):
    """Search the scaling variable of Fig. 5 (module text) from ``curves``, a dict t_w -> (t,
    A, sem) of the curves A(t, t_w) averaged over realizations (the CSV panel ``a`` of Fig. 5:
    series ``tw=<t_W>``); t = 0 and points without a standard error are left out, t_w must be
    > 0 and at least 2 curves are needed. Weights as in :meth:`Ageing.fit`: the standard
    error of a mean of squares is proportional to its mean, so sigma = model(t) x median(sem /
    A), the model being the collapse fitted first with the points' own sem (not each point's
    noisy sem), or the curve smoothed over delays within a factor 1.2 where that is higher
    (eq. 6 may not be the master curve); the unscaled eq. 6 is fitted with the same weights, so that the two reduced
    chi2 compare. Returns a :class:`ScalingCollapse`."""
    if len(curves) < 2:
        raise ValueError(f"curves has {len(curves)} waiting time(s); a collapse needs at least 2")
    if any(float(tw) <= 0 for tw in curves):
        raise ValueError(f"waiting times {sorted(curves)} must be > 0 (t_w = 0 has no scale)")
    curves = _clean_curves(curves)
    t, a, sem, tw = _stack(curves)
    positive = a > 0
    if not positive.any():
        raise ValueError("every A(t, t_w) is 0: nothing to collapse")
    ratio = float(np.median(sem[positive] / a[positive]))
    law = ScaledAgeingLaw(tw, fit_amplitude=fit_amplitude)
    first = law.fit(t, a, sem)
    # where eq. 6 misses the data (the law is not the master curve), a model far below them
    # would give their points weights without bound: never below the curve's own level,
    # A smoothed over delays within a factor exp(_LEVEL_LOG_WINDOW)
    level = np.concatenate([_log_window_mean(c[0], c[1]) for c in curves.values()])
    model = np.maximum(np.maximum(first(t), level), 1e-300) * ratio
    sigma, start = {}, 0
    for k, c in curves.items():
        sigma[k] = model[start:start + c[0].size]
        start += c[0].size
    scaled = law.fit(t, a, model, p0=list(first.params.values())).improved()
    unscaled = AgeingLaw().fit(t, a, model).improved()
    return ScalingCollapse(scaled, unscaled, curves, sigma)
