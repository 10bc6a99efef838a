# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""tapmc.packing.PackingCheck: overlaps against an all-pairs oracle (nearest periodic image),
exact lattices at contact, the floor and the walls, the stereology scalars against their
analytic values and against a paper-scale run's printed row."""

import math
import os
import sys
from pathlib import Path

import numpy as np
import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc._validate import NotComputedError  # noqa: E402
from tapmc.packing import PackingCheck  # noqa: E402
from tapmc.readers import Frame, read_dump  # noqa: E402


def frame(positions, radii, lo, hi, periodic):
    positions = np.asarray(positions, float)
    return Frame(0, lo, hi, periodic, np.arange(1, len(positions) + 1), positions,
                 np.broadcast_to(np.asarray(radii, float), len(positions)).copy())


def square_layer(n_side, radius, z=None):
    """One layer of n_side^2 spheres on a square lattice of spacing 2R, touching the floor and
    each other, in a periodic box of side 2R n_side."""
    side = 2 * radius * n_side
    g = (np.arange(n_side) + 0.5) * 2 * radius
    x, y = np.meshgrid(g, g, indexing="ij")
    zc = np.full(x.size, radius if z is None else z)
    return np.column_stack([x.ravel(), y.ravel(), zc]), side


def fcc_block(cells, radius):
    """FCC at contact (a = 2 sqrt(2) R), `cells` cubic cells per side, lowest layer on z = 0."""
    a = 2 * math.sqrt(2) * radius
    basis = np.array([[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]])
    idx = np.array([[i, j, k] for i in range(cells) for j in range(cells) for k in range(cells)])
    pos = ((idx[:, None, :] + basis[None, :, :]).reshape(-1, 3)) * a
    pos[:, 2] += radius
    return pos, a * cells


def all_pairs_min_gap(pos, r, lo, hi, periodic):
    """O(N^2) oracle: smallest relative gap over pairs, nearest periodic image."""
    best, overlaps = math.inf, 0
    length = np.asarray(hi, float) - np.asarray(lo, float)
    for i in range(len(pos)):
        d = pos[i + 1:] - pos[i]
        for axis in range(3):
            if periodic[axis]:
                d[:, axis] -= length[axis] * np.round(d[:, axis] / length[axis])
        contact = r[i] + r[i + 1:]
        rel = (np.linalg.norm(d, axis=1) - contact) / contact
        if rel.size:
            best = min(best, float(rel.min()))
            overlaps += int(np.count_nonzero(rel < -1e-10))
    return best, overlaps


def test_fcc_at_contact_is_legal_with_zero_gap():
    pos, side = fcc_block(4, 0.5)
    check = PackingCheck(frame(pos, 0.5, [0, 0, 0], [side, side, 20], [True, True, False]),
                         digits=None).compute()
    assert check.n == 256
    assert abs(check.min_gap) < 1e-12
    assert check.overlaps == 0 and check.legal
    assert check.floor_gap == pytest.approx(0.0, abs=1e-12)
    assert check.wall_gap is None


def test_a_pushed_sphere_overlaps_and_the_packing_is_illegal():
    pos, side = fcc_block(3, 0.5)
    pos[5] += np.array([1e-6, 1e-6, 0.0])   # towards some neighbours
    check = PackingCheck(frame(pos, 0.5, [0, 0, 0], [side, side, 20], [True, True, False]),
                         digits=None).compute()
    assert check.overlaps >= 1 and not check.legal
    assert check.min_gap < -1e-7
    assert 6 in check.closest_pair


