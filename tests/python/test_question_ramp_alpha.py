# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""tapmc-paper question ramp-alpha (issue 46): alpha at the end of every level of the ramps at
the paper's protocol, on synthetic ramps whose profiles have a known gradient per level (one
still running, its profile in segments written by resumed attempts, its live block cut short),
its CSV and page section; and the register's rows of gradient-no-hysteresis at 4000 taps per
level on known answers: a decrease on the first increase agrees, one above it disagrees (the
control); ramps below (sqrt eps)* are not counted."""

import os
import sys
from pathlib import Path

import numpy as np
import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(SOURCE / "tools" / "python"))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from claims_fakes import BY_ID, report  # noqa: E402
from tapmc.paper import claims, cli, questions  # noqa: E402
from tapmc.paper.questions import ramp_alpha  # noqa: E402

RADIUS, PHI0, HEIGHT = 0.5, 0.62, 30.0      # the packing: Phi0 - alpha z/R up to HEIGHT
ZB = np.arange(0.1, 40.0, 0.2)              # bins of R/5 (z/R), as compute stereo/profile
TAPS = 4                                    # taps per level of the synthetic ramps
#: (branch index of in.ramp: 0 up1, 1 down, 2 up2; sqrt(eps)) of a ramp turning at 0.075
LEVELS = [(0, 0.025), (0, 0.05), (0, 0.075), (1, 0.05), (1, 0.025), (2, 0.05), (2, 0.075)]
HEAD = ("# Time-averaged data for fix zprof\n# TimeStep Number-of-rows\n"
        "# Row c_phi[1] c_phi[2] c_phi[3]\n")


def block(step, alpha):
    """A profile_z.dat block: z, a count, Phi = PHI0 - alpha z/R below HEIGHT, 0 above."""
    phi = np.where(ZB < HEIGHT, PHI0 - alpha * ZB, 0.0)
    rows = "".join(f"{i + 1} {z * RADIUS:.6f} 1.0 {p:.9f}\n" for i, (z, p) in
                   enumerate(zip(ZB, phi)))
    return f"{step} {len(ZB)}\n" + rows


def write_ramp(campaign, name, alphas, split=None, live=False):
    """runs/<name>: taps.dat of LEVELS (TAPS per level) and the profile at t = 0 (alpha
    0.001) and at every level's end (``alphas``). ``split`` = (k, step): the first file stops
    after level k's block plus a block 99 at the next level end (a killed attempt's, which
    the resumed attempt writes again), the rest in profile_z.dat.from<step>; ``live``: the
    last block is cut short (a run still writing it)."""
    folder = campaign / "runs" / name
    folder.mkdir(parents=True)
    taps = ["# step level branch sqrt_eps phi_b phi_c Z", "0 -1 0 0.000000 0.54 0.58 7.3"]
    for k, (branch, x) in enumerate(LEVELS[:len(alphas)]):
        taps += [f"{k * TAPS + t} {k} {branch} {x:.6f} 0.54 0.58 7.3" for t in range(1, TAPS + 1)]
    (folder / "taps.dat").write_text("\n".join(taps) + "\n")
    blocks = [block(0, 0.001)] + [block((k + 1) * TAPS, a) for k, a in enumerate(alphas)]
    if live:
        blocks[-1] = blocks[-1][:len(blocks[-1]) // 2]
    if split is None:
        (folder / "profile_z.dat").write_text(HEAD + "".join(blocks))
        return folder
    k, step = split
    (folder / "profile_z.dat").write_text(HEAD + "".join(blocks[:k + 2])
                                          + block((k + 2) * TAPS, 99.0))
    (folder / f"profile_z.dat.from{step}").write_text(HEAD + "".join(blocks[k + 2:]))
    return folder


def test_alpha_of_every_level_end_with_the_segments_of_a_running_ramp(tmp_path):
    """Every whole level's alpha is its profile's known gradient, on its branch and sqrt(eps)
    read from taps.dat; a running ramp's segments are joined as the campaign merges them (the
    killed attempt's block is replaced by the resumed one's) and its last block, cut short,
    is left out; the files are not touched."""
    campaign = tmp_path / "campaign"
    done = [0.001, 0.002, 0.003, 0.0025, 0.0012, 0.0021, 0.0031]
    write_ramp(campaign, "paperramp0.075_pbc_s1", done)
    running = write_ramp(campaign, "paperramp0.075_pbc_eta1e-06_s2", done[:6], split=(1, 10),
                         live=True)
    before = sorted(p.name for p in running.iterdir())
    rows = ramp_alpha.analyse(campaign, default_eta=1e-7)
    assert sorted(p.name for p in running.iterdir()) == before
    first = [r for r in rows if r[0] == "paperramp0.075_pbc_s1"]
    assert [r[4] for r in first] == [4, 8, 12, 16, 20, 24, 28]
    assert [r[5] for r in first] == ["up1"] * 3 + ["down"] * 2 + ["up2"] * 2
    assert [float(r[6]) for r in first] == [x for _, x in LEVELS]
    assert [float(r[7]) for r in first] == pytest.approx(done, abs=1e-9)
    assert [float(r[11]) for r in first] == pytest.approx(done, abs=1e-9)  # 5-18R: the same
    assert all(r[12:14] == ["5", "18"] for r in first)
    # the bands' mean Phi: PHI0 - alpha times the mean z/R of the band's bins
    for r, alpha in zip(first, done):
        expected = [PHI0 - alpha * ZB[(ZB >= lo) & (ZB < hi)].mean()
                    for lo, hi in ramp_alpha.PHI_BANDS]
        assert [float(v) for v in r[14:]] == pytest.approx(expected, abs=1e-8)
    assert all(r[1:4] == ["0.075", "1e-07", 1] for r in first)
    assert float(first[0][10]) == pytest.approx(22.0 / 28.0 * HEIGHT, abs=0.3)
    second = [r for r in rows if r[0] == "paperramp0.075_pbc_eta1e-06_s2"]
    assert [r[4] for r in second] == [4, 8, 12, 16, 20]          # the live sixth left out
    assert [float(r[7]) for r in second] == pytest.approx(done[:5], abs=1e-9)  # not 99
    assert all(r[2:4] == ["1e-06", 2] for r in second)


def test_command_csv_and_page_section(tmp_path):
    """The command writes ramp_alpha.csv, which reads back; the page's table gives each
    ramp's decrease minus first increase and second increase minus decrease with no verdict."""
    campaign = tmp_path / "campaign"
    write_ramp(campaign, "paperramp0.075_pbc_s1", [0.001, 0.002, 0.003, 0.0025, 0.0013,
                                                   0.0021, 0.0031])
    out = tmp_path / "questions"
    assert cli.main(["question", "ramp-alpha", "--campaign", str(campaign), "--out",
                     str(out)]) == 0
    rows = ramp_alpha.load(out / ramp_alpha.CSV)
    assert list(rows[0]) == ramp_alpha.HEADER and len(rows) == 7
    text = "\n".join(questions.render_section(out))
    assert "alpha on the ramps at the paper's protocol (ramp-alpha)" in text
    # decrease minus first increase at 0.05 and 0.025: +0.0005 and +0.0003
    assert text.count("0.0004 ± 0.0001 (2)") == 2       # Fig. 6's window and 5-18R
    assert "decrease minus first increase, 5-18R" in text
    # where the decrease gains: 0-4R (mean z/R 2): -0.0005 x 2 and -0.0003 x 2
    assert "   * - 0.075\n     - 1e-7\n     - 1\n     - -0.0008 ± 0.0002 (2)" in text
    assert "0.00100 to 0.00300" in text
    assert "agrees" not in text and "disagrees" not in text
    assert (out / ramp_alpha.PNG).stat().st_size > 0
    assert ".. image:: validation/questions/ramp_alpha.png" in text
    (out / ramp_alpha.PNG).unlink()                         # no figure, no image line
    assert ".. image::" not in "\n".join(questions.render_section(out))


