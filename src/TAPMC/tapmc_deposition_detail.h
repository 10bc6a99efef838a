// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The sequential deposition's internals shared by its files (tapmc_deposition*.cpp), not part of
// the public tapmc_deposition.h: the 3-vector, the constraints (spheres, planes, the cylinder
// wall) and their contact functions, the paths (a circle, the roll along the wall) and the laws
// of their support forces, the contact set and the descent at a point, the random numbers of
// unstable equilibria, and the functions that one file defines and another calls. Everything
// small and hot is inline here.
#ifndef TAPMC_DEPOSITION_DETAIL_H
#define TAPMC_DEPOSITION_DETAIL_H

#include "tapmc_defaults.h"
#include "tapmc_deposition.h"
#include "tapmc_math.h"
#include "tapmc_random.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace tapmc {
namespace deposition_detail {

using defaults::kDepositionAngleTolerance;
using defaults::kDepositionEquilibriumTolerance;
using defaults::kDepositionForceTolerance;
using defaults::kDepositionGrazingDepth;
using defaults::kDepositionMaxSegments;
using defaults::kDepositionSupportTolerance;

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Vec3 {
  double x, y, z;
};
inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b)
{
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 unit(Vec3 a) { return (1.0 / norm(a)) * a; }

const Vec3 kGravity{0.0, 0.0, -1.0};

inline double wrap_angle(double t)
{
  t = std::fmod(t, kTwoPi);
  return t < 0.0 ? t + kTwoPi : t;
}

inline std::int64_t floor_div(std::int64_t a, std::int64_t b)
{
  std::int64_t q = a / b;
  if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
  return q;
}

struct Constraint {
  bool is_sphere;
  std::int64_t id;   // sphere index, or a PlaneId (tapmc_contact.h)
  int image_x = 0;   // periodic image of a sphere (box lengths added to its stored centre)
  int image_y = 0;
  Vec3 c;            // sphere: image centre; plane: unit normal pointing into the allowed side;
                     // cylinder: a point of its axis at z = 0
  double dist;       // sphere: contact distance r + r_k; plane: offset (allowed: n.p >= offset);
                     // cylinder: the largest distance R_c - r of the centre from the axis
  bool is_cylinder = false;  // the cylinder wall (is_sphere false, id kCylinderWall)
  bool same(const Constraint &o) const
  {
    return is_sphere == o.is_sphere && id == o.id && image_x == o.image_x && image_y == o.image_y;
  }
};

// The id of the cylinder wall: not a PlaneId (tapmc_contact.h numbers the flat planes only), so
// kept far below them.
constexpr std::int64_t kCylinderWall = -1000;

inline double axis_distance(const Constraint &k, Vec3 p)
{
  return std::hypot(p.x - k.c.x, p.y - k.c.y);
}
inline double gap_of(const Constraint &k, Vec3 p)
{
  if (k.is_cylinder) return k.dist - axis_distance(k, p);
  return k.is_sphere ? norm(p - k.c) - k.dist : dot(k.c, p) - k.dist;
}
inline Vec3 normal_of(const Constraint &k, Vec3 p)
{
  if (k.is_cylinder) {
    const double h = axis_distance(k, p);
    return {(k.c.x - p.x) / h, (k.c.y - p.y) / h, 0.0};
  }
  return k.is_sphere ? unit(p - k.c) : k.c;
}

// A trigonometric polynomial of degree 2: a0 + a1 cos t + b1 sin t + a2 cos 2t + b2 sin 2t.
struct Trig2 {
  double a0 = 0, a1 = 0, b1 = 0, a2 = 0, b2 = 0;
  // (K + P cos t + Q sin t)^2
  static Trig2 square(double K, double P, double Q)
  {
    return {K * K + 0.5 * (P * P + Q * Q), 2.0 * K * P, 2.0 * K * Q, 0.5 * (P * P - Q * Q),
            P * Q};
  }
  // A lower bound of its minimum (each harmonic at its own minimum).
  double lower_bound() const { return a0 - std::hypot(a1, b1) - std::hypot(a2, b2); }
};

// A roll: p(t) = m + rho (cos t e1 + sin t e2), t in [0, t_end]; e2 is the initial direction.
struct Circle {
  Vec3 m, e1, e2;
  double rho;
  double t_end;
  Vec3 at(double t) const { return m + rho * (std::cos(t) * e1 + std::sin(t) * e2); }
};

// Support force of an active constraint along a roll: mu(t) = K + P cos t + Q sin t.
struct ForceLaw {
  double K, P, Q;
};

// The constraints touching the dropped sphere at one point and their unit normals there
// (normals[k] belongs to constraints[k]). Every step that reads contacts takes this set and
// considers all of it, as candidate supports and as obstacles, with no size limit: an ignored
// touching constraint would let the descent enter it. A sphere touches at most 12 equal spheres,
// but a large sphere among small ones (polydisperse radii) can touch more. The set is bounded by
// geometry and a generic drop touches at most three constraints at once, so the subset search
// of solve_descent stays cheap.
struct ContactSet {
  std::vector<Constraint> constraints;
  std::vector<Vec3> normals;
  int size() const { return static_cast<int>(constraints.size()); }
};

// The descent at a point: active set (indices into a ContactSet) and direction.
struct Descent {
  bool found = false;
  int n_active = 0;
  int active[3] = {-1, -1, -1};
  Vec3 d{0, 0, 0};
};

// How a roll starts: a path (Ok), none (Degenerate: the attempt is given up), or none because
// every way is blocked (Wedged: at rest).
enum class RollSetup { Ok, Degenerate, Wedged };

// ---------------------------------------------------------------------------------------------
// The random numbers that leave unstable equilibria: the draws of sphere k (the k-th inserted)
// are the stream k of purpose kDepositionEquilibria under the seed, numbered from 0 and
// continued over every drop of that sphere until it is inserted, so a drop is reproducible.
class EquilibriumDraws {
 public:
  explicit EquilibriumDraws(std::uint64_t seed = 0) : seed_(seed) {}
  void start_sphere(std::uint64_t sphere)
  {
    sphere_ = sphere;
    next_ = 0;
  }
  double uniform()
  {
    return CounterRandom(seed_, RandomPurpose::kDepositionEquilibria, sphere_).uniform(next_++);
  }
  Vec3 horizontal_direction()
  {
    const double angle = kTwoPi * uniform();
    return {std::cos(angle), std::sin(angle), 0.0};
  }
  bool sign() { return uniform() < 0.5; }

 private:
  std::uint64_t seed_, sphere_ = 0, next_ = 0;
};

// ---------------------------------------------------------------------------------------------
// The roll on one sphere j along the cylinder wall (the active set {j, wall}). The centre keeps
// its distance rho from the axis and its distance D from c_j (their values at the start, equal
// to R_c - r and r + r_j within the contact tolerance, so the path never deepens an overlap), and
// its azimuth turns by t from u0 towards v0:
//   p_xy(t) = A + rho (cos t u0 + sin t v0),  p_z(t) = z_j + Z(t),  Z^2 = D^2 - h2(t),
// h2 = |p_xy - c_j,xy|^2 = hK + hP cos t + hQ sin t. The descent turns away from c_j (h2 grows,
// Z falls) down to the lowest point, where h2 is largest.
struct WallRoll {
  Vec3 axis;    // (A_x, A_y, 0)
  Vec3 u0, v0;  // horizontal unit vectors: the start's radial direction and the way it turns
  double rho;
  Vec3 cj;      // centre of the supporting sphere
  double D2;
  double hK, hP, hQ;
  double t_end;  // the lowest point

  Vec3 xy(double t) const
  {
    return axis + rho * (std::cos(t) * u0 + std::sin(t) * v0);
  }
  Vec3 at(double t) const
  {
    Vec3 q = xy(t);
    const double dx = q.x - cj.x, dy = q.y - cj.y;
    q.z = cj.z + std::sqrt(std::max(0.0, D2 - (dx * dx + dy * dy)));
    return q;
  }
};

// ---------------------------------------------------------------------------------------------
// The functions that one file of the deposition defines and another calls.

struct DepositedSpheres;  // tapmc_deposition_grid.h

// The descent at a point (tapmc_deposition_paths.cpp).
Descent solve_descent(const ContactSet &contacts, const std::vector<int> &forced);
bool blocked(Vec3 dir, const ContactSet &contacts, const Descent &descent);

// The searches of the deposited spheres (tapmc_deposition_paths.cpp).
void collect_touching(const DepositedSpheres &packing, Vec3 p, double r, ContactSet &contacts);
double start_height(const DepositedSpheres &packing, double x, double y, double r);
double fall_event(const DepositedSpheres &packing, Vec3 p, double r,
                  const std::vector<Constraint> &active, Constraint &hit, bool &entering_now);
double roll_event(const DepositedSpheres &packing, const Circle &path, double r,
                  const std::vector<Constraint> &active, const ForceLaw *forces, int n_forces,
                  Constraint &hit, bool &is_contact, bool &entering_now);

// The roll of one segment (tapmc_deposition_paths.cpp).
RollSetup make_roll(Vec3 p, const ContactSet &contacts, const Descent &descent, bool equilibrium,
                    EquilibriumDraws &draws, Circle &path, ForceLaw *forces);

// The cylinder wall (tapmc_deposition_cylinder.cpp).
double circle_wall_entry(const Circle &path, const Constraint &wall, double r, double t_max,
                         bool &now);
bool wall_pair_rests(Vec3 p, const Constraint &j, const Constraint &wall);
RollSetup make_wall_roll(Vec3 p, const Constraint &j, const Constraint &wall,
                         const ContactSet &contacts, const Descent &descent, bool equilibrium,
                         EquilibriumDraws &draws, WallRoll &path);
double wall_roll_event(const DepositedSpheres &packing, const WallRoll &path, double r,
                       const std::vector<Constraint> &active, Constraint &hit, bool &is_contact,
                       bool &entering_now, bool &support_lost);
void check_cylinder(const DepositionDomain &domain, double max_radius);

}  // namespace deposition_detail
}  // namespace tapmc

#endif
