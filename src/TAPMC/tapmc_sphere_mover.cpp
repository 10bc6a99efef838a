// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The trial-move engine of the redeposition (paper, section II) with neighbour lists kept up to
// date locally.
//
// Lists. Every sphere i has a reference position ref_i (its position when its list was last
// made) and lists every sphere j whose reference is within reach:
//     |ref_i - ref_j| < (R_i + R_j) + d_max + skin + margin      (nearest periodic image),
// a symmetric predicate (the same arithmetic from either side), so the lists are symmetric:
// j in list(i) <=> i in list(j). Invariant: every sphere is within skin/2 of its reference.
// A trial puts i at most d_max from r_i; if it overlapped j then
//     |ref_i - ref_j| <= |ref_i - r_i| + |r_i - trial| + |trial - r_j| + |r_j - ref_j|
//                     <  skin/2 + d_max + (R_i + R_j) + skin/2,
// so j is listed: the lists never miss an overlap, and the accepted moves are those of an
// all-pairs test whatever the skin. `margin` (defaults::kGridRoundingMargin of the coordinate
// scale) covers the rounding of positions, steps and wraps.
//
// Local upkeep. When an accepted move (or set_position) takes sphere i beyond skin/2 of ref_i,
// ref_i becomes its current position: i is removed from the lists of its old neighbours, moved
// to the grid cell of its new reference, and its new list is found by a 27-cell query over the
// reference positions, i being inserted in the list of each new neighbour. The work is O(list
// length), never O(N). Positions stay wrapped into the box along periodic axes and every test
// takes the nearest image, so crossing a periodic side needs no update.
//
// Storage. Each sphere has a 32-byte record (x, y, z, R: two to a cache line), its reference
// position apart, its image counts and a list row, all kept in an internal spatial order (cell order
// at reset), so the neighbours of a sphere lie close in memory; the caller's indices map to
// internal slots. The picks draw candidates[k] by the same random numbers whatever the internal
// order: results do not depend on it. A list row has a fixed capacity (the count, then the
// neighbours' slots: one cache line at the paper's densities); a row that would overflow widens
// every row (O(N), rare; counted in capacity_grows()). In the code: SlotRecords (records, image
// counts, index maps), CountedRows (the list rows, and the grid cells), ReferenceGrid, MovedSlots
// (for take_moved); State holds them, with the list upkeep (relist) and the full build.
//
// Hot loop. Picks are drawn a batch ahead (TrialMoveSampler::draw_batch); the picked spheres'
// records and rows are prefetched 16 trials ahead, the records of the first few entries of their
// lists 8 trials ahead (the test exits at the first overlap, after 2.2 entries on average; the
// entry that blocked a trial moves to the front of its row, so that the next trial of that
// sphere checks it first).
// Records, rows and cells live in large-page storage (tapmc_memory.h): with 4 KiB pages the
// random picks of a 262144-sphere bed miss the TLB, and huge pages made that bed 1.3-2.3 times
// faster (bench_mc_settle --scaling, alternating runs). The loop is compiled once per
// combination of mono/poly, periodic axes, region and cylindrical container (dispatched once
// per call), with the
// overlap arithmetic of tapmc_contact.h and tapmc_settle_geometry.h.
#include "tapmc_sphere_mover.h"

#include "tapmc_cell_grid.h"
#include "tapmc_contact.h"
#include "tapmc_defaults.h"
#include "tapmc_memory.h"
#include "tapmc_settle_geometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
namespace tapmc {

using namespace settle_geometry;

namespace {

// The distinct cells next to cell c along one axis (1 to 3: an axis of fewer than 3 periodic
// cells would otherwise visit a cell twice).
int neighbour_cells(const GridAxis &axis, int c, int out[3])
{
  int count = 0;
  for (int o = -1; o <= 1; ++o) {
    int k = c + o;
    if (axis.periodic) k = (k + axis.cells) % axis.cells;
    else if (k < 0 || k >= axis.cells) continue;
    bool seen = false;
    for (int q = 0; q < count; ++q) seen = seen || out[q] == k;
    if (!seen) out[count++] = k;
  }
  return count;
}

inline void prefetch(const void *p) { __builtin_prefetch(p, 0, 3); }

// Sphere records: kRecord doubles (x, y, z, R); reference positions kRecord doubles apart.
constexpr int kRecord = 4;

// Grid cells hold a count and their spheres' slots in rows a multiple of this many ints wide.
constexpr int kCellCapacityStep = 4;

// Rows of one fixed width in large-page storage: row r = its count, then its entries. The
// neighbour lists (a row per slot) and the grid cells (a row per cell) are such rows; a row that
// would overflow widens every row by `step` entries (O(rows), rare).
struct CountedRows {
  int stride = 0;  // ints per row: the count and at most stride - 1 entries
  int step = 0;    // entries added to every row by a widening
  LargeVector<int> data;
  long widenings = 0;

