# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Synthetic figure data for the claims' tests (tests/python/test_claims*.py): tables of each
figure with known answers, the report built from them, and the controls on which every
statistic of the register must agree and must not."""

import dataclasses
import math
import os
import sys
from pathlib import Path

import numpy as np
import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc.paper import claims  # noqa: E402
from tapmc.paper import _plotting as P  # noqa: E402
from tapmc.paper.fig10 import EVERY_DUMP_STATISTICS  # noqa: E402
from tapmc.laws import ProfileLaw  # noqa: E402
from tapmc.fluctuations import binned_periodogram_layout  # noqa: E402
from tapmc.pores import percus_yevick_p0  # noqa: E402

REGISTER = claims.load_register()
BY_ID = {c.id: c for c in REGISTER}
SEEDS = 5  # realizations behind the synthetic means (dof = 4)


class Table:
    """A figure's data built in memory, as tapmc.paper._plotting.read_table returns it."""

    def __init__(self):
        self.table = {}

    def add(self, panel, series, x, mean, sem=None, n=SEEDS):
        x = np.atleast_1d(np.asarray(x, float))
        mean = np.broadcast_to(np.asarray(mean, float), x.shape).copy()
        sem = np.full(x.shape, np.nan) if sem is None else \
            np.broadcast_to(np.asarray(sem, float), x.shape).copy()
        self.table[(panel, series)] = {"x": x, "mean": mean, "sem": sem,
                                       "n": np.full(x.shape, n)}
        return self

    def param(self, series, value, sem=None, n=SEEDS, x=0.0):
        return self.add("params", series, x, value, sem, n)

    def data(self):
        return claims.FigureData(self.table)


def report(summary=None, **figures):
    base = {"sizes": [[4096, 32.0]], "eta": [1e-7], "preset": True, "scale": "full",
            "fields": None, "initial_phi_c": [0.584, 0.001, SEEDS]}
    base.update(summary or {})
    return claims.ReportData(base, {k: COMPLETE_ROWS.get(k, lambda tab: tab)(v).data()
                                    for k, v in figures.items()})


T = np.unique(np.round(np.geomspace(1, 4000, 120)))


T = np.concatenate([[0.0], T])


def fig2(curves):
    tab = Table()
    for eps, y in curves.items():
        tab.add("a", f"eps={P.fmt_eps(eps)}", T, y, 0.0005)
        tab.param(f"eps={P.fmt_eps(eps)}:reduced_chi2", 1.0, x=eps)
    return tab


def inverse_log(t, x_inf=0.62, dx=0.04, b=1.0, tau=10.0):
    return x_inf - dx / (1 + b * np.log1p(t / tau))


RISING = inverse_log(T)


def fig3(spectra=None, slope=-1.2, intercept=0.001, intercept_sem=0.002,
         intercept_detrended=0.001):
    tab = Table()
    # the bins of a 1000-tap window's periodogram: the layout Fig. 3's spectra have
    f = binned_periodogram_layout(1000)[0]
    for eps, scale in (spectra or {}).items():
        tab.add("a", f"eps={P.fmt_eps(eps)}", f, scale(f), 0.02 * scale(f))
    tab.param("eps=0.01:slope", slope, 0.05, x=0.01)
    tab.param("intercept", intercept, intercept_sem)
    tab.param("intercept_detrended", intercept_detrended, intercept_sem)
    for series in ("sigma_Z", "sigma_Z_detrended"):
        tab.add("b", series, [0.05, 0.1, 0.15, 0.2, 0.3], [0.05, 0.1, 0.15, 0.2, 0.3], 0.003)
    return tab


X = np.round(np.arange(0.05, 0.40, 0.025), 4)


def fig4(steady, up1=None, down=None, up2=None):
    tab = Table().add("a", "steady", X, steady, 0.001)
    for name, y in (("up1", up1), ("down", down), ("up2", up2)):
        if y is not None:
            tab.add("a", name, X, y, 0.001)
    return tab


BELL = 0.60 - 2.0 * (X - 0.15) ** 2


def ramp_pores(gap, slope, sem=0.001, levels=(0.025, 0.05, 0.075, 0.1, 0.125),
               run="ramp_pbc_s1"):
    """tapmc-paper question ramp-pores rows of a ramp ``run`` beyond (sqrt eps)*: nu on the
    first increase 0.1 - 0.05 sqrt(eps), the decrease ``gap`` away at 0.1 with ``slope``."""
    rows = []
    for branch, nus in ((0, [0.1 - 0.05 * x for x in levels]),
                        (1, [0.1 + gap + slope * (x - 0.1) for x in levels])):
        rows += [{"run": run, "branch": str(branch), "sqrt_eps": f"{x:g}",
                  "nu": f"{nu:.8f}", "nu_sem": f"{sem:g}"} for x, nu in zip(levels, nus)]
    # the ramp below (sqrt eps)* in the same table is not read for the ramp beyond's signs
    rows += [{"run": "ramplow_pbc_s1", "branch": str(b), "sqrt_eps": "0.05", "nu": "0.5",
              "nu_sem": f"{sem:g}"} for b in (0, 1)]
    return claims.ReportData(report().summary, {}, questions={"ramp_pores": rows})


def ramps_turning(down_changes, sem=0.0005, n=SEEDS):
    """Fig. 4 params of ramps turning at each sqrt(eps) of ``down_changes`` (top -> the
    decrease minus the top level), one CSV tag per ramp."""
    tab = fig4(BELL).param("critical_sqrt_eps", 0.15, None, 1)
    for tag, (top, change) in zip(FIG4_RAMP_TAGS, sorted(down_changes.items())):
        tab.param(f"{tag}:top_sqrt_eps", top, None, n)
        tab.param(f"{tag}:down_change", change, sem, n, x=top)
    return tab


def _critical(down_changes, **kw):
    (m,) = claims.critical_separation(report(fig4=ramps_turning(down_changes, **kw)),
                                      BY_ID["critical-sqrt-eps"])
    return m, str(claims.verdict(BY_ID["critical-sqrt-eps"], m))


