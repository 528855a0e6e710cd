#include "lapis/viewer/surface_select.h"

#include <algorithm>

#include "lapis/core/error.h"
#include "lapis/geometry/normals.h"

namespace lapis::viewer {
namespace {

std::vector<int> sorted(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

void check_range(const geometry::Connectivity& conn, const std::vector<int>& set, const char* fn) {
  for (int v : set)
    if (v < 0 || v >= conn.num_vertices())
      throw InvalidArgument(std::string(fn) + ": vertex " + std::to_string(v) + " out of range [0, " +
                            std::to_string(conn.num_vertices()) + ")");
}

}  // namespace

std::vector<int> brush_vertices(const geometry::TriMesh& mesh, const geometry::Connectivity& conn,
                                const geometry::Bvh& bvh, const geometry::CameraMatrices& camera,
                                const Eigen::Vector2d& pixel, const BrushOptions& options) {
  if (options.through) {
    std::vector<int> out;
    for (int v = 0; v < mesh.num_vertices(); ++v) {
      const Eigen::Vector3d s = geometry::project(camera, mesh.V.row(v).transpose());
      if (s.z() > 0 && s.z() < 1 && (s.head<2>() - pixel).norm() <= options.radius_px) out.push_back(v);
    }
    return out;
  }
  const geometry::Ray ray = geometry::unproject_ray(camera, pixel.x(), pixel.y());
  const auto hit = bvh.intersect(ray.origin, ray.direction);
  if (!hit) return {};
  // The world radius: how far one brush radius on screen reaches at the hit's depth.
  const double depth = geometry::project(camera, hit->point).z();
  const Eigen::Vector3d edge = geometry::unproject(camera, pixel.x() + options.radius_px, pixel.y(), depth);
  const double radius = (edge - hit->point).norm();
  // Flood fill from the hit face inside the ball: the far side of a thin part is inside the
  // ball but not reached, so the brush paints only the sheet under the cursor.
  std::vector<char> seen(static_cast<size_t>(mesh.num_vertices()), 0);
  std::vector<int> stack, out;
  for (int k = 0; k < 3; ++k) {
    const int v = mesh.F(hit->face, k);
    if (!seen[v]) seen[v] = 1, stack.push_back(v);
  }
  while (!stack.empty()) {
    const int v = stack.back();
    stack.pop_back();
    // The hit face's corners always count, so even a tiny brush on a big face paints.
    const bool corner = v == mesh.F(hit->face, 0) || v == mesh.F(hit->face, 1) || v == mesh.F(hit->face, 2);
    if (!corner && (mesh.V.row(v).transpose() - hit->point).norm() > radius) continue;
    out.push_back(v);
    for (int w : conn.vertex_neighbors(v))
      if (!seen[w]) seen[w] = 1, stack.push_back(w);
  }
  return sorted(std::move(out));
}

bool point_in_polygon(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p) {
  const size_t n = polygon.size();
  if (n < 3) return false;
  bool inside = false;
  for (size_t i = 0, j = n - 1; i < n; j = i++) {
    const Eigen::Vector2d &a = polygon[i], &b = polygon[j];
    // Edge crosses the horizontal line through p, to the right of p: toggle.
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

std::vector<int> lasso_vertices(const geometry::TriMesh& mesh, const geometry::Bvh& bvh,
                                const geometry::CameraMatrices& camera, const std::vector<Eigen::Vector2d>& polygon,
                                const LassoOptions& options) {
  if (polygon.size() < 3) return {};
  Eigen::Vector2d lo = polygon[0], hi = polygon[0];
  for (const auto& p : polygon) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const Eigen::Vector3d eye = geometry::eye_position(camera);
  geometry::Vertices normals;
  if (options.visible_only) normals = geometry::vertex_normals(mesh);
  std::vector<int> out;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const Eigen::Vector3d p = mesh.V.row(v).transpose();
    const Eigen::Vector3d s = geometry::project(camera, p);
    if (!(s.z() > 0 && s.z() < 1)) continue;
    const Eigen::Vector2d q = s.head<2>();
    if ((q.array() < lo.array()).any() || (q.array() > hi.array()).any() || !point_in_polygon(polygon, q)) continue;
    if (options.visible_only) {
      // Visible when it faces the eye and nothing lies between them (the vertex's own faces
      // end the ray at t = 1, so the ray stops just short). The facing test also catches the
      // rare ray that slips between two occluding triangles through their shared edge.
      const Eigen::Vector3d d = p - eye;
      if (normals.row(v).dot(-d) <= 0 || bvh.intersect(eye, d, 1.0 - 1e-6)) continue;
    }
    out.push_back(v);
  }
  return out;
}

std::vector<int> grow_rings(const geometry::Connectivity& conn, const std::vector<int>& set, int rings) {
  check_range(conn, set, "viewer::grow_rings()");
  if (set.empty() || rings <= 0) return sorted(set);
  return sorted(geometry::k_ring(conn, set, rings));
}

std::vector<int> shrink_rings(const geometry::Connectivity& conn, const std::vector<int>& set, int rings) {
  check_range(conn, set, "viewer::shrink_rings()");
  if (rings <= 0) return sorted(set);
  std::vector<char> in(static_cast<size_t>(conn.num_vertices()), 0);
  for (int v : set) in[v] = 1;
  for (int r = 0; r < rings; ++r) {
    // One ring per pass: a vertex with a neighbour outside leaves (decided on the old mask).
    std::vector<int> leave;
    for (int v = 0; v < conn.num_vertices(); ++v) {
      if (!in[v]) continue;
      for (int w : conn.vertex_neighbors(v))
        if (!in[w]) {
          leave.push_back(v);
          break;
        }
    }
    if (leave.empty()) break;
    for (int v : leave) in[v] = 0;
  }
  std::vector<int> out;
  for (int v = 0; v < conn.num_vertices(); ++v)
    if (in[v]) out.push_back(v);
  return out;
}

}  // namespace lapis::viewer
