# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Statistics of the compaction laws (eq. 3, the inverse-log law, and eq. 4, Z's law; Fig. 2):
the fits' quality over realizations, whether eq. 3's triplet is fixed, and B's exponential
dependence on eps."""

from __future__ import annotations

import dataclasses
import math
import sys

import numpy as np
from scipy.stats import chi2 as chi2_distribution

from tapmc.laws import (InverseLogLaw, RealizationLawTest, SURROGATE_P_MIN, TwoExponentials,
                        ZLaw)
from tapmc.stats import mean_dof

from .common import curve_arrays, fig2_curves, not_in_campaign, paper_precision
from .conventions import (FIT_P_VALUE, PACKING_FRACTION_PRECISION, RANDOM_CLOSE_PACKING,
                          REALIZATION_MIN_SEEDS, REALIZATION_MIN_TAPS, SURROGATE_BAND_WIDENING)
from .measure import Measure, fmt
from .registry import statistic


def _fit_quality(curve, npoints, nparams, label):
    """The reduced chi-square of the figure's own fit of one curve (a Fig. 2 CurveFit)."""
    chi = curve.reduced_chi2.value
    if not np.isfinite(chi):
        return Measure(label=label, undecided="no fit in the figure data")
    dof = npoints - nparams
    shown = f"reduced chi2 {fmt(chi)} ({dof} dof)"
    if dof < 1:
        return Measure(chi, label=label, shown=shown, undecided="fewer points than parameters")
    return Measure(chi, dof=dof, label=label, shown=shown)


def _law_quality(eps, curve):
    """The chi-square of a 4-parameter law of Fig. 2 on one curve (a CurveFit, the figure's
    ``eps=<e>:<prefix>reduced_chi2``; eq. 3: no prefix; eq. 4: ``Z:``), shown but undecided:
    the taps of a run are correlated (Fig. 3), so a chi-square over them with per-tap errors
    has no known distribution, whatever the number of seeds (with two seeds the medium
    preset's eq. 3 fits had reduced chi2 0.03: a test that cannot fail). The laws are decided
    across realizations (:func:`_law_across_realizations`)."""
    t, _, _, n = curve_arrays(curve)
    m = _fit_quality(curve, len(t), 4, f"eps = {eps:g}")
    if m.undecided is None:
        seeds = mean_dof(n)
        if seeds is None:
            # without error bars the fit's "reduced chi2" is its mean squared residual
            m.shown = f"rms residual {fmt(math.sqrt(m.value))}"
            m.undecided = ("one realization: no error bars for a chi-square (the taps' "
                           "scatter is correlated)")
        else:
            m.undecided = (f"{seeds + 1} seeds: a chi-square over correlated taps has no "
                           f"known distribution; needs {REALIZATION_MIN_SEEDS} "
                           "realizations (tapmc-paper question early-taps)")
    return m


def realization_curves(data, eps, column):
    """(t, curves) of ``column`` over the realizations of early_taps.csv at ``eps`` (one row
    per seed, the taps 0..T every one of them has), or None when fewer than
    :data:`REALIZATION_MIN_SEEDS` span :data:`REALIZATION_MIN_TAPS` taps."""
    by_seed = {}
    for r in data.question("early_taps"):
        if math.isclose(float(r["eps"]), eps, rel_tol=1e-9):
            by_seed.setdefault(int(r["seed"]), {})[int(float(r["t"]))] = float(r[column])
    seeds = [s for s, v in by_seed.items() if max(v) >= REALIZATION_MIN_TAPS]
    if len(seeds) < REALIZATION_MIN_SEEDS:
        return None
    last = min(max(by_seed[s]) for s in seeds)
    t = np.arange(0, last + 1)
    if not all(all(k in by_seed[s] for k in t) for s in seeds):
        return None
    return t.astype(float), np.array([[by_seed[s][k] for k in t] for s in sorted(seeds)])


def loosening_end(data, eps):
    """The first tap at which the mean Phi_b over the realizations of early_taps.csv at
    ``eps`` is back at its t = 0 value (the first taps loosen the deposited packing, which no
    monotonic law follows), or None (too few realizations, or still loose at their last tap)."""
    curves = realization_curves(data, eps, "phi_b")
    return None if curves is None else back_at_start(curves[0], curves[1].mean(axis=0))


