# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The outputs of a tapping run in a tube (examples/cylinder): its settings from the LAMMPS log,
the compaction curve of its ``taps.dat`` (``fix print``: step Phi_b <Phi^c> <Z> phi_wall
phi_core sweeps, tap 0 included) and the radial profiles of its ``profile_r.dat`` (``fix
ave/time ... mode vector`` of ``compute stereo/profile ... container ID axis r``).

* :class:`TubeSettings` (``from_log``): N, sphere radius, the container, eps, eta and the stop
  rule, seed, taps,
  and ``describe()``, the line a figure states;
* :class:`TubeCompaction` (``from_file``): the curves, eq. 3 fitted to <Phi^c>, ``plot(ax)``
  (Phi_b, <Phi^c>, the wall zone and the core against taps) and ``plot_height(ax)`` (<Z>);
* :class:`RadialProfiles` (``from_file``, ``from_ave_time``): one radial profile per written
  step, ``profile(index)`` as a :class:`tapmc.tube.TubeProfile`, ``plot(ax)``.

:mod:`tapmc.paper.tube` writes both as PNG and CSV; examples/cylinder/plot_tube.py draws them
from a run's folder.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Optional

import numpy as np

from ._legends import place_legend
from ._validate import as_1d, log_path, new_axis, require, result, same_length
from .cylinder import Cylinder
from .laws import InverseLogLaw
from .readers import read_ave_time, read_fix_print
from .tube import WALL_ZONE_OVER_R, TubeProfile

__all__ = ["TubeSettings", "TubeCompaction", "RadialProfiles", "TAPS_COLUMNS", "DEFAULT_ETA",
           "MIN_FIT_TAPS"]

#: the columns of examples/cylinder's taps.dat, in order, as its title line names them
TAPS_COLUMNS = ("step", "Phi_b", "<Phi^c>", "<Z>", "phi_wall", "phi_core", "sweeps")
#: fix mc/settle's eta when the input gives none (doc/fix_mc_settle.rst)
DEFAULT_ETA = "1e-7"
#: taps after t = 0 needed before eq. 3 (4 parameters) is fitted
MIN_FIT_TAPS = 8

# accepted names of each curve: examples/cylinder's title, then the quickstart's
_ALIASES = {"step": ("step", "tap", "TimeStep"), "Phi_b": ("Phi_b", "phi_b"),
            "<Phi^c>": ("<Phi^c>", "Phi_c", "phi_c"), "<Z>": ("<Z>", "Z"),
            "phi_wall": ("phi_wall", "wall"), "phi_core": ("phi_core", "core")}


def _number(text):
    try:
        v = float(text)
    except ValueError:
        return None
    return v if math.isfinite(v) else None


def stop_text(settle):
    """The stop rule of a fix mc/settle line's keywords (after its seed): "stop change
    (default)" or "stop drift", with its dmax when the line sets one."""
    stop = re.search(r"\bstop\s+(\S+)", settle)
    dmax = re.search(r"\bdmax\s+(\S+)", settle)
    return ((f"stop {stop.group(1)}" if stop else "stop change (default)")
            + (f", dmax {dmax.group(1)}" if dmax else ""))


