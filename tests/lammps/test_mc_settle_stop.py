# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# fix mc/settle's stopping rule keywords ('stop change' / 'stop drift', 'window'), run by
# lmp_tapmc as a child process: the default is the paper's rule, the drift rule stops only after
# a full window, bad values stop with a message naming keyword, value and range, and restart
# files keep the rule.
import os

import numpy as np
import pytest

from lmprun import read_dump, run_lammps, thermo_table, written_restart

# 294 spheres of diameter 1 on a simple cubic lattice (spacing 1.1, 7 x 7 x 6) in an 8 x 8 box.
SCENE = """units lj
atom_style sphere
boundary p p fm
region box block 0 8 0 8 0 30
create_box 1 box
lattice sc 0.751314800901578 origin 0.5 0.5 0.5
region fill block 0 8 0 8 0.5 7 units box
create_atoms 1 region fill
reset_atom_ids sort yes
set group all diameter 1.0
"""

RUN = """fix tap all tapdilate 0.02 floor 0.0
fix settle all mc/settle 31 floor 0.0 {keywords}
thermo_style custom step f_settle[1] f_settle[4] f_settle[5]
thermo 1
thermo_modify format float %.10g
dump d all custom 1 dump.taps id x y z
dump_modify d sort id format float %.17g
run {taps}
"""


def tapping(keywords, taps=3):
    rc, out, wd = run_lammps(SCENE + RUN.format(keywords=keywords, taps=taps))
    assert rc == 0, out
    sweeps = []
    header = None
    for line in open(os.path.join(wd, "log.lammps")):
        words = line.split()
        if words[:1] == ["Step"]:
            header = words
        elif header and len(words) == len(header) and words[0].isdigit() and int(words[0]) > 0:
            sweeps.append((float(words[1]), float(words[2])))
        elif line.startswith("Loop time"):
            header = None
    return read_dump(os.path.join(wd, "dump.taps")), sweeps


def test_stop_change_is_the_default_and_drift_waits_for_its_window():
    default, _ = tapping("eta 1e-4")
    change, _ = tapping("eta 1e-4 stop change")
    for (sa, _, _, fa), (sb, _, _, fb) in zip(default, change):
        assert sa == sb
        np.testing.assert_array_equal(fa["z"], fb["z"])
    drift, sweeps = tapping("eta 1e-4 stop drift window 12")
    assert len(sweeps) == 3
    for used, capped in sweeps:
        assert capped == 0
        assert used >= 12  # one check per sweep: never before the window of 12 checks is full
    assert not np.array_equal(drift[-1][3]["z"], change[-1][3]["z"])
    # A window longer than the sweep cap can never fill (every tap ended at the cap, warning
    # each time): refused at the first redeposition. A window of the whole cap may stop at it.
    rc, out, _ = run_lammps(SCENE + RUN.format(
        keywords="eta 1e-4 stop drift window 50 maxsweeps 20", taps=1))
    assert rc != 0 and "window = 50 checks of 'stop drift' is more than the cap allows (20 " \
        "checks" in out, out
    _, sweeps = tapping("eta 1e-4 stop drift window 20 maxsweeps 20", taps=1)
    assert sweeps[0][0] == 20.0


BOX = """units lj
atom_style sphere
boundary p p fm
region box block 0 8 0 8 0 10
create_box 1 box
create_atoms 1 single 2 2 1
set group all diameter 1.0
"""

BAD = [
    ("stop bogus", "stop = bogus must be 'change' (the paper's rule) or 'drift'"),
    ("stop 3", "stop = 3 must be 'change'"),
    ("stop", "keyword 'stop' needs 1 value(s)"),
    ("stop drift window 1", "window = 1 is outside the allowed range [2, 100000]"),
    ("window 0", "window = 0 is outside the allowed range [2, 100000]"),
    ("stop drift window -4", "window = -4 is outside the allowed range [2, 100000]"),
    ("stop drift window 100001", "window = 100001 is outside the allowed range [2, 100000]"),
    ("stop drift window 2.5", "2.5"),
    ("stop drift window", "keyword 'window' needs 1 value(s)"),
]


@pytest.mark.parametrize("keywords,message", BAD)
def test_bad_stop_values_stop_with_a_message_naming_them(keywords, message):
    rc, out, _ = run_lammps(BOX + f"fix s all mc/settle 1 {keywords}\nrun 1\n")
    assert rc != 0, out
    assert "ERROR" in out and message in out, out


def test_restart_keeps_the_stop_rule():
    wd, same = written_restart(SCENE, "tapdilate 0.02 floor 0.0",
                               "mc/settle 11 floor 0.0 eta 1e-4 stop drift window 16")
    rc, out, _ = run_lammps(same, workdir=wd)
    assert rc == 0 and "differ from the restart file" not in out, out
    rc, out, _ = run_lammps(same.replace(" stop drift window 16", ""), workdir=wd)
    assert rc == 0, out
    assert "WARNING: fix mc/settle: settings differ from the restart file (restart -> now): " \
           "stop (0 change, 1 drift) 1 -> 0, window 16 -> 32;" in out, out


def test_window_without_stop_drift_is_ignored_with_a_warning():
    warning = "WARNING: fix mc/settle: window = 12 is ignored with 'stop change' (the default)"
    plain, _ = tapping("eta 1e-3", taps=2)
    for keywords in ("eta 1e-3 window 12", "eta 1e-3 stop change window 12"):
        rc, out, wd = run_lammps(SCENE + RUN.format(keywords=keywords, taps=2))
        assert rc == 0 and out.count(warning) == 1, out
        frames = read_dump(os.path.join(wd, "dump.taps"))  # ignored indeed: the same taps
        for (_, _, _, a), (_, _, _, b) in zip(plain, frames):
            np.testing.assert_array_equal(a["z"], b["z"])
    rc, out, _ = run_lammps(SCENE + RUN.format(keywords="eta 1e-3 stop drift window 12", taps=1))
    assert rc == 0 and "is ignored" not in out, out


