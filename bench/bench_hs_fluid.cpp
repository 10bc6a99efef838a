// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Equilibrium hard-sphere fluid by NVT Metropolis Monte Carlo in a periodic cube: the reference
// against which tapmc-paper question p0-fluid reads Gotoh's P0(sigma) of the tapped packings
// (Fig. 9) and the Percus-Yevick form. Diameter 1 (the dumps carry radius 0.5).
//
//   start      FCC lattice of 4 K^3 spheres at min(phi, --start-phi), melted by MC sweeps;
//   compress   the melt is scaled to the target phi (its spheres then overlap) and the overlaps
//              are removed by steepest descent of a harmonic repulsion between spheres of
//              diameter kInflate (a preparation only: what follows forgets it);
//   equilibrate until the mean-square displacement reaches --eq-msd (diameters^2), at most
//              --max-sweeps sweeps, the trial cube side being adjusted after every sweep to the
//              target acceptance (the structure relaxes from the descent meanwhile), then frozen
//              for the sampling (a fixed move set keeps detailed balance);
//   sample     --configs configurations, each after a further --spacing-msd of mean-square
//              displacement (at most --max-sweeps sweeps each), written as LAMMPS dumps
//              (PREFIX.<k>.lammpstrj); the contact value g(1+) is measured all along.
//
// Output on stdout: "key value" lines (N, phi, L, delta, acceptance, sweeps per stage, msd,
// g_contact and its sem over the configurations' intervals, the Carnahan-Starling value,
// min_distance, moves_per_second).
//
// Usage: bench_hs_fluid --phi PHI [--cells K] [--seed S] [--configs C] [--eq-msd D2]
//                       [--spacing-msd D2] [--max-sweeps M] [--acceptance A] [--start-phi P]
//                       [--prefix PREFIX]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace {

constexpr double kPi = 3.14159265358979323846;
// the fluid freezes at 0.494 and its metastable branch crystallises ever faster above about
// 0.55 (nucleation rates rise by orders of magnitude per percent); random close packing is 0.64.
constexpr double kMaxPhi = 0.58;
// the FCC start is far below its melting density (0.545), so it melts within the first sweeps.
constexpr double kDefaultStartPhi = 0.30;
constexpr int kMeltSweeps = 200;
// trial cube side bounds (diameters): the upper one keeps moves local at low density.
constexpr double kMinDelta = 1e-4;
constexpr double kMaxDelta = 1.0;
// multiplicative step of the acceptance tuning.
constexpr double kDeltaStep = 1.03;
// diameter of the repulsion that removes the overlaps after the scaling: 1 % above contact, so
// the force still pushes pairs at contact apart and the descent, stopped as soon as no pair is
// closer than one diameter, ends in a few hundred steps (phi 0.58 * 1.01^3 = 0.60 is still
// below jamming, 0.64, where the descent could get stuck).
constexpr double kInflate = 1.01;
// descent step (diameters per unit of the harmonic force) and iteration bound.
constexpr double kDescentStep = 0.2;
constexpr int kMaxDescent = 100000;
// contact value: g(r) in kContactBins shells of kContactBin diameters from contact,
// ln g fitted by a straight line and extrapolated to r = 1.
constexpr int kContactBins = 8;
constexpr double kContactBin = 0.005;
// sweeps between samples of g(r) and of the mean-square displacement.
constexpr int kSampleEvery = 10;

[[noreturn]] void fail(const std::string& message) {
  std::fprintf(stderr, "bench_hs_fluid: %s\n", message.c_str());
  std::exit(1);
}

double number(const char* name, const char* text, double lo, double hi) {
  char* end = nullptr;
  double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || !(v >= lo && v <= hi)) {
    char buf[256];
    std::snprintf(buf, sizeof buf, "%s must be a number in [%g, %g], got '%s'", name, lo, hi,
                  text);
    fail(buf);
  }
  return v;
}

struct Fluid {
  int n = 0;
  double L = 0.0;
  int m = 0;                        // cells per side, each at least `reach` wide
  double reach = 1.0;               // range of the pair checks (diameters)
  std::vector<double> x;            // wrapped positions, 3n
  std::vector<double> u;            // unwrapped positions, 3n (for the displacement)
  std::vector<std::vector<int>> cells;
  std::vector<int> cell_of, slot;

  int cell_index(const double* p) const {
    int c[3];
    for (int k = 0; k < 3; ++k) {
      c[k] = static_cast<int>(p[k] / L * m);
      if (c[k] >= m) c[k] = m - 1;  // p == L after rounding
      if (c[k] < 0) c[k] = 0;
    }
    return (c[0] * m + c[1]) * m + c[2];
  }

