#include "cgal_peer.h"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_deformation.h>

#include "lapis_bench.h"

namespace lapis::bench {

PeerTiming cgal_original_arap(const geometry::TriMesh& mesh, const std::vector<int>& roi, const std::vector<int>& handle,
                              const std::vector<Eigen::Matrix4d>& frames, int iterations) {
  using K = CGAL::Simple_cartesian<double>;
  using SM = CGAL::Surface_mesh<K::Point_3>;
  using VD = SM::Vertex_index;
  using Deform = CGAL::Surface_mesh_deformation<SM, CGAL::Default, CGAL::Default, CGAL::ORIGINAL_ARAP>;
  SM sm;
  std::vector<VD> vd;
  vd.reserve(mesh.V.rows());
  for (int i = 0; i < mesh.num_vertices(); ++i) vd.push_back(sm.add_vertex(K::Point_3(mesh.V(i, 0), mesh.V(i, 1), mesh.V(i, 2))));
  for (int f = 0; f < mesh.num_faces(); ++f) sm.add_face(vd[mesh.F(f, 0)], vd[mesh.F(f, 1)], vd[mesh.F(f, 2)]);

  PeerTiming t;
  Deform dm(sm);
  t.setup_s = time_ms([&] {
                std::vector<VD> r;
                for (int v : roi) r.push_back(vd[v]);
                dm.insert_roi_vertices(r.begin(), r.end());
                for (int v : handle) dm.insert_control_vertex(vd[v]);
                dm.preprocess();
              }) / 1000.0;
  std::vector<double> per_it;
  for (const Eigen::Matrix4d& T : frames) {
    for (int v : handle) {
      const Eigen::Vector3d p = T.topLeftCorner<3, 3>() * mesh.V.row(v).transpose() + T.topRightCorner<3, 1>();
      dm.set_target_position(vd[v], K::Point_3(p.x(), p.y(), p.z()));
    }
    per_it.push_back(time_ms([&] { dm.deform(static_cast<unsigned>(iterations), 0.0); }) / iterations);
  }
  t.ms_per_iteration = median(per_it);
  t.frames = static_cast<int>(frames.size());
  return t;
}

}  // namespace lapis::bench
