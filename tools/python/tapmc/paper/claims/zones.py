# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Statistics of the profiles and zones (Figs. 6-8): the final alpha, the central zone against
the lateral one, the zones' bell in sqrt(eps), and the lateral zone over the first taps from
the paper's F.B.C. start."""

from __future__ import annotations

import math

import numpy as np

from tapmc.laws import ProfileLaw
from tapmc.profiles import PROFILE_JACKKNIFE_BLOCKS
from tapmc.stats import mean_dof, t_quantile, weighted_line

from .._runs import PAPER_START_TAG, eps_tag
from .bell import steady_maximum
from .common import (jackknife_dof, not_in_campaign, one_seed_error_text, seed_mean_of,
                     steady_dof, value_triple)
from ..fig7 import FIRST_LAYER_WIDTH, LATERAL_WIDTH
from .conventions import BELL_SIDE_POINTS, EQ7_SMOOTHING_WIDTH, WALL_LAYERS_APPROXIMATELY
from .measure import Measure, fmt
from .registry import statistic


def _fbc_group_names(eps):
    """The names realization-scatter gives the group of the F.B.C. constant-eps runs at
    ``eps`` (either start: tapmc.paper._runs.constant_eps_run); () without an eps."""
    if not np.isfinite(eps):
        return ()
    return tuple(f"const_{tag}_eps{eps_tag(eps)}" for tag in ("fbc", PAPER_START_TAG))


@statistic("final_alpha")
def final_alpha(data, claim):
    fig6 = data.result("fig6")
    if fig6 is None:
        return not_in_campaign("no Fig. 6 runs")
    profiles = fig6.profiles
    m, s, n = value_triple(None if profiles is None else profiles.alpha["final"])
    if not np.isfinite(m):
        return not_in_campaign("no F.B.C. profile runs")
    if n >= 2:
        m, s, dof, how = seed_mean_of(data, profiles.alpha["final"], profiles.alpha_seeds,
                                      "packing:alpha", "fbc", _fbc_group_names(profiles.eps))
        return [Measure(m, s, dof, shown=fmt(m, s) + (f" ({how})" if how else ""))]
    within = " (one seed: lateral jackknife of its packing)" if n == 1 and np.isfinite(s) else ""
    return [Measure(m, s, jackknife_dof(n, s, PROFILE_JACKKNIFE_BLOCKS),
                    shown=fmt(m, s) + within)]


def smoothed_departures(profile, curve, bottom, width):
    """(departures, errors) of ``profile`` (a Series over z/R) from the eq. 7 ``curve`` (a
    Series on the same bins) smoothed over blocks of ``width`` R from ``bottom`` up to the
    packing's top (the last block whose bins all have a positive error): each block's mean of
    the profile minus its mean of the curve, and the mean of the bins' errors, the most the
    block mean's error can be (the bins share spheres: their errors are correlated)."""
    fitted = np.interp(profile.x, curve.x, curve.mean, left=np.nan, right=np.nan)
    departures, errors = [], []
    start = bottom
    while True:
        block = (profile.x >= start) & (profile.x < start + width)
        errs = profile.err[block]
        if not block.any() or not np.all(np.isfinite(fitted[block])) \
                or not np.all(np.isfinite(errs) & (errs > 0)):
            break
        departures.append(float(np.mean(profile.mean[block] - fitted[block])))
        errors.append(float(np.mean(errs)))
        start += width
    return np.array(departures), np.array(errors)


@statistic("eq7_smoothed_fit")
def eq7_smoothed_fit(data, claim):
    """Section IV.A: eq. 7 is "the following average fit for a typical vertical profile",
    read "after a smoothing of the profile". Fig. 6's final profile (seed mean) smoothed
    over blocks of EQ7_SMOOTHING_WIDTH from the bottom of the gradient window to the
    packing's top, against eq. 7 fitted to it (tapmc.paper.fig6): a chi-square of the blocks'
    departures over their errors, with the blocks less the law's parameters as dof. The raw
    bins' rms departure in the window is shown beside it: the wall layers stacked from the
    floor, which eq. 7 does not describe and the smoothing removes."""
    fig6 = data.result("fig6")
    profiles = None if fig6 is None else fig6.profiles
    if profiles is None or "final" not in profiles.law_curves:
        return not_in_campaign("no eq. 7 fit of Fig. 6's final profile")
    final, curve = profiles.final, profiles.law_curves["final"]
    departures, errors = smoothed_departures(final, curve, profiles.window[0],
                                             EQ7_SMOOTHING_WIDTH)
    dof = len(departures) - len(ProfileLaw.names)
    if dof < 1:
        return [Measure(undecided=f"{len(departures)} blocks of {EQ7_SMOOTHING_WIDTH:g}R "
                                  "under the packing's top: too few for eq. 7's parameters")]
    reduced = float(np.sum((departures / errors) ** 2) / dof)
    lo, hi = profiles.window
    inside = (final.x >= lo) & (final.x <= hi)
    raw = final.mean[inside] - np.interp(final.x[inside], curve.x, curve.mean)
    return [Measure(reduced, math.nan, dof, shown=(
        f"smoothed over {EQ7_SMOOTHING_WIDTH:g}R: reduced chi2 {reduced:.3g} over "
        f"{len(departures)} blocks from z/R = {lo:g}, largest departure "
        f"{np.max(np.abs(departures)):.2g}; raw bins in {lo:g}-{hi:g}R: rms departure "
        f"{np.sqrt(np.mean(raw ** 2)):.2g} against errors {np.median(final.err[inside]):.2g}"))]


