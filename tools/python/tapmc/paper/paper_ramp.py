# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Section III.B's question at the paper's own ramp protocol: is the branch below (sqrt eps)*
irreversible (frozen)?

The campaign's ``paperramp*`` runs (tier 7 of :mod:`tapmc.paper.plan`) ramp sqrt(eps) up to a
turning level below (sqrt eps)* ~ 0.15 and back down at 4000 taps per level, at the default
redeposition threshold and at looser ones. Each run is read from its taps.dat (finished or not:
the levels done whole so far count), cut into levels by :class:`tapmc.hysteresis.Hysteresis`
(the last 1000 taps of each level) and judged by :class:`tapmc.hysteresis.RampBranches`: the branch
is *frozen* when the descending levels stay within noise of the turning level
(``down_change`` within ``Z_DECIDE`` standard errors), and *compacts* when they rise beyond it.
Once the ramp goes up again, :meth:`PaperRampRun.retrace` applies the paper's own test of its
reversible branch ("if we compute another increase process, we approximately come across the
same values"): the second increase against the descent at the sqrt(eps) both visited. Back at
the turning level, :meth:`PaperRampRun.return_to_top` tells what the packing gives back of the
descent's compaction (a frozen branch gives back nothing) from what the loop keeps over its
first visit (the first increase, which a reversible branch need not come back to).
The per-run table is written to ``paper_ramp.csv`` of the report's questions folder, its levels
drawn in ``paper_ramp.png`` beside it (:func:`plot`, one panel per eta), and the report's
first screen states the finding from it (:func:`finding_text`) with that figure.

  /usr/bin/python3 -m tapmc.paper paper-ramp --campaign DIR --out doc/paper_scale
"""

from __future__ import annotations

import csv
import re
from dataclasses import asdict, dataclass, fields, replace
from pathlib import Path

import numpy as np
from scipy.stats import chi2

from ..hysteresis import (CRITICAL_SQRT_EPS, LEVEL_TOLERANCE, BranchData, BranchStatistic,
                          Hysteresis, RampBranches, branch_difference, common_levels,
                          seeds_together)
from ..stats import CALIBRATION_ALPHA, realization_factor
from . import _runs
from .scales import FULL

#: Taps per level of the paper's protocol, and the taps averaged at the end of each level.
TAPS_PER_LEVEL = 4000
LAST_TAPS = 1000
#: Levels of the ramps' loops (descending and second increase) that calibrate the error of a
#: level's mean from the ramps themselves (:func:`window_factor`): an rms of fewer would be
#: a noisy factor of its own.
MIN_WINDOW_LEVELS = 8
#: Descending levels a ramp needs before its branch is judged: a change needs two levels.
MIN_DOWN_LEVELS = 2
#: Why a ramp with fewer descending levels decides nothing (page, claims and progress text).
NOT_DOWN_YET = "the ramp has not come down two levels yet"
CSV_NAME = "paper_ramp.csv"
PNG_NAME = "paper_ramp.png"
#: A branch's marker and legend words in :func:`plot` (the open symbols of the paper's Fig. 4).
BRANCH_STYLE = {"up1": ("o", "increase"), "down": ("v", "decrease"),
                "up2": ("^", "increase again")}
#: What the command reads, for its message when a campaign has none of it.
RUNS_READ = "runs/paperramp* with a taps.dat"
#: The name of a run: paperramp<top>_<bc>[_eta<eta>]_s<seed> (tapmc.paper._runs).
NAME = re.compile(rf"^{_runs.PAPER_RAMP_PREFIX}(?P<top>[0-9.]+)_(?P<bc>pbc|fbc)"
                  r"(?:_eta(?P<eta>[0-9.e+-]+))?_s(?P<seed>\d+)$")


@dataclass(frozen=True)
class PaperRampRun:
    """One ramp run: its settings, how far it got, and (once its descending branch has two
    levels) the change of that branch from the turning level with its standard error, the rise
    along it (last level minus first) and the verdict (frozen, compacts, loosens); and its
    levels done whole (all their taps: branch, sqrt(eps), <Phi^c> and its batch-means error),
    from which the claims of Fig. 4 read the branches (:meth:`branch`)."""

    run: str
    top: float
    eta: float
    seed: int
    taps_done: int
    finished: bool
    down_levels: int
    down_first: float   # sqrt(eps) of the first and last descending levels
    down_last: float
    down_change: float  # mean of the descending levels minus the turning level
    down_change_sem: float
    down_rise: float    # last descending level minus the first
    down_rise_sem: float
    verdict: str        # "frozen", "compacts", "loosens" or "running" (fewer than 2 levels down)
    level_branches: str = ""  # the whole levels' branches (up1, down, up2), space-separated
    level_sqrt_eps: tuple = ()
    level_mean: tuple = ()
    level_sem: tuple = ()
    #: per whole level, the mean of the LAST_TAPS taps before its last LAST_TAPS: how far a
    #: level's mean moves from one window to the next (:func:`window_factor`)
    level_previous: tuple = ()

    def branch(self, name):
        """(sqrt_eps, mean, sem) arrays of the whole levels of branch ``name`` (up1, down,
        up2), in the ramp's order."""
        at = np.array(self.level_branches.split(), dtype=str) == name  # empty: no level yet
        return tuple(np.asarray(v, dtype=float)[at] for v in (self.level_sqrt_eps,
                                                              self.level_mean, self.level_sem))

    def return_to_top(self):
        """The :class:`ReturnToTop` of a ramp whose second increase has a whole level back at
        the turning level, else None."""
        up1, down, up2 = (self.branch(name) for name in ("up1", "down", "up2"))
        if not (len(up1[0]) and len(down[0]) and len(up2[0])) or \
                abs(up2[0][-1] - self.top) > LEVEL_TOLERANCE or \
                abs(up1[0][-1] - self.top) > LEVEL_TOLERANCE:
            return None
        return ReturnToTop(self.top, _level_difference(up2, down), _level_difference(up2, up1))

    def retrace(self):
        """The :class:`Retrace` of the second increase against the descent at the sqrt(eps)
        both have whole levels at, or None before the second increase reaches one of them."""
        down, up2 = self.branch("down"), self.branch("up2")
        if not (len(down[0]) and len(up2[0])):
            return None
        down, up2 = BranchData(*down), BranchData(*up2)
        pairs = common_levels(up2, down)
        if not pairs:
            return None
        i, j = map(list, zip(*pairs))
        return Retrace(tuple(float(x) for x in up2.sqrt_eps[i]),
                       tuple(float(d) for d in up2.mean[i] - down.mean[j]),
                       tuple(float(s) for s in np.hypot(up2.sem[i], down.sem[j])),
                       branch_difference(up2, down))


def _level_difference(a, b):
    """The last level of branch ``a`` minus the last of ``b`` ((sqrt_eps, mean, sem) each),
    with the error of two independent level means."""
    return BranchStatistic(float(a[1][-1] - b[1][-1]), float(np.hypot(a[2][-1], b[2][-1])), 2)


def _retrace_verdict(stat):
    """A second increase minus the descent (:class:`Retrace`) in a word."""
    return "above" if stat.positive else "below" if stat.negative else "retraces"


def _return_verdict(stat):
    """What the packing gives back at the turning level (:class:`ReturnToTop`) in a word."""
    return "loosens" if stat.negative else "compacts" if stat.positive else "frozen"


@dataclass(frozen=True)
class ReturnToTop:
    """A ramp back at its turning level after the descent (the last level of its second
    increase), against the two levels that frame the loop: ``given_back`` = back at the top
    minus the bottom of the loop (the last descending level): < 0 when the packing loosens as
    the taps grow again, a reversible response (a frozen branch gives back nothing);
    ``kept`` = back at the top minus the first visit of the turning level: what the loop left,
    the compaction the way back up did not undo. :class:`tapmc.hysteresis.BranchStatistic` each."""

    sqrt_eps: float
    given_back: BranchStatistic
    kept: BranchStatistic

    @property
    def verdict(self):
        """"loosens", "frozen" (within noise) or "compacts", by ``given_back``."""
        return _return_verdict(self.given_back)


@dataclass(frozen=True)
class Retrace:
    """The second increase of a ramp against its descent, at the sqrt(eps) both visited: the
    paper's test of its reversible branch (section III.B: "if we compute another increase
    process, we approximately come across the same values"). ``levels`` those sqrt(eps) in the
    second increase's order, ``differences`` second increase minus descent at each, ``sems``
    their errors (two independent level means); ``mean`` the mean difference over the levels
    (:func:`tapmc.hysteresis.branch_difference`, as the claims judge the reversible branch)."""

    levels: tuple
    differences: tuple
    sems: tuple
    mean: BranchStatistic

    @property
    def verdict(self):
        """"retraces" (the mean within noise), "above" (the packing still compacts as the
        taps grow again) or "below" (it loosens below the descent)."""
        return _retrace_verdict(self.mean)


def read_taps(path):
    """(sqrt_eps, <Phi^c>, the last tap) of a ramp's taps.dat (columns step level branch
    sqrt_eps phi_b phi_c Z; :func:`tapmc.paper._runs.run_taps`: tap 0 left out, a tap written
    twice by a resumed run counted once with its last row, a damaged file named)."""
    step, sqrt_eps, phi_c = _runs.run_taps(path, ("step", "sqrt_eps", "phi_c"))
    return sqrt_eps, phi_c, int(step[-1]) if len(step) else 0


def _running(base, down_levels):
    """The row of a ramp that has not yet come down two levels: no answer yet."""
    nan = float("nan")
    return PaperRampRun(**base, down_levels=down_levels, down_first=nan, down_last=nan,
                        down_change=nan, down_change_sem=nan, down_rise=nan, down_rise_sem=nan,
                        verdict="running")


def _whole_levels(hysteresis):
    """The levels of a computed :class:`Hysteresis` that have all their taps: a level in
    progress is not yet a level of the paper's protocol (its last 1000 taps are not its end)."""
    levels = hysteresis.levels
    return levels[levels["last_tap"] - levels["first_tap"] + 1 == TAPS_PER_LEVEL]


def _level_fields(whole, phi_c):
    """The fields of :class:`PaperRampRun` that keep the whole levels (``phi_c``: the run's
    per-tap <Phi^c>, tap 1 first)."""
    previous = tuple(float(np.mean(phi_c[last - 2 * LAST_TAPS:last - LAST_TAPS]))
                     for last in whole["last_tap"])
    return {"level_branches": " ".join(str(b) for b in whole["branch"]),
            **{f"level_{k}": tuple(float(v) for v in whole[k]) for k in ("sqrt_eps", "mean",
                                                                          "sem")},
            "level_previous": previous}


def analyse_run(run_dir, default_eta):
    """The :class:`PaperRampRun` of one run directory (name ``paperramp...``)."""
    run_dir = Path(run_dir)
    m = NAME.match(run_dir.name)
    if not m:
        raise ValueError(f"run directory {run_dir.name!r} is not a paper ramp "
                         f"({_runs.PAPER_RAMP_PREFIX}<top>_<bc>[_eta<eta>]_s<seed>)")
    sqrt_eps, phi_c, taps_done = read_taps(run_dir / "taps.dat")
    eta = float(m.group("eta")) if m.group("eta") else float(default_eta)
    base = dict(run=run_dir.name, top=float(m.group("top")), eta=eta, seed=int(m.group("seed")),
                taps_done=taps_done, finished=(run_dir / "DONE.json").exists())
    if len(phi_c) < TAPS_PER_LEVEL:  # a run just started: not one whole level yet
        return _running(base, 0)
    whole = _whole_levels(Hysteresis(sqrt_eps, phi_c, TAPS_PER_LEVEL, LAST_TAPS).compute())
    base.update(_level_fields(whole, phi_c))
    up1, down, up2 = (whole[whole["branch"] == b] for b in ("up1", "down", "up2"))
    if len(down) < MIN_DOWN_LEVELS:
        return _running(base, len(down))
    branches = RampBranches(BranchData.from_levels(up1), BranchData.from_levels(down),
                            BranchData.from_levels(up2) if len(up2) else None).compute()
    change = branches.down_change
    rise = float(down["mean"][-1] - down["mean"][0])
    rise_sem = float(np.hypot(down["sem"][-1], down["sem"][0]))
    verdict = _down_verdict(change)
    return PaperRampRun(**base, down_levels=len(down), down_first=float(down["sqrt_eps"][0]),
                        down_last=float(down["sqrt_eps"][-1]), down_change=change.value,
                        down_change_sem=change.sem, down_rise=rise, down_rise_sem=rise_sem,
                        verdict=verdict)


def _down_verdict(change):
    """"frozen" (the descent's change within noise), "compacts" or "loosens"."""
    return "frozen" if change.within_noise else "compacts" if change.positive else "loosens"


def calibrated(rows, factor):
    """The rows (:class:`PaperRampRun`) with every error times ``factor`` and the descent's
    verdict decided again. A run's batch-means errors are those of its own time averages; the
    campaign's groups of runs that differ only in their seed show that another realization
    lands about ``factor`` of them away (``ReportData.run_error('phi_c:halves')`` of
    :mod:`tapmc.paper.claims`: the factor of a difference of two parts of one run), and a
    verdict about the model needs that error. ``factor`` None (no report to take it from)
    leaves the rows as they are."""
    if factor is None:
        return list(rows)
    factor = realization_factor(factor, "error factor")
    out = []
    for r in rows:
        scaled = dict(down_change_sem=r.down_change_sem * factor,
                      down_rise_sem=r.down_rise_sem * factor,
                      level_sem=tuple(s * factor for s in r.level_sem))
        if r.verdict != "running":
            scaled["verdict"] = _down_verdict(BranchStatistic(
                r.down_change, scaled["down_change_sem"], r.down_levels))
        out.append(replace(r, **scaled))
    return out


#: The one-run error whose realizations' factor the verdicts take: a ramp's statistics are
#: differences of level means of one run.
ERROR_QUANTITY = "phi_c:halves"


@dataclass(frozen=True)
class LevelErrors:
    """The factor that turns a level's batch-means error into the error the verdicts take,
    and where it comes from: ``report`` (the campaign's realizations' factor of a difference
    of two parts of one run, :func:`errors_from_report`; None without a report) and
    ``window`` (:func:`window_factor`, over ``window_levels`` loop levels; None with fewer
    than :data:`MIN_WINDOW_LEVELS`). ``value``: the window's factor where the windows reject
    the report's (or, without one, the batch-means errors) at CALIBRATION_ALPHA, else the
    report's (at least 1): a factor measured on a few levels is itself noisy, and only a
    spread that the smaller errors cannot explain replaces them."""

    report: float = None
    window: float = None
    window_levels: int = 0

    @property
    def base(self):
        return max(1.0, self.report or 1.0)

    @property
    def window_p_value(self):
        """P(chi2 with window_levels dof >= the windows' sum of squares at ``base``), or NaN."""
        if self.window is None:
            return float("nan")
        return float(chi2.sf(self.window_levels * (self.window / self.base) ** 2,
                             self.window_levels))

    @property
    def from_window(self):
        """Whether the ramps' own windows set the factor (they spread more than the
        report's errors allow)."""
        return self.window is not None and self.window > self.base and \
            self.window_p_value < CALIBRATION_ALPHA

    @property
    def value(self):
        return self.window if self.from_window else self.base

    def text(self):
        """How the finding's errors were made (:func:`calibrated`)."""
        if self.value == 1.0:
            return "errors: the levels' batch-means errors"
        if self.from_window:
            report = (f"; the campaign's realizations give x {self.report:.1f}"
                      if self.report not in (None, 1.0) else "")
            return (f"errors: the levels' batch-means errors x {self.value:.1f}, the spread "
                    f"of one {LAST_TAPS}-tap mean to the next within a level over the ramps' "
                    f"{self.window_levels} levels after their turn{report}")
        return (f"errors: the levels' batch-means errors x {self.value:.1f}, the spread of the "
                "campaign's realizations for a difference of two parts of one run")


def window_factor(rows):
    """(factor, levels): how far a level's mean of the last LAST_TAPS taps moves from the
    mean of the LAST_TAPS before it, in units of its batch-means error, over the levels after
    the ramps' turn (descending and second increase; the first increase still compacts):
    the rms of (mean - previous) / (sqrt(2) sem), the factor a steady level's batch-means
    error falls short by for 1000-tap means (the slow fluctuations of <Phi^c> outlast the
    batches). A level's residual drift adds to it, and two neighbouring windows share part of
    their fluctuations, which takes from it. (None, n) with fewer than MIN_WINDOW_LEVELS
    levels."""
    z = []
    for r in rows:
        if len(r.level_previous) != len(r.level_mean):
            continue   # a row written before level_previous was kept
        for branch, mean, sem, prev in zip(r.level_branches.split(), r.level_mean,
                                           r.level_sem, r.level_previous):
            if branch in ("down", "up2") and sem > 0:
                z.append((mean - prev) / (np.sqrt(2.0) * sem))
    if len(z) < MIN_WINDOW_LEVELS:
        return None, len(z)
    return float(np.sqrt(np.mean(np.square(z)))), len(z)


def level_errors(rows, report_factor=None):
    """The :class:`LevelErrors` of ``rows`` (every paper ramp of the campaign: their loops
    calibrate the windows) with the report's factor ``report_factor``."""
    window, levels = window_factor(rows)
    return LevelErrors(report_factor, window, levels)


def errors_from_report(data):
    """The ``error_factor`` of :func:`headline_text` and :func:`finding_text` from a report's
    :class:`~tapmc.paper.claims.ReportData` (its ``run_error`` of :data:`ERROR_QUANTITY`; 1
    when the campaign's seeds do not reject the runs' own errors)."""
    return data.run_error(ERROR_QUANTITY)[0]


def analyse(campaign, default_eta):
    """Every ``paperramp*`` run of the campaign directory (its ``runs/`` folder) that has a
    taps.dat, sorted by eta, top and seed."""
    runs_dir = Path(campaign) / "runs"
    found = [analyse_run(d, default_eta) for d in sorted(runs_dir.glob(
        f"{_runs.PAPER_RAMP_PREFIX}*")) if (d / "taps.dat").exists()]
    return sorted(found, key=lambda r: (-r.eta, r.top, r.seed))


def write_csv(rows, path):
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=[fl.name for fl in fields(PaperRampRun)])
        w.writeheader()
        for r in rows:
            w.writerow({k: " ".join(repr(x) for x in v) if isinstance(v, tuple) else v
                        for k, v in asdict(r).items()})
    return path


