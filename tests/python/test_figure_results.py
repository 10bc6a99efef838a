# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# The typed results of the figure modules (tapmc.paper.figN.FigNResult): each committed figure
# CSV loads into its result and saves back to the same bytes; each analysis on a small written
# campaign gives the numbers the test chose; plot() draws a result without error (Agg); a CSV
# that is not a figure's is refused with its file named.
import filecmp
import os
import sys
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", HERE.parent.parent))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from paper_fakes import FakeCampaign, write_constant_eps, write_profile_x  # noqa: E402
from tapmc.ageing import Ageing  # noqa: E402
from tapmc.fluctuations import SteadyState  # noqa: E402
from tapmc.paper import _runs, fig2, fig3, fig4, fig5, fig6, fig7, fig8, fig9, fig10  # noqa: E402
from tapmc.laws import InverseLogLaw, ZLaw  # noqa: E402
from tapmc.pores import percus_yevick_p0  # noqa: E402
from tapmc.paper._results import CsvRows, FigureCsvError, Value, save_rows  # noqa: E402
from tapmc.paper.scales import QUICK, Scale  # noqa: E402

#: the figures whose analysis returns a typed result
TYPED = ("fig2", "fig3", "fig4", "fig5", "fig6", "fig7", "fig8", "fig9", "fig10")
#: the folders of committed figure CSVs (quick campaign, paper-scale campaign)
COMMITTED = ("doc/validation", "doc/paper_scale/validation")
#: a scale of no preset, as in test_fbc_start.py
TINY = Scale(**dict(QUICK.as_dict(), N=64, L=16.0, eta=1e-4, taps=8, steady_last=2,
                     profile_eps=(0.02, 0.1)))


def result_class(name):
    module = __import__(f"tapmc.paper.{name}", fromlist=["_"])
    return module, getattr(module, name.capitalize() + "Result")


@pytest.mark.parametrize("folder", COMMITTED)
@pytest.mark.parametrize("name", TYPED)
def test_committed_csv_round_trips_to_the_same_bytes(name, folder, tmp_path):
    module, cls = result_class(name)
    committed = SOURCE / folder / f"{name}.csv"
    result = cls.load(committed)
    saved = result.save(tmp_path / f"{name}.csv")
    assert filecmp.cmp(committed, saved, shallow=False)
    plt.close(module.plot(result))          # a loaded result draws


def test_a_csv_with_rows_of_no_field_is_refused(tmp_path):
    path = tmp_path / "fig7.csv"
    text = (SOURCE / "doc/validation/fig7.csv").read_text()
    path.write_text(text + "params,surprise,0,1,,1\n")
    with pytest.raises(FigureCsvError, match=r"fig7.csv: rows of no field.*params/surprise"):
        fig7.Fig7Result.load(path)
    path.write_text(text.replace("params,eps,", "params,eps,zero,", 1))
    with pytest.raises(FigureCsvError, match=r"fig7.csv:\d+: "):
        fig7.Fig7Result.load(path)
    path.write_text("")
    with pytest.raises(FigureCsvError, match=r"fig7.csv: empty file"):
        fig7.Fig7Result.load(path)
    path.write_text("panel,series\n")
    with pytest.raises(FigureCsvError, match=r"fig7.csv:1: header"):
        fig7.Fig7Result.load(path)


@pytest.mark.parametrize("name,row,message", [
    # the initial nu: the page then stated tap 1's nu as the initial one
    ("fig10", "params,nu,0,", r"no params row nu at x = 0 \(every dump of panel a has one\)"),
    ("fig3", "params,k_reduced_chi2,", r"no rows of params/k_reduced_chi2, which are written "
                                       r"with params/k, b/fit:k sqrt\(eps\)"),    # a traceback
    ("fig5", "params,collapse:reduced_chi2,", r"no rows of params/collapse:reduced_chi2, which "
                                              r"are written with params/collapse:A_inf"),
    # a row of the claim's table disappeared, or the claim read "no F.B.C. profile"
    ("fig8", "params,eps=0.02:final_central,",
     r"no rows of panel 'params', series 'eps=0.02:final_central'"),
    ("fig8", "params,eps=0.02:first_tap_lateral,", r"no rows of params/eps=0.02:first_tap_"
                                                   r"lateral, which are written with"),
])
def test_a_csv_missing_a_row_written_with_others_is_refused(name, row, message, tmp_path):
    """report --from-data read these rows as absent and wrote the page (exit 0) with other
    statements, or failed with a traceback."""
    _, cls = result_class(name)
    text = (SOURCE / "doc/paper_scale/validation" / f"{name}.csv").read_text()
    lines = text.splitlines(keepends=True)
    assert any(line.startswith(row) for line in lines)
    path = tmp_path / f"{name}.csv"
    path.write_text("".join(line for line in lines if not line.startswith(row)))
    with pytest.raises(FigureCsvError, match=f"{name}.csv: " + message):
        cls.load(path)


