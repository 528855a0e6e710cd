// Head loading, scalp, roots and growth determinism.
#include <doctest/doctest.h>

#include <omp.h>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>

#include "fixture.h"
#include "lapis/core/error.h"
#include "lapis/geometry/connected_region.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/procedural.h"
#include "lapis/hair_sketch/stream_curve.h"

using namespace hair_test;

namespace {

std::filesystem::path temp_file(const std::string& name, const std::string& text) {
  const auto p = std::filesystem::temp_directory_path() / ("lapis_hair_" + name);
  std::ofstream(p) << text;
  return p;
}

}  // namespace

TEST_CASE("hair_sketch: the bundled head is a closed mesh with a scalp cap above the face") {
  const Head& head = bundled_head();
  CHECK(head.mesh.num_faces() > 10000);
  const int scalp = head.scalp_face_count();
  CHECK(scalp > head.mesh.num_faces() / 6);
  CHECK(scalp < head.mesh.num_faces() / 2);
  CHECK(head.inside(head.center));
  // Neck below, crown above the centre.
  CHECK(head.box.min().y() < head.center.y() - 1.5);
  CHECK(head.box.max().y() > head.center.y() + 0.5);
}

namespace {

double smallest_angle(const lapis::geometry::TriMesh& m, int f) {
  double least = std::numbers::pi;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d p = m.V.row(m.F(f, k)).transpose(), a = m.V.row(m.F(f, (k + 1) % 3)).transpose(),
                          b = m.V.row(m.F(f, (k + 2) % 3)).transpose();
    least = std::min(least, std::acos(std::clamp((a - p).normalized().dot((b - p).normalized()), -1.0, 1.0)));
  }
  return least;
}

double signed_volume(const lapis::geometry::TriMesh& m) {
  double v = 0;
  for (int f = 0; f < m.num_faces(); ++f) v += m.V.row(m.F(f, 0)).dot(m.V.row(m.F(f, 1)).cross(m.V.row(m.F(f, 2))));
  return v / 6;
}

}  // namespace

TEST_CASE("hair_sketch: the bundled head is one closed, oriented, manifold surface of genus 0") {
  const auto& mesh = bundled_head().mesh;
  CHECK(mesh.num_faces() > 20000);  // tens of thousands of triangles
  CHECK(mesh.num_faces() < 100000);
  const lapis::geometry::Connectivity conn(mesh);
  int open_or_shared = 0, same_direction = 0;
  for (int e = 0; e < conn.num_edges(); ++e) {
    open_or_shared += conn.edge_face_count(e) != 2;
    // Consistently oriented: the two faces run along their edge in opposite directions.
    const auto [f, g] = conn.edge_faces(e);
    if (f < 0 || g < 0) continue;
    auto forward = [&](int face) {
      for (int k = 0; k < 3; ++k)
        if (mesh.F(face, k) == conn.edges()[e][0]) return mesh.F(face, (k + 1) % 3) == conn.edges()[e][1];
      return false;
    };
    same_direction += forward(f) == forward(g);
  }
  CHECK(open_or_shared == 0);
  CHECK(same_direction == 0);
  // Manifold vertices: the faces around each one form a single closed fan.
  int not_a_disc = 0;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    try {
      not_a_disc += conn.one_ring_ordered(v).size() != conn.vertex_faces(v).size() || conn.vertex_faces(v).empty();
    } catch (const lapis::InvalidArgument&) {
      ++not_a_disc;
    }
  }
  CHECK(not_a_disc == 0);
  CHECK(lapis::geometry::connected_components(conn).count == 1);
  CHECK(lapis::geometry::euler_characteristic(conn) == 2);
  CHECK(signed_volume(mesh) > 0);  // normals point out
}

