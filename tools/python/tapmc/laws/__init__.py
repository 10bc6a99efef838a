# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Fits of the laws of Philippe & Bideau with parameters, 1-sigma uncertainties, a goodness of
fit and an explicit verdict on whether the parameters are determined by the data.

* :class:`InverseLogLaw`, eq. 3: X(t) = X_inf - dX_inf / (1 + B ln(1 + t/tau)), X = Phi_b or
  <Phi^c> (section III.A).
* :class:`ZLaw`, eq. 4: <Z>(t) = Z_inf (1 + B L) / (Z_inf/Z_0 + B L), L = ln(1 + t/tau).
* :class:`TwoExponentials`: y_inf + a1 exp(-t/tau1) + a2 exp(-t/tau2), tau1 <= tau2
  (section III.A: "a sum of two exponentials can also fit reasonably well <Z>(t)").
* :class:`AgeingLaw`, eq. 6: A(t) = A_inf (1 - 1/(1 + B_A ln(1 + t/tau_A))) (section III.C).
* :class:`ProfileLaw`, eq. 7: Phi(zb) = (Phi0 - alpha zb) / (1 + exp(beta (zb - zb_star))),
  zb = z/R, fitted above the wall layers (section IV.A), with :func:`profile_gradient`, the
  straight-line gradient alpha in the paper's window (5 <= z/R <= 22 FBC, 26 PBC).

Every fitter has ``fit(x, y, sigma=None) -> FitResult``, with automatic starting values
(eqs. 3, 4 and 6 from a grid over (B, tau), their amplitudes solved exactly at every node).
A :class:`FitResult` says whether the data determine the parameters (section III.B: at small
eps the triplet (X_inf, B, tau) "is no longer unique") and gives each parameter a 68 %
profile-likelihood :class:`Interval`, open on a side the data do not close, never a curvature
error where the data fix only a combination of parameters.

Modules, one concern each (every public name above is imported from this package):

* :mod:`.fitting`: :class:`Law`, :class:`FitResult`, :class:`Interval`, the profile
  likelihood, and the tolerances of the determination verdict.
* :mod:`.compaction`: the laws of the taps (eqs. 3, 4, 6, two exponentials), their refits
  over tap ranges (:func:`range_refits`, section III.B) and the test of B's exponential
  dependence on eps^(1/2) (:func:`exponential_dependence`, section III.A).
* :mod:`.profile`: eq. 7 and the gradient alpha (section IV.A).
* :mod:`.surrogates`: :class:`SurrogateFits`, the same questions asked of one run with
  correlated taps, from Fourier surrogates of its residuals.
* :mod:`.realizations`: :class:`RealizationLawTest` (a law tested across independent
  realizations) and :class:`RealizationFits` (its parameters' spread over them).
* :mod:`._computed`: the results of a ``compute`` call, shared by the last two.
"""

from .compaction import (LINEARITY_P_MIN, RANGE_Z_LIMIT, AgeingLaw, ExponentialDependence,
                          InverseLogLaw, LogLinear, RangeRefits, TwoExponentials, ZLaw,
                          default_tap_ranges, exponential_dependence, range_refits)
from .fitting import (CORRELATION_LIMIT, POSITIVE_DECADES, PROFILE_DELTA_CHI2,
                       RELATIVE_ERROR_LIMIT, TIME_SCALE_DECADES, UNBOUNDED_SPAN, FitResult,
                       Interval, Law)
from .profile import PROFILE_WINDOWS, ProfileLaw, StraightLine, profile_gradient
from .realizations import (REALIZATION_MAX_BINS, REALIZATION_P_MIN, RealizationFits,
                            RealizationLawTest, hotelling_gls, realization_bin_covariance,
                            spread_interval, spread_verdict)
from .surrogates import DETERMINED_FACTOR, SURROGATE_P_MIN, SURROGATES, SurrogateFits

__all__ = ["FitResult", "Law", "InverseLogLaw", "ZLaw", "TwoExponentials", "AgeingLaw",
           "ProfileLaw", "StraightLine", "profile_gradient", "PROFILE_WINDOWS",
           "CORRELATION_LIMIT", "RELATIVE_ERROR_LIMIT", "DETERMINED_FACTOR",
           "PROFILE_DELTA_CHI2",
           "POSITIVE_DECADES", "TIME_SCALE_DECADES", "UNBOUNDED_SPAN", "RANGE_Z_LIMIT",
           "LINEARITY_P_MIN", "Interval", "RangeRefits", "range_refits", "default_tap_ranges",
           "LogLinear", "ExponentialDependence", "exponential_dependence",
           "RealizationLawTest", "realization_bin_covariance", "hotelling_gls",
           "REALIZATION_MAX_BINS", "REALIZATION_P_MIN",
           "SurrogateFits", "SURROGATES", "SURROGATE_P_MIN", "RealizationFits",
           "spread_interval", "spread_verdict"]
