# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""p0-fluid: is a tapped packing expected to follow the Percus-Yevick P0(sigma) of Fig. 9 as
closely as it does (max |P0 - PY| = 0.025 at Phi = 0.606)? PY is a theory of the equilibrium
hard-sphere fluid: P0 measured with the same tool and settings (tapmc-pores --p0, Fig. 9's
random point count) on equilibrium fluids at several Phi (NVT Metropolis MC,
bench/bench_hs_fluid.cpp: 4000 spheres in a periodic cube, several configurations per Phi),
with the contact value g(1+) against Carnahan-Starling as the check of equilibrium: the
baseline of the packing's deviation, and a validation of the measurement where PY is
accurate (p0_fluid.csv). The configurations and tapmc-pores outputs stay in --work DIR when
given (a re-run reuses them); the MC program is --mc EXE, else build/bench/bench_hs_fluid,
else bench/bench_hs_fluid.cpp compiled with $CXX (default c++) into the work folder."""

from __future__ import annotations

import math
import os
import subprocess
import tempfile
from pathlib import Path

import numpy as np

from tapmc.pores import percus_yevick_p0, read_pores

from .. import _runs
from .._pores import P0_POINTS
from .._rst import list_table
from ..claims import fmt
from .common import QuestionError, QuestionRunError, csv_schema, write_csv

NAME = "p0-fluid"
CSV = "p0_fluid.csv"
HEADER = ["phi", "N", "configs", "phi_points", "phi_points_sem", "p0_points", "max_abs_diff",
          "max_abs_diff_sem", "sigma_at_max", "diff_at_max", "py_at_max",
          "max_abs_diff_per_config", "max_abs_diff_per_config_sem", "max_abs_diff_exact_phi",
          "acceptance", "delta", "eq_sweeps", "sample_sweeps", "eq_msd", "min_spacing_msd",
          "g_contact", "g_contact_sem", "g_contact_cs", "min_distance", "mc_seconds"]
CURVES_HEADER = ["phi", "sigma", "P0", "P0_sem", "PY", "P0_minus_PY", "P0_minus_PY_sem"]
#: Phi of the fluids: stable fluid up to freezing (0.494), then metastable ones (the 4000
#: spheres do not crystallise within the runs at 0.54: g(1+) stays on the fluid's branch).
P0_FLUID_PHI = (0.30, 0.40, 0.45, 0.49, 0.52, 0.54)
#: FCC cells per side of the start lattice: 4 * 10^3 = 4000 spheres, near the paper's 4096.
P0_FLUID_CELLS = 10
#: configurations per Phi: the sem of max |P0 - PY| is then about 3e-4, a tenth of the
#: smallest value measured (200000 random points give each configuration about 1e-3).
P0_FLUID_CONFIGS = 8
#: mean-square displacement (diameters^2) before the first configuration: every sphere has
#: moved by about 1.4 diameters, far beyond the cage (a tenth of a diameter) that sets the
#: local structure P0 measures.
P0_FLUID_EQ_MSD = 2.0
#: between configurations: beyond the structural relaxation (rms 0.7 diameter), so the
#: configurations are independent samples of the local structure.
P0_FLUID_SPACING_MSD = 0.5
#: sweep bound per stage; a stage stopped by it is seen in the CSV (eq_msd, min_spacing_msd).
P0_FLUID_MAX_SWEEPS = 400000
MC_SOURCE = _runs.SOURCE_DIR / "bench" / "bench_hs_fluid.cpp"
MC_FLAGS = ("-O2", "-std=c++17")
#: the lowest and highest Phi a fluid is asked at (a dilute gas, just below random close
#: packing's neighbourhood where the MC no longer equilibrates)
PHI_RANGE = (0.01, 0.58)
#: relative departure of the measured contact value g(1+) from Carnahan-Starling allowed of an
#: equilibrium fluid: CS is within 1 % of simulations up to Phi = 0.54, the extrapolation of
#: g(r) to contact adds about as much; a crystallised or unrelaxed sample is off by more.
CONTACT_TOLERANCE = 0.03
#: the packing's max |P0 - PY| is called "of the fluid's size" when within this factor of the
#: fluid's (at the highest Phi measured, or the fluid's trend carried to the packing's Phi when
#: that is larger), and beyond it otherwise.
BASELINE_FACTOR = 2.0


def add_arguments(parser):
    parser.add_argument("--phi", type=float, nargs="+", default=list(P0_FLUID_PHI),
                        help="volume fractions Phi of the equilibrium fluids, each in "
                             f"[{PHI_RANGE[0]}, {PHI_RANGE[1]}] (default: %(default)s)")
    parser.add_argument("--configs", type=int, default=P0_FLUID_CONFIGS,
                        help="configurations sampled per Phi, at least 2 (default %(default)s)")
    parser.add_argument("--cells", type=int, default=P0_FLUID_CELLS,
                        help="FCC cells per side of the start lattice: 4 CELLS^3 spheres "
                             "(default %(default)s: 4000 spheres)")
    parser.add_argument("--eq-msd", type=float, default=P0_FLUID_EQ_MSD,
                        help="mean-square displacement (diameters^2) of the equilibration "
                             "before the first configuration (default %(default)s)")
    parser.add_argument("--spacing-msd", type=float, default=P0_FLUID_SPACING_MSD,
                        help="mean-square displacement (diameters^2) between successive "
                             "configurations (default %(default)s)")
    parser.add_argument("--max-sweeps", type=int, default=P0_FLUID_MAX_SWEEPS,
                        help="MC sweeps at most per stage (the equilibration, each spacing); "
                             "a stage it stops shows in the CSV's eq_msd and min_spacing_msd "
                             "(default %(default)s)")
    parser.add_argument("--seed", type=int, default=1,
                        help="seed of the MC: the fluid at Phi runs with seed "
                             "SEED * 1000 + round(1000 Phi) (default %(default)s)")
    parser.add_argument("--work", default=None, type=Path,
                        help="folder kept for the MC configurations and tapmc-pores outputs "
                             "(WORK/phi_<Phi>/, reused by a re-run) and p0_fluid_curves.csv "
                             "(default: a temporary folder, removed at the end)")
    parser.add_argument("--mc", default=None,
                        help="the hard-sphere MC executable (default: bench/bench_hs_fluid of "
                             "$TAPMC_BUILD_DIR or build/, else bench/bench_hs_fluid.cpp "
                             "compiled with $CXX, default c++, into the work folder)")


def check(args):
    if args.configs < 2:
        raise QuestionError(f"--configs must be at least 2 (error bars), got {args.configs}")
    if any(not PHI_RANGE[0] <= p <= PHI_RANGE[1] for p in args.phi):
        raise QuestionError(f"--phi values must be in [{PHI_RANGE[0]}, {PHI_RANGE[1]}], got "
                            f"{args.phi}")


def mc_command(exe, work):
    """The hard-sphere MC program: --mc EXE, build/bench/bench_hs_fluid, else compiled."""
    candidates = [Path(exe)] if exe else [
        Path(os.environ.get("TAPMC_BUILD_DIR", _runs.SOURCE_DIR / "build")) / "bench"
        / "bench_hs_fluid"]
    for path in candidates:
        if path.is_file() and os.access(path, os.X_OK):
            if path.stat().st_mtime < MC_SOURCE.stat().st_mtime:
                print(f"p0-fluid: warning: {path} is older than {MC_SOURCE}")
            return ["nice", "-n", "2", str(path)]
    if exe:
        raise QuestionError(f"--mc {exe}: no such executable")
    built = Path(work) / "bench_hs_fluid"
    if not built.is_file() or built.stat().st_mtime < MC_SOURCE.stat().st_mtime:
        cxx = os.environ.get("CXX", "c++")
        done = subprocess.run([cxx, *MC_FLAGS, "-o", str(built), str(MC_SOURCE)],
                              capture_output=True, text=True)
        if done.returncode != 0:
            raise QuestionRunError(f"compiling {MC_SOURCE} with {cxx} failed:\n"
                                f"{done.stderr[-2000:]}")
    return ["nice", "-n", "2", str(built)]


def parse_mc(text):
    """(dict of the 'key value' lines, list of per-configuration dicts) of bench_hs_fluid."""
    values, configs = {}, []
    for line in text.splitlines():
        fields = line.split()
        if fields and fields[0] == "config":
            configs.append({fields[k]: float(fields[k + 1]) for k in range(0, len(fields), 2)})
        elif len(fields) == 2:
            values[fields[0]] = float(fields[1])
    return values, configs


def fluid_configurations(mc, folder, phi, args):
    """Run the MC for ``phi`` into ``folder`` unless a finished run is there (mc.txt is written
    last); returns (values, configs, dumps)."""
    log = folder / "mc.txt"
    dumps = [folder / f"fluid.{k}.lammpstrj" for k in range(1, args.configs + 1)]
    if not (log.is_file() and all(d.is_file() for d in dumps)):
        folder.mkdir(parents=True, exist_ok=True)
        seed = args.seed * 1000 + round(1000 * phi)
        cmd = [*mc, "--phi", f"{phi:g}", "--cells", str(args.cells), "--seed", str(seed),
               "--configs", str(args.configs), "--eq-msd", f"{args.eq_msd:g}",
               "--spacing-msd", f"{args.spacing_msd:g}", "--max-sweeps", str(args.max_sweeps),
               "--prefix", str(folder / "fluid")]
        done = subprocess.run(cmd, capture_output=True, text=True)
        if done.returncode != 0:
            raise QuestionRunError(f"{' '.join(cmd)} failed:\n{done.stderr[-2000:]}")
        (folder / "mc.txt.partial").write_text(done.stdout)
        (folder / "mc.txt.partial").rename(log)
    values, configs = parse_mc(log.read_text())
    if len(configs) != args.configs or int(values["N"]) != 4 * args.cells ** 3:
        raise QuestionError(f"{log} is from other settings (remove {folder})")
    return values, configs, dumps


def measured_p0(pores, folder, dumps):
    """(sigma, P0 per configuration, Phi seen by each configuration's points): tapmc-pores
    with Fig. 9's settings (P0_POINTS random points, one seed per configuration; the box is
    triply periodic, so the selection is the whole box), outputs kept in ``folder``."""
    p0s, phis = [], []
    for k, dump in enumerate(dumps, start=1):
        prefix = folder / f"pores_{k}"
        if not Path(str(prefix) + ".p0.csv").is_file():
            cmd = [*pores, "-q", "--p0", str(P0_POINTS), "--seed", str(k), "-o", str(prefix),
                   str(dump)]
            done = subprocess.run(cmd, capture_output=True, text=True)
            if done.returncode != 0:
                raise QuestionRunError(f"{' '.join(cmd)} failed:\n{done.stderr}")
        result = read_pores(prefix)
        sigma = np.asarray(result.p0["sigma"], dtype=float)
        p0s.append(np.asarray(result.p0["P0_measured"], dtype=float))
        phis.append(float(result.frames["phi_p0"][0]))
    return sigma, np.array(p0s), np.array(phis)


def fluid_rows(values, configs, sigma, p0s, phis):
    """(the p0_fluid.csv row of one Phi, its rows of p0_fluid_curves.csv)."""
    n = len(p0s)
    mean, sem = p0s.mean(axis=0), p0s.std(axis=0, ddof=1) / np.sqrt(n)
    # as Fig. 9: each configuration against PY at the volume fraction its random points see
    # (the same points, so their noise cancels in part); mean and sem of that difference
    # over the configurations
    theories = np.array([percus_yevick_p0(sigma, q) for q in phis], dtype=float)
    diffs = p0s - theories
    diff = diffs.mean(axis=0)
    diff_sem = diffs.std(axis=0, ddof=1) / np.sqrt(n)
    theory = theories.mean(axis=0)
    at = int(np.argmax(np.abs(diff)))
    singles = np.abs(diffs).max(axis=1)
    exact = np.asarray(percus_yevick_p0(sigma, values["phi"]), dtype=float)
    spacing = min(c["msd_spacing"] for c in configs)
    row = [f"{values['phi']:.6g}", int(values["N"]), n, f"{float(phis.mean()):.6g}",
           f"{phis.std(ddof=1) / np.sqrt(n):.3g}", P0_POINTS,
           f"{abs(diff[at]):.6g}", f"{diff_sem[at]:.3g}", f"{sigma[at]:.6g}",
           f"{diff[at]:.6g}", f"{theory[at]:.6g}",
           f"{np.mean(singles):.6g}", f"{np.std(singles, ddof=1) / np.sqrt(n):.3g}",
           f"{np.max(np.abs(mean - exact)):.6g}", f"{values['acceptance']:.4g}",
           f"{values['delta']:.4g}", int(values["eq_sweeps"]),
           int(values["sample_sweeps"]), f"{values['eq_msd']:.4g}", f"{spacing:.4g}",
           f"{values['g_contact']:.6g}", f"{values['g_contact_sem']:.3g}",
           f"{values['g_contact_cs']:.6g}", f"{values['min_distance']:.9g}",
           f"{values['seconds']:.4g}"]
    curves = [[f"{values['phi']:.6g}", f"{s:.6g}", f"{m:.6g}", f"{e:.3g}", f"{t:.6g}",
               f"{d:.6g}", f"{de:.3g}"]
              for s, m, e, t, d, de in zip(sigma, mean, sem, theory, diff, diff_sem)]
    print(f"Phi {values['phi']:.3f}: max |P0 - PY| = {abs(diff[at]):.4f} +- "
          f"{diff_sem[at]:.4f} at sigma = {sigma[at]:.3f}; g(1+) {values['g_contact']:.3f} "
          f"(CS {values['g_contact_cs']:.3f}); msd {values['eq_msd']:.2f}; "
          f"{values['seconds']:.0f} s", flush=True)
    return row, curves


def measure(args):
    check(args)
    with tempfile.TemporaryDirectory() as scratch:
        work = Path(args.work) if args.work else Path(scratch)
        work.mkdir(parents=True, exist_ok=True)
        mc = mc_command(args.mc, work)
        pores = ["nice", "-n", "2", _runs.pores_executable()]
        rows, curves = [], []
        for phi in args.phi:
            folder = work / f"phi_{phi:g}"
            values, configs, dumps = fluid_configurations(mc, folder, phi, args)
            row, curve = fluid_rows(values, configs, *measured_p0(pores, folder, dumps))
            rows.append(row)
            curves += curve
        save(args.out / CSV, rows)
        if args.work:
            write_csv(work / "p0_fluid_curves.csv", CURVES_HEADER, curves)


save, load = csv_schema(HEADER)


def packing_p0(fig9, configs=None):
    """(Phi, max |P0 - PY|, sigma of the max, P0 - PY there, PY there, what) of Fig. 9's
    tapped packing: over the tapped configurations of ``configs`` (p0_configs.csv) when given,
    else Fig. 9's own curve; None when neither is there."""
    if configs is not None and Path(configs).is_file():
        rows = load(configs)
        data = [r for r in rows if r["sigma"] != "phi"]
        phi = float(next(r for r in rows if r["sigma"] == "phi")["tapped"])
        sigma = np.array([float(r["sigma"]) for r in data])
        final = np.array([float(r["tapped"]) for r in data])
        theory = np.asarray(percus_yevick_p0(sigma, phi), dtype=float)
        diff = final - theory
        at = int(np.argmax(np.abs(diff)))
        return (phi, float(abs(diff[at])), float(sigma[at]), float(diff[at]), float(theory[at]),
                f"mean of {data[0]['tapped_n']} tapped configurations, ``p0_configs.csv``")
    if fig9 is None:
        return None
    phi = fig9.param("phi_final")[0]
    value = fig9.param("max_abs_diff_final_py")[0]
    if not (np.isfinite(phi) and np.isfinite(value)):
        return None
    final, theory = fig9.get("a", "final"), fig9.get("a", "percus_yevick")
    sigma = signed = py = math.nan
    if final is not None and theory is not None and len(final[0]) == len(theory[0]):
        diff = final[1] - theory[1]
        at = int(np.nanargmax(np.abs(diff)))
        sigma, signed, py = float(final[0][at]), float(diff[at]), float(theory[1][at])
    return phi, value, sigma, signed, py, "Fig. 9's run"


