# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The typed results of the figure modules and their one CSV form.

Each figure module ``tapmc.paper.figN`` splits into ``analyse(...) -> FigNResult`` (numbers
and their errors, no drawing), ``plot(result)`` (drawing only) and ``draw(campaign,
out_dir)`` (both, and the two files). A result is a frozen dataclass of :class:`Series`
(a curve: x, mean, err, n per point) and :class:`Value` (one number: x, value, err, n); its
``save(path)`` writes the figure CSV of ``tapmc.paper._plotting`` (``panel, series, x, mean,
sem, n``) and its ``load(path)`` reads it back. The schema of each figure lives in its result's
``rows`` (what save writes, in order) and ``from_rows`` (what load reads); :class:`CsvRows`
here only groups the rows and refuses a file it cannot read, naming it.
"""

from __future__ import annotations

import os
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ._plotting import (FigureCsvError, FigureTable, figure_csv_rows, figure_paths,
                        save_figure)


@dataclass(frozen=True, eq=False)
class Series:
    """A curve: per point the abscissa, the mean, its error (NaN: none) and the realizations
    (seeds) behind the mean (0 for a fitted curve)."""

    x: np.ndarray
    mean: np.ndarray
    err: np.ndarray
    n: np.ndarray

    @classmethod
    def of(cls, x, mean, err=None, n=1):
        """A series from arrays or scalars (``err`` None: no error; ``n`` broadcast)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        mean = np.atleast_1d(np.asarray(mean, dtype=float))
        err = np.full(x.shape, np.nan) if err is None else np.asarray(err, dtype=float)
        return cls(x, mean, np.broadcast_to(err, x.shape).copy(),
                   np.broadcast_to(np.asarray(n), x.shape).astype(int))

    def __len__(self):
        return len(self.x)

    def stats(self):
        """(mean, err, n): the triple the figure modules pass around."""
        return self.mean, self.err, self.n


@dataclass(frozen=True)
class Value:
    """One number of a figure: its abscissa (an eps, a time, or 0), value, error (NaN: none)
    and the realizations behind it (or a 0/1 flag, as the figure's schema says)."""

    x: float
    value: float
    err: float = np.nan
    n: int = 1

    @classmethod
    def of_stats(cls, x, stats):
        """The value at ``x`` of a (mean, sem, n) triple of scalars or of one-point arrays
        (``_plotting.seed_stats``)."""
        mean, err, n = (np.atleast_1d(np.asarray(v))[0] for v in stats)
        return cls(float(x), float(mean), float(err), int(n))

    @classmethod
    def of_series(cls, series, index=0):
        return cls(float(series.x[index]), float(series.mean[index]), float(series.err[index]),
                   int(series.n[index]))

    def series(self):
        return Series.of(self.x, self.value, self.err, self.n)


@dataclass(frozen=True)
class Estimate:
    """A fitted parameter: its :class:`Value` (best value, error, n = 1 determined / 0 not)
    and the rows that qualify it, by suffix in the CSV's order (e.g. ``lo``, ``hi``: the
    68 % interval, NaN on an open side; ``jackknife``; ``range_deviation``)."""

    value: Value
    parts: dict

    def part(self, suffix):
        """The :class:`Value` of one qualifying row (None when the CSV has none)."""
        return self.parts.get(suffix)

    def rows(self, panel, key):
        return [(panel, key, self.value)] + [(panel, f"{key}:{suffix}", v)
                                             for suffix, v in self.parts.items()]

    @classmethod
    def from_rows(cls, rows, panel, key, suffixes):
        """The estimate of rows ``key`` and ``key:<suffix>`` (those of ``suffixes`` the CSV
        has)."""
        value = rows.take_value(panel, key)
        return cls(value, {s: rows.take_value(panel, f"{key}:{s}") for s in suffixes
                           if rows.has(panel, f"{key}:{s}")})


def estimates(rows, panel, prefix, names, suffixes):
    """name -> :class:`Estimate` of the rows ``<prefix><name>`` the CSV has, for ``names``."""
    return {name: Estimate.from_rows(rows, panel, prefix + name, suffixes) for name in names
            if rows.has(panel, prefix + name)}


def values(rows, panel, prefix, names):
    """name -> :class:`Value` of the one-row groups ``<prefix><name>`` the CSV has."""
    return {name: rows.take_value(panel, prefix + name) for name in names
            if rows.has(panel, prefix + name)}


