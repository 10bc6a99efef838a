// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Contacts of a sphere packing within a gap: the coordination number of every sphere, its floor
// contact, and their distribution (compute contacts, doc/compute_contacts.rst; the same rule in
// Python, without the container wall: tools/python/tapmc/contacts.py).
//
// The gap g is relative to each pair's contact distance. Spheres i and j are in contact when
//     |r_ij| <= (R_i + R_j) (1 + g + tol),
// that is when the gap between their surfaces, |r_ij| - (R_i + R_j), is at most g (R_i + R_j)
// (plus the rounding tolerance tol = defaults::kContactsGapTolerance; overlapping pairs count).
// Sphere i touches the floor z = z0 when z_i - R_i - z0 <= (g + tol) 2 R_i: its surface gap to
// the plane is at most g times its diameter, the contact distance of two spheres of its size
// (the package measures plane gaps against the diameter: tapmc_contact.h). In a vertical
// cylindrical container of radius Rc (tapmc_cylinder.h) sphere i touches the wall when
//     (Rc - R_i) - |centre_i - axis| <= (g + tol) 2 R_i,
// the same rule with the radial gap of the wall (a sphere beyond the wall touches it).
//
// Counting is O(N): the spheres are binned in cells at least one largest pair reach wide
// (tapmc_cell_grid.h). Along a periodic axis a pair is taken at its nearest image, which needs
// the period to exceed two largest reaches; along the other axes there are no images, so a
// caller holding its own images (LAMMPS ghost atoms) passes them as spheres and makes no axis
// periodic.
#ifndef TAPMC_CONTACTS_H
#define TAPMC_CONTACTS_H

#include "tapmc_cell_grid.h"
#include "tapmc_cylinder.h"
#include "tapmc_defaults.h"

#include <cmath>

#include <vector>

namespace tapmc {
namespace contacts {

// What counts as a contact.
struct Settings {
  double gap = 0.0;      // g, relative to the contact distance R_i + R_j, in [0, kContactsMaxGap]
  bool floor = false;    // count the contact of each sphere with the floor plane
  double floor_z = 0.0;  // z0 of the floor plane
  bool wall = false;     // count the contact of each sphere with the wall of `cylinder`
  Cylinder cylinder;     // the container (vertical axis through cx, cy; its radius)
};
// Throws std::invalid_argument naming the setting, its value and the allowed range (with a
// wall, the cylinder's as tapmc::validate(Cylinder) names them).
void validate(const Settings &settings);

// 1 + g + tol: the contact distance R_i + R_j times this is the largest centre distance of a
// contact.
inline double reach_factor(double gap) { return 1.0 + gap + defaults::kContactsGapTolerance; }
// Whether a sphere of centre height z and radius r touches the floor (settings.floor set).
inline bool touches_floor(double z, double r, const Settings &settings)
{
  return (z - r) - settings.floor_z <= (settings.gap + defaults::kContactsGapTolerance) * (2.0 * r);
}
// Whether a sphere of centre (x, y) and radius r touches the wall (settings.wall set): its
// surface within g times its diameter of the wall, or beyond it. The radial gap is computed as
// the redeposition's (CylinderWall::gap), so a sphere the kernel left touching the wall at its
// reach (Rc - r) counts at g = 0.
inline bool touches_wall(double x, double y, double r, const Settings &settings)
{
  const double dx = x - settings.cylinder.cx, dy = y - settings.cylinder.cy;
  const double gap = (settings.cylinder.radius - r) - std::sqrt(dx * dx + dy * dy);
  return gap <= (settings.gap + defaults::kContactsGapTolerance) * (2.0 * r);
}

// Spheres read in place: sphere i is xyz[3 i .. 3 i + 2] with radius[i], or uniform_radius
// when radius is nullptr.
struct Spheres {
  const double *xyz = nullptr;
  const double *radius = nullptr;
  double uniform_radius = 0.0;
  int count = 0;
  double radius_of(int i) const { return radius ? radius[i] : uniform_radius; }
};

// Orthogonal box: lo and hi matter along the periodic axes only (a period hi - lo, the spheres
// taken modulo it); along the other axes the spheres may lie anywhere.
struct Box {
  double lo[3] = {0.0, 0.0, 0.0};
  double hi[3] = {1.0, 1.0, 1.0};
  bool periodic[3] = {false, false, false};
};

// The contacts of the first `centres` spheres with all spheres (the centres included, never a
// sphere with itself): counts[i] = number of spheres touching sphere i, plus 1 when the floor is
// counted and sphere i touches it, plus 1 when the wall is counted and sphere i touches it;
// on_floor[i] and on_wall[i] (optional, may be nullptr) = 1 when it touches the floor (the
// wall), else 0. Storage is reused between calls.
class Counter {
 public:
  // Throws std::invalid_argument for invalid settings, a radius <= 0 or not finite, a coordinate
  // that is not finite, a periodic axis with hi <= lo or a period not above two largest pair
  // reaches (a pair would meet more than one image of its partner), a wall with a periodic x or
  // y, or centres outside [0, spheres.count].
  void count(const Spheres &spheres, int centres, const Box &box, const Settings &settings,
             int *counts, unsigned char *on_floor = nullptr, unsigned char *on_wall = nullptr);

 private:
  CellGrid grid_;
  std::vector<double> xyz_, radius_;  // the spheres, wrapped into the box along periodic axes

  // Copies and checks the spheres; returns the largest radius.
  double load(const Spheres &spheres, const Box &box);
  // Bins the loaded spheres in cells at least one largest pair reach wide.
  void bin(const Box &box, double reach);
};

// The same, returning the counts (convenience for tests and one-off use).
std::vector<int> count_contacts(const Spheres &spheres, int centres, const Box &box,
                                const Settings &settings);

// ---- the distribution, summed over sets of spheres (ranks) then finished ----------------------
// Layout of the sums: accumulate() adds into sums[kNumSums] (combine ranks with a sum), the
// largest count is combined with a max.
enum Sum {
  kSumSpheres,   // spheres counted
  kSumContacts,  // sum of their counts Z
  kSumNone,      // spheres with Z = 0
  kSumFew,       // spheres with Z < kContactsFewBelow
  kSumFloor,     // spheres touching the floor
  kSumWall,      // spheres touching the wall
  kSumHistogram  // then kHistogramRows entries: spheres with Z = 0 .. kContactsMaxZ - 1, then
                 // with Z >= kContactsMaxZ
};
constexpr int kHistogramRows = defaults::kContactsMaxZ + 1;
constexpr int kNumSums = kSumHistogram + kHistogramRows;

// Adds the n spheres counts[index[k]] (index nullptr: counts[k]), with their floor and wall
// contacts on_floor and on_wall (each may be nullptr: none), to sums; returns their largest
// count (0 when n = 0).
int accumulate(const int *counts, const unsigned char *on_floor, const unsigned char *on_wall,
               const int *index, int n, double *sums);

struct Distribution {
  double spheres = 0.0;          // number of spheres
  double mean = 0.0;             // <Z>
  double fraction_none = 0.0;    // P(Z = 0)
  double fraction_few = 0.0;     // P(Z < kContactsFewBelow)
  double fraction_floor = 0.0;   // fraction touching the floor
  double fraction_wall = 0.0;    // fraction touching the wall
  int max = 0;                   // largest Z
  std::vector<double> fraction;  // P(Z) for Z = 0 .. kContactsMaxZ (last: Z >= kContactsMaxZ)
};
// Every fraction of the summed spheres; all 0 when there are none.
Distribution finish(const double *sums, int max_count);

}  // namespace contacts
}  // namespace tapmc

#endif
