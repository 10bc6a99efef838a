# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""tapmc.tube_runs and tapmc.paper.tube on synthetic outputs of examples/cylinder: the settings
from a log, the compaction curve of taps.dat (its figure's PNG, and a CSV holding the plotted
numbers), the reader of profile_r.dat and its figure, and examples/cylinder/plot_tube.py."""

import csv
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", HERE.parent.parent))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

import matplotlib  # noqa: E402

matplotlib.use("Agg")

from tapmc.cylinder import Cylinder  # noqa: E402
from tapmc.laws import InverseLogLaw  # noqa: E402
from tapmc.paper.tube import compaction_figure, radial_profile_figure  # noqa: E402
from tapmc.readers import AveTime, TapmcFormatError  # noqa: E402
from tapmc.tube_runs import RadialProfiles, TubeCompaction, TubeSettings  # noqa: E402

# the commands a log of in.cylinder echoes, before and after variable substitution
LOG = """LAMMPS (29 Sep 2021 - Update 2)
region          tube cylinder z $(v_Rc) $(v_Rc) $(v_Rc) INF INF
region          tube cylinder z 4 4 4 INF INF
create_packing  ${N} 1 ${R} ${seed} floor 0.0 container tube
create_packing  1200 1 0.5 7 floor 0.0 container tube
fix             tap all tapdilate ${eps} floor 0.0 container tube
fix             tap all tapdilate 0.0225 floor 0.0 container tube
fix             settle all mc/settle 7 floor 0.0 eta ${eta} container tube
fix             settle all mc/settle 7 floor 0.0 eta 1e-5 container tube
compute         phi all stereo/profile floor 0.0 container tube
run             ${taps}
run             60
"""
TAPS = 60


def write_run(folder, taps=TAPS):
    """taps.dat (eq. 3 curves, the core NaN at t = 0 as a tube without core would print it
    never; here a core), profile_r.dat (two blocks of 8 annuli) and log.lammps."""
    folder = Path(folder)
    t = np.arange(taps + 1.0)
    phi_c = InverseLogLaw.function(t, 0.60, 0.05, 0.5, 3.0)
    rows = np.column_stack([t, phi_c - 0.04, phi_c, 20 - 0.3 * np.log1p(t), phi_c - 0.01,
                            phi_c + 0.02, 100 + t])
    with open(folder / "taps.dat", "w") as f:
        f.write("# step Phi_b <Phi^c> <Z> phi_wall phi_core sweeps\n")
        for row in rows:
            f.write(" ".join(f"{v:.8f}" if k else f"{int(v)}" for k, v in enumerate(row)) + "\n")
    r = 0.25 + 0.5 * np.arange(8)
    with open(folder / "profile_r.dat", "w") as f:
        f.write("# Time-averaged data for fix rprof\n# TimeStep Number-of-rows\n"
                "# Row c_rprof[1] c_rprof[2] c_rprof[3]\n")
        for step, shift in ((0, 0.0), (taps, 0.01)):
            f.write(f"{step} 8\n")
            for k, rk in enumerate(r):
                f.write(f"{k + 1} {rk} {0.58 + shift - 0.02 * k} {0.59 + shift - 0.02 * k}\n")
    (folder / "log.lammps").write_text(LOG)
    return rows, r


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_settings_from_the_log(tmp_path):
    write_run(tmp_path)
    s = TubeSettings.from_log(tmp_path / "log.lammps")
    assert (s.n, s.sphere_radius, s.eps, s.eta, s.seed, s.taps) == (1200, 0.5, "0.0225", "1e-5",
                                                                   "7", 60)
    assert s.cylinder == Cylinder(4.0, 4.0, 4.0) and s.wall_zone_start == 0.5
    assert s.describe() == ("N = 1200, tube D = 8 (8 bead diameters), eps = 0.0225, "
                            "eta = 1e-5, stop change (default), seed = 7, 60 taps")
    assert TubeSettings.from_log(tmp_path / "missing.log").describe() == (
        "N = ?, tube D = ?, eps = ?, eta = ?, stop ?, ? taps")
    # a run in a box is not described as a tube of unknown diameter
    box_log = SOURCE / "examples" / "tapping" / "log.29Nov26.tapping_pbc.g++.1"
    with pytest.raises(ValueError, match="not a run in a tube .*container ID"):
        TubeSettings.from_log(box_log)


def test_settings_state_a_stop_rule_and_dmax_the_input_sets(tmp_path):
    write_run(tmp_path)
    log = tmp_path / "log.lammps"
    text = log.read_text()
    assert "mc/settle 7 " in text
    log.write_text(text.replace("mc/settle 7 ", "mc/settle 7 stop drift dmax 0.1 "))
    assert ", stop drift, dmax 0.1, seed = 7" in TubeSettings.from_log(log).describe()


def test_from_log_takes_a_log_read_by_read_log():
    """The docs write from_log(log): a Log (read_log's) ended in a raw TypeError of pathlib.
    It is read from the path it carries; anything else is named."""
    from tapmc.readers import read_log
    log_path = SOURCE / "examples" / "cylinder" / "log.29Nov26.cylinder.g++.1"
    log = read_log(log_path, strict=False)
    assert Cylinder.from_log(log) == Cylinder.from_log(log_path) == Cylinder(5.0, 5.0, 5.0)
    assert TubeSettings.from_log(log) == TubeSettings.from_log(log_path)
    with pytest.raises(TypeError, match="from_log takes a log's path or a Log, got int"):
        Cylinder.from_log(3)


def test_compaction_curve_and_its_figure(tmp_path):
    rows, _ = write_run(tmp_path)
    curve = TubeCompaction.from_file(tmp_path / "taps.dat").compute()
    assert curve.settings.taps == TAPS and curve.settings.n == 1200
    assert curve.initial["phi_core"] == pytest.approx(rows[0, 5])
    assert curve.change["<Phi^c>"] == pytest.approx(rows[-1, 2] - rows[0, 2])
    fit = curve.fit_result
    assert fit.params["X_inf"] == pytest.approx(0.60, abs=1e-4)
    ax = curve.plot()
    assert ax.get_xlabel() == "tap t" and ax.get_ylabel() == "packing fraction"
    assert "N = 1200" in ax.get_title() and "eta = 1e-5" in ax.get_title()
    assert "60 taps" in ax.get_title() and "tube D = 8" in ax.get_title()
    png, csv_path = compaction_figure(curve, tmp_path / "out" / "tube_compaction")
    assert png.stat().st_size > 10_000 and png.read_bytes()[:4] == b"\x89PNG"
    table = read_csv(csv_path)
    series = {}
    for row in table:
        series.setdefault((row["panel"], row["series"]), []).append(
            (float(row["x"]), float(row["mean"])))
    assert set(series) == {("a", "Phi_b"), ("a", "<Phi^c>"), ("a", "phi_wall"),
                           ("a", "phi_core"), ("a", "fit:<Phi^c>"), ("b", "<Z>")}
    for (panel, name), column in ((("a", "Phi_b"), 1), (("a", "<Phi^c>"), 2), (("b", "<Z>"), 3),
                                  (("a", "phi_wall"), 4), (("a", "phi_core"), 5)):
        x, y = np.array(series[(panel, name)]).T
        np.testing.assert_array_equal(x, rows[1:, 0])          # taps >= 1: the log axis
        np.testing.assert_allclose(y, rows[1:, column], atol=1e-8)     # taps.dat's %.8f
        np.testing.assert_allclose(y, curve.curves[name][1:], rtol=1e-9)
    x, y = np.array(series[("a", "fit:<Phi^c>")]).T
    np.testing.assert_allclose(y, fit(x), rtol=1e-9)


def test_compaction_arguments_are_checked(tmp_path):
    with pytest.raises(ValueError, match="Phi_b has 2 values but .*taps has 3|taps has 3 values"):
        TubeCompaction([0, 1, 2], [0.5, 0.5], [0.5] * 3, [1] * 3, [0.5] * 3, [0.5] * 3)
    with pytest.raises(ValueError, match="taps must increase"):
        TubeCompaction([0, 2, 1], *([[0.5] * 3] * 5))
    short = TubeCompaction([0, 1, 2], *([[0.5] * 3] * 5)).compute()
    assert short.fit_result is None and short.settings.taps == 2
    (tmp_path / "bad.dat").write_text("# a b c\n1 2 3\n")
    with pytest.raises(KeyError, match="no column 'step'"):
        TubeCompaction.from_file(tmp_path / "bad.dat")


def test_radial_profiles_reader_and_figure(tmp_path):
    _, r = write_run(tmp_path)
    profiles = RadialProfiles.from_file(tmp_path / "profile_r.dat")
    assert list(profiles.steps) == [0, TAPS] and profiles.phi.shape == (2, 8)
    np.testing.assert_allclose(profiles.r, r)
    np.testing.assert_allclose(profiles.edges, np.linspace(0, 4, 9))
    first = profiles.profile(0)
    assert first.axis == "r" and first.step == 0 and first.cylinder == Cylinder(4, 4, 4)
    np.testing.assert_allclose(first.rows[:, 2], 0.59 - 0.02 * np.arange(8))
    with pytest.raises(ValueError, match="index = 2 outside the 2 profiles"):
        profiles.profile(2)
    ax = profiles.plot()
    assert ax.get_xlabel().startswith("distance from the axis")
    assert "annulus volume fraction" in ax.get_ylabel() and "60 taps" in ax.get_title()
    png, csv_path = radial_profile_figure(profiles, tmp_path / "tube_profile_r")
    assert png.read_bytes()[:4] == b"\x89PNG"
    table = read_csv(csv_path)
    assert {row["series"] for row in table} == {"t=0", f"t={TAPS}"}
    last = [(float(row["x"]), float(row["mean"])) for row in table if row["series"] == f"t={TAPS}"]
    np.testing.assert_allclose(np.array(last), np.column_stack([r, profiles.phi[1]]))
    scalar = AveTime(["c_phi[1]"], steps=[0, 1], data=np.zeros((2, 1)))
    with pytest.raises(ValueError, match="expected a vector-mode fix ave/time table"):
        RadialProfiles.from_ave_time(scalar)
    (tmp_path / "cut.dat").write_text("# Time-averaged data\n# TimeStep Number-of-rows\n"
                                      "# Row c_r[1] c_r[2] c_r[3]\n0 2\n1 0.5 0.6\n")
    with pytest.raises(TapmcFormatError):
        RadialProfiles.from_file(tmp_path / "cut.dat")


def test_plot_tube_script(tmp_path):
    write_run(tmp_path)
    env = dict(os.environ, PYTHONPATH=str(SOURCE / "tools" / "python"))
    script = SOURCE / "examples" / "cylinder" / "plot_tube.py"
    proc = subprocess.run([sys.executable, str(script), str(tmp_path)], capture_output=True,
                          text=True, env=env, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert "N = 1200, tube D = 8 (8 bead diameters)" in proc.stdout
    for name in ("tube_compaction.png", "tube_compaction.csv", "tube_profile_r.png",
                 "tube_profile_r.csv"):
        assert (tmp_path / name).stat().st_size > 0
    (tmp_path / "taps.dat").write_text("")
    proc = subprocess.run([sys.executable, str(script), str(tmp_path)], capture_output=True,
                          text=True, env=env, timeout=120)
    assert proc.returncode == 1 and "taps.dat: empty file" in proc.stderr
