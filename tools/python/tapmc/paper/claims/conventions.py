# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Every hand-typed number that decides a verdict of the register, in one place: each a named
constant with what it decides and where it comes from (the paper's section, a statistical
standard, or "convention" with the reason for its value). The rules and statistics import
them from here; :data:`CONVENTIONS` lists them for the page's table of tolerances, which
says how many verdicts change when each is halved or doubled (:mod:`.sensitivity`).

A few conventions act before the report: they were applied when a figure or a question of
``tapmc-paper`` wrote its CSV (a gradient window, the limit of a "determined" parameter), so
the committed CSVs cannot be re-evaluated with another value; they are listed with their
source and marked so.
"""

from __future__ import annotations

from dataclasses import dataclass

from tapmc.laws import DETERMINED_FACTOR, RANGE_Z_LIMIT, RELATIVE_ERROR_LIMIT, SURROGATE_P_MIN
from tapmc.stats import CALIBRATION_ALPHA, CONFIDENCE

from ..fig6 import WINDOW_TOP_FRACTION

#: p-value below which a fit's test rejects the law (rule ``fit``; B's exponential
#: dependence): a 1 % test, stricter than the 5 % of a sign because a law is tested at many
#: eps and tap ranges at once (convention)
FIT_P_VALUE = 0.01

#: "nearly" / "approximately the same" (rule ``near``): within a tenth of the effect the claim
#: is measured against, the share below which the ramp-levels text also calls a shift
#: negligible (convention: the paper gives no precision for "approximately")
NEAR_FRACTION = 0.1

#: rounding of the pore dumps' coordinates (6 printed digits of lengths ~1), allowed below
#: xi_T by the ``check`` rule
XI_CHECK_ROUNDING = 1e-3

#: CALIBRATION_ALPHA (tapmc.stats, where the paper ramps' own calibration reads it too):
#: one-sided significance below which the realizations' spread rejects one run's own error,
#: and two-sided significance below which two sets of groups (or a statistic's few seeds and
#: the groups, or the groups at different eps) do not share one factor

#: the paper's "(sqrt eps)* ~ 0.15" (section III.B): a separation located within two of its
#: ramp steps (dsqrt = 0.025) of 0.15 agrees; a bracket of turning points wider than that
#: cannot tell 0.15 from its neighbours
CRITICAL_BRACKET_HALF_WIDTH = 0.05

#: fraction of the frequencies, the lowest, where ``spectrum_low_band`` asks whether eps is
#: noticeable (section III.A, "eps is noticeable only at high frequencies": the highest band
#: is shown beside it; convention: a quarter of the frequencies, the paper names none)
SPECTRUM_BAND = 0.25

#: realizations of the first decade (tapmc-paper question early-taps) below which its rates
#: keep one run's error (one tap's spread): the sem of fewer has too few degrees of freedom
#: to decide anything (convention)
EARLY_MIN_SEEDS = 4

#: realizations (early_taps.csv) that test a law of Fig. 2 across runs: a 4-parameter law
#: needs 6 (tapmc.laws.RealizationLawTest: realizations > bins > parameters) ...
REALIZATION_MIN_SEEDS = 6

#: ... spanning at least two decades of taps, over which the laws' curvature shows
#: (convention)
REALIZATION_MIN_TAPS = 100

#: levels of a branch measured at the paper's taps per level before their largest shift
#: stands for the whole branch (one level says nothing of how the shift varies along it)
RAMP_REDUCTION_MIN_LEVELS = 2

#: levels of a ramp's branch (common to the two branches a difference reads) from which the
#: difference of a few seeds judged alone is decided by the paired test over the levels
#: rather than by the seeds' own spread (at least this many levels give the test 2 dof)
PAIRED_MIN_LEVELS = 3

#: levels of the decrease on the first increase a paper ramp's seed needs to take part in the
#: check of alpha's level-scatter error on pairs of seeds (gradient-no-hysteresis): the error
#: from the scatter of two differences has one degree of freedom and is itself too noisy
SCATTER_CHECK_LEVELS = 3


@dataclass(frozen=True)
class Convention:
    """One convention: the constant ``name`` (of this module, or of the module ``where``
    when it acts before the report), what it decides, its source, and how the table of
    tolerances varies it: ``vary`` "value" (halved and doubled), "tail" (a confidence level:
    its tail 1 - value halved and doubled), "integer" (halved and doubled, rounded, at least
    1) or "" (acts before the report: not re-evaluated)."""

    name: str
    decides: str
    source: str
    vary: str = "value"
    where: str = ""

    @property
    def value(self):
        return _VALUES[self.name]

    def varied(self, factor):
        """The value with the convention scaled by ``factor`` (0.5: halved, 2: doubled), as
        :attr:`vary` says; None when it is not varied."""
        if self.vary == "value":
            return self.value * factor
        if self.vary == "tail":
            return 1.0 - (1.0 - self.value) * factor
        if self.vary == "integer":
            return max(1, int(round(self.value * factor)))
        return None


#: Half a unit of the last digit the paper prints of a packing fraction (58.4 %, 60.6 %,
#: section IV.B): the precision at which the paper can tell a law from its curves of Phi
#: (eq. 3 "compatible" with Fig. 2, section III.A), the register's ``rounding`` of a value
PACKING_FRACTION_PRECISION = 0.0005

#: realizations below which the law-free dispersion is not read: its bound
#: (:func:`.ageing.dispersion_p_bound`) integrates the tail of F(1, n - 1), whose mean exists
#: only for n - 1 > 2
LAW_FREE_MIN_REALIZATIONS = 4

#: the random close packing the paper sets as the limit X_inf "can get over" (section I:
#: "approximately ... 64 %, the random close packing")
RANDOM_CLOSE_PACKING = 0.64

#: how much wider than one run's surrogate bands (tapmc.laws.SurrogateFits) the truth lies:
#: a band of eq. 3's B held the value of independent realizations in 33 to 47 % of the runs
#: for a nominal 68 % (tests/python/test_slow_surrogate_fits.py), the coverage of a Gaussian
#: half width of 0.43 to 0.63 standard deviations: 1 / 0.43. Two bands of one run each
#: separate a parameter at two eps only once both are widened by it (about the fitted value,
#: on the band's own scale, linear or log)
SURROGATE_BAND_WIDENING = 2.3

#: the share of a Gaussian beyond its mean plus this many standard deviations (2.3 %) is what
#: ``pore_gaussian_excess`` compares the pores' volume distribution with: the tail of the
#: largest pores, where the paper sees the over-population
GAUSSIAN_TAIL_SD = 2.0

#: points a straight line through one side of a bell needs (a slope with its own error)
BELL_SIDE_POINTS = 3

#: the "smoothing of the profile" the paper applies before reading Fig. 6 (section IV.A):
#: means over blocks of this height, in R, from the bottom of the gradient window. One
#: sphere diameter: the wall layers stacked from the floor, which the smoothing removes, are
#: about a diameter apart (the paper-scale profile oscillates with a period of 1.6R, close to
#: the sqrt(8/3) R of close-packed layers); the paper gives no width
EQ7_SMOOTHING_WIDTH = 2.0

#: "approximately a three layers range" (section IV.A): a count of wall layers within this
#: many layers of three. One layer: the paper's own reading of the range, the lateral zone
#: "at a distance less than 7R from the walls corresponding roughly to this wall effects
#: range", is 3.5 sphere diameters, room for the centres of three or four layers
WALL_LAYERS_APPROXIMATELY = 1.0


#: the conventions of the table of tolerances, in the order of the register's rules, then the
#: statistics by section of the paper, then those applied before the report
CONVENTIONS = (
    Convention("CONFIDENCE", "the t quantile of every sign, zero, range, value and near rule "
               "and of every one-sided test of the statistics",
               "statistical standard: a two-sided 95 % interval", vary="tail"),
    Convention("FIT_P_VALUE", "the p-value a law's fit needs (rule fit; B's exponential "
               "dependence)", "convention: a 1 % test, the laws being tested many times"),
    Convention("NEAR_FRACTION", "'nearly' / 'approximately the same' (rule near): the share "
               "of the effect a difference may reach",
               "convention: the paper gives no precision; a tenth of the hysteresis gap"),
    Convention("XI_CHECK_ROUNDING", "the pore analysis check's allowance below xi_T",
               "the dumps' printed precision"),
    Convention("CALIBRATION_ALPHA", "when the realizations' spread rejects one run's error, "
               "and when groups (boundary conditions, a statistic's seeds, eps) share one factor",
               "convention: a 1 % test, as the fits'"),
    Convention("PAIRED_MIN_LEVELS", "levels from which a ramp difference of seeds judged alone "
               "is decided by the paired test over its levels", "convention: 2 dof at least",
               vary="integer"),
    Convention("SCATTER_CHECK_LEVELS", "levels a paper ramp's seed needs to take part in the "
               "check of alpha's level-scatter error on pairs of seeds", "convention: 2 dof at "
               "least for each seed's error", vary="integer"),
    Convention("RAMP_REDUCTION_MIN_LEVELS", "levels of a branch measured at 4000 taps before "
               "its largest shift stands for the branch (ramps at fewer taps per level)",
               "convention: one level says nothing of the variation along the branch",
               vary="integer"),
    Convention("CRITICAL_BRACKET_HALF_WIDTH", "how far from 0.15 the turning ramps may "
               "locate (sqrt eps)*", "the paper's ramp step: two steps of 0.025 in sqrt(eps) "
               "(section III.B)"),
    Convention("SPECTRUM_BAND", "the lowest frequencies, where the spectra of every eps must "
               "coincide (eps 'noticeable only at high frequencies')",
               "convention: a quarter of the frequencies; the paper names none"),
    Convention("PACKING_FRACTION_PRECISION", "the paper's precision of a law of Phi (eq. 3 "
               "'compatible'): an outcome 'at the paper's precision, not at ours'",
               "the paper's printed digits: half a unit of 58.4 %, 60.6 % (section IV.B)"),
    Convention("RANDOM_CLOSE_PACKING", "the limit X_inf of eq. 3 'can get over'",
               "the paper's 64 % (section I)"),
    Convention("LAW_FREE_MIN_REALIZATIONS", "realizations a curve of Fig. 5 needs for the "
               "law-free collapse's dispersion", "the mean of F(1, n - 1) exists for n >= 4",
               vary="integer"),
    Convention("GAUSSIAN_TAIL_SD", "where the large-pore tail of rho_v starts, against a "
               "Gaussian's", "convention: 2 standard deviations (2.3 % of a Gaussian)"),
    Convention("BELL_SIDE_POINTS", "points one side of a bell of delta Phi needs for its "
               "slope", "a slope with its own error needs 3", vary="integer"),
    Convention("EQ7_SMOOTHING_WIDTH", "the smoothing of Fig. 6's profile before eq. 7 is "
               "compared with it: means over blocks of this height (in R)",
               "convention: one sphere diameter, about the wall layers' spacing; the paper "
               "smooths but gives no width (section IV.A)"),
    Convention("WALL_LAYERS_APPROXIMATELY", "'approximately a three layers range' of Fig. "
               "7: the count of wall layers within this many layers of three",
               "the paper's 7R wall-effects range (section IV.A): 3.5 diameters, three or "
               "four layers"),
    Convention("EARLY_MIN_SEEDS", "realizations of the first decade below which its rates "
               "keep one run's error", "convention", vary="integer"),
    Convention("REALIZATION_MIN_SEEDS", "realizations that test a law of Fig. 2 across runs",
               "RealizationLawTest: realizations > bins > parameters", vary="integer"),
    Convention("REALIZATION_MIN_TAPS", "taps the realizations of a law's test must span",
               "convention: two decades of taps", vary="integer"),
    Convention("WINDOW_TOP_FRACTION", "the top of the gradient alpha's window (Figs. 6, 8), "
               "as a fraction of the packing height", "the paper's 5R to 22R of a 28R packing "
               "(section IV.A)", vary="", where="tapmc.paper.fig6, when the figure is drawn"),
    Convention("RELATIVE_ERROR_LIMIT", "an amplitude of eq. 3 or 4 'determined': its band "
               "within this share of its value", "convention", vary="",
               where="tapmc.laws, when fit-surrogates and seed-fits ran"),
    Convention("DETERMINED_FACTOR", "B or tau of eq. 3 or 4 'determined': its band within "
               "this factor", "convention: a scale known to a factor 2 is known to its "
               "order", vary="", where="tapmc.laws, when fit-surrogates and seed-fits ran"),
    Convention("RANGE_Z_LIMIT", "a fitted parameter 'dependent on the range of taps'",
               "convention: 3 standard deviations for 4 ranges tested together", vary="",
               where="tapmc.laws, when the figure is drawn"),
    Convention("SURROGATE_BAND_WIDENING", "one run's surrogate bands widened by this factor "
               "before two of them separate eps (tau of eq. 3 growing at the smallest eps; "
               "X_inf beyond the random close packing)", "measured: the bands' coverage "
               "33-47 % of a nominal 68 % (test_slow_surrogate_fits.py), 1 / 0.43"),
    Convention("SURROGATE_P_MIN", "a parameter range dependent in one run's surrogate fits "
               "(eq. 3's triplet)", "convention: a 1 % test, as the fits'"),
)


_VALUES = {name: value for name, value in globals().items() if name.isupper()}
