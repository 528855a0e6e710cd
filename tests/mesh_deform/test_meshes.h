// Procedural meshes and selections shared by the mesh_deform tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <tuple>

#include "lapis/geometry/tri_mesh.h"
#include "lapis/mesh_deform/deformer.h"

namespace lapis::mesh_deform::test {

// Planar (z = 0) grid of nx by ny vertices over [0, 1]², interior vertices jittered by up to
// `jitter` cells (the irregular mesh of thesis Fig. 2.4). Diagonals alternate so corners have
// valence 2 and 3.
inline TriMesh planar_grid(int nx, int ny, double jitter, unsigned seed = 1) {
  TriMesh m;
  m.V.resize(nx * ny, 3);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      double x = double(i) / (nx - 1), y = double(j) / (ny - 1);
      if (i > 0 && j > 0 && i < nx - 1 && j < ny - 1) {
        x += u(rng) / (nx - 1);
        y += u(rng) / (ny - 1);
      }
      m.V.row(j * nx + i) << x, y, 0;
    }
  m.F.resize(2 * (nx - 1) * (ny - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const int a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      m.F.row(f++) << a, b, d;
      m.F.row(f++) << a, d, c;
    }
  return m;
}

// Closed box bar [0, w]² x [0, h] with n cells across and n * h / w cells along, every face
// a grid of right triangles; vertices welded.
inline TriMesh box_bar(int n, double w, double h) {
  const int nz = static_cast<int>(std::lround(n * h / w));
  std::map<std::tuple<long, long, long>, int> index;
  std::vector<Eigen::RowVector3d> pts;
  std::vector<Eigen::RowVector3i> tris;
  auto vid = [&](const Eigen::RowVector3d& p) {
    const auto key = std::make_tuple(std::lround(p.x() * 1e6), std::lround(p.y() * 1e6), std::lround(p.z() * 1e6));
    auto it = index.find(key);
    if (it != index.end()) return it->second;
    index[key] = static_cast<int>(pts.size());
    pts.push_back(p);
    return static_cast<int>(pts.size()) - 1;
  };
  // A face: origin o, edge vectors a (na cells), b (nb cells); normal a x b points outwards.
  auto face = [&](Eigen::RowVector3d o, Eigen::RowVector3d a, int na, Eigen::RowVector3d b, int nb) {
    for (int j = 0; j < nb; ++j)
      for (int i = 0; i < na; ++i) {
        auto P = [&](int s, int t) { return vid(o + a * (double(s) / na) + b * (double(t) / nb)); };
        const int p00 = P(i, j), p10 = P(i + 1, j), p01 = P(i, j + 1), p11 = P(i + 1, j + 1);
        tris.emplace_back(p00, p10, p11);
        tris.emplace_back(p00, p11, p01);
      }
  };
  using R = Eigen::RowVector3d;
  face(R(0, 0, 0), R(0, w, 0), n, R(w, 0, 0), n);    // bottom, normal -z
  face(R(0, 0, h), R(w, 0, 0), n, R(0, w, 0), n);    // top, +z
  face(R(0, 0, 0), R(w, 0, 0), n, R(0, 0, h), nz);   // y = 0, normal -y
  face(R(w, w, 0), R(-w, 0, 0), n, R(0, 0, h), nz);  // y = w, +y
  face(R(0, w, 0), R(0, -w, 0), n, R(0, 0, h), nz);  // x = 0, -x
  face(R(w, 0, 0), R(0, w, 0), n, R(0, 0, h), nz);   // x = w, +x
  TriMesh m;
  m.V.resize(static_cast<int>(pts.size()), 3);
  for (size_t i = 0; i < pts.size(); ++i) m.V.row(static_cast<int>(i)) = pts[i];
  m.F.resize(static_cast<int>(tris.size()), 3);
  for (size_t i = 0; i < tris.size(); ++i) m.F.row(static_cast<int>(i)) = tris[i];
  return m;
}

// Open tube of radius r around the vertical axis through (0.5, 0.5), height h: `around`
// vertices per ring, rings spaced like the ring's edges. Curved everywhere, so every Laplacian
// coordinate is non-zero and the naive method's unrotated details show.
inline TriMesh tube(int around, double r, double h) {
  const double edge = 2 * M_PI * r / around;
  const int rings = static_cast<int>(std::lround(h / edge)) + 1;
  TriMesh m;
  m.V.resize(around * rings, 3);
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < around; ++i) {
      const double a = 2 * M_PI * (i + 0.5 * (j % 2)) / around;
      m.V.row(j * around + i) << 0.5 + r * std::cos(a), 0.5 + r * std::sin(a), h * j / (rings - 1);
    }
  m.F.resize(2 * around * (rings - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < rings; ++j)
    for (int i = 0; i < around; ++i) {
      const int a = j * around + i, b = j * around + (i + 1) % around;
      const int c = (j + 1) * around + i, d = (j + 1) * around + (i + 1) % around;
      if (j % 2 == 0) {
        m.F.row(f++) << a, b, c;
        m.F.row(f++) << b, d, c;
      } else {
        m.F.row(f++) << a, d, c;
        m.F.row(f++) << a, b, d;
      }
    }
  return m;
}

// Vertices whose coordinate `axis` lies in the lowest `lo` / highest `hi` fraction of the
// bounding box.
inline std::vector<int> slab(const TriMesh& m, int axis, double from, double to) {
  const double mn = m.V.col(axis).minCoeff(), mx = m.V.col(axis).maxCoeff();
  std::vector<int> out;
  for (int i = 0; i < m.num_vertices(); ++i) {
    const double t = (m.V(i, axis) - mn) / (mx - mn);
    if (t >= from && t <= to) out.push_back(i);
  }
  return out;
}

inline std::vector<int> all_vertices(const TriMesh& m) {
  std::vector<int> v(m.num_vertices());
  for (int i = 0; i < m.num_vertices(); ++i) v[i] = i;
  return v;
}

// ROI = everything above the bottom `fixed` fraction along `axis`; one region handle = the top
// `handle` fraction.
inline Selection bottom_fixed_top_handle(const TriMesh& m, int axis, double fixed, double handle) {
  Selection s;
  s.roi = slab(m, axis, fixed + 1e-9, 1.0);
  s.region_handles.push_back(slab(m, axis, 1.0 - handle, 1.0));
  return s;
}

inline double bbox_diagonal(const geometry::Vertices& V) {
  return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

// Rotation by `degrees` about the axis through `centre`, then translation t.
inline Eigen::Matrix4d rotation_about(const Eigen::Vector3d& axis, double degrees, const Eigen::Vector3d& centre,
                                      const Eigen::Vector3d& t = Eigen::Vector3d::Zero()) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  const Eigen::Matrix3d R = Eigen::AngleAxisd(degrees * M_PI / 180, axis.normalized()).toRotationMatrix();
  T.topLeftCorner<3, 3>() = R;
  T.topRightCorner<3, 1>() = centre - R * centre + t;
  return T;
}

// The bar of Fig. 2.7: bottom 10% fixed, top 10% the handle, twisted `twist` degrees about its
// own axis, then carried to the end of a quarter circle as long as the free part and turned
// 90° about y to stay tangent to it.
inline Eigen::Matrix4d bend_and_twist(const TriMesh& m, double twist) {
  const double zmax = m.V.col(2).maxCoeff(), zmin = m.V.col(2).minCoeff();
  const double z0 = zmin + 0.1 * (zmax - zmin);
  const Eigen::Vector3d axis_point(0.5, 0.5, 0);
  const Eigen::Matrix4d Tw = rotation_about(Eigen::Vector3d::UnitZ(), twist, axis_point);
  const double free_length = 0.8 * (zmax - zmin);  // between the fixed part and the handle
  const double radius = 2 * free_length / M_PI;
  const Eigen::Matrix4d Bend = rotation_about(Eigen::Vector3d::UnitY(), 90, Eigen::Vector3d(0.5 + radius, 0.5, z0));
  Eigen::Matrix4d Down = Eigen::Matrix4d::Identity();
  Down(2, 3) = -free_length;
  return Bend * Down * Tw;
}

// Rotation by `degrees` about axis, scaled, then shifted.
inline Eigen::Matrix4d similarity(double degrees, const Eigen::Vector3d& axis, double scale,
                                  const Eigen::Vector3d& shift) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = scale * Eigen::AngleAxisd(degrees * M_PI / 180, axis.normalized()).toRotationMatrix();
  T.topRightCorner<3, 1>() = shift;
  return T;
}

// Largest distance of X from T applied to V.
inline double max_deviation(const Vertices& X, const Vertices& V, const Eigen::Matrix4d& T) {
  double e = 0;
  for (int i = 0; i < V.rows(); ++i) e = std::max(e, (X.row(i).transpose() - apply(T, V.row(i).transpose())).norm());
  return e;
}

// The whole bar as ROI, its bottom and top tenths the two region handles.
inline Selection whole_bar_two_ends(const TriMesh& m) {
  Selection s;
  s.roi = all_vertices(m);
  s.region_handles = {slab(m, 2, 0.0, 0.1), slab(m, 2, 0.9, 1.0)};
  return s;
}

}  // namespace lapis::mesh_deform::test
