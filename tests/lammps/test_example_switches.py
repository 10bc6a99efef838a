# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Every documented -var switch of every example input (examples/tapping, deposition, paper,
# scale: the `variable NAME index ...` lines of each input, which its comments and its folder's
# README document) runs at a tiny size for one to four taps with a non-default but valid value,
# and the switch has its documented effect where that is cheap to see: a file name, a column,
# the number of spheres, the substituted command in the log (eps, seeds, eta, window). Switches
# with independent effects share a run; a resumed run reuses the folder of the first. The
# switches an input validates (bc, resume, dump_ends, nlev, P) stop with the input's ERROR line
# and a non-zero exit. test_every_switch_is_exercised fails when an input gains a switch that
# no run here sets, so the table below cannot fall behind the inputs.
import math
import os
import re
import shlex
import subprocess
from pathlib import Path

import numpy as np
import pytest

from lmprun import LMP, min_gap, read_dump

EXAMPLES = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2])) / \
    "examples"

# The size of every paper-protocol run here: 64 spheres on an 8R x 8R base, a loose
# redeposition threshold, so that a tap costs milliseconds and the runs cost their start-up.
TINY = {"N": 64, "L": 8, "eta": 1e-5}

# Runs of each input, each a dict of -var switches (a list is a multi-valued index variable).
# The values differ from the inputs' defaults (test_every_switch_is_exercised checks that).
CONSTANT_EPS_FRESH = dict(
    TINY, R=0.6, eps=0.05, sqrteps=0.15, taps=2, seed=7, pack_seed=9, bc="fbc", pevery=1,
    zbins_per_R=3, xbins_per_R=2, lateral_R=3, wfrac=0.7, thermo_every=1, rsteps=1,
    taps_file="t.dat", zprof_file="z.dat", xprof_file="x.dat", dump_ends="yes",
    settle_keys="dmax 0.12 stop drift")
# eps without sqrteps takes effect: sqrteps = 0 is the default
CONSTANT_EPS_RESUME = dict(CONSTANT_EPS_FRESH, eps=0.03, taps=3, resume="yes",
                           resume_file="restart.1")
del CONSTANT_EPS_RESUME["sqrteps"]
# the paper's F.B.C. start (section IV.A): periodic deposition, walls, lifted spheres, agitation
CONSTANT_EPS_PAPER_START = dict(TINY, R=0.6, eps=0.05, taps=2, seed=7, pack_seed=9, bc="fbc",
                                thermo_every=1, dump_ends="yes", fbc_start="paper",
                                agitate_taps=2, agitate_eps=0.002)
RAMP_FRESH = dict(TINY, R=0.6, sqrt0=0.1, dsqrt=0.05, nlev=2, P=1, seed=3, pack_seed=5,
                  bc="fbc", zbins_per_R=2, thermo_every=1, rsteps=2, taps_file="r.dat",
                  zprof_file="rz.dat")
RAMP_RESUME = dict(RAMP_FRESH, resume="yes", resume_file="restart.2")
RAMP_STOP = dict(RAMP_FRESH, stop=3, rsteps=3)
AGEING_FRESH = dict(TINY, R=0.6, sqrteps=0.2, taps=2, seed=3, pack_seed=6, bc="fbc",
                    thermo_every=1, rsteps=1, taps_file="a.dat")
AGEING_RESUME = dict(AGEING_FRESH, eps=0.03, taps=3, resume="yes", resume_file="restart.1")
del AGEING_RESUME["sqrteps"]
PORES_FRESH = dict(TINY, R=0.6, sqrteps=0.1, taps=2, seed=3, pack_seed=6, bc="pbc",
                   dump_times=[2], thermo_every=1, rsteps=1, taps_file="p.dat",
                   dump_file="pd.*.txt")
PORES_RESUME = dict(PORES_FRESH, eps=0.03, taps=3, dump_times=[2, 3], resume="yes",
                    resume_file="restart.1")
