# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""What a statistic measures (:class:`Measure`) and how the report prints a number
(:func:`fmt`)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass
class Measure:
    """What a statistic measured for one row: ``value`` with standard error ``err`` whose
    degrees of freedom are ``dof``; ``shown`` replaces the default text of the value;
    ``quantile`` replaces the t quantile (e.g. Bonferroni-corrected maxima); ``sign`` the
    claim's expected sign (a claim measured twice, e.g. both sides of a bell); ``effect`` is the
    size of the effect a ``zero`` claim denies (agreement needs an uncertainty below it);
    ``undecided`` says why the data cannot decide (the value may still be shown); ``lacks``
    the aspects of the paper's scale (:data:`ASPECTS`) this measure's own runs lack, when they
    are not the campaign's (a scan at N = 1024); ``p_value`` is a fit test's own p-value (the
    F of tapmc.laws.RealizationLawTest), which the fit rule uses instead of the chi-square's;
    ``systematic`` = (low, high) how far a bias the measure does not sample could move the
    value (a ramp's levels at fewer taps than the paper's: :mod:`.reduced_ramps`), on top of
    its error: the rule then decides only where its verdict is the same anywhere within it;
    ``paper_precision`` is a law's largest departure from the data in units of the paper's
    precision for it (claims.common.paper_precision): at most 1, the fit rule calls a law its
    test rejects one that agrees at the paper's precision, not at ours; ``meets`` the aspects
    of the paper's scale this measure's own runs have when the campaign's other runs lack them
    (the ramps at the paper's 4000 taps per level in a campaign whose Fig. 4 ramps have 1000)."""

    value: float = math.nan
    err: float = math.nan
    dof: float | None = None
    label: str = ""
    shown: str | None = None
    quantile: float | None = None
    effect: float | None = None
    sign: int | None = None
    undecided: str | None = None
    lacks: tuple = ()
    p_value: float | None = None
    systematic: tuple | None = None
    paper_precision: float | None = None
    meets: tuple = ()

    def text(self):
        if self.shown is not None:
            return self.shown
        return fmt(self.value, self.err)


def fmt(value, err=None, pct=False, digits=3):
    """A number with its error, as the report prints it ("n/a" when not finite)."""
    if value is None or not np.isfinite(value):
        return "n/a"
    if pct:
        if err is None or not np.isfinite(err):
            return f"{100 * value:.2f} %"
        return f"{100 * value:.2f} ± {100 * err:.2f} %"
    if err is None or not np.isfinite(err):
        return f"{value:.{digits}g}"
    return f"{value:.{digits}g} ± {err:.2g}"
