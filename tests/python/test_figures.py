# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The quick campaign of every figure of the paper (tapmc.paper.fig2 ... fig10): one campaign
shared by all figures (runs common to several figures run once), then one test per figure on
the numbers of its CSV (ranges, and the trends the model guarantees) and on its PNG (size, and
axes that hold data), and the validation report built from the same campaign."""

import filecmp
import math
import os
import shutil
import sys
import time
from pathlib import Path

import numpy as np
import pytest

SOURCE_DIR = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
# The tapmc package of this tree, whatever tree the user-site tapmc.pth points at.
sys.path.insert(0, str(SOURCE_DIR / "tools" / "python"))

from tapmc.campaign import Campaign  # noqa: E402
from tapmc.paper import FIGURES, _plotting, _runs  # noqa: E402
from tapmc.paper import claims, validation  # noqa: E402
from tapmc.paper.scales import QUICK  # noqa: E402

import importlib  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402

SEEDS = QUICK.seeds
#: a PNG of a figure with data is tens of kB; the project keeps them under 200 kB.
PNG_MIN_BYTES, PNG_MAX_BYTES = 10_000, 200_000

MODULES = {name: importlib.import_module(f"tapmc.paper.{name}") for name in FIGURES}


needs_pores = pytest.mark.skipif(not _runs.pores_available(), reason="tapmc-pores is not built "
                                 "(TAPMC_BUILD_PORES=OFF): Figs. 9 and 10 need it")


@pytest.fixture(scope="module")
def campaign(tmp_path_factory):
    """Every figure's quick runs in one campaign folder."""
    runs, seen = [], set()
    for name, module in MODULES.items():
        if name in ("fig9", "fig10") and not _runs.pores_available():
            continue
        for spec in module.runs(QUICK, SEEDS):
            if spec.name not in seen:
                seen.add(spec.name)
                runs.append(spec)
    directory = tmp_path_factory.mktemp("quick_campaign")
    t0 = time.time()
    camp = Campaign(directory, runs, lmp=os.environ.get("TAPMC_LMP"), jobs=2,
                    progress_interval=120).run(progress=False)
    print(f"quick campaign: {len(runs)} runs in {time.time() - t0:.0f} s")
    return camp


@pytest.fixture(scope="module")
def out_dir(tmp_path_factory):
    return tmp_path_factory.mktemp("figures")


def draw(campaign, out_dir, name):
    png, csv = MODULES[name].draw(campaign, out_dir)
    assert Path(png).name == f"{name}.png" and Path(csv).name == f"{name}.csv"
    check_png(png)
    check_round_trip(name, csv)
    return _plotting.read_table(csv)


def check_round_trip(name, csv):
    """The figure's CSV is its typed result saved: loading it and saving it again gives the
    same bytes."""
    result = getattr(MODULES[name], name.capitalize() + "Result").load(csv)
    again = result.save(Path(csv).with_suffix(".again.csv"))
    assert filecmp.cmp(csv, again, shallow=False), f"{csv}: the result does not round-trip"
    again.unlink()


def check_png(path):
    """The PNG exists, is of a sensible size and is not blank: its pixels vary and a fair
    share of them is not background white."""
    size = Path(path).stat().st_size
    assert PNG_MIN_BYTES < size < PNG_MAX_BYTES, f"{path}: {size} bytes"
    img = mpimg.imread(path)[..., :3]
    assert img.shape[0] > 200 and img.shape[1] > 200
    assert img.var() > 1e-3
    not_white = np.mean(np.any(img < 0.9, axis=-1))
    assert not_white > 0.02, f"{path}: only {not_white:.1%} of the pixels are drawn"


def series(table, panel, prefix=""):
    return {s: d for (p, s), d in table.items() if p == panel and s.startswith(prefix)}


def param(table, name):
    d = table[("params", name)]
    return d["mean"][0], d["sem"][0], d["n"][0]


def eps_of(label):
    return float(label.split("=")[1].split(":")[0])


def test_seed_stats_mean_and_standard_error():
    mean, sem, n = _plotting.seed_stats([[1.0, 2.0, 3.0], [3.0, 4.0], [5.0, 6.0, 9.0]])
    assert np.allclose(mean, [3.0, 4.0, 6.0])
    # column 3: std of (3, 9) = sqrt(18) over sqrt(2 seeds) = 3
    assert np.allclose(sem, [2.0 / math.sqrt(3), 2.0 / math.sqrt(3), 3.0])
    assert list(n) == [3, 3, 2]
    _, sem1, _ = _plotting.seed_stats([[1.0, 2.0]])
    assert np.all(np.isnan(sem1))


