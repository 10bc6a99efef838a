# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""tapmc.crystallinity.Crystallinity: Steinhardt q4, q6 of exact lattices in periodic boxes
(FCC, HCP, BCC with its 8 nearest neighbours, SC) against closed forms that this file derives
again from the lattices' own bond vectors (Legendre addition theorem, no spherical harmonics);
rotation invariance; a random (ideal-gas) control that must fail; the tree's bonds, q_l and
solid-like bonds against an O(N^2) oracle; zones, profiles and a dump; bad input refused by
name."""

import itertools
import math
import os
import sys
from pathlib import Path

import numpy as np
import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc._validate import NotComputedError  # noqa: E402
from tapmc.crystallinity import (LATTICE_Q, MIN_SOLID_BONDS, SOLID_BOND_THRESHOLD,  # noqa: E402
                                 Crystallinity, spherical_harmonics)
from tapmc.readers import Frame, read_dump  # noqa: E402

# The standard values (Steinhardt et al. 1983 and later tables), to their printed 4 digits, and
# the exact first-shell values q_l^2 (rational: the bond cosines of these lattices are rational)
LITERATURE = {"fcc": {4: 0.1909, 6: 0.5745}, "hcp": {4: 0.0972, 6: 0.4848},
              "bcc": {4: 0.5092, 6: 0.6285}, "sc": {4: 0.7638, 6: 0.3536}}
EXACT_Q2 = {"fcc": {4: 7 / 192, 6: 169 / 512}, "hcp": {4: 49 / 5184, 6: 29237 / 124416},
            "bcc": {4: 7 / 27, 6: 32 / 81}, "sc": {4: 7 / 12, 6: 1 / 8}}
NEIGHBOURS = {"fcc": 12, "hcp": 12, "bcc": 8, "sc": 6}


# ---- lattices (nearest-neighbour distance 1, radius 0.5) ------------------------------------
def cells(basis, cell, reps):
    idx = np.array(list(itertools.product(*(range(r) for r in reps))), float)
    pos = ((idx[:, None, :] + np.asarray(basis, float)[None]) * cell).reshape(-1, 3)
    return pos, np.asarray(cell, float) * reps


def lattice(name):
    """(positions, box length (3,), cutoff) of a periodic block of `name`, contact distance 1."""
    if name == "fcc":
        a = math.sqrt(2)
        pos, box = cells([[0, 0, 0], [.5, .5, 0], [.5, 0, .5], [0, .5, .5]], [a, a, a], [3, 3, 3])
        return pos, box, None
    if name == "hcp":
        c = math.sqrt(8 / 3)     # ideal c/a
        basis = [[0, 0, 0], [.5, .5, 0], [.5, 1 / 6, .5], [0, 2 / 3, .5]]
        pos, box = cells(basis, [1.0, math.sqrt(3), c], [3, 2, 3])
        return pos, box, None
    if name == "bcc":
        a = 2 / math.sqrt(3)
        pos, box = cells([[0, 0, 0], [.5, .5, .5]], [a, a, a], [3, 3, 3])
        return pos, box, 0.5 * (1 + a)       # between the 8 at 1 and the 6 at a = 1.155
    pos, box = cells([[0, 0, 0]], [1.0, 1.0, 1.0], [4, 4, 4])
    return pos, box, None


def bond_vectors(pos, box, periodic, cutoff):
    """O(N^2) oracle: for every sphere the unit vectors to its neighbours within `cutoff` at
    the nearest image along the periodic axes, and the set of pairs i < j."""
    pos = np.asarray(pos, float)
    vectors, pairs = [], set()
    for i in range(len(pos)):
        d = pos - pos[i]
        for axis in range(3):
            if periodic[axis]:
                d[:, axis] -= box[axis] * np.round(d[:, axis] / box[axis])
        r = np.linalg.norm(d, axis=1)
        near = np.flatnonzero((r < cutoff) & (np.arange(len(pos)) != i))
        vectors.append(d[near] / r[near, None])
        pairs.update((min(i, j), max(i, j)) for j in near)
    return vectors, pairs


def legendre_q(unit, l):
    """q_l of one sphere by the addition theorem: q_l^2 = (1/N^2) sum_jk P_l(r_j . r_k)."""
    from scipy.special import eval_legendre
    if len(unit) == 0:
        return math.nan
    return math.sqrt(float(eval_legendre(l, np.clip(unit @ unit.T, -1, 1)).sum()) / len(unit) ** 2)


def legendre_product(ui, uj, l):
    """Re q_l(i).q_l(j)* normalised, by the addition theorem (no Y_lm)."""
    from scipy.special import eval_legendre
    cross = float(eval_legendre(l, np.clip(ui @ uj.T, -1, 1)).sum()) / (len(ui) * len(uj))
    return cross / (legendre_q(ui, l) * legendre_q(uj, l))


def periodic_crystal(name, **kwargs):
    pos, box, cutoff = lattice(name)
    return Crystallinity(pos, 0.5, [0, 0, 0], box, [True, True, True], cutoff=cutoff,
                         **kwargs).compute()


# ---- spherical harmonics --------------------------------------------------------------------
def test_spherical_harmonics_addition_theorem_and_scipy():
    rng = np.random.default_rng(1)
    u = rng.normal(size=(50, 3))
    u /= np.linalg.norm(u, axis=1)[:, None]
    for l in (1, 4, 6, 12):
        y = spherical_harmonics(l, u)
        w = np.full(l + 1, 2.0)
        w[0] = 1.0
        # sum over m of |Y_lm|^2 = (2l+1)/(4 pi) for every direction (Unsold)
        assert np.allclose(np.abs(y) ** 2 @ w, (2 * l + 1) / (4 * np.pi), rtol=1e-12)
        # sum_m Y_lm(a) Y_lm(b)* = (2l+1)/(4 pi) P_l(a.b)
        from scipy.special import eval_legendre
        cross = (y[:, None, :] * np.conj(y[None, :, :])).real @ w
        assert np.allclose(cross, (2 * l + 1) / (4 * np.pi) * eval_legendre(l, u @ u.T),
                           atol=1e-12)
    theta, phi = np.arccos(u[:, 2]), np.arctan2(u[:, 1], u[:, 0])
    import scipy.special as special
    if hasattr(special, "sph_harm_y"):          # scipy >= 1.15: (l, m, polar, azimuth)
        ref = lambda l, m: special.sph_harm_y(l, m, theta, phi)  # noqa: E731
    elif hasattr(special, "sph_harm"):          # older scipy: (m, l, azimuth, polar)
        ref = lambda l, m: special.sph_harm(m, l, phi, theta)  # noqa: E731
    else:
        pytest.skip("scipy has no spherical harmonics to compare with")
    for l in (4, 6):
        y = spherical_harmonics(l, u)
        for m in range(l + 1):
            assert np.allclose(y[:, m], ref(l, m), atol=1e-12)


# ---- exact lattices -------------------------------------------------------------------------
@pytest.mark.parametrize("name", ["fcc", "hcp", "bcc", "sc"])
def test_exact_values_from_the_lattices_own_bonds(name):
    """The closed forms above, derived again from the lattice's first shell by the addition
    theorem, and the literature's 4 digits."""
    pos, box, cutoff = lattice(name)
    vectors, _ = bond_vectors(pos, box, [True] * 3, cutoff or 1.2)
    assert {len(v) for v in vectors} == {NEIGHBOURS[name]}
    for l in (4, 6):
        values = [legendre_q(v, l) for v in vectors]
        assert np.allclose(values, math.sqrt(EXACT_Q2[name][l]), rtol=0, atol=1e-12)
        assert math.sqrt(EXACT_Q2[name][l]) == pytest.approx(LITERATURE[name][l], abs=5e-5)
        assert LATTICE_Q[name][l] == pytest.approx(math.sqrt(EXACT_Q2[name][l]), abs=1e-15)


