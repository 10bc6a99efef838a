# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Run specifications shared by the figure modules, and access to their outputs.

Figures that use the same protocol share runs: a run is named by its protocol, boundary
conditions, excitation and seed only (e.g. ``const_fbc_eps0.05_s3``), so that one campaign
folder serves every figure that needs it and :class:`tapmc.campaign.Campaign` runs it once.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
from collections import defaultdict
from pathlib import Path

import numpy as np

from tapmc._source import source_tree
from tapmc.campaign import CampaignDirectoryError, RunSpec, atomic, verify_finished_run
from tapmc.pores import hist_is_current
from tapmc.readers import TapmcFormatError, read_ave_time, read_fix_print

from .scales import FULL, SCALES, Scale

#: Inputs of the paper's protocols, relative to the repository root.
CONSTANT_EPS = "examples/paper/in.constant_eps"
RAMP = "examples/paper/in.ramp"
AGEING = "examples/paper/in.ageing"
PORE_DUMPS = "examples/paper/in.pore_dumps"

#: Where the repository's layout (doc/, examples/, build/) is read and written by default: the
#: source tree this package is part of; for an installed package (no tree: its prefix must not
#: be written) the current directory, so that `tapmc-paper` run inside a checkout of the data
#: finds it, and elsewhere its defaults name folders of the current directory.
SOURCE_DIR = source_tree() or Path(".")
#: Where the inputs above are: $TAPMC_DATA_DIR when set (the installed tapmc-paper sets it to
#: PREFIX/share/tapmc, which holds examples/), else SOURCE_DIR.
DATA_DIR = Path(os.environ["TAPMC_DATA_DIR"]) if os.environ.get("TAPMC_DATA_DIR") else SOURCE_DIR


def seed_list(seeds):
    """``seeds`` as a list of ints: an int k gives 1..k, an iterable is used as is."""
    if isinstance(seeds, (int, np.integer)):
        if seeds < 1:
            raise ValueError(f"seeds = {seeds}: need at least one seed (an int >= 1 or a list)")
        return list(range(1, int(seeds) + 1))
    out = [int(s) for s in seeds]
    if not out:
        raise ValueError("seeds is empty: give an int >= 1 or a non-empty list of seeds")
    return out


def _input(path):
    return str(DATA_DIR / path)


def _size(scale):
    return {"N": int(scale.N), "L": float(scale.L), "eta": float(scale.eta),
            "rsteps": int(scale.restart_every)}


def eps_tag(eps):
    return f"{float(eps):.6g}"


#: Name tag of the F.B.C. constant-eps runs that start from the paper's packing (section IV.A).
PAPER_START_TAG = "fbcpaper"


def constant_eps_run(scale, bc, eps, seed, taps=None):
    """A constant-eps tapping sequence (in.constant_eps): taps.dat, profiles and packing dumps
    at 0 and the end. F.B.C. runs of a scale with ``fbc_start = 'paper'`` start from the
    paper's packing (``-var fbc_start paper``, section IV.A) and are named
    ``const_fbcpaper_eps..._s...``; runs with the default start keep their variables and names
    (``const_fbc_...``), so campaigns made before the option existed stay valid."""
    taps = int(scale.taps if taps is None else taps)
    variables = dict(_size(scale), eps=float(eps), taps=taps, bc=bc, pevery=taps,
                     dump_ends="yes")
    tag = bc
    if bc == "fbc" and scale.fbc_start == "paper":
        variables["fbc_start"] = "paper"
        tag = PAPER_START_TAG
    return RunSpec(f"const_{tag}_eps{eps_tag(eps)}_s{seed}", _input(CONSTANT_EPS), variables,
                      int(seed))


def fbc_start_of(spec):
    """The F.B.C. start of a constant-eps run: its ``fbc_start`` variable, 'walls' without."""
    return spec.variables.get("fbc_start", "walls")


def ramp_run(scale, bc, seed):
    """The ramp of Fig. 4 (in.ramp): sqrt(eps) up from ``ramp_sqrt0`` by ``ramp_dsqrt`` over
    ``ramp_levels`` levels (beyond (sqrt eps)* ~ 0.15 in every preset), down and up again."""
    variables = dict(_size(scale), bc=bc, sqrt0=float(scale.ramp_sqrt0),
                     dsqrt=float(scale.ramp_dsqrt), nlev=int(scale.ramp_levels),
                     P=int(scale.ramp_taps_per_level))
    return RunSpec(f"ramp_{bc}_s{seed}", _input(RAMP), variables, int(seed))


