// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Unit tests of the contact counter: exact lattices (FCC shells over a gap sweep, simple cubic),
// blocks with free faces, the floor, the wall of a cylindrical container, polydisperse spheres,
// explicit images against periodic axes, random packings against an all-pairs minimum-image
// oracle, the distribution sums and the refusals.
#include "tapmc_contacts.h"
#include "tapmc_math.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using namespace tapmc::contacts;

namespace {

constexpr double kTol = tapmc::defaults::kContactsGapTolerance;

struct Packing {
  std::vector<double> xyz, radius;
  Box box;
  Spheres spheres() const
  {
    Spheres s;
    s.xyz = xyz.data();
    s.radius = radius.data();
    s.count = static_cast<int>(radius.size());
    return s;
  }
  int size() const { return static_cast<int>(radius.size()); }
};

// n^3 cubic cells of side a holding the given basis (fractions of a cell), spheres of radius r;
// the box is the block of cells, periodic along every axis or none.
Packing cubic_lattice(const std::vector<std::array<double, 3>> &basis, double a, int n, double r,
                      bool periodic)
{
  Packing p;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        for (const auto &b : basis) {
          p.xyz.push_back((i + b[0]) * a);
          p.xyz.push_back((j + b[1]) * a);
          p.xyz.push_back((k + b[2]) * a);
          p.radius.push_back(r);
        }
  for (int d = 0; d < 3; ++d) {
    p.box.lo[d] = 0.0;
    p.box.hi[d] = n * a;
    p.box.periodic[d] = periodic;
  }
  return p;
}

// FCC with nearest neighbours at distance 1 (a = sqrt 2), spheres of radius 1/2 at contact.
Packing fcc(int n, bool periodic)
{
  return cubic_lattice({{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}}, std::sqrt(2.0),
                       n, 0.5, periodic);
}

// The oracle: every pair, at its nearest image along the periodic axes.
std::vector<int> brute_force(const Packing &p, const Settings &s)
{
  const int n = p.size();
  std::vector<int> counts(n, 0);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      if (j == i) continue;
      double d2 = 0.0;
      for (int d = 0; d < 3; ++d) {
        double dx = p.xyz[3 * j + d] - p.xyz[3 * i + d];
        if (p.box.periodic[d]) {
          const double length = p.box.hi[d] - p.box.lo[d];
          dx -= length * std::round(dx / length);
        }
        d2 += dx * dx;
      }
      const double reach = (p.radius[i] + p.radius[j]) * (1.0 + s.gap + kTol);
      counts[i] += d2 <= reach * reach ? 1 : 0;
    }
    if (s.floor && p.xyz[3 * i + 2] - p.radius[i] - s.floor_z <= (s.gap + kTol) * 2.0 * p.radius[i])
      ++counts[i];
    if (s.wall) {
      const double axis =
          std::hypot(p.xyz[3 * i] - s.cylinder.cx, p.xyz[3 * i + 1] - s.cylinder.cy);
      if ((s.cylinder.radius - p.radius[i]) - axis <= (s.gap + kTol) * 2.0 * p.radius[i])
        ++counts[i];
    }
  }
  return counts;
}

Settings with_gap(double gap)
{
  Settings s;
  s.gap = gap;
  return s;
}

std::vector<int> count_all(const Packing &p, const Settings &s)
{
  return count_contacts(p.spheres(), p.size(), p.box, s);
}

void expect_all_equal(const std::vector<int> &counts, int expected, const std::string &what)
{
  ASSERT_FALSE(counts.empty());
  for (std::size_t i = 0; i < counts.size(); ++i)
    ASSERT_EQ(counts[i], expected) << what << ", sphere " << i;
}

}  // namespace

TEST(Contacts, FccAtContactHasTwelve)
{
  const Packing p = fcc(4, true);
  expect_all_equal(count_all(p, with_gap(0.0)), 12, "FCC, g = 0");
}

// Shells of FCC at 1, sqrt 2, sqrt 3, 2 (12, 6, 24, 12 spheres): g below sqrt(2) - 1 keeps the
// first shell, up to sqrt(3) - 1 the first two, and g = 1 reaches the shell at 2 exactly (the
// tolerance takes it in).
TEST(Contacts, FccGapSweepCountsTheShells)
{
  const Packing p = fcc(5, true);
  const double second = std::sqrt(2.0) - 1.0, third = std::sqrt(3.0) - 1.0;
  const struct {
    double gap;
    int expected;
  } sweep[] = {{0.0, 12},           {1e-3, 12},          {0.01, 12},          {0.1, 12},
               {second - 1e-6, 12}, {second + 1e-6, 18}, {0.5, 18},           {third - 1e-6, 18},
               {third + 1e-6, 42},  {0.9, 42},           {1.0 - 1e-6, 42},    {1.0, 54}};
  for (const auto &c : sweep)
    expect_all_equal(count_all(p, with_gap(c.gap)), c.expected, "g = " + std::to_string(c.gap));
}

