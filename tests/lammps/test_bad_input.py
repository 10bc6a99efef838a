# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Every invalid argument of fix tapdilate and fix mc/settle stops lmp_tapmc with a non-zero
# exit and a message naming the argument and the allowed range (LAMMPS errors end the process,
# so each case is a child process).
import os
import re
import struct
from pathlib import Path

import numpy as np
import pytest

from lmprun import LMP, run_lammps, thermo_table

BOX = """units lj
atom_style sphere
boundary {boundary}
region box block 0 8 0 8 0 10
create_box 1 box
create_atoms 1 single 2 2 1
create_atoms 1 single 5 5 1
set group all diameter 1.0
"""


def run_case(body, boundary="p p fm", extra=""):
    rc, out, _ = run_lammps(extra + BOX.format(boundary=boundary) + body)
    return rc, out


TAPDILATE_CASES = [
    ("fix t all tapdilate -0.1", "eps = -0.1 is outside the allowed range [0, 1]"),
    ("fix t all tapdilate 1e6", "eps = 1e+06 is outside the allowed range [0, 1]"),
    ("fix t all tapdilate 1e300", "eps = 1e+300 is outside the allowed range [0, 1]"),
    ("variable e equal 5\nfix t all tapdilate v_e\nrun 1",
     "(variable 'e', step 1): eps = 5 is outside the allowed range [0, 1]"),
    ("fix t all tapdilate abc", "abc"),
    ("fix t all tapdilate 0.1 every 0",
     "every = 0 is outside the allowed range [1, 2147483647] (an integer)"),
    # LAMMPS 2021's inumeric wrapped these to 1 and to -2147483648
    ("fix t all tapdilate 0.1 every 4294967297",
     "every = 4294967297 is outside the allowed range [1, 2147483647] (an integer)"),
    ("fix t all tapdilate 0.1 every 2147483648",
     "every = 2147483648 is outside the allowed range [1, 2147483647] (an integer)"),
    ("fix t all tapdilate 0.1 every 1.5",
     "every = 1.5 is not a whole number (allowed range [1, 2147483647], an integer)"),
    ("fix t all tapdilate 0.1 floor", "keyword 'floor' needs 1 value(s)"),
    ("fix t all tapdilate 0.1 bogus 3",
     "unknown keyword 'bogus' (allowed: every, floor, container)"),
    ("fix t all tapdilate", "expected 'fix ID group tapdilate eps"),
    ("fix t all tapdilate v_nothere\nrun 1", "variable 'nothere' for eps does not exist"),
    ("variable e atom x\nfix t all tapdilate v_e\nrun 1", "variable 'e' for eps must be equal-style"),
    ("variable e equal -0.5\nfix t all tapdilate v_e\nrun 1",
     "eps = -0.5 is outside the allowed range [0, 1]"),
    ("fix t all tapdilate 0.1 floor 3.0\nrun 1", "below the floor"),
]


def test_tapdilate_fixed_top_would_lose_atoms():
    rc, out = run_case("create_atoms 1 single 5 2 8\nset group all diameter 1.0\n"
                       "fix t all tapdilate 0.5\nrun 1", boundary="p p ff")
    assert rc != 0 and "above the fixed upper z boundary" in out, out


def test_tapdilate_fixed_top_with_room_is_fine():
    rc, out = run_case("fix t all tapdilate 0.5\nrun 2", boundary="p p ff")
    assert rc == 0, out


SEED_RANGE = "is outside the allowed range [1, 9223372036854775807] (an integer)"

