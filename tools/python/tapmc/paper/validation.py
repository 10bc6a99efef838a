# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The validation report (``tapmc-paper report``): the numbers of Philippe & Bideau next to
TAPMC's, computed from a campaign, written as ``validation.rst`` with the figures embedded.

Every verdict is computed from the numbers by the rule printed next to it (:data:`RULES`);
nothing is written by hand. A TAPMC number is the mean over seeds with its standard error
(sem); the paper gives no error bars, so a value "agrees" with a paper number when the two
differ by less than ``2 sem`` plus half a unit of the paper's last printed digit.
"""

from __future__ import annotations

import json
import math
import shutil
from pathlib import Path

import numpy as np

from . import FIGURES
from . import _plotting as P
from . import _runs

#: the paper's numbers (sections III-IV), with the rule used to compare.
PAPER = {
    "phi_initial": 0.584,      # initial <Phi^c>, P.B.C. (section IV.B, Fig. 9)
    "phi_tapped": 0.606,       # <Phi^c> after 4000 taps, P.B.C. (section IV.B, Fig. 9)
    "bell_range": (0.1, 0.2),  # sqrt(eps) of the steady-state maximum (section III.B)
    "slope_range": (1.0, 1.5),  # |log-log slope| of the power spectrum of <Z> (section III.A)
    "xi_T": P.XI_T,            # smallest pore: the tetrahedral site (section IV.B)
}
#: half a unit of the last digit of the paper's packing fractions (58.4 %, 60.6 %).
PAPER_ROUNDING = 0.0005
#: xi_min "equals" xi_T when no pore is smaller (beyond the dumps' rounding) and the smallest
#: pore lies within this distance above xi_T (one bin of tapmc-pores' default histogram).
XI_MIN_TOLERANCE = 0.01
#: P0 "does not distinguish" the initial and the tapped packings when the curves differ by less
#: than this everywhere (absolute probability).
P0_TOLERANCE = 0.02

RULES = {
    "value": "agrees when |TAPMC - paper| < 2 sem + 0.05 % (half a unit of the paper's last "
             "digit)",
    "range": "agrees when the value, within 2 sem, falls in the paper's range",
    "sign": "agrees when the sign is the paper's and the value is more than 2 sem from 0",
    "zero": "agrees when the value is within 2 sem of 0",
    "less": "agrees when the first value is smaller than the second by more than 2 sem of "
            "the difference, disagrees when larger by more than that",
    "bound": "agrees when the number is below the bound given in the verdict",
    "xi": f"agrees when no pore is below xi_T (beyond 1e-3) and xi_min - xi_T <= "
          f"{XI_MIN_TOLERANCE}",
}

FIG_DIR = "validation"


def _fmt(value, err=None, pct=False, digits=3):
    if value is None or not np.isfinite(value):
        return "n/a"
    if pct:
        if err is None or not np.isfinite(err):
            return f"{100 * value:.2f} %"
        return f"{100 * value:.2f} ± {100 * err:.2f} %"
    if err is None or not np.isfinite(err):
        return f"{value:.{digits}g}"
    return f"{value:.{digits}g} ± {err:.2g}"


def _sem(err):
    return 0.0 if err is None or not np.isfinite(err) else float(err)


def verdict_value(value, err, paper):
    if not np.isfinite(value):
        return "not measured"
    ok = abs(value - paper) < 2 * _sem(err) + PAPER_ROUNDING
    return "agrees" if ok else "disagrees"


def verdict_range(value, err, lo, hi):
    if not np.isfinite(value):
        return "not measured"
    s = 2 * _sem(err)
    return "agrees" if (value + s >= lo and value - s <= hi) else "disagrees"


def verdict_sign(value, err, sign):
    if not np.isfinite(value):
        return "not measured"
    if abs(value) <= 2 * _sem(err):
        return "undecided (|value| < 2 sem)"
    return "agrees" if np.sign(value) == sign else "disagrees"


def verdict_zero(value, err):
    if not np.isfinite(value):
        return "not measured"
    return "agrees" if abs(value) <= 2 * _sem(err) else "disagrees"


def verdict_less(a, b, sa=None, sb=None):
    if not (np.isfinite(a) and np.isfinite(b)):
        return "not measured"
    margin = 2 * math.hypot(_sem(sa), _sem(sb))
    if abs(b - a) <= margin:
        return "undecided (difference < 2 sem)"
    return "agrees" if a < b else "disagrees"


class _Csv:
    """Access to one figure CSV: ``row(panel, series)`` -> (x, mean, sem, n) arrays."""

    def __init__(self, path):
        self.table = P.read_table(path)

    def get(self, panel, series):
        d = self.table.get((panel, series))
        if d is None:
            return None
        return d["x"], d["mean"], d["sem"], d["n"]

    def param(self, series):
        d = self.get("params", series)
        if d is None:
            return np.nan, np.nan, 0
        return float(d[1][0]), float(d[2][0]), int(d[3][0])

    def series(self, panel):
        return [s for (p, s) in self.table if p == panel]


#: the campaign's facts the report needs beyond the figure CSVs, kept next to them so that the
#: report can be rewritten from committed data alone (:func:`regenerate`).
SUMMARY_FILE = "report.json"
#: Scale fields listed for a scale that is no preset.
_SCALE_KEYS = ("taps", "steady_last", "fig2_eps", "steady sqrt(eps)", "ramp_sqrt0",
               "ramp_dsqrt", "ramp_levels", "ramp_taps_per_level", "ageing_eps",
               "ageing_taps", "ageing_waiting_times", "profile_eps", "pore_eps", "dump_times")


def campaign_summary(campaign):
    """What the report says of the campaign itself (a JSON-ready dict): its scale, sizes,
    runs, taps, seeds, eta, and the initial <Phi^c> of its P.B.C. packings."""
    from .scales import SCALES

    specs = campaign.runs
    scale = _runs.campaign_scale(campaign)
    preset = scale is not None and scale.name in SCALES and SCALES[scale.name] == scale
    fields = None
    if scale is not None and not preset:
        fields = scale.as_dict()
        fields["steady sqrt(eps)"] = tuple(round(math.sqrt(e), 4) for e in scale.steady_eps)
        fields = {k: fields[k] for k in _SCALE_KEYS}
    return {
        "scale": None if scale is None else scale.name,
        "preset": preset,
        "fields": fields,
        "sizes": sorted({(int(s.variables["N"]), float(s.variables["L"])) for s in specs
                         if "N" in s.variables}),
        "runs": len(specs),
        "taps": sorted({int(s.taps) for s in specs if s.taps is not None}),
        "seeds": len({s.seed for s in specs}),
        "eta": sorted({float(s.variables["eta"]) for s in specs if "eta" in s.variables}),
        "initial_phi_c": list(_initial_phi(campaign)),
    }


def describe_scale(summary):
    """The scale that was run, from :func:`campaign_summary`."""
    size = ", ".join(f"N = {n} spheres in a {l:g}R x {l:g}R box" for n, l in summary["sizes"])
    if summary["scale"] is None:
        name = "a scale of no preset"
    elif summary["preset"]:
        name = f"the ``{summary['scale']}`` preset"
    else:
        name = f"the scale ``{summary['scale']}``"
    text = (f"Scale: {name} ({size}; {summary['runs']} runs of "
            f"{', '.join(map(str, summary['taps']))} taps; {summary['seeds']} seeds per point; "
            f"redeposition threshold eta = {', '.join(f'{e:g}' for e in summary['eta'])}). "
            "The paper used N = 4096, L = 32R, 4000 taps and 10 realizations.")
    if summary["fields"]:
        fields = {k: tuple(v) if isinstance(v, list) else v
                  for k, v in summary["fields"].items()}
        text += (" Its fields (a ``Scale.replace`` of the quick preset, recorded in the "
                 "campaign's ``scale.json``): "
                 + "; ".join(f"{k} = {fields[k]}" for k in _SCALE_KEYS) + ".")
    return text


def _initial_phi(campaign):
    """<Phi^c> of the initial P.B.C. packings, one per packing seed: (mean, sem, n)."""
    per_seed = {}
    for spec in _runs.select(campaign, "const_", bc="pbc"):
        if spec.seed not in per_seed:
            per_seed[spec.seed] = [float(_runs.taps_table(campaign, spec)["phi_c"][0])]
    if not per_seed:
        return np.nan, np.nan, 0
    m, s, n = P.seed_stats(list(per_seed.values()))
    return float(m[0]), float(s[0]), int(n[0])


def _collect(drawn, out_dir):
    """Move (or draw) the figure files into out_dir/validation; returns name -> (png, csv)
    relative to out_dir."""
    target = Path(out_dir) / FIG_DIR
    target.mkdir(parents=True, exist_ok=True)
    out = {}
    for name, paths in drawn.items():
        moved = []
        for path in paths:
            path = Path(path)
            dest = target / path.name
            if path.resolve() != dest.resolve():
                shutil.move(str(path), dest)
            moved.append(dest)
        out[name] = tuple(moved)
    return out


def _initial_phi_row(summary):
    """Initial <Phi^c> of the P.B.C. packings against the paper's 58.4 %."""
    m, s, _ = (np.nan if v is None else v for v in summary["initial_phi_c"])
    return ("Initial <Phi^c> (P.B.C.)", "58.4 %", _fmt(m, s, pct=True),
            verdict_value(m, s, PAPER["phi_initial"]), "value")


