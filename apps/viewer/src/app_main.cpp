#include "lapis/viewer/app_main.h"

#include <cstdio>

#include "lapis/core/main_guard.h"

namespace lapis::viewer {

int app_main(int argc, char** argv, const std::string& title, const std::string& usage, const MakeApp& make_app) {
  return core::guarded_main(title, [&] {
    ViewerOptions options;
    options.title = title;
    std::vector<std::string> rest = parse_viewer_flags(argc, argv, options);
    if (!rest.empty() && (rest[0] == "--help" || rest[0] == "-h")) {
      std::printf("%s", usage.c_str());
      return 0;
    }
    const std::unique_ptr<ViewerApp> app = make_app(std::move(rest));
    Viewer viewer(options);
    return viewer.run(*app);
  });
}

}  // namespace lapis::viewer
