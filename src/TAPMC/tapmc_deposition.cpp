// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Sequential deposition with steepest descent (Jullien & Meakin 1987): the method and its engine.
//
// A dropped sphere (centre p, radius r) moves by steepest descent of its height under the
// non-penetration constraints of the spheres and planes it touches. Constraint k keeps
// f_k(p) >= 0 (sphere: |p - c_k| >= r + r_k; plane: n_k.p >= offset_k) with outward unit normal
// n_k. At a point, the descent direction d is the projection of gravity g = -e_z onto the cone
// {d : n_k.d >= 0 for every touching k}; the active set S (at most three independent normals)
// satisfies g + sum_S mu_k n_k = d with support forces mu_k >= 0 (the KKT conditions). Then:
//   S empty (or vertical walls only) -> vertical fall (a line),
//   S = {one sphere}                 -> roll on the great circle in the vertical plane,
//   S = {sphere, sphere or wall}     -> roll on the circle of points touching both,
//   d = 0, floor in S or |S| = 3     -> at rest (mu >= 0: gravity is balanced; for three spheres
//                                       this is the projection of p inside their triangle).
// Every path is a line or a circle p(t) = m + rho (cos t e1 + sin t e2); along a circle each
// contact function and each support force is K + P cos t + Q sin t, so the next event (a new
// contact, a support force reaching zero, the lowest point) is found in closed form.
//
// A vertical cylindrical container (the tube) adds its wall, one more constraint, and one more
// path, the roll on one sphere along the wall (tapmc_deposition_cylinder.cpp, whose header
// comment gives their geometry).
//
// The files of the deposition, by concern: tapmc_deposition_detail.h (the shared types: the
// 3-vector, the constraints and their contact functions, the paths and support forces, the contact
// set and descent, the random numbers of unstable equilibria; the declarations across files);
// tapmc_deposition_grid.h (the layered grid and the deposited spheres, inline);
// tapmc_deposition_roots.h/.cpp (the closed-form root finding of trigonometric polynomials);
// tapmc_deposition_paths.cpp (the descent at a point, the searches of the deposited spheres, the
// roll of one segment); tapmc_deposition_cylinder.cpp (the tube). This file: the engine (Impl)
// that drops a sphere with them, and the public functions of tapmc_deposition.h.
#include "tapmc_deposition.h"

#include "tapmc_checks.h"
#include "tapmc_contact.h"
#include "tapmc_defaults.h"
#include "tapmc_deposition_detail.h"
#include "tapmc_deposition_grid.h"
#include "tapmc_math.h"
#include "tapmc_random.h"
#include "tapmc_stereology.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tapmc {

// The internals shared by the deposition's files (tapmc_deposition_detail.h).
using namespace deposition_detail;

// ---------------------------------------------------------------------------------------------
// The engine: the deposited spheres, the equilibrium draws of the sphere being dropped, the
// counters, and the drop itself (segment after segment: contacts, descent, fall or roll).
struct SequentialDeposition::Impl {
  DepositedSpheres packing;
  EquilibriumDraws equilibrium_draws;  // of sphere packing.size(), the next to be inserted
  DepositionStats stats;

  void insert(Vec3 p, double r)
  {
    packing.insert(p, r);
    equilibrium_draws.start_sphere(packing.size());
  }

