# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# create_packing through lmp_tapmc: the same packing on 1, 2 and 4 ranks (also decomposed in z,
# and beyond one broadcast piece), every atom once, no overlaps, walls / regions /
# shrink-wrapped tops, and bad input (also a deposition that fails on rank 0 of several).
import os
import re
import resource
import subprocess
import tempfile

import numpy as np
import pytest

from lmprun import LMP, min_gap, read_dump, run_lammps

# Relative overlap tolerance of the whole package (tapmc_defaults.h, kContactTolerance).
CONTACT_TOL = 1e-10

HEADER = """units lj
atom_style sphere
boundary {boundary}
region box block 0 {L} 0 {L} 0 {H}
create_box {ntypes} box
"""

DUMP = """dump d all custom 1 packing.dump id type x y z radius mass
dump_modify d sort id format float %.17g
run 0
"""


def packing_script(n=800, L=16, H=40, boundary="p p fm", args="", pre="", ntypes=1):
    return (HEADER.format(boundary=boundary, L=L, H=H, ntypes=ntypes) + pre +
            f"create_packing {n} 1 1.0 4928 {args}\n" + DUMP)


def run_packing(script, nprocs=1):
    rc, out, wd = run_lammps(script, nprocs=nprocs)
    assert rc == 0, out
    step, box, bounds, cols = read_dump(os.path.join(wd, "packing.dump"))[-1]
    return out, box, bounds, cols


def check_geometry(cols, box, periodic_xy, floor, radius_range=(1.0, 1.0), walls=None):
    xyz = np.column_stack([cols["x"], cols["y"], cols["z"]])
    r = cols["radius"]
    assert r.min() >= radius_range[0] - 1e-12 and r.max() <= radius_range[1] + 1e-12
    gap, i, j = min_gap(xyz, r, box, periodic_xy, floor=floor)
    assert gap >= -CONTACT_TOL * 2 * r.max(), (gap, i, j)
    if walls is not None:
        for dim, (lo, hi) in walls.items():
            assert (xyz[:, dim] - r >= lo - 1e-9).all() and (xyz[:, dim] + r <= hi + 1e-9).all()
    # rmass = density * 4/3 pi r^3 with the default density 1
    np.testing.assert_allclose(cols["mass"], 4.0 / 3.0 * np.pi * r ** 3, rtol=1e-12)


@pytest.mark.parametrize("nprocs,processors", [(2, ""), (4, ""), (4, "processors 1 1 4\n"),
                                               (4, "processors 2 2 1\n")])
def test_same_packing_on_1_2_4_ranks(nprocs, processors):
    _, _, _, serial = run_packing(packing_script())
    _, _, _, parallel = run_packing(processors + packing_script(), nprocs=nprocs)
    assert len(parallel["id"]) == 800
    np.testing.assert_array_equal(parallel["id"], np.arange(1, 801))
    for c in ("x", "y", "z", "radius", "type"):
        np.testing.assert_array_equal(parallel[c], serial[c])


# Rank 0 deposits and broadcasts pieces of 65536 spheres (kPackingBroadcastSpheres): 70000
# spheres take two pieces, the second one partial.
def test_packing_larger_than_one_broadcast_piece_is_the_same_on_2_ranks():
    script = packing_script(n=70000, L=60, H=40, args="floor 0.0").replace(
        "create_packing 70000 1 1.0", "create_packing 70000 1 0.5")
    _, _, _, serial = run_packing(script)
    _, _, _, parallel = run_packing(script, nprocs=2)
    np.testing.assert_array_equal(parallel["id"], np.arange(1, 70001))
    for c in ("x", "y", "z", "radius"):
        np.testing.assert_array_equal(parallel[c], serial[c])


def test_deposition_failing_on_rank_0_stops_every_rank_with_its_message():
    # The room check passes (random close packing would fit), the deposition does not.
    rc, out, _ = run_lammps(HEADER.format(boundary="p p ff", L=16, H=10, ntypes=1) +
                            "create_packing 380 1 1.0 5", nprocs=2, timeout=120)
    assert rc != 0
    # the digits beyond ~1e-13 depend on the build's floating-point contractions (FMA with
    # -march=native, none in the portable build)
    message = re.compile(r"rests with its top at z = 10\.03770550818\d*, above the top limit "
                         r"z_top = 10:")
    assert len(message.findall(out)) == 1, out


