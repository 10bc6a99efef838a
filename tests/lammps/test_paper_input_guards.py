# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# The paper inputs (examples/paper) refuse what they would otherwise run silently wrong:
#  - a sqrteps that is negative or above 1 (only sqrteps > 0 replaces eps, so -0.1 used to run
#    the default eps): the input's ERROR line naming it, exit 2, before anything runs;
#  - a resume (-var resume yes) with a bc other than the restart's: the boundary comes from the
#    restart file, so -var bc fbc on a periodic restart used to continue periodic. The fresh
#    start records bc in its restarts (the empty group tapmc_bc_<bc>; restart files keep group
#    names); the resume compares, and warns when the restart records none (an older input's).
#  - with no central zone (the reference logs' L = 12R box, lateral zones of 7R), taps.dat's
#    central column is nan, not 0.00000000.
import math
import re

import pytest

from lmprun import run_lammps
from test_example_switches import TINY, run, run_ok, table

INPUTS = ["paper/in.constant_eps", "paper/in.ageing", "paper/in.pore_dumps"]
SQRTEPS_ALLOWED = "allowed: 0 (eps is used) or a number in (0, 1] (eps = sqrteps^2)"


@pytest.mark.parametrize("example", INPUTS)
@pytest.mark.parametrize("value", ["-0.1", "-1e-9", "1.5"])
def test_sqrteps_out_of_range_stops_naming_it(tmp_path, example, value):
    rc, screen, log = run(example, dict(TINY, sqrteps=value), tmp_path)
    message = f"ERROR: sqrteps = {value}; {SQRTEPS_ALLOWED}"
    assert rc == 2, screen
    assert message in screen.splitlines() and message in log.splitlines(), screen
    assert not re.search(r"^create_packing", log, re.M) and not list(tmp_path.glob("*.dat"))


@pytest.mark.parametrize("example", INPUTS)
@pytest.mark.parametrize("value, eps", [("0", "0.03"), ("1", "1")])
def test_sqrteps_range_ends_are_accepted(tmp_path, example, value, eps):
    """0 keeps eps (the default); 1 gives eps = 1, the largest fix tapdilate takes."""
    log = run_ok(example, dict(TINY, sqrteps=value, eps=0.03, taps=1, rsteps=10), tmp_path)
    assert re.search(rf"^fix\s+tap all tapdilate {re.escape(eps)} floor 0\.0\s*$", log, re.M), log


# (input, extra -var of every run): each input's smallest run
RESUME_INPUTS = [
    ("paper/in.constant_eps", {}),
    ("paper/in.ageing", {}),
    ("paper/in.pore_dumps", {"dump_times": [1]}),
    ("paper/in.ramp", {"P": 1, "nlev": 2}),
]


def fresh_then_resume(tmp_path, example, extra, bc, resume_vars):
    """A fresh run with `bc` (restart.1 and restart.2), then a resume from restart.1 with
    `resume_vars`; returns the resume's (returncode, screen, log) and the rows of taps.dat
    before the resume."""
    fresh = dict(TINY, bc=bc, rsteps=1, **extra)
    taps = {"taps": 2} if example != "paper/in.ramp" else {"stop": 2}
    log = run_ok(example, dict(fresh, **taps), tmp_path)
    assert f"0 atoms in group tapmc_bc_{bc}" in log
    rows = (tmp_path / "taps.dat").read_text()
    more = {"taps": 3} if example != "paper/in.ramp" else {"stop": 0}
    return run(example, dict(fresh, **more, resume="yes", resume_file="restart.1",
                             **resume_vars), tmp_path), rows


@pytest.mark.parametrize("example, extra", RESUME_INPUTS)
@pytest.mark.parametrize("bc, other", [("pbc", "fbc"), ("fbc", "pbc")])
def test_resume_with_another_bc_stops_naming_both(tmp_path, example, extra, bc, other):
    (rc, screen, log), rows = fresh_then_resume(tmp_path, example, extra, bc, {"bc": other})
    message = (f"ERROR: bc = {other}, but restart.1 (step 1) was written with bc = {bc}; "
               f"resume with -var bc {bc}")
    assert rc == 2, screen
    assert message in screen.splitlines() and message in log.splitlines(), screen
    assert (tmp_path / "taps.dat").read_text() == rows      # nothing appended
    assert "Setting up Verlet run" not in log


