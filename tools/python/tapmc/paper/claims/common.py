# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Pieces the statistics of several sections share: reading series of a figure CSV, the mean
difference of two curves, the degrees of freedom of a steady mean, and the error of a mean of
a few seeds judged with the campaign's groups of realizations."""

from __future__ import annotations

import math

import numpy as np

from tapmc.fluctuations import DEFAULT_BATCHES
from tapmc.stats import beyond

from .. import _plotting as P
from .._results import Series, Value
from .conventions import PAIRED_MIN_LEVELS
from ..fig2 import LAWS as FIG2_LAWS
from ..paper_ramp import eta_text
from .measure import Measure, fmt


def paper_precision(deviation, precision):
    """A law's largest departure from the data, ``deviation``, in units of the paper's
    ``precision`` for it: at most 1 when the paper could not tell the law from the data;
    None when either is not a positive finite number."""
    if not (np.isfinite(deviation) and np.isfinite(precision) and precision > 0):
        return None
    return float(deviation / precision)


def above(value, err, dof, reference=0.0):
    """``value`` above ``reference`` beyond t err (tapmc.stats.beyond, one side)."""
    return value > reference and beyond(value, err, dof, reference)


def below(value, err, dof, reference=0.0):
    """``value`` below ``reference`` beyond t err (tapmc.stats.beyond, one side)."""
    return value < reference and beyond(value, err, dof, reference)


def one_seed_error_text(factor):
    """What a one-seed value's error is, as its TAPMC column says it."""
    if factor == 1.0:
        return "one seed: error within the run"
    return (f"one seed: error within the run x {factor:.1f}, the spread of realizations "
            "measured by realization-scatter")


def not_in_campaign(what):
    return [Measure(undecided=f"not in this campaign ({what})")]


def eps_of(series):
    """eps of a series named 'eps=<eps>' or 'eps=<eps>:<name>'."""
    return float(series.split("=")[1].split(":")[0])


def common_x(a, b):
    """Index pairs (i, k) of the x common to the curves a and b ((x, mean, sem, n) each)."""
    pairs = []
    for i, x in enumerate(a[0]):
        match = np.isclose(b[0], x)
        if np.any(match):
            pairs.append((i, int(np.argmax(match))))
    return pairs


def mean_difference(a, b):
    """Mean over the common x of the curves a - b ((x, mean, sem, n) each), its error and dof;
    None when they share no x."""
    pairs = common_x(a, b)
    if not pairs:
        return None
    diffs = [a[1][i] - b[1][k] for i, k in pairs]
    errs = np.array([math.hypot(a[2][i], b[2][k]) for i, k in pairs])
    ns = [min(a[3][i], b[3][k]) for i, k in pairs]
    err = float(np.sqrt(np.sum(errs**2)) / len(errs)) if np.all(np.isfinite(errs)) else math.nan
    return float(np.mean(diffs)), err, steady_dof(int(np.min(ns)), err), len(diffs)


#: Degrees of freedom of the batch-means error of one run's steady state (the batches of
#: tapmc.fluctuations.SteadyState, minus one): the uncertainty of a figure value of one seed.
WITHIN_RUN_DOF = DEFAULT_BATCHES - 1


def steady_dof(n, err):
    """dof of a steady-state value: seeds - 1, or for one seed with a batch-means error
    :data:`WITHIN_RUN_DOF`."""
    if n >= 2:
        return n - 1
    return WITHIN_RUN_DOF if n == 1 and np.isfinite(err) else None


def fig2_curves(data, tag="eq3"):
    """(curves, None) with curves [(eps, CurveFit)] of Fig. 2's typed result for law ``tag``
    ('eq3': Phi_b, panel a; 'eq4': <Z>, panel c) by eps, eps as the figure labels it; or
    (None, the undecided measures) when there is no Fig. 2 or no curve of that law."""
    fig2 = data.result("fig2")
    if fig2 is None:
        return None, not_in_campaign("no Fig. 2 runs")
    law = fig2.laws.get(tag)
    curves = [] if law is None else sorted(
        ((float(P.fmt_eps(c.eps)), c) for c in law.curves.values()), key=lambda ec: ec[0])
    if not curves:
        return None, not_in_campaign(f"no curve in panel {FIG2_LAWS[tag][2]} of Fig. 2")
    return curves, None


def curve_arrays(curve):
    """(t, mean, sem, n) of a Fig. 2 CurveFit's data."""
    return curve.data.x, curve.data.mean, curve.data.err, curve.data.n


def per_fig2_curve(data, measure):
    """``measure(eps, t, mean, sem, n)`` of every Phi_b curve of Fig. 2 (panel a), by eps."""
    curves, missing = fig2_curves(data)
    if curves is None:
        return missing
    return [measure(eps, *curve_arrays(c)) for eps, c in curves]


def paired_levels(a, b):
    """a - b at the sqrt(eps) common to the branch curves a and b ((x, mean, sem, n) each)."""
    return np.array([a[1][i] - b[1][k] for i, k in common_x(a, b)])


def curve_of(series):
    """(x, mean, sem, n) of a figure result's Series (None: None), the curves' form of
    :func:`common_x` and :func:`paired_levels`."""
    return None if series is None else (series.x, series.mean, series.err, series.n)


def value_triple(value):
    """(value, err, n) of a figure result's Value; NaNs and n = 0 for one the CSV does not
    have (None: drawn before it was)."""
    return (math.nan, math.nan, 0) if value is None else (value.value, value.err, value.n)


