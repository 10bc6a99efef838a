# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Draw the compaction curve of a tapping run: <Phi^c> and Phi_b against the tap count, with
the paper's law (eq. 3, section III.A) fitted to <Phi^c>, and <Z>. Reads the ``fix print``
file of in.quickstart (``taps.dat``: tap Phi_b Phi_c Z sweeps) and the settings from the
LAMMPS log beside it; writes compaction.png and compaction.csv and prints a summary.

    /usr/bin/python3 plot_compaction.py [taps.dat] [--log log.lammps] [--out compaction]

Needs the Python package tapmc on the path (``PYTHONPATH=tools/python`` from the repository
root, an installed prefix, or a venv).
"""

import argparse
import re
import sys
from pathlib import Path

import numpy as np

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from tapmc import InverseLogLaw, TapmcFormatError, read_fix_print  # noqa: E402
from tapmc._legends import place_legend, replace_legends  # noqa: E402

#: the fix mc/settle threshold when the input gives no eta (its default, doc/fix_mc_settle.rst)
DEFAULT_ETA = "1e-7"
#: taps needed before eq. 3 (4 parameters) is fitted and drawn
MIN_FIT_TAPS = 8


def run_settings(log_path):
    """N, the box, eps, seed, eta and the redeposition's stop rule of a run, from the commands
    its LAMMPS log echoes (after variable substitution); values the log does not show are '?',
    fix mc/settle's defaults are marked '(default)'."""
    text = Path(log_path).read_text(errors="replace") if Path(log_path).exists() else ""
    def last(pattern):
        found = re.findall(pattern, text, re.M)
        return found[-1] if found else "?"
    settle = last(r"^fix\s+\S+\s+\S+\s+mc/settle\s+(.*)$")
    eta = re.search(r"\beta\s+(\S+)", settle) if settle != "?" else None
    stop = re.search(r"\bstop\s+(\S+)", settle) if settle != "?" else None
    dmax = re.search(r"\bdmax\s+(\S+)", settle) if settle != "?" else None
    return {"N": last(r"^create_packing\s+(\d+)"),
            "box": box_text(last(r"^region\s+\S+\s+block\s+(.*)$"),
                            last(r"^create_packing\s+\S+\s+\S+\s+(\S+)"),
                            last(r"^boundary\s+(.*)$")),
            "stop": ("?" if settle == "?" else f"stop {stop.group(1)}" if stop
                     else "stop change (default)") + (f", dmax {dmax.group(1)}" if dmax else ""),
            "eps": last(r"^fix\s+\S+\s+\S+\s+tapdilate\s+(\S+)"),
            "seed": settle.split()[0] if settle != "?" else "?",
            "eta": eta.group(1) if eta else (f"{DEFAULT_ETA} (default)" if settle != "?" else "?")}


def box_text(block, radius, boundary):
    """'box 16R x 16R (P.B.C.)': the base of the region block in sphere radii and whether its
    sides are periodic, from the log's region, create_packing radius and boundary; 'box ?'."""
    try:
        xlo, xhi, ylo, yhi = (float(v) for v in block.split()[:4])
        r = float(radius)
    except (ValueError, AttributeError):
        return "box ?"
    sides = boundary.split()[:2] if boundary != "?" else []
    bc = " (P.B.C.)" if sides == ["p", "p"] else " (walls)" if sides else ""
    return f"box {(xhi - xlo) / r:g}R x {(yhi - ylo) / r:g}R{bc}"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("taps", nargs="?", default="taps.dat", help="fix print file (default taps.dat)")
    parser.add_argument("--log", default=None, help="LAMMPS log of the run (default: log.lammps beside taps)")
    parser.add_argument("--out", default="compaction", help="output prefix (default compaction)")
    args = parser.parse_args(argv)
    log = args.log or str(Path(args.taps).with_name("log.lammps"))
    try:
        table = read_fix_print(args.taps)
        tap, phi_b, phi_c, z = (table[name] for name in ("tap", "Phi_b", "Phi_c", "Z"))
    except (OSError, TapmcFormatError, KeyError) as err:
        sys.exit(f"plot_compaction.py: {args.taps}: {err}")
    after = tap >= 1
    if not after.any():
        sys.exit(f"plot_compaction.py: {args.taps}: no tap after t = 0 to draw")
    # eq. 3 has 4 parameters: below MIN_FIT_TAPS taps the curve is drawn without it
    fit = InverseLogLaw().fit(tap[after], phi_c[after]) if after.sum() >= MIN_FIT_TAPS else None
    s = run_settings(log)
    settings = (f"N = {s['N']}, {s['box']}, eps = {s['eps']}, eta = {s['eta']}, {s['stop']}, "
                f"seed = {s['seed']}, {int(tap[-1])} taps")

    np.savetxt(args.out + ".csv", np.column_stack([tap, phi_b, phi_c, z, fit(tap) if fit else np.full(tap.shape, np.nan)]),
               delimiter=",", fmt="%.8g", header="tap,Phi_b,Phi_c,Z,Phi_c_eq3_fit", comments="")
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    left.semilogx(tap[after], phi_c[after], ".", ms=3, label=r"$\langle\Phi^c\rangle$ (bed mean, floor band corrected)")
    left.semilogx(tap[after], phi_b[after], ".", ms=3, label=r"$\Phi_b$ (bottom slab, 4R)")
    if fit:
        left.semilogx(tap[after], fit(tap[after]), "k-", lw=1, label="eq. 3 fitted to " + r"$\langle\Phi^c\rangle$")
    left.set_xlabel("tap t")
    left.set_ylabel("packing fraction")
    place_legend(left, later=True, fontsize=8)
    right.semilogx(tap[after], z[after], ".", ms=3, color="C2", label=r"$\langle Z\rangle$")
    right.set_xlabel("tap t")
    right.set_ylabel(r"mean centre height $\langle Z\rangle$ (distance units)")
    place_legend(right, later=True, fontsize=8)
    fig.suptitle(settings, fontsize=9)
    replace_legends(fig, fig.tight_layout)   # legends off the data, for the laid-out axes
    fig.savefig(args.out + ".png", dpi=120)

    print(f"{settings}: <Phi^c> {phi_c[0]:.4f} before the first tap, {phi_c[after][0]:.4f} after it, "
          f"{phi_c[-1]:.4f} after tap {int(tap[-1])}; Phi_b {phi_b[0]:.4f} -> {phi_b[-1]:.4f}")
    if fit is None:
        print(f"eq. 3 not fitted: {int(after.sum())} taps, it needs {MIN_FIT_TAPS}")
    else:
        p = fit.params
        print(f"eq. 3 fitted to <Phi^c>: X_inf {p['X_inf']:.4f}, B {p['B']:.3g}, tau {p['tau']:.3g}"
              + ("" if fit.determined else " (not unique at these taps: the data fix a combination of"
                                            " X_inf, B and tau, as the paper says of small eps, section III.B)"))
    print(f"wrote {args.out}.png and {args.out}.csv")


if __name__ == "__main__":
    main()
