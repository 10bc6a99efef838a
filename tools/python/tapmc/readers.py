# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Readers for the LAMMPS outputs of a tapping run: log files (thermo of several ``run``
commands), ``fix ave/time`` files (scalar and vector mode), ``fix print`` files and text dumps
(``dump custom`` / ``dump atom``, plain or gzip; read by :mod:`tapmc.dumps`, whose
:func:`read_dump`, :class:`Dump` and :class:`Frame` this module names too).

Every malformed file raises :class:`TapmcFormatError` with the file name and, where the fault
sits on one line, its number: an empty or binary file (bytes that are not UTF-8 text), a damaged
gzip stream, a wrong number of fields, a non-numeric field. A last line without its end-of-line
is a write cut short (a job killed while LAMMPS was writing it): logs, ``fix ave/time`` and
``fix print`` files keep the complete lines before it and leave it out, since a number cut
short still parses as a number; in a dump it cuts the last frame short and raises.
"""

import re
import warnings

import numpy as np

from ._text_files import TapmcFormatError, cut_short_note, floats, is_float, read_lines
from .dumps import Dump, Frame, read_dump

__all__ = ["TapmcFormatError", "Table", "Thermo", "Log", "AveTime", "Frame", "Dump",
           "read_log", "read_ave_time", "read_ave_time_blocks", "read_fix_print", "read_dump"]


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


#: A run-boundary step whose two prints differ by more than this (relative, or absolute near
#: zero) changed between the runs; less is the rounding of two thermo formats (%.10g, %g).
_BOUNDARY_RTOL, _BOUNDARY_ATOL = 1e-3, 1e-9


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
        """All runs as one :class:`Thermo`: :meth:`join` with ``repeats="error"``."""
        return self.join()

    def join(self, repeats="error"):
        """All runs as one :class:`Thermo`. Columns are the union over the runs in order of
        appearance (NaN where a run does not print a column). Consecutive runs repeat their
        boundary step (the last row of one run and the first of the next): the two rows are
        merged into one, the earlier run's values winning, so that every step appears once.

        A run that starts below the previous run's last step (a run resumed from a restart
        file into the same log with ``log ... append``, or after ``reset_timestep``) would
        count those steps twice: ``repeats="error"`` raises :class:`TapmcFormatError` naming
        the run and the steps, ``"last"`` keeps the later run's rows of the steps printed
        again (as ``read_fix_print``), ``"all"`` every row as printed."""
        if repeats not in FIX_PRINT_REPEATS:
            raise ValueError(f"repeats = {repeats!r}; allowed: "
                             + ", ".join(repr(r) for r in FIX_PRINT_REPEATS))
        columns = []
        for run in self.runs:
            columns += [c for c in run.columns if c not in columns]
        rows = []
        steps = []
        has_step = "Step" in columns
        for k, run in enumerate(self.runs):
            block = np.full((len(run), len(columns)), np.nan)
            for j, c in enumerate(run.columns):
                block[:, columns.index(c)] = run.data[:, j]
            start = 0
            first = block[0, columns.index("Step")] if has_step and len(run) else np.nan
            if steps and first < steps[-1] and repeats != "all":
                if repeats == "error":
                    raise TapmcFormatError(
                        self.path, None, f"run {k + 1} starts at step "
                        f"{first:g}, after step {steps[-1]:g}: a run resumed from a restart "
                        "file (log ... append) or after reset_timestep prints those steps "
                        "again; Log.join(repeats='last') keeps the later run's rows, "
                        "repeats='all' every row, Log.runs each run alone")
                while steps and steps[-1] >= first:
                    steps.pop()
                    rows.pop()
            if has_step and rows and len(run) and "Step" in run.columns \
                    and steps and block[0, columns.index("Step")] == steps[-1]:
                last = rows[-1]
                fill = np.isnan(last)
                # beyond the rounding of two thermo formats: e.g. atoms deleted between the runs
                differs = ~fill & ~np.isnan(block[0]) & ~np.isclose(
                    last, block[0], rtol=_BOUNDARY_RTOL, atol=_BOUNDARY_ATOL)
                if np.any(differs):
                    changed = [columns[j] for j in np.flatnonzero(differs)]
                    warnings.warn(f"{self.path}: step {steps[-1]:g} ends run "
                                  f"{k} and starts run {k + 1} with other values of "
                                  f"{', '.join(changed)}; Log.thermo keeps the earlier run's "
                                  "(Log.runs has both)", stacklevel=3)
                last[fill] = block[0, fill]
                start = 1
            for row in block[start:]:
                rows.append(row.copy())
                if has_step:
                    steps.append(row[columns.index("Step")])
        return Thermo(columns, np.array(rows).reshape(-1, len(columns)), self.path,
                      self.warnings, all(r.complete for r in self.runs))


_MEMORY_LINE = re.compile(r"^\s*(Per MPI rank memory|Memory usage per processor)")
#: The echo of a run command with 'pre no': LAMMPS sets nothing up and prints no memory line,
#: its thermo header follows the echo.
_RUN_PRE_NO = re.compile(r"^\s*run\s.*\bpre\s+no\b")


def _table_header_line(lines, i):
    """The index of the thermo header a table starting at line i has (after the memory line,
    or after the echo of a 'run ... pre no'), else None."""
    if i + 1 >= len(lines):
        return None
    if _MEMORY_LINE.match(lines[i]):
        return i + 1
    following = lines[i + 1].split()
    if _RUN_PRE_NO.match(lines[i]) and following and not is_float(following[0]) \
            and not _MEMORY_LINE.match(lines[i + 1]):
        return i + 1
    return None


def read_log(path, strict=True):
    """Read a LAMMPS log file: the thermo table of every ``run`` (one-line thermo styles: the
    header line follows the "Per MPI rank memory" line, or the echo of a ``run ... pre no``,
    which prints none; the table ends at ``Loop time``; a ``Loop time`` line without a table
    raises, as a run left out would be silently missing) and
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
    lines, cut_short = read_lines(path)
    i = 0
    n = len(lines)
    while i < n:
        line = lines[i]
        if line.startswith("WARNING"):
            warnings.append(line.strip())
        if line.startswith("Loop time"):
            raise TapmcFormatError(path, i + 1, "a run's 'Loop time' without its thermo table "
                                   "(its header is found after the 'Per MPI rank memory' line "
                                   "or the echo of a 'run ... pre no': a run with 'pre no' and "
                                   "'echo none'?)")
        at = _table_header_line(lines, i)
        if at is not None:
            header = lines[at].split()
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
                elif len(fields) == len(header) and is_float(fields[0]):
                    rows.append(floats(path, i + 1, fields, len(header)))
                elif fields and strict:
                    what = (f"expected {len(header)} fields, found {len(fields)}"
                            if is_float(fields[0]) else "unexpected text")
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
        raise TapmcFormatError(path, None, what + cut_short_note(cut_short, len(lines)))
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
    lines, cut_short = read_lines(path)
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
                               + cut_short_note(cut_short and k == len(lines), len(lines)))
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
        rows = [(ln, floats(path, ln, fields, len(names))) for ln, fields in body]
        return lines, k, names, False, [(row[0], [ln], row) for ln, row in rows]
    blocks = []
    j = 0
    while j < len(body):
        ln, fields = body[j]
        step, nrows = floats(path, ln, fields, 2)
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
        values = [floats(path, rln, rfields, len(names) + 1)[1:] for rln, rfields in rows]
        blocks.append((step, [ln] + [rln for rln, _ in rows], values))
        j += nrows + 1
    if not blocks and not killed:
        raise TapmcFormatError(path, None, "vector-mode file with no data block"
                               + cut_short_note(cut_short, len(lines)))
    return lines, k, names, True, blocks


