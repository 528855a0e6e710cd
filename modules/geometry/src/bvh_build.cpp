// Binned-SAH construction of Bvh (Wald, "On fast construction of SAH-based bounding volume
// hierarchies", 2007): each split sorts triangle centroids into bins along the widest
// centroid axis and takes the bin boundary with the lowest surface area cost.
#include <algorithm>
#include <array>
#include <atomic>
#include <string>

#include "lapis/core/error.h"
#include "lapis/geometry/bvh.h"
#include "parallel.h"

namespace lapis::geometry {

namespace {
struct Box {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  void grow(const Eigen::Vector3d& p) { lo = lo.cwiseMin(p), hi = hi.cwiseMax(p); }
  void grow(const Box& b) { lo = lo.cwiseMin(b.lo), hi = hi.cwiseMax(b.hi); }
  // A quarter of the half surface area, from half extents: comparisons of costs are
  // unchanged, and a box spanning -DBL_MAX..DBL_MAX keeps finite extents.
  double half_area() const {
    if (lo.x() > hi.x()) return 0;
    const Eigen::Vector3d d = half_extent(lo, hi);
    return d.x() * d.y() + d.y() * d.z() + d.z() * d.x();
  }
  static Eigen::Vector3d half_extent(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    return 0.5 * hi - 0.5 * lo;
  }
};

// Which of nb bins along [lo, lo + 2 half_extent] holds x, in [0, nb): halved terms keep a
// span of finite coordinates finite, and the clamp keeps rounding at the ends in range.
int bin_index(double x, double lo, double half_extent, int nb) {
  const double t = (0.5 * x - 0.5 * lo) / half_extent;
  return t > 0 ? std::min(nb - 1, static_cast<int>(std::min(1.0, t) * nb)) : 0;
}
}  // namespace

struct BvhBuilder {
  Bvh& bvh;
  std::vector<Box> boxes;  // per face
  std::vector<Eigen::Vector3d> centroids;
  std::atomic<int> next_node{1};

  void set_node(int node, const Box& b, int first, int count) {
    Bvh::Node& n = bvh.nodes_[node];
    for (int k = 0; k < 3; ++k) n.lo[k] = b.lo[k], n.hi[k] = b.hi[k];
    n.first = first;
    n.count = count;
  }

  static constexpr int kLeaf = -1, kMedian = -2;

  // Returns the split position in (begin, end), kLeaf, or kMedian (split at the centroid
  // median: SAH found nothing, e.g. all centroids in one bin).
  int split(int begin, int end, const Box& bounds, const Box& cb) {
    const int n = end - begin;
    const BvhOptions& o = bvh.options_;
    int axis = 0;
    Box::half_extent(cb.lo, cb.hi).maxCoeff(&axis);
    const double lo = cb.lo[axis], extent = Box::half_extent(cb.lo, cb.hi)[axis];
    if (!(extent > 0)) return n <= o.max_leaf_size ? kLeaf : kMedian;  // coincident centroids
    constexpr int kMaxBins = 64;
    const int nb = std::clamp(o.bins, 2, kMaxBins);
    std::array<Box, kMaxBins> bin_box;
    std::array<int, kMaxBins> bin_count{};
    auto bin_of = [&](int f) { return bin_index(centroids[f][axis], lo, extent, nb); };
    for (int i = begin; i < end; ++i) {
      const int f = bvh.order_[i], b = bin_of(f);
      bin_box[b].grow(boxes[f]);
      ++bin_count[b];
    }
    // Sweep from the right to get suffix areas, then from the left to evaluate each boundary.
    std::array<double, kMaxBins> right_cost{};
    Box acc;
    int cnt = 0;
    for (int b = nb - 1; b > 0; --b) {
      acc.grow(bin_box[b]);
      cnt += bin_count[b];
      right_cost[b] = acc.half_area() * cnt;
    }
    Box left;
    int left_count = 0, best = -1;
    double best_cost = std::numeric_limits<double>::infinity();
    for (int b = 1; b < nb; ++b) {
      left.grow(bin_box[b - 1]);
      left_count += bin_count[b - 1];
      const double cost = left.half_area() * left_count + right_cost[b];
      if (left_count > 0 && left_count < n && cost < best_cost) best_cost = cost, best = b;
    }
    // Leaf when it is allowed and no split beats intersecting every triangle (traversal cost 1).
    if (n <= o.max_leaf_size && !(best_cost < bounds.half_area() * (n - 1))) return kLeaf;
    if (best < 0) return kMedian;
    const auto mid =
        std::partition(bvh.order_.begin() + begin, bvh.order_.begin() + end, [&](int f) { return bin_of(f) < best; });
    return static_cast<int>(mid - bvh.order_.begin());
  }

