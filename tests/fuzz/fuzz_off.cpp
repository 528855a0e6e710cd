// Fuzz target: geometry::read_off on arbitrary bytes (OFF / COFF meshes).
#include "fuzz_input.h"
#include "lapis/geometry/io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return lapis::fuzz::read_as_file(data, size, ".off", [](const auto& path) {
    lapis::geometry::Warnings warnings;
    (void)lapis::geometry::read_off(path, &warnings);
  });
}
