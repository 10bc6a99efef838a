# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The constant-eps F.B.C. runs of the packing-fraction profiles, shared by Figs. 6, 7 and 8
(section IV.A): the runs (one per eps of ``scale.profile_eps`` and seed), the runs at the eps
nearest to the paper's 0.1, and their stereo/profile profiles averaged over seeds.

The runs start from the F.B.C. packing of the scale (``Scale.fbc_start``): deposited between
the walls (``walls``, the default) or the paper's periodic deposition adapted to the walls by a
slight agitation (``paper``, section IV.A), whose under-populated walls make delta
Phi_lateral jump at the first tap (Figs. 7b and 8)."""

from __future__ import annotations

import numpy as np

from . import _plotting as P
from . import _runs

#: Boundary conditions of the profile runs (Figs. 6 to 8: F.B.C.).
BC = "fbc"
#: the paper's eps of Figs. 6 and 7.
PAPER_EPS = 0.1


def runs(scale, seeds):
    """Constant-eps F.B.C. runs, one per eps of ``scale.profile_eps`` and seed."""
    return [_runs.constant_eps_run(scale, BC, eps, s)
            for eps in scale.profile_eps for s in _runs.seed_list(seeds)]


def nearest_eps_runs(campaign, bc=BC, target=PAPER_EPS):
    """(eps, specs) of the campaign's constant-eps runs with eps nearest to ``target``."""
    groups = _runs.constant_eps_groups(campaign, bc)
    eps = min(groups, key=lambda e: abs(np.log(e / target)))
    return eps, groups[eps]


def radius(spec):
    """The sphere radius R of a run (its variable ``R``, 0.5 when it has none)."""
    return float(spec.variables.get("R", 0.5))


def profiles(campaign, specs, filename):
    """(x/R, initial mean, sem, n, final mean, sem, n) over seeds of a stereo/profile file
    (columns: plane position, Phi at the plane, exact bin mean; the bin mean is used)."""
    init, final = [], []
    x = None
    for spec in specs:
        blocks = _runs.profile(campaign, spec, filename).blocks
        x = blocks[0, :, 0] / radius(spec)
        init.append(blocks[0, :, 2])
        final.append(blocks[-1, :, 2])
    return (x, *P.seed_stats(init), *P.seed_stats(final))


def fbc_start(specs):
    """The F.B.C. start of the runs ``specs`` ('walls' or 'paper'; one start for all)."""
    starts = {_runs.fbc_start_of(s) for s in specs}
    if not starts:
        raise ValueError("no F.B.C. run to draw")
    if len(starts) != 1:
        raise ValueError(f"runs {[s.name for s in specs]} mix the F.B.C. starts "
                         f"{sorted(starts)}")
    return starts.pop()


#: legend words of each F.B.C. start.
START_LABEL = {"walls": "F.B.C.", "paper": "F.B.C., the paper's start"}