def test_periodic_packing_is_valid_and_reports_phi():
    out, box, bounds, cols = run_packing(packing_script(n=1024, L=16, H=60))
    assert len(cols["id"]) == 1024
    np.testing.assert_array_equal(cols["id"], np.arange(1, 1025))
    check_geometry(cols, box, (True, True), floor=0.0)
    assert "Created 1024 spheres by sequential deposition" in out
    phi = float(out.split("interior volume fraction")[1].split()[0])
    assert 0.55 < phi < 0.62, out


def printed_measures(out):
    """Phi_b, <Phi^c>, <Z> and h_s from create_packing's line of compute stereo/profile's
    measures."""
    line = next(ln for ln in out.splitlines()
                if ln.startswith("  compute stereo/profile (defaults): Phi_b "))
    words = line.replace(",", "").split()
    return [float(words[words.index(name) + 1]) for name in ("Phi_b", "<Phi^c>", "<Z>", "h_s")]


STEREO_AFTER = """compute phi all stereo/profile floor {floor}
thermo_style custom step c_phi[1] c_phi[2] c_phi[3] c_phi[4]
thermo_modify format float %.10f
run 0
"""


@pytest.mark.parametrize("boundary,args,floor", [
    ("p p fm", "floor 0.0", 0.0),                          # the README's quick start set-up
    ("f f fm", "floor 1.5 dispersity 0.2", 1.5),           # walls, mixed radii, raised floor
])
def test_printed_packing_fractions_are_compute_stereo_profiles(boundary, args, floor):
    # create_packing prints Phi_b, <Phi^c>, <Z> and h_s with compute stereo/profile's names,
    # definitions and defaults: a compute on the new packing reports the same numbers (the
    # quick-start packing: Phi_b 0.5429, where the line used to read "bulk packing fraction
    # 0.5830", a slab far from the floor, under a name that read as Phi_b).
    script = (HEADER.format(boundary=boundary, L=16, H=40, ntypes=1) +
              f"create_packing 4096 1 0.5 4928 {args}\n" + STEREO_AFTER.format(floor=floor))
    rc, out, _ = run_lammps(script)
    assert rc == 0, out
    lines = out.splitlines()
    header = next(k for k, ln in enumerate(lines) if ln.split()[:1] == ["Step"])
    phi_b, phi_c, mean_z, top = (float(v) for v in lines[header + 1].split()[1:])
    printed = printed_measures(out)
    np.testing.assert_allclose(printed[:3], [phi_b, phi_c, mean_z], atol=6e-5)
    # c_phi[4] is z_top = floor + 0.9 (h_s - floor)
    np.testing.assert_allclose(floor + 0.9 * (printed[3] - floor), top, rtol=1e-3)
    assert "bulk packing fraction" not in out
    interior = next(ln for ln in lines if ln.startswith("  interior volume fraction "))
    assert "6R above the floor to 6R below twice the mean centre height" in interior


def test_printed_mean_height_keeps_its_digits_in_si_units():
    """A bed of 5-micron spheres in SI units: <Z> printed 0.0000 (four decimals of metres);
    it keeps four significant digits there, as h_s does, and equals the compute's."""
    script = ("units si\natom_style sphere\nboundary p p fm\n"
              "region box block 0 6e-5 0 6e-5 0 3e-4\ncreate_box 1 box\n"
              "create_packing 300 1 5e-6 4928 floor 0.0\n" + STEREO_AFTER.format(floor=0.0)
              .replace("%.10f", "%.10g"))
    rc, out, _ = run_lammps(script)
    assert rc == 0, out
    lines = out.splitlines()
    header = next(k for k, ln in enumerate(lines) if ln.split()[:1] == ["Step"])
    mean_z = float(lines[header + 1].split()[3])
    assert 1e-5 < mean_z < 1e-4
    assert printed_measures(out)[2] == pytest.approx(mean_z, rel=1e-3)


def test_walls_in_nonperiodic_box():
    out, box, bounds, cols = run_packing(packing_script(boundary="f f fm"), nprocs=2)
    assert len(cols["id"]) == 800
    assert "sides: x walls, y walls" in out
    check_geometry(cols, box, (False, False), floor=0.0, walls={0: (0, 16), 1: (0, 16)})


