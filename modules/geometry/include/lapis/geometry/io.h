// Mesh and polyline file I/O: OBJ, OFF/COFF, PLY (ASCII, binary little/big endian) and STL
// (ASCII, binary). Readers reject malformed input with lapis::IoError naming the file, the
// line or byte offset and what was expected; writers save atomically (see atomic_file.h).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::geometry {

// Non-fatal findings of a reader (polygons fan-triangulated, ignored elements). Readers
// append to *warnings when given, and print nothing; with no sink, warnings are dropped.
using Warnings = std::vector<std::string>;

// Dispatches on the extension (.obj .off .ply .stl, case-insensitive). Throws IoError for an
// unknown extension, an unreadable file or malformed content. The mesh is not validated
// beyond index range and finiteness: call require_valid() for the topological checks.
TriMesh read_mesh(const std::filesystem::path& path, Warnings* warnings = nullptr);
TriMesh read_obj(const std::filesystem::path& path, Warnings* warnings = nullptr);
TriMesh read_off(const std::filesystem::path& path, Warnings* warnings = nullptr);
TriMesh read_ply(const std::filesystem::path& path, Warnings* warnings = nullptr);
// STL stores each triangle's corners separately; bitwise-equal positions are merged so that
// the result is an indexed mesh with connectivity.
TriMesh read_stl(const std::filesystem::path& path, Warnings* warnings = nullptr);

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

// Writers: doubles are printed in shortest round-trip form, so reading back is exact.
void write_mesh(const std::filesystem::path& path, const TriMesh& mesh);  // by extension
void write_obj(const std::filesystem::path& path, const TriMesh& mesh);
void write_off(const std::filesystem::path& path, const TriMesh& mesh);
// Binary PLY stores double positions and int32 indices (lists with uint8 counts).
void write_ply(const std::filesystem::path& path, const TriMesh& mesh,
               PlyFormat format = PlyFormat::BinaryLittleEndian);
// Binary STL (float32: lossy for doubles, as the format is).
void write_stl(const std::filesystem::path& path, const TriMesh& mesh);

// Curves as OBJ 'l' statements (style curves, merging boundaries).
struct Polylines {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<int>> lines;  // 0-based indices into points
};
void write_obj_polylines(const std::filesystem::path& path, const std::vector<std::vector<Eigen::Vector3d>>& polylines);
Polylines read_obj_polylines(const std::filesystem::path& path);

}  // namespace lapis::geometry
