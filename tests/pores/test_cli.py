# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# tapmc-pores as users run it: many files and frames (gzip), outputs, P0, bad input refused with
# file, frame and line and a non-zero exit code, the overlap refusal (deepest pair, threshold,
# --overlap-tol), no output after a refused run, the closing line, and help/doc/config agreement.
import json
import math
import os
import re

import numpy as np
import pytest

from pores_py_util import dump_text, random_packing, read_csv, read_dump_frame, run, surface_height, write

GOOD = dump_text(random_packing(120, 7.0, [True, True, True], 1), 7.0, [True, True, True])


def test_help():
    result = run("--help")
    assert result.returncode == 0
    assert "Usage: tapmc-pores" in result.stdout
    assert "2 usage error" in result.stdout and "--version" in result.stdout


def test_version():
    # the one version of TAPMC: __version__ of tools/python/tapmc/__init__.py
    source = os.environ.get("TAPMC_SOURCE_DIR", ".")
    init = open(os.path.join(source, "tools/python/tapmc/__init__.py")).read()
    version = re.search(r'^__version__ = "([0-9.]+)"$', init, re.M).group(1)
    result = run("--version")
    assert result.returncode == 0 and result.stdout == f"tapmc-pores {version}\n", result


def test_usage_errors():
    # exit code 2, as for tapmc-paper (argparse); bad input gives 2 as well
    assert run().returncode == 2
    result = run("--bins", "zero", "x.dump")
    assert result.returncode == 2 and "--bins" in result.stderr
    result = run("--frobnicate", "x.dump")
    assert result.returncode == 2 and "unknown option" in result.stderr


def test_xi_max_beyond_its_limit_is_a_usage_error():
    # --xi-max 1e300 overflowed the v = xi^3 histogram to inf (empty v_lo, n_v 0), exit 0;
    # 1e-200 underflowed it to [0, 0), an error naming neither the option nor its value
    for value in ("1e300", "1000.5", "0", "-1", "1e-200"):
        result = run("-q", "--xi-max", value, "x.dump")
        assert result.returncode == 2, result.stderr
        assert f"--xi-max = {value}: allowed range [0.001, 1000] (a pore radius over R)" \
            in result.stderr, result.stderr
    assert run("--xi-max", "1000", "--help").returncode == 0


@pytest.mark.parametrize("option,value,allowed", [
    ("--radius", "-1", "(0, inf)"), ("--wall-gap", "-1", "[0, inf), in R"),
    ("--surface-gap", "-3", "[0, inf), in R"), ("--sigma-max", "0.5", "(1, 1000] (in R)"),
    ("--sigma-max", "1e308", "(1, 1000] (in R)"),   # every grid step was inf
    ("--overlap-tol", "2", "[0, 1)"), ("--merge-tol", "1e9", "[0, 0.1)"),
])
def test_a_value_out_of_range_is_named_with_its_range(option, value, allowed):
    """These said "--radius must be positive" without the value given."""
    result = run("-q", option, value, "x.dump")
    assert result.returncode == 2
    assert f"{option} = {value}: allowed range {allowed}" in result.stderr, result.stderr


def test_an_empty_output_prefix_is_a_usage_error():
    """-o '' wrote the hidden files .hist.csv and .frames.csv into the working folder."""
    result = run("-q", "-o", "", "x.dump")
    assert result.returncode == 2 and "-o expects a file prefix" in result.stderr, result.stderr