def _tapped_phi(c):
    """Fig. 9 runs: <Phi^c> after the taps against the paper's 60.6 %."""
    m, s, _ = c.param("phi_c_final")
    return [("<Phi^c> after the taps (P.B.C., Fig. 9 runs)", "60.6 % (4000 taps)",
             _fmt(m, s, pct=True), verdict_value(m, s, PAPER["phi_tapped"]), "value")], None


def _steady_state(c):
    """Fig. 4: the highest steady state, where it lies, the bell shape and the hysteresis."""
    rows = []
    m, s, _ = c.param("phi_c_max")
    rows.append(("Highest steady-state <Phi^c> (Fig. 4 squares)", "60.6 % (after 4000 taps)",
                 _fmt(m, s, pct=True), verdict_value(m, s, PAPER["phi_tapped"]), "value"))
    m, s, _ = c.param("sqrt_eps_max")
    lo, hi = PAPER["bell_range"]
    rows.append(("sqrt(eps) of the steady-state maximum (bell)", "between 0.1 and 0.2",
                 _fmt(m, s), verdict_range(m, s, lo, hi), "range"))
    steady = c.get("a", "steady")
    if steady is not None and len(steady[0]) >= 3:
        mean, sem = steady[1], steady[2]
        i = int(np.nanargmax(mean))
        rows.append(("Bell: steady state at the largest sqrt(eps) below the maximum",
                     "lower (bell shape)", f"{_fmt(mean[-1], sem[-1], pct=True)} vs "
                     f"{_fmt(mean[i], sem[i], pct=True)}",
                     verdict_less(mean[-1], mean[i], sem[-1], sem[i]), "less"))
    note, row = _hysteresis(c)
    if row is not None:
        rows.append(row)
    return rows, note


