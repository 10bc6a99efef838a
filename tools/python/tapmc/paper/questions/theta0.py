# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""theta0: does theta0 = pi/4 give the largest compaction rate, and does a much smaller
theta0 decompact (section II)? From the same fresh packings (N = 1024, the paper's bed height
on a 16R base, P.B.C., eps = 0.0225, the default eta) 100 taps at seven widths theta0 of the
trial moves' angular distribution (eq. 1), pi/16 to pi/2: <Phi^c> at t = 0 and its mean over
taps 91-100 per seed (theta0.csv). --N sets the spheres (box 32R sqrt(N/4096), the paper's
bed height; the CSV then ends in _N<N>); a scan started again skips the runs its CSV has.
--stop drift (with --eta, default 1e-7: the front's reference) repeats it with a converged
redeposition, into theta0_drift.csv. --theta-law solid reads P(theta) of eq. 1 per unit solid
angle (fix mc/settle theta_law solid; CSV tag _solid); --theta-law exponential or linear scans
section II's alternative laws of the same width (CSV tags _exponential, _linear: the claim
theta-law-shape sets them against eq. 1's scan of the same N and stop); --wide scans instead
the widths beyond the paper's truncation pi/2 (3/4 pi, pi, 30 pi: the flat limit; CSV tag
_wide). --widths F ... scans only those widths (multiples of pi, e.g. 0.0625 0.25 0.5: the
ends of the scan and the paper's value, what theta-law-shape reads, at a quarter of the
cost of N = 4096's full scan); the CSV is the same scan's, so a later full scan adds to it."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .. import _plotting, _runs
from .._rst import list_table
from ..claims import (STATISTICS, ReportData, fmt, load_register, scan_settings, scan_table,
                      verdict)
from ..claims.scan_tables import ALTERNATIVE_THETA_LAWS
from ..claims.scans import mean_angle
from . import knob_scan
from .common import QuestionError, read_csv

NAME = "theta0"


def add_arguments(parser):
    knob_scan.add_arguments(parser)
    parser.add_argument("--theta-law", choices=("angle", "solid", "exponential", "linear"),
                        default="angle",
                        help="fix mc/settle's theta_law, the law of the moves' angle: angle "
                             "(eq. 1 as a density in theta), solid (per unit solid angle), "
                             "exponential or linear (section II's alternative laws of the same "
                             "width); another law than angle adds _<law> to the CSV's name "
                             "(default %(default)s)")
    parser.add_argument("--wide", action="store_true",
                        help="scan instead the widths beyond the paper's truncation pi/2 "
                             "(3/4 pi, pi, 30 pi: the flat limit); adds _wide to the CSV's name")
    parser.add_argument("--widths", type=float, nargs="+", metavar="F",
                        help="only these widths theta0 / pi (default: the scan's seven, or the "
                             "wide scan's three)")


def measure(args):
    law = args.theta_law
    tags = ([law] if law != "angle" else []) + (["wide"] if args.wide else [])
    widths = args.widths or (knob_scan.THETA0_WIDE_PI if args.wide else knob_scan.THETA0_PI)
    bad = [f for f in widths if not 0.0 < f * np.pi <= 1e3]
    if bad:
        raise QuestionError(f"--widths {bad[0]:g}: theta0 = {bad[0]:g} pi is outside fix "
                            "mc/settle's range (0, 1000] rad")
    knob_scan.knob_scan(args, "theta0_over_pi", [(f, np.pi * f) for f in widths], "theta0",
                        extra_keys=f"theta_law {law}" if law != "angle" else "",
                        extra_tags=tags)
    if law in ALTERNATIVE_THETA_LAWS or law == "angle":
        for path in write_laws_figure(args.out):
            print(f"wrote {path}")


def law_scans(folder):
    """Per size tag ("", "_N4096"): eq. 1's scan and section II's alternative laws scanned at
    the same size, {"angle": rows, "exponential": rows, ...}; sizes without an alternative
    law are left out."""
    folder = Path(folder)
    out = {}
    for size in ("", "_N4096"):
        scans = {law: read_csv(folder / f"theta0_{law}{size}.csv")
                 for law in ALTERNATIVE_THETA_LAWS
                 if (folder / f"theta0_{law}{size}.csv").is_file()}
        if scans and (folder / f"theta0{size}.csv").is_file():
            out[size] = {"angle": read_csv(folder / f"theta0{size}.csv"), **scans}
    return out


def render_laws(folder):
    """Section II's alternative laws of theta against eq. 1's, per size: the compaction over the
    scan's taps at every width with the mean angle <theta> of the moves there (is the width,
    read as <theta>, the pertinent parameter?), and the verdict of the claim theta-law-shape."""
    lines = []
    claim = next(c for c in load_register() if c.id == "theta-law-shape")
    for size, scans in law_scans(folder).items():
        eq1 = scans["angle"]
        tables = {law: {r["value"]: r for r in scan_table(rows, "theta0")}
                  for law, rows in scans.items()}
        first = eq1[0]
        lines += [f"Section II's \"Poissonian and linear\" laws of theta (fix mc/settle theta_law "
                  f"exponential: exp(-theta/theta0); linear: 1 - theta/theta0 up to theta0) "
                  f"against eq. 1's Gaussian, {first['taps']} taps at eps = "
                  f"{float(first['eps']):g} from the same fresh packings (N = {first['N']}, "
                  f"P.B.C., {scan_settings(eq1)}; ``theta0{size}.csv`` and "
                  + ", ".join(f"``theta0_{law}{size}.csv``" for law in scans if law != "angle")
                  + "). Gain: <Phi^c> over the last 10 taps minus t = 0, mean ± sem over seeds; "
                  "in brackets the mean angle <theta> of the law's moves at that width:", ""]
        names = {"angle": "eq. 1 (Gaussian)", "exponential": "exponential", "linear": "linear"}
        widths = sorted(tables["angle"])
        lines += list_table(
            ["theta0"] + [names[law] for law in scans],
            [[tables["angle"][w]["name"]] +
             [f"{fmt(t[w]['gain'], t[w]['gain_sem'], True)} "
              f"({np.degrees(mean_angle(law, np.pi * w)):.1f} deg)" if w in t else "n/a"
              for law, t in tables.items()] for w in widths])
        data = ReportData({}, {}, (), {"theta0": [eq1]},
                          {f"theta0_{law}{size}": rows for law, rows in scans.items()
                           if law != "angle"})
        verdicts = [f"{m.label.split(',')[0]}: {verdict(claim, m)}"
                    + (f" at N = {first['N']}, below the paper's N (the claims' table counts it "
                       "undecided there)" if m.lacks else "")
                    for m in STATISTICS["theta_law_shape"](data, claim)]
        lines += ["", f"Verdict of ``theta-law-shape`` (rule {claim.rule}): "
                  + "; ".join(verdicts) + ".", ""]
        png = Path(folder) / LAWS_PNG.format(size=size)
        if png.is_file():
            lines += [f".. image:: {_runs.FIG_DIR}/{Path(folder).name}/{png.name}",
                      "   :alt: the compaction of each law of theta against "
                      "its width and its mean angle", ""]
    return lines


#: the figure of the laws side by side, per size tag: theta_laws[_N4096].png, and beside it
#: theta_laws[_N4096]_figure.csv, every number it draws (panel a: against theta0 / pi, b:
#: against the mean angle in degrees)
LAWS_PNG = "theta_laws{size}.png"
LAW_NAMES = {"angle": "eq. 1 (Gaussian)", "exponential": "exponential", "linear": "linear"}


def plot_laws(scans, axes=None, table=None):
    """The compaction over the scan's taps (mean ± sem over seeds) of each law against its
    width theta0 (top) and against the mean angle <theta> of its moves (bottom); ``scans``:
    one size of :func:`law_scans`; ``table``: a FigureTable that gets every plotted number.
    Returns the axes."""
    if axes is None:
        _, axes = _plotting.new_figure(nrows=2, height=2.6, width=5.0)
    for colour, (law, rows) in enumerate(scans.items()):
        scan = scan_table(rows, "theta0")
        width = np.array([r["value"] for r in scan])
        gain = 100 * np.array([r["gain"] for r in scan])
        sem = 100 * np.array([r["gain_sem"] for r in scan])
        mean = np.degrees([mean_angle(law, np.pi * w) for w in width])
        for panel, ax, x in zip("ab", axes, (width, mean)):
            _plotting.errorbars(ax, x, gain, sem, label=LAW_NAMES[law], color=f"C{colour}",
                                marker="o", ms=3)
            if table is not None:
                table.add(panel, LAW_NAMES[law], x, gain, sem, [r["n"] for r in scan])
    axes[0].set_xlabel(r"$\theta_0 / \pi$")
    axes[1].set_xlabel(r"mean angle $\langle\theta\rangle$ of the moves (degrees)")
    for ax in axes:
        ax.axhline(0.0, color="0.5", lw=0.8, ls=":")
        ax.set_ylabel(r"gain of $\langle\Phi^c\rangle$ (%)", fontsize=8)
        _plotting.legend(ax, fontsize=6)
    return axes


def write_laws_figure(folder):
    """theta_laws[_N4096].png in ``folder`` for every size of :func:`law_scans`, its settings
    on top, and beside each its CSV (every number it draws, gains in %);
    returns the PNGs' paths."""
    paths = []
    for size, scans in law_scans(folder).items():
        table = _plotting.FigureTable()
        fig = plot_laws(scans, table=table)[0].figure
        first = scans["angle"][0]
        seeds = sorted({int(r["seed"]) for rows in scans.values() for r in rows})
        _plotting.finish_figure(fig, (
            f"N = {first['N']}, box {knob_scan.box_side(int(first['N'])):g}R x "
            f"{knob_scan.box_side(int(first['N'])):g}R, "
            f"P.B.C., eps = {float(first['eps']):g}, {first['taps']} taps from "
            f"the same fresh packings, {scan_settings(scans['angle'])}; gain: <Phi^c> over the "
            f"last 10 taps minus t = 0; seeds {', '.join(map(str, seeds))}"))
        paths.append(_plotting.write_figure(fig, Path(folder) / LAWS_PNG.format(size=size),
                                            table)[0])
    return paths
