# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Statistics of the pores (section IV, Figs. 9-10): P0's change against the packing
fraction's and P0 against Percus-Yevick, xi_min, nu and its hysteresis along the ramp, the
rho_v tail and the pore distribution's quadratic law."""

from __future__ import annotations

import math

import numpy as np
from scipy import stats

from tapmc.hysteresis import CRITICAL_SQRT_EPS
from tapmc.pores import JACKKNIFE_BLOCKS, percus_yevick_p0
from tapmc.stats import bonferroni_t_quantile, mean_dof, weighted_line

from .. import _plotting as P
from .._runs import RAMP_BRANCHES
from ..paper_ramp import NAME as PAPER_RAMP_NAME, TAPS_PER_LEVEL as PAPER_RAMP_TAPS
from .common import (campaign_eta, common_x, jackknife_dof, not_in_campaign, paired_levels,
                     paper_precision, protocol_label)
from .conventions import GAUSSIAN_TAIL_SD
from .data import ReportData
from .measure import Measure, fmt
from .registry import statistic


def _pointwise_zero(x, diff, err, n, what, effect):
    """The largest standardized difference over the points, tested against the Bonferroni
    corrected t quantile (so that many points do not make a disagreement by chance); its
    ``p_value`` is that test's (Bonferroni-corrected, two-sided) for the fit rule."""
    ok = np.isfinite(diff) & np.isfinite(err) & (err > 0)
    if not np.any(ok):
        k = int(np.nanargmax(np.abs(diff))) if np.any(np.isfinite(diff)) else 0
        return [Measure(float(diff[k]) if len(diff) else math.nan,
                        undecided="one realization: the curves have no error bars",
                        shown=f"max |{what}| = {fmt(np.nanmax(np.abs(diff)))}")]
    idx = np.flatnonzero(ok)
    k = idx[int(np.argmax(np.abs(diff[idx]) / err[idx]))]
    dof = mean_dof(n[k])
    if dof is None:
        return [Measure(float(diff[k]), undecided="one realization")]
    quantile = bonferroni_t_quantile(dof, len(idx))
    p = min(1.0, len(idx) * 2.0 * float(stats.t.sf(abs(diff[k]) / err[k], dof)))
    return [Measure(float(diff[k]), float(err[k]), dof, quantile=quantile, effect=effect,
                    p_value=p, shown=f"{fmt(diff[k], err[k])} at sigma = {x[k]:.3g} (largest "
                                     f"of {len(idx)} standardized differences)")]


def _py_change(fig9, sigma):
    """Largest change over sigma of the Percus-Yevick P0 (eqs. 8-9) between the initial and
    the tapped packing fractions of Fig. 9's result: the effect a P0 claim is measured against
    (None when the packing fractions are not in the data)."""
    phi_i, phi_f = fig9.phi["initial"].value, fig9.phi["final"].value
    if not (np.isfinite(phi_i) and np.isfinite(phi_f)):
        return None
    return float(np.max(np.abs(percus_yevick_p0(sigma, phi_f) -
                               percus_yevick_p0(sigma, phi_i))))


def _p0_configurations(data, what, more_than=1):
    """The comparison of :func:`_p0_difference` over the configurations of
    tapmc-paper question p0-configs (depositions at t = 0, dumps of the continued Fig. 9
    run), None when they are not there or are not more than ``more_than`` of each kind."""
    rows = [r for r in data.question("p0_configs") if r["sigma"] != "phi"]
    phi = [r for r in data.question("p0_configs") if r["sigma"] == "phi"]
    if len(rows) < 3 or not phi:
        return None
    col = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    if min(col["initial_n"].min(), col["tapped_n"].min()) <= more_than:
        return None
    phi_i, phi_t = float(phi[0]["initial"]), float(phi[0]["tapped"])
    x = col["sigma"]
    effect = float(np.max(np.abs(percus_yevick_p0(x, phi_t) - percus_yevick_p0(x, phi_i))))
    diff = np.asarray(percus_yevick_p0(x, phi_t), float) - col["tapped"]
    err, n = col["tapped_sem"], col["tapped_n"]
    out = _pointwise_zero(x, diff, err, n, what, effect)
    for m in out:
        m.shown = (m.shown or m.text()) + (
            f" (P0 over {int(col['initial_n'].min())} depositions and "
            f"{int(col['tapped_n'].min())} configurations of the tapped packing: "
            "tapmc-paper question p0-configs)")
    return out


