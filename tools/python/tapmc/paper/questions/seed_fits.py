# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""seed-fits: do independent realizations fix the triplet (X_inf, B, tau) of eq. 3 (and eq.
4's parameters) over a whole run, and do they depend on the range of taps fitted (section
III.B)? Every group of finished constant-eps and ageing runs that differ only in their seed
(realization-scatter's groups): each run fitted from tap 1 over all its taps and over taps
1-T/4, 1-T/2 and T/10-T, the spread of each parameter over the runs with its 95 % chi-square
interval, and the paired t-test of each range against all taps (tapmc.laws.RealizationFits;
no simulation, seconds; seed_fits.csv)."""

from __future__ import annotations

from collections import defaultdict

import numpy as np

from tapmc.laws import RealizationFits

from .._rst import list_table
from .common import csv_schema, last_rows, seed_groups, taps_table
from .fit_surrogates import FIT_LAWS, law as fit_law

NAME = "seed-fits"
CSV = "seed_fits.csv"
#: the header of seed_fits.csv (values: each run's fit in the comparison scale, ln for B and
#: tau; determined: 1, 0, or empty when the realizations cannot tell)
SEED_FITS_HEADER = ["group", "bc", "eps", "law", "taps", "realizations", "parameter", "values",
                    "mean", "spread", "spread_low", "spread_high", "limit", "log_scale",
                    "determined", "range_shift", "range_bound", "range_p"]


def add_arguments(parser):
    """No options beyond --campaign and --out."""


def _parameter_row(group, bc, eps, law_name, last, fits, k):
    d = fits.determined[k]
    return [group, bc, eps, law_name, last, fits.realizations, k,
            ";".join(f"{v:.6g}" for v in fits.values[k]),
            f"{fits.mean[k]:.8g}", f"{fits.spread[k]:.6g}",
            f"{fits.spread_low[k]:.6g}", f"{fits.spread_high[k]:.6g}",
            f"{fits.limit[k]:.6g}", int(fits.log_scale[k]),
            "" if d is None else int(d), f"{fits.range_shift[k]:.6g}",
            f"{fits.range_bound[k]:.6g}", f"{fits.range_p[k]:.4g}"]


def analyse(campaign):
    """Per group of realizations and law of Fig. 2: RealizationFits over the taps every run
    has, from tap 1."""
    rows = []
    for group, runs in seed_groups(campaign).items():
        tables = [taps_table(run_dir / "taps.dat") for _, run_dir in runs]
        printed = [last_rows(table) for table in tables]
        last = min(max(p) for p in printed)
        t = np.arange(1, last + 1, dtype=float)
        bc = group.split("_")[1]
        eps = float(group.split("_eps")[1])
        for law_name, column in FIT_LAWS:
            curves = [[float(table[column][p[int(k)]]) for k in t]
                      for table, p in zip(tables, printed)]
            fits = RealizationFits(fit_law(law_name)).compute(t, curves)
            rows += [_parameter_row(group, bc, eps, law_name, last, fits, k)
                     for k in fits.law.names]
            print(f"{group} {law_name}: {fits}", flush=True)
    return rows


def measure(args):
    save(args.out / CSV, analyse(args.campaign))


save, load = csv_schema(SEED_FITS_HEADER)


def render(path):
    rows = load(path)
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
             "noise, and decides both ways:", ""]
    table = []
    for (bc, eps, group, law), group_rows in sorted(groups.items()):
        cells = []
        for r in group_rows:
            unit = "ln " if r["log_scale"] == "1" else ""
            cells.append(f"{r['parameter']} {float(r['mean']):.3g} (sd of {unit}"
                         f"{r['parameter']} {float(r['spread']):.2g}, "
                         f"{float(r['spread_low']):.2g} to {float(r['spread_high']):.2g}; "
                         f"{states[r['determined']]}; range p {float(r['range_p']):.2g})")
        first = group_rows[0]
        table.append([group, law.replace('eq', 'eq. '), first['realizations'], first['taps'],
                      '; '.join(cells)])
    header = ["group", "law", "runs", "taps",
              "parameters (mean; sd with its 95 % interval; verdict; range p)"]
    return lines + list_table(header, table) + [""]