def fig6_ramp(gap):
    """alpha at the end of the ramp's levels (Fig. 6 bottom, one seed): the decrease is the
    first increase plus ``gap`` and a level-to-level scatter of 5e-5."""
    alpha = 0.001 + 0.01 * X
    jitter = 5e-5 * (-1.0) ** np.arange(len(X))
    return (Table().add("b", "ramp:up1", X, alpha, 3e-4, 1)
            .add("b", "ramp:down", X, alpha + gap + jitter, 3e-4, 1))


def fig6_profile(departure=0.0):
    """Fig. 6's final profile (0.2R bins, errors 0.003) about its eq. 7 fit: wall layers one
    diameter apart decaying from the floor, which the smoothing over 2R removes, plus a smooth
    ``departure`` from eq. 7 over 10-16R that it keeps."""
    z = np.arange(0.1, 40.0, 0.2)
    params = {"Phi0": 0.59, "alpha": 0.0015, "beta": 2.0, "zb_star": 29.6}
    law = ProfileLaw.function(z, *params.values())
    layers = 0.05 * np.exp(-z / 4.0) * np.sin(np.pi * z)
    bump = departure * np.exp(-((z - 13.0) / 3.0) ** 2)
    above = z >= 5.0
    tab = (Table().add("a", "initial", z, law, 0.003)
           .add("a", "final", z, law + layers + bump, np.where(law > 1e-3, 0.003, 0.0))
           .add("a", "fit:final", z[above], law[above], None, n=0)
           .param("window_lo", 5.0, None).param("window_hi", 22.0, None))
    for name, value in params.items():
        tab.param(f"final:eq7_{name}", value, 1e-4, n=1)
    return tab


def fig7_profile(layering=0.05):
    """Fig. 7's transversal profile in a 32R box (0.2R bins): three layers 1.8R apart from
    each wall, peaks ``layering`` high, on a bulk of 0.58 with a scatter of 0.004 between
    its bins."""
    x = np.arange(0.1, 32.0, 0.2)
    d = np.minimum(x, 32.0 - x)
    peaks = sum(np.exp(-((d - centre) / 0.3) ** 2) for centre in (1.0, 2.8, 4.6))
    phi = 0.58 + layering * peaks + 0.004 * np.sin(7.3 * x)
    return (Table().add("a", "initial", x, phi, 0.005).add("a", "final", x, phi, 0.005)
            .param("frontier_lo", 7.0, None).param("frontier_hi", 25.0, None)
            .param("eps", 0.1, None))


#: the one-row params of Fig. 9's typed result (tapmc.paper.fig9.Fig9Result) besides its curves
FIG9_PARAMS = ("phi_initial", "phi_final", "phi_c_initial", "phi_c_final",
               "max_abs_diff_initial_final", "max_abs_diff_final_py")


def with_fig9_params(tab):
    """``tab`` with every param of Fig. 9's result, NaN (not measured) where it has none."""
    for name in FIG9_PARAMS:
        if ("params", name) not in tab.table:
            tab.param(name, math.nan, None, n=1)
    return tab


def fig9(diff=0.0, py_shift=0.0, initial_phi=None):
    """Fig. 9 of 5 seeds: P0 of the tapped packing at Phi 0.606 (Percus-Yevick's, shifted by
    ``py_shift``), the initial packing's the same plus ``diff`` or, with ``initial_phi``,
    Percus-Yevick's at that packing fraction."""
    sigma = np.linspace(0.0, 2.0, 60)
    final = percus_yevick_p0(sigma, 0.606) + py_shift
    tab = Table().add("a", "final", sigma, final, 0.0005)
    initial = final + diff if initial_phi is None else percus_yevick_p0(sigma, initial_phi)
    tab.add("a", "initial", sigma, initial, 0.0005)
    tab.add("a", "percus_yevick", sigma, percus_yevick_p0(sigma, 0.606), None, 1)
    tab.param("phi_initial", 0.584, 0.001).param("phi_final", 0.606, 0.001)
    tab.param("phi_c_initial", 0.584, 0.001).param("phi_c_final", 0.606, 0.001)
    return with_fig9_params(tab)


def one_run_fig9(steady, sem=0.0002, tap_sd=0.001):
    """Fig. 9 data of one seed: no sem over seeds, the steady state with its within-run error."""
    tab = fig9()
    tab.param("phi_c_initial", 0.584, None, n=1)
    tab.param("phi_c_steady", steady, sem, n=1).param("phi_c_tap_sd", tap_sd, None, n=1)
    return tab


XI = np.linspace(0.2, 0.7, 51)


def pore_curve(tail):
    quad = np.where((XI > P.XI_T) & (XI <= P.XI_O), 40 * (XI - P.XI_T) ** 2, 0.0)
    big = np.where(XI > P.XI_O, 40 * (P.XI_O - P.XI_T) ** 2 * np.exp(-(XI - P.XI_O) / tail), 0)
    return quad + big


def with_fig10_rows(tab):
    """``tab`` with every row of Fig. 10's typed result (tapmc.paper.fig10.Fig10Result): the
    distributions of each dump its params name (one NaN point where it has none), the
    statistics every dump has (NaN: not measured) and the shares' changes (NaN)."""
    steps = sorted({float(x) for (panel, _), d in tab.table.items() if panel == "params"
                    for x in d["x"]})
    for step in steps:
        for panel in ("a", "b"):
            if (panel, f"t={step:g}") not in tab.table:
                tab.add(panel, f"t={step:g}", [math.nan], [math.nan], None, n=1)
    for name in EVERY_DUMP_STATISTICS:
        if ("params", name) not in tab.table:
            tab.add("params", name, steps, [math.nan] * len(steps), None, n=1)
    for name in ("small_change", "large_change"):
        if ("params", name) not in tab.table:
            tab.param(name, math.nan, None, n=1, x=max(steps, default=0.0))
    return tab


