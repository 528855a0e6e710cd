// Runs the `lapis` executable in tests: exit status and everything it printed.
#pragma once

#include <doctest/doctest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace lapis::cli_test {

struct Result {
  int status;
  std::string output;  // stdout and stderr
};

inline Result lapis_cli(const std::string& args) {
  const std::string cmd = std::string(LAPIS_CLI_EXE) + " " + args + " 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  REQUIRE(pipe);
  std::string out;
  std::array<char, 4096> buf{};
  while (size_t n = fread(buf.data(), 1, buf.size(), pipe.get())) out.append(buf.data(), n);
  const int status = pclose(pipe.release());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

// A per-process scratch directory named after `what`.
inline std::filesystem::path scratch_dir(const std::string& what) {
  const auto d = std::filesystem::temp_directory_path() / ("lapis_" + what + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

}  // namespace lapis::cli_test
