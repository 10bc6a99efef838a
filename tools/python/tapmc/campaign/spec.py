# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""RunSpec: one LAMMPS run of a campaign, its parameters checked when it is made."""

import re
from pathlib import Path

__all__ = ["RunSpec", "Words", "RESERVED_VARIABLES"]

_NAME_RE = re.compile(r"^[A-Za-z0-9_.+-]+$")
_VAR_RE = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
#: variables the campaign sets itself (seed from RunSpec.seed, resume from the restart files)
RESERVED_VARIABLES = ("seed", "resume", "resume_file")


class Words(str):
    """A variable value of several words given to LAMMPS as one ``-var`` value (e.g. the
    fix mc/settle keywords ``"dmax 0.05 stop drift"`` of in.constant_eps's ``settle_keys``);
    a plain string may not hold spaces, so that a value split by mistake is caught. No quote
    and no line break: the partition driver quotes it."""

    def __new__(cls, text):
        text = str(text)
        if not text.strip() or any(c in text for c in "\"'\n\r") or text != text.strip():
            raise ValueError(f"Words({text!r}): words separated by spaces, without quotes, "
                             "line breaks or surrounding spaces")
        return super().__new__(cls, text)


class RunSpec:
    """One LAMMPS run of a campaign.

    Parameters
    ----------
    name : str
        unique in the campaign, letters, digits and ``_.+-`` (it names the run folder),
        e.g. ``"pbc_eps0.005_s3"``.
    input : path
        the LAMMPS input (e.g. ``examples/paper/in.constant_eps``).
    variables : dict
        ``-var`` values (numbers or strings without spaces; :class:`Words` for one value of
        several words, e.g. ``settle_keys``; a list or tuple gives a multi-valued index
        variable, e.g. ``dump_times``). ``seed``, ``resume`` and ``resume_file`` are set by
        the campaign.
    seed : int
        the Monte Carlo seed (``-var seed``), positive.
    nprocs : int
        MPI ranks of this run (default 1).
    taps : int or None
        total taps of the run (its last step), for the progress report and the completion
        check; default ``variables['taps']``, or P (3 nlev - 2) for the ramp protocol
        (variables ``P`` and ``nlev`` of ``examples/paper/in.ramp``).
    """

    def __init__(self, name, input, variables=None, seed=1, nprocs=1, taps=None):
        if not isinstance(name, str) or not _NAME_RE.match(name):
            raise ValueError(f"name = {name!r}: must be a non-empty string of letters, digits "
                             "and _.+-")
        path = Path(input)
        if not path.is_file():
            raise ValueError(f"input = {str(input)!r}: no such file")
        variables = dict(variables or {})
        for key, value in variables.items():
            if not isinstance(key, str) or not _VAR_RE.match(key):
                raise ValueError(f"variables: name {key!r} is not a LAMMPS variable name")
            if key in RESERVED_VARIABLES:
                raise ValueError(f"variables[{key!r}]: set by the campaign (use RunSpec.seed "
                                 "for the seed)")
            values = value if isinstance(value, (list, tuple)) else [value]
            if not values:
                raise ValueError(f"variables[{key!r}] = {value!r}: empty list")
            for v in values:
                if not isinstance(v, (int, float, str)) or isinstance(v, bool) or \
                        (isinstance(v, str) and not isinstance(v, Words)
                         and (not v or any(c.isspace() for c in v))):
                    raise ValueError(f"variables[{key!r}] = {value!r}: allowed values are "
                                     "numbers and strings without spaces, Words (or a list of "
                                     "them)")
        if isinstance(seed, bool) or not isinstance(seed, int) or seed < 1:
            raise ValueError(f"seed = {seed!r}: must be an integer >= 1")
        if isinstance(nprocs, bool) or not isinstance(nprocs, int) or nprocs < 1:
            raise ValueError(f"nprocs = {nprocs!r}: must be an integer >= 1")
        if taps is None and "taps" in variables:
            taps = variables["taps"]
        if taps is None and "P" in variables and "nlev" in variables:  # examples/paper/in.ramp
            taps = int(variables["P"]) * (3 * int(variables["nlev"]) - 2)
        if taps is not None:
            try:
                taps = int(taps)
            except (TypeError, ValueError):
                raise ValueError(f"taps = {taps!r}: must be an integer >= 0") from None
            if taps < 0:
                raise ValueError(f"taps = {taps!r}: must be an integer >= 0")
        self.name = name
        self.input = path.resolve()
        self.variables = variables
        self.seed = seed
        self.nprocs = nprocs
        self.taps = taps

    @property
    def level_taps(self):
        """Taps per level of a ramp run (variable ``P`` of ``examples/paper/in.ramp``), None
        for the other protocols: a finished ramp keeps its restart files at the level ends,
        from which a level can be continued to measure the effect of the taps per level."""
        if "P" in self.variables and "nlev" in self.variables:
            return int(self.variables["P"])
        return None

    @property
    def taps_file(self):
        """Name of the per-tap file (first column: the step) in the run folder."""
        return str(self.variables.get("taps_file", "taps.dat"))

    def var_args(self):
        """The ``-var`` arguments of this run (without resume)."""
        args = []
        for key, value in list(self.variables.items()) + [("seed", self.seed)]:
            values = value if isinstance(value, (list, tuple)) else [value]
            args += ["-var", key] + [str(v) for v in values]
        return args

    def describe(self):
        """A JSON-able description (what the manifest and DONE.json record)."""
        return {"name": self.name, "input": self.input.name, "variables": self.variables,
                "seed": self.seed, "nprocs": self.nprocs, "taps": self.taps}

    def __repr__(self):
        return (f"RunSpec(name={self.name!r}, input={str(self.input)!r}, "
                f"variables={self.variables!r}, seed={self.seed}, nprocs={self.nprocs})")
