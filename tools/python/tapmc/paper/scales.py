# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Scales of the paper's campaigns: ``QUICK`` (minutes on 2 cores, used by the tests), ``MEDIUM``
(the validation report's) and ``FULL`` (the paper's set-up, section II: N = 4096 spheres,
L = 32R, 4000 taps).

A :class:`Scale` holds every size the figure modules need; ``Scale.replace(**fields)`` gives a
variant (e.g. ``FULL.replace(seeds=20)``). Lengths are in units of the sphere radius R; eps is
the dilation of one tap, the excitation is sqrt(eps) (paper, eq. 2).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

# (sqrt eps)* ~ 0.15 of section III.B: a ramp that went beyond it comes back on the reversible
# branch, one that stayed below it on the irreversible (nearly frozen) one.
from ..hysteresis import CRITICAL_SQRT_EPS

__all__ = ["Scale", "QUICK", "MEDIUM", "FULL", "SCALES", "get_scale", "FBC_STARTS",
           "CRITICAL_SQRT_EPS"]

#: The F.B.C. initial packings of ``in.constant_eps`` (``-var fbc_start``): ``walls``, deposited
#: directly between the side walls; ``paper``, the paper's (section IV.A): a periodic
#: deposition, then the walls and a slight agitation (examples/paper/README.md).
FBC_STARTS = ("walls", "paper")


def _sq(values):
    return tuple(round(v * v, 10) for v in values)


@dataclass(frozen=True)
class Scale:
    """Sizes of one campaign scale (all fields read-only; see QUICK and FULL)."""

    name: str
    N: int                            #: spheres per packing
    L: float                          #: box side in units of R
    eta: float                        #: redeposition threshold of fix mc/settle
    taps: int                         #: taps of a constant-eps run
    seeds: int                        #: default number of seeds (realizations)
    steady_last: int                  #: taps averaged for a steady state (paper: last 1000)
    fig2_eps: tuple                   #: Fig. 2 eps values (FBC)
    steady_eps: tuple                 #: Figs. 3-4 eps values of the constant-eps PBC runs
    ramp_sqrt0: float                 #: Fig. 4 ramp: first sqrt(eps)
    ramp_dsqrt: float                 #: Fig. 4 ramp: sqrt(eps) step (paper: 0.025)
    ramp_levels: int                  #: Fig. 4 ramp: levels of the first up branch
    ramp_taps_per_level: int          #: Fig. 4 ramp: taps per level (paper: 4000)
    ageing_eps: float                 #: Fig. 5 eps
    ageing_taps: int                  #: Fig. 5 taps per realization
    ageing_waiting_times: tuple       #: Fig. 5 waiting times t_W
    profile_eps: tuple                #: Figs. 6-8 eps values (FBC); Figs. 6-7 use the largest
    pore_eps: float                   #: Fig. 10 eps (paper: 2e-2, FBC)
    dump_times: tuple                 #: Fig. 10 dump taps (t = 0 is always dumped)
    pore_bc: str = "fbc"              #: Fig. 10 boundary conditions
    restart_every: int = 500          #: taps between restart files (what a killed run loses)
    p0_eps: float = 0.0225            #: Fig. 9 eps (P.B.C. constant-eps run, dumped at both ends)
    fbc_start: str = "walls"          #: F.B.C. initial packing of the constant-eps runs (FBC_STARTS)
    ramp_below_top: float = 0.125     #: Fig. 4 second ramp: highest sqrt(eps), below CRITICAL_SQRT_EPS

    def __post_init__(self):
        for field in ("N", "taps", "seeds", "steady_last", "ramp_levels",
                      "ramp_taps_per_level", "ageing_taps", "restart_every"):
            value = getattr(self, field)
            if isinstance(value, bool) or not isinstance(value, int) or value < 1:
                raise ValueError(f"Scale.{field} = {value!r}: must be an integer >= 1")
        for field in ("L", "eta", "ramp_sqrt0", "ramp_dsqrt", "ageing_eps", "pore_eps",
                      "p0_eps"):
            value = getattr(self, field)
            if not isinstance(value, (int, float)) or not value > 0:
                raise ValueError(f"Scale.{field} = {value!r}: must be a number > 0")
        if not self.eta < 1:
            raise ValueError(f"Scale.eta = {self.eta!r}: must be in (0, 1)")
        for field in ("fig2_eps", "steady_eps", "profile_eps", "ageing_waiting_times",
                      "dump_times"):
            values = tuple(getattr(self, field))
            if not values or any(not v > 0 for v in values):
                raise ValueError(f"Scale.{field} = {values!r}: must be a non-empty list of "
                                 "positive numbers")
            object.__setattr__(self, field, values)
        if list(self.dump_times) != sorted(set(self.dump_times)):
            raise ValueError(f"Scale.dump_times = {self.dump_times!r}: must be increasing")
        if self.steady_last > self.taps:
            raise ValueError(f"Scale.steady_last = {self.steady_last}: must be <= taps = "
                             f"{self.taps}")
        if self.pore_bc not in ("pbc", "fbc"):
            raise ValueError(f"Scale.pore_bc = {self.pore_bc!r}: allowed values 'pbc', 'fbc'")
        if self.fbc_start not in FBC_STARTS:
            raise ValueError(f"Scale.fbc_start = {self.fbc_start!r}: allowed values "
                             f"{', '.join(map(repr, FBC_STARTS))}")
        if (not isinstance(self.ramp_below_top, (int, float))
                or not self.ramp_sqrt0 <= self.ramp_below_top < CRITICAL_SQRT_EPS):
            raise ValueError(f"Scale.ramp_below_top = {self.ramp_below_top!r}: must be in "
                             f"[ramp_sqrt0, {CRITICAL_SQRT_EPS}) = [{self.ramp_sqrt0}, "
                             f"{CRITICAL_SQRT_EPS}) (the ramp that stays below (sqrt eps)*)")

    @property
    def ramp_below_levels(self):
        """Levels of the first increase of the ramp that stays below (sqrt eps)*: sqrt(eps) =
        ramp_sqrt0 + k ramp_dsqrt up to ramp_below_top (1e-9 relative tolerance)."""
        return int((self.ramp_below_top - self.ramp_sqrt0) / self.ramp_dsqrt * (1 + 1e-9)) + 1

    @property
    def ramp_near_levels(self):
        """Levels of the first increase of the ramp that turns at the first level beyond
        (sqrt eps)*: the smallest k with ramp_sqrt0 + (k - 1) ramp_dsqrt > CRITICAL_SQRT_EPS
        (FULL: 7, up to 0.175), which with the ramp below it brackets (sqrt eps)* within one
        step of the ramp."""
        return max(1, int((CRITICAL_SQRT_EPS - self.ramp_sqrt0) / self.ramp_dsqrt * (1 + 1e-9)) + 2)

    @property
    def ramp_top(self):
        """Highest sqrt(eps) of the ramp of Fig. 4 (the one meant to go beyond (sqrt eps)*)."""
        return self.ramp_sqrt0 + (self.ramp_levels - 1) * self.ramp_dsqrt

    def replace(self, **fields):
        """A copy with some fields changed (validated again)."""
        return dataclasses.replace(self, **fields)

    def as_dict(self):
        return dataclasses.asdict(self)


