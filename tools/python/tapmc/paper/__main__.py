# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""``python3 -m tapmc.paper`` = the ``tapmc-paper`` command."""

import sys

from .cli import main

sys.exit(main())