del PORES_RESUME["sqrteps"]
TAPPING = dict(taps=1, eps=0.02, seed=11)   # these inputs fix N = 4096: one tap, ~2 s
QUICKSTART = dict(taps=12, eps=0.03, seed=5)   # N = 1024: ~2 s
SCALE = dict(N=64, L=8, R=0.6, eps=0.02, eta=1e-5, taps=2, seed=5)
CYLINDER = dict(N=300, R=0.6, tube_d=6, eps=0.03, taps=3, eta=1e-5, seed=5)   # ~1 s

RUNS = {
    "paper/in.constant_eps": [CONSTANT_EPS_FRESH, CONSTANT_EPS_RESUME, CONSTANT_EPS_PAPER_START],
    "paper/in.ramp": [RAMP_FRESH, RAMP_RESUME, RAMP_STOP],
    "paper/in.ageing": [AGEING_FRESH, AGEING_RESUME],
    "paper/in.pore_dumps": [PORES_FRESH, PORES_RESUME],
    "tapping/in.tapping_pbc": [TAPPING],
    "tapping/in.tapping_fbc": [TAPPING],
    "quickstart/in.quickstart": [QUICKSTART],
    "scale/in.paper_x100": [SCALE],
    "deposition/in.deposition": [{}],
    "cylinder/in.cylinder": [CYLINDER],
}


def example_command(lmp, example, variables):
    """The command line that runs examples/<example> with `variables` (a list value gives a
    multi-valued -var) under the LAMMPS executable `lmp`, logging to log.lammps."""
    cmd = [lmp, "-in", str(EXAMPLES / example), "-log", "log.lammps", "-nocite"]
    for name, value in variables.items():
        values = value if isinstance(value, list) else [value]
        cmd += ["-var", name] + [str(v) for v in values]
    return cmd


def run(example, variables, workdir):
    """Run lmp_tapmc on examples/<example> in `workdir`; returns (returncode, screen, log)."""
    proc = subprocess.run(example_command(LMP, example, variables), cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, timeout=300, stdin=subprocess.DEVNULL)
    log = Path(workdir) / "log.lammps"
    return proc.returncode, proc.stdout, log.read_text() if log.exists() else ""


def run_ok(example, variables, workdir):
    rc, screen, log = run(example, variables, workdir)
    assert rc == 0, screen
    return log


def commands(log, name):
    """The commands of the log that start with `name` after every variable substitution
    (LAMMPS echoes each stage; the last has no '$'), with whitespace collapsed."""
    out = []
    for line in log.splitlines():
        words = line.split()
        if words[:len(name.split())] == name.split() and "$" not in line:
            out.append(" ".join(words))
    return out


def thermo_steps(log):
    """Steps of the thermo rows of every run in the log."""
    steps, inside = [], False
    for line in log.splitlines():
        if line.split()[:1] == ["Step"]:   # 2026 right-aligns the header
            inside = True
        elif line.startswith("Loop time"):
            inside = False
        elif inside and not line.startswith("WARNING"):   # LAMMPS interleaves warnings
            steps.append(int(line.split()[0]))
    return steps


def table(path):
    """Rows of a fix print file (comment lines skipped) as a 2-d array."""
    rows = [[float(v) for v in line.split()] for line in Path(path).read_text().splitlines()
            if line.strip() and not line.startswith("#")]
    return np.array(rows)


def ave_time_blocks(path):
    """{step: rows} of a fix ave/time file in vector mode."""
    lines = [ln for ln in Path(path).read_text().splitlines() if not ln.startswith("#")]
    blocks, k = {}, 0
    while k < len(lines):
        step, nrows = (int(v) for v in lines[k].split())
        blocks[step] = lines[k + 1:k + 1 + nrows]
        k += 1 + nrows
    return blocks


