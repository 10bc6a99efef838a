# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""sigma_<Z> and the steady packing against the redeposition threshold eta.

Fig. 3 (section III.B) has sigma_<Z> proportional to sqrt(eps). The campaign at the default
threshold finds it nearly flat with an offset (sigma_<Z> = offset + slope sqrt(eps), offset
> 0). Two readings: the offset is the model's, or it is settling noise that a tighter
redeposition removes. The paper gives no threshold, so the question is decided by measurement:
the same constant-eps runs at other thresholds (``consteta_*`` runs, tier 8 of
:mod:`tapmc.paper.plan`) beside the default ones (``const_*``), and per eta:

- sigma_<Z> and <Phi^c> of the steady state (the last quarter of each run, as Figs. 3 and 4)
  per eps, mean and standard error over seeds (one seed: batch means of the run itself), on
  the page never below the runs' batch-means errors times the campaign's realizations'
  factor of the quantity (:func:`calibrated`);
- the straight line sigma_<Z> = offset + slope sqrt(eps) through them (weighted; errors
  scaled by the reduced chi-square when the scatter exceeds them);
- the same for sigma_<Z> about each run's straight line over its window (``sigma_linear``):
  a run still compacting (or loosening) in its last quarter counts its drift as fluctuation
  in the paper's sigma_<Z>, so the two tell the offset's fluctuation from its drift (the line
  also takes out part of the slowest fluctuations: a lower estimate);
- the largest steady <Phi^c> over the eps (the bell's top), against the paper's 60.6 %
  (section III.D, after 4000 taps).

The answer (:func:`finding_text`): whether the offset shrinks as eta tightens (the tightest
threshold's offset below the loosest one's beyond t times their combined error), and which
eta's bell top meets 60.6 %. A run still going counts once it holds ``MIN_STEADY_TAPS`` taps of
its protocol's steady window (the last quarter of the taps the campaign's manifest plans for it:
taps 3001-4000 of a 4000-tap run, never the last quarter of the taps it has so far, when the
packing still compacts); the table says how many taps each point had. :func:`write_figure`
draws both against sqrt(eps), a colour per eta, beside the table (``sigma_eta.png``).

  /usr/bin/python3 -m tapmc.paper sigma-eta --campaign DIR --out doc/paper_scale
"""

from __future__ import annotations

import csv
import math
import re
from dataclasses import asdict, dataclass, fields, replace
from pathlib import Path

import numpy as np

from tapmc.campaign.provenance import read_manifest
from tapmc.fluctuations import DEFAULT_BATCHES, SteadyState
from tapmc.stats import beyond, realization_factor, t_quantile, weighted_line_fit

from . import _plotting, _runs
from ._steady_state import BC, sigma_error_one_run, steady_last
from .scales import FULL

CSV_NAME = "sigma_eta.csv"
PNG_NAME = "sigma_eta.png"
#: The paper's steady packing fraction after 4000 taps (section III.D, Fig. 9), in percent.
PAPER_PHI_PERCENT = 60.6
#: A run counts once its steady window (the last quarter) holds this many taps: the batch
#: means of a shorter window have too few taps per batch to stand for a correlated series
#: (the campaign's runs decorrelate within tens of taps, Fig. 3's spectra).
MIN_STEADY_TAPS = 250
#: What the command reads, for its message when a campaign has none of it.
RUNS_READ = f"P.B.C. constant-eps runs with {MIN_STEADY_TAPS} steady taps"
NAME = re.compile(rf"^(?:{re.escape(_runs.CONSTANT_ETA_PREFIX)}(?P<bc1>pbc|fbc)_eps"
                  r"(?P<eps1>[0-9.e+-]+)_eta(?P<eta>[0-9.e+-]+)|const_(?P<bc0>pbc|fbc)_eps"
                  r"(?P<eps0>[0-9.e+-]+))_s(?P<seed>\d+)$")


@dataclass(frozen=True)
class RunSteady:
    """The steady state of one run: sigma_<Z> (about the window's mean, the paper's
    definition) with its batch-means error, and <Phi^c> with its batch-means error."""

    run: str
    eta: float
    eps: float
    seed: int
    taps: int
    finished: bool
    sigma: float
    sigma_err: float
    phi_c: float
    phi_c_err: float
    sigma_linear: float
    sigma_linear_err: float


@dataclass(frozen=True)
class EtaPoint:
    """One (eta, eps): means over the seeds' runs with their errors (one run: its own
    batch-means errors); ``*_inside``: the root mean square of the runs' own batch-means
    errors over sqrt(seeds), the floor of the errors (:func:`_mean_sem`), which the
    realizations' factors scale (:func:`calibrated`); ``sigma_linear*``: sigma_<Z> about each
    run's straight line over its window, likewise."""

    eta: float
    eps: float
    seeds: int
    taps: int  # the fewest taps among the runs (a run still going has fewer than planned)
    finished: bool
    sigma: float
    sigma_sem: float
    phi_c: float
    phi_c_sem: float
    sigma_inside: float
    phi_c_inside: float
    sigma_linear: float
    sigma_linear_sem: float
    sigma_linear_inside: float

    @property
    def sqrt_eps(self):
        return math.sqrt(self.eps)