def test_bins_beyond_the_limit_is_a_usage_error():
    # --bins 10^15 used to reach the allocation of the histograms: "internal error:
    # std::bad_alloc", exit code 3. The limit is kMaxBins of pores_config.h, quoted by --help.
    source = os.environ.get("TAPMC_SOURCE_DIR", ".")
    config = open(os.path.join(source, "tools/pores/include/tapmc_pores/pores_config.h")).read()
    limit = int(re.search(r"constexpr std::size_t kMaxBins = (\d+);", config).group(1))
    for value in ("1000000000000000", str(limit + 1), "0", "99999999999999999999999"):
        result = run("-q", "--bins", value, "x.dump")
        assert result.returncode == 2, result.stderr
        assert f"tapmc-pores: --bins = {value}: allowed range [1, {limit}]" in result.stderr, result.stderr
        assert "internal error" not in result.stderr
    # The limit itself is accepted (with --help: parsed, nothing analysed).
    assert run("--bins", limit, "--help").returncode == 0
    assert run("--bins", limit + 1, "--help").returncode == 2
    help_line = next(l for l in run("--help").stdout.split("\n  -")[1:] if l.startswith("-bins"))
    assert f"at most {limit}" in help_line, help_line


def _config_limit(name):
    """The value of the constant `name` of pores_config.h."""
    source = os.environ.get("TAPMC_SOURCE_DIR", ".")
    config = open(os.path.join(source, "tools/pores/include/tapmc_pores/pores_config.h")).read()
    return re.search(rf"constexpr (?:std::size_t|double) {name} = ([0-9.e+]+);", config).group(1)


def _help_entry(option):
    """The --help entry of `option`, continuation lines included, on one line."""
    entry = next(e for e in run("--help").stdout.split("\n  -")[1:] if e.startswith(option[1:] + " "))
    return " ".join(entry.split())


def test_sigma_steps_and_p0_beyond_their_limits_are_usage_errors(tmp_path):
    # --sigma-steps 10^15 ended in "internal error: std::bad_alloc" (exit code 3), --p0 10^15 in
    # "FILE:1: frame 1 (timestep 20): std::bad_alloc" (exit code 2) once the frame was
    # triangulated. The limits are kMaxSigmaSteps and kMaxP0Samples of pores_config.h.
    steps, samples = int(_config_limit("kMaxSigmaSteps")), int(_config_limit("kMaxP0Samples"))
    for option, minimum, limit in (("--sigma-steps", 2, steps), ("--p0", 1, samples)):
        for value in ("1000000000000000", str(limit + 1), str(minimum - 1), "99999999999999999999999"):
            result = run("-q", "--p0", 100, option, value, "-o", tmp_path / "out", DATA)
            assert result.returncode == 2, result.stderr
            assert f"tapmc-pores: {option} = {value}: allowed range [{minimum}, {limit}]" in result.stderr, result.stderr
            assert "internal error" not in result.stderr and "bad_alloc" not in result.stderr
            assert not list(tmp_path.iterdir())
        # The limit itself is parsed (with --help: nothing analysed), limit + 1 is not.
        assert run(option, limit, "--help").returncode == 0
        assert run(option, limit + 1, "--help").returncode == 2
    assert f"at most {samples}" in _help_entry("--p0")
    assert f"--sigma-steps K steps (default 200, at most {steps})" in _help_entry("--sigma-max")
    # The largest grid is cheap to run: one frame, 100 points, a CSV row per step.
    result = run("-q", "--p0", 100, "--sigma-steps", steps, "-o", tmp_path / "fine", DATA)
    assert result.returncode == 0, result.stderr
    p0 = read_csv(tmp_path / "fine.p0.csv")
    assert len(p0["sigma"]) == steps and p0["sigma"][-1] == 2.0
    assert np.all(np.diff(p0["P0_measured"]) <= 0) and p0["P0_measured"][0] == 1.0