def test_walls_keyword_in_periodic_box():
    out, box, bounds, cols = run_packing(packing_script(args="walls x"))
    assert "sides: x walls, y periodic" in out
    check_geometry(cols, box, (False, True), floor=0.0, walls={0: (0, 16)})
    # the last 'walls' holds, as the last of any keyword (they accumulated: x y walls)
    out, _, _, _ = run_packing(packing_script(n=50, args="walls x y walls none"))
    assert "sides: x periodic, y periodic" in out
    out, _, _, _ = run_packing(packing_script(n=50, args="walls y walls x"))
    assert "sides: x walls, y periodic" in out


def test_column_one_diameter_wide_is_a_straight_stack_at_rest():
    """Four walls one diameter apart: each sphere lands on top of the one below, where every
    way off enters a wall: wedged at rest (z = 1, 3, ..., 19), with no step-cap warning."""
    out, box, bounds, cols = run_packing(packing_script(n=10, L=2, boundary="f f fm"))
    np.testing.assert_allclose(np.sort(cols["z"]), 1.0 + 2.0 * np.arange(10), atol=1e-9)
    np.testing.assert_allclose(cols["x"], 1.0, atol=1e-12)
    np.testing.assert_allclose(cols["y"], 1.0, atol=1e-12)
    assert "unstable equilibria left 0, wedged at rest 9, re-drops 0, unresolved 0" in out
    assert "stability not proven" not in out
    check_geometry(cols, box, (False, False), floor=0.0, walls={0: (0, 2), 1: (0, 2)})


def test_region_sets_extent_floor_and_walls():
    pre = "region slab block 2 14 INF INF 1.5 INF\n"
    out, box, bounds, cols = run_packing(packing_script(n=400, args="region slab", pre=pre),
                                         nprocs=2)
    assert "sides: x walls, y periodic" in out
    check_geometry(cols, box, (False, True), floor=1.5, walls={0: (2, 14)})


def test_floor_keyword():
    out, box, bounds, cols = run_packing(packing_script(n=300, args="floor 2.5"))
    assert cols["z"].min() >= 3.5 - 1e-12
    check_geometry(cols, box, (True, True), floor=2.5)


def test_shrink_wrapped_top_grows_the_box_on_ranks_split_in_z():
    script = "processors 1 1 2\n" + packing_script(n=800, H=3, boundary="p p fs")
    out, box, bounds, cols = run_packing(script, nprocs=2)
    assert len(cols["id"]) == 800
    assert box[2, 1] >= cols["z"].max()
    _, _, _, serial = run_packing(packing_script(n=800, H=3, boundary="p p fs"))
    np.testing.assert_array_equal(cols["z"], serial["z"])


@pytest.mark.parametrize("grows", [True, False])
def test_a_shrink_wrapped_floor_stays_where_the_packing_was_deposited(grows):
    """boundary p p ss: create_box pads the lower z face once; growing the box's top for the
    packing padded it again, so the box's lower bound (the floor every style defaults to) sat
    below the floor the spheres were deposited on (<Z> off by that gap). It stays put, whether
    the top grows (a box 2 high) or not (40 high)."""
    script = f"""units lj
atom_style sphere
boundary p p ss
region box block 0 8 0 8 0 {2 if grows else 40}
create_box 1 box
create_packing 300 1 0.5 21
print "ZLO $(zlo:%.17g) ZHI $(zhi:%.17g)"
"""
    rc, out, _ = run_lammps(script)
    assert rc == 0, out
    floor = float(re.search(r"floor z = (\S+)", out).group(1))
    zlo, zhi = (float(v) for v in re.search(r"ZLO (\S+) ZHI (\S+)", out).groups())
    assert floor < 0.0 and zlo == pytest.approx(floor, abs=5e-5 * abs(floor) + 1e-12), out
    assert (2.5 < zhi < 39.0) == grows   # grown to hold the packing, or left at 40


def test_polydisperse_and_existing_atoms():
    pre = "create_atoms 1 single 8 8 38\nset atom 1 diameter 2.0\n"
    out, box, bounds, cols = run_packing(packing_script(n=500, args="dispersity 0.2", pre=pre),
                                         nprocs=4)
    assert len(cols["id"]) == 501
    np.testing.assert_array_equal(cols["id"], np.arange(1, 502))
    new = {c: v[1:] for c, v in cols.items()}  # tag 1 is the pre-existing atom (far above)
    check_geometry(new, box, (True, True), floor=0.0, radius_range=(0.8, 1.2))
    assert np.ptp(new["radius"]) > 0.2


