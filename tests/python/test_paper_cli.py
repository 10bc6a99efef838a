# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The tapmc-paper command: argument validation, --help, the message for a missing figure
module, the Scale presets, and one end-to-end figure through a stub figure module (runs a
tiny campaign, draws, prints the PNG and CSV paths) on a copy of the package."""

import argparse
import hashlib
import json
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

from campaign_runs import WHOLE_RESTART  # noqa: E402
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


def test_help_lists_every_figure(capsys):
    out = _main(capsys, "--help")
    assert out.returncode == 0
    for fig in FIGURES:
        assert fig in out.stdout
    assert "report" in out.stdout
    sub = _main(capsys, "fig2", "--help")
    assert sub.returncode == 0
    for option in ("--quick", "--full", "--seeds", "--jobs", "--campaign", "--out"):
        assert option in sub.stdout


def _parsers(parser, name="tapmc-paper"):
    """(name, parser) of ``parser`` and of every sub-command under it, e.g. "tapmc-paper
    question ramp-levels"."""
    yield name, parser
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for sub_name, sub in action.choices.items():
                yield from _parsers(sub, f"{name} {sub_name}")


def test_every_option_has_help():
    """--help explains every option of every command, the questions' own options included:
    none is listed bare."""
    from tapmc.paper.cli import build_parser

    parsers = list(_parsers(build_parser()))
    assert any(name.startswith("tapmc-paper question ") for name, _ in parsers)
    bare = [f"{name} {'/'.join(action.option_strings)}" for name, parser in parsers
            for action in parser._actions
            if action.option_strings and not set(action.option_strings) <= {"-h", "--help"}
            and not (action.help or "").strip()]
    assert not bare, "options without a help text:\n  " + "\n  ".join(bare)


@pytest.mark.parametrize("args, message", [
    ((), "required: COMMAND"),
    (("fig1",), "invalid choice: 'fig1'"),
    (("fig2", "--seeds", "0"), "argument --seeds: 0 is not >= 1"),
    (("fig2", "--jobs", "two"), "argument --jobs: 'two' is not an integer"),
    (("fig2", "--quick", "--full"), "not allowed with argument"),
    (("fig2", "--mode", "mpi"), "invalid choice: 'mpi'"),
    # an unset shell variable must not make the working directory a campaign
    (("fig9", "--campaign", ""), "argument --campaign: an empty path (an unset shell variable?)"),
    (("fig9", "--out", ""), "argument --out: an empty path"),
    (("paper-ramp", "--campaign", " "), "argument --campaign: an empty path"),
    (("question", "first-tap", "--jobs", "0"), "argument --jobs: 0 is not >= 1"),
    (("question", "noise-floor", "--jobs", "-1"), "argument --jobs: -1 is not >= 1"),
    (("question", "seed-fits", "--campaign", ""), "argument --campaign: an empty path"),
])
def test_bad_arguments(args, message, capsys):
    out = _main(capsys, *args)
    assert out.returncode == 2
    assert message in out.stderr


def test_campaign_help_offers_only_what_it_takes(capsys):
    out = _main(capsys, "campaign", "--help")
    assert out.returncode == 0
    assert "--full" in out.stdout and "--tier" in out.stdout
    for refused in ("--quick", "--medium", "--seeds", "--fbc-start", "--out"):
        assert refused not in out.stdout, refused


def test_ctrl_c_outside_the_runs_is_one_line(monkeypatch, capsys):
    # Ctrl-C while starting up, reading or drawing (the runs stop with exit 3 on their own).
    from tapmc.paper import cli

    def interrupted(argv=None):
        raise KeyboardInterrupt

    monkeypatch.setattr(cli, "_main", interrupted)
    assert cli.main(["report", "--finished-only"]) == 130
    err = capsys.readouterr().err
    assert err == "tapmc-paper: interrupted (Ctrl-C)\n"