def test_overlap_across_a_periodic_side_only_when_periodic():
    pos = [[0.2, 2.0, 0.5], [3.8, 2.0, 0.5]]   # 0.4 apart through x = 0 (box 4 wide)
    periodic = PackingCheck(frame(pos, 0.5, [0, 0, 0], [4, 4, 10], [True, True, False]),
                            digits=None).compute()
    assert periodic.overlaps == 1 and periodic.min_gap == pytest.approx(-0.6)
    walls = PackingCheck(frame(pos, 0.5, [0, 0, 0], [4, 4, 10], [False, False, False]),
                         digits=None).compute()
    assert walls.overlaps == 0 and walls.min_gap == pytest.approx(2.6)
    # both spheres cross a side wall by 0.3: 0.3 of a diameter
    assert walls.wall_gap == pytest.approx(-0.3) and not walls.legal


def test_below_the_floor_is_illegal():
    pos, side = square_layer(4, 0.5)
    pos[3, 2] -= 1e-5
    check = PackingCheck(frame(pos, 0.5, [0, 0, 0], [side, side, 5], [True, True, False]),
                         digits=None).compute()
    assert check.overlaps == 0
    assert check.floor_gap == pytest.approx(-1e-5)
    assert not check.legal


@pytest.mark.parametrize("seed", range(8))
def test_min_gap_and_overlaps_match_all_pairs(seed):
    rng = np.random.default_rng(seed)
    n = 150
    lo, hi = np.array([-1.0, 2.0, 0.0]), np.array([5.0, 7.0, 6.0])
    periodic = [bool(seed % 2), bool(seed % 3), False]
    pos = lo + rng.random((n, 3)) * (hi - lo)
    r = rng.uniform(0.2, 0.45, n)
    check = PackingCheck(frame(pos, r, lo, hi, periodic), digits=None).compute()
    best, overlaps = all_pairs_min_gap(pos, r, lo, hi, periodic)
    assert check.min_gap == pytest.approx(best, rel=1e-12, abs=1e-12)
    assert check.overlaps == overlaps


def test_sparse_packing_takes_the_nearest_neighbour():
    pos = [[1.0, 1.0, 1.0], [4.0, 1.0, 1.0], [1.0, 5.5, 1.0]]
    check = PackingCheck(frame(pos, [0.5, 0.5, 1.0], [0, 0, 0], [8, 8, 8],
                               [False, False, False]), digits=None).compute()
    assert check.min_gap == pytest.approx((3.0 - 1.0) / 1.0)
    assert check.closest_pair in ((1, 2), (2, 1))


def test_resolution_of_a_ten_digit_dump():
    pos, side = square_layer(8, 0.5)    # largest coordinate 7.5: units of 1e-9
    check = PackingCheck(frame(pos, 0.5, [0, 0, 0], [side, side, 5], [True, True, False]))
    assert check.resolution == pytest.approx(2 * math.sqrt(3) * 0.5e-9)
    assert PackingCheck(frame(pos, 0.5, [0, 0, 0], [side, side, 5], [True, True, False]),
                        digits=None).resolution == 0.0


def test_scalars_of_one_layer_on_the_floor():
    radius, n_side = 0.5, 8
    pos, side = square_layer(n_side, radius)
    check = PackingCheck(frame(pos, radius, [0, 0, 0], [side, side, 10], [True, True, False]),
                         digits=None).compute()
    n, area = n_side ** 2, side * side
    sphere = 4.0 / 3.0 * math.pi * radius ** 3
    assert check.z_mean == pytest.approx(radius)
    assert check.surface == pytest.approx(2 * radius)          # one sphere per 2R column
    assert check.window_top == pytest.approx(0.9 * 2 * radius)
    assert check.phi_b == pytest.approx(n * sphere / (area * 4 * radius))

    def slab(a, b):   # volume of one sphere centred at 0 between heights a and b
        return math.pi * (radius ** 2 * (b - a) - (b ** 3 - a ** 3) / 3)

    top = 0.9 * 2 * radius
    expected = n * (16 / 11 * slab(-radius, 0.0) + slab(0.0, top - radius)) / (area * top)
    assert check.phi_c == pytest.approx(expected)
    assert set(check.scalars()) == {"phi_b", "phi_c", "Z", "z_top", "h_s"}


