// Shared by the fuzz targets: the input as a file (for readers that take a path) and the
// rule that a lapis::Error is an expected rejection. Anything else escapes to libFuzzer (or
// the replay driver) and is a finding.
#pragma once

#include <unistd.h>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "lapis/core/error.h"

namespace lapis::fuzz {

// Writes the input to one file per process and returns its path; `extension` keeps
// dispatching readers honest (".obj", ".ply", ...).
inline std::filesystem::path input_file(const std::uint8_t* data, std::size_t size, const std::string& extension) {
  const auto path = std::filesystem::temp_directory_path() / ("lapis_fuzz_" + std::to_string(::getpid()) + extension);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

// Runs `body`, treating lapis::Error as the reader's documented rejection. With
// LAPIS_FUZZ_VERBOSE set, says whether each input was accepted (to check a seed corpus).
template <class Body>
int expect_lapis_errors_only(Body&& body) {
  static const bool verbose = std::getenv("LAPIS_FUZZ_VERBOSE") != nullptr;
  try {
    body();
    if (verbose) std::fprintf(stderr, "accepted\n");
  } catch (const lapis::Error& e) {
    if (verbose) std::fprintf(stderr, "rejected: %s\n", e.what());
  }
  return 0;
}

// Reads the file the input was written to with `reader(path)`.
template <class Reader>
int read_as_file(const std::uint8_t* data, std::size_t size, const std::string& extension, Reader&& reader) {
  const auto path = input_file(data, size, extension);
  return expect_lapis_errors_only([&] { reader(path); });
}

}  // namespace lapis::fuzz