@dataclass(frozen=True)
class TubeSettings:
    """What a figure of a tube run states: ``n`` spheres of radius ``sphere_radius``, the
    ``cylinder``, ``eps``, ``eta``, ``seed`` and ``taps`` (None where unknown; eta and eps as
    written in the input)."""

    n: Optional[int] = None
    sphere_radius: Optional[float] = None
    cylinder: Optional[Cylinder] = None
    eps: Optional[str] = None
    eta: Optional[str] = None
    seed: Optional[str] = None
    taps: Optional[int] = None
    #: the redeposition's stop rule and its non-default keywords (e.g. "stop change (default)",
    #: "stop drift, dmax 0.05"), from the fix mc/settle line
    stop: Optional[str] = None

    @classmethod
    def from_log(cls, path, taps=None):
        """The settings a LAMMPS log echoes after variable substitution (the last full echo of
        create_packing, fix tapdilate, fix mc/settle and the container's region); ``taps``
        overrides the last ``run N``. ``path``: the log's path, or a
        :class:`~tapmc.readers.Log` (its ``path``). A missing file gives an empty
        TubeSettings; a log whose fix mc/settle has no tube (a box run) raises ValueError."""
        path = Path(log_path(path))
        text = path.read_text(errors="replace") if path.is_file() else ""

        def last(pattern, convert=_number):
            found = [m for m in (convert(g) for g in re.findall(pattern, text, re.M))
                     if m is not None]
            return found[-1] if found else None

        packing = [m for m in re.findall(r"^create_packing\s+(\S+)\s+\S+\s+(\S+)", text, re.M)
                   if _number(m[0]) is not None and _number(m[1]) is not None]
        settle = last(r"^fix\s+\S+\s+\S+\s+mc/settle\s+(.*)$",
                      lambda s: None if "$" in s else s)
        eta = re.search(r"\beta\s+(\S+)", settle) if settle else None
        try:
            cylinder = Cylinder.from_log(path) if text else None
        except ValueError as error:
            if settle is not None:   # a run, but in a box: its settings are not a tube's
                raise ValueError(f"{path}: not a run in a tube ({error})") from None
            cylinder = None
        run = last(r"^run\s+(\S+)")
        return cls(n=int(float(packing[-1][0])) if packing else None,
                   sphere_radius=float(packing[-1][1]) if packing else None,
                   cylinder=cylinder,
                   eps=last(r"^fix\s+\S+\s+\S+\s+tapdilate\s+(\S+)",
                            lambda s: s if _number(s) is not None else None),
                   eta=(eta.group(1) if eta else DEFAULT_ETA) if settle else None,
                   seed=settle.split()[0] if settle else None,
                   taps=taps if taps is not None else (int(run) if run is not None else None),
                   stop=stop_text(settle) if settle else None)

    def with_taps(self, taps):
        return replace(self, taps=int(taps))

    @property
    def wall_zone_start(self):
        """Radius where the wall zone begins, Rc - 7R (None without the tube or R)."""
        if self.cylinder is None or self.sphere_radius is None:
            return None
        return self.cylinder.radius - WALL_ZONE_OVER_R * self.sphere_radius

    def describe(self):
        """One line: N, the tube's diameter (in bead diameters when R is known), eps, eta and
        the stop rule, seed and taps, '?' for what is unknown."""
        tube = "?"
        if self.cylinder is not None:
            tube = f"{self.cylinder.diameter:g}"
            if self.sphere_radius:
                tube += f" ({self.cylinder.radius / self.sphere_radius:g} bead diameters)"
        parts = [f"N = {self.n if self.n is not None else '?'}", f"tube D = {tube}",
                 f"eps = {self.eps or '?'}", f"eta = {self.eta or '?'}"]
        parts.append(self.stop or "stop ?")
        if self.seed is not None:
            parts.append(f"seed = {self.seed}")
        parts.append(f"{self.taps if self.taps is not None else '?'} taps")
        return ", ".join(parts)


def _column(table, name):
    for alias in _ALIASES[name]:
        if alias in table.columns:
            return table[alias]
    if list(table.columns) == [f"c{k + 1}" for k in range(len(table.columns))] \
            and len(table.columns) >= 6:   # no title line: examples/cylinder's order
        return table.data[:, TAPS_COLUMNS.index(name)]
    raise KeyError(f"{table.path}: no column {name!r} (columns {list(table.columns)}); "
                   f"expected {' '.join(TAPS_COLUMNS)}")


