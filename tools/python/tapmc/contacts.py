# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Contacts of one packing within a gap: the coordination number of every sphere, its floor
contact, and their distribution P(Z), as ``compute contacts`` defines them
(doc/compute_contacts.rst), from a dump (:func:`tapmc.readers.read_dump`) or from arrays
(numpy and scipy).

The gap ``g`` is relative to each pair's contact distance. Spheres i and j are in contact when

    |r_ij| <= (R_i + R_j) (1 + g + tol),

that is when the gap between their surfaces is at most g (R_i + R_j); sphere i touches the floor
z0 when z_i - R_i - z0 <= (g + tol) 2 R_i (its surface gap to the plane is at most g times its
diameter), and the wall of a tube (``cylinder``, the compute's ``container``) when
(R_c - R_i) - d_i <= (g + tol) 2 R_i, d_i its distance from the axis. ``tol`` = ``GAP_TOLERANCE`` = 1e-10 is the model's contact tolerance
(src/TAPMC/tapmc_defaults.h, kContactsGapTolerance): with g = 0 the spheres the model takes as
touching count (exact lattices, the analytic contacts of create_packing). Along a periodic axis
a pair is taken at its nearest image (the period must exceed twice the largest contact reach
2 R_max (1 + g)); a non-periodic axis never wraps. The floor, when given, counts as one contact
of each sphere touching it.

The counts of a Monte Carlo packing depend strongly on the gap: its spheres never touch exactly
(their gaps are continuous), so g = 0 finds almost no contact after a tap, and the mean
coordination climbs with g (numbers in doc/compute_contacts.rst). :meth:`Contacts.sweep` gives
that curve from one neighbour search.

Counts equal the compute's exactly for the same spheres (a dump written with ``%.17g`` holds
them exactly), up to a pair whose distance lies within rounding (~1e-16 relative) of its
threshold.
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from ._geometry import near_pairs, validated_box, validated_spheres
from ._legends import place_legend
from ._validate import as_1d, choice, in_range, new_axis, require, result
from .cylinder import as_cylinder

__all__ = ["Contacts", "ContactSummary", "GapSweep", "GAP_TOLERANCE", "MAX_GAP", "FEW_BELOW",
           "MAX_Z"]

#: relative rounding tolerance of the contact rule (tapmc_defaults.h, kContactsGapTolerance =
#: kContactTolerance): g = 0 counts exact contacts made with rounding
GAP_TOLERANCE = 1e-10
#: largest gap (kContactsMaxGap): beyond one contact distance the count is a neighbour shell
MAX_GAP = 1.0
#: ``fraction_few`` counts the spheres with fewer contacts than this (kContactsFewBelow: a
#: frictionless sphere needs d + 1 = 4 contacts to be locally jammed in three dimensions)
FEW_BELOW = 4
#: the distribution has rows Z = 0 .. MAX_Z, the last holding every Z >= MAX_Z (kContactsMaxZ)
MAX_Z = 24

ContactSummary = namedtuple("ContactSummary", "n mean fraction_none fraction_few fraction_floor "
                                              "largest distribution")
ContactSummary.__doc__ = (
    "Contacts of a set of spheres: ``n`` spheres, ``mean`` coordination <Z>, ``fraction_none`` "
    "(Z = 0), ``fraction_few`` (Z < FEW_BELOW), ``fraction_floor`` (touching the floor), "
    "``largest`` Z, ``distribution`` P(Z) for Z = 0 .. MAX_Z (last row: Z >= MAX_Z); the "
    "fractions and the mean are 0 for an empty set, as the compute gives them.")
GapSweep = namedtuple("GapSweep", "gaps mean fraction_none fraction_few fraction_floor")
GapSweep.__doc__ = ("The contacts of one packing at several gaps: ``gaps`` and, one value per "
                    "gap, ``mean``, ``fraction_none``, ``fraction_few``, ``fraction_floor``.")


def _summary(counts, on_floor):
    n = int(counts.size)
    if n == 0:
        return ContactSummary(0, 0.0, 0.0, 0.0, 0.0, 0, np.zeros(MAX_Z + 1))
    hist = np.bincount(np.minimum(counts, MAX_Z), minlength=MAX_Z + 1).astype(float)
    return ContactSummary(n, float(counts.mean()), float(np.mean(counts == 0)),
                          float(np.mean(counts < FEW_BELOW)), float(np.mean(on_floor)),
                          int(counts.max()), hist / n)