def read_csv(path):
    """The rows of :func:`write_csv` as :class:`PaperRampRun` (types restored)."""
    with open(path) as f:
        return runs_from_rows(csv.DictReader(f))


def runs_from_rows(rows):
    """CSV rows of :func:`write_csv` (dicts of text) as :class:`PaperRampRun`."""
    kinds = {fl.name: fl.type for fl in fields(PaperRampRun)}
    convert = {"str": str, "float": float, "int": int, "bool": lambda v: v == "True",
               "tuple": lambda v: tuple(float(x) for x in v.split())}
    return [PaperRampRun(**{k: convert[kinds[k]](v) for k, v in row.items()}) for row in rows]


def eta_text(eta):
    """A threshold as the report writes it (1e-5, not 1e-05)."""
    return f"{eta:.0e}".replace("e-0", "e-")


def progress_text(seed, taps_done, down_levels, turned=False):
    """How far a ramp that has not come down two levels got: "seed 1 at tap 23737, 1
    descending level of the 2 needed" (or "..., on its first descending level" once it
    ``turned``, or "..., still going up")."""
    down = int(down_levels)
    where = (f"{down} descending level{'s' if down > 1 else ''} of the {MIN_DOWN_LEVELS} "
             "needed" if down else "on its first descending level" if turned
             else "still going up")
    return f"seed {seed} at tap {taps_done}, {where}"


