# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Questions of the validation settled by a measurement, rendered from the CSVs that
``bench/paper_questions.py`` writes into ``<report>/validation/questions/``: every number and
every conclusion below is computed from those files, so the report can be rewritten from
committed data.

* ``first_tap.csv``: <Phi^c> before and after one tap from fresh packings, at several eta:
  whether the drop of <Phi^c> at the first tap of P.B.C. runs survives a tighter redeposition.
* ``noise_floor.csv``: sigma_<Z> of 1000 taps at eps = 0 from a tapped packing: the floor
  under Fig. 3's sigma_<Z> = k sqrt(eps).
* ``spectral_window.csv``: the slope of Fig. 3's spectrum over steady windows of several
  lengths, per run: whether the window (250 taps in the medium preset, 1000 in the paper)
  moves it.
* ``pbc_course.csv``: the course of <Phi^c> in every P.B.C. run of the campaign: how deep
  and how long the dip after the first taps is, and whether strong taps (eps >= 0.09) leave
  the packing looser than it started or still compacting at the end.
* ``realization_scatter.csv``: the steady state of every group of runs that differ only in
  their seed: whether one run's batch-means error tells how far another realization lands,
  and the factor it falls short by (tapmc.fluctuations.ErrorCalibration).
* ``packing_scatter.csv``: the same question for the spatial jackknife of one packing (nu of
  the pores, alpha of the profile) over the final and the initial packings of those groups.
* ``integrity.csv``: every dump of the campaign checked offline: overlaps, floor and walls,
  and the printed scalars of that tap recomputed from the positions.
* ``early_taps.csv``: the first 400 taps from the campaign's F.B.C. packing over several
  realizations: the first-decade rates of the efficiency and slowing claims, and the test of
  eqs. 3 and 4 across realizations.
* ``fit_surrogates.csv``: eqs. 3 and 4 fitted to each F.B.C. run with Fourier surrogates of
  its residuals, and to each realization of the first taps: whether one run fixes the triplet
  and whether it depends on the tap range (section III.B).
* ``seed_fits.csv``: the same fits over realizations of whole runs (the groups of seeds):
  whether the triplet is fixed, decided both ways by the spread over the runs.
* ``initial_packing.csv``: the initial P.B.C. packing of several depositions at t = 0: the
  spread between packings that a campaign started from one packing hides.
* ``p0_configs.csv``: Fig. 9's P0(sigma) over several depositions and several configurations
  of the tapped packing: the error bars that decide Fig. 9's two comparisons.
* ``lateral_first_tap.csv``: the first taps from the paper's F.B.C. start (periodic
  deposition, walls, slight agitation), which the campaign's F.B.C. runs do not use.
* ``ramp_levels.csv``: ramp levels continued from their end to the paper's 4000 taps: what
  the campaign's shorter levels change.
* Fig. 10's pores (its CSV, no measurement of its own): how much the small pores change
  against the large ones, and how closely (xi - xi_T)^2 follows xi^3 P(xi) between xi_T and
  xi_O, the two pore claims a precise single run rejects.
* the final <Phi^c> of Fig. 9's run carried to every redeposition setting of the
  run-time-versus-error front (its ``front_summary.csv``): which thresholds the paper's 60.6 %
  fits.
* ``theta0.csv``: the compaction over 100 taps from the same packings at several widths
  theta0 of the trial moves' angular distribution: whether pi/4 compacts most (section II).
* ``p0_fluid.csv``: Gotoh's P0(sigma) of equilibrium hard-sphere fluids measured as Fig. 9
  measures the packings, against Percus-Yevick: how closely PY describes an exact fluid, the
  baseline of the packings' agreement with it (Fig. 9).
