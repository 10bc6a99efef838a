# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Readers for the LAMMPS outputs of a tapping run: log files (thermo of several ``run``
commands), ``fix ave/time`` files (scalar and vector mode), ``fix print`` files and text dumps
(``dump custom`` / ``dump atom``, plain or gzip).

Every malformed file raises :class:`TapmcFormatError` with the file name and, where the fault
sits on one line, its number: an empty or binary file (bytes that are not UTF-8 text), a damaged
gzip stream, a wrong number of fields, a non-numeric field. A last line without its end-of-line
is a write cut short (a job killed while LAMMPS was writing it): logs, ``fix ave/time`` and
``fix print`` files keep the complete lines before it and leave it out, since a number cut
short still parses as a number; in a dump it cuts the last frame short and raises.
"""

import gzip
import os
import re
import tempfile
import zlib
from collections import namedtuple

import numpy as np

__all__ = ["TapmcFormatError", "Table", "Thermo", "Log", "AveTime", "Frame", "Dump",
           "read_log", "read_ave_time", "read_ave_time_blocks", "read_fix_print", "read_dump"]


class TapmcFormatError(ValueError):
    """A file that does not have the expected format; ``path`` and ``line`` (1-based, or None
    for the whole file) say where, the message reads ``FILE:LINE: what``."""

    def __init__(self, path, line, what):
        self.path = str(path)
        self.line = line
        self.what = what
        where = f"{self.path}:{line}" if line is not None else self.path
        super().__init__(f"{where}: {what}")


def _mdanalysis_universe(path):
    """MDAnalysis Universe of a LAMMPS dump, without its import-time and mass-guessing
    warnings (irrelevant here: only positions are used)."""
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        import MDAnalysis
        return MDAnalysis.Universe(path, format="LAMMPSDUMP")


_GZIP_MAGIC = b"\x1f\x8b"
# What a damaged gzip stream raises: BadGzipFile (an OSError) for a bad header, zlib.error for
# corrupt data, EOFError for a stream cut short.
_GZIP_ERRORS = (OSError, EOFError, zlib.error)


def _open_text(path):
    """Open a text file, gzip-compressed or not (detected from the content, not the name)."""
    with open(path, "rb") as probe:
        magic = probe.read(2)
    if magic == _GZIP_MAGIC:
        return gzip.open(path, "rt")
    return open(path, "r")


def _open_bytes(path):
    """Open a file for reading bytes, through gzip when its content starts with gzip's magic."""
    with open(path, "rb") as probe:
        magic = probe.read(2)
    return gzip.open(path, "rb") if magic == _GZIP_MAGIC else open(path, "rb")


def _decode_line(path, lineno, raw):
    """One line of bytes as text; bytes that are not UTF-8 mean a binary file, named here."""
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as err:
        raise TapmcFormatError(path, lineno, f"byte 0x{raw[err.start]:02x} at column "
                               f"{err.start + 1} is not UTF-8 text (a binary file?)") from None


def _read_lines(path):
    """The complete lines of a text file (plain or gzip) without their end-of-line, and whether a
    last line without an end-of-line was left out (see the module's docstring). Lines are split
    at line feeds only, not at the other characters str.splitlines() breaks at (form feed,
    \\x1c, ...), so that line numbers are the ones an editor shows."""
    try:
        with _open_bytes(path) as f:
            data = f.read()
    except _GZIP_ERRORS as err:
        raise TapmcFormatError(path, None, f"damaged gzip file ({err})") from None
    pieces = data.split(b"\n")
    cut_short = pieces[-1].strip() != b""
    lines = []
    for i, raw in enumerate(pieces[:-1]):
        lines.append(_decode_line(path, i + 1, raw[:-1] if raw.endswith(b"\r") else raw))
    return lines, cut_short


def _cut_short_note(cut_short, nlines):
    """Appended to a 'nothing found' message when the only content was a line cut short."""
    return (f" (line {nlines + 1}, the last, has no end-of-line and was left out as cut short)"
            if cut_short else "")


def _floats(path, lineno, fields, expected=None):
    if expected is not None and len(fields) != expected:
        raise TapmcFormatError(path, lineno, f"expected {expected} fields, found {len(fields)}")
    try:
        return [float(f) for f in fields]
    except ValueError:
        bad = next(f for f in fields if not _is_float(f))
        raise TapmcFormatError(path, lineno, f"non-numeric field {bad!r}") from None


def _is_float(text):
    try:
        float(text)
        return True
    except ValueError:
        return False