  // One attempt: fall and roll from (x, y) until at rest, or until the segment cap.
  DropOutcome descend(double x, double y, double r)
  {
    Vec3 p{x, y, 0.0};
    packing.wrap(p);
    p.z = start_height(packing, p.x, p.y, r);
    std::vector<Constraint> forced;
    std::vector<int> forced_idx;
    std::vector<Constraint> active;
    ContactSet contacts;  // storage reused by every segment of this drop
    for (int segment = 0; segment < kDepositionMaxSegments; ++segment) {
      ++stats.segments;
      collect_touching(packing, p, r, contacts);
      forced_idx.clear();
      for (const auto &f : forced)
        for (int k = 0; k < contacts.size(); ++k)
          if (contacts.constraints[k].same(f)) forced_idx.push_back(k);
      Descent descent = solve_descent(contacts, forced_idx);
      if (!descent.found && !forced_idx.empty()) {
        forced.clear();
        forced_idx.clear();
        descent = solve_descent(contacts, forced_idx);
      }
      if (!descent.found) break;  // no consistent active set: give up this attempt

      active.clear();
      bool on_floor = false;
      int n_spheres = 0;
      const Constraint *wall = nullptr, *sphere = nullptr;
      for (int a = 0; a < descent.n_active; ++a) {
        const Constraint &k = contacts.constraints[descent.active[a]];
        active.push_back(k);
        on_floor = on_floor || (!k.is_sphere && k.id == kFloorPlane);
        n_spheres += k.is_sphere ? 1 : 0;
        if (k.is_cylinder) wall = &k;
        if (k.is_sphere) sphere = &k;
      }
      // on one sphere along the cylinder wall (the only active pair that is not a circle)
      const bool wall_pair = wall != nullptr && n_spheres == 1 && descent.n_active == 2;
      const bool equilibrium = norm(descent.d) < kDepositionEquilibriumTolerance;
      if (equilibrium &&
          (on_floor || descent.n_active == 3 || (wall_pair && wall_pair_rests(p, *sphere, *wall))))
        return {p.x, p.y, p.z, on_floor ? RestingOn::Floor : RestingOn::Supports, segment + 1};
      if (equilibrium) ++stats.perturbations;
      // Only an equilibrium can be wedged: it was met, not left.
      const auto wedged_here = [&] {
        --stats.perturbations;
        ++stats.wedged;
        return DropOutcome{p.x, p.y, p.z, RestingOn::Supports, segment + 1};
      };

      Constraint hit{};
      bool entering_now = false;
      if (n_spheres == 0) {  // free fall (possibly sliding along vertical walls)
        const double t = fall_event(packing, p, r, active, hit, entering_now);
        p.z -= t;
        if (!(t > 0.0) && entering_now) {
          forced.push_back(hit);
        } else {
          forced.clear();
        }
        continue;
      }
      if (wall_pair) {
        ++stats.wall_rolls;
        WallRoll path;
        const RollSetup setup = make_wall_roll(p, *sphere, *wall, contacts, descent, equilibrium,
                                               equilibrium_draws, path);
        if (setup == RollSetup::Wedged) return wedged_here();
        if (setup == RollSetup::Degenerate) break;
        bool is_contact = false, support_lost = false;
        const double t = wall_roll_event(packing, path, r, active, hit, is_contact, entering_now,
                                         support_lost);
        if (is_contact && entering_now) {
          bool known = false;
          for (const auto &f : forced) known = known || f.same(hit);
          if (!known) forced.push_back(hit);
          continue;
        }
        forced.clear();
        p = path.at(t);
        // Heights set exactly where the event fixes them: level with c_j (its support is lost;
        // the next segment falls clear of it) or on the floor.
        if (support_lost) p.z = path.cj.z;
        if (is_contact && !hit.is_sphere) p.z = packing.domain.z_floor + r;
        continue;
      }
      // Roll on one sphere, or on two constraints with at least one sphere.
      Circle path;
      ForceLaw forces[2];
      const RollSetup setup =
          make_roll(p, contacts, descent, equilibrium, equilibrium_draws, path, forces);
      if (setup == RollSetup::Wedged) return wedged_here();
      if (setup == RollSetup::Degenerate) break;
      bool is_contact = false;
      const double t = roll_event(packing, path, r, active, forces, descent.n_active, hit,
                                  is_contact, entering_now);
      if (is_contact && entering_now) {
        bool known = false;
        for (const auto &f : forced) known = known || f.same(hit);
        if (!known) forced.push_back(hit);
        continue;  // same point, the entered constraint joins the active set
      }
      forced.clear();
      p = path.at(t);
      packing.wrap(p);
    }
    return {p.x, p.y, p.z, RestingOn::Unresolved, kDepositionMaxSegments};
  }
};

namespace {
void check_radius(double radius, double max_radius)
{
  if (!(radius > 0.0) || radius > max_radius)
    throw_outside_range("radius", radius, "(0, max_radius] = (0, " + number(max_radius) + "]");
}
}  // namespace

