# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""campaign-runs: which runs stand behind the page, at which settings, how far each got, what
it cost and which TAPMC ran it? Every run of the campaign's manifest (no simulation): its
input, boundaries, N, redeposition threshold eta, eps (or a ramp's sqrt(eps) range and taps
per level), taps and seed; whether it is done, under way (the tap of its latest restart file,
where it resumes) or not started; the CPU and wall time its attempts recorded (lower bounds
when some attempts recorded none) and the CPU time its LAMMPS logs measured (each run
command's loop time times its CPU use) over the taps they ran; what the cost rule of
``tapmc-paper plan`` gives for it and for what is left of it; and the TAPMC versions its
attempts ran (campaign_runs.csv). Read it with the campaign stopped: an attempt still
running counts as one its campaign was killed in."""

from __future__ import annotations

import math

from tapmc.campaign import CampaignDirectoryError, provenance
from tapmc.campaign.run_folder import resume_restart

from .. import cost
from .._runs import ramp_level
from .._rst import list_table
from .common import QuestionError, csv_schema, runs_folder, taps_table

NAME = "campaign-runs"
CSV = "campaign_runs.csv"
HEADER = ["run", "input", "bc", "N", "L", "eta", "eps", "sqrt_eps_from", "sqrt_eps_top",
          "taps_per_level", "taps", "seed", "ranks", "status", "resumes_from", "attempts",
          "tapmc_versions", "attempts_without_version", "cpu_h", "attempts_without_cpu_time",
          "wall_h", "attempts_without_wall_time", "log_cpu_h", "log_taps", "rule_cpu_h",
          "rule_cpu_h_left"]
#: the states of a run, in the order the page counts them
STATES = ("done", "under way", "not started")


def add_arguments(parser):
    """No options beyond --campaign and --out."""


def _ramp_range(v):
    """(first, top) sqrt(eps) of a ramp's variables (in.ramp: nlev levels of dsqrt from
    sqrt0 up, then down and up again), or ("", "") for a run at one eps."""
    if "nlev" not in v:
        return "", ""
    top = ramp_level(int(v["nlev"]) - 1, v["nlev"], v["sqrt0"], v["dsqrt"])[1]
    return f"{float(v['sqrt0']):g}", f"{top:g}"


def _with_killed_attempt(record):
    """The record with the attempt its campaign was killed in (``running_attempt``: its start
    only, no entry of its own until the run is prepared again, when the campaign records it as
    interrupted) counted as an attempt without times: the table is read with the campaign
    stopped, so such an attempt has ended."""
    running = record.get("running_attempt")
    if not running:
        return record
    return {**record, "attempts": list(record.get("attempts", []))
            + [{"interrupted": True, "tapmc_version": running.get("tapmc_version")}]}


def _status(record, run_dir):
    """(state, resumes_from): "done" (a DONE.json), "under way" (an attempt, a restart file
    or a log: the step of the latest whole restart, where it resumes, "" when none) or "not
    started". A done run whose taps.dat stops short of its last tap, and a run the manifest
    records attempts of whose folder is gone, are damaged: QuestionError (they read "done" and
    "under way")."""
    if (run_dir / "DONE.json").is_file():
        taps_table(run_dir / "taps.dat")  # whole, to the run's last tap
        return "done", ""
    if not run_dir.is_dir() and record.get("attempts"):
        raise QuestionError(f"{run_dir}: no such folder, but the campaign's manifest records "
                            f"{len(record['attempts'])} attempt(s) of the run (moved or "
                            "deleted?)")
    step = resume_restart(run_dir)[0] if run_dir.is_dir() else None
    if step is not None or record.get("attempts") or (run_dir / "log.lammps").is_file():
        return "under way", "" if step is None else str(step)
    return "not started", ""


def _rule_hours(record, resumes_from, rule):
    """(CPU h of the whole run, CPU h from its resume point) by the cost rule, times its
    ranks; ("", "") when the rule cannot price it (no rule, a setting it has not measured)."""
    if rule is None:
        return "", ""
    try:
        seconds = cost.tap_seconds(cost.run_spec_like(record), rule) * int(record.get("nprocs", 1)) / 3600.0
    except (cost.CostError, KeyError, ValueError, TypeError):
        return "", ""
    start = int(resumes_from) if resumes_from else 0
    return f"{seconds.sum():.4g}", f"{seconds[start:].sum():.4g}"


def _hours(seconds):
    return "" if seconds is None else f"{seconds / 3600.0:.4g}"


def _row(record, runs, rule):
    record = _with_killed_attempt(record)
    v = record.get("variables", {})
    run_dir = runs / record["name"]
    state, resumes_from = _status(record, run_dir)
    versions, unknown = provenance.attempt_versions(record)
    costs = provenance.attempt_costs(record)
    whole, left = _rule_hours(record, resumes_from, rule)
    log_cpu, log_taps = cost.log_cpu_seconds(run_dir) if run_dir.is_dir() else (0.0, 0)
    if state == "done":
        left = "0"
    first, top = _ramp_range(v)
    return [record["name"], record.get("input", ""), v.get("bc", ""), v.get("N", ""),
            v.get("L", ""), v.get("eta", ""), v.get("eps", "") if not top else "", first, top,
            v.get("P", "") if top else "", record.get("taps", ""), record.get("seed", ""),
            record.get("nprocs", 1), state, resumes_from, len(record.get("attempts", [])),
            " ".join(versions), unknown, _hours(costs["cpu_s"]),
            costs.get("attempts_without_cpu_time", 0), _hours(costs["wall_s"]),
            costs.get("attempts_without_wall_time", 0), _hours(log_cpu if log_taps else None),
            log_taps, whole, left]


def analyse(campaign):
    """The rows of campaign_runs.csv: one per run of ``campaign``'s manifest.json, in its
    order; QuestionError when the campaign has no manifest or no run in it."""
    runs = runs_folder(campaign)
    try:
        manifest = provenance.read_manifest(campaign)
    except CampaignDirectoryError as err:
        raise QuestionError(str(err)) from None
    records = [r for r in manifest.get("runs", []) if isinstance(r, dict) and "name" in r]
    if not records:
        raise QuestionError(f"--campaign {campaign}: its manifest.json lists no run (a campaign "
                            "writes it when it starts)")
    try:
        rule = cost.CostRule.from_summary()
    except cost.CostError:
        rule = None  # the rule's columns stay empty; the recorded costs do not need it
    return [_row(r, runs, rule) for r in records]


def measure(args):
    save(args.out / CSV, analyse(args.campaign))


save, load = csv_schema(HEADER)


def _float(text):
    return float(text) if text not in ("", None) else math.nan


def _sum(rows, key):
    return sum(_float(r[key]) for r in rows if r[key] != "")


def _settings_cell(r):
    """eps, or a ramp's sqrt(eps) range with its taps per level."""
    if r["sqrt_eps_top"]:
        return (f"ramp sqrt(eps) {r['sqrt_eps_from']}-{r['sqrt_eps_top']}, "
                f"{r['taps_per_level']} taps per level")
    return f"eps = {_float(r['eps']):g}" if r["eps"] else ""


