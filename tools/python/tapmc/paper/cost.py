# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The cost rule: the CPU time of a tapping run before it runs, from the front's measurements.

A tap costs the redeposition's trial moves plus a part that grows with N alone (dilation,
stereology, neighbour upkeep, the deposition spread over the run):

    CPU s per tap = N (overhead + trial S(N, eps, setting)),

``trial`` (seconds per trial move) and ``overhead`` (seconds per sphere and tap) fitted to the
CPU times of every run of the front (doc/validation/front, one core, summarised in
``front_summary.csv``), and S the sweeps (N trial moves each) per tap, a power law in N and eps
per setting,

    S = S0 (N / N0)^a (eps / eps0)^b,   N0 = 1024, eps0 = 0.0225,

fitted in logs to the setting's measured sweeps (4 points for the settings run at both N and
both eps of the front). A setting measured at fewer points borrows the missing exponents from
the measured settings of its stop rule, interpolated in log eta (clamped at the ends); a variant
of another knob (d_max, check) borrows them from the setting of its stop rule and eta. The
exponents are measured between N = 1024 and 4096 and eps = 0.0225 and 0.1; beyond them the rule
extrapolates, and :func:`campaign_check` measures how well it does on a campaign's runs.
"""

import json
import math
import re
from pathlib import Path

import numpy as np

from ..readers import TapmcFormatError, read_log
from . import front
from ._runs import ramp_level

#: the point the power laws are anchored at: the front's smaller N and its smaller eps
N0 = 1024
EPS0 = 0.0225
#: the purposes of the front's recommended settings (doc/front.rst), most accurate first, and
#: the short names the command line also takes
TIERS = tuple(p for p, _, _ in front.PURPOSES)
TIER_ALIASES = {"smoke": "smoke test"}
#: a run's CPU seconds come from the loops its logs report (an attempt killed before its end
#: reports none); below this share of the run's taps the sample is a short stretch of one
#: level, run beside whatever else the machine did then, not the run's cost
MIN_CPU_COVERAGE = 0.25


class CostError(ValueError):
    """A setting, size or tap strength the rule cannot price, or a summary it cannot read."""


def setting_name(eta, stop="change"):
    """The front's name of a plain threshold setting (``stop`` rule and ``eta``), e.g. 'change
    1e-7 (default)'; a name the front does not list is returned all the same (the rule then
    borrows its exponents, see the module text)."""
    if stop not in ("change", "drift"):
        raise CostError(f"stop = {stop!r}: allowed values are change, drift")
    return front.setting_named(eta, stop) or f"{stop} {_eta_text(eta)}"


def _eta_text(eta):
    """eta as the front writes it: 1e-7, 4e-7, 0.001."""
    return re.sub(r"e([+-])0*(\d)", r"e\1\2", f"{float(eta):g}").replace("e+", "e")


def _stop_and_eta(name):
    """(stop rule, eta, plain) of a setting name of the front or of :func:`setting_name`."""
    spec = front.SETTINGS.get(name)
    if spec is not None:
        keys = spec["keys"]
        return keys.get("stop", "change"), float(spec["eta"]), set(keys) <= {"stop"}
    m = re.fullmatch(r"(change|drift) ([0-9.eE+-]+)", name)
    if not m:
        raise CostError(f"setting = {name!r}: allowed values are the purposes "
                        f"({', '.join(TIERS)}, or smoke), the front's settings ({', '.join(front.SETTINGS)}) "
                        "and 'change ETA' / 'drift ETA'")
    return m.group(1), float(m.group(2)), True


class CostRule:
    """The rule fitted to the rows of a front summary (dicts with N, eps, setting,
    sweeps_per_tap, cpu_per_tap). ``trial`` and ``overhead`` in seconds; ``laws`` maps each
    measured setting to (S0, a, b, measured points); :meth:`seconds_per_tap`,
    :meth:`cpu_hours`, :meth:`sweeps_per_tap`."""

    def __init__(self, rows, source="front summary"):
        self.source = source
        rows = [dict(r) for r in rows]
        if not rows:
            raise CostError(f"{source}: no rows")
        try:
            for r in rows:
                r["N"], r["eps"] = int(r["N"]), float(r["eps"])
                r["sweeps_per_tap"], r["cpu_per_tap"] = float(r["sweeps_per_tap"]), float(r["cpu_per_tap"])
        except (KeyError, ValueError) as err:
            raise CostError(f"{source}: a row lacks N, eps, sweeps_per_tap or cpu_per_tap ({err})") from None
        self.rows = rows
        self.summary_rows = [{k: _number(v) for k, v in r.items()} for r in rows]
        self.trial, self.overhead = self._fit_times(rows)
        self.laws = self._fit_sweeps(rows)

    @classmethod
    def from_summary(cls, path=None):
        path = Path(path or front.SUMMARY)
        if not path.is_file():
            raise CostError(f"{path}: no such file")
        try:  # the summary's schema belongs to tapmc.paper.front.summary
            rows = front.read_summary(path)
        except (OSError, UnicodeDecodeError) as err:
            raise CostError(f"{path}: {err}") from None
        return cls(rows, source=str(path))

    @staticmethod
    def _fit_times(rows):
        """(seconds per trial, seconds per sphere and tap): least squares in relative error."""
        cpu = np.array([r["cpu_per_tap"] for r in rows])
        design = np.array([[r["N"] * r["sweeps_per_tap"], r["N"]] for r in rows]) / cpu[:, None]
        (trial, overhead), *_ = np.linalg.lstsq(design, np.ones(len(rows)), rcond=None)
        if not trial > 0:
            raise CostError("the front's CPU times give no positive cost per trial move")
        return float(trial), max(float(overhead), 0.0)

    @staticmethod
    def _fit_sweeps(rows):
        laws = {}
        for name in sorted({r["setting"] for r in rows}):
            mine = [r for r in rows if r["setting"] == name]
            x_n = np.array([math.log(r["N"] / N0) for r in mine])
            x_e = np.array([math.log(r["eps"] / EPS0) for r in mine])
            y = np.array([math.log(r["sweeps_per_tap"]) for r in mine])
            columns = [np.ones_like(y)]
            has_n, has_e = np.ptp(x_n) > 0, np.ptp(x_e) > 0
            columns += [x_n] if has_n else []
            columns += [x_e] if has_e else []
            coef, *_ = np.linalg.lstsq(np.column_stack(columns), y, rcond=None)
            coef = list(coef)
            a = coef.pop(1) if has_n else None
            b = coef.pop(1) if has_e else None
            # without a spread in N (eps), the anchor is the mean at the rows' own N (eps)
            laws[name] = {"lnS0": coef[0], "a": a, "b": b, "points": len(mine),
                          "N": sorted({r["N"] for r in mine}), "eps": sorted({r["eps"] for r in mine}),
                          "x_n": float(np.mean(x_n)), "x_e": float(np.mean(x_e))}
        return laws

    def _borrowed(self, name, key):
        """Exponent ``key`` ('a' or 'b') of setting ``name``: its own, else borrowed."""
        own = self.laws.get(name)
        if own is not None and own[key] is not None:
            return own[key], None
        stop, eta, plain = _stop_and_eta(name)
        if not plain:  # a d_max or check variant: the plain setting of its rule and eta
            return self._borrowed(setting_name(eta, stop), key)
        donors = sorted((_stop_and_eta(n)[1], n) for n, law in self.laws.items()
                        if law[key] is not None and _stop_and_eta(n)[0] == stop and _stop_and_eta(n)[2])
        if not donors:
            raise CostError(f"setting = {name!r}: no measured {stop} setting gives its "
                            f"{'N' if key == 'a' else 'eps'} dependence")
        x = math.log10(eta)
        xs = [math.log10(e) for e, _ in donors]
        values = [self.laws[n][key] for _, n in donors]
        order = np.argsort(xs)
        value = float(np.interp(x, np.array(xs)[order], np.array(values)[order]))
        return value, "+".join(n for _, n in donors)

    def _anchor(self, setting):
        """ln S at (N0, EPS0) of ``setting``: its own fit, or for a plain threshold setting the
        front does not list, interpolated in log eta between the measured ones of its rule."""
        law = self.laws.get(setting)
        if law is not None:  # a borrowed exponent moves the anchor from the rows' mean N, eps
            shift_n = law["x_n"] * self._borrowed(setting, "a")[0] if law["a"] is None else 0.0
            shift_e = law["x_e"] * self._borrowed(setting, "b")[0] if law["b"] is None else 0.0
            return law["lnS0"] - shift_n - shift_e
        stop, eta, plain = _stop_and_eta(setting)
        donors = sorted((_stop_and_eta(n)[1], law["lnS0"]) for n, law in self.laws.items()
                        if _stop_and_eta(n)[0] == stop and _stop_and_eta(n)[2])
        lo, hi = (donors[0][0], donors[-1][0]) if donors else (math.nan, math.nan)
        if not plain or not lo <= eta <= hi:
            measured = ", ".join(sorted(self.laws))
            raise CostError(f"setting = {setting!r}: not measured by the front, and not a {stop} "
                            f"threshold between its measured ones ({_eta_text(lo)} .. "
                            f"{_eta_text(hi)}); measured: {measured}")
        return float(np.interp(math.log10(eta), [math.log10(e) for e, _ in donors],
                               [v for _, v in donors]))

    def sweeps_per_tap(self, N, eps, setting):
        """Predicted sweeps per tap of ``setting`` at N spheres and tap strength eps."""
        N, eps = _check_size(N, eps)
        ln_s0 = self._anchor(setting)
        a, _ = self._borrowed(setting, "a")
        b, _ = self._borrowed(setting, "b")
        return math.exp(ln_s0 + a * math.log(N / N0) + b * math.log(eps / EPS0))

    def seconds_per_tap(self, N, eps, setting):
        return N * (self.overhead + self.trial * self.sweeps_per_tap(N, eps, setting))

    def cpu_hours(self, N, taps, eps, setting):
        """CPU hours of ``taps`` taps at tap strength ``eps``."""
        if int(taps) < 0:
            raise CostError(f"taps = {taps}: must be >= 0")
        return int(taps) * self.seconds_per_tap(N, eps, setting) / 3600.0

    def exponents(self, setting):
        """(a, b, where they come from): the N and eps exponents of ``setting``'s sweeps."""
        a, a_from = self._borrowed(setting, "a")
        b, b_from = self._borrowed(setting, "b")
        return a, b, {"a": a_from, "b": b_from}

    def describe(self):
        return (f"{self.trial * 1e9:.1f} ns per trial move and {self.overhead * 1e6:.2f} us per "
                f"sphere and tap, fitted to the {len(self.rows)} rows of {Path(self.source).name}")


