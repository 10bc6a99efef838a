# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The report's questions settled by measurement (tapmc.paper.questions): the conclusions are
computed from the CSVs, and each can come out either way."""

import os
import sys
from pathlib import Path

import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc.paper import _plotting, claims, cli, questions  # noqa: E402
from tapmc.paper.questions import common, launch, pbc_course, ramp_levels  # noqa: E402


def question(*argv):
    """``tapmc-paper question ARGV``, asserted to succeed."""
    assert cli.main(["question", *map(str, argv)]) == 0


def first_tap_csv(folder, drop_loose, drop_tight):
    lines = ["eps,eta,seed,phi_c_0,phi_c_1,Z_0,Z_1,sweeps_1"]
    for eta, drop in ((1e-7, drop_loose), (1e-9, drop_tight)):
        for seed, jitter in ((1, -0.0002), (2, 0.0), (3, 0.0002)):
            lines.append(f"0.15,{eta:g},{seed},0.583,{0.583 + drop + jitter},7.3,7.4,5000")
    (folder / "first_tap.csv").write_text("\n".join(lines) + "\n")


def test_first_tap_drop_that_survives_a_tight_eta_is_the_model(tmp_path):
    first_tap_csv(tmp_path, -0.012, -0.010)
    text = "\n".join(questions.render_section(tmp_path))
    assert "Questions settled by measurement" in text
    assert "83 % of the change" in text and "a property of the model" in text


def test_first_tap_drop_that_vanishes_is_the_stopping_rule(tmp_path):
    first_tap_csv(tmp_path, -0.012, -0.0001)
    text = "\n".join(questions.render_section(tmp_path))
    assert "not distinguishable from an effect of the stopping rule" in text


def test_noise_floor_against_fig3(tmp_path):
    (tmp_path / "noise_floor.csv").write_text(
        "quantity,value\nsigma_Z,0.001\nsigma_Z_detrended,0.0003\ndrift_per_tap,-6e-06\n"
        "Z_first,6.94\nZ_last,6.934\ntaps,1000\nmean_sweeps,8.4\nspectral_slope,-2.0\n"
        "spectral_slope_detrended,-1.9\n")
    fig3 = claims.FigureData({("params", "k"): {"x": [0.0], "mean": [0.05], "sem": [0.001],
                                                "n": [5]}})
    text = "\n".join(questions.render_section(tmp_path, {"fig3": fig3}))
    assert "sigma_<Z> = 0.001" in text and "sqrt(eps) = 0.02" in text
    assert "slope -2.00 (-1.90 detrended): a slow creep" in text


def test_spectral_window_says_whether_the_window_moves_the_slope(tmp_path):
    (tmp_path / "spectral_window.csv").write_text(
        "run,eps,taps,window,slope,slope_error\n"
        "a,0.01,4000,250,-1.10,0.15\na,0.01,4000,1000,-1.12,0.10\n"
        "b,0.1,4000,250,-0.70,0.05\nb,0.1,4000,1000,-1.30,0.05\n")
    text = "\n".join(questions.render_section(tmp_path))
    assert "eps = 0.01 (4000 taps): W = 250: -1.1 ± 0.15, W = 1000: -1.12 ± 0.1; the window " \
           "moves it by less than twice its error." in text
    assert "eps = 0.1 (4000 taps)" in text and "beyond twice its error" in text


def test_a_question_csv_cut_mid_row_is_named_at_its_line(tmp_path):
    """A row with fewer or more fields than the header (a file cut mid-row, or damaged) raises
    at its line: read as dicts it gave None values and one claim's row went missing."""
    path = tmp_path / "q.csv"
    path.write_text("a,b,c\n1,2,3\n4,5\n")
    with pytest.raises(common.QuestionError, match=r"q.csv:3: 2 fields, the header has 3"):
        common.read_csv(path)
    path.write_text("a,b,c\n1,2,3,4\n")
    with pytest.raises(common.QuestionError, match=r"q.csv:2: 4 fields, the header has 3"):
        common.read_csv(path)
    path.write_text("a,b,c\n1,,3\n")   # an empty field is a field
    assert common.read_csv(path) == [{"a": "1", "b": "", "c": "3"}]


def test_out_a_file_is_refused_before_the_analysis(tmp_path, capsys):
    (tmp_path / "afile").write_text("")
    status = cli.main(["question", "pbc-course", "--campaign", str(tmp_path / "none"),
                       "--out", str(tmp_path / "afile")])
    assert status == 2
    assert f"--out {tmp_path / 'afile'} is a file, not a folder" in capsys.readouterr().err


def test_a_missing_taps_file_is_named_as_missing(tmp_path):
    """(it read "damaged gzip file ([Errno 2] ...)")"""
    with pytest.raises(common.QuestionError, match=r"taps.dat: no such file$"):
        common.taps_table(tmp_path / "run" / "taps.dat")


def test_nothing_to_render_without_the_csvs(tmp_path):
    assert questions.render_section(tmp_path) == []


def _front_rows(biases):
    """Rows of a front summary at N = 1024, eps = 0.0225: setting -> steady <Phi^c> bias."""
    return [{"setting": name, "N": 1024.0, "eps": 0.0225, "phi_c_steady_bias": bias,
             "phi_c_steady_bias_se": 0.0005, "cpu_per_tap": cpu, "paired_seeds": 4.0}
            for cpu, (name, bias) in enumerate(biases.items(), start=1)]


def _fig9(phi):
    return claims.FigureData({("params", "phi_c_steady"): {"x": [0.0], "mean": [phi],
                                                           "sem": [0.0002], "n": [1]}})


