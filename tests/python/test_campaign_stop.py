# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""tapmc.campaign stopped by a signal (SIGTERM, Ctrl-C): the running runs' attempts recorded
whole (wall and CPU time, the last tap), no other run started, CampaignStopped and its exit
status, the resume; pool and partition modes, and a signal that reaches a child first."""

import json
import shutil
import signal
import subprocess
import sys
import time

import pytest

from campaign_runs import CONSTANT_EPS, LMP, SOURCE, TINY, steps
from tapmc.campaign import STOPPED_STATUS, Campaign, RunSpec, provenance  # noqa: E402

pytestmark = pytest.mark.skipif(not LMP.is_file(), reason=f"no LAMMPS executable at {LMP}")


STOPPABLE = """
import sys
sys.path.insert(0, {python!r})
from tapmc.campaign import STOPPED_STATUS, Campaign, CampaignStopped, RunSpec
runs = [RunSpec(name, {inp!r}, {long!r}, seed=seed) for name, seed in (("long", 2), ("next", 3))]
try:
    Campaign({folder!r}, runs, lmp={lmp!r}, jobs=1, progress_interval=0.5).run()
except CampaignStopped as err:
    print("STOPPED", err.signal, err, flush=True)
    sys.exit(STOPPED_STATUS)
"""


def test_a_stopped_campaign_records_its_attempts_and_starts_nothing(tmp_path):
    """SIGTERM (a batch system's, or kill's) stops the running LAMMPS child and records its
    attempt whole (wall and CPU time, the last tap), starts no other run and exits with
    STOPPED_STATUS; the next session resumes it, and its kept log joins that attempt instead
    of making a second one, so DONE.json's cost is complete."""
    long = dict(TINY, N=128, taps=200, eta=1e-6, rsteps=20, pevery=50)
    folder = tmp_path / "c"
    script = STOPPABLE.format(python=str(SOURCE / "tools" / "python"), inp=str(CONSTANT_EPS),
                              long=long, folder=str(folder), lmp=str(LMP))
    runner = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True)
    long_taps = folder / "runs" / "long" / "taps.dat"
    deadline = time.time() + 40
    while time.time() < deadline:  # stop once the run is past a restart file
        if (folder / "runs" / "long" / "restart.40").exists() and long_taps.exists() \
                and steps(long_taps)[-1] >= 45:
            break
        time.sleep(0.05)
    runner.send_signal(signal.SIGTERM)
    out, _ = runner.communicate(timeout=60)
    assert runner.returncode == STOPPED_STATUS, out
    assert "[campaign] SIGTERM: stopping the running runs" in out
    stopped_at = steps(long_taps)[-1]
    assert 45 <= stopped_at < 200, "the run finished before the stop: make it longer"
    assert f"STOPPED SIGTERM stopped by SIGTERM: 1 running run stopped and recorded ('long' " \
        f"at tap {stopped_at}), 1 not started" in out
    assert not (folder / "runs" / "next").exists()    # queued, never started
    manifest = json.loads((folder / "manifest.json").read_text())
    long_rec, next_rec = manifest["runs"]
    assert long_rec["status"] == "stopped" and "running_attempt" not in long_rec
    assert next_rec["status"] == "pending" and next_rec["attempts"] == []
    (attempt,) = long_rec["attempts"]
    assert attempt["returncode"] == -signal.SIGTERM and attempt["end_step"] == stopped_at
    assert attempt["wall_s"] > 0 and attempt["cpu_s"] > 0
    assert attempt["error"].startswith("stopped with its campaign by SIGTERM")

    # the next session: the kept log joins the recorded attempt; the cost covers every attempt
    campaign = Campaign(folder, [RunSpec(n, CONSTANT_EPS, long, seed=s)
                                 for n, s in (("long", 2), ("next", 3))], lmp=LMP, jobs=1)
    campaign.run(progress=False)
    record = json.loads((folder / "manifest.json").read_text())["runs"][0]
    first, second = record["attempts"]
    assert first["log"] == "log.attempt1.lammps" and second["resumed_from_step"] >= 40
    done = provenance.read_done(campaign.result("long") / "DONE.json")
    assert done["attempts"] == 2
    assert done["wall_s"] == pytest.approx(first["wall_s"] + second["wall_s"], abs=0.01)
    assert done["cpu_s"] == pytest.approx(first["cpu_s"] + second["cpu_s"], abs=0.01)
    assert "attempts_without_cpu_time" not in done and "attempts_without_wall_time" not in done
    assert steps(campaign.result("long") / "taps.dat") == list(range(201))


