# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""How the front writes its numbers in text: value +- error, seed counts."""


def plus_minus(value, err, digits=4, sign=True):
    """'+0.0012 +- 0.0003' (n/a for nan; the error left out when it is nan)."""
    if value != value:
        return "n/a"
    text = f"{value:+.{digits}f}" if sign else f"{value:.{digits}f}"
    return text if err != err else f"{text} +- {err:.{digits}f}"


def seeds_text(n):
    n = int(n)
    return f"{n} seed" if n == 1 else f"{n} seeds"

