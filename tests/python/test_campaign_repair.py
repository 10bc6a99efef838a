# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""tapmc.campaign against what a kill, a full disk or a second process leave in a campaign
folder: files rewritten whole or not at all, a per-tap file checked step by step before a run
is sealed, restart files cut while LAMMPS wrote them, leftover temporary files, input copies,
LAMMPS children that outlive their runner; each time the resumed run gives the same bytes as
an uninterrupted one, or the campaign refuses with one line naming the file."""

import io
import json
import os
import signal
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

from campaign_runs import CONSTANT_EPS, LMP, TINY, steps
from tapmc.campaign import (Campaign, CampaignDirectoryError, CampaignError,  # noqa: E402
                            RunSpec, launch, provenance, run_folder)

pytestmark = pytest.mark.skipif(not LMP.is_file(), reason=f"no LAMMPS executable at {LMP}")

#: a run of 20 taps with a restart and profiles every 5 taps
SHORT = dict(TINY, taps=20, pevery=5)

#: LAMMPS that stops at tap 10 whatever taps it is given: a session that ended at tap 10
STOP_AT_10 = """#!{python}
import os, sys
args = sys.argv[1:]
for k in range(len(args) - 2):
    if args[k:k + 2] == ["-var", "taps"]:
        args[k + 2] = "10"
