# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""A vertical cylindrical container and the exact geometry of spheres inside it (numpy only).

* :class:`Cylinder`: the container's axis (cx, cy) along z and its radius, validated (finite
  centre, radius finite and > 0; :meth:`Cylinder.check_spheres` adds radius > the largest
  sphere radius), read from a LAMMPS log with :meth:`Cylinder.from_log`.
* :func:`disk_lens_area`, :func:`circle_arc_in_disk`: the area common to two disks, and the arc
  of a circle inside a disk (its derivative with respect to the circle's radius).
* :func:`sphere_cylinder_volume`: the volume of a sphere inside a coaxial cylinder and a slab,
  the integral over z of the lens area of its horizontal cut and the cylinder's disk;
  :func:`sphere_cylinder_surface_area`: the area of the sphere's material on the cylinder's
  surface (the derivative of that volume with respect to the cylinder's radius).

The integrals follow compute stereo/profile (doc/compute_stereo_profile.rst, "In a cylindrical
container"): the variable is the sphere's polar angle phi (z = -R cos phi), in which the cut
radius R sin phi is analytic; the range is split at the kinks of the integrand (the cut radius
equal to |rho - d| or rho + d, where the lens meets tangency) and at the equator; each piece is
mapped by phi = mid + half (3 t - t^3) / 2, which makes the |phi - phi_k|^(p/2) behaviour at a
kink smooth in t, and integrated by ``QUADRATURE_NODES``-point Gauss-Legendre. A sphere wholly
inside or outside takes the closed forms. Accuracy ~1e-15 R^3, the compute's.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ._validate import log_path

__all__ = ["Cylinder", "as_cylinder", "disk_lens_area", "circle_arc_in_disk", "sphere_cylinder_volume",
           "sphere_cylinder_surface_area", "sphere_slab_volume", "QUADRATURE_NODES",
           "LENS_SERIES_ANGLE"]

#: Gauss-Legendre nodes per piece of a lens integral (the compute's kCylinderQuadratureNodes)
QUADRATURE_NODES = 20
#: below this segment angle phi, phi - sin(phi) is summed as its Taylor series (thin lenses near
#: tangency keep their relative accuracy; the compute's kLensSeriesAngle)
LENS_SERIES_ANGLE = 0.25

_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(QUADRATURE_NODES)
_MAP = 0.5 * _NODES * (3.0 - _NODES * _NODES)          # phi offset / half-width
_JACOBIAN = _WEIGHTS * 1.5 * (1.0 - _NODES) * (1.0 + _NODES)


@dataclass(frozen=True)
class Cylinder:
    """A vertical cylindrical container: axis along z through (``cx``, ``cy``), wall at
    ``radius`` from the axis (LAMMPS ``region ID cylinder z cx cy radius lo hi``). Its end caps
    play no part: the floor is the analyses' own, the top is open. ValueError naming the field
    and its value unless the centre is finite and the radius finite and > 0."""

    cx: float
    cy: float
    radius: float

    def __post_init__(self):
        for name in ("cx", "cy", "radius"):
            value = getattr(self, name)
            try:
                v = float(value)
            except (TypeError, ValueError):
                raise ValueError(f"cylinder {name} = {value!r} must be a number") from None
            object.__setattr__(self, name, v)
        if not math.isfinite(self.cx):
            raise ValueError(f"cylinder cx = {self.cx!r} must be finite")
        if not math.isfinite(self.cy):
            raise ValueError(f"cylinder cy = {self.cy!r} must be finite")
        if not (math.isfinite(self.radius) and self.radius > 0):
            raise ValueError(f"cylinder radius = {self.radius!r} must be finite and > 0")

    @property
    def diameter(self):
        return 2.0 * self.radius

    @property
    def area(self):
        """pi radius^2, the cross-section that normalises the horizontal cuts."""
        return math.pi * self.radius * self.radius

    def check_spheres(self, radii):
        """The container must be wider than its largest sphere (a sphere of radius r fits only
        within radius - r of the axis): ValueError naming ``cylinder.radius`` otherwise.
        Returns self."""
        r = np.asarray(radii, dtype=float)
        largest = float(r.max()) if r.size else 0.0
        if not self.radius > largest:
            raise ValueError(f"cylinder.radius = {self.radius!r} must exceed the largest sphere "
                             f"radius {largest!r} (the container must be wider than its spheres)")
        return self

    def axis_distance(self, positions):
        """Distance of each point (N, 2 or 3) from the axis."""
        pos = np.asarray(positions, dtype=float)
        return np.hypot(pos[:, 0] - self.cx, pos[:, 1] - self.cy)

    def wall_gap(self, positions, radii):
        """(radius - r_i) - distance from the axis of each sphere: > 0 inside with room, < 0
        when its surface is beyond the wall (the flat walls' wall gap)."""
        return (self.radius - np.asarray(radii, dtype=float)) - self.axis_distance(positions)

    @classmethod
    def from_log(cls, path, region=None):
        """The container of a LAMMPS run from its log: the region named by ``region`` (default:
        the last ``container ID`` keyword the log echoes), from its last fully substituted
        ``region ID cylinder z cx cy radius ...`` command. ``path``: the log's path, or a
        :class:`~tapmc.readers.Log` read from it (its ``path``). ValueError when the log has
        none."""
        path = log_path(path)
        text = Path(path).read_text(errors="replace")
        if region is None:
            named = re.findall(r"^\s*(?:compute|fix|create_packing)\b.*\bcontainer\s+(\S+)",
                               text, re.M)
            if not named:
                raise ValueError(f"{path}: no 'container ID' keyword in the log (give region=)")
            region = named[-1]
        found = None
        pattern = (r"^\s*region\s+" + re.escape(region)
                   + r"\s+cylinder\s+z\s+(\S+)\s+(\S+)\s+(\S+)")
        for match in re.finditer(pattern, text, re.M):
            try:
                found = tuple(float(v) for v in match.groups())
            except ValueError:        # an echo before variable substitution
                continue
        if found is None:
            raise ValueError(f"{path}: no 'region {region} cylinder z cx cy radius' command "
                             "with numbers in the log")
        return cls(*found)


def as_cylinder(cylinder):
    """A :class:`tapmc.cylinder.Cylinder`, or a (cx, cy, radius) triple made into one;
    ValueError naming ``cylinder`` otherwise."""
    if isinstance(cylinder, Cylinder):
        return cylinder
    try:
        cx, cy, radius = cylinder
    except (TypeError, ValueError):
        raise ValueError(f"cylinder = {cylinder!r} must be a Cylinder or (cx, cy, radius)") \
            from None
    return Cylinder(cx, cy, radius)


def sphere_slab_volume(radius, zlo, zhi):
    """Volume of a sphere (centre at z = 0) between the heights zlo and zhi, closed form."""
    a = np.clip(zlo, -radius, radius)
    b = np.clip(zhi, -radius, radius)
    return np.where(b > a, np.pi * (b - a) * (radius * radius - (a * a + a * b + b * b) / 3.0),
                    0.0)


def _phi_minus_sin(phi):
    """phi - sin(phi), by its Taylor series below LENS_SERIES_ANGLE (terms through phi^13)."""
    phi = np.asarray(phi, dtype=float)
    p2 = phi * phi
    term = phi * p2 / 6.0
    series = np.zeros_like(phi)
    for k in range(6):
        series = series + term
        term = term * (-p2 / ((2 * k + 4) * (2 * k + 5)))
    return np.where(phi < LENS_SERIES_ANGLE, series, phi - np.sin(phi))


def _segment_area(r, theta):
    return 0.5 * r * r * _phi_minus_sin(2.0 * theta)


def _common_chord(a, b, d):
    """Half the common chord h of two crossing circles (radii a, b, centres d apart) and the
    signed distance of the chord from a's centre; h^2 from four factors of the inputs (no
    cancellation near tangency)."""
    prod = (a + b - d) * (d + a - b) * (d - a + b) * (a + b + d)
    with np.errstate(divide="ignore", invalid="ignore"):
        h = np.sqrt(np.maximum(0.0, prod)) / (2.0 * d)
        x_a = (d * d + (a - b) * (a + b)) / (2.0 * d)
    return h, x_a


def disk_lens_area(a, b, d):
    """Area common to two disks of radii ``a`` and ``b`` whose centres are ``d`` apart (0 when
    a radius is <= 0; NaN where an input is NaN); arrays broadcast. Two circular segments,
    accurate relative to the lens."""
    a, b, d = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (a, b, d)))
    small, big, d = np.minimum(a, b), np.maximum(a, b), np.abs(d)
    both = (small > 0) & (big > 0)
    full = both & (d <= big - small)
    cross = both & ~full & (d < small + big)
    h, x_a = _common_chord(small, big, d)
    with np.errstate(invalid="ignore"):
        lens = (_segment_area(small, np.arctan2(h, x_a))
                + _segment_area(big, np.arctan2(h, d - x_a)))
    return _nan_where_undefined(np.where(full, np.pi * small * small,
                                         np.where(cross, lens, 0.0)), a, b, d)


def circle_arc_in_disk(rho, a, d):
    """Length of the arc of the circle of radius ``rho`` inside the disk of radius ``a`` whose
    centre is ``d`` from the circle's: d/d(rho) of disk_lens_area(a, rho, d) (NaN where an
    input is NaN)."""
    rho, a, d = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (rho, a, d)))
    d = np.abs(d)
    both = (rho > 0) & (a > 0)
    whole = both & (d + rho <= a)
    cross = both & ~whole & ~((d >= a + rho) | (rho >= a + d))
    h, x_rho = _common_chord(rho, a, d)
    with np.errstate(invalid="ignore"):
        arc = 2.0 * rho * np.arctan2(h, x_rho)
    return _nan_where_undefined(np.where(whole, 2.0 * np.pi * rho, np.where(cross, arc, 0.0)),
                                rho, a, d)


