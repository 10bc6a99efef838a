// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The --help text of tapmc-pores (every option, its default and range; doc/tapmc-pores.rst
// says the same, a test keeps them one story).
#include "tapmc_pores/usage.h"

namespace tapmc {
namespace pores {

const char* usage_text() {
  return R"(Usage: tapmc-pores [options] DUMP [DUMP ...]

Pore-size analysis of LAMMPS text dumps (dump custom / dump atom, plain or gzip; any number of
frames and files). Every Voronoi vertex of the sphere centres is a pore; its size is
xi = r/R, r the radius of the empty sphere tangent to the four spheres of its Delaunay
tetrahedron (Philippe & Bideau, section IV.B). Periodicity and box come from each frame's header.

Input
  -r, --radius R       sphere radius; needed when the dump has no radius/diameter column
  --boundary XYZ       override the periodicity, e.g. ppf (p: periodic, f: not periodic)
  --skip N             skip the first N frames of every file (default 0)
  --every K            analyse every K-th frame after that (default 1)
  --max-frames M       stop after M analysed frames in total (default: all)
Selection of pores (by the position of the pore centre; z is the vertical)
  Default: the packing itself, found in every frame. Periodic directions are used whole.
  Non-periodic x, y: 2R inside the outermost sphere surfaces (the side walls). Non-periodic z:
  from 2R above the floor to 4R below the free surface h_s, the mean over columns 2R wide of
  the highest sphere top (as compute stereo/profile defines it).
  --floor Z0           height of the floor (default: the lowest sphere bottom, min z - R)
  --x LO:HI --y LO:HI --z LO:HI
                       selection bounds; either side may be left empty (default for that side)
  --radii              read those bounds as multiples of R above the lower reference: the floor
                       along z, the side wall or the periodic box face along x and y
  --wall-gap G         default distance from the side walls and the floor, in R (default 2)
  --surface-gap G      default distance below the free surface h_s, in R (default 4)
  --paper-window       the paper's statistics box (section IV.B): 2R from the side walls,
                       height 18R from 2R above the floor (same as --radii --z 2:20)
  --cylinder CX:CY:RC  a vertical tube of radius RC about (CX, CY) (region cylinder z): x and y
                       of the selection are the disk of radius RC - 2R (--wall-gap) about the
                       axis; needs non-periodic x and y; not with --x, --y
Histograms
  --bins N             bins of xi on [0, XI_MAX) and of v = xi^3 on [0, XI_MAX^3) (default 150,
                       at most 1000000)
  --xi-max X           (default 1.5, from 0.001 to 1000: a pore radius over R)
Outputs (files PREFIX.*)
  -o, --output PREFIX  default "pores". Always: PREFIX.hist.csv (over all analysed frames: P(xi),
                       xi^3 P(xi), the number density n_v(v) of v = xi^3 (integral 1) and the
                       paper's volume distribution rho_v(v) = v n_v(v) = (xi/3) P(xi) (integral
                       nu)) and PREFIX.frames.csv (one line per frame: counts, nu)
  --frame-hist         also PREFIX.frame_hist.csv, the histograms of every frame
  --pores              also PREFIX.pores.csv, every pore (centre, xi, four atom ids, selected)
  --json               also PREFIX.json with the same content for Python
  --p0 N               sample N random points per frame in the selection (at most 100000000):
                       PREFIX.p0.csv with the measured P0(sigma) next to Gotoh's Percus-Yevick P0
                       (eq. 8 for sigma <= 1; for sigma > 1 the scaled-particle form that
                       replaces the printed eq. 9, see doc/tapmc-pores.rst), e.g. --p0 100000
  --sigma-max S        P0 grid 0..S (default 2) in --sigma-steps K steps (default 200,
                       at most 100000)
  --seed S             seed of the P0 sampling (default 1)
Tolerances
  --overlap-tol T      spheres closer than 2R (1 - T) are refused (default 1e-3); overlapping
                       inputs such as DEM dumps need T above their deepest overlap
  --merge-tol T        circumcentres closer than T R are one pore (default 1e-8, or 10 times
                       the rounding of the dump's largest coordinate over R when coarser;
                       e.g. 1e-4 for %g coordinates below 10 with R = 0.5)
  --padding P          periodic image padding in R (default 4, at least 2, at most 32; grown automatically)
Other
  -q, --quiet          no progress lines on stderr (warnings and errors still)
  -h, --help           this text
  --version            print "tapmc-pores VERSION" and exit

Outputs are written only when every frame was analysed; warnings (stderr, exit code 0) flag a
selection without pores, with unresolved or out-of-range pores, or reaching the free surface.
Exit codes: 0 success; 2 usage error (as for tapmc-paper; the message points to --help) or bad
input (the message names file, frame and line), nothing written; 3 internal error.
Documentation: doc/tapmc-pores.rst.
)";
}

}  // namespace pores
}  // namespace tapmc