class Table:
    """Columns of numbers: ``columns`` (names), ``data`` (rows x columns), ``table[name]``
    (one column), ``len(table)`` rows."""

    def __init__(self, columns, data, path=None):
        self.columns = list(columns)
        data = np.asarray(data, dtype=float)
        self.data = data.reshape(-1, len(self.columns)) if data.size == 0 else data
        self.path = path

    def __getitem__(self, name):
        try:
            return self.data[:, self.columns.index(name)]
        except ValueError:
            raise KeyError(f"no column {name!r} in {self.path or 'table'}; "
                           f"columns are {self.columns}") from None

    def __contains__(self, name):
        return name in self.columns

    def __len__(self):
        return self.data.shape[0]

    def __repr__(self):
        return f"<{type(self).__name__} {len(self)} rows x {self.columns}>"


class Thermo(Table):
    """Thermo output of one ``run`` command (``warnings`` printed during that run, ``complete``
    False if the log ends before the run's ``Loop time`` line)."""

    def __init__(self, columns, data, path=None, warnings=(), complete=True):
        super().__init__(columns, data, path)
        self.warnings = list(warnings)
        self.complete = complete


class Log:
    """A LAMMPS log: ``runs`` (one :class:`Thermo` per ``run``), ``warnings`` (every
    ``WARNING`` line of the file, in order), ``thermo`` (all runs concatenated) and
    ``skipped`` (lines left out of the tables by ``read_log(..., strict=False)``)."""

    def __init__(self, runs, warnings, path=None):
        self.runs = runs
        self.warnings = warnings
        self.path = path
        self.skipped = []

    @property
    def thermo(self):
        """All runs as one :class:`Thermo`. Columns are the union over the runs in order of
        appearance (NaN where a run does not print a column). Consecutive runs repeat their
        boundary step (the last row of one run and the first of the next): the two rows are
        merged into one, the earlier run's values winning, so that every step appears once."""
        columns = []
        for run in self.runs:
            columns += [c for c in run.columns if c not in columns]
        rows = []
        steps = []
        has_step = "Step" in columns
        for run in self.runs:
            block = np.full((len(run), len(columns)), np.nan)
            for j, c in enumerate(run.columns):
                block[:, columns.index(c)] = run.data[:, j]
            start = 0
            if has_step and rows and len(run) and "Step" in run.columns \
                    and steps and block[0, columns.index("Step")] == steps[-1]:
                last = rows[-1]
                fill = np.isnan(last)
                last[fill] = block[0, fill]
                start = 1
            for row in block[start:]:
                rows.append(row.copy())
                if has_step:
                    steps.append(row[columns.index("Step")])
        return Thermo(columns, np.array(rows).reshape(-1, len(columns)), self.path,
                      self.warnings, all(r.complete for r in self.runs))


_MEMORY_LINE = re.compile(r"^\s*(Per MPI rank memory|Memory usage per processor)")


def read_log(path, strict=True):
    """Read a LAMMPS log file: the thermo table of every ``run`` (one-line thermo styles: the
    header line follows the "Per MPI rank memory" line, the table ends at ``Loop time``) and
    the ``WARNING`` lines. A log cut during a run (killed job, ``ERROR``) keeps the rows written
    so far and marks that run ``complete = False``.

    A last line without its end-of-line (the job was killed while LAMMPS wrote it) is left
    out: the run keeps its complete rows.

    A table row with a non-numeric field raises :class:`TapmcFormatError`. Other lines inside a
    table (a wrong number of fields, text) raise it too when ``strict``; with ``strict=False``
    they are skipped and listed in ``Log.skipped`` as (line number, text), for logs where
    ``fix print`` or ``print`` also write to the screen during runs. An empty or binary file
    raises it as well."""
    runs, warnings, skipped = [], [], []
    lines, cut_short = _read_lines(path)
    i = 0
    n = len(lines)
    while i < n:
        line = lines[i]
        if line.startswith("WARNING"):
            warnings.append(line.strip())
        if _MEMORY_LINE.match(line) and i + 1 < n:
            header = lines[i + 1].split()
            if not header:
                raise TapmcFormatError(path, i + 2, "empty thermo header line")
            if header[0].startswith("---"):
                raise TapmcFormatError(path, i + 2, "multi-line thermo output (thermo_modify "
                                       "line multi) is not supported: use one-line thermo")
            i += 2
            rows, run_warnings, complete = [], [], False
            while i < n:
                text = lines[i]
                fields = text.split()
                if text.startswith("Loop time"):
                    complete = True
                    break
                if text.startswith("ERROR"):
                    break  # the run stopped with an error: keep its rows, not complete
                if text.startswith("WARNING"):
                    warnings.append(text.strip())
                    run_warnings.append(text.strip())
                elif fields == header:
                    pass  # header repeated (thermo_modify line yes / multi-line styles)
                elif len(fields) == len(header) and _is_float(fields[0]):
                    rows.append(_floats(path, i + 1, fields, len(header)))
                elif fields and strict:
                    what = (f"expected {len(header)} fields, found {len(fields)}"
                            if _is_float(fields[0]) else "unexpected text")
                    raise TapmcFormatError(path, i + 1,
                                           f"{what} in the thermo table of run {len(runs) + 1}: "
                                           f"{text.strip()[:60]!r} (other output during the "
                                           "run? read_log(path, strict=False) skips it)")
                elif fields:
                    skipped.append((i + 1, text))
                i += 1
            runs.append(Thermo(header, np.array(rows).reshape(-1, len(header)), path,
                               run_warnings, complete))
        i += 1
    if not runs:
        what = "empty file" if not lines and not cut_short else \
            "no thermo table found (no 'run' in this log?)"
        raise TapmcFormatError(path, None, what + _cut_short_note(cut_short, len(lines)))
    log = Log(runs, warnings, path)
    log.skipped = skipped
    return log


