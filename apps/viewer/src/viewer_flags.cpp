// The command-line flags every app shares (viewer.h), parsed before the app reads its own.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "lapis/core/error.h"
#include "lapis/viewer/viewer.h"

namespace lapis::viewer {

std::vector<std::string> parse_viewer_flags(int argc, char** argv, ViewerOptions& o) {
  std::vector<std::string> rest;
  auto value = [&](int& i, const char* flag) -> std::string {
    if (i + 1 >= argc) throw UsageError(std::string("viewer: ") + flag + " needs a value");
    return argv[++i];
  };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--headless")
      o.headless = true;
    else if (a == "--replay")
      o.replay = value(i, "--replay");
    else if (a == "--record")
      o.record = value(i, "--record");
    else if (a == "--screenshot")
      o.screenshot = value(i, "--screenshot");
    else if (a == "--render")
      o.render = value(i, "--render"), o.headless = true;
    else if (a == "--supersample") {
      const std::string s = value(i, "--supersample");
      if (std::sscanf(s.c_str(), "%d", &o.supersample) != 1 || o.supersample < 1 || o.supersample > 8)
        throw UsageError("viewer: --supersample expects 1..8 samples per pixel along each axis, got '" + s + "'");
    } else if (a == "--render-tile") {
      const std::string s = value(i, "--render-tile");
      if (std::sscanf(s.c_str(), "%d", &o.render_tile) != 1 || o.render_tile < 16)
        throw UsageError("viewer: --render-tile expects a tile side of at least 16 pixels, got '" + s + "'");
    } else if (a == "--orbit") {
      const std::string s = value(i, "--orbit");
      double yaw = 0, pitch = 0;
      if (std::sscanf(s.c_str(), "%lf,%lf", &yaw, &pitch) != 2 || !std::isfinite(yaw) || !(std::abs(pitch) < 90))
        throw UsageError("viewer: --orbit expects YAW,PITCH in degrees (|pitch| < 90), got '" + s + "'");
      o.orbit = Eigen::Vector2d(yaw, pitch);
    } else if (a == "--exit-after-replay")
      o.exit_after_replay = true;
    else if (a == "--no-frame-cache")
      o.frame_cache = false;
    else if (a == "--benchmark")
      o.benchmark = value(i, "--benchmark");
    else if (a == "--ready-file")
      o.ready_file = value(i, "--ready-file");
    else if (a == "--size") {
      const std::string s = value(i, "--size");
      if (std::sscanf(s.c_str(), "%dx%d", &o.width, &o.height) != 2 || o.width < 64 || o.height < 64)
        throw UsageError("viewer: --size expects WIDTHxHEIGHT (at least 64x64), got '" + s + "'");
    } else if (a == "--msaa") {
      const std::string s = value(i, "--msaa");
      if (std::sscanf(s.c_str(), "%d", &o.msaa_samples) != 1 || o.msaa_samples < 0 || o.msaa_samples > 16)
        throw UsageError("viewer: --msaa expects 0..16 samples per pixel, got '" + s + "'");
    } else
      rest.push_back(a);
  }
  return rest;
}

}  // namespace lapis::viewer