def test_final_phi_c_carried_to_every_threshold_of_the_front(tmp_path):
    first_tap_csv(tmp_path, -0.012, -0.010)
    rows = _front_rows({"change 1e-5": -0.0124, "change 1e-7 (default)": -0.0044,
                        "dmax R/2": -0.02, "drift 1e-7": 0.0})
    text = "\n".join(questions.render_section(tmp_path, {"fig9": _fig9(0.6086)}, [1e-7], rows))
    # 60.86 % at eta = 1e-7; eta = 1e-5 is 0.80 % lower, the reference 0.44 % higher
    assert "60.06 ± 0.07 %" in text and "61.30 ± 0.07 %" in text
    assert "lies inside the range the thresholds span" in text and "closest: change 1e-5" not in text
    assert "dmax" not in text  # d_max is the model's parameter, not a threshold
    # a paper value no threshold reaches
    far = "\n".join(questions.render_section(tmp_path, {"fig9": _fig9(0.640)}, [1e-7], rows))
    assert "lies outside the range" in far and "no redeposition threshold explains" in far
    # nothing to say without the front, or for a campaign of several eta
    assert "threshold" not in "\n".join(questions.render_section(tmp_path, {"fig9": _fig9(0.6)},
                                                                  [1e-7], []))
    assert "threshold" not in "\n".join(questions.render_section(tmp_path, {"fig9": _fig9(0.6)},
                                                                  [1e-7, 1e-5], rows))


def scan_csv(path, column, values, settings, sweeps):
    """A knob scan of 3 seeds: per value (value, scale of the knob, gain, jitter per seed); every
    seed shifts all gains alike (paired); sweeps(value) per tap."""
    lines = [f"{column},{column.split('_over_')[0]},seed,N,eps,taps,eta,stop,phi_c_0,phi_c_end,"
             "sweeps_per_tap"]
    for seed, shift in ((1, -0.001), (2, 0.0), (3, 0.001)):
        for value, scale, gain, jitter in values:
            lines.append(f"{value},{value * scale},{seed},1024,0.0225,100,{settings},0.58,"
                         f"{0.58 + gain + shift + jitter * seed},{sweeps(value)}")
    path.write_text("\n".join(lines) + "\n")


def test_theta0_scan_table_and_verdict(tmp_path):
    scan_csv(tmp_path / "theta0.csv", "theta0_over_pi",
             ((0.0625, 3.14159, -0.02, 0.0002), (0.25, 3.14159, 0.01, -0.0001),
              (0.5, 3.14159, 0.004, 0.0001)), "1e-7,change", lambda v: 1000 + 2000 * v)
    text = "\n".join(questions.render_section(tmp_path))
    assert "``theta0``" in text and "   * - pi/16" in text and "   * - pi/2" in text
    assert "-1.96 ± 0.07 %" in text          # pi/16: gain -0.02 + jitter 0.0002 x mean seed 2
    assert "takes more sweeps" not in text    # pi/4 compacts most here: nothing to explain
    assert "Verdict of the claim (rule pattern, t sem with 3 seeds): agrees" in text


def test_theta_laws_side_by_side_with_their_mean_angles(tmp_path):
    from tapmc.paper.questions import theta0
    pi = 3.14159
    scan_csv(tmp_path / "theta0.csv", "theta0_over_pi",
             ((0.0625, pi, -0.02, 0.0002), (0.25, pi, 0.01, -0.0001), (0.5, pi, 0.004, 0.0001)),
             "1e-7,change", lambda v: 1000 + 2000 * v)
    # the linear law: none without eq. 1's scan of its size, nothing at all without a law
    assert theta0.render_laws(tmp_path) == []
    scan_csv(tmp_path / "theta0_linear_N4096.csv", "theta0_over_pi",
             ((0.0625, pi, -0.03, 0.0), (0.5, pi, 0.01, 0.0)), "1e-7,change", lambda v: 1000)
    assert theta0.law_scans(tmp_path) == {}
    scan_csv(tmp_path / "theta0_linear.csv", "theta0_over_pi",
             ((0.0625, pi, -0.03, 0.0002), (0.25, pi, -0.01, 0.0001), (0.5, pi, 0.01, 0.0)),
             "1e-7,change", lambda v: 1000)
    assert list(theta0.law_scans(tmp_path)) == [""]
    (png,) = theta0.write_laws_figure(tmp_path)
    assert png.name == "theta_laws.png" and png.stat().st_size > 10000
    # beside it, every number it draws: the linear law at pi/4, -0.98 % at <theta> = 15 deg
    from tapmc.paper._plotting import figure_csv_rows
    rows = figure_csv_rows(tmp_path / "theta_laws_figure.csv")
    (a,) = [r for r in rows if r[1:3] == ("a", "linear") and r[3] == 0.25]
    (b,) = [r for r in rows if r[1:3] == ("b", "linear") and abs(r[3] - 15.0) < 1e-5]
    assert a[4] == b[4] == pytest.approx(-0.98, abs=0.005) and a[6] == 3
    text = "\n".join(questions.render_section(tmp_path))
    assert "The laws of theta (theta-law-shape)" in text
    assert "``theta0.csv`` and ``theta0_linear.csv``" in text
    # pi/4 under the linear law: <theta> = theta0 / 3 = 15 degrees; eq. 1's 25.0
    assert "-0.98 ± 0.06 % (15.0 deg)" in text and "(25.0 deg)" in text
    assert ("Verdict of ``theta-law-shape`` (rule pattern): linear P(theta) against eq. 1's: "
            "agrees at N = 1024, below the paper's N") in text
    assert "validation/" + tmp_path.name + "/theta_laws.png" in text
    # the theta0 claim itself does not read the other laws
    assert text.count("Verdict of the claim (rule pattern") == 1


def test_dmax_scan_table_and_verdict(tmp_path):
    scan_csv(tmp_path / "dmax_drift.csv", "dmax_over_R",
             ((0.02, 0.5, 0.001, 0.0002), (0.2, 0.5, 0.01, -0.0001), (1.0, 0.5, 0.002, 0.0001)),
             "1e-7,drift", lambda v: 1800 + 100 * v)
    text = "\n".join(questions.render_section(tmp_path))
    assert "``dmax``" in text and "``dmax_drift.csv``" in text and "stop drift, eta = 1e-07" in text
    assert "   * - R/50" in text and "   * - R/5" in text and "   * - R\n" in text
    # R/5 compacts more than both ends: both measures agree (rule sign)
    assert ("Verdict of the claim (rule sign, t sem with 3 seeds): agrees; agrees at N = 1024, "
            "below the paper's N") in text