def narrow_bed(boundary, width, spheres, outputs, taps):
    """A bed of ``spheres`` of diameter 1 in a ``width`` x ``width`` box, tapped ``taps`` times
    at eps 0.01 (fix mc/settle's keywords: the template's {keywords}), thermo of ``outputs``."""
    return f"""units lj
atom_style sphere
boundary {boundary}
region box block 0 {width} 0 {width} 0 40
create_box 1 box
create_packing {spheres} 1 0.5 4928 floor 0.0
fix tap all tapdilate 0.01 floor 0.0
fix settle all mc/settle 4928 floor 0.0 {{keywords}}
thermo_style custom step {outputs}
thermo 1
thermo_modify format float %.12g
run {taps}
"""


# 16 spheres in a 2 x 2 periodic box: one accepted move changes <Z> by about 1e-3 of itself, far
# more than eta = 1e-7, so the paper's rule stops only at a check (16 trials) that accepts none.
SMALL_BED = narrow_bed("p p fm", 2, 16, "f_settle[1] f_settle[13]", 6)
IDLE_STOP = "which none of its 16 trials was accepted. 'stop change' reads an unchanged <Z>"


@pytest.mark.parametrize("nprocs,scheme", [(1, "gather"), (2, "domain")])
def test_a_stop_at_an_idle_check_warns_once(nprocs, scheme):
    rc, out, _ = run_lammps(SMALL_BED.format(keywords=f"scheme {scheme}"), nprocs=nprocs)
    assert rc == 0, out
    assert out.count(IDLE_STOP) == 1, out
    assert "(here 16 movable spheres)" in out and "(warned once)" in out, out
    idle = thermo_table(out, "f_settle[1]")[1][1:, 2]   # [13], per tap: every stop was idle
    np.testing.assert_array_equal(idle, np.ones(6))
    # The drift rule stops by eta, also here.
    rc, out, _ = run_lammps(SMALL_BED.format(keywords=f"scheme {scheme} stop drift eta 4e-7"),
                            nprocs=nprocs)
    assert rc == 0 and "none of its" not in out, out
    np.testing.assert_array_equal(thermo_table(out, "f_settle[1]")[1][:, 2], np.zeros(7))


# A column one diameter wide (walls on x and y): create_packing stacks the spheres, each wedged
# on top of the one below; every trial move has a sideways part that enters a wall.
COLUMN = {width: narrow_bed("f f fm", width, 10, "f_settle[2] f_settle[3]", 7)
          for width in (1.0, 1.1)}
NO_MOVE = "5 redepositions in a row accepted none of their trial moves"


@pytest.mark.parametrize("nprocs,scheme", [(1, "gather"), (2, "domain")])
def test_a_packing_that_cannot_move_is_named_not_silently_dilated(nprocs, scheme):
    """Nothing is ever accepted: <Z> grows by 1 + eps per tap (the model's answer in this
    geometry), and the fix says so once, at the fifth tap, under either stop rule. A column a
    little wider lets the spheres move: no warning. The small periodic bed, whose 'stop change'
    redepositions all stop at an idle check, accepts moves: no warning either."""
    for stop in ("", "stop drift"):
        keywords = f"scheme {scheme} {stop}"
        rc, out, _ = run_lammps(COLUMN[1.0].format(keywords=keywords), nprocs=nprocs)
        assert rc == 0, out
        assert out.count(NO_MOVE) == 1 and "(warned once)" in out, out
        assert "step 5: " + NO_MOVE in out, out
        table = thermo_table(out, "f_settle[2]")[1]
        np.testing.assert_array_equal(table[1:, 1], np.zeros(7))     # acceptance 0 every tap
        # each tap's <Z> 1.01 times the last (step 0 has had no redeposition: [3] is 0)
        np.testing.assert_allclose(table[2:, 2] / table[1:-1, 2], 1.01, rtol=1e-9)
        rc, out, _ = run_lammps(COLUMN[1.1].format(keywords=keywords), nprocs=nprocs)
        assert rc == 0 and NO_MOVE not in out, out
    rc, out, _ = run_lammps(SMALL_BED.format(keywords=f"scheme {scheme}"), nprocs=nprocs)
    assert rc == 0 and IDLE_STOP in out and NO_MOVE not in out, out


def test_taps_too_weak_for_the_trial_steps_are_named_with_dmax():
    """eps = 1e-8 opens gaps of at most 1e-8 (eps times a diameter) between touching spheres of
    a settled periodic bed, a ten-millionth of the trial steps (up to dmax = R/5 = 0.1): no
    trial is accepted, and the warning names that cause and dmax beside the jammed column's (it
    named only the column)."""
    bed = """units lj
atom_style sphere
boundary p p fm
region box block 0 6 0 6 0 30
create_box 1 box
create_packing 300 1 0.5 4928 floor 0.0
fix tap all tapdilate 1e-8 floor 0.0
fix settle all mc/settle 4928 floor 0.0
run 5
"""
    rc, out, _ = run_lammps(bed)
    assert rc == 0, out
    assert "step 5: " + NO_MOVE in out, out
    assert "the taps open gaps far narrower than the trial steps (up to dmax = 0.1;" in out, out