def fig10(first=pore_curve(0.1), last=pore_curve(0.05), nu=(0.12, 0.10), tail_ratio=1.0,
          xi_min=0.226):
    tab = Table().add("a", "t=0", XI, first, 0.002).add("a", "t=4000", XI, last, 0.002)
    tab.add("params", "nu", [0, 4000], list(nu), 0.001)
    tab.add("params", "nu_tail", [0, 4000], [nu[0] * tail_ratio, nu[1] * tail_ratio], 0.001)
    tab.add("params", "xi_min", [0, 4000], [xi_min, xi_min], 0.0001)
    return with_fig10_rows(tab)


def fig8(central, lateral, paper_first_tap=None):
    """Fig. 8's zones at two eps, the runs from the walls' start or, with ``paper_first_tap``,
    from the paper's start."""
    tab = Table()
    for eps in (0.005, 0.1):
        tab.param(f"eps={P.fmt_eps(eps)}:final_central", central, 0.0005, x=eps)
        tab.param(f"eps={P.fmt_eps(eps)}:final_lateral", lateral, 0.0005, x=eps)
        if paper_first_tap is None:
            tab.add("a", f"eps={P.fmt_eps(eps)}", [0, 1, 2], [0, -0.003, -0.002], 0.0003)
        else:
            tab.add("a", f"paper:eps={P.fmt_eps(eps)}", [0, 1, 2],
                    [0, paper_first_tap, paper_first_tap], 0.0003)
    return with_fig8_rows(tab)


def with_fig8_rows(tab):
    """``tab`` with every row of Fig. 8's typed result (tapmc.paper.fig8.Fig8Result): the
    lateral (a) and central (b) curves of each eps its params name (one NaN point where it has
    none), from the start its curves name."""
    prefix = "paper:" if any(series.startswith("paper:") for panel, series in tab.table
                             if panel == "a") else ""
    labels = {series.split(":")[0] for panel, series in tab.table if panel == "params"}
    labels |= {series[len(prefix):] for panel, series in tab.table if panel == "a"}
    for label in sorted(labels, key=lambda label: float(label[len("eps="):])):
        for panel in ("a", "b"):
            if (panel, prefix + label) not in tab.table:
                tab.add(panel, prefix + label, [math.nan], [math.nan], None, n=1)
    return tab


def with_fig3_rows(tab):
    """``tab`` with every row of Fig. 3's typed result (tapmc.paper.fig3.Fig3Result): a slope
    for each spectrum and a spectrum for each slope, and sigma_<Z> (NaN where it has none)."""
    spectra = {series for panel, series in tab.table if panel == "a"}
    slopes = {series[:-len(":slope")] for panel, series in tab.table
              if panel == "params" and series.endswith(":slope")}
    for label in sorted(spectra - slopes):
        tab.param(f"{label}:slope", math.nan, None, n=1, x=float(label[len("eps="):]))
    for label in sorted(slopes - spectra):
        tab.add("a", label, [math.nan], [math.nan], None, n=1)
    if ("b", "sigma_Z") not in tab.table:
        tab.add("b", "sigma_Z", [math.nan], [math.nan], None, n=1)
    return tab


def with_fig2_rows(tab):
    """``tab`` with the row of Fig. 2's typed result (tapmc.paper.fig2.Fig2Result) that gives
    each curve its eps: the fit's reduced chi2 of every curve of panel a (eq. 3) and c (eq. 4),
    NaN where the table has none."""
    for (panel, series) in list(tab.table):
        prefix = {"a": "", "c": "Z:"}.get(panel)
        if prefix is None or not series.startswith("eps=") or ":" in series:
            continue
        if ("params", f"{series}:{prefix}reduced_chi2") not in tab.table:
            tab.param(f"{series}:{prefix}reduced_chi2", math.nan, None, n=0,
                      x=float(series[len("eps="):]))
    return tab


#: the rows of Fig. 6's top panel (tapmc.paper.fig6.VerticalProfiles): its curves, its params
FIG6_PROFILE_CURVES = ("initial", "final")


FIG6_PROFILE_PARAMS = ("initial:alpha", "final:alpha", "window_lo", "window_hi", "eps")


def with_fig6_rows(tab):
    """``tab`` with every row of Fig. 6's typed result (tapmc.paper.fig6.Fig6Result): a table
    with any row of the top panel has all of them (NaN where it has none)."""
    top = ([("a", c) for c in FIG6_PROFILE_CURVES]
           + [("params", name) for name in FIG6_PROFILE_PARAMS + ("final:alpha:seeds",)])
    if not any(key in tab.table for key in top):
        return tab
    for curve in FIG6_PROFILE_CURVES:
        if ("a", curve) not in tab.table:
            tab.add("a", curve, [math.nan], [math.nan], None, n=1)
    for name in FIG6_PROFILE_PARAMS:
        if ("params", name) not in tab.table:
            tab.param(name, math.nan, None, n=1)
    return tab


#: the ramps of Fig. 4's typed result (tapmc.paper.fig4.RAMPS), by CSV tag
FIG4_RAMP_TAGS = ("low", "near", "ramp")


def with_fig4_rows(tab):
    """``tab`` with every row of Fig. 4's typed result (tapmc.paper.fig4.Fig4Result): the
    highest square's params, and for a ramp with params a branch and a top (NaN where it has
    none)."""
    if ("a", "steady") not in tab.table:
        tab.add("a", "steady", [math.nan], [math.nan], None, n=1)
    for name in ("sqrt_eps_max", "phi_c_max"):
        if ("params", name) not in tab.table:
            tab.param(name, math.nan, None, n=1)
    for tag in FIG4_RAMP_TAGS:
        prefix = "" if tag == "ramp" else f"{tag}:"
        if not any(panel == "params" and series.startswith(f"{tag}:")
                   for panel, series in tab.table):
            continue
        if not any(("a", prefix + branch) in tab.table for branch in ("up1", "down", "up2")):
            tab.add("a", prefix + "up1", [math.nan], [math.nan], None, n=1)
        if ("params", f"{tag}:top_sqrt_eps") not in tab.table:
            tab.param(f"{tag}:top_sqrt_eps", math.nan, None, n=1)
    return tab


