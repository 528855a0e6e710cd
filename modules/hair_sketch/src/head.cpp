#include "lapis/hair_sketch/head.h"

#include <cmath>
#include <fstream>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>
#include <string>

#include "lapis/core/error.h"
#include "lapis/geometry/io.h"
#include "lapis/geometry/normals.h"

namespace lapis::hair_sketch {

namespace {

// Where the ray from the centre in direction (θ from +y, φ about y) leaves the head, if that
// is on the scalp; the last crossing is the outer surface even where a ray grazes an ear.
std::optional<geometry::RayHit> scalp_hit(const Head& head, double theta, double phi) {
  const Eigen::Vector3d d(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
  auto hit = head.bvh->intersect(head.center, d, 10 * head.box.sizes().maxCoeff());
  if (!hit || !head.scalp_face[hit->face]) return std::nullopt;
  return hit;
}

// Solid angle of the directions from the centre that leave the head through the scalp, from
// a 60 × 120 pass in θ, φ weighted by sin θ. It sets the sampling step of sample_roots(); it
// is computed once per head because it is most of the cost of sampling a few hundred roots.
double estimate_scalp_solid_angle(const Head& head) {
  const double pi = std::numbers::pi;
  int hits = 0, total = 0;
  for (int i = 0; i < 60; ++i)
    for (int j = 0; j < 120; ++j) {
      const double theta = (i + 0.5) * pi / 60, phi = (j + 0.5) * 2 * pi / 120;
      const int w = static_cast<int>(1000 * std::sin(theta));
      total += w;
      if (scalp_hit(head, theta, phi)) hits += w;
    }
  return 4 * pi * hits / total;
}

}  // namespace

std::pair<Eigen::Vector3d, Eigen::Vector3d> Head::closest(const Eigen::Vector3d& p) const {
  const geometry::ClosestPoint c = bvh->closest_point(p);
  return {face_normals.row(c.face).transpose(), c.point};
}

int Head::scalp_face_count() const {
  int n = 0;
  for (char c : scalp_face) n += c;
  return n;
}

Head make_head(geometry::TriMesh mesh, const std::vector<int>& scalp_vertices) {
  geometry::require_valid(mesh, {}, "hair_sketch::make_head()");
  if (mesh.num_faces() < 4)
    throw InvalidArgument("hair_sketch::make_head(): a head needs a closed mesh, got " +
                          std::to_string(mesh.num_faces()) + " faces");
  Head h;
  std::vector<char> in(mesh.num_vertices(), 0);
  for (int v : scalp_vertices) {
    if (v < 0 || v >= mesh.num_vertices())
      throw InvalidArgument("hair_sketch::make_head(): scalp vertex " + std::to_string(v) + " outside [0, " +
                            std::to_string(mesh.num_vertices()) + ")");
    in[v] = 1;
  }
  h.scalp_face.assign(mesh.num_faces(), 0);
  for (int f = 0; f < mesh.num_faces(); ++f) h.scalp_face[f] = in[mesh.F(f, 0)] && in[mesh.F(f, 1)] && in[mesh.F(f, 2)];
  for (int i = 0; i < mesh.num_vertices(); ++i) h.box.extend(mesh.V.row(i).transpose());
  // The box spans neck to crown, so its centre can sit in the jaw; the cranium's centre is
  // better found from the scalp's height range.
  h.center = h.box.center();
  if (!scalp_vertices.empty()) {
    double lo = 1e300, hi = -1e300;
    for (int v : scalp_vertices) lo = std::min(lo, mesh.V(v, 1)), hi = std::max(hi, mesh.V(v, 1));
    h.center.y() = lo + 0.25 * (hi - lo);
  }
  h.face_normals = geometry::face_normals(mesh);
  h.bvh = std::make_shared<geometry::Bvh>(mesh);
  h.mesh = std::move(mesh);
  h.scalp_solid_angle = estimate_scalp_solid_angle(h);
  return h;
}

std::vector<int> scalp_vertices_above(const geometry::TriMesh& mesh, const Eigen::Vector3d& point,
                                      const Eigen::Vector3d& up) {
  std::vector<int> out;
  for (int i = 0; i < mesh.num_vertices(); ++i)
    if ((mesh.V.row(i).transpose() - point).dot(up) > 0) out.push_back(i);
  return out;
}

std::vector<int> read_scalp_mask(const std::filesystem::path& path, int num_vertices) {
  std::ifstream in(path);
  if (!in) throw IoError("hair_sketch::read_scalp_mask(): cannot open " + path.string());
  std::vector<int> out;
  std::string line;
  for (int lineno = 1; std::getline(in, line); ++lineno) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream ss(line);
    long long v;
    std::string rest;
    if (!(ss >> v) || (ss >> rest))
      throw IoError("hair_sketch::read_scalp_mask(): " + path.string() + ":" + std::to_string(lineno) +
                    ": expected one vertex index, got '" + line + "'");
    if (v < 0 || v >= num_vertices)
      throw IoError("hair_sketch::read_scalp_mask(): " + path.string() + ":" + std::to_string(lineno) + ": vertex " +
                    std::to_string(v) + " outside [0, " + std::to_string(num_vertices) + ")");
    out.push_back(static_cast<int>(v));
  }
  return out;
}

Head load_head(const std::filesystem::path& mesh_path, const std::filesystem::path& mask_path) {
  geometry::TriMesh mesh = geometry::read_mesh(mesh_path);
  if (mesh.num_faces() == 0) throw IoError("hair_sketch::load_head(): " + mesh_path.string() + " has no faces");
  std::vector<int> scalp;
  if (!mask_path.empty()) {
    scalp = read_scalp_mask(mask_path, mesh.num_vertices());
  } else {
    Eigen::AlignedBox3d box;
    for (int i = 0; i < mesh.num_vertices(); ++i) box.extend(mesh.V.row(i).transpose());
    const Eigen::Vector3d p = box.center() + Eigen::Vector3d(0, 0.15 * box.sizes().y(), 0);
    scalp = scalp_vertices_above(mesh, p, Eigen::Vector3d::UnitY());
  }
  return make_head(std::move(mesh), scalp);
}

Head load_bundled_head(const std::filesystem::path& source_dir) {
  return load_head(source_dir / "assets" / "head.obj", source_dir / "assets" / "head_scalp.txt");
}

std::vector<Eigen::Vector3d> sample_roots(const Head& head, const RootOptions& options) {
  if (options.count <= 0)
    throw InvalidArgument("hair_sketch::sample_roots(): count must be positive, got " + std::to_string(options.count));
  if (!(head.scalp_solid_angle > 0)) throw InvalidArgument("hair_sketch::sample_roots(): the scalp is empty");
  const double pi = std::numbers::pi;
  const double size = head.box.sizes().maxCoeff();
  auto cast = [&](double theta, double phi, Eigen::Vector3d& root) {
    const auto hit = scalp_hit(head, theta, phi);
    if (!hit) return false;
    root = hit->point + options.lift * size * head.face_normals.row(hit->face).transpose();
    return !head.inside(root);
  };
  const double step = std::sqrt(head.scalp_solid_angle / options.count);  // radians, uniform per solid angle
  std::mt19937 rng(options.seed);
  std::uniform_real_distribution<double> u(-options.jitter, options.jitter);
  std::vector<Eigen::Vector3d> roots;
  roots.reserve(options.count + options.count / 8);
  const int nt = static_cast<int>(std::ceil(pi / step));
  for (int i = 0; i < nt; ++i) {
    const double theta0 = (i + 0.5) * pi / nt;
    const int np = std::max(1, static_cast<int>(std::round(2 * pi * std::sin(theta0) / step)));
    for (int j = 0; j < np; ++j) {
      // Draw both jitters always so the sequence does not depend on which rays hit.
      const double ut = u(rng), up = u(rng);
      const double theta = std::clamp(theta0 + ut * pi / nt, 0.0, pi);
      const double phi = (j + 0.5 + up) * 2 * pi / np;
      Eigen::Vector3d root;
      if (cast(theta, phi, root)) roots.push_back(root);
    }
  }
  return roots;
}

}  // namespace lapis::hair_sketch