  // `count` empty rows of `width` ints.
  void assign(std::size_t count, int width, int widen_step)
  {
    stride = width;
    step = widen_step;
    data.assign(count * width, 0);
  }
  std::size_t count() const { return data.size() / stride; }
  int *row(int r) { return data.data() + static_cast<std::size_t>(r) * stride; }
  const int *row(int r) const { return data.data() + static_cast<std::size_t>(r) * stride; }

  void append(int r, int entry)
  {
    if (row(r)[0] + 1 >= stride) widen();
    int *x = row(r);
    x[++x[0]] = entry;
  }

  // Removes `entry` from row `x` (the last entry takes its place).
  static void remove(int *x, int entry)
  {
    for (int q = 1; q <= x[0]; ++q)
      if (x[q] == entry) {
        x[q] = x[x[0]--];
        return;
      }
  }

  void widen()
  {
    const int wider = stride + step;
    const std::size_t rows = count();
    LargeVector<int> grown(rows * wider);
    for (std::size_t r = 0; r < rows; ++r) {
      const int *x = data.data() + r * stride;
      std::copy(x, x + x[0] + 1, grown.data() + r * wider);
    }
    data.swap(grown);
    stride = wider;
    ++widenings;
  }
};

// Per internal slot: one 32-byte record of x, y, z, R (half a cache line), which is all a trial
// reads of the picked sphere and of its neighbours; apart from it, the reference position
// (wrapped into the box), read only by the list upkeep of an accepted move; the periods each
// sphere was wrapped by; the maps between the caller's indices and the slots.
struct SlotRecords {
  LargeVector<double> storage, ref_storage;
  double *records = nullptr;  // storage aligned to a record (never across a cache line)
  double *refs = nullptr;     // the reference positions, same layout
  std::vector<int> image;     // periods wrapped along x, y: image[2 s + axis]
  std::vector<int> slot_of, external_of;

  static double *aligned(LargeVector<double> &v, int n)
  {
    v.resize(static_cast<std::size_t>(n) * kRecord + kRecord);
    double *p = v.data();
    while (reinterpret_cast<std::uintptr_t>(p) % (kRecord * sizeof(double)) != 0) ++p;
    return p;
  }
  void allocate(int n)
  {
    records = aligned(storage, n);
    refs = aligned(ref_storage, n);
    image.resize(2 * static_cast<std::size_t>(n));
  }
  double *at(int s) { return records + static_cast<std::size_t>(s) * kRecord; }
  const double *at(int s) const { return records + static_cast<std::size_t>(s) * kRecord; }
  double *ref(int s) { return refs + static_cast<std::size_t>(s) * kRecord; }
  const double *ref(int s) const { return refs + static_cast<std::size_t>(s) * kRecord; }
};

// The grid of the reference positions: cell c = cells.row(c): count, then the slots binned there.
struct ReferenceGrid {
  std::array<GridAxis, 3> axes;
  CountedRows cells;
  std::vector<int> cell_of_slot;  // grid cell of each slot's reference

  int cell_index(const double *p) const
  {
    return (axes[2].cell_of(p[2]) * axes[1].cells + axes[1].cell_of(p[1])) * axes[0].cells +
           axes[0].cell_of(p[0]);
  }

  // Slot s, whose reference is now at p, moves to the cell of p if it left its cell.
  void rebin(int s, const double *p)
  {
    const int c = cell_index(p);
    if (c == cell_of_slot[s]) return;
    CountedRows::remove(cells.row(cell_of_slot[s]), s);
    cells.append(c, s);
    cell_of_slot[s] = c;
  }