def test_ctrl_c_while_the_command_imports_is_one_line_too():
    """The command's modules take about 1.5 s to import; a Ctrl-C then ended in a traceback
    and status -2."""
    import signal
    import time

    env = dict(os.environ, PYTHONPATH=str(SOURCE / "tools" / "python"))
    child = subprocess.Popen([sys.executable, "-m", "tapmc.paper", "--help"], env=env,
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    time.sleep(0.3)
    child.send_signal(signal.SIGINT)
    _, err = child.communicate(timeout=60)
    assert child.returncode == 130 and err == "tapmc-paper: interrupted (Ctrl-C)\n", err


def test_finished_only_on_a_missing_campaign_creates_nothing(tmp_path, capsys):
    out = _main(capsys, "report", "--quick", "--finished-only", "--campaign", tmp_path / "none",
                "--out", tmp_path / "out")
    assert out.returncode == 2
    assert f"campaign directory {tmp_path / 'none'}: does not exist" in out.stderr
    assert not list(tmp_path.iterdir())


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
    # the stub's variables carry no eps: listed without a CPU-hour estimate, saying why
    assert "stub_s1  [in.constant_eps, taps 4, cost unknown, to run]" in dry.stdout
    assert "2 runs without an estimate: stub_s1 has no 'eps' variable" in dry.stdout
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
    # done, with the CPU and wall time its one attempt recorded
    assert "stub_s2  [in.constant_eps, taps 4, cost unknown, done; 1 attempt: " in again.stdout
    assert " h of wall time recorded]" in again.stdout and "unknown for" not in again.stdout


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
    from tapmc.paper import fig2, fig3, fig6, fig9, fig10, plan

    tier1 = plan.tier_runs(1)
    everything = plan.runs(3)
    names = [s.name for s in everything]
    assert len(names) == len(set(names))
    assert names[:len(tier1)] == [s.name for s in tier1]
    assert [s.name for s in plan.runs(1)] == [s.name for s in tier1]
    by_name = {s.name: s.describe() for s in everything}
    for module in (fig2, fig3, fig6, fig9, fig10):
        for spec in module.runs(FULL, 1):
            assert by_name.get(spec.name) == spec.describe(), spec.name
    sqrt_eps = sorted(round(s.variables["eps"] ** 0.5, 4) for s in tier1
                      if s.name.startswith("const_pbc"))
    assert len(sqrt_eps) >= 8 and sqrt_eps[0] == 0.05 and sqrt_eps[-1] == 0.3873
    assert {0.0707, 0.2236, 0.3873} <= set(sqrt_eps)
    assert {s.seed for s in tier1} == {1}
    assert all(s.variables["rsteps"] == FULL.restart_every for s in everything)
    with pytest.raises(ValueError, match="tier = 9"):
        plan.runs(9)
    # two jobs: the longest run (the ramp, one process) first, the rest in the same order
    two = [s.name for s in plan.runs(3, jobs=2)]
    assert two[0] == "ramp_pbc_s1" and sorted(two) == sorted(names)
    assert two[1:] == [n for n in names if n != "ramp_pbc_s1"]
    assert [s.name for s in plan.runs(2, jobs=2)] == [s.name for s in plan.runs(2)]
    with pytest.raises(ValueError, match="jobs = 0"):
        plan.runs(3, jobs=0)


def test_campaign_subcommand(tmp_path, capsys):
    from tapmc.paper import plan

    out = _main(capsys, "campaign", "--dry-run", "--tier", "2", "--campaign",
                tmp_path / "c")
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    assert "full plan, tiers 1-2" in lines[0]
    assert len(lines) - 2 == len(plan.runs(2))   # the header, the runs, the CPU hours left
    assert all(line.endswith("CPU h, to run]") for line in lines[1:-1])
    assert lines[-1].startswith("left to run: about ")
    two = _main(capsys, "campaign", "--dry-run", "--tier", "3", "--jobs", "2", "--campaign",
                tmp_path / "c")
    assert two.returncode == 0 and two.stdout.splitlines()[1].split()[0] == "ramp_pbc_s1"
    for option in ("--quick", "--medium", "--seeds", "--fbc-start"):  # the plan fixes them
        bad = _main(capsys, "campaign", option, "--dry-run", "--campaign", tmp_path / "c")
        assert bad.returncode == 2 and "unrecognized arguments" in bad.stderr, bad.stderr
    # --first: the matching runs first, in the patterns' order, the rest as planned
    names = [s.name for s in plan.runs(3, jobs=2)]
    first = _main(capsys, "campaign", "--dry-run", "--tier", "3", "--jobs", "2", "--campaign",
                tmp_path / "c", "--first", "ageing_*_s2", "const_fbc_eps0.02_s1", "ageing_*")
    assert first.returncode == 0, first.stderr
    order = [line.split()[0] for line in first.stdout.splitlines()[1:-1]]
    ageing = [n for n in names if n.startswith("ageing_")]
    head = ["ageing_pbc_eps0.01_s2", "const_fbc_eps0.02_s1"] + [
        n for n in ageing if n != "ageing_pbc_eps0.01_s2"]
    assert order == head + [n for n in names if n not in head]
    typo = _main(capsys, "campaign", "--dry-run", "--tier", "3", "--campaign", tmp_path / "c",
                 "--first", "agieng_*")
    assert typo.returncode == 2 and "--first 'agieng_*': matches no run" in typo.stderr


def test_dry_run_prices_the_taps_left_and_shows_the_recorded_cost(tmp_path, capsys):
    """A run under way is priced by its taps left from where it resumes (its latest restart
    file, not the last row of its per-tap file: the taps after the restart run again; the cost
    rule per tap: a ramp's strong levels cost more), and each run shows what its attempts
    recorded, naming those without a time (the sums are then lower bounds)."""
    from tapmc.paper import cost, plan

    folder = tmp_path / "c"
    spec = plan.runs(2)[0]
    (folder / "runs" / spec.name).mkdir(parents=True)
    (folder / "runs" / spec.name / "taps.dat").write_text(
        "# step level\n" + "".join(f"{k} 0\n" for k in range(131)))
    (folder / "runs" / spec.name / "restart.100").write_bytes(WHOLE_RESTART)
    attempts = [{"cpu_s": 3600.0, "wall_s": 7200.0}, {"interrupted": True, "log": "x"}]
    (folder / "manifest.json").write_text(json.dumps(
        {"format": 1, "runs": [{"name": spec.name, "attempts": attempts}]}))
    out = _main(capsys, "campaign", "--dry-run", "--tier", "2", "--campaign", folder)
    assert out.returncode == 0, out.stderr
    line = next(x for x in out.stdout.splitlines() if x.startswith(f"  {spec.name}  ["))
    left = cost.tap_seconds(spec, cost.CostRule.from_summary())[100:].sum() / 3600.0
    assert (f", resumes from tap 100, {left:.3g} CPU h to run; 2 attempts: 1 CPU h, 2 h of "
            "wall time recorded (CPU time unknown for 1, wall time unknown for 1)]") in line, line
    other = plan.runs(2)[1].name
    assert next(x for x in out.stdout.splitlines() if x.startswith(f"  {other}  [")) \
        .endswith("CPU h, to run]")
    # an executable of another build: the warning the campaign would start with, on stderr
    fake = tmp_path / "lmp_other"
    fake.write_text(SLEEPING_LMP)
    fake.chmod(0o755)
    other_build = _main(capsys, "campaign", "--dry-run", "--tier", "2", "--campaign", folder,
                        "--lmp", fake)
    assert other_build.returncode == 0 and other_build.stdout == out.stdout
    assert other_build.stderr.startswith(f"tapmc-paper: warning: the executable {fake} was "
                                         "built from fake, and this TAPMC is ")
    # a finished run whose outputs changed since (taps.dat cut) or whose DONE.json is damaged:
    # not "done", priced as a campaign would redo it
    taps = folder / "runs" / spec.name / "taps.dat"
    done = {"run": {"name": spec.name}, "outputs": {"taps.dat": {
        "sha256": hashlib.sha256(taps.read_bytes()).hexdigest(), "size": taps.stat().st_size}}}
    (folder / "runs" / spec.name / "DONE.json").write_text(json.dumps(done))
    intact = _main(capsys, "campaign", "--dry-run", "--tier", "2", "--campaign", folder)
    line = next(x for x in intact.stdout.splitlines() if x.startswith(f"  {spec.name}  ["))
    assert "CPU h, done;" in line, line
    taps.write_text(taps.read_text()[:200])
    for damage in ("damaged (taps.dat), to run again",
                   "damaged (DONE.json unreadable: the campaign stops at it)"):
        if "DONE.json" in damage:
            (folder / "runs" / spec.name / "DONE.json").write_text("{")
        out = _main(capsys, "campaign", "--dry-run", "--tier", "2", "--campaign", folder)
        line = next(x for x in out.stdout.splitlines() if x.startswith(f"  {spec.name}  ["))
        assert damage in line, line


def _one_line_error(out, rc=2):
    """A bad path ends with exit `rc` and one line on stderr, never a traceback."""
    assert out.returncode == rc, (out.stdout, out.stderr)
    lines = out.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("tapmc-paper: "), out.stderr
    return lines[0]


def _main(capsys, *args):
    """tapmc-paper in this process (a child process costs seconds of imports per case): the
    exit status and stdout / stderr; an exception, which would be a traceback, fails the
    test."""
    from tapmc.paper.cli import main

    try:
        status = main([str(a) for a in args])
    except SystemExit as done:  # argparse: --help (0) and usage errors (2)
        status = done.code
    captured = capsys.readouterr()
    return subprocess.CompletedProcess(args, status, captured.out, captured.err)


def _folder(tmp_path, manifest=None, scale=None):
    """A campaign folder with a manifest.json text (or a directory when manifest is ...) and
    a scale.json of Scale `scale`."""
    from tapmc.paper import _runs

    folder = tmp_path / "camp"
    folder.mkdir()
    if manifest is ...:
        (folder / "manifest.json").mkdir()
    elif manifest is not None:
        (folder / "manifest.json").write_text(manifest)
    if scale is not None:
        _runs.write_scale(folder, scale)
    return folder


@pytest.mark.parametrize("case", [
    "campaign_is_file", "campaign_below_file", "campaign_uncreatable", "out_is_file",
    "out_below_file", "out_uncreatable", "manifest_is_directory", "manifest_not_json",
    "manifest_not_object", "manifest_newer_format", "manifest_format_text",
    "manifest_format_true", "other_fbc_start", "manifest_attempts_damaged",
    "manifest_time_damaged", "other_preset", "campaign_other_preset",
    "edited_preset", "scale_json_damaged", "lmp_not_executable", "tapmc_lmp_missing"])
def test_bad_paths(tmp_path, case, capsys, monkeypatch):
    """Each bad path: exit 2, one line naming the path and what is wrong. The checks run
    before any LAMMPS run, so the real figure modules are used; --dry-run only where a check
    must not need it (the ones that write nothing)."""
    monkeypatch.setenv("TAPMC_LMP", str(LMP))
    afile = tmp_path / "F"
    afile.write_text("a regular file\n")
    camp = tmp_path / "camp"
    args, expected = None, None
    if case == "campaign_is_file":
        args = ["--campaign", afile]
        expected = f"campaign directory {afile}: exists and is not a directory"
    elif case == "campaign_below_file":
        args = ["--campaign", afile / "sub"]
        expected = (f"campaign directory {afile / 'sub'}: cannot be created: {afile} is not "
                    "a directory")
    elif case == "campaign_uncreatable":   # /proc takes no new entries, even from root
        args = ["--campaign", "/proc/tapmc-test-campaign"]
        expected = "campaign directory /proc/tapmc-test-campaign: cannot be created or written"
    elif case == "out_is_file":
        args = ["--campaign", camp, "--out", afile]
        expected = f"--out {afile}: exists and is not a directory"
    elif case == "out_below_file":
        args = ["--campaign", camp, "--out", afile / "figs"]
        expected = f"--out {afile / 'figs'}: cannot be created: {afile} is not a directory"
    elif case == "out_uncreatable":
        args = ["--campaign", camp, "--out", "/proc/tapmc-test-out"]
        expected = "--out /proc/tapmc-test-out: cannot be created or written"
    elif case == "manifest_is_directory":
        folder = _folder(tmp_path, manifest=...)
        args = ["--campaign", folder, "--dry-run"]
        expected = (f"campaign manifest {folder / 'manifest.json'}: cannot be read (Is a "
                    "directory)")
    elif case == "manifest_not_json":
        folder = _folder(tmp_path, manifest='{"runs": [')
        args = ["--campaign", folder, "--dry-run"]
        expected = f"campaign manifest {folder / 'manifest.json'}: not valid JSON"
    elif case == "manifest_not_object":
        folder = _folder(tmp_path, manifest="[1, 2]")
        args = ["--campaign", folder, "--dry-run"]
        expected = f"campaign manifest {folder / 'manifest.json'}: not a campaign manifest"
    elif case == "manifest_attempts_damaged":   # an AttributeError traceback before
        folder = _folder(tmp_path, manifest='{"runs": [{"name": "r1", "attempts": "oops"}]}')
        args = ["--campaign", folder, "--dry-run"]
        expected = (f"campaign manifest {folder / 'manifest.json'}: run 'r1': attempts is "
                    "'oops', not a list of attempt records")
    elif case == "manifest_time_damaged":       # a TypeError traceback, or "nan h", before
        folder = _folder(tmp_path, manifest='{"runs": [{"name": "r1", "attempts": '
                                            '[{"wall_s": "abc"}]}]}')
        args = ["--campaign", folder, "--dry-run"]
        expected = (f"campaign manifest {folder / 'manifest.json'}: run 'r1', attempt 1: "
                    "wall_s = 'abc', not a finite number of seconds >= 0")
    elif case == "manifest_newer_format":
        folder = _folder(tmp_path, manifest='{"format": 2, "runs": []}')
        args = ["--campaign", folder, "--dry-run"]
        expected = (f"campaign manifest {folder / 'manifest.json'}: format 2, this TAPMC reads "
                    "format 1; the campaign was made by another TAPMC version")
    elif case in ("manifest_format_text", "manifest_format_true"):   # true == 1 passed
        value = '"1"' if case == "manifest_format_text" else "true"
        folder = _folder(tmp_path, manifest='{"format": %s, "runs": []}' % value)
        args = ["--campaign", folder, "--dry-run"]
        shown = "True" if value == "true" else "'1'"
        expected = (f"campaign manifest {folder / 'manifest.json'}: format {shown}, this TAPMC "
                    "reads format 1")
    elif case == "other_fbc_start":   # it blamed another TAPMC's Scale
        folder = _folder(tmp_path, scale=QUICK.replace(fbc_start="paper"))
        args = ["--quick", "--campaign", folder, "--dry-run"]
        expected = (f"campaign {folder}: made with --fbc-start paper, not walls "
                    f"({folder / 'scale.json'}); use --fbc-start paper or another --campaign")
    elif case == "other_preset":
        folder = _folder(tmp_path, scale=QUICK)
        args = ["--full", "--campaign", folder]
        expected = (f"campaign {folder}: made with Scale 'quick', not the 'full' asked for "
                    f"({folder / 'scale.json'}: N = 512 instead of 4096")
    elif case == "campaign_other_preset":
        folder = _folder(tmp_path, scale=QUICK)
        out = _main(capsys, "campaign", "--campaign", folder)
        assert "use --quick or another --campaign" in _one_line_error(out)
        assert sorted(p.name for p in folder.iterdir()) == ["scale.json"]   # nothing ran
        return
    elif case == "edited_preset":
        folder = _folder(tmp_path, scale=QUICK.replace(taps=50, steady_last=10))
        args = ["--quick", "--campaign", folder, "--dry-run"]
        expected = (f"campaign {folder}: made with another Scale 'quick' than this TAPMC's "
                    f"({folder / 'scale.json'}: taps = 50 instead of 100, steady_last = 10 "
                    "instead of 25); use another --campaign")
    elif case == "scale_json_damaged":
        folder = _folder(tmp_path)
        (folder / "scale.json").write_text("{")
        args = ["--campaign", folder, "--dry-run"]
        expected = f"{folder / 'scale.json'}: not valid JSON"
    elif case == "lmp_not_executable":
        args = ["--campaign", camp, "--lmp", afile]
        expected = f"lmp = '{afile}': not an executable file"
    elif case == "tapmc_lmp_missing":   # another executable was taken silently before
        monkeypatch.setenv("TAPMC_LMP", str(tmp_path / "nowhere" / "lmp_tapmc"))
        args = ["--campaign", camp]
        expected = (f"TAPMC_LMP = '{tmp_path / 'nowhere' / 'lmp_tapmc'}': not an executable "
                    "file (unset it for build/lmp_tapmc or lmp_tapmc on the PATH, or pass --lmp)")
    line = _one_line_error(_main(capsys, "fig2", "--quiet", *args))
    assert line.startswith("tapmc-paper: " + expected), line
    if case in ("out_is_file", "out_below_file", "lmp_not_executable", "tapmc_lmp_missing"):
        assert not camp.exists(), "a refused command left a campaign folder behind"


def test_bad_path_process(tmp_path):
    """The command as a process: a campaign that is a regular file (a FileExistsError
    traceback before) ends with status 2 and one line."""
    afile = tmp_path / "F"
    afile.write_text("")
    line = _one_line_error(cli("fig2", "--quick", "--campaign", afile))
    assert line == f"tapmc-paper: campaign directory {afile}: exists and is not a directory"


SLEEPING_LMP = """#!/bin/sh
case " $* " in *" -in "*) ;; *) echo "TAPMC build: fake"; exit 0 ;; esac
touch started.$$
exec sleep 60
"""


def test_a_campaign_stopped_by_sigterm(tmp_path):
    """kill (or a batch system's SIGTERM) on a running campaign: its LAMMPS children stop
    (not left running for the minute they had), the command says where and how to go on in
    one line, and exits with STOPPED_STATUS, neither success nor a failed run."""
    import signal
    import time
    from tapmc.campaign import STOPPED_STATUS

    fake = tmp_path / "lmp_sleeps"
    fake.write_text(SLEEPING_LMP)
    fake.chmod(0o755)
    camp = tmp_path / "c"
    env = dict(os.environ, PYTHONPATH=str(PYTHON_DIR))
    proc = subprocess.Popen([sys.executable, "-m", "tapmc.paper", "fig2", "--quick", "--jobs",
                             "2", "--campaign", str(camp), "--lmp", str(fake), "--quiet"],
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.time() + 60
    while time.time() < deadline and len(list(camp.glob("runs/*/started.*"))) < 2:
        time.sleep(0.05)
    started = list(camp.glob("runs/*/started.*"))
    assert len(started) == 2, "the two runs did not start"
    t0 = time.time()
    proc.send_signal(signal.SIGTERM)
    out, err = proc.communicate(timeout=30)
    assert time.time() - t0 < 10, "the command waited for its children instead of stopping them"
    assert proc.returncode == STOPPED_STATUS, (out, err)
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith(
        "tapmc-paper: stopped by SIGTERM: 2 running runs stopped and recorded ("), err
    assert "running the campaign again resumes each from its latest restart file" in lines[0]
    for marker in started:   # no child left behind
        assert not Path("/proc", marker.name.split(".")[1]).exists()


@pytest.mark.skipif(not shutil.which("setpriv") and os.geteuid() == 0,
                    reason="root reads any folder; setpriv is needed to run as another user")
def test_unreadable_campaign_and_manifest(tmp_path):
    """Folders and manifests the user may not read (mode 000). Root reads them anyway, so as
    root the command runs as user nobody (setpriv) on a world-traversable copy of the
    situation."""
    import tempfile

    base = Path(tempfile.mkdtemp(prefix="tapmc_unreadable_"))
    try:
        base.chmod(0o755)
        closed = base / "closed"
        closed.mkdir(mode=0o000)
        closed.chmod(0o000)
        camp = base / "camp"
        camp.mkdir()
        camp.chmod(0o777)
        (camp / "manifest.json").write_text('{"runs": []}')
        (camp / "manifest.json").chmod(0o000)
        prefix = []
        if os.geteuid() == 0:
            prefix = ["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"]
        home = base / "home"   # matplotlib's cache: nobody cannot write root's home
        home.mkdir()
        home.chmod(0o777)
        env = dict(os.environ, PYTHONPATH=str(PYTHON_DIR), TAPMC_LMP=str(LMP), HOME=str(home),
                   MPLCONFIGDIR=str(home))
        for folder, expected in [
                (closed, f"campaign directory {closed}: cannot be read (Permission denied)"),
                (camp, f"campaign manifest {camp / 'manifest.json'}: cannot be read "
                       "(Permission denied)")]:
            out = subprocess.run([*prefix, sys.executable, "-m", "tapmc.paper", "fig2",
                                  "--dry-run", "--campaign", str(folder)], env=env,
                                 cwd=base, capture_output=True, text=True, timeout=120)
            assert _one_line_error(out) == "tapmc-paper: " + expected
    finally:
        for p in (base / "closed", base / "camp" / "manifest.json"):
            if p.exists():
                p.chmod(0o700)
        shutil.rmtree(base)


def test_campaign_keeps_the_scale_it_started_with(tmp_path, capsys):
    """The plan's campaign is pinned to its recorded Scale: a scale.json written before a
    field existed reads with that field's default, and one that differs from today's FULL is
    kept (with a note) instead of refused."""
    import json

    from tapmc.paper import _runs, plan

    folder = tmp_path / "c"
    folder.mkdir()
    old = FULL.as_dict()
    del old["p0_eps"]  # a record written before the field existed
    (folder / "scale.json").write_text(json.dumps(old))
    assert _runs.recorded_scale(folder) == FULL
    _runs.check_scale(folder, FULL)  # accepted: the missing field takes its default
    (folder / "scale.json").write_text(json.dumps(dict(old, restart_every=50)))
    out = _main(capsys, "campaign", "--dry-run", "--campaign", folder)
    assert out.returncode == 0, out.stderr
    assert "keeps the Scale it started with (restart_every differ" in out.stdout
    assert len([line for line in out.stdout.splitlines() if "to run]" in line]) == \
        len(plan.runs(1))
    (folder / "scale.json").write_text(json.dumps(dict(old, bogus=1)))
    bad = _main(capsys, "campaign", "--dry-run", "--campaign", folder)
    assert bad.returncode == 2 and "not a Scale record of this TAPMC" in bad.stderr


def test_output_closed_early_ends_quietly(tmp_path):
    """`tapmc-paper ... --dry-run | head -1`: the reader of the output is gone; the command
    stops without a traceback."""
    env = dict(os.environ, PYTHONPATH=str(PYTHON_DIR), TAPMC_LMP=str(LMP))
    proc = subprocess.Popen([sys.executable, "-m", "tapmc.paper", "campaign", "--tier", "3",
                             "--dry-run", "--campaign", str(tmp_path / "c")], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    proc.stdout.close()  # before Python has started: its first write meets a closed pipe
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=120) in (0, 1)
    assert "Traceback" not in err and "BrokenPipeError" not in err, err


def test_finished_view_reads_a_run_with_the_variables_it_ran_with(tmp_path):
    """report --finished-only of a paper-scale campaign: the figure modules' FULL asks 4000
    taps per ramp level, the plan ran 1000; the view takes the spec whose variables the run's
    DONE.json records, so that Fig. 4 cuts the ramp into the levels it has."""
    import json

    from tapmc.campaign import Campaign
    from tapmc.paper import _runs, cli

    ran = _runs.ramp_run(FULL.replace(ramp_taps_per_level=1000), "pbc", 1)
    preset = _runs.ramp_run(FULL, "pbc", 1)
    assert ran.name == preset.name and ran.variables["P"] != preset.variables["P"]
    folder = tmp_path / "runs" / ran.name
    folder.mkdir(parents=True)
    camp = Campaign(tmp_path, [preset], lmp=sys.executable)
    for done, per_level in ((ran, 1000), (preset, 4000)):
        (folder / "DONE.json").write_text(json.dumps({"run": done.describe()}))
        view, planned = cli._finished_view(camp, [ran])
        assert [s.variables["P"] for s in view.runs] == [per_level] and planned == 1
    (folder / "DONE.json").write_text("{}")   # no record: the plan's spec (what campaign runs)
    view, _ = cli._finished_view(camp, [ran])
    assert view.runs[0].variables["P"] == 1000


def test_report_prints_the_figures_where_the_report_leaves_them(tmp_path, capsys):
    """The report moves the figures it embeds into OUT/validation: it printed OUT/fig2.png, a
    path that no longer existed."""
    from types import SimpleNamespace

    def draw(campaign, out):
        out.mkdir(parents=True, exist_ok=True)
        png, csv = out / "fig2.png", out / "fig2.csv"
        png.write_text("png")
        csv.write_text("csv")
        return png, csv

    def report(campaign, out_dir, drawn, planned_runs=None):   # as validation.report moves them
        target = out_dir / "validation"
        target.mkdir()
        for png, csv in drawn.values():
            png.rename(target / png.name)
            csv.rename(target / csv.name)
        (out_dir / "validation.rst").write_text("page")
        return out_dir / "validation.rst"

    from tapmc.paper import cli as paper_cli
    validation = SimpleNamespace(FIG_DIR="validation", report=report)
    status = paper_cli._draw_and_report(SimpleNamespace(finished_only=False), None,
                                        [("fig2", SimpleNamespace(draw=draw))], validation,
                                        tmp_path, None)
    lines = capsys.readouterr().out.splitlines()
    assert status == 0 and lines[-1] == f"report: {tmp_path / 'validation.rst'}", lines
    printed = [Path(p) for p in lines[0].split(": ", 1)[1].split()]
    assert lines[0].startswith("fig2: ") and printed and all(p.is_file() for p in printed), lines


def test_the_report_draws_the_bells_three_seeds_and_no_run_of_another_protocol():
    """report --finished-only draws the plan's tiers 1-6 and tier 8's default-eta seeds of the
    bell: every square of Fig. 4 with 3 seeds. The 4000-tap ramps (tier 7) and the runs at
    other eta (tier 8's consteta_*) stay out of the figures: among them the page's summary
    listed 4 eta and 2 taps per level, and the claims' protocol labels failed."""
    from tapmc.paper import _runs, plan
    names = [spec.name for spec in plan.drawn_runs()]
    assert len(names) == len(set(names))
    for eps in FULL.steady_eps:
        for seed in (1, 2, 3):
            assert _runs.constant_eps_run(FULL, "pbc", eps, seed).name in names
    assert not [n for n in names if n.startswith(("consteta_", "paperramp"))]
    every = {spec.name for spec in plan.runs(8)}
    assert set(names) <= every and len(every - set(names)) == 7 + 16  # paper ramps, consteta


def test_the_readme_counts_the_runs_and_taps_the_pages_draw():
    """README.md says how many runs and taps the paper-scale page draws and the plan holds: the
    numbers of plan.drawn_runs() and plan.runs(), kept true as tiers join the figures."""
    import re
    from tapmc.paper import plan
    text = " ".join((SOURCE / "README.md").read_text().split())
    drawn = re.search(r"the `full` preset's (\d+) runs \(([\d ]+) taps", text)
    total = re.search(r"(\d+) runs and ([\d ]+) taps in all", text)
    assert drawn and total, "README.md no longer counts the paper-scale runs"
    for match, specs in ((drawn, plan.drawn_runs()), (total, plan.runs(8))):
        assert int(match.group(1)) == len(specs), match.group(0)
        assert int(match.group(2).replace(" ", "")) == sum(s.taps for s in specs), match.group(0)