class AveTime(Table):
    """A ``fix ave/time`` file. Scalar mode: ``columns`` (first ``TimeStep``), ``data``,
    ``table[name]`` (one value per time), ``steps``. Vector mode (``vector`` True): ``steps``
    (n_t,), ``columns`` (the value columns after ``Row``), ``blocks`` (n_t, n_rows, n_cols) and
    ``table[name]`` of shape (n_t, n_rows)."""

    def __init__(self, columns, data=None, steps=None, blocks=None, path=None):
        self.vector = blocks is not None
        if self.vector:
            self.columns = list(columns)
            self.steps = np.asarray(steps, dtype=float)
            self.blocks = np.asarray(blocks, dtype=float)
            self.data = self.blocks.reshape(-1, len(self.columns))
            self.path = path
        else:
            super().__init__(columns, data, path)
            self.steps = self.data[:, 0]
            self.blocks = None

    def __getitem__(self, name):
        if not self.vector:
            return super().__getitem__(name)
        try:
            return self.blocks[:, :, self.columns.index(name)]
        except ValueError:
            raise KeyError(f"no column {name!r} in {self.path}; columns are "
                           f"{self.columns}") from None

    def __len__(self):
        return len(self.steps)


def _parse_ave_time(path, killed=False):
    """The one parser of ``fix ave/time`` files, behind :func:`read_ave_time` and
    :func:`read_ave_time_blocks`. Returns (lines, number of header lines, column names, vector
    mode?, blocks); a block is (step, line numbers (1-based) of its lines, values): one row in
    scalar mode (values: the row), a ``TimeStep Number-of-rows`` line and its rows in vector mode
    (values: the rows without their ``Row`` column). ``killed``: the file was written by a run
    that was killed, so a last vector block cut short is left out instead of raising."""
    lines, cut_short = _read_lines(path)
    if not lines and not cut_short:
        raise TapmcFormatError(path, None, "empty file")
    comments = []
    k = 0
    while k < len(lines) and lines[k].startswith("#"):
        comments.append(lines[k].lstrip("#").split())
        k += 1
    if len(comments) < 2:
        raise TapmcFormatError(path, k + 1, "not a fix ave/time file: expected at least two "
                               "'#' header lines (title and column names)"
                               + _cut_short_note(cut_short and k == len(lines), len(lines)))
    # Vector mode names its second header line "TimeStep Number-of-rows": a file cut before
    # the third ("# Row ...") is a vector file without its column names, not a scalar one.
    vector = (len(comments) >= 3 and comments[2][:1] == ["Row"]) or \
        comments[1] == ["TimeStep", "Number-of-rows"]
    if vector and (len(comments) < 3 or comments[2][:1] != ["Row"]):
        raise TapmcFormatError(path, 3, "vector-mode fix ave/time file without its "
                               "third header line '# Row <names>'")
    names = comments[2][1:] if vector else comments[1]
    if not names:
        raise TapmcFormatError(path, 3 if vector else 2, "header line names no column")
    body = [(i + 1, lines[i].split()) for i in range(k, len(lines)) if lines[i].strip()]
    if not vector:
        rows = [(ln, _floats(path, ln, fields, len(names))) for ln, fields in body]
        return lines, k, names, False, [(row[0], [ln], row) for ln, row in rows]
    blocks = []
    j = 0
    while j < len(body):
        ln, fields = body[j]
        step, nrows = _floats(path, ln, fields, 2)
        if not np.isfinite(nrows) or nrows != int(nrows) or nrows < 1:
            raise TapmcFormatError(path, ln, f"row count {fields[1]!r} is not a positive integer")
        nrows = int(nrows)
        if blocks and nrows != len(blocks[0][2]):
            raise TapmcFormatError(path, ln, f"block has {nrows} rows, the first block had "
                                   f"{len(blocks[0][2])}")
        if j + nrows >= len(body):
            if killed:
                break
            raise TapmcFormatError(path, ln, f"truncated block: {nrows} rows announced, "
                                   f"{len(body) - j - 1} present")
        rows = body[j + 1:j + 1 + nrows]
        values = [_floats(path, rln, rfields, len(names) + 1)[1:] for rln, rfields in rows]
        blocks.append((step, [ln] + [rln for rln, _ in rows], values))
        j += nrows + 1
    if not blocks and not killed:
        raise TapmcFormatError(path, None, "vector-mode file with no data block"
                               + _cut_short_note(cut_short, len(lines)))
    return lines, k, names, True, blocks


