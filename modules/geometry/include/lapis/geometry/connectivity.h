// Mesh adjacency, built once per mesh and then queried cheaply: edges with their faces,
// vertex-face and vertex-vertex lists, ordered 1-rings, boundary loops, plus the graph
// queries merging and editing need (k-rings, components, Euler characteristic, genus).
#pragma once

#include <array>
#include <span>
#include <vector>

#include "lapis/geometry/mesh_edit.h"
#include "lapis/geometry/tri_mesh.h"

namespace lapis::geometry {

// Variable-length lists in two arrays (CSR): one allocation instead of a vector per vertex,
// which matters at a million vertices.
struct AdjacencyLists {
  std::vector<int> offsets;  // size n + 1
  std::vector<int> items;
  std::span<const int> operator[](int i) const {
    return {items.data() + offsets[i], static_cast<size_t>(offsets[i + 1] - offsets[i])};
  }
  int size() const { return static_cast<int>(offsets.size()) - 1; }
};

// Faces around each vertex in ascending order (a face with a repeated index once).
// Every index of F must be in [0, num_vertices).
AdjacencyLists vertex_face_lists(const Faces& F, int num_vertices);

class Connectivity {
 public:
  // Throws InvalidArgument when a face index is out of range. Works on any such mesh;
  // non-manifold edges keep their first two faces and are flagged (edge_face_count > 2).
  explicit Connectivity(const TriMesh& mesh);

  int num_vertices() const { return num_vertices_; }
  int num_faces() const { return static_cast<int>(F_.rows()); }
  int num_edges() const { return static_cast<int>(edges_.size()); }

  // Edge e joins edges()[e][0] < edges()[e][1].
  const std::vector<std::array<int, 2>>& edges() const { return edges_; }
  // The (up to) two faces of edge e; -1 where there is none (boundary edge).
  std::array<int, 2> edge_faces(int e) const { return edge_faces_[e]; }
  int edge_face_count(int e) const { return edge_face_count_[e]; }
  bool is_boundary_edge(int e) const { return edge_face_count_[e] == 1; }
  // Edge of face f from corner k to corner (k + 1) % 3.
  int face_edge(int f, int k) const { return face_edges_[3 * f + k]; }
  // Edge between a and b, or -1.
  int find_edge(int a, int b) const;
  // Faces sharing an edge with f across its edge k, or -1 (boundary / non-manifold).
  int face_neighbor(int f, int k) const;

  std::span<const int> vertex_faces(int v) const { return vertex_faces_[v]; }
  // Neighbours of v in ascending order.
  std::span<const int> vertex_neighbors(int v) const { return vertex_neighbors_[v]; }
  // Edges incident to v, parallel to vertex_neighbors(v).
  std::span<const int> vertex_edges(int v) const { return vertex_edges_[v]; }
  int degree(int v) const { return static_cast<int>(vertex_neighbors(v).size()); }

  // Neighbours of v in the cyclic order of the faces' orientation (counter-clockwise seen
  // from outside). For a boundary vertex the ring starts at the boundary neighbour the
  // fan begins with and ends at the other one. Throws InvalidArgument when the faces
  // around v do not form a single fan (non-manifold vertex).
  std::vector<int> one_ring_ordered(int v) const;

  bool is_boundary_vertex(int v) const { return is_boundary_vertex_[v]; }
  bool is_isolated_vertex(int v) const { return vertex_faces(v).empty(); }

  // Boundary loops as ordered vertex cycles (first vertex not repeated), each traversed in
  // the direction of its faces' half-edges, i.e. with the surface on the left.
  const std::vector<std::vector<int>>& boundary_loops() const { return boundary_loops_; }

 private:
  void build_edges();
  void build_boundary_loops();

  Faces F_;
  int num_vertices_ = 0;
  std::vector<std::array<int, 2>> edges_;
  std::vector<std::array<int, 2>> edge_faces_;
  std::vector<int> edge_face_count_;
  std::vector<int> face_edges_;
  AdjacencyLists vertex_faces_, vertex_neighbors_, vertex_edges_;
  std::vector<char> is_boundary_vertex_;
  std::vector<std::vector<int>> boundary_loops_;
};

// Vertices within k edges of any seed, in breadth-first order (seeds first). Throws
// InvalidArgument for k < 0 or a seed out of range.
std::vector<int> k_ring(const Connectivity& conn, const std::vector<int>& seeds, int k);

// Connected components through shared edges (faces) and edges (vertices).
struct Components {
  int count = 0;
  std::vector<int> face_component;    // #F, component of each face
  std::vector<int> vertex_component;  // #V, component of each vertex; -1 for isolated ones
};
Components connected_components(const Connectivity& conn);
Components connected_components(const TriMesh& mesh);

// V - E + F counting only vertices used by a face (isolated vertices are file debris, not
// topology).
int euler_characteristic(const Connectivity& conn);
int euler_characteristic(const TriMesh& mesh);

// Sum of the genera of the components, from chi = sum_i (2 - 2 g_i - b_i) for orientable
// surfaces with b boundary loops.
int genus(const Connectivity& conn);
int genus(const TriMesh& mesh);

}  // namespace lapis::geometry
