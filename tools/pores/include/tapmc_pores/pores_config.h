// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Every tolerance and default of the pore tool (tapmc-pores), named, with the reason for its value.
// doc/tapmc-pores.rst quotes these values; change both together.
#ifndef TAPMC_PORES_CONFIG_H
#define TAPMC_PORES_CONFIG_H

#include <cstddef>

namespace tapmc {
namespace pores {
namespace config {

// ---- degenerate Voronoi vertices -----------------------------------------------------------
// Face-adjacent Delaunay tetrahedra whose circumcentres are closer than kMergeTolerance * R and
// whose circumradii differ by less than kMergeTolerance * R share one empty sphere (five or more
// cospherical centres, e.g. the octahedral hole of FCC split into four tetrahedra): one pore.
// Double-precision circumcentres of tetrahedra carry ~1e-15 R of rounding (slivers are computed
// exactly, see kSliverRelativeVolume), and genuinely distinct Voronoi vertices closer than
// 1e-8 R are indistinguishable once a dump has been printed with 6 to 17 digits.
constexpr double kMergeTolerance = 1e-8;

// A tetrahedron is a sliver when |det(b-a, c-a, d-a)| < kSliverRelativeVolume * |b-a||c-a||d-a|
// (6 V over the product of three edges; 0.47 for a regular tetrahedron). Its circumcentre is then
// ill-conditioned in double precision (error ~ 1e-16 / this ratio), so it is computed in exact
// rational arithmetic instead; 1e-6 keeps the double path's error below 1e-10 R, far under
// kMergeTolerance, while slivers that thin are rare in random packings (cost negligible).
constexpr double kSliverRelativeVolume = 1e-6;

// ---- periodic image padding -----------------------------------------------------------------
// Periodic directions are padded with images of the centres within this distance (in units of R)
// of each face. A pore is exact when its empty sphere fits in the padded slab, which holds for
// every pore with circumradius up to half the padding: 4 R resolves xi <= 1, beyond the interior
// pores of hard-sphere packings (Bernal's largest hole: 0.645; our phi = 0.33 random packings
// need no retry). The padding costs (1 + 2 P / L)^2 more points: 56 % for the paper's 32 R box at
// 4 R (89 % at 6 R). Wider empty spheres of pores centred in the selection sub-box trigger a
// retry that inserts just the extra layer of images needed (at most kMaxPaddingRetries retries,
// padding at most 4 R x 2^retries = 16 R); what is wider still, or wide and outside the sub-box
// (flat hull cells open towards a wall or free surface), is counted as unresolved and left out,
// never silently kept (an error when triply periodic).
constexpr double kPaddingOverRadius = 4.0;
constexpr int kMaxPaddingRetries = 2;

// ---- input checks ---------------------------------------------------------------------------
// Two spheres overlap when their distance is below 2R (1 - kOverlapTolerance). LAMMPS's default
// dump format (%g) keeps 6 significant digits, so spheres in contact in a box 100 diameters wide
// can look overlapping by ~1e-4 of a diameter; real overlaps (soft-sphere DEM) above 1e-3 are
// refused because the tangent-sphere pore is then ill-defined. Overridable (--overlap-tol).
constexpr double kOverlapTolerance = 1e-3;

// Radii that differ by more than kPolydisperseTolerance (relative to the mean) make the input
// polydisperse; the tangent-sphere pore of equal spheres does not apply. 1e-6 is above the
// rounding of a printed radius (6 digits) and far below any physical size dispersion.
constexpr double kPolydisperseTolerance = 1e-6;

// A centre is outside a non-periodic box side when it lies beyond the bound by more than
// kBoxTolerance times the box length (room for the rounding of printed bounds only).
constexpr double kBoxTolerance = 1e-9;

// ---- statistics defaults --------------------------------------------------------------------
// Pores closer than kDefaultWallGap * R to a non-periodic box face are left out of the statistics
// (paper, section IV.B: "at a distance 2R from the walls").
constexpr double kDefaultWallGap = 2.0;
// Histogram of xi on [0, kDefaultXiMax] with kDefaultBins bins; v = xi^3 on [0, kDefaultXiMax^3].
// 1.5 covers every interior pore of a hard-sphere packing (Bernal's largest hole: 0.645).
constexpr double kDefaultXiMax = 1.5;
constexpr std::size_t kDefaultBins = 150;
// Gotoh's P0(sigma) is tabulated on [0, kDefaultSigmaMax] with kDefaultSigmaBins steps.
constexpr double kDefaultSigmaMax = 2.0;
constexpr std::size_t kDefaultSigmaBins = 200;
// Random points per frame for P0 when --p0 is given without a count.
constexpr std::size_t kDefaultP0Samples = 100000;

}  // namespace config
}  // namespace pores
}  // namespace tapmc

#endif