#: The ramp's branches in the order of in.ramp's branch column (0, 1, 2).
#: the report's folder of figures, their CSVs, report.json and the questions' CSVs, inside
#: the report's output folder (doc/validation, doc/paper_scale/validation)
FIG_DIR = "validation"

RAMP_BRANCHES = ("up1", "down", "up2")
#: (marker, legend words) of each branch of the ramp beyond (sqrt eps)* (Figs. 4 and 6).
RAMP_BRANCH_STYLE = {"up1": ("o", "increase"), "down": ("^", "decrease"),
                     "up2": ("v", "increase again")}

#: Name prefix of the ramp that stays below (sqrt eps)* (Fig. 4, section III.B).
RAMP_BELOW_PREFIX = "ramplow_"


def ramp_below_run(scale, bc, seed):
    """The second ramp of Fig. 4 (in.ramp, section III.B): the same sqrt0, step and taps per
    level, but up only to ``scale.ramp_below_top`` < (sqrt eps)* ~ 0.15, down and up again;
    named ``ramplow_<bc>_s<seed>`` (``select(campaign, 'ramp_')`` does not see it)."""
    variables = dict(_size(scale), bc=bc, sqrt0=float(scale.ramp_sqrt0),
                     dsqrt=float(scale.ramp_dsqrt), nlev=int(scale.ramp_below_levels),
                     P=int(scale.ramp_taps_per_level))
    return RunSpec(f"{RAMP_BELOW_PREFIX}{bc}_s{seed}", _input(RAMP), variables, int(seed))


#: Name prefix of the ramp that turns at the first level beyond (sqrt eps)* (section III.B).
RAMP_NEAR_PREFIX = "rampnear_"


def ramp_near_run(scale, bc, seed):
    """The ramp that turns just beyond (sqrt eps)* (in.ramp, section III.B): the same sqrt0,
    step and taps per level, up to the first level above 0.15 (``scale.ramp_near_levels``),
    down and up again; named ``rampnear_<bc>_s<seed>``. With the ramp below (sqrt eps)* it
    locates the separation of the two behaviours within one step; with the same seed its
    first increase is the ramp beyond's first levels, tap for tap."""
    variables = dict(_size(scale), bc=bc, sqrt0=float(scale.ramp_sqrt0),
                     dsqrt=float(scale.ramp_dsqrt), nlev=int(scale.ramp_near_levels),
                     P=int(scale.ramp_taps_per_level))
    return RunSpec(f"{RAMP_NEAR_PREFIX}{bc}_s{seed}", _input(RAMP), variables, int(seed))


#: Name prefix of the ramps at the paper's own protocol (section III.B: 4000 taps per level),
#: apart from the campaign's 1000-tap ramps (``ramp_``, ``ramplow_``, ``rampnear_``) so that
#: no figure mixes the two protocols: ``paperramp<top>_<bc>[_eta<eta>]_s<seed>``.
PAPER_RAMP_PREFIX = "paperramp"


def paper_ramp_run(scale, bc, seed, top, eta=None):
    """A ramp of Fig. 4 (in.ramp) at ``scale.ramp_taps_per_level`` taps per level that turns
    at sqrt(eps) = ``top`` (a level of the ramp's grid from ``ramp_sqrt0`` by ``ramp_dsqrt``),
    down and up again, at the redeposition threshold ``eta`` (default: the scale's, and then
    no eta in the name)."""
    levels = (top - scale.ramp_sqrt0) / scale.ramp_dsqrt
    if abs(levels - round(levels)) > 1e-9 or round(levels) < 0:
        raise ValueError(f"top = {top!r}: must be ramp_sqrt0 + k ramp_dsqrt (k >= 0) = "
                         f"{scale.ramp_sqrt0} + k {scale.ramp_dsqrt}")
    size = _size(scale if eta is None else scale.replace(eta=float(eta)))
    variables = dict(size, bc=bc, sqrt0=float(scale.ramp_sqrt0), dsqrt=float(scale.ramp_dsqrt),
                     nlev=int(round(levels)) + 1, P=int(scale.ramp_taps_per_level))
    eta_tag = "" if eta is None else f"_eta{float(eta):g}"
    return RunSpec(f"{PAPER_RAMP_PREFIX}{float(top):g}_{bc}{eta_tag}_s{seed}", _input(RAMP),
                      variables, int(seed))


