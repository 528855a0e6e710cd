// Inspection exports of a hairstyle: strands as OBJ polylines (any mesh viewer),
// the vector field as a legacy-VTK image (ParaView) or as raw float32 (numpy.fromfile).
// The .hair exchange format has its own header, hair_file.h. Every write is atomic.
#pragma once

#include <filesystem>

#include "lapis/hair_field/grid.h"
#include "lapis/hair_field/grid_operators.h"
#include "lapis/hair_sketch/growth.h"

namespace lapis::hair_sketch {

// The strands that grew hair: without the roots whose field was too weak there (one point, no
// segment) and without strands whose points all coincide (no length). Growth keeps one strand
// per root, so that an edit regrows strand i from root i; an export writes only these.
Strands grown_strands(const Strands& strands);

// One 'l' polyline per strand; strands with fewer than two points (roots whose field was
// too weak to grow) are skipped. Throws IoError when writing fails.
void write_strands_obj(const std::filesystem::path& path, const Strands& strands);

// Legacy VTK STRUCTURED_POINTS (ASCII) with the field as VECTORS "direction" and its length
// as SCALARS "magnitude". Throws InvalidArgument when field is not num_nodes by 3.
void write_field_vtk(const std::filesystem::path& path, const hair_field::Grid& grid, const hair_field::Field& field);

// float32 little-endian, x y z per node, nodes in grid index order (x fastest): a
// dims[2] x dims[1] x dims[0] x 3 array. Throws InvalidArgument on a size mismatch.
void write_field_raw(const std::filesystem::path& path, const hair_field::Grid& grid, const hair_field::Field& field);

}  // namespace lapis::hair_sketch
