# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The files of the front, each read and written here only: ``runs.csv`` (one row per finished
run: its setting, seed and cost), ``taps/<N_eps>/<setting>_s<seed>.dat.gz`` (the run's per-tap
table, read through :func:`tapmc.readers.read_fix_print`) and ``meta.json`` (what built the
binary and where it ran).

Every reader checks what it reads and raises :class:`FrontDataError` naming the file (and the
line) and what is wrong; every writer writes a temporary file and renames it when complete, so
that a kill or an error never leaves a committed file empty or cut short.
"""

import csv
import json
import os
from dataclasses import dataclass

from ...readers import TapmcFormatError, read_fix_print
from .settings import SETTINGS

#: where ``tapmc-paper front run`` writes (relative to the repository) and the page reads
DATA_DIR = os.path.join("doc", "validation", "front")
RUNS_CSV = "runs.csv"
META = "meta.json"
#: the columns of runs.csv, in their order
RUN_FIELDS = ["setting", "N", "eps", "seed", "taps", "eta", "settle_keys", "cpu_s", "wall_s",
              "cpu_per_tap", "sweeps_per_tap", "capped_taps"]
#: the keys of meta.json the page states
META_KEYS = ("commit", "machine", "cores", "jobs", "nice", "started")
#: the taps.dat columns the front reads (the title line of examples/paper/in.constant_eps's
#: fix print names them)
TAPS_READ = ("step", "phi_b", "phi_c", "Z", "sweeps", "capped")


class FrontDataError(ValueError):
    """A file of the front that cannot be used; the message reads ``FILE[:LINE]: what``."""

    def __init__(self, path, line, what):
        where = f"{path}:{line}" if line is not None else f"{path}"
        super().__init__(f"{where}: {what}")
        self.path, self.line, self.what = str(path), line, what


@dataclass(frozen=True)
class RunRow:
    """One row of runs.csv: a finished run and its cost (CPU seconds of the lmp process, user
    plus system, for the taps it kept; see :func:`tapmc.paper.front.runs.run_cpu_seconds`)."""
    setting: str
    N: int
    eps: str            # as written, "%g"
    seed: int
    taps: int
    eta: str
    settle_keys: str
    cpu_s: str
    wall_s: str
    cpu_per_tap: str
    sweeps_per_tap: str
    capped_taps: int
    line: int = 0       # its line in runs.csv (0: not read from a file)

    @property
    def key(self):
        """What makes a run: (setting, N, eps, seed, taps)."""
        return (self.setting, self.N, self.eps, self.seed, self.taps)

    def as_csv(self):
        return {f: getattr(self, f) for f in RUN_FIELDS}


_INTEGERS = ("N", "seed", "taps", "capped_taps")
_NUMBERS = ("eps", "cpu_s", "wall_s", "cpu_per_tap", "sweeps_per_tap")


def _run_row(path, line, raw):
    """A RunRow from one csv.DictReader row, or FrontDataError naming the line."""
    extra = raw.pop(None, None) or []
    found = len([v for v in raw.values() if v is not None]) + len(extra)
    if found != len(RUN_FIELDS):
        why = " (a row cut short?)" if found < len(RUN_FIELDS) else ""
        raise FrontDataError(path, line, f"{found} fields, expected {len(RUN_FIELDS)}{why}")
    values = {}
    for field in RUN_FIELDS:
        text = raw[field].strip()
        try:
            if field in _INTEGERS:
                values[field] = int(text)
            else:
                if field in _NUMBERS:
                    float(text)
                values[field] = text
        except ValueError:
            raise FrontDataError(path, line, f"column {field}: {text!r} is not "
                                 f"{'an integer' if field in _INTEGERS else 'a number'}") from None
    if values["setting"] not in SETTINGS:
        raise FrontDataError(path, line, f"setting {values['setting']!r} is not a setting of "
                             f"the front ({', '.join(SETTINGS)})")
    values["eps"] = "%g" % float(values["eps"])
    return RunRow(line=line, **values)


def read_runs(path):
    """The rows of runs.csv as RunRow ([] when the file does not exist)."""
    if not os.path.exists(path):
        return []
    try:
        with open(path, newline="") as f:
            text = f.read()
    except (OSError, UnicodeDecodeError) as err:
        raise FrontDataError(path, None, f"cannot be read ({err})") from None
    if text and not text.endswith("\n"):
        last = text.count("\n") + 1
        raise FrontDataError(path, last, "the last line has no end-of-line: the file was cut "
                             "short (restore it from git, or delete the line to run it again)")
    reader = csv.DictReader(text.splitlines())
    header = reader.fieldnames or []
    missing = [f for f in RUN_FIELDS if f not in header]
    if missing:
        raise FrontDataError(path, 1, f"no column {', '.join(missing)} (the header has "
                             f"{', '.join(header) or 'nothing'}; expected {', '.join(RUN_FIELDS)})")
    rows = [_run_row(path, reader.line_num, raw) for raw in reader]
    seen = {}
    for row in rows:
        if row.key in seen:
            raise FrontDataError(path, row.line, f"the run of line {seen[row.key]} again "
                                 f"({row.setting}, N {row.N}, eps {row.eps}, seed {row.seed})")
        seen[row.key] = row.line
    return rows


def _replace(path, write):
    """Write `path` through a temporary file: `write(f)` fills it, the rename makes it whole."""
    part = f"{path}.part"
    try:
        with open(part, "w", newline="") as f:
            write(f)
        os.replace(part, path)
    finally:
        if os.path.exists(part):
            os.remove(part)


def append_runs(path, rows):
    """Add `rows` (RunRow) to runs.csv: the file is written again whole and renamed, so that a
    kill never leaves a row cut short."""
    old = read_runs(path)

    def write(f):
        w = csv.DictWriter(f, fieldnames=RUN_FIELDS)
        w.writeheader()
        for row in list(old) + list(rows):
            w.writerow(row.as_csv())
    _replace(path, write)


def _slug(name):
    return name.replace(" ", "_").replace("/", "_over_").replace("(", "").replace(")", "") \
        .replace(",", "")


def run_name(setting, N, eps, seed):
    """The name of a run (its campaign run folder): letters, digits and _.+- only."""
    return "N%d_eps%g_%s_s%d" % (N, eps, _slug(setting), seed)


def taps_path(out_dir, name, N, eps, seed):
    """The gzipped taps.dat of one finished run."""
    return os.path.join(out_dir, "taps", "N%d_eps%g" % (N, eps), "%s_s%d.dat.gz" % (_slug(name), seed))


@dataclass(frozen=True)
class TapsTable:
    """The per-tap columns the front reads (lists, taps 1 to the last; step 0 left out)."""
    step: list
    phi_b: list
    phi_c: list
    Z: list
    sweeps: list
    capped: list

    def __len__(self):
        return len(self.step)

    def column(self, name):
        return getattr(self, name)


def read_taps(path, taps=None):
    """The TapsTable of a taps.dat (plain or gzipped); with `taps`, it must hold steps 1 to
    `taps` each once. FrontDataError names the file and what is wrong."""
    try:
        table = read_fix_print(path)
    except TapmcFormatError as err:
        raise FrontDataError(err.path, err.line, err.what) from None
    except OSError as err:
        raise FrontDataError(path, None, f"cannot be read ({err.strerror})") from None
    missing = [c for c in TAPS_READ if c not in table]
    if missing:
        raise FrontDataError(path, None, f"no column {', '.join(missing)} in its title line "
                             f"(columns: {', '.join(table.columns)})")
    keep = table["step"] > 0
    columns = {c: table[c][keep].tolist() for c in TAPS_READ}
    columns["step"] = [int(s) for s in columns["step"]]
    rows = TapsTable(**columns)
    if taps is not None and rows.step != list(range(1, taps + 1)):
        last = rows.step[-1] if rows.step else 0
        raise FrontDataError(path, None, f"{len(rows)} taps (steps 1 to {last}), expected steps "
                             f"1 to {taps} each once: the file is cut short or damaged")
    return rows


def write_meta(out_dir, meta):
    """meta.json of the front (once: an existing one is kept)."""
    path = os.path.join(out_dir, META)
    if os.path.exists(path):
        return path

    def write(f):
        json.dump(meta, f, indent=1, sort_keys=True)
        f.write("\n")
    _replace(path, write)
    return path


def read_meta(data_dir):
    """meta.json of the front as a dict, None when there is none; FrontDataError when it is
    not a JSON object with META_KEYS."""
    path = os.path.join(data_dir, META)
    if not os.path.isfile(path):
        return None
    try:
        with open(path) as f:
            meta = json.load(f)
    except (OSError, ValueError) as err:
        raise FrontDataError(path, None, f"not readable JSON ({err})") from None
    if not isinstance(meta, dict):
        raise FrontDataError(path, None, f"expected a JSON object, found {type(meta).__name__}")
    missing = [k for k in META_KEYS if k not in meta]
    if missing:
        raise FrontDataError(path, None, f"no {', '.join(missing)} (expected the keys "
                             f"{', '.join(META_KEYS)}, as 'tapmc-paper front run' writes them)")
    return meta

