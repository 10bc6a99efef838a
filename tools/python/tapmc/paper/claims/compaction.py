# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Statistics of the initial packing and of the compaction curves (section III.A, Fig. 2; the
steady states of Fig. 9): the packing fractions, the gain in Phi_b, the efficiency that
decreases over the first decade, and the late share of the gain (the slowing strongest at
small eps)."""

from __future__ import annotations

import math

import numpy as np

from tapmc.fluctuations import DEFAULT_BATCHES, SteadyState
from tapmc.stats import mean_dof

from .._runs import eps_tag
from .common import (WITHIN_RUN_DOF, curve_arrays, fig2_curves, not_in_campaign,
                     one_seed_error_text, per_fig2_curve, seeds_error, steady_dof,
                     value_triple)
from .conventions import EARLY_MIN_SEEDS
from .measure import Measure, fmt
from .registry import statistic


@statistic("initial_phi")
def initial_phi(data, claim):
    """<Phi^c> of the initial P.B.C. packing. A campaign with one packing (the paper's
    protocol) is decided by the depositions of the same size measured at t = 0 (``initial-
    packing``), when there: the paper's value is one packing's, so the interval is the mean's
    error combined with the spread of single packings (a prediction interval)."""
    m, s, n = (math.nan if v is None else v for v in data.summary["initial_phi_c"])
    sizes = {(int(N), float(L)) for N, L in data.summary.get("sizes") or ()}
    phis = np.array([float(r["phi_c"]) for r in data.question("initial_packing")
                     if r["bc"] == "pbc" and (int(r["N"]), float(r["L"])) in sizes])
    if len(phis) >= 2 and not (np.isfinite(n) and n >= len(phis)):
        mean, sd = float(phis.mean()), float(phis.std(ddof=1))
        sem = sd / math.sqrt(len(phis))
        return [Measure(mean, math.hypot(sem, sd), len(phis) - 1,
                        shown=f"{fmt(mean, sem, pct=True)} over {len(phis)} depositions (one "
                              f"packing spreads {100 * sd:.2f} %; the campaign's: "
                              f"{fmt(m, None, pct=True)})")]
    return [Measure(m, s, mean_dof(n), shown=fmt(m, s, pct=True))]


@statistic("tapped_phi")
def tapped_phi(data, claim):
    """The steady <Phi^c> after the taps against the paper's value read at tap 4000: a single
    tap's value, so the interval is the steady state's error combined with the spread of
    single taps (a prediction interval). Without the steady state: the value at the end."""
    fig9 = data.result("fig9")
    if fig9 is None:
        return not_in_campaign("no Fig. 9 runs")
    m, s, n = value_triple(fig9.phi_c_steady)
    if not np.isfinite(m):
        m, s, n = value_triple(fig9.phi_c["final"])
        return [Measure(m, s, mean_dof(n), shown=fmt(m, s, pct=True))]
    sd = value_triple(fig9.phi_c_tap_sd)[0]
    err = math.hypot(s, sd) if np.isfinite(s) else math.nan
    return [Measure(m, err, steady_dof(n, s),
                    shown=f"{fmt(m, s, pct=True)} (steady state; single taps spread "
                          f"{100 * sd:.2f} %" + (f"; {_tapped_one_seed(data)})" if n == 1
                                                 else ")"))]


def _tapped_one_seed(data):
    factor = data.run_error("phi_c")[0]
    if factor == 1.0:
        return "one seed: the spread between realizations is not included"
    return one_seed_error_text(factor)


@statistic("pbc_compaction")
def pbc_compaction(data, claim):
    fig9 = data.result("fig9")
    if fig9 is None:
        return not_in_campaign("no Fig. 9 runs")
    mi, si, ni = value_triple(fig9.phi_c["initial"])
    mf, sf, nf = value_triple(fig9.phi_c_steady)
    if not np.isfinite(mf):
        mf, sf, nf = value_triple(fig9.phi_c["final"])
        dof = mean_dof(min(ni, nf))
    else:
        dof = steady_dof(min(ni, nf), sf)
        if nf == 1:
            si = 0.0  # one packing: its initial value is exact, the steady mean is not
    return [Measure(mf - mi, math.hypot(si, sf), dof,
                    shown=f"{fmt(mi, si, pct=True)} -> {fmt(mf, sf, pct=True)}")]


def _fbc_groups(data):
    """eps -> [(start, mean, sem)] of <Phi^c> of the F.B.C. constant-eps groups of
    realization_scatter.csv (``const_fbc_eps<eps>``: seeds of one eps, each from its own
    packing, the window of the last 1000 taps)."""
    out = {}
    for r in data.question("realization_scatter"):
        if r["column"] == "phi_c" and r["group"].startswith("const_fbc_eps"):
            out.setdefault(float(r["group"][len("const_fbc_eps"):]), []).append(
                (float(r["start"]), float(r["mean"]), float(r["sem"])))
    return out


@statistic("pbc_vs_fbc")
def pbc_vs_fbc(data, claim):
    """Section IV.A: "the absolute value of the packing fraction is larger in periodic
    conditions but its increase due to compaction is a bit smaller". At each eps where the
    campaign has both: P.B.C., Fig. 4's steady square (from the bell's packing, whose <Phi^c>
    the campaign's initial packings give); F.B.C., the groups of seeds of realization-scatter
    (each from its own packing). Two rows: the steady <Phi^c> of P.B.C. minus F.B.C. (sign
    +), and the increase of P.B.C. minus that of F.B.C. (sign -). The F.B.C. seeds' errors are
    judged with the campaign's groups of realizations (common.seeds_error)."""
    fig4 = data.result("fig4")
    groups = _fbc_groups(data)
    m0, s0, n0 = (math.nan if v is None else v for v in data.summary.get("initial_phi_c")
                  or (None, None, None))
    if fig4 is None or not groups or not np.isfinite(m0):
        return not_in_campaign("P.B.C. steady states (Fig. 4), F.B.C. groups of seeds "
                               "(realization-scatter) and the initial P.B.C. packings")
    out = []
    for eps, seeds in sorted(groups.items()):
        match = np.flatnonzero(np.isclose(fig4.steady.x, math.sqrt(eps), rtol=1e-6))
        if not match.size or len(seeds) < 2:
            continue
        k = int(match[0])
        pbc, pbc_err, pbc_n = (float(v[k]) for v in (fig4.steady.mean, fig4.steady.err,
                                                     fig4.steady.n))
        start, mean, sem = (np.array(v) for v in zip(*seeds))
        group = (f"const_fbc_eps{eps_tag(eps)}",)
        fbc_err, fbc_dof, _, _ = seeds_error(data, mean, sem, "phi_c", "fbc", group)
        rise_err, rise_dof, _, _ = seeds_error(data, mean - start, sem, "phi_c", "fbc", group)
        dofs = [d for d in (steady_dof(int(pbc_n), pbc_err), fbc_dof) if d is not None]
        dof = min(dofs) if len(dofs) == 2 else None
        fbc, fbc_rise, pbc_rise = float(mean.mean()), float((mean - start).mean()), pbc - m0
        out.append(Measure(pbc - fbc, math.hypot(pbc_err, fbc_err), dof, sign=1,
                           label=f"eps = {eps:g}, denser in P.B.C.",
                           shown=f"P.B.C. {fmt(pbc, pbc_err, pct=True)} vs F.B.C. "
                                 f"{fmt(fbc, fbc_err, pct=True)} ({len(seeds)} seeds)"))
        out.append(Measure(pbc_rise - fbc_rise, math.hypot(pbc_err, s0, rise_err), dof, sign=-1,
                           label=f"eps = {eps:g}, smaller increase in P.B.C.",
                           shown=f"increase P.B.C. {fmt(pbc_rise, math.hypot(pbc_err, s0))} "
                                 f"(from {fmt(m0, s0, pct=True)}) vs F.B.C. "
                                 f"{fmt(fbc_rise, rise_err)}"))
    return out or not_in_campaign("no eps with both a P.B.C. steady square and F.B.C. seeds")


