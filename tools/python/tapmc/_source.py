# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Where this package runs from: TAPMC's source tree, or an install (``cmake --install``, a
venv, a wheel) that has none. The paper's tools default to the tree's ``doc/`` and
``examples/``, and record the tree's ``git describe``; an installed package must neither
write into its prefix (``PREFIX/lib`` sits where the tree's root would) nor describe a git
repository that merely contains the prefix or the venv (a project's ``.venv``)."""

from pathlib import Path

__all__ = ["source_tree", "git_checkout"]

_PACKAGE = Path(__file__).resolve().parent
#: tools/python/tapmc -> the root of the source tree, when there is one
_ROOT = _PACKAGE.parents[2]


def source_tree():
    """The root of the TAPMC source tree this package is part of (its ``tools/python/tapmc``
    is this very package, beside the top ``CMakeLists.txt``), else None."""
    try:
        mine = (_ROOT / "tools" / "python" / "tapmc").resolve() == _PACKAGE
    except OSError:
        return None
    return _ROOT if mine and (_ROOT / "CMakeLists.txt").is_file() else None


def git_checkout():
    """:func:`source_tree` when it is a git checkout (its own ``.git``, as the build's id
    requires), else None: only then does ``git -C`` describe TAPMC and not an enclosing
    repository."""
    root = source_tree()
    return root if root is not None and (root / ".git").exists() else None