def test_bad_campaigns_are_named_in_one_line(tmp_path, capsys):
    """No paper ramp; a profile that does not start at t = 0: one line, exit 2, the committed
    CSV kept."""
    out = tmp_path / "out"
    out.mkdir()
    (out / ramp_alpha.CSV).write_text("run\ncommitted\n")
    (tmp_path / "campaign" / "runs").mkdir(parents=True)
    args = ["question", "ramp-alpha", "--campaign", str(tmp_path / "campaign"), "--out", str(out)]
    assert cli.main(args) == 2
    assert "no paper ramp" in capsys.readouterr().err
    folder = write_ramp(tmp_path / "campaign", "paperramp0.075_pbc_s1", [0.001, 0.002])
    (folder / "profile_z.dat").write_text(HEAD + block(4, 0.001) + block(8, 0.002))
    assert cli.main(args) == 2
    err = capsys.readouterr().err
    assert "its first profile is at step 4" in err and err.count("\n") == 1
    assert "Traceback" not in err
    # a killed attempt's segment whose block is malformed mid-file: named with its line
    (folder / "profile_z.dat").write_text(HEAD + block(0, 0.001) + "4 2\n1 0.05 1.0\n8 1\n")
    (folder / "profile_z.dat.from6").write_text(HEAD + block(8, 0.002))
    assert cli.main(args) == 2
    err = capsys.readouterr().err
    assert "profile_z.dat:" in err and err.count("\n") == 1 and "Traceback" not in err
    assert (out / ramp_alpha.CSV).read_text() == "run\ncommitted\n"