def wall_hours(run_hours, jobs):
    """Hours of wall time for independent runs of ``run_hours`` (CPU hours each, one core
    each) on ``jobs`` cores, longest first to the least loaded core: never less than the
    longest run, which no number of cores shortens (total / jobs alone priced one 2.9 h run
    at 0.4 h on 8 cores)."""
    loads = [0.0] * max(1, int(jobs))
    for hours in sorted((float(h) for h in run_hours), reverse=True):
        loads[loads.index(min(loads))] += hours
    return max(loads)


def _number(value):
    """A summary cell as front.recommend reads it: a float where it is one."""
    if isinstance(value, str):
        try:
            return float(value)
        except ValueError:
            return value
    return value


def _check_size(N, eps):
    try:
        N, eps = int(N), float(eps)
    except (TypeError, ValueError):
        raise CostError(f"N = {N!r}, eps = {eps!r}: numbers expected") from None
    if N < 1:
        raise CostError(f"N = {N}: must be >= 1")
    if not 0 < eps <= 1:
        raise CostError(f"eps = {eps}: must be in (0, 1]")
    return N, eps


# ---- the runs of a campaign ----------------------------------------------------------------

def run_eps(variables, taps):
    """The eps of every tap of a run of the paper's inputs (constant eps, ageing, pore dumps:
    ``eps`` or ``sqrteps``; the ramp: its levels, ``P`` taps each), as an array."""
    if "nlev" in variables:
        nlev, P = int(variables["nlev"]), int(variables["P"])
        levels = [ramp_level(k, nlev, variables["sqrt0"], variables["dsqrt"])[1]
                  for k in range(3 * nlev - 2)]
        return np.repeat(np.square(levels), P)[:int(taps)]
    sqrteps = float(variables.get("sqrteps", 0) or 0)
    eps = sqrteps ** 2 if sqrteps > 0 else float(variables["eps"])
    return np.full(int(taps), eps)