TEST_CASE("hair_sketch: the bundled head has well-shaped triangles and no creases") {
  const auto& mesh = bundled_head().mesh;
  const auto& normals = bundled_head().face_normals;
  double area_sum = 0, least_area = 1e300, least_angle = std::numbers::pi;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)).transpose(), b = mesh.V.row(mesh.F(f, 1)).transpose(),
                          c = mesh.V.row(mesh.F(f, 2)).transpose();
    const double area = 0.5 * (b - a).cross(c - a).norm();
    area_sum += area;
    least_area = std::min(least_area, area);
    least_angle = std::min(least_angle, smallest_angle(mesh, f));
  }
  CHECK(least_area > 0.01 * area_sum / mesh.num_faces());
  CHECK(least_angle * 180 / std::numbers::pi > 25);  // the mesher bounds it by 30 degrees
  // Smooth: neighbouring faces turn by little anywhere, the lips' parting included.
  const lapis::geometry::Connectivity conn(mesh);
  double sharpest = 0;
  for (int e = 0; e < conn.num_edges(); ++e) {
    const auto [f, g] = conn.edge_faces(e);
    const double cos = std::clamp(normals.row(f).dot(normals.row(g)), -1.0, 1.0);
    sharpest = std::max(sharpest, std::acos(cos) * 180 / std::numbers::pi);
  }
  CHECK(sharpest < 60);
}

TEST_CASE("hair_sketch: the bundled scalp is one cap on the cranium, above the face and clear of the ears") {
  const Head& head = bundled_head();
  const auto& V = head.mesh.V;
  const auto mask =
      read_scalp_mask(std::filesystem::path(LAPIS_SOURCE_DIR) / "assets" / "head_scalp.txt", head.mesh.num_vertices());
  REQUIRE(mask.size() > 1000);
  // The landmarks of the bundled head's conventions: brow ridges at y = 0.12, the face in
  // front (z > 0), the ears' shells about |x| = 0.8 below y = 0.15, the nape at y ≈ -0.3.
  int below_brow_in_front = 0, on_face = 0, on_ear = 0, below_nape = 0, off_cranium = 0;
  for (int v : mask) {
    const Eigen::Vector3d p = V.row(v).transpose();
    below_brow_in_front += p.z() > 0 && p.y() < 0.12;
    on_face += p.z() > 0.5 && p.y() < 0.35;
    on_ear += std::abs(p.x()) > 0.72 && p.y() < 0.15 && std::abs(p.z() + 0.08) < 0.2;
    below_nape += p.y() < -0.4;
    // The cranium: an ellipsoid with semi-axes (0.78, 0.98, 0.98) about (0, 0.02, -0.05).
    const double r = Eigen::Vector3d(p.x() / 0.78, (p.y() - 0.02) / 0.98, (p.z() + 0.05) / 0.98).norm();
    off_cranium += r < 0.95 || r > 1.1;
  }
  CHECK(below_brow_in_front == 0);
  CHECK(on_face == 0);
  CHECK(on_ear == 0);
  CHECK(below_nape == 0);
  CHECK(off_cranium == 0);
  // The crown belongs to the scalp, and the scalp is one patch reachable from it.
  int crown = 0;
  for (int v = 1; v < head.mesh.num_vertices(); ++v)
    if (V(v, 1) > V(crown, 1)) crown = v;
  std::vector<char> in(head.mesh.num_vertices(), 0);
  for (int v : mask) in[v] = 1;
  REQUIRE(in[crown]);
  const lapis::geometry::Connectivity conn(head.mesh);
  CHECK(lapis::geometry::connected_region(conn, crown, in).size() == mask.size());
}