def estimated_height(v):
    """hest of the paper inputs: the bed height at packing fraction 0.58."""
    side = v["L"] * v["R"]
    return v["N"] * 4.0 / 3.0 * math.pi * v["R"] ** 3 / (0.58 * side ** 2)


def check_packing(log, v):
    """N, R, pack_seed and the side L R reached create_packing and the box."""
    assert f"create_packing {v['N']} 1 {v['R']} {v['pack_seed']} floor 0.0" in \
        commands(log, "create_packing")
    side = v["L"] * v["R"]
    box = re.search(r"Created orthogonal box = \(0\S* 0\S* 0\S*\) to \((\S+) (\S+) ", log)
    assert box and float(box.group(1)) == pytest.approx(side) == float(box.group(2))


def check_fresh_common(log, v, eps):
    check_packing(log, v)
    assert f"fix tap all tapdilate {eps} floor 0.0" in commands(log, "fix tap")
    keys = f" {v['settle_keys']}" if "settle_keys" in v else ""  # in.constant_eps only
    assert f"fix settle all mc/settle {v['seed']} floor 0.0 eta {v['eta']}{keys}" in \
        commands(log, "fix settle")
    assert f"boundary {'f f' if v['bc'] == 'fbc' else 'p p'} fm" in commands(log, "boundary")
    assert thermo_steps(log) == list(range(v["taps"] + 1))   # thermo_every = 1


def test_constant_eps_every_switch(tmp_path):
    v = CONSTANT_EPS_FRESH
    log = run_ok("paper/in.constant_eps", v, tmp_path)
    check_fresh_common(log, v, "0.0225")     # eps = sqrteps^2, -var eps ignored
    rows = table(tmp_path / "t.dat")
    assert rows.shape == (3, 11) and list(rows[:, 0]) == [0, 1, 2]
    hest = estimated_height(v)
    z, x = ave_time_blocks(tmp_path / "z.dat"), ave_time_blocks(tmp_path / "x.dat")
    assert sorted(z) == sorted(x) == [0, 1, 2]           # pevery = 1
    assert all(len(b) == math.ceil(1.5 * hest / v["R"] * 3) for b in z.values())
    assert all(len(b) == 8 * 2 for b in x.values())        # L xbins_per_R
    (tprof,) = [c for c in commands(log, "compute tprof") if "window" in c]
    window = re.search(r"window (\S+) (\S+) lateral (\S+)", tprof)
    assert [float(w) for w in window.groups()] == pytest.approx([1.2, 0.7 * hest, 3 * 0.6])
    for step in (0, 2):                                     # dump_ends = yes
        ((_, box, bounds, atoms),) = read_dump(tmp_path / f"dump.{step}.lammpstrj")
        assert bounds == ["ff", "ff", "fm"] and len(atoms["id"]) == 64
        assert np.all(atoms["radius"] == 0.6) and box[0, 1] == pytest.approx(4.8)
    assert {p.name for p in tmp_path.glob("restart.*")} == {"restart.1", "restart.2"}
    assert not any((tmp_path / f).exists() for f in ("taps.dat", "profile_z.dat",
                                                     "profile_x.dat"))

    v = CONSTANT_EPS_RESUME
    log = run_ok("paper/in.constant_eps", v, tmp_path)
    assert "read_restart restart.1" in commands(log, "read_restart")
    assert "fix tap all tapdilate 0.03 floor 0.0" in commands(log, "fix tap")
    # appended; the resumed run writes the row of its restart step again
    assert list(table(tmp_path / "t.dat")[:, 0]) == [0, 1, 2, 1, 2, 3]
    assert sorted(ave_time_blocks(tmp_path / "z.dat.from1")) == [1, 2, 3]
    assert sorted(ave_time_blocks(tmp_path / "x.dat.from1")) == [1, 2, 3]
    assert (tmp_path / "dump.3.lammpstrj").exists()

    # the default resume_file (restart.*) is the restart of the latest step: 3
    log = run_ok("paper/in.constant_eps", dict(v, taps=4, resume_file="restart.*"), tmp_path)
    assert (tmp_path / "z.dat.from3").exists() and table(tmp_path / "t.dat")[-1, 0] == 4


