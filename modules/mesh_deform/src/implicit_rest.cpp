#include "implicit_rest.h"

#include <cmath>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include <Eigen/Eigenvalues>

#include "lapis/geometry/normals.h"

namespace lapis::mesh_deform::detail {
namespace {

long long edge_key(int a, int b) { return (static_cast<long long>(a) << 32) | static_cast<unsigned>(b); }

// Vertices within `rings` edges of a free vertex.
std::vector<char> near_free(const Stencil& s, const std::vector<VertexRole>& role, int rings) {
  std::vector<char> mark(role.size(), 0);
  std::vector<int> front;
  for (size_t i = 0; i < role.size(); ++i)
    if (role[i] == VertexRole::Free) {
      mark[i] = 1;
      front.push_back(static_cast<int>(i));
    }
  for (int r = 0; r < rings; ++r) {
    std::vector<int> next;
    for (int i : front)
      for (int k = s.offsets[i]; k < s.offsets[i + 1]; ++k)
        if (!mark[s.nbr[k]]) {
          mark[s.nbr[k]] = 1;
          next.push_back(s.nbr[k]);
        }
    front.swap(next);
  }
  return mark;
}

// §2.4.3, boundary variant 1: a boundary vertex of valence < 3 (one triangle) has V_i V_iᵀ of
// rank ≤ 2 whatever its position, so the edge opposite to it is split at its midpoint.
void insert_midpoints(WorkMesh& w, const Stencil& s) {
  const int n = w.mesh.num_vertices();
  auto needs_midpoint = [&](int a) { return w.active[a] && s.boundary[a] && s.valence(a) < 3; };
  // Only the edges opposite such vertices are ever looked up (both directions): the map holds
  // those and the edges of the faces made here, not every edge of the mesh (a map of all of
  // them was 50 ms at 50K vertices, on the set-up's critical path).
  std::unordered_set<long long> wanted;
  for (int a = 0; a < n; ++a)
    if (needs_midpoint(a)) {
      const int p = s.nbr[s.offsets[a]], q = s.nbr[s.offsets[a] + 1];
      wanted.insert(edge_key(p, q));
      wanted.insert(edge_key(q, p));
    }
  if (wanted.empty()) return;
  std::unordered_map<long long, int> face_of;  // directed edge -> face
  for (int f = 0; f < w.mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c)
      if (const long long e = edge_key(w.mesh.F(f, c), w.mesh.F(f, (c + 1) % 3)); wanted.count(e)) face_of[e] = f;
  std::vector<std::array<int, 3>> faces(w.mesh.F.rows());
  for (int f = 0; f < w.mesh.num_faces(); ++f) faces[f] = {w.mesh.F(f, 0), w.mesh.F(f, 1), w.mesh.F(f, 2)};
  std::vector<Eigen::RowVector3d> new_points;
  auto set_face = [&](size_t f, std::array<int, 3> t) {
    if (f == faces.size()) faces.push_back(t);
    faces[f] = t;
    for (int c = 0; c < 3; ++c) face_of[edge_key(t[c], t[(c + 1) % 3])] = static_cast<int>(f);
  };
  auto has = [&](int f, int v) { return faces[f][0] == v || faces[f][1] == v || faces[f][2] == v; };
  for (int a = 0; a < n; ++a) {
    if (!needs_midpoint(a)) continue;
    int p = s.nbr[s.offsets[a]], q = s.nbr[s.offsets[a] + 1];
    // The face (a, p, q) in its orientation; its edge p -> q is opposite to a.
    auto it = face_of.find(edge_key(p, q));
    if (it == face_of.end() || !has(it->second, a)) {
      std::swap(p, q);
      it = face_of.find(edge_key(p, q));
    }
    if (it == face_of.end() || !has(it->second, a)) continue;
    const int f = it->second;
    auto other = face_of.find(edge_key(q, p));
    const int g = other == face_of.end() ? -1 : other->second;
    face_of.erase(edge_key(p, q));
    face_of.erase(edge_key(q, p));
    const int m = n + static_cast<int>(new_points.size());
    new_points.push_back(0.5 * (w.mesh.V.row(p) + w.mesh.V.row(q)));
    w.inserted.push_back({p, q});
    set_face(static_cast<size_t>(f), {a, p, m});
    set_face(faces.size(), {a, m, q});
    if (g >= 0) {
      const int x = faces[g][0] + faces[g][1] + faces[g][2] - p - q;
      set_face(static_cast<size_t>(g), {q, m, x});
      set_face(faces.size(), {m, p, x});
    }
    // The midpoint moves with whatever moves its edge: free if anything near it is free.
    const VertexRole rp = w.role[p], rq = w.role[q], ra = w.role[a];
    VertexRole r = VertexRole::Fixed;
    int h = -1;
    if (ra == VertexRole::Free || rp == VertexRole::Free || rq == VertexRole::Free) {
      r = VertexRole::Free;
    } else if (rp == VertexRole::RegionHandle && rq == rp && w.handle_of[p] == w.handle_of[q]) {
      r = VertexRole::RegionHandle;
      h = w.handle_of[p];
    } else if (rp != VertexRole::Fixed || rq != VertexRole::Fixed) {
      // Ends held by different handles (merging makes every boundary vertex its own handle):
      // no single transform carries the midpoint, so the solve places it.
      r = VertexRole::Free;
    }
    w.role.push_back(r);
    w.handle_of.push_back(h);
  }
  if (new_points.empty()) return;
  Vertices V(n + static_cast<int>(new_points.size()), 3);
  V.topRows(n) = w.mesh.V;
  for (size_t k = 0; k < new_points.size(); ++k) V.row(n + static_cast<int>(k)) = new_points[k];
  w.mesh.V = std::move(V);
  w.mesh.F.resize(static_cast<int>(faces.size()), 3);
  for (size_t f = 0; f < faces.size(); ++f)
    for (int c = 0; c < 3; ++c) w.mesh.F(static_cast<int>(f), c) = faces[f][c];
}

bool neighbours_collinear(const Stencil& s, const Vertices& P, int i) {
  const int k0 = s.offsets[i], k1 = s.offsets[i + 1];
  if (k1 - k0 < 3) return true;
  const Eigen::RowVector3d a = P.row(s.nbr[k0]);
  double longest = 0, area = 0;
  for (int k = k0 + 1; k < k1; ++k) {
    const Eigen::RowVector3d d = P.row(s.nbr[k]) - a;
    longest = std::max(longest, d.squaredNorm());
    for (int l = k + 1; l < k1; ++l) area = std::max(area, d.cross(P.row(s.nbr[l]) - a).norm());
  }
  return area <= 1e-10 * longest;
}

// Eq. 2.9: v'_i = v_i + s_disp / |N(i)| Σ_j ‖v_i − v_j‖ n_i.
void displace(Vertices& P, const Stencil& s, const Vertices& normals, int i, double s_disp) {
  double sum = 0;
  for (int k = s.offsets[i]; k < s.offsets[i + 1]; ++k) sum += (P.row(i) - P.row(s.nbr[k])).norm();
  P.row(i) += s_disp * sum / std::max(1, s.valence(i)) * normals.row(i);
}

Eigen::Matrix3d scatter(const Stencil& s, const Vertices& P, int i, Eigen::Vector3d& centre) {
  const int k0 = s.offsets[i], k1 = s.offsets[i + 1];
  centre.setZero();
  for (int k = k0; k < k1; ++k) centre += P.row(s.nbr[k]).transpose();
  centre /= std::max(1, k1 - k0);
  Eigen::Vector3d d = P.row(i).transpose() - centre;
  Eigen::Matrix3d VV = d * d.transpose();
  for (int k = k0; k < k1; ++k) {
    d = P.row(s.nbr[k]).transpose() - centre;
    VV.noalias() += d * d.transpose();
  }
  return VV;
}

}  // namespace

double stencil_condition(const Stencil& s, const Vertices& P, int i) {
  Eigen::Vector3d c;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(scatter(s, P, i, c), Eigen::EigenvaluesOnly);
  const double lo = es.eigenvalues()(0), hi = es.eigenvalues()(2);
  return lo > 0 ? hi / lo : std::numeric_limits<double>::infinity();
}

WorkMesh build_work_mesh(const TriMesh& rest, const Layout& layout, const ImplicitOptions& o) {
  WorkMesh w;
  w.mesh = rest;
  w.role = layout.role;
  w.handle_of = layout.handle_of;
  Stencil s = make_stencil(w.mesh.V, w.mesh.F, LaplacianWeights::Uniform);
  w.active = near_free(s, w.role, 2);
  insert_midpoints(w, s);
  if (!w.inserted.empty()) {
    s = make_stencil(w.mesh.V, w.mesh.F, LaplacianWeights::Uniform);
    w.active = near_free(s, w.role, 2);
  }
  // §2.4.3: one sequential traversal, so a vertex sees the displacements made before it.
  const Vertices normals = geometry::vertex_normals(w.mesh);
  w.displaced = w.mesh.V;
  std::vector<char> moved(w.role.size(), 0);
  auto move = [&](int v) {
    if (moved[v]) return;
    displace(w.displaced, s, normals, v, o.s_disp);
    moved[v] = 1;
  };
  for (int i = 0; i < s.size(); ++i) {
    if (!w.active[i] || stencil_condition(s, w.displaced, i) <= o.degenerate_condition) continue;
    ++w.degenerate;
    int target = i;
    // Boundary variant 2: collinear neighbours stay collinear however v_i moves, so an
    // interior neighbour is displaced instead.
    if (s.boundary[i] && neighbours_collinear(s, w.displaced, i))
      for (int k = s.offsets[i]; k < s.offsets[i + 1]; ++k)
        if (!s.boundary[s.nbr[k]]) {
          target = s.nbr[k];
          break;
        }
    move(target);
  }
  for (int v = 0; v < s.size(); ++v)
    if (moved[v]) w.moved.push_back(v);
  w.stencil = std::move(s);
  return w;
}

GradientStencils gradient_stencils(const Stencil& s, const Vertices& P, const std::vector<char>& active) {
  const int n = s.size();
  GradientStencils G;
  G.offsets.assign(static_cast<size_t>(n) + 1, 0);
  for (int i = 0; i < n; ++i) G.offsets[i + 1] = G.offsets[i] + (active[i] ? s.valence(i) + 1 : 0);
  G.vertex.resize(static_cast<size_t>(G.offsets[n]));
  G.g.resize(static_cast<size_t>(G.offsets[n]));
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    if (!active[i]) continue;
    Eigen::Vector3d c;
    const Eigen::Matrix3d VV = scatter(s, P, i, c);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
    es.computeDirect(VV);
    Eigen::Vector3d lam = es.eigenvalues();
    const double floor = 1e-12 * std::max(lam(2), 1e-300);
    for (int a = 0; a < 3; ++a) lam(a) = std::max(lam(a), floor);
    const Eigen::Matrix3d inv = es.eigenvectors() * lam.cwiseInverse().asDiagonal() * es.eigenvectors().transpose();
    // Column k of V_i is p_k − c; row k of V_iᵀ (V_i V_iᵀ)⁻¹ is inv (p_k − c). The centre c is
    // the neighbours' mean, so its coefficient sum is spread over the neighbours.
    const int k0 = s.offsets[i], k1 = s.offsets[i + 1], base = G.offsets[i];
    Eigen::Vector3d sum = inv * (P.row(i).transpose() - c);
    G.vertex[base] = i;
    G.g[base] = sum;
    for (int k = k0; k < k1; ++k) {
      const Eigen::Vector3d gk = inv * (P.row(s.nbr[k]).transpose() - c);
      G.vertex[base + 1 + k - k0] = s.nbr[k];
      G.g[base + 1 + k - k0] = gk;
      sum += gk;
    }
    const Eigen::Vector3d share = sum / (k1 - k0);
    for (int k = k0; k < k1; ++k) G.g[base + 1 + k - k0] -= share;
  }
  return G;
}