TEST(Contacts, SimpleCubicHasSixThenEighteen)
{
  const Packing p = cubic_lattice({{0, 0, 0}}, 1.0, 6, 0.5, true);
  expect_all_equal(count_all(p, with_gap(0.0)), 6, "SC, g = 0");
  expect_all_equal(count_all(p, with_gap(0.4)), 6, "SC, g = 0.4");
  expect_all_equal(count_all(p, with_gap(0.42)), 18, "SC, g = 0.42");
}

// A sphere just outside the threshold is no contact, just inside it is; the tolerance is
// relative to the contact distance.
TEST(Contacts, ThresholdIsRelativeToThePairsContactDistance)
{
  for (double gap : {0.0, 0.001, 0.01, 0.3}) {
    for (double ri : {0.5, 2.0}) {
      const double rj = 0.25, contact = ri + rj;
      for (double factor : {1.0 - 1e-9, 1.0 + 1e-9}) {
        Packing p;
        p.xyz = {0.0, 0.0, 0.0, 0.0, 0.0, contact * (1.0 + gap) * factor};
        p.radius = {ri, rj};
        const std::vector<int> c = count_all(p, with_gap(gap));
        const int expected = factor < 1.0 ? 1 : 0;
        EXPECT_EQ(c[0], expected) << gap << " " << ri << " " << factor;
        EXPECT_EQ(c[1], expected) << gap << " " << ri << " " << factor;
      }
    }
  }
}

// A block with free faces: a corner site of FCC has 3 neighbours, a face-centre site on a face
// 8, an interior site 12; every count equals the oracle's.
TEST(Contacts, FreeFacesGiveEdgeSpheresFewerContacts)
{
  const Packing p = fcc(4, false);
  const std::vector<int> c = count_all(p, with_gap(0.01));
  EXPECT_EQ(c, brute_force(p, with_gap(0.01)));
  EXPECT_EQ(c[0], 3);  // the corner (0, 0, 0)
  EXPECT_EQ(*std::max_element(c.begin(), c.end()), 12);
  const double a = std::sqrt(2.0);
  for (int i = 0; i < p.size(); ++i) {
    const double x = p.xyz[3 * i], y = p.xyz[3 * i + 1], z = p.xyz[3 * i + 2];
    if (std::fabs(z) < 1e-12 && std::fabs(x - 1.5 * a) < 1e-12 && std::fabs(y - 1.5 * a) < 1e-12)
      EXPECT_EQ(c[i], 8) << "face site";
    if (std::fabs(x - 2 * a) < 1e-12 && std::fabs(y - 2 * a) < 1e-12 &&
        std::fabs(z - 2 * a) < 1e-12)
      EXPECT_EQ(c[i], 12) << "interior site";
  }
  // periodic along x and y only: the floor layer (z = 0) loses the 4 neighbours below it
  Packing slab = p;
  slab.box.periodic[0] = slab.box.periodic[1] = true;
  const std::vector<int> s = count_all(slab, with_gap(0.01));
  EXPECT_EQ(s, brute_force(slab, with_gap(0.01)));
  for (int i = 0; i < slab.size(); ++i)
    if (std::fabs(slab.xyz[3 * i + 2]) < 1e-12) EXPECT_EQ(s[i], 8) << i;
}

TEST(Contacts, FloorContactIsRelativeToTheDiameter)
{
  Packing p;
  const double r = 0.5, floor = 1.0;
  // heights above contact with the floor, in diameters: 0, 0.0099, 0.0101, -0.01 (below)
  for (double gap : {0.0, 0.0099, 0.0101, -0.01}) {
    p.xyz.insert(p.xyz.end(), {10.0 * p.size(), 0.0, floor + r + gap * 2.0 * r});
    p.radius.push_back(r);
  }
  Settings s = with_gap(0.01);
  s.floor = true;
  s.floor_z = floor;
  std::vector<int> counts(p.size());
  std::vector<unsigned char> on_floor(p.size());
  Counter counter;
  counter.count(p.spheres(), p.size(), p.box, s, counts.data(), on_floor.data());
  EXPECT_EQ(counts, (std::vector<int>{1, 1, 0, 1}));
  EXPECT_EQ(on_floor, (std::vector<unsigned char>{1, 1, 0, 1}));
  s.gap = 0.0;
  EXPECT_EQ(count_all(p, s), (std::vector<int>{1, 0, 0, 1}));
  s.floor = false;
  EXPECT_EQ(count_all(p, s), (std::vector<int>{0, 0, 0, 0}));
}

