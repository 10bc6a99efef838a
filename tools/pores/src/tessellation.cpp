// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The only CGAL translation unit of the pore tool: padded Delaunay triangulation, canonical
// periodic tetrahedra, merged degenerate Voronoi vertices, nearest-centre queries.
#include "tapmc_pores/tessellation.h"
#include "tapmc_pores/errors.h"

#include "tapmc_math.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <set>
#include <sstream>
#include <tuple>
#include <utility>

namespace tapmc {
namespace pores {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using ExactKernel = CGAL::Exact_predicates_exact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, Kernel>;
using CellBase = CGAL::Triangulation_cell_base_with_info_3<std::uint32_t, Kernel>;
using DataStructure = CGAL::Triangulation_data_structure_3<VertexBase, CellBase>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, DataStructure>;
using Point = Kernel::Point_3;
using CellHandle = Delaunay::Cell_handle;

struct Sphere {
  double x, y, z, r;
};

double squared(double v) { return v * v; }

// Circumsphere of a tetrahedron. Well-shaped tetrahedra: the closed formula in double precision
// relative to p0; slivers (config::kSliverRelativeVolume): exact rational arithmetic.
Sphere circumsphere(const Point& p0, const Point& p1, const Point& p2, const Point& p3) {
  const double ax = p1.x() - p0.x(), ay = p1.y() - p0.y(), az = p1.z() - p0.z();
  const double bx = p2.x() - p0.x(), by = p2.y() - p0.y(), bz = p2.z() - p0.z();
  const double cx = p3.x() - p0.x(), cy = p3.y() - p0.y(), cz = p3.z() - p0.z();
  const double bcx = by * cz - bz * cy, bcy = bz * cx - bx * cz, bcz = bx * cy - by * cx;
  const double cax = cy * az - cz * ay, cay = cz * ax - cx * az, caz = cx * ay - cy * ax;
  const double abx = ay * bz - az * by, aby = az * bx - ax * bz, abz = ax * by - ay * bx;
  const double det = ax * bcx + ay * bcy + az * bcz;
  const double a2 = ax * ax + ay * ay + az * az, b2 = bx * bx + by * by + bz * bz,
               c2 = cx * cx + cy * cy + cz * cz;
  Sphere s;
  if (std::abs(det) >= config::kSliverRelativeVolume * std::sqrt(a2 * b2 * c2)) {
    const double scale = 0.5 / det;
    const double ux = (a2 * bcx + b2 * cax + c2 * abx) * scale;
    const double uy = (a2 * bcy + b2 * cay + c2 * aby) * scale;
    const double uz = (a2 * bcz + b2 * caz + c2 * abz) * scale;
    s = {p0.x() + ux, p0.y() + uy, p0.z() + uz, std::sqrt(ux * ux + uy * uy + uz * uz)};
  } else {
    const auto exact = [](const Point& p) { return ExactKernel::Point_3(p.x(), p.y(), p.z()); };
    const ExactKernel::Point_3 c = CGAL::circumcenter(exact(p0), exact(p1), exact(p2), exact(p3));
    s.x = CGAL::to_double(c.x());
    s.y = CGAL::to_double(c.y());
    s.z = CGAL::to_double(c.z());
    s.r = std::sqrt(squared(s.x - p0.x()) + squared(s.y - p0.y()) + squared(s.z - p0.z()));
  }
  return s;
}

double tetrahedron_volume(const Point& p0, const Point& p1, const Point& p2, const Point& p3) {
  const double ax = p1.x() - p0.x(), ay = p1.y() - p0.y(), az = p1.z() - p0.z();
  const double bx = p2.x() - p0.x(), by = p2.y() - p0.y(), bz = p2.z() - p0.z();
  const double cx = p3.x() - p0.x(), cy = p3.y() - p0.y(), cz = p3.z() - p0.z();
  return std::abs(ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx)) / 6.0;
}

std::uint32_t find_root(std::vector<std::uint32_t>& parent, std::uint32_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

}  // namespace

struct Tessellation::Impl {
  Box box;
  PoreOptions options;
  std::vector<std::uint32_t> origin;              // padded point -> input index
  std::vector<std::uint8_t> primary;              // padded point -> 1 if the centre itself (no shift)
  Delaunay triangulation;
  PoreResult result;
  std::vector<std::int64_t> ids;      // atom ids (copied: pores are emitted after construction)
  std::vector<CellHandle> cells;      // finite cells, indexed by their info()
  std::vector<std::uint32_t> grouped; // cells of degenerate clusters, consecutive per cluster
  // A kept pore: one cell (size 1, begin = cell index) or grouped[begin, begin + size).
  struct Kept {
    std::uint32_t begin, size;
  };
  std::vector<Kept> kept_pores;

