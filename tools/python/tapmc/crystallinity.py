# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Crystallinity of one packing: Steinhardt bond-orientational order and the ten Wolde-Frenkel
crystalline-sphere criterion, for the whole packing, per zone (bulk, near the floor, near the
side walls) and per height band. It answers "did tapping crystallize the densest packings, and
is there order near the walls and the floor?" from a dumped packing alone (numpy and scipy).

Bonds. Two spheres are neighbours when their centres are closer than ``cutoff`` (default
``CUTOFF_OVER_DIAMETER`` = 1.2 mean diameters, the first minimum of g(r) of dense random
packings of spheres), at the nearest periodic image along the periodic axes; a non-periodic axis
(the vertical, a wall-bounded side) never wraps.

Per-sphere order (Steinhardt, Nelson & Ronchetti, Phys. Rev. B 28, 784 (1983)). For sphere i
with N_b(i) bonds of unit vectors r_ij:

    q_lm(i) = (1/N_b(i)) sum_j Y_lm(r_ij),   q_l(i) = sqrt(4 pi/(2l+1) sum_m |q_lm(i)|^2),

with the orthonormal spherical harmonics Y_lm (Condon-Shortley phase), computed here from
``scipy.special.lpmv``. q_l(i) is invariant under rotations. Exact values at the first shell:
FCC q4 = sqrt(7/192) = 0.19094, q6 = sqrt(169/512) = 0.57452; HCP q4 = 7/72 = 0.09722,
q6 = sqrt(29237/124416) = 0.48476; BCC (8 neighbours) q4 = sqrt(7/27) = 0.50918,
q6 = sqrt(32/81) = 0.62854; SC q4 = sqrt(7/12) = 0.76376, q6 = sqrt(1/8) = 0.35355
(``LATTICE_Q``).

Global order. Q_lm is the mean of Y_lm over every bond of the packing (each bond seen from both
ends), Q_l = sqrt(4 pi/(2l+1) sum_m |Q_lm|^2): the q_l of a single crystal, ~ 1/sqrt(bonds)
for bonds of random orientation (a random packing, or crystallites of random orientations).

Crystalline spheres (ten Wolde, Ruiz-Montero & Frenkel, J. Chem. Phys. 104, 9932 (1996)). A
bond i-j is solid-like when the normalised product of the 13-vectors q_6m (m = -6 .. 6),
Re sum_m q_6m(i) q_6m(j)* / (|q_6(i)| |q_6(j)|), exceeds ``SOLID_BOND_THRESHOLD`` = 0.7; a
sphere with at least ``MIN_SOLID_BONDS`` = 8 solid-like bonds is crystalline. Every sphere of
FCC, HCP and BCC (8 neighbours) is crystalline; SC (6 neighbours) is not; a random packing has
almost none.

Zones. :meth:`Crystallinity.zones` picks the spheres whose centre lies within ``band``
(default ``NEAR_BOUNDARY_OVER_R`` = 2 R, R the mean radius) of the floor (and ``margin`` or
more from the side walls), within ``band`` of a side wall (a non-periodic lateral axis, walls
at the box faces; ``margin`` or more from the floor and the free surface), and the bulk:
``margin`` (default ``BULK_MARGIN_OVER_R`` = 7 R) or more from the floor, the walls and the
free surface (h_s, the mean column top of :class:`tapmc.packing.PackingCheck`). A sphere near
a boundary has fewer bonds (none across the floor or a wall): read its q_l with its neighbour
count. :meth:`Crystallinity.by_mask` gives the same summary for any mask, and
:meth:`Crystallinity.profile` per height band.
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from ._geometry import near_pairs, validated_box, validated_spheres
from ._legends import place_legend
from ._validate import as_1d, choice, in_range, new_axis, positive, positive_int, require, result
from .cylinder import as_cylinder
from .packing import PackingCheck
from .readers import Frame

__all__ = ["Crystallinity", "ZoneSummary", "CrystallinityProfile", "spherical_harmonics",
           "CUTOFF_OVER_DIAMETER", "SOLID_BOND_THRESHOLD", "MIN_SOLID_BONDS", "CRYSTAL_L",
           "DEFAULT_L", "MAX_L", "NEAR_BOUNDARY_OVER_R", "BULK_MARGIN_OVER_R", "LATTICE_Q"]

