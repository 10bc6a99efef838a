# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""front_summary.csv, package data: the front's table (one row per N, eps and setting) that
``tapmc-paper front`` writes and the validation reports and ``tapmc-paper plan`` read, and the
sentence the reports print on the bias of their redeposition setting."""

import csv
import io
import os

from .settings import REFERENCE, TAPS, setting_named, time_window
from .text import plus_minus

#: the summary the reports read (package data, written by ``tapmc-paper front``)
SUMMARY = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                       "front_summary.csv")
#: its text columns (every other column is a number)
TEXT_COLUMNS = ("setting", "eta", "settle_keys")


def summary_text(rows):
    """The CSV text of the summary rows (``Front.summary_rows()``; floats with 6 significant
    digits)."""
    out = io.StringIO()
    w = csv.DictWriter(out, fieldnames=list(rows[0].keys()))
    w.writeheader()
    for r in rows:
        w.writerow({k: (("%.6g" % v) if isinstance(v, float) else v) for k, v in r.items()})
    return out.getvalue()


def read_summary(path=SUMMARY):
    """The rows of front_summary.csv (numbers as floats), or [] when absent."""
    if not os.path.isfile(path):
        return []
    out = []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            conv = {}
            for k, v in row.items():
                try:
                    conv[k] = float(v) if k not in TEXT_COLUMNS else v
                except ValueError:
                    conv[k] = v
            out.append(conv)
    return out


def bias_sentence(eta, stop="change", path=SUMMARY):
    """What the front measured of a redeposition setting, as one sentence for the reports."""
    name = setting_named(eta, stop)
    rows = [r for r in read_summary(path) if r["setting"] == name] if name else []
    if not rows:
        return (f"The run-time-versus-error front (``doc/front.rst``) has not measured "
                f"eta = {eta:g} (stop {stop}).")
    parts = []
    for r in sorted(rows, key=lambda r: (r["N"], r["eps"])):
        if name != REFERENCE and not r.get("paired_seeds", 0) >= 1:
            continue  # the reference has not run at this N and eps yet: no bias to state
        if name == REFERENCE:
            parts.append(f"N = {r['N']:.0f}, eps = {r['eps']:g}: the reference itself")
            continue
        seeds_ = int(r["paired_seeds"])
        parts.append(f"N = {r['N']:.0f}, eps = {r['eps']:g} ({seeds_} seed{'s' if seeds_ != 1 else ''}): "
                     f"<Phi^c> {plus_minus(r['phi_c_t1000_bias'], r['phi_c_t1000_bias_se'])} over taps "
                     "%d-%d, " % time_window(TAPS)
                     + f"{plus_minus(r['phi_c_steady_bias'], r['phi_c_steady_bias_se'])} "
                     f"steady, Phi_b {plus_minus(r['phi_b_steady_bias'], r['phi_b_steady_bias_se'])} "
                     f"steady, at {r['cpu_per_tap']:.3f} CPU s per tap")
    return (f"Measured bias of eta = {eta:g} (stop {stop}) against *{REFERENCE}* on the "
            f"run-time-versus-error front (``doc/front.rst``): " + "; ".join(parts) + ".")
