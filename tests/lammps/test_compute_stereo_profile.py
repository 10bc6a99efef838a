# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# compute stereo/profile run as lmp_tapmc child processes: thermo / print / fix ave/time output on
# an FCC lattice, identical numbers on 1 and 2 MPI ranks, and every bad argument rejected.
import math
import os
import re

import numpy as np
import pytest

from lmprun import ave_time_rows, fcc_lattice, printed, run_lammps

FCC = math.pi / (3.0 * math.sqrt(2.0))


VECTOR_PRINT = 'print "VEC ' + " ".join("$(c_{id}[%d]:%%.17g)" % i for i in range(1, 8)) + '"\n'


def test_thermo_print_and_time_average_on_fcc():
    script = fcc_lattice() + """
compute phi all stereo/profile floor 2.0 bulk 4.0 column 2.0
compute pz all stereo/profile planes 2.0 10.0 4
thermo_style custom step c_phi[1] c_phi[3]
thermo_modify format float %.15g
fix av all ave/time 1 1 1 c_pz[*] mode vector file prof.dat format " %.17g"
run 0
""" + VECTOR_PRINT.format(id="phi")
    rc, out, wd = run_lammps(script)
    assert rc == 0, out[-2000:]
    # thermo line: step, Phi_b, <Z> (layers at z = 0 .. 15 above a floor at 2)
    m = re.search(r"^\s+0\s+(\S+)\s+(\S+)\s*$", out, re.M)
    assert m, out[-2000:]
    assert float(m.group(1)) == pytest.approx(FCC, abs=1e-13)
    assert float(m.group(2)) == pytest.approx(5.5, abs=1e-13)
    vec = printed(out, "VEC")
    assert vec[0] == pytest.approx(FCC, abs=1e-14)
    # h_s: columns one cell wide each hold two top-layer spheres: top layer + R
    assert vec[6] == pytest.approx(15.0 + math.sqrt(0.5), abs=1e-12)
    assert vec[3] == pytest.approx(2.0 + 0.9 * (vec[6] - 2.0), abs=1e-12)  # z_top
    rows = ave_time_rows(f"{wd}/prof.dat")
    assert rows.shape == (4, 4)
    np.testing.assert_allclose(rows[:, 1], [3.0, 5.0, 7.0, 9.0], atol=1e-14)
    np.testing.assert_allclose(rows[:, 2], math.pi / 4.0, atol=1e-13)  # cuts through layers
    np.testing.assert_allclose(rows[:, 3], FCC, atol=1e-13)  # bins of one period


PERTURBED = """
displace_atoms all random 0.15 0.15 0.15 4711 units box
region low block INF INF INF INF INF 9.0 units box
group low region low
set group low diameter 1.2
compute phi all stereo/profile floor 0.5 lateral 1.5
compute low low stereo/profile floor 0.5 top_fraction 0.8 lateral 2.0
compute px all stereo/profile axis x planes -0.5 8.5 30
compute pz low stereo/profile planes 0.0 16.0 40
thermo_style custom step c_phi[1] c_phi[2] c_phi[3] c_phi[4] c_phi[5] c_phi[6] c_phi[7] c_low[2]
fix ax all ave/time 1 1 1 c_px[*] mode vector file px.dat format " %.17g"
fix az all ave/time 1 1 1 c_pz[*] mode vector file pz.dat format " %.17g"
run 0
"""


@pytest.mark.parametrize("boundary", ["p p f", "f f f"])
def test_same_numbers_on_one_and_two_ranks(boundary):
    body = fcc_lattice(boundary, "0.1 3.9 0.1 3.9 0.1 7.9") + PERTURBED
    tail = VECTOR_PRINT.format(id="phi") + VECTOR_PRINT.format(id="low").replace("VEC", "LOW")
    results = []
    for nprocs, grid in [(1, "* * *"), (2, "2 1 1"), (2, "1 1 2")]:
        rc, out, wd = run_lammps(f"processors {grid}\n" + body + tail, nprocs=nprocs)
        assert rc == 0, out[-2000:]
        results.append((printed(out, "VEC"), printed(out, "LOW"), ave_time_rows(f"{wd}/px.dat"),
                        ave_time_rows(f"{wd}/pz.dat")))
    serial = results[0]
    assert np.all(serial[0][[0, 1, 4, 5]] > 0.1), serial[0]  # every zone holds spheres
    assert np.all(serial[1][[0, 1, 4, 5]] > 0.1), serial[1]
    assert serial[2][:, 3].max() > 0.3 and serial[3][:, 3].max() > 0.3
    for parallel in results[1:]:
        for a, b in zip(serial, parallel):
            np.testing.assert_allclose(b, a, rtol=1e-12, atol=1e-14)


