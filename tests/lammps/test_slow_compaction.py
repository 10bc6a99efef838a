# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Slow validation (label "slow"; TAPMC_SLOW=1 tools/run-tests.sh): the paper's periodic set-up
# as shipped (examples/tapping/in.tapping_pbc: 4096 spheres, L = 32R, Jullien-Meakin start, seed
# 4928) tapped 200 times at eps = 0.01 with the default redeposition settings densifies, measured
# by the exact stereology compute. About 3 minutes of one core.
from lmprun import run_lammps
from lmprun import thermo_table
from test_compaction import EXAMPLE


def test_bulk_packing_fraction_rises_over_200_taps(tmp_path):
    with open(EXAMPLE) as f:
        script = f.read()
    rc, out, _ = run_lammps(script, workdir=str(tmp_path), variables={"taps": 200}, timeout=3600)
    assert rc == 0, out
    names, table = thermo_table(out)
    col = {name: k for k, name in enumerate(names)}
    step, phi_b, phi_c, mean_z = (table[:, col[c]] for c in
                                  ("Step", "c_phi[1]", "c_phi[2]", "c_phi[3]"))
    hit_cap = table[:, col["f_settle[4]"]]
    print("step  Phi_b  <Phi^c>  <Z>")
    for row in zip(step, phi_b, phi_c, mean_z):
        print("%4d  %.4f  %.4f  %.4f" % row)
    assert step[-1] == 200
    assert not hit_cap.any(), "a redeposition stopped at the sweep cap"
    # The bulk fraction rises: the last 30 taps are denser than the start and than tap 5.
    late = phi_b[step >= 170].mean()
    assert late > phi_b[0] + 0.008, (phi_b[0], late)
    assert late > phi_b[1] + 0.008, (phi_b[1], late)
    # and the potential energy per sphere falls after the first taps.
    assert mean_z[step >= 170].mean() < mean_z[1] - 0.05