os.execv({lmp!r}, [{lmp!r}] + args)
"""


def _stopped_at_10(folder, specs, tmp_path):
    """A campaign folder whose runs ``specs`` ran to tap 10 (restarts 5 and 10) and failed;
    returns their folders."""
    wrapper = tmp_path / "lmp_stop_at_10"
    wrapper.write_text(STOP_AT_10.format(python=sys.executable, lmp=str(LMP)))
    wrapper.chmod(0o755)
    with pytest.raises(CampaignError, match="ends at step 10, expected 20"):
        Campaign(folder, specs, lmp=wrapper, jobs=len(specs)).run(progress=False)
    run_dirs = [folder / "runs" / spec.name for spec in specs]
    for run_dir in run_dirs:
        assert steps(run_dir / "taps.dat") == list(range(11))
        assert (run_dir / "restart.10").is_file()
    return run_dirs


def _reference(tmp_path, spec):
    """The folder of ``spec`` run without interruption."""
    return Campaign(tmp_path / "ref", [spec], lmp=LMP, jobs=1).run(progress=False).result(
        spec.name)


def _same_outputs(run_dir, ref):
    for name in ("taps.dat", "profile_z.dat", "profile_x.dat"):
        assert (run_dir / name).read_bytes() == (ref / name).read_bytes(), name


def test_rewrites_of_a_run_folder_are_whole_or_not_at_all(tmp_path, monkeypatch):
    """The resume's trim of the per-tap file, the finish's removal of repeated titles and the
    merge of profile segments write a new file that replaces the old one: killed before the
    rename (os.replace fails here), the old file is intact, never truncated in place (a
    SIGKILL between the truncation and the write once sealed an empty taps.dat into a
    finished run)."""
    taps = tmp_path / "taps.dat"
    taps.write_text("# step x\n0 1\n1 2\n# step x\n2 3\n3 4\n")
    header = "# Time-averaged data\n# TimeStep Number-of-rows\n# Row c_p[1]\n"
    (tmp_path / "prof.dat").write_text(header + "0 1\n1 0.5\n")
    (tmp_path / "prof.dat.from1").write_text(header + "1 1\n1 0.25\n")
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir()}

    def killed(src, dst):
        raise KeyboardInterrupt("killed before the rename")

    with monkeypatch.context() as m:
        m.setattr(os, "replace", killed)
        for rewrite in (lambda: run_folder.trim_rows(taps, 2),
                        lambda: run_folder.drop_repeated_titles(taps),
                        lambda: run_folder.merge_ave_time_parts(tmp_path)):
            with pytest.raises(KeyboardInterrupt):
                rewrite()
            assert {p.name: p.read_bytes() for p in tmp_path.iterdir()
                    if not p.name.endswith(".tmp")} == before
    # done for real, each file is a new one (a reader holding the old file reads it whole)
    inode = taps.stat().st_ino
    run_folder.trim_rows(taps, 2)
    assert taps.read_text() == "# step x\n0 1\n1 2\n# step x\n" and taps.stat().st_ino != inode
    assert run_folder.remove_temporary_files(tmp_path) == ["prof.dat.tmp"]


def test_the_steps_of_a_per_tap_file(tmp_path):
    """step_rows_problem: the rows first..last once each and in order, first one of the
    allowed starts; names the first row that breaks it."""
    path = tmp_path / "taps.dat"
    path.write_text("# step\n0 a\n1 b\n# step\n2 c\n")
    assert run_folder.step_rows_problem(path, 2) == ""
    assert run_folder.step_rows_problem(path, 3) == "taps.dat ends at step 2, expected 3"
    path.write_text("# step\n0\n1\n2\n1\n2\n")
    assert run_folder.step_rows_problem(path, 2) == \
        "taps.dat:5: step 1 where 3 was due (rows repeated)"
    path.write_text("# step\n0\n2\n")
    assert run_folder.step_rows_problem(path, 2) == \
        "taps.dat:3: step 2 where 1 was due (rows missing)"
    path.write_text("# step\n10\n11\n")
    assert run_folder.step_rows_problem(path, 11) == "taps.dat starts at step 10, not at 0"
    assert run_folder.step_rows_problem(path, 11, {0, 10}) == ""
    path.write_text("# step\n0\n\0\0\0 1\n")
    assert run_folder.step_rows_problem(path, 1) == "taps.dat:3: not a row of a step"
    path.write_text("# step\n")
    assert run_folder.step_rows_problem(path, 9) == \
        "taps.dat has no rows (steps up to 9 expected)"
    assert run_folder.step_rows_problem(path, 9, {0, 10}) == ""


def test_a_per_tap_file_emptied_before_a_resume_starts_the_run_over(tmp_path):
    """A kill during the rewrite of an older TAPMC left taps.dat empty while the run had
    reached tap 10: resumed from restart.10, it would have been sealed with rows 10..20 only.
    The resume sees the rows before its restart missing, sets the run's files aside and runs
    it again from the start, to the bytes of an uninterrupted run."""
    spec = RunSpec("r", CONSTANT_EPS, SHORT, seed=3)
    folder = tmp_path / "c"
    (run_dir,) = _stopped_at_10(folder, [spec], tmp_path)
    (run_dir / "taps.dat").write_bytes(b"")
    stream = io.StringIO()
    Campaign(folder, [spec], lmp=LMP, jobs=1, stream=stream).run(progress=False)
    assert (f"[campaign] run 'r': {run_dir / 'taps.dat'}: taps.dat has no rows (steps up to 9 "
            "expected), before its restart at step 10; the run goes again from the start "
            "(its files moved to damaged1/)") in stream.getvalue()
    assert "Reading restart file" not in (run_dir / "log.lammps").read_text()
    _same_outputs(run_dir, _reference(tmp_path, spec))


def test_a_restart_cut_short_is_set_aside_and_the_run_resumes_from_the_one_before(tmp_path):
    """A kill, a stop or a full disk while LAMMPS wrote restart.10 left it cut short, and every
    resume failed on it for good ("Unexpected end of file"). A restart without LAMMPS's end
    mark is set aside before the resume (the dry run's resume point skips it too); one whose
    end mark survived but that LAMMPS cannot read is set aside when read_restart fails, and
    the run goes on at once from the restart before. Both give the bytes of an uninterrupted
    run."""
    runs = [RunSpec(name, CONSTANT_EPS, SHORT, seed=4) for name in ("cut", "unread")]
    folder = tmp_path / "c"
    cut, unread = _stopped_at_10(folder, runs, tmp_path)
    whole = (cut / "restart.10").read_bytes()
    assert whole.startswith(run_folder.RESTART_MARK) and whole.endswith(run_folder.RESTART_MARK)
    (cut / "restart.10").write_bytes(whole[:len(whole) // 2])
    (unread / "restart.10").write_bytes(whole[:3000] + run_folder.RESTART_MARK)
    assert run_folder.resume_restart(cut)[0] == 5 and run_folder.resume_restart(unread)[0] == 10
    stream = io.StringIO()
    Campaign(folder, runs, lmp=LMP, jobs=1, stream=stream).run(progress=False)
    text = stream.getvalue()
    assert (f"[campaign] run 'cut': {cut / 'restart.10'}: {len(whole) // 2} bytes without "
            "LAMMPS's end mark: cut short while it was written (a kill, a stop or a full "
            "disk); moved to damaged1/, the run resumes from restart.5") in text
    assert (f"[campaign] run 'unread': {unread / 'restart.10'}: LAMMPS could not read it "
            "(ERROR on proc 0: Unexpected end of file while reading file") in text
    assert "moved to damaged1/, the run resumes from restart.5" in text.split("'unread'")[1]
    ref = _reference(tmp_path, runs[0])
    for run_dir in (cut, unread):
        assert (run_dir / "damaged1" / "restart.10").exists()
        assert "read_restart    restart.5" in (run_dir / "log.lammps").read_text()
        _same_outputs(run_dir, ref)
    record = json.loads((folder / "manifest.json").read_text())["runs"][1]
    assert [a["resumed_from_step"] for a in record["attempts"]] == [None, 10, 5]
    assert record["damaged"][0]["rerun_from_step"] == 5


FAKE_TWO_WRITERS = """#!/bin/sh
case " $* " in *" -in "*) ;; *) exit 0 ;; esac
printf '# step x\\n0 0\\n1 0\\n2 0\\n1 0\\n2 0\\n3 0\\n' > taps.dat
echo 'Total wall time: 0:00:01' > log.lammps
"""


def test_a_per_tap_file_with_repeated_rows_is_never_sealed(tmp_path):
    """A per-tap file that reaches the last tap but repeats rows (two LAMMPS processes wrote
    it) is no finished run: no DONE.json, its files set aside, and the failure says so."""
    fake = tmp_path / "lmp_fake"
    fake.write_text(FAKE_TWO_WRITERS)
    fake.chmod(0o755)
    spec = RunSpec("twice", CONSTANT_EPS, dict(TINY, taps=3), seed=1)
    folder = tmp_path / "c"
    with pytest.raises(CampaignError) as err:
        Campaign(folder, [spec], lmp=str(fake), jobs=1).run(progress=False)
    assert ("run 'twice' failed: its per-tap file is damaged (taps.dat:5: step 1 where 3 was "
            "due (rows repeated)): no DONE.json; its files are in damaged1/ and it runs again "
            "from the start") in str(err.value)
    run_dir = folder / "runs" / "twice"
    assert not (run_dir / "DONE.json").exists() and (run_dir / "damaged1" / "taps.dat").exists()


def test_a_temporary_file_of_the_campaign_is_no_output(tmp_path):
    """A DONE.json.tmp left by a kill before its rename (or any NAME.tmp of the campaign's own
    writes) is no output: it was checksummed into the next DONE.json, found gone at the check
    after, and the finished run went again from tap 0 and then failed. A DONE.json of an older
    TAPMC that lists one is not damaged for its absence."""
    spec = RunSpec("r", CONSTANT_EPS, dict(TINY, taps=5), seed=2)
    folder = tmp_path / "c"
    run_dir = Campaign(folder, [spec], lmp=LMP, jobs=1).run(progress=False).result("r")
    (run_dir / "DONE.json").rename(run_dir / "DONE.json.tmp")     # killed before the rename
    (run_dir / "taps.dat.tmp").write_text("0 cut")
    assert run_folder.output_files(run_dir) == [
        "profile_x.dat", "profile_z.dat", "restart.5", "taps.dat"]
    Campaign(folder, [spec], lmp=LMP, jobs=1).run(progress=False)   # resumes at tap 5
    done = provenance.read_done(run_dir / "DONE.json")
    assert not any(name.endswith(".tmp") for name in done["outputs"])
    stream = io.StringIO()
    Campaign(folder, [spec], lmp=LMP, jobs=1, stream=stream).run()
    assert "1 of 1 runs already done, 0 to run" in stream.getvalue()
    older = dict(done["outputs"], **{"DONE.json.tmp": {"sha256": "0" * 64, "size": 9}})
    assert provenance.damaged_outputs(run_dir, older) == {}


COPY_UNDER_A_FULL_DISK = """
import resource, sys
sys.path.insert(0, {python!r})
from tapmc.campaign import RunSpec, provenance
spec = RunSpec("r", {inp!r}, {{"taps": 1}})
resource.setrlimit(resource.RLIMIT_FSIZE, (4096, 4096))   # writes past 4 KiB fail (EFBIG)
try:
    provenance.copy_inputs({folder!r}, [spec], False, sys.stdout)
