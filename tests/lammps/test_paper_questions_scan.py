# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# tapmc-paper question knob scans (theta0, dmax) keep their rows in <out>/partial/ until
# every run is in, so that the report never reads half a scan; a scan started again skips the
# runs its CSV has (a finished scan is reopened, and published again when whole).
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


def scan(out, *seeds):
    return subprocess.run([*QUESTION, "dmax",
                           "--N", "64", "--lmp", str(LMP), "--out", str(out), "--seeds",
                           *map(str, seeds)], capture_output=True, text=True, timeout=300)


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_scan_is_published_whole_and_resumes(tmp_path):
    partial = tmp_path / "partial" / "dmax_N64.csv"
    done = scan(tmp_path, 1)
    assert done.returncode == 0, done.stderr
    first = rows(tmp_path / "dmax_N64.csv")
    assert len(first) == 7 and not partial.exists()
    # a scan stopped after two runs: its rows wait in partial/, the report folder has none
    partial.parent.mkdir(exist_ok=True)
    with open(partial, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(first[0]))
        writer.writeheader()
        writer.writerows(first[:2])
    (tmp_path / "dmax_N64.csv").unlink()
    done = scan(tmp_path, 1)
    assert done.returncode == 0, done.stderr
    again = rows(tmp_path / "dmax_N64.csv")
    assert again[:2] == first[:2] and len(again) == 7 and not partial.exists()
    assert done.stdout.count("sweeps per tap") == 5          # only the missing runs ran
    assert [r["phi_c_end"] for r in again] == [r["phi_c_end"] for r in first]  # same seed
    # started again when whole: it reopens the finished scan, runs nothing, publishes it again
    done = scan(tmp_path, 1)
    assert done.returncode == 0, done.stderr
    assert "sweeps per tap" not in done.stdout
    assert rows(tmp_path / "dmax_N64.csv") == again and not partial.exists()


def test_theta0_scan_of_the_solid_law_beyond_pi_over_2(tmp_path):
    # --theta-law solid --wide: the widths beyond the paper's truncation, fix mc/settle
    # theta_law solid, into their own CSV (tags solid, wide), which the claims leave out (they
    # test another reading of eq. 1, not the paper's claim).
    done = subprocess.run([*QUESTION, "theta0",
                           "--N", "64", "--lmp", str(LMP), "--out", str(tmp_path), "--seeds", "1",
                           "--theta-law", "solid", "--wide"],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    table = rows(tmp_path / "theta0_solid_wide_N64.csv")
    assert [float(r["theta0_over_pi"]) for r in table] == [0.75, 1.0, 30.0]
    sys.path.insert(0, str(SOURCE / "tools" / "python"))
    from tapmc.paper.claims import scan_files
    (tmp_path / "theta0_N64.csv").write_text("")
    assert [p.name for p in scan_files(tmp_path, "theta0")] == ["theta0_N64.csv"]


def test_killed_scan_resumes_where_it_stopped(tmp_path):
    """A scan killed midway (its LAMMPS run dies with it) is started again: the rows written
    before the kill stay as they were, the runs finished before it are not run again (their
    campaign folder keeps them), and the CSV is published whole."""
    import signal
    import time

    partial = tmp_path / "partial" / "dmax_N64.csv"
    command = [*QUESTION, "dmax", "--N", "64", "--lmp", str(LMP), "--out", str(tmp_path),
               "--seeds", "1", "2"]
    running = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True)
    deadline = time.monotonic() + 240
    while time.monotonic() < deadline and running.poll() is None:
        if partial.is_file() and len(rows(partial)) >= 2:
            break
        time.sleep(0.2)
    assert running.poll() is None, running.communicate()
    running.send_signal(signal.SIGKILL)
    running.communicate()
    before = rows(partial)
    assert 2 <= len(before) < 14 and not (tmp_path / "dmax_N64.csv").exists()
    done = subprocess.run(command, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    table = rows(tmp_path / "dmax_N64.csv")
    assert len(table) == 14 and table[:len(before)] == before and not partial.exists()
    assert done.stdout.count("sweeps per tap") == 14 - len(before)


def test_theta0_scan_of_an_alternative_law_at_chosen_widths(tmp_path):
    # --theta-law linear --widths: only those widths, every run with fix mc/settle theta_law
    # linear, into theta0_linear_N64.csv (which the claim theta0-optimum leaves out)
    done = subprocess.run([*QUESTION, "theta0", "--N", "64", "--lmp", str(LMP), "--out",
                           str(tmp_path), "--seeds", "1", "2", "--theta-law", "linear",
                           "--widths", "0.0625", "0.5"],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    table = rows(tmp_path / "theta0_linear_N64.csv")
    assert [(float(r["theta0_over_pi"]), r["seed"]) for r in table] == [
        (0.0625, "1"), (0.5, "1"), (0.0625, "2"), (0.5, "2")]
    logs = list(tmp_path.rglob("log.lammps"))
    assert len(logs) == 4
    assert all("theta_law linear" in log.read_text() for log in logs)
    sys.path.insert(0, str(SOURCE / "tools" / "python"))
    from tapmc.paper.claims import scan_files
    assert scan_files(tmp_path, "theta0") == []
    # a width outside fix mc/settle's range: one line naming it, exit 1, nothing run
    bad = subprocess.run([*QUESTION, "theta0", "--N", "64", "--lmp", str(LMP), "--out",
                          str(tmp_path / "bad"), "--widths", "0.25", "-1"],
                         capture_output=True, text=True, timeout=60)
    assert bad.returncode == 2 and "--widths -1: theta0 = -1 pi is outside" in bad.stderr
    assert not (tmp_path / "bad").exists()
