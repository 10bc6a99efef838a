# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The report's conventions and the rules that must not flip on one degree of freedom: the
table of tolerances counts the verdicts a convention moves (a control whose doubling flips a
synthetic verdict, and one it leaves), a ramp difference of two seeds judged alone is decided
by the paired test over its levels (not by t with 1 dof), a mean of a few seeds that is a
group of realizations takes the groups' error and dof (not t with 2 dof), and no few-seed
error is smaller than the groups' realization error."""

from claims_fakes import *  # noqa: F401,F403  (the synthetic figure data and controls)

from tapmc.paper.claims import conventions, sensitivity
from tapmc.paper.claims.calibration import measured_factor
from tapmc.fluctuations import ErrorCalibration


def test_every_convention_has_a_source_and_a_value():
    names = [c.name for c in conventions.CONVENTIONS]
    assert len(names) == len(set(names))
    for c in conventions.CONVENTIONS:
        assert c.source.strip() and c.decides.strip(), c
        assert isinstance(c.value, (int, float)), c
        if c.vary:
            assert c.varied(0.5) != c.value != c.varied(2), c
        else:
            assert c.where and c.varied(2) is None, c
    confidence = next(c for c in conventions.CONVENTIONS if c.name == "CONFIDENCE")
    assert confidence.varied(0.5) == pytest.approx(0.975)    # its tail, halved
    assert confidence.varied(2) == pytest.approx(0.90)


def test_a_patched_convention_reaches_every_module_that_binds_it():
    from tapmc.paper.claims import rules

    with sensitivity.patched("NEAR_FRACTION", conventions.NEAR_FRACTION, 0.3) as modules:
        assert rules.NEAR_FRACTION == 0.3
        assert {m.__name__ for m in modules} >= {"tapmc.paper.claims.rules",
                                                  "tapmc.paper.claims.conventions"}
    assert rules.NEAR_FRACTION == 0.1
    from tapmc import stats

    with sensitivity.patched("CONFIDENCE", stats.CONFIDENCE, 0.5):
        assert stats.t_quantile(10) == pytest.approx(0.6998, abs=1e-4)   # read when called
    assert stats.t_quantile(10) == pytest.approx(2.2281, abs=1e-4)


def _near_rows(value):
    """The evaluated rows of 'reversible-retraced' (rule near) with a second increase
    ``value`` above the decrease, against a hysteresis gap of 0.01 (tolerance 0.001)."""
    claim = BY_ID["reversible-retraced"]
    tab = Table()
    tab.add("a", "up1", X, 0.59, 1e-5).add("a", "down", X, 0.60, 1e-5)
    tab.add("a", "up2", X, 0.60 + value, 1e-5)
    summary = {"ramp_taps_per_level": [4000]}
    data = report(summary, fig4=tab)
    return claims.evaluate([claim], data)


def test_the_table_counts_a_verdict_the_doubling_of_a_convention_flips():
    """A second increase 0.0015 from the decrease is beyond a tenth of the gap (0.001):
    it disagrees; with NEAR_FRACTION doubled (0.002) it agrees, halved it still disagrees:
    counted 1 and 0. The control, 0.0001, agrees either way: counted 0 and 0."""
    near = next(c for c in conventions.CONVENTIONS if c.name == "NEAR_FRACTION")
    rows = _near_rows(0.0015)
    assert [str(r.verdict) for r in rows] == ["disagrees"]
    (found,) = sensitivity.sensitivities(rows, (near,))
    assert (found.halved, found.doubled, found.claims) == (0, 1, ("reversible-retraced",))
    (control,) = sensitivity.sensitivities(_near_rows(0.0001), (near,))
    assert (control.halved, control.doubled, control.claims) == (0, 0, ())
    table = sensitivity.tolerance_table(rows, (near,))
    assert table[0] == "Tolerances and their sensitivity"
    assert "   * - ``NEAR_FRACTION``" in table and "     - reversible-retraced" in table


