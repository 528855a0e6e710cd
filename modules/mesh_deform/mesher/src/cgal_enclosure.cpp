#include "lapis/mesh_deform/cgal_enclosure.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polyhedral_mesh_domain_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/alpha_wrap_3.h>
#include <CGAL/make_mesh_3.h>

#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "lapis/core/error.h"

namespace lapis::mesh_deform {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Wrap = CGAL::Surface_mesh<Point>;
using Domain = CGAL::Polyhedral_mesh_domain_3<Wrap, K>;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;

constexpr const char* kFn = "mesh_deform::cgal_enclosure()";

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

Wrap alpha_wrap(const geometry::TriMesh& s, double alpha, double offset) {
  std::vector<Point> points;
  points.reserve(static_cast<size_t>(s.num_vertices()));
  for (int i = 0; i < s.num_vertices(); ++i) points.emplace_back(s.V(i, 0), s.V(i, 1), s.V(i, 2));
  std::vector<std::array<std::size_t, 3>> faces;
  faces.reserve(static_cast<size_t>(s.num_faces()));
  for (int f = 0; f < s.num_faces(); ++f)
    faces.push_back({static_cast<std::size_t>(s.F(f, 0)), static_cast<std::size_t>(s.F(f, 1)),
                     static_cast<std::size_t>(s.F(f, 2))});
  Wrap wrap;
  CGAL::alpha_wrap_3(points, faces, alpha, offset, wrap);
  return wrap;
}

// The cells in the complex as a TetMesh, each positively oriented.
geometry::TetMesh to_tets(const C3t3& c3t3) {
  std::map<Tr::Vertex_handle, int> index;
  std::vector<Eigen::RowVector4i> tets;
  std::vector<Eigen::RowVector3d> points;
  for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c) {
    Eigen::RowVector4i t;
    for (int k = 0; k < 4; ++k) {
      const auto v = c->vertex(k);
      auto [it, fresh] = index.try_emplace(v, static_cast<int>(points.size()));
      if (fresh) {
        const auto p = v->point().point();
        points.emplace_back(p.x(), p.y(), p.z());
      }
      t[k] = it->second;
    }
    tets.push_back(t);
  }
  geometry::TetMesh m;
  m.V.resize(static_cast<int>(points.size()), 3);
  for (size_t i = 0; i < points.size(); ++i) m.V.row(static_cast<int>(i)) = points[i];
  m.T.resize(static_cast<int>(tets.size()), 4);
  for (size_t t = 0; t < tets.size(); ++t) {
    Eigen::RowVector4i c = tets[t];
    auto P = [&](int k) { return Eigen::Vector3d(m.V.row(c[k]).transpose()); };
    if (geometry::tet_volume(P(0), P(1), P(2), P(3)) < 0) std::swap(c[2], c[3]);
    m.T.row(static_cast<int>(t)) = c;
  }
  return m;
}

geometry::TetMesh mesh_wrap(const Domain& domain, double h, bool odt) {
  // Coarse tets: facets and cells at the size h, the boundary within h/4 of the wrap (the
  // wrap's offset keeps the input inside that tolerance, see cgal_enclosure()).
  namespace p = CGAL::parameters;
  const Criteria criteria(p::facet_angle = 20, p::facet_size = h, p::facet_distance = 0.25 * h,
                          p::cell_radius_edge_ratio = 3, p::cell_size = h);
  const C3t3 c3t3 = odt ? CGAL::make_mesh_3<C3t3>(domain, criteria, p::odt(), p::no_perturb(), p::no_exude())
                        : CGAL::make_mesh_3<C3t3>(domain, criteria, p::no_odt(), p::no_perturb(), p::no_exude());
  return to_tets(c3t3);
}

}  // namespace

geometry::TetMesh cgal_enclosure(const geometry::TriMesh& surface, const EnclosureOptions& o, EnclosureReport* report) {
  geometry::require_valid(surface, {}, kFn);
  if (surface.num_faces() == 0) throw InvalidArgument(std::string(kFn) + ": the surface has no faces");
  if (o.target_vertices < 8 || !(o.alpha_fraction > 0) || !(o.offset_fraction > 0) || o.attempts < 1)
    throw InvalidArgument(std::string(kFn) +
                          ": expected target_vertices >= 8, alpha_fraction > 0, offset_fraction > 0, attempts >= 1");
  EnclosureReport r;
  const double diag = (surface.V.colwise().maxCoeff() - surface.V.colwise().minCoeff()).norm();
  auto t0 = std::chrono::steady_clock::now();
  const Wrap wrap = alpha_wrap(surface, o.alpha_fraction * diag, o.offset_fraction * diag);
  r.wrap_ms = ms_since(t0);
  r.wrap_vertices = static_cast<int>(wrap.number_of_vertices());
  r.wrap_faces = static_cast<int>(wrap.number_of_faces());
  if (wrap.is_empty() || !CGAL::is_closed(wrap))
    throw SolverFailure(std::string(kFn) + ": alpha wrap produced no closed surface (alpha " +
                        std::to_string(o.alpha_fraction) + ", offset " + std::to_string(o.offset_fraction) +
                        " of the diagonal)");
  const Domain domain(wrap);
  // A tet mesh of n vertices at edge length h fills the volume with ~n·h³/√2·… cells; start
  // from the box volume, then correct h by (count / target)^(1/3).
  const Eigen::Vector3d extent = surface.V.colwise().maxCoeff() - surface.V.colwise().minCoeff();
  double h = std::cbrt(extent.prod() / o.target_vertices) * 1.5;
  geometry::TetMesh best;
  t0 = std::chrono::steady_clock::now();
  for (int a = 0; a < o.attempts; ++a) {
    geometry::TetMesh m = mesh_wrap(domain, h, o.odt);
    ++r.attempts;
    const bool closer = best.num_tets() == 0 || std::abs(m.num_vertices() - o.target_vertices) <
                                                    std::abs(best.num_vertices() - o.target_vertices);
    if (m.num_tets() > 0 && closer) best = std::move(m);
    if (best.num_tets() > 0 && std::abs(best.num_vertices() - o.target_vertices) < 0.2 * o.target_vertices) break;
    const int count = best.num_tets() > 0 ? best.num_vertices() : 1;
    h *= std::cbrt(static_cast<double>(std::max(count, 4)) / o.target_vertices);
  }
  r.mesh_ms = ms_since(t0);
  if (report) *report = r;
  if (best.num_tets() == 0)
    throw SolverFailure(std::string(kFn) + ": tetrahedral meshing of the wrap produced no tetrahedra");
  geometry::require_valid_tets(best, kFn);
  return best;
}

}  // namespace lapis::mesh_deform
