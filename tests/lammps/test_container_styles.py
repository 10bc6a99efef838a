# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# One container per run, and the styles that gained 'container' (fix tapdilate, compute
# contacts), run as lmp_tapmc child processes: fix mc/settle stops a run whose TAPMC styles
# disagree about the container (one without, or two regions), naming both styles and what to
# do, and lets a consistent run go; fix tapdilate and compute contacts refuse a bad container
# naming it; compute contacts in a tube counts the wall contacts (per atom, vector entry 6)
# exactly as an all-pairs numpy count of the dumped positions, on 1 and 2 ranks.
import os

import numpy as np
import pytest

from lmprun import read_dump, run_lammps, thermo_table

GAP_TOLERANCE = 1e-10  # defaults::kContactsGapTolerance

# 300 spheres of radius 1/2 deposited in a tube of radius 4 about (4, 4); a second region of
# the same shape, so that only the IDs differ.
TUBE = """units lj
atom_style sphere
boundary f f fm
region box block 0 8 0 8 0 30
create_box 1 box
region tube cylinder z 4 4 4 INF INF
region other cylinder z 4 4 4 INF INF
create_packing 300 1 0.5 4928 floor 0.0 container tube
"""

TAPPING = """fix tap all tapdilate 0.01 floor 0.0{tap}
fix settle all mc/settle 4928 floor 0.0 eta 1e-3{settle}
compute phi all stereo/profile floor 0.0{phi}
thermo_style custom step c_phi[1] f_settle[1]
run 2
"""


def tapping(tap=" container tube", settle=" container tube", phi=" container tube", extra="",
            nprocs=1):
    script = TUBE + extra + TAPPING.format(tap=tap, settle=settle, phi=phi)
    return run_lammps(script, nprocs=nprocs)


def first_error(out):
    errors = [line for line in out.splitlines() if "ERROR" in line]
    assert errors, out[-2000:]
    return errors[0]


MISSING = "container missing on one of the styles of a run"
WHAT_TO_DO = "to every TAPMC style of the run"


def test_consistent_run_taps():
    rc, out, _ = tapping(extra="compute z all contacts 0.01 container tube\n")
    assert rc == 0, out[-2000:]
    assert "ERROR" not in out


def test_stereo_profile_without_the_container_stops_the_run():
    """The case that would otherwise go unnoticed: Phi over the box's area, not the disk's."""
    rc, out, _ = tapping(phi="")
    assert rc != 0
    error = first_error(out)
    assert MISSING in error, error
    assert "fix settle (mc/settle) has container tube" in error, error
    assert "compute phi (stereo/profile) has no container" in error, error
    assert "give the same 'container tube' " + WHAT_TO_DO in error, error


@pytest.mark.parametrize("nprocs", [1, 2])
def test_tapdilate_without_the_container_stops_the_run(nprocs):
    rc, out, _ = tapping(tap="", nprocs=nprocs)
    assert rc != 0
    error = first_error(out)
    assert MISSING in error and "fix tap (tapdilate) has no container" in error, error


def test_mc_settle_without_the_container_of_the_others_stops_the_run():
    rc, out, _ = tapping(settle="")
    assert rc != 0
    error = first_error(out)
    assert MISSING in error, error
    assert "fix settle (mc/settle) has no container" in error, error
    assert "give the same 'container tube'" in error, error


def test_two_regions_stop_the_run():
    rc, out, _ = tapping(phi=" container other")
    assert rc != 0
    error = first_error(out)
    assert "two different containers in one run" in error, error
    assert "fix settle (mc/settle) has container tube" in error, error
    assert "compute phi (stereo/profile) has container other" in error, error
    assert "(tube or other) " + WHAT_TO_DO in error, error


