// Fuzz target: the handles file of `lapis deform` and the deform app
// (mesh_deform::read_handles).
#include "fuzz_input.h"
#include "lapis/mesh_deform/selection_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return lapis::fuzz::read_as_file(data, size, ".handles.json",
                                   [](const auto& path) { (void)lapis::mesh_deform::read_handles(path); });
}
