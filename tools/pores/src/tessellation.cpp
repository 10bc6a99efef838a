// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The only CGAL translation unit of the pore tool: padded Delaunay triangulation, canonical
// periodic tetrahedra, merged degenerate Voronoi vertices, nearest-centre queries.
#include "tapmc_pores/tessellation.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
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
  const std::vector<std::int64_t>* ids = nullptr;
  std::vector<std::uint32_t> origin;              // padded point -> input index
  std::vector<std::array<std::int8_t, 3>> shift;  // padded point -> image shift (box lengths)
  Delaunay triangulation;
  PoreResult result;

  void build(const std::vector<double>& xyz, double padding);
  void check_overlaps(const std::vector<CellHandle>& cells) const;
  void find_pores(double padding);
};

void Tessellation::Impl::build(const std::vector<double>& xyz, double padding) {
  const std::size_t n = xyz.size() / 3;
  std::array<int, 3> images{{0, 0, 0}};
  for (int d = 0; d < 3; ++d)
    if (box.periodic[d]) images[d] = static_cast<int>(std::ceil(padding / box.length(d)));
  if (std::max({images[0], images[1], images[2]}) > 100)
    throw std::invalid_argument("padding " + std::to_string(padding) +
                                " is over 100 box lengths: the periodic box is far too small for R");

  std::vector<std::pair<Point, std::uint32_t>> points;
  points.reserve(n + n / 4);
  origin.clear();
  shift.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const double* p = &xyz[3 * i];
    for (int sx = -images[0]; sx <= images[0]; ++sx)
      for (int sy = -images[1]; sy <= images[1]; ++sy)
        for (int sz = -images[2]; sz <= images[2]; ++sz) {
          const int s[3] = {sx, sy, sz};
          double q[3];
          bool inside = true;
          for (int d = 0; d < 3 && inside; ++d) {
            q[d] = s[d] == 0 ? p[d] : p[d] + s[d] * box.length(d);
            if (s[d] != 0) inside = q[d] >= box.lo[d] - padding && q[d] < box.hi[d] + padding;
          }
          if (!inside) continue;
          points.emplace_back(Point(q[0], q[1], q[2]), static_cast<std::uint32_t>(origin.size()));
          origin.push_back(static_cast<std::uint32_t>(i));
          shift.push_back({static_cast<std::int8_t>(sx), static_cast<std::int8_t>(sy), static_cast<std::int8_t>(sz)});
        }
  }
  if (points.size() >= std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("too many centres with their periodic images (" + std::to_string(points.size()) + ")");
  triangulation.clear();
  triangulation.insert(points.begin(), points.end());  // spatially sorted insertion
}

void Tessellation::Impl::check_overlaps(const std::vector<CellHandle>& cells) const {
  // The closest pair is a Delaunay edge, so checking edges that touch a primary centre finds
  // every overlap, across periodic boundaries included.
  const double contact = 2.0 * options.radius * (1.0 - options.overlap_tolerance);
  const double contact2 = contact * contact;
  for (const CellHandle& c : cells) {
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        const auto va = c->vertex(a), vb = c->vertex(b);
        const std::uint32_t pa = va->info(), pb = vb->info();
        const bool primary_a = shift[pa] == std::array<std::int8_t, 3>{{0, 0, 0}};
        const bool primary_b = shift[pb] == std::array<std::int8_t, 3>{{0, 0, 0}};
        if (!primary_a && !primary_b) continue;
        const double d2 = CGAL::squared_distance(va->point(), vb->point());
        if (d2 < contact2) {
          const std::size_t ia = origin[pa], ib = origin[pb];
          std::ostringstream what;
          what.precision(10);
          if (ia == ib) {
            what << "sphere " << (*ids)[ia] << " overlaps its own periodic image (box length below 2R)";
          } else {
            what << "spheres " << (*ids)[ia] << " and " << (*ids)[ib] << " overlap: centre distance "
                 << std::sqrt(d2) << " < 2R = " << 2.0 * options.radius
                 << " (tolerance " << options.overlap_tolerance
                 << " of a diameter; the pore of a tangent empty sphere needs hard spheres)";
          }
          throw OverlapError(what.str(), ia, ib);
        }
      }
  }
}