def _fluctuations(c):
    """Fig. 3: spectral slopes of <Z> and sigma_<Z> proportional to sqrt(eps)."""
    rows = []
    slopes = [(float(series.split("=")[1].split(":")[0]), *c.param(series))
              for series in c.series("params") if series.endswith(":slope")]
    lo, hi = PAPER["slope_range"]
    for eps, m, s, _ in slopes:
        rows.append((f"Spectral slope of <Z> (eps = {eps:g})", "-1 to -1.5", _fmt(m, s),
                     verdict_range(-m, s, lo, hi), "range"))
    m, s, _ = c.param("intercept")
    k, ks, _ = c.param("k")
    rows.append(("sigma_<Z> = k sqrt(eps): intercept of a free line", "0 (proportional)",
                 _fmt(m, s), verdict_zero(m, s), "zero"))
    note = (f"Proportional fit: k = {_fmt(k, ks)}; reduced chi2 "
            f"{_fmt(c.param('k_reduced_chi2')[0])}.")
    return rows, note


def _vertical_gradient(c):
    """Fig. 6: the sign of the vertical gradient alpha after the taps (eq. 7)."""
    m, s, _ = c.param("final:alpha")
    row = ("Vertical gradient alpha after the taps (Phi = Phi0 - alpha z/R)",
           "alpha > 0 (density decreasing upwards)", _fmt(m, s), verdict_sign(m, s, +1), "sign")
    mi, si, _ = c.param("initial:alpha")
    lo, _, _ = c.param("window_lo")
    hi, _, _ = c.param("window_hi")
    note = (f"Gradient window {lo:.3g} <= z/R <= {hi:.3g}; initial packing: "
            f"alpha = {_fmt(mi, si)}.")
    return [row], note


