# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Fig. 6 of Philippe & Bideau: vertical packing-fraction profiles Phi(z/R) with the eq. 7 fit
(section IV.A).

F.B.C.; the initial packing (dotted) and the packing after the run (solid) at the campaign's
eps nearest to the paper's 0.1. The profile is the exact slab average of compute
stereo/profile over bins of R/5 (the "smoothing" of the paper), averaged over seeds. Thin
lines: eq. 7 (``tapmc.laws.ProfileLaw``) fitted to the seed-averaged profiles.

The gradient alpha (``tapmc.laws.profile_gradient``, straight line Phi0 - alpha z/R) is fitted
per seed in the paper's window 5 <= z/R <= 22 (F.B.C.), cut at 78 % of the packing height
(22R of the paper's 28R) when the packing is lower; alpha > 0 is the paper's "negative
vertical gradient" (density decreasing with height).

Bottom panel, when the campaign has the P.B.C. constant-eps runs of the bell (Figs. 3-4):
alpha after the taps against sqrt(eps), the paper's "approximately the same kind of bell shape
dependence as the other steady-state values" (section IV.A), fitted in the P.B.C. window
5 <= z/R <= 26 cut as above; the sem is over seeds, or for one seed (the paper's protocol)
the error within its packing: the lateral jackknife of the profile of the packing dumped after
the last tap (4 x 4 blocks, ``tapmc.profiles.vertical_profile_jackknife``), as for
``final:alpha``. ``runs`` does not add those runs: ``tapmc-paper fig6`` alone draws the top panel, the
report (every figure) both.

Open symbols in the bottom panel, when the campaign has the ramp of Fig. 4: alpha in the profile
the ramp prints at the end of every level (``in.ramp``'s profile_z.dat), per branch (first
increase, decrease, second increase), for the paper's "alpha presents no hysteresis effect"
(section IV.A). The ramp prints no h_s, so its window is cut at WINDOW_TOP_FRACTION of the
height of its initial profile (:func:`profile_height`); the error is over seeds, or for one
seed the straight line's own (too small: the claim's statistic uses the scatter of the levels).

CSV panels: ``a`` (series ``initial``, ``final``, ``fit:initial``, ``fit:final``; x = z/R),
``b`` (series ``bell:alpha`` and ``ramp:up1``, ``ramp:down``, ``ramp:up2``: x = sqrt(eps)),
``params`` (``initial:alpha``, ``final:alpha``
over seeds; with two seeds or more ``final:alpha:seeds``, one row per seed: its alpha and the
lateral jackknife of its packing; ``final:<eq. 7 parameter>``, ``window_lo``, ``window_hi``,
``eps``; ``taps``: the taps of the runs, the legend's "after N taps").

:func:`analyse` returns a :class:`Fig6Result` (its ``save``/``load`` are the CSV), :func:`plot`
draws one, :func:`draw` does both into a folder.
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from tapmc.fluctuations import jackknife_error
from tapmc.laws import PROFILE_WINDOWS, ProfileLaw, profile_gradient
from tapmc.profiles import vertical_profile_jackknife
from tapmc.readers import read_ave_time, read_dump

from . import _plotting as P
from . import _profile_runs, _runs, _steady_state
from ._profile_runs import BC, nearest_eps_runs, profiles, radius
from ._results import FigureResult, Series, Value

NAME = "fig6"
#: upper end of the gradient window as a fraction of the packing height (22R of 28R).
WINDOW_TOP_FRACTION = 22.0 / 28.0


def runs(scale, seeds):
    """Constant-eps F.B.C. runs of ``scale.profile_eps`` (shared with Figs. 7 and 8:
    ``_profile_runs.runs``)."""
    return _profile_runs.runs(scale, seeds)


def gradient_window(campaign, specs, bc=BC):
    """The paper's gradient window, cut at WINDOW_TOP_FRACTION of the initial packing height."""
    return window_below([_runs.taps_table(campaign, s)["h_s"][0] / radius(s) for s in specs],
                        bc)


def window_below(heights, bc=BC):
    """The paper's gradient window for ``bc``, cut at WINDOW_TOP_FRACTION of the lowest of
    the initial packing heights ``heights`` (in R)."""
    lo, hi = PROFILE_WINDOWS[bc]
    return lo, min(hi, WINDOW_TOP_FRACTION * float(np.min(heights)))


def final_dump(folder, taps):
    """The packing a constant-eps run dumps after its last tap (``dump_ends``)."""
    return Path(folder) / f"dump.{int(taps)}.lammpstrj"


def _alpha_jackknife(dump, r, centres, window, bc):
    """Error of alpha within the packing after the last tap: the lateral jackknife of its
    profile (``tapmc.profiles.vertical_profile_jackknife``) from the run's dump of that step;
    None when the run has no such dump."""
    if not dump.is_file():
        return None
    frame = next(iter(read_dump(dump).frames))
    width = (centres[-1] - centres[0]) / (len(centres) - 1)   # the compute's uniform bins
    edges = np.append(centres - width / 2, centres[-1] + width / 2)
    _, replicates = vertical_profile_jackknife(frame.positions, r, edges, frame.box_lo,
                                               frame.box_hi)
    alphas = [profile_gradient(centres / r, rep, window=window, boundary=bc).params["alpha"]
              for rep in replicates]
    return float(jackknife_error(alphas))


def final_alpha(campaign, spec, window, bc):
    """(alpha, its error) of the last profile of a run in ``window`` (:func:`run_alpha`)."""
    return run_alpha(_runs.run_dir(campaign, spec), int(spec.variables["taps"]), radius(spec),
                     window, bc)


def run_alpha(folder, taps, r, window, bc):
    """(alpha, its error) of the last profile (``profile_z.dat``) of the run in ``folder``
    (``taps`` taps, sphere radius ``r``) in ``window``. The error is the lateral jackknife of
    the packing dumped after the last tap (``dump.<taps>.lammpstrj``: the profile's bins share
    spheres, so the straight line's own error is too small); the line's own error when there
    is no dump."""
    folder = Path(folder)
    blocks = read_ave_time(folder / "profile_z.dat").blocks
    fit = profile_gradient(blocks[-1, :, 0] / r, blocks[-1, :, 2], window=window, boundary=bc)
    within = _alpha_jackknife(final_dump(folder, taps), r, blocks[-1, :, 0], window, bc)
    return float(fit.params["alpha"]), (float(fit.errors["alpha"]) if within is None
                                        else within)


def alpha_bell(campaign, bc=_steady_state.BC):
    """(sqrt_eps, mean, sem, n) of alpha after the taps of the constant-eps runs of the bell;
    None when the campaign has none. One seed: the fit's own error (module docstring)."""
    try:
        groups = _runs.constant_eps_groups(campaign, bc)
    except ValueError:
        return None
    fits = {}
    for eps, specs in groups.items():
        window = gradient_window(campaign, specs, bc)
        fits[eps] = [final_alpha(campaign, spec, window, bc) for spec in specs]
    return bell_series(fits)


def bell_point(fits):
    """(mean, error, n) of alpha over the seeds of one eps from their (alpha, error within
    the packing) ``fits``: the mean and sem over seeds, or for one seed its own value and
    error (the lateral jackknife of its packing, :func:`run_alpha`)."""
    if len(fits) == 1:
        return fits[0][0], fits[0][1], 1
    m, s, n = P.seed_stats([[a] for a, _ in fits])
    return m[0], s[0], n[0]


def bell_series(fits):
    """(sqrt_eps, mean, error, n) arrays of the bell's alphas from ``fits`` (eps -> the
    seeds' (alpha, error)), in the order of ``fits``, each point by :func:`bell_point`."""
    rows = [(np.sqrt(eps), *bell_point(seeds)) for eps, seeds in fits.items()]
    return tuple(np.array(col, dtype=float) for col in zip(*rows))


def profile_height(zb, phi, window):
    """Height (z/R) of a packing from its vertical profile: the first zb above the window's
    bottom where Phi falls below half of its median inside the window. For a deposited
    packing it matches the mean top of the columns, h_s of compute stereo/profile, to about
    a bin (29.25R against 28.98R for the full preset's initial packing)."""
    lo, hi = window
    inside = (zb >= lo) & (zb <= hi)
    if inside.sum() < 3:
        raise ValueError(f"window = ({lo:g}, {hi:g}) holds {inside.sum()} profile points; "
                         "at least 3 are needed")
    level = 0.5 * float(np.median(phi[inside]))
    below = np.flatnonzero((zb > lo) & (phi < level))
    if not len(below):
        raise ValueError("the profile does not fall below half of its median: the packing "
                         "reaches the top of the profile, so its height is unknown")
    return float(zb[below[0]])


def ramp_alpha(campaign, bc=_steady_state.BC, prefix="ramp_"):
    """dict branch ('up1', 'down', 'up2') -> (sqrt_eps, alpha, err, n): alpha of the profile
    every ramp run named ``prefix...`` prints at the end of each level (in.ramp's
    profile_z.dat; its branch column names the branch), averaged over seeds; the error is the
    sem over seeds, or with one seed the straight line's own error. Empty when the campaign
    has no such ramp."""
    collected = defaultdict(lambda: defaultdict(list))
    for spec in _runs.select(campaign, prefix, bc=bc):
        prof = _runs.profile(campaign, spec, "profile_z.dat")
        levels = level_alphas(prof.blocks, prof.steps, _runs.taps_table(campaign, spec),
                              radius(spec), bc)
        for level in levels:
            collected[level.branch][round(level.sqrt_eps, 9)].append((level.alpha, level.err))
    out = {}
    for branch in _runs.RAMP_BRANCHES:
        by_sq = collected.get(branch)
        if not by_sq:
            continue
        sq = np.array(sorted(by_sq))
        rows = []
        for key in sq:
            m, s, n = P.seed_stats([[a] for a, _ in by_sq[key]])
            rows.append((m[0], s[0] if n[0] >= 2 else by_sq[key][0][1], n[0]))
        out[branch] = (sq,) + tuple(np.array(col, dtype=float) for col in zip(*rows))
    return out


@dataclass(frozen=True)
class LevelAlpha:
    """alpha of the profile a ramp prints at the end of one level."""

    step: int
    branch: str
    sqrt_eps: float
    alpha: float
    #: the straight line's own error (too small: the bins of one profile share spheres)
    err: float
    #: the gradient window (lo, hi) in R
    window: tuple


def level_alphas(blocks, steps, table, r, bc=_steady_state.BC, window=None):
    """[LevelAlpha] of a ramp's vertical profiles (``blocks``, one per output ``steps``;
    columns z, ..., Phi as in.ramp's profile_z.dat), the level of each read from the ramp's
    taps ``table`` (columns step, branch, sqrt_eps; the last row of a step written twice by a
    resumed run). The window is the boundary's (tapmc.laws.PROFILE_WINDOWS) cut at
    WINDOW_TOP_FRACTION of the height of the profile at step 0, which must be there, unless
    ``window`` (lo, hi) in R is given; a block whose step has no row of the table is left
    out."""
    steps = np.asarray(steps, dtype=int)
    if not len(steps) or steps[0] != 0:
        raise ValueError("the profiles do not start with the initial packing's (step 0): "
                         "the gradient window cannot be cut at its height")
    if window is None:
        lo, hi = PROFILE_WINDOWS[bc]
        height = profile_height(blocks[0][:, 0] / r, blocks[0][:, 2], (lo, hi))
        window = (lo, min(hi, WINDOW_TOP_FRACTION * height))
    tap_steps = np.asarray(table["step"], dtype=int)
    sqrt_eps = _runs.ramp_sqrt_eps(table)
    out = []
    for block, step in zip(blocks[1:], steps[1:]):
        row = np.flatnonzero(tap_steps == step)
        if not len(row):
            continue
        fit = profile_gradient(block[:, 0] / r, block[:, 2], window=window, boundary=bc)
        out.append(LevelAlpha(int(step), _runs.RAMP_BRANCHES[int(table["branch"][row[-1]])],
                              float(sqrt_eps[row[-1]]), float(fit.params["alpha"]),
                              float(fit.errors["alpha"]), window))
    return out


#: the two packings of the top panel: (tag, index of its profile block)
PACKINGS = (("initial", 0), ("final", -1))


@dataclass(frozen=True)
class VerticalProfiles:
    """The top panel: the profiles at one eps, their eq. 7 fits and their gradients alpha."""

    eps: float
    seeds: int
    initial: Series
    final: Series
    #: (lo, hi) of the gradient window, in R
    window: tuple
    #: tag ('initial', 'final') -> the eq. 7 curve over z >= the window's bottom; a failed fit
    #: is absent
    law_curves: dict
    #: tag -> eq. 7 parameter name -> Value (n = 1 determined, 0 not)
    eq7: dict
    #: tag -> alpha over seeds ('final': one seed, the error within its packing)
    alpha: dict
    #: each seed's final alpha and its lateral jackknife (two seeds or more, else None)
    alpha_seeds: Series = None
    #: taps of the runs (the legend's "after N taps"; None in CSVs written before it)
    taps: int = None

    def rows(self):
        out = [("a", "initial", self.initial), ("a", "final", self.final)]
        for tag, curve in self.law_curves.items():
            out.append(("a", f"fit:{tag}", curve))
            out += [("params", f"{tag}:eq7_{name}", v) for name, v in self.eq7[tag].items()]
        out += [("params", f"{tag}:alpha", v) for tag, v in self.alpha.items()]
        if self.alpha_seeds is not None:
            out.append(("params", "final:alpha:seeds", self.alpha_seeds))
        x, n = self.eps, self.seeds
        if self.taps is not None:
            out.append(("params", "taps", Value(x, float(self.taps), np.nan, n)))
        return out + [("params", "window_lo", Value(x, self.window[0], np.nan, n)),
                      ("params", "window_hi", Value(x, self.window[1], np.nan, n)),
                      ("params", "eps", Value(x, self.eps, np.nan, n))]

    @classmethod
    def from_rows(cls, rows):
        initial, final = rows.take("a", "initial"), rows.take("a", "final")
        curves, eq7 = {}, {}
        for tag, _ in PACKINGS:
            if rows.has("a", f"fit:{tag}"):
                curves[tag] = rows.take("a", f"fit:{tag}")
                eq7[tag] = {name: rows.take_value("params", f"{tag}:eq7_{name}")
                            for name in ProfileLaw.names}
        alpha = {tag: rows.take_value("params", f"{tag}:alpha") for tag, _ in PACKINGS}
        seeds = rows.take_optional("params", "final:alpha:seeds")
        lo, hi = rows.take_value("params", "window_lo"), rows.take_value("params", "window_hi")
        eps = rows.take_value("params", "eps")
        taps = rows.take_value("params", "taps") if rows.has("params", "taps") else None
        return cls(eps.value, eps.n, initial, final, (lo.value, hi.value), curves, eq7, alpha,
                   seeds, None if taps is None else int(taps.value))


@dataclass(frozen=True)
class Fig6Result(FigureResult):
    """The numbers of Fig. 6 (CSV schema: module text)."""

    #: the top panel; None when the campaign has no F.B.C. constant-eps run
    profiles: VerticalProfiles
    #: alpha after the taps of the bell's runs against sqrt(eps) (None: no such runs)
    bell: Series = None
    #: branch -> alpha at the end of every level of the ramp against sqrt(eps)
    ramp: dict = None

    def rows(self):
        out = [] if self.profiles is None else self.profiles.rows()
        if self.bell is not None:
            out.append(("b", "bell:alpha", self.bell))
        return out + [("b", f"ramp:{branch}", s) for branch, s in (self.ramp or {}).items()]

    @classmethod
    def from_rows(cls, rows):
        profiles = VerticalProfiles.from_rows(rows) if rows.has("a", "initial") else None
        ramp = {branch: rows.take("b", f"ramp:{branch}") for branch in _runs.RAMP_BRANCHES
                if rows.has("b", f"ramp:{branch}")}
        return cls(profiles, rows.take_optional("b", "bell:alpha"), ramp)


def _eq7_fits(zb, means, window, eps):
    """(curves, parameters) of eq. 7 fitted to each seed-averaged profile of ``means`` (tag ->
    mean profile); a profile the law cannot fit is left out."""
    law = ProfileLaw(window=window)
    curves, params = {}, {}
    for tag, mean in means.items():
        try:
            fit = law.fit(zb, mean)
        except (ValueError, RuntimeError):
            continue
        keep = zb >= window[0]
        curves[tag] = Series.of(zb[keep], fit(zb[keep]), None, 0)
        params[tag] = {name: Value(eps, value, fit.errors.get(name, np.nan),
                                   int(bool(fit.determined)))
                       for name, value in fit.params.items()}
    return curves, params


def _alphas(campaign, specs, window, eps):
    """(tag -> alpha over seeds, each seed's final alpha with its jackknife or None): the
    gradient of each seed's initial and final profile in ``window``."""
    alpha, seeds = {}, None
    for tag, index in PACKINGS:
        alphas, withins = [], []
        for spec in specs:
            blocks = _runs.profile(campaign, spec, "profile_z.dat").blocks
            z = blocks[index, :, 0] / radius(spec)
            alphas.append([profile_gradient(z, blocks[index, :, 2], window=window)
                           .params["alpha"]])
            if tag == "final":                   # the error within each seed's packing
                dump = final_dump(_runs.run_dir(campaign, spec), spec.variables["taps"])
                withins.append(_alpha_jackknife(dump, radius(spec), blocks[-1, :, 0], window,
                                                BC))
        m, s, n = P.seed_stats(alphas)
        if tag == "final" and len(specs) == 1:   # one seed: the error within its packing
            s = [np.nan if withins[0] is None else withins[0]]
        alpha[tag] = Value.of_stats(eps, (m, s, n))
        if tag == "final" and len(specs) >= 2 and all(w is not None for w in withins):
            seeds = Series.of([eps] * len(specs), [a[0] for a in alphas], withins, 1)
    return alpha, seeds


def vertical_profiles(campaign):
    """The top panel (:class:`VerticalProfiles`) at the eps nearest to the paper's 0.1;
    ValueError when the campaign has no F.B.C. constant-eps run."""
    eps, specs = nearest_eps_runs(campaign)
    window = gradient_window(campaign, specs)
    zb, im, isem, i_n, fm, fsem, f_n = profiles(campaign, specs, "profile_z.dat")
    curves, eq7 = _eq7_fits(zb, {"initial": im, "final": fm}, window, eps)
    alpha, seeds = _alphas(campaign, specs, window, eps)
    return VerticalProfiles(eps, len(specs), Series.of(zb, im, isem, i_n),
                            Series.of(zb, fm, fsem, f_n), window, curves, eq7, alpha, seeds,
                            int(specs[0].variables["taps"]))


def analyse(campaign):
    """Fig. 6 from the campaign: the top panel when it has the F.B.C. runs, the bottom one
    when it has the bell's runs or the ramp."""
    bell = alpha_bell(campaign)
    ramp = ramp_alpha(campaign)
    try:
        top = vertical_profiles(campaign)
    except ValueError:
        if bell is None and not ramp:
            raise
        top = None
    return Fig6Result(top, None if bell is None else Series.of(*bell),
                      {branch: Series.of(*columns) for branch, columns in ramp.items()})


def plot(result, settings=None):
    """The figure of a :class:`Fig6Result` (drawing only)."""
    bottom = result.bell is not None or bool(result.ramp)
    fig, axes = P.new_figure((result.profiles is not None) + bottom, 1, height=4.0)
    final = P.after_taps(None if result.profiles is None else result.profiles.taps, settings)
    if result.profiles is not None:
        _profile_panel(axes[0], result.profiles, final)
    if bottom:
        _bell_panel(axes[-1], result.bell, result.ramp or {}, final)
    return P.finish_figure(fig, settings, P.plotted_seeds(result))


def _profile_panel(ax, top, final):
    ax.plot(top.initial.x, top.initial.mean, ":", color="k", label="initial packing")
    ax.plot(top.final.x, top.final.mean, "-", color="C3", label=final)
    err = np.nan_to_num(top.final.err)
    ax.fill_between(top.final.x, top.final.mean - err, top.final.mean + err, color="C3",
                    alpha=0.25, lw=0)
    for tag, color in (("initial", "k"), ("final", "C3")):
        if tag in top.law_curves:
            curve = top.law_curves[tag]
            ax.plot(curve.x, curve.mean, "-", lw=0.6, color=color, alpha=0.7)
    for edge in top.window:
        ax.axvline(edge, color="0.6", lw=0.6, ls="--")
    ax.set_xlabel("z/R")
    ax.set_ylabel(r"$\Phi$")
    ax.set_ylim(bottom=0)
    P.legend(ax, fontsize=8,
              title=f"F.B.C., eps = {P.fmt_eps(top.eps)}; dashed: gradient window",
              title_fontsize=7)


def _bell_panel(ax, bell, ramp, final):
    if bell is not None:
        ax.errorbar(bell.x, bell.mean, yerr=np.nan_to_num(bell.err), marker="s", ls="-",
                    color="k", capsize=2, label=final)
    for branch, series in ramp.items():
        marker, label = _runs.RAMP_BRANCH_STYLE[branch]
        ax.errorbar(series.x, series.mean, yerr=np.nan_to_num(series.err), marker=marker,
                    mfc="none", ls="-", lw=0.8, capsize=2, label=f"ramp: {label}")
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel(r"$\varepsilon^{1/2}$")
    ax.set_ylabel(r"$\alpha$ (P.B.C.)")
    if ramp:
        P.legend(ax, fontsize=7, title="open: end of every level of the ramp",
                  title_fontsize=7)


def draw(campaign, out_dir):
    """Fig. 6's PNG and CSV in ``out_dir``; returns their paths."""
    return analyse(campaign).save_with_png(
        plot, out_dir, NAME, P.figure_settings(campaign, figure_runs(campaign)))


def figure_runs(campaign):
    """The runs Fig. 6 draws: the F.B.C. runs of its top panel, the bell's constant-eps
    P.B.C. runs and the ramp of its bottom panel."""
    out = []
    try:
        out += _profile_runs.nearest_eps_runs(campaign)[1]
    except ValueError:
        pass
    try:
        out += [s for group in _runs.constant_eps_groups(campaign, _steady_state.BC).values()
                for s in group]
    except ValueError:
        pass
    return out + _runs.select(campaign, "ramp_", bc=_steady_state.BC)
