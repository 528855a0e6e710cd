// Fuzz target: Cem Yuksel's .hair format (hair_sketch::read_hair_file), then the strands it
// holds.
#include "fuzz_input.h"
#include "lapis/hair_sketch/hair_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return lapis::fuzz::read_as_file(data, size, ".hair", [](const auto& path) {
    const auto file = lapis::hair_sketch::read_hair_file(path);
    (void)lapis::hair_sketch::strands_from_hair_file(file);
  });
}
