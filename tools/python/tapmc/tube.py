# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Exact stereology of a packing in a vertical tube, from sphere positions (a dump), as
``compute stereo/profile ... container ID`` defines it (doc/compute_stereo_profile.rst, "In a
cylindrical container"), with numpy only.

Every measure counts the sphere material inside the container's disk (a sphere inside the tube
counts whole; one poking through the wall of an invalid packing counts with its part inside):

* horizontal cuts are normalised by pi Rc^2 instead of the box's L_x L_y: Phi(z), Phi_b over
  [z0, z0 + 4R], <Phi^c> with its 16/11 wall band, the window top z_top = z0 + 0.9 (h_s - z0),
  h_s from columns 2R wide tiling the container's bounding square;
* the lateral zone becomes the wall zone, the annulus within w = 7R of the wall, and the central
  zone the core r < Rc - w, over the z-window [z0 + 2R, z_top];
* the transversal profile is radial: coaxial annuli and the cylindrical surfaces at their
  central radii.

:class:`TubeStereology` gives the compute's vector (``vector``) and arrays
(:meth:`TubeStereology.vertical_profile`, :meth:`TubeStereology.radial_profile`), each a
:class:`TubeProfile`. The sphere volumes inside a coaxial cylinder come from
:mod:`tapmc.cylinder`. On the same positions (a dump written with ``%.17g``) the numbers equal
the compute's to rounding (tests/python/test_tube.py: 1e-9).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from ._geometry import validated_spheres
from ._legends import place_legend
from ._validate import in_range, new_axis, positive, positive_int, require, result
from .cylinder import (Cylinder, as_cylinder, disk_lens_area, sphere_cylinder_surface_area,
                       sphere_cylinder_volume)
from ._stereo_defaults import (BULK_OVER_R, COLUMN_OVER_R, TOP_FRACTION, WALL_BAND_OVER_R,
                               WALL_FACTOR, column_count)

__all__ = ["TubeStereology", "TubeProfile", "as_cylinder", "WALL_ZONE_OVER_R",
           "WINDOW_BOTTOM_OVER_R", "PROFILE_BINS"]

#: width of the wall zone, in mean radii: the paper's lateral zone within 7R of the walls
#: (section IV.A, FIG. 8), bent round (the compute's *lateral* default)
WALL_ZONE_OVER_R = 7.0
#: bottom of the default z-window of the zones and the radial profile, above the floor
WINDOW_BOTTOM_OVER_R = 2.0
#: bins of a profile when none are given (the compute's *planes* default n)
PROFILE_BINS = 100


def _planes(name, planes):
    try:
        lo, hi, n = planes
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {planes!r} must be (lo, hi, n)") from None
    lo = in_range(f"{name} lo", lo, -math.inf, math.inf)
    hi = in_range(f"{name} hi", hi, -math.inf, math.inf)
    if not hi > lo:
        raise ValueError(f"{name} = {planes!r}: hi must exceed lo")
    return np.linspace(lo, hi, positive_int(f"{name} n", n) + 1)