def back_at_start(t, mean):
    """The first tap t >= 1 at which ``mean`` (Phi_b over realizations, t[0] = 0) is back at
    its t = 0 value, or None."""
    back = np.flatnonzero((np.asarray(t) >= 1) & (np.asarray(mean) >= mean[0]))
    return float(t[back[0]]) if back.size else None


#: RealizationLawTest results already computed, by (law class, t_min, curves, the library's
#: conventions): see :func:`_realization_law_test`
_LAW_TESTS = {}


def _library_conventions():
    """The values of every upper-case name the modules of the library (tapmc outside
    tapmc.paper, where RealizationLawTest and what it calls live) bind now: a convention the
    report's table of tolerances varies there changes them, and with them the cache key."""
    return tuple((key, name, value) for key, module in sorted(sys.modules.items())
                 if module is not None and key.startswith("tapmc.")
                 and not key.startswith("tapmc.paper")
                 for name, value in sorted(vars(module).items())
                 if name.isupper() and isinstance(value, (int, float)))


def _realization_law_test(law, t_min, curves):
    """``RealizationLawTest(law, t_min).compute(*curves)``, computed once per law class, start,
    curves and state of the library's conventions: the report's table of tolerances
    re-evaluates the Fig. 2 claims on the same data for every convention it varies (each test
    fits its law on grids of starts, about 0.2 s). The laws of Fig. 2 have no parameters of
    their own (each call site makes a fresh one), so the class stands for the law; the
    result is read, never changed, by its callers."""
    t, values = curves
    key = (type(law).__qualname__, float(t_min), np.asarray(t).tobytes(),
           np.asarray(values).shape, np.asarray(values).tobytes(), _library_conventions())
    if key not in _LAW_TESTS:
        _LAW_TESTS[key] = RealizationLawTest(law, t_min=t_min).compute(*curves)
    return _LAW_TESTS[key]


def _law_across_realizations(data, eps, law, column):
    """One measure per eps of a law of Fig. 2 tested across the realizations of
    early_taps.csv at ``eps`` (tapmc.laws.RealizationLawTest) from the end of the first taps'
    loosening (:func:`loosening_end`): the first taps loosen the deposited packing below its
    t = 0 value, which no monotonic law follows, so the law is tested where the compaction
    has begun; the test over every tap is shown beside it and decides nothing. With the
    largest departure of the law from the bins' means against the paper's precision
    (:func:`_law_precision`). None when the realizations are too few."""
    curves = realization_curves(data, eps, column)
    if curves is None:
        return None
    label = f"eps = {eps:g}"
    back = loosening_end(data, eps)
    if back is None or back * 10 > curves[0][-1]:
        return [Measure(label=label, undecided=(
            "the packing is still looser than at t = 0 a decade before the realizations' "
            "last tap"))]
    test = _realization_law_test(law, back, curves)
    edges = test.bin_edges
    shown = (f"T^2 {fmt(test.chi2)} ({test.dof} dof) over taps {edges[0]:g}-{edges[-1] - 1:g} "
             f"in {len(edges) - 1} log bins, {test.realizations} realizations from the same "
             f"packing; {_deviation_text(test, column)}")
    if back > 1.0:
        every = _realization_law_test(law, 1.0, curves)
        shown += (f"; from tap 1, the loosening included (decides nothing): T^2 "
                  f"{fmt(every.chi2)}, p = {every.p_value:.2g}")
    return [Measure(test.chi2, dof=test.dof, p_value=test.p_value, label=label, shown=shown,
                    paper_precision=_law_precision(test, column))]


def _law_precision(test, column):
    """The largest departure of a RealizationLawTest's law from the bins' means in units of
    the paper's precision: for Phi_b, half a unit of the last digit the paper prints of a
    packing fraction (:data:`PACKING_FRACTION_PRECISION`); None for <Z>, of which the paper
    prints no value."""
    if column != "phi_b":
        return None
    return paper_precision(_largest_deviation(test), PACKING_FRACTION_PRECISION)


