# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# fix tapdilate + fix mc/settle run by lmp_tapmc as a child process, serial and under mpirun:
# seed reproducibility, exact restart round trip (serial, and scheme domain on 2 ranks), fix
# order, tap steps, narrow theta0, restart settings. The all-pairs oracle on 1, 2 and 4 ranks is
# test_mc_settle_ranks.py (its own ctest entry, so that no single entry runs much over a minute).
import functools
import os
import struct

import numpy as np
import pytest

from lmprun import dump_atoms_text, min_gap, read_dump, run_lammps, written_restart

CONTACT_TOL = 1e-10  # defaults::kContactTolerance (relative to the contact distance)

# 1024 spheres of diameter 1 on a dilute simple cubic lattice (spacing 1.25) in a 10 x 10 box:
# the first redeposition settles them into a packing, the taps then compact it.
SCENE = """units lj
atom_style sphere
boundary {boundary}
processors * * {zprocs}
region box block 0 10 0 10 0 40
create_box 1 box
lattice sc 0.512 origin 0.5 0.5 0.5
region fill block 0 10 0 10 0.6 20.6 units box
create_atoms 1 region fill
reset_atom_ids sort yes
set group all diameter 1.0
"""

TAPPING = """fix tap all tapdilate {eps} floor 0.0
fix settle all mc/settle {seed} floor 0.0 eta 1e-3
thermo_style custom step atoms f_settle[1] f_settle[2] f_settle[3] f_settle[4]
thermo 10
thermo_modify lost error
dump d all custom {every} dump.taps id x y z radius xu yu
dump_modify d sort id format float %.17g
run {taps}
"""


def tapping_run(boundary, nprocs, taps=100, eps=0.02, seed=4928, every=1, workdir=None,
                scheme="auto"):
    script = SCENE.format(boundary=boundary, zprocs=1) + TAPPING.replace(
        "eta 1e-3", f"eta 1e-3 scheme {scheme}").format(eps=eps, seed=seed, every=every,
                                                         taps=taps)
    rc, out, wd = run_lammps(script, nprocs=nprocs, workdir=workdir)
    assert rc == 0, out
    return read_dump(os.path.join(wd, "dump.taps")), out


@functools.lru_cache(maxsize=None)
def serial_run(boundary, taps):
    return tapping_run(boundary, 1, taps=taps)[0]


def check_frames(frames, periodic_xy, walls):
    for step, box, _, cols in frames:
        assert len(cols["id"]) == 1024, f"step {step}: atom count {len(cols['id'])}"
        assert np.array_equal(cols["id"], np.arange(1, 1025))
        xyz = np.column_stack([cols["x"], cols["y"], cols["z"]])
        radius = cols["radius"]
        gap, i, j = min_gap(xyz, radius, box, periodic_xy, floor=0.0)
        assert gap >= -CONTACT_TOL * 1.0, f"step {step}: gap {gap} between {i} and {j}"
        for dim in range(2):
            if walls[dim]:
                assert (xyz[:, dim] - radius).min() >= -CONTACT_TOL, f"step {step}: wall {dim}"
                assert (xyz[:, dim] + radius).max() <= 10 + CONTACT_TOL, f"step {step}: wall {dim}"
    # Image flags follow every periodic wrap: unwrapped positions (when dumped) never jump by a
    # box length between frames.
    for dim, c in ((0, "xu"), (1, "yu")):
        if periodic_xy[dim] and c in frames[0][3]:
            for (step, _, _, a), (_, _, _, b) in zip(frames[:-1], frames[1:]):
                assert np.abs(b[c] - a[c]).max() < 5.0, f"step {step}: {c} jumps"


def test_same_seed_same_trajectory_other_seed_differs():
    a, _ = tapping_run("p p fm", 1, taps=5)
    b, _ = tapping_run("p p fm", 1, taps=5)
    c, _ = tapping_run("p p fm", 1, taps=5, seed=4929)
    np.testing.assert_array_equal(a[-1][3]["z"], b[-1][3]["z"])
    assert not np.array_equal(a[-1][3]["z"], c[-1][3]["z"])


FINAL_DUMP = ("write_dump all custom final.dump id x y z ix iy iz modify sort id "
              "format float %.17g\n")