def _central_lateral(c):
    """Fig. 8: the centre of an F.B.C. packing compacts less than its walls, per eps."""
    rows = []
    eps_list = sorted({float(x.split("=")[1].split(":")[0]) for x in c.series("params")})
    for eps in eps_list:
        lat = c.param(f"eps={P.fmt_eps(eps)}:final_lateral")
        cen = c.param(f"eps={P.fmt_eps(eps)}:final_central")
        rows.append((f"delta Phi_central < delta Phi_lateral (F.B.C., eps = {eps:g})",
                     "central smaller", f"{_fmt(cen[0], cen[1])} vs {_fmt(lat[0], lat[1])}",
                     verdict_less(cen[0], lat[0], cen[1], lat[1]), "less"))
    return rows, None


def _bounded(value):
    """Verdict of a number that must stay below P0_TOLERANCE."""
    return ("agrees" if value < P0_TOLERANCE else "disagrees") + f" (bound {P0_TOLERANCE})"


def _contact_probability(c):
    """Fig. 9: P0 barely changes with the taps and follows Percus-Yevick."""
    d_if, _, _ = c.param("max_abs_diff_initial_final")
    d_py, _, _ = c.param("max_abs_diff_final_py")
    return [("max |P0(initial) - P0(tapped)|", "no significant difference", _fmt(d_if),
             _bounded(d_if), "bound"),
            ("max |P0(tapped) - Percus-Yevick|", "good agreement", _fmt(d_py),
             _bounded(d_py), "bound")], None


def _pores(c):
    """Fig. 10: the smallest pore is the tetrahedral site; the taps shrink the large pores."""
    rows = []
    d = c.get("params", "xi_min")
    if d is not None:
        i = int(np.argmin(d[1]))
        m, s = float(d[1][i]), float(d[2][i])
        ok = m >= PAPER["xi_T"] - 1e-3 and m - PAPER["xi_T"] <= XI_MIN_TOLERANCE
        rows.append(("Smallest pore xi_min", f"xi_T = {PAPER['xi_T']:.4f}",
                     _fmt(m, s, digits=4), "agrees" if ok else "disagrees", "xi"))
    small, _, _ = c.param("small_change")
    large, _, _ = c.param("large_change")
    rows.append(("Change of xi^3 P(xi), small pores [xi_T, xi_O] vs large (> xi_O)",
                 "small pores invariant, tail shrinks", f"{_fmt(small)} vs {_fmt(large)}",
                 verdict_less(small, large), "less"))
    nu = c.get("params", "nu")
    if nu is not None:
        rows.append(("nu = <xi^3> from t = 0 to the last dump", "decreases",
                     f"{_fmt(nu[1][0], nu[2][0], digits=4)} -> "
                     f"{_fmt(nu[1][-1], nu[2][-1], digits=4)}",
                     verdict_less(nu[1][-1], nu[1][0], nu[2][-1], nu[2][0]), "less"))
    return rows, None


