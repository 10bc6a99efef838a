# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Spheres in an orthogonal box and their near pairs at the nearest image: the argument checks
and the neighbour search that the offline analyses of one packing share (contacts,
crystallinity, packing)."""

import numpy as np

from ._validate import as_1d

#: relative slack of the tree query beyond the radius asked for: the tree's arithmetic differs
#: from the callers' exact rules in the last bits, so the query keeps a hair more and the
#: callers decide on their own separations
QUERY_SLACK = 1e-9


def validated_spheres(positions, radii, min_count=0):
    """(positions (N, 3) floats, radii (N,) floats): finite positions, radii a scalar or N
    values, all > 0; at least ``min_count`` spheres. ValueError naming what is wrong."""
    pos = np.asarray(positions, dtype=float)
    if pos.ndim != 2 or pos.shape[1] != 3:
        raise ValueError(f"positions must have shape (N, 3), got {pos.shape}")
    if pos.shape[0] < min_count:
        raise ValueError(f"positions holds {pos.shape[0]} sphere(s); needs at least {min_count}")
    if not np.all(np.isfinite(pos)):
        bad = int(np.flatnonzero(~np.all(np.isfinite(pos), axis=1))[0])
        raise ValueError(f"positions[{bad}] = {pos[bad]} is not finite (all must be)")
    n = pos.shape[0]
    r = np.asarray(radii, dtype=float)
    if r.ndim == 0:
        r = np.full(n, float(r))
    r = as_1d("radii", r, min_len=0)
    if r.size != n:
        raise ValueError(f"radii has {r.size} values but positions has {n} spheres")
    if np.any(~(r > 0)):
        bad = int(np.flatnonzero(~(r > 0))[0])
        raise ValueError(f"radii[{bad}] = {r[bad]} must be > 0")
    return pos, r


def validated_box(box_lo, box_hi, periodic):
    """(box_lo (3,), box_hi (3,), periodic (3,) bools), box_hi > box_lo along every axis."""
    lo, hi = as_1d("box_lo", box_lo), as_1d("box_hi", box_hi)
    for name, v in (("box_lo", lo), ("box_hi", hi)):
        if v.size != 3:
            raise ValueError(f"{name} = {list(v)} must hold 3 values (x, y, z)")
    if np.any(hi <= lo):
        raise ValueError(f"box_hi = {list(hi)} must exceed box_lo = {list(lo)} along every axis")
    per = np.asarray(periodic)
    if per.shape != (3,) or per.dtype != bool:
        raise ValueError(f"periodic = {periodic!r} must be 3 booleans (x, y, z)")
    return lo, hi, per.copy()


def wrapped_positions(positions, box_lo, box_hi, periodic):
    """The positions with every coordinate along a periodic axis taken into [lo, hi) (those
    already inside unchanged, bit for bit), as compute contacts' counter takes them."""
    wrapped = np.array(positions, dtype=float)
    for d in np.flatnonzero(periodic):
        lo, hi = float(box_lo[d]), float(box_hi[d])
        length = hi - lo
        x = wrapped[:, d]
        outside = (x < lo) | (x >= hi)
        w = x - np.floor((x - lo) / length) * length
        w = np.where(w >= hi, w - length, np.where(w < lo, w + length, w))
        wrapped[:, d] = np.where(outside, np.clip(w, lo, np.nextafter(hi, lo)), x)
    return wrapped


def near_pairs(positions, box_lo, box_hi, periodic, radius):
    """(pairs, delta) of the spheres at ``positions``: every pair i < j (rows sorted) whose
    centres lie within ``radius`` (and a relative QUERY_SLACK more) at the nearest image along
    the periodic axes, and delta = x_j - x_i at that image, from the wrapped positions
    (:func:`wrapped_positions`). A periodic length must exceed 2 radius (one image per pair);
    the callers check it with their own message."""
    from scipy.spatial import cKDTree

    pos = np.asarray(positions, dtype=float)
    if pos.shape[0] < 2:
        return np.empty((0, 2), dtype=np.intp), np.empty((0, 3))
    radius = float(radius)
    wrapped = wrapped_positions(pos, box_lo, box_hi, periodic)
    shifted = np.empty_like(pos)
    boxsize = np.empty(3)
    for d in range(3):
        if periodic[d]:
            length = float(box_hi[d] - box_lo[d])
            t = wrapped[:, d] - float(box_lo[d])
            shifted[:, d] = np.where(t >= length, 0.0, t)
            boxsize[d] = length
        else:
            # cKDTree wraps every axis of a boxsize: a period beyond the extent plus twice the
            # radius never connects two spheres across a non-periodic axis
            base = float(pos[:, d].min()) - radius
            shifted[:, d] = pos[:, d] - base
            boxsize[d] = float(shifted[:, d].max()) + 4.0 * radius
    tree = cKDTree(shifted, boxsize=boxsize)
    pairs = tree.query_pairs(radius * (1.0 + QUERY_SLACK), output_type="ndarray")
    pairs = np.sort(np.asarray(pairs, dtype=np.intp).reshape(-1, 2), axis=1)
    pairs = pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))]
    delta = wrapped[pairs[:, 1]] - wrapped[pairs[:, 0]]
    for d in np.flatnonzero(periodic):
        length = float(box_hi[d] - box_lo[d])
        delta[:, d] -= length * np.round(delta[:, d] / length)
    return pairs, delta