"""

from __future__ import annotations

import csv
import math
from collections import defaultdict
from pathlib import Path

import numpy as np

from tapmc.fluctuations import DEFAULT_BATCHES

from tapmc.pores import XI_T

from .claims import (CALIBRATION_ALPHA, RAMP_LEVELS_DEFAULT_RUN, RUN_ERROR_LABELS,
                     RUN_ERROR_QUANTITIES, ZONE_QUANTITIES, fmt,
                     realization_calibrations,
                     realization_factors, realization_sharing, t_quantile)

FOLDER = "questions"
#: share of the first-tap drop at eta = 1e-7 that must remain at the tightest eta for the
#: drop to be called a property of the model rather than of the stopping rule.
MODEL_EFFECT_SHARE = 0.5
#: relative departure of the measured contact value g(1+) from Carnahan-Starling allowed of an
#: equilibrium fluid: CS is within 1 % of simulations up to Phi = 0.54, the extrapolation of
#: g(r) to contact adds about as much; a crystallised or unrelaxed sample is off by more.
CONTACT_TOLERANCE = 0.03
#: the packing's max |P0 - PY| is called "of the fluid's size" when within this factor of the
#: fluid's (at the highest Phi measured, or the fluid's trend carried to the packing's Phi when
#: that is larger), and beyond it otherwise.
BASELINE_FACTOR = 2.0
#: the strong taps of the question on loosening (issue of the paper-scale validation: the
#: packing was seen to loosen at eps >= 0.09, where Fig. 4's bell falls)
STRONG_EPS = 0.09
#: degrees of freedom of the difference of the steady window's halves (each half has half the
#: batches of tapmc.fluctuations.SteadyState)
HALVES_DOF = DEFAULT_BATCHES // 2 - 1
#: rms departure of the (xi - xi_T)^2 law from xi^3 P(xi), relative to the curve's largest
#: value between xi_T and xi_O, below which the law is called a fair description of the shape
#: (the paper's "reasonably well", read off its figure: a tenth of the curve's height is
#: about the width of its plotted line and symbols)
LAW_FAIR_DEVIATION = 0.1


def _read(path):
    with open(path, newline="") as handle:
        return list(csv.DictReader(handle))


def _first_tap(path):
    rows = _read(path)
    groups = defaultdict(list)
    for r in rows:
        groups[(float(r["eps"]), float(r["eta"]))].append(r)
    lines = ["The first tap of P.B.C. runs lowers <Phi^c> (the dip of the first taps). Is it the "
             "model or a redeposition stopped too early? One tap from the same fresh packings "
             "(N = 4096, L = 32R), at three eta (``first_tap.csv``; mean ± sem over seeds):", "",
             ".. list-table::", "   :header-rows: 1", "",
             "   * - eps", "     - eta", "     - <Phi^c> at t = 0", "     - after one tap",
             "     - change", "     - sweeps"]
    drops = {}
    for (eps, eta), group in sorted(groups.items(), key=lambda kv: (kv[0][0], -kv[0][1])):
        p0 = np.array([float(r["phi_c_0"]) for r in group])
        p1 = np.array([float(r["phi_c_1"]) for r in group])
        sweeps = np.array([float(r["sweeps_1"]) for r in group])
        d = p1 - p0
        sem = float(np.std(d, ddof=1) / math.sqrt(len(d))) if len(d) > 1 else math.nan
        drops[(eps, eta)] = (float(np.mean(d)), sem, len(d))
        lines += [f"   * - {eps:g}", f"     - {eta:g}", f"     - {fmt(np.mean(p0), None, True)}",
                  f"     - {fmt(np.mean(p1), None, True)}",
                  f"     - {fmt(np.mean(d), sem, True)}", f"     - {np.mean(sweeps):.0f}"]
    lines.append("")
    for eps in sorted({e for e, _ in drops}):
        etas = sorted(eta for e, eta in drops if e == eps)
        loose, tight = drops[(eps, etas[-1])], drops[(eps, etas[0])]
        share = tight[0] / loose[0] if loose[0] else math.nan
        significant = tight[2] > 1 and abs(tight[0]) > t_quantile(tight[2] - 1) * tight[1]
        model = significant and share >= MODEL_EFFECT_SHARE
        lines.append(
            f"* eps = {eps:g}: at eta = {etas[0]:g} the change is {fmt(tight[0], tight[1], True)}, "
            f"{100 * share:.0f} % of the change at eta = {etas[-1]:g}: "
            + ("a property of the model (the redeposition of the dilated packing leaves it "
               "looser than the sequential deposition it starts from), not of the stopping rule."
               if model else
               "not distinguishable from an effect of the stopping rule at these seeds."))
    lines += ["", "The paper draws Fig. 2 from t = 1 on a logarithmic axis, where a change at "
              "the first tap does not show.", ""]
    return lines


def _noise_floor(path, fig3=None):
    values = {r["quantity"]: float(r["value"]) for r in _read(path)}
    sigma = values["sigma_Z"]
    lines = [f"sigma_<Z> without taps (``noise_floor.csv``): {int(values['taps'])} taps at "
             f"eps = 0 from the P.B.C. packing after 4000 taps at eps = 0.0225 give sigma_<Z> = "
             f"{fmt(sigma)} ({fmt(values['sigma_Z_detrended'])} about a straight line: <Z> keeps "
             f"settling by {fmt(values['drift_per_tap'])} per tap, "
             f"{values['mean_sweeps']:.3g} sweeps per tap)."]
    if "spectral_slope" in values:
        slope = values["spectral_slope"]
        kind = ("a slow creep (a random walk's slope is -2), not white noise"
                if slope < -1.5 else "close to white noise" if slope > -0.5 else
                "between white noise and a random walk")
        lines[-1] += (f" Its power spectrum falls with slope {slope:.2f} "
                      f"({values.get('spectral_slope_detrended', math.nan):.2f} detrended): "
                      f"{kind}.")
    if fig3 is not None:
        k, ks, _ = fig3.param("k")
        b, bs, _ = fig3.param("intercept")
        if np.isfinite(k) and k > 0:
            lines[-1] += (f" With Fig. 3's k = {fmt(k, ks)} the floor equals k sqrt(eps) at "
                          f"sqrt(eps) = {sigma / k:.3g}")
            if np.isfinite(b):
                lines[-1] += f"; the free line's intercept is {fmt(b, bs)}"
            lines[-1] += "."
        bd, bds, npoints = fig3.param("intercept_detrended")
        floor = values["sigma_Z_detrended"]
        if np.isfinite(bd) and bds > 0 and npoints > 2:
            gap = (bd - floor) / bds
            # the claims' rule: t quantile with the line's degrees of freedom
            beyond = gap > t_quantile(npoints - 2)
            lines[-1] += (f" About each run's straight line (the runs still compact at tap "
                          f"4000), the free line's intercept is {fmt(bd, bds)}, "
                          f"{abs(gap):.1f} of its standard errors "
                          f"{'above' if gap > 0 else 'below'} the floor's detrended "
                          f"{fmt(floor)}"
                          + (": the settles' own noise does not account for it."
                             if beyond else ": within the floor's reach."))
    return lines + [""]


def _spectral_window(path):
    rows = _read(path)
    runs = defaultdict(list)
    for r in rows:
        runs[(float(r["eps"]), r["run"], int(r["taps"]))].append(
            (int(r["window"]), float(r["slope"]), float(r["slope_error"])))
    lines = ["Fig. 3's spectral slope against the length of the steady window "
             "(``spectral_window.csv``; the last W taps of each P.B.C. run of the campaign):", ""]
    for (eps, run, taps), items in sorted(runs.items()):
        slopes = np.array([v for _, v, _ in items])
        errors = np.array([e for _, _, e in items])
        spread = float(np.ptp(slopes))
        moved = spread > 2 * float(np.max(errors))
        text = ", ".join(f"W = {w}: {fmt(v, e)}" for w, v, e in items)
        lines.append(f"* eps = {eps:g} ({taps} taps): {text}; the window "
                     + ("moves the slope beyond twice its error." if moved else
                        "moves it by less than twice its error."))
    return lines + [""]


def _integrity(path):
    rows = _read(path)
    if not rows:
        return []
    by_run = defaultdict(list)
    for r in rows:
        by_run[r["run"]].append(r)
    lines = ["Do thousands of taps leave a legal hard-sphere packing, and do the numbers a run "
             "prints describe the packing it dumps? Every dump of the campaign checked offline "
             "(``integrity.csv``; ``tapmc.packing.PackingCheck``, numpy, no LAMMPS): the "
             "spheres; the closest pair, \\|r_ij\\| - (R_i + R_j) over R_i + R_j, in the deposited "
             "packing (t = 0) and after taps; the overlaps, pairs closer than contact by more "
             "than the model's tolerance (1e-10) plus what the dump's rounding allows; the "
             "lowest sphere's gap to the floor and the closest sphere's to a side wall (over "
             "its diameter); and Phi_b, <Phi^c>, <Z>, z_top and h_s recomputed from the "
             "positions against the run's printed row of that tap, as the largest difference "
             "in units of what the print's last digit and the dump's rounding allow (below 1 "
             "is agreement):", "",
             ".. list-table::", "   :header-rows: 1", "",
             "   * - run", "     - dumps at taps", "     - spheres",
             "     - closest pair, t = 0", "     - closest pair after taps", "     - overlaps",
             "     - floor gap", "     - wall gap", "     - printed scalars"]

    def low(items, key):
        values = [float(r[key]) for r in items if r[key] != ""]
        return min(values) if values else None

    def gap(value):
        return "none" if value is None else fmt(value)

    worst_all = (0.0, "", "", "")
    for run, items in sorted(by_run.items()):
        items.sort(key=lambda r: int(r["tap"]))
        wall = low(items, "wall_gap")
        printed = [r for r in items if r["scalars_worst"] != ""]
        worst = max(printed, key=lambda r: float(r["scalars_worst"])) if printed else None
        if worst is not None and float(worst["scalars_worst"]) >= worst_all[0]:
            worst_all = (float(worst["scalars_worst"]), worst["scalars_worst_column"], run,
                         worst["tap"])
        counts = sorted({int(r["n"]) for r in items})
        lines += [f"   * - {run}", f"     - {', '.join(r['tap'] for r in items)}",
                  f"     - {', '.join(map(str, counts))}",
                  f"     - {gap(low([r for r in items if r['tap'] == '0'], 'min_gap'))}",
                  f"     - {gap(low([r for r in items if r['tap'] != '0'], 'min_gap'))}",
                  f"     - {sum(int(r['overlaps']) for r in items)}",
                  f"     - {fmt(low(items, 'floor_gap'))}",
                  f"     - {'periodic' if wall is None else fmt(wall)}",
                  "     - " + ("not printed" if worst is None else
                               f"{float(worst['scalars_worst']):.2f} "
                               f"({worst['scalars_worst_column']}, t = {worst['tap']})")]
    illegal = [r for r in rows if r["legal"] != "1"]
    counts = {int(r["n"]) for r in rows}
    resolution = max(float(r["resolution_rel"]) for r in rows)
    tapped = [r for r in rows if r["tap"] != "0"]
    closest = min(tapped, key=lambda r: float(r["min_gap"])) if tapped else None
    mismatched = [r for r in rows if r["scalars_worst"] != "" and float(r["scalars_worst"]) >= 1]
    start = [float(r["min_gap"]) for r in rows if r["tap"] == "0"]
    deposited = ("" if not start else
                 "The deposited packings (t = 0) hold exact contacts: their closest pairs are "
                 "within the resolution of zero" if max(abs(g) for g in start) <= resolution
                 else f"The deposited packings' (t = 0) closest pair is {fmt(min(start))} of "
                      "contact")
    lines += ["", f"* {len(rows)} dumps of {len(by_run)} runs: "
              + (f"every one holds {counts.pop()} spheres" if len(counts) == 1 else
                 f"the sphere counts differ ({', '.join(map(str, sorted(counts)))})")
              + "; " + ("every one is a legal hard-sphere packing: no overlap beyond the "
                        "tolerance and the dumps' resolution (pair distances known to "
                        f"{resolution:.2g} of contact), nothing below the floor or through a "
                        "wall. " + deposited
                        + ("" if closest is None else
                           f"; after taps the closest pair is {fmt(float(closest['min_gap']))}"
                           f" of contact ({closest['run']}, t = {closest['tap']}): thousands of "
                           "taps of dilation and redeposition leave no rounding drift into "
                           "overlap") + "."
                        if not illegal else
                        "NOT all are legal: " + "; ".join(
                            f"{r['run']} t = {r['tap']} ({r['overlaps']} overlaps, floor gap "
                            f"{r['floor_gap']}, wall gap {r['wall_gap'] or 'periodic'})"
                            for r in illegal) + "."),
              "* The printed scalars "
              + ("are those of the dumped packings: recomputed from the positions alone, "
                 "every one matches its print within the print's last digit (largest: "
                 f"{worst_all[0]:.2f} of the allowance, {worst_all[1]} of {worst_all[2]} "
                 f"at t = {worst_all[3]}), so the page's numbers, read from the prints, "
                 "describe the packings the pore and P0 analyses read from the dumps."
                 if not mismatched else
                 "differ from the dumped packings' at " + "; ".join(
                     f"{r['run']} t = {r['tap']} ({r['scalars_worst_column']}: "
                     f"{float(r['scalars_worst']):.3g} of the allowance)" for r in mismatched)
                 + "."), ""]
    return lines


def _early_taps(path):
    rows = _read(path)
    if not rows:
        return []
    curves = defaultdict(dict)
    for r in rows:
        curves[float(r["eps"])].setdefault(int(r["seed"]), {})[int(r["t"])] = float(r["phi_b"])
    lines = ["Does Phi_b compact faster per tap in the first decade than later, and how far apart "
             "are realizations at its end? One run gives the first decade's rate with one "
             "tap's spread of the steady state as its error. Here the campaign's F.B.C. packing "
             "is tapped up to 400 times at each eps of Fig. 2 with more Monte Carlo seeds, the "
             "campaign's own run being one of them (``early_taps.csv``; mean ± sem over "
             "realizations; the rates from the means of the decade's halves, taps 1-5 and "
             "6-10 per tap, split at sqrt(10) per unit ln t, as the claims compute them):", "",
             ".. list-table::", "   :header-rows: 1", "",
             "   * - eps", "     - realizations", "     - Phi_b at t = 0", "     - t = 1",
             "     - t = 10", "     - spread at t = 10", "     - rate per tap",
             "     - rate per unit ln t", "     - back at the t = 0 value from tap"]
    from .claims import EARLY_DECADE, first_decade_rates

    taps = np.arange(EARLY_DECADE[0], EARLY_DECADE[1] + 1)
    for eps in sorted(curves):
        series = [c for c in curves[eps].values() if all(k in c for k in [0, *taps])]
        if len(series) < 2:
            continue
        x = np.array([[c[k] for k in [0, *taps]] for c in series])
        t = np.array([0, *taps], dtype=float)
        rates = np.array([[v for v, _ in first_decade_rates(t, row)] for row in x])
        n = len(series)

        def mean_sem(values):
            sem = float(np.std(values, ddof=1) / math.sqrt(n))
            return float(np.mean(values)), sem if sem > 0 else None

        lines += [f"   * - {eps:g}", f"     - {n}", f"     - {fmt(*mean_sem(x[:, 0]), digits=5)}",
                  f"     - {fmt(*mean_sem(x[:, 1]), digits=5)}",
                  f"     - {fmt(*mean_sem(x[:, -1]), digits=5)}",
                  f"     - {fmt(float(np.std(x[:, -1], ddof=1)))}",
                  f"     - {fmt(*mean_sem(rates[:, 0]))}", f"     - {fmt(*mean_sem(rates[:, 1]))}",
                  f"     - {_back_at_start(curves[eps])}"]
    return lines + ["", "The claims on the compaction's efficiency and its slowing in log time "
                    "take their first-decade rates from these realizations (their error over "
                    "realizations, n - 1 degrees of freedom) and their late rates from the "
                    "campaign's run (batch means). The first taps loosen the deposited "
                    "packing; the last column is the first tap at which the realizations' mean "
                    "Phi_b is back at its t = 0 value (over the taps every realization has). "
                    "Eqs. 3 and 4 are tested across the realizations that span 100 taps or "
                    "more (tapmc.laws.RealizationLawTest), over every tap and from that tap on, "
                    "in the claims' table.", ""]


def _fit_surrogates(path, seed_rows=None):
    rows = _read(path)
    if not rows:
        return []
    groups = defaultdict(list)
    for r in rows:
        groups[(r["source"] == "realizations", r["law"], float(r["eps"]), r["source"],
                int(r["taps"]), int(r["fits"]))].append(r)
    lines = ["Does one run fix the triplet (X_inf, B, tau) of eq. 3, and eq. 4's parameters, "
             "and do they depend on the range of taps fitted (section III.B)? The fits' own "
             "intervals treat correlated taps as independent. Here each F.B.C. run of the "
             "campaign is fitted from tap 1, and its residuals give Fourier surrogates (the "
             "same periodogram, random phases) added to the fitted curve, each fitted again "
             "over all taps and over taps 1-T/4, 1-T/2 and T/10-T "
             "(``fit_surrogates.csv``, tapmc.laws.SurrogateFits). Against independent "
             "realizations of noise with the runs' spectrum, these bands are narrower than "
             "the realizations' spread where that fixes a parameter, and say \"undetermined\" "
             "in most runs where it does not (tests/python/test_slow_surrogate_fits.py): "
             "\"undetermined\" is safe, \"determined\" only an upper bound. The last rows fit each realization of the "
             "first taps (``early_taps.csv``) and give the spread of the fitted values over "
             "them, which needs no such model. Value, 16-84 % band (B and tau judged in ln: "
             "determined when the band is at most a factor 2 either side; the others when "
             "its half width is at most the value), and the range test's p-value:", "",
             ".. list-table::", "   :header-rows: 1", "",
             "   * - source", "     - eps", "     - law", "     - taps", "     - fits",
             "     - parameters (value, band, determined?, range p)"]
    for (_, law, eps, source, taps, fits), group in sorted(groups.items()):
        cells = []
        for r in group:
            p = r["range_p"]
            cells.append(f"{r['parameter']} {float(r['value']):.3g} "
                         f"({float(r['low']):.3g} to {float(r['high']):.3g}"
                         f"{'' if r['determined'] == '1' else ', undetermined'}"
                         f"{'' if p == 'nan' else f', range p {float(p):.2g}'})")
        name = "realizations" if source == "realizations" else \
            f"campaign run {source.rsplit('_', 1)[1]}"
        lines += [f"   * - {name}",
                  f"     - {eps:g}", f"     - {law.replace('eq', 'eq. ')}", f"     - {taps}",
                  f"     - {fits}", f"     - {'; '.join(cells)}"]
    b_rows = [(key, r) for key, group in groups.items() for r in group
              if r["parameter"] == "B" and key[1] == "eq3"]
    runs = [r for key, r in b_rows if not key[0]]
    realized = [r for key, r in b_rows if key[0]]
    lines += ["", "A row without a range p: a range fit of the run itself sits on the edge of "
              "(B, tau)'s allowed range, where the parameters are not defined. "
              f"Eq. 3's B is undetermined in {sum(r['determined'] != '1' for r in runs)} of "
              f"{len(runs)} campaign runs and at {sum(r['determined'] != '1' for r in realized)}"
              f" of {len(realized)} eps over the realizations of the first taps."]
    return lines + _surrogates_against_seeds(b_rows, seed_rows or []) + [""]


def _surrogates_against_seeds(b_rows, seed_rows):
    """Where several seeds of one eps were fitted with surrogates and seed-fits has their
    group: each run's half width of ln B (eq. 3) against the realizations' sd of ln B, the
    quantity it estimates (the calibration of tests/python/test_slow_surrogate_fits.py, on the
    campaign's own runs)."""
    runs = defaultdict(list)
    for key, r in b_rows:
        if not key[0]:
            runs[key[2]].append(r)
    spread = {float(r["eps"]): r for r in seed_rows
              if r["law"] == "eq3" and r["parameter"] == "B" and r["bc"] == "fbc"}
    out = []
    for eps, rows in sorted(runs.items()):
        if len(rows) < 2 or eps not in spread:
            continue
        sd = spread[eps]
        each = ", ".join(f"{float(r['half_width']):.2g} ({r['source'].rsplit('_', 1)[1]}"
                         f"{'' if r['determined'] == '1' else ', undetermined'})"
                         for r in sorted(rows, key=lambda r: r["source"]))
        halves = [float(r["half_width"]) for r in rows]
        verdicts = {r["determined"] == "1" for r in rows}
        low, high = float(sd["spread_low"]), float(sd["spread_high"])
        found = (["the surrogates' verdict on B differs between the runs"]
                 if len(verdicts) > 1 else []) + \
            (["every run's half width is below the realizations' spread"]
             if max(halves) < low else []) + \
            (["every run's half width is within the realizations' spread"]
             if low <= min(halves) and max(halves) <= high else [])
        out.append(f"At eps = {eps:g}, {len(rows)} runs: their surrogates give ln B (eq. 3) "
                   f"half widths of {each}, against a spread over the {sd['realizations']} "
                   f"realizations (seed-fits) of {float(sd['spread']):.2g} (95 %: "
                   f"{low:.2g} to {high:.2g})" + (f": {'; '.join(found)}." if found else "."))
    return ["", " ".join(out)] if out else []


def _seed_fits(path):
    rows = _read(path)
    if not rows:
        return []
    groups = defaultdict(list)
    for r in rows:
        groups[(r["bc"], float(r["eps"]), r["group"], r["law"])].append(r)
    states = {"1": "determined", "0": "undetermined", "": "cannot tell"}
    lines = ["Do independent realizations fix eq. 3's triplet (X_inf, B, tau) and eq. 4's "
             "parameters over a whole run, and do they depend on the range of taps fitted "
             "(section III.B)? Every group of runs that differ only in their seed "
             "(``seed_fits.csv``, tapmc.laws.RealizationFits): each run fitted from tap 1 over "
             "all its taps, the parameters' sample sd over the runs with its 95 % chi-square "
             "interval (B and tau in ln: determined when the whole interval is within ln 2, "
             "undetermined when none of it is, else the realizations cannot tell; the "
             "amplitudes against their mean), and the paired t-test of the fits over taps "
             "1-T/4, 1-T/2 and T/10-T against all taps (p, Bonferroni over the ranges; range "
             "dependent below 0.01). Unlike one run's surrogates, this needs no model of the "
             "noise, and decides both ways:", "",
             ".. list-table::", "   :header-rows: 1", "",
             "   * - group", "     - law", "     - runs", "     - taps",
             "     - parameters (mean; sd with its 95 % interval; verdict; range p)"]
    for (bc, eps, group, law), group_rows in sorted(groups.items()):
        cells = []
        for r in group_rows:
            unit = "ln " if r["log_scale"] == "1" else ""
            cells.append(f"{r['parameter']} {float(r['mean']):.3g} (sd of {unit}"
                         f"{r['parameter']} {float(r['spread']):.2g}, "
                         f"{float(r['spread_low']):.2g} to {float(r['spread_high']):.2g}; "
                         f"{states[r['determined']]}; range p {float(r['range_p']):.2g})")
        first = group_rows[0]
        lines += [f"   * - {group}", f"     - {law.replace('eq', 'eq. ')}",
                  f"     - {first['realizations']}", f"     - {first['taps']}",
                  f"     - {'; '.join(cells)}"]
    return lines + [""]


def _back_at_start(by_seed):
    """claims.back_at_start of the mean Phi_b over the realizations ``by_seed`` (seed ->
    {tap: Phi_b}), over the taps all of them have ("-" if never)."""
    from .claims import back_at_start

    last = min(max(c) for c in by_seed.values())
    t = np.arange(last + 1)
    if not all(all(k in c for k in t) for c in by_seed.values()):
        return "-"
    back = back_at_start(t, np.mean([[c[k] for k in t] for c in by_seed.values()], axis=0))
    return f"{back:g}" if back is not None else f"- (not by tap {last})"


def _initial_packing(path):
    rows = _read(path)
    if len(rows) < 2:
        return []
    col = {k: np.array([float(r[k]) for r in rows]) for k in ("phi_b", "phi_c", "Z")}
    n = len(rows)
    sizes = sorted({(int(r["N"]), float(r["L"])) for r in rows})
    where = ", ".join(f"N = {N}, L = {L:g}R" for N, L in sizes)

    def stat(x, pct):
        sd = float(np.std(x, ddof=1))
        spread = f"{100 * sd:.2f} %" if pct else f"{sd:.3g}"
        return f"{fmt(float(np.mean(x)), sd / math.sqrt(n), pct)} (one packing spreads {spread})"

    phi = col["phi_c"]
    away = (PAPER_INITIAL_PHI_C - phi.mean()) / phi.std(ddof=1)
    return [f"The initial P.B.C. packing over {n} depositions (``initial_packing.csv``; {where}, "
            "measured as the runs measure it at t = 0): <Phi^c> = " + stat(phi, True)
            + f", range {fmt(phi.min(), None, True)} to {fmt(phi.max(), None, True)}; "
            f"Phi_b = {stat(col['phi_b'], True)}; <Z> = {stat(col['Z'], False)}. The paper's "
            f"{100 * PAPER_INITIAL_PHI_C:.1f} % is one packing's, {away:+.1f} spreads of one "
            "packing from the mean: the claim's row compares it with that prediction interval.",
            ""]


#: the tapped configurations count as independent when their P0 scatter is at least this
#: share of the independent depositions' (a smaller scatter means correlated configurations,
#: and error bars too small by about the square root of the ratio)
P0_INDEPENDENT_SHARE = 0.5


def _p0_configs(path):
    rows = _read(path)
    data = [r for r in rows if r["sigma"] != "phi"]
    phi = [r for r in rows if r["sigma"] == "phi"]
    if len(data) < 3 or not phi:
        return []
    col = {k: np.array([float(r[k]) for r in data]) for k in data[0]}
    n_i, n_t = int(col["initial_n"].min()), int(col["tapped_n"].min())
    # scatter of one configuration about the mean, summed over sigma, tapped over initial
    spread = {k: float(np.sqrt(np.sum((col[f"{k}_sem"] ** 2) * col[f"{k}_n"])))
              for k in ("initial", "tapped")}
    ratio = spread["tapped"] / spread["initial"] if spread["initial"] > 0 else math.nan
    p = phi[0]
    independent = ratio >= P0_INDEPENDENT_SHARE
    from tapmc.pores import percus_yevick_p0

    gap = np.abs(col["initial"] - col["tapped"])
    k = int(np.argmax(gap))
    diff = float(gap[k])
    predicted = float(np.max(np.abs(percus_yevick_p0(col["sigma"], float(p["tapped"]))
                                    - percus_yevick_p0(col["sigma"], float(p["initial"])))))
    return [f"Fig. 9's P0(sigma) with error bars (``p0_configs.csv``): {n_i} depositions at "
            f"t = 0 (Phi seen by the points {fmt(float(p['initial']), float(p['initial_sem']), True)}"
            f") and {n_t} configurations of the tapped packing, the Fig. 9 run continued at its "
            f"eps one dump every 100 taps ({fmt(float(p['tapped']), float(p['tapped_sem']), True)}"
            "). One tapped configuration scatters about the mean "
            f"{ratio:.2f} times as much as one deposition: "
            + ("the configurations are about as different as independent packings, and their "
               "sem is the error of the tapped curve." if independent else
               "the configurations are correlated; their sem underestimates the error of the "
               "tapped curve, and a disagreement found with it is not conclusive."),
            "The claims' rows of Fig. 9 compare the curves sigma by sigma with these errors "
            "(Bonferroni-corrected t over the sigma points).",
            f"The two packings' curves differ by at most {fmt(diff, None)} (sigma = "
            f"{col['sigma'][k]:.3g}); Percus-Yevick predicts a change of at most "
            f"{fmt(predicted, None)} between their Phi: the measured difference is "
            f"{100 * diff / predicted:.0f} % of it. "
            + ("The curves differ about as their packing fractions predict: at these errors "
               "the paper's 'no significant difference' does not hold; the change is small "
               "against P0 itself (a few % of it near sigma = 1), which a plot hardly shows."
               if diff >= 0.5 * predicted else
               "The curves differ much less than their packing fractions predict, as the paper "
               "says."), ""]


def _relative_change(a, ea, b, eb):
    """(b - a) / a and its error (independent errors)."""
    r = (b - a) / a
    return r, abs(b / a) * math.hypot(ea / a, eb / b)


def _pores(fig10):
    """The small pores against the large ones and the (xi - xi_T)^2 law, from Fig. 10's CSV."""
    from .claims import pore_law_deviation

    if fig10 is None:
        return []
    small, large = fig10.get("params", "small"), fig10.get("params", "large")
    if small is None or large is None or len(small[0]) < 2 or not np.all(np.isfinite(small[2])):
        return []
    t0, t1 = small[0][0], small[0][-1]
    rel = {name: _relative_change(c[1][0], c[2][0], c[1][-1], c[2][-1])
           for name, c in (("small", small), ("large", large))}
    absolute = abs(large[1][-1] - large[1][0]) / abs(small[1][-1] - small[1][0])
    as_much = abs(rel["small"][0]) >= 0.5 * abs(rel["large"][0])
    lines = [f"Are the small pores (xi_T to xi_O) unaffected by the taps (Fig. 10)? Their share of "
             f"xi^3 P(xi) from t = {t0:g} to t = {t1:g}: {fmt(small[1][0], small[2][0])} -> "
             f"{fmt(small[1][-1], small[2][-1])} ({fmt(rel['small'][0], rel['small'][1], True)}); "
             f"the large pores' (beyond xi_O): {fmt(large[1][0], large[2][0])} -> "
             f"{fmt(large[1][-1], large[2][-1])} ({fmt(rel['large'][0], rel['large'][1], True)}). "
             f"In absolute terms, the scale of the paper's figure, the small pores' share moves "
             f"{absolute:.1f} times less than the large pores'; "
             + ("relative to their own size they change about as much: the paper's 'not notably "
                "affected' holds on the figure's scale only, and the claim's rule (no change "
                "beyond the error) rejects it." if as_much else
                "relative to their own size too they change much less: the taps act on the "
                "large pores."), ""]
    law = pore_law_deviation(fig10)
    if law is not None:
        xi_t = fig10.get("params", "xi_T")
        onset = ""
        if xi_t is not None and np.isfinite(xi_t[2][-1]):
            onset = (f" Fitted with a free onset (``tapmc.pores.TetrahedralLaw``, 0.15 to xi_O) "
                     f"the law starts at xi = {fmt(xi_t[1][-1], xi_t[2][-1], digits=4)}, "
                     f"{abs(xi_t[1][-1] - XI_T) / xi_t[2][-1]:.1f} errors "
                     f"{'below' if xi_t[1][-1] < XI_T else 'above'} the tetrahedral site "
                     f"{XI_T:.4f}, where the smallest pore lies.")
        lines += [f"How closely does (xi - xi_T)^2 follow xi^3 P(xi) between xi_T and xi_O "
                  f"(t = {law['t']:g}, {law['bins']} bins, amplitude fitted)? Relative to the "
                  f"curve's largest value there, the law departs from the histogram by "
                  f"{100 * law['rms']:.1f} % rms, at most {100 * law['max']:.1f} % (at xi = "
                  f"{law['at']:.3f}), against bin errors of {100 * law['error']:.1f} % "
                  "(median): "
                  + ("a fair description of the shape, as the paper says ('reasonably well'), "
                     "but not the law of the data at their precision, which the fit rule "
                     "tests." if law["rms"] < LAW_FAIR_DEVIATION else
                     "not a fair description of the shape.") + onset, ""]
    return lines


def _lateral_first_tap(path, fig8=None):
    rows = _read(path)
    per = defaultdict(lambda: defaultdict(dict))
    for r in rows:
        per[float(r["eps"])][int(r["seed"])][int(r["t"])] = (float(r["lateral"]),
                                                             float(r["central"]))
    if not per:
        return []
    last = min(max(t) for seeds in per.values() for t in seeds.values())
    lines = ["Does the first tap compact the lateral zone of the paper's F.B.C. start (Fig. 8)? "
             "The campaign's F.B.C. runs start from packings deposited between the walls; the "
             "paper's start (periodic deposition, then the walls and a slight agitation) tapped "
             f"{last} times at each eps (``lateral_first_tap.csv``; delta Phi against t = 0, "
             "mean ± sem over seeds):", "",
             ".. list-table::", "   :header-rows: 1", "",
             "   * - eps", "     - seeds", "     - delta Phi_lateral, t = 1",
             "     - delta Phi_central, t = 1", f"     - delta Phi_lateral, t = {last}"]

    def stat(values):
        v = np.asarray(values)
        return fmt(float(v.mean()), float(v.std(ddof=1) / math.sqrt(len(v)))
                   if len(v) > 1 else None)

    looser = float(np.mean([t[0][1] - t[0][0] for seeds in per.values()
                            for t in seeds.values()]))
    jumps, more = {}, True
    for eps, seeds in sorted(per.items()):
        lat1 = [t[1][0] - t[0][0] for t in seeds.values()]
        jumps[eps] = float(np.mean(lat1))
        more &= jumps[eps] > float(np.mean([t[1][1] - t[0][1] for t in seeds.values()]))
        lines += [f"   * - {eps:g}", f"     - {len(seeds)}", f"     - {stat(lat1)}",
                  f"     - {stat([t[1][1] - t[0][1] for t in seeds.values()])}",
                  f"     - {stat([t[last][0] - t[0][0] for t in seeds.values()])}"]
    walls = []
    if fig8 is not None:
        for s in fig8.series("a"):
            if s.startswith("eps="):
                t, mean, _, _ = fig8.get("a", s)
                if np.any(t == 1):
                    walls.append(f"{mean[t == 1][0]:+.4f} at eps = {s.split('=')[1]}")
    lines += ["", "From the paper's start the lateral zone "
              + ("gains at the first tap at every eps" if all(j > 0 for j in jumps.values())
                 else "does not gain at the first tap at every eps")
              + (", more than the central zone" if more else ", not more than the central zone")
              + (f" (at t = 0 it is looser than the central zone by {fmt(looser, None, True)}: "
                 "the start's walls are under-populated)" if looser > 0 else "")
              + (f"; from the start deposited between the walls it changes by "
                 f"{', '.join(walls)} instead" if walls else "") + ".", ""]
    return lines


BRANCH_NAMES = ("first increase", "decrease", "second increase")
#: taps per level of the paper's ramp (section III.B, Fig. 4)
PAPER_RAMP_TAPS = 4000


def _ramp_levels(path, fig4=None, factors=None):
    """``factors``: as in :func:`_pbc_course`; a level's shift compares two windows of one
    run, so its error takes the factor of <Phi^c>'s halves."""
    rows = _read(path)
    k = (factors or {}).get("phi_c:halves", (1.0, None))[0]
    if not rows:
        return []
    taps, longer = int(rows[0]["taps"]), int(rows[0]["taps_long"])
    paper = " (the paper's)" if longer == PAPER_RAMP_TAPS else ""
    lines = [f"What do the ramp's {taps} taps per level change against {longer}{paper}? "
             f"Levels of the campaign's ramp continued from their end at the same sqrt(eps) to "
             f"{longer} taps (``ramp_levels.csv``; <Phi^c> over the last quarter of the level, "
             "batch-means errors" + (f"; the shift's error times {k:.1f}, the realizations' "
                                     "factor of a difference of two windows of one run "
                                     "(realization-scatter)" if k != 1.0 else "") + "):", "",
             ".. list-table::", "   :header-rows: 1", "",
             "   * - ramp", "     - level (branch)", "     - sqrt(eps)",
             f"     - after {taps} taps", f"     - after {longer} taps", "     - shift"]
    shifts = defaultdict(list)
    for r in rows:
        ramp = r.get("ramp") or RAMP_LEVELS_DEFAULT_RUN
        a, ea = float(r["phi_c"]), float(r["phi_c_sem"])
        b, eb = float(r["phi_c_long"]), float(r["phi_c_long_sem"])
        shifts[ramp].append((b - a, k * math.hypot(ea, eb)))
        start = r.get("start") or "run"
        mark = "; replayed" if start.startswith("replay") else ""
        lines += [f"   * - {ramp}", f"     - {r['level']} ({BRANCH_NAMES[int(r['branch'])]}{mark})",
                  f"     - {float(r['sqrt_eps']):g}", f"     - {fmt(a, ea, True)}",
                  f"     - {fmt(b, eb, True)}", f"     - {fmt(*shifts[ramp][-1], True)}"]
    from .claims import ReportData, hysteresis_gap

    gap = None if fig4 is None else hysteresis_gap(ReportData({}, {"fig4": fig4}))
    texts = []
    for ramp, moves in shifts.items():
        largest = max(moves, key=lambda d: abs(d[0]))
        moved = [d for d in moves if abs(d[0]) > t_quantile(HALVES_DOF) * d[1]]
        texts.append(f"{ramp}: the longer levels move <Phi^c> by at most "
                     f"{fmt(largest[0], largest[1], True)}; {len(moved)} of {len(moves)} beyond "
                     "their error")
    largest = max(shifts.get(RAMP_LEVELS_DEFAULT_RUN) or [(0.0, 0.0)], key=lambda d: abs(d[0]))
    text = "; ".join(texts) + "."
    replays = sorted({(r.get("start") or "run")[len("replay ("):-1] for r in rows
                      if (r.get("start") or "").startswith("replay")})
    if replays:
        text += (" The levels marked replayed start from the ramp run again up to their end "
                 "(``--replay``: the campaign's restart file of that level end was gone); the "
                 "replay's taps against the campaign's: " + ", ".join(replays) + ".")
    if gap is not None:
        text += (f" The hysteresis gap of {RAMP_LEVELS_DEFAULT_RUN} (decrease minus first "
                 f"increase) is {fmt(gap, None, True)}: its shorter levels "
                 + ("change the branches by less than a tenth of it." if abs(largest[0])
                    < 0.1 * abs(gap) else f"shift a level by {abs(largest[0] / gap):.0%} of it."))
    return lines + ["", text, ""]


def _ramp_pores(path):
    rows = _read(path)
    if not rows:
        return []
    lines = ["Does nu, the mean normalised pore volume, follow <Phi^c> around the ramp (section "
             "IV.B: the same reversible-irreversible behaviour)? The packings at the level ends "
             "of the campaign's ramp analysed as Fig. 10's dumps are (``ramp_pores.csv``: one "
             "packing per level, the statistics box from 2R to "
             f"{float(rows[0]['window_top']):g}R above the floor, the error the lateral "
             "jackknife over 4 x 4 blocks):", "",
             ".. list-table::", "   :header-rows: 1", "",
             "   * - run", "     - level (branch)", "     - sqrt(eps)", "     - nu"]
    for r in rows:
        mark = "; replayed" if r["source"].startswith("replay") else ""
        lines += [f"   * - {r['run']}",
                  f"     - {r['level']} ({BRANCH_NAMES[int(r['branch'])]}{mark})",
                  f"     - {float(r['sqrt_eps']):g}",
                  f"     - {fmt(float(r['nu']), float(r['nu_sem']))}"]
    text = ("The levels marked replayed are the ends of a replay of the ramp (``--replay``, "
            "bit for bit the campaign's taps) where the campaign's restart file was gone; the "
            "claims table reads the signs (``nu-hysteresis``).")
    return lines + ["", text, ""]


def _pbc_course(path, factors=None):
    """``factors``: realization factors (tapmc.paper.claims.realization_factors) that turn
    the runs' batch-means errors of <Phi^c>'s steady state and halves into a realization's."""
    rows = _read(path)
    steady_k = (factors or {}).get("phi_c", (1.0, None))[0]
    halves_k = (factors or {}).get("phi_c:halves", (1.0, None))[0]
    if not rows:
        return []
    by_eps = defaultdict(list)
    for r in rows:
        by_eps[float(r["eps"])].append(r)
    lines = ["How long does the dip of <Phi^c> after the first taps last, and does the packing "
             f"loosen at strong taps (eps >= {STRONG_EPS:g})? The course of <Phi^c> in every "
             "P.B.C. run of the campaign (``pbc_course.csv``; back from: the first tap from "
             "which a 10-tap running mean stays at or above the t = 0 value for 10 taps; "
             "steady: the last 1000 taps, batch-means error; halves: the steady window's "
             "second half minus its first" + (
                 f"; both errors times the realizations' factor, {steady_k:.1f} and "
                 f"{halves_k:.1f} (realization-scatter)" if (steady_k, halves_k) != (1.0, 1.0)
                 else "") + "):", "",
             ".. list-table::", "   :header-rows: 1", "",
             "   * - eps", "     - seed", "     - <Phi^c> at t = 0", "     - lowest (tap)",
             "     - back from tap", "     - steady", "     - halves"]
    summary = {}
    for eps in sorted(by_eps):
        group = by_eps[eps]
        for r in sorted(group, key=lambda r: int(r["seed"])):
            back = r["tap_back"] or "never"
            lines += [f"   * - {eps:g}", f"     - {r['seed']}",
                      f"     - {fmt(float(r['phi_c_0']), None, True)}",
                      f"     - {fmt(float(r['phi_c_min']), None, True)} ({r['tap_min']})",
                      f"     - {back}",
                      f"     - {fmt(float(r['phi_c_steady']), steady_k * float(r['phi_c_steady_sem']), True)}",
                      f"     - {fmt(float(r['steady_halves_diff']), halves_k * float(r['steady_halves_diff_sem']), True)}"]
        col = {k: np.array([float(r[k]) if r[k] != "" else math.nan for r in group])
               for k in ("phi_c_0", "phi_c_min", "tap_back", "phi_c_steady", "phi_c_steady_sem",
                         "steady_halves_diff", "steady_halves_diff_sem")}
        col["phi_c_steady_sem"] = col["phi_c_steady_sem"] * steady_k
        col["steady_halves_diff_sem"] = col["steady_halves_diff_sem"] * halves_k
        n = len(group)
        summary[eps] = {"depth": float(np.mean(col["phi_c_0"] - col["phi_c_min"])),
                        "back": col["tap_back"],
                        "gain": float(np.mean(col["phi_c_steady"] - col["phi_c_0"])),
                        "steady": float(np.mean(col["phi_c_steady"])),
                        "steady_se": float(np.sqrt(np.sum(col["phi_c_steady_sem"] ** 2)) / n),
                        "halves": float(np.mean(col["steady_halves_diff"])),
                        "halves_se": float(np.sqrt(np.sum(col["steady_halves_diff_sem"] ** 2))
                                           / n)}
    eps_sorted = sorted(summary)
    def grows(values):
        return all(b >= a for a, b in zip(values, values[1:]))

    deeper = grows([summary[e]["depth"] for e in eps_sorted])
    lengths = [float(np.max(summary[e]["back"])) for e in eps_sorted]
    longer = all(np.isfinite(lengths)) and grows(lengths)

    def back_text(e):
        back = summary[e]["back"]
        if np.any(~np.isfinite(back)):
            return "never regains it"
        return f"regains it from tap {int(np.max(back))}"

    lines += ["", "* The dip: " + "; ".join(
        f"eps = {e:g}: {fmt(summary[e]['depth'], None, True)} below t = 0, {back_text(e)}"
        for e in eps_sorted) + ". The dip " + (
        "deepens" if deeper else "does not deepen steadily") + " and " + (
        "lengthens" if longer else "does not lengthen steadily") + " with eps."]
    top = max(eps_sorted, key=lambda e: summary[e]["steady"])
    strong = [e for e in eps_sorted if e >= STRONG_EPS]
    if not strong:
        return lines + [f"* No run at eps >= {STRONG_EPS:g} yet: the loosening at strong taps "
                        "is not measured.", ""]
    for e in strong:
        d = summary[e]
        below = summary[top]["steady"] - d["steady"]
        below_se = math.hypot(summary[top]["steady_se"], d["steady_se"])
        moving = abs(d["halves"]) > t_quantile(HALVES_DOF) * d["halves_se"]
        ends = ("ends above its initial packing" if d["gain"] > 0 else
                "ends below its initial packing: a loosening that the taps do not undo")
        lines.append(
            f"* eps = {e:g}: the steady <Phi^c> is {fmt(below, below_se, True)} below the "
            f"largest (eps = {top:g}) and {fmt(abs(d['gain']), None, True)} "
            f"{'above' if d['gain'] > 0 else 'below'} t = 0: the packing {ends}. "
            + (f"Its halves differ by {fmt(d['halves'], d['halves_se'], True)}: still "
               + ("compacting" if d["halves"] > 0 else "loosening")
               + " at the end, so the value after these taps bounds the steady state from "
               + ("below." if d["halves"] > 0 else "above.")
               if moving else "Its halves agree within their error: steady."))
    transient = all(summary[e]["gain"] > 0 and np.all(np.isfinite(summary[e]["back"]))
                    for e in strong)
    still = [e for e in strong if summary[e]["halves"]
             > t_quantile(HALVES_DOF) * summary[e]["halves_se"]]
    lines.append(
        "* Verdict: the loosening at strong taps is "
        + ("transient: the first taps leave the packing looser than the sequential deposition "
           "it starts from (the first-tap measurement above tells whether that is the model "
           "or the redeposition's threshold), the taps then compact it beyond its start, and "
           "what remains is the falling side of Fig. 4's bell, which the paper shows itself"
           + (f"; at eps = {', '.join(f'{e:g}' for e in still)} part of the fall is a slower "
              "approach to the steady state, still under way after the run's taps, as it may "
              "be in the paper's values after 4000 taps." if still else ".")
           if transient else
           "not undone by the taps at every strong eps (see above): a difference from the "
           "paper's Fig. 4, whose squares all lie above the initial packing."))
    return lines + [""]


#: the window means of realization_scatter.csv, as the page names them
SCALAR_NAMES = {q: RUN_ERROR_LABELS[q] for q in RUN_ERROR_QUANTITIES}
#: the rows of the realization-scatter table: the window means and Fig. 8's zones
TABLE_NAMES = {**SCALAR_NAMES, **{q: RUN_ERROR_LABELS[q] for q in ZONE_QUANTITIES}}


def _realization_scatter(path):
    """The table of each group's spread against its runs' own errors and the pooled factors
    (tapmc.paper.claims.realization_calibrations), with the verdict."""
    rows = _read(path)
    calib = realization_calibrations(rows)
    if not rows or not calib:
        return []
    starts = defaultdict(set)
    for r in rows:
        if r["column"] == "phi_c":
            starts[r["group"]].add(r["start"])
    lines = ["Does the error one run gives its steady state tell how far another realization "
             "lands? Every one-seed point of this page (the paper's protocol: one run per "
             "point) carries its run's batch-means error (last 1000 taps, "
             f"{DEFAULT_BATCHES} batches). The campaign's groups of runs that differ only in "
             "their seed (``realization_scatter.csv``) measure it: the spread of their steady "
             "states against their own errors (tapmc.fluctuations.ErrorCalibration; 1 when the "
             "errors are calibrated):", ""]
    lines += _calibration_table(
        calib, TABLE_NAMES, {k: _scatter_quantity(k) for k in RUN_ERROR_LABELS},
        ("runs", "rms error within a run"),
        lambda group, n: f"{n} (" + ("one packing" if len(starts[group]) == 1 else
                                     f"{len(starts[group])} packings") + ")")
    lines += _scatter_by_bc(rows)
    short = {k: c for k, c in calib.items() if c.p_value < CALIBRATION_ALPHA}
    if not short:
        lines += ["* Verdict: the one-run errors are compatible with the realizations' spread "
                  f"(no p below {CALIBRATION_ALPHA:g}): a one-seed error bar is the error of "
                  "the model's steady state.", ""]
        return lines
    means = [k for k in SCALAR_NAMES if k in short]
    text = ", ".join(f"{SCALAR_NAMES[k]} {short[k].factor:.1f}" for k in means)
    lines += [
        "* Verdict: the one-run errors are too small" + (f" (window means: {text})" if text
                                                         else "")
        + ": fluctuations slower than a batch (Fig. 3's spectra fall as f^-1 to f^-1.5) move "
        "a run's whole window, so a one-seed error bar is the error of that run's time "
        "average, not of the model's steady state, and another realization lands about k of "
        "them away. Where a row of the claims' table or a measurement below rests on one "
        "run's time average, its error is the batch-means error times the factor of its "
        "quantity (the note under the claims' rules lists them; a difference of two windows "
        "of one run takes the halves' factor)."
        + (" The realizations' spread does not reject the errors of "
           + ", ".join(f"{RUN_ERROR_LABELS[k]} (k = {calib[k].factor:.2f})"
                       for k in RUN_ERROR_LABELS if k in calib and k not in short)
           + ": those stand as they are." if set(calib) - set(short) else ""), ""]
    return lines


#: the quantities of packing_scatter.csv, as the page names them
PACKING_NAMES = {"packing:nu": "nu (pores)", "packing:alpha": "alpha (the profile's gradient)"}


def _packing_scatter(path):
    """The table of each group's spread of a packing's nu and alpha against their spatial
    jackknife errors, the pooled factors and the verdict."""
    rows = _read(path)
    calib = realization_calibrations(rows)
    if not rows or not calib:
        return []
    lines = ["Does the spatial jackknife of one packing (4 x 4 lateral blocks: the error of "
             "nu and of alpha wherever one run gives a point) tell how far another "
             "realization lands? The final packings of the campaign's groups of runs that "
             "differ only in their seed, and their distinct initial packings "
             "(``packing_scatter.csv``, ``bench/paper_questions.py packing-scatter``: "
             "tapmc-pores in Fig. 10's statistics box; alpha in Fig. 6's window):", ""]
    lines += _calibration_table(
        calib, PACKING_NAMES, PACKING_NAMES, ("packings", "rms jackknife error"),
        lambda group, n: f"{n} (" + ("t = 0" if group.startswith("initial_")
                                     else "after the taps") + ")")
    lines += _scatter_by_bc(rows)
    short = [k for k in PACKING_NAMES if k in calib and calib[k].p_value < CALIBRATION_ALPHA]
    wide = [k for k in PACKING_NAMES if k in calib and calib[k].interval()[1] < 1]
    verdict = []
    if short:
        verdict.append(", ".join(PACKING_NAMES[k] for k in short) + ": the jackknife is too "
                       "small; a one-run value carries its jackknife error times k.")
    if wide:
        verdict.append(", ".join(PACKING_NAMES[k] for k in wide) + ": the jackknife is "
                       "larger than the spread of realizations (k below 1 at 95 %), as it is "
                       "when the blocks of one packing are anticorrelated (the statistics "
                       "box holds a nearly fixed number of spheres) where the jackknife "
                       "takes them as independent; the page keeps the jackknife error, an "
                       "upper bound of a realization's.")
    fine = [k for k in PACKING_NAMES if k in calib and k not in short and k not in wide]
    if fine:
        verdict.append(", ".join(f"{PACKING_NAMES[k]} (k = {calib[k].factor:.2f})"
                                 for k in fine)
                       + ": the jackknife is compatible with the realizations' spread: a "
                       "one-seed error bar is the error of a realization.")
    return lines + ["* Verdict: " + " ".join(verdict), ""]


def _calibration_table(calib, table_names, pooled_names, headers, realizations):
    """The list-table of every group's spread against its own errors for the quantities of
    ``table_names`` (key -> name) and the line of the factors pooled over the groups for
    those of ``pooled_names``; ``headers``: (the groups' column, the errors' column);
    ``realizations(group, n)``: the text of a group's realizations cell."""
    lines = [".. list-table::", "   :header-rows: 1", "",
             f"   * - {headers[0]}", "     - realizations", "     - quantity",
             "     - spread between realizations", f"     - {headers[1]}", "     - ratio"]
    for column in (c for c in table_names if c in calib):
        c = calib[column]
        for group in c.ratios:
            lines += [f"   * - {group}", f"     - {realizations(group, len(c.groups[group][0]))}",
                      f"     - {table_names[column]}", f"     - {c.spreads[group]:.3g}",
                      f"     - {c.errors[group]:.3g}", f"     - {c.ratios[group]:.2f}"]
    pooled = []
    for key in (k for k in pooled_names if k in calib):
        c = calib[key]
        low, high = c.interval()
        pooled.append(f"{pooled_names[key]}: k = {c.factor:.2f} (95 %: {low:.2f} to "
                      f"{high:.2f}; {c.dof} dof, p of k = 1: {c.p_value:.2g})")
    return lines + ["", "* Pooled over the groups: " + "; ".join(pooled) + "."]


def _scatter_quantity(key):
    """How the realization-scatter section names a quantity of realization_scatter.csv."""
    what = {"": " steady state", "halves": ", halves' difference"}.get(
        key.partition(":")[2], "")
    return RUN_ERROR_LABELS[key].removesuffix(" halves") + what


def _scatter_by_bc(rows):
    """The line that compares the P.B.C. and F.B.C. groups' factors (none without groups of
    both)."""
    sharing = realization_sharing(rows)
    if not sharing:
        return []
    by_bc = {bc: realization_calibrations(rows, bc) for bc in ("pbc", "fbc")}
    items = [f"{_scatter_quantity(key)}: P.B.C. k = {by_bc['pbc'][key].factor:.2f} "
             f"({by_bc['pbc'][key].dof} dof), F.B.C. k = {by_bc['fbc'][key].factor:.2f} "
             f"({by_bc['fbc'][key].dof} dof), p = {sharing[key]:.2g}"
             for key in RUN_ERROR_LABELS if key in sharing]
    apart = [_scatter_quantity(k) for k in RUN_ERROR_LABELS
             if sharing.get(k, 1.0) < CALIBRATION_ALPHA]
    return ["* By boundary condition (does one factor serve both? two-sided F test of the "
            "ratio of their k^2): " + "; ".join(items) + ". " + (
                "No quantity rejects one shared factor: the pooled k above serves the runs of "
                "both." if not apart else
                f"{', '.join(apart)}: the factors differ (p < {CALIBRATION_ALPHA:g}), so the "
                "runs of each boundary condition take their own groups' k there; the other "
                "quantities take the pooled k.")]


def _packing_p0(fig9, configs=None):
    """(Phi, max |P0 - PY|, sigma of the max, P0 - PY there, PY there, what) of Fig. 9's
    tapped packing: over the tapped configurations of ``configs`` (p0_configs.csv) when given,
    else Fig. 9's own curve; None when neither is there."""
    if configs is not None and Path(configs).is_file():
        from tapmc.pores import percus_yevick_p0

        rows = _read(configs)
        data = [r for r in rows if r["sigma"] != "phi"]
        phi = float(next(r for r in rows if r["sigma"] == "phi")["tapped"])
        sigma = np.array([float(r["sigma"]) for r in data])
        final = np.array([float(r["tapped"]) for r in data])
        theory = np.asarray(percus_yevick_p0(sigma, phi), dtype=float)
        diff = final - theory
        at = int(np.argmax(np.abs(diff)))
        return (phi, float(abs(diff[at])), float(sigma[at]), float(diff[at]), float(theory[at]),
                f"mean of {data[0]['tapped_n']} tapped configurations, ``p0_configs.csv``")
    if fig9 is None:
        return None
    phi = fig9.param("phi_final")[0]
    value = fig9.param("max_abs_diff_final_py")[0]
    if not (np.isfinite(phi) and np.isfinite(value)):
        return None
    final, theory = fig9.get("a", "final"), fig9.get("a", "percus_yevick")
    sigma = signed = py = math.nan
    if final is not None and theory is not None and len(final[0]) == len(theory[0]):
        diff = final[1] - theory[1]
        at = int(np.nanargmax(np.abs(diff)))
        sigma, signed, py = float(final[0][at]), float(diff[at]), float(theory[1][at])
    return phi, value, sigma, signed, py, "Fig. 9's run"


def _p0_fluid(path, fig9=None):
    rows = sorted(_read(path), key=lambda r: float(r["phi"]))
    if not rows:
        return []
    f = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    lo_c, hi_c = int(f["configs"].min()), int(f["configs"].max())
    configs = f"{lo_c}" if lo_c == hi_c else f"{lo_c} to {hi_c}"
    lines = ["Is a tapped packing expected to follow the Percus-Yevick P0(sigma) as closely as "
             "Fig. 9 shows? PY is a theory of the equilibrium hard-sphere fluid. The same "
             f"measurement (tapmc-pores --p0, {int(f['p0_points'][0])} random points per "
             "configuration, PY at the volume fraction seen by the points) on equilibrium "
             f"hard-sphere fluids of N = {int(f['N'][0])} spheres in a periodic cube (NVT "
             f"Monte Carlo, ``p0_fluid.csv``; mean ± sem over {configs} configurations per "
             "Phi; the contact value g(1+) against Carnahan-Starling checks the equilibrium):",
             "",
             ".. list-table::", "   :header-rows: 1", "",
             "   * - Phi", "     - max abs(P0 - PY)", "     - at sigma", "     - P0 - PY there",
             "     - g(1+)", "     - Carnahan-Starling",
             "     - MSD before sampling (diameters²)"]
    for k in range(len(rows)):
        lines += [f"   * - {f['phi'][k]:.3f}",
                  f"     - {fmt(f['max_abs_diff'][k], f['max_abs_diff_sem'][k])}",
                  f"     - {f['sigma_at_max'][k]:.3f}", f"     - {f['diff_at_max'][k]:+.4f}",
                  f"     - {f['g_contact'][k]:.3f} ± {f['g_contact_sem'][k]:.3f}",
                  f"     - {f['g_contact_cs'][k]:.3f}", f"     - {f['eq_msd'][k]:.2f}"]
    lines.append("")
    off = np.abs(f["g_contact"] / f["g_contact_cs"] - 1)
    bad = [f"{p:.3f}" for p, o in zip(f["phi"], off) if not o <= CONTACT_TOLERANCE]
    if bad:
        lines.append(f"* g(1+) departs from Carnahan-Starling by more than "
                     f"{100 * CONTACT_TOLERANCE:.0f} % at Phi = {', '.join(bad)}: those samples "
                     "are not equilibrium fluids, and their rows say nothing about PY.")
    else:
        lines.append(f"* g(1+) is within {100 * off.max():.1f} % of Carnahan-Starling at every "
                     "Phi: the samples are equilibrium fluids.")
    ok = np.array([o <= CONTACT_TOLERANCE for o in off])
    if not ok.any():
        return lines + [""]
    lo, hi = int(np.flatnonzero(ok)[0]), int(np.flatnonzero(ok)[-1])
    def side(k):
        return "above" if f["diff_at_max"][k] > 0 else "below"

    text = (f"* At Phi = {f['phi'][lo]:.3f}, where PY is most accurate, the measured P0 departs "
            f"from it by at most {fmt(f['max_abs_diff'][lo], f['max_abs_diff_sem'][lo])} (P0 "
            f"{side(lo)} PY): the measurement agrees with the theory to that level where the "
            "theory holds, which bounds the error of the tool.")
    if hi != lo:
        text += (f" At Phi = {f['phi'][hi]:.3f} the exact fluid departs from PY by "
                 f"{fmt(f['max_abs_diff'][hi], f['max_abs_diff_sem'][hi])} (at sigma = "
                 f"{f['sigma_at_max'][hi]:.2f}, P0 {side(hi)} PY).")
    lines.append(text)
    packing = _packing_p0(fig9, Path(path).with_name("p0_configs.csv"))
    if packing is None:
        return lines + [""]
    phi, value, sigma, signed, py, what = packing
    baseline = f["max_abs_diff"][hi]
    where = ""
    if np.isfinite(sigma):
        same = (signed > 0) == (f["diff_at_max"][hi] > 0)
        where = (f" at sigma = {sigma:.2f}, P0 " + ("above" if signed > 0 else "below")
                 + " PY (" + ("the fluid's direction" if same else "opposite to the fluid")
                 + ")")
    text = (f"* The tapped packing of Fig. 9 ({what}; Phi = {100 * phi:.1f} %) departs from "
            "PY by "
            f"{fmt(value)}{where}: {value / baseline:.1f} times the equilibrium fluid's at "
            f"Phi = {f['phi'][hi]:.3f}.")
    valid = np.flatnonzero(ok)
    if len(valid) >= 2 and phi > f["phi"][hi]:
        # the packing is denser than any fluid measured: extend the fluid's trend to its Phi
        # (a straight line through the valid rows) and compare with the larger of the two
        slope, icpt = np.polyfit(f["phi"][valid], f["max_abs_diff"][valid], 1)
        reach = slope * phi + icpt
        text += (f" A straight line through the fluid's values (slope {slope:.3f} per unit of "
                 f"Phi) reaches {reach:.4f} at the packing's Phi; the packing's is "
                 f"{value / reach:.1f} times that.")
        baseline = max(baseline, reach)
    if np.isfinite(py) and py > 0 and "py_at_max" in f:
        # P0 falls steeply with sigma: the deviation relative to PY where it is largest
        fluid_rel = np.abs(f["diff_at_max"][valid]) / f["py_at_max"][valid]
        trend = ""
        if len(valid) >= 2:
            rising = np.polyfit(f["phi"][valid], fluid_rel, 1)[0] > 0
            trend = " (growing with Phi)" if rising else " (falling with Phi)"
        text += (f" Relative to PY there, the packing departs by {100 * value / py:.0f} %, the "
                 f"fluid by {100 * fluid_rel.min():.1f} to {100 * fluid_rel.max():.1f} %"
                 f"{trend}.")
    ratio = value / baseline
    lines.append(text + " "
                 + ("Its agreement with PY is of the size PY itself misses in an equilibrium "
                    "fluid: as close as a fluid's, no closer."
                    if ratio <= BASELINE_FACTOR else
                    "The packing follows PY markedly less closely than an equilibrium fluid "
                    "does: Fig. 9's agreement is approximate, a packing resembling a dense "
                    "fluid, not the accuracy PY has for the fluid."))
    return lines + [""]


#: knob -> (the question, the knob's name, the paper's value as written, the claim's statistic)
_SCAN_QUESTIONS = {
    "theta0": ("Does theta0 = pi/4, the width of the trial moves' angular distribution (eq. 1), "
               "give the largest compaction rate, and does a much smaller theta0 decompact "
               "(section II)?", "theta0", "pi/4", "theta0_optimum"),
    "dmax": ("Is d_max = R/5 an intermediate value, much smaller or larger steps slowing the "
             "redeposition (section II)?", "d_max", "R/5", "dmax_intermediate"),
}


def _scan(path, knob):
    """One knob scan of bench/paper_questions.py (theta0 or dmax): the table, the claim's
    verdict on it and whether the value that compacts most just redeposits longer."""
    from .claims import (SCANS, STATISTICS, ReportData, load_register, scan_settings,
                         scan_table, verdict)

    rows = _read(path)
    table = scan_table(rows, knob)
    if not table:
        return []
    question, name, paper, statistic = _SCAN_QUESTIONS[knob]
    first = rows[0]
    sweeps = defaultdict(list)
    for r in rows:
        sweeps[float(r[SCANS[knob]["column"]])].append(float(r["sweeps_per_tap"]))
    lines = [f"{question} {first['taps']} taps at eps = {float(first['eps']):g} from the same "
             f"fresh packings (N = {first['N']}, P.B.C., {scan_settings(rows)}) at each {name} "
             f"(``{Path(path).name}``; gain: <Phi^c> over the last 10 taps minus <Phi^c> at "
             f"t = 0, mean ± sem over seeds; against {paper}: the paired difference on the same "
             "seeds):", "",
             ".. list-table::", "   :header-rows: 1", "",
             f"   * - {name}", "     - gain of <Phi^c>", f"     - against {paper}",
             "     - sweeps per tap"]
    for r in table:
        lines += [f"   * - {r['name']}", f"     - {fmt(r['gain'], r['gain_sem'], True)}",
                  "     - 0" if r["is_paper"] else f"     - {fmt(r['vs_paper'], r['vs_paper_sem'], True)}",
                  f"     - {np.mean(sweeps[r['value']]):.0f}"]
    claim = next(c for c in load_register() if c.statistic == statistic)
    measures = STATISTICS[statistic](ReportData({}, {}, (), {knob: [rows]}), claim)
    below = any(m.lacks for m in measures)
    text = (f"Verdict of the claim (rule {claim.rule}, t sem with {table[0]['n']} seeds): "
            + "; ".join(str(verdict(claim, m)) for m in measures)
            + (f" at N = {int(float(rows[0]['N']))}, below the paper's N (the claims' table "
               "counts it undecided there)" if below else "") + ".")
    # does the value that compacts most simply redeposit longer than the paper's?
    ref = next(r for r in table if r["is_paper"])
    best = max(table, key=lambda r: r["gain"])
    s_q, s_b = np.mean(sweeps[ref["value"]]), np.mean(sweeps[best["value"]])
    if best is not ref:
        if s_b > 1.1 * s_q:
            text += (f" {best['name']}, which compacts most, also takes more sweeps per tap than "
                     f"{paper} ({s_b:.0f} against {s_q:.0f}) before the stopping rule ends a "
                     f"tap: its gain mixes the effect of {name} with the redeposition's length.")
        else:
            text += (f" {best['name']}, which compacts most, takes about as many sweeps per tap "
                     f"as {paper} ({s_b:.0f} against {s_q:.0f}): its gain is the effect of "
                     f"{name} itself, not of a longer redeposition.")
    return lines + ["", text, ""]


#: <Phi^c> the paper reports after 4000 taps (section IV.B, Fig. 9)
PAPER_FINAL_PHI_C = 0.606


def _register_target(claim_id):
    from .claims import load_register

    return next(c.target for c in load_register() if c.id == claim_id)


#: <Phi^c> of the paper's initial P.B.C. packing (section IV.B): the register's target
PAPER_INITIAL_PHI_C = _register_target("phi-initial")


def _final_phi_eta(fig9, etas, front_rows):
    """Fig. 9's steady <Phi^c> carried to every redeposition setting of the front: the
    campaign's value plus (bias of the setting - bias of the campaign's eta) in the steady
    window, at the front's eps = 0.0225 (the bell's top, Fig. 9's eps) and its largest N with a
    reference. The paper does not give its eta, so this says which thresholds its 60.6 % fits."""
    from .front import REFERENCE, SETTINGS, setting_named

    if fig9 is None or len(etas) != 1:
        return []
    phi, phi_se, _ = fig9.param("phi_c_steady")
    own = setting_named(etas[0])
    sizes = sorted({r["N"] for r in front_rows if r["setting"] == REFERENCE})
    if not (np.isfinite(phi) and own and sizes):
        return []
    # the largest N whose default row has error bars (two paired seeds or more), else the largest
    with_errors = [n for n in sizes if any(r["N"] == n and r["setting"] == own
                                           and r.get("paired_seeds", 0) >= 2 for r in front_rows)]
    N = (with_errors or sizes)[-1]
    at = [r for r in front_rows if r["N"] == N]
    eps = min({r["eps"] for r in at}, key=lambda e: abs(e - 0.0225))
    # the redeposition's stopping settings only: d_max is a parameter of the model (R/5)
    rows = {r["setting"]: r for r in at if r["eps"] == eps
            and "dmax" not in SETTINGS.get(r["setting"], {}).get("keys", {"dmax": None})}
    if own not in rows:
        return []
    base, base_se = rows[own]["phi_c_steady_bias"], rows[own]["phi_c_steady_bias_se"]
    ordered = sorted(rows.values(), key=lambda r: r["cpu_per_tap"])
    lines = [f"The paper's <Phi^c> after 4000 taps is {100 * PAPER_FINAL_PHI_C:.1f} % and does not "
             f"say with which redeposition threshold. Fig. 9's run (eta = {etas[0]:g}) gives "
             f"{fmt(phi, phi_se, True)} steady. The run-time-versus-error front "
             f"(``doc/front.rst``, N = {N:.0f}, eps = {eps:g}, steady window, "
             f"{int(rows[own]['paired_seeds'])} paired seed{'s' if rows[own]['paired_seeds'] != 1 else ''}) measures how much each setting "
             "moves the steady <Phi^c> (its stopping settings; d_max stays the paper's R/5); carried to Fig. 9's run, assuming the shifts hold at "
             "its N and tap count (value + shift; error: the two biases' standard errors "
             "combined):", "",
             ".. list-table::", "   :header-rows: 1", "",
             "   * - setting", "     - CPU s per tap (front)", "     - shift against "
             f"eta = {etas[0]:g}", "     - Fig. 9's steady <Phi^c> with it"]
    predicted = []
    for r in ordered:
        shift = r["phi_c_steady_bias"] - base
        shift_se = 0.0 if r["setting"] == own else math.hypot(r["phi_c_steady_bias_se"], base_se)
        value = phi + shift
        predicted.append((value, r["setting"], math.hypot(shift_se, phi_se)))
        lines += [f"   * - {r['setting']}", f"     - {r['cpu_per_tap']:.3f}",
                  "     - 0" if r["setting"] == own else f"     - {fmt(shift, shift_se, True)}",
                  f"     - {fmt(value, math.hypot(shift_se, phi_se), True)}"]
    lo, hi = min(predicted), max(predicted)
    closest = min(predicted, key=lambda p: abs(p[0] - PAPER_FINAL_PHI_C))
    if lo[0] <= PAPER_FINAL_PHI_C <= hi[0]:
        verdict = (f"The paper's {100 * PAPER_FINAL_PHI_C:.1f} % lies inside the range the "
                   f"thresholds span ({fmt(lo[0], None, True)} with {lo[1]} to "
                   f"{fmt(hi[0], None, True)} with {hi[1]}); closest: {closest[1]} "
                   f"({fmt(closest[0], closest[2], True)}). The final <Phi^c> therefore tests "
                   "the paper's redeposition threshold as much as the model: the disagreement "
                   f"of Fig. 9's run at eta = {etas[0]:g} is of the size of the threshold's "
                   "effect, and cannot separate model and paper while the paper's eta is unknown.")
    else:
        verdict = (f"The paper's {100 * PAPER_FINAL_PHI_C:.1f} % lies outside the range the "
                   f"thresholds span ({fmt(lo[0], None, True)} to {fmt(hi[0], None, True)}): "
                   "no redeposition threshold explains the difference.")
    return lines + ["", verdict, ""]


def render_section(folder, figures=None, etas=(), front_rows=None):
    """The rst lines of the section, or [] when ``folder`` holds none of the CSVs.
    ``figures``: name -> tapmc.paper.claims.FigureData of the same report (Fig. 3's k, Fig. 9's
    packing)."""
    folder = Path(folder)
    parts = []
    if (folder / "first_tap.csv").is_file():
        parts += _first_tap(folder / "first_tap.csv")
    if (folder / "noise_floor.csv").is_file():
        parts += _noise_floor(folder / "noise_floor.csv", (figures or {}).get("fig3"))
    if (folder / "spectral_window.csv").is_file():
        parts += _spectral_window(folder / "spectral_window.csv")
    factors = realization_factors(_read(folder / "realization_scatter.csv")) \
        if (folder / "realization_scatter.csv").is_file() else {}
    if (folder / "realization_scatter.csv").is_file():
        parts += _realization_scatter(folder / "realization_scatter.csv")
    if (folder / "packing_scatter.csv").is_file():
        parts += _packing_scatter(folder / "packing_scatter.csv")
    if (folder / "pbc_course.csv").is_file():
        parts += _pbc_course(folder / "pbc_course.csv", factors)
    if (folder / "integrity.csv").is_file():
        parts += _integrity(folder / "integrity.csv")
    if (folder / "early_taps.csv").is_file():
        parts += _early_taps(folder / "early_taps.csv")
    if (folder / "fit_surrogates.csv").is_file():
        parts += _fit_surrogates(folder / "fit_surrogates.csv",
                                 _read(folder / "seed_fits.csv")
                                 if (folder / "seed_fits.csv").is_file() else [])
    if (folder / "seed_fits.csv").is_file():
        parts += _seed_fits(folder / "seed_fits.csv")
    if (folder / "initial_packing.csv").is_file():
        parts += _initial_packing(folder / "initial_packing.csv")
    if (folder / "p0_configs.csv").is_file():
        parts += _p0_configs(folder / "p0_configs.csv")
    if (folder / "ramp_levels.csv").is_file():
        parts += _ramp_levels(folder / "ramp_levels.csv", (figures or {}).get("fig4"), factors)
    if (folder / "ramp_pores.csv").is_file():
        parts += _ramp_pores(folder / "ramp_pores.csv")
    if (folder / "lateral_first_tap.csv").is_file():
        parts += _lateral_first_tap(folder / "lateral_first_tap.csv",
                                    (figures or {}).get("fig8"))
    from .claims import SCANS, scan_files

    for knob in SCANS:
        for scan in scan_files(folder, knob):
            parts += _scan(scan, knob)
    if (folder / "p0_fluid.csv").is_file():
        parts += _p0_fluid(folder / "p0_fluid.csv", (figures or {}).get("fig9"))
    parts += _pores((figures or {}).get("fig10")) if parts else []
    if parts:
        parts += _final_phi_eta((figures or {}).get("fig9"), list(etas), front_rows or [])
    if not parts:
        return []
    title = "Questions settled by measurement"
    # the commands that made the CSVs (p0-fluid named only when its CSV is there)
    commands = "``first-tap``, ``noise-floor``, ``spectral-window``" + (
        ", ``realization-scatter``" if (folder / "realization_scatter.csv").is_file()
        else "") + (
        ", ``packing-scatter``" if (folder / "packing_scatter.csv").is_file() else "") + (
        ", ``pbc-course``" if (folder / "pbc_course.csv").is_file() else "") + (
        ", ``integrity``" if (folder / "integrity.csv").is_file() else "") + (
        ", ``early-taps``" if (folder / "early_taps.csv").is_file() else "") + (
        ", ``fit-surrogates``" if (folder / "fit_surrogates.csv").is_file() else "") + (
        ", ``seed-fits``" if (folder / "seed_fits.csv").is_file() else "") + (
        ", ``initial-packing``" if (folder / "initial_packing.csv").is_file() else "") + (
        ", ``p0-configs``" if (folder / "p0_configs.csv").is_file() else "") + (
        ", ``lateral-first-tap``" if (folder / "lateral_first_tap.csv").is_file() else "") + (
        ", ``ramp-levels``" if (folder / "ramp_levels.csv").is_file() else "") + (
        ", ``ramp-pores``" if (folder / "ramp_pores.csv").is_file() else "") + (
        "".join(f", ``{k}``" for k in ("theta0", "dmax") if any(folder.glob(f"{k}*.csv")))) + (
        ", ``p0-fluid``" if (folder / "p0_fluid.csv").is_file() else "")
    return [title, "-" * len(title), "",
            f"Measured by ``bench/paper_questions.py`` ({commands}), whose "
            "CSVs are in ``validation/questions/``; the text below is computed from them.", ""] \
        + parts


__all__ = ["render_section", "FOLDER"]