BAD = [
    ("compute s all stereo/profile radius 0",
     "compute stereo/profile: radius = 0 is outside the allowed range (0, +inf)"),
    ("compute s all stereo/profile radius -1.5",
     "compute stereo/profile: radius = -1.5 is outside the allowed range (0, +inf)"),
    ("compute s all stereo/profile planes 0 10 0",
     "planes n = 0 is outside the allowed range [1, 2147483647] (an integer)"),
    ("compute s all stereo/profile planes 0 10 4294967298",  # was 2 planes (atoi wrapped)
     "planes n = 4294967298 is outside the allowed range [1, 2147483647] (an integer)"),
    ("compute s all stereo/profile planes 5 5 10",
     "planes lo = 5 is outside the allowed range (-inf, hi) = (-inf, 5)"),
    ("compute s all stereo/profile planes 6 5 10",
     "planes lo = 6 is outside the allowed range (-inf, hi) = (-inf, 5)"),
    ("compute s all stereo/profile bogus 3", "unknown keyword 'bogus'"),
    ("compute s all stereo/profile window 5 3",
     "window za = 5 is outside the allowed range (-inf, zb) = (-inf, 3)"),
    ("compute s all stereo/profile window 4 4",
     "window za = 4 is outside the allowed range (-inf, zb) = (-inf, 4)"),
    ("compute s all stereo/profile top_fraction 0",
     "top_fraction = 0 is outside the allowed range (0, 1]"),
    ("compute s all stereo/profile top_fraction 1.5",
     "top_fraction = 1.5 is outside the allowed range (0, 1]"),
    ("compute s all stereo/profile top_fraction -0.2",
     "top_fraction = -0.2 is outside the allowed range (0, 1]"),
    ("compute s all stereo/profile axis w", "axis = w must be x, y or z"),
    ("compute s all stereo/profile lateral 0",
     "lateral = 0 is outside the allowed range (0, +inf)"),
    ("compute s all stereo/profile bulk -1", "bulk = -1 is outside the allowed range (0, +inf)"),
    ("compute s all stereo/profile column 0", "column = 0 is outside the allowed range (0, +inf)"),
    ("compute s all stereo/profile wall_factor 0",
     "wall_factor = 0 is outside the allowed range (0, +inf)"),
    ("compute s all stereo/profile wall_band -2",
     "wall_band = -2 is outside the allowed range (0, +inf)"),
    ("compute s all stereo/profile floor", "keyword 'floor' needs 1 value(s)"),
    ("compute s all stereo/profile planes 0 1", "keyword 'planes' needs 3 value(s)"),
    ("compute s all stereo/profile planes 0 1 x", "x"),
    ("compute s all stereo/profile floor 30", "default planes 30 .. 20 are empty"),
    ("set group all diameter 0.0\ncompute s all stereo/profile\nrun 0",
     "per-atom radius must be > 0"),
]


@pytest.mark.parametrize("body,message", BAD)
def test_bad_argument(body, message):
    rc, out, _ = run_lammps(fcc_lattice() + body)
    assert rc != 0
    assert "ERROR" in out and message in out, out[-1500:]


def test_missing_radius_with_atom_style_atomic():
    script = fcc_lattice().replace("atom_style sphere", "atom_style atomic").replace(
        "set group all diameter 1.4142135623730951\nset group all density 1.0\n", "mass 1 1.0\n")
    rc, out, _ = run_lammps(script + "compute s all stereo/profile\n")
    assert rc != 0 and "radius keyword required: atom style atomic" in out, out[-1500:]
    # and with the radius keyword it runs
    rc, out, _ = run_lammps(script + "compute s all stereo/profile floor 2.0 bulk 4.0 "
                            "radius 0.70710678118654752\nthermo_style custom step c_s[1]\nrun 0\n"
                            + VECTOR_PRINT.format(id="s"))
    assert rc == 0, out[-1500:]
    assert printed(out, "VEC")[0] == pytest.approx(FCC, abs=1e-14)


def test_periodic_z_is_rejected():
    rc, out, _ = run_lammps(fcc_lattice("p p p") + "compute s all stereo/profile\n")
    assert rc != 0 and "z boundary is periodic" in out, out[-1500:]


