#include "curve_sampling.h"

#include <cmath>
#include <string>

#include "lapis/core/error.h"
#include "lapis/core/format.h"

namespace lapis::hair_sketch::detail {
using hair_field::Constraint;
using hair_field::Grid;

std::vector<Eigen::Vector3d> resample(const std::vector<Eigen::Vector3d>& poly, double h, const char* who) {
  if (poly.size() < 2)
    throw InvalidArgument(std::string(who) + ": a curve needs at least 2 points, got " + std::to_string(poly.size()));
  double length = 0;
  for (size_t i = 0; i < poly.size(); ++i) {
    if (!poly[i].allFinite())
      throw InvalidArgument(std::string(who) + ": point " + std::to_string(i) + " is not finite");
    if (i) length += (poly[i] - poly[i - 1]).norm();
  }
  if (!(length > 0)) throw InvalidArgument(std::string(who) + ": the curve has zero length");
  if (!(std::isfinite(h) && h > 0))
    throw InvalidArgument(std::string(who) + ": spacing " + format_number(h) + " is not positive");
  // The sample count before any sample: a point far from the others (-1e308) would otherwise
  // have the loop below allocate until memory runs out.
  const double samples = length / h + 2;
  if (!(samples <= kMaxCurveSamples))
    throw ResourceLimit(std::string(who) + ": a curve of length " + format_number(length) + " at spacing " +
                        format_number(h) + " needs " + format_number(samples) + " samples, at most " +
                        format_number(kMaxCurveSamples) + " allowed");
  std::vector<Eigen::Vector3d> out{poly.front()};
  out.reserve(static_cast<size_t>(samples));
  double next = h, along = 0;
  for (size_t i = 1; i < poly.size(); ++i) {
    const double seg = (poly[i] - poly[i - 1]).norm();
    while (seg > 0 && next <= along + seg) {
      out.push_back(poly[i - 1] + (next - along) / seg * (poly[i] - poly[i - 1]));
      next += h;
    }
    along += seg;
  }
  if (length - (next - h) > 0.5 * h) out.push_back(poly.back());
  if (out.size() < 2) out.push_back(poly.back());
  return out;
}

namespace {

// The nodes of the cell containing grid coordinate x along one axis: its lower node and how many
// (2; 1 when x is on a node plane to rounding: the point lies on the face between two cells and
// trilinear lookups there read only that face's nodes, so only they are constrained, which
// keeps the constraints of a curve's mirror image the mirror of the curve's, symmetry.h).
int cell_span(double x, int& lower) {
  const double nearest = std::round(x);
  if (std::abs(x - nearest) < 1e-9) {
    lower = static_cast<int>(nearest);
    return 1;
  }
  lower = static_cast<int>(std::floor(x));
  return 2;
}

}  // namespace

void constrain_cell(const Grid& grid, const Eigen::Vector3d& p, const Eigen::Vector3d& dir,
                    std::vector<Constraint>& out) {
  const Eigen::Vector3d q = grid.to_grid(p);
  int i0 = 0, j0 = 0, k0 = 0;
  const int ni = cell_span(q.x(), i0), nj = cell_span(q.y(), j0), nk = cell_span(q.z(), k0);
  for (int dk = 0; dk < nk; ++dk)
    for (int dj = 0; dj < nj; ++dj)
      for (int di = 0; di < ni; ++di) {
        const int i = i0 + di, j = j0 + dj, k = k0 + dk;
        if (i < 0 || j < 0 || k < 0 || i >= grid.dims[0] || j >= grid.dims[1] || k >= grid.dims[2]) continue;
        out.push_back({grid.index(i, j, k), dir});
      }
}

void constrain_nearest(const Grid& grid, const Eigen::Vector3d& p, const Eigen::Vector3d& dir,
                       std::vector<Constraint>& out) {
  const Eigen::Vector3d q = grid.to_grid(p);
  const int i = static_cast<int>(std::lround(q.x())), j = static_cast<int>(std::lround(q.y())),
            k = static_cast<int>(std::lround(q.z()));
  if (i < 0 || j < 0 || k < 0 || i >= grid.dims[0] || j >= grid.dims[1] || k >= grid.dims[2]) return;
  out.push_back({grid.index(i, j, k), dir});
}

void orthonormal_frame(const Eigen::Vector3d& t, Eigen::Vector3d& u, Eigen::Vector3d& v) {
  const Eigen::Vector3d a = std::abs(t.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  u = t.cross(a).normalized();
  v = t.cross(u).normalized();
}

}  // namespace lapis::hair_sketch::detail
