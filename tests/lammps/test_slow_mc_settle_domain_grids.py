# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Slow statistical validation (label "slow"; TAPMC_SLOW=1 tools/run-tests.sh): the domain-
# decomposed redeposition gives the serial scheme's physics on every processor grid, for strong
# taps that lift the bed above the box top. Three scenes of 2048 spheres on a 16 x 16 base:
#   shrink  periodic sides, shrink-wrapped top with a minimum ('p p fm', box 12 high: the first
#           taps lift the deposited bed, centres up to 8.2, above it), monodisperse, eps = 0.5;
#   walls   side walls, shrink-wrapped top without a minimum ('f f fs': the box, and a split z's
#           sub-domains, follow the bed up at every tap and down during every redeposition),
#           polydisperse (W = 0.3), eps = 0.7;
#   fixed   periodic sides, a fixed top far above the bed ('p p f', 30 high), eps = 0.5;
# on x, y, z, x-y, x-z and x-y-z grids of 2, 3, 4 and 8 ranks. Over 8 independent seeds, each
# grid's <Phi^c>, <Z> and bed top (90th percentile of the centres' heights) over the last taps
# agree with the serial scheme's within 4 combined standard errors, and no sphere hangs over a
# hole at the end (free-drop oracle). 4 standard errors: 36 comparisons with t of about 14
# degrees of freedom give a false alarm in about 5 % of full runs (3.5 errors and 4 seeds gave
# one in two). About 35 minutes on two busy cores; the fast version is
# test_mc_settle_domain_grids.py.
import os

import numpy as np
import pytest

from lmprun import free_drops, read_dump, run_lammps, thermo_table

SEEDS = [11, 22, 33, 44, 55, 66, 77, 88]
TOLERANCE_SE = 4.0
TAPS = 8
LAST = 4  # taps averaged per run
RADIUS = 0.5

SCENES = {
    "shrink": dict(boundary="p p fm", height=12, dispersity="", eps=0.5),
    "walls": dict(boundary="f f fs", height=12, dispersity="dispersity 0.3", eps=0.7),
    "fixed": dict(boundary="p p f", height=30, dispersity="", eps=0.5),
}
GRIDS = {
    "shrink": [(2, "2 1 1"), (2, "1 2 1"), (2, "1 1 2"), (3, "1 1 3"), (4, "2 2 1"),
               (4, "2 1 2"), (8, "2 2 2")],
    "walls": [(2, "1 1 2"), (3, "3 1 1"), (4, "1 2 2")],
    "fixed": [(2, "1 1 2"), (4, "2 2 1")],
}
CASES = [(scene, nprocs, grid) for scene, grids in GRIDS.items() for nprocs, grid in grids]

SCRIPT = """processors {grid}
units lj
atom_style sphere
boundary {boundary}
region box block 0 16 0 16 0 {height}
create_box 1 box
create_packing 2048 1 0.5 {seed} floor 0.0 {dispersity}
fix tap all tapdilate {eps} floor 0.0
fix settle all mc/settle {seed} floor 0.0 eta 1e-5 scheme {scheme}
compute phi all stereo/profile floor 0.0
thermo_style custom step c_phi[2] f_settle[3]
thermo_modify format float %.8f lost error
thermo 1
dump d all custom 1 dump.taps id z
dump_modify d sort id format float %.17g
dump e all custom {taps} dump.end id x y z radius
dump_modify e sort id format float %.17g
run {taps}
"""
OBSERVABLES = ["<Phi^c>", "<Z>", "90th percentile z"]


def run_means(scene, nprocs, grid, seed, workdir):
    """Observables averaged over the last taps of one run; asserts the end packing's support."""
    spec = SCENES[scene]
    scheme = "gather" if nprocs == 1 else "domain verify yes"
    script = SCRIPT.format(grid=grid, seed=seed, scheme=scheme, taps=TAPS, **spec)
    rc, out, wd = run_lammps(script, nprocs=nprocs, workdir=workdir)
    assert rc == 0, out
    rows = thermo_table(out, "c_phi[2]")[1][1:, 1:3]
    assert len(rows) == TAPS, out
    rows = rows[-LAST:]
    frames = read_dump(os.path.join(wd, "dump.taps"))[-LAST:]
    heights = np.array([[np.percentile(cols["z"], 90)] for _, _, _, cols in frames])
    _, box, _, cols = read_dump(os.path.join(wd, "dump.end"))[-1]
    xyz = np.column_stack([cols["x"], cols["y"], cols["z"]])
    periodic = (spec["boundary"][0] == "p", spec["boundary"][2] == "p")
    drops = free_drops(xyz, cols["radius"], box, periodic, 0.0)
    assert drops.max() < 2 * RADIUS, (
        f"{scene} {grid} seed {seed}: {(drops >= 2 * RADIUS).sum()} spheres hang over a hole")
    return np.concatenate([rows.mean(axis=0), heights.mean(axis=0)])


@pytest.fixture(scope="module")
def serial_means(tmp_path_factory):
    return {scene: np.array([run_means(scene, 1, "1 1 1", seed,
                                       str(tmp_path_factory.mktemp(f"{scene}s{seed}")))
                             for seed in SEEDS])
            for scene in SCENES}


@pytest.mark.parametrize("scene,nprocs,grid", CASES)
def test_every_grid_gives_the_serial_physics(serial_means, tmp_path, scene, nprocs, grid):
    parallel = []
    for seed in SEEDS:
        (tmp_path / f"s{seed}").mkdir()
        parallel.append(run_means(scene, nprocs, grid, seed, str(tmp_path / f"s{seed}")))
    parallel = np.array(parallel)
    serial = serial_means[scene]
    n = len(SEEDS)
    for k, name in enumerate(OBSERVABLES):
        a, b = serial[:, k], parallel[:, k]
        se = np.hypot(a.std(ddof=1), b.std(ddof=1)) / np.sqrt(n)
        print(f"{scene} {grid}: {name} serial {a.mean():.4f}, {nprocs} ranks {b.mean():.4f} "
              f"({(b.mean() - a.mean()) / se:+.2f} SE)")
        assert abs(b.mean() - a.mean()) <= TOLERANCE_SE * se, name