  void rebuild() {
    m = static_cast<int>(std::floor(L / reach));
    if (m < 3) fail("box narrower than 3 cells: raise --cells");
    cells.assign(static_cast<size_t>(m) * m * m, {});
    cell_of.assign(n, 0);
    slot.assign(n, 0);
    for (int i = 0; i < n; ++i) insert(i);
  }

  void insert(int i) {
    int c = cell_index(&x[3 * i]);
    cell_of[i] = c;
    slot[i] = static_cast<int>(cells[c].size());
    cells[c].push_back(i);
  }

  void remove(int i) {
    auto& v = cells[cell_of[i]];
    int last = v.back();
    v[slot[i]] = last;
    slot[last] = slot[i];
    v.pop_back();
  }

  double image(double d) const { return d - L * std::round(d / L); }

  // Calls f(j, r2) for every sphere j != skip in the 27 cells around p.
  template <class F>
  bool around(const double* p, int skip, F&& f) const {
    int c = cell_index(p);
    int cz = c % m, cy = (c / m) % m, cx = c / (m * m);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          int nc = (((cx + dx + m) % m) * m + (cy + dy + m) % m) * m + (cz + dz + m) % m;
          for (int j : cells[nc]) {
            if (j == skip) continue;
            double a = image(p[0] - x[3 * j]), b = image(p[1] - x[3 * j + 1]),
                   e = image(p[2] - x[3 * j + 2]);
            if (!f(j, a * a + b * b + e * e)) return false;
          }
        }
    return true;
  }

  bool free_at(const double* p, int skip) const {
    return around(p, skip, [](int, double r2) { return r2 >= 1.0; });
  }

  // Smallest centre distance over all pairs, and the histogram of pairs near contact.
  double scan(std::vector<double>* hist) const {
    double best = 1e300;
    const double reach = 1.0 + kContactBins * kContactBin;
    for (int i = 0; i < n; ++i)
      around(&x[3 * i], i, [&](int j, double r2) {
        if (j < i) return true;
        best = std::min(best, r2);
        if (hist && r2 < reach * reach) {
          int b = static_cast<int>((std::sqrt(r2) - 1.0) / kContactBin);
          if (b >= 0 && b < kContactBins) (*hist)[b] += 1.0;
        }
        return true;
      });
    return std::sqrt(best);
  }

  void scale(double s) {
    L *= s;
    for (double& v : x) v *= s;
    for (double& v : u) v *= s;
    rebuild();
  }

  double phi() const { return n * kPi / 6.0 / (L * L * L); }
};

struct Mover {
  Fluid& f;
  std::mt19937_64 rng;
  double delta;
  long long tried = 0, accepted = 0;

  // One sweep: n trial moves of random spheres, uniform in a cube of side delta.
  double sweep() {
    std::uniform_int_distribution<int> pick(0, f.n - 1);
    std::uniform_real_distribution<double> unit(-0.5, 0.5);
    long long acc = 0;
    for (int t = 0; t < f.n; ++t) {
      int i = pick(rng);
      double d[3] = {delta * unit(rng), delta * unit(rng), delta * unit(rng)};
      double p[3];
      for (int k = 0; k < 3; ++k) {
        p[k] = f.x[3 * i + k] + d[k];
        p[k] -= f.L * std::floor(p[k] / f.L);
        if (p[k] >= f.L) p[k] = 0.0;
      }
      if (!f.free_at(p, i)) continue;
      f.remove(i);
      for (int k = 0; k < 3; ++k) {
        f.x[3 * i + k] = p[k];
        f.u[3 * i + k] += d[k];
      }
      f.insert(i);
      ++acc;
    }
    tried += f.n;
    accepted += acc;
    return static_cast<double>(acc) / f.n;
  }

  void tune(double rate, double target) {
    delta *= rate > target ? kDeltaStep : 1.0 / kDeltaStep;
    delta = std::clamp(delta, kMinDelta, kMaxDelta);
  }
};