MC_SETTLE_CASES = [
    ("fix s all mc/settle 0", "seed = 0 " + SEED_RANGE),
    ("fix s all mc/settle -5", "seed = -5 " + SEED_RANGE),
    ("fix s all mc/settle 99999999999999999999",
     "seed = 99999999999999999999 is outside the allowed range [1, 9223372036854775807]"),
    ("fix s all mc/settle 9223372036854775808",
     "seed = 9223372036854775808 is outside the allowed range [1, 9223372036854775807]"),
    ("fix s all mc/settle 1.5", "seed = 1.5 is not a whole number (allowed range [1, "
     "9223372036854775807], an integer)"),
    ("create_packing 10 1 0.5 99999999999999999999",
     "create_packing: seed = 99999999999999999999 is outside the allowed range [1, "),
    ("fix s all mc/settle 1 dmax 0", "dmax = 0 is outside the allowed range (0, +inf)"),
    ("fix s all mc/settle 1 dmax -0.1", "dmax = -0.1 is outside the allowed range (0, +inf)"),
    ("fix s all mc/settle 1 theta0 0",
     "theta0 = 0 is outside the allowed range (0, 1000] (radians)"),
    ("fix s all mc/settle 1 theta0 1001",
     "theta0 = 1001 is outside the allowed range (0, 1000] (radians)"),
    ("fix s all mc/settle 1 theta_law solid theta0 -1",
     "theta0 = -1 is outside the allowed range (0, 1000] (radians)"),
    ("fix s all mc/settle 1 theta_law sphere",
     "fix mc/settle: theta_law = sphere must be 'angle' (P(theta) of eq. 1 per unit angle, the "
     "default), 'solid' (per unit solid angle), 'exponential' or 'linear' (section II's "
     "alternative laws)"),
    ("fix s all mc/settle 1 theta_law linear theta0 0",
     "theta0 = 0 is outside the allowed range (0, 1000] (radians)"),
    ("fix s all mc/settle 1 theta_law", "keyword 'theta_law' needs 1 value(s)"),
    ("fix s all mc/settle 1 eta 0", "eta = 0 is outside the allowed range (0, 1)"),
    ("fix s all mc/settle 1 eta -1e-3", "eta = -0.001 is outside the allowed range (0, 1)"),
    ("fix s all mc/settle 1 eta 1", "eta = 1 is outside the allowed range (0, 1)"),
    ("fix s all mc/settle 1 check -1", "check = -1 is outside the allowed range [0, +inf)"),
    ("fix s all mc/settle 1 maxsweeps 0", "maxsweeps = 0 is outside the allowed range [1, +inf)"),
    # a check longer than the cap would run past it (9e18 trials: forever): a LAMMPS error of
    # the fix (it escaped as a C++ exception: no log line, and a Python caller aborted)
    ("fix s all mc/settle 1 check 1000 maxsweeps 10\nrun 1",
     "ERROR: fix mc/settle: check = 1000 trials exceeds the cap of maxsweeps = 10 sweeps of 2 movable spheres (20 "
     "trials)"),
    ("fix s all mc/settle 1 check 9223372036854775807\nrun 1",
     "ERROR: fix mc/settle: check = 9223372036854775807 trials exceeds the cap of maxsweeps = 50000 sweeps"),
    # 'stop drift' never stops before its window: beyond the cap, every tap ran to the cap
    ("fix s all mc/settle 1 stop drift window 100000 maxsweeps 30\nrun 1",
     "window = 100000 checks of 'stop drift' is more than the cap allows (30 checks"),
    ("fix s all mc/settle 1 diameter 0",
     "fix mc/settle: diameter = 0 is outside the allowed range (0, +inf)"),
    ("fix s all mc/settle 1 order backwards", "order = backwards must be 'random'"),
    ("fix s all mc/settle 1 xwalls 0 8", "xwalls given but the x boundary is periodic"),
    ("fix s all mc/settle 1 ywalls 3 1", "ywalls lo = 3 must be below hi = 1"),
    ("fix s all mc/settle 1 wiggle 3", "unknown keyword 'wiggle'"),
    ("fix s all mc/settle 1 eta", "keyword 'eta' needs 1 value(s)"),
    ("fix s all mc/settle", "expected 'fix ID group mc/settle seed"),
    ("fix s all mc/settle 1 floor 0.8\nrun 1", "below the floor"),
    # spheres falling below the fixed lower face would be lost by LAMMPS ("Lost atoms")
    ("fix s all mc/settle 1 floor -1\nrun 1",
     "floor z0 = -1 is below the fixed ('f') lower z face of the box, 0"),
    ("create_atoms 1 single 2.5 2 1\nfix s all mc/settle 1\nrun 1", "overlap by 0.5"),
    ("set atom 1 diameter 0.0\nfix s all mc/settle 1\nrun 1", "every sphere needs a radius > 0"),
    # 'threads' is no keyword: one rank's trial moves run on one thread (MPI ranks divide the
    # work); an input that still asks for threads stops, naming it and the allowed keywords.
    ("fix s all mc/settle 1 threads 2",
     "fix mc/settle: unknown keyword 'threads' (allowed: dmax, theta0, theta_law, eta, check, "
     "maxsweeps, floor, diameter, xwalls, ywalls, order, scheme, stop, window, container, "
     "verify)"),
]


@pytest.mark.parametrize("body,message", TAPDILATE_CASES + MC_SETTLE_CASES)
def test_bad_argument_stops_with_a_message_naming_it(body, message):
    rc, out = run_case(body)
    assert rc != 0, out
    assert "ERROR" in out and message in out, out


FIX_LINES = ["fix t all tapdilate 0.1", "fix s all mc/settle 1", "compute c all stereo/profile"]


@pytest.mark.parametrize("fix_line", FIX_LINES)
def test_periodic_z_is_refused(fix_line):
    rc, out = run_case(fix_line, boundary="p p p")
    assert rc != 0 and "z boundary is periodic" in out, out


@pytest.mark.parametrize("fix_line", FIX_LINES)
def test_triclinic_box_is_refused(fix_line):
    script = BOX.format(boundary="p p fm").replace(
        "region box block 0 8 0 8 0 10", "region box prism 0 8 0 8 0 10 1 0 0")
    rc, out, _ = run_lammps(script + fix_line)
    assert rc != 0 and "triclinic" in out, out


def test_mc_settle_needs_a_radius():
    script = BOX.format(boundary="p p fm").replace("atom_style sphere", "atom_style atomic") \
                .replace("set group all diameter 1.0", "mass 1 1.0")
    rc, out, _ = run_lammps(script + "fix s all mc/settle 1")
    assert rc != 0 and "has no radius; use atom_style sphere or the 'diameter'" in out, out
    rc, out, _ = run_lammps(script + "fix s all mc/settle 1 diameter 1.0\nrun 2")
    assert rc == 0, out


@pytest.mark.parametrize("line,given", [
    ("fix s all mc/settle 1 floor 0.0 diameter 0.8", "fix mc/settle: diameter 0.8 gives the "
     "spheres radius 0.4"),
    ("compute phi all stereo/profile floor 0.0 radius 0.4", "compute stereo/profile: radius 0.4 "
     "gives the spheres radius 0.4"),
    ("compute n all contacts 0.01 radius 0.4", "compute contacts: radius 0.4 gives the spheres "
     "radius 0.4"),
])
def test_a_radius_keyword_against_per_atom_radii_is_named(line, given):
    """Per-atom radii 0.5 and a keyword for 0.4: the redeposition left the spheres 20 % into one
    another by their own radii (<Phi^c> 0.98, no message); now fix mc/settle stops, and a compute
    (a measurement of other spheres, strange but harmless) warns, naming an atom, its radius and
    both ways out. The keyword with the atoms' own radius is accepted silently."""
    rc, out = run_case(line + "\nrun 1\n")
    named = given + ", but atom 1 of group all has per-atom radius 0.5 (atom style sphere)"
    assert named in out and "set group all diameter 0.8" in out, out
    if line.startswith("fix"):
        assert rc != 0 and "ERROR: " + named in out, out
    else:
        assert rc == 0 and "WARNING: " + named in out and "Loop time" in out, out
    rc, out = run_case(line.replace("0.8", "1.0").replace("0.4", "0.5") + "\nrun 1\n")
    assert rc == 0 and "Loop time" in out and "per-atom radius" not in out, out