class Contacts:
    """Coordination numbers of one packing within a gap (module text).

    ``positions`` (N, 3); ``radii`` (a scalar or N values, > 0); ``box_lo``, ``box_hi`` (3,)
    and ``periodic`` (3 bools): the box matters along periodic axes only; ``gap``: g in
    [0, ``MAX_GAP``], relative to each pair's contact distance; ``floor``: height of the floor
    plane whose contacts count (None: no floor, as the compute without its ``floor`` keyword);
    ``cylinder``: a tube's container (a :class:`tapmc.cylinder.Cylinder`, as the compute's
    ``container``), whose wall counts as one contact of each sphere touching it (None: no
    wall, as the compute without ``container``). :meth:`from_frame` takes a :class:`tapmc.readers.Frame` with radii (a dump), with its box
    and periodicity.

    After :meth:`compute`: ``n``; ``coordination`` (N ints: contacts with other spheres, plus 1
    for the floor and 1 for the wall); ``on_floor`` and ``on_wall`` (N bools each); ``pairs`` (the contacts i < j, indices into
    positions); ``mean``, ``fraction_none``, ``fraction_few``, ``fraction_floor``, ``largest``,
    ``distribution`` (P(Z), ``MAX_Z`` + 1 rows) and ``summary`` (the compute's vector and
    array in one :class:`ContactSummary`). Then :meth:`by_mask`, :meth:`sweep`, :meth:`plot`."""

    def __init__(self, positions, radii, box_lo, box_hi, periodic=(True, True, False), gap=0.0,
                 floor=None, cylinder=None):
        self.positions, self.radii = validated_spheres(positions, radii)
        self.box_lo, self.box_hi, per = validated_box(box_lo, box_hi, periodic)
        self.periodic = per
        self.gap = in_range("gap", gap, 0.0, MAX_GAP)
        self.floor = None if floor is None else in_range("floor", floor, -math.inf, math.inf,
                                                         lo_open=True, hi_open=True)
        if self.floor is not None and self.periodic[2]:
            raise ValueError(f"floor = {floor!r} given but z is periodic: a floor needs a "
                             "non-periodic z")
        if cylinder is not None and (self.periodic[0] or self.periodic[1]):
            raise ValueError("cylinder given but x or y is periodic: a tube needs non-periodic "
                             "x and y")
        self.cylinder = (None if cylinder is None
                         else as_cylinder(cylinder).check_spheres(self.radii))
        self._check_periods(self.gap)
        self.frame = None
        self._n = None

    @classmethod
    def from_frame(cls, frame, gap=0.0, floor=None, select=None, cylinder=None):
        """From a :class:`tapmc.readers.Frame` with radii (``read_dump``): its box and
        periodicity. ``floor``: None (no floor contacts), a height, or "box" (the box's lower z
        bound). ``select``: N booleans choosing the spheres that count (the compute's group:
        the others neither count nor are counted); None: all."""
        if frame.radii is None:
            raise ValueError("frame has no radii: read the dump with a radius column or "
                             "with radius=R")
        if isinstance(floor, str):
            choice("floor", floor, {"box"})
            floor = float(frame.box_lo[2])
        pos, radii = np.asarray(frame.positions, float), np.asarray(frame.radii, float)
        if select is not None:
            m = np.asarray(select)
            if m.dtype != bool or m.shape != (frame.n_atoms,):
                raise ValueError(f"select must be {frame.n_atoms} booleans (one per atom), got "
                                 f"dtype {m.dtype} and shape {m.shape}")
            pos, radii = pos[m], radii[m]
        obj = cls(pos, radii, frame.box_lo, frame.box_hi, np.asarray(frame.periodic[:3], bool),
                  gap=gap, floor=floor, cylinder=cylinder)
        obj.frame = frame
        return obj

    def _check_periods(self, gap):
        if self.radii.size == 0:
            return
        reach = 2.0 * float(self.radii.max()) * (1.0 + gap + GAP_TOLERANCE)
        for d in np.flatnonzero(self.periodic):
            length = float(self.box_hi[d] - self.box_lo[d])
            if not length > 2.0 * reach:
                raise ValueError(f"periodic box length along {'xyz'[d]} = {length:g} must exceed "
                                 f"2 reach = {2.0 * reach:g} (reach = 2 R_max (1 + gap): nearest "
                                 "images)")

    # ---- computation -------------------------------------------------------------------------
    def _candidates(self, gap):
        """Pairs i < j within the largest reach at ``gap`` (a superset of the contacts) and
        their separations at the nearest image."""
        pos, r = self.positions, self.radii
        if pos.shape[0] < 2:
            return np.empty((0, 2), dtype=np.intp), np.empty((0, 3))
        reach = 2.0 * float(r.max()) * (1.0 + gap + GAP_TOLERANCE)
        # separations as the compute's counter takes them: coordinates wrapped into the box along
        # periodic axes (unchanged when inside), x_j - x_i, then the image shift
        pairs, delta = near_pairs(pos, self.box_lo, self.box_hi, self.periodic, reach)
        return pairs, delta

    def _touching_wall(self, gap):
        """The spheres touching the tube's wall at ``gap`` (none without ``cylinder``)."""
        if self.cylinder is None:
            return np.zeros(self.positions.shape[0], dtype=bool)
        r = self.radii
        gap_to_wall = (self.cylinder.radius - r) - self.cylinder.axis_distance(self.positions)
        return gap_to_wall <= (gap + GAP_TOLERANCE) * (2.0 * r)

    def _counts(self, pairs, dist2, gap):
        """(coordination, on_floor, contact mask of the pairs) at ``gap``; the wall's contacts
        are in the coordination."""
        n, r = self.positions.shape[0], self.radii
        reach = (r[pairs[:, 0]] + r[pairs[:, 1]]) * (1.0 + gap + GAP_TOLERANCE)
        touching = dist2 <= reach * reach
        i, j = pairs[touching, 0], pairs[touching, 1]
        counts = np.bincount(i, minlength=n) + np.bincount(j, minlength=n)
        if self.floor is None:
            on_floor = np.zeros(n, dtype=bool)
        else:
            z = self.positions[:, 2]
            on_floor = (z - r) - self.floor <= (gap + GAP_TOLERANCE) * (2.0 * r)
        on_wall = self._touching_wall(gap)
        return counts.astype(int) + on_floor.astype(int) + on_wall.astype(int), on_floor, touching

    def compute(self):
        pairs, delta = self._candidates(self.gap)
        dist2 = (delta[:, 0] * delta[:, 0] + delta[:, 1] * delta[:, 1]) + delta[:, 2] * delta[:, 2]
        counts, on_floor, touching = self._counts(pairs, dist2, self.gap)
        self._pairs = pairs[touching]
        self._coordination = counts
        self._on_floor = on_floor
        self._on_wall = self._touching_wall(self.gap)
        self._summary = _summary(counts, on_floor)
        self._n = self.positions.shape[0]
        return self

    n = result("_n")
    coordination = result("_coordination")
    on_floor = result("_on_floor")
    on_wall = result("_on_wall")
    pairs = result("_pairs")
    summary = result("_summary")

    @property
    def mean(self):
        return self.summary.mean

    @property
    def fraction_none(self):
        return self.summary.fraction_none

    @property
    def fraction_few(self):
        return self.summary.fraction_few

    @property
    def fraction_floor(self):
        return self.summary.fraction_floor

    @property
    def fraction_wall(self):
        """The share of spheres touching the tube's wall (0 without ``cylinder``): the
        compute's vector entry 6."""
        return float(np.mean(self.on_wall)) if self.n else 0.0

    @property
    def largest(self):
        return self.summary.largest

    @property
    def distribution(self):
        return self.summary.distribution

    def by_mask(self, mask):
        """The :class:`ContactSummary` of the spheres of ``mask`` (N booleans), with their
        contacts counted against all spheres (e.g. the bulk of a packing, away from its floor
        and surface)."""
        require(self, "_n")
        m = np.asarray(mask)
        if m.dtype != bool or m.shape != (self.positions.shape[0],):
            raise ValueError(f"mask must be {self.positions.shape[0]} booleans (one per "
                             f"sphere), got dtype {m.dtype} and shape {m.shape}")
        return _summary(self._coordination[m], self._on_floor[m])

    def sweep(self, gaps):
        """The contacts at every gap of ``gaps`` (each in [0, ``MAX_GAP``]), from one
        neighbour search at the largest: a :class:`GapSweep`. The instance's own ``gap`` is not
        used; each value is what :meth:`compute` gives at that gap."""
        g = as_1d("gaps", gaps)
        for value in g:
            in_range("gaps", value, 0.0, MAX_GAP)
        self._check_periods(float(g.max()))
        pairs, delta = self._candidates(float(g.max()))
        dist2 = (delta[:, 0] * delta[:, 0] + delta[:, 1] * delta[:, 1]) + delta[:, 2] * delta[:, 2]
        rows = [_summary(*self._counts(pairs, dist2, float(v))[:2]) for v in g]
        return GapSweep(g, np.array([s.mean for s in rows]),
                        np.array([s.fraction_none for s in rows]),
                        np.array([s.fraction_few for s in rows]),
                        np.array([s.fraction_floor for s in rows]))

    def plot(self, ax=None):
        """P(Z) as bars (the last bar holds Z >= ``MAX_Z``), the mean as a vertical line."""
        require(self, "_n")
        ax = new_axis(ax)
        z = np.arange(MAX_Z + 1)
        ax.bar(z, self.distribution, width=0.8, color="C0",
               label=f"gap {self.gap:g} of the contact distance")
        ax.axvline(self.mean, color="k", lw=0.8, ls="--", label=f"<Z> = {self.mean:.3f}")
        ax.set_xlabel("contacts Z")
        ax.set_ylabel("P(Z)")
        place_legend(ax, fontsize="small")
        return ax

    def __repr__(self):
        if self._n is None:
            return (f"<Contacts of {self.positions.shape[0]} spheres, gap {self.gap:g}: "
                    "not computed>")
        return (f"<Contacts {self.n} spheres, gap {self.gap:g}: <Z> {self.mean:.4f}, "
                f"{100 * self.fraction_none:.2f} % without contact>")
