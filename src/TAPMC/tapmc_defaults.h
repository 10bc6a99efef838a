// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Every default and tolerance of the package, named, with the reason for its value.
// Docs (doc/*.rst) quote these values; change both together.
#ifndef TAPMC_DEFAULTS_H
#define TAPMC_DEFAULTS_H

namespace tapmc {
namespace defaults {

// ---- contact geometry ------------------------------------------------------------------------
// Two spheres overlap when |r_ij| < R_i + R_j - tol, tol = kContactTolerance * (R_i + R_j).
// A tiny positive tolerance makes exact lattices at contact (built with rounding) legal input;
// 1e-10 of a diameter is far below any physical length of the model yet far above the
// 1e-16 relative rounding of the coordinates. The same relative tolerance applies to the floor
// and to side walls (measured against the sphere's diameter).
constexpr double kContactTolerance = 1e-10;

// ---- trial moves (paper, section II) -------------------------------------------------------
// d_max = R/5: the paper's optimised step (too small freezes, too large is always rejected).
constexpr double kMaxStepOverRadius = 0.2;
// theta0 = pi/4: width of P(theta) = A exp(-(theta/theta0)^2) (eq. 1), the paper's value
// giving the maximal compaction rate.
constexpr double kThetaWidth = 0.78539816339744830962;  // pi/4

}  // namespace defaults
}  // namespace tapmc

#endif