def test_save_never_leaves_an_empty_file(tmp_path):
    path = tmp_path / "fig7.csv"
    path.write_text("kept\n")
    with pytest.raises(FigureCsvError, match="fig7.csv: a figure result without rows"):
        save_rows(path, [])
    assert path.read_text() == "kept\n" and list(tmp_path.iterdir()) == [path]


def test_rows_group_by_series_in_file_order(tmp_path):
    path = tmp_path / "t.csv"
    path.write_text("panel,series,x,mean,sem,n\na,s,1,2,,3\nparams,v,0,5,0.5,2\na,s,2,4,1,3\n")
    rows = CsvRows(path)
    assert rows.keys() == [("a", "s"), ("params", "v")]
    s = rows.take("a", "s")
    np.testing.assert_array_equal(s.x, [1, 2])
    assert np.isnan(s.err[0]) and s.err[1] == 1 and list(s.n) == [3, 3]
    assert rows.take_value("params", "v") == Value(0.0, 5.0, 0.5, 2)
    rows.finish()


def fbc_campaign(tmp_path, start, wall_phi0, taps=8):
    """Two seeds of the profile runs at eps 0.02 and 0.1, walls at Phi ``wall_phi0`` within 2R
    of either wall initially and 0.5 finally, 0.55 and 0.58 elsewhere (test_fbc_start.py)."""
    runs = fig7.runs(TINY.replace(fbc_start=start, taps=taps), 2)
    camp = FakeCampaign(tmp_path / start, runs)
    x = np.arange(0.05, 8.0, 0.1)               # bins of R/5 in distance units (R = 0.5)
    dist = np.minimum(x, 8.0 - x) / 0.5
    for spec in runs:
        lateral = [0.5 + 0.001 * k for k in range(taps + 1)]
        central = [0.55 + 0.0005 * k for k in range(taps + 1)]
        write_constant_eps(camp, spec, lateral, central)
        write_profile_x(camp, spec, x, np.where(dist < 2, wall_phi0, 0.55),
                        np.where(dist < 2, 0.5, 0.58), taps)
    return camp


def test_fig7_analysis_of_known_profiles(tmp_path):
    result = fig7.analyse(fbc_campaign(tmp_path, "paper", wall_phi0=0.35))
    assert result.eps == 0.1 and result.seeds == 2 and result.paper_start is True
    assert result.frontiers == (7.0, 9.0) and result.side == 16.0 and result.taps == 8
    within = result.zones[("initial", "within_2R")]
    assert within.value == pytest.approx(0.35) and within.n == 2
    assert result.zones[("final", "central")].value == pytest.approx(0.58)
    assert result.zones[("final", "2R_to_7R")].value == pytest.approx(0.58)
    assert np.all(result.initial.n == 2) and result.initial.x[0] == pytest.approx(0.1)
    saved = result.save(tmp_path / "fig7.csv")
    again = fig7.Fig7Result.load(saved).save(tmp_path / "again.csv")
    assert filecmp.cmp(saved, again, shallow=False)
    plt.close(fig7.plot(result))
    assert _runs.fbc_start_of(fig7.runs(TINY.replace(fbc_start="paper"), 1)[0]) == "paper"