def _largest_deviation(test):
    return float(np.max(np.abs(np.asarray(test.bin_means, dtype=float) - test.bin_model)))


def _deviation_text(test, column):
    text = f"the law departs from the bins' means by at most {fmt(_largest_deviation(test))}"
    if column != "phi_b":
        return text
    return text + f" (the paper's precision: {fmt(PACKING_FRACTION_PRECISION)})"


def _fig2_law_quality(data, law, column, tag):
    """Per eps of Fig. 2's curves of law ``tag``: the law across realizations where
    early_taps.csv has them (from the end of the first taps' loosening), else the chi-square
    of the figure's own fit (:func:`_law_quality`)."""
    curves, missing = fig2_curves(data, tag)
    if curves is None:
        return missing
    out = []
    for eps, curve in curves:
        ms = _law_across_realizations(data, eps, law, column)
        out += ms if ms is not None else [_law_quality(eps, curve)]
    return out


@statistic("eq3_fit_quality")
def eq3_fit_quality(data, claim):
    return _fig2_law_quality(data, InverseLogLaw(), "phi_b", "eq3")


#: Parameters of eq. 3 whose uniqueness section III.B discusses: the triplet (X_inf, B, tau).
EQ3_TRIPLET = ("X_inf", "B", "tau")


#: why the fits of Fig. 2 decide nothing with one run per eps: their errors come from the
#: scatter of the taps about the law, whose correlation (Fig. 3's spectrum) they ignore, so
#: the intervals, the range tests and B's errors would be too narrow
ONE_RUN_FITS = "one realization: the fits' intervals ignore the taps' correlation"

#: the same for a curve averaged over seeds: each tap's error is the seeds' spread there, but
#: a seed's taps move together over hundreds of taps, and the fit takes the taps as
#: independent points, so its intervals and range tests are too narrow in both directions
#: (a "unique" and a "range dependent" alike); fits of each seed (seed-fits) or of one run's
#: surrogates (fit-surrogates) decide instead
AVERAGED_FITS = ("a seed-averaged curve: the fits' intervals take its correlated taps as "
                 "independent (tapmc-paper question fit-surrogates and seed-fits decide)")


def _one_run_fig2(curves):
    """True when every curve of Fig. 2 (``curves``: [(eps, CurveFit)]) is one run (n = 1)."""
    return bool(curves) and max(np.nanmax(c.data.n) for _, c in curves) < 2


def _run_seed(name):
    """The seed of a campaign run's folder name (``..._s<seed>``)."""
    return int(name.rsplit("_s", 1)[1])


def surrogate_fits(data, law):
    """eps -> {parameter: row} of fit_surrogates.csv for ``law`` ('eq3', 'eq4') and the
    campaign's run of the paper's protocol at each eps: the first seed (the other seeds'
    rows, and the realizations of the first taps, are shown beside it, not read here)."""
    first = {}
    for r in data.question("fit_surrogates"):
        if r["source"] != "realizations" and r["law"] == law:
            e = float(r["eps"])
            first[e] = min(first.get(e, r["source"]), r["source"], key=_run_seed)
    out = {}
    for r in data.question("fit_surrogates"):
        if r["law"] == law and first.get(float(r["eps"])) == r["source"]:
            out.setdefault(float(r["eps"]), {})[r["parameter"]] = r
    return dict(sorted(out.items()))


def _surrogate_uniqueness(params, names):
    """(unique, reason) of one run's parameters ``names`` from its fit_surrogates rows."""
    undetermined = [k for k in names if params[k]["determined"] != "1"]
    dependent = [k for k in names if float(params[k]["range_p"]) < SURROGATE_P_MIN]
    reasons = ([f"{', '.join(undetermined)} undetermined"] if undetermined else []) + \
        ([f"{', '.join(dependent)} range dependent"] if dependent else [])
    return not reasons, "; ".join(reasons) or "unique within the surrogates"