  // Calls visit(j) for every slot j binned in the (distinct) cells around p.
  template <class Visit>
  void for_each_around(const double *p, Visit &&visit) const
  {
    int cx[3], cy[3], cz[3];
    const int nx = neighbour_cells(axes[0], axes[0].cell_of(p[0]), cx);
    const int ny = neighbour_cells(axes[1], axes[1].cell_of(p[1]), cy);
    const int nz = neighbour_cells(axes[2], axes[2].cell_of(p[2]), cz);
    for (int a = 0; a < nz; ++a)
      for (int b = 0; b < ny; ++b)
        for (int c = 0; c < nx; ++c)
        {
          const int *cr = cells.row((cz[a] * axes[1].cells + cy[b]) * axes[0].cells + cx[c]);
          for (int q = 1; q <= cr[0]; ++q) visit(cr[q]);
        }
  }
};

// Slots that accepted a move since the last take_moved(), each once (a flag per slot).
struct MovedSlots {
  std::vector<int> slots;
  std::vector<unsigned char> flag;

  void clear(int n)
  {
    slots.clear();
    flag.assign(n, 0);
  }
  void note(int s)
  {
    if (!flag[s]) {
      flag[s] = 1;
      slots.push_back(s);
    }
  }
};

}  // namespace

// The engine's state: the scene, the parts above, and the upkeep of the lists (relist).
struct SphereMover::State {
  Scene scene;  // planes, periodic lengths, tolerance (radii are in the records, not scene.radius)
  int n = 0;
  double skin_over_max_radius = defaults::kListSkinOverRadius;
  double d_max = 0.0, half_skin_sq = 0.0;
  double list_extra = 0.0;  // d_max + skin + rounding margin, added to R_i + R_j

  SlotRecords spheres;
  CountedRows lists;  // row s: the slots of the spheres in reach of slot s (see header)
  ReferenceGrid grid;
  MovedSlots moved;
  long full_builds = 0, local_updates = 0;

  // Scratch of reset / build, kept to avoid reallocation.
  std::vector<double> wrapped;
  std::vector<int> wrapped_image, order_start, cell_ext, pairs;
  // Scratch of run(): slots of the candidates of the current block, a batch of draws and the
  // slots of their picks. The slots stay valid for the candidates prepare_candidates() was
  // given while no build renumbers the slots (build_generation unchanged).
  std::vector<int> candidate_slots;
  std::uint64_t build_generation = 0;  // builds since construction (never reset)
  const int *prepared_candidates = nullptr;
  long prepared_m = 0;
  std::uint64_t prepared_generation = 0;
  std::array<TrialDraw, TrialMoveSampler::kBatchMax> batch{};
  std::array<int, TrialMoveSampler::kBatchMax> batch_slot{};

  // The list predicate over reference positions (symmetric in a, b, bit for bit).
  bool in_reach(int a, int b) const
  {
    const double *pa = spheres.ref(a), *pb = spheres.ref(b);
    const Scene &sc = scene;
    const double dx = sc.periodic[0]
                          ? nearest_separation(pb[0], pa[0], sc.length[0], 0.5 * sc.length[0])
                          : pb[0] - pa[0];
    const double dy = sc.periodic[1]
                          ? nearest_separation(pb[1], pa[1], sc.length[1], 0.5 * sc.length[1])
                          : pb[1] - pa[1];
    const double reach = (spheres.at(a)[3] + spheres.at(b)[3]) + list_extra;
    return distance_sq(dx, dy, pb[2] - pa[2]) < reach * reach;
  }

  // ref_s := the current position of s; the lists and grid follow (local upkeep, see header).
  void relist(int s)
  {
    int *r = lists.row(s);
    for (int q = 1; q <= r[0]; ++q) CountedRows::remove(lists.row(r[q]), s);
    r[0] = 0;
    const double *p = spheres.at(s);
    double *q = spheres.ref(s);
    for (int d = 0; d < 3; ++d) q[d] = p[d];
    grid.rebin(s, q);
    grid.for_each_around(q, [&](int j) {
      if (j != s && in_reach(s, j)) {
        lists.append(s, j);
        lists.append(j, s);
      }
    });
    ++local_updates;
  }

