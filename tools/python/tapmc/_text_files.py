# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""What every reader of :mod:`tapmc.readers` shares: :class:`TapmcFormatError`, and the
lines of a text file, plain or gzip, with a last line cut short told apart."""

import gzip
import zlib

class TapmcFormatError(ValueError):
    """A file that does not have the expected format; ``path`` and ``line`` (1-based, or None
    for the whole file) say where, the message reads ``FILE:LINE: what``."""

    def __init__(self, path, line, what):
        self.path = str(path)
        self.line = line
        self.what = what
        where = f"{self.path}:{line}" if line is not None else self.path
        super().__init__(f"{where}: {what}")

GZIP_MAGIC = b"\x1f\x8b"
# What a damaged gzip stream raises: BadGzipFile (an OSError) for a bad header, zlib.error for
# corrupt data, EOFError for a stream cut short.
GZIP_ERRORS = (OSError, EOFError, zlib.error)


def open_text(path):
    """Open a text file, gzip-compressed or not (detected from the content, not the name)."""
    with open(path, "rb") as probe:
        magic = probe.read(2)
    if magic == GZIP_MAGIC:
        return gzip.open(path, "rt")
    return open(path, "r")


def open_bytes(path):
    """Open a file for reading bytes, through gzip when its content starts with gzip's magic."""
    with open(path, "rb") as probe:
        magic = probe.read(2)
    return gzip.open(path, "rb") if magic == GZIP_MAGIC else open(path, "rb")


def decode_line(path, lineno, raw):
    """One line of bytes as text; bytes that are not UTF-8 mean a binary file, named here."""
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as err:
        raise TapmcFormatError(path, lineno, f"byte 0x{raw[err.start]:02x} at column "
                               f"{err.start + 1} is not UTF-8 text (a binary file?)") from None


def read_lines(path):
    """The complete lines of a text file (plain or gzip) without their end-of-line, and whether a
    last line without an end-of-line was left out (see the module's docstring). Lines are split
    at line feeds only, not at the other characters str.splitlines() breaks at (form feed,
    \\x1c, ...), so that line numbers are the ones an editor shows."""
    handle = open_bytes(path)  # a missing or unreadable file: its OSError, as open() gives it
    try:
        with handle as f:
            data = f.read()
    except GZIP_ERRORS as err:
        raise TapmcFormatError(path, None, f"damaged gzip file ({err})") from None
    pieces = data.split(b"\n")
    cut_short = pieces[-1].strip() != b""
    lines = []
    for i, raw in enumerate(pieces[:-1]):
        lines.append(decode_line(path, i + 1, raw[:-1] if raw.endswith(b"\r") else raw))
    return lines, cut_short


def cut_short_note(cut_short, nlines):
    """Appended to a 'nothing found' message when the only content was a line cut short."""
    return (f" (line {nlines + 1}, the last, has no end-of-line and was left out as cut short)"
            if cut_short else "")


def floats(path, lineno, fields, expected=None):
    if expected is not None and len(fields) != expected:
        raise TapmcFormatError(path, lineno, f"expected {expected} fields, found {len(fields)}")
    try:
        return [float(f) for f in fields]
    except ValueError:
        bad = next(f for f in fields if not is_float(f))
        raise TapmcFormatError(path, lineno, f"non-numeric field {bad!r}") from None


def is_float(text):
    try:
        float(text)
        return True
    except ValueError:
        return False