#: why a "unique" triplet of one run decides nothing: the surrogates' bands are narrower than
#: the spread of independent realizations (tests/python/test_slow_surrogate_fits.py)
SURROGATES_UNIQUE = ("one run's surrogates show an upper bound of how well the triplet is "
                     "fixed: 'unique' needs realizations")


def realization_fits(data, law, bc):
    """eps -> {parameter: row} of seed_fits.csv (tapmc-paper question seed-fits: whole runs
    fitted over realizations, tapmc.laws.RealizationFits) for ``law`` ('eq3', 'eq4') and
    boundary condition ``bc``; at an eps with several groups, the one of most realizations."""
    out = {}
    for r in data.question("seed_fits"):
        if r["law"] != law or r["bc"] != bc:
            continue
        group = out.setdefault(float(r["eps"]), {})
        if group and int(next(iter(group.values()))["realizations"]) > int(r["realizations"]):
            continue
        if group and next(iter(group.values()))["group"] != r["group"]:
            group.clear()
        group[r["parameter"]] = r
    return dict(sorted(out.items()))


def _realization_uniqueness(params, names):
    """(unique: True, False or None, reason) of the triplet ``names`` from one group's
    seed_fits rows: the spread over realizations decides "determined" both ways (its
    chi-square interval), a paired t-test over the ranges "range dependent"."""
    def spread(k):
        r = params[k]
        unit = "ln " if r["log_scale"] == "1" else ""
        return (f"sd of {unit}{k} {float(r['spread']):.2g} (95 %: {float(r['spread_low']):.2g} "
                f"to {float(r['spread_high']):.2g}; limit {float(r['limit']):.2g})")

    undetermined = [k for k in names if params[k]["determined"] == "0"]
    open_ = [k for k in names if params[k]["determined"] == ""]
    dependent = [k for k in names if float(params[k]["range_p"]) < SURROGATE_P_MIN]
    n = params[names[0]]["realizations"]
    reasons = ([f"{', '.join(undetermined)} undetermined ({'; '.join(map(spread, undetermined))})"]
               if undetermined else []) + \
        ([f"{', '.join(dependent)} range dependent"] if dependent else [])
    if reasons:
        return False, f"{n} realizations: " + "; ".join(reasons)
    if open_:
        return None, (f"{n} realizations cannot tell whether {', '.join(open_)} "
                      f"{'is' if len(open_) == 1 else 'are'} fixed "
                      f"({'; '.join(map(spread, open_))})")
    return True, f"{n} realizations: unique"


def _triplet_pattern(states, shown):
    """The pattern over ``states`` [(eps, unique: True/False/None, reason)], by eps: holds
    (1) when the smallest eps is not unique and a larger one is, contradicted (0) when the
    smallest is unique or none is, undecided otherwise."""
    first = states[0][1]
    if first is True or all(u is False for _, u, _ in states):
        return [Measure(0.0, shown=shown)]
    if first is False and any(u is True for _, u, _ in states[1:]):
        return [Measure(1.0, shown=shown)]
    return None


def _triplet_from_surrogates(rows, realized=None):
    """The pattern from one run per eps (fit_surrogates.csv): "not unique" is safe (the
    surrogates' bands are too narrow, never too wide), "unique" is not. Where realizations
    of whole runs (``realized``: seed_fits rows by eps) decide, they replace the run's
    verdict; where they cannot tell, a run's "not unique" still decides."""
    realized = realized or {}
    states = []
    for e in sorted(set(rows) | set(realized)):
        one = _surrogate_uniqueness(rows[e], EQ3_TRIPLET) if e in rows else None
        many = _realization_uniqueness(realized[e], EQ3_TRIPLET) if e in realized else None
        if many is not None and (many[0] is not None or one is None or one[0]):
            unique = many[0]
            why = many[1] + (f" (the run's surrogates: {one[1]})" if one else "")
        else:
            unique = False if not one[0] else None
            why = one[1] + (f" ({many[1]})" if many else "")
        states.append((e, unique, why))
    shown = "; ".join(f"eps = {e:g}: {why}" for e, _, why in states) + \
        " (one run per eps, Fourier surrogates of its residuals: fit_surrogates.csv" + \
        ("; realizations of whole runs: seed_fits.csv)" if realized else ")")
    decided = _triplet_pattern(states, shown)
    if decided is not None:
        return decided
    unsure = [e for e, u, _ in states if u is None]
    if all(e not in realized for e in unsure):
        return [Measure(undecided=SURROGATES_UNIQUE, shown=shown)]
    return [Measure(undecided=_REALIZATIONS_UNSURE.format(", ".join(f"{e:g}" for e in unsure)),
                    shown=shown)]


