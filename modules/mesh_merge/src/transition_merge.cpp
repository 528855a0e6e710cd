#include "transition_merge.h"

#include <chrono>
#include <string>

#include "lapis/geometry/laplacian.h"
#include "lapis/geometry/mesh_edit.h"
#include "lapis/geometry/polar.h"
#include "lapis/mesh_deform/implicit_laplacian.h"
#include "lapis/mesh_merge/constraints.h"
#include "lapis/mesh_merge/refine.h"
#include "lapis/mesh_merge/transition.h"
#include "lapis/mesh_merge/zip.h"
#include "lapis/solver/least_squares.h"

namespace lapis::mesh_merge::detail {

namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// One pair's two bands and the overlap maps between them.
struct PairBands {
  TransitionBand source, target;
  std::vector<BandPoint> source_on_target, target_on_source;  // parallel to source.vertices / target.vertices
};

// The deformed Laplacian coordinates of one mesh as curvature normals, K_i = R_i δ_i / (s_i A_i):
// s_i R_i the similarity that best maps the rest 1-ring (and v_i) onto the deformed one (Eq.
// 2.11's R_i S_i), A_i the rest Voronoi area. Curvature normals rather than raw δ cross
// between the meshes, so that the blend stays right when their sampling densities differ.
// At border vertices δ is not a curvature normal: they take their inner neighbours' mean.
Vertices deformed_curvature(const TriMesh& rest, const Connectivity& conn, const Vertices& deformed,
                            const std::vector<int>& vertices) {
  const Eigen::MatrixX3d delta = geometry::laplacian_coordinates(rest);
  const Eigen::VectorXd area = geometry::vertex_areas(rest);
  Vertices K = Vertices::Zero(rest.num_vertices(), 3);
  std::vector<char> done(static_cast<size_t>(rest.num_vertices()), 0);
  for (int v : vertices) {
    if (conn.is_boundary_vertex(v) || done[v]) continue;
    const auto ring = conn.vertex_neighbors(v);
    Eigen::MatrixX3d from(static_cast<Eigen::Index>(ring.size()) + 1, 3), to(from.rows(), 3);
    from.row(0) = rest.V.row(v), to.row(0) = deformed.row(v);
    for (size_t k = 0; k < ring.size(); ++k)
      from.row(static_cast<Eigen::Index>(k) + 1) = rest.V.row(ring[k]),
                                              to.row(static_cast<Eigen::Index>(k) + 1) = deformed.row(ring[k]);
    const geometry::Similarity3 S = geometry::fit_similarity(from, to);
    K.row(v) = (S.R * delta.row(v).transpose() / (S.s * area(v))).transpose();
    done[v] = 1;
  }
  for (int v : vertices) {
    if (!conn.is_boundary_vertex(v)) continue;
    int n = 0;
    for (int u : conn.vertex_neighbors(v))
      if (done[u]) K.row(v) += K.row(u), ++n;
    if (n) K.row(v) /= n;
  }
  return K;
}

// Poisson reconstruction of the kept band (§3.3.3, Fig. 3.7 (b)) on the zipped mesh: the band's
// vertices take the wanted Laplacian coordinates, every other vertex stays, so both ends of the
// band meet their surroundings with continuous tangents (the strip included).
void reconstruct_band(TriMesh& mesh, const std::vector<int>& unknown, const Vertices& target_delta) {
  if (unknown.empty()) return;  // a band narrower than an edge, gone with the zipped ring
  const int n = mesh.num_vertices();
  Vertices& positions = mesh.V;
  std::vector<char> is_unknown(static_cast<size_t>(n), 0);
  for (int v : unknown) is_unknown[v] = 1;
  std::vector<int> fixed;
  for (int v = 0; v < n; ++v)
    if (!is_unknown[v]) fixed.push_back(v);
  // A vertex whose faces are all degenerate (collapsed in the zip's strip, or laid flat on the
  // other band's rim by kept_band_spread) has no cotangent row: it takes the umbrella row and
  // sits at its neighbours' mean instead of leaving the system singular.
  const Eigen::SparseMatrix<double> L = geometry::cotan_laplacian(mesh);
  const Eigen::SparseMatrix<double> U = geometry::uniform_laplacian(mesh);
  std::vector<char> umbrella(unknown.size(), 0);
  std::vector<Eigen::Triplet<double, int>> t;
  for (size_t r = 0; r < unknown.size(); ++r) {
    umbrella[r] = !(L.coeff(unknown[r], unknown[r]) < 0);
    const Eigen::SparseMatrix<double>& row = umbrella[r] ? U : L;
    for (Eigen::SparseMatrix<double>::InnerIterator it(row, unknown[r]); it; ++it)  // symmetric
      t.emplace_back(static_cast<int>(r), static_cast<int>(it.row()), it.value());
  }
  solver::SparseMatrix rows(static_cast<Eigen::Index>(unknown.size()), n);
  rows.setFromTriplets(t.begin(), t.end());
  solver::LeastSquares ls(n);
  ls.add_block(rows, 1.0, "L x = interpolated δ (§3.3.3)");
  ls.set_fixed(fixed);
  ls.precompute();
  solver::DenseMatrix rhs(static_cast<Eigen::Index>(unknown.size()), 3),
      values(static_cast<Eigen::Index>(fixed.size()), 3);
  for (size_t r = 0; r < unknown.size(); ++r)
    rhs.row(static_cast<Eigen::Index>(r)) =
        umbrella[r] ? Eigen::RowVector3d::Zero() : Eigen::RowVector3d(target_delta.row(unknown[r]));
  for (size_t k = 0; k < fixed.size(); ++k) values.row(static_cast<Eigen::Index>(k)) = positions.row(fixed[k]);
  const solver::DenseMatrix x = ls.solve({rhs}, values);
  for (int v : unknown) positions.row(v) = x.row(v);
}

// A face with all three corners on a merging loop ends up flat: the whole loop lands on the
// other mesh's polyline. Flip its inner edge (to the neighbouring face's far vertex) while that
// keeps both new faces turned like the old pair. Vertex indices stay, so keys and maps do too.
int flip_loop_ears(TriMesh& m, const std::vector<BoundaryCorrespondence>& pairs) {
  std::vector<char> on_loop(static_cast<size_t>(m.num_vertices()), 0);
  for (const auto& c : pairs)
    for (int v : c.source_loop) on_loop[v] = 1;
  auto normal = [&](int a, int b, int c) {
    return Eigen::Vector3d((m.V.row(b) - m.V.row(a)).cross(m.V.row(c) - m.V.row(a)));
  };
  int flips = 0;
  // Flips of one pass touch disjoint vertices, so the pass's connectivity stays right for them.
  for (int pass_flips = -1; pass_flips != 0;) {
    pass_flips = 0;
    const Connectivity conn(m);
    std::vector<char> touched(static_cast<size_t>(m.num_vertices()), 0);
    for (int f = 0; f < m.num_faces(); ++f) {
      if (!on_loop[m.F(f, 0)] || !on_loop[m.F(f, 1)] || !on_loop[m.F(f, 2)]) continue;
      for (int j = 0; j < 3; ++j) {
        const int e = conn.face_edge(f, j);
        if (conn.is_boundary_edge(e) || conn.edge_face_count(e) != 2) continue;
        const int x = m.F(f, j), y = m.F(f, (j + 1) % 3), b = m.F(f, (j + 2) % 3);
        const auto ef = conn.edge_faces(e);
        const int g = ef[0] == f ? ef[1] : ef[0];
        int d = -1;
        for (int k = 0; k < 3; ++k)
          if (m.F(g, k) != x && m.F(g, k) != y) d = m.F(g, k);
        if (d < 0 || on_loop[d] || conn.find_edge(b, d) >= 0) continue;
        if (touched[x] || touched[y] || touched[b] || touched[d]) continue;
        const Eigen::Vector3d before = normal(x, y, b).normalized() + normal(y, x, d).normalized();
        if (!(normal(x, d, b).dot(before) > 0) || !(normal(d, y, b).dot(before) > 0)) continue;
        m.F.row(f) << x, d, b;
        m.F.row(g) << d, y, b;
        touched[x] = touched[y] = touched[b] = touched[d] = 1;
        ++pass_flips;
        break;
      }
    }
    flips += pass_flips;
  }
  return flips;
}

[[noreturn]] void bands_overlap(int a, size_t b) {
  throw InvalidArgument("mesh_merge::merge(): the transition bands of pairs " + std::to_string(a) + " and " +
                        std::to_string(b) + " overlap; choose smaller widths");
}

Eigen::RowVector3d blend(const BandPoint& p, const Vertices& X) {
  Eigen::RowVector3d r = Eigen::RowVector3d::Zero();
  for (int j = 0; j < 3; ++j) r += p.weights[j] * X.row(p.vertices[j]);
  return r;
}

// The source at the target's scale (§3.3.1's s_i would bring it there anyway): source widths,
// the deformer's mean edge length and the overlap are then independent of the placement.
TriMesh source_at_target_scale(const TriMesh& source, const TriMesh& target,
                               const std::vector<BoundaryCorrespondence>& corr) {
  double ps = 0, pt = 0;
  for (const auto& c : corr)
    ps += loop_perimeter(source.V, c.source_loop), pt += loop_perimeter(target.V, c.target_loop);
  TriMesh src = source;
  src.V = ((source.V.rowwise() - source.V.colwise().mean()) * (pt / ps)).eval();
  flip_loop_ears(src, corr);
  return src;
}

// u along the source loop: each source vertex's correspondence point on the target loop,
// whose u is tu.
std::vector<double> source_loop_params(const BoundaryCorrespondence& c, const std::vector<double>& tu) {
  std::vector<double> su(c.source_loop.size());
  for (size_t i = 0; i < su.size(); ++i) {
    const int e = c.target_edge[i];
    const double next = e + 1 < static_cast<int>(tu.size()) ? tu[e + 1] : 1.0;
    su[i] = tu[e] + c.target_t[i] * (next - tu[e]);
  }
  return su;
}

// Every pair's bands, cut and parameterized (u along both loops follows the key
// correspondences).
// Throws when two pairs' bands overlap or a rim lies inside another pair's band.
std::vector<PairBands> make_bands(const TriMesh& src, const Connectivity& sconn, const TriMesh& target,
                                  const Connectivity& tconn, const std::vector<BoundaryCorrespondence>& corr,
                                  const TransitionOptions& o) {
  const int ns = src.num_vertices(), nt = target.num_vertices();
  std::vector<PairBands> bands;
  std::vector<int> band_of(static_cast<size_t>(ns + nt), -1);
  for (size_t p = 0; p < corr.size(); ++p) {
    const BoundaryCorrespondence& c = corr[p];
    const std::vector<double> tu = arc_length_params(target.V, c.target_loop);
    const std::vector<double> su = source_loop_params(c, tu);
    PairBands b;
    b.target = transition_band(target, tconn, c.target_loop, tu, o.target_width, true, "target");
    b.source = transition_band(src, sconn, c.source_loop, su, o.source_width, false, "source");
    for (const auto& [list, offset] : {std::pair{&b.source.vertices, 0}, std::pair{&b.target.vertices, ns}})
      for (int v : *list) {
        if (band_of[v + offset] >= 0) bands_overlap(band_of[v + offset], p);
        band_of[v + offset] = static_cast<int>(p);
      }
    b.source_on_target = overlap_points(b.source, b.target);
    b.target_on_source = overlap_points(b.target, b.source);
    bands.push_back(std::move(b));
  }
  // A rim inside another pair's band would move with that band, under the kept band zipped to it.
  for (size_t p = 0; p < bands.size(); ++p)
    for (const auto& [list, offset] : {std::pair{&bands[p].source.rim, 0}, std::pair{&bands[p].target.rim, ns}})
      for (int v : *list)
        if (band_of[v + offset] >= 0 && band_of[v + offset] != static_cast<int>(p))
          bands_overlap(band_of[v + offset], p);
  return bands;
}

// One implicit Laplacian system over both meshes (source first, then the target): the source
// ROI and the target bands deform, the rest of both meshes is the fixed region, and
// E_T ties each band vertex's transformed δ to the other band's at the same (u, 1 − v).
// Returns both meshes' deformed vertices; records the ROI, the source boundary, the solver's
// figures and the setup and solve times (setup counted from t0) in r.
Vertices deform_both(const TriMesh& src, const TriMesh& target, const std::vector<PairBands>& bands,
                     const std::vector<int>& source_roi, const std::vector<BoundaryConstraint>& cons,
                     const MergeOptions& o, MergeResult& r, std::chrono::steady_clock::time_point t0) {
  const int ns = src.num_vertices(), nt = target.num_vertices();
  TriMesh both;
  both.V.resize(ns + nt, 3);
  both.V << src.V, target.V;
  both.F.resize(src.num_faces() + target.num_faces(), 3);
  both.F << src.F, (target.F.array() + ns).matrix();
  mesh_deform::Selection sel;
  sel.roi = source_roi;
  std::vector<mesh_deform::LaplacianBlend> terms;
  for (const PairBands& b : bands) {
    for (int v : b.target.vertices) sel.roi.push_back(v + ns);
    for (size_t k = 0; k < b.source.vertices.size(); ++k) {
      const BandPoint& q = b.source_on_target[k];
      terms.push_back({b.source.vertices[k], {q.vertices[0] + ns, q.vertices[1] + ns, q.vertices[2] + ns}, q.weights});
    }
    for (size_t k = 0; k < b.target.vertices.size(); ++k) {
      const BandPoint& q = b.target_on_source[k];
      terms.push_back({b.target.vertices[k] + ns, q.vertices, q.weights});
    }
  }
  r.roi_vertices = static_cast<int>(sel.roi.size());
  mesh_deform::HandleTransforms tf;
  add_region_handles(src, cons, sel, tf);
  for (const BoundaryConstraint& k : cons) r.source_boundary.push_back(k.vertex);
  mesh_deform::ImplicitLaplacianDeformer deformer(both, o.implicit);
  deformer.set_selection(std::move(sel));
  deformer.set_laplacian_blends(std::move(terms), o.transition.weight);
  r.timings.setup_ms = ms_since(t0);

  t0 = std::chrono::steady_clock::now();
  Vertices X = deformer.deform(tf);
  r.solver = deformer.report();
  r.timings.solve_ms = ms_since(t0) - r.solver.setup_ms;
  r.timings.setup_ms += r.solver.setup_ms;
  return X;
}

// The kept band laid over both bands before zipping: its vertex at v (0 on its loop, 1 on
// its rim) goes to v · its own position + (1 − v) · its overlap point on the other band, whose
// parameter there is 1 − v. Its loop then meets the other band's rim, where the seam is
// zipped, and its rim stays: the band spans both bands, as the reconstruction (§3.3.3, "the
// connectivity information of one transition region") will, and the strip is triangulated
// across a closed gap rather than across a whole band.
Vertices kept_band_spread(const Vertices& kept, const Vertices& other, const std::vector<PairBands>& bands,
                          bool keep_source) {
  Vertices X = kept;
  for (const PairBands& b : bands) {
    const TransitionBand& own = keep_source ? b.source : b.target;
    const std::vector<BandPoint>& on_other = keep_source ? b.source_on_target : b.target_on_source;
    for (size_t k = 0; k < own.vertices.size(); ++k) {
      const int v = own.vertices[k];
      const double along = own.at(v).y();
      X.row(v) = along * kept.row(v) + (1 - along) * blend(on_other[k], other);
    }
  }
  return X;
}

// §3.3.3, Fig. 3.7 (b): the surface keeps one band's connectivity; the other band goes and
// the seam is zipped where the kept band, spread over both (kept_band_spread), meets the rest
// of the other mesh. Fills r's source and target vertex maps into the zipped mesh.
ZipResult zip_kept_band(const TriMesh& src, const TriMesh& target, const Vertices& Xt,
                        const std::vector<PairBands>& bands, bool keep_source, MergeResult& r) {
  const int ns = src.num_vertices(), nt = target.num_vertices();
  std::vector<BoundaryCorrespondence> seams(bands.size());
  std::vector<int> cut_map, removed;
  for (const PairBands& b : bands) {
    const TransitionBand& gone = keep_source ? b.target : b.source;
    removed.insert(removed.end(), gone.faces.begin(), gone.faces.end());
  }
  TriMesh rest_of_other = keep_source ? geometry::remove_faces(TriMesh{Xt, target.F}, removed, &cut_map)
                                      : geometry::remove_faces(TriMesh{r.source_deformed, src.F}, removed, &cut_map);
  const Vertices kept = keep_source ? kept_band_spread(r.source_deformed, Xt, bands, true)
                                    : kept_band_spread(Xt, r.source_deformed, bands, false);
  for (size_t p = 0; p < bands.size(); ++p) {
    const PairBands& b = bands[p];
    if (keep_source) {
      seams[p].source_loop = b.source.loop;
      for (int v : b.target.rim) seams[p].target_loop.push_back(cut_map[v]);
    } else {
      for (int v : b.source.rim) seams[p].source_loop.push_back(cut_map[v]);
      seams[p].target_loop = b.target.loop;
    }
  }
  // The zip removes the ring of its target argument next to each loop, which pinches where
  // the loop passes within a triangle of itself: the edges there are split (refine.h) and the
  // zip runs again.
  TriMesh kept_mesh{kept, keep_source ? src.F : target.F};
  TriMesh& ringed = keep_source ? rest_of_other : kept_mesh;
  const auto zip = [&] {
    return keep_source ? zip_seams(rest_of_other, kept_mesh, seams) : zip_seams(kept_mesh, rest_of_other, seams);
  };
  ZipResult z;
  try {
    z = zip();
  } catch (const InvalidArgument&) {
    std::vector<std::vector<int>> loops;
    for (const auto& seam : seams) loops.push_back(seam.target_loop);
    if (separate_loop_neighbourhoods(ringed, loops) == 0) throw;
    z = zip();
  }
  r.target_map.assign(static_cast<size_t>(nt), -1);
  r.source_map.assign(static_cast<size_t>(ns), -1);
  for (int v = 0; v < nt; ++v) {
    const int c = keep_source ? cut_map[v] : v;
    if (c >= 0) r.target_map[v] = z.target_map[c];
  }
  for (int v = 0; v < ns; ++v) {
    const int c = keep_source ? v : cut_map[v];
    if (c >= 0) r.source_map[v] = z.source_map[c];
  }
  return z;
}

// "We first apply the implicitly defined local deformation gradients onto the LCs before
// interpolating them": each kept band vertex wants τ (target) + (1 − τ) (source) of the
// deformed curvature normals, τ the target's share (v on the target band, 1 − v on the
// source band's: 1 next to the kept target, 0 next to the rest of the source). Reconstructs
// the kept bands in z.mesh and lists their vertices and shares in r.
void blend_kept_band(const TriMesh& src, const Connectivity& sconn, const TriMesh& target, const Connectivity& tconn,
                     const Vertices& Xt, const std::vector<PairBands>& bands, bool keep_source, ZipResult& z,
                     MergeResult& r) {
  std::vector<int> src_listed, tgt_listed;
  for (const PairBands& b : bands) {
    src_listed.insert(src_listed.end(), b.source.param_vertex.begin(), b.source.param_vertex.end());
    tgt_listed.insert(tgt_listed.end(), b.target.param_vertex.begin(), b.target.param_vertex.end());
  }
  const Vertices Ks = deformed_curvature(src, sconn, r.source_deformed, src_listed);
  const Vertices Kt = deformed_curvature(target, tconn, Xt, tgt_listed);
  const std::vector<int>& kept_map = keep_source ? r.source_map : r.target_map;
  const Eigen::VectorXd area = geometry::vertex_areas(z.mesh);
  Vertices wanted = Vertices::Zero(z.mesh.num_vertices(), 3);
  for (const PairBands& b : bands) {
    const TransitionBand& own = keep_source ? b.source : b.target;
    const std::vector<BandPoint>& other = keep_source ? b.source_on_target : b.target_on_source;
    const Vertices& k_own = keep_source ? Ks : Kt;
    const Vertices& k_other = keep_source ? Kt : Ks;
    for (size_t k = 0; k < own.vertices.size(); ++k) {
      const int v = own.vertices[k], m = kept_map[v];
      if (m < 0) continue;  // zipped away
      const double tau = keep_source ? 1 - own.at(v).y() : own.at(v).y();
      const double own_share = keep_source ? 1 - tau : tau;
      r.transition_vertices.push_back(m);
      r.transition_share.push_back(tau);
      wanted.row(m) = area(m) * (own_share * k_own.row(v) + (1 - own_share) * blend(other[k], k_other));
    }
  }
  reconstruct_band(z.mesh, r.transition_vertices, wanted);
}

// Splits the edges where `mesh` reaches back to one of `loops` within a triangle (refine.h),
// when a band of `width` next to one of them is not an annulus; transition_band() then says
// what still fails.
void separate_where_pinched(TriMesh& mesh, const std::vector<std::vector<int>>& loops, double width) {
  const Connectivity conn(mesh);
  for (const auto& loop : loops)
    if (!band_is_annulus(mesh, conn, loop, width, "")) {
      separate_loop_neighbourhoods(mesh, loops);
      return;
    }
}

std::vector<int> every_vertex(int n) {
  std::vector<int> all(static_cast<size_t>(n));
  for (int v = 0; v < n; ++v) all[v] = v;
  return all;
}

// §3.3.2's ROI, widened to the source bands, which E_T must be free to deform; a handle in a
// band is an error.
std::vector<int> dependent_roi_with_bands(const TriMesh& src, const Connectivity& sconn,
                                          const std::vector<PairBands>& bands, const MergeOptions& o) {
  std::vector<char> in(static_cast<size_t>(src.num_vertices()), 0);
  for (int v : dependent_roi(src, sconn, o)) in[v] = 1;
  std::vector<char> handle(in.size(), 0);
  for (int h : o.handles) handle[h] = 1;
  for (const PairBands& b : bands)
    for (int v : b.source.vertices) {
      if (handle[v])
        throw InvalidArgument("mesh_merge::merge(): handle vertex " + std::to_string(v) +
                              " lies in the source transition band; narrow the band or move the handle");
      in[v] = 1;
    }
  std::vector<int> roi;
  for (int v = 0; v < src.num_vertices(); ++v)
    if (in[v]) roi.push_back(v);
  return roi;
}

}  // namespace

