# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# tapmc-pores as users run it: many files and frames (gzip), outputs, P0, and bad input refused
# with file, frame and line and a non-zero exit code.
import json
import math

import numpy as np
import pytest

from pores_py_util import dump_text, random_packing, read_csv, read_dump_frame, run, surface_height, write

GOOD = dump_text(random_packing(120, 7.0, [True, True, True], 1), 7.0, [True, True, True])


def test_help():
    result = run("--help")
    assert result.returncode == 0
    assert "Usage: tapmc-pores" in result.stdout


def test_usage_errors():
    assert run().returncode == 1
    result = run("--bins", "zero", "x.dump")
    assert result.returncode == 1 and "--bins" in result.stderr
    result = run("--frobnicate", "x.dump")
    assert result.returncode == 1 and "unknown option" in result.stderr


def test_many_files_and_frames_aggregate(tmp_path):
    packings = [random_packing(150, 7.0, [True, True, False], s) for s in range(4)]
    a = write(tmp_path / "a.dump.gz", dump_text(packings[0], 7.0, [1, 1, 0], 0) + dump_text(packings[1], 7.0, [1, 1, 0], 100))
    b = write(tmp_path / "b.dump", dump_text(packings[2], 7.0, [1, 1, 0], 0, columns="z y x id diameter")
              + dump_text(packings[3], 7.0, [1, 1, 0], 100, columns="xu yu zu id radius"))
    result = run("-q", "--json", "--frame-hist", "--pores", "-o", tmp_path / "out", a, b)
    assert result.returncode == 0, result.stderr
    frames = read_csv(tmp_path / "out.frames.csv")
    assert len(frames["frame"]) == 4
    assert list(frames["timestep"]) == [0, 100, 0, 100]
    hist = read_csv(tmp_path / "out.hist.csv")
    data = json.load(open(tmp_path / "out.json"))
    # Loose RSA packings have some pores beyond xi = 1.5: counted as overflow, not dropped.
    assert hist["count_xi"].sum() + data["aggregate"]["xi_overflow"] == frames["selected"].sum()
    in_range = hist["count_xi"].sum() / frames["selected"].sum()
    assert abs((hist["P_xi"] * (hist["xi_hi"] - hist["xi_lo"])).sum() - in_range) < 1e-9
    pores = read_csv(tmp_path / "out.pores.csv")
    sel = pores["selected"] == 1
    # Default selection: whole x and y (periodic), z from 2R (= 1.0) above the floor (the lowest
    # sphere bottom) to 4R (= 2.0) below the free surface h_s (oracle: surface_height).
    frame_of = [f"{f}:{int(t)}" for f, t in zip(pores["file"], pores["timestep"])]
    keys = [f"{a}:0", f"{a}:100", f"{b}:0", f"{b}:100"]
    for key, packing in zip(keys, packings):
        floor = packing[:, 2].min() - 0.5
        top = surface_height(packing, 0.5, [0, 0], [7, 7], 1.0) - 2.0
        mine = np.array([k == key for k in frame_of])
        assert mine.sum() > 500, key
        z = pores["z"][mine]
        assert np.array_equal(pores["selected"][mine] == 1, (z >= floor + 1.0) & (z < top)), key
    assert sel.sum() == frames["selected"].sum()
    nu = np.mean(pores["xi"][sel] ** 3)
    assert data["frames_analysed"] == 4
    assert data["aggregate"]["pores"] == sel.sum()
    assert math.isclose(data["aggregate"]["nu"], nu, rel_tol=1e-9)
    assert len(data["frames"][0]["statistics"]["count_xi"]) == 150
    per_frame = read_csv(tmp_path / "out.frame_hist.csv")
    assert per_frame["count_xi"].sum() == hist["count_xi"].sum()
    # Frame selection options.
    result = run("-q", "--skip", "1", "--every", "2", "-o", tmp_path / "sub", a, b)
    assert result.returncode == 0, result.stderr
    assert list(read_csv(tmp_path / "sub.frames.csv")["timestep"]) == [100, 100]