BAD_CASES = [
    ("create_packing 0 1 1.0 5",
     "N = 0 is outside the allowed range [1, 2^31 - 2] (a number of spheres)"),
    ("create_packing -5 1 1.0 5",
     "N = -5 is outside the allowed range [1, 2^31 - 2] (a number of spheres)"),
    ("create_packing 10 1 0.0 5",
     "R = 0 is outside the allowed range (0, +inf) (the mean sphere radius)"),
    ("create_packing 10 1 -1 5",
     "R = -1 is outside the allowed range (0, +inf) (the mean sphere radius)"),
    ("create_packing 10 2 1.0 5",
     "create_packing: type = 2 is outside the allowed range [1, 1] (the atom types of the box)"),
    ("create_packing 10 4294967298 1.0 5",  # was type 2 (atoi wrapped)
     "create_packing: type = 4294967298 is outside the allowed range [1, 1] (the atom types of "
     "the box)"),
    ("create_packing 10 1 1.0 0", "create_packing: seed = 0 is outside the allowed range "
     "[1, 9223372036854775807] (an integer)"),
    ("create_packing 10 1 1.0", "expected 'create_packing N type R seed"),
    ("create_packing 10 1 1.0 5 region nothere", "region ID 'nothere' does not exist"),
    ("create_packing 10 1 1.0 5 bogus 1", "unknown keyword 'bogus'"),
    ("create_packing 10 1 1.0 5 dispersity 1.5",
     "dispersity = 1.5 is outside the allowed range [0, 1)"),
    ("create_packing 10 1 1.0 5 density 0", "density = 0 is outside the allowed range (0, +inf)"),
    ("create_packing 10 1 1.0 5 walls", "walls needs 'x', 'y', 'x y' or 'none'"),
    ("create_packing 10 1 1.0 5 floor -1", "floor = -1 is below the box bottom"),
    ("create_packing 10 1 20.0 5", "less than one sphere diameter"),
    ("region thin block 0 16 0 1 0 10\ncreate_packing 10 1 1.0 5 region thin",
     "region 'thin' is 1 wide in y, less than one sphere diameter"),
    ("region low block INF INF INF INF 0 3\ncreate_packing 2000 1 1.0 5 region low",
     "region 'low' cannot hold N = 2000 spheres"),
    # Passes the volume estimate, but the deposit's top ends above the region's top.
    ("region low block INF INF INF INF 0 4\ncreate_packing 120 1 1.0 5 region low",
     "the domain cannot hold the spheres"),
]


@pytest.mark.parametrize("body,message", BAD_CASES)
def test_bad_argument(body, message):
    rc, out, _ = run_lammps(HEADER.format(boundary="p p fm", L=16, H=40, ntypes=1) + body)
    assert rc != 0, out
    assert "ERROR" in out and message in out, out


def test_bad_periodic_z():
    rc, out, _ = run_lammps(HEADER.format(boundary="p p p", L=16, H=40, ntypes=1) +
                            "create_packing 10 1 1.0 5")
    assert rc != 0 and "z boundary is periodic" in out, out


def test_a_region_outside_the_box_is_named():
    # it read "region 'r' is -1 wide in x" (the clipped width)
    rc, out, _ = run_lammps(HEADER.format(boundary="p p fm", L=16, H=40, ntypes=1) +
                            "region r block 17 20 INF INF INF INF\n"
                            "create_packing 10 1 1.0 5 region r")
    assert rc != 0 and "region 'r' lies outside the box in x (region 17 to 20, box 0 to 16)" \
        in out, out


def test_bad_walls_none_without_periodic_sides():
    rc, out, _ = run_lammps(HEADER.format(boundary="f p fm", L=16, H=40, ntypes=1) +
                            "create_packing 10 1 1.0 5 walls none")
    assert rc != 0 and "the x direction needs walls" in out, out


def test_bad_fixed_top_too_low():
    rc, out, _ = run_lammps(HEADER.format(boundary="p p ff", L=16, H=4, ntypes=1) +
                            "create_packing 120 1 1.0 5")
    assert rc != 0 and "cannot hold" in out and "fixed box top" in out, out


def test_bad_triclinic():
    script = HEADER.format(boundary="p p fm", L=16, H=40, ntypes=1).replace(
        "region box block 0 16 0 16 0 40", "region box prism 0 16 0 16 0 40 1 0 0")
    rc, out, _ = run_lammps(script + "create_packing 10 1 1.0 5")
    assert rc != 0 and "triclinic" in out, out