#: Small packings and few taps: every figure's campaign in about a minute on 2 cores.
QUICK = Scale(
    name="quick", N=512, L=16.0, eta=1e-5, taps=100, seeds=2, steady_last=25,
    fig2_eps=(5e-3, 5e-2, 0.15),
    steady_eps=_sq((0.05, 0.1, 0.2, 0.3)),
    ramp_sqrt0=0.05, ramp_dsqrt=0.05, ramp_levels=4, ramp_taps_per_level=25,
    ageing_eps=0.01, ageing_taps=100, ageing_waiting_times=(5, 10, 20, 40),
    profile_eps=(5e-3, 2e-2, 5e-2, 0.1),
    pore_eps=2e-2, dump_times=(1, 4, 10, 30, 100), p0_eps=0.04,
)

#: The paper's set-up (section II): 4096 spheres, L = 32R, 4000 taps; one run per point (section
#: III.B), 10 realizations for the ageing (section III.C), the seeds here. The bell
#: (Fig. 4 squares, steady_eps) spans sqrt(eps) = 0.05 to 0.387, dense around the maximum the
#: paper places between 0.1 and 0.2, and holds Fig. 2's eps = 5e-3, 5e-2, 0.15 and Figs. 6-7's
#: eps = 0.1 at P.B.C.
FULL = Scale(
    name="full", N=4096, L=32.0, eta=1e-7, taps=4000, seeds=10, steady_last=1000,
    fig2_eps=(5e-3, 5e-2, 0.15),
    steady_eps=(0.0025, 0.005, 0.01, 0.015625, 0.0225, 0.04, 0.05, 0.09, 0.1, 0.15),
    ramp_sqrt0=0.025, ramp_dsqrt=0.025, ramp_levels=12, ramp_taps_per_level=4000,
    ageing_eps=0.01, ageing_taps=4000, ageing_waiting_times=(10, 30, 100, 300, 1000),
    profile_eps=(5e-3, 2e-2, 5e-2, 0.1),
    pore_eps=2e-2, dump_times=(1, 4, 10, 30, 100, 300, 1000, 4000), restart_every=100,
)

#: Between the two: 1024 spheres (the paper's bed height on a 16R x 16R base), 1000 taps, two
#: seeds; about 25 minutes on 2 cores. The smoke test doc/validation.rst is made from this
#: preset.
MEDIUM = Scale(
    name="medium", N=1024, L=16.0, eta=1e-5, taps=1000, seeds=2, steady_last=250,
    fig2_eps=(5e-3, 5e-2, 0.15),
    steady_eps=(0.0025, 0.01, 0.0225, 0.04, 0.09),
    ramp_sqrt0=0.05, ramp_dsqrt=0.05, ramp_levels=5, ramp_taps_per_level=200,
    ageing_eps=0.01, ageing_taps=1000, ageing_waiting_times=(10, 30, 100, 250),
    profile_eps=(5e-3, 2e-2, 5e-2, 0.1),
    pore_eps=2e-2, dump_times=(1, 4, 10, 30, 100, 300, 1000),
)

SCALES = {"quick": QUICK, "medium": MEDIUM, "full": FULL}


def get_scale(name):
    """The preset called ``name`` ('quick', 'medium' or 'full')."""
    try:
        return SCALES[name]
    except KeyError:
        raise ValueError(f"scale = {name!r}: allowed values are {sorted(SCALES)}") from None
