# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Fig. 9 of Philippe & Bideau: Gotoh's pore size distribution P0(sigma) against the
Percus-Yevick expression (section IV.B, eqs. 8-9).

P.B.C.; P0 measured by tapmc-pores (the probability that a random point of the statistics
box lies farther than sigma R from every centre) for the packing after the run (open
circles) and for the initial packing (thin line), mean and standard error over seeds; the
thick line is the Percus-Yevick P0 (``tapmc.pores.percus_yevick_p0``) at the volume fraction
of the final packings (the fraction of random points inside a sphere). The paper finds the
measured P0 close to the theory and hardly different between the initial (58.4 %) and the
tapped (60.6 %) packings.

CSV panels: ``a`` (series ``final``, ``initial``, ``percus_yevick``; x = sigma), ``params``
(``phi_initial``, ``phi_final`` seen by the random points; ``max_abs_diff_initial_final``,
``max_abs_diff_final_py``; ``phi_c_initial``, ``phi_c_final`` of the stereology at the two
dumps; ``phi_c_steady``: the steady state of <Phi^c>, the mean over the last quarter of the
taps (the paper's last 1000 of 4000), whose sem is over seeds, or for one seed (n = 1) the
batch-means error of that mean (``tapmc.fluctuations.SteadyState``, successive taps being
correlated); ``phi_c_tap_sd``: the standard deviation of single taps about it (the spread of a
value read at one tap, as the paper's 60.6 % is); ``taps``: the taps of the runs, after
which the final packing is dumped).

:func:`analyse` returns a :class:`Fig9Result` (its ``save``/``load`` are the CSV), :func:`plot`
draws one, :func:`draw` does both into a folder.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tapmc.fluctuations import SteadyState
from tapmc.pores import percus_yevick_p0, read_pores

from . import _plotting as P
from . import _pores, _runs
from ._results import FigureResult, Series, Value
from ._steady_state import steady_last

NAME = "fig9"
BC = "pbc"
#: eps of the Fig. 9 runs when the campaign's scale is not recorded (that of the presets).
DEFAULT_P0_EPS = 0.0225


def runs(scale, seeds):
    """One constant-eps P.B.C. run per seed at ``scale.p0_eps`` (the paper does not give the eps
    of Fig. 9; the presets take one of their bell's eps, so the run is shared with Figs. 3-4),
    which dumps its packing at t = 0 and after ``scale.taps`` taps."""
    return [_runs.constant_eps_run(scale, BC, scale.p0_eps, s) for s in _runs.seed_list(seeds)]


def p0_runs(campaign, bc=BC):
    """(eps, specs): the campaign's constant-eps runs of ``bc`` at its scale's ``p0_eps``
    (nearest eps when the scale is not recorded)."""
    scale = _runs.campaign_scale(campaign)
    groups = _runs.constant_eps_groups(campaign, bc)
    target = scale.p0_eps if scale is not None else DEFAULT_P0_EPS
    eps = min(groups, key=lambda e: abs(np.log(e / target)))
    return eps, groups[eps]


def p0_curves(campaign, bc=BC):
    """dict 'initial'/'final' -> (sigma, list of P0 per seed, list of phi per seed) and the
    stereological <Phi^c> at both ends, over the runs of :func:`p0_runs` (with ``taps``: the
    tap of each run's final dump)."""
    _, specs = p0_runs(campaign, bc)
    out = {"initial": [None, [], []], "final": [None, [], []]}
    phi_c = {"initial": [], "final": [], "steady": [], "taps": []}
    for spec in specs:
        files = _pores.dumps(_runs.run_dir(campaign, spec))
        first, last = min(files), max(files)
        phi_c["taps"].append(int(last))
        tab = _runs.taps_table(campaign, spec)
        for key, step in (("initial", first), ("final", last)):
            prefix, _ = _pores.analyse(campaign, spec, f"p0_t{step}", steps=[step],
                                       extra=["--p0", str(_pores.P0_POINTS), "--seed",
                                              str(spec.seed)])
            pores = read_pores(prefix)
            out[key][0] = pores.p0["sigma"]
            out[key][1].append(pores.p0["P0_measured"])
            out[key][2].append([float(pores.frames["phi_p0"][0])])
            row = np.searchsorted(tab["step"], step)
            phi_c[key].append([tab["phi_c"][row]])
        series = np.asarray(tab["phi_c"], dtype=float)
        phi_c["steady"].append(SteadyState(series, last=steady_last(len(series) - 1)).compute())
    return out, phi_c


def steady_phi(states):
    """(mean, sem, n, tap_sd) of the steady <Phi^c> over the runs' SteadyState results: sem
    over seeds, or the batch-means error of one run's mean when there is one seed."""
    means = [s.mean for s in states]
    tap_sd = float(np.mean([s.std for s in states]))
    if len(states) == 1:
        return means[0], states[0].sem, 1, tap_sd
    m, s, n = P.seed_stats([[v] for v in means])
    return float(m[0]), float(s[0]), int(n[0]), tap_sd


#: the packings of panel a, in the CSV's order
STATES = ("final", "initial")


@dataclass(frozen=True)
class Fig9Result(FigureResult):
    """The numbers of Fig. 9 (CSV schema: module text)."""

    #: state ('final', 'initial') -> P0(sigma) over seeds
    p0: dict
    #: state -> the volume fraction the random points see
    phi: dict
    #: state -> the stereological <Phi^c> at that dump
    phi_c: dict
    #: Percus-Yevick P0 at the final packings' volume fraction
    percus_yevick: Series
    max_abs_diff_initial_final: Value
    max_abs_diff_final_py: Value
    #: steady <Phi^c> and the spread of single taps about it (None in CSVs drawn before them)
    phi_c_steady: Value = None
    phi_c_tap_sd: Value = None
    #: taps of the runs, dumped after them (the legend's "after N taps"; None in CSVs drawn
    #: before it)
    taps: Value = None

    def rows(self):
        out = []
        for state in STATES:
            out += [("a", state, self.p0[state]), ("params", f"phi_{state}", self.phi[state]),
                    ("params", f"phi_c_{state}", self.phi_c[state])]
        for name in ("phi_c_steady", "phi_c_tap_sd", "taps"):
            if getattr(self, name) is not None:
                out.append(("params", name, getattr(self, name)))
        return out + [("a", "percus_yevick", self.percus_yevick),
                      ("params", "max_abs_diff_initial_final", self.max_abs_diff_initial_final),
                      ("params", "max_abs_diff_final_py", self.max_abs_diff_final_py)]

    @classmethod
    def from_rows(cls, rows):
        def each(panel, name):
            return {state: (rows.take(panel, state) if panel == "a"
                            else rows.take_value(panel, name.format(state)))
                    for state in STATES}

        optional = {name: rows.take_value("params", name)
                    for name in ("phi_c_steady", "phi_c_tap_sd", "taps")
                    if rows.has("params", name)}
        return cls(each("a", "{}"), each("params", "phi_{}"), each("params", "phi_c_{}"),
                   rows.take("a", "percus_yevick"),
                   rows.take_value("params", "max_abs_diff_initial_final"),
                   rows.take_value("params", "max_abs_diff_final_py"), **optional)


def analyse(campaign):
    """Fig. 9 from the campaign's P.B.C. runs at its scale's ``p0_eps`` (:func:`p0_runs`)."""
    curves, phi_c = p0_curves(campaign)
    p0, phi, phi_c_ends = {}, {}, {}
    for state in STATES:
        sigma, p0s, phis = curves[state]
        p0[state] = Series.of(sigma, *P.seed_stats(p0s))
        phi[state] = Value.of_stats(0.0, P.seed_stats(phis))
        phi_c_ends[state] = Value.of_stats(0.0, P.seed_stats(phi_c[state]))
    m, s, n, tap_sd = steady_phi(phi_c["steady"])
    sigma, final, initial = p0["final"].x, p0["final"].mean, p0["initial"].mean
    theory = np.asarray(percus_yevick_p0(sigma, phi["final"].value), dtype=float)
    return Fig9Result(
        p0, phi, phi_c_ends, Series.of(sigma, theory, None, 0),
        Value(0.0, float(np.max(np.abs(final - initial)))),
        Value(0.0, float(np.max(np.abs(final - theory)))),
        Value(0.0, m, s, n), Value(0.0, tap_sd, np.nan, n),
        _taps_value(phi_c.get("taps"), n))


def _taps_value(taps, n):
    """The tap of the final dumps (one count for every run, else None: the legend then says
    "after the taps")."""
    return (Value(0.0, float(taps[0]), np.nan, n) if taps and len(set(taps)) == 1
            else None)


def plot(result, settings=None):
    """The figure of a :class:`Fig9Result` (drawing only)."""
    fig, (ax,) = P.new_figure(1, 1, height=4.0)
    final, initial, theory = result.p0["final"], result.p0["initial"], result.percus_yevick
    every = max(len(final.x) // 40, 1)
    final_label = P.after_taps(None if result.taps is None else result.taps.value, settings)
    ax.errorbar(final.x[::every], final.mean[::every], yerr=np.nan_to_num(final.err[::every]),
                marker="o", mfc="none", ls="none", color="C0", capsize=1,
                label=f"{final_label} ($\\Phi$ = {100 * result.phi['final'].value:.1f} %)")
    ax.plot(initial.x, initial.mean, "-", lw=0.8, color="k",
            label=f"initial packing ($\\Phi$ = {100 * result.phi['initial'].value:.1f} %)")
    ax.plot(theory.x, theory.mean, "-", lw=2.5, color="C1", alpha=0.7,
            label=f"Percus-Yevick, $\\Phi$ = {100 * result.phi['final'].value:.1f} %")
    ax.set_yscale("log")
    ax.set_ylim(max(1e-5, float(np.nanmin(final.mean[final.mean > 0])) / 2), 1.2)
    ax.set_xlabel(r"$\sigma = r'/R$")
    ax.set_ylabel(r"$P_0(\sigma)$")
    P.legend(ax, fontsize=7, title="P.B.C.", title_fontsize=7)
    return P.finish_figure(fig, settings, P.plotted_seeds(result))


def figure_runs(campaign):
    """The runs Fig. 9 draws: the P.B.C. runs at the scale's p0_eps (:func:`p0_runs`)."""
    return p0_runs(campaign)[1]


def draw(campaign, out_dir):
    """Fig. 9's PNG and CSV in ``out_dir``; returns their paths."""
    settings = P.figure_settings(campaign, figure_runs(campaign), eps=True)
    return analyse(campaign).save_with_png(plot, out_dir, NAME, settings)