class TubeCompaction:
    """The compaction curve of a tube run.

    ``taps`` (the step column: one tap per step, 0 = the deposited packing), ``phi_b``,
    ``phi_c`` (<Phi^c>), ``z`` (<Z>), ``phi_wall``, ``phi_core`` (NaN where the tube has no
    core): equal lengths. ``settings``: a :class:`TubeSettings` (its taps default to the last
    tap). ``fit``: fit eq. 3 (tapmc.laws.InverseLogLaw) to <Phi^c> over t >= 1 when at least
    MIN_FIT_TAPS taps are there.

    After :meth:`compute`: ``fit_result`` (a FitResult, or None when not fitted), ``initial``
    and ``final`` (dicts of the curves at the first and last rows), ``change`` (final minus
    initial)."""

    CURVES = ("Phi_b", "<Phi^c>", "phi_wall", "phi_core")

    def __init__(self, taps, phi_b, phi_c, z, phi_wall, phi_core, settings=None, fit=True):
        self.taps = as_1d("taps", taps)
        curves = {"Phi_b": phi_b, "<Phi^c>": phi_c, "<Z>": z, "phi_wall": phi_wall,
                  "phi_core": phi_core}
        self.curves = {}
        for name, values in curves.items():
            arr = as_1d(name, values, finite=name != "phi_core")
            same_length("taps", self.taps, name, arr)
            self.curves[name] = arr
        if np.any(np.diff(self.taps) <= 0):
            raise ValueError("taps must increase (one row per tap)")
        settings = settings if settings is not None else TubeSettings()
        if not isinstance(settings, TubeSettings):
            raise ValueError(f"settings = {settings!r} must be a TubeSettings")
        self.settings = settings if settings.taps is not None else \
            settings.with_taps(int(self.taps[-1]))
        self.fit = bool(fit)
        self._initial = None

    @classmethod
    def from_file(cls, path, log=None, settings=None, fit=True):
        """From a taps.dat of examples/cylinder (``read_fix_print``; the quickstart's names
        tap/Phi_c/Z are accepted too) and the settings of ``log`` (default: log.lammps beside
        it, when present) unless ``settings`` is given; the taps are the file's last tap."""
        table = read_fix_print(path)
        if settings is None:
            log = Path(log) if log is not None else Path(path).with_name("log.lammps")
            settings = TubeSettings.from_log(log)
        return cls(*(_column(table, name) for name in
                     ("step", "Phi_b", "<Phi^c>", "<Z>", "phi_wall", "phi_core")),
                   settings=settings.with_taps(int(_column(table, "step")[-1])), fit=fit)

    def compute(self):
        after = self.taps >= 1
        self._fit = None
        if self.fit and np.count_nonzero(after) >= MIN_FIT_TAPS:
            self._fit = InverseLogLaw().fit(self.taps[after], self.curves["<Phi^c>"][after])
        self._initial = {k: float(v[0]) for k, v in self.curves.items()}
        self._final = {k: float(v[-1]) for k, v in self.curves.items()}
        self._change = {k: self._final[k] - self._initial[k] for k in self.curves}
        return self

    initial = result("_initial")

    @property
    def computed(self):
        """True once :meth:`compute` has run."""
        return self._initial is not None
    final = result("_final")
    change = result("_change")

    @property
    def fit_result(self):
        require(self, "_initial")
        return self._fit

    def plotted(self, logx=True):
        """dict name -> (taps, values) of the curves :meth:`plot` draws (t >= 1 on a log
        axis), the eq. 3 fit as 'fit:<Phi^c>'."""
        keep = self.taps >= 1 if logx else np.ones(self.taps.size, dtype=bool)
        out = {name: (self.taps[keep], self.curves[name][keep]) for name in self.CURVES
               if np.any(np.isfinite(self.curves[name][keep]))}
        if self.fit_result is not None:
            out["fit:<Phi^c>"] = (self.taps[keep], self.fit_result(self.taps[keep]))
        return out

    def plot(self, ax=None, logx=True):
        """Phi_b, <Phi^c>, the wall zone, the core (and eq. 3 fitted to <Phi^c>) against
        taps, the settings in the title. Returns the axis."""
        ax = new_axis(ax)
        labels = {"Phi_b": r"$\Phi_b$ (bottom slab, 4R)",
                  "<Phi^c>": r"$\langle\Phi^c\rangle$ (over the disk)",
                  "phi_wall": "wall zone (within 7R of the wall)", "phi_core": "core",
                  "fit:<Phi^c>": r"eq. 3 fitted to $\langle\Phi^c\rangle$"}
        for name, (t, y) in self.plotted(logx).items():
            style = dict(color="k", lw=1) if name.startswith("fit:") else dict(marker=".",
                                                                                ms=3, lw=0.6)
            ax.plot(t, y, label=labels[name], **style)
        if logx:
            ax.set_xscale("log")
        ax.set_xlabel("tap t")
        ax.set_ylabel("packing fraction")
        ax.set_title(self.settings.describe(), fontsize=8)
        place_legend(ax, fontsize=7)
        return ax

    def plot_height(self, ax=None, logx=True):
        """<Z> against taps. Returns the axis."""
        ax = new_axis(ax)
        keep = self.taps >= 1 if logx else np.ones(self.taps.size, dtype=bool)
        ax.plot(self.taps[keep], self.curves["<Z>"][keep], ".", ms=3, color="C4")
        if logx:
            ax.set_xscale("log")
        ax.set_xlabel("tap t")
        ax.set_ylabel(r"mean centre height $\langle Z\rangle$ (distance units)")
        return ax

    def __repr__(self):
        if self._initial is None:
            return f"<TubeCompaction {self.taps.size} rows: not computed>"
        i, f = self.initial, self.final
        return (f"<TubeCompaction to tap {int(self.taps[-1])}: <Phi^c> {i['<Phi^c>']:.4f} -> "
                f"{f['<Phi^c>']:.4f}, wall zone {i['phi_wall']:.4f} -> {f['phi_wall']:.4f}, "
                f"core {i['phi_core']:.4f} -> {f['phi_core']:.4f}>")