def test_fig2_phi_b_compaction(campaign, out_dir):
    table = draw(campaign, out_dir, "fig2")
    data = series(table, "a", "eps=")
    assert sorted(eps_of(s) for s in data) == sorted(QUICK.fig2_eps)
    gains = []
    for label, d in data.items():
        assert np.array_equal(d["x"], np.arange(QUICK.taps + 1))
        assert np.all((d["mean"] > 0.4) & (d["mean"] < 0.7))
        assert np.all(d["n"] == SEEDS) and np.all(np.isfinite(d["sem"]))
        q = QUICK.taps // 4
        gains.append(d["mean"][-q:].mean() - d["mean"][0])
        fit = table[("a", f"fit:{label}")]
        assert np.all(np.isfinite(fit["mean"])) and fit["x"].min() >= 1
        for p in ("X_inf", "dX_inf", "B", "tau", "reduced_chi2"):
            assert ("params", f"{label}:{p}") in table
        # what the fits can say: profile intervals, range refits, and <Z> with eq. 4
        for p in ("X_inf", "dX_inf", "B", "tau"):
            for suffix in ("lo", "hi", "range_deviation", "range_spread"):
                assert ("params", f"{label}:{p}:{suffix}") in table
            value, err, determined = param(table, f"{label}:{p}")
            assert determined in (0, 1) and (determined or np.isnan(err))
        z = table[("c", label)]
        assert np.array_equal(z["x"], d["x"]) and np.all(z["mean"] > 0)
        assert ("c", f"fit:{label}") in table and ("params", f"{label}:Z:B:lo") in table
    for law in ("eq3", "eq4"):
        assert len(table[("B", f"{law}:B")]["x"]) == len(data)
        assert ("B", f"{law}:p_value") in table and ("B", f"{law}:reduced_chi2") in table
    # tapping compacts: Phi_b after the taps exceeds the initial value on average over eps
    assert np.mean(gains) > 0.005


def test_fig3_fluctuations_of_z(campaign, out_dir):
    table = draw(campaign, out_dir, "fig3")
    spectra = series(table, "a", "eps=")
    assert len(spectra) == len(QUICK.steady_eps)
    for d in spectra.values():
        assert np.all((d["x"] > 0) & (d["x"] <= 0.5)) and np.all(np.diff(d["x"]) > 0)
        assert np.all(d["mean"] > 0)
    slopes = [param(table, f"{label}:slope")[0] for label in spectra]
    assert np.mean(slopes) < 0  # more power at low frequencies (paper: slope -1 to -1.5)
    sig = table[("b", "sigma_Z")]
    assert np.allclose(sig["x"] ** 2, sorted(QUICK.steady_eps))
    assert np.all(sig["mean"] > 0) and np.all(sig["n"] == SEEDS)
    # the fluctuations grow with the excitation (paper: sigma_<Z> proportional to sqrt(eps))
    assert sig["mean"][-1] > 2 * sig["mean"][0]
    k, k_err, _ = param(table, "k")
    assert k > 0 and k_err > 0


def test_fig4_steady_state_and_hysteresis(campaign, out_dir):
    table = draw(campaign, out_dir, "fig4")
    steady = table[("a", "steady")]
    assert np.allclose(steady["x"], np.sqrt(sorted(QUICK.steady_eps)))
    assert np.all((steady["mean"] > 0.55) & (steady["mean"] < 0.65))
    levels = [QUICK.ramp_sqrt0 + k * QUICK.ramp_dsqrt for k in range(QUICK.ramp_levels)]
    up1, down, up2 = (table[("a", b)] for b in ("up1", "down", "up2"))
    assert np.allclose(up1["x"], levels)
    assert np.allclose(down["x"], levels[:-1]) and np.allclose(up2["x"], levels[1:])
    for d in (up1, down, up2):
        assert np.all((d["mean"] > 0.55) & (d["mean"] < 0.65)) and np.all(d["n"] == SEEDS)
    # the bell's maximum: a parabola's vertex with its error, or, untested, the highest square
    top, err, _ = param(table, "sqrt_eps_max")
    assert steady["x"].min() <= top <= steady["x"].max()
    assert np.isfinite(err) or top in steady["x"]


