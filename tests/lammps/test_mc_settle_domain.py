# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# fix mc/settle's domain-decomposed redeposition (scheme domain, the default on several ranks)
# under mpirun: hard-sphere invariants after every tap by the independent all-pairs oracle on
# 1, 2 and 4 ranks, x, y, x-y and z grids, PBC and FBC, polydisperse with fixed obstacles; atom
# count conserved; every ghost the kernel sees checked against its owner after every round
# ('verify yes'); every sphere active once per cycle across ghost rebuilds; the scale example at
# the paper's size; deterministic for a fixed grid; clear errors without a hang. (Its exact
# restart round trip is tested with the serial one in test_mc_settle.py.)
import os

import numpy as np
import pytest

from lmprun import min_gap, read_dump, run_lammps, thermo_table
from test_mc_settle import CONTACT_TOL, SCENE, TAPPING, check_frames

# 'verify yes': after every round a full forward communication checks that the ghosts the kernel
# sees (refreshed with the moved spheres only) are where their owners are; the run stops otherwise.
DOMAIN_TAPPING = TAPPING.replace("eta 1e-3", "eta 1e-3 scheme domain verify yes")


def scene(boundary, grid):
    return SCENE.format(boundary=boundary, zprocs=1).replace("processors * * 1",
                                                             f"processors {grid}")


def domain_run(boundary, nprocs, grid, taps=30, seed=4928, workdir=None):
    script = scene(boundary, grid) + DOMAIN_TAPPING.format(eps=0.02, seed=seed, every=1,
                                                           taps=taps)
    rc, out, wd = run_lammps(script, nprocs=nprocs, workdir=workdir)
    assert rc == 0, out
    assert f"{grid.replace(' ', ' by ')} MPI processor grid" in out
    return read_dump(os.path.join(wd, "dump.taps")), out


@pytest.mark.parametrize("nprocs,grid,boundary", [
    (2, "2 1 1", "p p fm"),
    (2, "1 2 1", "f f fm"),
    (4, "2 2 1", "p p fm"),
    (4, "2 2 1", "f f fm"),
    (2, "1 1 2", "p p fm"),
    (1, "1 1 1", "f p fm"),
])
def test_no_overlap_after_every_tap(nprocs, grid, boundary):
    # A dilute lattice falls into a packing (ghosts rebuilt many times), then 29 taps.
    periodic = (boundary[0] == "p", boundary[2] == "p")
    frames, _ = domain_run(boundary, nprocs, grid)
    assert len(frames) == 31
    check_frames(frames, periodic, (not periodic[0], not periodic[1]))  # also no xu / yu jumps
    assert frames[-1][3]["z"].mean() < 0.8 * frames[0][3]["z"].mean()


def test_fixed_grid_and_seed_give_one_trajectory_and_seeds_differ():
    a, _ = domain_run("p p fm", 2, "2 1 1", taps=8)
    b, _ = domain_run("p p fm", 2, "2 1 1", taps=8)
    c, _ = domain_run("p p fm", 2, "2 1 1", taps=8, seed=4929)
    for (_, _, _, fa), (_, _, _, fb) in zip(a, b):
        for col in ("x", "y", "z"):
            np.testing.assert_array_equal(fa[col], fb[col])
    assert not np.array_equal(a[-1][3]["z"], c[-1][3]["z"])


