// `lapis transfer`: deformation transfer by handle correspondence (mesh_deform, Au et al. 2007
// §6). Fits the source poses' per-isoline transforms (Eq. 11) and rebuilds the target from
// them (Eq. 12); several poses (an animation) share one set-up.
#include <nlohmann/json.hpp>

#include "args.h"
#include "cli_io.h"
#include "command.h"
#include "lapis/core/atomic_file.h"
#include "lapis/geometry/io.h"
#include "lapis/mesh_deform/deformation_transfer.h"
#include "lapis/mesh_deform/selection_io.h"

namespace lapis::cli {
namespace {

using nlohmann::json;
using namespace lapis::mesh_deform;

constexpr const char* kUsage =
    "usage: lapis transfer --source REST --source-deformed POSE[,POSE...] --source-handles H.json\n"
    "                      --target MESH --target-handles H.json --out OUT\n"
    "                      [--source-roi ROI] [--target-roi ROI] [--isolines N] [--report OUT.json]\n"
    "  H.json: a handles file of lapis deform (its vertices are read, its transforms ignored);\n"
    "  handles pair one to one in order, region with region and point with point. ROI: the\n"
    "  vertices not held by the fixed region ('all', the default: no fixed region); both meshes\n"
    "  must have one or neither. Each POSE has the source's vertices in its order. With several\n"
    "  poses OUT gets _0, _1, ... before its extension. --isolines per handle (20).\n";

std::vector<std::string> split_commas(const std::string& s) {
  std::vector<std::string> out;
  size_t start = 0;
  for (size_t comma; (comma = s.find(',', start)) != std::string::npos; start = comma + 1)
    out.push_back(s.substr(start, comma - start));
  out.push_back(s.substr(start));
  return out;
}

Selection read_selection(const Args& args, const char* handles, const char* roi, int n) {
  Selection s = read_handles(args.get(handles)).selection;
  const std::string spec = args.get(roi, "all");
  if (spec == "all")
    for (int i = 0; i < n; ++i) s.roi.push_back(i);
  else
    s.roi = read_roi(spec);
  return s;
}

// OUT for one pose; OUT with _k before the extension for several.
std::string pose_path(const std::string& out, size_t k, size_t count) {
  if (count == 1) return out;
  const std::filesystem::path p(out);
  return (p.parent_path() / (p.stem().string() + "_" + std::to_string(k) + p.extension().string())).string();
}

int run(const std::vector<std::string>& argv) {
  const Args args(argv, {});
  args.allow_only({"--source", "--source-deformed", "--source-handles", "--target", "--target-handles", "--out",
                   "--source-roi", "--target-roi", "--isolines", "--report"});
  const geometry::TriMesh source = read_valid_mesh(args.get("--source"));
  const geometry::TriMesh target = read_valid_mesh(args.get("--target"));
  TransferOptions o;
  o.isolines = static_cast<int>(args.get_int("--isolines", o.isolines, 2, 100000));
  const std::string out = args.get("--out");
  std::vector<geometry::TriMesh> poses;
  for (const std::string& path : split_commas(args.get("--source-deformed"))) {
    poses.push_back(read_valid_mesh(path));
    if (poses.back().num_vertices() != source.num_vertices())
      throw InvalidArgument(path + ": " + std::to_string(poses.back().num_vertices()) +
                            " vertices, expected the source's " + std::to_string(source.num_vertices()));
  }
  DeformationTransfer transfer(source, read_selection(args, "--source-handles", "--source-roi", source.num_vertices()),
                               target, read_selection(args, "--target-handles", "--target-roi", target.num_vertices()),
                               o);
  json frames = json::array();
  std::vector<geometry::TriMesh> results;
  for (const geometry::TriMesh& pose : poses) {
    geometry::TriMesh r = target;
    r.V = transfer.transfer(pose.V);
    results.push_back(std::move(r));
    frames.push_back(
        {{"eq11_residual", transfer.report().eq11_residual}, {"eq12_residual", transfer.report().eq12_residual}});
  }
  const json report = {{"source_vertices", source.num_vertices()},
                       {"target_vertices", target.num_vertices()},
                       {"handles", transfer.report().handles},
                       {"unknowns", transfer.report().unknowns},
                       {"pinned", transfer.report().pinned},
                       {"setup_s", transfer.report().setup_ms / 1000},
                       {"poses", frames}};
  require_finite_numbers(report, "report");  // all outputs or none
  core::AtomicFileGroup outputs;
  for (size_t k = 0; k < results.size(); ++k) geometry::write_mesh(pose_path(out, k, results.size()), results[k]);
  emit_report(report, args);
  outputs.commit();
  return 0;
}

}  // namespace

extern const Command kTransferCommand = {
    "transfer", "carry a source mesh's deformation onto a target through corresponding handles (Au et al.)", kUsage,
    run};

}  // namespace lapis::cli
