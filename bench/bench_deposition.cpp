// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Benchmark of the sequential deposition (create_packing's kernel): time for N = 4096, 1e5 and
// 1e6 monodisperse spheres at the paper's height (box side 32R sqrt(N / 4096), PBC), time per
// sphere to show the linear growth, and a naive O(N)-per-drop scan as the reference; then
// N = 4096 in a tube 10 diameters wide (radius 10R, the Knight / Nowak aspect ratio), whose
// curved wall adds the sphere-cylinder paths, against the box's time per sphere.
// Usage: bench_deposition [--quick]   (--quick skips N = 1e6)
#include "bench_common.h"
#include "tapmc_deposition.h"
#include "tapmc_math.h"
#include "tapmc_stereology.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

using tapmc_bench::cpu_model;
using tapmc_bench::median;
using tapmc_bench::seconds_since;

namespace {



tapmc::DepositionDomain domain_for(long n)
{
  tapmc::DepositionDomain d;
  const double side = 32.0 * std::sqrt(static_cast<double>(n) / 4096.0);
  d.xhi = side;
  d.yhi = side;
  return d;
}

// The least work of a deposition without a grid: each new sphere scans every earlier one once
// (here for its first vertical contact only). Returns the total time; `sink` keeps the result.
double naive_scan_time(const tapmc::Packing &p, double &sink)
{
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n = p.radius.size();
  for (std::size_t i = 0; i < n; ++i) {
    double best = 0.0;
    const double xi = p.xyz[3 * i], yi = p.xyz[3 * i + 1];
    for (std::size_t j = 0; j < i; ++j) {
      const double dx = xi - p.xyz[3 * j], dy = yi - p.xyz[3 * j + 1];
      const double h2 = 4.0 - dx * dx - dy * dy;
      if (h2 > 0.0) best = std::max(best, p.xyz[3 * j + 2] + std::sqrt(h2));
    }
    sink += best;
  }
  return seconds_since(t0);
}

}  // namespace

int main(int argc, char **argv)
{
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  std::printf("bench_deposition: sequential deposition (Jullien-Meakin), monodisperse R = 1, "
              "PBC, side 32R sqrt(N/4096)\nCPU: %s (one core)\n\n",
              cpu_model().c_str());
  std::printf("%10s %8s %7s %12s %14s %10s %9s %8s\n", "N", "side/R", "repeats", "median s",
              "us per sphere", "segs/sph", "phi_bulk", "redrops");
  std::vector<long> sizes = {4096, 100000};
  if (!quick) sizes.push_back(1000000);
  double per_sphere_small = 0.0;
  double sink = 0.0;
  tapmc::Packing reference;
  for (long n : sizes) {
    const int repeats = n <= 4096 ? 9 : (n <= 100000 ? 3 : 1);
    std::vector<double> times;
    tapmc::Packing p;
    const auto d = domain_for(n);
    for (int k = 0; k < repeats; ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      p = tapmc::deposit_packing(n, tapmc::RadiusDistribution::monodisperse(1.0), d, 1 + k);
      times.push_back(seconds_since(t0));
    }
    std::sort(times.begin(), times.end());
    const double median = times[times.size() / 2];
    double z0, z1;
    tapmc::bulk_window(p, d, 6.0, z0, z1);
    const double phi = tapmc::slab_volume_fraction(p, d, z0, z1);
    const double per_sphere = median / n * 1e6;
    if (n == 4096) {
      per_sphere_small = per_sphere;
      reference = p;
    }
    std::printf("%10ld %8.1f %7d %12.4f %14.2f %10.2f %9.4f %8lld\n", n, d.xhi, repeats, median,
                per_sphere, static_cast<double>(p.stats.segments) / n, phi,
                static_cast<long long>(p.stats.redrops));
    if (n != 4096)
      std::printf("%10s time per sphere / N=4096's: %.2f (1 = linear growth; cache misses grow "
                  "it at large N)\n", "", per_sphere / per_sphere_small);
  }
  {
    const long n = 4096;
    const int repeats = 9;
    tapmc::DepositionDomain d;
    d.xlo = d.ylo = -10.0;
    d.xhi = d.yhi = 10.0;
    d.periodic_x = d.periodic_y = false;
    d.has_cylinder = true;
    d.cylinder = {0.0, 0.0, 10.0};
    std::vector<double> times;
    tapmc::Packing p;
    for (int k = 0; k < repeats; ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      p = tapmc::deposit_packing(n, tapmc::RadiusDistribution::monodisperse(1.0), d, 1 + k);
      times.push_back(seconds_since(t0));
    }
    const double med = median(times);
    double z0, z1;
    tapmc::bulk_window(p, d, 6.0, z0, z1);
    const tapmc::stereo::Spheres spheres{p.xyz.data(), p.radius.data(), 0.0, nullptr,
                                         static_cast<int>(n)};
    const double phi = tapmc::stereo::cylinder_slab_volume(spheres, d.cylinder, z0, z1) /
                       (tapmc::kPi * 100.0 * (z1 - z0));
    const auto zones = tapmc::stereo::cylinder_zones(spheres, d.cylinder, 7.0, z0, z1);
    std::printf("\nTube of radius 10R (no flat walls), N = %ld, %d repeats: median %.4f s, %.2f us "
                "per sphere (%.2f x the box's at N = 4096),\n  %.2f segments per sphere, %.3f wall "
                "rolls per sphere, phi_bulk %.4f over the tube, %.4f in the core (r < R_c - 7R)\n",
                n, repeats, med, med / n * 1e6, med / n * 1e6 / per_sphere_small,
                static_cast<double>(p.stats.segments) / n,
                static_cast<double>(p.stats.wall_rolls) / n, phi, zones.phi_core);
  }
  const double naive = naive_scan_time(reference, sink);
  std::printf("\nReference, N = 4096: a naive scan of all earlier spheres per drop (first contact "
              "only) takes %.4f s,\n  O(N^2): about %.0f s extrapolated to N = 1e6 (checksum %g).\n",
              naive, naive * std::pow(1e6 / 4096.0, 2), sink);
  return 0;
}