// The wall of a tube of radius 5.5 about (1, 2): spheres of radius 1/2 around it, far apart, at
// wall gaps (in diameters) 0 (centre exactly at the reach Rc - r = 5, a 3-4-5 triangle from the
// axis: exact), 0.0099, 0.0101 and -0.01 (beyond the wall), and one on the axis; a sphere of
// radius 1 at 0.015 of its own diameter; the floor under the first two.
TEST(Contacts, WallContactIsRelativeToTheDiameter)
{
  Packing p;
  const double cx = 1.0, cy = 2.0, rc = 5.5, r = 0.5;
  auto at_gap = [&](double angle, double gap, double radius, double z) {
    const double d = (rc - radius) - gap * 2.0 * radius;
    p.xyz.insert(p.xyz.end(), {cx + d * std::cos(angle), cy + d * std::sin(angle), z});
    p.radius.push_back(radius);
  };
  p.xyz = {cx + 3.0, cy + 4.0, r};  // the exact one, on the floor
  p.radius = {r};
  at_gap(2.0, 0.0099, r, r);
  at_gap(3.0, 0.0101, r, 5.0);
  at_gap(4.0, -0.01, r, 10.0);
  p.xyz.insert(p.xyz.end(), {cx, cy, 15.0});
  p.radius.push_back(r);
  at_gap(5.0, 0.015, 1.0, 20.0);
  Settings s = with_gap(0.01);
  s.wall = true;
  s.cylinder = {cx, cy, rc};
  std::vector<int> counts(p.size());
  std::vector<unsigned char> on_floor(p.size()), on_wall(p.size());
  Counter counter;
  counter.count(p.spheres(), p.size(), p.box, s, counts.data(), on_floor.data(), on_wall.data());
  EXPECT_EQ(counts, (std::vector<int>{1, 1, 0, 1, 0, 0}));
  EXPECT_EQ(on_wall, (std::vector<unsigned char>{1, 1, 0, 1, 0, 0}));
  EXPECT_EQ(on_floor, (std::vector<unsigned char>(p.size(), 0)));
  s.gap = 0.0;
  EXPECT_EQ(count_all(p, s), (std::vector<int>{1, 0, 0, 1, 0, 0}));
  s.gap = 0.02;
  EXPECT_EQ(count_all(p, s), (std::vector<int>{1, 1, 1, 1, 0, 1}));
  // the floor and the wall are two contacts of a sphere that touches both
  s.gap = 0.01;
  s.floor = true;
  counter.count(p.spheres(), p.size(), p.box, s, counts.data(), on_floor.data(), on_wall.data());
  EXPECT_EQ(counts, (std::vector<int>{2, 2, 0, 1, 0, 0}));
  EXPECT_EQ(on_floor, (std::vector<unsigned char>{1, 1, 0, 0, 0, 0}));
  s.wall = false;
  EXPECT_EQ(count_all(p, s), (std::vector<int>{1, 1, 0, 0, 0, 0}));
}

// A gap sweep: 40 spheres of radius 1/2 round the wall at gaps 0.0025, 0.0075, ... (in
// diameters, halfway between the thresholds), each at its own height; at g = 0.01 k exactly the
// first k touch, and the counter's flags say which.
TEST(Contacts, WallGapSweep)
{
  Packing p;
  const double rc = 6.0, r = 0.5;
  const int n = 40;
  for (int k = 0; k < n; ++k) {
    const double gap = 0.005 * k + 0.0025, d = (rc - r) - gap * 2.0 * r, angle = 0.7 * k;
    p.xyz.insert(p.xyz.end(), {d * std::cos(angle), d * std::sin(angle), 2.0 * k});
    p.radius.push_back(r);
  }
  Settings s;
  s.wall = true;
  s.cylinder = {0.0, 0.0, rc};
  Counter counter;
  std::vector<int> counts(n);
  std::vector<unsigned char> on_wall(n);
  for (int step = 0; step <= 21; ++step) {
    s.gap = 0.01 * step;
    counter.count(p.spheres(), n, p.box, s, counts.data(), nullptr, on_wall.data());
    for (int k = 0; k < n; ++k) {
      const int expected = k < 2 * step ? 1 : 0;
      ASSERT_EQ(counts[k], expected) << "g = " << s.gap << ", sphere " << k;
      ASSERT_EQ(on_wall[k], expected) << "g = " << s.gap << ", sphere " << k;
    }
    EXPECT_EQ(counts, brute_force(p, s)) << "g = " << s.gap;
  }
}

