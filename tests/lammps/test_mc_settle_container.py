# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# fix mc/settle with 'container REGION-ID' (a vertical cylinder): after every tap no overlap, no
# sphere through the floor and every centre within the container radius minus its own radius of
# the axis (independent check with square roots), N conserved, on 1 and 2 ranks with both
# schemes; a restart round trip; bad input stops with a message naming the keyword and value.
import os

import numpy as np
import pytest

from lmprun import min_gap, read_dump, run_lammps

CONTACT_TOL = 1e-10  # defaults::kContactTolerance

# Spheres of diameter 1 on a dilute simple cubic lattice inside a tube of radius 4.5 (9
# diameters) about (5, 5): the first redeposition settles them, the taps then compact them.
SCENE = """units lj
atom_style sphere
boundary f f fm
processors * * 1
region box block 0 10 0 10 0 40
create_box 1 box
region tube cylinder z 5 5 4.5 INF INF
lattice sc 0.512 origin 0.5 0.5 0.5
region fill cylinder z 5 5 3.9 0.6 20.6 units box
create_atoms 1 region fill
reset_atom_ids sort yes
set group all diameter 1.0
"""

TAPPING = """fix tap all tapdilate {eps} floor 0.0 container tube
fix settle all mc/settle 4928 floor 0.0 eta 1e-3 container tube scheme {scheme}
thermo_style custom step atoms f_settle[1] f_settle[2]
thermo 10
thermo_modify lost error
dump d all custom 1 dump.taps id x y z radius
dump_modify d sort id format float %.17g
run {taps}
"""


def tube_run(nprocs=1, scheme="auto", taps=30, eps=0.05):
    rc, out, wd = run_lammps(SCENE + TAPPING.format(eps=eps, scheme=scheme, taps=taps),
                             nprocs=nprocs)
    assert rc == 0, out
    return read_dump(os.path.join(wd, "dump.taps"))


def check_tube(frames):
    n0 = len(frames[0][3]["id"])
    assert n0 > 300
    for step, box, _, cols in frames:
        assert len(cols["id"]) == n0, f"step {step}: atoms {len(cols['id'])} of {n0}"
        xyz = np.column_stack([cols["x"], cols["y"], cols["z"]])
        radius = cols["radius"]
        gap, i, j = min_gap(xyz, radius, box, (False, False), floor=0.0)
        assert gap >= -CONTACT_TOL, f"step {step}: gap {gap} between {i} and {j}"
        wall_gap = (4.5 - radius) - np.hypot(xyz[:, 0] - 5.0, xyz[:, 1] - 5.0)
        assert wall_gap.min() >= -CONTACT_TOL * 2 * radius.max(), f"step {step}: {wall_gap.min()}"
    return n0


@pytest.mark.parametrize("nprocs,scheme", [(1, "auto"), (2, "gather"), (2, "domain")])
def test_taps_in_a_tube_keep_every_sphere_inside(nprocs, scheme):
    frames = tube_run(nprocs, scheme)
    check_tube(frames)
    # settling and compaction happened, and the wall was reached
    z0, z_end = frames[0][3]["z"].mean(), frames[-1][3]["z"].mean()
    assert z_end < 0.8 * z0
    last = frames[-1][3]
    wall_gap = (4.5 - last["radius"]) - np.hypot(last["x"] - 5.0, last["y"] - 5.0)
    assert (wall_gap < 0.05).sum() > 20


def test_gather_on_two_ranks_is_the_serial_trajectory():
    serial, two = tube_run(1, "gather", taps=5), tube_run(2, "gather", taps=5)
    for c in ("x", "y", "z"):
        np.testing.assert_array_equal(serial[-1][3][c], two[-1][3][c])


def test_restart_round_trip_in_a_tube(tmp_path):
    straight = SCENE + TAPPING.format(eps=0.05, scheme="auto", taps=6).replace(
        "run 6", "run 6\nwrite_dump all custom final.dump id x y z modify sort id format float %.17g")
    rc, out, wd = run_lammps(straight)
    assert rc == 0, out
    first = SCENE + TAPPING.format(eps=0.05, scheme="auto", taps=3) + "write_restart tube.restart\n"
    rc, out, wd2 = run_lammps(first, workdir=str(tmp_path))
    assert rc == 0, out
    second = """read_restart tube.restart
region tube cylinder z 5 5 4.5 INF INF
fix tap all tapdilate 0.05 floor 0.0 container tube
fix settle all mc/settle 4928 floor 0.0 eta 1e-3 container tube
run 3
write_dump all custom final.dump id x y z modify sort id format float %.17g
"""
    rc, out, _ = run_lammps(second, workdir=str(tmp_path))
    assert rc == 0, out
    with open(os.path.join(wd, "final.dump")) as a, open(tmp_path / "final.dump") as b:
        assert a.read().split("ITEM: ATOMS")[1] == b.read().split("ITEM: ATOMS")[1]


@pytest.mark.parametrize("change,message", [
    ("boundary f f fm|boundary p f fm", "periodic"),
    ("region tube cylinder z 5 5 4.5 INF INF|region tube block 0.5 9.5 0.5 9.5 INF INF", "cylinder"),
    ("region tube cylinder z 5 5 4.5 INF INF|region tube cylinder x 5 5 4.5 INF INF", "axis"),
    ("region tube cylinder z 5 5 4.5 INF INF|region tube cylinder z 5 5 0.4 INF INF", "0.4"),
    ("container tube scheme|container nowhere scheme", "fix mc/settle: container = nowhere"),
    ("container tube scheme|container tube xwalls 0 10 scheme", "fix mc/settle: xwalls"),
])
def test_bad_container_input_names_the_argument(change, message):
    old, new = change.split("|")
    script = (SCENE + TAPPING.format(eps=0.05, scheme="auto", taps=1)).replace(old, new)
    assert new in script
    rc, out, _ = run_lammps(script)
    assert rc != 0
    errors = [line for line in out.splitlines() if "ERROR" in line]
    assert errors and message in errors[0], out[-2000:]
