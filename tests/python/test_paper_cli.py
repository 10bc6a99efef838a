# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The tapmc-paper command: argument validation, --help, the message for a missing figure
module, the Scale presets, and one end-to-end figure through a stub figure module (runs a
tiny campaign, draws, prints the PNG and CSV paths) on a copy of the package."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
BUILD = Path(os.environ.get("TAPMC_BUILD_DIR", SOURCE / "build"))
LMP = Path(os.environ.get("TAPMC_LMP", BUILD / "lmp_tapmc"))
PYTHON_DIR = SOURCE / "tools" / "python"
sys.path.insert(0, str(PYTHON_DIR))

from tapmc.paper import FIGURES  # noqa: E402
from tapmc.paper.scales import FULL, QUICK, Scale, get_scale  # noqa: E402

STUB = """# stub figure module written by test_paper_cli.py
from pathlib import Path
from tapmc.campaign import RunSpec
INPUT = {input!r}

def runs(scale, seeds):
    return [RunSpec(f"stub_s{{s}}", INPUT, dict(N=64, L=8, eta=scale.eta, taps=4), seed=s)
            for s in range(1, seeds + 1)]

def draw(campaign, out_dir):
    rows = [(s.name, (campaign.result(s.name) / "taps.dat").read_text().splitlines()[-1])
            for s in campaign.runs]
    csv = Path(out_dir) / "stub.csv"
    csv.write_text("".join(f"{{n}},{{r}}\\n" for n, r in rows))
    png = Path(out_dir) / "stub.png"
    png.write_bytes(b"png")
    return png, csv
"""


def cli(*args, pythonpath=PYTHON_DIR, cwd=None):
    env = dict(os.environ, PYTHONPATH=str(pythonpath), TAPMC_LMP=str(LMP))
    return subprocess.run([sys.executable, "-m", "tapmc.paper", *map(str, args)], env=env,
                          cwd=cwd, capture_output=True, text=True, timeout=120)


@pytest.fixture
def package_copy(tmp_path):
    """A copy of tools/python/tapmc without any figure module."""
    root = tmp_path / "python"
    shutil.copytree(PYTHON_DIR / "tapmc", root / "tapmc",
                    ignore=shutil.ignore_patterns("__pycache__", "fig*.py"))
    return root


def test_help_lists_every_figure():
    out = cli("--help")
    assert out.returncode == 0
    for fig in FIGURES:
        assert fig in out.stdout
    assert "report" in out.stdout
    sub = cli("fig2", "--help")
    assert sub.returncode == 0
    for option in ("--quick", "--full", "--seeds", "--jobs", "--campaign", "--out"):
        assert option in sub.stdout


@pytest.mark.parametrize("args, message", [
    ((), "required: COMMAND"),
    (("fig1",), "invalid choice: 'fig1'"),
    (("fig2", "--seeds", "0"), "argument --seeds: 0 is not >= 1"),
    (("fig2", "--jobs", "two"), "argument --jobs: 'two' is not an integer"),
    (("fig2", "--quick", "--full"), "not allowed with argument"),
    (("fig2", "--mode", "mpi"), "invalid choice: 'mpi'"),
])
def test_bad_arguments(args, message):
    out = cli(*args)
    assert out.returncode == 2
    assert message in out.stderr


def test_missing_figure_module(package_copy):
    out = cli("fig5", "--dry-run", pythonpath=package_copy)
    assert out.returncode == 2
    assert "fig5: the figure module tapmc.paper.fig5 is not installed" in out.stderr
    assert "available figures: none" in out.stderr
    (package_copy / "tapmc" / "paper" / "fig5.py").write_text("def runs(scale, seeds):\n"
                                                             "    return []\n")
    out = cli("fig5", "--dry-run", pythonpath=package_copy)
    assert out.returncode == 2
    assert "module tapmc.paper.fig5 has no draw() function" in out.stderr
    out = cli("report", "--dry-run", pythonpath=package_copy)
    assert out.returncode == 2 and "tapmc.paper.fig2 is not installed" in out.stderr