  // Squared displacement of s from its reference (nearest image).
  template <bool PeriodicX, bool PeriodicY>
  double drift_sq(int s) const
  {
    const double *p = spheres.at(s), *q = spheres.ref(s);
    const Scene &sc = scene;
    return distance_sq(axis_separation<PeriodicX>(p[0], q[0], sc.length[0], 0.5 * sc.length[0]),
                       axis_separation<PeriodicY>(p[1], q[1], sc.length[1], 0.5 * sc.length[1]),
                       p[2] - q[2]);
  }

  // The same, with the periodic axes read at run time (set_position, check_lists).
  double drift_sq(int s) const
  {
    const bool px = scene.periodic[0], py = scene.periodic[1];
    return px ? (py ? drift_sq<true, true>(s) : drift_sq<true, false>(s))
              : (py ? drift_sq<false, true>(s) : drift_sq<false, false>(s));
  }

  void build(const double *xyz_wrapped, const double *radius, const int *image_in);
};

// Sorts the spheres into cell order, bins them and makes every list (O(N)).
void SphereMover::State::build(const double *xyz_wrapped, const double *radius,
                               const int *image_in)
{
  const Scene &sc = scene;
  const double margin = rounding_margin(sc, xyz_wrapped, n);
  const double skin = skin_over_max_radius * sc.r_max;
  half_skin_sq = 0.25 * skin * skin;
  list_extra = d_max + skin + margin;
  std::array<GridAxis, 3> &axes = grid.axes;
  axes = grid_axes(sc, xyz_wrapped, n, 2.0 * sc.r_max + list_extra + margin);

  // Internal order: by cell (stable), so neighbours are close in memory.
  const int n_cells = axes[0].cells * axes[1].cells * axes[2].cells;
  order_start.assign(static_cast<std::size_t>(n_cells) + 1, 0);
  cell_ext.resize(n);
  for (int i = 0; i < n; ++i) {
    cell_ext[i] = grid.cell_index(xyz_wrapped + 3 * i);
    ++order_start[cell_ext[i] + 1];
  }
  int fullest = 0;
  for (int c = 0; c < n_cells; ++c) {
    fullest = std::max(fullest, order_start[c + 1]);
    order_start[c + 1] += order_start[c];
  }
  spheres.slot_of.resize(n);
  spheres.external_of.resize(n);
  for (int i = 0; i < n; ++i) {
    const int s = order_start[cell_ext[i]]++;
    spheres.slot_of[i] = s;
    spheres.external_of[s] = i;
  }
  spheres.allocate(n);
  grid.cell_of_slot.resize(n);
  grid.cells.assign(
      static_cast<std::size_t>(n_cells),
      ((fullest + 1 + kCellCapacityStep - 1) / kCellCapacityStep + 1) * kCellCapacityStep,
      kCellCapacityStep);
  for (int s = 0; s < n; ++s) {
    const int i = spheres.external_of[s];
    double *p = spheres.at(s), *q = spheres.ref(s);
    for (int d = 0; d < 3; ++d) p[d] = q[d] = xyz_wrapped[3 * i + d];
    p[3] = radius[i];
    spheres.image[2 * s] = image_in[2 * i];
    spheres.image[2 * s + 1] = image_in[2 * i + 1];
    grid.cell_of_slot[s] = cell_ext[i];
    int *cr = grid.cells.row(cell_ext[i]);
    cr[++cr[0]] = s;
  }

  // Every pair in reach once (j > s), then rows wide enough for the longest list plus slack
  // (widened later only if a list outgrows its row).
  pairs.clear();
  std::vector<int> &count = cell_ext;  // reused: one count per slot
  count.assign(n, 0);
  for (int s = 0; s < n; ++s)
    grid.for_each_around(spheres.ref(s), [&](int j) {
      if (j > s && in_reach(s, j)) {
        pairs.push_back(s);
        pairs.push_back(j);
        ++count[s];
        ++count[j];
      }
    });
  const int longest = n > 0 ? *std::max_element(count.begin(), count.end()) : 0;
  const int step = defaults::kListCapacityStep;
  lists.assign(static_cast<std::size_t>(n),
               ((longest + 1 + defaults::kListSlack + step - 1) / step) * step, step);
  for (std::size_t q = 0; q < pairs.size(); q += 2) {
    int *a = lists.row(pairs[q]), *b = lists.row(pairs[q + 1]);
    a[++a[0]] = pairs[q + 1];
    b[++b[0]] = pairs[q];
  }
  ++full_builds;
  ++build_generation;
}

SphereMover::SphereMover() : state_(std::make_unique<State>()) {}
SphereMover::~SphereMover() = default;

void SphereMover::set_skin(double skin_over_max_radius)
{
  if (!(skin_over_max_radius > 0.0 && std::isfinite(skin_over_max_radius)))
    throw_outside_range("list skin (units of R_max)", skin_over_max_radius, "(0, +inf)");
  state_->skin_over_max_radius = skin_over_max_radius;
}

double SphereMover::skin() const { return state_->skin_over_max_radius; }

void SphereMover::reset(const double *xyz, const double *radius, int n, const SettleBox &box,
                        double d_max, double contact_tol)
{
  State &st = *state_;
  check_contact_tol(contact_tol);
  if (n < 0) throw_outside_range("n", n, "[0, +inf)");
  if (n > 0 && (!xyz || !radius))
    throw std::invalid_argument("xyz and radius must not be null when n > 0");
  if (!(d_max > 0.0 && std::isfinite(d_max))) throw_outside_range("dmax", d_max, "(0, +inf)");
  Scene sc = make_scene(radius, n, box, contact_tol);
  for (int d = 0; d < 2; ++d)
    if (sc.periodic[d] && !(d_max < sc.length[d]))
      throw_outside_range("dmax", d_max,
                          "(0, periodic length) = (0, " + number(sc.length[d]) + ")");
  sc.radius = nullptr;
  st.scene = sc;
  st.n = n;
  st.d_max = d_max;
  st.full_builds = st.local_updates = st.lists.widenings = 0;
  st.moved.clear(n);

  std::vector<double> &wrapped = st.wrapped;
  std::vector<int> &image = st.wrapped_image;
  wrapped.assign(xyz, xyz + 3 * static_cast<std::size_t>(n));
  image.assign(2 * static_cast<std::size_t>(n), 0);
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 2; ++d)
      if (sc.periodic[d])
        wrapped[3 * i + d] =
            wrap_periodic(xyz[3 * i + d], sc.lo[d], sc.hi[d], sc.length[d], image[2 * i + d]);
  st.build(wrapped.data(), radius, image.data());
}