#: why realizations of whole runs leave the pattern open (they decide "fixed" both ways)
_REALIZATIONS_UNSURE = ("the realizations cannot tell whether the triplet is fixed at eps = {}: "
                        "their spread's 95 % interval straddles the limit")


def _triplet_from_realizations(realized, label):
    """The pattern from realizations of whole runs alone (seed_fits.csv rows by eps)."""
    states = [(e, *_realization_uniqueness(p, EQ3_TRIPLET)) for e, p in realized.items()]
    shown = "; ".join(f"eps = {e:g}: {why}" for e, _, why in states) + \
        " (realizations of whole runs: seed_fits.csv)"
    decided = _triplet_pattern(states, shown)
    if decided is not None:
        return [Measure(decided[0].value, label=label, shown=shown)]
    unsure = ", ".join(f"{e:g}" for e, u, _ in states if u is None)
    return [Measure(undecided=_REALIZATIONS_UNSURE.format(unsure), label=label, shown=shown)]


@statistic("eq3_triplet_pattern")
def eq3_triplet_pattern(data, claim):
    """Section III.B: the triplet is not unique at the smallest eps and unique at some larger
    eps (1), or not (0). Fig. 2's F.B.C. runs (their surrogates, and realizations of whole
    runs where the campaign has them); a second row from the P.B.C. groups of realizations
    when there are two eps or more. Fig. 2's own fits (one run, or a seed-averaged curve)
    decide nothing (:data:`ONE_RUN_FITS`, :data:`AVERAGED_FITS`)."""
    rows = surrogate_fits(data, "eq3")
    if len(rows) >= 2:
        out = _triplet_from_surrogates(rows, realization_fits(data, "eq3", "fbc"))
        pbc = realization_fits(data, "eq3", "pbc")
        if len(pbc) >= 2:
            out = [dataclasses.replace(out[0], label="F.B.C., Fig. 2's runs")] + \
                _triplet_from_realizations(pbc, "P.B.C. realizations")
        return out
    if data.result("fig2") is None:
        return not_in_campaign("no Fig. 2 runs")
    curves = fig2_curves(data)[0] or []
    if len(curves) < 2:
        return not_in_campaign("fewer than two eps in Fig. 2")
    return [Measure(undecided=ONE_RUN_FITS if _one_run_fig2(curves) else AVERAGED_FITS)]


def _band(row):
    """(value, low, high, determined) of a fit_surrogates.csv row."""
    return (float(row["value"]), float(row["low"]), float(row["high"]),
            row["determined"] == "1")


def _widened(row, factor=None):
    """(low, high) of a fit_surrogates.csv row's band widened by ``factor`` (default
    :data:`SURROGATE_BAND_WIDENING`) about its fitted value, on the band's own scale (log for
    B and tau, ``log_scale``): what one run's surrogates can exclude, not their bare band."""
    factor = SURROGATE_BAND_WIDENING if factor is None else factor
    value, low, high, _ = _band(row)
    if row.get("log_scale") == "1" and min(value, low, high) > 0:
        return value * (low / value) ** factor, value * (high / value) ** factor
    return value - factor * (value - low), value + factor * (high - value)