// Random mixed spheres in a tube (many touching each other, a third near the wall, some beyond
// it) with a floor, against the all-pairs oracle with the wall rule, over gaps and seeds.
TEST(Contacts, RandomTubePackingsMatchTheOracle)
{
  for (unsigned seed = 1; seed <= 4; ++seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double rc = 4.0, cx = 0.5, cy = -1.5;
    Packing p;
    for (int i = 0; i < 300; ++i) {
      const double radius = 0.3 + 0.3 * unit(rng);
      // one in three near the wall, at wall gaps from -0.02 to 0.12 diameters
      const double rho = i % 3 == 0 ? (rc - radius) - (0.14 * unit(rng) - 0.02) * 2.0 * radius
                                    : (rc - radius) * std::sqrt(unit(rng));
      const double angle = tapmc::kTwoPi * unit(rng);
      p.xyz.insert(p.xyz.end(),
                   {cx + rho * std::cos(angle), cy + rho * std::sin(angle), 12.0 * unit(rng)});
      p.radius.push_back(radius);
    }
    for (double g : {0.0, 0.001, 0.01, 0.05, 0.1}) {
      Settings s = with_gap(g);
      s.wall = true;
      s.cylinder = {cx, cy, rc};
      s.floor = true;
      s.floor_z = 0.3;
      std::vector<int> counts(p.size());
      std::vector<unsigned char> on_wall(p.size());
      Counter().count(p.spheres(), p.size(), p.box, s, counts.data(), nullptr, on_wall.data());
      EXPECT_EQ(counts, brute_force(p, s)) << "seed " << seed << " g " << g;
      s.wall = false;
      const std::vector<int> without = count_all(p, s);
      int touching = 0;
      for (int i = 0; i < p.size(); ++i) {
        ASSERT_EQ(counts[i] - without[i], on_wall[i]) << i;
        touching += on_wall[i];
      }
      EXPECT_GT(touching, 3) << "seed " << seed << " g " << g;  // about 14 at g = 0
    }
  }
}

// One sphere of radius 2 touched by six of radius 1/2 along the axes, at the pair gaps 0, 0.5 %,
// 1 %, 2 %, 5 %, 10 % of the contact distance 2.5; the small ones are far apart.
TEST(Contacts, PolydisperseGapsUseEachPairsContactDistance)
{
  Packing p;
  p.xyz = {0.0, 0.0, 0.0};
  p.radius = {2.0};
  const double gaps[6] = {0.0, 0.005, 0.01, 0.02, 0.05, 0.1};
  const int axis[6] = {0, 0, 1, 1, 2, 2};
  for (int k = 0; k < 6; ++k) {
    double c[3] = {0.0, 0.0, 0.0};
    c[axis[k]] = (k % 2 ? -1.0 : 1.0) * 2.5 * (1.0 + gaps[k]);
    p.xyz.insert(p.xyz.end(), {c[0], c[1], c[2]});
    p.radius.push_back(0.5);
  }
  for (double g : {0.0, 0.004, 0.0051, 0.011, 0.03, 0.06, 0.2}) {
    const std::vector<int> c = count_all(p, with_gap(g));
    int expected = 0;
    for (double gk : gaps) expected += gk <= g ? 1 : 0;
    EXPECT_EQ(c[0], expected) << "g = " << g;
    for (int k = 0; k < 6; ++k) EXPECT_EQ(c[1 + k], gaps[k] <= g ? 1 : 0) << g << " " << k;
  }
}