def test_doc_examples_run():
    """The Examples block of doc/compute_stereo_profile.rst runs as written."""
    doc = os.path.join(os.environ.get("TAPMC_SOURCE_DIR", "../.."), "doc",
                       "compute_stereo_profile.rst")
    with open(doc) as f:
        text = f.read()
    block = text.split("Examples\n\"\"\"\"\"\"\"\"")[1].split("Description\n")[0]
    # the container examples need a tube: test_compute_stereo_profile_container.py runs them
    block = block.split(".. snippet: skip")[0]
    commands = [l.strip() for l in block.splitlines() if l.startswith("   ") and l.strip()]
    assert len(commands) >= 5 and all("stereo/profile" in c or "c_" in c for c in commands)
    rc, out, wd = run_lammps(fcc_lattice() + "\n".join(commands) + "\nrun 0\n")
    assert rc == 0, out[-1500:]
    for name in ("profile_z.dat", "profile_x.dat"):
        assert os.path.getsize(os.path.join(wd, name)) > 0


def test_a_profile_nobody_reads_allocates_nothing():
    """The array is made when first computed: a compute of the largest allowed planes n
    (2^31 - 1 rows, 51 GB) whose vector alone is read runs (its constructor allocated and
    zeroed the array: 'Failed to allocate 51539607528 bytes'); one of 4 planes read by fix
    ave/time and thermo is made and filled."""
    script = fcc_lattice() + """compute big all stereo/profile planes 0.0 8.0 2147483647
compute p all stereo/profile planes 0.0 8.0 4
fix az all ave/time 1 1 1 c_p[*] mode vector file p.dat format " %.17g"
thermo_style custom step c_big[1] c_p[1][2]
run 0
"""
    rc, out, wd = run_lammps(script)
    assert rc == 0, out[-2000:]
    rows = ave_time_rows(os.path.join(wd, "p.dat"))
    np.testing.assert_array_equal(rows[:, 1], [1, 3, 5, 7])
    assert np.all(rows[:, 2] > 0)


@pytest.mark.parametrize("nprocs", [1, 2])
def test_empty_group_gives_zero_fractions(nprocs):
    """An empty group is no error: every fraction and <Z> are 0, z_top = h_s = the floor, the
    profile rows keep their plane positions (doc page, "Window top"); serial and under mpirun."""
    script = fcc_lattice() + """group none empty
compute s none stereo/profile floor 1.5
compute r none stereo/profile floor 0.5 radius 0.7
compute p none stereo/profile planes 0.0 8.0 4
compute q none stereo/profile axis x planes 0.0 8.0 4
fix az all ave/time 1 1 1 c_p[*] c_q[*] mode vector file p.dat format " %.17g"
thermo_style custom step c_s[1] c_s[3] c_r[1]
run 0
""" + VECTOR_PRINT.format(id="s") + VECTOR_PRINT.format(id="r").replace("VEC", "RAD")
    rc, out, wd = run_lammps(script, nprocs=nprocs)
    assert rc == 0, out[-2000:]
    assert "Traceback" not in out and "terminate called" not in out
    np.testing.assert_array_equal(printed(out, "VEC"), [0, 0, 0, 1.5, 0, 0, 1.5])
    np.testing.assert_array_equal(printed(out, "RAD"), [0, 0, 0, 0.5, 0, 0, 0.5])
    rows = ave_time_rows(os.path.join(wd, "p.dat"))
    np.testing.assert_array_equal(rows[:, 1], [1, 3, 5, 7])
    np.testing.assert_array_equal(rows[:, [2, 3, 5, 6]], 0.0)


# One layer of spheres on the floor: the default window [floor + 2R, window top] is empty.
ONE_LAYER = """units lj
atom_style sphere
boundary p p fm
region box block 0 6 0 6 0 4
create_box 1 box
lattice sc 1.0 origin 0.5 0.5 0.5
region layer block 0 6 0 6 0 1 units box
create_atoms 1 region layer
set group all diameter 1.0
"""


@pytest.mark.parametrize("nprocs", [1, 2])
def test_a_bed_of_one_layer_has_no_zone_means(nprocs):
    """One layer on the floor: the default window [floor + 2R, window top] is empty, and the
    lateral and central means (entries 5, 6) read 0, as measurements. They are NaN, with one
    warning naming the window; the other entries are measured."""
    script = ONE_LAYER + """compute phi all stereo/profile floor 0.0
thermo_style custom step c_phi[1] c_phi[5] c_phi[6]
run 1
run 1
""" + VECTOR_PRINT.format(id="phi")
    rc, out, _ = run_lammps(script, nprocs=nprocs)
    assert rc == 0, out[-2000:]
    values = printed(out, "VEC")
    assert math.isnan(values[4]) and math.isnan(values[5]), values
    assert np.all(np.isfinite(np.delete(values, [4, 5]))) and values[0] > 0.1, values
    assert out.count("compute stereo/profile phi: empty vertical window: its top z = 0.9 is not "
                     "above its bottom z = 1 (a bed of about one layer") == 1, out[-3000:]


