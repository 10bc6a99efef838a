# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The claims register and its verdicts: the register is valid; each rule decides known cases
(Student's t for few seeds, undecided without an uncertainty); and every statistic a claim
uses has a control: synthetic figure data on which it must agree and data on which it must
not (time-reversed, swapped, flat, shifted), so that no row of the report cannot fail."""

import dataclasses
import math
import os
import sys
from pathlib import Path

import numpy as np
import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc.paper import claims  # noqa: E402
from tapmc.paper import _plotting as P  # noqa: E402
from tapmc.pores import percus_yevick_p0  # noqa: E402

REGISTER = claims.load_register()
BY_ID = {c.id: c for c in REGISTER}
SEEDS = 5  # realizations behind the synthetic means (dof = 4)


# ---------------------------------------------------------------- the register


def test_register_is_valid_and_covers_the_paper():
    ids = [c.id for c in REGISTER]
    assert len(ids) == len(set(ids))
    sections = {c.section for c in REGISTER}
    assert {"II", "III.A", "III.B", "III.C", "IV.A", "IV.B"} <= sections
    for c in REGISTER:
        assert c.tolerance.strip() and c.decided_by.strip()
        if c.statistic:
            assert c.statistic in claims.STATISTICS
    # the rows of the issue's list of unanswered claims are all in the register
    for needed in ("spectrum-high-frequency", "ramp-up-near-squares", "critical-sqrt-eps",
                   "reversible-above", "irreversible-frozen", "gradient-bell",
                   "gradient-no-hysteresis", "lateral-first-tap-jump", "pore-law-quadratic",
                   "eq4-compatible", "b-exponential", "ageing-scaling", "eq3-triplet-range"):
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


# ---------------------------------------------------------------- the rules


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


# ---------------------------------------------------------------- synthetic figure data


class Table:
    """A figure's data built in memory, as tapmc.paper._plotting.read_table returns it."""

    def __init__(self):
        self.table = {}

    def add(self, panel, series, x, mean, sem=None, n=SEEDS):
        x = np.atleast_1d(np.asarray(x, float))
        mean = np.broadcast_to(np.asarray(mean, float), x.shape).copy()
        sem = np.full(x.shape, np.nan) if sem is None else \
            np.broadcast_to(np.asarray(sem, float), x.shape).copy()
        self.table[(panel, series)] = {"x": x, "mean": mean, "sem": sem,
                                       "n": np.full(x.shape, n)}
        return self

    def param(self, series, value, sem=None, n=SEEDS, x=0.0):
        return self.add("params", series, x, value, sem, n)

    def data(self):
        return claims.FigureData(self.table)


def report(summary=None, **figures):
    base = {"sizes": [[4096, 32.0]], "eta": [1e-7], "preset": True, "scale": "full",
            "fields": None, "initial_phi_c": [0.584, 0.001, SEEDS]}
    base.update(summary or {})
    return claims.ReportData(base, {k: COMPLETE_ROWS.get(k, lambda tab: tab)(v).data()
                                    for k, v in figures.items()})


T = np.unique(np.round(np.geomspace(1, 4000, 120)))
T = np.concatenate([[0.0], T])


def fig2(curves):
    tab = Table()
    for eps, y in curves.items():
        tab.add("a", f"eps={P.fmt_eps(eps)}", T, y, 0.0005)
        tab.param(f"eps={P.fmt_eps(eps)}:reduced_chi2", 1.0, x=eps)
    return tab


def inverse_log(t, x_inf=0.62, dx=0.04, b=1.0, tau=10.0):
    return x_inf - dx / (1 + b * np.log1p(t / tau))


RISING = inverse_log(T)


def fig3(spectra=None, slope=-1.2, intercept=0.001, intercept_sem=0.002,
         intercept_detrended=0.001):
    tab = Table()
    f = np.geomspace(1e-3, 0.5, 40)
    for eps, scale in (spectra or {}).items():
        tab.add("a", f"eps={P.fmt_eps(eps)}", f, scale(f), 0.02 * scale(f))
    tab.param("eps=0.01:slope", slope, 0.05, x=0.01)
    tab.param("intercept", intercept, intercept_sem)
    tab.param("intercept_detrended", intercept_detrended, intercept_sem)
    for series in ("sigma_Z", "sigma_Z_detrended"):
        tab.add("b", series, [0.05, 0.1, 0.15, 0.2, 0.3], [0.05, 0.1, 0.15, 0.2, 0.3], 0.003)
    return tab


X = np.round(np.arange(0.05, 0.40, 0.025), 4)


def fig4(steady, up1=None, down=None, up2=None):
    tab = Table().add("a", "steady", X, steady, 0.001)
    for name, y in (("up1", up1), ("down", down), ("up2", up2)):
        if y is not None:
            tab.add("a", name, X, y, 0.001)
    return tab


BELL = 0.60 - 2.0 * (X - 0.15) ** 2


def ramp_pores(gap, slope, sem=0.001, levels=(0.025, 0.05, 0.075, 0.1, 0.125)):
    """tapmc-paper question ramp-pores rows of a ramp beyond (sqrt eps)*: nu on the first
    increase 0.1 - 0.05 sqrt(eps), the decrease ``gap`` away at 0.1 with ``slope``."""
    rows = []
    for branch, nus in ((0, [0.1 - 0.05 * x for x in levels]),
                        (1, [0.1 + gap + slope * (x - 0.1) for x in levels])):
        rows += [{"run": "ramp_pbc_s1", "branch": str(branch), "sqrt_eps": f"{x:g}",
                  "nu": f"{nu:.8f}", "nu_sem": f"{sem:g}"} for x, nu in zip(levels, nus)]
    # the ramp below (sqrt eps)* in the same table is not read for the ramp beyond's signs
    rows += [{"run": "ramplow_pbc_s1", "branch": str(b), "sqrt_eps": "0.05", "nu": "0.5",
              "nu_sem": f"{sem:g}"} for b in (0, 1)]
    return claims.ReportData(report().summary, {}, questions={"ramp_pores": rows})


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


def ramps_turning(down_changes, sem=0.0005, n=SEEDS):
    """Fig. 4 params of ramps turning at each sqrt(eps) of ``down_changes`` (top -> the
    decrease minus the top level), one CSV tag per ramp."""
    tab = fig4(BELL).param("critical_sqrt_eps", 0.15, None, 1)
    for tag, (top, change) in zip(FIG4_RAMP_TAGS, sorted(down_changes.items())):
        tab.param(f"{tag}:top_sqrt_eps", top, None, n)
        tab.param(f"{tag}:down_change", change, sem, n, x=top)
    return tab


def _critical(down_changes, **kw):
    (m,) = claims.critical_separation(report(fig4=ramps_turning(down_changes, **kw)),
                                      BY_ID["critical-sqrt-eps"])
    return m, str(claims.verdict(BY_ID["critical-sqrt-eps"], m))


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


def fig6_ramp(gap):
    """alpha at the end of the ramp's levels (Fig. 6 bottom, one seed): the decrease is the
    first increase plus ``gap`` and a level-to-level scatter of 5e-5."""
    alpha = 0.001 + 0.01 * X
    jitter = 5e-5 * (-1.0) ** np.arange(len(X))
    return (Table().add("b", "ramp:up1", X, alpha, 3e-4, 1)
            .add("b", "ramp:down", X, alpha + gap + jitter, 3e-4, 1))


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


#: the one-row params of Fig. 9's typed result (tapmc.paper.fig9.Fig9Result) besides its curves
FIG9_PARAMS = ("phi_initial", "phi_final", "phi_c_initial", "phi_c_final",
               "max_abs_diff_initial_final", "max_abs_diff_final_py")


def with_fig9_params(tab):
    """``tab`` with every param of Fig. 9's result, NaN (not measured) where it has none."""
    for name in FIG9_PARAMS:
        if ("params", name) not in tab.table:
            tab.param(name, math.nan, None, n=1)
    return tab


def fig9(diff=0.0, py_shift=0.0):
    sigma = np.linspace(0.0, 2.0, 60)
    final = percus_yevick_p0(sigma, 0.606) + py_shift
    tab = Table().add("a", "final", sigma, final, 0.0005)
    tab.add("a", "initial", sigma, final + diff, 0.0005)
    tab.add("a", "percus_yevick", sigma, percus_yevick_p0(sigma, 0.606), None, 1)
    tab.param("phi_initial", 0.584, 0.001).param("phi_final", 0.606, 0.001)
    tab.param("phi_c_initial", 0.584, 0.001).param("phi_c_final", 0.606, 0.001)
    return with_fig9_params(tab)


def one_run_fig9(steady, sem=0.0002, tap_sd=0.001):
    """Fig. 9 data of one seed: no sem over seeds, the steady state with its within-run error."""
    tab = fig9()
    tab.param("phi_c_initial", 0.584, None, n=1)
    tab.param("phi_c_steady", steady, sem, n=1).param("phi_c_tap_sd", tap_sd, None, n=1)
    return tab


def test_one_run_steady_state_is_decided_by_its_within_run_error():
    m = claims.STATISTICS["tapped_phi"](report(fig9=one_run_fig9(0.6065)), BY_ID["phi-tapped"])
    assert m[0].dof == claims.WITHIN_RUN_DOF
    assert m[0].err == pytest.approx(math.hypot(0.0002, 0.001))
    # the prediction interval of a single tap: 2.09 * 0.00102 = 0.0021 around the steady state
    assert str(claims.verdict(BY_ID["phi-tapped"], m[0])) == "agrees"
    far = claims.STATISTICS["tapped_phi"](report(fig9=one_run_fig9(0.603)), BY_ID["phi-tapped"])
    assert str(claims.verdict(BY_ID["phi-tapped"], far[0])) == "disagrees"


XI = np.linspace(0.2, 0.7, 51)


def pore_curve(tail):
    quad = np.where((XI > P.XI_T) & (XI <= P.XI_O), 40 * (XI - P.XI_T) ** 2, 0.0)
    big = np.where(XI > P.XI_O, 40 * (P.XI_O - P.XI_T) ** 2 * np.exp(-(XI - P.XI_O) / tail), 0)
    return quad + big


def with_fig10_rows(tab):
    """``tab`` with every row of Fig. 10's typed result (tapmc.paper.fig10.Fig10Result): the
    distributions of each dump its params name (one NaN point where it has none) and the
    shares' changes (NaN: not measured)."""
    steps = sorted({float(x) for (panel, _), d in tab.table.items() if panel == "params"
                    for x in d["x"]})
    for step in steps:
        for panel in ("a", "b"):
            if (panel, f"t={step:g}") not in tab.table:
                tab.add(panel, f"t={step:g}", [math.nan], [math.nan], None, n=1)
    for name in ("small_change", "large_change"):
        if ("params", name) not in tab.table:
            tab.param(name, math.nan, None, n=1, x=max(steps, default=0.0))
    return tab


def fig10(first=pore_curve(0.1), last=pore_curve(0.05), nu=(0.12, 0.10), tail_ratio=1.0,
          xi_min=0.226):
    tab = Table().add("a", "t=0", XI, first, 0.002).add("a", "t=4000", XI, last, 0.002)
    tab.add("params", "nu", [0, 4000], list(nu), 0.001)
    tab.add("params", "nu_tail", [0, 4000], [nu[0] * tail_ratio, nu[1] * tail_ratio], 0.001)
    tab.add("params", "xi_min", [0, 4000], [xi_min, xi_min], 0.0001)
    return with_fig10_rows(tab)


def fig8(central, lateral, paper_first_tap=None):
    """Fig. 8's zones at two eps, the runs from the walls' start or, with ``paper_first_tap``,
    from the paper's start."""
    tab = Table()
    for eps in (0.005, 0.1):
        tab.param(f"eps={P.fmt_eps(eps)}:final_central", central, 0.0005, x=eps)
        tab.param(f"eps={P.fmt_eps(eps)}:final_lateral", lateral, 0.0005, x=eps)
        if paper_first_tap is None:
            tab.add("a", f"eps={P.fmt_eps(eps)}", [0, 1, 2], [0, -0.003, -0.002], 0.0003)
        else:
            tab.add("a", f"paper:eps={P.fmt_eps(eps)}", [0, 1, 2],
                    [0, paper_first_tap, paper_first_tap], 0.0003)
    return with_fig8_rows(tab)


def with_fig8_rows(tab):
    """``tab`` with every row of Fig. 8's typed result (tapmc.paper.fig8.Fig8Result): the
    lateral (a) and central (b) curves of each eps its params name (one NaN point where it has
    none), from the start its curves name."""
    prefix = "paper:" if any(series.startswith("paper:") for panel, series in tab.table
                             if panel == "a") else ""
    labels = {series.split(":")[0] for panel, series in tab.table if panel == "params"}
    labels |= {series[len(prefix):] for panel, series in tab.table if panel == "a"}
    for label in sorted(labels, key=lambda label: float(label[len("eps="):])):
        for panel in ("a", "b"):
            if (panel, prefix + label) not in tab.table:
                tab.add(panel, prefix + label, [math.nan], [math.nan], None, n=1)
    return tab


def with_fig3_rows(tab):
    """``tab`` with every row of Fig. 3's typed result (tapmc.paper.fig3.Fig3Result): a slope
    for each spectrum and a spectrum for each slope, and sigma_<Z> (NaN where it has none)."""
    spectra = {series for panel, series in tab.table if panel == "a"}
    slopes = {series[:-len(":slope")] for panel, series in tab.table
              if panel == "params" and series.endswith(":slope")}
    for label in sorted(spectra - slopes):
        tab.param(f"{label}:slope", math.nan, None, n=1, x=float(label[len("eps="):]))
    for label in sorted(slopes - spectra):
        tab.add("a", label, [math.nan], [math.nan], None, n=1)
    if ("b", "sigma_Z") not in tab.table:
        tab.add("b", "sigma_Z", [math.nan], [math.nan], None, n=1)
    return tab


#: the rows of Fig. 6's top panel (tapmc.paper.fig6.VerticalProfiles): its curves, its params
FIG6_PROFILE_CURVES = ("initial", "final")
FIG6_PROFILE_PARAMS = ("initial:alpha", "final:alpha", "window_lo", "window_hi", "eps")


def with_fig6_rows(tab):
    """``tab`` with every row of Fig. 6's typed result (tapmc.paper.fig6.Fig6Result): a table
    with any row of the top panel has all of them (NaN where it has none)."""
    top = ([("a", c) for c in FIG6_PROFILE_CURVES]
           + [("params", name) for name in FIG6_PROFILE_PARAMS + ("final:alpha:seeds",)])
    if not any(key in tab.table for key in top):
        return tab
    for curve in FIG6_PROFILE_CURVES:
        if ("a", curve) not in tab.table:
            tab.add("a", curve, [math.nan], [math.nan], None, n=1)
    for name in FIG6_PROFILE_PARAMS:
        if ("params", name) not in tab.table:
            tab.param(name, math.nan, None, n=1)
    return tab


#: the ramps of Fig. 4's typed result (tapmc.paper.fig4.RAMPS), by CSV tag
FIG4_RAMP_TAGS = ("low", "near", "ramp")


def with_fig4_rows(tab):
    """``tab`` with every row of Fig. 4's typed result (tapmc.paper.fig4.Fig4Result): the
    highest square's params, and for a ramp with params a branch and a top (NaN where it has
    none)."""
    if ("a", "steady") not in tab.table:
        tab.add("a", "steady", [math.nan], [math.nan], None, n=1)
    for name in ("sqrt_eps_max", "phi_c_max"):
        if ("params", name) not in tab.table:
            tab.param(name, math.nan, None, n=1)
    for tag in FIG4_RAMP_TAGS:
        prefix = "" if tag == "ramp" else f"{tag}:"
        if not any(panel == "params" and series.startswith(f"{tag}:")
                   for panel, series in tab.table):
            continue
        if not any(("a", prefix + branch) in tab.table for branch in ("up1", "down", "up2")):
            tab.add("a", prefix + "up1", [math.nan], [math.nan], None, n=1)
        if ("params", f"{tag}:top_sqrt_eps") not in tab.table:
            tab.param(f"{tag}:top_sqrt_eps", math.nan, None, n=1)
    return tab


#: figure -> what completes a test's table into every row of the figure's typed result
COMPLETE_ROWS = {"fig3": with_fig3_rows, "fig4": with_fig4_rows, "fig6": with_fig6_rows,
                 "fig8": with_fig8_rows}


def _low_first(eps_curves):
    return dict(sorted(eps_curves.items()))


def fig2_fits(unique_by_eps, chi2_eq4=1.0, b_chi2=1.0, b_dof=1):
    """Fig. 2 data with the fits' intervals, range refits, eq. 4 and ln B(sqrt eps) rows."""
    tab = fig2({eps: RISING for eps in unique_by_eps})
    for eps, unique in unique_by_eps.items():
        tag = f"eps={P.fmt_eps(eps)}"
        tab.add("c", tag, T, 7.4 - (RISING - 0.58), 0.001)
        tab.param(f"{tag}:Z:reduced_chi2", chi2_eq4, x=eps)
        for name in ("X_inf", "B", "tau"):
            tab.param(f"{tag}:{name}", 1.0, 0.1, n=1 if unique else 0, x=eps)
            tab.param(f"{tag}:{name}:range_deviation", 1.0, None, n=1, x=eps)
    for law in ("eq3", "eq4"):
        tab.add("B", f"{law}:reduced_chi2", 0.0, b_chi2, None, b_dof)
        tab.add("B", f"{law}:slope", 0.0, -3.0, 1.0, 1)
    return tab


def realization_rows(eps, phi_b, Z, seeds=range(1, 10), taps=400, seed=13, spread=(2e-4, 2e-3)):
    """early_taps.csv rows of realizations from the same packing: Phi_b = phi_b(t) and
    <Z> = Z(t) plus each realization's AR(1) noise (correlation time ~20 taps)."""
    rng = np.random.default_rng(seed)
    t = np.arange(taps + 1.0)
    rows = []
    for s in seeds:
        noise = np.zeros((2, t.size))
        for k in range(1, t.size):
            noise[:, k] = 0.95 * noise[:, k - 1] + rng.normal(0, 0.31, 2) * np.array(spread)
        x, z = phi_b(t) + noise[0], Z(t) + noise[1]
        rows += [{"eps": str(eps), "seed": str(s), "t": str(int(k)), "phi_b": f"{a:.8f}",
                  "phi_c": "0.55", "Z": f"{b:.8f}"} for k, a, b in zip(t, x, z)]
    return rows



def realized(phi_b, Z, eps=0.05):
    """Fig. 2 with its one-run fits at ``eps`` and 9 realizations of 400 taps (early_taps.csv)
    whose Phi_b and <Z> follow ``phi_b(t)`` and ``Z(t)``."""
    return claims.ReportData(report().summary, {"fig2": fig2_fits({eps: True}).data()},
                             questions={"early_taps": realization_rows(eps, phi_b, Z)})


def eq3_law(t):
    return inverse_log(t, 0.6, 0.08, 0.3, 5.0)


def eq4_law(t):
    L = 0.4 * np.log1p(t / 3.0)
    return 7.1 * (1.0 + L) / (7.1 / 7.6 + L)


def fig5_collapse(p_value, realizations=10, tested=True):
    """Fig. 5 data whose drawn collapse (three waiting times, time and amplitude) has the
    test across ``realizations`` given by its p-value."""
    tab = Table()
    for tw in (0, 10, 30, 100):
        tab.add("a", f"tw={tw}", np.arange(0, 101), np.linspace(0, 0.1, 101), 0.001,
                realizations)
        tab.add("b", f"tw={tw}", np.arange(1, 101), np.linspace(0, 1, 100), 0.01)
    tab.param("drawn:mu", 1.0, None, n=1).param("scaling:reduced_chi2", 37.6)
    tab.param("scaling:mu", 1.0, 0.1, n=1).param("unscaled:reduced_chi2", 40.0)
    tab.param("scaling_test:needed", 7)
    if tested and realizations >= 7:
        tab.param("scaling_test:T2", 10.0).param("scaling_test:dof", 3)
        tab.param("scaling_test:p_value", p_value).param("scaling_test:bins", 8)
        tab.param("scaling_test_long:p_value", 0.5)
    return tab


def fig5_eq6(p_value, realizations=10, tested=True):
    """Fig. 5 data whose curves have eq. 6's test across ``realizations``, every curve with
    the p-value ``p_value``."""
    tab = fig5_collapse(0.3, realizations)
    tab.param("eq6_test:needed", 5)
    if tested and realizations >= 5:
        for tw in (10, 30, 100):
            tab.param(f"eq6_test:tw={tw}:T2", 4.0).param(f"eq6_test:tw={tw}:dof", 5)
            tab.param(f"eq6_test:tw={tw}:p_value", p_value).param(f"eq6_test:tw={tw}:bins", 8)
            tab.param(f"drift_share:tw={tw}", 0.97)
            tab.param(f"eq6_test_long:tw={tw}:p_value", 0.4)
    return tab


FROZEN = 0.58 + 0.02 * (1 - 1 / (1 + 0.3 * np.log1p(T)))    # slows down on ln t
STEADY_LOG = 0.58 + 0.04 * np.log1p(T) / np.log(4001)       # keeps its rate on ln t


#: statistic (or claim id, which comes first) -> (data on which its claims must agree, data on
#: which they must not).
def front_report(r10_bias, r2_bias):
    """A report whose front has d_max R/10, R/5 (the default) and R/2 at eps 0.0225, 4 seeds:
    steady <Phi^c> biases against the reference as given (R/5: -0.002), se 0.0003 each."""
    rows = [{"setting": name, "N": 1024.0, "eps": 0.0225, "phi_c_steady_bias": bias,
             "phi_c_steady_bias_se": 0.0003, "paired_seeds": 4.0, "sweeps_per_tap": 1800.0}
            for name, bias in (("change 1e-7 (default)", -0.002), ("dmax R/10", r10_bias),
                               ("dmax R/2", r2_bias))]
    data = report()
    data.front = rows
    return data


def theta0_report(gains):
    """A report with a theta0 scan: theta0 / pi -> compaction over the taps; 4 seeds, each seed
    shifting every theta0's gain alike (paired) plus a small jitter per theta0."""
    rows = []
    for seed, shift in zip(range(1, 5), (-0.002, -0.001, 0.001, 0.002)):
        for k, (frac, gain) in enumerate(sorted(gains.items())):
            jitter = 0.0002 * ((seed + k) % 3 - 1)
            rows.append({"theta0_over_pi": f"{frac:.6f}", "seed": str(seed), "N": "1024",
                         "eps": "0.0225", "taps": "100", "phi_c_0": "0.58",
                         "phi_c_end": f"{0.58 + gain + shift + jitter:.8f}",
                         "sweeps_per_tap": "1800"})
    data = report()
    data.scans["theta0"] = [rows]
    return data


#: the paper's pattern (pi/16 decompacts, pi/4 compacts most) and one where pi/3 compacts most
THETA0_PAPER = {1 / 16: -0.02, 1 / 8: -0.01, 1 / 4: 0.010, 1 / 3: 0.009, 1 / 2: 0.004}
THETA0_WIDER = {**THETA0_PAPER, 1 / 3: 0.016}


CONTROLS = {
    "initial_phi": (report(), report({"initial_phi_c": [0.570, 0.001, SEEDS]})),
    "theta0_optimum": (theta0_report(THETA0_PAPER), theta0_report(THETA0_WIDER)),
    # both other d_max leave the packing looser (slower) / both leave it denser than R/5
    "dmax_intermediate": (front_report(-0.005, -0.007), front_report(0.0, 0.0)),
    "tapped_phi": (report(fig9=fig9()),
                   report(fig9=fig9().param("phi_c_final", 0.593, 0.0005))),
    # one run: the steady state's batch-means error and the spread of single taps decide
    "phi-tapped": (report(fig9=one_run_fig9(0.6065)), report(fig9=one_run_fig9(0.600))),
    "pbc-bulk-compacts": (report(fig9=one_run_fig9(0.6065)),
                          report(fig9=one_run_fig9(0.5838))),
    "pbc_compaction": (report(fig9=fig9()),
                       report(fig9=fig9().param("phi_c_final", 0.570, 0.001))),
    "phi_b_gain": (report(fig2=fig2({0.05: RISING})),
                   report(fig2=fig2({0.05: RISING[::-1]}))),  # time-reversed
    "efficiency_decrease": (report(fig2=fig2({0.05: RISING})),
                            report(fig2=fig2({0.05: 0.58 + 1e-5 * T}))),  # steady rate
    "eq3_triplet_pattern": (report(fig2=fig2_fits({0.005: False, 0.05: True, 0.15: True})),
                            report(fig2=fig2_fits({0.005: False, 0.05: False, 0.15: False}))),
    # across realizations: the laws themselves, and a power of t that neither law follows
    "eq4_fit_quality": (realized(eq3_law, eq4_law),
                        realized(eq3_law, lambda t: 7.7 - 0.05 * t ** 0.3)),
    "b_exponential": (report(fig2=fig2_fits({0.05: True}, b_chi2=1.0, b_dof=3)),
                      report(fig2=fig2_fits({0.05: True}, b_chi2=8.0, b_dof=3))),
    # the test across realizations decides, not the reduced chi2 over correlated delays
    "ageing_collapse": (report(fig5=fig5_collapse(0.3)), report(fig5=fig5_collapse(0.002))),
    "ageing_eq6": (report(fig5=fig5_eq6(0.3)), report(fig5=fig5_eq6(0.002))),
    "eq3_fit_quality": (realized(eq3_law, eq4_law),
                        realized(lambda t: 0.52 + 0.01 * t ** 0.3, eq4_law)),
    "log_time_slowing": (report(fig2=fig2(_low_first({0.005: FROZEN, 0.15: STEADY_LOG}))),
                         report(fig2=fig2(_low_first({0.005: STEADY_LOG, 0.15: FROZEN})))),
    # the curve that keeps its rate on ln t makes a larger share of its gain late
    "late_gain_share": (report(fig2=fig2(_low_first({0.005: STEADY_LOG, 0.15: FROZEN}))),
                        report(fig2=fig2(_low_first({0.005: FROZEN, 0.15: STEADY_LOG})))),
    "spectral_slopes": (report(fig3=fig3(slope=-1.2)), report(fig3=fig3(slope=-0.5))),
    "spectrum_eps_spread": (
        # spectra that coincide at low f and separate at high f, and the reverse
        report(fig3=fig3({e: (lambda f, e=e: 1e-3 / f + 10 * e) for e in (0.01, 0.04, 0.09)})),
        report(fig3=fig3({e: (lambda f, e=e: 1e-3 * e / f + 1.0) for e in (0.01, 0.04, 0.09)}))),
    "sigma_intercept": (report(fig3=fig3()), report(fig3=fig3(intercept=0.05))),
    # each row reads its own sigma: the other's intercept stays zero in the failing case
    "sigma-proportional-detrended": (report(fig3=fig3(intercept=0.05)),
                                     report(fig3=fig3(intercept_detrended=0.05))),
    "bell_maximum": (report(fig4=fig4(BELL)),
                     report(fig4=fig4(0.60 - 2.0 * (X - 0.3) ** 2))),
    "bell_side_slope": (report(fig4=fig4(BELL)), report(fig4=fig4(0.65 - BELL))),
    # per claim where one statistic serves two claims: the side of the bell that must fail
    "bell-rising": (report(fig4=fig4(BELL)), report(fig4=fig4(0.62 - 0.05 * X))),
    "bell-falling": (report(fig4=fig4(BELL)), report(fig4=fig4(0.58 + 0.05 * X))),
    # rule near: within a tenth of the gap (0.003 here), beyond it
    "ramp_up_minus_steady": (report(fig4=fig4(BELL, up1=BELL, down=BELL + 0.03)),
                             report(fig4=fig4(BELL, up1=BELL - 0.01, down=BELL + 0.01))),
    "ramp_down_minus_up": (report(fig4=fig4(BELL, up1=BELL, down=BELL + 0.01)),
                           report(fig4=fig4(BELL, up1=BELL, down=BELL - 0.01))),
    "ramp_up2_minus_down": (report(fig4=fig4(BELL, up1=BELL, down=BELL + 0.03,
                                             up2=BELL + 0.03)),
                            report(fig4=fig4(BELL, up1=BELL, down=BELL + 0.03, up2=BELL))),
    "low_ramp_frozen": (
        report(fig4=fig4(BELL).param("low:down_change", 0.0002, 0.0005)
               .param("ramp:down_change", 0.01, 0.0005)),
        report(fig4=fig4(BELL).param("low:down_change", 0.01, 0.0005)
               .param("ramp:down_change", 0.01, 0.0005))),
    # turning at 0.125 (frozen) and 0.175 (compacts on the way down), and the reverse
    "critical_separation": (report(fig4=ramps_turning({0.125: 0.0002, 0.175: 0.01})),
                            report(fig4=ramps_turning({0.125: 0.01, 0.175: 0.0002}))),
    # nu: below its first increase on the way down and rising with sqrt(eps); the reverse
    "nu_ramp_hysteresis": (ramp_pores(gap=-0.02, slope=0.05), ramp_pores(gap=0.02, slope=-0.05)),
    "ramp_branch_slope": (report(fig4=fig4(BELL, down=0.62 - 0.1 * X)),
                          report(fig4=fig4(BELL, down=0.58 + 0.1 * X))),
    "alpha_ramp_hysteresis": (report(fig6=fig6_ramp(0.0)), report(fig6=fig6_ramp(0.001))),
    "alpha_bell": (report(fig6=Table().add("b", "bell:alpha", X, 0.004 - 0.1 * (X - 0.15) ** 2,
                                          0.0002), fig4=fig4(BELL)),
                   report(fig6=Table().add("b", "bell:alpha", X, 0.001 + 0.01 * X, 0.0002),
                          fig4=fig4(BELL))),
    "final_alpha": (report(fig6=Table().param("final:alpha", 0.002, 0.0002)),
                    report(fig6=Table().param("final:alpha", -0.002, 0.0002))),
    "central_minus_lateral": (report(fig8=fig8(0.01, 0.02)), report(fig8=fig8(0.02, 0.01))),
    "lateral_first_tap": (report(fig8=fig8(0.01, 0.02, paper_first_tap=0.01)),
                          report(fig8=fig8(0.01, 0.02, paper_first_tap=-0.01))),
    "p0_initial_minus_final": (report(fig9=fig9()), report(fig9=fig9(diff=0.05))),
    "p0_final_minus_py": (report(fig9=fig9()), report(fig9=fig9(py_shift=0.05))),
    "xi_min": (report(fig10=fig10()), report(fig10=fig10(xi_min=0.20))),
    "pore_quadratic_fit": (report(fig10=fig10()),
                           report(fig10=fig10(last=np.where(XI > P.XI_T, XI - P.XI_T, 0.0)))),
    "pore_share_change": (
        report(fig10=fig10()),
        # small pores change as much as the tail, and the tail grows
        report(fig10=fig10(first=pore_curve(0.05), last=1.5 * pore_curve(0.1)))),
    "nu_tail_over_nu": (report(fig10=fig10()), report(fig10=fig10(tail_ratio=1.5))),
    "nu_change": (report(fig10=fig10()), report(fig10=fig10(nu=(0.10, 0.12)))),
}


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


def _outcomes(claim, data):
    return [str(claims.verdict(claim, m)) for m in claims.STATISTICS[claim.statistic](data, claim)]


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
    from tapmc.paper.fig3 import sigma_error_one_run

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
    out = tmp_path / "fig5.csv"
    fig5.refit_table(table.table).write(out)
    new = P.read_table(out)
    assert new[("params", "scaling:mu")]["mean"][0] == pytest.approx(0.7, abs=0.05)
    assert new[("params", "drawn:mu")]["n"][0] == 1
    assert ("params", "tw=10:A_inf") in new and ("params", "collapse:reduced_chi2") in new
    assert len(new[("b", "tw=10")]["x"]) == 151
    refitted = Table()
    refitted.table = new
    outcome = _outcomes(BY_ID["ageing-scaling"], report(fig5=refitted))
    # four realizations: too few for the test across realizations, whatever the refit says
    assert outcome[0].startswith("undecided (4 realizations: the test of the collapse across "
                                 "realizations needs at least 7")


def test_ageing_collapse_is_undecided_without_its_test():
    claim = BY_ID["ageing-scaling"]
    assert _outcomes(claim, report(fig5=fig5_collapse(0.3, realizations=4)))[0].startswith(
        "undecided (4 realizations")
    assert "draw Fig. 5 again" in _outcomes(
        claim, report(fig5=fig5_collapse(0.3, tested=False)))[0]
    m = claims.STATISTICS["ageing_collapse"](report(fig5=fig5_collapse(0.3)), claim)[0]
    assert m.text() == ("T^2 10 (3 dof) over 8 log bins of delays, 10 realizations; mu = 1 ± "
                        "0.1; reduced chi2 over the correlated delays 37.6 (decides nothing); "
                        "the test over the delays >= 100 alone (a linear axis of t, as the "
                        "paper draws it): p = 0.5")


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
    rows = []
    for seed, shift in zip(range(1, 5), (-0.002, -0.001, 0.001, 0.002)):
        for k, (frac, gain) in enumerate(((0.02, 0.002), (0.2, 0.010), (1.0, 0.001))):
            rows.append({"dmax_over_R": str(frac), "seed": str(seed), "N": "1024",
                         "eps": "0.0225", "taps": "100", "eta": "1e-07", "stop": "change",
                         "phi_c_0": "0.58", "sweeps_per_tap": "1800",
                         "phi_c_end": f"{0.58 + gain + shift + 0.0002 * ((seed + k) % 3 - 1):.8f}"})
    data = front_report(-0.005, -0.007)
    data.scans["dmax"] = [rows]
    claim = BY_ID["dmax-intermediate"]
    measures = claims.STATISTICS["dmax_intermediate"](data, claim)
    scan = [m for m in measures if m.label.startswith("d_max scan")]
    assert [m.value for m in scan] == pytest.approx([0.008, 0.009], abs=2e-4)
    assert "minus with R/50" in scan[0].label and "minus with R;" in scan[1].label
    assert all(str(claims.verdict(claim, m)).startswith("agrees") for m in measures)


def test_one_seed_zones_are_decided_by_their_paired_error_within_the_run():
    """The paper's protocol (one run per point): delta Phi_central - delta Phi_lateral of one
    seed gets the batch-means error of its own difference series; a clear gap decides, no gap
    stays undecided."""

    rng = np.random.default_rng(7)
    noise = 0.002 * rng.standard_normal(4000)
    lateral = 0.02 + noise                     # the zones move together (same taps) ...
    outcomes = {}
    for gap, name in ((-0.01, "clear"), (0.0, "none")):
        central = lateral + gap + 0.0005 * rng.standard_normal(4000)
        stats = P.window_stats([central - lateral], 1000)
        assert stats[2][0] == 1 and np.isfinite(stats[1][0])
        # ... so the paired error is far below the zones' own errors combined
        combined = math.hypot(P.window_stats([central], 1000)[1][0],
                              P.window_stats([lateral], 1000)[1][0])
        assert stats[1][0] < combined / 2
        tab = Table()
        for eps in (0.005, 0.1):
            tag = f"eps={P.fmt_eps(eps)}"
            tab.param(f"{tag}:final_central", 0.02 + gap, None, n=1, x=eps)
            tab.param(f"{tag}:final_lateral", 0.02, None, n=1, x=eps)
            tab.param(f"{tag}:final_central_minus_lateral", stats[0][0], stats[1][0], n=1, x=eps)
        outcomes[name] = _outcomes(BY_ID["central-smaller"], report(fig8=tab))
    assert outcomes["clear"] and all(o.startswith("agrees") for o in outcomes["clear"])
    assert outcomes["none"] and all(o.startswith("undecided") for o in outcomes["none"])


def test_bell_maximum_needs_more_than_three_steady_states():
    """Three points fit any parabola exactly: the vertex would restate the largest point. The
    paper-scale campaign's first runs (sqrt(eps) = 0.071, 0.15, 0.32, one seed each) must not
    place the maximum; five points of the same bell do, with one seed's batch-means errors."""
    x = np.array([0.0707, 0.15, 0.3162])
    three = Table().add("a", "steady", x, 0.60 - 2.0 * (x - 0.15) ** 2, 0.0002, n=1)
    (m,) = claims.bell_maximum(report(fig4=three), BY_ID["bell-maximum"])
    assert m.undecided and "three" in m.undecided
    x = np.array([0.05, 0.1, 0.15, 0.2, 0.25])
    five = Table().add("a", "steady", x, 0.60 - 2.0 * (x - 0.14) ** 2, 0.0002, n=1)
    (m,) = claims.bell_maximum(report(fig4=five), BY_ID["bell-maximum"])
    assert m.dof == 2 and abs(m.value - 0.14) < 1e-6
    assert str(claims.verdict(BY_ID["bell-maximum"], m)) == "agrees"


def test_one_run_spectra_are_decided_by_the_periodograms_own_errors():
    """One run per eps (the paper's protocol): the spectra carry PowerSpectrum.power_error; the
    spread rule resamples them as the Gamma means they are and decides with the normal
    quantile. White noise of an eps-dependent level at high f over a common 1/f^2 part at low
    f separates at high f (agrees); the same spectra without the separation stay undecided."""
    from tapmc.fluctuations import PowerSpectrum

    rng = np.random.default_rng(3)

    def one_run_fig3(levels):
        tab = Table()
        for eps, level in levels.items():
            walk = np.cumsum(rng.normal(size=4000)) * 0.01
            sp = PowerSpectrum(walk + level * rng.normal(size=4000)).compute()
            tab.add("a", f"eps={P.fmt_eps(eps)}", sp.frequency, sp.power, sp.power_error, n=1)
        return report(fig3=tab)

    claim = BY_ID["spectrum-high-frequency"]
    separated = one_run_fig3({0.01: 0.02, 0.04: 0.08, 0.09: 0.3})
    (m,) = claims.spectrum_eps_spread(separated, claim)
    assert m.dof == math.inf and "periodogram's own errors" in m.text()
    assert str(claims.verdict(claim, m)) == "agrees"
    same = one_run_fig3({0.01: 0.05, 0.04: 0.05, 0.09: 0.05})
    (m,) = claims.spectrum_eps_spread(same, claim)
    assert str(claims.verdict(claim, m)).startswith("undecided")


def _packings(phis, N=4096, L=32):
    return [{"seed": str(i + 1), "N": str(N), "L": str(L), "bc": "pbc", "phi_c": str(p)}
            for i, p in enumerate(phis)]


def test_one_initial_packing_is_decided_by_the_depositions_of_its_size():
    """The campaign's runs share one packing (no error): depositions of the same size measured
    at t = 0 decide the paper's single-packing value with a prediction interval; depositions
    of another size are not used."""
    paper = {"sizes": [[4096, 32.0]], "eta": [1e-7], "preset": True, "scale": "full",
             "fields": None, "initial_phi_c": [0.5829, None, 1]}
    claim = BY_ID["phi-initial"]
    spread = 0.5827 + 0.0008 * np.linspace(-1.6, 1.6, 20)
    data = claims.ReportData(paper, {}, questions={"initial_packing": _packings(spread)})
    (m,) = claims.initial_phi(data, claim)
    assert m.dof == 19 and "over 20 depositions" in m.text() and "58.29 %" in m.text()
    assert m.err > np.std(spread, ddof=1)           # one packing's spread is in the interval
    # 58.27 % vs 58.4 %: within one packing's spread
    assert str(claims.verdict(claim, m)) == "agrees"
    tight = claims.ReportData(
        paper, {}, questions={"initial_packing": _packings(0.5800 + 0.00005 * np.arange(20))})
    assert str(claims.verdict(claim, claims.initial_phi(tight, claim)[0])) == "disagrees"
    other = claims.ReportData(
        paper, {}, questions={"initial_packing": _packings(spread, N=1024, L=16)})
    (m,) = claims.initial_phi(other, claim)
    assert str(claims.verdict(claim, m)).startswith("undecided")


def _p0_rows(initial, tapped, sem, phi_i=0.582, phi_t=0.604, n=8):
    sigma = np.linspace(0.0, 2.0, 60)
    rows = [{"sigma": f"{x}", "initial": f"{a}", "initial_sem": f"{sem}", "initial_n": f"{n}",
             "tapped": f"{b}", "tapped_sem": f"{sem}", "tapped_n": f"{n}"}
            for x, a, b in zip(sigma, initial(sigma), tapped(sigma))]
    rows.append({"sigma": "phi", "initial": f"{phi_i}", "initial_sem": "0.0005",
                 "initial_n": f"{n}", "tapped": f"{phi_t}", "tapped_sem": "0.0005",
                 "tapped_n": f"{n}"})
    return rows


def test_one_realization_p0_curves_are_decided_over_configurations():
    """Fig. 9 of one run (no error bars) is compared over the p0-configs configurations: the
    same curve for both packings agrees with 'no significant difference', curves that follow
    Percus-Yevick at their own Phi differ by PY's change and disagree; the tapped curve on PY
    agrees with PY."""
    py = lambda phi: (lambda s: np.asarray(percus_yevick_p0(s, phi), float))  # noqa: E731
    one_run = Table()
    sigma = np.linspace(0.0, 2.0, 60)
    one_run.add("a", "final", sigma, py(0.604)(sigma), None, n=1)
    one_run.add("a", "initial", sigma, py(0.582)(sigma), None, n=1)
    one_run.add("a", "percus_yevick", sigma, py(0.604)(sigma), None, n=0)
    with_fig9_params(one_run)
    same = claims.ReportData(report().summary, {"fig9": one_run.data()},
                             questions={"p0_configs": _p0_rows(py(0.604), py(0.604), 1e-4)})
    (m,) = claims.p0_initial_minus_final(same, BY_ID["p0-insensitive"])
    assert "8 depositions and 8 configurations" in m.text()
    assert str(claims.verdict(BY_ID["p0-insensitive"], m)) == "agrees"
    own_phi = claims.ReportData(report().summary, {"fig9": one_run.data()},
                                questions={"p0_configs": _p0_rows(py(0.582), py(0.604), 1e-4)})
    (m,) = claims.p0_initial_minus_final(own_phi, BY_ID["p0-insensitive"])
    assert str(claims.verdict(BY_ID["p0-insensitive"], m)) == "disagrees"
    (m,) = claims.p0_final_minus_py(own_phi, BY_ID["p0-percus-yevick"])
    assert str(claims.verdict(BY_ID["p0-percus-yevick"], m)) == "agrees"
    without = claims.ReportData(report().summary, {"fig9": one_run.data()})
    (m,) = claims.p0_initial_minus_final(without, BY_ID["p0-insensitive"])
    assert m.undecided
    # two seeds (a campaign under way): the 8 configurations still decide; as many seeds
    # as configurations: the seeds do
    for seeds, configs in ((2, True), (8, False)):
        runs = Table()
        for name, phi in (("final", 0.604), ("initial", 0.604)):
            runs.add("a", name, sigma, py(phi)(sigma), 1e-3, n=seeds)
        runs.add("a", "percus_yevick", sigma, py(0.604)(sigma), None, n=0)
        with_fig9_params(runs)
        data = claims.ReportData(report().summary, {"fig9": runs.data()},
                                 questions={"p0_configs": _p0_rows(py(0.582), py(0.604), 1e-4)})
        (m,) = claims.p0_initial_minus_final(data, BY_ID["p0-insensitive"])
        assert ("configurations of the tapped packing" in m.text()) == configs


def test_one_pore_dump_is_decided_by_its_jackknife_error():
    """Fig. 10 of one run (the paper's protocol): values with the spatial jackknife's errors
    (n = 1) are decided with blocks - 1 degrees of freedom; without errors they stay
    undecided."""
    from tapmc.pores import JACKKNIFE_BLOCKS

    tab = Table()
    tab.add("params", "nu", [0, 4000], [0.1208, 0.0913], [0.0018, 0.0012], n=1)
    (m,) = claims.nu_change(report(fig10=with_fig10_rows(tab)), BY_ID["nu-decreases"])
    assert m.dof == JACKKNIFE_BLOCKS ** 2 - 1
    assert str(claims.verdict(BY_ID["nu-decreases"], m)) == "agrees"
    bare = Table().add("params", "nu", [0, 4000], [0.1208, 0.0913], None, n=1)
    (m,) = claims.nu_change(report(fig10=with_fig10_rows(bare)), BY_ID["nu-decreases"])
    assert str(claims.verdict(BY_ID["nu-decreases"], m)).startswith("undecided")


def test_lateral_first_tap_from_the_measured_paper_start():
    """Without paper-start runs in the campaign, the first taps of lateral-first-tap decide
    the jump of delta Phi_lateral at t = 1, per eps over its seeds."""
    claim = BY_ID["lateral-first-tap-jump"]

    def rows(jump):
        out = []
        for eps in (0.005, 0.1):
            for seed, noise in ((1, -0.0004), (2, 0.0), (3, 0.0004)):
                out += [{"eps": f"{eps}", "seed": f"{seed}", "t": "0", "lateral": "0.560"},
                        {"eps": f"{eps}", "seed": f"{seed}", "t": "1",
                         "lateral": f"{0.560 + jump + noise}"}]
        return out

    walls_only = fig8(0.01, 0.02)                 # the campaign's start, between walls
    jumps = claims.ReportData(report().summary, {"fig8": walls_only.data()},
                              questions={"lateral_first_tap": rows(0.01)})
    measures = claims.lateral_first_tap(jumps, claim)
    assert [m.label for m in measures] == ["eps = 0.005", "eps = 0.1"]
    assert all(str(claims.verdict(claim, m)) == "agrees" for m in measures)
    assert "3 seeds: tapmc-paper question lateral-first-tap" in measures[0].text()
    dips = claims.ReportData(report().summary, {"fig8": walls_only.data()},
                             questions={"lateral_first_tap": rows(-0.01)})
    assert all(str(claims.verdict(claim, m)) == "disagrees"
               for m in claims.lateral_first_tap(dips, claim))


def test_one_seed_phi_b_gain_has_the_batch_means_error_of_its_last_quarter():
    """Fig. 2 of one run per eps: the gain of Phi_b (last quarter minus t = 0) is decided by
    the run's own batch-means error; a run that does not compact stays undecided."""
    rng = np.random.default_rng(2)
    t = np.arange(4001.0)
    tab = Table()
    rising = 0.52 + 0.03 * np.log1p(t) / np.log(4001) + rng.normal(0, 0.002, t.size)
    noise = rng.normal(0, 0.002, t.size)
    flat = 0.52 + noise - noise[-1000:].mean()     # no gain over the last quarter
    flat[0] = 0.52
    tab.add("a", "eps=0.005", t, rising, None, n=1)
    tab.add("a", "eps=0.15", t, flat, None, n=1)
    m_rise, m_flat = claims.phi_b_gain(report(fig2=tab), BY_ID["phi-b-rises"])
    assert m_rise.dof == claims.WITHIN_RUN_DOF and "error within the run" in m_rise.text()
    assert str(claims.verdict(BY_ID["phi-b-rises"], m_rise)) == "agrees"
    assert str(claims.verdict(BY_ID["phi-b-rises"], m_flat)).startswith("undecided")


def test_one_seed_efficiency_decrease_from_the_runs_own_windows():
    """Fig. 2 of one run: a log-like compaction gains much more per tap in its first decade
    than over its last half (agrees); a run that compacts at a constant rate does not."""
    rng = np.random.default_rng(4)
    t = np.arange(4001.0)
    tab = Table()
    tab.add("a", "eps=0.005", t, 0.52 + 0.004 * np.log1p(t) + rng.normal(0, 0.0005, t.size),
            None, n=1)
    tab.add("a", "eps=0.15", t, 0.52 + 2e-6 * t + rng.normal(0, 0.0005, t.size), None, n=1)
    log_like, linear = claims.efficiency_decrease(report(fig2=tab),
                                                  BY_ID["efficiency-decreases"])
    assert "errors within the run" in log_like.text()
    assert str(claims.verdict(BY_ID["efficiency-decreases"], log_like)) == "agrees"
    assert not str(claims.verdict(BY_ID["efficiency-decreases"], linear)).startswith("agrees")


def test_a_scan_below_the_papers_N_is_undecided_by_scale():
    """A knob scan is its own measurement: at N = 1024 its row lacks the paper's size (the
    verdict is shown, not counted), at N = 4096 it is decided, whatever the campaign."""
    data = theta0_report(THETA0_PAPER)
    (row,) = claims.evaluate([BY_ID["theta0-optimum"]], data)
    assert row.missing_scale == ("size",)
    assert str(row.verdict) == "undecided (scale: needs the paper's size; at this scale it agrees)"
    for r in data.scans["theta0"][0]:
        r["N"] = "4096"
    (row,) = claims.evaluate([BY_ID["theta0-optimum"]], data)
    assert row.missing_scale == () and str(row.verdict) == "agrees"


def test_one_seed_log_time_slowing_from_the_runs_own_windows():
    """Fig. 2 of one run per eps: the late/early rates per unit ln t come from the means of
    each decade's halves; a small-eps curve that flattens in log time against a large-eps one
    that keeps its log rate agrees, the reverse disagrees."""
    rng = np.random.default_rng(8)
    t = np.arange(4001.0)
    lt = np.log1p(t)
    steady_log = 0.52 + 0.006 * lt + rng.normal(0, 0.0005, t.size)
    flattening = 0.52 + 0.02 * (1 - np.exp(-lt / 2.0)) + rng.normal(0, 0.0005, t.size)
    claim = BY_ID["slowing-small-eps"]
    for small, large, expected in ((flattening, steady_log, "agrees"),
                                   (steady_log, flattening, "disagrees")):
        tab = Table()
        tab.add("a", "eps=0.005", t, small, None, n=1)
        tab.add("a", "eps=0.15", t, large, None, n=1)
        (m,) = claims.log_time_slowing(report(fig2=tab), claim)
        assert m.dof == claims.WITHIN_RUN_DOF
        assert str(claims.verdict(claim, m)) == expected, m


def test_one_seed_fig2_fits_are_not_tested():
    """One run per eps: the fits' chi-square and profile intervals would rest on the taps'
    scatter, which is correlated; the claims that need them stay undecided and say why."""
    t = np.arange(200.0)
    tab = Table()
    for eps in (0.005, 0.15):
        tab.add("a", f"eps={P.fmt_eps(eps)}", t, 0.52 + 0.01 * np.log1p(t), None, n=1)
        tab.param(f"eps={P.fmt_eps(eps)}:reduced_chi2", 2.5e-7, None, n=1, x=eps)
    data = report(fig2=tab)
    (m,) = claims.eq3_triplet_pattern(data, BY_ID["eq3-triplet-range"])
    assert m.undecided and "correlation" in m.undecided
    fits = claims.eq3_fit_quality(data, BY_ID["eq3-compatible"])
    assert all(f.undecided and "rms residual 0.0005" in f.text() for f in fits)


def test_one_seed_b_dependence_is_not_tested():
    t = np.arange(200.0)
    tab = Table()
    for eps in (0.005, 0.05, 0.15):
        tab.add("a", f"eps={P.fmt_eps(eps)}", t, 0.52 + 0.01 * np.log1p(t), None, n=1)
    tab.add("B", "eq3:reduced_chi2", [0.0], [0.8], None, n=1)
    tab.add("B", "eq3:slope", [0.0], [3.0], [0.5], n=1)
    (m,) = claims.b_exponential(report(fig2=tab), BY_ID["b-exponential"])
    assert m.undecided == claims.ONE_RUN_FITS and "d ln B / d sqrt(eps) = 3" in m.text()


def early_rows(eps, rate, spread, seeds=range(1, 10), seed=11):
    """early_taps.csv rows: Phi_b(t) = 0.52 + rate t at t = 0..10 plus a realization's own
    offset and tap noise of ``spread``."""
    rng = np.random.default_rng(seed)
    rows = []
    for s in seeds:
        x = 0.52 + rate * np.arange(11.0) + rng.normal(0, spread, 11)
        x[0] = 0.52                                       # the same packing
        rows += [{"eps": str(eps), "seed": str(s), "t": str(k), "phi_b": f"{v:.8f}",
                  "phi_c": "0.55", "Z": "7.5"} for k, v in enumerate(x)]
    return rows


def test_one_seed_first_decade_rates_over_realizations_of_early_taps():
    """Fig. 2 of one run per eps whose first decade is within one tap's spread (the steady
    state's, 0.002): undecided from the run alone; with 9 realizations of the first decade
    (tapmc-paper question early-taps) whose taps scatter 1e-4, the early rate is known
    and the efficiency decrease agrees; realizations that do not compact early leave it
    undecided; fewer than EARLY_MIN_SEEDS are not used."""
    rng = np.random.default_rng(6)
    t = np.arange(4001.0)
    tab = Table()
    curve = 0.52 + 0.004 * np.log1p(t) * (t > 10) + rng.normal(0, 0.002, t.size) * (t > 10)
    curve[:11] = 0.52 + 6e-5 * t[:11]
    tab.add("a", "eps=0.005", t, curve, None, n=1)
    claim = BY_ID["efficiency-decreases"]
    (alone,) = claims.efficiency_decrease(report(fig2=tab), claim)
    assert str(claims.verdict(claim, alone)).startswith("undecided")

    def with_rows(rows):
        return claims.ReportData(report().summary, {"fig2": tab.data()},
                                 questions={"early_taps": rows})

    (m,) = claims.efficiency_decrease(with_rows(early_rows(0.005, 6e-5, 1e-4)), claim)
    assert "first decade over 9 realizations from the same packing" in m.text()
    assert m.dof == 8 and str(claims.verdict(claim, m)) == "agrees"
    (flat,) = claims.efficiency_decrease(with_rows(early_rows(0.005, 0.0, 1e-4)), claim)
    assert not str(claims.verdict(claim, flat)).startswith("agrees")
    (few,) = claims.efficiency_decrease(
        with_rows(early_rows(0.005, 6e-5, 1e-4, seeds=range(1, claims.EARLY_MIN_SEEDS))), claim)
    assert "one seed" in few.text()
    (other,) = claims.efficiency_decrease(with_rows(early_rows(0.05, 6e-5, 1e-4)), claim)
    assert "one seed" in other.text()                     # rows of another eps are not used


def test_one_seed_late_gain_share_from_the_runs_own_windows():
    """Fig. 2 of one run per eps: the share of the gain over the last decade, from the means
    of [0.9 T, T] and [0.09 T, 0.11 T] with batch-means errors; a curve that keeps rising on
    ln t at the smallest eps against one that saturates at the largest agrees, the reverse
    disagrees, and curves of the same shape are undecided."""
    rng = np.random.default_rng(9)
    t = np.arange(4001.0)
    lt = np.log1p(t)
    rising = 0.52 + 0.006 * lt + rng.normal(0, 0.0005, t.size)
    saturating = 0.52 + 0.03 * (1 - np.exp(-lt / 1.5)) + rng.normal(0, 0.0005, t.size)
    rising[0] = saturating[0] = 0.52
    claim = BY_ID["unreached-small-eps"]
    for small, large, expected in ((rising, saturating, "agrees"),
                                   (saturating, rising, "disagrees"),
                                   (rising, rising + rng.normal(0, 0.0005, t.size), "undecided")):
        tab = Table()
        tab.add("a", "eps=0.005", t, small, None, n=1)
        tab.add("a", "eps=0.15", t, large, None, n=1)
        (m,) = claims.late_gain_share(report(fig2=tab), claim)
        assert m.dof == claims.SHORT_WINDOW_BATCHES - 1
        assert str(claims.verdict(claim, m)).startswith(expected), m


def test_fig2_laws_across_realizations_of_early_taps():
    """Fig. 2 of one run per eps decides nothing on eqs. 3 and 4 (the taps are correlated);
    with 9 realizations of 400 taps from the same packing (early_taps.csv) the laws are tested
    across them (tapmc.laws.RealizationLawTest): realizations that follow the laws agree,
    realizations whose Phi_b grows as a power of t disagree with eq. 3, and realizations that
    are too few or too short leave the figure's one-run verdict."""
    from tapmc.laws import InverseLogLaw, ZLaw

    t = np.arange(4001.0)
    tab = Table()
    for eps in (0.005, 0.15):
        tab.add("a", f"eps={P.fmt_eps(eps)}", t, 0.52 + 0.01 * np.log1p(t), None, n=1)
        tab.add("c", f"eps={P.fmt_eps(eps)}", t, 7.7 - 0.1 * np.log1p(t), None, n=1)
        tab.add("params", f"eps={P.fmt_eps(eps)}:reduced_chi2", [0.0], [1e-6], None, n=1)
        tab.add("params", f"eps={P.fmt_eps(eps)}:Z:reduced_chi2", [0.0], [1e-4], None, n=1)

    def law_rows(eps, seed):
        return realization_rows(eps, lambda t: InverseLogLaw.function(t, 0.6, 0.08, 0.3, 5.0),
                                lambda t: ZLaw.function(t, 7.1, 7.6, 0.4, 3.0), seed=seed)

    def data(rows):
        return claims.ReportData(report().summary, {"fig2": tab.data()},
                                 questions={"early_taps": rows})

    eq3, eq4 = BY_ID["eq3-compatible"], BY_ID["eq4-compatible"]
    both = data(law_rows(0.005, 1) + law_rows(0.15, 2))
    for fits, claim in ((claims.eq3_fit_quality(both, eq3), eq3),
                        (claims.eq4_fit_quality(both, eq4), eq4)):
        assert [m.label for m in fits] == [
            f"eps = {e}, {part}" for e in (0.005, 0.15)
            for part in ("every tap", "after the first taps' loosening")]
        for m in fits:          # a rising Phi_b is never looser than at t = 0: both from tap 1
            assert "over taps 1-400 in 8 log bins, 9 realizations" in m.text(), m
            assert m.dof == 4 and str(claims.verdict(claim, m)).startswith("agrees (p = "), m
    power = realization_rows(0.005, lambda t: 0.52 + 0.01 * t ** 0.3,
                             lambda t: ZLaw.function(t, 7.1, 7.6, 0.4, 3.0))
    (wrong, _, one_run) = claims.eq3_fit_quality(data(power), eq3)
    assert str(claims.verdict(eq3, wrong)).startswith("disagrees"), wrong
    assert one_run.undecided and "rms residual" in one_run.text()   # eps = 0.15: no rows
    # the first three taps loosen the packing below its t = 0 value, then the law holds
    loose = realization_rows(0.005, lambda t: np.where((t >= 1) & (t <= 3), 0.51,
                                                       InverseLogLaw.function(t, 0.6, 0.08,
                                                                              0.3, 5.0)),
                             lambda t: ZLaw.function(t, 7.1, 7.6, 0.4, 3.0))
    assert claims.loosening_end(data(loose), 0.005) == 4.0
    (every, after, _) = claims.eq3_fit_quality(data(loose), eq3)
    assert str(claims.verdict(eq3, every)).startswith("disagrees"), every
    assert "over taps 4-400" in after.text()
    assert str(claims.verdict(eq3, after)).startswith("agrees")
    still = realization_rows(0.005, lambda t: np.where(t >= 1, 0.51, 0.52),
                             lambda t: ZLaw.function(t, 7.1, 7.6, 0.4, 3.0))
    assert claims.loosening_end(data(still), 0.005) is None
    (_, never, _) = claims.eq3_fit_quality(data(still), eq3)
    assert "still looser than at t = 0" in never.undecided
    few = law_rows(0.005, 1)[: (claims.REALIZATION_MIN_SEEDS - 1) * 401]
    short = [r for r in law_rows(0.005, 1) if int(r["t"]) < claims.REALIZATION_MIN_TAPS]
    for rows in (few, short):
        (m, _) = claims.eq3_fit_quality(data(rows), eq3)
        assert m.undecided and "one realization" in m.undecided, m
    # a mean of seeds with per-tap errors gives a chi-square, shown, that decides nothing
    (seeds,) = claims.eq3_fit_quality(report(fig2=fig2({0.05: RISING})), eq3)
    assert seeds.undecided.startswith("5 seeds: a chi-square over correlated taps")
    assert seeds.text().startswith("reduced chi2 1 ")


def surrogate_rows(states, law="eq3", b_values=None):
    """fit_surrogates.csv rows of one campaign run per eps: ``states`` eps -> (undetermined
    parameters, range-dependent parameters); B = ``b_values[eps]`` with a 10 % band."""
    names = {"eq3": ("X_inf", "dX_inf", "B", "tau"), "eq4": ("Z_inf", "Z_0", "B", "tau")}[law]
    rows = []
    for eps, (undetermined, dependent) in states.items():
        for k in names:
            value = (b_values or {}).get(eps, 0.5) if k == "B" else 1.0
            rows.append({"source": f"const_fbc_eps{eps:g}_s1", "eps": f"{eps}", "law": law,
                         "taps": "4000", "parameter": k, "value": f"{value}",
                         "low": f"{value * 0.9}", "high": f"{value * 1.1}",
                         "half_width": "0.1", "log_scale": str(int(k in ("B", "tau"))),
                         "determined": "0" if k in undetermined else "1",
                         "range_p": "0.001" if k in dependent else "0.4", "fits": "200"})
    # the realizations' rows are another source: never read as a campaign run
    rows.append(dict(rows[0], source="realizations", eps="0.005", determined="1"))
    return rows


def surrogate_report(rows):
    return claims.ReportData(report().summary, {}, questions={"fit_surrogates": rows})


def test_one_runs_surrogates_decide_only_what_they_can():
    """Surrogate bands are too narrow (test_slow_surrogate_fits.py): a triplet that is not
    unique at any eps disagrees with the paper's contrast; one that looks unique somewhere
    stays undecided; B's dependence is tested only where B is determined, and agreement
    decides while a rejection does not."""
    claim = BY_ID["eq3-triplet-range"]
    none_unique = surrogate_rows({0.005: (["B", "tau"], []), 0.05: (["B"], []),
                                  0.15: ([], ["tau"])})
    (m,) = claims.eq3_triplet_pattern(surrogate_report(none_unique), claim)
    assert str(claims.verdict(claim, m)) == "disagrees", m
    assert "eps = 0.15: tau range dependent" in m.text()
    paper_like = surrogate_rows({0.005: (["B", "tau"], []), 0.05: ([], []), 0.15: ([], [])})
    (m,) = claims.eq3_triplet_pattern(surrogate_report(paper_like), claim)
    assert m.undecided == claims.SURROGATES_UNIQUE

    claim = BY_ID["b-exponential"]
    eps = (0.005, 0.05, 0.15)
    undetermined = surrogate_rows({0.005: (["B"], []), 0.05: ([], []), 0.15: ([], [])})
    (m,) = claims.b_exponential(surrogate_report(undetermined), claim)
    assert m.undecided and "B undetermined at eps = 0.005" in m.undecided
    exponential = surrogate_rows({e: ([], []) for e in eps},
                                 b_values={e: 0.2 * np.exp(3 * np.sqrt(e)) for e in eps})
    (m,) = claims.b_exponential(surrogate_report(exponential), claim)
    assert str(claims.verdict(claim, m)).startswith("agrees"), m
    bent = surrogate_rows({e: ([], []) for e in eps},
                          b_values={0.005: 0.2, 0.05: 20.0, 0.15: 0.2})
    (m,) = claims.b_exponential(surrogate_report(bent), claim)
    assert m.undecided and "too narrow to reject" in m.undecided
    both = claims.ReportData(report().summary, {}, questions={
        "fit_surrogates": undetermined + surrogate_rows({e: (["B"], []) for e in eps}, "eq4")})
    assert [x.label for x in claims.b_exponential(both, claim)] == ["B of eq. 3", "B of eq. 4"]


def seed_fit_rows(states, bc="fbc", law="eq3", realizations=3, group=None):
    """seed_fits.csv rows of one group of realizations per eps: ``states`` eps -> (undetermined
    parameters, parameters the realizations cannot tell, range-dependent parameters)."""
    names = {"eq3": ("X_inf", "dX_inf", "B", "tau"), "eq4": ("Z_inf", "Z_0", "B", "tau")}[law]
    rows = []
    for eps, (undetermined, unsure, dependent) in states.items():
        for k in names:
            rows.append({"group": group or f"const_{bc}_eps{eps:g}", "bc": bc, "eps": f"{eps}",
                         "law": law, "taps": "4000", "realizations": str(realizations),
                         "parameter": k, "values": "1;2;3", "mean": "0.5", "spread": "0.3",
                         "spread_low": "0.15", "spread_high": "1.9", "limit": "0.69",
                         "log_scale": str(int(k in ("B", "tau"))),
                         "determined": "0" if k in undetermined else "" if k in unsure else "1",
                         "range_shift": "0.1", "range_bound": "0.5",
                         "range_p": "0.001" if k in dependent else "0.4"})
    return rows


def test_realizations_of_whole_runs_decide_the_triplet_both_ways():
    """Where the campaign has realizations of a whole run (seed_fits.csv), their spread
    replaces the run's surrogates in both directions; where they cannot tell, a run's "not
    unique" still decides and its "unique" still does not. The P.B.C. groups give a row of
    their own."""
    claim = BY_ID["eq3-triplet-range"]
    runs = surrogate_rows({0.005: (["B", "tau"], []), 0.02: ([], []), 0.15: (["B"], [])})

    def rows_of(seed_rows):
        data = claims.ReportData(report().summary, {}, questions={
            "fit_surrogates": runs, "seed_fits": seed_rows})
        return claims.eq3_triplet_pattern(data, claim)

    # the run's surrogates alone: "unique" at 0.02 is only an upper bound
    (m,) = rows_of([])
    assert m.undecided == claims.SURROGATES_UNIQUE
    # other seeds' surrogates are shown on the page, not read: the first seed is the run of
    # the paper's protocol, whichever order the rows come in
    other = [dict(r, source=r["source"].replace("_s1", "_s12"), determined="0")
             for r in runs if r["eps"] == "0.02"]
    for rows in (runs + other, other + runs):
        data = claims.ReportData(report().summary, {}, questions={"fit_surrogates": rows})
        picked = claims.surrogate_fits(data, "eq3")[0.02]
        assert {r["source"] for r in picked.values()} == {"const_fbc_eps0.02_s1"}
    # three realizations at 0.02 find B undetermined: no eps is unique
    (m,) = rows_of(seed_fit_rows({0.02: (["B"], [], [])}))
    assert str(claims.verdict(claim, m)) == "disagrees", m
    assert "eps = 0.02: 3 realizations: B undetermined (sd of ln B 0.3" in m.text()
    assert "(the run's surrogates: unique within the surrogates)" in m.text()
    # ... or range dependent: the same
    (m,) = rows_of(seed_fit_rows({0.02: ([], [], ["tau"])}))
    assert str(claims.verdict(claim, m)) == "disagrees" and "tau range dependent" in m.text()
    # they fix it: the paper's contrast holds
    (m,) = rows_of(seed_fit_rows({0.02: ([], [], [])}))
    assert str(claims.verdict(claim, m)) == "agrees", m
    # they cannot tell: undecided, and says where
    (m,) = rows_of(seed_fit_rows({0.02: ([], ["B", "tau"], [])}))
    assert m.undecided.startswith("the realizations cannot tell whether the triplet is fixed "
                                  "at eps = 0.02"), m
    # realizations that cannot tell leave a run's "not unique" standing (0.15), and
    # realizations that fix the smallest eps contradict the paper
    (m,) = rows_of(seed_fit_rows({0.02: (["B"], [], []), 0.15: ([], ["B"], [])}))
    assert str(claims.verdict(claim, m)) == "disagrees", m
    (m,) = rows_of(seed_fit_rows({0.005: ([], [], [])}))
    assert str(claims.verdict(claim, m)) == "disagrees", m
    # P.B.C. groups at two eps or more: a second row, decided by them alone
    pbc = seed_fit_rows({0.0025: (["B"], [], []), 0.0225: ([], [], [])}, bc="pbc")
    fbc_row, pbc_row = rows_of(seed_fit_rows({0.02: ([], ["B"], [])}) + pbc)
    assert fbc_row.label == "F.B.C., Fig. 2's runs" and fbc_row.undecided
    assert pbc_row.label == "P.B.C. realizations"
    assert str(claims.verdict(claim, pbc_row)) == "agrees", pbc_row
    pbc = seed_fit_rows({0.0025: (["B"], [], []), 0.0225: ([], ["tau"], [])}, bc="pbc")
    _, pbc_row = rows_of(pbc)
    assert pbc_row.undecided.endswith("at eps = 0.0225: their spread's 95 % interval "
                                      "straddles the limit")
    # two groups at one eps (ten ageing streams, three constant-eps seeds): the larger decides
    both = seed_fit_rows({0.01: (["B"], [], [])}, bc="pbc", realizations=10,
                         group="ageing_pbc_eps0.01") + \
        seed_fit_rows({0.01: ([], [], [])}, bc="pbc")
    for order in (both, both[::-1]):
        data = claims.ReportData(report().summary, {}, questions={"seed_fits": order})
        picked = claims.realization_fits(data, "eq3", "pbc")[0.01]
        assert {r["group"] for r in picked.values()} == {"ageing_pbc_eps0.01"}
        assert len(picked) == 4


def _ramp_levels_rows(shifts):
    """ramp_levels.csv rows: (level, branch, shift of <Phi^c> from 1000 to 4000 taps), each
    with batch-means errors of 1e-4."""
    return [{"level": str(k), "branch": str(b), "sqrt_eps": "0.1", "taps": "1000",
             "taps_long": "4000", "phi_c": "0.60", "phi_c_sem": "1e-4",
             "phi_c_long": f"{0.60 + d:.6f}", "phi_c_long_sem": "1e-4"}
            for k, b, d in shifts]


def test_ramp_reduction_decides_only_the_verdicts_it_cannot_change():
    """The campaign's ramp has 1000 taps per level: its claims are undecided for the scale,
    unless ramp-levels measured the shift to 4000 taps on every branch the measure reads (two
    levels each) and the verdict stays the same anywhere within it."""
    by_id = {c.id: c for c in REGISTER}
    summary = {"ramp_taps_per_level": [1000]}
    fig = fig4(BELL, up1=BELL, down=BELL + 0.03, up2=BELL + 0.03)
    small = _ramp_levels_rows([(1, 0, 0.001), (5, 0, 0.0005), (15, 1, 0.0002), (20, 1, 0.0)])

    def outcome(claim_id, rows):
        data = claims.ReportData(dict(report().summary, **summary),
                                 {"fig4": with_fig4_rows(fig).data()},
                                 questions={"ramp_levels": rows})
        (row,) = claims.evaluate([by_id[claim_id]], data)
        return str(row.verdict)

    # down - up1 = 0.03 against shifts of at most 0.001 + 0.0002 (+ t err): decided
    text = outcome("reversible-above", small)
    assert text.startswith("agrees (at 1000 taps per level") and "up1: levels 1, 5" in text
    assert outcome("reversible-falls", small).startswith("agrees (at 1000 taps per level")
    # a shift as large as the gap could undo it: undecided, and says by how much
    large = _ramp_levels_rows([(1, 0, 0.04), (5, 0, 0.0), (15, 1, 0.0), (20, 1, 0.0)])
    text = outcome("reversible-above", large)
    assert text.startswith("undecided (scale: needs the paper's ramp_taps; at this scale it "
                           "agrees; the paper's 4000 could move it by -0.04")
    # down - up1: up1's shift (+0.04) lowers the difference; down's (0, 0.0002) barely raises it
    assert text.endswith("to 0.000592)")
    # one measured level of a branch bounds nothing; up2 was not measured at all
    assert outcome("reversible-above", small[1:]).startswith("undecided (scale")
    assert outcome("reversible-retraced", small).startswith("undecided (scale")
    # "nearly the same" disagrees at this scale at both ends of the interval the shift
    # allows (0.006 - 0.012 and 0.006, beyond a tenth of the gap, 0.0024) but agrees at zero,
    # inside it: not decided
    wide = _ramp_levels_rows([(1, 0, -0.012), (5, 0, 0.0), (15, 1, 0.0), (20, 1, 0.0)])
    near = claims.ReportData(dict(report().summary, **summary),
                             {"fig4": with_fig4_rows(fig4(BELL, up1=BELL + 0.006,
                                                         down=BELL + 0.03)).data()},
                             questions={"ramp_levels": wide})
    (row,) = claims.evaluate([by_id["ramp-up-near-squares"]], near)
    assert str(row.verdict).startswith("undecided (scale: needs the paper's ramp_taps; at this "
                                  "scale it disagrees")
    # the same shift upwards only moves the first increase farther from the squares: decided
    away = _ramp_levels_rows([(1, 0, 0.012), (5, 0, 0.0), (15, 1, 0.0), (20, 1, 0.0)])
    (row,) = claims.evaluate([by_id["ramp-up-near-squares"]],
                             claims.ReportData(near.summary, near.figures,
                                               questions={"ramp_levels": away}))
    assert str(row.verdict).startswith("disagrees (at 1000 taps per level")
    # the alpha claim has no bound in <Phi^c>: it stays undecided at this scale
    assert claims.ramp_reduction_shift(by_id["gradient-no-hysteresis"], near,
                                       {"ramp": claims.ramp_reduction_bounds(near)}) is None


def test_near_rule_agrees_within_a_tenth_of_the_effect_and_says_when_it_cannot_tell():
    """'Nearly the same': a real but small difference agrees (the strict zero rule would call
    it a disagreement), one beyond a tenth of the effect disagrees, and a band that straddles
    the tenth, or a measure without an effect, is undecided."""
    claim = {c.id: c for c in REGISTER}["reversible-retraced"]
    assert claim.rule == "near"
    tenth = claims.NEAR_FRACTION * 0.02
    band = claims.t_quantile(9)
    small = claims.Measure(0.0002, 0.0001 / band, 9, effect=0.02)   # |v| + band = 3e-4 < 2e-3
    assert str(claims.verdict(claim, small)) == "agrees"
    assert str(claims.verdict(dataclasses.replace(claim, rule="zero"), small)) == "disagrees"
    assert str(claims.verdict(claim, claims.Measure(0.005, 0.001 / band, 9, effect=0.02))) == \
        "disagrees"
    straddle = claims.Measure(tenth, 0.0005 / band, 9, effect=0.02)
    assert str(claims.verdict(claim, straddle)).startswith("undecided (|value| +- t sem")
    assert str(claims.verdict(claim, claims.Measure(0.0, 1e-5, 9))).startswith(
        "undecided (no effect")


def _scatter_rows(quantity, spread, error, groups=2, runs=4, prefix="g"):
    """realization_scatter.csv rows of ``quantity`` whose realizations spread ``spread``
    against their own errors ``error`` (exactly: means at +-spread * sqrt((n-1)/n)); groups
    named ``<prefix><g>``."""
    offsets = np.array([1.0, -1.0] * (runs // 2)) * spread * np.sqrt((runs - 1) / runs)
    return [{"group": f"{prefix}{g}", "column": quantity, "mean": str(0.6 + o),
             "sem": str(error), "sem_dof": "19"} for g in range(groups) for o in offsets]


def test_fbc_runs_share_the_pbc_factor_unless_their_own_groups_reject_it():
    """F.B.C. runs without a group of their own borrow the P.B.C. factor; F.B.C. groups that
    spread alike join the P.B.C. groups in one pooled factor for both; F.B.C. groups that
    spread far more (an F test of the two k^2 below CALIBRATION_ALPHA) give the F.B.C. runs
    their own factor and leave the P.B.C. runs theirs."""
    pbc = _scatter_rows("phi_c", 0.004, 0.001, groups=3, prefix="const_pbc_eps0.0")
    borrowed = claims.ReportData({}, {}, questions={"realization_scatter": pbc})
    assert borrowed.run_error("phi_c", "fbc") == borrowed.run_error("phi_c") == (
        pytest.approx(4.0), 9)
    assert "F.B.C. runs, which have no group, take the same" in borrowed.run_error_note()
    alike = pbc + _scatter_rows("phi_c", 0.004, 0.001, groups=1, prefix="const_fbc_eps0.02_")
    assert claims.realization_sharing(alike)["phi_c"] > 0.5      # equal k: F(3, 9) at 1
    data = claims.ReportData({}, {}, questions={"realization_scatter": alike})
    assert data.run_error("phi_c", "fbc") == data.run_error("phi_c") == (pytest.approx(4.0), 12)
    assert "both boundary conditions, which share one factor" in data.run_error_note()
    apart = pbc + _scatter_rows("phi_c", 0.04, 0.001, groups=1, prefix="const_fbc_eps0.02_")
    assert claims.realization_sharing(apart)["phi_c"] < 1e-4
    data = claims.ReportData({}, {}, questions={"realization_scatter": apart})
    assert data.run_error("phi_c") == (pytest.approx(4.0), 9)
    assert data.run_error("phi_c", "fbc") == (pytest.approx(40.0), 3)
    assert "<Phi^c> x 4.0 (P.B.C.), x 40.0 (F.B.C.)" in data.run_error_note()
    # the profile's zones (F.B.C., no group measures them) take the F.B.C. runs' largest
    assert data.run_error(None, "fbc")[0] == pytest.approx(40.0)
    with pytest.raises(ValueError, match="bc = 'wall'"):
        claims.realization_calibrations(apart, "wall")


def test_one_run_errors_take_the_realizations_factor():
    """A calibration that rejects the one-run errors scales them where a row rests on one
    run (Fig. 3's one-run sigmas refitted, Fig. 2's gain), and only there; one that does not
    reject them changes nothing."""
    rows = _scatter_rows("Z:sigma", 0.004, 0.001) + _scatter_rows("phi_b", 0.0021, 0.002)
    factors = claims.realization_factors(rows)
    assert factors["Z:sigma"][0] == pytest.approx(4.0) and "phi_b" not in factors
    line = Table()
    sq = np.array([0.05, 0.1, 0.15, 0.2, 0.3])
    line.add("b", "sigma_Z", sq, 0.002 + 0.05 * sq, [0.001, 0.0003, 0.001, 0.001, 0.001],
             n=np.array([1, 3, 1, 1, 1]))
    line.param("intercept", 0.002, 0.0005, n=5)
    claim = next(c for c in REGISTER if c.statistic == "sigma_intercept"
                 and c.params.get("about") != "line")
    own = claims.sigma_intercept(report(fig3=line), claim)[0]
    data = report(fig3=line)
    data.questions["realization_scatter"] = rows
    scaled = claims.sigma_intercept(data, claim)[0]
    assert own.err == 0.0005 and scaled.value == pytest.approx(0.002)
    # the one seed-averaged point keeps its error: the intercept's error grows by less than 4
    assert 1.5 * own.err < scaled.err < 4 * own.err
    assert "error within the run x 4.0" in scaled.text()
    assert data.run_error("phi_b") == (1.0, None)


def test_fig8_zones_take_their_own_measured_factor_or_else_the_largest():
    """Fig. 8's final zone means and their paired difference (one run each, F.B.C.) take the
    factor realization-scatter measured for that zone; without zone rows (a CSV from before
    they were measured) the largest factor of the window means, as the page says."""
    tab = Table()
    tag = "eps=0.1"
    tab.param(f"{tag}:final_central", 0.01, 0.001, n=1, x=0.1)
    tab.param(f"{tag}:final_lateral", 0.02, 0.001, n=1, x=0.1)
    tab.param(f"{tag}:final_central_minus_lateral", -0.01, 0.001, n=1, x=0.1)
    means = _scatter_rows("phi_b", 0.008, 0.001) + _scatter_rows("phi_c", 0.004, 0.001)
    zones = (_scatter_rows("zone:central", 0.003, 0.001)
             + _scatter_rows("zone:lateral", 0.005, 0.001)
             + _scatter_rows("zone:central_minus_lateral", 0.002, 0.001))

    def scaled(rows):
        data = report(fig8=tab)
        data.questions["realization_scatter"] = rows
        fig = data.figure("fig8")
        errors = [fig.param(f"{tag}:final_{z}")[1] for z in
                  ("central", "lateral", "central_minus_lateral")]
        (m,) = claims.central_minus_lateral(data, BY_ID["central-smaller"])
        return errors, m, data.run_error_note()

    errors, m, note = scaled(means + zones)
    assert errors == pytest.approx([0.003, 0.005, 0.002])
    assert m.err == pytest.approx(0.002) and "error within the run x 2.0" in m.text()
    assert "central minus lateral zone x 2.0" in note and "zones the largest" not in note
    errors, m, note = scaled(means)
    assert errors == pytest.approx([0.008] * 3) and "x 8.0" in m.text()
    assert "a profile's zones the largest" in note


def test_a_packing_jackknife_takes_its_factor_only_where_realizations_reject_it():
    """nu of Fig. 10 and alpha of Fig. 6 from one packing (n = 1) carry the spatial
    jackknife; packing_scatter.csv rows that reject it (k = 3) scale those rows and only
    those, rows that find it conservative (k < 1) leave every error as it is."""
    tab10 = Table()
    tab10.add("params", "nu", [0, 4000], [0.12, 0.09], [0.001, 0.001], n=np.array([1, 1]))
    tab6 = Table().param("final:alpha", 0.003, 0.0005, n=1)
    tab6.add("b", "bell:alpha", [0.1, 0.2], [0.002, 0.003], [0.0004, 0.0004],
             n=np.array([1, 3]))
    for spread, factor in ((0.003, 3.0), (0.0003, 1.0)):
        rows = [dict(r, group=r["group"].replace("g", "const_fbc_eps0.0")) for r in
                _scatter_rows("packing:nu", spread, 0.001)
                + _scatter_rows("packing:alpha", spread / 2, 0.0005)]
        data = report(fig10=tab10, fig6=tab6)
        data.questions["packing_scatter"] = rows
        nu = data.figure("fig10").get("params", "nu")[2]
        np.testing.assert_allclose(nu, [0.001 * factor] * 2)
        fig6 = data.figure("fig6")
        assert fig6.param("final:alpha")[1] == pytest.approx(0.0005 * factor)
        # bell:alpha of P.B.C. runs borrows the F.B.C. groups' factor; the 3-seed point keeps
        # its error over seeds
        np.testing.assert_allclose(fig6.get("b", "bell:alpha")[2], [0.0004 * factor, 0.0004])


def test_low_ramp_frozen_is_decided_by_its_own_levels():
    """The ramp below (sqrt eps)* changes on the way down by 0.01 (beyond t sem): at 1000 taps
    per level that stays undecided until ramp-levels measured that ramp's turning level and
    two levels of its decrease; shifts that small leave 'disagrees', the other ramp's levels
    do not count, and a turning level that moves as much as the change leaves it undecided."""
    claim = next(c for c in REGISTER if c.statistic == "low_ramp_frozen")
    fig = (fig4(BELL).param("low:down_change", 0.01, 0.0005, n=1)
           .param("ramp:down_change", 0.02, 0.0005, n=1).param("low:top_sqrt_eps", 0.125, n=1))

    def outcome(rows):
        data = claims.ReportData(dict(report().summary, ramp_taps_per_level=[1000]),
                                 {"fig4": with_fig4_rows(fig).data()},
                                 questions={"ramp_levels": rows})
        (row,) = claims.evaluate([claim], data)
        return str(row.verdict)

    def low(shifts, ramp="ramplow_pbc_s1"):
        rows = _ramp_levels_rows(shifts)
        for r, (k, _, _) in zip(rows, shifts):
            r.update(ramp=ramp, sqrt_eps="0.125" if k == 4 else "0.05")
        return rows

    assert outcome([]).startswith("undecided (scale: needs the paper's ramp_taps; at this "
                                  "scale it disagrees")
    small = low([(4, 0, 0.001), (5, 1, 0.0005), (8, 1, 0.0)])
    text = outcome(small)
    assert text.startswith("disagrees (at 1000 taps per level") and \
        "low ramp, down: levels 5, 8; top: level 4" in text
    assert outcome(low([(4, 0, 0.001), (5, 1, 0.0005), (8, 1, 0.0)], "ramp_pbc_s1")) \
        .startswith("undecided (scale")
    assert outcome(low([(4, 0, 0.009), (5, 1, 0.0005), (8, 1, 0.0)])).startswith(
        "undecided (scale: needs the paper's ramp_taps; at this scale it disagrees; the "
        "paper's 4000 could move it by -0.0")


def test_a_mean_of_two_seeds_is_judged_with_the_groups_of_realizations():
    """Two seeds of a statistic, each with its batch-means error: their group joins the
    campaign's groups (k = 4 on 6 dof) in one ErrorCalibration, so the error is the pooled
    k' times sqrt(e1^2 + e2^2) / 2 on 7 dof, worked out by hand; seeds that spread far more
    than the groups allow (F test), or a campaign without groups, leave the seeds alone."""
    rows = _scatter_rows("phi_c", 0.004, 0.001)                  # 2 groups x 4 runs: k = 4
    data = claims.ReportData({}, {}, questions={"realization_scatter": rows})
    values, errors = [0.0054, 0.0047], [0.0002, 0.0001]
    ratio2 = (np.std(values, ddof=1) / np.sqrt(np.mean(np.square(errors)))) ** 2
    k = np.sqrt((6 * 16.0 + 1 * ratio2) / 7)
    err, dof, factor = data.seed_mean_error("phi_c", values, errors)
    assert factor == pytest.approx(k) and dof == 7
    assert err == pytest.approx(k * np.hypot(*errors) / 2)
    assert data.seed_mean_error("phi_c", [0.005, 0.205], errors) is None     # F test
    assert data.seed_mean_error("phi_b", values, errors) is None             # no groups
    assert data.seed_mean_error("phi_c", values[:1], errors[:1]) is None
    assert data.seed_mean_error("phi_c", values, [0.0002, 0.0]) is None
    # groups that find the errors conservative do not shrink them: k' at least 1
    calm = claims.ReportData({}, {}, questions={
        "realization_scatter": _scatter_rows("phi_c", 0.0002, 0.001)})
    assert calm.seed_mean_error("phi_c", [0.0050, 0.005045], errors)[2] == 1.0


def test_low_ramp_frozen_with_two_seeds_takes_the_groups_dof():
    """The low ramp's change on the way down, 0.005 over two seeds: by the seeds alone (t
    with 1 dof, 12.7) 0.005 +- 0.0004 is swallowed by a band of 0.0051 and the row agrees;
    judged with the groups of realizations (k = 2 on 6 + 1 dof) it is a change: the row
    disagrees, and says how its error was obtained."""
    claim = next(c for c in REGISTER if c.statistic == "low_ramp_frozen")
    tab = (fig4(BELL).param("low:down_change", 0.005, 0.0004, n=2, x=0.125)
           .param("ramp:down_change", 0.018, 0.0002, n=1).param("low:top_sqrt_eps", 0.125, n=2))
    alone = report(fig4=tab)
    (m,) = claims.low_ramp_frozen(alone, claim)
    assert m.dof == 1 and str(claims.verdict(claim, m)) == "agrees"
    tab.add("params", "low:down_change:seeds", [0.125, 0.125], [0.0054, 0.0046],
            [0.0002, 0.0002], n=1)
    (m,) = claims.low_ramp_frozen(report(fig4=tab), claim)     # no groups: the seeds alone
    assert m.dof == 1 and "seeds" not in m.text()
    pooled = report(fig4=tab)
    pooled.questions["realization_scatter"] = _scatter_rows("phi_c", 0.002, 0.001)
    (m,) = claims.low_ramp_frozen(pooled, claim)
    assert m.dof == 7 and 2.0 < m.err / (np.hypot(0.0002, 0.0002) / 2) < 2.2
    assert str(claims.verdict(claim, m)).startswith("disagrees")
    assert "2 seeds: their own errors x 2.1, pooled with the groups of realizations " \
        "(7 dof)" in m.text()
    # the same seeds beside groups they do not resemble: the seeds alone again
    pooled.questions["realization_scatter"] = _scatter_rows("phi_c", 0.00001, 0.001)
    (m,) = claims.low_ramp_frozen(pooled, claim)
    assert m.dof == 1 and "2 seeds (0.0054, 0.0046): the spread of their own values, " \
        "which differs" in m.text()
    # seeds that differ more than the row's error says (a row that combines the levels'
    # sems as independent): the sem of the seeds' values, 0.0015, with 1 dof
    tab.add("params", "low:down_change:seeds", [0.125, 0.125], [0.0065, 0.0035],
            [0.0002, 0.0002], n=1)
    for groups in (0.00001, None):
        data = report(fig4=tab)
        if groups:
            data.questions["realization_scatter"] = _scatter_rows("phi_c", groups, 0.001)
        (m,) = claims.low_ramp_frozen(data, claim)
        assert m.dof == 1 and m.err == pytest.approx(0.0015) and m.value == 0.005


def test_ramp_branch_differences_of_two_seeds_take_the_groups_dof():
    """The reversible ramp's decrease minus its first increase over two seeds: the curves'
    own sem over seeds gives 1 dof; with each seed's difference (``ramp:down_minus_up1:seeds``)
    the error is pooled with the groups of realizations, the value stays the curves' mean."""
    claim = BY_ID["reversible-above"]
    tab = Table()
    tab.add("a", "up1", X, 0.59, 0.0002, n=2).add("a", "down", X, 0.6, 0.0002, n=2)
    data = report(fig4=tab)
    (alone,) = claims.ramp_down_minus_up(data, claim)
    assert alone.dof == 1 and alone.value == pytest.approx(0.01)
    tab.param("ramp:down_minus_up1", 0.01, 0.0001, n=2, x=0.3)
    tab.add("params", "ramp:down_minus_up1:seeds", [0.3, 0.3], [0.0099, 0.0101],
            [0.0001, 0.0001], n=1)
    data = report(fig4=tab)
    data.questions["realization_scatter"] = _scatter_rows("phi_c", 0.002, 0.001)
    (m,) = claims.ramp_down_minus_up(data, claim)
    assert m.dof == 7 and m.value == pytest.approx(0.01)
    # k'^2 = (6 x 2^2 + 1 x (1.41e-4 / 1e-4)^2) / 7
    assert m.err == pytest.approx(np.sqrt(26 / 7) * np.hypot(1e-4, 1e-4) / 2)
    assert "x 1.9, pooled with the groups of realizations (7 dof)" in m.text()


def test_ramp_first_increase_of_two_seeds_against_the_squares_adds_the_squares_once():
    """The first increase minus the steady squares with two seeds of the ramp: each seed's
    mean of up1 at the squares' sqrt(eps) (``ramp:up1_at_steady:seeds``) is pooled with the
    groups of realizations; the squares (one run per sqrt(eps), common to both seeds, their
    one-run errors times the factor) are added once, with the Welch-Satterthwaite dof."""
    claim = BY_ID["ramp-up-near-squares"]
    tab = Table()
    tab.add("a", "steady", X, 0.599, 0.0002, n=1).add("a", "up1", X, 0.6, 0.0002, n=2)
    tab.add("a", "down", X, 0.61, 0.0002, n=2)
    tab.add("params", "ramp:up1_at_steady:seeds", [0.3, 0.3], [0.5998, 0.6002],
            [0.0001, 0.0001], n=1)
    data = report(fig4=tab)
    data.questions["realization_scatter"] = _scatter_rows("phi_c", 0.002, 0.001)
    assert data.run_error("phi_c")[0] == pytest.approx(2.0)      # the squares' factor
    (m,) = claims.ramp_up_minus_steady(data, claim)
    assert m.value == pytest.approx(0.001)
    # k'^2 = (6 x 2^2 + 1 x (2.83e-4 / 1e-4)^2) / 7: the seeds' part
    seeds = np.sqrt(32 / 7) * np.hypot(1e-4, 1e-4) / 2
    squares = 2 * 0.0002 / np.sqrt(len(X))                       # sqrt(sum (2 sem)^2) / k
    assert m.err == pytest.approx(np.hypot(seeds, squares))
    parts = np.r_[seeds ** 2, np.full(len(X), (2 * 0.0002 / len(X)) ** 2)]
    dofs = np.r_[7, np.full(len(X), claims.WITHIN_RUN_DOF)]
    assert m.dof == int(parts.sum() ** 2 / np.sum(parts ** 2 / dofs))
    assert "2 seeds: their own errors x 2.1, pooled" in m.text() and "squares' own" in m.text()
    # seeds that spread far beyond the groups are judged by their own spread (its 1 dof
    # dominates the Welch-Satterthwaite sum)
    tab.add("params", "ramp:up1_at_steady:seeds", [0.3, 0.3], [0.59, 0.61],
            [0.0001, 0.0001], n=1)
    (wide,) = claims.ramp_up_minus_steady(_with_scatter(tab), claim)
    assert wide.err == pytest.approx(np.hypot(0.01, squares)) and wide.dof == 1
    assert "2 seeds (0.59, 0.61): the spread of their own values, which differs" in wide.text()
    # without the seeds' row: the curves' errors, as with one seed
    del tab.table[("params", "ramp:up1_at_steady:seeds")]
    (curves,) = claims.ramp_up_minus_steady(_with_scatter(tab), claim)
    assert "seeds" not in curves.text() and curves.value == pytest.approx(0.001)


def test_steady_squares_of_several_seeds_take_at_least_the_pooled_error():
    """Fig. 4's steady squares of three seeds: a sem over seeds below what the groups of
    realizations give their mean (the seeds are the group const_pbc_eps<eps> of
    realization_scatter.csv) is raised to it; a larger sem stays; a square whose group does not
    match its mean, or has another number of runs, keeps its own error."""
    x = np.array([0.05, 0.1, 0.15, 0.2])
    tab = Table().add("a", "steady", x, [0.605, 0.607, 0.59, 0.604], [0.0001, 0.0002, 0.01,
                                                                         0.0001], n=3)
    data = report(fig4=tab)
    rows = _scatter_rows("phi_c", 0.002, 0.001)
    for eps, means in ((0.0025, (0.6049, 0.605, 0.6051)), (0.0225, (0.5899, 0.59, 0.5901)),
                       (0.04, (0.6029, 0.603, 0.6031))):     # eps = 0.04: another mean
        rows += [{"group": f"const_pbc_eps{eps:g}", "column": "phi_c", "mean": str(m),
                  "sem": "0.0002", "sem_dof": "19"} for m in means]
    data.questions["realization_scatter"] = rows
    sem = data.figure("fig4").get("a", "steady")[2]
    # the groups g0, g1 (k = 2, 3 dof each) and the three of three seeds (sd 1e-4 against
    # errors 2e-4: k^2 = 1/4, 2 dof each) pool to k^2 = (6 x 4 + 3 x 2 / 4) / 12
    assert sem[0] == pytest.approx(np.sqrt(25.5 / 12) * 0.0002 / np.sqrt(3))
    assert sem[1] == 0.0002             # no group of realizations at eps = 0.01
    assert sem[2] == 0.01               # the seeds' own spread is the larger
    assert sem[3] == 0.0001             # the group's mean is not this square's
    assert report(fig4=tab).figure("fig4").get("a", "steady")[2][0] == 0.0001   # no groups


def _with_scatter(tab):
    data = report(fig4=tab)
    data.questions["realization_scatter"] = _scatter_rows("phi_c", 0.002, 0.001)
    return data


def test_fbc_few_seed_values_of_figs_6_and_8_are_pooled_with_their_groups():
    """Fig. 8's central minus lateral zone and Fig. 6's final alpha over two seeds: with each
    seed's own value and error they take the F.B.C. groups' factor of that quantity and its
    pooled dof; without the seeds' rows the sem over seeds with 1 dof, as before."""
    tag = "eps=0.1"
    tab8 = Table()
    tab8.param(f"{tag}:final_central", 0.011, 0.001, n=2, x=0.1)
    tab8.param(f"{tag}:final_lateral", 0.023, 0.001, n=2, x=0.1)
    tab8.param(f"{tag}:final_central_minus_lateral", -0.012, 0.0004, n=2, x=0.1)
    tab6 = Table().param("final:alpha", 0.0024, 0.0002, n=2)
    data = report(fig8=tab8, fig6=tab6)
    (cml,) = claims.central_minus_lateral(data, BY_ID["central-smaller"])
    alpha = next(c for c in REGISTER if c.statistic == "final_alpha")
    (a,) = claims.final_alpha(data, alpha)
    assert cml.dof == 1 and a.dof == 1 and cml.err == 0.0004 and a.err == 0.0002
    tab8.add("params", f"{tag}:final_central_minus_lateral:seeds", [0.1, 0.1],
             [-0.0124, -0.0116], [0.0002, 0.0002], n=1)
    tab6.add("params", "final:alpha:seeds", [0.1, 0.1], [0.0022, 0.0026], [0.0001, 0.0001],
             n=1)
    data = report(fig8=tab8, fig6=tab6)
    rows = [dict(r, group=r["group"].replace("g", "const_fbc_eps0.0"))
            for r in _scatter_rows("zone:central_minus_lateral", 0.006, 0.001)
            + _scatter_rows("packing:alpha", 0.003, 0.001)]
    data.questions["realization_scatter"] = rows[:8]
    data.questions["packing_scatter"] = rows[8:]
    (cml,) = claims.central_minus_lateral(data, BY_ID["central-smaller"])
    (a,) = claims.final_alpha(data, alpha)
    # k^2 = (6 x 36 + 1 x (5.66e-4 / 2e-4)^2) / 7 and (6 x 9 + 1 x (2.83e-4 / 1e-4)^2) / 7
    assert cml.dof == 7 and cml.err == pytest.approx(np.sqrt(224 / 7) * 0.0002 / np.sqrt(2))
    assert a.dof == 7 and a.err == pytest.approx(np.sqrt(62 / 7) * 0.0001 / np.sqrt(2))
    assert cml.value == -0.012 and a.value == 0.0024
    assert "pooled with the groups of realizations (7 dof)" in cml.text() + a.text()
    # the same seeds as one of the groups (realization-scatter's const_fbc_eps0.1): they do
    # not count twice, the groups' own k = 6 and 3 on 6 dof serve
    rows = [dict(r, group=r["group"].replace("g0", "const_fbc_eps0.1").replace(
        "g1", "const_fbc_eps0.02")) for r in _scatter_rows("zone:central_minus_lateral",
                                                           0.006, 0.001)
            + _scatter_rows("packing:alpha", 0.003, 0.001)]
    tab6.param("eps", 0.1, n=2, x=0.1)
    data = report(fig8=tab8, fig6=tab6)
    data.questions["realization_scatter"] = rows[:8]
    data.questions["packing_scatter"] = rows[8:]
    (cml,) = claims.central_minus_lateral(data, BY_ID["central-smaller"])
    (a,) = claims.final_alpha(data, alpha)
    assert cml.dof == 6 and cml.err == pytest.approx(6.0 * 0.0002 / np.sqrt(2))
    assert a.dof == 6 and a.err == pytest.approx(3.0 * 0.0001 / np.sqrt(2))


def test_critical_separation_is_decided_by_each_ramps_own_levels():
    """At 1000 taps per level the ramp turning at 0.125 compacts on the way down (0.005, a
    contradiction of the paper's frozen branch), the ramp turning at 0.3 too: 'disagrees' at
    this scale, undecided at the paper's. Each ramp's decrease and turning level measured at
    4000 taps decide it when the contradiction survives every end of the ramps' ranges, and
    not when the low ramp's turning level could rise as much as its change."""
    claim = BY_ID["critical-sqrt-eps"]
    tab = fig4(BELL).param("critical_sqrt_eps", 0.15, None, 1)
    for tag, top, change in (("low", 0.125, 0.005), ("ramp", 0.3, 0.018)):
        tab.param(f"{tag}:top_sqrt_eps", top, None, 1)
        tab.param(f"{tag}:down_change", change, 0.0002, 1, x=top)

    def outcome(low_top_shift):
        rows = []
        for run, top, levels in (("ramplow_pbc_s1", 0.125, ((4, 0, low_top_shift),
                                                            (5, 1, 0.001), (8, 1, 0.0))),
                                 ("ramp_pbc_s1", 0.3, ((11, 0, 0.001), (17, 1, 0.0),
                                                       (22, 1, 0.0005)))):
            for r, (k, b, _) in zip(_ramp_levels_rows(levels), levels):
                r.update(ramp=run, sqrt_eps=str(top) if b == 0 else "0.1")
                rows.append(r)
        data = claims.ReportData(dict(report().summary, ramp_taps_per_level=[1000]),
                                 {"fig4": with_fig4_rows(tab).data()},
                                 questions={"ramp_levels": rows})
        (row,) = claims.evaluate([claim], data)
        return str(row.verdict)

    assert outcome(0.002).startswith("disagrees (at 1000 taps per level; the paper's 4000 "
                                     "would move the changes on the way down, top 0.125 by")
    assert "top 0.3 by" in outcome(0.002)
    assert outcome(0.006) == ("undecided (scale: needs the paper's ramp_taps; at this scale "
                              "it disagrees)")


def test_the_pooled_error_of_two_seeds_covers_the_truth_95_percent_of_the_time():
    """Brute-force oracle: realizations spread k = 4 times their own errors; 4 groups of 4
    runs and a pair of seeds are drawn afresh each time. The pair's mean +- t err (pooled k',
    pooled dof) covers the true mean in 95 % of 2000 draws (within 3 sigma), where the bare
    within-run errors would cover it in about 40 %."""
    from scipy import stats as st

    rng = np.random.default_rng(2026)
    draws, covered, bare = 2000, 0, 0
    for _ in range(draws):
        rows = [{"group": f"g{g}", "column": "phi_c", "mean": str(0.6 + 4 * 0.001 * z),
                 "sem": "0.001", "sem_dof": "19"}
                for g in range(4) for z in rng.standard_normal(4)]
        data = claims.ReportData({}, {}, questions={"realization_scatter": rows})
        errors = np.array([0.001, 0.0015])
        values = 0.01 + 4 * errors * rng.standard_normal(2)
        found = data.seed_mean_error("phi_c", values, errors)
        if found is None:               # the F test set them apart: judged alone (rare)
            found = (np.std(values, ddof=1) / np.sqrt(2), 1, None)
        err, dof, _ = found
        covered += abs(values.mean() - 0.01) <= st.t.ppf(0.975, dof) * err
        bare += abs(values.mean() - 0.01) <= 1.96 * np.hypot(*errors) / 2
    sigma = np.sqrt(0.95 * 0.05 / draws)
    assert abs(covered / draws - 0.95) < 3 * sigma
    assert bare / draws < 0.5
