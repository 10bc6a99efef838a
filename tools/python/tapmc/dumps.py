# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""LAMMPS text dumps (``dump custom`` / ``dump atom``, plain or gzip) as :class:`Dump` frames,
read by :func:`read_dump` (also :mod:`tapmc.readers`' name for it). A dump cut short (the last
line without its end-of-line) cuts its last frame short and raises
:class:`~tapmc.readers.TapmcFormatError`."""

import os
import re
import tempfile
from collections import namedtuple

import numpy as np

from ._text_files import (GZIP_ERRORS, TapmcFormatError, decode_line, floats, is_float,
                          open_bytes, open_text)

__all__ = ["Frame", "Dump", "read_dump"]


def _mdanalysis_universe(path):
    """MDAnalysis Universe of a LAMMPS dump, without its import-time and mass-guessing
    warnings (irrelevant here: only positions are used)."""
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        import MDAnalysis
        return MDAnalysis.Universe(path, format="LAMMPSDUMP")


class Frame:
    """One dump frame. ``step``; ``box_lo``, ``box_hi`` (3,) and ``periodic`` (3,) bool from
    the header; ``ids`` (N,) sorted ascending; ``positions`` (N, 3) in the dump's own frame
    (absolute coordinates, not shifted to the origin; scaled ``xs`` columns converted);
    ``radii`` (N,) from a ``radius`` or ``diameter`` column (or the reader's ``radius``
    argument), else None; ``types`` (N,) or None; ``fields`` dict of every per-atom column;
    ``digits``: the significant digits the dump wrote its coordinates with (at least 6,
    LAMMPS's default ``%g``; 10 after ``dump_modify format float %.10g``), None for positions
    not read from text."""

    def __init__(self, step, box_lo, box_hi, periodic, ids, positions, radii=None, types=None,
                 fields=None, digits=None):
        self.step = step
        self.box_lo = np.asarray(box_lo, dtype=float)
        self.box_hi = np.asarray(box_hi, dtype=float)
        self.periodic = np.asarray(periodic, dtype=bool)
        self.ids = ids
        self.positions = positions
        self.radii = radii
        self.types = types
        self.fields = fields or {}
        self.digits = digits

    @property
    def n_atoms(self):
        return len(self.ids)

    def __repr__(self):
        return f"<Frame step {self.step}: {self.n_atoms} atoms>"


_COORDS = (("x", "y", "z", False), ("xs", "ys", "zs", True), ("xu", "yu", "zu", False),
           ("xsu", "ysu", "zsu", True))
_COORD_NAMES = frozenset(name for names in _COORDS for name in names[:3])
#: significant digits of LAMMPS's default float format in dumps (``%g``): the fewest a dump
#: holds, whatever its numbers' trailing zeros
DEFAULT_DUMP_DIGITS = 6
# coordinates sampled per column to find the digits they were written with: %.10g trims a
# trailing zero one time in ten, so 64 values all shorter than written happen 1e-64 of the time
_DIGITS_SAMPLE = 64
# the columns a Frame is made of: finite numbers required (others may hold text, NaN or inf)
_USED_COLUMNS = frozenset({"id", "type", "radius", "diameter"}
                          | {name for triple in _COORDS for name in triple[:3]})


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
        except GZIP_ERRORS as err:
            raise self.error(f"damaged gzip file ({err})") from None
        if not raw.endswith(b"\n"):
            if raw.strip():  # the file ends inside this line: its last number may be cut short
                raise self.error("the file ends inside this line (no end-of-line): cut short "
                                 "while being written?")
            return None
        return decode_line(self.path, self.lineno, raw)

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
        bounds.append(floats(lines.path, lines.lineno, fields, 2))
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


def _significant_digits(word):
    """Significant digits of one number as written: '-1.50e+01' -> 3, '0.000123' -> 3."""
    mantissa = word.lstrip("+-").split("e")[0].split("E")[0].replace(".", "")
    return len(mantissa.lstrip("0"))


def _written_digits(header, words):
    """The significant digits the coordinates were written with: the most over a sample of each
    coordinate column, and at least LAMMPS's default %g's."""
    width = len(header.columns)
    digits = DEFAULT_DUMP_DIGITS
    for j, name in enumerate(header.columns):
        if name in _COORD_NAMES:
            sample = words[j:j + width * _DIGITS_SAMPLE:width]
            digits = max([digits] + [_significant_digits(w) for w in sample])
    return digits


def _read_atom_table(lines, header):
    """The per-atom block: an (N, columns) float array, a dict of the text columns (e.g.
    ``element``: their strings; NaN in the array) and the significant digits of the
    coordinates (:func:`_written_digits`). Parsed whole when it is clean (every line of
    the header's width: a short line and a long one would otherwise make up the total and shift
    the fields between atoms), column by column otherwise so that the error names the bad line.
    The columns the reader uses (ids, types, coordinates, radii) must be finite numbers; any
    other column may hold text, NaN or inf (a per-atom variable), kept as written."""
    n_atoms, width = header.n_atoms, len(header.columns)
    text = [lines.next_in_frame() for _ in range(n_atoms)]
    used = [j for j, name in enumerate(header.columns) if name in _USED_COLUMNS]
    for a, line_text in enumerate(text):
        if len(line_text.split()) != width:
            raise lines.error(f"expected {width} fields ({' '.join(header.columns)}), "
                              f"found {len(line_text.split())}", header.line + 1 + a)
    words = " ".join(text).split()
    digits = _written_digits(header, words)
    try:
        table = np.array(words, dtype=float).reshape(n_atoms, width)
    except ValueError:
        table = None
    if table is not None and np.all(np.isfinite(table[:, used])):
        return table, {}, digits
    # a text column (e.g. element) or a non-finite used column: parsed column by column from
    # the same words (every line has the header's width, so column j is words[j::width])
    table = np.empty((n_atoms, width))
    text_columns = {}
    for j, name in enumerate(header.columns):
        column = words[j::width]
        try:
            table[:, j] = np.array(column, dtype=float)
        except ValueError:
            if j in used:
                a = next(a for a in range(n_atoms) if not is_float(column[a]))
                raise lines.error(f"non-numeric {name} {column[a]!r}",
                                  header.line + 1 + a) from None
            table[:, j] = np.nan
            text_columns[name] = np.array(column, dtype=str)
            continue
        if j in used and not np.all(np.isfinite(table[:, j])):
            a = int(np.flatnonzero(~np.isfinite(table[:, j]))[0])
            raise lines.error(f"{name} {column[a]!r} is not finite", header.line + 1 + a)
    return table, text_columns, digits


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


def _frame_from_table(path, header, table, text_columns, digits, radius, boundary):
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
    fields = {name: text_columns[name][order] if name in text_columns else table[order, j]
              for j, name in enumerate(header.columns)}
    return Frame(header.step, lo, hi, periodic, ids[order], pos[order], radii, types, fields,
                 digits)


def _parse_dump_frames(path, radius=None, boundary=None):
    """Generator over the frames of a text dump, float64, checked line by line. A dump without
    any frame raises: no caller can mean an empty trajectory, and a file that LAMMPS has not
    written yet (or a wrong path to an empty file) would otherwise pass silently."""
    with open_bytes(path) as f:
        lines = _DumpLines(path, f)
        frames = 0
        while True:
            line = lines.next_or_none()
            if line is None:
                break
            if not line.strip():
                continue
            header = _read_frame_header(lines, line)
            table, text_columns, digits = _read_atom_table(lines, header)
            frames += 1
            yield _frame_from_table(path, header, table, text_columns, digits, radius, boundary)
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
    ``id`` or ``type`` or with extra header items (``dump_modify units/time yes``) is rewritten
    into a temporary copy with the ids (1 to N without an ``id`` column), a ``type`` column of
    ones and the standard header, the simplest way to give MDAnalysis what it needs without
    changing the user's file.
    """

    def __init__(self, path, radius=None, boundary=None, backend="native"):
        if os.path.isdir(path):
            raise IsADirectoryError(f"dump file {os.fspath(path)!r} is a directory: give one "
                                    "dump file (read_dump reads one file's frames)")
        if not os.path.isfile(path):
            raise FileNotFoundError(f"dump file {os.fspath(path)!r} does not exist")
        if backend not in ("native", "mdanalysis"):
            raise ValueError(f"backend = {backend!r} must be 'native' or 'mdanalysis'")
        if radius is not None and not 0 < float(radius) < np.inf:
            raise ValueError(f"radius = {radius!r} must be finite and > 0")
        if boundary is not None and (len(boundary) != 3 or set(boundary) - set("pfsm")):
            raise ValueError(f"boundary = {boundary!r} must be three letters of p, f, s, m "
                             "(e.g. 'ppf')")
        self.path = str(path)
        self.radius = radius
        self.boundary = boundary
        self.backend = backend
        self._frames = None

    def __repr__(self):
        read = "not read yet" if self._frames is None else f"{len(self._frames)} frames"
        return f"<Dump {self.path!r} ({self.backend}): {read}>"

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
        """Path of a file MDAnalysis can read: the dump itself when it has ``id``, ``type``,
        ``x y z`` and the standard nine header lines, else a rewritten temporary copy (caller
        removes it)."""
        with open_text(self.path) as f:
            head = [f.readline() for _ in range(9)]
        columns = head[8].split()[2:] if head[8].startswith("ITEM: ATOMS") else []
        # scaled coordinates are rewritten too: MDAnalysis 2.4 converts xs to x relative to the
        # origin and then still subtracts the lower corner (wrong for a box not at the origin)
        standard = head[0].startswith("ITEM: TIMESTEP") and {"id", "type"} <= set(columns) \
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
        self._require_one_atom_count(frames)
        path, temporary = self._mda_compatible_file(frames)
        universe = _mdanalysis_universe(path)
        if temporary:  # MDAnalysis keeps reading the file: remove it when Python exits
            import atexit
            atexit.register(lambda: os.path.exists(path) and os.remove(path))
        return universe

    def _require_one_atom_count(self, frames):
        counts = sorted({fr.n_atoms for fr in frames})
        if len(counts) > 1:  # MDAnalysis keeps one topology for the whole trajectory
            step = next(fr.step for fr in frames if fr.n_atoms != frames[0].n_atoms)
            raise TapmcFormatError(self.path, None, f"frames of {counts[0]} to {counts[-1]} "
                                   f"atoms (the first change at step {step}): MDAnalysis reads "
                                   "one atom count per file; use backend='native'")

    def _mdanalysis_positions(self, frames):
        self._require_one_atom_count(frames)
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