def render(path, fig9=None):
    rows = sorted(load(path), key=lambda r: float(r["phi"]))
    if not rows:
        return []
    f = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    lo_c, hi_c = int(f["configs"].min()), int(f["configs"].max())
    configs = f"{lo_c}" if lo_c == hi_c else f"{lo_c} to {hi_c}"
    lines = ["Is a tapped packing expected to follow the Percus-Yevick P0(sigma) as closely as "
             "Fig. 9 shows? PY is a theory of the equilibrium hard-sphere fluid. The same "
             f"measurement (tapmc-pores --p0, {int(f['p0_points'][0])} random points per "
             "configuration, PY at the volume fraction seen by the points) on equilibrium "
             f"hard-sphere fluids of N = {int(f['N'][0])} spheres in a periodic cube (NVT "
             f"Monte Carlo, ``p0_fluid.csv``; mean ± sem over {configs} configurations per "
             "Phi; the contact value g(1+) against Carnahan-Starling checks the equilibrium):",
             ""]
    header = ["Phi", "max abs(P0 - PY)", "at sigma", "P0 - PY there", "g(1+)",
              "Carnahan-Starling", "MSD before sampling (diameters²)"]
    lines += list_table(header, [
        [f"{f['phi'][k]:.3f}", fmt(f['max_abs_diff'][k], f['max_abs_diff_sem'][k]),
         f"{f['sigma_at_max'][k]:.3f}", f"{f['diff_at_max'][k]:+.4f}",
         f"{f['g_contact'][k]:.3f} ± {f['g_contact_sem'][k]:.3f}", f"{f['g_contact_cs'][k]:.3f}",
         f"{f['eq_msd'][k]:.2f}"] for k in range(len(rows))]) + [""]
    off = np.abs(f["g_contact"] / f["g_contact_cs"] - 1)
    bad = [f"{p:.3f}" for p, o in zip(f["phi"], off) if not o <= CONTACT_TOLERANCE]
    if bad:
        lines.append(f"* g(1+) departs from Carnahan-Starling by more than "
                     f"{100 * CONTACT_TOLERANCE:.0f} % at Phi = {', '.join(bad)}: those samples "
                     "are not equilibrium fluids, and their rows say nothing about PY.")
    else:
        lines.append(f"* g(1+) is within {100 * off.max():.1f} % of Carnahan-Starling at every "
                     "Phi: the samples are equilibrium fluids.")
    ok = np.array([o <= CONTACT_TOLERANCE for o in off])
    if not ok.any():
        return lines + [""]
    lo, hi = int(np.flatnonzero(ok)[0]), int(np.flatnonzero(ok)[-1])
    def side(k):
        return "above" if f["diff_at_max"][k] > 0 else "below"

    text = (f"* At Phi = {f['phi'][lo]:.3f}, where PY is most accurate, the measured P0 departs "
            f"from it by at most {fmt(f['max_abs_diff'][lo], f['max_abs_diff_sem'][lo])} (P0 "
            f"{side(lo)} PY): the measurement agrees with the theory to that level where the "
            "theory holds, which bounds the error of the tool.")
    if hi != lo:
        text += (f" At Phi = {f['phi'][hi]:.3f} the exact fluid departs from PY by "
                 f"{fmt(f['max_abs_diff'][hi], f['max_abs_diff_sem'][hi])} (at sigma = "
                 f"{f['sigma_at_max'][hi]:.2f}, P0 {side(hi)} PY).")
    lines.append(text)
    return lines + _against_packing(f, ok, hi, fig9, path)