@dataclass(frozen=True)
class EtaLine:
    """sigma_<Z> = offset + slope sqrt(eps) at one eta (None when fewer than 3 eps), and
    the bell's top: the largest steady <Phi^c> over the eps, at ``top_eps``; ``top_inside``
    when eps on both sides of it were measured (a top the data show, not the edge of the eps
    done so far)."""

    eta: float
    eps_count: int
    offset: float
    offset_err: float
    slope: float
    slope_err: float
    dof: int | None
    top_eps: float
    top_phi_c: float
    top_phi_c_sem: float
    top_inside: bool = True


def steady_window(taps, planned=None):
    """Taps of a run's steady window that it has: the last quarter of its ``planned`` taps
    (:func:`steady_last`, as for a finished run), of which a run still going has the taps past
    the window's start (0 before it); without a plan, the last quarter of ``taps``."""
    if planned is None or taps >= planned:
        return steady_last(taps) if taps else 0
    return max(0, taps - (planned - steady_last(planned)))


def read_run(run_dir, default_eta, planned_taps=None):
    """The :class:`RunSteady` of one ``const_*`` / ``consteta_*`` run directory, or None when
    it holds fewer than ``MIN_STEADY_TAPS`` taps of its steady window (:func:`steady_window`;
    ``planned_taps``: the run's taps in the campaign's plan, None when unknown). A tap written
    twice (a run resumed from a restart) counts once, with its last row."""
    run_dir = Path(run_dir)
    m = NAME.match(run_dir.name)
    if not m:
        raise ValueError(f"run directory {run_dir.name!r} is not a constant-eps run "
                         f"(const_<bc>_eps<eps>_s<seed> or "
                         f"{_runs.CONSTANT_ETA_PREFIX}<bc>_eps<eps>_eta<eta>_s<seed>)")
    z, phi_c = _runs.run_taps(run_dir / "taps.dat", ("Z", "phi_c"))
    taps = len(z)
    window = steady_window(taps, planned_taps)
    if window < MIN_STEADY_TAPS:
        return None
    sigma = SteadyState(z, last=window).compute().std
    sigma_linear = SteadyState(z, last=window, detrend="linear").compute().std
    packing = SteadyState(phi_c, last=window).compute()
    eta = float(m.group("eta")) if m.group("eta") else float(default_eta)
    return RunSteady(run=run_dir.name, eta=eta, eps=float(m.group("eps0") or m.group("eps1")),
                     seed=int(m.group("seed")), taps=taps,
                     finished=(run_dir / "DONE.json").exists(), sigma=sigma,
                     sigma_err=sigma_error_one_run(z, window), phi_c=packing.mean,
                     phi_c_err=packing.sem, sigma_linear=sigma_linear,
                     sigma_linear_err=sigma_error_one_run(z, window, detrend="linear"))


