# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""theta0: does theta0 = pi/4 give the largest compaction rate, and does a much smaller
theta0 decompact (section II)? From the same fresh packings (N = 1024, the paper's bed height
on a 16R base, P.B.C., eps = 0.0225, the default eta) 100 taps at seven widths theta0 of the
trial moves' angular distribution (eq. 1), pi/16 to pi/2: <Phi^c> at t = 0 and its mean over
taps 91-100 per seed (theta0.csv). --N sets the spheres (box 32R sqrt(N/4096), the paper's
bed height; the CSV then ends in _N<N>); a scan started again skips the runs its CSV has.
--stop drift (with --eta, default 1e-7: the front's reference) repeats it with a converged
redeposition, into theta0_drift.csv. --theta-law solid reads P(theta) of eq. 1 per unit solid
angle (fix mc/settle theta_law solid; CSV tag _solid); --theta-law exponential or linear scans
section II's alternative laws of the same width (CSV tags _exponential, _linear: the claim
theta-law-shape sets them against eq. 1's scan of the same N and stop); --wide scans instead
the widths beyond the paper's truncation pi/2 (3/4 pi, pi, 30 pi: the flat limit; CSV tag
_wide)."""

from __future__ import annotations

import numpy as np

from . import knob_scan

NAME = "theta0"


def add_arguments(parser):
    knob_scan.add_arguments(parser)
    parser.add_argument("--theta-law", choices=("angle", "solid", "exponential", "linear"), default="angle")
    parser.add_argument("--wide", action="store_true")


def measure(args):
    law = args.theta_law
    tags = ([law] if law != "angle" else []) + (["wide"] if args.wide else [])
    widths = knob_scan.THETA0_WIDE_PI if args.wide else knob_scan.THETA0_PI
    knob_scan.knob_scan(args, "theta0_over_pi", [(f, np.pi * f) for f in widths], "theta0",
                        extra_keys=f"theta_law {law}" if law != "angle" else "",
                        extra_tags=tags)