TEST_CASE("hair_sketch: the scalp's solid angle seen from the centre is that of its cap") {
  // Unit sphere, scalp above y = 0.5: the centre sits a quarter up the scalp (y = 0.625),
  // below the cap's rim circle (radius √0.75 at y = 0.5), so the rim is seen at
  // θ = π − atan(√0.75 / 0.125) from +y and the cap spans 2π(1 − cos θ).
  const auto sphere = lapis::geometry::make_icosphere(5);
  const Head head = make_head(sphere, scalp_vertices_above(sphere, {0, 0.5, 0}, Eigen::Vector3d::UnitY()));
  CHECK(head.center.y() == doctest::Approx(0.625).epsilon(0.01));
  const double rim_below_centre = head.center.y() - 0.5;
  const double theta = std::numbers::pi - std::atan(std::sqrt(0.75) / rim_below_centre);
  const double expected = 2 * std::numbers::pi * (1 - std::cos(theta));
  CHECK(head.scalp_solid_angle == doctest::Approx(expected).epsilon(0.03));
  // No scalp: no roots, with the reason.
  const Head bald = make_head(sphere, {});
  CHECK(bald.scalp_solid_angle == 0);
  CHECK_THROWS_WITH_AS(sample_roots(bald), doctest::Contains("scalp is empty"), lapis::InvalidArgument);
}

TEST_CASE("hair_sketch: roots lie on the scalp, never inside the head, deterministic per seed") {
  const Head& head = bundled_head();
  RootOptions o;
  o.count = 5000;
  const auto a = sample_roots(head, o);
  const auto b = sample_roots(head, o);
  CHECK(a.size() > 0.8 * o.count);
  CHECK(a.size() < 1.2 * o.count);
  REQUIRE(a.size() == b.size());
  for (size_t i = 0; i < a.size(); ++i) REQUIRE(a[i] == b[i]);
  int inside = 0;
  for (const auto& r : a) inside += head.inside(r);
  CHECK(inside == 0);
  for (size_t i = 0; i < a.size(); i += 97) {
    const auto c = head.bvh->closest_point(a[i]);
    CHECK(c.distance < 0.01);
    CHECK(head.scalp_face[c.face]);
  }
  o.seed = 2;
  const auto c = sample_roots(head, o);
  CHECK((c.size() != a.size() || c[0] != a[0]));
}

namespace {

// The exact field of one stream curve down the back of the head, on a small grid.
SampledField stream_curve_field() {
  const Grid g = small_grid(6000);
  StreamCurve s;
  s.points = {{0, 1.3, 0}, {0, 0.8, -1.2}, {0, -1.0, -1.3}};
  return SampledField(g, solve_exact(g, ConstraintSet::from(s.constraints(g))));
}

std::vector<Eigen::Vector3d> scalp_roots(int count) {
  RootOptions ro;
  ro.count = count;
  return sample_roots(bundled_head(), ro);
}

}  // namespace

TEST_CASE("hair_sketch: growth is deterministic and independent of the thread count") {
  const SampledField field = stream_curve_field();
  const auto roots = scalp_roots(2000);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const Strands one = grow_strands(field, roots);
  omp_set_num_threads(std::max(2, threads));
  const Strands two = grow_strands(field, roots);
  omp_set_num_threads(threads);
  REQUIRE(one.offsets == two.offsets);
  CHECK(one.points == two.points);
  CHECK(one.segments() > 10 * one.count());  // strands actually grew
  for (int i = 0; i < one.count(); ++i) CHECK_FALSE(bundled_head().inside(one.points[one.offsets[i]].cast<double>()));
}