@statistic("eq3_small_eps_asymptote")
def eq3_small_eps_asymptote(data, claim):
    """Section III.B: "in this small excitations range, X_inf can get over the R.C.P. limit
    and tau, the characteristic time of the fit, increases spectacularly". From one run per
    eps of Fig. 2 (fit_surrogates.csv, the paper's protocol), two patterns: tau's band at the
    smallest eps above the band of every larger eps where tau is determined (1); X_inf's band
    at the smallest eps beyond RANDOM_CLOSE_PACKING (1). One run's surrogate bands are too
    narrow (test_slow_surrogate_fits.py): each is widened by SURROGATE_BAND_WIDENING before it
    separates anything (:func:`_widened`), an overlap stays undecided (never contradicts), and
    a degenerate fit (X_inf undetermined, up to 1e4) is reported as such."""
    rows = surrogate_fits(data, "eq3")
    if len(rows) < 2:
        return not_in_campaign("fewer than two eps with fits of one run's surrogates "
                               "(tapmc-paper question fit-surrogates)")
    eps = sorted(rows)
    small, others = eps[0], eps[1:]
    x_text = "; ".join(
        f"eps = {e:g}: X_inf {_band(rows[e]['X_inf'])[0]:.3g} "
        + ("({:.3g}-{:.3g})".format(*_band(rows[e]["X_inf"])[1:3])
           if _band(rows[e]["X_inf"])[3] else "(degenerate: undetermined)") for e in eps)
    tau_text = "; ".join(f"eps = {e:g}: tau {_band(rows[e]['tau'])[0]:.3g} "
                         f"({_band(rows[e]['tau'])[1]:.3g}-{_band(rows[e]['tau'])[2]:.3g})"
                         for e in eps)
    widening = (f"bands widened x {SURROGATE_BAND_WIDENING:g}, the surrogates' measured "
                "under-coverage")
    low = _widened(rows[small]["tau"])[0]
    determined = [e for e in others if _band(rows[e]["tau"])[3]]
    if not determined:
        tau = Measure(label="tau grows at the smallest eps", shown=tau_text,
                      undecided="tau undetermined at every larger eps")
    else:
        top_eps = max(determined, key=lambda e: _widened(rows[e]["tau"])[1])
        high = _widened(rows[top_eps]["tau"])[1]
        compared = (f"{widening}: tau above {low:.3g} at eps = {small:g}, below {high:.3g} "
                    f"at eps = {top_eps:g}")
        if low > high:
            tau = Measure(1.0, label="tau grows at the smallest eps",
                          shown=f"{tau_text} ({compared})")
        else:
            tau = Measure(label="tau grows at the smallest eps", shown=tau_text, undecided=(
                f"{compared}: they overlap (one run's surrogates: too narrow to decide "
                "either way)"))
    fixed = _band(rows[small]["X_inf"])[3]
    low, high = _widened(rows[small]["X_inf"])
    label = "X_inf beyond the random close packing at the smallest eps"
    if fixed and low > RANDOM_CLOSE_PACKING:
        x_inf = Measure(1.0, label=label, shown=f"{x_text} ({widening}: above {low:.3g})")
    else:
        x_inf = Measure(label=label, shown=x_text, undecided=(
            f"X_inf at eps = {small:g} " + ("undetermined (a degenerate fit)" if not fixed else
                                            f"within {low:.3g}-{high:.3g} ({widening}), not "
                                            f"above {RANDOM_CLOSE_PACKING:g}: one run's "
                                            "surrogates, too narrow to contradict")))
    return [tau, x_inf]


@statistic("z_two_exponentials")
def z_two_exponentials(data, claim):
    """Section III.A: "a sum of two exponentials can also fit reasonably well <Z>(t)":
    tapmc.laws.TwoExponentials tested like eq. 4, across the realizations of early_taps.csv
    at each eps from the end of the first taps' loosening (:func:`_law_across_realizations`)."""
    eps_values = sorted({float(r["eps"]) for r in data.question("early_taps")})
    out = []
    for eps in eps_values:
        out += _law_across_realizations(data, eps, TwoExponentials(), "Z") or []
    return out or not_in_campaign(f"fewer than {REALIZATION_MIN_SEEDS} realizations of "
                                  f"{REALIZATION_MIN_TAPS} taps or more (tapmc-paper question "
                                  "early-taps)")


@statistic("eq4_fit_quality")
def eq4_fit_quality(data, claim):
    return _fig2_law_quality(data, ZLaw(), "Z", "eq4")


