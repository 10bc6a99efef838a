# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""How much the verdicts rest on the report's conventions (:mod:`.conventions`): the register
re-evaluated on the same loaded data with each convention halved and doubled, and the
page's table of tolerances (:func:`tolerance_table`).

A convention is patched where the modules bind it (each imports it by name from
:mod:`.conventions` or tapmc.stats), for the duration of one evaluation. Only the claims it
can reach are evaluated again: those of the statistic modules that bind it, every claim when
a module of the rules, the calibration or the shared statistics binds it, and a convention of
the rules alone re-decides the measures of the first evaluation without computing them
again (:func:`tapmc.paper.claims.evaluate`'s ``measures``).
"""

from __future__ import annotations

import contextlib
import sys
from dataclasses import dataclass

from .._rst import list_table
from .conventions import CONVENTIONS
from .evaluate import evaluate
from .registry import STATISTICS

#: the package whose modules may bind a convention
_PACKAGE = "tapmc"
#: the package of the register's statistics and rules
_CLAIMS = "tapmc.paper.claims"
#: modules whose binding of a convention only changes how a measure is decided (the rules,
#: the scale's exception for ramps), not the measure
_RULE_MODULES = {f"{_CLAIMS}.{name}" for name in ("rules", "conventions", "evaluate",
                                                   "reduced_ramps")}
#: modules outside the register's package whose binding reaches every statistic
_SHARED_MODULES = {"tapmc.stats"}
#: modules whose binding of a convention changes the realizations' calibration that
#: ReportData applies once where the figures load: evaluated on a copy calibrated anew
_CALIBRATION_MODULES = {f"{_CLAIMS}.{name}" for name in ("calibration", "data")}


@dataclass(frozen=True)
class Sensitivity:
    """One convention (:class:`.conventions.Convention`) and the verdicts (rows of the
    register) that change when it is halved and when it is doubled (None: not re-evaluated,
    the convention acts before the report), with the ids of their claims."""

    convention: object
    halved: int | None
    doubled: int | None
    claims: tuple = ()


def binding_modules(name, value):
    """The loaded modules of the package that bind ``name`` to ``value`` (the same object,
    as ``from M import name`` binds it)."""
    return [module for key, module in sorted(sys.modules.items())
            if module is not None and (key == _PACKAGE or key.startswith(_PACKAGE + "."))
            and getattr(module, "__dict__", {}).get(name, _MISSING) is value]


_MISSING = object()


@contextlib.contextmanager
def patched(name, value, new):
    """Every module that binds ``name`` to ``value`` binds it to ``new`` inside the block."""
    modules = binding_modules(name, value)
    for module in modules:
        setattr(module, name, new)
    try:
        yield modules
    finally:
        for module in modules:
            setattr(module, name, value)


def _outcomes(rows):
    """claim id -> [(label, outcome), ...] of its rows, in order."""
    out = {}
    for row in rows:
        out.setdefault(row.claim.id, []).append((row.label, row.outcome))
    return out


def changed(before, after):
    """(claim id, label) of the rows whose outcome differs between two evaluations
    (:func:`_outcomes`); a claim whose rows differ in their labels (a convention that
    changes what is measured) has every row of the first evaluation changed."""
    out = []
    for claim in sorted(set(before) | set(after)):
        old, new = before.get(claim, []), after.get(claim, [])
        if [label for label, _ in old] != [label for label, _ in new]:
            out += [(claim, label) for label, _ in (old or new)]
        else:
            out += [(claim, label) for (label, a), (_, b) in zip(old, new) if a != b]
    return out


def _reached(modules, register, measures):
    """(claims to evaluate again, the measures they may reuse, whether the data must be
    calibrated anew) for a convention the ``modules`` bind: a module of the rules reaches
    every claim, whose measures are reused but for the claims of a statistic module that
    binds it too; statistic modules alone reach their own claims; any other module of the
    register (the shared statistics, the calibration) or tapmc.stats every claim afresh."""
    # the package re-exports the conventions; a library module outside the register's
    # package (tapmc.laws' SurrogateFits) binds one for its own computations, which the
    # report reads from the CSVs
    names = {m.__name__ for m in modules if m.__name__ != _CLAIMS
             and (m.__name__.startswith(_CLAIMS + ".") or m.__name__ in _SHARED_MODULES)}
    statistic_modules = {f.__module__ for f in STATISTICS.values()}
    own = [c for c in register if c.statistic and STATISTICS[c.statistic].__module__ in names]
    if names - _RULE_MODULES - statistic_modules:
        return list(register), {}, bool(names & _CALIBRATION_MODULES)
    if names & _RULE_MODULES - {f"{_CLAIMS}.conventions"}:
        fresh = {c.id for c in own}
        return list(register), {k: v for k, v in measures.items() if k not in fresh}, False
    return own, {}, False


def convention_changes(convention, factor, rows, measures):
    """The rows of ``rows`` (:class:`.evaluate.Rows` of the first evaluation) whose outcome
    changes with ``convention`` scaled by ``factor`` (:meth:`Convention.varied`); None when
    the convention is not varied. ``measures``: the first evaluation's measures by claim id
    (reused where the convention cannot change them, :func:`_reached`)."""
    new = convention.varied(factor)
    if new is None:
        return None
    with patched(convention.name, convention.value, new) as modules:
        claims, reused, recalibrate = _reached(modules, rows.register, measures)
        if not claims:
            return []
        data = rows.data.recalibrated() if recalibrate else rows.data
        again = evaluate(claims, data, reused)
    ids = {c.id for c in claims}
    return changed(_outcomes([r for r in rows if r.claim.id in ids]), _outcomes(again))


def sensitivities(rows, conventions=CONVENTIONS):
    """:class:`Sensitivity` of every convention for the rows of one evaluation
    (:class:`.evaluate.Rows`, which keep the register and the loaded data)."""
    measures = {}                 # the measures the rules re-decide: one row per measure
    for row in rows:
        if row.claim.statistic:
            measures.setdefault(row.claim.id, []).append(row.measure)
    out = []
    for convention in conventions:
        halved, doubled = (convention_changes(convention, f, rows, measures) for f in (0.5, 2))
        claims = sorted({k[0] for k in (halved or []) + (doubled or [])})
        out.append(Sensitivity(convention, None if halved is None else len(halved),
                               None if doubled is None else len(doubled), tuple(claims)))
    return out


def _number(value):
    return f"{value:g}" if isinstance(value, float) else str(value)


def tolerance_table(rows, conventions=CONVENTIONS):
    """The page's table of tolerances (rst lines): each convention of the report, its value,
    what it decides, its source and how many verdicts change when it is halved and doubled
    (:func:`sensitivities` of ``rows``, a :class:`.evaluate.Rows`)."""
    found = sensitivities(rows, conventions)
    lines = ["Tolerances and their sensitivity", "-" * 32, "",
             "Every hand-typed number that decides a verdict "
             "(``tools/python/tapmc/paper/claims/conventions.py``): its source, and how many "
             f"of the {len(rows)} rows' verdicts (:doc:`validation_claims`) change when it is "
             "halved and when it is "
             "doubled (re-evaluated on the same data; a confidence level's tail 1 - level is "
             "halved and doubled; a count is rounded). '-': applied when a figure or a "
             "question wrote its CSV, not re-evaluated from the committed data.", ""]
    table = []
    for s in found:
        c = s.convention
        source = c.source + (f" (applied in {c.where})" if c.where else "")
        table.append([f"``{c.name}``", _number(c.value), c.decides, source,
                      '-' if s.halved is None else s.halved,
                      '-' if s.doubled is None else s.doubled,
                      ', '.join(s.claims) or ('none' if s.halved is not None else '-')])
    header = ["Convention", "Value", "Decides", "Source", "Halved", "Doubled",
              "Claims that change"]
    return lines + list_table(header, table, widths=(18, 8, 30, 26, 6, 6, 16)) + [""]