def test_constant_eps_paper_fbc_start(tmp_path):
    """fbc_start = paper: a periodic deposition, then walls; the spheres crossing a wall are
    re-deposited above the bed between the walls, agitate_taps taps at agitate_eps (own seed)
    settle them, and the tapping sequence starts at t = 0 from a legal F.B.C. packing."""
    v = CONSTANT_EPS_PAPER_START
    log = run_ok("paper/in.constant_eps", v, tmp_path)
    assert commands(log, "boundary") == ["boundary p p fm"]
    assert "change_box all boundary f f fm" in commands(log, "change_box")
    assert "create_packing 64 1 0.6 9 floor 0.0" in commands(log, "create_packing")
    (lifted,) = re.findall(r"^Paper F.B.C. start: (\d+) of 64 spheres crossed a side wall", log,
                           re.M)
    assert 0 < int(lifted) < 64
    assert f"create_packing {lifted} 1 0.6 1000012 region above_bed" in \
        commands(log, "create_packing")
    assert "fix agitate_tap all tapdilate 0.002 floor 0.0" in commands(log, "fix agitate_tap")
    assert "fix agitate_settle all mc/settle 1000010 floor 0.0 eta 1e-05" in \
        commands(log, "fix agitate_settle")
    assert "fix settle all mc/settle 7 floor 0.0 eta 1e-05 check 0" in commands(log, "fix settle")
    # the agitation's 2 taps (thermo at its ends), then the sequence from t = 0 again
    assert thermo_steps(log) == [0, 2, 0, 1, 2]
    assert list(table(tmp_path / "taps.dat")[:, 0]) == [0, 1, 2]
    ((_, box, bounds, atoms),) = read_dump(tmp_path / "dump.0.lammpstrj")
    assert bounds == ["ff", "ff", "fm"] and len(atoms["id"]) == 64
    side = 8 * 0.6
    for axis in ("x", "y"):   # every sphere between the walls at t = 0
        assert np.all(atoms[axis] >= 0.6 - 1e-9) and np.all(atoms[axis] <= side - 0.6 + 1e-9)
    xyz = np.column_stack([atoms["x"], atoms["y"], atoms["z"]])
    gap, _, _ = min_gap(xyz, atoms["radius"], box, periodic_xy=(False, False), floor=0.0)
    assert gap > -1e-9 * 1.2                                # no overlap, none below the floor


def test_ramp_every_switch(tmp_path):
    v = RAMP_FRESH
    log = run_ok("paper/in.ramp", v, tmp_path)
    check_fresh_common(log, dict(v, taps=4), "v_eps")   # P (3 nlev - 2) = 4 taps
    rows = table(tmp_path / "r.dat")
    assert rows.shape == (5, 7)
    level, branch, sqrt_eps = rows[1:, 1], rows[1:, 2], rows[1:, 3]
    # one tap per level: up (0.1, 0.15), down to 0.1, up again to 0.15
    assert list(level) == [0, 1, 2, 3] and list(branch) == [0, 0, 1, 2]
    assert sqrt_eps == pytest.approx([0.1, 0.15, 0.1, 0.15])
    z = ave_time_blocks(tmp_path / "rz.dat")
    assert sorted(z) == [0, 1, 2, 3, 4]                    # every P taps
    assert all(len(b) == math.ceil(1.5 * estimated_height(v) / v["R"] * 2) for b in z.values())
    assert {p.name for p in tmp_path.glob("restart.*")} == {"restart.2", "restart.4"}

    log = run_ok("paper/in.ramp", RAMP_RESUME, tmp_path)
    assert "read_restart restart.2" in commands(log, "read_restart")
    assert sorted(ave_time_blocks(tmp_path / "rz.dat.from2")) == [2, 3, 4]
    assert table(tmp_path / "r.dat")[-1, 0] == 4

    # stop: the same ramp ended after step 3 (a replay of its first levels), tap for tap
    replay = tmp_path / "replay"
    replay.mkdir()
    run_ok("paper/in.ramp", RAMP_STOP, replay)
    assert (replay / "r.dat").read_text() == \
        "".join((tmp_path / "r.dat").read_text().splitlines(keepends=True)[:5])
    assert {p.name for p in replay.glob("restart.*")} == {"restart.3"}