namespace {

// Up to kSharedAnchors vertices of the group, each the farthest from those picked before (the
// first: the group's first vertex), so the fit sees the whole group.
std::vector<int> spread_anchors(const Vertices& P, const std::vector<int>& group) {
  if (group.size() <= static_cast<size_t>(kSharedAnchors)) return group;
  std::vector<double> gap(group.size(), std::numeric_limits<double>::infinity());
  std::vector<int> anchors;
  size_t next = 0;
  while (anchors.size() < static_cast<size_t>(kSharedAnchors)) {
    anchors.push_back(group[next]);
    const Eigen::RowVector3d a = P.row(group[next]);
    size_t far = 0;
    for (size_t k = 0; k < group.size(); ++k) {
      gap[k] = std::min(gap[k], (P.row(group[k]) - a).squaredNorm());
      if (gap[k] > gap[far]) far = k;
    }
    next = far;
  }
  return anchors;
}

}  // namespace

void share_gradients(GradientStencils& G, const Vertices& P, const std::vector<std::vector<int>>& groups,
                     const std::vector<char>& active) {
  const int n = static_cast<int>(G.offsets.size()) - 1;
  std::vector<int> group_of(static_cast<size_t>(n), -1);
  std::vector<std::vector<int>> anchors;
  std::vector<std::vector<Eigen::Vector3d>> weights;
  for (size_t f = 0; f < groups.size(); ++f) {
    for (int v : groups[f])
      if (active[v]) group_of[v] = static_cast<int>(f);
    anchors.push_back(spread_anchors(P, groups[f]));
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int v : anchors.back()) c += P.row(v).transpose();
    c /= static_cast<double>(anchors.back().size());
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    for (int v : anchors.back()) scatter += (P.row(v).transpose() - c) * (P.row(v) - c.transpose());
    // As for a 1-ring: a flat group gets a Tikhonov-regularized inverse.
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
    es.computeDirect(scatter);
    Eigen::Vector3d lam = es.eigenvalues();
    for (int a = 0; a < 3; ++a) lam(a) = std::max(lam(a), 1e-12 * std::max(lam(2), 1e-300));
    const Eigen::Matrix3d inv = es.eigenvectors() * lam.cwiseInverse().asDiagonal() * es.eigenvectors().transpose();
    weights.emplace_back();
    for (int v : anchors.back()) weights.back().push_back(inv * (P.row(v).transpose() - c));
  }
  GradientStencils out;
  out.offsets.assign(static_cast<size_t>(n) + 1, 0);
  for (int i = 0; i < n; ++i) {
    const int f = group_of[i];
    const int count = f >= 0 ? static_cast<int>(anchors[f].size()) : G.offsets[i + 1] - G.offsets[i];
    out.offsets[i + 1] = out.offsets[i] + count;
  }
  out.vertex.reserve(static_cast<size_t>(out.offsets[n]));
  out.g.reserve(static_cast<size_t>(out.offsets[n]));
  for (int i = 0; i < n; ++i) {
    const int f = group_of[i];
    if (f >= 0) {
      out.vertex.insert(out.vertex.end(), anchors[f].begin(), anchors[f].end());
      out.g.insert(out.g.end(), weights[f].begin(), weights[f].end());
    } else {
      out.vertex.insert(out.vertex.end(), G.vertex.begin() + G.offsets[i], G.vertex.begin() + G.offsets[i + 1]);
      out.g.insert(out.g.end(), G.g.begin() + G.offsets[i], G.g.begin() + G.offsets[i + 1]);
    }
  }
  G = std::move(out);
}

}  // namespace lapis::mesh_deform::detail