def test_fcc_and_paper_window(tmp_path):
    # FCC at contact (R = 1/sqrt 2, cube edge 2: exact coordinates), 4^3 cells, periodic.
    basis = np.array([[0, 0, 0], [1, 1, 0], [1, 0, 1], [0, 1, 1]])
    cells = np.array([[i, j, k] for i in range(4) for j in range(4) for k in range(4)]) * 2
    centres = (cells[:, None, :] + basis[None, :, :]).reshape(-1, 3).astype(float)
    dump = write(tmp_path / "fcc.dump", dump_text(centres, 8.0, [True] * 3, radius=math.sqrt(0.5), columns="id x y z"))
    result = run("-q", "-r", math.sqrt(0.5), "--p0", 20000, "-o", tmp_path / "fcc", dump)
    assert result.returncode == 0, result.stderr
    frames = read_csv(tmp_path / "fcc.frames.csv")
    assert frames["pores"][0] == 3 * 256 and frames["degenerate_selected"][0] == 256
    assert math.isclose(frames["tetrahedra_volume"][0], 512.0, rel_tol=1e-12)
    hist = read_csv(tmp_path / "fcc.hist.csv")
    peaks = hist["xi"][hist["count_xi"] > 0]
    assert len(peaks) == 2
    assert abs(peaks[0] - (math.sqrt(1.5) - 1)) < 0.01 and abs(peaks[1] - (math.sqrt(2) - 1)) < 0.01
    p0 = read_csv(tmp_path / "fcc.p0.csv")
    phi = math.pi / (3 * math.sqrt(2))  # FCC packing fraction 0.7405
    assert abs(frames["phi_p0"][0] - phi) < 5 * math.sqrt(phi * (1 - phi) / 20000)
    assert np.all(np.diff(p0["P0_measured"]) <= 0)
    # No point is farther than the octahedral hole's radius sqrt(2) R from every centre.
    assert np.all(p0["P0_measured"][p0["sigma"] > math.sqrt(2) + 1e-9] == 0)
    # Paper window in units of R above the box floor: pores with z in [2R, 6R).
    result = run("-q", "-r", math.sqrt(0.5), "--radii", "--z", "2:6", "--pores", "-o", tmp_path / "win", dump)
    assert result.returncode == 0, result.stderr
    pores = read_csv(tmp_path / "win.pores.csv")
    sel = pores["selected"] == 1
    r = math.sqrt(0.5)
    assert np.all((pores["z"][sel] >= 2 * r) & (pores["z"][sel] < 6 * r))
    assert np.all((pores["z"][~sel] < 2 * r) | (pores["z"][~sel] >= 6 * r))
    # --paper-window: z in [2R, 20R) above the floor (here: the whole 8-long periodic box from 2R).
    result = run("-q", "-r", r, "--paper-window", "--pores", "-o", tmp_path / "paper", dump)
    assert result.returncode == 0, result.stderr
    pores = read_csv(tmp_path / "paper.pores.csv")
    sel = pores["selected"] == 1
    assert np.all(sel == (pores["z"] >= 2 * r) & (pores["z"] < 20 * r))


def _frame(n_atoms_line, atom_lines, flags="pp pp pp", columns="id x y z radius", bounds=("0 7", "0 7", "0 7")):
    return "\n".join(["ITEM: TIMESTEP", "0", "ITEM: NUMBER OF ATOMS", n_atoms_line, "ITEM: BOX BOUNDS " + flags,
                      *bounds, "ITEM: ATOMS " + columns, *atom_lines]) + "\n"


BAD = {
    "truncated": (_frame("3", ["1 1 1 1 0.5", "2 3 3 3 0.5"]), 11, "truncated"),
    "non_numeric": (_frame("2", ["1 1 1 1 0.5", "2 3 x 3 0.5"]), 11, "non-numeric"),
    "nan": (_frame("2", ["1 1 1 1 0.5", "2 3 nan 3 0.5"]), 11, "non-finite"),
    "missing_coordinates": (_frame("1", ["1 1 1 0.5"], columns="id x y radius"), 9, "no z coordinate"),
    "zero_atoms": (_frame("0", []), 4, "zero atoms"),
    "duplicate_ids": (_frame("2", ["7 1 1 1 0.5", "7 3 3 3 0.5"]), 11, "duplicate atom id 7"),
    "outside_box": (_frame("2", ["1 1 1 1 0.5", "2 3 3 7.5 0.5"], flags="pp pp fm"), 11, "outside the non-periodic box"),
    "triclinic": (_frame("1", ["1 1 1 1 0.5"], flags="xy xz yz pp pp pp", bounds=("0 7 0", "0 7 0", "0 7 0")), 5, "triclinic"),
    "overlap": (_frame("2", ["1 1 1 1 0.5", "2 1.5 1 1 0.5"]), 10, "overlap"),
    "polydisperse": (_frame("2", ["1 1 1 1 0.5", "2 3 3 3 0.6"]), 11, "polydisperse"),
}


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_input_is_refused_with_file_frame_and_line(tmp_path, name):
    text, line, fragment = BAD[name]
    good = write(tmp_path / "good.dump", GOOD)
    bad = write(tmp_path / f"{name}.dump.gz", text)
    result = run("-q", "-o", tmp_path / "out", good, bad)
    assert result.returncode == 2, result.stderr
    message = result.stderr
    assert f"{name}.dump.gz:{line}:" in message, message
    assert "frame 1" in message and fragment in message, message
    assert "Traceback" not in message and "internal error" not in message


def test_missing_radius_and_missing_file(tmp_path):
    dump = write(tmp_path / "nor.dump", _frame("1", ["1 1 1 1"], columns="id x y z"))
    result = run("-q", "-o", tmp_path / "out", dump)
    assert result.returncode == 2 and "--radius" in result.stderr
    result = run("-q", "-o", tmp_path / "out", tmp_path / "missing.dump")
    assert result.returncode == 2 and "missing.dump" in result.stderr and "cannot open" in result.stderr