def test_ageing_every_switch(tmp_path):
    v = AGEING_FRESH
    log = run_ok("paper/in.ageing", v, tmp_path)
    check_fresh_common(log, v, "0.04")
    rows = table(tmp_path / "a.dat")
    assert rows.shape == (3, 4) and list(rows[:, 0]) == [0, 1, 2]
    assert {p.name for p in tmp_path.glob("restart.*")} == {"restart.1", "restart.2"}

    log = run_ok("paper/in.ageing", AGEING_RESUME, tmp_path)
    assert "read_restart restart.1" in commands(log, "read_restart")
    assert "fix tap all tapdilate 0.03 floor 0.0" in commands(log, "fix tap")
    assert list(table(tmp_path / "a.dat")[:, 0]) == [0, 1, 2, 1, 2, 3]


def test_pore_dumps_every_switch(tmp_path):
    v = PORES_FRESH
    log = run_ok("paper/in.pore_dumps", v, tmp_path)
    check_fresh_common(log, v, "0.01")
    assert table(tmp_path / "p.dat").shape == (3, 4)
    assert sorted(p.name for p in tmp_path.glob("pd.*.txt")) == ["pd.0.txt", "pd.2.txt"]
    ((step, box, bounds, atoms),) = read_dump(tmp_path / "pd.2.txt")
    assert step == 2 and bounds == ["pp", "pp", "fm"] and len(atoms["id"]) == 64
    assert np.all(atoms["radius"] == 0.6)

    log = run_ok("paper/in.pore_dumps", PORES_RESUME, tmp_path)
    assert "read_restart restart.1" in commands(log, "read_restart")
    assert "fix tap all tapdilate 0.03 floor 0.0" in commands(log, "fix tap")
    # a resumed run dumps the listed steps after the restart, not the restart step itself
    assert sorted(p.name for p in tmp_path.glob("pd.*.txt")) == ["pd.0.txt", "pd.2.txt",
                                                                  "pd.3.txt"]
    assert table(tmp_path / "p.dat")[-1, 0] == 3


@pytest.mark.parametrize("example", ["tapping/in.tapping_pbc", "tapping/in.tapping_fbc"])
def test_tapping_switches(tmp_path, example):
    log = run_ok(example, TAPPING, tmp_path)
    assert "create_packing 4096 1 0.5 11 floor 0.0" in commands(log, "create_packing")
    assert "fix tap all tapdilate 0.02 floor 0.0" in commands(log, "fix tap")
    assert "fix settle all mc/settle 11 floor 0.0" in commands(log, "fix settle")
    assert thermo_steps(log) == [0, 1]


