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
"""

import numpy as np

from ._validate import as_1d, as_2d, new_axis, require, result
from .laws import AgeingLaw

__all__ = ["Ageing", "MIN_BOOTSTRAP_REALIZATIONS"]

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
    different t_w collapse; ``plot(ax)`` draws the curves and the collapse fit."""

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
        ax.legend()
        return ax
