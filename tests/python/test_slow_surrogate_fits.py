# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Calibration of tapmc.laws.SurrogateFits against independent realizations (slow: about
5 minutes on one core). Eq. 3 over 2000 taps with noise of the runs' spectrum (power law of
slope -1.3, Fig. 3) at the campaign's residual size (rms 1e-3) and five times smaller.

Measured (24 realizations, 50 surrogates each): where the realizations spread ln B by 0.25
(rms 2e-4), one run's surrogates give a half width of about 0.14 and call B determined in
every run; where they spread it by 3.2 (rms 1e-3), the surrogates call B undetermined in 22
of 24 runs, their bounded half widths (0.5 to 5.6) on either side of that spread. The band
holds the true value in 33-47 % of the runs (68 % nominal); the 1 % range test rejected the
law in no run. So "undetermined" is safe and "determined" is not: the claims use only the first."""

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


@pytest.mark.parametrize("rms, seed, fixed", [(1e-3, 11, False), (2e-4, 12, True)])
def test_undetermined_is_safe(rms, seed, fixed):
    """A verdict "undetermined" from one run's surrogates must not fall on a parameter that
    independent realizations fix: where they fix ln B (spread below ln 2), the surrogates
    say so in nearly every run, with bands narrower than that spread (so "determined" is
    only an upper bound); where they do not, the surrogates say "undetermined" in most runs.
    And the range test does not reject a law that holds beyond its level."""
    rng = np.random.default_rng(seed)
    t = np.arange(1, TAPS + 1, dtype=float)
    clean = LAW.function(t, *TRUTH.values())
    fitted, halves, undetermined, rejected = [], [], 0, 0
    for k in range(REALIZATIONS):
        y = clean + rms * power_law_noise(TAPS, -1.3, rng)
        fits = SurrogateFits(LAW, surrogates=SURROGATES, seed=k).compute(t, y)
        fitted.append(np.log(fits.params["B"]))
        halves.append(fits.half_width["B"])
        undetermined += not fits.determined["B"]
        rejected += bool(fits.range_dependent)
    spread = (np.percentile(fitted, 84) - np.percentile(fitted, 16)) / 2
    assert (spread < np.log(2.0)) == fixed, spread   # the regime this case is about
    if fixed:
        assert undetermined <= 0.1 * REALIZATIONS, undetermined
        assert np.mean(np.asarray(halves) < spread) >= 0.6, (halves, spread)
    else:
        assert undetermined >= 0.75 * REALIZATIONS, undetermined
    assert rejected <= 2, rejected