def test_a_diameter_keyword_against_an_obstacle_outside_the_group_is_named():
    """The keyword sizes every sphere the redeposition sees, its fixed obstacles too: a group of
    0.8-wide spheres beside an obstacle of per-atom radius 0.5 settled into the obstacle by 0.1
    (exit 0, checked against the group only); now the obstacle is named."""
    rc, out = run_case("set atom 1 diameter 0.8\ngroup one id 1\n"
                       "fix s one mc/settle 1 floor 0.0 diameter 0.8\nrun 1\n")
    assert rc != 0 and "ERROR: fix mc/settle: diameter 0.8 gives the spheres radius 0.4, but " \
        "atom 2 of group all has per-atom radius 0.5" in out, out


def test_styles_without_radii_are_told_of_two_radii():
    script = BOX.format(boundary="p p fm").replace("atom_style sphere", "atom_style atomic") \
                .replace("set group all diameter 1.0", "mass 1 1.0")
    settle = "fix s all mc/settle 1 floor 0.0 diameter 1.0\n"
    for line, named in (("compute phi all stereo/profile floor 0.0 radius 0.4",
                         "compute phi (stereo/profile) radius 0.4"),
                        ("compute n all contacts 0.01 radius 0.7", "compute n (contacts) radius 0.7")):
        rc, out, _ = run_lammps(script + settle + line + "\nrun 1\n")
        assert rc == 0 and "WARNING: fix mc/settle: two different sphere radii in one run: fix s " \
            "(mc/settle) takes radius 0.5, " + named in out, out
    rc, out, _ = run_lammps(script + settle + "compute phi all stereo/profile floor 0.0 radius "
                            "0.5\nrun 1\n")
    assert rc == 0 and "Loop time" in out and "two different sphere radii" not in out, out


def test_mc_settle_needs_atom_ids():
    rc, out = run_case("fix s all mc/settle 1\nrun 1", extra="atom_modify id no\n")
    assert rc != 0 and "the atoms have no IDs ('atom_modify id no')" in out, out


def test_mc_settle_sphere_through_a_side_wall():
    rc, out = run_case("create_atoms 1 single 7.8 5 3\nfix s all mc/settle 1\nrun 1",
                       boundary="f f fm")
    assert rc != 0 and "crosses a side wall in x" in out, out


def test_default_side_walls_follow_the_box_between_runs():
    """Without xwalls, the walls are the faces of the box of each run: after change_box moves
    the x face to 5.3, the sphere near x = 5 (radius 0.5; it settled a little in the first
    run) crosses it (the walls of the first run, at 8, would have let it stick out of the
    box)."""
    rc, out = run_case("fix s all mc/settle 1 eta 1e-3\nrun 1\n"
                       "change_box all x final 0 5.3\nrun 1", boundary="f f fm")
    assert rc != 0 and "atom 2 crosses a side wall in x by 0.1" in out, out
    assert "(the high x wall)" in out
    assert "Step" in out  # the first run ran


@pytest.mark.parametrize("fix_line", FIX_LINES[:2])
@pytest.mark.parametrize("change,message", [
    ("change_box all z final 0 9 boundary p p p", "the z boundary is periodic"),
    ("change_box all triclinic", "triclinic boxes are not supported"),
])
def test_a_box_changed_between_runs_is_checked_again(fix_line, change, message):
    rc, out = run_case(f"{fix_line}\nrun 1\n{change}\nrun 1")
    assert rc != 0 and message in out and "Lost atoms" not in out, out


@pytest.mark.parametrize("body,message", [
    ("fix s all mc/settle 1 scheme domain\nrun 1",
     "fix mc/settle: 'comm_modify mode multi' gives hard spheres no ghost atoms"),
    ("compute n all contacts 0.01\nthermo_style custom step c_n[1]\nrun 0",
     "compute contacts: 'comm_modify mode multi' gives hard spheres no ghost atoms"),
])
def test_styles_reading_ghosts_refuse_comm_mode_multi(body, message):
    """LAMMPS sizes multi-mode ghosts from the pair cutoffs, and hard spheres have none: with no
    ghost atoms, the domain scheme let spheres of two sub-domains overlap by 97 % of a diameter
    and compute contacts missed every pair across a sub-domain or periodic face, silently. The
    gather scheme reads no ghosts and runs."""
    multi = "neighbor 0.3 multi\ncomm_modify mode multi\n"
    rc, out = run_case(body, extra=multi)
    assert rc != 0 and message in out and "use 'comm_modify mode single' (the default)" in out, out
    rc, out = run_case("fix s all mc/settle 1 scheme gather\nrun 1", extra=multi)
    assert rc == 0 and "Loop time" in out, out


