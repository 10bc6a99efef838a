# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# fix mc/settle with threads inside each rank ('threads N'): the trajectory of one thread, bit
# for bit (positions, image flags, sweeps, acceptance and <Z> of every tap), with 2, 4 and more
# threads than cores, PBC and FBC, polydisperse spheres with fixed obstacles, scheme gather and
# scheme domain on 2 and 4 ranks with threads inside each; 'threads auto'; the warning for more
# threads than cores. Bad values are in test_bad_input.py.
import os

import numpy as np
import pytest

from lmprun import read_dump, run_lammps
from test_mc_settle import SCENE, TAPPING

# 'check 4096' (trials between <Z> checks): blocks long enough for the threads' windows (a
# shorter block runs on the serial loop, with the same moves); <Z> printed to the last bit.
THERMO = ("thermo_style custom step f_settle[1] f_settle[2] f_settle[3] f_settle[5]\nthermo 1\n"
          "thermo_modify format float %.17g\n")


def run(script, nprocs=1):
    rc, out, wd = run_lammps(script, nprocs=nprocs)
    assert rc == 0, out
    return read_dump(os.path.join(wd, "dump.taps")), out


def thermo_rows(out):
    """The thermo rows of the run (step, sweeps, acceptance, <Z>, trials), as text."""
    rows, inside = [], False
    for line in out.splitlines():
        if line.split()[:2] == ["Step", "f_settle[1]"]:
            inside = True
            continue
        if inside and line.startswith("Loop time"):
            break
        if inside:
            rows.append(line.split())
    return rows


def expect_same(reference, other):
    (frames_a, out_a), (frames_b, out_b) = reference, other
    assert len(frames_a) == len(frames_b)
    for (s1, _, _, a), (s2, _, _, b) in zip(frames_a, frames_b):
        assert s1 == s2
        for c in ("x", "y", "z", "xu", "yu"):
            np.testing.assert_array_equal(a[c], b[c], err_msg=f"step {s1} column {c}")
    assert thermo_rows(out_a) == thermo_rows(out_b)
    assert len(thermo_rows(out_a)) > 3


def tapping(boundary, threads, grid="* * 1", scheme="auto", taps=6):
    fix = f"eta 1e-3 check 4096 scheme {scheme} threads {threads}"
    script = SCENE.format(boundary=boundary, zprocs=1).replace(
        "processors * * 1", f"processors {grid}") + TAPPING.replace("eta 1e-3", fix).replace(
        "thermo_style custom step atoms f_settle[1] f_settle[2] f_settle[3] f_settle[4]\n"
        "thermo 10\n", THERMO).format(eps=0.02, seed=4928, every=1, taps=taps)
    assert "threads" in script and "f_settle[5]" in script
    return script


@pytest.mark.parametrize("boundary", ["p p fm", "f f fm"])
def test_threads_give_the_one_thread_trajectory(boundary):
    one = run(tapping(boundary, 1))
    for threads in (2, 5):
        many = run(tapping(boundary, threads))
        expect_same(one, many)
        warned = "more than the" in many[1]
        assert warned == (threads > os.cpu_count()), many[1]


def test_polydisperse_with_obstacles_and_threads():
    script = """units lj
atom_style sphere
boundary p p fm
region box block 0 12 0 12 0 30
create_box 1 box
create_packing 1200 1 0.5 77 floor 0.0 dispersity 0.3
variable low atom z<1.0
group bottom variable low
group grains subtract all bottom
fix tap grains tapdilate 0.05 floor 0.0
fix settle grains mc/settle 5 floor 0.0 eta 1e-4 check 4096 threads {threads}
""" + THERMO + """dump d all custom 1 dump.taps id x y z radius xu yu
dump_modify d sort id format float %.17g
run 6
"""
    one = run(script.format(threads=1))
    expect_same(one, run(script.format(threads=3)))


@pytest.mark.parametrize("nprocs,grid", [(2, "2 1 1"), (4, "2 2 1")])
def test_domain_scheme_with_threads_in_each_rank(nprocs, grid):
    one = run(tapping("p p fm", 1, grid=grid, scheme="domain", taps=6), nprocs)
    expect_same(one, run(tapping("p p fm", 2, grid=grid, scheme="domain", taps=6), nprocs))


def test_threads_auto_runs_the_same_trajectory():
    one = run(tapping("p p fm", 1, taps=4))
    expect_same(one, run(tapping("p p fm", "auto", taps=4)))