def test_fig9_analysis_of_known_curves(monkeypatch):
    """Two seeds whose P0 curves are exp(-k sigma) with k = 3, 5 (final) and 2, 4 (initial):
    the means, the phi of the random points and the Percus-Yevick curve at the final phi."""
    sigma = np.linspace(0.0, 1.0, 11)
    curves = {"final": [sigma, [np.exp(-3 * sigma), np.exp(-5 * sigma)], [[0.60], [0.62]]],
              "initial": [sigma, [np.exp(-2 * sigma), np.exp(-4 * sigma)], [[0.58], [0.58]]]}
    steady = [SteadyState(np.full(40, v) + 1e-4 * np.sin(np.arange(40)), last=20).compute()
              for v in (0.605, 0.607)]
    phi_c = {"final": [[0.606], [0.608]], "initial": [[0.583], [0.585]], "steady": steady}
    monkeypatch.setattr(fig9, "p0_curves", lambda campaign: (curves, phi_c))
    result = fig9.analyse(None)
    final = (np.exp(-3 * sigma) + np.exp(-5 * sigma)) / 2
    np.testing.assert_allclose(result.p0["final"].mean, final)
    assert result.phi["final"] == fig9.Value(0.0, pytest.approx(0.61), pytest.approx(0.01), 2)
    assert result.phi_c["initial"].value == pytest.approx(0.584)
    assert result.phi_c_steady.value == pytest.approx(0.606, abs=1e-4)
    np.testing.assert_allclose(result.percus_yevick.mean, percus_yevick_p0(sigma, 0.61))
    initial = (np.exp(-2 * sigma) + np.exp(-4 * sigma)) / 2
    assert result.max_abs_diff_initial_final.value == pytest.approx(np.max(initial - final))
    plt.close(fig9.plot(result))


def test_fig8_analysis_of_known_increases(tmp_path):
    """Lateral 0.5 + 0.001 t and central 0.55 + 0.0005 t for both seeds, 8 taps: the window
    of the last quarter (t = 7, 8) has the mean increases 0.0075 and 0.00375."""
    result = fig8.analyse(fbc_campaign(tmp_path, "paper", wall_phi0=0.35))
    assert result.paper_start is True and sorted(result.increases) == [0.02, 0.1]
    inc = result.increases[0.1]
    np.testing.assert_allclose(inc.lateral.mean, 0.001 * np.arange(9), atol=1e-12)
    assert inc.final["lateral"].value == pytest.approx(0.0075)
    assert inc.final["central_minus_lateral"].value == pytest.approx(-0.00375)
    assert inc.first_tap["central"] == fig8.Value(0.1, pytest.approx(0.0005), 0.0, 2)
    assert not inc.final_seeds             # a window of two taps has no batch-means error
    saved = result.save(tmp_path / "fig8.csv")
    assert "paper:eps=0.1" in saved.read_text()
    again = fig8.Fig8Result.load(saved).save(tmp_path / "again.csv")
    assert filecmp.cmp(saved, again, shallow=False)
    plt.close(fig8.plot(result))


def test_fig3_analysis_of_a_known_proportional_law(monkeypatch):
    """sigma_<Z> = 0.3 sqrt(eps) with 2 % errors at three eps: k = 0.3, intercepts 0."""
    freq = np.array([0.01, 0.02, 0.04])

    def one(eps):
        sigma = (0.3 * np.sqrt(eps), 0.006 * np.sqrt(eps), 2)
        return {"frequency": freq, "power": (1 / freq, 0.1 / freq, np.full(3, 2)),
                "slope": (-1.2, 0.1, 2), "sigma": sigma, "sigma_detrended": sigma}

    monkeypatch.setattr(fig3, "per_eps", lambda campaign, column, bc: {
        e: one(e) for e in (0.01, 0.04, 0.09)})
    result = fig3.analyse(None)
    assert result.k.value == pytest.approx(0.3) and result.k.n == 3
    assert result.intercept.value == pytest.approx(0.0, abs=1e-9)
    assert result.intercept_detrended.value == pytest.approx(0.0, abs=1e-9)
    assert result.spectra[0.04].slope == fig3.Value(0.04, -1.2, 0.1, 2)
    np.testing.assert_allclose(result.sigma.x, [0.1, 0.2, 0.3])
    np.testing.assert_allclose(result.law_curve.mean, 0.3 * result.law_curve.x)
    plt.close(fig3.plot(result))


