// `lapis mesh`: load a mesh, report its validity and topology as JSON, optionally convert
// it to another format. The quickest way to see whether a file is usable by the modules.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "args.h"
#include "cli_io.h"
#include "command.h"
#include "lapis/core/atomic_file.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/io.h"
#include "lapis/geometry/tri_mesh.h"

namespace lapis::cli {
namespace {

constexpr const char* kUsage =
    "usage: lapis mesh --in MESH [--out MESH] [--report OUT.json]\n"
    "  Loads MESH (.obj .off .ply .stl), validates it (indices, NaN, degenerate and duplicate\n"
    "  faces, non-manifold edges and vertices) and prints counts, components, boundary loops,\n"
    "  Euler characteristic and genus as JSON. --out converts it (format by extension).\n"
    "  Exit status 1 when the mesh cannot be read or is invalid.\n";

int run(const std::vector<std::string>& argv) {
  const Args args(argv);
  args.allow_only({"--in", "--out", "--report"});
  geometry::Warnings warnings;
  const geometry::TriMesh mesh = geometry::read_mesh(args.get("--in"), &warnings);
  const geometry::ValidationReport report = geometry::validate(mesh);
  nlohmann::json j;
  j["file"] = args.get("--in");
  j["vertices"] = mesh.num_vertices();
  j["faces"] = mesh.num_faces();
  j["warnings"] = warnings;
  j["valid"] = report.ok();
  if (!report.ok()) j["problems"] = report.summary();
  if (report.ok()) {
    const geometry::Connectivity conn(mesh);
    j["edges"] = conn.num_edges();
    j["components"] = geometry::connected_components(conn).count;
    j["boundary_loops"] = conn.boundary_loops().size();
    j["euler_characteristic"] = geometry::euler_characteristic(conn);
    j["genus"] = geometry::genus(conn);
  }
  emit_report(j, args);
  if (!report.ok()) {
    std::fprintf(stderr, "lapis mesh: error: invalid mesh: %s\n", report.summary(3).c_str());
    return 1;
  }
  if (args.has("--out")) geometry::write_mesh(args.get("--out"), mesh);
  return 0;
}

}  // namespace

extern const Command kMeshCommand = {"mesh", "inspect, validate and convert a mesh file", kUsage, run};

}  // namespace lapis::cli
