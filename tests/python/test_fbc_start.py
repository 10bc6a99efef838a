# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# The paper's F.B.C. start (section IV.A) through the campaign: Scale.fbc_start, the runs it
# names and the switch it passes to in.constant_eps, the refusal of a campaign that mixes
# starts, Figs. 7 and 8 drawn from written runs with known under-populated walls and a known
# first-tap jump (and from the start between walls, where the jump is a dip), and the
# tapmc-paper option --fbc-start.
import csv
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", HERE.parent.parent))
PYTHON_DIR = SOURCE / "tools" / "python"
sys.path.insert(0, str(PYTHON_DIR))

from paper_fakes import FakeCampaign, write_constant_eps, write_profile_x  # noqa: E402
from tapmc.paper import _profile_runs, _runs, claims, fig7, fig8  # noqa: E402
from tapmc.paper.scales import FULL, QUICK, Scale  # noqa: E402

#: a scale of no preset (the figures then use every eps of the runs)
TINY = Scale(**dict(QUICK.as_dict(), N=64, L=16.0, eta=1e-4, taps=8, steady_last=2,
                     profile_eps=(0.02, 0.1)))


def read_csv(path):
    return {(r["panel"], r["series"]): r for r in csv.DictReader(open(path))}


def test_scale_fbc_start():
    assert QUICK.fbc_start == FULL.fbc_start == "walls"
    assert QUICK.replace(fbc_start="paper").fbc_start == "paper"
    with pytest.raises(ValueError, match="Scale.fbc_start = 'wall': allowed values 'walls', "
                                         "'paper'"):
        QUICK.replace(fbc_start="wall")


def test_runs_of_each_start():
    walls = _runs.constant_eps_run(QUICK, "fbc", 0.1, 2)
    assert walls.name == "const_fbc_eps0.1_s2" and "fbc_start" not in walls.variables
    paper = _runs.constant_eps_run(QUICK.replace(fbc_start="paper"), "fbc", 0.1, 2)
    assert paper.name == "const_fbcpaper_eps0.1_s2"
    assert paper.variables == dict(walls.variables, fbc_start="paper")
    assert _runs.fbc_start_of(walls) == "walls" and _runs.fbc_start_of(paper) == "paper"
    # periodic runs have no F.B.C. start: unchanged names and switches
    pbc = _runs.constant_eps_run(QUICK.replace(fbc_start="paper"), "pbc", 0.1, 2)
    assert pbc.describe() == _runs.constant_eps_run(QUICK, "pbc", 0.1, 2).describe()
    names = [s.name for s in fig8.runs(QUICK.replace(fbc_start="paper"), 1)]
    assert names == [f"const_fbcpaper_eps{e:g}_s1" for e in QUICK.profile_eps]


def test_a_campaign_mixing_starts_is_refused(tmp_path):
    runs = [_runs.constant_eps_run(TINY, "fbc", 0.1, 1),
            _runs.constant_eps_run(TINY.replace(fbc_start="paper"), "fbc", 0.1, 1)]
    with pytest.raises(ValueError, match="mix the F.B.C. starts paper, walls"):
        _runs.constant_eps_groups(FakeCampaign(tmp_path, runs), "fbc")


def test_zone_means_known_answer():
    x = np.arange(0.5, 16, 1.0)                 # bins of R, side 16R
    phi = np.where(np.minimum(x, 16 - x) < 2, 0.3, np.where(np.minimum(x, 16 - x) < 7, 0.5,
                                                             0.6))
    zones = fig7.zone_means(x, phi, 16.0)
    assert zones == {"within_2R": 0.3, "2R_to_7R": 0.5, "central": 0.6}
    flat = fig7.zone_means(x, np.full(x.size, 0.55), 16.0)
    assert flat["within_2R"] == flat["2R_to_7R"] == flat["central"] == 0.55


def fbc_campaign(tmp_path, start, first_tap_lateral, wall_phi0, taps=TINY.taps):
    """Written F.B.C. runs of TINY (two seeds, eps 0.02 and 0.1; ``taps`` taps):
    delta Phi_lateral after the first tap is first_tap_lateral + 0.001 (seed - 1.5) (mean
    first_tap_lateral, sem 0.0005), delta Phi_central 0.002; the initial profile is wall_phi0
    within 2R of the walls and 0.55 beyond, the final one 0.5 and 0.58."""
    scale = TINY.replace(fbc_start=start, taps=taps)
    runs = fig8.runs(scale, 2)
    camp = FakeCampaign(tmp_path / start, runs)
    x = np.arange(0.05, 8.0, 0.1)               # bins of R/5 in distance units (R = 0.5)
    dist = np.minimum(x, 8.0 - x) / 0.5
    for spec in runs:
        jump = first_tap_lateral + 0.001 * (spec.seed - 1.5)
        lateral = [0.5, 0.5 + jump] + [0.5 + jump + 0.001 * k for k in range(1, taps)]
        central = [0.55, 0.552] + [0.552 + 0.0005 * k for k in range(1, taps)]
        write_constant_eps(camp, spec, lateral, central)
        write_profile_x(camp, spec, x, np.where(dist < 2, wall_phi0, 0.55),
                        np.where(dist < 2, 0.5, 0.58), taps)
    return camp


