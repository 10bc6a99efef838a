# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""tapmc.campaign: a process pool of tiny runs, resuming a killed campaign from restart files
(finished runs untouched, the resumed trajectory identical to an uninterrupted one), the
manifest, LAMMPS -partition mode under mpirun, and clear errors for bad runs."""

import contextlib
import io
import hashlib
import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from campaign_runs import CONSTANT_EPS, LMP, SOURCE, TINY, steps
from tapmc.campaign import (Campaign, CampaignDirectoryError, CampaignError,  # noqa: E402
                            MANIFEST_FORMAT, RunSpec, Words, launch, provenance)

pytestmark = pytest.mark.skipif(not LMP.is_file(), reason=f"no LAMMPS executable at {LMP}")


def test_pool_two_jobs_and_manifest(tmp_path):
    runs = [RunSpec(f"pbc_eps{eps}_s{s}", CONSTANT_EPS, dict(TINY, taps=12, eps=eps), seed=s)
            for eps in (0.01, 0.05) for s in (1, 2)]
    campaign = Campaign(tmp_path / "c", runs, lmp=LMP, jobs=2, progress_interval=0.2)
    assert campaign.run(progress=False) is campaign
    for spec in runs:
        folder = campaign.result(spec.name)
        assert folder == tmp_path / "c" / "runs" / spec.name
        assert steps(folder / "taps.dat") == list(range(13))
        assert (folder / "DONE.json").exists()
        log = (folder / "log.lammps").read_text()
        assert f"mc/settle {spec.seed} " in log  # each run got its own seed
    # different seeds, different trajectories; a run is reproducible from its seed
    a = (campaign.result("pbc_eps0.01_s1") / "taps.dat").read_text()
    b = (campaign.result("pbc_eps0.01_s2") / "taps.dat").read_text()
    assert a != b

    manifest = json.loads((tmp_path / "c" / "manifest.json").read_text())
    assert manifest["mode"] == "pool" and manifest["jobs"] == 2
    assert manifest["format"] == MANIFEST_FORMAT
    assert "2021" in manifest["lammps_version"]
    # the commit the executable was built from, as its -h says
    help_text = subprocess.run([str(LMP), "-h"], capture_output=True, text=True).stdout
    assert f"TAPMC build: {manifest['lmp_build']} " in help_text
    entry = manifest["inputs"]["in.constant_eps"]
    assert entry["sha256"] == hashlib.sha256(CONSTANT_EPS.read_bytes()).hexdigest()
    assert (tmp_path / "c" / entry["copy"]).read_bytes() == CONSTANT_EPS.read_bytes()
    assert [r["name"] for r in manifest["runs"]] == [r.name for r in runs]
    # no folder of this machine: the campaign's and the repository's paths are tagged
    text = (tmp_path / "c" / "manifest.json").read_text()
    assert str(tmp_path) not in text and str(SOURCE) not in text
    assert manifest["campaign"] == "<campaign>"
    assert manifest["runs"][0]["cwd"] == "<campaign>/runs/" + runs[0].name
    assert entry["source"] == "<repo>/examples/paper/in.constant_eps"
    for rec, spec in zip(manifest["runs"], runs):
        assert rec["status"] == "done" and rec["seed"] == spec.seed
        assert rec["variables"]["eps"] == spec.variables["eps"]
        cmd = rec["command"]
        lmp = str(LMP.resolve())  # under the repository when it is the build's lmp_tapmc
        assert cmd[0] in (lmp, "<repo>" + lmp[len(str(SOURCE.resolve())):])
        assert cmd[cmd.index("seed") - 1] == "-var" and cmd[cmd.index("seed") + 1] == str(spec.seed)
        assert rec["attempts"][-1]["returncode"] == 0 and rec["wall_s"] > 0

    # a second run() does nothing: every run is done
    mtimes = {r.name: (campaign.result(r.name) / "log.lammps").stat().st_mtime_ns for r in runs}
    Campaign(tmp_path / "c", runs, lmp=LMP, jobs=2).run(progress=False)
    assert mtimes == {r.name: (campaign.result(r.name) / "log.lammps").stat().st_mtime_ns
                      for r in runs}
    with pytest.raises(KeyError, match="nope"):
        campaign.result("nope")


RUNNER = """
import sys
sys.path.insert(0, {python!r})
from tapmc.campaign import Campaign, RunSpec
runs = [RunSpec("short", {inp!r}, {short!r}, seed=1), RunSpec("long", {inp!r}, {long!r}, seed=2)]
Campaign({folder!r}, runs, lmp={lmp!r}, jobs=1, progress_interval=0.5).run()
"""


def test_resume_after_kill(tmp_path, monkeypatch):
    short = dict(TINY, taps=5)
    long = dict(TINY, N=128, taps=200, eta=1e-6, rsteps=20, pevery=50)
    folder = tmp_path / "c"
    script = RUNNER.format(python=str(SOURCE / "tools" / "python"), inp=str(CONSTANT_EPS),
                           short=short, long=long, folder=str(folder), lmp=str(LMP))
    runner = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.DEVNULL,
                              stderr=subprocess.STDOUT)
    long_taps = folder / "runs" / "long" / "taps.dat"
    deadline = time.time() + 40
    while time.time() < deadline:  # kill once the long run is past a restart file
        if (folder / "runs" / "long" / "restart.40").exists() and long_taps.exists() \
                and steps(long_taps)[-1] >= 45:
            break
        time.sleep(0.05)
    runner.send_signal(signal.SIGKILL)
    runner.wait()
    killed_at = steps(long_taps)[-1]
    assert 45 <= killed_at < 200, "the long run finished before the kill: make it longer"
    assert not (folder / "runs" / "long" / "DONE.json").exists()
    time.sleep(1.0)
    assert steps(long_taps)[-1] == killed_at, "the LAMMPS child outlived its campaign"

    short_log = folder / "runs" / "short" / "log.lammps"
    before = short_log.stat().st_mtime_ns, (folder / "runs" / "short" / "DONE.json").read_text()
    killed = json.loads((folder / "manifest.json").read_text())
    first_version = killed["tapmc_version"]
    # the killed campaign left the start of its running attempt, with the versions that ran it
    running = killed["runs"][1]["running_attempt"]
    assert running["tapmc_version"] == first_version and running["resumed_from_step"] is None
    assert running["lammps_version"] == killed["lammps_version"] and running["started"]
    assert running["lmp_build"] == killed["lmp_build"] is not None
    runs = [RunSpec("short", CONSTANT_EPS, short, seed=1), RunSpec("long", CONSTANT_EPS, long, seed=2)]
    # ... and the campaign resumes under another TAPMC build: it says so and records both
    monkeypatch.setattr(provenance, "tapmc_version", lambda: "next-build")
    latest = max((p.name for p in (folder / "runs" / "long").glob("restart.*")),
                 key=lambda name: int(name.split(".")[1]))
    stream = io.StringIO()
    campaign = Campaign(folder, runs, lmp=LMP, jobs=1, stream=stream).run(progress=False)
    assert (f"[campaign] run 'long': resumes from {latest} under TAPMC "
            f"next-build; its last attempt ran TAPMC {first_version} (") in stream.getvalue()

    # the finished run was not redone
    assert (short_log.stat().st_mtime_ns,
            (folder / "runs" / "short" / "DONE.json").read_text()) == before
    # the killed run continued from its latest restart file, to the right final step
    run_dir = campaign.result("long")
    log = (run_dir / "log.lammps").read_text()
    assert "read_restart" in log and "Reading restart file" in log
    assert (run_dir / "log.attempt1.lammps").exists()
    assert steps(run_dir / "taps.dat") == list(range(201))
    record = json.loads((folder / "manifest.json").read_text())["runs"][1]
    attempts = record["attempts"]
    assert attempts[0]["interrupted"] and attempts[-1]["resumed_from_step"] >= 40
    assert attempts[0]["tapmc_version"] == first_version and attempts[0]["started"]
    # the killed attempt's wall time: its start to its log's last write (seconds, not hours)
    assert 0 < attempts[0]["wall_s"] < 60 and attempts[-1]["wall_s"] > 0
    assert record["wall_s"] == pytest.approx(sum(a["wall_s"] for a in attempts), abs=0.01)
    assert attempts[-1]["tapmc_version"] == "next-build" and "running_attempt" not in record
    done = provenance.read_done(run_dir / "DONE.json")
    assert done["tapmc_versions"] == [first_version, "next-build"]
    assert "attempts_without_version" not in done
    # ... and followed exactly the trajectory of an uninterrupted run (counter-based RNG)
    stream = io.StringIO()
    ref = Campaign(tmp_path / "ref", [RunSpec("long", CONSTANT_EPS, long, seed=2)], lmp=LMP,
                   jobs=1, stream=stream).run(progress=False).result("long")
    assert "resumes" not in stream.getvalue()
    assert (run_dir / "taps.dat").read_text() == (ref / "taps.dat").read_text()
    assert (run_dir / "profile_z.dat").read_text() == (ref / "profile_z.dat").read_text()
    assert not list(run_dir.glob("*.from*"))


@pytest.mark.skipif(shutil.which("mpirun") is None, reason="no mpirun")
def test_partition_mode_two_partitions(tmp_path):
    """Two runs as two partitions of one mpirun, in a campaign folder whose path has a space
    (the driver names the run folders relative to its own: a world variable takes one value
    per word); the same trajectories as in pool mode."""
    runs = [RunSpec(f"fbc_s{s}", CONSTANT_EPS, dict(TINY, taps=8 + s, bc="fbc"), seed=s)
            for s in (1, 2)]
    folder = tmp_path / "with space" / "p"
    campaign = Campaign(folder, runs, lmp=LMP, jobs=2, mode="partition")
    campaign.run(progress=False)
    for spec in runs:
        assert steps(campaign.result(spec.name) / "taps.dat") == list(range(spec.taps + 1))
    manifest = json.loads((folder / "manifest.json").read_text())
    cmd = manifest["runs"][0]["command"]
    assert "mpirun" in cmd[0] and cmd[cmd.index("-partition") + 1] == "2x1"
    driver = (folder / manifest["runs"][0]["driver"]).read_text()
    assert "variable seed world 1 2" in driver and "variable taps world 9 10" in driver
    assert "variable run_dir world ../runs/fbc_s1 ../runs/fbc_s2" in driver
    assert "include ../../inputs/in.constant_eps" in driver
    # the same runs in pool mode give the same trajectories
    pool = Campaign(tmp_path / "q", runs, lmp=LMP, jobs=2).run(progress=False)
    for spec in runs:
        assert (pool.result(spec.name) / "taps.dat").read_text() == \
            (campaign.result(spec.name) / "taps.dat").read_text()


def test_bad_input_names_run_and_log(tmp_path):
    bad_bc = RunSpec("bad_bc", CONSTANT_EPS, dict(TINY, taps=3, bc="xyz"), seed=1)
    broken = tmp_path / "in.broken"
    broken.write_text("units lj\natom_style sphere\nfix_this is not a command\n")
    bad_cmd = RunSpec("broken", broken, {}, seed=1)
    good = RunSpec("good", CONSTANT_EPS, dict(TINY, taps=3), seed=1)
    campaign = Campaign(tmp_path / "c", [bad_bc, bad_cmd, good], lmp=LMP, jobs=2)
    with pytest.raises(CampaignError) as err:
        campaign.run(progress=False)
    text = str(err.value)
    assert "2 of 3 runs failed" in text
    assert "run 'bad_bc' failed: ERROR: bc = xyz; allowed values: pbc, fbc" in text
    assert str(tmp_path / "c" / "runs" / "bad_bc" / "log.lammps") in text
    assert "run 'broken' failed" in text and "fix_this" in text
    assert campaign.result("good").is_dir()
    with pytest.raises(RuntimeError, match="has not finished"):
        campaign.result("bad_bc")


def test_run_stopped_by_a_signal_says_so(tmp_path):
    """A LAMMPS stopped from outside (SIGTERM) is named as such, not by a line of its echoed
    input that happens to mention ERROR (in.ramp's check of bc)."""
    fake = tmp_path / "lmp_stopped"
    # the campaign also asks the executable for its version: only the run writes a log
    fake.write_text("#!/bin/sh\ncase \" $* \" in *\" -in \"*) ;; *) exit 0 ;; esac\n"
                    "cat > log.lammps <<'EOF'\n"
                    "if \"${bc} != pbc\" then \"print 'ERROR: bc'\" \"quit 2\"\nEOF\n"
                    "kill -TERM $$\n")
    fake.chmod(0o755)
    spec = RunSpec("stopped", CONSTANT_EPS, dict(TINY, taps=3), seed=1)
    campaign = Campaign(tmp_path / "c", [spec], lmp=str(fake), jobs=1)
    with pytest.raises(CampaignError) as err:
        campaign.run(progress=False)
    assert "run 'stopped' failed: LAMMPS was stopped by signal SIGTERM" in str(err.value)
    assert "ERROR: bc" in (tmp_path / "c" / "runs" / "stopped" / "log.lammps").read_text()


def test_the_error_line_of_a_log(tmp_path):
    """log_error quotes LAMMPS's own ERROR line, or one behind a prefix, and never an echoed
    input line that would print one."""
    from tapmc.campaign.run_folder import log_error
    log = tmp_path / "log.lammps"
    echoed = "if \"${bc} != pbc\" then \"print 'ERROR: bc = ${bc}'\" \"quit 2\"\n"
    log.write_text(echoed + '  "print \\"ERROR: sqrteps\\"" "quit 2"\n')
    assert log_error(log) == ""
    log.write_text(echoed + "ERROR: bc = x; allowed values: pbc, fbc\n")
    assert log_error(log) == "ERROR: bc = x; allowed values: pbc, fbc"
    log.write_text(echoed + "[host:01] ERROR on proc 0: Lost atoms (src/thermo.cpp:481)\n")
    assert log_error(log) == "[host:01] ERROR on proc 0: Lost atoms (src/thermo.cpp:481)"
    assert log_error(tmp_path / "missing.lammps") == ""


def test_runspec_and_campaign_validation(tmp_path):
    with pytest.raises(ValueError, match="name = 'a b'"):
        RunSpec("a b", CONSTANT_EPS)
    with pytest.raises(ValueError, match="input = .*no such file"):
        RunSpec("a", tmp_path / "missing")
    with pytest.raises(ValueError, match="seed = 0"):
        RunSpec("a", CONSTANT_EPS, seed=0)
    with pytest.raises(ValueError, match=r"variables\['seed'\]"):
        RunSpec("a", CONSTANT_EPS, {"seed": 3})
    with pytest.raises(ValueError, match="nprocs = 0"):
        RunSpec("a", CONSTANT_EPS, nprocs=0)
    with pytest.raises(ValueError, match="strings without spaces"):
        RunSpec("a", CONSTANT_EPS, {"bc": "p p"})
    assert RunSpec("r", SOURCE / "examples/paper/in.ramp", {"P": 10, "nlev": 3}).taps == 70
    spec = RunSpec("a", CONSTANT_EPS, {"taps": 4})
    with pytest.raises(ValueError, match="appears twice"):
        Campaign(tmp_path, [spec, spec], lmp=LMP)
    with pytest.raises(ValueError, match="mode = 'mpi'"):
        Campaign(tmp_path, [spec], lmp=LMP, mode="mpi")
    with pytest.raises(ValueError, match="jobs = 0"):
        Campaign(tmp_path, [spec], lmp=LMP, jobs=0)
    with pytest.raises(FileNotFoundError, match="lmp = "):
        Campaign(tmp_path, [spec], lmp=tmp_path / "no_lmp")


def test_changed_input_stops_or_is_pinned(tmp_path):
    """An input edited after the campaign started: the default stops with a message naming
    it; pin_inputs=True keeps executing the campaign's copy, and the manifest records both
    digests."""
    source = tmp_path / "in.constant_eps"
    source.write_bytes(CONSTANT_EPS.read_bytes())
    runs = [RunSpec("a", source, dict(TINY, taps=3, eps=0.01), seed=1)]
    Campaign(tmp_path / "c", runs, lmp=LMP, jobs=1).run(progress=False)
    original = source.read_bytes()
    source.write_bytes(original + b"# edited after the campaign started\n")
    more = runs + [RunSpec("b", source, dict(TINY, taps=3, eps=0.02), seed=1)]
    with pytest.raises(CampaignDirectoryError, match="in.constant_eps: differs from the copy"):
        Campaign(tmp_path / "c", more, lmp=LMP, jobs=1).run(progress=False)
    stream = io.StringIO()
    Campaign(tmp_path / "c", more, lmp=LMP, jobs=1, stream=stream,
             pin_inputs=True).run(progress=True)
    assert "keep executing the campaign's copy" in stream.getvalue()
    assert (tmp_path / "c" / "inputs" / "in.constant_eps").read_bytes() == original
    entry = json.loads((tmp_path / "c" / "manifest.json").read_text())["inputs"]["in.constant_eps"]
    assert entry["sha256"] == hashlib.sha256(original).hexdigest()
    assert entry["source_sha256"] == hashlib.sha256(source.read_bytes()).hexdigest()
    assert steps(tmp_path / "c" / "runs" / "b" / "taps.dat") == [0, 1, 2, 3]


def test_campaign_folder_checks(tmp_path):
    """A manifest without "format" (written before TAPMC recorded it) is format 1 and is kept
    (its created date too); a finished run asked again with other parameters, a damaged
    DONE.json and a regular file as the folder are refused with CampaignDirectoryError."""
    folder = tmp_path / "c"
    folder.mkdir()
    (folder / "manifest.json").write_text(json.dumps({"created": "2026-01-01T00:00:00Z",
                                                      "runs": []}))
    spec = RunSpec("a", CONSTANT_EPS, dict(TINY, taps=2), seed=1)
    Campaign(folder, [spec], lmp=LMP).run(progress=False)
    manifest = json.loads((folder / "manifest.json").read_text())
    assert manifest["format"] == MANIFEST_FORMAT
    assert manifest["created"] == "2026-01-01T00:00:00Z"
    other = RunSpec("a", CONSTANT_EPS, dict(TINY, taps=3), seed=1)
    with pytest.raises(CampaignDirectoryError, match="run 'a': finished in .* with other "
                                                     "parameters"):
        Campaign(folder, [other], lmp=LMP).run(progress=False)
    (folder / "runs" / "a" / "DONE.json").write_text("{")
    with pytest.raises(CampaignDirectoryError, match="DONE.json: cannot be read as the record"):
        Campaign(folder, [spec], lmp=LMP).run(progress=False)
    with pytest.raises(CampaignDirectoryError, match="manifest.json: exists and is not a dir"):
        Campaign(folder / "manifest.json", [spec], lmp=LMP)


def _flip_byte(path, offset):
    data = bytearray(Path(path).read_bytes())
    data[offset] ^= 0x01
    Path(path).write_bytes(bytes(data))


def test_damaged_output_is_rerun(tmp_path):
    """DONE.json records the sha256 and size of every output; a later run() finds a damaged
    one, sets DONE.json and the damaged file aside, names them, and redoes exactly that run:
    from the start for a damaged per-tap file, from the latest restart for a damaged final
    dump. The redone runs give back the files recorded when they first finished. A missing
    final restart file is no damage."""
    ends = dict(TINY, taps=5, rsteps=2, pevery=1, dump_ends="yes")
    runs = [RunSpec(name, CONSTANT_EPS, ends, seed=s)
            for s, name in enumerate(("taps_damaged", "dump_damaged", "intact"), start=1)]
    folder = tmp_path / "c"
    campaign = Campaign(folder, runs, lmp=LMP, jobs=2).run(progress=False)
    done = {r.name: json.loads((campaign.result(r.name) / "DONE.json").read_text())
            for r in runs}
    outputs = done["intact"]["outputs"]
    assert sorted(outputs) == ["dump.0.lammpstrj", "dump.5.lammpstrj", "profile_x.dat",
                               "profile_z.dat", "restart.4", "taps.dat"]
    for name, digest in outputs.items():
        path = campaign.result("intact") / name
        assert digest == {"sha256": hashlib.sha256(path.read_bytes()).hexdigest(),
                          "size": path.stat().st_size}
    original = {name: (campaign.result(name) / file).read_bytes() for name, file in
                (("taps_damaged", "taps.dat"), ("dump_damaged", "dump.5.lammpstrj"))}
    intact_log = (campaign.result("intact") / "log.lammps").stat().st_mtime_ns

    # a final restart left out (as a committed campaign does) is no damage
    (campaign.result("intact") / "restart.4").unlink()
    _flip_byte(campaign.result("taps_damaged") / "taps.dat", -10)
    dump = campaign.result("dump_damaged") / "dump.5.lammpstrj"
    dump.write_bytes(dump.read_bytes()[:-100])
    stream = io.StringIO()
    Campaign(folder, runs, lmp=LMP, jobs=2, stream=stream).run(progress=True)
    text = stream.getvalue()
    assert (f"run 'taps_damaged': {folder / 'runs' / 'taps_damaged' / 'taps.dat'}: sha256 "
            "differs from the one recorded when the run finished; the run goes again from "
            "the start") in text
    assert (f"run 'dump_damaged': {dump}: {len(original['dump_damaged']) - 100} bytes, "
            f"{len(original['dump_damaged'])} when the run finished; the run goes again "
            "from its restart at step 4") in text
    assert "1 of 3 runs already done, 2 to run" in text

    assert (campaign.result("intact") / "log.lammps").stat().st_mtime_ns == intact_log
    for name, file in (("taps_damaged", "taps.dat"), ("dump_damaged", "dump.5.lammpstrj")):
        run_dir = campaign.result(name)
        assert (run_dir / file).read_bytes() == original[name]
        assert json.loads((run_dir / "DONE.json").read_text())["outputs"][file] == \
            done[name]["outputs"][file]
        aside = run_dir / "damaged1"
        assert json.loads((aside / "DONE.json").read_text()) == done[name]
        assert (aside / file).read_bytes() != original[name]
    resumed = (campaign.result("dump_damaged") / "log.lammps").read_text()
    redone = (campaign.result("taps_damaged") / "log.lammps").read_text()
    assert "Reading restart file" in resumed and "Reading restart file" not in redone
    manifest = {r["name"]: r for r in json.loads((folder / "manifest.json").read_text())["runs"]}
    assert manifest["taps_damaged"]["damaged"][0]["files"] == {
        "taps.dat": "sha256 differs from the one recorded when the run finished"}
    assert manifest["taps_damaged"]["damaged"][0]["rerun_from_step"] == 0
    assert manifest["dump_damaged"]["damaged"][0]["rerun_from_step"] == 4
    assert manifest["dump_damaged"]["damaged"][0]["set_aside"] == "damaged1"
    assert "damaged" not in manifest["intact"]
    assert all(r["status"] == "done" for r in manifest.values())


def test_damaged_run_that_cannot_be_rerun_is_named(tmp_path, monkeypatch):
    import tapmc.campaign.run_folder as run_folder

    spec = RunSpec("a", CONSTANT_EPS, dict(TINY, taps=2), seed=1)
    folder = tmp_path / "c"
    Campaign(folder, [spec], lmp=LMP).run(progress=False)
    (folder / "runs" / "a" / "profile_z.dat").unlink()

    def refuse(run_dir, names):
        raise PermissionError(13, "Permission denied", str(run_dir))

    monkeypatch.setattr(run_folder, "set_aside", refuse)
    with pytest.raises(CampaignError, match=r"run 'a': damaged since it finished: "
                                            r"profile_z.dat \(missing\) in .*runs/a; it cannot "
                                            r"be re-run: Permission denied"):
        Campaign(folder, [spec], lmp=LMP).run(progress=False)
    assert (folder / "runs" / "a" / "DONE.json").exists()


def test_folder_written_before_outputs_were_recorded(tmp_path):
    """A campaign folder written by TAPMC before DONE.json recorded the outputs
    (tests/python/data/campaign_before_checksums, see its README) keeps resuming: its finished
    run is trusted as it is, even with a changed file, and new runs record their outputs."""
    folder = tmp_path / "c"
    shutil.copytree(Path(__file__).parent / "data" / "campaign_before_checksums", folder)
    run_dir = folder / "runs" / "pbc_s1"
    done_before = (run_dir / "DONE.json").read_text()
    assert "outputs" not in json.loads(done_before)
    (run_dir / "taps.dat").write_text((run_dir / "taps.dat").read_text() + "# a note\n")
    log_before = (run_dir / "log.lammps").stat().st_mtime_ns
    inp = folder / "inputs" / "in.constant_eps"  # the input the folder's run executed
    old = RunSpec("pbc_s1", inp, dict(N=64, L=8, eta=1e-5, rsteps=2, thermo_every=1, taps=3,
                                      pevery=1), seed=1)
    new = RunSpec("pbc_s2", inp, dict(TINY, taps=2), seed=2)
    campaign = Campaign(folder, [old, new], lmp=LMP, jobs=1).run(progress=False)
    assert (run_dir / "DONE.json").read_text() == done_before
    assert (run_dir / "log.lammps").stat().st_mtime_ns == log_before
    assert "taps.dat" in json.loads((campaign.result("pbc_s2") / "DONE.json").read_text())[
        "outputs"]
    manifest = json.loads((folder / "manifest.json").read_text())
    assert manifest["format"] == MANIFEST_FORMAT
    assert [r["status"] for r in manifest["runs"]] == ["done", "done"]


AFFINITY = """
import sys
sys.path.insert(0, {python!r})
from tapmc.campaign import Campaign, RunSpec, available_cores
spec = RunSpec("a", {inp!r}, {{"taps": 1}})
print(available_cores(), Campaign({folder!r}, [spec], lmp={lmp!r}).jobs)
"""


def test_default_jobs_follow_cpu_affinity(tmp_path):
    """The default jobs count the cores this process may use, not the machine's."""
    from tapmc.campaign import available_cores
    if hasattr(os, "sched_getaffinity"):
        assert available_cores() == len(os.sched_getaffinity(0))
    spec = RunSpec("a", CONSTANT_EPS, {"taps": 1})
    assert Campaign(tmp_path / "c", [spec], lmp=LMP).jobs == available_cores()
    if shutil.which("taskset") is None:
        pytest.skip("no taskset")
    script = AFFINITY.format(python=str(SOURCE / "tools" / "python"), inp=str(CONSTANT_EPS),
                             folder=str(tmp_path / "c"), lmp=str(LMP))
    out = subprocess.run(["taskset", "-c", "0", sys.executable, "-c", script],
                         capture_output=True, text=True, check=True).stdout
    assert out.split() == ["1", "1"]


def test_merge_ave_time_parts_reads_with_the_readers_parser(tmp_path):
    """Segments of a resumed run's profile are merged keeping every byte of the blocks they
    keep; the earlier segment, written by a killed run, may end in a block cut short; a
    malformed last segment raises the readers' TapmcFormatError naming it."""
    from tapmc.campaign import merge_ave_time_parts
    from tapmc.readers import TapmcFormatError

    header = "# Time-averaged data\n# TimeStep Number-of-rows\n# Row c_p[1]\n"
    block = "{} 2\n1 {}.5\n2 {}.25\n"
    (tmp_path / "prof.dat").write_text(header + block.format(0, 0, 0) + block.format(5, 9, 9)
                                       + "10 2\n1 3.5\n")
    (tmp_path / "prof.dat.from5").write_text(header + block.format(5, 5, 5)
                                             + block.format(10, 10, 10))
    assert merge_ave_time_parts(tmp_path) == ["prof.dat"]
    assert (tmp_path / "prof.dat").read_text() == (header + block.format(0, 0, 0)
                                                   + block.format(5, 5, 5)
                                                   + block.format(10, 10, 10))
    assert not (tmp_path / "prof.dat.from5").exists()
    (tmp_path / "prof.dat.from10").write_text(header + "10 2\n1 3.5\n")
    with pytest.raises(TapmcFormatError, match=r"prof.dat.from10:4: truncated block"):
        merge_ave_time_parts(tmp_path)


def test_merge_skips_the_empty_segment_of_a_run_killed_before_its_first_output(tmp_path):
    """A resumed run killed before it wrote a profile leaves an empty X.from<step>: the merge
    keeps the earlier blocks up to the next segment and removes it (a paper-scale run with
    profiles at t = 0 and 4000 only was killed twice and met this); an empty last segment, the
    output of the run that finished, is still an error."""
    from tapmc.campaign import merge_ave_time_parts
    from tapmc.readers import TapmcFormatError

    header = "# Time-averaged data\n# TimeStep Number-of-rows\n# Row c_p[1]\n"
    block = "{} 1\n1 {}.5\n"
    (tmp_path / "prof.dat").write_text(header + block.format(0, 0) + block.format(20, 1))
    (tmp_path / "prof.dat.from19").write_text("")
    (tmp_path / "prof.dat.from29").write_text(header + block.format(40, 4))
    assert merge_ave_time_parts(tmp_path) == ["prof.dat"]
    assert (tmp_path / "prof.dat").read_text() == (header + block.format(0, 0) + block.format(20, 1)
                                                   + block.format(40, 4))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["prof.dat"]
    (tmp_path / "prof.dat.from40").write_text("")
    with pytest.raises(TapmcFormatError, match="empty file"):
        merge_ave_time_parts(tmp_path)


def test_joined_ave_time_reads_a_running_run_as_the_merge_would_write_it(tmp_path):
    """A run still running (or killed): its segments joined as the merge joins them, nothing
    written; the live segment's last block cut short and an empty live segment are left out."""
    from tapmc.campaign import joined_ave_time, merge_ave_time_parts

    header = "# Time-averaged data\n# TimeStep Number-of-rows\n# Row c_p[1]\n"
    block = "{} 1\n1 {}.5\n"
    assert joined_ave_time(tmp_path, "prof.dat") == ([], [])
    (tmp_path / "prof.dat").write_text(header + block.format(0, 0) + block.format(20, 9))
    (tmp_path / "prof.dat.from19").write_text(header + block.format(20, 2) + "40 1\n")
    head, blocks = joined_ave_time(tmp_path, "prof.dat")
    assert "".join(head) == header
    assert [(s, "".join(b)) for s, b in blocks] == [(0, block.format(0, 0)),
                                                    (20, block.format(20, 2))]
    (tmp_path / "prof.dat.from39").write_text("")
    assert [s for s, _ in joined_ave_time(tmp_path, "prof.dat")[1]] == [0, 20]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["prof.dat", "prof.dat.from19",
                                                          "prof.dat.from39"]
    (tmp_path / "prof.dat.from39").write_text(header + block.format(40, 4))
    expected = joined_ave_time(tmp_path, "prof.dat")
    merge_ave_time_parts(tmp_path)
    assert (tmp_path / "prof.dat").read_text() == "".join(expected[0]) + "".join(
        "".join(b) for _, b in expected[1])


def test_finished_ramp_keeps_its_level_end_restarts(tmp_path):
    """A finished run keeps only its latest restart file; a ramp (variables P and nlev of
    in.ramp) also keeps those at its level ends, from which a level can be continued."""
    from tapmc.campaign import run_folder

    ramp = RunSpec("ramp", SOURCE / "examples" / "paper" / "in.ramp",
                   dict(P=200, nlev=3, sqrt0=0.05, dsqrt=0.05), seed=1)
    assert ramp.level_taps == 200 and ramp.taps == 200 * 7
    assert RunSpec("c", CONSTANT_EPS, dict(TINY, taps=12)).level_taps is None
    for step in range(100, 1401, 100):
        (tmp_path / f"restart.{step}").write_bytes(b"x")
    run_folder.keep_latest_restart(tmp_path, keep_every=ramp.level_taps)
    kept = sorted(int(p.name.split(".")[1]) for p in tmp_path.glob("restart.*"))
    assert kept == [200, 400, 600, 800, 1000, 1200, 1400]
    run_folder.keep_latest_restart(tmp_path)
    assert [p.name for p in tmp_path.glob("restart.*")] == ["restart.1400"]


def test_words_pass_several_words_as_one_value(tmp_path):
    """Words (e.g. fix mc/settle keywords) is one -var value with spaces; a plain string with
    spaces is still refused, and the partition driver quotes Words as one world value."""
    keys = Words("dmax 0.05 stop drift")
    spec = RunSpec("a", CONSTANT_EPS, {"settle_keys": keys, "taps": 2})
    args = spec.var_args()
    assert args[args.index("settle_keys") + 1] == "dmax 0.05 stop drift"
    assert json.loads(json.dumps(spec.describe()))["variables"]["settle_keys"] == keys
    for bad in ("", " stop drift", 'stop "drift"', "stop\ndrift"):
        with pytest.raises(ValueError, match="Words"):
            Words(bad)
    with pytest.raises(ValueError, match="strings without spaces"):
        RunSpec("a", CONSTANT_EPS, {"settle_keys": "stop drift"})
    other = RunSpec("b", CONSTANT_EPS, {"settle_keys": Words("check 0"), "taps": 2})
    resume = {"resume": "no", "resume_file": "restart.*"}
    driver = launch.partition_driver([spec, other], {"a": tmp_path / "a", "b": tmp_path / "b"},
                                     {"a": resume, "b": resume}, CONSTANT_EPS)
    assert 'variable settle_keys world "dmax 0.05 stop drift" "check 0"' in driver
    # the input copy relative to the run folders, quoted when its name has a space
    named = tmp_path / "inputs" / "in constant eps"
    driver = launch.partition_driver([spec, other], {"a": tmp_path / "runs" / "a",
                                                     "b": tmp_path / "runs" / "b"},
                                     {"a": resume, "b": resume}, named, cwd=tmp_path / "part")
    assert 'include "../../inputs/in constant eps"' in driver


def test_an_attempt_records_its_cpu_time_and_last_step(tmp_path):
    spec = RunSpec("tiny", CONSTANT_EPS, dict(TINY, taps=3), seed=4928)
    Campaign(tmp_path / "c", [spec], lmp=LMP, jobs=1).run(progress=False)
    (record,) = json.loads((tmp_path / "c" / "manifest.json").read_text())["runs"]
    (attempt,) = record["attempts"]
    assert attempt["end_step"] == 3 and attempt["resumed_from_step"] is None
    assert 0 < attempt["cpu_s"] <= attempt["wall_s"] + 1  # one serial process: about its wall


def test_each_run_has_mpi_session_directories_of_its_own(tmp_path, monkeypatch):
    """A child gets a fresh OMPI_MCA_orte_tmpdir_base under the user's (made if missing),
    removed after it ends."""
    monkeypatch.setenv("OMPI_MCA_orte_tmpdir_base", str(tmp_path / "not" / "yet"))
    seen = []
    for k in range(2):
        screen = tmp_path / f"env{k}.txt"
        assert launch.run_child(["env"], tmp_path, screen) == 0
        line = [x for x in screen.read_text().splitlines()
                if x.startswith("OMPI_MCA_orte_tmpdir_base=")]
        assert len(line) == 1
        seen.append(Path(line[0].split("=", 1)[1]))
    assert seen[0] != seen[1]
    assert all(p.parent == tmp_path / "not" / "yet" and p.name.startswith("tapmc-mpi-")
               for p in seen)
    assert not any(p.exists() for p in seen)  # removed with its run
    # a base that cannot be made (below a file): the child gets the environment unchanged,
    # and Open MPI reports the base itself
    blocked = tmp_path / "file"
    blocked.write_text("")
    monkeypatch.setenv("OMPI_MCA_orte_tmpdir_base", str(blocked / "base"))
    with launch.private_mpi_session() as env:
        assert env["OMPI_MCA_orte_tmpdir_base"] == str(blocked / "base")


def test_runs_start_while_singletons_end_beside_them(tmp_path, monkeypatch):
    """Open MPI 4 singletons started with ess_singleton_isolated=1 share one session directory,
    removed by whichever ends: a loop doing what an ending singleton does to the user's session
    base killed about 1 start in 8 in MPI_Init (session_dir.c); a campaign's runs do not share
    it, so all of them start."""
    import socket
    import threading

    base = tmp_path / "base"
    base.mkdir()
    monkeypatch.setenv("OMPI_MCA_orte_tmpdir_base", str(base))
    monkeypatch.setenv("OMPI_MCA_ess_singleton_isolated", "1")
    top = base / f"ompi.{socket.gethostname().split('.')[0]}.{os.getuid()}"
    chain = [top, top / "jf.0", top / "jf.0" / "1", top / "jf.0" / "1" / "0"]
    stop = threading.Event()

    def end_singletons():
        while not stop.is_set():
            for d in chain:
                with contextlib.suppress(OSError):
                    d.mkdir()
            for d in reversed(chain):
                with contextlib.suppress(OSError):
                    d.rmdir()

    (tmp_path / "in.one").write_text("units lj\n")
    command = [str(LMP), "-log", "none", "-in", str(tmp_path / "in.one")]
    churn = threading.Thread(target=end_singletons, daemon=True)
    churn.start()
    try:
        codes = [launch.run_child(command, tmp_path, tmp_path / f"screen{k}.txt")
                 for k in range(30)]
    finally:
        stop.set()
        churn.join()
    failed = [(k, (tmp_path / f"screen{k}.txt").read_text()[-300:])
              for k, c in enumerate(codes) if c != 0]
    assert not failed


def test_the_versions_that_ran_a_run():
    """Each attempt names the TAPMC that ran it, in order, once each; attempts recorded before
    attempts carried a version are counted, not guessed."""
    record = {"attempts": [{"interrupted": True, "log": "log.attempt1.lammps"},
                           {"started": "t", "tapmc_version": "b"},
                           {"interrupted": True, "tapmc_version": "b", "log": "x"},
                           {"started": "u", "tapmc_version": "c"}]}
    assert provenance.attempt_versions(record) == (["b", "c"], 1)
    assert provenance.attempt_versions({"attempts": []}) == ([], 0)


def test_an_executable_no_commit_of_this_tapmc_describes():
    """A campaign says so when its executable was built from another commit than this TAPMC,
    or from a tree with uncommitted changes; a dirty TAPMC tree (Python edits) over a build of
    its commit, and versions unknown, say nothing."""
    other = provenance.build_mismatch("/x/lmp_tapmc", "51b121b-dirty", "42e987c")
    assert other.startswith("the executable /x/lmp_tapmc was built from 51b121b-dirty, and "
                            "this TAPMC is 42e987c: its attempts record 51b121b-dirty as")
    dirty = provenance.build_mismatch("lmp", "42e987c-dirty", "42e987c-dirty")
    assert "a tree with uncommitted changes" in dirty and "point TAPMC_LMP or --lmp" in dirty
    for build, tapmc in [("42e987c", "42e987c"), ("42e987c", "42e987c-dirty"),
                         (None, "42e987c"), ("42e987c", None)]:
        assert provenance.build_mismatch("lmp", build, tapmc) is None


FAKE_LMP = """#!/bin/sh
case " $* " in *" -in "*) ;; *) echo "TAPMC build: ${FAKE_BUILD:-}"; exit 0 ;; esac
printf '# step level\\n0 0\\n1 0\\n2 0\\n' > taps.dat
m='LammpS RestartT\\000'  # a restart file's marks: whole, format revision 2
printf "$m\\001\\000\\000\\000\\002\\000\\000\\000$m" > restart.2
if [ -e finish ]; then printf '3 0\\n' >> taps.dat; echo 'Total wall time: 0:00:01' > log.lammps
else echo 'LAMMPS (fake)' > log.lammps; kill -TERM $$; fi
"""


def test_a_run_resumed_after_attempts_without_versions(tmp_path, monkeypatch):
    """A manifest from before attempts recorded their version: the resume names the campaign's
    last session's TAPMC, and DONE.json counts the attempts whose version is not known instead
    of guessing it."""
    fake = tmp_path / "lmp_fake"
    fake.write_text(FAKE_LMP)
    fake.chmod(0o755)
    spec = RunSpec("old", CONSTANT_EPS, dict(TINY, taps=3), seed=1)
    folder = tmp_path / "c"
    monkeypatch.setattr(provenance, "tapmc_version", lambda: "old-build")
    with pytest.raises(CampaignError, match="stopped by signal SIGTERM"):
        Campaign(folder, [spec], lmp=str(fake), jobs=1).run(progress=False)
    manifest = json.loads((folder / "manifest.json").read_text())
    (attempt,) = manifest["runs"][0]["attempts"]
    assert attempt["tapmc_version"] == "old-build"
    for attempt in manifest["runs"][0]["attempts"]:   # as an older TAPMC wrote it
        del attempt["tapmc_version"], attempt["lammps_version"], attempt["lmp_build"]
    (folder / "manifest.json").write_text(json.dumps(manifest))
    (folder / "runs" / "old" / "finish").touch()
    monkeypatch.setattr(provenance, "tapmc_version", lambda: "next-build")
    stream = io.StringIO()
    Campaign(folder, [spec], lmp=str(fake), jobs=1, stream=stream).run(progress=False)
    assert ("[campaign] run 'old': resumes from restart.2 under TAPMC next-build; the "
            "campaign's last session ran (its attempts did not record their version) TAPMC "
            "old-build") in stream.getvalue()
    done = provenance.read_done(folder / "runs" / "old" / "DONE.json")
    # the failed attempt (its kept log joined to it, not counted twice) and the finishing one
    assert done["attempts"] == 2
    assert done["tapmc_versions"] == ["next-build"] and done["attempts_without_version"] == 1


def test_a_run_resumed_by_another_build_of_the_executable(tmp_path, monkeypatch):
    """The same TAPMC tree, another build of the executable (lmp -h's 'TAPMC build:'): the
    resume says so, and each attempt records its build."""
    fake = tmp_path / "lmp_fake"
    fake.write_text(FAKE_LMP)
    fake.chmod(0o755)
    spec = RunSpec("rebuilt", CONSTANT_EPS, dict(TINY, taps=3), seed=1)
    folder = tmp_path / "c"
    monkeypatch.setenv("FAKE_BUILD", "b1")
    monkeypatch.setattr(provenance, "tapmc_version", lambda: "t1")
    with pytest.raises(CampaignError):
        Campaign(folder, [spec], lmp=str(fake), jobs=1).run(progress=False)
    (folder / "runs" / "rebuilt" / "finish").touch()
    monkeypatch.setenv("FAKE_BUILD", "b2")
    stream = io.StringIO()
    Campaign(folder, [spec], lmp=str(fake), jobs=1, stream=stream).run(progress=False)
    assert (f"[campaign] warning: the executable {fake} was built from b2, and this TAPMC is "
            "t1: ") in stream.getvalue()
    assert ("resumes from restart.2 under TAPMC " in stream.getvalue()
            and "; its executable is built from b2, its last attempt's from b1 (" in
            stream.getvalue() and "ran TAPMC" not in stream.getvalue())
    record = json.loads((folder / "manifest.json").read_text())["runs"][0]
    # one entry per attempt: the failed one (with its kept log) and the finishing one
    assert [a.get("lmp_build") for a in record["attempts"]] == ["b1", "b2"]
    assert record["attempts"][0]["log"] == "log.attempt1.lammps"


def test_a_ramps_eta_weighs_its_taps_by_their_cost(tmp_path):
    """A run whose taps differ in cost (a ramp's weak levels first): its ETA scales the time
    so far by the cost left over the cost done, where its rate so far would promise the end
    too soon; the overall ETA takes the same per-tap cost; tap_costs that do not fit the runs
    are refused."""
    from tapmc.campaign.progress import weighted_seconds_left
    sums = [0.0, 1.0, 2.0, 4.0, 6.0]                     # taps costing 1, 1, 2, 2
    assert weighted_seconds_left(sums, 0, 2, 10.0) == pytest.approx(20.0)
    assert weighted_seconds_left(sums, 1, 3, 30.0) == pytest.approx(20.0)  # 30 s x 2 / 3
    assert weighted_seconds_left(sums, 2, 2, 5.0) is None  # no tap done yet this session
    fake = tmp_path / "lmp_fake"
    fake.write_text(FAKE_LMP)
    fake.chmod(0o755)
    spec = RunSpec("ramp", CONSTANT_EPS, dict(TINY, taps=4), seed=1)
    with pytest.raises(ValueError, match=r"tap_costs\['ramp'\]: 3 costs, the run has 4 taps"):
        Campaign(tmp_path / "a", [spec], lmp=str(fake), tap_costs={"ramp": [1, 1, 2]})
    with pytest.raises(ValueError, match="every cost must be finite and > 0"):
        Campaign(tmp_path / "a", [spec], lmp=str(fake), tap_costs={"ramp": [1, 0, 2, 2]})
    with pytest.raises(ValueError, match="'other' is not a run of the campaign"):
        Campaign(tmp_path / "a", [spec], lmp=str(fake), tap_costs={"other": [1] * 4})
    # the progress report of a run 2 taps in, 10 s after its start this session
    stream = io.StringIO()
    campaign = Campaign(tmp_path / "b", [spec], lmp=str(fake), jobs=1, stream=stream,
                        tap_costs={"ramp": [1, 1, 2, 2]})
    run = campaign.run_dir("ramp")
    run.mkdir(parents=True)
    (run / "taps.dat").write_text("# step\n0\n1\n2\n")
    now = time.time()
    campaign._t0, campaign._done0 = {"ramp": now - 10.0}, {"ramp": 0}
    campaign._report(now - 10.0)
    lines = stream.getvalue().splitlines()
    assert lines[0].startswith("[campaign]   ramp: 2/4 taps (50%), ETA 20s")   # not 10 s
    assert lines[1].endswith("ETA 20s")