def test_fig10_analysis_of_known_distributions(monkeypatch):
    """Two seeds with xi^3 P(xi) = 1 at t = 0 and 1.5 at t = 10 on a fine grid: the shares
    are the widths of their ranges (times 1.5 at t = 10) and both change by half."""
    xi = np.linspace(0.0, 1.0, 1001)

    def dump(level):
        return {"xi": [xi, xi], "xi3_P_xi": [np.full(xi.size, level)] * 2, "v": [xi ** 3] * 2,
                "rho_v": [np.full(xi.size, level / 3)] * 2, "nu": [[0.5], [0.52]],
                "xi_min": [[0.1], [0.12]], "xi_T": [[0.22], [0.24]], "nu_tail": []}

    monkeypatch.setattr(fig10, "distributions", lambda campaign, bc: {0: dump(1.0),
                                                                      10: dump(1.5)})
    result = fig10.analyse(None)
    late = result.dumps[10].statistics
    assert "nu_tail" not in late and late["nu"] == fig10.Value(10, 0.51, pytest.approx(0.01), 2)
    width = fig10.P.XI_O - fig10.P.XI_T
    assert late["small"].value == pytest.approx(1.5 * width, abs=2e-3)
    assert result.small_change.value == pytest.approx(0.5)
    assert result.large_change.value == pytest.approx(0.5) and result.large_change.x == 10
    plt.close(fig10.plot(result))


def test_fig6_analysis_of_a_known_gradient(tmp_path):
    """Straight vertical profiles Phi = 0.6 - alpha z/R below 20R (h_s = 10 distance units,
    R = 0.5), alpha = 0.001 initially and 0.002 finally: the window is cut at 22/28 of 20R and
    the gradients are found; no P.B.C. run, so no bottom panel."""
    camp = fbc_campaign(tmp_path, "walls", wall_phi0=0.45)
    z = np.arange(0.05, 15.0, 0.1)
    for spec in camp.runs:
        write_profile_x(camp, spec, z, np.where(z < 10, 0.6 - 0.001 * z / 0.5, 0.0),
                        np.where(z < 10, 0.6 - 0.002 * z / 0.5, 0.0), 8)
        folder = camp.result(spec.name)
        (folder / "profile_x.dat").rename(folder / "profile_z.dat")
    result = fig6.analyse(camp)
    top = result.profiles
    assert result.bell is None and result.ramp == {} and top.eps == 0.1 and top.seeds == 2
    assert top.window == pytest.approx((5.0, 20.0 * 22.0 / 28.0))
    assert top.alpha["initial"].value == pytest.approx(0.001)
    assert top.alpha["final"] == fig6.Value(0.1, pytest.approx(0.002), pytest.approx(0.0), 2)
    assert top.alpha_seeds is None          # no dump after the last tap: no jackknife
    saved = result.save(tmp_path / "fig6.csv")
    again = fig6.Fig6Result.load(saved).save(tmp_path / "again.csv")
    assert filecmp.cmp(saved, again, shallow=False)
    plt.close(fig6.plot(result))


def test_fig6_bottom_panel_alone(tmp_path, monkeypatch):
    """A campaign with the bell's runs but no F.B.C. run: one panel, the bell alone."""
    monkeypatch.setattr(fig6, "alpha_bell", lambda campaign: (np.array([0.1, 0.2]),
                                                               np.array([1e-3, 2e-3]),
                                                               np.array([1e-4, 1e-4]),
                                                               np.array([2, 2])))
    monkeypatch.setattr(fig6, "ramp_alpha", lambda campaign: {})
    result = fig6.analyse(FakeCampaign(tmp_path, []))
    assert result.profiles is None and list(result.bell.mean) == [1e-3, 2e-3]
    saved = result.save(tmp_path / "fig6.csv")
    assert saved.read_text().splitlines()[1] == "b,bell:alpha,0.1,0.001,0.0001,2"
    loaded = fig6.Fig6Result.load(saved)
    fig = fig6.plot(loaded)
    assert loaded.profiles is None and len(fig.axes) == 1
    plt.close(fig)