@pytest.mark.parametrize("name", ["fcc", "hcp", "bcc", "sc"])
def test_periodic_lattice(name):
    c = periodic_crystal(name)
    assert np.all(c.neighbours == NEIGHBOURS[name])
    for l in (4, 6):
        exact = math.sqrt(EXACT_Q2[name][l])
        assert np.max(np.abs(c.q[l] - exact)) < 1e-9
        assert c.q[l] == pytest.approx(np.full(c.n, LITERATURE[name][l]), abs=5e-5)
    # one crystal: the bond-averaged Q_l is the q_l of every sphere (HCP's two sites are each
    # other's environment inverted, which leaves every even-l q_lm unchanged)
    for l in (4, 6):
        assert c.Q[l] == pytest.approx(math.sqrt(EXACT_Q2[name][l]), abs=1e-9)
    assert np.allclose(c.bond_product, 1.0, atol=1e-12)
    if name == "sc":        # 6 bonds, all solid-like, fewer than MIN_SOLID_BONDS
        assert np.all(c.solid_bonds == 6) and not c.crystalline.any()
        assert c.crystalline_fraction == 0.0
    else:
        assert np.all(c.solid_bonds == NEIGHBOURS[name]) and c.crystalline.all()
        assert c.crystalline_fraction == 1.0


