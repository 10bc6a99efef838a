# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Slow statistical validation (label "slow"; TAPMC_SLOW=1 tools/run-tests.sh): on the paper's
# periodic set-up, 200 taps at eps = 0.01 with the default redeposition compact the packing for
# every one of 5 independent seeds (initial packing and moves), and the mean rise of Phi_b and
# <Phi^c> over the seeds is positive by more than 3 standard errors. About 15 minutes.

import numpy as np
import pytest

from lmprun import run_lammps
from lmprun import thermo_table
from test_compaction import EXAMPLE

SEEDS = [101, 202, 303, 404, 505]


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    with open(EXAMPLE) as f:
        script = f.read()
    results = {}
    for seed in SEEDS:
        rc, out, _ = run_lammps(script, workdir=str(tmp_path_factory.mktemp(f"seed{seed}")),
                                variables={"taps": 200, "seed": seed})
        assert rc == 0, out
        names, table = thermo_table(out)
        results[seed] = {name: table[:, k] for k, name in enumerate(names)}
    return results


@pytest.mark.parametrize("column", ["c_phi[1]", "c_phi[2]"])
def test_packing_fraction_rises_for_every_seed(runs, column):
    rises = []
    for seed, cols in runs.items():
        late = cols[column][cols["Step"] >= 170].mean()
        rises.append(late - cols[column][0])
        print(f"seed {seed}: {column} {cols[column][0]:.4f} -> {late:.4f}")
    rises = np.array(rises)
    stderr = rises.std(ddof=1) / np.sqrt(len(rises))
    print(f"{column}: mean rise {rises.mean():.4f} +- {stderr:.4f} (standard error, 5 seeds)")
    assert (rises > 0).all()
    assert rises.mean() > 3 * stderr