#: Name prefix of the constant-eps runs at another redeposition threshold than the scale's,
#: apart from ``const_`` so that no figure mixes thresholds: ``consteta_<bc>_eps<eps>_eta<eta>_s<seed>``.
CONSTANT_ETA_PREFIX = "consteta_"


def constant_eps_eta_run(scale, bc, eps, seed, eta):
    """The constant-eps run of :func:`constant_eps_run` at the threshold ``eta``."""
    spec = constant_eps_run(scale.replace(eta=float(eta)), bc, eps, seed)
    return RunSpec(f"{CONSTANT_ETA_PREFIX}{bc}_eps{eps_tag(eps)}_eta{float(eta):g}_s{seed}",
                      spec.input, spec.variables, int(seed))


def ageing_run(scale, bc, eps, seed, taps=None):
    taps = int(scale.ageing_taps if taps is None else taps)
    variables = dict(_size(scale), eps=float(eps), taps=taps, bc=bc)
    return RunSpec(f"ageing_{bc}_eps{eps_tag(eps)}_s{seed}", _input(AGEING), variables,
                      int(seed))


def pore_run(scale, bc, eps, seed, dump_times, taps=None, kind="pores"):
    times = sorted(int(t) for t in dump_times if int(t) > 0)
    taps = int(times[-1] if taps is None else taps)
    variables = dict(_size(scale), eps=float(eps), taps=taps, bc=bc,
                     dump_times=times)
    return RunSpec(f"{kind}_{bc}_eps{eps_tag(eps)}_t{taps}_s{seed}", _input(PORE_DUMPS),
                      variables, int(seed))


def select(campaign, prefix, **match):
    """The campaign's runs whose name starts with ``prefix`` and whose variables equal
    ``match`` (floats compared to 1e-9 relative)."""
    out = []
    for spec in campaign.runs:
        if not spec.name.startswith(prefix):
            continue
        ok = True
        for key, value in match.items():
            have = spec.variables.get(key)
            if isinstance(value, float):
                ok = have is not None and abs(float(have) - value) <= 1e-9 * max(1.0, abs(value))
            else:
                ok = have == value
            if not ok:
                break
        if ok:
            out.append(spec)
    return out


def by_variable(specs, key):
    """Group specs by ``spec.variables[key]`` -> dict value -> specs sorted by seed."""
    groups = defaultdict(list)
    for spec in specs:
        groups[spec.variables[key]].append(spec)
    return {k: sorted(v, key=lambda s: s.seed) for k, v in sorted(groups.items())}


def constant_eps_groups(campaign, bc, eps_values=None):
    """The campaign's constant-eps runs with boundary ``bc``, grouped by eps (dict eps -> specs
    sorted by seed), restricted to ``eps_values`` when given (1e-9 relative); raises ValueError
    when none is left."""
    specs = select(campaign, "const_", bc=bc)
    starts = sorted({fbc_start_of(s) for s in specs})
    if len(starts) > 1:
        raise ValueError(f"campaign {campaign.directory}: its constant-eps {bc} runs mix the "
                         f"F.B.C. starts {', '.join(starts)}; draw each from a campaign of one "
                         "start (Scale.fbc_start)")
    groups = by_variable(specs, "eps")
    if eps_values is not None:
        groups = {e: g for e, g in groups.items()
                  if any(abs(e - v) <= 1e-9 * v for v in eps_values)}
    if not groups:
        raise ValueError(f"campaign {campaign.directory} has no constant-eps {bc} run")
    return groups


def run_dir(campaign, spec):
    return Path(campaign.result(spec.name))


def check_finished_runs(campaign):
    """Check every finished run of ``campaign`` against its DONE.json before anything reads
    it (:func:`tapmc.campaign.verify_finished_run`): what draws from a campaign without
    running it (``report --finished-only``, the questions) calls this first. Raises
    CampaignDirectoryError (a DONE.json missing, cut or incomplete) or CampaignError (an
    output changed since the run finished), naming the file and what is wrong."""
    for spec in campaign.runs:
        if campaign.is_done(spec.name):
            verify_finished_run(campaign.run_dir(spec.name), spec)


