# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Slow statistical validation of tapmc.ageing.ScalingRealizationTest, the test of Fig. 5's
# collapse across realizations: with the paper's 10 realizations of curves that do collapse
# (eq. 6 exactly, for every waiting time), its p-values are uniform, although a
# realization's mean of squared displacements over a bin is far from Gaussian; and of
# Ageing.eq6_test, eq. 6 on one curve, where a drift makes most of A (as in the paper-scale
# runs); and of the collapse's interval of mu (profile widened by the jackknife and the
# bootstrap over realizations) on random walks, which do not age.
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


def test_eq6_test_is_calibrated_where_a_drift_dominates():
    """Eq. 6's test on one curve (Ageing.eq6_test) where A is 98 % the square of a mean
    compaction, as in the paper-scale runs, and eq. 6 exactly: fluctuations whose A is eq. 6
    plus a drift whose square is 50 times that eq. 6."""
    from tapmc.laws import AgeingLaw

    rng = np.random.default_rng(5)
    realizations, sets, taps, tw = 10, 100, 400, 10
    eq6 = AgeingLaw.function(np.arange(taps + 1 - tw, dtype=float), 4e-3, 0.6, 5.0)
    drift = np.zeros(taps + 1)
    drift[tw:] = -np.sqrt(50.0 * eq6)
    z = stationary_realizations(rng, realizations * sets, taps=taps) + drift
    p, share = [], []
    for k in range(sets):
        ageing = Ageing(z[k * realizations:(k + 1) * realizations], [tw]).compute()
        p.append(ageing.eq6_test(tw).p_value)
        share.append(ageing.drift_share(tw))
    p = np.array(p)
    assert 0.95 < np.mean(share) < 1.0
    # Binomial(100, 0.01) and (100, 0.05): at most 4 and 11 rejections when calibrated
    assert np.sum(p < 0.01) <= 4 and np.sum(p < 0.05) <= 11, np.sort(p)[:12]
    assert 0.35 <= np.median(p) <= 0.65, np.median(p)


def test_collapse_of_a_random_walk_keeps_mu_compatible_with_no_ageing():
    # increments independent of the age: no ageing, mu = 0. The delays of a curve are
    # correlated, so the profile alone is far too narrow (it misses 0 in 11 of 12 seeds);
    # widened by the jackknife and the bootstrap over realizations it holds 0 at about its
    # nominal rate (10 of 12 seeds; here 6 seeds, at least 4 expected for a 68 % interval)
    widened = profile = 0
    for seed in range(6):
        rng = np.random.default_rng(seed)
        z = 7.3 + np.cumsum(rng.normal(0, 1e-3, (10, 501)), axis=1)
        col = Ageing(z, [10, 30, 100]).compute().scaling(fit_amplitude=False, bootstrap=20)
        assert col.bootstrap is not None and np.isfinite(col.bootstrap["mu"])
        iv, bare = col.interval("mu"), col.fit.intervals["mu"]
        widened += iv.lo <= 0.0 <= iv.hi
        profile += bare.lo <= 0.0 <= bare.hi
    assert widened >= 4 and profile <= 2, (widened, profile)