except OSError as err:
    print("ERROR", err.filename, err.strerror)
try:
    provenance.write_manifest({folder!r}, {{"runs": [], "note": "x" * 8192}})
except OSError as err:
    print("ERROR", err.filename, err.strerror)
"""


def test_an_input_copy_is_whole_and_checked_against_the_manifest(tmp_path):
    """The copy of an input is written whole or not at all: a write that fails (a full disk;
    here a file size limit) leaves no copy and names the copy, not its source (a cut copy was
    then run, for good, as "the input changed since the campaign started"). A copy whose
    sha256 differs from the one the manifest recorded is copied again from its source when the
    source still has it; when neither has it, the campaign refuses naming both files."""
    source = tmp_path / "in.constant_eps"
    source.write_bytes(CONSTANT_EPS.read_bytes())
    folder = tmp_path / "c"
    script = COPY_UNDER_A_FULL_DISK.format(python=str(Path(provenance.__file__).parents[2]),
                                           inp=str(source), folder=str(folder))
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    copy = folder / "inputs" / "in.constant_eps"
    assert out.stdout.splitlines() == [f"ERROR {copy} File too large",
                                       f"ERROR {folder / 'manifest.json'} File too large"], \
        out.stdout + out.stderr
    assert list((folder / "inputs").iterdir()) == []
    assert sorted(p.name for p in folder.iterdir()) == ["inputs"]

    spec = RunSpec("r", source, dict(TINY, taps=2), seed=1)
    Campaign(folder, [spec], lmp=LMP, jobs=1).run(progress=False)
    copy.write_bytes(copy.read_bytes()[:4096])        # damaged after the campaign started
    stream = io.StringIO()
    Campaign(folder, [spec], lmp=LMP, jobs=1, stream=stream).run(progress=False)
    assert (f"[campaign] input copy {copy}: its sha256 differed from the one manifest.json "
            f"recorded (damaged since); copied again from {source}, which has it"
            ) in stream.getvalue()
    assert copy.read_bytes() == source.read_bytes()
    copy.write_bytes(b"")
    source.write_bytes(source.read_bytes() + b"# edited\n")
    with pytest.raises(CampaignDirectoryError) as err:
        Campaign(folder, [spec], lmp=LMP, jobs=1, pin_inputs=True).run(progress=False)
    assert str(err.value) == (
        f"input copy {copy}: its sha256 differs from the one {folder / 'manifest.json'} "
        f"recorded, and so does its source {source}: the input this campaign started with "
        "is gone; put it back in either place or use a new campaign directory")


def test_a_lammps_child_dies_with_its_runner_even_in_the_fork_window(tmp_path):
    """Between fork and exec a child still has its runner's Python SIGTERM handler, which
    swallowed the parent-death signal; and a runner killed before the child's prctl was never
    noticed. The child's setup restores SIGTERM's default action, asks for the parent-death
    signal and then ends itself when its parent is not the runner any more. Both cases are
    made here on purpose: a SIGTERM in the setup window, and a runner that is another process
    than the child's parent."""
    caught = []
    previous = signal.signal(signal.SIGTERM, lambda signum, frame: caught.append(signum))
    try:
        setup = launch.child_setup(os.getpid())

        def term_in_the_window():
            setup()
            os.kill(os.getpid(), signal.SIGTERM)

        # from a worker thread, as a campaign starts its runs
        with ThreadPoolExecutor(1) as pool:
            code = pool.submit(lambda: subprocess.run(
                ["true"], preexec_fn=term_in_the_window).returncode).result()
    finally:
        signal.signal(signal.SIGTERM, previous)
    assert code == -signal.SIGTERM and caught == []
    orphan = subprocess.run(["sleep", "30"], preexec_fn=launch.child_setup(os.getppid()))
    assert orphan.returncode == -signal.SIGTERM


