# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""integrity: do thousands of taps leave a legal hard-sphere packing, and do the numbers a run
prints describe the packing it dumps? Every dump of the paper-scale campaign (no simulation:
the t = 0 and final packings of every run, Fig. 10's nine) checked offline
(tapmc.packing.PackingCheck): spheres, the closest pair (overlaps beyond the model's
tolerance and the dump's rounding), the floor and the side walls; and Phi_b, <Phi^c>, <Z>,
z_top, h_s recomputed from the positions against the run's taps.dat row of that tap
(integrity.csv)."""

from __future__ import annotations

from collections import defaultdict

from tapmc.packing import PackingCheck
from tapmc.readers import TapmcFormatError, read_dump

from .._rst import list_table
from ..claims import fmt
from .common import QuestionError, csv_schema, last_rows, runs_folder, taps_table

NAME = "integrity"
CSV = "integrity.csv"
HEADER = ["run", "tap", "n", "min_gap", "overlaps", "floor_gap", "wall_gap", "legal",
          "resolution_rel", "phi_c", "scalars_worst", "scalars_worst_column"]
#: columns of a run's taps.dat that a dumped packing reproduces (tapmc.packing.PackingCheck)
INTEGRITY_COLUMNS = ("phi_b", "phi_c", "Z", "z_top", "h_s")
#: what the dump's rounding (%.10g: 5e-9 on a coordinate of the paper's box) can move a mean
#: height, a slab fraction or the surface height by, at most (with a factor 2 of room)
INTEGRITY_SLACK = 1e-8


def add_arguments(parser):
    """No options beyond --campaign and --out."""


def printed_decimals(path, width):
    """dict step -> the decimals printed in each field of that step's last row of a taps.dat
    (read_fix_print gives the values; the allowance of a printed value is half a unit of its
    last printed digit, which only the text holds). Rows of another width (a cut last line)
    are left out."""
    decimals = {}
    with open(path) as handle:
        for line in handle:
            fields = line.split()
            if line.startswith("#") or len(fields) != width:
                continue
            decimals[int(float(fields[0]))] = [len(f.split(".")[1]) if "." in f else 0
                                               for f in fields]
    return decimals


def _frame(dump):
    """The last frame of a dump, QuestionError naming the file when it is damaged."""
    try:
        return read_dump(dump).frames[-1]
    except (TapmcFormatError, ValueError, IndexError, OSError) as err:
        raise QuestionError(f"{dump}: not a readable dump ({err})") from None


def _worst_scalar(scalars, table, decimals, step):
    """(the largest difference between a recomputed and a printed scalar, in units of what
    the print and the dump's rounding allow, its column); (None, "") when the tap was not
    printed."""
    rows = last_rows(table)
    if step not in rows:
        return None, ""
    worst, worst_name = 0.0, ""
    for name in INTEGRITY_COLUMNS:
        if name not in table.columns:
            continue
        printed = float(table[name][rows[step]])
        places = decimals.get(step, [0] * len(table.columns))[table.columns.index(name)]
        allowed = 0.5 * 10.0 ** -places + INTEGRITY_SLACK
        ratio = abs(scalars[name] - printed) / allowed
        if ratio >= worst:
            worst, worst_name = ratio, name
    return worst, worst_name


def _dump_row(run_dir, dump, table, decimals):
    frame = _frame(dump)
    last = int(table["step"][-1])
    if frame.step > last:   # a run's taps.dat prints every tap up to its last dump
        raise QuestionError(f"{run_dir / 'taps.dat'}: ends at step {last} (row {len(table)}), "
                            f"before the dump {dump.name} of step {frame.step}: cut short?")
    check = PackingCheck(frame).compute()
    worst, worst_name = _worst_scalar(check.scalars(), table, decimals, frame.step)
    print(f"{run_dir.name} t = {frame.step}: {check!r}, printed scalars within "
          f"{worst if worst is not None else float('nan'):.2f} of their allowance "
          f"({worst_name})", flush=True)
    return [run_dir.name, frame.step, check.n, f"{check.min_gap:.4g}", check.overlaps,
            f"{check.floor_gap:.4g}", "" if check.wall_gap is None else f"{check.wall_gap:.4g}",
            int(check.legal), f"{check.resolution / (2 * float(check.radii.min())):.3g}",
            f"{check.phi_c:.8f}", "" if worst is None else f"{worst:.3g}", worst_name]


def analyse(campaign):
    """The rows of integrity.csv: every dump of every run with a taps.dat."""
    rows = []
    for run_dir in sorted(p for p in runs_folder(campaign).iterdir() if p.is_dir()):
        dumps = sorted(run_dir.glob("dump.*.lammpstrj"),
                       key=lambda p: int(p.name.split(".")[1]))
        if not dumps or not (run_dir / "taps.dat").is_file():
            continue
        table = taps_table(run_dir / "taps.dat")
        decimals = printed_decimals(run_dir / "taps.dat", len(table.columns))
        rows += [_dump_row(run_dir, dump, table, decimals) for dump in dumps]
    if not rows:
        raise QuestionError(f"--campaign {campaign}: no run has dumps and a taps.dat")
    return rows


def measure(args):
    save(args.out / CSV, analyse(args.campaign))


save, load = csv_schema(HEADER)


def render(path):
    rows = load(path)
    if not rows:
        return []
    by_run = defaultdict(list)
    for r in rows:
        by_run[r["run"]].append(r)
    lines = ["Do thousands of taps leave a legal hard-sphere packing, and do the numbers a run "
             "prints describe the packing it dumps? Every dump of the campaign checked offline "
             "(``integrity.csv``; ``tapmc.packing.PackingCheck``, numpy, no LAMMPS): the "
             "spheres; the closest pair, \\|r_ij\\| - (R_i + R_j) over R_i + R_j, in the deposited "
             "packing (t = 0) and after taps; the overlaps, pairs closer than contact by more "
             "than the model's tolerance (1e-10) plus what the dump's rounding allows; the "
             "lowest sphere's gap to the floor and the closest sphere's to a side wall (over "
             "its diameter); and Phi_b, <Phi^c>, <Z>, z_top and h_s recomputed from the "
             "positions against the run's printed row of that tap, as the largest difference "
             "in units of what the print's last digit and the dump's rounding allow (below 1 "
             "is agreement):", ""]
    header = ["run", "dumps at taps", "spheres", "closest pair, t = 0",
              "closest pair after taps", "overlaps", "floor gap", "wall gap", "printed scalars"]
    table = []

    def low(items, key):
        values = [float(r[key]) for r in items if r[key] != ""]
        return min(values) if values else None

    def gap(value):
        return "none" if value is None else fmt(value)

    worst_all = (0.0, "", "", "")
    for run, items in sorted(by_run.items()):
        items.sort(key=lambda r: int(r["tap"]))
        wall = low(items, "wall_gap")
        printed = [r for r in items if r["scalars_worst"] != ""]
        worst = max(printed, key=lambda r: float(r["scalars_worst"])) if printed else None
        if worst is not None and float(worst["scalars_worst"]) >= worst_all[0]:
            worst_all = (float(worst["scalars_worst"]), worst["scalars_worst_column"], run,
                         worst["tap"])
        counts = sorted({int(r["n"]) for r in items})
        table.append([run, ', '.join(r['tap'] for r in items), ', '.join(map(str, counts)),
                      gap(low([r for r in items if r['tap'] == '0'], 'min_gap')),
                      gap(low([r for r in items if r['tap'] != '0'], 'min_gap')),
                      sum(int(r['overlaps']) for r in items), fmt(low(items, 'floor_gap')),
                      'periodic' if wall is None else fmt(wall),
                      "not printed" if worst is None else
                      f"{float(worst['scalars_worst']):.2f} "
                      f"({worst['scalars_worst_column']}, t = {worst['tap']})"])
    return lines + list_table(header, table) + _summary(rows, by_run, worst_all)


def _summary(rows, by_run, worst_all):
    """The page's two readings of integrity.csv: legal packings, and printed scalars that
    describe them (``worst_all``: the largest printed-scalar difference, its column, run and
    tap)."""
    lines = []
    illegal = [r for r in rows if r["legal"] != "1"]
    counts = {int(r["n"]) for r in rows}
    resolution = max(float(r["resolution_rel"]) for r in rows)
    tapped = [r for r in rows if r["tap"] != "0"]
    closest = min(tapped, key=lambda r: float(r["min_gap"])) if tapped else None
    mismatched = [r for r in rows if r["scalars_worst"] != "" and float(r["scalars_worst"]) >= 1]
    start = [float(r["min_gap"]) for r in rows if r["tap"] == "0"]
    deposited = ("" if not start else
                 "The deposited packings (t = 0) hold exact contacts: their closest pairs are "
                 "within the resolution of zero" if max(abs(g) for g in start) <= resolution
                 else f"The deposited packings' (t = 0) closest pair is {fmt(min(start))} of "
                      "contact")
    lines += ["", f"* {len(rows)} dumps of {len(by_run)} runs: "
              + (f"every one holds {counts.pop()} spheres" if len(counts) == 1 else
                 f"the sphere counts differ ({', '.join(map(str, sorted(counts)))})")
              + "; " + ("every one is a legal hard-sphere packing: no overlap beyond the "
                        "tolerance and the dumps' resolution (pair distances known to "
                        f"{resolution:.2g} of contact), nothing below the floor or through a "
                        "wall. " + deposited
                        + ("" if closest is None else
                           f"; after taps the closest pair is {fmt(float(closest['min_gap']))}"
                           f" of contact ({closest['run']}, t = {closest['tap']}): thousands of "
                           "taps of dilation and redeposition leave no rounding drift into "
                           "overlap") + "."
                        if not illegal else
                        "NOT all are legal: " + "; ".join(
                            f"{r['run']} t = {r['tap']} ({r['overlaps']} overlaps, floor gap "
                            f"{r['floor_gap']}, wall gap {r['wall_gap'] or 'periodic'})"
                            for r in illegal) + "."),
              "* The printed scalars "
              + ("are those of the dumped packings: recomputed from the positions alone, "
                 "every one matches its print within the print's last digit (largest: "
                 f"{worst_all[0]:.2f} of the allowance, {worst_all[1]} of {worst_all[2]} "
                 f"at t = {worst_all[3]}), so the page's numbers, read from the prints, "
                 "describe the packings the pore and P0 analyses read from the dumps."
                 if not mismatched else
                 "differ from the dumped packings' at " + "; ".join(
                     f"{r['run']} t = {r['tap']} ({r['scalars_worst_column']}: "
                     f"{float(r['scalars_worst']):.3g} of the allowance)" for r in mismatched)
                 + "."), ""]
    return lines