SequentialDeposition::SequentialDeposition(const DepositionDomain &domain, double max_radius,
                                           std::uint64_t seed, std::int64_t expected_spheres)
    : impl_(std::make_unique<Impl>())
{
  if (!(max_radius > 0.0) || !std::isfinite(max_radius))
    throw_outside_range("max_radius", max_radius, "(0, +inf)");
  const double diameter = 2.0 * max_radius;
  const std::string one_diameter = "[2 max_radius, +inf) = [" + number(diameter) + ", +inf)";
  if (!(domain.xhi - domain.xlo >= diameter))
    throw_outside_range("x extent xhi - xlo", domain.xhi - domain.xlo, one_diameter);
  if (!(domain.yhi - domain.ylo >= diameter))
    throw_outside_range("y extent yhi - ylo", domain.yhi - domain.ylo, one_diameter);
  if (!std::isfinite(domain.z_floor)) throw_outside_range("z_floor", domain.z_floor, "(finite)");
  if (domain.has_cylinder) check_cylinder(domain, max_radius);
  DepositedSpheres &packing = impl_->packing;
  packing.domain = domain;
  packing.r_max = max_radius;
  // Cells of one maximal contact distance (2 r_max): a fall visits 3 x 3 columns. A dense bed
  // has fewer columns than spheres; a sparse one gets wider columns (the searches read ranges).
  const long max_columns =
      expected_spheres > 0
          ? defaults::kGridCellsPerSphere * static_cast<long>(expected_spheres) +
                defaults::kGridMinCells
          : static_cast<long>(defaults::kGridMaxCellsPerSideAxis) *
                defaults::kGridMaxCellsPerSideAxis;
  packing.grid.setup(domain, diameter, max_columns);
  impl_->equilibrium_draws = EquilibriumDraws(seed);
}

SequentialDeposition::~SequentialDeposition() = default;
SequentialDeposition::SequentialDeposition(SequentialDeposition &&) noexcept = default;
SequentialDeposition &SequentialDeposition::operator=(SequentialDeposition &&) noexcept = default;

void SequentialDeposition::add_fixed_sphere(double x, double y, double z, double radius)
{
  check_radius(radius, impl_->packing.r_max);
  Vec3 p{x, y, z};
  impl_->packing.wrap(p);
  impl_->insert(p, radius);
}

DropOutcome SequentialDeposition::drop(double x, double y, double radius)
{
  Impl &s = *impl_;
  const DepositionDomain &domain = s.packing.domain;
  check_radius(radius, s.packing.r_max);
  const double slack = kDepositionSupportTolerance * radius;
  if (domain.has_cylinder) {
    const Cylinder &c = domain.cylinder;
    const double h = std::hypot(x - c.cx, y - c.cy);
    if (!(h <= c.radius - radius + slack))
      throw_outside_range("drop point distance from the cylinder axis", h,
                          "[0, cylinder radius - r] = [0, " + number(c.radius - radius) + "]");
  }
  if (!domain.periodic_x && (x < domain.xlo + radius - slack || x > domain.xhi - radius + slack))
    throw_outside_range("drop point x", x,
                        "[xlo + r, xhi - r] = [" + number(domain.xlo + radius) + ", " +
                            number(domain.xhi - radius) + "] (between walls)");
  if (!domain.periodic_y && (y < domain.ylo + radius - slack || y > domain.yhi - radius + slack))
    throw_outside_range("drop point y", y,
                        "[ylo + r, yhi - r] = [" + number(domain.ylo + radius) + ", " +
                            number(domain.yhi - radius) + "] (between walls)");
  DropOutcome out = s.descend(x, y, radius);
  if (out.rest != RestingOn::Unresolved) s.insert({out.x, out.y, out.z}, radius);
  return out;
}

std::size_t SequentialDeposition::size() const { return impl_->packing.size(); }
const double *SequentialDeposition::centre(std::size_t i) const
{
  return &impl_->packing.centres[3 * i];
}
double SequentialDeposition::radius(std::size_t i) const { return impl_->packing.radii[i]; }
const DepositionStats &SequentialDeposition::stats() const { return impl_->stats; }

// ---------------------------------------------------------------------------------------------
void validate(const PackingParams &params)
{
  if (params.n < 1 || params.n > std::numeric_limits<std::int32_t>::max() - 1)
    throw_outside_range("N", params.n, "[1, 2^31 - 2] (a number of spheres)");
  if (!(params.radius > 0.0) || !std::isfinite(params.radius))
    throw_outside_range("R", params.radius, "(0, +inf) (the mean sphere radius)");
  if (!(params.dispersity >= 0.0 && params.dispersity < 1.0))
    throw_outside_range("dispersity", params.dispersity,
                        "[0, 1) (radii uniform in [R(1 - W), R(1 + W)])");
  if (!(params.density > 0.0)) throw_outside_range("density", params.density, "(0, +inf)");
}