def test_final_phi_c_uses_the_largest_N_with_error_bars(tmp_path):
    first_tap_csv(tmp_path, -0.012, -0.010)
    rows = _front_rows({"change 1e-5": -0.0124, "change 1e-7 (default)": -0.0044, "drift 1e-7": 0.0})
    one_seed = [dict(r, N=4096.0, paired_seeds=1.0, phi_c_steady_bias_se=float("nan"))
                for r in _front_rows({"change 1e-7 (default)": -0.0015, "drift 1e-7": 0.0})]
    text = "\n".join(questions.render_section(tmp_path, {"fig9": _fig9(0.6086)}, [1e-7],
                                              rows + one_seed))
    assert "N = 1024, eps = 0.0225, steady window, 4 paired seeds" in text
    # with two seeds at N = 4096 that N is taken
    two = [dict(r, paired_seeds=2.0, phi_c_steady_bias_se=0.0005) for r in one_seed]
    text = "\n".join(questions.render_section(tmp_path, {"fig9": _fig9(0.6086)}, [1e-7], rows + two))
    assert "N = 4096, eps = 0.0225, steady window, 2 paired seeds" in text


def test_recovery_tap_ignores_single_taps_above_the_start():
    import numpy as np

    t = np.arange(200.0)
    phi = np.full(200, 0.560)
    phi[0] = 0.583
    phi[30] = 0.590                       # one noisy tap above the start is no recovery
    phi[120:] = 0.584                     # from tap 120 on it stays above
    assert pbc_course.recovery_tap(t, phi, phi[0]) == 120
    assert pbc_course.recovery_tap(t, np.minimum(phi, 0.58), phi[0]) is None


def pbc_course_csv(folder, strong_gain, strong_back, strong_halves):
    header = ("run,eps,seed,taps,phi_c_0,phi_c_min,tap_min,tap_back,phi_c_steady,"
              "phi_c_steady_sem,phi_c_steady_sd,steady_halves_diff,steady_halves_diff_sem")
    rows = ["a,0.005,1,4000,0.583,0.581,3,25,0.607,0.0002,0.001,0.0001,0.0003",
            "b,0.0225,1,4000,0.583,0.580,2,40,0.609,0.0002,0.001,0.0,0.0003",
            f"c,0.15,1,4000,0.583,0.568,4,{strong_back},{0.583 + strong_gain},0.0004,0.001,"
            f"{strong_halves},0.0005"]
    (folder / "pbc_course.csv").write_text("\n".join([header] + rows) + "\n")


def test_pbc_course_transient_loosening_still_compacting(tmp_path):
    pbc_course_csv(tmp_path, 0.004, 1391, 0.0032)
    text = "\n".join(questions.render_section(tmp_path))
    assert "``pbc-course``" in text
    assert "eps = 0.15: 1.50 % below t = 0, regains it from tap 1391" in text
    assert "The dip deepens and lengthens with eps." in text
    assert "2.20 ± 0.04 % below the largest (eps = 0.0225)" in text
    assert "still compacting at the end" in text
    assert "the loosening at strong taps is transient" in text
    assert "at eps = 0.15 part of the fall is a slower approach" in text


def test_pbc_course_loosening_that_lasts(tmp_path):
    pbc_course_csv(tmp_path, -0.002, "", 0.0)
    text = "\n".join(questions.render_section(tmp_path))
    assert "never regains it" in text and "does not lengthen steadily" in text
    assert "ends below its initial packing" in text
    assert "Its halves agree within their error: steady." in text
    assert "not undone by the taps" in text


def test_initial_packing_states_the_spread_one_packing_hides(tmp_path):
    rows = ["seed,N,L,bc,phi_b,phi_c,Z"] + [
        f"{s},4096,32,pbc,{0.542 + 0.001 * (s % 3)},{0.5827 + 0.0004 * (s % 5 - 2)},7.34"
        for s in range(1, 11)]
    (tmp_path / "initial_packing.csv").write_text("\n".join(rows) + "\n")
    text = "\n".join(questions.render_section(tmp_path))
    assert "``initial-packing``" in text
    assert "over 10 depositions" in text and "N = 4096, L = 32R" in text
    assert "<Phi^c> = 58.27 ± 0.02 % (one packing spreads 0.06 %)" in text
    assert "range 58.19 % to 58.35 %" in text and "The paper's 58.4 % is one packing's, +2.2" in text


def _p0_configs_csv(folder, tapped_sem):
    lines = ["sigma,initial,initial_sem,initial_n,tapped,tapped_sem,tapped_n"]
    lines += [f"{0.1 * i:.1f},{1 - 0.1 * i},0.002,8,{1 - 0.1 * i},{tapped_sem},8"
              for i in range(10)]
    lines.append("phi,0.5826,0.0003,8,0.6038,0.0002,8")
    (folder / "p0_configs.csv").write_text("\n".join(lines) + "\n")


def test_p0_configs_says_whether_the_tapped_configurations_are_independent(tmp_path):
    _p0_configs_csv(tmp_path, 0.0018)
    text = "\n".join(questions.render_section(tmp_path))
    assert "``p0-configs``" in text and "8 depositions at t = 0" in text
    assert "(Phi seen by the points 58.26 ± 0.03 %)" in text
    assert "0.90 times as much as one deposition" in text and "about as different" in text
    _p0_configs_csv(tmp_path, 0.0004)
    text = "\n".join(questions.render_section(tmp_path))
    assert "0.20 times" in text and "the configurations are correlated" in text


def _fig10(small, large, power=2.0, xi_t_fit=(0.2166, 0.002)):
    import numpy as np

    xi = np.linspace(0.005, 0.995, 100)
    curve = np.where(xi > _plotting.XI_T, np.abs(xi - _plotting.XI_T) ** power, 0.0) * 3.0
    table = {("a", "t=0"): {"x": list(xi), "mean": list(curve), "sem": [0.003] * 100,
                            "n": [1] * 100},
             ("a", "t=4000"): {"x": list(xi), "mean": list(curve), "sem": [0.003] * 100,
                               "n": [1] * 100}}
    for name, (a, b) in (("small", small), ("large", large), ("nu", (0.12, 0.10))):
        table[("params", name)] = {"x": [0, 4000], "mean": [a, b], "sem": [0.0003, 0.0003],
                                   "n": [1, 1]}
    table[("params", "xi_T")] = {"x": [0, 4000], "mean": [xi_t_fit[0]] * 2,
                                 "sem": [xi_t_fit[1]] * 2, "n": [1, 1]}
    return claims.FigureData(table)