def test_a_convention_of_a_statistic_module_reevaluates_its_claims():
    """CRITICAL_BRACKET_HALF_WIDTH (bell): ramps turning at 0.125 (frozen) and 0.25
    (compacting) bracket (sqrt eps)* in (0.125, 0.25], wider than 0.15 +- 0.05: undecided;
    doubled (0.1) the bracket locates it: agrees. Counted once, doubled only."""
    claim = BY_ID["critical-sqrt-eps"]
    data = report({"ramp_taps_per_level": [4000]},
                  fig4=ramps_turning({0.125: 0.0, 0.25: 0.02}))
    rows = claims.evaluate([claim], data)
    assert rows[0].outcome == claims.Outcome.UNDECIDED, rows[0].verdict
    bracket = next(c for c in conventions.CONVENTIONS
                   if c.name == "CRITICAL_BRACKET_HALF_WIDTH")
    (found,) = sensitivity.sensitivities(rows, (bracket,))
    assert (found.halved, found.doubled) == (0, 1)


def _ramp_two_seeds(levels_down):
    """Fig. 4's ramp of two seeds whose own differences (0.016, 0.013) spread far beyond
    the groups of realizations (k = 2 on errors of 1e-4): judged alone. ``levels_down``:
    the decreasing branch's excess over the first increase at each level."""
    tab = Table()
    tab.add("a", "up1", X, 0.59, 0.0002, n=2)
    tab.add("a", "down", X, 0.59 + np.asarray(levels_down), 0.0002, n=2)
    tab.param("ramp:down_minus_up1", float(np.mean(levels_down)), 0.0015, n=2, x=0.3)
    tab.add("params", "ramp:down_minus_up1:seeds", [0.3, 0.3], [0.016, 0.013],
            [0.0001, 0.0001], n=1)
    data = report(fig4=tab)
    data.questions["realization_scatter"] = _scatter_rows("phi_c", 0.0002, 0.0001)
    return data


def test_two_seeds_judged_alone_are_decided_by_the_paired_test_over_the_levels():
    """The 1-dof flip: two seeds that both rise on the way down at all 14 levels, 0.0145
    +- 0.0015 between them, are undecided by their own spread (t = 12.7 with 1 dof); the
    paired test over the levels (13 dof) decides: agrees. The control that must fail: levels
    of both signs about a mean of zero stay within the uncertainty of zero."""
    claim = BY_ID["reversible-above"]
    rise = 0.0145 + 0.003 * np.sin(np.arange(len(X)))
    (m,) = claims.ramp_down_minus_up(_ramp_two_seeds(rise), claim)
    assert m.dof == len(X) - 1 and "paired test over the 14 common levels" in m.text()
    assert m.err == pytest.approx(max(np.std(rise, ddof=1) / np.sqrt(len(X)), 0.0015))
    assert str(claims.verdict(claim, m)) == "agrees"
    one_dof = dataclasses.replace(m, dof=1)             # what the seeds alone would give
    assert claims.verdict(claim, one_dof).outcome == claims.Outcome.UNDECIDED
    mixed = 0.01 * np.sin(np.arange(len(X)))
    mixed -= mixed.mean()
    (m,) = claims.ramp_down_minus_up(_ramp_two_seeds(mixed), claim)
    assert claims.verdict(claim, m).outcome == claims.Outcome.UNDECIDED


def _slope_report(slopes, errors, spread=0.06, error=0.1):
    """Fig. 3 with a slope at eps = 0.01 over the seeds ``slopes``, which are a group of
    realization_scatter.csv (Z:slope) beside 4 others spreading ``spread`` against own
    errors ``error``."""
    tab = fig3()
    sem = float(np.std(slopes, ddof=1) / np.sqrt(len(slopes)))
    tab.param("eps=0.01:slope", float(np.mean(slopes)), sem, n=len(slopes), x=0.01)
    data = report(fig3=tab)
    rows = [dict(r, sem_dof="") for r in _scatter_rows("Z:slope", spread, error, groups=4)]
    rows += [{"group": "const_pbc_eps0.01", "column": "Z:slope", "mean": repr(s),
              "sem": repr(e), "sem_dof": ""} for s, e in zip(slopes, errors)]
    data.questions["realization_scatter"] = rows
    return data