UP = np.array([0.025, 0.05, 0.075, 0.1, 0.125, 0.15, 0.175, 0.2])
DOWN = np.array([0.175, 0.15, 0.125, 0.1])


def alpha_rows(run, top, eta, seed, levels):
    """ramp_alpha.csv rows (text, as the report reads them) of ``levels``: [(branch, x, a)]."""
    return [{"run": run, "top": f"{top:g}", "eta": f"{eta:g}", "seed": str(seed),
             "step": str(4000 * (k + 1)), "branch": b, "sqrt_eps": f"{x:g}",
             "alpha": f"{a:.10g}", "alpha_err": "0.0002", "window_lo": "5",
             "window_hi": "22.8"} for k, (b, x, a) in enumerate(levels)]


def ramp_beyond(gap, eta=1e-7, seed=1, down=DOWN):
    """A ramp turning at 0.2: alpha = 0.001 + 0.005 sqrt(eps) on its first increase (a
    variation of 0.000875), ``gap`` above it on the way down, +-0.00002 level to level."""
    up = [("up1", x, 0.001 + 0.005 * x) for x in UP]
    noise = 0.00002 * (-1.0) ** np.arange(len(down))
    return alpha_rows(f"paperramp0.2_pbc_s{seed}" + ("" if eta == 1e-7 else f"_eta{eta:g}"),
                      0.2, eta, seed, up + [("down", x, 0.001 + 0.005 * x + gap + n)
                                           for x, n in zip(down, noise)])


def no_hysteresis_rows(rows):
    data = report()
    data.questions["ramp_alpha"] = rows
    return claims.alpha_ramp_hysteresis(data, BY_ID["gradient-no-hysteresis"])


def test_register_rows_at_the_paper_protocol_agree_and_the_control_disagrees():
    """Decrease on the first increase: agrees (its error is below alpha's variation); 0.0004
    above it (the control): disagrees; a ramp turning below (sqrt eps)* with a large gap is
    not counted; a second eta has its own row after the campaign's; two levels of the
    decrease are undecided."""
    claim = BY_ID["gradient-no-hysteresis"]
    below = alpha_rows("paperramp0.125_pbc_s1", 0.125, 1e-7, 1,
                       [("up1", x, 0.001) for x in UP[:5]] + [("down", 0.1, 0.01)] * 3)
    agree, = no_hysteresis_rows(ramp_beyond(0.0) + below)
    assert agree.label == "4000 taps per level, eta = 1e-7" and agree.meets == ("ramp_taps",)
    assert agree.value == pytest.approx(0.0, abs=1e-12) and agree.dof == 3
    assert agree.effect == pytest.approx(0.000875)
    assert str(claims.verdict(claim, agree)) == "agrees"
    control, = no_hysteresis_rows(ramp_beyond(0.0004))
    assert control.value == pytest.approx(0.0004)
    assert str(claims.verdict(claim, control)).startswith("disagrees")
    assert "46% of alpha's variation along the first increase" in control.shown
    first, other = no_hysteresis_rows(ramp_beyond(0.0004, eta=1e-6) + ramp_beyond(0.0))
    assert (first.label, other.label) == ("4000 taps per level, eta = 1e-7",
                                          "4000 taps per level, eta = 1e-6")
    short, = no_hysteresis_rows(ramp_beyond(0.0, down=DOWN[:2]))
    assert short.undecided.startswith("2 level(s) of the decrease")


def test_seeds_of_one_eta_pool_their_levels():
    """Two seeds at one eta: their 8 level differences in one row (7 dof), the variation of
    their mean first increase."""
    row, = no_hysteresis_rows(ramp_beyond(0.0002) + ramp_beyond(0.0, seed=2))
    assert row.dof == 7 and row.value == pytest.approx(0.0001)
    assert "mean of 8 common sqrt(eps)" in row.shown