#: figure -> what completes a test's table into every row of the figure's typed result
COMPLETE_ROWS = {"fig2": with_fig2_rows, "fig3": with_fig3_rows, "fig4": with_fig4_rows, "fig6": with_fig6_rows,
                 "fig8": with_fig8_rows}


def _low_first(eps_curves):
    return dict(sorted(eps_curves.items()))


def fig2_fits(unique_by_eps, chi2_eq4=1.0, b_chi2=1.0, b_dof=1):
    """Fig. 2 data with the fits' intervals, range refits, eq. 4 and ln B(sqrt eps) rows."""
    tab = fig2({eps: RISING for eps in unique_by_eps})
    for eps, unique in unique_by_eps.items():
        tag = f"eps={P.fmt_eps(eps)}"
        tab.add("c", tag, T, 7.4 - (RISING - 0.58), 0.001)
        tab.param(f"{tag}:Z:reduced_chi2", chi2_eq4, x=eps)
        for name in ("X_inf", "B", "tau"):
            tab.param(f"{tag}:{name}", 1.0, 0.1, n=1 if unique else 0, x=eps)
            tab.param(f"{tag}:{name}:range_deviation", 1.0, None, n=1, x=eps)
    for law in ("eq3", "eq4"):
        tab.add("B", f"{law}:reduced_chi2", 0.0, b_chi2, None, b_dof)
        tab.add("B", f"{law}:slope", 0.0, -3.0, 1.0, 1)
    return tab


def realization_rows(eps, phi_b, Z, seeds=range(1, 10), taps=400, seed=13, spread=(2e-4, 2e-3)):
    """early_taps.csv rows of realizations from the same packing: Phi_b = phi_b(t) and
    <Z> = Z(t) plus each realization's AR(1) noise (correlation time ~20 taps)."""
    rng = np.random.default_rng(seed)
    t = np.arange(taps + 1.0)
    rows = []
    for s in seeds:
        noise = np.zeros((2, t.size))
        for k in range(1, t.size):
            noise[:, k] = 0.95 * noise[:, k - 1] + rng.normal(0, 0.31, 2) * np.array(spread)
        x, z = phi_b(t) + noise[0], Z(t) + noise[1]
        rows += [{"eps": str(eps), "seed": str(s), "t": str(int(k)), "phi_b": f"{a:.8f}",
                  "phi_c": "0.55", "Z": f"{b:.8f}"} for k, a, b in zip(t, x, z)]
    return rows


def realized(phi_b, Z, eps=0.05):
    """Fig. 2 with its one-run fits at ``eps`` and 9 realizations of 400 taps (early_taps.csv)
    whose Phi_b and <Z> follow ``phi_b(t)`` and ``Z(t)``."""
    return claims.ReportData(report().summary, {"fig2": fig2_fits({eps: True}).data()},
                             questions={"early_taps": realization_rows(eps, phi_b, Z)})


def eq3_law(t):
    return inverse_log(t, 0.6, 0.08, 0.3, 5.0)


def eq4_law(t):
    L = 0.4 * np.log1p(t / 3.0)
    return 7.1 * (1.0 + L) / (7.1 / 7.6 + L)


def fig5_collapse(p_value, realizations=10, tested=True, dispersion=1.1):
    """Fig. 5 data whose drawn collapse (three waiting times, time and amplitude) has the
    test across ``realizations`` given by its p-value and the law-free ``dispersion`` at its
    best exponents."""
    tab = Table()
    for tw in (0, 10, 30, 100):
        tab.add("a", f"tw={tw}", np.arange(0, 101), np.linspace(0, 0.1, 101), 0.001,
                realizations)
        tab.add("b", f"tw={tw}", np.arange(1, 101), np.linspace(0, 1, 100), 0.01)
    tab.param("drawn:mu", 1.0, None, n=1).param("scaling:reduced_chi2", 37.6)
    tab.param("scaling:mu", 1.0, 0.1, n=1).param("unscaled:reduced_chi2", 40.0)
    tab.param("scaling_test:needed", 7)
    tab.param("scaling:dispersion_min", dispersion).param("scaling:dispersion_mu", 0.9)
    tab.param("scaling:dispersion_kappa", 0.1).param("unscaled:dispersion", 40.0)
    if tested and realizations >= 7:
        tab.param("scaling_test:T2", 10.0).param("scaling_test:dof", 3)
        tab.param("scaling_test:p_value", p_value).param("scaling_test:bins", 8)
        tab.param("scaling_test_long:p_value", 0.5)
    return tab


def fig5_eq6(p_value, realizations=10, tested=True):
    """Fig. 5 data whose curves have eq. 6's test across ``realizations``, every curve with
    the p-value ``p_value``."""
    tab = fig5_collapse(0.3, realizations)
    tab.param("eq6_test:needed", 5)
    if tested and realizations >= 5:
        for tw in (10, 30, 100):
            tab.param(f"eq6_test:tw={tw}:T2", 4.0).param(f"eq6_test:tw={tw}:dof", 5)
            tab.param(f"eq6_test:tw={tw}:p_value", p_value).param(f"eq6_test:tw={tw}:bins", 8)
            tab.param(f"drift_share:tw={tw}", 0.97)
            tab.param(f"eq6_test_long:tw={tw}:p_value", 0.4)
    return tab


FROZEN = 0.58 + 0.02 * (1 - 1 / (1 + 0.3 * np.log1p(T)))    # slows down on ln t


STEADY_LOG = 0.58 + 0.04 * np.log1p(T) / np.log(4001)       # keeps its rate on ln t