def _p0_difference(data, what):
    """P0 of the tapped packing against Percus-Yevick's (exact) at its packing fraction,
    sigma by sigma (:func:`_pointwise_zero`). Curves
    of fewer realizations than ``p0-configs`` has configurations (one run per point, the
    paper's protocol, or a campaign under way with two seeds, whose sem over two is itself
    hardly known) are compared over those configurations instead, when there."""
    fig9 = data.result("fig9")
    if fig9 is None:
        return not_in_campaign("no Fig. 9 runs")
    final = fig9.p0["final"]
    ref = fig9.percus_yevick
    measured = _p0_configurations(data, what, more_than=int(np.nanmax(final.n)))
    if measured is not None:
        return measured
    x = final.x
    ref_err = np.nan_to_num(np.interp(x, ref.x, ref.err))  # Percus-Yevick: exact
    return _pointwise_zero(x, np.interp(x, ref.x, ref.mean) - final.mean,
                           np.hypot(ref_err, final.err), final.n, what, _py_change(fig9, x))


def _p0_pair(data):
    """(sigma, P0 initial, its error, P0 tapped, its error, realizations, (phi initial, its
    error), (phi tapped, its error), source text) from the configurations of tapmc-paper
    question p0-configs when they are more realizations than Fig. 9's curves, else from
    Fig. 9's result; None without either (or without errors)."""
    fig9 = data.result("fig9")
    rows = [r for r in data.question("p0_configs") if r["sigma"] != "phi"]
    phi = [r for r in data.question("p0_configs") if r["sigma"] == "phi"]
    seeds = 0 if fig9 is None else int(np.nanmax(fig9.p0["final"].n))
    if len(rows) >= 3 and phi and min(int(r["tapped_n"]) for r in rows) > max(seeds, 1):
        col = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
        p = phi[0]
        return (col["sigma"], col["initial"], col["initial_sem"], col["tapped"],
                col["tapped_sem"], int(min(col["initial_n"].min(), col["tapped_n"].min())),
                (float(p["initial"]), float(p["initial_sem"])),
                (float(p["tapped"]), float(p["tapped_sem"])),
                f"P0 over {int(col['initial_n'].min())} depositions and "
                f"{int(col['tapped_n'].min())} configurations of the tapped packing: "
                "tapmc-paper question p0-configs")
    if fig9 is None or seeds < 2:
        return None
    initial, final = fig9.p0["initial"], fig9.p0["final"]
    x = final.x
    return (x, np.interp(x, initial.x, initial.mean), np.interp(x, initial.x, initial.err),
            final.mean, final.err, int(min(np.min(final.n), np.min(initial.n))),
            (fig9.phi["initial"].value, fig9.phi["initial"].err),
            (fig9.phi["final"].value, fig9.phi["final"].err), f"{seeds} seeds")


def _py_change_at(sigma, phi_initial, phi_tapped):
    """The largest |P0| change over ``sigma`` that Percus-Yevick (eqs. 8-9) gives between two
    packing fractions, and where."""
    change = np.abs(np.asarray(percus_yevick_p0(sigma, phi_tapped), float)
                    - np.asarray(percus_yevick_p0(sigma, phi_initial), float))
    k = int(np.argmax(change))
    return float(change[k]), k