@pytest.mark.parametrize("body,message", [
    ("fix s all mc/settle 1 scheme domain\nrun 1",
     "fix mc/settle: 'comm_modify group one' sends ghost atoms of that group only, and 1 atoms "
     "it reads are outside it, so scheme domain would move spheres"),
    ("compute n all contacts 0.01\nthermo_style custom step c_n[1]\nrun 0",
     "compute contacts: 'comm_modify group one' sends ghost atoms of that group only, and 1 "
     "atoms it reads are outside it, so the contacts across sub-domain and periodic faces"),
])
def test_styles_reading_ghosts_refuse_a_ghost_group_without_every_atom(body, message):
    """'comm_modify group G' makes ghosts of G's atoms only: the domain scheme moved spheres
    into the others (a 1024-sphere bed on 2 ranks compacted to Phi_b 0.552 in 10 taps, 0.546
    with every ghost) and compute contacts missed their contacts (<Z> 5.07 for 5.69), silently.
    A group holding every atom, and the gather scheme, which reads no ghosts, run."""
    first = "atom_modify first one\n"
    rc, out = run_case("group one id 1\ncomm_modify group one\n" + body, extra=first)
    assert rc != 0 and message in out and "use 'comm_modify group all' (the default)" in out, out
    rc, out = run_case("group one id 1 2\ncomm_modify group one\n" + body, extra=first)
    assert rc == 0 and "Loop time" in out, out
    rc, out = run_case("group one id 1\ncomm_modify group one\n"
                       "fix s all mc/settle 1 scheme gather\nrun 1", extra=first)
    assert rc == 0 and "Loop time" in out, out
    # compute contacts reads its own group's ghosts only: that group's are all sent
    rc, out = run_case("group one id 1\ncomm_modify group one\ncompute n one contacts 0.01\n"
                       "thermo_style custom step c_n[1]\nrun 0", extra=first)
    assert rc == 0 and "Loop time" in out, out


def test_a_bed_coming_apart_stops_by_name():
    """eps = 1 with a loose eta: the stop rule compares the change of <Z> with eta <Z>, which
    the spheres left high make large, so they stay high and double their height every tap
    (z = 5e7 by step 58, h_s printed as 3e6) until LAMMPS lost an atom. The tap that would
    lift a sphere beyond the coordinates where contacts are resolved now stops the run."""
    rc, out, _ = run_lammps("""units lj
atom_style sphere
boundary p p fm
region box block 0 4 0 4 0 20
create_box 1 box
create_packing 60 1 0.5 77 floor 0.0
fix tap all tapdilate 1 floor 0.0
fix settle all mc/settle 77 floor 0.0 eta 1e-4
run 300
""")
    assert rc != 0 and "the bed has come apart" in out and "beyond |z| = 1.13e+05" in out, out
    assert "Lost atoms" not in out and "atom count changed" not in out


PRE_NO = "fix t all tapdilate 0.05\nfix s all mc/settle 1 eta 1e-3\nrun 2\n{change}\n" \
         "run 2 pre no post no\n"


@pytest.mark.parametrize("change,now", [("unfix t", "now: none"),
                                        ("unfix t\nfix t all tapdilate 0.2 every 2",
                                         "now: t, defined again since")])
def test_tapping_fixes_changed_before_a_run_without_setup_stop(change, now):
    """A run with 'pre no' skips init(): a tapping fix deleted since (a dangling pointer, a
    segfault before) or defined since (never scheduled: it never tapped) stops the run."""
    rc, out = run_case(PRE_NO.format(change=change))
    assert rc != 0 and "the tapping fixes changed since the run's setup (then: t; " + now \
        in out, out


FLOORS = """units lj
atom_style sphere
boundary {boundary}
region box block 0 6 0 6 -2 30
create_box 1 box
create_packing 60 1 0.5 7 floor 0.0
fix settle all mc/settle 7 floor 0.0 eta 1e-3
{line}
run 1
"""


@pytest.mark.parametrize("line,other", [
    ("fix tap all tapdilate 0.05", "fix tap (tapdilate) has floor -2"),
    ("compute phi all stereo/profile", "compute phi (stereo/profile) has floor -2"),
    ("compute n all contacts 0.01 floor 0.5", "compute n (contacts) has floor 0.5"),
])
def test_styles_with_different_floors_stop_naming_both(line, other):
    """The box starts at z = -2, the bed at the floor 0: a style left at its default floor (the
    box's lower bound) would tap about another floor (an extra lift of 2 eps) or measure an
    empty slab (Phi_b 0); the run stops at setup naming both styles and floors."""
    rc, out, _ = run_lammps(FLOORS.format(boundary="p p fm", line=line))
    assert rc != 0 and "two different floors in one run: fix settle (mc/settle) has floor 0, " \
        + other in out, out
    same = line.replace("0.05", "0.05 floor 0.0").replace("profile", "profile floor 0.0") \
        .replace("floor 0.5", "floor 0.0")
    rc, out, _ = run_lammps(FLOORS.format(boundary="p p fm", line=same))
    assert rc == 0 and "Loop time" in out, out
    # compute contacts without 'floor' has no floor: nothing to compare
    rc, out, _ = run_lammps(FLOORS.format(boundary="p p fm", line="compute n all contacts 0.01"))
    assert rc == 0, out


SIDE_WALLS = """units lj
atom_style sphere
boundary f f fm
region box block 0 16 0 8 0 30
create_box 1 box
region bed block 4 12 0 8 0 30
create_packing 400 1 0.5 4928 floor 0.0 region bed
fix settle all mc/settle 4928 floor 0.0 eta 1e-5 {walls}
compute phi all stereo/profile floor 0.0
thermo_style custom step c_phi[2]
run 1
"""


