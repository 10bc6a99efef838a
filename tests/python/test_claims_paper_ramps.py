# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The claims of Fig. 4 decided on the ramps at the paper's own protocol (paper_ramp.csv,
4000 taps per level): the first increase against the squares, the frozen branch and the
separation at (sqrt eps)*, the reversible branch of a ramp beyond it (known answers on
synthetic rows, controls that must fail; claims_fakes.py)."""
import csv

from claims_fakes import *  # noqa: F401,F403  (the synthetic figure data and controls)

from tapmc.paper import paper_ramp  # noqa: E402


def _paper_ramps(tmp_path, runs, down=()):
    """paper_ramp.csv's text rows (as the report reads them) of ``runs``: (seed, eta, first
    increase's levels done whole, their <Phi^c>), ramps turning at 0.125 still going up; and
    of ``down``: (top, seed, eta, change on the way down), ramps that came down."""
    nan = float("nan")
    rows = [paper_ramp.PaperRampRun(
        run=f"paperramp0.125_pbc_s{seed}", top=0.125, eta=eta, seed=seed, taps_done=4000 * len(x),
        finished=False, down_levels=0, down_first=nan, down_last=nan, down_change=nan,
        down_change_sem=nan, down_rise=nan, down_rise_sem=nan, verdict="running",
        level_branches=" ".join(["up1"] * len(x)), level_sqrt_eps=tuple(x), level_mean=tuple(y),
        level_sem=(0.0002,) * len(x)) for seed, eta, x, y in runs]
    rows += [paper_ramp.PaperRampRun(
        run=f"paperramp{top:g}_pbc_s{seed}", top=top, eta=eta, seed=seed, taps_done=40000,
        finished=False, down_levels=2, down_first=top - 0.025, down_last=top - 0.05,
        down_change=change, down_change_sem=0.0002, down_rise=0.0, down_rise_sem=0.0002,
        verdict="compacts" if change > 0.0006 else "frozen") for top, seed, eta, change in down]
    path = paper_ramp.write_csv(rows, tmp_path / "paper_ramp.csv")
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_paper_protocol_ramps_decide_the_separation_and_the_frozen_branch(tmp_path):
    """At the paper's protocol (paper_ramp.csv), per eta: a ramp turning at 0.125 that stays
    within its errors on the way down and one turning at 0.2 that compacts separate at
    (sqrt eps)* (agrees); the ramp at 0.125 compacting too contradicts the separation
    (disagrees, the control); the frozen branch's row reads only the ramp below 0.15."""
    separation, frozen = BY_ID["critical-sqrt-eps"], BY_ID["irreversible-frozen"]
    tab = ramps_turning({0.125: 0.0002, 0.175: 0.01})

    def rows(changes):
        data = report(fig4=tab)
        data.questions["paper_ramp"] = _paper_ramps(
            tmp_path, [], [(top, 1, 1e-7, c) for top, c in changes.items()])
        return data

    data = rows({0.125: 0.0001, 0.2: 0.01})
    *_, paper = claims.critical_separation(data, separation)
    assert paper.label == "4000 taps per level, eta = 1e-7" and paper.meets == ("ramp_taps",)
    assert str(claims.verdict(separation, paper)) == "agrees"
    assert "(sqrt eps)* in (0.125, 0.2]" in paper.shown
    *_, below = claims.low_ramp_frozen(data, frozen)
    assert below.value == pytest.approx(0.0001) and "decrease minus turning level 0.125" \
        in below.text()
    *_, control = claims.critical_separation(rows({0.125: 0.005, 0.2: 0.01}), separation)
    assert str(claims.verdict(separation, control)).startswith("disagrees")
    assert "top 0.125 moves on the way down" in control.shown


