# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""tapmc.campaign.progress: the campaign's ETA from what each run costs per tap and from how
the runs left share the jobs (no LAMMPS run)."""

import os
import sys
from pathlib import Path

import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc.campaign.progress import estimate_seconds_left, past_seconds_per_tap  # noqa: E402


def test_eta_counts_what_each_run_costs_per_tap():
    """The campaign's ETA takes each run's taps left times its own cost per tap (its running
    rate, else finished runs that differ only by seed, else of its input, else the session's);
    a mean rate over cheap taps would promise the expensive runs too soon. The runs running now
    hold a job each, the others go in order to the job free first: the ETA is when the last job
    ends, never less than the longest run (one run left on two jobs is not done in half its
    time)."""
    def record(name, eps, seed, attempts, inp="in.constant_eps"):
        return {"name": name, "input": inp, "variables": {"eps": eps, "taps": 100},
                "seed": seed, "nprocs": 1, "taps": 100, "attempts": attempts}

    done = {"returncode": 0, "wall_s": 100.0, "resumed_from_step": None}
    records = {
        "weak_s1": record("weak_s1", 0.01, 1, [done]),                        # 1 s per tap
        # a killed attempt (no wall time), then 300 s for the taps 50..100: 6 s per tap
        "strong_s1": record("strong_s1", 0.2, 1, [
            {"interrupted": True, "taps_done": 57},
            {"returncode": -15, "wall_s": 40.0, "resumed_from_step": 0},
            {"returncode": 0, "wall_s": 300.0, "resumed_from_step": 50}]),
        "strong_s2": record("strong_s2", 0.2, 2, []),
        "other_s1": record("other_s1", 0.05, 1, []),
        "ageing_s1": record("ageing_s1", 0.01, 1, [], inp="in.ageing"),
    }
    assert past_seconds_per_tap(records) == {"weak_s1": 1.0, "strong_s1": 6.0}
    # strong_s2 like strong_s1; other_s1 as the mean of its input (3.5); 2 jobs, one each
    eta = estimate_seconds_left({"strong_s2": 100, "other_s1": 100}, records, {}, 2, 0.0)
    assert eta == pytest.approx(100 * 6.0)
    # one job: one after the other
    eta = estimate_seconds_left({"strong_s2": 100, "other_s1": 100}, records, {}, 1, 0.0)
    assert eta == pytest.approx(100 * 6.0 + 100 * 3.5)
    # one run left on two jobs: its own time, not half of it
    assert estimate_seconds_left({"strong_s2": 100}, records, {}, 2, 0.0) == \
        pytest.approx(100 * 6.0)
    # three runs on two jobs, in order: the third waits for the job that frees first
    eta = estimate_seconds_left({"strong_s2": 100, "other_s1": 100, "weak_s1": 100}, records,
                                {}, 2, 0.0)
    assert eta == pytest.approx(max(100 * 6.0, 100 * 3.5 + 100 * 1.0))
    # a running run's own rate first; a run of no known input takes the session's
    eta = estimate_seconds_left({"strong_s2": 10, "ageing_s1": 100}, records,
                                {"strong_s2": 2.0}, 2, 0.5)
    assert eta == pytest.approx(max(10 * 2.0, 100 * 2 / 0.5))
    # a run running now holds its job, also before its rate is known: the others queue
    eta = estimate_seconds_left({"strong_s2": 100, "other_s1": 100, "weak_s1": 100}, records,
                                {}, 2, 0.0, started={"weak_s1", "other_s1"})
    assert eta == pytest.approx(100 * 1.0 + 100 * 6.0)
    # nothing to go on: no estimate
    assert estimate_seconds_left({"ageing_s1": 100}, records, {}, 2, 0.0) is None
