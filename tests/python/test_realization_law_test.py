# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# tapmc.laws.RealizationLawTest, the test of a law across independent realizations: its
# p-values are uniform when the law holds (correlated taps, few realizations), it rejects a
# wrong law, recovers a right one's parameters, and names what is wrong with bad input.
import os
import sys
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", HERE.parent.parent))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc.laws import InverseLogLaw, RealizationLawTest, ZLaw  # noqa: E402

REALIZATION_TAPS = np.arange(0.0, 401.0)


def correlated_noise(rng, n, sd, phi=0.95):
    """n realizations of an AR(1) noise (correlation time ~20 taps): the taps of one run are
    correlated, as the spectra of Fig. 3 say, and realizations are independent."""
    out = np.empty((n, REALIZATION_TAPS.size))
    x = rng.normal(0.0, sd, n)
    for i in range(REALIZATION_TAPS.size):
        x = phi * x + np.sqrt(1.0 - phi ** 2) * rng.normal(0.0, sd, n)
        out[:, i] = x
    return out


@pytest.mark.parametrize("law,true,sd", [
    (InverseLogLaw(), (0.60, 0.08, 0.3, 5.0), 1e-3),
    (ZLaw(), (7.1, 7.6, 0.4, 3.0), 1e-2),
])
def test_realization_test_is_calibrated_when_the_law_holds(law, true, sd):
    # 120 sets of 9 realizations (F(4, 5) test): under the law the p-values are uniform, so
    # the rejections at 5 % are Binomial(120, 0.05) (mean 6, sd 2.4); 16 is 4 sd above (the
    # linearisation of B and tau makes the test slightly liberal: 6.3 % in 1000 sets).
    rng = np.random.default_rng(7)
    curve = law.function(REALIZATION_TAPS, *true)
    p = np.array([RealizationLawTest(law).compute(
        REALIZATION_TAPS, curve + correlated_noise(rng, 9, sd)).p_value for _ in range(120)])
    assert 1 <= np.sum(p < 0.05) <= 16, np.sum(p < 0.05)
    assert 0.3 <= np.median(p) <= 0.7, np.median(p)


def test_realization_test_rejects_a_wrong_law_and_fits_a_right_one():
    rng = np.random.default_rng(3)
    power_law = 0.52 + 0.01 * REALIZATION_TAPS ** 0.3
    wrong = RealizationLawTest(InverseLogLaw()).compute(
        REALIZATION_TAPS, power_law + correlated_noise(rng, 9, 1e-3))
    assert wrong.p_value < 0.01 and not wrong.compatible, wrong
    true = (0.60, 0.08, 0.3, 5.0)
    right = RealizationLawTest(InverseLogLaw()).compute(
        REALIZATION_TAPS, InverseLogLaw.function(REALIZATION_TAPS, *true)
        + correlated_noise(rng, 9, 1e-5))
    assert right.compatible and right.dof == 4 and right.realizations == 9
    assert right.bin_edges[0] == 1 and right.bin_edges[-1] == 401 and len(right.bin_edges) == 9
    for name, value in zip(InverseLogLaw.names, true):
        assert abs(right.params[name] - value) <= 5 * right.errors[name] + 1e-9, (name, right)
    np.testing.assert_allclose(right.bin_model, right.bin_means, atol=5 * right.bin_sem.max())


def test_realization_test_messages():
    law = InverseLogLaw()
    curves = np.ones((5, REALIZATION_TAPS.size))
    with pytest.raises(ValueError, match="5 realizations: a test of 4 parameters needs at "
                                         "least 6"):
        RealizationLawTest(law).compute(REALIZATION_TAPS, curves)
    with pytest.raises(ValueError, match="bins = 3: must be an integer >= 5"):
        RealizationLawTest(law, bins=3)
    with pytest.raises(ValueError, match=r"curves must have shape \(realizations, 401\)"):
        RealizationLawTest(law).compute(REALIZATION_TAPS, curves[:, :10])
    with pytest.raises(ValueError, match="singular covariance"):
        RealizationLawTest(law).compute(REALIZATION_TAPS, np.ones((9, REALIZATION_TAPS.size)))
    with pytest.raises(ValueError, match=r"t_min = 1000 leaves 0 taps \(t ends at 400\): 8 "
                                         r"bins need at least 8"):
        RealizationLawTest(law, t_min=1000).compute(REALIZATION_TAPS,
                                                    np.ones((9, REALIZATION_TAPS.size)))
    with pytest.raises(ValueError, match="t_min = nan: must be finite"):
        RealizationLawTest(law, t_min=float("nan"))
    with pytest.raises(RuntimeError, match="compute"):
        RealizationLawTest(law).p_value
    with pytest.raises(TypeError, match="tapmc.laws.Law"):
        RealizationLawTest("eq. 3")