def test_three_seeds_that_are_a_group_take_the_groups_error_and_dof():
    """The t(2) case: three slopes -0.85, -0.90, -0.95 (sem 0.029, 2 dof, t = 4.3) meet
    [-1.5, -1] by t(2). As a group of realizations (Z:slope, beside 4 groups whose slopes
    spread half their own errors: k measured below 1) they take the groups' error of such a
    mean, k sqrt(sum e^2) / 3, when larger than their sem, with the pooled dof: -0.90 then
    misses -1. The control: -0.96 with the same errors still meets it."""
    claim = BY_ID["spectral-slope"]
    errors = [0.12, 0.12, 0.12]
    data = _slope_report([-0.85, -0.90, -0.95], errors, spread=0.05, error=0.1)
    (m,) = [m for m in claims.spectral_slopes(data, claim) if m.label == "eps = 0.01"]
    pooled = data.pooled_calibration("Z:slope", "pbc")
    k = measured_factor(pooled)
    assert k == pytest.approx(pooled.factor) and k < 1
    assert m.dof == pooled.dof == 14          # 4 groups of 4 runs and the 3 seeds
    assert m.err == pytest.approx(max(0.05 / np.sqrt(3), k * 0.12 / np.sqrt(3)))
    assert m.err > 0.05 / np.sqrt(3)          # the floor, above the seeds' own sem
    assert str(claims.verdict(claim, m)) == "disagrees"
    assert str(claims.verdict(claim, dataclasses.replace(m, dof=2))) == "agrees"
    control = _slope_report([-0.91, -0.96, -1.01], errors, spread=0.05, error=0.1)
    (c,) = [m for m in claims.spectral_slopes(control, claim) if m.label == "eps = 0.01"]
    assert c.dof == 14 and str(claims.verdict(claim, c)) == "agrees"


def test_no_few_seed_error_is_smaller_than_the_groups_realization_error():
    """Three seeds that happen to agree within 1e-4 (sem 6e-5) where realizations spread
    k = 2 times their errors of 1e-3: their error is floored at 2 x sqrt(3) x 1e-3 / 3; a
    group whose own spread is the larger keeps it."""
    rows = _scatter_rows("phi_c", 0.002, 0.001, groups=3)
    data = claims.ReportData({}, {}, questions={"realization_scatter": rows})
    floor = data.realization_floor("phi_c", [0.001] * 3)
    assert floor == pytest.approx(2 * np.sqrt(3) * 0.001 / 3)
    err, dof, text, pooled = claims.common.seeds_error(data, [0.6, 0.6001, 0.6002],
                                                       [0.001] * 3, "phi_c")
    assert err >= floor
    assert data.realization_floor("phi_b", [0.001] * 3) is None         # no groups


def test_the_measured_factor_is_one_unless_the_groups_reject_it():
    """k as the groups measure it where it differs from 1 at CALIBRATION_ALPHA on either
    side (errors too small, or measurably conservative), else 1."""
    def calibration(spread):
        rows = _scatter_rows("phi_c", spread, 0.001, groups=4)
        return claims.realization_calibrations(rows)["phi_c"]

    assert measured_factor(calibration(0.004)) == pytest.approx(4.0)
    assert measured_factor(calibration(0.0011)) == 1.0
    small = ErrorCalibration({f"g{g}": ([0.0, 0.0001, -0.0001, 0.00005],
                                        [0.001] * 4) for g in range(6)}, within_dof=None)
    assert measured_factor(small.compute()) == pytest.approx(small.factor)
    assert small.factor < 1


def _eps_groups(ratios, runs=6, error=0.001):
    """realization_scatter.csv rows of phi_c: one group of ``runs`` per eps -> k_g (their
    spread exactly k_g times their own errors)."""
    rows = []
    for eps, k in ratios.items():
        rows += [dict(r, group=f"const_pbc_eps{eps:g}") for r in
                 _scatter_rows("phi_c", k * error, error, groups=1, runs=runs)]
    return rows