void SphereMover::set_position(int i, const double *xyz)
{
  State &st = *state_;
  if (!(i >= 0 && i < st.n))
    throw_outside_range("sphere index", i, "[0, " + std::to_string(st.n) + ")");
  for (int d = 0; d < 3; ++d)
    if (!std::isfinite(xyz[d]))
      throw_outside_range("position of sphere " + std::to_string(i), xyz[d], "(finite)");
  const Scene &sc = st.scene;
  const int s = st.spheres.slot_of[i];
  double *p = st.spheres.at(s);
  for (int d = 0; d < 3; ++d) p[d] = xyz[d];
  for (int d = 0; d < 2; ++d)
    if (sc.periodic[d]) {
      st.spheres.image[2 * s + d] = 0;
      p[d] = wrap_periodic(xyz[d], sc.lo[d], sc.hi[d], sc.length[d], st.spheres.image[2 * s + d]);
    }
  if (st.drift_sq(s) > st.half_skin_sq) st.relist(s);
}

const double *SphereMover::position(int i) const
{
  return state_->spheres.at(state_->spheres.slot_of[i]);
}

int SphereMover::image_shift(int i, int axis) const
{
  return state_->spheres.image[2 * static_cast<std::size_t>(state_->spheres.slot_of[i]) + axis];
}

long SphereMover::full_builds() const { return state_->full_builds; }
long SphereMover::local_updates() const { return state_->local_updates; }
long SphereMover::capacity_grows() const { return state_->lists.widenings; }

double SphereMover::mean_list_length() const
{
  const State &st = *state_;
  if (st.n == 0) return 0.0;
  double sum = 0.0;
  for (int s = 0; s < st.n; ++s) sum += st.lists.row(s)[0];
  return sum / st.n;
}

