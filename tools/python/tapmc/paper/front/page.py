# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The page of the front, doc/front.rst, and its figure: text and drawing only, from a computed
:class:`~tapmc.paper.front.analysis.Front`. :func:`write_page` computes the front, then writes
the figure and its CSV (one per N the reference has run at), front_summary.csv and the page,
each through a temporary file: an error leaves every committed file as it was."""

import math
import os

from .._plotting import FigureTable, finish_figure, legend, new_figure, write_figure
from .._rst import simple_table
from ..scales import SCALES
from . import data
from .analysis import Front, worst_bias, worst_bound, worst_trend
from .settings import (DEFAULT, PRESET_PURPOSE, PURPOSES, REFERENCE, SETTINGS, SIZES,
                       STEADY_LAST, TAPS, TIMES, BOUNDED, box_side_R, lammps_line,
                       setting_named, time_window)
from .summary import SUMMARY, summary_text
from .text import plus_minus, seeds_text
from ...stats import beyond, t_quantile_of_mean

PAGE = os.path.join("doc", "front.rst")
FIGURE = "front"
#: two standard errors: how much closer to the reference a d_max must be to beat R/5
DMAX_CLOSER_SE = 2


def figure_table(front, N):
    """The numbers drawn by :func:`plot` (a _plotting.FigureTable): panel a/b, bias of the
    steady <Phi^c> against CPU s per tap at each eps (series = setting, x = cost);
    panel c, bias of <Phi^c> against the tap count at the first eps (x = taps; the steady
    window is drawn at x = 2 TAPS)."""
    table = FigureTable()
    for panel, eps in zip("ab", front.eps_values):
        for r in front.rows(N=N, eps=eps):
            table.add(panel, r.setting, r.cpu_per_tap.mean, r.biases["phi_c_steady"].mean,
                      r.biases["phi_c_steady"].se, r.paired_seeds)
    first = front.eps_values[0]
    for r in front.rows(N=N, eps=first):
        xs = list(TIMES) + [2 * TAPS]
        table.add("c", r.setting, xs,
                  [r.biases[f"phi_c_t{t}"].mean for t in TIMES] + [r.biases["phi_c_steady"].mean],
                  [r.biases[f"phi_c_t{t}"].se for t in TIMES] + [r.biases["phi_c_steady"].se],
                  r.paired_seeds)
    return table


#: the three panels stacked (a, b, c from the top): side by side they made a figure of 1400 to
#: 1560 pixels that the page showed at about 820, its legends at 5 pixels
FIGURE_LAYOUT = {"nrows": 3, "ncols": 1, "height": 2.6, "width": 5.0}


def plot(front, N, ax=None):
    """Panels a, b (bias against cost at each eps) and c (bias against taps); `ax`: three
    axes, or None for a new figure. Returns the axes; their legends find their places off
    the data when the figure is laid out (:func:`figure`, _plotting.finish_figure)."""
    if ax is None:
        _, ax = new_figure(**FIGURE_LAYOUT)
    table = figure_table(front, N)
    by = {}
    for panel, series, x, mean, sem, n in table.rows:
        by.setdefault((panel, series), []).append((x, mean, sem))
    names = list(SETTINGS)
    colors = {name: "C%d" % (i % 10) for i, name in enumerate(names)}
    for (panel, series), pts in by.items():
        pts = [p for p in pts if p[1] == p[1]]  # no bias yet where the reference has not run
        if not pts:
            continue
        a = ax["abc".index(panel)]
        xs, ms, ss = zip(*pts)
        ss = [0.0 if s != s else s for s in ss]
        style = dict(color=colors[series], capsize=2, label=series)
        if panel == "c":
            a.errorbar(xs, ms, yerr=ss, marker="o", ms=3, lw=1, **style)
        else:
            a.errorbar(xs, ms, yerr=ss, marker="o", ms=4, linestyle="none", **style)
    for i, eps in enumerate(front.eps_values[:2]):
        ax[i].set_title(f"N = {N}, eps = {eps:g}: taps {TAPS - STEADY_LAST + 1}-{TAPS}", fontsize=9)
        ax[i].set_xscale("log")
        ax[i].set_xlabel("CPU s per tap (one core)")
        ax[i].set_ylabel(f"bias of <Phi^c> vs {REFERENCE}")
    ax[2].set_title(f"N = {N}, eps = {front.eps_values[0]:g}", fontsize=9)
    ax[2].set_xscale("log")
    ax[2].set_xlabel(f"taps (steady window drawn at {2 * TAPS})")
    ax[2].set_ylabel("bias of <Phi^c>")
    for a in ax:
        a.axhline(0.0, color="k", lw=0.5)
    for a in ax:  # off the data, beside the axes where no place inside is free
        legend(a, fontsize=6, title="redeposition setting", title_fontsize=6)
    return ax


def settings_line(front, N):
    """The settings every panel shares (the figure's top line): N, the box, the taps and the
    seeds; eps is in each panel's title, eta and the stop rule are the series."""
    seeds = sorted({int(n) for *_, n in figure_table(front, N).rows})
    counted = (seeds_text(seeds[0]) if seeds[0] == seeds[-1]
               else f"{seeds[0]} to {seeds_text(seeds[-1])}")
    side = box_side_R(N)
    return (f"N = {N}, box {side:g}R x {side:g}R; {TAPS} taps per run; {counted} per "
            f"setting, paired with those of the reference {REFERENCE}")



def figure(front, N):
    """The front's figure at N (:func:`plot`), its settings on top and its legends placed off
    the data: a matplotlib figure, not saved."""
    fig, ax = new_figure(**FIGURE_LAYOUT)
    plot(front, N, ax=ax)
    return finish_figure(fig, settings_line(front, N))


def _write_figure(front, N, png, csv_path):
    return write_figure(figure(front, N), png, figure_table(front, N), csv_path)


def _dmax_lines(front, N):
    """The paper's d_max = R/5 ("an intermediate value", section II) against R/10 and R/2 at the
    default eta, from the rows at the first eps where all three ran."""
    for eps in front.eps_values:
        base = front.rows(N=N, eps=eps, setting=DEFAULT)
        alts = [front.rows(N=N, eps=eps, setting=n) for n in ("dmax R/10", "dmax R/2")]
        if not base or not all(alts):
            continue
        b = base[0]
        parts, beaten = [], []
        for (a,) in alts:
            ratio = a.cpu_per_tap.mean / b.cpu_per_tap.mean
            parts.append(f"{a.setting[5:]} costs {ratio:.2f} times its CPU time per tap "
                         f"({a.sweeps_per_tap:.0f} sweeps) and leaves <Phi^c> "
                         f"{plus_minus(a.biases['phi_c_steady'].mean, a.biases['phi_c_steady'].se)} steady")
            se = math.hypot(a.biases["phi_c_steady"].se, b.biases["phi_c_steady"].se)
            closer = abs(b.biases["phi_c_steady"].mean) - abs(a.biases["phi_c_steady"].mean) > DMAX_CLOSER_SE * se
            if ratio <= 1.0 and closer:
                beaten.append(a.setting[5:])
        verdict = ("so a d_max of " + " and ".join(beaten) + " redeposits better at no more cost "
                   "than the paper's R/5" if beaten else
                   "neither is both cheaper and closer to the reference (by two standard errors) "
                   "than the paper's R/5")
        return [f"**d_max** (section II: R/5 is \"an intermediate value\"), at eps = {eps:g} and "
                f"eta = {b.eta}: against R/5 ({b.sweeps_per_tap:.0f} sweeps per tap, "
                f"<Phi^c> {plus_minus(b.biases['phi_c_steady'].mean, b.biases['phi_c_steady'].se)} steady), " + "; ".join(parts) + f": {verdict}.", ""]
    return []


def _default_lines(front, N, recs):
    """A sentence on the package default at N when no purpose recommends it: its bias, its two
    bounds against the tolerances, and its cost against the publication setting's."""
    rows = front.rows(N=N, setting=DEFAULT)
    if not rows or any(r.setting == DEFAULT for r in recs.values()) or "publication" not in recs:
        return []
    bound, trend = worst_bound(DEFAULT, rows), worst_trend(DEFAULT, rows)
    cpu = sum(r.cpu_per_tap.mean for r in rows) / len(rows)
    return [f"The package default, *{DEFAULT}*, is recommended for no purpose at N = {N}: its "
            f"worst bias of <Phi^c> is {worst_bias(DEFAULT, rows):+.4f}, its 95 % bounds are "
            f"{bound:.4f} on the bias and {trend:.4f} on its change with eps and taps "
            f"(tolerances {PURPOSES[0][1]:g} and {PURPOSES[1][1]:g}), at "
            f"{cpu / recs['publication'].cpu_per_tap:.2f} times the CPU time per tap of "
            f"*{recs['publication'].setting}*.", ""]


def _preset_lines(front):
    """The presets of tapmc-paper, each made for a purpose: its setting, that setting's worst
    95 % bound and the setting this front recommends for the purpose, at the preset's own N
    when the front has it, else at the nearest N it has."""
    body = []
    for preset, purpose in PRESET_PURPOSE.items():
        scale = SCALES[preset]
        N = min(front.compared_sizes or front.sizes, key=lambda n: (abs(math.log(n / scale.N)), n))
        name = setting_named(scale.eta)
        rows = front.rows(N=N, setting=name) if name else []
        worst = worst_bound(name, rows) if name else math.nan
        rec = front.recommendations(N).get(purpose)
        recommended = rec.setting if rec else None
        ratio = (rec.cpu_per_tap / (sum(r.cpu_per_tap.mean for r in rows) / len(rows))
                 if rec and rows else math.nan)
        body.append([preset, f"N = {scale.N}, {scale.taps} taps", f"N = {N}", purpose,
                     name or f"eta {scale.eta:g} (not on the front)",
                     "n/a" if worst != worst else "%.4f" % worst, recommended or "none yet",
                     "yes" if recommended == name else "no",
                     "n/a" if ratio != ratio else "%.1f" % ratio])
    return ["**The presets of tapmc-paper** (:doc:`tapmc-paper`) against the recommendations, "
            "at the preset's N or the nearest N measured (last column: the CPU time per tap of "
            "the recommended setting over the preset's, mean over eps):", ""] + simple_table(
        ["preset", "scale", "front at", "purpose", "its setting", "its worst 95 % bound",
         "recommended", "same", "CPU ratio"], body) + [""]


def figure_name(N):
    """File name (no extension) of the figure and CSV of the front at N."""
    return FIGURE if N == SIZES[0] else f"{FIGURE}_N{N}"


def _intro_lines(runs_note):
    return [".. TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.",
            ".. Generated by 'build/tapmc-paper front' from doc/validation/front: do not edit.", "",
            "Run time against error of the redeposition", "=" * 42, "",
            "Every setting of :doc:`fix mc/settle <fix_mc_settle>` that trades accuracy for time, "
            "measured on the paper's protocol (``examples/paper/in.constant_eps``: a fresh "
            f"Jullien-Meakin packing, periodic sides, {TAPS} taps at constant eps). Each run is one "
            "setting and one seed; the seed fixes the initial packing and the moves, so settings "
            "are compared seed by seed: *bias* is the mean over the seeds of (setting - reference) "
            "on the same seed, with its standard error, and the *95 % bound* is \\|bias\\| + t(0.975, "
            "seeds - 1) x its standard error, the largest bias the seeds allow at 95 % confidence. "
            f"The reference is *{REFERENCE}* (stop drift, eta = 1e-7: the drift of <Z> per sweep "
            "averaged over 32 checks, plus two standard errors, below 1e-7 <Z>). Cost is the CPU "
            "time of the lmp process per tap (deposition included, one core) and the sweeps "
            f"(N trial moves) per tap. Steady: the mean over the last {STEADY_LAST} taps; "
            "t = a-b: the mean over taps a to b (one tap's value scatters by the tap-to-tap "
            "fluctuation, which a window averages down).", "",
            runs_note, ""]


def _eps_table_lines(rows):
    """The table of every setting at one N and eps: cost and paired biases."""
    seeds_ = max(r.seeds for r in rows)
    lines = [f"eps = {rows[0].eps:g} ({seeds_text(seeds_)}; bias of each quantity against "
             f"*{REFERENCE}*, mean +- standard error):", ""]
    w100, w1000 = time_window(100), time_window(TAPS)
    header = ["setting", "sweeps/tap", "CPU s/tap", "<Phi^c> t=1",
              "<Phi^c> t=%d-%d" % w100, "<Phi^c> t=%d-%d" % w1000, "<Phi^c> steady",
              "Phi_b steady", "<Z> steady",
              "95 % bound"]
    body = []
    for r in rows:
        bound = max((r.biases[q].bound for q in BOUNDED), default=math.nan)
        body.append([r.setting + (f" ({seeds_text(r.seeds)})" if r.seeds != seeds_ else ""),
                     "%.0f" % r.sweeps_per_tap, "%.3f" % r.cpu_per_tap.mean,
                     plus_minus(r.biases["phi_c_t1"].mean, r.biases["phi_c_t1"].se),
                     plus_minus(r.biases["phi_c_t100"].mean, r.biases["phi_c_t100"].se),
                     plus_minus(r.biases["phi_c_t1000"].mean, r.biases["phi_c_t1000"].se),
                     plus_minus(r.biases["phi_c_steady"].mean, r.biases["phi_c_steady"].se),
                     plus_minus(r.biases["phi_b_steady"].mean, r.biases["phi_b_steady"].se),
                     plus_minus(r.biases["Z_steady"].mean, r.biases["Z_steady"].se, digits=3),
                     "reference" if r.setting == REFERENCE else
                     ("n/a" if bound != bound else "%.4f" % bound)])
    return lines + simple_table(header, body) + [""]


def _still_moves(r):
    """Whether the reference's <Phi^c> still moves into the steady window, as a clause."""
    if r.seeds < 2:
        return "one seed cannot say whether it still moves."
    if not beyond(r.rise.mean, r.rise.se, r.seeds - 1):
        return (f"no change resolved at 95 % confidence "
                f"(t = {t_quantile_of_mean(r.seeds):.3g}).")
    return "the packing still compacts, so the steady column is the mean of that window, not a limit."


def _reference_lines(r):
    """The reference's own values at one N and eps."""
    return [f"Reference values (mean +- standard error over {seeds_text(r.seeds)}): "
            f"<Phi^c> = {plus_minus(r.values['phi_c_t1'].mean, r.values['phi_c_t1'].se, sign=False)} after one tap, "
            f"{plus_minus(r.values['phi_c_t1000'].mean, r.values['phi_c_t1000'].se, sign=False)} over taps "
            "%d-%d, " % time_window(TAPS) +
            f"{plus_minus(r.values['phi_c_steady'].mean, r.values['phi_c_steady'].se, sign=False)} steady; "
            f"Phi_b = {plus_minus(r.values['phi_b_steady'].mean, r.values['phi_b_steady'].se, sign=False)} steady; "
            f"<Z> = {plus_minus(r.values['Z_steady'].mean, r.values['Z_steady'].se, digits=3, sign=False)} steady. "
            f"From taps {TAPS - 2 * STEADY_LAST + 1}-{TAPS - STEADY_LAST} to the steady "
            f"window <Phi^c> changes by {plus_minus(r.rise.mean, r.rise.se)}: "
            + _still_moves(r), ""]


def _check_lines(front, N):
    """The tighter settings against the reference at N."""
    checks = front.reference_check(N)
    if not checks:
        return []
    lines = ["**Is the reference converged?** Each tighter setting against it (the "
             "quantities whose 95 % interval of the bias excludes zero, out of those "
             "compared: every observable at tap 1, around taps 10, 100 and 1000 and steady):", ""]
    for c in checks:
        lines.append(f"- *{c.setting}* at eps = {c.eps:g}, {c.paired_seeds} paired seeds: "
                     + (f"all {c.compared} agree with the reference." if not c.differing else
                        f"{len(c.differing)} of {c.compared} differ: {', '.join(c.differing)}."))
    return lines + [""]


_RECOMMENDATION_TEXT = (
    "**Recommended settings**: for each purpose the cheapest setting, run at every "
    "eps above, whose 95 % bounds on <Phi^c> over taps "
    f"{time_window(100)[0]}-{time_window(100)[1]} and steady are within the "
    "purpose's tolerance at every eps. *Publication* bounds the bias itself by "
    "0.001, the last digit the paper quotes. *Exploration* compares curves run at "
    "one setting: a bias common to every eps and tap shifts all curves alike, so it "
    "bounds by 0.003 (a tenth of the paper's compaction over 4000 taps at eps = "
    "0.0225) the part of the bias that changes with eps or with the tap count "
    "(the paired difference of the biases at two eps or two windows, seed by "
    "seed), and states the bias. *Smoke test*: "
    "the cheapest setting, its bias stated. The line to paste is for spheres of "
    "radius 0.5 on a floor at z = 0; ``tapmc-paper plan`` prices a study with "
    "each.")


def _recommendation_lines(front, N, recs):
    """The table of the recommended settings at N, and the package default's sentence."""
    body = []
    for purpose, _, _ in PURPOSES:
        if purpose not in recs:
            body.append([purpose, "none meets it yet", "", "", "", "", ""])
            continue
        rec = recs[purpose]
        criterion = {"bias": "bias", "trend": "its change"}.get(rec.criterion, "-")
        bound = rec.worst_bound if rec.criterion != "trend" else rec.worst_trend
        body.append([purpose, rec.setting,
                     "-" if rec.tolerance is None else f"{criterion} <= {rec.tolerance:g}",
                     "0 (reference)" if rec.setting == REFERENCE else
                     "n/a" if bound != bound else "%.4f" % bound,
                     "%+.4f" % rec.worst_bias, "%.3f" % rec.cpu_per_tap,
                     "``" + lammps_line(rec.setting, N) + "``"])
    return ([_RECOMMENDATION_TEXT, ""]
            + simple_table(["purpose", "setting", "bound on", "its worst 95 % bound",
                         "worst bias of <Phi^c>", "CPU s/tap (mean over eps)",
                         "fix mc/settle"], body) + [""]
            + _default_lines(front, N, recs))


def _figure_lines(front, N):
    return [f".. image:: validation/front/{figure_name(N)}.png", "",
            f"Top, middle: bias of the steady <Phi^c> (taps {TAPS - STEADY_LAST + 1}-{TAPS}) "
            f"against the CPU time per tap "
            f"(error bars: standard error of the paired bias). Bottom: the bias against the "
            f"tap count at eps = {front.eps_values[0]:g} (the steady window at {2 * TAPS}). "
            f"Data: ``doc/validation/front/{figure_name(N)}.csv``.", ""]


def _size_lines(front, N):
    """The section of the page on one N."""
    title = f"N = {N} (box {box_side_R(N):g}R x {box_side_R(N):g}R)"
    lines = [title, "-" * len(title), ""]
    for eps in front.eps_values:
        rows = front.rows(N=N, eps=eps)
        if not rows:
            continue
        lines += _eps_table_lines(rows)
        ref = front.rows(N=N, eps=eps, setting=REFERENCE)
        if ref:
            lines += _reference_lines(ref[0])
    lines += _dmax_lines(front, N)
    lines += _check_lines(front, N)
    if N not in front.compared_sizes:
        return lines + [f"The reference has not run at N = {N} yet: no bias, recommendation or "
                        "figure at this N.", ""]
    recs = front.recommendations(N)
    if recs:
        lines += _recommendation_lines(front, N, recs)
    return lines + _figure_lines(front, N)


def render_rst(front, runs_note):
    """The page doc/front.rst of a computed Front; `runs_note` says which binary and machine."""
    lines = _intro_lines(runs_note)
    for N in front.sizes:
        lines += _size_lines(front, N)
    lines += _preset_lines(front)
    for N in SIZES:
        if N not in front.sizes:
            lines += [f"N = {N}: not measured yet (``build/tapmc-paper front run --N {N} "
                      "--jobs 2``).", ""]
    lines += ["Reproduce: ``build/tapmc-paper front run --jobs 2`` (resumable; adds the "
              "runs missing from ``doc/validation/front/runs.csv``), then ``build/tapmc-paper "
              "front`` (this page, its figure and ``tools/python/tapmc/paper/front_summary.csv``, "
              "which the validation reports read to state the bias of their settings).", ""]
    return "\n".join(lines)


def runs_note(data_dir):
    """What ran the front (from meta.json), as a sentence."""
    m = data.read_meta(data_dir)
    if m is None:
        return "(No meta.json: the binary and machine of these runs are not recorded.)"
    return (f"Runs: ``lmp_tapmc`` built from commit {m['commit']}, on {m['machine']} "
            f"({m['cores']} cores, {m['jobs']} runs at a time at nice {m['nice']}, other "
            f"simulations at nice 19 on the same cores), started {m['started']}.")


def _part(path):
    """The temporary name of `path` (same folder and suffix: matplotlib picks the format
    from it)."""
    root, ext = os.path.splitext(path)
    return f"{root}.part{ext}"


def _write_whole(paths, write):
    """`write(parts)` writes the temporary files of `paths`; each is renamed to its path only
    when all were written, and none is left behind."""
    parts = [_part(p) for p in paths]
    try:
        write(*parts)
        for part, path in zip(parts, paths):
            os.replace(part, path)
    finally:
        for part in parts:
            if os.path.exists(part):
                os.remove(part)


def _write_text(path, text):
    def write(part):
        with open(part, "w", newline="") as f:
            f.write(text)
    _write_whole([path], write)


def write_page(root, data_dir=None):
    """Writes doc/front.rst, its figures and their CSVs, and the package summary under `root`
    (the repository); returns the page's path. Everything is computed before anything is
    written, and each file is written whole or not at all."""
    root = os.fspath(root)
    data_dir = data_dir or os.path.join(root, data.DATA_DIR)
    fr = Front(data_dir).compute()
    note = runs_note(data_dir)
    page_text = render_rst(fr, note)
    summary = summary_text(fr.summary_rows())
    for N in fr.compared_sizes:
        name = figure_name(N)
        paths = [os.path.join(data_dir, name + ext) for ext in (".png", ".csv")]
        _write_whole(paths, lambda png, csv_path: _write_figure(fr, N, png, csv_path))
    package = os.path.join(root, "tools", "python", "tapmc", "paper")
    os.makedirs(package, exist_ok=True)
    _write_text(os.path.join(package, os.path.basename(SUMMARY)), summary)
    page = os.path.join(root, PAGE)
    os.makedirs(os.path.dirname(page), exist_ok=True)
    _write_text(page, page_text)
    return page