def wall_layers(distance, phi, threshold, gap=FIRST_LAYER_WIDTH):
    """The layers along one wall of a transversal profile: (first, last) distances of each
    run of bins above ``threshold``, walking from the wall (bins ordered by ``distance``)
    until the profile stays at or below it for ``gap`` (one diameter: a layer's spacing
    without a layer ends the layering; the first layer must start within it of the wall)."""
    layers, below_since, inside = [], 0.0, False
    for d, value in zip(distance, phi):
        if value > threshold and not inside:
            layers.append([d, d])
            inside = True
        elif value <= threshold and inside:
            layers[-1][1], below_since, inside = d, d, False
        elif not inside and d - below_since >= gap:
            break
    return [tuple(layer) for layer in layers]


@statistic("wall_layering")
def wall_layering(data, claim):
    """Section IV.A: the F.B.C. transversal profile (Fig. 7, after the taps) shows "a local
    organisation in layers due to the walls; this effect has approximately a three layers
    range". From each wall, the runs of bins above the bulk's spread: the central zone's
    (beyond LATERAL_WIDTH of the walls) mean plus t times the sd of its bins, with one dof
    per sphere diameter of the zone less one (neighbouring bins share spheres). The pattern
    agrees when the count is within WALL_LAYERS_APPROXIMATELY of three."""
    fig7 = data.result("fig7")
    if fig7 is None or not np.any(np.isfinite(fig7.final.mean)):
        return not_in_campaign("no Fig. 7 runs")
    x, phi, side = fig7.final.x, fig7.final.mean, fig7.side
    bulk = np.minimum(x, side - x) >= LATERAL_WIDTH
    dof = (side - 2 * LATERAL_WIDTH) / FIRST_LAYER_WIDTH - 1
    if bulk.sum() < 3 or dof < 1:
        return [Measure(undecided="no central zone to measure the bulk's spread in")]
    spread = float(np.std(phi[bulk], ddof=1))
    threshold = float(np.mean(phi[bulk])) + t_quantile(dof) * spread
    out = []
    for wall, order in (("x = 0", np.argsort(x)), (f"x = {side:g}R", np.argsort(-x))):
        layers = wall_layers(np.minimum(x, side - x)[order], phi[order], threshold)
        count = len(layers)
        agrees = abs(count - 3) <= WALL_LAYERS_APPROXIMATELY
        where = ", ".join(f"{lo:.1f}-{hi:.1f}R" for lo, hi in layers)
        out.append(Measure(1.0 if agrees else 0.0, label=f"wall at {wall}", shown=(
            f"{count} layers above Phi = {threshold:.3f} (bulk {np.mean(phi[bulk]):.3f}, "
            f"sd {spread:.2g} over its bins){': ' + where if where else ''}")))
    return out


@statistic("central_minus_lateral")
def central_minus_lateral(data, claim):
    fig8 = data.result("fig8")
    if fig8 is None:
        return not_in_campaign("no Fig. 8 runs")
    out = []
    for eps, zones in sorted(fig8.increases.items()):
        if not (zones.final or zones.final_seeds or zones.first_tap):
            continue    # no statistics at this eps
        cen = value_triple(zones.final.get("central"))
        lat = value_triple(zones.final.get("lateral"))
        # the zones of one run move together: their difference per seed (paired) has the
        # error; CSVs written before it was drawn fall back to the zones' errors combined
        diff = value_triple(zones.final.get("central_minus_lateral"))
        if not np.isfinite(diff[0]):
            diff = (cen[0] - lat[0], math.hypot(cen[1], lat[1]), min(cen[2], lat[2]))
        value, err, n = diff
        factor = data.run_error("zone:central_minus_lateral", "fbc")[0]
        within = (f" ({one_seed_error_text(factor)})" if n == 1 and np.isfinite(err) else "")
        dof = steady_dof(n, err)
        seeds = zones.final_seeds.get("central_minus_lateral")
        if n >= 2 and seeds is not None:
            _, err, dof, how = seed_mean_of(data, zones.final["central_minus_lateral"], seeds,
                                            "zone:central_minus_lateral", "fbc",
                                            _fbc_group_names(eps))
            within = f" ({how})"
        out.append(Measure(value, err, dof, label=f"eps = {eps:g}",
                           shown=f"{fmt(cen[0], cen[1])} vs {fmt(lat[0], lat[1])}; "
                                 f"difference {fmt(value, err)}{within}"))
    return out or not_in_campaign("no F.B.C. profile")


