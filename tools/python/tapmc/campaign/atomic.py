# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Files the campaign writes whole or not at all. The manifest, DONE.json, the input copies and
the files of a run that a resume or a finish rewrites (its per-tap file, its merged profiles)
are written to ``NAME.tmp`` in the same folder, which then replaces NAME (``os.replace``): a
kill, a full disk or a stop leaves the old file or the new one, never one cut short. A
``NAME.tmp`` left by such a write is no output of a run. An OSError names the file it was
writing (a write error of Python's own carries no path)."""

import os
import shutil
from pathlib import Path

__all__ = ["TMP_SUFFIX", "temporary", "is_temporary", "write_text", "copy_file", "named"]

#: the suffix of the files the campaign writes before they replace their target
TMP_SUFFIX = ".tmp"


def temporary(path):
    """The temporary file through which ``path`` is written."""
    path = Path(path)
    return path.with_name(path.name + TMP_SUFFIX)


def is_temporary(name):
    """True for the name of a file written by :func:`write_text` or :func:`copy_file` that
    did not replace its target (killed in between), or of an older TAPMC's DONE.json.tmp."""
    return str(name).endswith(TMP_SUFFIX)


def named(err, path):
    """``err`` (an OSError) with ``path`` as its file name when it has none."""
    if err.filename or not isinstance(err, OSError) or err.errno is None:
        return err
    return type(err)(err.errno, err.strerror or str(err), str(path))


def _discard(tmp):
    try:
        tmp.unlink()
    except OSError:
        pass


def write_text(path, text):
    """Write ``text`` to ``path`` through :func:`temporary` and ``os.replace``; on an OSError
    the target is as it was, the temporary file removed, and the error names ``path``."""
    path = Path(path)
    tmp = temporary(path)
    try:
        with open(tmp, "w") as f:
            f.write(text)
        os.replace(tmp, path)
    except OSError as err:
        _discard(tmp)
        raise named(err, path) from None


def copy_file(src, dst):
    """Copy ``src`` to ``dst`` through :func:`temporary` and ``os.replace``; on an OSError
    ``dst`` is as it was (absent if it was) and the error names the file it could not read or
    write."""
    dst = Path(dst)
    tmp = temporary(dst)
    try:
        source = open(src, "rb")
    except OSError as err:
        raise named(err, src) from None
    with source:
        try:
            with open(tmp, "wb") as out:
                shutil.copyfileobj(source, out)
            os.replace(tmp, dst)
        except OSError as err:
            _discard(tmp)
            raise named(err, dst) from None