@dataclass(frozen=True)
class TubeProfile:
    """One profile of compute stereo/profile in a tube: ``axis`` 'z' (horizontal cuts over the
    disk) or 'r' (coaxial annuli within the z-window ``window``); ``position`` (the planes: z,
    or the central radius from the axis), ``phi_plane`` (Phi at the plane, or the covered
    fraction of the cylindrical surface), ``phi_bin`` (the exact mean over the bin, or the
    annulus' volume fraction), ``edges`` (bin edges), ``cylinder`` (when known), ``step``
    (the timestep, from a file). ``rows`` is the compute's array (n, 3)."""

    axis: str
    position: np.ndarray
    phi_plane: np.ndarray
    phi_bin: np.ndarray
    edges: np.ndarray
    window: Optional[tuple] = None
    cylinder: Optional[Cylinder] = None
    step: Optional[int] = None

    @property
    def rows(self):
        return np.column_stack([self.position, self.phi_plane, self.phi_bin])

    def mean(self):
        """The volume fraction of the whole range: the bins' means weighted by their volumes
        (annuli's areas for axis r)."""
        weight = (np.diff(self.edges ** 2) if self.axis == "r" else np.diff(self.edges))
        return float(np.sum(weight * self.phi_bin) / np.sum(weight))

    def plot(self, ax=None, settings=None, label=None, **kw):
        """The bin means against the position (axis r: the distance from the axis, the wall
        marked when the cylinder is known); ``settings`` (a string or an object with
        ``describe()``) becomes the title. Returns the axis."""
        ax = new_axis(ax)
        step = "" if self.step is None else f"t = {self.step}"
        ax.plot(self.position, self.phi_bin, marker=".", label=label or step or None, **kw)
        if self.axis == "r":
            ax.set_xlabel("distance from the axis r (distance units)")
            ax.set_ylabel(r"annulus volume fraction $\Phi(r)$")
            if self.cylinder is not None:
                ax.axvline(self.cylinder.radius, color="0.5", lw=0.8, ls="--")
        else:
            ax.set_xlabel("height z (distance units)")
            ax.set_ylabel(r"$\Phi(z)$ over the disk (bin mean)")
        if settings is not None:
            ax.set_title(settings if isinstance(settings, str) else settings.describe(),
                         fontsize=8)
        if label or step:
            place_legend(ax, fontsize=8)
        return ax


