// lapis-hair-sketch [--session FILE] [--head MESH] [--replay EVENTS] [--screenshot OUT.png]
//                   [--headless] [--exit-after-replay] [--record EVENTS] [--benchmark OUT.json]
//                   [--export-hair OUT.hair] [--export-obj OUT.obj] [--save-session OUT.json]
//                   [--roots N] [--draw-segments N] [--strands ribbons|lines] [--gravity-prior S]
//                   [--render OUT.png --size WxH [--supersample N]]
#include <filesystem>
#include <memory>

#include "args.h"
#include "hair_sketch_app.h"
#include "lapis/core/asset_path.h"
#include "lapis/hair_sketch/export.h"
#include "lapis/hair_sketch/hair_file.h"
#include "lapis/hair_sketch/session.h"
#include "lapis/viewer/app_main.h"

namespace {

constexpr const char* kUsage =
    "usage: lapis-hair-sketch [--session FILE] [--head MESH] [--headless] [--replay EVENTS]\n"
    "                         [--record EVENTS] [--screenshot OUT.png] [--exit-after-replay]\n"
    "                         [--benchmark OUT.json] [--ready-file F] [--size WxH] [--export-hair OUT.hair]\n"
    "                         [--export-obj OUT.obj] [--save-session OUT.json] [--roots N]\n"
    "                         [--draw-segments N]  (strand segments drawn; 0: all; default:\n"
    "                         adapted to the frame time in a window, all with --headless)\n"
    "                         [--strands ribbons|lines]  (default ribbons: tapered, shaded, self-shadowed)\n"
    "                         [--gravity-prior S]  (hair falls where nothing is sketched; 0: the thesis'\n"
    "                         field; default 0.3 for a new style, the session's value otherwise)\n"
    "                         [--render OUT.png [--supersample N]]  (once grown, the hair on the head\n"
    "                         without panels at --size, N x N samples per pixel (default 3); then exit)\n"
    "--save-session: where Ctrl+S saves (default: the --session file, else hairstyle.json);\n"
    "the autosave (every minute and on exit) goes beside it as OUT.json.autosave.json.\n"
    "Left-drag sketches with the current tool (keys 1-8; 7 draws a cut line, 8 paints the selected detail's region; M "
    "mirrors new curves), "
    "right-drag orbits, middle-drag pans,\n"
    "wheel zooms, F frames the head, Ctrl+Z / Ctrl+Shift+Z undo / redo, Ctrl+S / Ctrl+O save /\n"
    "open the session, Ctrl+E exports .hair and .obj, Delete removes the selected curve.\n";

// A new style starts with hair that falls (gravity_prior.h); sessions keep what they were made with.
constexpr double kNewStylePrior = 0.3;

std::unique_ptr<lapis::viewer::ViewerApp> make_app(const std::vector<std::string>& rest) {
  using namespace lapis;
  const cli::Args args(rest);
  args.allow_only({"--session", "--head", "--export-hair", "--export-obj", "--save-session", "--roots",
                   "--draw-segments", "--strands", "--gravity-prior"});
  hair_app::AppPaths paths;
  hair_sketch::Hairstyle style;
  hair_sketch::Head head;
  if (args.has("--session")) {
    paths.session = args.get("--session");
    style = hair_sketch::load_session(paths.session);
    head = hair_sketch::load_session_head(style, paths.session, args.get("--head", ""));
    // Absolute while the app runs: a session saved elsewhere (--save-session) then still finds
    // the head, save_session() writing the paths relative to where it goes.
    for (std::string* p : {&style.settings.head_mesh, &style.settings.scalp_mask})
      if (!p->empty() && std::filesystem::path(*p).is_relative())
        *p = std::filesystem::absolute(paths.session.parent_path() / *p).lexically_normal().string();
  } else if (args.has("--head")) {
    style.settings.gravity_prior.strength = kNewStylePrior;
    paths.session = "hairstyle.json";
    head = hair_sketch::load_head(args.get("--head"));
    style.settings.head_mesh = std::filesystem::absolute(args.get("--head")).lexically_normal().string();
  } else {
    paths.session = "hairstyle.json";
    style.settings.gravity_prior.strength = kNewStylePrior;
    style.settings.head_mesh = asset_path("head.obj").string();
    style.settings.scalp_mask = asset_path("head_scalp.txt").string();
    head = hair_sketch::load_head(style.settings.head_mesh, style.settings.scalp_mask);
  }
  style.settings.roots.count = static_cast<int>(args.get_int("--roots", style.settings.roots.count, 1, 2000000));
  style.settings.gravity_prior.strength =
      args.get_double("--gravity-prior", style.settings.gravity_prior.strength, 0, 10);
  if (args.has("--save-session")) paths.session = args.get("--save-session");
  paths.autosave = paths.session.string() + ".autosave.json";
  paths.export_hair = args.get("--export-hair", "out/hairstyle.hair");
  paths.export_obj = args.get("--export-obj", "out/hairstyle.obj");
  paths.export_on_exit = args.has("--export-hair") || args.has("--export-obj");
  auto app = std::make_unique<hair_app::HairSketchApp>(std::move(head), std::move(style), paths);
  const std::string look = args.get("--strands", "ribbons");
  if (look != "ribbons" && look != "lines")
    throw UsageError("lapis-hair-sketch: --strands expects ribbons or lines, got '" + look + "'");
  app->set_strand_look(look == "lines" ? hair_app::StrandLook::Lines : hair_app::StrandLook::Ribbons);
  if (args.has("--draw-segments"))
    app->set_drawn_segments(static_cast<int>(args.get_int("--draw-segments", 0, 0, 100000000)));
  return app;
}

}  // namespace

int main(int argc, char** argv) { return lapis::viewer::app_main(argc, argv, "lapis-hair-sketch", kUsage, make_app); }