#: default neighbour cutoff in mean diameters: the first minimum of g(r) of dense random
#: packings of equal spheres lies near 1.2 d (before the split second peak at sqrt(3) d and
#: 2 d); it keeps the 12 first neighbours of FCC and HCP (next shell at sqrt(2) d) and the 6 of
#: SC. BCC's first 8 neighbours need a cutoff below its second shell at 2/sqrt(3) d = 1.155 d:
#: pass ``cutoff``.
CUTOFF_OVER_DIAMETER = 1.2
#: a bond i-j is solid-like when Re q6(i).q6(j)* / (|q6(i)| |q6(j)|) > 0.7, and a sphere with at
#: least 8 solid-like bonds is crystalline: the crystalline-particle criterion of ten Wolde,
#: Ruiz-Montero & Frenkel, J. Chem. Phys. 104, 9932 (1996), with the threshold values commonly
#: used for dense hard-sphere systems (the values vary between studies: both are parameters).
SOLID_BOND_THRESHOLD = 0.7
MIN_SOLID_BONDS = 8
#: the order of the bond vectors q_lm of the crystal criterion (ten Wolde et al.: l = 6)
CRYSTAL_L = 6
#: the orders reported by default: q4 and q6 together tell FCC, HCP, BCC and SC apart
#: (Steinhardt et al. 1983)
DEFAULT_L = (4, 6)
#: highest order accepted: beyond it the factorial ratio of the normalisation and lpmv lose
#: digits, and no packing question needs it
MAX_L = 12
#: zones: spheres whose centre lies within 2 R of the floor or of a side wall are the first
#: layer there (a sphere touching the floor has its centre at R; the next layer of a random
#: packing starts about 1.6 R higher)
NEAR_BOUNDARY_OVER_R = 2.0
#: the bulk keeps 7 R from the floor, the walls and the free surface: the paper's lateral zone
#: (section IV.A, Fig. 8: within 7R of the walls, ``tapmc.profiles.ProfileIncrease``)
BULK_MARGIN_OVER_R = 7.0

#: exact first-shell values {lattice: {l: q_l}}, from the Legendre addition theorem
#: q_l^2 = (1/N_b^2) sum_jk P_l(r_j . r_k) with rational cosines (module text)
LATTICE_Q = {
    "fcc": {4: math.sqrt(7 / 192), 6: math.sqrt(169 / 512)},
    "hcp": {4: 7 / 72, 6: math.sqrt(29237 / 124416)},
    "bcc": {4: math.sqrt(7 / 27), 6: math.sqrt(32 / 81)},
    "sc": {4: math.sqrt(7 / 12), 6: math.sqrt(1 / 8)},
}

#: a vector q_6m(i) shorter than this has no direction (|q_6m| <= sqrt((2l+1)/(4 pi)) = 1.02):
#: its bonds are not solid-like (guards a 0/0 that no real set of bonds reaches)
_TINY_NORM = 1e-12

ZoneSummary = namedtuple("ZoneSummary", "n crystalline_fraction q_mean Q neighbours_mean "
                                        "solid_bonds_mean")
ZoneSummary.__doc__ = (
    "Order of a set of spheres: ``n`` spheres, ``crystalline_fraction``, ``q_mean`` {l: mean "
    "q_l(i) over its spheres with bonds}, ``Q`` {l: Q_l over the bonds of its spheres}, "
    "``neighbours_mean``, ``solid_bonds_mean`` (nan values for an empty set).")
CrystallinityProfile = namedtuple("CrystallinityProfile", "edges n crystalline_fraction q_mean "
                                                          "neighbours_mean")
CrystallinityProfile.__doc__ = (
    "Order per height band: ``edges`` (n_bands + 1), ``n`` spheres with their centre in "
    "[edge_k, edge_k+1), ``crystalline_fraction``, ``q_mean`` {l: array}, ``neighbours_mean``.")


def _ylm_norm(l, m):
    return math.sqrt((2 * l + 1) / (4 * math.pi) * math.factorial(l - m) / math.factorial(l + m))


