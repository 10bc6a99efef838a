# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Pores, section IV.B of Philippe & Bideau (Figs. 9, 10): reading ``tapmc-pores`` outputs,
the distributions xi^3 P(xi) and rho_v(v) at several taps, the (xi - xi_T)^2 law between xi_T
and xi_O, the exponential tail of rho_v(v) against nu, and Gotoh's P0(sigma) with its
Percus-Yevick form.

The two distributions of the normalised pore volume v = xi^3 (section IV.B):

* ``n_v``: the number density of v, n_v(v) = P(xi) / (3 xi^2); its integral is 1;
* ``rho_v``: the paper's rho_v(v) = (xi/3) P(xi) = v n_v(v), the volume-weighted distribution
  (rho_v(v) dv = xi^3 P(xi) dxi); its integral is nu ("nu = int xi^3 P(xi) dxi =
  int rho_v(v) dv"), and it is the function of the claim rho_v(v) ~ exp(-v/nu) (Fig. 10b).

Percus-Yevick P0 (eqs. 8, 9). P0(sigma) is the probability that no sphere centre lies within
sigma R of a random point. For sigma <= 1 at most one centre can (centres are 2R apart), so
P0 = 1 - Phi sigma^3 exactly (eq. 8). For sigma >= 1 the scaled-particle / Percus-Yevick
theory (Reiss, Frisch & Lebowitz) makes -ln P0 a cubic in sigma that continues eq. 8 with its
value and first two derivatives at sigma = 1 and whose cubic coefficient is Phi times the PY
compressibility pressure, beta P / rho = (1 + Phi + Phi^2)/(1 - Phi)^3. With t = sigma - 1:

    P0 = (1 - Phi) exp{-Phi/(1 - Phi)^3 [3 (1 - Phi)^2 t + (1 - Phi)(3 + 3 Phi / 2) t^2
                                          + (1 + Phi + Phi^2) t^3]}.

Checks: continuous with eq. 8 (value, slope, curvature) at sigma = 1; P0 -> 0 as sigma grows;
at low density -ln P0 -> Phi sigma^3 (ideal gas). Eq. 9 as printed in the paper,
(1 - Phi) exp[Phi/(1 - Phi)^2 (-(1 - 2 Phi) sigma^3 + 9/2 Phi sigma^2 + 1 - sigma)], does not
meet eq. 8 at sigma = 1 (its exponent there is Phi (13 Phi/2 - 1)/(1 - Phi)^2, not 0) and grows
without bound for Phi > 1/2, so it is a misprint; the form above is the one it stands for, and
the one tapmc-pores writes in its p0 file.
"""

import csv
import json
import math
import os
import re

import numpy as np

from ._legends import place_legend
from ._validate import as_1d, in_range, new_axis, positive_int, same_length
from .fluctuations import jackknife_error
from .laws import Law
from .readers import TapmcFormatError

__all__ = ["XI_T", "XI_O", "CsvTable", "PoreOutput", "PoreDistribution", "read_pores",
           "JACKKNIFE_BLOCKS", "jackknife_error",
           "hist_is_current", "percus_yevick_p0", "TetrahedralLaw", "VolumeTail"]

#: tetrahedral site, the smallest pore: sqrt(3/2) - 1 (section IV.B)
XI_T = np.sqrt(1.5) - 1.0
#: octahedral site: sqrt(2) - 1 (section IV.B)
XI_O = np.sqrt(2.0) - 1.0


def percus_yevick_p0(sigma, phi):
    """Gotoh's P0(sigma) for hard spheres at volume fraction ``phi`` (0 <= phi < 1): eq. 8 for
    sigma <= 1, the scaled-particle / Percus-Yevick form for sigma >= 1 (module text)."""
    phi = in_range("phi", phi, 0.0, 1.0, hi_open=True)
    s = np.asarray(sigma, dtype=float)
    if np.any(s < 0) or not np.all(np.isfinite(s)):
        raise ValueError("sigma must be finite and >= 0 (sigma = r'/R)")
    t = np.maximum(s - 1.0, 0.0)
    q = 1.0 - phi
    exponent = -phi / q ** 3 * (3 * q ** 2 * t + q * (3 + 1.5 * phi) * t ** 2
                                + (1 + phi + phi ** 2) * t ** 3)
    inner = 1.0 - phi * np.minimum(s, 1.0) ** 3
    return np.where(s <= 1.0, inner, q * np.exp(exponent))


def _number(text):
    try:
        return float(text)
    except ValueError:
        return None


class CsvTable:
    """A CSV file with a header row: ``columns``, ``table[name]`` (float array when every entry
    is numeric or empty, an empty one NaN: tapmc-pores leaves nu and mean_xi empty for a frame
    without a selected pore, and P0_percus_yevick where Phi = 1; else str array), ``len(table)``,
    ``comments`` (leading '#' lines)."""

    def __init__(self, path):
        self.path = str(path)
        with open(path, newline="") as f:
            lines = f.read().splitlines()
        self.comments = []
        k = 0
        while k < len(lines) and lines[k].startswith("#"):
            self.comments.append(lines[k].lstrip("# ").strip())
            k += 1
        if k >= len(lines):
            raise TapmcFormatError(path, k + 1 if lines else None, "no CSV header row")
        rows = list(csv.reader(lines[k:]))
        self.columns = rows[0]
        body = [r for r in rows[1:] if r]
        for i, r in enumerate(body):
            if len(r) != len(self.columns):
                raise TapmcFormatError(path, k + 2 + i, f"expected {len(self.columns)} fields, "
                                       f"found {len(r)}")
        self._data = {}
        for j, name in enumerate(self.columns):
            col = [r[j] for r in body]
            nums = [math.nan if v == "" else _number(v) for v in col]
            if all(v is not None for v in nums):
                self._data[name] = np.array(nums, dtype=float)
            else:
                self._data[name] = np.array(col, dtype=str)

    def __getitem__(self, name):
        try:
            return self._data[name]
        except KeyError:
            raise KeyError(f"no column {name!r} in {self.path}; columns are "
                           f"{self.columns}") from None

    def __contains__(self, name):
        return name in self._data

    def __len__(self):
        return len(next(iter(self._data.values()))) if self._data else 0


_HIST_COLUMNS = ("xi_lo", "xi_hi", "xi", "count_xi", "P_xi", "xi3_P_xi", "v_lo", "v_hi", "v",
                 "count_v", "n_v", "rho_v")
#: columns that are densities (combined over frames by their selected pores, not summed)
_DENSITY_COLUMNS = ("P_xi", "xi3_P_xi", "n_v", "rho_v")


def _check_volume_columns(table):
    """Refuse a histogram file written before the ``n_v`` column: its ``rho_v`` column is the
    number density of v (integral 1), not the paper's rho_v(v) (integral nu)."""
    if "rho_v" in table and "n_v" not in table:
        raise TapmcFormatError(table.path, None, "written by an older tapmc-pores, whose rho_v "
                               "column is the number density of v = xi^3 (now n_v), not the "
                               "paper's rho_v(v) = v n_v(v) (section IV.B): run tapmc-pores "
                               "again on the dumps")


def hist_is_current(path):
    """True when ``path`` (a PREFIX.hist.csv) has the present columns, so that a cached output
    can be reused; False for a missing or older file."""
    try:
        with open(path) as f:
            for line in f:
                if not line.startswith("#"):
                    return line.strip().split(",") == ["bin", *_HIST_COLUMNS]
    except OSError:
        return False
    return False


#: lateral blocks per side of the spatial jackknife of one frame's distributions: 4 x 4 blocks
#: of about 7R x 7R over the paper's statistics box (28R wide at L = 32R), each holding some
#: 800 pores, far wider than the 2R over which neighbouring pores share spheres
#: (tapmc.fluctuations.jackknife_error gives the error from the replicates)
JACKKNIFE_BLOCKS = 4


def _histogram_columns(xi, xi_edges, v_edges, template):
    """The histogram columns of tapmc-pores (its .hist.csv) from the selected pores' xi: counts
    per bin, P(xi) = count / (N w), xi^3 P(xi) at the bin centre, n_v = count / (N w_v) and the
    paper's rho_v = sum of v in the bin / (N w_v)."""
    n = len(xi)
    v = xi ** 3
    w_xi, w_v = np.diff(xi_edges), np.diff(v_edges)
    count_xi = np.histogram(xi, bins=xi_edges)[0].astype(float)
    count_v = np.histogram(v, bins=v_edges)[0].astype(float)
    sum_v = np.histogram(v, bins=v_edges, weights=v)[0]
    out = {c: template[c] for c in ("xi_lo", "xi_hi", "xi", "v_lo", "v_hi", "v")}
    out.update(count_xi=count_xi, P_xi=count_xi / (n * w_xi),
               xi3_P_xi=count_xi * template["xi"] ** 3 / (n * w_xi), count_v=count_v,
               n_v=count_v / (n * w_v), rho_v=sum_v / (n * w_v))
    return out


class PoreDistribution:
    """Histograms of one set of frames: arrays ``xi``, ``xi_lo``, ``xi_hi``, ``count_xi``,
    ``P_xi``, ``xi3_P_xi`` (rho_v(xi) = xi^3 P(xi)), ``v``, ``v_lo``, ``v_hi``, ``count_v``,
    ``n_v`` (the number density of v = xi^3, integral 1), ``rho_v`` (the paper's
    rho_v(v) = v n_v(v) = (xi/3) P(xi), integral nu; module text), plus ``nu`` (mean normalised
    pore volume, exact from the pores), ``selected`` (pores) and ``timestep`` (None for the
    aggregate)."""

    def __init__(self, columns, nu, selected, timestep=None):
        for name in _HIST_COLUMNS:
            setattr(self, name, np.asarray(columns[name], dtype=float))
        self.nu = nu
        self.selected = selected
        self.timestep = timestep

    def __repr__(self):
        at = "all timesteps" if self.timestep is None else f"timestep {self.timestep}"
        return f"<PoreDistribution ({at}): {self.selected} selected pores, nu {self.nu:.4g}>"

    def tetrahedral_law(self, xi_range=None, fit_xi_t=True):
        """:class:`TetrahedralLaw` fitted to this xi^3 P(xi) with Poisson errors."""
        law = TetrahedralLaw(xi_range=xi_range, fit_xi_t=fit_xi_t)
        return law.fit(self.xi, self.xi3_P_xi, counts=self.count_xi)

    def volume_tail(self, v_range=None):
        """:class:`VolumeTail` fitted to this rho_v(v) (the paper's, not ``n_v``) with Poisson
        errors."""
        return VolumeTail(v_range=v_range).fit(self.v, self.rho_v, counts=self.count_v)

    def plot(self, ax=None, kind="xi3P", **kw):
        """xi^3 P(xi) against xi (``kind='xi3P'``, Fig. 10a) or rho_v(v) against v
        (``kind='rho_v'``, Fig. 10b)."""
        ax = new_axis(ax)
        kw.setdefault("label", "initial" if self.timestep == 0 else
                      (f"t = {self.timestep}" if self.timestep is not None else "all frames"))
        if kind == "xi3P":
            ax.plot(self.xi, self.xi3_P_xi, **kw)
            ax.set_xlabel(r"$\xi$")
            ax.set_ylabel(r"$\xi^3 P(\xi)$")
        elif kind == "rho_v":
            ax.plot(self.v, self.rho_v, **kw)
            ax.set_xlabel(r"$v = \xi^3$")
            ax.set_ylabel(r"$\rho_v(v)$")
        else:
            raise ValueError(f"kind = {kind!r} must be 'xi3P' or 'rho_v'")
        if len(ax.get_legend_handles_labels()[0]) > 1:   # several distributions drawn here
            place_legend(ax, fontsize=8)
        return ax


#: the files of one ``tapmc-pores -o PREFIX`` run, after PREFIX (frame_hist before hist: the
#: longer suffix first)
_OUTPUT_SUFFIXES = (".frame_hist.csv", ".hist.csv", ".frames.csv", ".p0.csv", ".pores.csv",
                    ".json")


class PoreOutput:
    """The output files of one ``tapmc-pores -o PREFIX`` run: ``hist`` (PREFIX.hist.csv,
    aggregate), ``frames`` (PREFIX.frames.csv), and when present ``frame_hist``
    (``--frame-hist``), ``p0`` (``--p0``), ``pores`` (``--pores``), ``json`` (``--json``, a
    dict). ``timesteps`` lists the frames' timesteps; ``distribution(timestep=None)`` gives a
    :class:`PoreDistribution` (the aggregate, or the frames of one timestep combined, e.g. over
    several dumps of different seeds, weighted by their selected pores)."""

    def __init__(self, prefix):
        self.prefix = str(prefix)
        path = lambda suffix: self.prefix + suffix  # noqa: E731
        for required in (".hist.csv", ".frames.csv"):
            if not os.path.isfile(path(required)):
                raise FileNotFoundError(f"tapmc-pores output {path(required)!r} not found")
        self.hist = CsvTable(path(".hist.csv"))
        self.frames = CsvTable(path(".frames.csv"))
        self.frame_hist = CsvTable(path(".frame_hist.csv")) \
            if os.path.isfile(path(".frame_hist.csv")) else None
        for table in (self.hist, self.frame_hist):
            if table is not None:
                _check_volume_columns(table)
        self.p0 = CsvTable(path(".p0.csv")) if os.path.isfile(path(".p0.csv")) else None
        self.pores = CsvTable(path(".pores.csv")) if os.path.isfile(path(".pores.csv")) else None
        self.json = None
        if os.path.isfile(path(".json")):
            with open(path(".json")) as f:
                self.json = json.load(f)

    @property
    def p0_phi(self):
        """The volume fraction used by the Percus-Yevick column of the p0 file (the fraction
        of random points inside a sphere, from its comment line), or None."""
        if self.p0 is None:
            return None
        for line in self.p0.comments:
            match = re.search(r"phi[^=]*=\s*([-+0-9.eE]+)", line)
            if match:
                return float(match.group(1))
        return None

    @property
    def timesteps(self):
        return sorted(set(int(s) for s in self.frames["timestep"]))

    def __repr__(self):
        return (f"<PoreOutput {self.prefix!r}: {len(self.timesteps)} timesteps, "
                f"{int(np.sum(self.frames['selected']))} selected pores>")

    @property
    def nu(self):
        """nu over all analysed frames (weighted by their selected pores; a frame without any
        has no nu, NaN, and no weight); NaN when no frame has a selected pore."""
        w = self.frames["selected"]
        if not np.sum(w) > 0:
            return math.nan
        return float(np.sum(np.where(w > 0, self.frames["nu"], 0.0) * w) / np.sum(w))

    def distribution(self, timestep=None):
        if timestep is None:
            return PoreDistribution({c: self.hist[c] for c in _HIST_COLUMNS}, self.nu,
                                    int(np.sum(self.frames["selected"])))
        if self.frame_hist is None:
            raise ValueError(f"{self.prefix}.frame_hist.csv is missing: run tapmc-pores with "
                             "--frame-hist for per-timestep distributions")
        timestep = positive_int("timestep", timestep, minimum=0)
        fsel = self.frames["timestep"] == timestep
        if not np.any(fsel):
            raise ValueError(f"timestep = {timestep!r} is not in {self.prefix}.frames.csv; "
                             f"timesteps are {self.timesteps}")
        fh = self.frame_hist
        frames = list(zip(self.frames["file"][fsel], self.frames["frame"][fsel],
                          self.frames["selected"][fsel], self.frames["nu"][fsel]))
        total = sum(f[2] for f in frames)
        combined = {}
        for file, frame, selected, _ in frames:
            rows = (fh["file"] == file) & (fh["frame"] == frame)
            for c in _HIST_COLUMNS:
                values = fh[c][rows]
                if c.startswith("count"):
                    combined[c] = combined.get(c, 0) + values
                elif c in _DENSITY_COLUMNS:
                    combined[c] = combined.get(c, 0) + values * selected / total
                else:
                    combined[c] = values
        nu = sum(f[3] * f[2] for f in frames) / total
        return PoreDistribution(combined, nu, int(total), timestep)

    def jackknife(self, timestep, blocks=JACKKNIFE_BLOCKS):
        """Leave-one-block-out replicates of ``distribution(timestep)``: the selected pores of
        the timestep's frames, split into ``blocks`` x ``blocks`` lateral blocks of the
        statistics box (x, y of their centres), each replicate built without one block. The
        spread of any statistic over them (:func:`jackknife_error`) is its error within one
        packing, where seeds give none (the paper's protocol: one run). Needs ``--pores`` and
        ``--frame-hist``."""
        if self.pores is None:
            raise ValueError(f"{self.prefix}.pores.csv is missing: run tapmc-pores with --pores "
                             "for the spatial jackknife")
        blocks = int(blocks)
        if blocks < 2:
            raise ValueError(f"blocks = {blocks}: at least 2 per side")
        full = self.distribution(timestep)
        pick = (self.pores["timestep"] == timestep) & (self.pores["selected"] == 1)
        xi = self.pores["xi"][pick]
        if len(xi) != full.selected:
            raise ValueError(f"{self.prefix}.pores.csv holds {len(xi)} selected pores at "
                             f"timestep {timestep}, the histograms {full.selected}")
        label = np.zeros(len(xi), dtype=int)
        for axis, scale in (("x", 1), ("y", blocks)):
            c = self.pores[axis][pick]
            edges = np.linspace(c.min(), c.max(), blocks + 1)
            label += scale * np.clip(np.searchsorted(edges, c, side="right") - 1, 0, blocks - 1)
        template = {c: getattr(full, c) for c in ("xi_lo", "xi_hi", "xi", "v_lo", "v_hi", "v")}
        xi_edges = np.append(full.xi_lo, full.xi_hi[-1])
        v_edges = np.append(full.v_lo, full.v_hi[-1])
        replicates = []
        for k in range(blocks * blocks):
            keep = xi[label != k]
            replicates.append(PoreDistribution(
                _histogram_columns(keep, xi_edges, v_edges, template),
                float(np.mean(keep ** 3)), len(keep), timestep))
        return replicates


def read_pores(path, prefix=None):
    """Open the outputs of ``tapmc-pores -o PREFIX``. ``path`` is the prefix itself (e.g.
    ``out/fig10``), one of its files (``out/fig10.hist.csv``, ``.frames.csv``, ...) or a
    directory holding exactly one ``*.hist.csv`` (or give ``prefix``, the file-name prefix
    inside that directory)."""
    path = os.fspath(path)
    for suffix in _OUTPUT_SUFFIXES:
        if path.endswith(suffix) and os.path.isfile(path):
            path = path[:-len(suffix)]
            break
    if os.path.isdir(path):
        if prefix is None:
            hists = sorted(f for f in os.listdir(path) if f.endswith(".hist.csv"))
            if len(hists) != 1:
                raise ValueError(f"{path!r} holds {len(hists)} tapmc-pores outputs "
                                 f"({', '.join(hists) or 'none'}); give prefix")
            prefix = hists[0][:-len(".hist.csv")]
        return PoreOutput(os.path.join(path, prefix))
    return PoreOutput(path)


def _poisson_sigma(x_power, values, counts):
    """1-sigma errors of a histogram density from its bin counts: value per count times
    sqrt(count), one count for empty bins (so that they weigh, not vanish). The value per count
    is x^k times a constant (the normalisation), estimated from the non-empty bins: x^3 for
    xi^3 P(xi) against the counts of xi; x = v for rho_v(v) against the counts of v (a bin of
    rho_v is the sum of its pores' v over N w, so each pore adds about v / (N w) and the
    Poisson error of c pores is about v sqrt(c) / (N w)); x^0 for P(xi) or n_v(v)."""
    counts = np.asarray(counts, dtype=float)
    full = counts > 0
    if not np.any(full):
        raise ValueError("every bin is empty")
    per_count = np.median(values[full] / counts[full] / x_power[full])
    return np.maximum(per_count * x_power, 1e-300) * np.sqrt(np.maximum(counts, 1.0))


def _bin_errors(x_name, x, values, counts, sigma, x_power):
    """The errors of a histogram's bins for a fit: ``sigma`` (one value or one per bin), else
    Poisson from ``counts`` (one per bin, :func:`_poisson_sigma`), else None; lengths checked
    against the bins of ``x`` by name."""
    if sigma is not None:
        s = np.asarray(sigma, dtype=float)
        if s.ndim > 1 or s.size not in (1, x.size):
            raise ValueError(f"sigma has {s.size} values; give one or one per bin of {x_name} "
                             f"({x.size})")
        return np.broadcast_to(s.reshape(-1) if s.ndim else s, x.shape)
    if counts is None:
        return None
    counts = as_1d("counts", counts)
    same_length(x_name, x, "counts", counts)
    if np.any(counts < 0):  # a count is a number of pores; max(count, 1) would hide a sign
        bad = int(np.flatnonzero(counts < 0)[0])
        raise ValueError(f"counts[{bad}] = {counts[bad]:g} is negative: counts are the "
                         f"numbers of pores per bin of {x_name} (>= 0)")
    return _poisson_sigma(x_power, values, counts)


class TetrahedralLaw(Law):
    """xi^3 P(xi) = a (xi - xi_T)^2 for xi_T <= xi <= xi_O, zero below xi_T (section IV.B).
    Parameters ``a`` and ``xi_T`` (``fit_xi_t=True``, to test that the smallest pores are
    tetrahedral sites, xi_T = sqrt(3/2) - 1) or ``a`` alone with xi_T fixed at that value.
    ``xi_range`` (default (0.15, xi_O)) selects the bins; below xi_T they hold no pore and fix
    xi_T."""

    x_label = "xi = r/R"
    y_label = "xi^3 P(xi)"

    def __init__(self, xi_range=None, fit_xi_t=True):
        lo, hi = xi_range if xi_range is not None else (0.15, XI_O)
        if not (0 <= lo < hi):
            raise ValueError(f"xi_range = {xi_range!r} must be (lo, hi) with 0 <= lo < hi")
        self.xi_range = (float(lo), float(hi))
        self.fit_xi_t = bool(fit_xi_t)
        self.names = ("a", "xi_T") if self.fit_xi_t else ("a",)

    def function(self, xi, a, xi_t=XI_T):
        return a * np.maximum(xi - xi_t, 0.0) ** 2

    def bounds(self, x, y):
        return ([0.0, 0.0], [np.inf, self.xi_range[1]]) if self.fit_xi_t else ([0.0], [np.inf])

    def initial_guess(self, xi, y, w):
        nonzero = xi[y > 0]
        xi_t = nonzero.min() if nonzero.size else XI_T
        xi_t = min(xi_t, 0.5 * (self.xi_range[0] + self.xi_range[1])) if self.fit_xi_t else XI_T
        d2 = np.maximum(xi - xi_t, 0.0) ** 2
        a = np.sum(w * d2 * y) / max(np.sum(w * d2 * d2), 1e-300)
        return [a, xi_t] if self.fit_xi_t else [a]

    def fit(self, xi, xi3_p, counts=None, sigma=None, p0=None):
        xi = as_1d("xi", xi)
        xi3_p = as_1d("xi3_P_xi", xi3_p)
        same_length("xi", xi, "xi3_P_xi", xi3_p)
        sel = (xi >= self.xi_range[0]) & (xi <= self.xi_range[1])
        s = _bin_errors("xi", xi, xi3_p, counts, sigma, xi ** 3)
        return super().fit(xi[sel], xi3_p[sel], None if s is None else s[sel], p0)


class VolumeTail(Law):
    """rho_v(v) = c exp(-v / nu_tail) over the tail of the volume distribution (section IV.B:
    "compatible with a Poisson law exp(-v/nu)", nu the mean normalised pore volume), rho_v the
    paper's rho_v(v) = v n_v(v) (module text; fitting the number density n_v instead gives a
    shorter decay, since n_v = rho_v / v). Parameters ``c`` and ``nu_tail``; ``v_range``
    defaults to (xi_O^3, largest non-empty v). With ``counts`` (the counts of v, ``count_v``)
    the errors are Poisson: sigma of a bin about v sqrt(count) / (N w). Compare ``nu_tail``
    with the distribution's ``nu``."""

    x_label = "v = xi^3"
    y_label = "rho_v(v)"

    names = ("c", "nu_tail")

    def __init__(self, v_range=None):
        if v_range is not None:
            try:
                lo, hi = (float(b) for b in v_range)
            except (TypeError, ValueError):
                lo, hi = np.nan, np.nan
            if not (0 <= lo < hi):
                raise ValueError(f"v_range = {v_range!r} must be (lo, hi) with 0 <= lo < hi")
            v_range = (lo, hi)
        self.v_range = v_range

    @staticmethod
    def function(v, c, nu_tail):
        return c * np.exp(-v / nu_tail)

    def bounds(self, x, y):
        return ([0.0, 0.0], [np.inf, np.inf])

    def initial_guess(self, v, y, w):
        pos = y > 0
        if pos.sum() >= 2:
            slope, intercept = np.polyfit(v[pos], np.log(y[pos]), 1)
            if slope < 0:
                return [np.exp(intercept), -1.0 / slope]
        return [max(y.max(), 1e-300), max(np.ptp(v), 1e-3)]

    def fit(self, v, rho_v, counts=None, sigma=None, p0=None):
        v = as_1d("v", v)
        rho_v = as_1d("rho_v", rho_v)
        same_length("v", v, "rho_v", rho_v)
        if self.v_range is None:
            nonzero = v[rho_v > 0]
            lo, hi = XI_O ** 3, (nonzero.max() if nonzero.size else v.max())
        else:
            lo, hi = self.v_range
        sel = (v >= lo) & (v <= hi)
        s = _bin_errors("v", v, rho_v, counts, sigma, v)
        return super().fit(v[sel], rho_v[sel], None if s is None else s[sel], p0)