def test_quickstart_switches_and_its_plot(tmp_path):
    """in.quickstart writes one line per tap (tap 0 included) to taps.dat; plot_compaction.py
    draws it and names the run's settings, read back from the log."""
    log = run_ok("quickstart/in.quickstart", QUICKSTART, tmp_path)
    assert "create_packing 1024 1 0.5 5 floor 0.0" in commands(log, "create_packing")
    assert "fix tap all tapdilate 0.03 floor 0.0" in commands(log, "fix tap")
    assert "fix settle all mc/settle 5 floor 0.0" in commands(log, "fix settle")
    taps = table(tmp_path / "taps.dat")
    assert taps[:, 0].tolist() == list(range(13))
    assert np.all((taps[:, 1:3] > 0.5) & (taps[:, 1:3] < 0.65))
    env = dict(os.environ, PYTHONPATH=str(EXAMPLES.parent / "tools" / "python"))
    plot = subprocess.run(["/usr/bin/python3", str(EXAMPLES / "quickstart" / "plot_compaction.py")],
                          cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120)
    assert plot.returncode == 0, plot.stderr
    assert ("N = 1024, box 16R x 16R (P.B.C.), eps = 0.03, eta = 1e-7 (default), "
            "stop change (default), seed = 5, 12 taps") in plot.stdout
    assert (tmp_path / "compaction.png").stat().st_size > 10000
    rows = np.loadtxt(tmp_path / "compaction.csv", delimiter=",", skiprows=1)
    assert np.allclose(rows[:, :4], taps[:, :4])


def test_quickstart_plot_names_a_bad_file(tmp_path):
    (tmp_path / "taps.dat").write_text("# tap Phi_b Phi_c Z sweeps\n0 0.5 0.5\n")
    env = dict(os.environ, PYTHONPATH=str(EXAMPLES.parent / "tools" / "python"))
    plot = subprocess.run(["/usr/bin/python3", str(EXAMPLES / "quickstart" / "plot_compaction.py")],
                          cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120)
    assert plot.returncode != 0 and "taps.dat" in plot.stderr and "Traceback" not in plot.stderr


def test_scale_switches(tmp_path):
    v = SCALE
    log = run_ok("scale/in.paper_x100", v, tmp_path)
    check_packing(log, dict(v, pack_seed=v["seed"]))
    assert "fix tap all tapdilate 0.02 floor 0.0" in commands(log, "fix tap")
    assert "fix settle all mc/settle 5 floor 0.0 eta 1e-05" in commands(log, "fix settle")
    assert thermo_steps(log) == [0, 1, 2]
    assert "for 2 steps with 64 atoms" in log


def test_deposition_runs(tmp_path):
    log = run_ok("deposition/in.deposition", {}, tmp_path)
    assert "Initial packing: N = 4096" in log


@pytest.mark.parametrize("example, name, value, message", [
    ("paper/in.constant_eps", "bc", "xyz", "ERROR: bc = xyz; allowed values: pbc, fbc"),
    ("paper/in.constant_eps", "resume", "maybe",
     "ERROR: resume = maybe; allowed values: no, yes"),
    ("paper/in.constant_eps", "dump_ends", "all",
     "ERROR: dump_ends = all; allowed values: yes, no"),
    ("paper/in.constant_eps", "fbc_start", "xyz",
     "ERROR: fbc_start = xyz; allowed values: walls, paper"),
    ("paper/in.constant_eps", "fbc_start", "paper",
     "ERROR: fbc_start = paper needs bc = fbc (bc = pbc)"),
    ("paper/in.ramp", "bc", "xyz", "ERROR: bc = xyz; allowed values: pbc, fbc"),
    ("paper/in.ramp", "resume", "maybe", "ERROR: resume = maybe; allowed values: no, yes"),
    ("paper/in.ramp", "nlev", "0", "ERROR: nlev = 0; allowed: an integer >= 1"),
    ("paper/in.ramp", "P", "0", "ERROR: P = 0; allowed: an integer >= 1"),
    ("paper/in.ramp", "nlev", "1.5", "ERROR: nlev = 1.5; allowed: an integer >= 1"),
    ("paper/in.ramp", "P", "2.5", "ERROR: P = 2.5; allowed: an integer >= 1"),
    ("paper/in.ramp", "stop", "-1",
     "ERROR: stop = -1; allowed: an integer from 0 (the whole ramp) to 136000"),
    ("paper/in.ramp", "stop", "136001",
     "ERROR: stop = 136001; allowed: an integer from 0 (the whole ramp) to 136000"),
    ("paper/in.ramp", "stop", "2.5",
     "ERROR: stop = 2.5; allowed: an integer from 0 (the whole ramp) to 136000"),
    ("paper/in.ageing", "bc", "xyz", "ERROR: bc = xyz; allowed values: pbc, fbc"),
    ("paper/in.ageing", "resume", "maybe", "ERROR: resume = maybe; allowed values: no, yes"),
    ("paper/in.pore_dumps", "bc", "xyz", "ERROR: bc = xyz; allowed values: pbc, fbc"),
    ("paper/in.pore_dumps", "resume", "maybe",
     "ERROR: resume = maybe; allowed values: no, yes"),
])
def test_invalid_switch_value(tmp_path, example, name, value, message):
    rc, screen, log = run(example, dict(TINY, **{name: value}), tmp_path)
    assert rc != 0
    assert message in screen.splitlines() and message in log.splitlines()
    assert not list(tmp_path.glob("*.dat")), "the input ran before checking its switches"