// Steepest descent of sum over pairs closer than kInflate of (1 - r / kInflate)^2; returns the
// iterations it took until no pair is closer than one diameter.
int remove_overlaps(Fluid& f) {
  f.reach = kInflate;
  f.rebuild();
  std::vector<double> force(f.x.size());
  int it = 0;
  for (; it < kMaxDescent; ++it) {
    std::fill(force.begin(), force.end(), 0.0);
    double closest = 1e300;
    for (int i = 0; i < f.n; ++i)
      f.around(&f.x[3 * i], i, [&](int j, double r2) {
        if (j < i || r2 >= kInflate * kInflate) return true;
        closest = std::min(closest, r2);
        double r = std::sqrt(r2);
        double d[3];
        for (int k = 0; k < 3; ++k) d[k] = f.image(f.x[3 * i + k] - f.x[3 * j + k]);
        double mag = (1.0 - r / kInflate) / std::max(r, 1e-12);
        for (int k = 0; k < 3; ++k) {
          force[3 * i + k] += mag * d[k];
          force[3 * j + k] -= mag * d[k];
        }
        return true;
      });
    if (closest >= 1.0) break;
    for (int i = 0; i < f.n; ++i)
      for (int k = 0; k < 3; ++k) {
        double step = kDescentStep * force[3 * i + k];
        double& p = f.x[3 * i + k];
        p += step;
        p -= f.L * std::floor(p / f.L);
        if (p >= f.L) p = 0.0;
        f.u[3 * i + k] += step;
      }
    f.rebuild();
  }
  if (it == kMaxDescent) fail("overlaps not removed after the descent (phi too high?)");
  f.reach = 1.0;
  f.rebuild();
  return it;
}

double msd(const Fluid& f, const std::vector<double>& u0) {
  double s = 0.0;
  for (size_t k = 0; k < f.u.size(); ++k) s += (f.u[k] - u0[k]) * (f.u[k] - u0[k]);
  return s / f.n;
}

// Contact value from the pair histogram of `samples` configurations.
double contact_value(const std::vector<double>& hist, double samples, const Fluid& f) {
  double rho = f.n / (f.L * f.L * f.L);
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int k = 0;
  for (int b = 0; b < kContactBins; ++b) {
    double lo = 1.0 + b * kContactBin, hi = lo + kContactBin;
    double shell = 4.0 * kPi / 3.0 * (hi * hi * hi - lo * lo * lo);
    double g = hist[b] / (samples * 0.5 * f.n * rho * shell);
    if (g <= 0) continue;
    double r = 0.5 * (lo + hi), y = std::log(g);
    sx += r; sy += y; sxx += r * r; sxy += r * y; ++k;
  }
  if (k < 2) return std::nan("");
  double slope = (k * sxy - sx * sy) / (k * sxx - sx * sx);
  double icpt = (sy - slope * sx) / k;
  return std::exp(icpt + slope * 1.0);
}

void write_dump(const Fluid& f, const std::string& path, long step) {
  FILE* out = std::fopen(path.c_str(), "w");
  if (!out) fail("cannot write " + path);
  std::fprintf(out, "ITEM: TIMESTEP\n%ld\nITEM: NUMBER OF ATOMS\n%d\n", step, f.n);
  std::fprintf(out, "ITEM: BOX BOUNDS pp pp pp\n");
  for (int k = 0; k < 3; ++k) std::fprintf(out, "0 %.17g\n", f.L);
  std::fprintf(out, "ITEM: ATOMS id type x y z radius\n");
  for (int i = 0; i < f.n; ++i)
    std::fprintf(out, "%d 1 %.17g %.17g %.17g 0.5\n", i + 1, f.x[3 * i], f.x[3 * i + 1],
                 f.x[3 * i + 2]);
  if (std::fclose(out) != 0) fail("cannot write " + path);
}

}  // namespace

