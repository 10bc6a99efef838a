// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Scenes for the settle tests and benchmark: boxes, dilute lattices, settled beds, and an
// independent brute-force overlap oracle (all pairs, all periodic images).
#ifndef TAPMC_SETTLE_TEST_SCENES_H
#define TAPMC_SETTLE_TEST_SCENES_H

#include "tapmc_random.h"
#include "tapmc_settle.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace tapmc {
namespace test_scenes {

struct Scene {
  std::vector<double> xyz, radius;
  SettleBox box{};
  int size() const { return static_cast<int>(radius.size()); }
};

// Square box [0, L)^2 in x, y, floor at z = 0; periodic sides or walls on the box faces.
// A scene variant as failure messages name it: "PBC poly seed 3", "walls mono seed 1".
inline std::string variant_name(bool periodic, bool poly, std::uint64_t seed)
{
  return std::string(periodic ? "PBC" : "walls") + (poly ? " poly" : " mono") + " seed " +
         std::to_string(seed);
}

inline SettleBox make_box(double side, bool periodic, double height = 0.0)
{
  SettleBox b{};
  for (int d = 0; d < 2; ++d) {
    b.lo[d] = 0.0;
    b.hi[d] = side;
    b.periodic[d] = periodic;
    b.wall_lo[d] = b.wall_hi[d] = !periodic;
    b.wall_lo_pos[d] = 0.0;
    b.wall_hi_pos[d] = side;
  }
  b.lo[2] = 0.0;
  b.hi[2] = height;
  b.floor_z = 0.0;
  return b;
}

// n spheres on a loose square lattice (layers of k x k sites, spacing >= 2.2 R_max) above the
// floor, each jittered by up to 0.04 R_max. Radii: all r_max, or (poly) uniform in
// [r_min_fraction r_max, r_max]. No overlaps, no plane violations.
inline Scene dilute_lattice(int n, double side, double r_max, bool periodic, bool poly,
                            std::uint64_t seed, double r_min_fraction = 0.7)
{
  Scene s;
  s.box = make_box(side, periodic);
  const CounterRandom rng(seed, 0xC0FFEE);
  const int k = std::max(1, static_cast<int>(std::floor(side / (2.2 * r_max))));
  const double a = side / k, az = 2.2 * r_max;
  s.xyz.resize(3 * static_cast<std::size_t>(n));
  s.radius.resize(n);
  for (int i = 0; i < n; ++i) {
    const int layer = i / (k * k), ix = i % k, iy = (i / k) % k;
    const RandomBlock w = rng.block(static_cast<std::uint64_t>(i));
    const double jitter = 0.04 * r_max;
    s.xyz[3 * i + 0] = (ix + 0.5) * a + jitter * (2 * uniform_from_u32(w[0]) - 1);
    s.xyz[3 * i + 1] = (iy + 0.5) * a + jitter * (2 * uniform_from_u32(w[1]) - 1);
    s.xyz[3 * i + 2] = 1.1 * r_max + layer * az + jitter * (2 * uniform_from_u32(w[2]) - 1);
    s.radius[i] = poly ? r_max * (r_min_fraction + (1 - r_min_fraction) * uniform_from_u32(w[3]))
                       : r_max;
  }
  return s;
}

// n spheres at random positions (random sequential addition, no overlaps) filling the box up
// to the height giving a loose volume fraction phi_loose, above the floor. Radii as in
// dilute_lattice. A random start, unlike a lattice, settles into a random packing.
inline Scene random_loose(int n, double side, double r_max, bool periodic, bool poly,
                          std::uint64_t seed, double phi_loose = 0.3, double r_min_fraction = 0.7)
{
  Scene s;
  s.box = make_box(side, periodic);
  const CounterRandom rng(seed, 0xBADC0DE);
  s.radius.resize(n);
  double volume = 0.0;
  for (int i = 0; i < n; ++i) {
    const RandomBlock w = rng.block(static_cast<std::uint64_t>(i));
    s.radius[i] = poly ? r_max * (r_min_fraction + (1 - r_min_fraction) * uniform_from_u32(w[0]))
                       : r_max;
    volume += 4.18879020478639098 * s.radius[i] * s.radius[i] * s.radius[i];
  }
  const double height = volume / (side * side * phi_loose) + 2 * r_max;
  // Bins of side >= 2 r_max: candidates only need the 27 surrounding bins.
  const int nb = std::max(1, static_cast<int>(side / (2 * r_max)));
  const int nbz = std::max(1, static_cast<int>(height / (2 * r_max)));
  const double bw = side / nb, bz = height / nbz;
  std::vector<std::vector<int>> bins(static_cast<std::size_t>(nb) * nb * nbz);
  auto bin_of = [&](double v, double w, int cells) {
    return std::min(cells - 1, std::max(0, static_cast<int>(v / w)));
  };
  s.xyz.resize(3 * static_cast<std::size_t>(n));
  std::uint64_t attempt = 0;
  for (int i = 0; i < n; ++i) {
    const double r = s.radius[i];
    for (;;) {
      const RandomBlock w = rng.block((std::uint64_t{1} << 40) + attempt++);
      const double lo = periodic ? 0.0 : r, span = periodic ? side : side - 2 * r;
      const double x = lo + span * uniform_from_u32(w[0]), y = lo + span * uniform_from_u32(w[1]);
      const double z = r + (height - 2 * r) * uniform_from_u32(w[2]);
      const int bx = bin_of(x, bw, nb), by = bin_of(y, bw, nb), bzz = bin_of(z, bz, nbz);
      bool clash = false;
      for (int oz = -1; oz <= 1 && !clash; ++oz) {
        const int cz = bzz + oz;
        if (cz < 0 || cz >= nbz) continue;
        for (int oy = -1; oy <= 1 && !clash; ++oy)
          for (int ox = -1; ox <= 1 && !clash; ++ox) {
            int cx = bx + ox, cy = by + oy;
            if (periodic) {
              cx = (cx + nb) % nb;
              cy = (cy + nb) % nb;
            } else if (cx < 0 || cx >= nb || cy < 0 || cy >= nb) {
              continue;
            }
            for (int j : bins[(static_cast<std::size_t>(cz) * nb + cy) * nb + cx]) {
              double dx = s.xyz[3 * j] - x, dy = s.xyz[3 * j + 1] - y;
              if (periodic) {
                dx -= side * std::round(dx / side);
                dy -= side * std::round(dy / side);
              }
              const double dz = s.xyz[3 * j + 2] - z, c = 1.001 * (r + s.radius[j]);
              if (dx * dx + dy * dy + dz * dz < c * c) clash = true;
            }
          }
      }
      if (clash) continue;
      s.xyz[3 * i] = x;
      s.xyz[3 * i + 1] = y;
      s.xyz[3 * i + 2] = z;
      bins[(static_cast<std::size_t>(bzz) * nb + by) * nb + bx].push_back(i);
      break;
    }
  }
  return s;
}

// Parameters of the paper (d_max = R/5, theta0 = pi/4) for a sphere radius r.
inline SettleParams paper_params(double r, std::uint64_t seed, std::uint64_t stream,
                                 double eta = 1e-4, long max_checks = 100000)
{
  SettleParams p{};
  p.d_max = 0.2 * r;
  p.theta0 = 0.78539816339744830962;
  p.eta = eta;
  p.check_interval = 0;
  p.max_checks = max_checks;
  p.contact_tol = 1e-10;
  p.seed = seed;
  p.stream = stream;
  p.order = PickOrder::Random;
  return p;
}

// A settled bed: the random loose packing after `sweeps` sweeps of the redeposition (no eta stop),
// then until <Z> changes by less than eta_final per sweep.
inline Scene settled_bed(int n, double side, double r, bool periodic, bool poly,
                         std::uint64_t seed, long sweeps = 400, double eta_final = 1e-5)
{
  Scene s = random_loose(n, side, r, periodic, poly, seed);
  Settler settler;
  SettleParams p = paper_params(r, seed, 1, 1e-300, sweeps);
  settler.settle(s.xyz.data(), s.radius.data(), nullptr, n, s.box, p);
  p.eta = eta_final;
  p.max_checks = 100000;
  p.stream = 2;
  settler.settle(s.xyz.data(), s.radius.data(), nullptr, n, s.box, p);
  return s;
}

// Homothetic dilation of the heights about the floor (the tap: paper, section II).
inline void dilate(Scene &s, double eps)
{
  for (int i = 0; i < s.size(); ++i)
    s.xyz[3 * i + 2] = s.box.floor_z + (s.xyz[3 * i + 2] - s.box.floor_z) * (1.0 + eps);
}

// Volume fraction of the slab [z0, z1] (exact: integral of the sphere cross-sections).
inline double slab_fraction(const Scene &s, double z0, double z1)
{
  const double area = (s.box.hi[0] - s.box.lo[0]) * (s.box.hi[1] - s.box.lo[1]);
  double volume = 0.0;
  for (int i = 0; i < s.size(); ++i) {
    const double z = s.xyz[3 * i + 2], r = s.radius[i];
    const double a = std::max(z0, z - r), b = std::min(z1, z + r);
    if (b <= a) continue;
    // integral of pi (r^2 - (t - z)^2) dt from a to b
    auto f = [&](double t) { return r * r * (t - z) - (t - z) * (t - z) * (t - z) / 3.0; };
    volume += 3.14159265358979323846 * (f(b) - f(a));
  }
  return volume / (area * (z1 - z0));
}

// The spheres of `s` (a scene in a square box with walls) whose centres lie within
// cylinder_radius - r of the vertical axis through the middle of the box, in a vertical
// cylindrical container of that radius instead of the flat walls.
inline Scene in_cylinder(const Scene &s, double cylinder_radius)
{
  Scene out;
  out.box = s.box;
  for (int d = 0; d < 2; ++d) out.box.wall_lo[d] = out.box.wall_hi[d] = false;
  out.box.cylinder = true;
  out.box.cylinder_cx = 0.5 * (s.box.lo[0] + s.box.hi[0]);
  out.box.cylinder_cy = 0.5 * (s.box.lo[1] + s.box.hi[1]);
  out.box.cylinder_radius = cylinder_radius;
  for (int i = 0; i < s.size(); ++i) {
    const double dx = s.xyz[3 * i] - out.box.cylinder_cx, dy = s.xyz[3 * i + 1] - out.box.cylinder_cy;
    const double reach = cylinder_radius - s.radius[i];
    if (reach < 0 || dx * dx + dy * dy > reach * reach) continue;
    out.xyz.insert(out.xyz.end(), &s.xyz[3 * i], &s.xyz[3 * i] + 3);
    out.radius.push_back(s.radius[i]);
  }
  return out;
}

// Independent oracle: every pair and every periodic image (shifts -1, 0, +1 periods), plain
// arithmetic. Counts overlaps |r_ij| < (R_i + R_j)(1 - tol) and plane violations.
struct OracleReport {
  long pair_overlaps = 0, plane_violations = 0;
  double worst_gap = 0.0;  // most negative gap seen (0 if none)
};

inline OracleReport brute_force_check(const double *xyz, const double *radius, int n,
                                      const SettleBox &box, double tol)
{
  OracleReport rep;
  const double lx = box.hi[0] - box.lo[0], ly = box.hi[1] - box.lo[1];
  for (int i = 0; i < n; ++i) {
    const double r = radius[i];
    double gaps[5] = {xyz[3 * i + 2] - r - box.floor_z, 1e300, 1e300, 1e300, 1e300};
    for (int d = 0; d < 2; ++d) {
      if (box.wall_lo[d]) gaps[1 + 2 * d] = xyz[3 * i + d] - r - box.wall_lo_pos[d];
      if (box.wall_hi[d]) gaps[2 + 2 * d] = box.wall_hi_pos[d] - xyz[3 * i + d] - r;
    }
    for (double g : gaps)
      if (g < -tol * 2 * r) {
        ++rep.plane_violations;
        rep.worst_gap = std::min(rep.worst_gap, g);
      }
    if (box.cylinder) {
      // the radial gap with a square root (the kernels compare squares); 1e-12 of the radius
      // absorbs the rounding of a centre accepted exactly at its reach
      const double dx = xyz[3 * i] - box.cylinder_cx, dy = xyz[3 * i + 1] - box.cylinder_cy;
      const double g = (box.cylinder_radius - r) - std::sqrt(dx * dx + dy * dy);
      if (g < -tol * 2 * r - 1e-12 * box.cylinder_radius) {
        ++rep.plane_violations;
        rep.worst_gap = std::min(rep.worst_gap, g);
      }
    }
    for (int j = i + 1; j < n; ++j) {
      const double contact = (r + radius[j]) * (1 - tol);
      for (int sx = -1; sx <= 1; ++sx) {
        if (!box.periodic[0] && sx != 0) continue;
        for (int sy = -1; sy <= 1; ++sy) {
          if (!box.periodic[1] && sy != 0) continue;
          const double dx = xyz[3 * j] - xyz[3 * i] + sx * lx;
          const double dy = xyz[3 * j + 1] - xyz[3 * i + 1] + sy * ly;
          const double dz = xyz[3 * j + 2] - xyz[3 * i + 2];
          const double dist = std::sqrt(dx * dx + dy * dy + dz * dz);
          if (dist < contact) {
            ++rep.pair_overlaps;
            rep.worst_gap = std::min(rep.worst_gap, dist - (r + radius[j]));
          }
        }
      }
    }
  }
  return rep;
}

}  // namespace test_scenes
}  // namespace tapmc

#endif