@pytest.mark.skipif(not LMP.is_file(), reason=f"no LAMMPS executable at {LMP}")
def test_figure_end_to_end_with_stub(package_copy, tmp_path):
    (package_copy / "tapmc" / "paper" / "fig3.py").write_text(
        STUB.format(input=str(SOURCE / "examples" / "paper" / "in.constant_eps")))
    campaign, out_dir = tmp_path / "camp", tmp_path / "figs"
    dry = cli("fig3", "--dry-run", "--seeds", "2", "--campaign", campaign,
              pythonpath=package_copy)
    assert dry.returncode == 0, dry.stderr
    assert "stub_s1  [in.constant_eps, taps 4, to run]" in dry.stdout
    assert not (campaign / "runs").exists()
    out = cli("fig3", "--quick", "--seeds", "2", "--jobs", "2", "--campaign", campaign,
              "--out", out_dir, "--quiet", pythonpath=package_copy)
    assert out.returncode == 0, out.stderr
    assert f"fig3: {out_dir / 'stub.png'}  {out_dir / 'stub.csv'}" in out.stdout
    rows = (out_dir / "stub.csv").read_text().splitlines()
    assert [r.split(",")[0] for r in rows] == ["stub_s1", "stub_s2"]
    assert all(r.split(",")[1].split()[0] == "4" for r in rows)  # 4 taps done
    assert (campaign / "manifest.json").exists()
    again = cli("fig3", "--dry-run", "--seeds", "2", "--campaign", campaign,
                pythonpath=package_copy)
    assert "stub_s2  [in.constant_eps, taps 4, done]" in again.stdout


def test_scales():
    assert get_scale("quick") is QUICK and get_scale("full") is FULL
    with pytest.raises(ValueError, match="scale = 'huge'"):
        get_scale("huge")
    # the paper's set-up (section II) and figure parameters
    assert (FULL.N, FULL.L, FULL.taps) == (4096, 32.0, 4000) and FULL.seeds >= 10
    assert FULL.fig2_eps == (5e-3, 5e-2, 0.15) and FULL.pore_eps == 2e-2
    assert FULL.dump_times == (1, 4, 10, 30, 100, 300, 1000, 4000)
    assert (FULL.ramp_dsqrt, FULL.ramp_taps_per_level, FULL.steady_last) == (0.025, 4000, 1000)
    assert len(FULL.profile_eps) == 4
    assert QUICK.N <= 512 and QUICK.taps <= 200 and QUICK.eta == 1e-5
    with pytest.raises(ValueError, match="Scale.N = 0"):
        QUICK.replace(N=0)
    with pytest.raises(ValueError, match="Scale.dump_times"):
        QUICK.replace(dump_times=(4, 1))
    with pytest.raises(ValueError, match="Scale.steady_last = 500"):
        QUICK.replace(steady_last=500)
    assert isinstance(QUICK.replace(seeds=5), Scale) and QUICK.replace(seeds=5).seeds == 5


@pytest.mark.skipif(not (BUILD / "tapmc-paper").exists(), reason="build/tapmc-paper not built")
def test_launcher_in_build():
    launcher = BUILD / "tapmc-paper"
    assert os.access(launcher, os.X_OK)
    text = launcher.read_text()
    assert "TAPMC_LMP" in text and "TAPMC_PORES" in text and "-m tapmc.paper" in text
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "TAPMC_LMP")}
    out = subprocess.run([str(launcher), "--help"], env=env, capture_output=True, text=True,
                         timeout=60)
    assert out.returncode == 0 and "fig10" in out.stdout


def test_paper_scale_plan():
    """The paper-scale plan: unique names, the tiers in order, the bell of Fig. 4 as the
    figures define it (same names and parameters, so the figures find the plan's runs), one
    initial packing per boundary condition in tier 1 (the paper's protocol: seed 1 for every
    eps), restart files every FULL.restart_every taps."""
    from tapmc.paper import fig2, fig3, fig6, fig10, plan

    tier1 = plan.tier_runs(1)
    everything = plan.runs(3)
    names = [s.name for s in everything]
    assert len(names) == len(set(names))
    assert names[:len(tier1)] == [s.name for s in tier1]
    assert [s.name for s in plan.runs(1)] == [s.name for s in tier1]
    by_name = {s.name: s.describe() for s in everything}
    for module in (fig2, fig3, fig6, fig10):
        for spec in module.runs(FULL, 1):
            assert by_name.get(spec.name) == spec.describe(), spec.name
    sqrt_eps = sorted(round(s.variables["eps"] ** 0.5, 4) for s in tier1
                      if s.name.startswith("const_pbc"))
    assert len(sqrt_eps) >= 8 and sqrt_eps[0] == 0.05 and sqrt_eps[-1] == 0.3873
    assert {0.0707, 0.2236, 0.3873} <= set(sqrt_eps)
    assert {s.seed for s in tier1} == {1}
    assert all(s.variables["rsteps"] == FULL.restart_every for s in everything)
    with pytest.raises(ValueError, match="tier = 4"):
        plan.runs(4)


def test_campaign_subcommand(tmp_path):
    from tapmc.paper import plan

    out = cli("campaign", "--dry-run", "--tier", "2", "--campaign", tmp_path / "c")
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    assert "full plan, tiers 1-2" in lines[0]
    assert len(lines) - 1 == len(plan.runs(2))
    assert all(line.endswith("to run]") for line in lines[1:])
    bad = cli("campaign", "--quick", "--dry-run", "--campaign", tmp_path / "c")
    assert bad.returncode == 2 and "paper-scale plan only" in bad.stderr