void Tessellation::Impl::find_pores(double padding) {
  result = PoreResult{};
  result.padding = padding;
  std::vector<CellHandle> cells;
  cells.reserve(7 * triangulation.number_of_vertices());
  for (auto c = triangulation.finite_cells_begin(); c != triangulation.finite_cells_end(); ++c) {
    c->info() = static_cast<std::uint32_t>(cells.size());
    cells.push_back(c);
  }
  check_overlaps(cells);
  const std::size_t count = cells.size();

  std::vector<Sphere> spheres(count);
  for (std::size_t i = 0; i < count; ++i) {
    const CellHandle& c = cells[i];
    spheres[i] = circumsphere(c->vertex(0)->point(), c->vertex(1)->point(), c->vertex(2)->point(),
                              c->vertex(3)->point());
  }

  // Degenerate Voronoi vertices: union face-adjacent tetrahedra with one common empty sphere.
  const double tolerance = options.merge_tolerance * options.radius;
  std::vector<std::uint32_t> parent(count);
  std::iota(parent.begin(), parent.end(), 0u);
  for (std::size_t i = 0; i < count; ++i) {
    for (int k = 0; k < 4; ++k) {
      const CellHandle neighbour = cells[i]->neighbor(k);
      if (triangulation.is_infinite(neighbour)) continue;
      const std::uint32_t j = neighbour->info();
      if (j <= i) continue;
      const Sphere &a = spheres[i], &b = spheres[j];
      if (std::abs(a.r - b.r) < tolerance &&
          squared(a.x - b.x) + squared(a.y - b.y) + squared(a.z - b.z) < tolerance * tolerance) {
        const std::uint32_t ri = find_root(parent, static_cast<std::uint32_t>(i)), rj = find_root(parent, j);
        if (ri != rj) parent[std::max(ri, rj)] = std::min(ri, rj);
      }
    }
  }
  std::vector<std::uint32_t> members(count, 0);  // cluster size, indexed by root
  for (std::size_t i = 0; i < count; ++i) {
    parent[i] = find_root(parent, static_cast<std::uint32_t>(i));
    ++members[parent[i]];
  }
  std::vector<std::uint32_t> grouped;  // cells of multi-tetrahedron clusters, grouped by root
  for (std::size_t i = 0; i < count; ++i)
    if (members[parent[i]] > 1) grouped.push_back(static_cast<std::uint32_t>(i));
  std::stable_sort(grouped.begin(), grouped.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return parent[a] < parent[b]; });

  // Keep each periodic cluster once: the copy whose lowest-index centre is the primary one
  // (image shift 0). A canonical vertex rule, independent of rounding of circumcentres.
  const std::array<std::int8_t, 3> primary{{0, 0, 0}};
  auto process = [&](const std::uint32_t* first, const std::uint32_t* last) {
    std::uint32_t min_origin = std::numeric_limits<std::uint32_t>::max(), min_point = 0;
    for (const std::uint32_t* c = first; c != last; ++c)
      for (int k = 0; k < 4; ++k) {
        const std::uint32_t p = cells[*c]->vertex(k)->info();
        if (origin[p] < min_origin) min_origin = origin[p], min_point = p;
      }
    if (shift[min_point] != primary) return;
    bool resolved = true;
    for (const std::uint32_t* c = first; c != last && resolved; ++c) {
      const Sphere& s = spheres[*c];
      const double centre[3] = {s.x, s.y, s.z};
      for (int d = 0; d < 3; ++d)
        if (box.periodic[d] && (centre[d] - s.r < box.lo[d] - padding || centre[d] + s.r > box.hi[d] + padding))
          resolved = false;
    }
    const Sphere& s = spheres[*first];
    if (!resolved) {
      ++result.unresolved;
      bool in_box = true;
      const double centre[3] = {s.x, s.y, s.z};
      for (int d = 0; d < 3; ++d)
        if (!box.periodic[d] && (centre[d] < box.lo[d] || centre[d] > box.hi[d])) in_box = false;
      if (in_box) ++result.unresolved_in_box;
      return;
    }
    for (const std::uint32_t* c = first; c != last; ++c)
      for (int k = 0; k < 4; ++k) {
        const std::uint32_t p = cells[*c]->vertex(k)->info();
        if (origin[p] == min_origin && p != min_point)
          throw std::runtime_error(
              "periodic box too small: sphere " + std::to_string((*ids)[min_origin]) +
              " and its own image bound one pore (a periodic length is below the pore diameter)");
      }
    Pore pore;
    pore.centre = {s.x, s.y, s.z};
    for (int d = 0; d < 3; ++d)
      if (box.periodic[d]) {
        double t = (pore.centre[d] - box.lo[d]) / box.length(d);
        t -= std::floor(t);
        pore.centre[d] = std::min(box.lo[d] + t * box.length(d), std::nextafter(box.hi[d], box.lo[d]));
      }
    pore.xi = (s.r - options.radius) / options.radius;
    for (int k = 0; k < 4; ++k) pore.ids[k] = (*ids)[origin[cells[*first]->vertex(k)->info()]];
    std::sort(pore.ids.begin(), pore.ids.end());
    pore.tetrahedra = static_cast<int>(last - first);
    for (const std::uint32_t* c = first; c != last; ++c) {
      const CellHandle& h = cells[*c];
      pore.volume += tetrahedron_volume(h->vertex(0)->point(), h->vertex(1)->point(), h->vertex(2)->point(),
                                        h->vertex(3)->point());
    }
    result.tetrahedra += pore.tetrahedra;
    result.tetrahedra_volume += pore.volume;
    result.pores.push_back(pore);
  };

  result.pores.reserve(count / 2);
  for (std::uint32_t i = 0; i < count; ++i)
    if (members[parent[i]] == 1) process(&i, &i + 1);
  for (std::size_t begin = 0; begin < grouped.size();) {
    std::size_t end = begin + 1;
    while (end < grouped.size() && parent[grouped[end]] == parent[grouped[begin]]) ++end;
    process(grouped.data() + begin, grouped.data() + end);
    begin = end;
  }
}