def read_ave_time(path):
    """Read a ``fix ave/time`` output file, scalar or vector mode (told apart by the header:
    vector mode has a third comment line starting with ``# Row``). A last line without its
    end-of-line (a killed run) is left out; a scalar-mode file with its header and no row yet
    gives an empty table, a vector-mode file without a complete block raises."""
    _, _, names, vector, blocks = _parse_ave_time(path)
    if not vector:
        rows = [values for _, _, values in blocks]
        return AveTime(names, np.array(rows).reshape(-1, len(names)), path=path)
    return AveTime(names, steps=[step for step, _, _ in blocks],
                   blocks=np.array([values for _, _, values in blocks]), path=path)


def read_ave_time_blocks(path, killed=False):
    """The text of a ``fix ave/time`` file, for tools that rewrite such files keeping every byte
    of what they keep (:func:`tapmc.campaign.merge_ave_time_parts`): ``(header, blocks)``, the
    header lines and a list of ``(step, lines)``, one per output time (a row in scalar mode, a
    block in vector mode), each line with its end-of-line. Parsed and checked as by
    :func:`read_ave_time`, with the same errors; a step that is not an integer is refused.
    ``killed=True`` is for a file of a run that was killed: a last vector block cut short is
    left out (a last row cut short always is), and a file with no complete block is allowed."""
    lines, nheader, _, _, blocks = _parse_ave_time(path, killed)
    out = []
    for step, linenos, _ in blocks:
        if not np.isfinite(step) or step != int(step):
            raise TapmcFormatError(path, linenos[0], f"step {step!r} is not an integer")
        out.append((int(step), [lines[n - 1] + "\n" for n in linenos]))
    return [line + "\n" for line in lines[:nheader]], out


#: What read_fix_print does with a step printed again (see its docstring).
FIX_PRINT_REPEATS = ("error", "last", "all")

#: The title LAMMPS writes when fix print has no ``title`` keyword: words, not column names.
_FIX_PRINT_DEFAULT_TITLE = re.compile(r"^\s*Fix print output for fix \S+\s*$")