  static Sphere sphere_of(const CellHandle& c) {
    return circumsphere(c->vertex(0)->point(), c->vertex(1)->point(), c->vertex(2)->point(), c->vertex(3)->point());
  }
  static double volume_of(const CellHandle& c) {
    return tetrahedron_volume(c->vertex(0)->point(), c->vertex(1)->point(), c->vertex(2)->point(),
                              c->vertex(3)->point());
  }
  Pore make_pore(const Kept& kept) const;
  std::array<double, 3> wrapped(double x, double y, double z) const {
    std::array<double, 3> p{{x, y, z}};
    for (int d = 0; d < 3; ++d)
      if (box.periodic[d]) p[d] = wrap_periodic(p[d], box.lo[d], box.hi[d]);
    return p;
  }
  bool in_focus(const Sphere& s) const {
    const auto p = wrapped(s.x, s.y, s.z);
    for (int d = 0; d < 3; ++d)
      if (p[d] < options.focus_lo[d] || p[d] >= options.focus_hi[d]) return false;  // as Region::contains
    return true;
  }
  // A cell unresolved at this padding asks for a wider one when its pore is centred in the
  // selection, or in a triply periodic box, whose cells must all tile it: a cell outside the
  // selection that never asked stopped the run, or not, depending on which periodic copy the
  // canonical rule kept (so on the atoms' order).
  bool may_widen_padding(const Sphere& s) const {
    return (box.periodic[0] && box.periodic[1] && box.periodic[2]) || in_focus(s);
  }
  void build(const std::vector<double>& xyz, double padding, double previous);
  // Throws OverlapError for centres (or images) at one position, which the triangulation merges.
  void refuse_coincident(const std::vector<double>& xyz, const std::vector<std::pair<Point, std::uint32_t>>& points) const;
  // Closest pair of centres seen on the Delaunay edges of the current attempt (padded indices).
  struct ClosestPair {
    double d2 = std::numeric_limits<double>::infinity();
    std::uint32_t a = 0, b = 0;
  } closest;
  void check_overlaps(const CellHandle& cell, double contact2);
  void refuse_overlaps(double contact) const;
  // Finds the pores; unless final_attempt, returns early (result.retry_padding > 0) as soon as
  // it is known that a wider padding is needed.
  void find_pores(double padding, double max_padding, bool final_attempt);

