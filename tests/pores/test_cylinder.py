# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# --cylinder CX:CY:RC (doc/tapmc-pores.rst, "Selection"): in a vertical tube the selection in x
# and y is the disk of radius RC - G R about the axis (G = --wall-gap, 2 by default), the
# side-wall rule measured radially from the tube's wall; z keeps its rule. On a synthesized
# packing in a tube (hard spheres inside a disk, box non-periodic), with a control showing that
# the default square selection takes in the empty corners outside the tube, and the errors.
import numpy as np
import pytest

from pores_py_util import dump_text, random_packing, read_csv, run, write

R = 0.5
SIDE = 10.0
CX, CY, RC = 5.0, 5.0, 5.0
TUBE = f"{CX}:{CY}:{RC}"


@pytest.fixture(scope="module")
def tube_dump(tmp_path_factory):
    """Random hard spheres in a box 20R wide, kept when inside the tube of radius RC = 10R about
    the box's vertical axis (centres at most RC - R from it); x, y and z non-periodic."""
    centres = random_packing(450, SIDE, (False, False, False), seed=3)
    centres = centres[np.hypot(centres[:, 0] - CX, centres[:, 1] - CY) <= RC - R]
    assert len(centres) > 250
    return write(tmp_path_factory.mktemp("tube") / "tube.dump", dump_text(centres, SIDE, (False, False, False)))


def pores_of(tmp_path, dump, name, *options):
    prefix = tmp_path / name
    result = run("-q", "--pores", "-o", prefix, *options, dump)
    assert result.returncode == 0, result.stderr
    pores = read_csv(f"{prefix}.pores.csv")
    pores["radial"] = np.hypot(pores["x"] - CX, pores["y"] - CY)
    return pores, pores["selected"] == 1, read_csv(f"{prefix}.frames.csv")


def z_range(pores, selected):
    return pores["z"][selected].min(), pores["z"][selected].max()


def test_the_default_square_takes_in_the_corners_outside_the_tube(tmp_path, tube_dump):
    # Control: without --cylinder the selection is the x-y extent of the spheres (a square) less
    # 2R, whose corners lie outside the disk RC - 2R and even outside the tube: hull cells.
    pores, selected, _ = pores_of(tmp_path, tube_dump, "square")
    assert (pores["radial"][selected] >= RC - 2 * R).sum() > 10
    outside = selected & (pores["radial"] > RC)
    assert outside.sum() >= 1
    assert pores["xi"][outside].min() > 0.5  # empty space between the tube wall and the square


def test_cylinder_keeps_the_disk_rc_minus_the_wall_gap(tmp_path, tube_dump):
    square, square_selected, _ = pores_of(tmp_path, tube_dump, "square")
    pores, selected, frames = pores_of(tmp_path, tube_dump, "tube", "--cylinder", TUBE)
    assert selected.sum() > 100
    assert pores["radial"][selected].max() < RC - 2 * R
    # z keeps its rule (2R above the floor to 4R below h_s): the same bounds as without the tube,
    # and inside them exactly the pores of the disk are selected.
    z_lo, z_hi = z_range(square, square_selected)
    in_z = (pores["z"] >= z_lo) & (pores["z"] <= z_hi)
    assert np.array_equal(selected, in_z & (pores["radial"] < RC - 2 * R))
    height = frames["region_volume"][0] / (np.pi * (RC - 2 * R) ** 2)
    assert z_lo >= 2 * R and z_hi - z_lo <= height + 1e-9


def test_wall_gap_and_paper_window_measure_from_the_tube_wall(tmp_path, tube_dump):
    pores, selected, _ = pores_of(tmp_path, tube_dump, "gap1", "--cylinder", TUBE, "--wall-gap", "1")
    radial = pores["radial"][selected]
    assert radial.max() < RC - R and (radial > RC - 2 * R).any()
    pores, selected, _ = pores_of(tmp_path, tube_dump, "paper", "--cylinder", TUBE, "--paper-window")
    assert pores["radial"][selected].max() < RC - 2 * R
    assert pores["z"][selected].min() >= 2 * R  # the floor (lowest sphere bottom) is at z >= 0


def test_p0_points_are_drawn_in_the_disk(tmp_path, tube_dump):
    # Points in the empty corners would lower the volume fraction they see.
    phi = {}
    for name, options in (("square", ()), ("tube", ("--cylinder", TUBE))):
        result = run("-q", "--p0", 20000, "-o", tmp_path / name, *options, tube_dump)
        assert result.returncode == 0, result.stderr
        phi[name] = read_csv(tmp_path / f"{name}.frames.csv")["phi_p0"][0]
    assert phi["tube"] > phi["square"] + 0.01


@pytest.mark.parametrize("value, says", [
    ("5:5:0", "RC = 0 must be > 0"),
    ("5:5:-1", "RC = -1 must be > 0"),
    ("5:5", "expects CX:CY:RC"),
    ("5:x:3", "expects a number, got 'x'"),
])
def test_bad_values_are_usage_errors(tmp_path, tube_dump, value, says):
    result = run("-o", tmp_path / "bad", "--cylinder", value, tube_dump)
    assert result.returncode == 2 and "--cylinder" in result.stderr and says in result.stderr, result.stderr
    assert not list(tmp_path.glob("bad*"))


@pytest.mark.parametrize("options, says", [
    (("--cylinder", "6:5:5"), "CX must lie in [5, 5]"),          # the tube leaves the box
    (("--cylinder", "5:2:4"), "CY must lie in [4, 6]"),
    (("--cylinder", "5:5:1"), "empty selection"),                # RC within --wall-gap 2R
    (("--cylinder", "4:4:4"), "outside the tube of radius 4"),   # spheres outside the tube
    (("--cylinder", TUBE, "--boundary", "pff"), "x is periodic"),
    (("--cylinder", TUBE, "--boundary", "fpf"), "y is periodic"),
    (("--cylinder", TUBE, "--y", "1:2"), "--y cannot be given with it"),
])
def test_refused_runs_name_the_option(tmp_path, tube_dump, options, says):
    result = run("-o", tmp_path / "bad", *options, tube_dump)
    assert result.returncode == 2 and "--cylinder" in result.stderr and says in result.stderr, result.stderr
    assert not list(tmp_path.glob("bad*"))
