// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Every tolerance, default and limit of the pore tool (tapmc-pores), named, with the reason for
// its value.
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
// ... unless the dump's coordinates were written with fewer digits: without --merge-tol the
// tolerance is then kMergeRoundingFactor times the rounding of the largest coordinate (half a
// unit of its last written digit), over R. Measured on FCC written with %g (6 digits, rounding
// 1e-5 R): the octahedral holes came out as 1 to 4 pores (nu 0.0467 for 0.0313) up to a
// tolerance of 2e-5 R and whole from 5e-5 R; 10 times the rounding is 1e-4 R there. Dumps
// written with %.10g (the paper inputs', rounding ~1e-8 R) get ~1e-7 R, with %.17g 1e-8 R.
constexpr double kMergeRoundingFactor = 10.0;
// ... and never above kMaxMergeTolerance (below --merge-tol's bound 0.1): a dump written with a
// few digits of large coordinates would otherwise merge every pore with its neighbours.
constexpr double kMaxMergeTolerance = 1e-2;
// Written digits are read from the first kDigitsSample atoms of each frame (the most over their
// coordinates): %.10g trims a trailing zero one time in ten, so 3 x 64 values all written short
// happen 1e-192 of the time. Text never holds fewer than kLeastDumpDigits (LAMMPS's %g).
constexpr std::size_t kDigitsSample = 64;
constexpr int kLeastDumpDigits = 6;

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
// --padding below kMinPaddingOverRadius (in R) is a usage error: a padding P resolves at the
// first attempt the pores of empty-sphere radius up to xi = P / (2 R) - 1, so below 2 R not
// even a pore of zero size (four spheres in contact) would fit beside a periodic face.
constexpr double kMinPaddingOverRadius = 2.0;
constexpr int kMaxPaddingRetries = 2;
// --padding above kMaxPaddingOverRadius (in R) is a usage error. 32 R resolves at the first
// attempt every pore whose circumsphere has a radius up to 16 R (xi up to 15), up to 64 R after
// the retries: far beyond the interior pores of any packing (xi < 1), and beyond the need of
// gases (30 random spheres at phi = 0.016, periodic, are resolved by the default). The images
// cost (1 + 2 P / L)^k times the centres (k periodic directions, L in R), some 600 bytes per
// point triangulated: in the paper's 32 R box, 9x (periodic x, y) or 27x (triply periodic:
// 0.07 GB for 4096 spheres), 81x or 729x (2 GB) if retries reach 128 R. Without a limit,
// --padding 1000 ran for over two minutes on 512 spheres, and --padding 1e15 overflowed the
// count of images and ended with exit code 0.
constexpr double kMaxPaddingOverRadius = 32.0;
// A retry pads to at least kRetryPaddingMargin times the widest padding a pore asked for: the
// relative margin 1e-4 lies far above the rounding of the circumradius (~1e-15) and far below
// a layer of images, so the pore surely fits next time at no visible cost.
constexpr double kRetryPaddingMargin = 1.0001;
// A retry grows the padding by at least kMinPaddingGrowth: a pore asking for barely more than
// the current padding would otherwise lead to near-identical retries, while 1.25 adds at least
// one radius of images to the 4 R padding (the retry cap of 16 R stays).
constexpr double kMinPaddingGrowth = 1.25;
// Room reserved for the pores kept in the selection: the primary share of the Delaunay cells
// (all cells x primary centres / all centres) plus kKeptPoresHeadroom (2 %), the spread of that
// share between the image layers, so the list is almost never reallocated.
constexpr double kKeptPoresHeadroom = 1.02;

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

// A dump with both a radius and a diameter column is refused when |diameter - 2 radius| exceeds
// kRadiusDiameterTolerance times the diameter. Each column printed with 6 significant digits
// (LAMMPS's default %g) is off by up to 5e-6 relative, so the two can disagree by up to 1e-5;
// twice that is still far below a real mismatch (a column written from another variable).
constexpr double kRadiusDiameterTolerance = 2e-5;

// A centre is outside a non-periodic box side when it lies beyond the bound by more than
// kBoxTolerance times the box length (room for the rounding of printed bounds only).
constexpr double kBoxTolerance = 1e-9;

// ---- where the packing is (the default selection; doc/tapmc-pores.rst, "Selection") ----------
// z is the vertical. Along a non-periodic z the packing lies on a floor (default: the lowest
// sphere bottom, min z_i - R, which is the floor plane for a packing resting on it whatever the
// box bounds) and ends at a free surface of height h_s: the mean, over columns
// kSurfaceColumnWidth R wide tiling the horizontal extent, of the highest sphere top z_i + R in
// the column (empty columns skipped). This is the surface height of compute stereo/profile
// (doc/compute_stereo_profile.rst): columns one diameter wide each hold about one sphere of the
// top layer, so h_s is the mean height of the top layer, and a stray sphere above the surface
// moves it by its excess height over the number of columns only.
constexpr double kSurfaceColumnWidth = 2.0;

