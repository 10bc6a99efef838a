# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""crystallinity: do the campaign's densest tapped packings crystallize? The paper's steady
packings reach <Phi^c> ~ 60.6 % at most and show layering only near the walls (section
III.B, IV): a denser packing here is the model's random packing only if it did not order.
Every finished constant-eps run of the paper-scale campaign (const_pbc_* and const_fbc_*; no
simulation: its dump.0 and its last dump, read back) measured by
:class:`tapmc.crystallinity.Crystallinity` (Steinhardt q6, ten Wolde-Frenkel crystalline
spheres): the global Q6, the mean local q6, and the crystalline fraction over all spheres, in
the bulk, in the floor layer and (F.B.C.) in the side-wall layer, with <Phi^c> of that tap
from taps.dat (crystallinity.csv). The page compares them with the initial (deposited)
packings and with exact FCC and HCP lattices measured by the same code. About 0.1 s per dump
of 4096 spheres: the committed campaign's 50 dumps took 7 s (wall time, one core)."""

from __future__ import annotations

import itertools
import math
from collections import namedtuple

import numpy as np

from tapmc.crystallinity import (BULK_MARGIN_OVER_R, CRYSTAL_L, NEAR_BOUNDARY_OVER_R,
                                 Crystallinity)
from tapmc.readers import TapmcFormatError, read_dump

from .._rst import list_table
from .common import QuestionError, csv_schema, eps_of, finished_runs, last_rows, taps_table

NAME = "crystallinity"
CSV = "crystallinity.csv"
HEADER = ["run", "bc", "eps", "seed", "tap", "taps", "n", "phi_c", "Q6", "q6_mean",
          "crystalline_all", "n_bulk", "crystalline_bulk", "n_floor", "crystalline_floor",
          "n_walls", "crystalline_walls"]
#: the runs read (a glob): the constant-eps runs of both boundary conditions (const_pbc_*,
#: const_fbc_*), which dump their packing at t = 0 and at their last tap (the ageing and ramp
#: runs dump none; const_fbcpaper_* start from another packing)
RUN_PATTERN = "const_[pf]bc_eps*_s*"
#: the floor layer and the side-wall layer: centres within 2 R of the floor or of a wall, the
#: first layer only (a sphere touching the floor has its centre at R; the next layer of a
#: random packing starts ~1.6 R higher, FCC's (100) next layer 1.41 R higher), where the
#: paper sees its layering (section IV.A); tapmc.crystallinity's own default
FLOOR_BAND_OVER_R = NEAR_BOUNDARY_OVER_R
#: the bulk: 7 R or more from the floor, the side walls and the free surface, the paper's
#: lateral zone's width (section IV.A, Fig. 8); tapmc.crystallinity's own default
BULK_OVER_R = BULK_MARGIN_OVER_R
#: the exact lattices of the page's references: periodic blocks of (cells per axis) of their
#: orthogonal cells, each side longer than twice the bond cutoff (1.2 d) so that every sphere
#: sees its 12 first neighbours once
REFERENCE_CELLS = {"fcc": (3, 3, 3), "hcp": (3, 2, 3)}
#: the zones of the CSV, as the page names them
ZONES = {"bulk": "bulk", "floor": "floor layer", "walls": "side-wall layer"}

Reference = namedtuple("Reference", "n phi crystalline_fraction q6_mean Q6")
Reference.__doc__ = ("The order of an exact lattice as :class:`Crystallinity` measures it: "
                     "``n`` spheres, ``phi`` their volume fraction in the periodic block "
                     "(pi/sqrt(18) for both), ``crystalline_fraction``, ``q6_mean``, ``Q6``.")


def add_arguments(parser):
    """No options beyond --campaign and --out."""


def lattice(name):
    """(positions, box side lengths) of a periodic block of FCC or HCP (ideal c/a) of
    contact distance 1 (radius 0.5), :data:`REFERENCE_CELLS` cells."""
    if name == "fcc":
        a = math.sqrt(2.0)
        basis, cell = [[0, 0, 0], [.5, .5, 0], [.5, 0, .5], [0, .5, .5]], [a, a, a]
    elif name == "hcp":
        basis = [[0, 0, 0], [.5, .5, 0], [.5, 1 / 6, .5], [0, 2 / 3, .5]]
        cell = [1.0, math.sqrt(3.0), math.sqrt(8.0 / 3.0)]
    else:
        raise ValueError(f"lattice name = {name!r} must be one of {sorted(REFERENCE_CELLS)}")
    reps = REFERENCE_CELLS[name]
    idx = np.array(list(itertools.product(*(range(r) for r in reps))), float)
    pos = ((idx[:, None, :] + np.asarray(basis, float)[None]) * np.asarray(cell)).reshape(-1, 3)
    return pos, np.asarray(cell) * np.asarray(reps)