def test_hcp_global_order_by_the_addition_theorem():
    pos, box, _ = lattice("hcp")
    vectors, _ = bond_vectors(pos, box, [True] * 3, 1.2)
    c = periodic_crystal("hcp")
    allv = np.concatenate(vectors)
    for l in (4, 6):
        assert c.Q[l] == pytest.approx(legendre_q(allv, l), abs=1e-10)


def test_thresholds_are_parameters():
    c = periodic_crystal("sc", min_solid_bonds=6)
    assert c.crystalline.all()
    assert SOLID_BOND_THRESHOLD == 0.7 and MIN_SOLID_BONDS == 8
    pos, side = ideal_gas(400, 12, np.random.default_rng(2))
    last = None
    for threshold in (-0.5, 0.0, 0.3, 0.7, 0.9):
        g = Crystallinity(pos, 0.5, [0, 0, 0], [side] * 3, [True] * 3,
                          bond_threshold=threshold, min_solid_bonds=3).compute()
        assert g.solid_bonds.sum() == 2 * np.count_nonzero(g.bond_product > threshold)
        assert np.array_equal(g.crystalline, g.solid_bonds >= 3)
        if last is not None:
            assert np.all(g.solid_bonds <= last) and g.solid_bonds.sum() < last.sum()
        last = g.solid_bonds


def test_rotated_fcc_crystal_keeps_every_sphere_value():
    pos, _ = cells([[0, 0, 0], [.5, .5, 0], [.5, 0, .5], [0, .5, .5]], [math.sqrt(2)] * 3,
                   [4, 4, 4])
    rng = np.random.default_rng(7)
    rot, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    turned = (pos - pos.mean(axis=0)) @ rot.T
    args = dict(periodic=[False] * 3, l=(4, 6, 8))
    a = Crystallinity(pos, 0.5, pos.min(0) - 1, pos.max(0) + 1, **args).compute()
    b = Crystallinity(turned, 0.5, turned.min(0) - 1, turned.max(0) + 1, **args).compute()
    assert np.array_equal(a.neighbours, b.neighbours)
    assert set(np.unique(a.neighbours)) > {12}          # a finite block: its faces have fewer
    for l in (4, 6, 8):
        assert np.max(np.abs(a.q[l] - b.q[l])) < 1e-10
        assert a.Q[l] == pytest.approx(b.Q[l], abs=1e-10)
    assert np.array_equal(a.solid_bonds, b.solid_bonds)
    interior = a.neighbours == 12
    assert np.allclose(a.q[6][interior], math.sqrt(169 / 512), atol=1e-10)


# ---- the control that must fail -------------------------------------------------------------
def ideal_gas(n, neighbours, rng):
    """n uniform random points in a periodic cube, about `neighbours` within cutoff 1.2."""
    side = (n * 4 * math.pi / 3 * 1.2 ** 3 / neighbours) ** (1 / 3)
    return rng.random((n, 3)) * side, side


@pytest.mark.parametrize("n", [500, 4000])
def test_ideal_gas_is_not_crystalline(n):
    pos, side = ideal_gas(n, 12, np.random.default_rng(n))
    c = Crystallinity(pos, 0.5, [0, 0, 0], [side] * 3, [True] * 3).compute()
    assert 10 < c.neighbours.mean() < 14
    assert c.crystalline_fraction < 0.01
    # bonds of random orientation: Q6^2 ~ (1/pairs) chi2_13/13 (each bond counted twice)
    scaled = c.Q[6] * math.sqrt(len(c.pairs))
    assert 0.4 < scaled < 2.0
    assert c.Q[6] < 3.0 / math.sqrt(n)


def rsa(n, box, periodic, rng, diameter=1.0):
    """Random sequential addition of n hard spheres (nearest image along periodic axes)."""
    box = np.asarray(box, float)
    pos = np.empty((0, 3))
    for _ in range(1000 * n):
        if len(pos) == n:
            return pos
        p = rng.random(3) * box
        if not periodic[2]:
            p[2] = 0.5 * diameter + rng.random() * (box[2] - diameter)
        d = pos - p
        for axis in range(3):
            if periodic[axis]:
                d[:, axis] -= box[axis] * np.round(d[:, axis] / box[axis])
        if len(pos) == 0 or np.min(np.einsum("ij,ij->i", d, d)) >= diameter ** 2:
            pos = np.vstack([pos, p])
    raise RuntimeError(f"random sequential addition placed {len(pos)} of {n} spheres")