std::string SphereMover::check_lists() const
{
  const State &st = *state_;
  const ReferenceGrid &grid = st.grid;
  std::vector<int> times_listed(st.n);
  for (int a = 0; a < st.n; ++a) {
    const std::string sphere = "sphere " + std::to_string(st.spheres.external_of[a]);
    if (st.drift_sq(a) > st.half_skin_sq) return sphere + " is beyond skin/2 of its reference";
    const int cell = grid.cell_of_slot[a];
    if (cell != grid.cell_index(st.spheres.ref(a)))
      return sphere + " is not in the cell of its reference";
    int binned = 0;
    for (std::size_t c = 0; c < grid.cells.count(); ++c) {
      const int *cr = grid.cells.row(static_cast<int>(c));
      for (int q = 1; q <= cr[0]; ++q) binned += cr[q] == a && static_cast<int>(c) == cell;
      for (int q = 1; q <= cr[0]; ++q)
        if (cr[q] == a && static_cast<int>(c) != cell) return sphere + " binned twice";
    }
    if (binned != 1) return sphere + " binned " + std::to_string(binned) + " times";
    std::fill(times_listed.begin(), times_listed.end(), 0);
    const int *r = st.lists.row(a);
    for (int q = 1; q <= r[0]; ++q) ++times_listed[r[q]];
    for (int b = 0; b < st.n; ++b) {
      const int expected = b != a && st.in_reach(a, b) ? 1 : 0;
      if (times_listed[b] != expected)
        return sphere + " lists sphere " + std::to_string(st.spheres.external_of[b]) + " " +
               std::to_string(times_listed[b]) + " times (expected " + std::to_string(expected) +
               ")";
    }
  }
  return "";
}

namespace {

struct RunArgs {
  const int *candidates;
  const int *candidate_slots;  // slots of the candidates, or nullptr (then looked up per trial)
  long m;
  bool random;
  long *sweep_cursor;
  const TrialMoveSampler *sampler;
  const CounterRandom *rng;
  std::uint64_t first_trial;
  long trials;
  const MoveRegion *region;
  TrialTally *tally;
};

}  // namespace

// Does a sphere of radius r at (x, y, z) overlap one of the spheres of list row `row` (nearest
// image)? Flat loop, early exit on the first overlap. The blocker moves to the front of the row:
// a resting sphere's next trials are mostly blocked by the same neighbour (its moves point
// down, onto its supports), which is then checked first, and its record is among those
// prefetched. Any order of the row gives the same answer: only the work changes.
template <bool Mono, bool PeriodicX, bool PeriodicY>
inline bool overlaps_listed(const SphereMover::State &st, int *row, double x, double y, double z,
                            double r, double threshold_sq_mono, double half_x, double half_y)
{
  const Scene &sc = st.scene;
  for (int q = 1, end = row[0]; q <= end; ++q) {
    const int j = row[q];
    const double *pj = st.spheres.at(j);
    const double dx = axis_separation<PeriodicX>(pj[0], x, sc.length[0], half_x);
    const double dy = axis_separation<PeriodicY>(pj[1], y, sc.length[1], half_y);
    const double limit =
        Mono ? threshold_sq_mono : overlap_threshold_sq(r, pj[3], sc.one_minus_tol);
    if (distance_sq(dx, dy, pj[2] - z) < limit) {
      row[q] = row[1];
      row[1] = j;
      return true;
    }
  }
  return false;
}

// The acceptance rule of a trial (section II), compiled per (mono/poly, periodic x, periodic y,
// region, cylindrical container).
template <bool Mono, bool PeriodicX, bool PeriodicY, bool Region, bool Cylinder>
struct TrialRule {
  SphereMover::State &st;
  double r_mono, threshold_sq_mono, half_x, half_y;
  MoveRegion region;

  TrialRule(SphereMover::State &state, const MoveRegion *move_region) :
      st(state), r_mono(state.scene.r_mono),
      threshold_sq_mono(overlap_threshold_sq(r_mono, r_mono, state.scene.one_minus_tol)),
      half_x(0.5 * state.scene.length[0]), half_y(0.5 * state.scene.length[1]),
      region(Region ? *move_region : MoveRegion{})
  {
  }