def reference(name):
    """The :class:`Reference` of the exact lattice ``name`` ("fcc" or "hcp"), periodic on
    every axis, measured with the campaign's criterion."""
    pos, box = lattice(name)
    c = Crystallinity(pos, 0.5, [0.0, 0.0, 0.0], box, [True, True, True]).compute()
    phi = c.n * (4.0 / 3.0) * math.pi * 0.5 ** 3 / float(np.prod(box))
    return Reference(c.n, phi, c.crystalline_fraction, float(np.nanmean(c.q[CRYSTAL_L])),
                     c.Q[CRYSTAL_L])


def read_packing(dump):
    """The last frame of a dump with its radii, QuestionError naming the file when it is
    missing, damaged (cut short) or has no radius column."""
    try:
        frame = read_dump(dump).frames[-1]
    except (TapmcFormatError, ValueError, IndexError, OSError) as err:
        raise QuestionError(f"{dump}: not a readable dump ({err})") from None
    if frame.radii is None:
        raise QuestionError(f"{dump}: no radius column (id x y z radius expected)")
    return frame


def run_dumps(run_dir):
    """(dump.0, dump.<last>) of a run folder, QuestionError naming the folder when either is
    missing."""
    steps = {}
    for path in run_dir.glob("dump.*.lammpstrj"):
        tag = path.name.split(".")[1]
        if tag.isdigit():
            steps[int(tag)] = path
    if 0 not in steps or len(steps) < 2:
        raise QuestionError(f"{run_dir}: needs dump.0.lammpstrj and a final dump.<taps>."
                            f"lammpstrj, has {sorted(p.name for p in steps.values()) or 'none'}")
    return steps[0], steps[max(steps)]


def packing_row(run_dir, dump, table):
    """The CSV row of one dump of a run (``table``: its taps.dat)."""
    frame = read_packing(dump)
    rows = last_rows(table)
    if frame.step not in rows:
        raise QuestionError(f"{run_dir / 'taps.dat'}: no row of step {frame.step}, the step "
                            f"of {dump.name} (ends at step {int(table['step'][-1])}: cut short?)")
    try:
        c = Crystallinity.from_frame(frame).compute()
    except ValueError as err:
        raise QuestionError(f"{dump}: {err}") from None
    zones = c.zones(band=FLOOR_BAND_OVER_R, margin=BULK_OVER_R)
    name = run_dir.name
    row = [name, name.split("_")[1], f"{eps_of(name):g}", int(name.rsplit("_s", 1)[1]),
           frame.step, int(table["step"][-1]), c.n,
           f"{float(table['phi_c'][rows[frame.step]]):.8f}", f"{c.Q[CRYSTAL_L]:.6f}",
           f"{zones['all'].q_mean[CRYSTAL_L]:.6f}", f"{c.crystalline_fraction:.6f}"]
    for zone in ZONES:
        z = zones[zone]
        row += [z.n, "" if z.n == 0 else f"{z.crystalline_fraction:.6f}"]
    print(f"{name} t = {frame.step}: {c!r}; bulk {zones['bulk'].crystalline_fraction:.4f}, "
          f"floor {zones['floor'].crystalline_fraction:.4f}", flush=True)
    return row


def analyse(campaign):
    """The rows of crystallinity.csv: dump.0 and the last dump of every finished run of
    :data:`RUN_PATTERN` (QuestionError when there is none)."""
    rows = []
    for run_dir in finished_runs(campaign, RUN_PATTERN):
        table = taps_table(run_dir / "taps.dat")
        if "phi_c" not in table.columns:
            raise QuestionError(f"{run_dir / 'taps.dat'}: no phi_c column")
        rows += [packing_row(run_dir, dump, table) for dump in run_dumps(run_dir)]
    return rows


def measure(args):
    save(args.out / CSV, analyse(args.campaign))


save, load = csv_schema(HEADER)


# ---- the page ------------------------------------------------------------------------------
def _value(row, key):
    return math.nan if row.get(key, "") == "" else float(row[key])


def _pct(value):
    return "—" if not np.isfinite(value) else f"{100 * value:.2f} %"


def initial_packings(rows, bc):
    """The distinct t = 0 packings of ``bc`` (runs of one seed share theirs), one row each."""
    seen = {}
    for r in rows:
        if r["bc"] == bc and r["tap"] == "0":
            seen.setdefault((r["phi_c"], r["Q6"], r["crystalline_all"]), r)
    return list(seen.values())


def _mean(rows, key):
    values = [_value(r, key) for r in rows]
    values = [v for v in values if np.isfinite(v)]
    return float(np.mean(values)) if values else math.nan