def fbc_groups(mean, start, eps=0.01, sem=0.0005):
    """A report with Fig. 4's bell (P.B.C. squares; initial packings at 0.584) and three F.B.C.
    seeds at ``eps`` (realization-scatter's ``const_fbc_eps<eps>``): <Phi^c> ``mean`` from
    ``start``, each seed a little apart."""
    data = report(fig4=fig4(BELL))
    data.questions["realization_scatter"] = [
        {"group": f"const_fbc_eps{eps:g}", "run": f"const_fbc_eps{eps:g}_s{k}", "seed": str(k),
         "column": "phi_c", "start": str(start + d), "mean": str(mean + d), "sem": str(sem),
         "sem_dof": "19"} for k, d in ((1, -0.0004), (2, 0.0), (3, 0.0004))]
    return data


#: eps of a Fig. 8 on both sides of BELL's maximum (sqrt(eps) = 0.15), four each
ZONE_EPS = (0.0025, 0.0064, 0.01, 0.016, 0.04, 0.0625, 0.09, 0.12)


def fig8_bell(shape):
    """Fig. 8's final zones at ZONE_EPS, lateral ``shape(sqrt(eps))`` and central half of it,
    with the bell of Fig. 4."""
    tab = Table()
    for eps in ZONE_EPS:
        tab.param(f"eps={P.fmt_eps(eps)}:final_lateral", shape(math.sqrt(eps)), 0.0002, x=eps)
        tab.param(f"eps={P.fmt_eps(eps)}:final_central", shape(math.sqrt(eps)) / 2, 0.0002,
                  x=eps)
    return report(fig8=with_fig8_rows(tab), fig4=fig4(BELL))


def asymptote_rows(tau_small, x_inf_small):
    """fit_surrogates.csv rows of one run at eps 0.005 and 0.05: tau and X_inf at the smallest
    eps as given (10 % bands), tau = 10 and X_inf = 0.6 at the larger."""
    rows = []
    for eps, tau, x_inf in ((0.005, tau_small, x_inf_small), (0.05, 10.0, 0.6)):
        for name, value in (("X_inf", x_inf), ("dX_inf", 0.05), ("B", 0.5), ("tau", tau)):
            rows.append({"source": f"const_fbc_eps{eps:g}_s1", "eps": f"{eps}", "law": "eq3",
                         "taps": "4000", "parameter": name, "value": f"{value}",
                         "low": f"{value * 0.97}", "high": f"{value * 1.03}",
                         "half_width": f"{value * 0.03}", "log_scale": "0", "determined": "1",
                         "range_p": "0.4", "fits": "200"})
    return claims.ReportData(report().summary, {}, questions={"fit_surrogates": rows})


#: statistic (or claim id, which comes first) -> (data on which its claims must agree, data on
#: which they must not).
def front_report(r10_bias, r2_bias):
    """A report whose front has d_max R/10, R/5 (the default) and R/2 at eps 0.0225, 4 seeds:
    steady <Phi^c> biases against the reference as given (R/5: -0.002), se 0.0003 each."""
    rows = [{"setting": name, "N": 1024.0, "eps": 0.0225, "phi_c_steady_bias": bias,
             "phi_c_steady_bias_se": 0.0003, "paired_seeds": 4.0, "sweeps_per_tap": 1800.0}
            for name, bias in (("change 1e-7 (default)", -0.002), ("dmax R/10", r10_bias),
                               ("dmax R/2", r2_bias))]
    data = report()
    data.front = rows
    return data


def theta0_report(gains):
    """A report with a theta0 scan: theta0 / pi -> compaction over the taps; 4 seeds, each seed
    shifting every theta0's gain alike (paired) plus a small jitter per theta0."""
    data = report()
    data.scans["theta0"] = [_theta0_rows(gains)]
    return data


def theta_law_report(law_gains, law="exponential"):
    """theta0_report(THETA0_PAPER) with a scan of ``law`` (theta0_<law>.csv) as given."""
    data = theta0_report(THETA0_PAPER)
    data.questions[f"theta0_{law}"] = _theta0_rows(law_gains)
    return data


def _theta0_rows(gains):
    rows = []
    for seed, shift in zip(range(1, 5), (-0.002, -0.001, 0.001, 0.002)):
        for k, (frac, gain) in enumerate(sorted(gains.items())):
            jitter = 0.0002 * ((seed + k) % 3 - 1)
            rows.append({"theta0_over_pi": f"{frac:.6f}", "seed": str(seed), "N": "1024",
                         "eps": "0.0225", "taps": "100", "phi_c_0": "0.58",
                         "phi_c_end": f"{0.58 + gain + shift + jitter:.8f}",
                         "sweeps_per_tap": "1800"})
    return rows


#: the paper's pattern (pi/16 decompacts, pi/4 compacts most) and one where pi/3 compacts most
THETA0_PAPER = {1 / 16: -0.02, 1 / 8: -0.01, 1 / 4: 0.010, 1 / 3: 0.009, 1 / 2: 0.004}


THETA0_WIDER = {**THETA0_PAPER, 1 / 3: 0.016}


