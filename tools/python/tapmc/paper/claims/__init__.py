# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The claims of Philippe & Bideau, measured and judged.

The register (``tapmc/paper/claims.toml``) lists every claim of the paper (section, figure,
meaning, the statistic that tests it, the rule, where its tolerance comes from, the scale it
needs and the runs that decide it). Follow a row from the register:

* :mod:`.register`: the register's entries (:class:`Claim`, :func:`load_register`);
* :mod:`.data`: what a report measures from (:class:`ReportData`: the figure CSVs, with the
  realizations' calibration of one-run errors applied once where they load, and the CSVs of
  the paper's questions); :mod:`.calibration` the realization factors it applies;
* the statistics, one module per part of the paper, each function registered under the name
  the register gives it (:mod:`.registry`): :mod:`.compaction` (initial packing and the
  compaction curves, Fig. 2), :mod:`.laws` (eq. 3 and eq. 4), :mod:`.fluctuations` (Fig. 3),
  :mod:`.bell` (the bell and the ramps, Fig. 4 and section III.B, with alpha's bell of
  Fig. 6), :mod:`.ageing` (Fig. 5, eq. 6), :mod:`.zones` (profiles and zones, Figs. 6-8),
  :mod:`.pores` (Figs. 9-10), :mod:`.scans` (theta0 and d_max, section II); each returns
  :class:`Measure` values (:mod:`.measure`);
* :mod:`.rules`: each rule of the register, its decision and its text in one object, and the
  verdict it gives a measure;
* :mod:`.evaluate`: the rows of the report, with the scale each claim needs
  (:mod:`.reduced_ramps` for ramps at fewer taps per level than the paper's);
* :mod:`.conventions`: every hand-typed number that decides a verdict, with its source;
  :mod:`.sensitivity` the verdicts that change when each is halved or doubled (the page's
  table of tolerances).
"""

from __future__ import annotations

# the statistic modules register their statistics when imported
from . import ageing, bell, compaction, fluctuations, laws, pores, scans, zones  # noqa: F401
from .ageing import LAW_FREE_MIN_REALIZATIONS, ageing_collapse, ageing_eq6, dispersion_p_bound
from .bell import (ALPHA_ABOVE_STEADY, CRITICAL_BRACKET_HALF_WIDTH, alpha_bell,
                   alpha_ramp_hysteresis, bell_maximum, bell_side_slope, critical_separation,
                   hysteresis_gap, low_ramp_frozen, ramp_branch_slope, ramp_down_minus_up,
                   ramp_up2_minus_down, ramp_up_minus_steady)
from .calibration import (CALIBRATION_ALPHA, ONE_RUN_WINDOW_ROWS, RUN_ERROR_LABELS,
                          RUN_ERROR_QUANTITIES, SEEDS_GROUP, ZONE_QUANTITIES, group_bc,
                          measured_factor, realization_calibrations, realization_factors,
                          realization_sharing)
from .common import WITHIN_RUN_DOF
from .conventions import CONVENTIONS, PAIRED_MIN_LEVELS, Convention
from .compaction import (DECADE_BEFORE_WINDOW, EARLY_DECADE, EARLY_MIN_SEEDS, LATE_WINDOW,
                         SHORT_WINDOW_BATCHES, efficiency_decrease, first_decade_rates,
                         initial_phi, late_gain_share, pbc_compaction, pbc_vs_fbc,
                         phi_b_gain, tapped_phi)
from .data import QUESTION_CSVS, FigureData, ReportData
from .evaluate import Row, Rows, evaluate, scale_aspects
from .fluctuations import SPECTRUM_BAND, sigma_intercept, spectral_slopes, spectrum_low_band
from .laws import (AVERAGED_FITS, EQ3_TRIPLET, ONE_RUN_FITS, RANDOM_CLOSE_PACKING,
                   REALIZATION_MIN_SEEDS, REALIZATION_MIN_TAPS, SURROGATES_UNIQUE, b_exponential, back_at_start,
                   eq3_fit_quality, eq3_small_eps_asymptote, eq3_triplet_pattern,
                   eq4_fit_quality, loosening_end, realization_curves, realization_fits,
                   surrogate_fits, z_two_exponentials)
from .measure import Measure, fmt
from .pores import (GAUSSIAN_TAIL_SD, nu_change, nu_ramp_hysteresis, nu_tail_over_nu,
                    p0_change_over_density, p0_final_minus_py, pore_gaussian_excess,
                    pore_law_deviation, pore_quadratic_fit, pore_share_change, xi_min)
from .reduced_ramps import (RAMP_LEVELS_DEFAULT_RUN, RAMP_REDUCTION_BRANCHES,
                            RAMP_REDUCTION_MIN_LEVELS, RAMP_REDUCTION_TAGS, ramp_reduction_bounds,
                            ramp_reduction_shift, ramp_tag)
from .register import ASPECTS, KINDS, PAPER_SCALE, REGISTER, Claim, load_register
from .registry import STATISTICS, statistic
from .rules import (FIT_P_VALUE, NEAR_FRACTION, RULE_NAMES, RULES, XI_CHECK_ROUNDING, Outcome,
                    Rule, Verdict, verdict)
from .scan_tables import (OTHER_READING_TAGS, SCANS, read_scan, scan_files, scan_settings,
                          scan_table)
from .scans import dmax_intermediate, theta0_optimum
from .sensitivity import Sensitivity, convention_changes, sensitivities, tolerance_table
from .zones import (BELL_SIDE_POINTS, central_minus_lateral, eq7_smoothed_fit, final_alpha,
                    lateral_first_tap, smoothed_departures, wall_layering, wall_layers,
                    zone_bell)
from tapmc.stats import t_quantile  # noqa: F401  (named here by older callers)

__all__ = [name for name in dir() if not name.startswith("_")
           and name not in ("annotations", "ageing", "bell", "compaction", "fluctuations",
                            "laws", "pores", "scans", "zones", "conventions", "sensitivity")]
