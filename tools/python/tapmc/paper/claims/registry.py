# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The statistics the register (``claims.toml``) can name: each statistic module registers its
functions here with :func:`statistic`, the way LAMMPS registers its granular sub-models, so
the name in the register leads to the one function that computes the claim's number."""

from __future__ import annotations

#: name in claims.toml -> statistic(data, claim) -> [Measure, ...]
STATISTICS = {}


def statistic(name):
    """Register the decorated function as the statistic ``name`` of the register."""
    def register(function):
        if name in STATISTICS:
            raise ValueError(f"statistic {name!r} registered twice ({STATISTICS[name].__module__}"
                             f" and {function.__module__})")
        STATISTICS[name] = function
        return function
    return register
