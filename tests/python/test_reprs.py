# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Every analysis class of tapmc says what it holds in its repr (freud's habit): the inputs and
'not computed' before compute(), a result after; never the default '<... object at 0x...>'."""
import os
import sys
from pathlib import Path

import numpy as np
import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc.ageing import Ageing  # noqa: E402
from tapmc.connected_ageing import ConnectedAgeing  # noqa: E402
from tapmc.fluctuations import ErrorCalibration, PowerSpectrum, SteadyState  # noqa: E402
from tapmc.hysteresis import Hysteresis  # noqa: E402
from tapmc.profiles import ProfileIncrease  # noqa: E402

RNG = np.random.default_rng(5)
Z = np.cumsum(RNG.normal(size=(6, 41)), axis=1)


@pytest.mark.parametrize("make, before, after", [
    (lambda: SteadyState(np.arange(10.0), last=4), "of 10 values, last 4",
     "X_SS 7.5 +- 1, sigma_X 1.29"),   # batch means 6.5, 8.5
    (lambda: PowerSpectrum(RNG.normal(size=64)), "of 1 run(s) x 64 taps", "frequency bins"),
    (lambda: ErrorCalibration({"a": ([1.0, 1.2, 0.9], [0.1, 0.1, 0.1]),
                               "b": ([2.0, 2.1], [0.1, 0.1])}), "of 2 groups", "factor "),
    (lambda: Hysteresis(np.repeat([0.1, 0.2, 0.1], 10), np.arange(30.0), taps_per_level=10,
                        last=5), "of 30 taps, 10 per level", "3 levels"),
    (lambda: Ageing(Z, [5, 10]), "of 6 realizations x 40 taps, t_w [5, 10]",
     "A(t, t_w) at"),
    (lambda: ConnectedAgeing(Z, [5, 10]), "of 6 realizations x 40 taps, t_w [5, 10]",
     "C(t, t_w) at"),
    (lambda: ProfileIncrease(np.arange(1.0, 6.0), np.linspace(0.5, 0.6, 5),
                             np.linspace(0.6, 0.62, 5)), "of 1 seed(s) x 5 times",
     "delta Phi lateral 0.1, central 0.02 at the last time"),
])
def test_repr_names_inputs_then_results(make, before, after):
    analysis = make()
    name = type(analysis).__name__
    assert repr(analysis) == f"<{name} {before}: not computed>"
    text = repr(analysis.compute())
    assert text.startswith(f"<{name} {before}: ") and after in text and "not computed" not in text
    assert " object at 0x" not in text
