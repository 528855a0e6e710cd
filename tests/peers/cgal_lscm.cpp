#include "cgal_lscm.h"

#include <stdexcept>
#include <string>

#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Two_vertices_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

namespace lapis::peers {

Eigen::MatrixX2d cgal_lscm(const geometry::TriMesh& input, int pin_a, int pin_b) {
  using K = CGAL::Simple_cartesian<double>;
  using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;
  using Vertex = SurfaceMesh::Vertex_index;
  namespace SMP = CGAL::Surface_mesh_parameterization;
  SurfaceMesh mesh;
  std::vector<Vertex> vertex;
  for (int i = 0; i < input.num_vertices(); ++i)
    vertex.push_back(mesh.add_vertex(K::Point_3(input.V(i, 0), input.V(i, 1), input.V(i, 2))));
  for (int f = 0; f < input.num_faces(); ++f)
    mesh.add_face(vertex[input.F(f, 0)], vertex[input.F(f, 1)], vertex[input.F(f, 2)]);
  const auto border = CGAL::Polygon_mesh_processing::longest_border(mesh).first;
  auto uv = mesh.add_property_map<Vertex, K::Point_2>("v:uv").first;
  using Border = SMP::Two_vertices_parameterizer_3<SurfaceMesh>;
  SMP::LSCM_parameterizer_3<SurfaceMesh, Border> lscm(Border(vertex[pin_a], vertex[pin_b]));
  const SMP::Error_code error = SMP::parameterize(mesh, lscm, border, uv);
  if (error != SMP::OK) throw std::runtime_error(std::string("CGAL LSCM: ") + SMP::get_error_message(error));
  Eigen::MatrixX2d out(input.num_vertices(), 2);
  for (int i = 0; i < input.num_vertices(); ++i) out.row(i) << uv[vertex[i]].x(), uv[vertex[i]].y();
  return out;
}

}  // namespace lapis::peers