def low_pair(gaps, eta=1e-7):
    """Two seeds of a ramp turning at 0.125: down minus up1 = gaps[seed] +- 0.0001 over 4
    levels (each seed's scatter error 0.0001 / sqrt(4) x sqrt(4/3))."""
    rows = []
    for seed, gap in enumerate(gaps, 1):
        noise = 0.0001 * (-1.0) ** np.arange(4)
        rows += alpha_rows(f"paperramp0.125_pbc_s{seed}", 0.125, eta, seed,
                           [("up1", x, 0.001) for x in UP[:5]]
                           + [("down", x, 0.001 + gap + n)
                              for x, n in zip(UP[:4][::-1], noise)])
    return rows


def test_the_level_scatter_error_is_checked_on_pairs_of_seeds():
    """Seeds of the ramps at 0.125 apart within their scatter errors: the error is kept, the
    chi2 the brute force's; apart far beyond them (the control): the 0.2 ramp's error takes
    sqrt(chi2 / dof), and its verdict follows the wider error."""
    claim = BY_ID["gradient-no-hysteresis"]
    sem = 0.0001 * np.sqrt(4 / 3) / 2                     # each seed's scatter error
    kept, = no_hysteresis_rows(ramp_beyond(0.0004) + low_pair([0.0002, 0.0003]))
    chi2 = (0.0001 / 2) ** 2 / sem ** 2 * 2               # two seeds about their mean
    assert f"chi2 = {chi2:.1f} over 1 dof" in kept.shown and "kept" in kept.shown
    assert kept.err == pytest.approx(0.00002 * np.sqrt(4 / 3) / 2)   # ramp_beyond's noise
    widened, = no_hysteresis_rows(ramp_beyond(0.0004) + low_pair([0.0, 0.003]))
    chi2 = (0.003 / 2) ** 2 / sem ** 2 * 2
    assert widened.err == pytest.approx(kept.err * np.sqrt(chi2))
    assert f"x {np.sqrt(chi2):.1f}" in widened.shown
    assert str(claims.verdict(claim, kept)).startswith("disagrees")
    assert not str(claims.verdict(claim, widened)).startswith("disagrees")


def test_level_alphas_needs_the_initial_profile_and_takes_a_window(tmp_path):
    """fig6.level_alphas: without the profile at step 0 the window cannot be cut (ValueError);
    a given window is used as it is; a block whose step has no tap row is left out."""
    from tapmc.paper import fig6
    from tapmc.readers import read_fix_print

    folder = write_ramp(tmp_path, "paperramp0.075_pbc_s1", [0.001, 0.002])
    table = read_fix_print(folder / "taps.dat")
    blocks = [np.loadtxt(block(s, a).splitlines()[1:])[:, 1:]
              for s, a in ((0, 0.001), (4, 0.001), (8, 0.002), (99, 0.5))]
    with pytest.raises(ValueError, match="step 0"):
        fig6.level_alphas(blocks[1:], [4, 8, 99], table, RADIUS)
    levels = fig6.level_alphas(blocks, [0, 4, 8, 99], table, RADIUS, window=(5.0, 18.0))
    assert [lv.step for lv in levels] == [4, 8]                 # step 99: no tap row
    assert [lv.window for lv in levels] == [(5.0, 18.0)] * 2
    assert [lv.alpha for lv in levels] == pytest.approx([0.001, 0.002], abs=1e-9)


def test_the_figure_states_the_scale_its_campaign_records(tmp_path, monkeypatch):
    """A campaign made at another Scale (its scale.json) gets a figure that states that
    scale's N, box and taps, and names it; one without scale.json is the full preset's
    (the committed campaign's); an edited preset is named as a scale, not as the preset."""
    from tapmc.paper import _plotting, _runs
    from tapmc.paper.scales import FULL, QUICK
    stated = []
    monkeypatch.setattr(_plotting, "finish_figure", lambda fig, text, *a, **k: stated.append(text))
    for name, scale in (("quick", QUICK), ("bare", None)):
        campaign = tmp_path / name
        write_ramp(campaign, "paperramp0.075_pbc_s1", [0.001, 0.002, 0.003, 0.0025, 0.0013,
                                                       0.0021, 0.0031])
        if scale is not None:
            _runs.write_scale(campaign, scale)
        assert cli.main(["question", "ramp-alpha", "--campaign", str(campaign), "--out",
                         str(tmp_path / f"{name}_out")]) == 0
    quick, bare = stated
    assert f"N = {QUICK.N}, box {QUICK.L:g}R" in quick and "campaign: quick preset" in quick
    assert f"N = {FULL.N}, box {FULL.L:g}R" in bare and "campaign: full preset" in bare
    assert _runs.folder_scale(tmp_path / "bare") == FULL
    assert _plotting.scale_text(QUICK.replace(N=100)) == "campaign: scale quick"