def turned(run):
    """Whether a ramp (:class:`PaperRampRun`) is past its first increase: the paper's protocol
    goes up from sqrt(eps) = 0.025 by 0.025 per level of 4000 taps to its turning level."""
    levels_up = round((run.top - FULL.ramp_sqrt0) / FULL.ramp_dsqrt) + 1
    return run.taps_done > levels_up * TAPS_PER_LEVEL


def below_critical(rows):
    """The runs that turn below (sqrt eps)* ~ 0.15: the ramps the central question is about
    (a ramp beyond it comes down the reversible branch, whatever the answer)."""
    return [r for r in rows if r.top < CRITICAL_SQRT_EPS]


def beyond_critical(rows):
    """The runs that turn beyond (sqrt eps)*: the ramps of the reversible branch."""
    return [r for r in rows if r.top > CRITICAL_SQRT_EPS]


def by_eta(rows, first=None):
    """(eta, decided, running) per eta of the rows (:class:`PaperRampRun`): ``first`` (the
    default eta) first, then the loosest first; ``decided`` are the seeds whose ramp came down
    two levels, ``running`` says how far the others got (:func:`progress_text`; "" when none
    is running)."""
    for eta, group in groups_by_eta(rows, first):
        decided = [r for r in group if r.verdict != "running"]
        running = "; ".join(progress_text(r.seed, r.taps_done, r.down_levels, turned(r))
                            for r in group
                            if r.verdict == "running")
        yield eta, decided, running


