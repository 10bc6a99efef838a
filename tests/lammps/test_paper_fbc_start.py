# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# The paper's F.B.C. start (in.constant_eps -var fbc_start paper, section IV.A) against the
# start deposited between walls, on a small bed (N = 256, L = 12R, eta = 1e-5, eps = 0.1, two
# taps, seeds 1 and 2; a fraction of a second each): the periodic packing adapted to the walls is
# under-populated along them at t = 0 (the transversal profile within 2R of the walls, Fig. 7b)
# and delta Phi_lateral jumps at the first tap (Fig. 8), where the start between walls dips.
# Measured on this scene: Phi within 2R of the walls at t = 0 0.30, 0.36 (paper) against 0.44,
# 0.44 (walls); delta Phi_lateral after tap 1 +0.026, +0.007 against -0.011, -0.014.
import subprocess

import numpy as np
import pytest

from lmprun import LMP
from test_example_switches import EXAMPLES, ave_time_blocks, table

SCENE = {"N": 256, "L": 12, "eta": 1e-5, "bc": "fbc", "eps": 0.1, "taps": 2, "pevery": 1}
R = 0.5


def run_start(workdir, start, seed):
    cmd = [LMP, "-in", str(EXAMPLES / "paper" / "in.constant_eps"), "-log", "log.lammps",
           "-nocite", "-screen", "none"]
    for name, value in dict(SCENE, fbc_start=start, seed=seed).items():
        cmd += ["-var", name, str(value)]
    workdir.mkdir()
    proc = subprocess.run(cmd, cwd=workdir, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, (workdir / "log.lammps").read_text()[-2000:]
    lateral = table(workdir / "taps.dat")[:, 5]
    block = ave_time_blocks(workdir / "profile_x.dat")[0]
    x, phi = (np.array([float(row.split()[k]) for row in block]) for k in (1, 3))
    dist = np.minimum(x, SCENE["L"] * R - x) / R
    return lateral[1] - lateral[0], float(phi[dist < 2].mean())


@pytest.mark.parametrize("seed", [1, 2])
def test_paper_start_under_populated_walls_and_first_tap_jump(tmp_path, seed):
    jump_paper, walls_phi_paper = run_start(tmp_path / "paper", "paper", seed)
    jump_walls, walls_phi_walls = run_start(tmp_path / "walls", "walls", seed)
    assert walls_phi_paper < walls_phi_walls - 0.05
    assert jump_paper > 0.005 and jump_walls < 0
