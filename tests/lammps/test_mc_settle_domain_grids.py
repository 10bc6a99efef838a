# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# The domain-decomposed redeposition gives the serial scheme's physics on every processor grid,
# also when a tap lifts the bed above the box top (a shrink-wrapped top then grows, and the
# sub-domains of a z split move with it during the redeposition): <Phi^c> and <Z> after every
# tap agree with the serial scheme's from the same packing, and no sphere is left hanging over a
# hole (the independent free-drop oracle of lmprun). Strong taps (eps = 0.5) of a 4096-sphere
# bed in a 16 x 16 x 24 box, whose bed rises above z = 24 from the second tap on. The slow
# version (more grids, ranks, seeds and taps): test_slow_mc_settle_domain.py.
import functools
import os

import numpy as np
import pytest

from lmprun import free_drops, read_dump, run_lammps, thermo_table

RADIUS = 0.5
TAPS = 4
# One tap's <Phi^c> from two independent trajectories of the same packing differs by about
# 0.002 (and <Z> by about 0.05) at this size; a bed that hangs on a sub-domain face loses 0.1
# of <Phi^c> and gains 1.5 of <Z> within four taps.
PHI_C_TOLERANCE = 0.01
Z_TOLERANCE = 0.15

SCRIPT = """{processors}
units lj
atom_style sphere
boundary {boundary}
region box block 0 16 0 16 0 24
create_box 1 box
create_packing 4096 1 0.5 4928 floor 0.0 {dispersity}
fix tap all tapdilate 0.5 floor 0.0
fix settle all mc/settle 77 floor 0.0 eta 1e-5 scheme {scheme}
compute phi all stereo/profile floor 0.0
thermo_style custom step c_phi[2] f_settle[3] zhi
thermo_modify format float %.8f lost error
thermo 1
dump d all custom {taps} dump.end id x y z radius
dump_modify d sort id format float %.17g
run {taps}
"""


def tapping(nprocs, grid, boundary, dispersity, scheme):
    """(per-tap rows of <Phi^c> and <Z>, last frame, output) of the scene on a grid."""
    processors = f"processors {grid}" if grid else ""
    script = SCRIPT.format(processors=processors, boundary=boundary, scheme=scheme,
                           dispersity=dispersity, taps=TAPS)
    rc, out, wd = run_lammps(script, nprocs=nprocs)
    assert rc == 0, out
    rows = thermo_table(out, "c_phi[2]")[1][1:, 1:3]
    assert len(rows) == TAPS, out
    return rows, read_dump(os.path.join(wd, "dump.end"))[-1], out


@functools.lru_cache(maxsize=None)
def serial(boundary, dispersity):
    return tapping(1, "1 1 1", boundary, dispersity, "gather")


def assert_serial_physics(rows, frame, boundary, dispersity):
    reference, _, _ = serial(boundary, dispersity)
    for tap, (got, want) in enumerate(zip(rows, reference), start=1):
        assert abs(got[0] - want[0]) < PHI_C_TOLERANCE, (
            f"tap {tap}: <Phi^c> {got[0]:.4f}, serial scheme {want[0]:.4f}")
        assert abs(got[1] - want[1]) < Z_TOLERANCE, (
            f"tap {tap}: <Z> {got[1]:.3f}, serial scheme {want[1]:.3f}")
    _, box, _, cols = frame
    assert len(cols["id"]) == 4096
    xyz = np.column_stack([cols["x"], cols["y"], cols["z"]])
    drops = free_drops(xyz, cols["radius"], box, (boundary[0] == "p", boundary[2] == "p"), 0.0)
    hanging = np.flatnonzero(drops >= 2 * RADIUS)
    assert hanging.size == 0, (f"{hanging.size} spheres hang over a hole (largest free drop "
                               f"{drops.max():.2f} at z = {xyz[drops.argmax(), 2]:.2f})")


@pytest.mark.parametrize("nprocs,grid,boundary,dispersity", [
    (2, "1 1 2", "p p fm", ""),
    (2, "2 1 1", "p p fm", ""),
    (3, "1 1 3", "p p fm", ""),
    (2, "1 1 2", "f f fm", "dispersity 0.3"),
    (2, "1 1 2", "p p fs", ""),
])
def test_strong_taps_give_the_serial_physics_on_every_grid(nprocs, grid, boundary, dispersity):
    rows, frame, _ = tapping(nprocs, grid, boundary, dispersity, "domain verify yes")
    assert_serial_physics(rows, frame, boundary, dispersity)


def test_the_grid_lammps_chooses_itself_gives_the_serial_physics():
    """Without a processors command LAMMPS splits this box along z on 2 ranks."""
    rows, frame, out = tapping(2, None, "p p fm", "", "domain verify yes")
    assert "1 by 1 by 2 MPI processor grid" in out
    assert_serial_physics(rows, frame, "p p fm", "")
