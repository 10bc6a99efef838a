# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Slow statistical validation of tapmc.ageing.ScalingRealizationTest, the test of Fig. 5's
# collapse across realizations: with the paper's 10 realizations of curves that do collapse
# (eq. 6 exactly, for every waiting time), its p-values are uniform, although a
# realization's mean of squared displacements over a bin is far from Gaussian.
import os
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", HERE.parent.parent))
sys.path.insert(0, str(SOURCE / "tools" / "python"))
sys.path.insert(0, str(HERE))

from tapmc.ageing import Ageing  # noqa: E402
from test_hysteresis_ageing import stationary_realizations  # noqa: E402


def test_scaling_test_is_calibrated_with_ten_realizations():
    # 40 sets: rejections at 5 % are Binomial(40, 0.05) (mean 2, sd 1.4) when calibrated
    rng = np.random.default_rng(11)
    p = np.array([Ageing(stationary_realizations(rng, 10), [10, 30, 100]).compute()
                  .scaling_test(True).p_value for _ in range(40)])
    assert np.sum(p < 0.05) <= 6 and np.sum(p < 0.01) <= 3, np.sort(p)
    assert 0.3 <= np.median(p) <= 0.7, np.median(p)