LOCK_DRIVER = """
import sys
sys.path.insert(0, {python!r})
from tapmc.campaign import Campaign, RunSpec
Campaign({folder!r}, [RunSpec("r", {inp!r}, {{"taps": 3}})], lmp={lmp!r}, jobs=1).run()
"""

#: LAMMPS that, with a file ``hold`` in its folder, outlives its runner (SIGTERM ignored: the
#: parent-death signal does nothing) and writes its pid; else it fails at once
FAKE_ORPHAN = """#!/bin/sh
case " $* " in *" -in "*) ;; *) exit 0 ;; esac
if [ -e hold ]; then rm hold; trap '' TERM; echo $$ > {pidfile}; exec sleep 60; fi
echo 'LAMMPS (fake)' > log.lammps; exit 1
"""


def test_a_lammps_run_left_by_a_killed_runner_keeps_the_campaign_locked(tmp_path):
    """A LAMMPS child that outlives a SIGKILLed runner (the QA saw one write a finished run's
    taps.dat together with the next session's) holds the campaign's lock: the runner passes
    the lock's descriptor to its children, and a new session is refused, naming campaign.lock,
    until that process ends."""
    pidfile = tmp_path / "orphan.pid"
    fake = tmp_path / "lmp_fake"
    fake.write_text(FAKE_ORPHAN.format(pidfile=pidfile))
    fake.chmod(0o755)
    folder = tmp_path / "c"
    (folder / "runs" / "r").mkdir(parents=True)
    (folder / "runs" / "r" / "hold").touch()
    script = LOCK_DRIVER.format(python=str(Path(provenance.__file__).parents[2]),
                                folder=str(folder), inp=str(CONSTANT_EPS), lmp=str(fake))
    env = dict(os.environ, OMPI_MCA_orte_tmpdir_base=str(tmp_path / "mpi"))
    driver = subprocess.Popen([sys.executable, "-c", script], env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)
    orphan = None
    try:
        deadline = time.time() + 30
        while not (pidfile.exists() and pidfile.read_text().strip()) and time.time() < deadline:
            time.sleep(0.05)
        orphan = int(pidfile.read_text())
        driver.kill()
        driver.wait()
        spec = RunSpec("r", CONSTANT_EPS, {"taps": 3})
        with pytest.raises(CampaignError, match=r"being run by another process \(campaign.lock "
                                                r"is held: by another runner, or by a LAMMPS "
                                                r"run a killed runner left, until it ends"):
            Campaign(folder, [spec], lmp=str(fake), jobs=1).run(progress=False)
    finally:
        if orphan is not None:
            os.kill(orphan, signal.SIGKILL)
        driver.kill()
        driver.wait()
    deadline = time.time() + 30
    while time.time() < deadline:   # the lock is free once the orphan has gone
        try:
            with launch.campaign_lock(folder):
                break
        except CampaignError:
            time.sleep(0.05)
    with pytest.raises(CampaignError, match="run 'r' failed"):
        Campaign(folder, [spec], lmp=str(fake), jobs=1).run(progress=False)