// ---- statistics defaults --------------------------------------------------------------------
// Pores closer than kDefaultWallGap * R to a side wall or to the floor are left out of the
// statistics (paper, section IV.B: "at a distance 2R from the walls").
constexpr double kDefaultWallGap = 2.0;
// Pores closer than kDefaultSurfaceGap * R below the free surface h_s are left out: free-surface
// pores are larger. Measured on 4096-sphere packings of the TAPMC tapping example (R = 0.5,
// L = 32R, h_s = 29-30R, 0 to 30 taps, side walls and periodic): nu = <xi^3> in 1R slabs below
// h_s is 0.26-0.56, 0.14-0.20, 0.11-0.15, then 0.10-0.13 as in the bulk (0.115-0.122). Up to
// three radii are perturbed; 4R keeps one radius of margin for rougher surfaces.
constexpr double kDefaultSurfaceGap = 4.0;
// Histogram of xi on [0, kDefaultXiMax] with kDefaultBins bins; v = xi^3 on [0, kDefaultXiMax^3].
// 1.5 covers every interior pore of a hard-sphere packing (Bernal's largest hole: 0.645).
constexpr double kDefaultXiMax = 1.5;
// --xi-max above kMaxXiMax is a usage error: xi is a pore radius over R, and a pore of 1e3 R is
// no pore of a packing but open space; beyond about 5e102 the v = xi^3 histogram overflowed to
// inf (v_lo empty, n_v 0 with counts) without a word.
constexpr double kMaxXiMax = 1000.0;
// --xi-max below kMinXiMax is a usage error: the smallest pore of equal hard spheres is the
// tetrahedral hole, xi = 0.225, so a range below 1e-3 holds none; and near 1e-103 the v = xi^3
// range underflowed to [0, 0) (a histogram error naming neither the option nor its value).
constexpr double kMinXiMax = 1e-3;
constexpr std::size_t kDefaultBins = 150;
// --bins above kMaxBins is a usage error. 10^6 bins are 1.5e-6 wide at the default --xi-max, far
// below the ~1e-4 to which 6-digit dumps fix xi, and outnumber the pores of most frames (6.5
// per sphere), so more only costs memory: 32 bytes per bin (counts and sums of xi and v) for each
// histogram held, one per frame with --json, and a CSV row per bin (per frame with --frame-hist).
// Without a limit, --bins 1e15 ended in std::bad_alloc.
constexpr std::size_t kMaxBins = 1000000;
// Gotoh's P0(sigma) is tabulated on [0, kDefaultSigmaMax] with kDefaultSigmaBins steps.
constexpr double kDefaultSigmaMax = 2.0;
// --sigma-max above kMaxSigmaMax is a usage error: sigma R beyond the largest pore (kMaxXiMax R)
// is open space, and 1e308 made every grid step inf (written inf, and null in the JSON).
constexpr double kMaxSigmaMax = kMaxXiMax;
constexpr std::size_t kDefaultSigmaBins = 200;
// --sigma-steps above kMaxSigmaSteps is a usage error. 10^5 steps are 2e-5 R apart at the
// default --sigma-max, 500 times finer than the default grid and about the precision to which
// 6-digit dumps fix a distance; P0 is smooth, so more steps only cost: 8 bytes per step for each
// of the two P0 curves held (frame, total), 24 more with --json, a CSV row per step, and time, as
// each sample point counts in every step below its distance (~samples x steps / 2 increments per
// frame: 1 s for 10^5 points at 10^5 steps, 25 s at 10^6). Without a limit, --sigma-steps 1e15
// ended in std::bad_alloc.
constexpr std::size_t kMaxSigmaSteps = 100000;
// --p0 above kMaxP0Samples (random points per frame) is a usage error. The statistical error of
// the measured P0 is sqrt(P0 (1 - P0) / N) per frame: 5e-5 at 10^8 points, 500 times the 2e5
// per frame of the Fig. 9 command (tapmc.paper), and frames add up. Every point of a frame is
// held at once, 48 bytes each (its coordinates, its distance, its place in the query order):
// 4.8 GB at the limit (measured on 512 spheres), ~1.7 us each (3 min per frame). The query order
// numbers the points in 32 bits: the limit must stay below 2^32. Without a limit, --p0 1e15
// ended in std::bad_alloc.
constexpr std::size_t kMaxP0Samples = 100000000;

// ---- warnings (stderr, exit code still 0) ----------------------------------------------------
// Selected pores with xi >= --xi-max are counted in the normalisation of P(xi) but fall outside
// the histogram; above this fraction of the selection the histogram visibly misses probability
// (and interior pores of hard-sphere packings stay far below the default 1.5: such pores are
// hull cells of a free surface or a wall inside the selection).
constexpr double kOverflowWarningFraction = 0.01;
// Unresolved cells centred in the selection (empty spheres wider than the largest padding) are
// left out of the statistics, and they are the widest ones: leaving out more than this fraction
// of the selection (unresolved + selected pores) makes nu too small by a visible amount.
constexpr double kUnresolvedWarningFraction = 0.01;

}  // namespace config
}  // namespace pores
}  // namespace tapmc

#endif