def groups_by_eta(rows, first=None):
    """(eta, its rows) per eta of ``rows``: ``first`` (the default eta) first, then the
    loosest."""
    etas = sorted({r.eta for r in rows}, key=lambda e: (e != first, -e))
    return [(eta, [r for r in rows if r.eta == eta]) for eta in etas]


def eta_label(eta, default_eta):
    """'eta = 1e-7 (the default)', or without the parenthesis for another eta."""
    return f"eta = {eta_text(eta)}" + (" (the default)" if eta == default_eta else "")


#: The headline's answer for one eta, by the verdicts of its decided seeds.
NO_BRANCH = "no irreversible branch"
FROZEN_BRANCH = "an irreversible (frozen) branch"
SEEDS_DISAGREE = "the seeds disagree"


def _eta_answer(decided):
    verdicts = {r.verdict for r in decided}
    return (FROZEN_BRANCH if verdicts == {"frozen"} else SEEDS_DISAGREE if "frozen" in verdicts
            else NO_BRANCH)


def headline_text(rows, default_eta, error_factor=None):
    """The answer for the report's first screen and README.md: a sentence that gives the
    answer when every eta gives the same one, then a bullet per eta ("- ..." lines, rst and
    Markdown alike, after a blank line): the answer (no irreversible branch, a frozen branch,
    the seeds disagree) with the seeds' changes of the descending branch and the second
    increase against it, or undecided with how far the running seeds got; the numbers with
    their errors are in :func:`finding_text`. Only the ramps that turn below (sqrt eps)* count
    (:func:`below_critical`). ``error_factor``: the errors' factor of :func:`calibrated`, with
    which the verdicts are decided, or the ramps' own windows' when larger
    (:func:`level_errors`). The ramps that turn beyond it, down the paper's reversible branch,
    follow in a last bullet of their own, for comparison (:func:`_beyond_headline`)."""
    every = calibrated(rows, level_errors(rows, error_factor).value)
    rows = below_critical(every)
    if not rows:
        return ""
    bullets, answers = [], set()
    for eta, decided, running in by_eta(rows, default_eta):
        label = eta_label(eta, default_eta)
        if not decided:
            bullets.append(f"- {label}: undecided, {NOT_DOWN_YET} ({running}).")
            answers.add(None)
            continue
        answer = _eta_answer(decided)
        answers.add(answer)
        changes = " and ".join(f"{r.down_change:+.4f}" for r in decided)
        seeds = f"{len(decided)} seed{'s' if len(decided) > 1 else ''}"
        bullets.append(f"- {label}: {answer} ({seeds}; {_descent_words(changes)}"
                       f"{_retrace_headline(decided)}).")
    etas = len(bullets)
    beyond = _beyond_headline(beyond_critical(every), default_eta)
    where = (f"at any of the {etas} redeposition thresholds eta measured" if etas > 1
             else "at the redeposition threshold eta measured")
    overall = (f"{answers.pop()} {where}" if len(answers) == 1 and None not in answers
               else "per redeposition threshold eta")
    return ("The paper's central question (section III.B: is the branch below (sqrt eps)* ~ "
            f"0.15 irreversible?) at its own ramp protocol ({TAPS_PER_LEVEL} taps per level, "
            f"N = 4096, P.B.C.): {overall}.\n\n" + "\n".join(bullets + beyond))