def test_a_stop_that_reaches_the_child_first_is_no_failure(tmp_path):
    """A batch system's SIGTERM reaches every process of the job at once, and Ctrl-C the whole
    foreground group: a LAMMPS child may die of it before the campaign's handler runs. The run
    is then stopped with its campaign, not failed. A fake LAMMPS: the first run dies of SIGTERM
    at once and has its campaign signalled a second later (the next run starts in
    between, and the handler stops it)."""
    fake = tmp_path / "lmp_fake"
    first = tmp_path / "first_done"
    fake.write_text("#!/bin/sh\ncase \" $* \" in *\" -in \"*) ;; *) exit 0 ;; esac\n"
                    "echo 'LAMMPS (fake)' > log.lammps\n"
                    f"if [ -e {first} ]; then exec sleep 30; fi\ntouch {first}\n"
                    "campaign=$PPID\n(sleep 1; kill -TERM $campaign) &\nkill -TERM $$\n")
    fake.chmod(0o755)
    script = STOPPABLE.format(python=str(SOURCE / "tools" / "python"), inp=str(CONSTANT_EPS),
                              long=dict(TINY, taps=3), folder=str(tmp_path / "c"),
                              lmp=str(fake))
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         timeout=60)
    assert out.returncode == STOPPED_STATUS, out.stdout + out.stderr
    assert "STOPPED SIGTERM stopped by SIGTERM: 2 running runs stopped and recorded" \
        in out.stdout and "0 not started" in out.stdout
    assert "failed" not in out.stdout
    records = json.loads((tmp_path / "c" / "manifest.json").read_text())["runs"]
    assert [r["status"] for r in records] == ["stopped", "stopped"]


@pytest.mark.skipif(shutil.which("mpirun") is None, reason="no mpirun")
def test_a_stopped_partition_batch(tmp_path):
    """SIGTERM in partition mode reaches mpirun and its partitions: both runs of the batch are
    recorded as stopped in the campaign's words (the partition's log holds only echoed input
    with "ERROR" in it), the next batch never starts, and the resume finishes them; DONE.json
    has no CPU time to give (partition mode measures none per run) and says so."""
    long = dict(TINY, N=128, taps=3000, eta=1e-7, rsteps=20)
    folder = tmp_path / "p"
    script = STOPPABLE.replace("jobs=1", "jobs=2, mode='partition'").replace(
        '(("long", 2), ("next", 3))', '(("a", 1), ("b", 2), ("c", 3))').format(
        python=str(SOURCE / "tools" / "python"), inp=str(CONSTANT_EPS), long=long,
        folder=str(folder), lmp=str(LMP))
    runner = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True)
    deadline = time.time() + 60
    taps = [folder / "runs" / name / "taps.dat" for name in "ab"]
    while time.time() < deadline and not all(
            t.exists() and steps(t) and steps(t)[-1] >= 45 for t in taps):
        time.sleep(0.05)
    runner.send_signal(signal.SIGTERM)
    out, _ = runner.communicate(timeout=60)
    assert runner.returncode == STOPPED_STATUS, out
    assert "2 running runs stopped and recorded ('a' at tap " in out and "1 not started" in out
    records = json.loads((folder / "manifest.json").read_text())["runs"]
    assert [r["status"] for r in records] == ["stopped", "stopped", "pending"]
    for record in records[:2]:
        (attempt,) = record["attempts"]
        assert attempt["error"].startswith("stopped with its campaign by SIGTERM")
        assert 45 <= attempt["end_step"] < 3000, "the run finished before the stop"
    runs = [RunSpec(n, CONSTANT_EPS, long, seed=s) for n, s in (("a", 1), ("b", 2), ("c", 3))]
    campaign = Campaign(folder, runs, lmp=LMP, jobs=2, mode="partition").run(progress=False)
    done = provenance.read_done(campaign.result("a") / "DONE.json")
    assert done["attempts"] == 2 and done["wall_s"] > 0
    assert done["cpu_s"] is None and done["attempts_without_cpu_time"] == 2
    assert steps(campaign.result("a") / "taps.dat") == list(range(3001))
