# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Ageing as ageing (section III.C): the connected two-time function and a collapse that
assumes no law.

The paper's A(t, t_w) (eq. 5, :class:`tapmc.ageing.Ageing`) is the mean over realizations of
(<Z>(t_w + t) - <Z>(t_w))^2. Where the packing still compacts, that mean is mostly the square of
the mean displacement, the drift that every realization shares (``Ageing.drift_share``), so A
starts as t^2 and measures the compaction law, not the memory of the packing. The connected
function removes it:

    C(t, t_w) = variance over realizations of d(t, t_w),   d = <Z>(t_w + t) - <Z>(t_w),

i.e. A - mean(d)^2 with the unbiased estimator; adding one sequence to every realization (any
drift) leaves C unchanged. Ageing then means that C depends on t_w; simple ageing that it
depends on t / t_w only.

The collapse C(t, t_w) = r^kappa F(t / r^mu), r = t_w / t_ref (t_ref the geometric mean of the
waiting times), is fitted without a form for F: the exponents minimise the law-free dispersion
of the rescaled curves about each other (:func:`tapmc.ageing.collapse_dispersion`, each curve
against the others interpolated in ln t). mu = 0 is no ageing in time, mu = 1 simple ageing.
The delays of one curve share their realizations, so the exponents' error comes from the
realizations: a grouped jackknife (leave one group of realizations out, curves and exponents
recomputed), not from the dispersion's curvature.
"""

import numpy as np

from ._legends import place_legend
from ._validate import as_2d, computed_repr, new_axis, require, result
from .ageing import SCALING_EXPONENT_RANGE, collapse_dispersion

__all__ = ["ConnectedAgeing", "LawFreeCollapse", "connected_curves"]

#: groups of realizations of the jackknife of the exponents (each fit is a minimisation; more
#: groups than realizations are not possible, and ten already give the error to about 25 %).
JACKKNIFE_GROUPS = 10
#: grid of mu for the starting point of the minimisation (the range of SCALING_EXPONENT_RANGE
#: in steps of 0.1): the dispersion can have local minima where curves stop overlapping.
_MU_START_GRID = np.round(np.arange(SCALING_EXPONENT_RANGE[0], SCALING_EXPONENT_RANGE[1] + 1e-9,
                                    0.1), 10)


def connected_curves(z, waiting_times, t):
    """dict t_w -> (t, C, sigma_C) over the delays ``t`` > 0: C the unbiased variance over the
    rows of ``z`` (realizations) of <Z>(t_w + t) - <Z>(t_w), sigma_C its jackknife error over
    realizations (leave one out, in closed form)."""
    n = z.shape[0]
    out = {}
    for tw in waiting_times:
        d = z[:, tw + t] - z[:, [tw]]
        dev2 = (d - d.mean(axis=0)) ** 2
        total = dev2.sum(axis=0)
        c = total / (n - 1)
        # variance without realization i: (total - n/(n-1) dev_i^2) / (n - 2)
        loo = (total - n / (n - 1) * dev2) / (n - 2)
        sigma = np.sqrt((n - 1) / n * ((loo - loo.mean(axis=0)) ** 2).sum(axis=0))
        out[tw] = (t.astype(float), c, sigma)
    return out


class ConnectedAgeing:
    """C(t, t_w), the variance over realizations of <Z>(t_w + t) - <Z>(t_w) (module text).

    Parameters: ``z_series`` (n_realizations, n_taps + 1): <Z> after 0, 1, ... taps of every
    realization (at least 3: a variance and its jackknife error); ``waiting_times``: the t_w in
    taps (integers >= 0 leaving at least 3 delays).

    Results after ``compute()``: ``t`` (delays 1 .. n_taps - max t_w), ``C`` and ``C_error``
    (dict t_w -> array over t), ``drift`` (dict t_w -> mean displacement over realizations,
    what C leaves out). ``collapse()`` fits the exponents without a law
    (:class:`LawFreeCollapse`); ``plot(ax)`` draws C against t."""

    def __init__(self, z_series, waiting_times):
        self.z = as_2d("z_series", z_series, min_rows=3, min_cols=4)
        tw = np.atleast_1d(np.asarray(waiting_times))
        if tw.size == 0 or np.any(tw < 0) or np.any(tw != np.round(tw)):
            raise ValueError(f"waiting_times = {waiting_times!r}: must be integers >= 0 (taps)")
        self.waiting_times = sorted({int(v) for v in tw})
        taps = self.z.shape[1] - 1
        if taps - max(self.waiting_times) < 3:
            raise ValueError(f"waiting time {max(self.waiting_times)} leaves fewer than 3 "
                             f"delays in a series of {taps} taps")
        self._t_in = np.arange(1, taps - max(self.waiting_times) + 1)

    def compute(self):
        curves = connected_curves(self.z, self.waiting_times, self._t_in)
        self._t = self._t_in.astype(float)
        self._C = {tw: c[1] for tw, c in curves.items()}
        self._C_error = {tw: c[2] for tw, c in curves.items()}
        self._drift = {tw: (self.z[:, tw + self._t_in] - self.z[:, [tw]]).mean(axis=0)
                       for tw in self.waiting_times}
        return self

    t = result("_t")
    C = result("_C")

    def __repr__(self):
        return computed_repr(self, "_C", f"of {self.z.shape[0]} realizations x "
                             f"{self.z.shape[1] - 1} taps, t_w {self.waiting_times}",
                             lambda: f"C(t, t_w) at {len(self._t)} delays")
    C_error = result("_C_error")
    drift = result("_drift")

    @property
    def n_realizations(self):
        return self.z.shape[0]

    def collapse(self, fit_amplitude=True, groups=JACKKNIFE_GROUPS):
        """The law-free collapse of the curves (:class:`LawFreeCollapse`, computed)."""
        return LawFreeCollapse(fit_amplitude, groups).compute(self)

    def plot(self, ax=None):
        """C(t, t_W) against the delay, one curve per t_W with its error as a band."""
        ax = new_axis(ax)
        for tw in self.waiting_times:
            c, err = self.C[tw], self.C_error[tw]
            line, = ax.plot(self.t, c, lw=1, label=f"$t_W$ = {tw}")
            ax.fill_between(self.t, c - err, c + err, color=line.get_color(), alpha=0.2, lw=0)
        ax.set_xscale("log")
        ax.set_xlabel("delay t (taps)")
        ax.set_ylabel(r"$C(t, t_W)$ = var $[\langle Z\rangle(t_W+t) - \langle Z\rangle(t_W)]$")
        place_legend(ax, fontsize="small")
        return ax


class LawFreeCollapse:
    """Exponents mu (time) and kappa (amplitude, 0 unless ``fit_amplitude``) of the collapse
    C(t, t_w) = r^kappa F(t / r^mu) that minimise the law-free dispersion, with grouped
    jackknife errors over realizations. The curves of t_w > 0 collapse (t_w = 0 has no scale:
    its curve is left out, as :meth:`tapmc.ageing.Ageing.scaling` leaves it).

    Results after ``compute(connected)``: ``mu``, ``kappa``, ``mu_error``, ``kappa_error``,
    ``dispersion`` (at the exponents), ``dispersion_unscaled`` (mu = kappa = 0: no ageing),
    ``dispersion_simple`` (mu = 1, kappa = 0: simple ageing). ``consistent_with(mu)`` says
    whether a value of mu lies within two jackknife errors."""

    def __init__(self, fit_amplitude=True, groups=JACKKNIFE_GROUPS):
        if isinstance(groups, bool) or int(groups) != groups or groups < 2:
            raise ValueError(f"groups = {groups!r}: must be an integer >= 2")
        self.fit_amplitude = bool(fit_amplitude)
        self.groups = int(groups)

    def _exponents(self, curves):
        from scipy.optimize import minimize

        lo, hi = SCALING_EXPONENT_RANGE

        def cost(v):
            mu, kappa = (v[0], v[1]) if self.fit_amplitude else (v[0], 0.0)
            if not (lo <= mu <= hi and lo <= kappa <= hi):
                return np.inf
            d = collapse_dispersion(curves, mu, kappa)
            return d if np.isfinite(d) else np.inf

        start = min(_MU_START_GRID, key=lambda mu: cost([mu, 0.0]))
        x0 = [start, 0.0] if self.fit_amplitude else [start]
        res = minimize(cost, x0, method="Nelder-Mead",
                       options={"xatol": 1e-4, "fatol": 1e-8, "maxiter": 600})
        return float(res.x[0]), float(res.x[1]) if self.fit_amplitude else 0.0

    def compute(self, connected):
        require(connected, "_C")
        waiting = [tw for tw in connected.waiting_times if tw > 0]
        curves = {tw: (connected.t, connected.C[tw], connected.C_error[tw]) for tw in waiting}
        if len(curves) < 2:
            raise ValueError("a collapse needs at least 2 waiting times > 0, got "
                             f"{connected.waiting_times}")
        self._mu, self._kappa = self._exponents(curves)
        self._dispersion = collapse_dispersion(curves, self._mu, self._kappa)
        self._dispersion_unscaled = collapse_dispersion(curves, 0.0, 0.0)
        self._dispersion_simple = collapse_dispersion(curves, 1.0, 0.0)
        n = connected.n_realizations
        groups = np.array_split(np.arange(n), min(self.groups, n))
        values = []
        for left_out in groups:
            keep = np.setdiff1d(np.arange(n), left_out)
            sub = connected_curves(connected.z[keep], waiting, connected.t.astype(int))
            values.append(self._exponents(sub))
        values = np.array(values)
        g = len(groups)
        err = np.sqrt((g - 1) / g * ((values - values.mean(axis=0)) ** 2).sum(axis=0))
        self._mu_error, self._kappa_error = float(err[0]), float(err[1])
        return self

    mu = result("_mu")
    kappa = result("_kappa")
    mu_error = result("_mu_error")
    kappa_error = result("_kappa_error")
    dispersion = result("_dispersion")
    dispersion_unscaled = result("_dispersion_unscaled")
    dispersion_simple = result("_dispersion_simple")

    def consistent_with(self, mu):
        """Whether ``mu`` lies within two jackknife errors of the fitted mu."""
        return abs(self.mu - mu) <= 2.0 * self.mu_error

    def __repr__(self):
        if getattr(self, "_mu", None) is None:
            return "LawFreeCollapse(not computed)"
        return (f"LawFreeCollapse(mu={self.mu:.3f} +- {self.mu_error:.3f}, kappa="
                f"{self.kappa:.3f} +- {self.kappa_error:.3f}, dispersion {self.dispersion:.3g} "
                f"(no ageing {self.dispersion_unscaled:.3g}, simple ageing "
                f"{self.dispersion_simple:.3g}))")
