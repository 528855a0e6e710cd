// Uses the installed Lapis: deforms a grid with lapis::mesh_deform, samples hair roots on the
// installed bundled head with lapis::hair_sketch and round-trips a session. Prints what it
// finds and exits 0 only when every result is right.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "lapis/core/asset_path.h"
#include "lapis/geometry/procedural.h"
#include "lapis/hair_sketch/head.h"
#include "lapis/hair_sketch/session.h"
#include "lapis/mesh_deform/methods.h"

namespace {

int failures = 0;

void check(bool ok, const char* what) {
  std::printf("%s: %s\n", ok ? "ok" : "FAILED", what);
  if (!ok) ++failures;
}

// A 10 x 10 grid on [0,1]²: the border fixed, the centre vertex lifted by 0.25.
void deform_grid() {
  using namespace lapis;
  const int n = 10, centre = (n / 2) * (n + 1) + n / 2;
  const geometry::TriMesh grid = geometry::make_plane_grid(n, n);
  mesh_deform::Selection selection;
  for (int j = 1; j < n; ++j)
    for (int i = 1; i < n; ++i) selection.roi.push_back(j * (n + 1) + i);
  selection.point_handles = {centre};
  auto deformer = mesh_deform::make_deformer(grid, {});
  deformer->set_selection(selection);
  auto transforms = mesh_deform::HandleTransforms::identity(selection);
  transforms.points[0] = Eigen::Vector3d(0, 0, 0.25);
  const geometry::Vertices V = deformer->deform(transforms);
  const int beside = centre + 1, corner = 0;
  std::printf("deformed %s: centre z %.4f, its neighbour z %.4f, corner z %.4f\n", deformer->name().c_str(),
              V(centre, 2), V(beside, 2), V(corner, 2));
  check(std::abs(V(centre, 2) - 0.25) < 1e-9, "the handle reaches its target");
  check(V(beside, 2) > 0.01 && V(beside, 2) < 0.25, "a free neighbour follows part of the way");
  check(V.row(corner) == grid.V.row(corner), "the fixed border stays");
}

// Roots on the installed bundled head (found by lapis::asset_path) and a session round trip.
void hair_on_bundled_head() {
  using namespace lapis;
  const std::filesystem::path mesh = asset_path("head.obj"), mask = asset_path("head_scalp.txt");
  std::printf("bundled head: %s\n", mesh.c_str());
  if (const char* dir = std::getenv("LAPIS_ASSET_DIR"))
    check(mesh.parent_path() == std::filesystem::path(dir), "the head comes from $LAPIS_ASSET_DIR");
  const hair_sketch::Head head = hair_sketch::load_head(mesh, mask);
  hair_sketch::RootOptions options;
  options.count = 300;
  const auto roots = hair_sketch::sample_roots(head, options);
  int outside = 0;
  for (const auto& r : roots) outside += head.inside(r) ? 0 : 1;
  std::printf("head: %d scalp faces, %zu roots, %d outside\n", head.scalp_face_count(), roots.size(), outside);
  check(head.scalp_face_count() > 0, "the head has a scalp");
  check(roots.size() > 100 && outside == static_cast<int>(roots.size()), "roots sit on the scalp, none inside");

  hair_sketch::Hairstyle style;
  style.settings.roots.count = 123;
  style.settings.head_mesh = mesh.string();
  const hair_sketch::Hairstyle back = hair_sketch::session_from_json(hair_sketch::session_to_json(style));
  check(back.settings.roots.count == 123 && back.settings.head_mesh == mesh.string(), "a session round-trips");
}

}  // namespace

int main() {
  try {
    deform_grid();
    hair_on_bundled_head();
  } catch (const lapis::Error& e) {
    std::printf("FAILED: %s\n", e.what());
    return 1;
  }
  std::printf("%s\n", failures == 0 ? "consumer: all checks passed" : "consumer: checks failed");
  return failures == 0 ? 0 : 1;
}