class RadialProfiles:
    """The radial profiles of a ``profile_r.dat`` (compute stereo/profile ... axis r, written
    by fix ave/time in vector mode): ``steps`` (n_t,), ``r`` (the central radii, n_r),
    ``phi_surface`` and ``phi`` (n_t, n_r: the covered fraction of the cylindrical surface at
    r and the annulus' volume fraction), ``edges`` (the annuli's radii, equal bins), and
    ``settings`` (a :class:`TubeSettings`, for the wall and the figure's title)."""

    def __init__(self, steps, r, phi_surface, phi, settings=None):
        self.steps = np.asarray(steps, dtype=int)
        self.r = as_1d("r", r)
        self.phi_surface = np.atleast_2d(np.asarray(phi_surface, dtype=float))
        self.phi = np.atleast_2d(np.asarray(phi, dtype=float))
        shape = (self.steps.size, self.r.size)
        for name, arr in (("phi_surface", self.phi_surface), ("phi", self.phi)):
            if arr.shape != shape:
                raise ValueError(f"{name} has shape {arr.shape}; steps and r give {shape}")
        if self.r.size > 1 and np.any(np.diff(self.r) <= 0):
            raise ValueError("r must increase (the annuli's central radii)")
        self.settings = settings if settings is not None else TubeSettings()

    @classmethod
    def from_ave_time(cls, table, settings=None):
        """From a vector-mode :class:`tapmc.readers.AveTime` of the compute's 3 columns
        (one tap per step: ``settings``' taps become the last step)."""
        if not getattr(table, "vector", False) or table.blocks.shape[2] < 3:
            raise ValueError("expected a vector-mode fix ave/time table with the 3 columns of "
                             "compute stereo/profile's array (axis r)")
        b = table.blocks
        if np.any(b[:, :, 0] != b[:1, :, 0]):
            raise ValueError("the radii of the rows change between steps: not one profile")
        if settings is not None:      # the taps: the last profile's step
            settings = settings.with_taps(int(table.steps[-1]))
        return cls(table.steps, b[0, :, 0], b[:, :, 1], b[:, :, 2], settings)

    @classmethod
    def from_file(cls, path, log=None, settings=None):
        """From a profile_r.dat (``read_ave_time``) and the settings of ``log`` (default:
        log.lammps beside it, when present)."""
        if settings is None:
            log = Path(log) if log is not None else Path(path).with_name("log.lammps")
            settings = TubeSettings.from_log(log)
        return cls.from_ave_time(read_ave_time(path), settings)

    @property
    def edges(self):
        if self.r.size == 1:
            lo = 0.0
            return np.array([lo, 2.0 * self.r[0] - lo])
        w = float(np.mean(np.diff(self.r)))
        return np.concatenate([[self.r[0] - 0.5 * w], self.r + 0.5 * w])

    def profile(self, index=-1):
        """The profile written at steps[index], as a :class:`tapmc.tube.TubeProfile`."""
        n = self.steps.size
        if isinstance(index, bool) or int(index) != index or not -n <= index < n:
            raise ValueError(f"index = {index!r} outside the {n} profiles of the file")
        index = int(index) % n
        return TubeProfile("r", self.r, self.phi_surface[index], self.phi[index], self.edges,
                           cylinder=self.settings.cylinder, step=int(self.steps[index]))

    def plot(self, ax=None, indices=None):
        """The annulus volume fraction against r, one curve per step (default all), the wall
        (dashed) and the start of the wall zone Rc - 7R (dotted) when known, the settings in
        the title. Returns the axis."""
        ax = new_axis(ax)
        for k in range(self.steps.size) if indices is None else indices:
            self.profile(k).plot(ax, label=f"t = {self.steps[k]}")
        start = self.settings.wall_zone_start
        if start is not None and start > 0:
            ax.axvline(start, color="0.5", lw=0.8, ls=":")
        ax.set_title(self.settings.describe(), fontsize=8)
        return ax

    def __repr__(self):
        return f"<RadialProfiles {self.r.size} annuli at steps {list(self.steps)}>"
