// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Every default and tolerance of the package, named, with the reason for its value.
// Docs (doc/*.rst) quote these values; change both together.
#ifndef TAPMC_DEFAULTS_H
#define TAPMC_DEFAULTS_H

#include "tapmc_math.h"

namespace tapmc {
namespace defaults {

// ---- contact geometry ------------------------------------------------------------------------
// Two spheres overlap when |r_ij| < R_i + R_j - tol, tol = kContactTolerance * (R_i + R_j).
// A tiny positive tolerance makes exact lattices at contact (built with rounding) legal input;
// 1e-10 of a diameter is far below any physical length of the model yet far above the
// 1e-16 relative rounding of the coordinates. The same relative tolerance applies to the floor
// and to side walls (measured against the sphere's diameter).
constexpr double kContactTolerance = 1e-10;
// Two styles' floors are one floor when they differ by at most this fraction of the larger
// |z0| (or of 1): the same number given twice is equal, a box face read back from a restart
// file may differ in its last bits.
constexpr double kFloorMatchTolerance = 1e-12;
// A style's radius keyword (fix mc/settle 'diameter', the computes' 'radius') and a sphere's
// per-atom radius, or two styles' keywords, are one radius within this fraction of it: the same
// number given twice ('diameter 1.0' and 'set group all diameter 1.0') is equal.
constexpr double kRadiusMatchTolerance = 1e-12;
// Coordinates far from the origin are resolved coarsely: a double at |x| is |x| 2^-52 from
// its neighbour, and a distance carries the rounding of both positions and of its arithmetic.
// The contact test is exact only where kCoordinateRoundingMargin such spacings stay below the
// tolerance of the smallest contact, kContactTolerance * 2 R_min: |x| up to 1.1e5 for spheres
// of diameter 1. Measured: create_packing with the floor at z = 1e6 leaves pairs 1.04e-10
// (relative) inside contact, which fix mc/settle then refuses; at z = 1e4 the taps are bit for
// bit those at z = 0. The styles refuse a box beyond the bound (lammps_box.h).
constexpr double kCoordinateRoundingMargin = 4.0;
// Largest contact tolerance the kernels accept: beyond a tenth of the contact distance the
// "hard" spheres would interpenetrate visibly and the packing fractions would be biased.
constexpr double kMaxContactTolerance = 0.1;

// ---- the tap: fix tapdilate (paper, section II) --------------------------------------------
// Largest eps. The paper taps with eps from 5e-3 to 0.15 (FIG. 2, eps^1/2 up to ~0.4 in FIG. 4);
// eps = 1 doubles every height above the floor, which already turns the redeposition into a
// fresh sedimentation of a gas. Larger values only cost time (the spheres fall freely for
// ~eps h / d_max sweeps) and, near the double range, lose atoms: refused.
constexpr double kMaxTapEps = 1.0;

// ---- trial moves (paper, section II) -------------------------------------------------------
// d_max = R/5: the paper's optimised step (too small freezes, too large is always rejected).
constexpr double kMaxStepOverRadius = 0.2;
// theta0 = pi/4: width of P(theta) = A exp(-(theta/theta0)^2) (eq. 1), the paper's value
// giving the maximal compaction rate.
constexpr double kThetaWidth = 0.25 * kPi;
// Largest theta0 accepted (radians). theta0 above pi/2 is allowed so that the flat limit of
// eq. 1 (theta uniform on [0, pi/2]; with theta_law solid, directions uniform on the downward
// hemisphere) can be tested; the paper stops at the truncation pi/2. At theta0 = 1e3 the law
// departs from that limit by 2.5e-6 of the density (1 - exp(-(pi/2 / theta0)^2)), beyond what
// any run resolves (1e10 draws resolve ~1e-5): larger values would add nothing, so they are
// refused as likely typos. The samplers stay exact and accept > 99 % of their proposals there.
constexpr double kThetaWidthMax = 1e3;
constexpr const char *kThetaWidthRange = "(0, 1000] (radians)";
// Exact theta sampler (tapmc_trial_move.h): a strip whose flat envelope would accept fewer than
// this fraction of its proposals uses the tangent exponential envelope instead (one log per
// proposal, acceptance >= 0.74 in the tail strips). Speed only: both envelopes are exact. At
// theta0 = pi/4 every strip stays flat (lowest flat acceptance 0.77).
constexpr double kThetaFlatMinAcceptance = 0.5;

// ---- stereology: compute stereo/profile (paper, sections III and IV.A) --------------------
// R below is the sphere radius (the group's mean radius for mixed radii).
// Phi_b is the mean of Phi(z) over [floor, floor + 4R]: the paper's bottom slab "between 0 and 4R".
constexpr double kBulkHeightOverRadius = 4.0;
// The perturbed-zone wall correction (paper ref. [20]) multiplies Phi(z) by 16/11 over the band
// [floor, floor + R], where a plane wall lowers the density of an otherwise unperturbed packing.
constexpr double kWallBandOverRadius = 1.0;
constexpr double kWallBandFactor = 16.0 / 11.0;
// <Phi^c> covers "approximately 90 % of the packing": z_top = floor + 0.9 (h_s - floor).
constexpr double kTopFraction = 0.9;
// h_s is the mean over columns of the highest sphere top: columns one diameter wide hold about
// one top-layer sphere each, so h_s follows the top layer and one stray sphere moves it by
// (its excess height) / (number of columns) only.
constexpr double kSurfaceColumnOverRadius = 2.0;
// A box that is a whole number of columns wide in one unit system (6 diameters of 0.2) is one
// within rounding in another (1.2 / 0.2 = 5.999...): the column count is floor(length / width
// + this), so that it, and h_s, do not depend on the last bit of the units.
constexpr double kColumnCountRounding = 1e-9;
// At most this many columns along x and along y: a column width far below the spheres' size
// (a typo such as 1e-4) would otherwise ask for a grid that cannot be allocated.
constexpr int kMaxColumnsPerAxis = 4096;
// Lateral zone of the transversal profiles: within 7R of the side walls ("roughly the wall
// effects range", paper section IV.A).
constexpr double kLateralWidthOverRadius = 7.0;
// Default z-window of vertical cuts starts 2R above the floor: it leaves out the first, wall-
// ordered layer, whose peaks would otherwise dominate transversal profiles.
constexpr double kVerticalWindowBottomOverRadius = 2.0;
// Default number of cut planes of the profile array (bins of about 0.3R for a 32R box).
constexpr int kProfilePlanes = 100;

// ---- a cylindrical container (tapmc_cylinder.h) -------------------------------------------
// The wall zone of a tube is the annulus within kLateralWidthOverRadius (7R) of the wall, the
// box's lateral zone of FIG. 8 bent round; the core is the disk inside it.
// The volume of a sphere inside a coaxial cylinder is the integral over z of a lens area,
// computed by Gauss-Legendre with this many nodes on each of at most six pieces between the
// kinks of the lens (tapmc_cylinder.cpp). Worst error against a 30-digit quadrature over 130
// random and adversarial cases (kinks at the poles and at the equator, within 1e-9 R of them):
// 3e-9 R^3 with 12 nodes, 8e-14 with 16, 1e-14 with 20, 2e-15 with 24; 20 costs about 120 lens
// areas per sphere and cylinder. The surface areas (the derivative in the cylinder's radius)
// use the same nodes: ~1e-15 R^2 in general, up to 4e-8 R^2 where a kink lies within 1e-7 R
// of a pole cut by the slab or of the equator (an arc behaves like a square root there).
constexpr int kCylinderQuadratureNodes = 20;
// Circular segments of a lens (tapmc_cylinder.cpp) take phi - sin(phi) (phi: the chord's full
// angle) from its Taylor series below this angle, where the difference loses more than two
// digits; its six terms through phi^13 are exact to 1e-18 relative at the threshold.
constexpr double kLensSeriesAngle = 0.25;

// ---- contacts: compute contacts and tapmc.contacts (tapmc_contacts.h) -----------------------
// Spheres i and j are in contact when |r_ij| <= (R_i + R_j)(1 + g + tol), a sphere and the floor
// when z_i - R_i - z0 <= (g + tol) 2 R_i, with tol = kContactsGapTolerance: the model's contact
// tolerance, so that g = 0 counts what the model takes as touching (exact lattices built with
// rounding, the analytic contacts of create_packing, within ~1e-15; pairs overlapping within the
// hard-sphere tolerance). It is far below any gap a user can resolve, and the gaps of a Monte
// Carlo packing are continuous: no pair of one sits within it of a chosen threshold.
constexpr double kContactsGapTolerance = kContactTolerance;
// Largest gap g: at g = 1 the centres of a "contact" are two contact distances apart; beyond
// that the count is a neighbour shell, not contacts (compute coord/atom counts neighbours within
// any cutoff). It also bounds the ghost shell the compute asks for, 2 R_max (1 + g).
constexpr double kContactsMaxGap = 1.0;
// Vector entry 3 of compute contacts is the fraction of spheres with fewer contacts than this:
// in three dimensions a frictionless sphere needs d + 1 = 4 contacts to be locally jammed (the
// usual definition of a rattler has fewer; under gravity a sphere can rest on 3).
constexpr int kContactsFewBelow = 4;
// The distribution P(Z) has rows Z = 0 .. kContactsMaxZ, the last one holding every Z >=
// kContactsMaxZ, so that its length is fixed (fix ave/time averages it row by row). 24 is twice
// the kissing number 12 of equal spheres: equal spheres stay below it at every gap up to
// sqrt(3) - 1 (FCC: 12 contacts up to sqrt(2) - 1, then 18); only larger gaps or very unequal
// radii reach the last row (vector entry 5 gives the largest Z).
constexpr int kContactsMaxZ = 24;

// ---- initial packing: create_packing, sequential deposition (Jullien & Meakin 1987) ---------
// A sphere or plane counts as touching (a possible support) when its gap is below this fraction
// of the contact distance: well above the ~1e-15 rounding of analytically computed contact
// points, well below any real gap. The tests identify supports with the same number.
constexpr double kDepositionSupportTolerance = 1e-9;
// Sign tolerance of the dimensionless support forces (gravity = 1) and of the slope of the
// descent direction against a touching normal: rounding sits near 1e-15.
constexpr double kDepositionForceTolerance = 1e-10;
// Below this length of the (unit-gravity) descent direction the sphere is at an equilibrium;
// an unstable one (on top of a sphere or of a ridge) is left in a random direction.
constexpr double kDepositionEquilibriumTolerance = 1e-10;
// Angle (radians) within which a touching constraint is taken as being left, not entered,
// along a roll: a contact grazed at 1e-16 relative gap is left within ~1e-8 rad.
constexpr double kDepositionAngleTolerance = 1e-7;
// Relative depth below which a constraint is taken as never entered along a path (of the roll's
// constraint functions f = K + P cos t + Q sin t; of the sphere diameter in the contact search):
// far below the contact tolerance, above the ~1e-13 rounding of f.
constexpr double kDepositionGrazingDepth = 1e-11;
// Two unit contact normals whose 1 - cos^2 of their angle is below this are taken as
// (anti)parallel: a one-contact set covers the two-contact descent, whose solve divides by it
// (far above the ~1e-16 rounding of the cosine).
constexpr double kDepositionParallelNormals = 1e-12;
// Three unit contact normals whose triple product is below this are taken as coplanar: no
// isolated three-contact rest point (the Cramer solve of the support forces divides by it).
constexpr double kDepositionCoplanarNormals = 1e-9;
// Determinant below which the 2x2 force balance of a roll on two contacts is taken as singular
// (the force solve divides by it): the roll is degenerate.
constexpr double kDepositionSingularRoll = 1e-12;
// A roll direction shorter than this (after removing its radial part) has no direction.
constexpr double kDepositionZeroLength = 1e-300;
// Random horizontal directions tried to leave an unstable equilibrium on one sphere (a direction
// that a touching contact blocks is rejected) before the free directions are found exactly
// (the edges of the cone the touching contacts leave free; none: the sphere is wedged at rest).
constexpr int kDepositionLeaveAttempts = 8;
// Samples of a contact function on each piece of a path between the roots that bound its sign
// changes (the cylinder wall's paths, tapmc_deposition_cylinder.cpp): one would give the sign;
// three also see the depth of a piece (the grazing rule) and guard against a root lost to
// rounding.
constexpr int kDepositionPieceSamples = 3;
// create_packing refuses at once a region whose volume could not hold the spheres even at
// random close packing (packing fraction ~0.64): a cheap, safe bound on what deposition can do.
constexpr double kRandomClosePacking = 0.64;
// Cap on path pieces per drop (a drop takes about 3 to 10): beyond it the drop restarts from a
// fresh random (x, y), so a degenerate geometry never loops forever.
constexpr int kDepositionMaxSegments = 1000;
// Drops per sphere before it is left where it stopped (non-overlapping) and counted unresolved.
constexpr int kDepositionMaxAttempts = 8;
// Bulk window of create_packing's reported packing fraction: this many mean radii away from the
// floor (wall layering decays within about 3 diameters) and from the mean surface height.
constexpr double kDepositionBulkMarginOverRadius = 6.0;
// Mass density given to created spheres (rmass = density * 4/3 pi r^3), as create_atoms does.
constexpr double kDepositionDensity = 1.0;
// create_packing deposits on rank 0 and broadcasts the spheres in pieces of this many (4 doubles
// each: 2 MiB), so that no other rank ever holds more than a piece of the packing.
constexpr long kPackingBroadcastSpheres = 65536;

// ---- redeposition: fix mc/settle and its kernel (tapmc_settle.h) -------------------------
// eta (no value in the paper): the redeposition stops when <Z> changes by less than eta
// (relative) between two checks one sweep apart. Run time against accuracy on the paper's PBC
// set-up (bench/tapping_front.py: N = 4096, Jullien-Meakin start, eps = 0.01, 80 taps, 5 seeds,
// d_max = R/5; deviations from eta = 1e-7 in paired standard errors; see bench/README.md):
//   eta    sweeps/tap  CPU s/tap  <Phi^c>(80)          dev.    <Z>(80)    dev.
//   1e-5      353        0.16     0.5811 +- 0.0007     -17.8   7.338      +26.3
//   1e-6     1262        0.54     0.5862 +- 0.0002     -12.6   7.280       +7.1
//   1e-7     3268        1.40     0.5894 +- 0.0004       -     7.251        -
// A 10 times longer check interval at eta = 1e-6 agrees with eta = 1e-7 within 1 SE in <Phi^c>
// (at 1.9 times its cost): 1e-7 is converged at this precision, 1e-6 leaves <Phi^c> 0.003 low
// (a third of the compaction of 200 taps). Right after deposition, 1e-3 to 1e-5 can stop after
// a single sweep (the first sweeps after a small tap change <Z> by less than 1e-5). The default
// is the accurate value; 1e-6 is the documented faster choice.
constexpr double kSettleEta = 1e-7;
// The eta test only counts once the packing no longer falls freely: fewer than this fraction of
// the interval's trials may have been accepted. A sphere with nothing below it accepts every
// trial (each move only goes down or sideways), so free fall means acceptance 1; a settled
// packing accepts ~1 % (the paper's set-up at eta = 1e-7, eps = 0.01). Without the rule, a
// packing lifted very high (huge eps) changes <Z> by less than eta per sweep while every sphere
// is still falling, and would be reported converged after one sweep.
constexpr double kSettleFreeFallAcceptance = 0.5;
// 'stop drift' (tapmc_stop_rule.h): the drift of <Z> per sweep is the mean of the per-sweep
// decrements over the last kSettleDriftWindow checks, and the redeposition stops when that mean
// plus kSettleDriftConfidence standard errors (from the scatter of the decrements in the window)
// is below eta <Z>. The single-check change of the paper's rule is a noisy estimate of the drift
// (standard deviation / mean of one sweep's decrement near eta = 4e-7: 0.66, 0.34, 0.21, 0.14
// at N = 1024, 4096, 16384, 32768), so that rule stops at the first lucky sweep: at eta = 1e-7
// after 1716, 3384, 5188, 6074 sweeps. The mean drift itself is intensive (it crosses 4e-7 after
// 3321, 3406, 3372, 3374 sweeps). 32 checks and 2 standard errors stopped every recorded tap
// within -5 % / +10 % of the crossing of the drift smoothed over 200 sweeps (N = 1024 to 32768,
// eta 1e-6 to 1e-7; -2 % / +6 % from N = 4096 on); 8 checks stopped N = 1024 up to 30 % early.
// The window lags by window/2 sweeps, negligible against the thousands a tap needs.
// (bench/stop_rule_scaling.py --trajectories; bench/README.md.)
constexpr long kSettleDriftWindow = 32;
constexpr double kSettleDriftConfidence = 2.0;
// Largest accepted window (bounds the memory of the estimate; far beyond a useful window).
constexpr long kSettleDriftWindowMax = 100000;
// Cap on sweeps per redeposition, 15 times what eta = 1e-7 needs after a tap of eps = 0.01: it
// only ends a run whose eta is unreachable; reaching it is reported in the fix's output vector
// and as a warning.
constexpr long kSettleMaxSweeps = 50000;
// Consecutive redepositions that accept no trial move before fix mc/settle warns that the
// packing only dilates: every trial move has a sideways part (theta > 0 almost surely), so
// spheres held on every side (a column one sphere diameter wide) never move, and each tap
// multiplies <Z> by 1 + eps. A small bed's first check can accept none by chance under 'stop
// change' (0.86^16, about 1 tap in 11 at 16 spheres, 14 % acceptance); five taps in a row,
// about 1 in 200 000. A settled bed of the paper's size accepts ~1 % of thousands of trials.
constexpr int kSettleNoMoveTaps = 5;

// ---- neighbour lists of the trial-move engine (tapmc_sphere_mover.cpp) --------------------
// Skin of the lists in units of the largest radius R_max: a pair is listed when its reference
// positions are within (R_i + R_j) + d_max + skin; a sphere's list is remade (locally) when it
// has moved skin/2 from its reference. The lists are exact, so the skin never changes the
// moves, only the speed: a wider skin means longer lists (more overlap tests per trial), a
// narrower one more local updates (bench/bench_mc_settle.cpp, bench/README.md).
constexpr double kListSkinOverRadius = 0.2;
// A list row holds its count and the neighbours' indices; rows are a multiple of this many
// ints wide (16 ints = one 64-byte cache line), widened by this step when a list outgrows its row.
constexpr int kListCapacityStep = 16;
// Room left in every row at a build beyond the longest list (local updates lengthen lists a
// little as the packing compacts; widening is O(N), so it should stay rare).
constexpr int kListSlack = 2;
// The trial loop prefetches a picked sphere's record and list row kOwnPrefetchAhead trials
// ahead, and the records of the first kNeighbourPrefetchCount entries of its list
// kNeighbourPrefetchAhead trials ahead: at large N (N = 262144: trials read 96 bytes a sphere,
// beyond the caches) each trial would otherwise wait for memory, and the overlap test exits at its first
// overlap after 2.2 entries on average (lists of 8.4; entries roughly in order of height, lowest
// first), so the other entries are rarely read. Measured on one core (M moves/s): N = 262144,
// neighbours none / all / first 4: 8.7 / 12.4-12.7 / 12.9-13.7; neighbours 2 / 4 / 8 / 16
// trials ahead 11.5 / 12.1 / 12.7 / 12.2; own data 16 trials ahead about 5 % faster than all 128
// of a batch at its draw (10 ahead: slower, 24 or 32: the same); N = 4096: no change (20.0),
// N = 32768: 18.2 without, 19.1 with the first 4.
constexpr int kOwnPrefetchAhead = 16;
constexpr int kNeighbourPrefetchAhead = 8;
constexpr int kNeighbourPrefetchCount = 4;

// ---- domain-decomposed redeposition (tapmc_decomposition.h, lammps_domain_settle.h) ----------
// Move margin e of the rounds' regions, in units of d_max: a sphere active in a round reaches its
// region's edge only by travelling e within that round (the trials rejected there are the
// scheme's one artefact). The narrowest sub-domain is 2 contact distances + 4 e (7.2 R at the
// default d_max = R/5), so 4 ranks along the paper's L = 32 R still fit.
constexpr double kDomainMoveMarginOverStep = 4.0;
// A sphere that has left its rank's sub-domain by more than e - d_max (3 d_max) along a split
// axis calls for a migration before its next round: until it migrates, its round's region ends
// e beyond the sub-domain face, a face that does not move between rebuilds (unlike the cuts,
// drawn anew each cycle), so its trials past the face would be refused cycle after cycle and,
// under the moves' downward bias, a bed split along z would hang on the face. Within e - d_max
// of its sub-domain a sphere has at least one whole step before the face's region edge.
constexpr double kDomainFaceSlackOverStep = kDomainMoveMarginOverStep - 1.0;
static_assert(kDomainFaceSlackOverStep >= 0.0, "the move margin must be at least one step");
// Ghost skin in units of R_max: atoms migrate and ghosts are rebuilt (exchange + borders) once a
// sphere has moved this far since the last build. Larger: more ghosts refreshed every round;
// smaller: more rebuilds. The ghost cutoff is 2 R_max + e + skin.
constexpr double kDomainGhostSkinOverRadius = 1.0;

// ---- cell grid of the kernel's neighbour searches (tapmc_cell_grid.h) -----------------------
// Cells are at least the search radius plus this relative rounding margin wide (relative to
// 2 R_max + the largest coordinate): positions, steps and wraps round at ~1e-16 of the
// coordinates, so the margin keeps every pair within the search radius in the 27-cell stencil,
// and it lies far below contact_tol, so it never changes which pairs count.
constexpr double kGridRoundingMargin = 1e-12;
// At most this many cells along x and along y (wider cells beyond): bounds the grid of a very
// wide box of few spheres.
constexpr int kGridMaxCellsPerSideAxis = 4096;
// At most kGridCellsPerSphere * N + kGridMinCells cells in all (the z axis gets the cells left):
// a floor far below the spheres must not allocate a huge empty grid, while a dense packing
// (a few spheres per cell) stays well inside the cap. The deposition's columns
// (tapmc_deposition_grid.h) follow the same two caps.
constexpr int kGridCellsPerSphere = 16;
constexpr int kGridMinCells = 4096;

}  // namespace defaults
}  // namespace tapmc

#endif