def _against_packing(f, ok, hi, fig9, path):
    """The tapped packing's departure from PY against the fluids' (``f``: the columns of
    p0_fluid.csv, ``ok``: the rows that are equilibrium fluids, ``hi``: the densest of them)."""
    lines = []
    packing = packing_p0(fig9, Path(path).with_name("p0_configs.csv"))
    if packing is None:
        return lines + [""]
    phi, value, sigma, signed, py, what = packing
    baseline = f["max_abs_diff"][hi]
    where = ""
    if np.isfinite(sigma):
        same = (signed > 0) == (f["diff_at_max"][hi] > 0)
        where = (f" at sigma = {sigma:.2f}, P0 " + ("above" if signed > 0 else "below")
                 + " PY (" + ("the fluid's direction" if same else "opposite to the fluid")
                 + ")")
    text = (f"* The tapped packing of Fig. 9 ({what}; Phi = {100 * phi:.1f} %) departs from "
            "PY by "
            f"{fmt(value)}{where}: {value / baseline:.1f} times the equilibrium fluid's at "
            f"Phi = {f['phi'][hi]:.3f}.")
    valid = np.flatnonzero(ok)
    if len(valid) >= 2 and phi > f["phi"][hi]:
        # the packing is denser than any fluid measured: extend the fluid's trend to its Phi
        # (a straight line through the valid rows) and compare with the larger of the two
        slope, icpt = np.polyfit(f["phi"][valid], f["max_abs_diff"][valid], 1)
        reach = slope * phi + icpt
        text += (f" A straight line through the fluid's values (slope {slope:.3f} per unit of "
                 f"Phi) reaches {reach:.4f} at the packing's Phi; the packing's is "
                 f"{value / reach:.1f} times that.")
        baseline = max(baseline, reach)
    if np.isfinite(py) and py > 0 and "py_at_max" in f:
        # P0 falls steeply with sigma: the deviation relative to PY where it is largest
        fluid_rel = np.abs(f["diff_at_max"][valid]) / f["py_at_max"][valid]
        trend = ""
        if len(valid) >= 2:
            rising = np.polyfit(f["phi"][valid], fluid_rel, 1)[0] > 0
            trend = " (growing with Phi)" if rising else " (falling with Phi)"
        text += (f" Relative to PY there, the packing departs by {100 * value / py:.0f} %, the "
                 f"fluid by {100 * fluid_rel.min():.1f} to {100 * fluid_rel.max():.1f} %"
                 f"{trend}.")
    ratio = value / baseline
    lines.append(text + " "
                 + ("Its agreement with PY is of the size PY itself misses in an equilibrium "
                    "fluid: as close as a fluid's, no closer."
                    if ratio <= BASELINE_FACTOR else
                    "The packing follows PY markedly less closely than an equilibrium fluid "
                    "does: Fig. 9's agreement is approximate, a packing resembling a dense "
                    "fluid, not the accuracy PY has for the fluid."))
    return lines + [""]

