# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""``python3 -m tapmc.paper`` = the ``tapmc-paper`` command."""

import os
import sys

try:  # the command's modules take about 1.5 s to import: Ctrl-C then is main()'s one line too
    from .cli import main
except KeyboardInterrupt:
    print("tapmc-paper: interrupted (Ctrl-C)", file=sys.stderr)
    sys.exit(130)

try:
    status = main()
    sys.stdout.flush()
except BrokenPipeError:
    # The reader of our output left (``tapmc-paper ... --dry-run | head``): stop quietly, as
    # shell tools do, instead of a traceback; stdout goes to /dev/null so that the
    # interpreter's own final flush fails no more.
    os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    status = 1
sys.exit(status)