CONTROLS = {
    "initial_phi": (report(), report({"initial_phi_c": [0.570, 0.001, SEEDS]})),
    "theta0_optimum": (theta0_report(THETA0_PAPER), theta0_report(THETA0_WIDER)),
    # the exponential law turns earlier but decompacts at pi/16 / compacts there
    "theta_law_shape": (theta_law_report({**THETA0_PAPER, 1 / 8: 0.004}),
                        theta_law_report({**THETA0_PAPER, 1 / 16: 0.003})),
    # both other d_max leave the packing looser (slower) / both leave it denser than R/5
    "dmax_intermediate": (front_report(-0.005, -0.007), front_report(0.0, 0.0)),
    "tapped_phi": (report(fig9=fig9()),
                   report(fig9=fig9().param("phi_c_final", 0.593, 0.0005))),
    # one run: the steady state's batch-means error and the spread of single taps decide
    "phi-tapped": (report(fig9=one_run_fig9(0.6065)), report(fig9=one_run_fig9(0.600))),
    "pbc-bulk-compacts": (report(fig9=one_run_fig9(0.6065)),
                          report(fig9=one_run_fig9(0.5838))),
    "pbc_compaction": (report(fig9=fig9()),
                       report(fig9=fig9().param("phi_c_final", 0.570, 0.001))),
    "phi_b_gain": (report(fig2=fig2({0.05: RISING})),
                   report(fig2=fig2({0.05: RISING[::-1]}))),  # time-reversed
    "efficiency_decrease": (report(fig2=fig2({0.05: RISING})),
                            report(fig2=fig2({0.05: 0.58 + 1e-5 * T}))),  # steady rate
    # across realizations: the laws themselves, and a power of t that neither law follows
    "eq4_fit_quality": (realized(eq3_law, eq4_law),
                        realized(eq3_law, lambda t: 7.7 - 0.05 * t ** 0.3)),
    "b_exponential": (report(fig2=fig2_fits({0.05: True}, b_chi2=1.0, b_dof=3)),
                      report(fig2=fig2_fits({0.05: True}, b_chi2=8.0, b_dof=3))),
    # the test across realizations decides, not the reduced chi2 over correlated delays
    # the law-free dispersion decides, whatever the collapse on eq. 6 gives
    "ageing_collapse": (report(fig5=fig5_collapse(0.002)),
                        report(fig5=fig5_collapse(0.3, dispersion=40.0))),
    "ageing_eq6": (report(fig5=fig5_eq6(0.3)), report(fig5=fig5_eq6(0.002))),
    "eq3_fit_quality": (realized(eq3_law, eq4_law),
                        realized(lambda t: 0.52 + 0.01 * t ** 0.3, eq4_law)),
    # the paper's own eq. 3 with tau growing at small eps (section III.B) agrees; the reverse not
    "slowing-small-eps": (
        report(fig2=fig2(_low_first({0.005: inverse_log(T, tau=300.0), 0.15: inverse_log(T)}))),
        report(fig2=fig2(_low_first({0.005: inverse_log(T), 0.15: inverse_log(T, tau=300.0)})))),
    # the curve that keeps its rate on ln t makes a larger share of its gain late
    "late_gain_share": (report(fig2=fig2(_low_first({0.005: STEADY_LOG, 0.15: FROZEN}))),
                        report(fig2=fig2(_low_first({0.005: FROZEN, 0.15: STEADY_LOG})))),
    "spectral_slopes": (report(fig3=fig3(slope=-1.2)), report(fig3=fig3(slope=-0.5))),
    "spectrum_low_band": (
        # spectra that coincide at low f and separate at high f only, and the reverse (low
        # bands a factor 24 apart: one run's lowest quarter has about five dof, its level is
        # known to a factor of about two)
        report(fig3=fig3({e: (lambda f, e=e: 1e-3 / f + 10 * e * f) for e in (0.01, 0.04, 0.09)})),
        report(fig3=fig3({e: (lambda f, e=e: 1e-3 * (e / 0.01) ** 2 / f + 1.0)
                          for e in (0.01, 0.04, 0.09)}))),
    "sigma_intercept": (report(fig3=fig3()), report(fig3=fig3(intercept=0.05))),
    # each row reads its own sigma: the other's intercept stays zero in the failing case
    "sigma-proportional-detrended": (report(fig3=fig3(intercept=0.05)),
                                     report(fig3=fig3(intercept_detrended=0.05))),
    "bell_maximum": (report(fig4=fig4(BELL)),
                     report(fig4=fig4(0.60 - 2.0 * (X - 0.3) ** 2))),
    "bell_side_slope": (report(fig4=fig4(BELL)), report(fig4=fig4(0.65 - BELL))),
    # per claim where one statistic serves two claims: the side of the bell that must fail
    "bell-rising": (report(fig4=fig4(BELL)), report(fig4=fig4(0.62 - 0.05 * X))),
    "bell-falling": (report(fig4=fig4(BELL)), report(fig4=fig4(0.58 + 0.05 * X))),
    # rule near: within a tenth of the gap (0.003 here), beyond it
    "ramp_up_minus_steady": (report(fig4=fig4(BELL, up1=BELL, down=BELL + 0.03)),
                             report(fig4=fig4(BELL, up1=BELL - 0.01, down=BELL + 0.01))),
    "ramp_down_minus_up": (report(fig4=fig4(BELL, up1=BELL, down=BELL + 0.01)),
                           report(fig4=fig4(BELL, up1=BELL, down=BELL - 0.01))),
    "ramp_up2_minus_down": (report(fig4=fig4(BELL, up1=BELL, down=BELL + 0.03,
                                             up2=BELL + 0.03)),
                            report(fig4=fig4(BELL, up1=BELL, down=BELL + 0.03, up2=BELL))),
    "low_ramp_frozen": (
        report(fig4=fig4(BELL).param("low:down_change", 0.0002, 0.0005)
               .param("ramp:down_change", 0.01, 0.0005)),
        report(fig4=fig4(BELL).param("low:down_change", 0.01, 0.0005)
               .param("ramp:down_change", 0.01, 0.0005))),
    # turning at 0.125 (frozen) and 0.175 (compacts on the way down), and the reverse
    "critical_separation": (report(fig4=ramps_turning({0.125: 0.0002, 0.175: 0.01})),
                            report(fig4=ramps_turning({0.125: 0.01, 0.175: 0.0002}))),
    # nu: below its first increase on the way down and rising with sqrt(eps); the reverse
    "nu_ramp_hysteresis": (ramp_pores(gap=-0.02, slope=0.05), ramp_pores(gap=0.02, slope=-0.05)),
    "ramp_branch_slope": (report(fig4=fig4(BELL, down=0.62 - 0.1 * X)),
                          report(fig4=fig4(BELL, down=0.58 + 0.1 * X))),
    "alpha_ramp_hysteresis": (report(fig6=fig6_ramp(0.0)), report(fig6=fig6_ramp(0.001))),
    "alpha_bell": (report(fig6=Table().add("b", "bell:alpha", X, 0.004 - 0.1 * (X - 0.15) ** 2,
                                          0.0002), fig4=fig4(BELL)),
                   report(fig6=Table().add("b", "bell:alpha", X, 0.001 + 0.01 * X, 0.0002),
                          fig4=fig4(BELL))),
    # wall layers the smoothing removes; a smooth departure of 0.02 over 10-16R it keeps
    "eq7_smoothed_fit": (report(fig6=fig6_profile()), report(fig6=fig6_profile(0.02))),
    # three layers from each wall; none
    "wall_layering": (report(fig7=fig7_profile()), report(fig7=fig7_profile(0.0))),
    "final_alpha": (report(fig6=Table().param("final:alpha", 0.002, 0.0002)),
                    report(fig6=Table().param("final:alpha", -0.002, 0.0002))),
    "central_minus_lateral": (report(fig8=fig8(0.01, 0.02)), report(fig8=fig8(0.02, 0.01))),
    "lateral_first_tap": (report(fig8=fig8(0.01, 0.02, paper_first_tap=0.01)),
                          report(fig8=fig8(0.01, 0.02, paper_first_tap=-0.01))),
    # P0 changes with Phi as Percus-Yevick says; and as much again beyond it
    "p0_change_over_density": (report(fig9=fig9(initial_phi=0.584)),
                               report(fig9=fig9(diff=0.05))),
    "p0_final_minus_py": (report(fig9=fig9()), report(fig9=fig9(py_shift=0.05))),
    "xi_min": (report(fig10=fig10()), report(fig10=fig10(xi_min=0.20))),
    # a linear onset at every dump: no spread between the curves hides it (the paper's
    # precision for this law, which it calls superimposed for the small pores)
    "pore_quadratic_fit": (report(fig10=fig10()),
                           report(fig10=fig10(first=np.where(XI > P.XI_T, XI - P.XI_T, 0.0),
                                              last=np.where(XI > P.XI_T, XI - P.XI_T, 0.0)))),
    "pore_share_change": (
        report(fig10=fig10()),
        # small pores change as much as the tail, and the tail grows
        report(fig10=fig10(first=pore_curve(0.05), last=1.5 * pore_curve(0.1)))),
    "nu_tail_over_nu": (report(fig10=fig10()), report(fig10=fig10(tail_ratio=1.5))),
    "nu_change": (report(fig10=fig10()), report(fig10=fig10(nu=(0.10, 0.12)))),
    # denser in P.B.C. with a smaller increase; F.B.C. denser, rising less
    "pbc_vs_fbc": (fbc_groups(0.57, 0.55), fbc_groups(0.61, 0.605)),
    "zone_bell": (fig8_bell(lambda x: 0.03 - 2.0 * (x - 0.15) ** 2),
                  fig8_bell(lambda x: 0.01 + 2.0 * (x - 0.15) ** 2)),
    # an exponential tail over the quadratic onset; a box of pores, no tail at all
    "pore_gaussian_excess": (report(fig10=fig10()),
                             report(fig10=fig10(first=np.where(np.abs(XI - 0.45) < 0.15, 1.0, 0.0),
                                                last=np.where(np.abs(XI - 0.45) < 0.15, 1.0,
                                                              0.0)))),
    # one run's surrogates: a spectacular tau and X_inf beyond 0.64 agree; the reverse cannot
    # contradict (their bands are too narrow), it stays undecided
    "eq3_small_eps_asymptote": (asymptote_rows(1e4, 0.7), asymptote_rows(5.0, 0.58)),
    # <Z> as two exponentials across realizations; a logarithmic decay they cannot follow
    "z_two_exponentials": (
        realized(eq3_law, lambda t: 7.1 + 0.3 * np.exp(-t / 5.0) + 0.2 * np.exp(-t / 80.0)),
        realized(eq3_law, lambda t: 7.7 - 0.05 * np.log1p(t))),
}