def test_bad_atom_style():
    script = HEADER.format(boundary="p p fm", L=16, H=40, ntypes=1).replace(
        "atom_style sphere", "atom_style atomic")
    rc, out, _ = run_lammps(script + "create_packing 10 1 1.0 5")
    assert rc != 0 and "use atom_style sphere" in out, out


def test_bad_no_box():
    rc, out, _ = run_lammps("units lj\natom_style sphere\ncreate_packing 10 1 1.0 5\n")
    assert rc != 0 and "no simulation box yet" in out, out


def test_example_runs_and_matches_its_log():
    source = os.environ.get("TAPMC_SOURCE_DIR",
                            os.path.join(os.path.dirname(__file__), "..", ".."))
    example = os.path.join(source, "examples", "deposition")
    with open(os.path.join(example, "in.deposition")) as f:
        rc, out, _ = run_lammps(f.read())
    assert rc == 0, out
    logs = [n for n in os.listdir(example) if n.startswith("log.") and
            n.endswith(".deposition.g++.1")]
    assert len(logs) == 1, logs
    with open(os.path.join(example, logs[0])) as f:
        log = f.read()

    def phi_lines(text):
        return [line for line in text.splitlines()
                if line.startswith(("  compute stereo/profile (defaults): Phi_b ",
                                    "  interior volume fraction "))]

    assert len(phi_lines(out)) == 2
    assert phi_lines(out) == phi_lines(log)
    phi = float(phi_lines(out)[1].split("interior volume fraction")[1].split()[0])
    assert 0.56 <= phi <= 0.61
    # R = 1: Phi_b is the slab of 4R above the floor, with the floor's loose first layer
    assert 0.52 <= printed_measures(out)[0] <= 0.56
    assert "Initial packing: N = 4096" in out


def memory_available_gib():
    """MemAvailable + SwapFree of /proc/meminfo, in GiB (what create_packing compares with)."""
    kib = 0
    with open("/proc/meminfo") as f:
        for line in f:
            key, value = line.split()[:2]
            if key in ("MemAvailable:", "SwapFree:"):
                kib += int(value)
    return kib / 2**20


def test_more_spheres_than_memory_are_refused_naming_n_and_the_memory():
    # 10^9 spheres need about 284 GiB on one rank (305 bytes each): refused before anything is
    # allocated, where the deposition used to end in a bare "std::bad_alloc".
    if memory_available_gib() > 284:
        pytest.skip("this machine could hold 10^9 spheres")
    rc, out, _ = run_lammps(HEADER.format(boundary="p p fm", L=16, H=40, ntypes=1) +
                            "create_packing 1000000000 1 0.5 7\n")
    assert rc != 0, out
    assert "ERROR: create_packing: N = 1000000000 spheres need about 284 GiB of memory where " \
           "MPI rank 0 runs (about 160 bytes per sphere for the deposition on rank 0, 145 per " \
           "atom for the atoms of the ranks there), but only " in out, out
    assert "bad_alloc" not in out, out


def test_out_of_memory_in_the_deposition_names_n_and_the_memory():
    # Under an address-space limit (ulimit -v, as batch systems set) the deposition of 2 10^7
    # spheres (5.68 GiB) fails to allocate although the machine has the memory: the error names
    # N and the memory instead of a bare "std::bad_alloc". (The limit is below the packing's
    # first allocation, 480 MB, so the failure comes at once.)
    limit = 400 * 2**20

    def limited():
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))

    workdir = tempfile.mkdtemp(prefix="tapmc_")
    with open(os.path.join(workdir, "in.test"), "w") as f:
        f.write(HEADER.format(boundary="p p fm", L=16, H=40, ntypes=1) +
                "create_packing 20000000 1 0.5 7\n")
    proc = subprocess.run([LMP, "-in", "in.test", "-log", "none", "-nocite"], cwd=workdir,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          timeout=300, stdin=subprocess.DEVNULL, preexec_fn=limited)
    out = proc.stdout
    assert proc.returncode != 0, out
    assert "ERROR: create_packing (the box: open top): N = 20000000 spheres: rank 0 ran out " \
           "of memory during the deposition (std::bad_alloc); it needs about 5.68 GiB there" \
        in out, out