def test_tree_matches_the_brute_force_oracle():
    """Bonds, q_l and solid-like bonds of a small packing periodic in x and y, open in z,
    against O(N^2) neighbour lists and the addition theorem."""
    rng = np.random.default_rng(3)
    box = np.array([5.0, 6.0, 5.0])
    periodic = [True, True, False]
    pos = rsa(80, box, periodic, rng)    # packing fraction 0.28
    pos[:, :2] += 10.0              # coordinates outside the box: wrapped along x and y
    c = Crystallinity(pos, 0.5, [10, 10, 0], [15, 16, 5], periodic, floor=0.0).compute()
    vectors, pairs = bond_vectors(pos, box, periodic, c.cutoff)
    assert {tuple(p) for p in c.pairs.tolist()} == pairs
    assert len(c.pairs) == len(pairs)
    raw = pos[c.pairs[:, 1]] - pos[c.pairs[:, 0]]
    assert np.any(np.abs(raw[:, 0]) > c.cutoff) and np.any(np.abs(raw[:, 1]) > c.cutoff)
    assert np.all(np.abs(raw[:, 2]) < c.cutoff)          # never across z
    assert np.array_equal(c.neighbours, [len(v) for v in vectors])
    for l in (4, 6):
        oracle = np.array([legendre_q(v, l) for v in vectors])
        assert np.allclose(c.q[l], oracle, atol=1e-10, equal_nan=True)
    product = np.array([legendre_product(vectors[i], vectors[j], 6) for i, j in c.pairs])
    assert np.allclose(c.bond_product, product, atol=1e-10)
    solid = np.zeros(len(pos), int)
    for (i, j), d in zip(c.pairs, product):
        if d > SOLID_BOND_THRESHOLD:
            solid[i] += 1
            solid[j] += 1
    assert np.array_equal(c.solid_bonds, solid)


# ---- zones, profiles, a dump ----------------------------------------------------------------
def fcc_on_floor(reps=(6, 6, 5)):
    """FCC with (100) planes on the floor z = 0, side walls at the faces of the box; the
    lowest layer and the outer columns touch the floor and the walls."""
    a = math.sqrt(2)
    pos, _ = cells([[0, 0, 0], [.5, .5, 0], [.5, 0, .5], [0, .5, .5]], [a, a, a], reps)
    pos += 0.5
    hi = pos.max(axis=0) + 0.5
    hi[2] += 20.0
    return pos, np.zeros(3), hi


def test_zones_of_a_crystal_on_a_floor_between_walls(tmp_path):
    pos, lo, hi = fcc_on_floor()
    ids = np.arange(1, len(pos) + 1)
    path = tmp_path / "dump.fcc"
    with open(path, "w") as f:
        f.write(f"ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n{len(pos)}\n"
                "ITEM: BOX BOUNDS ff ff fm\n")
        for d in range(3):
            f.write(f"{lo[d]:.16e} {hi[d]:.16e}\n")
        f.write("ITEM: ATOMS id x y z radius\n")
        for i, p in zip(ids, pos):
            f.write(f"{i} {p[0]:.17g} {p[1]:.17g} {p[2]:.17g} 0.5\n")
    frame = read_dump(str(path)).frames[0]
    c = Crystallinity.from_frame(frame).compute()
    assert c.floor == 0.0 and list(c.periodic) == [False, False, False]
    masks = c.zone_masks(band=2.0, margin=3.0)
    z, x, y = pos[:, 2], pos[:, 0], pos[:, 1]
    wall_gap = np.minimum.reduce([x - lo[0], hi[0] - x, y - lo[1], hi[1] - y])
    surface = c.surface()
    assert surface == pytest.approx(z.max() + 0.5, abs=0.8)
    assert np.array_equal(masks["floor"], (z < 1.0) & (wall_gap >= 1.5))
    assert np.array_equal(masks["walls"], (wall_gap < 1.0) & (z >= 1.5) & (z <= surface - 1.5))
    assert np.array_equal(masks["bulk"], (z >= 1.5) & (wall_gap >= 1.5) & (z <= surface - 1.5))
    zones = c.zones(band=2.0, margin=3.0)
    assert zones["bulk"].n > 0 and zones["bulk"].crystalline_fraction == 1.0
    assert zones["bulk"].q_mean[6] == pytest.approx(math.sqrt(169 / 512), abs=1e-10)
    assert zones["bulk"].neighbours_mean == 12
    # the (100) floor layer: 4 in-plane + 4 above = 8 bonds, all solid-like
    assert zones["floor"].neighbours_mean == 8 and zones["floor"].crystalline_fraction == 1.0
    everything = zones["all"]
    assert everything.n == c.n and everything.crystalline_fraction == c.crystalline_fraction
    assert everything.Q[6] == pytest.approx(c.Q[6], abs=1e-14)
    prof = c.profile(np.arange(0.0, 8.5, 0.5 * math.sqrt(2)))
    assert prof.n.sum() == c.n
    assert prof.n[0] == np.count_nonzero(z < 0.5 * math.sqrt(2))
    first = c.by_mask(z < 0.5 * math.sqrt(2))
    assert prof.q_mean[6][0] == pytest.approx(first.q_mean[6])
    assert prof.crystalline_fraction[0] == pytest.approx(first.crystalline_fraction)
    empty = c.by_mask(np.zeros(c.n, bool))
    assert empty.n == 0 and math.isnan(empty.crystalline_fraction)