def test_fig5_ageing(campaign, out_dir):
    table = draw(campaign, out_dir, "fig5")
    curves = series(table, "a", "tw=")
    assert sorted(float(s[3:]) for s in curves) == sorted(QUICK.ageing_waiting_times)
    grow = []
    for d in curves.values():
        assert d["x"][0] == 0 and d["mean"][0] == 0  # A(0, t_W) = 0 exactly
        assert np.all(d["mean"] >= 0) and np.all(d["n"] == SEEDS)
        grow.append(d["mean"][-10:].mean() - d["mean"][1:4].mean())
    assert np.mean(grow) > 0  # the packing drifts away from its state at t_W
    # the scaling variable: exponents with their intervals, the collapse against no rescaling
    for tag in ("scaling", "scaling_time"):
        mu, _, _ = param(table, f"{tag}:mu")
        assert np.isfinite(mu) and np.isfinite(param(table, f"{tag}:reduced_chi2")[0])
        assert ("params", f"{tag}:mu:lo") in table and ("params", f"{tag}:mu:jackknife") in table
    assert np.isfinite(param(table, "unscaled:reduced_chi2")[0])
    rescaled = series(table, "b", "tw=")
    assert sorted(rescaled) == sorted(s for s in curves if float(s[3:]) > 0)
    assert np.all(np.isfinite(table[("b", "eq6")]["mean"]))
    # the test across realizations: the realizations it needs, tested when there are enough
    full = param(table, "drawn:mu")[2] == 1
    needed = param(table, "scaling_test:needed")[0]
    assert needed == max(len(curves), (5 if full else 4) + 1) + 1   # bins >= curves, > params
    assert (("params", "scaling_test:T2") in table) == (SEEDS >= needed)
    # eq. 6 on each curve alone, across realizations, with the share of A that is drift
    assert param(table, "eq6_test:needed")[0] == 5
    for name in curves:
        tw = float(name[3:])
        if tw > 0:
            assert (("params", f"eq6_test:tw={tw:g}:p_value") in table) == (SEEDS >= 5)
            assert (("params", f"drift_share:tw={tw:g}") in table) == (SEEDS >= 5)
            assert (("params", f"eq6_test_long:tw={tw:g}:p_value") in table) == (SEEDS >= 5)


def test_fig6_vertical_profiles(campaign, out_dir):
    table = draw(campaign, out_dir, "fig6")
    init, final = table[("a", "initial")], table[("a", "final")]
    assert np.array_equal(init["x"], final["x"]) and init["x"][0] < 0.5
    for d in (init, final):
        assert np.all((d["mean"] >= 0) & (d["mean"] < 0.78))
        assert d["mean"][-1] < 0.01  # above the free surface
        lo, hi = param(table, "window_lo")[0], param(table, "window_hi")[0]
        bulk = d["mean"][(d["x"] >= lo) & (d["x"] <= hi)]
        assert 0.45 < bulk.mean() < 0.66
    assert param(table, "eps")[0] == max(QUICK.profile_eps)
    for tag in ("initial", "final"):
        alpha, alpha_sem, n = param(table, f"{tag}:alpha")
        assert np.isfinite(alpha) and abs(alpha) < 0.05 and n == SEEDS
    # each seed's final alpha with the lateral jackknife of its own packing
    seeds = table[("params", "final:alpha:seeds")]
    assert len(seeds["mean"]) == SEEDS >= 2 and np.all(seeds["n"] == 1)
    assert np.mean(seeds["mean"]) == pytest.approx(param(table, "final:alpha")[0], abs=1e-9)
    assert np.all(np.isfinite(seeds["sem"]) & (seeds["sem"] > 0))
    assert ("params", "initial:alpha:seeds") not in table
    assert ("a", "fit:final") in table
    # open symbols: alpha at the end of every level of the ramp, per branch
    ramps = [s for s in campaign.runs if s.name.startswith("ramp_")]
    sq = QUICK.ramp_sqrt0 + QUICK.ramp_dsqrt * np.arange(QUICK.ramp_levels)
    for branch, levels in (("up1", sq), ("down", sq[:-1]), ("up2", sq[1:])):
        d = table[("b", f"ramp:{branch}")]
        np.testing.assert_allclose(d["x"], levels)
        assert np.all(np.abs(d["mean"]) < 0.05) and np.all(d["n"] == len(ramps))
        assert np.all(np.isfinite(d["sem"]) & (d["sem"] > 0))


def test_fig7_transversal_profiles(campaign, out_dir):
    table = draw(campaign, out_dir, "fig7")
    init, final = table[("a", "initial")], table[("a", "final")]
    assert init["x"].min() > 0 and init["x"].max() < QUICK.L
    for d in (init, final):
        assert np.all((d["mean"] > 0) & (d["mean"] < 0.8))
        # wall layer: the cut planes nearest the walls meet only sphere caps
        assert d["mean"][0] < 0.3 and d["mean"][-1] < 0.3
    assert param(table, "frontier_lo")[0] == 7.0
    assert param(table, "frontier_hi")[0] == QUICK.L - 7.0


