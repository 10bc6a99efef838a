# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Private helpers shared by the analysis classes: argument validation that names the
parameter, its value and the allowed range, and result properties that refuse to be read before
``compute()`` / ``fit()``."""

import os

import numpy as np


class NotComputedError(RuntimeError):
    """A result property was read before the method that computes it."""


def require(obj, attr, method="compute"):
    """Return ``obj.<attr>`` or raise NotComputedError naming the method to call first."""
    value = getattr(obj, attr, None)
    if value is None:
        raise NotComputedError(
            f"{type(obj).__name__}: call {method}() before reading this result")
    return value


def float_array(name, values):
    """``values`` as a float array, or ValueError naming ``name`` (not numpy's bare message)."""
    try:
        return np.asarray(values, dtype=float)
    except (TypeError, ValueError) as error:
        raise ValueError(f"{name} must hold numbers: {error}") from None


def as_1d(name, values, min_len=1, finite=True):
    """A 1-D float array of at least ``min_len`` entries (all finite if ``finite``)."""
    arr = float_array(name, values)
    if arr.ndim != 1:
        raise ValueError(f"{name} must be one-dimensional, got shape {arr.shape}")
    if arr.size < min_len:
        raise ValueError(f"{name} needs at least {min_len} values, got {arr.size}")
    if finite and not np.all(np.isfinite(arr)):
        bad = int(np.flatnonzero(~np.isfinite(arr))[0])
        raise ValueError(f"{name}[{bad}] = {arr[bad]} is not finite (all values must be)")
    return arr


def as_2d(name, values, min_rows=1, min_cols=1):
    arr = float_array(name, values)
    if arr.ndim != 2:
        raise ValueError(f"{name} must be two-dimensional (realizations x taps), "
                         f"got shape {arr.shape}")
    if arr.shape[0] < min_rows or arr.shape[1] < min_cols:
        raise ValueError(f"{name} has shape {arr.shape}; needs at least {min_rows} rows "
                         f"and {min_cols} columns")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} holds non-finite values (all values must be finite)")
    return arr


def same_length(name_a, a, name_b, b):
    if len(a) != len(b):
        raise ValueError(f"{name_a} has {len(a)} values but {name_b} has {len(b)}; "
                         "they must have the same length")


def positive_int(name, value, minimum=1):
    try:
        whole = not isinstance(value, bool) and int(value) == value
    except (TypeError, ValueError, OverflowError):  # None, text, NaN, infinity
        whole = False
    if not whole or value < minimum:
        raise ValueError(f"{name} = {value!r} must be an integer >= {minimum}")
    return int(value)


def log_path(path, caller="from_log"):
    """The path of a LAMMPS log given as a path or as a :class:`~tapmc.readers.Log` (which
    carries the path it was read from); TypeError for anything else."""
    path = getattr(path, "path", path)
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"{caller} takes a log's path or a Log, got {type(path).__name__}")
    return path


def positive(name, value, allow_zero=False):
    v = float(value)
    if not np.isfinite(v) or v < 0 or (v == 0 and not allow_zero):
        rng = ">= 0" if allow_zero else "> 0"
        raise ValueError(f"{name} = {value!r} must be finite and {rng}")
    return v


def in_range(name, value, lo, hi, lo_open=False, hi_open=False):
    v = float(value)
    ok = np.isfinite(v) and (v > lo if lo_open else v >= lo) and (v < hi if hi_open else v <= hi)
    if not ok:
        left = "(" if lo_open else "["
        right = ")" if hi_open else "]"
        raise ValueError(f"{name} = {value!r} must lie in {left}{lo}, {hi}{right}")
    return v


def choice(name, value, allowed):
    if value not in allowed:
        raise ValueError(f"{name} = {value!r} must be one of {sorted(allowed)}")
    return value


def new_axis(ax):
    """The given matplotlib axis, or a new figure's axis on the user's backend: never switched
    (a switch closes the user's open figures); without a display matplotlib itself picks Agg."""
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt
    _, ax = plt.subplots()
    return ax


def computed_repr(obj, attr, inputs, results):
    """``<Class inputs: results>`` once ``obj.<attr>`` is set (``results()`` formats them),
    ``<Class inputs: not computed>`` before."""
    done = getattr(obj, attr, None) is not None
    return f"<{type(obj).__name__} {inputs}: {results() if done else 'not computed'}>"


def result(attr, method="compute", doc=None):
    """A read-only property returning ``self.<attr>``, or raising NotComputedError before
    ``method()`` has set it."""
    return property(lambda self: require(self, attr, method), doc=doc)