def _state_cell(r):
    if r["status"] == "under way":
        return (f"under way (resumes from tap {r['resumes_from']})" if r["resumes_from"] else
                "under way (no restart file yet: starts again from tap 0)")
    return r["status"]


def _cost_cell(r):
    """What the attempts recorded, with how many recorded none."""
    if not int(r["attempts"]):
        return ""
    gap = int(r["attempts_without_cpu_time"])
    if r["cpu_h"] == "":
        return "not recorded"
    return f"{_float(r['cpu_h']):.2f}" + (f" (+ {gap} untimed)" if gap else "")


def _log_cell(r):
    """The logs' CPU hours over the taps they ran."""
    return f"{_float(r['log_cpu_h']):.2f} over {r['log_taps']} taps" if r["log_cpu_h"] else ""


def _versions_cell(r):
    known = r["tapmc_versions"].split()
    unknown = int(r["attempts_without_version"])
    return ", ".join(known + ([f"{unknown} unrecorded"] if unknown else []))


def summary(rows):
    """The section's first paragraph: the runs by state, what they recorded, what the cost
    rule gives for the plan and for what is left."""
    states = {s: sum(r["status"] == s for r in rows) for s in STATES}
    attempts = sum(int(r["attempts"]) for r in rows)
    untimed = sum(int(r["attempts_without_cpu_time"]) for r in rows)
    etas = sorted({_float(r["eta"]) for r in rows if r["eta"]}, reverse=True)
    priced = [r for r in rows if r["rule_cpu_h"] != ""]
    rule = (" The cost rule of ``tapmc-paper plan`` prices the plan at "
            f"{_sum(priced, 'rule_cpu_h'):.1f} CPU h and what is left at "
            f"{_sum(priced, 'rule_cpu_h_left'):.1f} CPU h"
            + (f" ({len(rows) - len(priced)} runs it cannot price)" if len(priced) < len(rows)
               else "") + "." if priced else "")
    return (f"The campaign's {len(rows)} runs (its ``manifest.json``; ``{CSV}``): "
            + ", ".join(f"{n} {s}" for s, n in states.items())
            + f"; redeposition thresholds eta = {', '.join(f'{e:g}' for e in etas)}. "
            f"Their {attempts} attempts recorded {_sum(rows, 'cpu_h'):.1f} CPU h and "
            f"{_sum(rows, 'wall_h'):.1f} h of wall time"
            + (f"; {untimed} attempts recorded no CPU time (killed with their campaign, or from "
               "before attempts recorded it), so these are lower bounds" if untimed else "")
            + ". Their LAMMPS logs (each run command's loop time times its CPU use) measure "
            f"{_sum(rows, 'log_cpu_h'):.1f} CPU h over {sum(int(r['log_taps']) for r in rows)} "
            "taps run (taps a resumed attempt ran again count again)."
            + rule + " Each run names the TAPMC versions (commits) its attempts ran; "
            "'unrecorded': attempts from before attempts carried their version.")


def render(path):
    """The appendix section: the summary, then one row per run."""
    rows = load(path)
    if not rows:
        return []
    header = ["run", "eta", "eps or ramp", "taps", "seed", "state", "attempts",
              "CPU h its attempts recorded", "CPU h its logs measured",
              "CPU h by the cost rule", "TAPMC versions"]
    table = [[r["run"], f"{_float(r['eta']):g}" if r["eta"] else "", _settings_cell(r),
              r["taps"], r["seed"], _state_cell(r), r["attempts"], _cost_cell(r), _log_cell(r),
              f"{_float(r['rule_cpu_h']):.2f}" if r["rule_cpu_h"] else "", _versions_cell(r)]
             for r in rows]
    return [summary(rows), ""] + list_table(header, table) + [""]
