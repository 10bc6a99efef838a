# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# tapmc-paper question campaign-runs on a synthetic campaign whose every answer is known: a
# finished run, a ramp under way (restart files at two steps, attempts with and without their
# CPU time and version), a run not started; the CSV, the appendix's summary and table, the cost
# rule's columns, and a folder that is no campaign or has a damaged manifest.
import json
import os
import sys

import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "tools", "python"))

from campaign_runs import WHOLE_RESTART  # noqa: E402
from tapmc.paper import cli, cost, questions  # noqa: E402
from tapmc.paper.questions import campaign_runs  # noqa: E402

RAMP = {"N": 4096, "L": 32.0, "eta": 1e-06, "rsteps": 100, "bc": "pbc", "sqrt0": 0.025,
        "dsqrt": 0.025, "nlev": 5, "P": 4000}
CONST = {"N": 4096, "L": 32.0, "eta": 1e-07, "rsteps": 100, "eps": 0.0225, "taps": 4000,
         "bc": "pbc"}


def record(name, variables, taps, seed, attempts=(), status="pending", input_="in.ramp"):
    return {"name": name, "input": input_, "variables": variables, "seed": seed, "nprocs": 1,
            "taps": taps, "attempts": list(attempts), "status": status}


def loop(seconds, steps, cpu_use):
    """The lines LAMMPS writes at the end of a run command."""
    return (f"Loop time of {seconds} on 1 procs for {steps} steps with 4096 atoms\n\n"
            f"{cpu_use}% CPU use with 1 MPI tasks x 1 OpenMP threads\n\nMPI task timing\n")


def write_campaign(root):
    """done: 2 attempts (1800 s and an untimed one from before versions were recorded);
    ramp: 3 attempts (3600 s under abc1234, 7200 s under def5678, one killed untimed under
    def5678), restart.12000 and restart.12800 on disk; fresh: nothing. The logs: done's two
    run commands 1 CPU h over 1500 taps, the ramp's kept attempt 0.1 CPU h over 10 taps."""
    runs = root / "runs"
    done = record("const_pbc_eps0.0225_s1", CONST, 4000, 1, status="done",
                  input_="in.constant_eps",
                  attempts=[{"interrupted": True, "taps_done": 100},
                            {"cpu_s": 1800.0, "wall_s": 2000.0, "tapmc_version": "abc1234"}])
    ramp = record("paperramp0.125_pbc_eta1e-06_s2", RAMP, 52000, 2, attempts=[
        {"cpu_s": 3600.0, "wall_s": 3700.0, "tapmc_version": "abc1234"},
        {"cpu_s": 7200.0, "wall_s": 7300.0, "tapmc_version": "def5678"},
        {"interrupted": True, "tapmc_version": "def5678", "taps_done": 12900}])
    fresh = record("const_pbc_eps0.0225_s2", CONST, 4000, 2, input_="in.constant_eps")
    for r in (done, ramp, fresh):
        (runs / r["name"]).mkdir(parents=True)
    (runs / done["name"] / "DONE.json").write_text(json.dumps({"run": done}))
    (runs / done["name"] / "taps.dat").write_text(
        "# step phi_c\n" + "".join(f"{t} 0.58\n" for t in range(4001)))
    (runs / done["name"] / "log.lammps").write_text(loop(3600.0, 1000, 50.0)
                                                     + loop(1800.0, 500, 100.0))
    (runs / ramp["name"] / "log.attempt1.lammps").write_text(loop(360.0, 10, 100.0))
    for step in (12000, 12800):
        (runs / ramp["name"] / f"restart.{step}").write_bytes(WHOLE_RESTART)
    (root / "manifest.json").write_text(json.dumps({"format": 1, "runs": [done, ramp, fresh]}))
    return root


def measured(tmp_path):
    campaign = write_campaign(tmp_path / "campaign")
    out = tmp_path / "questions"
    assert cli.main(["question", "campaign-runs", "--campaign", str(campaign), "--out",
                     str(out)]) == 0
    return out / campaign_runs.CSV, {r["run"]: r for r in campaign_runs.load(out /
                                                                            campaign_runs.CSV)}


