# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""connected-ageing: does the packing age once the drift of its compaction is removed
(section III.C, Fig. 5)? The paper's A(t, t_W) (eq. 5) is mostly the square of the mean
compaction that every realization shares (``Ageing.drift_share``), so its curves measure the
compaction law. The campaign's finished ageing realizations (runs ``ageing_<bc>_eps*_s*``, no
simulation) are re-analysed with the connected function C(t, t_W), the variance over
realizations of <Z>(t_W + t) - <Z>(t_W) (:class:`tapmc.connected_ageing.ConnectedAgeing`), and
a collapse that assumes no law (:class:`tapmc.connected_ageing.LawFreeCollapse`: mu = 0 no
ageing, mu = 1 simple ageing), at Fig. 5's waiting times (connected_ageing.csv, with A and C
at log-spaced delays for the figure connected_ageing.png)."""

from __future__ import annotations

import json
import math
from collections import defaultdict

import numpy as np

from tapmc.ageing import Ageing
from tapmc.connected_ageing import ConnectedAgeing

from .. import _plotting, _runs, fig5
from .._rst import list_table
from ..scales import FULL
from ..claims import fmt
from .common import (QuestionError, csv_schema, eps_of, finished_runs, last_rows,
                     taps_table)

NAME = "connected-ageing"
CSV = "connected_ageing.csv"
PNG = "connected_ageing.png"
#: long format: one quantity per row. Per ageing eps: the settings (``realizations``,
#: ``taps``, ``N``, ``L``, ``eta``: value only), per waiting time ``drift_share`` (t_W), the
#: curves ``A`` and ``C`` (t_W, t, value, error) and the collapse's ``mu`` and ``kappa``
#: (value, error) and ``dispersion``, ``dispersion_unscaled``, ``dispersion_simple``.
HEADER = ["eps", "quantity", "t_w", "t", "value", "error"]
#: the boundary condition of Fig. 5's realizations
BC = fig5.BC
#: the delays written per waiting time: log-spaced, this many per decade (the curves are
#: smooth in ln t; all 3000 delays of a 4000-tap run would make the CSV 100 times larger)
DELAYS_PER_DECADE = 12
#: how many errors of mu away a value is "excluded" (LawFreeCollapse.consistent_with: 2)
EXCLUDED_AT = 2.0
SETTINGS = ("realizations", "taps", "N", "L", "eta")
DISPERSIONS = ("dispersion", "dispersion_unscaled", "dispersion_simple")


def add_arguments(parser):
    """No options beyond --campaign and --out."""


def logspaced_delays(last, per_decade=DELAYS_PER_DECADE):
    """Delays 1 .. ``last``, log-spaced (``per_decade`` a decade, integers, each once), both
    ends and every power of 10 between kept (the page's table reads C at 10, 100, 1000)."""
    count = max(2, int(math.ceil(math.log10(max(last, 1)) * per_decade)) + 1)
    decades = 10 ** np.arange(int(math.log10(max(last, 1))) + 1)
    return np.unique(np.concatenate([np.round(np.logspace(0, math.log10(max(last, 1)),
                                                          count)), decades]).astype(int))


def realizations(run_dirs):
    """(z, variables): <Z> after 0, 1, ... taps of every realization in ``run_dirs`` (rows,
    cut to the shortest; a tap printed twice by a resumed run counts once, its last print)
    and the variables of the first's DONE.json."""
    series = []
    for run_dir in run_dirs:
        table = taps_table(run_dir / "taps.dat")
        if "Z" not in table.columns:
            raise QuestionError(f"{run_dir / 'taps.dat'}: no Z column (an ageing run prints "
                                "step Z phi_b phi_c)")
        last = last_rows(table)
        steps = sorted(last)
        if steps[0] != 0 or steps != list(range(len(steps))):
            raise QuestionError(f"{run_dir / 'taps.dat'}: taps missing (steps {steps[0]} to "
                                f"{steps[-1]} with {len(steps)} rows); the run is damaged")
        series.append(np.asarray(table["Z"], dtype=float)[[last[s] for s in steps]])
    length = min(len(z) for z in series)
    done = run_dirs[0] / "DONE.json"
    try:
        variables = json.loads(done.read_text()).get("run", {}).get("variables", {})
    except (OSError, ValueError, AttributeError) as err:
        raise QuestionError(f"{done}: not a run's DONE.json ({err})") from None
    return np.array([z[:length] for z in series]), variables


def _group_rows(eps, run_dirs):
    z, variables = realizations(run_dirs)
    taps = z.shape[1] - 1
    waiting = fig5.default_waiting_times(taps)
    if len(run_dirs) < 3:
        raise QuestionError(f"eps = {eps:g}: {len(run_dirs)} ageing realizations; the "
                            "connected function needs at least 3")
    try:
        connected = ConnectedAgeing(z, waiting).compute()
        collapse = connected.collapse()
        paper = Ageing(z, waiting).compute()
    except ValueError as err:   # too few taps for Fig. 5's waiting times
        raise QuestionError(f"eps = {eps:g}: {err}") from None
    settings = {"realizations": len(run_dirs), "taps": taps,
                **{k: variables.get(k, "") for k in ("N", "L", "eta")}}
    rows = [[f"{eps:g}", key, "", "", value, ""] for key, value in settings.items()]
    delays = logspaced_delays(int(connected.t[-1]))
    for tw in waiting:
        rows.append([f"{eps:g}", "drift_share", tw, "", f"{paper.drift_share(tw):.6g}", ""])
        at = np.searchsorted(paper.t, delays)
        rows += [[f"{eps:g}", "A", tw, int(paper.t[k]), f"{paper.A[tw][k]:.6g}",
                  f"{paper.A_sem[tw][k]:.4g}"] for k in at]
        at = delays - 1                                  # connected.t is 1, 2, ...
        rows += [[f"{eps:g}", "C", tw, int(connected.t[k]), f"{connected.C[tw][k]:.6g}",
                  f"{connected.C_error[tw][k]:.4g}"] for k in at]
    rows += [[f"{eps:g}", "mu", "", "", f"{collapse.mu:.6g}", f"{collapse.mu_error:.4g}"],
             [f"{eps:g}", "kappa", "", "", f"{collapse.kappa:.6g}",
              f"{collapse.kappa_error:.4g}"]]
    rows += [[f"{eps:g}", key, "", "", f"{getattr(collapse, key):.6g}", ""]
             for key in DISPERSIONS]
    print(f"eps = {eps:g}, {len(run_dirs)} realizations of {taps} taps: {collapse!r}",
          flush=True)
    return rows


def analyse(campaign):
    """The rows of connected_ageing.csv: the campaign's finished ageing realizations of
    :data:`BC`, by eps."""
    groups = defaultdict(list)
    for run_dir in finished_runs(campaign, f"ageing_{BC}_eps*_s*"):
        groups[eps_of(run_dir.name)].append(run_dir)
    return [row for eps in sorted(groups) for row in _group_rows(eps, groups[eps])]


save, load = csv_schema(HEADER)


def measure(args):
    path = save(args.out / CSV, analyse(args.campaign))
    print(f"wrote {write_figure(load(path), args.out / PNG, _runs.folder_scale(args.campaign))}")


# ---- reading the CSV -----------------------------------------------------------------------
class Result:
    """One eps of connected_ageing.csv: ``settings`` (dict), ``drift_share`` (t_W -> share),
    ``curves`` ("A" or "C" -> t_W -> (t, value, error) arrays), ``mu``, ``kappa`` ((value,
    error)) and ``dispersions`` (dict)."""

    def __init__(self, eps, rows):
        self.eps = eps
        self.settings, self.drift_share, self.dispersions = {}, {}, {}
        self.curves = {"A": defaultdict(list), "C": defaultdict(list)}
        for r in rows:
            q = r["quantity"]
            if q in SETTINGS:
                self.settings[q] = float(r["value"]) if r["value"] != "" else None
            elif q == "drift_share":
                self.drift_share[int(r["t_w"])] = float(r["value"])
            elif q in self.curves:
                self.curves[q][int(r["t_w"])].append((float(r["t"]), float(r["value"]),
                                                      float(r["error"])))
            elif q in ("mu", "kappa"):
                setattr(self, q, (float(r["value"]), float(r["error"])))
            elif q in DISPERSIONS:
                self.dispersions[q] = float(r["value"])
        self.curves = {k: {tw: tuple(np.array(c) for c in zip(*pts))
                           for tw, pts in sorted(v.items())} for k, v in self.curves.items()}

    def excluded_by(self, mu):
        """How many errors of the fitted mu a value ``mu`` lies from it."""
        value, error = self.mu
        return abs(value - mu) / error if error > 0 else math.inf


def results(rows):
    """[Result] per eps of connected_ageing.csv's ``rows``, by eps."""
    by_eps = defaultdict(list)
    for r in rows:
        by_eps[float(r["eps"])].append(r)
    return [Result(eps, by_eps[eps]) for eps in sorted(by_eps)]


def _settings_text(res):
    s = res.settings
    n, taps = int(s["realizations"]), int(s["taps"])
    size = f"N = {int(s['N'])}, L = {s['L']:g}R, " if s.get("N") and s.get("L") else ""
    eta = f", eta = {s['eta']:g}" if s.get("eta") else ""
    return f"{size}P.B.C., eps = {res.eps:g}, {n} realizations of {taps} taps{eta}"


def _verdict(res):
    """The answer in words: what mu = 0 and mu = 1 are against the fit."""
    none, simple = res.excluded_by(0.0), res.excluded_by(1.0)
    if none <= EXCLUDED_AT and simple > EXCLUDED_AT:
        value, error = res.mu
        return (f"no ageing at this precision (mu = 0 within {none:.1f} errors), simple "
                f"ageing (mu = 1) excluded by {simple:.1f} errors, any ageing with mu above "
                f"{value + EXCLUDED_AT * error:.2f} by {EXCLUDED_AT:g}")
    if simple <= EXCLUDED_AT and none > EXCLUDED_AT:
        return (f"simple ageing (mu = 1 within {simple:.1f} errors); no ageing (mu = 0) "
                f"excluded by {none:.1f} errors")
    if none > EXCLUDED_AT and simple > EXCLUDED_AT:
        return (f"ageing, but not simple ageing (mu = 0 excluded by {none:.1f} errors, mu = 1 "
                f"by {simple:.1f})")
    return (f"undecided: neither no ageing (mu = 0, {none:.1f} errors away) nor simple ageing "
            f"(mu = 1, {simple:.1f} errors away) is excluded; more realizations decide")


def finding_text(rows):
    """The main page's finding (one paragraph per eps), or "" without rows."""
    parts = []
    for res in results(rows):
        shares = sorted(res.drift_share.values())
        tws = sorted(res.drift_share)
        mu, kappa, d = res.mu, res.kappa, res.dispersions
        parts.append(
            f"Ageing as ageing (section III.C, Fig. 5; {_settings_text(res)}): the paper's "
            f"A(t, t_W) (eq. 5) is {100 * shares[0]:.1f}-{100 * shares[-1]:.1f} % the square "
            f"of the mean compaction that every realization shares (t_W = "
            f"{', '.join(map(str, tws))}): it measures the compaction's drift, not the "
            "packing's memory. With the drift removed, the connected function C(t, t_W) (the "
            "variance over realizations of <Z>(t_W + t) - <Z>(t_W)) collapses without a law "
            f"at mu = {fmt(*mu)}, kappa = {fmt(*kappa)} (jackknife over realizations): "
            f"{_verdict(res)}. Law-free dispersion of the curves about each other (about 1 "
            f"for curves one within their errors): {d['dispersion']:.3g} at the fit, "
            f"{d['dispersion_unscaled']:.3g} unscaled, {d['dispersion_simple']:.3g} with "
            "simple ageing's t / t_W.")
    return " ".join(parts)


def render(path):
    """The appendix section: per eps and waiting time, the drift's share of A and C at a few
    delays, then the collapse."""
    lines = []
    for res in results(load(path)):
        lines += [f"The campaign's ageing realizations ({_settings_text(res)}; "
                  f"``{CSV}``):", ""]
        marks = [t for t in (10, 100, 1000) if any(t in c[0] for c in res.curves["C"].values())]
        table = []
        for tw, share in sorted(res.drift_share.items()):
            t, c, err = res.curves["C"][tw]
            table.append([str(tw), f"{100 * share:.2f} %"] + [
                fmt(c[t == m][0], err[t == m][0]) if (t == m).any() else "" for m in marks])
        lines += list_table(["t_W", "A's share that is drift"] + [f"C(t = {m})" for m in marks],
                            table)
        lines += ["", finding_text([r for r in load(path) if float(r["eps"]) == res.eps]), ""]
    return lines


# ---- the figure ----------------------------------------------------------------------------
def plot(rows, axes=None):
    """Two panels for the first eps of ``rows``: (a) the paper's A(t, t_W), (b) the connected
    C(t, t_W), against the delay, one curve per t_W with its error as a band. ``axes``: two
    axes, new ones when None. Returns the axes."""
    res = results(rows)[0]
    if axes is None:
        _, axes = _plotting.new_figure(nrows=1, ncols=2, height=3.6, width=4.0)
    if len(axes) < 2:
        raise ValueError(f"axes: {len(axes)} given, the figure has 2 panels")
    labels = {"A": r"$A(t, t_W)$ (eq. 5): drift included",
              "C": r"$C(t, t_W)$: the spread over realizations"}
    for ax, key in zip(axes, ("A", "C")):
        for tw, (t, value, err) in res.curves[key].items():
            line, = ax.plot(t, value, lw=1.2, label=f"$t_W$ = {tw}")
            ax.fill_between(t, value - err, value + err, color=line.get_color(), alpha=0.2,
                            lw=0)
        ax.set_xscale("log")
        ax.set_yscale("log" if key == "A" else "linear")
        ax.set_xlabel("delay t (taps)")
        ax.set_ylabel(labels[key], fontsize=8)
        _plotting.legend(ax, fontsize=6)
    axes[1].set_title(f"no law: mu = {fmt(*res.mu)} (0: no ageing, 1: simple ageing)",
                      fontsize=7)
    return axes


def write_figure(rows, path, scale=FULL):
    """connected_ageing.png: :func:`plot`, its settings on top (``scale``: the campaign's,
    :func:`~tapmc.paper._runs.folder_scale`); returns the path."""
    fig = plot(rows)[0].figure
    stop = _plotting.planned_stop(_runs.ageing_run(scale, fig5.BC, scale.ageing_eps, 1))
    _plotting.finish_figure(fig, _settings_text(results(rows)[0]) + f", {stop}; bands: "
                            "jackknife errors over realizations; " + _plotting.scale_text(scale))
    return _plotting.save_figure(fig, path)