def test_fig8_lateral_and_central_increases(campaign, out_dir):
    table = draw(campaign, out_dir, "fig8")
    lat, cen = series(table, "a", "eps="), series(table, "b", "eps=")
    assert sorted(eps_of(s) for s in lat) == sorted(QUICK.profile_eps) and lat.keys() == cen.keys()
    later = []
    for label in lat:
        for d in (lat[label], cen[label]):
            assert d["x"][0] == 0 and d["mean"][0] == 0  # relative to the initial packing
            assert np.all(np.abs(d["mean"]) < 0.1)
        later.append(lat[label]["mean"][-QUICK.taps // 4:].mean() - lat[label]["mean"][1])
    assert np.mean(later) > 0  # the side zones densify after the first tap


@needs_pores
def test_fig9_p0_against_percus_yevick(campaign, out_dir):
    table = draw(campaign, out_dir, "fig9")
    for key in ("initial", "final"):
        d = table[("a", key)]
        assert d["x"][0] == 0 and d["mean"][0] == 1.0  # P0(0) = 1
        assert np.all(np.diff(d["mean"]) <= 1e-12)  # P0 decreases with sigma
        phi = param(table, f"phi_{key}")[0]
        assert 0.5 < phi < 0.66
        inside = d["x"] <= 1.0  # eq. 8 is exact below contact
        assert np.allclose(d["mean"][inside], 1 - phi * d["x"][inside] ** 3, atol=0.01)
    py = table[("a", "percus_yevick")]
    phi = param(table, "phi_final")[0]
    assert np.allclose(py["mean"][py["x"] <= 1], 1 - phi * py["x"][py["x"] <= 1] ** 3)
    assert np.all(np.diff(py["mean"]) <= 0)


@needs_pores
def test_fig10_pore_volume_distributions(campaign, out_dir):
    table = draw(campaign, out_dir, "fig10")
    curves = series(table, "a", "t=")
    steps = sorted(int(s[2:]) for s in curves)
    assert steps == [0, *QUICK.dump_times]
    for label, d in curves.items():
        assert np.all(d["mean"] >= 0)
        # no pore smaller than a tetrahedral site (one histogram bin of slack)
        assert np.all(d["mean"][d["x"] < _plotting.XI_T - 0.01] == 0)
        step = int(label[2:])
        nu = table[("params", "nu")]
        nu_t = nu["mean"][nu["x"] == step][0]
        integral = np.sum(d["mean"] * np.gradient(d["x"]))
        assert integral == pytest.approx(nu_t, rel=0.1)  # nu = integral of xi^3 P(xi)
        # the paper's rho_v(v) = (xi/3) P(xi) (section IV.B) integrates to nu, not to 1: the tool
        # sums the pores' v in each bin, so this holds to the CSV's 10 digits when no pore is
        # beyond --xi-max (the statistics box keeps off the free surface)
        rho_v = table[("b", label)]
        assert np.sum(rho_v["mean"] * np.gradient(rho_v["x"])) == pytest.approx(nu_t, rel=1e-6)
    xi_min = table[("params", "xi_min")]
    assert np.all(xi_min["mean"] >= _plotting.XI_T - 1e-3)
    large = table[("params", "large")]
    assert large["mean"][-1] < large["mean"][0]  # the tail of large pores shrinks


@needs_pores
def test_validation_report(campaign, out_dir, tmp_path):
    # The figures the tests above drew are handed to the report (copies: report() moves
    # them); one run alone (-k) has none and the report draws them all.
    drawn = {}
    for name in FIGURES:
        png, csv = out_dir / f"{name}.png", out_dir / f"{name}.csv"
        if png.exists() and csv.exists():
            drawn[name] = tuple(Path(shutil.copy(f, tmp_path / f.name)) for f in (png, csv))
    rst = validation.report(campaign, tmp_path, drawn=drawn)
    text = rst.read_text()
    assert text.startswith(".. TAPMC:")
    assert "the ``quick`` preset" in text and "N = 512" in text
    for name in FIGURES:
        assert f".. image:: validation/{name}.png" in text
        check_png(tmp_path / "validation" / f"{name}.png")
        assert (tmp_path / "validation" / f"{name}.csv").exists()
    # every claim of the register has its row, measured on the quick campaign's CSVs
    for claim in claims.load_register():
        assert claim.claim in text
    for quantity in ("the initial P.B.C. packing has <Phi^c> = 58.4 %", "maximum between",
                     "power law of slope", "negative gradient", "smaller than the tetrahedral",
                     "small pores"):
        assert quantity in text
    assert "/tmp" not in text and str(campaign.directory) not in text
    verdicts = [line for line in text.splitlines() if line.strip().startswith("- ")
                and ("agrees" in line or "disagrees" in line or "undecided" in line)]
    assert len(verdicts) >= 15


def test_draw_refuses_a_campaign_without_its_runs(tmp_path):
    spec = _runs.constant_eps_run(QUICK, "pbc", 0.01, 1)
    camp = Campaign(tmp_path, [spec], lmp=os.environ.get("TAPMC_LMP"))
    with pytest.raises(ValueError, match="no constant-eps fbc run"):
        MODULES["fig2"].draw(camp, tmp_path / "out")
