# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# The default selection of tapmc-pores is the packing itself (doc/tapmc-pores.rst, "Selection"):
# on a real TAPMC dump (tests/pores/data/small_tapped.dump.gz: 512 spheres, R = 0.5, periodic x
# and y, floor at z = 0, box top at z = 20 far above the packing), in a box starting below the
# floor (DEM-like), with --floor; and the warnings for selections without pores, with unresolved
# or out-of-range pores, or reaching the free surface.
import os
import re

import numpy as np

from pores_py_util import read_csv, read_dump_frame, run, surface_height, write

DATA = os.path.join(os.environ.get("TAPMC_SOURCE_DIR", "."), "tests/pores/data/small_tapped.dump.gz")
R = 0.5


def packing():
    centres, bounds, periodic, text = read_dump_frame(DATA)
    floor = centres[:, 2].min() - R
    h_s = surface_height(centres, R, bounds[:2, 0], bounds[:2, 1], 2 * R)
    return centres, bounds, periodic, text, floor, h_s


def deep_box(tmp_path, text, z_bounds="-5 40"):
    """The same frame in a box from z = -5 to 40 (a DEM box starting below the floor)."""
    lines = text.splitlines()
    lines[7] = z_bounds
    return write(tmp_path / "deep_box.dump", "\n".join(lines) + "\n")


def selection_of(prefix):
    pores = read_csv(f"{prefix}.pores.csv")
    return pores, pores["selected"] == 1


def hist_comment(prefix):
    with open(f"{prefix}.hist.csv") as f:
        return f.readline()


def test_default_selection_is_the_packing_not_the_box(tmp_path):
    centres, bounds, periodic, _, floor, h_s = packing()
    assert periodic == [True, True, False]
    assert abs(floor) < 1e-3  # the packing rests on the floor z = 0 (the box bottom here)
    assert bounds[2, 1] - h_s > 20 * R  # the box top is open space far above the packing
    result = run("--pores", "-o", tmp_path / "out", DATA)
    assert result.returncode == 0, result.stderr
    assert "warning" not in result.stderr, result.stderr
    pores, sel = selection_of(tmp_path / "out")
    # Selected: whole x and y; z from 2R above the floor to 4R below h_s (oracle in Python).
    expected = (pores["z"] >= floor + 2 * R) & (pores["z"] < h_s - 4 * R)
    assert np.array_equal(sel, expected)
    assert sel.sum() > 1500
    # Interior pores of a hard-sphere packing only: no hull cell of the free surface (those have
    # xi of several R), nothing out of the histogram's range, nothing unresolved in the selection.
    assert pores["xi"][sel].max() < 1.0
    assert "above 0" in hist_comment(tmp_path / "out")
    frames = read_csv(tmp_path / "out.frames.csv")
    nu = frames["nu"][0]
    assert abs(nu - np.mean(pores["xi"][sel] ** 3)) < 1e-9
    assert nu < 0.2  # a random packing near phi = 0.6 has nu ~ 0.12; open space gives nu > 1


def test_a_box_starting_below_the_floor_changes_nothing(tmp_path):
    centres, bounds, periodic, text, floor, h_s = packing()
    deep = deep_box(tmp_path, text)
    for options, name in ([], "default"), (["--paper-window"], "paper"):
        a = run("-q", "--pores", *options, "-o", tmp_path / f"{name}_a", DATA)
        b = run("-q", "--pores", *options, "-o", tmp_path / f"{name}_b", deep)
        assert a.returncode == 0 and b.returncode == 0, a.stderr + b.stderr
        pores_a, sel_a = selection_of(tmp_path / f"{name}_a")
        pores_b, sel_b = selection_of(tmp_path / f"{name}_b")
        assert np.array_equal(sel_a, sel_b), name
        assert sel_a.sum() > 1500
        assert np.all(pores_b["z"][sel_b] >= floor + 2 * R)  # counted from the floor, not from z = -5
        if name == "paper":  # --radii --z 2:20 above the floor: here up to the box top of the first box
            assert np.array_equal(sel_b, (pores_b["z"] >= floor + 2 * R) & (pores_b["z"] < floor + 20 * R))
            # 20R above the floor is above this small packing's surface: said on stderr.
            assert "free surface" in b.stderr and "warning" in b.stderr


