# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""packing-scatter: does the spatial jackknife of one packing (4 x 4 lateral blocks), the
error of nu (pores, Fig. 10) and of alpha (the profile's gradient, Fig. 6) wherever one run
gives a point, tell how far another realization lands? The final packings (dump.<taps>) of
every group of finished constant-eps runs that differ only in their seed, and the distinct
initial packings (dump.0) of each boundary condition, no simulation (tapmc-pores in Fig.
10's statistics box, a few seconds per packing; alpha in Fig. 6's window): per packing nu
and alpha with their jackknife errors, in realization_scatter.csv's columns
(packing_scatter.csv)."""

from __future__ import annotations

from pathlib import Path

from tapmc.pores import JACKKNIFE_BLOCKS, jackknife_error, read_pores
from tapmc.profiles import PROFILE_JACKKNIFE_BLOCKS

from .. import _pores, _runs, fig6
from ..claims import CALIBRATION_ALPHA, group_bc, realization_calibrations
from .calibration import calibration_table, load, save, scatter_by_bc
from .common import run_radius, seed_groups, taps_table, work_folder

NAME = "packing-scatter"
CSV = "packing_scatter.csv"
#: packing-scatter's quantities of one packing, as realization_scatter.csv names columns
PACKING_NU, PACKING_ALPHA = "packing:nu", "packing:alpha"
#: the quantities of packing_scatter.csv, as the page names them
PACKING_NAMES = {PACKING_NU: "nu (pores)", PACKING_ALPHA: "alpha (the profile's gradient)"}
#: the jackknifes' dof: their blocks (lateral, per side) squared, minus one
NU_DOF, ALPHA_DOF = JACKKNIFE_BLOCKS ** 2 - 1, PROFILE_JACKKNIFE_BLOCKS ** 2 - 1


def add_arguments(parser):
    parser.add_argument("--work", default=None, type=Path,
                        help="where tapmc-pores' outputs go (default OUT/partial/"
                             "packing_scatter)")


def packing_nu(dump, work, radius):
    """(nu, its spatial jackknife error) of one dump in Fig. 10's statistics box (2R above
    the floor to 20R or SURFACE_FRACTION of the highest centre), tapmc-pores' outputs kept in
    ``work`` under the dump's run folder name (one analysis per dump: dumps of different runs
    share their step)."""
    dump = Path(dump)
    step = int(dump.name.split(".")[1])
    top = _pores.window_top(dump, radius)
    prefix = _runs.run_pores([dump], Path(work) / f"{dump.parent.name}_t{step}",
                             ["--radii", "--z", f"{_pores.WINDOW_BOTTOM:g}:{top:.4f}",
                              "--frame-hist", "--pores"])
    pores = read_pores(prefix)
    return (pores.distribution(step).nu,
            jackknife_error([r.nu for r in pores.jackknife(step)]))


def _group_rows(group, runs, work, initial):
    """The rows of one group's final packings; records each seed's initial packing (one
    per seed and boundary condition, told apart by their <Phi^c>) in ``initial``."""
    bc = group_bc(group)
    tables = {seed: taps_table(run_dir / "taps.dat") for seed, run_dir in runs}
    taps = {int(t["step"][-1]) for t in tables.values()}
    if len(taps) != 1:
        print(f"{group}: seeds of different lengths {sorted(taps)}: skipped")
        return []
    last = taps.pop()
    radii = {seed: run_radius(run_dir) for seed, run_dir in runs}
    window = fig6.window_below([t["h_s"][0] / radii[seed] for seed, t in tables.items()], bc)
    rows = []
    for seed, run_dir in runs:
        start = tables[seed]["phi_c"][0]
        nu, nu_err = packing_nu(fig6.final_dump(run_dir, last), work, radii[seed])
        alpha, alpha_err = fig6.run_alpha(run_dir, last, radii[seed], window, bc)
        rows.append([group, run_dir.name, seed, last, PACKING_NU, f"{start:.8g}",
                     f"{nu:.8g}", f"{nu_err:.4g}", "", NU_DOF])
        rows.append([group, run_dir.name, seed, last, PACKING_ALPHA, f"{start:.8g}",
                     f"{alpha:.8g}", f"{alpha_err:.4g}", "", ALPHA_DOF])
        print(f"{run_dir.name}: nu {nu:.5f} +- {nu_err:.5f}, alpha {alpha:.5f} +- "
              f"{alpha_err:.5f}", flush=True)
        initial.setdefault(bc, {}).setdefault(f"{start:.8f}", (seed, run_dir))
    return rows


def analyse(campaign, work):
    """The rows of packing_scatter.csv (calibration.SCATTER_HEADER)."""
    groups = seed_groups(campaign)        # a bad campaign is refused before any file is made
    Path(work).mkdir(parents=True, exist_ok=True)
    rows, initial = [], {}
    for group, runs in groups.items():
        if group.startswith("const_"):      # the ageing runs dump no packing
            rows += _group_rows(group, runs, work, initial)
    for bc, packings in sorted(initial.items()):
        if len(packings) < 2:
            continue
        for seed, run_dir in sorted(packings.values()):
            nu, nu_err = packing_nu(run_dir / "dump.0.lammpstrj", work, run_radius(run_dir))
            rows.append([f"initial_{bc}", run_dir.name, seed, 0, PACKING_NU,
                         f"{taps_table(run_dir / 'taps.dat')['phi_c'][0]:.8g}",
                         f"{nu:.8g}", f"{nu_err:.4g}", "", NU_DOF])
            print(f"{run_dir.name} at t = 0: nu {nu:.5f} +- {nu_err:.5f}", flush=True)
    return rows


def measure(args):
    save(args.out / CSV, analyse(args.campaign, work_folder(args, "packing_scatter")))


def render(path):
    """The table of each group's spread of a packing's nu and alpha against their spatial
    jackknife errors, the pooled factors and the verdict."""
    rows = load(path)
    calib = realization_calibrations(rows)
    if not rows or not calib:
        return []
    lines = ["Does the spatial jackknife of one packing (4 x 4 lateral blocks: the error of "
             "nu and of alpha wherever one run gives a point) tell how far another "
             "realization lands? The final packings of the campaign's groups of runs that "
             "differ only in their seed, and their distinct initial packings "
             "(``packing_scatter.csv``, ``tapmc-paper question packing-scatter``: "
             "tapmc-pores in Fig. 10's statistics box; alpha in Fig. 6's window):", ""]
    lines += calibration_table(
        calib, PACKING_NAMES, PACKING_NAMES, ("packings", "rms jackknife error"),
        lambda group, n: f"{n} (" + ("t = 0" if group.startswith("initial_")
                                     else "after the taps") + ")")
    lines += scatter_by_bc(rows)
    short = [k for k in PACKING_NAMES if k in calib and calib[k].p_value < CALIBRATION_ALPHA]
    wide = [k for k in PACKING_NAMES if k in calib and calib[k].interval()[1] < 1]
    verdict = []
    if short:
        verdict.append(", ".join(PACKING_NAMES[k] for k in short) + ": the jackknife is too "
                       "small; a one-run value carries its jackknife error times k.")
    if wide:
        verdict.append(", ".join(PACKING_NAMES[k] for k in wide) + ": the jackknife is "
                       "larger than the spread of realizations (k below 1 at 95 %), as it is "
                       "when the blocks of one packing are anticorrelated (the statistics "
                       "box holds a nearly fixed number of spheres) where the jackknife "
                       "takes them as independent; the page keeps the jackknife error, an "
                       "upper bound of a realization's.")
    fine = [k for k in PACKING_NAMES if k in calib and k not in short and k not in wide]
    if fine:
        verdict.append(", ".join(f"{PACKING_NAMES[k]} (k = {calib[k].factor:.2f})"
                                 for k in fine)
                       + ": the jackknife is compatible with the realizations' spread: a "
                       "one-seed error bar is the error of a realization.")
    return lines + ["* Verdict: " + " ".join(verdict), ""]