def _descent_words(changes):
    """The descent's move (:attr:`PaperRampRun.down_change`, the mean of the descending levels
    minus the turning level), as the headline says it: the shares of the second increase
    refer to it."""
    return (f"the descending levels lie {changes} in <Phi^c> from the turning level on average "
            "(the descent's move)")


def _beyond_headline(rows, default_eta):
    """The headline's comparison: one bullet ("- ...") on the ramps that turned beyond
    (sqrt eps)*, down the branch the paper calls reversible, with their seeds' descents and
    second increases in the words of the bullets below it ([] without a ramp there that came
    down two levels)."""
    parts = []
    for eta, decided, _ in by_eta(rows, default_eta):
        if not decided:
            continue
        tops = " and ".join(f"{t:g}" for t in sorted({r.top for r in decided}))
        changes = " and ".join(f"{r.down_change:+.4f}" for r in decided)
        seeds = f"{len(decided)} seed{'s' if len(decided) > 1 else ''}"
        parts.append(f"at {eta_label(eta, default_eta)}, turning at {tops} ({seeds}): "
                     f"{_descent_words(changes)}"
                     f"{_retrace_headline(decided)}")
    if not parts:
        return []
    return ["- For comparison, beyond (sqrt eps)* (the branch the paper calls reversible): "
            + "; ".join(parts) + "."]


