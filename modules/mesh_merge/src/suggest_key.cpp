#include "lapis/mesh_merge/suggest_key.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Eigenvalues>

namespace lapis::mesh_merge {
namespace {

[[noreturn]] void fail(const std::string& why) { throw InvalidArgument("mesh_merge::suggest_key(): " + why); }

// A loop's points (rows), with its vertices' arc-length parameters in [0, 1).
struct Polyline {
  Eigen::MatrixX3d points;
  std::vector<double> param;
};

Polyline loop_points(const TriMesh& mesh, const Eigen::Matrix4d& placement, const std::vector<int>& loop,
                     const char* which) {
  if (loop.size() < 3)
    fail(std::string(which) + " loop has " + std::to_string(loop.size()) + " vertices, expected 3 or more");
  Polyline p;
  p.points.resize(static_cast<Eigen::Index>(loop.size()), 3);
  for (size_t i = 0; i < loop.size(); ++i) {
    if (loop[i] < 0 || loop[i] >= mesh.num_vertices())
      fail(std::string(which) + " loop vertex " + std::to_string(loop[i]) + " out of range");
    const Eigen::Vector3d x = mesh.V.row(loop[i]).transpose();
    p.points.row(static_cast<Eigen::Index>(i)) =
        (placement.topLeftCorner<3, 3>() * x + placement.topRightCorner<3, 1>()).transpose();
  }
  const Eigen::Index n = p.points.rows();
  p.param.assign(loop.size() + 1, 0.0);
  for (Eigen::Index i = 0; i < n; ++i)
    p.param[static_cast<size_t>(i) + 1] =
        p.param[static_cast<size_t>(i)] + (p.points.row((i + 1) % n) - p.points.row(i)).norm();
  const double length = p.param.back();
  if (!(length > 0) || !std::isfinite(length)) fail(std::string(which) + " loop has no length");
  for (double& t : p.param) t /= length;
  p.param.pop_back();
  return p;
}

// `samples` points equally spaced by arc length, centred, scaled to unit RMS radius.
Eigen::MatrixX3d normalized_samples(const Polyline& p, int samples) {
  const Eigen::Index n = p.points.rows();
  Eigen::MatrixX3d out(samples, 3);
  Eigen::Index seg = 0;
  for (int k = 0; k < samples; ++k) {
    const double t = double(k) / samples;
    while (seg + 1 < n && p.param[static_cast<size_t>(seg) + 1] <= t) ++seg;
    const double t0 = p.param[static_cast<size_t>(seg)], t1 = seg + 1 < n ? p.param[static_cast<size_t>(seg) + 1] : 1.0;
    const double f = t1 > t0 ? (t - t0) / (t1 - t0) : 0.0;
    out.row(k) = (1 - f) * p.points.row(seg) + f * p.points.row((seg + 1) % n);
  }
  out.rowwise() -= out.colwise().mean();
  const double rms = std::sqrt(out.squaredNorm() / samples);
  if (rms > 0) out /= rms;
  return out;
}

// The vertex of `p` farthest along its points' principal direction.
int principal_extreme(const Polyline& p) {
  const Eigen::MatrixX3d centred = p.points.rowwise() - p.points.colwise().mean();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(centred.transpose() * centred);
  const Eigen::Vector3d axis = eig.eigenvectors().col(2);  // the largest eigenvalue's
  Eigen::Index best = 0;
  (centred * axis).maxCoeff(&best);
  return static_cast<int>(best);
}

double circular_gap(double a, double b) {
  const double d = std::abs(a - b);
  return std::min(d, 1 - d);
}

}  // namespace

KeySuggestion suggest_key(const TriMesh& source, const Eigen::Matrix4d& placement, const std::vector<int>& source_loop,
                          const TriMesh& target, const std::vector<int>& target_loop, int samples) {
  if (samples < 8) fail(std::to_string(samples) + " samples, expected 8 or more");
  // At least two samples per loop vertex (up to 4096: 16M distance terms), so the match is not
  // coarser than the loops.
  samples =
      std::max(samples, static_cast<int>(std::min<size_t>(4096, 2 * std::max(source_loop.size(), target_loop.size()))));
  const Polyline s = loop_points(source, placement, source_loop, "source");
  const std::vector<int> backward(target_loop.rbegin(), target_loop.rend());
  const Polyline t = loop_points(target, Eigen::Matrix4d::Identity(), backward, "target");
  const Eigen::MatrixX3d S = normalized_samples(s, samples), T = normalized_samples(t, samples);
  // Squared distance at every cyclic shift (sample k of the source meets sample k + shift of
  // the target).
  std::vector<double> cost(static_cast<size_t>(samples), 0.0);
  for (int shift = 0; shift < samples; ++shift)
    for (int k = 0; k < samples; ++k)
      cost[static_cast<size_t>(shift)] += (S.row(k) - T.row((k + shift) % samples)).squaredNorm();
  const int best = static_cast<int>(std::min_element(cost.begin(), cost.end()) - cost.begin());
  // Between samples: the vertex of the parabola through the best shift and its neighbours.
  const double before = cost[static_cast<size_t>((best + samples - 1) % samples)],
               here = cost[static_cast<size_t>(best)], after = cost[static_cast<size_t>((best + 1) % samples)];
  const double curvature = before - 2 * here + after;
  const double offset = curvature > 0 ? std::clamp(0.5 * (before - after) / curvature, -0.5, 0.5) : 0.0;
  double runner_up = std::numeric_limits<double>::infinity();
  for (int shift = 0; shift < samples; ++shift)
    if (circular_gap(double(shift) / samples, double(best) / samples) > 0.25)
      runner_up = std::min(runner_up, cost[static_cast<size_t>(shift)]);

  KeySuggestion out;
  out.residual = std::sqrt(cost[static_cast<size_t>(best)] / samples);
  out.runner_up = std::sqrt(runner_up / samples);
  const int i = principal_extreme(s);
  double goal = s.param[static_cast<size_t>(i)] + (best + offset) / samples;
  goal -= std::floor(goal);
  size_t j = 0;
  for (size_t k = 1; k < t.param.size(); ++k)
    if (circular_gap(t.param[k], goal) < circular_gap(t.param[j], goal)) j = k;
  out.key = {source_loop[static_cast<size_t>(i)], backward[j]};
  return out;
}

}  // namespace lapis::mesh_merge