def run_setting(variables):
    """The front's setting of a run: its eta and stop rule (``settle_keys``)."""
    keys = str(variables.get("settle_keys", ""))
    stop = "drift" if re.search(r"\bstop\s+drift\b", keys) else "change"
    return setting_name(variables.get("eta", 1e-7), stop)


def tap_seconds(spec, rule):
    """CPU seconds of each tap of one RunSpec by the rule (N, the eps of the tap, the run's
    setting), as an array: a ramp's strong levels cost more per tap than its weak ones."""
    v = spec.variables
    eps = run_eps(v, int(spec.taps))
    setting = run_setting(v)
    values, inverse = np.unique(eps, return_inverse=True)
    per_eps = np.array([rule.seconds_per_tap(int(v["N"]), float(e), setting) for e in values])
    return per_eps[inverse]


def run_cost(spec, rule):
    """CPU hours of one RunSpec (N, its taps, the eps of each tap, its setting)."""
    return float(tap_seconds(spec, rule).sum()) / 3600.0


def _thermo_sweeps(run_dir):
    """(steps, sweeps) of the thermo rows (step >= 1) of every log of a run folder: the sweeps
    of the tap printed (fix mc/settle's f_settle[1]), one row every thermo interval."""
    steps, sweeps = [], []
    for log in sorted(Path(run_dir).glob("log*.lammps")):
        try:
            thermo = read_log(log, strict=False).thermo
        except TapmcFormatError:  # an attempt killed before its first thermo row
            continue
        if "Step" in thermo and "f_settle[1]" in thermo:
            keep = thermo["Step"] >= 1
            steps += list(thermo["Step"][keep])
            sweeps += list(thermo["f_settle[1]"][keep])
    unique = dict(zip(steps, sweeps))
    return np.array(sorted(unique)), np.array([unique[k] for k in sorted(unique)])


