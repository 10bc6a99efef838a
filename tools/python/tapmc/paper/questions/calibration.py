# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The page's calibration tables, shared by realization-scatter and packing-scatter: each
group's spread between realizations against its own errors, the factors pooled over the
groups, and the comparison of the boundary conditions' factors. Both questions write
realization_scatter.csv's columns (SCATTER_HEADER)."""

from __future__ import annotations

from .._rst import list_table
from ..claims import (CALIBRATION_ALPHA, RUN_ERROR_LABELS, realization_calibrations,
                      realization_sharing)
from .common import csv_schema

#: the columns of realization_scatter.csv and packing_scatter.csv
SCATTER_HEADER = ["group", "run", "seed", "taps", "column", "start", "mean", "sem", "last",
                  "sem_dof"]


save, load = csv_schema(SCATTER_HEADER)


def calibration_table(calib, table_names, pooled_names, headers, realizations):
    """The list-table of every group's spread against its own errors for the quantities of
    ``table_names`` (key -> name) and the line of the factors pooled over the groups for
    those of ``pooled_names``; ``headers``: (the groups' column, the errors' column);
    ``realizations(group, n)``: the text of a group's realizations cell."""
    table = []
    for column in (c for c in table_names if c in calib):
        c = calib[column]
        for group in c.ratios:
            table.append([group, realizations(group, len(c.groups[group][0])),
                          table_names[column], f"{c.spreads[group]:.3g}",
                          f"{c.errors[group]:.3g}", f"{c.ratios[group]:.2f}"])
    lines = list_table([headers[0], "realizations", "quantity", "spread between realizations",
                        headers[1], "ratio"], table)
    pooled = []
    for key in (k for k in pooled_names if k in calib):
        c = calib[key]
        low, high = c.interval()
        pooled.append(f"{pooled_names[key]}: k = {c.factor:.2f} (95 %: {low:.2f} to "
                      f"{high:.2f}; {c.dof} dof, p of k = 1: {c.p_value:.2g})")
    return lines + ["", "* Pooled over the groups: " + "; ".join(pooled) + "."]


def scatter_quantity(key):
    """How the realization-scatter section names a quantity of realization_scatter.csv."""
    what = {"": " steady state", "halves": ", halves' difference"}.get(
        key.partition(":")[2], "")
    return RUN_ERROR_LABELS[key].removesuffix(" halves") + what


def scatter_by_bc(rows):
    """The line that compares the P.B.C. and F.B.C. groups' factors (none without groups of
    both)."""
    sharing = realization_sharing(rows)
    if not sharing:
        return []
    by_bc = {bc: realization_calibrations(rows, bc) for bc in ("pbc", "fbc")}
    items = [f"{scatter_quantity(key)}: P.B.C. k = {by_bc['pbc'][key].factor:.2f} "
             f"({by_bc['pbc'][key].dof} dof), F.B.C. k = {by_bc['fbc'][key].factor:.2f} "
             f"({by_bc['fbc'][key].dof} dof), p = {sharing[key]:.2g}"
             for key in RUN_ERROR_LABELS if key in sharing]
    apart = [scatter_quantity(k) for k in RUN_ERROR_LABELS
             if sharing.get(k, 1.0) < CALIBRATION_ALPHA]
    return ["* By boundary condition (does one factor serve both? two-sided F test of the "
            "ratio of their k^2): " + "; ".join(items) + ". " + (
                "No quantity rejects one shared factor: the pooled k above serves the runs of "
                "both." if not apart else
                f"{', '.join(apart)}: the factors differ (p < {CALIBRATION_ALPHA:g}), so the "
                "runs of each boundary condition take their own groups' k there; the other "
                "quantities take the pooled k.")]

