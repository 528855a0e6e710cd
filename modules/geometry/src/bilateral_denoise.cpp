#include "lapis/geometry/bilateral_denoise.h"

#include <cmath>
#include <string>
#include <vector>

#include "lapis/core/error.h"
#include "lapis/core/parallel_for.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/normals.h"

namespace lapis::geometry {
namespace {

double mean_edge_length(const TriMesh& mesh, const Connectivity& conn) {
  double sum = 0;
  for (const auto& e : conn.edges()) sum += (mesh.V.row(e[0]) - mesh.V.row(e[1])).norm();
  return conn.num_edges() > 0 ? sum / conn.num_edges() : 0.0;
}

// The vertices within `radius` of v reached along edges through vertices within it, v left out.
// stamp (#V, marks the vertices seen for v) and frontier are the caller's, reused vertex to vertex.
void neighbourhood(const Connectivity& conn, const Vertices& V, int v, double radius, std::vector<int>& out,
                   std::vector<int>& stamp, std::vector<int>& frontier) {
  out.clear();
  stamp[v] = v;
  frontier.assign(1, v);
  const double r2 = radius * radius;
  while (!frontier.empty()) {
    const int u = frontier.back();
    frontier.pop_back();
    for (int w : conn.vertex_neighbors(u)) {
      if (stamp[w] == v || (V.row(w) - V.row(v)).squaredNorm() > r2) continue;
      stamp[w] = v;
      out.push_back(w);
      frontier.push_back(w);
    }
  }
}

// One pass (Fleishman et al., Fig. 3 "DenoisePoint") over every vertex, from V into out.
void denoise_pass(const Connectivity& conn, const Vertices& V, const Vertices& N, double sigma_c, Vertices& out) {
  const auto n = static_cast<std::ptrdiff_t>(V.rows());
  core::parallel_for(0, n, 4096, [&](std::ptrdiff_t lo, std::ptrdiff_t hi) {
    std::vector<int> near, frontier, stamp(static_cast<size_t>(n), -1);
    std::vector<double> height;
    for (std::ptrdiff_t i = lo; i < hi; ++i) {
      const int v = static_cast<int>(i);
      out.row(v) = V.row(v);
      neighbourhood(conn, V, v, 2 * sigma_c, near, stamp, frontier);
      if (near.empty() || N.row(v).squaredNorm() == 0) continue;
      height.clear();
      double mean = 0;
      for (int q : near) {
        height.push_back(N.row(v).dot(V.row(q) - V.row(v)));
        mean += height.back();
      }
      mean /= static_cast<double>(near.size());
      double var = 0;
      for (double h : height) var += (h - mean) * (h - mean);
      const double sigma_s = std::max(std::sqrt(var / static_cast<double>(near.size())), 1e-12 * sigma_c);
      double sum = 0, normalizer = 0;
      for (size_t k = 0; k < near.size(); ++k) {
        const double t2 = (V.row(near[k]) - V.row(v)).squaredNorm(), h = height[k];
        const double w = std::exp(-t2 / (2 * sigma_c * sigma_c)) * std::exp(-h * h / (2 * sigma_s * sigma_s));
        sum += w * h;
        normalizer += w;
      }
      if (normalizer > 0) out.row(v) += (sum / normalizer) * N.row(v);
    }
  });
}

}  // namespace

TriMesh bilateral_denoise(const TriMesh& mesh, const BilateralOptions& options) {
  const std::string fn = "geometry::bilateral_denoise(): ";
  if (options.iterations < 0) throw InvalidArgument(fn + "iterations = " + std::to_string(options.iterations) + " < 0");
  if (!(options.sigma_c >= 0) || !std::isfinite(options.sigma_c))
    throw InvalidArgument(fn + "sigma_c must be finite and >= 0");
  if (options.iterations == 0) return mesh;
  const Connectivity conn(mesh);
  const double sigma_c = options.sigma_c > 0 ? options.sigma_c : mean_edge_length(mesh, conn);
  TriMesh result = mesh;
  if (!(sigma_c > 0)) return result;  // no edges, or every edge of zero length
  Vertices next(mesh.V.rows(), 3);
  for (int it = 0; it < options.iterations; ++it) {
    denoise_pass(conn, result.V, vertex_normals(result), sigma_c, next);
    result.V.swap(next);
  }
  return result;
}

}  // namespace lapis::geometry