def test_a_factor_that_grows_with_eps_is_taken_at_each_rows_eps():
    """Groups whose factor grows with eps (1, 2, 4, 8 at eps 0.01 to 0.16, 6 runs each):
    Bartlett's test sets them apart and the trend in sqrt(eps) is beyond its error, so a
    one-run row at eps = 0.16 takes about 8 and one at 0.01 about 1, where one pooled
    factor (5.2) would under-cover the first and over-cover the second. Controls: the same
    factors rearranged over eps (1, 8, 8, 1) differ but have no trend (the pooled factor
    serves), and
    groups that agree within chance have no trend either."""
    rising = _eps_groups({0.01: 1.0, 0.04: 2.0, 0.09: 4.0, 0.16: 8.0})
    calibration = claims.realization_calibrations(rising)["phi_c"]
    assert claims.calibration.factor_heterogeneity(calibration) < 1e-3
    (trend,) = claims.calibration.realization_trends(rising).values()
    assert trend.factor(0.16) == pytest.approx(8.0, rel=0.15)
    assert trend.factor(0.01) == pytest.approx(1.0, rel=0.15)
    data = claims.ReportData({}, {}, questions={"realization_scatter": rising})
    pooled = data.run_error("phi_c")[0]
    assert pooled == pytest.approx(np.sqrt((1 + 4 + 16 + 64) / 4))
    assert data.run_error("phi_c", eps=0.16)[0] == pytest.approx(trend.factor(0.16))
    assert data.run_error("phi_c", eps=0.16)[1] == calibration.dof - 1
    # Fig. 4's one-run squares (x = sqrt(eps)) take the factor at their own eps
    tab = fig4(BELL)
    tab.table[("a", "steady")]["n"][:] = 1
    data = claims.ReportData({}, {"fig4": with_fig4_rows(tab).data()},
                             questions={"realization_scatter": rising})
    scaled = data.figure("fig4").get("a", "steady")[2] / 0.001
    assert scaled[0] == pytest.approx(max(1.0, trend.factor(X[0] ** 2)))
    assert scaled[-1] == pytest.approx(trend.factor(X[-1] ** 2))
    assert "a trend in sqrt(eps)" in data.run_error_note()
    shuffled = _eps_groups({0.01: 1.0, 0.04: 8.0, 0.09: 8.0, 0.16: 1.0})
    assert claims.calibration.factor_heterogeneity(
        claims.realization_calibrations(shuffled)["phi_c"]) < 0.01
    assert claims.calibration.realization_trends(shuffled) == {}
    alike = _eps_groups({0.01: 3.0, 0.04: 4.0, 0.09: 3.5, 0.16: 4.5}, runs=3)
    assert claims.calibration.factor_heterogeneity(
        claims.realization_calibrations(alike)["phi_c"]) > 0.01
    assert claims.calibration.realization_trends(alike) == {}


def test_a_convention_reaches_the_claims_of_every_module_that_binds_it():
    """FIT_P_VALUE is bound by the rules (every claim of rule fit: the measures re-decided)
    and by the laws' statistics (their claims measured afresh); SPECTRUM_BAND by one
    statistic module (its claims only); CONFIDENCE by tapmc.stats (every claim afresh)."""
    measures = {c.id: [] for c in REGISTER if c.statistic}

    def reach(name):
        value = getattr(conventions, name)
        return sensitivity._reached(sensitivity.binding_modules(name, value), REGISTER,
                                    measures)

    claims_, reused, recalibrate = reach("FIT_P_VALUE")
    assert len(claims_) == len(REGISTER) and not recalibrate
    assert "eq3-compatible" not in reused and "ageing-scaling" in reused
    claims_, reused, _ = reach("SPECTRUM_BAND")
    assert {c.id for c in claims_} == {c.id for c in REGISTER
                                       if c.statistic.startswith(("spectr", "sigma"))}
    assert reused == {}
    claims_, reused, _ = reach("CONFIDENCE")
    assert len(claims_) == len(REGISTER) and reused == {}
    assert reach("CALIBRATION_ALPHA")[2]          # the calibration binds it: calibrated anew


def test_a_spectral_band_of_one_frequency_is_continued_flat_without_warning():
    """A quick campaign's windows give a band of one frequency: polyfit warned 'poorly
    conditioned' on every report and returned an arbitrary slope; the null campaigns of the
    bootstrap are now drawn with the band continued flat, silently."""
    import warnings

    import numpy as np

    from tapmc.fluctuations import binned_periodogram_layout
    from tapmc.paper.claims import fluctuations

    samples = 25
    _, counts, relative = binned_periodogram_layout(samples)[:3]
    band = np.array([0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        chunks = list(fluctuations._null_statistics(np.ones(len(counts)), counts, band,
                                                    np.array([2.0, 2.0]), samples,
                                                    relative[np.ix_(band, band)], 64))
    statistics = np.concatenate(chunks)
    assert len(statistics) == 64 and np.all(np.isfinite(statistics))