def test_a_manifest_that_cannot_be_written_hides_no_error_of_the_session(tmp_path, monkeypatch):
    """On a full disk the manifest written after the runs failed and its OSError, without a
    path, replaced the session's own error (a failed run here). The writes of the manifest
    while the runs run and after them are best effort: one line says so, the runs go on, and
    the session's error comes first, followed by the manifest's, path first."""
    spec = RunSpec("bad", CONSTANT_EPS, dict(TINY, taps=3, bc="xyz"), seed=1)
    written = provenance.write_manifest

    def disk_full_once_a_run_ended(directory, data):
        if any(r["attempts"] for r in data["runs"]):
            raise OSError(28, "No space left on device", str(directory / "manifest.json"))
        written(directory, data)

    monkeypatch.setattr(provenance, "write_manifest", disk_full_once_a_run_ended)
    stream = io.StringIO()
    with pytest.raises(CampaignError) as err:
        Campaign(tmp_path / "c", [spec], lmp=LMP, jobs=1, stream=stream).run(progress=False)
    manifest = tmp_path / "c" / "manifest.json"
    assert str(err.value).startswith("1 of 1 runs failed:\n  run 'bad' failed: ERROR: bc = xyz")
    assert str(err.value).endswith(f"; and the manifest could not be written ({manifest}: No "
                                   "space left on device)")
    assert stream.getvalue().count(f"[campaign] warning: {manifest}: No space left on device: "
                                   "the manifest is not written; the runs go on") == 1


