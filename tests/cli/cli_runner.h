// Runs the `lapis` executable in tests: exit status and everything it printed.
#pragma once

#include <doctest/doctest.h>

#include <sys/wait.h>
#include <unistd.h>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

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

// A 3 x 3 vertex grid of 8 triangles in the z = 0 plane as OBJ, then `extra` lines.
inline std::filesystem::path write_grid_obj(const std::filesystem::path& path, const std::string& extra = "") {
  std::ofstream obj(path);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) obj << "v " << i << " " << j << " 0\n";
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int a = j * 3 + i + 1;
      obj << "f " << a << " " << a + 1 << " " << a + 4 << "\nf " << a << " " << a + 4 << " " << a + 3 << "\n";
    }
  obj << extra;
  return path;
}

}  // namespace lapis::cli_test