def test_padding_beyond_its_limit_is_a_usage_error(tmp_path):
    # --padding sizes the periodic images: --padding 1000 ran over two minutes on this 512-sphere dump,
    # and --padding 1e15 overflowed the count of images and ended with exit code 0 ("no pore in
    # the selection"). The limit is kMaxPaddingOverRadius of pores_config.h, in R.
    limit = float(_config_limit("kMaxPaddingOverRadius"))
    for value in ("1e15", "1000", f"{limit + 1:g}", f"{limit * (1 + 1e-12)!r}", "1.5"):
        result = run("-q", "--padding", value, "-o", tmp_path / "out", DATA)
        assert result.returncode == 2, result.stderr
        assert f"tapmc-pores: --padding = {value}: allowed range [2, {limit:g}], in R" in result.stderr, result.stderr
        assert not list(tmp_path.iterdir())
    assert f"at most {limit:g};" in _help_entry("--padding")
    # The limit itself runs (this slab, periodic in x and y: 25 times the centres) and selects the
    # pores of the default padding; only hull cells above the free surface are resolved in addition.
    frames, hist = {}, {}
    for padding in (f"{limit:g}", "4"):
        result = run("-q", "--padding", padding, "-o", tmp_path / padding, DATA)
        assert result.returncode == 0, result.stderr
        frames[padding] = read_csv(tmp_path / f"{padding}.frames.csv")
        hist[padding] = read_csv(tmp_path / f"{padding}.hist.csv")
    wide, default = f"{limit:g}", "4"
    assert frames[wide]["selected"][0] == frames[default]["selected"][0] > 1000
    assert frames[wide]["unresolved"][0] <= frames[default]["unresolved"][0]
    assert np.array_equal(hist[wide]["count_xi"], hist[default]["count_xi"])


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


@pytest.mark.parametrize("digits", [6, 10, 17])
def test_fcc_written_with_few_digits_keeps_its_octahedra_whole(tmp_path, digits):
    """FCC shifted off the lattice planes (coordinates of many digits), written with %g (LAMMPS's
    default, 6 digits), %.10g and %.17g: at every precision 3 pores per sphere, a quarter of
    them octahedra of 4 tetrahedra, and nu = (2 xi_T^3 + xi_O^3) / 3. At 6 digits the fixed
    tolerance 1e-8 split the octahedra (nu 0.0467); it now follows the digits (1e-4 here), and
    --merge-tol 1e-8 given by hand still splits them."""
    R = math.sqrt(0.5)
    basis = np.array([[0, 0, 0], [1, 1, 0], [1, 0, 1], [0, 1, 1]])
    cells = np.array([[i, j, k] for i in range(4) for j in range(4) for k in range(4)]) * 2
    centres = (cells[:, None, :] + basis[None, :, :]).reshape(-1, 3) + np.array([0.1234567891, 0.2345678912, 0.3456789123])
    lines = ["ITEM: TIMESTEP", "0", "ITEM: NUMBER OF ATOMS", str(len(centres)),
             "ITEM: BOX BOUNDS pp pp pp"] + ["0 8"] * 3 + ["ITEM: ATOMS id x y z"]
    lines += [f"{i + 1} " + " ".join(f"{v:.{digits}g}" for v in c) for i, c in enumerate(centres)]
    dump = write(tmp_path / "fcc.dump", "\n".join(lines) + "\n")
    nu = (2 * (math.sqrt(1.5) - 1) ** 3 + (math.sqrt(2) - 1) ** 3) / 3
    result = run("-q", "-r", R, "-o", tmp_path / "fcc", dump)
    assert result.returncode == 0, result.stderr
    frames = read_csv(tmp_path / "fcc.frames.csv")
    assert frames["pores"][0] == 3 * 256 and frames["degenerate_selected"][0] == 256
    assert math.isclose(frames["nu"][0], nu, rel_tol=1e-4), frames["nu"][0]
    if digits == 6:
        result = run("-q", "-r", R, "--merge-tol", "1e-8", "-o", tmp_path / "split", dump)
        assert result.returncode == 0, result.stderr
        assert read_csv(tmp_path / "split.frames.csv")["pores"][0] > 3 * 256


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
    "radius_diameter": (_frame("2", ["1 1 1 1 0.5 1", "2 3 3 3 0.5 1.2"], columns="id x y z radius diameter"), 11,
                        "atom 2: the radius and diameter columns disagree: radius 0.5, diameter 1.2 "
                        "(|diameter - 2 radius| / diameter = 0.167, allowed range [0, 2e-05])"),
}


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_input_is_refused_with_file_frame_and_line(tmp_path, name):
    text, line, fragment = BAD[name]
    good = write(tmp_path / "good.dump", GOOD)
    bad = write(tmp_path / f"{name}.dump.gz", text)
    result = run("-q", "-o", tmp_path / "out", good, bad)
    assert result.returncode == 2, result.stderr
    message = result.stderr
    # One form for every located message, from the reader as from the analysis.
    assert f"{name}.dump.gz:{line}: frame 1 (timestep 0): " in message, message
    assert fragment in message and "frame 1: (timestep" not in message, message
    assert "Traceback" not in message and "internal error" not in message