int main(int argc, char** argv) {
  double phi = -1, eq_msd = 2.0, spacing_msd = 0.5, target = 0.35, start_phi = kDefaultStartPhi;
  int cells = 10, configs = 4;
  long max_sweeps = 200000;
  unsigned long long seed = 1;
  std::string prefix;
  for (int a = 1; a < argc; ++a) {
    std::string k = argv[a];
    if (a + 1 >= argc) fail("option " + k + " needs a value");
    const char* v = argv[++a];
    if (k == "--phi") phi = number("--phi", v, 0.01, kMaxPhi);
    else if (k == "--cells") cells = static_cast<int>(number("--cells", v, 2, 40));
    else if (k == "--seed") seed = static_cast<unsigned long long>(number("--seed", v, 0, 1e15));
    else if (k == "--configs") configs = static_cast<int>(number("--configs", v, 0, 1000));
    else if (k == "--eq-msd") eq_msd = number("--eq-msd", v, 0, 1e4);
    else if (k == "--spacing-msd") spacing_msd = number("--spacing-msd", v, 0, 1e4);
    else if (k == "--max-sweeps") max_sweeps = static_cast<long>(number("--max-sweeps", v, 1, 1e9));
    else if (k == "--acceptance") target = number("--acceptance", v, 0.05, 0.95);
    else if (k == "--start-phi") start_phi = number("--start-phi", v, 0.01, 0.45);
    else if (k == "--prefix") prefix = v;
    else fail("unknown option " + k + " (see the file header)");
  }
  if (phi < 0) fail("--phi is required (0.01 to 0.58)");
  if (configs > 0 && prefix.empty()) fail("--prefix is required with --configs > 0");

  Fluid f;
  f.n = 4 * cells * cells * cells;
  double phi0 = std::min(phi, start_phi);
  double a = std::cbrt(4.0 * kPi / 6.0 / phi0);  // FCC cell edge at phi0
  f.L = cells * a;
  const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j)
      for (int k = 0; k < cells; ++k)
        for (const auto& b : basis) {
          f.x.push_back((i + b[0] + 0.25) * a);
          f.x.push_back((j + b[1] + 0.25) * a);
          f.x.push_back((k + b[2] + 0.25) * a);
        }
  f.u = f.x;
  if (f.L < 3.0) fail("--cells too small for a 3-cell periodic box");
  f.rebuild();
  Mover mv{f, std::mt19937_64(seed), 0.5};
  auto clock0 = std::chrono::steady_clock::now();

  for (int s = 0; s < kMeltSweeps; ++s) mv.tune(mv.sweep(), target);
  const double l_target = std::cbrt(f.n * kPi / 6.0 / phi);
  long compress_sweeps = 0;
  if (f.L > l_target) {
    f.scale(l_target / f.L);
    compress_sweeps = remove_overlaps(f);
  }

  const std::vector<double> u0 = f.u;
  long eq_sweeps = 0;
  double m2 = 0.0;
  while (m2 < eq_msd && eq_sweeps < max_sweeps) {
    for (int s = 0; s < kSampleEvery; ++s) mv.tune(mv.sweep(), target);
    eq_sweeps += kSampleEvery;
    m2 = msd(f, u0);
  }
  mv.tried = mv.accepted = 0;
  std::printf("N %d\nphi %.10g\nL %.10g\ndelta %.6g\ndescent_steps %ld\neq_sweeps %ld\n"
              "eq_msd %.6g\n", f.n, f.phi(), f.L, mv.delta, compress_sweeps, eq_sweeps, m2);

  std::vector<double> g_batch;
  double min_spacing = 1e300;
  long sample_sweeps = 0;
  for (int c = 1; c <= configs; ++c) {
    std::vector<double> hist(kContactBins, 0.0);
    double samples = 0;
    const std::vector<double> uc = f.u;
    long sw = 0;
    double m2c = 0.0;
    while (m2c < spacing_msd && sw < max_sweeps) {
      for (int s = 0; s < kSampleEvery; ++s) mv.sweep();
      sw += kSampleEvery;
      f.scan(&hist);
      samples += 1;
      m2c = msd(f, uc);
    }
    sample_sweeps += sw;
    min_spacing = std::min(min_spacing, m2c);
    double dmin = f.scan(nullptr);
    if (dmin < 1.0) fail("overlap in the sampled configuration (program error)");
    g_batch.push_back(contact_value(hist, samples, f));
    write_dump(f, prefix + "." + std::to_string(c) + ".lammpstrj", eq_sweeps + sample_sweeps);
    std::printf("config %d sweeps %ld msd_spacing %.6g g_contact %.6g min_distance %.12g\n", c,
                sw, m2c, g_batch.back(), dmin);
  }
  double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock0).count();
  double gm = 0, gs = 0;
  for (double g : g_batch) gm += g;
  if (!g_batch.empty()) gm /= g_batch.size();
  for (double g : g_batch) gs += (g - gm) * (g - gm);
  double gsem = g_batch.size() > 1 ? std::sqrt(gs / (g_batch.size() - 1) / g_batch.size())
                                   : std::nan("");
  double p = f.phi();
  std::printf("acceptance %.6g\nsample_sweeps %ld\nmin_spacing_msd %.6g\ntotal_msd %.6g\n"
              "g_contact %.6g\ng_contact_sem %.6g\ng_contact_cs %.6g\nmin_distance %.12g\n"
              "moves_per_second %.4g\nseconds %.4g\n",
              mv.tried ? static_cast<double>(mv.accepted) / mv.tried : std::nan(""),
              sample_sweeps, min_spacing, msd(f, u0), gm, gsem,
              (1.0 - p / 2.0) / std::pow(1.0 - p, 3), f.scan(nullptr),
              (kMeltSweeps + eq_sweeps + sample_sweeps) *
                  static_cast<double>(f.n) / seconds,
              seconds);
  return 0;
}