def taps_table(campaign, spec):
    """The per-tap table (``taps.dat``) of a run: ``Table`` with named columns. A file cut
    short raises TapmcFormatError naming it and its line (:func:`_check_not_cut_short`)."""
    path = run_dir(campaign, spec) / spec.taps_file
    table = read_fix_print(path)
    _check_not_cut_short(path, table, spec)
    return table


def run_taps(path, columns):
    """The per-tap columns of a run's taps.dat, in the order of ``columns`` (names of its
    title line), as float arrays from tap 1 on (the step-0 row left out), each step once with
    its last print (a run resumed from a restart prints the taps after it again); a file with
    its title and no tap yet (a run just started) gives empty arrays. A damaged file raises
    TapmcFormatError naming it: a non-numeric field (at its line), a missing column, a value
    that is not finite (at its step), or a finished run's file (a DONE.json beside it naming
    the run's taps) that stops before its last tap."""
    path = Path(path)
    planned = finished_taps(path.parent)
    if not _has_data_line(path):
        if planned:
            raise TapmcFormatError(path, None, f"cut short: no tap, but its run finished "
                                   f"{planned:g} taps ({DONE_FILE})")
        return [np.empty(0) for _ in columns]
    table = read_fix_print(path, repeats="last")
    last = float(table["step"][-1]) if "step" in table else 0.0
    require_last_tap(path, last, planned)
    missing = [c for c in ("step", *columns) if c not in table]
    if missing:
        raise TapmcFormatError(path, None, f"no column {', '.join(missing)} in its title line "
                               f"(columns: {' '.join(table.columns)})")
    after = table["step"] > 0
    out = [np.asarray(table[c][after], dtype=float) for c in columns]
    for name, values in zip(columns, out):
        bad = np.flatnonzero(~np.isfinite(values))
        if bad.size:
            step = table["step"][after][bad[0]]
            raise TapmcFormatError(path, None, f"{name} = {values[bad[0]]} at step {step:g} "
                                   "(every value must be finite)")
    return out


#: The record a campaign writes into a run's folder when the run has finished.
DONE_FILE = "DONE.json"


def finished_taps(run_dir):
    """The taps of a finished run (its DONE.json's run record), or None: no DONE.json, or one
    that does not say (an older record). A DONE.json that is not JSON raises TapmcFormatError."""
    done = Path(run_dir) / DONE_FILE
    if not done.is_file():
        return None
    try:
        record = json.loads(done.read_text() or "{}")
    except ValueError as err:
        raise TapmcFormatError(done, None, f"not JSON ({err})") from None
    taps = (record.get("run") or {}).get("taps") if isinstance(record, dict) else None
    return float(taps) if isinstance(taps, (int, float)) and not isinstance(taps, bool) else None


def require_last_tap(path, last_step, planned):
    """TapmcFormatError naming ``path`` when a finished run's per-tap file ends at
    ``last_step``, before its ``planned`` taps (:func:`finished_taps`; None: nothing to
    check)."""
    if planned and last_step < planned:
        raise TapmcFormatError(path, None, f"cut short: it ends at step {last_step:g}, before "
                               f"the last tap {planned:g} of its finished run ({DONE_FILE})")


def _has_data_line(path):
    """Whether a text file has a line that is neither blank nor a '#' comment."""
    with open(path, errors="replace") as handle:
        return any(line.strip() and not line.startswith("#") for line in handle)


def _check_not_cut_short(path, table, spec):
    """Refuse a per-tap file cut short: a last line without its end-of-line (which
    read_fix_print leaves out, as in a killed run), or, in a finished run's folder (with its
    DONE.json, which the campaign writes only when the file reaches the last tap), a last
    step before the run's last tap."""
    data = Path(path).read_bytes()
    complete_lines = data.count(b"\n")
    if data and not data.endswith(b"\n"):
        raise TapmcFormatError(path, complete_lines + 1, "cut short: the last line has no "
                               "end-of-line (a finished run's per-tap file ends with a "
                               "complete row)")
    last = float(table.data[-1, 0])
    finished = (Path(path).parent / DONE_FILE).is_file()
    if finished and spec.taps is not None and last < spec.taps:
        raise TapmcFormatError(path, complete_lines, f"cut short: ends at step {last:g}, "
                               f"before the last tap {spec.taps} of the run {spec.name!r}")