def test_ramp_first_increase_at_the_paper_protocol_against_the_squares(tmp_path):
    """The ramps at the paper's own protocol (paper_ramp.csv) at the campaign's eta: a seed
    whose first increase is done to its turning level 0.125 is held against the squares at
    the sqrt(eps) they share (0.05-0.125 of X), with its levels' errors times the realizations'
    factor and the squares' errors added; 0.0001 above them agrees, 0.01 above (the control)
    disagrees; a seed still going up and a ramp at another eta are not counted, and with no
    seed done the row is undecided."""
    claim = BY_ID["ramp-up-near-squares"]
    tab = fig4(BELL, up1=BELL, down=BELL + 0.03)                 # the gap: 0.03
    levels = np.array([0.025, 0.05, 0.075, 0.1, 0.125])
    squares = 0.60 - 2.0 * (levels - 0.15) ** 2                  # BELL at the ramp's levels

    def rows(shift, runs=()):
        data = report(fig4=tab)
        data.questions["paper_ramp"] = _paper_ramps(
            tmp_path, [(1, 1e-7, levels, squares + shift)] + list(runs))
        return claims.ramp_up_minus_steady(data, claim)

    _, paper = rows(0.0001)
    assert paper.label == "4000 taps per level, eta = 1e-7" and paper.meets == ("ramp_taps",)
    assert paper.value == pytest.approx(0.0001)
    own = np.sqrt(4 * 0.0002 ** 2) / 4                            # one seed, factor 1
    assert paper.err == pytest.approx(np.hypot(own, np.sqrt(4 * 0.001 ** 2) / 4))
    assert "mean of 4 common sqrt(eps); one seed" in paper.text()
    assert str(claims.verdict(claim, paper)) == "agrees"
    _, control = rows(0.01)
    assert str(claims.verdict(claim, control)).startswith("disagrees")
    _, counted = rows(0.0001, [(2, 1e-7, levels[:2], squares[:2]), (3, 1e-5, levels, squares)])
    assert counted.value == pytest.approx(0.0001) and "one seed" in counted.text()
    assert ("not counted yet: seed 2 (turning at 0.125) at tap 8000, 2 of its first increase's "
            "levels done") in counted.text()
    two = report(fig4=tab)
    two.questions["paper_ramp"] = _paper_ramps(tmp_path, [(1, 1e-7, levels, squares + 0.001),
                                                          (2, 1e-7, levels, squares + 0.002)])
    _, both = claims.ramp_up_minus_steady(two, claim)
    assert both.value == pytest.approx(0.0015) and "2 seeds" in both.text()
    none = report(fig4=tab)
    none.questions["paper_ramp"] = _paper_ramps(tmp_path, [(2, 1e-7, levels[:2], squares[:2])])
    _, waiting = claims.ramp_up_minus_steady(none, claim)
    assert waiting.undecided.startswith("no ramp has finished its first increase")
    assert len(claims.ramp_up_minus_steady(report(fig4=tab), claim)) == 1   # no paper ramps


def _beyond_ramp(tmp_path, up1, down, up2=(), top=0.2, taps=60000):
    """paper_ramp.csv's text rows of one ramp turning at ``top`` (eta 1e-7) with whole levels
    ``up1``, ``down``, ``up2``: lists of (sqrt_eps, <Phi^c>), each with sem 0.0002."""
    levels = [("up1", x, y) for x, y in up1] + [("down", x, y) for x, y in down] + \
        [("up2", x, y) for x, y in up2]
    nan = float("nan")
    run = paper_ramp.PaperRampRun(
        run=f"paperramp{top:g}_pbc_s1", top=top, eta=1e-7, seed=1, taps_done=taps,
        finished=False, down_levels=len(down), down_first=nan, down_last=nan, down_change=nan,
        down_change_sem=nan, down_rise=nan, down_rise_sem=nan, verdict="running",
        level_branches=" ".join(b for b, _, _ in levels),
        level_sqrt_eps=tuple(x for _, x, _ in levels), level_mean=tuple(y for _, _, y in levels),
        level_sem=(0.0002,) * len(levels))
    with open(paper_ramp.write_csv([run], tmp_path / "paper_ramp.csv"), newline="") as f:
        return list(csv.DictReader(f))