@pytest.mark.parametrize("example", ["paper/in.constant_eps", "paper/in.ageing",
                                     "paper/in.pore_dumps"])
def test_sqrteps_that_is_no_number_stops(tmp_path, example):
    """A sqrteps that is not a number stops before anything runs, naming the switch (it used
    to be ignored, leaving the default eps)."""
    rc, screen, _ = run(example, dict(TINY, sqrteps="x"), tmp_path)
    assert rc != 0
    assert any(line.startswith("ERROR: Variable sqrteps_must_be_a_number")
               for line in screen.splitlines()), screen
    assert not list(tmp_path.glob("*.dat"))


def index_variables(example):
    """{name: default} of the `variable NAME index ...` lines of an input."""
    out = {}
    for line in (EXAMPLES / example).read_text().splitlines():
        m = re.match(r"variable\s+(\w+)\s+index\s+([^#]*)", line)
        if m:
            out[m.group(1)] = shlex.split(m.group(2))  # "a b" is one value, as LAMMPS reads it
    return out


def test_every_switch_is_exercised():
    """Every index variable of every example input is set by a run above, at least once to a
    value other than its default; a run sets no variable the input does not declare."""
    inputs = sorted(str(p.relative_to(EXAMPLES)) for p in EXAMPLES.glob("*/in.*"))
    assert sorted(RUNS) == inputs
    for example, runs in RUNS.items():
        declared = index_variables(example)
        for v in runs:
            assert set(v) <= set(declared), (example, set(v) - set(declared))
        for name, default in declared.items():
            values = [[str(x) for x in (v[name] if isinstance(v[name], list) else [v[name]])]
                      for v in runs if name in v]
            assert any(val != default for val in values), (example, name, default)


def test_cylinder_example_taps_in_its_tube(tmp_path):
    """in.cylinder deposits and taps inside one tube: a row per tap (tap 0 included) with Phi_b,
    <Phi^c>, <Z>, the wall zone and the core, every sphere inside the wall after the taps, and the
    radial profile at t = 0 and at the end over the annuli 0 .. Rc."""
    log = run_ok("cylinder/in.cylinder", CYLINDER, tmp_path)
    rows = table(tmp_path / "taps.dat")
    assert rows.shape == (CYLINDER["taps"] + 1, 7)
    assert np.all((rows[:, 1:3] > 0.3) & (rows[:, 1:3] < 0.7))
    assert np.all(rows[1:, 6] > 0)  # every tap ran a redeposition
    assert "container 'tube'" in log
    blocks = ave_time_blocks(tmp_path / "profile_r.dat")
    assert sorted(blocks) == [0, CYLINDER["taps"]]
    radii = [float(line.split()[1]) for line in blocks[CYLINDER["taps"]]]
    rc = CYLINDER["tube_d"] * CYLINDER["R"]
    assert len(radii) == 20 and 0 < radii[0] < radii[-1] < rc