  // Below depth kSahDepth splits are at the median, which bounds the depth by
  // kSahDepth + log2(#F) < 100: traversal stacks of 128 entries always suffice.
  static constexpr int kSahDepth = 64;

  void build(int node, int begin, int end, int depth) {
    Box bounds, cb;  // of the triangles, of their centroids: one pass for both
    for (int i = begin; i < end; ++i) {
      const int f = bvh.order_[i];
      bounds.grow(boxes[f]);
      cb.grow(centroids[f]);
    }
    int mid = depth < kSahDepth                           ? split(begin, end, bounds, cb)
              : end - begin <= bvh.options_.max_leaf_size ? kLeaf
                                                          : kMedian;
    if (mid == kLeaf) return set_node(node, bounds, begin, end - begin);
    if (mid == kMedian) {
      mid = begin + (end - begin) / 2;
      int axis = 0;
      Box::half_extent(bounds.lo, bounds.hi).maxCoeff(&axis);
      std::nth_element(bvh.order_.begin() + begin, bvh.order_.begin() + mid, bvh.order_.begin() + end,
                       [&](int a, int b) { return centroids[a][axis] < centroids[b][axis]; });
    }
    const int left = next_node.fetch_add(2);
    set_node(node, bounds, left, 0);
    if (end - begin >= bvh.options_.parallel_cutoff) {
#pragma omp task default(shared) firstprivate(left, begin, mid, depth)
      build(left, begin, mid, depth + 1);
#pragma omp task default(shared) firstprivate(left, mid, end, depth)
      build(left + 1, mid, end, depth + 1);
#pragma omp taskwait
    } else {
      build(left, begin, mid, depth + 1);
      build(left + 1, mid, end, depth + 1);
    }
  }
};

Bvh::Bvh(const TriMesh& mesh, const BvhOptions& options) : mesh_(mesh), options_(options) {
  require_indices_in_range(mesh, "geometry::Bvh()");
  require_finite_vertices(mesh, "geometry::Bvh()");
  if (options.max_leaf_size < 1) throw InvalidArgument("geometry::Bvh(): max_leaf_size must be at least 1");
  const int nf = mesh.num_faces();
  BvhBuilder b{*this, std::vector<Box>(nf), std::vector<Eigen::Vector3d>(nf)};
#pragma omp parallel for schedule(static) if (nf >= detail::kParallelMin)
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) b.boxes[f].grow(Eigen::Vector3d(mesh.V.row(mesh.F(f, k))));
    b.centroids[f] = 0.5 * b.boxes[f].lo + 0.5 * b.boxes[f].hi;  // lo + hi may overflow
  }
  order_.resize(nf);
  for (int f = 0; f < nf; ++f) order_[f] = f;
  nodes_.resize(std::max(1, 2 * nf - 1));  // a binary tree with at most nf leaves
  if (nf == 0) return;                     // queries check for an empty mesh before touching the tree
#pragma omp parallel if (nf >= detail::kParallelMin)
#pragma omp single
  b.build(0, 0, nf, 0);
  nodes_.resize(b.next_node.load());
}

}  // namespace lapis::geometry