def finding_text(rows, default_eta, error_factor=None, source=""):
    """The finding of the report's first screen: a sentence with the protocol and how the
    errors were made (``error_factor``: as for :func:`headline_text`), closed by ``source``
    (where the numbers are, e.g. " Per run: ..."), then a list item ("  - ", an rst list nested
    in the page's item) per eta: whether the model has an irreversible branch below
    (sqrt eps)* at the paper's ramp protocol, with each seed's numbers, the runs still running
    named with how far they got; ramps that turn beyond (sqrt eps)* in an item of their own,
    after them (:func:`_beyond_text`)."""
    errors = level_errors(rows, error_factor)
    rows = calibrated(rows, errors.value)
    below = below_critical(rows)
    if not rows:
        return ""
    parts = []
    for eta, decided, running in by_eta(below, default_eta):
        label = eta_label(eta, default_eta)
        if not decided:
            parts.append(f"at {label} {NOT_DOWN_YET} ({running}): undecided.")
            continue
        verdicts = {r.verdict for r in decided}
        seeds = "; ".join(
            f"seed {r.seed}: {r.down_change:+.4f} +- {r.down_change_sem:.4f} from the turning "
            f"level at {r.top:g}, {r.down_rise:+.4f} +- {r.down_rise_sem:.4f} from "
            f"{r.down_first:g} to {r.down_last:g}" for r in decided)
        if verdicts == {"frozen"}:
            head = "the model has an irreversible (frozen) branch"
        elif "frozen" in verdicts:
            head = "the seeds disagree about a frozen branch"
        elif verdicts == {"compacts"}:
            head = "the model has no irreversible branch: the descending branch compacts"
        else:
            head = "the model has no frozen branch: the descending branch moves"
        parts.append(f"at {label}, {head} ({len(decided)} seed{'s' if len(decided) > 1 else ''};"
                     f" <Phi^c> of the descending levels, {seeds})"
                     + (f"; not counted yet: {running}" if running else "")
                     + _retrace_finding(decided) + _return_finding(decided))
    beyond = _beyond_text(beyond_critical(rows), default_eta)
    if not parts:
        return beyond + source
    items = [p[0].upper() + p[1:] + ("" if p.endswith(".") else ".") for p in parts]
    return ("Section III.B's question at the paper's own ramp protocol (N = 4096, L = 32R, "
            f"P.B.C., {TAPS_PER_LEVEL} taps per level, steps of 0.025 in sqrt(eps), turning "
            f"below (sqrt eps)* ~ 0.15; means of the last {LAST_TAPS} taps of each level; "
            f"{errors.text()}), answered per redeposition threshold eta"
            + (", then beyond (sqrt eps)*" if beyond else "") + f".{source}\n\n"
            + "\n".join(f"  - {item}" for item in items + ([beyond] if beyond else [])))


