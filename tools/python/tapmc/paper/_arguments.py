# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Argument types of the tapmc-paper command line: each refuses a bad value with a one-line
usage error (exit 2) that names it."""

from __future__ import annotations

import argparse
from pathlib import Path


def positive_int(text):
    """An integer >= 1 (runs at a time, seeds, spheres, taps)."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"{value} is not >= 1")
    return value


def folder(text):
    """A folder path; an empty one is refused: Path('') is the current folder, so an unset shell
    variable (--campaign "$DIR") would make the working directory a campaign."""
    if not str(text).strip():
        raise argparse.ArgumentTypeError("an empty path (an unset shell variable?); give a "
                                         "folder, e.g. ./tapmc-paper-quick")
    return Path(text)