def test_pores_small_against_large_and_the_quadratic_law(tmp_path):
    first_tap_csv(tmp_path, -0.012, -0.010)      # the section needs one question CSV
    text = "\n".join(questions.render_section(
        tmp_path, {"fig10": _fig10((0.0151, 0.0193), (0.106, 0.072))}))
    assert "Are the small pores (xi_T to xi_O) unaffected by the taps" in text
    assert "moves 8.1 times less" in text and "about as much" in text
    assert "departs from the histogram by 0.0 % rms" in text and "a fair description" in text
    assert "4.1 errors below the tetrahedral site" in text
    text = "\n".join(questions.render_section(
        tmp_path, {"fig10": _fig10((0.0151, 0.0155), (0.106, 0.072), power=0.5)}))
    assert "much less: the taps act on the large pores" in text
    assert "not a fair description of the shape" in text


def test_p0_configs_compares_the_difference_with_percus_yevicks_change(tmp_path):
    import numpy as np
    from tapmc.pores import percus_yevick_p0

    sigma = np.linspace(0, 2, 41)
    for tapped_phi, words in ((0.604, "about as their packing fractions predict"),
                              (0.583, "much less than their packing fractions predict")):
        lines = ["sigma,initial,initial_sem,initial_n,tapped,tapped_sem,tapped_n"]
        lines += [f"{x},{percus_yevick_p0(x, 0.582)},0.001,8,{percus_yevick_p0(x, tapped_phi)},"
                  "0.001,8" for x in sigma]
        lines.append("phi,0.582,0.0005,8,0.604,0.0005,8")
        (tmp_path / "p0_configs.csv").write_text("\n".join(lines) + "\n")
        text = "\n".join(questions.render_section(tmp_path))
        assert words in text, text


def test_lateral_first_tap_table_and_reading(tmp_path):
    lines = ["eps,seed,t,lateral,central,phi_c"]
    for eps in (0.005, 0.1):
        for seed in (1, 2, 3):
            for t, lat, cen in ((0, 0.550, 0.570), (1, 0.560, 0.571), (5, 0.562, 0.572)):
                lines.append(f"{eps},{seed},{t},{lat + 0.0001 * seed},{cen},0.58")
    (tmp_path / "lateral_first_tap.csv").write_text("\n".join(lines) + "\n")
    text = "\n".join(questions.render_section(tmp_path))
    assert "``lateral-first-tap``" in text and "tapped 5 times at each eps" in text
    assert "gains at the first tap at every eps, more than the central zone" in text
    assert "looser than the central zone by 1.98 %" in text


def test_ramp_levels_against_the_hysteresis_gap(tmp_path):
    (tmp_path / "ramp_levels.csv").write_text(
        "level,branch,sqrt_eps,taps,taps_long,phi_c,phi_c_sem,phi_c_long,phi_c_long_sem\n"
        "11,0,0.3,1000,4000,0.5950,0.0003,0.5960,0.0003\n"
        "16,1,0.175,1000,4000,0.6080,0.0003,0.6081,0.0003\n")
    x = [0.1, 0.2, 0.3]
    fig4 = claims.FigureData({("a", "up1"): {"x": x, "mean": [0.600, 0.600, 0.595],
                                             "sem": [0.0003] * 3, "n": [1] * 3},
                              ("a", "down"): {"x": x, "mean": [0.620, 0.620, 0.615],
                                              "sem": [0.0003] * 3, "n": [1] * 3}})
    text = "\n".join(questions.render_section(tmp_path, {"fig4": fig4}))
    assert "change against 4000 (the paper's)?" in text
    assert "ramp_pbc_s1: the longer levels move <Phi^c> by at most 0.10 ± 0.04 %; 1 of 2 " \
           "beyond their error" in text
    assert "gap of ramp_pbc_s1 (decrease minus first increase) is 2.00 %" in text
    assert "by less than a tenth of it" in text


def test_ramp_levels_of_two_ramps_bound_each_its_own_claims(tmp_path):
    """Rows of the ramp below (sqrt eps)* (column 'ramp') beside rows written before the
    column existed (the ramp beyond it): each ramp's summary and bounds read its own rows; the
    low ramp's turning level is the pseudo-branch 'top' of its frozen claim."""
    import numpy as np

    header = "level,branch,sqrt_eps,taps,taps_long,phi_c,phi_c_sem,phi_c_long,phi_c_long_sem"
    (tmp_path / "ramp_levels.csv").write_text(
        header + "\n11,0,0.3,1000,4000,0.5950,0.0003,0.5960,0.0003\n"
        "16,1,0.175,1000,4000,0.6080,0.0003,0.6081,0.0003\n")
    ramp_levels.save(tmp_path / "ramp_levels.csv", [
        [4, 0, "0.125", 1000, 4000, "0.6073", "0.0001", "0.6103", "0.0001", "run",
         "ramplow_pbc_s1"],
        [5, 1, "0.1", 1000, 4000, "0.6104", "0.0001", "0.6110", "0.0001", "run",
         "ramplow_pbc_s1"],
        [8, 1, "0.025", 1000, 4000, "0.6150", "0.0001", "0.6152", "0.0001", "run",
         "ramplow_pbc_s1"]])
    rows = claims.read_scan(tmp_path / "ramp_levels.csv")
    assert [(r["ramp"], r["level"], r["start"]) for r in rows][:2] == [
        ("ramp_pbc_s1", "11", "run"), ("ramp_pbc_s1", "16", "run")]
    text = "\n".join(questions.render_section(tmp_path))
    assert "ramplow_pbc_s1: the longer levels move <Phi^c> by at most 0.30 ± 0.01 %" in text
    fig4 = claims.FigureData({("params", "low:top_sqrt_eps"): {
        "x": np.array([0.0]), "mean": np.array([0.125]), "sem": np.array([np.nan]),
        "n": np.array([1])}})
    data = claims.ReportData({}, {"fig4": fig4}, questions={"ramp_levels": rows})
    low = claims.ramp_reduction_bounds(data, "low")
    assert low["top"][1] == [4] and low["down"][1] == [5, 8] and "up1" not in low
    assert low["top"][0] > 0.003 and 0.0006 < low["down"][0] < 0.001
    assert set(claims.ramp_reduction_bounds(data, "ramp")) == set()   # one level a branch


