# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""How the front writes its numbers in text: value +- error, seed counts, rst tables."""


def plus_minus(value, err, digits=4, sign=True):
    """'+0.0012 +- 0.0003' (n/a for nan; the error left out when it is nan)."""
    if value != value:
        return "n/a"
    text = f"{value:+.{digits}f}" if sign else f"{value:.{digits}f}"
    return text if err != err else f"{text} +- {err:.{digits}f}"


def seeds_text(n):
    n = int(n)
    return f"{n} seed" if n == 1 else f"{n} seeds"


def rst_table(header, rows):
    """An rst simple table."""
    cols = list(zip(*([header] + rows)))
    widths = [max(len(str(c)) for c in col) for col in cols]
    rule = "  ".join("=" * w for w in widths)
    out = [rule, "  ".join(str(h).ljust(w) for h, w in zip(header, widths)), rule]
    out += ["  ".join(str(c).ljust(w) for c, w in zip(r, widths)) for r in rows]
    out.append(rule)
    return out
