# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# tapmc-paper question ramp-levels on a tiny finished ramp: the campaign kept the restart
# files of the level ends, the chosen levels are continued from them at their sqrt(eps), and
# the CSV the report renders compares each level after its own taps and after the longer run.
import csv
import os
import subprocess
import sys
from pathlib import Path

from lmprun import LMP

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
#: ``tapmc-paper question`` of this source tree
QUESTION = [sys.executable, "-c", "import sys; sys.path.insert(0, sys.argv.pop(1)); "
            "from tapmc.paper.cli import main; sys.exit(main())", str(SOURCE / "tools" / "python"),
            "question"]
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc.campaign import Campaign, RunSpec  # noqa: E402
from tapmc.paper import questions  # noqa: E402

# 64 spheres, 3 levels up (sqrt(eps) 0.05, 0.15, 0.25), down, up again: 7 levels of 10 taps
RAMP = dict(N=64, L=8, eta=1e-5, rsteps=5, thermo_every=5, P=10, nlev=3, sqrt0=0.05,
            dsqrt=0.1)


def test_ramp_levels_continues_the_kept_level_ends(tmp_path):
    spec = RunSpec("ramp_pbc_s1", SOURCE / "examples" / "paper" / "in.ramp", RAMP, seed=3)
    Campaign(tmp_path / "c", [spec], lmp=str(LMP), jobs=1).run(progress=False)
    kept = sorted(int(p.name.split(".")[1])
                  for p in (tmp_path / "c" / "runs" / spec.name).glob("restart.*"))
    assert kept == [10, 20, 30, 40, 50, 60, 70]
    out = tmp_path / "q"
    done = subprocess.run([*QUESTION,
                           "ramp-levels", "--lmp", str(LMP), "--campaign", str(tmp_path / "c"),
                           "--levels", "2", "3", "--extend", "20", "--out", str(out)],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    with open(out / "ramp_levels.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert [(r["level"], r["branch"], r["sqrt_eps"]) for r in rows] == [
        ("2", "0", "0.25"), ("3", "1", "0.15")]
    assert all(r["taps"] == "10" and r["taps_long"] == "30" and r["start"] == "run"
               for r in rows)
    text = "\n".join(questions.render_section(out))
    assert "``ramp-levels``" in text and "change against 30?" in text
    assert "2 (first increase)" in text and "3 (decrease)" in text
    # a later call for one level keeps the other's row (its restart may be gone by then)
    again = subprocess.run([*QUESTION,
                            "ramp-levels", "--lmp", str(LMP), "--campaign", str(tmp_path / "c"),
                            "--levels", "3", "--extend", "20", "--out", str(out)],
                           capture_output=True, text=True, timeout=300)
    assert again.returncode == 0, again.stderr
    with open(out / "ramp_levels.csv", newline="") as f:
        assert list(csv.DictReader(f)) == rows
    # continued in its own folder: a longer --extend resumes it from its latest restart and
    # gives the taps of one uninterrupted continuation, bit for bit
    steps = []
    for extend, work in ((10, "w1"), (20, "w1"), (20, "w2")):
        again = subprocess.run([*QUESTION,
                                "ramp-levels", "--lmp", str(LMP), "--campaign",
                                str(tmp_path / "c"), "--levels", "2", "--extend", str(extend),
                                "--work", str(tmp_path / work), "--out", str(tmp_path / work)],
                               capture_output=True, text=True, timeout=300)
        assert again.returncode == 0, again.stderr
        steps.append(sorted(int(p.name.split(".")[1])
                            for p in (tmp_path / work / "runs" / "ramp_pbc_s1_level2")
                            .glob("restart.*")))
    assert steps == [[40], [50], [50]]   # only the latest restart is kept
    one, two = ((tmp_path / w / "ramp_levels.csv").read_text() for w in ("w1", "w2"))
    assert one == two and ",10,30," in one
    # a level whose restart was not kept names the file
    bad = subprocess.run([*QUESTION,
                          "ramp-levels", "--lmp", str(LMP), "--campaign", str(tmp_path / "c"),
                          "--levels", "9", "--out", str(out)], capture_output=True, text=True,
                         timeout=60)
    assert bad.returncode != 0 and "restart.100 not found" in bad.stderr

    # a level whose restart file is gone: --replay runs the ramp again up to the level's end
    # (in.ramp -var stop); the replay reproduces the campaign's rows bit for bit, and the
    # level's row is the one the kept file gave
    def levels_csv(out, *extra):
        done = subprocess.run([*QUESTION,
                               "ramp-levels", "--lmp", str(LMP), "--campaign",
                               str(tmp_path / "c"), "--levels", "1", "--extend", "20",
                               "--out", str(out), *extra], capture_output=True, text=True,
                              timeout=300)
        return done, (list(csv.DictReader(open(out / "ramp_levels.csv", newline="")))
                      if done.returncode == 0 else None)

    done, (kept,) = levels_csv(tmp_path / "k")
    assert done.returncode == 0, done.stderr
    assert kept["start"] == "run"
    (tmp_path / "c" / "runs" / spec.name / "restart.20").unlink()
    done, _ = levels_csv(tmp_path / "r")
    assert done.returncode != 0 and "--replay" in done.stderr
    done, (replayed,) = levels_csv(tmp_path / "r", "--replay")
    assert done.returncode == 0, done.stderr
    assert replayed.pop("start") == "replay (identical)"
    kept.pop("start")
    assert replayed == kept
    replay = (tmp_path / "r" / "partial" / "ramp_levels" / "replays" / "runs"
              / "ramp_pbc_s1_replay")
    assert sorted(p.name for p in replay.glob("restart.*")) == ["restart.10", "restart.20"]
    text = "\n".join(questions.render_section(tmp_path / "r"))
    assert "1 (first increase; replayed)" in text
    assert "the replay's taps against the campaign's: identical." in text


def test_ramp_pores_measures_nu_at_the_kept_level_ends(tmp_path):
    """tapmc-paper question ramp-pores on a tiny finished ramp: nu at every kept level end
    (the pore analysis of Fig. 10 on the packing of the restart file), level, branch and
    sqrt(eps) as in.ramp numbers them; a level with no restart file is refused naming it, and a
    later call for some levels keeps the rows of the others."""
    spec = RunSpec("ramp_pbc_s1", SOURCE / "examples" / "paper" / "in.ramp", RAMP, seed=3)
    Campaign(tmp_path / "c", [spec], lmp=str(LMP), jobs=1).run(progress=False)
    out = tmp_path / "q"

    def ramp_pores(*extra):
        return subprocess.run([*QUESTION,
                               "ramp-pores", "--lmp", str(LMP), "--campaign", str(tmp_path / "c"),
                               "--work", str(tmp_path / "w"), "--out", str(out), *extra],
                              capture_output=True, text=True, timeout=300)

    done = ramp_pores()
    assert done.returncode == 0, done.stderr
    with open(out / "ramp_pores.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    # 3 levels up (0.05, 0.15, 0.25), down (0.15, 0.05), up again (0.15, 0.25)
    assert {r["run"] for r in rows} == {"ramp_pbc_s1"}
    assert [(r["level"], r["branch"], r["sqrt_eps"], r["step"]) for r in rows] == [
        ("0", "0", "0.05", "10"), ("1", "0", "0.15", "20"), ("2", "0", "0.25", "30"),
        ("3", "1", "0.15", "40"), ("4", "1", "0.05", "50"), ("5", "2", "0.15", "60"),
        ("6", "2", "0.25", "70")]
    nus = [float(r["nu"]) for r in rows]
    assert all(0.01 < nu < 0.5 for nu in nus) and len(set(nus)) > 1
    assert all(float(r["nu_sem"]) > 0 and r["source"] == "run" for r in rows)
    text = "\n".join(questions.render_section(out))
    assert "``ramp-pores``" in text and "0 (first increase)" in text and "4 (decrease)" in text
    refused = ramp_pores("--levels", "9")
    assert refused.returncode != 0 and "--levels 9" in refused.stderr and "0 .. 6" in refused.stderr
    # a level whose restart file is gone: measured again from its dump, the same row
    (tmp_path / "c" / "runs" / spec.name / "restart.20").unlink()
    again = ramp_pores("--levels", "1")
    assert again.returncode == 0, again.stderr
    with open(out / "ramp_pores.csv", newline="") as f:
        assert list(csv.DictReader(f)) == rows
    # neither restart file nor dump (a new work folder): refused, naming the way out; the
    # levels still there are measured, the row of the gone one kept
    gone = subprocess.run([*QUESTION,
                           "ramp-pores", "--lmp", str(LMP), "--campaign", str(tmp_path / "c"),
                           "--work", str(tmp_path / "w2"), "--out", str(out), "--levels", "1"],
                          capture_output=True, text=True, timeout=300)
    assert gone.returncode != 0 and "levels [1]" in gone.stderr and "--replay" in gone.stderr
    kept = subprocess.run([*QUESTION,
                           "ramp-pores", "--lmp", str(LMP), "--campaign", str(tmp_path / "c"),
                           "--work", str(tmp_path / "w2"), "--out", str(out)],
                          capture_output=True, text=True, timeout=300)
    assert kept.returncode == 0, kept.stderr
    with open(out / "ramp_pores.csv", newline="") as f:
        assert [r["level"] for r in csv.DictReader(f)] == [r["level"] for r in rows]
