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