def test_resume_of_a_periodic_restart_with_the_paper_fbc_start_stops(tmp_path):
    """The QA case: -var bc fbc -var fbc_start paper on a periodic restart."""
    (rc, screen, _), _ = fresh_then_resume(tmp_path, "paper/in.constant_eps", {}, "pbc",
                                           {"bc": "fbc", "fbc_start": "paper"})
    assert rc == 2 and ("ERROR: bc = fbc, but restart.1 (step 1) was written with bc = pbc; "
                        "resume with -var bc pbc") in screen, screen


@pytest.mark.parametrize("example, extra", RESUME_INPUTS)
@pytest.mark.parametrize("bc", ["pbc", "fbc"])
def test_resume_with_the_same_bc_runs(tmp_path, example, extra, bc):
    (rc, screen, log), _ = fresh_then_resume(tmp_path, example, extra, bc, {})
    assert rc == 0, screen
    assert "ERROR" not in screen and "does not record its bc" not in screen
    assert re.search(r"^boundary\b", log, re.M) is None       # the boundary of the restart
    # the restart written by the resumed run records bc again (the group is in the restart)
    assert (tmp_path / "restart.3").exists() or (tmp_path / "restart.4").exists()


OLD_RESTART = """units lj
atom_style sphere
boundary {boundary}
region box block 0 4.8 0 4.8 0 20
create_box 1 box
create_packing 64 1 0.6 9 floor 0.0
write_restart old.restart
"""


@pytest.mark.parametrize("boundary", ["p p fm", "f f fm"])
def test_resume_of_a_restart_without_bc_warns_and_runs(tmp_path, boundary):
    """A restart of an older input (no tapmc_bc_ group) cannot be checked: a warning, then the
    run continues with the restart's boundary as before."""
    rc, out, _ = run_lammps(OLD_RESTART.format(boundary=boundary), workdir=str(tmp_path))
    assert rc == 0, out
    rc, screen, log = run("paper/in.ageing", dict(TINY, R=0.6, taps=1, resume="yes",
                                                  resume_file="old.restart"), tmp_path)
    assert rc == 0, screen
    assert ("WARNING: old.restart (step 0) does not record its bc (written by an older input): "
            "its boundary is not checked against bc = pbc") in screen.splitlines(), screen
    assert list(table(tmp_path / "taps.dat")[:, 0]) == [0, 1]


def test_no_central_zone_gives_nan_in_taps_dat(tmp_path):
    """L = 8R with the default lateral_R = 7: no central zone (as in the reference logs, L = 12R):
    the central column is nan with one warning from compute tprof naming the widths; with
    lateral_R = 3 the column holds numbers and no warning."""
    log = run_ok("paper/in.constant_eps", dict(TINY, taps=1, rsteps=10), tmp_path)
    rows = table(tmp_path / "taps.dat")
    assert rows.shape == (2, 11)
    assert all(math.isnan(v) for v in rows[:, 6]) and all(math.isfinite(v) for v in rows[:, 5])
    text = (tmp_path / "taps.dat").read_text().splitlines()
    assert all(line.split()[6] == "nan" for line in text[1:]), text
    tprof = [l for l in log.splitlines() if l.startswith("WARNING: compute stereo/profile tprof")]
    assert len(tprof) == 1 and ("(lateral = 3.5 from both x faces) cover the whole box width 4 "
                                "along x" in tprof[0]) and "lateral < 2 " in tprof[0], tprof

    narrow = tmp_path / "narrow"
    narrow.mkdir()
    log = run_ok("paper/in.constant_eps", dict(TINY, taps=1, rsteps=10, lateral_R=3), narrow)
    assert all(math.isfinite(v) and v > 0.3 for v in table(narrow / "taps.dat")[:, 6])
    assert "WARNING: compute stereo/profile tprof" not in log