  // The steps of find_pores.
  std::vector<std::uint32_t> parent;      // cell -> union-find parent (degenerate clusters)
  std::vector<std::uint8_t> clustered;    // cell -> 1 if merged with a neighbour
  void index_cells();
  void scan_cells(double padding, double max_padding, bool final_attempt, double contact);
  void merge_with_neighbours(std::uint32_t i, const Sphere& a);
  void group_clusters();
  void keep_pore(const std::uint32_t* first, const std::uint32_t* last, Kept kept, double padding, double max_padding);
  // The padded point of the lowest input index among the vertices of cells [first, last).
  struct Canonical {
    std::uint32_t origin, point;
  };
  Canonical canonical_vertex(const std::uint32_t* first, const std::uint32_t* last) const;
  // How far the empty sphere `s` reaches beyond the periodic faces (0 when inside the box).
  double padding_needed(const Sphere& s) const;
};

// Adds the images within `padding` of the periodic faces that are not already there (those within
// `previous` of them; previous < 0: start from scratch with the centres themselves).
void Tessellation::Impl::build(const std::vector<double>& xyz, double padding, double previous) {
  const std::size_t n = xyz.size() / 3;
  std::array<int, 3> images{{0, 0, 0}};
  for (int d = 0; d < 3; ++d) {
    if (!box.periodic[d]) continue;
    // Compared before the conversion: a count beyond int (padding 1e15) used to wrap around.
    const double layers = std::ceil(padding / box.length(d));
    if (!(layers <= 100))
      throw std::invalid_argument("padding " + message_number(padding) +
                                  " is over 100 box lengths: the periodic box is far too small for R");
    images[d] = static_cast<int>(layers);
  }
  const bool fresh = previous < 0;
  if (fresh) {
    origin.clear();
    primary.clear();
    triangulation.clear();
  }
  auto within = [&](const double* q, const int* s, double margin) {
    for (int d = 0; d < 3; ++d)
      if (s[d] != 0 && !(q[d] >= box.lo[d] - margin && q[d] < box.hi[d] + margin)) return false;
    return true;
  };
  std::vector<std::pair<Point, std::uint32_t>> points;
  points.reserve(fresh ? n + n / 4 : n / 8);
  for (std::size_t i = 0; i < n; ++i) {
    const double* p = &xyz[3 * i];
    for (int sx = -images[0]; sx <= images[0]; ++sx)
      for (int sy = -images[1]; sy <= images[1]; ++sy)
        for (int sz = -images[2]; sz <= images[2]; ++sz) {
          const int s[3] = {sx, sy, sz};
          const bool is_primary = sx == 0 && sy == 0 && sz == 0;
          if (!fresh && is_primary) continue;
          double q[3];
          for (int d = 0; d < 3; ++d) q[d] = s[d] == 0 ? p[d] : p[d] + s[d] * box.length(d);
          if (!within(q, s, padding) || (!fresh && within(q, s, previous))) continue;
          points.emplace_back(Point(q[0], q[1], q[2]), static_cast<std::uint32_t>(origin.size()));
          origin.push_back(static_cast<std::uint32_t>(i));
          primary.push_back(is_primary ? 1 : 0);
        }
  }
  if (origin.size() >= std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("too many centres with their periodic images (" + std::to_string(origin.size()) + ")");
  const std::size_t vertices = triangulation.number_of_vertices();
  triangulation.insert(points.begin(), points.end());  // spatially sorted insertion
  // CGAL keeps one vertex per position: a centre at exactly another's position would vanish
  // silently, where one 1e-9 away is refused as an overlap.
  if (triangulation.number_of_vertices() - vertices < points.size()) refuse_coincident(xyz, points);
}

void Tessellation::Impl::refuse_coincident(const std::vector<double>& xyz,
                                           const std::vector<std::pair<Point, std::uint32_t>>& points) const {
  std::vector<std::uint8_t> has_vertex(origin.size(), 0);
  for (auto v = triangulation.finite_vertices_begin(); v != triangulation.finite_vertices_end(); ++v)
    has_vertex[v->info()] = 1;
  // The inputs of each coinciding pair, reported for the lowest pair, preferably two centres
  // rather than images only (a duplicated sphere also duplicates its images).
  std::set<std::pair<std::uint32_t, std::uint32_t>> pairs;
  bool found = false;
  std::tuple<bool, std::uint32_t, std::uint32_t> first{};  // (images only, ia, ib) of the lowest
  std::array<double, 3> position{};
  for (const auto& [point, index] : points) {
    if (has_vertex[index]) continue;
    const std::uint32_t other = triangulation.nearest_vertex(point)->info();  // at the same position
    const std::uint32_t a = std::min(origin[index], origin[other]), b = std::max(origin[index], origin[other]);
    pairs.emplace(a, b);
    const bool images_only = !primary[index] && !primary[other];
    const std::tuple<bool, std::uint32_t, std::uint32_t> key{images_only, a, b};
    if (found && !(key < first)) continue;
    found = true;
    first = key;
    const std::uint32_t centre = primary[index] ? origin[index] : origin[other];
    position = images_only ? wrapped(point.x(), point.y(), point.z())
                           : std::array<double, 3>{{xyz[3 * centre], xyz[3 * centre + 1], xyz[3 * centre + 2]}};
  }
  const auto [images_only, ia, ib] = first;
  const double diameter = 2.0 * options.radius, contact = diameter * (1.0 - options.overlap_tolerance);
  std::ostringstream what;
  what.precision(10);
  if (ia == ib) {
    what << "sphere " << ids[ia] << " coincides with its own periodic image at (" << position[0] << ", " << position[1]
         << ", " << position[2] << "): a periodic box length vanishes next to the coordinates";
  } else {
    what << "spheres " << ids[ia] << " and " << ids[ib] << " overlap by 100 % of a diameter (centre distance 0, 2R = "
         << diameter << "): both " << (images_only ? "have a periodic image" : "are") << " at (" << position[0] << ", "
         << position[1] << ", " << position[2] << ")";
    if (pairs.size() > 1) what << ", the first of " << pairs.size() << " coinciding pairs";
    what << "; pairs closer than 2R (1 - " << options.overlap_tolerance << ") = " << contact
         << " are refused: the pore of a tangent empty sphere needs hard spheres";
  }
  throw OverlapError(what.str(), ia, ib, 0.0, contact, 1.0, pairs.size());
}

void Tessellation::Impl::check_overlaps(const CellHandle& c, double contact2) {
  // The closest pair is a Delaunay edge, so the deepest overlap is found on the edges that touch
  // a primary centre, across periodic boundaries included.
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) {
      const auto va = c->vertex(a), vb = c->vertex(b);
      const std::uint32_t pa = va->info(), pb = vb->info();
      if (!primary[pa] && !primary[pb]) continue;
      const double d2 = CGAL::squared_distance(va->point(), vb->point());
      if (d2 >= closest.d2) continue;
      if (origin[pa] == origin[pb] && d2 < contact2) {
        std::ostringstream what;
        what.precision(10);
        what << "sphere " << ids[origin[pa]] << " overlaps its own periodic image: a periodic box length "
             << std::sqrt(d2) << " is below the threshold 2R (1 - " << options.overlap_tolerance
             << ") = " << std::sqrt(contact2);
        throw OverlapError(what.str(), origin[pa], origin[pb], std::sqrt(d2), std::sqrt(contact2),
                           1.0 - std::sqrt(d2) / (2.0 * options.radius), 1);
      }
      closest = {d2, pa, pb};
    }
}

// Throws OverlapError for the closest pair when it is closer than the threshold.
void Tessellation::Impl::refuse_overlaps(double contact) const {
  if (!(closest.d2 < contact * contact)) return;
  // Rare path: count the overlapping pairs (each once, images of one pair included once).
  std::set<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (auto e = triangulation.finite_edges_begin(); e != triangulation.finite_edges_end(); ++e) {
    const auto va = e->first->vertex(e->second), vb = e->first->vertex(e->third);
    const std::uint32_t pa = va->info(), pb = vb->info();
    if ((!primary[pa] && !primary[pb]) || origin[pa] == origin[pb]) continue;
    if (CGAL::squared_distance(va->point(), vb->point()) < contact * contact)
      pairs.emplace(std::min(origin[pa], origin[pb]), std::max(origin[pa], origin[pb]));
  }
  const std::size_t ia = std::min(origin[closest.a], origin[closest.b]), ib = std::max(origin[closest.a], origin[closest.b]);
  const double distance = std::sqrt(closest.d2), diameter = 2.0 * options.radius;
  const double depth = 1.0 - distance / diameter;
  std::ostringstream what;
  what.precision(6);
  what << "spheres " << ids[ia] << " and " << ids[ib] << " overlap by " << 100.0 * depth
       << " % of a diameter (centre distance " << distance << ", 2R = " << diameter
       << "), the deepest of " << pairs.size() << " overlapping pair" << (pairs.size() == 1 ? "" : "s")
       << "; pairs closer than 2R (1 - " << options.overlap_tolerance << ") = " << contact
       << " are refused: the pore of a tangent empty sphere needs hard spheres";
  throw OverlapError(what.str(), ia, ib, distance, contact, depth, pairs.size());
}

Tessellation::Impl::Canonical Tessellation::Impl::canonical_vertex(const std::uint32_t* first,
                                                                   const std::uint32_t* last) const {
  Canonical lowest{std::numeric_limits<std::uint32_t>::max(), 0};
  for (const std::uint32_t* c = first; c != last; ++c)
    for (int k = 0; k < 4; ++k) {
      const std::uint32_t p = cells[*c]->vertex(k)->info();
      if (origin[p] < lowest.origin) lowest = {origin[p], p};
    }
  return lowest;
}

double Tessellation::Impl::padding_needed(const Sphere& s) const {
  double needed = 0.0;
  const double centre[3] = {s.x, s.y, s.z};
  for (int d = 0; d < 3; ++d)
    if (box.periodic[d]) needed = std::max({needed, box.lo[d] - (centre[d] - s.r), centre[d] + s.r - box.hi[d]});
  return needed;
}

void Tessellation::Impl::index_cells() {
  cells.clear();
  cells.reserve(7 * triangulation.number_of_vertices());
  for (auto c = triangulation.finite_cells_begin(); c != triangulation.finite_cells_end(); ++c) {
    c->info() = static_cast<std::uint32_t>(cells.size());
    cells.push_back(c);
  }
}

// Degenerate Voronoi vertices: union face-adjacent tetrahedra with one common empty sphere.
// Necessary condition first (cheap, no storage): the neighbour's opposite vertex lies on this
// sphere within 2 tol (triangle inequality); only then compare the two circumspheres.
void Tessellation::Impl::merge_with_neighbours(std::uint32_t i, const Sphere& a) {
  const double tolerance = options.merge_tolerance * options.radius;
  const CellHandle& c = cells[i];
  for (int k = 0; k < 4; ++k) {
    const CellHandle neighbour = c->neighbor(k);
    if (triangulation.is_infinite(neighbour)) continue;
    const std::uint32_t j = neighbour->info();
    if (j <= i) continue;
    const Point& apex = neighbour->vertex(neighbour->index(c))->point();
    const double off = std::sqrt(squared(apex.x() - a.x) + squared(apex.y() - a.y) + squared(apex.z() - a.z)) - a.r;
    if (std::abs(off) > 2.0 * tolerance + 1e-14 * a.r) continue;
    const Sphere b = sphere_of(neighbour);
    if (std::abs(a.r - b.r) < tolerance &&
        squared(a.x - b.x) + squared(a.y - b.y) + squared(a.z - b.z) < tolerance * tolerance) {
      const std::uint32_t ri = find_root(parent, i), rj = find_root(parent, j);
      if (ri != rj) parent[std::max(ri, rj)] = std::min(ri, rj);
      clustered[i] = clustered[j] = 1;
    }
  }
}

// One pass over the cells: overlaps, the padding wanted (unless final_attempt), degenerate clusters.
void Tessellation::Impl::scan_cells(double padding, double max_padding, bool final_attempt, double contact) {
  const std::size_t count = cells.size();
  parent.resize(count);
  std::iota(parent.begin(), parent.end(), 0u);
  clustered.assign(count, 0);
  // Software prefetch of the neighbour cells and vertices a few cells ahead hides most of this
  // loop's cache misses (the neighbour test was a third of the pore time without it).
  constexpr std::size_t kPrefetchFar = 16;
  for (std::uint32_t i = 0; i < count; ++i) {
    if (i + kPrefetchFar < count) {
      const CellHandle& ahead = cells[i + kPrefetchFar];
      for (int k = 0; k < 4; ++k) {
        __builtin_prefetch(&*ahead->neighbor(k));
        __builtin_prefetch(&*ahead->vertex(k));
      }
    }
    check_overlaps(cells[i], contact * contact);
    const Sphere a = sphere_of(cells[i]);
    // Padding check on the cell's own canonical copy: if some pore needs a wider padding, the
    // caller inserts more images and comes back, so the rest of this pass would be wasted.
    if (!final_attempt && primary[canonical_vertex(&i, &i + 1).point]) {
      const double needed = padding_needed(a);
      if (needed > padding && needed <= max_padding && may_widen_padding(a))
        result.retry_padding = std::max(result.retry_padding, needed);
    }
    merge_with_neighbours(i, a);
  }
}

// The cells of multi-tetrahedron clusters in `grouped`, consecutive per cluster (by root).
void Tessellation::Impl::group_clusters() {
  grouped.clear();
  for (std::size_t i = 0; i < cells.size(); ++i)
    if (clustered[i]) {
      parent[i] = find_root(parent, static_cast<std::uint32_t>(i));
      grouped.push_back(static_cast<std::uint32_t>(i));
    }
  std::stable_sort(grouped.begin(), grouped.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return parent[a] < parent[b]; });
}

