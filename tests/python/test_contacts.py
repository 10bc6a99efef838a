# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""tapmc.contacts.Contacts: exact lattices (FCC shells over a gap sweep, simple cubic, a block with
free faces), the floor, mixed radii, random packings against an O(N^2) minimum-image oracle,
the sweep against one computation per gap, the constants against src/TAPMC/tapmc_defaults.h,
a dump, and bad input refused by name. (The compute against this class on the same packing:
tests/lammps/test_compute_contacts.py.)"""

import itertools
import math
import os
import re
import sys
from pathlib import Path

import numpy as np
import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc._validate import NotComputedError  # noqa: E402
from tapmc.contacts import (FEW_BELOW, GAP_TOLERANCE, MAX_GAP, MAX_Z,  # noqa: E402
                            Contacts)
from tapmc.readers import Frame, read_dump  # noqa: E402


def lattice(basis, cell, reps):
    idx = np.array(list(itertools.product(*(range(r) for r in reps))), float)
    pos = ((idx[:, None, :] + np.asarray(basis, float)[None]) * cell).reshape(-1, 3)
    return pos, np.full(3, cell * np.asarray(reps, float))


FCC_BASIS = [[0, 0, 0], [.5, .5, 0], [.5, 0, .5], [0, .5, .5]]


def fcc(reps=4):
    """FCC with nearest neighbours at 1 (radius 1/2 at contact)."""
    pos, box = lattice(FCC_BASIS, math.sqrt(2), [reps] * 3)
    return pos, box


def oracle(pos, radii, box, periodic, gap, floor=None):
    """O(N^2): contacts of every sphere at the nearest image along periodic axes."""
    pos = np.asarray(pos, float)
    radii = np.broadcast_to(np.asarray(radii, float), len(pos))
    counts = np.zeros(len(pos), int)
    for i in range(len(pos)):
        d = pos - pos[i]
        for axis in range(3):
            if periodic[axis]:
                d[:, axis] -= box[axis] * np.round(d[:, axis] / box[axis])
        reach = (radii + radii[i]) * (1 + gap + GAP_TOLERANCE)
        touching = (d * d).sum(axis=1) <= reach * reach
        touching[i] = False
        counts[i] = int(touching.sum())
        if floor is not None and (pos[i, 2] - radii[i] - floor
                                  <= (gap + GAP_TOLERANCE) * 2 * radii[i]):
            counts[i] += 1
    return counts


def test_constants_are_the_kernels():
    text = (SOURCE / "src" / "TAPMC" / "tapmc_defaults.h").read_text()

    def constant(name):
        value = re.search(rf"constexpr \w+ {name} = ([^;]+);", text).group(1).strip()
        return constant(value) if value.startswith("k") else float(value)
    assert GAP_TOLERANCE == constant("kContactsGapTolerance") == 1e-10
    assert MAX_GAP == constant("kContactsMaxGap")
    assert FEW_BELOW == constant("kContactsFewBelow")
    assert MAX_Z == constant("kContactsMaxZ")


@pytest.mark.parametrize("gap,expected", [(0.0, 12), (0.01, 12), (math.sqrt(2) - 1 - 1e-6, 12),
                                          (math.sqrt(2) - 1 + 1e-6, 18), (0.7, 18),
                                          (math.sqrt(3) - 1 + 1e-6, 42), (1.0, 54)])
def test_fcc_shells(gap, expected):
    pos, box = fcc(5)
    c = Contacts(pos, 0.5, [0, 0, 0], box, [True] * 3, gap=gap).compute()
    assert np.all(c.coordination == expected)
    assert c.mean == expected and c.largest == expected
    assert c.fraction_none == 0 and c.fraction_few == 0 and c.fraction_floor == 0
    p = np.zeros(MAX_Z + 1)
    p[min(expected, MAX_Z)] = 1
    np.testing.assert_array_equal(c.distribution, p)
    assert len(c.pairs) == expected * len(pos) // 2


def test_simple_cubic_and_sweep_against_compute():
    pos, box = lattice([[0, 0, 0]], 1.0, [5, 5, 5])
    c = Contacts(pos, 0.5, [0, 0, 0], box, [True] * 3, gap=0.0)
    assert np.all(c.compute().coordination == 6)
    gaps = [0.0, 0.2, 0.4, 0.42, 0.7, 0.74]
    s = c.sweep(gaps)
    np.testing.assert_array_equal(s.mean, [6, 6, 6, 18, 18, 26])
    for g, mean in zip(gaps, s.mean):
        assert Contacts(pos, 0.5, [0, 0, 0], box, [True] * 3, gap=g).compute().mean == mean


def test_block_with_free_faces_and_a_floor():
    pos, box = fcc(4)
    pos[:, 2] += 0.5                         # the bottom layer on a floor at z = 0
    c = Contacts(pos, 0.5, [0, 0, 0], box, [False] * 3, gap=0.01).compute()
    np.testing.assert_array_equal(c.coordination, oracle(pos, 0.5, box, [False] * 3, 0.01))
    assert c.coordination[0] == 3 and c.largest == 12       # a corner, the interior
    slab = Contacts(pos, 0.5, [0, 0, 0], box, [True, True, False], gap=0.01, floor=0.0).compute()
    bottom = np.isclose(pos[:, 2], 0.5)
    assert np.all(slab.coordination[bottom] == 9)          # 8 spheres and the floor
    assert np.all(slab.on_floor == bottom)
    assert slab.fraction_floor == pytest.approx(bottom.mean())
    top = np.isclose(pos[:, 2], pos[:, 2].max())
    assert np.all(slab.coordination[top] == 8)
    np.testing.assert_array_equal(slab.coordination,
                                  oracle(pos, 0.5, box, [True, True, False], 0.01, floor=0.0))
    bulk = slab.by_mask(~bottom & ~top)
    assert bulk.mean == 12 and bulk.fraction_floor == 0 and bulk.n == (~bottom & ~top).sum()


def test_floor_gap_is_relative_to_the_diameter():
    heights = np.array([0.0, 0.0099, 0.0101, -0.01])         # in diameters above contact
    pos = np.column_stack([10.0 * np.arange(4), np.zeros(4), 1.0 + 0.5 + heights])
    box_hi = [40, 1, 10]
    on = Contacts(pos, 0.5, [0, 0, 0], box_hi, [False] * 3, gap=0.01, floor=1.0).compute()
    np.testing.assert_array_equal(on.coordination, [1, 1, 0, 1])
    assert on.fraction_floor == 0.75 and on.fraction_none == 0.25
    exact = Contacts(pos, 0.5, [0, 0, 0], box_hi, [False] * 3, gap=0.0, floor=1.0).compute()
    np.testing.assert_array_equal(exact.coordination, [1, 0, 0, 1])


def test_a_tube_wall_counts_as_the_compute_with_container_counts_it():
    """compute contacts with 'container' adds the wall as one contact of every sphere within g
    of it (radial gap relative to the diameter); Contacts had no wall, so a wall sphere read 1
    less than the compute. Spheres at radial gaps 0, 0.0099 d, 0.0101 d and poking through by
    0.01 d, in a tube of radius 4 about (4, 4), one of them also on the floor."""
    from tapmc.cylinder import Cylinder

    tube = Cylinder(4.0, 4.0, 4.0)
    gaps = np.array([0.0, 0.0099, 0.0101, -0.01])          # in diameters inside the wall
    angles = np.array([0.0, 1.5, 3.0, 4.5])
    d = 4.0 - 0.5 - gaps                                    # centre distances from the axis
    z = np.array([0.5, 3.0, 6.0, 9.0])                      # the first one on the floor
    pos = np.column_stack([4 + d * np.cos(angles), 4 + d * np.sin(angles), z])
    on = Contacts(pos, 0.5, [0, 0, 0], [8, 8, 12], [False] * 3, gap=0.01, floor=0.0,
                  cylinder=tube).compute()
    np.testing.assert_array_equal(on.on_wall, [True, True, False, True])
    np.testing.assert_array_equal(on.coordination, [2, 1, 0, 1])   # floor + wall for the first
    assert on.fraction_wall == 0.75
    exact = Contacts(pos, 0.5, [0, 0, 0], [8, 8, 12], [False] * 3, gap=0.0, cylinder=tube)
    np.testing.assert_array_equal(exact.compute().coordination, [1, 0, 0, 1])
    plain = Contacts(pos, 0.5, [0, 0, 0], [8, 8, 12], [False] * 3, gap=0.01).compute()
    assert not plain.on_wall.any() and plain.fraction_wall == 0.0
    with pytest.raises(ValueError, match="cylinder given but x or y is periodic"):
        Contacts(pos, 0.5, [0, 0, 0], [8, 8, 12], [True, True, False], cylinder=tube)
    # a (cx, cy, radius) triple is the same tube (a raw AttributeError before)
    triple = Contacts(pos, 0.5, [0, 0, 0], [8, 8, 12], [False] * 3, gap=0.01, floor=0.0,
                      cylinder=(4.0, 4.0, 4.0)).compute()
    np.testing.assert_array_equal(triple.coordination, on.coordination)
    # a tube narrower than its spheres (every sphere, even one outside it, read on the wall)
    with pytest.raises(ValueError, match="cylinder.radius = 0.4 must exceed the largest sphere"):
        Contacts(pos, 0.5, [0, 0, 0], [8, 8, 12], [False] * 3, cylinder=Cylinder(4, 4, 0.4))


def test_mixed_radii_use_each_pairs_contact_distance():
    gaps = [0.0, 0.005, 0.01, 0.02, 0.05, 0.1]
    pos = [[0, 0, 0]]
    for k, g in enumerate(gaps):
        p = np.zeros(3)
        p[k // 2] = (-1) ** k * 2.5 * (1 + g)
        pos.append(p)
    radii = [2.0] + [0.5] * 6
    for g in (0.0, 0.004, 0.0051, 0.011, 0.03, 0.06, 0.2):
        c = Contacts(pos, radii, [-5] * 3, [5] * 3, [False] * 3, gap=g).compute()
        assert c.coordination[0] == sum(gk <= g for gk in gaps), g


@pytest.mark.parametrize("seed", range(4))
def test_random_packings_against_the_oracle(seed):
    rng = np.random.default_rng(seed)
    box = np.array([7.0, 6.0, 8.0])
    pos = rng.uniform(0, 1, (300, 3)) * box - 1.0
    radii = rng.uniform(0.3, 0.6, 300)
    for periodic in ([True, True, False], [True] * 3, [False] * 3):
        c = Contacts(pos, radii, [-1] * 3, box - 1, periodic, gap=0.0)
        sweep = c.sweep([0.0, 0.01, 0.05, 0.1])
        for k, g in enumerate([0.0, 0.01, 0.05, 0.1]):
            expected = oracle(pos, radii, box, periodic, g, floor=0.0)
            got = Contacts(pos, radii, [-1] * 3, box - 1, periodic, gap=g,
                           floor=None if periodic[2] else 0.0).compute()
            if periodic[2]:
                expected = oracle(pos, radii, box, periodic, g)
            np.testing.assert_array_equal(got.coordination, expected)
            if not periodic[2]:
                continue
            assert sweep.mean[k] == pytest.approx(expected.mean(), abs=1e-15)


def test_from_frame_with_select_and_box_floor(tmp_path):
    pos, box = fcc(3)
    pos[:, 2] += 0.5
    n = len(pos)
    frame = Frame(7, [0, 0, 0], box, [True, True, False], np.arange(1, n + 1), pos,
                  np.full(n, 0.5))
    c = Contacts.from_frame(frame, gap=0.001, floor="box").compute()
    assert c.frame is frame and c.floor == 0.0
    assert c.coordination[np.isclose(pos[:, 2], 0.5)].tolist() == [9] * 18
    low = pos[:, 2] < 2
    sub = Contacts.from_frame(frame, gap=0.001, select=low).compute()
    assert sub.n == low.sum() and sub.floor is None
    np.testing.assert_array_equal(sub.coordination,
                                  oracle(pos[low], 0.5, box, [True, True, False], 0.001))
    # through a dump file
    path = tmp_path / "fcc.dump"
    with open(path, "w") as f:
        f.write(f"ITEM: TIMESTEP\n7\nITEM: NUMBER OF ATOMS\n{n}\nITEM: BOX BOUNDS pp pp fm\n")
        for d in range(3):
            f.write(f"0 {box[d]!r}\n")
        f.write("ITEM: ATOMS id x y z radius\n")
        for i in range(n):
            f.write(f"{i + 1} {pos[i, 0]!r} {pos[i, 1]!r} {pos[i, 2]!r} 0.5\n")
    dumped = read_dump(str(path)).frames[0]
    d = Contacts.from_frame(dumped, gap=0.001, floor="box").compute()
    np.testing.assert_array_equal(d.coordination, c.coordination)
    ax = d.plot()
    assert ax.get_xlabel() == "contacts Z"
    assert "<Z> 10.8333" in repr(d)      # (9 + 8 + 4 x 12) / 6 layers


def test_empty_and_single_sphere():
    c = Contacts(np.empty((0, 3)), np.empty(0), [0, 0, 0], [4, 4, 4], gap=0.1).compute()
    assert c.n == 0 and c.mean == 0 and c.largest == 0 and c.distribution.sum() == 0
    one = Contacts([[1, 1, 0.5]], 0.5, [0, 0, 0], [4, 4, 4], gap=0.0, floor=0.0).compute()
    assert one.coordination.tolist() == [1] and one.fraction_few == 1


@pytest.mark.parametrize("kwargs,message", [
    (dict(gap=-0.1), "gap = -0.1 must lie in [0.0, 1.0]"),
    (dict(gap=1.5), "gap = 1.5 must lie in [0.0, 1.0]"),
    (dict(gap=float("nan")), "gap = nan must lie in [0.0, 1.0]"),
    (dict(radii=0.0), "radii[0] = 0.0 must be > 0"),
    (dict(periodic=[True, True, True], floor=0.0), "a floor needs a non-periodic z"),
    (dict(floor=float("inf")), "floor = inf must lie in"),
    (dict(box_hi=[1.5, 4, 4]), "periodic box length along x = 1.5 must exceed 2 reach"),
    (dict(positions=np.zeros((3, 2))), "positions must have shape (N, 3)"),
    (dict(periodic=[1, 1, 0]), "periodic = [1, 1, 0] must be 3 booleans"),
])
def test_bad_input_is_refused_by_name(kwargs, message):
    args = dict(positions=[[1, 1, 1], [2, 2, 2]], radii=0.5, box_lo=[0, 0, 0], box_hi=[4, 4, 4],
                periodic=[True, True, False], gap=0.01)
    args.update(kwargs)
    with pytest.raises(ValueError, match=re.escape(message)):
        Contacts(**args)


def test_results_refuse_before_compute_and_sweep_checks_gaps():
    c = Contacts([[1, 1, 1]], 0.5, [0, 0, 0], [4, 4, 4])
    with pytest.raises(NotComputedError, match="call compute"):
        c.coordination
    with pytest.raises(NotComputedError):
        c.mean
    with pytest.raises(ValueError, match="gaps = 2.0 must lie in"):
        c.sweep([0.1, 2.0])
    with pytest.raises(ValueError, match="mask must be 1 booleans"):
        c.compute().by_mask([True, False])