def _mean_sem(values, own_err):
    """(mean over the seeds, its standard error, the floor inside the runs); one seed: its own
    error, twice. With a few seeds the spread can fall far below the runs' own batch-means
    errors by chance (3 seeds: 1 time in 20 below a third of it), so the error is never below
    their root mean square over sqrt(seeds), the same variance measured inside the runs (the
    floor)."""
    values, own_err = np.asarray(values, dtype=float), np.asarray(own_err, dtype=float)
    if len(values) == 1:
        return float(values[0]), float(own_err[0]), float(own_err[0])
    spread = float(values.std(ddof=1) / math.sqrt(len(values)))
    inside = float(np.sqrt(np.mean(own_err ** 2)) / math.sqrt(len(values)))
    return (float(values.mean()), max(spread, inside) if np.isfinite(inside) else spread,
            inside)


def points(runs):
    """The :class:`EtaPoint` of every (eta, eps) of ``runs``, sorted by eta (loosest first)
    then eps."""
    groups = {}
    for r in runs:
        groups.setdefault((r.eta, r.eps), []).append(r)
    out = []
    for (eta, eps), group in groups.items():
        sigma, sigma_sem, sigma_in = _mean_sem([r.sigma for r in group],
                                               [r.sigma_err for r in group])
        phi, phi_sem, phi_in = _mean_sem([r.phi_c for r in group], [r.phi_c_err for r in group])
        flat, flat_sem, flat_in = _mean_sem([r.sigma_linear for r in group],
                                            [r.sigma_linear_err for r in group])
        out.append(EtaPoint(eta=eta, eps=eps, seeds=len(group), taps=min(r.taps for r in group),
                            finished=all(r.finished for r in group), sigma=sigma,
                            sigma_sem=sigma_sem, phi_c=phi, phi_c_sem=phi_sem,
                            sigma_inside=sigma_in, phi_c_inside=phi_in, sigma_linear=flat,
                            sigma_linear_sem=flat_sem, sigma_linear_inside=flat_in))
    return sorted(out, key=lambda p: (-p.eta, p.eps))


def analyse(campaign, default_eta, bc=BC):
    """The points of every constant-eps run of ``bc`` in the campaign directory (its runs/
    folder) with a steady window long enough, at every eta; each run's planned taps come from
    the campaign's manifest.json (a run it does not list is judged on the taps it has)."""
    runs_dir = Path(campaign) / "runs"
    planned = {r.get("name"): r.get("taps") for r in read_manifest(campaign).get("runs", [])
               if isinstance(r, dict)}
    found = []
    for d in sorted(runs_dir.glob(f"*_{bc}_eps*_s*")):
        if not NAME.match(d.name) or not (d / "taps.dat").exists():
            continue
        run = read_run(d, default_eta, planned.get(d.name))
        if run is not None:
            found.append(run)
    return points(found)


def line(eta_points, sigma="sigma"):
    """The :class:`EtaLine` of the points of one eta (``sigma``: the field fitted, "sigma"
    the paper's, "sigma_linear" about each run's straight line)."""
    eta = eta_points[0].eta
    if any(p.eta != eta for p in eta_points):
        raise ValueError("line(): the points must share one eta")
    top = max(eta_points, key=lambda p: p.phi_c)
    offset, offset_err, slope, slope_err, dof = weighted_line_fit(
        [p.sqrt_eps for p in eta_points], [getattr(p, sigma) for p in eta_points],
        [getattr(p, f"{sigma}_sem") for p in eta_points])
    measured = [p.eps for p in eta_points]
    return EtaLine(eta=eta, eps_count=len(eta_points), offset=offset, offset_err=offset_err,
                   slope=slope, slope_err=slope_err, dof=dof, top_eps=top.eps,
                   top_phi_c=top.phi_c, top_phi_c_sem=top.phi_c_sem,
                   top_inside=min(measured) < top.eps < max(measured))


def lines(all_points, sigma="sigma"):
    """One :class:`EtaLine` per eta, loosest threshold first (``sigma``: as :func:`line`)."""
    etas = sorted({p.eta for p in all_points}, reverse=True)
    return [line([p for p in all_points if p.eta == eta], sigma) for eta in etas]