def test_in_a_tube_the_walls_are_the_cylinder():
    """A simple cubic stack cut to a tube of radius 4.05 about (4, 4): the wall zone is the
    spheres within the band of the cylinder, not of the box faces (105 of the 172 spheres
    near a tube's wall were missed, and spheres in the box corners outside the tube counted)."""
    from tapmc.cylinder import Cylinder

    g = np.arange(0.5, 8.0, 1.0)
    x, y, z = (a.ravel() for a in np.meshgrid(g, g, np.arange(0.5, 8.0, 1.0), indexing="ij"))
    tube = Cylinder(4.0, 4.0, 4.05)
    inside = np.hypot(x - 4, y - 4) <= 3.55
    pos = np.column_stack([x, y, z])[inside]
    c = Crystallinity(pos, 0.5, [0, 0, 0], [8, 8, 20], (False, False, False), floor=0.0,
                      cylinder=tube).compute()
    masks = c.zone_masks(band=2.0, margin=3.0)
    gap = 4.05 - np.hypot(pos[:, 0] - 4, pos[:, 1] - 4)
    surface = c.surface()
    height_ok = (pos[:, 2] >= 1.5) & (pos[:, 2] <= surface - 1.5)
    assert surface == pytest.approx(8.0, abs=1e-9)   # the flat top of the stack, in the tube
    assert np.array_equal(masks["walls"], (gap < 1.0) & height_ok)
    assert np.array_equal(masks["bulk"], (gap >= 1.5) & height_ok)
    boxed = Crystallinity(pos, 0.5, [0, 0, 0], [8, 8, 20], (False, False, False),
                          floor=0.0).compute().zone_masks(band=2.0, margin=3.0)
    assert np.count_nonzero(masks["walls"] & ~boxed["walls"]) > 0   # what the box faces miss
    with pytest.raises(ValueError, match="cylinder given but x or y is periodic"):
        Crystallinity(pos, 0.5, [0, 0, 0], [8, 8, 20], (True, True, False), cylinder=tube)
    triple = Crystallinity(pos, 0.5, [0, 0, 0], [8, 8, 20], (False, False, False), floor=0.0,
                           cylinder=(4.0, 4.0, 4.05)).compute()
    assert np.array_equal(triple.zone_masks(band=2.0, margin=3.0)["walls"], masks["walls"])
    with pytest.raises(ValueError, match="cylinder.radius = 0.4 must exceed the largest sphere"):
        Crystallinity(pos, 0.5, [0, 0, 0], [8, 8, 20], (False, False, False),
                      cylinder=Cylinder(4, 4, 0.4))


def test_periodic_sides_have_no_walls_and_no_floor_without_one():
    pos, box, _ = lattice("fcc")
    c = periodic_crystal("fcc")
    masks = c.zone_masks()
    assert not masks["floor"].any() and not masks["walls"].any() and masks["bulk"].all()
    assert c.surface() is None
    frame = Frame(0, [0, 0, 0], box, [True, True, True], np.arange(1, len(pos) + 1), pos,
                  np.full(len(pos), 0.5))
    assert Crystallinity.from_frame(frame).floor is None


