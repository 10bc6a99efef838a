# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""noise-floor: what is sigma_<Z> without any tap (eps = 0), the redeposition's own noise,
the floor under Fig. 3's sigma_<Z> = k sqrt(eps)? 1000 taps at eps = 0 from the packing after
4000 taps at eps = 0.0225 (the paper-scale campaign's restart.4000 of that run, committed as
the input of this measurement): sigma_<Z> over them as Fig. 3 computes it, the drift of <Z>,
and the slope of their power spectrum (Fig. 3's estimator) (noise_floor.csv)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from tapmc.fluctuations import PowerSpectrum
from tapmc.stats import beyond

from ..claims import fmt
from . import launch
from .common import CAMPAIGN_RUN, PAPER, QuestionError, read_csv, work_folder, write_csv

NAME = "noise-floor"
CSV = "noise_floor.csv"
HEADER = ["quantity", "value"]
NOISE_TAPS = 1000
NOISE_FROM_STEP = 4000


def add_arguments(parser):
    parser.add_argument("--restart", type=Path, default=CAMPAIGN_RUN / "restart.4000",
                        help="restart file the runs continue from: the P.B.C. packing after "
                             "4000 taps at eps = 0.0225 (default: restart.4000 of the "
                             "paper-scale campaign's run const_pbc_eps0.0225_s1, in "
                             "doc/validation/data/full/runs/)")


def campaign_restart(path):
    """The restart file of --restart, resolved; QuestionError when it is missing."""
    restart = Path(path).resolve()
    if not restart.is_file():
        raise QuestionError(f"restart file {restart} not found (--restart FILE: the packing "
                            "after 4000 taps of the paper-scale campaign's eps = 0.0225 run)")
    return restart


def measure(args):
    lmp = launch.lammps(args.lmp)
    restart = campaign_restart(args.restart)
    work = work_folder(args, "noise_floor")
    run = launch.spec("eps0", dict(PAPER, bc="pbc", eps=0, eta=1e-7, seed=1,
                                   taps=NOISE_FROM_STEP + NOISE_TAPS,
                                   rsteps=launch.NO_RESTART))
    launch.start_from(work, run.name, restart)
    taps = launch.run_one(work, run, lmp)
    after = taps["step"] > NOISE_FROM_STEP
    z = taps["Z"][after]
    t = np.arange(1, len(z) + 1, dtype=float)
    slope = float(np.polyfit(t, z, 1)[0])
    detrended = z - np.polyval(np.polyfit(t, z, 1), t)
    rows = [["sigma_Z", f"{np.std(z, ddof=1):.8g}"],
            ["sigma_Z_detrended", f"{np.std(detrended, ddof=1):.8g}"],
            ["drift_per_tap", f"{slope:.8g}"],
            ["Z_first", f"{z[0]:.8f}"], ["Z_last", f"{z[-1]:.8f}"],
            ["spectral_slope", f"{PowerSpectrum(z).compute().slope:.6g}"],
            ["spectral_slope_detrended", f"{PowerSpectrum(detrended).compute().slope:.6g}"],
            ["taps", len(z)], ["mean_sweeps", f"{np.mean(taps['sweeps'][after]):.4g}"]]
    for name, value in rows:
        print(f"{name} = {value}")
    save(args.out / CSV, rows)


def save(path, rows):
    return write_csv(path, HEADER, rows)


def load(path):
    return {r["quantity"]: float(r["value"]) for r in read_csv(path)}


def render(path, fig3=None):
    values = load(path)
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
        bd, bds, npoints = fig3.param("intercept_detrended")
        floor = values["sigma_Z_detrended"]
        if np.isfinite(bd) and bds > 0 and npoints > 2:
            gap = (bd - floor) / bds
            # the claims' rule: t quantile with the line's degrees of freedom
            above = gap > 0 and beyond(bd, bds, npoints - 2, reference=floor)
            lines[-1] += (f" About each run's straight line (the runs still compact at tap "
                          f"4000), the free line's intercept is {fmt(bd, bds)}, "
                          f"{abs(gap):.1f} of its standard errors "
                          f"{'above' if gap > 0 else 'below'} the floor's detrended "
                          f"{fmt(floor)}"
                          + (": the settles' own noise does not account for it."
                             if above else ": within the floor's reach."))
    return lines + [""]

