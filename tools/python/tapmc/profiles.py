# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Density profiles, section IV.A of Philippe & Bideau (Figs. 6-8).

* :class:`ProfileIncrease`: delta Phi_lateral and delta Phi_central per tap, the lateral
  (within 7R of the walls) and central means of the transversal profile minus their initial
  values (Fig. 8); compute stereo/profile gives both means exactly (its vector, entries 5 and 6,
  with a fixed *window*).
* :func:`vertical_profile` / :func:`transversal_profile`: (position / R, Phi) from the global
  array of compute stereo/profile written by ``fix ave/time ... mode vector`` (Figs. 6, 7),
  ready for :class:`tapmc.laws.ProfileLaw` (eq. 7) and :func:`tapmc.laws.profile_gradient`.
"""

import numpy as np

from ._validate import as_1d, new_axis, positive, result, same_length
from .laws import PROFILE_WINDOWS, ProfileLaw, profile_gradient  # noqa: F401 (re-exported)

__all__ = ["ProfileIncrease", "vertical_profile", "transversal_profile", "ProfileLaw",
           "profile_gradient", "PROFILE_WINDOWS"]


def _series(name, values):
    arr = np.asarray(values, dtype=float)
    if arr.ndim == 1:
        arr = arr[None, :]
    if arr.ndim != 2 or arr.shape[1] < 1:
        raise ValueError(f"{name} must be one series (n_t,) or several seeds (n_seeds, n_t), "
                         f"got shape {np.shape(values)}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} holds non-finite values")
    return arr


class ProfileIncrease:
    """delta Phi_lateral(t) and delta Phi_central(t) against the initial profile (section
    IV.A, Fig. 8).

    Parameters: ``t`` (taps, n_t), ``lateral`` and ``central`` (the lateral and central means,
    shape (n_t,) or (n_seeds, n_t) for several realizations), ``initial`` (optional pair
    (lateral_0, central_0), per seed or common; default the values at the first entry, which
    should be t = 0, the initial packing).

    Results after ``compute()``: ``delta_lateral``, ``delta_central`` (means over seeds),
    ``delta_lateral_sem``, ``delta_central_sem`` (standard errors over seeds; NaN for one seed)
    and ``delta_lateral_all``, ``delta_central_all`` (per seed)."""

    def __init__(self, t, lateral, central, initial=None):
        self.t = as_1d("t", t)
        self.lateral = _series("lateral", lateral)
        self.central = _series("central", central)
        if self.lateral.shape != self.central.shape:
            raise ValueError(f"lateral has shape {self.lateral.shape} but central has "
                             f"{self.central.shape}; they must match")
        same_length("t", self.t, "lateral (per seed)", self.lateral[0])
        self.initial = initial

    @classmethod
    def from_ave_time(cls, table, lateral="c_tprof[5]", central="c_tprof[6]", initial=None):
        """From a scalar-mode :class:`tapmc.readers.AveTime` holding the two means; t is its
        ``TimeStep`` column (one tap per timestep in TAPMC runs)."""
        return cls(table.steps, table[lateral], table[central], initial)

    def compute(self):
        if self.initial is None:
            lat0, cen0 = self.lateral[:, :1], self.central[:, :1]
        else:
            lat0, cen0 = (np.asarray(v, dtype=float).reshape(-1, 1) for v in self.initial)
        self._dl_all = self.lateral - lat0
        self._dc_all = self.central - cen0
        n = self._dl_all.shape[0]
        self._dl = self._dl_all.mean(axis=0)
        self._dc = self._dc_all.mean(axis=0)
        if n > 1:
            self._dl_sem = self._dl_all.std(axis=0, ddof=1) / np.sqrt(n)
            self._dc_sem = self._dc_all.std(axis=0, ddof=1) / np.sqrt(n)
        else:
            self._dl_sem = np.full_like(self._dl, np.nan)
            self._dc_sem = np.full_like(self._dc, np.nan)
        return self

    delta_lateral = result("_dl")
    delta_central = result("_dc")
    delta_lateral_sem = result("_dl_sem")
    delta_central_sem = result("_dc_sem")
    delta_lateral_all = result("_dl_all")
    delta_central_all = result("_dc_all")

    def plot(self, ax=None, logx=True):
        """delta Phi_lateral and delta Phi_central against taps (Fig. 8)."""
        ax = new_axis(ax)
        keep = self.t > 0 if logx else np.ones_like(self.t, dtype=bool)
        for values, sem, label in ((self.delta_lateral, self.delta_lateral_sem, "lateral"),
                                   (self.delta_central, self.delta_central_sem, "central")):
            ax.errorbar(self.t[keep], values[keep],
                        yerr=None if np.all(np.isnan(sem)) else sem[keep], marker=".",
                        label=r"$\delta\Phi_{%s}$" % label)
        if logx:
            ax.set_xscale("log")
        ax.set_xlabel("taps")
        ax.legend()
        return ax


def _profile(table, radius, origin, index, value):
    if not getattr(table, "vector", False):
        raise ValueError("expected a vector-mode fix ave/time table of compute stereo/profile "
                         "(read_ave_time of a 'mode vector' file)")
    radius = positive("radius", radius)
    if value not in ("bin", "plane"):
        raise ValueError(f"value = {value!r} must be 'bin' (exact bin mean, column 3) or "
                         "'plane' (Phi at the plane, column 2)")
    n_t = table.blocks.shape[0]
    if not -n_t <= index < n_t:
        raise ValueError(f"index = {index} outside the {n_t} blocks of the file")
    if table.blocks.shape[2] < 3:
        raise ValueError("the table needs the 3 columns of compute stereo/profile's array")
    block = table.blocks[index]
    return (block[:, 0] - origin) / radius, block[:, 2 if value == "bin" else 1]


def vertical_profile(table, radius, floor=0.0, index=-1, value="bin"):
    """(z/R above the floor, Phi) of block ``index`` of a vector-mode ave/time table of
    ``compute stereo/profile`` (axis z). ``value`` 'bin' gives the exact mean over each bin
    (the smoothing of section IV.A), 'plane' the surface fraction at the plane."""
    return _profile(table, radius, float(floor), index, value)


def transversal_profile(table, radius, wall=0.0, index=-1, value="bin"):
    """(x/R from the wall at ``wall``, Phi) of a transversal profile (compute stereo/profile
    with axis x or y), block ``index``."""
    return _profile(table, radius, float(wall), index, value)
