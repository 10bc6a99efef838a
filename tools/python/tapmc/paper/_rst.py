# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The two rst tables the pages write: the simple table (columns aligned in the source) and
the list-table (one line per cell: cells of any length, and the form Sphinx wraps)."""


def simple_table(header, rows):
    """An rst simple table of a header and rows of cells (each written with str())."""
    cols = list(zip(*([header] + rows)))
    widths = [max(len(str(c)) for c in col) for col in cols]
    rule = "  ".join("=" * w for w in widths)
    out = [rule, "  ".join(str(h).ljust(w) for h, w in zip(header, widths)), rule]
    out += ["  ".join(str(c).ljust(w) for c, w in zip(r, widths)) for r in rows]
    out.append(rule)
    return out


def list_table(header, rows, widths=None):
    """The lines of an rst list-table: a header row, then the rows (sequences of cells, each
    written with str()); ``widths``: the relative column widths, or None for Sphinx's."""
    lines = [".. list-table::", "   :header-rows: 1"]
    if widths:
        lines.append("   :widths: " + " ".join(str(w) for w in widths))
    lines.append("")
    for row in [header, *rows]:
        lines += [f"   * - {row[0]}"] + [f"     - {cell}" for cell in row[1:]]
    return lines