@pytest.mark.parametrize("behaviour,expected", [
    ("exit 0", "LAMMPS exited with code 0 without finishing the run (its log was not written): "
               "is {lmp} a LAMMPS that runs in.constant_eps?"),
    ("echo 'LAMMPS (fake)' > log.lammps; exit 0",
     "LAMMPS exited with code 0 without finishing the run (its log has no Total wall time "
     "line): is {lmp} a LAMMPS that runs in.constant_eps?"),
    ("printf '# s\\n0\\n1\\n' > taps.dat; kill -SEGV $$",
     "LAMMPS crashed (signal SIGSEGV) after tap 1: a fault of the executable, not a stop from "
     "outside (its log and screen.txt say where;")])
def test_a_lammps_that_ends_early_is_named_for_what_it_did(tmp_path, behaviour, expected):
    """An executable that exits 0 without running was "LAMMPS exited with code 0", and a crash
    (SIGSEGV) "stopped by signal SIGSEGV", as if stopped from outside."""
    fake = tmp_path / "lmp_fake"
    fake.write_text("#!/bin/sh\ncase \" $* \" in *\" -in \"*) ;; *) exit 0 ;; esac\n"
                    + behaviour + "\n")
    fake.chmod(0o755)
    spec = RunSpec("r", CONSTANT_EPS, dict(TINY, taps=3), seed=1)
    with pytest.raises(CampaignError) as err:
        Campaign(tmp_path / "c", [spec], lmp=str(fake), jobs=1).run(progress=False)
    assert f"run 'r' failed: {expected.format(lmp=fake)}" in str(err.value)


def test_a_run_begun_under_other_parameters_is_refused_not_resumed(tmp_path):
    """A run stopped at tap 10 (eps 0.02) and asked again with eps 0.1 resumed from its eps 0.02
    restart: a taps.dat of two eps under a DONE.json naming the new one; asked with fewer taps
    than it had, it resumed beyond them and failed at every session. Both are refused by name
    (nothing moved); asked as it was, or with more taps, it resumes."""
    folder = tmp_path / "c"
    spec = RunSpec("r", CONSTANT_EPS, dict(SHORT, eps=0.02), seed=1)
    (run_dir,) = _stopped_at_10(folder, [spec], tmp_path)
    before = sorted(p.name for p in run_dir.iterdir())
    for changed, message in (
            (dict(SHORT, eps=0.1), r"begun in .* with other parameters \(eps 0.02 -> 0.1\)"),
            (dict(SHORT, eps=0.02, taps=8), r"with other parameters \(taps 20 -> 8 \(fewer\)\)")):
        with pytest.raises(CampaignDirectoryError, match=message):
            Campaign(folder, [RunSpec("r", CONSTANT_EPS, changed, seed=1)], lmp=LMP,
                     jobs=1).run(progress=False)
        assert sorted(p.name for p in run_dir.iterdir()) == before
    # more taps, with the variables that follow them (a question continuing a level sets
    # pevery = taps: it was refused)
    longer = RunSpec("r", CONSTANT_EPS, dict(SHORT, eps=0.02, taps=25, pevery=25), seed=1)
    done = Campaign(folder, [longer], lmp=LMP, jobs=1).run(progress=False).result("r")
    assert steps(done / "taps.dat") == list(range(26))