def test_surface_ignores_empty_columns_and_follows_one_high_sphere_by_its_share():
    radius, n_side = 0.5, 4
    pos, side = square_layer(n_side, radius)
    pos[0, 2] += 3.0                                  # one sphere 3 above the layer
    check = PackingCheck(frame(pos, radius, [0, 0, 0], [side, side, 10], [True, True, False]),
                         digits=None).compute()
    assert check.surface == pytest.approx(2 * radius + 3.0 / n_side ** 2)


def test_results_need_compute_and_radii_are_required():
    pos, side = square_layer(2, 0.5)
    check = PackingCheck(frame(pos, 0.5, [0, 0, 0], [side, side, 5], [True, True, False]))
    with pytest.raises(NotComputedError):
        check.min_gap
    with pytest.raises(NotComputedError):
        check.wall_gap
    bare = Frame(0, [0, 0, 0], [side, side, 5], [True, True, False], np.arange(1, 5), pos)
    with pytest.raises(ValueError, match="no radii"):
        PackingCheck(bare)
    with pytest.raises(ValueError, match="digits"):
        PackingCheck(frame(pos, 0.5, [0, 0, 0], [side, side, 5], [True, True, False]),
                     digits=0)


RUN = SOURCE / "doc" / "validation" / "data" / "full" / "runs" / "const_pbc_eps0.0225_s1"


@pytest.mark.skipif(not (RUN / "dump.4000.lammpstrj").is_file(), reason="campaign data absent")
def test_paper_scale_dump_reproduces_its_printed_row():
    """After 4000 taps at N = 4096: a legal packing whose scalars are the ones the run's
    compute stereo/profile printed for that tap (to the print's last digit)."""
    check = PackingCheck(read_dump(RUN / "dump.4000.lammpstrj").frames[-1]).compute()
    assert check.n == 4096 and check.legal and check.overlaps == 0
    rows = {}
    for line in (RUN / "taps.dat").read_text().splitlines():
        if line.startswith("#"):
            names = line[1:].split()
        elif line.strip():
            rows[int(line.split()[0])] = line.split()
    row = dict(zip(names, rows[4000]))
    got = check.scalars()
    for name in ("phi_b", "phi_c", "Z"):
        assert got[name] == pytest.approx(float(row[name]), abs=0.5e-8 + 1e-8), name
    for name in ("z_top", "h_s"):
        assert got[name] == pytest.approx(float(row[name]), abs=0.5e-6 + 1e-8), name


def test_a_box_a_whole_number_of_columns_wide_only_within_rounding_has_them_all():
    """Six diameters of 0.2 make 1.2, and 1.2 / 0.2 = 5.999...: the compute counts columns as
    floor(L / 2R + 1e-9) (6 here), so h_s is the mean top of the 36 one-sphere columns. The
    check counted 5 (h_s 0.5954 for the compute's 0.5823, <Phi^c> 0.1126 for 0.1120)."""
    radius, side = 0.1, 1.2
    assert side / (2 * radius) < 6
    rng = np.random.default_rng(3)
    pos, _ = square_layer(6, radius)
    pos[:, 2] += rng.uniform(0, 0.8, len(pos))
    check = PackingCheck(frame(pos, radius, [0, 0, 0], [side, side, 3], [True, True, False]),
                         digits=None).compute()
    assert check.surface == pytest.approx(np.mean(pos[:, 2] + radius), rel=1e-14)
    assert check.window_top == pytest.approx(0.9 * check.surface, rel=1e-14)