def test_a_box_too_small_for_its_spheres_is_named_whatever_the_padding(tmp_path):
    # One sphere in a periodic box of its own diameter: every pore is bound by the sphere and
    # its own images. The default padding said only "too sparse ... raise --padding" (and
    # --padding 32 then named the real cause): both now name a periodic length below a pore.
    dump = write(tmp_path / "one.dump", _frame("1", ["1 0.5 0.5 0.5 0.5"], bounds=("0 1",) * 3))
    for padding in ("8", "32"):
        result = run("-q", "--padding", padding, "-o", tmp_path / "out", dump)
        assert result.returncode == 2, result.stderr
        assert "one.dump:1: frame 1 (timestep 0): " in result.stderr
        assert re.search(r"periodic length is (likely )?below (a|the) pore'?s? diameter",
                         result.stderr), result.stderr
        assert not list(tmp_path.glob("out*"))


def test_numbers_in_messages_are_short(tmp_path):
    # std::to_string printed a radius of 1e300 as a padding of 301 digits, and a 1e-9 as 0.000000.
    huge = write(tmp_path / "huge.dump", _frame("1", ["1 0.5 0.5 0.5 1e300"], bounds=("0 1",) * 3))
    result = run("-q", "-o", tmp_path / "out", huge)
    assert result.returncode == 2 and "padding 4e+300 is over 100 box lengths" in result.stderr, \
        result.stderr
    assert not re.search(r"\d{20}", result.stderr)
    tiny = write(tmp_path / "tiny.dump", _frame("1", ["1 0.5 0.5 0.5 -1e-9"]))
    result = run("-q", "-o", tmp_path / "out", tiny)
    assert result.returncode == 2 and "radius must be positive, found -1e-09" in result.stderr, \
        result.stderr


def test_an_empty_dump_is_named_as_such(tmp_path):
    # It used to end the file cleanly: the run then said only "no frame analysed".
    good = write(tmp_path / "good.dump", GOOD)
    for name in ("empty.dump", "empty.dump.gz"):
        empty = write(tmp_path / name, "")
        result = run("-q", "-o", tmp_path / "out", good, empty)
        assert result.returncode == 2, result.stderr
        assert f"{empty}: empty file" in result.stderr, result.stderr
        assert "no frame analysed" not in result.stderr


def test_missing_radius_and_missing_file(tmp_path):
    dump = write(tmp_path / "nor.dump", _frame("1", ["1 1 1 1"], columns="id x y z"))
    result = run("-q", "-o", tmp_path / "out", dump)
    assert result.returncode == 2 and "--radius" in result.stderr
    result = run("-q", "-o", tmp_path / "out", tmp_path / "missing.dump")
    assert result.returncode == 2 and "missing.dump" in result.stderr and "cannot open" in result.stderr


DATA = os.path.join(os.environ.get("TAPMC_SOURCE_DIR", "."), "tests/pores/data/small_tapped.dump.gz")