def _gain(eps, t, mean, sem, n, run_error=(1.0, None)):
    """Mean of the last quarter minus the first point. One seed (the paper's protocol): the
    curve is the run itself, so the last quarter's mean has its batch-means error
    (tapmc.fluctuations.SteadyState) and the start, the run's own packing, none."""
    q = max(len(t) // 4, 1)
    gain = float(np.mean(mean[-q:]) - mean[0])
    if np.nanmax(n) == 1 and q >= 2 * DEFAULT_BATCHES:
        err = SteadyState(mean, last=q).compute().sem * run_error[0]
        return Measure(gain, err, WITHIN_RUN_DOF, label=f"eps = {eps:g}",
                       shown=f"{fmt(gain, err)} ({one_seed_error_text(run_error[0])})")
    err = float(math.sqrt(np.nanmean(sem[-q:]) ** 2 + sem[0] ** 2)) \
        if np.isfinite(sem[0]) else math.nan
    return Measure(gain, err, mean_dof(n), label=f"eps = {eps:g}")


@statistic("phi_b_gain")
def phi_b_gain(data, claim):
    return per_fig2_curve(data, lambda *curve: _gain(*curve,
                                                     run_error=data.run_error("phi_b", "fbc")))


#: The first decade of taps, whose rate ``efficiency_decrease`` compares with the last half's.
EARLY_DECADE = (1.0, 10.0)


def first_decade_rates(t, x):
    """(rate per tap, rate per unit ln t) of one realization over the first decade
    (:data:`EARLY_DECADE`), each from the means of the decade's two halves (per tap: taps 1-5
    and 6-10; per ln t: split at sqrt(10)), and the two gaps between the halves (taps, ln t):
    ((rate, gap), (log_rate, log_gap))."""
    lo, hi = EARLY_DECADE
    mid = math.sqrt(lo * hi)
    low, high = (t >= lo) & (t < mid), (t >= mid) & (t <= hi)
    with np.errstate(divide="ignore"):      # tap 0's ln is -inf, outside both halves
        log_t = np.log(t)
    return _means_rate(t, x, *_decade_halves(t)), _means_rate(log_t, x, low, high)


def _decade_halves(t):
    """Masks of the first decade's two halves in taps (taps 1-5 and 6-10)."""
    lo, hi = EARLY_DECADE
    return (t >= lo) & (t <= hi / 2), (t > hi / 2) & (t <= hi)


def _means_rate(t, x, first, second):
    """(rate, gap): the change of x between the means over two windows (masks of t), per unit
    of t, and the gap between the windows' mean t."""
    gap = float(np.mean(t[second]) - np.mean(t[first]))
    return (float(np.mean(x[second])) - float(np.mean(x[first]))) / gap, gap


def _early_seeds(data, eps):
    """The first decade's rates over the realizations of early_taps.csv at ``eps`` (the
    campaign's run and more Monte Carlo seeds from the same packing): (per tap (mean, sem),
    per ln t (mean, sem), seeds) or None when fewer than :data:`EARLY_MIN_SEEDS`."""
    rows = [r for r in data.question("early_taps")
            if math.isclose(float(r["eps"]), eps, rel_tol=1e-9)]
    by_seed = {}
    for r in rows:
        by_seed.setdefault(int(r["seed"]), []).append((float(r["t"]), float(r["phi_b"])))
    rates = []
    for points in by_seed.values():
        t, x = (np.array(v) for v in zip(*sorted(points)))
        if np.all(np.isin(np.arange(EARLY_DECADE[0], EARLY_DECADE[1] + 1), t)):
            (rate, _), (log_rate, _) = first_decade_rates(t, x)
            rates.append((rate, log_rate))
    if len(rates) < EARLY_MIN_SEEDS:
        return None
    values = np.array(rates)
    sem = values.std(axis=0, ddof=1) / math.sqrt(len(values))
    mean = values.mean(axis=0)
    return (mean[0], sem[0]), (mean[1], sem[1]), len(values)


def _rate_change_one_run(eps, t, x, early_seeds=None, halves_factor=1.0):
    """:func:`_rate_change` of one run (the curve is the run): the late rate from the means of
    its last two quarters (each with its batch-means error); the early rate from the means of
    the two halves of the first decade (taps 1-5 and 6-10, as the line over the decade for
    several seeds): over the realizations of ``early_seeds`` (:func:`_early_seeds`) when
    there, else the run's own, each half with one tap's spread about the steady state as its
    error (taps that close together are correlated, so the spread is not divided by their
    number). ``halves_factor``: as in :func:`_log_rates_one_run`."""
    q = len(t) // 4
    third, fourth = (SteadyState(x[:len(t) - k * q], last=q).compute() for k in (1, 0))
    late = (fourth.mean - third.mean) / q
    e_late = halves_factor * math.hypot(third.sem, fourth.sem) / q
    if early_seeds is not None:
        (early, e_early), _, seeds = early_seeds
        dof = min(seeds - 1, WITHIN_RUN_DOF)
        source = f"the first decade over {seeds} realizations from the same packing"
    else:
        (early, gap), _ = first_decade_rates(t, x)
        e_early = math.sqrt(2.0) * fourth.std / gap
        dof = WITHIN_RUN_DOF
        source = "one seed: errors within the run"
    if halves_factor != 1.0:
        source += f"; the last half's error x {halves_factor:.1f} (realization-scatter)"
    return Measure(late - early, math.hypot(e_late, e_early), dof,
                   label=f"eps = {eps:g}",
                   shown=f"{fmt(late, e_late)} vs {fmt(early, e_early)} per tap (last half vs "
                         f"first decade; {source})")


def _window_rate(t, mean, sem, first, second):
    """(rate, its error) between the means of the seed-averaged curve over two windows (masks
    of t): each window's error is its taps' sem averaged, not divided by their number (a
    seed's taps that close together move together: the bound for fully correlated taps), and
    the two windows' errors add in quadrature (a seed high in one is high in the next, which
    only narrows the difference: an upper bound)."""
    if not (first.any() and second.any()):
        return math.nan, math.nan
    rate, gap = _means_rate(t, mean, first, second)
    return rate, math.hypot(float(np.mean(sem[first])), float(np.mean(sem[second]))) / gap


def _rate_change(eps, t, mean, sem, n, early_seeds=None, halves_factor=1.0):
    """Rate dPhi_b/dt over the last half of the taps minus that over the first decade. Several
    seeds: each rate between the means of two windows of the seed-averaged curve (the last
    half's quarters; the first decade's halves, taps 1-5 and 6-10, as for one run), with the
    seeds' sem as each window's error (:func:`_window_rate`): a straight-line fit through the
    taps took them as independent points, errors several times too small for seeds whose
    taps are correlated over hundreds of taps (tests/python/test_claims.py)."""
    if np.nanmax(n) == 1 and len(t) >= 8 * DEFAULT_BATCHES and t[-1] > 10 * EARLY_DECADE[1]:
        return _rate_change_one_run(eps, t, mean, early_seeds, halves_factor)
    early, e_early = _window_rate(t, mean, sem, *_decade_halves(t))
    end = t[-1]
    late, e_late = _window_rate(t, mean, sem, (t >= end / 2) & (t < 0.75 * end),
                                (t >= 0.75 * end) & (t <= end))
    label = f"eps = {eps:g}"
    if not all(np.isfinite(v) for v in (early, late, e_early, e_late)):
        return Measure(label=label, undecided="no error bars on the curve, or a window empty")
    return Measure(late - early, math.hypot(e_late, e_early), mean_dof(n), label=label,
                   shown=f"{fmt(late, e_late)} vs {fmt(early, e_early)} per tap "
                         f"(last half vs first decade; windows' means over seeds)")


@statistic("efficiency_decrease")
def efficiency_decrease(data, claim):
    return per_fig2_curve(data, lambda eps, *curve: _rate_change(
        eps, *curve, early_seeds=_early_seeds(data, eps),
        halves_factor=data.run_error("phi_b:halves", "fbc")[0]))


def _fig2_end_curves(data):
    """([(eps, (t, mean, sem, n)) of the smallest and the largest eps of Fig. 2's Phi_b], None),
    or (None, the missing-data measures) when there are not two eps."""
    if data.result("fig2") is None:
        return None, not_in_campaign("no Fig. 2 runs")
    curves, _ = fig2_curves(data)
    if curves is None or len(curves) < 2:
        return None, not_in_campaign("fewer than two eps in Fig. 2")
    return [(eps, curve_arrays(c)) for eps, c in (curves[0], curves[-1])], None


#: late_gain_share: the windows, as fractions of the run's taps T, whose means give Phi_b at
#: the end ([0.9 T, T]) and a decade before it ([0.09 T, 0.11 T]); batches of the earlier,
#: shorter window (81 taps of 4000: batches of 8)
LATE_WINDOW = (0.9, 1.0)


DECADE_BEFORE_WINDOW = (0.09, 0.11)


SHORT_WINDOW_BATCHES = 10


def _late_share(t, mean, sem, n, factor=1.0):
    """(share of the gain X(T) - X(0) made over the last decade, its error, dof) of one
    curve: X over [0.9 T, T] and over [0.09 T, 0.11 T] (one run: batch-means errors times
    ``factor``, :meth:`ReportData.run_error`; several
    seeds: the curve's sem averaged over each window, not reduced for the taps' correlation)."""
    T = t[-1]
    windows = [(t >= lo * T) & (t <= hi * T) for lo, hi in (LATE_WINDOW, DECADE_BEFORE_WINDOW)]
    end, before = (float(np.mean(mean[w])) for w in windows)
    if np.nanmax(n) == 1:
        errs = [factor * SteadyState(mean[w], last=int(w.sum()), batches=b).compute().sem
                for w, b in zip(windows, (DEFAULT_BATCHES, SHORT_WINDOW_BATCHES))]
        dof = min(DEFAULT_BATCHES, SHORT_WINDOW_BATCHES) - 1
    else:
        errs = [float(np.nanmean(sem[w])) for w in windows]
        dof = mean_dof(n)
    gain = end - mean[0]
    share = (end - before) / gain
    # d share / d end = (before - X0) / gain^2, d share / d before = -1 / gain
    err = math.hypot((before - mean[0]) / gain ** 2 * errs[0], errs[1] / gain)
    return share, err, dof


@statistic("late_gain_share")
def late_gain_share(data, claim):
    """Share of Phi_b's gain made over the last decade at the smallest eps minus that at the
    largest: positive when the smallest eps is farthest from its steady state at the end of
    the run (section III.A: 'without never really reaching it', most of all at small eps)."""
    ends, missing = _fig2_end_curves(data)
    if ends is None:
        return missing
    shares = []
    for eps, (t, mean, sem, n) in ends:
        if t[-1] < 10 * EARLY_DECADE[1] or (
                np.nanmax(n) == 1 and np.sum(t >= LATE_WINDOW[0] * t[-1]) < 2 * DEFAULT_BATCHES):
            return not_in_campaign("runs too short for a last decade of taps")
        shares.append((eps, *_late_share(t, mean, sem, n, data.run_error("phi_b", "fbc")[0])))
    (e0, s0, d0, f0), (e1, s1, d1, f1) = shares
    dofs = [d for d in (f0, f1) if d is not None]
    return [Measure(s0 - s1, math.hypot(d0, d1), min(dofs) if len(dofs) == 2 else None,
                    shown=f"share of the gain over the last decade {fmt(s0, d0)} "
                          f"(eps = {e0:g}) vs {fmt(s1, d1)} (eps = {e1:g})")]
