// Fuzz target: the handle-region file of `lapis merge --mode dependent`
// (mesh_merge::read_handles_file).
#include "fuzz_input.h"
#include "lapis/mesh_merge/pairs_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return lapis::fuzz::read_as_file(data, size, ".json",
                                   [](const auto& path) { (void)lapis::mesh_merge::read_handles_file(path); });
}