@statistic("p0_change_over_density")
def p0_change_over_density(data, claim):
    """Section IV.B: the initial packing's P0 "is quite close" to the tapped one's, "this
    slight difference" meaning that P0 is "insufficiently sensitive to small structural
    changes as compaction": its change is the one the packing fraction alone gives. The
    largest change of P0 over sigma between the two packings over the largest change
    Percus-Yevick gives between their packing fractions, minus 1: 0 when P0 sees the
    compaction only through Phi. Errors: the curves' at the largest change, and the packing
    fractions' through Percus-Yevick."""
    pair = _p0_pair(data)
    if pair is None:
        return not_in_campaign("no P0 of the initial and tapped packings with errors")
    x, a, ea, b, eb, n, (phi_i, e_i), (phi_t, e_t), source = pair
    if not (np.isfinite(phi_i) and np.isfinite(phi_t)):
        return [Measure(undecided=f"no packing fractions of the two packings ({source})",
                        shown=source)]
    e_i, e_t = (e if np.isfinite(e) else 0.0 for e in (e_i, e_t))
    change = np.abs(b - a)
    k = int(np.argmax(change))
    py, j = _py_change_at(x, phi_i, phi_t)
    if not (np.isfinite(py) and py > 0):
        return [Measure(undecided="the two packings have the same packing fraction")]
    # the packing fractions' errors moved through Percus-Yevick's change
    shifts = [abs(_py_change_at(x, phi_i + e_i, phi_t)[0] - py),
              abs(_py_change_at(x, phi_i, phi_t + e_t)[0] - py)]
    ratio = change[k] / py
    err = ratio * math.hypot(math.hypot(ea[k], eb[k]) / change[k] if change[k] > 0 else 0.0,
                             math.hypot(*shifts) / py)
    return [Measure(ratio - 1.0, err, mean_dof(n), effect=1.0,
                    shown=f"largest change {fmt(change[k])} at sigma = {x[k]:.3g} against "
                          f"Percus-Yevick's {fmt(py)} at sigma = {x[j]:.3g} for Phi "
                          f"{100 * phi_i:.2f} % -> {100 * phi_t:.2f} %: ratio "
                          f"{fmt(ratio, err)} ({source})")]


@statistic("p0_final_minus_py")
def p0_final_minus_py(data, claim):
    """Section IV.B: Fig. 9 confronts the tapped packing's P0 with Percus-Yevick's (eqs. 8-9)
    at its Phi, which "agrees well" with random close packings. The largest standardized
    difference over sigma (:func:`_p0_difference`) as a fit of the law: its Bonferroni p-value
    decides; the paper's precision for it is the largest change Percus-Yevick gives between
    the initial and tapped packing fractions: the paper calls the two curves "quite close",
    "a slight difference", so it reads a departure within that change as slight. Undecided
    while the difference's uncertainty is not below that change (the test could not tell the
    law from the other packing's)."""
    out = _p0_difference(data, "Percus-Yevick - P0(tapped)")
    for m in out:
        if m.undecided or m.effect is None or not np.isfinite(m.err):
            continue
        band = m.quantile * m.err
        if not band < abs(m.effect):
            m.undecided = (f"uncertainty {fmt(band)} not below the change Percus-Yevick "
                           f"gives between the two packings, {fmt(abs(m.effect))}")
        m.paper_precision = paper_precision(abs(m.value), abs(m.effect))
        m.shown = (m.shown or m.text()) + (
            f"; {abs(m.value) / abs(m.effect):.2g} of Percus-Yevick's change between the "
            "initial and tapped packing fractions")
    return out


@statistic("xi_min")
def xi_min(data, claim):
    if data.result("fig10") is None:
        return not_in_campaign("no pore dumps")
    values = _pore_values(data, "xi_min")
    if not values:
        return not_in_campaign("no xi_min")
    low = min(values, key=lambda v: v.value)
    return [Measure(low.value, low.err, mean_dof(low.n), shown=fmt(low.value, low.err, digits=4))]


def _pore_dof(n, err):
    """dof of a Fig. 10 value (tapmc.pores.PoreOutput.jackknife for one seed)."""
    return jackknife_dof(n, err, JACKKNIFE_BLOCKS)


@statistic("nu_ramp_hysteresis")
def nu_ramp_hysteresis(data, claim):
    """Section IV.B: nu has the reversible-irreversible behaviour of <Phi^c> (section III.B).
    From nu at the level ends of the ramp beyond (sqrt eps)* (tapmc-paper question
    ramp-pores: one packing per level, the spatial jackknife's error), the two signs that
    make <Phi^c>'s reversible branch, with nu's sign reversed (more pore volume, less
    packing): the decreasing branch lies below the first increase (mean of the differences at
    their common sqrt(eps), the levels' errors combined), and on it nu rises with sqrt(eps)
    (weighted straight line). The campaign's ramp, then per eta the ramps at the paper's own
    protocol that turn beyond (sqrt eps)* (paperramp..., 4000 taps per level)."""
    every = data.question("ramp_pores")
    # the ramp beyond (sqrt eps)* (runs ramp_<bc>_s<seed>; ramplow_ and rampnear_ are others)
    rows = [r for r in every if r["run"].startswith("ramp_")]
    # one packing per level: its jackknife times the packings' factor where they reject it
    factor = data.run_error("packing:nu")[0]
    paper = _paper_nu_rows(data, every, factor)
    if not rows:
        return paper or not_in_campaign("no nu at the level ends of the ramp beyond (sqrt "
                                        "eps)* (tapmc-paper question ramp-pores)")
    return _nu_measures(rows, factor) + paper


