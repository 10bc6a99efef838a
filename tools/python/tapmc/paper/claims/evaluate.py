# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The rows of the report: each claim of the register measured by its statistic and judged
by its rule, with the parts of the paper's scale the campaign lacks."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from ..fig4 import RAMPS
from ..scales import SCALES
from .common import campaign_ramp_label
from .measure import Measure
from .reduced_ramps import reduced_ramp_verdict, ramp_reduction_bounds
from .register import Claim, PAPER_SCALE
from .registry import STATISTICS
from .rules import Outcome, Verdict, undecided, verdict


def scale_aspects(summary):
    """The parts of the paper's scale (:data:`ASPECTS`) a campaign summary meets."""
    met = set()
    sizes = [tuple(s) for s in summary.get("sizes", [])]
    if sizes and all(int(n) == PAPER_SCALE["N"] and float(l) == PAPER_SCALE["L"]
                     for n, l in sizes):
        met.add("size")
    etas = summary.get("eta", [])
    if etas and all(math.isclose(float(e), PAPER_SCALE["eta"]) for e in etas):
        met.add("eta")
    scale = None
    if summary.get("preset") and summary.get("scale") in SCALES:
        scale = SCALES[summary["scale"]]
    fields = summary.get("fields") or {}
    taps = scale.taps if scale is not None else fields.get("taps")
    per_level = scale.ramp_taps_per_level if scale is not None else \
        fields.get("ramp_taps_per_level")
    if taps is not None and int(taps) >= PAPER_SCALE["taps"]:
        met.add("taps")
    if summary.get("ramp_taps_per_level"):   # what the ramps ran with decides, not the preset
        per_level = min(summary["ramp_taps_per_level"])
    if per_level is not None and int(per_level) >= PAPER_SCALE["ramp_taps"]:
        met.add("ramp_taps")
    return met


@dataclass
class Row:
    """One row of the report: the claim, the label of its measure, the measure, the verdict
    and whether the campaign had the scale the claim needs."""

    claim: Claim
    label: str
    measure: Measure
    verdict: Verdict
    missing_scale: tuple

    @property
    def outcome(self):
        """The verdict's :class:`Outcome`."""
        return self.verdict.outcome


class Rows(list):
    """The rows of one evaluation (:func:`evaluate`), with what they were evaluated from:
    ``register`` (the claims) and ``data`` (the :class:`ReportData`), so that the table of
    tolerances (:mod:`.sensitivity`) re-evaluates them without loading the data again."""

    def __init__(self, rows=(), register=(), data=None):
        super().__init__(rows)
        self.register = list(register)
        self.data = data


def evaluate(claims, data, measures=None):
    """The report rows (:class:`Rows`) of every claim (one per measure) for ``data``
    (:class:`ReportData`).

    A model claim the campaign lacks part of the paper's scale for is undecided, with one
    exception: the ramp at fewer taps per level than the paper's, when ramp-levels measured
    the levels' shift to 4000 taps on every branch the measure reads and the verdict stays
    the same anywhere within the range the shifts give (:func:`reduced_ramp_verdict`). A row
    of a claim that needs the paper's ramp_taps and was decided on the campaign's own ramps is
    labelled with their taps per level and eta (:func:`.common.campaign_ramp_label`).
    ``measures``: claim id -> its statistic's measures, filled by the statistics the first
    time and read the next (a convention of the rules alone re-decides the same measures)."""
    met = scale_aspects(data.summary)
    bounds = {tag: ramp_reduction_bounds(data, tag) for tag, *_ in RAMPS}
    per_level = ", ".join(map(str, data.summary.get("ramp_taps_per_level") or []))
    ramp_label = campaign_ramp_label(data.summary)
    rows = Rows(register=claims, data=data)
    for claim in claims:
        missing = tuple(a for a in claim.needs if a not in met)
        if not claim.statistic:
            rows.append(Row(claim, "", Measure(), verdict(claim, Measure()), missing))
            continue
        if measures is None or claim.id not in measures:
            found_measures = STATISTICS[claim.statistic](data, claim)
            if measures is not None:
                measures[claim.id] = found_measures
        else:
            found_measures = measures[claim.id]
        for m in found_measures:
            if "ramp_taps" in claim.needs and "ramp_taps" not in m.meets and ramp_label \
                    and not m.label:
                m = dataclasses.replace(m, label=ramp_label)   # decided on the campaign's ramps
            found = verdict(claim, m)
            lacking = tuple(a for a in missing if a not in m.meets) + tuple(
                a for a in m.lacks if a not in missing)
            if lacking and found.outcome != Outcome.UNDECIDED and claim.kind == "model":
                decided, reach = (reduced_ramp_verdict(claim, m, found, data, bounds, per_level)
                                  if lacking == ("ramp_taps",) else (None, ""))
                found = decided or undecided(f"scale: needs the paper's {', '.join(lacking)}; "
                                             f"at this scale it {found.outcome}{reach}")
            rows.append(Row(claim, m.label, m, found, lacking))
    return rows