def integrity_csv(folder, overlaps=0, worst=0.9):
    header = ("run,tap,n,min_gap,overlaps,floor_gap,wall_gap,legal,resolution_rel,phi_c,"
              "scalars_worst,scalars_worst_column")
    legal = 1 if overlaps == 0 else 0
    rows = ["const_fbc_eps0.1_s1,0,4096,-1.05e-08,0,0,0,1,1.73e-08,0.5557,0.66,h_s",
            f"const_fbc_eps0.1_s1,4000,4096,{-2e-6 if overlaps else 2.6e-08},{overlaps},"
            f"8.4e-08,6.4e-07,{legal},1.73e-08,0.5767,{worst},h_s",
            "const_pbc_eps0.1_s1,0,4096,-1.26e-08,0,0,,1,1.73e-08,0.5829,0.79,z_top",
            "const_pbc_eps0.1_s1,4000,4096,4.2e-08,0,7e-08,,1,1.73e-08,0.6019,0.42,h_s"]
    (folder / "integrity.csv").write_text("\n".join([header] + rows) + "\n")


def test_integrity_of_legal_dumps_whose_scalars_match(tmp_path):
    integrity_csv(tmp_path)
    text = "\n".join(questions.render_section(tmp_path))
    assert "``integrity``" in text
    assert "4 dumps of 2 runs: every one holds 4096 spheres" in text
    assert "every one is a legal hard-sphere packing" in text
    assert "after taps the closest pair is 2.6e-08 of contact (const_fbc_eps0.1_s1, t = 4000)" \
        in text
    assert "largest: 0.90 of the allowance, h_s of const_fbc_eps0.1_s1 at t = 4000" in text
    assert "     - periodic" in text


def test_integrity_names_the_overlapping_dump_and_the_mismatched_print(tmp_path):
    integrity_csv(tmp_path, overlaps=3, worst=12.5)
    text = "\n".join(questions.render_section(tmp_path))
    assert "NOT all are legal: const_fbc_eps0.1_s1 t = 4000 (3 overlaps" in text
    assert "differ from the dumped packings' at const_fbc_eps0.1_s1 t = 4000 (h_s: 12.5 of " \
           "the allowance)" in text


def test_integrity_command_on_a_paper_scale_run_and_a_corrupted_copy(tmp_path):
    """tapmc-paper question integrity on a committed run of the campaign (its t = 0 and
    t = 4000 dumps and taps.dat), then on a copy with one sphere pushed into another."""
    import shutil

    import pytest

    run = SOURCE / "doc" / "validation" / "data" / "full" / "runs" / "const_pbc_eps0.0225_s1"
    if not (run / "dump.4000.lammpstrj").is_file():
        pytest.skip("campaign data absent")
    for name, corrupt in (("good", False), ("bad", True)):
        folder = tmp_path / name / "runs" / run.name
        folder.mkdir(parents=True)
        for f in ("dump.0.lammpstrj", "dump.4000.lammpstrj", "taps.dat"):
            shutil.copy(run / f, folder / f)
        if corrupt:   # sphere 2 onto sphere 1's centre, 0.1 above it
            lines = (folder / "dump.4000.lammpstrj").read_text().splitlines()
            first = next(k for k, line in enumerate(lines) if line.startswith("ITEM: ATOMS"))
            one = lines[first + 1].split()
            two = lines[first + 2].split()
            two[1:4] = one[1], one[2], f"{float(one[3]) + 0.1:.10g}"
            lines[first + 2] = " ".join(two)
            (folder / "dump.4000.lammpstrj").write_text("\n".join(lines) + "\n")
        question("integrity", "--campaign", tmp_path / name, "--out", tmp_path / name)
    good = common.read_csv(tmp_path / "good" / "integrity.csv")
    bad = common.read_csv(tmp_path / "bad" / "integrity.csv")
    assert [r["tap"] for r in good] == ["0", "4000"]
    assert all(r["legal"] == "1" and r["n"] == "4096" for r in good)
    assert all(float(r["scalars_worst"]) < 1 for r in good)
    assert bad[1]["legal"] == "0" and int(bad[1]["overlaps"]) >= 1
    assert float(bad[1]["min_gap"]) == pytest.approx(-0.9, abs=1e-6)
    assert float(bad[1]["scalars_worst"]) >= 1     # the print no longer describes it


def test_early_taps_table_gives_the_first_decade_over_realizations(tmp_path):
    lines = ["eps,seed,t,phi_b,phi_c,Z"]
    for seed, slope in ((1, 5e-5), (2, 6e-5), (3, 7e-5)):
        for t in range(11):
            lines.append(f"0.005,{seed},{t},{0.521 + slope * t:.8f},0.556,7.6")
    (tmp_path / "early_taps.csv").write_text("\n".join(lines) + "\n")
    text = "\n".join(questions.render_section(tmp_path))
    assert "``early-taps``" in text
    # the same packing at t = 0 (no error), per-tap rates 5e-5 .. 7e-5 (sem 5.8e-6)
    assert "   * - 0.005\n     - 3\n     - 0.521\n" in text
    assert "     - 6e-05 ± 5.8e-06" in text
    assert "spread at t = 10" in text
    assert "     - 1\n" in text.split("rate per unit ln t")[1]      # rising from the first tap


