// Fuzz target: geometry::read_ply on arbitrary bytes (PLY meshes, ASCII and binary little / big endian).
#include "fuzz_input.h"
#include "lapis/geometry/io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return lapis::fuzz::read_as_file(data, size, ".ply", [](const auto& path) {
    lapis::geometry::Warnings warnings;
    (void)lapis::geometry::read_ply(path, &warnings);
  });
}