TEST_CASE("hair_sketch: growth given the head's clearance keeps every strand out of the head") {
  const Head& head = bundled_head();
  const Grid g = small_grid(6000);
  const HeadClearance clearance(head, g);
  StreamCurve curve;  // no avoidance: hair runs into the head
  curve.points = {{0, 1.3, 0}, {0, 0.8, -1.2}, {0, -1.0, -1.3}};
  const Field f = solve_exact(g, ConstraintSet::from(curve.constraints(g)));
  const SampledField bare(g, f), kept(g, f, &clearance);
  const auto roots = scalp_roots(2000);
  const GrowthOptions opt;
  const Strands before = grow_strands(bare, roots, opt), after = grow_strands(kept, roots, opt);
  const int pen_before = count_penetrating_segments(before, head), pen_after = count_penetrating_segments(after, head);
  MESSAGE("penetrating segments: " << pen_before << " without the clearance, " << pen_after << " with it");
  REQUIRE(pen_before > 100);
  CHECK(pen_after == 0);
  REQUIRE(after.count() == before.count());
  const float least = static_cast<float>(opt.head_clearance * g.spacing);
  int changed = 0, short_segments = 0;
  for (int s = 0; s < after.count(); ++s) {
    // Up to the first point growth put closer than the clearance, or whose segment passes
    // closer at its midpoint, the strand is the bare one, float for float: the check changes
    // nothing it need not.
    const int a = before.offsets[s], n = before.offsets[s + 1] - a, m = after.offsets[s + 1] - after.offsets[s];
    auto clear = [&](int i) {
      const Eigen::Vector3f& p = before.points[a + i];
      return clearance(p) >= least && clearance(0.5f * (p + before.points[a + i - 1])) >= least;
    };
    int k = 1;
    while (k < n && clear(k)) ++k;
    REQUIRE(m >= std::min(k, n));
    for (int i = 0; i < std::min(k, n); ++i) {
      INFO("s " << s << " i " << i << " k " << k << " n " << n);
      REQUIRE(after.points[after.offsets[s] + i] == before.points[a + i]);
    }
    changed += k < n;
    // Strands slide along the scalp or end: no point is left on top of the one before it.
    for (int i = after.offsets[s] + 1; i < after.offsets[s + 1]; ++i)
      short_segments += (after.points[i] - after.points[i - 1]).norm() < 0.05f * 0.5f * g.spacing * 0.05f;
  }
  MESSAGE(changed << " of " << after.count() << " strands came closer than the clearance");
  CHECK(changed > 100);
  CHECK(short_segments == 0);
  // Off, the clearance is ignored: the thesis' strands.
  GrowthOptions off;
  off.keep_outside_head = false;
  const Strands thesis = grow_strands(kept, roots, off);
  CHECK(thesis.offsets == before.offsets);
  CHECK(thesis.points == before.points);
  // The same on one thread as on two.
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const Strands one = grow_strands(kept, roots, opt);
  omp_set_num_threads(threads);
  CHECK(one.offsets == after.offsets);
  CHECK(one.points == after.points);
  // A clearance sampled on another grid is refused by name.
  const HeadClearance other(head, small_grid(3000));
  CHECK_THROWS_WITH_AS(SampledField(g, f, &other), doctest::Contains("another grid"), lapis::InvalidArgument);
}

TEST_CASE(
    "hair_sketch: growth follows the §4.6 rule step by step; regrowth into reused storage "
    "gives the same strands") {
  const SampledField field = stream_curve_field();
  const Grid& g = field.grid();
  const auto roots = scalp_roots(3000);
  const GrowthOptions opt;
  const Strands grown = grow_strands(field, roots, opt);
  REQUIRE(grown.count() == static_cast<int>(roots.size()));
  // The reference: one strand at a time through the public scalar lookup, in grid
  // coordinates q += 0.5·v(q), p = origin + d·q (so p += l·v with l = 0.5 d), until
  // |v| < 0.05, the box is left (v = 0 there) or the length cap. The kernel (eight strands
  // side by side, vector lerps) must give exactly these floats.
  const float step = static_cast<float>(opt.step), d = static_cast<float>(g.spacing);
  const Eigen::Vector3f origin = g.origin.cast<float>();
  const int max_steps = static_cast<int>(opt.max_length / opt.step);
  for (int i = 0; i < grown.count(); i += 7) {
    std::vector<Eigen::Vector3f> ref{roots[i].cast<float>()};
    Eigen::Vector3f q = (ref[0] - origin) * static_cast<float>(1.0 / g.spacing);
    for (int it = 0; it < max_steps; ++it) {
      const Eigen::Vector3f v = field.at_grid(q);
      if (v.squaredNorm() < static_cast<float>(opt.min_magnitude * opt.min_magnitude)) break;
      q += step * v;
      ref.push_back(origin + d * q);
    }
    REQUIRE(grown.offsets[i + 1] - grown.offsets[i] == static_cast<int>(ref.size()));
    for (size_t k = 0; k < ref.size(); ++k) REQUIRE(grown.points[grown.offsets[i] + k] == ref[k]);
  }
  // Regrowth into storage that held more strands, then fewer.
  StrandGrower grower(opt);
  Strands reused;
  grower.grow(field, roots, reused);
  const std::vector<Eigen::Vector3d> fewer(roots.begin(), roots.begin() + roots.size() / 3);
  grower.grow(field, fewer, reused);
  const Strands fresh = grow_strands(field, fewer, opt);
  REQUIRE(reused.offsets == fresh.offsets);
  CHECK(reused.points == fresh.points);
  grower.grow(field, roots, reused);
  REQUIRE(reused.offsets == grown.offsets);
  CHECK(reused.points == grown.points);
}

