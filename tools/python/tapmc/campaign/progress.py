# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""What the progress lines of a campaign say of the time left: each run's cost per tap (its own
rate, finished runs like it, a cost per tap given for a ramp's taps) and the campaign's ETA."""

import json
import math
from itertools import accumulate

__all__ = ["format_seconds", "past_seconds_per_tap", "estimate_seconds_left", "cost_sums",
           "weighted_seconds_left"]


def format_seconds(s):
    """Seconds as the progress lines write them (``1h02m03s``, ``4m05s``, ``6s``; ``?`` for
    None)."""
    if s is None:
        return "?"
    s = int(round(s))
    h, rem = divmod(s, 3600)
    m, sec = divmod(rem, 60)
    return f"{h}h{m:02d}m{sec:02d}s" if h else (f"{m}m{sec:02d}s" if m else f"{sec}s")


def _sibling_key(describe):
    """What makes two runs cost the same per tap: their input, variables and ranks (the seed
    and the name aside)."""
    return (describe["input"], json.dumps(describe["variables"], sort_keys=True),
            describe.get("nprocs", 1))


def past_seconds_per_tap(records):
    """Wall seconds per tap of the finished attempts in manifest ``records`` (name -> record):
    dict name -> s per tap, from the attempts that ended with returncode 0 (taps = the run's
    taps - the step it resumed from; attempts of no tap aside)."""
    out = {}
    for name, rec in records.items():
        wall = taps = 0.0
        for attempt in rec.get("attempts", []):
            if attempt.get("returncode") != 0 or not attempt.get("wall_s") or not rec.get("taps"):
                continue
            covered = rec["taps"] - (attempt.get("resumed_from_step") or 0)
            if covered > 0:
                wall += attempt["wall_s"]
                taps += covered
        if taps:
            out[name] = wall / taps
    return out


def estimate_seconds_left(left, records, running, jobs, session_rate, started=None):
    """Wall seconds until the last run ends, from what each run costs per tap rather than
    from the campaign's mean rate (taps of different runs differ several times in cost: a
    weak tap settles in fewer sweeps than a strong one).

    ``left``: name -> taps still to run (unfinished runs, in the order the campaign starts
    them); ``records``: the manifest's records (name -> describe() plus attempts); ``running``:
    name -> this session's measured s per tap of a running run; ``jobs``: runs at a time;
    ``session_rate``: taps per second of the whole session, or 0; ``started``: the names of
    the runs running now (default: those of ``running``). Each run's s per tap: its own rate
    when running, else the mean of finished runs that differ from it only by seed, else of
    finished runs of the same input, else the session's (jobs / session_rate). The runs
    running now hold a job each, the others go in order to the job that is free first (as
    the pool starts them), and the ETA is when the last job ends: never less than the longest
    run left, which no number of jobs shortens (the sum over the runs divided by the jobs
    promised one run left on two jobs in half its time). None when some run has no
    estimate."""
    past = past_seconds_per_tap(records)
    siblings, inputs = {}, {}
    for name, spt in past.items():
        rec = records[name]
        siblings.setdefault(_sibling_key(rec), []).append(spt)
        inputs.setdefault(rec["input"], []).append(spt)
    fallback = jobs / session_rate if session_rate > 0 else None
    started = set(running if started is None else started)
    now, queued = [], []
    for name, taps in left.items():
        if taps <= 0:
            continue
        rec = records.get(name, {})
        spt = running.get(name)
        if spt is None and rec:
            similar = siblings.get(_sibling_key(rec)) or inputs.get(rec.get("input"))
            spt = sum(similar) / len(similar) if similar else None
        spt = fallback if spt is None else spt
        if spt is None:
            return None
        (now if name in started else queued).append(taps * spt)
    loads = now + [0.0] * max(0, int(jobs) - len(now))
    for seconds in queued:
        loads[loads.index(min(loads))] += seconds
    return max(loads, default=0.0)


def cost_sums(tap_costs, runs):
    """name -> cumulative tap costs (index k: the cost of taps 1..k) of Campaign's
    ``tap_costs``, checked against the runs (a known name, one positive finite cost per tap)."""
    sums = {}
    for name, costs in tap_costs.items():
        spec = runs.get(name)
        if spec is None:
            raise ValueError(f"tap_costs: {name!r} is not a run of the campaign")
        costs = [float(c) for c in costs]
        if spec.taps is None or len(costs) != spec.taps:
            raise ValueError(f"tap_costs[{name!r}]: {len(costs)} costs, the run has "
                             f"{spec.taps} taps: one cost per tap")
        if not all(math.isfinite(c) and c > 0 for c in costs):
            raise ValueError(f"tap_costs[{name!r}]: every cost must be finite and > 0")
        sums[name] = list(accumulate(costs, initial=0.0))
    return sums


def weighted_seconds_left(cost_sums, done0, done, elapsed):
    """Seconds a running run still needs when its taps differ in cost: the ``elapsed`` seconds
    it took from tap ``done0`` to tap ``done`` times the cost of the taps left over the cost of
    those done (``cost_sums``: cumulative costs, index k the cost of taps 1..k, the last the
    run's total); None before it has done a tap this session."""
    spent = cost_sums[done] - cost_sums[done0]
    if not spent > 0:
        return None
    return float(elapsed * (cost_sums[-1] - cost_sums[done]) / spent)
