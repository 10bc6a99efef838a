# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The claims register and its verdicts: the register is valid; each rule decides known cases
(Student's t for few seeds, undecided without an uncertainty); and every statistic a claim
uses has a control: synthetic figure data on which it must agree and data on which it must
not (time-reversed, swapped, flat, shifted), so that no row of the report cannot fail."""

from claims_fakes import *  # noqa: F401,F403  (the synthetic figure data and controls)


def test_register_is_valid_and_covers_the_paper():
    ids = [c.id for c in REGISTER]
    assert len(ids) == len(set(ids))
    sections = {c.section for c in REGISTER}
    assert {"II", "III.A", "III.B", "III.C", "IV.A", "IV.B"} <= sections
    for c in REGISTER:
        assert c.tolerance.strip() and c.decided_by.strip()
        if c.statistic:
            assert c.statistic in claims.STATISTICS
    # the rows of the list of unanswered claims are all in the register
    for needed in ("spectrum-high-frequency", "ramp-up-near-squares", "critical-sqrt-eps",
                   "reversible-above", "irreversible-frozen", "gradient-bell",
                   "gradient-no-hysteresis", "lateral-first-tap-jump", "pore-law-quadratic",
                   "eq4-compatible", "b-exponential", "ageing-scaling", "eq3-triplet-range",
                   # issue 42's claims of the paper that had no row
                   "pbc-denser-smaller-increase", "eq3-asymptote-small-eps", "zones-bell",
                   "eq7-fit", "wall-layering", "z-two-exponentials", "pores-gaussian-excess",
                   "theta-law-shape"):
        assert needed in BY_ID


def test_register_errors_name_the_field(tmp_path):
    path = tmp_path / "claims.toml"
    base = ('[[claim]]\nid = "x"\nsection = "II"\nfigure = ""\nclaim = "c"\npaper = "p"\n'
            'kind = "model"\ntolerance = "t"\ndecided_by = "d"\n')
    path.write_text(base + 'statistic = "nope"\nrule = "sign"\nsign = 1\n')
    with pytest.raises(ValueError, match="statistic = 'nope'"):
        claims.load_register(path)
    path.write_text(base + 'statistic = "phi_b_gain"\nrule = "sign"\n')
    with pytest.raises(ValueError, match="needs the field 'sign'"):
        claims.load_register(path)
    path.write_text(base + 'statistic = "phi_b_gain"\nrule = "sign"\nsign = 1\nneeds = ["big"]\n')
    with pytest.raises(ValueError, match="needs = \\['big'\\]"):
        claims.load_register(path)
    path.write_text((base + 'statistic = ""\nrule = "none"\n') * 2)
    with pytest.raises(ValueError, match="used twice"):
        claims.load_register(path)


def test_value_rule_uses_student_t():
    c = BY_ID["phi-tapped"]
    # 0.606 vs 0.600 +- 0.002: 3 sem away; agrees with 2 seeds (t = 12.7), not with 30 seeds
    assert str(claims.verdict(c, claims.Measure(0.600, 0.002, 1))) == "agrees"
    assert str(claims.verdict(c, claims.Measure(0.600, 0.002, 29))) == "disagrees"
    assert str(claims.verdict(c, claims.Measure(0.600, math.nan, None))).startswith("undecided")
    assert str(claims.verdict(c, claims.Measure(0.6062, 0.0, 5))) == "agrees"  # paper's rounding


def test_sign_zero_range_fit_check_rules():
    sign = BY_ID["phi-b-rises"]
    assert str(claims.verdict(sign, claims.Measure(1.0, 0.1, 4))) == "agrees"
    assert str(claims.verdict(sign, claims.Measure(-1.0, 0.1, 4))) == "disagrees"
    assert str(claims.verdict(sign, claims.Measure(0.1, 0.1, 4))).startswith("undecided")
    zero = BY_ID["reversible-retraced"]
    assert str(claims.verdict(zero, claims.Measure(0.01, 0.01, 4, effect=1.0))) == "agrees"
    assert str(claims.verdict(zero, claims.Measure(1.0, 0.01, 4, effect=1.0))) == "disagrees"
    # consistent with zero but too uncertain to tell it from the effect: undecided
    assert str(claims.verdict(zero, claims.Measure(0.01, 1.0, 4, effect=0.1))).startswith(
        "undecided")
    assert str(claims.verdict(zero, claims.Measure(0.01, 0.01, 4))).startswith("undecided")
    rng = BY_ID["bell-maximum"]
    assert str(claims.verdict(rng, claims.Measure(0.15, 0.01, 10))) == "agrees"
    assert str(claims.verdict(rng, claims.Measure(0.25, 0.01, 10))) == "disagrees"
    assert str(claims.verdict(rng, claims.Measure(0.25, 0.1, 10))) == "agrees"
    fit = BY_ID["eq3-compatible"]
    assert str(claims.verdict(fit, claims.Measure(1.0, dof=100))).startswith("agrees")
    assert str(claims.verdict(fit, claims.Measure(3.0, dof=100))).startswith("disagrees")
    check = BY_ID["no-pore-below-xi-t"]
    assert str(claims.verdict(check, claims.Measure(P.XI_T + 0.001))) == "holds"
    assert str(claims.verdict(check, claims.Measure(P.XI_T - 0.01))) == "fails"


def test_every_rule_is_explained_in_the_report():
    from tapmc.paper import validation

    assert set(validation.RULES) == set(claims.RULE_NAMES)


def test_scale_aspects_and_scale_verdicts():
    paper = {"sizes": [[4096, 32.0]], "eta": [1e-7], "preset": True, "scale": "full",
             "fields": None}
    assert claims.scale_aspects(paper) >= {"size", "eta", "taps"}
    medium = {"sizes": [[1024, 16.0]], "eta": [1e-5], "preset": True, "scale": "medium",
              "fields": None}
    assert claims.scale_aspects(medium) == set()
    data = claims.ReportData(dict(medium, initial_phi_c=[0.584, 0.001, 3]), {})
    rows = claims.evaluate([BY_ID["phi-initial"]], data)
    assert rows[0].missing_scale == ("size",)
    assert str(rows[0].verdict).startswith("undecided (scale") and "agrees" in str(rows[0].verdict)
    data = claims.ReportData(dict(paper, initial_phi_c=[0.584, 0.001, 3]), {})
    assert str(claims.evaluate([BY_ID["phi-initial"]], data)[0].verdict) == "agrees"


def test_nu_ramp_hysteresis_known_answer():
    claim = BY_ID["nu-hysteresis"]
    below, rises = claims.nu_ramp_hysteresis(ramp_pores(gap=-0.02, slope=0.05), claim)
    # gap + slope (x - 0.1) + 0.05 x averaged over x (mean 0.075)
    assert below.value == pytest.approx(-0.02 + 0.05 * (0.075 - 0.1) + 0.05 * 0.075)
    # five levels, each 1e-3: the mean difference's error sqrt(2 * 5) 1e-3 / 5
    assert below.err == pytest.approx(np.sqrt(10) * 1e-3 / 5)
    assert below.dof == 15 and below.sign == -1 and rises.sign == 1
    assert rises.value == pytest.approx(0.05)
    # no ramp-pores rows: what decides it
    (m,) = claims.nu_ramp_hysteresis(report(), claim)
    assert "ramp-pores" in str(claims.verdict(claim, m))


def test_critical_separation_needs_a_ramp_on_each_side_near_the_critical_value():
    # the campaign's pair: frozen at 0.125, compacting at 0.3 -> bracket too wide to locate 0.15
    m, v = _critical({0.125: 0.0002, 0.3: 0.018})
    assert v.startswith("undecided") and "(0.125, 0.3]" in v and "(0.15, 0.2]" in v
    # only the ramp beyond: no side below
    m, v = _critical({0.3: 0.018})
    assert v.startswith("undecided") and "no ramp turning below 0.15" in v
    # a frozen-looking change with errors as large as the other ramp's change: within errors
    m, v = _critical({0.125: 0.0002, 0.175: 0.002}, sem=0.001)
    assert v.startswith("undecided") and "within the errors" in v
    # two ramps turning at the same sqrt(eps), one without an error: undecided, no TypeError
    tab = ramps_turning({0.125: 0.0002, 0.175: 0.01})
    tab.param("ramp:top_sqrt_eps", 0.175, None, SEEDS).param("ramp:down_change", 0.0, None,
                                                             SEEDS, x=0.175)
    (m,) = claims.critical_separation(report(fig4=tab), BY_ID["critical-sqrt-eps"])
    assert str(claims.verdict(BY_ID["critical-sqrt-eps"], m)).startswith("undecided")
    # a ramp beyond 0.15 that decompacts on the way down contradicts the paper
    m, v = _critical({0.125: 0.0002, 0.175: -0.01})
    assert v == "disagrees" and "does not compact on the way down" in m.shown
    # located: (0.125, 0.175], within two ramp steps of 0.15; with one seed the batch-means
    # error (WITHIN_RUN_DOF) decides
    m, v = _critical({0.1: 0.0001, 0.125: 0.0002, 0.175: 0.01, 0.3: 0.018}, n=1)
    assert v == "agrees" and "(0.125, 0.175]" in m.shown


def test_alpha_ramp_hysteresis_known_answer_and_too_few_levels():
    claim = {c.id: c for c in REGISTER}["gradient-no-hysteresis"]
    (m,) = claims.alpha_ramp_hysteresis(report(fig6=fig6_ramp(0.001)), claim)
    k = len(X)
    jitter = 5e-5 * (-1.0) ** np.arange(k)
    assert m.value == pytest.approx(0.001 + jitter.mean())
    assert m.err == pytest.approx(np.std(jitter, ddof=1) / np.sqrt(k)) and m.dof == k - 1
    assert m.effect == pytest.approx(0.01 * np.ptp(X))
    (m,) = claims.alpha_ramp_hysteresis(report(fig6=Table().add("b", "ramp:up1", X[:2], 0.001)
                                               .add("b", "ramp:down", X[:2], 0.002)), claim)
    assert m.undecided and "three" in m.undecided
    (m,) = claims.alpha_ramp_hysteresis(report(fig6=Table().add("b", "bell:alpha", X, 0.001)),
                                        claim)
    assert m.undecided.startswith("not in this campaign")


def test_the_ramps_own_taps_per_level_decide_the_ramp_taps_aspect():
    """The paper-scale plan runs its ramp at fewer taps per level than the full preset: the
    taps per level the campaign's ramps ran with decide, not the preset's."""
    base = {"sizes": [[4096, 32.0]], "eta": [1e-7], "preset": True, "scale": "full"}
    assert "ramp_taps" in claims.scale_aspects(base)
    assert "ramp_taps" not in claims.scale_aspects(dict(base, ramp_taps_per_level=[1000]))
    assert "ramp_taps" not in claims.scale_aspects(dict(base, ramp_taps_per_level=[1000, 4000]))
    assert "ramp_taps" in claims.scale_aspects(dict(base, ramp_taps_per_level=[4000]))


def test_one_run_steady_state_is_decided_by_its_within_run_error():
    m = claims.STATISTICS["tapped_phi"](report(fig9=one_run_fig9(0.6065)), BY_ID["phi-tapped"])
    assert m[0].dof == claims.WITHIN_RUN_DOF
    assert m[0].err == pytest.approx(math.hypot(0.0002, 0.001))
    # the prediction interval of a single tap: 2.09 * 0.00102 = 0.0021 around the steady state
    assert str(claims.verdict(BY_ID["phi-tapped"], m[0])) == "agrees"
    far = claims.STATISTICS["tapped_phi"](report(fig9=one_run_fig9(0.603)), BY_ID["phi-tapped"])
    assert str(claims.verdict(BY_ID["phi-tapped"], far[0])) == "disagrees"


def test_alpha_bell_reads_the_steady_states_maximum_too():
    """The gradient's bell, two readings: about alpha's own largest value, and "the same kind
    of bell as the steady states" (falling above Fig. 4's maximum). An alpha that peaks late
    (a tent at the steady states' maximum + 0.225) agrees with the first and contradicts the
    second; without Fig. 4 the second row is not there."""
    claim = BY_ID["gradient-bell"]
    wide = np.round(np.arange(0.05, 0.49, 0.025), 4)   # the paper's range and beyond
    late = Table().add("b", "bell:alpha", wide, 0.004 - 0.02 * abs(wide - 0.375), 0.0001)
    own, steady = claims.alpha_bell(report(fig6=late, fig4=fig4(BELL)), claim)
    assert own.label == "about its own largest value"
    assert str(claims.verdict(claim, own)) == "agrees", own
    assert steady.label == claims.ALPHA_ABOVE_STEADY
    assert str(claims.verdict(claim, steady)) == "disagrees", steady
    # Fig. 4's parabola vertex, 0.15, sets where "above" starts
    assert "sqrt(eps) >= 0.15 (Fig. 4's maximum)" in steady.text()
    (alone,) = claims.alpha_bell(report(fig6=late), claim)
    assert alone.label == "" and str(claims.verdict(claim, alone)) == "agrees"
    # alpha rising over the whole range: its own side above is missing (undecided), the
    # steady states' reading decides
    rising = Table().add("b", "bell:alpha", X, 0.001 + 0.01 * X, 0.0002)
    own, steady = claims.alpha_bell(report(fig6=rising, fig4=fig4(BELL)), claim)
    assert own.undecided.startswith("fewer than three alphas above the largest")
    assert str(claims.verdict(claim, steady)) == "disagrees"
    # fewer than three alphas above the steady states' maximum: undecided
    few = Table().add("b", "bell:alpha", X[:6], 0.001 + 0.01 * X[:6], 0.0002)
    _, steady = claims.alpha_bell(report(fig6=few, fig4=fig4(BELL)), claim)
    assert steady.undecided.startswith("fewer than three alphas above the steady states' "
                                       "maximum")


def test_every_statistic_of_the_register_has_a_control():
    used = {c.statistic for c in REGISTER if c.statistic}
    missing = sorted(used - set(CONTROLS))
    assert not missing, f"statistics without a control case: {missing}"


@pytest.mark.parametrize("claim", [c for c in REGISTER if c.statistic in CONTROLS],
                         ids=lambda c: c.id)
def test_claim_agrees_on_its_control_and_fails_on_the_reverse(claim):
    good, bad = CONTROLS.get(claim.id, CONTROLS[claim.statistic])
    passing = "holds" if claim.rule == "check" else "agrees"
    outcomes = _outcomes(claim, good)
    assert outcomes and all(o.startswith(passing) for o in outcomes), outcomes
    outcomes = _outcomes(claim, bad)
    assert outcomes and not any(o.startswith(passing) for o in outcomes), outcomes


def test_one_realization_is_never_agreed():
    """Means of one seed carry no sem: every rule that needs one says undecided."""
    tab = Table()
    for eps in (0.005, 0.1):
        tab.param(f"eps={P.fmt_eps(eps)}:final_central", 0.01, None, n=1, x=eps)
        tab.param(f"eps={P.fmt_eps(eps)}:final_lateral", 0.02, None, n=1, x=eps)
    data = report(fig8=tab)
    outcomes = _outcomes(BY_ID["central-smaller"], data)
    assert outcomes and all(o.startswith("undecided") for o in outcomes)


def test_missing_figures_are_undecided_with_what_decides():
    rows = claims.evaluate(REGISTER, report())
    for row in rows:
        if row.claim.id == "phi-initial":
            continue
        assert row.outcome == "undecided", (row.claim.id, row.verdict)
    # a claim without a statistic yet names the runs that would decide it
    pending = dataclasses.replace(BY_ID["nu-hysteresis"], statistic="", rule="none")
    (row,) = claims.evaluate([pending], report())
    assert row.outcome == "undecided" and pending.decided_by in str(row.verdict)


def test_sigma_error_of_one_run_matches_the_spread_of_realizations():
    """Fig. 3's error of sigma_<Z> for one run (batch means of squared deviations) against the
    spread of sigma over 300 realizations of a correlated series (AR(1), correlation 0.8)."""
    from tapmc.paper._steady_state import sigma_error_one_run

    rng = np.random.default_rng(7)
    sigmas, errors = [], []
    for _ in range(300):
        noise = rng.standard_normal(1200)
        x = np.empty_like(noise)
        x[0] = noise[0]
        for i in range(1, len(x)):
            x[i] = 0.8 * x[i - 1] + noise[i]
        sigmas.append(np.std(x[-1000:]))
        errors.append(sigma_error_one_run(x, 1000))
    assert np.mean(errors) == pytest.approx(np.std(sigmas), rel=0.3)
    # white noise has a smaller error than the correlated series: the estimate sees correlation
    white = [sigma_error_one_run(rng.standard_normal(1200) * 1.6, 1000) for _ in range(50)]
    assert np.mean(white) < 0.7 * np.mean(errors)


def test_fig4_steady_state_of_one_seed_carries_its_batch_means_error(tmp_path):
    """The paper's protocol has one run per eps: Fig. 4's square then carries that run's own
    (batch-means) error, which the bell's statistics use; two seeds give the error over seeds."""
    sys.path.insert(0, str(Path(__file__).parent))
    from paper_fakes import FakeCampaign
    from tapmc.fluctuations import SteadyState
    from tapmc.paper import _runs, fig4
    from tapmc.paper.scales import QUICK

    rng = np.random.default_rng(3)
    specs = [_runs.constant_eps_run(QUICK, "pbc", eps, seed)
             for eps, seeds in ((0.01, (1,)), (0.04, (1, 2))) for seed in seeds]
    camp = FakeCampaign(tmp_path, specs)
    series = {}
    for spec in specs:
        phi = 0.6 + 0.002 * rng.standard_normal(401)
        series[spec.name] = phi
        rows = ["# step phi_b phi_c Z z_top lateral central h_s sweeps accept capped"]
        rows += [f"{t} 0.55 {p:.10f} 5.0 9.0 0.5 0.5 10.0 100 0.1 0" for t, p in enumerate(phi)]
        (camp.result(spec.name) / "taps.dat").write_text("\n".join(rows) + "\n")
    sq, mean, sem, n = fig4.steady_states(camp)
    one = SteadyState(series[specs[0].name][1:], last=100).compute()
    assert list(n) == [1, 2]
    assert mean[0] == pytest.approx(one.mean) and sem[0] == pytest.approx(one.sem)
    means = [SteadyState(series[s.name][1:], last=100).compute().mean for s in specs[1:]]
    assert sem[1] == pytest.approx(np.std(means, ddof=1) / np.sqrt(2))


def test_fig2_refit_table_recomputes_the_statistics_from_the_curves(tmp_path):
    """``report --from-data --refit``: Fig. 2's intervals, range refits and fit curves come
    from the CSV's own curves; the curves are kept as they are."""
    from tapmc.paper import fig2

    t = np.concatenate([[0.0], np.unique(np.round(np.geomspace(1, 1000, 150)))])
    rng = np.random.default_rng(11)
    table = Table()
    for eps, (b, tau) in ((0.05, (0.3, 20.0)), (0.15, (0.2, 5.0))):
        y = inverse_log(t, x_inf=0.62, dx=0.05, b=b, tau=tau) + 2e-4 * rng.standard_normal(t.size)
        table.add("a", f"eps={P.fmt_eps(eps)}", t, y, 2e-4, 3)
        table.add("a", f"fit:eps={P.fmt_eps(eps)}", t, np.full(t.size, 0.5), None, 0)
        table.param(f"eps={P.fmt_eps(eps)}:tau", 2.67e5, 0.026, n=0, x=eps)  # a stale row
    out = tmp_path / "fig2.csv"
    fig2.refit_table(table.table).write(out)
    new = P.read_table(out)
    for eps in ("0.05", "0.15"):
        assert np.allclose(new[("a", f"eps={eps}")]["mean"], table.table[("a", f"eps={eps}")]["mean"])
        tau = new[("params", f"eps={eps}:tau")]
        assert tau["n"][0] == 1 and 1.0 < tau["mean"][0] < 100.0  # determined, not 2.67e5
        assert ("params", f"eps={eps}:tau:lo") in new
        assert ("params", f"eps={eps}:X_inf:range_deviation") in new
        fit = new[("a", f"fit:eps={eps}")]["mean"]
        assert np.max(np.abs(fit - new[("a", f"eps={eps}")]["mean"])) < 0.002
    assert ("B", "eq3:slope") in new


def test_fig5_refit_table_finds_the_scaling_of_its_curves(tmp_path):
    """``report --from-data --refit`` on Fig. 5: the collapse of the CSV's own curves (here
    built with mu = 0.7, kappa = 0.3) replaces the rows of an older analysis, and the ageing
    claim is decided from it."""
    from test_fit_limits import _ageing_curves
    from tapmc.paper import fig5

    table = Table()
    for tw, (t, a, sem) in _ageing_curves(0.7, 0.3, 1).items():
        every = slice(0, None, 5)  # 151 delays per curve: enough, and fast
        table.add("a", f"tw={tw:g}", t[every], a[every], sem[every], 4)
        table.param(f"tw={tw:g}:A_inf", 0.02, 0.001, n=1, x=tw)
    table.add("b", "tw=10", [1.0, 2.0], [0.0, 0.0])  # an unscaled panel b of an older analysis
    table.param("collapse:reduced_chi2", 2.4e4)
    for name in ("A_inf", "B_A", "tau_A"):    # written with it
        table.param(f"collapse:{name}", 1.0, 0.1)
    out = tmp_path / "fig5.csv"
    fig5.refit_table(table.table).write(out)
    new = P.read_table(out)
    assert new[("params", "scaling:mu")]["mean"][0] == pytest.approx(0.7, abs=0.05)
    assert new[("params", "drawn:mu")]["n"][0] == 1
    assert ("params", "tw=10:A_inf") in new and ("params", "collapse:reduced_chi2") in new
    assert len(new[("b", "tw=10")]["x"]) == 151
    refitted = Table()
    refitted.table = new
    (m,) = claims.STATISTICS["ageing_collapse"](report(fig5=refitted), BY_ID["ageing-scaling"])
    # curves built to collapse: the law-free dispersion of the refit is about 1 and agrees
    assert m.value < 2 and "4 realizations" in m.text(), m
    assert str(claims.verdict(BY_ID["ageing-scaling"], m)).startswith("agrees"), m


def test_ageing_collapse_is_law_free():
    """The collapse is decided by the law-free dispersion at its best exponents, with a
    p-value bound that holds whatever the delays' correlation: eq. 6's collapse test is shown
    and decides nothing; too few realizations leave it undecided."""
    claim = BY_ID["ageing-scaling"]
    assert _outcomes(claim, report(fig5=fig5_collapse(0.3, realizations=2)))[0].startswith(
        "undecided (2 realizations")
    m = claims.STATISTICS["ageing_collapse"](report(fig5=fig5_collapse(0.3)), claim)[0]
    assert m.text() == ("law-free dispersion 1.1 at mu = 0.9, kappa = 0.1 (1 for curves that "
                        "are one within their errors; unscaled 40), 10 realizations; on eq. 6 "
                        "as master curve (decides nothing): T^2 10 (3 dof), p = 0.3; p <= 1 "
                        "whatever the delays' correlation")
    # the bound: one squared standardized difference F(1, 9) dominates the mean of many
    assert claims.dispersion_p_bound(1.0, 10) == 1.0
    assert 1e-3 < claims.dispersion_p_bound(30.0, 10) < 1e-2
    assert claims.dispersion_p_bound(30.0, 4) > claims.dispersion_p_bound(30.0, 10)
    assert np.isnan(claims.dispersion_p_bound(30.0, 3))  # F(1, 2) has no mean: no bound


def test_ageing_eq6_rows_per_curve_and_undecided_without_its_test():
    claim = BY_ID["ageing-eq6"]
    rows = claims.STATISTICS["ageing_eq6"](report(fig5=fig5_eq6(0.3)), claim)
    assert [m.label for m in rows] == ["t_W = 10", "t_W = 30", "t_W = 100"]
    assert rows[0].text() == ("T^2 4 (5 dof) over 8 log bins of delays, 10 realizations; the "
                              "mean displacement's square is 97.00 % of A; over the delays "
                              ">= 100 alone (a linear axis of t, as the paper draws it): p = "
                              "0.4")
    few = _outcomes(claim, report(fig5=fig5_eq6(0.3, realizations=4)))
    assert len(few) == 3 and all(o.startswith(
        "undecided (4 realizations: eq. 6's test across realizations needs at least 5") for o in few)
    assert all("draw Fig. 5 again" in o
               for o in _outcomes(claim, report(fig5=fig5_eq6(0.3, tested=False))))
    assert _outcomes(claim, report())[0].startswith("undecided (not in this campaign")


def test_theta0_scan_within_noise_is_undecided():
    # pi/2 compacts as much as pi/4 within the seeds' error: the pattern is not decided
    m = claims.STATISTICS["theta0_optimum"](theta0_report({**THETA0_PAPER, 1 / 2: 0.0099}),
                                             BY_ID["theta0-optimum"])[0]
    assert m.undecided and "compacts less than pi/4" in m.undecided
    assert "pi/16: -2.00 ± " in m.shown and "most: pi/4" in m.shown


def test_theta_law_shape_reads_each_law_against_eq1s_scan_of_the_same_size():
    claim = BY_ID["theta-law-shape"]
    statistic = claims.STATISTICS["theta_law_shape"]
    data = theta_law_report({**THETA0_PAPER, 1 / 8: 0.004})
    (m,) = statistic(data, claim)
    assert m.value == 1.0
    assert m.label.startswith("exponential P(theta) against eq. 1's, N = 1024")
    # turns between pi/16 (-0.0200) and pi/8 (+0.0041 with the seeds' jitter): 0.83 of the way,
    # theta0 = 0.114 pi; eq. 1 between pi/8 (-0.0101) and pi/4 (+0.0100): theta0 = 0.187 pi
    assert "exponential turns at theta0 = 0.114 pi, <theta> = 19.2 deg" in m.shown
    assert "eq. 1 turns at theta0 = 0.187 pi, <theta> = 18.9 deg" in m.shown
    # the smallest width within the seeds' noise: undecided, naming it
    (m,) = statistic(theta_law_report({**THETA0_PAPER, 1 / 16: 0.0001}), claim)
    assert m.undecided == "within t sem at the smallest width pi/16"
    # a law scanned at another N than eq. 1's: undecided, not compared across sizes
    data = theta_law_report(THETA0_PAPER, law="linear")
    for row in data.questions["theta0_linear"]:
        row["N"] = "4096"
    data.questions["theta0_linear_N4096"] = data.questions.pop("theta0_linear")
    (m,) = statistic(data, claim)
    assert m.undecided == "no scan of eq. 1's law at the same N, stop rule and eta"
    assert statistic(theta0_report(THETA0_PAPER), claim)[0].undecided.startswith(
        "no scan of the alternative laws")


def test_mean_angle_of_the_theta_laws():
    from tapmc.paper.claims.scans import mean_angle
    # linear within pi/2: the triangle's mean theta0 / 3; flat limits: pi/4
    for theta0 in (0.2, 0.7, 1.5):
        assert mean_angle("linear", theta0) == pytest.approx(theta0 / 3, rel=1e-6)
    for law in ("angle", "exponential", "linear"):
        assert mean_angle(law, 1e3) == pytest.approx(math.pi / 4, rel=2e-3)
    # narrow: the half-Gaussian's theta0 / sqrt(pi), the exponential's theta0
    assert mean_angle("angle", 0.01) == pytest.approx(0.01 / math.sqrt(math.pi), rel=1e-4)
    assert mean_angle("exponential", 0.01) == pytest.approx(0.01, rel=1e-4)


def test_dmax_is_compared_within_one_N_of_the_front():
    # a second N where only the default has run (no reference yet: no bias) changes nothing
    data = front_report(-0.005, -0.007)
    data.front.append({"setting": "change 1e-7 (default)", "N": 4096.0, "eps": 0.0225,
                       "phi_c_steady_bias": float("nan"), "phi_c_steady_bias_se": float("nan"),
                       "paired_seeds": 0.0, "sweeps_per_tap": 3700.0})
    measures = claims.STATISTICS["dmax_intermediate"](data, BY_ID["dmax-intermediate"])
    assert [round(m.value, 6) for m in measures] == [0.003, 0.005]
    assert all("N = 1024" in m.label and "1800 and 1800 sweeps" in m.label for m in measures)


def test_dmax_scan_adds_both_ends_to_the_front():
    """The scan's two sides of 'intermediate', each with the paper's own quantity: the
    compaction over the taps against the smallest d_max (nearly frozen), the compaction per
    sweep of the redeposition against the largest (evolves very slowly): a largest d_max that
    compacts as much per tap at three times the sweeps agrees, one that does at half the
    sweeps disagrees."""
    def scan(large_gain=0.001, large_sweeps=1800):
        rows = []
        for seed, shift in zip(range(1, 5), (-0.002, -0.001, 0.001, 0.002)):
            for k, (frac, gain, sweeps) in enumerate(((0.02, 0.002, 1800), (0.2, 0.010, 1800),
                                                      (1.0, large_gain, large_sweeps))):
                rows.append({"dmax_over_R": str(frac), "seed": str(seed), "N": "1024",
                             "eps": "0.0225", "taps": "100", "eta": "1e-07", "stop": "change",
                             "phi_c_0": "0.58", "sweeps_per_tap": str(sweeps),
                             "phi_c_end": f"{0.58 + gain + shift + 0.0002 * ((seed + k) % 3 - 1):.8f}"})
        data = front_report(-0.005, -0.007)
        data.scans["dmax"] = [rows]
        return data

    claim = BY_ID["dmax-intermediate"]
    measures = claims.STATISTICS["dmax_intermediate"](scan(), claim)
    found = [m for m in measures if m.label.startswith("d_max scan")]
    assert [m.value for m in found] == pytest.approx([0.008, 0.009 / (100 * 1800)], rel=0.05)
    assert "minus with R/50 (nearly frozen)" in found[0].label
    assert "per sweep with R/5 minus with R (evolves very slowly)" in found[1].label
    assert all(str(claims.verdict(claim, m)).startswith("agrees") for m in measures)
    (_, slow) = [m for m in claims.STATISTICS["dmax_intermediate"](
        scan(0.010, 5400), claim) if m.label.startswith("d_max scan")]
    assert str(claims.verdict(claim, slow)) == "agrees", slow
    (_, fast) = [m for m in claims.STATISTICS["dmax_intermediate"](
        scan(0.010, 900), claim) if m.label.startswith("d_max scan")]
    assert str(claims.verdict(claim, fast)) == "disagrees", fast

def test_eq7_smoothing_removes_the_wall_layers_and_keeps_a_departure():
    """Fig. 6's profile about eq. 7: layers one diameter apart average out over blocks of 2R;
    a smooth departure stays and the fit rule rejects it."""
    claim = BY_ID["eq7-fit"]
    profiles = report(fig6=fig6_profile()).result("fig6").profiles
    departures, errors = claims.smoothed_departures(profiles.final, profiles.law_curves["final"],
                                                    5.0, 2.0)
    assert len(departures) == 13      # blocks from 5R up to the packing's top, 31R
    # a decaying layering averages out to within a third of the errors
    np.testing.assert_allclose(departures, 0.0, atol=1e-3)
    np.testing.assert_allclose(errors, 0.003)
    (m,) = claims.eq7_smoothed_fit(report(fig6=fig6_profile(0.02)), claim)
    assert str(claims.verdict(claim, m)).startswith("disagrees")


def test_wall_layers_are_counted_from_each_wall_until_a_diameter_without_one():
    (left, right) = claims.wall_layering(report(fig7=fig7_profile()), BY_ID["wall-layering"])
    for m in (left, right):
        assert m.text().startswith("3 layers") and m.value == 1
    # a run of bins above the level is one layer; a diameter below it ends the count, and a
    # first layer further than a diameter from the wall is none
    d = np.arange(0.1, 10.0, 0.2)
    phi = np.where((d > 1) & (d < 2), 1.0, 0.0) + np.where((d > 3) & (d < 3.5), 1.0, 0.0) \
        + np.where(d > 6, 1.0, 0.0)
    assert claims.wall_layers(d, phi, 0.5) == [(pytest.approx(1.1), pytest.approx(2.1)),
                                               (pytest.approx(3.1), pytest.approx(3.5))]
    assert claims.wall_layers(d, np.where(d > 2.5, 1.0, 0.0), 0.5) == []


def test_p0_off_percus_yevick_by_less_than_its_change_agrees_at_the_papers_precision():
    """Fig. 9: a tapped P0 that Percus-Yevick's test rejects agrees at the paper's precision
    while its departure is within the change Percus-Yevick gives between the initial and
    tapped packing fractions (what the paper calls a slight difference), not beyond it."""
    claim = BY_ID["p0-percus-yevick"]
    change = float(np.max(np.abs(percus_yevick_p0(np.linspace(0.0, 2.0, 60), 0.606)
                                 - percus_yevick_p0(np.linspace(0.0, 2.0, 60), 0.584))))
    (m,) = claims.p0_final_minus_py(report(fig9=fig9(py_shift=0.5 * change)), claim)
    assert m.paper_precision == pytest.approx(0.5)
    assert claims.verdict(claim, m).outcome == claims.Outcome.AGREES_AT_PAPER_PRECISION
    (m,) = claims.p0_final_minus_py(report(fig9=fig9(py_shift=1.5 * change)), claim)
    assert claims.verdict(claim, m).outcome == claims.Outcome.DISAGREES


def test_several_seeds_rate_change_error_covers_seeds_correlated_over_hundreds_of_taps():
    """efficiency_decrease from a seed-averaged curve: each seed's Phi_b wanders about the law
    with a memory of 300 taps (AR(1)), as a real run does. The rate change's error must cover
    its scatter over replicas of the seeds (a line fitted through the taps as independent
    points: 69 % of the replicas within 2 errors, median pull 1.5; the windows' bound: 98 %,
    median pull 0.4, conservative by about 1.7)."""
    from scipy.signal import lfilter
    from tapmc.paper.claims.compaction import _rate_change

    rng = np.random.default_rng(1995)
    t = np.arange(0.0, 4001.0)
    law = 0.62 - 0.04 / (1.0 + np.log1p(t / 10.0))
    memory = math.exp(-1.0 / 300.0)
    flat = np.full_like(t, 1e-4)
    truth = _rate_change(0.05, t, law, flat, np.full_like(t, 3)).value
    pulls = []
    for _ in range(200):
        kicks = 0.003 * math.sqrt(1 - memory ** 2) * rng.standard_normal((3, t.size))
        seeds = law + lfilter([1.0], [1.0, -memory], kicks, axis=1)
        mean, sem = seeds.mean(axis=0), seeds.std(axis=0, ddof=1) / math.sqrt(3)
        m = _rate_change(0.05, t, mean, sem, np.full_like(t, 3))
        pulls.append((m.value - truth) / m.err)
    pulls = np.abs(pulls)
    # bounds, not estimates: at least the coverage of an exact error, not wildly wider
    assert np.mean(pulls < 2.0) >= 0.93
    assert np.median(pulls) > 0.2


def test_fits_of_a_seed_averaged_curve_decide_no_triplet_and_reject_no_line():
    """Fig. 2's fits of a curve averaged over seeds take its taps as independent points (each
    seed's taps are correlated): their 'unique' and 'range dependent' are both unsafe, so the
    triplet's pattern stays undecided whatever their flags, and a B line they reject stays
    undecided while one they accept agrees (too narrow errors only make rejection easier)."""
    claim = BY_ID["eq3-triplet-range"]
    for flags in ({0.005: False, 0.05: True, 0.15: True}, {0.005: True, 0.05: False}):
        (m,) = claims.eq3_triplet_pattern(report(fig2=fig2_fits(flags)), claim)
        assert m.undecided == claims.AVERAGED_FITS, m
    claim = BY_ID["b-exponential"]
    for law in claims.b_exponential(report(fig2=fig2_fits({0.05: True}, b_chi2=8.0, b_dof=3)),
                                    claim):   # eq. 3's and eq. 4's B
        assert law.undecided and law.undecided.endswith("too narrow to reject"), law
    for law in claims.b_exponential(report(fig2=fig2_fits({0.05: True}, b_chi2=1.0, b_dof=3)),
                                    claim):
        assert str(claims.verdict(claim, law)).startswith("agrees"), law
