// The main() every Lapis app shares: the viewer's flags, --help, the app built from the rest
// of the command line, the window run, and errors reported the way every Lapis program does.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "lapis/viewer/viewer.h"

namespace lapis::viewer {

// Builds the app from the arguments the viewer's flags left.
using MakeApp = std::function<std::unique_ptr<ViewerApp>(std::vector<std::string> args)>;

// `title` names the window and the program in messages. --help or -h prints `usage` and
// returns 0; a malformed command line returns 2, any other error 1 (core::guarded_main).
int app_main(int argc, char** argv, const std::string& title, const std::string& usage, const MakeApp& make_app);

}  // namespace lapis::viewer