def read_fix_print(path, columns=None, repeats="error"):
    """Read a ``fix print`` file of numeric lines. Column names: ``columns`` if given, else the
    last ``#`` line before the data when it has one name per field (a ``title`` such as
    ``"# step phib z"``; LAMMPS's own title "# Fix print output for fix ID" never counts),
    else ``c1, c2, ...``. A row identical to the previous one is dropped (``fix print`` writes
    the boundary step of consecutive runs twice). A last line without its end-of-line (a killed
    run) is left out.

    Steps printed again: with a column named ``step`` (any case), a row whose step is not
    above the previous row's comes from a run resumed from a restart file with ``append``
    (it prints the taps after the restart again) or from consecutive runs that print their
    boundary step with other values. ``repeats`` says what to do: ``"error"`` (the default)
    raises :class:`TapmcFormatError` at that line, since counting such taps twice is silently
    wrong; ``"last"`` keeps the last print of each step (the rows from that step on that were
    printed before are dropped: the continued run supersedes them; ``Table.superseded``
    counts them); ``"all"`` keeps every row as printed. Without a step column nothing is
    checked."""
    if repeats not in FIX_PRINT_REPEATS:
        raise ValueError(f"repeats = {repeats!r}; allowed: "
                         + ", ".join(repr(r) for r in FIX_PRINT_REPEATS))
    lines, cut_short = _read_lines(path)
    rows, linenos, title = [], [], None
    width = None
    for i, line in enumerate(lines):
        if line.startswith("#"):
            if not rows and not _FIX_PRINT_DEFAULT_TITLE.match(line.lstrip("#")):
                title = line.lstrip("#").split()
            continue
        fields = line.split()
        if not fields:
            continue
        row = _floats(path, i + 1, fields, width)
        width = len(row)
        if not rows or row != rows[-1]:
            rows.append(row)
            linenos.append(i + 1)
    if not rows:
        what = "empty file" if not lines and not cut_short else "no numeric line found"
        raise TapmcFormatError(path, None, what + _cut_short_note(cut_short, len(lines)))
    if columns is None:
        columns = title if title and len(title) == width else [f"c{j + 1}" for j in range(width)]
    elif len(columns) != width:
        raise ValueError(f"columns has {len(columns)} names but {path} has {width} fields")
    names = [str(c).lower() for c in columns]
    superseded = 0
    if repeats != "all" and "step" in names:
        rows, superseded = _steps_once(path, rows, linenos, names.index("step"), repeats)
    table = Table(columns, np.array(rows), path)
    table.superseded = superseded
    return table


def _steps_once(path, rows, linenos, k, repeats):
    """(rows, how many were dropped): each step once, the last print kept (``repeats`` "last"),
    or TapmcFormatError at the first step not above the previous one ("error")."""
    kept = []
    dropped = 0
    for row, lineno in zip(rows, linenos):
        if kept and row[k] <= kept[-1][k]:
            if repeats == "error":
                raise TapmcFormatError(
                    path, lineno, f"step {row[k]:g} printed after step {kept[-1][k]:g}: a run "
                    "resumed from a restart file (or consecutive runs printing their boundary "
                    "step with other values) printed it again; read_fix_print(..., "
                    "repeats='last') keeps the last print of each step (the continued run's), "
                    "repeats='all' every row")
            while kept and kept[-1][k] >= row[k]:
                kept.pop()
                dropped += 1
        kept.append(row)
    return kept, dropped


class Frame:
    """One dump frame. ``step``; ``box_lo``, ``box_hi`` (3,) and ``periodic`` (3,) bool from
    the header; ``ids`` (N,) sorted ascending; ``positions`` (N, 3) in the dump's own frame
    (absolute coordinates, not shifted to the origin; scaled ``xs`` columns converted);
    ``radii`` (N,) from a ``radius`` or ``diameter`` column (or the reader's ``radius``
    argument), else None; ``types`` (N,) or None; ``fields`` dict of every per-atom column."""

    def __init__(self, step, box_lo, box_hi, periodic, ids, positions, radii=None, types=None,
                 fields=None):
        self.step = step
        self.box_lo = np.asarray(box_lo, dtype=float)
        self.box_hi = np.asarray(box_hi, dtype=float)
        self.periodic = np.asarray(periodic, dtype=bool)
        self.ids = ids
        self.positions = positions
        self.radii = radii
        self.types = types
        self.fields = fields or {}

    @property
    def n_atoms(self):
        return len(self.ids)

    def __repr__(self):
        return f"<Frame step {self.step}: {self.n_atoms} atoms>"


_COORDS = (("x", "y", "z", False), ("xs", "ys", "zs", True), ("xu", "yu", "zu", False),
           ("xsu", "ysu", "zsu", True))


class _DumpLines:
    """The lines of an open dump (bytes, plain or gzip) with the number of the last one read,
    so that every error names its line. Lines are decoded one by one, so that a binary file or
    a damaged gzip stream is reported at its line too."""

    def __init__(self, path, f):
        self.path = path
        self.lineno = 0
        self._file = f

    def next_or_none(self):
        """The next raw line (with its end-of-line), or None at the end of the file."""
        self.lineno += 1
        try:
            raw = self._file.readline()
        except _GZIP_ERRORS as err:
            raise self.error(f"damaged gzip file ({err})") from None
        if not raw.endswith(b"\n"):
            if raw.strip():  # the file ends inside this line: its last number may be cut short
                raise self.error("the file ends inside this line (no end-of-line): cut short "
                                 "while being written?")
            return None
        return _decode_line(self.path, self.lineno, raw)

    def next_in_frame(self):
        """The next line without its newline; the end of the file here cuts a frame short."""
        line = self.next_or_none()
        if line is None:
            raise TapmcFormatError(self.path, self.lineno,
                                   "unexpected end of file inside a frame")
        return line.rstrip("\n")

    def error(self, what, line=None):
        """A TapmcFormatError at ``line``, by default the last line read."""
        return TapmcFormatError(self.path, self.lineno if line is None else line, what)


