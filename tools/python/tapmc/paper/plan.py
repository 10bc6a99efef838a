# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The paper-scale campaign in the order its runs are worth running.

At the paper's scale (``FULL``: N = 4096, L = 32R, 4000 taps, eta = 1e-7) one run costs one to
four core-hours, so the campaign behind the validation report spans many working sessions. Its
runs come in tiers; each tier completes figures on its own:

1. the paper's own protocol, one run per point from the same initial packing (seed 1 for every
   eps, so ``pack_seed`` is shared, section III.B): the P.B.C. bell of Fig. 4 (squares) with
   Fig. 3 from the same runs, Fig. 2's F.B.C. eps, Figs. 6-7 at eps = 0.1 (F.B.C. and P.B.C.),
   Fig. 10's pore-dump run (F.B.C., eps = 2e-2); Fig. 9 uses the packing dumps (t = 0 and
   after 4000 taps) of the P.B.C. run at ``FULL.p0_eps`` = 0.0225, the bell's top;
2. error bars where the bell's shape is decided: seeds 2 and 3 at both ends and at the top,
   and Fig. 8's fourth eps;
3. the history-dependent protocols: the ramp (Fig. 4 open symbols) at 1000 taps per level
   instead of the paper's 4000, and ageing (Fig. 5); with two jobs or more the ramp, the
   longest run, starts first (:func:`runs`);
4. the paper's 10 ageing realizations (section III.C: seeds 5 to 10 join tier 3's four; a test
   of the collapse across realizations needs more realizations than bins of delays, and the
   runs cost about half a core-hour each), then the ramp pair of section III.B: the ramp that
   stays below (sqrt eps)* ~ 0.15 (up to
   ``FULL.ramp_below_top`` = 0.125, down and up again; run ``ramplow_pbc_s1``) at tier 3's taps
   per level, which with tier 3's ramp (up to 0.3) decides the reversible and irreversible
   branches; the ramp that turns at the first level beyond 0.15 (0.175, ``rampnear_pbc_s1``),
   which locates (sqrt eps)* between 0.125 and 0.175; then a second seed of the pair for
   error bars over seeds;
5. the F.B.C. realizations: seeds 2 and 3 at ``TIER5_FBC_EPS`` = 0.02 (Fig. 8's and Fig. 10's
   eps, the cheapest F.B.C. run), so that the spread of F.B.C. realizations is measured
   (``tapmc-paper question realization-scatter``) instead of borrowed from the P.B.C.
   groups of tier 2 and the ageing runs: the F.B.C. figures (2, 6, 8) have one run per eps;
6. seeds 2 and 3 at ``TIER6_FBC_EPS`` = 0.1, the eps of Figs. 6-7 and Fig. 8's strongest: the
   F.B.C. profiles, alpha and zones of the paper's central eps over realizations, and a
   second F.B.C. group for the factors of realization-scatter and packing-scatter (about
   1.5 core-hours each);
7. section III.B's question at the paper's own protocol (4000 taps per level, ``paperramp*``
   runs, apart from the 1000-tap ramps the figures draw): the ramp that turns at 0.125 below
   (sqrt eps)* (2 seeds) and one that turns at 0.2 beyond it, at the scale's eta; then the
   ramp below at looser redeposition thresholds (eta = 1e-5, 1e-6; 2 seeds each), which asks
   whether an under-settled redeposition freezes the small taps. 52 000 taps for a ramp
   below, 88 000 beyond: serial chains of 8 to 20 core-hours each at eta = 1e-7;
8. sigma_<Z> against the threshold (section III.B: sigma_<Z> ~ sqrt(eps) or an offset from
   settling noise?): the steady state at four sqrt(eps) of the bell (0.05, 0.1, 0.15, 0.3) at
   eta = 1e-6 and 1e-8 (``consteta_*`` runs, 2 seeds each), then the default-eta seeds that
   give every square of the bell 3 seeds.

