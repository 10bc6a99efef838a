# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Size of the test of the claim 'spectrum-high-frequency' (tapmc.paper.claims.fluctuations.
spectrum_low_band) in the campaign's own layout: 10 eps, seeds per eps 3,1,1,1,3,1,1,1,1,3
(Fig. 3's CSV), 1000-tap windows, every eps the SAME f^-alpha spectrum (the null hypothesis).
Prints, for each alpha, the rate of p < 0.01 and p < 0.05 of the test (Bartlett's statistic,
the levels' statistics from the binning; p from the parametric bootstrap, and from the
chi-square approximation) beside the earlier chi-square of the logarithms with each spectrum's
own errors, and P(statistic >= 27.0) of the earlier one (the published chi2). Then the power:
the rate of p < 0.01 when one spectrum is a factor `ratio` above the others.

Not part of the fast suite (minutes): run
    PYTHONPATH=tools/python nice -n 19 /usr/bin/python3 tests/python/studies/study_low_band_size.py [campaigns [bootstrap replicas]]
"""
import sys

import numpy as np
from scipy.stats import chi2

from tapmc.fluctuations import PowerSpectrum
from tapmc.paper._results import Series
from tapmc.paper.claims.fluctuations import band_levels_test

SEEDS = [3, 1, 1, 1, 3, 1, 1, 1, 1, 3]
WINDOW = 1000


def powerlaw_noise(rng, n, alpha):
    """Gaussian noise of spectrum f^-alpha (random Fourier amplitudes), made on 4 n samples and
    cut to the last n (no periodic wrap-around), fixed normalisation."""
    big = 4 * n
    f = np.fft.rfftfreq(big)
    amplitude = np.zeros_like(f)
    amplitude[1:] = f[1:] ** (-alpha / 2)
    z = rng.standard_normal(len(f)) + 1j * rng.standard_normal(len(f))
    return np.fft.irfft(z * amplitude, n=big)[-n:] / np.sqrt(2 * np.sum(amplitude[1:] ** 2)) * big


def old_test(spectra):
    """The earlier statistic: chi-square of one level through log10 of the band means, each
    with its own error (one seed: the periodogram's, scaled by its own power; several: sem)."""
    levels = []
    for s in spectra:
        k = max(int(len(s.x) * 0.25), 1)
        mean = float(np.mean(s.mean[:k]))
        levels.append((np.log10(mean), np.sqrt(np.sum(s.err[:k] ** 2)) / k / (mean * np.log(10))))
    y, e = (np.array(v) for v in zip(*levels))
    w = 1 / e ** 2
    c = float(np.sum(w * (y - np.sum(w * y) / np.sum(w)) ** 2))
    return c, float(chi2.sf(c, len(y) - 1))


def campaign(rng, alpha, ratio=1.0):
    out = []
    for i, seeds in enumerate(SEEDS):
        sp = [PowerSpectrum(powerlaw_noise(rng, WINDOW, alpha)
                            * (np.sqrt(ratio) if i == 0 else 1.0)).compute() for _ in range(seeds)]
        if seeds == 1:
            p, err = sp[0].power, sp[0].power_error
        else:
            stack = np.array([s.power for s in sp])
            p, err = stack.mean(0), stack.std(0, ddof=1) / np.sqrt(seeds)
        out.append(Series.of(sp[0].frequency, p, err, seeds))
    return out


def main(replicas, bootstrap):
    rng = np.random.default_rng(2026)
    band = 2 * np.sqrt(0.01 * 0.99 / replicas)
    for alpha in (1.0, 1.3, 1.5):
        boot_p, chi2_p, old_p, old_c = [], [], [], []
        for _ in range(replicas):
            spectra = campaign(rng, alpha)
            boot_p.append(band_levels_test(spectra, replicas=bootstrap)[2])
            chi2_p.append(band_levels_test(spectra, replicas=0)[2])
            c, p = old_test(spectra)
            old_c.append(c)
            old_p.append(p)
        boot_p, chi2_p, old_p, old_c = map(np.array, (boot_p, chi2_p, old_p, old_c))
        print(f"alpha {alpha} (null, 2-sd band of a 1 % rate +- {band:.3f}): rejections at 1 % / 5 %: "
              f"bootstrap {np.mean(boot_p < 0.01):.3f} / {np.mean(boot_p < 0.05):.3f}; "
              f"Bartlett chi-square {np.mean(chi2_p < 0.01):.3f} / {np.mean(chi2_p < 0.05):.3f}; "
              f"earlier {np.mean(old_p < 0.01):.3f} / {np.mean(old_p < 0.05):.3f}, "
              f"its P(chi2 >= 27) = {np.mean(old_c >= 27):.3f}", flush=True)
    for ratio in (2.0, 4.0, 8.0):
        boot_p, chi2_p = [], []
        for _ in range(replicas // 4):
            spectra = campaign(rng, 1.3, ratio)
            boot_p.append(band_levels_test(spectra, replicas=bootstrap)[2])
            chi2_p.append(band_levels_test(spectra, replicas=0)[2])
        print(f"power (alpha 1.3, the first eps's spectrum x{ratio:g}): rejections at 1 %: "
              f"bootstrap {np.mean(np.array(boot_p) < 0.01):.3f}, "
              f"Bartlett chi-square {np.mean(np.array(chi2_p) < 0.01):.3f}", flush=True)


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 400,
         int(sys.argv[2]) if len(sys.argv) > 2 else 400)
