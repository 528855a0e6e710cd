#include "lapis/mesh_merge/merge_setup.h"

#include <algorithm>
#include <numbers>

namespace lapis::mesh_merge {

TriMesh placed_source(const MergeSetup& setup) {
  TriMesh m = *setup.source;
  if (setup.placement.isIdentity()) return m;  // bit for bit: the file the user loaded
  const Eigen::Matrix3d A = setup.placement.topLeftCorner<3, 3>();
  const Eigen::Vector3d t = setup.placement.topRightCorner<3, 1>();
  for (int v = 0; v < m.num_vertices(); ++v) m.V.row(v) = (A * m.V.row(v).transpose() + t).transpose();
  return m;
}

std::vector<LoopPair> loop_pairs(const MergeSetup& setup) {
  std::vector<LoopPair> out;
  for (const PickedPair& p : setup.pairs) out.push_back(LoopPair{p.keys});
  return out;
}

int pair_loops(MergeSetup& setup, int source_loop, int target_loop) {
  if (source_loop < 0 || target_loop < 0)
    throw InvalidArgument("mesh_merge::pair_loops(): loop indices must be >= 0, got " + std::to_string(source_loop) +
                          " and " + std::to_string(target_loop));
  std::erase_if(setup.pairs,
                [&](const PickedPair& p) { return p.source_loop == source_loop || p.target_loop == target_loop; });
  setup.pairs.push_back(PickedPair{source_loop, target_loop, {}});
  return static_cast<int>(setup.pairs.size()) - 1;
}

void add_key(MergeSetup& setup, int pair, KeyCorrespondence key, const std::vector<int>& source_loop) {
  constexpr const char* fn = "mesh_merge::add_key()";
  if (pair < 0 || pair >= static_cast<int>(setup.pairs.size()))
    throw InvalidArgument(std::string(fn) + ": pair " + std::to_string(pair) + " out of range");
  auto position = [&](int v) { return std::find(source_loop.begin(), source_loop.end(), v) - source_loop.begin(); };
  if (position(key.source) == static_cast<long>(source_loop.size()))
    throw InvalidArgument(std::string(fn) + ": source vertex " + std::to_string(key.source) +
                          " is not on the pair's source loop");
  PickedPair& picked = setup.pairs[static_cast<size_t>(pair)];
  if (picked.keys_suggested) picked.keys.clear(), picked.keys_suggested = false;
  auto& keys = picked.keys;
  std::erase_if(keys, [&](const KeyCorrespondence& k) { return k.source == key.source || k.target == key.target; });
  keys.push_back(key);
  std::sort(keys.begin(), keys.end(),
            [&](const auto& a, const auto& b) { return position(a.source) < position(b.source); });
}

std::vector<KeySuggestion> suggest_keys(MergeSetup& setup, const std::vector<std::vector<int>>& source_loops,
                                        const std::vector<std::vector<int>>& target_loops, int pair) {
  constexpr const char* fn = "mesh_merge::suggest_keys()";
  const int n = static_cast<int>(setup.pairs.size());
  if (pair < -1 || pair >= n)
    throw InvalidArgument(std::string(fn) + ": pair " + std::to_string(pair) + " out of range");
  std::vector<KeySuggestion> out;
  for (int p = pair < 0 ? 0 : pair; p < (pair < 0 ? n : pair + 1); ++p) {
    PickedPair& picked = setup.pairs[static_cast<size_t>(p)];
    if (picked.source_loop >= static_cast<int>(source_loops.size()) ||
        picked.target_loop >= static_cast<int>(target_loops.size()))
      throw InvalidArgument(std::string(fn) + ": pair " + std::to_string(p) + " names loops " +
                            std::to_string(picked.source_loop) + " and " + std::to_string(picked.target_loop) +
                            ", but the meshes have " + std::to_string(source_loops.size()) + " and " +
                            std::to_string(target_loops.size()));
    out.push_back(suggest_key(*setup.source, setup.placement, source_loops[static_cast<size_t>(picked.source_loop)],
                              *setup.target, target_loops[static_cast<size_t>(picked.target_loop)]));
    picked.keys = {out.back().key};
    picked.keys_suggested = true;
  }
  return out;
}

void toggle_handle(MergeSetup& setup, int vertex) {
  auto& h = setup.options.handles;
  const auto it = std::find(h.begin(), h.end(), vertex);
  if (it != h.end())
    h.erase(it);
  else
    h.push_back(vertex);
}

namespace {

void loop_centroid_perimeter(const TriMesh& m, const std::vector<int>& loop, Eigen::Vector3d& c, double& perimeter) {
  c.setZero();
  perimeter = 0;
  const size_t n = loop.size();
  for (size_t i = 0; i < n; ++i) {
    c += m.V.row(loop[i]).transpose();
    perimeter += (m.V.row(loop[(i + 1) % n]) - m.V.row(loop[i])).norm();
  }
  if (n) c /= static_cast<double>(n);
}

}  // namespace

Eigen::Matrix4d suggest_placement(const TriMesh& source, const std::vector<int>& source_loop, const TriMesh& target,
                                  const std::vector<int>& target_loop) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  if (source_loop.size() < 3 || target_loop.size() < 3) return T;
  Eigen::Vector3d cs, ct;
  double ps = 0, pt = 0;
  loop_centroid_perimeter(source, source_loop, cs, ps);
  loop_centroid_perimeter(target, target_loop, ct, pt);
  if (!(ps > 0) || !(pt > 0)) return T;
  const double scale = pt / ps;
  Eigen::Vector3d away = ct - target.V.colwise().mean().transpose();
  away = away.norm() > 0 ? away.normalized() : Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d goal = ct + away * (0.5 * pt / (2 * std::numbers::pi));  // half the loop's radius
  T.topLeftCorner<3, 3>() *= scale;
  T.topRightCorner<3, 1>() = goal - scale * cs;
  return T;
}

