# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Slow statistical validation (label "slow"; TAPMC_SLOW=1 tools/run-tests.sh): the physics of the
# domain-decomposed redeposition does not depend on the rank count. Phi_b, <Phi^c> and <Z> after
# T taps of eps = 0.01 (mean over the last taps) on 1 rank (serial kernel), 2 ranks (grid 2 1 1)
# and 4 ranks (grid 2 2 1), over independent seeds: each parallel mean agrees with the serial
# one within 3.5 combined standard errors. About 10 minutes on two cores.
import numpy as np
import pytest

from lmprun import run_lammps
from lmprun import thermo_table

SEEDS = [11, 22, 33, 44, 55, 66]
TAPS = 60
CONFIGS = [(1, "1 1 1", "gather"), (2, "2 1 1", "domain"), (4, "2 2 1", "domain")]

# 2048 spheres of radius 0.5 in the paper's L = 32 R (half the paper's bed height).
SCRIPT = """processors {grid}
units lj
atom_style sphere
boundary p p fm
region box block 0 16 0 16 0 30
create_box 1 box
create_packing 2048 1 0.5 {seed} floor 0.0
compute phi all stereo/profile floor 0.0
fix tap all tapdilate 0.01 floor 0.0
fix settle all mc/settle {seed} floor 0.0 eta 1e-6 scheme {scheme}
thermo_style custom step c_phi[1] c_phi[2] c_phi[3] f_settle[1]
thermo_modify format float %.8f
thermo 1
run {taps}
"""


@pytest.fixture(scope="module")
def late_means(tmp_path_factory):
    """{config: array (seeds x 3) of Phi_b, <Phi^c>, <Z> averaged over the last 20 taps}."""
    means = {}
    for nprocs, grid, scheme in CONFIGS:
        rows = []
        for seed in SEEDS:
            rc, out, _ = run_lammps(
                SCRIPT.format(grid=grid, seed=seed, scheme=scheme, taps=TAPS), nprocs=nprocs,
                workdir=str(tmp_path_factory.mktemp(f"r{nprocs}s{seed}")))
            assert rc == 0, out
            _, table = thermo_table(out)
            rows.append(table[-20:, 1:4].mean(axis=0))
        means[nprocs] = np.array(rows)
    return means


@pytest.mark.parametrize("nprocs", [2, 4])
def test_physics_does_not_depend_on_the_rank_count(late_means, nprocs):
    serial, parallel = late_means[1], late_means[nprocs]
    n = len(SEEDS)
    for k, name in enumerate(["Phi_b", "<Phi^c>", "<Z>"]):
        a, b = serial[:, k], parallel[:, k]
        se = np.hypot(a.std(ddof=1), b.std(ddof=1)) / np.sqrt(n)
        print(f"{name}: 1 rank {a.mean():.5f} +- {a.std(ddof=1) / np.sqrt(n):.5f}, "
              f"{nprocs} ranks {b.mean():.5f} +- {b.std(ddof=1) / np.sqrt(n):.5f}, "
              f"difference {b.mean() - a.mean():+.5f} ({(b.mean() - a.mean()) / se:+.2f} SE)")
        assert abs(b.mean() - a.mean()) <= 3.5 * se, name