def test_polydisperse_with_fixed_obstacles_on_two_by_two_ranks():
    script = """units lj
atom_style sphere
boundary p p fm
processors 2 2 1
region box block 0 12 0 12 0 30
create_box 1 box
create_packing 600 1 0.5 77 floor 0.0 dispersity 0.3
variable low atom z<1.0
group bottom variable low
group grains subtract all bottom
fix tap grains tapdilate 0.05 floor 0.0
fix settle grains mc/settle 5 floor 0.0 eta 1e-4 scheme domain verify yes
dump d all custom 1 dump.taps id x y z radius
dump_modify d sort id format float %.17g
thermo_modify lost error
run 20
"""
    rc, out, wd = run_lammps(script, nprocs=4)
    assert rc == 0, out
    frames = read_dump(os.path.join(wd, "dump.taps"))
    first = frames[0][3]
    bottom = first["z"] < 1.0
    assert 0 < bottom.sum() < len(bottom)
    for step, box, _, cols in frames:
        assert len(cols["id"]) == 600
        xyz = np.column_stack([cols["x"], cols["y"], cols["z"]])
        gap, i, j = min_gap(xyz, cols["radius"], box, (True, True), floor=0.0)
        assert gap >= -CONTACT_TOL * 1.3, f"step {step}: gap {gap} between {i} and {j}"
        for c in ("x", "y", "z"):
            np.testing.assert_array_equal(cols[c][bottom], first[c][bottom])


def test_every_sphere_is_active_once_per_cycle_across_ghost_rebuilds():
    # The check interval is one sweep, so a cycle of rounds activates every movable sphere once
    # and makes exactly N trials: the trials of each tap are a whole number of sweeps, also in
    # the taps whose cycles were cut by ghost rebuilds (an atom that migrates keeps its round).
    taps = 6
    script = scene("p p fm", "2 2 1") + DOMAIN_TAPPING.replace(
        "thermo_style custom step atoms f_settle[1] f_settle[2] f_settle[3] f_settle[4]\n"
        "thermo 10", "thermo_style custom step atoms f_settle[5] f_settle[7]\nthermo 1"
    ).format(eps=0.05, seed=4928, every=taps, taps=taps)
    rc, out, _ = run_lammps(script, nprocs=4)
    assert rc == 0, out
    rows = thermo_table(out, "Atoms")[1][1:]
    assert len(rows) == taps, out
    n = rows[:, 1]
    trials, rebuilds = rows[:, 2], rows[:, 3]
    assert (rebuilds > 0).sum() >= 3, rows  # the falling lattice and the taps rebuild ghosts
    np.testing.assert_array_equal(trials % n, 0)
    assert (trials > 0).all()


def test_scale_example_runs_at_paper_size_on_two_ranks():
    # examples/scale/in.paper_x100 with its switches set to the paper's own size (4096 spheres,
    # L = 32 R): the input runs as documented, with the domain scheme's columns.
    source = os.environ.get("TAPMC_SOURCE_DIR", "../..")
    with open(os.path.join(source, "examples", "scale", "in.paper_x100")) as f:
        script = f.read()
    rc, out, _ = run_lammps(script, nprocs=2, variables={"N": 4096, "L": 32})
    assert rc == 0, out
    assert "Created 4096 spheres by sequential deposition" in out
    assert "1 by 2 by 1 MPI processor grid" in out or "2 by 1 by 1 MPI processor grid" in out
    lines = out.splitlines()
    head = next(k for k, line in enumerate(lines) if line.split()[:2] == ["Step", "c_phi[1]"])
    names = lines[head].split()
    tap = dict(zip(names, (float(v) for v in lines[head + 2].split())))
    assert tap["Step"] == 1 and tap["f_settle[1]"] > 100  # sweeps at the default eta
    assert tap["f_settle[8]"] == 2 * tap["f_settle[1]"]  # 2 rounds per sweep on 2 ranks
    assert 0.5 < tap["c_phi[1]"] < 0.6  # Phi_b


def test_gather_scheme_on_two_ranks_is_the_serial_trajectory():
    serial = TAPPING.replace("eta 1e-3", "eta 1e-3 scheme gather")
    runs = []
    for nprocs, grid in ((1, "1 1 1"), (2, "2 1 1")):
        rc, out, wd = run_lammps(scene("p p fm", grid) + serial.format(
            eps=0.02, seed=4928, every=5, taps=10), nprocs=nprocs)
        assert rc == 0, out
        runs.append(read_dump(os.path.join(wd, "dump.taps")))
    for (_, _, _, a), (_, _, _, b) in zip(*runs):
        for c in ("x", "y", "z"):
            np.testing.assert_array_equal(a[c], b[c])