@statistic("zone_bell")
def zone_bell(data, claim):
    """Section IV.A: delta Phi_lateral and delta Phi_central "have the same dependence on
    eps^(1/2) than the other ones (bell shape curves)": each zone's final increase (Fig. 8,
    mean over the last quarter of the taps) rises with sqrt(eps) below the steady states'
    maximum (Fig. 4) and falls above it. A weighted straight line through each side (sign:
    rising below, falling above); a side of fewer than BELL_SIDE_POINTS eps is undecided."""
    fig8 = data.result("fig8")
    if fig8 is None:
        return not_in_campaign("no Fig. 8 runs")
    top = steady_maximum(data)
    if top is None:
        return not_in_campaign("no maximum of the steady states (Fig. 4)")
    out = []
    for zone in ("lateral", "central"):
        points = [(math.sqrt(eps), *value_triple(z.final.get(zone)))
                  for eps, z in sorted(fig8.increases.items()) if z.final.get(zone) is not None]
        for side, sign in (("below", 1), ("above", -1)):
            pick = [p for p in points if (p[0] < top) == (side == "below")
                    and np.isfinite(p[1]) and np.isfinite(p[2])]
            label = f"delta Phi_{zone}, {side} sqrt(eps) = {top:.3g} (Fig. 4's maximum)"
            if len(pick) < BELL_SIDE_POINTS:
                out.append(Measure(label=label, sign=sign, undecided=(
                    f"{len(pick)} eps of Fig. 8 {side} the maximum: a slope needs "
                    f"{BELL_SIDE_POINTS}")))
                continue
            x, y, s, _ = (np.array(v, dtype=float) for v in zip(*pick))
            slope, err, dof = weighted_line(x, y, s)
            out.append(Measure(slope, err, dof, label=label, sign=sign,
                               shown=f"slope {fmt(slope, err)} through {len(pick)} eps"))
    return out


@statistic("lateral_first_tap")
def lateral_first_tap(data, claim):
    fig8 = data.result("fig8")
    if fig8 is None:
        return not_in_campaign("no Fig. 8 runs")
    lateral = sorted((eps, zones.lateral) for eps, zones in fig8.increases.items())
    if not fig8.paper_start and data.question("lateral_first_tap"):
        return _lateral_first_tap_measured(data.question("lateral_first_tap"))
    if not fig8.paper_start:
        values = [f"{fmt(c.mean[c.x == 1][0], c.err[c.x == 1][0])} at eps = {eps:g}"
                  for eps, c in lateral if np.any(c.x == 1)]
        seen = "; with the start deposited between walls: " + ", ".join(values) if values else ""
        return [Measure(undecided="no F.B.C. run from the paper's start" + seen)]
    out = []
    for eps, curve in lateral:
        if not np.any(curve.x == 1):
            continue
        k = int(np.argmax(curve.x == 1))
        out.append(Measure(curve.mean[k], curve.err[k], mean_dof(curve.n[k]),
                           label=f"eps = {eps:g}"))
    return out or not_in_campaign("no tap 1 in the paper-start curves")


def _lateral_first_tap_measured(rows):
    """delta Phi_lateral at t = 1 per eps over the seeds of tapmc-paper question
    lateral-first-tap (the paper's F.B.C. start, taps from t = 0)."""
    per = {}
    for r in rows:
        per.setdefault(float(r["eps"]), {}).setdefault(int(r["seed"]), {})[int(r["t"])] = \
            float(r["lateral"])
    out = []
    for eps, seeds in sorted(per.items()):
        jumps = np.array([t[1] - t[0] for t in seeds.values() if 0 in t and 1 in t])
        if len(jumps) == 0:
            continue
        sem = float(jumps.std(ddof=1) / math.sqrt(len(jumps))) if len(jumps) > 1 else math.nan
        out.append(Measure(float(jumps.mean()), sem, mean_dof(len(jumps)), label=f"eps = {eps:g}",
                           shown=f"{fmt(float(jumps.mean()), sem)} (the paper's start, "
                                 f"{len(jumps)} seeds: tapmc-paper question "
                                 "lateral-first-tap)"))
    return out or not_in_campaign("no tap 1 from the paper's start")
