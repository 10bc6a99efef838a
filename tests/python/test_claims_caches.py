# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# The report's table of tolerances re-evaluates the claims many times on the same data; two
# computations are kept between evaluations (tapmc.paper.claims.laws._realization_law_test,
# tapmc.paper.claims.ageing.dispersion_p_bound). Kept results must be the ones a fresh
# computation gives, and a changed constant of the library must give a fresh one.
import math
import os
import sys
from pathlib import Path

import numpy as np
from scipy import integrate
from scipy.stats import f as f_distribution

HERE = Path(__file__).resolve().parent
SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", HERE.parent.parent))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc.laws import InverseLogLaw, RealizationLawTest  # noqa: E402
from tapmc.laws import realizations as realizations_module  # noqa: E402
from tapmc.paper.claims import ageing as claim_ageing  # noqa: E402
from tapmc.paper.claims import laws as claim_laws  # noqa: E402

TAPS = np.arange(0.0, 401.0)


def test_a_law_test_is_kept_and_made_anew_when_a_library_constant_changes(monkeypatch):
    rng = np.random.default_rng(5)
    values = (InverseLogLaw.function(TAPS, 0.60, 0.08, 0.3, 5.0)
              + rng.normal(0.0, 1e-3, (9, TAPS.size)))
    first = claim_laws._realization_law_test(InverseLogLaw(), 1.0, (TAPS, values))
    fresh = RealizationLawTest(InverseLogLaw(), t_min=1.0).compute(TAPS, values)
    assert (first.chi2, first.p_value, first.dof) == (fresh.chi2, fresh.p_value, fresh.dof)
    # the same law, start and curves (another array with the same numbers): the kept result
    assert claim_laws._realization_law_test(InverseLogLaw(), 1.0, (TAPS, values.copy())) is first
    # other curves, another start: computed
    assert claim_laws._realization_law_test(InverseLogLaw(), 1.0, (TAPS, values + 1e-4)) \
        is not first
    assert claim_laws._realization_law_test(InverseLogLaw(), 2.0, (TAPS, values)) is not first
    # a constant of the library changed, as the table of tolerances varies one: computed anew
    assert len(first.bin_edges) - 1 == 8
    monkeypatch.setattr(realizations_module, "REALIZATION_MAX_BINS", 6)
    fewer = claim_laws._realization_law_test(InverseLogLaw(), 1.0, (TAPS, values))
    assert fewer is not first and len(fewer.bin_edges) - 1 == 6


def test_the_ageing_bound_is_the_integral_of_the_f_distributions_survival():
    # the bound integrates scipy.special.fdtrc: the same numbers as scipy.stats.f(1, n - 1).sf
    dispersion, realizations = 4.7, 10
    law = f_distribution(1, realizations - 1)
    grid = np.linspace(0.0, dispersion, 201)[:-1]
    reference = min(1.0, min(integrate.quad(law.sf, a, np.inf, limit=200)[0] / (dispersion - a)
                             for a in grid))
    assert claim_ageing.dispersion_p_bound(dispersion, realizations) == reference
    assert 0.1 < reference < 0.3
    # below 4 realizations F(1, n - 1) has no mean: no bound
    assert math.isnan(claim_ageing.dispersion_p_bound(dispersion, 3))