@pytest.mark.parametrize("nprocs,grid,message", [
    (4, "4 1 1", "the narrowest sub-domain along x is 2.5 wide; the decomposed redeposition "
                 "needs at least 3.6 (2 contact distances + 4 move margins); 'scheme gather' "
                 "runs the same input on this processor grid"),
    (2, "1 2 1", None),
])
def test_narrow_sub_domains_are_refused_with_the_needed_width(nprocs, grid, message):
    script = scene("p p fm", grid) + DOMAIN_TAPPING.format(eps=0.02, seed=1, every=1, taps=2)
    rc, out, _ = run_lammps(script, nprocs=nprocs, timeout=120)
    if message is None:
        assert rc == 0, out
        return
    assert rc != 0
    assert message in out, out
    # What the message offers holds: the same input with 'scheme gather' runs on that grid.
    rc, out, _ = run_lammps(script.replace("scheme domain verify yes", "scheme gather"),
                            nprocs=nprocs, timeout=120)
    assert rc == 0, out


@pytest.mark.parametrize("nprocs,keywords,warning", [
    (1, "scheme gather verify yes", "verify yes is ignored with scheme gather; it checks the "
                                    "ghosts of scheme domain"),
    (1, "verify yes", "verify yes is ignored with scheme gather (scheme auto on one rank)"),
    (2, "scheme gather verify yes", "verify yes is ignored with scheme gather;"),
    (2, "scheme domain verify yes", None),
    (2, "verify yes", None),
])
def test_verify_without_scheme_domain_is_ignored_with_a_warning(nprocs, keywords, warning):
    script = scene("p p fm", f"{nprocs} 1 1") + TAPPING.replace(
        "eta 1e-3", "eta 1e-3 " + keywords).format(eps=0.02, seed=1, every=1, taps=1)
    rc, out, _ = run_lammps(script, nprocs=nprocs, timeout=120)
    assert rc == 0, out
    if warning is None:
        assert "verify yes is ignored" not in out, out
    else:
        assert out.count("WARNING: fix mc/settle: " + warning) == 1, out


@pytest.mark.parametrize("keywords,message", [
    ("scheme tiles", "scheme = tiles must be 'auto' (gather on one rank, domain on several), "
                     "'gather' or 'domain'"),
    ("verify maybe", "fix mc/settle: verify = maybe must be 'yes' or 'no'"),
])
def test_bad_scheme_or_verify_is_refused(keywords, message):
    script = scene("p p fm", "1 1 1") + TAPPING.replace("eta 1e-3", "eta 1e-3 " + keywords) \
        .format(eps=0.02, seed=1, every=1, taps=1)
    rc, out, _ = run_lammps(script)
    assert rc != 0
    assert message in out


@pytest.mark.parametrize("atoms,message", [
    ("create_atoms 1 single 7.0 5.0 3.0\ncreate_atoms 1 single 7.5 5.0 3.0\n",
     "fix mc/settle: atoms 1 and 2 overlap by 0.5 at the start"),
    ("create_atoms 1 single 7.0 5.0 0.2\n",
     "fix mc/settle: atom 1 reaches 0.3 below the floor z0 = 0"),
])
def test_bad_start_is_reported_once_by_the_rank_that_finds_it(atoms, message):
    # The atoms sit in rank 1's half: every rank stops with rank 1's message, no hang.
    script = """processors 2 1 1
units lj
atom_style sphere
boundary p p fm
region box block 0 10 0 10 0 20
create_box 1 box
""" + atoms + """set group all diameter 1.0
fix settle all mc/settle 3 floor 0.0 scheme domain
run 1
"""
    rc, out, _ = run_lammps(script, nprocs=2, timeout=120)
    assert rc != 0
    assert message in out, out


