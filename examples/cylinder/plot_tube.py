# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Draw a tapping run in a tube (in.cylinder): the compaction curve of taps.dat (Phi_b, <Phi^c>,
the wall zone within 7R of the wall and the core against the tap count, eq. 3 fitted to
<Phi^c>, and <Z>) and the radial profiles of profile_r.dat (the annuli's volume fraction
against the distance from the axis, at t = 0 and after the last tap). The settings (N, tube
diameter, eps, eta, taps) come from the LAMMPS log beside them. Writes tube_compaction.png/.csv
and tube_profile_r.png/.csv and prints a summary.

    /usr/bin/python3 plot_tube.py [RUN_DIR] [--log log.lammps] [--out-dir DIR]

Needs the Python package tapmc on the path (``PYTHONPATH=tools/python`` from the repository
root, an installed prefix, or a venv).
"""

import argparse
import sys
from pathlib import Path

from tapmc.paper.tube import compaction_figure, radial_profile_figure
from tapmc.readers import TapmcFormatError
from tapmc.tube_runs import RadialProfiles, TubeCompaction, TubeSettings


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run", nargs="?", default=".",
                        help="folder of the run: taps.dat, profile_r.dat, log.lammps (default .)")
    parser.add_argument("--log", default=None, help="LAMMPS log (default RUN/log.lammps)")
    parser.add_argument("--out-dir", default=None, help="where the figures go (default RUN)")
    args = parser.parse_args(argv)
    run = Path(args.run)
    out = Path(args.out_dir) if args.out_dir else run
    settings = TubeSettings.from_log(args.log or run / "log.lammps")
    try:
        curve = TubeCompaction.from_file(run / "taps.dat", settings=settings).compute()
        profiles = RadialProfiles.from_file(run / "profile_r.dat", settings=settings)
    except (OSError, TapmcFormatError, KeyError, ValueError) as err:
        sys.exit(f"plot_tube.py: {err}")
    written = compaction_figure(curve, out / "tube_compaction")
    written += radial_profile_figure(profiles, out / "tube_profile_r")

    i, f = curve.initial, curve.final
    print(f"{curve.settings.describe()}:")
    for name in ("Phi_b", "<Phi^c>", "phi_wall", "phi_core"):
        print(f"  {name:9s} {i[name]:.4f} at t = 0 -> {f[name]:.4f} "
              f"after tap {int(curve.taps[-1])}")
    if curve.fit_result is not None:
        p = curve.fit_result.params
        print(f"  eq. 3 fitted to <Phi^c>: X_inf {p['X_inf']:.4f}, B {p['B']:.3g}, "
              f"tau {p['tau']:.3g}"
              + ("" if curve.fit_result.determined else " (not determined at these taps)"))
    for k, step in enumerate(profiles.steps):
        print(f"  radial profile at t = {step}: volume fraction {profiles.profile(k).mean():.4f}"
              f" over the {profiles.r.size} annuli")
    print("wrote " + ", ".join(str(p) for p in written))


if __name__ == "__main__":
    main()