_FrameHeader = namedtuple("_FrameHeader", "step n_atoms bounds flags columns line")


# ASCII digits only: str.isdigit also accepts characters such as '\u00b2' that int() refuses.
_INTEGER = re.compile(r"-?[0-9]+")


def _read_timestep(lines):
    text = lines.next_in_frame().split()
    if len(text) != 1 or not _INTEGER.fullmatch(text[0]):
        raise lines.error(f"bad timestep {' '.join(text)!r}")
    return int(text[0])


def _read_atom_count(lines):
    text = lines.next_in_frame().strip()
    if not _INTEGER.fullmatch(text) or text.startswith("-"):
        raise lines.error(f"bad atom count {text!r}")
    return int(text)


def _read_box_bounds(lines, item):
    """(lo, hi) of the three axes and the boundary flags of the item (None when absent)."""
    words = item.split()[2:]
    if any(w in ("xy", "xz", "yz") for w in words):
        raise lines.error("triclinic boxes are not supported")
    flags = words if len(words) == 3 else None
    bounds = []
    for _ in range(3):
        fields = lines.next_in_frame().split()
        bounds.append(_floats(lines.path, lines.lineno, fields, 2))
    return bounds, flags


def _read_frame_header(lines, line):
    """The ITEM lines of one frame, in any order, from ``line`` (already read) to ATOMS."""
    step = n_atoms = bounds = flags = None
    while True:
        if not line.startswith("ITEM:"):
            raise lines.error(f"expected an 'ITEM:' line, found {line.strip()[:60]!r}")
        item = line[5:].strip()
        if item.startswith("TIMESTEP"):
            step = _read_timestep(lines)
        elif item.startswith("NUMBER OF ATOMS"):
            n_atoms = _read_atom_count(lines)
        elif item.startswith("BOX BOUNDS"):
            bounds, flags = _read_box_bounds(lines, item)
        elif item.startswith("ATOMS"):
            columns = item.split()[1:]
            break
        elif item.startswith(("UNITS", "TIME")):
            lines.next_in_frame()
        else:
            raise lines.error(f"unknown dump item {item!r}")
        line = lines.next_or_none()
        if line is None:
            raise lines.error("unexpected end of file in a header")
    if step is None or n_atoms is None or bounds is None:
        raise lines.error("frame header lacks TIMESTEP, NUMBER OF ATOMS or BOX BOUNDS")
    if not columns:  # old dump atom without column names
        columns = ["id", "type", "xs", "ys", "zs"]
    return _FrameHeader(step, n_atoms, bounds, flags, columns, lines.lineno)


def _read_atom_table(lines, header):
    """The per-atom block as an (N, columns) float array: parsed whole when it is clean,
    line by line otherwise so that the error names the bad line."""
    n_atoms, width = header.n_atoms, len(header.columns)
    text = [lines.next_in_frame() for _ in range(n_atoms)]
    try:
        flat = np.array(" ".join(text).split(), dtype=float)
        if flat.size == n_atoms * width and np.all(np.isfinite(flat)):
            return flat.reshape(n_atoms, width)
    except ValueError:
        pass
    table = np.empty((n_atoms, width))
    for a, line_text in enumerate(text):
        here = header.line + 1 + a
        fields = line_text.split()
        if len(fields) != width:
            raise lines.error(f"expected {width} fields ({' '.join(header.columns)}), "
                              f"found {len(fields)}", here)
        table[a] = _floats(lines.path, here, fields)
        if not np.all(np.isfinite(table[a])):
            raise lines.error("NaN or infinite value", here)
    return table


def _periodic_axes(boundary, flags):
    """Periodicity per axis: the reader's ``boundary`` wins over the dump's flags."""
    if boundary is not None:
        return np.array([c == "p" for c in boundary])
    if flags is not None:
        return np.array([fl == "pp" for fl in flags])
    return np.zeros(3, dtype=bool)


