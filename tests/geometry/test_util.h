// Shared helpers of the geometry tests: a scratch directory per test binary run, and small
// hand-made meshes.
#pragma once

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <string>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::geometry::test {

// A fresh directory under the system temp dir, unique to this process, removed at exit.
inline std::filesystem::path scratch_dir() {
  struct Scratch {
    std::filesystem::path dir;
    Scratch() : dir(std::filesystem::temp_directory_path() / ("lapis_geometry_test_" + std::to_string(::getpid()))) {
      std::filesystem::remove_all(dir);
      std::filesystem::create_directories(dir);
    }
    ~Scratch() {
      std::error_code ignored;
      std::filesystem::remove_all(dir, ignored);
    }
  };
  static const Scratch scratch;
  return scratch.dir;
}

inline std::filesystem::path write_bytes(const std::string& name, const std::string& bytes) {
  const auto path = scratch_dir() / name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

// A regular tetrahedron, outward oriented.
inline TriMesh tetrahedron() {
  TriMesh m;
  m.V.resize(4, 3);
  m.V << 1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1;
  m.F.resize(4, 3);
  m.F << 0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2;
  return m;
}

inline std::filesystem::path external_asset(const std::string& name) {
  return std::filesystem::path(LAPIS_SOURCE_DIR) / "assets" / "external" / name;
}

}  // namespace lapis::geometry::test
