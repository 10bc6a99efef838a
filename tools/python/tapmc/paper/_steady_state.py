# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The steady state of the constant-eps P.B.C. runs, shared by Figs. 3 and 4: the runs (one
per eps of ``scale.steady_eps`` and seed) and the segment of the taps taken as the steady state
(section III.A)."""

from __future__ import annotations

from . import _runs

#: Boundary conditions of the steady-state runs (Figs. 3 and 4: P.B.C.).
BC = "pbc"


def runs(scale, seeds):
    """Constant-eps P.B.C. runs, one per eps of ``scale.steady_eps`` and seed."""
    return [_runs.constant_eps_run(scale, BC, eps, s)
            for eps in scale.steady_eps for s in _runs.seed_list(seeds)]


def steady_last(taps):
    """Taps of the steady segment: the last quarter, the paper's proportion (the last 1000
    of 4000 taps), and at least the 16 samples a spectrum needs."""
    return int(min(max(taps // 4, 16), taps))