def _absolute_positions(path, header, table, col, lo, hi):
    """(N, 3) positions from the first coordinate triple present, scaled ones unscaled."""
    for cx, cy, cz, scaled in _COORDS:
        if cx in col and cy in col and cz in col:
            pos = table[:, [col[cx], col[cy], col[cz]]]
            return lo + pos * (hi - lo) if scaled else pos
    raise TapmcFormatError(path, header.line, f"no coordinate columns (x y z, xs ys zs, xu yu "
                           f"zu or xsu ysu zsu) in {' '.join(header.columns)}")


def _integer_column(path, header, table, col, name):
    """Column ``name`` as int64, refused at its first line that is not an integer in range
    (a cast would silently truncate 1.5 to 1 or wrap 1e30)."""
    values = table[:, col[name]]
    bad = np.flatnonzero((values != np.round(values)) | (np.abs(values) >= 2.0 ** 63))
    if bad.size:
        raise TapmcFormatError(path, header.line + 1 + bad[0], f"atom {name} "
                               f"{values[bad[0]]!r} is not an integer")
    return values.astype(np.int64)


def _frame_from_table(path, header, table, radius, boundary):
    """The Frame of a parsed block, atoms sorted by id."""
    n_atoms = header.n_atoms
    lo = np.array([b[0] for b in header.bounds])
    hi = np.array([b[1] for b in header.bounds])
    periodic = _periodic_axes(boundary, header.flags)
    col = {name: j for j, name in enumerate(header.columns)}
    pos = _absolute_positions(path, header, table, col, lo, hi)
    ids = _integer_column(path, header, table, col, "id") if "id" in col \
        else np.arange(1, n_atoms + 1, dtype=np.int64)
    if len(np.unique(ids)) != n_atoms:
        raise TapmcFormatError(path, header.line, "duplicate atom ids in the frame")
    order = np.argsort(ids, kind="stable")
    if "radius" in col:
        radii = table[order, col["radius"]]
    elif "diameter" in col:
        radii = 0.5 * table[order, col["diameter"]]
    elif radius is not None:
        radii = np.full(n_atoms, float(radius))
    else:
        radii = None
    types = _integer_column(path, header, table, col, "type")[order] if "type" in col else None
    fields = {name: table[order, j] for j, name in enumerate(header.columns)}
    return Frame(header.step, lo, hi, periodic, ids[order], pos[order], radii, types, fields)


def _parse_dump_frames(path, radius=None, boundary=None):
    """Generator over the frames of a text dump, float64, checked line by line. A dump without
    any frame raises: no caller can mean an empty trajectory, and a file that LAMMPS has not
    written yet (or a wrong path to an empty file) would otherwise pass silently."""
    with _open_bytes(path) as f:
        lines = _DumpLines(path, f)
        frames = 0
        while True:
            line = lines.next_or_none()
            if line is None:
                break
            if not line.strip():
                continue
            header = _read_frame_header(lines, line)
            table = _read_atom_table(lines, header)
            frames += 1
            yield _frame_from_table(path, header, table, radius, boundary)
    if frames == 0:
        raise TapmcFormatError(path, None, "empty file: no dump frame" if lines.lineno == 1
                               else "no dump frame: the file holds only blank lines")


