// `lapis hair`: replay a hairstyle session headless (thesis ch. 4 pipeline: strokes ->
// primitives -> field -> strands) and write the strands as .hair / OBJ with a JSON report.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>

#include "args.h"
#include "cli_io.h"
#include "command.h"
#include "lapis/core/atomic_file.h"
#include "lapis/hair_sketch/export.h"
#include "lapis/hair_sketch/hair_file.h"
#include "lapis/hair_sketch/session.h"
#include "lapis/hair_sketch/stroke_commands.h"
#include "lapis/hair_sketch/style_field.h"

namespace lapis::cli {
namespace {

using namespace lapis::hair_sketch;
using namespace lapis::hair_field;

constexpr const char* kUsage =
    "usage: lapis hair --session FILE.json [--head MESH] [--grid-unknowns N] [--roots N]\n"
    "                  [--field-method auto|thesis|refactorize|multigrid] [--gravity-prior S]\n"
    "                  --out-hair OUT.hair [--out-obj OUT.obj] [--out-field OUT.vtk] [--report OUT.json]\n"
    "  Replays a hairstyle session: its recorded strokes (if any) are interpreted again,\n"
    "  otherwise its stored primitives are used; the vector field is solved, strands grow\n"
    "  from the scalp and are written in Cem Yuksel's .hair format (and as OBJ polylines).\n"
    "  --head replaces the session's head mesh (its scalp is then the default cap);\n"
    "  --grid-unknowns, --roots and --field-method override the session's settings (auto picks\n"
    "  by the grid's size; thesis: update/downdate of the Cholesky factor, 4.4.2). --gravity-prior S\n"
    "  lets hair fall where no curve steers it (0: the thesis' field). The report (printed and\n"
    "  saved) holds counts, timings and the field solver's decisions.\n";

// The session format's names (session.h).
FieldMethod field_method_named(const std::string& name) {
  if (name == "auto") return FieldMethod::Auto;
  if (name == "thesis") return FieldMethod::Thesis;
  if (name == "refactorize") return FieldMethod::Refactorize;
  if (name == "multigrid") return FieldMethod::Multigrid;
  throw UsageError("--field-method must be auto, thesis, refactorize or multigrid, not '" + name + "'");
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

int run(const std::vector<std::string>& argv) {
  const auto t0 = std::chrono::steady_clock::now();
  const Args args(argv);
  args.allow_only({"--session", "--head", "--grid-unknowns", "--roots", "--field-method", "--gravity-prior",
                   "--out-hair", "--out-obj", "--out-field", "--report"});
  const std::filesystem::path session_path = args.get("--session");
  const std::string out_hair = args.get("--out-hair");
  // Flags are checked before any file is read.
  const std::optional<FieldMethod> method =
      args.has("--field-method") ? std::optional(field_method_named(args.get("--field-method"))) : std::nullopt;
  const std::optional<double> prior =
      args.has("--gravity-prior") ? std::optional(args.get_double("--gravity-prior", 0, 0, 10)) : std::nullopt;
  Hairstyle session = load_session(session_path);
  if (method) session.settings.field_method = *method;
  if (prior) session.settings.gravity_prior.strength = *prior;
  if (args.has("--grid-unknowns"))
    session.settings.grid.target_unknowns = static_cast<double>(args.get_int("--grid-unknowns", 0, 8, 100'000'000));
  if (args.has("--roots")) session.settings.roots.count = static_cast<int>(args.get_int("--roots", 0, 0, 10'000'000));
  const Head head = load_session_head(session, session_path, args.get("--head", ""));

  auto t = std::chrono::steady_clock::now();
  const bool replay = !session.strokes.empty();
  const Hairstyle style = replay ? replay_strokes(session, head) : session;
  const double replay_ms = ms_since(t);
  const HairstyleResult r = build_hairstyle(style, head);

  t = std::chrono::steady_clock::now();
  core::AtomicFileGroup outputs;                   // .hair, .obj, .vtk and the report: all new or all old
  const Strands grown = grown_strands(r.strands);  // not the roots that grew nothing
  write_hair_file(out_hair, to_hair_file(grown));
  if (args.has("--out-obj")) write_strands_obj(args.get("--out-obj"), grown);
  if (args.has("--out-field")) write_field_vtk(args.get("--out-field"), r.grid, r.field);
  const double write_ms = ms_since(t);

  nlohmann::json j;
  j["session"] = session_path.string();
  j["replayed_strokes"] = replay ? static_cast<int>(session.strokes.size()) : 0;
  j["primitives"] = style.primitives.size();
  j["details"] = nlohmann::json::array();
  for (const auto& d : style.details) j["details"].push_back(detail_type(d));
  j["strands"] = grown.count();
  j["roots_without_hair"] = r.strands.count() - grown.count();
  j["segments"] = grown.segments();
  j["penetrating_segments"] = r.penetrating_segments;
  j["constraints"] = r.constraints;
  j["grid"] = {{"dims", r.grid.dims}, {"spacing", r.grid.spacing}, {"unknowns", r.grid.num_nodes()}};
  j["solves"] = nlohmann::json::array();
  for (const auto& s : r.solves)
    j["solves"].push_back({{"method", to_string(s.method)},
                           {"added", s.added},
                           {"removed", s.removed},
                           {"changed", s.changed},
                           {"update_ms", s.update_ms},
                           {"solve_ms", s.solve_ms},
                           {"iterations", s.iterations},
                           {"detail", s.detail}});
  j["timings_ms"] = {{"replay", replay_ms},
                     {"grid", r.grid_ms},
                     {"solve", r.solve_ms},
                     {"clearance", r.clearance_ms},
                     {"growth", r.growth_ms},
                     {"detail", r.detail_ms},
                     {"penetration", r.penetration_ms},
                     {"write", write_ms},
                     {"total", ms_since(t0)}};
  emit_report(j, args);
  outputs.commit();
  return 0;
}

}  // namespace

extern const Command kHairCommand = {"hair", "replay a hairstyle session and export its strands", kUsage, run};

}  // namespace lapis::cli
