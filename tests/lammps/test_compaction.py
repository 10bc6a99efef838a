# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Compaction happens (fast version): a quarter of the paper's periodic set-up (1024 spheres on a
# 16R x 16R base, so the same bed height as the paper's 4096 on 32R x 32R, Jullien-Meakin start)
# tapped 120 times at eps = 0.01 with the default redeposition settings densifies, measured by
# the exact stereology compute. The paper's full set-up (4096 spheres, 200 taps) is the slow
# test_slow_compaction.py; its spread over seeds is test_slow_compaction_seeds.py.
import glob
import os

import numpy as np

from lmprun import run_lammps, thermo_table

EXAMPLE = os.path.join(os.environ.get("TAPMC_SOURCE_DIR", "../.."), "examples", "tapping",
                       "in.tapping_pbc")

TAPS = 120
SMALL_BED = """units           lj
atom_style      sphere
boundary        p p fm
region          box block 0 8 0 8 0 40
create_box      1 box
create_packing  1024 1 0.5 4928 floor 0.0
compute         phi all stereo/profile floor 0.0
fix             tap all tapdilate 0.01 floor 0.0
fix             settle all mc/settle 4928 floor 0.0
thermo_style    custom step c_phi[1] c_phi[2] c_phi[3] f_settle[1] f_settle[4]
thermo_modify   format float %.6f
thermo          1
run             {taps}
"""
# Margins, from this scene at taps 1-5 against the last 30 of 120, over 8 seeds (101, 202, ...,
# 808): the fall of <Z> was 0.071 to 0.16 (mean 0.114, standard deviation 0.020), the rise of
# Phi_b 0.0038 to 0.013 (mean 0.0084, sd 0.0030). Tap to tap, Phi_b fluctuates by 0.0004 and <Z>
# by 0.007 (sd about a linear trend), so with no compaction the two differences would be about
# 0 +- 0.0002 and 0 +- 0.0035: the margins are 7 and 11 times that noise.
MIN_FALL_OF_MEAN_Z = 0.04
MIN_RISE_OF_PHI_B = 0.0015


def test_small_bed_compacts_over_120_taps(tmp_path):
    rc, out, _ = run_lammps(SMALL_BED.format(taps=TAPS), workdir=str(tmp_path))
    assert rc == 0, out
    names, table = thermo_table(out)
    col = {name: k for k, name in enumerate(names)}
    step, phi_b, mean_z = (table[:, col[c]] for c in ("Step", "c_phi[1]", "c_phi[3]"))
    assert step[-1] == TAPS
    assert not table[:, col["f_settle[4]"]].any(), "a redeposition stopped at the sweep cap"
    first, late = (step >= 1) & (step <= 5), step > TAPS - 30
    print("Phi_b: initial %.4f, taps 1-5 %.4f, last 30 taps %.4f" %
          (phi_b[0], phi_b[first].mean(), phi_b[late].mean()))
    print("<Z>:   initial %.4f, taps 1-5 %.4f, last 30 taps %.4f" %
          (mean_z[0], mean_z[first].mean(), mean_z[late].mean()))
    # The potential energy per sphere falls ...
    assert mean_z[late].mean() < mean_z[first].mean() - MIN_FALL_OF_MEAN_Z
    # ... and the bulk packing fraction rises above the initial packing's and the first taps'.
    assert phi_b[late].mean() > max(phi_b[0], phi_b[first].mean()) + MIN_RISE_OF_PHI_B


def test_example_reference_log_initial_state(tmp_path):
    """examples/tapping/in.tapping_pbc still starts from the packing of its reference log."""
    with open(EXAMPLE) as f:
        script = f.read()
    rc, out, _ = run_lammps(script, workdir=str(tmp_path), variables={"taps": 0})
    assert rc == 0, out
    names, table = thermo_table(out)
    (reference,) = glob.glob(os.path.join(os.path.dirname(EXAMPLE), "log.*.tapping_pbc.g++.1"))
    with open(reference) as f:
        ref_names, ref_table = thermo_table(f.read())
    assert ref_names == names
    np.testing.assert_allclose(table[0, :4], ref_table[0, :4], rtol=1e-6)
