#include "cgal_arap.h"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_deformation.h>

namespace lapis::peers {

namespace {
using K = CGAL::Simple_cartesian<double>;
using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;
using VertexIndex = SurfaceMesh::Vertex_index;
using Deformation = CGAL::Surface_mesh_deformation<SurfaceMesh, CGAL::Default, CGAL::Default, CGAL::ORIGINAL_ARAP>;
}  // namespace

struct CgalArap::Impl {
  SurfaceMesh mesh;
  std::vector<VertexIndex> vertex;
  std::unique_ptr<Deformation> deformation;
};

CgalArap::CgalArap(const geometry::TriMesh& mesh, const std::vector<int>& roi, const std::vector<int>& control)
    : impl_(std::make_unique<Impl>()), control_(control) {
  Impl& m = *impl_;
  m.vertex.reserve(static_cast<size_t>(mesh.num_vertices()));
  for (int i = 0; i < mesh.num_vertices(); ++i)
    m.vertex.push_back(m.mesh.add_vertex(K::Point_3(mesh.V(i, 0), mesh.V(i, 1), mesh.V(i, 2))));
  for (int f = 0; f < mesh.num_faces(); ++f)
    m.mesh.add_face(m.vertex[mesh.F(f, 0)], m.vertex[mesh.F(f, 1)], m.vertex[mesh.F(f, 2)]);
  m.deformation = std::make_unique<Deformation>(m.mesh);
  std::vector<VertexIndex> r;
  r.reserve(roi.size());
  for (int v : roi) r.push_back(m.vertex[v]);
  m.deformation->insert_roi_vertices(r.begin(), r.end());
  for (int v : control) m.deformation->insert_control_vertex(m.vertex[v]);
  m.deformation->preprocess();
}

CgalArap::~CgalArap() = default;

void CgalArap::set_targets(const geometry::Vertices& targets) {
  for (int v : control_)
    impl_->deformation->set_target_position(impl_->vertex[v], K::Point_3(targets(v, 0), targets(v, 1), targets(v, 2)));
}

void CgalArap::deform(unsigned iterations, double tolerance) { impl_->deformation->deform(iterations, tolerance); }

geometry::Vertices CgalArap::positions() const {
  geometry::Vertices X(static_cast<Eigen::Index>(impl_->vertex.size()), 3);
  for (size_t i = 0; i < impl_->vertex.size(); ++i) {
    const K::Point_3& p = impl_->mesh.point(impl_->vertex[i]);
    X.row(static_cast<Eigen::Index>(i)) << p.x(), p.y(), p.z();
  }
  return X;
}

}  // namespace lapis::peers
