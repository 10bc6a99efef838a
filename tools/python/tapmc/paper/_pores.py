# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Pore analysis of the dumps of ``examples/paper/in.pore_dumps`` runs for Figs. 9 and 10:
tapmc-pores is run once per run folder (outputs cached next to the dumps) in a sub-box away
from the floor, the side walls and the free surface."""

from __future__ import annotations

import re
from pathlib import Path

from tapmc.readers import read_dump

from . import _runs

#: bottom of the statistics box above the floor, in R (paper: "located at a distance 2R").
WINDOW_BOTTOM = 2.0
#: the paper's statistics box is 18R high (Fig. 10): top at 20R above the floor at most.
WINDOW_TOP = 20.0
#: the box top stays below this fraction of the highest sphere centre (the free surface).
SURFACE_FRACTION = 0.8
#: random points per frame for P0 (Fig. 9).
P0_POINTS = 200000


def dumps(run_dir):
    """dict step -> dump path of a pore-dump run folder."""
    out = {}
    for path in Path(run_dir).glob("dump.*.lammpstrj"):
        m = re.fullmatch(r"dump\.(\d+)\.lammpstrj", path.name)
        if m:
            out[int(m.group(1))] = path
    if not out:
        raise FileNotFoundError(f"{run_dir}: no dump.<step>.lammpstrj file")
    return dict(sorted(out.items()))


def window_top(dump_path, radius):
    """Top of the statistics box in R: the paper's 20R, lowered to SURFACE_FRACTION of the
    highest sphere centre of the frame when the packing is lower."""
    frame = next(iter(read_dump(dump_path).frames))
    floor = frame.box_lo[2]
    zmax = (frame.positions[:, 2].max() - floor) / radius
    return min(WINDOW_TOP, SURFACE_FRACTION * zmax)


def analyse(campaign, spec, tag, steps=None, extra=()):
    """Run tapmc-pores on the dumps of ``spec`` (all steps, or ``steps``) with one z-window
    set by the lowest frame; returns (prefix, window)."""
    run_dir = _runs.run_dir(campaign, spec)
    files = dumps(run_dir)
    if steps is not None:
        files = {s: files[s] for s in steps}
    radius = float(spec.variables.get("R", 0.5))
    top = min(window_top(p, radius) for p in files.values())
    window = (WINDOW_BOTTOM, top)
    args = ["--radii", "--z", f"{window[0]:g}:{top:.4f}", *extra]
    prefix = _runs.run_pores(list(files.values()), run_dir / f"pores_{tag}", args)
    return prefix, window