def ramp_sqrt_eps(table):
    """sqrt(eps) per row of a ramp's taps table (in.ramp: columns step, level, sqrt_eps).
    A run resumed from a restart file that does not hold fix tapdilate's latest eps (files of
    TAPMC before it kept it) prints 0 in the row of the restart step, before its first tap:
    such a row (0 after step 0, in a level whose other rows are not 0) takes the value of its
    level's other rows."""
    sq = np.array(table["sqrt_eps"], dtype=float)
    steps = np.asarray(table["step"], dtype=float)
    levels = np.asarray(table["level"], dtype=float)
    resumed = (sq == 0.0) & (steps > 0)
    for i in np.flatnonzero(resumed):
        same = (levels == levels[i]) & ~resumed
        if same.any():
            sq[i] = float(np.median(sq[same]))
    return sq


def ramp_level(level, nlev, sqrt0, dsqrt):
    """(branch, sqrt(eps)) of level ``level`` (0 .. 3 nlev - 3) of in.ramp: branch 0 up the
    first nlev levels, 1 down to sqrt0, 2 up again; sqrt(eps) = sqrt0 + dsqrt * rung, the rung
    k, 2m - k, k - 2m on the three branches (m = nlev - 1), as in.ramp computes it."""
    m = int(nlev) - 1
    k = int(level)
    if not 0 <= k <= 3 * m:
        raise ValueError(f"level = {level!r}: allowed levels are 0 .. {3 * m} (nlev = {nlev})")
    branch = int(k > m) + int(k > 2 * m)
    rung = (k, 2 * m - k, k - 2 * m)[branch]
    return branch, float(sqrt0) + float(dsqrt) * rung


def profile(campaign, spec, name):
    """A vector-mode profile file (``profile_z.dat`` or ``profile_x.dat``) of a run."""
    return read_ave_time(run_dir(campaign, spec) / name)


def pores_available():
    """Whether :func:`pores_executable` finds tapmc-pores (Figs. 9 and 10 need it)."""
    try:
        pores_executable()
        return True
    except FileNotFoundError:
        return False


def pores_executable():
    """The tapmc-pores program: $TAPMC_PORES, else $TAPMC_BUILD_DIR/tools/pores/tapmc-pores,
    else build/tools/pores/tapmc-pores of the source tree, else tapmc-pores on PATH."""
    candidates = []
    if os.environ.get("TAPMC_PORES"):
        candidates.append(Path(os.environ["TAPMC_PORES"]))
    if os.environ.get("TAPMC_BUILD_DIR"):
        candidates.append(Path(os.environ["TAPMC_BUILD_DIR"]) / "tools/pores/tapmc-pores")
    if source_tree() is not None:  # an installed package looks on the PATH, as find_lmp does
        candidates.append(source_tree() / "build/tools/pores/tapmc-pores")
    for path in candidates:
        if path.is_file() and os.access(path, os.X_OK):
            return str(path)
    found = shutil.which("tapmc-pores")
    if found:
        return found
    raise FileNotFoundError(
        "tapmc-pores not found: build it (cmake -DTAPMC_BUILD_PORES=ON) or set TAPMC_PORES "
        "to its path; looked in " + ", ".join(str(c) for c in candidates))


class PoresFailed(RuntimeError):
    """tapmc-pores ended with an error (its command line and message): a failed run, exit 1
    of the command that ran it."""


def run_pores(dumps, prefix, args):
    """Run tapmc-pores on ``dumps`` with output prefix ``prefix`` unless its outputs are newer
    than the dumps and have the present columns (figures are redrawn cheaply; an output of an
    older tool, whose rho_v was the number density of v, is made again); returns the prefix
    as a Path."""
    prefix = Path(prefix)
    hist = Path(str(prefix) + ".hist.csv")
    newest = max(Path(d).stat().st_mtime for d in dumps)
    if hist.exists() and hist.stat().st_mtime >= newest and hist_is_current(hist):
        return prefix
    cmd = [pores_executable(), *args, "-o", str(prefix), *map(str, dumps)]
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if proc.returncode != 0:
        raise PoresFailed(f"{' '.join(cmd)} failed ({proc.returncode}): {proc.stderr.strip()}")
    return prefix