Within a tier the runs that settle the report's open questions first come first. Runs carry
the names of the figure modules' runs (:mod:`tapmc.paper._runs`), so the figures find them.
"""

from __future__ import annotations

from fnmatch import fnmatchcase

from . import _runs
from .scales import FULL

#: P.B.C. eps of tier 1 in the order they run: the eps of the report's <Phi^c> question and of
#: the bell's top first, then the ends, then the rest of the bell.
TIER1_PBC_EPS = (0.0225, 0.005, 0.15, 0.1, 0.05, 0.0025, 0.01, 0.015625, 0.04, 0.09)
#: F.B.C. eps of tier 1: Figs. 6-7 (0.1), then Fig. 2 (5e-3, 5e-2, 0.15).
TIER1_FBC_EPS = (0.1, 0.005, 0.05, 0.15)
#: Tier 2: P.B.C. eps with more seeds (the bell's ends and top) and the seeds added.
TIER2_PBC_EPS = (0.0025, 0.0225, 0.15)
TIER2_SEEDS = (2, 3)
#: Tier 2: the F.B.C. eps Fig. 8 adds to tier 1's.
TIER2_FBC_EPS = (0.02,)
#: Tier 3: taps per level of the ramp (the paper: 4000) and ageing realizations.
TIER3_RAMP_TAPS_PER_LEVEL = 1000
TIER3_AGEING_SEEDS = (1, 2, 3, 4)

#: Tier 4: the ageing realizations that complete the paper's 10 (section III.C).
TIER4_AGEING_SEEDS = (5, 6, 7, 8, 9, 10)
#: Tier 4: seeds of the ramp pair (the ramp below (sqrt eps)* first: tier 3 ran the other one
#: with seed 1).
TIER4_SEEDS = (1, 2)
#: Tier 5: the F.B.C. eps and seeds that join tier 2's seed 1 in a group of realizations.
TIER5_FBC_EPS = (0.02,)
TIER5_FBC_SEEDS = (2, 3)
#: Tier 6: the same for the F.B.C. run of Figs. 6-7 (eps = 0.1, tier 1's seed 1).
TIER6_FBC_EPS = (0.1,)
TIER6_FBC_SEEDS = (2, 3)

#: Tier 7: the paper's taps per level (section III.B), the ramps' turning points and seeds,
#: and the looser thresholds of the ramp below (sqrt eps)* (the cheapest first).
TIER7_RAMP_TAPS_PER_LEVEL = 4000
TIER7_BELOW_SEEDS = (1, 2)
TIER7_BEYOND_TOP = 0.2
TIER7_BEYOND_SEEDS = (1,)
TIER7_LOOSE_ETAS = (1e-5, 1e-6)
TIER7_LOOSE_SEEDS = (1, 2)

#: Tier 8: sigma_<Z> against eta at four eps of the bell, and the bell's missing seeds (their
#: const_* runs join the figures: drawn_runs).
TIER8_EPS = (0.0025, 0.01, 0.0225, 0.09)
TIER8_ETAS = (1e-6, 1e-8)
TIER8_SEEDS = (1, 2)
TIER8_BELL_SEEDS = (2, 3)

TIERS = (1, 2, 3, 4, 5, 6, 7, 8)
#: The tiers whose runs the figures and the validation report draw whole (drawn_runs).
DRAWN_TIERS = (1, 2, 3, 4, 5, 6)


def tier_runs(tier, scale=FULL):
    """The RunSpecs of one tier (1 to 6), in running order."""
    if tier == 1:
        pbc = [_runs.constant_eps_run(scale, "pbc", eps, 1) for eps in TIER1_PBC_EPS]
        fbc = [_runs.constant_eps_run(scale, "fbc", eps, 1) for eps in TIER1_FBC_EPS]
        pores = _runs.pore_run(scale, scale.pore_bc, scale.pore_eps, 1, scale.dump_times)
        # the first P.B.C. run, then Fig. 10's dumps, then alternate so both figure families fill
        return [pbc[0], pores, pbc[1], pbc[2], fbc[0], pbc[3], *fbc[1:], *pbc[4:]]
    if tier == 2:
        return ([_runs.constant_eps_run(scale, "pbc", eps, s)
                 for s in TIER2_SEEDS for eps in TIER2_PBC_EPS]
                + [_runs.constant_eps_run(scale, "fbc", eps, 1) for eps in TIER2_FBC_EPS])
    if tier == 3:
        ramp_scale = scale.replace(ramp_taps_per_level=TIER3_RAMP_TAPS_PER_LEVEL)
        return ([_runs.ramp_run(ramp_scale, "pbc", 1)]
                + [_runs.ageing_run(scale, "pbc", scale.ageing_eps, s)
                   for s in TIER3_AGEING_SEEDS])
    if tier == 4:
        ramp_scale = scale.replace(ramp_taps_per_level=TIER3_RAMP_TAPS_PER_LEVEL)
        pair = []
        for seed in TIER4_SEEDS:
            if seed != 1:   # tier 3 holds the ramp beyond (sqrt eps)* of seed 1
                pair.append(_runs.ramp_run(ramp_scale, "pbc", seed))
            pair.append(_runs.ramp_below_run(ramp_scale, "pbc", seed))
            if seed == 1:   # one seed locates (sqrt eps)*; error bars come from the pair
                pair.append(_runs.ramp_near_run(ramp_scale, "pbc", seed))
        ageing = [_runs.ageing_run(scale, "pbc", scale.ageing_eps, s)
                  for s in TIER4_AGEING_SEEDS]
        return ageing + sorted(pair, key=lambda spec: spec.seed)
    if tier == 5:
        return [_runs.constant_eps_run(scale, "fbc", eps, s)
                for s in TIER5_FBC_SEEDS for eps in TIER5_FBC_EPS]
    if tier == 6:
        return [_runs.constant_eps_run(scale, "fbc", eps, s)
                for s in TIER6_FBC_SEEDS for eps in TIER6_FBC_EPS]
    if tier == 7:
        paper = scale.replace(ramp_taps_per_level=TIER7_RAMP_TAPS_PER_LEVEL)
        below = [_runs.paper_ramp_run(paper, "pbc", s, paper.ramp_below_top)
                 for s in TIER7_BELOW_SEEDS]
        beyond = [_runs.paper_ramp_run(paper, "pbc", s, TIER7_BEYOND_TOP)
                  for s in TIER7_BEYOND_SEEDS]
        loose = [_runs.paper_ramp_run(paper, "pbc", s, paper.ramp_below_top, eta=eta)
                 for eta in TIER7_LOOSE_ETAS for s in TIER7_LOOSE_SEEDS]
        return [below[0], *loose[:len(TIER7_LOOSE_SEEDS)], *below[1:], *beyond,
                *loose[len(TIER7_LOOSE_SEEDS):]]
    if tier == 8:
        thresholds = [_runs.constant_eps_eta_run(scale, "pbc", eps, s, eta)
                      for eta in TIER8_ETAS for s in TIER8_SEEDS for eps in TIER8_EPS]
        have = {(eps, s) for eps in TIER2_PBC_EPS for s in TIER2_SEEDS}
        bell = [_runs.constant_eps_run(scale, "pbc", eps, s)
                for s in TIER8_BELL_SEEDS for eps in scale.steady_eps if (eps, s) not in have]
        return thresholds + bell
    raise ValueError(f"tier = {tier!r}: allowed values are {', '.join(map(str, TIERS))}")


def runs(up_to_tier=TIERS[-1], scale=FULL, jobs=1):
    """Every run of tiers 1 .. ``up_to_tier``, in running order: the tiers in turn. With two
    jobs or more, tier 3's ramp, when asked for, goes first: it is the campaign's longest run
    and cannot be split (34 levels of 1000 taps, some 14 core-hours in one process, five
    working sessions or more), so it takes one job from the start while the others go through
    the tiers in order (longest first: the campaign ends when its last run does). With one
    job the tiers keep their order, so that the figures fill first."""
    if up_to_tier not in TIERS:
        raise ValueError(f"tier = {up_to_tier!r}: allowed values are "
                         f"{', '.join(map(str, TIERS))}")
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise ValueError(f"jobs = {jobs!r}: must be an integer >= 1")
    ordered = [spec for tier in TIERS if tier <= up_to_tier for spec in tier_runs(tier, scale)]
    if up_to_tier < 3 or jobs < 2:
        return ordered
    longest = [spec for spec in ordered if spec.name == _runs.ramp_run(scale, "pbc", 1).name]
    return longest + [spec for spec in ordered if spec not in longest]


def drawn_runs(scale=FULL):
    """The runs the figures and the validation report draw (``report --finished-only`` counts
    them as planned): every run of DRAWN_TIERS, and tier 8's default-eta seeds of the bell
    (``const_*``), which give every square of Fig. 4 three seeds. The runs at other protocols,
    tier 7's ``paperramp*`` (4000 taps per level) and tier 8's ``consteta_*`` (other eta), are
    read by their own questions (``paper-ramp``, ``sigma-eta``) and by the rows of the claims
    that name their protocol: among the figures' runs they would give the page several eta
    and several taps per level, where its rows name one of each."""
    bell = [spec for spec in tier_runs(8, scale) if spec.name.startswith("const_")]
    return runs(DRAWN_TIERS[-1], scale) + bell


def first(specs, patterns):
    """``specs`` with the runs whose names match ``patterns`` (shell-style: ``ageing_*``)
    moved to the front, in the order of the patterns, the rest in their order: a campaign
    under way can finish what a session needs first. A pattern that matches no run is refused
    (a typo would otherwise silently change nothing)."""
    specs = list(specs)
    front = []
    for pattern in patterns:
        matched = [spec for spec in specs if fnmatchcase(spec.name, pattern)]
        if not matched:
            raise ValueError(f"--first {pattern!r}: matches no run of the plan (its runs: "
                             f"{', '.join(spec.name for spec in specs)})")
        front += [spec for spec in matched if spec not in front]
    return front + [spec for spec in specs if spec not in front]