def test_compute_contacts_may_leave_the_container_out_but_not_name_another():
    rc, out, _ = tapping(extra="compute z all contacts 0.01\n")
    assert rc == 0, out[-2000:]            # sphere-sphere contacts only: a choice
    rc, out, _ = tapping(extra="compute z all contacts 0.01 container other\n")
    assert rc != 0
    error = first_error(out)
    assert "two different containers in one run" in error, error
    assert "compute z (contacts) has container other" in error, error
    # a box run with a compute that counts a wall: mismatch as well
    rc, out, _ = tapping(tap="", settle="", phi="",
                         extra="compute z all contacts 0.01 container tube\n")
    assert rc != 0
    error = first_error(out)
    assert MISSING in error and "compute z (contacts) has container tube" in error, error


@pytest.mark.parametrize("line,message", [
    ("fix tap all tapdilate 0.01 floor 0.0 container nowhere",
     "fix tapdilate: container = nowhere: no region with this ID"),
    ("fix tap all tapdilate 0.01 floor 0.0 container",
     "fix tapdilate: keyword 'container' needs 1 value(s)"),
    ("region thin cylinder z 4 4 0.4 INF INF\nfix tap all tapdilate 0.01 floor 0.0 container thin"
     "\nrun 1", "fix tapdilate: container = thin: cylinder radius = 0.4 is outside the allowed "
     "range (R_max, +inf) = (0.5, +inf)"),
    ("region slab block 1 7 1 7 INF INF\nfix tap all tapdilate 0.01 floor 0.0 container slab",
     "fix tapdilate: container = slab: region style 'block' has no exact container test here"),
    ("fix tap all tapdilate 0.01 floor 0.0 bogus 1",
     "fix tapdilate: unknown keyword 'bogus' (allowed: every, floor, container)"),
    ("compute z all contacts 0.01 container nowhere",
     "compute contacts: container = nowhere: no region with this ID"),
    ("region thin cylinder z 4 4 0.4 INF INF\ncompute z all contacts 0.01 container thin\n"
     "thermo_style custom step c_z[1]\nrun 0",
     "compute contacts: container = thin: cylinder radius = 0.4 is outside the allowed range"),
])
def test_bad_container_names_the_argument(line, message):
    rc, out, _ = run_lammps(TUBE + line + "\n")
    assert rc != 0
    assert message in first_error(out), out[-2000:]


@pytest.mark.parametrize("style", ["fix tap all tapdilate 0.01 floor 0.0",
                                   "compute z all contacts 0.01"])
def test_container_in_a_periodic_box_is_refused(style):
    script = TUBE.replace("boundary f f fm", "boundary p f fm").replace(
        " container tube", "") + style + " container tube\n"
    rc, out, _ = run_lammps(script)
    assert rc != 0
    error = first_error(out)
    assert "container = tube: the container needs non-periodic x and y" in error, error
    assert "periodic in x" in error, error


@pytest.mark.parametrize("style", ["fix tap all tapdilate 0.01 floor 0.0",
                                   "compute z all contacts 0.01",
                                   "compute p all stereo/profile floor 0.0"])
def test_a_shrink_wrapped_side_with_a_container_is_refused_before_the_first_run(style):
    """'s' shrinks the box to the spheres, inside the cylinder: the first run passed (checked
    before LAMMPS shrank the box) and every later run stopped with a cylinder outside the box.
    'm' keeps the box's bounds as its minimum and runs on."""
    body = style + " container tube\nthermo_style custom step atoms\nrun 1\nrun 1\n"
    script = TUBE + body
    rc, out, _ = run_lammps(script.replace("boundary f f fm", "boundary s f fm"))
    assert rc != 0 and "Loop time" not in out, out
    error = first_error(out)
    assert "container = tube: the x boundary is shrink-wrapped ('s')" in error, error
    rc, out, _ = run_lammps(script.replace("boundary f f fm", "boundary m m fm"))
    assert rc == 0 and out.count("Loop time") == 2, out


# ---- compute contacts in a tube against numpy ------------------------------------------------

GAPS = {"z0": 0.0, "z1": 0.01, "z2": 0.05}