Tessellation::Tessellation(const Box& box, const std::vector<double>& xyz, const std::vector<std::int64_t>& ids,
                           const PoreOptions& options)
    : impl_(std::make_unique<Impl>()) {
  if (!(options.radius > 0) || !std::isfinite(options.radius))
    throw std::invalid_argument("radius must be positive and finite, got " + std::to_string(options.radius));
  if (!(options.merge_tolerance >= 0 && options.merge_tolerance < 0.1))
    throw std::invalid_argument("merge tolerance must be in [0, 0.1), got " + std::to_string(options.merge_tolerance));
  if (!(options.overlap_tolerance >= 0 && options.overlap_tolerance < 1))
    throw std::invalid_argument("overlap tolerance must be in [0, 1), got " + std::to_string(options.overlap_tolerance));
  if (!(options.padding_over_radius >= 2))
    throw std::invalid_argument("padding must be at least 2 R, got " + std::to_string(options.padding_over_radius));
  if (xyz.size() != 3 * ids.size())
    throw std::invalid_argument("xyz holds " + std::to_string(xyz.size()) + " values for " +
                                std::to_string(ids.size()) + " ids (expected 3 per id)");
  if (ids.size() < 4 && !(box.periodic[0] || box.periodic[1] || box.periodic[2]))
    throw std::invalid_argument("at least 4 centres are needed for a tetrahedron, got " + std::to_string(ids.size()));
  if (ids.empty()) throw std::invalid_argument("no centres given");
  impl_->box = box;
  impl_->options = options;
  impl_->ids = &ids;
  double padding = options.padding_over_radius * options.radius;
  for (int attempt = 0;; ++attempt) {
    impl_->build(xyz, padding);
    impl_->find_pores(padding);
    if (impl_->result.unresolved_in_box == 0 || attempt >= options.max_padding_retries) break;
    padding *= 2.0;
  }
  impl_->ids = nullptr;  // the caller's ids may go away; pores hold copies
}

Tessellation::~Tessellation() = default;

const PoreResult& Tessellation::result() const { return impl_->result; }

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
