# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""dmax: is d_max = R/5 an intermediate value, much smaller or larger steps slowing the
redeposition (section II)? The same scan as theta0 over seven d_max, R/50 to R (dmax.csv;
--stop drift: dmax_drift.csv)."""

from __future__ import annotations

from . import knob_scan

NAME = "dmax"


def add_arguments(parser):
    knob_scan.add_arguments(parser)


def measure(args):
    knob_scan.knob_scan(args, "dmax_over_R",
                        [(f, f * knob_scan.THETA0_RADIUS) for f in knob_scan.DMAX_OVER_R], "dmax")