def _paper_nu_rows(data, rows, factor):
    """nu-hysteresis's two rows per eta of the paper ramps beyond (sqrt eps)* in ramp_pores
    (their seeds' nu averaged level by level, their errors combined); [] without them."""
    runs = {}
    for r in rows:
        m = PAPER_RAMP_NAME.match(r["run"])
        if m and float(m.group("top")) > CRITICAL_SQRT_EPS:
            eta = float(m.group("eta")) if m.group("eta") else campaign_eta(data.summary)
            runs.setdefault(eta, []).append(r)
    first = campaign_eta(data.summary)
    out = []
    for eta in sorted(runs, key=lambda e: (e != first, -e)):
        out += _nu_measures(runs[eta], factor, f", {protocol_label(PAPER_RAMP_TAPS, eta)}",
                            meets=("ramp_taps",))
    return out


def _nu_branches(rows, factor):
    """branch -> (x, nu, error, n) of ramp_pores ``rows``: per sqrt(eps) the mean over the
    rows' seeds, its error their jackknife errors (times ``factor``) combined."""
    branches = {}
    for index, name in enumerate(RAMP_BRANCHES):   # in.ramp's branch column
        by_x = {}
        for r in rows:
            if int(r["branch"]) == index:
                by_x.setdefault(round(float(r["sqrt_eps"]), 9), []).append(
                    (float(r["nu"]), float(r["nu_sem"]) * factor))
        if by_x:
            x = np.array(sorted(by_x))
            y = np.array([np.mean([v for v, _ in by_x[k]]) for k in x])
            e = np.array([math.sqrt(sum(s * s for _, s in by_x[k])) / len(by_x[k]) for k in x])
            branches[name] = (x, y, e, np.ones(len(x), int))
    return branches


def _nu_measures(rows, factor, suffix="", **row):
    """The two rows of nu-hysteresis from ramp_pores ``rows`` of one protocol: the decrease
    minus the first increase, and the slope on the decrease; labels followed by ``suffix``,
    ``row`` (meets) given to both."""
    branches = _nu_branches(rows, factor)
    dof = _pore_dof(1, 0.0)
    out = []
    up, down = branches.get("up1"), branches.get("down")
    pairs = [] if up is None or down is None else common_x(down, up)
    label = "decrease minus first increase" + suffix
    if pairs:
        diffs = paired_levels(down, up)
        err = math.sqrt(sum(down[2][i] ** 2 + up[2][k] ** 2 for i, k in pairs)) / len(pairs)
        value = float(np.mean(diffs))
        out.append(Measure(value, err, dof, label=label, sign=-1, shown=(
            f"{fmt(value, err)} (mean of {len(pairs)} common sqrt(eps); one packing per level, "
            "lateral jackknife)"), **row))
    else:
        out.append(Measure(label=label, undecided="no level of the first increase at a "
                                                  "sqrt(eps) of the decrease", **row))
    label = "slope on the decrease" + suffix
    if down is not None:
        slope, err, line_dof = weighted_line(*down[:3])
        if np.isfinite(slope):
            out.append(Measure(slope, err, line_dof, label=label, sign=1,
                               shown=f"slope {fmt(slope, err)} over {len(down[0])} levels",
                               **row))
            return out
    out.append(Measure(label=label, undecided="fewer than three levels of the decrease", **row))
    return out


def _pore_curves(data):
    """[(t, xi^3 P(xi) at t)] of Fig. 10's dumps by t, None without them."""
    fig10 = data.result("fig10")
    if fig10 is None:
        return None
    curves = sorted((float(step), dump.xi3_P_xi) for step, dump in fig10.dumps.items())
    return curves or None


def _band_integral(x, y, s, lo, hi):
    """Integral of a histogram curve over lo < x <= hi (bin width from the x spacing) and its
    error (bins independent)."""
    width = np.gradient(x) if len(x) > 1 else np.ones_like(x)
    pick = (x > lo) & (x <= hi)
    value = float(np.sum(y[pick] * width[pick]))
    err = float(math.sqrt(np.sum((s[pick] * width[pick]) ** 2)))
    return value, err