@dataclass(frozen=True)
class OffsetTrend:
    """The offset's change from the loosest to the tightest threshold (tightest minus
    loosest) with its error; ``shrinks`` when the change is negative beyond t times its error
    (dof: the smaller of the two fits'), ``grows`` when positive beyond it."""

    loose_eta: float
    tight_eta: float
    change: float
    change_err: float
    dof: int | None

    @property
    def shrinks(self):
        return self.change < 0 and beyond(self.change, self.change_err, self.dof)

    @property
    def grows(self):
        return self.change > 0 and beyond(self.change, self.change_err, self.dof)


def offset_trend(eta_lines):
    """The :class:`OffsetTrend` between the loosest and the tightest eta whose lines were
    fitted, or None with fewer than two such etas."""
    fitted = [ln for ln in eta_lines if ln.dof is not None]
    if len(fitted) < 2:
        return None
    loose, tight = max(fitted, key=lambda ln: ln.eta), min(fitted, key=lambda ln: ln.eta)
    return OffsetTrend(loose_eta=loose.eta, tight_eta=tight.eta,
                       change=tight.offset - loose.offset,
                       change_err=math.hypot(loose.offset_err, tight.offset_err),
                       dof=min(loose.dof, tight.dof))


#: Degrees of freedom of a point's error floor (the runs' batch means, 20 batches; the
#: realizations' factor that scales it is estimated with as many): a point's error is never
#: below that floor, so the t of a verdict on it takes these dof. The seeds' own spread, when
#: larger, stays the error, but not its dof: with two seeds, t of 1 dof (12.7) would let a top
#: four errors from the paper's value meet it.
ERROR_FLOOR_DOF = DEFAULT_BATCHES - 1


def meets_paper_phi(eta_line):
    """Whether the bell's top of one eta meets the paper's 60.6 %: within t times its error
    (t of :data:`ERROR_FLOOR_DOF`) plus half a unit of the paper's last digit (0.05 %)."""
    band = t_quantile(ERROR_FLOOR_DOF) * 100.0 * eta_line.top_phi_c_sem + 0.05
    return abs(100.0 * eta_line.top_phi_c - PAPER_PHI_PERCENT) <= band


def write_csv(rows, path):
    """The points, one row each, written whole to a temporary file and renamed."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(path.suffix + ".tmp")
    with open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=[fl.name for fl in fields(EtaPoint)])
        w.writeheader()
        for r in rows:
            w.writerow(asdict(r))
    tmp.replace(path)
    return path


def read_csv(path):
    """The rows of :func:`write_csv` as :class:`EtaPoint` (types restored); a file whose
    header is not :class:`EtaPoint`'s fields raises ValueError naming the file."""
    kinds = {fl.name: fl.type for fl in fields(EtaPoint)}
    convert = {"float": float, "int": int, "bool": lambda v: v == "True"}
    with open(path) as f:
        reader = csv.DictReader(f)
        if reader.fieldnames != list(kinds):
            raise ValueError(f"{path}: header {reader.fieldnames} is not {list(kinds)}")
        return [EtaPoint(**{k: convert[kinds[k]](v) for k, v in row.items()}) for row in reader]


#: The one-run errors whose realizations' factors scale a point's error floor (ReportData's
#: run_error quantities): sigma_<Z> and the window mean of <Phi^c>.
ERROR_QUANTITIES = {"sigma": "Z:sigma", "phi_c": "phi_c", "sigma_linear": "Z:sigma"}
#: How the text and the figure name those quantities (sigma_linear takes sigma_<Z>'s factor
#: and is not named apart).
ERROR_NAMES = {"sigma": "sigma_<Z>", "phi_c": "<Phi^c>"}


def errors_from_report(data):
    """The ``factor_of`` of :func:`finding_text` from a report's
    :class:`~tapmc.paper.claims.ReportData`: (quantity, eps) -> its realizations' factor for a
    P.B.C. run at that eps (1 when the campaign's seeds do not reject the runs' own errors)."""
    return lambda quantity, eps: data.run_error(quantity, "pbc", eps)[0]