// Keeps each periodic cluster of cells [first, last) once: the copy whose lowest-index centre is
// the primary one (image shift 0). A canonical vertex rule, independent of rounding of circumcentres.
void Tessellation::Impl::keep_pore(const std::uint32_t* first, const std::uint32_t* last, Kept kept, double padding,
                                   double max_padding) {
  const Canonical canonical = canonical_vertex(first, last);
  if (!primary[canonical.point]) return;
  // Exact iff every empty sphere of the cluster fits in the padded slab; `needed` is the
  // padding that would make it fit.
  double needed = 0.0;
  for (const std::uint32_t* c = first; c != last; ++c) needed = std::max(needed, padding_needed(sphere_of(cells[*c])));
  if (needed > padding) {
    ++result.unresolved;
    // Resolvable with a wider padding (up to max_padding): ask for a retry. Wider cells are
    // hull cells open towards a wall or a free surface (not pores of the packing).
    const Sphere head = sphere_of(cells[*first]);
    if (in_focus(head)) ++result.unresolved_in_focus;
    if (needed <= max_padding && may_widen_padding(head))
      result.retry_padding = std::max(result.retry_padding, needed);
    return;
  }
  for (const std::uint32_t* c = first; c != last; ++c)
    for (int k = 0; k < 4; ++k) {
      const std::uint32_t p = cells[*c]->vertex(k)->info();
      if (origin[p] == canonical.origin && p != canonical.point)
        throw std::runtime_error("periodic box too small: sphere " + std::to_string(ids[canonical.origin]) +
                                 " and its own image bound one pore (a periodic length is below the pore diameter)");
    }
  for (const std::uint32_t* c = first; c != last; ++c) result.tetrahedra_volume += volume_of(cells[*c]);
  result.tetrahedra += static_cast<std::size_t>(last - first);
  kept_pores.push_back(kept);
}

