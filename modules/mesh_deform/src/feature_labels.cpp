#include "lapis/mesh_deform/feature_labels.h"

#include <algorithm>
#include <string>

namespace lapis::mesh_deform {

void FeatureLabels::seed(const std::vector<Feature>& features, int num_vertices) {
  feature_of.assign(static_cast<size_t>(num_vertices), kNone);
  count = 0;
  for (const Feature& f : features) paint(f, count);
}

void FeatureLabels::paint(const std::vector<int>& vertices, int feature) {
  if (feature < kNone)
    throw InvalidArgument("mesh_deform::FeatureLabels::paint(): feature " + std::to_string(feature) +
                          ", expected >= -1");
  for (int v : vertices)
    if (v < 0 || v >= static_cast<int>(feature_of.size()))
      throw InvalidArgument("mesh_deform::FeatureLabels::paint(): vertex " + std::to_string(v) + " out of range [0, " +
                            std::to_string(feature_of.size()) + ")");
  for (int v : vertices) feature_of[static_cast<size_t>(v)] = feature;
  count = std::max(count, feature + 1);
}

void FeatureLabels::merge(int a, int b) {
  if (a == b || a < 0 || b < 0 || a >= count || b >= count)
    throw InvalidArgument("mesh_deform::FeatureLabels::merge(): features " + std::to_string(a) + " and " +
                          std::to_string(b) + ", expected two different indices in [0, " + std::to_string(count) + ")");
  for (int& f : feature_of) {
    if (f == b) f = a;
    if (f > b) --f;
  }
  --count;
}

int FeatureLabels::size_of(int feature) const {
  return static_cast<int>(std::count(feature_of.begin(), feature_of.end(), feature));
}

std::vector<Feature> FeatureLabels::features() const {
  std::vector<Feature> out(static_cast<size_t>(count));
  for (size_t v = 0; v < feature_of.size(); ++v)
    if (feature_of[v] >= 0) out[static_cast<size_t>(feature_of[v])].push_back(static_cast<int>(v));
  out.erase(std::remove_if(out.begin(), out.end(), [](const Feature& f) { return f.empty(); }), out.end());
  return out;
}

}  // namespace lapis::mesh_deform