@pytest.mark.parametrize("check", [1, 7, 300])
def test_a_check_below_one_sweep_makes_exactly_its_trials_per_cycle(check):
    # A cycle of rounds is one check: its trials are shared over the (round, rank) parts in
    # proportion to their active spheres and add up to the check exactly. (Each part rounding
    # its own share made 0 trials a cycle at check 1: the redeposition ran to the sweep cap
    # without a move.)
    script = scene("p p fm", "2 1 1") + DOMAIN_TAPPING.replace(
        "verify yes", f"check {check} maxsweeps 20").replace(
        "thermo_style custom step atoms f_settle[1] f_settle[2] f_settle[3] f_settle[4]",
        "thermo_style custom step atoms f_settle[5] f_settle[8]").replace(
        "thermo 10", "thermo 1").format(eps=0.05, seed=4928, every=4, taps=4)
    rc, out, _ = run_lammps(script, nprocs=2, timeout=120)
    assert rc == 0, out
    rows = thermo_table(out, "Atoms")[1][1:]
    assert len(rows) == 4, out
    trials, rounds = rows[:, 2], rows[:, 3]
    checks = rounds / 2  # 2 rounds a cycle (x split, y periodic on one rank)
    np.testing.assert_array_equal(trials, check * checks)
    assert (trials > 0).all(), rows


SWEEP_BED = """processors 2 1 1
units lj
atom_style sphere
boundary p p fm
region box block 0 8 0 8 0 30
create_box 1 box
create_packing 500 1 0.5 77 floor 0.0
fix tap all tapdilate 0.1 floor 0.0
fix settle all mc/settle 4928 floor 0.0 eta 1e-5 order sweep check 250 scheme domain
dump d all custom 1 dump.taps id x y z radius
dump_modify d sort id format float %.17g
run 3
"""


def test_order_sweep_below_one_sweep_reaches_every_sphere():
    # order sweep with a check of half a sweep: each round goes on in tag order from where its
    # sweep stopped, so every sphere is moved in each redeposition (about 150 sweeps a tap).
    # (A sweep restarted every round never reached the higher tags: 242 of 500 spheres stayed
    # where the tap had lifted them, and the bed dilated tap after tap.)
    rc, out, wd = run_lammps(SWEEP_BED, nprocs=2, timeout=120)
    assert rc == 0, out
    frames = read_dump(os.path.join(wd, "dump.taps"))
    assert len(frames) == 4
    for (_, _, _, before), (step, _, _, after) in zip(frames, frames[1:]):
        untouched = ((before["x"] == after["x"]) & (before["y"] == after["y"])
                     & np.isclose(after["z"], 1.1 * before["z"], rtol=0.0, atol=1e-12))
        assert untouched.sum() == 0, (step, before["id"][untouched])


SHORT_BED_Z_SPLIT = """processors 1 1 2
units lj
atom_style sphere
boundary p p fs
region box block 0 8 0 8 0 30
create_box 1 box
create_packing 400 1 0.5 77 floor 0.0
fix tap all tapdilate 0.1 floor 0.0
fix settle all mc/settle 4928 floor 0.0 eta 1e-4 scheme domain
thermo 1
run 3
"""


def test_a_shrink_wrapped_bed_too_short_for_a_z_split_is_refused_before_the_first_tap():
    # The box top follows the bed (6.6 tall at rest: two z sub-domains of 3.3, below the 3.6
    # needed). The dilated box of the first tap was wide enough, so the run used to stop at a
    # ghost rebuild in a later redeposition; the setup now checks the bed at rest.
    rc, out, _ = run_lammps(SHORT_BED_Z_SPLIT, nprocs=2, timeout=120)
    assert rc != 0
    assert ("the narrowest sub-domain along z is 3.3" in out
            and "the top is shrink-wrapped, so the 2 sub-domains along z share the bed's height"
            in out), out
    assert not any(line.split()[:1] == ["Step"] for line in out.splitlines()), out
    # A fixed top keeps the sub-domains the box's: the same bed runs.
    rc, out, _ = run_lammps(SHORT_BED_Z_SPLIT.replace("p p fs", "p p f"), nprocs=2, timeout=120)
    assert rc == 0, out