def read_ave_time(path, killed=False):
    """Read a ``fix ave/time`` output file, scalar or vector mode (told apart by the header:
    vector mode has a third comment line starting with ``# Row``). A last line without its
    end-of-line (a killed run) is left out; a scalar-mode file with its header and no row yet
    gives an empty table, a vector-mode file without a complete block raises. A vector block
    with fewer rows than it announces raises too, unless ``killed=True`` (the file of a run
    that was killed while writing it): a last block cut short is then left out and the
    complete blocks before it are read."""
    _, _, names, vector, blocks = _parse_ave_time(path, killed)
    if vector and not blocks:
        raise TapmcFormatError(path, None, "vector-mode file with no complete data block")
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

#: Names of a fix print column that counts the taps (any case): the step check reads it.
FIX_PRINT_STEP_NAMES = ("step", "tap", "timestep")


def read_fix_print(path, columns=None, repeats="error"):
    """Read a ``fix print`` file of numeric lines. Column names: ``columns`` if given, else the
    last ``#`` line before the data when it has one name per field (a ``title`` such as
    ``"# step phib z"``; LAMMPS's own title "# Fix print output for fix ID" never counts),
    else ``c1, c2, ...``. A last line without its end-of-line (a killed run) is left out.

    Steps printed again: with a step column (named ``step``, ``tap`` or ``timestep``, any case:
    :data:`FIX_PRINT_STEP_NAMES`), a row identical to the previous one is dropped (``fix
    print`` writes the boundary step of consecutive runs twice), and a row whose step is not
    above the previous row's comes from a run resumed from a restart file with ``append`` (it
    prints the taps after the restart again) or from consecutive runs that print their boundary
    step with other values. ``repeats`` says what to do: ``"error"`` (the default) raises
    :class:`TapmcFormatError` at that line, since counting such taps twice is silently wrong;
    ``"last"`` keeps the last print of each step (the rows from that step on that were printed
    before are dropped: the continued run supersedes them; ``Table.superseded`` counts them);
    ``"all"`` keeps every row as printed.

    Without a step column no row can be told from a repeat: every row is kept (an unchanged tap
    printed with few digits is a real row), with a warning when a row equals the one before it
    (it may be the boundary step of consecutive runs); a ``#`` line after the data (the title a
    fix defined again writes, e.g. a run resumed with ``append``) raises
    :class:`TapmcFormatError` unless ``repeats="all"``. Print a step column to have both
    checked."""
    if repeats not in FIX_PRINT_REPEATS:
        raise ValueError(f"repeats = {repeats!r}; allowed: "
                         + ", ".join(repr(r) for r in FIX_PRINT_REPEATS))
    lines, cut_short = read_lines(path)
    rows, linenos, title = [], [], None
    width = None
    title_after_data = None  # the line of the first '#' line after a row
    for i, line in enumerate(lines):
        if line.startswith("#"):
            if not rows and not _FIX_PRINT_DEFAULT_TITLE.match(line.lstrip("#")):
                title = line.lstrip("#").split()
            elif rows and title_after_data is None:
                title_after_data = i + 1
            continue
        fields = line.split()
        if not fields:
            continue
        row = floats(path, i + 1, fields, width)
        width = len(row)
        rows.append(row)
        linenos.append(i + 1)
    if not rows:
        what = "empty file" if not lines and not cut_short else "no numeric line found"
        raise TapmcFormatError(path, None, what + cut_short_note(cut_short, len(lines)))
    if columns is None:
        columns = title if title and len(title) == width else [f"c{j + 1}" for j in range(width)]
    elif len(columns) != width:
        raise ValueError(f"columns has {len(columns)} names but {path} has {width} fields")
    names = [str(c).lower() for c in columns]
    step = next((names.index(n) for n in FIX_PRINT_STEP_NAMES if n in names), None)
    superseded = 0
    if step is not None:
        kept = [j for j in range(len(rows)) if j == 0 or rows[j] != rows[j - 1]]
        rows, linenos = [rows[j] for j in kept], [linenos[j] for j in kept]
        if repeats != "all":
            rows, superseded = _steps_once(path, rows, linenos, step, repeats)
    else:
        _check_without_steps(path, rows, title_after_data, repeats)
    table = Table(columns, np.array(rows), path)
    table.superseded = superseded
    return table


def _check_without_steps(path, rows, title_after_data, repeats):
    """read_fix_print without a step column: a title after the data stops ("error", "last"),
    rows equal to the one before are kept with a warning."""
    if repeats != "all" and title_after_data is not None:
        raise TapmcFormatError(
            path, title_after_data, "a '#' line after the data: a fix print defined again "
            "(e.g. a run resumed from a restart file with 'append') wrote here, and without a "
            "step column (" + ", ".join(FIX_PRINT_STEP_NAMES) + ") the taps it printed again "
            "cannot be found; print a step column, or read with repeats='all' to keep every row")
    same = sum(1 for a, b in zip(rows, rows[1:]) if a == b)
    if same:
        warnings.warn(f"{path}: {same} row(s) equal to the row before, kept: without a step "
                      "column an unchanged tap cannot be told from the boundary step that "
                      "consecutive runs print twice; print a step column", stacklevel=3)


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