@statistic("pore_share_change")
def pore_share_change(data, claim):
    """Change from t = 0 to the last dump of the integral of xi^3 P(xi) over the small pores
    (xi_T, xi_O] or the large ones (> xi_O)."""
    curves = _pore_curves(data)
    if curves is None:
        return not_in_campaign("no pore dumps")
    (t0, first), (t1, last) = curves[0], curves[-1]
    lo, hi = (P.XI_T, P.XI_O) if claim.params.get("range") == "small" else (P.XI_O, math.inf)
    a, ea = _band_integral(first.x, first.mean, first.err, lo, hi)
    b, eb = _band_integral(last.x, last.mean, last.err, lo, hi)
    n = min(first.n.min(), last.n.min())
    shown = f"{fmt(a, ea)} (t = {t0:g}) -> {fmt(b, eb)} (t = {t1:g})"
    dof = _pore_dof(n, [ea, eb])
    if dof is None:
        return [Measure(b - a, shown=shown, undecided="one realization: no error bars")]
    # invariance of the small pores means small against the change of the large ones
    la, _ = _band_integral(first.x, first.mean, first.err, P.XI_O, math.inf)
    lb, _ = _band_integral(last.x, last.mean, last.err, P.XI_O, math.inf)
    return [Measure(b - a, math.hypot(ea, eb), dof, shown=shown, effect=abs(lb - la))]


def _quadratic_law(x, y, s):
    """Weighted fit of c (xi - xi_T)^2 to the bins of (xi_T, xi_O] with error bars: (pick,
    basis, c), None when fewer than three such bins."""
    pick = (x > P.XI_T) & (x <= P.XI_O) & np.isfinite(s) & (s > 0)
    if pick.sum() < 3:
        return None
    basis = (x[pick] - P.XI_T) ** 2
    w = 1 / s[pick] ** 2
    return pick, basis, float(np.sum(w * basis * y[pick]) / np.sum(w * basis**2))


@statistic("pore_quadratic_fit")
def pore_quadratic_fit(data, claim):
    """Chi-square of xi^3 P(xi) = c (xi - xi_T)^2 over (xi_T, xi_O] at the last dump."""
    curves = _pore_curves(data)
    if curves is None:
        return not_in_campaign("no pore dumps")
    t, last = curves[-1]
    x, y, s = last.x, last.mean, last.err
    law = _quadratic_law(x, y, s)
    if law is None:
        return [Measure(undecided="fewer than three histogram bins with error bars between "
                                  "xi_T and xi_O")]
    pick, basis, c = law
    dof = int(pick.sum()) - 1
    chi = float(np.sum((y[pick] - c * basis) ** 2 / s[pick] ** 2)) / dof
    precision = _superimposed_spread(curves, pick, x)
    deviation = float(np.max(np.abs(y[pick] - c * basis)))
    shown = f"reduced chi2 {fmt(chi)} ({dof} dof, t = {t:g})"
    if precision is not None:
        shown += (f"; the law departs from the histogram by at most {fmt(deviation)}, the "
                  f"curves of t = {curves[0][0]:g} to {t:g} by up to {fmt(precision)} (which "
                  "the paper calls superimposed)")
    return [Measure(chi, dof=dof, shown=shown, paper_precision=None if precision is None
                    else paper_precision(deviation, precision))]


def _superimposed_spread(curves, pick, x):
    """The paper's precision for a law of the small pores of Fig. 10a: it calls its curves of
    every t "superimposed for the small pores" (section IV.B), so it could not tell apart
    curves as far from each other as they are there: the largest difference, over the bins
    ``pick`` of (xi_T, xi_O], between any dump's xi^3 P(xi) and the last one's; None with one
    dump."""
    last = curves[-1][1]
    spreads = [np.max(np.abs(np.interp(x[pick], c.x, c.mean) - last.mean[pick]))
               for _, c in curves[:-1]]
    return float(max(spreads)) if spreads and max(spreads) > 0 else None