int facing_target_loop(const TriMesh& source, const std::vector<int>& source_loop, const TriMesh& target,
                       const std::vector<std::vector<int>>& target_loops) {
  Eigen::Vector3d cs;
  double ps = 0;
  loop_centroid_perimeter(source, source_loop, cs, ps);
  const Eigen::Vector3d extends = source.V.colwise().mean().transpose() - cs;
  const Eigen::Vector3d target_mean = target.V.colwise().mean().transpose();
  int best = -1;
  double best_dot = -1e300;
  for (size_t l = 0; l < target_loops.size(); ++l) {
    Eigen::Vector3d ct;
    double pt = 0;
    loop_centroid_perimeter(target, target_loops[l], ct, pt);
    const double d = (ct - target_mean).normalized().dot(extends.normalized());
    if (d > best_dot) best_dot = d, best = static_cast<int>(l);
  }
  return best;
}

namespace {

// A closed mesh has no loop to size and place the source by: scaled to half the target's
// bounding-box diagonal (a part to paint and cut off), beside the target along x, a twentieth of
// its diagonal apart, their boxes' centres level.
Eigen::Matrix4d beside_by_boxes(const TriMesh& source, const TriMesh& target) {
  const Eigen::RowVector3d smin = source.V.colwise().minCoeff(), smax = source.V.colwise().maxCoeff();
  const Eigen::RowVector3d tmin = target.V.colwise().minCoeff(), tmax = target.V.colwise().maxCoeff();
  const double sd = (smax - smin).norm(), td = (tmax - tmin).norm();
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  if (!(sd > 0) || !(td > 0)) return T;
  const double k = 0.5 * td / sd;
  Eigen::RowVector3d centre = 0.5 * (tmin + tmax);
  centre.x() = tmax.x() + 0.05 * td + 0.5 * k * (smax.x() - smin.x());
  T.topLeftCorner<3, 3>() *= k;
  T.topRightCorner<3, 1>() = (centre - k * 0.5 * (smin + smax)).transpose();
  return T;
}

}  // namespace

Eigen::Matrix4d suggest_placement(const TriMesh& source, const TriMesh& target) {
  if (source.num_vertices() == 0 || target.num_vertices() == 0) return Eigen::Matrix4d::Identity();
  const Connectivity sc(source), tc(target);
  if (sc.boundary_loops().empty() || tc.boundary_loops().empty()) return beside_by_boxes(source, target);
  const auto& sl = sc.boundary_loops()[0];
  const int tl = facing_target_loop(source, sl, target, tc.boundary_loops());
  return suggest_placement(source, sl, target, tc.boundary_loops()[static_cast<size_t>(tl)]);
}

namespace {

std::vector<int> faces_of(const TriMesh& mesh, const std::vector<int>& vertices) {
  std::vector<char> in(static_cast<size_t>(mesh.num_vertices()), 0);
  for (int v : vertices)
    if (v >= 0 && v < mesh.num_vertices()) in[v] = 1;
  std::vector<int> faces;
  for (int f = 0; f < mesh.num_faces(); ++f)
    if (in[mesh.F(f, 0)] && in[mesh.F(f, 1)] && in[mesh.F(f, 2)]) faces.push_back(f);
  return faces;
}

}  // namespace

BoundaryRegions boundary_regions(const MergeSetup& setup) {
  BoundaryRegions r;
  if (!setup.source || !setup.target) return r;
  if (!setup.optimal.rough.empty()) r.roi_faces = faces_of(*setup.source, setup.optimal.rough);
  r.feature_faces = faces_of(*setup.source, setup.optimal.feature);
  if (!setup.optimal.target.empty()) r.target_faces = faces_of(*setup.target, setup.optimal.target);
  return r;
}

std::string missing_input(const MergeSetup& setup, int source_loops) {
  if (!setup.source || !setup.target) return "load a source and a target mesh";
  if (setup.options.mode == MergeMode::OptimalBoundary) {
    if (setup.optimal.feature.empty()) return "paint the feature region on the source (tool 5, region: feature)";
    if (setup.optimal.rough.empty() && source_loops == 0)
      return "paint the rough region around the feature on the source (tool 5, region: rough)";
    return "";
  }
  if (source_loops == 0) return "the source has no boundary loop: cut a part off it first";
  const int paired = static_cast<int>(setup.pairs.size());
  if (paired < source_loops)
    return "pair every source boundary loop with a target loop (" + std::to_string(paired) + " of " +
           std::to_string(source_loops) + " paired)";
  for (size_t p = 0; p < setup.pairs.size(); ++p)
    if (setup.pairs[p].keys.empty()) return "pair " + std::to_string(p + 1) + " needs a key correspondence";
  return "";
}

}  // namespace lapis::mesh_merge