#: file of a campaign folder that records the Scale the campaign was built with.
SCALE_FILE = "scale.json"


def write_scale(directory, scale):
    """Record ``scale`` in the campaign folder (see :func:`campaign_scale`)."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    atomic.write_text(directory / SCALE_FILE, json.dumps(scale.as_dict(), indent=1) + "\n")


def recorded_scale(directory):
    """The Scale recorded in a campaign folder (``scale.json``; fields added to Scale since it
    was written take their defaults, what the code that wrote it used), or None when the
    folder records none. A file that is no Scale record raises CampaignDirectoryError."""
    path = Path(directory) / SCALE_FILE
    if not path.exists():
        return None
    try:
        recorded = json.loads(path.read_text())
    except OSError as err:
        raise CampaignDirectoryError(f"{path}: cannot be read ({err.strerror})") from None
    except ValueError as err:
        raise CampaignDirectoryError(f"{path}: not valid JSON ({err})") from None
    if not isinstance(recorded, dict):
        raise CampaignDirectoryError(f"{path}: not a Scale record (expected a JSON object)")
    try:
        return Scale(**recorded)
    except (TypeError, ValueError) as err:
        raise CampaignDirectoryError(f"{path}: not a Scale record of this TAPMC ({err})") from None


def check_scale(directory, scale):
    """Raise :class:`tapmc.campaign.CampaignDirectoryError` when the campaign folder records
    (``scale.json``) another Scale than ``scale``: its runs, and the figures drawn from them
    (:func:`campaign_scale`), belong to the recorded one. Every field counts, so a preset
    edited since the campaign started is refused too. A folder without the file passes."""
    found = recorded_scale(directory)
    if found is None:
        return
    path = Path(directory) / SCALE_FILE
    recorded = json.loads(json.dumps(found.as_dict()))
    asked = json.loads(json.dumps(scale.as_dict()))
    differ = [k for k in asked if recorded.get(k) != asked[k]]
    if not differ:
        return
    name = recorded.get("name")
    shown = [f"{k} = {recorded.get(k)!r} instead of {asked[k]!r}" for k in differ
             if k != "name"]
    shown = ", ".join(shown[:3]) + (", ..." if len(shown) > 3 else "")
    if name != scale.name:
        hint = f"--{name} or another --campaign" if name in SCALES else "another --campaign"
        raise CampaignDirectoryError(f"campaign {Path(directory)}: made with Scale {name!r}, "
                                     f"not the {scale.name!r} asked for ({path}: {shown}); "
                                     f"use {hint}")
    if differ == ["fbc_start"]:  # the option, not the version, differs
        raise CampaignDirectoryError(f"campaign {Path(directory)}: made with --fbc-start "
                                     f"{recorded.get('fbc_start')}, not "
                                     f"{asked['fbc_start']} ({path}); use --fbc-start "
                                     f"{recorded.get('fbc_start')} or another --campaign")
    raise CampaignDirectoryError(f"campaign {Path(directory)}: made with another Scale "
                                 f"{name!r} than this TAPMC's ({path}: {shown}); use another "
                                 "--campaign")


def folder_scale(directory):
    """The Scale a campaign folder records (:func:`recorded_scale`), the full preset when it
    records none (the committed campaign's): what a figure drawn from the folder states."""
    return recorded_scale(directory) or FULL


def campaign_scale(campaign):
    """The Scale of a campaign: the one recorded in its folder (:func:`recorded_scale`),
    else the preset of ``tapmc.paper.scales`` that its runs match, else None (the runs
    themselves do not record the scale)."""
    found = recorded_scale(campaign.directory)
    return found if found is not None else matching_scale(campaign.runs)


def matching_scale(specs):
    """The preset of ``tapmc.paper.scales`` whose N, L and eta are those of ``specs`` (the
    runs do not record their scale), or None."""
    for scale in SCALES.values():
        if all(int(s.variables.get("N", -1)) == scale.N
               and float(s.variables.get("L", -1)) == float(scale.L)
               and float(s.variables.get("eta", -1)) == float(scale.eta) for s in specs):
            return scale
    return None
