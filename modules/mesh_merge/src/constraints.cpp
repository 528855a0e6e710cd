#include "lapis/mesh_merge/constraints.h"

#include <cmath>
#include <string>

#include "lapis/geometry/normals.h"
#include "lapis/geometry/polar.h"

namespace lapis::mesh_merge {

namespace {

constexpr const char* kFn = "mesh_merge::boundary_constraints()";

// [t n b] (columns): the frame of §3.3.1 with n made orthogonal to t. geometry::local_frame
// builds [t1 t2 n] with t1 the reference projected, i.e. the same frame up to a fixed column
// permutation, which cancels in R = F_t F_sᵀ.
Eigen::Matrix3d frame(const Eigen::Vector3d& tangent, const Eigen::Vector3d& normal, int vertex) {
  const Eigen::Vector3d n_perp = normal - normal.dot(tangent) / tangent.squaredNorm() * tangent;
  if (!(tangent.norm() > 0) || !(n_perp.norm() > 1e-6 * normal.norm()))
    throw InvalidArgument(std::string(kFn) + ": no local frame at source boundary vertex " + std::to_string(vertex) +
                          " (zero tangent or normal along the boundary)");
  return geometry::local_frame(normal, tangent);
}

}  // namespace

std::vector<BoundaryConstraint> boundary_constraints(const TriMesh& source, const TriMesh& target,
                                                     const std::vector<BoundaryCorrespondence>& pairs,
                                                     bool keep_frames) {
  const Vertices ns = geometry::vertex_normals(source);
  const Vertices nt = keep_frames ? Vertices() : geometry::vertex_normals(target);
  std::vector<BoundaryConstraint> out;
  for (const BoundaryCorrespondence& c : pairs) {
    const int n = static_cast<int>(c.source_loop.size());
    const int m = static_cast<int>(c.target_loop.size());
    for (int i = 0; i < n; ++i) {
      const int prev = (i + n - 1) % n, next = (i + 1) % n;
      const int v = c.source_loop[i];
      const Eigen::Vector3d ts =
          0.5 * (source.V.row(c.source_loop[next]) - source.V.row(c.source_loop[prev])).transpose();
      const Eigen::Vector3d tt = 0.5 * (c.target_points.row(next) - c.target_points.row(prev)).transpose();
      BoundaryConstraint k;
      k.vertex = v;
      k.position = c.target_points.row(i).transpose();
      if (!(ts.norm() > 0) || !(tt.norm() > 0))
        throw InvalidArgument(std::string(kFn) + ": zero boundary tangent at source vertex " + std::to_string(v));
      k.scale = tt.norm() / ts.norm();
      if (!keep_frames) {
        const double t = c.target_t[i];
        const Eigen::Vector3d n_t = (1 - t) * nt.row(c.target_loop[c.target_edge[i]]).transpose() +
                                    t * nt.row(c.target_loop[(c.target_edge[i] + 1) % m]).transpose();
        const Eigen::Matrix3d Fs = frame(ts, ns.row(v).transpose(), v);
        const Eigen::Matrix3d Ft = frame(tt, n_t, v);
        k.rotation = Ft * Fs.transpose();
      }
      out.push_back(k);
    }
  }
  return out;
}

void add_region_handles(const TriMesh& source, const std::vector<BoundaryConstraint>& constraints,
                        mesh_deform::Selection& selection, mesh_deform::HandleTransforms& transforms) {
  for (const BoundaryConstraint& k : constraints) {
    const Eigen::Matrix3d M = k.gradient();
    Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
    T.topLeftCorner<3, 3>() = M;
    T.topRightCorner<3, 1>() = k.position - M * source.V.row(k.vertex).transpose();
    selection.region_handles.push_back({k.vertex});
    transforms.regions.push_back(T);
  }
}

}  // namespace lapis::mesh_merge
