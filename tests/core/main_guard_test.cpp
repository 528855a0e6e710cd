// core::guarded_main: the exit status and the one line every Lapis program prints for an error.
#include <doctest/doctest.h>

#include <unistd.h>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <new>
#include <string>

#include "lapis/core/error.h"
#include "lapis/core/main_guard.h"

namespace {

// Runs guarded_main with stderr sent to a file; returns its status and what it printed.
std::pair<int, std::string> guarded(const std::function<int()>& body, const std::string& usage = {}) {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("lapis_main_guard_" + std::to_string(::getpid()));
  std::fflush(stderr);
  const int saved = ::dup(2);
  REQUIRE(std::freopen(file.c_str(), "w", stderr) != nullptr);
  const int status = lapis::core::guarded_main("prog", body, usage);
  std::fflush(stderr);
  ::dup2(saved, 2);
  ::close(saved);
  std::ifstream in(file);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  std::filesystem::remove(file);
  return {status, text};
}

}  // namespace

TEST_CASE("core: guarded_main returns the body's status and names the program in every error") {
  CHECK(guarded([] { return 7; }) == std::pair<int, std::string>{7, ""});
  CHECK(guarded([]() -> int { throw lapis::UsageError("--n needs a value"); }) ==
        std::pair<int, std::string>{2, "prog: --n needs a value (see --help)\n"});
  CHECK(guarded([]() -> int { throw lapis::UsageError("--n needs a value"); }, "usage: prog --n N\n") ==
        std::pair<int, std::string>{2, "prog: --n needs a value\nusage: prog --n N\n"});
  CHECK(guarded([]() -> int { throw lapis::IoError("a.obj: line 3: bad face"); }) ==
        std::pair<int, std::string>{1, "prog: error: a.obj: line 3: bad face\n"});
  // Not a Lapis error: reported, not an abort.
  const auto [status, text] = guarded([]() -> int { throw std::bad_alloc(); });
  CHECK(status == 1);
  CHECK(text.find("prog: internal error: ") == 0);
}
