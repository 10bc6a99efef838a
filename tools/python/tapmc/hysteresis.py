# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Steady-state values along a ramp of the excitation, section III.B and Fig. 4 of Philippe &
Bideau: sqrt(eps) raised by 0.025 every 4000 taps, then lowered, then raised again; the steady
state of every level is the mean over its last 1000 taps, and the levels form the branches
'up1', 'down' and 'up2' (the paper's "irreversible" first increase and "reversible" branch)."""

import numpy as np

from ._validate import as_1d, new_axis, positive_int, result, same_length
from .fluctuations import SteadyState

__all__ = ["Hysteresis", "LEVEL_TOLERANCE"]

#: sqrt(eps) values closer than this belong to one level (thermo prints 6 digits or more)
LEVEL_TOLERANCE = 1e-6

_DTYPE = [("branch", "U4"), ("level", int), ("sqrt_eps", float), ("mean", float),
          ("sem", float), ("std", float), ("first_tap", int), ("last_tap", int)]


class Hysteresis:
    """Per-level steady states of a ramp run (section III.B, Fig. 4).

    Parameters: ``sqrt_eps_per_tap`` and ``x_per_tap`` (one entry per tap, entry k = the tap
    k + 1 and the state after it; e.g. fix tapdilate's f_ID[2] and <Phi^c> from compute
    stereo/profile, without the initial row of step 0), ``taps_per_level`` (default 4000),
    ``last`` (taps averaged at the end of each level, default 1000).

    The run is cut into consecutive levels of ``taps_per_level`` taps (an unfinished last level
    shorter than ``last`` is left out; ``incomplete_taps`` counts those taps). Inside the
    averaging window of a level sqrt(eps) must be constant. Branches: the first level and every
    level up to the highest sqrt(eps) are 'up1', the levels after it that decrease are 'down',
    and the levels after the lowest point of the descent are 'up2'.

    Results after ``compute()``: ``levels`` (numpy structured array with fields branch, level,
    sqrt_eps, mean, sem, std, first_tap, last_tap), ``branch(name)``, ``plot(ax)``."""

    def __init__(self, sqrt_eps_per_tap, x_per_tap, taps_per_level=4000, last=1000):
        self.sqrt_eps = as_1d("sqrt_eps_per_tap", sqrt_eps_per_tap)
        self.x = as_1d("x_per_tap", x_per_tap)
        same_length("sqrt_eps_per_tap", self.sqrt_eps, "x_per_tap", self.x)
        self.taps_per_level = positive_int("taps_per_level", taps_per_level, minimum=2)
        self.last = positive_int("last", last, minimum=2)
        if self.last > self.taps_per_level:
            raise ValueError(f"last = {last} exceeds taps_per_level = {taps_per_level}")
        if len(self.x) < self.last:
            raise ValueError(f"the run has {len(self.x)} taps, fewer than last = {last}")

    def compute(self):
        rows = []
        n = len(self.x)
        n_levels = int(np.ceil(n / self.taps_per_level))
        self.incomplete_taps = 0
        for k in range(n_levels):
            a = k * self.taps_per_level
            b = min(n, a + self.taps_per_level)
            if b - a < self.last:
                self.incomplete_taps = b - a
                break
            window = self.sqrt_eps[b - self.last:b]
            if np.ptp(window) > LEVEL_TOLERANCE:
                raise ValueError(f"level {k} (taps {a + 1}..{b}): sqrt(eps) varies from "
                                 f"{window.min():g} to {window.max():g} inside the averaging "
                                 f"window of the last {self.last} taps; check taps_per_level and that "
                                 "entry k is tap k + 1 (no step-0 row)")
            ss = SteadyState(self.x[a:b], last=self.last).compute()
            rows.append(["", k, float(np.median(window)), ss.mean, ss.sem, ss.std, a + 1, b])
        values = np.array([r[2] for r in rows])
        top = int(np.argmax(values))
        branch = "up1"
        for k, row in enumerate(rows):
            if k > top and branch == "up1":
                branch = "down"
            if branch == "down" and k > 0 and values[k] > values[k - 1] + LEVEL_TOLERANCE:
                branch = "up2"
            row[0] = branch
        self._levels = np.array([tuple(r) for r in rows], dtype=_DTYPE)
        return self

    levels = result("_levels")

    def branch(self, name):
        """The levels of one branch ('up1', 'down' or 'up2')."""
        if name not in ("up1", "down", "up2"):
            raise ValueError(f"branch = {name!r} must be 'up1', 'down' or 'up2'")
        return self.levels[self.levels["branch"] == name]

    def plot(self, ax=None, ylabel=r"$\langle\Phi^c\rangle$"):
        """Steady state against sqrt(eps), one marker per branch (Fig. 4)."""
        ax = new_axis(ax)
        style = {"up1": ("o", "C0"), "down": ("v", "C1"), "up2": ("^", "C2")}
        for name, (marker, color) in style.items():
            lv = self.branch(name)
            if len(lv):
                ax.errorbar(lv["sqrt_eps"], lv["mean"], yerr=lv["sem"], marker=marker,
                            color=color, ls="-", label=name, capsize=2)
        ax.set_xlabel(r"$\varepsilon^{1/2}$")
        ax.set_ylabel(ylabel)
        ax.legend()
        return ax