def test_plot_and_results_before_compute():
    pos, box, _ = lattice("sc")
    c = Crystallinity(pos, 0.5, [0, 0, 0], box, [True] * 3)
    for name in ("q", "Q", "crystalline", "crystalline_fraction", "solid_bonds", "neighbours",
                 "pairs", "n"):
        with pytest.raises(NotComputedError, match="compute"):
            getattr(c, name)
    with pytest.raises(NotComputedError):
        c.zones()
    assert "not computed" in repr(c)
    ax = c.compute().plot()
    assert ax.get_ylabel() == "$q_6(i)$"
    assert "0.00 % crystalline" in repr(c)
    # spheres with no neighbour within the cutoff: no bond, and a repr without numpy's warning
    import warnings
    apart = Crystallinity(np.array([[1.0, 1, 1], [3.5, 3.5, 3.5]]), 0.5, [0, 0, 0], [6, 6, 6],
                          [False] * 3).compute()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert "mean q6 none (no bonds)" in repr(apart)


# ---- bad input --------------------------------------------------------------------------------
GOOD = dict(positions=np.array([[1.0, 1, 1], [2, 1, 1], [1, 2.5, 1]]), radii=0.5,
            box_lo=[0, 0, 0], box_hi=[4, 4, 4], periodic=[False, False, False])


@pytest.mark.parametrize("change, match", [
    (dict(positions=np.zeros((3, 2))), "positions"),
    (dict(positions=np.zeros((1, 3))), "positions"),
    (dict(positions=[[0, 0, 0], [np.nan, 1, 1]]), r"positions\[1\]"),
    (dict(radii=[0.5, 0.5]), "radii"),
    (dict(radii=[0.5, -0.5, 0.5]), r"radii\[1\] = -0.5"),
    (dict(box_hi=[4, 0, 4]), "box_hi"),
    (dict(box_lo=[0, 0]), "box_lo"),
    (dict(periodic=[True, True]), "periodic"),
    (dict(cutoff=0.0), "cutoff = 0.0"),
    (dict(cutoff=-1), "cutoff"),
    (dict(periodic=[True, False, False], cutoff=2.5), r"along x = 4 must exceed 2 \* cutoff"),
    (dict(l=0), "l = 0"),
    (dict(l=(4, 13)), r"l = 13 must be an integer in \[1, 12\]"),
    (dict(l=2.5), "l = 2.5"),
    (dict(l=()), "l = "),
    (dict(bond_threshold=1.0), "bond_threshold = 1.0"),
    (dict(bond_threshold=float("nan")), "bond_threshold"),
    (dict(min_solid_bonds=0), "min_solid_bonds = 0"),
    (dict(min_solid_bonds=2.5), "min_solid_bonds"),
    (dict(periodic=[False, False, True], floor=0.0), "floor = 0.0"),
    (dict(floor=float("inf")), "floor"),
])
def test_bad_input_is_refused_by_name(change, match):
    with pytest.raises(ValueError, match=match):
        Crystallinity(**{**GOOD, **change})


def test_bad_calls_are_refused_by_name():
    c = Crystallinity(**GOOD).compute()
    with pytest.raises(ValueError, match="mask must be 3 booleans"):
        c.by_mask([True, False])
    with pytest.raises(ValueError, match="mask"):
        c.by_mask(np.ones(3))
    with pytest.raises(ValueError, match="z_edges"):
        c.profile([0, 2, 1])
    with pytest.raises(ValueError, match="z_edges"):
        c.profile([0])
    with pytest.raises(ValueError, match="band = -1"):
        c.zone_masks(band=-1)
    with pytest.raises(ValueError, match="margin = 0"):
        c.zone_masks(margin=0)
    with pytest.raises(ValueError, match="l = 5"):
        c.plot(l=5)
    frame = Frame(0, [0, 0, 0], [4, 4, 4], [True, True, False], np.arange(1, 4),
                  GOOD["positions"])
    with pytest.raises(ValueError, match="no radii"):
        Crystallinity.from_frame(frame)
    frame.radii = np.full(3, 0.5)
    with pytest.raises(ValueError, match="floor = 'top'"):
        Crystallinity.from_frame(frame, floor="top")
    with pytest.raises(ValueError, match="coincide"):
        Crystallinity(np.array([[1.0, 1, 1], [1, 1, 1]]), 0.5, [0, 0, 0], [4, 4, 4],
                      [False] * 3).compute()