def test_styles_with_different_side_walls_stop_naming_both():
    """fix mc/settle holds the bed between xwalls 4 and 12, compute stereo/profile measures
    between the box faces 0 and 16: it divided by twice the bed's area (<Phi^c> 0.27 for the
    packing's 0.54), in silence. The run stops naming both; walls at the box faces run."""
    rc, out, _ = run_lammps(SIDE_WALLS.format(walls="xwalls 4 12"))
    assert rc != 0 and "two different side walls along x in one run: fix settle (mc/settle) " \
        "has them at x = 4 and 12, compute phi (stereo/profile) at 0 and 16" in out, out
    assert "('boundary f' with the box from 4 to 12)" in out, out
    rc, out, _ = run_lammps(SIDE_WALLS.format(walls="xwalls 0 16 ywalls 0 8"))
    assert rc == 0 and "Loop time" in out, out


def two_layers(boundary, spheres, cut):
    """A packing in an 8 x 8 box split at height ``cut`` into the groups low and high."""
    return f"""units lj
atom_style sphere
boundary {boundary}
region box block 0 8 0 8 0 30
create_box 1 box
create_packing {spheres} 1 0.5 4928 floor 0.0
region low block INF INF INF INF INF {cut}
group low region low
group high subtract all low
"""


TWO_SETTLES_WIDENED = two_layers("f f fm", 150, 0.55) + """fix tap all tapdilate 0.01 floor 0.0
fix s1 low mc/settle 11 floor 0.0 eta 1e-5
fix s2 high mc/settle 12 floor 0.0 eta 1e-5 {walls}
change_box all x final 0 10 units box
run 2
"""


def test_two_settles_compare_their_walls_as_they_are_now():
    """Two fix mc/settle on the box faces, the box widened between their definition and the
    run: the first fix's init() must read the second one's walls as the box now has them (it
    read the faces the second had stored, 0 and 8, and refused the run); walls that really
    differ still stop it."""
    rc, out, _ = run_lammps(TWO_SETTLES_WIDENED.format(walls=""))
    assert rc == 0 and "Loop time" in out, out
    rc, out, _ = run_lammps(TWO_SETTLES_WIDENED.format(walls="xwalls 0 8"))
    assert rc != 0 and "two different side walls along x in one run" in out, out


@pytest.mark.parametrize("boundary,axis", [("s p fm", "x"), ("p m fm", "y")])
def test_stereo_profile_refuses_shrink_wrapped_sides(boundary, axis):
    """A shrink-wrapped side spans the sphere centres, not the bed: the packing fractions would
    divide by too small an area (a simple cubic lattice read 0.684 for pi/6)."""
    rc, out, _ = run_lammps(FLOORS.format(boundary=boundary, line="").replace(
        "fix settle all mc/settle 7 floor 0.0 eta 1e-3",
        "compute phi all stereo/profile floor 0.0\nthermo_style custom step c_phi[1]").replace(
        "floor 0.0\n", "floor 0.0 region box\n", 1))
    assert rc != 0 and f"compute stereo/profile: the {axis} boundary is shrink-wrapped" in out, out
    # create_packing's walls at the faces of such a box: refused (LAMMPS widened the box by
    # 1e-4 of its length, and the packing reached past walls at the region's faces)
    rc, out, _ = run_lammps(FLOORS.format(boundary=boundary, line=""))
    assert rc != 0 and f"create_packing: the {axis} boundary is shrink-wrapped, so the box " \
        "faces are no walls" in out, out


SUBSET_TAP = """units lj
atom_style sphere
boundary p p fm
region box block 0 4 0 4 0 10
create_box 2 box
create_atoms 1 single 2 2 0.5
create_atoms 2 single 2 2 {z_fixed}
set group all diameter 1.0
group grain type 1
fix tap grain tapdilate 0.2 floor 0.0
fix settle grain mc/settle 7 floor 0.0
run 3
"""


TWO_TAPPERS = two_layers("p p fm", 400, 2.5) + """fix tap1 low tapdilate {eps_low} floor 0.0
fix tap2 high tapdilate 0.01 floor 0.0
fix settle all mc/settle 4928 floor 0.0 eta 1e-5
run 2
"""


def test_tapping_fixes_that_dilate_groups_differently_are_named_as_the_cause():
    """Every atom is tapped and redeposited, the lower group at eps 0.2 and the upper at 0.01:
    the lower spheres are lifted into the upper ones. The message names the unequal tapping
    fixes (it blamed atoms standing still, which there are none of); equal eps runs."""
    rc, out, _ = run_lammps(TWO_TAPPERS.format(eps_low=0.2))
    assert rc != 0 and "every atom is tapped, but by tapping fixes of different groups" in out
    assert "stands still" not in out, out
    rc, out, _ = run_lammps(TWO_TAPPERS.format(eps_low=0.01))
    assert rc == 0 and "Loop time" in out, out


def test_a_tap_that_pushes_a_sphere_into_one_standing_still_stops():
    """Only the grain (type 1) is tapped and redeposited: the sphere resting on it (type 2)
    stands still, so the tap lifts the grain into it; the run stops at that tap, naming both
    atoms and the overlap (the tap lifts the grain by 0.2 x 0.5). A fixed sphere below the
    grain (a rough floor) is never reached: the run goes on."""
    rc, out, _ = run_lammps(SUBSET_TAP.format(z_fixed=1.5))
    assert rc != 0 and "step 1: atoms 1 and 2 overlap by 0.0999999" in out, out
    assert "after the tap: part of the bed stands still" in out
    rc, out, _ = run_lammps(SUBSET_TAP.format(z_fixed=0.5).replace(
        "create_atoms 1 single 2 2 0.5", "create_atoms 1 single 2 2 1.5"))
    assert rc == 0 and "Loop time" in out, out


