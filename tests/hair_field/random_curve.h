// Random constraint sets for the field solver tests: walks of grid nodes whose direction
// turns smoothly, a stand-in for the style curves of hair_sketch.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "lapis/hair_field/constraints.h"
#include "lapis/hair_field/grid.h"

namespace hair_field_test {

using namespace lapis::hair_field;

// A random "curve": a walk of nodes with a smoothly turning direction.
inline std::vector<Constraint> random_curve(const Grid& g, std::mt19937& rng, int len) {
  std::uniform_int_distribution<int> ux(1, g.dims[0] - 2), uy(1, g.dims[1] - 2), uz(1, g.dims[2] - 2);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Constraint> out;
  int i = ux(rng), j = uy(rng), k = uz(rng);
  Eigen::Vector3d dir(u(rng), u(rng), u(rng));
  for (int s = 0; s < len; ++s) {
    dir = (dir + 0.3 * Eigen::Vector3d(u(rng), u(rng), u(rng))).normalized();
    out.push_back({g.index(i, j, k), dir});
    const int a = std::abs(dir.x()) > std::abs(dir.y()) ? (std::abs(dir.x()) > std::abs(dir.z()) ? 0 : 2)
                                                        : (std::abs(dir.y()) > std::abs(dir.z()) ? 1 : 2);
    int* c[3] = {&i, &j, &k};
    *c[a] = std::clamp(*c[a] + (dir[a] > 0 ? 1 : -1), 0, g.dims[a] - 1);
  }
  return out;
}

}  // namespace hair_field_test