def calibrated(all_points, factor_of):
    """The points with the floor of their errors (``*_inside``: one seed's own batch-means
    error, several seeds' root mean square of theirs over sqrt(seeds)) times its realizations'
    factor (``factor_of(quantity, eps)``, :data:`ERROR_QUANTITIES`): one run's batch-means
    errors are those of its own time average, and another realization lands about that factor
    of them away (the campaign's groups of seeds); a spread of the seeds above the scaled floor
    stays. Returns (points, {quantity: (smallest, largest) factor applied}); ``factor_of``
    None leaves the points as they are."""
    if factor_of is None:
        return list(all_points), {}
    out, used = [], {}
    for p in all_points:
        scaled = {}
        for field, quantity in ERROR_QUANTITIES.items():
            k = realization_factor(factor_of(quantity, p.eps),
                                   f"factor of {quantity} at eps = {p.eps:g}")
            floor = getattr(p, f"{field}_inside") * k
            scaled[f"{field}_sem"] = max(getattr(p, f"{field}_sem"), floor)
            scaled[f"{field}_inside"] = floor
            if field in ERROR_NAMES:
                lo, hi = used.get(field, (k, k))
                used[field] = (min(lo, k), max(hi, k))
        out.append(replace(p, **scaled))
    return out, used


def _errors_text(used):
    """How the finding's errors were made (:func:`calibrated`'s factors)."""
    if all(hi == 1.0 for _, hi in used.values()):  # none, or seeds that reject no error
        return "mean +- sem over seeds; one seed: its batch means"
    factors = ", ".join(f"{ERROR_NAMES[q]} x {lo:.1f}" + (f"-{hi:.1f}" if hi - lo >= 0.05 else "")
                        for q, (lo, hi) in used.items())
    return ("mean +- sem over seeds, never below the runs' batch-means errors times the "
            f"spread of the campaign's realizations ({factors}); one seed: that error")


def _eta_text(eta):
    return f"{eta:.0e}".replace("e-0", "e-")


def finding_text(all_points, default_eta, factor_of=None):
    """One paragraph: per eta, the line through sigma_<Z> and the bell's top; then whether the
    offset shrinks as eta tightens and which eta meets the paper's 60.6 %. ``factor_of``: the
    realizations' factors the errors of one-seed points take (:func:`calibrated`,
    :func:`errors_from_report`), said in the text; None: the runs' own errors."""
    if not all_points:
        return ""
    all_points, used = calibrated(all_points, factor_of)
    eta_lines = lines(all_points)
    parts = []
    for ln in eta_lines:
        label = f"eta = {_eta_text(ln.eta)}" + (" (the default)" if ln.eta == default_eta
                                                  else "")
        fit = (f"sigma_<Z> = {ln.offset:.4f} +- {ln.offset_err:.4f} + ({ln.slope:.4f} +- "
               f"{ln.slope_err:.4f}) sqrt(eps) over {ln.eps_count} eps"
               if ln.dof is not None else f"{ln.eps_count} eps (too few for a line)")
        top = (f"bell top <Phi^c> = {100 * ln.top_phi_c:.2f} +- {100 * ln.top_phi_c_sem:.2f} % "
               f"at eps = {ln.top_eps:g}"
               + (" (meets 60.6 %)" if meets_paper_phi(ln) else "")
               if ln.top_inside else
               f"largest <Phi^c> {100 * ln.top_phi_c:.2f} +- {100 * ln.top_phi_c_sem:.2f} % at "
               f"eps = {ln.top_eps:g}, the edge of the eps measured: no top yet")
        parts.append(f"{label}: {fit}; {top}{_going_text(all_points, ln.eta)}")
    verdict = _trend_text(offset_trend(eta_lines))
    meeting = [ln.eta for ln in eta_lines if ln.top_inside and meets_paper_phi(ln)]
    paper = (f"The bell's top meets the paper's {PAPER_PHI_PERCENT} % at eta = "
             + ", ".join(_eta_text(e) for e in meeting) if meeting
             else f"No threshold's bell top meets the paper's {PAPER_PHI_PERCENT} %")
    return ("sigma_<Z> against the redeposition threshold (P.B.C. constant-eps runs, steady "
            f"state over the last quarter; {_errors_text(used)}): " + "; ".join(parts)
            + ". Trend: " + verdict + " " + paper + ". " + _drift_free_text(all_points))