FAR_BOX = """units lj
atom_style sphere
boundary p p fm
region box block 0 6 0 6 {z0} {z1}
create_box 1 box
"""


@pytest.mark.parametrize("z0,body,style", [
    (1e6, "create_packing 50 1 0.5 7 floor 1e6", "create_packing"),
    (-2e5, "create_packing 50 1 0.5 7 floor -2e5", "create_packing"),
    (1e6, "create_atoms 1 single 3 3 1000000.5\nset group all diameter 1.0\n"
          "fix s all mc/settle 1 floor 1e6\nrun 1", "fix mc/settle"),
])
def test_a_box_beyond_exact_contacts_is_refused(z0, body, style):
    """Far from the origin a double cannot resolve a contact to its tolerance (at z = 1e6 the
    deposited pairs sat 1.04e-10 inside contact): the styles refuse the box, naming the bound;
    at z = 1e5 the same bed taps as at z = 0."""
    rc, out, _ = run_lammps(FAR_BOX.format(z0=z0, z1=z0 + 40) + body + "\n")
    assert rc != 0 and f"ERROR: {style}: the box reaches z = " in out, out
    assert "beyond |z| = 1.13e+05, 2.25e+05 times that radius; move the box and the floor " \
        "nearer the origin" in out, out
    near = "create_packing 50 1 0.5 7 floor {z}\nfix t all tapdilate 0.01 floor {z}\n" \
           "fix s all mc/settle 7 floor {z} eta 1e-5\nthermo_style custom step f_s[1] f_s[3]\n" \
           "thermo 1\nrun 3\n"
    rows = []
    for z in (0.0, 1e5):
        rc, out, _ = run_lammps(FAR_BOX.format(z0=z, z1=z + 40) + near.format(z=z))
        assert rc == 0, out
        rows.append(thermo_table(out, "f_s[1]")[1])
    assert rows[0].shape == (4, 3) and rows[0][-1, 1] > 0
    np.testing.assert_array_equal(rows[0], rows[1])   # sweeps and <Z> above the floor


@pytest.mark.parametrize("body,named", [
    # an open top grows with the packing: the floor above the box was not checked (1e300: 436
    # overlapping pairs and Phi 0, exit 0), nor the packing grown beyond the bound
    ("create_packing 100 1 0.5 7 floor 1e300", "the floor z = 1e+300"),
    ("create_packing 4000 1 0.5 7 floor 1.125e5", "the packing's top reaches z = 1126"),
])
def test_a_floor_or_packing_beyond_exact_contacts_is_refused(body, named):
    rc, out, _ = run_lammps(FAR_BOX.format(z0=0, z1=30) + body + "\n")
    assert rc != 0 and f"ERROR: create_packing: {named}" in out, out
    assert "beyond |z| = 1.13e+05" in out and "by sequential deposition" not in out, out


def test_the_bound_names_the_smallest_spheres_as_a_remedy():
    """A box at the origin is refused for radii 1e-4 of its height (dispersity 0.9999): the
    message says that larger spheres are the remedy, not only moving the box."""
    rc, out, _ = run_lammps(FAR_BOX.format(z0=0, z1=30) + "create_packing 400 1 0.5 4928 floor "
                            "0.0 dispersity 0.9999\n")
    assert rc != 0 and "ERROR: create_packing: the box reaches z = 30" in out, out
    assert "or make the smallest spheres larger (radius, dispersity)" in out, out


def test_largest_seed_is_accepted():
    rc, out = run_case("fix t all tapdilate 0.1\nfix s all mc/settle 9223372036854775807\nrun 2")
    assert rc == 0, out


@pytest.mark.parametrize("walls,message", [
    ("xwalls -10 50", "xwalls lo = -10 is outside the box: along a fixed ('f') x boundary the "
                      "side walls must lie within the box faces [0, 8]"),
    ("ywalls 0 9", "ywalls hi = 9 is outside the box"),
])
def test_side_walls_beyond_fixed_box_faces_are_refused_at_setup(walls, message):
    rc, out = run_case(f"fix s all mc/settle 1 {walls}", boundary="f f fm")
    assert rc != 0 and message in out, out
    rc, out = run_case("fix t all tapdilate 0.1\nfix s all mc/settle 1 xwalls 1 7 ywalls 0 8\nrun 2",
                       boundary="f f fm")
    assert rc == 0, out


def test_stereo_profile_warns_about_atoms_below_its_floor():
    rc, out = run_case("compute c all stereo/profile floor 3.0\nthermo_style custom step c_c[1]\n"
                       "run 0\nrun 0")
    assert rc == 0, out
    assert out.count("WARNING: compute stereo/profile: atom 1 of group all reaches down to "
                     "z = 0.5, below the floor z0 = 3") == 2, out  # once per run
    rc, out = run_case("compute c all stereo/profile floor 0.5\nthermo_style custom step c_c[1]\n"
                       "run 0")
    assert rc == 0 and "below the floor" not in out, out


def test_mc_settle_shrink_wrapped_sides_need_walls():
    rc, out = run_case("fix s all mc/settle 1", boundary="s s fm")
    assert rc != 0 and "give 'xwalls lo hi'" in out, out
    rc, out = run_case("fix s all mc/settle 1 xwalls 0 8 ywalls 0 8\nrun 2", boundary="s s fm")
    assert rc == 0, out