def test_early_taps_table_gives_the_tap_where_the_loosening_ends(tmp_path):
    """The first taps loosen the packing: the table gives the first tap at which the mean
    Phi_b over the realizations is back at its t = 0 value, or says it never is."""
    lines = ["eps,seed,t,phi_b,phi_c,Z"]
    for eps, dip in ((0.005, 4), (0.15, 99)):
        for seed in (1, 2, 3):
            for t in range(21):
                phi = 0.521 - 1e-3 if 1 <= t < dip else 0.521 + 1e-5 * t + 1e-6 * seed
                lines.append(f"{eps},{seed},{t},{phi:.8f},0.556,7.6")
    (tmp_path / "early_taps.csv").write_text("\n".join(lines) + "\n")
    rows = "\n".join(questions.render_section(tmp_path)).split("   * - ")
    assert rows[-2].splitlines()[-1] == "     - 4"
    assert rows[-1].splitlines()[8] == "     - - (not by tap 20)"


def test_question_runs_hold_the_campaign_lock_and_a_dead_holder_frees_it(tmp_path):
    """Two processes never run one question's runs at once: the runs are a tapmc.campaign
    folder, and a second runner of a held folder stops with a message naming campaign.lock
    (it does not wait, nor run the same realization twice); the lock of a killed process is
    free again (an flock dies with its holder)."""
    import subprocess

    import pytest

    from tapmc.campaign.launch import campaign_lock

    fake = tmp_path / "lmp"
    fake.write_text("#!/bin/sh\nexit 0\n")
    fake.chmod(0o755)
    work = tmp_path / "work"
    run = launch.spec("eps0.005_s2", {"N": 64, "L": 4, "eps": 0.005, "taps": 1, "seed": 2})
    held = ("import sys; sys.path.insert(0, sys.argv[1]); "
            "from tapmc.campaign.launch import campaign_lock\n"
            "with campaign_lock(sys.argv[2]): pass")
    done = subprocess.run([sys.executable, "-c", held, str(SOURCE / "tools" / "python"),
                           str(work)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    with campaign_lock(work):          # the dead process's lock is free: taken here
        with pytest.raises(common.QuestionError, match="campaign.lock is held"):
            launch.run_all(work, [run], fake)


def _scatter_campaign(root, rng):
    """A campaign folder whose finished runs differ only in their seed: <Phi^c> and the
    central zone of each realization shifted by an offset of sd 0.0005 over white taps of sd
    0.001 (the window mean's own error 0.001 / sqrt(1000): another realization lands about
    sqrt(1 + 0.5^2 * 1000) = 15.8 errors away), Phi_b, <Z> and the lateral zone without one.
    Two column orders (the constant-eps and the ageing inputs write different ones; the
    ageing input has no zones); a group of F.B.C. runs; one unfinished run and one
    single-seed group, which the measurement skips."""
    import numpy as np

    taps = 1200
    const = "step phi_b phi_c Z lateral central"
    runs = {**{f"const_pbc_eps0.05_s{s}": const for s in (1, 2, 3, 4)},
            **{f"ageing_pbc_eps0.01_s{s}": "step Z phi_b phi_c" for s in range(1, 7)},
            **{f"const_fbc_eps0.02_s{s}": const for s in (1, 2, 3)},
            "const_pbc_eps0.1_s1": const,
            "const_pbc_eps0.2_s1": const,
            "const_pbc_eps0.2_s2": const}
    for name, header in runs.items():
        folder = root / "runs" / name
        folder.mkdir(parents=True)
        values = {"step": np.arange(taps + 1.0),
                  "phi_b": 0.59 + 0.001 * rng.normal(size=taps + 1),
                  "phi_c": 0.60 + 0.0005 * rng.normal() + 0.001 * rng.normal(size=taps + 1),
                  "Z": 7.0 + 0.01 * rng.normal(size=taps + 1),
                  "lateral": 0.58 + 0.001 * rng.normal(size=taps + 1),
                  "central": 0.59 + 0.0005 * rng.normal() + 0.001 * rng.normal(size=taps + 1)}
        if name.startswith("ageing"):
            values["phi_c"][0] = 0.583   # the ageing runs start from one packing
        table = np.column_stack([values[c] for c in header.split()])
        np.savetxt(folder / "taps.dat", table, header=header, comments="# ")
        if name != "const_pbc_eps0.2_s2":
            (folder / "DONE.json").write_text("{}")


def test_realization_scatter_measures_the_factor_and_the_report_uses_it(tmp_path):
    import numpy as np

    _scatter_campaign(tmp_path / "campaign", np.random.default_rng(5))
    out = tmp_path / "questions"
    question("realization-scatter", "--campaign", tmp_path / "campaign", "--out", out)
    rows = claims.read_scan(out / "realization_scatter.csv")
    assert {r["group"] for r in rows} == {"const_pbc_eps0.05", "ageing_pbc_eps0.01",
                                          "const_fbc_eps0.02"}
    # header names, not positions: <Phi^c> starts near 0.60 in both column orders
    assert all(abs(float(r["mean"]) - 0.60) < 0.01 for r in rows if r["column"] == "phi_c")
    # Fig. 8's zones over the last quarter of the taps, where the input writes them
    zone_rows = [r for r in rows if r["column"].startswith("zone:")]
    assert {r["group"] for r in zone_rows} == {"const_pbc_eps0.05", "const_fbc_eps0.02"}
    assert {r["column"] for r in zone_rows} == set(claims.ZONE_QUANTITIES)
    assert {r["last"] for r in zone_rows} == {"300"}
    calib = claims.realization_calibrations(rows)
    assert 8 < calib["phi_c"].factor < 30 and calib["phi_c"].dof == 3 + 5 + 2
    assert claims.realization_calibrations(rows, "pbc")["phi_c"].dof == 3 + 5
    factors = claims.realization_factors(rows)
    # white taps: the batch-means errors are calibrated, no factor; the offset rejects them
    assert "phi_b" not in factors and "Z" not in factors and "zone:lateral" not in factors
    assert factors["zone:central"][0] > 4
    # one offset for both boundary conditions: the F test keeps one pooled factor
    assert claims.realization_sharing(rows)["phi_c"] > claims.CALIBRATION_ALPHA
    assert factors["phi_c"][0] == calib["phi_c"].factor
    text = "\n".join(questions.render_section(out))
    assert "``realization-scatter``" in text
    assert "     - 6 (one packing)" in text
    assert f"<Phi^c> steady state: k = {calib['phi_c'].factor:.2f}" in text
    assert "     - the central zone" in text
    assert "* By boundary condition (does one factor serve both?" in text
    assert "No quantity rejects one shared factor" in text
    assert f"the one-run errors are too small (window means: <Phi^c> " \
           f"{calib['phi_c'].factor:.1f})" in text
    # the report: one-run rows (n = 1) of Fig. 4 take the factor, rows over seeds do not
    fig4 = claims.FigureData({("a", "steady"): {"x": np.array([0.1, 0.2]),
                                                "mean": np.array([0.60, 0.61]),
                                                "sem": np.array([0.001, 0.002]),
                                                "n": np.array([1, 3])}})
    data = claims.ReportData({}, {"fig4": fig4}, questions={"realization_scatter": rows})
    k = calib["phi_c"].factor
    np.testing.assert_allclose(data.figure("fig4").get("a", "steady")[2], [0.001 * k, 0.002])
    assert data.run_error(None) == factors["phi_c"]   # the largest measured
    assert data.run_error("phi_b") == (1.0, None)
    assert f"<Phi^c> x {k:.1f}" in data.run_error_note()
    # without the measurement nothing changes
    plain = claims.ReportData({}, {"fig4": fig4})
    assert plain.figure("fig4") is fig4 and plain.run_error_note() == ""


def test_realization_scatter_calibrated_errors_change_nothing(tmp_path):
    rows = ["group,run,seed,taps,column,start,mean,sem,last,sem_dof"]
    for g, means in (("a", (0.600, 0.6002, 0.5999)), ("b", (0.610, 0.6101, 0.6098))):
        for s, m in enumerate(means, 1):
            rows.append(f"{g},{g}_s{s},{s},4000,phi_c,0.58,{m},0.0002,1000,19")
    (tmp_path / "realization_scatter.csv").write_text("\n".join(rows) + "\n")
    text = "\n".join(questions.render_section(tmp_path))
    assert "the one-run errors are compatible with the realizations' spread" in text
    assert claims.realization_factors(claims.read_scan(tmp_path / "realization_scatter.csv")) \
        == {}


def test_pbc_course_reads_the_halves_with_the_realizations_factor(tmp_path):
    # the strong run's halves differ by 0.0032 +- 0.0005: compacting with the run's own
    # error, within the error of a realization when that is 10 times larger
    pbc_course_csv(tmp_path, 0.004, 1391, 0.0032)
    own = "\n".join(pbc_course.render(tmp_path / "pbc_course.csv"))
    scaled = "\n".join(pbc_course.render(tmp_path / "pbc_course.csv",
                                             {"phi_c": (2.0, 15), "phi_c:halves": (10.0, 15)}))
    assert "still compacting at the end" in own
    assert "Its halves agree within their error: steady." in scaled
    assert "both errors times the realizations' factor, 2.0 and 10.0" in scaled
    assert "2.20 ± 0.09 % below the largest" in scaled


def _packing_campaign(root):
    """Three finished P.B.C. runs of one eps that differ only in their seed, each with the
    reference tapped packing of the pore tests (512 spheres) as its t = 0 and final dumps,
    shifted laterally by a seed's own amount (periodic: the same packing, other jackknife
    blocks), a profile_z.dat and the taps.dat columns packing-scatter reads."""
    import gzip

    import numpy as np

    text = gzip.decompress((SOURCE / "tests" / "pores" / "data" / "small_tapped.dump.gz")
                           .read_bytes()).decode().splitlines()
    head, atoms = text[:9], [line.split() for line in text[9:]]
    z = np.arange(0.25, 8.0, 0.25)
    for seed in (1, 2, 3):
        folder = root / "runs" / f"const_pbc_eps0.05_s{seed}"
        folder.mkdir(parents=True)
        for step in (0, 20):
            moved = [f"{a[0]} {a[1]} {(float(a[2]) + 1.7 * seed) % 8.0:.9f} {a[3]} {a[4]} {a[5]}"
                     for a in atoms]
            lines = head[:1] + [str(step)] + head[2:] + moved
            (folder / f"dump.{step}.lammpstrj").write_text("\n".join(lines) + "\n")
        rows = ["# step phi_b phi_c Z z_top lateral central h_s sweeps accept capped"]
        rows += [f"{t} 0.55 {0.58 + 0.001 * seed} 5.0 8.0 0.56 0.57 8.0 100 0.1 0"
                 for t in range(21)]
        (folder / "taps.dat").write_text("\n".join(rows) + "\n")
        profile = ["# Time-averaged data for fix zprof", "# TimeStep Number-of-rows",
                   "# Row c_zprof[1] c_zprof[2] c_zprof[3]"]
        for step in (0, 20):
            profile.append(f"{step} {len(z)}")
            profile += [f"{i + 1} {zi:.4f} {0.6 - 0.002 * zi:.6f} {0.6 - 0.002 * zi:.6f}"
                        for i, zi in enumerate(z)]
        (folder / "profile_z.dat").write_text("\n".join(profile) + "\n")
        (folder / "DONE.json").write_text("{}")


def test_packing_scatter_measures_the_jackknife_against_realizations(tmp_path):
    """packing-scatter on three seeds of one packing that differ only by a lateral shift:
    nu and alpha per final packing with their 4 x 4 jackknife errors (15 dof), the distinct
    initial packings as their own group, and a page section whose verdict reads k < 1 (the
    realizations agree far better than the jackknife says) as an upper bound kept."""
    import pytest

    from tapmc.paper import _runs

    if not _runs.pores_available():
        pytest.skip("tapmc-pores not built")
    _packing_campaign(tmp_path / "campaign")
    out = tmp_path / "questions"
    question("packing-scatter", "--campaign", tmp_path / "campaign", "--out", out)
    rows = claims.read_scan(out / "packing_scatter.csv")
    assert {(r["group"], r["column"]) for r in rows} == {
        ("const_pbc_eps0.05", "packing:nu"), ("const_pbc_eps0.05", "packing:alpha"),
        ("initial_pbc", "packing:nu")}
    nu = [r for r in rows if r["column"] == "packing:nu"]
    assert len(nu) == 6 and {r["sem_dof"] for r in rows} == {"15"}
    assert all(0.08 < float(r["mean"]) < 0.16 and float(r["sem"]) > 0 for r in nu)
    # one packing shifted: the same nu, other blocks
    assert max(float(r["mean"]) for r in nu) - min(float(r["mean"]) for r in nu) < 1e-6
    assert len({r["sem"] for r in nu}) > 1
    calib = claims.realization_calibrations(rows)
    assert calib["packing:nu"].factor < 0.01 and calib["packing:nu"].dof == 2 + 2
    text = "\n".join(questions.render_section(out))
    assert "``packing-scatter``" in text and "     - 3 (t = 0)" in text
    assert "the page keeps the jackknife error, an upper bound" in text
    # the report keeps one run's jackknife: k < 1 never shrinks an error
    data = claims.ReportData({}, {}, questions={"packing_scatter": rows})
    assert data.run_error("packing:nu") == (1.0, None)


def test_seed_fits_fits_every_group_of_realizations_and_the_page_shows_it(tmp_path):
    """seed-fits on realization-scatter's groups: one row per group, law and parameter, each
    run's fit listed. Taps without any compaction (white noise about a constant) fix no B:
    every group finds it undetermined, and the F.B.C. group's realizations overrule the
    run's surrogates' "unique" (test_claims covers the other outcomes)."""
    import numpy as np

    _scatter_campaign(tmp_path / "campaign", np.random.default_rng(5))
    out = tmp_path / "questions"
    question("seed-fits", "--campaign", tmp_path / "campaign", "--out", out)
    rows = claims.read_scan(out / "seed_fits.csv")
    groups = {r["group"]: r["realizations"] for r in rows}
    assert groups == {"const_pbc_eps0.05": "4", "ageing_pbc_eps0.01": "6",
                      "const_fbc_eps0.02": "3"}
    assert len(rows) == 3 * 2 * 4          # groups x laws (eqs. 3, 4) x parameters
    assert all(len(r["values"].split(";")) == int(r["realizations"]) for r in rows)
    assert all(r["taps"] == "1200" and r["bc"] in ("pbc", "fbc") for r in rows)
    for group in groups:
        scales = [r["determined"] for r in rows if r["group"] == group and r["law"] == "eq3"
                  and r["parameter"] in ("B", "tau")]
        assert "0" in scales and "1" not in scales, (group, scales)
    assert all(float(r["spread_low"]) <= float(r["spread"]) <= float(r["spread_high"])
               for r in rows if np.isfinite(float(r["spread"])))
    text = "\n".join(questions.render_section(out))
    assert "``seed-fits``" in text and "tapmc.laws.RealizationFits" in text
    assert "   * - const_fbc_eps0.02\n     - eq. 3\n     - 3\n     - 1200" in text
    data = claims.ReportData({}, {}, questions={
        "seed_fits": rows, "fit_surrogates": [
            dict(r, source=f"const_fbc_eps{e}_s1", eps=str(e),
                 determined="0" if e == 0.005 and r["parameter"] == "B" else "1")
            for e in (0.005, 0.02) for r in _surrogate_rows_unique()]})
    claim = {c.id: c for c in claims.load_register()}["eq3-triplet-range"]
    fbc, pbc = claims.eq3_triplet_pattern(data, claim)
    assert str(claims.verdict(claim, fbc)) == "disagrees", fbc
    assert pbc.label == "P.B.C. realizations" and str(claims.verdict(claim, pbc)) == "disagrees"


def test_surrogates_of_several_seeds_are_set_against_the_realizations(tmp_path):
    """fit_surrogates.csv with three runs of one eps and seed_fits.csv with their group: the
    page lists each run and compares its half width of ln B with the realizations' spread."""
    header = ("source,eps,law,taps,parameter,value,low,high,half_width,log_scale,determined,"
              "range_p,fits")
    lines = [header]
    for seed, half, det in ((1, 0.4, 1), (2, 0.76, 0), (3, 0.5, 1)):
        lines.append(f"const_fbc_eps0.02_s{seed},0.02,eq3,4000,B,0.3,0.2,0.45,{half},1,{det},"
                     "0.5,200")
    (tmp_path / "fit_surrogates.csv").write_text("\n".join(lines) + "\n")
    seed_rows = _seed_fit_csv_row(spread=1.5, low=0.8, high=9.4)
    (tmp_path / "seed_fits.csv").write_text(seed_rows)
    text = "\n".join(questions.render_section(tmp_path))
    assert "   * - campaign run s2\n     - 0.02" in text
    assert ("At eps = 0.02, 3 runs: their surrogates give ln B (eq. 3) half widths of 0.4 (s1), "
            "0.76 (s2, undetermined), 0.5 (s3), against a spread over the 3 realizations "
            "(seed-fits) of 1.5 (95 %: 0.8 to 9.4): the surrogates' verdict on B differs "
            "between the runs; every run's half width is below the realizations' spread.") in text
    assert "``seed-fits``" in text


def _seed_fit_csv_row(spread, low, high):
    head = ("group,bc,eps,law,taps,realizations,parameter,values,mean,spread,spread_low,"
            "spread_high,limit,log_scale,determined,range_shift,range_bound,range_p")
    return (f"{head}\nconst_fbc_eps0.02,fbc,0.02,eq3,4000,3,B,-1;0;1,0.3,{spread},{low},{high},"
            "0.693,1,0,0.5,3,0.4\n")


def _surrogate_rows_unique():
    """fit_surrogates.csv rows of one run whose surrogates find eq. 3's triplet unique (the
    test marks B undetermined at the smallest eps, as the campaign's run finds it)."""
    return [{"law": "eq3", "taps": "1200", "parameter": k, "value": "0.5", "low": "0.4",
             "high": "0.6", "half_width": "0.1", "log_scale": str(int(k in ("B", "tau"))),
             "determined": "1", "range_p": "0.4", "fits": "200"}
            for k in ("X_inf", "dX_inf", "B", "tau")]