def log_cpu_seconds(run_dir):
    """(CPU seconds, taps) of a run folder's logs (log*.lammps, every attempt's): each run
    command's loop time times its CPU use, over the taps those commands ran (one rank;
    taps a resumed attempt ran again count again: they were paid twice)."""
    cpu, taps = 0.0, 0
    for log in Path(run_dir).glob("log*.lammps"):
        text = log.read_text(errors="replace")
        for loop, n, use in re.findall(r"Loop time of ([0-9.eE+-]+) on 1 procs for (\d+) steps"
                                       r"[^\n]*\n(?:[^\n]*\n){0,3}?\s*([0-9.]+)% CPU use", text):
            cpu += float(loop) * float(use) / 100.0
            taps += int(n)
    return cpu, taps


def campaign_check(directory, rule):
    """The rule against a campaign's finished runs (folders with DONE.json): one dict per run
    with its N, setting, mean eps, the sweeps per tap its thermo rows show and the rule's
    prediction at the same taps, and the CPU seconds per tap (each log's loop time times its
    CPU use; NaN when the logs cover less than :data:`MIN_CPU_COVERAGE` of its taps) with the
    rule's prediction."""
    out = []
    for done in sorted(Path(directory, "runs").glob("*/DONE.json")):
        run = json.loads(done.read_text())["run"]
        v, taps = run["variables"], int(run["taps"])
        N, setting, eps = int(v["N"]), run_setting(v), run_eps(v, taps)
        steps, sweeps = _thermo_sweeps(done.parent)
        if not len(steps):
            continue
        at = eps[np.clip(steps.astype(int) - 1, 0, taps - 1)]
        cpu, cpu_taps = log_cpu_seconds(done.parent)
        out.append({"run": run["name"], "N": N, "setting": setting, "eps": float(np.mean(eps)),
                    "sweeps": float(np.mean(sweeps)), "samples": int(len(sweeps)),
                    "sweeps_predicted": float(np.mean([rule.sweeps_per_tap(N, e, setting) for e in at])),
                    "cpu_taps": cpu_taps,
                    "cpu_per_tap": (cpu / cpu_taps if cpu_taps >= MIN_CPU_COVERAGE * taps
                                    else math.nan),
                    "cpu_per_tap_predicted": run_cost(run_spec_like(run), rule) * 3600.0 / taps})
    return out


class _SpecView:
    """The fields of a RunSpec that :func:`run_cost` reads, from a DONE.json record."""

    def __init__(self, run):
        self.variables, self.taps = run["variables"], int(run["taps"])


def run_spec_like(run):
    return _SpecView(run)


def lammps_line(setting, N=4096):
    """The fix mc/settle command of ``setting`` (spheres of radius 0.5, a floor at z = 0)."""
    if setting in front.SETTINGS:
        return front.lammps_line(setting, N)
    stop, eta, _ = _stop_and_eta(setting)
    words = ["fix", "settle", "all", "mc/settle", "SEED", "floor", "0.0"]
    words += ["stop", "drift"] if stop == "drift" else []
    return " ".join(words + ([] if eta == 1e-7 else ["eta", _eta_text(eta)]))


def tier_setting(name, rule, N):
    """The setting of a purpose (publication, exploration, smoke test) as the front recommends
    it at the measured N nearest to N (in log N), or the setting ``name`` itself."""
    purpose = TIER_ALIASES.get(name, name)
    if purpose not in TIERS:
        _stop_and_eta(name)  # raises CostError naming the allowed values
        return name
    sizes = sorted({int(r["N"]) for r in rule.rows if r["setting"] == front.REFERENCE})
    if not sizes:
        raise CostError(f"{rule.source}: the reference {front.REFERENCE!r} has no row: no "
                        "recommended settings")
    nearest = min(sizes, key=lambda n: abs(math.log(n / N)))
    recommended = front.recommend(rule.summary_rows, nearest).get(purpose)
    if recommended is None:
        raise CostError(f"{rule.source}: no setting meets the {purpose} tolerance at N = {nearest}")
    return recommended.setting
