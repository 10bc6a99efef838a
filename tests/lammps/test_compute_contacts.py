# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# compute contacts run as lmp_tapmc child processes: thermo, dump and fix ave/time output on an
# FCC lattice; identical numbers on 1 and 2 MPI ranks; after taps of fix tapdilate + fix
# mc/settle, the dumped per-atom counts equal an all-pairs count of the dumped packing and
# tapmc.contacts.Contacts on it; every bad argument rejected with a message naming it; the
# library interface stopped before ghosts exist or when they are too thin.
import os
import re
import subprocess
import sys
import tempfile

import numpy as np
import pytest

from lmprun import (LMP, ave_time_rows, fcc_lattice, printed, read_dump, run_lammps,
                    thermo_table)

SOURCE = os.environ.get("TAPMC_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(SOURCE, "tools", "python"))

from tapmc.contacts import GAP_TOLERANCE, MAX_Z, Contacts  # noqa: E402
from tapmc.readers import read_dump as tapmc_read_dump  # noqa: E402


VECTOR_PRINT = 'print "{tag} ' + " ".join("$(c_{id}[%d]:%%.17g)" % i for i in range(1, 6)) + '"\n'


def vector_print(cid, tag):
    return VECTOR_PRINT.replace("{tag}", tag).replace("{id}", cid)


def brute_force(xyz, radius, box, periodic, gap, floor=None):
    """All pairs at the nearest image along the periodic axes (independent of tapmc)."""
    lengths = box[:, 1] - box[:, 0]
    counts = np.zeros(len(xyz), int)
    for i in range(len(xyz)):
        d = xyz - xyz[i]
        for axis in range(3):
            if periodic[axis]:
                d[:, axis] -= lengths[axis] * np.round(d[:, axis] / lengths[axis])
        reach = (radius + radius[i]) * (1 + gap + GAP_TOLERANCE)
        touching = (d * d).sum(axis=1) <= reach * reach
        touching[i] = False
        counts[i] = touching.sum()
        if floor is not None and (xyz[i, 2] - radius[i] - floor
                                  <= (gap + GAP_TOLERANCE) * 2 * radius[i]):
            counts[i] += 1
    return counts


def test_thermo_dump_and_time_average_on_fcc():
    """16 layers: the bottom and top layers have 8 contacts, the 14 others 12 (<Z> = 11.5); with
    the floor under the bottom layer, its spheres have 9."""
    script = fcc_lattice() + """
compute z all contacts 0.01
compute zf all contacts 0.01 floor -0.70710678118654752
thermo_style custom step c_z[1] c_zf[1] c_zf[4]
thermo_modify format float %.15g
dump d all custom 1 fcc.dump id z c_z c_zf
dump_modify d sort id
fix av all ave/time 1 1 1 c_zf[*] mode vector file p.dat format " %.17g"
run 0
""" + vector_print("z", "VEC") + vector_print("zf", "FLOOR")
    rc, out, wd = run_lammps(script)
    assert rc == 0, out[-2000:]
    m = re.search(r"^\s+0\s+(\S+)\s+(\S+)\s+(\S+)\s*$", out, re.M)
    assert m, out[-2000:]
    assert [float(v) for v in m.groups()] == [11.5, 11.5625, 0.0625]
    np.testing.assert_array_equal(printed(out, "VEC"), [11.5, 0, 0, 0, 12])
    np.testing.assert_array_equal(printed(out, "FLOOR"), [11.5625, 0, 0, 0.0625, 12])
    step, box, _, cols = read_dump(os.path.join(wd, "fcc.dump"))[0]
    z = cols["z"]
    bottom, top = z == z.min(), z == z.max()
    assert bottom.sum() == 32 and top.sum() == 32
    np.testing.assert_array_equal(cols["c_z"], np.where(bottom | top, 8, 12))
    np.testing.assert_array_equal(cols["c_zf"], np.where(top, 8, np.where(bottom, 9, 12)))
    rows = ave_time_rows(os.path.join(wd, "p.dat"))
    assert rows.shape == (MAX_Z + 1, 3)
    np.testing.assert_array_equal(rows[:, 1], np.arange(MAX_Z + 1))
    expected = np.zeros(MAX_Z + 1)
    expected[[8, 9, 12]] = [1 / 16, 1 / 16, 14 / 16]
    np.testing.assert_allclose(rows[:, 2], expected, rtol=0, atol=1e-15)


PERTURBED = """
displace_atoms all random 0.12 0.12 0.12 4711 units box
region low block INF INF INF INF INF 9.0 units box
group low region low
set group low diameter 1.35
compute a all contacts 0.02 floor 0.3
compute l low contacts 0.05
thermo_style custom step c_a[1] c_l[1]
dump d all custom 1 per.dump id x y z c_a c_l
dump_modify d sort id format float %.17g
fix av all ave/time 1 1 1 c_a[*] c_l[*] mode vector file p.dat format " %.17g"
run 0
"""


@pytest.mark.parametrize("boundary", ["p p f", "f f f"])
def test_same_numbers_on_one_and_two_ranks(boundary):
    body = fcc_lattice(boundary, "0.1 3.9 0.1 3.9 0.1 7.9") + PERTURBED
    tail = vector_print("a", "VEC") + vector_print("l", "LOW")
    results = []
    for nprocs, grid in [(1, "* * *"), (2, "2 1 1"), (2, "1 1 2")]:
        rc, out, wd = run_lammps(f"processors {grid}\n" + body + tail, nprocs=nprocs)
        assert rc == 0, out[-2000:]
        _, _, _, cols = read_dump(os.path.join(wd, "per.dump"))[0]
        # create_atoms numbers the atoms rank by rank: compare them by position
        order = np.lexsort((cols["z"], cols["y"], cols["x"]))
        results.append((printed(out, "VEC"), printed(out, "LOW"), cols["c_a"][order],
                        cols["c_l"][order], ave_time_rows(os.path.join(wd, "p.dat")),
                        np.column_stack([cols[c][order] for c in "xyz"])))
    serial = results[0]
    assert 2 < serial[0][0] < 10 and 2 < serial[1][0] < 10, serial[:2]
    assert 0 < serial[0][3] < 0.3        # some spheres touch the floor at 0.3
    for parallel in results[1:]:
        for a, b in zip(serial, parallel):
            np.testing.assert_array_equal(b, a)


TAPPED = """units lj
atom_style sphere
boundary p p fm
region box block 0 6 0 6 0 30
create_box 1 box
create_packing 300 1 0.5 4928 floor 0.0
compute z0 all contacts 0.0
compute z1 all contacts 0.001
compute z2 all contacts 0.01 floor 0.0
compute z3 all contacts 0.05
fix tap all tapdilate 0.01 floor 0.0
fix settle all mc/settle 4928 floor 0.0 eta 1e-5
thermo_style custom step c_z0[1] c_z1[1] c_z2[1] c_z3[1] c_z2[4]
thermo_modify format float %.17g
thermo 1
dump d all custom 1 taps.dump id x y z radius c_z0 c_z1 c_z2 c_z3
dump_modify d sort id format float %.17g
run 3
"""


@pytest.mark.parametrize("nprocs", [1, 2])
def test_counts_after_taps_equal_an_all_pairs_count_and_python(nprocs):
    """A deposited packing tapped three times (both redeposition schemes: gather on 1 rank,
    domain on 2): at every dumped step each sphere's count at each gap equals an all-pairs count
    of the dumped positions (written exactly, %.17g) and tapmc.contacts.Contacts on the dump;
    the thermo means are their means."""
    rc, out, wd = run_lammps(TAPPED, nprocs=nprocs)
    assert rc == 0, out[-2000:]
    _, thermo = thermo_table(out, "c_z0[1]")
    assert thermo[:, 0].tolist() == [0, 1, 2, 3]
    gaps = {"c_z0": (0.0, None), "c_z1": (0.001, None), "c_z2": (0.01, 0.0), "c_z3": (0.05, None)}
    frames = read_dump(os.path.join(wd, "taps.dump"))
    python_frames = tapmc_read_dump(os.path.join(wd, "taps.dump")).frames
    assert [f[0] for f in frames] == [0, 1, 2, 3]
    for (step, box, bounds, cols), pframe, row in zip(frames, python_frames, thermo):
        xyz = np.column_stack([cols["x"], cols["y"], cols["z"]])
        periodic = [b == "pp" for b in bounds]
        assert periodic == [True, True, False]
        for k, (column, (gap, floor)) in enumerate(gaps.items()):
            dumped = cols[column].astype(int)
            np.testing.assert_array_equal(
                dumped, brute_force(xyz, cols["radius"], box, periodic, gap, floor),
                err_msg=f"step {step} {column}")
            c = Contacts.from_frame(pframe, gap=gap, floor=floor).compute()
            np.testing.assert_array_equal(c.coordination, dumped, err_msg=f"{step} {column}")
            assert row[1 + k] == pytest.approx(dumped.mean(), abs=1e-14)
        on_floor = cols["z"] - cols["radius"] <= (0.01 + GAP_TOLERANCE) * (2 * cols["radius"])
        assert on_floor.any() and row[5] == pytest.approx(on_floor.mean(), abs=1e-15)
    # the deposited packing (step 0) has exact contacts; the Monte Carlo packing has almost none
    # at g = 0 and many more within a few percent
    assert thermo[0, 1] > 4.0
    assert thermo[-1, 1] < 1.0
    assert thermo[-1, 1] < thermo[-1, 2] < thermo[-1, 3] < thermo[-1, 4]


@pytest.mark.parametrize("nprocs", [1, 2])
def test_a_dynamic_group_counts_its_members_with_ghosts_for_any_atom(nprocs):
    """A dynamic group is empty at init (LAMMPS fills it at setup): the ghosts were sized from
    its radii then, 0, and the compute stopped with 'set comm_modify cutoff'. Sized for every
    atom, it counts, at each dumped step, the contacts between the group's members (dumped with
    gmask) as an all-pairs count of them does, on 1 and 2 ranks."""
    script = TAPPED.split("compute z0")[0] + """variable low atom z<5
group low dynamic all var low every 1
variable member atom gmask(low)
compute zl low contacts 0.01 floor 0.0
fix tap all tapdilate 0.01 floor 0.0
fix settle all mc/settle 4928 floor 0.0 eta 1e-5
dump d all custom 1 low.dump id x y z radius c_zl v_member
dump_modify d sort id format float %.17g
run 2
"""
    rc, out, wd = run_lammps(script, nprocs=nprocs)
    assert rc == 0, out[-2000:]
    assert "move(s) atoms besides" not in out and "GROUP" not in out.split("run 2")[-1]
    frames = read_dump(os.path.join(wd, "low.dump"))
    assert [f[0] for f in frames] == [0, 1, 2]
    for step, box, bounds, cols in frames:
        member = cols["v_member"] == 1
        assert 50 < member.sum() < len(member), step
        xyz = np.column_stack([cols["x"], cols["y"], cols["z"]])[member]
        expected = brute_force(xyz, cols["radius"][member], box,
                               [b == "pp" for b in bounds], 0.01, floor=0.0)
        np.testing.assert_array_equal(cols["c_zl"][member].astype(int), expected,
                                      err_msg=f"step {step}")


TUBE = """units lj
atom_style sphere
boundary f f fm
region box block 0 8 0 8 0 30
create_box 1 box
region tube cylinder z 4 4 4 INF INF
create_packing 300 1 0.5 4928 floor 0.0 container tube
fix tap all tapdilate 0.02 floor 0.0 container tube
fix settle all mc/settle 7 floor 0.0 eta 1e-4 container tube
compute zt all contacts 0.01 floor 0.0 container tube
dump d all custom 2 tube.dump id x y z radius c_zt
dump_modify d sort id format float %.17g
thermo_style custom step c_zt[1] c_zt[6]
run 2
"""


def test_tube_counts_equal_python_with_the_cylinder():
    """In a tube, the compute with 'container' counts the wall: tapmc.contacts.Contacts with
    the same cylinder gives the same count sphere by sphere (without it, a wall sphere read one
    less), the deposited packing and after two taps."""
    from tapmc.cylinder import Cylinder

    rc, out, wd = run_lammps(TUBE)
    assert rc == 0, out[-2000:]
    _, thermo = thermo_table(out, "c_zt[1]")
    frames = read_dump(os.path.join(wd, "tube.dump"))
    python_frames = tapmc_read_dump(os.path.join(wd, "tube.dump")).frames
    for (step, _, _, cols), frame, row in zip(frames, python_frames, thermo):
        c = Contacts.from_frame(frame, gap=0.01, floor=0.0,
                                cylinder=Cylinder(4.0, 4.0, 4.0)).compute()
        np.testing.assert_array_equal(c.coordination, cols["c_zt"].astype(int), err_msg=step)
        assert c.on_wall.any() and row[2] == pytest.approx(c.fraction_wall, abs=1e-8)  # %g


def test_ghost_shell_does_not_depend_on_the_unit_scale():
    """A simple cubic lattice of spheres of diameter 1e-3 (lj units, whose neighbour skin is
    0.3): the compute added the skin to its ghost cutoff, 300 diameters, and LAMMPS copied the
    216 spheres into about 5 million periodic images (679 MB at 300 spheres). Without a pair
    style nothing moves between rebuilds: the shell is the contact reach, at every scale."""
    script = """units lj
atom_style sphere
boundary p p p
lattice sc {density}
region box block 0 6 0 6 0 6
create_box 1 box
create_atoms 1 box
set group all diameter {diameter}
compute z all contacts 0.01
thermo_style custom step c_z[1]
run 0
"""
    ghosts = {}
    for diameter in (1.0, 1e-3):
        rc, out, _ = run_lammps(script.format(density=diameter ** -3, diameter=diameter),
                                timeout=120)
        assert rc == 0, out[-2000:]
        assert thermo_table(out, "c_z[1]")[1][0, 1] == 6.0  # simple cubic: 6 contacts each
        ghosts[diameter] = float(re.search(r"Nghost: +([0-9.e+]+) ave", out).group(1))
    assert ghosts[1e-3] == ghosts[1.0] < 10 * 216, ghosts


BAD = [
    ("compute c all contacts",
     "compute contacts: the gap g is missing (relative to the contact distance R_i + R_j, in "
     "[0, 1]): compute ID group-ID contacts g [floor z0] [radius R] [container region-ID]"),
    ("compute c all contacts -0.1",
     "compute contacts: gap = -0.1 is outside the allowed range [0, 1] (relative to the contact "
     "distance R_i + R_j)"),
    ("compute c all contacts 1.5", "gap = 1.5 is outside the allowed range [0, 1]"),
    ("compute c all contacts nan", "gap = nan is not a finite number (allowed range [0, 1])"),
    ("compute c all contacts abc",
     "compute contacts: gap = abc is not a finite number (allowed range [0, 1])"),
    ("compute c all contacts 0.01x", "gap = 0.01x is not a finite number"),
    ("compute c all contacts floor 0.0", "gap = floor is not a finite number"),
    ("compute c all contacts 0.01 floor", "compute contacts: keyword 'floor' needs 1 value(s)"),
    ("compute c all contacts 0.01 floor zz",
     "compute contacts: floor = zz is not a finite number"),
    ("compute c all contacts 0.01 floor inf", "compute contacts: floor = inf is not a finite number"),
    ("compute c all contacts 0.01 radius 0",
     "compute contacts: radius = 0 is outside the allowed range (0, +inf)"),
    ("compute c all contacts 0.01 radius -1",
     "compute contacts: radius = -1 is outside the allowed range (0, +inf)"),
    ("compute c all contacts 0.01 bogus 1",
     "compute contacts: unknown keyword 'bogus' (allowed: floor, radius, container)"),
    ("set group all diameter 0.0\ncompute c all contacts 0.01\nrun 0",
     "compute contacts: per-atom radius must be > 0 (an atom of group all has radius 0)"),
]


@pytest.mark.parametrize("body,message", BAD)
def test_bad_argument(body, message):
    rc, out, _ = run_lammps(fcc_lattice() + body)
    assert rc != 0
    assert "ERROR" in out and message in out, out[-1500:]
    assert "Illegal compute command" not in out


def test_a_periodic_box_below_a_diameter_is_refused():
    """A radius of 1e3 in a periodic box of 8 made LAMMPS build the images of images until the
    memory ran out (a hang); now the box length, the axis and the diameter are named."""
    rc, out, _ = run_lammps("units lj\natom_style atomic\nboundary p p fm\n"
                            "region box block 0 6 0 6 0 30\ncreate_box 1 box\nmass 1 1.0\n"
                            "create_atoms 1 single 3 3 1\n"
                            "compute c all contacts 1 radius 1e3\nrun 0\n")
    assert rc != 0 and "the periodic box length along x = 6 is below the largest sphere " \
        "diameter 2000" in out, out[-2000:]


def test_box_restrictions_and_missing_radius():
    rc, out, _ = run_lammps(fcc_lattice("p p p") + "compute c all contacts 0.01 floor 0.0\n")
    assert rc != 0 and "the floor keyword needs a non-periodic z boundary" in out, out[-1500:]
    rc, out, _ = run_lammps(fcc_lattice("p p p") + "compute c all contacts 0.01\n"
                            "thermo_style custom step c_c[1]\nrun 0\n")
    assert rc == 0, out[-1500:]                   # no floor: any boundary
    tri = fcc_lattice().replace("region box block 0 4 0 4 0 10", "region box prism 0 4 0 4 0 10 1 0 0")
    rc, out, _ = run_lammps(tri + "compute c all contacts 0.01\n")
    assert rc != 0 and "compute contacts: triclinic boxes are not supported" in out, out[-1500:]
    atomic = fcc_lattice().replace("atom_style sphere", "atom_style atomic").replace(
        "set group all diameter 1.4142135623730951\nset group all density 1.0\n", "mass 1 1.0\n")
    rc, out, _ = run_lammps(atomic + "compute c all contacts 0.01\n")
    assert rc != 0 and "compute contacts: radius keyword required: atom style atomic has no " \
                       "per-atom radius" in out, out[-1500:]
    rc, out, _ = run_lammps(atomic + "compute c all contacts 0.01 radius 0.70710678118654752\n"
                            "thermo_style custom step c_c[1]\nrun 0\n" + vector_print("c", "VEC"))
    assert rc == 0, out[-1500:]
    assert printed(out, "VEC")[0] == 11.5


def test_outputs_read_on_one_step_share_a_count_that_a_new_run_renews():
    """The vector and the per-atom vector read on one step come from one count; atoms displaced
    between two 'run 0' at the same step are counted afresh (a count kept from the first run
    would still read the lattice's 11.5)."""
    script = fcc_lattice() + """compute z all contacts 0.0
compute zsum all reduce sum c_z
variable n equal count(all)
thermo_style custom step c_z[1] c_z[5] c_zsum
run 0
print "BEFORE $(c_z[1]:%.17g) $(c_zsum/v_n:%.17g)"
displace_atoms all random 0.02 0.02 0.0 77 units box
run 0
print "AFTER $(c_z[1]:%.17g) $(c_zsum/v_n:%.17g)"
"""
    rc, out, wd = run_lammps(script)
    assert rc == 0, out[-2000:]
    before, after = printed(out, "BEFORE"), printed(out, "AFTER")
    assert before[0] == 11.5 and before[1] == 11.5, before
    assert after[0] < 11.0 and after[1] == pytest.approx(after[0], abs=1e-12), after


@pytest.mark.parametrize("nprocs", [1, 2])
def test_empty_group_gives_zeros(nprocs):
    script = fcc_lattice() + """group none empty
compute c none contacts 0.01 floor 0.0
fix av all ave/time 1 1 1 c_c[*] mode vector file p.dat
thermo_style custom step c_c[1]
run 0
""" + vector_print("c", "VEC")
    rc, out, wd = run_lammps(script, nprocs=nprocs)
    assert rc == 0, out[-2000:]
    np.testing.assert_array_equal(printed(out, "VEC"), [0, 0, 0, 0, 0])
    rows = ave_time_rows(os.path.join(wd, "p.dat"))
    np.testing.assert_array_equal(rows[:, 2], 0.0)


LIBRARY = """
import ctypes, sys, lammps
lmp = lammps.lammps(cmdargs=["-log", "none", "-nocite"])
ctypes.CDLL(sys.argv[1]).tapmc_register(lmp.lmp)
for line in '''{setup}'''.strip().splitlines():
    lmp.command(line)
print("EXTRACTING", flush=True)
v = lmp.extract_compute("c", lammps.LMP_STYLE_GLOBAL, lammps.LMP_TYPE_VECTOR)
print("MEAN", v[0], flush=True)
"""


def run_library(setup):
    lib = os.environ.get("TAPMC_LIB", os.path.join(os.path.dirname(LMP), "libtapmc.so"))
    workdir = tempfile.mkdtemp(prefix="tapmc_")
    path = os.path.join(workdir, "lib.py")
    with open(path, "w") as f:
        f.write(LIBRARY.format(setup=setup))
    proc = subprocess.run(["/usr/bin/python3", path, lib], cwd=workdir, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True, timeout=120,
                          stdin=subprocess.DEVNULL)
    return proc.returncode, proc.stdout


def test_library_use_before_a_run_and_with_thin_ghosts():
    """Through the library interface the compute can be invoked when LAMMPS has built no ghost
    atoms (before any run) or built them for smaller spheres: it stops and says what to do."""
    rc, out = run_library(fcc_lattice() + "compute c all contacts 0.01\n")
    assert rc != 0 and "EXTRACTING" in out, out[-1500:]
    assert "compute contacts c: invoked before the first run" in out and "'run 0'" in out, out
    rc, out = run_library(fcc_lattice() + "compute c all contacts 0.01\nrun 0\n")
    assert rc == 0 and "MEAN 11.5" in out, out[-1500:]
    # spheres grown after the run: their contacts reach beyond the ghosts of that run
    rc, out = run_library(fcc_lattice() + "compute c all contacts 0.01\nrun 0\n"
                          "set group all diameter 4.0\n")
    assert rc != 0, out[-1500:]
    need = 4.0 * (1 + 0.01 + GAP_TOLERANCE)
    m = re.search(r"compute contacts c: the ghost atoms reach (\S+) beyond each sub-domain, but "
                  r"a contact within gap 0.01 of spheres of radius up to 2 reaches (\S+): set "
                  r"'comm_modify cutoff (\S+)' \(or larger\) and run again", out)
    assert m, out[-1500:]
    assert float(m.group(2)) == pytest.approx(need) and float(m.group(3)) == pytest.approx(need)
    assert float(m.group(1)) < need
    # and a run re-made the ghosts: the new spheres overlap everything within 4 * 1.01
    rc, out = run_library(fcc_lattice() + "compute c all contacts 0.01\nrun 0\n"
                          "set group all diameter 4.0\nrun 0\n")
    assert rc == 0, out[-1500:]
    assert float(re.search(r"MEAN (\S+)", out).group(1)) > 12


def test_doc_examples_run():
    """The Examples block of doc/compute_contacts.rst runs as written on a lattice."""
    with open(os.path.join(SOURCE, "doc", "compute_contacts.rst")) as f:
        text = f.read()
    block = text.split("Examples\n\"\"\"\"\"\"\"\"")[1].split("Description\n")[0]
    commands = [l.strip() for l in block.splitlines() if l.startswith("   ") and l.strip()]
    assert len(commands) >= 4 and any("contacts" in c for c in commands)
    rc, out, wd = run_lammps(fcc_lattice() + "\n".join(commands) + "\nrun 0\n")
    assert rc == 0, out[-1500:]
    assert "WARNING" not in out, out[-1500:]
