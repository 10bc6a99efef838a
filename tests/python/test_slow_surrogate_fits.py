# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Calibration of tapmc.laws.SurrogateFits against independent realizations (slow: about
5 minutes on one core). Eq. 3 over 2000 taps with noise of the runs' spectrum (power law of
slope -1.3, Fig. 3) at the campaign's residual size (rms 1e-3) and five times smaller.

Measured (30 realizations, 50 surrogates each): the surrogates' 16-84 % half width of ln B
is 1.6 where the realizations spread by 5.7 (rms 1e-3), 0.14 where they spread by 0.25
(rms 2e-4), below the realizations' spread in 97 % and 83 % of the runs; the band holds the
true value in 33-47 % of the runs (68 % nominal). The 1 % range test rejected the law in no
run. So "undetermined" is safe and "determined" is not: the claims use only the first."""

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools" / "python"))

from tapmc.laws import InverseLogLaw, SurrogateFits  # noqa: E402

LAW = InverseLogLaw()
TRUTH = dict(X_inf=0.60, dX_inf=0.04, B=0.3, tau=5.0)
TAPS = 2000
REALIZATIONS = 24
SURROGATES = 50


def power_law_noise(n, slope, rng):
    f = np.fft.rfftfreq(2 * n)
    amplitude = np.zeros_like(f)
    amplitude[1:] = f[1:] ** (slope / 2.0)
    x = np.fft.irfft(amplitude * (rng.standard_normal(f.size) + 1j * rng.standard_normal(f.size)),
                     n=2 * n)[:n]
    return x / x.std()


@pytest.mark.parametrize("rms, seed", [(1e-3, 11), (2e-4, 12)])
def test_surrogate_bands_are_narrower_than_the_realizations_spread(rms, seed):
    rng = np.random.default_rng(seed)
    t = np.arange(1, TAPS + 1, dtype=float)
    clean = LAW.function(t, *TRUTH.values())
    fitted, halves, rejected = [], [], 0
    for k in range(REALIZATIONS):
        y = clean + rms * power_law_noise(TAPS, -1.3, rng)
        fits = SurrogateFits(LAW, surrogates=SURROGATES, seed=k).compute(t, y)
        fitted.append(np.log(fits.params["B"]))
        halves.append(fits.half_width["B"])
        rejected += bool(fits.range_dependent)
    spread = (np.percentile(fitted, 84) - np.percentile(fitted, 16)) / 2
    below = np.mean(np.asarray(halves) < spread)
    # the conservative side: one run's band is narrower than the spread of realizations
    assert below >= 0.6, (below, np.median(halves), spread)
    # and the range test does not reject a law that holds beyond its level
    assert rejected <= 2, rejected