@pytest.mark.parametrize("lo,hi,message", [
    ([0, 0, 0], [0, 4, 10], r"box_hi = \[0.0, 4.0, 10.0\] must exceed box_lo"),
    ([4, 0, 0], [0, 4, 10], r"box_hi = \[0.0, 4.0, 10.0\] must exceed box_lo = \[4.0"),
    ([0, 0, 0], [np.nan, 4, 10], r"box_hi\[0\] = nan is not finite"),
    # spheres of diameter 1 that reach their own images: legal = True, no overlap, before
    ([0, 0, 0], [0.9, 4, 10], r"periodic box length along x = 0.9 must be at least the largest "
                              r"diameter 1 \(a sphere would overlap its own image\)"),
])
def test_a_box_without_width_is_refused_by_name(lo, hi, message):
    """A periodic x of zero width gave legal = True and Phi = inf, an inverted box negative
    fractions, a NaN bound a numpy error: the box is checked as Contacts checks it."""
    pos = [[1.0, 1.0, 0.5], [2.5, 2.0, 0.5]]
    with pytest.raises(ValueError, match=message):
        PackingCheck(frame(pos, 0.5, lo, hi, [True, True, False]))


def test_radii_and_positions_of_different_lengths_are_refused_by_name():
    bad = Frame(0, [0, 0, 0], [4, 4, 10], [True, True, False], np.arange(1, 3),
                np.array([[1.0, 1.0, 0.5], [2.5, 2.0, 0.5]]), np.array([0.5, 0.5, 0.5]))
    with pytest.raises(ValueError, match="radii has 3 values but positions has 2 spheres"):
        PackingCheck(bad)


def _write_dump(path, positions, radius, box, fmt):
    """One frame of a dump custom 'id x y z radius' with the coordinates written by ``fmt``."""
    lines = ["ITEM: TIMESTEP", "0", "ITEM: NUMBER OF ATOMS", str(len(positions)),
             "ITEM: BOX BOUNDS pp pp fm"] + [f"0 {b!r}" for b in box]
    lines.append("ITEM: ATOMS id x y z radius")
    lines += [f"{i + 1} " + " ".join(fmt % c for c in p) + f" {radius!r}"
              for i, p in enumerate(positions)]
    path.write_text("\n".join(lines) + "\n")


@pytest.mark.parametrize("fmt, digits", [("%g", 6), ("%.10g", 10), ("%.17g", 17)])
def test_the_digits_a_dump_was_written_with_decide_its_resolution(tmp_path, fmt, digits):
    """Touching spheres of irrational radius, dumped with LAMMPS's default %g (6 digits): the
    rounding makes some pairs closer than contact by about 1e-6, which the check must take for
    rounding (the reader records the 6 digits), not for overlaps; at 10 and 17 digits the
    same packing is legal too, and a real overlap of 1e-3 is found at every precision."""
    radius = math.pi / 6
    pos, side = square_layer(12, radius)
    pos = pos + np.array([0.1234567891, 0.9876543219, 0.0])   # coordinates with many digits
    path = tmp_path / "layer.dump"
    _write_dump(path, pos, radius, (side, side, 4.0), fmt)
    read = read_dump(path).frames[0]
    assert read.digits == digits
    check = PackingCheck(read).compute()
    assert check.resolution > 0 and check.legal and check.overlaps == 0, check.min_gap
    if digits == 6:
        # read as if written at the paper inputs' 10 digits, the rounding looks like overlaps
        assert PackingCheck(read, digits=10).compute().overlaps > 0
    pos[1, 1] -= 1e-3 * 2 * radius                             # push one sphere into its neighbour
    _write_dump(path, pos, radius, (side, side, 4.0), fmt)
    assert PackingCheck(read_dump(path).frames[0]).compute().overlaps == 1


def test_a_frame_made_by_hand_is_checked_at_the_paper_inputs_digits():
    pos, side = square_layer(4, 0.5)
    made = frame(pos, 0.5, [0, 0, 0], [side, side, 5], [True, True, False])
    assert made.digits is None
    assert PackingCheck(made).digits == 10 and PackingCheck(made, digits=None).digits is None
    with pytest.raises(ValueError, match="digits"):
        PackingCheck(made, digits="dump")