def test_fig8_first_tap_jump_of_the_paper_start(tmp_path):
    camp = fbc_campaign(tmp_path, "paper", first_tap_lateral=0.015, wall_phi0=0.35)
    _, path = fig8.draw(camp, tmp_path / "figs_paper")
    rows = read_csv(path)
    assert {("a", "paper:eps=0.1"), ("b", "paper:eps=0.1"), ("a", "paper:eps=0.02")} <= set(rows)
    assert not any(s.startswith("eps=") for p, s in rows if p in "ab")
    jump = rows[("params", "eps=0.1:first_tap_lateral")]
    assert float(jump["mean"]) == pytest.approx(0.015)
    assert float(jump["sem"]) == pytest.approx(0.0005) and int(jump["n"]) == 2
    assert float(rows[("params", "eps=0.1:first_tap_central")]["mean"]) == pytest.approx(0.002)
    assert ("params", "eps=0.1:final_lateral") in rows        # the report's rows stay
    # a window of 2 taps has no batch-means error: no seeds' rows
    assert not any(s.endswith(":seeds") for _, s in rows)
    # every params series parses as 'eps=<eps>:<name>' (the report reads them so)
    assert all(float(s.split("=")[1].split(":")[0]) in (0.02, 0.1)
               for p, s in rows if p == "params")


def test_fig8_writes_each_seeds_final_zones_for_the_report_to_pool(tmp_path):
    """Two seeds of 80 taps (a window of 20): each seed's window mean of every final zone and
    its batch-means error (tapmc.fluctuations.SteadyState), whose mean is the row's value."""
    camp = fbc_campaign(tmp_path, "walls", first_tap_lateral=-0.01, wall_phi0=0.45, taps=80)
    _, path = fig8.draw(camp, tmp_path / "figs_seeds")
    table = claims.FigureData.read(path)
    for zone in ("lateral", "central", "central_minus_lateral"):
        x, values, errors, n = table.get("params", f"eps=0.1:final_{zone}:seeds")
        assert len(values) == 2 and np.all(n == 1) and np.all(errors > 0), zone
        assert np.mean(values) == pytest.approx(table.param(f"eps=0.1:final_{zone}")[0],
                                                abs=1e-9), zone
    # the seeds of this fake differ by a constant: their paired difference is one value
    assert np.ptp(table.get("params", "eps=0.1:final_central_minus_lateral:seeds")[1]) \
        == pytest.approx(0.001)
    assert table.get("params", "eps=0.1:first_tap_lateral:seeds") is None


def test_fig8_of_the_start_between_walls_dips(tmp_path):
    camp = fbc_campaign(tmp_path, "walls", first_tap_lateral=-0.01, wall_phi0=0.45)
    _, path = fig8.draw(camp, tmp_path / "figs_walls")
    rows = read_csv(path)
    assert ("a", "eps=0.1") in rows and not any(s.startswith("paper:") for _, s in rows)
    assert float(rows[("params", "eps=0.1:first_tap_lateral")]["mean"]) == pytest.approx(-0.01)


@pytest.mark.parametrize("start, wall_phi0", [("paper", 0.35), ("walls", 0.45)])
def test_fig7_zone_means_and_start(tmp_path, start, wall_phi0):
    camp = fbc_campaign(tmp_path, start, first_tap_lateral=0.01, wall_phi0=wall_phi0)
    _, path = fig7.draw(camp, tmp_path / f"figs7_{start}")
    rows = read_csv(path)

    def param(name):
        return float(rows[("params", name)]["mean"])

    assert param("paper_start") == (1.0 if start == "paper" else 0.0)
    assert param("eps") == 0.1
    assert param("initial:within_2R") == pytest.approx(wall_phi0)
    assert param("initial:2R_to_7R") == pytest.approx(0.55)
    assert param("initial:central") == pytest.approx(0.55)
    assert param("final:within_2R") == pytest.approx(0.5)
    assert param("final:central") == pytest.approx(0.58)
    assert _profile_runs.START_LABEL[start].startswith("F.B.C.")


def cli(*args, cwd):
    env = dict(os.environ, PYTHONPATH=str(PYTHON_DIR))
    return subprocess.run([sys.executable, "-m", "tapmc.paper", *map(str, args)], env=env,
                          cwd=cwd, capture_output=True, text=True, timeout=120)


def test_cli_fbc_start(tmp_path):
    out = cli("fig8", "--quick", "--fbc-start", "paper", "--dry-run", cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    assert f"campaign {tmp_path / 'tapmc-paper-quick-fbc-paper'} (quick" in out.stdout
    assert "const_fbcpaper_eps0.1_s1  [in.constant_eps" in out.stdout
    walls = cli("fig8", "--quick", "--dry-run", cwd=tmp_path)
    assert f"campaign {tmp_path / 'tapmc-paper-quick'} (quick" in walls.stdout
    assert "const_fbc_eps0.1_s1  [in.constant_eps" in walls.stdout
    bad = cli("fig8", "--fbc-start", "wall", "--dry-run", cwd=tmp_path)
    assert bad.returncode == 2 and "invalid choice: 'wall'" in bad.stderr
    plan = cli("campaign", "--fbc-start", "paper", "--dry-run", "--campaign", tmp_path / "c",
               cwd=tmp_path)
    assert plan.returncode == 2 and "unrecognized arguments: --fbc-start" in plan.stderr
