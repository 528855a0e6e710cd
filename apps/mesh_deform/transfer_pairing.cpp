#include "transfer_pairing.h"

#include <algorithm>
#include <queue>
#include <tuple>

#include "lapis/core/error.h"
#include "lapis/geometry/laplacian.h"

namespace lapis::deform_app {
namespace {

PairSlot unplaced(std::string name, int label, std::vector<double> part_areas) {
  PairSlot s;
  s.name = std::move(name);
  s.label = label;
  s.part_areas = std::move(part_areas);
  return s;
}

}  // namespace

// Its own Dijkstra rather than geometry::dijkstra(): that one splits the mesh into the seeds'
// Voronoi cells, so a small handle next to a large fixed region could not cover its share;
// here a region that has its share stops and its neighbours grow on past it.
std::vector<std::vector<int>> grow_regions(const geometry::Vertices& V, const geometry::Connectivity& conn,
                                           const Eigen::VectorXd& vertex_areas, const std::vector<int>& seeds,
                                           const std::vector<double>& area_fractions) {
  const int n = conn.num_vertices();
  const double total = vertex_areas.sum();
  std::vector<std::vector<int>> regions(seeds.size());
  std::vector<double> covered(seeds.size(), 0.0);
  std::vector<int> owner(static_cast<size_t>(n), -1);
  using Entry = std::tuple<double, int, int>;  // distance, vertex, region
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> front;
  for (size_t k = 0; k < seeds.size(); ++k) {
    if (seeds[k] < 0 || seeds[k] >= n)
      throw InvalidArgument("deform_app::grow_regions(): seed " + std::to_string(seeds[k]) + " is not a vertex");
    front.emplace(0.0, seeds[k], static_cast<int>(k));
  }
  while (!front.empty()) {
    const auto [d, v, k] = front.top();
    front.pop();
    const size_t r = static_cast<size_t>(k);
    // A region stops once it covers its share; its seed always goes in (if still free).
    if (owner[static_cast<size_t>(v)] >= 0 || (!regions[r].empty() && covered[r] >= area_fractions[r] * total))
      continue;
    owner[static_cast<size_t>(v)] = k;
    regions[r].push_back(v);
    covered[r] += vertex_areas[v];
    for (int w : conn.vertex_neighbors(v))
      if (owner[static_cast<size_t>(w)] < 0) front.emplace(d + (V.row(w) - V.row(v)).norm(), w, k);
  }
  for (auto& region : regions) std::sort(region.begin(), region.end());
  return regions;
}

std::vector<double> part_areas(const geometry::Connectivity& conn, const Eigen::VectorXd& vertex_areas,
                               const std::vector<int>& vertices) {
  const double total = vertex_areas.sum();
  std::vector<char> in(static_cast<size_t>(conn.num_vertices()), 0);
  for (int v : vertices) in[static_cast<size_t>(v)] = 1;
  std::vector<double> parts;
  std::vector<int> pending;
  for (int start : vertices) {
    if (in[static_cast<size_t>(start)] != 1) continue;
    double area = 0;
    in[static_cast<size_t>(start)] = 2;
    pending.assign(1, start);
    while (!pending.empty()) {
      const int v = pending.back();
      pending.pop_back();
      area += vertex_areas[v];
      for (int w : conn.vertex_neighbors(v))
        if (in[static_cast<size_t>(w)] == 1) in[static_cast<size_t>(w)] = 2, pending.push_back(w);
    }
    parts.push_back(total > 0 ? area / total : 0.0);
  }
  std::sort(parts.rbegin(), parts.rend());
  while (parts.size() > 1 && parts.back() < 0.05 * parts.front()) parts.pop_back();
  return parts;
}

geometry::Vertices Placement::apply(const geometry::Vertices& V) const {
  geometry::Vertices out = scale * V;
  out.rowwise() += offset.transpose();
  return out;
}

Placement place_beside(const geometry::TriMesh& source, const geometry::TriMesh& target) {
  const Eigen::Vector3d slo = source.V.colwise().minCoeff(), shi = source.V.colwise().maxCoeff();
  const Eigen::Vector3d tlo = target.V.colwise().minCoeff(), thi = target.V.colwise().maxCoeff();
  const double source_diagonal = (shi - slo).norm(), target_diagonal = (thi - tlo).norm();
  Placement p;
  p.scale = target_diagonal > 0 ? source_diagonal / target_diagonal : 1.0;
  // The target's box: left side a fifth of a diagonal right of the source's, centred in y, z.
  const Eigen::Vector3d source_centre = 0.5 * (slo + shi), target_centre = 0.5 * (tlo + thi) * p.scale;
  p.offset = source_centre - target_centre;
  p.offset.x() = shi.x() + 0.2 * source_diagonal - p.scale * tlo.x();
  return p;
}

TransferPairing::TransferPairing(geometry::TriMesh target)
    : target_(std::move(target)),
      conn_(target_),
      areas_(geometry::vertex_areas(target_, geometry::MassType::Barycentric)) {}

void TransferPairing::set_source(const geometry::TriMesh& source, const geometry::Connectivity& source_conn,
                                 const mesh_deform::Selection& selection, const std::vector<int>& handle_label) {
  const Eigen::VectorXd areas = geometry::vertex_areas(source, geometry::MassType::Barycentric);
  auto fraction = [&](const std::vector<int>& vs) { return part_areas(source_conn, areas, vs); };
  std::vector<PairSlot> slots;
  if (static_cast<int>(selection.roi.size()) < source.num_vertices()) {
    std::vector<char> in_roi(static_cast<size_t>(source.num_vertices()), 0);
    for (int v : selection.roi) in_roi[static_cast<size_t>(v)] = 1;
    std::vector<int> fixed;
    for (int v = 0; v < source.num_vertices(); ++v)
      if (!in_roi[static_cast<size_t>(v)]) fixed.push_back(v);
    slots.push_back(unplaced("fixed region", -1, fraction(fixed)));
  }
  for (size_t k = 0; k < selection.region_handles.size(); ++k)
    slots.push_back(
        unplaced("handle " + std::to_string(handle_label[k]), handle_label[k], fraction(selection.region_handles[k])));
  // A slot keeps its clicks while the source still has it (same label) in as many parts.
  for (PairSlot& s : slots)
    for (const PairSlot& old : slots_)
      if (old.label == s.label && static_cast<int>(old.seeds.size()) <= s.parts()) s.seeds = old.seeds;
  slots_ = std::move(slots);
  regrow();
}

void TransferPairing::place(int slot, int vertex) {
  if (slot < 0 || slot >= static_cast<int>(slots_.size())) return;
  if (vertex < 0 || vertex >= target_.num_vertices())
    throw InvalidArgument("deform_app::TransferPairing::place(): " + std::to_string(vertex) + " is not a vertex");
  PairSlot& s = slots_[static_cast<size_t>(slot)];
  if (s.placed()) s.seeds.clear();
  s.seeds.push_back(vertex);
  regrow();
}

void TransferPairing::clear(int slot) {
  if (slot < 0 || slot >= static_cast<int>(slots_.size())) return;
  slots_[static_cast<size_t>(slot)].seeds.clear();
  regrow();
}

int TransferPairing::next_unplaced() const {
  for (size_t k = 0; k < slots_.size(); ++k)
    if (!slots_[k].placed()) return static_cast<int>(k);
  return -1;
}

bool TransferPairing::complete() const {
  if (slots_.empty()) return false;
  for (const PairSlot& s : slots_)
    if (!s.placed() || !s.problem.empty()) return false;
  return true;
}

mesh_deform::Selection TransferPairing::selection() const {
  if (!complete()) throw InvalidArgument("deform_app::TransferPairing: the target's handles are not all placed");
  mesh_deform::Selection s;
  size_t k = 0;
  if (slots_.front().label < 0) {
    std::vector<char> fixed(static_cast<size_t>(target_.num_vertices()), 0);
    for (int v : slots_.front().region) fixed[static_cast<size_t>(v)] = 1;
    for (int v = 0; v < target_.num_vertices(); ++v)
      if (!fixed[static_cast<size_t>(v)]) s.roi.push_back(v);
    k = 1;
  } else {
    for (int v = 0; v < target_.num_vertices(); ++v) s.roi.push_back(v);
  }
  for (; k < slots_.size(); ++k) s.region_handles.push_back(slots_[k].region);
  return s;
}

void TransferPairing::regrow() {
  // Every click at once, each with its part's area (the k-th click: the k-th largest part).
  std::vector<int> seeds, slot_of;
  std::vector<double> fractions;
  for (size_t k = 0; k < slots_.size(); ++k) {
    PairSlot& s = slots_[k];
    s.region.clear();
    s.problem.clear();
    for (size_t i = 0; i < s.seeds.size(); ++i) {
      seeds.push_back(s.seeds[i]);
      fractions.push_back(s.part_areas[i]);
      slot_of.push_back(static_cast<int>(k));
    }
  }
  const std::vector<std::vector<int>> regions = grow_regions(target_.V, conn_, areas_, seeds, fractions);
  for (size_t i = 0; i < regions.size(); ++i) {
    PairSlot& s = slots_[static_cast<size_t>(slot_of[i])];
    if (regions[i].empty()) s.problem = "two clicks on one point; click elsewhere";
    s.region.insert(s.region.end(), regions[i].begin(), regions[i].end());
  }
  for (PairSlot& s : slots_) std::sort(s.region.begin(), s.region.end());
  ++revision_;
}

}  // namespace lapis::deform_app