  // Sphere at record p (slot s) moved by `move`: true when accepted, with the new centre
  // (periodic axes wrapped, wraps counted) in x, y, z.
  bool accepts(const double *p, int s, const Displacement &move, double &x, double &y, double &z,
               int &wrap_x, int &wrap_y) const
  {
    const Scene &sc = st.scene;
    const double r = Mono ? r_mono : p[3];
    x = p[0] + move.dx;
    y = p[1] + move.dy;
    z = p[2] + move.dz;
    wrap_x = wrap_y = 0;
    if (PeriodicX) x = wrap_step(x, sc.lo[0], sc.hi[0], sc.length[0], wrap_x);
    if (PeriodicY) y = wrap_step(y, sc.lo[1], sc.hi[1], sc.length[1], wrap_y);
    if (Region && !(x >= region.lo[0] && x < region.hi[0] && y >= region.lo[1] &&
                    y < region.hi[1] && z >= region.lo[2] && z < region.hi[2]))
      return false;
    double gap;
    if (plane_violation<PeriodicX, PeriodicY>(sc, x, y, z, r, gap)) return false;
    if (Cylinder &&
        !sc.wall.contains(x, y, Mono ? sc.cylinder_reach_sq_mono : sc.wall.reach_sq(r)))
      return false;
    return !overlaps_listed<Mono, PeriodicX, PeriodicY>(st, st.lists.row(s), x, y, z, r,
                                                        threshold_sq_mono, half_x, half_y);
  }
};

// One block of trials, compiled per (mono/poly, periodic x, periodic y, region, cylinder).
template <bool Mono, bool PeriodicX, bool PeriodicY, bool Region, bool Cylinder>
void run_trials(SphereMover::State &st, const RunArgs &a)
{
  SlotRecords &spheres = st.spheres;
  const CountedRows &lists = st.lists;
  const TrialRule<Mono, PeriodicX, PeriodicY, Region, Cylinder> rule(st, a.region);
  const std::uint32_t n_pick = a.random ? static_cast<std::uint32_t>(a.m) : 0u;
  long accepted = 0;
  double sum_dz = a.tally->sum_dz;
  for (long done = 0; done < a.trials;) {
    const int count =
        static_cast<int>(std::min<long>(TrialMoveSampler::kBatchMax, a.trials - done));
    a.sampler->draw_batch(*a.rng, a.first_trial + static_cast<std::uint64_t>(done), count, n_pick,
                          st.batch.data());
    done += count;
    for (int b = 0; b < count; ++b) {
      long k = st.batch[b].pick;
      if (!a.random) {
        k = *a.sweep_cursor;
        if (++*a.sweep_cursor == a.m) *a.sweep_cursor = 0;
      }
      const int s = a.candidate_slots ? a.candidate_slots[k] : spheres.slot_of[a.candidates[k]];
      st.batch_slot[b] = s;
      if (b < defaults::kOwnPrefetchAhead) {
        prefetch(spheres.at(s));
        prefetch(lists.row(s));
      }
    }
    for (int b = 0; b < count; ++b) {
      if (b + defaults::kOwnPrefetchAhead < count) {
        const int later = st.batch_slot[b + defaults::kOwnPrefetchAhead];
        prefetch(spheres.at(later));
        prefetch(lists.row(later));
      }
      if (b + defaults::kNeighbourPrefetchAhead < count) {
        const int *ahead = lists.row(st.batch_slot[b + defaults::kNeighbourPrefetchAhead]);
        const int prefetched = std::min(ahead[0], defaults::kNeighbourPrefetchCount);
        for (int q = 1; q <= prefetched; ++q) prefetch(spheres.at(ahead[q]));
      }
      const int s = st.batch_slot[b];
      double *p = spheres.at(s);
      double x, y, z;
      int wrap_x, wrap_y;
      if (!rule.accepts(p, s, st.batch[b].move, x, y, z, wrap_x, wrap_y)) continue;
      ++accepted;
      sum_dz += z - p[2];  // <Z> kept incrementally, in trial order (section II)
      p[0] = x;
      p[1] = y;
      p[2] = z;
      st.moved.note(s);
      if (PeriodicX && wrap_x) spheres.image[2 * s] += wrap_x;
      if (PeriodicY && wrap_y) spheres.image[2 * s + 1] += wrap_y;
      if (st.drift_sq<PeriodicX, PeriodicY>(s) > st.half_skin_sq) st.relist(s);
    }
  }
  a.tally->trials += a.trials;
  a.tally->accepted += accepted;
  a.tally->sum_dz = sum_dz;
}