def _table(rows, tapped, refs):
    """The list-table: the exact lattices, the initial packings per bc (means over the
    distinct ones), every run's last packing."""
    cols = ["phi_c", "Q6", "q6_mean", "crystalline_all"] + [f"crystalline_{z}" for z in ZONES]
    header = ["packing", "<Phi^c>", "Q6", "mean q6", "crystalline: all"] + list(ZONES.values())
    table = []

    def line(label, values):
        phi, q_glob, q_loc = values[:3]
        return [[label, _pct(phi), '—' if not np.isfinite(q_glob) else f'{q_glob:.3f}',
                 '—' if not np.isfinite(q_loc) else f'{q_loc:.3f}']
                + [_pct(v) for v in values[3:]]]

    for name, ref in refs.items():
        table += line(f"{name.upper()} (exact lattice, periodic)",
                      [ref.phi, ref.Q6, ref.q6_mean, ref.crystalline_fraction]
                      + [math.nan] * len(ZONES))
    for bc in ("pbc", "fbc"):
        start = initial_packings(rows, bc)
        if start:
            table += line(f"initial {bc.upper()[0]}.B.C. packings (t = 0, mean of "
                          f"{len(start)})", [_mean(start, k) for k in cols])
    for r in tapped:
        table += line(f"{r['run']} (t = {r['tap']})", [_value(r, k) for k in cols])
    return list_table(header, table)


def _finding(rows, tapped, refs):
    """The sentences the numbers say: the densest tapped packing against its initial one, and
    the floor and wall layers against the bulk."""
    dense = max(tapped, key=lambda r: _value(r, "phi_c"))
    start = next((r for r in rows if r["run"] == dense["run"] and r["tap"] == "0"), None)

    def zone_text(zone):
        now = _value(dense, f"crystalline_{zone}")
        before = math.nan if start is None else _value(start, f"crystalline_{zone}")
        return f"{_pct(now)} (t = 0: {_pct(before)})"

    text = (f"* The densest tapped packing, {dense['run']} (<Phi^c> = "
            f"{_pct(_value(dense, 'phi_c'))} after {dense['tap']} taps), is crystalline in "
            f"the bulk at {zone_text('bulk')}, in the floor layer at {zone_text('floor')}")
    if dense["n_walls"] not in ("", "0"):
        text += f", in the side-wall layer at {zone_text('walls')}"
    text += ", against " + ", ".join(f"{_pct(r.crystalline_fraction)} for {n.upper()}"
                                     for n, r in refs.items()) + ". "
    text += _layers(tapped)
    return [text, ""]


def _layers(tapped):
    """Whether the floor and side-wall layers differ from the bulk, over the tapped
    packings."""
    parts = []
    for zone in ("floor", "walls"):
        pairs = [(r, _value(r, f"crystalline_{zone}") - _value(r, "crystalline_bulk"))
                 for r in tapped if np.isfinite(_value(r, f"crystalline_{zone}"))
                 and np.isfinite(_value(r, "crystalline_bulk"))]
        if not pairs:
            continue
        more = sum(d > 0 for _, d in pairs)
        top, excess = max(pairs, key=lambda p: p[1])
        parts.append(f"the {ZONES[zone]} is more crystalline than the bulk in {more} of "
                     f"{len(pairs)} tapped packings" + (
                         f" (largest excess: {top['run']}, "
                         f"{_pct(_value(top, f'crystalline_{zone}'))} against "
                         f"{_pct(_value(top, 'crystalline_bulk'))})" if excess > 0 else ""))
    bulk = max(tapped, key=lambda r: _value(r, "crystalline_bulk"))
    parts.append(f"the most crystalline bulk is {bulk['run']}'s, "
                 f"{_pct(_value(bulk, 'crystalline_bulk'))}")
    text = "; ".join(parts) + "."
    return text[0].upper() + text[1:]


def render(path, refs=None):
    """The table of the packings' order against the exact lattices and the initial
    packings, and the sentence of what it says; ``refs``: {name: Reference} (default: FCC
    and HCP measured now by :func:`reference`)."""
    rows = sorted(load(path), key=lambda r: (r["bc"] != "pbc", float(r["eps"]),
                                             int(r["seed"]), int(r["tap"])))
    tapped = [r for r in rows if r["tap"] != "0" and np.isfinite(_value(r, "phi_c"))]
    if not tapped:
        return []
    refs = refs if refs is not None else {name: reference(name) for name in REFERENCE_CELLS}
    lines = ["Do the campaign's densest tapped packings crystallize, which would make a "
             "packing denser than the paper's a model effect of ordering? Every finished "
             "constant-eps run's packing at t = 0 and after its taps (``crystallinity.csv``, "
             "``tapmc-paper question crystallinity``: ``tapmc.crystallinity.Crystallinity``, "
             "bonds within 1.2 d, Steinhardt q6; a sphere is crystalline with 8 or more "
             "solid-like bonds, ten Wolde et al. 1996): the global Q6, the mean local q6 and "
             "the crystalline fraction of all spheres, of the bulk "
             f"({BULK_OVER_R:g} R or more from the floor, the walls and the free surface), of "
             f"the floor layer and of the side-wall layer (centres within "
             f"{FLOOR_BAND_OVER_R:g} R), beside exact lattices measured by the same code:", ""]
    return lines + _table(rows, tapped, refs) + [""] + _finding(rows, tapped, refs)