def _b_from_surrogates(rows, label):
    """ln B against sqrt(eps) from one run per eps (fit_surrogates.csv): only where B is
    determined (an undetermined B is safe, a determined one an upper bound), with the
    surrogates' half widths as errors. Too narrow errors make a rejection unsafe and an
    agreement safe, so only agreement decides."""
    determined = {e: p["B"] for e, p in rows.items() if p["B"]["determined"] == "1"}
    text = "; ".join(f"eps = {e:g}: B {float(p['B']['value']):.3g} "
                     f"({float(p['B']['low']):.3g}-{float(p['B']['high']):.3g})"
                     for e, p in rows.items())
    if len(determined) < 3:
        missing = [f"{e:g}" for e in rows if e not in determined]
        return Measure(label=label, shown=text,
                       undecided=f"B undetermined at eps = {', '.join(missing)} (one run per "
                                 "eps, Fourier surrogates): fewer than three eps with a "
                                 "determined B")
    x = np.sqrt(np.array(list(determined)))
    y = np.log([float(p["value"]) for p in determined.values()])
    err = np.array([float(p["half_width"]) for p in determined.values()])
    coef = np.polyfit(x, y, 1, w=1.0 / err)
    chi = float(np.sum(((y - np.polyval(coef, x)) / err) ** 2))
    dof = len(x) - 2
    p_value = float(chi2_distribution.sf(chi, dof))
    shown = f"{text}; d ln B / d sqrt(eps) = {coef[0]:.3g}, chi2 {chi:.3g} ({dof} dof)"
    if p_value >= FIT_P_VALUE:
        return Measure(chi / dof, dof=dof, label=label, shown=shown, p_value=p_value)
    return Measure(label=label, shown=shown,
                   undecided=f"p = {p_value:.2g}, but one run's surrogate errors are too "
                             "narrow to reject")


def _has_b_fit(dependence):
    """Whether Fig. 2's data have the straight line of ln B in sqrt(eps) of a law (its
    ``<law>:reduced_chi2`` row; a table built in memory may lack it: NaN with n = 0 and no
    B rows)."""
    chi2 = dependence.reduced_chi2
    return np.isfinite(chi2.value) or chi2.n != 0 or len(dependence.B) > 0


@statistic("b_exponential")
def b_exponential(data, claim):
    """ln B linear in sqrt(eps) (Fig. 2 panel B) for the B of eq. 3 and of eq. 4."""
    from_surrogates = [_b_from_surrogates(rows, f"B of {law.replace('eq', 'eq. ')}")
                       for law in ("eq3", "eq4") if len(rows := surrogate_fits(data, law)) >= 1]
    if from_surrogates:
        return from_surrogates
    fig2 = data.result("fig2")
    if fig2 is None:
        return not_in_campaign("no Fig. 2 runs")
    one_run = _one_run_fig2(fig2_curves(data)[0] or [])
    out = []
    for law in ("eq3", "eq4"):
        dependence = fig2.laws[law].B if law in fig2.laws else None
        if dependence is None or not _has_b_fit(dependence):
            continue
        chi, dof = dependence.reduced_chi2.value, dependence.reduced_chi2.n
        slope = dependence.slope
        text = "" if slope is None else \
            f"d ln B / d sqrt(eps) = {fmt(slope.value.value, slope.value.err)}; "
        label = f"B of {law.replace('eq', 'eq. ')}"
        if one_run:
            out.append(Measure(label=label, undecided=ONE_RUN_FITS,
                               shown=text.rstrip("; ") or None))
        elif dof < 1 or not np.isfinite(chi):
            out.append(Measure(label=label, undecided="fewer than three eps with a determined B",
                               shown=text.rstrip("; ") or None))
        elif chi2_distribution.sf(chi * dof, dof) < FIT_P_VALUE:
            out.append(Measure(label=label, shown=f"{text}reduced chi2 {fmt(chi)} ({dof} dof)",
                               undecided=f"{AVERAGED_FITS}: too narrow to reject"))
        else:
            out.append(Measure(chi, dof=dof, label=label,
                               shown=f"{text}reduced chi2 {fmt(chi)} ({dof} dof)"))
    return out or not_in_campaign("no B(sqrt(eps)) fit in the Fig. 2 data")
