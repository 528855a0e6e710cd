// Inspection exports: OBJ strands, VTK and raw field images.
#include "lapis/hair_sketch/export.h"

#include <bit>
#include <cstdio>
#include <string>
#include <vector>

#include "lapis/core/atomic_file.h"
#include "lapis/core/error.h"
#include "lapis/geometry/io.h"

namespace lapis::hair_sketch {
using hair_field::Field;
using hair_field::Grid;

namespace {

void check_field(const Grid& grid, const Field& field, const char* fn) {
  if (field.rows() != grid.num_nodes())
    throw InvalidArgument(std::string(fn) + ": field has " + std::to_string(field.rows()) + " rows, the grid has " +
                          std::to_string(grid.num_nodes()) + " nodes");
}

}  // namespace

Strands grown_strands(const Strands& strands) {
  Strands out;
  out.points.reserve(strands.points.size());
  out.offsets.reserve(strands.offsets.size());
  for (int s = 0; s < strands.count(); ++s) {
    const int a = strands.offsets[s], b = strands.offsets[s + 1];
    bool long_enough = false;
    for (int i = a + 1; i < b && !long_enough; ++i) long_enough = strands.points[i] != strands.points[a];
    if (!long_enough) continue;
    out.points.insert(out.points.end(), strands.points.begin() + a, strands.points.begin() + b);
    out.offsets.push_back(static_cast<int>(out.points.size()));
  }
  return out;
}

void write_strands_obj(const std::filesystem::path& path, const Strands& strands) {
  std::vector<std::vector<Eigen::Vector3d>> lines;
  lines.reserve(strands.count());
  for (int s = 0; s < strands.count(); ++s) {
    if (strands.offsets[s + 1] - strands.offsets[s] < 2) continue;
    auto& line = lines.emplace_back();
    for (int i = strands.offsets[s]; i < strands.offsets[s + 1]; ++i) line.push_back(strands.points[i].cast<double>());
  }
  geometry::write_obj_polylines(path, lines);
}

void write_field_vtk(const std::filesystem::path& path, const Grid& grid, const Field& field) {
  check_field(grid, field, "hair_sketch::write_field_vtk()");
  core::write_file_atomically(path, [&](std::ostream& out) {
    char line[512];
    out << "# vtk DataFile Version 3.0\nLapis hair vector field\nASCII\nDATASET STRUCTURED_POINTS\n";
    std::snprintf(line, sizeof line, "DIMENSIONS %d %d %d\nORIGIN %.17g %.17g %.17g\nSPACING %.17g %.17g %.17g\n",
                  grid.dims[0], grid.dims[1], grid.dims[2], grid.origin.x(), grid.origin.y(), grid.origin.z(),
                  grid.spacing, grid.spacing, grid.spacing);
    out << line << "POINT_DATA " << grid.num_nodes() << "\nVECTORS direction float\n";
    for (Eigen::Index i = 0; i < field.rows(); ++i) {
      std::snprintf(line, sizeof line, "%.9g %.9g %.9g\n", field(i, 0), field(i, 1), field(i, 2));
      out << line;
    }
    out << "SCALARS magnitude float 1\nLOOKUP_TABLE default\n";
    for (Eigen::Index i = 0; i < field.rows(); ++i) {
      std::snprintf(line, sizeof line, "%.9g\n", field.row(i).norm());
      out << line;
    }
  });
}

void write_field_raw(const std::filesystem::path& path, const Grid& grid, const Field& field) {
  static_assert(std::endian::native == std::endian::little, "raw field files are little-endian");
  check_field(grid, field, "hair_sketch::write_field_raw()");
  const Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor> f = field.cast<float>();
  core::write_file_atomically(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(f.data()), static_cast<std::streamsize>(f.size() * sizeof(float)));
  });
}

}  // namespace lapis::hair_sketch
