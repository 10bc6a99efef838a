# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""What the campaign tests share: the paths of the build they test, the tiny run they make,
the bytes of a restart file that looks whole and the reader of a per-tap file's steps."""

import os
import sys
from pathlib import Path

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
BUILD = Path(os.environ.get("TAPMC_BUILD_DIR", SOURCE / "build"))
LMP = Path(os.environ.get("TAPMC_LMP", BUILD / "lmp_tapmc"))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

CONSTANT_EPS = SOURCE / "examples" / "paper" / "in.constant_eps"
#: a run of seconds: 64 spheres in an 8R box, a loose threshold, a restart every 5 taps
TINY = dict(N=64, L=8, eta=1e-5, rsteps=5, thermo_every=5)
#: a stand-in for a restart file that looks whole to the campaign: LAMMPS's marks at its start
#: (with the byte order and format revision 2) and at its end
WHOLE_RESTART = (b"LammpS RestartT\0" + (1).to_bytes(4, "little") + (2).to_bytes(4, "little")
                 + b"x" * 64 + b"LammpS RestartT\0")


def steps(path):
    """Steps of the data rows of a per-tap file."""
    return [int(line.split()[0]) for line in Path(path).read_text().splitlines()
            if line.strip() and not line.startswith("#")]