// Random spheres (mixed radii, many overlapping and near-contact pairs) in boxes periodic along
// x and y, along all axes, or none, against the all-pairs oracle, over gaps and seeds; a small
// periodic box (two cells per axis) included.
TEST(Contacts, RandomPackingsMatchTheAllPairsOracle)
{
  for (unsigned seed = 1; seed <= 6; ++seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const bool small = seed % 3 == 0;
    const double length[3] = {small ? 3.5 : 9.0, small ? 3.3 : 7.0, small ? 3.4 : 8.0};
    const int n = small ? 60 : 400;
    Packing p;
    for (int i = 0; i < n; ++i) {
      for (int d = 0; d < 3; ++d) p.xyz.push_back(-1.0 + length[d] * unit(rng));
      p.radius.push_back(0.35 + 0.3 * unit(rng));
    }
    for (int d = 0; d < 3; ++d) {
      p.box.lo[d] = -1.0;
      p.box.hi[d] = -1.0 + length[d];
    }
    for (int periodic = 0; periodic < 3; ++periodic) {
      for (int d = 0; d < 3; ++d) p.box.periodic[d] = periodic == 2 || (periodic == 1 && d < 2);
      for (double g : {0.0, 0.001, 0.01, 0.05, 0.1}) {
        const std::vector<int> c = count_all(p, with_gap(g));
        EXPECT_EQ(c, brute_force(p, with_gap(g))) << "seed " << seed << " periodic " << periodic
                                                  << " g " << g;
      }
    }
  }
}

// The caller's own images (as LAMMPS ghost atoms): the spheres of a periodic box plus their
// images within reach, no axis periodic, the first n spheres as centres, count as the periodic
// box does.
TEST(Contacts, ExplicitImagesCountAsPeriodicAxes)
{
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Packing p;
  const double length = 6.0;
  const int n = 150;
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) p.xyz.push_back(length * unit(rng));
    p.radius.push_back(0.4 + 0.2 * unit(rng));
  }
  for (int d = 0; d < 3; ++d) {
    p.box.hi[d] = length;
    p.box.periodic[d] = d < 2;
  }
  const Settings s = with_gap(0.05);
  const std::vector<int> periodic = count_all(p, s);

  Packing images = p;
  images.box.periodic[0] = images.box.periodic[1] = false;
  const double cut = 2.0 * 0.6 * (1.0 + s.gap) + 1e-9;
  for (int i = 0; i < n; ++i)
    for (int sx = -1; sx <= 1; ++sx)
      for (int sy = -1; sy <= 1; ++sy) {
        if (sx == 0 && sy == 0) continue;
        const double x = p.xyz[3 * i] + sx * length, y = p.xyz[3 * i + 1] + sy * length;
        if (x < -cut || x > length + cut || y < -cut || y > length + cut) continue;
        images.xyz.insert(images.xyz.end(), {x, y, p.xyz[3 * i + 2]});
        images.radius.push_back(p.radius[i]);
      }
  ASSERT_GT(images.size(), n);
  EXPECT_EQ(count_contacts(images.spheres(), n, images.box, s), periodic);
  EXPECT_EQ(periodic, brute_force(p, s));
}

TEST(Contacts, UniformRadiusAndCentreSubset)
{
  const Packing p = fcc(3, true);
  Spheres s = p.spheres();
  s.radius = nullptr;
  s.uniform_radius = 0.5;
  const std::vector<int> c = count_contacts(s, 10, p.box, with_gap(0.0));
  ASSERT_EQ(c.size(), 10u);
  expect_all_equal(c, 12, "uniform radius");
  EXPECT_TRUE(count_contacts(s, 0, p.box, with_gap(0.0)).empty());
  Spheres none;
  EXPECT_TRUE(count_contacts(none, 0, Box(), with_gap(0.0)).empty());
}