void Tessellation::Impl::find_pores(double padding, double max_padding, bool final_attempt) {
  result = PoreResult{};
  result.padding = padding;
  closest = ClosestPair{};
  index_cells();
  const double contact = 2.0 * options.radius * (1.0 - options.overlap_tolerance);
  scan_cells(padding, max_padding, final_attempt, contact);
  refuse_overlaps(contact);
  if (result.retry_padding > 0) return;  // not the final attempt: more images first
  group_clusters();
  kept_pores.clear();
  const std::uint32_t count = static_cast<std::uint32_t>(cells.size());
  const std::size_t primaries = static_cast<std::size_t>(std::count(primary.begin(), primary.end(), 1));
  kept_pores.reserve(static_cast<std::size_t>(config::kKeptPoresHeadroom * count * primaries /
                                              std::max<std::size_t>(1, primary.size())) + 16);
  for (std::uint32_t i = 0; i < count; ++i)
    if (!clustered[i]) keep_pore(&i, &i + 1, Kept{i, 1}, padding, max_padding);
  for (std::size_t begin = 0; begin < grouped.size();) {
    std::size_t end = begin + 1;
    while (end < grouped.size() && parent[grouped[end]] == parent[grouped[begin]]) ++end;
    keep_pore(grouped.data() + begin, grouped.data() + end,
              Kept{static_cast<std::uint32_t>(begin), static_cast<std::uint32_t>(end - begin)}, padding, max_padding);
    begin = end;
  }
  result.pore_count = kept_pores.size();
}