def seed_mean(data, fig, series, quantity, bc="pbc", groups=()):
    """:func:`seed_mean_of` the params row ``series`` of ``fig`` (rows by panel and series)
    and its ``<series>:seeds`` row."""
    seeds = fig.get("params", f"{series}:seeds")
    seeds = None if seeds is None else Series(*seeds)
    m, s, n = fig.param(series)
    return seed_mean_of(data, Value(0.0, m, s, n), seeds, quantity, bc, groups)


def seed_mean_of(data, value, seeds, quantity, bc="pbc", groups=(), levels=None):
    """(value, error, dof, text) of a figure's :class:`Value` ``value``: with two seeds or
    more and their own values ``seeds`` (a :class:`Series`; Fig. 4's ramp statistics, Fig. 8's final
    zones, Fig. 6's final alpha) the error of their mean judged with the campaign's groups
    of realizations of ``quantity``
    (ReportData.seed_mean_error); otherwise the row's own error (the sem over seeds, or
    one seed's batch-means error) with :func:`steady_dof`. ``text``: how the error was
    obtained ("" for the row's own). ``groups``: the names the seeds have as a group of
    realizations (ReportData.seed_mean_error). Seeds judged alone (no groups, or a spread
    unlike theirs) take at least the sem of their own values: a row that combines the
    levels' sems over seeds as independent understates the spread of seeds that differ at
    every level alike. ``levels``: the value's paired differences at each level common to
    the branches it compares (a ramp's), which decide seeds judged alone
    (:func:`seeds_error`)."""
    m, s, n = value_triple(value)
    if n >= 2 and seeds is not None and len(seeds) >= 2:
        err, dof, text, pooled = seeds_error(data, seeds.mean, seeds.err, quantity, bc, groups,
                                             levels)
        return m, err if pooled else max(s, err), dof, text
    return m, s, steady_dof(n, s), ""


def seeds_error(data, values, errors, quantity, bc="pbc", groups=(), levels=None):
    """(error, dof, text, pooled) of the mean of a few seeds ``values`` of ``quantity``, each
    with its own error ``errors``: pooled with the campaign's groups of realizations
    (ReportData.seed_mean_error: their own errors times the pooled factor, the pooled dof),
    or judged alone (no groups, or a spread unlike theirs). Seeds judged alone take the sem
    of their own values, never less than the groups' realization error of such a mean
    (ReportData.realization_floor), with n - 1 dof; but two seeds have one (t = 12.7), so a
    value made of :data:`PAIRED_MIN_LEVELS` paired levels or more (``levels``: its paired
    differences, mean over the seeds, at each level) is decided by the paired test over
    them: the error is at least their scatter over the levels, sd / sqrt(levels), with
    levels - 1 dof, and no smaller than the seeds' own spread or the groups' floor. ``text``
    says how ("" for seeds alone in a campaign without groups)."""
    found = data.seed_mean_error(quantity, values, errors, bc, groups)
    if found is not None:
        err, dof, factor = found
        return err, dof, (f"{len(values)} seeds: their own errors x {factor:.1f}, pooled "
                          f"with the groups of realizations ({dof} dof)"), True
    values = np.asarray(values, dtype=float)
    sem = float(np.std(values, ddof=1) / math.sqrt(len(values)))
    floor = data.realization_floor(quantity, errors, bc)
    err, dof = max(sem, floor or 0.0), len(values) - 1
    listed = ", ".join(fmt(v) for v in values)
    text = ""
    if floor is not None:
        text = (f"{len(values)} seeds ({listed}): the spread of their own values, which "
                "differs from the groups of realizations")
    paired = None if levels is None else np.asarray(levels, dtype=float)
    if paired is not None and len(paired) >= PAIRED_MIN_LEVELS and np.all(np.isfinite(paired)):
        scatter = float(np.std(paired, ddof=1) / math.sqrt(len(paired)))
        err, dof = max(err, scatter), len(paired) - 1
        text = (f"{len(values)} seeds ({listed}) judged alone: the paired test over the "
                f"{len(paired)} common levels (their scatter {fmt(scatter)}, {dof} dof), the "
                f"error no smaller than the seeds' own spread {fmt(sem)}"
                + ("" if floor is None else f" or the groups' realization error {fmt(floor)}"))
    return err, dof, text, False


def jackknife_dof(n, err, blocks_per_side):
    """dof of a value of one packing or several: seeds - 1, or for one seed with the error of
    a lateral jackknife over blocks_per_side^2 blocks, that number minus one."""
    n = int(np.nanmin(np.atleast_1d(n))) if np.size(n) else 0
    if n >= 2:
        return n - 1
    return blocks_per_side ** 2 - 1 if n == 1 and np.all(np.isfinite(err)) else None


def protocol_label(taps_per_level, eta):
    """Which ramps a ramp claim's row was decided on: taps per level and redeposition
    threshold (section III.B's protocol has 4000 taps per level)."""
    return f"{taps_per_level} taps per level, eta = {eta_text(eta)}"


def campaign_eta(summary):
    """The campaign's eta from its summary (report.json lists the values of its runs: one in a
    campaign at one threshold, which the runs without an eta in their name share); None when
    it lists several or none."""
    etas = summary.get("eta")
    etas = etas if isinstance(etas, list) else [] if etas is None else [etas]
    return float(etas[0]) if len(etas) == 1 else None


def campaign_ramp_label(summary):
    """The label of the rows decided on the campaign's own ramps, from its summary
    (report.json): "" unless it gives one taps per level and one eta."""
    per_level, eta = summary.get("ramp_taps_per_level"), campaign_eta(summary)
    if not (isinstance(per_level, list) and len(per_level) == 1) or eta is None:
        return ""
    return protocol_label(int(per_level[0]), eta)