def _outcomes(claim, data):
    return [str(claims.verdict(claim, m)) for m in claims.STATISTICS[claim.statistic](data, claim)]


def _packings(phis, N=4096, L=32):
    return [{"seed": str(i + 1), "N": str(N), "L": str(L), "bc": "pbc", "phi_c": str(p)}
            for i, p in enumerate(phis)]


def _p0_rows(initial, tapped, sem, phi_i=0.582, phi_t=0.604, n=8):
    sigma = np.linspace(0.0, 2.0, 60)
    rows = [{"sigma": f"{x}", "initial": f"{a}", "initial_sem": f"{sem}", "initial_n": f"{n}",
             "tapped": f"{b}", "tapped_sem": f"{sem}", "tapped_n": f"{n}"}
            for x, a, b in zip(sigma, initial(sigma), tapped(sigma))]
    rows.append({"sigma": "phi", "initial": f"{phi_i}", "initial_sem": "0.0005",
                 "initial_n": f"{n}", "tapped": f"{phi_t}", "tapped_sem": "0.0005",
                 "tapped_n": f"{n}"})
    return rows


def early_rows(eps, rate, spread, seeds=range(1, 10), seed=11):
    """early_taps.csv rows: Phi_b(t) = 0.52 + rate t at t = 0..10 plus a realization's own
    offset and tap noise of ``spread``."""
    rng = np.random.default_rng(seed)
    rows = []
    for s in seeds:
        x = 0.52 + rate * np.arange(11.0) + rng.normal(0, spread, 11)
        x[0] = 0.52                                       # the same packing
        rows += [{"eps": str(eps), "seed": str(s), "t": str(k), "phi_b": f"{v:.8f}",
                  "phi_c": "0.55", "Z": "7.5"} for k, v in enumerate(x)]
    return rows


