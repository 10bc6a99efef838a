# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Density profiles, section IV.A of Philippe & Bideau (Figs. 6-8).

* :class:`ProfileIncrease`: delta Phi_lateral and delta Phi_central per tap, the lateral
  (within 7R of the walls) and central means of the transversal profile minus their initial
  values (Fig. 8); compute stereo/profile gives both means exactly (its vector, entries 5 and 6,
  with a fixed *window*).
* :func:`vertical_profile` / :func:`transversal_profile`: (position / R, Phi) from the global
  array of compute stereo/profile written by ``fix ave/time ... mode vector`` (Figs. 6, 7),
  ready for :class:`tapmc.laws.ProfileLaw` (eq. 7) and :func:`tapmc.laws.profile_gradient`.
* :func:`slab_fractions` / :func:`vertical_profile_jackknife`: the same exact slab means from
  sphere positions (a dump), and their leave-one-block-out replicates over lateral blocks: the
  error of a profile statistic (alpha) within one packing, where one run has no seeds.
"""

import numpy as np

from ._legends import place_legend
from ._validate import as_1d, computed_repr, new_axis, positive, result, same_length
from .laws import PROFILE_WINDOWS, ProfileLaw, profile_gradient  # noqa: F401 (re-exported)

__all__ = ["ProfileIncrease", "vertical_profile", "transversal_profile", "ProfileLaw",
           "profile_gradient", "PROFILE_WINDOWS", "sphere_slab_volume", "slab_fractions",
           "vertical_profile_jackknife",
           "PROFILE_JACKKNIFE_BLOCKS"]

#: lateral blocks per side of the jackknife of a vertical profile: 4 x 4 blocks of 8R x 8R at
#: the paper's L = 32R (as the pores' jackknife), each a column of some 250 spheres, far wider
#: than the 2R over which a sphere's sections reach
PROFILE_JACKKNIFE_BLOCKS = 4


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
        self.initial = None if initial is None else self._initial(initial)

    def _initial(self, initial):
        """(lateral_0, central_0), each (n_seeds, 1): one value common to all seeds or one per
        seed, finite."""
        seeds = self.lateral.shape[0]
        try:
            pair = list(initial)
        except TypeError:
            pair = []
        if len(pair) != 2:
            raise ValueError(f"initial = {initial!r} must be a pair (lateral_0, central_0), "
                             "each a value or one value per seed")
        out = []
        for name, v in zip(("lateral_0", "central_0"), pair):
            v = np.asarray(v, dtype=float).reshape(-1, 1)
            if v.shape[0] not in (1, seeds) or not np.all(np.isfinite(v)):
                raise ValueError(f"initial: {name} has {v.shape[0]} values; give 1 (common) or "
                                 f"{seeds} (one per seed), all finite")
            out.append(v)
        return tuple(out)

    @classmethod
    def from_ave_time(cls, table, lateral="c_tprof[5]", central="c_tprof[6]", initial=None):
        """From a scalar-mode :class:`tapmc.readers.AveTime` holding the two means; t is its
        ``TimeStep`` column (one tap per timestep in TAPMC runs)."""
        return cls(table.steps, table[lateral], table[central], initial)

    def compute(self):
        if self.initial is None:
            lat0, cen0 = self.lateral[:, :1], self.central[:, :1]
        else:
            lat0, cen0 = self.initial
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

    def __repr__(self):
        return computed_repr(self, "_dl", f"of {self.lateral.shape[0]} seed(s) x {len(self.t)} "
                             "times", lambda: f"delta Phi lateral {self._dl[-1]:.4g}, central "
                                              f"{self._dc[-1]:.4g} at the last time")

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
        ax.set_ylabel(r"$\delta\Phi$ (against the initial packing)")
        place_legend(ax)
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
    if isinstance(index, bool) or not isinstance(index, (int, np.integer)) or \
            not -n_t <= index < n_t:
        raise ValueError(f"index = {index!r} must be an integer block index in "
                         f"[{-n_t}, {n_t - 1}] (the file has {n_t} blocks)")
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


def sphere_slab_volume(z, radius, lo, hi):
    """Volume of each sphere (centre height ``z``, radius ``radius``) between the heights
    ``lo`` and ``hi``, exact (the integral of its cut disks' areas); the arguments broadcast
    (a radius per sphere, a pair of edges per slab)."""
    a = np.clip(lo - z, -radius, radius)
    b = np.clip(hi - z, -radius, radius)
    return np.pi * (radius * radius * (b - a) - (b ** 3 - a ** 3) / 3.0)


def _radii(radius, count):
    """A positive radius, or one per sphere (``count`` of them, each finite and > 0), as a
    column to broadcast against the slabs."""
    if np.ndim(radius) == 0:
        return positive("radius", radius)
    r = as_1d("radius", radius, min_len=0)
    if len(r) != count:
        raise ValueError(f"radius has {len(r)} values for {count} spheres (give one radius, "
                         "or one per sphere)")
    if np.any(r <= 0):
        bad = int(np.flatnonzero(r <= 0)[0])
        raise ValueError(f"radius[{bad}] = {r[bad]} must be > 0")
    return r[:, None]


def slab_fractions(z, radius, edges, area):
    """Exact mean solid fraction of each slab [edges[k], edges[k+1]) of the spheres at heights
    ``z`` (``radius``: one for all, or one per sphere: a polydisperse bed) over a base of
    ``area``: the sphere volume inside the slab over its volume, what compute stereo/profile's
    bin means are (section IV.A's smoothing); no sphere gives zeros."""
    z = as_1d("z", z, min_len=0)
    radius = _radii(radius, len(z))
    edges = as_1d("edges", edges, min_len=2)
    if np.any(np.diff(edges) <= 0):
        raise ValueError("edges must increase")
    inside = sphere_slab_volume(z[:, None], radius, edges[None, :-1], edges[None, 1:])
    return inside.sum(axis=0) / (positive("area", area) * np.diff(edges))


def vertical_profile_jackknife(positions, radius, edges, box_lo, box_hi,
                               blocks=PROFILE_JACKKNIFE_BLOCKS):
    """(profile, replicates): the exact slab fractions of the spheres at ``positions`` (n x 3;
    ``radius`` one for all or one per sphere) between the lateral bounds box_lo[:2]..box_hi[:2],
    and blocks^2 replicates, each without
    the spheres whose centres lie in one lateral block (its base area removed too). The spread
    of a statistic of the replicates (tapmc.fluctuations.jackknife_error) is its error within
    the packing."""
    pos = np.asarray(positions, dtype=float)
    if pos.ndim != 2 or pos.shape[1] != 3:
        raise ValueError(f"positions must be (n, 3), got shape {pos.shape}")
    blocks = int(blocks)
    if blocks < 2:
        raise ValueError(f"blocks = {blocks}: at least 2 per side")
    lo, hi = np.asarray(box_lo, float)[:2], np.asarray(box_hi, float)[:2]
    if np.any(hi <= lo):
        raise ValueError(f"box_hi {list(hi)} must exceed box_lo {list(lo)} in x and y")
    cell = np.clip(((pos[:, :2] - lo) / (hi - lo) * blocks).astype(int), 0, blocks - 1)
    label = cell[:, 0] + blocks * cell[:, 1]
    area = float(np.prod(hi - lo))
    width = np.diff(np.asarray(edges, float))
    radii = np.full(len(pos), positive("radius", radius)) if np.ndim(radius) == 0 else \
        _radii(radius, len(pos))[:, 0]
    per_block = np.array([slab_fractions(pos[label == k, 2], radii[label == k], edges, area)
                          * area for k in range(blocks * blocks)]) * width  # per slab
    total = per_block.sum(axis=0)
    rest = area * (1.0 - 1.0 / blocks ** 2)
    return total / (area * width), (total - per_block) / (rest * width)
