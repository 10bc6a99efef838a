# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# The shared library registers the TAPMC styles in a lammps.lammps() instance from Python
# (Debian's python3-lammps, ctypes), and they survive a `clear`.
import ctypes
import os

import numpy as np
import pytest

lammps = pytest.importorskip("lammps")

LIB = os.environ.get("TAPMC_LIB", os.path.join(os.environ.get("TAPMC_BUILD_DIR", "../../build"),
                                                "libtapmc.so"))

SETUP = """
units lj
atom_style sphere
boundary p p fm
region box block 0 6 0 6 0 8
create_box 1 box
create_atoms 1 single 1 1 2
create_atoms 1 single 3 3 4
set group all diameter 1.0
"""


def make_lammps():
    lmp = lammps.lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    assert ctypes.CDLL(LIB).tapmc_register(ctypes.c_void_p(lmp.lmp.value)) == 0
    return lmp


def heights(lmp):
    x = lmp.numpy.extract_atom("x")
    tag = lmp.numpy.extract_atom("id")
    return np.asarray(x[np.argsort(tag), 2])


def test_tapdilate_from_python():
    lmp = make_lammps()
    lmp.commands_string(SETUP + "fix tap all tapdilate 0.5 floor 0.0\nrun 2")
    np.testing.assert_allclose(heights(lmp), [2 * 1.5 ** 2, 4 * 1.5 ** 2], rtol=1e-14)
    assert lmp.extract_fix("tap", 0, 0) == pytest.approx(0.5)
    lmp.close()


def test_extract_fix_of_mc_settle_matches_thermo_and_refuses_other_indices():
    """The 13 values of fix mc/settle through the library interface are those thermo prints;
    an index beyond them (which the library does not check) gives NaN, where it read past the
    values (5e-324 at index 13)."""
    lmp = make_lammps()
    lmp.commands_string(SETUP + "fix settle all mc/settle 7 floor 0.0 eta 1e-3\n"
                        "variable trials equal f_settle[5]\nrun 1")
    values = [lmp.extract_fix("settle", 0, 1, n) for n in range(13)]
    assert values[4] == lmp.extract_variable("trials") > 0
    assert values[0] == pytest.approx(values[4] / 2)  # sweeps = trials / movable spheres
    for n in (13, 20, -1):
        assert np.isnan(lmp.extract_fix("settle", 0, 1, n)), n
    lmp.close()


def test_styles_survive_clear():
    lmp = make_lammps()
    lmp.commands_string(SETUP + "fix tap all tapdilate 0.5 floor 0.0\nrun 1\nclear")
    lmp.commands_string(SETUP + "fix tap all tapdilate 1.0 floor 0.0\nrun 1")
    np.testing.assert_allclose(heights(lmp), [4.0, 8.0], rtol=1e-14)
    lmp.close()


def test_a_compute_read_after_a_tap_describes_the_packing_after_it():
    """An eps variable that reads compute stereo/profile evaluates it before the tap, stamped
    with the step: the library handed out those values after the tap and the redeposition as
    current (<Z> one tap behind, every tap). After TAPMC moves atoms the computes are
    computed again: <Z> is the spheres' mean height and fix mc/settle's, and the variable,
    read between runs (which LAMMPS allows for a compute current at the run's last step),
    is that of the packing after the tap, not an error."""
    lmp = make_lammps()
    lmp.commands_string("""
units lj
atom_style sphere
boundary p p fm
region box block 0 6 0 6 0 30
create_box 1 box
create_packing 300 1 0.5 4928 floor 0.0
compute phi all stereo/profile floor 0.0
variable e equal 0.01+0.1*(0.58-c_phi[2])
fix tap all tapdilate v_e floor 0.0
fix settle all mc/settle 77 floor 0.0 eta 1e-5
""")
    for _ in range(3):
        lmp.command("run 1")
        mean_z = lmp.numpy.extract_compute("phi", lammps.LMP_STYLE_GLOBAL,
                                           lammps.LMP_TYPE_VECTOR)[2]
        assert mean_z == pytest.approx(heights(lmp).mean(), rel=1e-12)
        assert mean_z == pytest.approx(lmp.extract_fix("settle", 0, 1, 2), rel=1e-12)
        phi_c = lmp.numpy.extract_compute("phi", lammps.LMP_STYLE_GLOBAL,
                                          lammps.LMP_TYPE_VECTOR)[1]
        assert lmp.extract_variable("e") == pytest.approx(0.01 + 0.1 * (0.58 - phi_c),
                                                          rel=1e-12)
    lmp.close()