class TubeStereology:
    """compute stereo/profile with a container, from positions.

    ``positions`` (N, 3), ``radii`` (a scalar or N values > 0), ``cylinder`` (a
    :class:`tapmc.cylinder.Cylinder` or (cx, cy, radius), wider than the largest sphere),
    ``floor`` (z0). The compute's keywords, in distance units, None for the default in mean
    radii R: ``bulk`` (4R), ``wall_band`` (R), ``wall_factor`` (16/11), ``top_fraction``
    (0.9), ``column`` (2R), ``lateral`` (the wall zone's width w, 7R), ``window`` ((za, zb),
    default (z0 + 2R, z_top)).

    After :meth:`compute`: ``phi_b``, ``phi_c``, ``z_mean``, ``window_top``, ``phi_wall``,
    ``phi_core`` (NaN when w >= Rc: no core), ``surface`` (h_s), ``window`` (za, zb),
    ``wall_width`` (w), ``mean_radius`` and ``vector`` (the compute's 7 entries, in order).
    :meth:`cut_fraction` gives Phi(z) at any heights, :meth:`vertical_profile` and
    :meth:`radial_profile` the compute's arrays."""

    def __init__(self, positions, radii, cylinder, floor=0.0, bulk=None, wall_band=None,
                 wall_factor=WALL_FACTOR, top_fraction=TOP_FRACTION, column=None,
                 lateral=None, window=None):
        self.positions, self.radii = validated_spheres(positions, radii, min_count=1)
        self.cylinder = as_cylinder(cylinder).check_spheres(self.radii)
        self.floor = in_range("floor", floor, -math.inf, math.inf)
        self.bulk = None if bulk is None else positive("bulk", bulk)
        self.wall_band = None if wall_band is None else positive("wall_band", wall_band)
        self.wall_factor = positive("wall_factor", wall_factor)
        self.top_fraction = in_range("top_fraction", top_fraction, 0.0, 1.0, lo_open=True)
        self.column = None if column is None else positive("column", column)
        self.lateral = None if lateral is None else positive("lateral", lateral)
        if window is not None:
            try:
                za, zb = (float(v) for v in window)
            except (TypeError, ValueError):
                raise ValueError(f"window = {window!r} must be (za, zb)") from None
            if not (math.isfinite(za) and math.isfinite(zb) and za < zb):
                raise ValueError(f"window = {window!r} must be finite with za < zb")
            window = (za, zb)
        self.fixed_window = window
        self.distance = self.cylinder.axis_distance(self.positions)
        self._vector = None

    @classmethod
    def from_frame(cls, frame, cylinder, floor=None, **settings):
        """From a dumped :class:`tapmc.readers.Frame` with radii; the floor defaults to the
        box's lower z bound (the compute's default)."""
        if frame.radii is None:
            raise ValueError("frame has no radii: read the dump with a radius column or "
                             "with radius=R")
        floor = float(frame.box_lo[2]) if floor is None else floor
        return cls(frame.positions, frame.radii, cylinder, floor=floor, **settings)

    # ---- the sums ----------------------------------------------------------------------------
    def _volume(self, zlo, zhi, rho=None):
        """Sphere volume inside the coaxial cylinder of radius rho (default the container's)
        between the absolute heights zlo and zhi."""
        z = self.positions[:, 2]
        rho = self.cylinder.radius if rho is None else rho
        return float(np.sum(sphere_cylinder_volume(self.radii, self.distance, rho,
                                                   zlo - z, zhi - z)))

    def _surface(self, mean_r):
        c, rc = self.cylinder, self.cylinder.radius
        ncol = column_count(2.0 * rc, self.column or COLUMN_OVER_R * mean_r,
                            given=self.column is not None)
        width = 2.0 * rc / ncol
        ij = [np.clip(np.floor((self.positions[:, k] - (centre - rc)) / width).astype(int),
                      0, ncol - 1) for k, centre in ((0, c.cx), (1, c.cy))]
        tops = np.full(ncol * ncol, -np.inf)
        np.maximum.at(tops, ij[0] + ncol * ij[1], self.positions[:, 2] + self.radii)
        filled = tops[np.isfinite(tops)]
        return float(filled.mean()) if filled.size else self.floor

    def compute(self):
        r, z0, area = self.radii, self.floor, self.cylinder.area
        mean_r = float(r.mean())
        surface = self._surface(mean_r)
        top = z0 + self.top_fraction * max(0.0, surface - z0)
        bulk_top = z0 + (self.bulk or BULK_OVER_R * mean_r)
        band_top = min(top, z0 + (self.wall_band or WALL_BAND_OVER_R * mean_r))
        za, zb = self.fixed_window or (z0 + WINDOW_BOTTOM_OVER_R * mean_r, top)
        width = self.lateral or WALL_ZONE_OVER_R * mean_r

        def ratio(num, den):
            return num / den if den > 0 else 0.0

        phi_b = ratio(self._volume(z0, bulk_top), area * (bulk_top - z0))
        phi_c = ratio(self.wall_factor * self._volume(z0, band_top)
                      + self._volume(band_top, top), area * (top - z0))
        rc = self.cylinder.radius
        core = max(0.0, rc - width)
        height = max(0.0, zb - za)
        v_all = self._volume(za, zb) if za < zb else 0.0
        v_core = self._volume(za, zb, core) if (za < zb and core > 0) else 0.0
        wall_area = math.pi * (rc - core) * (rc + core)
        phi_wall = ratio(v_all - v_core, wall_area * height)
        phi_core = (ratio(v_core, math.pi * core * core * height) if core > 0 else math.nan)
        z_mean = float(np.mean(self.positions[:, 2] - z0))
        self._mean_r, self._window, self._width = mean_r, (za, zb), width
        self._surface_h, self._top = surface, top
        self._vector = np.array([phi_b, phi_c, z_mean, top, phi_wall, phi_core, surface])
        return self

    vector = result("_vector", doc="The compute's 7 entries: Phi_b, <Phi^c>, <Z>, z_top, "
                                   "phi_wall, phi_core, h_s.")
    phi_b = property(lambda self: float(require(self, "_vector")[0]))
    phi_c = property(lambda self: float(require(self, "_vector")[1]))
    z_mean = property(lambda self: float(require(self, "_vector")[2]))
    window_top = property(lambda self: float(require(self, "_vector")[3]))
    phi_wall = property(lambda self: float(require(self, "_vector")[4]))
    phi_core = property(lambda self: float(require(self, "_vector")[5]))
    surface = property(lambda self: float(require(self, "_vector")[6]))
    window = result("_window")
    wall_width = result("_width")
    mean_radius = result("_mean_r")

    def scalars(self):
        """The vector as a dict named like the taps.dat columns of examples/cylinder."""
        v = self.vector
        return {"Phi_b": v[0], "<Phi^c>": v[1], "<Z>": v[2], "z_top": v[3], "phi_wall": v[4],
                "phi_core": v[5], "h_s": v[6]}

    # ---- cuts and profiles -------------------------------------------------------------------
    def cut_fraction(self, z):
        """Phi(z) over the disk at the heights ``z`` (the cut disks' area inside the container
        over pi Rc^2)."""
        z = np.atleast_1d(np.asarray(z, dtype=float))
        u = z[:, None] - self.positions[None, :, 2]
        r = self.radii[None, :]
        a2 = np.where(np.abs(u) < r, (r - u) * (r + u), 0.0)
        area = disk_lens_area(np.sqrt(a2), self.cylinder.radius, self.distance[None, :])
        return area.sum(axis=1) / self.cylinder.area

    def vertical_profile(self, planes=None):
        """compute stereo/profile's array with axis z in the tube: ``planes`` (lo, hi, n)
        (default: the floor to the highest sphere top, PROFILE_BINS bins); a
        :class:`TubeProfile`."""
        if planes is None:
            planes = (self.floor, float(np.max(self.positions[:, 2] + self.radii)), PROFILE_BINS)
        edges = _planes("planes", planes)
        z = self.positions[:, 2]
        volume = sphere_cylinder_volume(self.radii[None, :], self.distance[None, :],
                                        self.cylinder.radius, edges[:-1, None] - z[None, :],
                                        edges[1:, None] - z[None, :]).sum(axis=1)
        centre = 0.5 * (edges[1:] + edges[:-1])
        return TubeProfile("z", centre, self.cut_fraction(centre),
                           volume / (self.cylinder.area * np.diff(edges)), edges,
                           cylinder=self.cylinder)

    def radial_profile(self, planes=None, window=None):
        """compute stereo/profile's array with axis r: annuli of ``planes`` (lo, hi, n) radii
        (default 0 .. Rc, PROFILE_BINS bins; lo >= 0) within the z-window ``window`` (default
        the zones' window, computed first); a :class:`TubeProfile`."""
        edges = _planes("planes", planes if planes is not None
                        else (0.0, self.cylinder.radius, PROFILE_BINS))
        if edges[0] < 0:
            raise ValueError(f"planes lo = {edges[0]!r} must be >= 0 (a radius)")
        if window is None:
            if self._vector is None:
                self.compute()
            window = self.fixed_window or self._window
        za, zb = (float(v) for v in window)
        centre = 0.5 * (edges[1:] + edges[:-1])
        height = max(0.0, zb - za)
        z = self.positions[:, 2]
        if height > 0:
            shape = (edges.size, z.size)
            args = (np.broadcast_to(self.radii, shape), np.broadcast_to(self.distance, shape))
            inside = sphere_cylinder_volume(*args, np.broadcast_to(edges[:, None], shape),
                                            za - z, zb - z)
            volume = np.diff(inside, axis=0).sum(axis=1)
            surface = sphere_cylinder_surface_area(*(a[:-1] for a in args),
                                                   np.broadcast_to(centre[:, None],
                                                                   (centre.size, z.size)),
                                                   za - z, zb - z).sum(axis=1)
            with np.errstate(invalid="ignore", divide="ignore"):
                phi_plane = np.where(centre > 0, surface / (2 * np.pi * centre * height), 0.0)
                annulus = np.pi * np.diff(edges) * (edges[1:] + edges[:-1]) * height
                phi_bin = np.where(annulus > 0, volume / annulus, 0.0)
        else:
            phi_plane = phi_bin = np.zeros(centre.size)
        return TubeProfile("r", centre, phi_plane, phi_bin, edges, window=(za, zb),
                           cylinder=self.cylinder)

    def __repr__(self):
        c = self.cylinder
        head = (f"<TubeStereology {len(self.radii)} spheres in the tube (cx {c.cx:g}, cy "
                f"{c.cy:g}, Rc {c.radius:g})")
        if self._vector is None:
            return head + ": not computed>"
        return (head + f": Phi_b {self.phi_b:.4f}, <Phi^c> {self.phi_c:.4f}, wall zone "
                f"{self.phi_wall:.4f}, core {self.phi_core:.4f}>")