def test_a_session_of_some_runs_keeps_the_records_of_the_others(tmp_path):
    """A session that runs (or draws) some of a campaign's runs rewrote manifest.json with its
    own runs only: the other runs' attempts, costs and versions, and their inputs' records
    (whose pinned copies guard against a changed input), were gone (a Fig. 2 drawn from the
    paper-scale campaign left 3 of its 78 run records)."""
    folder = tmp_path / "c"
    first = RunSpec("a", CONSTANT_EPS, dict(TINY, taps=5), seed=1)
    Campaign(folder, [first], lmp=LMP, jobs=1).run(progress=False)
    before = json.loads((folder / "manifest.json").read_text())
    other_input = tmp_path / "in.other"
    other_input.write_text(CONSTANT_EPS.read_text())
    second = RunSpec("b", other_input, dict(TINY, taps=5), seed=2)
    Campaign(folder, [second], lmp=LMP, jobs=1).run(progress=False)
    after = json.loads((folder / "manifest.json").read_text())
    assert [r["name"] for r in after["runs"]] == ["b", "a"]
    assert after["runs"][1] == before["runs"][0]
    assert after["inputs"]["in.constant_eps"] == before["inputs"]["in.constant_eps"]
    assert "in.other" in after["inputs"]


def test_a_run_killed_in_its_first_attempt_whose_log_and_taps_went_is_run_again(tmp_path):
    """Killed in its first attempt (the manifest holds its start, from tap 0), then its log and
    taps.dat removed, restarts left: the campaign resumed from the latest restart and sealed a
    taps.dat without its first taps (rows 340-1500 of 1501) as finished. The killed attempt is
    now recorded without its log, so the run needs its rows from tap 0, and starts over."""
    folder = tmp_path / "c"
    spec = RunSpec("r", CONSTANT_EPS, dict(SHORT, eps=0.02), seed=1)
    (run_dir,) = _stopped_at_10(folder, [spec], tmp_path)
    manifest = json.loads((folder / "manifest.json").read_text())
    record = manifest["runs"][0]
    first = record["attempts"].pop(0)           # as a SIGKILL leaves it: a start, no end
    record["running_attempt"] = {"started": first["started"], "resumed_from_step": None}
    (folder / "manifest.json").write_text(json.dumps(manifest))
    for name in ("log.lammps", "taps.dat"):
        (run_dir / name).unlink()
    stream = io.StringIO()
    done = Campaign(folder, [spec], lmp=LMP, jobs=1, stream=stream).run(progress=False)
    assert "the run goes again from the start" in stream.getvalue(), stream.getvalue()
    assert steps(done.result("r") / "taps.dat") == list(range(21))


def test_the_rows_a_resume_keeps_are_read_as_the_dry_run_reads_them(tmp_path):
    """A dry run reads the rows before the restart it would resume from (the resume trims the
    rest): rows lost there mean a run from the start (it said "resumes from tap 2300" for a run
    the campaign then ran again from tap 0). A killed first attempt's start (running_attempt)
    is where the run began."""
    taps = tmp_path / "taps.dat"
    taps.write_text("# step x\n" + "".join(f"{s} 1\n" for s in range(30)))
    assert run_folder.step_rows_problem(taps, 19, past_last=True) == ""
    assert "ends at step 29" in run_folder.step_rows_problem(taps, 19)
    taps.write_text("# step x\n" + "".join(f"{s} 1\n" for s in range(30) if s != 7))
    assert run_folder.step_rows_problem(taps, 19, past_last=True) == \
        "taps.dat:9: step 8 where 7 was due (rows missing)"
    from tapmc.campaign.repair import first_steps
    assert first_steps({"attempts": [], "running_attempt": {"resumed_from_step": None}}, 20) \
        == {0}
    assert first_steps({"attempts": []}, 20) == {0, 20}
