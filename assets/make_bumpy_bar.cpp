// Writes the salient method's figure case into a directory: the bumpy bar of
// tests/mesh_deform/salient_deformer_test.cpp (1 × 1 × 4, ~10K vertices, a bump on one side),
// its ROI (all but the bottom tenth), handle (the top tenth, bent 90°) and the bump as a
// feature, for `lapis deform` (docs/mesh_deform.md's picture).
//   lapis_make_bumpy_bar OUT_DIR
#include <cstdio>
#include <filesystem>

#include "lapis/geometry/io.h"
#include "lapis/mesh_deform/feature_io.h"
#include "lapis/mesh_deform/selection_io.h"
#include "salient_meshes.h"
#include "test_meshes.h"

int main(int argc, char** argv) {
  using namespace lapis::mesh_deform;
  if (argc != 2) {
    std::fprintf(stderr, "usage: lapis_make_bumpy_bar OUT_DIR\n");
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  std::filesystem::create_directories(dir);
  const test::BumpyBar bar = test::bumpy_bar(24);
  const Selection sel = test::bottom_fixed_top_handle(bar.mesh, 2, 0.1, 0.1);
  lapis::geometry::write_mesh(dir / "bumpy_bar.obj", bar.mesh);
  write_roi(dir / "bumpy_bar.roi.txt", sel.roi);
  write_handles(dir / "bumpy_bar.handles.json", sel, {HandleTransforms{{test::bend_and_twist(bar.mesh, 0)}, {}}});
  write_features(dir / "bumpy_bar.features.json", {bar.bump});
  std::printf("wrote %s/bumpy_bar.{obj,roi.txt,handles.json,features.json}\n", dir.string().c_str());
  return 0;
}
