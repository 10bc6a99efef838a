// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Benchmark input generator: random hard-sphere packings (random sequential addition on a cell
// grid) written as LAMMPS dumps, for bench_pores.py.
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

struct Options {
  long n = 4096;
  double radius = 0.5, lx = 16, ly = 16, phi = 0.33;
  bool periodic_z = false;
  int frames = 1;
  unsigned long seed = 1;
  std::string output = "packing.dump";
};

// Random sequential addition of up to n spheres in lx x ly x lz (periodic x, y; z periodic or
// bounded by walls), cell grid of side >= 2R; stops at n or when insertions keep failing.
std::vector<double> rsa(const Options& o, double lz, std::mt19937_64& engine) {
  const double d = 2 * o.radius;
  const std::array<double, 3> length{{o.lx, o.ly, lz}};
  std::array<int, 3> cells;
  for (int k = 0; k < 3; ++k) cells[k] = std::max(3, static_cast<int>(length[k] / d));
  std::vector<std::vector<int>> grid(static_cast<std::size_t>(cells[0]) * cells[1] * cells[2]);
  std::vector<double> xyz;
  xyz.reserve(3 * o.n);
  std::uniform_real_distribution<double> u(0, 1);
  long failures = 0;
  while (static_cast<long>(xyz.size() / 3) < o.n && failures < 200 * o.n + 1000000) {
    double c[3] = {o.lx * u(engine), o.ly * u(engine),
                   o.periodic_z ? lz * u(engine) : o.radius + (lz - d) * u(engine)};
    int cell[3];
    for (int k = 0; k < 3; ++k) cell[k] = std::min(cells[k] - 1, static_cast<int>(c[k] / length[k] * cells[k]));
    bool free = true;
    for (int dx = -1; dx <= 1 && free; ++dx)
      for (int dy = -1; dy <= 1 && free; ++dy)
        for (int dz = -1; dz <= 1 && free; ++dz) {
          int nb[3] = {cell[0] + dx, cell[1] + dy, cell[2] + dz};
          bool skip = false;
          for (int k = 0; k < 3; ++k) {
            if (nb[k] < 0 || nb[k] >= cells[k]) {
              if (k == 2 && !o.periodic_z) skip = true;
              nb[k] = (nb[k] + cells[k]) % cells[k];
            }
          }
          if (skip) continue;
          for (int j : grid[(static_cast<std::size_t>(nb[0]) * cells[1] + nb[1]) * cells[2] + nb[2]]) {
            double r2 = 0;
            for (int k = 0; k < 3; ++k) {
              double s = c[k] - xyz[3 * j + k];
              if (k < 2 || o.periodic_z) s -= length[k] * std::round(s / length[k]);
              r2 += s * s;
            }
            if (r2 < d * d) {
              free = false;
              break;
            }
          }
        }
    if (!free) {
      ++failures;
      continue;
    }
    grid[(static_cast<std::size_t>(cell[0]) * cells[1] + cell[1]) * cells[2] + cell[2]].push_back(
        static_cast<int>(xyz.size() / 3));
    xyz.insert(xyz.end(), c, c + 3);
  }
  return xyz;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--n") o.n = std::stol(value);
    else if (key == "--radius") o.radius = std::stod(value);
    else if (key == "--lx") o.lx = std::stod(value);
    else if (key == "--ly") o.ly = std::stod(value);
    else if (key == "--phi") o.phi = std::stod(value);
    else if (key == "--periodic-z") o.periodic_z = value == "1";
    else if (key == "--frames") o.frames = std::stoi(value);
    else if (key == "--seed") o.seed = std::stoul(value);
    else if (key == "--output") o.output = value;
    else {
      std::fprintf(stderr, "bench_pores_packing: unknown option %s\n", key.c_str());
      return 1;
    }
  }
  const double lz = o.n * 4.0 / 3.0 * M_PI * std::pow(o.radius, 3) / (o.phi * o.lx * o.ly);
  FILE* out = std::fopen(o.output.c_str(), "w");
  if (!out) {
    std::fprintf(stderr, "bench_pores_packing: cannot write %s\n", o.output.c_str());
    return 1;
  }
  std::mt19937_64 engine(o.seed);
  for (int f = 0; f < o.frames; ++f) {
    const std::vector<double> xyz = rsa(o, lz, engine);
    const long n = static_cast<long>(xyz.size() / 3);
    std::fprintf(out, "ITEM: TIMESTEP\n%d\nITEM: NUMBER OF ATOMS\n%ld\nITEM: BOX BOUNDS pp pp %s\n0 %.17g\n0 %.17g\n0 %.17g\n"
                      "ITEM: ATOMS id type x y z radius\n",
                 f, n, o.periodic_z ? "pp" : "ff", o.lx, o.ly, lz);
    for (long i = 0; i < n; ++i)
      std::fprintf(out, "%ld 1 %.17g %.17g %.17g %.17g\n", i + 1, xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2], o.radius);
    std::fprintf(stderr, "bench_pores_packing: frame %d: %ld spheres, box %g x %g x %g, phi %.3f\n", f, n, o.lx, o.ly, lz,
                 n * 4.0 / 3.0 * M_PI * std::pow(o.radius, 3) / (o.lx * o.ly * lz));
  }
  std::fclose(out);
  return 0;
}