def test_timings_are_rank_zeros_on_every_rank():
    """[9]-[12] are rank 0's seconds on every rank: each rank's own differed, and an 'if' on
    them sent rank 0 on and rank 1 into another run (a hang). Per-atom copies of each value,
    reduced to their minimum and maximum over the atoms of both ranks, agree at every tap."""
    columns = " ".join(f"c_lo{k} c_hi{k}" for k in range(9, 13))
    defines = "".join(f"variable t{k} equal f_settle[{k}]\nvariable own{k} atom v_t{k}\n"
                      f"compute lo{k} all reduce min v_own{k}\n"
                      f"compute hi{k} all reduce max v_own{k}\n" for k in range(9, 13))
    script = scene("p p fm", "2 1 1") + defines + f"""fix tap all tapdilate 0.05 floor 0.0
fix settle all mc/settle 4928 floor 0.0 eta 1e-3 scheme domain
thermo_style custom step {columns}
thermo 1
run 4
"""
    rc, out, _ = run_lammps(script, nprocs=2, timeout=300)
    assert rc == 0, out
    rows = thermo_table(out, "c_lo9")[1][1:]
    assert len(rows) == 4, out
    assert (rows[:, 1] > 0).all(), rows  # the trial moves take time
    np.testing.assert_array_equal(rows[:, 1::2], rows[:, 2::2])


def test_a_sphere_of_radius_zero_outside_the_group_is_named_by_its_id():
    """A fixed obstacle of radius 0 passed the group's check and stopped each rank in the
    kernel, with its internal index and MPI_Abort; now every rank names the atom's ID."""
    script = scene("p p fm", "2 1 1") + """set atom 5 diameter 0.0
group up id > 5
fix settle up mc/settle 4928 floor 0.0 scheme domain
run 1
"""
    rc, out, _ = run_lammps(script, nprocs=2, timeout=120)
    assert rc != 0 and "ERROR: fix mc/settle: atom 5 has radius 0; every sphere needs a " \
        "radius > 0" in out, out
    assert "MPI_Abort" not in out and "ERROR on proc" not in out, out


def test_a_step_of_a_whole_period_is_refused_when_the_fix_is_defined():
    """dmax >= a periodic length with one rank along it stopped only after the first tap's
    thermo, on each rank, without the fix's name."""
    script = """units lj
atom_style sphere
boundary p p fm
processors 2 1 1
region box block 0 20 0 1.2 0 40
create_box 1 box
create_atoms 1 single 5 0.6 1
create_atoms 1 single 15 0.6 1
set group all diameter 1.0
fix settle all mc/settle 4928 floor 0.0 dmax 1.5
"""
    rc, out, _ = run_lammps(script, nprocs=2, timeout=120)
    assert rc != 0 and "ERROR: fix mc/settle: dmax = 1.5 is outside the allowed range (0, " \
        "periodic length along y) = (0, 1.2)" in out, out
    assert "Last command: fix settle" in out, out


def test_the_trajectory_follows_the_sub_domains_not_the_ranks_that_hold_them():
    """The trial moves of a sub-domain are keyed by its place in the grid: 'map xyz' puts other
    ranks on the sub-domains of a 2 x 2 grid than the default 'map cart', and used to give
    another trajectory for the same grid and seed."""
    dumps = []
    for mapping in ("cart", "xyz"):
        script = scene("p p fm", f"2 2 1 map {mapping}") + DOMAIN_TAPPING.format(
            eps=0.02, seed=4928, every=1, taps=4)
        rc, out, wd = run_lammps(script, nprocs=4)
        assert rc == 0 and "2 by 2 by 1 MPI processor grid" in out, out
        dumps.append(read_dump(os.path.join(wd, "dump.taps")))
    assert len(dumps[0]) == 5
    for (_, _, _, a), (_, _, _, b) in zip(*dumps):
        for col in ("x", "y", "z"):
            np.testing.assert_array_equal(a[col], b[col])