def _going_text(all_points, eta):
    """" (runs still going at eps = 0.1 (3301 taps): their windows partial)" for the points of
    ``eta`` whose runs have not all finished (their steady windows hold fewer taps than the
    protocol's), "" when every run has."""
    going = [p for p in all_points if p.eta == eta and not p.finished]
    if not going:
        return ""
    where = ", ".join(f"eps = {p.eps:g} ({p.taps} taps)" for p in going)
    return f" (runs still going at {where}: their windows partial)"


def _trend_text(trend):
    """The offset's trend (:func:`offset_trend`) in words."""
    if trend is None:
        return "the offset's trend needs fitted lines at two thresholds: undecided."
    how = ("shrinks" if trend.shrinks else "grows" if trend.grows
           else "does not change beyond its error")
    return (f"from eta = {_eta_text(trend.loose_eta)} to {_eta_text(trend.tight_eta)} the "
            f"offset {how} ({trend.change:+.4f} +- {trend.change_err:.4f}).")


def _drift_free_text(all_points):
    """The sentence on sigma_<Z> about each run's straight line over its window: the
    offset per eta and its trend; "" when no eta has a line."""
    flat = [ln for ln in lines(all_points, "sigma_linear") if ln.dof is not None]
    if not flat:
        return ""
    offsets = "; ".join(f"{ln.offset:.4f} +- {ln.offset_err:.4f} at eta = {_eta_text(ln.eta)}"
                        for ln in flat)
    return ("About each run's straight line over its window (a drift of the steady state "
            "removed, with part of the slowest fluctuations: a lower estimate), the offset is "
            f"{offsets}; " + _trend_text(offset_trend(flat)))


#: The legend's entry of sigma_<Z> about each run's straight line (one for every eta).
DRIFT_FREE_LABEL = "crosses: about each run's straight line"


def _by_eta(all_points, default_eta):
    """(eta, its points) per eta: the default first, then the loosest."""
    etas = sorted({p.eta for p in all_points}, key=lambda e: (e != default_eta, -e))
    return [(eta, [p for p in all_points if p.eta == eta]) for eta in etas]


