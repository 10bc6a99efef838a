# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""fit-surrogates: does one 4000-tap run fix the triplet (X_inf, B, tau) of eq. 3 (and eq.
4's parameters), and do they depend on the range of taps fitted (section III.B)? Per
finished F.B.C. constant-eps run of the campaign (every seed; the claims read the first of
each eps): tapmc.laws.SurrogateFits (Fourier surrogates of the run's residuals, --surrogates,
default 200; no simulation). And, from early_taps.csv, the spread of the same fits over the
independent realizations of the first 400 taps (fit_surrogates.csv)."""

from __future__ import annotations

import time
from collections import defaultdict

import numpy as np

from tapmc.laws import (DETERMINED_FACTOR, RELATIVE_ERROR_LIMIT, SURROGATES, InverseLogLaw,
                        SurrogateFits, ZLaw)

from .._rst import list_table
from .common import csv_schema, eps_of, finished_runs, last_rows, taps_table
from .early_taps import CSV as EARLY_CSV, load as load_early

NAME = "fit-surrogates"
CSV = "fit_surrogates.csv"
HEADER = ["source", "eps", "law", "taps", "parameter", "value", "low", "high", "half_width",
          "log_scale", "determined", "range_p", "fits"]
#: the laws of Fig. 2 and the column each describes
FIT_LAWS = (("eq3", "phi_b"), ("eq4", "Z"))
#: the band of the realizations' fitted values: their 16-84 % percentiles (one sd each side
#: for a normal spread)
BAND_PERCENTILES = (16.0, 50.0, 84.0)


def add_arguments(parser):
    parser.add_argument("--surrogates", type=int, default=None,
                        help="Fourier surrogates of each run's residuals fitted per law, at "
                             f"least 20 (default {SURROGATES})")
    parser.add_argument("--seed", type=int, default=1,
                        help="seed of the surrogates' random phases, the same for every run "
                             "(default %(default)s)")


def law(name):
    """The law of Fig. 2 named ``name`` (eq3: eq. 3 of Phi_b, eq4: eq. 4 of <Z>)."""
    return {"eq3": InverseLogLaw, "eq4": ZLaw}[name]()


def curve(table, column):
    """(t, y) of a taps table's ``column``, the last print of each step, in step order."""
    rows = last_rows(table)
    t = np.array(sorted(rows), dtype=float)
    return t, np.array([table[column][rows[int(k)]] for k in t])


def run_rows(campaign, surrogates, seed):
    """Per finished F.B.C. constant-eps run and law: SurrogateFits from tap 1 (as Fig. 2 is
    drawn) over the run's taps."""
    rows = []
    for run_dir in finished_runs(campaign, "const_fbc_eps*_s*"):
        table = taps_table(run_dir / "taps.dat")
        for law_name, column in FIT_LAWS:
            start = time.monotonic()
            t, y = curve(table, column)
            fits = SurrogateFits(law(law_name), surrogates=surrogates, seed=seed).compute(t, y)
            for k in fits.params:
                rows.append([run_dir.name, eps_of(run_dir.name), law_name, int(t.max()), k,
                             f"{fits.params[k]:.8g}", f"{fits.low[k]:.8g}", f"{fits.high[k]:.8g}",
                             f"{fits.half_width[k]:.6g}", int(fits.log_scale[k]),
                             int(fits.determined[k]), f"{fits.range_p[k]:.4g}", fits.used])
            print(f"{run_dir.name} {law_name}: {fits} ({time.monotonic() - start:.0f} s)",
                  flush=True)
    return rows


def _spread_row(eps, law_name, name, values, taps):
    """The realizations' row of one parameter: median, 16-84 % band (B and tau in ln) and
    SurrogateFits' determination rule over realizations."""
    v = np.array([p[name] for p in values])
    log = name in ("B", "tau") and np.all(v > 0)
    scaled = np.log(v) if log else v
    lo, mid, hi = np.percentile(scaled, BAND_PERCENTILES)
    back = np.exp if log else float
    half = (hi - lo) / 2.0
    limit = np.log(DETERMINED_FACTOR) if log else RELATIVE_ERROR_LIMIT * abs(mid)
    return ["realizations", eps, law_name, taps, name, f"{float(back(mid)):.8g}",
            f"{float(back(lo)):.8g}", f"{float(back(hi)):.8g}", f"{half:.6g}", int(log),
            int(half <= limit), "nan", len(values)]


def realization_rows(early_rows):
    """Per eps of early_taps.csv and law: the spread of the fits over the realizations."""
    curves = {}
    for r in early_rows:
        curves.setdefault(float(r["eps"]), {}).setdefault(int(r["seed"]), []).append(r)
    rows = []
    for eps, by_seed in sorted(curves.items()):
        for law_name, column in FIT_LAWS:
            values = []
            for seed_rows in by_seed.values():
                t = np.array([float(r["t"]) for r in seed_rows])
                y = np.array([float(r[column]) for r in seed_rows])
                keep = t >= 1
                values.append(law(law_name).fit(t[keep], y[keep]).params)
            rows += [_spread_row(eps, law_name, k, values, int(t.max()))
                     for k in law(law_name).names]
            print(f"realizations eps {eps:g} {law_name}: {len(values)} fits", flush=True)
    return rows


def measure(args):
    rows = run_rows(args.campaign, args.surrogates, args.seed)
    early = args.out / EARLY_CSV
    if early.is_file():
        rows += realization_rows(load_early(early))
    save(args.out / CSV, rows)


save, load = csv_schema(HEADER)


def render(path, seed_rows=None):
    rows = load(path)
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
             "its half width is at most the value), and the range test's p-value:", ""]
    table = []
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
        table.append([name, f"{eps:g}", law.replace('eq', 'eq. '), taps, fits, '; '.join(cells)])
    lines += list_table(["source", "eps", "law", "taps", "fits",
                         "parameters (value, band, determined?, range p)"], table)
    b_rows = [(key, r) for key, group in groups.items() for r in group
              if r["parameter"] == "B" and key[1] == "eq3"]
    runs = [r for key, r in b_rows if not key[0]]
    realized = [r for key, r in b_rows if key[0]]
    lines += ["", "A row without a range p: a range fit of the run itself sits on the edge of "
              "(B, tau)'s allowed range, where the parameters are not defined. "
              f"Eq. 3's B is undetermined in {sum(r['determined'] != '1' for r in runs)} of "
              f"{len(runs)} campaign runs and at {sum(r['determined'] != '1' for r in realized)}"
              f" of {len(realized)} eps over the realizations of the first taps."]
    return lines + surrogates_against_seeds(b_rows, seed_rows or []) + [""]


def surrogates_against_seeds(b_rows, seed_rows):
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