Pore Tessellation::Impl::make_pore(const Kept& kept) const {
  const std::uint32_t* first = kept.size == 1 ? &kept.begin : grouped.data() + kept.begin;
  const CellHandle& head = cells[*first];
  const Sphere s = sphere_of(head);
  Pore pore;
  pore.centre = wrapped(s.x, s.y, s.z);
  pore.xi = (s.r - options.radius) / options.radius;
  for (int k = 0; k < 4; ++k) pore.ids[k] = ids[origin[head->vertex(k)->info()]];
  std::sort(pore.ids.begin(), pore.ids.end());
  pore.tetrahedra = static_cast<int>(kept.size);
  for (std::uint32_t c = 0; c < kept.size; ++c) pore.volume += volume_of(cells[first[c]]);
  return pore;
}

Tessellation::Tessellation(const Box& box, const std::vector<double>& xyz, const std::vector<std::int64_t>& ids,
                           const PoreOptions& options)
    : impl_(std::make_unique<Impl>()) {
  if (!(options.radius > 0) || !std::isfinite(options.radius))
    throw std::invalid_argument("radius must be positive and finite, got " + message_number(options.radius));
  if (!(options.merge_tolerance >= 0 && options.merge_tolerance < 0.1))
    throw std::invalid_argument("merge tolerance must be in [0, 0.1), got " + message_number(options.merge_tolerance));
  if (!(options.overlap_tolerance >= 0 && options.overlap_tolerance < 1))
    throw std::invalid_argument("overlap tolerance must be in [0, 1), got " + message_number(options.overlap_tolerance));
  if (!(options.padding_over_radius >= config::kMinPaddingOverRadius))
    throw std::invalid_argument("padding must be at least " + message_number(config::kMinPaddingOverRadius) +
                                " R, got " + message_number(options.padding_over_radius));
  if (xyz.size() != 3 * ids.size())
    throw std::invalid_argument("xyz holds " + std::to_string(xyz.size()) + " values for " +
                                std::to_string(ids.size()) + " ids (expected 3 per id)");
  if (ids.size() < 4 && !(box.periodic[0] || box.periodic[1] || box.periodic[2]))
    throw std::invalid_argument("at least 4 centres are needed for a tetrahedron, got " + std::to_string(ids.size()));
  if (ids.empty()) throw std::invalid_argument("no centres given");
  impl_->box = box;
  impl_->options = options;
  impl_->ids = ids;
  double padding = options.padding_over_radius * options.radius;
  const double max_padding = padding * std::pow(2.0, options.max_padding_retries);
  double triangulation_seconds = 0, pore_seconds = 0;
  double previous = -1.0;
  for (int attempt = 0;; ++attempt) {
    const auto start = std::chrono::steady_clock::now();
    impl_->build(xyz, padding, previous);  // a retry only inserts the extra layer of images
    const auto built = std::chrono::steady_clock::now();
    impl_->find_pores(padding, max_padding, attempt >= options.max_padding_retries);
    triangulation_seconds += std::chrono::duration<double>(built - start).count();
    pore_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - built).count();
    impl_->result.attempts = attempt + 1;
    // Very sparse periodic input can leave whole regions without any cell (nothing to flag as
    // unresolved): a flat triangulation, or a triply periodic box not tiled by the kept cells.
    const PoreResult& r = impl_->result;
    const bool all_periodic = box.periodic[0] && box.periodic[1] && box.periodic[2];
    const bool untiled = all_periodic && std::abs(r.tetrahedra_volume - box.volume()) > 1e-9 * box.volume();
    const bool flat = impl_->triangulation.dimension() < 3;
    const bool final_attempt = attempt >= options.max_padding_retries;
    if (final_attempt && flat)
      throw std::runtime_error("the centres span no volume (a " + std::to_string(impl_->triangulation.dimension()) +
                               "-dimensional set): there are no Delaunay tetrahedra, hence no pores");
    // Triply periodic: every cell is a pore of the packing, so none may stay unresolved, whether
    // the retries ran out or no larger padding would resolve the cells left.
    const bool stopping =
        final_attempt || (r.retry_padding <= 0 && !flat && !(untiled && r.unresolved == 0));
    // No cell left unresolved, yet the box untiled: the cells lost are those that a sphere and
    // its own image bound (a periodic length below a pore's diameter) at every padding tried.
    if (stopping && all_periodic && untiled && r.unresolved == 0)
      throw std::runtime_error("the cells cover " + message_number(r.tetrahedra_volume) + " of the box volume " +
                               message_number(box.volume()) + " with none unresolved at the padding " +
                               message_number(padding) + ": a periodic length is likely below a pore's diameter (a "
                               "sphere and its own image bound one pore; the box is too small for its spheres), "
                               "else raise --padding");
    if (stopping && all_periodic && (untiled || r.unresolved > 0))
      throw std::runtime_error("the packing is too sparse for the padding " + message_number(padding) + " (" +
                               std::to_string(r.unresolved) + " cells unresolved, cells cover " +
                               message_number(r.tetrahedra_volume) + " of the box volume " +
                               message_number(box.volume()) + "); raise --padding");
    if (stopping) break;
    previous = padding;
    padding = std::min(max_padding, std::max({config::kRetryPaddingMargin * r.retry_padding,
                                              config::kMinPaddingGrowth * padding,
                                              (flat || untiled) ? max_padding : 0.0}));
  }
  impl_->result.triangulation_seconds = triangulation_seconds;
  impl_->result.pore_seconds = pore_seconds;
}

