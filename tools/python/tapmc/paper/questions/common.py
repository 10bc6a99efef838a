# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""What the questions share: their folders, their error, the CSV files they write and read
(written whole or not at all), and the campaign's finished runs they re-analyse.

Every question module owns its CSV schema (the header it writes and the columns it reads);
this module only moves rows in and out of files, so that a mistyped path or an empty
campaign never replaces a committed result with an empty or partial one."""

from __future__ import annotations

import csv
import json
import os
import tempfile
from pathlib import Path

from tapmc.readers import TapmcFormatError, read_fix_print

from .. import _runs

#: Where the committed page reads the questions' CSVs (the report's validation/questions/).
DEFAULT_OUT = _runs.SOURCE_DIR / "doc" / "paper_scale" / "validation" / "questions"
#: The paper-scale campaign whose finished runs the re-analyses read.
DEFAULT_CAMPAIGN = _runs.SOURCE_DIR / "doc" / "validation" / "data" / "full"
#: The run of that campaign at eps = 0.0225 (Fig. 9's), whose restart.4000 starts the
#: noise-floor and p0-configs measurements.
CAMPAIGN_RUN = DEFAULT_CAMPAIGN / "runs" / "const_pbc_eps0.0225_s1"
#: Sub-folder of --out where the measurements keep their runs until they are complete.
PARTIAL = "partial"
#: The paper's scale (section II): N spheres in a box of side L (in R).
PAPER = {"N": 4096, "L": 32}


class QuestionError(RuntimeError):
    """A question that cannot run: a usage error, a path that cannot be used or a damaged
    input (a file and what is wrong with it). The command prints it on one line and exits 2,
    the convention of both TAPMC tools; nothing is written."""


class QuestionRunError(QuestionError):
    """A question whose runs failed (a LAMMPS run, the fluid Monte Carlo, the pore tool or its
    compilation) or whose campaign folder is in use: exit 1; nothing is written."""


def require_steady_window(run_dir, taps, window):
    """QuestionError when a run of ``taps`` taps is shorter than the steady window ``window`` a
    question reads (the paper's last 1000 of 4000 taps): a quick or medium campaign's runs."""
    if taps < window:
        raise QuestionError(f"{run_dir}: {taps} taps, fewer than the {window}-tap steady window "
                            "this question reads (the paper's last 1000 of 4000 taps); ask it of "
                            "a campaign at the paper's scale (--full)")


def work_folder(args, name):
    """The folder of a question's runs: --work when given, else <out>/partial/<name>."""
    work = getattr(args, "work", None)
    return Path(work) if work else Path(args.out) / PARTIAL / name


def write_csv(path, header, rows, allow_empty=False):
    """Write ``rows`` under ``header`` to ``path`` through a temporary file renamed into place
    when complete: a killed process leaves the old file. No rows (unless ``allow_empty``):
    QuestionError, the old file kept (an empty campaign must not replace a result)."""
    rows = list(rows)
    path = Path(path)
    if not rows and not allow_empty:
        raise QuestionError(f"{path}: nothing to write (no rows measured); the file is left as "
                            "it was")
    path.parent.mkdir(parents=True, exist_ok=True)
    handle, partial = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".part")
    try:
        with os.fdopen(handle, "w", newline="") as out:
            writer = csv.writer(out)
            writer.writerow(header)
            writer.writerows(rows)
        os.replace(partial, path)
    except BaseException:
        Path(partial).unlink(missing_ok=True)
        raise
    print(f"wrote {path}")
    return path


def read_csv(path):
    """The rows of a question's CSV as dicts (its header names the columns); a row with another
    number of fields than the header (a file cut mid-row) raises QuestionError at its line."""
    with open(path, newline="") as handle:
        reader = csv.DictReader(handle)
        rows = []
        for row in reader:
            extra = row.pop(None, None) or []           # fields beyond the header's
            missing = [k for k, v in row.items() if v is None]
            if extra or missing:
                width = len(reader.fieldnames)
                raise QuestionError(f"{path}:{reader.line_num}: {width - len(missing) + len(extra)}"
                                    f" fields, the header has {width}")
            rows.append(row)
        return rows


