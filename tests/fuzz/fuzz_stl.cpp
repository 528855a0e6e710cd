// Fuzz target: geometry::read_stl on arbitrary bytes (STL meshes, ASCII and binary).
#include "fuzz_input.h"
#include "lapis/geometry/io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return lapis::fuzz::read_as_file(data, size, ".stl", [](const auto& path) {
    lapis::geometry::Warnings warnings;
    (void)lapis::geometry::read_stl(path, &warnings);
  });
}