def _returns(decided):
    """(seed, ReturnToTop) of the decided runs back at their turning level."""
    return [(r.seed, back) for r in decided if (back := r.return_to_top()) is not None]


#: What the packing back at the turning level does, by the verdicts of its seeds.
RETURN_ANSWERS = {("loosens",): "it loosens as the taps grow again (a frozen branch would not)",
                  ("frozen",): "it stays where the descent left it (frozen)",
                  ("compacts",): "it compacts further"}


def _return_answer(backs):
    verdicts = tuple(sorted({b.verdict for _, b in backs}))
    if verdicts in RETURN_ANSWERS:
        return RETURN_ANSWERS[verdicts]
    return _mixed_answer([(s, b.given_back, b.verdict) for s, b in backs], _return_verdict,
                         RETURN_ANSWERS, short=False)


def _retraces(decided):
    """(run, Retrace) of the decided runs whose second increase has reached a level of the
    descent."""
    return [(r, back) for r in decided if (back := r.retrace()) is not None]


def _signed(value):
    """A difference in <Phi^c> as the report writes it: 4 decimals, signed, never -0.0000."""
    return f"{0.0 if abs(value) < 5e-5 else value:+.4f}"


#: What the second increase against the descent says, by the verdicts of its seeds: (the
#: finding's words, the headline's).
RETRACE_ANSWERS = {
    # within noise is a test against zero, not of how close: "approximately the same values"
    # within a tenth of the hysteresis gap is the register's reversible-retraced row
    ("retraces",): ("it comes across the same values within its errors (how close: the "
                    "register's reversible-retraced row)", "within its errors of the descent"),
    ("above",): ("it lies above the descent: the packing still compacts, neither frozen nor "
                 "reversible", "it lies above the descent: still compacting"),
    ("below",): ("it lies below the descent: the packing loosens as the taps grow again",
                 "it lies below the descent")}


#: A seed's verdict in words, where the seeds' verdicts differ (second increase, return to the top).
SEED_VERDICT_WORDS = {"retraces": "lies on the descent", "above": "lies above", "below": "lies below",
                      "loosens": "loosens", "frozen": "stays (frozen)", "compacts": "compacts"}


def _mixed_answer(seeded, verdict_of, answers, short):
    """The words for seeds whose verdicts differ: each seed's verdict, then the seeds
    together (:func:`seeds_together`): within their errors, the pooled mean and its verdict
    (``verdict_of(BranchStatistic)`` -> a key of ``answers``); beyond them, no answer over
    the seeds. ``seeded``: (seed, BranchStatistic, verdict) per seed."""
    each = ", ".join(f"seed {s} {SEED_VERDICT_WORDS[v]}" for s, _, v in seeded)
    together = seeds_together(stat for _, stat, _ in seeded)
    if not together.consistent:
        return (f"the seeds disagree beyond their errors ({each}; {together.scatter_text()}): "
                "one answer per seed")
    pooled = together.pooled
    words = answers[(verdict_of(pooled),)]
    words = words[int(short)] if isinstance(words, tuple) else words
    if short:
        return (f"together {_signed(pooled.value)} +- {pooled.sem:.4f}: {words} ({each}, "
                "within their errors)")
    return (f"the seeds' verdicts differ ({each}) within their errors "
            f"({together.scatter_text()}); over the {len(seeded)} seeds, "
            f"{_signed(pooled.value)} +- {pooled.sem:.4f}"
            + (f" (their errors' mean widened x {together.widened:.1f} by their scatter)"
               if together.widened > 1 else "") + f": {words}")


