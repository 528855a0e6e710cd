// lapis — every Lapis module's job, headless: `lapis <command> [options]`.
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "args.h"
#include "command.h"
#include "lapis/core/main_guard.h"

namespace {

void print_overview() {
  std::printf("usage: lapis <command> [options]   (lapis <command> --help for its options)\n\ncommands:\n");
  for (const auto& c : lapis::cli::commands()) std::printf("  %-10s %s\n", c.name, c.summary);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace lapis::cli;
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
    print_overview();
    return argc < 2 ? 2 : 0;
  }
  const std::string name = argv[1];
  for (const auto& c : commands()) {
    if (name != c.name) continue;
    const std::vector<std::string> args(argv + 2, argv + argc);
    if (!args.empty() && (args[0] == "--help" || args[0] == "-h")) {
      std::printf("%s", c.usage);
      return 0;
    }
    return lapis::core::guarded_main(
        std::string("lapis ") + c.name, [&] { return c.run(args); }, c.usage);
  }
  std::fprintf(stderr, "lapis: unknown command '%s'\n", name.c_str());
  print_overview();
  return 2;
}