def _nan_where_undefined(result, *inputs):
    """``result`` with NaN wherever an input is NaN: a NaN fails every comparison that selects
    a case, and would otherwise read as "no overlap", 0."""
    undefined = np.zeros(np.shape(result), dtype=bool)
    for v in inputs:
        undefined |= np.isnan(v)
    return np.where(undefined, np.nan, result) if undefined.any() else result


def _polar_angle(R, z):
    """Polar angle of height z on a sphere of radius R (0 at the bottom pole, pi at the top)."""
    return np.arctan2(np.sqrt(np.maximum(0.0, (R - z) * (R + z))), -z)


def _integrate_over_height(R, d, rho, zlo, zhi, cut):
    """Integral over z in [zlo, zhi] of cut(a(z), rho, d), a(z) = sqrt(R^2 - z^2), for 1-D
    arrays of spheres: the pieces between kinks in the polar angle, Gauss-Legendre on each
    (module text)."""
    lo, hi = np.maximum(zlo, -R), np.minimum(zhi, R)
    valid = lo < hi
    lo, hi = np.where(valid, lo, -R), np.where(valid, hi, -R)
    b0, b1 = _polar_angle(R, lo), _polar_angle(R, hi)
    candidates = [np.full_like(R, 0.5 * np.pi)]
    for c in (np.abs(rho - d), rho + d):
        ok = (c > 0) & (c < R)
        cc = np.where(ok, c, 0.0)
        phi_k = np.arctan2(cc, np.sqrt(np.maximum(0.0, (R - cc) * (R + cc))))
        candidates += [np.where(ok, phi_k, np.nan), np.where(ok, np.pi - phi_k, np.nan)]
    # a break outside (b0, b1) (or absent) becomes b1: a piece of zero width at the end
    inner = [np.where((k > b0) & (k < b1), k, b1) for k in candidates]
    breaks = np.sort(np.stack([b0, b1] + inner, axis=1), axis=1)
    half = 0.5 * (breaks[:, 1:] - breaks[:, :-1])                 # (n, pieces)
    mid = 0.5 * (breaks[:, 1:] + breaks[:, :-1])
    phi = mid[:, :, None] + half[:, :, None] * _MAP               # (n, pieces, nodes)
    s = np.sin(phi)
    values = cut(R[:, None, None] * s, rho[:, None, None], d[:, None, None])
    total = np.einsum("ipk,k->i", half[:, :, None] * s * values, _JACOBIAN)
    return np.where(valid, R * total, 0.0)