TEST(Contacts, DistributionSumsAndFractions)
{
  const std::vector<int> counts = {0, 1, 3, 4, 12, 30, 4, 0};
  const std::vector<unsigned char> floor = {0, 1, 1, 0, 0, 0, 0, 0};
  const std::vector<unsigned char> wall = {0, 0, 1, 1, 0, 0, 1, 0};
  double sums[kNumSums] = {};
  // two halves, as two ranks would add them, then combined
  const int first[] = {0, 1, 2, 3}, second[] = {4, 5, 6, 7};
  const int m1 = accumulate(counts.data(), floor.data(), wall.data(), first, 4, sums);
  const int m2 = accumulate(counts.data(), floor.data(), wall.data(), second, 4, sums);
  const Distribution d = finish(sums, std::max(m1, m2));
  EXPECT_EQ(d.spheres, 8.0);
  EXPECT_DOUBLE_EQ(d.mean, 54.0 / 8.0);
  EXPECT_DOUBLE_EQ(d.fraction_none, 2.0 / 8.0);
  EXPECT_DOUBLE_EQ(d.fraction_few, 4.0 / 8.0);
  EXPECT_DOUBLE_EQ(d.fraction_floor, 2.0 / 8.0);
  EXPECT_DOUBLE_EQ(d.fraction_wall, 3.0 / 8.0);
  EXPECT_EQ(d.max, 30);
  ASSERT_EQ(static_cast<int>(d.fraction.size()), tapmc::defaults::kContactsMaxZ + 1);
  EXPECT_DOUBLE_EQ(d.fraction[0], 0.25);
  EXPECT_DOUBLE_EQ(d.fraction[4], 0.25);
  EXPECT_DOUBLE_EQ(d.fraction[12], 0.125);
  EXPECT_DOUBLE_EQ(d.fraction[tapmc::defaults::kContactsMaxZ], 0.125);  // 30: the last row
  double total = 0.0;
  for (double f : d.fraction) total += f;
  EXPECT_DOUBLE_EQ(total, 1.0);

  double empty[kNumSums] = {};
  EXPECT_EQ(accumulate(counts.data(), nullptr, nullptr, nullptr, 0, empty), 0);
  const Distribution z = finish(empty, 0);
  EXPECT_EQ(z.spheres, 0.0);
  EXPECT_EQ(z.fraction_wall, 0.0);
  EXPECT_EQ(z.mean, 0.0);
  EXPECT_EQ(z.fraction, std::vector<double>(tapmc::defaults::kContactsMaxZ + 1, 0.0));
}

TEST(Contacts, RefusesInvalidInputNamingIt)
{
  const Packing p = fcc(3, true);
  auto message = [&](const Packing &q, const Settings &s, int centres) {
    try {
      count_contacts(q.spheres(), centres, q.box, s);
    } catch (const std::invalid_argument &e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_EQ(message(p, with_gap(-0.01), 1), "gap = -0.01 is outside the allowed range [0, 1]");
  EXPECT_EQ(message(p, with_gap(1.5), 1), "gap = 1.5 is outside the allowed range [0, 1]");
  EXPECT_EQ(message(p, with_gap(std::nan("")), 1), "gap = nan is outside the allowed range [0, 1]");
  Settings floor_nan = with_gap(0.0);
  floor_nan.floor = true;
  floor_nan.floor_z = INFINITY;
  EXPECT_EQ(message(p, floor_nan, 1), "floor = inf is outside the allowed range (finite)");
  Settings floor = with_gap(0.0);
  floor.floor = true;
  EXPECT_NE(message(p, floor, 1).find("a floor needs a non-periodic z"), std::string::npos);
  Settings wall = with_gap(0.0);
  wall.wall = true;
  wall.cylinder = {0.0, 0.0, 0.0};
  EXPECT_EQ(message(p, wall, 1), "cylinder radius = 0 is outside the allowed range (0, +inf)");
  wall.cylinder = {NAN, 0.0, 3.0};
  EXPECT_EQ(message(p, wall, 1), "cylinder cx = nan is outside the allowed range (finite)");
  wall.cylinder = {0.0, 0.0, 3.0};
  EXPECT_EQ(message(p, wall, 1), "a container wall needs non-periodic x and y (the box is "
                                 "periodic along x): the wall replaces the periodic sides");
  EXPECT_EQ(message(p, with_gap(0.0), -1), "centres = -1 is outside the allowed range [0, 108]");
  EXPECT_EQ(message(p, with_gap(0.0), 109), "centres = 109 is outside the allowed range [0, 108]");
  Packing bad = p;
  bad.radius[5] = 0.0;
  EXPECT_EQ(message(bad, with_gap(0.0), 1),
            "radius of sphere 5 = 0 is outside the allowed range (0, +inf)");
  bad = p;
  bad.xyz[3 * 7 + 1] = std::nan("");
  EXPECT_EQ(message(bad, with_gap(0.0), 1),
            "y of sphere 7 = nan is outside the allowed range (finite)");
  // a period of two reaches or less: a partner could be met at two images
  Packing tiny = cubic_lattice({{0, 0, 0}}, 1.0, 2, 0.5, true);
  EXPECT_EQ(message(tiny, with_gap(0.0), 1),
            "periodic box length along x = 2 is outside the allowed range (2 reach, +inf) = "
            "(2.0000000002, +inf) (reach = 2 R_max (1 + gap))");
}