def plot(all_points, default_eta, axes=None, table=None):
    """Two panels against sqrt(eps), a colour per eta (the default first): (a) sigma_<Z> with
    the line offset + slope sqrt(eps) of :func:`line` dashed over the eps measured and, as
    crosses, sigma_<Z> about each run's straight line (``sigma_linear``), (b) the
    steady <Phi^c> (the bell) with the paper's 60.6 % dotted; mean +- sem over seeds, open
    markers for points whose runs are still going. ``axes``: two axes, new ones when None.
    ``table``: a :class:`~tapmc.paper._plotting.FigureTable` that gets every plotted number
    (the errors as drawn; the dashed lines at the eps measured). Returns the axes."""
    if axes is None:
        _, axes = _plotting.new_figure(nrows=2, height=2.8, width=6.0)
    if len(axes) < 2:
        raise ValueError(f"axes: {len(axes)} given, the figure has 2 panels")
    for colour, (eta, group) in enumerate(_by_eta(all_points, default_eta)):
        ln = line(group)
        x = np.array([p.sqrt_eps for p in group])
        label = f"eta = {_eta_text(eta)}" + (" (the default)" if eta == default_eta else "")
        for ax, value, err in ((axes[0], "sigma", "sigma_sem"), (axes[1], "phi_c", "phi_c_sem")):
            y = np.array([getattr(p, value) for p in group])
            e = np.array([getattr(p, err) for p in group])
            done = np.array([p.finished for p in group])
            if table is not None:
                table.add("a" if value == "sigma" else "b", label, x, y, e,
                          [p.seeds for p in group])
            for mask, fill in ((done, f"C{colour}"), (~done, "none")):
                if mask.any():
                    ax.errorbar(x[mask], y[mask], yerr=e[mask], marker="o", ms=4, ls="none",
                                capsize=2, color=f"C{colour}", mfc=fill,
                                label=label if fill != "none" or not done.any() else None)
        flat = np.array([p.sigma_linear for p in group])
        flat_err = np.array([p.sigma_linear_sem for p in group])
        axes[0].errorbar(x, flat, yerr=flat_err, marker="x", ms=4, ls="none", capsize=2,
                         color=f"C{colour}", lw=0.6)
        if table is not None:
            table.add("a", f"{label}: about each run's line", x, flat, flat_err,
                      [p.seeds for p in group])
        if ln.dof is not None:
            xs = np.linspace(x.min(), x.max(), 50)
            axes[0].plot(xs, ln.offset + ln.slope * xs, color=f"C{colour}", ls="--", lw=0.8)
            if table is not None:
                table.add("a", f"{label}: offset + slope sqrt(eps)", x,
                          ln.offset + ln.slope * x)
    axes[0].plot([], [], marker="x", ls="none", color="0.3", label=DRIFT_FREE_LABEL)
    axes[1].axhline(PAPER_PHI_PERCENT / 100.0, color="0.5", ls=":", lw=1,
                    label=f"the paper's {PAPER_PHI_PERCENT} %")
    axes[0].set_ylabel(r"$\sigma_{\langle Z\rangle}$ (steady state)", fontsize=8)
    axes[1].set_ylabel(r"$\langle\Phi^c\rangle$ (steady state)", fontsize=8)
    for ax in axes[:2]:
        ax.set_xlabel(r"$\varepsilon^{1/2}$")
        _plotting.legend(ax, fontsize=6, outside=True)
    return axes


def settings_line(all_points, used=None, scale=FULL):
    """The settings the figure states on top (every number of it is a setting of the runs),
    with what its error bars are (``used``: :func:`calibrated`'s factors)."""
    seeds = [p.seeds for p in all_points]
    scaled = {q: hi for q, (_, hi) in (used or {}).items() if hi != 1.0}
    floor = ("one seed: its batch means" if not scaled else
             "never below the runs' batch-means errors x the realizations' spread, "
             + ", ".join(f"{ERROR_NAMES[q]} {k:.1f}" for q, k in scaled.items()))
    stop = _plotting.planned_stop(_runs.constant_eps_eta_run(scale, BC, 0.01, 1, scale.eta))
    return (f"P.B.C., N = {scale.N}, box {scale.L:g}R x {scale.L:g}R, {scale.taps} taps at "
            f"constant eps; eta: each series', {stop}; steady state: the last quarter of each "
            "run's planned taps; mean +- sem over "
            f"{min(seeds)} to {max(seeds)} seeds per point ({floor}); open "
            "markers: runs still going; "
            "dashed: sigma_<Z> = offset + slope sqrt(eps); crosses: sigma_<Z> about each "
            "run's straight line over its window; "
            + _plotting.scale_text(scale))


def write_figure(all_points, default_eta, path, factor_of=None, scale=FULL):
    """``sigma_eta.png``: :func:`plot` of the points with the errors the finding decides with
    (:func:`calibrated`), its settings on top, and beside it ``sigma_eta_figure.csv``, every
    number it draws (:data:`~tapmc.paper._plotting.CSV_COLUMNS`: the errors as drawn, the
    dashed lines' values); returns the PNG's path."""
    all_points, used = calibrated(all_points, factor_of)
    table = _plotting.FigureTable()
    fig = plot(all_points, default_eta, table=table)[0].figure
    _plotting.finish_figure(fig, settings_line(all_points, used, scale))
    return _plotting.write_figure(fig, Path(path), table)[0]
