# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The steady state of the constant-eps P.B.C. runs, shared by Figs. 3 and 4: the runs (one
per eps of ``scale.steady_eps`` and seed) and the segment of the taps taken as the steady state
(section III.A)."""

from __future__ import annotations

import numpy as np

from tapmc.fluctuations import DEFAULT_BATCHES, SteadyState

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


def sigma_error_one_run(x, last, batches=DEFAULT_BATCHES, detrend="constant"):
    """Error of sigma_X over the last ``last`` taps of one run: batch means of the squared
    deviations (from the segment's mean, or its straight line: ``detrend``) give the error of
    sigma_X^2, propagated to sigma_X."""
    dev2 = SteadyState(x, last=last, detrend=detrend).deviations() ** 2
    size = len(dev2) // batches
    if size < 1 or batches < 2:
        return np.nan
    means = dev2[: size * batches].reshape(batches, size).mean(axis=1)
    var_err = float(np.std(means, ddof=1) / np.sqrt(batches))
    sigma = float(np.sqrt(dev2.mean()))
    return var_err / (2.0 * sigma) if sigma > 0 else np.nan
