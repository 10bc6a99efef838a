// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Test helpers for the pore tool: exact lattices, random hard-sphere packings, periodic distances.
#ifndef TAPMC_PORES_TEST_UTIL_H
#define TAPMC_PORES_TEST_UTIL_H

#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "tapmc_pores/dump_reader.h"

namespace pores_test {

struct Packing {
  tapmc::pores::Box box;
  std::vector<double> xyz;
  std::vector<std::int64_t> ids;
  double radius = 0.5;
  std::size_t size() const { return ids.size(); }
  void add(double x, double y, double z) {
    xyz.insert(xyz.end(), {x, y, z});
    ids.push_back(static_cast<std::int64_t>(ids.size()) + 1);
  }
};

// Lattices at contact in a triply periodic box. `spacing_unit` scales the coordinates: with
// integer-friendly units (FCC: R = 1/sqrt(2), cube edge 2) every coordinate is exact.
inline Packing fcc(int n, double radius) {
  Packing p;
  p.radius = radius;
  const double a = 2.0 * radius * std::sqrt(2.0);
  const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        for (const auto& b : basis) p.add((i + b[0]) * a, (j + b[1]) * a, (k + b[2]) * a);
  p.box.lo = {0, 0, 0};
  p.box.hi = {n * a, n * a, n * a};
  return p;
}

inline Packing simple_cubic(int n, double radius) {
  Packing p;
  p.radius = radius;
  const double a = 2.0 * radius;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) p.add(i * a, j * a, k * a);
  p.box.lo = {0, 0, 0};
  p.box.hi = {n * a, n * a, n * a};
  return p;
}

// HCP (ABAB stacking along z) in an orthogonal box: nx x ny rectangular in-plane cells of two
// spheres each, nz layers (nz even).
inline Packing hcp(int nx, int ny, int nz, double radius) {
  Packing p;
  p.radius = radius;
  const double d = 2.0 * radius, row = d * std::sqrt(3.0), layer = d * std::sqrt(2.0 / 3.0);
  for (int k = 0; k < nz; ++k) {
    const double ox = (k % 2) ? 0.5 * d : 0.0, oy = (k % 2) ? d / (2.0 * std::sqrt(3.0)) : 0.0;
    for (int i = 0; i < nx; ++i)
      for (int j = 0; j < ny; ++j) {
        p.add(i * d + ox, j * row + oy, k * layer);
        p.add(i * d + 0.5 * d + ox, j * row + 0.5 * row + oy, k * layer);
      }
  }
  p.box.lo = {0, 0, 0};
  p.box.hi = {nx * d, ny * row, nz * layer};
  return p;
}

inline double wrap(double x, double lo, double length) {
  double t = (x - lo) / length;
  t -= std::floor(t);
  double w = lo + t * length;
  return w >= lo + length ? lo : w;
}

// Uniform perturbation of every coordinate by up to `amplitude`, wrapped back into the box.
inline void perturb(Packing& p, double amplitude, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  for (std::size_t i = 0; i < p.xyz.size(); ++i) {
    const int d = static_cast<int>(i % 3);
    p.xyz[i] = wrap(p.xyz[i] + u(engine), p.box.lo[d], p.box.length(d));
  }
}

// Minimum-image separation vector component along d.
inline double separation(const tapmc::pores::Box& box, int d, double a, double b) {
  double s = a - b;
  if (box.periodic[d]) s -= box.length(d) * std::round(s / box.length(d));
  return s;
}

inline double distance(const tapmc::pores::Box& box, const double* a, const double* b) {
  double sum = 0;
  for (int d = 0; d < 3; ++d) sum += std::pow(separation(box, d, a[d], b[d]), 2);
  return std::sqrt(sum);
}

// Random sequential addition of n non-overlapping spheres (brute force, small n): a random
// hard-sphere packing in general position. Non-periodic directions keep centres R from the faces.
inline Packing random_packing(std::size_t n, double side, std::array<bool, 3> periodic, std::uint64_t seed,
                              double radius = 0.5) {
  Packing p;
  p.radius = radius;
  p.box.lo = {0, 0, 0};
  p.box.hi = {side, side, side};
  p.box.periodic = periodic;
  std::mt19937_64 engine(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::size_t attempts = 0;
  while (p.size() < n) {
    if (++attempts > 1000000 * n) break;
    double c[3];
    for (int d = 0; d < 3; ++d)
      c[d] = periodic[d] ? side * u(engine) : radius + (side - 2 * radius) * u(engine);
    bool free = true;
    for (std::size_t j = 0; j < p.size() && free; ++j) free = distance(p.box, c, &p.xyz[3 * j]) >= 2.0 * radius;
    if (free) p.add(c[0], c[1], c[2]);
  }
  return p;
}

}  // namespace pores_test

#endif