def _retrace_answer(traces, short=False):
    verdicts = tuple(sorted({t.verdict for _, t in traces}))
    if verdicts in RETRACE_ANSWERS:
        return RETRACE_ANSWERS[verdicts][int(short)]
    return _mixed_answer([(r.seed, t.mean, t.verdict) for r, t in traces], _retrace_verdict,
                         RETRACE_ANSWERS, short)


def _retrace_headline(decided):
    """The headline's clause on the second increase against the descent ("" before it
    reaches a level of the descent)."""
    traces = _retraces(decided)
    if not traces:
        return ""
    moves = " and ".join(_signed(t.mean.value) for _, t in traces)
    counts = [t.mean.n for _, t in traces]  # per seed, in the order of the moves
    levels = str(counts[0]) if len(set(counts)) == 1 else " and ".join(map(str, counts))
    shares = " and ".join(f"{100 * t.mean.value / r.down_change:.0f} %" for r, t in traces
                          if r.down_change > 0)
    share = f"; {shares} of the descent's move" if shares else ""
    return (f"; the second increase minus the descent: {moves} (mean of {levels} level"
            f"{'s' if set(counts) != {1} else ''}{share}), {_retrace_answer(traces, short=True)}")


def _retrace_finding(decided):
    """The finding's sentence on the second increase against the descent, per seed and level
    ("" before it reaches a level of the descent)."""
    traces = _retraces(decided)
    if not traces:
        return ""
    seeds = "; ".join(
        f"seed {r.seed}: " + ", ".join(f"{_signed(d)} +- {e:.4f} at {x:g}" for x, d, e in
                                       zip(t.levels, t.differences, t.sems))
        + f"; mean {_signed(t.mean.value)} +- {t.mean.sem:.4f}" for r, t in traces)
    return (f". The second increase against the descent at the sqrt(eps) both visited ("
            f"{len(traces)} of {len(decided)} seed{'s' if len(decided) > 1 else ''}; the "
            f"paper's test of its reversible branch, 'we approximately come across the same "
            f"values'): {_retrace_answer(traces)} (second increase minus descent, {seeds})")


def _return_finding(decided):
    """The finding's sentence on the second increase back at the turning level ("" before):
    of what the descent gained down to the bottom of the loop, what the packing gives back
    and what the loop keeps, per seed."""
    backs = _returns(decided)
    if not backs:
        return ""
    seeds = "; ".join(
        f"seed {s}: of the {b.kept.value - b.given_back.value:+.4f} gained from the turning "
        f"level down to the bottom of the loop it gives back {b.given_back.value:+.4f} +- "
        f"{b.given_back.sem:.4f} and keeps {b.kept.value:+.4f} +- {b.kept.sem:.4f} over its "
        f"first visit, on the first increase"
        for s, b in backs)
    return (f". Back up at the turning level ({len(backs)} of {len(decided)} seed"
            f"{'s' if len(decided) > 1 else ''}), {_return_answer(backs)} ({seeds})")


def _beyond_text(rows, default_eta):
    """The ramps that turned beyond (sqrt eps)* (the paper's reversible branch), per eta:
    their decreasing branch from the turning level and, once they go up again, the second
    increase against it (:meth:`PaperRampRun.retrace`), or how far they got ("" without
    any)."""
    parts = []
    for eta, decided, running in by_eta(rows, default_eta):
        seeds = "; ".join(f"seed {r.seed}, turning at {r.top:g}: {r.down_change:+.4f} +- "
                          f"{r.down_change_sem:.4f} ({r.verdict}){_beyond_retrace(r)}"
                          for r in decided)
        parts.append(f"at {eta_label(eta, default_eta)}, "
                     + "; ".join(p for p in (seeds, running and f"running: {running}") if p))
    return ("Beyond (sqrt eps)* (the reversible branch of the paper), the descending branch "
            "from the turning level: " + ". ".join(parts) + ".") if parts else ""


def _beyond_retrace(run):
    """", second increase minus descent +0.0001 +- 0.0003 over 3 levels (retraces)" of a ramp
    beyond (sqrt eps)* going up again, or ""."""
    trace = run.retrace()
    if trace is None:
        return ""
    k = trace.mean.n
    return (f", second increase minus descent {_signed(trace.mean.value)} +- "
            f"{trace.mean.sem:.4f} over {k} level{'s' if k > 1 else ''} ({trace.verdict})")
