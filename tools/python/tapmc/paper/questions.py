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
"""

from __future__ import annotations

import csv
import math
from collections import defaultdict
from pathlib import Path

import numpy as np

from .claims import fmt, t_quantile

FOLDER = "questions"
#: share of the first-tap drop at eta = 1e-7 that must remain at the tightest eta for the
#: drop to be called a property of the model rather than of the stopping rule.
MODEL_EFFECT_SHARE = 0.5


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


def render_section(folder, figures=None):
    """The rst lines of the section, or [] when ``folder`` holds none of the CSVs.
    ``figures``: name -> tapmc.paper.claims.FigureData of the same report (Fig. 3's k)."""
    folder = Path(folder)
    parts = []
    if (folder / "first_tap.csv").is_file():
        parts += _first_tap(folder / "first_tap.csv")
    if (folder / "noise_floor.csv").is_file():
        parts += _noise_floor(folder / "noise_floor.csv", (figures or {}).get("fig3"))
    if (folder / "spectral_window.csv").is_file():
        parts += _spectral_window(folder / "spectral_window.csv")
    if not parts:
        return []
    title = "Questions settled by measurement"
    return [title, "-" * len(title), "",
            "Measured by ``bench/paper_questions.py`` (``first-tap``, ``noise-floor``, "
            "``spectral-window``), whose "
            "CSVs are in ``validation/questions/``; the text below is computed from them.", ""] \
        + parts


__all__ = ["render_section", "FOLDER"]