def _ageing(c):
    """Fig. 5: how well one eq. 6 collapses every waiting time (a note, no verdict)."""
    chi, _, det = c.param("collapse:reduced_chi2")
    return [], (f"One eq. 6 for all waiting times: reduced chi2 {_fmt(chi)}"
                f"{'' if det else ' (parameters not determined)'}.")


def _dynamics(c):
    """Fig. 2: whether Phi_b increased (rows) and the eq. 3 parameters per eps (note)."""
    rows, lines = [], []
    eps_list = sorted({float(s.split("=")[1].split(":")[0]) for s in c.series("params")})
    for eps in eps_list:
        tag = f"eps={P.fmt_eps(eps)}"
        params = {name: c.param(f"{tag}:{name}") for name in ("X_inf", "dX_inf", "B", "tau")}
        chi = c.param(f"{tag}:reduced_chi2")[0]
        determined = all(p[2] for p in params.values())
        lines.append(f"eps = {eps:g}: X_inf = {_fmt(*params['X_inf'][:2], digits=4)}, "
                     f"dX_inf = {_fmt(*params['dX_inf'][:2])}, B = {_fmt(*params['B'][:2])}, "
                     f"tau = {_fmt(*params['tau'][:2])}; reduced chi2 {_fmt(chi)}; "
                     f"{'determined' if determined else 'parameters not determined'}")
        data = c.get("a", tag)
        if data is None:
            continue
        t, mean, sem, _ = data
        q = max(len(t) // 4, 1)
        gain = float(np.mean(mean[-q:]) - mean[0])
        err = float(np.sqrt(np.nanmean(sem[-q:]) ** 2 + np.nan_to_num(sem[0]) ** 2))
        rows.append((f"Phi_b(end) - Phi_b(0), F.B.C., eps = {eps:g}", "> 0 (compaction)",
                     _fmt(gain, err), verdict_sign(gain, err, +1), "sign", (gain, err)))
    gains = list(rows)
    if len(gains) >= 2:
        (g_lo, e_lo), (g_hi, e_hi) = gains[0][5], gains[-1][5]
        rows.append((f"Compaction slower at small eps: gain at eps = {eps_list[0]:g} vs "
                     f"{eps_list[-1]:g}", "smaller at small eps",
                     f"{_fmt(g_lo, e_lo)} vs {_fmt(g_hi, e_hi)}",
                     verdict_less(g_lo, g_hi, e_lo, e_hi), "less"))
    return [r[:5] for r in rows], "\n".join(f"* {line}" for line in lines)


def _hysteresis(c):
    """(note, row) comparing the ramp's decreasing branch with its first increase."""
    up1, down = c.get("a", "up1"), c.get("a", "down")
    if up1 is None or down is None:
        return "No ramp run in this campaign.", None
    diffs, errs = [], []
    for x, m, s in zip(down[0], down[1], down[2]):
        match = np.isclose(up1[0], x)
        if np.any(match):
            diffs.append(m - up1[1][match][0])
            errs.append(math.hypot(_sem(s), _sem(up1[2][match][0])))
    if not diffs:
        return "The ramp's branches share no sqrt(eps).", None
    mean = float(np.mean(diffs))
    err = float(math.sqrt(np.sum(np.square(errs))) / len(errs))
    note = (f"Ramp: the decreasing branch lies above the first increase at "
            f"{sum(d > 0 for d in diffs)} of {len(diffs)} common sqrt(eps).")
    row = ("Ramp: decreasing branch minus first increase (mean over common sqrt(eps))",
           "> 0 (hysteresis)", _fmt(mean, err), verdict_sign(mean, err, +1), "sign")
    return note, row


#: (figure, comparison) in the order of the summary table; a comparison takes the figure's
#: CSV and returns (rows, note or None).
_COMPARISONS = (("fig9", _tapped_phi), ("fig4", _steady_state), ("fig3", _fluctuations),
                ("fig2", _dynamics), ("fig6", _vertical_gradient),
                ("fig8", _central_lateral), ("fig9", _contact_probability), ("fig10", _pores),
                ("fig5", _ageing))


def _rows_and_sections(summary, files):
    """The summary table rows (quantity, paper, TAPMC, verdict) and per-figure text."""
    csv = {name: _Csv(paths[1]) for name, paths in files.items()}
    rows, notes = [_initial_phi_row(summary)], {}
    for name, compare in _COMPARISONS:
        if name not in csv:
            continue
        new_rows, note = compare(csv[name])
        rows += new_rows
        if note is not None:
            notes[name] = note
    return rows, notes


CAPTIONS = {
    "fig2": "Phi_b against taps (F.B.C.), logarithmic (top) and linear (bottom) time; dotted: "
            "eq. 3 fits.",
    "fig3": "Power spectrum of <Z> - <Z>_SS (top) and sigma_<Z> against sqrt(eps) (bottom).",
    "fig4": "Steady-state <Phi^c> against sqrt(eps) (squares) and the ramp up, down and up "
            "again (open symbols).",
    "fig5": "A(t, t_W) for several waiting times (top) and their collapse on eq. 6 (bottom).",
    "fig6": "Vertical profiles of the initial packing and after the taps, with eq. 7 fits.",
    "fig7": "Transversal profiles of the initial packing and after the taps; dotted: the 7R "
            "frontiers.",
    "fig8": "delta Phi_lateral (top) and delta Phi_central (bottom) against taps.",
    "fig9": "P0(sigma) of the tapped packing (circles), the initial packing (thin line) and "
            "Percus-Yevick (thick line).",
    "fig10": "rho_v(xi) (top) and rho_v(v) (bottom) at several tap counts; T and O: tetrahedral "
             "and octahedral sites.",
}


def _rst_table(rows):
    lines = [".. list-table::", "   :header-rows: 1", "   :widths: 40 20 25 15", "",
             "   * - Quantity", "     - Paper", "     - TAPMC (mean ± sem over seeds)",
             "     - Verdict"]
    for quantity, paper, tapmc, verdict, rule in rows:
        lines += [f"   * - {quantity}", f"     - {paper}", f"     - {tapmc}",
                  f"     - {verdict} [{rule}]"]
    used = []
    for row in rows:
        if row[4] not in used:
            used.append(row[4])
    lines += ["", "Rules of the verdicts (sem: standard error over seeds):", ""]
    lines += [f"* [{key}] {RULES[key]}" for key in used]
    return lines


def render(summary, files):
    """The text of validation.rst from the campaign summary and the figure files (name ->
    (png, csv))."""
    rows, notes = _rows_and_sections(summary, files)
    undecided = sum(1 for r in rows if r[3].startswith("undecided"))
    agree = sum(1 for r in rows if r[3].startswith("agrees"))
    lines = [".. TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.", "",
             "Validation against Philippe & Bideau", "=" * 36, "",
             "This page is written by ``tapmc-paper report`` from one campaign: every number "
             "below is computed from the campaign's runs and every verdict from the numbers, "
             "by the rule stated next to it. TAPMC values are means over seeds with their "
             "standard errors (sem); the paper gives single runs without error bars.", "",
             describe_scale(summary), "",
             f"Summary: {agree} of {len(rows)} comparisons agree with the paper; "
             f"{undecided} are undecided at this statistics.", ""]
    lines += _rst_table(rows)
    lines += ["", f"The numbers come from the figure CSVs and ``{FIG_DIR}/{SUMMARY_FILE}`` (the "
              "campaign's scale and initial packings), committed with this page; rewrite it "
              "from them (a test checks that this gives the committed page):", "",
              ".. snippet: skip rewrites this page; tests/python/test_validation_report.py "
              "checks that it gives the committed text", "",
              ".. code-block:: sh", "",
              "   build/tapmc-paper report --from-data --out doc", "",
              "or run a campaign and draw everything anew (``--full`` for the paper's scale, "
              "hours to days):", "",
              ".. snippet: skip runs a whole campaign",
              "", ".. code-block:: sh", "",
              "   build/tapmc-paper report --quick --campaign tapmc-paper-quick --out doc", ""]
    for name in FIGURES:
        if name not in files:
            continue
        png, csv = files[name]
        number = name[3:]
        title = f"Fig. {number}"
        lines += [title, "-" * len(title), "", CAPTIONS.get(name, ""), "",
                  f".. image:: {FIG_DIR}/{Path(png).name}", f"   :alt: Fig. {number}", "",
                  f"Data: ``{FIG_DIR}/{Path(csv).name}`` (columns panel, series, x, mean, sem, "
                  "n).", ""]
        if name in notes:
            lines += [notes[name], ""]
    return "\n".join(lines).rstrip() + "\n"


def write_rst(summary, files, out_dir):
    """Write out_dir/validation.rst (:func:`render`) and the summary as
    out_dir/validation/report.json; returns the path of the rst."""
    out_dir = Path(out_dir)
    (out_dir / FIG_DIR).mkdir(parents=True, exist_ok=True)
    (out_dir / FIG_DIR / SUMMARY_FILE).write_text(json.dumps(summary, indent=1) + "\n")
    path = out_dir / "validation.rst"
    path.write_text(render(summary, files))
    return path


def committed_inputs(out_dir):
    """(summary, files) of a report already written to out_dir: report.json and the figure
    PNG/CSV pairs in out_dir/validation. Raises FileNotFoundError naming what is missing."""
    folder = Path(out_dir) / FIG_DIR
    path = folder / SUMMARY_FILE
    if not path.is_file():
        raise FileNotFoundError(f"{path}: no report summary (written by 'tapmc-paper report' "
                                "from a campaign)")
    summary = json.loads(path.read_text())
    files = {name: (folder / f"{name}.png", folder / f"{name}.csv") for name in FIGURES
             if (folder / f"{name}.csv").is_file()}
    if not files:
        raise FileNotFoundError(f"{folder}: no figure CSV (fig2.csv ... fig10.csv)")
    return summary, files


def regenerate(out_dir):
    """Rewrite out_dir/validation.rst from the committed data alone (report.json and the
    figure CSVs in out_dir/validation); nothing is run or drawn. Returns its path."""
    summary, files = committed_inputs(out_dir)
    path = Path(out_dir) / "validation.rst"
    path.write_text(render(summary, files))
    return path





def report(campaign, out_dir, drawn=None):
    """Write ``out_dir/validation.rst`` and the figures it embeds under ``out_dir/validation/``.

    ``drawn``: name -> (png, csv) of figures already drawn (moved into ``out_dir/validation``);
    the figures not given are drawn here. Returns the path of the rst."""
    from importlib import import_module

    out_dir = Path(out_dir)
    drawn = dict(drawn or {})
    target = out_dir / FIG_DIR
    for name in FIGURES:
        if name in drawn:
            continue
        module = import_module(f"{__package__}.{name}")
        try:
            drawn[name] = module.draw(campaign, target)
        except ValueError:
            continue  # this campaign has no run of that figure
    files = _collect(drawn, out_dir)
    return write_rst(campaign_summary(campaign), files, out_dir)


__all__ = ["report", "regenerate", "render", "write_rst", "campaign_summary",
           "committed_inputs", "PAPER", "RULES"]