class CsvRows:
    """The rows of one figure CSV grouped by (panel, series), in the order of first
    appearance; :meth:`take` hands each group to its result once, :meth:`finish` refuses rows
    no result field took (the schema would not round-trip)."""

    def __init__(self, path):
        self.path = Path(path)
        self._groups = {}
        try:
            rows = figure_csv_rows(self.path)
        except OSError as err:
            raise FigureCsvError(self.path, None,
                                 f"cannot read the figure CSV ({err.strerror or err})") from err
        for _, panel, series, x, mean, err, n in rows:
            group = self._groups.setdefault((panel, series), ([], [], [], []))
            for column, value in zip(group, (x, mean, err, n)):
                column.append(value)

    @classmethod
    def of_table(cls, path, table, partial=False):
        """The rows of a table already read, ``(panel, series) -> {"x", "mean", "sem", "n"}``
        (``_plotting.read_table``'s form, e.g. a figure's table after the report's realization
        calibration); ``path`` names their file in errors. ``partial``: rows of some fields
        only (a table built in memory, never a file): a field without rows is empty (a
        :class:`Series` of no point, a :class:`Value` of NaN with n = 0) and rows of no field
        are left."""
        rows = (_PartialRows if partial else cls).__new__(_PartialRows if partial else cls)
        rows.path = Path(path)
        rows._groups = {key: tuple(list(np.atleast_1d(d[c])) for c in ("x", "mean", "sem", "n"))
                        for key, d in table.items()}
        return rows

    def keys(self, panel=None):
        """The (panel, series) keys not yet taken, in file order (of ``panel`` only)."""
        return [k for k in self._groups if panel is None or k[0] == panel]

    def has(self, panel, series):
        return (panel, series) in self._groups

    def take(self, panel, series):
        """The :class:`Series` of one group, removed from the rows."""
        try:
            x, mean, err, n = self._groups.pop((panel, series))
        except KeyError:
            raise FigureCsvError(self.path, None, f"no rows of panel {panel!r}, series "
                                 f"{series!r}") from None
        return Series(np.array(x), np.array(mean), np.array(err), np.array(n, dtype=int))

    def take_value(self, panel, series):
        """The :class:`Value` of a one-row group."""
        s = self.take(panel, series)
        if len(s) != 1:
            raise FigureCsvError(self.path, None, f"panel {panel!r}, series {series!r} has "
                                 f"{len(s)} rows, expected one")
        return Value.of_series(s)

    def take_optional(self, panel, series):
        return self.take(panel, series) if self.has(panel, series) else None

    def together(self, *keys):
        """True when every (panel, series) of ``keys`` (rows a result writes together) is
        there, False when none is; some without the others is a damaged file, refused by
        name (read as absent, they turned a page's statement into another, silently)."""
        present = [key for key in keys if self.has(*key)]
        if present and len(present) < len(keys):
            missing = ", ".join(f"{p}/{s}" for p, s in keys if (p, s) not in present)
            there = ", ".join(f"{p}/{s}" for p, s in present)
            raise FigureCsvError(self.path, None, f"no rows of {missing}, which are written "
                                 f"with {there}")
        return bool(present)

    def finish(self):
        """Refuse the rows no field took."""
        if self._groups:
            left = ", ".join(f"{p}/{s}" for p, s in list(self._groups)[:5])
            raise FigureCsvError(self.path, None, f"rows of no field of the figure's result: "
                                 f"{left}")


class _PartialRows(CsvRows):
    """:class:`CsvRows` of a table with some fields only (:meth:`CsvRows.of_table`)."""

    def take(self, panel, series):
        if not self.has(panel, series):
            return Series.of([], [])
        return super().take(panel, series)

    def take_value(self, panel, series):
        if not self.has(panel, series):
            return Value(0.0, np.nan, np.nan, 0)
        return super().take_value(panel, series)

    def finish(self):
        """Rows of no field are left: a table in memory may hold others."""


def table_of(rows):
    """A ``FigureTable`` of (panel, series, Series or Value) triples, in order."""
    return add_rows(FigureTable(), rows)


def add_rows(table, rows):
    """Add (panel, series, Series or Value) triples to a ``FigureTable``; returns it."""
    for panel, series, data in rows:
        if isinstance(data, Value):
            data = data.series()
        table.add(panel, series, data.x, data.mean, data.err, data.n)
    return table


def save_rows(path, rows):
    """Write the figure CSV of ``rows`` (see :func:`table_of`) to ``path`` whole or not at
    all: written beside it and renamed, never left empty or cut."""
    table = table_of(rows)
    if not len(table):
        raise FigureCsvError(path, None, "a figure result without rows is not written")
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    os.close(handle)
    try:
        table.write(temporary)
        os.chmod(temporary, 0o644)      # mkstemp's 0600 is not a figure's mode
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise
    return path


class FigureResult:
    """Mixin of the figure results: ``save``/``load`` through ``rows``/``from_rows``."""

    def rows(self):  # pragma: no cover - every result defines its schema
        raise NotImplementedError

    def table(self):
        """The result as a ``FigureTable`` (the CSV's rows)."""
        return table_of(self.rows())

    def save(self, path):
        """Write the figure CSV; returns its path."""
        return save_rows(path, self.rows())

    def save_with_png(self, plot, out_dir, name, settings=None):
        """The figure's PNG (``plot(self, settings)``: ``settings`` the campaign's settings
        that it states, ``_plotting.run_settings``) and CSV in ``out_dir``, named ``name``;
        returns their paths (what every figure module's ``draw`` returns)."""
        png, csv = figure_paths(out_dir, name)
        save_figure(plot(self, settings), png)
        return png, self.save(csv)

    @classmethod
    def load(cls, path):
        """Read a figure CSV written by :meth:`save` back into the result."""
        return cls.of_rows(CsvRows(path))

    @classmethod
    def of_rows(cls, rows):
        """The result of :class:`CsvRows` (a file's or a table's), every row taken."""
        result = cls.from_rows(rows)
        rows.finish()
        return result

    def table_dict(self):
        """The result's rows as ``_plotting.read_table`` reads its CSV: ``(panel, series) ->
        {"x", "mean", "sem", "n"}`` arrays."""
        out = {}
        for panel, series, x, mean, sem, n in self.table().rows:
            d = out.setdefault((panel, series), {"x": [], "mean": [], "sem": [], "n": []})
            for key, value in (("x", x), ("mean", mean), ("sem", sem), ("n", n)):
                d[key].append(value)
        return {k: {c: np.asarray(v) for c, v in d.items()} for k, d in out.items()}