PACKING = """units lj
atom_style sphere
boundary p p fm
region box block 0 4 0 4 0 20
create_box 1 box
create_packing 64 1 0.5 7 floor 0.0
group low id 1:10
group high id 11:64
"""


@pytest.mark.parametrize("fixes,names", [
    ("fix a all tapdilate 0.01\nfix b low tapdilate 0.02", "fixes 'a' (group 'all') and 'b' "
     "(group 'low') both act on 10 atom(s)"),
    ("fix a all mc/settle 5 eta 1e-3\nfix b all mc/settle 6 eta 1e-3",
     "fixes 'a' (group 'all') and 'b' (group 'all') both act on 64 atom(s)"),
])
@pytest.mark.parametrize("nprocs", [1, 2])
def test_two_fixes_of_one_style_on_shared_atoms_stop(fixes, names, nprocs):
    rc, out, _ = run_lammps(PACKING + fixes + "\nrun 1", nprocs=nprocs)
    assert rc != 0 and names in out and "moved twice per step" in out, out


def test_fixes_of_one_style_on_disjoint_groups_run():
    rc, out, _ = run_lammps(PACKING + "fix a low tapdilate 0.01\nfix b high tapdilate 0.02\n"
                            "fix s low mc/settle 5 eta 1e-3\nfix t high mc/settle 6 eta 1e-3\n"
                            "run 2")
    assert rc == 0, out


@pytest.mark.parametrize("styles", [
    "fix tap all tapdilate 0.01",
    # lateral 1.0: a central zone in this box 4 wide (the default 7R = 3.5 leaves none, which
    # the compute warns about)
    "compute phi all stereo/profile lateral 1.0\nthermo_style custom step c_phi[1]",
    "fix tap all tapdilate 0.01\nfix s all mc/settle 5 eta 1e-3",
])
@pytest.mark.parametrize("nprocs", [1, 2])
def test_no_warning_without_a_pair_style(styles, nprocs):
    """The TAPMC styles need no pair style; LAMMPS's zero-cutoff ('Atoms may get lost') and
    sorting warnings must not reach a user who runs them alone or together. The one warning
    left is about the input itself (a run with a compute and no fix moves nothing: "No fixes
    defined, atoms won't move" in LAMMPS 2021, "No fixes with time integration, atoms won't
    move" in 2026)."""
    rc, out, _ = run_lammps(PACKING + styles + "\nrun 3", nprocs=nprocs)
    assert rc == 0, out
    warnings = [line for line in out.splitlines() if "WARNING" in line]
    assert all(re.search(r"WARNING: No fixes (defined|with time integration), atoms won't move",
                         w) for w in warnings), out


# ---- where a message comes from: src/TAPMC/<file>:<line> -------------------------------------
# LAMMPS ends every error and warning with (FILE:LINE) from FLERR = __FILE__, __LINE__, cut at
# the first "src/" of the path. The TAPMC sources are compiled with __FILE__ relative to the
# source tree (CMakeLists.txt, -fmacro-prefix-map), so the location reads src/TAPMC/<file>
# wherever the checkout lives; with absolute paths a checkout under a folder named src (e.g.
# /home/u/src) cited src/src/TAPMC/... or src/<checkout>/src/TAPMC/...

SOURCE_DIR = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
LIB = os.environ.get("TAPMC_LIB", os.path.join(os.path.dirname(os.path.abspath(LMP)),
                                               "libtapmc.so"))
TAPMC_LOCATION = re.compile(r"^(?:ERROR|WARNING)\b.*\((\S*TAPMC/[\w.]+):(\d+)\)$", re.M)


@pytest.mark.parametrize("body,source", [
    ("fix s all mc/settle 1 xwalls 1 7", "src/TAPMC/fix_mc_settle_walls.cpp"),  # error->all
    ("fix t all tapdilate -0.1", "src/TAPMC/lammps_support.h"),             # FLERR in a header
    ("compute c all stereo/profile floor 3.0\nthermo_style custom step c_c[1]\nrun 0",
     "src/TAPMC/compute_stereo_profile.cpp"),                               # a warning
])
def test_messages_cite_src_tapmc_file_and_line(body, source):
    rc, out = run_case(body)
    found = TAPMC_LOCATION.findall(out)
    assert found, out
    for path, line in found:
        assert path == source, out
        # the line is the FLERR of the call that wrote the message
        assert "FLERR" in (SOURCE_DIR / path).read_text().splitlines()[int(line) - 1], (path, line)


def read_sections(path, prefix):
    """Bytes of every section of the ELF file `path` whose name starts with `prefix`."""
    data = Path(path).read_bytes()
    assert data[:4] == b"\x7fELF" and data[4] == 2, path     # 64-bit ELF
    order = "<" if data[5] == 1 else ">"
    shoff, = struct.unpack_from(order + "Q", data, 0x28)
    shentsize, shnum, shstrndx = struct.unpack_from(order + "HHH", data, 0x3A)

    def header(i):  # (name offset, file offset, size)
        base = shoff + i * shentsize
        name, = struct.unpack_from(order + "I", data, base)
        offset, size = struct.unpack_from(order + "QQ", data, base + 0x18)
        return name, offset, size

    _, names_at, _ = header(shstrndx)
    out = []
    for i in range(shnum):
        name, offset, size = header(i)
        label = data[names_at + name:data.index(b"\0", names_at + name)].decode()
        if label.startswith(prefix):
            out.append(data[offset:offset + size])
    return out


