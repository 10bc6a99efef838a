# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The claims register (``tapmc/paper/claims.toml``): one :class:`Claim` per [[claim]], checked
when loaded (kind, rule and its fields, statistic, scale aspects, unique ids)."""

from __future__ import annotations

import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from .registry import STATISTICS
from .rules import RULE_NAMES, RULES


#: The register, in tapmc/paper beside this package.
REGISTER = Path(__file__).resolve().parent.parent / "claims.toml"


#: The paper's scale (section II): N, box side in R, taps per run and per ramp level, eta.
PAPER_SCALE = {"N": 4096, "L": 32.0, "taps": 4000, "ramp_taps": 4000, "eta": 1e-7}


KINDS = ("model", "check")


ASPECTS = ("size", "taps", "ramp_taps", "eta")


@dataclass(frozen=True)
class Claim:
    """One [[claim]] of the register (see the comments at the top of ``claims.toml``)."""

    id: str
    section: str
    figure: str
    claim: str
    paper: str
    kind: str
    statistic: str
    rule: str
    tolerance: str
    decided_by: str
    needs: tuple = ()
    target: float | None = None
    lo: float | None = None
    hi: float | None = None
    sign: int | None = None
    rounding: float = 0.0
    params: dict = field(default_factory=dict)
    headline: bool | str = False
    could_fail: bool = True

    def __post_init__(self):
        where = f"claim {self.id!r}"
        if self.kind not in KINDS:
            raise ValueError(f"{where}: kind = {self.kind!r}: allowed values {KINDS}")
        if self.rule not in RULE_NAMES:
            raise ValueError(f"{where}: rule = {self.rule!r}: allowed values {RULE_NAMES}")
        bad = [a for a in self.needs if a not in ASPECTS]
        if bad:
            raise ValueError(f"{where}: needs = {bad}: allowed values {ASPECTS}")
        if self.statistic and self.statistic not in STATISTICS:
            raise ValueError(f"{where}: statistic = {self.statistic!r} is not one of "
                             f"tapmc.paper.claims.STATISTICS")
        if (self.rule == "none") != (not self.statistic):
            raise ValueError(f"{where}: rule 'none' goes with an empty statistic and only then")
        for name in RULES[self.rule].fields:
            if getattr(self, name) is None:
                raise ValueError(f"{where}: rule {self.rule!r} needs the field {name!r}")
        if self.sign not in (None, -1, 1):
            raise ValueError(f"{where}: sign = {self.sign!r}: allowed values -1, 1")
        if not isinstance(self.headline, (bool, str)):
            raise ValueError(f"{where}: headline = {self.headline!r}: true, false or the label "
                             "of the row to show")
        if not isinstance(self.could_fail, bool):
            raise ValueError(f"{where}: could_fail = {self.could_fail!r}: true or false")
        if not self.tolerance.strip():
            raise ValueError(f"{where}: a tolerance needs its source (field 'tolerance')")


def load_register(path=REGISTER):
    """The claims of the register at ``path``, in its order (validated; ids unique)."""
    with open(path, "rb") as handle:
        raw = tomllib.load(handle)
    claims = []
    for entry in raw.get("claim", []):
        entry = dict(entry)
        entry["needs"] = tuple(entry.get("needs", ()))
        try:
            claims.append(Claim(**entry))
        except TypeError as err:
            raise ValueError(f"{path}: claim {entry.get('id')!r}: {err}") from None
    ids = [c.id for c in claims]
    duplicates = sorted({i for i in ids if ids.count(i) > 1})
    if duplicates:
        raise ValueError(f"{path}: claim ids used twice: {duplicates}")
    return claims