namespace {

template <bool Mono, bool PeriodicX, bool PeriodicY, bool Cylinder>
void dispatch_region(SphereMover::State &st, const RunArgs &a)
{
  if (a.region) run_trials<Mono, PeriodicX, PeriodicY, true, Cylinder>(st, a);
  else run_trials<Mono, PeriodicX, PeriodicY, false, Cylinder>(st, a);
}

// A cylindrical container comes only with non-periodic x and y (make_scene).
template <bool Mono>
void dispatch_axes(SphereMover::State &st, const RunArgs &a)
{
  const bool px = st.scene.periodic[0], py = st.scene.periodic[1];
  if (px && py) dispatch_region<Mono, true, true, false>(st, a);
  else if (px) dispatch_region<Mono, true, false, false>(st, a);
  else if (py) dispatch_region<Mono, false, true, false>(st, a);
  else if (st.scene.cylinder) dispatch_region<Mono, false, false, true>(st, a);
  else dispatch_region<Mono, false, false, false>(st, a);
}

}  // namespace

void SphereMover::take_moved(std::vector<Moved> &moved)
{
  State &st = *state_;
  const SlotRecords &spheres = st.spheres;
  moved.clear();
  for (int s : st.moved.slots) {
    const double *p = spheres.at(s);
    moved.push_back({spheres.external_of[s],
                     {spheres.image[2 * static_cast<std::size_t>(s)],
                      spheres.image[2 * static_cast<std::size_t>(s) + 1]},
                     {p[0], p[1], p[2]}});
    st.moved.flag[s] = 0;
  }
  st.moved.slots.clear();
}

namespace {
// The slots of candidates[0 .. m) into st.candidate_slots, each index checked to be a sphere.
void translate_candidates(SphereMover::State &st, const int *candidates, long m)
{
  st.candidate_slots.resize(m);
  int *slots = st.candidate_slots.data();
  const int *slot_of = st.spheres.slot_of.data();
  const int n = st.n;
  for (long k = 0; k < m; ++k) {
    const int c = candidates[k];
    if (!(c >= 0 && c < n))
      throw_outside_range("candidates[" + std::to_string(k) + "]", c,
                          "[0, " + std::to_string(n) + ")");
    slots[k] = slot_of[c];
  }
}
}  // namespace

void SphereMover::prepare_candidates(const int *candidates, long m)
{
  State &st = *state_;
  if (!(m >= 1 && static_cast<std::uint64_t>(m) < (std::uint64_t{1} << 32)))
    throw_outside_range("number of candidates", m, "[1, 2^32)");
  translate_candidates(st, candidates, m);
  st.prepared_candidates = candidates;
  st.prepared_m = m;
  st.prepared_generation = st.build_generation;
}

void SphereMover::run(const int *candidates, long m, PickOrder order, long &sweep_cursor,
                      const TrialMoveSampler &sampler, const CounterRandom &rng,
                      std::uint64_t first_trial, long trials, const MoveRegion *region,
                      TrialTally &tally)
{
  State &st = *state_;
  if (trials <= 0) return;
  if (!(m >= 1 && static_cast<std::uint64_t>(m) < (std::uint64_t{1} << 32)))
    throw_outside_range("number of candidates", m, "[1, 2^32)");
  if (!(sweep_cursor >= 0 && sweep_cursor < m))
    throw_outside_range("sweep_cursor", sweep_cursor, "[0, m)");
  if (sampler.d_max() > st.d_max)
    throw_outside_range("sampler d_max", sampler.d_max(),
                        "(0, " + number(st.d_max) + "] (the d_max of reset)");
  // A block of at least half a sweep translates the candidates to slots once (one pass in
  // order), so a random pick costs one indirection instead of two dependent ones; candidates
  // given to prepare_candidates() were translated there, once for every block.
  const int *candidate_slots = nullptr;
  const bool prepared = candidates == st.prepared_candidates && m == st.prepared_m &&
                        st.build_generation == st.prepared_generation;
  if (prepared) {
    candidate_slots = st.candidate_slots.data();
  } else if (trials >= m / 2) {
    st.prepared_candidates = nullptr;  // the slots below replace the prepared ones
    translate_candidates(st, candidates, m);
    candidate_slots = st.candidate_slots.data();
  }
  const RunArgs args{candidates, candidate_slots, m,      order == PickOrder::Random,
                     &sweep_cursor, &sampler,    &rng,   first_trial,
                     trials,        region,      &tally};
  if (st.scene.mono) dispatch_axes<true>(st, args);
  else dispatch_axes<false>(st, args);
}

}  // namespace tapmc