def spherical_harmonics(l, unit):
    """Y_lm(r) for m = 0 .. l of unit vectors ``unit`` (n, 3), shape (n, l + 1), complex:
    orthonormal on the sphere, Condon-Shortley phase. Y_l,-m = (-1)^m conj(Y_lm)."""
    from scipy.special import lpmv

    unit = np.asarray(unit, dtype=float)
    cos_theta = np.clip(unit[:, 2], -1.0, 1.0)
    phi = np.arctan2(unit[:, 1], unit[:, 0])
    out = np.empty((unit.shape[0], l + 1), dtype=complex)
    for m in range(l + 1):
        out[:, m] = _ylm_norm(l, m) * lpmv(m, l, cos_theta) * np.exp(1j * m * phi)
    return out


def _m_weights(l):
    """sum over m = -l..l of a product symmetric in +-m, from m >= 0 only: 1 for m = 0, 2
    above (|q_l,-m| = |q_lm| and q_l,-m(i) q_l,-m(j)* = conj(q_lm(i) q_lm(j)*))."""
    w = np.full(l + 1, 2.0)
    w[0] = 1.0
    return w


class Crystallinity:
    """Bond-orientational order and crystalline spheres of one packing (module text).

    ``positions`` (N, 3); ``radii`` (a scalar or N values, > 0: the default cutoff and the zones
    are in units of their mean); ``box_lo``, ``box_hi`` (3,) and ``periodic`` (3 bools): a
    periodic axis wraps at the box (its length must exceed 2 cutoff), a non-periodic lateral
    axis (x or y) has walls at the box faces; ``floor``: height of the floor (None: no floor);
    ``cutoff``: bond length (default ``CUTOFF_OVER_DIAMETER`` mean diameters); ``l``: the
    orders reported (integers 1 .. ``MAX_L``; ``CRYSTAL_L`` = 6 is always computed too);
    ``bond_threshold`` and ``min_solid_bonds``: the crystal criterion; ``cylinder``: the
    container of a tube run (a :class:`tapmc.cylinder.Cylinder`, with non-periodic x and y):
    its wall is the side wall of the zones and bounds the columns of h_s, where the box faces
    are otherwise. :meth:`from_frame` takes a :class:`tapmc.readers.Frame` with radii (a dump).

    After :meth:`compute`: ``n``; ``pairs`` (bonds i < j, indices into positions);
    ``neighbours`` (bonds per sphere); ``q`` {l: q_l(i), nan for a sphere without bonds};
    ``Q`` {l: global Q_l}; ``solid_bonds`` (solid-like bonds per sphere); ``crystalline``
    (bool); ``crystalline_fraction``. Then :meth:`by_mask`, :meth:`zones`, :meth:`profile`,
    :meth:`plot`."""

    def __init__(self, positions, radii, box_lo, box_hi, periodic=(True, True, False),
                 floor=None, cutoff=None, l=DEFAULT_L, bond_threshold=SOLID_BOND_THRESHOLD,
                 min_solid_bonds=MIN_SOLID_BONDS, cylinder=None):
        self.positions, r = validated_spheres(positions, radii, min_count=2)
        self.radii = r
        self.box_lo, self.box_hi, per = validated_box(box_lo, box_hi, periodic)
        self.periodic = per
        self.floor = None if floor is None else in_range("floor", floor, -math.inf, math.inf)
        if self.floor is not None and self.periodic[2]:
            raise ValueError(f"floor = {floor!r} given but z is periodic: a floor needs a "
                             "non-periodic z")
        if cylinder is not None and (self.periodic[0] or self.periodic[1]):
            raise ValueError("cylinder given but x or y is periodic: a tube needs "
                             "non-periodic x and y")
        self.cylinder = (None if cylinder is None
                         else as_cylinder(cylinder).check_spheres(r))
        self.mean_radius = float(r.mean())
        self.cutoff = (CUTOFF_OVER_DIAMETER * 2.0 * self.mean_radius if cutoff is None
                       else positive("cutoff", cutoff))
        for d in np.flatnonzero(self.periodic):
            length = float(self.box_hi[d] - self.box_lo[d])
            if length <= 2.0 * self.cutoff:
                raise ValueError(f"periodic box length along {'xyz'[d]} = {length:g} must "
                                 f"exceed 2 * cutoff = {2.0 * self.cutoff:g} (minimum image)")
        ls = [l] if np.ndim(l) == 0 else list(l)
        if not ls:
            raise ValueError("l = [] must name at least one order")
        for value in ls:
            positive_int("l", value)
            if value > MAX_L:
                raise ValueError(f"l = {value!r} must be an integer in [1, {MAX_L}]")
        self.l = tuple(sorted({int(v) for v in ls} | {CRYSTAL_L}))
        self.bond_threshold = in_range("bond_threshold", bond_threshold, -1.0, 1.0,
                                       hi_open=True)
        self.min_solid_bonds = positive_int("min_solid_bonds", min_solid_bonds)
        self.frame = None
        self._surface = None
        self._n = None

    @classmethod
    def from_frame(cls, frame, floor="box", **kwargs):
        """From a :class:`tapmc.readers.Frame` with radii (``read_dump``): its box and
        periodicity; ``floor``: "box" (default: the box's lower z bound when z is not
        periodic, as :class:`tapmc.packing.PackingCheck`), a height, or None."""
        if frame.radii is None:
            raise ValueError("frame has no radii: read the dump with a radius column or "
                             "with radius=R")
        if frame.n_atoms < 2:
            raise ValueError(f"frame holds {frame.n_atoms} atom(s); needs at least 2")
        periodic = np.asarray(frame.periodic[:3], dtype=bool)
        if isinstance(floor, str):
            choice("floor", floor, {"box"})
            floor = None if periodic[2] else float(frame.box_lo[2])
        obj = cls(frame.positions, frame.radii, frame.box_lo, frame.box_hi, periodic,
                  floor=floor, **kwargs)
        obj.frame = frame
        return obj

    # ---- computation -------------------------------------------------------------------------
    def compute(self):
        pairs, unit = self._bonds()
        n = self.positions.shape[0]
        i, j = pairs[:, 0], pairs[:, 1]
        counts = (np.bincount(i, minlength=n) + np.bincount(j, minlength=n)).astype(int)
        safe = np.maximum(counts, 1)
        sums, qlm, q, total = {}, {}, {}, {}
        for l in self.l:
            y = spherical_harmonics(l, unit)                  # bond i -> j
            sign = -1.0 if l % 2 else 1.0                     # Y_lm(-r) = (-1)^l Y_lm(r)
            s = np.empty((n, l + 1), dtype=complex)
            for m in range(l + 1):
                s[:, m] = (np.bincount(i, y[:, m].real, n) + sign * np.bincount(j, y[:, m].real, n)
                           + 1j * (np.bincount(i, y[:, m].imag, n)
                                   + sign * np.bincount(j, y[:, m].imag, n)))
            w = _m_weights(l)
            sums[l] = s
            qlm[l] = s / safe[:, None]
            q2 = (4 * np.pi / (2 * l + 1)) * (np.abs(qlm[l]) ** 2 @ w)
            q[l] = np.where(counts > 0, np.sqrt(q2), np.nan)
            total[l] = s.sum(axis=0)
        self._sums = sums
        self._Q = {l: self._global(total[l], counts.sum(), l) for l in self.l}
        # ten Wolde et al.: normalised q6(i).q6(j)* over each bond
        v = qlm[CRYSTAL_L]
        w = _m_weights(CRYSTAL_L)
        norm = np.sqrt(np.abs(v) ** 2 @ w)
        dot = ((v[i] * np.conj(v[j])).real @ w) if len(pairs) else np.empty(0)
        ok = (norm[i] > _TINY_NORM) & (norm[j] > _TINY_NORM)
        d = np.zeros(len(pairs))
        d[ok] = dot[ok] / (norm[i][ok] * norm[j][ok])
        solid = d > self.bond_threshold
        self._solid_bonds = (np.bincount(i[solid], minlength=n)
                             + np.bincount(j[solid], minlength=n)).astype(int)
        self._bond_product = d
        self._crystalline = self._solid_bonds >= self.min_solid_bonds
        self._pairs = pairs
        self._neighbours = counts
        self._q = q
        self._fraction = float(self._crystalline.mean())
        self._n = n
        return self

    def _bonds(self):
        """Bonds i < j within the cutoff (nearest image along periodic axes) and their unit
        vectors from i to j."""
        rc = self.cutoff
        pairs, delta = near_pairs(self.positions, self.box_lo, self.box_hi, self.periodic, rc)
        dist = np.sqrt(np.einsum("ij,ij->i", delta, delta))
        within = dist <= rc   # the query's slack keeps a hair more
        pairs, delta, dist = pairs[within], delta[within], dist[within]
        if np.any(dist == 0.0):
            k = int(np.flatnonzero(dist == 0.0)[0])
            raise ValueError(f"positions[{pairs[k, 0]}] and positions[{pairs[k, 1]}] coincide: "
                             "their bond has no direction")
        return pairs, delta / dist[:, None]

    @staticmethod
    def _global(sum_lm, bonds, l):
        if bonds == 0:
            return math.nan
        return float(math.sqrt((4 * math.pi / (2 * l + 1))
                               * float(np.abs(sum_lm / bonds) ** 2 @ _m_weights(l))))

    n = result("_n")
    pairs = result("_pairs")
    neighbours = result("_neighbours")
    q = result("_q")
    Q = result("_Q")
    solid_bonds = result("_solid_bonds")
    crystalline = result("_crystalline")
    crystalline_fraction = result("_fraction")
    bond_product = result("_bond_product", doc="normalised q6(i).q6(j)* of every bond of "
                                                "``pairs`` (0 for a sphere without order)")

    # ---- zones -------------------------------------------------------------------------------
    def _mask(self, mask):
        m = np.asarray(mask)
        if m.dtype != bool or m.shape != (self.positions.shape[0],):
            raise ValueError(f"mask must be {self.positions.shape[0]} booleans (one per "
                             f"sphere), got dtype {m.dtype} and shape {m.shape}")
        return m

    def by_mask(self, mask):
        """The :class:`ZoneSummary` of the spheres of ``mask`` (N booleans); their bonds may
        reach spheres outside it."""
        require(self, "_n")
        m = self._mask(mask)
        k = int(m.sum())
        if k == 0:
            nan = math.nan
            return ZoneSummary(0, nan, {l: nan for l in self.l}, {l: nan for l in self.l},
                               nan, nan)
        bonds = int(self._neighbours[m].sum())
        q_mean = {l: (float(np.nanmean(self._q[l][m])) if np.any(self._neighbours[m] > 0)
                      else math.nan) for l in self.l}
        Q = {l: self._global(self._sums[l][m].sum(axis=0), bonds, l) for l in self.l}
        return ZoneSummary(k, float(self._crystalline[m].mean()), q_mean, Q,
                           float(self._neighbours[m].mean()), float(self._solid_bonds[m].mean()))

    def zone_masks(self, band=NEAR_BOUNDARY_OVER_R, margin=BULK_MARGIN_OVER_R):
        """{"floor", "walls", "bulk"}: boolean masks, in mean radii R, of the spheres whose
        centre lies

        * "floor": within ``band`` of the floor, and ``margin`` or more from the side walls;
        * "walls": within ``band`` of a side wall (a non-periodic lateral axis), and ``margin``
          or more above the floor and below the free surface;
        * "bulk": ``margin`` or more from the floor, the walls and the free surface.

        Each zone thus sees one boundary at most (the corners and the surface layer are in
        none). Without a floor (or without walls) its mask is all False and the other zones
        ignore it."""
        band = positive("band", band) * self.mean_radius
        margin = positive("margin", margin) * self.mean_radius
        pos = self.positions
        n = pos.shape[0]
        near_floor = np.zeros(n, dtype=bool)
        off_floor = np.ones(n, dtype=bool)        # margin from the floor and the surface
        if self.floor is not None:
            height = pos[:, 2] - self.floor
            near_floor = height < band
            off_floor = (height >= margin) & (pos[:, 2] <= self.surface() - margin)
        near_wall = np.zeros(n, dtype=bool)
        off_wall = np.ones(n, dtype=bool)
        if self.cylinder is not None:  # a tube: the wall is the cylinder, not the box faces
            gap = self.cylinder.radius - self.cylinder.axis_distance(pos)
            near_wall, off_wall = gap < band, gap >= margin
        for d in (0, 1):
            if not self.periodic[d] and self.cylinder is None:
                gap = np.minimum(pos[:, d] - self.box_lo[d], self.box_hi[d] - pos[:, d])
                near_wall |= gap < band
                off_wall &= gap >= margin
        return {"floor": near_floor & off_wall, "walls": near_wall & off_floor,
                "bulk": off_floor & off_wall}

    def surface(self):
        """Height of the free surface h_s as :class:`tapmc.packing.PackingCheck` defines it
        (mean over 2R columns of the highest sphere top); None without a floor."""
        if self.floor is None:
            return None
        if self._surface is None:
            n = self.positions.shape[0]
            frame = Frame(0, self.box_lo, self.box_hi, self.periodic, np.arange(1, n + 1),
                          self.positions, self.radii)
            self._surface = PackingCheck(frame, floor=self.floor, digits=None,
                                         cylinder=self.cylinder).compute().surface
        return self._surface

    def zones(self, band=NEAR_BOUNDARY_OVER_R, margin=BULK_MARGIN_OVER_R):
        """{"all", "bulk", "floor", "walls"} -> :class:`ZoneSummary` (see :meth:`zone_masks`)."""
        require(self, "_n")
        masks = self.zone_masks(band, margin)
        out = {"all": self.by_mask(np.ones(self.positions.shape[0], dtype=bool))}
        out.update({name: self.by_mask(m) for name, m in masks.items()})
        return out

    def profile(self, z_edges):
        """A :class:`CrystallinityProfile` over height bands [edge_k, edge_k+1) of the centres
        (absolute z, as the positions)."""
        require(self, "_n")
        edges = as_1d("z_edges", z_edges, min_len=2)
        if np.any(np.diff(edges) <= 0):
            raise ValueError(f"z_edges = {list(edges)} must increase strictly")
        z = self.positions[:, 2]
        rows = [self.by_mask((z >= lo) & (z < hi)) for lo, hi in zip(edges[:-1], edges[1:])]
        return CrystallinityProfile(
            edges, np.array([r.n for r in rows]),
            np.array([r.crystalline_fraction for r in rows]),
            {l: np.array([r.q_mean[l] for r in rows]) for l in self.l},
            np.array([r.neighbours_mean for r in rows]))

    def plot(self, ax=None, l=CRYSTAL_L):
        """q_l(i) against the height of the centre (above the floor, in mean radii), the
        crystalline spheres in their own colour, the FCC and HCP values as lines."""
        require(self, "_n")
        choice("l", l, set(self.l))
        ax = new_axis(ax)
        base = 0.0 if self.floor is None else self.floor
        h = (self.positions[:, 2] - base) / self.mean_radius
        c = self._crystalline
        ax.scatter(h[~c], self._q[l][~c], s=2, color="0.6", label="other spheres")
        ax.scatter(h[c], self._q[l][c], s=4, color="C3", label="crystalline")
        for name, style in (("fcc", "--"), ("hcp", ":")):
            if l in LATTICE_Q[name]:
                ax.axhline(LATTICE_Q[name][l], ls=style, color="k", lw=0.8,
                           label=f"{name.upper()} {LATTICE_Q[name][l]:.3f}")
        ax.set_xlabel("height of the centre / R" if self.floor is not None else "z / R")
        ax.set_ylabel(f"$q_{l}(i)$")
        place_legend(ax, fontsize="small")
        return ax

    def __repr__(self):
        if self._n is None:
            return f"<Crystallinity of {self.positions.shape[0]} spheres: not computed>"
        q6 = self.q[CRYSTAL_L]
        bonded = np.isfinite(q6)   # q6 is NaN for a sphere without neighbours
        mean_q6 = f"{np.mean(q6[bonded]):.4f}" if bonded.any() else "none (no bonds)"
        return (f"<Crystallinity {self.n} spheres, cutoff {self.cutoff:.4g}: "
                f"{100 * self.crystalline_fraction:.2f} % crystalline, "
                f"Q6 {self.Q[CRYSTAL_L]:.4f}, mean q6 {mean_q6}>")
