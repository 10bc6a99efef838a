# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The vertical profile of the packing fraction (section IV.A): eq. 7 (:class:`ProfileLaw`)
and the straight-line gradient alpha in the paper's window (:func:`profile_gradient`,
:class:`StraightLine`, the numerator of eq. 7)."""

import warnings

import numpy as np

from .._validate import as_1d, same_length
from .fitting import Law

__all__ = ["StraightLine", "profile_gradient", "ProfileLaw", "PROFILE_WINDOWS"]

#: gradient windows of the paper (section IV.A), in units of R.
PROFILE_WINDOWS = {"fbc": (5.0, 22.0), "pbc": (5.0, 26.0)}
#: A default window whose lowest Phi falls below this fraction of its median reaches the free
#: surface's decay (a bed lower than the paper's 28 R or so): the line would fit the decay as a
#: gradient (alpha 0.0048 for 0.0017 on a 24 R bed), so profile_gradient warns.
SURFACE_DECAY_FRACTION = 0.9


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
    paper. Returns a :class:`FitResult` (params ``Phi0``, ``alpha``). A default window that
    reaches the free surface's decay (Phi below :data:`SURFACE_DECAY_FRACTION` of the window's
    median: a bed lower than the window) gives a warning: give ``window`` below the surface."""
    default = window is None
    lo, hi = _window(window, boundary)
    zb = as_1d("zb", zb)
    phi = as_1d("phi", phi)
    same_length("zb", zb, "phi", phi)
    inside = (zb >= lo) & (zb <= hi)
    if inside.sum() < 3:
        raise ValueError(f"window = ({lo:g}, {hi:g}) holds {inside.sum()} profile points; "
                         "at least 3 are needed")
    s = None if sigma is None else np.broadcast_to(np.asarray(sigma, float), zb.shape)[inside]
    median = float(np.median(phi[inside]))
    low = int(np.argmin(phi[inside]))
    if default and phi[inside][low] < SURFACE_DECAY_FRACTION * median:
        warnings.warn(f"the default window ({lo:g}, {hi:g}) of boundary {boundary!r} reaches the "
                      f"free surface's decay (Phi {phi[inside][low]:.3g} at z/R = "
                      f"{zb[inside][low]:.3g}, below {SURFACE_DECAY_FRACTION:g} of the window's "
                      f"median {median:.3g}): the line fits the decay as a gradient; give "
                      "window=(lo, hi) below the surface (e.g. an eq. 7 fit's zb_star - 3/beta)",
                      stacklevel=2)
    return StraightLine().fit(zb[inside], phi[inside], s)


class ProfileLaw(Law):
    """Eq. 7 (section IV.A): Phi(zb) = (Phi0 - alpha zb) / (1 + exp(beta (zb - zb_star))),
    zb = z/R. Parameters ``Phi0, alpha, beta, zb_star`` (beta > 0). The fit uses the points
    with zb >= window[0] (above the wall layers whose peaks eq. 7 does not describe); the
    window (default 5..22 for ``boundary='fbc'``, 5..26 for 'pbc') also sets the starting
    values of (Phi0, alpha) by :func:`profile_gradient`. A negative gradient in the paper's
    wording means the density decreases with height, i.e. alpha > 0 here."""

    x_label = "z/R"
    y_label = "Phi(z)"

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
