// Fuzz target: the `--flag value` parser (cli::Args) as each command line uses it. The first
// byte picks the command line, the rest is its argv split at NUL bytes; the parser is then
// asked what that command asks (allowed flags, switches, typed values with their ranges).
#include <set>
#include <string>
#include <vector>

#include "args.h"
#include "fuzz_input.h"

namespace {

struct Ranged {
  const char* flag;
  double lo, hi;
};

struct CommandLine {
  std::set<std::string> switches, known;
  std::vector<Ranged> ints, doubles;
};

// The flags, switches and ranges of `lapis mesh|hair|deform|merge` and of the hair, deform
// and merge apps, as their parsers declare them.
const std::vector<CommandLine>& command_lines() {
  static const std::vector<CommandLine> lines = {
      {{}, {"--in", "--out", "--report"}, {}, {}},
      {{},
       {"--session", "--head", "--grid-unknowns", "--roots", "--out-hair", "--out-obj", "--out-field", "--report"},
       {{"--grid-unknowns", 8, 1e8}, {"--roots", 0, 1e7}},
       {}},
      {{"--scale-features"},
       {"--mesh", "--roi", "--handles", "--method", "--weights", "--scale-features", "--iterations", "--out",
        "--report"},
       {{"--iterations", 1, 1e6}},
       {}},
      {{},
       {"--source", "--target", "--pairs", "--out", "--mode", "--handles", "--smooth", "--roi-width", "--source-width",
        "--target-width", "--keep", "--report"},
       {{"--smooth", 0, 1000}},
       {{"--roi-width", 0, 1e300}, {"--source-width", -1e300, 1e300}, {"--target-width", -1e300, 1e300}}},
      {{},
       {"--session", "--head", "--export-hair", "--export-obj", "--save-session", "--roots", "--draw-segments"},
       {{"--roots", 1, 2e6}, {"--draw-segments", 0, 1e8}},
       {}},
      {{"--scale-features", "--export-on-exit", "--full-while-dragging"},
       {"--mesh", "--subdivide", "--roi", "--handles", "--method", "--weights", "--scale-features", "--iterations",
        "--full-while-dragging", "--export", "--export-on-exit"},
       {{"--subdivide", 0, 4}, {"--iterations", 1, 1000}},
       {}},
      {{}, {"--source", "--target", "--preset", "--export"}, {{"--preset", 0, 7}}, {}},
  };
  return lines;
}

std::vector<std::string> split_at_nul(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> argv(1);
  for (std::size_t i = 0; i < size; ++i) {
    if (data[i] == 0)
      argv.emplace_back();
    else
      argv.back().push_back(static_cast<char>(data[i]));
  }
  return argv;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const CommandLine& line = command_lines()[data[0] % command_lines().size()];
  const auto argv = split_at_nul(data + 1, size - 1);
  return lapis::fuzz::expect_lapis_errors_only([&] {
    const lapis::cli::Args args(argv, line.switches);
    args.allow_only(line.known);
    for (const auto& flag : line.known) (void)args.get(flag, "");
    for (const auto& r : line.ints) (void)args.get_int(r.flag, 0, static_cast<long>(r.lo), static_cast<long>(r.hi));
    for (const auto& r : line.doubles) (void)args.get_double(r.flag, 0.0, r.lo, r.hi);
    if (!line.known.empty()) (void)args.get(*line.known.begin());
  });
}