def test_every_run_with_its_settings_state_costs_and_versions(tmp_path, capsys):
    path, rows = measured(tmp_path)
    assert list(rows) == ["const_pbc_eps0.0225_s1", "paperramp0.125_pbc_eta1e-06_s2",
                          "const_pbc_eps0.0225_s2"]               # the manifest's order
    done, ramp, fresh = rows.values()
    assert (done["status"], done["resumes_from"], done["attempts"]) == ("done", "", "2")
    assert (done["cpu_h"], done["attempts_without_cpu_time"]) == ("0.5", "1")
    assert (done["tapmc_versions"], done["attempts_without_version"]) == ("abc1234", "1")
    assert (done["eps"], done["sqrt_eps_top"], done["taps_per_level"]) == ("0.0225", "", "")
    # the ramp resumes from its latest restart file, not its first
    assert (ramp["status"], ramp["resumes_from"]) == ("under way", "12800")
    assert (ramp["sqrt_eps_from"], ramp["sqrt_eps_top"], ramp["taps_per_level"]) == (
        "0.025", "0.125", "4000")
    assert (ramp["eta"], ramp["eps"], ramp["taps"], ramp["seed"]) == ("1e-06", "", "52000", "2")
    assert (ramp["cpu_h"], ramp["attempts_without_cpu_time"]) == ("3", "1")
    assert (ramp["wall_h"], ramp["attempts_without_wall_time"]) == ("3.056", "1")
    assert ramp["tapmc_versions"] == "abc1234 def5678"         # each once, in order
    assert (fresh["status"], fresh["attempts"], fresh["cpu_h"]) == ("not started", "0", "")
    # the logs: loop time times CPU use, summed over every run command of every log
    assert (done["log_cpu_h"], done["log_taps"]) == ("1", "1500")
    assert (ramp["log_cpu_h"], ramp["log_taps"]) == ("0.1", "10")
    assert (fresh["log_cpu_h"], fresh["log_taps"]) == ("", "0")


def test_the_cost_rule_prices_the_whole_run_and_what_is_left(tmp_path, capsys):
    """The rule's CPU hours of the ramp from tap 12800 are those of its taps 12800-51999 by
    cost.tap_seconds; a finished run has nothing left, a fresh one all of it."""
    _, rows = measured(tmp_path)
    rule = cost.CostRule.from_summary()
    seconds = cost.tap_seconds(type("S", (), {"variables": RAMP, "taps": 52000}), rule)
    ramp = rows["paperramp0.125_pbc_eta1e-06_s2"]
    assert float(ramp["rule_cpu_h"]) == pytest.approx(seconds.sum() / 3600, rel=1e-3)
    assert float(ramp["rule_cpu_h_left"]) == pytest.approx(seconds[12800:].sum() / 3600,
                                                           rel=1e-3)
    assert 0 < float(ramp["rule_cpu_h_left"]) < float(ramp["rule_cpu_h"])
    done, fresh = rows["const_pbc_eps0.0225_s1"], rows["const_pbc_eps0.0225_s2"]
    assert done["rule_cpu_h_left"] == "0" and float(done["rule_cpu_h"]) > 0
    assert fresh["rule_cpu_h_left"] == fresh["rule_cpu_h"]


def test_the_appendix_counts_the_runs_and_lists_each(tmp_path, capsys):
    path, rows = measured(tmp_path)
    lines = campaign_runs.render(path)
    text = "\n".join(lines)
    assert lines[0].startswith("The campaign's 3 runs (its ``manifest.json``; "
                               "``campaign_runs.csv``): 1 done, 1 under way, 1 not started; "
                               "redeposition thresholds eta = 1e-06, 1e-07.")
    assert "Their 5 attempts recorded 3.5 CPU h and 3.6 h of wall time; 2 attempts " \
           "recorded no CPU time" in lines[0] and "lower bounds" in lines[0]
    left = sum(float(r["rule_cpu_h_left"]) for r in rows.values())
    assert f"what is left at {left:.1f} CPU h." in lines[0]
    assert "Their LAMMPS logs (each run command's loop time times its CPU use) measure 1.1 " \
           "CPU h over 1510 taps run" in lines[0]
    assert "- 1.00 over 1500 taps" in text and "- 0.10 over 10 taps" in text
    assert "- ramp sqrt(eps) 0.025-0.125, 4000 taps per level" in text
    assert "- under way (resumes from tap 12800)" in text
    assert "- 3.00 (+ 1 untimed)" in text and "- abc1234, def5678" in text
    assert "- abc1234, 1 unrecorded" in text and "- eps = 0.0225" in text
    # it stands with the integrity check on the checks' appendix
    parts = questions.render_parts(path.parent)
    assert "The campaign's runs (campaign-runs)" in "\n".join(parts["checks"])
    assert "campaign-runs" not in "\n".join(parts["questions"])


def test_all_timed_attempts_claim_no_lower_bound(tmp_path, capsys):
    campaign = write_campaign(tmp_path / "campaign")
    manifest = json.loads((campaign / "manifest.json").read_text())
    for r in manifest["runs"]:
        r["attempts"] = [a for a in r["attempts"] if "cpu_s" in a]
    (campaign / "manifest.json").write_text(json.dumps(manifest))
    rows = campaign_runs.analyse(campaign)
    campaign_runs.save(tmp_path / campaign_runs.CSV, rows)
    first = campaign_runs.render(tmp_path / campaign_runs.CSV)[0]
    assert "Their 3 attempts recorded 3.5 CPU h" in first and "lower bounds" not in first