def test_a_bed_of_one_layer_has_no_vertical_profile():
    """The profile of vertical cuts over the same empty window read 0 in every row, as an empty
    layer would: its Phi and bin means are NaN, with one warning naming the window; the plane
    positions and a z profile of the same bed are measured."""
    script = ONE_LAYER + """compute px all stereo/profile floor 0.0 axis x planes 0.0 6.0 3
compute pz all stereo/profile floor 0.0 planes 0.0 1.0 3
fix ax all ave/time 1 1 1 c_px[*] c_pz[*] mode vector file p.dat format " %.17g"
run 2
"""
    rc, out, wd = run_lammps(script)
    assert rc == 0, out[-2000:]
    rows = ave_time_rows(os.path.join(wd, "p.dat"))  # index, then x: 3 columns, z: 3 columns
    np.testing.assert_array_equal(rows[:, 1], [1, 3, 5])
    assert np.isnan(rows[:, [2, 3]]).all(), rows
    assert np.isfinite(rows[:, 4:]).all() and (rows[:, 6] > 0.3).all(), rows
    assert out.count("compute stereo/profile px: empty vertical window: its top z = 0.9 is not "
                     "above its bottom z = 1 (a bed of about one layer, below floor + 2R), so "
                     "the x profile's Phi and bin means (array columns 2 and 3) are NaN") == 1, \
        out[-3000:]


@pytest.mark.parametrize("nprocs", [1, 2])
def test_empty_central_zone_is_nan_with_one_warning(nprocs):
    """Lateral zones that reach the middle of the box (lateral >= half the box width, as the
    default 7R in the paper inputs' 12R reference box) leave no central zone: vector entry 6 is
    NaN (printed nan), not a 0 that reads as a measurement, and each such compute warns once
    (over every invocation and run), naming itself, the zone width, the box width and what
    would give a central zone. The lateral mean is then the mean over the whole width; a
    compute with a central zone is unchanged and silent."""
    script = fcc_lattice() + """
compute narrow all stereo/profile floor 0.5 axis x lateral 4.5 window 2.0 10.0
compute half all stereo/profile floor 0.5 lateral 4.0 window 2.0 10.0
compute wide all stereo/profile floor 0.5 axis x lateral 1.5 window 2.0 10.0
thermo_style custom step c_narrow[5] c_narrow[6] c_half[6] c_wide[6]
thermo 1
run 2
run 1
""" + VECTOR_PRINT.format(id="narrow") + VECTOR_PRINT.format(id="wide").replace("VEC", "WIDE") \
        + VECTOR_PRINT.format(id="half").replace("VEC", "HALF")
    rc, out, _ = run_lammps(script, nprocs=nprocs)
    assert rc == 0, out[-2000:]
    narrow, wide, half = printed(out, "VEC"), printed(out, "WIDE"), printed(out, "HALF")
    assert math.isnan(narrow[5]) and math.isnan(half[5]), (narrow, half)
    vec_line = [l for l in out.splitlines() if l.startswith("VEC ")][-1]
    assert vec_line.split()[6] == "nan", vec_line
    assert np.all(np.isfinite(np.delete(narrow, 5))) and np.all(np.isfinite(wide))
    # whole-width mean = lateral (2 x 1.5) and central (5) means of the same window, weighted
    assert narrow[4] == pytest.approx((3.0 * wide[4] + 5.0 * wide[5]) / 8.0, rel=1e-12)
    assert wide[5] > 0.3 and narrow[[0, 1, 2, 3, 6]] == pytest.approx(wide[[0, 1, 2, 3, 6]])
    warning = ("WARNING: compute stereo/profile {}: no central zone: the lateral zones "
               "(lateral = {} from both x faces) cover the whole box width 8 along x, so the "
               "central mean (vector entry 6) is NaN; a central zone needs lateral < 4 (half "
               "the box width) or a box wider than {} (2 lateral) along x")
    assert out.count(warning.format("narrow", 4.5, 9)) == 1, out[-3000:]
    assert out.count(warning.format("half", 4, 8)) == 1, out[-3000:]
    assert "compute stereo/profile wide" not in out
    assert out.count("no central zone") == 2, out[-3000:]
