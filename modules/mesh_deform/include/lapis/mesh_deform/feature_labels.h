// The salient method's features as an editor holds them (Zhao et al. §3.1: "interactively
// specifying the salient features, or grouping two features into one"): one feature index per
// vertex, seeded from a detection, then painted, erased and merged, and handed back as the
// feature list SalientDeformer::set_features() takes.
#pragma once

#include <vector>

#include "lapis/mesh_deform/salient_features.h"

namespace lapis::mesh_deform {

struct FeatureLabels {
  static constexpr int kNone = -1;
  std::vector<int> feature_of;  // #V: feature index or kNone
  int count = 0;                // feature indices in use are 0 … count − 1

  // Every vertex in no feature, then features[i] labelled i. Throws InvalidArgument for an
  // index outside [0, num_vertices).
  void seed(const std::vector<Feature>& features, int num_vertices);
  // Sets `vertices` to `feature` (kNone erases; count grows to feature + 1). Throws
  // InvalidArgument for a vertex out of range or feature < kNone.
  void paint(const std::vector<int>& vertices, int feature);
  // Feature b joins a (§3.1's grouping); the indices above b move down by one. Throws
  // InvalidArgument unless a != b are both in [0, count).
  void merge(int a, int b);
  int size_of(int feature) const;
  // The non-empty features in index order, each ascending.
  std::vector<Feature> features() const;
};

}  // namespace lapis::mesh_deform