COUNTS = "".join(f"compute {cid} all contacts {g} floor 0.0 container tube\n"
                 for cid, g in GAPS.items()) + """compute free all contacts 0.01 floor 0.0
dump d all custom 1 tube.dump id x y z radius c_z0 c_z1 c_z2 c_free
dump_modify d sort id format float %.17g
thermo_style custom step c_z0[1] c_z0[6] c_z1[1] c_z1[4] c_z1[6] c_z2[6] c_free[6]
thermo_modify format float %.17g
"""


def numpy_counts(xyz, r, gap, wall=True):
    """All pairs, the floor z = 0 and the wall of radius 4 about (4, 4), written apart from the
    kernel. Returns (per-sphere counts, touches the wall)."""
    d = xyz[:, None, :] - xyz[None, :, :]
    dist = np.sqrt((d * d).sum(axis=2))
    reach = (r[:, None] + r[None, :]) * (1 + gap + GAP_TOLERANCE)
    pairs = dist <= reach
    np.fill_diagonal(pairs, False)
    counts = pairs.sum(axis=1)
    counts += (xyz[:, 2] - r) <= (gap + GAP_TOLERANCE) * 2 * r
    on_wall = (4.0 - r) - np.hypot(xyz[:, 0] - 4.0, xyz[:, 1] - 4.0) \
        <= (gap + GAP_TOLERANCE) * 2 * r
    if wall:
        counts += on_wall
    return counts, on_wall


def check_counts(wd, out, steps):
    frames = read_dump(os.path.join(wd, "tube.dump"))
    _, rows = thermo_table(out, "c_z0[1]")
    assert [f[0] for f in frames] == steps and rows[:, 0].tolist() == steps
    walls = []
    for (step, _, _, cols), row in zip(frames, rows):
        xyz = np.column_stack([cols["x"], cols["y"], cols["z"]])
        r = cols["radius"]
        fractions = {}
        for cid, gap in GAPS.items():
            counts, on_wall = numpy_counts(xyz, r, gap)
            np.testing.assert_array_equal(cols["c" + "_" + cid].astype(int), counts,
                                          err_msg=f"step {step} {cid}")
            fractions[cid] = (counts.mean(), on_wall.mean())
        free, _ = numpy_counts(xyz, r, 0.01, wall=False)
        np.testing.assert_array_equal(cols["c_free"].astype(int), free, err_msg=f"step {step}")
        floor = ((xyz[:, 2] - r) <= (0.01 + GAP_TOLERANCE) * 2 * r).mean()
        expected = [fractions["z0"][0], fractions["z0"][1], fractions["z1"][0], floor,
                    fractions["z1"][1], fractions["z2"][1], 0.0]
        np.testing.assert_allclose(row[1:], expected, rtol=0, atol=1e-14, err_msg=f"step {step}")
        walls.append(fractions)
    return walls


@pytest.mark.parametrize("nprocs", [1, 2])
def test_contacts_in_a_tube_equal_a_numpy_count(nprocs):
    """The deposited packing (the wall a support of create_packing: exact wall contacts, counted
    at g = 0) and the same after two taps in the tube: every sphere's count at three gaps, and
    the vector's means and wall fractions, equal an independent count of the dumped positions."""
    script = TUBE + COUNTS + TAPPING.format(tap=" container tube", settle=" container tube",
                                            phi=" container tube").replace(
        "thermo_style custom step c_phi[1] f_settle[1]\n", "thermo 1\n")
    rc, out, wd = run_lammps(script, nprocs=nprocs)
    assert rc == 0, out[-2000:]
    walls = check_counts(wd, out, [0, 1, 2])
    deposited, tapped = walls[0], walls[-1]
    # create_packing rests spheres on the wall: many touch it exactly (g = 0); more within 5 %
    assert 0.1 < deposited["z0"][1] <= deposited["z2"][1] < 0.6, deposited
    # after the Monte Carlo redeposition contacts have gaps, the wall's too
    assert tapped["z0"][1] < deposited["z0"][1] and tapped["z2"][1] > 0.05, tapped
