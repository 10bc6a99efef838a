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


def test_styles_survive_clear():
    lmp = make_lammps()
    lmp.commands_string(SETUP + "fix tap all tapdilate 0.5 floor 0.0\nrun 1\nclear")
    lmp.commands_string(SETUP + "fix tap all tapdilate 1.0 floor 0.0\nrun 1")
    np.testing.assert_allclose(heights(lmp), [4.0, 8.0], rtol=1e-14)
    lmp.close()