MergeResult merge_with_transition(const TriMesh& source, const TriMesh& target_given,
                                  const std::vector<LoopPair>& pairs, const MergeOptions& o) {
  auto t0 = std::chrono::steady_clock::now();
  MergeResult r;
  const std::vector<BoundaryCorrespondence> corr =
      correspond_boundaries(source, Connectivity(source), target_given, Connectivity(target_given), pairs);
  const bool dependent = o.transition.configuration_dependent;
  // §3.3.2 keeps the user's placement; §3.3.1 may bring the source to the target's scale.
  TriMesh src = dependent ? source : source_at_target_scale(source, target_given, corr);
  if (dependent) flip_loop_ears(src, corr);
  // Where a mesh reaches back to its loop within a triangle, no band is an annulus: the edges
  // there are split. The loops keep their vertices, so the correspondences hold.
  TriMesh target = target_given;
  std::vector<std::vector<int>> source_loops, target_loops;
  for (const BoundaryCorrespondence& c : corr)
    source_loops.push_back(c.source_loop), target_loops.push_back(c.target_loop);
  separate_where_pinched(src, source_loops, o.transition.source_width);
  separate_where_pinched(target, target_loops, o.transition.target_width);
  const Connectivity sconn(src), tconn(target);
  const int ns = src.num_vertices(), nt = target.num_vertices();
  const std::vector<PairBands> bands = make_bands(src, sconn, target, tconn, corr, o.transition);
  // "With the same boundary condition as before" (§3.3.3): the source loop onto the target
  // loop, as in §3.3.1 (frames turned) or §3.3.2 (frames kept). The bands then lie on either
  // side of the seam and E_T mixes their details; the kept band is spread over both before the
  // zip (kept_band_spread).
  const std::vector<BoundaryConstraint> cons = boundary_constraints(src, target, corr, dependent);
  const std::vector<int> source_roi = dependent ? dependent_roi_with_bands(src, sconn, bands, o) : every_vertex(ns);

  const Vertices X = deform_both(src, target, bands, source_roi, cons, o, r, t0);
  r.source_rest = src;
  r.source_deformed = X.topRows(ns);

  t0 = std::chrono::steady_clock::now();
  const bool keep_source = o.transition.keep == TransitionKeep::Source;
  const Vertices Xt = X.bottomRows(nt);
  ZipResult z = zip_kept_band(src, target, Xt, bands, keep_source, r);
  r.timings.zip_ms = ms_since(t0);

  t0 = std::chrono::steady_clock::now();
  blend_kept_band(src, sconn, target, tconn, Xt, bands, keep_source, z, r);
  // The kept band was reconstructed to blend into the seam, and the source is deformed
  // anyway: both may move to unfold the seam. Of the rest, only the ring next to the seam may,
  // and only where a strip folds; those vertices are listed as smoothed, as the zip's
  // smoothing lists the target's seam band.
  std::vector<int> movable = r.transition_vertices;
  for (int v : seam_band(z.mesh, z.seam_vertices, 1)) movable.push_back(v);
  const Vertices before = z.mesh.V;
  unfold_seam(z.mesh, z.strip_faces, movable);
  flip_thin_diagonals(z.mesh, z.strip_faces);
  for (int v = 0; v < z.mesh.num_vertices(); ++v)
    if (z.mesh.V.row(v) != before.row(v)) r.smoothed.push_back(v);
  r.timings.smooth_ms = ms_since(t0);  // the band replaces the seam smoothing
  r.mesh = std::move(z.mesh);
  r.strip_faces = std::move(z.strip_faces);
  r.seam_vertices = std::move(z.seam_vertices);
  r.target_map.resize(static_cast<size_t>(target_given.num_vertices()));  // the meshes as given
  r.source_map.resize(static_cast<size_t>(source.num_vertices()));
  return r;
}

}  // namespace lapis::mesh_merge::detail