TEST_CASE(
    "hair_sketch: growth from a root outside the grid stops at once; bad roots and "
    "options are rejected by name") {
  const SampledField field = stream_curve_field();
  const Grid& g = field.grid();
  std::vector<Eigen::Vector3d> roots = scalp_roots(20);
  const Eigen::Vector3d far = g.origin - Eigen::Vector3d::Constant(10 * g.spacing);
  roots[3] = far;  // outside the box, where the field is zero
  const Strands s = grow_strands(field, roots);
  REQUIRE(s.count() == static_cast<int>(roots.size()));
  CHECK(s.offsets[4] - s.offsets[3] == 1);  // the root alone
  CHECK(s.points[s.offsets[3]] == far.cast<float>());
  CHECK(s.offsets[5] - s.offsets[4] > 1);  // its neighbours grow as usual

  auto message = [&](std::vector<Eigen::Vector3d> r, GrowthOptions o) -> std::string {
    try {
      grow_strands(field, r, o);
    } catch (const lapis::InvalidArgument& e) {
      return e.what();
    }
    return "no error";
  };
  roots[7].y() = std::numeric_limits<double>::quiet_NaN();
  CHECK(message(roots, {}).find("root 7 is not finite") != std::string::npos);
  roots[7] = roots[6];
  GrowthOptions o;
  o.step = 0;
  CHECK(message(roots, o).find("step must be positive") != std::string::npos);
  o = {};
  o.max_length = std::numeric_limits<double>::infinity();
  CHECK(message(roots, o).find("max_length must be non-negative") != std::string::npos);
  o = {};
  o.min_magnitude = -1;
  CHECK(message(roots, o).find("min_magnitude must be non-negative") != std::string::npos);
  CHECK(message(roots, {}) == "no error");
}

TEST_CASE("hair_sketch: malformed head and scalp files give clear errors") {
  CHECK_THROWS_AS(load_head(temp_file("bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n")), lapis::Error);
  CHECK_THROWS_AS(load_head(temp_file("garbage.obj", "this is not a mesh\n")), lapis::Error);
  CHECK_THROWS_AS(load_head("/nonexistent/head.obj"), lapis::IoError);
  const auto mask = temp_file("mask.txt", "# ok\n1\n2 3\n");
  try {
    read_scalp_mask(mask, 10);
    FAIL("expected IoError");
  } catch (const lapis::IoError& e) {
    CHECK(std::string(e.what()).find("hair_sketch::read_scalp_mask(): ") == 0);
    CHECK(std::string(e.what()).find(":3: expected one vertex index") != std::string::npos);
  }
  CHECK_THROWS_AS(read_scalp_mask(temp_file("mask2.txt", "12\n"), 10), lapis::IoError);
  // Without a mask the scalp is the cap above a plane.
  const Head h = load_head(std::filesystem::path(LAPIS_SOURCE_DIR) / "assets" / "head.obj");
  CHECK(h.scalp_face_count() > 0);
  CHECK(h.scalp_face_count() < h.mesh.num_faces() / 2);
}