def surrogate_rows(states, law="eq3", b_values=None):
    """fit_surrogates.csv rows of one campaign run per eps: ``states`` eps -> (undetermined
    parameters, range-dependent parameters); B = ``b_values[eps]`` with a 10 % band."""
    names = {"eq3": ("X_inf", "dX_inf", "B", "tau"), "eq4": ("Z_inf", "Z_0", "B", "tau")}[law]
    rows = []
    for eps, (undetermined, dependent) in states.items():
        for k in names:
            value = (b_values or {}).get(eps, 0.5) if k == "B" else 1.0
            rows.append({"source": f"const_fbc_eps{eps:g}_s1", "eps": f"{eps}", "law": law,
                         "taps": "4000", "parameter": k, "value": f"{value}",
                         "low": f"{value * 0.9}", "high": f"{value * 1.1}",
                         "half_width": "0.1", "log_scale": str(int(k in ("B", "tau"))),
                         "determined": "0" if k in undetermined else "1",
                         "range_p": "0.001" if k in dependent else "0.4", "fits": "200"})
    # the realizations' rows are another source: never read as a campaign run
    rows.append(dict(rows[0], source="realizations", eps="0.005", determined="1"))
    return rows


def surrogate_report(rows):
    return claims.ReportData(report().summary, {}, questions={"fit_surrogates": rows})


def seed_fit_rows(states, bc="fbc", law="eq3", realizations=3, group=None):
    """seed_fits.csv rows of one group of realizations per eps: ``states`` eps -> (undetermined
    parameters, parameters the realizations cannot tell, range-dependent parameters)."""
    names = {"eq3": ("X_inf", "dX_inf", "B", "tau"), "eq4": ("Z_inf", "Z_0", "B", "tau")}[law]
    rows = []
    for eps, (undetermined, unsure, dependent) in states.items():
        for k in names:
            rows.append({"group": group or f"const_{bc}_eps{eps:g}", "bc": bc, "eps": f"{eps}",
                         "law": law, "taps": "4000", "realizations": str(realizations),
                         "parameter": k, "values": "1;2;3", "mean": "0.5", "spread": "0.3",
                         "spread_low": "0.15", "spread_high": "1.9", "limit": "0.69",
                         "log_scale": str(int(k in ("B", "tau"))),
                         "determined": "0" if k in undetermined else "" if k in unsure else "1",
                         "range_shift": "0.1", "range_bound": "0.5",
                         "range_p": "0.001" if k in dependent else "0.4"})
    return rows


def _ramp_levels_rows(shifts):
    """ramp_levels.csv rows: (level, branch, shift of <Phi^c> from 1000 to 4000 taps), each
    with batch-means errors of 1e-4."""
    return [{"level": str(k), "branch": str(b), "sqrt_eps": "0.1", "taps": "1000",
             "taps_long": "4000", "phi_c": "0.60", "phi_c_sem": "1e-4",
             "phi_c_long": f"{0.60 + d:.6f}", "phi_c_long_sem": "1e-4"}
            for k, b, d in shifts]


def _scatter_rows(quantity, spread, error, groups=2, runs=4, prefix="g"):
    """realization_scatter.csv rows of ``quantity`` whose realizations spread ``spread``
    against their own errors ``error`` (exactly: means at +-spread * sqrt((n-1)/n)); groups
    named ``<prefix><g>``."""
    offsets = np.array([1.0, -1.0] * (runs // 2)) * spread * np.sqrt((runs - 1) / runs)
    return [{"group": f"{prefix}{g}", "column": quantity, "mean": str(0.6 + o),
             "sem": str(error), "sem_dof": "19"} for g in range(groups) for o in offsets]


def _with_scatter(tab):
    data = report(fig4=tab)
    data.questions["realization_scatter"] = _scatter_rows("phi_c", 0.002, 0.001)
    return data


#: every name the claims' test files take from here (star import), private helpers too
__all__ = ['os', 'sys', 'Path', 'SOURCE', 'REGISTER', 'BY_ID', 'SEEDS', 'claims', 'P',
           'percus_yevick_p0', 'np', 'pytest', 'math', 'dataclasses', 'Table', 'report', 'T',
           'fig2', 'inverse_log', 'RISING', 'fig3', 'X', 'fig4', 'BELL', 'ramp_pores',
           'ramps_turning', '_critical', 'fig6_ramp', 'fig6_profile', 'fig7_profile',
           'FIG9_PARAMS', 'with_fig9_params', 'fig9',
           'one_run_fig9', 'XI', 'pore_curve', 'with_fig10_rows', 'fig10', 'fig8',
           'with_fig8_rows', 'with_fig2_rows', 'with_fig3_rows', 'FIG6_PROFILE_CURVES', 'FIG6_PROFILE_PARAMS',
           'with_fig6_rows', 'FIG4_RAMP_TAGS', 'with_fig4_rows', 'COMPLETE_ROWS', '_low_first',
           'fig2_fits', 'realization_rows', 'realized', 'eq3_law', 'eq4_law', 'fig5_collapse',
           'fig5_eq6', 'FROZEN', 'STEADY_LOG', 'front_report', 'theta0_report', 'theta_law_report',
           'THETA0_PAPER', 'THETA0_WIDER', 'CONTROLS', '_outcomes', '_packings', '_p0_rows', 'early_rows',
           'surrogate_rows', 'surrogate_report', 'seed_fit_rows', '_ramp_levels_rows',
           '_scatter_rows', '_with_scatter', 'fbc_groups', 'ZONE_EPS', 'fig8_bell',
           'asymptote_rows']


def _triplet_report(at_002):
    """One run per eps (surrogates: not unique at 0.005 and 0.15, unique at 0.02) and three
    realizations at 0.02 with the parameters ``at_002`` undetermined."""
    runs = surrogate_rows({0.005: (["B", "tau"], []), 0.02: ([], []), 0.15: (["B"], [])})
    return claims.ReportData(report().summary, {}, questions={
        "fit_surrogates": runs, "seed_fits": seed_fit_rows({0.02: (at_002, [], [])})})


# the realizations fix the triplet at 0.02 (the paper's contrast) / find B undetermined there
CONTROLS["eq3_triplet_pattern"] = (_triplet_report([]), _triplet_report(["B"]))