def pore_law_deviation(fig10):
    """How far the fitted c (xi - xi_T)^2 departs from xi^3 P(xi) at the last dump, relative to
    the histogram's largest value in (xi_T, xi_O] (the scale of the figure; bins near xi_T,
    where the curve starts from zero, would make relative deviations meaningless): dict t,
    bins, rms, max, at (xi of the largest), error (median bin error on the same scale); None
    without bins with error bars."""
    curves = None if fig10 is None else _pore_curves(ReportData({}, {"fig10": fig10}))
    if not curves:
        return None
    t, last = curves[-1]
    x, y, s = last.x, last.mean, last.err
    law = _quadratic_law(x, y, s)
    if law is None:
        return None
    pick, basis, c = law
    scale = float(np.max(y[pick]))
    rel = (y[pick] - c * basis) / scale
    k = int(np.argmax(np.abs(rel)))
    return {"t": t, "bins": int(pick.sum()), "rms": float(np.sqrt(np.mean(rel**2))),
            "max": float(np.abs(rel[k])), "at": float(x[pick][k]),
            "error": float(np.median(s[pick]) / scale)}


def _pore_values(data, name):
    """The Values of statistic ``name`` of Fig. 10's dumps that have it, in the CSV's order
    ([] without Fig. 10)."""
    fig10 = data.result("fig10")
    return [] if fig10 is None else [dump.statistics[name] for dump in fig10.dumps.values()
                                     if name in dump.statistics]


@statistic("nu_tail_over_nu")
def nu_tail_over_nu(data, claim):
    """nu_tail / nu at every dump of Fig. 10 (section IV.B: Fig. 10b draws rho_v(v) at every
    stage of the compaction, t = 0 to 4000, and reads its tail as exp(-v/nu) on all of them),
    one row per t."""
    nu = {v.x: v for v in _pore_values(data, "nu")}
    tail = {v.x: v for v in _pore_values(data, "nu_tail")}
    steps = sorted(set(nu) & set(tail))
    if not steps:
        return not_in_campaign("no nu_tail")
    out = []
    for step in steps:
        m = tail[step].value / nu[step].value
        ratio_err = abs(m) * math.hypot(tail[step].err / tail[step].value,
                                        nu[step].err / nu[step].value)
        s = ratio_err if np.isfinite(ratio_err) else math.nan
        out.append(Measure(float(m), float(s), _pore_dof(min(nu[step].n, tail[step].n), s),
                           label=f"t = {step:g}"))
    return out


@statistic("pore_gaussian_excess")
def pore_gaussian_excess(data, claim):
    """Section IV.B: xi^3 P(xi) "is more or less close to a Gaussian distribution with an
    over-population for the largest pores". At every dump of Fig. 10a: the share of the
    distribution beyond its mean plus GAUSSIAN_TAIL_SD standard deviations (its own moments)
    minus a Gaussian's share there; positive: the largest pores over-populated. Error: the
    bins' own errors (independent), through the tail's integral."""
    curves = _pore_curves(data)
    if curves is None:
        return not_in_campaign("no pore dumps")
    gaussian = float(stats.norm.sf(GAUSSIAN_TAIL_SD))
    out = []
    for t, curve in curves:
        x, y, s = curve.x, curve.mean, curve.err
        ok = np.isfinite(y) & (y >= 0)
        total = _band_integral(x[ok], y[ok], s[ok], -math.inf, math.inf)[0]
        if not total > 0:
            continue
        mean = float(np.sum(x[ok] * y[ok]) / np.sum(y[ok]))
        sd = float(math.sqrt(np.sum((x[ok] - mean) ** 2 * y[ok]) / np.sum(y[ok])))
        edge = mean + GAUSSIAN_TAIL_SD * sd
        tail, err = _band_integral(x[ok], y[ok], s[ok], edge, math.inf)
        n = int(np.min(curve.n))
        out.append(Measure(tail / total - gaussian, err / total, _pore_dof(n, err),
                           label=f"t = {t:g}",
                           shown=f"share beyond xi = {edge:.3g} (mean {mean:.3g} + "
                                 f"{GAUSSIAN_TAIL_SD:g} sd): {fmt(tail / total, err / total)} "
                                 f"against a Gaussian's {100 * gaussian:.2f} %"))
    return out or not_in_campaign("no pore distribution")


@statistic("nu_change")
def nu_change(data, claim):
    nu = _pore_values(data, "nu")
    if not nu:
        return not_in_campaign("no nu")
    first, last = nu[0], nu[-1]
    err = math.hypot(last.err, first.err)
    return [Measure(last.value - first.value, err, _pore_dof(min(first.n, last.n), err),
                    shown=f"{fmt(first.value, first.err, digits=4)} -> "
                          f"{fmt(last.value, last.err, digits=4)}")]