def test_fig4_analysis_of_a_known_bell(tmp_path):
    """Constant-eps runs whose <Phi^c> is 0.6 - (sqrt(eps) - 0.2)^2 at every tap, two seeds,
    no ramp: the steady squares, the highest at sqrt(eps) = 0.2; three squares do not test a
    parabola, so the bell's maximum is that square, with no error, over 3 points."""
    scale = Scale(**dict(QUICK.as_dict(), N=64, L=8.0, eta=1e-4, taps=40,
                         steady_eps=(0.01, 0.04, 0.09)))
    runs = [r for r in fig4.runs(scale, 2) if r.name.startswith("const_")]
    camp = FakeCampaign(tmp_path, runs)
    for spec in runs:
        phi = 0.6 - (np.sqrt(spec.variables["eps"]) - 0.2) ** 2
        (camp.result(spec.name) / "taps.dat").write_text(
            "# step phi_b phi_c Z z_top lateral central h_s sweeps accept capped\n"
            + "".join(f"{t} 0.55 {phi:.8f} 5 9 0.5 0.5 10 100 0.1 0\n" for t in range(41)))
    result = fig4.analyse(camp)
    np.testing.assert_allclose(result.steady.x, [0.1, 0.2, 0.3])
    np.testing.assert_allclose(result.steady.mean, [0.59, 0.6, 0.59])
    top = result.sqrt_eps_max
    assert (top.x, top.value, top.n) == (0.0, pytest.approx(0.2), 3) and np.isnan(top.err)
    assert "three points" in fig4.bell_maximum(result.steady)[1]
    assert result.phi_c_max.value == pytest.approx(0.6) and result.ramps == {}
    assert result.critical_sqrt_eps.value == 0.15
    saved = result.save(tmp_path / "fig4.csv")
    again = fig4.Fig4Result.load(saved).save(tmp_path / "again.csv")
    assert filecmp.cmp(saved, again, shallow=False)
    plt.close(fig4.plot(result))


def test_fig5_analysis_of_a_known_drift(monkeypatch, tmp_path):
    """Four realizations of <Z> = 5 + 0.01 t with a noise of 1e-4: A(t, t_W) = (0.01 t)^2 for
    every waiting time; whatever the fits give, the result saves, loads and draws."""
    rng = np.random.default_rng(5)
    t = np.arange(61)
    z = np.array([5 + 0.01 * t + rng.normal(0, 1e-4, t.size) for _ in range(4)])
    monkeypatch.setattr(fig5, "ageing", lambda campaign, waiting_times: (
        Ageing(z, [2, 5]).compute(), 4))
    monkeypatch.setattr(fig5, "BOOTSTRAP_RESAMPLES", 3)      # the numbers are not tested
    result = fig5.analyse(None)
    assert sorted(result.curves) == [2.0, 5.0] and result.realizations == 4
    for curve in result.curves.values():
        np.testing.assert_allclose(curve.A.mean, 1e-4 * curve.A.x ** 2, rtol=0.02, atol=1e-6)
        assert np.all(curve.A.n == 4)
    assert result.eq6_test_needed.value == fig5.EQ6_TEST_MIN_REALIZATIONS
    assert result.eq6_tests == {}             # four realizations are too few for the test
    saved = result.save(tmp_path / "fig5.csv")
    again = fig5.Fig5Result.load(saved).save(tmp_path / "again.csv")
    assert filecmp.cmp(saved, again, shallow=False)
    plt.close(fig5.plot(result))


