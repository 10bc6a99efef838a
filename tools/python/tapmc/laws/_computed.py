# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The results of the tests of :mod:`tapmc.laws` that exist once their ``compute`` has run
(:class:`RealizationLawTest`, :class:`SurrogateFits`, :class:`RealizationFits`): shared by
the modules of the package only."""

import numpy as np


class Computed:
    """Results that exist once ``compute`` has run: ``_result`` (a dict) is None before, and
    every result property (:func:`result_property`) says which call fills it."""

    #: the call that fills the results, as the error before it names it
    _compute_call = "compute(...)"
    _result = None

    def _get(self, key):
        if self._result is None:
            raise RuntimeError(f"call {self._compute_call} first")
        return self._result[key]


def result_property(key):
    """A read-only property returning the computed result ``key`` of a :class:`Computed`."""
    return property(lambda self: self._get(key))


class RangeTested(Computed):
    """Fits over tap ranges with a p-value per parameter (``range_p``) and a level ``p_min``."""

    @property
    def range_dependent(self):
        """The parameters whose range test rejects one value over the ranges."""
        return [k for k, p in self.range_p.items() if np.isfinite(p) and p < self.p_min]