def csv_schema(header):
    """The ``save(path, rows)`` and ``load(path)`` of a question's CSV of columns ``header``:
    its one schema, written whole (:func:`write_csv`) and read back as dicts (:func:`read_csv`)."""
    def save(path, rows):
        return write_csv(path, header, rows)
    return save, read_csv


def runs_folder(campaign):
    """<campaign>/runs, or QuestionError naming the path when ``campaign`` is no campaign."""
    campaign = Path(campaign)
    if not campaign.exists():
        raise QuestionError(f"--campaign {campaign}: no such folder")
    if not campaign.is_dir():
        raise QuestionError(f"--campaign {campaign}: not a folder")
    runs = campaign / "runs"
    if not runs.is_dir():
        raise QuestionError(f"--campaign {campaign}: no runs/ folder (not a campaign)")
    return runs


def finished_runs(campaign, pattern):
    """The finished run folders (with a DONE.json) of ``campaign`` whose names match the glob
    ``pattern``, sorted; QuestionError when there is none (nothing to analyse)."""
    runs = [d for d in sorted(runs_folder(campaign).glob(pattern))
            if (d / "DONE.json").is_file()]
    if not runs:
        raise QuestionError(f"--campaign {campaign}: no finished run matches runs/{pattern} "
                            "(a finished run has a DONE.json)")
    return runs


def taps_table(path):
    """The taps.dat of a run (tapmc.readers.read_fix_print, every row as printed: a resumed
    continuation prints its restart step again, :func:`last_rows` picks the last print),
    QuestionError naming the file (and line) when it is missing or damaged."""
    try:
        table = read_fix_print(path, repeats="all")
    except FileNotFoundError:
        raise QuestionError(f"{path}: no such file") from None
    except TapmcFormatError as err:
        raise QuestionError(str(err)) from None
    if "step" not in table.columns:
        raise QuestionError(f"{path}: no '# step ...' title line with one name per field (its "
                            f"rows have {len(table.columns)} fields)")
    _require_whole_run(path, table)
    return table


def _require_whole_run(path, table):
    """A finished run's taps.dat (its folder holds a DONE.json naming the run's taps) must
    reach the last tap: a file cut short (a copy, a disk full) would otherwise be analysed
    as a shorter run, its steady state from the wrong taps."""
    last = float(table["step"][-1]) if len(table) else 0.0
    try:
        _runs.require_last_tap(path, last, _runs.finished_taps(Path(path).parent))
    except TapmcFormatError as err:
        raise QuestionError(str(err)) from None


def last_rows(table):
    """dict step -> row index of the last row printed for each step of a taps table: a
    resumed run prints the steps after its restart again, and the last print is the one of
    the run that continued."""
    return {int(step): k for k, step in enumerate(table["step"])}


def run_radius(run_dir):
    """The sphere radius R a finished run ran with (its DONE.json's variables; 0.5, the
    inputs' default, when it sets none)."""
    path = Path(run_dir) / "DONE.json"
    try:
        done = json.loads(path.read_text() or "{}")
    except ValueError as err:
        raise QuestionError(f"{path}: not JSON ({err})") from None
    return float(done.get("run", {}).get("variables", {}).get("R", 0.5))


def seed_groups(campaign):
    """dict group -> [(seed, run folder)] of the finished constant-eps and ageing runs
    (``<kind>_<bc>_eps<eps>_s<seed>``, P.B.C. and F.B.C.) with at least two seeds;
    QuestionError when there is no such group."""
    groups = {}
    for run_dir in finished_runs(campaign, "*_eps*_s*"):
        if not run_dir.name.startswith(("const_", "ageing_")):
            continue
        group, seed = run_dir.name.rsplit("_s", 1)
        groups.setdefault(group, []).append((int(seed), run_dir))
    groups = {g: sorted(runs) for g, runs in groups.items() if len(runs) >= 2}
    if not groups:
        raise QuestionError(f"--campaign {campaign}: no group of finished runs that differ only "
                            "in their seed (const_* or ageing_*, two seeds or more)")
    return groups


def eps_of(name):
    """eps of a run named ``<kind>_<bc>_eps<eps>_s<seed>``."""
    return float(name.split("_eps")[1].split("_s")[0])