def test_floor_option(tmp_path):
    centres, bounds, periodic, text, floor, h_s = packing()
    deep = deep_box(tmp_path, text)
    result = run("-q", "--pores", "--floor", "-1", "-o", tmp_path / "low", deep)
    assert result.returncode == 0, result.stderr
    pores, sel = selection_of(tmp_path / "low")
    assert np.array_equal(sel, (pores["z"] >= -1 + 2 * R) & (pores["z"] < h_s - 4 * R))
    # A floor above the lowest spheres: analysed, with a warning.
    result = run("-q", "--floor", "0.5", "-o", tmp_path / "high", deep)
    assert result.returncode == 0, result.stderr
    assert "reach below --floor 0.5" in result.stderr, result.stderr
    # A floor at or above the free surface, or along a periodic z: refused, nothing written.
    result = run("-q", "--floor", "100", "-o", tmp_path / "bad", deep)
    assert result.returncode == 2 and "--floor 100" in result.stderr and "free surface" in result.stderr
    result = run("-q", "--floor", "0", "--boundary", "ppp", "-o", tmp_path / "bad", DATA)
    assert result.returncode == 2 and "periodic" in result.stderr, result.stderr
    assert not list(tmp_path.glob("bad*"))
    # Usage errors name the option.
    for option in ("--floor", "--surface-gap"):
        result = run(option, "x", DATA)
        assert result.returncode == 2 and option in result.stderr
    assert run("--surface-gap", "-1", DATA).returncode == 2


def test_surface_gap_option(tmp_path):
    centres, bounds, periodic, text, floor, h_s = packing()
    result = run("-q", "--pores", "--surface-gap", "6", "-o", tmp_path / "gap", DATA)
    assert result.returncode == 0, result.stderr
    pores, sel = selection_of(tmp_path / "gap")
    assert np.array_equal(sel, (pores["z"] >= floor + 2 * R) & (pores["z"] < h_s - 6 * R))


def test_an_empty_default_selection_is_an_error(tmp_path):
    result = run("-q", "--surface-gap", "20", "-o", tmp_path / "out", DATA)
    assert result.returncode == 2
    assert "empty selection region along z" in result.stderr and "h_s" in result.stderr, result.stderr


def test_warnings(tmp_path):
    _, _, _, _, floor, h_s = packing()
    # No pore in a tiny selection (given twice: one warning for both frames).
    result = run("-q", "--x", "3:3.001", "--y", "3:3.001", "--z", "3:3.001", "-o", tmp_path / "none", DATA, DATA)
    assert result.returncode == 0, result.stderr
    assert re.search(r"warning: .*frame 1 \(timestep 20\): no pore in the selection", result.stderr), result.stderr
    assert "(and in 1 more of the 2 frames)" in result.stderr
    assert result.stderr.count("warning") == 1
    # Up to the box top: the free surface and its hull cells, xi beyond --xi-max.
    result = run("-q", "--z", "0:20", "-o", tmp_path / "top", DATA)
    assert result.returncode == 0, result.stderr
    assert f"R above the free surface h_s = {h_s:.6g}" in result.stderr, result.stderr
    assert "have xi >= --xi-max 1.5" in result.stderr
    # Above the surface only: open space, pores left unresolved (wider than the largest padding).
    result = run("-q", "--z", f"{h_s - R}:20", "-o", tmp_path / "above", DATA)
    assert result.returncode == 0, result.stderr
    assert re.search(r"warning: .* pores centred in the selection .* are unresolved", result.stderr), result.stderr


def test_a_triply_periodic_selection_does_not_depend_on_the_atom_order(tmp_path):
    """A loose triply periodic packing (RSA, phi 0.3) and a thin selection: a cell outside the
    selection left unresolved could not ask for a wider padding, so the run stopped ('too
    sparse for the padding') or not depending on which periodic copy the canonical rule kept,
    that is on the atoms' order (5 of 9 packings tried). Every cell of a triply periodic box
    now may: both orders give the same pores."""
    from pores_py_util import dump_text, random_packing

    for seed in range(1, 5):
        side = (100 * 4 / 3 * np.pi * 0.125 / 0.3) ** (1 / 3)
        centres = random_packing(100, side, [True] * 3, seed)
        order = np.random.default_rng(5).permutation(len(centres))
        outputs = []
        for name, (c, ids) in {"a": (centres, None), "b": (centres[order], order + 1)}.items():
            dump = write(tmp_path / f"{name}{seed}.dump", dump_text(c, side, [True] * 3, ids=ids))
            result = run("-q", "--z", "0:1", "-o", tmp_path / f"{name}{seed}", dump)
            assert result.returncode == 0, (seed, name, result.stderr)
            outputs.append((tmp_path / f"{name}{seed}.hist.csv").read_text().split("\n", 1)[1])
        assert outputs[0] == outputs[1], seed