@pytest.mark.parametrize("damage, message", [
    ("no-runs", "no runs/ folder (not a campaign)"),
    ("no-manifest", "its manifest.json lists no run"),
    ("bad-manifest", "not valid JSON"),
])
def test_a_folder_that_is_no_campaign_is_named_and_the_csv_kept(tmp_path, capsys, damage,
                                                                 message):
    campaign = write_campaign(tmp_path / "campaign")
    if damage == "no-runs":
        for run in (campaign / "runs").iterdir():
            for f in run.iterdir():
                f.unlink()
            run.rmdir()
        (campaign / "runs").rmdir()
    elif damage == "no-manifest":
        (campaign / "manifest.json").unlink()
    else:
        (campaign / "manifest.json").write_text("{ not json")
    out = tmp_path / "out"
    out.mkdir()
    (out / campaign_runs.CSV).write_text("run\ncommitted\n")
    status = cli.main(["question", "campaign-runs", "--campaign", str(campaign), "--out",
                       str(out)])
    err = capsys.readouterr().err
    assert status == 2 and "Traceback" not in err and err.count("\n") == 1
    assert message in err
    assert (out / campaign_runs.CSV).read_text() == "run\ncommitted\n"


def test_an_attempt_killed_with_its_campaign_counts_and_its_run_is_under_way(tmp_path):
    """A run whose campaign was killed (SIGKILL) in its first minutes: its record holds only
    the start of that attempt (running_attempt) and its folder a log but no restart file; it
    is under way, from tap 0, with one attempt of unknown time under that attempt's version.
    The control: the same run without the start and the log is not started."""
    campaign = write_campaign(tmp_path / "campaign")
    manifest = json.loads((campaign / "manifest.json").read_text())
    fresh = manifest["runs"][2]
    fresh["running_attempt"] = {"started": "2026-11-30T09:55:22Z", "tapmc_version": "0a1b2c3"}
    (campaign / "manifest.json").write_text(json.dumps(manifest))
    (campaign / "runs" / fresh["name"] / "log.lammps").write_text("LAMMPS (29 Sep 2021)\n")
    rows = {r[0]: dict(zip(campaign_runs.HEADER, map(str, r)))
            for r in campaign_runs.analyse(campaign)}
    killed = rows[fresh["name"]]
    assert (killed["status"], killed["resumes_from"], killed["attempts"]) == ("under way", "",
                                                                              "1")
    assert (killed["tapmc_versions"], killed["attempts_without_cpu_time"]) == ("0a1b2c3", "1")
    assert killed["rule_cpu_h_left"] == killed["rule_cpu_h"]     # it starts again from tap 0
    campaign_runs.save(tmp_path / campaign_runs.CSV, campaign_runs.analyse(campaign))
    assert "- under way (no restart file yet: starts again from tap 0)" in "\n".join(
        campaign_runs.render(tmp_path / campaign_runs.CSV))
    del fresh["running_attempt"]
    (campaign / "manifest.json").write_text(json.dumps(manifest))
    (campaign / "runs" / fresh["name"] / "log.lammps").unlink()
    status = campaign_runs.HEADER.index("status")
    assert {r[0]: r[status] for r in campaign_runs.analyse(campaign)}[fresh["name"]] == \
        "not started"


@pytest.mark.parametrize("damage", ["done_taps_cut", "folder_gone"])
def test_a_damaged_or_missing_run_is_named_not_listed(tmp_path, capsys, damage):
    """A done run whose taps.dat was cut read 'done', and a run whose folder was deleted read
    'under way' with its whole cost left: each is now named, exit 2, nothing written."""
    import shutil
    campaign = write_campaign(tmp_path / "campaign")
    runs = campaign / "runs"
    if damage == "done_taps_cut":
        path = runs / "const_pbc_eps0.0225_s1" / "taps.dat"
        path.write_text("".join(path.read_text().splitlines(keepends=True)[:2001]))
        named = f"{path}"
    else:
        shutil.rmtree(runs / "paperramp0.125_pbc_eta1e-06_s2")
        named = (f"{runs / 'paperramp0.125_pbc_eta1e-06_s2'}: no such folder, but the campaign's "
                 "manifest records 3 attempt(s)")
    out = tmp_path / "questions"
    status = cli.main(["question", "campaign-runs", "--campaign", str(campaign), "--out", str(out)])
    err = capsys.readouterr().err
    assert status == 2 and named in err and err.count("\n") == 1, err
    assert not (out / campaign_runs.CSV).exists()