def _spheres(R, d, rho, zlo, zhi):
    R, d, rho, zlo, zhi = np.broadcast_arrays(*(np.asarray(v, dtype=float)
                                                for v in (R, d, rho, zlo, zhi)))
    return R.shape, [v.ravel() for v in (R, np.abs(d), rho, zlo, zhi)]


def sphere_cylinder_volume(R, d, rho, zlo=-np.inf, zhi=np.inf):
    """Volume of a sphere of radius ``R`` (centre at height 0) inside a vertical cylinder of
    radius ``rho`` whose axis passes ``d`` from the sphere's centre, between the heights ``zlo``
    and ``zhi`` relative to the centre (default: the whole sphere); arrays broadcast; NaN where
    an input is NaN."""
    shape, (R, d, rho, zlo, zhi) = _spheres(R, d, rho, zlo, zhi)
    out = np.zeros(R.shape)
    ok = (R > 0) & (rho > 0) & (d < rho + R) & (zlo < zhi) & (zlo < R) & (zhi > -R)
    inside = ok & (d + R <= rho)
    out[inside] = sphere_slab_volume(R[inside], zlo[inside], zhi[inside])
    cut = ok & ~inside
    if np.any(cut):
        out[cut] = _integrate_over_height(R[cut], d[cut], rho[cut], zlo[cut], zhi[cut],
                                          lambda a, r, dd: disk_lens_area(a, r, dd))
    return _nan_where_undefined(out, R, d, rho, zlo, zhi).reshape(shape)


def sphere_cylinder_surface_area(R, d, rho, zlo=-np.inf, zhi=np.inf):
    """Area of the sphere's material on the surface of the vertical cylinder of radius ``rho``
    (axis ``d`` from the centre) between ``zlo`` and ``zhi`` (relative to the centre): the
    derivative of :func:`sphere_cylinder_volume` with respect to rho; arrays broadcast."""
    shape, (R, d, rho, zlo, zhi) = _spheres(R, d, rho, zlo, zhi)
    out = np.zeros(R.shape)
    cut = ((R > 0) & (rho > 0) & (d < rho + R) & (d + R > rho) & (zlo < zhi) & (zlo < R)
           & (zhi > -R))
    if np.any(cut):
        out[cut] = _integrate_over_height(R[cut], d[cut], rho[cut], zlo[cut], zhi[cut],
                                          lambda a, r, dd: circle_arc_in_disk(r, a, dd))
    return _nan_where_undefined(out, R, d, rho, zlo, zhi).reshape(shape)