Tessellation::~Tessellation() = default;

const PoreResult& Tessellation::result() const { return impl_->result; }

void Tessellation::for_each_pore(const std::function<void(const Pore&)>& visit) const {
  for (const auto& kept : impl_->kept_pores) visit(impl_->make_pore(kept));
}

std::vector<Pore> Tessellation::pores() const {
  std::vector<Pore> all;
  all.reserve(impl_->kept_pores.size());
  for_each_pore([&](const Pore& pore) { all.push_back(pore); });
  return all;
}

std::vector<double> Tessellation::nearest_centre_distances(const std::vector<double>& points) const {
  if (points.size() % 3 != 0)
    throw std::invalid_argument("points must hold 3 coordinates per point, got " + std::to_string(points.size()));
  const std::size_t count = points.size() / 3;
  std::vector<double> distances(count);
  // Query in a coarse grid order so that each answer is a good hint for the next one.
  const Box& box = impl_->box;
  const double cells_per_side = std::max(1.0, std::cbrt(static_cast<double>(count)) / 2);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> order(count);
  for (std::size_t i = 0; i < count; ++i) {
    std::uint64_t key = 0;
    for (int d = 0; d < 3; ++d) {
      const double t = (points[3 * i + d] - box.lo[d]) / box.length(d);
      key = key * 4096 + static_cast<std::uint64_t>(std::clamp(t * cells_per_side, 0.0, 4095.0));
    }
    order[i] = {key, static_cast<std::uint32_t>(i)};
  }
  std::sort(order.begin(), order.end());
  Delaunay::Vertex_handle hint;
  for (const auto& entry : order) {
    const std::size_t i = entry.second;
    const Point q(points[3 * i], points[3 * i + 1], points[3 * i + 2]);
    const Delaunay::Vertex_handle v =
        hint == Delaunay::Vertex_handle() ? impl_->triangulation.nearest_vertex(q)
                                          : impl_->triangulation.nearest_vertex(q, hint->cell());
    distances[i] = std::sqrt(CGAL::squared_distance(q, v->point()));
    hint = v;
  }
  return distances;
}

}  // namespace pores
}  // namespace tapmc
