# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""One packing checked offline: is it a legal hard-sphere packing (no overlaps, nothing below
the floor or through a side wall, section II), and what are its stereology scalars, recomputed
from the positions alone as ``compute stereo/profile`` defines them
(doc/compute_stereo_profile.rst): Phi_b, <Phi^c> (with its data-defined window top and the
16/11 wall band), <Z>, the surface height h_s and the window top z_top.

A run prints its scalars every tap and dumps a few packings; :class:`PackingCheck` on a dump
reproduces the printed row of that tap independently of the compute (numpy, no LAMMPS), and
tells whether thousands of taps left any overlap behind.

In a tube (``cylinder=``, a :class:`tapmc.cylinder.Cylinder`: the run's ``container``), the
side wall is the cylinder's (``wall_gap`` is the radial gap) and the scalars are those of
compute stereo/profile with that container (:class:`tapmc.tube.TubeStereology`), with the wall
zone and the core beside them.

Dumps round the positions: a dump written with ``%.10g`` (what the paper inputs write) knows a
coordinate x to 0.5 * 10^(floor(log10 |x|) - 9). A pair's distance is then known to within
``2 sqrt(3)`` times that, which :attr:`PackingCheck.resolution` gives in absolute units; a pair
counts as overlapping only when it is closer than contact by more than the model's contact
tolerance (1e-10 of R_i + R_j, src/TAPMC/tapmc_defaults.h) plus that resolution.
"""

from __future__ import annotations

import math

import numpy as np

from ._geometry import near_pairs, validated_box, validated_spheres
from ._stereo_defaults import (BULK_OVER_R, COLUMN_OVER_R, TOP_FRACTION, WALL_BAND_OVER_R,
                               WALL_FACTOR, column_count)
from ._validate import in_range, positive, positive_int, require, result
from .cylinder import as_cylinder
from .profiles import sphere_slab_volume
from .tube import TubeStereology

__all__ = ["PackingCheck", "CONTACT_TOLERANCE", "DUMP_DIGITS", "WALL_FACTOR", "TOP_FRACTION",
           "BULK_OVER_R", "COLUMN_OVER_R", "WALL_BAND_OVER_R"]

#: relative contact tolerance of the model: i and j overlap when |r_ij| < (R_i + R_j)(1 - tol)
#: (src/TAPMC/tapmc_defaults.h, kContactTolerance)
CONTACT_TOLERANCE = 1e-10
#: significant digits of the coordinates in the paper inputs' dumps (``format float %.10g``),
#: taken for a frame that does not say how it was written (one made by hand)
DUMP_DIGITS = 10
#: ``digits`` default: the frame's own (``Frame.digits``, read from the dump's text)
FRAME_DIGITS = "frame"


class PackingCheck:
    """Integrity and stereology scalars of one packing.

    ``frame``: a :class:`tapmc.readers.Frame` with radii (a dump with a ``radius`` column, or
    read with ``radius=``). ``floor``: height of the floor (default: the box's lower z bound,
    as the compute's default). ``digits``: significant digits of the dump's coordinates (default
    ``"frame"``: those the dump was written with, ``frame.digits``, e.g. 6 for LAMMPS's default
    ``%g`` and 10 for ``%.10g``; 10 for a frame made by hand; ``None``: exact positions,
    resolution 0). ``contact_tolerance``: the model's relative
    tolerance. ``cylinder``: the container of a tube run (a :class:`tapmc.cylinder.Cylinder`
    wider than the largest sphere), None for a box.

    After :meth:`compute`: ``n``; ``min_gap`` (the smallest |r_ij| - (R_i + R_j) over pairs,
    relative to R_i + R_j: negative for an overlap) and ``closest_pair`` (the two atom ids);
    ``overlaps`` (pairs closer than contact by more than tolerance and resolution);
    ``floor_gap`` (lowest sphere bottom above the floor, over its diameter), ``wall_gap``
    (closest sphere surface to a side wall along a non-periodic lateral axis, or to the
    cylinder's wall, over its diameter; None when both lateral axes are periodic);
    ``legal`` (no overlap and nothing through the floor or a wall beyond the same
    allowances); the scalars ``phi_b``,
    ``phi_c``, ``z_mean`` (<Z> above the floor), ``surface`` (h_s) and ``window_top``
    (z_top); in a tube (``cylinder``) also ``phi_wall`` and ``phi_core``."""

    def __init__(self, frame, floor=None, digits=FRAME_DIGITS,
                 contact_tolerance=CONTACT_TOLERANCE, cylinder=None):
        if frame.radii is None:
            raise ValueError("frame has no radii: read the dump with a radius column or "
                             "with radius=R")
        if frame.n_atoms < 1:
            raise ValueError("frame holds no atoms")
        self.frame = frame
        self.positions, self.radii = validated_spheres(frame.positions, frame.radii)
        self.box_lo, self.box_hi, self.periodic = validated_box(frame.box_lo, frame.box_hi,
                                                                np.asarray(frame.periodic, bool))
        # a sphere must not overlap its own image (the pairs are checked at nearest images,
        # which are the ones that can overlap)
        diameter = 2.0 * float(self.radii.max())
        for d in np.flatnonzero(self.periodic):
            length = float(self.box_hi[d] - self.box_lo[d])
            if not length >= diameter:
                raise ValueError(f"periodic box length along {'xyz'[d]} = {length:g} must be at "
                                 f"least the largest diameter {diameter:g} (a sphere would "
                                 "overlap its own image)")
        self.floor = (float(self.box_lo[2]) if floor is None
                      else in_range("floor", floor, -math.inf, math.inf))
        if isinstance(digits, str) and digits == FRAME_DIGITS:
            digits = getattr(frame, "digits", None) or DUMP_DIGITS
        self.digits = None if digits is None else positive_int("digits", digits)
        self.contact_tolerance = positive("contact_tolerance", contact_tolerance,
                                          allow_zero=True)
        self.cylinder = (None if cylinder is None
                         else as_cylinder(cylinder).check_spheres(self.radii))
        self._n = None

    @property
    def resolution(self):
        """Bound on the rounding error of one pair distance (absolute units; 0 for exact
        positions): 2 sqrt(3) times the rounding of the largest coordinate."""
        if self.digits is None:
            return 0.0
        largest = float(np.max(np.abs(self.positions)))
        if largest == 0.0:
            return 0.0
        half_unit = 0.5 * 10.0 ** (math.floor(math.log10(largest)) + 1 - self.digits)
        return 2.0 * math.sqrt(3.0) * half_unit

    def compute(self):
        self._geometry()
        self._stereology()
        self._n = self.frame.n_atoms
        return self

    # ---- geometry ----------------------------------------------------------------------------
    def _geometry(self):
        pos, r = self.positions, self.radii
        lo, hi, periodic = self.box_lo, self.box_hi, self.periodic
        reach = 2.0 * float(r.max())
        radius = reach * (1.0 + 1e-6)
        pairs, delta = near_pairs(pos, lo, hi, periodic, radius)
        # no pair within reach: widen the search until the nearest pair is in it
        span = 2.0 * (float(np.ptp(pos, axis=0).max()) + reach)
        while not len(pairs) and len(pos) > 1 and radius < span:
            radius *= 2.0
            pairs, delta = near_pairs(pos, lo, hi, periodic, radius)
        allowance = self.contact_tolerance
        if len(pairs):
            i, j = pairs[:, 0], pairs[:, 1]
            contact = r[i] + r[j]
            relative = (np.sqrt(np.einsum("ij,ij->i", delta, delta)) - contact) / contact
            k = int(np.argmin(relative))
            self._min_gap = float(relative[k])
            self._closest = (int(self.frame.ids[i[k]]), int(self.frame.ids[j[k]]))
            self._overlaps = int(np.count_nonzero(
                relative < -(allowance + self.resolution / contact)))
        else:  # a single sphere: no pair
            self._min_gap, self._closest, self._overlaps = math.inf, None, 0
        floor_gaps = (pos[:, 2] - r - self.floor) / (2.0 * r)
        self._floor_gap = float(floor_gaps.min())
        walls = [d for d in (0, 1) if not periodic[d]]
        if self.cylinder is not None:
            self._wall_gap = float(np.min(self.cylinder.wall_gap(pos, r) / (2.0 * r)))
        elif walls:
            gaps = [np.minimum(pos[:, d] - r - lo[d], hi[d] - pos[:, d] - r) / (2.0 * r)
                    for d in walls]
            self._wall_gap = float(min(g.min() for g in gaps))
        else:
            self._wall_gap = None
        slack = allowance + self.resolution / (2.0 * float(r.min()))
        self._legal = (self._overlaps == 0 and self._floor_gap >= -slack
                       and (self._wall_gap is None or self._wall_gap >= -slack))

    # ---- stereology (compute stereo/profile's scalars) ---------------------------------------
    def _stereology(self):
        if self.cylinder is not None:
            tube = TubeStereology(self.positions, self.radii, self.cylinder,
                                  floor=self.floor).compute()
            (self._phi_b, self._phi_c, self._z_mean, self._window_top, self._phi_wall,
             self._phi_core, self._surface) = (float(v) for v in tube.vector)
            return
        pos, r = self.positions, self.radii
        lo, hi, periodic = self.box_lo, self.box_hi, self.periodic[:2]
        mean_r = float(r.mean())
        area = float((hi[0] - lo[0]) * (hi[1] - lo[1]))
        z0, z = self.floor, pos[:, 2]
        # h_s: the mean over occupied columns (2R wide, tiling the box) of the highest top
        column = [0, 0]
        ncol = [0, 0]
        for d in (0, 1):
            length = float(hi[d] - lo[d])
            ncol[d] = column_count(length, COLUMN_OVER_R * mean_r)
            width = length / ncol[d]
            c = np.floor((pos[:, d] - lo[d]) / width).astype(int)
            column[d] = np.mod(c, ncol[d]) if periodic[d] else np.clip(c, 0, ncol[d] - 1)
        tops = np.full(ncol[0] * ncol[1], -np.inf)
        np.maximum.at(tops, column[0] + ncol[0] * column[1], z + r)
        filled = tops[np.isfinite(tops)]
        self._surface = float(filled.mean()) if filled.size else z0
        self._window_top = z0 + TOP_FRACTION * max(0.0, self._surface - z0)
        bulk_top = z0 + BULK_OVER_R * mean_r
        bulk = sphere_slab_volume(z, r, z0, bulk_top).sum()
        self._phi_b = float(bulk / (area * (bulk_top - z0)))
        band_top = min(z0 + WALL_BAND_OVER_R * mean_r, self._window_top)
        height = self._window_top - z0
        if height > 0:
            band = sphere_slab_volume(z, r, z0, band_top).sum()
            rest = sphere_slab_volume(z, r, band_top, self._window_top).sum()
            self._phi_c = float((WALL_FACTOR * band + rest) / (area * height))
        else:
            self._phi_c = 0.0
        self._z_mean = float(np.mean(z - z0))

    n = result("_n")
    min_gap = result("_min_gap")
    closest_pair = result("_closest")
    overlaps = result("_overlaps")
    floor_gap = result("_floor_gap")
    legal = result("_legal")
    phi_b = result("_phi_b")
    phi_c = result("_phi_c")
    z_mean = result("_z_mean")
    surface = result("_surface")
    window_top = result("_window_top")

    @property
    def phi_wall(self):
        """In a tube: the wall zone's volume fraction (within 7R of the wall); else None."""
        require(self, "_n")
        return self._phi_wall if self.cylinder is not None else None

    @property
    def phi_core(self):
        """In a tube: the core's volume fraction (NaN without a core); else None."""
        require(self, "_n")
        return self._phi_core if self.cylinder is not None else None

    @property
    def wall_gap(self):
        require(self, "_n")     # None is a result here (periodic sides), so check compute()
        return self._wall_gap

    def scalars(self):
        """The compute's scalars in the order of a paper input's taps.dat columns
        (phi_b, phi_c, Z, z_top, h_s), as a dict; in a tube phi_wall and phi_core follow."""
        out = {"phi_b": self.phi_b, "phi_c": self.phi_c, "Z": self.z_mean,
               "z_top": self.window_top, "h_s": self.surface}
        if self.cylinder is not None:
            out.update(phi_wall=self.phi_wall, phi_core=self.phi_core)
        return out

    def __repr__(self):
        if self._n is None:
            return f"<PackingCheck of {self.frame!r}: not computed>"
        return (f"<PackingCheck {self.n} spheres: min gap {self.min_gap:.3g}, "
                f"{self.overlaps} overlaps, legal {self.legal}>")
