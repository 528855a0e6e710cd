#include "isoline_guides.h"

#include "lapis/geometry/polar.h"
#include "rotation_guide.h"

namespace lapis::mesh_deform::detail {

void IsolineGuides::reset(int region_handles, int isolines) {
  angle.assign(static_cast<size_t>(region_handles), Eigen::Vector3d::Zero());
  guided.assign(static_cast<size_t>(isolines), 0);
  target.assign(static_cast<size_t>(isolines), Eigen::Matrix3d::Identity());
}

bool IsolineGuides::update(const HandleTransforms& t, const IsolineBasis& b, const HandleSets& sets,
                           double guide_angle) {
  const std::vector<char> before = guided;
  std::fill(guided.begin(), guided.end(), 0);
  for (size_t h = 0; h < angle.size(); ++h) {
    angle[h] = unwrap_rotation(geometry::polar_rotation(t.regions[h].topLeftCorner<3, 3>()), angle[h]);
    // Guides turn relative to the fixed region, the handle whose isolines sit at s = 0.
    if (!sets.has_fixed_region || angle[h].norm() <= guide_angle) continue;
    const int column = sets.column_of_region(static_cast<int>(h));
    const int set = b.sets == 1 ? (column == field_of_set(1, 0) ? 0 : -1) : column;
    if (set < 0) continue;
    for (int j = 0; j < b.isolines; ++j) {
      const int l = set * b.isolines + j;
      guided[l] = 1;
      target[l] = rotation_of(b.isovalue(j) * angle[h]);
    }
  }
  return guided != before;
}

}  // namespace lapis::mesh_deform::detail