def deepest_pair(centres, box, periodic):
    """Oracle: the closest pair of centres (minimum image along periodic directions)."""
    d = centres[:, None, :] - centres[None, :, :]
    for k in range(3):
        if periodic[k]:
            d[..., k] -= box[k] * np.round(d[..., k] / box[k])
    dist = np.sqrt(np.einsum("ijk,ijk->ij", d, d))
    np.fill_diagonal(dist, np.inf)
    i, j = np.unravel_index(np.argmin(dist), dist.shape)
    return min(i, j), max(i, j), dist[i, j], int(np.sum(dist < 0.999) // 2)


def test_overlap_message_names_deepest_pair_threshold_and_option(tmp_path):
    # A DEM-like frame: two pairs of the real packing pushed into each other, by 2 % and 4 %.
    centres, bounds, periodic, text = read_dump_frame(DATA)
    box = bounds[:, 1] - bounds[:, 0]
    for atom, depth in ((100, 0.02), (300, 0.04)):
        d = centres - centres[atom]
        d[:, :2] -= box[:2] * np.round(d[:, :2] / box[:2])
        dist = np.linalg.norm(d, axis=1)
        dist[atom] = np.inf
        other = int(np.argmin(dist))
        centres[other] = centres[atom] + d[other] / dist[other] * (1 - depth)
        centres[other, :2] %= box[:2]
    i, j, distance, pairs = deepest_pair(centres, box, periodic)
    lines = text.splitlines()
    for k, c in enumerate(centres):
        fields = lines[9 + k].split()
        fields[2:5] = [repr(v) for v in c]
        lines[9 + k] = " ".join(fields)
    dem = write(tmp_path / "dem.dump", "\n".join(lines) + "\n")
    result = run("-q", "--json", "-o", tmp_path / "out", dem)
    assert result.returncode == 2
    message = result.stderr
    depth = 1 - distance  # 2R = 1
    assert depth > 0.035
    assert f"dem.dump:{10 + i}: frame 1 (timestep 20): spheres {i + 1} and {j + 1} overlap by " in message, message
    assert f"{100 * depth:.4g} % of a diameter" in message, message
    assert f"the deepest of {pairs} overlapping pair" in message
    assert "pairs closer than 2R (1 - 0.001) = 0.999 are refused" in message
    assert f"(atom lines {10 + i} and {10 + j})" in message
    suggested = re.search(r"--overlap-tol ([0-9.e-]+) \(", message)
    assert suggested, message
    tolerance = float(suggested.group(1))
    assert depth < tolerance < depth + 0.002
    assert not list(tmp_path.glob("out*"))
    # The suggested tolerance accepts the frame; a slightly smaller one does not.
    assert run("-q", "--overlap-tol", tolerance, "-o", tmp_path / "out", dem).returncode == 0
    assert run("-q", "--overlap-tol", depth - 1e-4, "-o", tmp_path / "out2", dem).returncode == 2


def test_a_duplicated_sphere_is_refused_like_a_near_one(tmp_path):
    # A copy of atom 100 as atom 513 at exactly its position: CGAL's Delaunay merged the two
    # points, and the run gave the pores of 512 spheres with exit code 0.
    centres, bounds, periodic, text = read_dump_frame(DATA)
    lines = text.splitlines()
    copy = lines[9 + 99].split()
    assert copy[0] == "100"

    def with_copy(name, x):
        head = lines[:3] + ["513"] + lines[4:9 + 512]
        return write(tmp_path / name, "\n".join(head + [" ".join(["513", copy[1], x, *copy[3:]])]) + "\n")

    position = ", ".join(f"{float(v):.10g}" for v in copy[2:5])
    family = "dump:109: frame 1 (timestep 20): spheres 100 and 513 overlap by 100 % of a diameter (centre distance "
    result = run("-q", "-o", tmp_path / "out", with_copy("duplicate.dump", copy[2]))
    assert result.returncode == 2, result.stderr
    assert f"duplicate.{family}0, 2R = 1): both are at ({position}); pairs closer than 2R (1 - 0.001) = 0.999 " \
           "are refused" in result.stderr, result.stderr
    assert "(atom lines 109 and 522). The centres coincide" in result.stderr, result.stderr
    assert "no output written" in result.stderr and not list(tmp_path.glob("out*"))
    result = run("-q", "-o", tmp_path / "out", with_copy("near.dump", repr(float(copy[2]) + 1e-9)))
    assert result.returncode == 2, result.stderr
    assert f"near.{family}1e-09, 2R = 1)" in result.stderr, result.stderr


def test_a_refused_run_writes_no_file(tmp_path):
    good = write(tmp_path / "good.dump", GOOD)
    bad = write(tmp_path / "bad.dump", BAD["non_numeric"][0])
    result = run("--json", "--pores", "--frame-hist", "--p0", 100, "-o", tmp_path / "out", good, bad)
    assert result.returncode == 2
    assert "no output written" in result.stderr
    assert not list(tmp_path.glob("out*")), list(tmp_path.glob("out*"))


def test_an_output_name_taken_by_a_directory_writes_no_file(tmp_path):
    """x.hist.csv is a directory: the run is refused before any output is renamed into place
    (x.frames.csv was left behind, after "no output written")."""
    (tmp_path / "x.hist.csv").mkdir()
    good = write(tmp_path / "good.dump", GOOD)
    result = run("-q", "-o", tmp_path / "x", good)
    assert result.returncode == 2
    assert f"cannot write '{tmp_path / 'x.hist.csv'}': a directory of that name exists" \
        in result.stderr and "no output written" in result.stderr, result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["good.dump", "x.hist.csv"]


def test_closing_line_lists_every_file_written(tmp_path):
    prefix = tmp_path / "all"
    result = run("--json", "--pores", "--frame-hist", "--p0", 1000, "-o", prefix, DATA)
    assert result.returncode == 0, result.stderr
    closing = result.stderr.strip().splitlines()[-1]
    suffixes = ["frames.csv", "frame_hist.csv", "pores.csv", "hist.csv", "p0.csv", "json"]
    written = sorted(p.name for p in tmp_path.iterdir())
    assert written == sorted(f"all.{s}" for s in suffixes)
    for s in suffixes:
        assert f"{prefix}.{s}" in closing, closing
    assert "wrote" in closing


def test_help_doc_and_config_tell_one_story():
    """The defaults quoted by --help and by the table of doc/tapmc-pores.rst are those of
    pores_config.h, and both cite P0 the same way (eq. 8, and the form replacing eq. 9)."""
    source = os.environ.get("TAPMC_SOURCE_DIR", ".")
    config = open(os.path.join(source, "tools/pores/include/tapmc_pores/pores_config.h")).read()
    doc = open(os.path.join(source, "doc/tapmc-pores.rst")).read()
    values = {name: float(value) for name, value in
              re.findall(r"constexpr (?:double|int|std::size_t) (k\w+) = ([0-9.e+-]+);", config)}
    assert len(values) >= 14
    help_text = run("--help").stdout
    quoted = {"--wall-gap": "kDefaultWallGap", "--surface-gap": "kDefaultSurfaceGap",
              "--overlap-tol": "kOverlapTolerance", "--merge-tol": "kMergeTolerance",
              "--padding": "kPaddingOverRadius", "--bins": "kDefaultBins", "--xi-max": "kDefaultXiMax",
              "--sigma-max": "kDefaultSigmaMax"}
    for option, name in quoted.items():
        line = next(l for l in help_text.splitlines() if l.strip().startswith(option))
        assert float(re.search(r"\(default ([0-9.e+-]+)", line).group(1)) == values[name], line
    table = doc[doc.index("Tolerances and defaults ("):doc.index("A note on perturbed lattices")]
    for name, value in values.items():
        row = re.search(rf"``{name}``[^\n]*?\s{{2,}}([0-9.e+-]+)", table)
        if name in ("kDefaultBins", "kDefaultSigmaBins"):  # on the row of their range
            continue
        assert row, f"{name} missing from the table of doc/tapmc-pores.rst"
        assert float(row.group(1)) == value, (name, row.group(0))
    assert "eq. 8-9" not in help_text and "eq. 8-9" not in doc
    assert "replaces the printed eq. 9" in help_text and "replaces eq. 9" in doc