def test_fig2_analysis_of_known_laws(tmp_path):
    """Phi_b on eq. 3 and <Z> on eq. 4 with known parameters, two seeds a little apart, at
    two eps: each fit finds its parameters and the B panel holds one B per eps."""
    scale = Scale(**dict(QUICK.as_dict(), taps=400, fig2_eps=(0.01, 0.1)))
    runs = fig2.runs(scale, 2)
    camp = FakeCampaign(tmp_path, runs)
    t = np.arange(401.0)
    for spec in runs:
        b = 2.0 if spec.variables["eps"] == 0.01 else 5.0
        offset = 2e-4 * (spec.seed - 1.5)
        phi = InverseLogLaw.function(t, 0.62, 0.06, b, 3.0) + offset
        z = ZLaw.function(t, 6.0, 5.0, b, 3.0) + offset
        (camp.result(spec.name) / "taps.dat").write_text(
            "# step phi_b phi_c Z z_top lateral central h_s sweeps accept capped\n"
            + "".join(f"{k} {p:.10f} 0.56 {zz:.10f} 9 0.5 0.5 10 100 0.1 0\n"
                      for k, (p, zz) in enumerate(zip(phi, z))))
    result = fig2.analyse(camp, eps_values=(0.01, 0.1))
    assert sorted(result.laws) == ["eq3", "eq4"]
    eq3 = result.laws["eq3"].curves[0.1]
    assert eq3.params["X_inf"].value.value == pytest.approx(0.62, rel=1e-3)
    assert eq3.params["B"].value.value == pytest.approx(5.0, rel=0.05)
    assert result.laws["eq4"].curves[0.01].params["B"].value.value == pytest.approx(2.0,
                                                                                    rel=0.05)
    np.testing.assert_allclose(result.laws["eq3"].B.B.x, np.sqrt([0.01, 0.1]))
    saved = result.save(tmp_path / "fig2.csv")
    again = fig2.Fig2Result.load(saved).save(tmp_path / "again.csv")
    assert filecmp.cmp(saved, again, shallow=False)
    plt.close(fig2.plot(result))


@pytest.mark.parametrize("folder", ["doc/validation", "doc/paper_scale/validation"])
def test_fig4_refit_of_a_committed_csv_gives_it_back_and_moves_a_shifted_maximum(folder, tmp_path):
    """``report --from-data --refit`` on Fig. 4: the bell maximum fitted again from the CSV's
    own steady squares is the committed one, byte for byte; a maximum written wrong comes
    back to the vertex."""
    committed = SOURCE / folder / "fig4.csv"
    out = tmp_path / "fig4.csv"
    fig4.refit_table(fig4.P.read_table(committed)).write(out)
    assert filecmp.cmp(committed, out, shallow=False)
    result = fig4.Fig4Result.load(committed)
    wrong = fig4.replace(result, sqrt_eps_max=fig4.replace(result.sqrt_eps_max, value=0.3))
    wrong.save(tmp_path / "wrong.csv")
    again = fig4.refit_table(fig4.P.read_table(tmp_path / "wrong.csv"))
    again.write(tmp_path / "again.csv")
    assert filecmp.cmp(committed, tmp_path / "again.csv", shallow=False)


@pytest.mark.parametrize("name", ("fig2", "fig5"))
def test_the_smoke_pages_fig2_and_fig5_statistics_are_what_a_refit_gives(name, tmp_path):
    """doc/tapmc-paper.rst: the committed smoke test got its Fig. 2 and Fig. 5 statistics
    from ``report --from-data --refit``; they had drifted from what the fitting code gives
    (Fig. 2's tau at eps = 0.005: 245426 for 250833). After a change of the fits, run
    ``tapmc-paper report --from-data --refit --out doc``."""
    module, _ = result_class(name)
    committed = SOURCE / "doc/validation" / f"{name}.csv"
    module.refit_table(module.P.read_table(committed)).write(tmp_path / f"{name}.csv")
    assert filecmp.cmp(committed, tmp_path / f"{name}.csv", shallow=False)


def test_the_paper_scale_bell_draws_every_finished_default_eta_seed_of_the_campaign():
    """Fig. 4's squares at the paper's scale take every constant-eps P.B.C. run the committed
    campaign has finished (the plan's tiers all drawn: tier 8 gives each square 3 seeds), and
    none of the looser or tighter thresholds' ``consteta_*`` runs."""
    runs = SOURCE / "doc/validation/data/full/runs"
    finished = {}
    for done in runs.glob("const_pbc_eps*_s*/DONE.json"):
        eps = float(done.parent.name[len("const_pbc_eps"):].rsplit("_s", 1)[0])
        finished[eps] = finished.get(eps, 0) + 1
    result = fig4.Fig4Result.load(SOURCE / "doc/paper_scale/validation/fig4.csv")
    drawn = {round(x * x, 9): n for x, n in zip(result.steady.x, result.steady.n)}
    assert drawn == {round(eps, 9): n for eps, n in finished.items()}
    assert min(drawn.values()) >= 3