@pytest.mark.parametrize("nprocs,grid,scheme,eps,seed,taps", [
    pytest.param(1, "* * 1", "", 0.05, 11, 12, id="serial"),
    pytest.param(2, "2 1 1", " scheme domain", 0.02, 31, 6, id="domain_2_ranks"),
    pytest.param(1, "* * 1", " theta_law solid theta0 3", 0.05, 11, 12, id="serial_solid_law"),
    pytest.param(2, "2 1 1", " scheme domain theta_law linear", 0.02, 31, 6,
                 id="domain_2_ranks_linear_law"),
])
def test_restart_round_trip_is_exact(tmp_path, nprocs, grid, scheme, eps, seed, taps):
    # Uninterrupted: `taps` taps. Interrupted: half of them, write_restart, then a new process
    # on the same ranks and grid reads the restart and does the other half. Positions and image
    # flags must be identical bit for bit, serial and with the domain-decomposed scheme.
    scene = SCENE.format(boundary="p p fm", zprocs=1).replace("processors * * 1",
                                                              f"processors {grid}")
    tapping = (TAPPING.replace("eta 1e-3", "eta 1e-3" + scheme)
               .replace("dump d all custom {every} dump.taps id x y z radius xu yu\n", "")
               .replace("dump_modify d sort id format float %.17g\n", ""))
    assert "dump" not in tapping

    def taps_of(n):
        return tapping.format(eps=eps, seed=seed, taps=n)

    rc, out, wd_full = run_lammps(scene + taps_of(taps) + FINAL_DUMP, nprocs=nprocs)
    assert rc == 0, out
    wd = str(tmp_path)
    first = scene + taps_of(taps // 2) + "write_restart half.restart\n"
    rc, out, _ = run_lammps(first, nprocs=nprocs, workdir=wd)
    assert rc == 0, out
    second = (f"processors {grid}\nread_restart half.restart\n" + taps_of(taps - taps // 2)
              + FINAL_DUMP)
    rc, out, _ = run_lammps(second, nprocs=nprocs, workdir=wd)
    assert rc == 0, out
    assert "differ from the restart file" not in out, out
    assert dump_atoms_text(wd_full) == dump_atoms_text(wd)


def test_a_restart_read_on_another_grid_by_scheme_domain_is_named(tmp_path):
    # scheme domain redeposits sub-domain by sub-domain: a restart read without 'processors'
    # (LAMMPS picks 1 2 1 here) or on another grid continues another trajectory, said once with
    # both grids; scheme gather (the same trajectory on any grid) stores no grid.
    scene = SCENE.format(boundary="p p fm", zprocs=1).replace("processors * * 1",
                                                              "processors 2 1 1")
    settle = TAPPING.replace("eta 1e-3", "eta 1e-3 scheme domain").split("dump d")[0]
    wd = str(tmp_path)
    rc, out, _ = run_lammps(scene + settle.format(eps=0.02, seed=31) + "run 2\n"
                            "write_restart half.restart\n", nprocs=2, workdir=wd)
    assert rc == 0, out
    again = "processors {}\nread_restart half.restart\n" + settle.format(eps=0.02, seed=31) + \
        "run 1\n"
    rc, out, _ = run_lammps(again.format("1 2 1"), nprocs=2, workdir=wd)
    assert rc == 0, out
    assert ("settings differ from the restart file (restart -> now): processors x (0 = scheme "
            "gather, any grid) 2 -> 1, processors y 1 -> 2; the run will not continue") in out, out
    rc, out, _ = run_lammps(again.format("2 1 1").replace("scheme domain", "scheme gather"),
                            nprocs=2, workdir=wd)
    assert rc == 0, out
    assert "processors x (0 = scheme gather, any grid) 2 -> 0, processors y 1 -> 0, " \
           "processors z 1 -> 0;" in out, out


def test_polydisperse_and_fixed_obstacles():
    # Radii uniform in [0.35, 0.65] from create_packing; the spheres of the bottom layer (z < 1)
    # are not in the group: obstacles that never move and are never overlapped.
    script = """units lj
atom_style sphere
boundary p p fm
region box block 0 8 0 8 0 30
create_box 1 box
create_packing 400 1 0.5 77 floor 0.0 dispersity 0.3
group bottom variable low
group grains subtract all bottom
fix tap grains tapdilate 0.05 floor 0.0
fix settle grains mc/settle 5 floor 0.0 eta 1e-4
dump d all custom 1 dump.taps id x y z radius
dump_modify d sort id format float %.17g
thermo_modify lost error
run 30
""".replace("group bottom variable low", "variable low atom z<1.0\ngroup bottom variable low")
    rc, out, wd = run_lammps(script)
    assert rc == 0, out
    frames = read_dump(os.path.join(wd, "dump.taps"))
    first = frames[0][3]
    bottom = first["z"] < 1.0
    assert 0 < bottom.sum() < len(bottom)
    assert first["radius"].min() < 0.4 and first["radius"].max() > 0.6
    for step, box, _, cols in frames:
        xyz = np.column_stack([cols["x"], cols["y"], cols["z"]])
        gap, i, j = min_gap(xyz, cols["radius"], box, (True, True), floor=0.0)
        assert gap >= -CONTACT_TOL * 1.3, f"step {step}: gap {gap} between {i} and {j}"
        for c in ("x", "y", "z"):
            np.testing.assert_array_equal(cols[c][bottom], first[c][bottom])
    assert frames[-1][3]["z"][~bottom].mean() < first["z"][~bottom].mean() * 1.05


def small_run(fix_lines, steps, extra="", boundary="p p fm"):
    script = SCENE.format(boundary=boundary, zprocs=1) + fix_lines + """
thermo_style custom step f_settle[1] f_settle[5]
thermo 1
dump d all custom 1 dump.taps id x y z
dump_modify d sort id format float %.17g
""" + extra + f"run {steps}\n"
    rc, out, wd = run_lammps(script)
    assert rc == 0, out
    return read_dump(os.path.join(wd, "dump.taps")), out


def test_fix_order_does_not_matter():
    # mc/settle defined before tapdilate still redeposits after the tap of the same step.
    tap = "fix tap all tapdilate 0.05 floor 0.0\n"
    settle = "fix settle all mc/settle 7 floor 0.0 eta 1e-3\n"
    a, _ = small_run(tap + settle, 3)
    b, _ = small_run(settle + tap, 3)
    for (sa, _, _, fa), (sb, _, _, fb) in zip(a, b):
        assert sa == sb
        for c in ("x", "y", "z"):
            np.testing.assert_array_equal(fa[c], fb[c])


def test_settle_runs_only_on_tap_steps():
    # Taps every 2 steps: nothing moves on odd steps (no tap, no redeposition); even steps tap
    # and redeposit. Without tapdilate, mc/settle redeposits on every step.
    frames, out = small_run("fix tap all tapdilate 0.05 floor 0.0 every 2\n"
                            "fix settle all mc/settle 7 floor 0.0 eta 1e-3\n", 5)
    assert [f[0] for f in frames] == [0, 1, 2, 3, 4, 5]
    for k in range(1, 6):
        moved = not np.array_equal(frames[k][3]["z"], frames[k - 1][3]["z"])
        assert moved == (k % 2 == 0), k
    alone, _ = small_run("fix settle all mc/settle 7 floor 0.0 eta 1e-3\n", 3)
    for k in range(1, 4):
        assert not np.array_equal(alone[k][3]["z"], alone[k - 1][3]["z"]), k
    assert "Atom sorting therefore disabled" not in out, out


@pytest.mark.parametrize("fixes", [
    "fix tap all tapdilate 0.05 floor 0.0\nfix settle all mc/settle 7 floor 0.0 eta 1e-3\n",
    "fix settle all mc/settle 7 floor 0.0 eta 1e-3\nfix tap all tapdilate 0.05 floor 0.0 every 2\n",
    "fix settle all mc/settle 7 floor 0.0 eta 1e-3\n",
], ids=["tap-every-step", "tap-every-2", "settle-alone"])
@pytest.mark.parametrize("reset", [100, 1, 0])
def test_a_run_without_setup_after_reset_timestep_taps_as_one_with_it(fixes, reset):
    """'run N pre no' calls no setup hook of the fixes: after reset_timestep the last run's
    schedule (the step after its end) never met the new steps (reset forward: no tap at all) or
    met them late (reset back: the first taps skipped), silently. The tap and redeposition steps
    now follow the step itself: the run is the one 'pre yes' gives, move for move."""
    runs = {}
    for pre in ("yes", "no"):
        script = SCENE.format(boundary="p p fm", zprocs=1) + fixes + (
            "thermo_style custom step f_settle[5]\nthermo 1\nrun 2\n"
            f"reset_timestep {reset}\nrun 4 pre {pre}\n"
            "write_dump all custom final.dump id x y z modify sort id format float %.17g\n")
        rc, out, wd = run_lammps(script)
        assert rc == 0, out
        runs[pre] = dump_atoms_text(wd), out
    assert runs["no"][0] == runs["yes"][0]

    def trials_after_reset(out):  # f_settle[5] of the second run: each step's trials
        rows = [line.split() for line in out.split("Step f_settle[5]")[2].splitlines()]
        return [int(r[1]) for r in rows if len(r) == 2 and r[0].isdigit() and int(r[0]) > reset]
    # the same redepositions step by step (before, 'pre no' repeated the last run's count)
    assert trials_after_reset(runs["no"][1]) == trials_after_reset(runs["yes"][1])
    assert len(trials_after_reset(runs["no"][1])) == 4


@pytest.mark.parametrize("theta0", [0.1, 0.01])
def test_narrow_theta0_taps_keep_hard_spheres(theta0):
    # Small theta0 (nearly vertical moves, the paper's decompacting regime): every tap ends
    # with a valid packing, and the redeposition still settles the dilute start (its columns
    # close their vertical gaps of 0.25: <Z> falls from 10 towards 8).
    frames, out = small_run(f"fix tap all tapdilate 0.05 floor 0.0\n"
                            f"fix settle all mc/settle 9 floor 0.0 eta 1e-3 theta0 {theta0}\n", 10)
    check_frames([(s, b, h, dict(c, radius=np.full(1024, 0.5))) for s, b, h, c in frames],
                 (True, True), (False, False))
    assert frames[-1][3]["z"].mean() < 0.9 * frames[0][3]["z"].mean()


def test_restart_with_changed_settings_warns_naming_them():
    wd, same = written_restart(SCENE.format(boundary="p p fm", zprocs=1),
                               "tapdilate 0.05 floor 0.0", "mc/settle 11 floor 0.0 eta 1e-3",
                               taps=2)
    rc, out, _ = run_lammps(same, workdir=wd)
    assert rc == 0 and "differ from the restart file" not in out, out
    changed = same.replace("eta 1e-3", "eta 1e-4 theta0 0.5 dmax 0.05 order sweep")
    rc, out, _ = run_lammps(changed, workdir=wd)
    assert rc == 0, out
    assert "WARNING: fix mc/settle: settings differ from the restart file (restart -> now): " \
           "dmax (0 = default R/5) 0 -> 0.05, theta0 0.7853981633974483 -> 0.5, " \
           "eta 0.001 -> 0.0001, order (0 random, 1 sweep) 0 -> 1" in out, out
    rc, out, _ = run_lammps(same.replace("mc/settle 11", "mc/settle 12"), workdir=wd)
    assert rc == 0 and "seed 11 -> 12" in out, out
    # the value a default stands for, written out, is the same setting: dmax R/5 = 0.1 (it
    # read "0 -> 0.1; the run will not continue the original trajectory", which it did)
    rc, out, _ = run_lammps(same.replace("eta 1e-3", "eta 1e-3 dmax 0.1"), workdir=wd)
    assert rc == 0 and "differ from the restart file" not in out, out


def test_restart_compares_walls_by_the_planes_they_stand_for():
    """xwalls/ywalls on the box faces and the default walls (the box faces) are the same walls
    (the resumed run equals the uninterrupted one); other planes are named."""
    wd, walls = written_restart(SCENE.format(boundary="f f fm", zprocs=1),
                                "tapdilate 0.05 floor 0.0",
                                "mc/settle 11 floor 0.0 eta 1e-3 xwalls 0 10 ywalls 0 10", taps=2)
    default = walls.replace(" xwalls 0 10 ywalls 0 10", "")
    rc, out, _ = run_lammps(default, workdir=wd)
    assert rc == 0 and "differ from the restart file" not in out, out
    rc, out, _ = run_lammps(default.replace("eta 1e-3", "eta 1e-3 xwalls 0 9.9"), workdir=wd)
    assert "settings differ from the restart file (restart -> now): xwalls hi 10 -> 9.9" in out


def test_tap_outputs_continue_across_a_restart():
    # fix tapdilate keeps the eps of its latest tap in the restart file: a resumed run outputs
    # it before its own first tap (fix print of the restart step, thermo), as an uninterrupted
    # run would; a sequence whose eps varies (the ramp of Fig. 4) keeps its sqrt(eps) column.
    base = SCENE.format(boundary="p p fm", zprocs=1)
    fixes = ("variable e equal 0.01*step\n"
             "fix tap all tapdilate v_e floor 0.0\n"
             "fix settle all mc/settle 13 floor 0.0 eta 1e-3\n"
             "thermo_style custom step f_tap[1] f_tap[2]\nthermo_modify format float %.17g\n")
    rc, out, wd = run_lammps(base + fixes + "run 3\nwrite_restart a.restart\n")
    assert rc == 0, out
    assert last_thermo_row(out) == [0.03, np.sqrt(0.03)]
    rc, out, _ = run_lammps("read_restart a.restart\n" + fixes + "run 0\n", workdir=wd)
    assert rc == 0, out
    assert last_thermo_row(out) == [0.03, np.sqrt(0.03)]
    rc, out, _ = run_lammps("read_restart a.restart\n" + fixes + "run 1\n", workdir=wd)
    assert rc == 0, out
    assert last_thermo_row(out) == [0.04, 0.2]
    # a fix of another ID does not take the record: before its first tap it outputs 0
    rc, out, _ = run_lammps("read_restart a.restart\n" + fixes.replace("fix tap ", "fix tap2 ")
                            .replace("f_tap[", "f_tap2[") + "run 0\n", workdir=wd)
    assert rc == 0, out
    assert last_thermo_row(out) == [0.0, 0.0]


# The restart record of fix mc/settle (fix_mc_settle.cpp): an int byte count, then doubles:
# layout -5 (today's): -5, seed as two 32-bit halves, dmax, theta0, eta, check, maxsweeps,
# floor, diameter/2, order, xwalls lo hi, ywalls lo hi (NaN: none), stop, window, theta_law,
# the processor grid (x, y, z; 0 0 0 with scheme gather), then the diagnostics [1]-[6];
# layout -4 (before the grid): the same without it; layout -3 (before 'theta_law'): without
# theta_law too; layout -2 (before 'stop' and 'window'): without those three; seed only (the
# first runs): seed, diagnostics.
RECORD_DOUBLES = 1 + 2 + 18 + 6


def restart_record(data):
    """(offset of the byte count, the doubles) of the fix mc/settle record in restart bytes."""
    head = struct.pack("<i", 8 * RECORD_DOUBLES) + struct.pack("<d", -5.0)
    at = data.find(head)
    assert at >= 0 and data.find(head, at + 1) < 0
    return at, struct.unpack_from(f"<{RECORD_DOUBLES}d", data, at + 4)


def with_record(data, at, values):
    """The restart bytes with the record at `at` replaced by `values` (its byte count too)."""
    end = at + 4 + 8 * RECORD_DOUBLES
    return data[:at] + struct.pack(f"<i{len(values)}d", 8 * len(values), *values) + data[end:]


DIAGNOSTICS = "f_settle[1] f_settle[2] f_settle[3] f_settle[4] f_settle[5] f_settle[6]"


def last_thermo_row(out):
    """The values after Step of the last thermo row of the last run."""
    rows = [line.split() for line in out.splitlines()]
    header = max(i for i, r in enumerate(rows) if r[:1] == ["Step"])
    last = header + 1
    while rows[last + 1][:1] and rows[last + 1][0].isdigit():
        last += 1
    return [float(v) for v in rows[last][1:]]


def test_restart_record_layout_and_older_layouts_are_read():
    # Today's record holds exactly the documented fields, so files stay byte for byte what the
    # layout says; records of the four older layouts (written here from today's by dropping
    # fields, as those versions wrote them) are read: the diagnostics come back, the settings
    # they did not store are taken as those versions ran them ('theta_law angle',
    # 'stop change', window 32).
    base = SCENE.format(boundary="f p fm", zprocs=1)
    settle = ("fix tap all tapdilate 0.05 floor 0.0\n"
              "fix settle all mc/settle 8589934597 floor 0.0 eta 1e-3 xwalls 0 10 check 700\n"
              f"thermo_style custom step {DIAGNOSTICS}\nthermo_modify format float %.17g\n")
    rc, out, wd = run_lammps(base + settle + "run 2\nwrite_restart a.restart\n")
    assert rc == 0, out
    diagnostics = last_thermo_row(out)
    with open(os.path.join(wd, "a.restart"), "rb") as f:
        data = f.read()
    at, record = restart_record(data)
    settings = [0.0, np.pi / 4, 1e-3, 700, 50000, 0.0, 0.0, 0, 0.0, 10.0]
    assert record[:3] == (-5.0, 2.0, 5.0)  # 8589934597 = 2 * 2^32 + 5
    assert list(record[3:13]) == settings
    assert np.isnan(record[13:15]).all()  # no ywalls
    assert record[15:17] == (0.0, 32.0)   # stop change, window 32
    assert record[17] == 0.0              # theta_law angle
    assert record[18:21] == (0.0, 0.0, 0.0)  # scheme gather: any grid
    assert list(record[21:]) == diagnostics

    no_grid = (-4.0,) + record[1:18] + record[21:]
    no_law = (-3.0,) + record[1:17] + record[21:]
    no_stop = (-2.0,) + record[1:15] + record[21:]
    seed_only = (float(8589934597),) + record[21:]
    for name, values in (("no_grid", no_grid), ("no_law", no_law), ("no_stop", no_stop),
                         ("seed_only", seed_only)):
        with open(os.path.join(wd, name + ".restart"), "wb") as f:
            f.write(with_record(data, at, values))
        again = (f"read_restart {name}.restart\n" + settle + "run 0\n")
        rc, out, _ = run_lammps(again, workdir=wd)
        assert rc == 0, out
        assert "differ from the restart file" not in out, out
        assert last_thermo_row(out) == diagnostics, name
    for name in ("a", "no_grid", "no_law", "no_stop"):
        rc, out, _ = run_lammps(f"read_restart {name}.restart\n" + settle.replace(
            "check 700", "check 700 theta_law solid") + "run 0\n", workdir=wd)
        assert rc == 0, out
        assert "settings differ from the restart file (restart -> now): theta_law (0 angle, " \
               "1 solid, 2 exponential, 3 linear) 0 -> 1;" in out, (name, out)
    rc, out, _ = run_lammps("read_restart no_stop.restart\n" + settle.replace(
        "check 700", "check 700 stop drift") + "run 0\n", workdir=wd)
    assert rc == 0, out
    assert "settings differ from the restart file (restart -> now): stop (0 change, 1 drift) " \
           "0 -> 1;" in out, out
    rc, out, _ = run_lammps("read_restart seed_only.restart\n" + settle.replace(
        "8589934597", "7") + "run 0\n", workdir=wd)
    assert rc == 0, out
    assert "settings differ from the restart file (restart -> now): seed 8589934597 -> 7;" \
        in out, out
    # a solid-law record read back with the solid law: nothing differs
    rc, out, wd2 = run_lammps(base + settle.replace("check 700", "check 700 theta_law solid") +
                              "run 1\nwrite_restart s.restart\n")
    assert rc == 0, out
    assert restart_record(open(os.path.join(wd2, "s.restart"), "rb").read())[1][17] == 1.0
    rc, out, _ = run_lammps("read_restart s.restart\n" + settle.replace(
        "check 700", "check 700 theta_law solid") + "run 0\n", workdir=wd2)
    assert rc == 0 and "differ from the restart file" not in out, out
    # ... and with the exponential law: the record names the change
    rc, out, _ = run_lammps("read_restart s.restart\n" + settle.replace(
        "check 700", "check 700 theta_law exponential") + "run 0\n", workdir=wd2)
    assert rc == 0, out
    assert "theta_law (0 angle, 1 solid, 2 exponential, 3 linear) 1 -> 2;" in out, out


# A restart file of layout -3 (before 'theta_law') written by a real campaign run and kept in
# the repository (tests/python/data/campaign_before_checksums: seed 1, eta 1e-5, the default
# theta0): read today, it implies 'theta_law angle' and gives back its diagnostics.
OLD_LAYOUT_RESTART = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python",
                                  "data", "campaign_before_checksums", "runs", "pbc_s1",
                                  "restart.2")


def test_committed_restart_of_the_layout_before_theta_law_is_read():
    settle = ("fix settle all mc/settle 1 floor 0.0 eta 1e-5{}\n"
              f"thermo_style custom step {DIAGNOSTICS}\nthermo_modify format float %.17g\n"
              "run 0\n")
    read = f"read_restart {os.path.abspath(OLD_LAYOUT_RESTART)}\n"
    rc, out, _ = run_lammps(read + settle.format(""))
    assert rc == 0, out
    assert "differ from the restart file" not in out, out
    assert last_thermo_row(out) == [12.0, 0.057291666666666664, 2.064252000189685, 0.0, 768.0,
                                    2.066831549236659]
    rc, out, _ = run_lammps(read + settle.format(" theta_law solid"))
    assert rc == 0, out
    assert "settings differ from the restart file (restart -> now): theta_law (0 angle, " \
           "1 solid, 2 exponential, 3 linear) 0 -> 1;" in out, out