def test_paper_protocol_ramp_beyond_decides_the_reversible_branch(tmp_path):
    """The ramp turning at 0.2 at the paper's protocol: its decrease 0.01 above its first
    increase (reversible-above agrees; the control, a decrease equal to the increase, does
    not), falling with sqrt(eps) (slope -0.1 per unit: agrees), a second increase within a
    tenth of the gap of the decrease (retraced: agrees; 0.01 off: disagrees); before its
    descent the rows are undecided and say how far it got; the ramp below (sqrt eps)* is not
    read."""
    up = [(0.025 * k, 0.59 + 0.001 * k) for k in range(1, 9)]
    down = [(0.175, 0.6175), (0.15, 0.62), (0.125, 0.6225), (0.1, 0.625)]
    data = report(fig4=fig4(BELL, up1=BELL, down=BELL + 0.03))

    def rows(statistic, claim_id, up1=up, dn=down, up2=()):
        data.questions["paper_ramp"] = _beyond_ramp(tmp_path, up1, dn, up2)
        *_, paper = statistic(data, BY_ID[claim_id])
        assert paper.label == "4000 taps per level, eta = 1e-7"
        return paper, str(claims.verdict(BY_ID[claim_id], paper))

    above, word = rows(claims.ramp_down_minus_up, "reversible-above")
    mean_up = np.mean([0.59 + 0.001 * k for k in (7, 6, 5, 4)])
    assert above.value == pytest.approx(np.mean([y for _, y in down]) - mean_up)
    assert word == "agrees" and "turning at 0.2; 4 levels; one seed" in above.text()
    flat = [(x, 0.59 + 0.001 * round(x / 0.025)) for x, _ in down]
    assert not rows(claims.ramp_down_minus_up, "reversible-above", dn=flat)[1] == "agrees"
    slope, word = rows(claims.ramp_branch_slope, "reversible-falls")
    assert slope.value == pytest.approx(-0.1) and word == "agrees"
    retraced, word = rows(claims.ramp_up2_minus_down, "reversible-retraced",
                          up2=[(0.125, 0.6226), (0.15, 0.6199)])
    assert retraced.value == pytest.approx(0.0) and word == "agrees"
    off = rows(claims.ramp_up2_minus_down, "reversible-retraced",
               up2=[(0.125, 0.6325), (0.15, 0.63)])[1]
    assert off.startswith("disagrees")
    going, word = rows(claims.ramp_down_minus_up, "reversible-above", dn=[])
    assert word.startswith("undecided") and "(seed 1 (turning at 0.2) at tap 60000)" in \
        going.undecided
    data.questions["paper_ramp"] = _beyond_ramp(tmp_path, up, down, top=0.125)
    assert len(claims.ramp_down_minus_up(data, BY_ID["reversible-above"])) == 1


def test_nu_hysteresis_at_the_paper_protocol_has_rows_per_eta():
    """nu at the level ends of the paper ramps beyond (sqrt eps)* (ramp_pores.csv): per eta two
    rows labelled with the protocol, two seeds of one eta averaged level by level (their
    errors combined); the campaign's ramp keeps its own rows; a paper ramp below (sqrt eps)*
    is not read. The control: a decrease above the first increase disagrees."""
    claim = BY_ID["nu-hysteresis"]

    def rows(*ramps):
        table = [r for data in ramps for r in data.questions["ramp_pores"]]
        return claims.nu_ramp_hysteresis(claims.ReportData(report().summary, {}, questions={
            "ramp_pores": table}), claim)

    own, own_slope, paper, paper_slope = rows(
        ramp_pores(gap=-0.02, slope=0.05),
        ramp_pores(gap=-0.01, slope=0.05, run="paperramp0.2_pbc_s1"),
        ramp_pores(gap=-0.03, slope=0.05, run="paperramp0.2_pbc_s2"),
        ramp_pores(gap=0.5, slope=-1.0, run="paperramp0.125_pbc_s1"))
    assert own.label == "decrease minus first increase" and not own.meets
    assert paper.label == "decrease minus first increase, 4000 taps per level, eta = 1e-7"
    assert paper.meets == ("ramp_taps",) and paper_slope.meets == ("ramp_taps",)
    assert paper.value == pytest.approx(own.value)              # the seeds' mean gap: -0.02
    assert paper.err == pytest.approx(own.err / np.sqrt(2))     # two seeds per level
    assert paper_slope.value == pytest.approx(0.05)
    assert str(claims.verdict(claim, paper)) == "agrees"
    eta_rows = rows(ramp_pores(gap=0.02, slope=0.05, run="paperramp0.2_pbc_eta1e-06_s1"))
    assert [m.label for m in eta_rows] == [
        "decrease minus first increase, 4000 taps per level, eta = 1e-6",
        "slope on the decrease, 4000 taps per level, eta = 1e-6"]
    assert str(claims.verdict(claim, eta_rows[0])).startswith("disagrees")