Packing deposit_packing(std::int64_t n, const RadiusDistribution &radii,
                        const DepositionDomain &domain, std::uint64_t seed)
{
  if (n < 0 || n > std::numeric_limits<std::int32_t>::max() - 1)
    throw_outside_range("n", n, "[0, 2^31 - 2]");
  if (!(radii.r_min > 0.0)) throw_outside_range("r_min", radii.r_min, "(0, +inf)");
  if (!(radii.r_max >= radii.r_min && std::isfinite(radii.r_max)))
    throw_outside_range("r_max", radii.r_max,
                        "[r_min, +inf) = [" + number(radii.r_min) + ", +inf)");
  SequentialDeposition engine(domain, radii.r_max, seed, n);
  Packing out;
  out.xyz.reserve(3 * static_cast<std::size_t>(n));
  out.radius.reserve(static_cast<std::size_t>(n));
  const double top_slack = kDepositionSupportTolerance * 2.0 * radii.r_max;
  std::int64_t redrops = 0, unresolved = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    // Sphere i's draws: its radius at position 0, the drop point of attempt a at position 1 + a.
    const CounterRandom draws(seed, RandomPurpose::kDepositionDrops, static_cast<std::uint64_t>(i));
    const double r = radii.is_monodisperse()
                         ? radii.r_min
                         : radii.r_min + (radii.r_max - radii.r_min) * draws.uniform(0);
    // Drop points: uniform over the box (periodic) or over [lo + r, hi - r] (walls).
    const double x_lo = domain.periodic_x ? domain.xlo : domain.xlo + r;
    const double x_span = domain.periodic_x ? domain.xhi - domain.xlo : domain.xhi - domain.xlo - 2.0 * r;
    const double y_lo = domain.periodic_y ? domain.ylo : domain.ylo + r;
    const double y_span = domain.periodic_y ? domain.yhi - domain.ylo : domain.yhi - domain.ylo - 2.0 * r;
    DropOutcome o{};
    for (int attempt = 0; attempt < defaults::kDepositionMaxAttempts; ++attempt) {
      const RandomBlock point = draws.block(1 + static_cast<std::uint64_t>(attempt));
      const double u = uniform_from_u64(join_u32(point[0], point[1]));
      const double v = uniform_from_u64(join_u32(point[2], point[3]));
      double x = x_lo + x_span * u, y = y_lo + y_span * v;
      if (domain.has_cylinder) {  // uniform on the disk of radius R_c - r about the axis
        const Cylinder &c = domain.cylinder;
        const double h = (c.radius - r) * std::sqrt(u), angle = kTwoPi * v;
        x = c.cx + h * std::cos(angle);
        y = c.cy + h * std::sin(angle);
      }
      o = engine.drop(x, y, r);
      if (o.rest != RestingOn::Unresolved) break;
      ++redrops;
    }
    if (o.rest == RestingOn::Unresolved) {
      engine.add_fixed_sphere(o.x, o.y, o.z, r);
      ++unresolved;
    }
    if (o.z + r > domain.z_top + top_slack)
      throw std::runtime_error("sphere " + std::to_string(i) + " of " + std::to_string(n) +
                               " rests with its top at z = " + number(o.z + r) +
                               ", above the top limit z_top = " + number(domain.z_top) +
                               ": the domain cannot hold the spheres");
    out.xyz.insert(out.xyz.end(), {o.x, o.y, o.z});
    out.radius.push_back(r);
  }
  out.stats = engine.stats();
  out.stats.redrops = redrops;
  out.stats.unresolved = unresolved;
  return out;
}

void bulk_window(const Packing &packing, const DepositionDomain &domain, double margin,
                 double &z0, double &z1)
{
  double mean = 0.0;
  const std::size_t n = packing.radius.size();
  for (std::size_t i = 0; i < n; ++i) mean += packing.xyz[3 * i + 2] - domain.z_floor;
  mean = n ? mean / static_cast<double>(n) : 0.0;
  z0 = domain.z_floor + margin;
  z1 = domain.z_floor + 2.0 * mean - margin;
}

double slab_volume_fraction(const Packing &packing, const DepositionDomain &domain, double z0,
                            double z1)
{
  const stereo::Spheres spheres{packing.xyz.data(), packing.radius.data(), 0.0, nullptr,
                                static_cast<int>(packing.radius.size())};
  // in a tube every sphere lies inside the disk, whose area normalises the slab
  const double area = domain.has_cylinder
                          ? kPi * domain.cylinder.radius * domain.cylinder.radius
                          : (domain.xhi - domain.xlo) * (domain.yhi - domain.ylo);
  return stereo::horizontal_slab_volume(spheres, z0, z1) / (area * (z1 - z0));
}

}  // namespace tapmc