class Dump:
    """A LAMMPS text dump (``dump custom`` or ``dump atom``, plain or gzip) read frame by frame.

    ``frames`` is the list of :class:`Frame` (read on first use); ``len(dump)``, ``steps`` and
    iteration are available; ``universe()`` returns an MDAnalysis Universe of the same file.

    Backends. ``backend="native"`` (default) parses the file itself in double precision.
    ``backend="mdanalysis"`` takes the positions from MDAnalysis (``LAMMPSDUMP`` format).
    Why native is the default: MDAnalysis 2.4 stores positions in float32 (about 1e-6 relative
    error, enough to turn contacts into overlaps for the pore analysis), subtracts the box
    lower corner, drops the periodicity flags and the radius column, needs a ``type`` column and
    exactly nine header lines, and misplaces scaled coordinates in a box whose lower corner is
    not the origin. With the MDAnalysis backend the lower corner is added back and
    box, periodicity, ids and radii still come from the header and columns; a dump without
    ``type`` or with extra header items (``dump_modify units/time yes``) is rewritten into a
    temporary copy with a ``type`` column of ones and the standard header, the simplest way to
    give MDAnalysis what it needs without changing the user's file.
    """

    def __init__(self, path, radius=None, boundary=None, backend="native"):
        if not os.path.isfile(path):
            raise FileNotFoundError(f"dump file {path!r} does not exist")
        if backend not in ("native", "mdanalysis"):
            raise ValueError(f"backend = {backend!r} must be 'native' or 'mdanalysis'")
        if radius is not None and not float(radius) > 0:
            raise ValueError(f"radius = {radius!r} must be > 0")
        if boundary is not None and (len(boundary) != 3 or set(boundary) - set("pfsm")):
            raise ValueError(f"boundary = {boundary!r} must be three letters of p, f, s, m "
                             "(e.g. 'ppf')")
        self.path = str(path)
        self.radius = radius
        self.boundary = boundary
        self.backend = backend
        self._frames = None

    def __iter__(self):
        if self._frames is not None:
            return iter(self._frames)
        if self.backend == "native":
            return _parse_dump_frames(self.path, self.radius, self.boundary)
        return iter(self.frames)

    @property
    def frames(self):
        if self._frames is None:
            frames = list(_parse_dump_frames(self.path, self.radius, self.boundary))
            if self.backend == "mdanalysis":
                frames = self._mdanalysis_positions(frames)
            self._frames = frames
        return self._frames

    def __len__(self):
        return len(self.frames)

    @property
    def steps(self):
        return np.array([fr.step for fr in self.frames])

    def _mda_compatible_file(self, frames):
        """Path of a file MDAnalysis can read: the dump itself when it has ``type`` and the
        standard nine header lines, else a rewritten temporary copy (caller removes it)."""
        with _open_text(self.path) as f:
            head = [f.readline() for _ in range(9)]
        columns = head[8].split()[2:] if head[8].startswith("ITEM: ATOMS") else []
        # scaled coordinates are rewritten too: MDAnalysis 2.4 converts xs to x relative to the
        # origin and then still subtracts the lower corner (wrong for a box not at the origin)
        standard = head[0].startswith("ITEM: TIMESTEP") and "type" in columns \
            and {"x", "y", "z"} <= set(columns) and bool(frames)
        if standard:
            return self.path, False
        fd, tmp = tempfile.mkstemp(suffix=".lammpstrj")
        with os.fdopen(fd, "w") as out:
            for fr in frames:
                out.write(f"ITEM: TIMESTEP\n{fr.step}\nITEM: NUMBER OF ATOMS\n{fr.n_atoms}\n")
                out.write("ITEM: BOX BOUNDS " + " ".join("pp" if p else "ff" for p in fr.periodic)
                          + "\n")
                for d in range(3):
                    out.write(f"{fr.box_lo[d]:.17g} {fr.box_hi[d]:.17g}\n")
                out.write("ITEM: ATOMS id type x y z\n")
                types = fr.types if fr.types is not None else np.ones(fr.n_atoms, dtype=int)
                for i in range(fr.n_atoms):
                    x, y, z = fr.positions[i]
                    out.write(f"{fr.ids[i]} {types[i]} {x:.17g} {y:.17g} {z:.17g}\n")
        return tmp, True

    def universe(self):
        """An MDAnalysis Universe of this dump (positions shifted to the origin, as MDAnalysis
        does; add ``frame.box_lo`` back for absolute coordinates)."""
        frames = list(_parse_dump_frames(self.path, self.radius, self.boundary))
        path, temporary = self._mda_compatible_file(frames)
        universe = _mdanalysis_universe(path)
        if temporary:  # MDAnalysis keeps reading the file: remove it when Python exits
            import atexit
            atexit.register(lambda: os.path.exists(path) and os.remove(path))
        return universe

    def _mdanalysis_positions(self, frames):
        path, temporary = self._mda_compatible_file(frames)
        try:
            universe = _mdanalysis_universe(path)
            if len(universe.trajectory) != len(frames):
                raise TapmcFormatError(self.path, None, f"MDAnalysis reads "
                                       f"{len(universe.trajectory)} frames, the header scan "
                                       f"{len(frames)}")
            for ts, fr in zip(universe.trajectory, frames):
                # MDAnalysis subtracts the box lower corner: add it back (dump's own frame)
                fr.positions = ts.positions.astype(float) + fr.box_lo
            universe.trajectory.close()
        finally:
            if temporary:
                os.remove(path)
        return frames


def read_dump(path, radius=None, boundary=None, backend="native"):
    """Open a LAMMPS text dump; see :class:`Dump`."""
    return Dump(path, radius=radius, boundary=boundary, backend=backend)