def test_library_holds_source_paths_relative_to_the_source_tree():
    """The FLERR file names compiled into libtapmc.so are src/TAPMC/<file>, never the absolute
    path of the checkout (which LAMMPS would cut at its first "src/")."""
    rodata = b"\0".join(read_sections(LIB, ".rodata"))
    assert b"\0src/TAPMC/fix_mc_settle.cpp\0" in rodata, LIB
    assert b"\0src/TAPMC/lammps_support.h\0" in rodata, LIB
    absolute = sorted(set(re.findall(rb"[^\0]*/src/TAPMC/\w+\.(?:cpp|h)", rodata)))
    assert not absolute, absolute


LID_BED = """units lj
atom_style sphere
boundary p p fm
region box block 0 6 0 6 0 30
create_box 1 box
create_packing 400 1 0.5 4928 floor 0.0
{mover}
fix tap all tapdilate 0.05 floor 0.0
fix settle all mc/settle 4928 floor 0.0 eta 1e-5
run 10
"""


def test_a_fix_that_moves_atoms_besides_the_taps_is_checked_before_each_tap():
    """A wall/reflect lid just above the bed (highest centre 10.548) reflected spheres lifted by
    a tap back into the bed: 23 overlapping pairs, up to 0.91 of a diameter, after 10 taps, exit
    0. A run with such a fix (fix deform's remap too) is checked before each tap, and an
    overlap found there names the fix; an integrator that moves nothing (zero velocities) runs
    on, warned; the bed alone runs without warning."""
    rc, out, _ = run_lammps(LID_BED.format(mover="fix lid all wall/reflect zhi 10.6"))
    assert rc != 0 and "fix mc/settle: step 2: atoms 345 and 397 overlap by" in out, out
    assert "before the tap: fix lid (wall/reflect) move(s) atoms besides the taps" in out
    rc, out, _ = run_lammps(LID_BED.format(mover="fix still all nve/sphere"))
    assert rc == 0 and "Loop time" in out, out
    assert "fix still (nve/sphere) move(s) atoms besides the taps and the redeposition: the " \
           "spheres are checked for overlaps before each tap" in out
    rc, out, _ = run_lammps(LID_BED.format(mover="fix squeeze all deform 1 x final 0 5.0 remap x"))
    assert rc != 0 and "fix squeeze (deform) move(s) atoms besides the taps" in out, out
    rc, out, _ = run_lammps(LID_BED.format(mover=""))
    assert rc == 0 and "besides the taps" not in out, out


@pytest.mark.parametrize("command,style", [
    ("fix t all tapdilate 0.05", "fix tapdilate"),
    ("fix s all mc/settle 7", "fix mc/settle"),
    ("compute p all stereo/profile", "compute stereo/profile"),
    ("create_packing 10 1 0.5 7", "create_packing"),
])
def test_a_2d_simulation_is_refused_as_such(command, style):
    """In 2d LAMMPS makes z periodic: the styles said "the z boundary is periodic ... use e.g.
    'boundary p p fm'", advice that 'dimension 2' forbids."""
    rc, out, _ = run_lammps("units lj\ndimension 2\natom_style sphere\nboundary p p p\n"
                            "region box block 0 8 0 8 -0.5 0.5\ncreate_box 1 box\n" + command)
    assert rc != 0 and f"{style}: needs a 3d simulation ('dimension 3', the default)" in out, out


def test_fix_adapt_growing_the_radii_and_fix_deposit_are_checked_too():
    """fix adapt grew the diameters 2 % per step into overlaps of 0.02-0.08, and fix deposit
    dropped spheres into the bed: neither was among the fixes that move atoms, so the
    redeposition ran on with the overlaps, silently. Both are now, warned at setup and stopped
    at the first overlap before a tap."""
    adapt = LID_BED.replace("atom_style sphere", "atom_style sphere 1").format(
        mover="variable d equal 1.0+0.02*step\nfix ad all adapt 1 atom diameter v_d reset no")
    rc, out, _ = run_lammps(adapt)
    assert "fix ad (adapt) move(s) atoms besides the taps" in out, out
    assert rc != 0 and "before the tap: fix ad (adapt) move(s) atoms" in out, out
    deposit = LID_BED.format(mover="region drop block 0 6 0 6 3 6\n"
                                   "fix dep all deposit 3 1 1 12345 region drop near 0.6")
    rc, out, _ = run_lammps(deposit)
    assert "fix dep (deposit) move(s) atoms besides the taps" in out, out
    assert rc != 0 and "before the tap: fix dep (deposit) move(s) atoms" in out, out


def test_spheres_tapped_but_never_redeposited_are_named():
    """fix tapdilate on all with fix mc/settle on the spheres above z = 2: the lowest layer
    rose by (1 + eps) at every tap, for ever, silently (doc: atoms outside the group 'never
    move'). The run says how many are tapped and redeposited by no fix mc/settle; tapping
    only the settled group is quiet."""
    split = LID_BED.format(mover="region low block INF INF INF INF INF 2.0\ngroup low region low\n"
                                 "group up subtract all low").replace(
        "fix settle all mc/settle", "fix settle up mc/settle").replace("run 10", "run 2")
    rc, out, _ = run_lammps(split)
    assert rc == 0, out
    assert re.search(r"fix mc/settle: \d+ atom\(s\) are tapped \(fix tap\) but in the group of "
                     r"no fix mc/settle: nothing redeposits them", out), out
    # once, not at every run
    rc, out, _ = run_lammps(split.replace("run 2", "run 1\nrun 1"))
    assert rc == 0 and out.count("are tapped (fix tap)") == 1, out
    rc, out, _ = run_lammps(split.replace("fix tap all tapdilate", "fix tap up tapdilate"))
    assert rc == 0 and "are tapped (fix tap)" not in out, out
